//! `nullpath geodesic`: scatter one ray off a spacetime (see `spacetime::scattering`).

use clap::{Parser, ValueEnum};
use spacetime::scattering::{scatter, Scattering};
use spacetime::{Fate, Integrator, Minkowski, Spacetime};

#[derive(Clone, Copy, Debug, ValueEnum)]
pub enum SpacetimeKind {
    Minkowski,
    Schwarzschild,
    Kerr,
    Ellis,
    ReissnerNordstrom,
    KerrNewman,
    /// The wormhole of *Interstellar* (`--throat`, `--length`, `--lensing-width`).
    Wormhole,
}

#[derive(Clone, Copy, Debug, ValueEnum)]
pub enum IntegratorKind {
    Rk4,
    Adaptive,
}

#[derive(Parser, Debug)]
pub struct Args {
    /// Which spacetime.
    #[arg(long)]
    spacetime: SpacetimeKind,
    /// Mass M (Schwarzschild, Kerr, Reissner–Nordström, Kerr–Newman).
    #[arg(long, default_value_t = 1.0, allow_hyphen_values = true)]
    mass: f64,
    /// Spin a, |a| ≤ M (Kerr; a² + Q² ≤ M² for Kerr–Newman); positive b is then the prograde
    /// side.
    #[arg(long, default_value_t = 0.0, allow_hyphen_values = true)]
    spin: f64,
    /// Charge Q, |Q| ≤ M (Reissner–Nordström, Kerr–Newman).
    #[arg(long, default_value_t = 0.0, allow_hyphen_values = true)]
    charge: f64,
    /// Throat radius b₀ (Ellis, wormhole).
    #[arg(long, default_value_t = 1.0, allow_hyphen_values = true)]
    throat: f64,
    /// Length of the wormhole's cylindrical throat (wormhole).
    #[arg(long, default_value_t = 0.0, allow_hyphen_values = true)]
    length: f64,
    /// Lensing width 𝒲 of the wormhole's mouths (wormhole; required there).
    #[arg(long, allow_hyphen_values = true)]
    lensing_width: Option<f64>,
    /// Impact parameter b, in the same units as M or b₀.
    #[arg(long, allow_hyphen_values = true)]
    impact: f64,
    /// Tilt of the ray's plane from the equatorial plane, degrees.
    #[arg(long, default_value_t = 0.0, allow_hyphen_values = true)]
    inclination: f64,
    /// Integrator.
    #[arg(long, value_enum, default_value_t = IntegratorKind::Adaptive)]
    integrator: IntegratorKind,
    /// Relative tolerance of the adaptive integrator.
    #[arg(long, default_value_t = 1e-10, allow_hyphen_values = true)]
    rtol: f64,
    /// Step of the RK4 integrator: azimuth in radians for spherical spacetimes; for Kerr the
    /// step is a fixed fraction (0.1) of the distance from the centre.
    #[arg(long, default_value_t = 1e-3, allow_hyphen_values = true)]
    step: f64,
    /// Print one JSON object instead of text.
    #[arg(long)]
    json: bool,
}

fn check(name: &str, value: f64, ok: bool, what: &str) -> Result<f64, String> {
    if value.is_finite() && ok {
        Ok(value)
    } else {
        Err(format!("--{name} {value}: {what}"))
    }
}

fn spacetime(args: &Args) -> Result<Spacetime, String> {
    let s = match args.spacetime {
        SpacetimeKind::Minkowski => Ok(Spacetime::Minkowski(Minkowski)),
        SpacetimeKind::Schwarzschild => Spacetime::schwarzschild(args.mass),
        SpacetimeKind::Kerr => Spacetime::kerr(args.mass, args.spin),
        SpacetimeKind::Ellis => Spacetime::ellis(args.throat),
        SpacetimeKind::ReissnerNordstrom => Spacetime::reissner_nordstrom(args.mass, args.charge),
        SpacetimeKind::KerrNewman => Spacetime::kerr_newman(args.mass, args.spin, args.charge),
        SpacetimeKind::Wormhole => {
            let width = args.lensing_width.ok_or("wormhole spacetime: --lensing-width is required")?;
            Spacetime::wormhole(args.throat, args.length, width)
        }
    };
    let name = args.spacetime.to_possible_value().map_or(String::new(), |v| v.get_name().to_owned());
    s.map_err(|e| format!("{name} spacetime: {e}"))
}

pub fn run(args: &Args) -> Result<(), String> {
    let spacetime = spacetime(args)?;
    check("impact", args.impact, true, "must be a finite number")?;
    check("inclination", args.inclination, args.inclination.abs() <= 180.0, "must be in [−180, 180] degrees")?;
    let integrator = match args.integrator {
        IntegratorKind::Adaptive => Integrator::Adaptive {
            rtol: check("rtol", args.rtol, args.rtol > 0.0 && args.rtol < 1.0, "must be in (0, 1)")?,
        },
        IntegratorKind::Rk4 => Integrator::Rk4 { step: check("step", args.step, args.step > 0.0, "must be > 0")? },
    };
    let s = scatter(&spacetime, args.impact, args.inclination.to_radians(), integrator);
    if args.json {
        println!("{}", json(&s));
    } else {
        print!("{}", text(&s));
    }
    Ok(())
}

fn fate_name(s: &Scattering) -> &'static str {
    s.fate.name()
}

fn json(s: &Scattering) -> String {
    let deflection =
        if s.deflection_rad.is_finite() { serde_json::json!(s.deflection_rad) } else { serde_json::Value::Null };
    serde_json::json!({
        "fate": fate_name(s),
        "deflection_rad": deflection,
        "steps": s.steps,
        "max_abs_hamiltonian": s.max_abs_hamiltonian,
    })
    .to_string()
}

fn text(s: &Scattering) -> String {
    let mut out = format!("fate: {}\n", fate_name(s));
    if let Fate::Failed(why) = s.fate {
        out += &format!("failure: {why:?}\n");
    }
    if s.deflection_rad.is_finite() {
        out += &format!("deflection_rad: {:.15e}\n", s.deflection_rad);
    } else {
        out += "deflection_rad: none (the ray did not come back out)\n";
    }
    out + &format!("steps: {}\nmax_abs_hamiltonian: {:.3e}\n", s.steps, s.max_abs_hamiltonian)
}

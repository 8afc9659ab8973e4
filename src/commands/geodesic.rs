//! `nullpath geodesic`: scatter one ray off a spacetime (see `spacetime::scattering`).

use clap::builder::{PossibleValue, PossibleValuesParser};
use clap::{Arg, ArgMatches, FromArgMatches, Parser, ValueEnum};
use spacetime::metric::{find, parameters_of, MetricDescriptor, NamedValuesError, ParameterDescriptor, SPACETIMES};
use spacetime::scattering::{scatter, Scattering};
use spacetime::{Fate, Spacetime, Stepping};

#[derive(Clone, Copy, Debug, ValueEnum)]
pub enum SteppingKind {
    Rk4,
    Adaptive,
}

#[derive(Parser, Debug)]
pub struct Args {
    /// Which spacetime: a registered metric, as scene files name it.
    #[arg(long, value_parser = PossibleValuesParser::new(spacetime_names()))]
    spacetime: String,
    /// The spacetime's parameters, one flag each (`--lensing-width` for `lensing_width`), from
    /// the registered metrics' descriptors.
    #[command(flatten)]
    parameters: ParameterFlags,
    /// Impact parameter b, in the same units as M or b₀; for a spinning hole positive b is the
    /// prograde side.
    #[arg(long, allow_hyphen_values = true)]
    impact: f64,
    /// Tilt of the ray's plane from the equatorial plane, degrees.
    #[arg(long, default_value_t = 0.0, allow_hyphen_values = true)]
    inclination: f64,
    /// Integrator.
    #[arg(long, value_enum, default_value_t = SteppingKind::Adaptive)]
    integrator: SteppingKind,
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

/// The registered metrics, for `--spacetime`, each with its description in `--help`.
fn spacetime_names() -> Vec<PossibleValue> {
    SPACETIMES.iter().map(|d| PossibleValue::new(d.name).help(d.description)).collect()
}

/// A parameter's flag: its scene-file name with `-` for `_`.
fn flag(name: &str) -> String {
    name.replace('_', "-")
}

/// Each parameter of the registered metrics once, with the metrics that have it.
fn registered_parameters() -> Vec<(&'static ParameterDescriptor, Vec<&'static MetricDescriptor>)> {
    parameters_of(SPACETIMES)
}

/// The parameter flags given on the command line: one flag per parameter of the registered
/// metrics, generated from their descriptors.
#[derive(Clone, Debug, Default)]
struct ParameterFlags(Vec<(&'static str, f64)>);

impl FromArgMatches for ParameterFlags {
    fn from_arg_matches(matches: &ArgMatches) -> Result<Self, clap::Error> {
        let given = registered_parameters()
            .into_iter()
            .filter_map(|(p, _)| matches.get_one::<f64>(p.name).map(|&v| (p.name, v)))
            .collect();
        Ok(ParameterFlags(given))
    }

    fn update_from_arg_matches(&mut self, matches: &ArgMatches) -> Result<(), clap::Error> {
        *self = Self::from_arg_matches(matches)?;
        Ok(())
    }
}

impl clap::Args for ParameterFlags {
    fn augment_args(cmd: clap::Command) -> clap::Command {
        registered_parameters().into_iter().fold(cmd, |cmd, (p, of)| {
            let of: Vec<&str> = of.iter().map(|d| d.name).collect();
            let default = match p.command_line_default.or(p.default) {
                Some(v) => format!("default {v}"),
                None => "required there".to_string(),
            };
            let help = format!("{} ({}; {default})", capitalized(p.meaning), of.join(", "));
            cmd.arg(
                Arg::new(p.name)
                    .long(flag(p.name))
                    .value_name(flag(p.name).to_uppercase())
                    .value_parser(clap::value_parser!(f64))
                    .allow_hyphen_values(true)
                    .help(help),
            )
        })
    }

    fn augment_args_for_update(cmd: clap::Command) -> clap::Command {
        Self::augment_args(cmd)
    }
}

fn capitalized(s: &str) -> String {
    let mut chars = s.chars();
    chars.next().map_or_else(String::new, |c| c.to_uppercase().chain(chars).collect())
}

/// The spacetime named by `--spacetime`, from its flags: each parameter the flag's value, else
/// its command-line default ([`ParameterDescriptor::command_line_default`]), else the scene
/// files' default; checked by the metric's constructor. A flag of a parameter the spacetime does
/// not have is an error, not ignored.
fn spacetime(args: &Args) -> Result<Spacetime, String> {
    let Some(d) = find(&args.spacetime) else {
        let names: Vec<&str> = SPACETIMES.iter().map(|d| d.name).collect();
        return Err(format!("unknown spacetime \"{}\"; expected one of {}", args.spacetime, names.join(", ")));
    };
    d.build_named(&args.parameters.0, |p| p.command_line_default.or(p.default)).map_err(|e| match e {
        NamedValuesError::Unknown(name) => {
            let flags: Vec<String> = d.parameters.iter().map(|p| format!("--{}", flag(p.name))).collect();
            let has = if flags.is_empty() { "none".to_string() } else { flags.join(", ") };
            format!("{} spacetime: --{} is not one of its parameters (it has: {has})", d.name, flag(&name))
        }
        NamedValuesError::Missing(p) => format!("{} spacetime: --{} is required", d.name, flag(p)),
        NamedValuesError::Invalid(e) if e.parameter.is_empty() => format!("{} spacetime: {}", d.name, e.message),
        NamedValuesError::Invalid(e) => format!("{} spacetime: --{}: {}", d.name, flag(e.parameter), e.message),
    })
}

pub fn run(args: &Args) -> Result<(), String> {
    let spacetime = spacetime(args)?;
    check("impact", args.impact, true, "must be a finite number")?;
    check("inclination", args.inclination, args.inclination.abs() <= 180.0, "must be in [−180, 180] degrees")?;
    let integrator = match args.integrator {
        SteppingKind::Adaptive => Stepping::Adaptive {
            rtol: check("rtol", args.rtol, args.rtol > 0.0 && args.rtol < 1.0, "must be in (0, 1)")?,
        },
        SteppingKind::Rk4 => Stepping::Rk4 { step: check("step", args.step, args.step > 0.0, "must be > 0")? },
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

#[cfg(test)]
mod tests {
    use super::*;

    fn args(line: &[&str]) -> Result<Args, clap::Error> {
        Args::try_parse_from([&["geodesic"], line].concat())
    }

    /// Every registered metric is a `--spacetime`, and every parameter of one a flag.
    #[test]
    fn flags_come_from_the_descriptors() {
        for d in SPACETIMES {
            let mut line = vec!["--spacetime", d.name, "--impact", "5"];
            let valid = |name: &str| match name {
                "spin" => "0.6",
                "charge" => "-0.5",
                "length" => "0.01",
                "lensing_width" => "0.05",
                _ => "1.5",
            };
            let values: Vec<&str> = d.parameters.iter().map(|p| valid(p.name)).collect();
            let flags: Vec<String> = d.parameters.iter().map(|p| format!("--{}", flag(p.name))).collect();
            for (f, v) in flags.iter().zip(&values) {
                line.extend([f.as_str(), v]);
            }
            let parsed = args(&line).unwrap_or_else(|e| panic!("{}: {e}", d.name));
            let values: Vec<f64> = values.iter().map(|v| v.parse().unwrap_or(f64::NAN)).collect();
            let built = (d.build)(&values).expect("valid values");
            assert_eq!(spacetime(&parsed), Ok(built), "{}", d.name);
        }
        assert!(args(&["--spacetime", "kerrr", "--impact", "5"]).is_err());
    }

    #[test]
    fn defaults_and_foreign_flags() {
        let kn = args(&["--spacetime", "kerr-newman", "--spin", "0.3", "--charge", "-0.2", "--impact", "5"]);
        assert_eq!(spacetime(&kn.expect("parses")), Spacetime::kerr_newman(1.0, 0.3, -0.2).map_err(|e| e.to_string()));
        let flat = args(&["--spacetime", "minkowski", "--mass", "2", "--impact", "5"]).expect("parses");
        let e = spacetime(&flat).expect_err("minkowski has no mass");
        assert!(e.contains("--mass is not one of its parameters (it has: none)"), "{e}");
        let e = spacetime(&args(&["--spacetime", "kerr", "--spin", "2", "--impact", "5"]).expect("parses"));
        assert_eq!(e, Err("kerr spacetime: --spin: |spin| must be ≤ mass = 1, got 2".to_string()));
    }
}

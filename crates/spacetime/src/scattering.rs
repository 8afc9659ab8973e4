//! Scattering of a single ray that comes in from infinity: its fate and total bending angle.
//! This is what `nullpath geodesic` runs, and what the physics tests compare with exact results.
//!
//! The ray is traced backwards like every nullpath ray; the traced curve comes in from infinity
//! along +x with impact parameter `b`, offset towards +y (rotated towards +z by the inclination).
//! For a spinning hole, `b > 0` is the prograde side: the photon that travels the curve
//! physically (in the opposite sense) orbits with the hole.

use crate::geodesic::plane::{trace_plane, PlaneMetric, PlaneRay, PlaneStart};
use crate::geodesic::{HamiltonianTracer, State, Stepping, TraceSettings, Visit};
use crate::metric::{Metric, OwnStepper, Spacetime, Tracers};
use crate::tensor::{cross3, dot3, norm3, spatial};
use crate::Fate;
use std::f64::consts::PI;

/// What happened to the ray.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Scattering {
    pub fate: Fate,
    /// Bending angle in radians, positive towards the centre: the azimuth swept from the
    /// incoming to the outgoing asymptote minus π. `NaN` for captured or failed rays.
    pub deflection_rad: f64,
    pub steps: u32,
    /// Largest `|H|` along the ray, with `E = 1` (so relative to E²).
    pub max_abs_hamiltonian: f64,
}

/// Settings for scattering experiments: far escape radius and tight tolerance.
pub fn settings(stepping: Stepping) -> TraceSettings {
    TraceSettings { stepping, escape_radius: 1e3, max_step_fraction: 0.5, max_steps: 2_000_000, check_every_step: true }
}

/// Scatters a ray of impact parameter `b` (in the equatorial plane tilted by `inclination_rad`
/// about the incoming direction) off `spacetime`.
pub fn scatter(spacetime: &Spacetime, b: f64, inclination_rad: f64, stepping: Stepping) -> Scattering {
    spacetime.choose_tracer(Scatter { b, inclination_rad, stepping })
}

/// A scattering experiment, handed to the tracer the spacetime chooses.
struct Scatter {
    b: f64,
    inclination_rad: f64,
    stepping: Stepping,
}

impl Tracers for Scatter {
    type Output = Scattering;

    /// Flat space: the ray goes straight on, unbent.
    fn straight(self) -> Scattering {
        Scattering {
            fate: Fate::Escaped { direction: [1.0, 0.0, 0.0] },
            deflection_rad: 0.0,
            steps: 0,
            max_abs_hamiltonian: 0.0,
        }
    }

    fn in_plane<M: PlaneMetric>(self, metric: &M) -> Scattering {
        in_plane(metric, self.b, self.inclination_rad, self.stepping)
    }

    fn four_d<M: Metric>(self, metric: &M) -> Scattering {
        hamiltonian(metric, self.b, self.inclination_rad, self.stepping)
    }

    /// Scattering is measured with the 4-D tracer whatever the metric's own stepper.
    fn own_stepper<M: OwnStepper>(self, metric: &M) -> Scattering {
        self.four_d(metric)
    }
}

/// Unit offset direction of the impact parameter.
fn offset(inclination_rad: f64) -> [f64; 3] {
    [0.0, inclination_rad.cos(), inclination_rad.sin()]
}

/// Spherically symmetric spacetimes: exact reduction to the ray's plane.
fn in_plane<M: PlaneMetric>(metric: &M, b: f64, inclination_rad: f64, stepping: Stepping) -> Scattering {
    let scale = metric.length_scale();
    let settings = TraceSettings {
        escape_radius: 1e3 * scale.max(b.abs()),
        max_step_fraction: plane_step(stepping),
        ..settings(stepping)
    };
    let e = offset(inclination_rad);
    // At infinity the position direction is −x; the ray sweeps towards the offset side.
    let start = if b == 0.0 {
        let from = [-settings.escape_radius, 0.0, 0.0];
        PlaneStart::Radial { region: crate::Region::Upper, from, direction: [1.0, 0.0, 0.0] }
    } else {
        let side = if b > 0.0 { e } else { e.map(|c| -c) };
        PlaneStart::Plane(PlaneRay::from_infinity(metric, b.abs(), [-1.0, 0.0, 0.0], side))
    };
    let t = trace_plane(metric, start, &settings, |_| Visit::Continue);
    let deflection_rad = match t.fate {
        Fate::Escaped { .. } | Fate::Traversed { .. } => t.swept_minus_pi,
        _ => f64::NAN,
    };
    Scattering { fate: t.fate, deflection_rad, steps: t.steps, max_abs_hamiltonian: t.max_abs_hamiltonian }
}

/// The RK4 step in the plane is an azimuth step; the adaptive one is capped at half a radian.
fn plane_step(stepping: Stepping) -> f64 {
    match stepping {
        Stepping::Rk4 { step } => step,
        Stepping::Adaptive { .. } => 0.5,
    }
}

/// The backward-traced photon of energy 1 (`p_t = +1`) that comes in along +x at `distance`
/// with impact parameter `b` towards `side`: its covariant momentum is along x, with `p_x` from
/// `H = 0`, and its offset `y₀` is such that the angular momentum `|x⃗ × p⃗| = y₀ |p_x|` is `b`,
/// the impact parameter at infinity (`L / E`). Placing it at offset `b` instead would give it
/// `L = b |p_x|`, off by `O(M / distance)` in a chart where `|p_x| ≠ 1` there (Schwarzschild's
/// areal radius made Cartesian: `|p_x| ≈ 1 + 2M/r`), a bias that grows as `b` nears the
/// photon sphere. `|p_x|` depends on the offset only at second order, so a few fixed-point
/// passes settle it to rounding.
fn start_from_afar<M: Metric>(metric: &M, b: f64, side: [f64; 3], distance: f64) -> State {
    let momentum_x = |x: &[f64; 4]| {
        let g = metric.inverse_metric(x);
        let (a2, a1, a0) = (g[1][1], 2.0 * g[0][1], g[0][0]);
        (-a1 + (a1 * a1 - 4.0 * a2 * a0).sqrt()) / (2.0 * a2)
    };
    let mut x = [0.0, -distance, b * side[1], b * side[2]];
    for _ in 0..4 {
        let offset = b / momentum_x(&x).abs();
        x = [0.0, -distance, offset * side[1], offset * side[2]];
    }
    State { x, p: [1.0, momentum_x(&x), 0.0, 0.0] }
}

/// Any metric: 4-D Hamiltonian integration from a large distance, with the bending outside
/// that distance added from the straight asymptotes (its remainder is O(M b / D²)).
fn hamiltonian<M: Metric>(metric: &M, b: f64, inclination_rad: f64, stepping: Stepping) -> Scattering {
    let scale = metric.length_scale();
    let distance = 1e4 * scale.max(b.abs());
    let settings = TraceSettings { escape_radius: distance, max_step_fraction: 0.1, ..settings(stepping) };
    let start = start_from_afar(metric, b, offset(inclination_rad), distance);
    let x0 = start.x;
    let mut tracer = HamiltonianTracer::new(metric, start, settings);
    if let Stepping::Rk4 { .. } = stepping {
        tracer = HamiltonianTracer::new(
            metric,
            start,
            TraceSettings { stepping: Stepping::Rk4 { step: f64::INFINITY }, ..settings },
        );
    }
    // Orbital-plane normal of the traced curve at the start, to sign the swept azimuth.
    let normal = cross3(&spatial(&x0), &[1.0, 0.0, 0.0]);
    let mut swept = x0[2].hypot(x0[3]).atan2(distance);
    let trace = tracer.run(|step| {
        let (a, c) = (spatial(&step.start.x), spatial(&step.end.x));
        let cr = cross3(&a, &c);
        swept += norm3(&cr).atan2(dot3(&a, &c)) * dot3(&cr, &normal).signum();
        Visit::Continue
    });
    let deflection_rad = match trace.fate {
        Fate::Escaped { direction } | Fate::Traversed { direction } => {
            let end = spatial(&trace.end.x);
            let cr = cross3(&end, &direction);
            swept + norm3(&cr).atan2(dot3(&end, &direction)) * dot3(&cr, &normal).signum() - PI
        }
        _ => f64::NAN,
    };
    Scattering { fate: trace.fate, deflection_rad, steps: trace.steps, max_abs_hamiltonian: trace.max_abs_hamiltonian }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::analytic::schwarzschild_deflection;
    use crate::metric::written::tests::spherical_schwarzschild;

    /// Schwarzschild written in its own (areal) coordinates, traced in 4-D, bends light by the
    /// exact integral to 1e-7 from near the photon sphere out: the ray starts with angular
    /// momentum `b`, although in that chart `|p_x| ≈ 1 + 2M/r` far out, so an offset of `b` would
    /// be a ray of impact parameter `b (1 + 2M/r)` (2e-4 too large at the start's 10⁴ M, which
    /// bent the ray at b = 6 M by 1.2e-4 too little).
    #[test]
    fn a_chart_whose_momenta_are_not_unit_far_out_bends_by_the_exact_integral() {
        let metric = spherical_schwarzschild(1.0);
        for b in [5.5, 6.0, 10.0, 30.0] {
            let s = hamiltonian(&metric, b, 0.4, Stepping::Adaptive { rtol: 1e-12 });
            let exact = schwarzschild_deflection(1.0, b);
            assert!(((s.deflection_rad - exact) / exact).abs() < 1e-7, "b = {b}: {} against {exact}", s.deflection_rad);
        }
    }
}

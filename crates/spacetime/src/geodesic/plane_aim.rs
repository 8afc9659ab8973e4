//! Aiming a light ray at a point of a static, spherically symmetric spacetime: the shooting
//! problem of next-event estimation reduced to one unknown in the ray's plane.
//!
//! The centre, the start `x` and the target `y` span one plane, and every ray from `x` to `y`
//! lies in it ([`super::plane`]). A ray leaves `x` at angle `ψ` from the outward radial direction,
//! measured by the static observer there, towards `y`'s side of the plane, and obeys the Binet
//! equation of its metric with its impact parameter `b = f(u_x) sin ψ`
//! ([`PlaneMetric::impact_factor`]):
//!
//! ```text
//! u'' = −u + G(u, β),   u(0) = u_x,   u'(0) = −(u_x/σ_x) cot ψ,   β = 1/b²,        (1)
//! ```
//!
//! (`' = d/dφ`, `σ` the static frame's radial stretch). The ray must reach `u_y` at the target's
//! azimuth `Δφ ∈ (0, π)`: one equation `u(Δφ; ψ) = u_y` in one unknown, solved by Newton's method
//! on `ψ` inside a bracket that bisection keeps (rays that escape before `Δφ` bound `ψ` from
//! below, rays captured by a horizon or passing a throat from above; bisection on a sign change
//! converges whatever the metric's shape). Newton's derivative is the Jacobi field
//! `J = ∂u/∂ψ` at fixed `φ`, integrated beside the ray from the variational equation of (1):
//!
//! ```text
//! J'' = −J + G_u J + G_β β_ψ,   J(0) = 0,   J'(0) = (u_x/σ_x)/sin²ψ,   β_ψ = −2β cot ψ.   (2)
//! ```
//!
//! `G` is linear in `β` for every static spherically symmetric metric (the first integral is
//! `u'² = P(u) β + Q(u)`), so `G_β` is an exact difference; `G_u` is a central difference.
//!
//! The first shot is the straight line from `x` to `y`, and Newton's iteration from it is
//! deterministic, so the ray found is a function of the two points (the short way round, the
//! image the renderer's MIS weights check a BSDF-sampled ray against; other images are left
//! to BSDF sampling).
//!
//! Density: turning `ψ` by `dψ` moves the point at `φ = Δφ` radially by `ρ'(u_y) J dψ` in world
//! coordinates (`ρ` the areal radius); turning the plane by `dχ` about the axis through the
//! centre and `x` moves it by `ρ_y sin Δφ dχ` out of the plane. The solid angle at `x` is
//! `dΩ = sin ψ dψ dχ`, and the beam's cross-section perpendicular to the unit world tangent `t`
//! at `y` (in-plane tangential component `t_φ`) is `|ρ'(u_y) J| t_φ ρ_y sin Δφ dψ dχ`:
//!
//! ```text
//! dΩ/dA⊥ = sin ψ / (|ρ'(u_y) J| t_φ ρ_y sin Δφ),                                     (3)
//! ```
//!
//! which is `1/d²` in flat space (law of sines), and equation (3) of [`super::connect`] about
//! Schwarzschild.

use super::dopri5;
use super::plane::PlaneMetric;
use crate::tensor::{dot3, norm3, normalize3, scale3};
use std::f64::consts::PI;

/// Below this `sin Δφ` the plane is undetermined (`y` on the line through the centre and `x`).
const MIN_SIN_SWEEP: f64 = 1e-9;
/// Shots before the aim gives up: Newton's method needs three to five from the straight line,
/// bisection alone halves the bracket (0, π) to 10⁻¹² in forty.
const MAX_SHOTS: u32 = 48;
/// Steps of one shot before it counts as failed.
const MAX_STEPS: u32 = 2_000;
/// Relative step of the central difference for `G_u`: its truncation (~h²) and rounding
/// (~10⁻¹⁶/h) errors are both near 10⁻¹⁰, far below what the density needs.
const DIFFERENCE_STEP: f64 = 1e-5;

/// How a [`plane_aim`] is taken.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PlaneAimSettings {
    /// Relative tolerance of each shot's Dormand–Prince steps.
    pub rtol: f64,
    /// The aim is taken when the ray passes within this world distance of the target.
    pub tolerance: f64,
}

/// A ray from a start point through a target point, with its density.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PlaneAim {
    /// Unit direction the ray leaves the start in, in the static frame there (world axes).
    pub start: [f64; 3],
    /// Unit direction of travel at the target, in the static frame there (world axes).
    pub end: [f64; 3],
    /// Unit world tangent at the target.
    pub end_tangent: [f64; 3],
    /// `dΩ/dA⊥`: solid angle at the start per world area across `end_tangent`, equation (3).
    pub solid_angle_per_area: f64,
    /// Shots taken.
    pub shots: u32,
}

/// Where one shot ended, relative to the target.
enum Shot {
    /// It reached the target's azimuth with `(u, u', J)`.
    Reached { u: f64, du: f64, jacobi: f64 },
    /// It escaped before: `ψ` is too small.
    Below,
    /// A horizon or a throat took it before: `ψ` is too large.
    Above,
}

/// The aim's fixed data: the metric, the start and the target's place in the plane.
struct Shooter<'m, M: PlaneMetric + ?Sized> {
    metric: &'m M,
    rtol: f64,
    u_x: f64,
    /// `u_x/σ_x`.
    slope_scale: f64,
    /// `1/f(u_x)²`: `β sin²ψ`.
    beta_scale: f64,
    sweep: f64,
}

/// The ray from world point `x` to world point `y` of one region of `metric` (an in-plane
/// metric's world coordinates, as [`super::plane::PlaneStart::from_observer`] takes them), or
/// `None` where the points leave the plane undetermined, either lies where no static observer
/// is, or the iteration finds no ray within its shots.
pub fn plane_aim<M: PlaneMetric + ?Sized>(
    metric: &M,
    x: [f64; 3],
    y: [f64; 3],
    settings: &PlaneAimSettings,
) -> Option<PlaneAim> {
    let (rho_x, rho_y) = (norm3(&x), norm3(&y));
    let (u_x, u_y) = (metric.u_of_world_radius(rho_x)?, metric.u_of_world_radius(rho_y)?);
    if metric.capture_u().is_some_and(|uc| u_x >= uc || u_y >= uc) {
        return None;
    }
    // The plane's axes in world coordinates: radial at x, and towards y across it.
    let radial = scale3(&x, 1.0 / rho_x);
    let y_hat = scale3(&y, 1.0 / rho_y);
    let cos_sweep = dot3(&radial, &y_hat).clamp(-1.0, 1.0);
    let across_y = std::array::from_fn(|i| y_hat[i] - cos_sweep * radial[i]);
    let sin_sweep = norm3(&across_y);
    if sin_sweep < MIN_SIN_SWEEP {
        return None;
    }
    let across = scale3(&across_y, 1.0 / sin_sweep);
    let shooter = Shooter {
        metric,
        rtol: settings.rtol,
        u_x,
        slope_scale: u_x / metric.radial_stretch(u_x),
        beta_scale: 1.0 / metric.impact_factor(u_x).powi(2),
        sweep: sin_sweep.atan2(cos_sweep),
    };
    // The straight line's angle from the outward radial, towards y's side.
    let chord: [f64; 3] = std::array::from_fn(|i| y[i] - x[i]);
    let mut psi = dot3(&across, &chord).atan2(dot3(&radial, &chord));
    let (mut lo, mut hi) = (0.0, PI);
    let slope_y = metric.world_radius_slope(u_y);
    for shots in 1..=MAX_SHOTS {
        let next = match shooter.shoot(psi)? {
            Shot::Reached { u, du, jacobi } => {
                let miss = u - u_y;
                if (slope_y * miss).abs() <= settings.tolerance {
                    return shooter.found(psi, [radial, across], (u_y, du, jacobi), shots);
                }
                if miss < 0.0 {
                    lo = psi;
                } else {
                    hi = psi;
                }
                psi - miss / jacobi
            }
            Shot::Below => {
                lo = psi;
                f64::NAN
            }
            Shot::Above => {
                hi = psi;
                f64::NAN
            }
        };
        psi = if next > lo && next < hi { next } else { 0.5 * (lo + hi) };
    }
    None
}

impl<M: PlaneMetric + ?Sized> Shooter<'_, M> {
    /// Equations (1) and (2) as one system `[u, u', J, J']`.
    #[inline]
    fn rhs(&self, beta: f64, beta_psi: f64, y: &[f64; 4]) -> [f64; 4] {
        let [u, du, j, dj] = *y;
        let g = |u: f64, beta: f64| self.metric.binet_source(u, beta);
        let h = DIFFERENCE_STEP * u.abs().max(f64::MIN_POSITIVE);
        let g_u = (g(u + h, beta) - g(u - h, beta)) / (2.0 * h);
        // Exact for G linear in β (module docs), whatever β's size.
        let g_beta = (g(u, 2.0 * beta) - g(u, 0.0)) / (2.0 * beta);
        [du, -u + g(u, beta), dj, -j + g_u * j + g_beta * beta_psi]
    }

    /// The ray leaving at `ψ`, integrated to the target's azimuth; `None` where it fails.
    fn shoot(&self, psi: f64) -> Option<Shot> {
        let (sin, cos) = psi.sin_cos();
        let cot = cos / sin;
        let beta = self.beta_scale / (sin * sin);
        let beta_psi = -2.0 * beta * cot;
        let f = |_: f64, y: &[f64; 4]| self.rhs(beta, beta_psi, y);
        let mut y = [self.u_x, -self.slope_scale * cot, 0.0, self.slope_scale / (sin * sin)];
        let mut k = f(0.0, &y);
        let (mut phi, mut h) = (0.0, 0.1f64.min(self.sweep));
        for _ in 0..MAX_STEPS {
            let step = h.min(self.sweep - phi);
            let attempt = dopri5::attempt(&f, phi, &y, &k, step);
            let scale = |a: usize, y0: &[f64; 4], y1: &[f64; 4]| {
                (y0[a].abs() + y0[a + 1].abs()).max(y1[a].abs() + y1[a + 1].abs())
            };
            let err = [0, 2]
                .iter()
                .map(|&a| attempt.error[a].hypot(attempt.error[a + 1]) / (self.rtol * scale(a, &y, &attempt.y1)))
                .fold(0.0, f64::max);
            if !(err <= 1.0) {
                h = step * if err.is_finite() { dopri5::step_factor(err).min(1.0) } else { 0.2 };
                if h <= 1e-15 {
                    return None;
                }
                continue;
            }
            h = step * dopri5::step_factor(err);
            (phi, y, k) = (phi + step, attempt.y1, attempt.end_derivative());
            let [u, du, jacobi, _] = y;
            if u <= 0.0 {
                return Some(Shot::Below);
            }
            let beyond = |limit: Option<f64>| limit.is_some_and(|limit| u >= limit);
            if beyond(self.metric.capture_u()) || beyond(self.metric.throat_u()) {
                return Some(Shot::Above);
            }
            if phi >= self.sweep {
                return Some(Shot::Reached { u, du, jacobi });
            }
        }
        None
    }

    /// The aim of the ray leaving at `ψ` that reached `(u_y, u'_y)` with Jacobi field `J`, in
    /// world axes from the plane's (`radial` at the start, `across` towards the target).
    fn found(
        &self,
        psi: f64,
        [radial, across]: [[f64; 3]; 2],
        (u_y, du, jacobi): (f64, f64, f64),
        shots: u32,
    ) -> Option<PlaneAim> {
        let metric = self.metric;
        let (sin, cos) = psi.sin_cos();
        let start = std::array::from_fn(|i| cos * radial[i] + sin * across[i]);
        let (sin_sweep, cos_sweep) = self.sweep.sin_cos();
        let radial_y: [f64; 3] = std::array::from_fn(|i| cos_sweep * radial[i] + sin_sweep * across[i]);
        let azimuthal_y: [f64; 3] = std::array::from_fn(|i| -sin_sweep * radial[i] + cos_sweep * across[i]);
        let in_plane = |r: f64, a: f64| normalize3(&std::array::from_fn(|i| r * radial_y[i] + a * azimuthal_y[i]));
        let (rho, slope) = (metric.world_radius(u_y), metric.world_radius_slope(u_y));
        // The static observer sees `(n_r, n_φ) ∝ (−σ u', u)`; the world tangent is `dW/dφ`.
        let end = in_plane(-metric.radial_stretch(u_y) * du, u_y);
        let tangent_phi = rho / (slope * du).hypot(rho);
        let end_tangent = in_plane(slope * du, rho);
        let solid_angle_per_area = sin / ((slope * jacobi).abs() * tangent_phi * rho * sin_sweep);
        (solid_angle_per_area.is_finite() && solid_angle_per_area > 0.0).then_some(PlaneAim {
            start,
            end,
            end_tangent,
            solid_angle_per_area,
            shots,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geodesic::aim::{aim, AimSettings};
    use crate::geodesic::{Integrator, TraceSettings};
    use crate::metric::{Ellis, Region, ReissnerNordstrom, Schwarzschild};
    use crate::observer::Tetrad;

    const SETTINGS: PlaneAimSettings = PlaneAimSettings { rtol: 1e-9, tolerance: 1e-9 };

    /// Start and target pairs on both sides of a centre of unit length scale, near and far, and
    /// nearly opposite each other, where rays between them bend strongly.
    fn pairs() -> Vec<([f64; 3], [f64; 3])> {
        let mut pairs = Vec::new();
        for k in 0..6 {
            let t = f64::from(k);
            pairs.push(([2.5 + 0.3 * t, 0.1 * t, 0.3], [-2.6 - 0.2 * t, 0.6 - 0.08 * t, -0.2]));
        }
        for k in 0..12 {
            let t = f64::from(k);
            let x = [4.0 + 0.5 * t, 1.0 - 0.3 * t, 0.4 * (t * 0.7).sin()];
            let y = [-3.0 + 0.6 * (t * 1.3).cos(), 3.5 + 0.2 * t, -1.0 + 0.25 * t];
            pairs.push((x, y));
        }
        pairs
    }

    /// The unit world tangent at the start of `found`: the static frame's radial component
    /// stretched by `1/κ` (world radial length per proper length).
    fn start_tangent<M: PlaneMetric>(metric: &M, x: [f64; 3], found: &PlaneAim) -> [f64; 3] {
        let radial = normalize3(&x);
        let kappa = metric.radial_scale(metric.u_of_world_radius(norm3(&x)).unwrap());
        let n_r = dot3(&found.start, &radial);
        normalize3(&std::array::from_fn(|i| found.start[i] + (kappa - 1.0) * n_r * radial[i]))
    }

    /// The aim agrees with the 4-D aim (a different method on a different tracer, in the
    /// chart): start and end tangents to 1e-6, density to 1e-5.
    fn agrees_with_the_four_d_aim<M: PlaneMetric>(metric: &M) {
        let trace = TraceSettings {
            integrator: Integrator::Adaptive { rtol: 1e-10 },
            escape_radius: 100.0,
            max_step_fraction: 0.5,
            max_steps: 100_000,
        };
        let four_d = AimSettings { trace, tolerance: 1e-9, max_shots: 40 };
        let mut compared = 0;
        for (x, y) in pairs() {
            let Some(found) = plane_aim(metric, x, y, &SETTINGS) else { continue };
            let chart = metric.world_to_chart(Region::Upper, x, 0.0).unwrap();
            let frame = Tetrad::local_observer(metric, &chart).unwrap();
            let guess = std::array::from_fn(|i| y[i] - x[i]);
            let Some(reference) = aim(metric, chart, &frame, y, guess, &four_d) else { continue };
            compared += 1;
            let turn =
                norm3(&std::array::from_fn(|i| start_tangent(metric, x, &found)[i] - reference.start_tangent[i]));
            assert!(turn < 1e-6, "{x:?} → {y:?}: start tangent off by {turn:e}");
            let density = found.solid_angle_per_area / reference.solid_angle_per_area - 1.0;
            assert!(density.abs() < 1e-5, "{x:?} → {y:?}: density off by {density:e}");
            let tangent = norm3(&std::array::from_fn(|i| found.end_tangent[i] - reference.end_tangent[i]));
            assert!(tangent < 1e-6, "{x:?} → {y:?}: end tangent off by {tangent:e}");
            assert!(found.shots <= 12, "{x:?} → {y:?}: {} shots", found.shots);
        }
        assert!(compared >= 10, "only {compared} pairs compared");
    }

    #[test]
    fn agrees_with_the_four_d_aim_around_a_wormhole() {
        agrees_with_the_four_d_aim(&Ellis::new(1.2));
    }

    #[test]
    fn agrees_with_the_four_d_aim_around_a_charged_hole() {
        agrees_with_the_four_d_aim(&ReissnerNordstrom::new(0.5, 0.4));
    }

    #[test]
    fn agrees_with_the_four_d_aim_around_a_schwarzschild_hole() {
        agrees_with_the_four_d_aim(&Schwarzschild::new(0.5));
    }

    #[test]
    fn density_is_the_inverse_square_far_from_a_light_centre() {
        let metric = Schwarzschild::new(1e-9);
        for (x, y) in pairs() {
            let found = plane_aim(&metric, x, y, &SETTINGS).unwrap();
            let chord: [f64; 3] = std::array::from_fn(|i| y[i] - x[i]);
            let d2 = dot3(&chord, &chord);
            assert!((found.solid_angle_per_area * d2 - 1.0).abs() < 1e-6, "{}", found.solid_angle_per_area * d2);
            let along = normalize3(&chord);
            assert!(norm3(&std::array::from_fn(|i| found.start[i] - along[i])) < 1e-6);
            assert!(norm3(&std::array::from_fn(|i| found.end[i] - along[i])) < 1e-6);
        }
    }

    #[test]
    fn points_in_line_with_the_centre_have_no_plane() {
        assert_eq!(plane_aim(&Ellis::new(1.0), [3.0, 0.0, 0.0], [-5.0, 0.0, 0.0], &SETTINGS), None);
    }
}

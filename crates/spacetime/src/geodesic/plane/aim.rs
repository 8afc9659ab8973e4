//! Aiming a light ray at a point of a static, spherically symmetric spacetime: the shooting
//! problem of next-event estimation reduced to one unknown in the ray's plane.
//!
//! The centre, the start `x` and the target `y` span one plane, and every ray from `x` to `y`
//! lies in it ([`super`]). A ray leaves `x` at angle `ψ` from the outward radial direction,
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
//! Two rays that go round the centre less than once join the points ([`Way`]): the short way,
//! sweeping `Δφ`, and the long way, sweeping `2π − Δφ` in the plane's other sense, which passes
//! close to the photon sphere or the throat. Each is aimed alone, on its own bracket. The short
//! way's first shot is the straight line from `x` to `y`, the long way's the ray leaving
//! tangentially; the iteration from there is deterministic, so each way's ray is a function of
//! the two points (the renderer's MIS weights check a BSDF-sampled ray against it; rays that
//! wind round once or more are left to BSDF sampling).
//!
//! A wormhole's target may lie in the other region ([`Side::Other`]): the ray must pass the
//! throat. The tracer's lower-region variable `ũ = u_t²/u` ([`super`]; `u_t` the
//! throat's `u`) obeys the same equation, so a shot that reaches the throat carries on in it,
//! its Jacobi field changed with it at the same `φ`: `J̃ = −(ũ/u) J`, `J̃' = −(ũ/u) J' + 2(ũ/u²) u' J`.
//! Beyond the throat `ũ` at the target's azimuth falls as `ψ` grows (steeper rays sweep less
//! there), so the bracket's sense turns; rays that escape before the throat bound `ψ` from below,
//! rays that escape beyond it before the target's azimuth from above. The other region's world
//! is the chart turned inside out ([`super`]): the target is aimed at as the point
//! opposite it, and the directions found there are turned back.
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
//! which is `1/d²` in flat space (law of sines), and equation (3) of [`connect`](crate::metric::schwarzschild::connect) about
//! Schwarzschild.

use super::PlaneMetric;
use crate::geodesic::dopri5;
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

/// Which of the two rays that go round the centre less than once.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Way {
    /// Sweeping `Δφ ≤ π`.
    Short,
    /// Sweeping `2π − Δφ ≥ π` the other way round.
    Long,
}

impl Way {
    pub const BOTH: [Way; 2] = [Way::Short, Way::Long];

    /// The way a ray that swept `swept` radians about the centre went, if it went round less than
    /// once.
    pub fn of_sweep(swept: f64) -> Option<Way> {
        if swept <= PI {
            Some(Way::Short)
        } else if swept < 2.0 * PI {
            Some(Way::Long)
        } else {
            None
        }
    }
}

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

/// Which region a target lies in, seen from the start's.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Side {
    /// The start's region.
    Same,
    /// The other region of a wormhole, beyond its throat.
    Other,
}

/// Where one shot ended, relative to the target.
enum Shot {
    /// It reached the target's azimuth with `(u, u', J)`, in the start's region or, `beyond` the
    /// throat, in the other (`u` then the other region's `ũ`).
    Reached { u: f64, du: f64, jacobi: f64, beyond: bool },
    /// It escaped before, in the start's region: `ψ` is too small.
    Below,
    /// A horizon took it before, or a throat the target is not beyond, or it escaped beyond the
    /// throat: `ψ` is too large.
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
    side: Side,
}

/// The ray from world point `x` to world point `y` of `metric` (an in-plane metric's world
/// coordinates, as [`super::PlaneStart::from_observer`] takes them; `y` in the region
/// `side` of `x`'s) that goes round the centre `way`, or `None` where the points leave the plane
/// undetermined, either lies where no static observer is, the metric has no throat to reach the
/// other side through, or the iteration finds no ray within its shots.
pub fn plane_aim<M: PlaneMetric + ?Sized>(
    metric: &M,
    x: [f64; 3],
    (y, side): ([f64; 3], Side),
    way: Way,
    settings: &PlaneAimSettings,
) -> Option<PlaneAim> {
    let (rho_x, rho_y) = (norm3(&x), norm3(&y));
    let (u_x, u_y) = (metric.u_of_world_radius(rho_x)?, metric.u_of_world_radius(rho_y)?);
    if metric.capture_u().is_some_and(|uc| u_x >= uc || u_y >= uc) {
        return None;
    }
    // Beyond the throat the world is the chart turned inside out: y lies opposite its world point.
    let y = match side {
        Side::Same => y,
        Side::Other => {
            metric.throat_u()?;
            scale3(&y, -1.0)
        }
    };
    // The plane's axes in world coordinates: radial at x, and towards y across it.
    let radial = scale3(&x, 1.0 / rho_x);
    let y_hat = scale3(&y, 1.0 / rho_y);
    let cos_sweep = dot3(&radial, &y_hat).clamp(-1.0, 1.0);
    let across_y = std::array::from_fn(|i| y_hat[i] - cos_sweep * radial[i]);
    let sin_sweep = norm3(&across_y);
    if sin_sweep < MIN_SIN_SWEEP {
        return None;
    }
    let short = sin_sweep.atan2(cos_sweep);
    let (across, sweep) = match way {
        Way::Short => (scale3(&across_y, 1.0 / sin_sweep), short),
        Way::Long => (scale3(&across_y, -1.0 / sin_sweep), 2.0 * PI - short),
    };
    let shooter = Shooter {
        metric,
        rtol: settings.rtol,
        u_x,
        slope_scale: u_x / metric.radial_stretch(u_x),
        beta_scale: 1.0 / metric.impact_factor(u_x).powi(2),
        sweep,
        side,
    };
    let chord: [f64; 3] = std::array::from_fn(|i| y[i] - x[i]);
    let mut psi = match (side, way) {
        // The straight line's angle from the outward radial, towards y's side.
        (Side::Same, Way::Short) => dot3(&across, &chord).atan2(dot3(&radial, &chord)),
        (Side::Same, Way::Long) => 0.5 * PI,
        // Halfway from the throat's limb (in flat space) to the centre.
        (Side::Other, _) => PI - 0.5 * (metric.world_radius(metric.throat_u()?) / rho_x).min(1.0).asin(),
    };
    let (mut lo, mut hi) = (0.0, PI);
    let slope_y = metric.world_radius_slope(u_y);
    for shots in 1..=MAX_SHOTS {
        let next = match shooter.shoot(psi)? {
            Shot::Reached { u, du, jacobi, beyond } if beyond == (side == Side::Other) => {
                let miss = u - u_y;
                if (slope_y * miss).abs() <= settings.tolerance {
                    return shooter.found(psi, [radial, across], (u_y, du, jacobi), shots);
                }
                // u at the target's azimuth grows with ψ on the start's side, falls beyond.
                if (miss < 0.0) != beyond {
                    lo = psi;
                } else {
                    hi = psi;
                }
                psi - miss / jacobi
            }
            // Short of the throat the target is beyond.
            Shot::Reached { .. } => {
                lo = psi;
                f64::NAN
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

/// The fraction of `attempt` at which its `u` reaches `ut` (which it passes by its end), by
/// bisection on the step's dense output.
fn throat_crossing(attempt: &dopri5::Attempt<4>, ut: f64) -> f64 {
    let (mut lo, mut hi) = (0.0, 1.0);
    for _ in 0..48 {
        let mid = 0.5 * (lo + hi);
        if attempt.dense_component(mid, 0) < ut {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    hi
}

/// The state `[u, u', J, J']` of a ray at or past the throat (`u ≥ u_t`) in the other region's
/// variable `ũ = u_t²/u`, at the same azimuth (module docs).
fn through_throat(ut: f64, [u, du, j, dj]: [f64; 4]) -> [f64; 4] {
    let ratio = ut * ut / (u * u);
    [ut * ut / u, -ratio * du, -ratio * j, -ratio * dj + 2.0 * ratio * du * j / u]
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
        let mut beyond = false;
        for _ in 0..MAX_STEPS {
            let step = h.min(self.sweep - phi);
            let attempt = dopri5::attempt(&f, phi, &y, &k, step);
            let scale = |a: usize, y0: &[f64; 4], y1: &[f64; 4]| {
                (y0[a].abs() + y0[a + 1].abs()).max(y1[a].abs() + y1[a + 1].abs())
            };
            let norm = |a: usize| {
                let (e0, e1) = (attempt.error[a], attempt.error[a + 1]);
                (e0 * e0 + e1 * e1).sqrt() / (self.rtol * scale(a, &y, &attempt.y1))
            };
            let err = norm(0).max(norm(2));
            if !(err <= 1.0) {
                h = step * if err.is_finite() { dopri5::step_factor(err).min(1.0) } else { 0.2 };
                if h <= 1e-15 {
                    return None;
                }
                continue;
            }
            h = step * dopri5::step_factor(err);
            match self.metric.throat_u().filter(|&ut| attempt.y1[0] >= ut) {
                // Cut the step where it reaches the throat (the chart's equation need not hold
                // past it), and carry on in the other region's variable.
                Some(ut) if !beyond && self.side == Side::Other => {
                    let cut = step * throat_crossing(&attempt, ut);
                    let at_throat = dopri5::attempt(&f, phi, &y, &k, cut).y1;
                    (phi, y, beyond) = (phi + cut, through_throat(ut, at_throat), true);
                    k = f(phi, &y);
                    continue;
                }
                Some(_) => return Some(Shot::Above),
                None => (phi, y, k) = (phi + step, attempt.y1, attempt.end_derivative()),
            }
            if y[0] <= 0.0 {
                return Some(if beyond { Shot::Above } else { Shot::Below });
            }
            if self.metric.capture_u().is_some_and(|uc| y[0] >= uc) {
                return Some(Shot::Above);
            }
            if phi >= self.sweep {
                let [u, du, jacobi, _] = y;
                return Some(Shot::Reached { u, du, jacobi, beyond });
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
        // |sin Δφ| either way: the plane's turn moves the point by ρ_y |sin Δφ|.
        let radial_y: [f64; 3] = std::array::from_fn(|i| cos_sweep * radial[i] + sin_sweep * across[i]);
        let azimuthal_y: [f64; 3] = std::array::from_fn(|i| -sin_sweep * radial[i] + cos_sweep * across[i]);
        let in_plane = |r: f64, a: f64| normalize3(&std::array::from_fn(|i| r * radial_y[i] + a * azimuthal_y[i]));
        let (rho, slope) = (metric.world_radius(u_y), metric.world_radius_slope(u_y));
        // The static observer sees `(n_r, n_φ) ∝ (−σ u', u)`; the world tangent is `dW/dφ`.
        let turned = |v: [f64; 3]| match self.side {
            Side::Same => v,
            Side::Other => scale3(&v, -1.0),
        };
        let end = turned(in_plane(-metric.radial_stretch(u_y) * du, u_y));
        let tangent_phi = rho / (slope * du).hypot(rho);
        let end_tangent = turned(in_plane(slope * du, rho));
        let solid_angle_per_area = sin / ((slope * jacobi).abs() * tangent_phi * rho * sin_sweep.abs());
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
            check_every_step: true,
        };
        let four_d = AimSettings { trace, tolerance: 1e-9, max_shots: 40 };
        let mut compared = 0;
        for (x, y) in pairs() {
            let Some(found) = plane_aim(metric, x, (y, Side::Same), Way::Short, &SETTINGS) else { continue };
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
            let found = plane_aim(&metric, x, (y, Side::Same), Way::Short, &SETTINGS).unwrap();
            let chord: [f64; 3] = std::array::from_fn(|i| y[i] - x[i]);
            let d2 = dot3(&chord, &chord);
            assert!((found.solid_angle_per_area * d2 - 1.0).abs() < 1e-6, "{}", found.solid_angle_per_area * d2);
            let along = normalize3(&chord);
            assert!(norm3(&std::array::from_fn(|i| found.start[i] - along[i])) < 1e-6);
            assert!(norm3(&std::array::from_fn(|i| found.end[i] - along[i])) < 1e-6);
        }
    }

    /// Both ways round a Schwarzschild hole, the aim finds the rays Schwarzschild's own
    /// connector finds (Binet's equation by Taylor series, Newton on the start slope): start and
    /// end directions to 1e-6, density to 1e-5, sweeps that add up to 2π.
    #[test]
    fn both_ways_agree_with_the_schwarzschild_connector() {
        let hole = Schwarzschild::new(0.5);
        let connector = crate::metric::schwarzschild::connect::Connector::new(hole);
        let close = |a: [f64; 3], b: [f64; 3]| norm3(&std::array::from_fn(|i| a[i] - b[i]));
        let mut compared = [0; 2];
        for (x, y) in pairs() {
            for (k, way) in Way::BOTH.into_iter().enumerate() {
                let (Some(found), Some(own)) =
                    (plane_aim(&hole, x, (y, Side::Same), way, &SETTINGS), connector.connect(x, y, way))
                else {
                    continue;
                };
                compared[k] += 1;
                assert!(close(found.start, own.start) < 1e-6, "{way:?} {x:?} → {y:?}: start {:?}", found.start);
                assert!(close(found.end, own.end) < 1e-6, "{way:?} {x:?} → {y:?}: end {:?}", found.end);
                let density = found.solid_angle_per_area / own.solid_angle_per_area - 1.0;
                assert!(density.abs() < 1e-5, "{way:?} {x:?} → {y:?}: density off by {density:e}");
            }
        }
        assert!(compared.iter().all(|&n| n >= 15), "compared {compared:?} of {} pairs", pairs().len());
    }

    /// The long way round a wormhole's throat passes close to it and lands on the target, its
    /// direction leaving on the far side of the centre from the short way's.
    #[test]
    fn the_long_way_round_a_throat_reaches_the_target() {
        let throat = Ellis::new(1.2);
        let mut found_any = 0;
        for (x, y) in pairs() {
            let (Some(short), Some(long)) = (
                plane_aim(&throat, x, (y, Side::Same), Way::Short, &SETTINGS),
                plane_aim(&throat, x, (y, Side::Same), Way::Long, &SETTINGS),
            ) else {
                continue;
            };
            found_any += 1;
            let towards = normalize3(&std::array::from_fn(|i| y[i] - x[i]));
            let across = |d: [f64; 3]| {
                let n = crate::tensor::cross3(&x, &y);
                dot3(&crate::tensor::cross3(&x, &d), &n)
            };
            assert!(across(short.start) > 0.0 && across(long.start) < 0.0, "{x:?} → {y:?}: same side");
            assert!(dot3(&long.start, &towards) < dot3(&short.start, &towards));
            assert!(long.solid_angle_per_area < short.solid_angle_per_area, "a long way's image is smaller");
        }
        assert!(found_any >= 15, "only {found_any} pairs aimed both ways");
    }

    /// Aims through the throat, each way round: the ray leaving along the aimed direction,
    /// traced by the in-plane tracer, passes the target in the other region, arriving along the
    /// aimed end direction; the density matches finite differences of neighbouring aims (the
    /// solid angle their start directions span per area their targets span across the beam).
    fn aims_through_the_throat<M: PlaneMetric>(metric: &M) {
        // A long way through a throat sweeps far: its shots' rounding noise is above 1e-9.
        const SETTINGS: PlaneAimSettings = PlaneAimSettings { rtol: 1e-10, tolerance: 1e-8 };
        use crate::geodesic::plane::{trace_plane, PlaneStart};
        use crate::geodesic::Visit;
        let trace = TraceSettings {
            integrator: Integrator::Adaptive { rtol: 1e-11 },
            escape_radius: 1e3,
            max_step_fraction: 1.0,
            max_steps: 100_000,
            check_every_step: true,
        };
        let mut compared = [0; 2];
        for (x, y) in pairs() {
            for (k, way) in Way::BOTH.into_iter().enumerate() {
                let Some(found) = plane_aim(metric, x, (y, Side::Other), way, &SETTINGS) else { continue };
                compared[k] += 1;
                let start = PlaneStart::from_observer(metric, Region::Upper, x, found.start).unwrap();
                let mut nearest = (f64::INFINITY, [0.0; 3]);
                trace_plane(metric, start, &trace, |step| {
                    if step.region() == Region::Lower {
                        let miss = |theta: f64| {
                            let at = step.position(metric, theta);
                            norm3(&std::array::from_fn(|j| at[j] - y[j]))
                        };
                        // The nearest of 64 knots, then the nearest point between its neighbours.
                        let knot = (0..=64).map(|i| f64::from(i) / 64.0).min_by(|a, b| miss(*a).total_cmp(&miss(*b)));
                        let (mut a, mut b) =
                            knot.map_or((0.0, 0.0), |t| ((t - 1.0 / 64.0).max(0.0), (t + 1.0 / 64.0).min(1.0)));
                        for _ in 0..100 {
                            let (p, q) = (a + (b - a) / 3.0, b - (b - a) / 3.0);
                            (a, b) = if miss(p) < miss(q) { (a, q) } else { (p, b) };
                        }
                        if miss(a) < nearest.0 {
                            nearest = (miss(a), step.point(metric, a).direction);
                        }
                    }
                    Visit::Continue
                });
                let (miss, direction) = nearest;
                // The aim's tolerance is 1e-9, the tracer's 1e-8 relative.
                assert!(miss < 1e-6, "{way:?} {x:?} → {y:?}: passes the target {miss:e} away");
                let turn = norm3(&std::array::from_fn(|i| direction[i] - found.end[i]));
                assert!(turn < 1e-6, "{way:?} {x:?} → {y:?}: arrives along {direction:?}, aimed {:?}", found.end);

                let t = found.end_tangent;
                let e1 = normalize3(&crate::tensor::cross3(&t, &[0.3, 0.5, 0.8]));
                let e2 = crate::tensor::cross3(&t, &e1);
                let delta = 1e-4;
                let beside = |e: [f64; 3], side: f64| {
                    let target = std::array::from_fn(|i| y[i] + side * delta * e[i]);
                    match plane_aim(metric, x, (target, Side::Other), way, &SETTINGS) {
                        Some(a) => a.start,
                        None => panic!("{way:?} {x:?} → {target:?} not aimed at ({:?})", found.shots),
                    }
                };
                // Central differences: the span of start directions per 2δ across the beam.
                let span = |e: [f64; 3]| {
                    let (ahead, behind) = (beside(e, 1.0), beside(e, -1.0));
                    std::array::from_fn(|i| ahead[i] - behind[i])
                };
                let solid_angle = norm3(&crate::tensor::cross3(&span(e1), &span(e2)));
                let density = solid_angle / (4.0 * delta * delta) / found.solid_angle_per_area - 1.0;
                assert!(density.abs() < 1e-3, "{way:?} {x:?} → {y:?}: density off by {density:e}");
            }
        }
        assert!(compared.iter().all(|&n| n >= 12), "aimed {compared:?} of {} pairs", pairs().len());
    }

    #[test]
    fn aims_through_the_throat_of_an_ellis_wormhole() {
        aims_through_the_throat(&Ellis::new(1.2));
    }

    #[test]
    fn aims_through_the_throat_of_the_interstellar_wormhole() {
        aims_through_the_throat(&crate::metric::MorrisThorne::new(crate::metric::Dneg::new(1.0, 0.5, 0.2)));
    }

    #[test]
    fn points_in_line_with_the_centre_have_no_plane() {
        for way in Way::BOTH {
            assert_eq!(
                plane_aim(&Ellis::new(1.0), [3.0, 0.0, 0.0], ([-5.0, 0.0, 0.0], Side::Same), way, &SETTINGS),
                None
            );
            assert_eq!(
                plane_aim(&Ellis::new(1.0), [3.0, 0.0, 0.0], ([5.0, 0.0, 0.0], Side::Other), way, &SETTINGS),
                None
            );
        }
    }
}

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
//! which is `1/d²` in flat space (law of sines), and equation (3) of
//! [`connect`](crate::metric::schwarzschild::connect) about Schwarzschild.

use super::shoot::{Shooter, Shot};
use super::PlaneMetric;
use crate::tensor::{dot3, norm3, scale3};
use std::f64::consts::PI;

/// Below this `sin Δφ` the plane is undetermined (`y` on the line through the centre and `x`).
const MIN_SIN_SWEEP: f64 = 1e-9;
/// Shots before the aim gives up: Newton's method needs three to five from the straight line,
/// bisection alone halves the bracket (0, π) to 10⁻¹² in forty.
const MAX_SHOTS: u32 = 48;

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

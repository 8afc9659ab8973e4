//! The chart's coordinate time along an in-plane ray, for callers that ask for it
//! ([`trace_plane_in_time`](super::trace_plane_in_time)): integrated over each step's dense
//! output ([`quadrature`](crate::geodesic::quadrature)), never by the stepper, so a ray traced
//! without it takes the same steps at the same cost.
//!
//! Rays are traced backwards: the traced ray runs from the camera into the past, and the
//! chart's time falls along it. With `E = 1` and `b = L` (the plane's convention), a static
//! metric `−α² dt² + … + ρ² dΩ²` has `dt/dλ = 1/α²`, `dφ/dλ = b/ρ²`, so along the traced ray
//!
//! ```text
//! −dt/dφ = ρ²/(α² b)   (curved steps),    −dt/dl = 1/α, i.e. −dt/dρ = 1/(α κ)   (radial rays),
//! ```
//!
//! `l` the proper radial length and `κ = dρ/dl` ([`PlaneMetric::radial_scale`]). A hole's chart
//! is outgoing Kerr–Schild ([`ChartTime::OutgoingKerrSchild`]), whose time is `t̃ = t − h(r)` with
//! `dh/dr = m/f`, `f = α² = 1 − m`, `m = 2M/r − Q²/r²` (`docs/physics.md`, "Charts of each
//! metric"), so `−dt̃/dφ = (r²/f)(1/b − m u')`. Its factor `1/f` is cancelled by the bracket on
//! the past horizon that backward rays cross (`u' → 1/b` there), and with `u'² = 1/b² − u²f`
//!
//! ```text
//! −dt̃/dφ = r² ((1 + m)/b² + m²u²) / (1/b + m u'),
//! ```
//!
//! regular everywhere outside the horizon and on it (`|m u'| < 1/b` wherever `f > 0`). Radially,
//! `−dt̃/dρ` is 1 inwards (the photon, outgoing, keeps `t̃ − r` fixed) and `(1 + m)/f` outwards.
//!
//! Far from the centre the rate grows as `1/(b u²)` (the time a ray takes is its length), a pole
//! at `u = 0` just past the step that reaches the escape radius. The flat part of the time is
//! taken out exactly: in flat space the time along the line is `b u'/u` (minus the distance from
//! closest approach), and along any ray `d(b u'/u)/dφ = −b (S(u) + u² − u G(u))/u²` with
//! `S = u'²` and `G` the Binet source, so the quadrature integrates only the difference of the
//! two rates, whose pole is weaker (`2M/(b u)`: the Shapiro delay) and whose size is small.

use super::step::{PlaneAttempt, Segment};
use super::PlaneMetric;
use crate::geodesic::quadrature::integrate;

/// The time coordinate of a [`PlaneMetric`]'s 4-D chart, which the in-plane tracer reports.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ChartTime {
    /// The static observers' time `t` (Killing time with `g_ti = 0`).
    Static,
    /// The outgoing Kerr–Schild time `t̃ = t − h(r)` of a hole `g = η + m l ⊗ l`, whose lapse is
    /// `α² = 1 − m` and world radius the areal radius `1/u`.
    OutgoingKerrSchild,
}

/// Relative tolerance of the quadrature of a step's time, far below the steps' own truncation.
const RTOL: f64 = 1e-13;

/// The chart time where a step starts, and the ray's impact parameter: what a step needs to
/// give the time anywhere inside it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Clock {
    pub(super) start: f64,
    pub(super) b: f64,
}

/// `−dt/dφ` at `(u, u')` on a ray of impact parameter `b` (positive: time falls along the
/// backward ray).
fn fall_per_azimuth<M: PlaneMetric + ?Sized>(metric: &M, u: f64, du: f64, b: f64) -> f64 {
    match metric.chart_time() {
        ChartTime::Static => {
            let (rho, lapse) = (metric.world_radius(u), metric.lapse(u));
            rho * rho / (lapse * lapse * b)
        }
        ChartTime::OutgoingKerrSchild => {
            let lapse = metric.lapse(u);
            let m = 1.0 - lapse * lapse;
            let inv_b = 1.0 / b;
            ((1.0 + m) * inv_b * inv_b + m * m * u * u) / (u * u * (inv_b + m * du))
        }
    }
}

/// `−dt/dρ` at `u` on a radial ray going `outward` (or inward) in world radius.
fn fall_per_radius<M: PlaneMetric + ?Sized>(metric: &M, u: f64, outward: bool) -> f64 {
    match metric.chart_time() {
        ChartTime::Static => 1.0 / (metric.lapse(u) * metric.radial_scale(u)),
        ChartTime::OutgoingKerrSchild if outward => {
            let f = metric.lapse(u).powi(2);
            (2.0 - f) / f
        }
        ChartTime::OutgoingKerrSchild => 1.0,
    }
}

/// The time that falls over the first fraction `theta` of the integrator step `attempt` that
/// starts at azimuth `phi0` of `segment`, on a ray of impact parameter `b` (module
/// documentation: the flat part exactly, the rest by quadrature).
pub(super) fn curved_fall<M: PlaneMetric + ?Sized>(
    metric: &M,
    segment: &Segment,
    phi0: f64,
    attempt: &PlaneAttempt,
    b: f64,
    theta: f64,
) -> f64 {
    let inv_b2 = 1.0 / (b * b);
    let flat = |theta: f64| {
        let (_, u, du) = super::PlaneStep::curve(segment, phi0, attempt, theta);
        b * du / u
    };
    let rest = |theta: f64| {
        let (_, u, du) = super::PlaneStep::curve(segment, phi0, attempt, theta);
        let flat_rate = b * (metric.slope_squared(u, inv_b2) + u * u - u * metric.binet_source(u, inv_b2)) / (u * u);
        fall_per_azimuth(metric, u, du, b) - flat_rate
    };
    let (h, flat0, flat1) = (attempt.h(), flat(0.0), flat(theta));
    // The difference of the rates loses the digits of their size, the time's: no interval need
    // be resolved below them.
    let atol = RTOL * (flat0.abs() + flat1.abs()) / h;
    flat0 - flat1 + h * integrate(&rest, 0.0, theta, RTOL, atol)
}

/// The time that falls over the distance `s` of a straight piece from world radius `rho` (in
/// flat space, or along a radius: outward if `outward`).
pub(super) fn straight_fall<M: PlaneMetric + ?Sized>(metric: &M, rho: f64, outward: bool, s: f64) -> f64 {
    if metric.is_flat() || s == 0.0 {
        return s;
    }
    let sign = if outward { 1.0 } else { -1.0 };
    let rate = |sigma: f64| match metric.u_of_world_radius(rho + sign * sigma) {
        Some(u) => fall_per_radius(metric, u, outward),
        None => f64::NAN,
    };
    integrate(&rate, 0.0, s, RTOL, 0.0)
}

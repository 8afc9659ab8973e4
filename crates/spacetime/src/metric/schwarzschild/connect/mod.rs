//! Connecting two points of Schwarzschild spacetime by a light ray, with the ray bundle's
//! density: the shooting problem behind next-event estimation along geodesics.
//!
//! The centre, the start `x` and the end `y` span one plane, and every ray from `x` to `y` lies
//! in it (`docs/physics.md`, "Charts of each metric"). There the ray leaves `x` at angle `ψ` from the
//! outward radial direction, measured by the static observer, and obeys the Binet equation
//!
//! ```text
//! u'' = −u + 3Mu²,   u(0) = u_x,   u'(0) = s = −(u_x/σ_x) cot ψ,              (1)
//! ```
//!
//! (`u = 1/r`, `' = d/dφ`, `σ = 1/√(1 − 2Mu)` the static frame's radial stretch). Its Jacobi field
//! `J = ∂u/∂s` at fixed `φ` obeys the variational equation
//!
//! ```text
//! J'' = −(1 − 6Mu) J,   J(0) = 0,   J'(0) = 1.                                  (2)
//! ```
//!
//! Since `1 − 6Mu ≤ 1`, Sturm's comparison theorem puts the first zero of `J` at `φ ≥ π`, so for
//! every `Δφ ∈ (0, π]` the radius `u(Δφ; ψ)` is strictly increasing in `ψ`: the ray that sweeps
//! the short way round (`Δφ ≤ π`) is unique where it exists, and a bracketed Newton iteration on
//! the start slope `s`, which rises with `ψ ∈ (0, π)`, finds it. Rays that escape before `Δφ`
//! bracket it from below, captured ones from above.
//!
//! The long way round sweeps `2π − Δφ` in the plane's other sense. Such rays pass close to the
//! photon sphere (`b` just above `3√3 M`), where `1 − 6Mu < 0` and `J` grows instead of turning:
//! a point source in Schwarzschild has no radial caustic (its only caustics lie on the axis
//! through the hole; Bozza 2002, strong deflection limit), so `J > 0` there too and the same
//! bracketed iteration, on `ψ` below the critical angle, finds the unique long-way ray. A
//! converged ray with `J ≤ 0` would contradict that and is rejected. Higher windings
//! (`Δφ + 2πk`, `k ≥ 1`) are not found.
//!
//! Newton's step `δs = −(u − u_y)/J` leaves the miss `K δs²/2` of the quadratic term, with
//! `K = ∂²u/∂s² = ∂J/∂s` from differentiating (2):
//!
//! ```text
//! K'' = −(1 − 6Mu) K + 6M J²,   K(0) = K'(0) = 0.                               (4)
//! ```
//!
//! Where that bound is within tolerance the step is not shot again to confirm it: the ray's slope
//! and Jacobi field at `y` follow it to first order (`∂u'/∂s = J'`, `∂J/∂s = K`), errors second
//! order in `δs` like the miss. Shots far from the target are integrated coarsely (Newton's step
//! only needs them to a fraction of their miss); the last one, whose step is taken unconfirmed,
//! at full tolerance. Each way's start is tabulated (`start_table`) for ends the table covers,
//! close enough for the first shot to be the fine one: a typical connection is that one shot
//! (from the first guesses alone, one or two coarse shots come before it).
//!
//! Density: turning `ψ` by `dψ` moves the ray at `φ = Δφ` radially by `∂r/∂ψ = −J/u_y² · ds/dψ`,
//! with `ds/dψ = u_x/(σ_x sin²ψ)`; turning the plane by `dχ` about the axis through the centre
//! and `x` moves it by `r_y sin Δφ dχ` out of the plane. The solid angle at `x` is
//! `dΩ = sin ψ dψ dχ`, and the beam's world-coordinate cross-section at `y`, perpendicular to the
//! world tangent `t` (in-plane tangential component `t_φ`), is `|∂r/∂ψ| t_φ · r_y sin Δφ dψ dχ`:
//!
//! ```text
//! dΩ/dA⊥ = sin³ψ σ_x u_y³ / (u_x J sin Δφ t_φ),                                (3)
//! ```
//!
//! which is `1/d²` in flat space (`J = sin φ`, law of sines).

use super::binet_taylor;
use crate::geodesic::plane::{PlaneAxes, Way};
use crate::metric::Schwarzschild;
use crate::tensor::{cross3, dot3, norm3, normalize3, scale3};
use connection::{world_tangent, Ends, StartDirection};
use guess::{critical_sin, first_guess, guessed_parameter, inward_slope, long_start_slope, slope_scale};
use start_table::StartTables;
use std::f64::consts::PI;
use std::sync::Arc;

mod connection;
mod guess;
mod start_table;

pub use connection::{Connection, Waypoints};

/// Relative tolerance of the final shot's integration, per Taylor step. The connection serves
/// Monte Carlo sampling, where a relative error of 10⁻⁵ in a density is far below the noise, and
/// the tracer finds hits to a chord tolerance ε of 10⁻⁴ of the scene's radius: misses of 10⁻⁵ r
/// stay a tenth of it. Long ways round amplify the integration's error near the photon sphere:
/// on the tests' bundles (M = 1, a long way from r = 10) the largest miss is 8·10⁻⁶ r at 10⁻⁷
/// (2.7·10⁻⁷ r at 3·10⁻⁸, 1.35·10⁻⁷ r at 10⁻⁸, where Newton's own stopping term, `UTOL`, takes
/// over). The short way round stays well off the photon sphere and meets the same bounds at
/// 10⁻⁶ (misses seen up to 8·10⁻⁶ r). The looser pair, 10⁻⁶ and 10⁻⁷ rather than 10⁻⁷ and
/// 10⁻⁸, takes fewer Taylor steps in the render's solver and in the tables' build
/// (docs/perf-journal.md).
const fn final_rtol(way: Way) -> f64 {
    match way {
        Way::Short => 1e-6,
        Way::Long => 1e-7,
    }
}
/// Relative tolerance of the shots before the last, about the miss of the first guess.
const RTOL_COARSE: f64 = 1e-4;
/// A shot at full tolerance follows once Newton's model predicts a miss below this fraction of
/// `u_y`: from there its own step is usually within `UTOL` (a miss `ε u_y` leaves `K δs²/2`, of
/// order `ε² u_y` away from the photon sphere). Measured (at rtol 1e-6): 1e-4 costs 6 % more
/// steps, 1e-2 11 % more the long way.
const FINE_GATE: f64 = 1e-3;
/// Newton iterations converge when the miss left after the step, to second order, is within this
/// fraction of `u_y`.
const UTOL: f64 = 1e-6;
/// Below this `sin Δφ` the plane of the ray is undetermined (`y` on the line through the centre
/// and `x`): no connection is returned.
const MIN_SIN_SWEEP: f64 = 1e-9;
const MAX_ITERATIONS: u32 = 100;
/// A ray is dropped by [`Connector::connect_along`] when it meets the surface from behind by more than
/// this cosine: ten times the error of the direction it is judged by.
const FACING_MARGIN: f64 = 1e-2;
const MAX_STEPS: u32 = 10_000;

/// How one shot from `x` ended.
enum Shot {
    /// `u` reached 0 before the target azimuth: `ψ` is too small.
    Escapes,
    /// The ray crossed the horizon before the target azimuth: `ψ` is too large.
    Captured,
    /// `(u, u', J, J', K, K')` at the target azimuth, equations (1), (2) and (4).
    Reaches([f64; 6]),
}

/// Joins points of one Schwarzschild spacetime by light rays. It owns the tables of first
/// shots ([`StartTables`], built on each way's first use and shared by clones), so a render
/// builds one with its propagator and no state outlives it.
#[derive(Clone, Debug)]
pub struct Connector {
    metric: Schwarzschild,
    tables: Arc<StartTables>,
}

impl Connector {
    pub fn new(metric: Schwarzschild) -> Self {
        Self { metric, tables: Arc::default() }
    }

    /// A connector for the hole `metric` sharing this one's tables, which hold for every mass.
    pub fn for_hole(&self, metric: Schwarzschild) -> Self {
        Self { metric, tables: Arc::clone(&self.tables) }
    }

    /// The ray that leaves world point `x` and reaches world point `y` going `way` round the
    /// centre (both outside the horizon), or `None` where there is none (it would be captured,
    /// `y` lies on the line through the centre and `x`, or, the long way, `x` lies inside the
    /// photon sphere).
    pub fn connect(&self, x: [f64; 3], y: [f64; 3], way: Way) -> Option<Connection> {
        self.connect_along(x, y, way, None, &mut Waypoints::default())
    }

    /// [`Connector::connect`], filling `waypoints` with points along the ray (overwritten by
    /// each call), and to a point `y` on a surface that only the rays reaching it from the side
    /// of its world normal `facing` matter for (a one-sided emitter): a ray found arriving from
    /// the other side is dropped as soon as a shot gives its direction to about 10⁻³, before any
    /// shot that would refine it (rays within 10⁻² in the cosine of grazing the surface are kept
    /// and refined).
    pub fn connect_along(
        &self,
        x: [f64; 3],
        y: [f64; 3],
        way: Way,
        facing: Option<[f64; 3]>,
        waypoints: &mut Waypoints,
    ) -> Option<Connection> {
        solve(&self.metric, x, y, way, facing, Some(&self.tables), waypoints)
    }
}

/// [`Connector::connect_along`], starting from the tabulated
/// [`start_parameter`](guess::start_parameter) where `tables` are given and the way's table
/// covers the ends, else from [`guessed_parameter`].
fn solve(
    metric: &Schwarzschild,
    x: [f64; 3],
    y: [f64; 3],
    way: Way,
    facing: Option<[f64; 3]>,
    tables: Option<&StartTables>,
    waypoints: &mut Waypoints,
) -> Option<Connection> {
    let (rx, ry) = (norm3(&x), norm3(&y));
    let horizon = 2.0 * metric.mass;
    if !(rx > horizon && ry > horizon) {
        return None;
    }
    if way == Way::Short && facing.is_some_and(|n| short_way_arrives_behind(n, x, y)) {
        return None;
    }
    // Rays leaving inward at more than the critical angle `ψ_c` (impact parameter
    // b = sin ψ/(u_x √(1 − 2Mu_x)) below 3√3 M) are captured. Inside the photon sphere the
    // critical angle lies on the outward side instead, and the long way is not sought.
    if way == Way::Long && !(rx > 3.0 * metric.mass && metric.mass > 0.0) {
        return None;
    }
    let (xh, yh) = (scale3(&x, 1.0 / rx), scale3(&y, 1.0 / ry));
    let (cos, sin) = (dot3(&xh, &yh), norm3(&cross3(&xh, &yh)));
    if sin < MIN_SIN_SWEEP {
        return None;
    }
    let short = sin.atan2(cos);
    let e2 = normalize3(&std::array::from_fn(|i| yh[i] - cos * xh[i]));
    let (ux, uy) = (1.0 / rx, 1.0 / ry);
    let slope_scale = slope_scale(metric.mass, ux);
    let m = metric.mass;
    // The long way sweeps `2π − Δφ` in the plane's other sense: the same cosine, the other sine.
    let (e2, sweep, sweep_sin_cos) = match way {
        Way::Short => (e2, short, (sin, cos)),
        Way::Long => (scale3(&e2, -1.0), 2.0 * PI - short, (-sin, cos)),
    };
    let at_y = PlaneAxes::at_sin_cos(&xh, &e2, sweep_sin_cos);
    let correction = tables.and_then(|t| t.get(way).correction(m * ux, m * uy, sweep));
    // A tabulated start is close enough for the first shot to be the fine one.
    let mut fine = correction.is_some();
    let mut s = match way {
        // The short way's parameter is `Ms`: the guess, the slope of `first_guess`, holds
        // without mass too.
        Way::Short => first_guess(m, ux, uy, cos, sin) + correction.map_or(0.0, |c| c / m),
        Way::Long => {
            let guess = guessed_parameter(way, m, ux, uy, cos, sin, sweep);
            long_start_slope(m, ux, guess + correction.unwrap_or(0.0))
        }
    };
    let mut bracket = Bracket::of(way, m, ux);
    for _ in 0..MAX_ITERATIONS {
        let rtol = if fine { final_rtol(way) } else { RTOL_COARSE };
        match shoot(metric, ux, s, sweep, rtol, waypoints)? {
            Shot::Escapes => bracket.low = s,
            Shot::Captured => bracket.high = s,
            Shot::Reaches(end) => {
                let f = end[0] - uy;
                // Newton's step, and the miss it leaves to second order, equation (4).
                let step = -f / end[2];
                let remaining = (0.5 * end[4] * step * step).abs();
                if remaining <= FINE_GATE * uy
                    && facing
                        .is_some_and(|n| dot3(&n, &world_tangent(&at_y, uy, end[1] + end[3] * step)) > FACING_MARGIN)
                {
                    // It meets the surface from behind.
                    return None;
                }
                if fine && remaining <= UTOL * uy {
                    // The step taken unconfirmed: slope and Jacobi field at `y` follow it to first
                    // order, equation (4).
                    let (du, jacobi) = (end[1] + end[3] * step, end[2] + end[4] * step);
                    (waypoints.xh, waypoints.e2, waypoints.step) = (xh, e2, step);
                    let start = StartDirection::of_slope(s + step, slope_scale);
                    let (sin_sweep, _) = sweep_sin_cos;
                    let ends = Ends { xh, e2, at_y, sin_sweep, sweep, start, ux, uy, du, jacobi };
                    return ends.connection(metric);
                }
                // A shot's sign is trusted only well above its own integration error.
                if f.abs() > 10.0 * rtol * uy {
                    if f < 0.0 {
                        bracket.low = s;
                    } else {
                        bracket.high = s;
                    }
                }
                fine |= remaining <= FINE_GATE * uy;
                if s + step > bracket.low && s + step < bracket.high {
                    s += step;
                    continue;
                }
            }
        }
        s = bracket.bisect(slope_scale)?;
    }
    None
}

/// The start slopes known to fall short (`low`: the ray escapes or passes outside `y`) and to
/// overshoot (`high`: captured or inside `y`). Slopes rise with the start angle,
/// `s = −(u_x/σ_x) cot ψ`: Newton's steps are tested against the slopes, bisection halves the
/// angles (the slopes run to infinity at `ψ = 0` and `π`).
struct Bracket {
    low: f64,
    high: f64,
}

impl Bracket {
    /// All rays the short way; the long way's start inward of its critical angle `ψ_c`.
    fn of(way: Way, mass: f64, ux: f64) -> Self {
        let high = match way {
            Way::Short => f64::INFINITY,
            Way::Long => inward_slope(mass, ux, critical_sin(mass, ux)),
        };
        Self { low: f64::NEG_INFINITY, high }
    }

    /// The slope at the middle angle of the bracket, `None` once it is closed.
    fn bisect(&self, slope_scale: f64) -> Option<f64> {
        let angle = |s: f64| slope_scale.atan2(-s);
        let (low, high) = (angle(self.low), angle(self.high));
        (high - low > 1e-15).then(|| -slope_scale / (0.5 * (low + high)).tan())
    }
}

/// Whether the short way from `from` to `to` can only reach the plane through `to` with normal
/// `n` from behind (travelling along `n`): so when the centre lies on or in front of that plane
/// and `from` on or behind it. Reversed, the same ray leaves `to` into the side away from `n`:
/// an opaque surface at `to` whose front faces the centre reflects none of it.
///
/// Proof. In the ray's plane the surface's plane leaves a line, `u_L(φ) = cos(φ − φ_L)/d` in
/// polar coordinates about the centre (`d > 0` its distance), and the centre's side is
/// `u > u_L`. The ray's `g = u − u_L` obeys `g'' + g = 3Mu² > 0` by (1), since `u_L'' + u_L = 0`.
/// It starts on or behind the line (`g(0) ≤ 0`) and reaches it at `Δφ < π`. Arriving from the
/// front needs a last crossing `φ₁ ∈ [0, Δφ)` with `g > 0` on `(φ₁, Δφ)`; with `w = sin(φ − φ₁)`,
/// positive there, `∫(g'' + g) w dφ = [g'w − gw']` over `(φ₁, Δφ)` gives
/// `g'(Δφ) sin(Δφ − φ₁) > 0`: `g` rises through zero at `Δφ`, so it was negative just before, a
/// contradiction (Sturm's comparison, as for equation (2)): within a sweep below π a ray that has
/// crossed to the centre's side cannot come back to the plane. A line through the centre (`d = 0`)
/// is met at two azimuths π apart, so a sweep below π crosses it once at most.
pub fn short_way_arrives_behind(n: [f64; 3], from: [f64; 3], to: [f64; 3]) -> bool {
    let at = dot3(&n, &to);
    at <= 0.0 && dot3(&n, &from) <= at
}

/// Integrates (1), (2) and (4) from `φ = 0` to `sweep` by Taylor series at relative tolerance
/// `rtol` per step (see [`binet_taylor`]); `None` if it does not finish in `MAX_STEPS`. `K`
/// only sizes Newton's neglected term, so it is left out of the step control.
fn shoot(metric: &Schwarzschild, ux: f64, s: f64, sweep: f64, rtol: f64, track: &mut Waypoints) -> Option<Shot> {
    let capture = 1.0 / (2.0 * metric.mass);
    // Absolute floors keep the step rule finite where a component passes through zero.
    let floor = [1e-3 * ux, 1e-3];
    let mut y = [ux, s, 0.0, 1.0, 0.0, 0.0];
    let mut phi = 0.0;
    track.count = 0;
    for _ in 0..MAX_STEPS {
        let remaining = sweep - phi;
        let (next, h) = binet_taylor::step(metric.mass, &y, remaining, rtol, floor);
        (phi, y) = (phi + h, next);
        if y[0] <= 0.0 {
            return Some(Shot::Escapes);
        }
        if y[0] >= capture {
            return Some(Shot::Captured);
        }
        if h >= remaining {
            return Some(Shot::Reaches(y));
        }
        track.push(phi, &y);
    }
    None
}

//! Connecting two points of Schwarzschild spacetime by a light ray, with the ray bundle's
//! density: the shooting problem behind next-event estimation along geodesics.
//!
//! The centre, the start `x` and the end `y` span one plane, and every ray from `x` to `y` lies
//! in it (physics notes, "Charts without trouble"). There the ray leaves `x` at angle `ψ` from the
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
use crate::geodesic::plane::{PlaneAxes, PlaneMetric, Way};
use crate::geodesic::tangent_triangle::tangent_triangle;
use crate::metric::Schwarzschild;
use crate::tensor::{cross3, dot3, norm3, normalize3, scale3};
use start_table::StartTables;
use std::f64::consts::PI;
use std::sync::Arc;

mod start_table;

/// Relative tolerance of the final shot's integration, per Taylor step. The connection serves
/// Monte Carlo sampling, where a relative error of 10⁻⁵ in a density is far below the noise, and
/// the tracer finds hits to a chord tolerance ε of 10⁻⁴ of the scene's radius: misses of 10⁻⁵ r
/// stay a tenth of it. Long ways round amplify the integration's error near the photon sphere:
/// on the tests' bundles (M = 1, a long way from r = 10) the largest miss is 8·10⁻⁶ r at 10⁻⁷
/// (2.7·10⁻⁷ r at 3·10⁻⁸, 1.35·10⁻⁷ r at 10⁻⁸, where Newton's own stopping term, `UTOL`, takes
/// over). The short way round stays well off the photon sphere and meets the same bounds at
/// 10⁻⁶ (misses seen up to 8·10⁻⁶ r). On the black-hole room, 10⁻⁶ and 10⁻⁷ instead of 10⁻⁷ and
/// 10⁻⁸ take 14 % fewer instructions in the render's solver and 16 % in the tables' build.
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

/// A ray from `x` to `y` and its density.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Connection {
    /// Unit direction the ray leaves `x` in, in the static frame at `x` (axes along the world's).
    pub start: [f64; 3],
    /// Unit world-coordinate tangent at `x`.
    pub start_tangent: [f64; 3],
    /// Unit direction of travel at `y`, in the static frame at `y`.
    pub end: [f64; 3],
    /// Unit world-coordinate tangent at `y` (what a world-coordinate surface is projected along).
    pub end_tangent: [f64; 3],
    /// `dΩ_x/dA⊥`: solid angle at `x` per world-coordinate area of the beam cross-section at `y`
    /// perpendicular to `end_tangent`, equation (3). A surface with world unit normal `n` has
    /// `dΩ_x/dA = |n · end_tangent| · solid_angle_per_area`.
    pub solid_angle_per_area: f64,
    /// Azimuth swept from `x` to `y`: `Δφ ∈ (0, π]` the short way, `2π − Δφ` the long way.
    pub swept: f64,
    /// Unit normal of the ray's plane, the axis it sweeps round.
    pub axis: [f64; 3],
}

/// Most points kept along a ray between its ends; a ray that needs more keeps none.
const MAX_WAYPOINTS: usize = 24;

/// Points along a connecting ray, in its plane (basis `x̂`, `e₂`), where the last shot's Taylor
/// steps ended, less than a radian of azimuth apart: the solver's scratch, kept by the caller
/// beside the [`Connection`] it last filled them for ([`Connector::connect_along`]), so that a connection
/// does not carry (and copy) them where its single triangle settles its visibility.
#[derive(Clone, Debug, PartialEq)]
pub struct Waypoints {
    xh: [f64; 3],
    e2: [f64; 3],
    /// Newton's last step in the start slope `s`, taken without shooting again: the kept points
    /// follow it to first order (`∂u/∂s = J`, `∂u'/∂s = J'`).
    step: f64,
    /// States kept, or `MAX_WAYPOINTS + 1` where there were too many to keep.
    count: usize,
    /// The shot's `(φ, u, u', J, J')` at the ends of its steps, before the last.
    states: [[f64; 5]; MAX_WAYPOINTS],
}

impl Default for Waypoints {
    fn default() -> Self {
        Self { xh: [0.0; 3], e2: [0.0; 3], step: 0.0, count: 0, states: [[0.0; 5]; MAX_WAYPOINTS] }
    }
}

impl Waypoints {
    fn push(&mut self, phi: f64, y: &[f64; 6]) {
        if let Some(state) = self.states.get_mut(self.count) {
            *state = [phi, y[0], y[1], y[2], y[3]];
        }
        self.count = (self.count + 1).min(MAX_WAYPOINTS + 1);
    }

    /// The kept points `(φ, u, u')` of the ray Newton's last step led to.
    fn points(&self) -> impl Iterator<Item = [f64; 3]> + '_ {
        let step = self.step;
        self.states[..self.count.min(MAX_WAYPOINTS)]
            .iter()
            .map(move |[phi, u, du, j, dj]| [*phi, u + j * step, du + dj * step])
    }
}

impl Connection {
    /// A triangle `[x, z, y]` that holds the whole ray from `x` to `y`, or `None` where the ray
    /// goes the long way round or turns by π or more (or too little to place `z`): the ray bends
    /// towards the centre all along, so the triangle of its chord and end tangents holds it
    /// ([`tangent_triangle`]), and nothing that stays clear of the triangle can block it.
    pub fn enclosing_triangle(&self, x: [f64; 3], y: [f64; 3]) -> Option<[[f64; 3]; 3]> {
        if self.swept > PI {
            return None;
        }
        tangent_triangle(self.axis, (x, self.start_tangent), (y, self.end_tangent))
    }

    /// Triangles that together hold the ray from `x` to `y`, each the tangent triangle of a piece
    /// between waypoints, as [`Connection::enclosing_triangle`] bounds the whole short way; `None`
    /// for a piece that turns too little or too much to bound, and a single `None` where the
    /// waypoints were not kept. This bounds the long way round too, whose consecutive pieces are
    /// merged while the merged piece sweeps at most 2 rad and turns at most 45° (`MERGED_SWEEP`,
    /// `MERGED_TURN_COS`): fewer, still small triangles (it has a dozen waypoints). The short way
    /// is asked for its pieces only where its one triangle came near something, and there
    /// merged triangles would mostly come near it again.
    pub fn enclosing_triangles<'a>(
        &'a self,
        waypoints: &'a Waypoints,
        x: [f64; 3],
        y: [f64; 3],
    ) -> impl Iterator<Item = Option<[[f64; 3]; 3]>> + 'a {
        let (w, axis) = (waypoints, self.axis);
        let kept = w.count <= MAX_WAYPOINTS;
        let inner = w.points().map(|p| (p[0], w.world(&p)));
        let mut knots = std::iter::once((0.0, (x, self.start_tangent)))
            .chain(inner)
            .chain(std::iter::once((self.swept, (y, self.end_tangent))))
            .peekable();
        let (mut start, merge) = (knots.next(), self.swept > PI);
        let pieces = std::iter::from_fn(move || {
            let (phi, knot) = start?;
            let mut end = knots.next()?;
            while let Some(&(next_phi, next)) = knots.peek() {
                if !merge || next_phi - phi > MERGED_SWEEP || dot3(&knot.1, &next.1) < MERGED_TURN_COS {
                    break;
                }
                end = (next_phi, next);
                knots.next();
            }
            start = Some(end);
            Some(tangent_triangle(axis, knot, end.1))
        });
        let none_kept = (!kept).then_some(None);
        none_kept.into_iter().chain(pieces.take_while(move |_| kept))
    }
}

/// Most azimuth a merged piece of [`Connection::enclosing_triangles`] sweeps: below π, which
/// tangent triangles need.
const MERGED_SWEEP: f64 = 2.0;
/// Cosine of the most a merged piece turns, 45°: its tangents then meet within `tan(45°/2)` (0.41)
/// of its chord's length, so the triangle stays near the ray. (At 60° as many room connections
/// were cleared without tracing, but more near a ball beside the hole were traced.)
const MERGED_TURN_COS: f64 = std::f64::consts::FRAC_1_SQRT_2;

impl Waypoints {
    /// World position and unit world tangent of the point `(φ, u, u')`: world coordinates see
    /// the ray's direction as `(−u', u)` in the radial and azimuthal directions.
    fn world(&self, &[phi, u, du]: &[f64; 3]) -> ([f64; 3], [f64; 3]) {
        let axes = PlaneAxes::at(&self.xh, &self.e2, phi);
        (axes.at_radius(1.0 / u), world_tangent(&axes, u, du))
    }
}

/// Unit world tangent of the ray at `(u, u')`, given the plane's directions there: world
/// coordinates see its direction of travel as `(−u', u)` in the radial and azimuthal directions.
fn world_tangent(axes: &PlaneAxes, u: f64, du: f64) -> [f64; 3] {
    axes.along(-du, u)
}

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

/// [`Connector::connect_along`], starting from the tabulated [`start_parameter`] where `tables`
/// are given and the way's table covers the ends, else from [`guessed_parameter`].
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

/// The direction a ray leaves `x` in: `sin ψ` and `cos ψ`, from the outward radial direction.
struct StartDirection {
    sin: f64,
    cos: f64,
}

impl StartDirection {
    /// The direction of start slope `s` of (1): `cot ψ = −s/(u_x/σ_x)`, `ψ ∈ (0, π)`.
    fn of_slope(s: f64, slope_scale: f64) -> Self {
        let norm = (slope_scale * slope_scale + s * s).sqrt();
        Self { sin: slope_scale / norm, cos: -s / norm }
    }
}

/// The converged ray's data at both ends.
struct Ends {
    xh: [f64; 3],
    e2: [f64; 3],
    /// The plane's directions at `y`, and the sine of the sweep.
    at_y: PlaneAxes,
    sin_sweep: f64,
    sweep: f64,
    start: StartDirection,
    ux: f64,
    uy: f64,
    du: f64,
    jacobi: f64,
}

impl Ends {
    fn connection(&self, metric: &Schwarzschild) -> Option<Connection> {
        if !(self.jacobi > 0.0) {
            return None;
        }
        // `1/σ = √(1 − 2Mu)`, the static frame's radial scale (the lapse); multiplied in, not
        // divided by, and where a direction is normalised anyway, onto the other component.
        let lapse_x = metric.lapse(self.ux);
        let StartDirection { sin: s_psi, cos: c_psi } = self.start;
        let start = std::array::from_fn(|i| c_psi * self.xh[i] + s_psi * self.e2[i]);
        let start_tangent = normalize3(&std::array::from_fn(|i| c_psi * lapse_x * self.xh[i] + s_psi * self.e2[i]));
        let at_y = &self.at_y;
        // Static frame: (n_r, n_φ) ∝ (−σ u', u).
        let end = at_y.along(-self.du, metric.lapse(self.uy) * self.uy);
        let end_tangent = world_tangent(at_y, self.uy, self.du);
        // Equation (3), with `1/t_φ = √(u'² + u²)/u` at `y`.
        let density = s_psi.powi(3) * self.uy * self.uy * (self.du * self.du + self.uy * self.uy).sqrt()
            / (lapse_x * self.ux * self.jacobi * self.sin_sweep.abs());
        let (solid_angle_per_area, swept, axis) = (density, self.sweep, cross3(&self.xh, &self.e2));
        Some(Connection { start, start_tangent, end, end_tangent, solid_angle_per_area, swept, axis })
    }
}

/// The start slope `s` of (1) to first order in `M`: with the flat solution
/// `u₀ = u_x cos φ + s sin φ`, the correction `w'' + w = 3Mu₀²`, `w(0) = w'(0) = 0`, is
/// `3M[(u_x² + s²)(1 − cos φ)/2 + (u_x² − s²)(cos φ − cos 2φ)/6 + u_x s (2 sin φ − sin 2φ)/3]`,
/// and `u₀ + w = u_y` at `φ = Δφ` is a quadratic in `s`; its root nearest the flat one. A good
/// guess saves Newton iterations, each a full integration.
fn first_guess(mass: f64, ux: f64, uy: f64, cos: f64, sin: f64) -> f64 {
    let (cos2, sin2) = (cos * cos - sin * sin, 2.0 * sin * cos);
    let (even, odd) = ((1.0 - cos) / 2.0, (cos - cos2) / 6.0);
    let a2 = 3.0 * mass * (even - odd);
    let a1 = sin + mass * ux * (2.0 * sin - sin2);
    let a0 = ux * cos - uy + 3.0 * mass * ux * ux * (even + odd);
    let discriminant = a1 * a1 - 4.0 * a2 * a0;
    if a1 > 0.0 && discriminant >= 0.0 {
        // The root that tends to the flat −a0/a1 as M → 0, in cancellation-free form.
        -2.0 * a0 / (a1 + discriminant.sqrt())
    } else {
        (uy - ux * cos) / sin
    }
}

/// `sin ψ_c`, the sine of the critical angle at `u_x` (outside the photon sphere): rays leaving
/// inward at more than `ψ_c` fall into the hole.
fn critical_sin(mass: f64, ux: f64) -> f64 {
    3.0 * 3f64.sqrt() * mass * slope_scale(mass, ux)
}

/// `u_x/σ_x = u_x √(1 − 2Mu_x)`: the start slope of (1) is `s = −(u_x/σ_x) cot ψ`.
fn slope_scale(mass: f64, ux: f64) -> f64 {
    ux * (1.0 - 2.0 * mass * ux).sqrt()
}

/// The parameter each way is shot, guessed and tabulated by, scale-free in `M`: the short way
/// by `Ms`, `M` times the start slope of (1); the long way by `ln ε`, where
/// `sin ψ = sin ψ_c (1 + ε)`, in which the sweep is nearly linear near the photon sphere.
fn start_parameter(way: Way, mass: f64, ux: f64, psi: f64) -> f64 {
    match way {
        Way::Short => -mass * slope_scale(mass, ux) / psi.tan(),
        Way::Long => (psi.sin() / critical_sin(mass, ux) - 1.0).ln(),
    }
}

/// The long way's start slope `s` at [`start_parameter`] `ln ε`: `sin ψ = sin ψ_c (1 + ε)` on the
/// inward side.
fn long_start_slope(mass: f64, ux: f64, ln_epsilon: f64) -> f64 {
    inward_slope(mass, ux, (critical_sin(mass, ux) * (1.0 + ln_epsilon.exp())).min(1.0))
}

/// The start slope `s = −(u_x/σ_x) cot ψ` of a ray leaving `u_x` inward (`ψ > π/2`) with
/// `sin ψ = sin`, where `−cot ψ = √(1 − sin²ψ)/sin ψ`.
fn inward_slope(mass: f64, ux: f64, sin: f64) -> f64 {
    slope_scale(mass, ux) * (1.0 - sin * sin).sqrt() / sin
}

/// First guess of [`start_parameter`] for the ray from `u_x` to `u_y` sweeping `sweep` (the short
/// way's `Δφ` has cosine `cos` and sine `sin`).
///
/// Short way: [`first_guess`]. Long way: in the strong-deflection limit a ray with
/// `b = b_c(1 + ε)` from infinity to infinity sweeps `−ln ε + ln(216(7 − 4√3))` (Bozza 2002,
/// eq. 36 with π added), less the azimuth the critical ray sweeps between each end and infinity,
/// `S(u) = 2[artanh √(2M(u + 1/6M)) − artanh √(1/3)]` (the critical orbit's integral, since
/// `1/b_c² − u² + 2Mu³ = 2M(u − 1/3M)²(u + 1/6M)`); an end inside the photon sphere has no such
/// limit, and the guess is a little off critical.
fn guessed_parameter(way: Way, mass: f64, ux: f64, uy: f64, cos: f64, sin: f64, sweep: f64) -> f64 {
    match way {
        Way::Short => mass * first_guess(mass, ux, uy, cos, sin),
        Way::Long => {
            let to_infinity =
                |u: f64| 2.0 * ((2.0 * mass * u + 1.0 / 3.0).sqrt().atanh() - (1.0f64 / 3.0).sqrt().atanh());
            let ln_epsilon = (216.0 * (7.0 - 4.0 * 3f64.sqrt())).ln() - sweep - to_infinity(ux) - to_infinity(uy);
            if ln_epsilon.is_finite() {
                ln_epsilon
            } else {
                0.05f64.ln()
            }
        }
    }
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

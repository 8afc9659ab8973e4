//! What a connection gives: the ray's directions and density at both ends ([`Connection`],
//! equation (3) of [`super`]), the points kept along it ([`Waypoints`]), and the triangles that
//! hold it, by which its visibility is tested without tracing it.

use crate::geodesic::plane::{PlaneAxes, PlaneMetric};
use crate::geodesic::tangent_triangle::tangent_triangle;
use crate::metric::Schwarzschild;
use crate::tensor::{cross3, dot3, normalize3};
use std::f64::consts::PI;

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
/// beside the [`Connection`] it last filled them for
/// ([`Connector::connect_along`](super::Connector::connect_along)), so that a connection does not
/// carry (and copy) them where its single triangle settles its visibility.
#[derive(Clone, Debug, PartialEq)]
pub struct Waypoints {
    pub(super) xh: [f64; 3],
    pub(super) e2: [f64; 3],
    /// Newton's last step in the start slope `s`, taken without shooting again: the kept points
    /// follow it to first order (`∂u/∂s = J`, `∂u'/∂s = J'`).
    pub(super) step: f64,
    /// States kept, or `MAX_WAYPOINTS + 1` where there were too many to keep.
    pub(super) count: usize,
    /// The shot's `(φ, u, u', J, J')` at the ends of its steps, before the last.
    states: [[f64; 5]; MAX_WAYPOINTS],
}

impl Default for Waypoints {
    fn default() -> Self {
        Self { xh: [0.0; 3], e2: [0.0; 3], step: 0.0, count: 0, states: [[0.0; 5]; MAX_WAYPOINTS] }
    }
}

impl Waypoints {
    pub(super) fn push(&mut self, phi: f64, y: &[f64; 6]) {
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
pub(super) fn world_tangent(axes: &PlaneAxes, u: f64, du: f64) -> [f64; 3] {
    axes.along(-du, u)
}

/// The direction a ray leaves `x` in: `sin ψ` and `cos ψ`, from the outward radial direction.
pub(super) struct StartDirection {
    sin: f64,
    cos: f64,
}

impl StartDirection {
    /// The direction of start slope `s` of (1): `cot ψ = −s/(u_x/σ_x)`, `ψ ∈ (0, π)`.
    pub(super) fn of_slope(s: f64, slope_scale: f64) -> Self {
        let norm = (slope_scale * slope_scale + s * s).sqrt();
        Self { sin: slope_scale / norm, cos: -s / norm }
    }
}

/// The converged ray's data at both ends.
pub(super) struct Ends {
    pub(super) xh: [f64; 3],
    pub(super) e2: [f64; 3],
    /// The plane's directions at `y`, and the sine of the sweep.
    pub(super) at_y: PlaneAxes,
    pub(super) sin_sweep: f64,
    pub(super) sweep: f64,
    pub(super) start: StartDirection,
    pub(super) ux: f64,
    pub(super) uy: f64,
    pub(super) du: f64,
    pub(super) jacobi: f64,
}

impl Ends {
    pub(super) fn connection(&self, metric: &Schwarzschild) -> Option<Connection> {
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

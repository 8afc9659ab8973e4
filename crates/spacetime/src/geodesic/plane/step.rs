//! The steps of an in-plane ray: the stretches between throat crossings ([`Segment`]), the
//! integrator's step with its dense output ([`PlaneAttempt`]), and the accepted step a caller
//! sees ([`PlaneStep`]), which places points anywhere inside it in world coordinates.

use super::axes::{sin_cos_small, PlaneAxes};
use super::time::{curved_fall, straight_fall, Clock};
use super::{region_sign, PlaneMetric};
use crate::geodesic::Interpolant;
use crate::metric::schwarzschild::binet_taylor::OrbitStep;
use crate::metric::Region;
use crate::tensor::{cross3, dot3, norm3, scale3};

/// One stretch of a ray between throat crossings: the flat solution's constants and the plane
/// (opaque: steps refer to it so points inside them can be placed).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Segment {
    pub(super) e1: [f64; 3],
    pub(super) e2: [f64; 3],
    pub(super) region: Region,
    pub(super) phi_start: f64,
    /// Whether the flat solution is split off (`a`, `b` are then its constants, else zero).
    pub(super) split: bool,
    pub(super) a: f64,
    pub(super) b: f64,
}

impl Segment {
    /// A segment starting at `phi` with `(u, u')`, and the deviation `w` it starts from.
    pub(super) fn starting(
        e1: [f64; 3],
        e2: [f64; 3],
        region: Region,
        phi: f64,
        u: f64,
        du: f64,
        split: bool,
    ) -> (Segment, [f64; 2]) {
        if split {
            (Segment { e1, e2, region, phi_start: phi, split, a: u, b: du }, [0.0, 0.0])
        } else {
            (Segment { e1, e2, region, phi_start: phi, split, a: 0.0, b: 0.0 }, [u, du])
        }
    }

    #[inline]
    pub(super) fn flat(&self, phi: f64) -> (f64, f64) {
        if !self.split {
            return (0.0, 0.0);
        }
        let (s, c) = (phi - self.phi_start).sin_cos();
        (self.a * c + self.b * s, -self.a * s + self.b * c)
    }

    pub(super) fn chart_direction(&self, phi: f64) -> ([f64; 3], [f64; 3]) {
        let (s, c) = phi.sin_cos();
        let n = std::array::from_fn(|i| c * self.e1[i] + s * self.e2[i]);
        let t = std::array::from_fn(|i| -s * self.e1[i] + c * self.e2[i]);
        (n, t)
    }
}

/// One step of the in-plane integration, with the state anywhere inside it.
#[derive(Clone, Copy, Debug)]
pub enum PlaneAttempt {
    /// A Runge–Kutta step with its dense output.
    Runge(Interpolant<2>),
    /// A step of the orbit's Taylor series (Schwarzschild), which is its own dense output.
    Taylor(OrbitStep),
}

impl PlaneAttempt {
    pub fn h(&self) -> f64 {
        match self {
            PlaneAttempt::Runge(step) => step.h(),
            PlaneAttempt::Taylor(series) => series.h(),
        }
    }

    pub(super) fn y0(&self) -> [f64; 2] {
        self.dense(0.0)
    }

    pub(super) fn y1(&self) -> [f64; 2] {
        match self {
            PlaneAttempt::Runge(step) => step.y1(),
            PlaneAttempt::Taylor(series) => series.at(1.0),
        }
    }

    /// `(w, w')` at fraction `θ ∈ [0, 1]` of the step.
    #[inline]
    pub(super) fn dense(&self, theta: f64) -> [f64; 2] {
        match self {
            PlaneAttempt::Runge(step) => step.dense(theta),
            PlaneAttempt::Taylor(series) => series.at(theta),
        }
    }

    /// `w` alone at fraction `θ` (placing a point needs no slope).
    #[inline]
    fn dense_u(&self, theta: f64) -> f64 {
        match self {
            PlaneAttempt::Runge(step) => step.dense_head::<1>(theta)[0],
            PlaneAttempt::Taylor(series) => series.u(theta),
        }
    }
}

/// One accepted step of an in-plane ray. A curved step borrows the tracer's segment and
/// integrator step rather than copying them: building a step for every visit by value moved a
/// few hundred bytes each time, a measurable share of a render.
#[derive(Clone, Copy, Debug)]
pub enum PlaneStep<'a> {
    /// `span ≤ 1` is the fraction of the integrator step that belongs to this step (a step is
    /// cut where it leaves the escape sphere).
    /// `frame` is the chart direction and its in-plane normal at `phi0`, so points inside the step
    /// need only a small rotation.
    Curved {
        segment: &'a Segment,
        phi0: f64,
        attempt: &'a PlaneAttempt,
        span: f64,
        frame: ([f64; 3], [f64; 3]),
        clock: Option<Clock>,
    },
    /// A straight piece: flat space, or a radial ray. `length` may be infinite.
    Straight { region: Region, from: [f64; 3], direction: [f64; 3], length: f64, clock: Option<Clock> },
}

/// A point along a step in world terms: where, which way (in the static observer's frame, axes
/// aligned with the world's), and the inverse chart radius there.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PlanePoint {
    pub region: Region,
    pub position: [f64; 3],
    pub direction: [f64; 3],
}

impl PlaneStep<'_> {
    pub fn region(&self) -> Region {
        match self {
            PlaneStep::Curved { segment, .. } => segment.region,
            PlaneStep::Straight { region, .. } => *region,
        }
    }

    /// Azimuth swept since the ray's start at fraction `θ ∈ [0, 1]` of a curved step; `None` on
    /// straight pieces, whose rays have no plane (radial) or need none (flat space).
    pub fn azimuth(&self, theta: f64) -> Option<f64> {
        match self {
            PlaneStep::Curved { phi0, attempt, span, .. } => Some(phi0 + theta * span * attempt.h()),
            PlaneStep::Straight { .. } => None,
        }
    }

    /// The chart's coordinate time at fraction `θ ∈ [0, 1]` of the step, where the trace carries
    /// it ([`trace_plane_in_time`](super::trace_plane_in_time)); `None` where it does not. It
    /// falls along the ray, which is traced backwards (see [`super::time`]). On an infinite
    /// straight piece (flat space) every `θ > 0` is at infinity: chord hits there are placed
    /// by distance, [`PlaneStep::time_at_distance`].
    pub fn time_at<M: PlaneMetric + ?Sized>(&self, metric: &M, theta: f64) -> Option<f64> {
        match self {
            PlaneStep::Curved { segment, phi0, attempt, span, clock, .. } => {
                clock.map(|c| c.start - curved_fall(metric, segment, *phi0, attempt, c.b, theta * span))
            }
            PlaneStep::Straight { length, .. } => {
                let distance = if theta == 0.0 { 0.0 } else { theta * length };
                self.time_at_distance(metric, distance)
            }
        }
    }

    /// The chart's coordinate time at world distance `s` along a straight piece, where the
    /// trace carries it; `None` on curved steps and where it does not.
    pub fn time_at_distance<M: PlaneMetric + ?Sized>(&self, metric: &M, s: f64) -> Option<f64> {
        match self {
            PlaneStep::Straight { from, direction, clock, .. } => {
                clock.map(|c| c.start - straight_fall(metric, norm3(from), dot3(from, direction) > 0.0, s))
            }
            PlaneStep::Curved { .. } => None,
        }
    }

    /// `(φ, u, u')` at fraction `θ` of a curved step.
    pub(super) fn curve(segment: &Segment, phi0: f64, attempt: &PlaneAttempt, theta: f64) -> (f64, f64, f64) {
        let phi = phi0 + theta * attempt.h();
        let w = attempt.dense(theta);
        let (u0, du0) = segment.flat(phi);
        (phi, u0 + w[0], du0 + w[1])
    }

    /// World position and direction at fraction `θ ∈ [0, 1]` of the step.
    pub fn point<M: PlaneMetric + ?Sized>(&self, metric: &M, theta: f64) -> PlanePoint {
        match self {
            PlaneStep::Curved { segment, phi0, attempt, span, frame, .. } => {
                let (u, du, axes) = Self::axes(segment, *phi0, attempt, frame, theta * span);
                let direction = axes.along(-metric.radial_stretch(u) * du, u);
                PlanePoint { region: segment.region, position: axes.at_radius(metric.world_radius(u)), direction }
            }
            PlaneStep::Straight { region, from, direction, length, .. } => PlanePoint {
                region: *region,
                position: Self::along(from, direction, *length, theta),
                direction: *direction,
            },
        }
    }

    /// `(u, u')` and the radial and azimuthal directions at fraction `θ` of a curved step whose
    /// start has the directions `(n0, t0)`.
    fn axes(
        segment: &Segment,
        phi0: f64,
        attempt: &PlaneAttempt,
        (n0, t0): &([f64; 3], [f64; 3]),
        theta: f64,
    ) -> (f64, f64, PlaneAxes) {
        let (phi, u, du) = Self::curve(segment, phi0, attempt, theta);
        let (s, c) = sin_cos_small(phi - phi0);
        let radial = std::array::from_fn(|i| c * n0[i] + s * t0[i]);
        let azimuthal = std::array::from_fn(|i| -s * n0[i] + c * t0[i]);
        (u, du, PlaneAxes { sign: region_sign(segment.region), radial, azimuthal })
    }

    /// World position at fraction `θ ∈ [0, 1]` of the step: [`PlaneStep::point`] without the
    /// direction, which chord tests never need (they place many points per step, the direction
    /// costs a square root, a normalisation and `u'`).
    pub fn position<M: PlaneMetric + ?Sized>(&self, metric: &M, theta: f64) -> [f64; 3] {
        match self {
            PlaneStep::Curved { segment, phi0, attempt, span, frame: (n0, t0), .. } => {
                let phi = phi0 + theta * span * attempt.h();
                let u = segment.flat(phi).0 + attempt.dense_u(theta * span);
                let (s, c) = sin_cos_small(phi - phi0);
                let rho = region_sign(segment.region) * metric.world_radius(u);
                std::array::from_fn(|i| rho * (c * n0[i] + s * t0[i]))
            }
            PlaneStep::Straight { from, direction, length, .. } => Self::along(from, direction, *length, theta),
        }
    }

    /// World position and unit world tangent (the direction of travel in world coordinates, not
    /// the static observer's) at fraction `θ ∈ [0, 1]` of the step: `d(ρ n)/dφ = ρ'(u) u' n + ρ t`.
    pub fn knot<M: PlaneMetric + ?Sized>(&self, metric: &M, theta: f64) -> ([f64; 3], [f64; 3]) {
        match self {
            PlaneStep::Curved { segment, phi0, attempt, span, frame, .. } => {
                let (u, du, axes) = Self::axes(segment, *phi0, attempt, frame, theta * span);
                let rho = metric.world_radius(u);
                (axes.at_radius(rho), axes.along(metric.world_radius_slope(u) * du, rho))
            }
            PlaneStep::Straight { from, direction, length, .. } => {
                (Self::along(from, direction, *length, theta), *direction)
            }
        }
    }

    /// World position and velocity `dx/dθ` at fraction `θ ∈ [0, 1]` of the step: [`PlaneStep::knot`]
    /// with the tangent's length, `span · h · |dx/dφ|`, for root finding along the step.
    pub fn motion<M: PlaneMetric + ?Sized>(&self, metric: &M, theta: f64) -> ([f64; 3], [f64; 3]) {
        match self {
            PlaneStep::Curved { segment, phi0, attempt, span, frame, .. } => {
                let (u, du, axes) = Self::axes(segment, *phi0, attempt, frame, theta * span);
                let rho = metric.world_radius(u);
                let sweep = span * attempt.h();
                (axes.at_radius(rho), axes.scaled(sweep * metric.world_radius_slope(u) * du, sweep * rho))
            }
            PlaneStep::Straight { from, direction, length, .. } => {
                (Self::along(from, direction, *length, theta), scale3(direction, *length))
            }
        }
    }

    /// The axis a curved step sweeps round (right-handed with its direction of travel); `None`
    /// for a straight piece.
    pub fn axis(&self) -> Option<[f64; 3]> {
        match self {
            PlaneStep::Curved { frame: (n0, t0), .. } => Some(cross3(n0, t0)),
            PlaneStep::Straight { .. } => None,
        }
    }

    /// The point at fraction `θ` of a straight piece (`θ > 0` of an infinite one is at infinity).
    fn along(from: &[f64; 3], direction: &[f64; 3], length: f64, theta: f64) -> [f64; 3] {
        let s = if length.is_finite() {
            theta * length
        } else if theta > 0.0 {
            f64::INFINITY
        } else {
            0.0
        };
        std::array::from_fn(|i| from[i] + s * direction[i])
    }
}

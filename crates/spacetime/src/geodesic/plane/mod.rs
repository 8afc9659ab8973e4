//! In-plane integration for static, spherically symmetric spacetimes.
//!
//! Every geodesic of such a spacetime stays in one plane through the centre (`docs/physics.md`,
//! "Charts of each metric"), so a ray is integrated in its own plane with the azimuth `φ` as
//! parameter and `u = 1/s` (s the chart radius) as unknown, in Binet form `u'' = −u + G(u)`. The
//! flat part is solved exactly, `u₀(φ) = A cos(φ − φₛ) + B sin(φ − φₛ)`, and only the deviation
//! `w = u − u₀` is integrated: weak-field bending keeps its full relative precision, straight
//! rays cost nothing, and there is no pole anywhere — the plane is chosen per ray. The split
//! costs a sine and cosine per stage, so it is used only for rays that pass far from the centre
//! (`b > 64` length scales), where the bending is small and its precision matters; closer rays
//! integrate `u` itself.
//!
//! Schwarzschild rays that integrate `u` itself step by the Taylor series of their orbit
//! (`u'' = −u + 3Mu²` has a polynomial right-hand side:
//! [`binet_taylor`](crate::metric::schwarzschild::binet_taylor)), whose polynomial is also the
//! dense output; other rays by Dormand–Prince 5(4).
//!
//! A wormhole's lower region uses `ũ = 1/(b₀² u)`, which obeys the same equation (the isometry
//! `s ↦ b₀²/s`); the tracer switches at the throat.
//!
//! [`plane_aim`] aims a ray at a point in the same plane, one unknown instead of the 4-D aim's
//! two. The tracer and the aim live here, among the generic machinery, rather than beside one
//! metric: they serve every metric that implements [`PlaneMetric`] (Minkowski, Schwarzschild,
//! Reissner–Nordström, Ellis and Morris–Thorne wormholes), as [`super::HamiltonianTracer`] serves
//! every [`Metric`]. What serves Schwarzschild alone (its orbit's Taylor series, its light
//! connector) lives in [`crate::metric::schwarzschild`].
//!
//! The chart's coordinate time along a ray is not integrated by the stepper: callers that need it
//! ask for it ([`trace_plane_in_time`]), and it is integrated over each step's dense output
//! (`time`).
//!
//! Files: the ray's metric and start here; its steps and the points inside them in `step`; the
//! chart's time along them in `time`; the plane's directions at a point in `axes`; the tracer in
//! `trace`; the aim in `aim` and the shots it takes in `shoot`.

use crate::metric::{Metric, Region};
use crate::tensor::{dot3, norm3, scale3};

mod aim;
#[cfg(test)]
mod aim_tests;
mod axes;
mod shoot;
mod step;
mod time;
mod trace;

pub use aim::{plane_aim, PlaneAim, PlaneAimSettings, Side, Way};
pub(crate) use axes::PlaneAxes;
pub use step::{PlaneAttempt, PlanePoint, PlaneStep, Segment};
pub use time::{ChartTime, Clock};
pub use trace::{trace_plane, trace_plane_in_time, PlaneTrace};

/// A static, spherically symmetric metric reduced to the plane of a ray. `u` is the inverse
/// chart radius, `'` is `d/dφ`, and the photon's energy is 1 so `b = L/E = L`.
pub trait PlaneMetric: Metric {
    /// `G(u)` in `u'' = −u + G(u)`, for impact parameter `b` (`inv_b2 = 1/b²`).
    fn binet_source(&self, u: f64, inv_b2: f64) -> f64;
    /// `(u')²` on a null ray (the first integral of the Binet equation).
    fn slope_squared(&self, u: f64, inv_b2: f64) -> f64;
    /// The 4-D Hamiltonian `½ g^{μν} p_μ p_ν` of the ray at `(u, u')`, with `E = 1`.
    fn plane_hamiltonian(&self, u: f64, du: f64, b: f64) -> f64;
    /// `σ(u)`: a static observer sees the ray's direction as `(n_r, n_φ) ∝ (−σ u', u)`.
    fn radial_stretch(&self, u: f64) -> f64;
    /// `b = impact_factor(u) · n_φ` for a ray leaving a static observer at `u`.
    fn impact_factor(&self, u: f64) -> f64;
    /// World (areal) radius at `u`.
    fn world_radius(&self, u: f64) -> f64;
    /// `dρ/du`, the slope of [`PlaneMetric::world_radius`].
    fn world_radius_slope(&self, u: f64) -> f64;
    /// Inverse of [`PlaneMetric::world_radius`]; `None` inside a throat.
    fn u_of_world_radius(&self, rho: f64) -> Option<f64>;
    /// Lapse `α = √(−g_tt)` of the static observer at `u`: the energy it measures for a photon of
    /// conserved energy `E` is `E/α`.
    fn lapse(&self, u: f64) -> f64;
    /// `κ = dρ/dl` at `u`: world (areal) radial length per proper radial length. World tangential
    /// lengths are proper, so the static frame differs from world axes by this radial factor.
    fn radial_scale(&self, u: f64) -> f64;
    /// The time coordinate of the metric's 4-D chart, which the tracer reports along a ray where
    /// asked ([`trace_plane_in_time`]): the static time unless the chart says otherwise.
    fn chart_time(&self) -> ChartTime {
        ChartTime::Static
    }
    /// `u` of the horizon: rays reaching it are captured.
    fn capture_u(&self) -> Option<f64> {
        None
    }
    /// `u` of a wormhole throat, where the tracer moves to the other region.
    fn throat_u(&self) -> Option<f64> {
        None
    }
    /// Whether every ray, drawn in world coordinates, bends towards the centre all along: then
    /// each piece of it that sweeps at most π lies in the triangle of its chord and end tangents
    /// ([`tangent_triangle`](crate::geodesic::tangent_triangle)).
    fn bends_towards_centre(&self) -> bool {
        false
    }
    /// `M` where the Binet source is exactly `3Mu²` (Schwarzschild): the orbit's Taylor series
    /// then follows from a recurrence ([`binet_taylor`](crate::metric::schwarzschild::binet_taylor)), and the tracer
    /// takes steps of its series instead of Runge–Kutta steps.
    fn schwarzschild_mass(&self) -> Option<f64> {
        None
    }
    /// Flat space: every ray is one straight step.
    fn is_flat(&self) -> bool {
        false
    }
}

/// A ray ready for in-plane integration.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PlaneRay {
    /// Chart direction of the start point (`φ = 0`).
    pub e1: [f64; 3],
    /// In-plane unit vector orthogonal to `e1`, towards increasing `φ` (the ray's sense).
    pub e2: [f64; 3],
    pub region: Region,
    pub u: f64,
    pub du: f64,
    /// Impact parameter `b = L/E`.
    pub b: f64,
}

/// Where a ray starts: in a plane, or along a radius (impact parameter zero, no plane).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum PlaneStart {
    Plane(PlaneRay),
    /// Straight along a radius from world point `from` in direction `direction`.
    Radial {
        region: Region,
        from: [f64; 3],
        direction: [f64; 3],
    },
}

fn region_sign(region: Region) -> f64 {
    match region {
        Region::Upper => 1.0,
        Region::Lower => -1.0,
    }
}

impl PlaneStart {
    /// The backward-traced ray that leaves a static observer at world `position` of `region`
    /// along the unit `direction` measured in that observer's frame (axes aligned with the
    /// world's). `None` where no static observer exists (inside a horizon or a throat).
    pub fn from_observer<M: PlaneMetric + ?Sized>(
        metric: &M,
        region: Region,
        position: [f64; 3],
        direction: [f64; 3],
    ) -> Option<PlaneStart> {
        let rho = norm3(&position);
        let u = metric.u_of_world_radius(rho)?;
        if metric.capture_u().is_some_and(|uc| u >= uc) {
            return None;
        }
        let radial = scale3(&position, 1.0 / rho);
        let d_r = dot3(&direction, &radial);
        let tangent = std::array::from_fn(|i| direction[i] - d_r * radial[i]);
        let d_phi = norm3(&tangent);
        if d_phi <= 1e-12 {
            return Some(PlaneStart::Radial { region, from: position, direction: scale3(&radial, d_r.signum()) });
        }
        let sign = region_sign(region);
        let e1 = scale3(&radial, sign);
        let e2 = scale3(&tangent, sign / d_phi);
        let du = -u * d_r / (metric.radial_stretch(u) * d_phi);
        Some(PlaneStart::Plane(PlaneRay { e1, e2, region, u, du, b: metric.impact_factor(u) * d_phi }))
    }
}

impl PlaneRay {
    /// A ray coming in from infinity in the upper region with impact parameter `b > 0`, starting
    /// (at infinity) in chart direction `e1` and sweeping towards `e2`.
    pub fn from_infinity<M: PlaneMetric + ?Sized>(metric: &M, b: f64, e1: [f64; 3], e2: [f64; 3]) -> PlaneRay {
        let du = metric.slope_squared(0.0, 1.0 / (b * b)).sqrt();
        PlaneRay { e1, e2, region: Region::Upper, u: 0.0, du, b }
    }
}

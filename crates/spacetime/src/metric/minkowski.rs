//! Flat spacetime in Cartesian coordinates: `g = η`. Rays are straight lines.

use super::capabilities::{Capabilities, Forwards, LocalFrame, NoRest, Tracers};
use super::descriptor::{exactly, MetricDescriptor};
use super::{Metric, Region, Spacetime};
use crate::disk::CircularOrbits;
use crate::geodesic::plane::PlaneMetric;
use crate::metric::schwarzschild::connect::Connector;
use crate::tensor::{Covector4, Matrix4, Vector4, ETA};

/// Minkowski spacetime.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Minkowski;

/// `type = "minkowski"`: flat space, no parameters.
pub static MINKOWSKI: MetricDescriptor = MetricDescriptor {
    name: "minkowski",
    description: "flat space",
    parameters: &[],
    constraint: None,
    oriented: false,
    build: |v| {
        let [] = exactly(v)?;
        Ok(Spacetime::Minkowski(Minkowski))
    },
    values: |s| matches!(s, Spacetime::Minkowski(_)).then(Vec::new),
};

impl Metric for Minkowski {
    fn metric(&self, _x: &Vector4) -> Matrix4 {
        ETA
    }

    fn inverse_metric(&self, _x: &Vector4) -> Matrix4 {
        ETA
    }

    fn inverse_metric_derivatives(&self, _x: &Vector4) -> (Matrix4, [Matrix4; 4]) {
        (ETA, [[[0.0; 4]; 4]; 4])
    }

    fn geodesic_rhs(&self, _x: &Vector4, p: &Covector4) -> (Vector4, Covector4) {
        ([-p[0], p[1], p[2], p[3]], [0.0; 4])
    }

    fn length_scale(&self) -> f64 {
        1.0
    }
}

/// Straight lines: `u'' = −u` exactly.
impl PlaneMetric for Minkowski {
    fn binet_source(&self, _u: f64, _inv_b2: f64) -> f64 {
        0.0
    }

    fn slope_squared(&self, u: f64, inv_b2: f64) -> f64 {
        inv_b2 - u * u
    }

    fn plane_hamiltonian(&self, u: f64, du: f64, b: f64) -> f64 {
        0.5 * b * b * (du * du - self.slope_squared(u, 1.0 / (b * b)))
    }

    fn radial_stretch(&self, _u: f64) -> f64 {
        1.0
    }

    fn impact_factor(&self, u: f64) -> f64 {
        1.0 / u
    }

    fn world_radius(&self, u: f64) -> f64 {
        1.0 / u
    }

    fn world_radius_slope(&self, u: f64) -> f64 {
        -1.0 / (u * u)
    }

    fn u_of_world_radius(&self, rho: f64) -> Option<f64> {
        (rho > 0.0).then(|| 1.0 / rho)
    }

    fn lapse(&self, _u: f64) -> f64 {
        1.0
    }

    fn radial_scale(&self, _u: f64) -> f64 {
        1.0
    }

    fn is_flat(&self) -> bool {
        true
    }
}

/// Flat space: one region, static, straight rays, every observer at rest anywhere.
impl Capabilities for Minkowski {
    fn is_flat(&self) -> bool {
        true
    }

    fn is_spherically_symmetric(&self) -> bool {
        true
    }

    fn throat(&self) -> Option<f64> {
        None
    }

    /// Static: reversed rays are rays.
    fn forwards(&self) -> Forwards {
        Forwards::Reversed
    }

    fn rest(&self, region: Region, _p: [f64; 3]) -> Result<(), NoRest> {
        match region {
            Region::Upper => Ok(()),
            Region::Lower => Err(NoRest::NoSuchRegion),
        }
    }

    fn local_frame(&self, _region: Region, _p: [f64; 3]) -> LocalFrame {
        LocalFrame::Radial { kappa: 1.0 }
    }

    fn observer_lapse(&self, _region: Region, _p: [f64; 3]) -> f64 {
        1.0
    }

    fn impact_bound(&self, radius: f64) -> Option<f64> {
        Some(radius)
    }

    fn no_turning_beyond(&self) -> Option<f64> {
        None
    }

    fn light_connector(&self) -> Option<Connector> {
        None
    }

    /// No hole, no orbits for a disk.
    fn circular_orbits(&self) -> Option<CircularOrbits> {
        None
    }

    fn choose_tracer<T: Tracers>(&self, tracers: T) -> T::Output {
        tracers.straight()
    }
}

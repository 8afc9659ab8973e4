//! Schwarzschild black hole of mass `M` in outgoing Cartesian Kerr–Schild coordinates:
//! `g = η + (2M/r) l ⊗ l`, `l_μ = (1, −x/r, −y/r, −z/r)`, `r = |x|` (the areal radius).
//!
//! No poles, and the horizon `r = 2M` is an ordinary place in this chart, so a backward-traced
//! ray that falls in crosses it and is stopped there.

use super::capabilities::{
    radial_frame, radial_lapse, rest_outside_horizon, Capabilities, Forwards, LocalFrame, NoRest, Tracers,
};
use super::descriptor::{exactly, non_negative, MetricDescriptor, ParameterError, MASS};
use super::kerr_schild::{KerrSchild, KerrSchildPoint};
use super::Region;
use super::Spacetime;
use crate::disk::CircularOrbits;
use crate::geodesic::plane::{ChartTime, PlaneMetric};
use crate::tensor::{norm3, spatial, Vector4};
use connect::Connector;

pub mod binet_taylor;
pub mod connect;

/// Schwarzschild spacetime.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Schwarzschild {
    pub mass: f64,
}

impl Schwarzschild {
    pub fn new(mass: f64) -> Self {
        Self { mass }
    }
}

/// `type = "schwarzschild"`: [`Spacetime::schwarzschild`].
pub static SCHWARZSCHILD: MetricDescriptor = MetricDescriptor {
    name: "schwarzschild",
    description: "a non-rotating black hole; horizon radius `2·mass`",
    parameters: &[MASS],
    constraint: None,
    oriented: false,
    build: |v| {
        let [mass] = exactly(v)?;
        Spacetime::schwarzschild(mass)
    },
    values: |s| if let Spacetime::Schwarzschild(h) = s { Some(vec![h.mass]) } else { None },
};

impl Spacetime {
    /// Schwarzschild with `mass ≥ 0`.
    pub fn schwarzschild(mass: f64) -> Result<Self, ParameterError> {
        Ok(Spacetime::Schwarzschild(Schwarzschild::new(non_negative("mass", mass)?)))
    }
}

impl KerrSchild for Schwarzschild {
    /// `f = 2M/r`, `k = x/r`, `∂_i f = −2M x_i/r³`, `∂_i k_j = (δ_ij − k_i k_j)/r`.
    #[inline]
    fn fields(&self, x: &Vector4) -> KerrSchildPoint {
        let r = norm3(&spatial(x));
        let inv_r = 1.0 / r;
        let k = [x[1] * inv_r, x[2] * inv_r, x[3] * inv_r];
        let f = 2.0 * self.mass * inv_r;
        let df = [-f * k[0] * inv_r, -f * k[1] * inv_r, -f * k[2] * inv_r];
        let dk =
            std::array::from_fn(|i| std::array::from_fn(|j| (if i == j { 1.0 } else { 0.0 } - k[i] * k[j]) * inv_r));
        KerrSchildPoint { f, k, df, dk }
    }

    fn mass(&self) -> f64 {
        self.mass
    }

    fn radial_coordinate(&self, x: &Vector4) -> f64 {
        norm3(&spatial(x))
    }

    fn horizon_radius(&self) -> f64 {
        2.0 * self.mass
    }
}

/// In the ray's plane with `u = 1/r`: `(u')² = 1/b² − u² + 2Mu³`, so `u'' = −u + 3Mu²`
/// (the relativistic Binet equation). A static observer's frame stretches the radial direction
/// by `1/√(1 − 2M/r)`.
impl PlaneMetric for Schwarzschild {
    #[inline]
    fn binet_source(&self, u: f64, _inv_b2: f64) -> f64 {
        3.0 * self.mass * u * u
    }

    fn slope_squared(&self, u: f64, inv_b2: f64) -> f64 {
        inv_b2 - u * u + 2.0 * self.mass * u * u * u
    }

    fn plane_hamiltonian(&self, u: f64, du: f64, b: f64) -> f64 {
        let lapse2 = 1.0 - 2.0 * self.mass * u;
        b * b / (2.0 * lapse2) * (du * du - self.slope_squared(u, 1.0 / (b * b)))
    }

    fn radial_stretch(&self, u: f64) -> f64 {
        1.0 / (1.0 - 2.0 * self.mass * u).sqrt()
    }

    fn impact_factor(&self, u: f64) -> f64 {
        1.0 / (u * (1.0 - 2.0 * self.mass * u).sqrt())
    }

    fn world_radius(&self, u: f64) -> f64 {
        1.0 / u
    }

    fn world_radius_slope(&self, u: f64) -> f64 {
        -1.0 / (u * u)
    }

    /// The curvature of a ray in world coordinates is `3Mu⁵/(u² + u'²)^{3/2} ≥ 0`
    /// ([`connect`] equation (1)).
    fn bends_towards_centre(&self) -> bool {
        true
    }

    fn schwarzschild_mass(&self) -> Option<f64> {
        Some(self.mass)
    }

    fn u_of_world_radius(&self, rho: f64) -> Option<f64> {
        (rho > 0.0).then(|| 1.0 / rho)
    }

    fn lapse(&self, u: f64) -> f64 {
        (1.0 - 2.0 * self.mass * u).max(0.0).sqrt()
    }

    /// `dr/dl = √(1 − 2M/r)`.
    fn radial_scale(&self, u: f64) -> f64 {
        self.lapse(u)
    }

    fn capture_u(&self) -> Option<f64> {
        (self.mass > 0.0).then(|| 1.0 / self.horizon_radius())
    }

    /// The 4-D chart is outgoing Kerr–Schild.
    fn chart_time(&self) -> ChartTime {
        ChartTime::OutgoingKerrSchild
    }
}

/// A static hole: one region, observers at rest outside the horizon, the in-plane tracer with
/// its Taylor stepper, and the connector.
impl Capabilities for Schwarzschild {
    fn is_flat(&self) -> bool {
        self.mass == 0.0
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

    fn rest(&self, region: Region, p: [f64; 3]) -> Result<(), NoRest> {
        rest_outside_horizon(region, p, (self.mass > 0.0).then(|| self.horizon_radius()))
    }

    fn local_frame(&self, _region: Region, p: [f64; 3]) -> LocalFrame {
        radial_frame(self, p)
    }

    fn observer_lapse(&self, _region: Region, p: [f64; 3]) -> f64 {
        radial_lapse(self, p)
    }

    /// A ray of impact parameter `b = L/E` turns where `E²/A = L²/r²`, i.e. at `b = r/lapse(r)`,
    /// which grows with `r` outside the photon sphere `r = 3M` (below it, rays of `b < 3√3 M`
    /// are captured, so the bound at 3M covers them).
    fn impact_bound(&self, radius: f64) -> Option<f64> {
        if self.mass == 0.0 {
            return Some(radius);
        }
        let r = radius.max(3.0 * self.mass);
        Some(r / (1.0 - 2.0 * self.mass / r).sqrt())
    }

    /// Outside the photon sphere `u'' = −u + 3Mu² < 0`, so `u = 1/r` has no minimum.
    fn no_turning_beyond(&self) -> Option<f64> {
        Some(3.0 * self.mass)
    }

    fn light_connector(&self) -> Option<Connector> {
        (self.mass > 0.0).then(|| Connector::new(*self))
    }

    fn circular_orbits(&self) -> Option<CircularOrbits> {
        (self.mass > 0.0).then(|| CircularOrbits::new(self.mass, 0.0, 0.0))
    }

    fn choose_tracer<T: Tracers>(&self, tracers: T) -> T::Output {
        if self.mass == 0.0 {
            tracers.straight()
        } else {
            tracers.in_plane(self)
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::metric::Metric;

    #[test]
    fn static_observer_norm_matches_schwarzschild_lapse() {
        // g_tt = −(1 − 2M/r) in Kerr–Schild as in Schwarzschild coordinates.
        let m = Schwarzschild::new(1.5);
        let g = m.metric(&[0.0, 3.0, 4.0, 0.0]);
        assert!((g[0][0] + (1.0 - 3.0 / 5.0)).abs() < 1e-15);
    }
}

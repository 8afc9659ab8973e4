//! Reissner–Nordström black hole of mass `M` and charge `Q` (`|Q| ≤ M`, Gaussian units with
//! G = c = 1) in outgoing Cartesian Kerr–Schild coordinates:
//! `g = η + f l ⊗ l`, `f = (2Mr − Q²)/r²`, `l_μ = (1, −x/r, −y/r, −z/r)`, `r = |x|` the areal
//! radius. In Schwarzschild-like coordinates this is `A(r) = 1 − 2M/r + Q²/r²`, the outer
//! horizon `r₊ = M + √(M² − Q²)`, the photon sphere `r_ph = (3M + √(9M² − 8Q²))/2`
//! (Chandrasekhar 1983, "The Mathematical Theory of Black Holes", §40).
//!
//! As for [`Schwarzschild`](super::Schwarzschild) the horizon is an ordinary place in the chart;
//! rays reaching the outer horizon are captured. Without charge it is Schwarzschild exactly
//! (and takes Schwarzschild's Taylor stepper); with charge the in-plane tracer integrates
//! `u'' = −u + 3Mu² − 2Q²u³` by Runge–Kutta.

use super::capabilities::{
    radial_frame, radial_lapse, rest_outside_horizon, Capabilities, Forwards, LocalFrame, NoRest, Tracers,
};
use super::descriptor::{at_most_mass, exactly, non_negative, MetricDescriptor, ParameterError, CHARGE, MASS};
use super::kerr_schild::{KerrSchild, KerrSchildPoint};
use super::Region;
use super::Spacetime;
use crate::disk::CircularOrbits;
use crate::geodesic::plane::{ChartTime, PlaneMetric};
use crate::metric::schwarzschild::connect::Connector;
use crate::tensor::{norm3, spatial, Vector4};

/// Reissner–Nordström spacetime.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ReissnerNordstrom {
    pub mass: f64,
    pub charge: f64,
}

/// `type = "reissner-nordstrom"`: [`Spacetime::reissner_nordstrom`].
pub static REISSNER_NORDSTROM: MetricDescriptor = MetricDescriptor {
    name: "reissner-nordstrom",
    description: "a charged, non-rotating black hole; horizon radius `mass + √(mass² − charge²)`",
    parameters: &[MASS, CHARGE],
    constraint: Some("|charge| ≤ mass"),
    oriented: false,
    build: |v| {
        let [mass, charge] = exactly(v)?;
        Spacetime::reissner_nordstrom(mass, charge)
    },
    values: |s| if let Spacetime::ReissnerNordstrom(h) = s { Some(vec![h.mass, h.charge]) } else { None },
};

impl Spacetime {
    /// Reissner–Nordström with `|charge| ≤ mass`.
    pub fn reissner_nordstrom(mass: f64, charge: f64) -> Result<Self, ParameterError> {
        let mass = non_negative("mass", mass)?;
        Ok(Spacetime::ReissnerNordstrom(ReissnerNordstrom::new(mass, at_most_mass("charge", charge, mass)?)))
    }
}

impl ReissnerNordstrom {
    pub fn new(mass: f64, charge: f64) -> Self {
        Self { mass, charge }
    }

    /// `A = 1 − 2Mu + Q²u²` at `u = 1/r`.
    #[inline]
    fn a_of_u(&self, u: f64) -> f64 {
        1.0 - 2.0 * self.mass * u + self.charge * self.charge * u * u
    }

    /// The photon sphere's radius `(3M + √(9M² − 8Q²))/2`, where `A/r²` has its maximum.
    pub fn photon_sphere(&self) -> f64 {
        let (m, q2) = (self.mass, self.charge * self.charge);
        0.5 * (3.0 * m + (9.0 * m * m - 8.0 * q2).max(0.0).sqrt())
    }
}

impl KerrSchild for ReissnerNordstrom {
    /// `f = 2M/r − Q²/r²`, `k = x/r`, `∂_i f = (−2M/r² + 2Q²/r³) k_i`,
    /// `∂_i k_j = (δ_ij − k_i k_j)/r`.
    #[inline]
    fn fields(&self, x: &Vector4) -> KerrSchildPoint {
        let r = norm3(&spatial(x));
        let inv_r = 1.0 / r;
        let k = [x[1] * inv_r, x[2] * inv_r, x[3] * inv_r];
        let q2 = self.charge * self.charge * inv_r * inv_r;
        let f = 2.0 * self.mass * inv_r - q2;
        let dfdr = (-2.0 * self.mass * inv_r + 2.0 * q2) * inv_r;
        let df = [dfdr * k[0], dfdr * k[1], dfdr * k[2]];
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

    /// The outer horizon `r₊ = M + √(M² − Q²)`.
    fn horizon_radius(&self) -> f64 {
        self.mass + (self.mass * self.mass - self.charge * self.charge).max(0.0).sqrt()
    }
}

/// In the ray's plane with `u = 1/r`: `(u')² = 1/b² − u² A(u) = 1/b² − u² + 2Mu³ − Q²u⁴`, so
/// `u'' = −u + 3Mu² − 2Q²u³`. A static observer's frame stretches the radial direction by
/// `1/√A`.
impl PlaneMetric for ReissnerNordstrom {
    #[inline]
    fn binet_source(&self, u: f64, _inv_b2: f64) -> f64 {
        u * u * (3.0 * self.mass - 2.0 * self.charge * self.charge * u)
    }

    fn slope_squared(&self, u: f64, inv_b2: f64) -> f64 {
        inv_b2 - u * u * self.a_of_u(u)
    }

    fn plane_hamiltonian(&self, u: f64, du: f64, b: f64) -> f64 {
        b * b / (2.0 * self.a_of_u(u)) * (du * du - self.slope_squared(u, 1.0 / (b * b)))
    }

    fn radial_stretch(&self, u: f64) -> f64 {
        1.0 / self.a_of_u(u).sqrt()
    }

    fn impact_factor(&self, u: f64) -> f64 {
        1.0 / (u * self.a_of_u(u).sqrt())
    }

    fn world_radius(&self, u: f64) -> f64 {
        1.0 / u
    }

    fn world_radius_slope(&self, u: f64) -> f64 {
        -1.0 / (u * u)
    }

    /// A ray's curvature in world coordinates has the sign of `u'' + u = u²(3M − 2Q²u)`,
    /// positive outside `r = 2Q²/(3M) < M ≤ r₊`: everywhere a ray is traced.
    fn bends_towards_centre(&self) -> bool {
        true
    }

    fn schwarzschild_mass(&self) -> Option<f64> {
        (self.charge == 0.0).then_some(self.mass)
    }

    fn u_of_world_radius(&self, rho: f64) -> Option<f64> {
        (rho > 0.0).then(|| 1.0 / rho)
    }

    fn lapse(&self, u: f64) -> f64 {
        self.a_of_u(u).max(0.0).sqrt()
    }

    /// `dr/dl = √A`.
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

/// A static charged hole: as Schwarzschild, with its own horizon and photon sphere, and no
/// connector.
impl Capabilities for ReissnerNordstrom {
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

    /// A ray turns at `r` where `b = r/√A(r)`, which grows with `r` outside the photon sphere;
    /// rays from below it with `b` under the critical value are captured.
    fn impact_bound(&self, radius: f64) -> Option<f64> {
        if self.mass == 0.0 {
            return Some(radius);
        }
        let r = radius.max(self.photon_sphere());
        Some(r / self.a_of_u(1.0 / r).sqrt())
    }

    /// Outside the photon sphere `u'' = −u(1 − 3Mu + 2Q²u²) < 0`.
    fn no_turning_beyond(&self) -> Option<f64> {
        Some(self.photon_sphere())
    }

    /// [`Connector`] solves Schwarzschild's Binet equation only.
    fn light_connector(&self) -> Option<Connector> {
        None
    }

    fn circular_orbits(&self) -> Option<CircularOrbits> {
        (self.mass > 0.0).then(|| CircularOrbits::new(self.mass, 0.0, self.charge))
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
    use crate::metric::{Metric, Schwarzschild};

    /// `g_tt = −A(r)` and the horizons are where `A` vanishes.
    #[test]
    fn lapse_and_horizon_are_those_of_a() {
        let m = ReissnerNordstrom::new(1.0, 0.8);
        let g = m.metric(&[0.0, 3.0, 4.0, 0.0]);
        assert!((g[0][0] + (1.0 - 2.0 / 5.0 + 0.64 / 25.0)).abs() < 1e-15);
        assert!((m.horizon_radius() - 1.6).abs() < 1e-15);
        assert!(m.a_of_u(1.0 / 1.6).abs() < 1e-15 && m.a_of_u(1.0 / 0.4).abs() < 1e-15);
    }

    /// At the photon sphere the Binet equation has its circular orbit: `u'' = 0`, and `u' = 0`
    /// at the critical impact parameter `b_c` (the impact bound of the photon sphere); an extremal hole's photon sphere is at `2M`, `b_c = 4M`.
    #[test]
    fn the_photon_sphere_is_the_circular_orbit() {
        for q in [0.0, 0.3, 0.8, 1.0] {
            let m = ReissnerNordstrom::new(1.0, q);
            let u = 1.0 / m.photon_sphere();
            assert!((-u + m.binet_source(u, 0.0)).abs() < 1e-15, "q = {q}");
            let b = m.impact_bound(0.0).unwrap();
            assert!(m.slope_squared(u, 1.0 / (b * b)).abs() < 1e-15, "q = {q}");
        }
        let extremal = ReissnerNordstrom::new(1.0, 1.0);
        assert!((extremal.photon_sphere() - 2.0).abs() < 1e-15);
        assert!((extremal.impact_bound(0.0).unwrap() - 4.0).abs() < 1e-14);
    }

    /// Without charge it is Schwarzschild.
    #[test]
    fn without_charge_it_is_schwarzschild() {
        let (rn, s) = (ReissnerNordstrom::new(1.3, 0.0), Schwarzschild::new(1.3));
        let x = [0.0, 2.0, -3.0, 1.0];
        let ((a, da), (b, db)) = (rn.inverse_metric_derivatives(&x), s.inverse_metric_derivatives(&x));
        for i in 0..4 {
            for j in 0..4 {
                assert!((a[i][j] - b[i][j]).abs() < 1e-15);
                assert!((0..4).all(|d| (da[d][i][j] - db[d][i][j]).abs() < 1e-15));
            }
        }
        assert_eq!(rn.schwarzschild_mass(), Some(1.3));
        assert!((rn.impact_bound(0.0).unwrap() - 3.0 * 3f64.sqrt() * 1.3).abs() < 1e-14);
    }
}

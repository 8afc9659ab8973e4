//! Kerr–Newman black hole (mass `M`, spin `a` about +z, charge `Q`, `a² + Q² ≤ M²`, Gaussian
//! units with G = c = 1) in outgoing Cartesian Kerr–Schild coordinates, as
//! [`Kerr`](super::Kerr) with the charge in `f` alone (Debever, Kamran & McLenaghan 1984;
//! Visser 2007, §3):
//!
//! `g = η + f l ⊗ l`, `f = r² (2Mr − Q²) / (r⁴ + a² z²)`, `l` and the spheroidal radius `r`
//! those of Kerr. In Boyer–Lindquist form `Δ = r² − 2Mr + a² + Q²`: the outer horizon is at
//! `r₊ = M + √(M² − a² − Q²)`, and the circular equatorial photon orbits at the roots of
//! `r² − 3Mr + 2Q² ± 2a√(Mr − Q²) = 0` (+ prograde).

use super::capabilities::{tetrad_frame, tetrad_lapse};
use super::capabilities::{Capabilities, Forwards, LocalFrame, NoRest, OwnStepper, Tracers};
use super::descriptor::{at_most_mass, exactly, non_negative, MetricDescriptor, ParameterError, CHARGE, MASS, SPIN};
use super::kerr::{spheroidal, spheroidal_fields, spheroidal_rhs, spinning_rest};
use super::kerr_schild::{KerrSchild, KerrSchildPoint};
use super::schwarzschild::connect::Connector;
use super::spin_twin::SpinTwin;
use super::Region;
use super::Spacetime;
use crate::disk::CircularOrbits;
use crate::geodesic::{State, TraceSettings};
use crate::tensor::{Covector4, Vector4};
use mino::MinoTracer;

pub mod mino;

/// Kerr–Newman spacetime.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct KerrNewman {
    pub mass: f64,
    pub spin: f64,
    pub charge: f64,
}

/// `type = "kerr-newman"`: [`Spacetime::kerr_newman`].
pub static KERR_NEWMAN: MetricDescriptor = MetricDescriptor {
    name: "kerr-newman",
    description: "a charged, rotating black hole; horizon radius `mass + √(mass² − spin² − charge²)`",
    parameters: &[MASS, SPIN, CHARGE],
    constraint: Some("spin² + charge² ≤ mass²"),
    oriented: true,
    build: |v| {
        let [mass, spin, charge] = exactly(v)?;
        Spacetime::kerr_newman(mass, spin, charge)
    },
    values: |s| if let Spacetime::KerrNewman(h) = s { Some(vec![h.mass, h.spin, h.charge]) } else { None },
};

impl Spacetime {
    /// Kerr–Newman with `spin² + charge² ≤ mass²` (each of `|spin|` and `|charge|` at most the
    /// mass, checked first so that the error names the one at fault); spin along +z as
    /// [`Spacetime::kerr`]'s.
    pub fn kerr_newman(mass: f64, spin: f64, charge: f64) -> Result<Self, ParameterError> {
        let mass = non_negative("mass", mass)?;
        let spin = at_most_mass("spin", spin, mass)?;
        let charge = at_most_mass("charge", charge, mass)?;
        if !(spin * spin + charge * charge <= mass * mass) {
            return Err(ParameterError::new(
                "charge",
                format!(
                    "spin and charge must satisfy spin² + charge² ≤ mass² = {}, got {spin}² + {charge}²",
                    mass * mass
                ),
            ));
        }
        Ok(Spacetime::KerrNewman(KerrNewman::new(mass, spin, charge)))
    }
}

impl KerrNewman {
    pub fn new(mass: f64, spin: f64, charge: f64) -> Self {
        Self { mass, spin, charge }
    }
}

impl KerrSchild for KerrNewman {
    fn fields(&self, x: &Vector4) -> KerrSchildPoint {
        spheroidal_fields(self.mass, self.spin, self.charge, x)
    }

    #[inline]
    fn hamilton(&self, x: &Vector4, p: &Covector4) -> (Vector4, Covector4) {
        spheroidal_rhs(self.mass, self.spin, self.charge, x, p)
    }

    fn mass(&self) -> f64 {
        self.mass
    }

    fn radial_coordinate(&self, x: &Vector4) -> f64 {
        spheroidal::<f64>(self.spin, x[1], x[2], x[3]).0
    }

    /// Outer horizon `r₊ = M + √(M² − a² − Q²)`, the larger root of `Δ`.
    fn horizon_radius(&self) -> f64 {
        let (m, a, q) = (self.mass, self.spin, self.charge);
        m + (m * m - a * a - q * q).max(0.0).sqrt()
    }
}

/// A stationary, not static, hole, answering as [`Kerr`](super::Kerr) does: observers at rest
/// outside the ergoregion, the normal observer's frame inside it, the 4-D tracer, no connector.
impl Capabilities for KerrNewman {
    fn is_flat(&self) -> bool {
        self.mass == 0.0
    }

    /// Its chart has the spin axis, even where the spin is zero.
    fn is_spherically_symmetric(&self) -> bool {
        false
    }

    fn throat(&self) -> Option<f64> {
        None
    }

    /// Reversing time reverses the spin (treated as stationary whatever the spin).
    fn forwards(&self) -> Forwards {
        Forwards::SpinTwin(SpinTwin::new(self.mass, self.spin, self.charge))
    }

    fn rest(&self, region: Region, p: [f64; 3]) -> Result<(), NoRest> {
        spinning_rest(self, region, p)
    }

    fn local_frame(&self, region: Region, p: [f64; 3]) -> LocalFrame {
        tetrad_frame(self, region, p)
    }

    fn observer_lapse(&self, region: Region, p: [f64; 3]) -> f64 {
        tetrad_lapse(self, region, p)
    }

    fn impact_bound(&self, _radius: f64) -> Option<f64> {
        None
    }

    fn no_turning_beyond(&self) -> Option<f64> {
        None
    }

    fn light_connector(&self) -> Option<Connector> {
        None
    }

    fn circular_orbits(&self) -> Option<CircularOrbits> {
        (self.mass > 0.0).then(|| CircularOrbits::new(self.mass, self.spin, self.charge))
    }

    fn choose_tracer<T: Tracers>(&self, tracers: T) -> T::Output {
        if self.mass == 0.0 {
            tracers.straight()
        } else {
            tracers.own_stepper(self)
        }
    }
}

/// Rays in Mino time with their constants of motion ([`MinoTracer`]).
impl OwnStepper for KerrNewman {
    type Tracer = MinoTracer;

    fn ray_tracer(&self, start: State, settings: TraceSettings) -> MinoTracer {
        MinoTracer::new(self, start, settings)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::metric::{Kerr, Metric, ReissnerNordstrom};
    use crate::tensor::Matrix4;

    fn close(a: (Matrix4, [Matrix4; 4]), b: (Matrix4, [Matrix4; 4])) -> bool {
        (0..4).all(|i| {
            (0..4).all(|j| {
                (a.0[i][j] - b.0[i][j]).abs() < 1e-14 && (0..4).all(|d| (a.1[d][i][j] - b.1[d][i][j]).abs() < 1e-14)
            })
        })
    }

    /// Without charge it is Kerr; without spin, Reissner–Nordström.
    #[test]
    fn it_contains_kerr_and_reissner_nordstrom() {
        let x = [0.0, 2.0, -3.0, 1.0];
        let kn = KerrNewman::new(1.3, 0.7, 0.0);
        assert!(close(kn.inverse_metric_derivatives(&x), Kerr::new(1.3, 0.7).inverse_metric_derivatives(&x)));
        let kn = KerrNewman::new(1.3, 0.0, 0.9);
        let rn = ReissnerNordstrom::new(1.3, 0.9);
        assert!(close(kn.inverse_metric_derivatives(&x), rn.inverse_metric_derivatives(&x)));
        assert_eq!(kn.horizon_radius(), rn.horizon_radius());
    }

    /// The horizon is the null surface `Δ(r) = 0`: on it the gradient of the spheroidal radius is
    /// null, `g^{ij} ∂_i r ∂_j r = Δ/Σ` (`Σ = r² + a² cos²θ`), which vanishes at `r₊` and is
    /// positive outside (central differences for `∂_i r`).
    #[test]
    fn the_horizon_is_where_the_radius_turns_null() {
        let (m, a, q) = (1.0, 0.6, 0.5);
        let kn = KerrNewman::new(m, a, q);
        assert!((kn.horizon_radius() - (1.0 + 0.39f64.sqrt())).abs() < 1e-15);
        let theta = 0.8f64;
        for r in [kn.horizon_radius(), 2.0, 5.0] {
            let rho = (r * r + a * a).sqrt();
            let x = [0.0, rho * theta.sin() * 0.6, rho * theta.sin() * 0.8, r * theta.cos()];
            let h = 1e-6;
            let grad: [f64; 3] = std::array::from_fn(|i| {
                let (mut p, mut n) = (x, x);
                p[i + 1] += h;
                n[i + 1] -= h;
                (kn.radial_coordinate(&p) - kn.radial_coordinate(&n)) / (2.0 * h)
            });
            let ginv = kn.inverse_metric(&x);
            let norm: f64 = (0..3)
                .flat_map(|i| (0..3).map(move |j| (i, j)))
                .map(|(i, j)| ginv[i + 1][j + 1] * grad[i] * grad[j])
                .sum();
            let delta = r * r - 2.0 * m * r + a * a + q * q;
            let sigma = r * r + a * a * theta.cos().powi(2);
            assert!((norm - delta / sigma).abs() < 1e-8, "r = {r}: {norm} vs Δ/Σ = {}", delta / sigma);
        }
    }
}

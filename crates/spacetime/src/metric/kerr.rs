//! Kerr black hole (mass `M`, spin `a` about +z, `|a| ≤ M`) in outgoing Cartesian Kerr–Schild
//! coordinates (Kerr & Schild 1965; Visser 2007, "The Kerr spacetime: a brief introduction", §3):
//!
//! `g = η + f l ⊗ l`, `f = 2 M r³ / (r⁴ + a² z²)`,
//! `l_μ = (1, −(r x − a y)/(r² + a²), −(r y + a x)/(r² + a²), −z/r)`,
//! with `r` the spheroidal radius: `x² + y²)/(r² + a²) + z²/r² = 1`.
//!
//! The outgoing form is the time reverse of the usual ingoing one with `a → −a`; it is regular on
//! the past horizon, which backward-traced rays cross. The ring singularity (r = 0, z = 0) lies
//! inside the horizon, where rays are stopped.

use super::capabilities::{
    tetrad_frame, tetrad_lapse, Capabilities, Forwards, LocalFrame, NoRest, OwnStepper, Tracers,
};
use super::descriptor::{at_most_mass, exactly, non_negative, MetricDescriptor, ParameterError, MASS, SPIN};
use super::kerr_newman::mino::MinoTracer;
use super::kerr_schild::{hamilton_rhs, KerrSchild, KerrSchildPoint};
use super::schwarzschild::connect::Connector;
use super::spin_twin::SpinTwin;
use super::user::Scalar;
use super::{KerrNewman, Metric, Region, Spacetime};
use crate::disk::CircularOrbits;
use crate::geodesic::{State, TraceSettings};
use crate::observer::Tetrad;
use crate::tensor::{Covector4, Vector4};

/// Kerr spacetime.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Kerr {
    pub mass: f64,
    pub spin: f64,
}

/// Spheroidal radius `r`, `r²` and `k` (with `l_μ = (1, −k)`) of a hole of spin `a`, shared by
/// every metric of Kerr's family; generic so that the tests check [`spheroidal_fields`]'s
/// derivatives against dual numbers.
pub(super) fn spheroidal<D: Scalar>(a: f64, x: D, y: D, z: D) -> (D, D, [D; 3]) {
    let a2 = a * a;
    let rho2 = x * x + y * y + z * z;
    let half = (rho2 - a2) * 0.5;
    let r2 = half + (half * half + z * z * a2).sqrt();
    let r = r2.sqrt();
    let inv = (r2 + a2).recip();
    let k = [(r * x - y * a) * inv, (r * y + x * a) * inv, z / r];
    (r, r2, k)
}

/// What the Kerr–Schild fields of a hole of Kerr's family (mass `m`, spin `a`, charge `q`:
/// `f = r²(2Mr − Q²)/(r⁴ + a²z²)`) and Hamilton's equations there share, in closed form: this
/// runs at every step of every ray, and dual numbers cost about twice as much. The spheroidal
/// radius solves `r⁴ − (ρ² − a²) r² − a²z² = 0`, so `∂r/∂xⁱ = (xⁱ r² + a² z δⁱ_z) / (2 r s)` with
/// `2s = 2r² − ρ² + a²`; `k` and `f` follow by the chain rule, `∂_i f = g ∂_i r − h δ_iz`.
struct Spheroid {
    a: f64,
    /// The spatial point `(x, y, z)`.
    x: [f64; 3],
    r: f64,
    inv_r: f64,
    /// `1/(r² + a²)`.
    inv_w: f64,
    k: [f64; 3],
    /// `∂r/∂xⁱ`.
    dr: [f64; 3],
    f: f64,
    g: f64,
    h: f64,
}

impl Spheroid {
    #[inline]
    fn at(m: f64, a: f64, q: f64, x: &Vector4) -> Self {
        let (px, py, z) = (x[1], x[2], x[3]);
        let a2 = a * a;
        let half = 0.5 * (px * px + py * py + z * z - a2);
        let s = (half * half + z * z * a2).sqrt();
        let r2 = half + s;
        let r = r2.sqrt();
        let w = r2 + a2;
        let inv_w = 1.0 / w;
        let inv_r = 1.0 / r;
        let k = [(r * px - a * py) * inv_w, (r * py + a * px) * inv_w, z * inv_r];
        let scale = 0.5 / (r * s);
        let dr = [px * r2 * scale, py * r2 * scale, z * w * scale];
        let inv_den = 1.0 / (r2 * r2 + z * z * a2);
        let f = r2 * (2.0 * m * r - q * q) * inv_den;
        // ∂f = (∂num − f ∂den) / den with ∂num = r (6Mr − 2Q²) ∂r, ∂den = 4r³ ∂r + 2a²z δ_z.
        let g = (r * (6.0 * m * r - 2.0 * q * q) - 4.0 * f * r * r2) * inv_den;
        let h = 2.0 * f * a2 * z * inv_den;
        Self { a, x: [px, py, z], r, inv_r, inv_w, k, dr, f, g, h }
    }

    /// `∂_i f`.
    #[inline]
    fn df(&self) -> [f64; 3] {
        let (g, dr) = (self.g, &self.dr);
        [g * dr[0], g * dr[1], g * dr[2] - self.h]
    }
}

/// The Kerr–Schild fields at `x` of the hole of Kerr's family with mass `m`, spin `a` and
/// charge `q`, with their derivatives ([`Spheroid`]).
pub(super) fn spheroidal_fields(m: f64, a: f64, q: f64, x: &Vector4) -> KerrSchildPoint {
    let point = Spheroid::at(m, a, q, x);
    let Spheroid { a, x: [px, py, _], r, inv_r, inv_w, k, dr, f, .. } = point;
    let dk = std::array::from_fn(|i| {
        let along = |axis: usize| if i == axis { 1.0 } else { 0.0 };
        [
            inv_w * (dr[i] * (px - 2.0 * r * k[0]) + r * along(0) - a * along(1)),
            inv_w * (dr[i] * (py - 2.0 * r * k[1]) + r * along(1) + a * along(0)),
            inv_r * (along(2) - k[2] * dr[i]),
        ]
    });
    KerrSchildPoint { f, k, df: point.df(), dk }
}

/// Hamilton's equations at `x` about the hole of Kerr's family with mass `m`, spin `a` and
/// charge `q`: [`KerrSchildPoint::geodesic_rhs`] without forming the nine derivatives of `k`,
/// whose contraction with the momentum is, by [`spheroidal_fields`]' `∂_i k_j`,
/// `∂_i k_j p_j = c ∂_i r + e_i` with `c = ((x − 2r k_x) p_x + (y − 2r k_y) p_y)/(r² + a²)
/// − k_z p_z / r` and `e = ((r p_x + a p_y)/(r² + a²), (r p_y − a p_x)/(r² + a²), p_z / r)`.
pub(super) fn spheroidal_rhs(m: f64, a: f64, q: f64, x: &Vector4, p: &Covector4) -> (Vector4, Covector4) {
    let point = Spheroid::at(m, a, q, x);
    let Spheroid { a, x: [px, py, _], r, inv_r, inv_w, k, dr, f, .. } = point;
    let c = inv_w * ((px - 2.0 * r * k[0]) * p[1] + (py - 2.0 * r * k[1]) * p[2]) - inv_r * k[2] * p[3];
    let e = [inv_w * (r * p[1] + a * p[2]), inv_w * (r * p[2] - a * p[1]), inv_r * p[3]];
    let dq = std::array::from_fn(|i| -(c * dr[i] + e[i]));
    hamilton_rhs(f, &k, &point.df(), &dq, p)
}

/// `type = "kerr"`: [`Spacetime::kerr`].
pub static KERR: MetricDescriptor = MetricDescriptor {
    name: "kerr",
    description: "a rotating black hole, angular momentum `spin·mass`",
    parameters: &[MASS, SPIN],
    constraint: Some("|spin| ≤ mass"),
    oriented: true,
    build: |v| {
        let [mass, spin] = exactly(v)?;
        Spacetime::kerr(mass, spin)
    },
    values: |s| if let Spacetime::Kerr(h) = s { Some(vec![h.mass, h.spin]) } else { None },
};

impl Spacetime {
    /// Kerr with `|spin| ≤ mass`; spin along +z, positive for counter-clockwise rotation seen
    /// from +z.
    pub fn kerr(mass: f64, spin: f64) -> Result<Self, ParameterError> {
        let mass = non_negative("mass", mass)?;
        Ok(Spacetime::Kerr(Kerr::new(mass, at_most_mass("spin", spin, mass)?)))
    }
}

impl Kerr {
    pub fn new(mass: f64, spin: f64) -> Self {
        Self { mass, spin }
    }

    /// Spheroidal radius `r` of a spatial point.
    pub fn spheroidal_radius(&self, x: &Vector4) -> f64 {
        spheroidal::<f64>(self.spin, x[1], x[2], x[3]).0
    }
}

impl KerrSchild for Kerr {
    fn fields(&self, x: &Vector4) -> KerrSchildPoint {
        spheroidal_fields(self.mass, self.spin, 0.0, x)
    }

    #[inline]
    fn hamilton(&self, x: &Vector4, p: &Covector4) -> (Vector4, Covector4) {
        spheroidal_rhs(self.mass, self.spin, 0.0, x, p)
    }

    fn mass(&self) -> f64 {
        self.mass
    }

    fn radial_coordinate(&self, x: &Vector4) -> f64 {
        self.spheroidal_radius(x)
    }

    /// Outer horizon `r₊ = M + √(M² − a²)`.
    fn horizon_radius(&self) -> f64 {
        self.mass + (self.mass * self.mass - self.spin * self.spin).max(0.0).sqrt()
    }
}

/// A stationary, not static, hole: observers at rest outside the ergoregion, the normal
/// observer's frame inside it, the 4-D tracer, no connector.
impl Capabilities for Kerr {
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
        Forwards::SpinTwin(SpinTwin::new(self.mass, self.spin, 0.0))
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
        (self.mass > 0.0).then(|| CircularOrbits::new(self.mass, self.spin, 0.0))
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
impl OwnStepper for Kerr {
    type Tracer = MinoTracer;

    fn ray_tracer(&self, start: State, settings: TraceSettings) -> MinoTracer {
        MinoTracer::new(&KerrNewman::new(self.mass, self.spin, 0.0), start, settings)
    }
}

/// Where an observer can stay at rest about a hole of Kerr's family: outside the horizon (in
/// its spheroidal radius) and outside the ergoregion, where the static observer exists.
pub(super) fn spinning_rest<M: KerrSchild>(m: &M, region: Region, p: [f64; 3]) -> Result<(), NoRest> {
    let Some(x) = m.world_to_chart(region, p, 0.0) else { return Err(NoRest::NoSuchRegion) };
    if m.mass() > 0.0 && m.inside_horizon(&x) {
        return Err(NoRest::InsideHorizon { radius: m.radial_coordinate(&x), horizon: m.horizon_radius() });
    }
    Tetrad::static_observer(m, &x).map(|_| ()).map_err(|_| NoRest::InsideErgoregion)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::metric::Schwarzschild;

    #[test]
    fn zero_spin_is_schwarzschild() {
        let k = Kerr::new(1.3, 0.0);
        let s = Schwarzschild::new(1.3);
        let x = [0.0, 2.0, -3.0, 1.0];
        let (a, da) = k.inverse_metric_derivatives(&x);
        let (b, db) = s.inverse_metric_derivatives(&x);
        for i in 0..4 {
            for j in 0..4 {
                assert!((a[i][j] - b[i][j]).abs() < 1e-14);
                for d in 0..4 {
                    assert!((da[d][i][j] - db[d][i][j]).abs() < 1e-14);
                }
            }
        }
    }

    /// The fields by dual numbers, as the closed form's check.
    fn dual_fields(m: f64, a: f64, q: f64, x: &Vector4) -> KerrSchildPoint {
        use num_dual::DualSVec64;
        let var = |i: usize, v: f64| DualSVec64::<3>::from_re(v).derivative(i);
        let z = var(2, x[3]);
        let (r, r2, k) = spheroidal(a, var(0, x[1]), var(1, x[2]), z);
        let f = r2 * (r * (2.0 * m) - q * q) / (r2 * r2 + z * z * (a * a));
        let grad = |d: &DualSVec64<3>| {
            let g = d.eps.unwrap_generic(nalgebra::Const::<3>, nalgebra::U1);
            [g[0], g[1], g[2]]
        };
        let dk_by_component = [grad(&k[0]), grad(&k[1]), grad(&k[2])];
        KerrSchildPoint {
            f: f.re,
            k: [k[0].re, k[1].re, k[2].re],
            df: grad(&f),
            dk: std::array::from_fn(|i| std::array::from_fn(|j| dk_by_component[j][i])),
        }
    }

    #[test]
    fn closed_form_fields_match_dual_numbers() {
        let points = [
            [0.0, 2.0, -3.0, 1.0],
            [0.0, 0.3, 0.2, 1.4],
            [0.0, -1.1, 0.05, -0.02],
            [0.0, 0.0, 0.0, 2.5],
            [0.0, 40.0, -7.0, 3.0],
            [0.0, 1.3, 1.2, 0.0],
        ];
        for (m, a, q) in [(1.0, 0.0, 0.0), (1.0, 0.9, 0.0), (1.0, -0.99, 0.0), (0.3, 0.24, 0.15), (1.0, 0.6, 0.8)] {
            for x in &points {
                let (c, d) = (spheroidal_fields(m, a, q, x), dual_fields(m, a, q, x));
                let close = |u: f64, v: f64| (u - v).abs() <= 1e-12 * (1.0 + v.abs());
                assert!(close(c.f, d.f), "f at {x:?}: {} against {}", c.f, d.f);
                for i in 0..3 {
                    assert!(close(c.k[i], d.k[i]) && close(c.df[i], d.df[i]), "k, ∂f at {x:?}");
                    for j in 0..3 {
                        assert!(
                            close(c.dk[i][j], d.dk[i][j]),
                            "∂_{i} k_{j} at {x:?}: {} against {}",
                            c.dk[i][j],
                            d.dk[i][j]
                        );
                    }
                }
            }
        }
    }

    /// The contracted right-hand side is the one the fields give.
    #[test]
    fn closed_form_rhs_matches_the_fields() {
        let p = [-1.0, 0.3, -0.7, 0.5];
        for (m, a, q) in [(1.0, 0.0, 0.0), (1.0, 0.9, 0.0), (1.0, -0.99, 0.0), (1.0, 0.6, 0.8)] {
            for x in [[0.0, 2.0, -3.0, 1.0], [0.0, -1.1, 0.05, -0.02], [0.0, 0.0, 0.0, 2.5], [0.0, 40.0, -7.0, 3.0]] {
                let ((dx, dp), (ex, ep)) =
                    (spheroidal_rhs(m, a, q, &x, &p), spheroidal_fields(m, a, q, &x).geodesic_rhs(&p));
                for i in 0..4 {
                    assert!((dx[i] - ex[i]).abs() <= 1e-13 * (1.0 + ex[i].abs()), "dx at {x:?}");
                    assert!((dp[i] - ep[i]).abs() <= 1e-13 * (1.0 + ep[i].abs()), "dp at {x:?}");
                }
            }
        }
    }

    #[test]
    fn horizon_radius_of_extremal_and_slow_holes() {
        assert!((Kerr::new(1.0, 1.0).horizon_radius() - 1.0).abs() < 1e-15);
        assert!((Kerr::new(1.0, 0.6).horizon_radius() - 1.8).abs() < 1e-15);
    }
}

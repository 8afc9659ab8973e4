//! Ellis (Ellis–Bronnikov) wormhole with throat radius `b₀`:
//! `ds² = −dt² + dl² + (l² + b₀²) dΩ²`, `l ∈ (−∞, ∞)` (Ellis 1973; Morris & Thorne 1988).
//!
//! Chart: isotropic Cartesian coordinates `X = s n̂` with `s = l + √(l² + b₀²) ∈ (0, ∞)`. Then
//! `l² + b₀² = (s Ω)²` and `dl = Ω ds` with `Ω(s) = ½ (1 + b₀²/s²)`, so the spatial metric is
//! conformally flat, `Ω² δ_ij`: no poles anywhere, the throat is the sphere `s = b₀`, the upper
//! region (l > 0) is `s > b₀` and the lower region (l < 0) is the ball `s < b₀`, whose centre is
//! the lower region's infinity. `s ↦ b₀²/s` is an isometry exchanging the two regions.
//!
//! World coordinates of each region: `Y = ±ρ n̂` with `ρ = √(l² + b₀²)` the areal radius, `+` in the
//! upper region and `−` (antipodal) in the lower one, so a ray straight through the throat keeps
//! its direction and neither region is mirrored. The throat is the sphere `|Y| = b₀` of both.

use super::capabilities::{radial_frame, rest_on_chart, Capabilities, Forwards, LocalFrame, NoRest, Tracers};
use super::descriptor::{exactly, positive, MetricDescriptor, ParameterError, THROAT};
use super::{Metric, Region, Spacetime, WorldPoint};
use crate::disk::CircularOrbits;
use crate::geodesic::plane::PlaneMetric;
use crate::metric::schwarzschild::connect::Connector;
use crate::tensor::{normalize3, Covector4, Matrix4, Vector4};

/// Ellis wormhole.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Ellis {
    pub throat: f64,
}

/// `type = "ellis"`: [`Spacetime::ellis`].
pub static ELLIS: MetricDescriptor = MetricDescriptor {
    name: "ellis",
    description: "a traversable (Ellis) wormhole with throat radius `throat`",
    parameters: &[THROAT],
    constraint: None,
    oriented: false,
    build: |v| {
        let [throat] = exactly(v)?;
        Spacetime::ellis(throat)
    },
    values: |s| if let Spacetime::Ellis(w) = s { Some(vec![w.throat]) } else { None },
};

impl Spacetime {
    /// The Ellis wormhole with `throat > 0`.
    pub fn ellis(throat: f64) -> Result<Self, ParameterError> {
        Ok(Spacetime::Ellis(Ellis::new(positive("throat", throat)?)))
    }
}

impl Ellis {
    pub fn new(throat: f64) -> Self {
        Self { throat }
    }

    /// Proper radial coordinate `l` of an isotropic radius `s`.
    pub fn proper_radial(&self, s: f64) -> f64 {
        0.5 * (s - self.throat * self.throat / s)
    }

    /// Isotropic radius `s` of a proper radial coordinate `l` (stable on both sides).
    pub fn isotropic_radius(&self, l: f64) -> f64 {
        let rho = l.hypot(self.throat);
        if l >= 0.0 {
            l + rho
        } else {
            self.throat * self.throat / (rho - l)
        }
    }

    /// Conformal factor `Ω = ½ (1 + b₀²/s²)`.
    #[inline]
    fn conformal(&self, s2: f64) -> f64 {
        0.5 * (1.0 + self.throat * self.throat / s2)
    }
}

#[inline]
fn s2_of(x: &Vector4) -> f64 {
    x[1] * x[1] + x[2] * x[2] + x[3] * x[3]
}

impl Metric for Ellis {
    fn metric(&self, x: &Vector4) -> Matrix4 {
        let w = self.conformal(s2_of(x)).powi(2);
        [[-1.0, 0.0, 0.0, 0.0], [0.0, w, 0.0, 0.0], [0.0, 0.0, w, 0.0], [0.0, 0.0, 0.0, w]]
    }

    fn inverse_metric(&self, x: &Vector4) -> Matrix4 {
        let w = self.conformal(s2_of(x)).powi(-2);
        [[-1.0, 0.0, 0.0, 0.0], [0.0, w, 0.0, 0.0], [0.0, 0.0, w, 0.0], [0.0, 0.0, 0.0, w]]
    }

    /// `∂_a Ω⁻² = 2 b₀² x_a / (s⁴ Ω³)`.
    fn inverse_metric_derivatives(&self, x: &Vector4) -> (Matrix4, [Matrix4; 4]) {
        let s2 = s2_of(x);
        let omega = self.conformal(s2);
        let c = 2.0 * self.throat * self.throat / (s2 * s2 * omega.powi(3));
        let mut d = [[[0.0; 4]; 4]; 4];
        for (da, xa) in d.iter_mut().zip(x).skip(1) {
            for (i, row) in da.iter_mut().enumerate().skip(1) {
                row[i] = c * xa;
            }
        }
        (self.inverse_metric(x), d)
    }

    #[inline]
    fn geodesic_rhs(&self, x: &Vector4, p: &Covector4) -> (Vector4, Covector4) {
        let s2 = s2_of(x);
        let omega = self.conformal(s2);
        let w = 1.0 / (omega * omega);
        let p2 = p[1] * p[1] + p[2] * p[2] + p[3] * p[3];
        let c = -self.throat * self.throat * p2 / (s2 * s2 * omega * omega * omega);
        ([-p[0], w * p[1], w * p[2], w * p[3]], [0.0, c * x[1], c * x[2], c * x[3]])
    }

    fn length_scale(&self) -> f64 {
        self.throat
    }

    /// Areal radius `ρ = s Ω`.
    fn radius(&self, x: &Vector4) -> f64 {
        let s2 = s2_of(x);
        s2.sqrt() * self.conformal(s2)
    }

    /// Away from the throat means `|l|` growing: `s` grows above the throat, shrinks below it.
    fn is_outgoing(&self, x: &Vector4, dx: &Vector4) -> bool {
        let radial = x[1] * dx[1] + x[2] * dx[2] + x[3] * dx[3];
        match self.region(x) {
            Region::Upper => radial > 0.0,
            Region::Lower => radial < 0.0,
        }
    }

    fn region(&self, x: &Vector4) -> Region {
        if s2_of(x) >= self.throat * self.throat {
            Region::Upper
        } else {
            Region::Lower
        }
    }

    /// `Y = ±ρ n̂`; `dY = ±[(l/s)(n̂·dX) n̂ + Ω (dX − n̂ (n̂·dX))]` since `dρ/ds = l/s`.
    fn to_world(&self, x: &Vector4, dx: &Vector4) -> WorldPoint {
        let s2 = s2_of(x);
        let s = s2.sqrt();
        let omega = self.conformal(s2);
        let n = [x[1] / s, x[2] / s, x[3] / s];
        let region = self.region(x);
        let sign = if region == Region::Upper { 1.0 } else { -1.0 };
        let rho = s * omega;
        let radial = n[0] * dx[1] + n[1] * dx[2] + n[2] * dx[3];
        let l_over_s = self.proper_radial(s) / s;
        let dy: [f64; 3] =
            std::array::from_fn(|i| sign * (l_over_s * radial * n[i] + omega * (dx[i + 1] - n[i] * radial)));
        WorldPoint {
            region,
            position: [sign * rho * n[0], sign * rho * n[1], sign * rho * n[2]],
            direction: normalize3(&dy),
        }
    }

    fn world_to_chart(&self, region: Region, p: [f64; 3], t: f64) -> Option<Vector4> {
        let rho = crate::tensor::norm3(&p);
        if !rho.is_finite() || rho < self.throat {
            return None;
        }
        let l_abs = ((rho - self.throat) * (rho + self.throat)).sqrt();
        let (l, sign) = match region {
            Region::Upper => (l_abs, 1.0),
            Region::Lower => (-l_abs, -1.0),
        };
        let scale = sign * self.isotropic_radius(l) / rho;
        Some([t, p[0] * scale, p[1] * scale, p[2] * scale])
    }
}

/// In the ray's plane with `u = 1/s`, a conformally flat space is a medium of index `Ω`:
/// `(u')² + u² = Ω²/b²`, so `u'' = −u + Ω Ω_u / b²` with `Ω_u = b₀² u`. The same equation holds
/// for `ũ = 1/(b₀² u)` in the lower region. No radial stretch: the chart is isotropic.
impl PlaneMetric for Ellis {
    #[inline]
    fn binet_source(&self, u: f64, inv_b2: f64) -> f64 {
        let b02 = self.throat * self.throat;
        0.5 * (1.0 + b02 * u * u) * b02 * u * inv_b2
    }

    fn slope_squared(&self, u: f64, inv_b2: f64) -> f64 {
        let omega = 0.5 * (1.0 + self.throat * self.throat * u * u);
        omega * omega * inv_b2 - u * u
    }

    fn plane_hamiltonian(&self, u: f64, du: f64, b: f64) -> f64 {
        let omega = 0.5 * (1.0 + self.throat * self.throat * u * u);
        b * b / (2.0 * omega * omega) * (du * du - self.slope_squared(u, 1.0 / (b * b)))
    }

    fn radial_stretch(&self, _u: f64) -> f64 {
        1.0
    }

    fn impact_factor(&self, u: f64) -> f64 {
        self.world_radius(u)
    }

    /// `ρ = s Ω = (1/u + b₀² u) / 2`.
    fn world_radius(&self, u: f64) -> f64 {
        0.5 * (1.0 / u + self.throat * self.throat * u)
    }

    fn world_radius_slope(&self, u: f64) -> f64 {
        0.5 * (self.throat * self.throat - 1.0 / (u * u))
    }

    fn u_of_world_radius(&self, rho: f64) -> Option<f64> {
        (rho >= self.throat).then(|| 1.0 / self.isotropic_radius(((rho - self.throat) * (rho + self.throat)).sqrt()))
    }

    fn lapse(&self, _u: f64) -> f64 {
        1.0
    }

    /// `dρ/dl = |l|/ρ = (1 − b₀²u²)/(1 + b₀²u²)` (the same for `ũ` in the lower region).
    fn radial_scale(&self, u: f64) -> f64 {
        let b2u2 = self.throat * self.throat * u * u;
        ((1.0 - b2u2) / (1.0 + b2u2)).abs()
    }

    fn throat_u(&self) -> Option<f64> {
        Some(1.0 / self.throat)
    }
}

/// A static wormhole: two regions joined by the throat, lapse 1, observers at rest wherever the
/// chart reaches (world radius ≥ throat), the in-plane tracer.
impl Capabilities for Ellis {
    fn is_flat(&self) -> bool {
        false
    }

    fn is_spherically_symmetric(&self) -> bool {
        true
    }

    fn throat(&self) -> Option<f64> {
        Some(self.throat)
    }

    /// Static: reversed rays are rays.
    fn forwards(&self) -> Forwards {
        Forwards::Reversed
    }

    fn rest(&self, region: Region, p: [f64; 3]) -> Result<(), NoRest> {
        rest_on_chart(self, region, p, self.throat)
    }

    fn local_frame(&self, _region: Region, p: [f64; 3]) -> LocalFrame {
        radial_frame(self, p)
    }

    fn observer_lapse(&self, _region: Region, _p: [f64; 3]) -> f64 {
        1.0
    }

    /// The areal radius is the world's and the lapse 1: a ray of impact parameter `b` turns at
    /// world radius `b`.
    fn impact_bound(&self, radius: f64) -> Option<f64> {
        Some(radius)
    }

    /// Rays bend away from the throat on the way out of it as well as towards it.
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
        tracers.in_plane(self)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn chart_radius_round_trips_and_areal_radius_matches() {
        let m = Ellis::new(2.0);
        for l in [-50.0, -2.0, -1e-3, 0.0, 0.5, 7.0, 1e4] {
            let s = m.isotropic_radius(l);
            assert!((m.proper_radial(s) - l).abs() < 1e-12 * (1.0 + l.abs()), "l = {l}");
            let x = [0.0, s, 0.0, 0.0];
            assert!((m.radius(&x) - l.hypot(2.0)).abs() < 1e-12 * (1.0 + l.abs()));
        }
    }

    #[test]
    fn radial_scale_is_areal_radius_per_proper_length() {
        let m = Ellis::new(1.3);
        for l in [-20.0, -2.0, -0.4, 0.3, 1.0, 9.0] {
            let h = 1e-6;
            let rho = |l: f64| l.hypot(1.3);
            let fd = (rho(l + h) - rho(l - h)).abs() / (2.0 * h);
            let u = 1.0 / m.isotropic_radius(l.abs());
            assert!((m.radial_scale(u) - fd).abs() < 1e-8, "l = {l}");
        }
    }

    #[test]
    fn world_coordinates_round_trip_on_both_sides() {
        let m = Ellis::new(1.5);
        for region in [Region::Upper, Region::Lower] {
            let p = [3.0, -1.0, 2.0];
            let x = m.world_to_chart(region, p, 0.0).unwrap();
            let w = m.to_world(&x, &[0.0, 1.0, 0.0, 0.0]);
            assert_eq!(w.region, region);
            for i in 0..3 {
                assert!((w.position[i] - p[i]).abs() < 1e-12);
            }
        }
        assert!(m.world_to_chart(Region::Upper, [0.5, 0.0, 0.0], 0.0).is_none(), "inside the throat");
    }
}

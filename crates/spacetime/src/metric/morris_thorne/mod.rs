//! Morris–Thorne wormholes of zero tidal force with any shape:
//! `ds² = −dt² + dl² + r(l)² dΩ²`, `l ∈ (−∞, ∞)` (Morris & Thorne 1988, eq. (1) with `Φ = 0`).
//! The areal radius `r(l)` ([`Shape`]) is the one thing that varies between them: the
//! *Interstellar* wormhole ([`Dneg`]) is one shape, Ellis's `√(l² + b₀²)` another (the
//! [`Ellis`](super::Ellis) metric keeps its own conformally flat chart).
//!
//! Chart: Cartesian `X = s n̂` with `s = L + √(L² + ρ²)` (`ρ` the throat radius) and
//! `L(l) = l − μ asinh(l/2μ)` an odd stretch of `l` that takes out the logarithm of the shape
//! far out ([`Shape::log_coefficient`]; `L = l` and Ellis's isotropic chart for `μ = 0`).
//! `s ↦ ρ²/s` is `l ↦ −l`, an isometry of every even shape, so the upper region (l > 0) is
//! `s > ρ` and the lower region the ball `s < ρ`, and the in-plane tracer's rule for crossing the
//! throat (`ũ = 1/(ρ² u)`) holds. With `dL = Ω ds`, `Ω = ½(1 + ρ²/s²)`, the spatial metric is
//! `(Ω/L')² n̂n̂ + (r/s)² (δ − n̂n̂)`: regular for `s > 0`, conformally flat for Ellis's shape only.
//!
//! World coordinates of each region: `Y = ±r n̂` (antipodal in the lower region, as Ellis's), so
//! a ray straight through keeps its direction. Where the shape has a cylinder of radius `ρ`
//! (Interstellar's interior), world points of radius `ρ` are its mouth, `|l| = a`.

mod dneg;

pub use dneg::{Dneg, MIN_RELATIVE_LENSING_WIDTH, WORMHOLE};

use super::capabilities::{radial_frame, rest_on_chart, Capabilities, Forwards, LocalFrame, NoRest, Tracers};
use super::{Metric, Region, WorldPoint};
use crate::disk::CircularOrbits;
use crate::geodesic::plane::PlaneMetric;
use crate::metric::schwarzschild::connect::Connector;
use crate::tensor::{norm3, normalize3, Matrix4, Vector4};

/// The areal radius of a wormhole at proper radial distance `l` from its throat's middle.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Radius {
    /// `r(l)`.
    pub r: f64,
    /// `dr/dl`.
    pub slope: f64,
    /// `r − l dr/dl`, where the tangent meets `l = 0`: given by the shape, because far out `r`
    /// and `l dr/dl` nearly cancel and the Binet equation needs their difference.
    pub intercept: f64,
}

/// A wormhole's shape function `r(l)`: even, at least C¹, `r ≥ r(0) = ρ` (the throat), strictly
/// increasing in `|l|` beyond the throat's extent (`r = ρ` may hold over an interval `|l| ≤ a`),
/// and asymptotically flat, `r/|l| → 1`.
pub trait Shape: Copy + std::fmt::Debug + PartialEq + Send + Sync {
    /// The throat radius `ρ`, the least areal radius.
    fn throat(&self) -> f64;
    /// `r`, `dr/dl` and `r − l dr/dl` at `l`.
    fn radius(&self, l: f64) -> Radius;
    /// The largest `l` with `r(l) = rho`, for `rho ≥ ρ`: where a world radius lies in the upper
    /// region (the mouth `l = a` for `rho = ρ`).
    fn proper_distance(&self, rho: f64) -> f64;
    /// `μ` in `r = |l| − μ ln |l| + O(1)` far out: the logarithm the chart takes out (the mass
    /// parameter of Interstellar's shape; 0 where `r − |l|` stays bounded, as for Ellis's).
    fn log_coefficient(&self) -> f64;
}

/// A Morris–Thorne wormhole of shape `S`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MorrisThorne<S: Shape> {
    pub shape: S,
}

/// The *Interstellar* wormhole (James et al. 2015).
pub type Wormhole = MorrisThorne<Dneg>;

/// The smallest `u`, in inverse throat radii, the in-plane functions are evaluated at: `u = 0`
/// (infinity) has no chart point, and every function used there has its limit well above this.
const U_FLOOR: f64 = 1e-100;

/// The chart's radial variable `L(l) = l − μ asinh(l/2μ)` at `l` and its derivatives
/// ([`MorrisThorne::stretch`]).
#[derive(Clone, Copy, Debug)]
struct Stretch {
    big_l: f64,
    /// `dL/dl ∈ [½, 1]`.
    d1: f64,
    /// `d²L/dl²`.
    d2: f64,
    /// `l dL/dl − L = μ (asinh z − z/√(1 + z²))`, `z = l/2μ`: small where `L` and `l dL/dl` are not.
    excess: f64,
}

/// Everything at one chart radius `s`: the shape there, `Ω = dL/ds` and the stretch of `l`.
#[derive(Clone, Copy, Debug)]
struct ChartPoint {
    radius: Radius,
    omega: f64,
    stretch: Stretch,
}

/// The in-plane ingredients at `u`: `Q = (ur)² L'/Ω`, `P = u (ur) L'/Ω` and their
/// `u`-derivatives, with `(u')² = Q²/b² − P²`.
#[derive(Clone, Copy, Debug)]
struct PlanePoint {
    u: f64,
    q: f64,
    dq: f64,
    p: f64,
    dp: f64,
    chart: ChartPoint,
}

impl<S: Shape> MorrisThorne<S> {
    pub fn new(shape: S) -> Self {
        Self { shape }
    }

    fn c2(&self) -> f64 {
        self.shape.throat() * self.shape.throat()
    }

    /// `L(l) = l − μ asinh(l/2μ)` with `μ` the shape's [`Shape::log_coefficient`]: odd, smooth,
    /// `dL/dl ∈ [½, 1]`, and far out `L − r` tends to a constant, so that the chart radius is
    /// proportional to the areal one up to `O(1/r)` (with `s = 2l` instead, the Binet source of
    /// a shape with `r ≈ |l| − μ ln |l|` would grow like `ln(1/u)` towards infinity).
    fn stretch(&self, l: f64) -> Stretch {
        let mu = self.shape.log_coefficient();
        if mu == 0.0 {
            return Stretch { big_l: l, d1: 1.0, d2: 0.0, excess: 0.0 };
        }
        let z = l / (2.0 * mu);
        let h = z.hypot(1.0);
        Stretch {
            big_l: l - mu * z.asinh(),
            d1: 1.0 - 0.5 / h,
            d2: z / (4.0 * mu) / h / h / h,
            excess: mu * (z.asinh() - z / h),
        }
    }

    /// `l` of a stretched `L` by Newton's method (`dL/dl ≥ ½`, `L` convex for `l > 0`, concave
    /// below: the iterates settle within a few steps).
    fn unstretch(&self, big_l: f64) -> f64 {
        let mu = self.shape.log_coefficient();
        if mu == 0.0 {
            return big_l;
        }
        let mut l = big_l + mu * (big_l / (2.0 * mu)).asinh();
        for _ in 0..60 {
            let st = self.stretch(l);
            let next = l - (st.big_l - big_l) / st.d1;
            let done = (next - l).abs() <= 1e-15 * next.abs().max(mu);
            l = next;
            if done {
                break;
            }
        }
        l
    }

    /// Chart radius `s = L + √(L² + ρ²)` of `l` (stable on both sides).
    fn chart_radius(&self, l: f64) -> f64 {
        let big_l = self.stretch(l).big_l;
        let root = big_l.hypot(self.shape.throat());
        if big_l >= 0.0 {
            big_l + root
        } else {
            self.c2() / (root - big_l)
        }
    }

    /// The point at chart radius `s`: `L = ½(s − ρ²/s)`, `Ω = dL/ds = ½(1 + ρ²/s²)`.
    fn at(&self, s: f64) -> ChartPoint {
        let l = self.unstretch(0.5 * (s - self.c2() / s));
        ChartPoint { radius: self.shape.radius(l), omega: 0.5 * (1.0 + self.c2() / (s * s)), stretch: self.stretch(l) }
    }

    /// `dl/du = −Ω/(u² L')`; `d(ur)/du = r − (r_l/L')(L + ρ²u)`, written as
    /// `[(r − l r_l) L' + r_l (l L' − L − ρ²u)]/L'` so that far out nothing large cancels.
    fn plane_point(&self, u: f64) -> PlanePoint {
        let c2 = self.c2();
        let u = u.max(U_FLOOR / self.shape.throat());
        let chart = self.at(1.0 / u);
        let ChartPoint { radius, omega, stretch } = chart;
        let v = u * radius.r;
        let dv = (radius.intercept * stretch.d1 + radius.slope * (stretch.excess - c2 * u)) / stretch.d1;
        let dl_du = -omega / (u * u * stretch.d1);
        let k = stretch.d1 / omega;
        let dk = stretch.d2 * dl_du / omega - k * c2 * u / omega;
        let (q, p) = (v * v * k, u * v * k);
        let dq = 2.0 * v * dv * k + v * v * dk;
        let dp = v * k + u * dv * k + u * v * dk;
        PlanePoint { u, q, dq, p, dp, chart }
    }
}

#[inline]
fn s2_of(x: &Vector4) -> f64 {
    x[1] * x[1] + x[2] * x[2] + x[3] * x[3]
}

impl<S: Shape> Metric for MorrisThorne<S> {
    /// `g_ij = (r/s)² δ_ij + ((Ω/L')² − (r/s)²) n_i n_j`.
    fn metric(&self, x: &Vector4) -> Matrix4 {
        let s2 = s2_of(x);
        let s = s2.sqrt();
        let pt = self.at(s);
        let a = (pt.omega / pt.stretch.d1).powi(2);
        let b = (pt.radius.r / s).powi(2);
        let mut g = [[0.0; 4]; 4];
        g[0][0] = -1.0;
        for i in 1..4 {
            for j in 1..4 {
                g[i][j] = (a - b) / s2 * (x[i] * x[j]) + if i == j { b } else { 0.0 };
            }
        }
        g
    }

    /// `g^ij = α δ_ij + γ x_i x_j` with `α = s²/r²`, `γ = ((L'/Ω)² − α)/s²`, and
    /// `∂_a g^ij = (x_a/s)(α_s δ_ij + γ_s x_i x_j) + γ (δ_ai x_j + δ_aj x_i)`, using
    /// `dl/ds = Ω/L'`, `dΩ/ds = −ρ²/s³`.
    fn inverse_metric_derivatives(&self, x: &Vector4) -> (Matrix4, [Matrix4; 4]) {
        let s2 = s2_of(x);
        let s = s2.sqrt();
        let ChartPoint { radius, omega, stretch } = self.at(s);
        let r = radius.r;
        let dl_ds = omega / stretch.d1;
        let r_s = dl_ds * radius.slope;
        let alpha = s2 / (r * r);
        let alpha_s = 2.0 * s / (r * r) * (1.0 - s * r_s / r);
        let inv_a = (stretch.d1 / omega).powi(2);
        let inv_a_s = 2.0 * stretch.d2 / omega + 2.0 * inv_a * self.c2() / (s2 * s * omega);
        let gamma = (inv_a - alpha) / s2;
        let gamma_s = (inv_a_s - alpha_s) / s2 - 2.0 * (inv_a - alpha) / (s2 * s);
        let mut ginv = [[0.0; 4]; 4];
        let mut d = [[[0.0; 4]; 4]; 4];
        ginv[0][0] = -1.0;
        for i in 1..4 {
            for j in 1..4 {
                let delta = if i == j { 1.0 } else { 0.0 };
                ginv[i][j] = alpha * delta + gamma * (x[i] * x[j]);
                for (a, da) in d.iter_mut().enumerate().skip(1) {
                    let mut v = x[a] / s * (alpha_s * delta + gamma_s * (x[i] * x[j]));
                    if a == i {
                        v += gamma * x[j];
                    }
                    if a == j {
                        v += gamma * x[i];
                    }
                    da[i][j] = v;
                }
            }
        }
        (ginv, d)
    }

    fn length_scale(&self) -> f64 {
        self.shape.throat()
    }

    fn radius(&self, x: &Vector4) -> f64 {
        self.at(s2_of(x).sqrt()).radius.r
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
        if s2_of(x) >= self.c2() {
            Region::Upper
        } else {
            Region::Lower
        }
    }

    /// `Y = ±r n̂`; `dY = ±[(dr/ds)(n̂·dX) n̂ + (r/s)(dX − n̂ (n̂·dX))]`.
    fn to_world(&self, x: &Vector4, dx: &Vector4) -> WorldPoint {
        let s = s2_of(x).sqrt();
        let n = [x[1] / s, x[2] / s, x[3] / s];
        let ChartPoint { radius, omega, stretch } = self.at(s);
        let region = self.region(x);
        let sign = if region == Region::Upper { 1.0 } else { -1.0 };
        let r_s = omega / stretch.d1 * radius.slope;
        let radial = n[0] * dx[1] + n[1] * dx[2] + n[2] * dx[3];
        let dy: [f64; 3] =
            std::array::from_fn(|i| sign * (r_s * radial * n[i] + radius.r / s * (dx[i + 1] - n[i] * radial)));
        WorldPoint { region, position: n.map(|c| sign * radius.r * c), direction: normalize3(&dy) }
    }

    fn world_to_chart(&self, region: Region, p: [f64; 3], t: f64) -> Option<Vector4> {
        let rho = norm3(&p);
        if !rho.is_finite() || rho < self.shape.throat() {
            return None;
        }
        let l_abs = self.shape.proper_distance(rho);
        let (l, sign) = match region {
            Region::Upper => (l_abs, 1.0),
            Region::Lower => (-l_abs, -1.0),
        };
        let scale = sign * self.chart_radius(l) / rho;
        Some([t, p[0] * scale, p[1] * scale, p[2] * scale])
    }
}

/// In the ray's plane with `u = 1/s`: `dl/dφ = ±r √(r² − b²)/b` and `du/dl = −u² L'/Ω`, so
/// `(u')² = Q²/b² − P²` with `Q = (ur)² L'/Ω`, `P = u (ur) L'/Ω`, and the Binet source is
/// `G = u + ½ d(u')²/du = u + Q Q_u/b² − P P_u`. Ellis's shape gives `Q = Ω`, `P = u`, his
/// metric's equation. The lower region's `ũ = 1/(ρ² u)` obeys the same equation (the shape is
/// even). A shape that is only C¹ (Interstellar's, at the mouths) makes `G` continuous with a
/// jump in its slope, which the step-size control resolves (tested to 10⁻⁷ in the bending).
impl<S: Shape> PlaneMetric for MorrisThorne<S> {
    /// Below the floor (beyond infinity, where a step that escapes ends), continued to first
    /// order: `G = u + ½F'(floor)`, consistent with [`PlaneMetric::slope_squared`]'s line.
    fn binet_source(&self, u: f64, inv_b2: f64) -> f64 {
        let pt = self.plane_point(u);
        u.max(pt.u) + pt.q * pt.dq * inv_b2 - pt.p * pt.dp
    }

    fn slope_squared(&self, u: f64, inv_b2: f64) -> f64 {
        let pt = self.plane_point(u);
        let at = pt.q * pt.q * inv_b2 - pt.p * pt.p;
        let beyond = (u - pt.u).min(0.0);
        at + 2.0 * (pt.q * pt.dq * inv_b2 - pt.p * pt.dp) * beyond
    }

    /// `H = ½(−1 + p_l² + b²/r²)` with `p_l = −b u'/Q`: `H = b²/(2Q²) (u'² − (Q²/b² − P²))`.
    fn plane_hamiltonian(&self, u: f64, du: f64, b: f64) -> f64 {
        let q = self.plane_point(u).q;
        b * b / (2.0 * q * q) * (du * du - self.slope_squared(u, 1.0 / (b * b)))
    }

    /// `σ = Ω/(u r L')`: the static observer's radial component is `(dl/dφ)/r = −u' Ω/(u² r L')`.
    fn radial_stretch(&self, u: f64) -> f64 {
        let pt = self.plane_point(u);
        pt.u / pt.p
    }

    fn impact_factor(&self, u: f64) -> f64 {
        self.world_radius(u)
    }

    fn world_radius(&self, u: f64) -> f64 {
        self.plane_point(u).chart.radius.r
    }

    /// `dr/du = −Ω/(u² L') dr/dl`.
    fn world_radius_slope(&self, u: f64) -> f64 {
        let PlanePoint { u, chart, .. } = self.plane_point(u);
        -chart.omega / (u * u * chart.stretch.d1) * chart.radius.slope
    }

    fn u_of_world_radius(&self, rho: f64) -> Option<f64> {
        (rho >= self.shape.throat()).then(|| 1.0 / self.chart_radius(self.shape.proper_distance(rho)))
    }

    fn lapse(&self, _u: f64) -> f64 {
        1.0
    }

    /// `κ = |dr/dl|` (the same for `ũ` in the lower region).
    fn radial_scale(&self, u: f64) -> f64 {
        self.plane_point(u).chart.radius.slope.abs()
    }

    fn throat_u(&self) -> Option<f64> {
        Some(1.0 / self.shape.throat())
    }
}

/// A static wormhole: two regions joined by the throat, lapse 1, observers at rest wherever the
/// chart reaches (world radius ≥ throat), the in-plane tracer: Ellis's answers, for any shape.
impl<S: Shape> Capabilities for MorrisThorne<S> {
    fn is_flat(&self) -> bool {
        false
    }

    fn is_spherically_symmetric(&self) -> bool {
        true
    }

    fn throat(&self) -> Option<f64> {
        Some(self.shape.throat())
    }

    /// Static: reversed rays are rays.
    fn forwards(&self) -> Forwards {
        Forwards::Reversed
    }

    fn rest(&self, region: Region, p: [f64; 3]) -> Result<(), NoRest> {
        rest_on_chart(self, region, p, self.shape.throat())
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
    use crate::metric::Ellis;

    /// Ellis's shape, to check the general wormhole against the Ellis metric.
    #[derive(Clone, Copy, Debug, PartialEq)]
    struct EllisShape(f64);

    impl Shape for EllisShape {
        fn throat(&self) -> f64 {
            self.0
        }
        fn radius(&self, l: f64) -> Radius {
            let r = l.hypot(self.0);
            Radius { r, slope: l / r, intercept: self.0 * self.0 / r }
        }
        fn proper_distance(&self, rho: f64) -> f64 {
            ((rho - self.0) * (rho + self.0)).sqrt()
        }
        fn log_coefficient(&self) -> f64 {
            0.0
        }
    }

    /// With Ellis's shape the chart is Ellis's isotropic one: the same metric, plane reduction
    /// and world coordinates, to rounding.
    #[test]
    fn ellis_shape_is_the_ellis_metric() {
        let (general, ellis) = (MorrisThorne::new(EllisShape(1.5)), Ellis::new(1.5));
        for x in [[0.0, 3.0, -1.0, 2.0], [0.2, 0.3, 0.4, -0.2], [1.0, 1.4, 0.1, 0.3], [0.0, 40.0, 3.0, 1.0]] {
            let (g1, g2) = (general.inverse_metric_derivatives(&x), ellis.inverse_metric_derivatives(&x));
            for i in 0..4 {
                for j in 0..4 {
                    assert!((g1.0[i][j] - g2.0[i][j]).abs() < 1e-12 * (1.0 + g2.0[i][j].abs()), "{x:?}");
                    for a in 0..4 {
                        let (d1, d2) = (g1.1[a][i][j], g2.1[a][i][j]);
                        assert!((d1 - d2).abs() < 1e-11 * (1.0 + d2.abs()), "∂_{a} g^{i}{j} at {x:?}: {d1} vs {d2}");
                    }
                }
            }
            let dx = [0.0, 0.3, -0.5, 0.8];
            let (w1, w2) = (general.to_world(&x, &dx), ellis.to_world(&x, &dx));
            assert_eq!(w1.region, w2.region);
            for i in 0..3 {
                assert!((w1.position[i] - w2.position[i]).abs() < 1e-12 * (1.0 + w2.position[i].abs()));
                assert!((w1.direction[i] - w2.direction[i]).abs() < 1e-12);
            }
        }
        for u in [0.0, 1e-6, 0.01, 0.3, 0.6, 0.66, 0.7] {
            for inv_b2 in [1e-6, 0.2, 1.0] {
                let (g1, g2) = (general.binet_source(u, inv_b2), ellis.binet_source(u, inv_b2));
                assert!((g1 - g2).abs() < 1e-13 * (u + g2.abs()) + 1e-99, "G at u = {u}: {g1} vs {g2}");
                let (f1, f2) = (general.slope_squared(u, inv_b2), ellis.slope_squared(u, inv_b2));
                assert!((f1 - f2).abs() < 1e-13 * (u * u + f2.abs()), "u'² at u = {u}: {f1} vs {f2}");
            }
            if u > 0.0 {
                assert!((general.world_radius(u) - ellis.world_radius(u)).abs() < 1e-12 * ellis.world_radius(u));
                assert!((general.radial_stretch(u) - 1.0).abs() < 1e-14);
            }
        }
    }
}

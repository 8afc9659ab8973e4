//! A ray's constants of motion and its Mino state `(u, u', n, v)` (module documentation of
//! [`super`]): the right-hand side, and the chart point and covariant momentum of a state.

use crate::geodesic::State;
use crate::metric::{KerrNewman, KerrSchild};
use crate::tensor::{Covector4, Vector4};

/// A hole's parameters and a ray's constants of motion (see the module documentation).
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) struct Constants {
    pub(super) mass: f64,
    pub(super) spin: f64,
    /// `Q_e²`, the charge squared.
    pub(super) charge2: f64,
    /// `E = −p_t`.
    pub(super) energy: f64,
    /// `L = p_φ`.
    pub(super) axial: f64,
    /// `K = Q + (L − aE)²`.
    pub(super) carter_k: f64,
    /// `b = a(aE − L)`.
    pub(super) b: f64,
    /// `c = a² + Q_e²`.
    pub(super) c: f64,
    /// `a²E²`.
    pub(super) a2e2: f64,
    /// `Q + L²`: `k = Q + L² + 2a²E² n_z²`.
    pub(super) sphere: f64,
}

impl Constants {
    /// Whether `G` is taken as `K u²/(A − u')` at `u'` and `A = E + b u²` (where `r'` has the
    /// sign of `P`, as on the past horizon that backward rays cross), not as `(A + u')/D`.
    #[inline]
    pub(super) fn g_by_quotient_of_k(w: f64, big_a: f64) -> bool {
        big_a * w < 0.0
    }

    /// `G = (P − r')/Δ` from `u`, `u'` and `A = E + b u²`, regular on the past horizon.
    #[inline]
    pub(super) fn g(&self, u: f64, w: f64, big_a: f64) -> f64 {
        if Self::g_by_quotient_of_k(w, big_a) {
            self.carter_k * u * u / (big_a - w)
        } else {
            (big_a + w) / (1.0 + u * (self.c * u - 2.0 * self.mass))
        }
    }

    /// The right-hand side `dy/dλ_M` of the state `y = (u, u', n, v)`.
    #[inline]
    pub(super) fn rhs(&self, y: &[f64; 8]) -> [f64; 8] {
        let [u, w, n0, n1, n2, v0, v1, v2] = *y;
        let u2 = u * u;
        let big_a = self.energy + self.b * u2;
        let dw = 2.0 * self.b * u * big_a - self.carter_k * u * (1.0 + u * (2.0 * self.c * u - 3.0 * self.mass));
        let f = self.spin * (self.g(u, w, big_a) - self.energy);
        let k = self.sphere + 2.0 * self.a2e2 * n2 * n2;
        [w, dw, v0 - f * n1, v1 + f * n0, v2, -f * v1 - k * n0, f * v0 - k * n1, (self.a2e2 - k) * n2]
    }

    /// The chart point `(x, y, z)` of `(u, n)`.
    #[inline]
    pub(super) fn point(&self, u: f64, n: [f64; 3]) -> [f64; 3] {
        let r = 1.0 / u;
        [r * n[0] + self.spin * n[1], r * n[1] - self.spin * n[0], r * n[2]]
    }

    /// The chart velocity `d(x, y, z)/dλ_M` of the state `y` whose derivative is `dy`.
    #[inline]
    pub(super) fn velocity(&self, y: &[f64; 8], dy: &[f64; 8]) -> [f64; 3] {
        let r = 1.0 / y[0];
        let dr = -dy[0] * r * r;
        let a = self.spin;
        [dr * y[2] + r * dy[2] + a * dy[3], dr * y[3] + r * dy[3] - a * dy[2], dr * y[4] + r * dy[4]]
    }

    /// The chart velocity `dx^μ/dλ` (affine) of the state `y`, time first.
    fn four_velocity(&self, y: &[f64; 8]) -> Vector4 {
        let dy = self.rhs(y);
        let [u, w, _, _, n2, ..] = *y;
        let (r, a) = (1.0 / u, self.spin);
        let dt = self.time_rate(u, w, y[2] * y[2] + y[3] * y[3]);
        let inv_sigma = 1.0 / (r * r + a * a * n2 * n2);
        let v = self.velocity(y, &dy);
        [dt * inv_sigma, v[0] * inv_sigma, v[1] * inv_sigma, v[2] * inv_sigma]
    }

    /// The Kerr–Schild `f` and `l_μ = (1, −k)` at the state `y`, `k` the chart's radial unit
    /// vector there: `n` itself, and `f = (2Mr − Q_e²)/Σ`.
    fn kerr_schild(&self, y: &[f64; 8]) -> (f64, [f64; 3]) {
        let r = 1.0 / y[0];
        let sigma = r * r + self.spin * self.spin * y[4] * y[4];
        ((2.0 * self.mass * r - self.charge2) / sigma, [y[2], y[3], y[4]])
    }

    /// The covariant momentum `p_μ = g_μν dx^ν/dλ` of the state `y`, and its Hamiltonian
    /// `½ g_μν ẋ^μ ẋ^ν` (zero on a null ray).
    pub(super) fn momentum(&self, y: &[f64; 8]) -> (Covector4, f64) {
        let v = self.four_velocity(y);
        let (f, k) = self.kerr_schild(y);
        // g = η + f l ⊗ l with l_μ = (1, −k).
        let lv = v[0] - (k[0] * v[1] + k[1] * v[2] + k[2] * v[3]);
        let p = [-v[0] + f * lv, v[1] - f * lv * k[0], v[2] - f * lv * k[1], v[3] - f * lv * k[2]];
        let h = 0.5 * (p[0] * v[0] + p[1] * v[1] + p[2] * v[2] + p[3] * v[3]);
        (p, h)
    }
}

/// The Mino state of the ray at `start` (chart position and covariant momentum) about `hole`,
/// and its constants (infinite `u` at the centre, which is inside the horizon).
pub(super) fn from_chart(hole: &KerrNewman, start: &State) -> (Constants, [f64; 8]) {
    let (x, p) = (&start.x, &start.p);
    let (m, a) = (hole.mass, hole.spin);
    let (dx, _) = crate::metric::Metric::geodesic_rhs(hole, x, p);
    let r = hole.radial_coordinate(x);
    let (px, py, z) = (x[1], x[2], x[3]);
    let rho2 = px * px + py * py + z * z;
    // r⁴ − (ρ² − a²) r² − a² z² = 0, differentiated along the ray.
    let dr = (r * r * (px * dx[1] + py * dx[2] + z * dx[3]) + a * a * z * dx[3]) / (r * (2.0 * r * r - rho2 + a * a));
    let inv_w = 1.0 / (r * r + a * a);
    let n = [(r * px - a * py) * inv_w, (r * py + a * px) * inv_w, z / r];
    // n_x + i n_y = (x + iy)/(r − ia): its derivative is ((ẋ + iẏ) − (n_x + i n_y) ṙ)(r + ia)/(r² + a²).
    let (cx, cy) = (dx[1] - n[0] * dr, dx[2] - n[1] * dr);
    let sigma = r * r + a * a * n[2] * n[2];
    let dn = [sigma * (r * cx - a * cy) * inv_w, sigma * (r * cy + a * cx) * inv_w, sigma * (dx[3] - n[2] * dr) / r];
    let u = 1.0 / r;
    let w = -sigma * dr * u * u;
    let (energy, axial) = (-p[0], px * p[2] - py * p[1]);
    // F = a(G − E) with G = E − p_r, p_r = p · n the chart's radial momentum.
    let f = -a * (p[1] * n[0] + p[2] * n[1] + p[3] * n[2]);
    let v = [dn[0] + f * n[1], dn[1] - f * n[0], dn[2]];
    let a2e2 = a * a * energy * energy;
    // |v|² = Q + L² + a²E² n_z².
    let carter_q = v[0] * v[0] + v[1] * v[1] + v[2] * v[2] - axial * axial - a2e2 * n[2] * n[2];
    let carter_k = carter_q + (axial - a * energy).powi(2);
    let charge2 = hole.charge * hole.charge;
    let c = a * a + charge2;
    let b = a * (a * energy - axial);
    let sphere = carter_q + axial * axial;
    let constants = Constants { mass: m, spin: a, charge2, energy, axial, carter_k, b, c, a2e2, sphere };
    (constants, [u, w, n[0], n[1], n[2], v[0], v[1], v[2]])
}

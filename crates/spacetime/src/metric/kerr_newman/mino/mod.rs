//! Rays about a hole of Kerr's family traced in Mino time with their constants of motion: the
//! stepper the hole provides ([`crate::metric::OwnStepper`]), where the 4-D tracer integrates
//! Hamilton's equations in the Kerr–Schild chart.
//!
//! In Boyer–Lindquist coordinates with Mino time `dλ_M = dλ/Σ`, `Σ = r² + a² cos²θ`, a null
//! geodesic of energy `E = −p_t`, axial angular momentum `L = p_φ` and Carter constant `Q` obeys
//! (Carter 1968; Mino 2003, eqs. 2.9–2.12), with `Δ = r² − 2Mr + a² + Q_e²` (`Q_e` the charge),
//! `P = E(r² + a²) − aL` and `K = Q + (L − aE)²`:
//!
//! - `(dr/dλ_M)² = R(r) = P² − ΔK`;
//! - `(dθ/dλ_M)² = Θ = Q + cos²θ (a²E² − L²/sin²θ)`;
//! - `dφ/dλ_M = aP/Δ + L/sin²θ − aE`, `dt/dλ_M = (r² + a²)P/Δ + a(L − aE sin²θ)`.
//!
//! Those equations are quadratic in `(E, L, √Q)`, so they hold for the backward momenta traced
//! here as for forward ones. Two choices make them regular wherever a backward ray goes:
//!
//! - **Radius.** `u = 1/r` obeys `(du/dλ_M)² = U(u) = u⁴R(1/u) = A² − D K u²` with
//!   `A = u²P = E + b u²`, `b = a(aE − L)`, `D = u²Δ = 1 − 2Mu + c u²`, `c = a² + Q_e²`; its
//!   second-order form `u'' = U'(u)/2 = 2b u A − K u (1 − 3Mu + 2c u²)` has no square root and
//!   no turning-point trouble, and stays smooth out to infinity (`u → 0` linearly in Mino time,
//!   where `r` has a pole), so a ray leaves for the escape radius in a step or two.
//! - **Angles.** The unit vector `n = (sinθ cos φ̃, sinθ sin φ̃, cos θ)` (`φ̃` the chart's
//!   azimuth) moves as `n' = F ẑ × n + v`: `v = θ' ê_θ + (L/sinθ) ê_φ` is the motion of a
//!   particle on the unit sphere with Hamiltonian `½|p|² − ½a²E² n_z²` (whose `p_θ² + L²/sin²θ
//!   = Q + L² + a²E² cos²θ` is Carter's `Θ` above), `v' = F ẑ × v − k n + a²E² n_z ẑ` with
//!   `k = |v|² + a²E² n_z²`, and `F(r)` turns both about the spin axis. There is no `1/sin²θ`
//!   anywhere: a ray through the axis (`L = 0`) passes straight through. On the ray `|v|² = Q +
//!   L² + a²E² n_z²`, so `k = Q + L² + 2a²E² n_z²`, which is what is integrated: it keeps the
//!   constraints below as an invariant set as `|v|² + a²E² n_z²` does (the residuals of `|v|²`,
//!   `n · v` and `|n|²` drive one another and nothing else), and its series costs one product
//!   where `|v|²`'s cost three.
//!
//! The chart is the hole's outgoing Kerr–Schild chart ([`crate::metric::SpinTwin`]'s
//! documentation): `x + iy = (r − ia)(n_x + i n_y)`, `z = r n_z`, `dφ̃ = dφ − a/Δ dr`,
//! `dt̃ = dt − (r² + a² − Δ)/Δ dr`. With `r' = dr/dλ_M`, `G = (P − r')/Δ`, the rotation rate is
//! `F = a(G − E)` and `dt̃/dλ_M = P + (2Mr − Q_e²) G + a(L − aE sin²θ)`. `G` is regular on the
//! past horizon that backward rays cross (there `r' = P`): where `r'` has the sign of `P` it is
//! computed as `K/(P + r')` (equal, since `P² − r'² = ΔK`), elsewhere as `(P − r')/Δ`; in `u`,
//! `G = K u²/(A − u')` or `(A + u')/D`. The chart's radial momentum is `p_r = p · n = E − G`.
//!
//! The state is `(u, u', n, v)`: eight numbers, as the 4-D tracer's, with a right-hand side of
//! about 40 flops and one division. The chart's time is not integrated: a hole is stationary, and
//! the time of a state here is the start's. Nothing is re-projected onto the constraints
//! `u'² = U(u)`, `|n| = 1`, `n · v = 0`, `|v|² = Q + L² + a²E² n_z²`: the steps' truncation
//! control keeps them (the tests measure how well).
//!
//! **Steps.** The right-hand side is polynomial in `(u, u', n, v)` but for the one quotient in
//! `G`, so the adaptive tracer takes Taylor steps: the series of the solution about the step's
//! start follows from recurrences ([`Recurrence`]; Jorba & Zou 2005, "A software package for
//! the numerical integration of ODEs by means of high-order Taylor methods", Exp. Math. 14),
//! its last two terms set the step's length ([`MinoTracer::taylor_step`]), and the polynomial
//! is the ray anywhere inside the step, as accurate there as at the end. In `(u, n)` even a
//! straight line is a harmonic oscillation (`u = sin(bλ)/b`-like), which a series resolves
//! in steps of a good part of a radian where Dormand–Prince 5(4) took a tenth.

use crate::geodesic::taylor::{self, product, product_without_first, square_from};
use crate::geodesic::{Failure, Fate, Integrator, Interpolant, RayStep, RayTracer, State, Trace, TraceSettings, Visit};
use crate::metric::{KerrNewman, KerrSchild};
use crate::tensor::{Covector4, Vector4};

/// A hole's parameters and a ray's constants of motion (see the module documentation).
#[derive(Clone, Copy, Debug, PartialEq)]
struct Constants {
    mass: f64,
    spin: f64,
    /// `Q_e²`, the charge squared.
    charge2: f64,
    /// `E = −p_t`.
    energy: f64,
    /// `L = p_φ`.
    axial: f64,
    /// `K = Q + (L − aE)²`.
    carter_k: f64,
    /// `b = a(aE − L)`.
    b: f64,
    /// `c = a² + Q_e²`.
    c: f64,
    /// `a²E²`.
    a2e2: f64,
    /// `Q + L²`: `k = Q + L² + 2a²E² n_z²`.
    sphere: f64,
}

impl Constants {
    /// Whether `G` is taken as `K u²/(A − u')` at `u'` and `A = E + b u²` (where `r'` has the
    /// sign of `P`, as on the past horizon that backward rays cross), not as `(A + u')/D`.
    #[inline]
    fn g_by_quotient_of_k(w: f64, big_a: f64) -> bool {
        big_a * w < 0.0
    }

    /// `G = (P − r')/Δ` from `u`, `u'` and `A = E + b u²`, regular on the past horizon.
    #[inline]
    fn g(&self, u: f64, w: f64, big_a: f64) -> f64 {
        if Self::g_by_quotient_of_k(w, big_a) {
            self.carter_k * u * u / (big_a - w)
        } else {
            (big_a + w) / (1.0 + u * (self.c * u - 2.0 * self.mass))
        }
    }

    /// The right-hand side `dy/dλ_M` of the state `y = (u, u', n, v)`.
    #[inline]
    fn rhs(&self, y: &[f64; 8]) -> [f64; 8] {
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
    fn point(&self, u: f64, n: [f64; 3]) -> [f64; 3] {
        let r = 1.0 / u;
        [r * n[0] + self.spin * n[1], r * n[1] - self.spin * n[0], r * n[2]]
    }

    /// The chart velocity `d(x, y, z)/dλ_M` of the state `y` whose derivative is `dy`.
    #[inline]
    fn velocity(&self, y: &[f64; 8], dy: &[f64; 8]) -> [f64; 3] {
        let r = 1.0 / y[0];
        let dr = -dy[0] * r * r;
        let a = self.spin;
        [dr * y[2] + r * dy[2] + a * dy[3], dr * y[3] + r * dy[3] - a * dy[2], dr * y[4] + r * dy[4]]
    }

    /// The chart velocity `dx^μ/dλ` (affine) of the state `y`, time first.
    fn four_velocity(&self, y: &[f64; 8]) -> Vector4 {
        let dy = self.rhs(y);
        let [u, w, _, _, n2, ..] = *y;
        let (r, a, e) = (1.0 / u, self.spin, self.energy);
        let big_a = e + self.b * u * u;
        let g = self.g(u, w, big_a);
        let sin2 = y[2] * y[2] + y[3] * y[3];
        let dt = big_a * r * r + (2.0 * self.mass * r - self.charge2) * g + a * (self.axial - a * e * sin2);
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
    fn momentum(&self, y: &[f64; 8]) -> (Covector4, f64) {
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
fn from_chart(hole: &KerrNewman, start: &State) -> (Constants, [f64; 8]) {
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

/// Order of the Taylor series a step takes (coefficients `0..=ORDER`). Jorba & Zou's optimum
/// is about `−ln(tol)/2`, 8 at the renderer's tolerance of 10⁻⁷, but the steps are also capped
/// (`max_step_fraction` of [`MinoTracer::step_scale`]), and a higher order lets more of them
/// reach the cap, until the extra coefficients cost more than the steps they save (the orders
/// measured against one another: docs/perf-journal.md, session 35).
const ORDER: usize = 10;

/// `1/(k + 1)`, the recurrence's divisors as factors.
const RECIPROCALS: [f64; ORDER] = {
    let mut r = [0.0; ORDER];
    let mut k = 0;
    while k < ORDER {
        r[k] = 1.0 / (k + 1) as f64;
        k += 1;
    }
    r
};

/// The Taylor coefficients of the state about a point: `series[i][k]` is the `k`-th of
/// component `i` of `y = (u, u', n, v)`.
type Series = [[f64; ORDER + 1]; 8];

/// The order-`k` coefficients of the state as one vector.
#[inline]
fn column(series: &Series, k: usize) -> [f64; 8] {
    std::array::from_fn(|i| series[i][k])
}

/// The recurrences of the Taylor coefficients about one point (automatic differentiation;
/// Jorba & Zou 2005, §2). Every right-hand side of the module documentation is built of sums
/// and Cauchy products of series, with one quotient, `G = num/den`, whose coefficients follow
/// from `G ∗ den = num` as `G_k = (num_k − Σ_{i≥1} den_i G_{k−i}) / den_0`. `G` is expanded by
/// the formula that [`Constants::g`] takes at the point (the other's denominator may vanish
/// there, on the past horizon); both are the same function, so their series are the same
/// wherever both exist. In either, `num` and `den` are linear in `1, u, u², u'`.
struct Recurrence {
    /// The state's series, filled order by order.
    y: Series,
    /// The series of `u²`, `u³`, `den`, `G`, `F = a(G − E)` and `k = Q + L² + 2a²E² n_z²`, to
    /// order `ORDER − 1`, all that the state's last order needs.
    u2: [f64; ORDER],
    u3: [f64; ORDER],
    den: [f64; ORDER],
    g: [f64; ORDER],
    f: [f64; ORDER],
    k: [f64; ORDER],
    /// `u'' = α u + β u² + γ u³`.
    radial: [f64; 3],
    /// `num` and `den` as the coefficients of `(1, u, u², u')`.
    num_of: [f64; 4],
    den_of: [f64; 4],
    /// `1/den₀`.
    inv_den: f64,
    spin: f64,
    energy: f64,
    a2e2: f64,
    sphere: f64,
}

impl Recurrence {
    /// The recurrence about `y` for the ray of `c`, its order 0 set.
    #[inline(always)]
    fn new(c: &Constants, y: &[f64; 8]) -> Self {
        let (m, e, kc, b) = (c.mass, c.energy, c.carter_k, c.b);
        let radial = [2.0 * b * e - kc, 3.0 * m * kc, 2.0 * b * b - 2.0 * c.c * kc];
        // G = K u²/(A − u') or (A + u')/D, with A = E + b u² and D = 1 − 2Mu + c u².
        let (num_of, den_of) = if Constants::g_by_quotient_of_k(y[1], e + b * y[0] * y[0]) {
            ([0.0, 0.0, kc, 0.0], [e, 0.0, b, -1.0])
        } else {
            ([e, 0.0, b, 1.0], [1.0, -2.0 * m, c.c, 0.0])
        };
        let mut r = Recurrence {
            y: [[0.0; ORDER + 1]; 8],
            u2: [0.0; ORDER],
            u3: [0.0; ORDER],
            den: [0.0; ORDER],
            g: [0.0; ORDER],
            f: [0.0; ORDER],
            k: [0.0; ORDER],
            radial,
            num_of,
            den_of,
            inv_den: 0.0,
            spin: c.spin,
            energy: e,
            a2e2: c.a2e2,
            sphere: c.sphere,
        };
        for i in 0..8 {
            r.y[i][0] = y[i];
        }
        r
    }

    /// The state's coefficients of order `K + 1` from those up to `K`.
    #[inline(always)]
    fn next<const K: usize>(&mut self) {
        let [u, w, n0, n1, n2, v0, v1, v2] = &mut self.y;
        let one = if K == 0 { 1.0 } else { 0.0 };
        self.u2[K] = square_from::<0, K>(&u[..]);
        self.u3[K] = product::<K>(&self.u2, &u[..]);
        let terms = [one, u[K], self.u2[K], w[K]];
        let linear = |of: &[f64; 4]| of[0] * terms[0] + of[1] * terms[1] + of[2] * terms[2] + of[3] * terms[3];
        self.den[K] = linear(&self.den_of);
        if K == 0 {
            self.inv_den = 1.0 / self.den[0];
        }
        self.g[K] = (linear(&self.num_of) - product_without_first::<K>(&self.den, &self.g)) * self.inv_den;
        self.f[K] = self.spin * (self.g[K] - self.energy * one);
        self.k[K] = self.sphere * one + 2.0 * self.a2e2 * square_from::<0, K>(&n2[..]);
        let (f, k, r) = (&self.f, &self.k, RECIPROCALS[K]);
        let [alpha, beta, gamma] = self.radial;
        u[K + 1] = w[K] * r;
        w[K + 1] = (alpha * u[K] + beta * self.u2[K] + gamma * self.u3[K]) * r;
        n0[K + 1] = (v0[K] - product::<K>(f, &n1[..])) * r;
        n1[K + 1] = (v1[K] + product::<K>(f, &n0[..])) * r;
        n2[K + 1] = v2[K] * r;
        v0[K + 1] = -(product::<K>(f, &v1[..]) + product::<K>(k, &n0[..])) * r;
        v1[K + 1] = (product::<K>(f, &v0[..]) - product::<K>(k, &n1[..])) * r;
        v2[K + 1] = (self.a2e2 * n2[K] - product::<K>(k, &n2[..])) * r;
    }
}

impl Constants {
    /// The Taylor series of the solution through `y` ([`Recurrence`]).
    fn series(&self, y: &[f64; 8]) -> Series {
        const _: () = assert!(ORDER == 10, "the recurrence is unrolled for this order");
        let mut r = Recurrence::new(self, y);
        r.next::<0>();
        r.next::<1>();
        r.next::<2>();
        r.next::<3>();
        r.next::<4>();
        r.next::<5>();
        r.next::<6>();
        r.next::<7>();
        r.next::<8>();
        r.next::<9>();
        r.y
    }
}

/// How a step carries the ray inside it.
#[derive(Clone, Copy, Debug)]
enum Dense {
    /// The Taylor polynomial of the adaptive stepper, over `h` of Mino time; `end` is its value
    /// at `h`.
    Taylor { series: Series, h: f64, end: [f64; 8] },
    /// RK4's Hermite interpolant.
    Rk4(Interpolant<8>),
}

impl Dense {
    /// The first `N` components of the state at fraction `θ` of the step.
    #[inline]
    fn head<const N: usize>(&self, theta: f64) -> [f64; N] {
        match self {
            Dense::Taylor { series, h, .. } => std::array::from_fn(|i| taylor::value(&series[i], theta * h)),
            Dense::Rk4(interpolant) => interpolant.dense_head::<N>(theta),
        }
    }

    /// `u` and `n` at fraction `θ` of the step: all that places a point.
    #[inline]
    fn position(&self, theta: f64) -> (f64, [f64; 3]) {
        match self {
            Dense::Taylor { series, h, .. } => {
                let t = theta * h;
                (taylor::value(&series[0], t), std::array::from_fn(|i| taylor::value(&series[2 + i], t)))
            }
            Dense::Rk4(interpolant) => {
                let [u, _, n0, n1, n2] = interpolant.dense_head::<5>(theta);
                (u, [n0, n1, n2])
            }
        }
    }

    fn end(&self) -> [f64; 8] {
        match self {
            Dense::Taylor { end, .. } => *end,
            Dense::Rk4(interpolant) => interpolant.y1(),
        }
    }
}

/// One accepted Mino step, with dense output for the ray anywhere inside it.
#[derive(Clone, Copy, Debug)]
pub struct MinoStep {
    constants: Constants,
    /// The chart time of every state (the start's).
    time: f64,
    dense: Dense,
}

impl RayStep for MinoStep {
    #[inline]
    fn position_at(&self, theta: f64) -> Vector4 {
        let (u, n) = self.dense.position(theta);
        let [x, y, z] = self.constants.point(u, n);
        [self.time, x, y, z]
    }

    fn end_position(&self) -> Vector4 {
        let y = self.dense.end();
        let [x, p, z] = self.constants.point(y[0], [y[2], y[3], y[4]]);
        [self.time, x, p, z]
    }

    fn at(&self, theta: f64) -> State {
        let y = self.dense.head::<8>(theta);
        let [x, py, z] = self.constants.point(y[0], [y[2], y[3], y[4]]);
        State { x: [self.time, x, py, z], p: self.constants.momentum(&y).0 }
    }
}

/// Traces one ray about a hole of Kerr's family in Mino time (see the module documentation),
/// with the 4-D tracer's settings: Taylor steps ([`MinoTracer::taylor_step`]) whose truncation
/// is held to the same relative tolerance on the chart position and velocity as the 4-D
/// tracer's error control, steps at most `max_step_fraction` of the step scale
/// ([`MinoTracer::step_scale`]), the same escape radius (in the spheroidal radius, as the chart's
/// [`crate::metric::Metric::radius`]) and the same horizon. RK4 takes Mino steps of the affine
/// length `step` as it is at the ray's start.
#[derive(Clone, Copy, Debug)]
pub struct MinoTracer {
    constants: Constants,
    settings: TraceSettings,
    /// `1/r₊`: a ray with `u` beyond it is inside the horizon.
    horizon_u: f64,
    time: f64,
    y: [f64; 8],
    /// RK4's `dy/dλ_M` at `y` (its next step's first stage; unused by Taylor steps).
    dy: [f64; 8],
    /// RK4's fixed Mino step.
    next: f64,
    steps: u32,
}

impl MinoTracer {
    /// The tracer of the ray from `start`, a state of `hole`'s chart.
    pub fn new(hole: &KerrNewman, start: State, settings: TraceSettings) -> Self {
        let horizon_u = 1.0 / hole.horizon_radius();
        let (constants, y) = from_chart(hole, &start);
        let dy = constants.rhs(&y);
        let next = match settings.integrator {
            Integrator::Rk4 { step } => {
                let r = 1.0 / y[0];
                step / (r * r + hole.spin * hole.spin * y[4] * y[4])
            }
            Integrator::Adaptive { .. } => 0.0,
        };
        Self { constants, settings, horizon_u, time: start.x[0], y, dy, next, steps: 0 }
    }

    /// The ray's state now.
    pub fn state(&self) -> State {
        self.state_and_hamiltonian().0
    }

    /// The ray's state now, and its Hamiltonian (both from its chart momentum).
    fn state_and_hamiltonian(&self) -> (State, f64) {
        let [x, y, z] = self.constants.point(self.y[0], [self.y[2], self.y[3], self.y[4]]);
        let (p, h) = self.constants.momentum(&self.y);
        (State { x: [self.time, x, y, z], p }, h)
    }

    /// The Mino step over which the ray's path changes: the time in which `n` turns a radian,
    /// `u` climbs by `1/M` inwards, or falls to 0 outwards (the pole of `r` at infinity, which no
    /// step may pass).
    fn step_scale(&self) -> f64 {
        let [u, w, _, _, _, v0, v1, v2] = self.y;
        let turn = (v0 * v0 + v1 * v1 + v2 * v2).sqrt();
        let climb = if w < 0.0 { -w / u } else { w * self.constants.mass };
        1.0 / turn.max(climb)
    }

    /// Scaled norm of an error `e` of the state over a step `y0 → y1`: the chart position's
    /// error (radial `δr = δu/u²` and transverse `r |δn|`) relative to the distance from the
    /// centre plus the mass, as the 4-D tracer's, and the chart velocity's (`∝ (u', u v)`)
    /// relative to its size. Linear in `e` (its weights are the states'), so a term `cₖhᵏ` of
    /// the series has the norm `hᵏ` times its coefficients'.
    fn error_norm(&self, y0: &[f64; 8], y1: &[f64; 8], e: &[f64; 8], rtol: f64) -> f64 {
        let u = y1[0];
        let far = 1.0 / y0[0].min(y1[0]);
        let dn2 = e[2] * e[2] + e[3] * e[3] + e[4] * e[4];
        let dr = e[0] / (u * u);
        let pos = (dr * dr + dn2 / (u * u)).sqrt() / (rtol * (self.constants.mass + far));
        let speed2 = |y: &[f64; 8]| y[1] * y[1] + u * u * (y[5] * y[5] + y[6] * y[6] + y[7] * y[7]);
        let dv2 = e[1] * e[1] + u * u * (e[5] * e[5] + e[6] * e[6] + e[7] * e[7]);
        let vel = (dv2 / speed2(y0).max(speed2(y1))).sqrt() / rtol;
        pos.max(vel)
    }

    /// Advances by one accepted step.
    fn step(&mut self) -> Result<MinoStep, Failure> {
        if self.steps >= self.settings.max_steps {
            return Err(Failure::OutOfSteps);
        }
        let constants = self.constants;
        let scale = self.step_scale();
        let cap = self.settings.max_step_fraction * scale;
        let dense = match self.settings.integrator {
            Integrator::Rk4 { .. } => {
                let f = |_t: f64, y: &[f64; 8]| constants.rhs(y);
                let (step, _) =
                    Interpolant::step(self.settings.integrator, &f, 0.0, &self.y, &self.dy, self.next.min(cap));
                self.dy = step.end_derivative();
                Dense::Rk4(step)
            }
            Integrator::Adaptive { rtol } => self.taylor_step(self.escape_cap(cap), scale, rtol)?,
        };
        // `dy` is RK4's (Taylor steps leave it as it was at the start).
        let y1 = dense.end();
        if !(y1[0] > 0.0 && y1.iter().chain(self.dy.iter()).all(|v| v.is_finite())) {
            return Err(Failure::NonFinite);
        }
        self.y = y1;
        self.steps += 1;
        Ok(MinoStep { constants, time: self.time, dense })
    }

    /// The cap `cap` of a Taylor step, lengthened for an outgoing ray (`u' < 0`) inside the
    /// escape radius to the Mino time in which `u`, at constant `u'` (as it nearly is far out:
    /// `u'' = U'(u)/2 = O(u)`), would fall to half its value at the escape radius (`r` twice
    /// that radius), within `max_step_fraction` of a turning time `1/|v|`. The step scale's
    /// fall to the pole of `r` (the time `u/|u'|`) would make each step at most double `r` on
    /// the way out, which with a distant escape radius (a camera far away sets it) is most of a
    /// ray's steps; a Taylor step cannot pass the pole either way (it is halved while its end
    /// has `u ≤ 0`), and its error control still bounds it.
    fn escape_cap(&self, cap: f64) -> f64 {
        let [u, w, _, _, _, v0, v1, v2] = self.y;
        let escape_u = 1.0 / self.settings.escape_radius;
        if !(w < 0.0 && u > escape_u) {
            return cap;
        }
        let longest = self.settings.max_step_fraction / (v0 * v0 + v1 * v1 + v2 * v2).sqrt();
        if cap >= longest {
            // The turning time binds already (the cap is the least of it and the pole's time).
            return cap;
        }
        // At constant `u'` the time to the target `u − target` over `−u'`. Far out, though,
        // `u'' = −ω² u + O(u²)` with ω² = Q + L² − a²E² (the radial quartic's linear term): `u`
        // oscillates harmonically (in flat space a straight line is u = cos(bλ)/b) and reaches 0
        // at the phase `atan(ω u/(−u'))`, sooner than the line, whose estimate would end each
        // step past the pole, to be halved (so `r` only doubled a step).
        let linear = (u - 0.5 * escape_u) / -w;
        let omega2 = self.constants.sphere - self.constants.a2e2;
        let to_twice_escape = if omega2 > 0.0 {
            let omega = omega2.sqrt();
            (omega * linear).atan() / omega
        } else {
            linear
        };
        cap.max(to_twice_escape.min(longest))
    }

    /// The Taylor step from the current state, at most `cap` long (one step scale where the cap
    /// is infinite): as long as the last two terms of the series, `c₉h⁹` and `c₁₀h¹⁰`, stay
    /// within the tolerance in the error norm ([`MinoTracer::error_norm`], linear in the error,
    /// so each bounds `h` by a root; Jorba & Zou 2005, §3.2.1; the next term, the truncation,
    /// is smaller by about the step over the series' radius of convergence), and halved while
    /// its end is past infinity (`u ≤ 0`, which a polynomial in `u` may reach where `r` does
    /// not).
    fn taylor_step(&self, cap: f64, scale: f64, rtol: f64) -> Result<Dense, Failure> {
        let longest = if cap.is_finite() { cap } else { scale };
        let series = self.constants.series(&self.y);
        let bound = |k: usize| {
            let norm = self.error_norm(&self.y, &self.y, &column(&series, k), rtol);
            (1.0 / (norm * longest.powi(k as i32))).min(1.0)
        };
        let fraction = taylor::shorter_root::<{ ORDER as i32 - 1 }, { ORDER as i32 }>(bound(ORDER - 1), bound(ORDER));
        let mut h = longest * fraction;
        loop {
            let end = std::array::from_fn(|i| taylor::value(&series[i], h));
            if end[0] > 0.0 {
                return Ok(Dense::Taylor { series, h, end });
            }
            if end[0].is_nan() {
                return Err(Failure::NonFinite);
            }
            h *= 0.5;
            if !(h > 1e-14 * longest) {
                return Err(Failure::StepUnderflow);
            }
        }
    }

    /// The fate of the ray at its current point, if it has ended: inside the horizon, or past the
    /// escape radius with `r` growing (`u' < 0`), leaving along its chart velocity there.
    fn ended(&self) -> Option<Fate> {
        let [u, w, ..] = self.y;
        if u >= self.horizon_u {
            return Some(Fate::Captured);
        }
        if u * self.settings.escape_radius < 1.0 && w < 0.0 {
            let d = self.constants.velocity(&self.y, &self.constants.rhs(&self.y));
            return Some(Fate::Escaped { direction: crate::tensor::normalize3(&d) });
        }
        None
    }
}

impl RayTracer for MinoTracer {
    type Step = MinoStep;

    /// Traces the ray to its end, showing every accepted step to `visit`; the trace's largest
    /// `|H|` is that of the chart momentum at the step ends (or at the start and end).
    fn run(mut self, mut visit: impl FnMut(&MinoStep) -> Visit) -> Trace {
        let mut max_h: f64 = self.constants.momentum(&self.y).1.abs();
        let fate = loop {
            if let Some(fate) = self.ended() {
                break fate;
            }
            // Seen where it was returned: a step (its series) is too large to move for nothing.
            match &self.step() {
                Ok(step) => {
                    if self.settings.check_every_step {
                        max_h = max_h.max(self.constants.momentum(&self.y).1.abs());
                    }
                    if visit(step) == Visit::Stop {
                        break Fate::Stopped;
                    }
                }
                Err(failure) => break Fate::Failed(*failure),
            }
        };
        let (end, end_h) = self.state_and_hamiltonian();
        Trace { fate, steps: self.steps, max_abs_hamiltonian: max_h.max(end_h.abs()), end }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geodesic::HamiltonianTracer;
    use crate::metric::Metric;
    use crate::observer::Tetrad;
    use crate::tensor::{norm3, sub3};

    /// The backward ray that a camera at rest (the local observer) at `at` sees along `dir`.
    fn camera_ray(hole: &KerrNewman, at: [f64; 3], dir: [f64; 3]) -> State {
        let x = [0.0, at[0], at[1], at[2]];
        let frame = Tetrad::local_observer(hole, &x).expect("a camera outside the horizon");
        State { x, p: frame.backward_momentum(&hole.metric(&x), crate::tensor::normalize3(&dir), 1.0) }
    }

    fn settings(rtol: f64, escape_radius: f64) -> TraceSettings {
        TraceSettings {
            integrator: Integrator::Adaptive { rtol },
            escape_radius,
            max_step_fraction: 0.5,
            max_steps: 100_000,
            check_every_step: true,
        }
    }

    /// Without `check_every_step` the trace is the same, and its `|H|` is the larger of the
    /// start's and the end's; with it, the largest over the step ends, which the steps between
    /// can raise (a ray that swings round the hole at a loose tolerance).
    #[test]
    fn the_hamiltonian_is_checked_at_every_step_only_when_asked() {
        let hole = KerrNewman::new(1.0, 0.9, 0.0);
        let start = camera_ray(&hole, [-40.0, 0.0, 3.0], [1.0, 0.13, -0.05]);
        let each = MinoTracer::new(&hole, start, settings(1e-5, 1e3)).run(|_| Visit::Continue);
        let ends_only = MinoTracer::new(&hole, start, TraceSettings { check_every_step: false, ..settings(1e-5, 1e3) })
            .run(|_| Visit::Continue);
        assert_eq!((each.fate, each.steps, each.end), (ends_only.fate, ends_only.steps, ends_only.end));
        let h = |s: &State| hole.hamiltonian(&s.x, &s.p).abs();
        let ends = h(&start).max(h(&ends_only.end));
        assert!(
            (ends_only.max_abs_hamiltonian - ends).abs() <= 1e-2 * ends,
            "{} vs {ends}",
            ends_only.max_abs_hamiltonian
        );
        assert!(each.max_abs_hamiltonian > 1.5 * ends, "{} vs {ends}", each.max_abs_hamiltonian);
    }

    /// What a scene sees of a ray: its crossings of the equatorial plane outside the horizon
    /// (point and momentum, found on the dense output by bisection) and its fate.
    struct Seen {
        crossings: Vec<State>,
        fate: Fate,
    }

    /// Crossings inside the horizon are left out: a ray is captured at the end of the first step
    /// that ends inside, and how far inside that step reaches is the stepper's own (a Taylor
    /// step of the Mino tracer may cross the plane there where the 4-D tracer's shorter last
    /// step stops before it); nothing outside sees them.
    fn seen<T: RayTracer>(hole: &KerrNewman, tracer: T) -> Seen {
        let mut crossings = Vec::new();
        let trace = tracer.run(|step| {
            let z = |theta: f64| step.position_at(theta)[3];
            let (mut lo, mut hi) = (0.0, 1.0);
            if z(lo) * z(hi) < 0.0 {
                for _ in 0..60 {
                    let mid = 0.5 * (lo + hi);
                    if z(mid) * z(lo) > 0.0 {
                        lo = mid;
                    } else {
                        hi = mid;
                    }
                }
                let crossing = step.at(0.5 * (lo + hi));
                if hole.radial_coordinate(&crossing.x) > hole.horizon_radius() {
                    crossings.push(crossing);
                }
            }
            Visit::Continue
        });
        Seen { crossings, fate: trace.fate }
    }

    /// The largest differences between two tracings of a ray: of crossing points (relative to
    /// the distance from the centre), of crossing momenta (relative to the energy), of escape
    /// directions; `None` where the fates or the numbers of crossings differ.
    fn differences(a: &Seen, b: &Seen) -> Option<[f64; 3]> {
        if a.crossings.len() != b.crossings.len() {
            return None;
        }
        let mut d = [0.0f64; 3];
        for (s, t) in a.crossings.iter().zip(&b.crossings) {
            let (xs, xt) = (crate::tensor::spatial(&s.x), crate::tensor::spatial(&t.x));
            d[0] = d[0].max(norm3(&sub3(&xs, &xt)) / norm3(&xt));
            let dp = (0..4).map(|i| (s.p[i] - t.p[i]).powi(2)).sum::<f64>().sqrt();
            d[1] = d[1].max(dp / t.p[0].abs());
        }
        match (a.fate, b.fate) {
            (Fate::Escaped { direction: u }, Fate::Escaped { direction: v }) => d[2] = norm3(&sub3(&u, &v)),
            (Fate::Captured, Fate::Captured) => {}
            _ => return None,
        }
        Some(d)
    }

    /// Rays of a camera 40 M from the hole at inclination 80°, over its field of view, and
    /// rays that skim the spin axis or run through it.
    fn rays(hole: &KerrNewman) -> Vec<State> {
        let m = hole.mass;
        let (si, ci) = 80f64.to_radians().sin_cos();
        let at = [40.0 * m * si, 0.0, 40.0 * m * ci];
        let mut rays = Vec::new();
        for i in -4..=4 {
            for j in -4..=4 {
                let (a, b) = (0.07 * f64::from(i), 0.07 * f64::from(j));
                // Towards the centre, offset sideways (y) and up.
                let dir = [-si + b * ci, a, -ci - b * si];
                rays.push(camera_ray(hole, at, dir));
            }
        }
        // In the plane of the axis, over the pole (L = 0), and passing about 10⁻⁶ M from it.
        for off in [0.0, 3e-8] {
            for tilt in [0.2, 0.26, 0.35] {
                rays.push(camera_ray(hole, [30.0 * m, 0.0, 0.0], [-1.0, off, tilt]));
            }
        }
        rays
    }

    /// Equatorial rays a relative `1e-5` inside and outside the edge of the shadow on both
    /// sides (prograde and retrograde), found by bisection on the ray's fate: they wind round
    /// the photon orbit before they fall in or leave.
    fn near_photon_orbit(hole: &KerrNewman) -> Vec<State> {
        let at = [40.0 * hole.mass, 0.0, 0.0];
        let aim = |t: f64| camera_ray(hole, at, [-1.0, t, 0.0]);
        let captured = |t: f64| {
            matches!(
                MinoTracer::new(hole, aim(t), settings(1e-11, 1e3 * hole.mass)).run(|_| Visit::Continue).fate,
                Fate::Captured
            )
        };
        let mut rays = Vec::new();
        for side in [-1.0, 1.0] {
            let (mut inside, mut outside) = (0.0, side * 0.5);
            for _ in 0..50 {
                let mid = 0.5 * (inside + outside);
                if captured(mid) {
                    inside = mid;
                } else {
                    outside = mid;
                }
            }
            rays.extend([aim(inside * (1.0 - 1e-5)), aim(outside * (1.0 + 1e-5))]);
        }
        rays
    }

    /// A ray from a camera 10⁶ M away that passes the hole and escapes to twice that distance
    /// leaves in a few strides past the hole, not in steps that each double `r` (16 of them from
    /// 40 M to 2 × 10⁶ M; aimed at constant `u'`, each stride ended past the pole and was halved,
    /// which doubled `r` 4 times more), and along the 4-D tracer's direction (to 10⁻⁸ at
    /// tolerance 10⁻¹⁰).
    #[test]
    fn escaping_rays_stride_to_a_far_escape_radius() {
        let hole = KerrNewman::new(1.0, 0.9, 0.0);
        let (d, inclination) = (1e6, 80f64.to_radians());
        let at = [d * inclination.sin(), 0.0, d * inclination.cos()];
        for b in [8.0, 10.0, 15.0] {
            let start = camera_ray(&hole, at, [-inclination.sin(), b / d, -inclination.cos()]);
            let mut outside = 0;
            MinoTracer::new(&hole, start, settings(1e-7, 2.0 * d)).run(|step| {
                let p = step.end_position();
                outside += usize::from(p[1] * p[1] + p[2] * p[2] + p[3] * p[3] > 1600.0);
                Visit::Continue
            });
            // The first step comes in from 10⁶ M; beyond 40 M on the way out, at most 3 (at the
            // renderer's tolerance).
            assert!(outside <= 4, "b = {b}: {outside} steps end beyond 40 M");
            let s = settings(1e-10, 2.0 * d);
            let mino = MinoTracer::new(&hole, start, s).run(|_| Visit::Continue);
            let ham = HamiltonianTracer::new(&hole, start, s).run(|_| Visit::Continue);
            let (Fate::Escaped { direction: a }, Fate::Escaped { direction: b4 }) = (mino.fate, ham.fate) else {
                panic!("b = {b}: {:?} vs {:?}", mino.fate, ham.fate);
            };
            let miss = (0..3).map(|i| (a[i] - b4[i]).abs()).fold(0.0, f64::max);
            assert!(miss < 1e-8, "b = {b}: directions differ by {miss}");
        }
    }

    #[test]
    fn agrees_with_the_four_d_tracer() {
        for hole in [
            KerrNewman::new(1.0, 0.9, 0.0),
            KerrNewman::new(1.0, 0.998, 0.0),
            KerrNewman::new(1.0, -0.6, 0.0),
            KerrNewman::new(1.0, 0.0, 0.0),
            KerrNewman::new(0.5, 0.3, 0.25),
        ] {
            let mut worst = [0.0f64; 3];
            for (k, start) in rays(&hole).into_iter().enumerate() {
                let s = settings(1e-10, 1e4 * hole.mass);
                let mino = seen(&hole, MinoTracer::new(&hole, start, s));
                let ham = seen(&hole, HamiltonianTracer::new(&hole, start, s));
                let d = differences(&mino, &ham).unwrap_or_else(|| {
                    panic!(
                        "{hole:?} ray {k}: {:?} {} vs {:?} {}",
                        mino.fate,
                        mino.crossings.len(),
                        ham.fate,
                        ham.crossings.len()
                    )
                });
                for i in 0..3 {
                    worst[i] = worst[i].max(d[i]);
                }
            }
            // Points to 10⁻⁶ of their distance, momenta and directions to 10⁻⁷ (worst seen with
            // Taylor steps: 3.2 × 10⁻⁸, 1.1 × 10⁻⁹, 1.4 × 10⁻⁸; with Dormand–Prince 5(4), before
            // them: 1.1 × 10⁻⁷, 1.7 × 10⁻⁹, 1.4 × 10⁻⁸).
            assert!(worst[0] < 1e-6 && worst[1] < 1e-7 && worst[2] < 1e-7, "{hole:?}: {worst:?}");
            // Rays that wind about the photon orbit magnify every error: against the 4-D tracer at
            // 10⁻¹³ (whose own error there, at a = 0.998 M, is 6 × 10⁻⁷ in direction, where at
            // 10⁻¹¹ it is 10⁻⁴ and this tracer's 1.1 × 10⁻⁶) they end alike, at the same points.
            for (k, start) in near_photon_orbit(&hole).into_iter().enumerate() {
                let (s, reference) = (settings(1e-11, 1e4 * hole.mass), settings(1e-13, 1e4 * hole.mass));
                let (mino, ham) = (
                    seen(&hole, MinoTracer::new(&hole, start, s)),
                    seen(&hole, HamiltonianTracer::new(&hole, start, reference)),
                );
                let d = differences(&mino, &ham)
                    .unwrap_or_else(|| panic!("{hole:?} winding ray {k}: {:?} vs {:?}", mino.fate, ham.fate));
                assert!(d[0] < 3e-5 && d[2] < 3e-5, "{hole:?} winding ray {k}: {d:?}");
            }
        }
    }

    /// Along a ray, the chart momentum's `E = −p_t`, `L = x p_y − y p_x` and Carter's `K`
    /// (recovered from the chart state as at the start) stay those of the start, the momentum
    /// stays null (`|H|` below 10⁻⁹ of its squared components), and the radial equation `u'² =
    /// U(u)` holds, at the end and in the middle of every step (the Taylor polynomial is the
    /// dense output the renderer places points with): nothing is re-projected, and the drift
    /// stays at the tolerance's level.
    #[test]
    fn constants_of_motion_are_conserved() {
        for hole in [KerrNewman::new(1.0, 0.9, 0.0), KerrNewman::new(1.0, -0.998, 0.0), KerrNewman::new(0.5, 0.3, 0.25)]
        {
            for start in rays(&hole).into_iter().chain(near_photon_orbit(&hole)) {
                let (c0, _) = from_chart(&hole, &start);
                let mut tracer = MinoTracer::new(&hole, start, settings(1e-10, 1e3 * hole.mass));
                let scale = c0.carter_k.max(c0.energy * c0.energy);
                let mut worst = [0.0f64; 4];
                while tracer.ended().is_none() {
                    let Ok(step) = tracer.step() else { panic!("{hole:?}: the ray failed") };
                    for theta in [0.5, 1.0] {
                        let (c, y) = from_chart(&hole, &step.at(theta));
                        let big_a = c.energy + c.b * y[0] * y[0];
                        let u_of =
                            big_a * big_a - (1.0 + y[0] * (c.c * y[0] - 2.0 * c.mass)) * c.carter_k * y[0] * y[0];
                        let drift = [
                            (c.energy - c0.energy).abs() / c0.energy.abs(),
                            (c.axial - c0.axial).abs() / scale.sqrt(),
                            (c.carter_k - c0.carter_k).abs() / scale,
                            (y[1] * y[1] - u_of).abs() / (c0.energy * c0.energy),
                        ];
                        for i in 0..4 {
                            worst[i] = worst[i].max(drift[i]);
                        }
                        let (p, h) = c0.momentum(&step.dense.head::<8>(theta));
                        let p2: f64 = p.iter().map(|c| c * c).sum();
                        assert!(h.abs() < 1e-9 * p2, "{hole:?}: not null at {theta}: H = {h}, |p|² = {p2}");
                    }
                    assert_eq!(step.dense.head::<8>(1.0), tracer.y, "the polynomial ends at the state");
                }
                assert!(worst.iter().all(|&d| d < 1e-7), "{hole:?}: drifts of E, L, K, U: {worst:?}");
            }
        }
    }

    /// The series' first coefficients are the right-hand side and half its derivative along
    /// the flow (by central differences), for rays of both formulas of `G`: falling in
    /// backwards (`A u' < 0`, across the past horizon) and on the way out.
    #[test]
    fn the_series_is_the_solutions() {
        let hole = KerrNewman::new(1.0, 0.9, 0.2);
        let mut branches = [false; 2];
        for start in rays(&hole) {
            let (c, y0) = from_chart(&hole, &start);
            let mut tracer = MinoTracer::new(&hole, start, settings(1e-8, 1e3));
            let mut y = y0;
            while tracer.ended().is_none() {
                branches[usize::from((c.energy + c.b * y[0] * y[0]) * y[1] < 0.0)] = true;
                let series = c.series(&y);
                let f = c.rhs(&y);
                let eps = 1e-6 / f.iter().map(|v| v.abs()).fold(0.0, f64::max);
                let shifted = |s: f64| c.rhs(&std::array::from_fn(|i| y[i] + s * eps * f[i]));
                let (ahead, behind) = (shifted(1.0), shifted(-1.0));
                for i in 0..8 {
                    let size = f.iter().map(|v| v.abs()).fold(y[i].abs(), f64::max);
                    assert!((series[i][1] - f[i]).abs() <= 1e-14 * size, "{i}: {} vs {}", series[i][1], f[i]);
                    let second = 0.25 * (ahead[i] - behind[i]) / eps;
                    assert!((series[i][2] - second).abs() <= 1e-6 * size, "{i}: {} vs {second}", series[i][2]);
                }
                if tracer.step().is_err() {
                    break;
                }
                y = tracer.y;
            }
        }
        assert_eq!(branches, [true, true], "both formulas of G");
    }

    /// RK4 (the poster's fixed steps) still traces the rays, through its Hermite interpolant:
    /// with a small step its escapes and crossings are the Taylor steps'.
    #[test]
    fn rk4_steps_trace_the_same_rays() {
        let hole = KerrNewman::new(1.0, 0.9, 0.0);
        for start in rays(&hole).into_iter().step_by(7) {
            let rk4 = TraceSettings { integrator: Integrator::Rk4 { step: 0.05 }, ..settings(1e-10, 1e3) };
            let (taylor, fixed) = (
                seen(&hole, MinoTracer::new(&hole, start, settings(1e-10, 1e3))),
                seen(&hole, MinoTracer::new(&hole, start, rk4)),
            );
            let d = differences(&fixed, &taylor).unwrap_or_else(|| panic!("{:?} vs {:?}", fixed.fate, taylor.fate));
            assert!(d.iter().all(|&d| d < 1e-4), "{d:?}");
        }
    }
}

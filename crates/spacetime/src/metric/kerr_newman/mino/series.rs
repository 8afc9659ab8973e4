//! The Taylor series of a Mino state about a point, from the recurrences of its coefficients
//! (Jorba & Zou 2005), and the dense output of a step: its Taylor polynomial, or RK4's Hermite
//! interpolant.

use super::motion::Constants;
use crate::geodesic::taylor::{self, product, product_without_first, square_from};
use crate::geodesic::Interpolant;

/// Order of the Taylor series a step takes (coefficients `0..=ORDER`). Jorba & Zou's optimum
/// is about `−ln(tol)/2`, 8 at the renderer's tolerance of 10⁻⁷, but the steps are also capped
/// (`max_step_fraction` of [`MinoTracer::step_scale`](super::MinoTracer::step_scale)), and a
/// higher order lets more of them reach the cap, until the extra coefficients cost more than the
/// steps they save (the orders
/// measured against one another: docs/perf-journal.md, session 35).
pub(super) const ORDER: usize = 10;

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
pub(super) type Series = [[f64; ORDER + 1]; 8];

/// The order-`k` coefficients of the state as one vector.
#[inline]
pub(super) fn column(series: &Series, k: usize) -> [f64; 8] {
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
    pub(super) fn series(&self, y: &[f64; 8]) -> Series {
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
pub(super) enum Dense {
    /// The Taylor polynomial of the adaptive stepper, over `h` of Mino time; `end` is its value
    /// at `h`.
    Taylor { series: Series, h: f64, end: [f64; 8] },
    /// RK4's Hermite interpolant.
    Rk4(Interpolant<8>),
}

impl Dense {
    /// The first `N` components of the state at fraction `θ` of the step.
    #[inline]
    pub(super) fn head<const N: usize>(&self, theta: f64) -> [f64; N] {
        match self {
            Dense::Taylor { series, h, .. } => std::array::from_fn(|i| taylor::value(&series[i], theta * h)),
            Dense::Rk4(interpolant) => interpolant.dense_head::<N>(theta),
        }
    }

    /// `u` and `n` at fraction `θ` of the step: all that places a point.
    #[inline]
    pub(super) fn position(&self, theta: f64) -> (f64, [f64; 3]) {
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

    /// The step's length in Mino time.
    pub(super) fn h(&self) -> f64 {
        match self {
            Dense::Taylor { h, .. } => *h,
            Dense::Rk4(interpolant) => interpolant.h(),
        }
    }

    pub(super) fn end(&self) -> [f64; 8] {
        match self {
            Dense::Taylor { end, .. } => *end,
            Dense::Rk4(interpolant) => interpolant.y1(),
        }
    }
}

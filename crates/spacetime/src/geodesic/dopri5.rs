//! Dormand–Prince 5(4) embedded Runge–Kutta pair with its 4th-order dense output
//! (Dormand & Prince 1980; Hairer, Nørsett & Wanner, "Solving ODEs I", §II.5–6, routine DOPRI5).
//!
//! Generic over the state size so the 4-D Hamiltonian system and the in-plane system share it.
//! The caller owns error norms and step-size control; this file only does one attempt.

const C2: f64 = 1.0 / 5.0;
const C3: f64 = 3.0 / 10.0;
const C4: f64 = 4.0 / 5.0;
const C5: f64 = 8.0 / 9.0;
const A21: f64 = 1.0 / 5.0;
const A31: f64 = 3.0 / 40.0;
const A32: f64 = 9.0 / 40.0;
const A41: f64 = 44.0 / 45.0;
const A42: f64 = -56.0 / 15.0;
const A43: f64 = 32.0 / 9.0;
const A51: f64 = 19372.0 / 6561.0;
const A52: f64 = -25360.0 / 2187.0;
const A53: f64 = 64448.0 / 6561.0;
const A54: f64 = -212.0 / 729.0;
const A61: f64 = 9017.0 / 3168.0;
const A62: f64 = -355.0 / 33.0;
const A63: f64 = 46732.0 / 5247.0;
const A64: f64 = 49.0 / 176.0;
const A65: f64 = -5103.0 / 18656.0;
const A71: f64 = 35.0 / 384.0;
const A73: f64 = 500.0 / 1113.0;
const A74: f64 = 125.0 / 192.0;
const A75: f64 = -2187.0 / 6784.0;
const A76: f64 = 11.0 / 84.0;
// Fifth-order weights minus fourth-order weights: the local error estimate.
const E1: f64 = 71.0 / 57600.0;
const E3: f64 = -71.0 / 16695.0;
const E4: f64 = 71.0 / 1920.0;
const E5: f64 = -17253.0 / 339200.0;
const E6: f64 = 22.0 / 525.0;
const E7: f64 = -1.0 / 40.0;
// Dense output coefficients (Hairer's CONTD5).
const D1: f64 = -12715105075.0 / 11282082432.0;
const D3: f64 = 87487479700.0 / 32700410799.0;
const D4: f64 = -10690763975.0 / 1880347072.0;
const D5: f64 = 701980252875.0 / 199316789632.0;
const D6: f64 = -1453857185.0 / 822651844.0;
const D7: f64 = 69997945.0 / 29380423.0;

/// One attempted step from `y0` at `t0` with size `h`; `k[0]` is `f(t0, y0)`, `k[6]` is `f` at the
/// end (first-same-as-last: the next step's `k[0]`).
#[derive(Clone, Copy, Debug)]
pub struct Attempt<const N: usize> {
    pub y0: [f64; N],
    pub y1: [f64; N],
    pub error: [f64; N],
    pub h: f64,
    k: [[f64; N]; 7],
}

/// `y + h Σ c k` over the `T` terms `(c, k)`. Always inlined, with the count of terms a
/// constant: taken out of line, the loop over a slice of terms ran one component at a time.
#[inline(always)]
fn combine<const N: usize, const T: usize>(y: &[f64; N], h: f64, terms: [(f64, &[f64; N]); T]) -> [f64; N] {
    let mut s = [0.0; N];
    for (c, k) in terms {
        for (s, k) in s.iter_mut().zip(k) {
            *s += c * k;
        }
    }
    std::array::from_fn(|i| y[i] + h * s[i])
}

/// Takes one Dormand–Prince step of size `h` (which may be negative).
#[inline]
pub fn attempt<const N: usize>(
    f: &impl Fn(f64, &[f64; N]) -> [f64; N],
    t0: f64,
    y0: &[f64; N],
    k1: &[f64; N],
    h: f64,
) -> Attempt<N> {
    let k2 = f(t0 + C2 * h, &combine(y0, h, [(A21, k1)]));
    let k3 = f(t0 + C3 * h, &combine(y0, h, [(A31, k1), (A32, &k2)]));
    let k4 = f(t0 + C4 * h, &combine(y0, h, [(A41, k1), (A42, &k2), (A43, &k3)]));
    let k5 = f(t0 + C5 * h, &combine(y0, h, [(A51, k1), (A52, &k2), (A53, &k3), (A54, &k4)]));
    let k6 = f(t0 + h, &combine(y0, h, [(A61, k1), (A62, &k2), (A63, &k3), (A64, &k4), (A65, &k5)]));
    let y1 = combine(y0, h, [(A71, k1), (A73, &k3), (A74, &k4), (A75, &k5), (A76, &k6)]);
    let k7 = f(t0 + h, &y1);
    let error =
        std::array::from_fn(|i| h * (E1 * k1[i] + E3 * k3[i] + E4 * k4[i] + E5 * k5[i] + E6 * k6[i] + E7 * k7[i]));
    Attempt { y0: *y0, y1, error, h, k: [*k1, k2, k3, k4, k5, k6, k7] }
}

impl<const N: usize> Attempt<N> {
    /// Derivative at the end of the step, the next step's first stage.
    pub fn end_derivative(&self) -> [f64; N] {
        self.k[6]
    }

    /// Continuous extension of order 4 at `θ ∈ [0, 1]` through the step.
    pub fn dense(&self, theta: f64) -> [f64; N] {
        std::array::from_fn(|i| self.dense_component(theta, i))
    }

    /// Component `i` of [`Attempt::dense`], for callers that need only one.
    #[inline]
    pub fn dense_component(&self, theta: f64, i: usize) -> f64 {
        let k = &self.k;
        let h = self.h;
        let t1 = 1.0 - theta;
        let ydiff = self.y1[i] - self.y0[i];
        let bspl = h * k[0][i] - ydiff;
        let r4 = ydiff - h * k[6][i] - bspl;
        let r5 = h * (D1 * k[0][i] + D3 * k[2][i] + D4 * k[3][i] + D5 * k[4][i] + D6 * k[5][i] + D7 * k[6][i]);
        self.y0[i] + theta * (ydiff + t1 * (bspl + theta * (r4 + t1 * r5)))
    }
}

/// Step-size factor for the next step from a scaled error norm (`≤ 1` accepted): the standard
/// `0.9 · err^(−1/5)` clamped to `[0.2, 5]` (Hairer et al. II.4).
#[inline]
pub fn step_factor(error_norm: f64) -> f64 {
    // Outside [3e-4, 3e3] the clamp decides; inside, a cheap fifth root is plenty for control.
    if error_norm < 0.9f64.powi(5) / 3125.0 {
        5.0
    } else if error_norm > 0.9f64.powi(5) * 3125.0 {
        0.2
    } else {
        (0.9 * inverse_fifth_root(error_norm)).clamp(0.2, 5.0)
    }
}

/// `x^(−1/5)` for positive normal `x`, to 1e-3 relative: the float's bits read as a scaled
/// logarithm give a first guess within 7.5 % (Blinn 1997, "Floating-point tricks"), which two
/// steps of Newton's method on `y⁻⁵ = x` refine (the error goes 7.5 % → 1.6 % → 9e-4). The
/// step-size factor is a heuristic that needs a few per cent at most; libm's `pow` costs more
/// than a whole in-plane step, and every further Newton step (a chain of dependent multiplies)
/// cost a tenth of one.
#[inline]
fn inverse_fifth_root(x: f64) -> f64 {
    // 6/5 of the bits of 1.0, minus a fifth of x's bits: in integers, since the conversions
    // to and from floating point and a division sat on every step's critical path.
    const SIX_FIFTHS_OF_ONE: u64 = (1023u64 << 52) / 5 * 6;
    let mut y = f64::from_bits(SIX_FIFTHS_OF_ONE - x.to_bits() / 5);
    for _ in 0..2 {
        y *= (6.0 - x * y.powi(5)) * 0.2;
    }
    y
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn fifth_order_on_the_exponential() {
        // y' = y: the global error of one step scales as h^6.
        let f = |_t: f64, y: &[f64; 1]| [y[0]];
        let err = |h: f64| (attempt(&f, 0.0, &[1.0], &[1.0], h).y1[0] - h.exp()).abs();
        let ratio = err(0.1) / err(0.05);
        assert!((ratio.log2() - 6.0).abs() < 0.3, "observed order {}", ratio.log2());
    }

    #[test]
    fn fifth_root_is_accurate_over_the_controlled_range() {
        // Log-spaced over 1e-4 … 1e4, past the clamps at 3e-4 and 3e3.
        for i in 0..=20_000 {
            let x = 10f64.powf(-4.0 + 8.0 * f64::from(i) / 20_000.0);
            let exact = x.powf(-0.2);
            assert!((inverse_fifth_root(x) / exact - 1.0).abs() < 1e-3, "x = {x}");
        }
    }

    #[test]
    fn dense_output_is_fourth_order_accurate_inside_the_step() {
        let f = |_t: f64, y: &[f64; 2]| [y[1], -y[0]];
        let h = 0.2;
        let a = attempt(&f, 0.0, &[0.0, 1.0], &[1.0, 0.0], h);
        for theta in [0.0, 0.25, 0.5, 0.9, 1.0] {
            let y = a.dense(theta);
            assert!((y[0] - (theta * h).sin()).abs() < 1e-7, "θ = {theta}");
        }
        assert_eq!(a.dense(1.0)[0], a.y1[0]);
    }
}

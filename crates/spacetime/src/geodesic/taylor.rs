//! Pieces shared by the Taylor-series steppers ([`crate::metric::schwarzschild::binet_taylor`]
//! for the Schwarzschild orbit, [`crate::metric::kerr_newman::mino`] for Kerr's family): the step
//! length from the last two coefficients
//! (Jorba & Zou 2005, "A software package for the numerical integration of ODEs by means of
//! high-order Taylor methods", Exp. Math. 14, §3.2.1), the Cauchy products `(a∗b)_N = Σ aᵢb_{N−i}`
//! of their recurrences (ibid. §2) and the evaluation of the polynomial. The products take
//! their order `N` as a constant, so that every sum is unrolled where a recurrence instantiates
//! them order by order.

/// `(a∗b)_N − a₀b_N = Σ aᵢb_{N−i}` over `0 < i ≤ N`, the newest `b` (`a₁b_{N−1}`) last.
#[inline(always)]
pub(crate) fn product_without_first<const N: usize>(a: &[f64], b: &[f64]) -> f64 {
    let mut sum = 0.0;
    for i in (1..N + 1).rev() {
        sum += a[i] * b[N - i];
    }
    sum
}

/// `(a∗b)_N = Σ aᵢb_{N−i}` over `0 ≤ i ≤ N`.
#[inline(always)]
pub(crate) fn product<const N: usize>(a: &[f64], b: &[f64]) -> f64 {
    product_without_first::<N>(a, b) + a[0] * b[N]
}

/// `(c∗c)_N` without its terms `cᵢc_{N−i}` of `i < FROM` or `N − i < FROM`, by its symmetry:
/// twice the products with `FROM ≤ i < N − i`, plus the middle square where `N` is even, the
/// newest (`c_FROM c_{N−FROM}`) last. `FROM = 0` is the whole square.
#[inline(always)]
pub(crate) fn square_from<const FROM: usize, const N: usize>(c: &[f64]) -> f64 {
    let mut sum = if N % 2 == 0 { 0.5 * c[N / 2] * c[N / 2] } else { 0.0 };
    for i in (FROM..N.div_ceil(2)).rev() {
        sum += c[i] * c[N - i];
    }
    2.0 * sum
}

/// The step `h ≤ 1` that keeps both `h^B ≤ before` and `h^L ≤ last` (bounds in `[0, 1]`, `B`
/// and `L = B + 1` the orders of the last two coefficients): which root is smaller is told by
/// integer powers, so only one root is taken.
#[inline]
pub(crate) fn shorter_root<const B: i32, const L: i32>(before: f64, last: f64) -> f64 {
    const { assert!(L == B + 1, "the last two orders") };
    if before.powi(L) < last.powi(B) {
        root::<B>(before)
    } else {
        root::<L>(last)
    }
}

/// `x^(1/N)` for `x ∈ [0, 1]` to within 2·10⁻³ relative, all a step length needs (the
/// truncation term grows as `hᴺ`, so its bound moves by `N` times that): the exponent divided
/// by `N` in the bits of `x` as a first guess, then one step of Halley's method for `yᴺ = x`,
/// which triples its digits. It stands in for libm's `powf`, which was a noticeable share of a
/// connection (docs/perf-journal.md).
fn root<const N: i32>(x: f64) -> f64 {
    if !(x > f64::MIN_POSITIVE) {
        return 0.0;
    }
    let one = 1.0f64.to_bits() as i64;
    let y = f64::from_bits(((x.to_bits() as i64 - one) / i64::from(N) + one) as u64);
    let (yn, n) = (y.powi(N), f64::from(N));
    y * ((n - 1.0) * yn + (n + 1.0) * x) / ((n + 1.0) * yn + (n - 1.0) * x)
}

/// A polynomial and its derivative at `h`.
#[inline]
pub(crate) fn value_and_slope<const N: usize>(c: &[f64; N], h: f64) -> (f64, f64) {
    (value(c, h), slope(c, h))
}

/// A polynomial at `h` by Horner's rule in `h²` on its even and odd coefficients apart,
/// `E(h²) + h O(h²)` (second-order Horner): two independent chains half as long as Horner's in
/// `h`, whose dependent multiply–adds, not their count, are what a step's points wait for
/// (measured with [`slope`]: docs/perf-journal.md, session 17).
#[inline]
pub(crate) fn value<const N: usize>(c: &[f64; N], h: f64) -> f64 {
    let z = h * h;
    let (mut even, mut odd) = (0.0, 0.0);
    for n in (0..N).rev() {
        if n % 2 == 0 {
            even = even * z + c[n];
        } else {
            odd = odd * z + c[n];
        }
    }
    even + h * odd
}

/// The derivative of a polynomial at `h`, as [`value`] evaluates it: `Σ n cₙ hⁿ⁻¹`, its even
/// and odd terms apart.
#[inline]
pub(crate) fn slope<const N: usize>(c: &[f64; N], h: f64) -> f64 {
    let z = h * h;
    let (mut even, mut odd) = (0.0, 0.0);
    for n in (1..N).rev() {
        let term = n as f64 * c[n];
        if n % 2 == 0 {
            even = even * z + term;
        } else {
            odd = odd * z + term;
        }
    }
    h * even + odd
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn roots_are_close_to_libms() {
        for k in 0..=1000 {
            let x = 10f64.powf(-20.0 * f64::from(k) / 1000.0);
            for (ours, n) in [(root::<7>(x), 7.0), (root::<8>(x), 8.0), (root::<9>(x), 9.0), (root::<10>(x), 10.0)] {
                assert!((ours / x.powf(1.0 / n) - 1.0).abs() < 2e-3, "{x}, order {n}");
            }
        }
        assert_eq!(root::<10>(0.0), 0.0);
        assert_eq!(root::<10>(1.0), 1.0);
    }

    #[test]
    fn the_shorter_root_is_the_smaller_of_the_two() {
        for (before, last) in [(1e-3f64, 1e-6f64), (1e-6, 1e-3), (0.5, 0.5), (1.0, 1e-12), (0.0, 0.3)] {
            let exact = before.powf(1.0 / 7.0).min(last.powf(1.0 / 8.0));
            assert!((shorter_root::<7, 8>(before, last) - exact).abs() <= 2e-3 * exact, "{before}, {last}");
        }
    }

    #[test]
    fn polynomials_and_their_slopes() {
        // 1 + 2h − h² + 0.5h³ at h = 0.3, and its derivative 2 − 2h + 1.5h².
        let c = [1.0, 2.0, -1.0, 0.5];
        let (v, s) = value_and_slope(&c, 0.3);
        assert!((v - (1.0 + 0.6 - 0.09 + 0.0135)).abs() < 1e-15 && (s - (2.0 - 0.6 + 0.135)).abs() < 1e-15);
    }
}

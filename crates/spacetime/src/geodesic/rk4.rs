//! The classical fourth-order Runge–Kutta step, as used by the poster (Ayush & Chaudhuri 2017),
//! with cubic Hermite dense output between the step's ends.

/// One classical RK4 step of size `h` from `y0` (with `k1 = f(t0, y0)`).
#[inline]
pub fn step<const N: usize>(
    f: &impl Fn(f64, &[f64; N]) -> [f64; N],
    t0: f64,
    y0: &[f64; N],
    k1: &[f64; N],
    h: f64,
) -> [f64; N] {
    let at = |k: &[f64; N], c: f64| -> [f64; N] { std::array::from_fn(|i| y0[i] + c * h * k[i]) };
    let k2 = f(t0 + 0.5 * h, &at(k1, 0.5));
    let k3 = f(t0 + 0.5 * h, &at(&k2, 0.5));
    let k4 = f(t0 + h, &at(&k3, 1.0));
    std::array::from_fn(|i| y0[i] + h / 6.0 * (k1[i] + 2.0 * k2[i] + 2.0 * k3[i] + k4[i]))
}

/// Cubic Hermite interpolation on `[0, h]` from values and derivatives at both ends.
#[inline]
pub fn hermite<const N: usize>(
    y0: &[f64; N],
    d0: &[f64; N],
    y1: &[f64; N],
    d1: &[f64; N],
    h: f64,
    theta: f64,
) -> [f64; N] {
    hermite_head(y0, d0, y1, d1, h, theta)
}

/// The first `M` components of [`hermite`].
#[inline]
pub fn hermite_head<const N: usize, const M: usize>(
    y0: &[f64; N],
    d0: &[f64; N],
    y1: &[f64; N],
    d1: &[f64; N],
    h: f64,
    theta: f64,
) -> [f64; M] {
    let t2 = theta * theta;
    let t3 = t2 * theta;
    let h00 = 2.0 * t3 - 3.0 * t2 + 1.0;
    let h10 = t3 - 2.0 * t2 + theta;
    let h01 = -2.0 * t3 + 3.0 * t2;
    let h11 = t3 - t2;
    std::array::from_fn(|i| h00 * y0[i] + h10 * h * d0[i] + h01 * y1[i] + h11 * h * d1[i])
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn fourth_order_on_the_exponential() {
        let f = |_t: f64, y: &[f64; 1]| [y[0]];
        let err = |h: f64| (step(&f, 0.0, &[1.0], &[1.0], h)[0] - h.exp()).abs();
        let ratio = err(0.1) / err(0.05);
        assert!((ratio.log2() - 5.0).abs() < 0.3, "observed local order {}", ratio.log2());
    }

    #[test]
    fn hermite_reproduces_cubics() {
        // y = t³ on [1, 2]: y0 = 1, y0' = 3, y1 = 8, y1' = 12.
        let y = hermite(&[1.0], &[3.0], &[8.0], &[12.0], 1.0, 0.5);
        assert!((y[0] - 1.5f64.powi(3)).abs() < 1e-14);
    }
}

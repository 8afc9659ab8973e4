//! The chart's time along a Mino step, for callers that ask for it
//! ([`MinoTracer::carrying_time`](super::MinoTracer::carrying_time)): integrated over the step's
//! dense output ([`quadrature`](crate::geodesic::quadrature)), never by the stepper, so a ray
//! traced without it takes the same steps at the same cost.
//!
//! The rate is Carter's separated `dt̃/dλ_M = P + (2Mr − Q_e²) G + a(L − aE sin²θ)` in the
//! outgoing Kerr–Schild chart (module documentation of [`super`]), with `P = A r²`. It grows as
//! `E r² = E/u²` far out, a pole at `u = 0` just past a step that reaches the escape radius, so
//! the part that makes it is taken out exactly: `d(u'/u)/dλ_M = (u''u − u'²)/u²`, and
//! `u'² → U(0) = E²` as `u → 0`, so `−(1/E) u'/u` carries the `E/u²` and the quadrature
//! integrates `dt̃/dλ_M + (1/E)(u''u − u'²)/u²`, whose pole is weaker (`1/u`, the logarithm of
//! the Shapiro delay) and whose size is small. The momenta traced are backward ones, so the
//! time falls along the ray as the 4-D tracer's `x⁰` does.

use super::motion::Constants;
use super::series::Dense;
use crate::geodesic::quadrature::integrate;

/// Relative tolerance of the quadrature of a step's time, far below the steps' own truncation.
const RTOL: f64 = 1e-13;

impl Constants {
    /// `dt̃/dλ_M` at `u`, `u'` and `sin²θ = n_x² + n_y²`.
    #[inline]
    pub(super) fn time_rate(&self, u: f64, w: f64, sin2: f64) -> f64 {
        let (r, a, e) = (1.0 / u, self.spin, self.energy);
        let big_a = e + self.b * u * u;
        big_a * r * r + (2.0 * self.mass * r - self.charge2) * self.g(u, w, big_a) + a * (self.axial - a * e * sin2)
    }
}

/// The chart time gained over the first fraction `theta` of the step `dense` of the ray of
/// `constants` (negative along a backward ray).
pub(super) fn elapsed(constants: &Constants, dense: &Dense, theta: f64) -> f64 {
    let far = if constants.energy != 0.0 { 1.0 / constants.energy } else { 0.0 };
    let flat = |theta: f64| {
        let [u, w] = dense.head::<2>(theta);
        -far * w / u
    };
    let rest = |theta: f64| {
        let y = dense.head::<8>(theta);
        let [u, w, n0, n1, ..] = y;
        let dw = constants.rhs(&y)[1];
        constants.time_rate(u, w, n0 * n0 + n1 * n1) + far * (dw * u - w * w) / (u * u)
    };
    let (h, flat0, flat1) = (dense.h(), flat(0.0), flat(theta));
    // The difference of the rates loses the digits of their size, the time's: no interval need
    // be resolved below them.
    let atol = RTOL * (flat0.abs() + flat1.abs()) / h;
    flat1 - flat0 + h * integrate(&rest, 0.0, theta, RTOL, atol)
}

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
//! about 40 flops and one division. The chart's time is not integrated by the stepper: a hole is
//! stationary, so nothing else depends on it, and a caller that needs it asks for it
//! ([`MinoTracer::carrying_time`]); it is then integrated over each step's dense output (`time`).
//! Nothing is re-projected onto the constraints
//! `u'² = U(u)`, `|n| = 1`, `n · v = 0`, `|v|² = Q + L² + a²E² n_z²`: the steps' truncation
//! control keeps them (the tests measure how well).
//!
//! **Steps.** The right-hand side is polynomial in `(u, u', n, v)` but for the one quotient in
//! `G`, so the adaptive tracer takes Taylor steps: the series of the solution about the step's
//! start follows from recurrences (`Recurrence`, in `series`; Jorba & Zou 2005, "A software
//! package for the numerical integration of ODEs by means of high-order Taylor methods", Exp.
//! Math. 14), its last two terms set the step's length ([`MinoTracer::taylor_step`]), and the
//! polynomial
//! is the ray anywhere inside the step, as accurate there as at the end. In `(u, n)` even a
//! straight line is a harmonic oscillation (`u = sin(bλ)/b`-like), which a series resolves
//! in steps of a good part of a radian where Dormand–Prince 5(4) took a tenth.
//!
//! Files: the constants of motion and the state in `motion`, the series and the dense output in
//! `series`, the chart's time along a step in `time`, the step control and the fate in `tracer`.

mod motion;
mod series;
#[cfg(test)]
mod tests;
mod time;
mod tracer;

pub use tracer::{MinoStep, MinoTracer};

use crate::geodesic::State;
use crate::metric::KerrNewman;

/// Carter's constant `Q` of the ray at `state` (chart position and covariant momentum) about
/// `hole` (Carter 1968): with `E` and `L_z` the third constant of motion of Kerr's family, zero
/// on rays in the equatorial plane. Quadratic in `p`, so a ray traced backwards has the `Q` of
/// the photon it describes.
pub fn carter_q(hole: &KerrNewman, state: &State) -> f64 {
    let (c, _) = motion::from_chart(hole, state);
    // `sphere = Q + L²`.
    c.sphere - c.axial * c.axial
}

//! Carter's constant of a geodesic about a hole of Kerr's family, from a Kerr–Schild state.

use crate::geodesic::State;
use crate::metric::{KerrNewman, KerrSchild, Metric};

/// Carter's constant `Q = p_θ² + cos²θ (a²(μ² − E²) + L_z²/sin²θ)` (Carter 1968; Misner, Thorne
/// & Wheeler 1973, eq. 33.31) of the geodesic through state `s` of `hole`'s Kerr–Schild chart,
/// with `E = −p_t`, `L_z = x p_y − y p_x` and the rest mass squared `μ² = −g^{μν} p_μ p_ν`
/// (1 for a body, 0 for light). Charge changes none of it (Carter 1968).
///
/// The chart is `x + iy = (r ∓ ia) sin θ e^{iφ}`, `z = r cos θ` (either sign: ingoing or
/// outgoing), whose `θ` is Boyer–Lindquist's and whose `p_θ` is too (the charts differ by
/// functions of `r` in `t` and `φ`). There `∂(x + iy)/∂θ = cot θ (x + iy)` and
/// `∂z/∂θ = −r sin θ`, so `p_θ = cot θ (x p_x + y p_y) − r sin θ p_z`, and with
/// `(x p_x + y p_y)² + L_z² = (x² + y²)(p_x² + p_y²)`, `x² + y² = (r² + a²) sin²θ`:
///
/// `Q = cos²θ (r² + a²)(p_x² + p_y²) − 2 r cos θ p_z (x p_x + y p_y) + r² sin²θ p_z²
///   + a² cos²θ (μ² − E²)`,
///
/// with no `1/sin θ` left: regular on the axis. Without spin it is `|x × p|² − L_z²`.
pub fn carter_constant(hole: &KerrNewman, s: &State) -> f64 {
    let (x, p) = (&s.x, &s.p);
    let a2 = hole.spin * hole.spin;
    let r = hole.radial_coordinate(x);
    let cos = x[3] / r;
    let (cos2, sin2) = (cos * cos, 1.0 - cos * cos);
    let rest_mass2 = -2.0 * hole.hamiltonian(x, p);
    let energy = -p[0];
    let planar = x[1] * p[1] + x[2] * p[2];
    cos2 * (r * r + a2) * (p[1] * p[1] + p[2] * p[2]) - 2.0 * r * cos * p[3] * planar
        + r * r * sin2 * p[3] * p[3]
        + a2 * cos2 * (rest_mass2 - energy * energy)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::tensor::cross3;

    /// Without spin, `Q + L_z²` is the squared total angular momentum.
    #[test]
    fn without_spin_it_is_the_angular_momentum_off_the_axis() {
        let hole = KerrNewman::new(1.0, 0.0, 0.3);
        let s = State { x: [0.0, 3.0, -2.0, 5.0], p: [-0.95, 0.1, 0.3, -0.2] };
        let l = cross3(&[s.x[1], s.x[2], s.x[3]], &[s.p[1], s.p[2], s.p[3]]);
        let expected = l[0] * l[0] + l[1] * l[1];
        assert!((carter_constant(&hole, &s) - expected).abs() < 1e-13, "{}", carter_constant(&hole, &s));
    }

    /// Light in the equatorial plane moving within it has `Q = 0`, whatever the spin.
    #[test]
    fn equatorial_motion_has_none() {
        let hole = KerrNewman::new(1.0, 0.9, 0.0);
        let s = State { x: [0.0, 6.0, 1.0, 0.0], p: [-1.0, 0.2, 0.5, 0.0] };
        assert!(carter_constant(&hole, &s).abs() < 1e-13);
    }
}

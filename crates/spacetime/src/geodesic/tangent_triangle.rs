//! A plane arc that bends one way and turns by less than π lies on one side of its chord and of
//! the tangent lines at both its ends, so inside the triangle they bound. In world coordinates a
//! Schwarzschild ray bends towards the centre all along (its curvature is `3Mu⁵/(u² + u'²)^{3/2}`,
//! [`connect`](crate::metric::schwarzschild::connect) equation (1)), so every piece of it that
//! sweeps at most π round the centre is held by such a triangle: nothing that stays clear of the
//! triangle can meet that piece of the ray, which tests its visibility without tracing it.
//!
//! The turning angle is the sweep `Δφ` plus the change of the tangent's angle from the outward
//! radial direction, which stays in `(0, π)` since the ray sweeps one way. Over a sweep `Δφ ≤ π`
//! it therefore lies in `[0, 2π)`, and the sine of the angle from the start tangent to the end
//! one, about the axis the ray sweeps round, is positive exactly when the turning is below π.

use crate::tensor::{cross3, dot3};

/// Below this sine of its turning angle a piece's end tangents meet too far off to bound it.
const MIN_SIN_TURN: f64 = 1e-9;

/// The triangle `[p, z, q]` of the chord from `p` to `q` and the tangent lines there (unit
/// tangents `tp`, `tq`, in the direction of travel) of a piece of ray that sweeps at most π about
/// `axis` and bends one way; `z` is where the tangent lines meet. `None` where the piece turns by
/// π or more, or too little to place `z`.
pub fn tangent_triangle(
    axis: [f64; 3],
    (p, tp): ([f64; 3], [f64; 3]),
    (q, tq): ([f64; 3], [f64; 3]),
) -> Option<[[f64; 3]; 3]> {
    let sin_turn = dot3(&cross3(&tp, &tq), &axis);
    if !(sin_turn > MIN_SIN_TURN) {
        return None;
    }
    // z = p + a tp = q − b tq, solved in the plane.
    let chord: [f64; 3] = std::array::from_fn(|i| q[i] - p[i]);
    let a = dot3(&cross3(&chord, &tq), &axis) / sin_turn;
    let b = dot3(&cross3(&tp, &chord), &axis) / sin_turn;
    if !(a > 0.0 && b > 0.0 && a.is_finite() && b.is_finite()) {
        return None;
    }
    Some([p, std::array::from_fn(|i| p[i] + a * tp[i]), q])
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_quarter_circle_is_held_by_the_square_corner_of_its_tangents() {
        // Counter-clockwise about +z from (1, 0, 0) to (0, 1, 0): the tangents meet at (1, 1, 0).
        let z = [0.0, 0.0, 1.0];
        let t = tangent_triangle(z, ([1.0, 0.0, 0.0], [0.0, 1.0, 0.0]), ([0.0, 1.0, 0.0], [-1.0, 0.0, 0.0]));
        let [_, corner, _] = t.expect("a quarter turn is bounded");
        assert!(corner.iter().zip([1.0, 1.0, 0.0]).all(|(c, e)| (c - e).abs() < 1e-15), "{corner:?}");
        // Swept the other way round the axis, the same ends turn by 3π/2: no triangle.
        let back = tangent_triangle(z, ([0.0, 1.0, 0.0], [1.0, 0.0, 0.0]), ([1.0, 0.0, 0.0], [0.0, -1.0, 0.0]));
        assert!(back.is_none());
        // A straight piece has no third corner.
        assert!(tangent_triangle(z, ([0.0; 3], [1.0, 0.0, 0.0]), ([1.0, 0.0, 0.0], [1.0, 0.0, 0.0])).is_none());
    }
}

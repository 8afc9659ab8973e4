//! Flat spacetime in Cartesian coordinates: `g = η`. Rays are straight lines.

use super::Metric;
use crate::tensor::{Covector4, Matrix4, Vector4, ETA};

/// Minkowski spacetime.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Minkowski;

impl Metric for Minkowski {
    fn metric(&self, _x: &Vector4) -> Matrix4 {
        ETA
    }

    fn inverse_metric(&self, _x: &Vector4) -> Matrix4 {
        ETA
    }

    fn inverse_metric_derivatives(&self, _x: &Vector4) -> (Matrix4, [Matrix4; 4]) {
        (ETA, [[[0.0; 4]; 4]; 4])
    }

    fn geodesic_rhs(&self, _x: &Vector4, p: &Covector4) -> (Vector4, Covector4) {
        ([-p[0], p[1], p[2], p[3]], [0.0; 4])
    }

    fn length_scale(&self) -> f64 {
        1.0
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn conformance() {
        super::super::conformance::check_metric(&Minkowski, &[0.0, 1.0, -2.0, 3.0]);
    }
}

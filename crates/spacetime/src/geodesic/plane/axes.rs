//! The directions of a ray's plane at a point, in world coordinates, and the sine and cosine of
//! the small angles a step sweeps.

use crate::tensor::{normalize3, scale3};

/// The chart's radial and azimuthal unit vectors at a point of a ray's plane, and the sign that
/// takes the chart to world coordinates in the point's region.
pub(crate) struct PlaneAxes {
    pub(super) sign: f64,
    pub(super) radial: [f64; 3],
    pub(super) azimuthal: [f64; 3],
}

impl PlaneAxes {
    /// The directions at azimuth `φ` of the plane with basis `x̂`, `e₂`, in the upper region.
    pub(crate) fn at(xh: &[f64; 3], e2: &[f64; 3], phi: f64) -> Self {
        Self::at_sin_cos(xh, e2, phi.sin_cos())
    }

    /// [`PlaneAxes::at`] the azimuth with sine and cosine `(sin, cos)`.
    pub(crate) fn at_sin_cos(xh: &[f64; 3], e2: &[f64; 3], (sin, cos): (f64, f64)) -> Self {
        let radial = std::array::from_fn(|i| cos * xh[i] + sin * e2[i]);
        let azimuthal = std::array::from_fn(|i| -sin * xh[i] + cos * e2[i]);
        Self { sign: 1.0, radial, azimuthal }
    }

    /// The world point at world radius `rho` along the radial direction.
    pub(crate) fn at_radius(&self, rho: f64) -> [f64; 3] {
        scale3(&self.radial, self.sign * rho)
    }

    /// The unit world vector with radial and azimuthal components in the ratio `dr : dphi`.
    pub(crate) fn along(&self, dr: f64, dphi: f64) -> [f64; 3] {
        normalize3(&self.scaled(dr, dphi))
    }

    /// The world vector with radial and azimuthal components `dr` and `dphi`.
    pub(super) fn scaled(&self, dr: f64, dphi: f64) -> [f64; 3] {
        std::array::from_fn(|i| self.sign * (dr * self.radial[i] + dphi * self.azimuthal[i]))
    }
}

/// `(sin x, cos x)` for the small angles inside one step (`|x| ≤ 1`), by their Taylor series to
/// degree 19 (truncation below 2·10⁻²⁰): much cheaper than libm's general `sin_cos`, which
/// dominated the cost of placing points on curved steps. Larger angles, which no step sweeps,
/// go to libm rather than lose accuracy.
#[inline]
pub(super) fn sin_cos_small(x: f64) -> (f64, f64) {
    if !(x.abs() <= 1.0 + 1e-12) {
        return x.sin_cos();
    }
    /// (−1)ⁿ/(2n+1)! and (−1)ⁿ/(2n)!, n = 0…9.
    const SIN: [f64; 10] = [
        1.0,
        -0.16666666666666666,
        0.008333333333333333,
        -0.0001984126984126984,
        2.7557319223985893e-06,
        -2.505210838544172e-08,
        1.6059043836821613e-10,
        -7.647163731819816e-13,
        2.8114572543455206e-15,
        -8.22063524662433e-18,
    ];
    const COS: [f64; 10] = [
        1.0,
        -0.5,
        0.041666666666666664,
        -0.001388888888888889,
        2.48015873015873e-05,
        -2.755731922398589e-07,
        2.08767569878681e-09,
        -1.1470745597729725e-11,
        4.779477332387385e-14,
        -1.5619206968586225e-16,
    ];
    let x2 = x * x;
    (x * estrin(&SIN, x2), estrin(&COS, x2))
}

/// `Σ cₙ zⁿ` for ten coefficients by Estrin's scheme: pairs, then pairs of pairs, so the chain
/// of dependent operations is 6 long instead of Horner's 20 (the latency, not the count of
/// operations, is what the placement of points on a step waits for).
#[inline]
fn estrin(c: &[f64; 10], z: f64) -> f64 {
    let pair = |k: usize| c[k] + c[k + 1] * z;
    let z2 = z * z;
    let z4 = z2 * z2;
    let low = pair(0) + pair(2) * z2;
    let high = pair(4) + pair(6) * z2;
    low + high * z4 + pair(8) * (z4 * z4)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn small_angle_sine_and_cosine_are_exact_to_rounding() {
        for i in -100..=100 {
            let x = f64::from(i) / 100.0;
            let (s, c) = sin_cos_small(x);
            assert!((s - x.sin()).abs() < 2e-16 && (c - x.cos()).abs() < 2e-16, "x = {x}");
        }
    }
}

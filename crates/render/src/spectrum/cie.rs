//! The CIE 1931 2° colour-matching functions as functions of wavelength, and XYZ by quadrature.

use super::cie_data::{CIE_1931_XYZ, CMF_ROWS, TABLE_LAMBDA_MIN};
use super::{Spectrum, Xyz};

/// x̄, ȳ, z̄ at `lambda` nm, linearly interpolated in the 1 nm table (CIE 015 recommends linear
/// interpolation of the tabulated functions); zero outside [360, 830] nm.
pub fn cmf(lambda: f64) -> Xyz {
    let t = lambda - TABLE_LAMBDA_MIN;
    if !(t >= 0.0) || t > (CMF_ROWS - 1) as f64 {
        return Xyz::ZERO;
    }
    let i = (t as usize).min(CMF_ROWS - 2);
    let f = t - i as f64;
    Xyz::from(CIE_1931_XYZ[i]).lerp(Xyz::from(CIE_1931_XYZ[i + 1]), f)
}

/// ∫ ȳ(λ) dλ over the table, in nm (about 106.86): the luminance of a spectrum equal to 1.
/// Summed at compile time: the XYZ estimator divides by it once per sample.
const Y_INTEGRAL: f64 = {
    let mut sum = 0.0;
    let mut i = 0;
    while i < CMF_ROWS {
        sum += CIE_1931_XYZ[i][1];
        i += 1;
    }
    sum
};

/// [`Y_INTEGRAL`].
pub fn y_integral() -> f64 {
    Y_INTEGRAL
}

/// XYZ of `spectrum` by quadrature at the table's 1 nm nodes, normalised by [`y_integral`]
/// (the reference that Monte Carlo estimates converge to).
pub fn xyz_quadrature(spectrum: &impl Spectrum) -> Xyz {
    let sum: Xyz = CIE_1931_XYZ
        .iter()
        .enumerate()
        .map(|(i, row)| Xyz::from(*row) * spectrum.eval(TABLE_LAMBDA_MIN + i as f64))
        .sum();
    sum / y_integral()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn interpolation_hits_the_table_and_vanishes_outside() {
        // CIE 015 table: ȳ(555) = 1.0, x̄(600) = 1.0622.
        assert!((cmf(555.0).y - 1.0).abs() < 1e-7);
        assert!((cmf(600.0).x - 1.0622).abs() < 1e-7);
        assert_eq!(cmf(359.9), Xyz::ZERO);
        assert_eq!(cmf(830.1), Xyz::ZERO);
        assert_eq!(cmf(f64::NAN), Xyz::ZERO);
        let mid = cmf(555.5).y;
        assert!((mid - 0.5 * (cmf(555.0).y + cmf(556.0).y)).abs() < 1e-12);
        // ∫ȳ of the 1931 observer over 360–830 nm at 1 nm: 106.856895 (pbrt-v4's CIE_Y_integral).
        assert!((y_integral() - 106.856895).abs() < 1e-4, "{}", y_integral());
    }
}

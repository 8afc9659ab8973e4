//! CIE standard illuminant D65, the white of Rec. 709 / sRGB, scaled to luminance Y = 1.

use super::cie_data::{D65_ROWS, TABLE_LAMBDA_MIN};
use super::{cie, cie_data, Spectrum};

/// Spacing of the D65 table, in nm.
const STEP: f64 = 5.0;

/// D65's relative spectral power, linearly interpolated in the 5 nm CIE table and scaled so that
/// its Y (convention of [`super`]) is 1; zero outside [360, 830] nm.
#[derive(Clone, Copy, Debug)]
pub struct D65 {
    scale: f64,
}

impl D65 {
    /// D65 with its normalisation computed once by quadrature.
    pub fn new() -> Self {
        let raw = cie::xyz_quadrature(&Self { scale: 1.0 }).y;
        Self { scale: 1.0 / raw }
    }
}

impl Default for D65 {
    fn default() -> Self {
        Self::new()
    }
}

impl Spectrum for D65 {
    fn eval(&self, lambda: f64) -> f64 {
        let t = (lambda - TABLE_LAMBDA_MIN) / STEP;
        if !(t >= 0.0) || t > (D65_ROWS - 1) as f64 {
            return 0.0;
        }
        let i = (t as usize).min(D65_ROWS - 2);
        let f = t - i as f64;
        let table = &cie_data::D65;
        self.scale * (table[i] + f * (table[i + 1] - table[i]))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::spectrum::chromaticity;

    #[test]
    fn d65_integrates_to_its_white_point() {
        // CIE 015:2018 Table 3: D65 white (x, y) = (0.31271, 0.32902) for the 1931 observer.
        let d65 = D65::new();
        let (x, y) = chromaticity(cie::xyz_quadrature(&d65));
        assert!((x - 0.31271).abs() < 1e-4 && (y - 0.32902).abs() < 1e-4, "({x}, {y})");
        assert!((cie::xyz_quadrature(&d65).y - 1.0).abs() < 1e-12);
    }
}

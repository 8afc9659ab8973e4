//! RGB inputs lifted to spectra: bounded reflectances, and emitters as a scaled reflectance-like
//! spectrum times D65 (pbrt-v4's `RGBAlbedoSpectrum` and `RGBIlluminantSpectrum`).

use super::{RgbToSpectrumTable, SigmoidPolynomial, Spectrum, D65};
use std::sync::OnceLock;

/// Lifts linear Rec. 709 colours to spectra with an optimised [`RgbToSpectrumTable`].
pub struct RgbUpsampler {
    table: RgbToSpectrumTable,
    d65: D65,
}

impl RgbUpsampler {
    /// An upsampler owning `table`.
    pub fn new(table: RgbToSpectrumTable) -> Self {
        Self { table, d65: D65::new() }
    }

    /// The upsampler spectral rendering uses, with the [`RgbToSpectrumTable::shipped`] table
    /// (read on first use, not optimised) and kept.
    pub fn get() -> &'static RgbUpsampler {
        static UPSAMPLER: OnceLock<RgbUpsampler> = OnceLock::new();
        UPSAMPLER.get_or_init(|| RgbUpsampler::new(RgbToSpectrumTable::shipped()))
    }

    /// The table it lifts colours with.
    pub fn table(&self) -> &RgbToSpectrumTable {
        &self.table
    }

    /// The reflectance of albedo `rgb` (components clamped to [0, 1]): a sigmoid polynomial, in
    /// [0, 1] at every wavelength, whose colour under D65 is `rgb`.
    pub fn albedo(&self, rgb: [f32; 3]) -> SigmoidPolynomial {
        self.table.lookup(rgb)
    }

    /// A non-negative RGB quantity with no bound (components < 0 taken as 0): with m the
    /// largest component, 2m × the reflectance of rgb / 2m (pbrt-v4's `RGBUnboundedSpectrum`).
    pub fn unbounded(&self, rgb: [f32; 3]) -> RgbUnboundedSpectrum {
        let rgb = rgb.map(|v| if v >= 0.0 { v } else { 0.0 });
        let scale = 2.0 * rgb.iter().copied().fold(0.0, f32::max);
        let reflectance = if scale > 0.0 && scale.is_finite() {
            self.table.lookup(rgb.map(|v| v / scale))
        } else {
            SigmoidPolynomial::constant(0.0)
        };
        RgbUnboundedSpectrum { scale: f64::from(scale), reflectance }
    }

    /// The spectral radiance of emitter `rgb` (components ≥ 0, unbounded): its
    /// [`RgbUpsampler::unbounded`] spectrum times D65, so that (1, 1, 1) is exactly D65 at Y = 1
    /// and a colour's chromaticity is kept at any brightness (pbrt-v4).
    pub fn illuminant(&self, rgb: [f32; 3]) -> RgbIlluminantSpectrum {
        RgbIlluminantSpectrum { unbounded: self.unbounded(rgb), d65: self.d65 }
    }
}

/// An unbounded RGB quantity's spectrum: scale × sigmoid polynomial (see [`RgbUpsampler::unbounded`]).
#[derive(Clone, Copy, Debug)]
pub struct RgbUnboundedSpectrum {
    scale: f64,
    reflectance: SigmoidPolynomial,
}

impl Spectrum for RgbUnboundedSpectrum {
    fn eval(&self, lambda: f64) -> f64 {
        if self.scale == 0.0 {
            return 0.0;
        }
        self.scale * self.reflectance.eval(lambda)
    }
}

/// An RGB emitter's spectral radiance: its unbounded spectrum × D65 (see [`RgbUpsampler::illuminant`]).
#[derive(Clone, Copy, Debug)]
pub struct RgbIlluminantSpectrum {
    unbounded: RgbUnboundedSpectrum,
    d65: D65,
}

impl Spectrum for RgbIlluminantSpectrum {
    fn eval(&self, lambda: f64) -> f64 {
        self.unbounded.eval(lambda) * self.d65.eval(lambda)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::spectrum::{test_support, xyz_quadrature, xyz_to_linear_srgb, LAMBDA_MIN};
    use glam::DVec3;

    /// A reflectance lit by D65 (Y = 1), back to linear Rec. 709.
    fn reflected_rgb(d65: &D65, s: &SigmoidPolynomial) -> DVec3 {
        struct Lit<'a>(&'a D65, &'a SigmoidPolynomial);
        impl Spectrum for Lit<'_> {
            fn eval(&self, lambda: f64) -> f64 {
                self.0.eval(lambda) * self.1.eval(lambda)
            }
        }
        xyz_to_linear_srgb(xyz_quadrature(&Lit(d65, s)))
    }

    /// The sRGB transfer function (IEC 61966-2-1), to compare in display terms.
    fn encode(v: f64) -> f64 {
        if v <= 0.0031308 {
            12.92 * v
        } else {
            1.055 * v.powf(1.0 / 2.4) - 0.055
        }
    }

    #[test]
    fn albedos_round_trip_within_one_percent_and_stay_below_one() {
        let table = test_support::table();
        let d65 = D65::new();
        let steps = 9;
        let mut worst: f64 = 0.0;
        for r in 0..=steps {
            for g in 0..=steps {
                for b in 0..=steps {
                    let rgb = [r, g, b].map(|v| v as f32 / steps as f32);
                    let s = table.lookup(rgb);
                    for k in 0..=94 {
                        let v = s.eval(LAMBDA_MIN + 5.0 * k as f64);
                        assert!((0.0..=1.0).contains(&v), "{rgb:?}: {v}");
                    }
                    let back = reflected_rgb(&d65, &s);
                    let input = DVec3::from(rgb.map(f64::from));
                    for c in 0..3 {
                        worst = worst.max((encode(back[c].max(0.0)) - encode(input[c])).abs());
                    }
                }
            }
        }
        assert!(worst <= 0.01, "worst sRGB difference {worst}");
        eprintln!("albedo round trip: worst sRGB difference {worst:.2e} over 10³ colours");
    }

    #[test]
    fn white_emitter_integrates_to_white_and_keeps_its_colour_when_scaled() {
        let up = RgbUpsampler::get();
        let white = xyz_to_linear_srgb(xyz_quadrature(&up.illuminant([1.0, 1.0, 1.0])));
        // The tabulated D65 integrates to (0.312727, 0.329023), 3e-5 from Rec. 709's nominal white.
        assert!((white - DVec3::ONE).abs().max_element() < 1e-3, "{white}");
        for rgb in [[0.9, 0.3, 0.1], [0.1, 0.2, 0.7]] {
            let one = xyz_to_linear_srgb(xyz_quadrature(&up.illuminant(rgb)));
            let bright = xyz_to_linear_srgb(xyz_quadrature(&up.illuminant(rgb.map(|v| 20.0 * v))));
            let input = DVec3::from(rgb.map(f64::from));
            assert!((one - input).abs().max_element() < 5e-3, "{rgb:?}: {one}");
            assert!((bright / 20.0 - input).abs().max_element() < 5e-3, "{rgb:?}: {bright}");
        }
        assert_eq!(up.illuminant([0.0, -1.0, f32::NAN]).eval(500.0), 0.0);
    }
}

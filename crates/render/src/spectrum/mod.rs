//! Spectral light: sampled wavelengths and spectra, the CIE 1931 observer and D65, XYZ ↔ linear
//! Rec. 709, RGB → spectrum upsampling (Jakob & Hanika 2019), Planck's law and the frequency shift
//! that gravity and motion apply to radiance.
//!
//! Conventions: wavelengths in nanometres over [`LAMBDA_MIN`, `LAMBDA_MAX`] = [360, 830] nm (the range
//! of the CIE tables); XYZ is normalised so that a spectrum equal to 1 everywhere has Y = 1
//! (XYZ = ∫ x̄ȳz̄(λ) S(λ) dλ / ∫ ȳ(λ) dλ, pbrt-v4's convention); D65 is scaled to Y = 1, so an RGB
//! emitter (1, 1, 1) and a white reflector under it both come back as RGB (1, 1, 1).
//! The design follows pbrt-v4's `spectrum.h` / `color.h` (Pharr, Jakob, Humphreys 2023, ch. 4.5–4.6).

mod atanh;
mod blackbody;
mod blackbody_colour;
mod cie;
mod cie_data;
mod colour;
mod d65;
mod fit;
mod rgb_spectrum;
mod rgb_table;
mod sampled;
mod shift;
mod sigmoid;
mod wavelengths;
mod xyz;

pub use blackbody::{Blackbody, NormalizedBlackbody, WIEN_DISPLACEMENT};
pub use blackbody_colour::BlackbodyColours;
pub use cie::{cmf, xyz_quadrature};
pub use colour::{Colour, LiftedIlluminant, LiftedReflectance};
pub use d65::D65;
pub use rgb_spectrum::{RgbIlluminantSpectrum, RgbUnboundedSpectrum, RgbUpsampler};
pub use rgb_table::RgbToSpectrumTable;
pub use sampled::SampledSpectrum;
pub use shift::{FrequencyShift, Shifted};
pub use sigmoid::SigmoidPolynomial;
pub use wavelengths::SampledWavelengths;
pub use xyz::{chromaticity, linear_srgb_to_xyz, xyz_to_linear_srgb, Xyz};

/// Shortest wavelength a path carries, in nm.
pub const LAMBDA_MIN: f64 = 360.0;

/// Longest wavelength a path carries, in nm.
pub const LAMBDA_MAX: f64 = 830.0;

/// Wavelengths per path: the hero and its companions (Wilkie et al. 2014).
pub const N_WAVELENGTHS: usize = 4;

/// A spectral distribution: a function of wavelength in nm (radiance per nm, reflectance, ...).
pub trait Spectrum {
    /// The value at wavelength `lambda` in nm.
    fn eval(&self, lambda: f64) -> f64;

    /// The values at a path's sampled wavelengths.
    fn sample(&self, wavelengths: &SampledWavelengths) -> SampledSpectrum {
        SampledSpectrum::from_fn(|i| self.eval(f64::from(wavelengths.lambda(i))) as f32)
    }
}

#[cfg(test)]
pub(crate) mod test_support {
    use super::{RgbToSpectrumTable, RgbUpsampler};

    /// The table rendering uses (the shipped one).
    pub fn table() -> &'static RgbToSpectrumTable {
        RgbUpsampler::get().table()
    }

    /// The wavelength in nm maximising `f` on [lo, hi] by golden-section search (unimodal `f`).
    pub fn argmax(f: impl Fn(f64) -> f64, mut lo: f64, mut hi: f64) -> f64 {
        let r = (5f64.sqrt() - 1.0) / 2.0;
        while hi - lo > 1e-10 * hi {
            let (a, b) = (hi - r * (hi - lo), lo + r * (hi - lo));
            if f(a) < f(b) {
                lo = a;
            } else {
                hi = b;
            }
        }
        0.5 * (lo + hi)
    }
}

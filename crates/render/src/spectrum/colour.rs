//! What a path carries from the lights to the camera, written once for both ways nullpath
//! renders: [`Rgb`] triples, or radiance at the path's sampled wavelengths ([`SampledSpectrum`]
//! at [`SampledWavelengths`]: one hero wavelength and its stratified companions, Wilkie et al.
//! 2014). Materials, emitters and the path integrator are generic over [`Colour`]. Scene inputs
//! stay RGB (or temperatures) and are lifted where a path meets them, as pbrt-v4 does:
//!
//! - reflectances to Jakob & Hanika's (2019) sigmoid polynomials, bounded by 1;
//! - other RGB quantities (a conductor's η and κ) to such a spectrum times a scale (pbrt-v4's
//!   `RGBUnboundedSpectrum`);
//! - RGB radiance to that times D65, the white of Rec. 709 (pbrt-v4's `RGBIlluminantSpectrum`);
//! - blackbodies to Planck's law at each wavelength.
//!
//! Constant inputs (a constant texture's reflectance, an emitter's RGB radiance) are lifted once,
//! where the scene is built ([`LiftedReflectance`], [`LiftedIlluminant`]): a path meeting them
//! evaluates their spectrum at its wavelengths, with no table lookup at each hit, and gets the
//! same numbers as lifting the colour there.
//!
//! **Frequency shifts.** Radiance seen with its colour shifted by the ratio `c = ν_seen/ν_emitted`
//! and its brightness by `b` ([`crate::emission::Shift::shown`]) is `c⁵ L(cλ) · (b/c)⁴`: with
//! `c = b = g` that is nature's `g⁵ L(gλ)` (`I_λ λ⁵` is invariant), and a toggle that leaves one
//! effect out keeps the other's total. An RGB triple has no spectrum to shift: in RGB mode it is
//! only brightened, by `b⁴` (its frequency-integrated radiance); a blackbody is shifted exactly in
//! both modes, being the blackbody at `cT`.

use super::{
    xyz_to_linear_srgb, Blackbody, BlackbodyColours, RgbIlluminantSpectrum, RgbUpsampler, SampledSpectrum,
    SampledWavelengths, SigmoidPolynomial, Spectrum, N_WAVELENGTHS,
};
use crate::rgb::{luminance, Rgb};
use std::fmt::Debug;
use std::ops::{Add, AddAssign, Div, Mul, MulAssign, Sub};

/// Radiance, reflectance or throughput as a path carries it. See the module documentation.
pub trait Colour:
    Copy
    + Debug
    + PartialEq
    + Send
    + Sync
    + Add<Output = Self>
    + AddAssign
    + Sub<Output = Self>
    + Mul<Output = Self>
    + MulAssign
    + Div<Output = Self>
    + Mul<f32, Output = Self>
    + Div<f32, Output = Self>
{
    /// What a value is sampled at: nothing for RGB, the path's wavelengths for spectra.
    type Lambda: Copy + Debug;

    const ZERO: Self;
    const ONE: Self;
    /// How many numbers a value holds: 3 channels, or one per wavelength.
    const COMPONENTS: usize;

    /// Component `i < COMPONENTS`.
    fn component(self, i: usize) -> f32;

    fn splat(v: f32) -> Self;

    fn max_element(self) -> f32;

    /// One number for how much the colour carries, for choosing between lobes: the luminance of
    /// RGB, the mean over wavelengths of a spectrum.
    fn weight(self) -> f32;

    fn is_finite(self) -> bool;

    /// Componentwise `f(self, other)`: per channel, or per wavelength.
    fn zip(self, other: Self, f: impl Fn(f32, f32) -> f32) -> Self;

    /// A reflectance given in linear Rec. 709 RGB, each channel in `[0, 1]`.
    fn reflectance(rgb: Rgb, lambda: &Self::Lambda) -> Self;

    /// A reflectance lifted where the scene was built: `reflectance` of its colour clamped to
    /// `[0, 1]`.
    fn lifted_reflectance(reflectance: &LiftedReflectance, lambda: &Self::Lambda) -> Self;

    /// A non-negative RGB quantity that is no reflectance (a conductor's η and κ).
    fn unbounded(rgb: Rgb, lambda: &Self::Lambda) -> Self;

    /// Radiance given in linear Rec. 709 RGB, seen with its colour shifted by `c` and its
    /// brightness by `b` (`shown = (c, b)`).
    fn illuminant(rgb: Rgb, shown: (f64, f64), lambda: &Self::Lambda) -> Self;

    /// Radiance lifted where the scene was built: `illuminant` of its colour.
    fn lifted_illuminant(radiance: &LiftedIlluminant, shown: (f64, f64), lambda: &Self::Lambda) -> Self;

    /// `scale` times Planck's law at `temperature` kelvin, seen with `shown = (c, b)`.
    fn blackbody(temperature: f64, scale: f64, shown: (f64, f64), lambda: &Self::Lambda) -> Self;

    /// The linear Rec. 709 colour of the value, for the film.
    fn to_rgb(self, lambda: &Self::Lambda) -> Rgb;

    /// The hero wavelength in nm: `None` in RGB, where quantities that vary with wavelength take
    /// their value at a reference line.
    fn hero(lambda: &Self::Lambda) -> Option<f64>;

    /// From here on only the hero wavelength counts: after a scattering whose direction depends on
    /// the wavelength (dispersion), the companions' paths would be others.
    fn keep_hero(lambda: &mut Self::Lambda);
}

/// The ratio `(b/c)⁴` that keeps a colour-shifted spectrum at the brightness shift `b`.
fn brightness_over_colour((colour, brightness): (f64, f64)) -> f64 {
    (brightness / colour).powi(4)
}

impl Colour for Rgb {
    type Lambda = ();

    const ZERO: Self = glam::Vec3::ZERO;
    const ONE: Self = glam::Vec3::ONE;
    const COMPONENTS: usize = 3;

    fn component(self, i: usize) -> f32 {
        self[i]
    }

    fn splat(v: f32) -> Self {
        glam::Vec3::splat(v)
    }

    fn max_element(self) -> f32 {
        glam::Vec3::max_element(self)
    }

    fn weight(self) -> f32 {
        luminance(self)
    }

    fn is_finite(self) -> bool {
        glam::Vec3::is_finite(self)
    }

    fn zip(self, other: Self, f: impl Fn(f32, f32) -> f32) -> Self {
        Rgb::new(f(self.x, other.x), f(self.y, other.y), f(self.z, other.z))
    }

    fn reflectance(rgb: Rgb, _: &()) -> Self {
        rgb
    }

    fn lifted_reflectance(reflectance: &LiftedReflectance, _: &()) -> Self {
        reflectance.rgb.clamp(Rgb::ZERO, Rgb::ONE)
    }

    fn unbounded(rgb: Rgb, _: &()) -> Self {
        rgb
    }

    fn illuminant(rgb: Rgb, (_, brightness): (f64, f64), _: &()) -> Self {
        rgb * brightness.powi(4) as f32
    }

    fn lifted_illuminant(radiance: &LiftedIlluminant, shown: (f64, f64), lambda: &()) -> Self {
        Self::illuminant(radiance.rgb, shown, lambda)
    }

    fn blackbody(temperature: f64, scale: f64, shown: (f64, f64), _: &()) -> Self {
        let (rgb, _) = BlackbodyColours::get().at(shown.0 * temperature);
        let scale = scale * brightness_over_colour(shown);
        Rgb::from_array(rgb.map(|c| (c * scale) as f32))
    }

    fn to_rgb(self, _: &()) -> Rgb {
        self
    }

    fn hero(_: &()) -> Option<f64> {
        None
    }

    fn keep_hero(_: &mut ()) {}
}

impl Colour for SampledSpectrum {
    type Lambda = SampledWavelengths;

    const ZERO: Self = SampledSpectrum::splat_const(0.0);
    const ONE: Self = SampledSpectrum::splat_const(1.0);
    const COMPONENTS: usize = N_WAVELENGTHS;

    fn component(self, i: usize) -> f32 {
        self.value(i)
    }

    fn splat(v: f32) -> Self {
        SampledSpectrum::splat(v)
    }

    fn max_element(self) -> f32 {
        self.max_value()
    }

    fn weight(self) -> f32 {
        self.average()
    }

    fn is_finite(self) -> bool {
        SampledSpectrum::is_finite(&self)
    }

    fn zip(self, other: Self, f: impl Fn(f32, f32) -> f32) -> Self {
        SampledSpectrum::from_fn(|i| f(self.value(i), other.value(i)))
    }

    fn reflectance(rgb: Rgb, lambda: &SampledWavelengths) -> Self {
        Self::lifted_reflectance(&LiftedReflectance::new(rgb), lambda)
    }

    fn lifted_reflectance(reflectance: &LiftedReflectance, lambda: &SampledWavelengths) -> Self {
        at_wavelengths(lambda, 1.0, |l| reflectance.spectrum.eval(l))
    }

    fn unbounded(rgb: Rgb, lambda: &SampledWavelengths) -> Self {
        let spectrum = RgbUpsampler::get().unbounded(rgb.to_array());
        at_wavelengths(lambda, 1.0, |l| spectrum.eval(l))
    }

    fn illuminant(rgb: Rgb, shown: (f64, f64), lambda: &SampledWavelengths) -> Self {
        Self::lifted_illuminant(&LiftedIlluminant::new(rgb), shown, lambda)
    }

    fn lifted_illuminant(radiance: &LiftedIlluminant, shown: (f64, f64), lambda: &SampledWavelengths) -> Self {
        let colour = shown.0;
        // c⁵ L(cλ) (b/c)⁴.
        let scale = colour.powi(5) * brightness_over_colour(shown);
        at_wavelengths(lambda, scale, |l| radiance.spectrum.eval(colour * l))
    }

    fn blackbody(temperature: f64, scale: f64, shown: (f64, f64), lambda: &SampledWavelengths) -> Self {
        // c⁵ B(cλ, T) = B(λ, cT).
        let Some(planck) = Blackbody::new(shown.0 * temperature) else { return Self::ZERO };
        at_wavelengths(lambda, scale * brightness_over_colour(shown), |l| planck.eval(l))
    }

    fn to_rgb(self, lambda: &SampledWavelengths) -> Rgb {
        xyz_to_linear_srgb(self.to_xyz(lambda)).as_vec3()
    }

    fn hero(lambda: &SampledWavelengths) -> Option<f64> {
        Some(f64::from(lambda.lambda(0)))
    }

    fn keep_hero(lambda: &mut SampledWavelengths) {
        lambda.terminate_secondary();
    }
}

/// A reflectance given in linear Rec. 709 RGB, with the spectrum of its colour clamped to
/// `[0, 1]` lifted once (see the module documentation).
#[derive(Clone, Copy, Debug)]
pub struct LiftedReflectance {
    rgb: Rgb,
    spectrum: SigmoidPolynomial,
}

impl LiftedReflectance {
    /// `rgb`, kept as given, and the reflectance spectrum of `rgb` clamped to `[0, 1]`.
    pub fn new(rgb: Rgb) -> Self {
        Self { rgb, spectrum: RgbUpsampler::get().albedo(rgb.clamp(Rgb::ZERO, Rgb::ONE).to_array()) }
    }

    /// The colour as given.
    pub fn rgb(&self) -> Rgb {
        self.rgb
    }
}

/// Equal when the colours are: the spectrum is a function of the colour.
impl PartialEq for LiftedReflectance {
    fn eq(&self, other: &Self) -> bool {
        self.rgb == other.rgb
    }
}

impl From<Rgb> for LiftedReflectance {
    fn from(rgb: Rgb) -> Self {
        Self::new(rgb)
    }
}

/// Radiance given in linear Rec. 709 RGB, with its spectrum ([`RgbUpsampler::illuminant`])
/// lifted once (see the module documentation).
#[derive(Clone, Copy, Debug)]
pub struct LiftedIlluminant {
    rgb: Rgb,
    spectrum: RgbIlluminantSpectrum,
}

impl LiftedIlluminant {
    /// `rgb` and its spectrum.
    pub fn new(rgb: Rgb) -> Self {
        Self { rgb, spectrum: RgbUpsampler::get().illuminant(rgb.to_array()) }
    }

    /// The colour as given.
    pub fn rgb(&self) -> Rgb {
        self.rgb
    }
}

/// Equal when the colours are: the spectrum is a function of the colour.
impl PartialEq for LiftedIlluminant {
    fn eq(&self, other: &Self) -> bool {
        self.rgb == other.rgb
    }
}

impl From<Rgb> for LiftedIlluminant {
    fn from(rgb: Rgb) -> Self {
        Self::new(rgb)
    }
}

/// `scale · f(λᵢ)` at each of the path's wavelengths.
fn at_wavelengths(lambda: &SampledWavelengths, scale: f64, f: impl Fn(f64) -> f64) -> SampledSpectrum {
    SampledSpectrum::from_fn(|i| (scale * f(f64::from(lambda.lambda(i)))) as f32)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::spectrum::{chromaticity, linear_srgb_to_xyz};

    /// The mean of many spectral estimates of `value` at stratified hero wavelengths, in RGB.
    fn expected_rgb(value: impl Fn(&SampledWavelengths) -> SampledSpectrum) -> Rgb {
        let n = 4096;
        (0..n)
            .map(|k| {
                let lambda = SampledWavelengths::sample_visible((k as f32 + 0.5) / n as f32);
                value(&lambda).to_rgb(&lambda)
            })
            .sum::<Rgb>()
            / n as f32
    }

    #[test]
    fn lifted_rgb_radiance_and_reflectance_come_back_as_their_rgb() {
        for rgb in [Rgb::ONE, Rgb::new(0.8, 0.3, 0.1), Rgb::new(0.05, 0.4, 0.9)] {
            let lit = expected_rgb(|l| SampledSpectrum::illuminant(rgb, (1.0, 1.0), l));
            assert!((lit - rgb).abs().max_element() < 5e-3, "{rgb} lit as {lit}");
            // A reflectance under white light is its RGB.
            let white = |l: &SampledWavelengths| SampledSpectrum::illuminant(Rgb::ONE, (1.0, 1.0), l);
            let reflected = expected_rgb(|l| white(l) * SampledSpectrum::reflectance(rgb, l));
            assert!((reflected - rgb).abs().max_element() < 5e-3, "{rgb} reflects {reflected}");
        }
    }

    #[test]
    fn a_shifted_blackbody_is_the_hotter_blackbody_in_both_modes() {
        let (t, g) = (3000.0, 1.7);
        let spectral = expected_rgb(|l| SampledSpectrum::blackbody(t, 1.0, (g, g), l));
        let rgb = Rgb::blackbody(t, 1.0, (g, g), &());
        let hotter = Rgb::blackbody(g * t, 1.0, (1.0, 1.0), &());
        assert_eq!(rgb, hotter);
        assert!(((spectral - rgb).abs() / rgb).max_element() < 2e-3, "{spectral} vs {rgb}");
    }

    #[test]
    fn a_shifted_rgb_light_changes_colour_only_in_spectral_mode() {
        let (rgb, g) = (Rgb::new(1.0, 0.9, 0.8), 1.3);
        assert_eq!(Rgb::illuminant(rgb, (g, g), &()), rgb * g.powi(4) as f32);
        let shifted = expected_rgb(|l| SampledSpectrum::illuminant(rgb, (g, g), l));
        // Brighter by g⁴ in total (Y), and bluer.
        let (y, y_rest) = (linear_srgb_to_xyz(shifted.as_dvec3()).y, linear_srgb_to_xyz(rgb.as_dvec3()).y);
        assert!((y / y_rest / g.powi(4) - 1.0).abs() < 0.05, "Y ratio {}", y / y_rest);
        assert!(shifted.z / shifted.x > 1.3 * rgb.z / rgb.x, "{shifted}");
        // Colour only: the chromaticity moves, the luminance stays.
        let colour_only = expected_rgb(|l| SampledSpectrum::illuminant(rgb, (g, 1.0), l));
        let y_colour = linear_srgb_to_xyz(colour_only.as_dvec3()).y;
        assert!((y_colour / y_rest - 1.0).abs() < 0.05, "Y ratio {}", y_colour / y_rest);
        let xy = |c: Rgb| chromaticity(linear_srgb_to_xyz(c.as_dvec3()));
        assert!((xy(colour_only).0 - xy(shifted).0).abs() < 2e-3);
    }

    #[test]
    fn keeping_the_hero_keeps_its_estimate_unbiased() {
        let rgb = Rgb::new(0.2, 0.6, 0.9);
        let expected = expected_rgb(|l| SampledSpectrum::illuminant(rgb, (1.0, 1.0), l));
        let n = 4096;
        let hero_only = (0..n)
            .map(|k| {
                let mut lambda = SampledWavelengths::sample_visible((k as f32 + 0.5) / n as f32);
                SampledSpectrum::keep_hero(&mut lambda);
                SampledSpectrum::illuminant(rgb, (1.0, 1.0), &lambda).to_rgb(&lambda)
            })
            .sum::<Rgb>()
            / n as f32;
        assert!((hero_only - expected).abs().max_element() < 1e-2, "{hero_only} vs {expected}");
    }
}

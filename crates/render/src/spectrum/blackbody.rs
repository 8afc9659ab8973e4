//! Planck's law: the spectral radiance of a blackbody, its Wien peak, and a luminance-normalised
//! variant for emitters whose temperature sets their colour and whose scale sets their brightness.

use super::{cie, Spectrum};

/// Planck's constant h in J s (SI 2019, exact).
const PLANCK: f64 = 6.626_070_15e-34;
/// Speed of light c in m/s (SI, exact).
const SPEED_OF_LIGHT: f64 = 299_792_458.0;
/// Boltzmann's constant k in J/K (SI 2019, exact).
const BOLTZMANN: f64 = 1.380_649e-23;
/// Metres per nanometre.
const NM: f64 = 1e-9;

/// Wien's displacement constant b = hc / (k x), x = 4.965114231744276... the root of x = 5(1 − e⁻ˣ),
/// in m K (CODATA 2018: 2.897 771 955 × 10⁻³ m K): B_λ(T) peaks at λ = b / T.
pub const WIEN_DISPLACEMENT: f64 = 2.897_771_955e-3;

/// A blackbody at a temperature: B_λ(λ, T) = 2hc² / λ⁵ / (exp(hc / (λkT)) − 1), in
/// W sr⁻¹ m⁻² nm⁻¹ (radiance per nanometre of wavelength).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Blackbody {
    temperature: f64,
}

impl Blackbody {
    /// A blackbody at `temperature` kelvin; `None` unless it is finite and positive.
    pub fn new(temperature: f64) -> Option<Self> {
        (temperature.is_finite() && temperature > 0.0).then_some(Self { temperature })
    }

    /// The temperature in kelvin.
    pub fn temperature(&self) -> f64 {
        self.temperature
    }

    /// Wien's peak b / T in nm: the wavelength where B_λ is largest.
    pub fn peak_wavelength(&self) -> f64 {
        WIEN_DISPLACEMENT / self.temperature / NM
    }
}

impl Spectrum for Blackbody {
    fn eval(&self, lambda: f64) -> f64 {
        let l = lambda * NM;
        if !(l > 0.0) {
            return 0.0;
        }
        let x = PLANCK * SPEED_OF_LIGHT / (l * BOLTZMANN * self.temperature);
        2.0 * PLANCK * SPEED_OF_LIGHT * SPEED_OF_LIGHT / l.powi(5) / x.exp_m1() * NM
    }
}

/// A blackbody scaled to luminance Y = 1 (the convention of [`super`]), so that a temperature
/// changes an emitter's colour and not its brightness, and `temperature = 6500` is as bright as an
/// RGB emitter (1, 1, 1). Chosen over pbrt's peak-1 normalisation, whose luminance varies with T
/// by orders of magnitude. The scale is fixed at the rest temperature: a frequency shift of the
/// normalised spectrum still brightens it as g⁴ (see [`super::FrequencyShift`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct NormalizedBlackbody {
    blackbody: Blackbody,
    scale: f64,
}

impl NormalizedBlackbody {
    /// The blackbody at `temperature` kelvin scaled to Y = 1; `None` unless the temperature is
    /// finite and positive and the blackbody emits a representable luminance (above about 40 K).
    pub fn new(temperature: f64) -> Option<Self> {
        let blackbody = Blackbody::new(temperature)?;
        let scale = 1.0 / cie::xyz_quadrature(&blackbody).y;
        (scale.is_finite() && scale > 0.0).then_some(Self { blackbody, scale })
    }

    /// The unscaled blackbody.
    pub fn blackbody(&self) -> Blackbody {
        self.blackbody
    }
}

impl Spectrum for NormalizedBlackbody {
    fn eval(&self, lambda: f64) -> f64 {
        self.scale * self.blackbody.eval(lambda)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::spectrum::{chromaticity, test_support};

    #[test]
    fn wien_constant_follows_from_h_c_k() {
        // x = 5(1 − e⁻ˣ) by fixed-point iteration (a contraction near 4.97).
        let x = (0..60).fold(5.0, |x: f64, _| 5.0 * (1.0 - (-x).exp()));
        let b = PLANCK * SPEED_OF_LIGHT / (BOLTZMANN * x);
        assert!((b / WIEN_DISPLACEMENT - 1.0).abs() < 1e-9, "b = {b}");
    }

    #[test]
    fn wien_peak_is_the_maximum() {
        for t in [3000.0, 5772.0, 10_000.0] {
            let bb = Blackbody::new(t).unwrap();
            let peak = test_support::argmax(|l| bb.eval(l), 50.0, 5000.0);
            assert!((peak / bb.peak_wavelength() - 1.0).abs() < 1e-7, "{t} K: {peak}");
        }
    }

    #[test]
    fn sun_radiance_has_the_stefan_boltzmann_total() {
        // ∫ B_λ dλ = σT⁴/π, σ = 5.670374419e-8 W m⁻² K⁻⁴ (CODATA 2018); midpoint rule, 1e-6.
        let bb = Blackbody::new(5772.0).unwrap();
        let h = 0.5;
        let total: f64 = (0..400_000).map(|i| bb.eval((i as f64 + 0.5) * h) * h).sum();
        let expected = 5.670_374_419e-8 * 5772f64.powi(4) / std::f64::consts::PI;
        assert!((total / expected - 1.0).abs() < 1e-6, "{total} vs {expected}");
    }

    #[test]
    fn chromaticity_is_on_the_planckian_locus() {
        // Planckian locus, CIE 1931 observer, 1 nm over 360–830 nm, c2 = hc/k: 6500 K at
        // (0.31353, 0.32363) (as computed by colour-science 0.4.7 `sd_blackbody`; Wyszecki & Stiles
        // 1982 tabulate (0.3135, 0.3236)); illuminant A, defined as a 2856 K Planckian radiator,
        // at (0.44757, 0.40745) (CIE 015:2018 Table 3; its c2 = 1.435e-2 m K at 2848 K differs
        // from today's c2 by 3e-5 in x).
        for (t, x0, y0) in [(6500.0, 0.31353, 0.32363), (2856.0, 0.44757, 0.40745)] {
            let (x, y) = chromaticity(cie::xyz_quadrature(&Blackbody::new(t).unwrap()));
            assert!((x - x0).abs() < 1e-3 && (y - y0).abs() < 1e-3, "{t} K: ({x}, {y})");
        }
    }

    #[test]
    fn normalised_blackbody_has_unit_luminance_and_rejects_bad_temperatures() {
        for t in [1000.0, 5800.0, 40_000.0] {
            let y = cie::xyz_quadrature(&NormalizedBlackbody::new(t).unwrap()).y;
            assert!((y - 1.0).abs() < 1e-12, "{t} K: Y = {y}");
        }
        for t in [0.0, -5.0, f64::NAN, f64::INFINITY, 1.0] {
            assert!(NormalizedBlackbody::new(t).is_none(), "{t}");
        }
    }
}

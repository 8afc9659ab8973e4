//! The frequency shift of radiance between an emitter and an observer (gravity, Doppler).
//!
//! With g = ν_obs / ν_emit, I_ν / ν³ is invariant along a ray (Liouville; Misner, Thorne & Wheeler
//! §22.6). Since I_λ dλ = I_ν dν with ν = c/λ, I_λ = I_ν ν² / c, so I_λ / ν⁵ is invariant too; the
//! light seen at λ left the emitter at λ_emit = c/ν_emit = g λ, hence
//!
//!   I_λ,obs(λ) = g⁵ I_λ,emit(g λ).
//!
//! For a blackbody, g⁵ B_λ(g λ, T) = B_λ(λ, g T) exactly: a shifted blackbody is the blackbody at
//! g T with no other factor, its Wien peak moves from λ_max to λ_max / g, and its total radiance
//! grows as g⁴.

use super::Spectrum;

/// The frequency ratio g = ν_observed / ν_emitted between an emitter and an observer.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FrequencyShift {
    g: f64,
}

impl FrequencyShift {
    /// The shift with ratio `g`; `None` unless `g` is finite and positive.
    pub fn new(g: f64) -> Option<Self> {
        (g.is_finite() && g > 0.0).then_some(Self { g })
    }

    /// The ratio g.
    pub fn ratio(&self) -> f64 {
        self.g
    }

    /// The emitted spectral radiance `spectrum` as the observer sees it.
    pub fn apply<S: Spectrum>(self, spectrum: S) -> Shifted<S> {
        Shifted { g: self.g, spectrum }
    }
}

/// A spectral radiance seen through a [`FrequencyShift`]: g⁵ S(g λ).
#[derive(Clone, Copy, Debug)]
pub struct Shifted<S> {
    g: f64,
    spectrum: S,
}

impl<S: Spectrum> Spectrum for Shifted<S> {
    fn eval(&self, lambda: f64) -> f64 {
        self.g.powi(5) * self.spectrum.eval(self.g * lambda)
    }
}

impl<S: Spectrum + ?Sized> Spectrum for &S {
    fn eval(&self, lambda: f64) -> f64 {
        (**self).eval(lambda)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::spectrum::{Blackbody, NormalizedBlackbody};

    #[test]
    fn shifted_blackbody_is_the_blackbody_at_g_t() {
        for g in [0.3, 0.8, 1.0, 1.25, 3.0] {
            let shift = FrequencyShift::new(g).unwrap();
            let bb = Blackbody::new(5800.0).unwrap();
            let hotter = Blackbody::new(g * 5800.0).unwrap();
            let seen = shift.apply(bb);
            for lambda in [200.0, 360.0, 500.0, 830.0, 2000.0] {
                let (a, b) = (seen.eval(lambda), hotter.eval(lambda));
                assert!((a / b - 1.0).abs() < 1e-12, "g {g}, {lambda} nm: {a} vs {b}");
            }
            // The normalised emitter keeps its rest scale: it brightens instead of staying at Y = 1.
            let norm = NormalizedBlackbody::new(5800.0).unwrap();
            let ratio = shift.apply(norm).eval(600.0) / norm.eval(600.0);
            assert!((ratio / (hotter.eval(600.0) / bb.eval(600.0)) - 1.0).abs() < 1e-12);
        }
    }

    #[test]
    fn wien_peak_moves_by_exactly_g() {
        let bb = Blackbody::new(4000.0).unwrap();
        for g in [0.5, 0.9, 1.1, 2.0] {
            let seen = FrequencyShift::new(g).unwrap().apply(bb);
            let peak = crate::spectrum::test_support::argmax(|l| seen.eval(l), 50.0, 10_000.0);
            let expected = bb.peak_wavelength() / g;
            assert!((peak / expected - 1.0).abs() < 1e-6, "g {g}: {peak} vs {expected}");
        }
    }

    #[test]
    fn rejects_bad_ratios() {
        for g in [0.0, -1.0, f64::NAN, f64::INFINITY] {
            assert!(FrequencyShift::new(g).is_none(), "{g}");
        }
    }
}

//! A blackbody emitter: Planck's law at a temperature, scaled to a luminance at rest
//! (`emission = { temperature = 5800, luminance = 1 }`). Seen with frequency ratio `g` it is the
//! blackbody at `gT` (`g⁵ B_λ(gλ, T) = B_λ(λ, gT)`), so gravity and motion change its colour as
//! well as its brightness.

use crate::rgb::Rgb;
use crate::spectrum::{BlackbodyColours, Colour};

/// Planck's law at `temperature` kelvin, scaled so that its luminance at rest is `luminance`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BlackbodyLight {
    temperature: f64,
    luminance: f64,
    /// `luminance / Y(B(T))`.
    scale: f64,
}

impl BlackbodyLight {
    /// `None` unless the temperature is finite and at least 100 K (cooler bodies emit nothing
    /// visible) and the luminance finite and not negative.
    pub fn new(temperature: f64, luminance: f64) -> Option<Self> {
        let y = BlackbodyColours::get().luminance(temperature);
        let valid = temperature.is_finite() && y > 0.0 && luminance.is_finite() && luminance >= 0.0;
        valid.then(|| Self { temperature, luminance, scale: luminance / y })
    }

    pub fn temperature(&self) -> f64 {
        self.temperature
    }

    /// The luminance at rest.
    pub fn luminance(&self) -> f64 {
        self.luminance
    }

    /// `luminance / Y(B(T))`: what Planck's law is multiplied by.
    pub(super) fn scale(&self) -> f64 {
        self.scale
    }

    /// The linear Rec. 709 radiance seen with frequency ratio `g`: the blackbody at `gT`.
    pub fn seen(&self, g: f64) -> Rgb {
        Rgb::blackbody(self.temperature, self.scale, (g, g), &())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::spectrum::{chromaticity, linear_srgb_to_xyz};

    #[test]
    fn the_colour_is_planckian_and_moves_along_the_locus_with_g() {
        // 6500 K on the Planckian locus at (0.31353, 0.32363) (CIE 1931, 1 nm); seen with g = 0.5
        // from 13 000 K it is the same blackbody.
        let at = |light: BlackbodyLight, g: f64| chromaticity(linear_srgb_to_xyz(light.seen(g).as_dvec3()));
        let (x, y) = at(BlackbodyLight::new(6500.0, 1.0).unwrap(), 1.0);
        assert!((x - 0.31353).abs() < 1e-3 && (y - 0.32363).abs() < 1e-3, "({x}, {y})");
        let (xs, ys) = at(BlackbodyLight::new(13_000.0, 1.0).unwrap(), 0.5);
        assert!((xs - x).abs() < 1e-5 && (ys - y).abs() < 1e-5);
        assert!(BlackbodyLight::new(50.0, 1.0).is_none() && BlackbodyLight::new(3000.0, -1.0).is_none());
    }
}

//! What a medium emits: radiance per unit of its rest-frame length, times its density. A slab
//! of thickness `L` that absorbs nothing adds `emission × L`; one of absorption `α` adds
//! `(j/α)(1 − e^{−αL})` and no more than `j/α` however thick (its source function).
//!
//! Emission is given in the gas's rest frame and seen at a frequency ratio `g` as
//! [`super::shift`] derives: per unit rest-frame length it shifts exactly as a surface's
//! radiance does, so the renderer's [`Colour`] shifts serve it.

use super::grid::Grid;
use crate::geometry::Vec3;
use crate::rgb::Rgb;
use crate::spectrum::Colour;

#[derive(Clone, Debug)]
pub enum Emission {
    None,
    /// Linear Rec. 709 radiance per unit length: grey, brightened by `g⁴` in RGB and lifted to a
    /// spectrum and shifted in spectral mode, like an RGB light.
    Rgb(Rgb),
    /// `scale` times Planck's law at the temperature (the units of
    /// [`crate::spectrum::BlackbodyColours`], W sr⁻¹ m⁻² nm⁻¹, per unit length): seen at `g`, the
    /// blackbody at `gT`. Gas in local thermodynamic equilibrium emits `α B(T)` (Kirchhoff): its
    /// `scale` is its absorption coefficient.
    Blackbody {
        temperature: Temperature,
        scale: f64,
    },
    /// A power law `j_ν ∝ ν^{−index}` of colour `colour` at rest (optically thin synchrotron
    /// radiation has `index ≈ 0.5–1`): seen at `g`, the same colour `g^{3+index}` times as bright.
    PowerLaw {
        colour: Rgb,
        index: f64,
    },
}

/// A temperature field in kelvin.
#[derive(Clone, Debug)]
pub enum Temperature {
    Uniform(f64),
    /// Kelvin at the grid's samples (0 outside its box: no light).
    Grid(Grid),
}

impl Temperature {
    pub fn at(&self, p: Vec3) -> f64 {
        match self {
            Self::Uniform(kelvin) => *kelvin,
            Self::Grid(grid) => grid.at(p),
        }
    }
}

impl Emission {
    /// The radiance emitted per unit rest-frame length at the world point `p`, where the
    /// density is `density`, seen with frequency ratio `g = ν_seen/ν_rest`.
    pub fn seen<C: Colour>(&self, p: Vec3, density: f64, g: f64, lambda: &C::Lambda) -> C {
        match self {
            Self::None => C::ZERO,
            Self::Rgb(rgb) => C::illuminant(*rgb * density as f32, (g, g), lambda),
            Self::Blackbody { temperature, scale } => C::blackbody(temperature.at(p), scale * density, (g, g), lambda),
            // Brightened by b⁴ = g^{3+index}, colour unshifted.
            Self::PowerLaw { colour, index } => {
                C::illuminant(*colour * density as f32, (1.0, g.powf((3.0 + index) / 4.0)), lambda)
            }
        }
    }

    /// Whether it emits at all (a path need not look for it otherwise).
    pub fn is_none(&self) -> bool {
        matches!(self, Self::None)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::spectrum::BlackbodyColours;

    #[test]
    fn rgb_emission_scales_with_density_and_g_to_the_fourth() {
        let e = Emission::Rgb(Rgb::new(1.0, 2.0, 3.0));
        let seen: Rgb = e.seen(Vec3::ZERO, 0.5, 2.0, &());
        assert_eq!(seen, Rgb::new(8.0, 16.0, 24.0));
    }

    #[test]
    fn a_power_law_keeps_its_colour_and_brightens_as_g_to_three_plus_index() {
        let e = Emission::PowerLaw { colour: Rgb::new(1.0, 0.5, 0.25), index: 0.7 };
        let seen: Rgb = e.seen(Vec3::ZERO, 1.0, 1.5, &());
        let factor = 1.5f64.powf(3.7) as f32;
        assert!((seen - Rgb::new(1.0, 0.5, 0.25) * factor).abs().max_element() < 1e-5 * factor);
    }

    #[test]
    fn a_shifted_blackbody_is_the_blackbody_at_g_t() {
        let e = Emission::Blackbody { temperature: Temperature::Uniform(3000.0), scale: 1.0 };
        let seen: Rgb = e.seen(Vec3::ZERO, 1.0, 2.0, &());
        let (rgb, _) = BlackbodyColours::get().at(6000.0);
        for c in 0..3 {
            assert!((f64::from(seen[c]) / rgb[c] - 1.0).abs() < 1e-5, "{seen} against {rgb:?}");
        }
    }
}

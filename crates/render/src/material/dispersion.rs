//! A glass whose index of refraction varies with wavelength, so that it splits white light into
//! rainbows. Scene files give a dielectric's `ior` at the Fraunhofer d line (587.56 nm) and its
//! Abbe number `abbe` (`V_d = (n_d − 1)/(n_F − n_C)`, as glass catalogues and Blender list it:
//! BK7 is `ior = 1.5168, abbe = 64.17`, flint SF11 `ior = 1.7847, abbe = 25.68`); the index
//! follows Cauchy's law `n(λ) = A + B/λ²` through those two numbers.
//!
//! Only spectral rendering can show dispersion: a path then refracts at its hero wavelength and
//! carries that one wavelength on ([`crate::spectrum::Colour::keep_hero`]). RGB rendering uses
//! the index at the d line.

/// The Fraunhofer lines the Abbe number is defined by, in nm: d (helium), F and C (hydrogen).
const D_LINE: f64 = 587.56;
const F_LINE: f64 = 486.13;
const C_LINE: f64 = 656.27;

/// Cauchy's law `n(λ) = a + b/λ²`, λ in nm.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Dispersion {
    a: f64,
    b: f64,
}

impl Dispersion {
    /// The law through the index `ior_d` at the d line with Abbe number `abbe`; `None` unless
    /// `ior_d > 1` (a glass denser than its surroundings, whose index falls with wavelength) and
    /// `abbe` is positive and finite.
    pub fn from_abbe(ior_d: f64, abbe: f64) -> Option<Self> {
        if !(ior_d > 1.0 && ior_d.is_finite() && abbe > 0.0 && abbe.is_finite()) {
            return None;
        }
        let b = (ior_d - 1.0) / (abbe * (F_LINE.powi(-2) - C_LINE.powi(-2)));
        Some(Self { a: ior_d - b / (D_LINE * D_LINE), b })
    }

    /// The index of refraction at `lambda` nm.
    pub fn ior(&self, lambda: f64) -> f64 {
        self.a + self.b / (lambda * lambda)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_law_meets_its_index_and_abbe_number() {
        let bk7 = Dispersion::from_abbe(1.5168, 64.17).unwrap();
        assert!((bk7.ior(D_LINE) - 1.5168).abs() < 1e-12);
        let abbe = (bk7.ior(D_LINE) - 1.0) / (bk7.ior(F_LINE) - bk7.ior(C_LINE));
        assert!((abbe - 64.17).abs() < 1e-9, "{abbe}");
        // Schott's BK7 at 400 and 700 nm is 1.5308 and 1.5131: Cauchy's two terms are close.
        assert!((bk7.ior(400.0) - 1.5308).abs() < 2e-3 && (bk7.ior(700.0) - 1.5131).abs() < 1e-3);
        assert!(Dispersion::from_abbe(1.0, 50.0).is_none() && Dispersion::from_abbe(1.5, 0.0).is_none());
    }
}

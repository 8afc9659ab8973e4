//! Participating media: gas, fog, smoke and clouds that absorb, scatter and emit light along a
//! ray rather than at a surface (docs/media.md).
//!
//! A [`Medium`] is a medium's coefficients per scene unit of length, in the medium's rest frame —
//! absorption `σ_a`, scattering `σ_s`, the Henyey–Greenstein phase function's `g`, an emission —
//! times a [`Density`] field, a pure number. Light is carried through it by tracking
//! ([`tracking`]) along each straight chord of a geodesic, against piecewise-constant bounds of
//! its extinction ([`majorant`]), with [`reference`] as the deterministic check. How emission
//! and absorption look at a frequency ratio `g` is [`shift`]'s.
//!
//! | module        | holds                                                                   |
//! |---------------|-------------------------------------------------------------------------|
//! | [`phase`]     | the Henyey–Greenstein phase function: evaluation, exact sampling         |
//! | [`density`]   | density fields: uniform, procedural noise, grids                        |
//! | [`grid`]      | scalar fields on a 3-D grid, trilinear                                   |
//! | [`noise`]     | fBm of gradient noise, bounded                                          |
//! | [`emission`]  | RGB, blackbody and power-law emission                                   |
//! | [`shift`]     | the invariants `j_ν/ν²`, `ν α_ν`, and the factors they give at `g`      |
//! | [`majorant`]  | extinction bounds: constant, or per grid brick walked by a DDA          |
//! | [`tracking`]  | delta tracking (free flights) and ratio tracking (transmittance)         |
//! | [`reference`] | dense quadrature of transmittance and emission                           |

pub mod density;
pub mod emission;
pub mod grid;
pub mod majorant;
pub mod noise;
pub mod phase;
pub mod reference;
pub mod shift;
#[cfg(test)]
mod test_media;
pub mod tracking;

pub use density::Density;
pub use emission::{Emission, Temperature};
pub use majorant::{MajorantSegment, MajorantWalk, Majorants};
pub use phase::{HenyeyGreenstein, PhaseSample};
pub use tracking::{Chord, Collision, Event, FreeFlight, RatioTracker};

use crate::geometry::Vec3;
use crate::spectrum::Colour;
use std::fmt;

/// A participating medium, in its rest frame.
#[derive(Clone, Debug)]
pub struct Medium {
    /// `σ_a` per scene unit of rest-frame length, at density 1.
    absorption: f64,
    /// `σ_s` per scene unit of rest-frame length, at density 1.
    scattering: f64,
    phase: HenyeyGreenstein,
    emission: Emission,
    density: Density,
    majorants: Majorants,
}

/// A medium's coefficients at a point (its own times the density there), per unit rest-frame
/// length.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Coefficients {
    pub absorption: f64,
    pub scattering: f64,
}

impl Coefficients {
    /// `σ_t = σ_a + σ_s`.
    pub fn extinction(&self) -> f64 {
        self.absorption + self.scattering
    }
}

/// Why a medium could not be made.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum MediumError {
    /// `absorption` or `scattering` is negative, NaN or infinite.
    InvalidCoefficient { name: &'static str, value: f64 },
}

impl fmt::Display for MediumError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::InvalidCoefficient { name, value } => {
                write!(f, "`{name}` is {value}, and must be a finite number, 0 or more (per scene unit of length)")
            }
        }
    }
}

impl std::error::Error for MediumError {}

impl Medium {
    /// A medium of `absorption` and `scattering` per scene unit of rest-frame length where the
    /// density is 1.
    pub fn new(
        absorption: f64,
        scattering: f64,
        phase: HenyeyGreenstein,
        emission: Emission,
        density: Density,
    ) -> Result<Self, MediumError> {
        for (name, value) in [("absorption", absorption), ("scattering", scattering)] {
            if !(value.is_finite() && value >= 0.0) {
                return Err(MediumError::InvalidCoefficient { name, value });
            }
        }
        let majorants = Majorants::of(&density);
        Ok(Self { absorption, scattering, phase, emission, density, majorants })
    }

    pub fn phase(&self) -> &HenyeyGreenstein {
        &self.phase
    }

    pub fn emission(&self) -> &Emission {
        &self.emission
    }

    pub fn density(&self) -> &Density {
        &self.density
    }

    /// The coefficients at the world point `p`.
    pub fn coefficients(&self, p: Vec3) -> Coefficients {
        let density = self.density.at(p);
        Coefficients { absorption: self.absorption * density, scattering: self.scattering * density }
    }

    /// The single-scattering albedo `σ_s/σ_t` (the same everywhere: both scale with density).
    pub fn albedo(&self) -> f64 {
        let extinction = self.absorption + self.scattering;
        if extinction > 0.0 {
            self.scattering / extinction
        } else {
            0.0
        }
    }

    /// The emission per unit rest-frame length at `p`, seen with frequency ratio `g`.
    pub fn emission_seen<C: Colour>(&self, p: Vec3, g: f64, lambda: &C::Lambda) -> C {
        self.emission.seen(p, self.density.at(p), g, lambda)
    }

    /// The bounds of the extinction (per unit rest-frame length) along `chord`, for tracking.
    pub fn majorants(&self, chord: &Chord) -> MajorantWalk<'_> {
        self.majorants.walk(chord.origin, chord.dir, chord.length, self.absorption + self.scattering)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::rgb::Rgb;

    fn slab(absorption: f64, emission: Rgb) -> Medium {
        Medium::new(absorption, 0.0, HenyeyGreenstein::ISOTROPIC, Emission::Rgb(emission), Density::Uniform).unwrap()
    }

    /// A uniform slab of thickness `L` adds `emission × L` when it absorbs nothing and
    /// `(j/α)(1 − e^{−αL})` when it absorbs `α`, to 1e-6, however few the quadrature's steps;
    /// emission per rest-frame length: a chord whose rest-frame length is twice its world
    /// length glows twice as much.
    #[test]
    fn a_uniform_slab_adds_its_emission_times_its_thickness() {
        let j = Rgb::new(0.25, 1.0, 3.0);
        for length in [0.1, 1.0, 7.5] {
            for steps in [1, 7, 1000] {
                let chord = Chord::flat(Vec3::ZERO, Vec3::Z, length);
                let (radiance, t) = reference::emitted(&slab(0.0, j), &chord, steps, 1.0);
                assert_eq!(t, 1.0);
                for c in 0..3 {
                    let exact = f64::from(j[c]) * length;
                    assert!((f64::from(radiance[c]) - exact).abs() <= 1e-6 * exact, "L {length}: {radiance}");
                }
                let alpha = 1.5;
                let (radiance, t) = reference::emitted(&slab(alpha, j), &chord, steps, 1.0);
                assert!((t - (-alpha * length).exp()).abs() < 1e-12);
                for c in 0..3 {
                    let exact = f64::from(j[c]) / alpha * (1.0 - (-alpha * length).exp());
                    assert!(
                        (f64::from(radiance[c]) - exact).abs() <= 1e-6 * exact,
                        "L {length}, α {alpha}: {radiance}"
                    );
                }
            }
        }
        let stretched = Chord { rest_length: 2.0, ..Chord::flat(Vec3::ZERO, Vec3::Z, 1.0) };
        let (radiance, _) = reference::emitted(&slab(0.0, j), &stretched, 3, 1.0);
        assert!((radiance - 2.0 * j).abs().max_element() < 1e-6);
    }

    /// The absorption estimator of emission: a path absorbed at a collision gathers `j/σ_a`
    /// there, so its mean over delta-tracked flights is the emission-absorption radiance (in a
    /// scattering-free slab), within 4 standard errors.
    #[test]
    fn absorbed_flights_gather_the_emitted_radiance() {
        let (alpha, length) = (0.8, 2.0);
        let j = Rgb::new(1.0, 0.5, 2.0);
        let medium = slab(alpha, j);
        let chord = Chord::flat(Vec3::ZERO, Vec3::Z, length);
        let mut rng = crate::sampling::Rng::new(4);
        let n = 40_000;
        let gathered: Vec<f64> = (0..n)
            .map(|_| {
                let mut flight = FreeFlight::start(rng.next_f64());
                match flight.track(&medium, &chord, medium.majorants(&chord), &mut || rng.next_f64()) {
                    Event::Absorb(c) => {
                        let e: Rgb = medium.emission_seen(c.point, 1.0, &());
                        f64::from(e.y) / medium.coefficients(c.point).absorption
                    }
                    Event::Scatter(_) | Event::Passed => 0.0,
                }
            })
            .collect();
        let mean = gathered.iter().sum::<f64>() / n as f64;
        let var = gathered.iter().map(|g| (g - mean).powi(2)).sum::<f64>() / (n - 1) as f64;
        let exact = 0.5 / alpha * (1.0 - (-alpha * length).exp());
        assert!((mean - exact).abs() < 4.0 * (var / n as f64).sqrt(), "mean {mean}, exact {exact}");
    }

    #[test]
    fn refuses_invalid_coefficients() {
        let make = |a, s| Medium::new(a, s, HenyeyGreenstein::ISOTROPIC, Emission::None, Density::Uniform);
        assert!(matches!(make(-1.0, 0.0), Err(MediumError::InvalidCoefficient { name: "absorption", .. })));
        assert!(matches!(make(0.0, f64::NAN), Err(MediumError::InvalidCoefficient { name: "scattering", .. })));
        assert!((make(1.0, 3.0).unwrap().albedo() - 0.75).abs() < 1e-15);
    }
}

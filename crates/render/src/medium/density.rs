//! Where a medium is dense: its coefficients are the medium's own times a density field, a
//! pure number, so one medium (an absorption, a scattering, an emission) can fill space evenly,
//! in procedural clouds or as a grid read from a file.

use super::grid::Grid;
use super::noise::NoiseDensity;
use crate::geometry::Vec3;

#[derive(Clone, Debug)]
pub enum Density {
    /// 1 everywhere (in whatever region the medium fills).
    Uniform,
    /// Fractional Brownian motion of gradient noise, in `[0, 1]`.
    Noise(NoiseDensity),
    /// Samples on a grid, 0 outside its box.
    Grid(Grid),
}

impl Density {
    /// The density at the world point `p`.
    pub fn at(&self, p: Vec3) -> f64 {
        match self {
            Self::Uniform => 1.0,
            Self::Noise(noise) => noise.at(p),
            Self::Grid(grid) => grid.at(p),
        }
    }

    /// No density anywhere exceeds this.
    pub fn max(&self) -> f64 {
        match self {
            Self::Uniform => 1.0,
            Self::Noise(_) => NoiseDensity::MAX,
            Self::Grid(grid) => grid.max(),
        }
    }
}

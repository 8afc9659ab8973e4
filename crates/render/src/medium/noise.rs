//! A procedural density: fractional Brownian motion of Perlin's gradient noise (the `noise`
//! crate's `Fbm<Perlin>`; Perlin 2002, "Improving noise"; Musgrave's fBm in Ebert et al.,
//! *Texturing & Modeling*), as clouds and nebulae are usually made.
//!
//! The density is `clamp(½ + ½·contrast·fbm(frequency·p), 0, 1)`: ½ on average, and never above
//! 1, which is the bound the tracking's majorant uses. (The crate's fBm is only approximately
//! within `[−1, 1]`; the clamp makes the bound exact rather than hoped for.)

use crate::geometry::Vec3;
use noise::{Fbm, MultiFractal, NoiseFn, Perlin};

/// The settings of a noise density.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct NoiseSettings {
    /// Features per scene unit of length.
    pub frequency: f64,
    /// Layers of noise, each `lacunarity` times finer and `persistence` times weaker.
    pub octaves: usize,
    pub lacunarity: f64,
    pub persistence: f64,
    /// How far the density swings about ½ (1: the noise's full range).
    pub contrast: f64,
    pub seed: u32,
}

impl Default for NoiseSettings {
    fn default() -> Self {
        Self { frequency: 1.0, octaves: 5, lacunarity: 2.0, persistence: 0.5, contrast: 1.0, seed: 0 }
    }
}

#[derive(Clone, Debug)]
pub struct NoiseDensity {
    settings: NoiseSettings,
    fbm: Fbm<Perlin>,
}

impl NoiseDensity {
    /// The most octaves the `noise` crate layers.
    pub const MAX_OCTAVES: usize = Fbm::<Perlin>::MAX_OCTAVES;

    /// `None` unless the frequency, lacunarity and persistence are finite and positive, the
    /// contrast finite and not negative, and `1 ≤ octaves ≤ MAX_OCTAVES`.
    pub fn new(settings: NoiseSettings) -> Option<Self> {
        let positive = |v: f64| v.is_finite() && v > 0.0;
        let valid = positive(settings.frequency)
            && positive(settings.lacunarity)
            && positive(settings.persistence)
            && settings.contrast.is_finite()
            && settings.contrast >= 0.0
            && (1..=Self::MAX_OCTAVES).contains(&settings.octaves);
        valid.then(|| {
            let fbm = Fbm::<Perlin>::new(settings.seed)
                .set_octaves(settings.octaves)
                .set_frequency(settings.frequency)
                .set_lacunarity(settings.lacunarity)
                .set_persistence(settings.persistence);
            Self { settings, fbm }
        })
    }

    pub fn settings(&self) -> &NoiseSettings {
        &self.settings
    }

    /// The density at the world point `p`, in `[0, 1]`.
    pub fn at(&self, p: Vec3) -> f64 {
        (0.5 + 0.5 * self.settings.contrast * self.fbm.get(p.to_array())).clamp(0.0, 1.0)
    }

    /// No density exceeds this.
    pub const MAX: f64 = 1.0;
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::sampling::Rng;

    #[test]
    fn the_density_stays_within_its_bound_and_varies() {
        let noise = NoiseDensity::new(NoiseSettings { contrast: 3.0, ..NoiseSettings::default() }).unwrap();
        let mut rng = Rng::new(1);
        let values: Vec<f64> =
            (0..10_000).map(|_| noise.at(Vec3::new(rng.next_f64(), rng.next_f64(), rng.next_f64()) * 8.0)).collect();
        assert!(values.iter().all(|v| (0.0..=NoiseDensity::MAX).contains(v)));
        let mean = values.iter().sum::<f64>() / values.len() as f64;
        assert!((0.3..0.7).contains(&mean), "mean {mean}");
        assert!(values.iter().any(|&v| v < 0.2) && values.iter().any(|&v| v > 0.8), "a contrast of 3 saturates");
    }

    #[test]
    fn refuses_invalid_settings() {
        for settings in [
            NoiseSettings { octaves: 0, ..NoiseSettings::default() },
            NoiseSettings { octaves: NoiseDensity::MAX_OCTAVES + 1, ..NoiseSettings::default() },
            NoiseSettings { frequency: 0.0, ..NoiseSettings::default() },
            NoiseSettings { contrast: f64::NAN, ..NoiseSettings::default() },
        ] {
            assert!(NoiseDensity::new(settings).is_none(), "{settings:?}");
        }
    }
}

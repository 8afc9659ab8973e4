//! Media the tests of this module share.

use super::grid::Grid;
use super::noise::{NoiseDensity, NoiseSettings};
use super::{Density, Emission, HenyeyGreenstein, Medium};
use crate::geometry::{Aabb, Vec3};
use crate::transform::Transform;

/// A homogeneous medium of absorption `a` and scattering `s`.
pub fn uniform(a: f64, s: f64) -> Medium {
    Medium::new(a, s, HenyeyGreenstein::ISOTROPIC, Emission::None, Density::Uniform).expect("a valid medium")
}

/// A lumpy cloud on a 24³ grid over `[−1, 1]³`: a smooth blob with a denser core and a hole,
/// absorption 0.25 and scattering 0.5 at density 1.
pub fn cloud() -> Medium {
    let n = 24;
    let mut values = Vec::with_capacity(n * n * n);
    for k in 0..n {
        for j in 0..n {
            for i in 0..n {
                let p = (Vec3::new(i as f64, j as f64, k as f64) + 0.5) / n as f64 * 2.0 - Vec3::ONE;
                let blob = (1.0 - p.length_squared()).max(0.0);
                let core = (-20.0 * (p - Vec3::new(0.3, -0.2, 0.1)).length_squared()).exp();
                let hole = f64::from((p - Vec3::new(-0.4, 0.3, 0.0)).length() > 0.25);
                values.push(((blob + 2.0 * core) * hole) as f32);
            }
        }
    }
    let bounds = Aabb::new(-Vec3::ONE, Vec3::ONE);
    let grid = Grid::new([n, n, n], values, bounds, &Transform::IDENTITY).expect("a valid grid");
    Medium::new(0.25, 0.5, HenyeyGreenstein::ISOTROPIC, Emission::None, Density::Grid(grid)).expect("a valid medium")
}

/// fBm noise, absorption 0.3 and scattering 0.4 at density 1.
pub fn noise_cloud() -> Medium {
    let noise = NoiseDensity::new(NoiseSettings { frequency: 1.5, contrast: 2.0, ..NoiseSettings::default() })
        .expect("valid noise");
    Medium::new(0.3, 0.4, HenyeyGreenstein::new(0.5).expect("a valid g"), Emission::None, Density::Noise(noise))
        .expect("a valid medium")
}

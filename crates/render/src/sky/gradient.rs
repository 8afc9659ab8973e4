//! # Gradient sky (`type = "gradient"`)
//!
//! A smooth sky for quick scenes: the colour blends linearly in `sin(elevation) = dir·up` from `horizon`
//! (at the horizon) to `zenith` (straight up), and below the horizon from `horizon` to `nadir`
//! (straight down). Set `nadir = horizon` for a uniform ground.
//!
//! | parameter  | type    | default              | meaning                                 |
//! |------------|---------|----------------------|-----------------------------------------|
//! | `horizon`  | colour  | `[0.9, 0.9, 1.0]`    | radiance at elevation 0                 |
//! | `zenith`   | colour  | `[0.3, 0.5, 0.9]`    | radiance straight up                    |
//! | `nadir`    | colour  | = `horizon`          | radiance straight down                  |
//! | `up`       | vector  | `[0, 1, 0]`          | the world's up (y-up by default)        |
//!
//! ```toml
//! [sky]
//! type = "gradient"
//! horizon = [0.9, 0.9, 1.0]
//! zenith = [0.3, 0.5, 0.9]
//! ```

use super::SkyFrame;
use crate::geometry::Vec3;
use crate::rgb::Rgb;

#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Gradient {
    pub horizon: Rgb,
    pub zenith: Rgb,
    pub nadir: Rgb,
    /// Only its `up` matters.
    pub frame: SkyFrame,
}

impl Gradient {
    pub fn radiance(&self, dir: Vec3) -> Rgb {
        let s = dir.dot(self.frame.up()).clamp(-1.0, 1.0) as f32;
        if s >= 0.0 {
            self.horizon.lerp(self.zenith, s)
        } else {
            self.horizon.lerp(self.nadir, -s)
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn endpoints_and_midpoint() {
        let g = Gradient {
            horizon: Rgb::new(1.0, 1.0, 1.0),
            zenith: Rgb::new(0.0, 0.0, 1.0),
            nadir: Rgb::new(0.2, 0.1, 0.0),
            frame: SkyFrame::Y_UP,
        };
        assert_eq!(g.radiance(Vec3::Y), g.zenith);
        assert_eq!(g.radiance(Vec3::NEG_Y), g.nadir);
        assert_eq!(g.radiance(Vec3::X), g.horizon);
        assert_eq!(g.radiance(Vec3::NEG_Z), g.horizon);
        // 30° elevation: sin = 1/2, halfway.
        let d = Vec3::new(0.0, 0.5, -(0.75f64).sqrt());
        assert!((g.radiance(d) - Rgb::new(0.5, 0.5, 1.0)).abs().max_element() < 1e-6);
        // A z-up world.
        let z_up = Gradient { frame: SkyFrame::new(Vec3::Z, 0.0).unwrap(), ..g };
        assert_eq!(z_up.radiance(Vec3::Z), g.zenith);
        assert_eq!(z_up.radiance(Vec3::Y), g.horizon);
    }
}

//! Skies: the radiance arriving from infinitely far away, looked up with the direction in which a traced
//! ray escapes (in an asymptotically flat region, once spacetime is flat enough to stop integrating).
//!
//! | `type`       | variant             | file           | what                                                |
//! |--------------|---------------------|----------------|-----------------------------------------------------|
//! | `"constant"` | [`Sky::Constant`]   | —              | one colour (a white furnace, a black void)          |
//! | `"gradient"` | [`Sky::Gradient`]   | [`gradient`]   | horizon → zenith (and → nadir) colours              |
//! | `"equirect"` | [`Sky::Equirect`]   | [`equirect`]   | a latitude–longitude panorama (PNG / EXR / HDR)     |
//! | `"stars"`    | [`Sky::StarField`]  | [`stars`]      | procedural stars of finite size, any resolution     |
//! | `"grid"`     | [`Sky::Grid`]       | [`grid`]       | latitude–longitude lines for lensing diagrams       |
//!
//! # Orientation
//! The world is **y-up** (a camera's up vector defaults to `+y`), and a sky's *forward* direction — the
//! centre of a panorama, the prime meridian of a grid — is **`−z`**, with `+x` to its right: longitude
//! increases from forward toward right (east), latitude from the horizon toward up. A sky can be turned
//! with [`SkyFrame::new`]`(up, rotation_deg)`, which every oriented sky carries. Directions are unit
//! vectors in the world (region) frame of the sky they are looked up in.
//!
//! Every lookup is allocation-free.
//!
//! ```toml
//! [sky]
//! type = "constant"
//! radiance = [0.1, 0.1, 0.1]
//! ```

pub mod distribution;
pub mod equirect;
pub mod gradient;
pub mod grid;
pub mod stars;

pub use distribution::{SkyDistribution, SkySample};
pub use equirect::{Equirect, EquirectDistribution};
pub use gradient::Gradient;
pub use grid::LatLongGrid;
pub use stars::{Star, StarDistribution, StarField, StarFieldParams};

use crate::geometry::Vec3;
use crate::rgb::Rgb;
use crate::spectrum::Colour;

/// The radiance from infinity in each direction. See the module documentation.
#[derive(Clone, Debug)]
pub enum Sky {
    Constant(Rgb),
    Gradient(Gradient),
    Equirect(Equirect),
    StarField(StarField),
    Grid(LatLongGrid),
}

impl Sky {
    /// Radiance arriving from the unit world direction `dir` (the direction the escaping ray travels in).
    pub fn radiance(&self, dir: Vec3) -> Rgb {
        match self {
            Sky::Constant(c) => *c,
            Sky::Gradient(g) => g.radiance(dir),
            Sky::Equirect(e) => e.radiance(dir),
            Sky::StarField(s) => s.radiance(dir),
            Sky::Grid(g) => g.radiance(dir),
        }
    }

    /// [`Sky::radiance`] seen with its colour shifted by one ratio and its brightness by another
    /// (`shown`, [`crate::emission::Shift::shown`]), in the colours `C` at `lambda`: a star field's
    /// stars as blackbodies, every other sky as its RGB colour lifted ([`Colour::illuminant`]).
    pub fn seen<C: Colour>(&self, dir: Vec3, shown: (f64, f64), lambda: &C::Lambda) -> C {
        match self {
            Sky::StarField(s) => s.seen(dir, shown, lambda),
            Sky::Constant(_) | Sky::Gradient(_) | Sky::Equirect(_) | Sky::Grid(_) => {
                C::illuminant(self.radiance(dir), shown, lambda)
            }
        }
    }
}

/// The orientation of a sky: an orthonormal, right-handed frame `(right, up, back)` with
/// `forward = −back` the direction of longitude 0 on the horizon.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SkyFrame {
    right: Vec3,
    up: Vec3,
    forward: Vec3,
}

impl Default for SkyFrame {
    fn default() -> Self {
        Self::Y_UP
    }
}

impl SkyFrame {
    /// Up `+y`, forward `−z`, right `+x`.
    pub const Y_UP: SkyFrame = SkyFrame { right: Vec3::X, up: Vec3::Y, forward: Vec3::NEG_Z };

    /// A frame with the given `up` (normalised here; must be non-zero and finite) and the sky turned by
    /// `rotation_deg` about it, counter-clockwise seen from above (right-hand rule): what was at
    /// longitude 0 appears `rotation_deg` to the left of where it was. Before the rotation, forward is
    /// `−z` made perpendicular to `up` (or `+y` when `up` is along `z`).
    pub fn new(up: Vec3, rotation_deg: f64) -> Result<Self, String> {
        let up = up.try_normalize().ok_or_else(|| format!("sky up vector {up} must be non-zero and finite"))?;
        if !rotation_deg.is_finite() {
            return Err(format!("sky rotation {rotation_deg}° must be finite"));
        }
        let reject = |v: Vec3| (v - up * v.dot(up)).try_normalize().filter(|_| v.cross(up).length() > 1e-6);
        let forward0 = reject(Vec3::NEG_Z).or_else(|| reject(Vec3::Y)).unwrap_or(Vec3::X);
        let (sin, cos) = rotation_deg.to_radians().sin_cos();
        let forward = (forward0 * cos + up.cross(forward0) * sin).normalize();
        Ok(Self { right: forward.cross(up), up, forward })
    }

    pub fn up(&self) -> Vec3 {
        self.up
    }

    /// Longitude 0 on the horizon.
    pub fn forward(&self) -> Vec3 {
        self.forward
    }

    /// Longitude +90° on the horizon.
    pub fn right(&self) -> Vec3 {
        self.right
    }

    /// `(latitude, longitude)` of a unit direction in radians: latitude in `[−π/2, π/2]` (up is +π/2),
    /// longitude in `(−π, π]`, 0 at forward, +π/2 at right.
    pub fn lat_long(&self, dir: Vec3) -> (f64, f64) {
        let lat = dir.dot(self.up).clamp(-1.0, 1.0).asin();
        let lon = dir.dot(self.right).atan2(dir.dot(self.forward));
        (lat, lon)
    }

    /// The unit direction at latitude `lat` and longitude `lon` (radians); inverse of [`SkyFrame::lat_long`].
    pub fn direction(&self, lat: f64, lon: f64) -> Vec3 {
        let (sin_lat, cos_lat) = lat.sin_cos();
        let (sin_lon, cos_lon) = lon.sin_cos();
        self.up * sin_lat + (self.forward * cos_lon + self.right * sin_lon) * cos_lat
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn default_frame_is_y_up_looking_down_negative_z() {
        let f = SkyFrame::default();
        let (lat, lon) = f.lat_long(Vec3::NEG_Z);
        assert!(lat.abs() < 1e-15 && lon.abs() < 1e-15);
        let (_, lon) = f.lat_long(Vec3::X);
        assert!((lon - std::f64::consts::FRAC_PI_2).abs() < 1e-15, "east is +x");
        let (lat, _) = f.lat_long(Vec3::Y);
        assert!((lat - std::f64::consts::FRAC_PI_2).abs() < 1e-15);
        assert_eq!(SkyFrame::new(Vec3::Y * 3.0, 0.0).unwrap(), f, "up is normalised");
    }

    #[test]
    fn frames_are_orthonormal_and_invert() {
        for (up, rot) in [(Vec3::Y, 30.0), (Vec3::Z, 0.0), (Vec3::NEG_Z, 45.0), (Vec3::new(1.0, 2.0, -0.5), -120.0)] {
            let f = SkyFrame::new(up, rot).unwrap();
            let (r, u, fw) = (f.right(), f.up(), f.forward());
            assert!((r.length() - 1.0).abs() < 1e-12 && (fw.length() - 1.0).abs() < 1e-12);
            assert!(r.dot(u).abs() < 1e-12 && r.dot(fw).abs() < 1e-12 && u.dot(fw).abs() < 1e-12);
            assert!((r.cross(u) + fw).length() < 1e-12, "right-handed (right, up, back)");
            for (lat, lon) in [(0.3, -2.0), (-1.2, 0.4), (0.0, 3.0)] {
                let d = f.direction(lat, lon);
                let (la, lo) = f.lat_long(d);
                assert!((la - lat).abs() < 1e-12 && (lo - lon).abs() < 1e-12);
            }
        }
    }

    #[test]
    fn rotation_turns_the_sky_counter_clockwise_about_up() {
        let f = SkyFrame::new(Vec3::Y, 90.0).unwrap();
        // Counter-clockwise seen from +y, −z turns into −x.
        assert!((f.forward() - Vec3::NEG_X).length() < 1e-12, "{}", f.forward());
    }

    #[test]
    fn bad_frames_are_errors() {
        assert!(SkyFrame::new(Vec3::ZERO, 0.0).is_err());
        assert!(SkyFrame::new(Vec3::new(f64::NAN, 1.0, 0.0), 0.0).is_err());
        assert!(SkyFrame::new(Vec3::Y, f64::INFINITY).is_err());
    }
}

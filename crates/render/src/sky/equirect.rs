//! # Equirectangular environment map (`type = "equirect"`)
//!
//! A latitude–longitude panorama (PNG, OpenEXR or Radiance HDR): the image's columns are longitude and
//! its rows latitude, both linear in angle. Seen from inside the sphere the image is upright and not
//! mirrored:
//!
//! - the image centre `(s, t) = (½, ½)` is *forward* (`−z` by default) on the horizon;
//! - `s` increases with longitude, toward the right (east, `+x`): `s = ½ + lon/2π`, so `s = ¾` is `+x`
//!   and the left/right edges (`s = 0, 1`) are behind (`+z`);
//! - the top row is straight up (`+y`), the bottom row straight down: `t = ½ − lat/π`.
//!
//! Lookups are bilinear, repeating in longitude and clamped in latitude. HDR/EXR values are taken as
//! linear radiance; 8-bit images as sRGB, decoded to linear.
//!
//! | parameter      | type   | default     | meaning                                                 |
//! |----------------|--------|-------------|---------------------------------------------------------|
//! | `file`         | path   | —           | relative to the scene file                              |
//! | `intensity`    | number | 1           | radiance scale                                          |
//! | `up`           | vector | `[0, 1, 0]` | the panorama's up                                       |
//! | `rotation_deg` | number | 0           | turns the panorama about `up`, counter-clockwise from above |
//!
//! ```toml
//! [sky]
//! type = "equirect"
//! file = "skies/milky_way.exr"
//! intensity = 1.0
//! rotation_deg = 90
//! ```

use super::SkyFrame;
use crate::color::Rgb;
use crate::geometry::Vec3;
use crate::image_io::{ImageData, WrapMode};
use std::f64::consts::{FRAC_1_PI, PI};
use std::sync::Arc;

#[derive(Clone, Debug)]
pub struct Equirect {
    pub image: Arc<ImageData>,
    pub frame: SkyFrame,
    pub intensity: f32,
}

impl Equirect {
    /// Image coordinates `(s, t)` (`t` down) of a unit direction.
    pub fn image_coordinates(&self, dir: Vec3) -> (f64, f64) {
        let (lat, lon) = self.frame.lat_long(dir);
        (0.5 + lon * (0.5 * FRAC_1_PI), 0.5 - lat * FRAC_1_PI)
    }

    /// The unit direction that maps to image coordinates `(s, t)`; inverse of
    /// [`Equirect::image_coordinates`].
    pub fn direction(&self, s: f64, t: f64) -> Vec3 {
        self.frame.direction((0.5 - t) * PI, (s - 0.5) * 2.0 * PI)
    }

    pub fn radiance(&self, dir: Vec3) -> Rgb {
        let (s, t) = self.image_coordinates(dir);
        self.image.sample(s, t, [WrapMode::Repeat, WrapMode::Clamp]) * self.intensity
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A 16×8 black panorama with one red marker pixel.
    fn marked(x: usize, y: usize) -> ImageData {
        let mut pixels = vec![Rgb::ZERO; 16 * 8];
        pixels[y * 16 + x] = Rgb::new(1.0, 0.0, 0.0);
        ImageData::new(16, 8, pixels).unwrap()
    }

    fn pixel_centre_dir(sky: &Equirect, x: usize, y: usize) -> Vec3 {
        sky.direction((x as f64 + 0.5) / 16.0, (y as f64 + 0.5) / 8.0)
    }

    #[test]
    fn marker_appears_in_the_predicted_direction() {
        // Column 12 is s = 12.5/16 ≈ 0.78: just right of +x (s = 0.75); row 2 is t = 2.5/8: 33.75° up.
        let sky = Equirect { image: Arc::new(marked(12, 2)), frame: SkyFrame::Y_UP, intensity: 2.0 };
        let lon = (12.5 / 16.0 - 0.5) * 2.0 * PI;
        let lat = (0.5 - 2.5 / 8.0) * PI;
        let expected = Vec3::new(lat.cos() * lon.sin(), lat.sin(), -lat.cos() * lon.cos());
        assert!((pixel_centre_dir(&sky, 12, 2) - expected).length() < 1e-12);
        assert!(expected.x > 0.0 && expected.y > 0.0, "east and up");
        assert_eq!(sky.radiance(expected), Rgb::new(2.0, 0.0, 0.0), "marker × intensity");
        // Everywhere else (at the other pixel centres) it is black.
        for y in 0..8 {
            for x in 0..16 {
                if (x, y) != (12, 2) {
                    assert_eq!(sky.radiance(pixel_centre_dir(&sky, x, y)), Rgb::ZERO, "pixel ({x}, {y})");
                }
            }
        }
    }

    #[test]
    fn cardinal_directions() {
        let sky = Equirect { image: Arc::new(marked(0, 0)), frame: SkyFrame::Y_UP, intensity: 1.0 };
        let st = |d| sky.image_coordinates(d);
        assert_eq!(st(Vec3::NEG_Z), (0.5, 0.5), "forward is the centre");
        assert_eq!(st(Vec3::X), (0.75, 0.5), "east is right of centre");
        assert_eq!(st(Vec3::NEG_X), (0.25, 0.5));
        assert_eq!(st(Vec3::Y).1, 0.0, "up is the top row");
        assert_eq!(st(Vec3::NEG_Y).1, 1.0);
    }

    #[test]
    fn rotation_moves_the_marker_left() {
        // Marker at the image centre (columns 7/8 straddle s = ½: use column 8, row 4 → just right, just below).
        let image = Arc::new(marked(8, 4));
        let plain = Equirect { image: image.clone(), frame: SkyFrame::Y_UP, intensity: 1.0 };
        let turned = Equirect { image, frame: SkyFrame::new(Vec3::Y, 90.0).unwrap(), intensity: 1.0 };
        let d = pixel_centre_dir(&plain, 8, 4);
        // Rotating the sky 90° counter-clockwise about +y moves the marker from near −z to near −x.
        let rotated = Vec3::new(d.z, d.y, -d.x);
        assert_eq!(turned.radiance(rotated), Rgb::new(1.0, 0.0, 0.0));
        assert_eq!(turned.radiance(d), Rgb::ZERO);
    }
}

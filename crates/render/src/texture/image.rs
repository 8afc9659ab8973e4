//! # Image (`type = "image"`)
//!
//! A picture from a file (PNG, OpenEXR or Radiance HDR, read by the scene crate into an
//! [`ImageData`]):
//! 8- and 16-bit images are taken as sRGB-encoded and decoded to linear, floating-point images as linear.
//! The image covers one unit square of the scaled coordinates `st` and repeats; `s` runs left to right and
//! `t` **bottom to top** (the usual texture convention, so a photo on a wall is upright when the wall's `v`
//! points up). Lookups are bilinear between pixel centres.
//!
//! | parameter  | type       | default  | meaning                                          |
//! |------------|------------|----------|--------------------------------------------------|
//! | `file`     | path       | —        | relative to the scene file                       |
//! | `uv_scale` | `[su, sv]` | `[1, 1]` | repetitions of the image per unit of `u` and `v` |
//!
//! ```toml
//! [objects.material]
//! type = "diffuse"
//! reflectance = { type = "image", file = "textures/poster.png", uv_scale = [2, 1] }
//! ```

use crate::rgb::Rgb;
use crate::texture::image_data::{ImageData, WrapMode};

/// The image's colour at scaled coordinates `st` (repeating, `t` up).
pub fn eval(image: &ImageData, st: [f64; 2]) -> Rgb {
    image.sample(st[0], 1.0 - st[1], [WrapMode::Repeat; 2])
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::Vec3;
    use crate::texture::Texture;
    use std::sync::Arc;

    #[test]
    fn is_upright() {
        // 2×2, rows from the top as files store them (the scene crate's reader keeps that order):
        // top row red, green; bottom row blue, white.
        let image = Arc::new(ImageData::new(2, 2, vec![Rgb::X, Rgb::Y, Rgb::Z, Rgb::ONE]).unwrap());
        let t = Texture::Image { image, uv_scale: [1.0, 1.0] };
        let at = |u, v| t.eval([u, v], Vec3::ZERO);
        // Pixel centres: v = 0.75 is the top row.
        assert_eq!(at(0.25, 0.75), Rgb::X, "top-left pixel");
        assert_eq!(at(0.75, 0.75), Rgb::Y, "top-right pixel");
        assert_eq!(at(0.25, 0.25), Rgb::Z, "bottom-left pixel");
        assert_eq!(at(0.75, 0.25), Rgb::ONE, "bottom-right pixel");
        // Halfway between the two top pixel centres: their average.
        assert!((at(0.5, 0.75) - Rgb::new(0.5, 0.5, 0.0)).abs().max_element() < 1e-6);
        // Repeats every unit of uv.
        assert_eq!(at(3.25, -0.25), Rgb::X);
    }
}

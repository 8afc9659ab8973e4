//! Images in memory — texture maps and environment maps — in linear RGB, and looking them up.
//!
//! An [`ImageData`] holds linear RGB pixels, never empty. Reading image files into one (PNG,
//! JPEG, OpenEXR, Radiance HDR, with sRGB decoding) is the scene crate's job (`scene::files`),
//! where every file a scene names is read under one policy; writing the renderer's own images is
//! the film's (`crate::film`). This module reads and writes no file.
//!
//! Pixel `(x, y)` has its centre at `((x + ½)/width, (y + ½)/height)` in the continuous image coordinates
//! `(s, t)` used by [`ImageData::sample`]; `t` runs **down** the image (row 0 at the top), as stored in
//! files. Textures flip `t` themselves.

use crate::digest::{write_f64s, ContentDigest, Hex};
use crate::rgb::Rgb;
use std::fmt;

/// A linear-RGB raster, row-major from the top-left pixel. Never empty.
///
/// `Debug` shows the size and a digest of the pixels, not the pixels (see [`crate::digest`]).
#[derive(Clone, PartialEq)]
pub struct ImageData {
    width: usize,
    height: usize,
    pixels: Vec<Rgb>,
    digest: ContentDigest,
}

impl fmt::Debug for ImageData {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let digest = self.digest.get(|h| write_f64s(h, self.pixels.iter().flat_map(|p| p.to_array().map(f64::from))));
        f.debug_struct("ImageData")
            .field("width", &self.width)
            .field("height", &self.height)
            .field("content", &Hex(digest))
            .finish()
    }
}

/// What a lookup does with coordinates outside the image.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum WrapMode {
    /// Tile the image (textures; longitude of an environment map).
    Repeat,
    /// Extend the edge pixels (latitude of an environment map).
    Clamp,
}

/// sRGB transfer function, encoded value → linear (IEC 61966-2-1).
pub fn srgb_to_linear(c: f32) -> f32 {
    if c <= 0.04045 {
        c / 12.92
    } else {
        ((c + 0.055) / 1.055).powf(2.4)
    }
}

impl ImageData {
    /// An image from linear pixels, row-major from the top-left. `None` unless
    /// `pixels.len() == width·height > 0`.
    pub fn new(width: usize, height: usize, pixels: Vec<Rgb>) -> Option<Self> {
        (width > 0 && height > 0 && width.checked_mul(height) == Some(pixels.len())).then_some(Self {
            width,
            height,
            pixels,
            digest: ContentDigest::default(),
        })
    }

    pub fn width(&self) -> usize {
        self.width
    }

    pub fn height(&self) -> usize {
        self.height
    }

    /// The pixels, row-major from the top-left.
    pub fn pixels(&self) -> &[Rgb] {
        &self.pixels
    }

    /// Pixel `(x, y)` (column, row from the top), with out-of-range indices wrapped.
    pub fn texel(&self, x: i64, y: i64, wrap: [WrapMode; 2]) -> Rgb {
        let xi = wrap_index(x, self.width, wrap[0]);
        let yi = wrap_index(y, self.height, wrap[1]);
        self.pixels[yi * self.width + xi]
    }

    /// Nearest-pixel lookup at continuous coordinates `(s, t) ∈ [0, 1)²` (`t` down).
    pub fn nearest(&self, s: f64, t: f64, wrap: [WrapMode; 2]) -> Rgb {
        let x = finite_or_zero(s * self.width as f64).floor() as i64;
        let y = finite_or_zero(t * self.height as f64).floor() as i64;
        self.texel(x, y, wrap)
    }

    /// Bilinear interpolation between the four pixel centres around `(s, t)` (`t` down). Exactly the
    /// pixel's value at its centre.
    pub fn sample(&self, s: f64, t: f64, wrap: [WrapMode; 2]) -> Rgb {
        let x = finite_or_zero(s * self.width as f64 - 0.5);
        let y = finite_or_zero(t * self.height as f64 - 0.5);
        let (x0, y0) = (x.floor(), y.floor());
        let (fx, fy) = ((x - x0) as f32, (y - y0) as f32);
        let (x0, y0) = (x0 as i64, y0 as i64);
        let (x1, y1) = (x0.saturating_add(1), y0.saturating_add(1));
        let top = self.texel(x0, y0, wrap).lerp(self.texel(x1, y0, wrap), fx);
        let bottom = self.texel(x0, y1, wrap).lerp(self.texel(x1, y1, wrap), fx);
        top.lerp(bottom, fy)
    }
}

fn finite_or_zero(x: f64) -> f64 {
    if x.is_finite() {
        x
    } else {
        0.0
    }
}

fn wrap_index(i: i64, n: usize, mode: WrapMode) -> usize {
    // `n ≥ 1` is an invariant of `ImageData`; images are far smaller than `i64::MAX` pixels.
    let n = n as i64;
    match mode {
        WrapMode::Repeat => i.rem_euclid(n) as usize,
        WrapMode::Clamp => i.clamp(0, n - 1) as usize,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn two_by_two() -> ImageData {
        // Row 0: red, green; row 1: blue, white.
        ImageData::new(2, 2, vec![Rgb::X, Rgb::Y, Rgb::Z, Rgb::ONE]).unwrap()
    }

    #[test]
    fn construction_checks_size() {
        assert!(ImageData::new(0, 1, vec![]).is_none());
        assert!(ImageData::new(2, 2, vec![Rgb::ONE; 3]).is_none());
        assert!(ImageData::new(usize::MAX, 2, vec![Rgb::ONE; 3]).is_none(), "overflow is an error");
    }

    #[test]
    fn bilinear_hits_pixel_centres_and_blends_between() {
        let img = two_by_two();
        let clamp = [WrapMode::Clamp; 2];
        assert_eq!(img.sample(0.25, 0.25, clamp), Rgb::X, "centre of pixel (0, 0)");
        assert_eq!(img.sample(0.75, 0.75, clamp), Rgb::ONE, "centre of pixel (1, 1)");
        let mid = img.sample(0.5, 0.5, clamp);
        assert!((mid - Rgb::new(0.5, 0.5, 0.5)).abs().max_element() < 1e-6, "average of four: {mid}");
        assert_eq!(img.sample(0.0, 0.25, clamp), Rgb::X, "clamped edge");
        // Repeat: the left edge blends with the right column.
        let edge = img.sample(0.0, 0.25, [WrapMode::Repeat; 2]);
        assert!((edge - Rgb::new(0.5, 0.5, 0.0)).abs().max_element() < 1e-6, "{edge}");
        assert_eq!(img.sample(1.25, -0.75, [WrapMode::Repeat; 2]), Rgb::X, "whole periods away");
        assert_eq!(img.sample(f64::NAN, f64::INFINITY, clamp), Rgb::X, "non-finite coordinates do not panic");
    }

    #[test]
    fn nearest_picks_the_containing_pixel() {
        let img = two_by_two();
        let r = [WrapMode::Repeat; 2];
        assert_eq!(img.nearest(0.49, 0.51, r), Rgb::Z);
        assert_eq!(img.nearest(0.51, 0.49, r), Rgb::Y);
        assert_eq!(img.nearest(-0.01, 0.0, r), Rgb::Y, "wraps to the last column");
        assert_eq!(img.texel(5, -1, [WrapMode::Clamp; 2]), Rgb::Y);
    }
}

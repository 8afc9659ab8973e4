//! Reading images — texture maps and environment maps — into linear RGB, and looking them up.
//!
//! Formats are recognised by content (falling back to the file extension): PNG, OpenEXR and Radiance HDR.
//! 8- and 16-bit data (PNG) is taken as sRGB-encoded and decoded to linear with the exact sRGB transfer
//! function (IEC 61966-2-1); floating-point data (EXR, HDR) is taken as linear. Alpha is dropped.
//! Non-finite or negative values in floating-point files are replaced by 0 so that one bad pixel cannot
//! poison a render.
//!
//! Pixel `(x, y)` has its centre at `((x + ½)/width, (y + ½)/height)` in the continuous image coordinates
//! `(s, t)` used by [`ImageData::sample`]; `t` runs **down** the image (row 0 at the top), as stored in the
//! file. Textures flip `t` themselves.
//!
//! Writing images is the film's business, not this module's.

use crate::color::Rgb;
use crate::digest::{write_f64s, ContentDigest, Hex};
use crate::resource::{ReadError, ReadPolicy, Resource};
use std::fmt;
use std::io::Cursor;
use std::path::{Path, PathBuf};

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

/// Why an image could not be loaded; its `Display` names the file (as the scene wrote it) and the
/// reason.
#[derive(Debug)]
pub struct ImageLoadError {
    pub path: PathBuf,
    pub kind: ImageLoadErrorKind,
}

/// The reason inside an [`ImageLoadError`].
#[derive(Debug)]
pub enum ImageLoadErrorKind {
    /// No file at that path.
    Missing,
    /// The file may not be read (see [`crate::resource`]) or could not be.
    Read(ReadError),
    /// Not a format nullpath reads (or a variant of one the decoder does not support).
    UnsupportedFormat(String),
    /// The file claims a supported format but its data is invalid or truncated.
    Decode(String),
    /// The image has no pixels.
    ZeroSize,
}

impl fmt::Display for ImageLoadError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "cannot load image '{}': ", self.path.display())?;
        match &self.kind {
            ImageLoadErrorKind::Missing => write!(f, "file not found"),
            ImageLoadErrorKind::Read(e) => write!(f, "{e}"),
            ImageLoadErrorKind::UnsupportedFormat(why) => {
                write!(f, "unsupported format ({why}); nullpath reads PNG, OpenEXR and Radiance HDR")
            }
            ImageLoadErrorKind::Decode(why) => write!(f, "decode error: {why}"),
            ImageLoadErrorKind::ZeroSize => write!(f, "the image has zero width or height"),
        }
    }
}

impl std::error::Error for ImageLoadError {
    fn source(&self) -> Option<&(dyn std::error::Error + 'static)> {
        match &self.kind {
            ImageLoadErrorKind::Read(e) => Some(e),
            _ => None,
        }
    }
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

    /// Reads a PNG, OpenEXR or Radiance HDR file into linear RGB (see the module documentation),
    /// from a path typed on the command line: any regular file (see [`ReadPolicy::anywhere`]).
    pub fn load(path: &Path) -> Result<Self, ImageLoadError> {
        Self::load_file(&ReadPolicy::anywhere().file(Path::new(""), path))
    }

    /// Reads the image file `file` (named by a scene) under its policy; errors name it as the scene
    /// wrote it.
    pub fn load_file(file: &Resource<'_>) -> Result<Self, ImageLoadError> {
        let fail = |kind| ImageLoadError { path: file.written().to_path_buf(), kind };
        let bytes = file.read().map_err(|e| {
            fail(match e {
                ReadError::NotFound => ImageLoadErrorKind::Missing,
                e => ImageLoadErrorKind::Read(e),
            })
        })?;
        let mut reader = image::ImageReader::new(Cursor::new(bytes));
        // The extension's format, unless the content says otherwise.
        if let Ok(format) = image::ImageFormat::from_path(file.written()) {
            reader.set_format(format);
        }
        let reader = reader.with_guessed_format().map_err(|e| fail(ImageLoadErrorKind::Decode(e.to_string())))?;
        if reader.format().is_none() {
            return Err(fail(ImageLoadErrorKind::UnsupportedFormat("unrecognised file type".into())));
        }
        let decoded = reader.decode().map_err(|e| {
            fail(match e {
                image::ImageError::Unsupported(u) => ImageLoadErrorKind::UnsupportedFormat(u.to_string()),
                other => ImageLoadErrorKind::Decode(other.to_string()),
            })
        })?;
        let (width, height) = (decoded.width() as usize, decoded.height() as usize);
        if width == 0 || height == 0 {
            return Err(fail(ImageLoadErrorKind::ZeroSize));
        }
        let linear = matches!(decoded, image::DynamicImage::ImageRgb32F(_) | image::DynamicImage::ImageRgba32F(_));
        let pixels = decoded
            .into_rgb32f()
            .pixels()
            .map(|p| {
                let c = Rgb::from_array(p.0);
                if linear {
                    // `max` also maps NaN to 0.
                    let c = c.max(Rgb::ZERO);
                    if c.is_finite() {
                        c
                    } else {
                        Rgb::ZERO
                    }
                } else {
                    c.map(srgb_to_linear)
                }
            })
            .collect();
        ImageData::new(width, height, pixels).ok_or_else(|| fail(ImageLoadErrorKind::ZeroSize))
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
pub(crate) mod tests {
    use super::*;

    /// A unique path in the temporary directory for a test's file.
    pub(crate) fn temp_path(name: &str) -> PathBuf {
        std::env::temp_dir().join(format!("nullpath-test-{}-{name}", std::process::id()))
    }

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

    #[test]
    fn png_is_srgb_decoded() {
        let path = temp_path("srgb.png");
        let png = image::RgbImage::from_raw(2, 1, vec![0, 128, 255, 255, 255, 255]).unwrap();
        png.save(&path).unwrap();
        let img = ImageData::load(&path).unwrap();
        std::fs::remove_file(&path).ok();
        assert_eq!((img.width(), img.height()), (2, 1));
        // sRGB 128/255 → 0.21586 linear.
        let p = img.pixels()[0];
        assert!(p.x == 0.0 && (p.y - 0.215_861).abs() < 1e-5 && p.z == 1.0, "{p}");
        assert_eq!(img.pixels()[1], Rgb::ONE);
    }

    #[test]
    fn exr_is_linear() {
        let path = temp_path("linear.exr");
        let exr = image::Rgb32FImage::from_raw(1, 2, vec![0.5, 2.0, 10.0, 0.25, 0.0, 1.0]).unwrap();
        exr.save(&path).unwrap();
        let img = ImageData::load(&path).unwrap();
        std::fs::remove_file(&path).ok();
        assert_eq!(img.pixels(), &[Rgb::new(0.5, 2.0, 10.0), Rgb::new(0.25, 0.0, 1.0)]);
    }

    #[test]
    fn load_errors_name_the_file_and_the_reason() {
        let missing = temp_path("does-not-exist.png");
        let e = ImageData::load(&missing).unwrap_err();
        assert!(matches!(e.kind, ImageLoadErrorKind::Missing));
        let msg = e.to_string();
        assert!(msg.contains("does-not-exist.png") && msg.contains("not found"), "{msg}");

        let garbage = temp_path("garbage.png");
        std::fs::write(&garbage, b"this is not a PNG file at all").unwrap();
        let e = ImageData::load(&garbage).unwrap_err();
        let msg = e.to_string();
        assert!(matches!(e.kind, ImageLoadErrorKind::Decode(_)), "{e:?}");
        assert!(msg.contains("garbage.png") && msg.contains("decode error"), "{msg}");

        let unknown = temp_path("garbage.xyz");
        std::fs::write(&unknown, b"neither an image nor anything else").unwrap();
        let e = ImageData::load(&unknown).unwrap_err();
        let msg = e.to_string();
        assert!(matches!(e.kind, ImageLoadErrorKind::UnsupportedFormat(_)), "{e:?}");
        assert!(msg.contains("garbage.xyz") && msg.contains("unsupported format"), "{msg}");
        std::fs::remove_file(&garbage).ok();
        std::fs::remove_file(&unknown).ok();
    }
}

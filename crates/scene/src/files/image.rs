//! Image files — texture maps and environment maps — read into the renderer's linear-RGB
//! [`ImageData`].
//!
//! Formats are recognised by content (falling back to the file extension): PNG, OpenEXR and Radiance HDR
//! (and JPEG, which glTF files use). 8- and 16-bit data (PNG, JPEG) is taken as sRGB-encoded and decoded
//! to linear with the exact sRGB transfer function (IEC 61966-2-1, [`srgb_to_linear`]); floating-point
//! data (EXR, HDR) is taken as linear. Alpha is dropped. Non-finite or negative values in floating-point
//! files are replaced by 0 so that one bad pixel cannot poison a render.
//!
//! Rows are stored from the top of the image down, as files store them (see
//! [`render::texture::image_data`] for the coordinates lookups use).

use super::policy::{ReadError, ReadPolicy, Resource};
use render::rgb::Rgb;
use render::texture::image_data::{srgb_to_linear, ImageData};
use std::fmt;
use std::io::Cursor;
use std::path::{Path, PathBuf};

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
    /// The file may not be read (see [`super::policy`]) or could not be.
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
            ImageLoadErrorKind::Missing
            | ImageLoadErrorKind::UnsupportedFormat(_)
            | ImageLoadErrorKind::Decode(_)
            | ImageLoadErrorKind::ZeroSize => None,
        }
    }
}

/// Reads a PNG, OpenEXR or Radiance HDR file into linear RGB (see the module documentation),
/// from a path typed on the command line: any regular file (see [`ReadPolicy::anywhere`]).
pub fn load_image_path(path: &Path) -> Result<ImageData, ImageLoadError> {
    load_image(&ReadPolicy::anywhere().file(Path::new(""), path))
}

/// Reads the image file `file` (named by a scene) under its policy; errors name it as the scene
/// wrote it.
pub fn load_image(file: &Resource<'_>) -> Result<ImageData, ImageLoadError> {
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

#[cfg(test)]
mod tests {
    use super::*;

    /// A unique path in the temporary directory for a test's file.
    fn temp_path(name: &str) -> PathBuf {
        std::env::temp_dir().join(format!("nullpath-test-{}-{name}", std::process::id()))
    }

    #[test]
    fn png_is_srgb_decoded() {
        let path = temp_path("srgb.png");
        let png = image::RgbImage::from_raw(2, 1, vec![0, 128, 255, 255, 255, 255]).unwrap();
        png.save(&path).unwrap();
        let img = load_image_path(&path).unwrap();
        std::fs::remove_file(&path).ok();
        assert_eq!((img.width(), img.height()), (2, 1));
        // sRGB 128/255 → 0.21586 linear.
        let p = img.pixels()[0];
        assert!(p.x == 0.0 && (p.y - 0.215_861).abs() < 1e-5 && p.z == 1.0, "{p}");
        assert_eq!(img.pixels()[1], Rgb::ONE);
    }

    #[test]
    fn rows_are_stored_from_the_top() {
        // 2×2 PNG: top row red, green; bottom row blue, white (sRGB 255 and 0 are exact in linear).
        let path = temp_path("rows.png");
        let png = image::RgbImage::from_raw(2, 2, vec![255, 0, 0, 0, 255, 0, 0, 0, 255, 255, 255, 255]).unwrap();
        png.save(&path).unwrap();
        let img = load_image_path(&path).unwrap();
        std::fs::remove_file(&path).ok();
        assert_eq!(img.pixels(), &[Rgb::X, Rgb::Y, Rgb::Z, Rgb::ONE]);
    }

    #[test]
    fn exr_is_linear() {
        let path = temp_path("linear.exr");
        let exr = image::Rgb32FImage::from_raw(1, 2, vec![0.5, 2.0, 10.0, 0.25, 0.0, 1.0]).unwrap();
        exr.save(&path).unwrap();
        let img = load_image_path(&path).unwrap();
        std::fs::remove_file(&path).ok();
        assert_eq!(img.pixels(), &[Rgb::new(0.5, 2.0, 10.0), Rgb::new(0.25, 0.0, 1.0)]);
    }

    #[test]
    fn load_errors_name_the_file_and_the_reason() {
        let missing = temp_path("does-not-exist.png");
        let e = load_image_path(&missing).unwrap_err();
        assert!(matches!(e.kind, ImageLoadErrorKind::Missing));
        let msg = e.to_string();
        assert!(msg.contains("does-not-exist.png") && msg.contains("not found"), "{msg}");

        let garbage = temp_path("garbage.png");
        std::fs::write(&garbage, b"this is not a PNG file at all").unwrap();
        let e = load_image_path(&garbage).unwrap_err();
        let msg = e.to_string();
        assert!(matches!(e.kind, ImageLoadErrorKind::Decode(_)), "{e:?}");
        assert!(msg.contains("garbage.png") && msg.contains("decode error"), "{msg}");

        let unknown = temp_path("garbage.xyz");
        std::fs::write(&unknown, b"neither an image nor anything else").unwrap();
        let e = load_image_path(&unknown).unwrap_err();
        let msg = e.to_string();
        assert!(matches!(e.kind, ImageLoadErrorKind::UnsupportedFormat(_)), "{e:?}");
        assert!(msg.contains("garbage.xyz") && msg.contains("unsupported format"), "{msg}");
        std::fs::remove_file(&garbage).ok();
        std::fs::remove_file(&unknown).ok();
    }
}

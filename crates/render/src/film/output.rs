//! Writing the film to an image file, the format chosen by the file's extension.
//!
//! | extension | contents |
//! |---|---|
//! | `.png` | 8-bit sRGB: exposure, tone curve, sRGB OETF ([`to_rgb8`]) |
//! | `.exr` | OpenEXR, 32-bit float linear RGB, ZIP (lossless): exposure as a linear scale only |
//! | `.hdr` | Radiance RGBE, linear: exposure as a linear scale; negatives clamped to 0 |
//!
//! Extensions match case-insensitively. Files are written to a temporary sibling and renamed into
//! place, so a reader (or a render interrupted mid-write) never sees a half-written image; the
//! temporaries of writers that were killed mid-write are removed by the next write beside them.
//! Partial films are fine: pixels with no samples are black.
//!
//! Metadata (what made the image: scene, settings, seed, samples, program version) goes into
//! PNG `iTXt` chunks and EXR header attributes, each key prefixed with [`METADATA_PREFIX`];
//! Radiance HDR has no place for it. [`read_metadata`] reads it back.
//!
//! The renderer's own outputs, these images and its checkpoints ([`super::write_checkpoint`]),
//! are the film's to write (and read back): they are the only files the render crate touches.
//! The files a scene names (meshes, textures, skies, glTF files) are read by the scene crate
//! (`scene::files`), under its read policy.

use std::ffi::OsString;
use std::fmt;
use std::fs::File;
use std::io::{BufWriter, Write};
use std::path::{Path, PathBuf};

use image::codecs::hdr::HdrEncoder;

use super::data::DataLayer;
use super::{to_rgb8, Film, ToneMap};

/// Text about an image, key to value (keys without [`METADATA_PREFIX`]).
pub type Metadata = std::collections::BTreeMap<String, String>;

/// Prefix of nullpath's keys in image files.
pub const METADATA_PREFIX: &str = "nullpath.";

/// The image formats [`write_image`] can produce.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ImageFormat {
    Png,
    Exr,
    Hdr,
}

impl ImageFormat {
    /// The format named by `path`'s extension (case-insensitive), if supported.
    pub fn from_path(path: &Path) -> Option<Self> {
        let ext = path.extension()?.to_str()?.to_ascii_lowercase();
        match ext.as_str() {
            "png" => Some(Self::Png),
            "exr" => Some(Self::Exr),
            "hdr" => Some(Self::Hdr),
            _ => None,
        }
    }
}

impl fmt::Display for ImageFormat {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            Self::Png => "PNG",
            Self::Exr => "OpenEXR",
            Self::Hdr => "Radiance HDR",
        })
    }
}

const SUPPORTED: &str = ".png, .exr, .hdr";

/// Why an image could not be written. Every variant names the file.
#[derive(Debug)]
pub enum ImageWriteError {
    /// The extension is missing or names no supported format.
    UnsupportedExtension { path: PathBuf },
    /// The directory the file should go in does not exist.
    MissingDirectory { path: PathBuf, directory: PathBuf },
    /// The file's parent path exists but is not a directory.
    NotADirectory { path: PathBuf, directory: PathBuf },
    /// The film has no pixels (zero width or height).
    EmptyImage { path: PathBuf },
    /// The tone map's exposure is NaN or infinite.
    InvalidExposure { path: PathBuf, exposure_ev: f64 },
    /// Creating, writing or renaming the file failed.
    Io { path: PathBuf, source: std::io::Error },
    /// The encoder failed.
    Encode { path: PathBuf, format: ImageFormat, source: Box<dyn std::error::Error + Send + Sync> },
    /// Data channels were asked for in a format that cannot hold them (only EXR can).
    DataNeedsExr { path: PathBuf },
}

impl fmt::Display for ImageWriteError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::UnsupportedExtension { path } => {
                let ext = match path.extension() {
                    Some(ext) => format!("unsupported extension '.{}'", ext.to_string_lossy()),
                    None => "no file extension".to_owned(),
                };
                write!(f, "cannot write image '{}': {ext} (supported: {SUPPORTED})", path.display())
            }
            Self::MissingDirectory { path, directory } => {
                write!(f, "cannot write image '{}': directory '{}' does not exist", path.display(), directory.display())
            }
            Self::NotADirectory { path, directory } => {
                write!(f, "cannot write image '{}': '{}' is not a directory", path.display(), directory.display())
            }
            Self::EmptyImage { path } => {
                write!(f, "cannot write image '{}': the image has no pixels", path.display())
            }
            Self::InvalidExposure { path, exposure_ev } => {
                write!(f, "cannot write image '{}': exposure must be finite (got {exposure_ev} EV)", path.display())
            }
            Self::Io { path, source } => {
                write!(f, "cannot write image '{}': {source}", path.display())
            }
            Self::Encode { path, format, source } => {
                write!(f, "cannot write image '{}' as {format}: {source}", path.display())
            }
            Self::DataNeedsExr { path } => write!(
                f,
                "cannot write image '{}' with data channels (render.channels): only an .exr file holds them",
                path.display()
            ),
        }
    }
}

impl std::error::Error for ImageWriteError {
    fn source(&self) -> Option<&(dyn std::error::Error + 'static)> {
        match self {
            Self::Io { source, .. } => Some(source),
            Self::Encode { source, .. } => Some(source.as_ref()),
            _ => None,
        }
    }
}

/// Checks, without writing anything, that `path` has a supported extension and that its directory
/// exists; returns the format. Call it before a long render so a typo fails fast.
pub fn check_output_path(path: &Path) -> Result<ImageFormat, ImageWriteError> {
    let format =
        ImageFormat::from_path(path).ok_or_else(|| ImageWriteError::UnsupportedExtension { path: path.to_owned() })?;
    if let Some(directory) = path.parent() {
        // An empty parent means the current directory.
        if !directory.as_os_str().is_empty() && !directory.is_dir() {
            let (path, directory) = (path.to_owned(), directory.to_owned());
            return Err(if directory.exists() {
                ImageWriteError::NotADirectory { path, directory }
            } else {
                ImageWriteError::MissingDirectory { path, directory }
            });
        }
    }
    Ok(format)
}

/// Checks that a file can be created in `path`'s directory, by creating and removing a
/// temporary there: a read-only directory or full disk is found before a long render, not after.
pub fn check_writable(path: &Path) -> Result<(), ImageWriteError> {
    let probe = temporary_sibling(path);
    let created = File::create(&probe);
    let _ = std::fs::remove_file(&probe);
    created.map(drop).map_err(|source| ImageWriteError::Io { path: path.to_owned(), source })
}

/// Writes `film` to `path` in the format its extension names (see the module docs), with
/// `metadata`; `tonemap`'s curve applies to PNG only, its exposure to every format.
pub fn write_image(film: &Film, path: &Path, tonemap: &ToneMap, metadata: &Metadata) -> Result<(), ImageWriteError> {
    write_image_with_data(film, None, path, tonemap, metadata)
}

/// [`write_image`] with the data channels `data` beside the colour (EXR only).
pub fn write_image_with_data(
    film: &Film,
    data: Option<&DataLayer>,
    path: &Path,
    tonemap: &ToneMap,
    metadata: &Metadata,
) -> Result<(), ImageWriteError> {
    let format = check_output_path(path)?;
    if data.is_some() && format != ImageFormat::Exr {
        return Err(ImageWriteError::DataNeedsExr { path: path.to_owned() });
    }
    if film.width() == 0 || film.height() == 0 {
        return Err(ImageWriteError::EmptyImage { path: path.to_owned() });
    }
    if !tonemap.exposure_ev.is_finite() {
        return Err(ImageWriteError::InvalidExposure { path: path.to_owned(), exposure_ev: tonemap.exposure_ev });
    }
    write_atomically(path, |temporary| write_to((film, data), temporary, format, tonemap, metadata))
}

/// Writes only `data`'s channels, no colour, to the OpenEXR file `path`, with `metadata`: the
/// maps of redshift and ray fates a physicist compares with other codes, made without rendering
/// the image (`nullpath render --data-only`).
pub fn write_data_image(data: &DataLayer, path: &Path, metadata: &Metadata) -> Result<(), ImageWriteError> {
    if check_output_path(path)? != ImageFormat::Exr {
        return Err(ImageWriteError::DataNeedsExr { path: path.to_owned() });
    }
    if data.width == 0 || data.height == 0 {
        return Err(ImageWriteError::EmptyImage { path: path.to_owned() });
    }
    write_atomically(path, |temporary| {
        write_file(temporary, ImageFormat::Exr, |writer| {
            encode_exr_channels(data_channels(data).collect(), (data.width, data.height), metadata, writer)
        })
    })
}

/// An encoder's error.
type EncodeError = Box<dyn std::error::Error + Send + Sync>;

/// Creates `path`, has `encode` write it as `format`, and flushes it to the disk.
fn write_file(
    path: &Path,
    format: ImageFormat,
    encode: impl FnOnce(&mut BufWriter<File>) -> Result<(), EncodeError>,
) -> Result<(), ImageWriteError> {
    let io_error = |source| ImageWriteError::Io { path: path.to_owned(), source };
    let mut writer = BufWriter::new(File::create(path).map_err(io_error)?);
    encode(&mut writer).map_err(|source| ImageWriteError::Encode { path: path.to_owned(), format, source })?;
    writer.flush().map_err(io_error)?;
    writer.get_ref().sync_all().map_err(io_error)
}

/// `layer`'s data channels and then its spectral channels, as EXR channels.
fn data_channels(layer: &DataLayer) -> impl Iterator<Item = exr::prelude::AnyChannel<exr::prelude::FlatSamples>> + '_ {
    use exr::prelude::{AnyChannel, FlatSamples};
    layer.named_channels().map(|(name, samples)| AnyChannel::new(name.as_str(), FlatSamples::F32(samples)))
}

/// Encodes `channels` of an image of `size` pixels, with `metadata`, as a lossless OpenEXR file.
fn encode_exr_channels(
    channels: Vec<exr::prelude::AnyChannel<exr::prelude::FlatSamples>>,
    (width, height): (u32, u32),
    metadata: &Metadata,
    writer: &mut BufWriter<File>,
) -> Result<(), EncodeError> {
    use exr::prelude::{AnyChannels, Encoding, Image, WritableImage as _};
    let mut image = Image::from_channels((width as usize, height as usize), AnyChannels::sort(channels.into()));
    image.layer_data.encoding = Encoding::SMALL_LOSSLESS;
    image.layer_data.attributes.other.extend(exr_attributes(metadata));
    Ok(image.write().to_buffered(writer)?)
}

/// Runs `write` on a temporary sibling of `path` and renames it into place; on failure the
/// temporary is removed and the error names `path`. Stale temporaries of `path` left by killed
/// processes are removed first.
pub(crate) fn write_atomically(
    path: &Path,
    write: impl FnOnce(&Path) -> Result<(), ImageWriteError>,
) -> Result<(), ImageWriteError> {
    let io_error = |source| ImageWriteError::Io { path: path.to_owned(), source };
    replace_atomically(path, write, io_error).map_err(|e| e.with_path(path))
}

/// Writes `contents` to `path` as images are written: into a temporary sibling, flushed to the
/// disk, then renamed over `path`; for the text files written beside images (statistics), so
/// that they too are whole or absent, never half-written.
pub fn write_file_atomically(path: &Path, contents: &[u8]) -> std::io::Result<()> {
    let write = |temporary: &Path| {
        let mut file = File::create(temporary)?;
        file.write_all(contents)?;
        file.sync_all()
    };
    replace_atomically(path, write, |e| e)
}

/// [`write_atomically`] for any error type: `rename_error` makes one of the rename's I/O error.
fn replace_atomically<E>(
    path: &Path,
    write: impl FnOnce(&Path) -> Result<(), E>,
    rename_error: impl FnOnce(std::io::Error) -> E,
) -> Result<(), E> {
    remove_stale_temporaries(path);
    let temporary = temporary_sibling(path);
    let result = write(&temporary).and_then(|()| std::fs::rename(&temporary, path).map_err(rename_error));
    if result.is_err() {
        // Best effort: the temporary may not exist, and the original error is what matters.
        let _ = std::fs::remove_file(&temporary);
    }
    result
}

impl ImageWriteError {
    /// Reports the user's path rather than the temporary one.
    fn with_path(self, user_path: &Path) -> Self {
        let path = user_path.to_owned();
        match self {
            Self::Io { source, .. } => Self::Io { path, source },
            Self::Encode { format, source, .. } => Self::Encode { path, format, source },
            other => other,
        }
    }
}

/// `dir/.name.partial-<pid>`: same directory (so the rename is atomic on one file system), hidden,
/// and distinct per process.
fn temporary_sibling(path: &Path) -> PathBuf {
    temporary_sibling_of(path, std::process::id())
}

fn temporary_sibling_of(path: &Path, pid: u32) -> PathBuf {
    let mut name = OsString::from(".");
    name.push(path.file_name().unwrap_or_default());
    name.push(format!(".partial-{pid}"));
    path.with_file_name(name)
}

/// Removes the temporaries of `path` whose writing process no longer runs (it was killed
/// mid-write). Where processes cannot be looked up (no `/proc`), nothing is removed.
fn remove_stale_temporaries(path: &Path) {
    let (Some(name), Some(directory)) = (path.file_name(), path.parent()) else { return };
    if !Path::new("/proc/self").exists() {
        return;
    }
    let mut prefix = OsString::from(".");
    prefix.push(name);
    prefix.push(".partial-");
    let directory = if directory.as_os_str().is_empty() { Path::new(".") } else { directory };
    let Ok(entries) = std::fs::read_dir(directory) else { return };
    for entry in entries.flatten() {
        let file_name = entry.file_name();
        let pid = file_name
            .to_str()
            .zip(prefix.to_str())
            .and_then(|(f, p)| f.strip_prefix(p))
            .and_then(|pid| pid.parse::<u32>().ok());
        if let Some(pid) = pid {
            if !Path::new("/proc").join(pid.to_string()).exists() {
                let _ = std::fs::remove_file(temporary_sibling_of(path, pid));
            }
        }
    }
}

/// The film's colour as the linear formats hold it (OpenEXR bit for bit): row by row, each
/// pixel's mean radiance scaled by `tonemap`'s exposure (its curve is for 8-bit output only),
/// rounded to `f32`. What `nullpath render -o x.exr` writes and what the Python module returns
/// are both this, so that the two agree to the bit.
pub fn linear_pixels(film: &Film, tonemap: &ToneMap) -> Vec<[f32; 3]> {
    let scale = tonemap.exposure_scale();
    film.bounds().pixels().map(|(x, y)| film.pixel_f64(x, y).map(|c| (c * scale) as f32)).collect()
}

fn write_to(
    (film, data): (&Film, Option<&DataLayer>),
    path: &Path,
    format: ImageFormat,
    tonemap: &ToneMap,
    metadata: &Metadata,
) -> Result<(), ImageWriteError> {
    let (width, height) = (film.width(), film.height());
    write_file(path, format, |writer| {
        match format {
            ImageFormat::Png => {
                let bytes = to_rgb8(film, tonemap);
                let mut encoder = png::Encoder::new(writer, width, height);
                encoder.set_color(png::ColorType::Rgb);
                encoder.set_depth(png::BitDepth::Eight);
                for (key, value) in metadata {
                    encoder.add_itxt_chunk(format!("{METADATA_PREFIX}{key}"), value.clone())?;
                }
                encoder.write_header().and_then(|mut w| w.write_image_data(&bytes).and_then(|()| w.finish()))?;
            }
            ImageFormat::Exr if data.is_some() => {
                use exr::prelude::{AnyChannel, FlatSamples};
                let pixels = linear_pixels(film, tonemap);
                let colour: [Vec<f32>; 3] = std::array::from_fn(|c| pixels.iter().map(|p| p[c]).collect());
                let [r, g, b] = colour.map(FlatSamples::F32);
                let mut channels = vec![AnyChannel::new("R", r), AnyChannel::new("G", g), AnyChannel::new("B", b)];
                channels.extend(data.into_iter().flat_map(data_channels));
                encode_exr_channels(channels, (width, height), metadata, writer)?;
            }
            ImageFormat::Exr => {
                use exr::prelude::{Encoding, Image, SpecificChannels, Vec2, WritableImage as _};
                let pixels = linear_pixels(film, tonemap);
                let channels = SpecificChannels::rgb(|Vec2(x, y): Vec2<usize>| {
                    let [r, g, b] = pixels[y * width as usize + x];
                    (r, g, b)
                });
                let size = (width as usize, height as usize);
                let mut image = Image::from_encoded_channels(size, Encoding::SMALL_LOSSLESS, channels);
                image.layer_data.attributes.other.extend(exr_attributes(metadata));
                image.write().to_buffered(writer)?;
            }
            ImageFormat::Hdr => {
                let pixels: Vec<image::Rgb<f32>> =
                    linear_pixels(film, tonemap).into_iter().map(|p| image::Rgb(p.map(|c| c.max(0.0)))).collect();
                HdrEncoder::new(writer).encode(&pixels, width as usize, height as usize)?;
            }
        }
        Ok(())
    })
}

/// `metadata` as EXR text attributes (UTF-8 bytes: EXR text is bytes, not Latin-1 only).
pub(crate) fn exr_attributes(
    metadata: &Metadata,
) -> impl Iterator<Item = (exr::meta::attribute::Text, exr::meta::attribute::AttributeValue)> + '_ {
    use exr::meta::attribute::{AttributeValue, Text};
    metadata.iter().map(|(key, value)| {
        (
            Text::from_slice_unchecked(format!("{METADATA_PREFIX}{key}").as_bytes()),
            AttributeValue::Text(Text::from_slice_unchecked(value.as_bytes())),
        )
    })
}

/// nullpath's metadata among EXR header attributes.
pub(crate) fn from_exr_attributes<'a>(
    attributes: impl Iterator<Item = (&'a exr::meta::attribute::Text, &'a exr::meta::attribute::AttributeValue)>,
) -> Metadata {
    use exr::meta::attribute::AttributeValue;
    attributes
        .filter_map(|(key, value)| {
            let key = String::from_utf8_lossy(key.as_slice()).strip_prefix(METADATA_PREFIX)?.to_owned();
            let AttributeValue::Text(text) = value else { return None };
            Some((key, String::from_utf8_lossy(text.as_slice()).into_owned()))
        })
        .collect()
}

/// Why an image's metadata could not be read.
#[derive(Debug)]
pub struct MetadataReadError {
    pub path: PathBuf,
    pub reason: String,
}

impl fmt::Display for MetadataReadError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "cannot read '{}': {}", self.path.display(), self.reason)
    }
}

impl std::error::Error for MetadataReadError {}

/// The nullpath metadata of a PNG or EXR file (empty for images made by other programs).
pub fn read_metadata(path: &Path) -> Result<Metadata, MetadataReadError> {
    let error = |reason: String| MetadataReadError { path: path.to_owned(), reason };
    match ImageFormat::from_path(path) {
        Some(ImageFormat::Png) => {
            let file = File::open(path).map_err(|e| error(e.to_string()))?;
            let reader =
                png::Decoder::new(std::io::BufReader::new(file)).read_info().map_err(|e| error(e.to_string()))?;
            let info = reader.info();
            let mut metadata = Metadata::new();
            for chunk in &info.utf8_text {
                if let Some(key) = chunk.keyword.strip_prefix(METADATA_PREFIX) {
                    metadata.insert(key.to_owned(), chunk.get_text().map_err(|e| error(e.to_string()))?);
                }
            }
            Ok(metadata)
        }
        Some(ImageFormat::Exr) => {
            let meta = exr::meta::MetaData::read_from_file(path, false).map_err(|e| error(e.to_string()))?;
            let header = meta.headers.first().ok_or_else(|| error("the file has no image".into()))?;
            Ok(from_exr_attributes(header.own_attributes.other.iter().chain(&header.shared_attributes.other)))
        }
        Some(ImageFormat::Hdr) => Err(error("Radiance HDR files carry no metadata; use .png or .exr".into())),
        None => Err(error(format!("not an image nullpath writes ({SUPPORTED})"))),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::film::Curve;
    use crate::rgb::Rgb;
    use std::sync::atomic::{AtomicUsize, Ordering};

    /// A fresh path in the system temporary directory, unique per process and call.
    fn temp_path(stem: &str, ext: &str) -> PathBuf {
        static COUNTER: AtomicUsize = AtomicUsize::new(0);
        let n = COUNTER.fetch_add(1, Ordering::Relaxed);
        std::env::temp_dir().join(format!("nullpath-film-{}-{stem}-{n}.{ext}", std::process::id()))
    }

    /// Removes the file when dropped, so failing tests do not leave files behind.
    struct Cleanup(PathBuf);
    impl Drop for Cleanup {
        fn drop(&mut self) {
            let _ = std::fs::remove_file(&self.0);
        }
    }

    /// 3×2 film: a few exact values, one pixel left without samples.
    fn small_film() -> Film {
        let mut film = Film::new(3, 2);
        film.add_sample(0, 0, Rgb::new(0.0, 0.5, 1.0), 1.0);
        film.add_sample(1, 0, Rgb::new(2.0, 0.18, 0.25), 1.0);
        film.add_sample(2, 0, Rgb::new(3.75, 1234.5, 1e-3), 1.0);
        film.add_sample(0, 1, Rgb::new(0.25, 0.25, 0.25), 1.0);
        film.add_sample(0, 1, Rgb::new(0.75, 0.75, 0.75), 1.0);
        film.add_sample(1, 1, Rgb::new(-0.5, 7.0, 0.125), 1.0);
        // (2, 1) has no samples: black.
        film
    }

    #[test]
    fn png_round_trip() {
        let film = small_film();
        let path = temp_path("round-trip", "png");
        let _cleanup = Cleanup(path.clone());
        let tonemap = ToneMap { exposure_ev: 0.0, curve: Curve::Linear };
        write_image(&film, &path, &tonemap, &Metadata::new()).expect("PNG written");
        let read = image::open(&path).expect("PNG readable").to_rgb8();
        assert_eq!(read.dimensions(), (3, 2));
        assert_eq!(read.as_raw(), &to_rgb8(&film, &tonemap));
        assert_eq!(read.get_pixel(0, 0).0, [0, 188, 255]);
        assert_eq!(read.get_pixel(1, 0).0[1], 118);
        assert_eq!(read.get_pixel(0, 1).0, [188, 188, 188]);
        assert_eq!(read.get_pixel(1, 1).0, [0, 255, 99]);
        assert_eq!(read.get_pixel(2, 1).0, [0, 0, 0]);
        // The temporary file was renamed away.
        assert!(!temporary_sibling(&path).exists());
    }

    #[test]
    fn exr_round_trip_is_exact_in_f32() {
        let film = small_film();
        let path = temp_path("round-trip", "EXR");
        let _cleanup = Cleanup(path.clone());
        // One stop up: an exact doubling in binary floating point. The curve does not apply.
        let tonemap = ToneMap { exposure_ev: 1.0, curve: Curve::Filmic };
        write_image(&film, &path, &tonemap, &Metadata::new()).expect("EXR written");
        let read = image::open(&path).expect("EXR readable").into_rgb32f();
        assert_eq!(read.dimensions(), (3, 2));
        for (x, y) in film.bounds().pixels() {
            let expected = film.pixel(x, y) * 2.0;
            let got = read.get_pixel(x, y).0;
            assert_eq!(got, expected.to_array(), "pixel ({x}, {y})");
        }
        assert_eq!(read.get_pixel(1, 1).0[0], -1.0, "no clamping");
        assert_eq!(read.get_pixel(2, 0).0[1], 2469.0, "values above 1 kept");
    }

    #[test]
    fn hdr_round_trip_within_rgbe_precision() {
        let film = small_film();
        let path = temp_path("round-trip", "hdr");
        let _cleanup = Cleanup(path.clone());
        write_image(&film, &path, &ToneMap::default(), &Metadata::new()).expect("HDR written");
        let read = image::open(&path).expect("HDR readable").into_rgb32f();
        // RGBE keeps 8 mantissa bits relative to the pixel's largest channel.
        for (x, y) in film.bounds().pixels() {
            let expected = film.pixel(x, y).max(Rgb::ZERO);
            let got = Rgb::from_array(read.get_pixel(x, y).0);
            let tolerance = expected.max_element() / 128.0;
            assert!((got - expected).abs().max_element() <= tolerance, "({x}, {y}): {got}");
        }
    }

    #[test]
    fn partial_film_writes_black_where_unsampled() {
        let mut film = Film::new(4, 1);
        film.add_sample(1, 0, Rgb::ONE, 1.0);
        let path = temp_path("partial", "png");
        let _cleanup = Cleanup(path.clone());
        write_image(&film, &path, &ToneMap::default(), &Metadata::new()).expect("PNG written");
        let read = image::open(&path).expect("PNG readable").to_rgb8();
        assert_eq!(read.as_raw(), &[0, 0, 0, 255, 255, 255, 0, 0, 0, 0, 0, 0]);
    }

    #[test]
    fn unsupported_extension_is_a_clear_error() {
        let film = small_film();
        for name in ["render.jpg", "render", "render.png.bak"] {
            let path = std::env::temp_dir().join(name);
            let err = write_image(&film, &path, &ToneMap::default(), &Metadata::new()).expect_err("must fail");
            assert!(matches!(err, ImageWriteError::UnsupportedExtension { .. }));
            let message = err.to_string();
            assert!(message.contains(&path.display().to_string()), "{message}");
            assert!(message.contains(".png") && message.contains(".exr"), "{message}");
            assert!(!path.exists());
        }
    }

    #[test]
    fn missing_directory_is_a_clear_error() {
        let directory = std::env::temp_dir().join(format!("nullpath-film-no-such-directory-{}", std::process::id()));
        let path = directory.join("out.png");
        let err = write_image(&small_film(), &path, &ToneMap::default(), &Metadata::new()).expect_err("must fail");
        assert!(matches!(err, ImageWriteError::MissingDirectory { .. }));
        let message = err.to_string();
        assert!(message.contains(&path.display().to_string()), "{message}");
        assert!(message.contains("does not exist"), "{message}");
        assert!(!directory.exists());
    }

    #[test]
    fn parent_that_is_a_file_is_a_clear_error() {
        let not_a_directory = temp_path("plain-file", "txt");
        let _cleanup = Cleanup(not_a_directory.clone());
        std::fs::write(&not_a_directory, b"x").expect("temp file");
        let path = not_a_directory.join("out.exr");
        let err = write_image(&small_film(), &path, &ToneMap::default(), &Metadata::new()).expect_err("must fail");
        assert!(matches!(err, ImageWriteError::NotADirectory { .. }));
        let message = err.to_string();
        assert!(message.contains(&path.display().to_string()), "{message}");
        assert!(message.contains("is not a directory"), "{message}");
    }

    #[test]
    fn io_failure_names_the_users_path_and_leaves_no_temporary() {
        // The target is an existing directory: everything succeeds until the final rename.
        let path = temp_path("is-a-directory", "png");
        std::fs::create_dir(&path).expect("temp directory");
        let err = write_image(&small_film(), &path, &ToneMap::default(), &Metadata::new()).expect_err("must fail");
        let temporary_left = temporary_sibling(&path).exists();
        std::fs::remove_dir(&path).expect("remove temp directory");
        assert!(matches!(err, ImageWriteError::Io { .. }), "{err:?}");
        assert!(err.to_string().contains(&path.display().to_string()), "{err}");
        assert!(std::error::Error::source(&err).is_some());
        assert!(!temporary_left);
    }

    #[test]
    fn text_files_are_replaced_whole_and_leave_no_temporary() {
        let path = temp_path("stats", "json");
        let _cleanup = Cleanup(path.clone());
        write_file_atomically(&path, b"first").expect("written");
        write_file_atomically(&path, b"second, longer").expect("replaced");
        assert_eq!(std::fs::read(&path).expect("readable"), b"second, longer");
        assert!(!temporary_sibling(&path).exists());
        // Onto a directory: the rename fails, the directory is kept and the temporary removed.
        let directory = temp_path("stats-directory", "json");
        std::fs::create_dir(&directory).expect("temp directory");
        let failed = write_file_atomically(&directory, b"x");
        let temporary_left = temporary_sibling(&directory).exists();
        std::fs::remove_dir(&directory).expect("still a directory");
        assert!(failed.is_err());
        assert!(!temporary_left);
    }

    #[test]
    fn empty_film_and_bad_exposure_are_errors() {
        let path = temp_path("empty", "png");
        let err = write_image(&Film::new(0, 4), &path, &ToneMap::default(), &Metadata::new()).expect_err("empty");
        assert!(matches!(err, ImageWriteError::EmptyImage { .. }));
        let tonemap = ToneMap { exposure_ev: f64::NAN, curve: Curve::Linear };
        let err = write_image(&small_film(), &path, &tonemap, &Metadata::new()).expect_err("NaN exposure");
        assert!(err.to_string().contains("exposure"));
        assert!(!path.exists());
    }

    #[test]
    fn format_from_extension() {
        assert_eq!(ImageFormat::from_path(Path::new("a/b.PNG")), Some(ImageFormat::Png));
        assert_eq!(ImageFormat::from_path(Path::new("b.exr")), Some(ImageFormat::Exr));
        assert_eq!(ImageFormat::from_path(Path::new("b.Hdr")), Some(ImageFormat::Hdr));
        assert_eq!(ImageFormat::from_path(Path::new("b.tiff")), None);
        assert_eq!(ImageFormat::from_path(Path::new(".png")), None);
        assert_eq!(check_output_path(Path::new("relative.png")).ok(), Some(ImageFormat::Png));
    }
}

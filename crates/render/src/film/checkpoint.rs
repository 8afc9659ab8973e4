//! Checkpoints: a render's exact state in an OpenEXR file, to continue it later, on this
//! machine or another.
//!
//! The file is an ordinary linear EXR whose `R`, `G`, `B` channels hold the image as it stands
//! (any EXR viewer shows it), plus the exact state of every pixel as named channels
//! ([`PixelChannels`]): each `f64` as two `u32` channels of its bits (`nullpath.<name>.hi` and
//! `.lo`; EXR has no 64-bit samples) and counters as `u32` channels. The path tracer's state
//! ([`write_checkpoint`]) is a film's sums and counts with the per-pixel sample target of the
//! pass in progress, `nullpath.target`; other integrators keep their own channels with
//! [`write_state`]. The header holds the caller's [`Metadata`] and a hash of the state, so
//! that a damaged file is refused rather than continued. Files are written atomically
//! (temporary sibling, then rename), so an interrupted write leaves the previous checkpoint
//! intact.

use super::output::{exr_attributes, from_exr_attributes, write_atomically, Metadata, METADATA_PREFIX};
use super::pixel::{PixelState, PixelSum};
use super::{Film, ImageWriteError};
use std::fmt;
use std::hash::{Hash, Hasher};
use std::path::{Path, PathBuf};

/// Names of the film's `f64` accumulators, in [`PixelState`] order.
const SUMS: [&str; 6] = ["r", "g", "b", "weight", "odd_y", "odd_weight"];
/// Names of the film's `u32` counters, in [`PixelState`] order.
const COUNTS: [&str; 2] = ["count", "taken"];
const TARGET: &str = "target";
/// Header keys that start with this belong to the state and are hashed with it.
pub const STATE_PREFIX: &str = "checkpoint.";
const NAN_SAMPLES: &str = "checkpoint.nan_samples";
const STATE_HASH: &str = "checkpoint.state_hash";

/// A film's state with the pass targets and the caller's metadata.
#[derive(Clone, Debug)]
pub struct Checkpoint {
    pub film: Film,
    /// Each pixel's sample target in the pass in progress, row-major.
    pub targets: Vec<u32>,
    pub metadata: Metadata,
}

/// A render's exact per-pixel state: named channels of one value a pixel, row-major.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct PixelChannels {
    pub f64s: Vec<(&'static str, Vec<f64>)>,
    pub u32s: Vec<(&'static str, Vec<u32>)>,
}

impl PixelChannels {
    /// The channel `name` of `f64`s, if it is there.
    pub fn f64s(&self, name: &str) -> Option<&[f64]> {
        self.f64s.iter().find(|(n, _)| *n == name).map(|(_, v)| v.as_slice())
    }

    /// The channel `name` of `u32`s, if it is there.
    pub fn u32s(&self, name: &str) -> Option<&[u32]> {
        self.u32s.iter().find(|(n, _)| *n == name).map(|(_, v)| v.as_slice())
    }
}

/// A state read back by [`read_state`].
#[derive(Clone, Debug)]
pub struct StateFile {
    pub width: u32,
    pub height: u32,
    pub channels: PixelChannels,
    /// The header: the state's own entries (keys starting with [`STATE_PREFIX`]) and the
    /// caller's metadata.
    pub metadata: Metadata,
}

/// Why a checkpoint could not be read.
#[derive(Debug)]
pub struct CheckpointError {
    pub path: PathBuf,
    pub reason: String,
}

impl fmt::Display for CheckpointError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}: not a usable checkpoint: {}", self.path.display(), self.reason)
    }
}

impl std::error::Error for CheckpointError {}

fn channel_name(name: &str) -> String {
    format!("{METADATA_PREFIX}{name}")
}

/// Hash of the exact state: the size, every channel's name and bits, and the header's state
/// entries.
fn state_hash(size: (u32, u32), channels: &PixelChannels, header: &Metadata) -> u64 {
    let mut hasher = std::hash::DefaultHasher::new();
    size.hash(&mut hasher);
    for (name, values) in &channels.f64s {
        name.hash(&mut hasher);
        values.iter().map(|v| v.to_bits()).for_each(|b| b.hash(&mut hasher));
    }
    channels.u32s.hash(&mut hasher);
    header.iter().filter(|(k, _)| k.starts_with(STATE_PREFIX)).for_each(|entry| entry.hash(&mut hasher));
    hasher.finish()
}

/// Writes `channels` with `preview` as the visible image and `header` (metadata and state
/// entries) to `path`, atomically.
///
/// # Panics
/// If a channel does not have one value per pixel of `preview`.
pub fn write_state(
    path: &Path,
    preview: &Film,
    channels: &PixelChannels,
    header: &Metadata,
) -> Result<(), ImageWriteError> {
    use exr::prelude::{AnyChannel, AnyChannels, Encoding, FlatSamples, Image, Layer, LayerAttributes, WritableImage};
    let pixels = preview.pixels.len();
    let mut list = Vec::with_capacity(3 + 2 * channels.f64s.len() + channels.u32s.len());
    for (k, name) in ["R", "G", "B"].into_iter().enumerate() {
        let values = preview.pixels.iter().map(|p| p.value()[k] as f32).collect();
        list.push(AnyChannel::new(name, FlatSamples::F32(values)));
    }
    for (name, values) in &channels.f64s {
        assert_eq!(values.len(), pixels, "channel {name}: one value per pixel");
        let hi = values.iter().map(|v| (v.to_bits() >> 32) as u32).collect();
        let lo = values.iter().map(|v| v.to_bits() as u32).collect();
        list.push(AnyChannel::new(channel_name(&format!("{name}.hi")).as_str(), FlatSamples::U32(hi)));
        list.push(AnyChannel::new(channel_name(&format!("{name}.lo")).as_str(), FlatSamples::U32(lo)));
    }
    for (name, values) in &channels.u32s {
        assert_eq!(values.len(), pixels, "channel {name}: one value per pixel");
        list.push(AnyChannel::new(channel_name(name).as_str(), FlatSamples::U32(values.clone())));
    }
    let size = (preview.width, preview.height);
    let mut header = header.clone();
    header.insert(STATE_HASH.into(), format!("{:016x}", state_hash(size, channels, &header)));
    let mut attributes = LayerAttributes::default();
    attributes.other.extend(exr_attributes(&header));
    let size = (size.0 as usize, size.1 as usize);
    let layer = Layer::new(size, attributes, Encoding::FAST_LOSSLESS, AnyChannels::sort(list.into()));
    write_atomically(path, |temporary| {
        Image::from_layer(layer).write().to_file(temporary).map_err(|e| ImageWriteError::Encode {
            path: temporary.to_owned(),
            format: super::ImageFormat::Exr,
            source: Box::new(e),
        })
    })
}

/// Reads the channels named `f64s` and `u32s` of a state written by [`write_state`], refusing
/// files that are damaged or lack one of them. The file is only read.
pub fn read_state(path: &Path, f64s: &[&'static str], u32s: &[&'static str]) -> Result<StateFile, CheckpointError> {
    use exr::prelude::{read, FlatSamples, ReadChannels as _, ReadLayers as _};
    let error = |reason: String| CheckpointError { path: path.to_owned(), reason };
    let image = read()
        .no_deep_data()
        .largest_resolution_level()
        .all_channels()
        .first_valid_layer()
        .all_attributes()
        .from_file(path)
        .map_err(|e| error(e.to_string()))?;
    let layer = &image.layer_data;
    let count = layer.size.0 * layer.size.1;
    let u32_channel = |name: &str| -> Result<&[u32], CheckpointError> {
        let full = channel_name(name);
        let channel = layer
            .channel_data
            .list
            .iter()
            .find(|c| c.name.as_slice() == full.as_bytes())
            .ok_or_else(|| error(format!("it has no channel {full} (an image, not a checkpoint?)")))?;
        match &channel.sample_data {
            FlatSamples::U32(values) if values.len() == count => Ok(values),
            _ => Err(error(format!("channel {full} is not {count} unsigned integers"))),
        }
    };
    let f64_channel = |name: &'static str| -> Result<(&'static str, Vec<f64>), CheckpointError> {
        let (hi, lo) = (u32_channel(&format!("{name}.hi"))?, u32_channel(&format!("{name}.lo"))?);
        Ok((name, hi.iter().zip(lo).map(|(&h, &l)| f64::from_bits(u64::from(h) << 32 | u64::from(l))).collect()))
    };
    let channels = PixelChannels {
        f64s: f64s.iter().map(|&name| f64_channel(name)).collect::<Result<_, _>>()?,
        u32s: u32s.iter().map(|&name| Ok((name, u32_channel(name)?.to_vec()))).collect::<Result<_, _>>()?,
    };
    let mut metadata = from_exr_attributes(layer.attributes.other.iter().chain(&image.attributes.other));
    let hash = metadata.remove(STATE_HASH).ok_or_else(|| error(format!("the header has no {STATE_HASH}")))?;
    let width = u32::try_from(layer.size.0).map_err(|_| error("too wide".into()))?;
    let height = u32::try_from(layer.size.1).map_err(|_| error("too tall".into()))?;
    // Hashed over the channels asked for: the ones this state is continued from.
    if format!("{:016x}", state_hash((width, height), &channels, &metadata)) != hash {
        return Err(error("its pixels do not match the hash in its header: the file is damaged".into()));
    }
    Ok(StateFile { width, height, channels, metadata })
}

/// A film's sums and counts and the pass `targets` as channels.
fn film_channels(film: &Film, targets: &[u32]) -> PixelChannels {
    let states: Vec<PixelState> = film.pixels.iter().map(PixelSum::state).collect();
    PixelChannels {
        f64s: SUMS.iter().enumerate().map(|(k, &name)| (name, states.iter().map(|(s, _)| s[k]).collect())).collect(),
        u32s: COUNTS
            .iter()
            .enumerate()
            .map(|(k, &name)| (name, states.iter().map(|(_, c)| c[k]).collect()))
            .chain([(TARGET, targets.to_vec())])
            .collect(),
    }
}

/// Writes `film` with `targets` (one per pixel) and `metadata` to `path`, atomically.
///
/// # Panics
/// If `targets` does not have one entry per pixel.
pub fn write_checkpoint(path: &Path, film: &Film, targets: &[u32], metadata: &Metadata) -> Result<(), ImageWriteError> {
    assert_eq!(targets.len(), film.pixels.len(), "one target per pixel");
    let mut header = metadata.clone();
    header.insert(NAN_SAMPLES.into(), film.nan_samples.to_string());
    write_state(path, film, &film_channels(film, targets), &header)
}

/// Reads a checkpoint written by [`write_checkpoint`], refusing files that are damaged or were
/// not written by it. The file is only read.
pub fn read_checkpoint(path: &Path) -> Result<Checkpoint, CheckpointError> {
    let mut state = read_state(path, &SUMS, &[COUNTS[0], COUNTS[1], TARGET])?;
    let error = |reason: String| CheckpointError { path: path.to_owned(), reason };
    let nan_samples = state
        .metadata
        .remove(NAN_SAMPLES)
        .and_then(|n| n.parse().ok())
        .ok_or_else(|| error(format!("the header has no {NAN_SAMPLES}")))?;
    let channels = &state.channels;
    let sums: Vec<&[f64]> = SUMS.iter().filter_map(|name| channels.f64s(name)).collect();
    let counts: Vec<&[u32]> = COUNTS.iter().filter_map(|name| channels.u32s(name)).collect();
    let pixels = (0..state.width as usize * state.height as usize)
        .map(|i| PixelSum::from_state((std::array::from_fn(|k| sums[k][i]), [counts[0][i], counts[1][i]])))
        .collect();
    let targets = channels.u32s(TARGET).map(<[u32]>::to_vec).unwrap_or_default();
    let film = Film { width: state.width, height: state.height, pixels, nan_samples };
    Ok(Checkpoint { film, targets, metadata: state.metadata })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::rgb::Rgb;

    fn temp_path(name: &str) -> PathBuf {
        std::env::temp_dir().join(format!("nullpath-checkpoint-{}-{name}.exr", std::process::id()))
    }

    fn film() -> Film {
        let mut film = Film::new(5, 3);
        for (i, (x, y)) in film.bounds().pixels().enumerate() {
            for s in 0..(i % 4) {
                film.add_sample(x, y, Rgb::new(0.1 * s as f32, 1.0 / 3.0, 7.0 + x as f32), 1.0 - 0.3 * s as f64);
            }
        }
        film.add_sample(1, 1, Rgb::splat(f32::NAN), 1.0);
        film
    }

    #[test]
    fn a_checkpoint_round_trips_every_bit() {
        let (film, path) = (film(), temp_path("round-trip"));
        let targets: Vec<u32> = (0..15).collect();
        let metadata = Metadata::from([("scene".into(), "room → hole".into())]);
        write_checkpoint(&path, &film, &targets, &metadata).unwrap();
        let read = read_checkpoint(&path).unwrap();
        std::fs::remove_file(&path).unwrap();
        assert_eq!(read.film.pixels, film.pixels);
        assert_eq!((read.film.width, read.film.height, read.film.nan_samples), (5, 3, 1));
        assert_eq!(read.targets, targets);
        assert_eq!(read.metadata, metadata);
    }

    #[test]
    fn damaged_files_and_plain_images_are_refused() {
        let (film, path) = (film(), temp_path("damaged"));
        write_checkpoint(&path, &film, &[0; 15], &Metadata::new()).unwrap();
        let mut bytes = std::fs::read(&path).unwrap();
        // Truncated: the reader fails.
        std::fs::write(&path, &bytes[..bytes.len() / 2]).unwrap();
        assert!(read_checkpoint(&path).is_err());
        // One byte of the last chunk changed: decompression or the hash catches it.
        let last = bytes.len() - 3;
        bytes[last] ^= 0x5a;
        std::fs::write(&path, &bytes).unwrap();
        let err = read_checkpoint(&path).expect_err("damaged");
        assert!(err.to_string().contains(&path.display().to_string()), "{err}");
        // A plain image is not a checkpoint.
        super::super::write_image(&film, &path, &Default::default(), &Metadata::new()).unwrap();
        let err = read_checkpoint(&path).expect_err("image");
        assert!(err.to_string().contains("not a checkpoint"), "{err}");
        std::fs::remove_file(&path).unwrap();
    }
}

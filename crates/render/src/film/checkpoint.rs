//! Checkpoints: a film's exact state in an OpenEXR file, to continue a render later, on this
//! machine or another.
//!
//! The file is an ordinary linear EXR whose `R`, `G`, `B` channels hold the image as it stands
//! (any EXR viewer shows it), plus the exact accumulators of every pixel: each `f64` sum as two
//! `u32` channels of its bits (`nullpath.<sum>.hi` and `.lo`; EXR has no 64-bit samples), the
//! sample counts `nullpath.count` and `nullpath.taken`, and the per-pixel sample target of the
//! pass in progress, `nullpath.target`. The header holds the caller's [`Metadata`], the film's
//! rejected-sample count and a hash of the state, so that a damaged file is refused rather than
//! continued. Files are written atomically (temporary sibling, then rename), so an interrupted
//! write leaves the previous checkpoint intact.

use super::output::{exr_attributes, from_exr_attributes, write_atomically, Metadata, METADATA_PREFIX};
use super::pixel::{PixelState, PixelSum};
use super::{Film, ImageWriteError};
use std::fmt;
use std::hash::{Hash, Hasher};
use std::path::{Path, PathBuf};

/// Names of the `f64` accumulators, in [`PixelState`] order.
const SUMS: [&str; 6] = ["r", "g", "b", "weight", "odd_y", "odd_weight"];
/// Names of the `u32` counters, in [`PixelState`] order.
const COUNTS: [&str; 2] = ["count", "taken"];
const TARGET: &str = "target";
/// Header keys the checkpoint itself owns (beside the caller's metadata).
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

/// Hash of the exact state (bits of every accumulator and counter, and the targets).
fn state_hash(film: &Film, targets: &[u32]) -> u64 {
    let mut hasher = std::hash::DefaultHasher::new();
    (film.width, film.height, film.nan_samples).hash(&mut hasher);
    for p in &film.pixels {
        let (sums, counts) = p.state();
        sums.map(f64::to_bits).hash(&mut hasher);
        counts.hash(&mut hasher);
    }
    targets.hash(&mut hasher);
    hasher.finish()
}

/// Writes `film` with `targets` (one per pixel) and `metadata` to `path`, atomically.
///
/// # Panics
/// If `targets` does not have one entry per pixel.
pub fn write_checkpoint(path: &Path, film: &Film, targets: &[u32], metadata: &Metadata) -> Result<(), ImageWriteError> {
    use exr::prelude::{AnyChannel, AnyChannels, Encoding, FlatSamples, Image, Layer, LayerAttributes, WritableImage};
    assert_eq!(targets.len(), film.pixels.len(), "one target per pixel");
    let states: Vec<PixelState> = film.pixels.iter().map(PixelSum::state).collect();
    let mut channels = Vec::with_capacity(3 + 2 * SUMS.len() + COUNTS.len() + 1);
    for (k, name) in ["R", "G", "B"].into_iter().enumerate() {
        let values = film.pixels.iter().map(|p| p.value()[k] as f32).collect();
        channels.push(AnyChannel::new(name, FlatSamples::F32(values)));
    }
    for (k, name) in SUMS.into_iter().enumerate() {
        let bits = || states.iter().map(move |(sums, _)| sums[k].to_bits());
        let hi = bits().map(|b| (b >> 32) as u32).collect();
        let lo = bits().map(|b| b as u32).collect();
        channels.push(AnyChannel::new(channel_name(&format!("{name}.hi")).as_str(), FlatSamples::U32(hi)));
        channels.push(AnyChannel::new(channel_name(&format!("{name}.lo")).as_str(), FlatSamples::U32(lo)));
    }
    for (k, name) in COUNTS.into_iter().enumerate() {
        let values = states.iter().map(|(_, counts)| counts[k]).collect();
        channels.push(AnyChannel::new(channel_name(name).as_str(), FlatSamples::U32(values)));
    }
    channels.push(AnyChannel::new(channel_name(TARGET).as_str(), FlatSamples::U32(targets.to_vec())));

    let mut header = metadata.clone();
    header.insert(NAN_SAMPLES.into(), film.nan_samples.to_string());
    header.insert(STATE_HASH.into(), format!("{:016x}", state_hash(film, targets)));
    let mut attributes = LayerAttributes::default();
    attributes.other.extend(exr_attributes(&header));
    let size = (film.width as usize, film.height as usize);
    let layer = Layer::new(size, attributes, Encoding::FAST_LOSSLESS, AnyChannels::sort(channels.into()));
    write_atomically(path, |temporary| {
        Image::from_layer(layer).write().to_file(temporary).map_err(|e| ImageWriteError::Encode {
            path: temporary.to_owned(),
            format: super::ImageFormat::Exr,
            source: Box::new(e),
        })
    })
}

/// Reads a checkpoint written by [`write_checkpoint`], refusing files that are damaged or were
/// not written by it. The file is only read.
pub fn read_checkpoint(path: &Path) -> Result<Checkpoint, CheckpointError> {
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
    let (width, height) = (layer.size.0, layer.size.1);
    let count = width * height;
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
    let sums: Vec<(&[u32], &[u32])> = SUMS
        .iter()
        .map(|name| Ok((u32_channel(&format!("{name}.hi"))?, u32_channel(&format!("{name}.lo"))?)))
        .collect::<Result<_, CheckpointError>>()?;
    let counts: Vec<&[u32]> = COUNTS.iter().map(|name| u32_channel(name)).collect::<Result<_, _>>()?;
    let targets = u32_channel(TARGET)?.to_vec();
    let pixels = (0..count)
        .map(|i| {
            let sum = |k: usize| f64::from_bits(u64::from(sums[k].0[i]) << 32 | u64::from(sums[k].1[i]));
            PixelSum::from_state((std::array::from_fn(sum), [counts[0][i], counts[1][i]]))
        })
        .collect();

    let mut metadata = from_exr_attributes(layer.attributes.other.iter().chain(&image.attributes.other));
    let nan_samples = metadata
        .remove(NAN_SAMPLES)
        .and_then(|n| n.parse().ok())
        .ok_or_else(|| error(format!("the header has no {NAN_SAMPLES}")))?;
    let hash = metadata.remove(STATE_HASH).ok_or_else(|| error(format!("the header has no {STATE_HASH}")))?;
    let (width, height) = (
        u32::try_from(width).map_err(|_| error("too wide".into()))?,
        u32::try_from(height).map_err(|_| error("too tall".into()))?,
    );
    let film = Film { width, height, pixels, nan_samples };
    if format!("{:016x}", state_hash(&film, &targets)) != hash {
        return Err(error("its pixels do not match the hash in its header: the file is damaged".into()));
    }
    Ok(Checkpoint { film, targets, metadata })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::color::Rgb;

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

//! An SPPM render between iterations: every pixel's estimate and the iterations finished, with
//! their checkpoint encoding (see [`crate::film::write_state`]). The iterations are
//! deterministic given the state they start from, so a render continued from a checkpoint
//! gives the uninterrupted render's image bit for bit.

use super::pixel::PixelEstimate;
use crate::film::{read_state, write_state, CheckpointError, Film, ImageWriteError, Metadata, PixelChannels};
use std::path::Path;

/// Channel names of [`PixelEstimate::to_array`]'s entries.
const ESTIMATE: [&str; 9] = [
    "sppm.radius",
    "sppm.kept",
    "sppm.tau_r",
    "sppm.tau_g",
    "sppm.tau_b",
    "sppm.emitted_r",
    "sppm.emitted_g",
    "sppm.emitted_b",
    "sppm.weight",
];
const ITERATIONS: &str = "checkpoint.sppm.iterations";
const DROPPED: &str = "checkpoint.sppm.dropped";

/// Every pixel's progressive estimate after some iterations.
#[derive(Clone, Debug, PartialEq)]
pub struct SppmState {
    width: u32,
    height: u32,
    pub(super) pixels: Vec<PixelEstimate>,
    /// Iterations finished.
    pub(super) iterations: u32,
    /// Camera samples and photon deposits dropped for being NaN or infinite.
    pub(super) dropped: u64,
}

impl SppmState {
    /// No iteration yet.
    pub fn new(width: u32, height: u32) -> Self {
        let pixels = vec![PixelEstimate::new(); width as usize * height as usize];
        Self { width, height, pixels, iterations: 0, dropped: 0 }
    }

    pub fn width(&self) -> u32 {
        self.width
    }

    pub fn height(&self) -> u32 {
        self.height
    }

    /// Iterations finished.
    pub fn iterations(&self) -> u32 {
        self.iterations
    }

    /// Samples and deposits dropped for being NaN or infinite.
    pub fn dropped(&self) -> u64 {
        self.dropped
    }

    /// The image as it stands, each pixel one sample of weight 1, with `photons` photons an
    /// iteration.
    pub fn film(&self, photons: u64) -> Film {
        let mut film = Film::new(self.width, self.height);
        for (i, pixel) in self.pixels.iter().enumerate() {
            if let Some(l) = pixel.radiance(photons) {
                film.add_sample(i as u32 % self.width, i as u32 / self.width, l, 1.0);
            }
        }
        film
    }

    /// Writes the state to `path` (atomically) with `metadata`, its image made with `photons`
    /// photons an iteration.
    pub fn write(&self, path: &Path, photons: u64, metadata: &Metadata) -> Result<(), ImageWriteError> {
        let values = |k: usize| self.pixels.iter().map(|p| p.to_array()[k]).collect();
        let channels = PixelChannels {
            f64s: ESTIMATE.iter().enumerate().map(|(k, &name)| (name, values(k))).collect(),
            u32s: Vec::new(),
        };
        let mut header = metadata.clone();
        header.insert(ITERATIONS.into(), self.iterations.to_string());
        header.insert(DROPPED.into(), self.dropped.to_string());
        write_state(path, &self.film(photons), &channels, &header)
    }

    /// Reads a state written by [`SppmState::write`] and the caller's metadata, refusing damaged
    /// files and other checkpoints.
    pub fn read(path: &Path) -> Result<(Self, Metadata), CheckpointError> {
        let mut file = read_state(path, &ESTIMATE, &[])?;
        let mut take = |key: &str| {
            file.metadata.remove(key).and_then(|v| v.parse::<u64>().ok()).ok_or_else(|| CheckpointError {
                path: path.to_owned(),
                reason: format!("the header has no {key} (not a photon-mapping checkpoint?)"),
            })
        };
        let iterations = take(ITERATIONS)?;
        let dropped = take(DROPPED)?;
        let iterations = u32::try_from(iterations)
            .map_err(|_| CheckpointError { path: path.to_owned(), reason: format!("{ITERATIONS} is too large") })?;
        let channels: Vec<&[f64]> = ESTIMATE.iter().filter_map(|name| file.channels.f64s(name)).collect();
        let pixels = (0..file.width as usize * file.height as usize)
            .map(|i| PixelEstimate::from_array(std::array::from_fn(|k| channels[k][i])))
            .collect();
        let state = Self { width: file.width, height: file.height, pixels, iterations, dropped };
        Ok((state, file.metadata))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::rgb::Rgb;

    #[test]
    fn a_state_round_trips_every_bit_and_damage_is_refused() {
        let mut state = SppmState::new(3, 2);
        state.pixels[1].add_iteration(Rgb::new(0.1, 0.2, 1.0 / 3.0), 0.75, (0.25, [1.0, 2.0, 3.0]), 7);
        state.pixels[4].add_iteration(Rgb::ZERO, 1.0, (0.5, [0.0; 3]), 0);
        (state.iterations, state.dropped) = (5, 2);
        let path = std::env::temp_dir().join(format!("nullpath-sppm-{}.exr", std::process::id()));
        let metadata = Metadata::from([("scene".into(), "room".into())]);
        state.write(&path, 100, &metadata).unwrap();
        let (read, read_metadata) = SppmState::read(&path).unwrap();
        assert_eq!(read, state);
        assert_eq!(read_metadata, metadata);
        // A path tracer's checkpoint is not an SPPM state.
        crate::film::write_checkpoint(&path, &Film::new(3, 2), &[0; 6], &metadata).unwrap();
        assert!(SppmState::read(&path).is_err());
        std::fs::remove_file(&path).unwrap();
    }
}

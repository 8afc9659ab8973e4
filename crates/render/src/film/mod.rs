//! The film: per-pixel accumulation of camera samples, reconstruction filters, tone mapping and
//! image output.
//!
//! # Conventions
//! * Pixel `(x, y)` has `x` to the right and `y` downward; `(0, 0)` is the top-left pixel and the
//!   first pixel written to image files. Its centre is at continuous film position
//!   `(x + 0.5, y + 0.5)`.
//! * Radiance is linear Rec. 709 RGB ([`Rgb`]); sums are kept in `f64`.
//!
//! # Determinism
//! Reconstruction uses *filter importance sampling* (pbrt-v4 §8.8): the camera places each sample
//! of pixel `(x, y)` at `centre + Filter::sample(u).offset` and the sample contributes to that
//! pixel alone, with weight [`FilterSample::weight`]. No sample is ever splatted into a neighbour,
//! so a pixel's value depends only on its own samples, in the order its (single) renderer adds
//! them. Render disjoint [`FilmTile`]s on any number of threads and merge them in any order: the
//! image is bit-identical.
//!
//! ```
//! use render::rgb::Rgb;
//! use render::film::{Film, FilmTile, Filter};
//! use render::sampling::Rng;
//!
//! let filter = Filter::default();
//! let mut film = Film::new(4, 3);
//! for bounds in film.tiles(2) {
//!     // Typically on a thread pool; each tile is independent.
//!     let mut tile = FilmTile::new(bounds);
//!     for (x, y) in bounds.pixels() {
//!         for s in 0..4 {
//!             let pixel_index = u64::from(y) * 4 + u64::from(x);
//!             let mut rng = Rng::for_sample(7, pixel_index, s);
//!             let fs = filter.sample(rng.next_2d());
//!             let _film_position = [
//!                 f64::from(x) + 0.5 + fs.offset[0],
//!                 f64::from(y) + 0.5 + fs.offset[1],
//!             ];
//!             let radiance = Rgb::splat(0.5); // trace a ray through _film_position here
//!             tile.add_sample(x, y, radiance, fs.weight);
//!         }
//!     }
//!     film.merge_tile(tile);
//! }
//! assert_eq!(film.pixel(3, 2), Rgb::splat(0.5));
//! ```

mod checkpoint;
mod data;
mod filter;
pub mod noise;
mod output;
mod pixel;
mod tile;
mod tonemap;

pub use checkpoint::{
    read_checkpoint, read_state, write_checkpoint, write_state, Checkpoint, CheckpointError, PixelChannels, StateFile,
    STATE_PREFIX,
};
pub use data::{DataChannel, DataLayer, FirstMet, PixelData, SpectrumChannels};
pub use filter::{
    BlackmanHarrisFilter, BoxFilter, Filter, FilterError, FilterKind, FilterSample, GaussianFilter, MitchellFilter,
    TentFilter, FILTERS, MAX_FILTER_RADIUS, MITCHELL_RECOMMENDED_B_C,
};
pub use output::{
    check_output_path, check_writable, linear_pixels, read_metadata, write_data_image, write_file_atomically,
    write_image, write_image_with_data, ImageFormat, ImageWriteError, Metadata, MetadataReadError, METADATA_PREFIX,
};
pub use tile::{FilmTile, TileBounds};
pub use tonemap::{srgb_oetf, to_rgb8, Curve, ToneMap};

use crate::rgb::Rgb;
use pixel::{is_valid_sample, PixelSum};

/// A `width × height` grid of pixel accumulators.
#[derive(Clone, Debug)]
pub struct Film {
    width: u32,
    height: u32,
    /// Row-major, `y * width + x`.
    pixels: Vec<PixelSum>,
    nan_samples: u64,
}

/// A film too large for the memory that can be had.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct FilmTooLarge {
    pub width: u32,
    pub height: u32,
    /// What the film's accumulators need.
    pub bytes: u64,
}

impl std::fmt::Display for FilmTooLarge {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(
            f,
            "a {}x{} film needs {:.1} GiB of memory ({} bytes a pixel), which cannot be allocated",
            self.width,
            self.height,
            self.bytes as f64 / f64::from(1u32 << 30),
            Film::BYTES_PER_PIXEL
        )
    }
}

impl std::error::Error for FilmTooLarge {}

impl Film {
    /// Memory of one pixel's accumulators.
    pub const BYTES_PER_PIXEL: u64 = std::mem::size_of::<PixelSum>() as u64;

    /// An empty (all-black, zero-sample) film.
    ///
    /// # Panics
    /// If the memory cannot be allocated; use [`Film::try_new`] for sizes a user chose.
    pub fn new(width: u32, height: u32) -> Self {
        Self::try_new(width, height).unwrap_or_else(|e| panic!("{e}"))
    }

    /// An empty film, or an error (instead of an abort) when its memory cannot be allocated.
    pub fn try_new(width: u32, height: u32) -> Result<Self, FilmTooLarge> {
        let count = width as usize * height as usize;
        let too_large = || FilmTooLarge { width, height, bytes: count as u64 * Self::BYTES_PER_PIXEL };
        let mut pixels = Vec::new();
        pixels.try_reserve_exact(count).map_err(|_| too_large())?;
        pixels.resize(count, PixelSum::default());
        Ok(Self { width, height, pixels, nan_samples: 0 })
    }

    pub fn width(&self) -> u32 {
        self.width
    }

    pub fn height(&self) -> u32 {
        self.height
    }

    /// The whole film as one rectangle.
    pub fn bounds(&self) -> TileBounds {
        TileBounds { x0: 0, y0: 0, x1: self.width, y1: self.height }
    }

    /// Disjoint tiles of at most `tile_size × tile_size` pixels covering the film, in row-major
    /// order of tiles (a `tile_size` of 0 is treated as 1). Use `tile_size ≥ width` for rows.
    pub fn tiles(&self, tile_size: u32) -> Vec<TileBounds> {
        TileBounds::grid(self.width, self.height, tile_size)
    }

    /// Accumulates one sample of pixel `(x, y)` with its filter weight (see the module docs). A
    /// sample whose radiance or weight is NaN or infinite is not accumulated; it is counted in
    /// [`Film::nan_samples`].
    ///
    /// # Panics
    /// If `(x, y)` lies outside the film.
    pub fn add_sample(&mut self, x: u32, y: u32, radiance: Rgb, weight: f64) {
        let index = self.index(x, y);
        if is_valid_sample(radiance, weight) {
            self.pixels[index].add(radiance, weight);
        } else {
            self.pixels[index].reject();
            self.nan_samples += 1;
        }
    }

    /// A tile over `bounds` that continues this film's sums: render more samples into it (each
    /// pixel continuing from its [`Film::taken_at`]) and hand it back with [`Film::store_tile`].
    /// Each pixel's sums then grow one sample at a time in sample order, however the samples are
    /// split into passes, so a render continued in passes, or stopped and resumed, is
    /// bit-identical to one made in one go.
    ///
    /// # Panics
    /// If the tile does not lie inside the film.
    pub fn tile(&self, bounds: TileBounds) -> FilmTile {
        self.check_fits(bounds);
        let pixels = bounds.pixels().map(|(x, y)| self.pixels[self.index(x, y)]).collect();
        FilmTile::continuing(bounds, pixels)
    }

    /// Puts a tile made by [`Film::tile`] back: its pixels replace the film's, and its rejected
    /// samples are counted.
    ///
    /// # Panics
    /// If the tile does not lie inside the film.
    pub fn store_tile(&mut self, tile: FilmTile) {
        self.for_tile_rows(&tile, |dst, src| *dst = *src);
        self.nan_samples += tile.nan_samples();
    }

    /// Copies the pixels of `tiles` from `other` (a film of the same size, e.g. one part of a
    /// split render) and adds its rejected-sample count.
    ///
    /// # Panics
    /// If the films differ in size or a tile does not fit.
    pub fn copy_tiles(&mut self, other: &Film, tiles: &[TileBounds]) {
        assert_eq!((self.width, self.height), (other.width, other.height), "films differ in size");
        for &bounds in tiles {
            self.store_tile(other.tile(bounds));
        }
        self.nan_samples += other.nan_samples;
    }

    /// Adds a tile's accumulators and rejected-sample count into the film.
    ///
    /// Merging is a per-pixel `f64` addition. When each pixel is covered by one tile (tiles from
    /// [`Film::tiles`]), merge order cannot change any pixel. If the same pixel receives several
    /// tiles (e.g. progressive passes), merge them in a fixed order to stay bit-reproducible.
    ///
    /// # Panics
    /// If the tile does not lie inside the film.
    pub fn merge_tile(&mut self, tile: FilmTile) {
        self.for_tile_rows(&tile, PixelSum::merge);
        self.nan_samples += tile.nan_samples();
    }

    /// Applies `f` to each film pixel and the tile's pixel over it.
    fn for_tile_rows(&mut self, tile: &FilmTile, f: impl Fn(&mut PixelSum, &PixelSum)) {
        let b = tile.bounds();
        self.check_fits(b);
        let tile_width = b.width() as usize;
        if tile_width > 0 {
            for (row, sums) in tile.pixel_sums().chunks_exact(tile_width).enumerate() {
                let start = self.index(b.x0, b.y0 + row as u32);
                for (dst, src) in self.pixels[start..start + tile_width].iter_mut().zip(sums) {
                    f(dst, src);
                }
            }
        }
    }

    fn check_fits(&self, b: TileBounds) {
        assert!(
            b.x1 <= self.width && b.y1 <= self.height,
            "tile {b:?} does not fit in a {}x{} film",
            self.width,
            self.height
        );
    }

    /// The reconstructed radiance of pixel `(x, y)`: the weighted mean of its own samples, black
    /// where it has none.
    ///
    /// # Panics
    /// If `(x, y)` lies outside the film.
    pub fn pixel(&self, x: u32, y: u32) -> Rgb {
        let [r, g, b] = self.pixel_f64(x, y);
        Rgb::new(r as f32, g as f32, b as f32)
    }

    /// [`Film::pixel`] at full `f64` precision.
    pub fn pixel_f64(&self, x: u32, y: u32) -> [f64; 3] {
        self.pixels[self.index(x, y)].value()
    }

    /// Number of samples accumulated at pixel `(x, y)` (rejected NaN/Inf samples excluded).
    pub fn samples_at(&self, x: u32, y: u32) -> u64 {
        self.pixels[self.index(x, y)].count()
    }

    /// Samples drawn at pixel `(x, y)`, rejected ones included: the index of its next sample.
    pub fn taken_at(&self, x: u32, y: u32) -> u32 {
        self.pixels[self.index(x, y)].taken()
    }

    /// The luminance estimates of pixel `(x, y)` from its even and its odd samples, two
    /// independent halves (see [`noise`]); `None` before each half has positive weight.
    pub fn half_luminances(&self, x: u32, y: u32) -> Option<(f64, f64)> {
        self.pixels[self.index(x, y)].half_luminances()
    }

    /// Number of samples rejected, over the whole film, because their radiance or weight was NaN
    /// or infinite.
    pub fn nan_samples(&self) -> u64 {
        self.nan_samples
    }

    fn index(&self, x: u32, y: u32) -> usize {
        assert!(
            x < self.width && y < self.height,
            "pixel ({x}, {y}) is outside the {}x{} film",
            self.width,
            self.height
        );
        y as usize * self.width as usize + x as usize
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::sampling::Rng;
    use rayon::prelude::*;

    #[test]
    fn new_film_is_black_with_no_samples() {
        let film = Film::new(3, 2);
        assert_eq!((film.width(), film.height()), (3, 2));
        assert_eq!(film.pixel(2, 1), Rgb::ZERO);
        assert_eq!(film.samples_at(2, 1), 0);
        assert_eq!(film.nan_samples(), 0);
    }

    #[test]
    fn pixel_is_the_weighted_mean_of_its_own_samples() {
        let mut film = Film::new(2, 2);
        film.add_sample(1, 0, Rgb::new(1.0, 2.0, 3.0), 1.0);
        film.add_sample(1, 0, Rgb::new(3.0, 4.0, 5.0), 1.0);
        film.add_sample(0, 1, Rgb::new(0.5, 0.0, 1.0), 3.0);
        film.add_sample(0, 1, Rgb::new(2.5, 4.0, 1.0), 1.0);
        // All sums are exact in binary, so the means are exact.
        assert_eq!(film.pixel(1, 0), Rgb::new(2.0, 3.0, 4.0));
        assert_eq!(film.pixel(0, 1), Rgb::new(1.0, 1.0, 1.0));
        assert_eq!(film.samples_at(1, 0), 2);
        // Neighbours are untouched: no splatting.
        assert_eq!(film.pixel(0, 0), Rgb::ZERO);
        assert_eq!(film.samples_at(1, 1), 0);
    }

    #[test]
    fn non_finite_samples_are_counted_not_accumulated() {
        let mut film = Film::new(1, 1);
        film.add_sample(0, 0, Rgb::splat(0.25), 1.0);
        film.add_sample(0, 0, Rgb::new(f32::NAN, 1.0, 1.0), 1.0);
        film.add_sample(0, 0, Rgb::new(1.0, f32::INFINITY, 1.0), 1.0);
        film.add_sample(0, 0, Rgb::new(1.0, 1.0, f32::NEG_INFINITY), 1.0);
        film.add_sample(0, 0, Rgb::ONE, f64::NAN);
        assert_eq!(film.nan_samples(), 4);
        assert_eq!(film.samples_at(0, 0), 1);
        assert_eq!(film.pixel(0, 0), Rgb::splat(0.25));
    }

    #[test]
    fn mitchell_weighted_mean_of_a_constant_is_the_constant() {
        let b = MITCHELL_RECOMMENDED_B_C;
        let filter = Filter::mitchell([2.0, 2.0], b, b).expect("valid mitchell");
        let constant = Rgb::new(0.37, 1.5, 12.0);
        let mut film = Film::new(8, 1);
        let mut negative = 0;
        for x in 0..8 {
            // Few samples per pixel, so some pixels have far more negative weight than average.
            for s in 0..(3 + 2 * u64::from(x)) {
                let fs = filter.sample(Rng::for_sample(11, u64::from(x), s).next_2d());
                negative += usize::from(fs.weight < 0.0);
                film.add_sample(x, 0, constant, fs.weight);
            }
        }
        assert!(negative > 0, "Mitchell should produce negative weights");
        for x in 0..8 {
            let p = film.pixel(x, 0);
            assert!((p - constant).abs().max_element() <= 1e-6 * 12.0, "pixel {x}: {p}");
        }
    }

    const SPP: u64 = 7;

    /// A deterministic stand-in for the integrator: sample `s` of pixel `(x, y)` of a 19×13 film.
    fn shade(filter: &Filter, x: u32, y: u32, s: u64) -> (Rgb, f64) {
        let index = u64::from(y) * 19 + u64::from(x);
        let mut rng = Rng::for_sample(42, index, s);
        let fs = filter.sample(rng.next_2d());
        let px = f64::from(x) + 0.5 + fs.offset[0];
        let py = f64::from(y) + 0.5 + fs.offset[1];
        let radiance = if (index + s) % 29 == 0 {
            Rgb::splat(f32::NAN)
        } else {
            Rgb::new((px * 0.7).sin().abs() as f32, (py * py * 0.01) as f32, rng.next_f64() as f32 * 3.0)
        };
        (radiance, fs.weight)
    }

    fn mitchell() -> Filter {
        Filter::mitchell([2.0, 2.0], 1.0 / 3.0, 1.0 / 3.0).expect("valid mitchell")
    }

    /// Renders the tiles on `threads` threads and merges them in `order(tile_count)`.
    fn render_tiled(threads: usize, tile_size: u32, order: impl Fn(usize) -> Vec<usize>) -> Film {
        let filter = mitchell();
        let mut film = Film::new(19, 13);
        let pool = rayon::ThreadPoolBuilder::new().num_threads(threads).build().expect("pool");
        let tiles: Vec<FilmTile> = pool.install(|| {
            film.tiles(tile_size)
                .into_par_iter()
                .map(|bounds| {
                    let mut tile = FilmTile::new(bounds);
                    for (x, y) in bounds.pixels() {
                        for s in 0..SPP {
                            let (radiance, weight) = shade(&filter, x, y, s);
                            tile.add_sample(x, y, radiance, weight);
                        }
                    }
                    tile
                })
                .collect()
        });
        let mut slots: Vec<Option<FilmTile>> = tiles.into_iter().map(Some).collect();
        for i in order(slots.len()) {
            film.merge_tile(slots[i].take().expect("each tile merged once"));
        }
        film
    }

    fn bits(film: &Film) -> Vec<u64> {
        film.bounds()
            .pixels()
            .flat_map(|(x, y)| film.pixel_f64(x, y).map(f64::to_bits))
            .chain([film.nan_samples()])
            .collect()
    }

    #[test]
    fn tile_merge_order_and_thread_count_do_not_change_a_bit() {
        let forward = render_tiled(1, 4, |n| (0..n).collect());
        let reversed = render_tiled(2, 4, |n| (0..n).rev().collect());
        let strided = render_tiled(3, 4, |n| (0..n).map(|i| (i * 7) % n).collect());
        let rows = render_tiled(2, 19, |n| (0..n).rev().collect());
        assert!(forward.nan_samples() > 0);
        assert_eq!(bits(&forward), bits(&reversed));
        assert_eq!(bits(&forward), bits(&strided));
        assert_eq!(bits(&forward), bits(&rows));

        // The same samples added straight to the film, without tiles, agree bit for bit too.
        let filter = mitchell();
        let mut direct = Film::new(19, 13);
        for (x, y) in direct.bounds().pixels() {
            for s in 0..SPP {
                let (radiance, weight) = shade(&filter, x, y, s);
                direct.add_sample(x, y, radiance, weight);
            }
        }
        assert_eq!(bits(&direct), bits(&forward));
    }

    #[test]
    #[should_panic(expected = "does not fit")]
    fn merging_a_tile_outside_the_film_panics() {
        let mut film = Film::new(4, 4);
        film.merge_tile(FilmTile::new(TileBounds { x0: 2, y0: 2, x1: 5, y1: 4 }));
    }

    #[test]
    #[should_panic(expected = "outside the 2x2 film")]
    fn sample_outside_the_film_panics() {
        Film::new(2, 2).add_sample(0, 2, Rgb::ONE, 1.0);
    }
}

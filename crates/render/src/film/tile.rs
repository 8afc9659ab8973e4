//! Tiles: disjoint rectangles of the film that threads render independently and hand back to be
//! merged. Because tiles never overlap, every pixel receives its samples from exactly one tile, and
//! the order in which tiles are merged cannot change any pixel.

use super::pixel::{is_valid_sample, PixelSum};
use crate::rgb::Rgb;

/// A half-open rectangle of pixels, `x0 ≤ x < x1`, `y0 ≤ y < y1`, in absolute film coordinates.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct TileBounds {
    pub x0: u32,
    pub y0: u32,
    pub x1: u32,
    pub y1: u32,
}

impl TileBounds {
    /// Width in pixels (zero if `x1 ≤ x0`).
    pub fn width(&self) -> u32 {
        self.x1.saturating_sub(self.x0)
    }

    /// Height in pixels (zero if `y1 ≤ y0`).
    pub fn height(&self) -> u32 {
        self.y1.saturating_sub(self.y0)
    }

    /// Number of pixels in the rectangle.
    pub fn pixel_count(&self) -> usize {
        self.width() as usize * self.height() as usize
    }

    pub fn contains(&self, x: u32, y: u32) -> bool {
        (self.x0..self.x1).contains(&x) && (self.y0..self.y1).contains(&y)
    }

    /// The pixels of the rectangle in row-major order, as absolute `(x, y)`.
    pub fn pixels(&self) -> impl Iterator<Item = (u32, u32)> {
        let (x0, x1) = (self.x0, self.x1);
        (self.y0..self.y1).flat_map(move |y| (x0..x1).map(move |x| (x, y)))
    }

    /// Splits a `width × height` image into tiles of at most `tile_size × tile_size` pixels, in
    /// row-major order of tiles (edge tiles are clipped). A `tile_size` of 0 is treated as 1.
    pub(crate) fn grid(width: u32, height: u32, tile_size: u32) -> Vec<TileBounds> {
        let size = tile_size.max(1);
        let mut tiles = Vec::new();
        for y0 in (0..height).step_by(size as usize) {
            for x0 in (0..width).step_by(size as usize) {
                tiles.push(TileBounds {
                    x0,
                    y0,
                    x1: x0.saturating_add(size).min(width),
                    y1: y0.saturating_add(size).min(height),
                });
            }
        }
        tiles
    }
}

/// A tile's own accumulators: render into it on any thread, then give it to `Film::merge_tile`.
#[derive(Clone, Debug)]
pub struct FilmTile {
    bounds: TileBounds,
    pixels: Vec<PixelSum>,
    nan_samples: u64,
}

impl FilmTile {
    /// An empty tile covering `bounds` (an empty rectangle gives a tile with no pixels).
    pub fn new(bounds: TileBounds) -> Self {
        Self { bounds, pixels: vec![PixelSum::default(); bounds.pixel_count()], nan_samples: 0 }
    }

    /// A tile that continues the given pixel sums (row-major over `bounds`).
    pub(crate) fn continuing(bounds: TileBounds, pixels: Vec<PixelSum>) -> Self {
        assert_eq!(pixels.len(), bounds.pixel_count(), "pixel sums for a tile of another size");
        Self { bounds, pixels, nan_samples: 0 }
    }

    pub fn bounds(&self) -> TileBounds {
        self.bounds
    }

    /// Accumulates one sample of pixel `(x, y)` (absolute film coordinates). A sample whose
    /// radiance or weight is NaN or infinite is not accumulated; it is counted in
    /// [`FilmTile::nan_samples`].
    ///
    /// # Panics
    /// If `(x, y)` lies outside the tile: that is a bug in the caller's loop, not bad input.
    pub fn add_sample(&mut self, x: u32, y: u32, radiance: Rgb, weight: f64) {
        let index = self.index(x, y);
        if is_valid_sample(radiance, weight) {
            self.pixels[index].add(radiance, weight);
        } else {
            self.pixels[index].reject();
            self.nan_samples += 1;
        }
    }

    /// Samples accumulated so far at pixel `(x, y)` (absolute coordinates; panics outside).
    pub fn samples_at(&self, x: u32, y: u32) -> u64 {
        self.pixels[self.index(x, y)].count()
    }

    /// Samples drawn so far at pixel `(x, y)`, rejected ones included: the index of its next
    /// sample (absolute coordinates; panics outside).
    pub fn taken_at(&self, x: u32, y: u32) -> u32 {
        self.pixels[self.index(x, y)].taken()
    }

    /// Samples rejected because they were NaN or infinite.
    pub fn nan_samples(&self) -> u64 {
        self.nan_samples
    }

    /// The accumulators, row-major over the tile, for merging.
    pub(crate) fn pixel_sums(&self) -> &[PixelSum] {
        &self.pixels
    }

    fn index(&self, x: u32, y: u32) -> usize {
        let b = self.bounds;
        assert!(b.contains(x, y), "pixel ({x}, {y}) is outside tile {b:?}");
        (y - b.y0) as usize * b.width() as usize + (x - b.x0) as usize
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn grid_covers_every_pixel_exactly_once() {
        for (w, h, s) in [(7, 5, 3), (8, 8, 4), (1, 1, 16), (10, 3, 1), (5, 4, 0), (0, 3, 2)] {
            let tiles = TileBounds::grid(w, h, s);
            let mut hits = vec![0u32; (w * h) as usize];
            for t in &tiles {
                assert!(t.width() >= 1 && t.height() >= 1);
                assert!(t.width() <= s.max(1) && t.height() <= s.max(1));
                for (x, y) in t.pixels() {
                    hits[(y * w + x) as usize] += 1;
                }
            }
            assert!(hits.iter().all(|&n| n == 1), "{w}x{h} tiles of {s}");
        }
    }

    #[test]
    fn tile_rejects_non_finite_samples_and_counts_them() {
        let mut tile = FilmTile::new(TileBounds { x0: 2, y0: 3, x1: 4, y1: 5 });
        tile.add_sample(3, 4, Rgb::ONE, 1.0);
        tile.add_sample(3, 4, Rgb::new(f32::NAN, 0.0, 0.0), 1.0);
        tile.add_sample(2, 3, Rgb::ONE, f64::INFINITY);
        assert_eq!(tile.samples_at(3, 4), 1);
        assert_eq!(tile.samples_at(2, 3), 0);
        assert_eq!((tile.taken_at(3, 4), tile.taken_at(2, 3)), (2, 1));
        assert_eq!(tile.nan_samples(), 2);
    }

    #[test]
    #[should_panic(expected = "outside tile")]
    fn sample_outside_tile_panics() {
        let mut tile = FilmTile::new(TileBounds { x0: 0, y0: 0, x1: 2, y1: 2 });
        tile.add_sample(2, 0, Rgb::ONE, 1.0);
    }
}

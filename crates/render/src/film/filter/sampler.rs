//! Importance sampling of a tabulated pixel filter: pbrt-v4's `FilterSampler` (Pharr, Jakob &
//! Humphreys, *Physically Based Rendering*, 4th ed., §8.8) built on a piecewise-constant 2-D
//! distribution (ibid. §A.5, marginal and conditional densities of §2.4.2).
//!
//! The filter `f` is tabulated on a regular grid over its support `[-r, r]²`. Camera-sample
//! offsets are drawn with density proportional to the tabulated `|f|`, and each carries the weight
//! `sign(f) · ∫|f| / ∫f`. That weight is exactly `1` for a filter that is never negative, and for a
//! filter with negative lobes it is a constant magnitude whose expectation is `1`, so both the
//! weighted-mean and the plain-mean pixel estimators see the signed filter `f / ∫f`.
//! (pbrt-v4 instead weights by `f(p) / pdf(p)` at the sampled point; using the cell's sign keeps
//! positive filters at weight exactly 1, at the cost of reconstructing with the tabulated filter,
//! which at 64 cells per pixel differs from `f` far below Monte Carlo noise.)
//!
//! Everything is built once, in [`FilterSampler::new`]; [`FilterSampler::sample`] allocates nothing
//! and is two binary searches.

use super::{FilterError, FilterSample};
use crate::sampling::PiecewiseConstant2D;

/// Table cells per pixel of filter width along each axis (pbrt-v4 uses 16; finer tables cost only
/// construction time and a little memory, and make the step approximation of smooth filters
/// negligible next to Monte Carlo noise).
const CELLS_PER_PIXEL: f64 = 64.0;
/// Fewest table cells along an axis, for very narrow filters.
const MIN_CELLS: usize = 16;
/// Most table cells along an axis: bounds the table at `MAX_CELLS²` entries for wide filters.
const MAX_CELLS: usize = 1024;
/// Each table cell holds the mean of `f` over `SUBSAMPLES²` midpoint-rule points, so the cell's
/// probability is its share of `∫|f|`, not `|f|` at one point.
const SUBSAMPLES: usize = 4;

/// A tabulated filter, sampled with density proportional to `|f|`.
#[derive(Clone, Debug)]
pub(crate) struct FilterSampler {
    radius: [f64; 2],
    distribution: PiecewiseConstant2D,
    /// `∫|f| / ∫f` over the table; exactly `1.0` when no cell is negative.
    weight_scale: f64,
}

impl FilterSampler {
    /// Tabulates `f` over `[-radius[0], radius[0]] × [-radius[1], radius[1]]`.
    ///
    /// Fails when the filter's integral is not positive (a filter that averages to zero or less
    /// cannot be normalised) or when the table contains non-finite values.
    pub(crate) fn new(radius: [f64; 2], f: impl Fn([f64; 2]) -> f64) -> Result<Self, FilterError> {
        let nx = cells_along(radius[0]);
        let ny = cells_along(radius[1]);
        let cell = [2.0 * radius[0] / nx as f64, 2.0 * radius[1] / ny as f64];
        let mut values = Vec::with_capacity(nx * ny);
        for iy in 0..ny {
            for ix in 0..nx {
                let x0 = -radius[0] + ix as f64 * cell[0];
                let y0 = -radius[1] + iy as f64 * cell[1];
                let mut sum = 0.0;
                for sy in 0..SUBSAMPLES {
                    for sx in 0..SUBSAMPLES {
                        let px = x0 + (sx as f64 + 0.5) / SUBSAMPLES as f64 * cell[0];
                        let py = y0 + (sy as f64 + 0.5) / SUBSAMPLES as f64 * cell[1];
                        sum += f([px, py]);
                    }
                }
                values.push(sum / (SUBSAMPLES * SUBSAMPLES) as f64);
            }
        }
        if values.iter().any(|v| !v.is_finite()) {
            return Err(FilterError::NonFiniteValue);
        }
        let signed: f64 = values.iter().sum();
        let absolute: f64 = values.iter().map(|v| v.abs()).sum();
        if signed <= 0.0 {
            return Err(FilterError::NonPositiveIntegral);
        }
        let has_negative_lobes = values.iter().any(|&v| v < 0.0);
        let weight_scale = if has_negative_lobes { absolute / signed } else { 1.0 };
        Ok(Self { radius, distribution: PiecewiseConstant2D::new(values, nx, ny), weight_scale })
    }

    /// Draws an offset from the pixel centre with density `∝ |f|` and its signed weight.
    pub(crate) fn sample(&self, u: [f64; 2]) -> FilterSample {
        let (p, value) = self.distribution.sample(u);
        let offset = [(2.0 * p[0] - 1.0) * self.radius[0], (2.0 * p[1] - 1.0) * self.radius[1]];
        let weight = if value < 0.0 { -self.weight_scale } else { self.weight_scale };
        FilterSample { offset, weight }
    }
}

/// Number of table cells along an axis of half-width `radius`.
fn cells_along(radius: f64) -> usize {
    // `radius` is validated finite and positive by the filter constructors; the cast saturates.
    ((2.0 * radius * CELLS_PER_PIXEL).ceil() as usize).clamp(MIN_CELLS, MAX_CELLS)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rejects_filters_without_positive_integral() {
        assert!(matches!(FilterSampler::new([1.0, 1.0], |_| -1.0), Err(FilterError::NonPositiveIntegral)));
        assert!(matches!(FilterSampler::new([1.0, 1.0], |_| f64::NAN), Err(FilterError::NonFiniteValue)));
    }

    #[test]
    fn positive_table_gives_unit_weights_and_offsets_inside_the_support() {
        let sampler =
            FilterSampler::new([1.5, 0.75], |p| 3.0 - p[0].abs() - p[1].abs()).expect("positive filter tabulates");
        for k in 0..1000 {
            let u = [f64::from(k) / 1000.0, f64::from((k * 7919) % 1000) / 1000.0];
            let s = sampler.sample(u);
            assert_eq!(s.weight, 1.0);
            assert!(s.offset[0].abs() <= 1.5 && s.offset[1].abs() <= 0.75);
        }
    }
}

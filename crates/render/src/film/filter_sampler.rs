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

use super::filter::{FilterError, FilterSample};

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

/// A piecewise-constant density on `[0, 1)²` proportional to `|values|`, stored row-major
/// (`ny` rows of `nx` cells; row index is `y`). Sampled as the marginal over rows followed by the
/// conditional within the chosen row, each by inverting its CDF (pbrt-v4 §A.5's
/// `PiecewiseConstant2D`, flattened into three vectors).
#[derive(Clone, Debug)]
struct PiecewiseConstant2D {
    /// Cells per row.
    nx: usize,
    /// The signed tabulated function (its sign becomes the sample weight's sign).
    values: Vec<f64>,
    /// Per row, the `nx + 1` entries of that row's conditional CDF, from 0 to 1.
    conditional_cdfs: Vec<f64>,
    /// The `ny + 1` entries of the marginal CDF over rows, from 0 to 1.
    marginal_cdf: Vec<f64>,
}

impl PiecewiseConstant2D {
    /// `values` must have `nx * ny` finite entries with a positive total `|values|`.
    fn new(values: Vec<f64>, nx: usize, ny: usize) -> Self {
        let mut conditional_cdfs = Vec::with_capacity(ny * (nx + 1));
        let mut row_masses = Vec::with_capacity(ny);
        for row in values.chunks_exact(nx) {
            row_masses.push(append_cdf(&mut conditional_cdfs, row.iter().map(|v| v.abs())));
        }
        let mut marginal_cdf = Vec::with_capacity(ny + 1);
        append_cdf(&mut marginal_cdf, row_masses.into_iter());
        Self { nx, values, conditional_cdfs, marginal_cdf }
    }

    /// Maps `u ∈ [0, 1)²` to a point of `[0, 1)²` with the table's density, and returns the signed
    /// table value of the cell it lies in. The map is monotone in each coordinate, so stratified or
    /// low-discrepancy `u` stay well distributed.
    fn sample(&self, u: [f64; 2]) -> ([f64; 2], f64) {
        let (y, row) = sample_cdf(&self.marginal_cdf, u[1]);
        let stride = self.nx + 1;
        let cdf = &self.conditional_cdfs[row * stride..(row + 1) * stride];
        let (x, column) = sample_cdf(cdf, u[0]);
        ([x, y], self.values[row * self.nx + column])
    }
}

/// Appends the normalised running sum (a CDF with `n + 1` entries) of `masses` to `out` and returns
/// the total mass. An all-zero row gets a uniform CDF (it is never selected by the marginal, but
/// must stay well formed).
fn append_cdf(out: &mut Vec<f64>, masses: impl ExactSizeIterator<Item = f64>) -> f64 {
    let n = masses.len();
    let start = out.len();
    out.push(0.0);
    let mut total = 0.0;
    for m in masses {
        total += m;
        out.push(total);
    }
    let cdf = &mut out[start..];
    if total > 0.0 {
        cdf.iter_mut().for_each(|c| *c /= total);
    } else {
        cdf.iter_mut().enumerate().for_each(|(i, c)| *c = i as f64 / n as f64);
    }
    // Guard against the running sum's rounding: the last entry is exactly 1.
    cdf[n] = 1.0;
    total
}

/// Inverts a piecewise-constant CDF (`cdf[0] = 0`, `cdf[n] = 1`): returns the continuous position
/// in `[0, 1)` and the cell index. Cells of zero probability are never returned.
fn sample_cdf(cdf: &[f64], u: f64) -> (f64, usize) {
    let n = cdf.len() - 1;
    // NaN maps to 0 rather than poisoning the search.
    let u = if u.is_nan() { 0.0 } else { u.clamp(0.0, ONE_MINUS_EPSILON) };
    // The last index whose CDF value is ≤ u: cdf[i] ≤ u < cdf[i + 1], so the cell has mass.
    let i = (cdf.partition_point(|&c| c <= u) - 1).min(n - 1);
    let width = cdf[i + 1] - cdf[i];
    let du = if width > 0.0 { (u - cdf[i]) / width } else { 0.0 };
    let x = ((i as f64 + du) / n as f64).min(ONE_MINUS_EPSILON);
    (x, i)
}

/// The largest `f64` below 1 (pbrt's `OneMinusEpsilon`).
const ONE_MINUS_EPSILON: f64 = 1.0 - f64::EPSILON / 2.0;

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn cdf_inversion_skips_empty_cells_and_stays_in_range() {
        let mut cdf = Vec::new();
        let total = append_cdf(&mut cdf, [0.0, 1.0, 0.0, 3.0].into_iter());
        assert_eq!(total, 4.0);
        assert_eq!(cdf, vec![0.0, 0.0, 0.25, 0.25, 1.0]);
        for k in 0..=1000 {
            let u = f64::from(k) / 1000.0;
            let (x, i) = sample_cdf(&cdf, u);
            assert!(i == 1 || i == 3, "u = {u} selected empty cell {i}");
            assert!((0.0..1.0).contains(&x));
        }
        // Monotone: larger u never maps to a smaller x.
        let xs: Vec<f64> = (0..=1000).map(|k| sample_cdf(&cdf, f64::from(k) / 1000.0).0).collect();
        assert!(xs.windows(2).all(|w| w[0] <= w[1]));
    }

    #[test]
    fn all_zero_row_gets_a_uniform_cdf() {
        let mut cdf = Vec::new();
        assert_eq!(append_cdf(&mut cdf, [0.0, 0.0].into_iter()), 0.0);
        assert_eq!(cdf, vec![0.0, 0.5, 1.0]);
    }

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

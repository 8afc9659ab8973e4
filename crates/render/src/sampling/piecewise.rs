//! A piecewise-constant 2-D distribution on the unit square (pbrt-v4 §A.5's
//! `PiecewiseConstant2D`): tabulated filters and panorama skies are importance-sampled with it.

/// A piecewise-constant density on `[0, 1)²` proportional to `|values|`, stored row-major
/// (`ny` rows of `nx` cells; row index is `y`). Sampled as the marginal over rows followed by the
/// conditional within the chosen row, each by inverting its CDF (pbrt-v4 §A.5's
/// `PiecewiseConstant2D`, flattened into three vectors).
#[derive(Clone, Debug)]
pub struct PiecewiseConstant2D {
    /// Cells per row, rows.
    nx: usize,
    ny: usize,
    /// The signed tabulated function (its sign becomes the sample weight's sign).
    values: Vec<f64>,
    /// Per row, the `nx + 1` entries of that row's conditional CDF, from 0 to 1.
    conditional_cdfs: Vec<f64>,
    /// The `ny + 1` entries of the marginal CDF over rows, from 0 to 1.
    marginal_cdf: Vec<f64>,
    /// Mean of `|values|`: the density of a cell is its `|value|` over this.
    mean: f64,
}

impl PiecewiseConstant2D {
    /// A table of `nx * ny` finite `values`; with a zero total, [`PiecewiseConstant2D::density`]
    /// is 0 everywhere and samples are uniform.
    pub fn new(values: Vec<f64>, nx: usize, ny: usize) -> Self {
        let mut conditional_cdfs = Vec::with_capacity(ny * (nx + 1));
        let mut row_masses = Vec::with_capacity(ny);
        for row in values.chunks_exact(nx) {
            row_masses.push(append_cdf(&mut conditional_cdfs, row.iter().map(|v| v.abs())));
        }
        let mut marginal_cdf = Vec::with_capacity(ny + 1);
        let total = append_cdf(&mut marginal_cdf, row_masses.into_iter());
        let mean = total / (nx * ny) as f64;
        Self { nx, ny, values, conditional_cdfs, marginal_cdf, mean }
    }

    /// Maps `u ∈ [0, 1)²` to a point of `[0, 1)²` with the table's density, and returns the signed
    /// table value of the cell it lies in. The map is monotone in each coordinate, so stratified or
    /// low-discrepancy `u` stay well distributed.
    pub fn sample(&self, u: [f64; 2]) -> ([f64; 2], f64) {
        let (y, row) = sample_cdf(&self.marginal_cdf, u[1]);
        let stride = self.nx + 1;
        let cdf = &self.conditional_cdfs[row * stride..(row + 1) * stride];
        let (x, column) = sample_cdf(cdf, u[0]);
        ([x, y], self.values[row * self.nx + column])
    }

    /// The density at `p ∈ [0, 1]²` (1 is in the last cell; outside, the nearest cell's).
    pub fn density(&self, p: [f64; 2]) -> f64 {
        if !(self.mean > 0.0) {
            return 0.0;
        }
        // The casts saturate: negative and NaN go to 0.
        let cell = |x: f64, n: usize| ((x * n as f64) as usize).min(n - 1);
        self.values[cell(p[1], self.ny) * self.nx + cell(p[0], self.nx)].abs() / self.mean
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
    fn density_is_the_normalised_table_and_integrates_to_one() {
        let table = PiecewiseConstant2D::new(vec![0.0, 1.0, 2.0, -5.0, 0.0, 4.0], 3, 2);
        // Mean |value| 2: densities 0, ½, 1 / 2½, 0, 2; their mean is 1.
        assert_eq!(table.density([0.5, 0.2]), 0.5);
        assert_eq!(table.density([0.1, 0.9]), 2.5);
        assert_eq!(table.density([1.0, 1.0]), 2.0);
        // Samples fall in cells in proportion to |value|: cell (0, 1) holds 5/12 of them.
        let n = 12_000;
        let hits = (0..n)
            .filter(|&k| {
                let u = [(f64::from(k) + 0.5) / f64::from(n), ((f64::from(k) * 0.618_034) % 1.0)];
                let (p, v) = table.sample(u);
                assert_eq!(v, [0.0, 1.0, 2.0, -5.0, 0.0, 4.0][usize::from(p[1] >= 0.5) * 3 + (p[0] * 3.0) as usize]);
                v == -5.0
            })
            .count();
        assert!((hits as f64 / f64::from(n) - 5.0 / 12.0).abs() < 0.01, "{hits}");
        assert_eq!(PiecewiseConstant2D::new(vec![0.0; 4], 2, 2).density([0.3, 0.3]), 0.0);
    }
}

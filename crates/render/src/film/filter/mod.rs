//! Pixel reconstruction filters, used by *filter importance sampling* (pbrt-v4 §8.8; Ernst et
//! al. 2006, "Filter Importance Sampling", IEEE Symposium on Interactive Ray Tracing).
//!
//! Rather than splatting each sample into every pixel its filter overlaps, the camera draws each
//! sample's film position around the pixel centre from the filter's own distribution; the sample
//! then belongs to that one pixel only, with the weight [`FilterSample::weight`]. Pixels never share
//! samples, which is what makes an image independent of thread count and scheduling.
//!
//! All filters here are products of a 1-D profile along x and one along y (as in pbrt-v4), each
//! supported on `[-radius, radius]`. Offsets are in pixels relative to the pixel centre.
//!
//! * box: `f = 1`; sampled analytically; weight 1.
//! * tent: `f = (rx − abs(x)) (ry − abs(y))`; sampled analytically (pbrt-v4 §A.4.1); weight 1.
//! * Gaussian: `f = (g(x) − g(rx)) (g(y) − g(ry))`; tabulated; weight 1.
//! * Mitchell–Netravali: `f = m(2x/rx) m(2y/ry)`, with negative lobes; tabulated `abs(f)`;
//!   weight `±∫abs(f) / ∫f`.
//! * Blackman–Harris: `f = w(x/rx) w(y/ry)`; tabulated; weight 1.

use std::f64::consts::PI;
use std::fmt;

mod sampler;

use sampler::FilterSampler;

/// The widest filter accepted, in pixels from the centre along either axis. Wider filters would
/// blur beyond any practical use and their tables would grow without bound.
pub const MAX_FILTER_RADIUS: f64 = 16.0;

/// Mitchell and Netravali's recommended parameters, `B = C = 1/3` (1988).
pub const MITCHELL_RECOMMENDED_B_C: f64 = 1.0 / 3.0;

/// One sampled film offset and its estimator weight.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FilterSample {
    /// Offset of the film position from the pixel centre, in pixels (x right, y down).
    pub offset: [f64; 2],
    /// Estimator weight: exactly `1` for filters that are never negative; `±∫|f| / ∫f` (expectation
    /// `1`) for filters with negative lobes. Pass it to `Film::add_sample` unchanged.
    pub weight: f64,
}

/// Why a filter could not be built from the given parameters.
#[derive(Clone, Debug, PartialEq)]
pub enum FilterError {
    /// A radius component is not finite, not positive, or exceeds [`MAX_FILTER_RADIUS`].
    InvalidRadius { radius: [f64; 2] },
    /// A shape parameter (named) is out of its domain.
    InvalidParameter { name: &'static str, value: f64 },
    /// The filter integrates to zero or less, so it cannot be normalised.
    NonPositiveIntegral,
    /// The filter evaluated to NaN or infinity somewhere in its support.
    NonFiniteValue,
}

impl fmt::Display for FilterError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::InvalidRadius { radius } => write!(
                f,
                "filter radius must be finite, positive and at most {MAX_FILTER_RADIUS} pixels \
                 (got [{}, {}])",
                radius[0], radius[1]
            ),
            Self::InvalidParameter { name, value } => {
                write!(f, "filter parameter `{name}` is out of range (got {value})")
            }
            Self::NonPositiveIntegral => {
                write!(f, "filter integrates to zero or less and cannot be normalised")
            }
            Self::NonFiniteValue => write!(f, "filter evaluates to NaN or infinity"),
        }
    }
}

impl std::error::Error for FilterError {}

/// A pixel reconstruction filter. Build one with the validating constructors
/// ([`Filter::box_filter`], [`Filter::tent`], [`Filter::gaussian`], [`Filter::mitchell`],
/// [`Filter::blackman_harris`]); any tables are built there, once.
#[derive(Clone, Debug)]
pub enum Filter {
    /// Constant over the support.
    Box(BoxFilter),
    /// Separable triangle.
    Tent(TentFilter),
    /// Separable truncated Gaussian.
    Gaussian(GaussianFilter),
    /// Separable Mitchell–Netravali cubic (negative lobes).
    Mitchell(MitchellFilter),
    /// Separable four-term Blackman–Harris window.
    BlackmanHarris(BlackmanHarrisFilter),
}

impl Default for Filter {
    /// A box of radius 0.5: each pixel averages radiance over exactly its own square.
    fn default() -> Self {
        Self::Box(BoxFilter { radius: [0.5, 0.5] })
    }
}

impl Filter {
    /// Box filter (`box` is a Rust keyword). Radius 0.5 covers exactly the pixel.
    pub fn box_filter(radius: [f64; 2]) -> Result<Self, FilterError> {
        BoxFilter::new(radius).map(Self::Box)
    }

    /// Tent (triangle) filter; pbrt-v4's default radius is 2.
    pub fn tent(radius: [f64; 2]) -> Result<Self, FilterError> {
        TentFilter::new(radius).map(Self::Tent)
    }

    /// Gaussian with standard deviation `sigma` pixels, shifted down to reach zero at the radius;
    /// pbrt-v4's defaults are radius 1.5, sigma 0.5.
    pub fn gaussian(radius: [f64; 2], sigma: f64) -> Result<Self, FilterError> {
        GaussianFilter::new(radius, sigma).map(Self::Gaussian)
    }

    /// Mitchell–Netravali cubic with parameters `b`, `c` (see [`MITCHELL_RECOMMENDED_B_C`]);
    /// the usual radius is 2.
    pub fn mitchell(radius: [f64; 2], b: f64, c: f64) -> Result<Self, FilterError> {
        MitchellFilter::new(radius, b, c).map(Self::Mitchell)
    }

    /// Four-term Blackman–Harris window (Cycles' default pixel filter, there with radius 0.75).
    pub fn blackman_harris(radius: [f64; 2]) -> Result<Self, FilterError> {
        BlackmanHarrisFilter::new(radius).map(Self::BlackmanHarris)
    }

    /// Its name in scene files, as [`FILTERS`] gives it.
    pub fn name(&self) -> &'static str {
        match self {
            Self::Box(_) => "box",
            Self::Tent(_) => "tent",
            Self::Gaussian(_) => "gaussian",
            Self::Mitchell(_) => "mitchell",
            Self::BlackmanHarris(_) => "blackman-harris",
        }
    }

    /// Half-width of the support along x and y, in pixels.
    pub fn radius(&self) -> [f64; 2] {
        match self {
            Self::Box(f) => f.radius,
            Self::Tent(f) => f.radius,
            Self::Gaussian(f) => f.radius,
            Self::Mitchell(f) => f.radius,
            Self::BlackmanHarris(f) => f.radius,
        }
    }

    /// The (unnormalised) filter value at offset `p` from the pixel centre; zero outside the
    /// support.
    pub fn evaluate(&self, p: [f64; 2]) -> f64 {
        match self {
            Self::Box(f) => f.evaluate(p),
            Self::Tent(f) => f.evaluate(p),
            Self::Gaussian(f) => f.evaluate(p),
            Self::Mitchell(f) => f.evaluate(p),
            Self::BlackmanHarris(f) => f.evaluate(p),
        }
    }

    /// Maps a uniform `u ∈ [0, 1)²` (values outside are clamped) to a film offset distributed as
    /// `|f|` and its weight. Deterministic, allocation-free, and monotone in each component of `u`,
    /// so stratified sample patterns stay stratified.
    pub fn sample(&self, u: [f64; 2]) -> FilterSample {
        match self {
            Self::Box(f) => f.sample(u),
            Self::Tent(f) => f.sample(u),
            Self::Gaussian(f) => f.sampler.sample(u),
            Self::Mitchell(f) => f.sampler.sample(u),
            Self::BlackmanHarris(f) => f.sampler.sample(u),
        }
    }
}

/// One kind of filter as scene files name it: its name, its default radius, its shape parameters
/// with their defaults, and its constructor, side by side so that no name can be listed without
/// the constructor it stands for (nor a radius apart from its filter).
#[derive(Debug)]
pub struct FilterKind {
    /// The name scene files give it (`filter = "mitchell"`).
    pub name: &'static str,
    /// Radius in pixels along both axes when none is given.
    pub default_radius: f64,
    /// The shape parameters besides the radius, each with its default, in the order
    /// [`FilterKind::build`] takes their values.
    pub parameters: &'static [(&'static str, f64)],
    /// The constructor; `values` has one value per entry of `parameters` (checked by `build`).
    constructor: fn(radius: [f64; 2], values: &[f64]) -> Result<Filter, FilterError>,
}

/// Every filter, in the order scene files' messages list them. Default radii are pbrt-v4's
/// (Blackman–Harris, which pbrt-v4 lacks, as its Gaussian).
pub const FILTERS: &[FilterKind] = &[
    FilterKind { name: "box", default_radius: 0.5, parameters: &[], constructor: |r, _| Filter::box_filter(r) },
    FilterKind { name: "tent", default_radius: 2.0, parameters: &[], constructor: |r, _| Filter::tent(r) },
    FilterKind {
        name: "gaussian",
        default_radius: 1.5,
        parameters: &[("sigma", 0.5)],
        constructor: |r, v| Filter::gaussian(r, v[0]),
    },
    FilterKind {
        name: "mitchell",
        default_radius: 2.0,
        parameters: &[("b", MITCHELL_RECOMMENDED_B_C), ("c", MITCHELL_RECOMMENDED_B_C)],
        constructor: |r, v| Filter::mitchell(r, v[0], v[1]),
    },
    FilterKind {
        name: "blackman-harris",
        default_radius: 1.5,
        parameters: &[],
        constructor: |r, _| Filter::blackman_harris(r),
    },
];

impl FilterKind {
    /// This filter with `radius` and `values`, one per entry of [`FilterKind::parameters`] and in
    /// their order.
    ///
    /// # Panics
    /// If `values` does not have one value per parameter: the caller's mistake, not its input's.
    pub fn build(&self, radius: [f64; 2], values: &[f64]) -> Result<Filter, FilterError> {
        assert_eq!(values.len(), self.parameters.len(), "the {} filter takes {:?}", self.name, self.parameters);
        (self.constructor)(radius, values)
    }

    /// This filter with its default radius and parameters.
    pub fn build_default(&self) -> Result<Filter, FilterError> {
        let values: Vec<f64> = self.parameters.iter().map(|p| p.1).collect();
        self.build([self.default_radius; 2], &values)
    }
}

/// Constant over `[-rx, rx] × [-ry, ry]`.
#[derive(Clone, Debug)]
pub struct BoxFilter {
    radius: [f64; 2],
}

impl BoxFilter {
    pub fn new(radius: [f64; 2]) -> Result<Self, FilterError> {
        Ok(Self { radius: validate_radius(radius)? })
    }

    pub fn radius(&self) -> [f64; 2] {
        self.radius
    }

    pub fn evaluate(&self, p: [f64; 2]) -> f64 {
        if p[0].abs() <= self.radius[0] && p[1].abs() <= self.radius[1] {
            1.0
        } else {
            0.0
        }
    }

    fn sample(&self, u: [f64; 2]) -> FilterSample {
        let u = clamp_unit(u);
        FilterSample { offset: [(2.0 * u[0] - 1.0) * self.radius[0], (2.0 * u[1] - 1.0) * self.radius[1]], weight: 1.0 }
    }
}

/// Separable tent: `max(0, rx - |x|) · max(0, ry - |y|)`.
#[derive(Clone, Debug)]
pub struct TentFilter {
    radius: [f64; 2],
}

impl TentFilter {
    pub fn new(radius: [f64; 2]) -> Result<Self, FilterError> {
        Ok(Self { radius: validate_radius(radius)? })
    }

    pub fn radius(&self) -> [f64; 2] {
        self.radius
    }

    pub fn evaluate(&self, p: [f64; 2]) -> f64 {
        (self.radius[0] - p[0].abs()).max(0.0) * (self.radius[1] - p[1].abs()).max(0.0)
    }

    fn sample(&self, u: [f64; 2]) -> FilterSample {
        let u = clamp_unit(u);
        FilterSample { offset: [sample_tent(u[0], self.radius[0]), sample_tent(u[1], self.radius[1])], weight: 1.0 }
    }
}

/// Inverse-CDF sample of the 1-D tent of half-width `r` (pbrt-v4 §A.4.1 `SampleTent`): the lower
/// half of `u` samples the rising edge, the upper half the falling edge, so that `u = 0 → -r`,
/// `u = 1/2 → 0`, `u → 1 → r` monotonically.
fn sample_tent(u: f64, r: f64) -> f64 {
    if u < 0.5 {
        // Density ∝ t on [0, 1]: t = sqrt(u').
        -r + r * (2.0 * u).sqrt()
    } else {
        // Density ∝ 1 - t on [0, 1]: t = 1 - sqrt(1 - u').
        r * (1.0 - (2.0 - 2.0 * u).sqrt())
    }
}

/// Separable Gaussian, shifted so each 1-D factor reaches zero at the radius (pbrt-v4
/// `GaussianFilter`): `max(0, g(x) - g(rx)) · max(0, g(y) - g(ry))`, `g` the normal density with
/// standard deviation `sigma`.
#[derive(Clone, Debug)]
pub struct GaussianFilter {
    radius: [f64; 2],
    sigma: f64,
    sampler: FilterSampler,
}

impl GaussianFilter {
    pub fn new(radius: [f64; 2], sigma: f64) -> Result<Self, FilterError> {
        let radius = validate_radius(radius)?;
        if !(sigma.is_finite() && sigma > 0.0) {
            return Err(FilterError::InvalidParameter { name: "sigma", value: sigma });
        }
        let sampler = FilterSampler::new(radius, |p| gaussian_filter(p, radius, sigma))?;
        Ok(Self { radius, sigma, sampler })
    }

    pub fn radius(&self) -> [f64; 2] {
        self.radius
    }

    pub fn sigma(&self) -> f64 {
        self.sigma
    }

    pub fn evaluate(&self, p: [f64; 2]) -> f64 {
        gaussian_filter(p, self.radius, self.sigma)
    }
}

fn gaussian_filter(p: [f64; 2], radius: [f64; 2], sigma: f64) -> f64 {
    let g = |x: f64| (-x * x / (2.0 * sigma * sigma)).exp() / ((2.0 * PI).sqrt() * sigma);
    let axis = |x: f64, r: f64| {
        if x.abs() <= r {
            (g(x) - g(r)).max(0.0)
        } else {
            0.0
        }
    };
    axis(p[0], radius[0]) * axis(p[1], radius[1])
}

/// Mitchell–Netravali piecewise cubic (Mitchell & Netravali 1988, "Reconstruction Filters in
/// Computer Graphics", SIGGRAPH '88), scaled so its natural support `[-2, 2]` spans the
/// radius: `m(2x/rx) · m(2y/ry)`. It has negative lobes for `1 < |2x/r| < 2` (when `C > 0`),
/// which sharpen the image; the product is negative wherever exactly one factor is.
#[derive(Clone, Debug)]
pub struct MitchellFilter {
    radius: [f64; 2],
    b: f64,
    c: f64,
    sampler: FilterSampler,
}

impl MitchellFilter {
    pub fn new(radius: [f64; 2], b: f64, c: f64) -> Result<Self, FilterError> {
        let radius = validate_radius(radius)?;
        for (name, value) in [("b", b), ("c", c)] {
            if !value.is_finite() {
                return Err(FilterError::InvalidParameter { name, value });
            }
        }
        let sampler = FilterSampler::new(radius, |p| mitchell_filter(p, radius, b, c))?;
        Ok(Self { radius, b, c, sampler })
    }

    pub fn radius(&self) -> [f64; 2] {
        self.radius
    }

    pub fn b(&self) -> f64 {
        self.b
    }

    pub fn c(&self) -> f64 {
        self.c
    }

    pub fn evaluate(&self, p: [f64; 2]) -> f64 {
        mitchell_filter(p, self.radius, self.b, self.c)
    }
}

fn mitchell_filter(p: [f64; 2], radius: [f64; 2], b: f64, c: f64) -> f64 {
    mitchell_1d(2.0 * p[0] / radius[0], b, c) * mitchell_1d(2.0 * p[1] / radius[1], b, c)
}

/// The 1-D Mitchell–Netravali cubic on `[-2, 2]`; it integrates to 1 for every `b`, `c`.
fn mitchell_1d(x: f64, b: f64, c: f64) -> f64 {
    let x = x.abs();
    if x <= 1.0 {
        ((12.0 - 9.0 * b - 6.0 * c) * x * x * x + (-18.0 + 12.0 * b + 6.0 * c) * x * x + (6.0 - 2.0 * b)) / 6.0
    } else if x <= 2.0 {
        ((-b - 6.0 * c) * x * x * x + (6.0 * b + 30.0 * c) * x * x + (-12.0 * b - 48.0 * c) * x + (8.0 * b + 24.0 * c))
            / 6.0
    } else {
        0.0
    }
}

/// Separable four-term Blackman–Harris window (Harris 1978, "On the Use of Windows for Harmonic
/// Analysis with the Discrete Fourier Transform", Proc. IEEE 66(1); the 4-term, −92 dB variant),
/// centred and stretched over `[-r, r]`: `w(t) = a0 + a1 cos(πt) + a2 cos(2πt) + a3 cos(3πt)` with
/// `t = x / r`. Positive everywhere (`w(±1) = 6·10⁻⁵`), `w(0) = 1`.
#[derive(Clone, Debug)]
pub struct BlackmanHarrisFilter {
    radius: [f64; 2],
    sampler: FilterSampler,
}

impl BlackmanHarrisFilter {
    pub fn new(radius: [f64; 2]) -> Result<Self, FilterError> {
        let radius = validate_radius(radius)?;
        let sampler = FilterSampler::new(radius, |p| blackman_harris_filter(p, radius))?;
        Ok(Self { radius, sampler })
    }

    pub fn radius(&self) -> [f64; 2] {
        self.radius
    }

    pub fn evaluate(&self, p: [f64; 2]) -> f64 {
        blackman_harris_filter(p, self.radius)
    }
}

fn blackman_harris_filter(p: [f64; 2], radius: [f64; 2]) -> f64 {
    blackman_harris_1d(p[0] / radius[0]) * blackman_harris_1d(p[1] / radius[1])
}

fn blackman_harris_1d(t: f64) -> f64 {
    const A: [f64; 4] = [0.35875, 0.48829, 0.14128, 0.01168];
    if t.abs() > 1.0 {
        return 0.0;
    }
    A[0] + A[1] * (PI * t).cos() + A[2] * (2.0 * PI * t).cos() + A[3] * (3.0 * PI * t).cos()
}

fn validate_radius(radius: [f64; 2]) -> Result<[f64; 2], FilterError> {
    let ok = |r: f64| r.is_finite() && r > 0.0 && r <= MAX_FILTER_RADIUS;
    if ok(radius[0]) && ok(radius[1]) {
        Ok(radius)
    } else {
        Err(FilterError::InvalidRadius { radius })
    }
}

/// Clamps sample coordinates into `[0, 1)`; NaN becomes 0.
fn clamp_unit(u: [f64; 2]) -> [f64; 2] {
    const ONE_MINUS_EPSILON: f64 = 1.0 - f64::EPSILON / 2.0;
    u.map(|v| if v.is_nan() { 0.0 } else { v.clamp(0.0, ONE_MINUS_EPSILON) })
}

#[cfg(test)]
mod tests;

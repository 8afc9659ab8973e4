//! # Star field (`type = "stars"`)
//!
//! A procedural night sky that stays sharp at any resolution and under any magnification by a lens:
//! every star is a small disc of finite angular radius with constant radiance over it, so a camera
//! resolves it once zoomed in far enough and a gravitational lens stretches it into arcs like any other
//! extended source. A star's radiance times its disc's solid angle is its flux.
//!
//! Stars are scattered uniformly over the sphere (a Poisson process of rate `density` per steradian),
//! deterministically from `seed`:
//! - the sphere is cut into the cells of a cube map (`N × N` per face); a cell holds a Poisson number of
//!   stars with mean `density × (its exact solid angle)`, placed in it uniformly *in solid angle*
//!   (rejection against the cube map's area distortion `(1 + x² + y²)^(−3/2)`), all drawn from a random
//!   stream keyed by the seed and the cell index — so any direction can be looked up on its own, in any
//!   order, from any thread;
//! - a lookup visits the cell the direction falls in and, near a cell border, its neighbours (across cube
//!   faces too), which covers every disc that can reach it because cells are at least 4× wider than the
//!   search margin;
//! - fluxes follow the power law of uniformly distributed sources in Euclidean space,
//!   `N(> F) ∝ F^(−3/2)` (the classic "log N – log S" counts), truncated to a range of 4096 (9 magnitudes)
//!   and scaled so the *mean* flux is `brightness`; the sky's average star radiance is therefore
//!   `density × brightness`;
//! - a star's angular radius grows slowly with its flux, `r = star_radius · (F/F_min)^(1/6)`, from
//!   `star_radius` for the faintest to 4× that for the brightest;
//! - every star is a blackbody: its temperature is drawn from the spectral classes of the naked-eye
//!   sky, roughly in the proportions of the Yale Bright Star Catalogue (stars to magnitude 6.5: a
//!   fifth B and A each, under a third K, a few percent M; see `CLASSES`), log-uniform within
//!   the class, and its radiance is Planck's law at that temperature scaled to the star's
//!   luminance. Seen with a frequency shift `g` (a moving camera, a camera deep in a well) a star
//!   is the blackbody at `gT`: the stars ahead of a fast camera turn blue, in RGB and in spectral
//!   rendering alike.
//!
//! Cost: a lookup generates the stars of about one cell (`≈ 2` on average when `density` allows small
//! enough cells; up to `density · 4π / (6 N²)` when the star size forces big cells).
//!
//! | parameter         | type   | default     | meaning                                                   |
//! |-------------------|--------|-------------|-----------------------------------------------------------|
//! | `density`         | number | 1000        | mean stars per steradian (the naked-eye sky: ≈ 500)        |
//! | `brightness`      | number | 2e-5        | mean flux per star (radiance × sr)                        |
//! | `seed`            | int    | 0           | which sky                                                 |
//! | `star_radius_deg` | number | 0.05        | angular radius of the faintest stars, `(0, 2]`            |
//! | `background`      | colour | `[0, 0, 0]` | faint radiance between the stars                          |
//!
//! ```toml
//! [sky]
//! type = "stars"
//! density = 2000
//! brightness = 2e-5
//! seed = 7
//! star_radius_deg = 0.05
//! background = [0.002, 0.002, 0.004]
//! ```

use crate::geometry::{Frame, Vec3};
use crate::rgb::{Rgb, MAX_RADIANCE};
use crate::sampling::{uniform_cone, Rng};
use crate::spectrum::{BlackbodyColours, Colour};
use std::f64::consts::PI;

/// Slope of the cumulative flux counts, `N(> F) ∝ F^(−γ)`: γ = 3/2 for sources uniform in Euclidean space.
const FLUX_SLOPE: f64 = 1.5;
/// Brightest over faintest flux.
const FLUX_RANGE: f64 = 4096.0;
/// `r ∝ F^RADIUS_EXPONENT`; with [`FLUX_RANGE`] the brightest stars are 4096^(1/6) = 4× the faintest.
const RADIUS_EXPONENT: f64 = 1.0 / 6.0;
const MAX_RADIUS_FACTOR: f64 = 4.0;
/// Mean stars per cell to aim for when choosing the cube map's resolution.
const STARS_PER_CELL: f64 = 2.0;
/// Refuse parameters that would put more stars than this in one cell (slow lookups).
const MAX_STARS_PER_CELL: f64 = 500.0;
/// The spectral classes of naked-eye stars: `(share of the stars, coolest and hottest
/// temperature in kelvin)`, O to M. The shares are roughly those of the Yale Bright Star
/// Catalogue (Hoffleit & Warren 1991, 9 110 stars to V = 6.5), where luminous hot stars and K
/// giants, seen from far, outnumber the red dwarfs that dominate space; the temperature ranges are
/// the classes' usual effective temperatures.
const CLASSES: [(f64, f64, f64); 7] = [
    (0.005, 30_000.0, 45_000.0),
    (0.155, 10_000.0, 30_000.0),
    (0.22, 7_500.0, 10_000.0),
    (0.145, 6_000.0, 7_500.0),
    (0.14, 5_200.0, 6_000.0),
    (0.29, 3_700.0, 5_200.0),
    (0.045, 2_400.0, 3_700.0),
];

/// The temperature of a star drawn with `u ∈ [0, 1)`: a class by its share, then log-uniform
/// within it.
fn temperature(u: f64) -> f64 {
    let mut left = u;
    for (share, coolest, hottest) in CLASSES {
        if left < share {
            return coolest * (hottest / coolest).powf(left / share);
        }
        left -= share;
    }
    // Rounding of the shares' sum: the coolest star.
    CLASSES[CLASSES.len() - 1].1
}

/// The parameters of a star field as a scene gives them.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct StarFieldParams {
    /// Mean number of stars per steradian.
    pub density: f64,
    /// Mean flux of a star (radiance × steradian).
    pub brightness: f64,
    pub seed: u64,
    /// Angular radius of the faintest stars, in degrees.
    pub star_radius_deg: f64,
    /// Radiance between the stars.
    pub background: Rgb,
}

impl Default for StarFieldParams {
    fn default() -> Self {
        Self { density: 1000.0, brightness: 2e-5, seed: 0, star_radius_deg: 0.05, background: Rgb::ZERO }
    }
}

/// One star.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Star {
    /// Unit direction of the disc's centre.
    pub dir: Vec3,
    /// Flux: luminance × solid angle of the disc.
    pub flux: f64,
    /// Angular radius of the disc, radians.
    pub radius: f64,
    /// Colour temperature, kelvin.
    pub temperature: f64,
}

impl Star {
    /// Solid angle of the disc, `2π(1 − cos r) = 4π sin²(r/2)`.
    pub fn solid_angle(&self) -> f64 {
        let s = (0.5 * self.radius).sin();
        4.0 * PI * s * s
    }

    /// The constant radiance over the disc, at rest.
    pub fn radiance(&self) -> Rgb {
        self.seen((1.0, 1.0), &())
    }

    /// The radiance over the disc seen with its colour shifted by one ratio and its brightness
    /// by another (`shown`, [`crate::emission::Shift::shown`]), in the colours `C` at `lambda`.
    pub fn seen<C: Colour>(&self, shown: (f64, f64), lambda: &C::Lambda) -> C {
        let luminance = self.flux / self.solid_angle();
        let scale = luminance / BlackbodyColours::get().luminance(self.temperature);
        C::blackbody(self.temperature, scale, shown, lambda)
    }

    /// True when `dir` lies on the disc.
    pub fn covers(&self, dir: Vec3) -> bool {
        dir.dot(self.dir) >= self.radius.cos()
    }
}

/// Directions drawn on the stars' discs in proportion to the stars' flux, for light that starts at
/// infinity (photons): a cell in proportion to the flux of its stars, then one of its stars likewise
/// (regenerated from the cell's stream), then a direction uniform in solid angle on its disc. A star is
/// thus drawn with probability `F / F_total` and a direction on it with density `F / (F_total Ω)`: its
/// luminance over `F_total`, summed over the discs that cover the direction.
///
/// It carries the field it was built from (whose stars its cells hold), so that it cannot be used
/// with another.
#[derive(Clone, Debug, PartialEq)]
pub struct StarDistribution {
    field: StarField,
    /// The cells that hold stars, and the running sums of their stars' flux.
    cells: Vec<Cell>,
    cdf: Vec<f64>,
}

impl StarDistribution {
    /// The luminous flux of all stars, `F_total`.
    pub fn total_flux(&self) -> f64 {
        self.cdf.last().copied().unwrap_or(0.0)
    }

    /// A direction drawn with `u_star` (which star) and `u` (where on its disc); `None` without stars.
    /// The field it draws from.
    pub fn field(&self) -> &StarField {
        &self.field
    }

    pub fn sample(&self, u_star: f64, u: [f64; 2]) -> Option<Vec3> {
        let target = u_star * self.total_flux();
        let k = self.cdf.partition_point(|&c| c <= target).min(self.cells.len().checked_sub(1)?);
        // What is left of `target` past the cells before this one picks the star within it.
        let mut left = target - if k == 0 { 0.0 } else { self.cdf[k - 1] };
        let mut chosen = None;
        self.field.cell_stars(self.cells[k], |star| {
            if left >= 0.0 {
                chosen = Some(*star);
                left -= star.flux;
            }
        });
        let star = chosen?;
        // 1 − cos r = 2 sin²(r/2) keeps its precision for discs of a few arcseconds.
        let cap = 2.0 * (0.5 * star.radius).sin().powi(2);
        Some(Frame::from_normal(star.dir).to_world(uniform_cone(cap, u)))
    }

    /// Density per steradian of `dir` among the stars: `Σ F / (F_total Ω)` over the discs covering it.
    pub fn pdf(&self, dir: Vec3) -> f64 {
        let total = self.total_flux();
        if !(total > 0.0) {
            return 0.0;
        }
        let mut density = 0.0;
        self.field.covering(dir, |star| density += star.flux / (total * star.solid_angle()));
        density
    }
}

/// A procedural star field; see the module documentation.
#[derive(Clone, Debug, PartialEq)]
pub struct StarField {
    params: StarFieldParams,
    /// Cells per cube-face edge.
    n: u32,
    min_flux: f64,
    min_radius: f64,
    /// How close (in face coordinates) to a cell border a direction must be for the neighbour to matter.
    margin: f64,
}

/// A cube-map cell: face `0..6` (`+x, −x, +y, −y, +z, −z`), column `i`, row `j`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
struct Cell {
    face: u32,
    i: u32,
    j: u32,
}

/// The face a direction falls on and its face coordinates `(x, y) ∈ [−1, 1]²`, where face `f` has major
/// axis `k = f/2` with sign `+` for even `f`, and `x`, `y` are the components along axes `k+1`, `k+2`
/// (cyclically) divided by the major one.
fn project(d: Vec3) -> (u32, f64, f64) {
    let a = d.abs();
    let k = if a.x >= a.y && a.x >= a.z {
        0
    } else if a.y >= a.z {
        1
    } else {
        2
    };
    let major = d[k];
    let face = 2 * k as u32 + u32::from(major < 0.0);
    let m = major.abs();
    (face, d[(k + 1) % 3] / m, d[(k + 2) % 3] / m)
}

/// The (unnormalised) point `(x, y)` of a face's plane, the inverse of [`project`].
fn face_point(face: u32, x: f64, y: f64) -> Vec3 {
    let k = (face / 2) as usize;
    let mut p = Vec3::ZERO;
    p[k] = if face % 2 == 0 { 1.0 } else { -1.0 };
    p[(k + 1) % 3] = x;
    p[(k + 2) % 3] = y;
    p
}

/// Solid angle subtended by the rectangle `[0, x] × [0, y]` of a plane at unit distance.
fn corner_solid_angle(x: f64, y: f64) -> f64 {
    (x * y / (1.0 + x * x + y * y).sqrt()).atan()
}

/// Poisson-distributed count with mean `lambda` (Knuth's multiplication method; `lambda ≤ 700`).
fn poisson(rng: &mut Rng, lambda: f64) -> u32 {
    let limit = (-lambda).exp();
    let mut product = rng.next_f64();
    let mut k = 0;
    while product > limit {
        k += 1;
        product *= rng.next_f64();
    }
    k
}

/// The largest mean flux per star (`brightness`) for stars of angular radius `star_radius_deg`:
/// the brightest stars' radiance, at most the brightest flux (`FLUX_RANGE` times the faintest)
/// over the smallest disc, stays within [`MAX_RADIANCE`].
pub fn max_brightness(star_radius_deg: f64) -> f64 {
    let smallest_disc = PI * star_radius_deg.to_radians().powi(2);
    MAX_RADIANCE * smallest_disc * mean_over_min_flux() / FLUX_RANGE
}

/// The mean of the truncated Pareto law `N(>F) ∝ F^−γ` on `[F_min, R·F_min]` over `F_min`:
/// `γ/(γ−1) · (1 − R^(1−γ)) / (1 − R^(−γ))`.
fn mean_over_min_flux() -> f64 {
    let g = FLUX_SLOPE;
    g / (g - 1.0) * (1.0 - FLUX_RANGE.powf(1.0 - g)) / (1.0 - FLUX_RANGE.powf(-g))
}

impl StarField {
    /// Validates the parameters and picks the cube map's resolution.
    pub fn new(params: StarFieldParams) -> Result<Self, String> {
        let StarFieldParams { density, brightness, star_radius_deg, background, .. } = params;
        if !(density.is_finite() && density >= 0.0) {
            return Err(format!("star density {density} must be a number ≥ 0"));
        }
        if !(brightness.is_finite() && brightness >= 0.0) {
            return Err(format!("star brightness {brightness} must be a number ≥ 0"));
        }
        if brightness > max_brightness(star_radius_deg) {
            return Err(format!(
                "star brightness {brightness} is too large for star_radius_deg {star_radius_deg}: at most {:.3e}",
                max_brightness(star_radius_deg)
            ));
        }
        if !(star_radius_deg > 0.0 && star_radius_deg <= 2.0) {
            return Err(format!("star_radius_deg {star_radius_deg} must lie in (0, 2]"));
        }
        if !(background.is_finite() && background.min_element() >= 0.0) {
            return Err(format!("star field background {background} must be finite and ≥ 0"));
        }
        let min_radius = star_radius_deg.to_radians();
        let max_radius = MAX_RADIUS_FACTOR * min_radius;
        // Gnomonic projection maps great circles to straight lines and shrinks angles by at most
        // 1/(1 + x² + y²) ≥ 1/3, so a disc of angular radius r lies within 3r (face units) of its centre.
        let margin = 3.0 * max_radius * (1.0 + 1e-6);
        // Cells at least 4 margins wide (2/N ≥ 4·margin), and about STARS_PER_CELL stars each.
        let n_max = (0.5 / margin).floor().max(1.0);
        let n_wanted = (4.0 * PI * density / (6.0 * STARS_PER_CELL)).sqrt().ceil().max(1.0);
        let n = n_wanted.min(n_max);
        let per_cell = 4.0 * PI * density / (6.0 * n * n);
        if per_cell > MAX_STARS_PER_CELL {
            return Err(format!(
                "star density {density}/sr is too high for star_radius_deg {star_radius_deg}: \
                 {per_cell:.0} stars per lookup cell (at most {MAX_STARS_PER_CELL}); use smaller stars"
            ));
        }
        Ok(Self { params, n: n as u32, min_flux: brightness / mean_over_min_flux(), min_radius, margin })
    }

    pub fn params(&self) -> &StarFieldParams {
        &self.params
    }

    /// Radiance from `dir` at rest: the background plus every star whose disc contains `dir`.
    pub fn radiance(&self, dir: Vec3) -> Rgb {
        self.seen(dir, (1.0, 1.0), &())
    }

    /// [`StarField::radiance`] seen with its colour shifted by one ratio and its brightness by
    /// another (`shown`), in the colours `C` at `lambda`: the stars as blackbodies, the
    /// background as its RGB colour.
    pub fn seen<C: Colour>(&self, dir: Vec3, shown: (f64, f64), lambda: &C::Lambda) -> C {
        let mut sum = C::illuminant(self.params.background, shown, lambda);
        self.covering(dir, |star| sum += star.seen(shown, lambda));
        sum
    }

    /// Calls `visit` for every star whose disc contains `dir`.
    fn covering(&self, dir: Vec3, mut visit: impl FnMut(&Star)) {
        let (cells, count) = self.candidate_cells(dir);
        for &c in &cells[..count] {
            self.cell_stars(c, |star| {
                if star.covers(dir) {
                    visit(star);
                }
            });
        }
    }

    /// The distribution of directions on the stars' discs in proportion to their flux, which
    /// carries a copy of the field (a few numbers: the stars are regenerated from them).
    pub fn distribution(&self) -> StarDistribution {
        let (mut cells, mut cdf, mut total) = (Vec::new(), Vec::new(), 0.0);
        for cell in self.cells() {
            let mut flux = 0.0;
            self.cell_stars(cell, |star| flux += star.flux);
            if flux > 0.0 {
                total += flux;
                cells.push(cell);
                cdf.push(total);
            }
        }
        StarDistribution { field: self.clone(), cells, cdf }
    }

    /// The cells that can hold a star whose disc reaches `dir`: its own cell and, when `dir` is within the
    /// search margin of a border, the neighbours across it (deduplicated; near a cube corner several
    /// offsets land in the same cell). Returns the cells and how many of them are valid.
    fn candidate_cells(&self, dir: Vec3) -> ([Cell; 9], usize) {
        let (face, x, y) = project(dir);
        let cell = self.cell_at(face, x, y);
        let h = 2.0 / f64::from(self.n);
        let x0 = -1.0 + f64::from(cell.i) * h;
        let y0 = -1.0 + f64::from(cell.j) * h;
        // Whether the neighbour at offset −1, 0, +1 along each axis can matter.
        let near = |lo: f64, v: f64| [v - lo < self.margin, true, lo + h - v < self.margin];
        let (near_i, near_j) = (near(x0, x), near(y0, y));
        let last = self.n - 1;
        let off_face = (near_i[0] && cell.i == 0)
            || (near_i[2] && cell.i == last)
            || (near_j[0] && cell.j == 0)
            || (near_j[2] && cell.j == last);
        let mut cells = [cell; 9];
        let mut count = 1;
        for (a, di) in [-1i64, 0, 1].into_iter().enumerate() {
            for (b, dj) in [-1i64, 0, 1].into_iter().enumerate() {
                // Across a face edge the cells of the two faces do not line up exactly (each face's
                // coordinates stretch differently away from the edge): then take the whole ring.
                if (di, dj) == (0, 0) || !(off_face || (near_i[a] && near_j[b])) {
                    continue;
                }
                let neighbour = self.neighbour(cell, di, dj);
                if !cells[..count].contains(&neighbour) {
                    cells[count] = neighbour;
                    count += 1;
                }
            }
        }
        (cells, count)
    }

    /// Calls `visit` for every star of the sky (for tests, statistics, or a renderer that wants to treat
    /// stars as lights). Allocation-free.
    pub fn for_each_star(&self, mut visit: impl FnMut(&Star)) {
        for cell in self.cells() {
            self.cell_stars(cell, &mut visit);
        }
    }

    /// Every cell of the cube map, face by face, row by row.
    fn cells(&self) -> impl Iterator<Item = Cell> + '_ {
        (0..6).flat_map(move |face| (0..self.n).flat_map(move |j| (0..self.n).map(move |i| Cell { face, i, j })))
    }

    fn cell_at(&self, face: u32, x: f64, y: f64) -> Cell {
        let n = f64::from(self.n);
        let index = |v: f64| (((v + 1.0) * 0.5 * n).floor().max(0.0) as u32).min(self.n - 1);
        Cell { face, i: index(x), j: index(y) }
    }

    /// The cell `(i + di, j + dj)`, continued onto the neighbouring face when it falls off this one: a
    /// point just beyond the edge, on this face's extended plane, projects into the adjacent face's cell
    /// that shares the edge (face coordinates along a shared edge agree).
    fn neighbour(&self, c: Cell, di: i64, dj: i64) -> Cell {
        let (i, j) = (i64::from(c.i) + di, i64::from(c.j) + dj);
        let n = i64::from(self.n);
        if (0..n).contains(&i) && (0..n).contains(&j) {
            return Cell { face: c.face, i: i as u32, j: j as u32 };
        }
        let h = 2.0 / f64::from(self.n);
        let coordinate = |k: i64| {
            if k < 0 {
                -1.0 - 1e-9
            } else if k >= n {
                1.0 + 1e-9
            } else {
                -1.0 + (k as f64 + 0.5) * h
            }
        };
        let (face, x, y) = project(face_point(c.face, coordinate(i), coordinate(j)));
        self.cell_at(face, x, y)
    }

    /// Generates the stars of one cell from its own random stream.
    fn cell_stars(&self, c: Cell, mut visit: impl FnMut(&Star)) {
        let n = f64::from(self.n);
        let h = 2.0 / n;
        let (x0, y0) = (-1.0 + f64::from(c.i) * h, -1.0 + f64::from(c.j) * h);
        let (x1, y1) = (x0 + h, y0 + h);
        let solid_angle = corner_solid_angle(x1, y1) - corner_solid_angle(x0, y1) - corner_solid_angle(x1, y0)
            + corner_solid_angle(x0, y0);
        let cell_index = (u64::from(c.face) * u64::from(self.n) + u64::from(c.j)) * u64::from(self.n) + u64::from(c.i);
        let mut rng = Rng::for_sample(self.params.seed, cell_index, 0);
        let count = poisson(&mut rng, (self.params.density * solid_angle).min(700.0));
        // Largest area density over the cell, at its point nearest the face centre.
        let nearest_to_zero = |a: f64, b: f64| if a <= 0.0 && b >= 0.0 { 0.0 } else { a.abs().min(b.abs()) };
        let (xm, ym) = (nearest_to_zero(x0, x1), nearest_to_zero(y0, y1));
        let density_max = (1.0 + xm * xm + ym * ym).powf(-1.5);
        for _ in 0..count {
            // Uniform in solid angle: rejection against dΩ/dA = (1 + x² + y²)^(−3/2). The acceptance rate
            // is above 0.19 even for a whole face; 64 tries fail with probability < 1e-5.
            let (mut x, mut y) = (x0, y0);
            for _ in 0..64 {
                x = x0 + h * rng.next_f64();
                y = y0 + h * rng.next_f64();
                if rng.next_f64() * density_max <= (1.0 + x * x + y * y).powf(-1.5) {
                    break;
                }
            }
            // Inverse CDF of the truncated Pareto law.
            let u = rng.next_f64();
            let flux_ratio = (1.0 - u * (1.0 - FLUX_RANGE.powf(-FLUX_SLOPE))).powf(-1.0 / FLUX_SLOPE);
            let temperature = temperature(rng.next_f64());
            visit(&Star {
                dir: face_point(c.face, x, y).normalize(),
                flux: self.min_flux * flux_ratio,
                radius: self.min_radius * flux_ratio.powf(RADIUS_EXPONENT).min(MAX_RADIUS_FACTOR),
                temperature,
            });
        }
    }
}

#[cfg(test)]
mod tests;

//! # Equirectangular environment map (`type = "equirect"`)
//!
//! A latitude–longitude panorama (PNG, OpenEXR or Radiance HDR): the image's columns are longitude and
//! its rows latitude, both linear in angle. Seen from inside the sphere the image is upright and not
//! mirrored:
//!
//! - the image centre `(s, t) = (½, ½)` is *forward* (`−z` by default) on the horizon;
//! - `s` increases with longitude, toward the right (east, `+x`): `s = ½ + lon/2π`, so `s = ¾` is `+x`
//!   and the left/right edges (`s = 0, 1`) are behind (`+z`);
//! - the top row is straight up (`+y`), the bottom row straight down: `t = ½ − lat/π`.
//!
//! Lookups are bilinear, repeating in longitude and clamped in latitude. HDR/EXR values are taken as
//! linear radiance; 8-bit images as sRGB, decoded to linear.
//!
//! Light paths that start at infinity (SPPM's photons) draw their directions from
//! [`Equirect::distribution`], in proportion to a bound of the luminance.
//!
//! | parameter      | type   | default     | meaning                                                 |
//! |----------------|--------|-------------|---------------------------------------------------------|
//! | `file`         | path   | —           | relative to the scene file                              |
//! | `intensity`    | number | 1           | radiance scale                                          |
//! | `up`           | vector | `[0, 1, 0]` | the panorama's up                                       |
//! | `rotation_deg` | number | 0           | turns the panorama about `up`, counter-clockwise from above |
//!
//! ```toml
//! [sky]
//! type = "equirect"
//! file = "skies/milky_way.exr"
//! intensity = 1.0
//! rotation_deg = 90
//! ```

use super::SkyFrame;
use crate::geometry::Vec3;
use crate::rgb::{luminance, Rgb};
use crate::sampling::PiecewiseConstant2D;
use crate::texture::image_data::{ImageData, WrapMode};
use std::f64::consts::{FRAC_1_PI, PI};
use std::sync::Arc;

#[derive(Clone, Debug)]
pub struct Equirect {
    pub image: Arc<ImageData>,
    pub frame: SkyFrame,
    pub intensity: f32,
}

impl Equirect {
    /// Image coordinates `(s, t)` (`t` down) of a unit direction.
    pub fn image_coordinates(&self, dir: Vec3) -> (f64, f64) {
        let (lat, lon) = self.frame.lat_long(dir);
        (0.5 + lon * (0.5 * FRAC_1_PI), 0.5 - lat * FRAC_1_PI)
    }

    /// The unit direction that maps to image coordinates `(s, t)`; inverse of
    /// [`Equirect::image_coordinates`].
    pub fn direction(&self, s: f64, t: f64) -> Vec3 {
        self.frame.direction((0.5 - t) * PI, (s - 0.5) * 2.0 * PI)
    }

    pub fn radiance(&self, dir: Vec3) -> Rgb {
        let (s, t) = self.image_coordinates(dir);
        self.image.sample(s, t, WRAP) * self.intensity
    }

    /// The distribution for sampling this sky, which it carries (a copy, sharing the image);
    /// built once (O(pixels)).
    pub fn distribution(&self) -> EquirectDistribution {
        EquirectDistribution::new(self.clone())
    }
}

/// Longitude repeats, latitude clamps: the wrap of every lookup, and of the neighbourhoods below.
const WRAP: [WrapMode; 2] = [WrapMode::Repeat, WrapMode::Clamp];

/// Directions drawn from an equirect sky in proportion to (a bound of) its luminance.
///
/// As pbrt-v3's `InfiniteAreaLight` does (§13.6.7 for the piecewise-constant 2-D distribution, §14.2.4 for
/// sampling the light and its pdf): a distribution over the image's pixels in `(s, t)`, mapped to the sphere with
/// `θ = π t`, `φ = 2π s`, whose Jacobian turns the density `p(s, t)` into `p(s, t) / (2π² sin θ)` per
/// steradian.
///
/// Unlike pbrt-v3, a pixel's weight is not its own value: [`Equirect::radiance`] is bilinear, so a black
/// pixel next to a bright one still has radiance over part of its area, and a distribution that gave it no
/// weight would never emit there — a biased estimator. The weight is therefore a bound over the pixel's
/// area: the largest |luminance| of the pixel and its 8 neighbours (the four pixel centres any point of the
/// pixel interpolates between lie among them), times the largest `sin θ` over the pixel's row. Any point
/// with nonzero radiance thus has nonzero density, except at the poles (`sin θ = 0`), a set of measure zero.
/// The sky's `intensity` scales every weight alike, so only [`EquirectDistribution::power`] uses it.
///
/// It carries the sky it was built from (whose image its weights are, and whose frame turns its
/// `(s, t)` into directions), so that it cannot be used with another.
#[derive(Clone, Debug)]
pub struct EquirectDistribution {
    sky: Equirect,
    /// Over the image's pixels in `(s, t) ∈ [0, 1]²`.
    pixels: PiecewiseConstant2D,
    power: f64,
}

impl EquirectDistribution {
    fn new(sky: Equirect) -> Self {
        let (image, intensity) = (&*sky.image, f64::from(sky.intensity));
        let (width, height) = (image.width(), image.height());
        let weights: Vec<f64> = (0..height)
            .flat_map(|y| (0..width).map(move |x| (x, y)))
            .map(|(x, y)| neighbourhood_luminance(image, x, y) * row_max_sin_theta(y, height))
            .collect();
        let power = bilinear_luminance_integral(image) * intensity;
        Self { pixels: PiecewiseConstant2D::new(weights, width, height), power, sky }
    }

    /// The sky it draws from.
    pub fn sky(&self) -> &Equirect {
        &self.sky
    }

    /// A unit direction (the direction the sky is *seen* in, as [`Equirect::radiance`] takes it) drawn from
    /// the distribution using `u`, with its density per steradian; None where the density is 0 (an
    /// all-black image, or the `sin θ = 0` poles).
    ///
    /// Light from the sky seen in `dir` travels along `−dir`. The density is [`EquirectDistribution::pdf`]
    /// of the returned direction, so the two agree exactly.
    pub fn sample(&self, u: [f64; 2]) -> Option<(Vec3, f64)> {
        let ([s, t], _) = self.pixels.sample(u);
        let dir = self.sky.direction(s, t);
        let pdf = self.pdf(dir);
        (pdf > 0.0).then_some((dir, pdf))
    }

    /// Density per steradian of `dir`.
    pub fn pdf(&self, dir: Vec3) -> f64 {
        let (s, t) = self.sky.image_coordinates(dir);
        // sin θ from whichever pole is nearer, so that it is exactly 0 at both (`sin π` is not).
        let sin_theta = (PI * t.min(1.0 - t)).sin();
        if sin_theta > 0.0 {
            self.pixels.density([s, t]) / (2.0 * PI * PI * sin_theta)
        } else {
            0.0
        }
    }

    /// ∫ luminance(radiance(ω)) dω over the sphere, the sky's total (luminance) power per unit area.
    ///
    /// Computed when the distribution is built, exactly (to rounding) for the bilinear reconstruction that
    /// [`Equirect::radiance`] looks up (integrated in closed form, row by row), not from the weights,
    /// which are only a bound.
    pub fn power(&self) -> f64 {
        self.power
    }
}

/// The largest |luminance| of pixel `(x, y)` and its 8 neighbours: a bound on the bilinear lookup anywhere
/// in the pixel, since luminance is linear in the colour and every point interpolates between four of these.
fn neighbourhood_luminance(image: &ImageData, x: usize, y: usize) -> f64 {
    let (x, y) = (x as i64, y as i64);
    (-1..=1)
        .flat_map(|dy| (-1..=1).map(move |dx| (x + dx, y + dy)))
        .map(|(xi, yi)| f64::from(luminance(image.texel(xi, yi, WRAP))).abs())
        .fold(0.0, f64::max)
}

/// The largest `sin θ` over row `y` of `height`: at the row's point nearest the horizon `t = ½`.
fn row_max_sin_theta(y: usize, height: usize) -> f64 {
    let h = height as f64;
    (PI * 0.5f64.clamp(y as f64 / h, (y + 1) as f64 / h)).sin()
}

/// `∫ luminance dω` of the image's bilinear reconstruction at intensity 1, in closed form.
///
/// With `dω = 2π² sin(π t) ds dt`: in `s` the reconstruction is periodic and piecewise linear between
/// pixel centres, so its integral over a row of `s` is the mean of the nodes — at every `t`, the linear
/// interpolation (clamped past the first and last row centres) of the rows' mean luminances. What is left
/// is `∫ (piecewise linear) · sin(π t) dt`, exact per piece.
fn bilinear_luminance_integral(image: &ImageData) -> f64 {
    let (width, height) = (image.width(), image.height());
    let means: Vec<f64> = image
        .pixels()
        .chunks(width)
        .map(|row| row.iter().map(|&c| f64::from(luminance(c))).sum::<f64>() / width as f64)
        .collect();
    let centre = |y: usize| (y as f64 + 0.5) / height as f64;
    let last = height - 1;
    let caps = means[0] * linear_sin_integral(0.0, centre(0), 1.0, 1.0)
        + means[last] * linear_sin_integral(centre(last), 1.0, 1.0, 1.0);
    let spans: f64 =
        means.windows(2).enumerate().map(|(y, m)| linear_sin_integral(centre(y), centre(y + 1), m[0], m[1])).sum();
    2.0 * PI * PI * (caps + spans)
}

/// `∫ₐᵇ f(t) sin(π t) dt` for `f` linear from `fa` at `a` to `fb` at `b` (`a < b`). By parts,
/// `[−f cos(πt)/π]ₐᵇ + f′ [sin(πt)]ₐᵇ / π²`, with the differences of cosines and sines written as products
/// so that narrow pieces (many rows) do not cancel.
fn linear_sin_integral(a: f64, b: f64, fa: f64, fb: f64) -> f64 {
    let (mid, half) = (0.5 * PI * (a + b), 0.5 * PI * (b - a));
    let cos_a_minus_cos_b = 2.0 * mid.sin() * half.sin();
    let sin_b_minus_sin_a = 2.0 * mid.cos() * half.sin();
    (fa * cos_a_minus_cos_b + (fa - fb) * (PI * b).cos()) * FRAC_1_PI
        + (fb - fa) / (b - a) * sin_b_minus_sin_a * (FRAC_1_PI * FRAC_1_PI)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::sampling::Rng;

    /// A 16×8 black panorama with one red marker pixel.
    fn marked(x: usize, y: usize) -> ImageData {
        let mut pixels = vec![Rgb::ZERO; 16 * 8];
        pixels[y * 16 + x] = Rgb::new(1.0, 0.0, 0.0);
        ImageData::new(16, 8, pixels).unwrap()
    }

    fn pixel_centre_dir(sky: &Equirect, x: usize, y: usize) -> Vec3 {
        sky.direction((x as f64 + 0.5) / 16.0, (y as f64 + 0.5) / 8.0)
    }

    /// A `w`×`h` grey panorama with luminance `f(x, y)`.
    fn grey(w: usize, h: usize, f: impl Fn(usize, usize) -> f32) -> ImageData {
        let pixels = (0..h).flat_map(|y| (0..w).map(move |x| (x, y))).map(|(x, y)| Rgb::splat(f(x, y))).collect();
        ImageData::new(w, h, pixels).unwrap()
    }

    fn sky_of(image: ImageData, frame: SkyFrame, intensity: f32) -> Equirect {
        Equirect { image: Arc::new(image), frame, intensity }
    }

    /// A frame whose up is tilted away from every axis, turned as well.
    fn tilted() -> SkyFrame {
        SkyFrame::new(Vec3::new(0.3, 1.0, -0.5), 37.0).unwrap()
    }

    /// `∫ luminance(radiance(ω)) dω` by a 1000 × 2000 midpoint rule in `(t, s)`, independent of the
    /// distribution (the integrand is continuous, so this is accurate to well under 0.1 %).
    fn quadrature(sky: &Equirect) -> f64 {
        let (rows, cols) = (1000, 2000);
        let mut sum = 0.0;
        for i in 0..rows {
            let t = (i as f64 + 0.5) / rows as f64;
            let row: f64 = (0..cols)
                .map(|j| f64::from(luminance(sky.radiance(sky.direction((j as f64 + 0.5) / cols as f64, t)))))
                .sum();
            sum += row * (PI * t).sin();
        }
        sum * 2.0 * PI * PI / (rows * cols) as f64
    }

    /// The mean of `f(direction, pdf)` over `n` samples (a sample with no direction counts as 0).
    fn sample_mean(sky: &Equirect, n: usize, f: impl Fn(Vec3, f64) -> f64) -> f64 {
        let dist = sky.distribution();
        let mut rng = Rng::new(7);
        let sum: f64 = (0..n).filter_map(|_| dist.sample(rng.next_2d())).map(|(d, pdf)| f(d, pdf)).sum();
        sum / n as f64
    }

    fn assert_close(got: f64, want: f64, rel: f64, what: &str) {
        assert!((got - want).abs() <= rel * want.abs(), "{what}: got {got}, want {want} (± {rel} relative)");
    }

    /// One pixel of luminance `bright` on a `background`.
    fn spot(w: usize, h: usize, at: (usize, usize), bright: f32, background: f32) -> ImageData {
        grey(w, h, |x, y| if (x, y) == at { bright } else { background })
    }

    #[test]
    fn sampled_pdf_matches_pdf_and_integrates_to_the_sphere() {
        for (seed, frame) in [(3, SkyFrame::Y_UP), (4, tilted())] {
            let sky = sky_of(spot(16, 8, (5, 2), 20.0, 1.0), frame, 1.5);
            let dist = sky.distribution();
            let mut rng = Rng::new(seed);
            let n = 1_000_000;
            let mut solid_angle = 0.0;
            for _ in 0..n {
                let (dir, pdf) = dist.sample(rng.next_2d()).expect("the density is positive almost everywhere");
                assert!((dir.length() - 1.0).abs() < 1e-12);
                let again = dist.pdf(dir);
                assert!((pdf - again).abs() <= 1e-9 * pdf, "sample says {pdf}, pdf says {again}");
                solid_angle += 1.0 / pdf;
            }
            assert_close(solid_angle / n as f64, 4.0 * PI, 0.01, "E[1/pdf] = ∫ dω");
        }
    }

    #[test]
    fn luminance_over_pdf_is_unbiased() {
        let skies = [
            // A bright pixel on a dim background, turned.
            sky_of(spot(16, 8, (5, 2), 20.0, 1.0), tilted(), 1.0),
            // A bright pixel among black ones: the bilinear lookup spills its light into its neighbours,
            // which only the neighbourhood bound gives any density (its own cell holds (¾)² of it).
            sky_of(spot(16, 8, (11, 5), 1.0, 0.0), SkyFrame::Y_UP, 3.0),
            // The same at the top row, where latitude clamps, and at the longitude seam.
            sky_of(spot(16, 8, (0, 0), 1.0, 0.0), tilted(), 1.0),
            // Something smooth with colour.
            sky_of(
                ImageData::new(
                    24,
                    12,
                    (0..24 * 12)
                        .map(|i| Rgb::new(1.0 + (i % 7) as f32, 0.5 * (i % 5) as f32, (i % 3) as f32))
                        .collect(),
                )
                .unwrap(),
                tilted(),
                0.7,
            ),
        ];
        for (k, sky) in skies.iter().enumerate() {
            let want = quadrature(sky);
            let got = sample_mean(sky, 1_000_000, |d, pdf| f64::from(luminance(sky.radiance(d))) / pdf);
            assert_close(got, want, 0.01, &format!("sky {k}: E[L/pdf] = ∫ L dω"));
        }
    }

    #[test]
    fn power_is_the_luminance_integral() {
        let skies = [
            sky_of(spot(16, 8, (5, 2), 20.0, 1.0), tilted(), 1.0),
            sky_of(spot(16, 8, (0, 7), 1.0, 0.0), SkyFrame::Y_UP, 2.0),
            sky_of(grey(5, 3, |x, y| (x + 2 * y) as f32), SkyFrame::Y_UP, 1.0),
        ];
        for (k, sky) in skies.iter().enumerate() {
            // The closed form is exact; the tolerance covers the midpoint rule's error (≤ 5e-6 here), while
            // integrating the pixels as constant boxes instead is off by percents.
            assert_close(sky.distribution().power(), quadrature(sky), 2e-5, &format!("sky {k}: power"));
        }
        // A uniform sky of luminance L has power 4π L.
        let uniform = sky_of(grey(7, 4, |_, _| 0.5), tilted(), 2.0);
        assert_close(uniform.distribution().power(), 4.0 * PI, 1e-12, "uniform");
    }

    #[test]
    fn a_bright_pixel_draws_most_samples() {
        let (at_x, at_y) = (9, 3);
        let sky = sky_of(spot(16, 8, (at_x, at_y), 1000.0, 1.0), tilted(), 1.0);
        let near = sample_mean(&sky, 20_000, |d, _| {
            let (s, t) = sky.image_coordinates(d);
            let (x, y) = ((s * 16.0) as i64, (t * 8.0) as i64);
            f64::from(u8::from(x.abs_diff(at_x as i64) <= 1 && y.abs_diff(at_y as i64) <= 1))
        });
        // Its 3×3 neighbourhood holds 9 × 1000 of the ≈ 9000 + 119 weight (times sin θ): ≈ 98 %.
        assert!(near > 0.9, "only {near} of the samples near the bright pixel");
    }

    #[test]
    fn black_skies_and_the_poles_have_no_density() {
        let black = sky_of(grey(8, 4, |_, _| 0.0), SkyFrame::Y_UP, 1.0);
        let dist = black.distribution();
        assert_eq!(dist.sample([0.3, 0.6]), None);
        assert_eq!(dist.pdf(Vec3::X), 0.0);
        assert_eq!(dist.power(), 0.0);
        // Upright, so that the poles are exactly `±y` (a tilted up vector only reaches sin θ ≈ 1e-8).
        let lit = sky_of(grey(8, 4, |_, _| 1.0), SkyFrame::Y_UP, 1.0);
        let dist = lit.distribution();
        assert_eq!(dist.pdf(Vec3::Y), 0.0);
        assert_eq!(dist.pdf(Vec3::NEG_Y), 0.0);
        assert!(dist.pdf(lit.direction(0.5, 0.5)) > 0.0);
    }

    #[test]
    fn marker_appears_in_the_predicted_direction() {
        // Column 12 is s = 12.5/16 ≈ 0.78: just right of +x (s = 0.75); row 2 is t = 2.5/8: 33.75° up.
        let sky = Equirect { image: Arc::new(marked(12, 2)), frame: SkyFrame::Y_UP, intensity: 2.0 };
        let lon = (12.5 / 16.0 - 0.5) * 2.0 * PI;
        let lat = (0.5 - 2.5 / 8.0) * PI;
        let expected = Vec3::new(lat.cos() * lon.sin(), lat.sin(), -lat.cos() * lon.cos());
        assert!((pixel_centre_dir(&sky, 12, 2) - expected).length() < 1e-12);
        assert!(expected.x > 0.0 && expected.y > 0.0, "east and up");
        assert_eq!(sky.radiance(expected), Rgb::new(2.0, 0.0, 0.0), "marker × intensity");
        // Everywhere else (at the other pixel centres) it is black.
        for y in 0..8 {
            for x in 0..16 {
                if (x, y) != (12, 2) {
                    assert_eq!(sky.radiance(pixel_centre_dir(&sky, x, y)), Rgb::ZERO, "pixel ({x}, {y})");
                }
            }
        }
    }

    #[test]
    fn cardinal_directions() {
        let sky = Equirect { image: Arc::new(marked(0, 0)), frame: SkyFrame::Y_UP, intensity: 1.0 };
        let st = |d| sky.image_coordinates(d);
        assert_eq!(st(Vec3::NEG_Z), (0.5, 0.5), "forward is the centre");
        assert_eq!(st(Vec3::X), (0.75, 0.5), "east is right of centre");
        assert_eq!(st(Vec3::NEG_X), (0.25, 0.5));
        assert_eq!(st(Vec3::Y).1, 0.0, "up is the top row");
        assert_eq!(st(Vec3::NEG_Y).1, 1.0);
    }

    #[test]
    fn rotation_moves_the_marker_left() {
        // Marker at the image centre (columns 7/8 straddle s = ½: use column 8, row 4 → just right, just below).
        let image = Arc::new(marked(8, 4));
        let plain = Equirect { image: image.clone(), frame: SkyFrame::Y_UP, intensity: 1.0 };
        let turned = Equirect { image, frame: SkyFrame::new(Vec3::Y, 90.0).unwrap(), intensity: 1.0 };
        let d = pixel_centre_dir(&plain, 8, 4);
        // Rotating the sky 90° counter-clockwise about +y moves the marker from near −z to near −x.
        let rotated = Vec3::new(d.z, d.y, -d.x);
        assert_eq!(turned.radiance(rotated), Rgb::new(1.0, 0.0, 0.0));
        assert_eq!(turned.radiance(d), Rgb::ZERO);
    }
}

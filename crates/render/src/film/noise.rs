//! How noisy a film still is, estimated from the film alone, and measured against a reference.
//!
//! Every pixel's samples split by index parity into two halves, each an independent estimate of
//! the pixel (see `pixel`): their luminances `A` and `B`. For halves of `n/2` samples each,
//! `E[(A − B)²] = Var A + Var B = 4 Var I`, so `((A − B)/2)²` estimates the variance of the
//! pixel's estimate `I` (as in Rousselle et al. 2012 and Blender Cycles' adaptive sampling). With
//! stratified samples the halves are each less well stratified than the whole, so the estimate
//! errs on the high side.
//!
//! Errors are relative, as the eye sees noise: a pixel's relative variance is
//! `((A − B)/2)² / (I² + ε²)` with `I` its luminance and [`BRIGHTNESS_FLOOR`] `ε`, below which
//! errors count as absolute (so black pixels need not be perfect). The image's relative error is
//! the root of the mean of its pixels' relative variances, the largest [`TRIMMED`] of them left
//! out so that a few fireflies do not hold a whole image back. Against a reference `R` the same
//! measure is the *relative RMSE* `√(mean (I − R)² / (R² + ε²))` (the relMSE of the denoising
//! literature, Rousselle et al. 2011, with its usual ε).

use super::Film;
use crate::rgb::luminance_f64;

/// Linear radiance below which a pixel's error counts as absolute: 1 % of display white.
pub const BRIGHTNESS_FLOOR: f64 = 0.01;

/// Fraction of the pixels, the noisiest, left out of the image's estimated error.
pub const TRIMMED: f64 = 1e-3;

/// The estimated relative variance of pixel `(x, y)`'s estimate; `None` before both halves of
/// its samples have positive weight.
pub fn pixel_relative_variance(film: &Film, x: u32, y: u32) -> Option<f64> {
    let (even, odd) = film.half_luminances(x, y)?;
    let value = luminance_f64(film.pixel_f64(x, y));
    let half_difference = (even - odd) / 2.0;
    Some(half_difference * half_difference / (value * value + BRIGHTNESS_FLOOR * BRIGHTNESS_FLOOR))
}

/// The estimated relative error of the film over `pixels` (see the module docs); `None` while
/// some pixel has no estimate or there are no pixels.
pub fn estimated_relative_error(film: &Film, pixels: impl Iterator<Item = (u32, u32)>) -> Option<f64> {
    let variances: Option<Vec<f64>> = pixels.map(|(x, y)| pixel_relative_variance(film, x, y)).collect();
    trimmed_root_mean(variances?)
}

/// `√(mean)` of the values without the largest [`TRIMMED`] fraction; `None` for no values.
fn trimmed_root_mean(mut values: Vec<f64>) -> Option<f64> {
    let keep = values.len() - (values.len() as f64 * TRIMMED).floor() as usize;
    if keep == 0 {
        return None;
    }
    if keep < values.len() {
        values.select_nth_unstable_by(keep - 1, f64::total_cmp);
    }
    Some((values[..keep].iter().sum::<f64>() / keep as f64).sqrt())
}

/// The relative RMSE of `image` against `reference` over all pixels (see the module docs).
///
/// # Panics
/// If the two films differ in size.
pub fn relative_rmse(image: &Film, reference: &Film) -> f64 {
    assert_eq!((image.width(), image.height()), (reference.width(), reference.height()), "films differ in size");
    let sum: f64 = image
        .bounds()
        .pixels()
        .map(|(x, y)| {
            let (i, r) = (luminance_f64(image.pixel_f64(x, y)), luminance_f64(reference.pixel_f64(x, y)));
            (i - r) * (i - r) / (r * r + BRIGHTNESS_FLOOR * BRIGHTNESS_FLOOR)
        })
        .sum();
    (sum / f64::from(image.width() * image.height()).max(1.0)).sqrt()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::rgb::Rgb;
    use crate::sampling::Rng;

    /// A film whose pixels are means of `n` samples of uniform noise in `[0, 2)·level`.
    fn noisy_film(n: u64, level: f32) -> Film {
        let mut film = Film::new(16, 16);
        for (x, y) in film.bounds().pixels() {
            for s in 0..n {
                let u = Rng::for_sample(3, u64::from(y * 16 + x), s).next_f64() as f32;
                film.add_sample(x, y, Rgb::splat(2.0 * u * level), 1.0);
            }
        }
        film
    }

    #[test]
    fn the_estimate_matches_the_error_of_independent_samples() {
        // Uniform noise on [0, 2): mean 1, variance 1/3, so the relative error of a mean of n is
        // √(1/(3n)). The estimate averages 256 pixels' squared half differences: ±20 %.
        for n in [16, 64, 256] {
            let film = noisy_film(n, 1.0);
            let estimate = estimated_relative_error(&film, film.bounds().pixels()).unwrap();
            let truth = (1.0 / (3.0 * n as f64)).sqrt();
            assert!((estimate / truth - 1.0).abs() < 0.2, "n = {n}: {estimate} against {truth}");
        }
    }

    #[test]
    fn the_reference_measure_of_a_film_against_itself_is_zero_and_scales_with_the_error() {
        let a = noisy_film(64, 1.0);
        assert_eq!(relative_rmse(&a, &a), 0.0);
        let mut flat = Film::new(16, 16);
        for (x, y) in flat.bounds().pixels() {
            flat.add_sample(x, y, Rgb::ONE, 1.0);
        }
        let measured = relative_rmse(&a, &flat);
        let truth = (1.0 / (3.0 * 64.0f64)).sqrt();
        assert!((measured / truth - 1.0).abs() < 0.2, "{measured} against {truth}");
    }

    #[test]
    fn dark_pixels_count_absolutely_and_fireflies_are_trimmed() {
        // Pixels far below the floor: the error is relative to the floor, so tiny.
        let dark = noisy_film(16, 1e-4);
        assert!(estimated_relative_error(&dark, dark.bounds().pixels()).unwrap() < 0.01);
        // One firefly pixel in 256 is not trimmed (0.1 % of 256 rounds down to none) ...
        let mut film = noisy_film(64, 1.0);
        let without = estimated_relative_error(&film, film.bounds().pixels()).unwrap();
        film.add_sample(5, 5, Rgb::splat(1e4), 1.0);
        let with = estimated_relative_error(&film, film.bounds().pixels()).unwrap();
        assert!(with > 1.2 * without, "{with} against {without}");
        // ... but among 2000 pixels it is.
        let values: Vec<f64> = (0..2000).map(|i| if i == 7 { 1e6 } else { 1e-4 }).collect();
        assert!((trimmed_root_mean(values).unwrap() - 1e-2).abs() < 1e-12);
        assert_eq!(trimmed_root_mean(Vec::new()), None);
    }

    #[test]
    fn a_pixel_without_two_halves_has_no_estimate() {
        let mut film = Film::new(2, 1);
        film.add_sample(0, 0, Rgb::ONE, 1.0);
        assert_eq!(pixel_relative_variance(&film, 0, 0), None);
        assert_eq!(estimated_relative_error(&film, film.bounds().pixels()), None);
    }
}

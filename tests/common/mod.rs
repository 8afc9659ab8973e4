//! What several test binaries share: statistics for the tests that compare integrators (replicas
//! of a render with seeds 0, 1, …, and the test that two sets of replicas agree within their
//! measured noise), and [`deadline`] for tests of commands that must answer at once.

#![allow(dead_code)] // Each test binary uses its share.

pub mod deadline;

use render::scene::Scene;
use render::settings::IntegratorKind;
use std::sync::atomic::AtomicBool;

/// Per-pixel values (sum of the three channels) of renders of `scene` with `integrator` at
/// `spp`, one per seed of `seeds`: `[replica][pixel]`. No sample is NaN, no ray fails.
pub fn replicas(scene: &Scene, integrator: IntegratorKind, spp: u32, seeds: std::ops::Range<u32>) -> Vec<Vec<f64>> {
    let mut scene = scene.clone();
    scene.settings.spp = spp;
    scene.settings.integrator = integrator;
    let (width, height) = (scene.settings.width, scene.settings.height);
    seeds
        .map(|seed| {
            scene.settings.seed = u64::from(seed);
            let (film, stats) = render::renderer::render(&scene, &AtomicBool::new(false), &|_, _| {});
            assert_eq!(stats.nan_samples, 0);
            assert_eq!(stats.paths.fates.failed, 0);
            (0..height)
                .flat_map(|y| (0..width).map(move |x| (x, y)))
                .map(|(x, y)| film.pixel_f64(x, y).iter().sum())
                .collect()
        })
        .collect()
}

/// Mean and variance of the mean of `values`.
pub fn mean_and_variance_of_mean(values: impl Iterator<Item = f64> + Clone) -> (f64, f64) {
    let n = values.clone().count() as f64;
    let mean = values.clone().sum::<f64>() / n;
    let variance = values.map(|v| (v - mean) * (v - mean)).sum::<f64>() / (n - 1.0);
    (mean, variance / n)
}

/// Sum over pixels of the variance of each pixel's mean.
pub fn spread(r: &[Vec<f64>]) -> f64 {
    (0..r[0].len()).map(|p| mean_and_variance_of_mean(r.iter().map(|img| img[p])).1).sum::<f64>()
}

/// Asserts that two unbiased estimators agree within their measured noise.
///
/// Whole image: the replicas' image means agree within 4 combined standard errors, and that
/// error is at most `max_sigma` of the mean (the test has power). Pixel by pixel: z = Δ/σ with σ
/// from both sides' replica variances. Unbiased, the z² average to ≈ 1 (Welch's t with ~30
/// degrees of freedom for 16 replicas: E z² ≈ 1.07; over a few hundred pixels its standard error
/// is ≈ 0.1), so 0.6 < mean z² < 1.6; and |z| > 4.5 happens in well under one pixel.
pub fn assert_agree(a: &[Vec<f64>], b: &[Vec<f64>], max_sigma: f64, what: &str) {
    let pixels = a[0].len();
    let image_mean =
        |r: &[Vec<f64>]| mean_and_variance_of_mean(r.iter().map(|img| img.iter().sum::<f64>() / pixels as f64));
    let ((ma, va), (mb, vb)) = (image_mean(a), image_mean(b));
    let sigma = (va + vb).sqrt();
    assert!((ma - mb).abs() < 4.0 * sigma, "{what}: image mean {ma} vs {mb}: {:.2} σ, σ = {sigma}", (ma - mb) / sigma);
    assert!(sigma < max_sigma * mb, "{what}: σ = {sigma} for a mean of {mb}");
    let (mut z2_sum, mut noisy, mut outliers) = (0.0, 0, 0);
    for p in 0..pixels {
        let (ma, va) = mean_and_variance_of_mean(a.iter().map(|img| img[p]));
        let (mb, vb) = mean_and_variance_of_mean(b.iter().map(|img| img[p]));
        let variance = va + vb;
        if variance == 0.0 {
            // Where every path is captured or sees the same constant: both exactly alike.
            assert_eq!(ma, mb, "{what}: pixel {p}");
            continue;
        }
        let z2 = (ma - mb) * (ma - mb) / variance;
        z2_sum += z2;
        noisy += 1;
        if z2 > 4.5 * 4.5 {
            outliers += 1;
        }
    }
    let mean_z2 = z2_sum / f64::from(noisy);
    assert!((0.6..1.6).contains(&mean_z2), "{what}: mean z² over pixels: {mean_z2}");
    assert!(outliers <= 2, "{what}: {outliers} pixels beyond 4.5 σ");
}

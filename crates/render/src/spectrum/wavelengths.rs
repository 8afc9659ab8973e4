//! Hero-wavelength sampling (Wilkie, Nawaz, Droske, Weidlich, Hanika 2014, "Hero Wavelength Spectral
//! Sampling", EGSR): one hero wavelength per path from one sample u, and N − 1 companions at u + i/N
//! (mod 1), a rotation that stratifies the N wavelengths over the range.

use super::atanh::atanh;
use super::{LAMBDA_MAX, LAMBDA_MIN, N_WAVELENGTHS};

/// Centre of the visible-importance density, in nm.
const VISIBLE_CENTRE: f64 = 538.0;
/// Inverse width of the visible-importance density, in 1/nm.
const VISIBLE_RATE: f64 = 0.0072;
/// tanh(a(λ − 538)) at the two ends of the range, 360 and 830 nm (computed once here rather than
/// for every path; a test checks them).
const VISIBLE_TANH_BOUNDS: (f64, f64) = (-0.856_910_625_469_828, 0.970_591_346_940_269_8);

/// The wavelengths a path carries (nm) and the density each was drawn with (1/nm).
/// Invariant: sampled wavelengths lie in [`LAMBDA_MIN`], [`LAMBDA_MAX`] with positive densities,
/// until [`SampledWavelengths::terminate_secondary`] sets the companions' to 0; wavelengths given
/// to [`SampledWavelengths::at`] are positive, with density 1.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SampledWavelengths {
    lambda: [f32; N_WAVELENGTHS],
    pdf: [f32; N_WAVELENGTHS],
}

impl SampledWavelengths {
    /// Uniform hero sampling: λ₀ = lerp(u, 360, 830), companions spaced by (830 − 360)/N and wrapped
    /// into the range; each has pdf 1/(830 − 360). `u` in [0, 1).
    pub fn sample_uniform(u: f32) -> Self {
        let pdf = (1.0 / (LAMBDA_MAX - LAMBDA_MIN)) as f32;
        Self {
            lambda: std::array::from_fn(|i| {
                let lambda = LAMBDA_MIN + rotated(u, i) * (LAMBDA_MAX - LAMBDA_MIN);
                lambda as f32
            }),
            pdf: [pdf; N_WAVELENGTHS],
        }
    }

    /// Visible-importance hero sampling (pbrt-v4's `SampleVisibleWavelengths`): each rotated sample
    /// uᵢ = u + i/N (mod 1) is mapped through the inverse CDF of p(λ) ∝ 1/cosh²(a(λ − 538 nm)),
    /// a = 0.0072/nm, on [360, 830] nm, a smooth bump over the luminous range. With
    /// t(λ) = tanh(a(λ − 538)), the CDF is (t(λ) − t(360)) / (t(830) − t(360)).
    /// The density at t is a (1 − t²) / (t(830) − t(360)), as 1/cosh² = 1 − tanh².
    pub fn sample_visible(u: f32) -> Self {
        let (t_lo, t_hi) = VISIBLE_TANH_BOUNDS;
        let t: [f64; N_WAVELENGTHS] = std::array::from_fn(|i| t_lo + rotated(u, i) * (t_hi - t_lo));
        let pdf = t.map(|t| (VISIBLE_RATE * (1.0 - t * t) / (t_hi - t_lo)) as f32);
        // The density is that of t, exact; atanh in f32 (the wavelength is kept in f32) and for
        // all N at once: its logarithm is the costliest step of drawing a path's wavelengths.
        let lambda = atanh(t).map(|a| {
            let lambda = VISIBLE_CENTRE as f32 + a / VISIBLE_RATE as f32;
            lambda.clamp(LAMBDA_MIN as f32, LAMBDA_MAX as f32)
        });
        Self { lambda, pdf }
    }

    /// Given wavelengths, each with density 1: for evaluating spectra at chosen wavelengths
    /// rather than estimating integrals over them.
    pub fn at(lambda: [f32; N_WAVELENGTHS]) -> Self {
        Self { lambda, pdf: [1.0; N_WAVELENGTHS] }
    }

    /// Wavelength `i` in nm (0 is the hero).
    pub fn lambda(&self, i: usize) -> f32 {
        self.lambda[i]
    }

    /// The density wavelength `i` was drawn with, in 1/nm.
    pub fn pdf(&self, i: usize) -> f32 {
        self.pdf[i]
    }

    /// Keeps only the hero wavelength: the companions' densities become 0 (they no longer
    /// count) and the hero's is divided by their number, so that its estimate alone stays
    /// unbiased (pbrt-v4's `TerminateSecondary`). Idempotent.
    pub fn terminate_secondary(&mut self) {
        if self.pdf[1..].iter().all(|&p| p == 0.0) {
            return;
        }
        self.pdf[0] /= N_WAVELENGTHS as f32;
        self.pdf[1..].fill(0.0);
    }
}

/// The i-th rotation of `u`, u + i/N mod 1, in f64 so that the wrap is exact.
fn rotated(u: f32, i: usize) -> f64 {
    (f64::from(u) + i as f64 / N_WAVELENGTHS as f64).fract()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn visible_tanh_bounds_are_the_range_ends() {
        let t = |l: f64| (VISIBLE_RATE * (l - VISIBLE_CENTRE)).tanh();
        assert_eq!(VISIBLE_TANH_BOUNDS, (t(LAMBDA_MIN), t(LAMBDA_MAX)));
    }

    /// The visible-importance density at `lambda`: a / (cosh²(a(λ − 538)) (t(830) − t(360))).
    fn visible_pdf(lambda: f64) -> f64 {
        let (t_lo, t_hi) = VISIBLE_TANH_BOUNDS;
        let c = (VISIBLE_RATE * (lambda - VISIBLE_CENTRE)).cosh();
        VISIBLE_RATE / (c * c * (t_hi - t_lo))
    }

    #[test]
    fn uniform_companions_are_stratified_over_the_range() {
        let stride = ((LAMBDA_MAX - LAMBDA_MIN) / N_WAVELENGTHS as f64) as f32;
        for k in 0..100 {
            let w = SampledWavelengths::sample_uniform(k as f32 / 100.0);
            let mut l = w.lambda;
            l.sort_by(f32::total_cmp);
            assert!(l[0] >= LAMBDA_MIN as f32 && l[0] < (LAMBDA_MIN as f32 + stride + 1e-3));
            for pair in l.windows(2) {
                // Exactly one wavelength in each of the N strata: sorted neighbours one stride apart.
                assert!((pair[1] - pair[0] - stride).abs() < 1e-3, "{l:?}");
            }
        }
    }

    #[test]
    fn visible_pdf_integrates_to_one_and_matches_the_sampler() {
        let n = 47_000;
        let h = (LAMBDA_MAX - LAMBDA_MIN) / n as f64;
        let total: f64 = (0..n).map(|i| visible_pdf(LAMBDA_MIN + (i as f64 + 0.5) * h) * h).sum();
        assert!((total - 1.0).abs() < 1e-9, "∫p = {total}");
        // The sampler inverts the CDF: the fraction of the range's probability below λ(u) is u.
        for k in 0..50 {
            let u = k as f32 / 50.0;
            let w = SampledWavelengths::sample_visible(u);
            let l = f64::from(w.lambda(0));
            assert!((f64::from(w.pdf(0)) / visible_pdf(l) - 1.0).abs() < 1e-5, "pdf at {l} nm");
            let m = ((l - LAMBDA_MIN) / h) as usize;
            let cdf: f64 = (0..m).map(|i| visible_pdf(LAMBDA_MIN + (i as f64 + 0.5) * h) * h).sum();
            assert!((cdf - f64::from(u)).abs() < 1e-3, "u {u}: cdf {cdf}");
        }
    }
}

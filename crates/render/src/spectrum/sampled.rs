//! A spectrum's values at a path's sampled wavelengths, with elementwise arithmetic.

use super::{cie, SampledWavelengths, Xyz, N_WAVELENGTHS};
use std::ops::{Add, AddAssign, Div, Mul, MulAssign, Sub};

/// N values of a spectrum, one per wavelength of a [`SampledWavelengths`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SampledSpectrum([f32; N_WAVELENGTHS]);

impl SampledSpectrum {
    /// The same value at every wavelength.
    pub fn splat(v: f32) -> Self {
        Self::splat_const(v)
    }

    /// [`SampledSpectrum::splat`] for constants.
    pub const fn splat_const(v: f32) -> Self {
        Self([v; N_WAVELENGTHS])
    }

    /// Value `f(i)` at wavelength `i`.
    pub fn from_fn(f: impl FnMut(usize) -> f32) -> Self {
        Self(std::array::from_fn(f))
    }

    /// The value at wavelength `i`.
    pub fn value(&self, i: usize) -> f32 {
        self.0[i]
    }

    /// The largest value (Russian roulette, bounds).
    pub fn max_value(&self) -> f32 {
        self.0.iter().copied().fold(f32::NEG_INFINITY, f32::max)
    }

    /// The mean of the values.
    pub fn average(&self) -> f32 {
        self.0.iter().sum::<f32>() / N_WAVELENGTHS as f32
    }

    /// True when every value is finite.
    pub fn is_finite(&self) -> bool {
        self.0.iter().all(|v| v.is_finite())
    }

    /// The Monte Carlo estimate of XYZ from these values: the mean over the wavelengths of
    /// x̄ȳz̄(λᵢ) S(λᵢ) / p(λᵢ), divided by ∫ȳ dλ (the convention of [`super`]). Unbiased for
    /// ∫ x̄ȳz̄ S dλ / ∫ȳ dλ whenever each λᵢ is marginally distributed by its pdf.
    pub fn to_xyz(&self, wavelengths: &SampledWavelengths) -> Xyz {
        let sum: Xyz = (0..N_WAVELENGTHS)
            .map(|i| {
                let pdf = wavelengths.pdf(i);
                if pdf > 0.0 {
                    let lambda = f64::from(wavelengths.lambda(i));
                    cie::cmf(lambda) * f64::from(self.0[i] / pdf)
                } else {
                    Xyz::ZERO
                }
            })
            .sum();
        sum / (N_WAVELENGTHS as f64 * cie::y_integral())
    }
}

impl Add for SampledSpectrum {
    type Output = Self;
    fn add(self, rhs: Self) -> Self {
        Self::from_fn(|i| self.0[i] + rhs.0[i])
    }
}

impl AddAssign for SampledSpectrum {
    fn add_assign(&mut self, rhs: Self) {
        *self = *self + rhs;
    }
}

impl Sub for SampledSpectrum {
    type Output = Self;
    fn sub(self, rhs: Self) -> Self {
        Self::from_fn(|i| self.0[i] - rhs.0[i])
    }
}

impl Mul for SampledSpectrum {
    type Output = Self;
    fn mul(self, rhs: Self) -> Self {
        Self::from_fn(|i| self.0[i] * rhs.0[i])
    }
}

impl MulAssign for SampledSpectrum {
    fn mul_assign(&mut self, rhs: Self) {
        *self = *self * rhs;
    }
}

impl Mul<f32> for SampledSpectrum {
    type Output = Self;
    fn mul(self, rhs: f32) -> Self {
        Self::from_fn(|i| self.0[i] * rhs)
    }
}

impl Div for SampledSpectrum {
    type Output = Self;
    fn div(self, rhs: Self) -> Self {
        Self::from_fn(|i| self.0[i] / rhs.0[i])
    }
}

impl Div<f32> for SampledSpectrum {
    type Output = Self;
    fn div(self, rhs: f32) -> Self {
        Self::from_fn(|i| self.0[i] / rhs)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::sampling::Rng;
    use crate::spectrum::Spectrum;

    #[test]
    fn arithmetic_is_elementwise() {
        let a = SampledSpectrum::from_fn(|i| i as f32);
        let b = SampledSpectrum::splat(2.0);
        assert_eq!((a * b + a).value(3), 9.0);
        assert_eq!((a / 2.0).value(1), 0.5);
        assert_eq!(a.max_value(), 3.0);
        assert_eq!(a.average(), 1.5);
        let mut c = a;
        c *= b;
        c += b;
        assert_eq!(c.value(2), 6.0);
        assert!(!(a / 0.0).is_finite());
    }

    /// A smooth reflectance-like spectrum: a Gaussian bump on a floor.
    struct Bump;
    impl Spectrum for Bump {
        fn eval(&self, lambda: f64) -> f64 {
            0.2 + (-((lambda - 600.0) / 40.0).powi(2)).exp()
        }
    }

    /// Mean and standard error per XYZ component of `n` one-path estimates of `Bump`'s XYZ.
    fn estimate(n: usize, sample: impl Fn(f32) -> SampledWavelengths) -> (Xyz, Xyz) {
        let mut rng = Rng::new(22);
        let (mut sum, mut sum_sq) = (Xyz::ZERO, Xyz::ZERO);
        for _ in 0..n {
            let w = sample(rng.next_f64() as f32);
            let e = Bump.sample(&w).to_xyz(&w);
            sum += e;
            sum_sq += e * e;
        }
        let mean = sum / n as f64;
        let variance = sum_sq / n as f64 - mean * mean;
        (mean, (variance / n as f64).powf(0.5))
    }

    #[test]
    fn hero_estimates_converge_to_the_quadrature() {
        // Unbiased: the mean of 20 000 paths lies within 4 standard errors of the 1 nm quadrature.
        let reference = cie::xyz_quadrature(&Bump);
        let (uniform, se_uniform) = estimate(20_000, SampledWavelengths::sample_uniform);
        let (visible, se_visible) = estimate(20_000, SampledWavelengths::sample_visible);
        for c in 0..3 {
            assert!((uniform[c] - reference[c]).abs() < 4.0 * se_uniform[c], "uniform {c}");
            assert!((visible[c] - reference[c]).abs() < 4.0 * se_visible[c], "visible {c}");
        }
        // Visible-importance sampling puts the wavelengths where x̄ȳz̄ are large: lower noise in Y.
        assert!(se_visible.y < se_uniform.y, "{se_visible} vs {se_uniform}");
        eprintln!(
            "standard error per path of XYZ: uniform {:.4}, visible {:.4}",
            se_uniform * 141.4,
            se_visible * 141.4
        );
    }
}

//! Jakob & Hanika's (2019) spectral basis: a quadratic in wavelength through a sigmoid, smooth and
//! bounded in [0, 1], so that an upsampled reflectance never exceeds 1.

use super::Spectrum;

/// S(c₀ λ² + c₁ λ + c₂) with λ in nm and S(x) = ½ + x / (2 √(1 + x²)) (Jakob & Hanika 2019, eq. 3);
/// an infinite polynomial (c₂ = ±∞, the constant spectra 0 and 1) gives S = 0 or 1.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SigmoidPolynomial {
    c: [f32; 3],
}

impl SigmoidPolynomial {
    /// The spectrum with coefficients `c` = [c₀, c₁, c₂] (of λ², λ, 1; λ in nm).
    pub fn new(c: [f32; 3]) -> Self {
        Self { c }
    }

    /// The constant spectrum `v` in [0, 1]: c₀ = c₁ = 0, c₂ = S⁻¹(v) = (v − ½) / √(v (1 − v)).
    pub fn constant(v: f32) -> Self {
        Self::new([0.0, 0.0, (v - 0.5) / (v * (1.0 - v)).sqrt()])
    }
}

/// S(x) = ½ + x / (2 √(1 + x²)), with its limits at ±∞.
pub(super) fn sigmoid(x: f64) -> f64 {
    if x.is_infinite() {
        return if x > 0.0 { 1.0 } else { 0.0 };
    }
    0.5 + x / (2.0 * (1.0 + x * x).sqrt())
}

impl Spectrum for SigmoidPolynomial {
    fn eval(&self, lambda: f64) -> f64 {
        let [c0, c1, c2] = self.c.map(f64::from);
        sigmoid((c0 * lambda + c1) * lambda + c2)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn constants_and_limits() {
        for v in [0.0, 0.1, 0.5, 0.9, 1.0] {
            let s = SigmoidPolynomial::constant(v);
            assert!((s.eval(400.0) - f64::from(v)).abs() < 1e-6, "{v}");
        }
        assert!(sigmoid(1e30) <= 1.0 && sigmoid(-1e30) >= 0.0);
        assert!((sigmoid(0.0) - 0.5).abs() < 1e-15);
    }
}

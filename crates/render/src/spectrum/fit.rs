//! The Gauss–Newton fit of one RGB colour to a sigmoid polynomial (Jakob & Hanika 2019, §4):
//! minimise the CIELAB difference between the target and the colour of the spectrum as a
//! reflectance under D65, seen by the CIE 1931 observer.

use super::sigmoid::sigmoid;
use super::{cie, linear_srgb_to_xyz, Spectrum, Xyz, D65, LAMBDA_MAX, LAMBDA_MIN};
use glam::{DMat3, DVec3};

/// Quadrature spacing of the fit, in nm (every fifth row of the CIE table, the D65 table's nodes).
const STEP: f64 = 5.0;
/// Gauss–Newton iterations at most (pbrt's `rgb2spec_opt`).
const ITERATIONS: usize = 15;
/// Squared CIELAB residual at which a fit is done.
const CONVERGED: f64 = 1e-6;
/// Central-difference step of the Jacobian, in normalised coefficients.
const DIFF_STEP: f64 = 1e-5;
/// Largest coefficient magnitude (normalised λ): keeps steep fits near black and white finite.
const MAX_COEFFICIENT: f64 = 200.0;

/// Quadrature nodes and weights for colours of sigmoid-polynomial reflectances under D65.
pub(super) struct Fitter {
    /// Node wavelengths normalised to [0, 1] over [360, 830] nm (the fit's well-conditioned variable).
    nodes: Vec<f64>,
    /// XYZ weights x̄ȳz̄(λ) D65(λ) Δλ / ∫ȳ at each node: Σ wᵢ ρ(λᵢ) is the XYZ of reflectance ρ.
    weights: Vec<Xyz>,
    /// XYZ of the Rec. 709 white, CIELAB's reference white.
    white: Xyz,
}

impl Fitter {
    pub fn new() -> Self {
        let d65 = D65::new();
        let n = ((LAMBDA_MAX - LAMBDA_MIN) / STEP) as usize + 1;
        let lambdas: Vec<f64> = (0..n).map(|i| LAMBDA_MIN + STEP * i as f64).collect();
        Self {
            nodes: lambdas.iter().map(|l| (l - LAMBDA_MIN) / (LAMBDA_MAX - LAMBDA_MIN)).collect(),
            weights: lambdas.iter().map(|&l| cie::cmf(l) * (d65.eval(l) * STEP / cie::y_integral())).collect(),
            white: linear_srgb_to_xyz(DVec3::ONE),
        }
    }

    /// Coefficients (of λ², λ, 1 with λ in nm) of the sigmoid polynomial whose colour is `rgb`,
    /// starting from normalised coefficients `start`; also returns the normalised solution, the
    /// start of the neighbouring fit.
    pub fn fit(&self, rgb: DVec3, start: DVec3) -> (DVec3, [f32; 3]) {
        let target = self.lab(linear_srgb_to_xyz(rgb));
        let mut c = start;
        for _ in 0..ITERATIONS {
            let r = self.residual(c, target);
            let j = self.jacobian(c, target);
            if !(j.determinant().abs() > 1e-15) {
                break;
            }
            c -= j.inverse() * r;
            let largest = c.abs().max_element();
            if largest > MAX_COEFFICIENT {
                c *= MAX_COEFFICIENT / largest;
            }
            if r.length_squared() < CONVERGED {
                break;
            }
        }
        (c, to_nanometres(c))
    }

    /// CIELAB of the reflectance with normalised coefficients `c`, minus `target`.
    fn residual(&self, c: DVec3, target: DVec3) -> DVec3 {
        let xyz: Xyz =
            self.nodes.iter().zip(&self.weights).map(|(&x, &w)| w * sigmoid((c.x * x + c.y) * x + c.z)).sum();
        self.lab(xyz) - target
    }

    /// ∂ residual / ∂ c by central differences; column k is the derivative in cₖ.
    fn jacobian(&self, c: DVec3, target: DVec3) -> DMat3 {
        let column = |k: usize| {
            let mut d = DVec3::ZERO;
            d[k] = DIFF_STEP;
            (self.residual(c + d, target) - self.residual(c - d, target)) / (2.0 * DIFF_STEP)
        };
        DMat3::from_cols(column(0), column(1), column(2))
    }

    /// CIELAB (L*, a*, b*) of `xyz` relative to the Rec. 709 white (CIE 015:2018 §8.2.1).
    fn lab(&self, xyz: Xyz) -> DVec3 {
        let f = |t: f64| {
            let delta: f64 = 6.0 / 29.0;
            if t > delta.powi(3) {
                t.cbrt()
            } else {
                t / (3.0 * delta * delta) + 4.0 / 29.0
            }
        };
        let (fx, fy, fz) = (f(xyz.x / self.white.x), f(xyz.y / self.white.y), f(xyz.z / self.white.z));
        DVec3::new(116.0 * fy - 16.0, 500.0 * (fx - fy), 200.0 * (fy - fz))
    }
}

/// Coefficients of λ in nm from those of x = (λ − 360) / 470: c₀x² + c₁x + c₂ expanded in λ.
fn to_nanometres(c: DVec3) -> [f32; 3] {
    let (m, w) = (LAMBDA_MIN, LAMBDA_MAX - LAMBDA_MIN);
    [c.x / (w * w), c.y / w - 2.0 * c.x * m / (w * w), c.x * m * m / (w * w) - c.y * m / w + c.z].map(|v| v as f32)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::spectrum::SigmoidPolynomial;

    #[test]
    fn nanometre_coefficients_give_the_same_spectrum() {
        let c = DVec3::new(-3.0, 4.0, -0.5);
        let s = SigmoidPolynomial::new(to_nanometres(c));
        for lambda in [360.0, 500.0, 700.0, 830.0] {
            let x = (lambda - LAMBDA_MIN) / (LAMBDA_MAX - LAMBDA_MIN);
            let expected = sigmoid((c.x * x + c.y) * x + c.z);
            assert!((s.eval(lambda) - expected).abs() < 1e-5, "{lambda}");
        }
    }

    #[test]
    fn fits_a_saturated_colour() {
        let fitter = Fitter::new();
        let (c, _) = fitter.fit(DVec3::new(0.8, 0.2, 0.1), DVec3::ZERO);
        let r = fitter.residual(c, fitter.lab(linear_srgb_to_xyz(DVec3::new(0.8, 0.2, 0.1))));
        assert!(r.length() < 1e-2, "ΔE = {}", r.length());
    }
}

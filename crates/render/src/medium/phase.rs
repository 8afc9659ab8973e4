//! The Henyey–Greenstein phase function (Henyey & Greenstein 1941, "Diffuse radiation in the
//! galaxy"; pbrt-v4 §11.3.1): the one-parameter lobe whose mean cosine is `g`,
//!
//! `p(cos θ) = (1 − g²) / (4π (1 + g² − 2g cos θ)^{3/2})`,
//!
//! over the unit sphere of directions, θ between the light's propagation direction before and
//! after scattering: `g > 0` scatters forward, `g < 0` back, `g = 0` is isotropic. Directions are
//! given in the medium's rest frame, as vectors of an orthonormal spatial basis of its observer
//! (the integrator measures them with the medium's tetrad), so the lobe is the same in any
//! spacetime.

use crate::geometry::{Frame, Vec3};
use std::f64::consts::PI;

/// `|g|` must stay below 1: at 1 the lobe is a Dirac delta with no density.
const MAX_ABS_G: f64 = 1.0 - 1e-6;

#[derive(Clone, Copy, Debug, PartialEq)]
pub struct HenyeyGreenstein {
    g: f64,
}

/// A scattered direction drawn from the phase function, and its density (per steradian). The
/// sampling is exact, so the phase function's value there is `pdf` too and a path's weight is 1.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PhaseSample {
    pub direction: Vec3,
    pub pdf: f64,
}

impl HenyeyGreenstein {
    /// The lobe of mean cosine `g`; `None` unless `g` is finite and `|g| < 1`.
    pub fn new(g: f64) -> Option<Self> {
        (g.abs() <= MAX_ABS_G).then_some(Self { g })
    }

    pub const ISOTROPIC: Self = Self { g: 0.0 };

    /// The mean cosine of the scattering angle.
    pub fn g(&self) -> f64 {
        self.g
    }

    /// The density of scattering by angle θ (per steradian).
    pub fn eval(&self, cos_theta: f64) -> f64 {
        let g = self.g;
        // `1 + g² − 2g cos θ` written as `(1 − g)² + 2g(1 − cos θ)`, which keeps its digits
        // when both `g` and `cos θ` are near 1 (a sharp forward lobe seen along its axis).
        let denominator = (1.0 - g) * (1.0 - g) + 2.0 * g * (1.0 - cos_theta.clamp(-1.0, 1.0));
        (1.0 - g * g) / (4.0 * PI * denominator * denominator.sqrt())
    }

    /// The density of scattering from propagation direction `incoming` into `outgoing` (unit
    /// vectors of the rest frame).
    pub fn eval_directions(&self, incoming: Vec3, outgoing: Vec3) -> f64 {
        self.eval(incoming.dot(outgoing))
    }

    /// The cosine of a scattering angle drawn by inverting the lobe's distribution at `u`. The
    /// textbook inverse, `(1 + g² − s²) / 2g` with `s = (1 − g²)/(1 + g w)` and `w = 2u − 1`,
    /// loses its digits as `g → 0`; multiplied out over `(1 + g w)²` it is the polynomial
    /// below, which is exactly `w` (uniform, isotropic) at `g = 0` and well defined up to
    /// `|g| → 1`.
    pub fn sample_cos_theta(&self, u: f64) -> f64 {
        let g = self.g;
        let w = 2.0 * u - 1.0;
        let numerator = w + 0.5 * g * (w * w + 3.0) + g * g * w + 0.5 * g * g * g * (w * w - 1.0);
        let t = 1.0 + g * w;
        (numerator / (t * t)).clamp(-1.0, 1.0)
    }

    /// A scattered propagation direction for light propagating along `incoming` (unit).
    pub fn sample(&self, incoming: Vec3, u: [f64; 2]) -> PhaseSample {
        let cos_theta = self.sample_cos_theta(u[0]);
        let sin_theta = (1.0 - cos_theta * cos_theta).max(0.0).sqrt();
        let phi = 2.0 * PI * u[1];
        let local = Vec3::new(sin_theta * phi.cos(), sin_theta * phi.sin(), cos_theta);
        PhaseSample { direction: Frame::from_normal(incoming).to_world(local), pdf: self.eval(cos_theta) }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::sampling::Rng;

    const GS: [f64; 7] = [-0.95, -0.5, -0.1, 0.0, 0.3, 0.8, 0.999];

    /// ∫ p dω = 2π ∫ p(μ) dμ by Simpson's rule in μ = cos θ, on a grid graded towards the peak.
    fn integral(phase: &HenyeyGreenstein, f: impl Fn(f64) -> f64) -> f64 {
        let n = 200_000;
        // μ = 1 − 2s² (or its mirror) crowds the nodes near the forward (backward) peak.
        let to_mu = |s: f64| if phase.g() >= 0.0 { 1.0 - 2.0 * s * s } else { -1.0 + 2.0 * s * s };
        let jacobian = |s: f64| 4.0 * s;
        let h = 1.0 / n as f64;
        let term = |i: usize| {
            let s = i as f64 * h;
            let mu = to_mu(s);
            phase.eval(mu) * f(mu) * jacobian(s)
        };
        let mut sum = term(0) + term(n);
        for i in 1..n {
            sum += if i % 2 == 1 { 4.0 } else { 2.0 } * term(i);
        }
        2.0 * PI * sum * h / 3.0
    }

    #[test]
    fn the_lobe_integrates_to_one_with_mean_cosine_g() {
        for g in GS {
            let phase = HenyeyGreenstein::new(g).unwrap();
            let norm = integral(&phase, |_| 1.0);
            let mean = integral(&phase, |mu| mu);
            assert!((norm - 1.0).abs() < 1e-6, "g = {g}: ∫p = {norm}");
            assert!((mean - g).abs() < 1e-6, "g = {g}: ⟨cos⟩ = {mean}");
        }
        assert_eq!(HenyeyGreenstein::ISOTROPIC.eval(0.3), 1.0 / (4.0 * PI));
    }

    #[test]
    fn refuses_g_of_one_and_nan() {
        assert!(HenyeyGreenstein::new(1.0).is_none());
        assert!(HenyeyGreenstein::new(-1.0).is_none());
        assert!(HenyeyGreenstein::new(f64::NAN).is_none());
    }

    #[test]
    fn isotropic_sampling_is_exactly_uniform_in_cosine() {
        for u in [0.0, 0.125, 0.5, 0.9] {
            assert_eq!(HenyeyGreenstein::ISOTROPIC.sample_cos_theta(u), 2.0 * u - 1.0);
        }
    }

    /// The sampled cosines' mean (g, within 5σ of the lobe's own spread) and a χ² test of
    /// their histogram in bins of equal probability under the lobe's exact CDF in `cos θ`.
    #[test]
    fn sampling_follows_the_lobe() {
        let n = 200_000;
        for g in GS {
            let phase = HenyeyGreenstein::new(g).unwrap();
            let mut rng = Rng::new(7);
            let incoming = Vec3::new(0.3, -0.5, 0.8).normalize();
            let mut cosines = Vec::with_capacity(n);
            for _ in 0..n {
                let s = phase.sample(incoming, rng.next_2d());
                assert!((s.direction.length() - 1.0).abs() < 1e-9);
                let mu = s.direction.dot(incoming);
                assert!((s.pdf - phase.eval(mu)).abs() <= 1e-6 * s.pdf, "g = {g}");
                cosines.push(mu);
            }
            let mean = cosines.iter().sum::<f64>() / n as f64;
            let second = integral(&phase, |mu| mu * mu);
            let sigma = ((second - g * g) / n as f64).sqrt();
            assert!((mean - g).abs() < 5.0 * sigma + 1e-9, "g = {g}: mean {mean}, σ {sigma}");

            // The exact CDF: P(cos θ ≤ μ) = (1 − g²)/(2g) · (1/√(1+g²−2gμ) − 1/(1+g)), or
            // (μ + 1)/2 at g = 0.
            let cdf = |mu: f64| {
                if g == 0.0 {
                    0.5 * (mu + 1.0)
                } else {
                    (1.0 - g * g) / (2.0 * g) * (1.0 / (1.0 + g * g - 2.0 * g * mu).sqrt() - 1.0 / (1.0 + g))
                }
            };
            let bins = 50;
            let mut counts = vec![0usize; bins];
            for mu in cosines {
                let p = cdf(mu).clamp(0.0, 1.0 - 1e-12);
                counts[(p * bins as f64) as usize] += 1;
            }
            let expected = n as f64 / bins as f64;
            let chi2: f64 = counts.iter().map(|&c| (c as f64 - expected).powi(2) / expected).sum();
            // 49 degrees of freedom: P(χ² > 95) ≈ 1e-4.
            assert!(chi2 < 95.0, "g = {g}: χ² = {chi2}");
        }
    }

    #[test]
    fn a_sharp_lobe_keeps_its_digits_along_its_axis() {
        let phase = HenyeyGreenstein::new(0.999).unwrap();
        // (1 − g²)/(4π(1 − g)³) = (1 + g)/(4π(1 − g)²)
        let exact = 1.999 / (4.0 * PI * 1e-6);
        assert!((phase.eval(1.0) / exact - 1.0).abs() < 1e-9);
    }
}

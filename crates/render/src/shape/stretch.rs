//! How an affine map stretches the area of a curved surface, and how to sample the stretched
//! surface uniformly anyway.
//!
//! A linear map `M` takes an area element `dA` with unit normal `n` to one of area
//! `|cof(M)·n| dA`, where `cof(M) = det(M)·M⁻ᵀ` is the cofactor matrix (Nanson's formula). Under a
//! similarity (rotation and uniform scale) the factor is a constant and a uniform sample of the
//! object-space surface maps to a uniform sample of the world-space surface. Under non-uniform
//! scale it varies over a curved surface (a sphere becomes an ellipsoid), so:
//!
//! * the area is an integral, computed once by Gauss–Legendre × trapezoidal quadrature, which
//!   converges exponentially for these smooth (and, in azimuth, periodic) integrands;
//! * uniform points come from rejection: an object-space candidate is accepted with probability
//!   `|cof(M)·n| / max|cof(M)·n|`, where the maximum is `|det M| / σ_min(M)`.
//!
//! Rejection needs more random numbers than the two a sample is given; later candidates come from
//! a stream seeded by the bits of `u`, so the result is still a deterministic function of `u`.
//! Only the first candidate keeps the sampler's stratification, which is the price of exactness.

use crate::geometry::Vec3;
use crate::sampling::Rng;
use crate::transform::Transform;
use glam::DMat3;
use std::f64::consts::{PI, TAU};

/// After this many rejected candidates the last one is returned; the acceptance rate is at least
/// about 1/2 for any map (the factor's mean over directions exceeds half its maximum), so this
/// happens with probability below 2⁻⁶⁴.
const MAX_CANDIDATES: usize = 64;

/// The area stretch of one object-to-world map.
#[derive(Clone, Copy, Debug)]
pub(super) struct AreaStretch {
    cofactor: DMat3,
    /// `max_n |cof(M)·n|` over unit `n`.
    bound: f64,
    /// The map is a similarity: the stretch is the same everywhere.
    uniform: bool,
}

impl AreaStretch {
    pub(super) fn new(to_world: &Transform) -> Self {
        let m = to_world.linear();
        let det = m.determinant();
        let cofactor = to_world.normal_matrix() * det;
        let (smallest, largest) = to_world.scale_bounds();
        Self { cofactor, bound: det.abs() / smallest, uniform: largest - smallest <= 1e-12 * largest }
    }

    /// The factor by which area elements with object-space unit normal `n` grow.
    #[inline]
    pub(super) fn factor(&self, n: Vec3) -> f64 {
        (self.cofactor * n).length()
    }

    /// `∫ factor(ŝ) dΩ` over the unit sphere: the world area of the image of the unit sphere.
    pub(super) fn unit_sphere_area(&self) -> f64 {
        if self.uniform {
            return 4.0 * PI * self.bound;
        }
        // θ ∈ [0, π] by Gauss–Legendre (the integrand sinθ·factor is smooth but not periodic in θ),
        // φ by the trapezoidal rule (periodic: exponential convergence).
        let (thetas, phis) = (64, 128);
        let mut sum = 0.0;
        for (x, w) in gauss_legendre(thetas) {
            let theta = 0.5 * PI * (x + 1.0);
            let (sin, cos) = theta.sin_cos();
            let mut ring = 0.0;
            for k in 0..phis {
                let (sp, cp) = (TAU * k as f64 / phis as f64).sin_cos();
                ring += self.factor(Vec3::new(sin * cp, sin * sp, cos));
            }
            sum += w * sin * ring;
        }
        sum * (0.5 * PI) * (TAU / phis as f64)
    }

    /// `∫ factor(n(φ)) dφ` over φ ∈ [0, 2π), `n(φ) = (cos φ, sin φ, 0)`: the world area of the
    /// image of the side of a unit cylinder of unit height.
    pub(super) fn unit_cylinder_side_area(&self) -> f64 {
        if self.uniform {
            return TAU * self.bound;
        }
        let n = 512;
        let sum: f64 = (0..n)
            .map(|k| {
                let (s, c) = (TAU * k as f64 / n as f64).sin_cos();
                self.factor(Vec3::new(c, s, 0.0))
            })
            .sum();
        sum * TAU / n as f64
    }

    /// A world-uniform sample: `propose` maps `[0,1)²` uniformly onto the object-space surface and
    /// returns the sample with its object-space unit normal; candidates are accepted in proportion
    /// to their area stretch.
    pub(super) fn sample<T>(&self, u: [f64; 2], propose: impl Fn([f64; 2]) -> (T, Vec3)) -> T {
        let (mut candidate, mut n) = propose(u);
        if self.uniform {
            return candidate;
        }
        let mut rng = Rng::new(u[0].to_bits() ^ u[1].to_bits().rotate_left(32));
        for _ in 0..MAX_CANDIDATES {
            if rng.next_f64() * self.bound <= self.factor(n) {
                break;
            }
            (candidate, n) = propose(rng.next_2d());
        }
        candidate
    }
}

/// Nodes and weights of the `n`-point Gauss–Legendre rule on `[−1, 1]`, by Newton's method on
/// the Legendre polynomial from Chebyshev initial guesses (Press et al., Numerical Recipes §4.6).
fn gauss_legendre(n: usize) -> Vec<(f64, f64)> {
    let mut rule = Vec::with_capacity(n);
    for i in 0..n {
        let mut x = (PI * (i as f64 + 0.75) / (n as f64 + 0.5)).cos();
        let mut derivative = 1.0;
        for _ in 0..100 {
            // Three-term recurrence for P_n(x); then P_n'(x) from P_n and P_{n−1}.
            let (mut p0, mut p1) = (1.0, 0.0);
            for j in 0..n {
                let p2 = p1;
                p1 = p0;
                p0 = ((2 * j + 1) as f64 * x * p1 - j as f64 * p2) / (j + 1) as f64;
            }
            derivative = n as f64 * (x * p0 - p1) / (x * x - 1.0);
            let step = p0 / derivative;
            x -= step;
            if step.abs() < 1e-15 {
                break;
            }
        }
        rule.push((x, 2.0 / ((1.0 - x * x) * derivative * derivative)));
    }
    rule
}

#[cfg(test)]
mod tests {
    use super::*;

    fn stretch(s: Vec3) -> AreaStretch {
        let t = Transform::scale(s).unwrap().then(&Transform::rotate_deg(Vec3::new(1.0, 2.0, -0.5), 50.0).unwrap());
        AreaStretch::new(&t)
    }

    #[test]
    fn gauss_legendre_integrates_polynomials_exactly() {
        let rule = gauss_legendre(8);
        let integral = |k: i32| rule.iter().map(|(x, w)| w * x.powi(k)).sum::<f64>();
        assert!((integral(0) - 2.0).abs() < 1e-14);
        assert!((integral(14) - 2.0 / 15.0).abs() < 1e-14);
        assert!(integral(7).abs() < 1e-14);
    }

    #[test]
    fn spheroid_areas_match_closed_forms() {
        // Prolate (a, a, c), c > a: 2πa²(1 + c/(a e) · asin e), e² = 1 − a²/c².
        let (a, c): (f64, f64) = (1.0, 3.0);
        let e = (1.0 - a * a / (c * c)).sqrt();
        let prolate = 2.0 * PI * a * a * (1.0 + c / (a * e) * e.asin());
        let got = stretch(Vec3::new(a, a, c)).unit_sphere_area();
        assert!((got / prolate - 1.0).abs() < 1e-10, "{got} vs {prolate}");
        // Oblate (a, a, c), c < a: 2πa² + π c²/e · ln((1 + e)/(1 − e)), e² = 1 − c²/a².
        let (a, c): (f64, f64) = (2.0, 0.5);
        let e = (1.0 - c * c / (a * a)).sqrt();
        let oblate = 2.0 * PI * a * a + PI * c * c / e * ((1.0 + e) / (1.0 - e)).ln();
        let got = stretch(Vec3::new(a, c, a)).unit_sphere_area();
        assert!((got / oblate - 1.0).abs() < 1e-10, "{got} vs {oblate}");
        assert!((stretch(Vec3::splat(2.0)).unit_sphere_area() - 16.0 * PI).abs() < 1e-9);
    }

    #[test]
    fn elliptic_cylinder_side_matches_the_ellipse_perimeter() {
        // Perimeter of an ellipse with semi-axes 1 and 2 (Gauss–Kummer series, converged).
        let (a, b): (f64, f64) = (2.0, 1.0);
        let h = ((a - b) / (a + b)).powi(2);
        let mut series = 1.0;
        let mut coefficient = 1.0;
        for k in 1..40 {
            // binomial(1/2, k)²
            coefficient *= (0.5 - (k - 1) as f64) / k as f64;
            series += coefficient * coefficient * h.powi(k);
        }
        let perimeter = PI * (a + b) * series;
        let t = Transform::scale(Vec3::new(a, b, 3.0)).unwrap();
        let got = AreaStretch::new(&t).unit_cylinder_side_area();
        assert!((got / (3.0 * perimeter) - 1.0).abs() < 1e-12, "{got} vs {}", 3.0 * perimeter);
    }
}

//! The GGX (Trowbridge–Reitz) microfacet distribution shared by the rough conductor and the rough
//! plastic: normal distribution `D`, Smith masking `G1` and height-correlated masking–shadowing `G`, and
//! sampling of the normals visible from a direction (Heitz 2018).
//!
//! Isotropic only: the shading frames the shapes provide have no meaningful tangent direction.
//!
//! References: Trowbridge & Reitz 1975; Walter, Marschner, Li & Torrance 2007, "Microfacet models for
//! refraction through rough surfaces" (EGSR); Heitz 2014, "Understanding the masking-shadowing function in
//! microfacet-based BRDFs" (JCGT 3(2)); Heitz 2018, "Sampling the GGX distribution of visible normals"
//! (JCGT 7(4)).

use crate::geometry::Vec3;
use std::f64::consts::PI;

/// Below this `alpha` a surface is treated as perfectly smooth (a delta lobe), as in pbrt-v4's
/// `EffectivelySmooth`: the GGX lobe would be narrower than f64 can sample and evaluate robustly.
pub const SMOOTH_ALPHA: f64 = 1e-3;

/// The user-facing roughness `r ∈ [0, 1]` → GGX `alpha = r²`. The square makes roughness perceptually
/// closer to linear (Burley 2012, "Physically-based shading at Disney").
pub fn roughness_to_alpha(roughness: f64) -> f64 {
    roughness * roughness
}

/// Mirror reflection of `w` about the unit normal `n`: `2(w·n)n − w`.
#[inline]
pub fn reflect(w: Vec3, n: Vec3) -> Vec3 {
    2.0 * w.dot(n) * n - w
}

/// Isotropic GGX distribution with width `alpha` (`alpha = 1`: very rough; `alpha → 0`: a mirror).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Ggx {
    pub alpha: f64,
}

impl Ggx {
    pub fn new(alpha: f64) -> Self {
        Self { alpha }
    }

    /// True when `alpha` is too small for a microfacet lobe: treat the surface as a smooth interface.
    pub fn is_smooth(&self) -> bool {
        self.alpha < SMOOTH_ALPHA
    }

    /// Normal distribution `D(h) = α² / (π (cos²θh (α² − 1) + 1)²)` for a unit half vector `h`
    /// (Walter et al. 2007, eq. 33, rewritten without tan θ). Zero for back-facing microfacets.
    pub fn d(&self, h: Vec3) -> f64 {
        if h.z <= 0.0 {
            return 0.0;
        }
        let a2 = self.alpha * self.alpha;
        let t = h.z * h.z * (a2 - 1.0) + 1.0;
        a2 / (PI * t * t)
    }

    /// Smith's auxiliary function `Λ(w) = (√(1 + α² tan²θ) − 1) / 2` (Heitz 2014).
    pub fn lambda(&self, w: Vec3) -> f64 {
        let cos2 = w.z * w.z;
        if cos2 == 0.0 {
            return f64::INFINITY;
        }
        let alpha2_tan2 = self.alpha * self.alpha * (1.0 - cos2).max(0.0) / cos2;
        0.5 * ((1.0 + alpha2_tan2).sqrt() - 1.0)
    }

    /// Smith masking `G1(w) = 1 / (1 + Λ(w))`.
    pub fn g1(&self, w: Vec3) -> f64 {
        1.0 / (1.0 + self.lambda(w))
    }

    /// Height-correlated masking–shadowing `G(wo, wi) = 1 / (1 + Λ(wo) + Λ(wi))` (Heitz 2014).
    pub fn g(&self, wo: Vec3, wi: Vec3) -> f64 {
        1.0 / (1.0 + self.lambda(wo) + self.lambda(wi))
    }

    /// Density of the normals visible from `w` (upper hemisphere), per unit solid angle of `h`:
    /// `D_w(h) = G1(w) max(0, w·h) D(h) / cos θw` (Heitz 2018, eq. 1).
    pub fn visible_normal_pdf(&self, w: Vec3, h: Vec3) -> f64 {
        if w.z <= 0.0 {
            return 0.0;
        }
        self.g1(w) * w.dot(h).max(0.0) * self.d(h) / w.z
    }

    /// Density, per unit solid angle of `wi`, of reflecting `wo` about a visible normal:
    /// `D_wo(h) / (4 |wo·h|)` with `h = normalize(wo + wi)` (the Jacobian of reflection, Walter et al. 2007,
    /// eq. 14). Zero when `wo` and `wi` are not both above the surface.
    pub fn reflection_pdf(&self, wo: Vec3, wi: Vec3) -> f64 {
        if wo.z <= 0.0 || wi.z <= 0.0 {
            return 0.0;
        }
        let h = (wo + wi).normalize();
        self.visible_normal_pdf(wo, h) / (4.0 * wo.dot(h))
    }

    /// A microfacet normal distributed as [`Ggx::visible_normal_pdf`] from `w` (which must have
    /// `w.z > 0`), by Heitz 2018, listing 1: stretch `w` to the configuration `α = 1`, sample the visible
    /// half of the unit disk projected along it, lift onto the hemisphere, unstretch.
    pub fn sample_visible_normal(&self, w: Vec3, u: [f64; 2]) -> Vec3 {
        // Section 3.2: the view direction in the hemisphere configuration.
        let vh = Vec3::new(self.alpha * w.x, self.alpha * w.y, w.z).normalize();
        // Section 4.1: an orthonormal basis around it (T1 horizontal).
        let len2 = vh.x * vh.x + vh.y * vh.y;
        let t1 = if len2 > 0.0 { Vec3::new(-vh.y, vh.x, 0.0) / len2.sqrt() } else { Vec3::X };
        let t2 = vh.cross(t1);
        // Section 4.2: a point of the projected area, uniformly.
        let r = u[0].sqrt();
        let phi = 2.0 * PI * u[1];
        let p1 = r * phi.cos();
        let s = 0.5 * (1.0 + vh.z);
        let p2 = (1.0 - s) * (1.0 - p1 * p1).max(0.0).sqrt() + s * r * phi.sin();
        // Section 4.3: reprojection onto the hemisphere.
        let nh = p1 * t1 + p2 * t2 + (1.0 - p1 * p1 - p2 * p2).max(0.0).sqrt() * vh;
        // Section 3.4: back to the ellipsoid configuration.
        Vec3::new(self.alpha * nh.x, self.alpha * nh.y, nh.z.max(0.0)).normalize()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::sampling::{uniform_sphere, Rng, UNIFORM_SPHERE_PDF};

    /// Monte Carlo estimate of `∫ f(ω) dω` over the sphere with uniform directions, with its standard error.
    fn integrate_sphere(n: usize, seed: u64, f: impl Fn(Vec3) -> f64) -> (f64, f64) {
        let mut rng = Rng::new(seed);
        let (mut sum, mut sum2) = (0.0, 0.0);
        for _ in 0..n {
            let v = f(uniform_sphere(rng.next_2d())) / UNIFORM_SPHERE_PDF;
            sum += v;
            sum2 += v * v;
        }
        let mean = sum / n as f64;
        (mean, ((sum2 / n as f64 - mean * mean) / n as f64).sqrt())
    }

    #[test]
    fn projected_area_of_microfacets_is_one() {
        // ∫ D(h) cos θh dh = 1: the microfacets project onto the macro surface exactly (Heitz 2014).
        for alpha in [0.1, 0.4, 1.0] {
            let g = Ggx::new(alpha);
            let (mean, err) = integrate_sphere(400_000, 1, |h| g.d(h) * h.z.max(0.0));
            assert!((mean - 1.0).abs() < 5.0 * err + 1e-3, "alpha {alpha}: {mean} ± {err}");
        }
    }

    #[test]
    fn visible_normals_are_normalised() {
        // ∫ D_w(h) dh = 1 for every w (Heitz 2018), including near grazing.
        for alpha in [0.2, 0.7] {
            let g = Ggx::new(alpha);
            for theta in [0.0f64, 1.0, 1.45] {
                let w = Vec3::new(theta.sin(), 0.0, theta.cos());
                let (mean, err) = integrate_sphere(400_000, 2, |h| g.visible_normal_pdf(w, h));
                assert!((mean - 1.0).abs() < 5.0 * err + 1e-3, "alpha {alpha} θ {theta}: {mean} ± {err}");
            }
        }
    }

    #[test]
    fn sampled_normals_are_visible_and_unit() {
        let g = Ggx::new(0.5);
        let mut rng = Rng::new(9);
        let w = Vec3::new(0.8, 0.1, 0.2).normalize();
        for _ in 0..10_000 {
            let h = g.sample_visible_normal(w, rng.next_2d());
            assert!((h.length() - 1.0).abs() < 1e-9 && h.z >= 0.0 && w.dot(h) >= -1e-9, "{h}");
        }
    }

    #[test]
    fn masking_limits() {
        let g = Ggx::new(0.3);
        assert_eq!(g.g1(Vec3::Z), 1.0, "no masking at normal incidence");
        assert_eq!(g.g1(Vec3::X), 0.0, "full masking at grazing");
        let (a, b) = (Vec3::new(0.3, 0.2, 0.9).normalize(), Vec3::new(-0.6, 0.1, 0.4).normalize());
        assert!((g.g(a, b) - g.g(b, a)).abs() < 1e-15);
        assert!(g.g(a, b) <= g.g1(a).min(g.g1(b)));
    }
}

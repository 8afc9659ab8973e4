//! # Dielectric (`type = "dielectric"`)
//!
//! A smooth interface between two dielectrics — glass, water, a diamond: light is either reflected at the
//! mirror angle or refracted by Snell's law, `η_o sin θo = η_i sin θi`, with the exact unpolarised Fresnel
//! reflectance `F` deciding how much goes each way. Beyond the critical angle (inside the denser medium)
//! everything is reflected: total internal reflection.
//!
//! | parameter       | type              | default | meaning                                                  |
//! |-----------------|-------------------|---------|----------------------------------------------------------|
//! | `ior`           | number            | 1.5     | index of refraction inside over outside, `η`; 1.33 water |
//! | `transmittance` | colour or texture | 1.0     | tint of refracted light (coloured glass), `[0, 1]`       |
//!
//! ```toml
//! [objects.material]
//! type = "dielectric"
//! ior = 1.5
//! ```
//!
//! ## Sides
//! "Outside" is the side the shading normal points to (`z > 0`); a `wo` with `wo.z < 0` is inside the
//! medium, where the relative index seen by the light is `1/η`. Shapes must therefore be closed and their
//! normals point out of the glass (a glass sphere around a black hole: normals away from the centre).
//!
//! ## Sampling
//! Both lobes are deltas. [`Bsdf::sample`](super::Bsdf::sample) picks reflection with probability
//! `F(cos θo)` and refraction with `1 − F` (as pbrt-v4's `DielectricBxDF` does), so the Fresnel factor
//! cancels and the weight is `1` for reflection and `transmittance / η_rel²` for refraction; the returned
//! `pdf` is that discrete probability.
//!
//! ## Radiance scaling across refraction
//! Radiance is not invariant across a refracting interface: the same flux is squeezed into a solid angle
//! `η²` times smaller on the denser side, so `L/η²` is what is conserved (Veach 1997, thesis §5.2,
//! "Non-symmetric scattering due to refraction"). nullpath traces from the camera (radiance transport,
//! not importance), so the refraction weight includes the factor `1/η_rel²` with
//! `η_rel = n(side of wi) / n(side of wo)`, reported as [`BsdfSample::eta`]: a camera ray entering glass
//! (`η_rel = 1.5`) carries back `1/2.25` of the radiance inside. A path that enters and leaves a closed
//! object gets `η²·(1/η²) = 1`. Integrators that use the weight for Russian roulette should divide the
//! factor back out (multiply the throughput by `η_rel²`), as pbrt-v4's `etaScale` does.

use super::fresnel;
use super::mirror::reflect_z;
use super::BsdfSample;
use crate::geometry::Vec3;
use crate::spectrum::Colour;

/// Refraction of `w` (pointing away from the interface, either side) through the interface with normal
/// `+z` and relative index `eta` (inside over outside): the transmitted direction (pointing away on the
/// other side) and the relative index `n(transmitted side) / n(side of w)`; `None` under total internal
/// reflection. pbrt-v4 `Refract`: `wt = −w/η + (cos θi/η − cos θt)·n`.
pub fn refract(w: Vec3, eta: f64) -> Option<(Vec3, f64)> {
    let (cos_i, eta, nz) = if w.z < 0.0 { (-w.z, 1.0 / eta, -1.0) } else { (w.z, eta, 1.0) };
    let sin2_i = (1.0 - cos_i * cos_i).max(0.0);
    let sin2_t = sin2_i / (eta * eta);
    if sin2_t >= 1.0 {
        return None;
    }
    let cos_t = (1.0 - sin2_t).sqrt();
    let wt = -w / eta + Vec3::new(0.0, 0.0, (cos_i / eta - cos_t) * nz);
    Some((wt, eta))
}

pub(super) fn sample<C: Colour>(eta: f64, transmittance: C, wo: Vec3, uc: f64) -> Option<BsdfSample<C>> {
    if wo.z == 0.0 {
        return None;
    }
    let r = fresnel::dielectric(wo.z, eta);
    if uc < r {
        // Reflection with probability F: weight F / F = 1.
        return Some(BsdfSample::delta(reflect_z(wo), C::ONE, r, 1.0));
    }
    match refract(wo, eta) {
        // Refraction with probability 1 − F: weight (1 − F) / (1 − F) · T / η_rel².
        Some((wi, eta_rel)) => {
            let weight = transmittance * (1.0 / (eta_rel * eta_rel)) as f32;
            Some(BsdfSample::delta(wi, weight, 1.0 - r, eta_rel))
        }
        // Only reachable through rounding at the critical angle, where F = 1 to within it.
        None => Some(BsdfSample::delta(reflect_z(wo), C::ONE, 1.0, 1.0)),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::rgb::Rgb;

    #[test]
    fn snell_law_and_round_trip() {
        let eta = 1.5;
        let wo = Vec3::new(0.6, -0.2, 0.5).normalize();
        let (wt, eta_rel) = refract(wo, eta).unwrap();
        assert_eq!(eta_rel, eta);
        assert!((wt.length() - 1.0).abs() < 1e-12 && wt.z < 0.0);
        let sin_i = (1.0 - wo.z * wo.z).sqrt();
        let sin_t = (1.0 - wt.z * wt.z).sqrt();
        assert!((sin_i - eta * sin_t).abs() < 1e-12, "Snell");
        // The refracted ray lies in the plane of incidence, on the other side of the normal.
        assert!(wo.cross(Vec3::Z).dot(wt).abs() < 1e-12 && wt.x * wo.x < 0.0);
        // Coming back out retraces the path.
        let (back, eta_back) = refract(wt, eta).unwrap();
        assert!((back - wo).length() < 1e-12 && (eta_back - 1.0 / eta).abs() < 1e-15);
    }

    #[test]
    fn total_internal_reflection_from_inside() {
        let eta = 1.5;
        let sin_critical = 1.0 / eta;
        for (sin_i, tir) in [(sin_critical * 1.001, true), (sin_critical * 0.999, false)] {
            let wo = Vec3::new(sin_i, 0.0, -(1.0 - sin_i * sin_i).sqrt());
            assert_eq!(refract(wo, eta).is_none(), tir, "sin θ {sin_i}");
            // Beyond the critical angle every sample reflects, back inside, with weight 1.
            if tir {
                for uc in [0.0, 0.5, 0.999_999] {
                    let s = sample(eta, Rgb::ONE, wo, uc).unwrap();
                    assert!((s.wi - reflect_z(wo)).length() < 1e-15 && s.wi.z < 0.0);
                    assert_eq!((s.weight, s.pdf, s.eta), (Rgb::ONE, 1.0, 1.0));
                }
            }
        }
    }

    #[test]
    fn index_matched_interface_is_invisible() {
        let wo = Vec3::new(0.3, 0.4, 0.5).normalize();
        let s = sample(1.0, Rgb::ONE, wo, 0.5).unwrap();
        assert!((s.wi + wo).length() < 1e-12 && s.weight == Rgb::ONE && s.pdf == 1.0);
    }
}

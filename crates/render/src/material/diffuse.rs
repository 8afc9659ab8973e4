//! # Diffuse (`type = "diffuse"`)
//!
//! An ideal Lambertian reflector: light is scattered equally into every direction of the hemisphere,
//! `f = ρ / π`. Directions are sampled proportionally to `cos θ` (Malley's method), so every sample's
//! weight is exactly `ρ`.
//!
//! | parameter     | type              | default | meaning                                   |
//! |---------------|-------------------|---------|-------------------------------------------|
//! | `reflectance` | colour or texture | 0.5     | albedo `ρ` per channel, in `[0, 1]`       |
//!
//! ```toml
//! [objects.material]
//! type = "diffuse"
//! reflectance = [0.8, 0.8, 0.8]
//! # or a texture: reflectance = { type = "checker", a = [0.9, 0.9, 0.9], b = [0.1, 0.1, 0.1], uv_scale = [8, 8] }
//! ```
//!
//! Two-sided (see [`super`]); all functions here take `wo` in the upper hemisphere.

use super::BsdfSample;
use crate::geometry::Vec3;
use crate::sampling::{cosine_hemisphere, cosine_hemisphere_pdf};
use crate::spectrum::Colour;
use std::f64::consts::FRAC_1_PI;

pub(super) fn f<C: Colour>(reflectance: C, wi: Vec3) -> C {
    if wi.z <= 0.0 {
        return C::ZERO;
    }
    reflectance * FRAC_1_PI as f32
}

pub(super) fn pdf(wi: Vec3) -> f64 {
    cosine_hemisphere_pdf(wi.z)
}

pub(super) fn sample<C: Colour>(reflectance: C, u: [f64; 2]) -> Option<BsdfSample<C>> {
    let wi = cosine_hemisphere(u);
    let pdf = cosine_hemisphere_pdf(wi.z);
    // f·cos θ / pdf = (ρ/π)·cos θ / (cos θ/π) = ρ.
    (pdf > 0.0).then_some(BsdfSample::continuous(wi, reflectance, pdf))
}

//! # Rough conductor (`type = "conductor"`)
//!
//! A metal: a GGX microfacet reflector (Walter et al. 2007) whose colour comes from the conductor Fresnel
//! equations,
//!
//! ```text
//! f(wo, wi) = F(wo·h) · D(h) · G(wo, wi) / (4 cos θo cos θi),      h = normalize(wo + wi)
//! ```
//!
//! with `D` the GGX distribution, `G` the height-correlated Smith masking–shadowing (see
//! [`microfacet`](super::microfacet)) and `F` either exact with a complex index of refraction or Schlick's
//! approximation (see [`fresnel`](super::fresnel)). Single scattering only: light that would bounce
//! between microfacets before leaving is lost, so rough metals are darker than real ones — a white
//! conductor reflects 82–97 % at `alpha = 0.3` and 31–93 % at `alpha = 1` depending on the angle (the
//! deficit multiple-scattering models restore: Heitz et al. 2016; Kulla & Conty 2017).
//!
//! | parameter   | type          | default  | meaning                                                          |
//! |-------------|---------------|----------|------------------------------------------------------------------|
//! | `roughness` | number        | 0.1      | `[0, 1]`; GGX `alpha = roughness²`; `alpha < 1e-3` is a mirror   |
//! | `metal`     | string        | "silver" | preset: "gold", "silver", "copper", "aluminium"                  |
//! | `eta`, `k`  | colour        | —        | complex index of refraction per channel, instead of `metal`      |
//! | `f0`        | colour        | —        | Schlick normal-incidence colour, instead of `metal` or `eta`/`k` |
//!
//! ```toml
//! [objects.material]
//! type = "conductor"
//! metal = "gold"
//! roughness = 0.3
//! ```
//!
//! ## Sampling
//! Directions are sampled from the distribution of normals visible from `wo` (Heitz 2018), reflected
//! about the sampled normal; the weight is then `F(wo·h) · G(wo, wi) / G1(wo)` (Heitz 2018),
//! never above 1. A sample whose reflection points below the surface is rejected (`None`); that is the
//! energy the single-scattering model loses. With `alpha < 1e-3` the surface is a smooth delta
//! reflector with weight `F(cos θo)`.
//!
//! Two-sided (see [`super`]); all functions here take `wo` in the upper hemisphere.

use super::fresnel::ConductorFresnel;
use super::microfacet::{reflect, Ggx};
use super::mirror::reflect_z;
use super::BsdfSample;
use crate::geometry::Vec3;
use crate::spectrum::Colour;

pub(super) fn f<C: Colour>(ggx: Ggx, fresnel: &ConductorFresnel<C>, wo: Vec3, wi: Vec3) -> C {
    if ggx.is_smooth() || wo.z <= 0.0 || wi.z <= 0.0 {
        return C::ZERO;
    }
    let h = (wo + wi).normalize();
    let scalar = ggx.d(h) * ggx.g(wo, wi) / (4.0 * wo.z * wi.z);
    fresnel.eval(wo.dot(h)) * scalar as f32
}

pub(super) fn pdf(ggx: Ggx, wo: Vec3, wi: Vec3) -> f64 {
    if ggx.is_smooth() {
        return 0.0;
    }
    ggx.reflection_pdf(wo, wi)
}

pub(super) fn sample<C: Colour>(
    ggx: Ggx,
    fresnel: &ConductorFresnel<C>,
    wo: Vec3,
    u: [f64; 2],
) -> Option<BsdfSample<C>> {
    if wo.z <= 0.0 {
        return None;
    }
    if ggx.is_smooth() {
        return Some(BsdfSample::delta(reflect_z(wo), fresnel.eval(wo.z), 1.0, 1.0));
    }
    let h = ggx.sample_visible_normal(wo, u);
    let wi = reflect(wo, h);
    if wi.z <= 0.0 {
        return None;
    }
    let pdf = ggx.reflection_pdf(wo, wi);
    if pdf <= 0.0 {
        return None;
    }
    // f·cos θi / pdf = F·D·G/(4 cos θo cos θi) · cos θi · 4(wo·h) cos θo / (G1(wo)(wo·h) D) = F·G/G1(wo).
    let weight = fresnel.eval(wo.dot(h)) * (ggx.g(wo, wi) / ggx.g1(wo)) as f32;
    Some(BsdfSample::continuous(wi, weight, pdf))
}

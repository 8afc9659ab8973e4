//! Materials and their BSDFs.
//!
//! A [`Material`] is what a scene file describes: a kind of surface with textured colours. At a hit the
//! integrator resolves it, with the hit's texture coordinates, to a [`Bsdf`]: plain numbers, `Copy`, no
//! allocation, ready to evaluate and sample. One file per BSDF, each opening with its user documentation:
//!
//! | scene `type`   | [`Bsdf`] variant              | file                       | lobes                              |
//! |----------------|-------------------------------|----------------------------|------------------------------------|
//! | `"diffuse"`    | [`Bsdf::Diffuse`]             | [`diffuse`]                | Lambertian                         |
//! | `"mirror"`     | [`Bsdf::Mirror`]              | [`mirror`]                 | delta reflection                   |
//! | `"dielectric"` | [`Bsdf::Dielectric`]          | [`dielectric`]             | delta reflection + refraction      |
//! | `"conductor"`  | [`Bsdf::RoughConductor`]      | [`conductor`]              | GGX reflection (delta if smooth)   |
//! | `"plastic"`    | [`Bsdf::RoughPlastic`]        | [`plastic`]                | GGX coating + diffuse base         |
//!
//! plus the shared [`microfacet`] distribution and [`fresnel`] terms.
//!
//! # Conventions
//! - **Local shading frame.** Every direction a BSDF sees is in the local orthonormal frame of the
//!   observer at the hit (in curved spacetime, the static observer's tetrad; see the design notes), with
//!   `z` = the shading normal. `cos θ` of a direction is its `z`.
//! - **`wo`** is the direction toward the viewer — where the scattered light goes, i.e. the reverse of the
//!   traced ray's direction of travel — and **`wi`** the direction toward the light. Both are unit vectors
//!   pointing **away** from the surface.
//! - Directions with `z < 0` are below the surface: for `wi` that is transmission, for `wo` a view from
//!   the back or from inside a dielectric.
//! - **Opaque BSDFs are two-sided** (as in pbrt-v4): seen from below (`wo.z < 0`) they behave exactly as
//!   seen from above with both directions mirrored through the surface, and they never transmit. Only
//!   [`Bsdf::Dielectric`] distinguishes its sides (outside: `z > 0`, where the normal points).
//! - [`Bsdf::f`] is the BSDF value *without* the cosine factor; [`Bsdf::pdf`] is the solid-angle density
//!   with which [`Bsdf::sample`] produces `wi`; [`BsdfSample::weight`] is the throughput multiplier
//!   `f·|cos θi| / pdf`. Delta lobes (mirrors, smooth glass) have `f = pdf = 0` for every pair of
//!   directions and appear only through `sample`, with `is_delta = true`, `weight` the lobe's reflectance
//!   (or transmittance) divided by the probability of choosing it, and `pdf` that probability (not a
//!   density: never weigh it against light-sampling densities).
//! - Radiance is linear Rec. 709 RGB in `f32` ([`Rgb`]); geometry is `f64` ([`Vec3`]).
//! - Transport is traced from the camera (radiance, not importance): refraction weights include the
//!   `1/η²` radiance scaling, see [`dielectric`].

pub mod conductor;
pub mod dielectric;
pub mod diffuse;
pub mod dispersion;
pub mod fresnel;
pub mod microfacet;
pub mod mirror;
pub mod normal_map;
pub mod plastic;

#[cfg(test)]
mod chi2;
#[cfg(test)]
mod tests;

pub use dispersion::Dispersion;
pub use fresnel::ConductorFresnel;
pub use microfacet::roughness_to_alpha;
pub use normal_map::NormalMap;

use crate::geometry::Vec3;
use crate::rgb::Rgb;
use crate::shape::SurfaceHit;
use crate::spectrum::Colour;
use crate::texture::Texture;
use microfacet::Ggx;
use plastic::Plastic;

/// One sampled scattering direction.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BsdfSample<C: Colour = Rgb> {
    /// The sampled direction toward the light, unit, in the local frame.
    pub wi: Vec3,
    /// `f·|cos θi| / pdf`: what the path throughput is multiplied by.
    pub weight: C,
    /// Solid-angle density of `wi`; for a delta lobe, the discrete probability of having chosen it.
    pub pdf: f64,
    /// True when `wi` came from a delta lobe (mirror reflection, smooth refraction).
    pub is_delta: bool,
    /// Relative index of refraction crossed, `n(side of wi) / n(side of wo)`; 1 for reflection. The
    /// weight already includes the radiance scaling `1/eta²`; see [`dielectric`].
    pub eta: f64,
}

impl<C: Colour> BsdfSample<C> {
    /// A sample from a lobe with a density (reflection, no index crossed).
    pub fn continuous(wi: Vec3, weight: C, pdf: f64) -> Self {
        Self { wi, weight, pdf, is_delta: false, eta: 1.0 }
    }

    /// A sample from a delta lobe chosen with probability `pdf`.
    pub fn delta(wi: Vec3, weight: C, pdf: f64, eta: f64) -> Self {
        Self { wi, weight, pdf, is_delta: true, eta }
    }
}

/// A BSDF with its parameters resolved at one surface point, in the colours `C` a path carries.
/// See the module documentation for the conventions, and each variant's file for its model and
/// scene-file parameters.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Bsdf<C: Colour = Rgb> {
    /// Lambertian reflection, `f = reflectance/π`.
    Diffuse { reflectance: C },
    /// Perfect specular reflection with a constant reflectance.
    Mirror { reflectance: C },
    /// Smooth dielectric interface; `eta` = index inside / index outside; `transmittance` tints refraction.
    Dielectric { eta: f64, transmittance: C },
    /// GGX metal; `alpha` = GGX width (`roughness²`); below [`microfacet::SMOOTH_ALPHA`] a delta reflector.
    RoughConductor { alpha: f64, fresnel: ConductorFresnel<C> },
    /// Diffuse base `diffuse` under a GGX dielectric coating of width `alpha` and relative index `eta`.
    RoughPlastic { diffuse: C, alpha: f64, eta: f64 },
}

/// Mirror a direction through the surface plane.
#[inline]
fn flip(w: Vec3) -> Vec3 {
    Vec3::new(w.x, w.y, -w.z)
}

/// For two-sided opaque BSDFs: the pair of directions as seen from the upper side.
#[inline]
fn upper(wo: Vec3, wi: Vec3) -> (Vec3, Vec3) {
    if wo.z < 0.0 {
        (flip(wo), flip(wi))
    } else {
        (wo, wi)
    }
}

/// Two-sided opaque BSDFs sample as seen from the upper side and mirror the result back.
#[inline]
fn two_sided<C: Colour>(wo: Vec3, sample_upper: impl FnOnce(Vec3) -> Option<BsdfSample<C>>) -> Option<BsdfSample<C>> {
    if wo.z < 0.0 {
        sample_upper(flip(wo)).map(|s| BsdfSample { wi: flip(s.wi), ..s })
    } else {
        sample_upper(wo)
    }
}

impl<C: Colour> Bsdf<C> {
    /// The BSDF value for light arriving from `wi` and leaving toward `wo`, without the cosine factor.
    /// Zero for delta lobes.
    pub fn f(&self, wo: Vec3, wi: Vec3) -> C {
        let (wo, wi) = upper(wo, wi);
        match *self {
            Bsdf::Diffuse { reflectance } => diffuse::f(reflectance, wi),
            Bsdf::Mirror { .. } | Bsdf::Dielectric { .. } => C::ZERO,
            Bsdf::RoughConductor { alpha, fresnel } => conductor::f(Ggx::new(alpha), &fresnel, wo, wi),
            Bsdf::RoughPlastic { diffuse, alpha, eta } => plastic(diffuse, alpha, eta).f(wo, wi),
        }
    }

    /// The solid-angle density with which [`Bsdf::sample`] returns `wi` given `wo`. Zero for delta lobes.
    pub fn pdf(&self, wo: Vec3, wi: Vec3) -> f64 {
        let (wo, wi) = upper(wo, wi);
        match *self {
            Bsdf::Diffuse { .. } => diffuse::pdf(wi),
            Bsdf::Mirror { .. } | Bsdf::Dielectric { .. } => 0.0,
            Bsdf::RoughConductor { alpha, .. } => conductor::pdf(Ggx::new(alpha), wo, wi),
            Bsdf::RoughPlastic { diffuse, alpha, eta } => plastic(diffuse, alpha, eta).pdf(wo, wi),
        }
    }

    /// Samples a direction `wi` toward the light given `wo`, from the lobe-selection number `uc ∈ [0, 1)`
    /// and the direction numbers `u ∈ [0, 1)²`. `None` when the sample carries no energy (e.g. a
    /// microfacet reflection that points below the surface, or `wo` exactly in the surface plane).
    pub fn sample(&self, wo: Vec3, uc: f64, u: [f64; 2]) -> Option<BsdfSample<C>> {
        match *self {
            Bsdf::Dielectric { eta, transmittance } => dielectric::sample(eta, transmittance, wo, uc),
            Bsdf::Diffuse { reflectance } => two_sided(wo, |_| diffuse::sample(reflectance, u)),
            Bsdf::Mirror { reflectance } => two_sided(wo, |wo| mirror::sample(reflectance, wo)),
            Bsdf::RoughConductor { alpha, fresnel } => {
                two_sided(wo, |wo| conductor::sample(Ggx::new(alpha), &fresnel, wo, u))
            }
            Bsdf::RoughPlastic { diffuse, alpha, eta } => {
                two_sided(wo, |wo| plastic(diffuse, alpha, eta).sample(wo, uc, u))
            }
        }
    }

    /// True when every lobe is a delta: `f` and `pdf` are zero everywhere and light sampling is useless.
    pub fn is_delta(&self) -> bool {
        match *self {
            Bsdf::Diffuse { .. } | Bsdf::RoughPlastic { .. } => false,
            Bsdf::Mirror { .. } | Bsdf::Dielectric { .. } => true,
            Bsdf::RoughConductor { alpha, .. } => Ggx::new(alpha).is_smooth(),
        }
    }

    /// True when the BSDF can send light through the surface (`wi` on the other side from `wo`).
    pub fn has_transmission(&self) -> bool {
        matches!(self, Bsdf::Dielectric { .. })
    }
}

fn plastic<C: Colour>(diffuse: C, alpha: f64, eta: f64) -> Plastic<C> {
    Plastic { diffuse, ggx: Ggx::new(alpha), eta }
}

/// A surface description from the scene: the BSDF model with its colours as textures, resolved per hit
/// by [`Material::bsdf`]. Roughness and indices of refraction are per material, not textured.
#[derive(Clone, Debug)]
pub enum Material {
    /// See [`diffuse`].
    Diffuse { reflectance: Texture },
    /// See [`mirror`].
    Mirror { reflectance: Texture },
    /// See [`dielectric`]. `ior` is the index inside relative to outside (at the d line when
    /// the glass disperses light: see [`dispersion`]).
    Dielectric { ior: f64, dispersion: Option<Dispersion>, transmittance: Texture },
    /// See [`conductor`]. `roughness ∈ [0, 1]`, `alpha = roughness²`.
    RoughConductor { roughness: f64, fresnel: ConductorFresnel },
    /// See [`plastic`]. `roughness ∈ [0, 1]`, `alpha = roughness²`; `ior ≥ 1` of the coating.
    RoughPlastic { diffuse: Texture, roughness: f64, ior: f64 },
    /// `base` with its shading normal bent by a [`normal_map`].
    NormalMapped { base: Box<Material>, map: NormalMap },
}

impl Material {
    /// The RGB BSDF at a surface point with texture coordinates `uv` and position `p`: see
    /// [`Material::resolve`].
    pub fn bsdf(&self, uv: [f64; 2], p: Vec3) -> Bsdf {
        self.resolve::<Rgb>(uv, p, &mut ())
    }

    /// The BSDF at a surface point with texture coordinates `uv` and position `p` (in the region's
    /// world coordinates, for solid textures), in the colours `C` a path carries at `lambda`.
    /// Colours are clamped to `[0, 1]` so that no texture can make a surface create energy. A
    /// dispersing glass refracts at the hero wavelength, which alone is carried on from here.
    pub fn resolve<C: Colour>(&self, uv: [f64; 2], p: Vec3, lambda: &mut C::Lambda) -> Bsdf<C> {
        let albedo = |t: &Texture, lambda: &C::Lambda| match t {
            Texture::Constant(c) => C::lifted_reflectance(c, lambda),
            Texture::Checker { .. } | Texture::Grid { .. } | Texture::Image { .. } | Texture::Earth(_) => {
                C::reflectance(t.eval(uv, p).clamp(Rgb::ZERO, Rgb::ONE), lambda)
            }
        };
        match self {
            Material::Diffuse { reflectance } => Bsdf::Diffuse { reflectance: albedo(reflectance, lambda) },
            Material::Mirror { reflectance } => Bsdf::Mirror { reflectance: albedo(reflectance, lambda) },
            Material::Dielectric { ior, dispersion, transmittance } => {
                let eta = match (dispersion, C::hero(lambda)) {
                    (Some(dispersion), Some(hero)) => {
                        C::keep_hero(lambda);
                        dispersion.ior(hero)
                    }
                    _ => *ior,
                };
                Bsdf::Dielectric { eta, transmittance: albedo(transmittance, lambda) }
            }
            Material::RoughConductor { roughness, fresnel } => {
                Bsdf::RoughConductor { alpha: roughness_to_alpha(*roughness), fresnel: fresnel.lift::<C>(lambda) }
            }
            Material::RoughPlastic { diffuse, roughness, ior } => Bsdf::RoughPlastic {
                diffuse: albedo(diffuse, lambda),
                alpha: roughness_to_alpha(*roughness),
                eta: *ior,
            },
            Material::NormalMapped { base, .. } => base.resolve(uv, p, lambda),
        }
    }

    /// The shading normal of `hit` on this material: the surface's own, or bent by a normal map.
    pub fn shading_normal(&self, hit: &SurfaceHit) -> Vec3 {
        match self {
            Material::Diffuse { .. }
            | Material::Mirror { .. }
            | Material::Dielectric { .. }
            | Material::RoughConductor { .. }
            | Material::RoughPlastic { .. } => hit.ns,
            Material::NormalMapped { map, .. } => map.shading_normal(hit),
        }
    }

    /// Checks the numbers a scene file supplied, so that [`Material::bsdf`] never sees a NaN-making value.
    /// The message names the offending parameter.
    pub fn validate(&self) -> Result<(), String> {
        let roughness_ok = |r: f64| {
            if (0.0..=1.0).contains(&r) {
                Ok(())
            } else {
                Err(format!("roughness {r} must lie in [0, 1]"))
            }
        };
        match self {
            Material::Diffuse { reflectance } | Material::Mirror { reflectance } => reflectance.validate(),
            Material::Dielectric { ior, transmittance, .. } => {
                transmittance.validate()?;
                if ior.is_finite() && *ior > 0.0 {
                    Ok(())
                } else {
                    Err(format!("ior {ior} must be a positive number"))
                }
            }
            Material::RoughConductor { roughness, fresnel } => {
                roughness_ok(*roughness)?;
                fresnel.validate()
            }
            Material::RoughPlastic { diffuse, roughness, ior } => {
                diffuse.validate()?;
                roughness_ok(*roughness)?;
                if ior.is_finite() && *ior >= 1.0 {
                    Ok(())
                } else {
                    Err(format!("ior {ior} of a plastic coating must be a number ≥ 1"))
                }
            }
            Material::NormalMapped { base, map } => {
                base.validate()?;
                map.validate()
            }
        }
    }
}

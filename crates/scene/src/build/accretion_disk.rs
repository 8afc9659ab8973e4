//! `[accretion_disk]`: a thin Novikov–Thorne disk about the hole, from its innermost stable
//! circular orbit to `outer_radius`, in the hole's equatorial plane (perpendicular to a spinning
//! hole's `axis`; about a hole without spin, perpendicular to `normal`).

use super::Builder;
use crate::reader::{num, Node, Result};
use render::emission::{DiskLight, Emission, Profile, Radiance};
use render::geometry::Vec3;
use render::material::Material;
use render::rgb::Rgb;
use render::shape::Shape;
use render::texture::Texture;
use render::transform::Transform;
use render::world::Object;
use spacetime::disk::ThinDisk;
use spacetime::Spacetime;
use std::sync::Arc;

pub(super) const KEYS: &[&str] = &["outer_radius", "temperature", "luminance", "normal", "texture"];

/// The hottest ring's temperature, K, unless the file says: a white-blue disk.
const DEFAULT_TEMPERATURE: f64 = 10_000.0;

impl Builder<'_> {
    /// The disk as an object of the upper region: an annulus that absorbs what falls on it
    /// (optically thick gas) and emits its blackbody light from both faces.
    pub(super) fn accretion_disk(&mut self, n: &Node<'_>, spacetime: &Spacetime, axis: Vec3) -> Result<Object> {
        let t = n.table(KEYS)?;
        let Some(orbits) = spacetime.capabilities().circular_orbits() else {
            return Err(n.err(format!(
                "an accretion disk orbits a black hole (schwarzschild, kerr, reissner-nordstrom or kerr-newman \
                 with mass > 0); this spacetime ({}) has no orbits for one",
                spacetime.name()
            )));
        };
        let spinning = !spacetime.capabilities().is_spherically_symmetric();
        let normal = match t.opt("normal", |n| n.direction())? {
            Some(_) if spinning => {
                return Err(t.loc("normal").err(
                    "a disk about a spinning hole lies in its equatorial plane: its normal is the spacetime's axis",
                ))
            }
            Some(normal) => normal.normalize(),
            None => axis.normalize(),
        };
        let outer = t.req("outer_radius", |n| n.f64())?;
        let isco = orbits.isco();
        if !(outer > isco) {
            return Err(t.loc("outer_radius").err(format!(
                "must lie beyond the innermost stable circular orbit, r = {} (the disk's inner edge)",
                num(isco)
            )));
        }
        let temperature = t.or("temperature", DEFAULT_TEMPERATURE, |n| n.f64())?;
        let luminance = t.or("luminance", 1.0, |n| n.f64())?;
        let light = DiskLight::new(ThinDisk::new(orbits, outer), normal, temperature, luminance)
            .ok_or_else(|| t.loc("temperature").err("the temperature must be at least 100 K and the luminance ≥ 0"))?;
        if !(luminance >= 0.0 && luminance.is_finite()) {
            return Err(t.loc("luminance").err(format!("must be ≥ 0, got {}", num(luminance))));
        }
        let light = match t.get("texture") {
            Some(n) => {
                let texture = self.texture(&n)?;
                texture.validate().map_err(|e| n.err(e))?;
                light.with_texture(texture)
            }
            None => light,
        };
        let (inner_world, outer_world) = light.world_radii();
        let shape = Shape::annulus(Vec3::ZERO, normal, inner_world, outer_world, &Transform::identity())
            .map_err(|e| n.err(e.to_string()))?;
        self.materials.push(Material::Diffuse { reflectance: Texture::from(Rgb::ZERO) });
        let emission =
            Emission { radiance: Radiance::Disk(Arc::new(light)), two_sided: true, profile: Profile::Uniform };
        Ok(Object { shape, material: self.materials.len() - 1, emission: Some(emission) })
    }
}

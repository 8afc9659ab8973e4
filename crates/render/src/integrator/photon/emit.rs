//! Photons leaving the area lights of both regions, with the power they carry.
//!
//! A photon starts at a point chosen uniformly by world area on an emitter, itself chosen first
//! by region (see [`RegionSplit`]), then by power within the region (the [`World`]'s CDF), and
//! leaves in a
//! cosine-distributed direction about the emitter's normal in the static observer's local frame.
//! Its power is the emitted flux over the density of that choice (pbrt-v3 §16.2.4):
//! `Φ = Le |cos θ| / (p_light · p_A · p_ω)` (`= Le · π · A · s / p_light` for cosine-distributed
//! directions), where the area density is per proper area: `p_A = 1 / (A · s)` with `s` the
//! proper area per world area at the point.
//!
//! [`aim`]: super::aim

use super::super::path::leave;
use super::aim::{self, Target};
use crate::color::Rgb;
use crate::geometry::Vec3;
use crate::propagator::Propagator;
use crate::sampling::Rng;
use crate::world::World;
use spacetime::Region;

/// A photon about to be traced.
#[derive(Clone, Copy, Debug)]
pub(super) struct Photon {
    pub region: Region,
    /// World position, just off the emitter.
    pub origin: Vec3,
    /// Direction of travel in the local static frame.
    pub direction: Vec3,
    /// Power measured by the static observer at `origin`.
    pub power: Rgb,
}

/// Probabilities of starting a photon in the upper and the lower region.
///
/// Photons mostly stay in the region they start in (crossing needs a throat), and are wasted
/// where no camera path looks; by power alone, a sun in one region would starve a lamp-lit room
/// in the other that fills the view. So half the photons are shared by power and half by the
/// regions' shares of visible points, among the regions with emitters. Any split that gives every
/// lit region a nonzero probability is unbiased: the photon's power is divided by it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) struct RegionSplit {
    upper: f64,
}

impl RegionSplit {
    /// The split for `visible` visible points in (upper, lower); `None` without emitters.
    pub fn new(world: &World, visible: [usize; 2]) -> Option<Self> {
        let power = [world.light_power(Region::Upper), world.light_power(Region::Lower)];
        let total = power[0] + power[1];
        if !(total > 0.0) {
            return None;
        }
        let lit_visible = |k: usize| if power[k] > 0.0 { visible[k] as f64 } else { 0.0 };
        let seen = lit_visible(0) + lit_visible(1);
        let by_view = if seen > 0.0 { lit_visible(0) / seen } else { power[0] / total };
        Some(Self { upper: 0.5 * (power[0] / total + by_view) })
    }

    fn choose(&self, u: f64) -> (Region, f64) {
        if u < self.upper {
            (Region::Upper, self.upper)
        } else {
            (Region::Lower, 1.0 - self.upper)
        }
    }
}

/// Samples a photon from the lights, aimed at the receivers of its region (`targets`, upper
/// and lower; see [`aim`]); `None` when it leaves the back of a one-sided emitter.
///
/// [`aim`]: super::aim
pub(super) fn emit(
    world: &World,
    propagator: &Propagator,
    (split, targets): (RegionSplit, &[Option<Target>; 2]),
    rng: &mut Rng,
) -> Option<Photon> {
    let (region, p_region) = split.choose(rng.next_f64());
    let choice = world.choose_light(region, rng.next_f64())?;
    let light = world.object(region, choice.object);
    let emission = light.emission?;
    let (point, normal) = light.shape.sample_area(rng.next_2d());
    let local_normal = propagator.local_normal(region, point, normal);
    let target = targets[usize::from(region == Region::Lower)];
    let numbers = (rng.next_f64(), rng.next_f64(), rng.next_2d());
    let aimed = aim::sample(point, local_normal, emission.two_sided, target, numbers);
    let cos = aimed.direction.dot(local_normal);
    if !(emission.two_sided || cos > 0.0) || !(aimed.pdf > 0.0) {
        return None;
    }
    let area = light.shape.area() * propagator.area_scale(point, normal);
    let scale = cos.abs() * area / (aimed.pdf * p_region * choice.probability);
    Some(Photon {
        region,
        origin: leave(point, normal, local_normal, aimed.direction),
        direction: aimed.direction,
        power: emission.radiance * scale as f32,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::material::Material;
    use crate::shape::Shape;
    use crate::sky::Sky;
    use crate::texture::Texture;
    use crate::transform::Transform;
    use crate::world::{Emission, Object};

    #[test]
    fn regions_share_photons_by_power_and_by_view() {
        let lamp = |r: f32| Object {
            shape: Shape::sphere(Vec3::ZERO, 1.0, &Transform::identity()).unwrap(),
            material: 0,
            emission: Some(Emission { radiance: Rgb::splat(r), two_sided: false }),
        };
        let black = || Sky::Constant(Rgb::ZERO);
        let materials = vec![Material::Diffuse { reflectance: Texture::Constant(Rgb::ONE) }];
        let world = World::new(materials.clone(), (vec![lamp(3.0)], black()), (vec![lamp(1.0)], black()));
        // Power ¾ : ¼; visible points 1 : 3.
        let split = RegionSplit::new(&world, [10, 30]).unwrap();
        assert!((split.upper - 0.5).abs() < 1e-12);
        // Visible points where there is no light do not count: by power alone then.
        let dark_lower = World::new(materials, (vec![lamp(3.0)], black()), (Vec::new(), black()));
        assert_eq!(RegionSplit::new(&dark_lower, [0, 30]).unwrap().choose(0.999), (Region::Upper, 1.0));
    }
}

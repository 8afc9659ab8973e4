//! Photons leaving the lights of both regions — area lights and skies — with the power they carry.
//!
//! A photon starts in a region chosen first (see [`RegionSplit`]), then at its sky or its area
//! lights (mostly by power, see [`MIN_SHARE`]); for area lights, at an emitter chosen by power
//! within the region (the [`World`]'s CDF), at a point chosen uniformly by world area on it,
//! leaving in a direction drawn about the emitter's normal in the static observer's local frame
//! (see [`aim`]).
//! Its power is the emitted flux over the density of that choice (pbrt-v3 §16.2.4):
//! `Φ = Le |cos θ| / (p_light · p_A · p_ω)` (`= Le · π · A · s / p_light` for cosine-distributed
//! directions), where the area density is per proper area: `p_A = 1 / (A · s)` with `s` the
//! proper area per world area at the point. Skies emit as [`sky`] describes.
//!
//! [`aim`]: super::aim
//! [`sky`]: super::sky

use super::super::path::leave;
use super::aim::{self, Target};
use super::sky::SkySource;
use super::slot;
use crate::emission::{EmittedBlackbody, Seen, Shift};
use crate::geometry::Vec3;
use crate::propagator::Propagator;
use crate::rgb::Rgb;
use crate::sampling::Rng;
use crate::world::World;
use spacetime::{Region, Spacetime};

/// A photon about to be traced.
#[derive(Clone, Copy, Debug)]
pub(super) struct Photon {
    pub region: Region,
    /// World position, just off the emitter.
    pub origin: Vec3,
    /// Direction of travel in the local static frame.
    pub direction: Vec3,
    /// Power measured by the static observer at `origin`; for a blackbody's light
    /// (`blackbody`), what its colour where it is seen is multiplied by.
    pub power: Rgb,
    /// The emitter's blackbody, whose colour depends on where the photon is seen (photons carry
    /// power, not a spectrum); `None` for light of one colour.
    pub blackbody: Option<EmittedBlackbody>,
    /// `ν_here / ν_emitted`: the photon's frequency over its emitter's local observer's.
    pub frequency: f64,
}

/// What photons leave from in each region (upper, lower): its area lights, aimed at its
/// receivers, and its sky where photons carry it.
#[derive(Clone, Debug)]
pub(super) struct Sources {
    targets: [Option<Target>; 2],
    skies: [Option<SkySource>; 2],
}

impl Sources {
    pub fn new(world: &World, spacetime: &Spacetime, propagator: &Propagator) -> Self {
        let targets = aim::targets(world, spacetime);
        let skies = [Region::Upper, Region::Lower]
            .map(|region| SkySource::new(world.sky(region), targets[slot(region)], propagator));
        Self { targets, skies }
    }

    /// Whether photons carry the light of `region`'s sky (they do unless it is black or its
    /// receivers are unbounded).
    pub fn carry_sky(&self, region: Region) -> bool {
        self.skies[slot(region)].is_some()
    }

    /// The powers of `region`'s area lights and of its sky, in the units of
    /// [`World::light_power`].
    fn powers(&self, world: &World, region: Region) -> (f64, f64) {
        (world.light_power(region), self.skies[slot(region)].as_ref().map_or(0.0, SkySource::power))
    }

    /// Probability that a photon of `region` leaves its sky rather than its area lights: by
    /// power, but at least [`MIN_SHARE`] for each where the region has both (see there).
    fn sky_probability(&self, world: &World, region: Region) -> f64 {
        match self.powers(world, region) {
            (_, 0.0) => 0.0,
            (0.0, _) => 1.0,
            (lights, sky) => MIN_SHARE + (1.0 - 2.0 * MIN_SHARE) * sky / (lights + sky),
        }
    }
}

/// The least share of a region's photons for its sky and for its lights when it has both. By
/// power alone a sun starves the sky, which is all the light on the earth's night side: with
/// a thousandth of the photons it shows as blotches (`scenes/wormhole-room-space.toml`). A tenth
/// costs the sunlit side little, while larger shares spend photons on sky light that mostly
/// starts far out and misses (measurements in `docs/perf-journal.md`, "Photon shares of sky and
/// lights"). Any share is unbiased: the photon's power is divided by it.
const MIN_SHARE: f64 = 0.1;

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
    pub fn new(world: &World, sources: &Sources, visible: [usize; 2]) -> Option<Self> {
        let power = [Region::Upper, Region::Lower].map(|region| {
            let (lights, sky) = sources.powers(world, region);
            lights + sky
        });
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

/// Samples a photon from the sources; `None` when it leaves the back of a one-sided emitter or
/// comes from a black part of a sky.
pub(super) fn emit(
    world: &World,
    propagator: &Propagator,
    (split, sources): (RegionSplit, &Sources),
    rng: &mut Rng,
) -> Option<Photon> {
    let (region, p_region) = split.choose(rng.next_f64());
    let p_sky = sources.sky_probability(world, region);
    if rng.next_f64() < p_sky {
        let sky = sources.skies[slot(region)].as_ref()?;
        let photon = sky.emit(region, propagator, rng)?;
        let p_source = p_region * p_sky;
        return Some(Photon { power: photon.power / p_source as f32, ..photon });
    }
    let choice = world.choose_light(region, rng.next_f64())?;
    let light = world.object(region, choice.object);
    let emission = light.emission.as_ref()?;
    let (point, normal) = light.shape.sample_area(rng.next_2d());
    let local_normal = propagator.local_normal(region, point, normal);
    let target = sources.targets[slot(region)];
    let numbers = (rng.next_f64(), rng.next_f64(), rng.next_2d());
    let aimed = aim::sample(point, local_normal, emission.two_sided, target, numbers);
    let cos = aimed.direction.dot(local_normal);
    if !(emission.two_sided || cos > 0.0) || !(aimed.pdf > 0.0) {
        return None;
    }
    let area = light.shape.area() * propagator.area_scale(region, point, normal);
    let p_source = p_region * (1.0 - p_sky);
    let scale = cos.abs() * area / (aimed.pdf * p_source * choice.probability);
    let seen = Seen { region, point, shift: Shift::NONE, propagator };
    let blackbody = emission.blackbody(local_normal, aimed.direction, &seen);
    let colour = match blackbody {
        Some(_) => Rgb::ONE,
        None => emission.seen::<Rgb>(local_normal, aimed.direction, &seen, &()),
    };
    Some(Photon {
        region,
        origin: leave(point, normal, local_normal, aimed.direction),
        direction: aimed.direction,
        power: colour * scale as f32,
        blackbody,
        frequency: 1.0,
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
            emission: Some(Emission::uniform(Rgb::splat(r), false)),
        };
        let black = || Sky::Constant(Rgb::ZERO);
        let materials = vec![Material::Diffuse { reflectance: Texture::from(Rgb::ONE) }];
        let flat = Spacetime::Minkowski(spacetime::Minkowski);
        let propagator = Propagator::new(flat.clone(), 1.0, 1e-7, crate::settings::Intersection::Chord);
        let split = |world: &World, visible| {
            RegionSplit::new(world, &Sources::new(world, &flat, &propagator), visible).unwrap()
        };
        let world = World::new(materials.clone(), (vec![lamp(3.0)], black()), (vec![lamp(1.0)], black()));
        // Power ¾ : ¼; visible points 1 : 3.
        assert!((split(&world, [10, 30]).upper - 0.5).abs() < 1e-12);
        // Visible points where there is no light do not count: by power alone then.
        let dark_lower = World::new(materials, (vec![lamp(3.0)], black()), (Vec::new(), black()));
        assert_eq!(split(&dark_lower, [0, 30]).choose(0.999), (Region::Upper, 1.0));
    }
}

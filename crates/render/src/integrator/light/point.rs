//! A point sampled on a light, and the solid-angle density a light ray to it has.

use super::Lit;
use crate::emission::{Seen, Shift};
use crate::geometry::Vec3;
use crate::integrator::path::leave;
use crate::integrator::stats::PathStats;
use crate::propagator::{Arrival, RayEnd};
use crate::spectrum::Colour;
use crate::world::{Emission, World};
use spacetime::Region;

/// A traced light ray counts as reaching its light point when it hits the light within this
/// many chord tolerances ε of it (the chord test places hits to within ~ε of the curve, and a
/// connection passes within ~ε of its point).
const ARRIVAL_TOLERANCE: f64 = 64.0;

/// A point sampled on a light.
pub(super) struct LightPoint<'w> {
    pub object: usize,
    pub region: spacetime::Region,
    pub point: Vec3,
    /// World unit normal.
    pub normal: Vec3,
    pub emission: &'w Emission,
    /// Probability of the light's choice.
    pub probability: f64,
    /// The light's world area (points are sampled uniformly in it).
    pub area: f64,
}

impl LightPoint<'_> {
    /// The point's area density: the light's probability over its world area.
    pub fn density(&self) -> f64 {
        self.probability / self.area
    }

    /// The radiance leaving the point in local direction `dir` (surface normal `normal` in
    /// the local frame), seen with frequency ratio `shift`, in the colours `C` at `lambda`.
    pub fn seen<C: Colour>(&self, normal: Vec3, dir: Vec3, shift: Shift, lit: Lit<'_>, lambda: &C::Lambda) -> C {
        let seen = Seen { region: self.region, point: self.point, shift, propagator: lit.propagator };
        self.emission.seen(normal, dir, &seen, lambda)
    }
}

/// Which lights a shading point samples.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) enum Reach {
    /// Those of its own region.
    OwnRegion,
    /// Those of both regions of a wormhole whose throat, of world radius `radius` about the
    /// world origin of each region, passes light between them, for a shading point at world
    /// point `from` of its own region.
    ThroughThroat { radius: f64, from: Vec3 },
}

/// The least probability of either region's lights where both have lights and light reaches a
/// point through a throat: the split below is a rough estimate, blind to occlusion and lensing,
/// and the floor keeps both strategies in the MIS mix (Hesterberg's defensive mixture), so a
/// bright light the estimate underrates is still sampled now and then rather than found only by
/// BSDF sampling, as fireflies.
const DEFENSIVE_REGION_PROBABILITY: f64 = 0.05;

/// The probability that a shading point of region `from` samples a light of region `to`.
/// Through a throat, each region is chosen in proportion to a rough estimate of the irradiance
/// its lights give the point ([`World::irradiance_estimate`]): the other region's is the
/// irradiance they give the throat's mouth, times the mouth's cross-section `π b²`, spread
/// evenly over the sphere about the mouth through the point, `E_mouth · b² / (4 |x|²)`.
fn region_probability(world: &World, from: Region, to: Region, reach: Reach) -> f64 {
    let own = match reach {
        Reach::OwnRegion => 1.0,
        Reach::ThroughThroat { .. } if world.light_count(from) == 0 => 0.0,
        Reach::ThroughThroat { .. } if world.light_count(from.other()) == 0 => 1.0,
        Reach::ThroughThroat { radius, from: x } => {
            let own = world.irradiance_estimate(from, x);
            let mouth = world.irradiance_estimate(from.other(), Vec3::ZERO);
            let through = mouth * radius * radius / (4.0 * x.length_squared().max(radius * radius));
            let p = DEFENSIVE_REGION_PROBABILITY;
            (own / (own + through)).clamp(p, 1.0 - p)
        }
    };
    if to == from {
        own
    } else {
        1.0 - own
    }
}

/// Samples a light for the shading point of `at`, in its region or as `reach` says
/// (`u_choice` picks the region and the light, `u_point` the point).
pub(super) fn sample_point<'w>(
    world: &'w World,
    at: &Arrival,
    reach: Reach,
    u_choice: f64,
    u_point: [f64; 2],
) -> Option<LightPoint<'w>> {
    let own = region_probability(world, at.region, at.region, reach);
    let (region, p_region, u_light) = if u_choice < own {
        (at.region, own, u_choice / own)
    } else {
        (at.region.other(), 1.0 - own, (u_choice - own) / (1.0 - own))
    };
    let choice = world.choose_light(region, u_light)?;
    let light = world.object(region, choice.object);
    let emission = light.emission.as_ref()?;
    let (point, normal) = light.shape.sample_area(u_point);
    let (probability, area) = (p_region * choice.probability, light.shape.area());
    Some(LightPoint { object: choice.object, region, point, normal, emission, probability, area })
}

/// The probability with which [`sample_point`] at a shading point of region `from` chooses the
/// emitter `arrival` reached, and its world area: `None` where the emitter is not sampled.
pub(super) fn choice(world: &World, from: Region, reach: Reach, arrival: &Arrival) -> Option<(f64, f64)> {
    let probability = region_probability(world, from, arrival.region, reach)
        * world.light_probability(arrival.region, arrival.object);
    (probability > 0.0).then(|| (probability, world.object(arrival.region, arrival.object).shape.area()))
}

/// `p_ω = p_A / (|n · t| dΩ/dA⊥)`: the solid-angle density at the start of a light ray that
/// reaches a surface of world normal `normal` along world tangent `tangent`, with bundle factor
/// `dΩ/dA⊥` (solid angle at the start per world area across the beam), for area density `p_A`.
pub(super) fn solid_angle_density(area_density: f64, normal: Vec3, tangent: Vec3, solid_angle_per_area: f64) -> f64 {
    area_density / (normal.dot(tangent).abs() * solid_angle_per_area)
}

/// Whether the light ray leaving the shading point of `at` (local geometric normal `ng_local`)
/// along local direction `wi` reaches the point `point` of light `object`, traced against the
/// scene as any ray is: the photon's energy there relative to here, `E_y/E_x`, if so, else
/// `None`.
pub(super) fn traced_arrival(
    lit: Lit<'_>,
    at: &Arrival,
    ng_local: Vec3,
    wi: Vec3,
    light: &LightPoint<'_>,
    stats: &mut PathStats,
) -> Option<f64> {
    let origin = leave(at.hit.p, at.hit.ng, ng_local, wi);
    stats.rays += 1;
    let tolerance = ARRIVAL_TOLERANCE * lit.propagator.epsilon();
    match lit.propagator.trace(lit.world, at.region, origin, wi) {
        RayEnd::Hit(a)
            if (a.region, a.object) == (light.region, light.object)
                && (a.hit.p - light.point).length() <= tolerance =>
        {
            Some(a.energy)
        }
        RayEnd::Failed => {
            stats.fates.failed += 1;
            None
        }
        RayEnd::Hit(_) | RayEnd::Escaped { .. } | RayEnd::Captured => None,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::material::Material;
    use crate::rgb::Rgb;
    use crate::shape::Shape;
    use crate::sky::Sky;
    use crate::texture::Texture;
    use crate::transform::Transform;
    use crate::world::Object;

    /// A lamp of radiance `upper` 3 above the upper region's throat and one of radiance `lower`
    /// 40 off in the lower region (none where 0).
    fn two_regions(upper: f32, lower: f32) -> World {
        let t = Transform::identity();
        let lamp = |centre: Vec3, radiance: f32| Object {
            shape: Shape::sphere(centre, 0.5, &t).unwrap(),
            material: 0,
            emission: Some(Emission::uniform(Rgb::splat(radiance), false)),
        };
        let lamps = |centre, radiance| if radiance > 0.0 { vec![lamp(centre, radiance)] } else { Vec::new() };
        let black = || Sky::Constant(Rgb::ZERO);
        World::new(
            vec![Material::Diffuse { reflectance: Texture::from(Rgb::splat(0.5)) }],
            (lamps(Vec3::new(0.0, 3.0, 0.0), upper), black()),
            (lamps(Vec3::new(40.0, 0.0, 0.0), lower), black()),
        )
    }

    fn through(from: Vec3) -> Reach {
        Reach::ThroughThroat { radius: 1.0, from }
    }

    /// Each point splits its samples between the regions, more to the other one near the
    /// throat's mouth, never below the defensive floor; a region without lights gets none, and
    /// without a throat a point samples only its own.
    #[test]
    fn regions_are_chosen_by_the_light_each_gives_the_point() {
        let both = two_regions(1.0, 400.0);
        let other = |x: Vec3| region_probability(&both, Region::Upper, Region::Lower, through(x));
        let (near, far) = (other(Vec3::new(0.0, 0.0, 1.1)), other(Vec3::new(0.0, 0.0, 8.0)));
        for x in [Vec3::new(0.0, 0.0, 1.1), Vec3::new(0.0, 0.0, 8.0), Vec3::new(5.0, -2.0, 3.0)] {
            let own = region_probability(&both, Region::Upper, Region::Upper, through(x));
            assert!((own + other(x) - 1.0).abs() < 1e-15);
            assert!((DEFENSIVE_REGION_PROBABILITY..=1.0 - DEFENSIVE_REGION_PROBABILITY).contains(&own));
        }
        assert!(near > 2.0 * far, "other region near the mouth {near}, far from it {far}");
        assert_eq!(region_probability(&both, Region::Upper, Region::Lower, Reach::OwnRegion), 0.0);

        let dark_upper = two_regions(0.0, 400.0);
        assert_eq!(region_probability(&dark_upper, Region::Upper, Region::Lower, through(Vec3::Z * 5.0)), 1.0);
        let dark_lower = two_regions(1.0, 0.0);
        assert_eq!(region_probability(&dark_lower, Region::Upper, Region::Upper, through(Vec3::Z * 5.0)), 1.0);
    }
}

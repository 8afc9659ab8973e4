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
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum Reach {
    /// Those of its own region.
    OwnRegion,
    /// Those of its own region where it has any, else the other region's of a wormhole, reached
    /// through the throat.
    ThroughThroat,
}

/// The probability that a shading point of region `from` samples a light of region `to`. Where
/// both regions have lights, a point samples its own: an even split between them doubled the
/// cost of a sample and raised its variance on the wormhole room (`equal_time`, 160 × 120: 3.21 →
/// 2.22 at equal time), whose throat passes little of the other side's light to most points.
fn region_probability(world: &World, from: Region, to: Region, reach: Reach) -> f64 {
    let lit = |region: Region| world.light_count(region) > 0;
    let sampled = match reach {
        Reach::ThroughThroat if !lit(from) => from.other(),
        Reach::OwnRegion | Reach::ThroughThroat => from,
    };
    f64::from(u8::from(to == sampled))
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

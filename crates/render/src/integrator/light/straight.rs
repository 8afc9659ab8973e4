//! Direct light in flat space: straight shadow rays to points sampled on the lights.

use super::point::{choice, sample_point, Reach};
use super::{contribution, Lit, Shading};
use crate::geometry::Ray;
use crate::integrator::stats::PathStats;
use crate::propagator::Arrival;
use crate::sampling::Sampler;
use crate::shape::offset_origin;
use crate::spectrum::Colour;

/// One light point, joined by a straight shadow ray.
pub(super) fn direct<C: Colour>(
    lit: Lit<'_>,
    at: &Arrival,
    shading: &Shading<'_, C>,
    sampler: &mut Sampler,
    stats: &mut PathStats,
) -> C {
    let (u_choice, u_point) = (sampler.next_f64(), sampler.next_2d());
    let Some(light) = sample_point(lit.world, at, Reach::OwnRegion, u_choice, u_point) else { return C::ZERO };
    let to_light = light.point - at.hit.p;
    let dist2 = to_light.length_squared();
    let wi = to_light / dist2.sqrt();
    if !light.emission.faces(light.normal, -wi) {
        return C::ZERO;
    }
    let pdf = light.probability * dist2 / (light.normal.dot(wi).abs() * light.area);
    let emitted = |g| light.seen(light.normal, -wi, g, lit, &shading.lambda);
    let visible = || {
        let origin = offset_origin(at.hit.p, at.hit.ng, wi);
        let to_point = light.point - origin;
        let length = to_point.length();
        stats.rays += 1;
        // Stop just short of the light so the light itself does not count as a blocker.
        let shadow = Ray::new(origin, to_point / length, length * (1.0 - 1e-6));
        (!lit.world.occluded(at.region, &shadow)).then_some(1.0)
    };
    contribution(shading, wi, pdf, visible, emitted)
}

/// The density [`direct`] has for the straight ray that reached the emitter of `arrival`
/// (local geometric normal `ng`).
pub(super) fn emitter_pdf(lit: Lit<'_>, arrival: &Arrival, ng: crate::geometry::Vec3) -> Option<f64> {
    let cos = ng.dot(arrival.direction).abs();
    let (probability, area) = choice(lit.world, arrival.region, Reach::OwnRegion, arrival)?;
    (cos > 0.0).then(|| probability * arrival.distance * arrival.distance / (cos * area))
}

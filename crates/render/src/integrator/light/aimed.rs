//! Direct light in any curved spacetime without a connector of its own: the ray from the
//! shading point to a point sampled on a light is aimed by Newton's method on its start
//! direction ([`Propagator::aim`]: `spacetime::geodesic::plane_aim` in static, spherically
//! symmetric spacetimes, `spacetime::geodesic::aim` in others), and its density in solid angle
//! at the shading point follows from the light's area density through the ray bundle:
//!
//! ```text
//! p_ω = P(light) / (A · |n · t| · dΩ/dA⊥),
//! ```
//!
//! as for the Schwarzschild connections ([`super::ways`]). The aim starts from the straight line
//! between the two points, so the ray it finds (the image of the light point nearest that line)
//! is a function of the two points: a BSDF-sampled ray that reaches a light is weighted against
//! this strategy exactly when aiming at the point it reached finds that same ray again, and has
//! weight 1 otherwise (the other images, which this strategy never produces).
//!
//! Visibility and the frequency shift come from tracing the aimed ray through the scene, as
//! any ray is traced: it must arrive at the sampled point's light within the tolerance the
//! chord test places hits to.

use super::point::{choice, sample_point, solid_angle_density, traced_arrival};
use super::{contribution, Bounce, Lit, Shading};
use crate::integrator::stats::PathStats;
use crate::propagator::Arrival;
use crate::sampling::Sampler;
use crate::spectrum::Colour;

/// A BSDF-sampled ray is the aimed one when their start directions differ by less than this
/// many chord tolerances ε per unit distance between the ends: the hit it found lies within ~ε
/// of the curve, the aim passes within ε of that hit. Other images of the same point leave in
/// directions apart by far more, except right at a caustic.
const SAME_RAY: f64 = 16.0;

/// One light point, joined by the ray aimed at it.
pub(super) fn direct<C: Colour>(
    lit: Lit<'_>,
    at: &Arrival,
    shading: &Shading<'_, C>,
    sampler: &mut Sampler,
    stats: &mut PathStats,
) -> C {
    let (u_choice, u_point) = (sampler.next_f64(), sampler.next_2d());
    let Some(light) = sample_point(lit.world, at, u_choice, u_point) else { return C::ZERO };
    let Some(aimed) = lit.propagator.aim(at.region, at.hit.p, light.point) else { return C::ZERO };
    let normal_local = lit.propagator.local_normal(at.region, light.point, light.normal);
    if !light.emission.faces(normal_local, -aimed.end) {
        return C::ZERO;
    }
    let pdf = solid_angle_density(light.density(), light.normal, aimed.end_tangent, aimed.solid_angle_per_area);
    let visible = || traced_arrival(lit, at, shading.ng, aimed.start, (light.object, light.point), stats);
    let emitted = |g| light.seen(normal_local, -aimed.end, g, lit, &shading.lambda);
    contribution(shading, aimed.start, pdf, visible, emitted)
}

/// The density [`direct`] has for the BSDF-sampled ray that left `bounce` and reached the
/// emitter of `arrival`: `None` where aiming at the point it reached finds another ray.
pub(super) fn emitter_pdf(lit: Lit<'_>, bounce: &Bounce, arrival: &Arrival) -> Option<f64> {
    let (probability, area) = choice(lit.world, arrival)?;
    let aimed = lit.propagator.aim(arrival.region, bounce.from, arrival.hit.p)?;
    let distance = (arrival.hit.p - bounce.from).length();
    if (aimed.start - bounce.direction).length() * distance > SAME_RAY * lit.propagator.epsilon() {
        return None;
    }
    let pdf = solid_angle_density(probability / area, arrival.hit.ng, aimed.end_tangent, aimed.solid_angle_per_area);
    Some(pdf).filter(|p| *p > 0.0 && p.is_finite())
}

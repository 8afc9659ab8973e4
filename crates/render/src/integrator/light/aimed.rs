//! Direct light in any curved spacetime without a connector of its own: the ray from the
//! shading point to a point sampled on a light is aimed by Newton's method on its start
//! direction ([`Propagator::aim`]: `spacetime::geodesic::plane::plane_aim` in static, spherically
//! symmetric spacetimes, `spacetime::geodesic::aim` in others), and its density in solid angle
//! at the shading point follows from the light's area density through the ray bundle and the
//! probability of trying the ray's way round:
//!
//! ```text
//! p_ω = P(way) · P(light) / (A · |n · t| · dΩ/dA⊥),
//! ```
//!
//! as for the Schwarzschild connections ([`super::ways`]). In the ray's plane two rays join the
//! points, the short way and the long way round the centre (past a photon sphere or round a
//! throat), tried as the Schwarzschild connections try them ([`way_probability`]); a 4-D aim
//! starts from the straight line between the points and finds one ray (the image nearest that
//! line), the short way's. Either way the ray is a function of the two points and its way: a
//! BSDF-sampled ray that reaches a light is weighted against this strategy exactly when aiming
//! its way (told by the azimuth it swept, where the in-plane tracer followed it) at the point
//! it reached finds that same ray again, and has weight 1 otherwise (rays that wound round once
//! or more, and the other images a 4-D aim never produces).
//!
//! Visibility and the frequency shift come from tracing the aimed ray through the scene, as
//! any ray is traced: it must arrive at the sampled point's light within the tolerance the
//! chord test places hits to.

use super::point::{choice, sample_point, solid_angle_density, traced_arrival, LightPoint, Reach};
use super::ways::way_probability;
use super::{contribution, Bounce, Lit, Shading};
use crate::geometry::Vec3;
use crate::integrator::stats::PathStats;
use crate::propagator::Arrival;
use crate::sampling::Sampler;
use crate::spectrum::Colour;
use spacetime::geodesic::plane::Way;

/// A BSDF-sampled ray is the aimed one when their start directions differ by less than this
/// many chord tolerances ε per unit distance between the ends: the hit it found lies within ~ε
/// of the curve, the aim passes within ε of that hit. Other images of the same point leave in
/// directions apart by far more, except right at a caustic.
const SAME_RAY: f64 = 16.0;

/// One light point, joined by the ray aimed at it the short way and, where light is aimed in
/// the ray's plane, at random the long way.
pub(super) fn direct<C: Colour>(
    lit: Lit<'_>,
    at: &Arrival,
    shading: &Shading<'_, C>,
    sampler: &mut Sampler,
    stats: &mut PathStats,
) -> C {
    let (u_choice, u_point, u_way) = (sampler.next_f64(), sampler.next_2d(), sampler.next_f64());
    let Some(light) = sample_point(lit.world, at, reach(lit, at.hit.p), u_choice, u_point) else { return C::ZERO };
    let ways: &[Way] = if lit.propagator.aims_both_ways() { &Way::BOTH } else { &[Way::Short] };
    let mut sum = C::ZERO;
    for &way in ways {
        let probability = way_probability(way, at.hit.p, in_start_chart(at.region, (light.region, light.point)));
        if u_way < probability {
            sum += aimed_way(lit, at, shading, &light, (way, probability), stats);
        }
    }
    sum
}

/// The light of `light` arriving along the ray aimed at it `way` round, which was tried with
/// probability `probability`.
fn aimed_way<C: Colour>(
    lit: Lit<'_>,
    at: &Arrival,
    shading: &Shading<'_, C>,
    light: &LightPoint<'_>,
    (way, probability): (Way, f64),
    stats: &mut PathStats,
) -> C {
    let Some(aimed) = lit.propagator.aim((at.region, at.hit.p), (light.region, light.point), way) else {
        return C::ZERO;
    };
    let normal_local = lit.propagator.local_normal(light.region, light.point, light.normal);
    if !light.emission.faces(normal_local, -aimed.end) {
        return C::ZERO;
    }
    let pdf =
        probability * solid_angle_density(light.density(), light.normal, aimed.end_tangent, aimed.solid_angle_per_area);
    let visible = || traced_arrival(lit, at, shading.ng, aimed.start, light, stats);
    let emitted = |g| light.seen(normal_local, -aimed.end, g, lit, &shading.lambda);
    contribution(shading, aimed.start, pdf, visible, emitted)
}

/// The density [`direct`] has for the BSDF-sampled ray that left `bounce` and reached the
/// emitter of `arrival`: `None` where aiming at the point it reached finds another ray.
pub(super) fn emitter_pdf(lit: Lit<'_>, bounce: &Bounce, arrival: &Arrival) -> Option<f64> {
    let way = match arrival.swept {
        Some(swept) if lit.propagator.aims_both_ways() => Way::of_sweep(swept)?,
        _ => Way::Short,
    };
    let (probability, area) = choice(lit.world, bounce.region, reach(lit, bounce.from), arrival)?;
    let aimed = lit.propagator.aim((bounce.region, bounce.from), (arrival.region, arrival.hit.p), way)?;
    let distance = (arrival.hit.p - bounce.from).length();
    if (aimed.start - bounce.direction).length() * distance > SAME_RAY * lit.propagator.epsilon() {
        return None;
    }
    let pdf = way_probability(way, bounce.from, in_start_chart(bounce.region, (arrival.region, arrival.hit.p)))
        * solid_angle_density(probability / area, arrival.hit.ng, aimed.end_tangent, aimed.solid_angle_per_area);
    Some(pdf).filter(|p| *p > 0.0 && p.is_finite())
}

/// Which lights a shading point at world point `from` samples: both regions' where light is
/// aimed through a wormhole's throat.
fn reach(lit: Lit<'_>, from: Vec3) -> Reach {
    lit.propagator.aims_through_throat().map_or(Reach::OwnRegion, |radius| Reach::ThroughThroat { radius, from })
}

/// World point `p` of `region` as seen from the start's region `start` about the centre: the
/// other region's world is the chart turned inside out (`spacetime::geodesic::plane`), so its
/// points lie opposite, for the azimuth a ray sweeps to them.
fn in_start_chart(start: spacetime::Region, (region, p): (spacetime::Region, Vec3)) -> Vec3 {
    if region == start {
        p
    } else {
        -p
    }
}

//! Direct light along geodesics (Schwarzschild): next-event estimation that joins a shading
//! point `x` to a point `y` sampled on an emitter by the light ray between them.
//!
//! Two rays join them, one each way round the hole: the short way (azimuth `Δφ ≤ π`) and the
//! long way (`2π − Δφ`, past the photon sphere), found by shooting in the plane of `x`, `y` and
//! the centre (`spacetime::metric::schwarzschild::connect`). They are two sampling strategies: the short way
//! is tried for every light point, the long way at random, the more often the closer the point
//! lies to across the hole ([`way_probability`]). Each one's density
//! in solid angle at `x` follows from the area density on the light through its ray bundle and
//! the probability of trying it:
//!
//! ```text
//! p_ω = P(way) · P(light) / (A · |n · t| · dΩ/dA⊥),
//! ```
//!
//! with `A` the light's world area (points are sampled uniformly in it), `n` its world normal, `t`
//! the ray's world tangent at `y` and `dΩ/dA⊥` the bundle factor (`connect`'s equation (3)). The
//! integral over the light in world coordinates is the integral over directions at `x` in the
//! static observer's frame, so no proper areas are needed. Radiance arriving at `x` is the
//! emitted radiance, seen by the static observer at `y`, times the frequency shift `(E_x/E_y)⁴`.
//!
//! A ray reaching a light by BSDF sampling is weighted against the strategy of its own way round,
//! told by the azimuth it swept. Rays that wound round the hole once or more are never sampled
//! here; BSDF sampling finds them, and their MIS weight is 1 (Veach 1997, ch. 9: a strategy's
//! weight only counts where that strategy can produce the path).
//!
//! Visibility: a connection lies inside the triangle of its chord and its end tangents, or the
//! short way round and in any case inside the triangles between its waypoints
//! ([`Connection::enclosing_triangle`]); where no object but the two it joins comes within ε of
//! them, nothing can block it. Any other connection is traced against the scene like any ray,
//! so occluders are seen exactly as BSDF-sampled rays see them. A light that emits from one
//! side is joined only by rays that reach that side (`connect_along` drops the others before
//! refining them).
//!
//! Other curved spacetimes aim their light rays ([`super::aimed`]).

use super::point::{choice, sample_point, solid_angle_density, traced_arrival, LightPoint, Reach};
use super::{contribution, Lit, Shading};
use crate::geometry::Vec3;
use crate::integrator::stats::PathStats;
use crate::propagator::{Arrival, Propagator};
use crate::sampling::Sampler;
use crate::spectrum::Colour;
use spacetime::geodesic::plane::Way;
use spacetime::metric::schwarzschild::connect::{short_way_arrives_behind, Connection, Waypoints};
use std::f64::consts::PI;

/// How fast the probability of trying the long way falls with the azimuth it sweeps beyond π
/// ([`way_probability`]).
const LONG_WAY_FALLOFF: f64 = 2.0;

/// Probability that the light point `y` is joined to the shading point `x` the way `way` round
/// the hole: the factor in that strategy's density. The short way is always tried. The long way
/// sweeps `S = 2π − Δφ` and passes close to the photon sphere, so its connection and visibility
/// cost several times the short way's; its image of a light shrinks with the sweep, as the
/// impact parameter's excess over the critical one falls as `e^(−S)` (strong-deflection limit,
/// Bozza 2002). It is tried with probability `e^(−2(S − π))`: always for points across the hole
/// from `x`, whose two images are alike, hardly for points beside it. Though rarely tried there,
/// its images are so compressed that its light-sampling density far exceeds BSDF sampling's, and
/// MIS takes the BSDF-sampled long-way hits (the fireflies of brute force) almost entirely off
/// them. The falloff trades the long way's cost against the variance it removes; never trying
/// the long way leaves the BSDF-sampled long-way hits as fireflies (the measurements that chose
/// it are in `docs/perf-journal.md`, "The long way round the hole").
pub(super) fn way_probability(way: Way, x: Vec3, y: Vec3) -> f64 {
    match way {
        Way::Short => 1.0,
        Way::Long => {
            let beyond_half_turn = PI - x.angle_between(y);
            (-LONG_WAY_FALLOFF * beyond_half_turn).exp()
        }
    }
}

/// A sampled light point joined to the shading point, before the visibility test.
pub(super) struct Candidate<'w> {
    /// Direction the ray leaves the shading point in (its static frame).
    pub wi: Vec3,
    /// The light point, and the local direction its light leaves in towards the shading point
    /// with the light's normal there.
    light: &'w LightPoint<'w>,
    leaving: Vec3,
    normal_local: Vec3,
    /// Density of `wi` in solid angle at the shading point.
    pub pdf: f64,
    point: Vec3,
    connection: Connection,
    /// Points along the connection, in the caller's scratch.
    waypoints: &'w Waypoints,
}

/// One light point joined by its geodesics, the short way round the hole and, at random, the
/// long way.
pub(super) fn direct<C: Colour>(
    lit: Lit<'_>,
    at: &Arrival,
    shading: &Shading<'_, C>,
    sampler: &mut Sampler,
    stats: &mut PathStats,
) -> C {
    let (u_choice, u_point, u_way) = (sampler.next_f64(), sampler.next_2d(), sampler.next_f64());
    let Some(point) = sample_point(lit.world, at, Reach::OwnRegion, u_choice, u_point) else {
        return C::ZERO;
    };
    let (mut sum, mut waypoints) = (C::ZERO, Waypoints::default());
    for way in Way::BOTH {
        let probability = way_probability(way, at.hit.p, point.point);
        if u_way >= probability || (way == Way::Short && reflects_none(at, shading, &point)) {
            continue;
        }
        if let Some(light) = join(&point, lit.propagator, at, (way, probability), &mut waypoints) {
            let visible = || light.arrives(lit, at, shading.ng, stats);
            let emitted = |g| light.light.seen(light.normal_local, light.leaving, g, lit, &shading.lambda);
            sum += contribution(shading, light.wi, light.pdf, visible, emitted);
        }
    }
    sum
}

/// Whether an opaque surface reflects none of the light coming the short way from `point`: when
/// its front (the side `wo` is on) faces the centre and the point lies on or behind its tangent
/// plane, the short way leaves it into the back ([`short_way_arrives_behind`], reversed). Such
/// points are not joined at all (the surface behind a one-sided light is the other case, dropped
/// by the connection solver).
fn reflects_none<C: Colour>(at: &Arrival, shading: &Shading<'_, C>, point: &LightPoint) -> bool {
    let front = if shading.wo.z >= 0.0 { at.hit.ns } else { -at.hit.ns };
    !shading.bsdf.has_transmission()
        && short_way_arrives_behind(front.to_array(), point.point.to_array(), at.hit.p.to_array())
}

/// Joins the shading point of `at` to the light point `light` by the ray going `way` round the hole,
/// which was tried with probability `probability` ([`way_probability`]), keeping its
/// waypoints in `waypoints`; `None` if there is none or it carries nothing.
fn join<'w>(
    light: &'w LightPoint<'w>,
    propagator: &Propagator,
    at: &Arrival,
    (way, probability): (Way, f64),
    waypoints: &'w mut Waypoints,
) -> Option<Candidate<'w>> {
    let facing = (!light.emission.two_sided).then_some(light.normal);
    let connection = propagator.connect(at.hit.p, light.point, way, facing, waypoints)?;
    let normal_local = propagator.local_normal(at.region, light.point, light.normal);
    let leaving = -Vec3::from_array(connection.end);
    let pdf = probability * connection_density(light.density(), light.normal, &connection);
    if !(light.emission.faces(normal_local, leaving) && pdf > 0.0 && pdf.is_finite()) {
        return None;
    }
    let wi = Vec3::from_array(connection.start);
    Some(Candidate { wi, light, leaving, normal_local, pdf, point: light.point, connection, waypoints })
}

impl Candidate<'_> {
    /// Whether the connection from the shading point of `at` (local geometric normal `ng_local`)
    /// reaches the sampled point unoccluded: the photon's energy there relative to here,
    /// `E_y/E_x`, if so, else `None`. A connection whose triangle no object comes near (within ε) is seen without
    /// tracing it; any other is traced against the scene.
    pub(super) fn arrives(&self, lit: Lit<'_>, at: &Arrival, ng_local: Vec3, stats: &mut PathStats) -> Option<f64> {
        if self.is_clear(lit, at) {
            let propagator = lit.propagator;
            return Some(propagator.lapse(at.region, at.hit.p) / propagator.lapse(at.region, self.point));
        }
        self.traced(lit, at, ng_local, stats)
    }

    /// Whether no object comes near the triangle that holds the connection, or else the
    /// triangles between its waypoints, except the two objects it joins, at its ends.
    fn is_clear(&self, lit: Lit<'_>, at: &Arrival) -> bool {
        let Lit { world, propagator } = lit;
        let (x, y) = (at.hit.p.to_array(), self.point.to_array());
        let clear = |triangle: [[f64; 3]; 3], first: bool, last: bool| {
            let [a, z, b] = triangle.map(Vec3::from_array);
            if propagator.in_empty_ball(world, at.region, a, b) {
                return true;
            }
            world.triangle_is_clear(at.region, [a, z, b], [first, false, last], propagator.epsilon())
        };
        if self.connection.enclosing_triangle(x, y).is_some_and(|triangle| clear(triangle, true, true)) {
            return true;
        }
        let mut pieces = self.connection.enclosing_triangles(self.waypoints, x, y).enumerate().peekable();
        while let Some((k, piece)) = pieces.next() {
            if !piece.is_some_and(|triangle| clear(triangle, k == 0, pieces.peek().is_none())) {
                return false;
            }
        }
        true
    }

    /// [`Candidate::arrives`] by tracing the connection against the scene.
    fn traced(&self, lit: Lit<'_>, at: &Arrival, ng_local: Vec3, stats: &mut PathStats) -> Option<f64> {
        traced_arrival(lit, at, ng_local, self.wi, self.light, stats)
    }
}

/// Density in solid angle at `from` with which [`LightPoint::join`] would have produced the ray
/// that reached the emitter of `arrival`: `None` where it never would (the ray wound round the
/// hole, or the emitter is not sampled), so BSDF sampling's MIS weight is then 1.
pub(super) fn emitter_pdf(lit: Lit<'_>, from: Vec3, arrival: &Arrival) -> Option<f64> {
    // Each way round, the ray is unique (monotone shooting, see `connect`): a ray that went less
    // than once round is exactly the one `connect` finds, that way round, between its ends.
    let way = Way::of_sweep(arrival.swept?)?;
    let (probability, area) = choice(lit.world, arrival.region, Reach::OwnRegion, arrival)?;
    let connection = lit.propagator.connect(from, arrival.hit.p, way, None, &mut Waypoints::default())?;
    let pdf =
        way_probability(way, from, arrival.hit.p) * connection_density(probability / area, arrival.hit.ng, &connection);
    Some(pdf).filter(|p| *p > 0.0 && p.is_finite())
}

/// [`solid_angle_density`] of a connection.
fn connection_density(area_density: f64, normal: Vec3, connection: &Connection) -> f64 {
    let tangent = Vec3::from_array(connection.end_tangent);
    solid_angle_density(area_density, normal, tangent, connection.solid_angle_per_area)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::integrator::path::leave;
    use crate::propagator::RayEnd;
    use crate::settings::Intersection;
    use crate::test_scenes::{floor_lamp_board_ball, uniform};
    use crate::world::World;
    use spacetime::{Region, Schwarzschild, Spacetime};

    /// The chord tracer round the test scene's hole (mass 0.3).
    fn propagator() -> Propagator {
        Propagator::new(Spacetime::Schwarzschild(Schwarzschild::new(0.3)), 11.0, 1e-7, Intersection::Chord)
    }

    /// A point of the floor, the board or the ball, seen from above the floor, and a point
    /// sampled on the lamp for it; `None` where the eye's ray missed them.
    fn shading_point<'w>(
        world: &'w World,
        propagator: &Propagator,
        uniform: &mut impl FnMut() -> f64,
    ) -> Option<(Arrival, LightPoint<'w>)> {
        let eye = Vec3::new(0.5, 3.0, 7.0);
        let target = Vec3::new(12.0 * uniform() - 6.0, -4.0, 16.0 * uniform() - 8.0);
        let RayEnd::Hit(at) = propagator.trace(world, Region::Upper, eye, (target - eye).normalize()) else {
            return None;
        };
        let point = sample_point(world, &at, Reach::OwnRegion, uniform(), [uniform(), uniform()])?;
        Some((at, point))
    }

    /// `point` joined to the shading point of `at` `way` round, tried with that way's probability.
    fn joined<'w>(
        propagator: &Propagator,
        at: &Arrival,
        point: &'w LightPoint<'w>,
        way: Way,
        waypoints: &'w mut Waypoints,
    ) -> Option<Candidate<'w>> {
        join(point, propagator, at, (way, way_probability(way, at.hit.p, point.point)), waypoints)
    }

    /// The triangle tests never clear a connection that tracing finds blocked, and they clear a
    /// good part of the others, either way round, with the same frequency shift.
    #[test]
    fn connections_cleared_by_their_triangles_are_seen_by_tracing() {
        let (world, propagator) = (floor_lamp_board_ball(), propagator());
        let mut uniform = uniform(7);
        for way in Way::BOTH {
            let (mut cleared, mut seen, mut blocked) = (0, 0, 0);
            for _ in 0..400 {
                let Some((at, point)) = shading_point(&world, &propagator, &mut uniform) else { continue };
                let mut waypoints = Waypoints::default();
                let Some(candidate) = joined(&propagator, &at, &point, way, &mut waypoints) else { continue };
                let mut stats = PathStats::default();
                let lit = Lit { world: &world, propagator: &propagator };
                let traced = candidate.traced(lit, &at, at.ng_local, &mut stats);
                let clear = candidate.is_clear(lit, &at);
                match traced {
                    Some(energy) => {
                        seen += 1;
                        if clear {
                            cleared += 1;
                            let direct =
                                propagator.lapse(at.region, at.hit.p) / propagator.lapse(at.region, candidate.point);
                            // The traced ray starts off the surface and ends within ~ε of the point.
                            assert!((direct / energy - 1.0).abs() < 2.5e-5, "energy {direct} vs traced {energy}");
                        }
                    }
                    None => {
                        blocked += 1;
                        assert!(!clear, "{way:?}: {:?} → {:?} cleared but blocked", at.hit.p, candidate.point);
                    }
                }
            }
            assert!(blocked > 20, "{way:?}: only {blocked} blocked: the test would not catch a wrong clearance");
            // Whatever comes near the ball's bounds is traced. Cleared: 165 of 237 the short way
            // (174 when its shots took shorter steps, leaving closer waypoints), 199 of 239 the
            // long way (213 before its pieces were merged, see `Connection::enclosing_triangles`).
            assert!(cleared as f64 > 0.65 * seen as f64, "{way:?}: {cleared} of {seen} unblocked connections cleared");
        }
    }

    /// The density a light point is joined with, either way round, is the one MIS gives a
    /// BSDF-sampled ray that reaches the same point that way: the ray along the joined direction
    /// arrives at the point, and `emitter_pdf` there matches the join's density (the way's
    /// probability included, a function of the two ends alone).
    #[test]
    fn joined_light_points_have_the_density_mis_gives_the_rays_reaching_them() {
        let (world, propagator) = (floor_lamp_board_ball(), propagator());
        let mut uniform = uniform(3);
        for way in Way::BOTH {
            let mut compared = 0;
            for _ in 0..300 {
                let Some((at, point)) = shading_point(&world, &propagator, &mut uniform) else { continue };
                let mut waypoints = Waypoints::default();
                let Some(candidate) = joined(&propagator, &at, &point, way, &mut waypoints) else { continue };
                let origin = leave(at.hit.p, at.hit.ng, at.ng_local, candidate.wi);
                let RayEnd::Hit(arrival) = propagator.trace(&world, Region::Upper, origin, candidate.wi) else {
                    continue;
                };
                if arrival.object != candidate.light.object {
                    continue;
                }
                let pdf = emitter_pdf(Lit { world: &world, propagator: &propagator }, at.hit.p, &arrival).unwrap();
                // The ray arrives within ~ε of the point; the density changes little over that.
                assert!(
                    (pdf / candidate.pdf - 1.0).abs() < 1e-3,
                    "{way:?}: {:?} → {:?}: joined with {}, MIS density {pdf}",
                    at.hit.p,
                    candidate.point,
                    candidate.pdf
                );
                compared += 1;
            }
            // Measured: 180 the short way, 195 the long way (of 300 shading points; the others
            // missed the floor and board, or their light point was not joined or is blocked).
            assert!(compared > 100, "{way:?}: only {compared} rays compared");
        }
    }
}

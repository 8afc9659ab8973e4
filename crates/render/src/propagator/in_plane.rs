//! The in-plane tracer of static, spherically symmetric spacetimes: a ray stays in the plane of
//! its start and the centre, and is traced there in azimuth ([`spacetime::geodesic::plane`]),
//! its steps tested against the scene by their chords ([`super::chords`]). Its energy at a hit
//! is the ratio of the lapses at its start and there (`docs/physics.md`, "Frequency ratios and
//! redshift").

use super::chords::{from_chord_side, ChordHit, CurvedStep, Knot};
use super::{Arrival, Propagator, RayEnd};
use crate::geometry::{Ray, Vec3};
use crate::world::World;
use spacetime::geodesic::plane::{trace_plane, PlaneMetric, PlaneStart, PlaneStep};
use spacetime::{Fate, Region, Visit};

impl Propagator {
    /// Traces the ray leaving world point `origin` of `region` along the local-frame unit
    /// direction `direction` in `metric`'s plane, to its end.
    pub(super) fn in_plane<M: PlaneMetric>(
        &self,
        metric: &M,
        world: &World,
        region: Region,
        origin: Vec3,
        direction: Vec3,
    ) -> RayEnd {
        let Some(start) = PlaneStart::from_observer(metric, region, origin.to_array(), direction.to_array()) else {
            return RayEnd::Captured;
        };
        let lapse = |p: Vec3| metric.u_of_world_radius(p.length()).map_or(1.0, |u| metric.lapse(u));
        let lapse0 = lapse(origin);
        let mut arrival: Option<(ChordHit, Vec3, Region, Option<f64>)> = None;
        // Rays that bend one way are bounded by the triangles of their chords and end tangents.
        let bounded = metric.bends_towards_centre() && self.bound_arcs;
        // Where the previous step ended, and in which region's coordinates.
        let (mut last, mut last_region) = (Knot { theta: 0.0, at: origin, tangent: None }, region);
        let mut leaves_origin = true;
        let t = trace_plane(metric, start, &self.plane_trace, |step| {
            let region = step.region();
            let knot = |theta: f64| {
                if bounded {
                    let (at, tangent) = step.knot(metric, theta);
                    Knot { theta, at: Vec3::from_array(at), tangent: Some(Vec3::from_array(tangent)) }
                } else {
                    Knot { theta, at: Vec3::from_array(step.position(metric, theta)), tangent: None }
                }
            };
            // A step starts where the previous one ended, unless it crossed a throat into the
            // other region's coordinates: reusing the end saves placing a point per step.
            let from = if region == last_region && (last.tangent.is_some() || !bounded) {
                Knot { theta: 0.0, ..last }
            } else {
                knot(0.0)
            };
            let to = knot(1.0);
            (last, last_region) = (to, region);
            let found = match step {
                PlaneStep::Straight { from, direction, length, .. } => {
                    let chord = Ray::new(Vec3::from_array(*from), Vec3::from_array(*direction), *length);
                    world.intersect(region, &chord).map(|(object, t)| ChordHit { object, chord, t, theta: 0.0 })
                }
                PlaneStep::Curved { .. } => {
                    let axis = step.axis().filter(|_| bounded).map(Vec3::from_array);
                    let motion = |theta: f64| {
                        let (at, velocity) = step.motion(metric, theta);
                        (Vec3::from_array(at), Vec3::from_array(velocity))
                    };
                    let curved = CurvedStep { knot: &knot, motion: Some(&motion), axis, leaves_origin };
                    self.curved(world, region, &curved, from, to)
                }
            };
            leaves_origin = false;
            match found {
                Some(hit) => {
                    let direction = match step {
                        PlaneStep::Straight { .. } => hit.chord.dir,
                        PlaneStep::Curved { .. } => Vec3::from_array(step.point(metric, hit.theta).direction),
                    };
                    arrival = Some((hit, direction, region, step.azimuth(hit.theta)));
                    Visit::Stop
                }
                None => Visit::Continue,
            }
        });
        match t.fate {
            Fate::Stopped => {
                let Some((found, direction, region, swept)) = arrival else { return RayEnd::Failed };
                let hit = world.surface(region, found.object, &found.chord, found.t);
                let ng_local = self.local_normal(region, hit.p, hit.ng);
                let direction = from_chord_side(&hit, ng_local, found.chord.dir, direction);
                let energy = lapse0 / lapse(hit.p);
                let object = found.object;
                RayEnd::Hit(Arrival { region, object, hit, ng_local, direction, distance: found.t, energy, swept })
            }
            Fate::Escaped { direction } | Fate::Traversed { direction } => {
                let traversed = matches!(t.fate, Fate::Traversed { .. });
                let region = if traversed { region.other() } else { region };
                self.beyond(world, region, last.at, Vec3::from_array(direction), traversed, lapse0)
            }
            Fate::Captured => RayEnd::Captured,
            Fate::Failed(_) => RayEnd::Failed,
        }
    }
}

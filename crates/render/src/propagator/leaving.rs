//! Rays leaving the scene: past the escape radius spacetime counts as flat, and the rest of a
//! ray is the straight line along its asymptotic direction; in flat space the whole ray is.

use super::{Arrival, Propagator, RayEnd};
use crate::geometry::{Ray, Vec3};
use crate::world::World;
use spacetime::Region;

impl Propagator {
    /// A ray past the escape radius: spacetime is flat enough there that the rest of the way is
    /// the straight line along its asymptotic direction; unbounded objects (infinite planes) can
    /// still be met on it. Its energy is then measured by static observers far away (`energy`),
    /// and the surface's normal in their frames, which still differ a little from the world's.
    pub(super) fn beyond(
        &self,
        world: &World,
        region: Region,
        from: Vec3,
        direction: Vec3,
        traversed: bool,
        energy: f64,
    ) -> RayEnd {
        match straight(world, region, from, direction) {
            RayEnd::Hit(a) => {
                let ng_local = self.local_normal(region, a.hit.p, a.hit.ng);
                RayEnd::Hit(Arrival { ng_local, energy, swept: None, ..a })
            }
            // A straight ray either hits or escapes; it is never captured nor fails.
            RayEnd::Escaped { .. } | RayEnd::Captured | RayEnd::Failed => {
                RayEnd::Escaped { region, direction, traversed, energy }
            }
        }
    }
}

/// Flat space, where local frames are the world's: one straight chord to infinity.
pub(super) fn straight(world: &World, region: Region, origin: Vec3, direction: Vec3) -> RayEnd {
    match world.intersect(region, &Ray::new(origin, direction, f64::INFINITY)) {
        Some((object, dist)) => {
            let hit = world.surface(region, object, &Ray::new(origin, direction, dist), dist);
            let ng_local = hit.ng;
            RayEnd::Hit(Arrival { region, object, hit, ng_local, direction, distance: dist, energy: 1.0, swept: None })
        }
        None => RayEnd::Escaped { region, direction, traversed: false, energy: 1.0 },
    }
}

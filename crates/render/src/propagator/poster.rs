//! The poster's intersection test ("Rendering Curved Spacetime in Everyday Scenes", Ayush &
//! Chaudhuri 2017; [`crate::settings::Intersection::Poster`]), kept to reproduce its figures: a
//! step meets an object where the object's surface function changes sign between the step's
//! ends. Unlike the chord test it misses thin objects crossed twice within a step.

use super::chords::ChordHit;
use super::Propagator;
use crate::geometry::{Ray, Vec3};
use crate::world::World;
use spacetime::Region;

impl Propagator {
    /// The poster's Algorithm 1: an object is hit in a step when its surface function changes
    /// sign between the step's ends `a` and `b`; the crossing is bisected on the curved step
    /// until the point is within ε of the surface. A thin object crossed between two step ends
    /// with the same sign is missed, as in the poster.
    pub(super) fn sign_change(
        &self,
        world: &World,
        region: Region,
        point: &dyn Fn(f64) -> Vec3,
        a: Vec3,
        b: Vec3,
    ) -> Option<ChordHit> {
        let mut best: Option<ChordHit> = None;
        for (index, object) in world.objects(region).iter().enumerate() {
            let f = |p: Vec3| object.shape.surface_function(p);
            let (fa, fb) = (f(a), f(b));
            if fa.signum() == fb.signum() || !fa.is_finite() || !fb.is_finite() {
                continue;
            }
            let (mut lo, mut hi) = (0.0, 1.0);
            for _ in 0..60 {
                let mid = 0.5 * (lo + hi);
                let fm = f(point(mid));
                if fm.abs() < self.epsilon && (hi - lo) < 1e-3 {
                    break;
                }
                if fm.signum() == fa.signum() {
                    lo = mid;
                } else {
                    hi = mid;
                }
            }
            if best.is_some_and(|h| h.theta <= lo) {
                continue;
            }
            // The surface record comes from the short chord across the bracketed crossing.
            let (p, q) = (point(lo), point(hi));
            let len = (q - p).length();
            let mut chord = Ray::new(p, (q - p) / len, len);
            if !(len > 0.0) {
                continue;
            }
            chord.t_max = len;
            if let Some(t) = object.shape.intersect(&chord) {
                best = Some(ChordHit { object: index, chord, t, theta: lo + (hi - lo) * t / len });
            }
        }
        best
    }
}

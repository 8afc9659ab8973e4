//! Crossings of flat objects' planes, solved on the curve rather than on a chord: a chord lies
//! within ε of the curve but may cross a plane it meets at a slant farther from where the curve
//! does, and a piece near only flat objects need not be split at all. The hit's point, direction
//! and energy are then the curve's, to a hundredth of ε ([`crate::crossing`]).

use super::chords::{ChordHit, CurvedStep, Knot};
use super::Propagator;
use crate::crossing::{crossing, Meeting};
use crate::geometry::{Ray, Vec3};
use crate::world::{FlatBlockers, World};
use spacetime::Region;

/// Crossings of flat objects are solved to this fraction of ε, far below what a chord finds
/// (about ε, more on a plane met at a slant): the hit's point, direction and energy are then the
/// curve's. On the black-hole room a crossing takes 2.3 points on the curve (at 10⁻⁴, 0.6 more).
const CROSSING_TOLERANCE: f64 = 1e-2;

impl Propagator {
    /// A chord's hit `hit` on a flat object, moved onto the curve: the crossing of its plane by
    /// the piece of `step` between `a` and `b` (whose chord crosses it, so the curve does too),
    /// solved on the curve to a hundredth of ε by regula falsi (Illinois), then checked against
    /// the object by a chord across the plane there, as [`Propagator::cross_flat`] does. A chord
    /// lies within ε of the curve but may cross a plane it meets at a slant farther from where
    /// the curve does; the hit's point, direction and energy are then the curve's. `None` (keep
    /// the chord's hit) for curved objects and where the crossing misses the object.
    pub(super) fn onto_curve(
        &self,
        world: &World,
        region: Region,
        step: &CurvedStep<'_>,
        (a, b): (&Knot, &Knot),
        hit: ChordHit,
    ) -> Option<ChordHit> {
        let (point, normal) = world.supporting_plane(region, hit.object)?;
        let height = |x: Vec3| normal.dot(x - point);
        let (mut lo, mut hi) = ((a.theta, height(a.at)), (b.theta, height(b.at)));
        if !(lo.1 * hi.1 < 0.0) {
            return None;
        }
        let tolerance = CROSSING_TOLERANCE * self.epsilon;
        // The chord's crossing lies on the plane; the curve's point at its θ need not.
        let (mut theta, mut x) = (hit.theta, (step.knot)(hit.theta).at);
        let mut kept = 0;
        for _ in 0..64 {
            let h = height(x);
            if h.abs() <= tolerance {
                break;
            }
            // Keep the bracket; halve the weight of an end kept twice (Illinois).
            if (h > 0.0) == (lo.1 > 0.0) {
                lo = (theta, h);
                kept = if kept < 0 { kept - 1 } else { -1 };
                if kept < -1 {
                    hi.1 *= 0.5;
                }
            } else {
                hi = (theta, h);
                kept = if kept > 0 { kept + 1 } else { 1 };
                if kept > 1 {
                    lo.1 *= 0.5;
                }
            }
            theta = lo.0 - lo.1 * (hi.0 - lo.0) / (hi.1 - lo.1);
            x = (step.knot)(theta).at;
        }
        let dir = if height(a.at) > 0.0 { -normal } else { normal };
        let chord = Ray::new(x - self.epsilon * dir, dir, 2.0 * self.epsilon);
        let t = world.object(region, hit.object).shape.intersect(&chord)?;
        Some(ChordHit { object: hit.object, chord, t, theta })
    }

    /// The first hit on the piece of a step from knot `a` to knot `b`, whose position and velocity
    /// are `motion(θ)`, among the flat objects `blockers` that come near its tangent triangle:
    /// their planes' crossings solved on the curve, each checked against its object by a chord
    /// across the plane there. `None` where a plane may be crossed twice: the piece is split.
    pub(super) fn cross_flat(
        &self,
        world: &World,
        region: Region,
        motion: &dyn Fn(f64) -> (Vec3, Vec3),
        a: Knot,
        b: Knot,
        blockers: &FlatBlockers,
    ) -> Option<Option<ChordHit>> {
        let tolerance = CROSSING_TOLERANCE * self.epsilon;
        let mut first: Option<ChordHit> = None;
        for object in blockers.iter() {
            let (point, normal) = world.supporting_plane(region, object)?;
            let height = |x: Vec3| normal.dot(x - point);
            let (s_a, s_b) = (height(a.at), height(b.at));
            match Meeting::of(s_a, s_b, height(Vec3::ZERO)) {
                Meeting::Never => continue,
                Meeting::Maybe => return None,
                Meeting::Once => {}
            }
            // Still on the starting side where an earlier object is hit: this plane comes later.
            if first.is_some_and(|hit| (height(hit.chord.at(hit.t)) > 0.0) == (s_a > 0.0)) {
                continue;
            }
            let (theta, x) = crossing(motion, point, normal, (a.theta, a.at), (b.theta, b.at), tolerance);
            if first.is_some_and(|hit| hit.theta <= theta) {
                continue;
            }
            // Along the normal, from the side the piece starts on: a chord that crosses the plane
            // at the crossing however grazing the ray, and tells which side it came from.
            let dir = if s_a > 0.0 { -normal } else { normal };
            let chord = Ray::new(x - self.epsilon * dir, dir, 2.0 * self.epsilon);
            if let Some(t) = world.object(region, object).shape.intersect(&chord) {
                first = Some(ChordHit { object, chord, t, theta });
            }
        }
        Some(first)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::propagator::RayEnd;
    use crate::settings::Intersection;
    use crate::shape::offset_origin;
    use crate::test_scenes::{rectangles, uniform, ROOM};
    use spacetime::{Schwarzschild, Spacetime};

    /// No ray leaves a closed room: rays that leave a wall near one of its edges and graze the
    /// wall beside it (0.05° to 5°), where a crossing lies just past an edge and the curve runs
    /// along the next plane, within tolerance of it, all hit a wall.
    #[test]
    fn grazing_rays_do_not_leave_a_closed_room() {
        let world = rectangles(&ROOM);
        let hole = Spacetime::Schwarzschild(Schwarzschild::new(0.3));
        let propagator = Propagator::new(hole, 11.0, 1e-7, Intersection::Chord);
        let mut uniform = uniform(5);
        let half = Vec3::new(6.0, 4.0, 8.0);
        let mut hits = 0;
        for k in 0..20_000 {
            // A point of the back or front wall, within 0.2 of the left or right wall, leaving
            // into the room and skimming that side wall.
            let side = if uniform() < 0.5 { -1.0 } else { 1.0 };
            let face = if uniform() < 0.5 { -1.0 } else { 1.0 };
            let on_wall = Vec3::new(side * (6.0 - 0.2 * uniform()), 8.0 * uniform() - 4.0, face * 8.0);
            let graze = (0.05 + 4.95 * uniform()).to_radians();
            let climb = std::f64::consts::TAU * uniform();
            let (sin, cos) = graze.sin_cos();
            // Mostly along the side wall (y and z), a little towards it (x).
            let along = Vec3::new(0.0, climb.sin(), -face * climb.cos().abs().max(0.05)).normalize();
            let direction = (cos * along + sin * side * Vec3::X).normalize();
            let origin = offset_origin(on_wall, Vec3::Z, -face * Vec3::Z);
            match propagator.trace(&world, Region::Upper, origin, direction) {
                RayEnd::Hit(a) => {
                    assert!((a.hit.p.abs() - half).max_element() < 1e-6, "ray {k}: hit at {}", a.hit.p);
                    hits += 1;
                }
                RayEnd::Captured => {}
                end => panic!("ray {k} from {origin:?} along {direction:?}: {end:?}"),
            }
        }
        assert!(hits > 19_000, "{hits} hits");
        // A ray from the black-hole room's back wall that skims its left wall up to the ceiling,
        // bending back to end a step 4·10⁻⁶ past the wall's plane and above the ceiling, once
        // escaped (a crossing was taken where the ray ran within tolerance of the plane, far
        // past where it crossed); and rays near it.
        let origin = Vec3::new(-5.9457814556959825, 1.2914639215015402, -7.999999992);
        let direction = Vec3::new(-0.022994719906528252, 0.915631263411206, 0.4013609750840494);
        for k in 0..2000 {
            let turn = if k == 0 { Vec3::ZERO } else { 1e-3 * (Vec3::new(uniform(), uniform(), uniform()) - 0.5) };
            let direction = (direction + turn).normalize();
            match propagator.trace(&world, Region::Upper, origin, direction) {
                RayEnd::Hit(a) => assert!((a.hit.p.abs() - half).max_element() < 1e-6, "ray {k}: hit at {}", a.hit.p),
                end => panic!("ray {k} along {direction:?}: {end:?}"),
            }
        }
    }

    /// Rays that leave the face of a board turned away from the hole bend back through the
    /// board's plane: they are found where they come back, not where they left (Newton's step
    /// at a ray's offset start points back to it), as chords 64 times closer to the curve find
    /// them.
    #[test]
    fn rays_bending_back_through_the_board_they_leave_hit_it_where_they_return() {
        // A board 1 below the hole, facing down (away from it), and a floor further down.
        let world = rectangles(&[
            [[-6.0, -1.0, -6.0], [12.0, 0.0, 0.0], [0.0, 0.0, 12.0]],
            [[-6.0, -8.0, 6.0], [12.0, 0.0, 0.0], [0.0, 0.0, -12.0]],
        ]);
        let hole = Spacetime::Schwarzschild(Schwarzschild::new(0.3));
        let bounded = Propagator::new(hole, 11.0, 1e-7, Intersection::Chord);
        let fine = Propagator { bound_arcs: false, epsilon: bounded.epsilon / 64.0, ..bounded.clone() };
        let mut uniform = uniform(17);
        let mut back_on_board = 0;
        for k in 0..500 {
            let on_board = Vec3::new(3.0 * uniform() - 1.5, -1.0, 3.0 * uniform() - 1.5);
            let (dip, heading) = ((0.5 + 9.5 * uniform()).to_radians(), std::f64::consts::TAU * uniform());
            let direction = Vec3::new(dip.cos() * heading.cos(), -dip.sin(), dip.cos() * heading.sin());
            let origin = offset_origin(on_board, Vec3::Y, -Vec3::Y);
            match (
                bounded.trace(&world, Region::Upper, origin, direction),
                fine.trace(&world, Region::Upper, origin, direction),
            ) {
                (RayEnd::Hit(a), RayEnd::Hit(b)) => {
                    assert_eq!(a.object, b.object, "ray {k} from {origin} along {direction}");
                    // The fine chords' own error on a plane met at a slant: ε/64 over the sine.
                    let (off, sine) = ((a.hit.p - b.hit.p).length(), a.direction.dot(a.ng_local).abs());
                    let bound = bounded.epsilon() * (0.01 + 2.0 / (64.0 * sine));
                    assert!(off < bound, "ray {k} from {origin} along {direction}: {off} (sine {sine})");
                    back_on_board += usize::from(a.object == 0);
                }
                (a, b) => assert!(
                    matches!(
                        (a, b),
                        (RayEnd::Escaped { .. }, RayEnd::Escaped { .. }) | (RayEnd::Captured, RayEnd::Captured)
                    ),
                    "ray {k} from {origin} along {direction}: {a:?} vs {b:?}"
                ),
            }
        }
        // Measured: 467 of the 500 come back to the board.
        assert!(back_on_board > 400, "{back_on_board} rays came back to the board");
    }
}

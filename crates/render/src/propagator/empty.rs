//! The room about the centre that no object reaches into: a ball ([`World::empty_radius`]) and a
//! box ([`World::empty_box`]). A piece of ray that stays inside either, with a margin ε, has
//! nothing in its way, and is cleared without a query of the scene.

use super::Propagator;
use crate::geometry::Vec3;
use crate::world::World;
use spacetime::Region;

impl Propagator {
    /// Whether the piece of a ray between world points `a` and `b` stays, with a margin ε, inside
    /// the ball about the centre that no object of `region` reaches into, so that nothing can be
    /// in its way. Beyond the radius [`Capabilities::no_turning_beyond`] (the photon sphere) a
    /// ray never reaches a greatest distance from the centre: a piece of it is no farther out
    /// than its farther end, or than that radius.
    pub fn in_empty_ball(&self, world: &World, region: Region, a: Vec3, b: Vec3) -> bool {
        let Some(turning) = self.no_turning_beyond else { return false };
        let radius = world.empty_radius(region) - self.epsilon;
        turning < radius && a.length_squared().max(b.length_squared()) < radius * radius
    }

    /// Whether a triangle stays, with a margin ε, inside the box about the centre that no object
    /// of `region` reaches into ([`World::empty_box`]): the box is convex, so a piece of ray the
    /// triangle holds has nothing in its way. Inside a room round the hole this clears pieces
    /// that the ball cannot (it only reaches the nearest wall or lamp) without a query of the
    /// scene.
    pub(super) fn in_empty_box(&self, world: &World, region: Region, corners: &[Vec3; 3]) -> bool {
        world.empty_box(region).is_some_and(|empty| {
            let (min, max) = (empty.min + self.epsilon, empty.max - self.epsilon);
            corners.iter().all(|c| c.cmpgt(min).all() && c.cmplt(max).all())
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::propagator::RayEnd;
    use crate::rgb::Rgb;
    use crate::settings::Intersection;
    use crate::shape::Shape;
    use crate::sky::Sky;
    use crate::test_scenes::{floor_lamp_board_ball, rectangles, uniform, ROOM};
    use crate::world::Object;
    use spacetime::{Schwarzschild, Spacetime};

    /// A speck at the centre, inside the horizon: no ray reaches it, but it takes the empty ball
    /// and box away.
    const SPECK: [[f64; 3]; 3] = [[-0.01, -0.01, 0.0], [0.02, 0.0, 0.0], [0.0, 0.02, 0.0]];

    /// The room's walls and its lamp, 0.02 below the ceiling, with `extra` rectangles.
    fn lit_room(extra: &[[[f64; 3]; 3]]) -> World {
        let lamp = [[-2.5, 3.98, -2.5], [5.0, 0.0, 0.0], [0.0, 0.0, 5.0]];
        rectangles(&[&ROOM[..], &[lamp], extra].concat())
    }

    /// No object reaches into the ball about the centre of radius `empty_radius`: the room's
    /// lamp hangs 3.98 from it; the board of the test scene passes through its plane, but its
    /// box keeps 1 away.
    #[test]
    fn the_empty_ball_reaches_the_nearest_object() {
        assert_eq!(floor_lamp_board_ball().empty_radius(Region::Upper), 1.0);
        let room = lit_room(&[]);
        assert!((room.empty_radius(Region::Upper) - 3.98).abs() < 1e-12);
        assert_eq!(floor_lamp_board_ball().empty_radius(Region::Lower), f64::INFINITY);
    }

    /// The empty box about the centre is the room's inside below its lamp; it is cut short where
    /// objects stand nearer (the test scene's board, 1 along x, and ball), and there is none where
    /// an object's box holds the centre.
    #[test]
    fn the_empty_box_is_the_inside_of_the_room() {
        let room = lit_room(&[]).empty_box(Region::Upper).unwrap();
        assert_eq!((room.min, room.max), (Vec3::new(-6.0, -4.0, -8.0), Vec3::new(6.0, 3.98, 8.0)));
        let scene = floor_lamp_board_ball().empty_box(Region::Upper).unwrap();
        let infinity = f64::INFINITY;
        assert_eq!((scene.min, scene.max), (Vec3::new(-infinity, -4.0, -infinity), Vec3::new(1.0, 3.98, 2.0)));
        assert!(lit_room(&[SPECK]).empty_box(Region::Upper).is_none());
    }

    /// Pieces of rays that the empty box clears find exactly the hits they find where a speck at
    /// the centre, inside the horizon, takes the box and the ball away: on rays from all over the
    /// room, many of them to the lamp, whose plane bounds the box 0.02 below the ceiling's.
    #[test]
    fn rays_cleared_by_the_empty_box_find_the_hits_they_find_without_it() {
        let with_box = lit_room(&[]);
        let without = lit_room(&[SPECK]);
        assert!(without.empty_box(Region::Upper).is_none() && without.empty_radius(Region::Upper) < 0.6);
        let hole = Spacetime::Schwarzschild(Schwarzschild::new(0.3));
        let propagator = Propagator::new(hole, 11.0, 1e-7, Intersection::Chord);
        let mut uniform = uniform(13);
        let mut on_lamp = 0;
        for k in 0..2000 {
            let origin = Vec3::new(11.0 * uniform() - 5.5, 7.0 * uniform() - 3.5, 15.0 * uniform() - 7.5);
            let z = 2.0 * uniform() - 1.0;
            let (sin, cos) = (std::f64::consts::TAU * uniform()).sin_cos();
            let direction = Vec3::new((1.0 - z * z).sqrt() * cos, z, (1.0 - z * z).sqrt() * sin);
            match (
                propagator.trace(&with_box, Region::Upper, origin, direction),
                propagator.trace(&without, Region::Upper, origin, direction),
            ) {
                (RayEnd::Hit(a), RayEnd::Hit(b)) => {
                    assert_eq!((a.object, a.hit.p), (b.object, b.hit.p), "ray {k} from {origin} along {direction}");
                    on_lamp += usize::from(a.object == ROOM.len());
                }
                (RayEnd::Captured, RayEnd::Captured) => {}
                (a, b) => panic!("ray {k} from {origin} along {direction}: {a:?} vs {b:?}"),
            }
        }
        assert!(on_lamp > 50, "{on_lamp} rays reached the lamp");
    }

    /// Pieces of rays inside the empty ball are not tested against the scene: rays through it find
    /// exactly the hits they find where a speck inside the horizon (never reached, but closer
    /// than the photon sphere) turns that off. The board's edge lies just outside the ball, 0.1
    /// beyond the photon sphere, so rays that wind round the hole meet it on leaving the ball.
    #[test]
    fn rays_through_the_empty_ball_find_the_hits_they_find_without_it() {
        let with_ball = floor_lamp_board_ball();
        let mut objects = with_ball.objects(Region::Upper).to_vec();
        let t = crate::transform::Transform::identity();
        let black = || Sky::Constant(Rgb::ZERO);
        let speck = Shape::rectangle(Vec3::new(0.1, 0.1, 0.1), Vec3::X * 0.01, Vec3::Y * 0.01, &t).unwrap();
        objects.push(Object { shape: speck, material: 0, emission: None });
        let without = World::new(with_ball.materials.clone(), (objects, black()), (Vec::new(), black()));
        assert!(without.empty_radius(Region::Upper) < 0.6);
        let propagator =
            Propagator::new(Spacetime::Schwarzschild(Schwarzschild::new(0.3)), 11.0, 1e-7, Intersection::Chord);
        let mut uniform = uniform(5);
        let (mut compared, mut near_board) = (0, 0);
        for k in 0..3000 {
            let origin = Vec3::new(10.0 * uniform() - 5.0, 6.0 * uniform() - 3.0, 14.0 * uniform() - 7.0);
            if origin.length() < 1.5 {
                continue;
            }
            // Impact parameters just above the critical 3√3 M = 1.56: the rays pass the hole
            // between the photon sphere and r ≈ 1.3, most of them inside the ball (b < 1.62).
            let b = 1.56 + 0.1 * uniform();
            let (r, inward) = (origin.length(), -origin.normalize());
            let across = inward.cross(Vec3::new(uniform() - 0.5, uniform() - 0.5, uniform() - 0.5)).normalize();
            let sin = b * (1.0 - 0.6 / r).sqrt() / r;
            let direction = inward * (1.0 - sin * sin).sqrt() + across * sin;
            let (a, b) = (
                propagator.trace(&with_ball, Region::Upper, origin, direction),
                propagator.trace(&without, Region::Upper, origin, direction),
            );
            match (a, b) {
                (RayEnd::Hit(a), RayEnd::Hit(b)) => {
                    assert_eq!((a.object, a.hit.p), (b.object, b.hit.p), "ray {k} from {origin} along {direction}");
                    near_board += usize::from(a.object == 2 && a.hit.p.length() < 1.5);
                    compared += 1;
                }
                (RayEnd::Escaped { direction: a, .. }, RayEnd::Escaped { direction: b, .. }) => {
                    assert_eq!(a, b, "ray {k}");
                }
                (RayEnd::Captured, RayEnd::Captured) => {}
                (a, b) => panic!("ray {k} from {origin} along {direction}: {a:?} vs {b:?}"),
            }
        }
        assert!(
            compared > 1000 && near_board > 20,
            "{compared} hits compared, {near_board} on the board near the ball"
        );
    }
}

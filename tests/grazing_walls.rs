//! Rays leaving the walls of the poster's closed room as diffuse bounces do, bent towards the
//! hole as they go, arrive on the side of the wall they came from. (A chord may cross a wall that
//! the curve grazes by less than ε before turning back; the arrival direction must then not point
//! out of the wall, or the path continues behind it and leaks out of the closed room. This
//! happened to about one bounce in 10⁵ before arrivals were put on their chord's side.)

#![allow(clippy::unwrap_used)] // A panic is a failed test.

use render::geometry::{Frame, Vec3};
use render::propagator::RayEnd;
use render::sampling::{cosine_hemisphere, Rng};
use spacetime::Region;

/// The six walls (the room's first six objects); the ceiling lamp, whose back faces the ceiling,
/// is met from behind by rays squeezing between them, and is left out.
const WALLS: usize = 6;

#[test]
fn bounces_off_the_walls_meet_walls_from_inside_the_room() {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/room-black-hole.toml");
    let scene = scene::load(&path).unwrap();
    let propagator = render::renderer::propagator(&scene);
    let walls = scene.world.objects(Region::Upper);
    let mut rng = Rng::new(17);
    let (mut hits, mut from_behind) = (0, Vec::new());
    // A bounce off the back wall that leaked (its chord met the right wall just past the turn of
    // its curve), then 200 000 random ones.
    let leaked = (
        Vec3::new(5.4256551056385085, -1.162659784761976, -7.999999992),
        Vec3::new(0.08942636583842625, 0.3537177347055243, 0.9310674998343161),
    );
    for k in 0..=200_000 {
        let (origin, direction) = if k == 0 {
            leaked
        } else {
            let (p, n) = walls[k % WALLS].shape.sample_area(rng.next_2d());
            let local = propagator.local_normal(Region::Upper, p, n);
            (p + n * 8e-9, Frame::from_normal(local).to_world(cosine_hemisphere(rng.next_2d())))
        };
        match propagator.trace(&scene.world, Region::Upper, origin, direction) {
            RayEnd::Hit(a) if a.object < WALLS => {
                hits += 1;
                if a.direction.dot(a.ng_local) >= 0.0 {
                    from_behind.push((origin, direction, a.hit.p));
                }
            }
            RayEnd::Escaped { .. } => panic!("a ray from {origin} along {direction} left the closed room"),
            _ => {}
        }
    }
    assert!(hits > 140_000, "only {hits} rays met a wall");
    assert!(from_behind.is_empty(), "{} rays arrived from behind a wall, e.g. {:?}", from_behind.len(), from_behind[0]);
}

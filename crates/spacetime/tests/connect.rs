//! The two-point connection against flat space (mass → 0) and against a bundle of rays traced
//! by the in-plane tracer, whose spread on a plane through the end point measures `dA⊥/dΩ`.

#![allow(clippy::unwrap_used)] // A panic is a failed test.

use spacetime::geodesic::plane::{trace_plane, PlaneStart, PlaneStep, Way};
use spacetime::metric::schwarzschild::connect::{Connection, Connector, Waypoints};
use spacetime::tensor::{cross3, dot3, norm3, normalize3};
use spacetime::{Region, Schwarzschild, Stepping, TraceSettings, Visit};

/// Start and end points: near and far, weak and strong bending, sweeps from 0.1 to 3.1 rad.
const PAIRS: [([f64; 3], [f64; 3]); 6] = [
    ([10.0, 0.0, 0.0], [9.0, 1.0, 0.5]),
    ([6.0, 2.0, -1.0], [-3.0, 7.0, 2.0]),
    ([4.0, -4.0, 0.0], [-4.5, 3.9, 0.2]),
    ([0.0, -4.0, 1.0], [0.3, 3.98, -0.2]),
    ([20.0, 5.0, 3.0], [-15.0, -2.0, -1.0]),
    ([3.5, 0.0, 0.0], [-12.0, 0.5, 0.0]),
];

fn sub(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    std::array::from_fn(|i| a[i] - b[i])
}

fn distance(a: [f64; 3], b: [f64; 3]) -> f64 {
    norm3(&sub(a, b))
}

/// One connector for the tests of this file, so its tables are built once; each test takes it
/// for its hole with [`Connector::for_hole`].
fn connector() -> &'static Connector {
    static CONNECTOR: std::sync::OnceLock<Connector> = std::sync::OnceLock::new();
    CONNECTOR.get_or_init(|| Connector::new(Schwarzschild::new(1.0)))
}

#[test]
fn without_mass_the_connection_is_the_straight_line_with_density_one_over_d_squared() {
    for mass in [0.0, 1e-9] {
        let hole = Schwarzschild::new(mass);
        for (x, y) in PAIRS {
            let d = distance(x, y);
            // Straight lines sweep less than π: there is no long way round. The least mass has
            // one, round its photon sphere at 3·10⁻⁹, whose image of `y` is vanishingly small.
            if let Some(long) = connector().for_hole(hole).connect(x, y, Way::Long) {
                assert!(mass > 0.0 && long.solid_angle_per_area * d * d < 1e-12, "{x:?} → {y:?}");
            }
            let c = connector().for_hole(hole).connect(x, y, Way::Short).unwrap();
            let line = normalize3(&sub(y, x));
            // Mass 1e-9 bends by ~4M/b ≲ 1e-9 rad and changes the density by as little; the
            // short way integrates to a relative 1e-6 per step and stops at a miss of 1e-6 in 1/r.
            let tol = 1e-5;
            assert!(distance(c.start, line) < tol, "M = {mass}, {x:?} → {y:?}: start {:?}", c.start);
            assert!(distance(c.end, line) < tol && distance(c.end_tangent, line) < tol);
            let rel = c.solid_angle_per_area * d * d - 1.0;
            assert!(rel.abs() < tol, "M = {mass}, {x:?} → {y:?}: dΩ/dA⊥ · d² − 1 = {rel:e}");
        }
    }
}

/// Where the ray leaving `x` along the static-frame direction `n` crosses the plane through `y`
/// with normal `t` (in the direction of `t`, within `r_y/10` of `y`: a ray going round the hole
/// may cross the plane elsewhere first), and its static-frame direction there.
fn crossing(hole: &Schwarzschild, x: [f64; 3], n: [f64; 3], y: [f64; 3], t: [f64; 3]) -> ([f64; 3], [f64; 3]) {
    let settings = TraceSettings { stepping: Stepping::Adaptive { rtol: 1e-12 }, ..TraceSettings::default() };
    let start = PlaneStart::from_observer(hole, Region::Upper, x, n).unwrap();
    let mut found = None;
    trace_plane(hole, start, &settings, |step: &PlaneStep| {
        let side = |theta: f64| dot3(&sub(step.point(hole, theta).position, y), &t);
        if !(side(0.0) < 0.0 && side(1.0) >= 0.0) {
            return Visit::Continue;
        }
        let (mut lo, mut hi) = (0.0, 1.0);
        for _ in 0..80 {
            let mid = 0.5 * (lo + hi);
            if side(mid) < 0.0 {
                lo = mid;
            } else {
                hi = mid;
            }
        }
        let p = step.point(hole, 0.5 * (lo + hi));
        if distance(p.position, y) > 0.1 * norm3(&y) {
            return Visit::Continue;
        }
        found = Some((p.position, p.direction));
        Visit::Stop
    });
    found.unwrap()
}

/// The connection from `x` to `y` going `way` round reaches `y` along the reported directions,
/// and its density matches the spread of a traced ray bundle.
fn assert_matches_traced_bundle(hole: &Schwarzschild, x: [f64; 3], y: [f64; 3], way: Way) {
    let c: Connection = connector().for_hole(*hole).connect(x, y, way).unwrap();

    let sweep = c.swept;
    assert_eq!(Way::of_sweep(sweep), Some(way), "{x:?} → {y:?}: swept {sweep}");
    let t = c.end_tangent;
    // The connecting ray reaches y, arriving along the reported directions.
    let (hit, direction) = crossing(hole, x, c.start, y, t);
    // The shooting stops at a relative miss of 1e-6 in 1/r (its last Newton step's second-order
    // term, not shot again), the short way's steps integrated to a relative 1e-6: within 1e-5,
    // a tenth of the chord tolerance ε (1e-4 of the scene's radius) the tracer finds hits to.
    assert!(distance(hit, y) < 1e-5 * norm3(&y), "{x:?} → {y:?} {way:?}: reaches {hit:?}");
    assert!(distance(direction, c.end) < 1e-5, "{x:?} → {y:?} {way:?}: arrives along {direction:?}, not {:?}", c.end);
    // A cone of four rays at angle δ around the start direction: central differences of their
    // crossings give the beam's cross-section per solid angle.
    let a = normalize3(&cross3(&c.start, &[0.3, 0.5, 0.8]));
    let b = cross3(&c.start, &a);
    // Long-way rays wind near the photon sphere, where the bundle changes on angular scales of
    // e^(−sweep): δ must be far smaller than that for central differences to hold.
    let delta = 1e-6;
    let spread = |e: [f64; 3]| {
        let ray = |sign: f64| normalize3(&std::array::from_fn(|i| c.start[i] + sign * delta * e[i]));
        let (plus, _) = crossing(hole, x, ray(1.0), y, t);
        let (minus, _) = crossing(hole, x, ray(-1.0), y, t);
        std::array::from_fn::<f64, 3, _>(|i| (plus[i] - minus[i]) / (2.0 * delta))
    };
    let area_per_solid_angle = norm3(&cross3(&spread(a), &spread(b)));
    let ratio = c.solid_angle_per_area * area_per_solid_angle;
    // Tracing noise 1e-12 · r / δ ≈ 1e-5 at most (seen: ≤ 1.3e-6); the shooting's own tolerance,
    // 1e-6 per step the short way, 1e-7 the long way.
    assert!((ratio - 1.0).abs() < 1e-5, "{x:?} → {y:?} (sweep {sweep}): measured/predicted = {ratio}");
}

#[test]
fn density_matches_the_spread_of_a_traced_ray_bundle() {
    let hole = Schwarzschild::new(1.0);
    for ((x, y), way) in PAIRS.into_iter().flat_map(|pair| Way::BOTH.map(|way| (pair, way))) {
        assert_matches_traced_bundle(&hole, x, y, way);
    }
}

/// Shading points on the walls, the floor and in the air of the black-hole room
/// (`scenes/room-black-hole.toml`, M = 0.3) joined to points of its ceiling lamp, as next-event
/// estimation joins them: mostly weak bending, where the first guess is close and one coarse and
/// one fine shot suffice, and rays grazing the hole.
#[test]
fn room_connections_match_traced_ray_bundles() {
    let hole = Schwarzschild::new(0.3);
    let lamp = [[0.0, 3.98, 0.0], [-2.4, 3.98, 2.4], [2.0, 3.98, -1.0]];
    let shading = [[-5.0, -4.0, 6.0], [0.1, -4.0, 0.2], [6.0, 1.0, -7.0], [0.5, -3.0, -8.0], [0.2, -1.0, 0.1]];
    for (x, y) in shading.into_iter().flat_map(|x| lamp.map(|y| (x, y))) {
        for way in Way::BOTH {
            assert_matches_traced_bundle(&hole, x, y, way);
        }
    }
}

#[test]
fn degenerate_pairs_have_no_connection() {
    let hole = Schwarzschild::new(1.0);
    // Inside the horizon, and on one line through the centre (no plane, no sweep).
    for way in Way::BOTH {
        assert!(connector().for_hole(hole).connect([1.0, 0.0, 0.0], [10.0, 0.0, 0.0], way).is_none());
        assert!(connector().for_hole(hole).connect([5.0, 0.0, 0.0], [10.0, 0.0, 0.0], way).is_none());
        assert!(connector().for_hole(hole).connect([5.0, 0.0, 0.0], [-10.0, 0.0, 0.0], way).is_none());
    }
    // Inside the photon sphere (r < 3M) a static observer has no critical angle to wind at.
    assert!(connector().for_hole(hole).connect([2.5, 0.0, 0.0], [0.0, 10.0, 0.0], Way::Long).is_none());
}

/// Uniform numbers in `[0, 1)` from a seeded 64-bit linear congruential generator.
fn uniform(seed: u64) -> impl FnMut() -> f64 {
    let mut state = seed;
    move || {
        state = state.wrapping_mul(6_364_136_223_846_793_005).wrapping_add(1_442_695_040_888_963_407);
        (state >> 11) as f64 / (1u64 << 53) as f64
    }
}

/// A uniform point of the black-hole room's box (`scenes/room-black-hole.toml`).
fn in_room(uniform: &mut impl FnMut() -> f64) -> [f64; 3] {
    [12.0 * uniform() - 6.0, 8.0 * uniform() - 4.0, 16.0 * uniform() - 8.0]
}

/// `n` random pairs of points in the black-hole room (M = 0.3), then the strong-bending pairs of
/// [`PAIRS`] (M = 1).
fn test_pairs(seed: u64, n: usize) -> Vec<(Schwarzschild, [f64; 3], [f64; 3])> {
    let mut uniform = uniform(seed);
    let room = Schwarzschild::new(0.3);
    let mut pairs: Vec<_> = (0..n).map(|_| (room, in_room(&mut uniform), in_room(&mut uniform))).collect();
    pairs.extend(PAIRS.map(|(x, y)| (Schwarzschild::new(1.0), x, y)));
    pairs
}

/// Points of the ray leaving `x` along the static-frame direction `n`, every tenth of a step,
/// until it has swept `sweep` about the centre.
fn ray_points(hole: &Schwarzschild, x: [f64; 3], n: [f64; 3], sweep: f64) -> Vec<[f64; 3]> {
    let settings = TraceSettings { stepping: Stepping::Adaptive { rtol: 1e-12 }, ..TraceSettings::default() };
    let start = PlaneStart::from_observer(hole, Region::Upper, x, n).unwrap();
    let mut points = Vec::new();
    trace_plane(hole, start, &settings, |step: &PlaneStep| {
        for k in 0..10 {
            let theta = f64::from(k) / 10.0;
            if step.azimuth(theta).unwrap() > sweep {
                return Visit::Stop;
            }
            points.push(step.point(hole, theta).position);
        }
        Visit::Continue
    });
    points
}

/// How far `p` lies outside the triangle `[a, b, c]`: its distance from the triangle's plane or
/// beyond the nearest of its edges, whichever is larger (0 inside).
fn outside(p: [f64; 3], [a, b, c]: [[f64; 3]; 3]) -> f64 {
    let normal = normalize3(&cross3(&sub(b, a), &sub(c, a)));
    let mut worst = dot3(&sub(p, a), &normal).abs();
    for (from, to) in [(a, b), (b, c), (c, a)] {
        // Distance beyond the edge, in the plane: positive on the side away from the triangle.
        let out = normalize3(&cross3(&sub(to, from), &normal));
        worst = worst.max(dot3(&sub(p, from), &out));
    }
    worst
}

/// The triangle of a connection's chord and end tangents holds the whole ray: the tangent at the
/// start is the ray's world tangent, and the ray bends one way by less than π. Pairs from the
/// black-hole room and the strong-bending pairs above (M = 1).
#[test]
fn the_short_way_round_lies_in_the_triangle_of_its_chord_and_end_tangents() {
    let (mut tried, mut bounded) = (0, 0);
    for (hole, x, y) in test_pairs(0x2545_f491_4f6c_dd1d, 200) {
        let Some(c) = connector().for_hole(hole).connect(x, y, Way::Short) else { continue };
        tried += 1;
        let Some(triangle) = c.enclosing_triangle(x, y) else { continue };
        bounded += 1;
        assert_eq!((triangle[0], triangle[2]), (x, y));
        let scale = norm3(&sub(y, x));
        for p in ray_points(&hole, x, c.start, c.swept) {
            // The ray misses y by up to 1e-5 r (the shooting's tolerance).
            let out = outside(p, triangle);
            assert!(out < 1e-5 * scale, "{x:?} → {y:?}: {p:?} lies {out:e} outside {triangle:?}");
        }
    }
    // Only rays turning by π or more, round the photon sphere, have no triangle.
    assert!(tried > 150 && bounded as f64 > 0.95 * tried as f64, "{bounded} of {tried} bounded");
}

/// The chain of triangles between a connection's waypoints holds the whole ray, either way
/// round: every traced point lies in one of them.
#[test]
fn both_ways_round_lie_in_the_triangles_between_their_waypoints() {
    let pairs = test_pairs(0x9e37_79b9_7f4a_7c15, 100);
    for way in Way::BOTH {
        let (mut tried, mut bounded, mut pieces) = (0, 0, 0);
        for &(hole, x, y) in &pairs {
            let mut waypoints = Waypoints::default();
            let Some(c) = connector().for_hole(hole).connect_along(x, y, way, None, &mut waypoints) else { continue };
            tried += 1;
            let Some(triangles) = c.enclosing_triangles(&waypoints, x, y).collect::<Option<Vec<_>>>() else { continue };
            bounded += 1;
            pieces += triangles.len();
            assert_eq!((triangles[0][0], triangles[triangles.len() - 1][2]), (x, y));
            let scale = norm3(&sub(y, x));
            for p in ray_points(&hole, x, c.start, c.swept) {
                let out = triangles.iter().map(|t| outside(p, *t)).fold(f64::INFINITY, f64::min);
                assert!(out < 1e-5 * scale, "{x:?} → {y:?} {way:?}: {p:?} lies {out:e} outside all");
            }
        }
        assert!(tried > 50 && bounded as f64 > 0.95 * tried as f64, "{way:?}: {bounded} of {tried} bounded");
        // The long way winds round the hole in several pieces.
        assert!(way == Way::Short || pieces > 3 * bounded, "{pieces} pieces for {bounded} rays");
    }
}

/// Joining a one-sided surface drops exactly the rays that reach it from behind: every ray it
/// keeps is the one `connect` finds, and every ray arriving from the front is kept.
#[test]
fn rays_reaching_a_one_sided_surface_from_behind_are_dropped() {
    let hole = Schwarzschild::new(0.3);
    let mut uniform = uniform(0x0123_4567_89ab_cdef);
    let (mut dropped, mut behind) = (0, 0);
    for _ in 0..300 {
        let (x, y) = (in_room(&mut uniform), in_room(&mut uniform));
        let normal = normalize3(&[uniform() - 0.5, uniform() - 0.5, uniform() - 0.5]);
        for way in Way::BOTH {
            let Some(full) = connector().for_hole(hole).connect(x, y, way) else { continue };
            let from_behind = dot3(&normal, &full.end_tangent) > 0.0;
            behind += usize::from(from_behind);
            match connector().for_hole(hole).connect_along(x, y, way, Some(normal), &mut Waypoints::default()) {
                Some(kept) => assert_eq!(kept, full, "{x:?} → {y:?} {way:?}"),
                None => {
                    dropped += 1;
                    assert!(from_behind, "{x:?} → {y:?} {way:?}: a ray from the front was dropped");
                }
            }
        }
    }
    // Half the rays arrive from behind; all but those within the margin of grazing are dropped.
    assert!(behind > 200 && dropped as f64 > 0.95 * behind as f64, "{dropped} of {behind} dropped");
}

/// The short way from a point behind a plane never reaches the plane from the front while the
/// centre lies on its front side (the proof at `connect::short_way_arrives_behind`), so
/// `connect_along` drops those pairs before shooting. Every such ray found without the check
/// arrives from behind, and the reversed ray leaves `y` into the back, in the room and on the
/// strong-bending pairs; with the centre behind the plane too, rays from behind do reach it from
/// the front, so the centre's side matters.
#[test]
fn the_short_way_from_behind_a_plane_facing_the_centre_arrives_behind_it() {
    let mut uniform = uniform(0x05ee_d0f9_1a9e);
    let (mut checked, mut round_to_front) = (0, 0);
    for (hole, x, y) in test_pairs(23, 3000) {
        for _ in 0..4 {
            let n = normalize3(&[uniform() - 0.5, uniform() - 0.5, uniform() - 0.5]);
            if dot3(&n, &sub(x, y)) >= 0.0 {
                continue;
            }
            let Some(ray) = connector().for_hole(hole).connect(x, y, Way::Short) else { continue };
            let arrival = dot3(&n, &ray.end_tangent);
            if dot3(&n, &y) <= 0.0 {
                checked += 1;
                assert!(arrival > -1e-9, "{x:?} → {y:?}, normal {n:?}: arrives from the front ({arrival})");
                assert_eq!(
                    connector().for_hole(hole).connect_along(x, y, Way::Short, Some(n), &mut Waypoints::default()),
                    None
                );
                // Reversed, the ray leaves `y` into the back: an opaque surface there reflects none.
                let back = connector().for_hole(hole).connect(y, x, Way::Short).unwrap();
                let leaving = dot3(&n, &back.start_tangent);
                assert!(leaving < 1e-9, "{y:?} → {x:?}, normal {n:?}: leaves into the front ({leaving})");
            } else if arrival < 0.0 {
                round_to_front += 1;
            }
        }
    }
    // Measured: 1510 checked, 297 round to the front.
    assert!(checked > 1000 && round_to_front > 100, "{checked} checked, {round_to_front} round to the front");
}

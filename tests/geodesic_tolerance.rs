//! The render's default geodesic tolerance is derived from the chord tolerance ε: loose enough
//! to be cheap, tight enough that rays in the poster's room go where a far tighter integration
//! (1e-11) puts them, to well within ε.

#![allow(clippy::unwrap_used)] // A panic is a failed test.

use render::geometry::{Aabb, Vec3};
use render::propagator::RayEnd;
use render::scene::Scene;
use render::settings::RenderSettings;
use spacetime::geodesic::plane::{trace_plane, PlaneStart};
use spacetime::{Region, Schwarzschild, Spacetime, Stepping, TraceSettings, Visit};
use std::collections::BTreeMap;

/// The reference tolerance.
const TIGHT: f64 = 1e-11;

fn room() -> Scene {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/room-black-hole.toml");
    scene::load(&path).unwrap()
}

/// A ray: where it starts and its direction.
type Start = (Vec3, Vec3);

/// The camera's rays through the pixel centres of a 64 × 48 image.
fn camera_rays(scene: &Scene) -> Vec<Start> {
    let (width, height) = (64, 48);
    (0..height)
        .flat_map(|y| (0..width).map(move |x| (x, y)))
        .map(|(x, y)| {
            let r = scene.camera.ray([x, y], [0.0; 2], [width, height], [0.5, 0.5]).unwrap();
            (r.origin, r.direction)
        })
        .collect()
}

/// Rays a path sends on from surfaces: fans over the hemisphere (up to 80° from the normal) from
/// points just above the floor and just in front of the back wall.
fn bounce_rays() -> Vec<Start> {
    let fan = |from: Vec3, normal_axis: usize| {
        (0..24).flat_map(move |i| {
            (1..6).map(move |j| {
                let (phi, theta) = (f64::from(i) * std::f64::consts::TAU / 24.0, f64::from(j) * 0.28);
                let (a, b, n) = (theta.sin() * phi.cos(), theta.sin() * phi.sin(), theta.cos());
                let dir = if normal_axis == 1 { Vec3::new(a, n, b) } else { Vec3::new(a, b, n) };
                (from, dir)
            })
        })
    };
    let floor = [Vec3::new(-3.0, -3.95, 2.0), Vec3::new(1.5, -3.95, -4.0)].into_iter().flat_map(move |p| fan(p, 1));
    floor.chain(fan(Vec3::new(0.5, 1.0, -7.95), 2)).collect()
}

/// For each ray that hits a surface at both `rtol` and [`TIGHT`]: the distance between the two
/// hit points, and their separation across the ray (the distance along it is the chord test's
/// resolution of a surface met at a grazing angle, not a position error). Rays whose ends differ
/// in kind (a hit against a capture) are counted apart.
fn hit_differences(scene: &Scene, rays: &[Start], rtol: f64) -> (f64, f64, usize) {
    let propagator = |rtol: f64| {
        let mut s = scene.clone();
        s.settings.geodesic_rtol = rtol;
        render::renderer::propagator(&s)
    };
    let (test, reference) = (propagator(rtol), propagator(TIGHT));
    let (mut distance, mut across, mut mismatches) = (0.0f64, 0.0f64, 0);
    for &(from, dir) in rays {
        match (
            test.trace(&scene.world, Region::Upper, from, dir),
            reference.trace(&scene.world, Region::Upper, from, dir),
        ) {
            (RayEnd::Hit(a), RayEnd::Hit(b)) => {
                let d = a.hit.p - b.hit.p;
                distance = distance.max(d.length());
                across = across.max((d - d.dot(b.direction) * b.direction).length());
            }
            (RayEnd::Captured, RayEnd::Captured) => {}
            _ => mismatches += 1,
        }
    }
    (distance, across, mismatches)
}

/// Azimuth between the points compared along a ray.
const DPHI: f64 = 0.002;

/// Points of a ray at every multiple of [`DPHI`] in azimuth while it stays inside `room`.
fn path(hole: &Schwarzschild, settings: &TraceSettings, room: Aabb, (from, dir): Start) -> BTreeMap<i64, Vec3> {
    let mut points = BTreeMap::new();
    let Some(start) = PlaneStart::from_observer(hole, Region::Upper, from.to_array(), dir.to_array()) else {
        return points;
    };
    trace_plane(hole, start, settings, |step| {
        let (Some(a), Some(b)) = (step.azimuth(0.0), step.azimuth(1.0)) else { return Visit::Stop };
        let mut k = (a / DPHI).ceil() as i64;
        while k as f64 * DPHI <= b {
            let p = Vec3::from_array(step.position(hole, (k as f64 * DPHI - a) / (b - a)));
            if p.cmplt(room.min).any() || p.cmpgt(room.max).any() {
                return Visit::Stop;
            }
            points.insert(k, p);
            k += 1;
        }
        Visit::Continue
    });
    points
}

/// The largest distance between points of the same ray at the same azimuth, integrated at
/// `rtol` and at [`TIGHT`], over the room: the integration's own position error, free of where
/// the chords fall.
fn path_deviation(scene: &Scene, rays: &[Start], rtol: f64) -> f64 {
    let Spacetime::Schwarzschild(hole) = scene.spacetime else { panic!("the room has a Schwarzschild hole") };
    let settings = |rtol| TraceSettings {
        stepping: Stepping::Adaptive { rtol },
        escape_radius: 100.0,
        max_step_fraction: 0.5,
        max_steps: 1_000_000,
        check_every_step: true,
    };
    let room = scene.world.bounds(Region::Upper);
    let mut max = 0.0f64;
    for &ray in rays {
        let (a, b) = (path(&hole, &settings(rtol), room, ray), path(&hole, &settings(TIGHT), room, ray));
        for (k, p) in &a {
            if let Some(q) = b.get(k) {
                max = max.max((*p - *q).length());
            }
        }
    }
    max
}

#[test]
fn default_tolerance_keeps_rays_well_within_the_chord_tolerance() {
    let scene = room();
    let rtol = RenderSettings::default().geodesic_rtol;
    let epsilon = render::renderer::propagator(&scene).epsilon();
    let (camera, bounces) = (camera_rays(&scene), bounce_rays());
    let all: Vec<Start> = camera.iter().chain(&bounces).copied().collect();

    let deviation = path_deviation(&scene, &all, rtol);
    let (camera_distance, camera_across, camera_mismatches) = hit_differences(&scene, &camera, rtol);
    let (bounce_distance, bounce_across, bounce_mismatches) = hit_differences(&scene, &bounces, rtol);
    println!("rtol {rtol:e}, epsilon {epsilon:.3e}: path deviation {deviation:.3e}");
    println!("camera rays: hit points {camera_distance:.3e} apart, {camera_across:.3e} across the ray");
    println!("bounce rays: hit points {bounce_distance:.3e} apart, {bounce_across:.3e} across the ray");

    assert!(deviation < 0.25 * epsilon, "path deviation {deviation} against ε = {epsilon}");
    assert_eq!(camera_mismatches + bounce_mismatches, 0);
    assert!(camera_distance < epsilon, "camera hits {camera_distance} apart, ε = {epsilon}");
    assert!(bounce_across < epsilon, "bounce hits {bounce_across} apart across the ray, ε = {epsilon}");
}

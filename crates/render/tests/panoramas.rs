//! Renders through the panoramic projections: the film's solid angle adds up to the sphere, a
//! black hole's shadow keeps its exact solid angle in a panorama (at rest and, aberrated, for a
//! moving camera), and a fisheye's film outside its circle is black without failing.

#![allow(clippy::unwrap_used)] // A panic is a failed test.

use glam::DQuat;
use render::camera::{Camera, Equirectangular, Fisheye, Projection};
use render::film::{Film, Filter};
use render::geometry::Vec3;
use render::renderer::{render, RenderStats};
use render::rgb::Rgb;
use render::scene::Scene;
use render::settings::{IntegratorKind, RenderSettings};
use render::sky::Sky;
use render::world::World;
use spacetime::{Minkowski, Region, Spacetime};
use std::f64::consts::PI;
use std::sync::atomic::AtomicBool;

/// `camera` in `spacetime` under a uniform white sky, with nothing else in the world.
fn open_sky(spacetime: Spacetime, camera: Camera, settings: RenderSettings) -> (Film, RenderStats) {
    let black = Sky::Constant(Rgb::ZERO);
    let expected_samples = u64::from(settings.width * settings.height * settings.spp);
    let scene = Scene {
        spacetime,
        axis: Vec3::Y,
        camera,
        world: World::new(Vec::new(), (Vec::new(), Sky::Constant(Rgb::ONE)), (Vec::new(), black)),
        settings,
        animation: None,
    };
    let (film, stats) = render(&scene, &AtomicBool::new(false), &|_, _| {});
    assert_eq!(stats.nan_samples, 0);
    assert_eq!(stats.paths.fates.failed, 0);
    assert_eq!(stats.samples, expected_samples);
    (film, stats)
}

/// An equirectangular camera at `(0, 0, r)` looking at the origin along −z.
fn panorama(r: f64) -> Camera {
    let projection = Projection::Equirectangular(Equirectangular);
    Camera::oriented(Region::Upper, Vec3::new(0.0, 0.0, r), DQuat::IDENTITY, projection).unwrap()
}

/// Longitude and latitude of the centre of pixel `(x, y)` of a `width × height` panorama.
fn centre(x: u32, y: u32, width: u32, height: u32) -> (f64, f64) {
    ((2.0 * (f64::from(x) + 0.5) / f64::from(width) - 1.0) * PI, (0.5 - (f64::from(y) + 0.5) / f64::from(height)) * PI)
}

/// Σ over the pixels of `value(x, y, longitude, latitude)` (at the pixel's centre) times the
/// pixel's solid angle Δλ (sin φ_top − sin φ_bottom).
fn over_the_sphere(width: u32, height: u32, value: impl Fn(u32, u32, f64, f64) -> f64) -> f64 {
    let latitude = |y: u32| (0.5 - f64::from(y) / f64::from(height)) * PI;
    let mut sum = 0.0;
    for y in 0..height {
        let band = 2.0 * PI / f64::from(width) * (latitude(y).sin() - latitude(y + 1).sin());
        for x in 0..width {
            let (longitude, latitude) = centre(x, y, width, height);
            sum += band * value(x, y, longitude, latitude);
        }
    }
    sum
}

#[test]
fn a_uniform_sky_fills_the_panoramas_4_pi() {
    let (width, height) = (64, 32);
    let settings = RenderSettings { width, height, spp: 2, max_depth: 1, ..RenderSettings::default() };
    let (film, _) = open_sky(Spacetime::Minkowski(Minkowski), panorama(0.0), settings);
    let total = over_the_sphere(width, height, |x, y, _, _| f64::from(film.pixel(x, y).x));
    assert!((total - 4.0 * PI).abs() < 1e-3, "∫ L dΩ = {total}");
}

#[test]
fn a_panorama_shows_a_black_holes_shadow_at_its_exact_solid_angle_at_rest_and_moving() {
    // The shadow seen by the static observer at r: a cap of half-angle α, sin α = 3√3 M √(1 − 2M/r)
    // / r (Synge 1966), solid angle 2π (1 − cos α). Moving at v towards the hole, the camera
    // sees the cap aberrated to cos α' = (cos α + v) / (1 + v cos α), and the sky (uniformly
    // blueshifted for the static observer) brightened by D⁴, D = 1 / (γ (1 − v cos θ')) at
    // angle θ' from the motion. Tolerance: the antialiased rim at 8 spp and 2° pixels.
    let (mass, r, width, height) = (1.0, 10.0, 180, 90);
    let settings = RenderSettings { width, height, spp: 8, max_depth: 1, ..RenderSettings::default() };
    let alpha = spacetime::analytic::schwarzschild_shadow_angle(mass, r);
    for v in [0.0, 0.5] {
        let camera = panorama(r).with_velocity(Vec3::new(0.0, 0.0, -v)).unwrap();
        let (film, _) = open_sky(Spacetime::schwarzschild(mass).unwrap(), camera, settings.clone());
        let gamma = 1.0 / (1.0 - v * v).sqrt();
        let doppler = |longitude: f64, latitude: f64| 1.0 / (gamma * (1.0 - v * latitude.cos() * longitude.cos()));
        // The static observer's sky brightness, from a pixel looking back.
        let (lon, lat) = centre(0, height / 2, width, height);
        let behind = f64::from(film.pixel(0, height / 2).x) / doppler(lon, lat).powi(4);
        let dark = over_the_sphere(width, height, |x, y, lon, lat| {
            1.0 - f64::from(film.pixel(x, y).x) / (behind * doppler(lon, lat).powi(4))
        });
        let cos_seen = (alpha.cos() + v) / (1.0 + v * alpha.cos());
        let exact = 2.0 * PI * (1.0 - cos_seen);
        assert!((dark / exact - 1.0).abs() < 0.01, "v = {v}: shadow {dark} sr, exact {exact} sr");
        // The centre looks into the hole; the pixel behind sees the sky with D⁴ from behind.
        assert_eq!(film.pixel(width / 2, height / 2), Rgb::ZERO);
        let redshift = 1.0 / (1.0 - 2.0 * mass / r).sqrt();
        assert!((behind / redshift.powi(4) - 1.0).abs() < 1e-3, "v = {v}: static sky {behind}");
    }
}

#[test]
fn a_fisheyes_film_outside_its_circle_is_black() {
    // 40 × 30: the circle's diameter is 30, so the left and right strips and the corners see
    // nothing. A wide filter spreads the circle's edge, never a NaN or a failed ray.
    let projection = Projection::Fisheye(Fisheye::new(180.0).unwrap());
    let camera = Camera::oriented(Region::Upper, Vec3::ZERO, DQuat::IDENTITY, projection).unwrap();
    for integrator in [IntegratorKind::Path, IntegratorKind::Photon] {
        let settings = RenderSettings {
            width: 40,
            height: 30,
            spp: 4,
            max_depth: 1,
            filter: Filter::gaussian([1.5, 1.5], 0.5).unwrap(),
            integrator,
            ..RenderSettings::default()
        };
        let (film, _) = open_sky(Spacetime::Minkowski(Minkowski), camera, settings);
        for (x, y) in [(0, 0), (39, 29), (2, 15), (37, 15)] {
            assert_eq!(film.pixel(x, y), Rgb::ZERO, "{integrator:?}: ({x}, {y})");
        }
        for (x, y) in [(20, 15), (20, 2), (8, 15), (31, 15)] {
            assert!((film.pixel(x, y).x - 1.0).abs() < 1e-6, "{integrator:?}: ({x}, {y}) {:?}", film.pixel(x, y));
        }
        let edge = film.pixel(5, 15).x;
        assert!(edge > 0.0 && edge < 1.0, "{integrator:?}: the rim is antialiased, {edge}");
    }
}

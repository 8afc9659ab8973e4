//! Rendering in curved spacetime against exact results: the size of a black hole's shadow, the
//! flat limit, and the chord test against the poster's sign-change test.

#![allow(clippy::unwrap_used)] // A panic is a failed test.

use render::camera::Camera;
use render::film::Film;
use render::geometry::Vec3;
use render::material::Material;
use render::propagator::{Propagator, RayEnd};
use render::renderer::render;
use render::rgb::Rgb;
use render::scene::Scene;
use render::settings::{Intersection, RenderSettings};
use render::shape::Shape;
use render::sky::Sky;
use render::texture::Texture;
use render::transform::Transform;
use render::world::{Emission, Object, World};
use spacetime::{Minkowski, Region, Spacetime};
use std::sync::atomic::AtomicBool;

fn run(scene: &Scene) -> (Film, render::renderer::RenderStats) {
    render(scene, &AtomicBool::new(false), &|_, _| {})
}

fn empty_world(sky: Sky) -> World {
    World::new(Vec::new(), (Vec::new(), sky), (Vec::new(), Sky::Constant(Rgb::ZERO)))
}

/// The area-equivalent radius in pixels of the shadow of `spacetime`'s hole on a bright sky, seen
/// from distance `r` with a `size`² image of field of view `fov` degrees, and the radius in
/// pixels of a disk of angular radius `alpha`.
fn shadow_radius_px(spacetime: Spacetime, r: f64, size: u32, fov: f64, alpha: f64) -> (f64, f64) {
    let camera = Camera::new(Region::Upper, Vec3::new(0.0, 0.0, r), Vec3::ZERO, Vec3::Y, fov, 0.0, None).unwrap();
    let settings = RenderSettings { width: size, height: size, spp: 16, max_depth: 1, ..RenderSettings::default() };
    let scene = Scene {
        spacetime,
        axis: Vec3::Y,
        camera,
        world: empty_world(Sky::Constant(Rgb::ONE)),
        settings,
        animation: None,
    };
    let (film, stats) = run(&scene);
    assert_eq!(stats.nan_samples, 0);
    assert_eq!(stats.paths.fates.failed, 0);
    // The sky is blueshifted by the same factor everywhere; normalise by a corner pixel.
    let sky = film.pixel(0, 0).x;
    let mut dark_area = 0.0;
    for y in 0..size {
        for x in 0..size {
            dark_area += f64::from(1.0 - film.pixel(x, y).x / sky);
        }
    }
    let radius_px = alpha.tan() / (0.5 * fov.to_radians()).tan() * f64::from(size) / 2.0;
    ((dark_area / std::f64::consts::PI).sqrt(), radius_px)
}

#[test]
fn shadow_has_the_exact_angular_radius() {
    // sin α = 3√3 M √(1 − 2M/r) / r for a static observer at r (Synge 1966).
    let (mass, r) = (1.0, 30.0);
    let alpha = spacetime::analytic::schwarzschild_shadow_angle(mass, r);
    let (measured, exact) = shadow_radius_px(Spacetime::schwarzschild(mass).unwrap(), r, 96, 30.0, alpha);
    // Antialiased edge, 16 spp: the area-equivalent radius is good to a small fraction of a pixel.
    assert!((measured - exact).abs() < 0.1, "shadow radius {measured} px, exact {exact} px");
}

/// A charged hole's shadow: `sin α = b_c √A(r) / r` with `A = 1 − 2M/r + Q²/r²` and the critical
/// impact parameter `b_c = r_ph/√A(r_ph)`, `r_ph = (3M + √(9M² − 8Q²))/2`: 4.32 M for Q = 0.9 M,
/// against 5.20 M without charge, so an uncharged shadow would miss the tolerance by pixels.
#[test]
fn charged_shadow_has_the_exact_angular_radius() {
    let (mass, charge, r) = (1.0, 0.9, 30.0);
    let alpha = spacetime::analytic::reissner_nordstrom_shadow_angle(mass, charge, r);
    let hole = Spacetime::reissner_nordstrom(mass, charge).unwrap();
    let (measured, exact) = shadow_radius_px(hole, r, 64, 30.0, alpha);
    // 64² at 16 spp: the area-equivalent radius is good to a fraction of a pixel.
    assert!((measured - exact).abs() < 0.15, "shadow radius {measured} px, exact {exact} px");
}

/// A small lit room: floor, a lamp and a glass ball; rendered at mass 0 in Schwarzschild and in
/// Minkowski.
fn room(spacetime: Spacetime) -> Scene {
    let t = Transform::identity();
    let objects = vec![
        Object { shape: Shape::plane(Vec3::new(0.0, -1.0, 0.0), Vec3::Y, &t).unwrap(), material: 0, emission: None },
        Object {
            shape: Shape::sphere(Vec3::new(0.0, 3.0, 0.0), 0.7, &t).unwrap(),
            material: 0,
            emission: Some(Emission::uniform(Rgb::splat(5.0), false)),
        },
        Object { shape: Shape::sphere(Vec3::new(0.6, 0.0, 0.0), 0.6, &t).unwrap(), material: 1, emission: None },
    ];
    let materials = vec![
        Material::Diffuse { reflectance: Texture::from(Rgb::splat(0.6)) },
        Material::Dielectric { ior: 1.5, dispersion: None, transmittance: Texture::from(Rgb::ONE) },
    ];
    let camera = Camera::new(Region::Upper, Vec3::new(0.0, 1.0, 5.0), Vec3::ZERO, Vec3::Y, 50.0, 0.0, None).unwrap();
    let settings = RenderSettings { width: 32, height: 32, spp: 8, max_depth: 5, ..RenderSettings::default() };
    let world =
        World::new(materials, (objects, Sky::Constant(Rgb::splat(0.2))), (Vec::new(), Sky::Constant(Rgb::ZERO)));
    Scene { spacetime, axis: Vec3::Y, camera, world, settings, animation: None }
}

#[test]
fn zero_mass_renders_the_minkowski_image() {
    let (flat, _) = run(&room(Spacetime::Minkowski(Minkowski)));
    let (massless, _) = run(&room(Spacetime::schwarzschild(0.0).unwrap()));
    let (kerr, _) = run(&room(Spacetime::kerr(0.0, 0.0).unwrap()));
    for y in 0..32 {
        for x in 0..32 {
            assert_eq!(flat.pixel(x, y), massless.pixel(x, y), "pixel ({x}, {y})");
            assert_eq!(flat.pixel(x, y), kerr.pixel(x, y), "pixel ({x}, {y})");
        }
    }
}

#[test]
fn a_thin_plate_inside_a_long_step_is_hit_by_chords_and_missed_by_sign_changes() {
    // A 1 mm plate far from a small hole: the geodesic step across it is many metres long, and
    // both its ends lie outside the plate.
    let t = Transform::identity();
    let plate = Object {
        shape: Shape::cuboid(Vec3::new(-5.0, -5.0, 49.9995), Vec3::new(5.0, 5.0, 50.0005), &t).unwrap(),
        material: 0,
        emission: None,
    };
    let world = World::new(
        vec![Material::Diffuse { reflectance: Texture::from(Rgb::ONE) }],
        (vec![plate], Sky::Constant(Rgb::ZERO)),
        (Vec::new(), Sky::Constant(Rgb::ZERO)),
    );
    let hole = Spacetime::schwarzschild(0.01).unwrap();
    let origin = Vec3::new(0.0, 1.0, 80.0);
    let dir = Vec3::new(0.0, 0.0, -1.0);
    let chord = Propagator::new(hole.clone(), 100.0, 1e-8, Intersection::Chord);
    let poster = Propagator::new(hole, 100.0, 1e-8, Intersection::POSTER);
    match chord.trace(&world, Region::Upper, origin, dir) {
        RayEnd::Hit(a) => assert!((a.hit.p.z - 50.0005).abs() < 1e-3, "hit at {:?}", a.hit.p),
        other => panic!("chord method missed the plate: {other:?}"),
    }
    assert!(matches!(poster.trace(&world, Region::Upper, origin, dir), RayEnd::Escaped { .. } | RayEnd::Captured));
}

/// The dark coverage of each row of a `size`² image of `spacetime`'s hole on a bright sky, seen
/// from `camera` looking at the centre with `+y` up: `(width, centroid)` in pixels per row, the
/// centroid from the image's centre, positive towards `+x`.
fn shadow_rows(spacetime: Spacetime, camera: Vec3, size: u32, fov: f64, spp: u32) -> Vec<(f64, f64)> {
    let camera = Camera::new(Region::Upper, camera, Vec3::ZERO, Vec3::Y, fov, 0.0, None).unwrap();
    let settings = RenderSettings { width: size, height: size, spp, max_depth: 1, ..RenderSettings::default() };
    let world = empty_world(Sky::Constant(Rgb::ONE));
    let scene = Scene { spacetime, axis: Vec3::Y, camera, world, settings, animation: None };
    let (film, stats) = run(&scene);
    assert_eq!((stats.nan_samples, stats.paths.fates.failed), (0, 0));
    let sky = film.pixel(0, 0).x;
    (0..size)
        .map(|y| {
            let dark: Vec<f64> = (0..size).map(|x| f64::from(1.0 - film.pixel(x, y).x / sky)).collect();
            let width: f64 = dark.iter().sum();
            let moment: f64 = dark.iter().enumerate().map(|(x, d)| (x as f64 + 0.5 - f64::from(size) / 2.0) * d).sum();
            (width, if width > 0.0 { moment / width } else { 0.0 })
        })
        .collect()
}

/// The same coverage of a curve's inside (`curve`: the upper half of a boundary symmetric about
/// `β = 0`, in order along it, as [`spacetime::analytic::kerr_newman_shadow`] gives it), in units
/// of `scale` per pixel, averaged over each row's height: `(width, centroid)` per row.
fn curve_rows(curve: &[(f64, f64)], scale: f64, size: u32) -> Vec<(f64, f64)> {
    let top = curve.iter().map(|p| p.1).fold(0.0, f64::max);
    let peak = curve.iter().position(|p| p.1 == top).unwrap();
    // α where the curve's rising (left) or falling (right) part crosses height β.
    let crossing = |part: &[(f64, f64)], beta: f64| {
        let k = part.windows(2).position(|w| (w[0].1 - beta) * (w[1].1 - beta) <= 0.0)?;
        let ((a0, b0), (a1, b1)) = (part[k], part[k + 1]);
        Some(a0 + (a1 - a0) * (beta - b0) / (b1 - b0))
    };
    // The curve meets β = 0 vertically: its ends extended there.
    let left: Vec<_> = std::iter::once((curve[0].0, 0.0)).chain(curve[..=peak].iter().copied()).collect();
    let right: Vec<_> = curve[peak..].iter().copied().chain(std::iter::once((curve[curve.len() - 1].0, 0.0))).collect();
    (0..size)
        .map(|y| {
            let (mut width, mut moment) = (0.0, 0.0);
            for sub in 0..32 {
                let beta = ((f64::from(size) / 2.0 - f64::from(y)) - (f64::from(sub) + 0.5) / 32.0) * scale;
                if let (Some(a), Some(b)) = (crossing(&left, beta.abs()), crossing(&right, beta.abs())) {
                    width += (b - a) / scale / 32.0;
                    moment += (b - a) * 0.5 * (a + b) / (scale * scale) / 32.0;
                }
            }
            (width, if width > 0.0 { moment / width } else { 0.0 })
        })
        .collect()
}

/// Largest differences of width and centroid, in pixels, between two rows' coverages, over the
/// rows where both are at least `min_width` wide (the caps, where the width changes fastest from
/// row to row and the film's filter mixes rows, are left out).
fn row_errors(measured: &[(f64, f64)], exact: &[(f64, f64)], min_width: f64) -> (f64, f64) {
    measured
        .iter()
        .zip(exact)
        .filter(|(m, e)| m.0 >= min_width && e.0 >= min_width)
        .fold((0.0, 0.0), |(w, c), (m, e)| (f64::max(w, (m.0 - e.0).abs()), f64::max(c, (m.1 - e.1).abs())))
}

/// A charged spinning hole's shadow is the generalised Bardeen curve (spherical photon orbits of
/// Kerr–Newman, [`spacetime::analytic::kerr_newman_shadow`]): `a = 0.8 M`, `Q = 0.5 M`, seen at
/// inclination 70° from 10³ M (where the distant observer's celestial coordinates are the
/// image's to `O(M/r)`, 0.04 px here). Every row of a 64² image at least 20 px wide (the shadow
/// is 45 px across) has the curve's width and centroid to 0.3 px (antialiased edges at 64 spp);
/// the curve without charge (Kerr's) is off by 4.9 px and is refused, and so is the
/// mirrored one (spin reversed), whose centroid is 17 px off (measured).
#[test]
fn kerr_newman_shadow_is_the_generalised_bardeen_curve() {
    let (mass, spin, charge, inclination) = (1.0, 0.8, 0.5, 70f64.to_radians());
    let (distance, size, fov) = (1e3, 64, 0.75);
    let position = Vec3::new(0.0, distance * inclination.cos(), distance * inclination.sin());
    let hole = Spacetime::kerr_newman(mass, spin, charge).unwrap();
    let measured = shadow_rows(hole, position, size, fov, 64);
    // Sky coordinates in M per pixel at the hole's distance.
    let scale = distance * (0.5 * fov.to_radians()).tan() / (f64::from(size) / 2.0);
    let rows = |spin: f64, charge: f64| {
        let curve = spacetime::analytic::kerr_newman_shadow(mass, spin, charge, inclination, 4000);
        curve_rows(&curve, scale, size)
    };
    let (width, centroid) = row_errors(&measured, &rows(spin, charge), 20.0);
    assert!(width < 0.3 && centroid < 0.3, "largest row errors: width {width} px, centroid {centroid} px");
    let (uncharged, _) = row_errors(&measured, &rows(spin, 0.0), 20.0);
    assert!(uncharged > 1.0, "Kerr's curve (Q = 0) would pass: width error {uncharged} px");
    let mirrored: Vec<(f64, f64)> = rows(spin, charge).iter().map(|&(w, c)| (w, -c)).collect();
    let (_, flipped) = row_errors(&measured, &mirrored, 20.0);
    eprintln!("row errors: width {width:.3} px, centroid {centroid:.3} px; Q = 0: {uncharged:.2} px; mirrored: {flipped:.2} px");
    assert!(flipped > 1.0, "the mirrored curve would pass: centroid error {flipped} px");
}

//! Light transport against known answers: furnaces, energy-conserving glass, a mirror, and
//! determinism across thread counts; in RGB and in spectral rendering.

#![allow(clippy::unwrap_used)] // A panic is a failed test.

use render::camera::Camera;
use render::film::Film;
use render::geometry::Vec3;
use render::material::Material;
use render::renderer::render;
use render::rgb::Rgb;
use render::scene::Scene;
use render::settings::{IntegratorKind, RenderSettings};
use render::shape::Shape;
use render::sky::{Gradient, Sky, SkyFrame};
use render::texture::Texture;
use render::transform::Transform;
use render::world::{Emission, Object, World};
use spacetime::{Minkowski, Region, Spacetime};
use std::sync::atomic::AtomicBool;

fn settings(size: u32, spp: u32, max_depth: u32) -> RenderSettings {
    RenderSettings { width: size, height: size, spp, max_depth, ..RenderSettings::default() }
}

fn camera(position: Vec3, look_at: Vec3, fov: f64) -> Camera {
    Camera::new(Region::Upper, position, look_at, Vec3::Y, fov, 0.0, None).unwrap()
}

fn scene(objects: Vec<Object>, materials: Vec<Material>, sky: Sky, camera: Camera, settings: RenderSettings) -> Scene {
    Scene {
        spacetime: Spacetime::Minkowski(Minkowski),
        axis: Vec3::Y,
        camera,
        world: World::new(materials, (objects, sky), (Vec::new(), Sky::Constant(Rgb::ZERO))),
        settings,
        animation: None,
    }
}

fn run(scene: &Scene, threads: usize) -> (Film, render::renderer::RenderStats) {
    let pool = rayon::ThreadPoolBuilder::new().num_threads(threads).build().unwrap();
    pool.install(|| render(scene, &AtomicBool::new(false), &|_, _| {}))
}

fn mean(film: &Film) -> Rgb {
    let mut sum = Rgb::ZERO;
    for y in 0..film.height() {
        for x in 0..film.width() {
            sum += film.pixel(x, y);
        }
    }
    sum / (film.width() * film.height()) as f32
}

fn diffuse(a: f32) -> Material {
    Material::Diffuse { reflectance: Texture::from(Rgb::splat(a)) }
}

/// Inside a closed sphere whose wall has albedo `a` and emits `Le`, every direction sees
/// `L = Le / (1 − a)` (the emission plus all its inter-reflections).
fn furnace(integrator: IntegratorKind, spectral: bool) -> Rgb {
    let wall = Object {
        shape: Shape::sphere(Vec3::ZERO, 2.0, &Transform::identity()).unwrap(),
        material: 0,
        emission: Some(Emission::uniform(Rgb::splat(0.25), true)),
    };
    let mut s = settings(16, 16, 200);
    s.integrator = integrator;
    s.spectral = spectral;
    let sc = scene(
        vec![wall],
        vec![diffuse(0.75)],
        Sky::Constant(Rgb::ZERO),
        camera(Vec3::new(0.3, 0.1, 0.0), Vec3::new(1.0, 0.0, 0.5), 90.0),
        s,
    );
    let (film, stats) = run(&sc, 2);
    assert_eq!(stats.nan_samples, 0);
    assert_eq!(stats.paths.fates.escaped, 0, "the enclosure is closed");
    mean(&film)
}

#[test]
fn white_furnace_converges_to_the_analytic_radiance() {
    for spectral in [false, true] {
        for kind in [IntegratorKind::Path, IntegratorKind::BruteForce] {
            let m = furnace(kind, spectral);
            // L = 0.25 / (1 − 0.75) = 1 (in spectral rendering, D65 at Y = 1: RGB 1); 4096 paths
            // averaged, whose noise (more in spectral rendering, whose wavelengths add colour
            // noise) stays well inside the tolerance.
            for c in m.to_array() {
                assert!((c - 1.0).abs() < 0.02, "{kind:?}, spectral {spectral}: mean radiance {m}");
            }
        }
    }
}

#[test]
fn glass_in_a_uniform_sky_conserves_energy() {
    let ball =
        Object { shape: Shape::sphere(Vec3::ZERO, 1.0, &Transform::identity()).unwrap(), material: 0, emission: None };
    let glass = Material::Dielectric { ior: 1.5, dispersion: None, transmittance: Texture::from(Rgb::ONE) };
    let sc = scene(
        vec![ball],
        vec![glass],
        Sky::Constant(Rgb::ONE),
        camera(Vec3::new(0.0, 0.0, 3.0), Vec3::ZERO, 45.0),
        settings(16, 4, 64),
    );
    let (film, stats) = run(&sc, 2);
    let m = mean(&film);
    // Every path ends in the sky with throughput exactly 1, unless it is trapped for 64 bounces.
    for c in m.to_array() {
        assert!((c - 1.0).abs() < 2e-3, "mean radiance through glass {m}");
    }
    assert!(stats.paths.fates.escaped > 0);
}

#[test]
fn dispersing_glass_in_a_uniform_sky_conserves_energy() {
    // Flint glass (Abbe number 20) refracts each path at its hero wavelength, which then alone
    // carries the path: each still ends in the sky with throughput 1, so the image is the sky's
    // white, though the hero alone is a noisier estimate of it than four wavelengths.
    let ball =
        Object { shape: Shape::sphere(Vec3::ZERO, 1.0, &Transform::identity()).unwrap(), material: 0, emission: None };
    let glass = Material::Dielectric {
        ior: 1.7,
        dispersion: Some(render::material::Dispersion::from_abbe(1.7, 20.0).unwrap()),
        transmittance: Texture::from(Rgb::ONE),
    };
    let mut s = settings(16, 64, 64);
    s.spectral = true;
    let sc =
        scene(vec![ball], vec![glass], Sky::Constant(Rgb::ONE), camera(Vec3::new(0.0, 0.0, 3.0), Vec3::ZERO, 45.0), s);
    let (film, _) = run(&sc, 2);
    let m = mean(&film);
    for c in m.to_array() {
        assert!((c - 1.0).abs() < 0.02, "mean radiance through dispersing glass {m}");
    }
}

#[test]
fn a_mirror_shows_the_sky_reflected() {
    // Mirror plane y = 0; the camera above it sees the reflection of the sky. The same view is
    // rendered directly by the camera reflected in the plane, whose image is left–right flipped.
    let sky = Sky::Gradient(Gradient {
        horizon: Rgb::new(1.0, 0.2, 0.1),
        zenith: Rgb::new(0.1, 0.3, 1.0),
        nadir: Rgb::new(0.1, 1.0, 0.2),
        frame: SkyFrame::new(Vec3::new(0.3, 1.0, 0.2), 0.0).unwrap(),
    });
    let mirror = Object {
        shape: Shape::plane(Vec3::ZERO, Vec3::Y, &Transform::identity()).unwrap(),
        material: 0,
        emission: None,
    };
    let chrome = Material::Mirror { reflectance: Texture::from(Rgb::ONE) };
    let (pos, at) = (Vec3::new(0.5, 2.0, 1.0), Vec3::new(-0.2, 0.0, -3.0));
    let flip = Vec3::new(1.0, -1.0, 1.0);
    let reflected = Camera::new(Region::Upper, pos * flip, at * flip, -Vec3::Y, 50.0, 0.0, None).unwrap();
    let s = settings(24, 16, 4);
    let with_mirror = scene(vec![mirror], vec![chrome], sky.clone(), camera(pos, at, 50.0), s.clone());
    let direct = scene(Vec::new(), Vec::new(), sky, reflected, s);
    let (a, _) = run(&with_mirror, 2);
    let (b, _) = run(&direct, 2);
    let mut worst: f32 = 0.0;
    for y in 0..24 {
        for x in 0..24 {
            worst = worst.max((a.pixel(x, y) - b.pixel(23 - x, y)).abs().max_element());
        }
    }
    // Different random streams per pixel; the sky is smooth, so pixel means agree closely.
    assert!(worst < 0.02, "largest pixel difference {worst}");
}

#[test]
fn the_image_does_not_depend_on_the_thread_count() {
    let floor = Object {
        shape: Shape::plane(Vec3::ZERO, Vec3::Y, &Transform::identity()).unwrap(),
        material: 0,
        emission: None,
    };
    let lamp = Object {
        shape: Shape::sphere(Vec3::new(0.0, 2.0, 0.0), 0.5, &Transform::identity()).unwrap(),
        material: 0,
        emission: Some(Emission::uniform(Rgb::new(4.0, 3.0, 2.0), false)),
    };
    let ball = Object {
        shape: Shape::sphere(Vec3::new(0.8, 0.5, 0.0), 0.5, &Transform::identity()).unwrap(),
        material: 1,
        emission: None,
    };
    // The glass disperses, so spectral paths through it narrow to their hero wavelength.
    let flint = Material::Dielectric {
        ior: 1.5,
        dispersion: render::material::Dispersion::from_abbe(1.5, 30.0),
        transmittance: Texture::from(Rgb::ONE),
    };
    let materials = vec![diffuse(0.6), flint];
    let sc = scene(
        vec![floor, lamp, ball],
        materials,
        Sky::Constant(Rgb::splat(0.1)),
        camera(Vec3::new(0.0, 1.5, 4.0), Vec3::new(0.0, 0.5, 0.0), 50.0),
        settings(40, 3, 6),
    );
    for spectral in [false, true] {
        let sc = Scene { settings: RenderSettings { spectral, ..sc.settings.clone() }, ..sc.clone() };
        let (one, _) = run(&sc, 1);
        let (two, _) = run(&sc, 2);
        for y in 0..40 {
            for x in 0..40 {
                let (p, q) = (one.pixel_f64(x, y), two.pixel_f64(x, y));
                let same = p.iter().zip(q).all(|(a, b)| a.to_bits() == b.to_bits());
                assert!(same, "spectral {spectral}: pixel ({x}, {y}) differs");
            }
        }
    }
}

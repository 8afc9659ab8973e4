//! No pole artefacts in the wormhole: a scene turned rigidly so that the camera sits on a
//! coordinate axis (the polar axis of the spherical charts other renderers integrate in, where
//! the poster had to fill in error pixels) renders the same image as the unturned scene.

#![allow(clippy::unwrap_used)] // A panic is a failed test.

use glam::{DQuat, DVec3};
use render::film::Film;
use std::sync::atomic::AtomicBool;

const SIZE: u32 = 32;

fn v(p: DVec3) -> String {
    format!("[{}, {}, {}]", p.x, p.y, p.z)
}

/// A two-region wormhole scene (lit objects on both sides of the throat), turned by `turn`.
fn scene(turn: DQuat) -> String {
    let (axis, angle) = turn.to_axis_angle();
    let rotate = format!("transform = {{ rotate = {{ axis = {}, degrees = {} }} }}", v(axis), angle.to_degrees());
    let camera = DVec3::new(3.0, 2.0, 6.5);
    let sphere = |center: DVec3, radius: f64, region: &str, material: &str| {
        format!(
            "[[objects]]\nshape = {{ type = \"sphere\", center = {}, radius = {radius} }}\nregion = \"{region}\"\n{material}\n",
            v(turn * center)
        )
    };
    let lamp = "material = { type = \"diffuse\", reflectance = 0.5 }\nemission = [3, 2.5, 2]";
    let white = "material = { type = \"diffuse\", reflectance = 0.7 }";
    format!(
        "[spacetime]\ntype = \"ellis\"\nthroat = 1\n\
         [camera]\nposition = {}\nlook_at = {}\nup = {}\nfov = 50\n\
         [render]\nwidth = {SIZE}\nheight = {SIZE}\nspp = 64\nmax_depth = 3\n\
         [sky]\ntype = \"constant\"\nradiance = [0.05, 0.05, 0.1]\n\
         [lower.sky]\ntype = \"constant\"\nradiance = [0.1, 0.05, 0.02]\n\
         {}{}{}{}\
         [[objects]]\nshape = {{ type = \"box\", min = [-1, -4, -6], max = [1, -3, -4] }}\nregion = \"lower\"\n{white}\n{rotate}\n",
        v(turn * camera),
        v(DVec3::ZERO),
        v(turn * DVec3::Y),
        sphere(DVec3::new(-2.0, 1.0, 3.0), 0.8, "upper", lamp),
        sphere(DVec3::new(1.5, -1.0, -2.0), 1.0, "upper", white),
        sphere(DVec3::new(0.5, 0.5, -5.0), 1.2, "lower", lamp),
        sphere(DVec3::new(-2.5, 0.0, -3.0), 0.9, "lower", white),
    )
}

fn render(text: &str, seed: u64) -> (Film, u64) {
    let mut scene = scene::parse(text, "poles.toml", std::path::Path::new(".")).unwrap();
    scene.settings.seed = seed;
    let (film, stats) = render::renderer::render(&scene, &AtomicBool::new(false), &|_, _| {});
    assert_eq!(stats.nan_samples, 0);
    (film, stats.paths.fates.failed)
}

fn pixels(film: &Film) -> Vec<f64> {
    (0..SIZE * SIZE).flat_map(|i| film.pixel_f64(i % SIZE, i / SIZE)).collect()
}

fn mean_squared_difference(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).map(|(x, y)| (x - y) * (x - y)).sum::<f64>() / a.len() as f64
}

#[test]
fn a_camera_on_a_coordinate_axis_sees_the_same_wormhole() {
    let camera = DVec3::new(3.0, 2.0, 6.5).normalize();
    let (unturned, failed) = render(&scene(DQuat::IDENTITY), 1);
    assert_eq!(failed, 0);
    let reference = pixels(&unturned);
    let (other_seed, _) = render(&scene(DQuat::IDENTITY), 2);
    // Two renders that differ only by Monte Carlo noise differ by this much.
    let noise = mean_squared_difference(&reference, &pixels(&other_seed));
    let mean = |p: &[f64]| p.iter().sum::<f64>() / p.len() as f64;
    for axis in [DVec3::Z, DVec3::Y, DVec3::NEG_X] {
        let (turned, failed) = render(&scene(DQuat::from_rotation_arc(camera, axis)), 1);
        assert_eq!(failed, 0, "camera on {axis}: failed rays");
        let turned = pixels(&turned);
        let difference = mean_squared_difference(&reference, &turned);
        assert!(difference < 1.5 * noise, "camera on {axis}: differs by {difference}, noise alone {noise}");
        let (a, b) = (mean(&reference), mean(&turned));
        assert!((a / b - 1.0).abs() < 0.02, "camera on {axis}: mean {b} vs {a}");
    }
}

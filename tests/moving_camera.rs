//! What a moving camera sees, rendered from scene files in flat space: relativistic aberration of
//! a marker, the Doppler brightening, and a zero velocity that changes nothing.

#![allow(clippy::unwrap_used)] // A panic is a failed test.

use render::film::Film;
use render::renderer::render;
use std::sync::atomic::AtomicBool;

const SIZE: u32 = 201;
const FOV_DEG: f64 = 60.0;

/// A camera at the origin looking along −z, moving with `velocity`, and a bright marker sphere
/// of angular radius 1.5° far away at `theta_deg` from −z (towards +x), on a black sky.
fn marker_scene(theta_deg: f64, velocity: &str) -> String {
    let (s, c) = theta_deg.to_radians().sin_cos();
    let distance = 1000.0;
    format!(
        "[camera]\nposition = [0, 0, 0]\nlook_at = [0, 0, -1]\nfov = {FOV_DEG}\n{velocity}\n\
         [render]\nwidth = {SIZE}\nheight = {SIZE}\nspp = 64\nmax_depth = 1\n\
         [[objects]]\nshape = {{ type = \"sphere\", center = [{}, 0, {}], radius = {} }}\n\
         material = {{ type = \"diffuse\", reflectance = 0 }}\nemission = [1, 1, 1]\n",
        distance * s,
        -distance * c,
        distance * 1.5f64.to_radians().sin(),
    )
}

fn film_of(text: &str) -> Film {
    let scene = scene::parse(text, "marker.toml", std::path::Path::new(".")).unwrap();
    render(&scene, &AtomicBool::new(false), &|_, _| {}).0
}

/// The marker's direction, in degrees from the view axis, and its brightness integrated over
/// solid angle. The direction is the brightness-weighted mean of the pixels' directions on the
/// sphere, which for a uniform disk on the sky is exactly its centre (a centroid on the film
/// plane would be pushed outwards by the projection's growing magnification).
fn marker(film: &Film) -> (f64, f64) {
    let tan_half = (0.5 * FOV_DEG).to_radians().tan();
    let film_coordinate = |c: f64| (2.0 * c / f64::from(SIZE) - 1.0) * tan_half;
    let (mut mean, mut flux) = ([0.0f64; 3], 0.0);
    for y in 0..SIZE {
        for x in 0..SIZE {
            let l = film.pixel_f64(x, y)[1];
            let (u, v) = (film_coordinate(f64::from(x) + 0.5), film_coordinate(f64::from(y) + 0.5));
            let norm = (1.0 + u * u + v * v).sqrt();
            // A pixel's solid angle is its film area × cos³ of its angle from the axis.
            let weight = l / (norm * norm * norm);
            flux += weight;
            for (m, d) in mean.iter_mut().zip([u / norm, v / norm, 1.0 / norm]) {
                *m += weight * d;
            }
        }
    }
    let length = (mean[0] * mean[0] + mean[1] * mean[1] + mean[2] * mean[2]).sqrt();
    ((mean[2] / length).acos().to_degrees(), flux)
}

#[test]
fn a_camera_moving_towards_a_point_sees_it_at_the_aberration_angle() {
    for theta in [15.0f64, 28.0] {
        let (at_rest, bright_at_rest) = marker(&film_of(&marker_scene(theta, "")));
        assert!((at_rest - theta).abs() < 0.02, "at rest: {at_rest}° for {theta}°");
        for v in [0.3, 0.6] {
            let text = marker_scene(theta, &format!("velocity = [0, 0, {}]", -v));
            let (seen, bright) = marker(&film_of(&text));
            let cos = theta.to_radians().cos();
            let expected = ((cos + v) / (1.0 + v * cos)).acos().to_degrees();
            // A finite marker is not a point: aberration and D⁴ shift its weighted centre by
            // O(r²) ≈ 0.01° for its 1.5° radius.
            assert!((seen - expected).abs() < 0.02, "v = {v}: seen at {seen}°, aberration says {expected}°");
            // The marker's total brightness is radiance × solid angle: D⁴ × D⁻² = D²,
            // D = γ(1 + v cos θ).
            let d = (1.0 + v * cos) / (1.0 - v * v).sqrt();
            let ratio = bright / bright_at_rest;
            assert!((ratio / (d * d) - 1.0).abs() < 0.01, "v = {v}: brightness ×{ratio}, D² = {}", d * d);
        }
    }
}

#[test]
fn a_zero_velocity_renders_the_static_image() {
    let still = film_of(&marker_scene(20.0, ""));
    let zero = film_of(&marker_scene(20.0, "velocity = [0, 0, 0]"));
    for y in 0..SIZE {
        for x in 0..SIZE {
            assert_eq!(still.pixel_f64(x, y), zero.pixel_f64(x, y));
        }
    }
}

//! Noise targets keep their promise: on three bundled scenes a render stopped by its estimated
//! relative error is, measured against a long reference render, at or below the target, with
//! uniform and with adaptive sampling.

#![allow(clippy::unwrap_used)] // A panic is a failed test.

use render::film::noise::relative_rmse;
use render::renderer::{progressive, render, Goal, NoiseTarget, Outcome, Part};
use std::sync::atomic::AtomicBool;

/// `scene` at `width × height`, depth at most 4, rendered to `target` by the renderer's
/// estimate; then a reference of 16 times the samples the noisiest pixel took, with another
/// seed, and the measured relative RMSE of the first against it.
fn check(name: &str, (width, height): (u32, u32), target: f64, adaptive: bool) {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes").join(name);
    let mut scene = scene::load(&path).unwrap();
    scene.settings.width = width;
    scene.settings.height = height;
    scene.settings.max_depth = scene.settings.max_depth.min(4);
    let cancel = AtomicBool::new(false);
    let goal = Goal { spp: 1 << 14, noise: Some(NoiseTarget { relative_error: target, adaptive }) };
    let renderer = progressive(&scene, Part::WHOLE, goal, None).unwrap();
    let stats = renderer.run(&cancel, &|_, _| {});
    assert_eq!(stats.outcome, Outcome::Converged, "{name}: {stats:?}");
    let estimate = stats.relative_error.unwrap();
    assert!(estimate <= target, "{name}: estimate {estimate}");
    let film = renderer.into_film();

    scene.settings.seed = 0x5eed;
    scene.settings.spp = 16 * stats.spp_max.min(256);
    let (reference, _) = render(&scene, &cancel, &|_, _| {});
    let measured = relative_rmse(&film, &reference);
    eprintln!(
        "{name}{}: estimated {estimate:.4}, measured {measured:.4} (target {target}) at {}–{} spp",
        if adaptive { " adaptive" } else { "" },
        stats.spp_min,
        stats.spp_max
    );
    assert!(measured <= target, "{name}: measured relative RMSE {measured} above the target {target}");
    if adaptive {
        assert!(stats.spp_min < stats.spp_max, "{name}: adaptive sampling sent samples everywhere alike");
    }
}

#[test]
fn the_cornell_box_meets_its_noise_target() {
    check("cornell-box.toml", (24, 24), 0.08, false);
    check("cornell-box.toml", (24, 24), 0.08, true);
}

#[test]
fn the_lensed_sky_meets_its_noise_target() {
    check("lensing-sky.toml", (32, 32), 0.02, false);
    check("lensing-sky.toml", (32, 32), 0.02, true);
}

#[test]
fn the_room_with_a_black_hole_meets_its_noise_target() {
    check("room-black-hole.toml", (20, 15), 0.15, false);
    check("room-black-hole.toml", (20, 15), 0.15, true);
}

//! `nullpath render` as a user runs it: the default scene, statistics, determinism across
//! thread counts, interruption, and errors for bad input.

#![allow(clippy::unwrap_used)] // A panic is a failed test.

use std::path::PathBuf;
use std::process::{Command, Stdio};

fn nullpath() -> Command {
    Command::new(env!("CARGO_BIN_EXE_nullpath"))
}

fn temp(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("nullpath-cli-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    dir.join(name)
}

#[test]
fn default_scene_renders_with_statistics() {
    let (out, stats) = (temp("default.png"), temp("default.json"));
    let status = nullpath()
        .args(["render", "-o", out.to_str().unwrap(), "--width", "24", "--height", "24", "--spp", "2"])
        .args(["--stats", stats.to_str().unwrap(), "--quiet"])
        .status()
        .unwrap();
    assert!(status.success());
    let img = image::open(&out).unwrap().to_rgb8();
    assert_eq!(img.dimensions(), (24, 24));
    let v: serde_json::Value = serde_json::from_str(&std::fs::read_to_string(&stats).unwrap()).unwrap();
    for key in ["rays", "samples", "seconds", "nan_samples"] {
        assert!(v[key].is_number(), "{key} in {v}");
    }
    for fate in ["escaped", "captured", "absorbed", "traversed", "failed"] {
        assert!(v["fates"][fate].is_u64(), "fates.{fate} in {v}");
    }
    assert_eq!(v["samples"], 24 * 24 * 2);
    assert_eq!(v["nan_samples"], 0);
}

#[test]
fn one_and_two_threads_give_the_same_image() {
    let render = |threads: &str| {
        let out = temp(&format!("threads-{threads}.exr"));
        let status = nullpath()
            .args(["render", "-o", out.to_str().unwrap(), "--width", "20", "--height", "16", "--spp", "3"])
            .args(["--seed", "11", "--threads", threads, "--quiet"])
            .status()
            .unwrap();
        assert!(status.success());
        // The pixels, not the file: its metadata records the command line and the time taken.
        image::open(out).unwrap().into_rgb32f().into_raw()
    };
    assert_eq!(render("1"), render("2"));
}

#[test]
fn bad_input_fails_with_a_precise_message_and_no_panic() {
    let dir = temp("bad");
    std::fs::create_dir_all(&dir).unwrap();
    let unknown = dir.join("unknown.toml");
    std::fs::write(&unknown, "[camera]\nposition = [0, 0, 5]\nlook_at = [0, 0, 0]\nfov = 40\nzoom = 2\n").unwrap();
    let cases: Vec<(Vec<String>, &str)> = vec![
        (vec!["render".into(), dir.join("missing.toml").display().to_string()], "missing.toml"),
        (vec!["render".into(), unknown.display().to_string()], "zoom"),
        (vec!["render".into(), "-o".into(), dir.join("x.bmp").display().to_string()], "x.bmp"),
        (vec!["render".into(), "-o".into(), dir.join("no/such/dir/x.png").display().to_string()], "no/such/dir"),
        (vec!["render".into(), "--spp".into(), "0".into()], "--spp"),
    ];
    for (args, needle) in cases {
        let out = nullpath().args(&args).output().unwrap();
        assert!(!out.status.success(), "{args:?} should fail");
        let err = String::from_utf8_lossy(&out.stderr);
        assert!(err.contains(needle), "{args:?}: {err}");
        assert!(!err.contains("panicked"), "{args:?}: {err}");
    }
    // The unknown field is reported with its line.
    let out = nullpath().args(["render", unknown.to_str().unwrap()]).output().unwrap();
    assert!(String::from_utf8_lossy(&out.stderr).contains(":5"), "{}", String::from_utf8_lossy(&out.stderr));
}

/// A camera inside a black hole's horizon is refused before rendering (it used to give a
/// black image and success).
#[test]
fn a_camera_inside_a_horizon_fails_with_its_position() {
    let dir = temp("horizon");
    std::fs::create_dir_all(&dir).unwrap();
    let file = dir.join("inside.toml");
    let text = "[spacetime]\ntype = \"schwarzschild\"\nmass = 1\n\
                [camera]\nposition = [0, 0, 1.5]\nlook_at = [0, 0, 0]\nfov = 40\n";
    std::fs::write(&file, text).unwrap();
    let out = nullpath()
        .args(["render", file.to_str().unwrap(), "-o", dir.join("x.png").to_str().unwrap()])
        .output()
        .unwrap();
    assert!(!out.status.success(), "a camera inside the horizon must fail");
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(err.contains("inside.toml:5") && err.contains("camera.position"), "{err}");
    assert!(err.contains("inside the event horizon") && !err.contains("panicked"), "{err}");
    assert!(!dir.join("x.png").exists(), "no image is written");
}

#[cfg(unix)]
#[test]
fn interrupting_a_render_keeps_what_was_computed() {
    let out = temp("interrupted.png");
    let checkpoint = temp("interrupted.checkpoint.exr");
    let _ = std::fs::remove_file(&out);
    let child = nullpath()
        .args(["render", concat!(env!("CARGO_MANIFEST_DIR"), "/scenes/cornell-box.toml"), "-o", out.to_str().unwrap()])
        .args(["--width", "256", "--height", "256", "--spp", "4096", "--quiet"])
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    std::thread::sleep(std::time::Duration::from_millis(1500));
    let _ = Command::new("kill").args(["-INT", &child.id().to_string()]).status();
    let result = child.wait_with_output().unwrap();
    assert_eq!(result.status.code(), Some(130), "an interrupted render reports it");
    let err = String::from_utf8_lossy(&result.stderr);
    assert!(err.contains("interrupted") && err.contains("--resume"), "{err}");
    // The work is in the checkpoint, a viewable EXR; no partial image takes the output's place.
    assert!(!out.exists());
    let img = image::open(&checkpoint).unwrap().into_rgb32f();
    assert_eq!(img.dimensions(), (256, 256));
    assert!(img.as_raw().iter().any(|&v| v > 0.0));
}

#[test]
fn data_channels_go_into_the_exr_beside_the_colour() {
    // A disk about a Schwarzschild hole, face on from its axis: every ray through the disk meets
    // it at the radius its pixel shows, and the ray through the centre falls into the hole.
    let scene = temp("disk-data.toml");
    std::fs::write(
        &scene,
        "[spacetime]\ntype = \"schwarzschild\"\nmass = 1\n\
         [camera]\nposition = [0, 200, 0]\nlook_at = [0, 0, 0]\nup = [0, 0, 1]\nfov = 8\n\
         [render]\nwidth = 9\nheight = 9\nspp = 1\nmax_depth = 0\nchannels = [\"redshift\", \"fate\", \"disk_radius\"]\n\
         spectrum = { min = 400, max = 700, count = 4 }\n\
         [accretion_disk]\nouter_radius = 12\n",
    )
    .unwrap();
    let out = temp("disk-data.exr");
    let status = nullpath().args(["render", scene.to_str().unwrap(), "-o", out.to_str().unwrap(), "--quiet"]).status();
    assert!(status.unwrap().success());
    let image = exr::prelude::read_all_flat_layers_from_file(&out).unwrap();
    let channels = &image.layer_data[0].channel_data.list;
    let named = |name: &str| {
        let c = channels.iter().find(|c| c.name.to_string() == name).unwrap_or_else(|| panic!("no channel {name}"));
        c.sample_data.values_as_f32().collect::<Vec<f32>>()
    };
    let (fate, redshift, radius) = (named("fate"), named("redshift"), named("disk_radius"));
    let centre = 4 * 9 + 4;
    assert_eq!(fate[centre], 4.0, "captured");
    assert!(redshift[centre].is_nan() && radius[centre].is_nan());
    // The corner rays miss the disk (r > 12 M there) and escape; the disk's pixels are emitters
    // whose gas, moving across the line of sight, is seen redshifted (g < 1).
    assert_eq!(fate[0], 2.0);
    let on_disk: Vec<usize> = (0..81).filter(|&i| fate[i] == 1.0).collect();
    assert!(on_disk.len() > 8, "{fate:?}");
    for &i in &on_disk {
        assert!((6.0..=12.0).contains(&radius[i]) && redshift[i] > 0.5 && redshift[i] < 1.0, "{i}: {radius:?}");
    }
    // The spectrum it brings, at 400, 500, 600 and 700 nm: the disk's light, none from the hole.
    let spectrum = ["S0.400,000000nm", "S0.500,000000nm", "S0.600,000000nm", "S0.700,000000nm"].map(named);
    assert!(on_disk.iter().all(|&i| spectrum.iter().all(|s| s[i] > 0.0)));
    assert!(spectrum.iter().all(|s| s[centre].is_nan()) && spectrum.iter().all(|s| s[0] == 0.0));
    // A PNG cannot hold them: the command refuses before rendering.
    let png = temp("disk-data.png");
    let out = nullpath().args(["render", scene.to_str().unwrap(), "-o", png.to_str().unwrap()]).output().unwrap();
    assert!(!out.status.success());
    assert!(String::from_utf8_lossy(&out.stderr).contains("only an .exr image holds"));
    // --data-only writes the same channels, bit for bit, and no colour.
    let data = temp("disk-data-only.exr");
    let stats = temp("disk-data-only.json");
    let status = nullpath()
        .args(["render", scene.to_str().unwrap(), "-o", data.to_str().unwrap(), "--data-only", "--quiet"])
        .args(["--stats", stats.to_str().unwrap()])
        .status();
    assert!(status.unwrap().success());
    let only = exr::prelude::read_all_flat_layers_from_file(&data).unwrap();
    let bits = |c: &exr::prelude::AnyChannel<exr::prelude::FlatSamples>| {
        (c.name.to_string(), c.sample_data.values_as_f32().map(f32::to_bits).collect::<Vec<u32>>())
    };
    let is_colour = |(name, _): &(String, Vec<u32>)| ["R", "G", "B"].contains(&name.as_str());
    let beside_colour: Vec<_> = channels.iter().map(bits).filter(|c| !is_colour(c)).collect();
    assert_eq!(only.layer_data[0].channel_data.list.iter().map(bits).collect::<Vec<_>>(), beside_colour);
    let stats: serde_json::Value = serde_json::from_str(&std::fs::read_to_string(&stats).unwrap()).unwrap();
    assert_eq!(stats["rays"], 81);
    assert_eq!(stats["fates"]["captured"], fate.iter().filter(|&&f| f == 4.0).count());
    assert_eq!(stats["fates"]["emitter"], on_disk.len());
    // It refuses what it cannot honour: a PNG, a sample count, parts, a scene without channels.
    let refused = |extra: &[&str], scene: &str, expected: &str| {
        let out = nullpath().args(["render", scene, "--data-only"]).args(extra).output().unwrap();
        let stderr = String::from_utf8_lossy(&out.stderr).into_owned();
        assert!(!out.status.success() && stderr.contains(expected), "{extra:?}: {stderr}");
    };
    let scene = scene.to_str().unwrap();
    refused(&["-o", png.to_str().unwrap()], scene, "only an .exr image holds");
    refused(&["-o", data.to_str().unwrap(), "--spp", "4"], scene, "--spp does not apply to --data-only");
    refused(&["-o", data.to_str().unwrap(), "--part", "1/2"], scene, "cannot be used with");
    let plain = temp("disk-no-data.toml");
    std::fs::write(&plain, "[camera]\nposition = [0, 0, 10]\nlook_at = [0, 0, 0]\n").unwrap();
    refused(&["-o", data.to_str().unwrap()], plain.to_str().unwrap(), "the scene asks for none");
}

#[test]
fn spectral_rendering_is_one_flag_and_photon_mapping_refuses_it() {
    let cornell = concat!(env!("CARGO_MANIFEST_DIR"), "/scenes/cornell-box.toml");
    let out = temp("cornell-spectral.exr");
    let args = ["render", cornell, "-o", out.to_str().unwrap(), "--width", "8", "--height", "8", "--spp", "2"];
    let status = nullpath().args(args).arg("--spectral").arg("--quiet").status().unwrap();
    assert!(status.success());
    let image = exr::prelude::read_all_flat_layers_from_file(&out).unwrap();
    let red = image.layer_data[0].channel_data.list.iter().find(|c| c.name.to_string() == "R").unwrap();
    assert!(red.sample_data.values_as_f32().any(|v| v > 0.0), "a lit box");
    let kerr = concat!(env!("CARGO_MANIFEST_DIR"), "/scenes/kerr-room.toml");
    let refused = nullpath().args(["render", kerr, "-o", out.to_str().unwrap(), "--spectral"]).output().unwrap();
    assert!(!refused.status.success());
    assert!(String::from_utf8_lossy(&refused.stderr).contains("--spectral needs a path tracer"));
}

//! `nullpath bench room` as a user runs it: one JSON object with both scenes' measurements and
//! the curved ÷ flat ratio of each interleaved pair with their median (and `bench spectral`'s
//! spectral ÷ RGB); bad sizes are refused.

#![allow(clippy::unwrap_used)] // A panic is a failed test.

use std::process::Command;

fn nullpath(args: &[&str]) -> std::process::Output {
    Command::new(env!("CARGO_BIN_EXE_nullpath")).args(args).output().unwrap()
}

#[test]
fn the_room_reports_each_pairs_ratio_and_their_median() {
    let out = nullpath(&["bench", "room", "--size", "4", "--repeat", "3", "--json"]);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(v["workload"], "room");
    for (scene, name) in [("curved", "room (black hole)"), ("flat", "room (mass 0)")] {
        assert_eq!(v[scene]["workload"], name);
        let results = v[scene]["results"].as_array().unwrap();
        assert_eq!(results[0]["threads"], 1);
        // 4 × 4 pixels at 64 samples each.
        assert!(results.iter().all(|r| r["samples"] == 1024 && r["seconds"].as_f64().unwrap() > 0.0));
    }
    // One pair per repetition on all threads; the median is the middle one of three.
    let mut pairs: Vec<f64> =
        v["curved_over_flat"]["pairs"].as_array().unwrap().iter().map(|r| r.as_f64().unwrap()).collect();
    assert_eq!(pairs.len(), 3);
    assert!(pairs.iter().all(|r| r.is_finite() && *r > 0.0), "{pairs:?}");
    pairs.sort_by(f64::total_cmp);
    assert_eq!(v["curved_over_flat"]["median"].as_f64().unwrap(), pairs[1]);
}

#[test]
fn the_spectral_workload_pairs_spectral_and_rgb_renders_of_the_room() {
    let out = nullpath(&["bench", "spectral", "--size", "4", "--repeat", "2", "--json"]);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(v["workload"], "spectral");
    assert_eq!(v["spectral"]["workload"], "room (spectral)");
    assert_eq!(v["rgb"]["workload"], "room (RGB)");
    let pairs = v["spectral_over_rgb"]["pairs"].as_array().unwrap();
    assert_eq!(pairs.len(), 2);
    assert!(v["spectral_over_rgb"]["median"].as_f64().unwrap() > 0.0);
}

#[test]
fn a_size_out_of_range_is_refused() {
    let out = nullpath(&["bench", "room", "--size", "0"]);
    assert!(!out.status.success());
    assert!(String::from_utf8_lossy(&out.stderr).contains("--size 0"), "{}", String::from_utf8_lossy(&out.stderr));
}

#[test]
fn the_mesh_workload_reports_millions_of_triangles_and_writes_its_image() {
    let image = std::env::temp_dir().join(format!("nullpath-bench-mesh-{}.png", std::process::id()));
    let out =
        nullpath(&["bench", "mesh", "--size", "6", "--repeat", "1", "--json", "--image", image.to_str().unwrap()]);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    // A rock of 4·500² triangles in the world's BVH, and twelve instances of another.
    assert_eq!(v["triangles"]["stored"], 2_000_000);
    assert_eq!(v["triangles"]["rendered"], 13_000_000);
    assert!(v["bvh_build_seconds"].as_f64().unwrap() > 0.0);
    if cfg!(target_os = "linux") {
        // The triangles, their shapes and BVH nodes: well over 50 bytes each, and instancing
        // keeps it far below the 13 M rendered ones' share of a few GB.
        let bytes = v["bytes_per_stored_triangle"].as_f64().unwrap();
        assert!((50.0..1000.0).contains(&bytes), "{bytes} bytes a triangle");
    }
    assert_eq!(v["room"]["workload"], "room");
    assert!(v["meshes_over_room"]["median"].as_f64().unwrap() > 0.0);
    assert!(image::open(&image).is_ok());
    std::fs::remove_file(&image).unwrap();
}

#[test]
fn the_disk_workload_traces_one_ray_a_pixel() {
    let out = nullpath(&["bench", "disk", "--size", "8", "--repeat", "1", "--json"]);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!((v["workload"].as_str(), v["spp"].as_u64(), v["max_depth"].as_u64()), (Some("disk"), Some(1), Some(0)));
    for r in v["results"].as_array().unwrap() {
        // 8 × 8 pixels, one camera ray each and no bounce.
        assert_eq!((r["samples"].as_u64(), r["rays"].as_u64()), (Some(64), Some(64)));
        assert!(r["rays_per_second"].as_f64().unwrap() > 0.0);
    }
}

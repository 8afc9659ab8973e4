//! Long renders as users run them: interrupted by SIGINT, SIGTERM or a time limit and resumed
//! from the checkpoint, split into parts and merged, and nothing lost on the way (the previous
//! image kept, unwritable paths refused before rendering, interruption answered at once).

#![allow(clippy::unwrap_used)] // A panic is a failed test.
#![cfg(unix)]

mod common;

use common::deadline::{output_within, ANSWER};
use std::path::{Path, PathBuf};
use std::process::{Child, Command, Output, Stdio};
use std::time::{Duration, Instant};

const CORNELL: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/scenes/cornell-box.toml");
/// A size whose samples are cheap, so that tests stay short.
const SIZE: [&str; 4] = ["--width", "40", "--height", "32"];

fn nullpath() -> Command {
    Command::new(env!("CARGO_BIN_EXE_nullpath"))
}

/// A fresh directory for one test.
fn temp_dir(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("nullpath-checkpoint-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

fn arg(path: &Path) -> &str {
    path.to_str().unwrap()
}

/// `nullpath render CORNELL SIZE --quiet` plus `args`, run to the end.
fn render(args: &[&str]) -> Output {
    render_scene(CORNELL, args)
}

/// `nullpath render SCENE SIZE --quiet` plus `args`, run to the end.
fn render_scene(scene: &str, args: &[&str]) -> Output {
    nullpath().args(["render", scene]).args(SIZE).arg("--quiet").args(args).output().unwrap()
}

/// The same, started and left running.
fn start(scene: &str, args: &[&str]) -> Child {
    nullpath().args(["render", scene]).args(SIZE).arg("--quiet").args(args).stderr(Stdio::piped()).spawn().unwrap()
}

/// The Cornell box rendered by photon mapping, as a scene file in `dir`.
fn photon_cornell(dir: &Path) -> String {
    let text =
        std::fs::read_to_string(CORNELL).unwrap().replacen("[render]\n", "[render]\nintegrator = \"photon\"\n", 1);
    assert!(text.contains("integrator = \"photon\""));
    let path = dir.join("photon-cornell.toml");
    std::fs::write(&path, text).unwrap();
    arg(&path).to_owned()
}

fn signal(child: &Child, name: &str) {
    assert!(Command::new("kill").args([&format!("-{name}"), &child.id().to_string()]).status().unwrap().success());
}

/// The decoded pixels of an EXR image (exact `f32`s).
fn pixels(path: &Path) -> Vec<f32> {
    image::open(path).unwrap_or_else(|e| panic!("{}: {e}", path.display())).into_rgb32f().into_raw()
}

/// A metadata entry of an image or checkpoint, through `nullpath info --json`.
fn info(path: &Path, key: &str) -> String {
    let out = nullpath().args(["info", "--json", arg(path)]).output().unwrap();
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    v["metadata"][key].as_str().unwrap_or_else(|| panic!("no {key} in {v}")).to_owned()
}

fn stderr(out: &Output) -> String {
    String::from_utf8_lossy(&out.stderr).into_owned()
}

/// Interrupts a render of a million samples per pixel (or photon-mapping iterations, with
/// `photon`) with `stop` (a signal name, or a time limit), resumes it from its checkpoint to a
/// few samples more than it reached, and checks the image against an uninterrupted render of as
/// many samples.
fn interrupted_and_resumed(stop: &str, photon: bool) {
    let dir = temp_dir(&format!("{stop}-{photon}"));
    let scene = if photon { photon_cornell(&dir) } else { CORNELL.to_owned() };
    let render = |args: &[&str]| render_scene(&scene, args);
    let (out, checkpoint) = (dir.join("image.exr"), dir.join("image.checkpoint.exr"));
    let stopped = if stop == "time-limit" {
        render(&["-o", arg(&out), "--spp", "1000000", "--time-limit", "2s"])
    } else {
        let child = start(&scene, &["-o", arg(&out), "--spp", "1000000"]);
        std::thread::sleep(Duration::from_millis(1500));
        signal(&child, stop);
        child.wait_with_output().unwrap()
    };
    let expected_code = match stop {
        "INT" => 130,
        "TERM" => 143,
        _ => 75,
    };
    assert_eq!(stopped.status.code(), Some(expected_code), "{}", stderr(&stopped));
    assert!(stderr(&stopped).contains("--resume"), "{}", stderr(&stopped));
    assert!(!out.exists(), "an interrupted render writes no image");
    let reached: u32 = info(&checkpoint, "spp").parse().unwrap();
    assert!(reached > 0, "the checkpoint holds samples");

    let spp = (reached + 3).to_string();
    let resumed = render(&["-o", arg(&out), "--spp", &spp, "--resume", arg(&checkpoint), "--threads", "1"]);
    assert!(resumed.status.success(), "{}", stderr(&resumed));
    assert!(!checkpoint.exists(), "the finished render removes the checkpoint it continued");
    let reference = dir.join("reference.exr");
    assert!(render(&["-o", arg(&reference), "--spp", &spp]).status.success());
    assert_eq!(pixels(&out), pixels(&reference), "resumed after {stop}: {reached} then {spp} spp");
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn a_render_interrupted_by_sigint_resumes_bit_identically() {
    interrupted_and_resumed("INT", false);
}

#[test]
fn a_render_interrupted_by_sigterm_resumes_bit_identically() {
    interrupted_and_resumed("TERM", false);
}

#[test]
fn a_render_stopped_at_its_time_limit_resumes_bit_identically() {
    interrupted_and_resumed("time-limit", false);
}

#[test]
fn a_photon_mapping_render_interrupted_by_sigint_resumes_bit_identically() {
    interrupted_and_resumed("INT", true);
}

#[test]
fn a_photon_mapping_render_stopped_at_its_time_limit_resumes_bit_identically() {
    interrupted_and_resumed("time-limit", true);
}

#[test]
fn photon_mapping_refuses_parts_and_noise_targets_with_reasons() {
    let dir = temp_dir("photon-refusals");
    let scene = photon_cornell(&dir);
    for (flags, reason) in [(["--part", "1/2"], "every photon"), (["--noise-target", "0.05"], "mostly bias")] {
        let out = render_scene(&scene, &[&["-o", arg(&dir.join("x.png"))], &flags[..]].concat());
        assert_eq!(out.status.code(), Some(1), "{flags:?}");
        assert!(stderr(&out).contains(reason), "{flags:?}: {}", stderr(&out));
    }
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn damaged_and_mismatched_checkpoints_are_refused_untouched() {
    let dir = temp_dir("refused");
    let (out, checkpoint) = (dir.join("image.png"), dir.join("state.exr"));
    let made = render(&["-o", arg(&out), "--spp", "4", "--checkpoint", arg(&checkpoint)]);
    assert!(made.status.success(), "{}", stderr(&made));
    let bytes = std::fs::read(&checkpoint).unwrap();
    let refused = |args: &[&str], needle: &str| {
        let out = render(&[&["-o", arg(&dir.join("again.png")), "--resume", arg(&checkpoint)], args].concat());
        assert_eq!(out.status.code(), Some(1), "{args:?}");
        assert!(stderr(&out).contains(needle), "{args:?}: {}", stderr(&out));
        assert!(!stderr(&out).contains("panicked"));
        assert_eq!(std::fs::read(&checkpoint).unwrap(), bytes, "{args:?}: the checkpoint was touched");
    };
    refused(&["--seed", "5"], "seed 0 → 5");
    refused(&["--spp", "2"], "already has 4 samples");
    let out = nullpath()
        .args(["render", concat!(env!("CARGO_MANIFEST_DIR"), "/scenes/lensing-sky.toml")])
        .args(SIZE)
        .args(["-o", arg(&dir.join("sky.png")), "--resume", arg(&checkpoint)])
        .output()
        .unwrap();
    assert!(stderr(&out).contains("cannot continue"), "{}", stderr(&out));
    // A damaged copy: one byte flipped in its last block.
    let damaged = dir.join("damaged.exr");
    let mut broken = bytes.clone();
    let last = broken.len() - 5;
    broken[last] ^= 0x21;
    std::fs::write(&damaged, &broken).unwrap();
    let out = render(&["-o", arg(&dir.join("d.png")), "--resume", arg(&damaged)]);
    assert_eq!(out.status.code(), Some(1));
    assert!(stderr(&out).contains("not a usable checkpoint"), "{}", stderr(&out));
    assert_eq!(std::fs::read(&damaged).unwrap(), broken);
    // An image is not a checkpoint.
    let out = render(&["-o", arg(&dir.join("i.png")), "--resume", arg(&out_exr(&dir))]);
    assert!(stderr(&out).contains("not a checkpoint"), "{}", stderr(&out));
    std::fs::remove_dir_all(&dir).unwrap();
}

/// A finished EXR image in `dir`.
fn out_exr(dir: &Path) -> PathBuf {
    let path = dir.join("plain.exr");
    assert!(render(&["-o", arg(&path), "--spp", "1"]).status.success());
    path
}

#[test]
fn merged_parts_are_the_single_render_bit_for_bit() {
    let dir = temp_dir("parts");
    let single = dir.join("single.exr");
    assert!(render(&["-o", arg(&single), "--spp", "3"]).status.success());
    for n in [1u32, 2, 7] {
        let parts: Vec<PathBuf> = (1..=n).map(|i| dir.join(format!("part-{i}-of-{n}.exr"))).collect();
        for (i, part) in parts.iter().enumerate() {
            let (spec, threads) = (format!("{}/{n}", i + 1), if i % 2 == 0 { "1" } else { "2" });
            let out = render(&["-o", arg(part), "--spp", "3", "--part", &spec, "--threads", threads]);
            assert!(out.status.success(), "{spec}: {}", stderr(&out));
        }
        let merged = dir.join(format!("merged-{n}.exr"));
        let mut merge = nullpath();
        merge.args(["merge", "--quiet", "-o", arg(&merged)]);
        // In any order.
        parts.iter().rev().for_each(|p| {
            merge.arg(p);
        });
        let out = merge.output().unwrap();
        assert!(out.status.success(), "{n} parts: {}", stderr(&out));
        assert_eq!(pixels(&merged), pixels(&single), "{n} parts");
        // Part N/N comes first, and of 7 it holds no tiles: the image still records 3 samples.
        assert_eq!(info(&merged, "spp"), "3", "{n} parts");
        if n == 7 {
            // A missing part, a part twice and parts of another render are refused.
            let out = nullpath().args(["merge", "-o", arg(&merged)]).args(&parts[..6]).output().unwrap();
            assert!(stderr(&out).contains("parts 7/7 are missing"), "{}", stderr(&out));
            let out = nullpath().args(["merge", "-o", arg(&merged), arg(&parts[0]), arg(&parts[0])]).output().unwrap();
            assert!(stderr(&out).contains("both part 1/7"), "{}", stderr(&out));
            let other = dir.join("other.exr");
            assert!(render(&["-o", arg(&other), "--spp", "3", "--seed", "9", "--part", "7/7"]).status.success());
            let out = nullpath().args(["merge", "-o", arg(&merged)]).args(&parts[..6]).arg(&other).output().unwrap();
            assert!(stderr(&out).contains("different renders"), "{}", stderr(&out));
        }
    }
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn an_interrupt_is_answered_at_once_and_the_previous_image_is_kept() {
    let dir = temp_dir("nothing-lost");
    let out = dir.join("image.png");
    assert!(render(&["-o", arg(&out), "--spp", "2"]).status.success());
    let finished = std::fs::read(&out).unwrap();
    let child = start(CORNELL, &["-o", arg(&out), "--spp", "1000000"]);
    std::thread::sleep(Duration::from_millis(1500));
    signal(&child, "INT");
    // The million samples a pixel would take hours.
    let result = output_within(child, ANSWER, "the interrupted render");
    assert_eq!(result.status.code(), Some(130), "{}", stderr(&result));
    assert_eq!(std::fs::read(&out).unwrap(), finished, "the finished image was replaced");
    assert!(dir.join("image.checkpoint.exr").exists());
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn a_second_interrupt_quits_at_once() {
    let dir = temp_dir("second-interrupt");
    let out = dir.join("image.png");
    // A large image, whose checkpoint takes a few seconds to write after the first Ctrl-C.
    let child = nullpath()
        .args(["render", CORNELL, "--width", "3000", "--height", "2000", "--spp", "1000000", "--quiet"])
        .args(["-o", arg(&out)])
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    std::thread::sleep(Duration::from_millis(1500));
    signal(&child, "INT");
    // Well past the 0.1 s within which a second SIGINT is a copy of the first press.
    std::thread::sleep(Duration::from_millis(400));
    signal(&child, "INT");
    let result = output_within(child, ANSWER, "the render interrupted twice");
    assert_eq!(result.status.code(), Some(130), "{}", stderr(&result));
    // It quit without finishing the first interrupt's checkpoint.
    assert!(!stderr(&result).contains("--resume"), "the first interrupt's answer finished: {}", stderr(&result));
    assert!(!dir.join("image.checkpoint.exr").exists(), "the checkpoint was written");
    assert!(!out.exists());
    std::fs::remove_dir_all(&dir).unwrap();
}

/// Starts a render of a million samples per pixel in `dir` that writes its checkpoint every
/// 50 ms, and waits for the first: the signal handlers are in place by then.
fn start_and_wait_for_checkpoint(dir: &Path) -> (Child, PathBuf) {
    let (out, checkpoint) = (dir.join("image.exr"), dir.join("state.exr"));
    let _ = std::fs::remove_file(&checkpoint);
    let child = start(
        CORNELL,
        &["-o", arg(&out), "--spp", "1000000", "--checkpoint", arg(&checkpoint), "--checkpoint-every", "0.05"],
    );
    let started = Instant::now();
    while !checkpoint.exists() {
        assert!(started.elapsed() < Duration::from_secs(60), "no checkpoint after a minute");
        std::thread::sleep(Duration::from_millis(5));
    }
    (child, checkpoint)
}

#[test]
fn a_repeated_sigterm_is_the_same_request_and_the_checkpoint_is_written() {
    // `timeout` and supervisors that signal the process group after the process send SIGTERM
    // twice within microseconds; others resend it later. Neither may cost the work.
    let dir = temp_dir("repeated-sigterm");
    for run in 0..10 {
        let (child, checkpoint) = start_and_wait_for_checkpoint(&dir);
        let pid = child.id().to_string();
        if run % 2 == 0 {
            // One `kill`, two signals: microseconds apart.
            assert!(Command::new("kill").args(["-TERM", &pid, &pid]).status().unwrap().success());
        } else {
            signal(&child, "TERM");
            std::thread::sleep(Duration::from_millis(1));
            signal(&child, if run == 9 { "HUP" } else { "TERM" });
        }
        let result = child.wait_with_output().unwrap();
        let message = stderr(&result);
        // When a SIGHUP follows, both may be pending when the signal thread wakes, and it reads
        // pending signals in number order: either names the stop, and neither loses the work.
        let sighup = run == 9 && message.contains("interrupted by SIGHUP");
        let (code, name) = if sighup { (129, "SIGHUP") } else { (143, "SIGTERM") };
        assert_eq!(result.status.code(), Some(code), "run {run}: {message}");
        assert!(message.contains(&format!("interrupted by {name}")), "run {run}: {message}");
        assert!(message.contains(&format!("the work is in the checkpoint {}", checkpoint.display())), "run {run}");
        assert!(message.contains("--resume"), "run {run}: {message}");
        assert!(info(&checkpoint, "spp").parse::<u32>().unwrap() > 0, "run {run}");
    }
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn copies_of_one_ctrl_c_are_one_request() {
    // A wrapper that forwards the SIGINT the terminal sent to the whole group as well.
    let dir = temp_dir("sigint-copies");
    for run in 0..3 {
        let (child, checkpoint) = start_and_wait_for_checkpoint(&dir);
        let pid = child.id().to_string();
        assert!(Command::new("kill").args(["-INT", &pid, &pid]).status().unwrap().success());
        let result = child.wait_with_output().unwrap();
        let message = stderr(&result);
        assert_eq!(result.status.code(), Some(130), "run {run}: {message}");
        assert!(message.contains("interrupted by SIGINT (Ctrl-C)") && message.contains("--resume"), "{message}");
        assert!(checkpoint.exists());
    }
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn the_time_limit_is_news_not_an_error() {
    let dir = temp_dir("time-limit-message");
    let (out, checkpoint) = (dir.join("image.exr"), dir.join("image.checkpoint.exr"));
    let stopped = render(&["-o", arg(&out), "--spp", "1000000", "--time-limit", "1s"]);
    let message = stderr(&stopped);
    assert_eq!(stopped.status.code(), Some(75), "{message}");
    assert!(message.starts_with("nullpath: stopped at the time limit (1s) at "), "{message}");
    assert!(!message.contains("error"), "{message}");
    let expected = format!(
        "samples per pixel; the work is in the checkpoint {c} ({o} was not touched). \
         Continue with the same command and --resume {c}\n",
        c = checkpoint.display(),
        o = out.display()
    );
    assert!(message.ends_with(&expected), "{message}");
    assert!(!out.exists());
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn parts_of_different_samples_are_not_merged() {
    let dir = temp_dir("merge-spp");
    let (first, second, merged) = (dir.join("p1.exr"), dir.join("p2.exr"), dir.join("merged.exr"));
    assert!(render(&["-o", arg(&first), "--spp", "2", "--part", "1/2"]).status.success());
    assert!(render(&["-o", arg(&second), "--spp", "4", "--part", "2/2"]).status.success());
    let out = nullpath().args(["merge", "-o", arg(&merged), arg(&first), arg(&second)]).output().unwrap();
    let message = stderr(&out);
    assert_eq!(out.status.code(), Some(1), "{message}");
    let figures =
        format!("{} (part 1/2) has 2 samples per pixel but {} (part 2/2) has 4", first.display(), second.display());
    assert!(message.contains(&figures), "{message}");
    assert!(!merged.exists());
    // The remedy the message gives: continue the part with fewer samples into itself.
    let remedy = format!("--part 1/2 --spp 4 --resume {} -o {}", first.display(), first.display());
    assert!(message.contains(&remedy), "{message}");
    assert!(render(&["-o", arg(&first), "--spp", "4", "--part", "1/2", "--resume", arg(&first)]).status.success());
    let out = nullpath().args(["merge", "--quiet", "-o", arg(&merged), arg(&first), arg(&second)]).output().unwrap();
    assert!(out.status.success(), "{}", stderr(&out));
    assert_eq!(info(&merged, "spp"), "4");
    let single = dir.join("single.exr");
    assert!(render(&["-o", arg(&single), "--spp", "4"]).status.success());
    assert_eq!(pixels(&merged), pixels(&single));
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn unwritable_paths_and_impossible_sizes_are_refused_before_rendering() {
    let dir = temp_dir("refused-early");
    let good = dir.join("fine.png");
    let huge = ["--width", "16384", "--height", "16384"];
    let cases: Vec<(Vec<&str>, &str)> = vec![
        // Even root cannot create files in /proc.
        (vec!["-o", "/proc/nullpath-test.png"], "/proc/nullpath-test.png"),
        (vec!["-o", arg(&good), "--stats", "/proc/nullpath-stats.json"], "/proc/nullpath-stats.json"),
        (vec!["-o", arg(&good), "--checkpoint", "/proc/nullpath.exr"], "/proc/nullpath.exr"),
        (vec!["-o", arg(&good), "--checkpoint", "state.png"], "must be an .exr"),
        (vec!["-o", arg(&good), "--threads", "100000"], "--threads"),
        ([&["-o", arg(&good), "--max-memory", "1G"][..], &huge[..]].concat(), "GiB"),
        (vec!["-o", arg(&good), "--noise-target", "2"], "--noise-target"),
        (vec!["-o", arg(&good), "--part", "3/2"], "part 3/2"),
    ];
    for (args, needle) in cases {
        // Refused up front: the million samples a pixel it would render first take hours.
        let child = nullpath()
            .args(["render", CORNELL, "--spp", "1000000", "--quiet"])
            .args(&args)
            .stderr(Stdio::piped())
            .spawn()
            .unwrap();
        let out = output_within(child, ANSWER, &format!("{args:?}"));
        assert_eq!(out.status.code(), Some(if needle == "part 3/2" { 2 } else { 1 }), "{args:?}: {}", stderr(&out));
        assert!(stderr(&out).contains(needle), "{args:?}: {}", stderr(&out));
        assert!(!stderr(&out).contains("panicked"), "{args:?}");
    }
    assert!(!good.exists());
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn a_killed_writers_temporary_file_is_cleaned_up() {
    let dir = temp_dir("stale");
    // No process has this id (the kernel's limit is below it), so its temporary is stale.
    let stale = dir.join(".image.png.partial-2000000000");
    std::fs::write(&stale, b"half an image").unwrap();
    assert!(render(&["-o", arg(&dir.join("image.png")), "--spp", "1"]).status.success());
    assert!(!stale.exists());
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn images_carry_what_made_them() {
    let dir = temp_dir("metadata");
    for name in ["image.png", "image.exr"] {
        let out = dir.join(name);
        assert!(render(&["-o", arg(&out), "--spp", "2", "--seed", "17"]).status.success());
        assert_eq!(info(&out, "seed"), "17");
        assert_eq!(info(&out, "spp"), "2");
        assert_eq!(info(&out, "version"), env!("CARGO_PKG_VERSION"));
        assert_eq!(info(&out, "scene"), CORNELL);
        assert!(info(&out, "scene.source").contains("[camera]"));
        let settings: serde_json::Value = serde_json::from_str(&info(&out, "settings")).unwrap();
        assert_eq!(settings["width"], 40);
    }
    let text = nullpath().args(["info", arg(&dir.join("image.png"))]).output().unwrap();
    assert!(String::from_utf8_lossy(&text.stdout).contains("seed: 17"));
    std::fs::remove_dir_all(&dir).unwrap();
}

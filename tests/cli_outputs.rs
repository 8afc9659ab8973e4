//! The files nullpath writes: never one it reads or another it writes, refused before any
//! rendering with both roles named; the checkpoint (or part file) continued into itself is the
//! one file brought up to date in place; statistics are replaced whole.

#![allow(clippy::unwrap_used)] // A panic is a failed test.
#![cfg(unix)]

mod common;

use common::deadline::{output_within, ANSWER};
use std::path::{Path, PathBuf};
use std::process::{Command, Output, Stdio};

const CORNELL: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/scenes/cornell-box.toml");
const FLYTHROUGH: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/scenes/room-black-hole-flythrough.toml");
/// A size whose samples are cheap, so that tests stay short.
const SIZE: [&str; 4] = ["--width", "40", "--height", "32"];

/// `nullpath`, run in `dir`, so that paths can be spelled relative to it.
fn nullpath(dir: &Path) -> Command {
    let mut command = Command::new(env!("CARGO_BIN_EXE_nullpath"));
    command.current_dir(dir);
    command
}

/// A fresh directory for one test, holding a copy of the Cornell box as `scene.toml`.
fn temp_dir(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("nullpath-outputs-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::copy(CORNELL, dir.join("scene.toml")).unwrap();
    dir
}

fn stderr(out: &Output) -> String {
    String::from_utf8_lossy(&out.stderr).into_owned()
}

/// `nullpath render scene.toml SIZE --quiet` plus `args`, in `dir`.
fn render(dir: &Path, args: &[&str]) -> Output {
    nullpath(dir).args(["render", "scene.toml"]).args(SIZE).arg("--quiet").args(args).output().unwrap()
}

/// The bytes of every file in `dir`, by name.
fn snapshot(dir: &Path) -> Vec<(String, Vec<u8>)> {
    let mut files: Vec<(String, Vec<u8>)> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.is_file())
        .map(|p| (p.file_name().unwrap().to_string_lossy().into_owned(), std::fs::read(&p).unwrap()))
        .collect();
    files.sort();
    files
}

#[test]
fn a_file_written_may_be_no_file_read_and_no_other_file_written() {
    let dir = temp_dir("collisions");
    // An image and a checkpoint already there, which a refused command must leave as they are.
    let made = render(&dir, &["-o", "image.exr", "--spp", "2", "--checkpoint", "state.exr"]);
    assert!(made.status.success(), "{}", stderr(&made));
    std::fs::create_dir(dir.join("sub")).unwrap();
    let before = snapshot(&dir);
    let cases: [(&[&str], [&str; 2]); 9] = [
        // The three: a finished image replaced by a checkpoint, a scene and an image by JSON.
        (&["-o", "image.exr", "--checkpoint", "image.exr"], ["--checkpoint", "the image (-o)"]),
        (&["-o", "new.png", "--stats", "scene.toml"], ["--stats", "the scene file"]),
        (&["-o", "image.exr", "--stats", "image.exr"], ["--stats", "the image (-o)"]),
        // Spelled differently, or through a directory and back.
        (&["-o", "./image.exr", "--checkpoint", "image.exr"], ["--checkpoint", "the image (-o)"]),
        (&["-o", "new.exr", "--checkpoint", "sub/../fresh.exr", "--stats", "./fresh.exr"], ["--stats", "--checkpoint"]),
        // The default checkpoint is written on an interruption, so it is taken too.
        (&["-o", "image.exr", "--stats", "image.checkpoint.exr"], ["--stats", "the checkpoint"]),
        // A checkpoint continued is not the image it becomes, nor the statistics.
        (&["-o", "state.exr", "--resume", "state.exr"], ["the image (-o)", "--resume"]),
        (&["-o", "new.png", "--resume", "state.exr", "--stats", "state.exr"], ["--stats", "--resume"]),
        (&["-o", "sub/../scene.toml"], ["the image (-o)", "the scene file"]),
    ];
    for (args, roles) in cases {
        // Refused up front: the million samples a pixel it would render first take hours.
        let mut command = nullpath(&dir);
        command.args(["render", "scene.toml"]).args(SIZE).args(["--quiet", "--spp", "1000000"]).args(args);
        let out = output_within(command.stderr(Stdio::piped()).spawn().unwrap(), ANSWER, &format!("{args:?}"));
        let message = stderr(&out);
        assert_eq!(out.status.code(), Some(1), "{args:?}: {message}");
        assert!(message.contains("is the same file as"), "{args:?}: {message}");
        for role in roles {
            assert!(message.contains(role), "{args:?}: no {role} in {message}");
        }
        assert!(!message.contains("panicked"), "{args:?}");
        assert_eq!(snapshot(&dir), before, "{args:?}: a file was touched");
    }
    // The data channels alone have an image and statistics too.
    let out = render(&dir, &["--data-only", "-o", "data.exr", "--stats", "./data.exr"]);
    let expected = "--stats './data.exr' is the same file as the data image (-o) 'data.exr'";
    assert!(stderr(&out).contains(expected), "{}", stderr(&out));
    assert_eq!(out.status.code(), Some(1));
    assert_eq!(snapshot(&dir), before);
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn merge_and_animate_write_over_none_of_their_inputs() {
    let dir = temp_dir("merge-animate");
    for i in 1..=2 {
        let part = format!("part-{i}.exr");
        let out = render(&dir, &["-o", &part, "--spp", "2", "--part", &format!("{i}/2")]);
        assert!(out.status.success(), "{}", stderr(&out));
    }
    let before = snapshot(&dir);
    let out = nullpath(&dir).args(["merge", "-o", "./part-2.exr", "part-1.exr", "part-2.exr"]).output().unwrap();
    assert_eq!(out.status.code(), Some(1), "{}", stderr(&out));
    assert!(stderr(&out).contains("the merged image (-o) './part-2.exr' is the same file as the part file"));
    assert_eq!(snapshot(&dir), before);
    // An animation's video over its scene, or over one of its frames.
    std::fs::copy(FLYTHROUGH, dir.join("fly.toml")).unwrap();
    std::fs::create_dir(dir.join("frames")).unwrap();
    for (video, roles) in
        [("fly.toml", ["--video", "the scene file"]), ("frames/frame_00001.png", ["frame 1", "--video"])]
    {
        let out = nullpath(&dir)
            .args(["animate", "fly.toml", "-o", "frames", "--frames", "0..3", "--video", video])
            .args(SIZE)
            .output()
            .unwrap();
        assert_eq!(out.status.code(), Some(1), "{video}: {}", stderr(&out));
        for role in roles {
            assert!(stderr(&out).contains(role), "{video}: no {role} in {}", stderr(&out));
        }
        assert_eq!(std::fs::read(dir.join("fly.toml")).unwrap(), std::fs::read(FLYTHROUGH).unwrap());
        assert_eq!(std::fs::read_dir(dir.join("frames")).unwrap().count(), 0, "{video}: a frame was rendered");
    }
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn a_checkpoint_or_part_continued_into_itself_is_brought_up_to_date() {
    let dir = temp_dir("in-place");
    let info_spp = |file: &str| {
        let out = nullpath(&dir).args(["info", "--json", file]).output().unwrap();
        let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
        v["metadata"]["spp"].as_str().unwrap().to_owned()
    };
    // --resume and --checkpoint the same file, spelled two ways.
    let out = render(&dir, &["-o", "image.png", "--spp", "2", "--checkpoint", "state.exr"]);
    assert!(out.status.success(), "{}", stderr(&out));
    let out = render(&dir, &["-o", "image.png", "--spp", "5", "--resume", "./state.exr", "--checkpoint", "state.exr"]);
    assert!(out.status.success(), "{}", stderr(&out));
    assert_eq!(info_spp("state.exr"), "5");
    // A part file continued into itself.
    let out = render(&dir, &["-o", "part.exr", "--spp", "2", "--part", "1/2"]);
    assert!(out.status.success(), "{}", stderr(&out));
    let out = render(&dir, &["-o", "part.exr", "--spp", "3", "--part", "1/2", "--resume", "./part.exr"]);
    assert!(out.status.success(), "{}", stderr(&out));
    assert_eq!(info_spp("part.exr"), "3");
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn statistics_replace_the_previous_file_whole() {
    let dir = temp_dir("stats");
    // A longer file than the statistics: a write in place that did not truncate would leave its tail.
    std::fs::write(dir.join("stats.json"), "x".repeat(100_000)).unwrap();
    let out = render(&dir, &["-o", "image.png", "--spp", "1", "--stats", "stats.json"]);
    assert!(out.status.success(), "{}", stderr(&out));
    let stats: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("stats.json")).unwrap()).unwrap();
    assert_eq!(stats["spp"], 1);
    let names: Vec<String> =
        std::fs::read_dir(&dir).unwrap().map(|e| e.unwrap().file_name().to_string_lossy().into_owned()).collect();
    assert!(!names.iter().any(|n| n.contains("partial")), "a temporary file is left: {names:?}");
    // A directory is no place for statistics, and is found out before rendering.
    std::fs::create_dir(dir.join("stats-dir")).unwrap();
    let out = render(&dir, &["-o", "image2.png", "--spp", "1000000", "--stats", "stats-dir"]);
    assert_eq!(out.status.code(), Some(1), "{}", stderr(&out));
    assert!(stderr(&out).contains("--stats 'stats-dir': cannot write: it is a directory"), "{}", stderr(&out));
    std::fs::remove_dir_all(&dir).unwrap();
}

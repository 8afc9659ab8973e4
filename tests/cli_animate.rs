//! `nullpath animate` as a user runs it: frames equal stills, interrupted animations resume
//! with only the missing frames, and videos are assembled by ffmpeg when it is there.

#![allow(clippy::unwrap_used)] // A panic is a failed test.

use std::path::{Path, PathBuf};
use std::process::{Command, Output, Stdio};
use std::time::{Duration, Instant, SystemTime};

const FLYTHROUGH: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/scenes/room-black-hole-flythrough.toml");

fn nullpath() -> Command {
    Command::new(env!("CARGO_BIN_EXE_nullpath"))
}

/// A fresh directory for one test.
fn temp_dir(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("nullpath-animate-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

fn run(command: &mut Command) -> Output {
    command.output().unwrap()
}

fn stderr(out: &Output) -> String {
    String::from_utf8_lossy(&out.stderr).into_owned()
}

fn pixels(path: &Path) -> Vec<f32> {
    image::open(path).unwrap().to_rgb32f().into_raw()
}

#[test]
fn frame_n_is_the_still_at_time_n_over_fps() {
    let dir = temp_dir("still");
    let size = ["--width", "20", "--height", "15", "--spp", "2", "--seed", "7"];
    let out = run(nullpath()
        .args(["animate", FLYTHROUGH, "-o", dir.to_str().unwrap(), "--frames", "41..=42", "--format", "exr"])
        .args(size));
    assert!(out.status.success(), "{}", stderr(&out));
    // The flythrough has 12 frames per second; frame 41 is at t = 41/12 s, while it moves.
    let time = format!("{}", 41.0 / 12.0);
    let still = dir.join("still.exr");
    let out = run(nullpath().args(["render", FLYTHROUGH, "-o", still.to_str().unwrap(), "--time", &time]).args(size));
    assert!(out.status.success(), "{}", stderr(&out));
    let frame = pixels(&dir.join("frame_00041.exr"));
    assert_eq!(frame, pixels(&still), "frame 41 differs from the still at t = {time}");
    assert_ne!(frame, pixels(&dir.join("frame_00042.exr")), "consecutive frames of a moving camera differ");
}

fn modified(path: &Path) -> SystemTime {
    std::fs::metadata(path).unwrap().modified().unwrap()
}

#[cfg(unix)]
#[test]
fn an_interrupted_animation_resumes_with_only_the_missing_frames() {
    let dir = temp_dir("resume");
    let args = |c: &mut Command| {
        c.args(["animate", FLYTHROUGH, "-o", dir.to_str().unwrap(), "--frames", "0..30"])
            .args(["--width", "40", "--height", "30", "--spp", "4"]);
    };
    let mut command = nullpath();
    args(&mut command);
    let child = command.stderr(Stdio::piped()).spawn().unwrap();
    // Interrupt as soon as two frames are on disk.
    let start = Instant::now();
    while !dir.join("frame_00001.png").exists() && start.elapsed() < Duration::from_secs(120) {
        std::thread::sleep(Duration::from_millis(5));
    }
    let _ = Command::new("kill").args(["-INT", &child.id().to_string()]).status();
    let first = child.wait_with_output().unwrap();
    assert_eq!(first.status.code(), Some(130), "an interrupted animation says so: {}", stderr(&first));
    let message = stderr(&first);
    assert!(message.contains("nullpath: interrupted by SIGINT (Ctrl-C) in frame"), "{message}");
    assert!(message.contains("Run the same command again"), "{message}");
    let done: Vec<u32> = (0..30).filter(|n| dir.join(format!("frame_{n:05}.png")).exists()).collect();
    let k = done.len() as u32;
    assert!((2..30).contains(&k), "{k} frames finished before the interrupt");
    assert_eq!(done, (0..k).collect::<Vec<_>>(), "frames are finished in order");
    let times: Vec<SystemTime> = done.iter().map(|n| modified(&dir.join(format!("frame_{n:05}.png")))).collect();

    let mut command = nullpath();
    args(&mut command);
    let second = run(&mut command);
    assert!(second.status.success(), "{}", stderr(&second));
    let message = stderr(&second);
    assert!(message.contains(&format!("rendered {}, {k} already complete", 30 - k)), "{message}");
    for (n, t) in done.iter().zip(times) {
        assert_eq!(modified(&dir.join(format!("frame_{n:05}.png"))), t, "frame {n} was rendered again");
    }
    assert!((0..30).all(|n| dir.join(format!("frame_{n:05}.png")).exists()));
}

#[cfg(unix)]
#[test]
fn videos_are_made_by_ffmpeg_or_explained_without_it() {
    use std::os::unix::fs::PermissionsExt;
    let dir = temp_dir("video");
    let frames = dir.join("frames");
    let small = ["--width", "8", "--height", "6", "--spp", "1", "--frames", "3..5", "--quiet"];
    let video = dir.join("out.mp4");
    let animate = |path: &str| {
        run(nullpath()
            .env("PATH", path)
            .args(["animate", FLYTHROUGH, "-o", frames.to_str().unwrap(), "--video", video.to_str().unwrap()])
            .args(small))
    };
    // No ffmpeg on PATH: the frames are made, and the message says how to get the video.
    let empty = dir.join("empty");
    std::fs::create_dir_all(&empty).unwrap();
    let out = animate(empty.to_str().unwrap());
    assert!(!out.status.success());
    assert!(stderr(&out).contains("ffmpeg is not installed"), "{}", stderr(&out));
    assert!(frames.join("frame_00003.png").exists() && frames.join("frame_00004.png").exists());
    // A stand-in ffmpeg records how it is called.
    let bin = dir.join("bin");
    std::fs::create_dir_all(&bin).unwrap();
    let fake = bin.join("ffmpeg");
    let log = dir.join("ffmpeg-args.txt");
    // It writes its last argument, the video, as ffmpeg does.
    let script =
        format!("#!/bin/sh\necho \"$@\" > '{}'\nfor last; do :; done\necho video > \"$last\"\n", log.display());
    std::fs::write(&fake, script).unwrap();
    std::fs::set_permissions(&fake, std::fs::Permissions::from_mode(0o755)).unwrap();
    let out = animate(&format!("{}:/bin:/usr/bin", bin.display()));
    assert!(out.status.success(), "{}", stderr(&out));
    let called = std::fs::read_to_string(&log).unwrap();
    for expected in ["-framerate 12", "-start_number 3", "frame_%05d.png", "-frames:v 2", "libx264", "out.mp4"] {
        assert!(called.contains(expected), "{called:?} lacks {expected:?}");
    }
    // Encoded beside the video under a temporary name, then renamed into place.
    assert!(!called.trim_end().ends_with(video.to_str().unwrap()), "{called:?}: ffmpeg wrote the video itself");
    assert_eq!(std::fs::read_to_string(&video).unwrap(), "video\n");
    let left: Vec<_> = std::fs::read_dir(&dir).unwrap().map(|e| e.unwrap().file_name()).collect();
    assert!(!left.iter().any(|n| n.to_string_lossy().contains("partial")), "{left:?}");
}

#[test]
fn bad_animation_arguments_are_explained() {
    let dir = temp_dir("bad");
    for (args, expected) in [
        (vec!["--frames", "5..2"], "holds no frames"),
        (vec!["--fps", "0"], "--fps must be in (0, 1000]"),
        (vec!["--format", "exr", "--video", "x.mp4"], "use --format png"),
    ] {
        let out = run(nullpath().args(["animate", FLYTHROUGH, "-o", dir.to_str().unwrap()]).args(&args));
        assert!(!out.status.success());
        assert!(stderr(&out).contains(expected), "{args:?}: {}", stderr(&out));
        assert!(!stderr(&out).contains("panicked"));
    }
}

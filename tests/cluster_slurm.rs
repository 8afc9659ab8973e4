//! The Slurm job scripts (cluster/slurm/) run on a real Slurm cluster: a still rendered in parts
//! by a job array and merged by a dependent job equals one `nullpath render`, and the frames of an
//! animation rendered by a job array equal one local `nullpath animate`.
//!
//! These tests need a running cluster whose nodes see this machine's temporary directory (the
//! single-node cluster of `cluster/slurm/local-cluster.sh start` does), so they are ignored by a
//! plain `cargo test`, which lists them as ignored. `cluster/slurm/ci-test.sh` (run by `.ci/run`)
//! starts the local cluster and runs them with `--ignored`, or prints SKIPPED with the reason when
//! this machine cannot run Slurm. Run with `--ignored` and no cluster, they fail: they never pass
//! without having run on Slurm.

#![allow(clippy::unwrap_used)] // A panic is a failed test.

use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

const SUBMIT: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/cluster/slurm/submit.sh");
const NEEDS: &str = "needs a Slurm cluster: run cluster/slurm/local-cluster.sh";
/// Longest wait for a job to finish; the tiny renders take a second, scheduling a few more.
const TIMEOUT: Duration = Duration::from_secs(180);

/// A lens with its own camera motion: a Schwarzschild hole before a grid sky, the camera orbiting
/// it, six frames. Tiny, so the cluster's scheduling dominates the test's time.
const ORBIT: &str = r#"
[spacetime]
type = "schwarzschild"
mass = 1.0

[camera]
position = [0.0, 2.0, 25.0]
look_at = [0.0, 0.0, 0.0]
up = [0, 1, 0]
fov = 45
orbit = { center = [0, 0, 0], axis = [0, 1, 0], period = 6 }

[animation]
fps = 1
frames = 6

[render]
width = 32
height = 24
spp = 2
max_depth = 1

[sky]
type = "grid"
background = [[0.55, 0.12, 0.1], [0.1, 0.4, 0.12], [0.1, 0.12, 0.5], [0.5, 0.42, 0.1]]
line = [0.95, 0.95, 0.95]
spacing_deg = 15
width_deg = 1.5
"#;

/// Writes the fixture scene into `dir`.
fn orbit_scene(dir: &Path) -> PathBuf {
    let scene = dir.join("orbit.toml");
    std::fs::write(&scene, ORBIT).unwrap();
    scene
}

fn nullpath() -> Command {
    Command::new(env!("CARGO_BIN_EXE_nullpath"))
}

/// A fresh directory for one test, in the temporary directory the cluster's node also sees.
fn temp_dir(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("nullpath-slurm-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

fn text(bytes: &[u8]) -> String {
    String::from_utf8_lossy(bytes).into_owned()
}

/// Runs `command`, panicking with its output unless it succeeds; returns its stdout.
fn check(command: &mut Command) -> String {
    let out = command.output().unwrap_or_else(|e| panic!("cannot run {command:?}: {e}"));
    assert!(out.status.success(), "{command:?} failed: {}{}", text(&out.stdout), text(&out.stderr));
    text(&out.stdout)
}

/// The two jobs `submit.sh` submitted; cancelled when dropped, so a failed test leaves no jobs.
struct Jobs {
    render: String,
    merge: String,
}

impl Drop for Jobs {
    fn drop(&mut self) {
        let _ = Command::new("scancel").args([&self.render, &self.merge]).stderr(Stdio::null()).status();
    }
}

/// Submits with `cluster/slurm/submit.sh ARGS` (with `path` before PATH, for the jobs too: they
/// inherit the environment) and reads the job ids it prints.
fn submit(args: &[&str], path: Option<&Path>) -> Jobs {
    let has_slurm = Command::new("sinfo").arg("--version").output().is_ok_and(|o| o.status.success());
    assert!(has_slurm, "no Slurm on this machine: {NEEDS} start");
    let mut command = Command::new("bash");
    command.arg(SUBMIT).args(["--nullpath", env!("CARGO_BIN_EXE_nullpath")]).args(args);
    if let Some(dir) = path {
        command.env("PATH", format!("{}:{}", dir.display(), std::env::var("PATH").unwrap_or_default()));
    }
    let printed = check(&mut command);
    let id = |key: &str| {
        let line = printed.lines().find_map(|l| l.strip_prefix(key));
        line.unwrap_or_else(|| panic!("submit.sh printed no {key}…: {printed}")).to_string()
    };
    Jobs { render: id("render_job="), merge: id("merge_job=") }
}

/// The `JobState` of each job (each task of an array) that `scontrol` reports for `id`.
fn job_states(id: &str) -> Vec<String> {
    let shown = check(Command::new("scontrol").args(["show", "job", "--oneliner", id]));
    let state = |line: &str| line.split_whitespace().find_map(|f| f.strip_prefix("JobState=")).map(str::to_string);
    shown.lines().filter_map(state).collect()
}

/// Waits until the merge job has ended and returns its state, failing after `TIMEOUT`.
fn wait_for(jobs: &Jobs, logs: &Path) -> String {
    let start = Instant::now();
    loop {
        let states = job_states(&jobs.merge);
        let state = states.first().cloned().unwrap_or_default();
        let running = ["PENDING", "CONFIGURING", "RUNNING", "COMPLETING", "SUSPENDED", "REQUEUED"];
        if !running.contains(&state.as_str()) {
            return state;
        }
        assert!(start.elapsed() < TIMEOUT, "jobs still {state} after {TIMEOUT:?}; logs in {}", logs.display());
        std::thread::sleep(Duration::from_millis(500));
    }
}

/// Everything the job logs in `logs` say, for a failure message.
fn logs_of(logs: &Path) -> String {
    let mut entries: Vec<PathBuf> = std::fs::read_dir(logs).unwrap().map(|e| e.unwrap().path()).collect();
    entries.sort();
    entries.iter().map(|p| format!("--- {}\n{}", p.display(), std::fs::read_to_string(p).unwrap_or_default())).collect()
}

/// The linear pixels of an image file.
fn pixels(path: &Path) -> Vec<f32> {
    image::open(path).unwrap_or_else(|e| panic!("{}: {e}", path.display())).to_rgb32f().into_raw()
}

#[test]
#[ignore = "needs a Slurm cluster: run cluster/slurm/local-cluster.sh"]
fn a_still_rendered_in_parts_by_a_job_array_and_merged_equals_one_render() {
    let dir = temp_dir("still");
    let scene = orbit_scene(&dir);
    let scene_arg = scene.to_str().unwrap();
    let (merged, single) = (dir.join("merged.png"), dir.join("single"));
    let jobs = submit(&[scene_arg, "--parts", "3", "-o", merged.to_str().unwrap(), "--", "--seed", "9"], None);
    let work = dir.join("merged.png.parts");
    let logs = work.join("logs");
    let state = wait_for(&jobs, &logs);
    assert_eq!(state, "COMPLETED", "the merge job ended {state}:\n{}", logs_of(&logs));
    assert_eq!(job_states(&jobs.render), ["COMPLETED"; 3], "{}", logs_of(&logs));

    let render = |ext: &str| {
        let out = single.with_extension(ext);
        check(nullpath().args(["render", scene_arg, "-o", out.to_str().unwrap(), "--seed", "9", "--quiet"]));
        out
    };
    let rgb8 = |path: &Path| image::open(path).unwrap().to_rgb8().into_raw();
    assert_eq!(rgb8(&merged), rgb8(&render("png")), "the merged PNG differs from one render's");
    // The parts the array wrote hold the exact sums: merged to linear EXR, they equal one render's EXR.
    let parts: Vec<PathBuf> = (1..=3).map(|i| work.join(format!("part_{i}.exr"))).collect();
    let exr = dir.join("merged.exr");
    check(nullpath().arg("merge").args(&parts).args(["-o", exr.to_str().unwrap()]));
    assert_eq!(pixels(&exr), pixels(&render("exr")), "the merged EXR differs from one render's");
    drop(jobs);
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
#[ignore = "needs a Slurm cluster: run cluster/slurm/local-cluster.sh"]
fn animation_frames_rendered_by_a_job_array_equal_a_local_animation() {
    let dir = temp_dir("frames");
    let scene = orbit_scene(&dir);
    let (frames, local) = (dir.join("frames"), dir.join("local"));
    let options = ["--format", "exr", "--seed", "5"];
    let mut args =
        vec![scene.to_str().unwrap(), "--parts", "3", "--frames", "0..6", "-o", frames.to_str().unwrap(), "--"];
    args.extend(options);
    let jobs = submit(&args, None);
    let logs = frames.join("logs");
    let state = wait_for(&jobs, &logs);
    assert_eq!(state, "COMPLETED", "the assemble job ended {state}:\n{}", logs_of(&logs));
    // The array ran as three tasks, each a slice of two frames, and all succeeded.
    assert_eq!(job_states(&jobs.render), ["COMPLETED"; 3], "{}", logs_of(&logs));

    check(
        nullpath().args(["animate", scene.to_str().unwrap(), "-o", local.to_str().unwrap(), "--quiet"]).args(options),
    );
    for n in 0..6 {
        let name = format!("frame_{n:05}.exr");
        assert_eq!(
            pixels(&frames.join(&name)),
            pixels(&local.join(&name)),
            "{name} from Slurm differs from the local one"
        );
    }
    let first = pixels(&local.join("frame_00000.exr"));
    assert_ne!(first, pixels(&local.join("frame_00003.exr")), "the orbiting camera's frames differ");
    drop(jobs);
    std::fs::remove_dir_all(&dir).unwrap();
}

#[cfg(unix)]
#[test]
#[ignore = "needs a Slurm cluster: run cluster/slurm/local-cluster.sh"]
fn the_video_is_assembled_after_the_frames_by_ffmpeg() {
    use std::os::unix::fs::PermissionsExt;
    let dir = temp_dir("video");
    let scene = orbit_scene(&dir);
    // A stand-in ffmpeg records how it is called and writes its last argument, the video, as
    // ffmpeg does (the real one is covered by tests/cli_animate.rs).
    let (bin, called) = (dir.join("bin"), dir.join("ffmpeg-args.txt"));
    std::fs::create_dir_all(&bin).unwrap();
    let fake = bin.join("ffmpeg");
    let script =
        format!("#!/bin/sh\necho \"$@\" > '{}'\nfor last; do :; done\necho video > \"$last\"\n", called.display());
    std::fs::write(&fake, script).unwrap();
    std::fs::set_permissions(&fake, std::fs::Permissions::from_mode(0o755)).unwrap();
    let (frames, video) = (dir.join("frames"), dir.join("orbit.mp4"));
    let (frames_arg, video_arg) = (frames.to_str().unwrap(), video.to_str().unwrap());
    let args = [scene.to_str().unwrap(), "--parts", "2", "--frames", "1..=4", "-o", frames_arg, "--video", video_arg];
    let jobs = submit(&args, Some(&bin));
    let logs = frames.join("logs");
    let state = wait_for(&jobs, &logs);
    assert_eq!(state, "COMPLETED", "the assemble job ended {state}:\n{}", logs_of(&logs));
    assert_eq!(job_states(&jobs.render), ["COMPLETED"; 2], "{}", logs_of(&logs));
    assert!((1..=4).all(|n| frames.join(format!("frame_{n:05}.png")).exists()), "{}", logs_of(&logs));
    let called =
        std::fs::read_to_string(&called).unwrap_or_else(|e| panic!("ffmpeg was not called ({e}):\n{}", logs_of(&logs)));
    for expected in ["-framerate 1", "-start_number 1", "frame_%05d.png", "-frames:v 4", "orbit.mp4"] {
        assert!(called.contains(expected), "{called:?} lacks {expected:?}");
    }
    // Encoded under a temporary name beside the video, then renamed into place.
    assert_eq!(std::fs::read_to_string(&video).unwrap(), "video\n", "{}", logs_of(&logs));
    drop(jobs);
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
#[ignore = "needs a Slurm cluster: run cluster/slurm/local-cluster.sh"]
fn a_failed_task_cancels_the_job_after_it_instead_of_leaving_it_pending() {
    let dir = temp_dir("failed");
    let scene = orbit_scene(&dir);
    let frames = dir.join("frames");
    let args = [
        scene.to_str().unwrap(),
        "--parts",
        "2",
        "--frames",
        "0..2",
        "-o",
        frames.to_str().unwrap(),
        "--",
        "--spp",
        "0",
    ];
    let jobs = submit(&args, None);
    let logs = frames.join("logs");
    let state = wait_for(&jobs, &logs);
    assert_eq!(state, "CANCELLED", "the assemble job after failed tasks ended {state}:\n{}", logs_of(&logs));
    assert_eq!(job_states(&jobs.render), ["FAILED"; 2], "{}", logs_of(&logs));
    assert!(logs_of(&logs).contains("--spp must be at least 1"), "{}", logs_of(&logs));
    drop(jobs);
    std::fs::remove_dir_all(&dir).unwrap();
}

//! `nullpath animate`: render a scene's animation frame by frame into a directory, resuming where
//! an earlier run stopped, and assemble the frames into a video with ffmpeg on request.
//!
//! Frame `n` is exactly the still `nullpath render --time n/fps` (same seed, same pixels), so a
//! frame can be re-rendered or checked on its own.

use super::files::{same_file, Files};
use super::interrupt::{Interrupts, StopReason};
use super::provenance;
use super::render::{summary, RenderOptions};
use super::Failure;
use clap::{Parser, ValueEnum};
use render::film::write_image;
use render::renderer::{Goal, Part};
use std::ops::Range;
use std::path::{Path, PathBuf};
use std::process::Command;

#[derive(Parser, Debug)]
pub struct Args {
    /// Scene file (TOML) with camera keyframes or an orbit.
    scene: PathBuf,
    /// Directory for the frames (created if missing): frame_00000.png, frame_00001.png, …
    #[arg(short, long)]
    output: PathBuf,
    /// Frames to render: `A..B` (A to B, B excluded), `A..=B` (B included) or one frame `N`.
    /// Default: all the scene's frames.
    #[arg(long, value_parser = parse_frames)]
    frames: Option<Range<u32>>,
    /// Frames per second of animation (default: the scene's `[animation] fps`).
    #[arg(long)]
    fps: Option<f64>,
    /// Image format of the frames.
    #[arg(long, value_enum, default_value_t = FrameFormat::Png)]
    format: FrameFormat,
    #[command(flatten)]
    options: RenderOptions,
    /// Also assemble the frames into this video (H.264 MP4) with ffmpeg, which must be installed.
    #[arg(long)]
    video: Option<PathBuf>,
}

#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
enum FrameFormat {
    /// 8-bit sRGB, tone mapped as the scene says.
    Png,
    /// Linear floating point, for compositing.
    Exr,
}

impl FrameFormat {
    fn extension(self) -> &'static str {
        match self {
            FrameFormat::Png => "png",
            FrameFormat::Exr => "exr",
        }
    }
}

/// `A..B`, `A..=B` or `N`, as a half-open range.
fn parse_frames(text: &str) -> Result<Range<u32>, String> {
    let number = |s: &str| s.trim().parse::<u32>().map_err(|_| format!("\"{s}\" is not a frame number"));
    let range = if let Some((a, b)) = text.split_once("..=") {
        number(a)?..number(b)?.checked_add(1).ok_or("frame number too large")?
    } else if let Some((a, b)) = text.split_once("..") {
        number(a)?..number(b)?
    } else {
        let n = number(text)?;
        n..n.checked_add(1).ok_or("frame number too large")?
    };
    if range.is_empty() {
        return Err(format!("\"{text}\" holds no frames (write A..B with A < B, or A..=B)"));
    }
    Ok(range)
}

/// The path of frame `n` in `dir`.
fn frame_path(dir: &Path, n: u32, format: FrameFormat) -> PathBuf {
    dir.join(format!("frame_{n:05}.{}", format.extension()))
}

/// The number of the frame (finished or partial) that `path` would be, were it in the frame
/// directory `dir`.
fn frame_number(path: &Path, dir: &Path, format: FrameFormat) -> Option<u32> {
    let in_dir = path.parent().is_some_and(|parent| {
        let parent = if parent.as_os_str().is_empty() { Path::new(".") } else { parent };
        same_file(parent, dir)
    });
    let name = path.file_name()?.to_str()?.strip_prefix("frame_")?;
    let extension = format!(".{}", format.extension());
    let digits = name.strip_suffix(&extension).map(|n| n.strip_suffix(".partial").unwrap_or(n))?;
    let n: u32 = digits.parse().ok()?;
    (in_dir && format!("{n:05}") == digits).then_some(n)
}

/// Refuses, before any frame is rendered, a frame or video that would be written over the scene
/// file, or a video that would be written over a frame.
fn check_files(args: &Args, frames: &Range<u32>) -> Result<(), String> {
    let mut files = Files::default();
    files.reads("the scene file", &args.scene);
    if let Some(video) = &args.video {
        files.writes("--video", video)?;
    }
    for path in [Some(&args.scene), args.video.as_ref()].into_iter().flatten() {
        if let Some(n) = frame_number(path, &args.output, args.format).filter(|n| frames.contains(n)) {
            files.writes(format!("frame {n}"), path)?;
        }
    }
    Ok(())
}

/// Whether a complete frame of the wanted size is already on disk. Frames are written whole
/// (to a temporary file, then renamed), so a readable file of the right size is complete.
fn is_complete(path: &Path, width: u32, height: u32) -> bool {
    image::image_dimensions(path).is_ok_and(|size| size == (width, height))
}

pub fn run(args: &Args) -> Result<(), Failure> {
    let mut scene = args.options.load(Some(&args.scene))?;
    let Some(mut animation) = scene.animation.clone() else {
        return Err(format!("{}: the scene has no camera to animate", args.scene.display()).into());
    };
    if let Some(fps) = args.fps {
        if !(fps > 0.0 && fps <= 1000.0) {
            return Err(format!("--fps must be in (0, 1000], got {fps}").into());
        }
        animation.fps = fps;
    }
    if args.video.is_some() && args.format != FrameFormat::Png {
        return Err(String::from("--video assembles PNG frames; use --format png").into());
    }
    let frames = args.frames.clone().unwrap_or(0..animation.frame_count());
    check_files(args, &frames)?;
    std::fs::create_dir_all(&args.output)
        .map_err(|e| format!("{}: cannot create the frame directory: {e}", args.output.display()))?;
    let pool = args.options.thread_pool()?;
    let interrupts = Interrupts::install()?;
    let (width, height) = (scene.settings.width, scene.settings.height);
    let mut rendered = 0;
    for n in frames.clone() {
        let path = frame_path(&args.output, n, args.format);
        if is_complete(&path, width, height) {
            continue;
        }
        if let Some(reason) = interrupts.reason() {
            return Err(stopped_in_frame(reason, n, rendered, None));
        }
        let time = animation.time(n);
        scene.set_time(time)?;
        let (film, stats) = args.options.render(&scene, &pool, &interrupts.cancel);
        let source = args.options.source(Some(&args.scene), time);
        let metadata = provenance::metadata(&scene, &source, Goal::spp(scene.settings.spp), Part::WHOLE, &stats);
        // A frame finished as the signal came is kept as finished.
        if let Some(reason) = interrupts.reason().filter(|_| !stats.is_complete()) {
            // Keep what was computed, under a name a later run does not take for a finished frame.
            let partial = path.with_extension(format!("partial.{}", args.format.extension()));
            write_image(&film, &partial, &scene.settings.tonemap, &metadata).map_err(|e| e.to_string())?;
            return Err(stopped_in_frame(reason, n, rendered, Some(&partial)));
        }
        write_image(&film, &path, &scene.settings.tonemap, &metadata).map_err(|e| e.to_string())?;
        rendered += 1;
        if !args.options.quiet {
            eprintln!("frame {n} (t = {time:.4} s): {}", summary(&stats, &scene));
        }
    }
    if !args.options.quiet {
        let skipped = frames.len() as u32 - rendered;
        eprintln!(
            "frames {}..{} in {}: rendered {rendered}, {skipped} already complete",
            frames.start,
            frames.end,
            args.output.display()
        );
    }
    match &args.video {
        Some(video) => Ok(assemble_video(&args.output, frames, animation.fps, video)?),
        None => Ok(()),
    }
}

/// The report of an animation stopped by `reason` in frame `n`, after `rendered` new frames, with
/// the `partial` frame written from what it had.
fn stopped_in_frame(reason: StopReason, n: u32, rendered: u32, partial: Option<&Path>) -> Failure {
    let kept = partial.map(|p| format!("; what it had is in {}", p.display())).unwrap_or_default();
    Failure::stopped(
        format!(
            "{reason} in frame {n}, after {rendered} new frames{kept}. \
             Run the same command again to render the missing frames."
        ),
        reason.exit_code(),
    )
}

/// Encodes the PNG frames `frames` of `dir` as an H.264 MP4 at `fps` frames per second into
/// `video`, atomically: ffmpeg writes a temporary sibling, renamed into place once it is whole.
fn assemble_video(dir: &Path, frames: Range<u32>, fps: f64, video: &Path) -> Result<(), String> {
    // Hidden and of this process, with the video's extension, from which ffmpeg picks the container.
    let extension = video.extension().map(|e| format!(".{}", e.to_string_lossy())).unwrap_or_default();
    let name = video.file_name().map(|n| n.to_string_lossy()).unwrap_or_default();
    let temporary = video.with_file_name(format!(".{name}.partial-{}{extension}", std::process::id()));
    let made = encode_video(dir, frames, fps, &temporary).and_then(|()| {
        std::fs::rename(&temporary, video).map_err(|e| format!("{}: cannot write the video: {e}", video.display()))
    });
    if made.is_err() {
        // Best effort: ffmpeg may have made nothing, and its error is what matters.
        let _ = std::fs::remove_file(&temporary);
    }
    made
}

/// Runs ffmpeg to encode the PNG frames `frames` of `dir` into `video`.
fn encode_video(dir: &Path, frames: Range<u32>, fps: f64, video: &Path) -> Result<(), String> {
    let pattern = dir.join("frame_%05d.png");
    let output = Command::new("ffmpeg")
        .args(["-y", "-loglevel", "error", "-framerate", &fps.to_string()])
        .args(["-start_number", &frames.start.to_string(), "-i"])
        .arg(&pattern)
        .args(["-frames:v", &frames.len().to_string()])
        // H.264 in yuv420p (what players accept) needs even sizes: pad by one pixel if odd.
        .args(["-vf", "pad=ceil(iw/2)*2:ceil(ih/2)*2", "-c:v", "libx264", "-pix_fmt", "yuv420p"])
        .arg(video)
        .output();
    match output {
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => Err(format!(
            "ffmpeg is not installed (or not on PATH), so no video was made; the frames are in {}. \
             Install ffmpeg (e.g. `apt install ffmpeg`) and run the same command again: finished frames are kept.",
            dir.display()
        )),
        Err(e) => Err(format!("cannot run ffmpeg: {e}")),
        Ok(out) if !out.status.success() => {
            Err(format!("ffmpeg failed ({}): {}", out.status, String::from_utf8_lossy(&out.stderr).trim()))
        }
        Ok(_) => Ok(()),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn frame_ranges() {
        assert_eq!(parse_frames("3..7"), Ok(3..7));
        assert_eq!(parse_frames("3..=7"), Ok(3..8));
        assert_eq!(parse_frames("12"), Ok(12..13));
        assert!(parse_frames("7..3").is_err());
        assert!(parse_frames("a..3").is_err());
        assert!(parse_frames("-1").is_err());
    }
}

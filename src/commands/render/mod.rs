//! `nullpath render`: render a scene file (or the default scene) to PNG, EXR or HDR,
//! progressively, with checkpoints, resumption, noise targets and parts of an image.

use super::files::{same_file, Files};
use super::interrupt::{Interrupts, StopReason};
use super::provenance::{self, Source};
use super::Failure;
use clap::Parser;
use progress::Progress;
use render::film::{
    check_output_path, check_writable, write_file_atomically, write_image_with_data, DataLayer, Film, ImageFormat,
    Metadata,
};
use render::integrator::PathStats;
use render::renderer::{
    progressive, render, Checkpointed, Goal, NoiseTarget, Part, Progressive, RenderStats, Resume, Unit,
};
use render::scene::Scene;
use render::settings::IntegratorKind;
use std::io::IsTerminal;
use std::path::{Path, PathBuf};
use std::sync::atomic::AtomicBool;
use std::sync::{Condvar, Mutex};
use std::time::{Duration, Instant};

mod data_only;
mod progress;

/// The scene rendered when none is named.
pub const DEFAULT_SCENE: &str = include_str!("../../../scenes/room-black-hole.toml");
pub const DEFAULT_SCENE_NAME: &str = "<default scene: scenes/room-black-hole.toml>";

/// Largest image side, in pixels.
const MAX_SIDE: u32 = 16384;
/// Most samples per pixel one command asks for.
const MAX_SPP: u32 = 1 << 20;
/// Most worker threads.
const MAX_THREADS: usize = 1024;
/// Memory a checkpoint needs, beyond the film, per pixel: the copy of the film it is written
/// from, and its encoding's `u32` and `f32` channels (see `render::film::write_checkpoint`).
const CHECKPOINT_BYTES_PER_PIXEL: u64 = Film::BYTES_PER_PIXEL + 4 * (3 + 2 * 6 + 3);

#[derive(Parser, Debug)]
#[command(after_help = "Flags override the scene file's values. Scenes: see docs/scene-format.md.\n\
    An interrupted render (Ctrl-C, SIGTERM, SIGHUP, --time-limit) keeps its work in a checkpoint \
    and leaves the output untouched; a second Ctrl-C quits at once, without the checkpoint \
    (a repeated SIGTERM or SIGHUP does not). No file written may be one read or another written.")]
pub struct Args {
    /// Scene file (TOML); the default scene (scenes/room-black-hole.toml, built in) when omitted.
    scene: Option<PathBuf>,
    /// Output image: .png (8-bit sRGB, tone mapped), .exr (linear float) or .hdr. With --part,
    /// the part file (.exr) that `nullpath merge` puts together.
    #[arg(short, long, default_value = "render.png")]
    output: PathBuf,
    /// Animation time (seconds) to render the camera at; frame N of `nullpath animate` is
    /// time N / fps.
    #[arg(long, default_value_t = 0.0, allow_negative_numbers = true)]
    time: f64,
    #[command(flatten)]
    options: RenderOptions,
    /// Write statistics (rays, samples, seconds, NaN samples, ray fates, spp reached, estimated
    /// error) as JSON here.
    #[arg(long, value_name = "PATH")]
    stats: Option<PathBuf>,
    /// Keep the render's state in this checkpoint (.exr): written every --checkpoint-every, when
    /// interrupted, and at the end (to continue later to more samples). Without it, an
    /// interrupted render writes OUTPUT's name with .checkpoint.exr. It may be the --resume
    /// checkpoint, which is then brought up to date in place.
    #[arg(long, value_name = "PATH")]
    checkpoint: Option<PathBuf>,
    /// How often to write the checkpoint, e.g. 10s, 5m, 1h (default 5m with --checkpoint).
    #[arg(long, value_name = "DURATION", value_parser = parse_duration)]
    checkpoint_every: Option<Duration>,
    /// Continue the render saved in this checkpoint (to --spp samples, or the scene's). The
    /// scene, view, time and settings must be those it was made with.
    #[arg(long, value_name = "PATH")]
    resume: Option<PathBuf>,
    /// Stop after this long (e.g. 90s, 30m, 2h, 1h30m), keeping the work in the checkpoint to
    /// continue with --resume; exits with status 75.
    #[arg(long, value_name = "DURATION", value_parser = parse_duration)]
    time_limit: Option<Duration>,
    /// Stop when the estimated relative error of the image (per pixel, from the variance of
    /// its samples) is at most this, e.g. 0.02; --spp (default 65536) is then the most a pixel
    /// takes. Renders in passes that double the samples; the progress bar shows the pass in
    /// progress. Path tracing only.
    #[arg(long, value_name = "ERROR")]
    noise_target: Option<f64>,
    /// With --noise-target: send samples only to the pixels that still need them.
    #[arg(long, requires = "noise_target")]
    adaptive: bool,
    /// Render part I of N of the image (by tiles, I from 1 to N) into the part file OUTPUT
    /// (.exr); `nullpath merge` puts the parts together, bit-identical to one render.
    #[arg(long, value_name = "I/N", value_parser = Part::parse)]
    part: Option<Part>,
    /// Write only the data channels (the scene's `[render] channels` and `spectrum`) into OUTPUT
    /// (.exr), without the image: one ray through each pixel's centre, the same values a full
    /// render writes beside its colour, at the cost of one ray a pixel.
    #[arg(long, conflicts_with_all = ["part", "resume", "checkpoint", "checkpoint_every", "time_limit", "noise_target"])]
    data_only: bool,
}

/// `90s`, `30m`, `2h`, `1h30m` or plain seconds.
fn parse_duration(text: &str) -> Result<Duration, String> {
    let duration = match text.trim().parse::<f64>() {
        Ok(seconds) if seconds.is_finite() && seconds >= 0.0 => Duration::from_secs_f64(seconds),
        Ok(_) => return Err(format!("\"{text}\" is not a duration")),
        Err(_) => humantime::parse_duration(text)
            .map_err(|e| format!("\"{text}\" is not a duration ({e}): write e.g. 90s, 30m, 2h"))?,
    };
    if duration.is_zero() {
        return Err("a duration must be longer than zero".into());
    }
    Ok(duration)
}

/// Options shared by the commands that render: view, image size, sampling, threads, memory,
/// reporting. Each overrides the scene file's value.
#[derive(clap::Args, Debug)]
pub struct RenderOptions {
    /// Render from the scene's view NAME (its `[views.NAME]` camera) instead of its `[camera]`.
    #[arg(long, value_name = "NAME")]
    view: Option<String>,
    /// Image width in pixels (1 to 16384; default: the scene's `[render] width`).
    #[arg(long)]
    width: Option<u32>,
    /// Image height in pixels (1 to 16384; default: the scene's `[render] height`).
    #[arg(long)]
    height: Option<u32>,
    /// Samples per pixel (photon-mapping iterations; default: the scene's `[render] spp`).
    #[arg(long)]
    spp: Option<u32>,
    /// Seed of the random numbers (default: the scene's `[render] seed`, else 0).
    #[arg(long)]
    seed: Option<u64>,
    /// Worker threads, 1 to 1024 (default: all cores). The image does not depend on it.
    #[arg(long)]
    threads: Option<usize>,
    /// Most memory the render may use, e.g. 8G or 512M (default: the memory available now).
    /// Checked before rendering, from the image size.
    #[arg(long, value_name = "BYTES", value_parser = parse_bytes)]
    max_memory: Option<u64>,
    /// Render spectrally, as the scene's `[render] spectral = true`: paths carry sampled
    /// wavelengths, so frequency shifts change every light's colour and dispersing glass splits
    /// it. Path tracing only.
    #[arg(long)]
    spectral: bool,
    /// Let the scene read files (meshes, images, glTF files and theirs) inside DIR too, not only
    /// inside its own folder; repeatable. See "Files a scene reads" in docs/scene-format.md.
    #[arg(long, value_name = "DIR")]
    allow_read: Vec<PathBuf>,
    /// No progress bar or summary.
    #[arg(long)]
    pub quiet: bool,
    /// Report progress as lines `progress DONE TOTAL` on standard error instead of a bar, for
    /// programs that run nullpath (the Blender add-on).
    #[arg(long)]
    progress_lines: bool,
}

/// `bytes` in GiB, or MiB below one GiB.
fn human_bytes(bytes: u64) -> String {
    let mib = bytes as f64 / f64::from(1u32 << 20);
    if mib < 1024.0 {
        format!("{mib:.1} MiB")
    } else {
        format!("{:.1} GiB", mib / 1024.0)
    }
}

/// `8G`, `512M`, `100k` or plain bytes (binary multiples).
fn parse_bytes(text: &str) -> Result<u64, String> {
    let t = text.trim();
    let (number, unit) = t.split_at(t.find(|c: char| c.is_ascii_alphabetic()).unwrap_or(t.len()));
    let scale: u64 = match unit.to_ascii_lowercase().trim_end_matches("ib").trim_end_matches('b') {
        "" => 1,
        "k" => 1 << 10,
        "m" => 1 << 20,
        "g" => 1 << 30,
        "t" => 1 << 40,
        _ => return Err(format!("\"{text}\" is not a size: write e.g. 8G or 512M")),
    };
    let value: f64 = number.trim().parse().map_err(|_| format!("\"{text}\" is not a size: write e.g. 8G or 512M"))?;
    if !(value.is_finite() && value > 0.0) {
        return Err(format!("\"{text}\" is not a size: write e.g. 8G or 512M"));
    }
    Ok((value * scale as f64) as u64)
}

/// Loads the named scene or the default one, from its `[camera]` or the view `view`.
pub fn load_scene(path: Option<&Path>, view: Option<&str>) -> Result<Scene, String> {
    match path {
        Some(p) => scene::load_view(p, view).map_err(|e| e.to_string()),
        None => scene::parse_view(DEFAULT_SCENE, DEFAULT_SCENE_NAME, Path::new("."), view).map_err(|e| e.to_string()),
    }
}

impl RenderOptions {
    /// The scene at `path` (or the default scene) from the chosen view, with the overrides.
    pub fn load(&self, path: Option<&Path>) -> Result<Scene, String> {
        let mut scene = match path {
            Some(p) => scene::load_allowing(p, self.view.as_deref(), &self.allow_read).map_err(|e| e.to_string())?,
            None => load_scene(None, self.view.as_deref())?,
        };
        self.apply(&mut scene)?;
        Ok(scene)
    }

    /// Where the scene came from, at animation time `time`.
    pub(super) fn source(&self, path: Option<&Path>, time: f64) -> Source {
        let (name, text) = match path {
            Some(p) => (p.display().to_string(), std::fs::read_to_string(p).unwrap_or_default()),
            None => (DEFAULT_SCENE_NAME.to_owned(), DEFAULT_SCENE.to_owned()),
        };
        Source { name, text, view: self.view.clone(), time }
    }

    /// Applies the command-line overrides to the scene's settings.
    fn apply(&self, scene: &mut Scene) -> Result<(), String> {
        let s = &mut scene.settings;
        let positive = |name: &str, v: Option<u32>, max: u32| match v {
            Some(0) => Err(format!("--{name} must be at least 1")),
            Some(v) if v > max => Err(format!("--{name} {v} is larger than {max}")),
            other => Ok(other),
        };
        if let Some(w) = positive("width", self.width, MAX_SIDE)? {
            s.width = w;
        }
        if let Some(h) = positive("height", self.height, MAX_SIDE)? {
            s.height = h;
        }
        if let Some(n) = positive("spp", self.spp, MAX_SPP)? {
            s.spp = n;
        }
        if let Some(seed) = self.seed {
            s.seed = seed;
        }
        if self.spectral {
            if s.integrator == IntegratorKind::Photon {
                return Err("--spectral needs a path tracer: photon mapping carries RGB power".to_owned());
            }
            s.spectral = true;
        }
        Ok(())
    }

    pub fn thread_pool(&self) -> Result<rayon::ThreadPool, String> {
        if let Some(n) = self.threads.filter(|n| !(1..=MAX_THREADS).contains(n)) {
            return Err(format!("--threads must be between 1 and {MAX_THREADS}, got {n}"));
        }
        rayon::ThreadPoolBuilder::new()
            .num_threads(self.threads.unwrap_or(0))
            .build()
            .map_err(|e| format!("--threads: {e}"))
    }

    /// Refuses a render whose data channels and, `with_film`, film and checkpoint encoding would
    /// not fit in `--max-memory`, or in the memory available now.
    pub fn check_memory(&self, scene: &Scene, with_film: bool) -> Result<(), String> {
        let settings = &scene.settings;
        let pixels = u64::from(settings.width) * u64::from(settings.height);
        let wavelengths = settings.spectrum.map_or(0, |s| s.wavelengths().len());
        let data = if settings.has_data_channels() {
            DataLayer::bytes_per_pixel(settings.channels.len(), wavelengths)
        } else {
            0
        };
        let film = Film::BYTES_PER_PIXEL + 4 + 3 + CHECKPOINT_BYTES_PER_PIXEL;
        let per_pixel = data + if with_film { film } else { 0 };
        let needed = pixels * per_pixel;
        let (limit, what) = match self.max_memory {
            Some(limit) => (limit, "--max-memory"),
            None => match available_memory() {
                Some(available) => (available, "the memory available"),
                None => return Ok(()),
            },
        };
        if needed > limit {
            return Err(format!(
                "a {}x{} render needs about {} ({per_pixel} bytes a pixel), more than {what} ({}): \
                 render a smaller image, or raise --max-memory if more memory will be free",
                settings.width,
                settings.height,
                human_bytes(needed),
                human_bytes(limit)
            ));
        }
        Ok(())
    }

    /// The progress display: a bar on a terminal, or lines, unless quiet.
    fn progress(&self) -> Progress {
        Progress::new(self.quiet, self.progress_lines, std::io::stderr().is_terminal())
    }

    /// Renders `scene` on `pool` showing its progress; setting `cancel` stops it within a sample.
    pub fn render(&self, scene: &Scene, pool: &rayon::ThreadPool, cancel: &AtomicBool) -> (Film, RenderStats) {
        let progress = self.progress();
        let result = pool.install(|| render(scene, cancel, &|done, total| progress.show(done, total)));
        progress.finish();
        result
    }
}

/// `MemAvailable` of `/proc/meminfo`, where there is one.
fn available_memory() -> Option<u64> {
    let info = std::fs::read_to_string("/proc/meminfo").ok()?;
    let line = info.lines().find(|l| l.starts_with("MemAvailable:"))?;
    let kib: u64 = line.split_whitespace().nth(1)?.parse().ok()?;
    Some(kib * 1024)
}

/// One line on a finished render: size, samples, time, ray fates.
pub fn summary(stats: &RenderStats, scene: &Scene) -> String {
    let f = &stats.paths.fates;
    let spp = if stats.spp_min == stats.spp_max {
        format!("{} spp", stats.spp_max)
    } else {
        format!("{}–{} spp", stats.spp_min, stats.spp_max)
    };
    let error = stats.relative_error.map_or(String::new(), |e| format!(", estimated relative error {e:.4}"));
    format!(
        "{}×{} at {spp} in {:.2} s ({:.0} samples/s{error}); rays escaped {}, captured {}, absorbed {}, traversed {}, failed {}; NaN samples {}",
        scene.settings.width,
        scene.settings.height,
        stats.seconds,
        stats.samples as f64 / stats.seconds.max(1e-9),
        f.escaped,
        f.captured,
        f.absorbed,
        f.traversed,
        f.failed,
        stats.nan_samples,
    )
}

/// `path` with its extension replaced by `.checkpoint.exr`: where an interrupted render without
/// `--checkpoint` keeps its work.
fn default_checkpoint(output: &Path) -> PathBuf {
    output.with_extension("checkpoint.exr")
}

/// Checks that `path` can be written as `what`, before anything is rendered.
fn check_path(path: &Path, what: &str, exr_only: bool) -> Result<(), String> {
    let format = check_output_path(path).map_err(|e| format!("{what}: {e}"))?;
    if exr_only && format != ImageFormat::Exr {
        return Err(format!("{what} '{}' must be an .exr file", path.display()));
    }
    check_writable(path).map_err(|e| format!("{what}: {e}"))
}

/// Checks that the statistics can be written to `path`, which they replace whole (see
/// [`write_json`]): a file can be made in its directory and `path` is not a directory.
fn check_stats_path(path: &Path) -> Result<(), String> {
    let refuse = |why: String| format!("--stats '{}': cannot write: {why}", path.display());
    if path.is_dir() {
        return Err(refuse("it is a directory".into()));
    }
    check_writable(path)
        .map_err(|e| refuse(std::error::Error::source(&e).map_or_else(|| e.to_string(), ToString::to_string)))
}

fn write_stats(path: &Path, stats: &RenderStats, scene: &Scene) -> Result<(), String> {
    write_json(path, &stats.to_json(&scene.settings))
}

/// Writes the statistics `value` to `path` as pretty JSON, atomically: a reader (or a process
/// killed mid-write) sees the previous file or the new one, never half of one.
fn write_json(path: &Path, value: &serde_json::Value) -> Result<(), String> {
    let text = serde_json::to_string_pretty(value).map_err(|e| e.to_string())? + "\n";
    write_file_atomically(path, text.as_bytes())
        .map_err(|e| format!("{}: cannot write statistics: {e}", path.display()))
}

/// Refuses, before anything is rendered, a command whose files collide: a file it writes (the
/// image, the checkpoint, the statistics) that is a file it reads (the scene, the `--resume`
/// checkpoint) or another it writes. The one file written in place of what is read is the
/// checkpoint continued (`--resume` with its own `--checkpoint`, or its default name), and a
/// part file continued into itself: each is read whole before it is replaced, with its samples
/// and more.
fn check_files(args: &Args) -> Result<(), String> {
    let mut files = Files::default();
    if let Some(scene) = &args.scene {
        files.reads("the scene file", scene);
    }
    let checkpoint = args.checkpoint_path();
    if let Some(resume) = &args.resume {
        let updated = same_file(resume, &checkpoint) || (args.part.is_some() && same_file(resume, &args.output));
        if !updated {
            files.reads("--resume", resume);
        }
    }
    let output = match (args.part, args.data_only) {
        (Some(_), _) => "the part file (-o)",
        (None, true) => "the data image (-o)",
        (None, false) => "the image (-o)",
    };
    files.writes(output, &args.output)?;
    if !args.data_only {
        let role =
            if args.checkpoint.is_some() { "--checkpoint" } else { "the checkpoint (-o's name, .checkpoint.exr)" };
        files.writes(role, &checkpoint)?;
    }
    match &args.stats {
        Some(stats) => files.writes("--stats", stats),
        None => Ok(()),
    }
}

impl Args {
    /// The render's goal, validated.
    fn goal(&self, scene: &Scene) -> Result<Goal, String> {
        let Some(error) = self.noise_target else { return Ok(Goal::spp(scene.settings.spp)) };
        if !(error > 0.0 && error < 1.0) {
            return Err(format!("--noise-target must be a relative error between 0 and 1 (e.g. 0.02), got {error}"));
        }
        let spp = self.options.spp.unwrap_or(1 << 16);
        Ok(Goal { spp, noise: Some(NoiseTarget { relative_error: error, adaptive: self.adaptive }) })
    }

    fn checkpoint_path(&self) -> PathBuf {
        self.checkpoint.clone().unwrap_or_else(|| default_checkpoint(&self.output))
    }
}

pub fn run(args: &Args) -> Result<(), Failure> {
    let mut scene = args.options.load(args.scene.as_deref())?;
    if !args.time.is_finite() {
        return Err(format!("--time must be a finite number of seconds, got {}", args.time).into());
    }
    scene.set_time(args.time)?;
    check_files(args)?;
    let source = args.options.source(args.scene.as_deref(), args.time);
    if args.data_only {
        return Ok(data_only::run(args, &scene, &source)?);
    }
    let part = args.part.unwrap_or(Part::WHOLE);
    let goal = args.goal(&scene)?;
    if scene.settings.integrator == IntegratorKind::Photon {
        refuse_for_photon_mapping(args)?;
    }
    if part != Part::WHOLE && goal.noise.is_some() {
        return Err("--noise-target decides from the whole image, so it cannot be used with --part".to_owned().into());
    }
    check_path(&args.output, "output", args.part.is_some())?;
    check_channels(args, &scene)?;
    check_path(&args.checkpoint_path(), "--checkpoint", true)?;
    if let Some(path) = &args.stats {
        check_stats_path(path)?;
    }
    let pool = args.options.thread_pool()?;
    args.options.check_memory(&scene, true)?;
    let interrupts = Interrupts::install()?;
    let command = Command { args, scene: &scene, source: &source, goal, part, pool: &pool, interrupts: &interrupts };
    let resume = args.resume.as_deref().map(|path| command.resume(path)).transpose()?;
    let renderer = progressive(&scene, part, goal, resume).map_err(|e| e.to_string())?;
    command.drive(renderer.as_ref())
}

/// Data channels (`[render] channels`) go into the one EXR image of a whole render.
fn check_channels(args: &Args, scene: &Scene) -> Result<(), String> {
    if !scene.settings.has_data_channels() {
        return Ok(());
    }
    if args.part.is_some() {
        return Err("render.channels are written with the whole image; a --part is a checkpoint of its tiles, and \
                    nullpath merge writes colour only: render the data channels of the whole image in one run"
            .into());
    }
    let is_exr = args.output.extension().is_some_and(|e| e.eq_ignore_ascii_case("exr"));
    if !is_exr {
        return Err(format!(
            "render.channels asks for data channels, which only an .exr image holds; the output is '{}'",
            args.output.display()
        ));
    }
    Ok(())
}

/// Photon mapping's iterations share every photon between all pixels, so a part of the image
/// would not be the whole render's part; and its estimate is consistent, not unbiased, so the
/// spread of its iterations does not measure its error.
fn refuse_for_photon_mapping(args: &Args) -> Result<(), String> {
    if args.part.is_some() {
        return Err("--part is not available with integrator = \"photon\": every photon of an iteration \
                    lands in any pixel, so a part cannot be rendered on its own; split the frames of an \
                    animation instead (nullpath animate --frames)"
            .into());
    }
    if args.noise_target.is_some() {
        return Err("--noise-target is not available with integrator = \"photon\": photon mapping's error is \
                    mostly bias that shrinks with the iterations, which the spread of its iterations does not \
                    measure; set the number of iterations (--spp) instead"
            .into());
    }
    Ok(())
}

/// One `nullpath render` command with its scene, validated.
struct Command<'a> {
    args: &'a Args,
    scene: &'a Scene,
    source: &'a Source,
    goal: Goal,
    part: Part,
    pool: &'a rayon::ThreadPool,
    interrupts: &'a Interrupts,
}

impl Command<'_> {
    fn metadata(&self, stats: &RenderStats) -> Metadata {
        provenance::metadata(self.scene, self.source, self.goal, self.part, stats)
    }

    /// Runs `render` to its end or an interruption and writes what it made.
    fn drive(&self, render: &dyn Progressive) -> Result<(), Failure> {
        let args = self.args;
        let checkpoint = args.checkpoint_path();
        let metadata = |stats: &RenderStats| self.metadata(stats);
        let save = || write_checkpoint(render, &checkpoint, &metadata);
        let stats = self.run_with_checkpoints(render, &save);
        if let Some(reason) = self.interrupts.reason().filter(|_| !stats.is_complete()) {
            let saved = write_checkpoint(render, &checkpoint, &|_| metadata(&stats));
            return interrupted(args, self.scene, &stats, (reason, render.unit()), saved);
        }
        if args.part.is_none() {
            let data = render::renderer::requested_data(self.scene);
            let (film, tonemap) = (render.film(), &self.scene.settings.tonemap);
            write_image_with_data(&film, data.as_ref(), &args.output, tonemap, &metadata(&stats))
                .map_err(|e| e.to_string())?;
        } else {
            write_checkpoint(render, &args.output, &|_| metadata(&stats))?;
        }
        if args.checkpoint.is_some() {
            write_checkpoint(render, &checkpoint, &|_| metadata(&stats))?;
        } else if args.resume.as_deref().is_some_and(|resume| same_file(resume, &checkpoint)) {
            // The work is in the image now; the checkpoint an interruption left is done with.
            let _ = std::fs::remove_file(&checkpoint);
        }
        if let Some(path) = &args.stats {
            write_stats(path, &stats, self.scene)?;
        }
        if !args.options.quiet {
            eprintln!("wrote {}", summary(&stats, self.scene));
            eprintln!("{}: {}", if args.part.is_none() { "image" } else { "part" }, args.output.display());
        }
        Ok(())
    }

    /// Runs `render` on the pool, calling `save` every `--checkpoint-every` from a second thread
    /// and stopping the render at `--time-limit`.
    fn run_with_checkpoints(
        &self,
        render: &dyn Progressive,
        save: &(dyn Fn() -> Result<(), String> + Sync),
    ) -> RenderStats {
        let args = self.args;
        let every = args.checkpoint_every.or(args.checkpoint.as_ref().map(|_| Duration::from_secs(300)));
        let start = Instant::now();
        let deadline = args.time_limit.map(|limit| start + limit);
        let finished = (Mutex::new(false), Condvar::new());
        let progress = args.options.progress();
        std::thread::scope(|scope| {
            scope.spawn(|| {
                let mut next_checkpoint = every.map(|e| start + e);
                let (lock, wake) = &finished;
                let mut done = lock.lock().unwrap_or_else(|e| e.into_inner());
                while !*done {
                    let now = Instant::now();
                    if deadline.is_some_and(|d| now >= d) {
                        self.interrupts.stop_for_time_limit();
                    }
                    if let (Some(at), Some(every)) = (next_checkpoint, every) {
                        if now >= at {
                            if let Err(e) = save() {
                                eprintln!("nullpath: warning: {e}");
                            }
                            next_checkpoint = Some(Instant::now() + every);
                        }
                    }
                    let wait = [next_checkpoint, deadline]
                        .into_iter()
                        .flatten()
                        .min()
                        .map_or(Duration::from_secs(3600), |t| {
                            t.saturating_duration_since(Instant::now()).max(Duration::from_millis(1))
                        });
                    done = wake.wait_timeout(done, wait).map(|(d, _)| d).unwrap_or_else(|e| e.into_inner().0);
                }
            });
            let stats =
                self.pool.install(|| render.run(&self.interrupts.cancel, &|done, total| progress.show(done, total)));
            progress.finish();
            *finished.0.lock().unwrap_or_else(|e| e.into_inner()) = true;
            finished.1.notify_all();
            stats
        })
    }

    /// The checkpoint at `path` (as the scene's light transport writes it), if this render
    /// continues it.
    fn resume(&self, path: &Path) -> Result<Resume, String> {
        let (state, metadata) =
            Checkpointed::read(path, self.scene.settings.integrator).map_err(|e| format!("--resume: {e}"))?;
        let (paths, seconds) = self.check_continues(path, &metadata, state.size(), state.reached())?;
        Ok(Resume { state, paths, seconds })
    }

    /// Whether the checkpoint at `path` with `metadata`, of `size` and `reached` samples (or
    /// iterations) per pixel, can be continued by this render; the work it records if so.
    fn check_continues(
        &self,
        path: &Path,
        metadata: &Metadata,
        (width, height): (u32, u32),
        reached: u32,
    ) -> Result<(PathStats, f64), String> {
        let refuse = |why: String| format!("--resume {}: cannot continue this render: {why}", path.display());
        provenance::check_resumable(metadata, &self.metadata(&RenderStats::default())).map_err(refuse)?;
        if (width, height) != (self.scene.settings.width, self.scene.settings.height) {
            return Err(refuse(format!("it is {width}x{height}")));
        }
        if reached > self.goal.spp {
            return Err(refuse(format!(
                "it already has {reached} samples per pixel, more than the {} asked for",
                self.goal.spp
            )));
        }
        Ok(provenance::recorded_work(metadata))
    }
}

/// Writes `render`'s checkpoint to `path` (see [`Progressive::write_checkpoint`]), its failure
/// worded for the command line.
fn write_checkpoint(
    render: &dyn Progressive,
    path: &Path,
    metadata: &dyn Fn(&RenderStats) -> Metadata,
) -> Result<(), String> {
    render.write_checkpoint(path, metadata).map_err(|e| format!("checkpoint: {e}"))
}

/// Reports a render stopped for `reason`, counting in `unit`, whose checkpoint was (or failed to
/// be) saved.
fn interrupted(
    args: &Args,
    scene: &Scene,
    stats: &RenderStats,
    (reason, unit): (StopReason, Unit),
    saved: Result<(), String>,
) -> Result<(), Failure> {
    saved?;
    if let Some(path) = &args.stats {
        write_stats(path, stats, scene)?;
    }
    let checkpoint = args.checkpoint_path();
    let spp = if stats.spp_min == stats.spp_max {
        stats.spp_max.to_string()
    } else {
        format!("{}–{}", stats.spp_min, stats.spp_max)
    };
    let why = match (reason, args.time_limit) {
        (StopReason::TimeLimit, Some(limit)) => format!("{reason} ({})", humantime::format_duration(limit)),
        _ => reason.to_string(),
    };
    // Asked for, and nothing lost: news, not an error; the exit status tells scripts it stopped.
    Err(Failure::stopped(
        format!(
            "{why} at {spp} {unit}; the work is in the checkpoint {} ({} was not touched). \
             Continue with the same command and --resume {}",
            checkpoint.display(),
            args.output.display(),
            checkpoint.display()
        ),
        reason.exit_code(),
    ))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn durations_and_sizes() {
        assert_eq!(parse_duration("90s"), Ok(Duration::from_secs(90)));
        assert_eq!(parse_duration("1h30m"), Ok(Duration::from_secs(5400)));
        assert_eq!(parse_duration("2.5"), Ok(Duration::from_millis(2500)));
        assert!(parse_duration("0").is_err());
        assert!(parse_duration("soon").is_err());
        assert!(parse_duration("-3").is_err());
        assert_eq!(parse_bytes("8G"), Ok(8 << 30));
        assert_eq!(parse_bytes("512MiB"), Ok(512 << 20));
        assert_eq!(parse_bytes("1000"), Ok(1000));
        assert!(parse_bytes("lots").is_err());
        assert!(parse_bytes("0").is_err());
        assert_eq!(default_checkpoint(Path::new("out/render.png")), Path::new("out/render.checkpoint.exr"));
    }
}

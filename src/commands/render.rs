//! `nullpath render`: render a scene file (or the default scene) to PNG or EXR.

use clap::Parser;
use indicatif::{ProgressBar, ProgressStyle};
use render::film::{check_output_path, write_image, Film};
use render::renderer::{render, RenderStats};
use render::scene::Scene;
use std::io::IsTerminal;
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::Arc;

/// The scene rendered when none is named.
pub const DEFAULT_SCENE: &str = include_str!("../../scenes/room-black-hole.toml");
pub const DEFAULT_SCENE_NAME: &str = "<default scene: scenes/room-black-hole.toml>";

#[derive(Parser, Debug)]
pub struct Args {
    /// Scene file (TOML); the default scene when omitted.
    scene: Option<PathBuf>,
    /// Output image: .png (8-bit sRGB, tone mapped), .exr (linear float) or .hdr.
    #[arg(short, long, default_value = "render.png")]
    output: PathBuf,
    /// Animation time (seconds) to render the camera at; frame N of `nullpath animate` is
    /// time N / fps.
    #[arg(long, default_value_t = 0.0, allow_negative_numbers = true)]
    time: f64,
    #[command(flatten)]
    options: RenderOptions,
    /// Write statistics (rays, samples, seconds, NaN samples, ray fates) as JSON here.
    #[arg(long)]
    stats: Option<PathBuf>,
}

/// Options shared by the commands that render: view, image size, sampling, threads, reporting.
#[derive(clap::Args, Debug)]
pub struct RenderOptions {
    /// Render from the scene's view NAME (its `[views.NAME]` camera) instead of its `[camera]`.
    #[arg(long, value_name = "NAME")]
    view: Option<String>,
    #[arg(long)]
    width: Option<u32>,
    #[arg(long)]
    height: Option<u32>,
    /// Samples per pixel.
    #[arg(long)]
    spp: Option<u32>,
    #[arg(long)]
    seed: Option<u64>,
    /// Worker threads (default: all cores). The image does not depend on it.
    #[arg(long)]
    threads: Option<usize>,
    /// No progress bar or summary.
    #[arg(long)]
    pub quiet: bool,
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
        let mut scene = load_scene(path, self.view.as_deref())?;
        self.apply(&mut scene)?;
        Ok(scene)
    }

    /// Applies the command-line overrides to the scene's settings.
    fn apply(&self, scene: &mut Scene) -> Result<(), String> {
        let s = &mut scene.settings;
        let positive = |name: &str, v: Option<u32>, max: u32| match v {
            Some(0) => Err(format!("--{name} must be at least 1")),
            Some(v) if v > max => Err(format!("--{name} {v} is larger than {max}")),
            other => Ok(other),
        };
        if let Some(w) = positive("width", self.width, 16384)? {
            s.width = w;
        }
        if let Some(h) = positive("height", self.height, 16384)? {
            s.height = h;
        }
        if let Some(n) = positive("spp", self.spp, 1 << 20)? {
            s.spp = n;
        }
        if let Some(seed) = self.seed {
            s.seed = seed;
        }
        Ok(())
    }

    pub fn thread_pool(&self) -> Result<rayon::ThreadPool, String> {
        rayon::ThreadPoolBuilder::new()
            .num_threads(self.threads.unwrap_or(0))
            .build()
            .map_err(|e| format!("--threads: {e}"))
    }

    /// Renders `scene` on `pool` with a progress bar (on a terminal, unless quiet); setting
    /// `cancel` stops it between tiles.
    pub fn render(&self, scene: &Scene, pool: &rayon::ThreadPool, cancel: &AtomicBool) -> (Film, RenderStats) {
        let bar = (!self.quiet && std::io::stderr().is_terminal()).then(|| {
            let bar = ProgressBar::new(1);
            bar.set_style(
                ProgressStyle::with_template("{spinner} [{elapsed_precise}] {wide_bar} {percent:>3}% ETA {eta}")
                    .unwrap_or_else(|_| ProgressStyle::default_bar()),
            );
            bar
        });
        let progress = |done: u64, total: u64| {
            if let Some(bar) = &bar {
                bar.set_length(total);
                bar.set_position(done);
            }
        };
        let result = pool.install(|| render(scene, cancel, &progress));
        if let Some(bar) = &bar {
            bar.finish_and_clear();
        }
        result
    }
}

/// A flag that Ctrl-C sets; renders poll it between tiles.
pub fn cancel_on_interrupt() -> Result<Arc<AtomicBool>, String> {
    let cancel = Arc::new(AtomicBool::new(false));
    let flag = Arc::clone(&cancel);
    // A second Ctrl-C while the image is being written kills the process as usual.
    ctrlc::set_handler(move || flag.store(true, Ordering::Relaxed))
        .map_err(|e| format!("cannot handle Ctrl-C: {e}"))?;
    Ok(cancel)
}

/// Statistics as the JSON object `--stats` writes.
pub fn stats_json(stats: &RenderStats, scene: &Scene) -> serde_json::Value {
    let f = &stats.paths.fates;
    serde_json::json!({
        "rays": stats.paths.rays,
        "samples": stats.samples,
        "seconds": stats.seconds,
        "nan_samples": stats.nan_samples,
        "fates": {
            "escaped": f.escaped, "captured": f.captured, "absorbed": f.absorbed,
            "traversed": f.traversed, "failed": f.failed,
        },
        "width": scene.settings.width,
        "height": scene.settings.height,
        "spp": scene.settings.spp,
        "tiles_done": stats.tiles_done,
        "tiles_total": stats.tiles_total,
        "complete": stats.tiles_done == stats.tiles_total,
    })
}

/// One line on a finished render: size, samples, time, ray fates.
pub fn summary(stats: &RenderStats, scene: &Scene) -> String {
    let f = &stats.paths.fates;
    format!(
        "{}×{} at {} spp in {:.2} s ({:.0} samples/s); rays escaped {}, captured {}, absorbed {}, traversed {}, failed {}; NaN samples {}",
        scene.settings.width,
        scene.settings.height,
        scene.settings.spp,
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

pub fn run(args: &Args) -> Result<(), String> {
    let mut scene = args.options.load(args.scene.as_deref())?;
    if !args.time.is_finite() {
        return Err(format!("--time must be a finite number of seconds, got {}", args.time));
    }
    scene.set_time(args.time)?;
    check_output_path(&args.output).map_err(|e| e.to_string())?;
    let pool = args.options.thread_pool()?;
    let cancel = cancel_on_interrupt()?;
    let (film, stats) = args.options.render(&scene, &pool, &cancel);
    write_image(&film, &args.output, &scene.settings.tonemap).map_err(|e| e.to_string())?;
    if let Some(path) = &args.stats {
        let text = serde_json::to_string_pretty(&stats_json(&stats, &scene)).map_err(|e| e.to_string())?;
        std::fs::write(path, text + "\n").map_err(|e| format!("{}: cannot write statistics: {e}", path.display()))?;
    }
    let interrupted = stats.tiles_done < stats.tiles_total;
    if !args.options.quiet {
        let verb = if interrupted { "interrupted: wrote the finished part of" } else { "wrote" };
        eprintln!("{verb} {}", summary(&stats, &scene));
        eprintln!("image: {}", args.output.display());
    }
    if interrupted {
        return Err(format!(
            "interrupted after {} of {} tiles; the finished tiles are in {}",
            stats.tiles_done,
            stats.tiles_total,
            args.output.display()
        ));
    }
    Ok(())
}

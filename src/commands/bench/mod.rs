//! `nullpath bench WORKLOAD`: throughput on the standard workloads, on one core and on all.

use clap::{Parser, ValueEnum};
use rayon::prelude::*;
use render::renderer::RenderStats;
use spacetime::fan::{trace_hamiltonian, trace_in_plane, Fan, FanRay};
use spacetime::{Schwarzschild, Stepping, TraceSettings};
use std::sync::atomic::AtomicBool;
use std::time::Instant;

mod mesh;

#[derive(Clone, Copy, Debug, ValueEnum)]
pub enum Workload {
    /// 512² camera fan at r = 30 M, 40° field of view, Schwarzschild, adaptive 1e-8.
    Geodesics,
    /// The Cornell box at 256², 64 samples per pixel, path depth 8.
    Cornell,
    /// The poster's room with its black hole, and the same room with mass 0 (256², 64 spp,
    /// depth 8): the ratio of their times is the cost of curved spacetime.
    Room,
    /// The poster's room with its black hole rendered in RGB and spectrally (paths carrying
    /// sampled wavelengths; 256², 64 spp, depth 8): the ratio of their times is the cost of
    /// spectral rendering.
    Spectral,
    /// The room with its black hole and millions of triangles: a rock of a million triangles
    /// and twelve instances of another (256², 16 spp, depth 8): BVH build time, memory per
    /// triangle, rays/s.
    Mesh,
    /// A thin accretion disk about a Kerr hole (a = 0.9 M) seen from 100 M at 80° from the spin
    /// axis, as scenes/accretion-disk.toml but on a black sky: 512², one camera ray per pixel,
    /// no bounce (the disk's own light): rays/s, to set beside kerrz and Gyoto
    /// (bench/peers/disk.py).
    Disk,
    /// The first frame `nullpath preview` shows of the default scene: its text parsed, the
    /// preview's low-resolution frame rendered at 1 spp on all cores and encoded as PNG.
    Preview,
}

/// The benchmark scenes, bundled with the binary so the benchmarks run anywhere.
const CORNELL_SCENE: &str = include_str!("../../../scenes/cornell-box.toml");
const ROOM_SCENE: &str = include_str!("../../../scenes/room-black-hole.toml");

/// The disk workload: scenes/accretion-disk.toml's hole, camera and disk, on a black sky, at one
/// sample per pixel with no bounce.
const DISK_SCENE: &str = r#"
[spacetime]
type = "kerr"
mass = 1.0
spin = 0.9
axis = [0, 1, 0]

[camera]
position = [0.0, 17.365, 98.481]
look_at = [0.0, 0.0, 0.0]
up = [0, 1, 0]
fov = 28

[render]
spp = 1
max_depth = 0

[accretion_disk]
outer_radius = 20.0
temperature = 9000
"#;

#[derive(Parser, Debug)]
pub struct Args {
    #[arg(value_enum)]
    workload: Workload,
    /// Image or fan size (pixels or rays per side); default 512 for geodesics, 256 for scenes.
    #[arg(long)]
    size: Option<u32>,
    /// Repetitions; the fastest is reported (and for the room, the median ratio of the pairs).
    #[arg(long, default_value_t = 3)]
    repeat: u32,
    /// Print one JSON object instead of text.
    #[arg(long)]
    json: bool,
    /// Also write one render of the workload's (first) scene to this image, to look at it.
    #[arg(long, value_name = "PATH")]
    image: Option<std::path::PathBuf>,
}

/// Throughput of one configuration.
struct Measurement {
    method: &'static str,
    threads: usize,
    rays: u64,
    steps: u64,
    seconds: f64,
}

impl Measurement {
    fn rays_per_second(&self) -> f64 {
        self.rays as f64 / self.seconds
    }

    fn steps_per_second(&self) -> f64 {
        self.steps as f64 / self.seconds
    }
}

fn measure(
    method: &'static str,
    threads: usize,
    rays: &[u64],
    repeat: u32,
    trace: &(dyn Fn(u64) -> FanRay + Sync),
) -> Result<Measurement, String> {
    let pool = rayon::ThreadPoolBuilder::new().num_threads(threads).build().map_err(|e| e.to_string())?;
    let mut best = f64::INFINITY;
    let mut steps = 0;
    for _ in 0..repeat.max(1) {
        let start = Instant::now();
        steps = pool.install(|| rays.par_iter().map(|&i| u64::from(trace(i).steps)).sum::<u64>());
        best = best.min(start.elapsed().as_secs_f64());
    }
    Ok(Measurement { method, threads, rays: rays.len() as u64, steps, seconds: best })
}

pub fn run(args: &Args) -> Result<(), String> {
    if let Some(size) = args.size.filter(|&s| s == 0 || s > 8192) {
        return Err(format!("--size {size}: must be between 1 and 8192"));
    }
    match args.workload {
        Workload::Geodesics => geodesics(args),
        Workload::Cornell => {
            let cornell = scene::parse(CORNELL_SCENE, "scenes/cornell-box.toml", std::path::Path::new("."))
                .map_err(|e| e.to_string())?;
            scene_bench(args, "cornell", cornell)
        }
        Workload::Room => room(args),
        Workload::Spectral => spectral(args),
        Workload::Mesh => mesh_bench(args),
        Workload::Preview => preview_first_frame(args),
        Workload::Disk => disk(args),
    }
}

/// The room with its black hole and with mass 0, rendered in turn (curved, flat, curved, …) so
/// that a machine's drift between runs, which on a shared host moves one scene's time by more
/// than a tenth, falls on both alike: the cost of curved spacetime is the median of the ratios
/// of the pairs on all threads.
fn room(args: &Args) -> Result<(), String> {
    let curved = room_scene()?;
    let flat =
        render::scene::Scene { spacetime: spacetime::Spacetime::Minkowski(spacetime::Minkowski), ..curved.clone() };
    let pair = Pair { workload: "room", names: ["room (black hole)", "room (mass 0)"], ratio: ("curved", "flat") };
    pair.run(args, [curved, flat])
}

/// The room with its black hole in spectral and in RGB rendering, in turn as [`room`]'s pair.
fn spectral(args: &Args) -> Result<(), String> {
    let rgb = room_scene()?;
    let mut spectral = rgb.clone();
    spectral.settings.spectral = true;
    let pair = Pair { workload: "spectral", names: ["room (spectral)", "room (RGB)"], ratio: ("spectral", "rgb") };
    pair.run(args, [spectral, rgb])
}

fn room_scene() -> Result<render::scene::Scene, String> {
    scene::parse(ROOM_SCENE, "scenes/room-black-hole.toml", std::path::Path::new(".")).map_err(|e| e.to_string())
}

/// Two scenes rendered in turn, reported with the median ratio of their times.
struct Pair {
    workload: &'static str,
    names: [&'static str; 2],
    /// What the first and the second are called in the ratio (`first_over_second` in JSON).
    ratio: (&'static str, &'static str),
}

impl Pair {
    fn run(&self, args: &Args, scenes: [render::scene::Scene; 2]) -> Result<(), String> {
        let scenes = scenes.map(|scene| workload(args, scene));
        let (rows, turns) = in_turn(args, &scenes)?;
        let ratios: Vec<f64> = turns.iter().map(|[first, second]| first / second).collect();
        let median = median(&ratios);
        let (first, second) = self.ratio;
        if args.json {
            let [a, b] = [0, 1].map(|i| report_json(self.names[i], &scenes[i], &rows[i]));
            let mut v = serde_json::json!({ "workload": self.workload });
            v[first] = a;
            v[second] = b;
            v[format!("{first}_over_{second}")] = serde_json::json!({ "median": median, "pairs": ratios });
            println!("{v}");
        } else {
            for ((name, scene), rows) in self.names.iter().zip(&scenes).zip(&rows) {
                report_text(name, scene, rows);
            }
            let pairs = ratios.iter().map(|r| format!("{r:.2}")).collect::<Vec<_>>().join(", ");
            println!(
                "{first} ÷ {second} time, all threads: {median:.2} (median of {} interleaved pairs: {pairs})",
                ratios.len()
            );
        }
        Ok(())
    }
}

/// The accretion disk at `--size`² (default 512), one ray per pixel.
fn disk(args: &Args) -> Result<(), String> {
    let mut scene = scene::parse(DISK_SCENE, "bench disk", std::path::Path::new(".")).map_err(|e| e.to_string())?;
    let size = args.size.unwrap_or(512);
    (scene.settings.width, scene.settings.height) = (size, size);
    let scene = [scene];
    let ([rows], _) = in_turn(args, &scene)?;
    if args.json {
        println!("{}", report_json("disk", &scene[0], &rows));
    } else {
        report_text("disk", &scene[0], &rows);
    }
    Ok(())
}

/// The room with millions of triangles (see [`mesh`]): what building it took, then its renders
/// in turn with the room's own, whose ratio is the cost of the triangles.
fn mesh_bench(args: &Args) -> Result<(), String> {
    let room = room_scene()?;
    let built = mesh::build(room.clone())?;
    let scenes = [built.scene, room].map(|scene| {
        let mut scene = workload(args, scene);
        scene.settings.spp = 16;
        scene
    });
    let (rows, turns) = in_turn(args, &scenes)?;
    let ratios: Vec<f64> = turns.iter().map(|[meshes, room]| meshes / room).collect();
    let ratio = median(&ratios);
    let per_triangle = built.bytes.map(|b| b as f64 / built.stored as f64);
    let user = mesh::user_path()?;
    if args.json {
        let mut report = report_json("mesh", &scenes[0], &rows[0]);
        report["triangles"] = serde_json::json!({ "stored": built.stored, "rendered": built.rendered });
        report["bvh_build_seconds"] = built.bvh_seconds.into();
        report["bytes_per_stored_triangle"] = per_triangle.into();
        report["room"] = report_json("room", &scenes[1], &rows[1]);
        report["meshes_over_room"] = serde_json::json!({ "median": ratio, "pairs": ratios });
        report["user_path"] = serde_json::json!({
            "triangles": user.triangles,
            "load_seconds": user.load_seconds,
            "metadata_seconds": user.metadata_seconds,
        });
        println!("{report}");
    } else {
        println!(
            "mesh: {} triangles stored, {} rendered (instances); BVHs built in {:.2} s; {} per stored triangle",
            built.stored,
            built.rendered,
            built.bvh_seconds,
            per_triangle.map_or("memory not measured".to_owned(), |b| format!("{b:.0} bytes"))
        );
        println!(
            "user path: a {}-triangle OBJ scene loaded in {:.2} s (parse, mesh, BVH), its image metadata made in {:.3} s",
            user.triangles, user.load_seconds, user.metadata_seconds
        );
        report_text("room with the meshes", &scenes[0], &rows[0]);
        report_text("room without them", &scenes[1], &rows[1]);
        println!("with ÷ without time, all threads: {ratio:.2} (median of {} interleaved pairs)", ratios.len());
    }
    Ok(())
}

/// The time from the default scene's text to the PNG of its first preview frame (`--size` does
/// not apply: the preview's own low resolution is measured); the fastest and the median of
/// `--repeat` runs.
fn preview_first_frame(args: &Args) -> Result<(), String> {
    if args.size.is_some() {
        return Err("--size does not apply to bench preview: it measures the preview's own first frame".into());
    }
    let cancel = AtomicBool::new(false);
    let mut times = Vec::new();
    let mut frame = (0, 0, 0);
    for _ in 0..args.repeat.max(1) {
        let start = Instant::now();
        let scene = super::render::load_scene(None, None)?;
        let low = super::preview::low_resolution(&scene);
        let (film, _) = render::renderer::render(&low, &cancel, &|_, _| {});
        let png = super::preview::encode_png(&film, &low)?;
        times.push(start.elapsed().as_secs_f64());
        frame = (film.width(), film.height(), png.len());
    }
    let fastest = times.iter().copied().fold(f64::INFINITY, f64::min);
    let median = median(&times);
    let cores = std::thread::available_parallelism().map_or(1, |n| n.get());
    if args.json {
        println!(
            "{}",
            serde_json::json!({ "workload": "preview", "width": frame.0, "height": frame.1, "png_bytes": frame.2,
                "threads": cores, "fastest_seconds": fastest, "median_seconds": median, "runs": times })
        );
    } else {
        println!(
            "preview: first frame of the default scene, {}×{} at 1 spp ({} bytes of PNG), {cores} threads: \
             fastest {:.3} s, median {:.3} s of {}",
            frame.0,
            frame.1,
            frame.2,
            fastest,
            median,
            times.len()
        );
    }
    Ok(())
}

/// The middle value of `values` (the mean of the middle two for an even count).
fn median(values: &[f64]) -> f64 {
    let mut sorted = values.to_vec();
    sorted.sort_by(f64::total_cmp);
    let n = sorted.len();
    if n == 0 {
        return f64::NAN;
    }
    0.5 * (sorted[(n - 1) / 2] + sorted[n / 2])
}

/// A scene's fastest render on each thread count: `(threads, stats)`.
type Rows = Vec<(usize, RenderStats)>;

/// `scene` as the scene benchmarks render it: `size`², 64 spp, depth 8.
fn workload(args: &Args, mut scene: render::scene::Scene) -> render::scene::Scene {
    let size = args.size.unwrap_or(256);
    scene.settings.width = size;
    scene.settings.height = size;
    scene.settings.spp = 64;
    scene.settings.max_depth = 8;
    scene
}

/// Renders `scenes` in turn (each once, then each again, …), `--repeat` turns on one thread and
/// on all: each scene's fastest render per thread count, and the seconds of every turn on all
/// threads.
fn in_turn<const N: usize>(
    args: &Args,
    scenes: &[render::scene::Scene; N],
) -> Result<([Rows; N], Vec<[f64; N]>), String> {
    if let Some(path) = &args.image {
        let film = render::renderer::render(&scenes[0], &AtomicBool::new(false), &|_, _| {}).0;
        let metadata = render::film::Metadata::from([("bench".to_owned(), format!("{:?}", args.workload))]);
        render::film::write_image(&film, path, &scenes[0].settings.tonemap, &metadata).map_err(|e| e.to_string())?;
    }
    let cores = std::thread::available_parallelism().map_or(1, |n| n.get());
    let cancel = AtomicBool::new(false);
    let mut rows: [Rows; N] = std::array::from_fn(|_| Vec::new());
    let mut turns = Vec::new();
    for threads in [1, cores] {
        let pool = rayon::ThreadPoolBuilder::new().num_threads(threads).build().map_err(|e| e.to_string())?;
        let mut best: [Option<RenderStats>; N] = std::array::from_fn(|_| None);
        for _ in 0..args.repeat.max(1) {
            let turn =
                scenes.each_ref().map(|scene| pool.install(|| render::renderer::render(scene, &cancel, &|_, _| {})).1);
            if threads == cores {
                turns.push(turn.each_ref().map(|stats| stats.seconds));
            }
            for (best, stats) in best.iter_mut().zip(turn) {
                if best.as_ref().is_none_or(|b| stats.seconds < b.seconds) {
                    *best = Some(stats);
                }
            }
        }
        for (rows, best) in rows.iter_mut().zip(best) {
            rows.extend(best.map(|stats| (threads, stats)));
        }
    }
    Ok((rows, turns))
}

/// Renders `scene` on one thread and on all, `--repeat` times each, and reports the fastest.
fn scene_bench(args: &Args, name: &str, scene: render::scene::Scene) -> Result<(), String> {
    let scene = [workload(args, scene)];
    let ([rows], _) = in_turn(args, &scene)?;
    if args.json {
        println!("{}", report_json(name, &scene[0], &rows));
    } else {
        report_text(name, &scene[0], &rows);
    }
    Ok(())
}

fn report_json(name: &str, scene: &render::scene::Scene, rows: &Rows) -> serde_json::Value {
    let results: Vec<_> = rows
        .iter()
        .map(|(threads, s)| {
            serde_json::json!({
                "threads": threads, "seconds": s.seconds, "samples": s.samples, "rays": s.paths.rays,
                "samples_per_second": s.samples as f64 / s.seconds, "rays_per_second": s.paths.rays as f64 / s.seconds,
            })
        })
        .collect();
    let settings = &scene.settings;
    serde_json::json!({ "workload": name, "size": settings.width, "spp": settings.spp, "max_depth": settings.max_depth,
        "results": results })
}

fn report_text(name: &str, scene: &render::scene::Scene, rows: &Rows) {
    let settings = &scene.settings;
    println!(
        "{name}: {0}×{0}, {1} spp, depth {2}, spacetime {3}",
        settings.width,
        settings.spp,
        settings.max_depth,
        scene.spacetime.name()
    );
    println!("{:>7} {:>10} {:>12} {:>14} {:>14}", "threads", "seconds", "samples", "samples/s", "rays/s");
    for (threads, s) in rows {
        println!(
            "{:>7} {:>10.3} {:>12} {:>14.0} {:>14.0}",
            threads,
            s.seconds,
            s.samples,
            s.samples as f64 / s.seconds,
            s.paths.rays as f64 / s.seconds
        );
    }
}

fn geodesics(args: &Args) -> Result<(), String> {
    let hole = Schwarzschild::new(1.0);
    let fan = Fan { size: args.size.unwrap_or(512), ..Fan::standard(1.0) };
    let settings = TraceSettings { stepping: Stepping::Adaptive { rtol: 1e-8 }, ..TraceSettings::default() };
    let all: Vec<u64> = (0..fan.rays()).collect();
    // The 4-D tracer is measured on every 4th ray of every 4th row, to keep the run short.
    let size = u64::from(fan.size);
    let sparse: Vec<u64> = all.iter().copied().filter(|i| (i % size) % 4 == 0 && (i / size) % 4 == 0).collect();
    let cores = std::thread::available_parallelism().map_or(1, |n| n.get());
    let plane = |i: u64| trace_in_plane(&hole, &fan, i, &settings);
    let full = |i: u64| trace_hamiltonian(&hole, &fan, i, &settings);
    let mut results = Vec::new();
    for threads in [1, cores] {
        results.push(measure("in-plane", threads, &all, args.repeat, &plane)?);
        results.push(measure("4-D Hamiltonian", threads, &sparse, args.repeat, &full)?);
    }
    if args.json {
        let rows: Vec<_> = results
            .iter()
            .map(|m| {
                serde_json::json!({
                    "method": m.method, "threads": m.threads, "rays": m.rays, "steps": m.steps,
                    "seconds": m.seconds, "rays_per_second": m.rays_per_second(), "steps_per_second": m.steps_per_second(),
                })
            })
            .collect();
        println!("{}", serde_json::json!({ "workload": "geodesics", "fan": fan.size, "results": rows }));
    } else {
        println!(
            "geodesics: {0}×{0} fan, camera at r = 30 M, 40° field of view, Schwarzschild, adaptive rtol 1e-8",
            fan.size
        );
        println!(
            "{:<16} {:>7} {:>9} {:>10} {:>12} {:>14}",
            "method", "threads", "rays", "seconds", "rays/s", "steps/s"
        );
        for m in &results {
            println!(
                "{:<16} {:>7} {:>9} {:>10.4} {:>12.0} {:>14.0}",
                m.method,
                m.threads,
                m.rays,
                m.seconds,
                m.rays_per_second(),
                m.steps_per_second()
            );
        }
    }
    Ok(())
}

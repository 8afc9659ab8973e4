//! Equal-time comparison of light sampling along geodesics against brute force on the poster's
//! room with its black hole (the measurement behind BENCHMARKS.md; not a test, since it times).
//!
//! 1. A long brute-force render in two independent halves is the reference.
//! 2. Each integrator's time per sample is measured on a short pilot render, after a one-sample
//!    render that builds what is built once per process (the connection solver's start tables,
//!    ~0.1 s), which no render of a real size notices and a tiny one would be dominated by.
//! 3. Brute force renders `budget` samples per pixel; the path integrator renders as many as fit
//!    in the same time, and so does photon mapping (as many iterations, of one photon per pixel)
//!    where the spacetime supports it. All use seeds other than the reference's. Photon
//!    mapping's error includes its bias, which shrinks with its gather radius.
//! 4. The RMSE of each against the reference (over pixels and channels) is printed, less the
//!    reference's own noise: its per-pixel variance is `E[(A − B)²]/4` for halves `A`, `B`, and
//!    it inflates every squared error by that much. The ratio of the RMSEs is printed as
//!    measured and scaled to exactly equal times (RMSE ∝ 1/√time), since the pilot's estimate
//!    of the path integrator's samples is rounded and CPU times vary from run to run.
//!
//! Times are CPU times of the process (all threads, from `/proc/self/stat`; wall-clock time where
//! that is not available), so other work on the machine does not skew the comparison.
//!
//! `cargo run --release --example equal_time -- [--scene PATH] [--reference PATH] [WIDTH HEIGHT REFERENCE_SPP BUDGET_SPP]`
//! (default the black-hole room, 240 180 1024 64; about two minutes on two cores; each reference half renders half of
//! REFERENCE_SPP). The ratio depends on the image size: the smaller it is, the more texture
//! edges fall inside each pixel, noise both integrators share at equal samples (BENCHMARKS.md).
//! `--reference PATH` keeps the reference in a file and reads it from there when it matches the
//! image size, for comparing builds against one reference (the file does not record the scene:
//! name one file per scene, size and reference samples).

use render::film::Film;
use render::scene::Scene;
use render::settings::IntegratorKind;
use std::sync::atomic::AtomicBool;

const USAGE: &str =
    "usage: equal_time [--scene PATH] [--reference PATH] [WIDTH HEIGHT REFERENCE_SPP BUDGET_SPP], all positive";

const SCENE: &str = include_str!("../scenes/room-black-hole.toml");

fn main() -> Result<(), String> {
    let mut args: Vec<String> = std::env::args().skip(1).collect();
    let mut flag = |name: &str| -> Option<String> {
        let at = args.iter().position(|a| a == name)?;
        (at + 1 < args.len()).then(|| {
            args.remove(at);
            args.remove(at)
        })
    };
    let (text, name) = match flag("--scene") {
        Some(path) => (std::fs::read_to_string(&path).map_err(|e| format!("{path}: {e}"))?, path),
        None => (SCENE.to_string(), "scenes/room-black-hole.toml".to_string()),
    };
    let cache = flag("--reference").map(std::path::PathBuf::from);
    let args: Vec<u32> =
        args.iter().map(|a| a.parse::<u32>().map_err(|e| format!("{a}: {e}"))).collect::<Result<_, _>>()?;
    let [width, height, reference_spp, budget] = match args.as_slice() {
        [] => [240, 180, 1024, 64],
        &[w, h, r, b] if w > 0 && h > 0 && r > 0 && b > 0 => [w, h, r, b],
        _ => return Err(USAGE.into()),
    };
    let mut scene = scene::parse(&text, &name, std::path::Path::new(".")).map_err(|e| e.to_string())?;
    scene.settings.width = width;
    scene.settings.height = height;
    let threads = rayon::current_num_threads();
    println!("{name} at {width}×{height}, depth {}, {threads} threads", scene.settings.max_depth);

    let reference = match cache.as_deref().map(|path| (path, Reference::load(path, width * height))) {
        Some((path, Ok(reference))) => {
            println!("reference: read from {}", path.display());
            reference
        }
        loaded => {
            if let Some((path, Err(e))) = loaded {
                println!("reference: {} not read ({e}), rendering it", path.display());
            }
            let half = (reference_spp / 2).max(1);
            let (reference_a, seconds_a) = run(&scene, IntegratorKind::BruteForce, half, 1000);
            let (reference_b, seconds_b) = run(&scene, IntegratorKind::BruteForce, half, 1001);
            let reference = Reference::new(&reference_a, &reference_b);
            println!("reference: brute force, 2 × {half} spp, {:.1} s", seconds_a + seconds_b);
            if let Some(path) = &cache {
                reference.save(path).map_err(|e| format!("{}: {e}", path.display()))?;
            }
            reference
        }
    };
    println!("reference: mean {:.5}, RMSE of its own noise {:.5}", reference.mean(), reference.noise.sqrt());

    run(&scene, IntegratorKind::Path, 1, 1);
    let pilot_spp = (budget / 4).max(1);
    let (_, t_brute) = run(&scene, IntegratorKind::BruteForce, pilot_spp, 2000);
    let mut rivals = vec![("path", IntegratorKind::Path)];
    if render::integrator::photon::supports(&scene.spacetime) {
        rivals.push(("photon", IntegratorKind::Photon));
    }
    let mut runs = vec![("brute force", IntegratorKind::BruteForce, budget)];
    for &(name, kind) in &rivals {
        let (_, t) = run(&scene, kind, pilot_spp, 2000);
        println!("pilot at {pilot_spp} spp: brute force {t_brute:.2} s, {name} {t:.2} s (÷ {:.2})", t / t_brute);
        runs.push((name, kind, ((f64::from(budget) * t_brute / t).round() as u32).max(1)));
    }

    println!("{:<12} {:>5} {:>9} {:>10} {:>10}", "integrator", "spp", "CPU s", "mean", "RMSE");
    let mut measured = Vec::new();
    for (name, kind, spp) in runs {
        let (film, seconds) = run(&scene, kind, spp, 3000);
        let e = reference.rmse(&film);
        println!("{name:<12} {spp:>5} {seconds:>9.2} {:>10.5} {e:>10.5}", mean(&film));
        measured.push((name, e, seconds));
    }
    let (_, brute_rmse, brute_seconds) = measured[0];
    for &(name, e, seconds) in &measured[1..] {
        let ratio = brute_rmse / e;
        let scaled = ratio * (brute_seconds / seconds).sqrt();
        println!("RMSE ratio brute force ÷ {name} at equal time: {ratio:.2} (scaled to equal CPU time: {scaled:.2})");
    }
    Ok(())
}

/// Renders with `integrator` at `spp` and `seed`; the film and the CPU seconds it took.
fn run(scene: &Scene, integrator: IntegratorKind, spp: u32, seed: u64) -> (Film, f64) {
    let mut scene = scene.clone();
    scene.settings.integrator = integrator;
    scene.settings.spp = spp;
    scene.settings.seed = seed;
    let cpu = cpu_seconds();
    let (film, stats) = render::renderer::render(&scene, &AtomicBool::new(false), &|_, _| {});
    match (cpu, cpu_seconds()) {
        (Some(start), Some(end)) => (film, end - start),
        _ => (film, stats.seconds),
    }
}

/// User and system CPU time of this process so far (Linux), in seconds at the usual 100 ticks
/// per second.
fn cpu_seconds() -> Option<f64> {
    let stat = std::fs::read_to_string("/proc/self/stat").ok()?;
    // Fields after the parenthesised command name; utime and stime are fields 14 and 15.
    let fields: Vec<&str> = stat.rsplit_once(')')?.1.split_whitespace().collect();
    let ticks = |i: usize| fields.get(i)?.parse::<f64>().ok();
    Some((ticks(11)? + ticks(12)?) / 100.0)
}

/// The mean of two independent reference renders, and the variance of its own noise per pixel
/// and channel.
struct Reference {
    pixels: Vec<[f64; 3]>,
    noise: f64,
}

impl Reference {
    fn new(a: &Film, b: &Film) -> Self {
        let noise = squared_difference(pixels(a), pixels(b)) / 4.0;
        let mean = pixels(a).zip(pixels(b)).map(|(p, q)| std::array::from_fn(|i| 0.5 * (p[i] + q[i])));
        Self { pixels: mean.collect(), noise }
    }

    /// The reference as [`Reference::save`] wrote it, if it has `pixels` pixels.
    fn load(path: &std::path::Path, pixels: u32) -> Result<Self, String> {
        let bytes = std::fs::read(path).map_err(|e| e.to_string())?;
        let values: Vec<f64> =
            bytes.chunks_exact(8).map(|b| f64::from_le_bytes(b.try_into().unwrap_or_default())).collect();
        let Some((&noise, rest)) = values.split_first() else { return Err("empty".into()) };
        if rest.len() != 3 * pixels as usize {
            return Err(format!("{} values, not 3 × {pixels}: another scene or size", rest.len()));
        }
        Ok(Self { pixels: rest.chunks_exact(3).map(|p| [p[0], p[1], p[2]]).collect(), noise })
    }

    /// Writes the noise and the pixels as little-endian `f64`s, for [`Reference::load`].
    fn save(&self, path: &std::path::Path) -> std::io::Result<()> {
        let values = std::iter::once(self.noise).chain(self.pixels.iter().flatten().copied());
        std::fs::write(path, values.flat_map(f64::to_le_bytes).collect::<Vec<u8>>())
    }

    fn mean(&self) -> f64 {
        self.pixels.iter().flatten().sum::<f64>() / (3 * self.pixels.len()) as f64
    }

    /// RMSE of `film` against the true image: the error against the reference less its noise.
    fn rmse(&self, film: &Film) -> f64 {
        (squared_difference(pixels(film), self.pixels.iter().copied()) - self.noise).max(0.0).sqrt()
    }
}

fn pixels(film: &Film) -> impl Iterator<Item = [f64; 3]> + '_ {
    (0..film.height()).flat_map(move |y| (0..film.width()).map(move |x| film.pixel_f64(x, y)))
}

fn mean(film: &Film) -> f64 {
    let n = f64::from(film.width() * film.height() * 3);
    pixels(film).map(|p| p.iter().sum::<f64>()).sum::<f64>() / n
}

/// Mean squared difference over pixels and channels.
fn squared_difference(a: impl Iterator<Item = [f64; 3]>, b: impl Iterator<Item = [f64; 3]>) -> f64 {
    let (sum, n) = a
        .zip(b)
        .fold((0.0, 0usize), |(sum, n), (p, q)| (sum + (0..3).map(|i| (p[i] - q[i]).powi(2)).sum::<f64>(), n + 3));
    sum / n.max(1) as f64
}

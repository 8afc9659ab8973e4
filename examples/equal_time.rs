//! Equal-time comparison of light sampling along geodesics against brute force on the poster's
//! room with its black hole (the measurement behind BENCHMARKS.md; not a test, since it times).
//!
//! 1. A long brute-force render is the reference.
//! 2. Each integrator's time per sample is measured on a short pilot render.
//! 3. Brute force renders `budget` samples per pixel; the path integrator renders as many as fit
//!    in the same time. Both use seeds other than the reference's.
//! 4. The RMSE of each against the reference (over pixels and channels) is printed.
//!
//! `cargo run --release --example equal_time -- [WIDTH HEIGHT REFERENCE_SPP BUDGET_SPP]`
//! (default 48 36 4096 64).

use render::film::Film;
use render::scene::Scene;
use render::settings::IntegratorKind;
use std::sync::atomic::AtomicBool;

const SCENE: &str = include_str!("../scenes/room-black-hole.toml");

fn main() -> Result<(), String> {
    let args: Vec<u32> = std::env::args()
        .skip(1)
        .map(|a| a.parse::<u32>().map_err(|e| format!("{a}: {e}")))
        .collect::<Result<_, _>>()?;
    let [width, height, reference_spp, budget] = match args.as_slice() {
        [] => [48, 36, 4096, 64],
        &[w, h, r, b] if w > 0 && h > 0 && r > 0 && b > 0 => [w, h, r, b],
        _ => return Err("usage: equal_time [WIDTH HEIGHT REFERENCE_SPP BUDGET_SPP], all positive".into()),
    };
    let mut scene =
        scene::parse(SCENE, "scenes/room-black-hole.toml", std::path::Path::new(".")).map_err(|e| e.to_string())?;
    scene.settings.width = width;
    scene.settings.height = height;
    let threads = rayon::current_num_threads();
    println!("room-black-hole at {width}×{height}, depth {}, {threads} threads", scene.settings.max_depth);

    let (reference, seconds) = run(&scene, IntegratorKind::BruteForce, reference_spp, 1000);
    println!("reference: brute force, {reference_spp} spp, {seconds:.1} s");

    let pilot_spp = (budget / 4).max(1);
    let (_, t_brute) = run(&scene, IntegratorKind::BruteForce, pilot_spp, 2000);
    let (_, t_path) = run(&scene, IntegratorKind::Path, pilot_spp, 2000);
    let path_spp = ((f64::from(budget) * t_brute / t_path).round() as u32).max(1);
    println!("pilot at {pilot_spp} spp: brute force {t_brute:.2} s, path {t_path:.2} s (÷ {:.2})", t_path / t_brute);

    println!("{:<12} {:>5} {:>9} {:>10} {:>10}", "integrator", "spp", "seconds", "mean", "RMSE");
    let mut rmse = Vec::new();
    for (name, kind, spp) in
        [("brute force", IntegratorKind::BruteForce, budget), ("path", IntegratorKind::Path, path_spp)]
    {
        let (film, seconds) = run(&scene, kind, spp, 3000);
        let e = rms_difference(&film, &reference);
        println!("{name:<12} {spp:>5} {seconds:>9.2} {:>10.5} {e:>10.5}", mean(&film));
        rmse.push(e);
    }
    println!(
        "reference mean {:.5}; RMSE ratio brute force ÷ path at equal time: {:.2}",
        mean(&reference),
        rmse[0] / rmse[1]
    );
    Ok(())
}

/// Renders with `integrator` at `spp` and `seed`; the film and the seconds it took.
fn run(scene: &Scene, integrator: IntegratorKind, spp: u32, seed: u64) -> (Film, f64) {
    let mut scene = scene.clone();
    scene.settings.integrator = integrator;
    scene.settings.spp = spp;
    scene.settings.seed = seed;
    let (film, stats) = render::renderer::render(&scene, &AtomicBool::new(false), &|_, _| {});
    (film, stats.seconds)
}

fn pixels(film: &Film) -> impl Iterator<Item = [f64; 3]> + '_ {
    (0..film.height()).flat_map(move |y| (0..film.width()).map(move |x| film.pixel_f64(x, y)))
}

fn mean(film: &Film) -> f64 {
    let n = f64::from(film.width() * film.height() * 3);
    pixels(film).map(|p| p.iter().sum::<f64>()).sum::<f64>() / n
}

fn rms_difference(a: &Film, b: &Film) -> f64 {
    let n = f64::from(a.width() * a.height() * 3);
    let sum: f64 = pixels(a).zip(pixels(b)).map(|(p, q)| (0..3).map(|i| (p[i] - q[i]).powi(2)).sum::<f64>()).sum();
    (sum / n).sqrt()
}

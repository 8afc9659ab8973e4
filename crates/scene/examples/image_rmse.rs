//! Error of rendered images against a reference made of two independent halves, as used for
//! the photon-mapping figures in BENCHMARKS.md:
//!
//! ```sh
//! cargo run --release -p nullpath-scene --example image_rmse -- [--crop X0,Y0,X1,Y1] REF_A.exr REF_B.exr TEST.exr…
//! ```
//!
//! `--crop` restricts every figure to the pixels `X0 ≤ x < X1`, `Y0 ≤ y < Y1`.
//!
//! The reference is the mean of the halves A and B (same settings, different seeds). Its own
//! noise has per-pixel variance `E[(A − B)²] / 4`, which inflates every test image's squared
//! error against it; the corrected RMSE subtracts it: `√(MSE − E[(A − B)²] / 4)`.
//! Errors are over all pixels and the three channels of linear radiance.
//!
//! It lives in the scene crate because that is where image files are read (`scene::files`).

use render::rgb::Rgb;
use std::path::Path;
use std::process::ExitCode;

/// A pixel rectangle, `[x0, y0, x1, y1)`.
type Crop = [usize; 4];

/// The image's pixels inside `crop` (all of them without one), row by row.
fn load(path: &str, crop: Option<Crop>) -> Result<Vec<Rgb>, String> {
    let image = scene::files::load_image_path(Path::new(path)).map_err(|e| e.to_string())?;
    let (w, h) = (image.width(), image.height());
    let [x0, y0, x1, y1] = crop.unwrap_or([0, 0, w, h]);
    if !(x0 < x1 && x1 <= w && y0 < y1 && y1 <= h) {
        return Err(format!("{path}: crop {x0},{y0},{x1},{y1} does not fit its {w}×{h} pixels"));
    }
    Ok((y0..y1).flat_map(|y| image.pixels()[y * w + x0..y * w + x1].to_vec()).collect())
}

fn parse_crop(text: &str) -> Result<Crop, String> {
    let numbers: Vec<usize> =
        text.split(',').map(str::parse).collect::<Result<_, _>>().map_err(|e| format!("--crop: {e}"))?;
    numbers.try_into().map_err(|_| "--crop takes four numbers: X0,Y0,X1,Y1".to_string())
}

fn mean(pixels: &[Rgb]) -> f64 {
    pixels.iter().map(|p| f64::from(p.x + p.y + p.z)).sum::<f64>() / (3 * pixels.len()) as f64
}

fn mse(a: &[Rgb], b: &[Rgb]) -> f64 {
    let sum: f64 = a.iter().zip(b).map(|(p, q)| f64::from((*p - *q).length_squared())).sum();
    sum / (3 * a.len()) as f64
}

fn run(args: &[String]) -> Result<(), String> {
    let (crop, args) = match args {
        [flag, crop, rest @ ..] if flag == "--crop" => (Some(parse_crop(crop)?), rest),
        _ => (None, args),
    };
    let [a, b, tests @ ..] = args else {
        return Err("usage: image_rmse [--crop X0,Y0,X1,Y1] REF_A REF_B TEST…".into());
    };
    let (a, b) = (load(a, crop)?, load(b, crop)?);
    if a.len() != b.len() {
        return Err("the reference halves differ in size".into());
    }
    let reference: Vec<Rgb> = a.iter().zip(&b).map(|(p, q)| 0.5 * (*p + *q)).collect();
    let noise = mse(&a, &b) / 4.0;
    println!("reference: mean {:.6}, RMSE of its own noise {:.6}", mean(&reference), noise.sqrt());
    for path in tests {
        let t = load(path, crop)?;
        if t.len() != a.len() {
            return Err(format!("{path}: size differs from the reference"));
        }
        let raw = mse(&t, &reference);
        let corrected = (raw - noise).max(0.0).sqrt();
        println!("{path}: mean {:.6}, RMSE {:.6} (raw {:.6})", mean(&t), corrected, raw.sqrt());
    }
    Ok(())
}

fn main() -> ExitCode {
    let args: Vec<String> = std::env::args().skip(1).collect();
    match run(&args) {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("image_rmse: {e}");
            ExitCode::FAILURE
        }
    }
}

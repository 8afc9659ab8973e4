//! Error of rendered images against a reference made of two independent halves, as used for
//! the photon-mapping figures in BENCHMARKS.md:
//!
//! ```sh
//! cargo run --release -p nullpath-render --example image_rmse -- REF_A.exr REF_B.exr TEST.exr…
//! ```
//!
//! The reference is the mean of the halves A and B (same settings, different seeds). Its own
//! noise has per-pixel variance `E[(A − B)²] / 4`, which inflates every test image's squared
//! error against it; the corrected RMSE subtracts it: `√(MSE − E[(A − B)²] / 4)`.
//! Errors are over all pixels and the three channels of linear radiance.

use render::color::Rgb;
use render::image_io::ImageData;
use std::path::Path;
use std::process::ExitCode;

fn load(path: &str) -> Result<ImageData, String> {
    ImageData::load(Path::new(path)).map_err(|e| e.to_string())
}

fn mean(pixels: &[Rgb]) -> f64 {
    pixels.iter().map(|p| f64::from(p.x + p.y + p.z)).sum::<f64>() / (3 * pixels.len()) as f64
}

fn mse(a: &[Rgb], b: &[Rgb]) -> f64 {
    let sum: f64 = a.iter().zip(b).map(|(p, q)| f64::from((*p - *q).length_squared())).sum();
    sum / (3 * a.len()) as f64
}

fn run(args: &[String]) -> Result<(), String> {
    let [a, b, tests @ ..] = args else {
        return Err("usage: image_rmse REF_A REF_B TEST…".into());
    };
    let (a, b) = (load(a)?, load(b)?);
    if (a.width(), a.height()) != (b.width(), b.height()) {
        return Err("the reference halves differ in size".into());
    }
    let reference: Vec<Rgb> = a.pixels().iter().zip(b.pixels()).map(|(p, q)| 0.5 * (*p + *q)).collect();
    let noise = mse(a.pixels(), b.pixels()) / 4.0;
    println!("reference: mean {:.6}, RMSE of its own noise {:.6}", mean(&reference), noise.sqrt());
    for path in tests {
        let t = load(path)?;
        if (t.width(), t.height()) != (a.width(), a.height()) {
            return Err(format!("{path}: size differs from the reference"));
        }
        let raw = mse(t.pixels(), &reference);
        let corrected = (raw - noise).max(0.0).sqrt();
        println!("{path}: mean {:.6}, RMSE {:.6} (raw {:.6})", mean(t.pixels()), corrected, raw.sqrt());
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

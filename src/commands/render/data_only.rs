//! `nullpath render --data-only`: the data channels without the image. One ray through each
//! pixel's centre gives them (as in a full render, bit for bit), so a map of redshifts and ray
//! fates to set beside Gyoto's or kerrz's costs one ray a pixel, not the image's samples and then
//! that ray.

use super::{Args, Source};
use crate::commands::provenance;
use render::film::{write_data_image, DataLayer, FirstMet};
use render::scene::Scene;
use std::time::Instant;

/// Traces the data channels `scene` asks for and writes them alone into `args.output`.
pub(super) fn run(args: &Args, scene: &Scene, source: &Source) -> Result<(), String> {
    check(args, scene)?;
    args.options.check_memory(scene, false)?;
    let pool = args.options.thread_pool()?;
    let start = Instant::now();
    let layer = pool.install(|| render::renderer::data_layer(scene, &render::renderer::propagator(scene)));
    let seconds = start.elapsed().as_secs_f64();
    let mut metadata = provenance::scene_metadata(scene, source);
    metadata.insert("content".to_owned(), "data channels only".to_owned());
    metadata.insert("stats".to_owned(), stats_json(&layer, seconds).to_string());
    write_data_image(&layer, &args.output, &metadata).map_err(|e| e.to_string())?;
    if let Some(path) = &args.stats {
        super::write_json(path, &stats_json(&layer, seconds))?;
    }
    if !args.options.quiet {
        eprintln!("wrote {}", summary(&layer, seconds));
        eprintln!("data: {}", args.output.display());
    }
    Ok(())
}

/// What `--data-only` needs beyond what clap checks: data channels to write, an EXR to hold
/// them, and no sample count (there is one ray a pixel).
fn check(args: &Args, scene: &Scene) -> Result<(), String> {
    if !scene.settings.has_data_channels() {
        return Err("--data-only writes the data channels, and the scene asks for none: \
                    set [render] channels (e.g. [\"redshift\", \"fate\"]) or spectrum"
            .into());
    }
    if args.options.spp.is_some() {
        return Err("--spp does not apply to --data-only, which traces one ray through each pixel's centre".into());
    }
    super::check_channels(args, scene)?;
    super::check_path(&args.output, "output", true)?;
    args.stats.as_deref().map_or(Ok(()), super::check_stats_path)
}

fn stats_json(layer: &DataLayer, seconds: f64) -> serde_json::Value {
    let counts = layer.fate_counts();
    let fates: serde_json::Map<String, serde_json::Value> =
        FirstMet::ALL.iter().map(|&fate| (fate.name().to_owned(), counts[fate as usize].into())).collect();
    serde_json::json!({
        "rays": layer.pixels.len(),
        "seconds": seconds,
        "width": layer.width,
        "height": layer.height,
        "fates": fates,
    })
}

/// One line: the size, the time, the rays a second, and what the rays met.
fn summary(layer: &DataLayer, seconds: f64) -> String {
    let counts = layer.fate_counts();
    let fates: Vec<String> = FirstMet::ALL
        .iter()
        .map(|&fate| format!("{} {}", fate.name().replace('_', " "), counts[fate as usize]))
        .collect();
    format!(
        "data channels of {}×{} in {seconds:.2} s ({:.0} rays/s); rays met: {}",
        layer.width,
        layer.height,
        layer.pixels.len() as f64 / seconds.max(1e-9),
        fates.join(", ")
    )
}

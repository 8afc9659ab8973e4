//! `nullpath merge`: put the parts of a split render (`nullpath render --part I/N`) together.
//! Each part holds the exact sums of its own tiles, so the merged image is bit for bit the one a
//! single render makes, whatever machines and thread counts rendered the parts.

use super::files::Files;
use super::provenance;
use clap::Parser;
use render::film::{read_checkpoint, write_image, Checkpoint, Film};
use render::renderer::Part;
use std::path::{Path, PathBuf};

#[derive(Parser, Debug)]
pub struct Args {
    /// The part files (.exr), all N parts of one render, in any order.
    #[arg(required = true)]
    parts: Vec<PathBuf>,
    /// The image: .png (8-bit sRGB, tone mapped as the scene says), .exr or .hdr (linear).
    #[arg(short, long)]
    output: PathBuf,
    /// No summary.
    #[arg(long)]
    quiet: bool,
}

/// A part file and which part it is.
struct PartFile {
    path: PathBuf,
    part: Part,
    checkpoint: Checkpoint,
}

fn read_part(path: &Path) -> Result<PartFile, String> {
    let checkpoint = read_checkpoint(path).map_err(|e| e.to_string())?;
    let part = checkpoint
        .metadata
        .get("part")
        .ok_or_else(|| format!("{}: records no part", path.display()))
        .and_then(|p| Part::parse(p).map_err(|e| format!("{}: {e}", path.display())))?;
    let finished = checkpoint.metadata.get("stats").and_then(|s| serde_json::from_str::<serde_json::Value>(s).ok());
    if finished.is_none_or(|s| s["complete"] != serde_json::Value::Bool(true)) {
        return Err(format!(
            "{}: part {part} is unfinished; continue it with `nullpath render ... --part {part} --resume {}`",
            path.display(),
            path.display()
        ));
    }
    Ok(PartFile { path: path.to_owned(), part, checkpoint })
}

/// Refuses parts `a` and `b` of one render made to different numbers of samples per pixel: their
/// tiles would be of different noise, and the image's metadata could record only one of them.
/// The settings' hash leaves the sample count out, since a checkpoint may be continued to more.
/// The goal is compared, not the samples reached: a part may hold no tiles (7 parts of a small
/// image), and so no samples.
fn check_same_samples(a: &PartFile, b: &PartFile) -> Result<(), String> {
    let goal = |p: &PartFile| p.checkpoint.metadata.get("spp.goal").cloned().unwrap_or_else(|| "?".into());
    if goal(a) == goal(b) {
        return Ok(());
    }
    let (fewer, more) = match (goal(a).parse::<u32>(), goal(b).parse::<u32>()) {
        (Ok(x), Ok(y)) if y < x => (b, a),
        _ => (a, b),
    };
    Err(format!(
        "{} (part {}) has {} samples per pixel but {} (part {}) has {}: the parts of one image must have \
         the same; continue the one with fewer: nullpath render ... --part {} --spp {} --resume {} -o {}",
        a.path.display(),
        a.part,
        goal(a),
        b.path.display(),
        b.part,
        goal(b),
        fewer.part,
        goal(more),
        fewer.path.display(),
        fewer.path.display()
    ))
}

pub fn run(args: &Args) -> Result<(), String> {
    let mut files = Files::default();
    for part in &args.parts {
        files.reads("the part file", part);
    }
    files.writes("the merged image (-o)", &args.output)?;
    render::film::check_output_path(&args.output).map_err(|e| e.to_string())?;
    let parts: Vec<PartFile> = args.parts.iter().map(|p| read_part(p)).collect::<Result<_, _>>()?;
    let first = &parts[0];
    let count = first.part.count();
    let same = |key: &str, p: &PartFile| first.checkpoint.metadata.get(key) == p.checkpoint.metadata.get(key);
    for p in &parts {
        if p.part.count() != count {
            return Err(format!(
                "{} is part {} but {} is part {}",
                p.path.display(),
                p.part,
                first.path.display(),
                first.part
            ));
        }
        if !same("sampling.hash", p) || !same("version", p) {
            return Err(format!(
                "{} and {} are parts of different renders (scene, settings or version differ)",
                first.path.display(),
                p.path.display()
            ));
        }
        check_same_samples(first, p)?;
        let mut same_part = parts.iter().filter(|q| q.part == p.part);
        if let (Some(a), Some(b)) = (same_part.next(), same_part.next()) {
            return Err(format!("{} and {} are both part {}", a.path.display(), b.path.display(), p.part));
        }
    }
    let missing: Vec<String> =
        (1..=count).filter(|&i| !parts.iter().any(|p| p.part.number() == i)).map(|i| format!("{i}/{count}")).collect();
    if !missing.is_empty() {
        return Err(format!("parts {} are missing", missing.join(", ")));
    }

    let (width, height) = (first.checkpoint.film.width(), first.checkpoint.film.height());
    let mut film = Film::try_new(width, height).map_err(|e| e.to_string())?;
    for p in &parts {
        film.copy_tiles(&p.checkpoint.film, &p.part.tiles(width, height));
    }
    let mut metadata = first.checkpoint.metadata.clone();
    metadata.insert("part".into(), Part::WHOLE.to_string());
    // Every part is finished to the one goal, without a noise target (parts take none): every
    // pixel has the goal's samples, whatever the first part (which may hold no tiles) reached.
    if let Some(goal) = metadata.get("spp.goal").cloned() {
        metadata.insert("spp".into(), goal.clone());
        metadata.insert("spp.min".into(), goal);
    }
    metadata
        .insert("merged_from".into(), args.parts.iter().map(|p| p.display().to_string()).collect::<Vec<_>>().join(" "));
    let tonemap = provenance::tonemap(&metadata).map_err(|e| format!("{}: {e}", first.path.display()))?;
    write_image(&film, &args.output, &tonemap, &metadata).map_err(|e| e.to_string())?;
    if !args.quiet {
        eprintln!("merged {count} parts ({width}×{height}) into {}", args.output.display());
    }
    Ok(())
}

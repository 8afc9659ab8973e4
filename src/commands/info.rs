//! `nullpath info`: what made an image or a checkpoint (scene, settings, seed, samples,
//! program version, command), as nullpath wrote it into the file.

use clap::Parser;
use render::film::read_metadata;
use std::path::PathBuf;

#[derive(Parser, Debug)]
pub struct Args {
    /// Images (.png, .exr) or checkpoints written by nullpath.
    #[arg(required = true)]
    images: Vec<PathBuf>,
    /// Print one JSON object per file (keys as below) instead of text.
    #[arg(long)]
    json: bool,
    /// Also print the scene file's text recorded in the image.
    #[arg(long)]
    scene_source: bool,
}

pub fn run(args: &Args) -> Result<(), String> {
    for path in &args.images {
        let mut metadata = read_metadata(path).map_err(|e| e.to_string())?;
        if metadata.is_empty() {
            return Err(format!("{}: holds no nullpath metadata (made by another program?)", path.display()));
        }
        if args.json {
            println!("{}", serde_json::json!({ "file": path.display().to_string(), "metadata": metadata }));
            continue;
        }
        let source = metadata.remove("scene.source");
        println!("{}:", path.display());
        for (key, value) in &metadata {
            println!("  {key}: {value}");
        }
        if let Some(text) = source.filter(|_| args.scene_source) {
            println!("  scene.source:");
            text.lines().for_each(|line| println!("    {line}"));
        }
    }
    Ok(())
}

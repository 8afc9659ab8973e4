//! `nullpath`: render ordinary scenes in curved spacetime, and explore its geodesics.

mod commands;

use clap::{Parser, Subcommand};
use std::process::ExitCode;

#[derive(Parser)]
#[command(name = "nullpath", version, about = "A physically based path tracer for curved spacetime")]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand)]
enum Command {
    /// Render a scene file (or the default scene) to an image.
    Render(commands::render::Args),
    /// Render a scene's camera animation to numbered frames (resumable), optionally as a video.
    Animate(commands::animate::Args),
    /// Trace one ray that comes in from infinity and report its fate and bending angle.
    Geodesic(commands::geodesic::Args),
    /// Measure performance on the standard workloads.
    Bench(commands::bench::Args),
}

fn main() -> ExitCode {
    let cli = Cli::parse();
    let result = match cli.command {
        Command::Render(args) => commands::render::run(&args),
        Command::Animate(args) => commands::animate::run(&args),
        Command::Geodesic(args) => commands::geodesic::run(&args),
        Command::Bench(args) => commands::bench::run(&args),
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(message) => {
            eprintln!("nullpath: error: {message}");
            ExitCode::FAILURE
        }
    }
}

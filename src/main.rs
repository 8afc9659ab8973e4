//! `nullpath`: render ordinary scenes in curved spacetime, and explore its geodesics.

mod commands;
mod panics;

use clap::{Parser, Subcommand};
use commands::Failure;
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
    /// Put the parts of a split render (`render --part I/N`) together into the image.
    Merge(commands::merge::Args),
    /// Print what made an image or checkpoint: scene, settings, seed, samples, version.
    Info(commands::info::Args),
    /// Trace one ray that comes in from infinity and report its fate and bending angle.
    Geodesic(commands::geodesic::Args),
    /// Serve a live, progressively refining preview of a scene on http://127.0.0.1:PORT/.
    Preview(commands::preview::Args),
    /// Measure performance on the standard workloads.
    Bench(commands::bench::Args),
}

fn main() -> ExitCode {
    let cli = Cli::parse();
    // The preview serves pages from threads whose panics never reach `main`: they keep Rust's
    // own report, which a hook that only records would hide.
    if !matches!(cli.command, Command::Preview(_)) {
        quit_on_closed_pipe();
        panics::install();
    }
    ExitCode::from(finish(panics::catching(|| run(cli))))
}

fn run(cli: Cli) -> Result<(), Failure> {
    match cli.command {
        Command::Render(args) => commands::render::run(&args),
        Command::Animate(args) => commands::animate::run(&args),
        Command::Merge(args) => commands::merge::run(&args).map_err(Failure::from),
        Command::Info(args) => commands::info::run(&args).map_err(Failure::from),
        Command::Geodesic(args) => commands::geodesic::run(&args).map_err(Failure::from),
        Command::Preview(args) => commands::preview::run(&args).map_err(Failure::from),
        Command::Bench(args) => commands::bench::run(&args).map_err(Failure::from),
    }
}

/// Tells the user how the command ended, unless it succeeded; the exit status.
fn finish(result: Result<(), Failure>) -> u8 {
    match result {
        Ok(()) => 0,
        Err(Failure { message, code, is_error: true }) => {
            eprintln!("nullpath: error: {message}");
            code
        }
        Err(Failure { message, code, is_error: false }) => {
            eprintln!("nullpath: {message}");
            code
        }
    }
}

/// A closed pipe (`nullpath info image.png | head`) ends the process quietly with status 141, as
/// it ends other command-line tools, instead of making `println!` panic (Rust ignores SIGPIPE).
/// Not for the preview, whose server must outlive browsers that hang up.
fn quit_on_closed_pipe() {
    let always = std::sync::Arc::new(std::sync::atomic::AtomicBool::new(true));
    // Should the handler not install, a closed pipe panics as before: nothing worse to report.
    let _ = signal_hook::flag::register_conditional_shutdown(signal_hook::consts::SIGPIPE, 141, always);
}

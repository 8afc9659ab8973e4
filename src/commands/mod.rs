//! One module per subcommand; each exposes `Args` (clap) and `run`, returning a user-facing
//! error message (and exit status) on failure.

pub mod animate;
pub mod bench;
pub mod geodesic;
pub mod info;
mod interrupt;
pub mod merge;
mod provenance;
pub mod render;

/// A command's failure: what to tell the user, and the process's exit status.
#[derive(Debug)]
pub struct Failure {
    pub message: String,
    pub code: u8,
}

impl From<String> for Failure {
    fn from(message: String) -> Self {
        Self { message, code: 1 }
    }
}

//! One module per subcommand; each exposes `Args` (clap) and `run`, returning a user-facing
//! error message (and exit status) on failure.

pub mod animate;
pub mod bench;
mod files;
pub mod geodesic;
pub mod info;
mod interrupt;
pub mod merge;
pub mod preview;
mod provenance;
pub mod render;

/// Why a command did not finish: what to tell the user, and the process's exit status.
#[derive(Debug)]
pub struct Failure {
    pub message: String,
    pub code: u8,
    /// False for a command that stopped as it was asked to (a signal, `--time-limit`) and kept
    /// its work: its message is news, not an error.
    pub is_error: bool,
}

impl Failure {
    /// A command that stopped as asked before it finished, with the exit status saying why.
    pub fn stopped(message: String, code: u8) -> Self {
        Self { message, code, is_error: false }
    }
}

impl From<String> for Failure {
    fn from(message: String) -> Self {
        Self { message, code: 1, is_error: true }
    }
}

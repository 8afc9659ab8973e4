//! One module per subcommand; each exposes `Args` (clap) and `run`, returning a user-facing
//! error message on failure.

pub mod animate;
pub mod bench;
pub mod geodesic;
pub mod render;

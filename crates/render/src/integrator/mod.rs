//! Light transport algorithms. They see the scene only through the [`World`] and the
//! [`Propagator`], so the same code renders flat and curved spacetime.
//!
//! [`World`]: crate::world::World
//! [`Propagator`]: crate::propagator::Propagator

mod light;
mod path;
pub mod photon;
mod stats;

pub use path::PathIntegrator;
pub use stats::{FateCounts, PathStats};

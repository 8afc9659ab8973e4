//! Random numbers and warps. Every sample of every pixel has its own stream, keyed by
//! `(seed, pixel, sample)`, so an image does not depend on which thread rendered what.

mod rng;
mod warp;

pub use rng::Rng;
pub use warp::*;

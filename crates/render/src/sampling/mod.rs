//! Random numbers and warps. Every sample of every pixel has its own numbers, keyed by
//! `(seed, pixel, sample)`, so an image does not depend on which thread rendered what: camera
//! paths draw from a stratified [`Sampler`], everything else from the random stream [`Rng`].

mod piecewise;
mod rng;
mod sampler;
mod warp;

pub use piecewise::PiecewiseConstant2D;
pub use rng::Rng;
pub use sampler::Sampler;
pub use warp::*;

//! nullpath's path tracer, built for curved rays: every query the integrator makes of the scene is a
//! segment (a geodesic step's chord) with a maximum distance, and every material works in the local
//! orthonormal frame of an observer at the hit.
//!
//! The scene (`shape`, `accel`, `material`, `texture`, `sky`, `camera`, `world`) is what rays
//! meet; the `propagator` follows rays through it along the spacetime's geodesics; the light
//! transport of `integrator` sends paths through the propagator; the `renderer` drives an
//! integrator over the `film`. This crate reads no files: the scene crate reads what a scene names
//! and builds a [`scene::Scene`]. ARCHITECTURE.md at the repository's root maps the whole workspace.

pub mod accel;
pub mod camera;
pub mod camera_path;
pub mod crossing;
pub mod digest;
pub mod emission;
pub mod film;
pub mod geometry;
pub mod integrator;
pub mod material;
pub mod medium;
pub mod propagator;
pub mod renderer;
pub mod rgb;
pub mod sampling;
pub mod scene;
pub mod settings;
pub mod shape;
pub mod sky;
pub mod spectrum;
#[cfg(test)]
mod test_scenes;
pub mod texture;
pub mod transform;
pub mod world;

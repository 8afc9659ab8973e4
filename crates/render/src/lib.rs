//! nullpath's path tracer, built for curved rays: every query the integrator makes of the scene is a
//! segment (a geodesic step's chord) with a maximum distance, and every material works in the local
//! orthonormal frame of an observer at the hit.
//!
//! Data flows one way: `geometry` → `shape` → `accel` → `texture`/`material`/`sky` → `sampling` → `film`.

pub mod color;
pub mod geometry;
pub mod sampling;
pub mod shape;
pub mod accel;
pub mod texture;
pub mod material;
pub mod sky;
pub mod film;

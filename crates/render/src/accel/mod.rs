//! Acceleration structures: which primitives a segment may hit, without testing them all.
//!
//! The BVH works on bounding boxes and primitive indices only; the caller intersects primitives
//! in a callback, so the same structure serves shapes, lights or anything else with bounds.

mod bvh;

pub use bvh::Bvh;

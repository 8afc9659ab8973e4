//! Content digests of bulk data (a mesh's vertices, an image's pixels), computed once and shown
//! in place of the data by `Debug`.
//!
//! A render's identity (what decides its samples, recorded in images and checked before a
//! checkpoint is continued) is the `Debug` text of its scene. Bulk data is shared by `Arc`: one
//! mesh by every triangle that refers to it, one image by every material that uses it. Printing
//! the data itself at each reference would make that text quadratic in the mesh (every triangle
//! printing every vertex); printing a digest of it, computed on first use and kept, makes it
//! linear: the data is read once, each reference costs a few bytes.

use std::hash::{DefaultHasher, Hasher};
use std::sync::OnceLock;

/// A 64-bit digest of data that never changes after it is built, computed on first use.
///
/// It is derived data: two digests always compare equal, so that a type holding one keeps the
/// equality its data gives it.
#[derive(Clone, Default)]
pub struct ContentDigest(OnceLock<u64>);

impl ContentDigest {
    /// The digest, computed by `feed` on the first call. `feed` must write the same bytes for
    /// the same content: the digest is cached, so a later change of the data is not seen.
    pub fn get(&self, feed: impl FnOnce(&mut DefaultHasher)) -> u64 {
        *self.0.get_or_init(|| {
            let mut hasher = DefaultHasher::new();
            feed(&mut hasher);
            hasher.finish()
        })
    }
}

impl PartialEq for ContentDigest {
    fn eq(&self, _: &Self) -> bool {
        true
    }
}

/// Shows `digest` as `Debug` does a number: 16 hexadecimal digits.
pub struct Hex(pub u64);

impl std::fmt::Debug for Hex {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "{:016x}", self.0)
    }
}

/// Writes each `f64` of `values` into `hasher` by its bits (so `-0.0` and `0.0` differ, as
/// they may in a render).
pub fn write_f64s(hasher: &mut impl Hasher, values: impl IntoIterator<Item = f64>) {
    for v in values {
        hasher.write_u64(v.to_bits());
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn computed_once_from_the_content() {
        let digest = ContentDigest::default();
        let first = digest.get(|h| write_f64s(h, [1.0, 2.0]));
        // A second feed is not called: the first result is kept.
        let second = digest.get(|_| panic!("the digest is computed once"));
        assert_eq!(first, second);
        let other = ContentDigest::default().get(|h| write_f64s(h, [1.0, 2.5]));
        assert_ne!(first, other, "different content, different digest");
    }
}

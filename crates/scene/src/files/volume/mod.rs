//! Volume files: 3-D grids of samples (a medium's density, a temperature) for
//! [`render::medium::grid::Grid`], in two formats (docs/media.md):
//!
//! - [`npy`]: NumPy's `.npy` (format versions 1–3), a 3-D array of `float32` or `float64` in
//!   either byte order, C or Fortran order, indexed `[x, y, z]`;
//! - [`raw`]: headerless little-endian `float32`, `x` fastest, whose dimensions the scene file
//!   gives.
//!
//! Both are read under the scene's [`ReadPolicy`](super::ReadPolicy), and both know the file's
//! size from what it declares (the `.npy` header, the scene's dimensions) before its data is
//! read: a file shorter or longer than declared is refused, so no header can make nullpath
//! allocate more than the file holds or read past a lie. Samples must be finite and not
//! negative. OpenVDB and NanoVDB are not read: see docs/media.md.

pub mod npy;
pub mod raw;

use super::policy::{ReadError, Resource, MAX_FILE_BYTES};
use std::fmt;
use std::path::PathBuf;

/// A grid of samples, `x` fastest: sample `(i, j, k)` is `values[i + nx (j + ny k)]`.
#[derive(Clone, Debug, PartialEq)]
pub struct Volume {
    pub dims: [usize; 3],
    pub values: Vec<f32>,
}

/// Why a volume file could not be read; its `Display` names the file as the scene wrote it.
#[derive(Debug)]
pub struct VolumeError {
    pub path: PathBuf,
    pub kind: VolumeErrorKind,
}

/// The reason inside a [`VolumeError`].
#[derive(Debug)]
pub enum VolumeErrorKind {
    /// The file may not be read (see [`super::policy`]) or could not be.
    Read(ReadError),
    /// Shorter than its header or dimensions declare.
    Truncated { size: u64, needed: u64 },
    /// Longer than its header or dimensions declare.
    Oversized { needed: u64 },
    /// Dimensions that are 0 or whose samples would not fit in one file nullpath reads.
    Dimensions { dims: [u64; 3], why: &'static str },
    /// Not a well-formed `.npy` header, or one that is not a 3-D float array.
    Header(String),
    /// A sample that is NaN, infinite or negative, at its `(x, y, z)`.
    Sample { at: [usize; 3], value: f64 },
}

impl fmt::Display for VolumeError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "cannot read volume '{}': ", self.path.display())?;
        match &self.kind {
            VolumeErrorKind::Read(e) => write!(f, "{e}"),
            VolumeErrorKind::Truncated { size, needed } => {
                write!(f, "it holds {size} bytes, fewer than the {needed} its dimensions declare (truncated?)")
            }
            VolumeErrorKind::Oversized { needed } => {
                write!(f, "it holds more than the {needed} bytes its dimensions declare (wrong dimensions?)")
            }
            VolumeErrorKind::Dimensions { dims, why } => write!(f, "dimensions {dims:?}: {why}"),
            VolumeErrorKind::Header(why) => write!(f, "not a 3-D float32/float64 .npy array: {why}"),
            VolumeErrorKind::Sample { at, value } => {
                write!(
                    f,
                    "sample {at:?} is {value}, and samples must be finite, not negative and within float32's range"
                )
            }
        }
    }
}

impl std::error::Error for VolumeError {
    fn source(&self) -> Option<&(dyn std::error::Error + 'static)> {
        match &self.kind {
            VolumeErrorKind::Read(e) => Some(e),
            VolumeErrorKind::Truncated { .. }
            | VolumeErrorKind::Oversized { .. }
            | VolumeErrorKind::Dimensions { .. }
            | VolumeErrorKind::Header(_)
            | VolumeErrorKind::Sample { .. } => None,
        }
    }
}

impl VolumeErrorKind {
    fn at(self, file: &Resource<'_>) -> VolumeError {
        VolumeError { path: file.written().to_path_buf(), kind: self }
    }
}

/// The number of samples of `dims`, and the bytes they take at `item` bytes each after `offset`
/// bytes of header: refused if a dimension is 0 or the file would exceed [`MAX_FILE_BYTES`].
fn sizes(dims: [u64; 3], item: u64, offset: u64) -> Result<(usize, u64), VolumeErrorKind> {
    if dims.contains(&0) {
        return Err(VolumeErrorKind::Dimensions { dims, why: "a dimension is 0" });
    }
    let too_large = VolumeErrorKind::Dimensions { dims, why: "more samples than nullpath reads from one file" };
    let count = dims.iter().try_fold(1u64, |n, &d| n.checked_mul(d));
    let bytes = count.and_then(|n| n.checked_mul(item)).and_then(|b| b.checked_add(offset));
    match (count.and_then(|n| usize::try_from(n).ok()), bytes) {
        (Some(count), Some(bytes)) if bytes <= MAX_FILE_BYTES => Ok((count, bytes)),
        _ => Err(too_large),
    }
}

/// The whole file, which must hold exactly `needed` bytes. The policy refuses a file shorter
/// than asked from its size, before reading it: asking first for one byte more than declared
/// tells a file of the right size (refused as one byte short, unread) from a longer one, and
/// reads no more than `needed + 1` bytes of a file that lies.
fn read_exactly(file: &Resource<'_>, needed: u64) -> Result<Vec<u8>, VolumeErrorKind> {
    match file.read_prefix(needed + 1) {
        Ok(_) => Err(VolumeErrorKind::Oversized { needed }),
        Err(ReadError::TooShort { size, .. }) if size == needed => {
            file.read_prefix(needed).map_err(VolumeErrorKind::Read)
        }
        Err(ReadError::TooShort { size, .. }) => Err(VolumeErrorKind::Truncated { size, needed }),
        Err(e) => Err(VolumeErrorKind::Read(e)),
    }
}

impl Volume {
    /// The samples `values` (`x` fastest), checked finite and not negative; `as_read(n, v)` is
    /// sample `n` (of value `v`) as the file held it, for the message.
    fn checked(
        dims: [usize; 3],
        values: Vec<f32>,
        as_read: impl Fn(usize, f32) -> f64,
    ) -> Result<Self, VolumeErrorKind> {
        if let Some(n) = values.iter().position(|v| !(v.is_finite() && *v >= 0.0)) {
            let at = [n % dims[0], (n / dims[0]) % dims[1], n / (dims[0] * dims[1])];
            return Err(VolumeErrorKind::Sample { at, value: as_read(n, values[n]) });
        }
        Ok(Self { dims, values })
    }
}

#[cfg(test)]
pub(crate) mod test_files {
    use std::path::PathBuf;

    /// A fresh folder for one test's files.
    pub fn folder(name: &str) -> PathBuf {
        let dir = std::env::temp_dir().join(format!("nullpath-volume-{}-{name}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(&dir).expect("a temporary folder");
        dir
    }
}

//! The raw volume format: nothing but the samples, little-endian IEEE 754 `float32`, `x` fastest
//! (sample `(i, j, k)` at byte `4 (i + nx (j + ny k))`), `nx·ny·nz·4` bytes in all. The scene file
//! gives the dimensions (and where the box lies), so the file's size is known before it is
//! read. NumPy writes one from an array `a` indexed `[x, y, z]` as `a.T.astype('<f4').tofile(path)`
//! (`tofile` writes in C order, and `a.T`, indexed `[z, y, x]`, has `x` last).

use super::{read_exactly, sizes, Volume, VolumeError, VolumeErrorKind};
use crate::files::policy::Resource;

/// Reads the raw volume `file` of dimensions `dims` (`[nx, ny, nz]`).
pub fn load_raw(file: &Resource<'_>, dims: [u64; 3]) -> Result<Volume, VolumeError> {
    read(file, dims).map_err(|kind| kind.at(file))
}

fn read(file: &Resource<'_>, dims: [u64; 3]) -> Result<Volume, VolumeErrorKind> {
    let (count, bytes) = sizes(dims, 4, 0)?;
    let data = read_exactly(file, bytes)?;
    let values: Vec<f32> = data.chunks_exact(4).map(|b| f32::from_le_bytes([b[0], b[1], b[2], b[3]])).collect();
    debug_assert_eq!(values.len(), count);
    // `sizes` has checked that the product of the dimensions fits in a `usize`.
    Volume::checked(dims.map(|d| d as usize), values, |_, v| f64::from(v))
}

#[cfg(test)]
mod tests {
    use super::super::test_files::folder;
    use super::*;
    use crate::files::policy::ReadPolicy;

    fn raw_bytes(values: &[f32]) -> Vec<u8> {
        values.iter().flat_map(|v| v.to_le_bytes()).collect()
    }

    #[test]
    fn reads_samples_x_fastest() {
        let dir = folder("raw-read");
        let values: Vec<f32> = (0..24).map(|n| n as f32 * 0.5).collect();
        std::fs::write(dir.join("v.raw"), raw_bytes(&values)).unwrap();
        let policy = ReadPolicy::new(&dir);
        let volume = load_raw(&policy.file(&dir, "v.raw"), [2, 3, 4]).unwrap();
        assert_eq!(volume, Volume { dims: [2, 3, 4], values });
        std::fs::remove_dir_all(&dir).ok();
    }

    #[test]
    fn refuses_files_of_the_wrong_size_naming_them() {
        let dir = folder("raw-size");
        std::fs::write(dir.join("v.raw"), raw_bytes(&[1.0; 24])).unwrap();
        let policy = ReadPolicy::new(&dir);
        let file = policy.file(&dir, "v.raw");
        let short = load_raw(&file, [2, 3, 5]).unwrap_err();
        assert!(matches!(short.kind, VolumeErrorKind::Truncated { size: 96, needed: 120 }), "{short:?}");
        assert!(short.to_string().contains("'v.raw'"), "{short}");
        let long = load_raw(&file, [2, 3, 3]).unwrap_err();
        assert!(matches!(long.kind, VolumeErrorKind::Oversized { needed: 72 }), "{long:?}");
        assert!(long.to_string().contains("'v.raw'") && long.to_string().contains("wrong dimensions"), "{long}");
        let huge = load_raw(&file, [1 << 40, 1 << 40, 1 << 40]).unwrap_err();
        assert!(matches!(huge.kind, VolumeErrorKind::Dimensions { .. }), "{huge:?}");
        let empty = load_raw(&file, [0, 3, 8]).unwrap_err();
        assert!(matches!(empty.kind, VolumeErrorKind::Dimensions { .. }), "{empty:?}");
        let outside = load_raw(&policy.file(&dir, "../elsewhere.raw"), [1, 1, 1]).unwrap_err();
        assert!(matches!(outside.kind, VolumeErrorKind::Read(_)), "{outside:?}");
        std::fs::remove_dir_all(&dir).ok();
    }

    #[test]
    fn refuses_negative_and_nan_samples_at_their_place() {
        let dir = folder("raw-samples");
        let mut values = vec![1.0f32; 24];
        values[1 + 2 * (1 + 3 * 2)] = f32::NAN;
        std::fs::write(dir.join("v.raw"), raw_bytes(&values)).unwrap();
        let policy = ReadPolicy::new(&dir);
        let e = load_raw(&policy.file(&dir, "v.raw"), [2, 3, 4]).unwrap_err();
        assert!(matches!(e.kind, VolumeErrorKind::Sample { at: [1, 1, 2], .. }), "{e:?}");
        std::fs::remove_dir_all(&dir).ok();
    }
}

//! Helpers shared by the integration tests.

#![allow(dead_code)]

use std::path::{Path, PathBuf};

/// The repository's `scenes/` directory.
pub fn scenes_dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../../scenes")
}

/// A fresh, empty directory for one test.
pub fn temp_dir(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("nullpath-scene-test-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).expect("create temp dir");
    dir
}

/// A 2×1 RGB PNG: an orange pixel (255, 128, 0) and a blue one (0, 0, 255).
pub const TINY_PNG: [u8; 72] = [
    137, 80, 78, 71, 13, 10, 26, 10, 0, 0, 0, 13, 73, 72, 68, 82, 0, 0, 0, 2, 0, 0, 0, 1, 8, 2, 0, 0, 0, 123, 64, 232,
    221, 0, 0, 0, 15, 73, 68, 65, 84, 120, 156, 99, 248, 223, 192, 192, 192, 240, 31, 0, 9, 128, 2, 127, 23, 129, 201,
    75, 0, 0, 0, 0, 73, 69, 78, 68, 174, 66, 96, 130,
];

/// A minimal valid scene body: a camera and nothing else.
pub const CAMERA: &str = "[camera]\nposition = [0, 0, 5]\nlook_at = [0, 0, 0]\nfov = 40\n";

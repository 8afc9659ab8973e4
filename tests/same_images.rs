//! Two directories of EXR renders hold the same pixels, to the bit: run by `scripts/same-images.sh`,
//! which renders every bundled scene from every view with a build of an earlier commit and with
//! this one, so that a restructuring that should change nothing is shown to change nothing.

#![allow(clippy::unwrap_used)] // A panic is a failed test.

use exr::prelude::{read_all_flat_layers_from_file, AnyChannel, FlatSamples};
use std::path::{Path, PathBuf};

/// Each channel of the image's first layer: its name and its samples' bits.
fn channels(path: &Path) -> Vec<(String, Vec<u32>)> {
    let image = read_all_flat_layers_from_file(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    let bits = |c: &AnyChannel<FlatSamples>| {
        (c.name.to_string(), c.sample_data.values_as_f32().map(f32::to_bits).collect::<Vec<u32>>())
    };
    image.layer_data[0].channel_data.list.iter().map(bits).collect()
}

fn exr_files(dir: &Path) -> Vec<PathBuf> {
    let mut files: Vec<PathBuf> = std::fs::read_dir(dir)
        .unwrap_or_else(|e| panic!("{}: {e}", dir.display()))
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|e| e == "exr"))
        .collect();
    files.sort();
    files
}

/// `NULLPATH_SAME_IMAGES=BEFORE:AFTER`: every EXR of BEFORE is in AFTER with the same pixels.
#[test]
#[ignore = "compares two directories of renders; run by scripts/same-images.sh"]
fn renders_are_bit_identical() {
    let dirs = std::env::var("NULLPATH_SAME_IMAGES").expect("NULLPATH_SAME_IMAGES=BEFORE:AFTER");
    let (before, after) = dirs.split_once(':').expect("NULLPATH_SAME_IMAGES=BEFORE:AFTER");
    let (before, after) = (Path::new(before), Path::new(after));
    let files = exr_files(before);
    assert!(!files.is_empty(), "no renders in {}", before.display());
    let names = |files: &[PathBuf]| files.iter().map(|p| p.file_name().unwrap().to_owned()).collect::<Vec<_>>();
    assert_eq!(names(&files), names(&exr_files(after)), "the two directories hold different renders");
    let differing: Vec<String> = files
        .iter()
        .filter(|file| channels(file) != channels(&after.join(file.file_name().unwrap())))
        .map(|file| file.file_name().unwrap().to_string_lossy().into_owned())
        .collect();
    assert!(differing.is_empty(), "these renders differ: {differing:?}");
    eprintln!("{} renders bit-identical", files.len());
}

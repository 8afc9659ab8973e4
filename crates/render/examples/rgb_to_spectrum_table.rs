//! Writes the RGB → spectrum table that nullpath ships, optimised afresh, over the shipped file:
//!
//! ```sh
//! cargo run --release -p nullpath-render --example rgb_to_spectrum_table
//! ```
//!
//! Run it after changing the fit (crates/render/src/spectrum/fit.rs, the CIE or D65 data): the test
//! `shipped_table_is_the_optimised_one` fails until then.

use render::spectrum::RgbToSpectrumTable;
use std::path::Path;
use std::process::ExitCode;

fn main() -> ExitCode {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("src/spectrum/srgb_to_spectrum_32.bin");
    let table = RgbToSpectrumTable::optimise(RgbToSpectrumTable::DEFAULT_RESOLUTION);
    match std::fs::write(&path, table.to_le_bytes()) {
        Ok(()) => {
            println!("wrote {}", path.display());
            ExitCode::SUCCESS
        }
        Err(e) => {
            eprintln!("{}: {e}", path.display());
            ExitCode::FAILURE
        }
    }
}

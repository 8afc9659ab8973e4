//! The Python module `nullpath._nullpath`, re-exported by the `nullpath` package
//! (python/nullpath/__init__.py), whose stubs (`_nullpath.pyi`) document every item.

use pyo3::prelude::*;

// --- spacetimes and geodesics (pygeo) ---
mod geodesic;
mod spacetime;
// --- end spacetimes and geodesics ---

/// The extension module.
#[pymodule]
fn _nullpath(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    // --- spacetimes and geodesics (pygeo) ---
    m.add_class::<spacetime::PySpacetime>()?;
    m.add("SpacetimeError", m.py().get_type::<spacetime::SpacetimeError>())?;
    m.add_function(wrap_pyfunction!(spacetime::spacetimes, m)?)?;
    m.add_function(wrap_pyfunction!(geodesic::geodesic, m)?)?;
    m.add_function(wrap_pyfunction!(geodesic::geodesics, m)?)?;
    m.add_function(wrap_pyfunction!(geodesic::deflections, m)?)?;
    m.add("FATES", geodesic::FATES)?;
    // --- end spacetimes and geodesics ---
    Ok(())
}

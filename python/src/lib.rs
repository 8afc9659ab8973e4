//! The Python module `nullpath._nullpath`, re-exported by the `nullpath` package
//! (python/nullpath/__init__.py), whose stubs (`_nullpath.pyi`) document every item.

use pyo3::prelude::*;

/// The extension module.
#[pymodule]
fn _nullpath(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    Ok(())
}

//! The Python module `nullpath._nullpath`, re-exported by the `nullpath` package
//! (python/nullpath/__init__.py), whose stubs (`_nullpath.pyi`) document every item.

use pyo3::prelude::*;

// Scene API and rendering (issue 42, pyscene).
mod exr_file;
mod render;
mod scene;

/// The extension module.
#[pymodule]
fn _nullpath(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    // Scene API and rendering (issue 42, pyscene).
    m.add_class::<scene::Scene>()?;
    m.add_class::<scene::SceneTable>()?;
    m.add_class::<render::RenderResult>()?;
    m.add("SceneError", m.py().get_type::<scene::SceneError>())?;
    m.add_function(wrap_pyfunction!(exr_file::read_exr, m)?)?;
    Ok(())
}

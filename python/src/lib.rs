//! The Python module `nullpath._nullpath`, re-exported by the `nullpath` package
//! (python/nullpath/__init__.py), whose stubs (`_nullpath.pyi`) document every item.
//!
//! Scenes and their renders: `scene` (the `Scene` class, its TOML text the source of truth),
//! `render` (the render of `nullpath render`, driven from Python), `exr_file` (`read_exr`).
//! Spacetimes and photons: `spacetime` (`Spacetime` from the metric registry or a `[spacetime]`
//! table), `geodesic` (one trajectory, many fates in parallel, scattering angles).

use pyo3::prelude::*;

mod exr_file;
mod geodesic;
mod render;
mod scene;
mod spacetime;

/// The extension module.
#[pymodule]
fn _nullpath(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    m.add_class::<scene::Scene>()?;
    m.add_class::<scene::SceneTable>()?;
    m.add_class::<render::RenderResult>()?;
    m.add("SceneError", m.py().get_type::<scene::SceneError>())?;
    m.add_function(wrap_pyfunction!(exr_file::read_exr, m)?)?;
    m.add_class::<spacetime::PySpacetime>()?;
    m.add("SpacetimeError", m.py().get_type::<spacetime::SpacetimeError>())?;
    m.add_function(wrap_pyfunction!(spacetime::spacetimes, m)?)?;
    m.add_function(wrap_pyfunction!(geodesic::geodesic, m)?)?;
    m.add_function(wrap_pyfunction!(geodesic::geodesics, m)?)?;
    m.add_function(wrap_pyfunction!(geodesic::deflections, m)?)?;
    m.add("FATES", geodesic::FATES)?;
    Ok(())
}

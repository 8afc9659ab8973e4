//! `nullpath.Spacetime` and `nullpath.spacetimes()`: every built-in metric by its scene-file name
//! and parameters, from the physics crate's registry of descriptors (names, defaults and the
//! validating constructor), and metrics written as expressions, read by the scene reader's
//! `[spacetime]` so that its checks and messages are the scene files'.

use pyo3::create_exception;
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList};
use pythonize::depythonize;
use spacetime::metric::{find, MetricDescriptor, NamedValuesError, ParameterDescriptor, ParameterError, SPACETIMES};
use spacetime::Spacetime;

create_exception!(
    nullpath,
    SpacetimeError,
    PyValueError,
    "A spacetime's parameter, or a photon's start, is outside what it may be. A `ValueError`; \
     `parameter` names the parameter at fault (`None` when the fault is no one parameter's)."
);

/// A `SpacetimeError` whose `parameter` attribute is `parameter`.
pub fn error(py: Python<'_>, parameter: Option<&str>, message: impl Into<String>) -> PyErr {
    let err = SpacetimeError::new_err(message.into());
    if let Err(e) = err.value(py).setattr("parameter", parameter) {
        return e;
    }
    err
}

/// A constructor's error, named as `nullpath.Spacetime`'s keywords name it.
fn parameter_error(py: Python<'_>, d: &MetricDescriptor, e: &ParameterError) -> PyErr {
    let parameter = (!e.parameter.is_empty()).then_some(e.parameter);
    error(py, parameter, format!("{} spacetime: {e}", d.name))
}

/// A spacetime: one of the built-in metrics with its parameters, or a metric written as
/// expressions.
///
/// ``Spacetime("kerr", mass=1.0, spin=0.9)`` builds the built-in metric of that scene-file
/// ``type`` (``nullpath.spacetimes()`` lists them). A parameter left out takes the value
/// ``nullpath geodesic`` takes (mass and throat radius 1, spin and charge 0), else the scene
/// files' default; every value is checked by the metric's constructor, and a bad one raises
/// ``SpacetimeError`` (a ``ValueError``) naming it. A spinning hole's axis is z.
#[pyclass(name = "Spacetime", module = "nullpath", frozen, eq)]
#[derive(Clone, Debug, PartialEq)]
pub struct PySpacetime {
    pub inner: Spacetime,
}

#[pymethods]
impl PySpacetime {
    #[new]
    #[pyo3(signature = (name, **parameters))]
    fn new(py: Python<'_>, name: &str, parameters: Option<&Bound<'_, PyDict>>) -> PyResult<Self> {
        let Some(d) = find(name) else {
            let names: Vec<&str> = SPACETIMES.iter().map(|d| d.name).collect();
            return Err(error(
                py,
                None,
                format!(
                    "unknown spacetime \"{name}\"; expected one of {} (or Spacetime.from_dict for a written metric)",
                    names.join(", ")
                ),
            ));
        };
        let mut given: Vec<(String, f64)> = Vec::new();
        for (key, value) in parameters.into_iter().flat_map(|p| p.iter()) {
            let key: String = key.extract()?;
            let value: f64 = value
                .extract()
                .map_err(|_| error(py, Some(&key), format!("{} spacetime: {key}: must be a number", d.name)))?;
            given.push((key, value));
        }
        let given: Vec<(&str, f64)> = given.iter().map(|(k, v)| (k.as_str(), *v)).collect();
        let inner = d.build_named(&given, |p| p.command_line_default.or(p.default)).map_err(|e| match e {
            NamedValuesError::Unknown(key) => {
                let names: Vec<&str> = d.parameters.iter().map(|p| p.name).collect();
                let has = if names.is_empty() { "none".to_string() } else { names.join(", ") };
                error(py, Some(&key), format!("{} spacetime has no parameter \"{key}\" (it has: {has})", d.name))
            }
            NamedValuesError::Missing(p) => error(py, Some(p), format!("{} spacetime: {p} is required", d.name)),
            NamedValuesError::Invalid(e) => parameter_error(py, d, &e),
        })?;
        Ok(PySpacetime { inner })
    }

    /// The spacetime of a scene file's ``[spacetime]`` table, read by the scene reader: a
    /// built-in ``type`` with its keys, or ``type = "metric"`` with its components written as
    /// expressions (docs/scene-format.md). Raises ``SpacetimeError`` with the reader's message.
    /// An ``axis`` key is read and checked but not applied: spins here are about z.
    #[staticmethod]
    fn from_toml(py: Python<'_>, text: &str) -> PyResult<Self> {
        let (inner, _axis) = scene::parse_spacetime(text, "<spacetime>").map_err(|e| {
            // The reader names the key as `spacetime.KEY`; the parameter is the key.
            let parameter = e.field().map(|f| f.strip_prefix("spacetime.").unwrap_or(f));
            error(py, parameter, e.to_string())
        })?;
        Ok(PySpacetime { inner })
    }

    /// The spacetime of a ``[spacetime]`` table given as a dict (``{"type": "metric", ...}``),
    /// read as ``from_toml`` reads it.
    #[staticmethod]
    fn from_dict(py: Python<'_>, table: &Bound<'_, PyDict>) -> PyResult<Self> {
        let table: toml::Table = depythonize(table.as_any())
            .map_err(|e| error(py, None, format!("the [spacetime] table cannot be written in TOML: {e}")))?;
        let mut root = toml::Table::new();
        root.insert("spacetime".to_string(), toml::Value::Table(table));
        Self::from_toml(py, &root.to_string())
    }

    /// The scene-file ``type``: a built-in metric's name, or ``"metric"`` for a written one.
    #[getter]
    fn name(&self) -> &'static str {
        self.inner.name()
    }

    /// The parameters and their values, as a dict (empty for a written metric).
    #[getter]
    fn parameters<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let out = PyDict::new(py);
        for p in self.inner.parameters() {
            out.set_item(p.name, p.value)?;
        }
        Ok(out)
    }

    /// The curvature length scale: the mass, or a wormhole's throat radius (1 for flat space).
    #[getter]
    fn length_scale(&self) -> f64 {
        self.inner.length_scale()
    }

    fn __repr__(&self) -> String {
        let parameters: Vec<String> =
            self.inner.parameters().iter().map(|p| format!(", {}={}", p.name, p.value)).collect();
        format!("Spacetime(\"{}\"{})", self.inner.name(), parameters.concat())
    }
}

/// The built-in spacetimes, each a dict: ``name``, ``description``, ``constraint`` (between
/// parameters, or ``None``) and ``parameters``, a list of dicts with ``name``, ``meaning``,
/// ``unit``, ``range`` (``"≥ 0"``, ``"> 0"`` or ``"of either sign"``) and ``default`` (the
/// value ``Spacetime`` takes when it is left out; ``None``: required).
#[pyfunction]
pub fn spacetimes(py: Python<'_>) -> PyResult<Bound<'_, PyList>> {
    let out = PyList::empty(py);
    for d in SPACETIMES {
        let entry = PyDict::new(py);
        entry.set_item("name", d.name)?;
        entry.set_item("description", d.description)?;
        entry.set_item("constraint", d.constraint)?;
        let parameters = PyList::empty(py);
        for p in d.parameters {
            parameters.append(parameter(py, p)?)?;
        }
        entry.set_item("parameters", parameters)?;
        out.append(entry)?;
    }
    Ok(out)
}

fn parameter<'py>(py: Python<'py>, p: &ParameterDescriptor) -> PyResult<Bound<'py, PyDict>> {
    let entry = PyDict::new(py);
    entry.set_item("name", p.name)?;
    entry.set_item("meaning", p.meaning)?;
    entry.set_item("unit", p.unit)?;
    entry.set_item("range", p.range.describe())?;
    entry.set_item("default", p.command_line_default.or(p.default))?;
    Ok(entry)
}

//! `nullpath.Scene`: a scene file held as its TOML text — the source of truth, edited with
//! `scene::edit` (which keeps the author's comments and layout) — and the scene that text builds.
//! Every change rebuilds through the scene crate, so it is checked as the file is, with the same
//! messages, and a refused change leaves the scene as it was.

use crate::render::{render_scene, Progress, RenderResult};
use pyo3::create_exception;
use pyo3::exceptions::{PyKeyError, PyTypeError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList};
use pythonize::{depythonize, pythonize};
use scene::edit::{value, Item};
use std::path::{Path, PathBuf};
use std::sync::Arc;

create_exception!(
    nullpath,
    SceneError,
    PyValueError,
    "A scene that does not load, or a change to one that it refuses. The message is the scene \
     reader's: file, line and column, the field, and why (`scene.toml:4:7: camera.fov: must be in \
     (0, 180) degrees, got 200`)."
);

fn scene_error(error: impl ToString) -> PyErr {
    SceneError::new_err(error.to_string())
}

/// A nullpath scene, read from a TOML file, text or dict, rendered into NumPy arrays.
///
/// The scene's TOML text is the source of truth: `camera`, `spacetime` and `settings` read and
/// write its `[camera]` (or the chosen view's `[views.NAME]`), `[spacetime]` and `[render]`
/// tables, and each change builds the scene again, checked as the file is: an invalid value
/// raises `SceneError` naming the field, and leaves the scene as it was.
#[pyclass(module = "nullpath")]
pub struct Scene {
    /// The scene's TOML text, as written, with the changes made since.
    text: String,
    /// How errors name the scene: its path, `<string>` or `<dict>`.
    origin: String,
    /// The folder the files it names are resolved against and read inside of.
    base_dir: PathBuf,
    /// Further folders it may read files inside of.
    allow_read: Vec<PathBuf>,
    /// The `[views.NAME]` camera it is seen from, if not `[camera]`.
    view: Option<String>,
    /// What `text` builds, from `view`.
    built: Arc<render::scene::Scene>,
}

/// The tables of the document that `Scene` exposes.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Part {
    /// `[camera]`, or the chosen view's `[views.NAME]`.
    Camera,
    Spacetime,
    /// `[render]`.
    Settings,
}

impl Scene {
    fn new(
        text: String,
        origin: String,
        base_dir: PathBuf,
        view: Option<String>,
        allow_read: Vec<PathBuf>,
    ) -> PyResult<Self> {
        let built = build(&text, &origin, &base_dir, view.as_deref(), &allow_read)?;
        Ok(Scene { text, origin, base_dir, allow_read, view, built })
    }

    /// Takes `text` seen from `view` if it builds; else raises and keeps the scene as it was.
    fn replace(&mut self, text: String, view: Option<String>) -> PyResult<()> {
        self.built = build(&text, &self.origin, &self.base_dir, view.as_deref(), &self.allow_read)?;
        self.text = text;
        self.view = view;
        Ok(())
    }

    /// The keys of `part`'s table from the document's root.
    fn keys_of(&self, part: Part) -> Vec<String> {
        match (part, &self.view) {
            (Part::Camera, None) => vec!["camera".into()],
            (Part::Camera, Some(view)) => vec!["views".into(), view.clone()],
            (Part::Spacetime, _) => vec!["spacetime".into()],
            (Part::Settings, _) => vec!["render".into()],
        }
    }

    /// `text` with `fields` of the table at `keys` set (or removed, where `None`).
    fn edited(&self, keys: &[String], fields: Vec<(String, Option<Item>)>) -> PyResult<String> {
        let keys: Vec<&str> = keys.iter().map(String::as_str).collect();
        scene::edit::with_fields(&self.text, &keys, fields).map_err(scene_error)
    }

    /// The document's table at `keys` (empty where it has none).
    fn table(&self, keys: &[String]) -> PyResult<toml::Table> {
        let mut table: toml::Table = toml::from_str(&self.text).map_err(scene_error)?;
        for key in keys {
            table = match table.remove(key) {
                Some(toml::Value::Table(inner)) => inner,
                _ => return Ok(toml::Table::new()),
            };
        }
        Ok(table)
    }

    /// The scene to render: the one built, or with `overrides` of `[render]` built anew.
    fn with_settings(&self, overrides: Vec<(String, Option<Item>)>) -> PyResult<Arc<render::scene::Scene>> {
        if overrides.is_empty() {
            return Ok(Arc::clone(&self.built));
        }
        let text = self.edited(&self.keys_of(Part::Settings), overrides)?;
        build(&text, &self.origin, &self.base_dir, self.view.as_deref(), &self.allow_read)
    }
}

/// Builds `text` as `nullpath render` builds a scene file: files resolved against `base_dir`
/// and read inside it (or `allow_read`), seen from `view`.
fn build(
    text: &str,
    origin: &str,
    base_dir: &Path,
    view: Option<&str>,
    allow_read: &[PathBuf],
) -> PyResult<Arc<render::scene::Scene>> {
    scene::parse_allowing(text, origin, base_dir, view, allow_read).map(Arc::new).map_err(scene_error)
}

/// A Python value as a TOML value of the field `field`.
fn toml_item(field: &str, object: &Bound<'_, PyAny>) -> PyResult<Item> {
    let refuse = |why: String| PyTypeError::new_err(format!("{field}: {why}"));
    let parsed: toml::Value = depythonize(object).map_err(|e| refuse(format!("cannot be written in TOML: {e}")))?;
    // `toml` writes the value inline, which `toml_edit` reads back as an item for the document.
    let inline: scene::edit::Value =
        parsed.to_string().parse().map_err(|e| refuse(format!("cannot be written in TOML: {e}")))?;
    Ok(Item::Value(inline))
}

#[pymethods]
impl Scene {
    /// Reads the scene file at `path`. Files it names resolve against its folder and are read
    /// only inside it, or inside the folders `allow_read`, as `nullpath render` reads them; it is
    /// seen from the view `view` (a `[views.NAME]` camera) when given.
    #[staticmethod]
    #[pyo3(signature = (path, view = None, allow_read = Vec::new()))]
    fn load(path: PathBuf, view: Option<String>, allow_read: Vec<PathBuf>) -> PyResult<Self> {
        let text = scene::read_text(&path).map_err(scene_error)?;
        let base_dir = scene::folder_of(&path).to_owned();
        Scene::new(text, path.display().to_string(), base_dir, view, allow_read)
    }

    /// Builds the scene written in `text` (TOML, as a scene file); files it names resolve
    /// against `base_dir` and are read only inside it (or `allow_read`). Errors name it `<string>`.
    #[staticmethod]
    #[pyo3(signature = (text, base_dir = PathBuf::from("."), view = None, allow_read = Vec::new()))]
    fn from_toml(text: String, base_dir: PathBuf, view: Option<String>, allow_read: Vec<PathBuf>) -> PyResult<Self> {
        Scene::new(text, "<string>".into(), base_dir, view, allow_read)
    }

    /// Builds the scene `document`: a dict as the scene file's TOML would parse (tables as dicts,
    /// arrays as lists). Files it names resolve against `base_dir`. Errors name it `<dict>`, with
    /// the line of the TOML text it is written as (`Scene.toml`).
    #[staticmethod]
    #[pyo3(signature = (document, base_dir = PathBuf::from("."), view = None, allow_read = Vec::new()))]
    fn from_dict(
        document: &Bound<'_, PyAny>,
        base_dir: PathBuf,
        view: Option<String>,
        allow_read: Vec<PathBuf>,
    ) -> PyResult<Self> {
        let table: toml::Table = depythonize(document)
            .map_err(|e| PyTypeError::new_err(format!("the scene cannot be written in TOML: {e}")))?;
        let text = toml::to_string(&table)
            .map_err(|e| PyTypeError::new_err(format!("the scene cannot be written in TOML: {e}")))?;
        Scene::new(text, "<dict>".into(), base_dir, view, allow_read)
    }

    /// The scene's TOML text, with the changes made since it was read.
    #[getter]
    fn toml(&self) -> &str {
        &self.text
    }

    /// The whole document as a dict (as `tomllib` would parse `Scene.toml`).
    fn to_dict<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        Ok(pythonize(py, &self.table(&[])?)?)
    }

    /// The names of the scene's `[views.NAME]` cameras, in file order.
    #[getter]
    fn views(&self) -> Vec<String> {
        scene::view_names(&self.text)
    }

    /// The view the scene is seen (and rendered) from, or None for `[camera]`; setting an
    /// unknown name raises `SceneError`.
    #[getter]
    fn view(&self) -> Option<String> {
        self.view.clone()
    }

    #[setter]
    fn set_view(&mut self, view: Option<String>) -> PyResult<()> {
        self.replace(self.text.clone(), view)
    }

    /// The camera's table: `[camera]`, or `[views.NAME]` when a view is chosen (keys `position`,
    /// `look_at`, `up`, `fov`, `projection`, … as in docs/scene-format.md).
    #[getter]
    fn camera(slf: Py<Self>) -> SceneTable {
        SceneTable { scene: slf, part: Part::Camera }
    }

    /// The `[spacetime]` table: `type` and the metric's parameters (`mass`, `spin`, …). A view's
    /// own `[views.NAME.spacetime]` parameters, where it has them, take precedence when rendered
    /// from it.
    #[getter]
    fn spacetime(slf: Py<Self>) -> SceneTable {
        SceneTable { scene: slf, part: Part::Spacetime }
    }

    /// The `[render]` table: `width`, `height`, `spp`, `seed`, `integrator`, `channels`, …
    #[getter]
    fn settings(slf: Py<Self>) -> SceneTable {
        SceneTable { scene: slf, part: Part::Settings }
    }

    /// Renders the scene as `nullpath render` does, on `threads` threads (default: all cores; the
    /// image does not depend on it), with `width`, `height`, `spp` and `seed` overriding
    /// `[render]`'s (checked as the file's are). The GIL is released while it renders; Ctrl-C
    /// (KeyboardInterrupt) stops it within a sample. `progress`: True shows a tqdm bar where tqdm
    /// is installed, False or None nothing, a callable is called with `(done, total)`.
    #[pyo3(signature = (width = None, height = None, spp = None, seed = None, threads = None, progress = Progress::Bar(true)))]
    #[allow(clippy::too_many_arguments)]
    fn render(
        slf: &Bound<'_, Self>,
        width: Option<i64>,
        height: Option<i64>,
        spp: Option<i64>,
        seed: Option<i64>,
        threads: Option<usize>,
        progress: Progress<'_>,
    ) -> PyResult<RenderResult> {
        let overrides: Vec<(String, Option<Item>)> =
            [("width", width), ("height", height), ("spp", spp), ("seed", seed)]
                .into_iter()
                .filter_map(|(key, given)| given.map(|v| (key.to_owned(), Some(value(v)))))
                .collect();
        // The scene is shared with the render, not borrowed by it: the object stays free to
        // change (from another thread) while the GIL is released.
        let scene = slf.borrow().with_settings(overrides)?;
        render_scene(slf.py(), scene, threads, progress)
    }

    fn __repr__(&self) -> String {
        match &self.view {
            Some(view) => format!("<nullpath.Scene {} from view {view:?}>", self.origin),
            None => format!("<nullpath.Scene {}>", self.origin),
        }
    }
}

/// One table of a `Scene`'s document (`scene.camera`, `scene.spacetime`, `scene.settings`),
/// read and written like a dict. Values are those written in the scene (a key left to its
/// default is absent); setting or deleting a key builds the scene again, and an invalid value
/// raises `SceneError` naming the field, leaving the scene as it was. `update` sets several keys
/// at once, checked together (e.g. a Kerr hole's `mass` and `spin`).
#[pyclass(module = "nullpath")]
pub struct SceneTable {
    scene: Py<Scene>,
    part: Part,
}

impl SceneTable {
    fn read(&self, py: Python<'_>) -> PyResult<toml::Table> {
        let scene = self.scene.borrow(py);
        scene.table(&scene.keys_of(self.part))
    }

    /// Sets (or removes, where `None`) `fields`, all at once.
    fn write(&self, py: Python<'_>, fields: Vec<(String, Option<Item>)>) -> PyResult<()> {
        let mut scene = self.scene.try_borrow_mut(py)?;
        let text = scene.edited(&scene.keys_of(self.part), fields)?;
        let view = scene.view.clone();
        scene.replace(text, view)
    }

    /// The table's name in the document: `camera`, `views.NAME`, `spacetime`, `render`.
    fn name(&self, py: Python<'_>) -> String {
        self.scene.borrow(py).keys_of(self.part).join(".")
    }
}

#[pymethods]
impl SceneTable {
    fn __getitem__<'py>(&self, py: Python<'py>, key: &str) -> PyResult<Bound<'py, PyAny>> {
        match self.read(py)?.get(key) {
            Some(found) => Ok(pythonize(py, found)?),
            None => Err(PyKeyError::new_err(key.to_owned())),
        }
    }

    fn __setitem__(&self, py: Python<'_>, key: String, object: &Bound<'_, PyAny>) -> PyResult<()> {
        let item = toml_item(&format!("{}.{key}", self.name(py)), object)?;
        self.write(py, vec![(key, Some(item))])
    }

    fn __delitem__(&self, py: Python<'_>, key: String) -> PyResult<()> {
        if !self.read(py)?.contains_key(&key) {
            return Err(PyKeyError::new_err(key));
        }
        self.write(py, vec![(key, None)])
    }

    fn __contains__(&self, py: Python<'_>, key: &str) -> PyResult<bool> {
        Ok(self.read(py)?.contains_key(key))
    }

    fn __len__(&self, py: Python<'_>) -> PyResult<usize> {
        Ok(self.read(py)?.len())
    }

    fn __iter__<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        PyList::new(py, self.keys(py)?)?.try_iter().map(Bound::into_any)
    }

    /// The keys written in the table, sorted.
    fn keys(&self, py: Python<'_>) -> PyResult<Vec<String>> {
        Ok(self.read(py)?.keys().cloned().collect())
    }

    /// The `(key, value)` pairs written in the table.
    fn items<'py>(&self, py: Python<'py>) -> PyResult<Vec<(String, Bound<'py, PyAny>)>> {
        self.read(py)?.iter().map(|(k, v)| Ok((k.clone(), pythonize(py, v)?))).collect()
    }

    /// The value of `key`, or `default` where the table has none.
    #[pyo3(signature = (key, default = None))]
    fn get<'py>(&self, py: Python<'py>, key: &str, default: Option<Bound<'py, PyAny>>) -> PyResult<Bound<'py, PyAny>> {
        match self.read(py)?.get(key) {
            Some(found) => Ok(pythonize(py, found)?),
            None => Ok(default.unwrap_or_else(|| py.None().into_bound(py))),
        }
    }

    /// Sets every key of `fields` (a mapping) and of `kwargs` at once: the scene is built once,
    /// with all of them, so values that are valid only together can be set.
    #[pyo3(signature = (fields = None, **kwargs))]
    fn update(
        &self,
        py: Python<'_>,
        fields: Option<&Bound<'_, PyAny>>,
        kwargs: Option<&Bound<'_, PyDict>>,
    ) -> PyResult<()> {
        let name = self.name(py);
        let mut items = Vec::new();
        let mut add = |mapping: &Bound<'_, PyAny>| -> PyResult<()> {
            let dict = PyDict::new(py);
            dict.call_method1("update", (mapping,))?;
            for (key, object) in dict.iter() {
                let key: String = key.extract()?;
                items.push((key.clone(), Some(toml_item(&format!("{name}.{key}"), &object)?)));
            }
            Ok(())
        };
        if let Some(fields) = fields {
            add(fields)?;
        }
        if let Some(kwargs) = kwargs {
            add(kwargs.as_any())?;
        }
        self.write(py, items)
    }

    /// The table as a plain dict.
    fn to_dict<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        Ok(pythonize(py, &self.read(py)?)?)
    }

    fn __repr__(&self, py: Python<'_>) -> PyResult<String> {
        let dict = self.to_dict(py)?;
        Ok(format!("[{}] {}", self.name(py), dict.repr()?))
    }
}

//! `Scene.render`: the render of `nullpath render` (the renderer's progressive render to the
//! scene's samples, the film's linear pixels, the requested data channels and the statistics'
//! JSON, the very library functions the command calls), driven from Python: on a worker thread
//! with the GIL released, while the calling thread reports progress and watches for Ctrl-C.

use numpy::{PyArray1, PyArrayMethods};
use pyo3::exceptions::{PyRuntimeError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::PyDict;
use pythonize::pythonize;
use render::film::{linear_pixels, DataLayer};
use render::renderer::{progressive, requested_data, Goal, Part, Progressive, RenderStats, Unit};
use render::scene::Scene;
use std::sync::atomic::{AtomicBool, AtomicU64, Ordering};
use std::sync::{Arc, Condvar, Mutex};
use std::time::Duration;

/// How often the calling thread looks for Ctrl-C and reports progress: well within the second
/// in which an interrupted render must stop, rarely enough to cost nothing.
const POLL: Duration = Duration::from_millis(50);

/// What `progress=` asks for: a bar (True) or none (False), or a callable (None: none).
#[derive(FromPyObject)]
pub enum Progress<'py> {
    Bar(bool),
    Callback(Bound<'py, PyAny>),
}

/// A finished render, as NumPy arrays and a dict.
#[pyclass(module = "nullpath", frozen)]
pub struct RenderResult {
    /// The image: float32, height × width × 3, linear RGB with the scene's exposure — exactly
    /// the pixels `nullpath render -o image.exr` writes.
    #[pyo3(get)]
    image: Py<PyAny>,
    /// The data channels the scene asks for (`[render] channels` and `spectrum`), by name, each
    /// float32 height × width: what the EXR holds beside the colour. Empty if it asks for none.
    #[pyo3(get)]
    channels: Py<PyDict>,
    /// The statistics, with the fields of `nullpath render --stats`'s JSON.
    #[pyo3(get)]
    stats: Py<PyAny>,
}

#[pymethods]
impl RenderResult {
    fn __repr__(&self, py: Python<'_>) -> PyResult<String> {
        let shape = self.image.bind(py).getattr("shape")?.repr()?;
        let names = self.channels.bind(py).keys().repr()?;
        Ok(format!("<nullpath.RenderResult image {shape}, channels {names}>"))
    }
}

/// Renders `scene` on a pool of `threads` (default: all cores), reporting to `progress`.
pub fn render_scene(
    py: Python<'_>,
    scene: Arc<Scene>,
    threads: Option<usize>,
    progress: Progress<'_>,
) -> PyResult<RenderResult> {
    if threads == Some(0) {
        return Err(PyValueError::new_err("threads must be at least 1"));
    }
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(threads.unwrap_or(0))
        .build()
        .map_err(|e| PyRuntimeError::new_err(format!("cannot start {threads:?} threads: {e}")))?;
    let goal = Goal::spp(scene.settings.spp);
    let renderer = progressive(&scene, Part::WHOLE, goal, None).map_err(|e| PyValueError::new_err(e.to_string()))?;
    let mut reporter = Reporter::new(py, progress, renderer.unit())?;
    let run = Run { scene: &scene, renderer: renderer.as_ref(), pool: &pool, shared: Shared::default() };
    let (stats, data) = run.drive(py, &mut reporter)?;
    let pixels = linear_pixels(&renderer.into_film(), &scene.settings.tonemap);
    result(py, &scene, pixels, data, &stats)
}

/// A render in progress.
struct Run<'a> {
    scene: &'a Scene,
    renderer: &'a dyn Progressive,
    pool: &'a rayon::ThreadPool,
    shared: Shared,
}

/// What the worker and the calling thread share.
#[derive(Default)]
struct Shared {
    cancel: AtomicBool,
    /// The last `(done, total)` the renderer told.
    done: AtomicU64,
    total: AtomicU64,
    finished: Finished,
}

impl Run<'_> {
    /// Renders on a worker until done, reporting progress to `reporter` meanwhile with the GIL
    /// held; on Ctrl-C (or an exception from the progress callback) stops the render, waits for
    /// the worker and raises.
    fn drive(&self, py: Python<'_>, reporter: &mut Reporter<'_>) -> PyResult<(RenderStats, Option<DataLayer>)> {
        let shared = &self.shared;
        std::thread::scope(|scope| {
            let worker = scope.spawn(|| {
                let _wake = WakeOnDrop(&shared.finished);
                self.pool.install(|| {
                    let report = |done, total| {
                        shared.done.store(done, Ordering::Relaxed);
                        shared.total.store(total, Ordering::Relaxed);
                    };
                    let stats = self.renderer.run(&shared.cancel, &report);
                    let data = if stats.is_complete() { requested_data(self.scene) } else { None };
                    (stats, data)
                })
            });
            let watched = self.watch(py, reporter);
            if watched.is_err() {
                shared.cancel.store(true, Ordering::Relaxed);
            }
            let joined = py.detach(move || worker.join());
            let closed = reporter.close();
            watched?;
            closed?;
            joined.map_err(|_| PyRuntimeError::new_err("the render failed (a worker panicked)"))
        })
    }

    /// Waits for the worker, reporting progress and running Python's signal handlers (whose
    /// KeyboardInterrupt it returns) every [`POLL`].
    fn watch(&self, py: Python<'_>, reporter: &mut Reporter<'_>) -> PyResult<()> {
        let shared = &self.shared;
        loop {
            let finished = py.detach(|| shared.finished.wait(POLL));
            reporter.report(shared.done.load(Ordering::Relaxed), shared.total.load(Ordering::Relaxed))?;
            py.check_signals()?;
            if finished {
                return Ok(());
            }
        }
    }
}

/// Set when the worker is done, by [`WakeOnDrop`] (so also when it panics).
#[derive(Default)]
struct Finished {
    done: Mutex<bool>,
    wake: Condvar,
}

impl Finished {
    /// Waits at most `timeout` for the worker; whether it is done.
    fn wait(&self, timeout: Duration) -> bool {
        let done = self.done.lock().unwrap_or_else(|e| e.into_inner());
        let (done, _) = self.wake.wait_timeout_while(done, timeout, |done| !*done).unwrap_or_else(|e| e.into_inner());
        *done
    }
}

struct WakeOnDrop<'a>(&'a Finished);

impl Drop for WakeOnDrop<'_> {
    fn drop(&mut self) {
        *self.0.done.lock().unwrap_or_else(|e| e.into_inner()) = true;
        self.0.wake.notify_all();
    }
}

/// Where progress goes: nowhere, a tqdm bar (made at the first report), or a callable.
enum Reporter<'py> {
    Silent,
    Bar { tqdm: Bound<'py, PyAny>, unit: &'static str, bar: Option<Bound<'py, PyAny>> },
    Callback(Bound<'py, PyAny>),
}

impl<'py> Reporter<'py> {
    /// The reporter `progress` asks for; a bar only where tqdm can be imported.
    fn new(py: Python<'py>, progress: Progress<'py>, unit: Unit) -> PyResult<Self> {
        Ok(match progress {
            Progress::Bar(false) => Reporter::Silent,
            Progress::Callback(callback) if callback.is_none() => Reporter::Silent,
            Progress::Callback(callback) => Reporter::Callback(callback),
            Progress::Bar(true) => match py.import("tqdm.auto") {
                Ok(module) => {
                    let unit = match unit {
                        Unit::SamplesPerPixel => "sample",
                        Unit::Iterations => "iteration",
                    };
                    Reporter::Bar { tqdm: module.getattr("tqdm")?, unit, bar: None }
                }
                Err(_) => Reporter::Silent,
            },
        })
    }

    /// Tells `(done, total)` (nothing before the render knows its total).
    fn report(&mut self, done: u64, total: u64) -> PyResult<()> {
        if total == 0 {
            return Ok(());
        }
        match self {
            Reporter::Silent => {}
            Reporter::Callback(callback) => {
                callback.call1((done, total))?;
            }
            Reporter::Bar { tqdm, unit, bar } => {
                let bar = match bar {
                    Some(bar) => bar,
                    None => {
                        let kwargs = PyDict::new(tqdm.py());
                        kwargs.set_item("total", total)?;
                        kwargs.set_item("unit", *unit)?;
                        kwargs.set_item("unit_scale", true)?;
                        bar.insert(tqdm.call((), Some(&kwargs))?)
                    }
                };
                if bar.getattr("total")?.extract::<u64>()? != total {
                    // A noise target's passes each have their own total.
                    bar.setattr("total", total)?;
                }
                // Told as an update, so that tqdm's rate is that of the samples taken.
                let shown: u64 = bar.getattr("n")?.extract()?;
                bar.call_method1("update", (done.saturating_sub(shown),))?;
            }
        }
        Ok(())
    }

    fn close(&mut self) -> PyResult<()> {
        if let Reporter::Bar { bar: Some(bar), .. } = self {
            bar.call_method0("close")?;
        }
        Ok(())
    }
}

/// The result object of a render of `scene`.
fn result(
    py: Python<'_>,
    scene: &Scene,
    pixels: Vec<[f32; 3]>,
    data: Option<DataLayer>,
    stats: &RenderStats,
) -> PyResult<RenderResult> {
    let (width, height) = (scene.settings.width as usize, scene.settings.height as usize);
    let flat: Vec<f32> = pixels.into_iter().flatten().collect();
    let image = PyArray1::from_vec(py, flat).reshape([height, width, 3])?;
    let channels = PyDict::new(py);
    for (name, samples) in data.iter().flat_map(DataLayer::named_channels) {
        channels.set_item(name, PyArray1::from_vec(py, samples).reshape([height, width])?)?;
    }
    let stats = pythonize(py, &stats.to_json(&scene.settings))?;
    Ok(RenderResult { image: image.into_any().unbind(), channels: channels.unbind(), stats: stats.unbind() })
}

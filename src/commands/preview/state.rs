//! What the server, the refining render and the file watcher share: the scene as the file has
//! it (or why it cannot be loaded), the page's changes, the scene those make, and the latest
//! frame. Every change that alters the picture bumps the generation; a render of an older
//! generation stops and its frames are no longer published.

use super::notices::{enclosure, notices};
use super::parameters::{parameters, Parameter};
use super::view::{Eye, Overrides};
use render::integrator::FateCounts;
use render::renderer::RenderStats;
use render::scene::Scene;
use render::settings::IntegratorKind;
use std::sync::{Arc, Condvar, Mutex, MutexGuard};
use std::time::Duration;

/// A frame as the page fetches it.
#[derive(Clone, Debug)]
pub struct Frame {
    pub png: Arc<Vec<u8>>,
    /// Counts every frame published, so that the page fetches each one once.
    pub version: u64,
    /// The generation it shows.
    pub generation: u64,
    pub width: u32,
    pub height: u32,
    /// Samples per pixel every pixel has.
    pub spp: u32,
    /// The last frame of its generation: refined to the target.
    pub done: bool,
    /// Seconds its render has taken so far (the stage's, from its start).
    pub seconds: f64,
    /// How its camera paths ended.
    pub fates: FateCounts,
}

/// A stage's render as a frame shows it: its statistics, and whether it is the generation's last.
pub struct Stage {
    pub stats: RenderStats,
    pub done: bool,
}

/// A full-quality render started from the page.
#[derive(Clone, Debug, serde::Serialize)]
pub struct RenderJob {
    /// Counts the renders started, so that the page can tell the one it asked for.
    pub id: u64,
    pub output: String,
    /// `"running"`, `"done"` or `"failed"`.
    pub state: &'static str,
    /// Progress from 0 to 1.
    pub progress: f64,
    pub message: String,
}

pub struct Inner {
    pub generation: u64,
    /// The scene file's scene, or its error as the command line prints it.
    pub loaded: Result<Arc<Scene>, String>,
    pub overrides: Overrides,
    /// `loaded` with `overrides`: what the preview renders, or why it cannot.
    pub current: Result<Arc<Scene>, String>,
    pub frame: Option<Frame>,
    /// How many times the file has been read again after a change.
    pub reloads: u64,
    pub job: Option<RenderJob>,
}

pub struct Shared {
    inner: Mutex<Inner>,
    changed: Condvar,
}

impl Inner {
    /// Recomputes `current` and starts a new generation.
    fn touch(&mut self) {
        let current = match &self.loaded {
            Ok(scene) => self.overrides.apply(scene),
            Err(e) => Err(e.clone()),
        };
        self.start(current);
    }

    /// Starts a new generation that renders `current`.
    fn start(&mut self, current: Result<Scene, String>) {
        self.current = current.map(Arc::new);
        self.generation += 1;
    }
}

impl Shared {
    pub fn new(loaded: Result<Scene, String>) -> Self {
        let mut inner = Inner {
            generation: 0,
            loaded: loaded.map(Arc::new),
            overrides: Overrides::default(),
            current: Err(String::new()),
            frame: None,
            reloads: 0,
            job: None,
        };
        inner.touch();
        Self { inner: Mutex::new(inner), changed: Condvar::new() }
    }

    pub fn lock(&self) -> MutexGuard<'_, Inner> {
        self.inner.lock().unwrap_or_else(|e| e.into_inner())
    }

    pub fn generation(&self) -> u64 {
        self.lock().generation
    }

    /// Replaces the file's scene after the file changed; the page's changes stay.
    pub fn reload(&self, loaded: Result<Scene, String>) {
        let mut inner = self.lock();
        inner.loaded = loaded.map(Arc::new);
        inner.reloads += 1;
        inner.touch();
        self.changed.notify_all();
    }

    /// Sets the page's changes made by `change` from the current ones and the file's scene,
    /// unless it fails or the result cannot be rendered (then nothing changes).
    pub fn change(&self, change: impl FnOnce(&Overrides, &Scene) -> Result<Overrides, String>) -> Result<(), String> {
        let mut inner = self.lock();
        let loaded = inner.loaded.clone()?;
        let next = change(&inner.overrides, &loaded)?;
        let current = next.apply(&loaded)?;
        inner.overrides = next;
        inner.start(Ok(current));
        self.changed.notify_all();
        Ok(())
    }

    /// Waits until the generation is not `seen`, then returns it with its scene.
    pub fn next_job(&self, seen: u64) -> (u64, Result<Arc<Scene>, String>, u32) {
        let mut inner = self.lock();
        while inner.generation == seen {
            inner = self.changed.wait_timeout(inner, Duration::from_secs(1)).unwrap_or_else(|e| e.into_inner()).0;
        }
        let spp = match (&inner.current, &inner.loaded) {
            (Ok(_), Ok(loaded)) => inner.overrides.spp(loaded),
            _ => 1,
        };
        (inner.generation, inner.current.clone(), spp)
    }

    /// Publishes a `width × height` frame of generation `generation`, unless a newer one has begun.
    pub fn publish(&self, generation: u64, png: Vec<u8>, (width, height): (u32, u32), stage: Stage) {
        let mut inner = self.lock();
        if inner.generation != generation {
            return;
        }
        let version = inner.frame.as_ref().map_or(1, |f| f.version + 1);
        let Stage { stats, done } = stage;
        inner.frame = Some(Frame {
            png: Arc::new(png),
            version,
            generation,
            width,
            height,
            spp: stats.spp_min,
            done,
            seconds: stats.seconds,
            fates: stats.paths.fates,
        });
    }

    /// The state as the page reads it (`GET /state`).
    pub fn report(&self, scene_name: &str) -> serde_json::Value {
        let inner = self.lock();
        let error = inner.current.as_ref().err();
        let frame = inner.frame.as_ref();
        let (camera, spacetime, sliders, spp, integrator, room, said) = match (&inner.current, &inner.loaded) {
            (Ok(current), Ok(loaded)) => (
                Eye::of(current),
                Some(current.spacetime.name()),
                parameters(&current.spacetime, &loaded.spacetime),
                Some(inner.overrides.spp(loaded)),
                Some(integrator_name(current.settings.integrator)),
                enclosure(loaded).map(|b| serde_json::json!({ "min": b.min.to_array(), "max": b.max.to_array() })),
                notices(current, loaded, frame.filter(|f| f.generation == inner.generation)),
            ),
            _ => (None, None, Vec::<Parameter>::new(), None, None, None, Vec::new()),
        };
        let frame = frame.map(|f| {
            serde_json::json!({ "version": f.version, "generation": f.generation, "width": f.width, "height": f.height,
                "spp": f.spp, "done": f.done, "seconds": f.seconds })
        });
        serde_json::json!({
            "scene": scene_name,
            "generation": inner.generation,
            "reloads": inner.reloads,
            "error": error,
            "spacetime": spacetime,
            "camera": camera,
            "parameters": sliders,
            "spp": spp,
            "max_spp": super::view::MAX_SPP,
            "integrator": integrator,
            "enclosure": room,
            "notices": said,
            "frame": frame,
            "render": inner.job,
        })
    }
}

/// The integrator as scene files name it: the page calls photon mapping's samples iterations.
fn integrator_name(kind: IntegratorKind) -> &'static str {
    match kind {
        IntegratorKind::Path => "path",
        IntegratorKind::BruteForce => "brute-force",
        IntegratorKind::Photon => "photon",
    }
}

//! The two progressive renders the command drives, behind one interface: the path tracer's
//! passes ([`Renderer`]) and photon mapping's iterations ([`PhotonRenderer`]). Both are
//! stopped within a sample (a photon chunk), checkpointed while they run, and continued from a
//! checkpoint bit-identically.

use render::film::{write_checkpoint, Film, Metadata};
use render::integrator::photon::PhotonRenderer;
use render::renderer::{Goal, RenderStats, Renderer};
use std::path::Path;
use std::sync::atomic::AtomicBool;

/// A render in progress.
pub trait Progressive: Sync {
    /// Renders until done or until `cancel` is set; `progress` is told `(done, total)`.
    fn run(&self, cancel: &AtomicBool, progress: &(dyn Fn(u64, u64) + Sync)) -> RenderStats;

    /// Writes a copy of the state as it stands to the checkpoint `path` (the render goes on
    /// meanwhile), with the metadata made from its statistics.
    fn checkpoint(&self, path: &Path, metadata: &dyn Fn(&RenderStats) -> Metadata) -> Result<(), String>;

    /// The film as it stands (the image to write).
    fn snapshot_film(&self) -> Film;
}

/// The path tracer's render to a goal.
pub struct PathRender<'s> {
    pub renderer: Renderer<'s>,
    pub goal: Goal,
}

impl Progressive for PathRender<'_> {
    fn run(&self, cancel: &AtomicBool, progress: &(dyn Fn(u64, u64) + Sync)) -> RenderStats {
        self.renderer.run(self.goal, cancel, progress)
    }

    fn checkpoint(&self, path: &Path, metadata: &dyn Fn(&RenderStats) -> Metadata) -> Result<(), String> {
        let (film, targets, stats) = self.renderer.snapshot();
        write_checkpoint(path, &film, &targets, &metadata(&stats)).map_err(|e| format!("checkpoint: {e}"))
    }

    fn snapshot_film(&self) -> Film {
        self.renderer.snapshot().0
    }
}

impl Progressive for PhotonRenderer<'_> {
    fn run(&self, cancel: &AtomicBool, progress: &(dyn Fn(u64, u64) + Sync)) -> RenderStats {
        PhotonRenderer::run(self, cancel, progress)
    }

    fn checkpoint(&self, path: &Path, metadata: &dyn Fn(&RenderStats) -> Metadata) -> Result<(), String> {
        let (state, stats) = self.snapshot();
        self.write_checkpoint(path, &state, &metadata(&stats)).map_err(|e| format!("checkpoint: {e}"))
    }

    fn snapshot_film(&self) -> Film {
        self.film(&self.snapshot().0)
    }
}

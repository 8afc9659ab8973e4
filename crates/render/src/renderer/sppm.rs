//! Photon mapping behind [`Progressive`]: SPPM iterations ([`crate::integrator::photon`]) run one
//! after another to the goal's count, each over the whole image. The state between iterations,
//! [`SppmState`], is what a snapshot copies and a checkpoint keeps; an iteration is deterministic
//! given the state it starts from, so a render continued from a checkpoint gives the
//! uninterrupted render's image bit for bit. A cancelled iteration is dropped whole.

use super::{propagator, Outcome, Progressive, RenderStats, Unit};
use crate::film::{Film, ImageWriteError, Metadata};
use crate::integrator::photon::{photons_per_iteration, Sppm, SppmState};
use crate::integrator::PathStats;
use crate::propagator::Propagator;
use crate::scene::Scene;
use std::path::Path;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::{Mutex, MutexGuard, OnceLock};
use std::time::{Duration, Instant};

/// Where a continued SPPM render starts: the state of a checkpoint, what it counted, and how
/// long it had run.
pub(super) struct SppmResume {
    pub state: SppmState,
    pub paths: PathStats,
    pub seconds: f64,
}

/// An SPPM render of a whole scene to a number of iterations, from scratch or continuing a
/// checkpoint; its state can be taken from another thread between iterations.
pub(super) struct SppmRender<'s> {
    scene: &'s Scene,
    propagator: Propagator,
    /// Iterations to run (the goal's samples per pixel).
    iterations: u32,
    state: Mutex<(SppmState, PathStats)>,
    /// Seconds of earlier runs that this one continues.
    earlier_seconds: f64,
    started: OnceLock<Instant>,
}

impl<'s> SppmRender<'s> {
    /// A render of `scene` to `iterations` iterations. The caller has checked that the scene's
    /// spacetime is [supported](crate::integrator::photon::supports).
    ///
    /// # Panics
    /// If `resume` is of another size than the scene.
    pub fn new(scene: &'s Scene, iterations: u32, resume: Option<SppmResume>) -> Self {
        let (width, height) = (scene.settings.width, scene.settings.height);
        let (state, paths, earlier_seconds) = match resume {
            Some(r) => {
                assert_eq!((r.state.width(), r.state.height()), (width, height), "the checkpoint is of another size");
                (r.state, r.paths, r.seconds)
            }
            None => (SppmState::new(width, height), PathStats::default(), 0.0),
        };
        Self {
            scene,
            propagator: propagator(scene),
            iterations,
            state: Mutex::new((state, paths)),
            earlier_seconds,
            started: OnceLock::new(),
        }
    }

    fn lock(&self) -> MutexGuard<'_, (SppmState, PathStats)> {
        self.state.lock().unwrap_or_else(|e| e.into_inner())
    }

    /// The image of `state` (see [`SppmState::film`]).
    fn film_of(&self, state: &SppmState) -> Film {
        state.film(photons_per_iteration(self.scene))
    }

    fn stats(&self, (state, paths): &(SppmState, PathStats), elapsed: Duration) -> RenderStats {
        let done = state.iterations();
        let film = self.film_of(state);
        let pixels = u64::from(state.width()) * u64::from(state.height());
        RenderStats {
            paths: *paths,
            samples: u64::from(done) * pixels,
            nan_samples: film.nan_samples() + state.dropped(),
            seconds: self.earlier_seconds + elapsed.as_secs_f64(),
            outcome: if done >= self.iterations { Outcome::Finished } else { Outcome::Interrupted },
            spp_min: done,
            spp_max: done,
            relative_error: None,
        }
    }

    /// A copy of the state after the last finished iteration, and the statistics so far.
    fn snapshot_state(&self) -> (SppmState, RenderStats) {
        let state = self.lock();
        let elapsed = self.started.get().map_or(Duration::ZERO, Instant::elapsed);
        (state.0.clone(), self.stats(&state, elapsed))
    }
}

impl Progressive for SppmRender<'_> {
    /// Iterations until the goal's count is reached or `cancel` is set (an unfinished iteration
    /// is dropped); `progress` is told the iterations done and the iterations asked for.
    fn run(&self, cancel: &AtomicBool, progress: &(dyn Fn(u64, u64) + Sync)) -> RenderStats {
        let start = *self.started.get_or_init(Instant::now);
        let sppm = Sppm::new(self.scene, &self.propagator);
        loop {
            let done = self.lock().0.iterations();
            if done >= self.iterations
                || cancel.load(Ordering::Relaxed)
                || sppm.iteration(&self.state, done, cancel).is_none()
            {
                break;
            }
            progress(u64::from(done) + 1, u64::from(self.iterations));
        }
        self.stats(&self.lock(), start.elapsed())
    }

    fn snapshot(&self) -> (Film, RenderStats) {
        let (state, stats) = self.snapshot_state();
        (self.film_of(&state), stats)
    }

    fn film(&self) -> Film {
        let state = self.lock().0.clone();
        self.film_of(&state)
    }

    /// The state after the last finished iteration (see [`SppmState::write`]), copied under the
    /// lock and written after it is released.
    fn write_checkpoint(
        &self,
        path: &Path,
        metadata: &dyn Fn(&RenderStats) -> Metadata,
    ) -> Result<(), ImageWriteError> {
        let (state, stats) = self.snapshot_state();
        state.write(path, photons_per_iteration(self.scene), &metadata(&stats))
    }

    fn into_film(self: Box<Self>) -> Film {
        let photons = photons_per_iteration(self.scene);
        let (state, _) = self.state.into_inner().unwrap_or_else(|e| e.into_inner());
        state.film(photons)
    }

    fn unit(&self) -> Unit {
        Unit::Iterations
    }
}

//! The path tracer behind [`Progressive`]: renders in passes over the whole image (or a part's
//! tiles), each pass taking every pixel on to its sample target, tiles in parallel. Every sample
//! has its own random stream keyed by (seed, pixel, sample) and each pixel's sums grow one sample
//! at a time in sample order (see [`Film::tile`]), so the image is bit-identical whatever the
//! thread count, however the samples fall into passes, and whether or not the render was stopped
//! and resumed on the way. A render stops within one sample of being cancelled, keeping every
//! finished sample; a snapshot takes a consistent copy of the state at any moment, for
//! checkpoints.
//!
//! With a noise target the passes stop once the film's estimated relative error (see
//! [`crate::film::noise`]) is below it, and in adaptive mode each pass sends samples only where
//! they lower the error most (see `adaptive`).

use super::{adaptive, propagator, Goal, Outcome, Part, Progressive, RenderStats, Unit};
use crate::film::{noise, write_checkpoint, Film, FilmTooLarge, ImageWriteError, Metadata, TileBounds};
use crate::integrator::{PathIntegrator, PathStats};
use crate::propagator::Propagator;
use crate::rgb::Rgb;
use crate::sampling::Sampler;
use crate::scene::Scene;
use rayon::prelude::*;
use std::path::Path;
use std::sync::atomic::{AtomicBool, AtomicU64, Ordering};
use std::sync::{Mutex, OnceLock};
use std::time::{Duration, Instant};

/// A pass is split into rounds of at most this long (once the rounds' size has adapted), so
/// that snapshots and the progress bar stay fresh even when a pass takes hours.
const ROUND: Duration = Duration::from_secs(2);

/// What a render has so far: the film, and each pixel's target in the pass in progress.
struct State {
    film: Film,
    targets: Vec<u32>,
    paths: PathStats,
}

/// A progressive path-tracing render of a scene (or of a part of it) to a goal: see the module
/// docs.
pub(super) struct PathRender<'s> {
    scene: &'s Scene,
    propagator: Propagator,
    goal: Goal,
    /// The tiles of the part this render makes.
    tiles: Vec<TileBounds>,
    state: Mutex<State>,
    /// Seconds of earlier runs that this one continues.
    earlier_seconds: f64,
    /// When [`Progressive::run`] started.
    started: OnceLock<Instant>,
}

/// Where a resumed path-tracing render starts: the film and targets of a snapshot, what it
/// counted, and how long it had run.
pub(super) struct PathResume {
    pub film: Film,
    pub targets: Vec<u32>,
    pub paths: PathStats,
    pub seconds: f64,
}

impl<'s> PathRender<'s> {
    /// A render of `part` of `scene` to `goal`, from scratch or continuing `resume`. Fails when
    /// the film's memory cannot be allocated.
    ///
    /// # Panics
    /// If `resume` does not fit the scene (its film of another size, or not one target a pixel).
    pub fn new(scene: &'s Scene, part: Part, goal: Goal, resume: Option<PathResume>) -> Result<Self, FilmTooLarge> {
        let (width, height) = (scene.settings.width, scene.settings.height);
        let (film, targets, paths, earlier_seconds) = match resume {
            Some(r) => {
                assert_eq!((r.film.width(), r.film.height()), (width, height), "the snapshot is of another size");
                assert_eq!(r.targets.len(), width as usize * height as usize, "one target per pixel");
                (r.film, r.targets, r.paths, r.seconds)
            }
            None => {
                let film = Film::try_new(width, height)?;
                let targets = vec![0; width as usize * height as usize];
                (film, targets, PathStats::default(), 0.0)
            }
        };
        Ok(Self {
            scene,
            propagator: propagator(scene),
            goal,
            tiles: part.tiles(width, height),
            state: Mutex::new(State { film, targets, paths }),
            earlier_seconds,
            started: OnceLock::new(),
        })
    }

    fn lock(&self) -> std::sync::MutexGuard<'_, State> {
        self.state.lock().unwrap_or_else(|e| e.into_inner())
    }

    /// Takes every pixel of the part to its target, in rounds that each take at most `chunk`
    /// more samples of a pixel (doubling while rounds are shorter than [`ROUND`]). False if
    /// cancelled.
    fn pass(
        &self,
        integrator: &PathIntegrator<'_>,
        goal: Goal,
        cancel: &AtomicBool,
        progress: &(dyn Fn(u64, u64) + Sync),
    ) -> bool {
        let (taken, total) = self.taken_and_target(goal.spp);
        let done = AtomicU64::new(taken);
        let mut chunk = 1u32;
        loop {
            let round = Instant::now();
            let more = AtomicBool::new(false);
            self.tiles.par_iter().for_each(|&bounds| {
                if !cancel.load(Ordering::Relaxed) {
                    let samples = self.render_tile(integrator, bounds, (chunk, goal.spp), cancel, &more);
                    progress(done.fetch_add(samples, Ordering::Relaxed) + samples, total);
                }
            });
            if cancel.load(Ordering::Relaxed) {
                return false;
            }
            if !more.load(Ordering::Relaxed) {
                return true;
            }
            if round.elapsed() < ROUND {
                chunk = chunk.saturating_mul(2);
            }
        }
    }

    /// The samples the part's pixels have taken, and the samples they will have after this
    /// pass (to their targets, at most `spp`).
    fn taken_and_target(&self, spp: u32) -> (u64, u64) {
        let state = self.lock();
        let width = state.film.width() as usize;
        self.tiles.iter().flat_map(|t| t.pixels()).fold((0, 0), |(taken, total), (x, y)| {
            let done = u64::from(state.film.taken_at(x, y));
            let target = state.targets[y as usize * width + x as usize].min(spp);
            (taken + done, total + done.max(u64::from(target)))
        })
    }

    /// Takes each pixel of one tile at most `chunk` samples closer to its target (at most `spp`:
    /// a resumed render may aim lower than the pass it continues); sets `more` if some pixel is
    /// still short of it. Returns the samples taken.
    fn render_tile(
        &self,
        integrator: &PathIntegrator<'_>,
        bounds: TileBounds,
        (chunk, spp): (u32, u32),
        cancel: &AtomicBool,
        more: &AtomicBool,
    ) -> u64 {
        let scene = self.scene;
        let settings = &scene.settings;
        let (mut tile, targets) = {
            let state = self.lock();
            let width = settings.width as usize;
            let targets: Vec<u32> =
                bounds.pixels().map(|(x, y)| state.targets[y as usize * width + x as usize]).collect();
            (state.film.tile(bounds), targets)
        };
        let mut stats = PathStats::default();
        let mut samples = 0;
        'pixels: for ((x, y), target) in bounds.pixels().zip(targets) {
            let pixel = u64::from(y) * u64::from(settings.width) + u64::from(x);
            let first = tile.taken_at(x, y);
            let target = target.min(spp);
            let end = target.min(first.saturating_add(chunk));
            for s in first..end {
                if cancel.load(Ordering::Relaxed) {
                    break 'pixels;
                }
                let mut sampler = Sampler::for_sample(settings.seed, pixel, u64::from(s));
                let fs = settings.filter.sample(sampler.next_2d());
                let size = [settings.width, settings.height];
                let l = match scene.camera.ray([x, y], fs.offset, size, sampler.next_2d()) {
                    Some(ray) => {
                        let start = (scene.camera.region, ray.origin, ray.direction);
                        integrator.radiance(start, ray.doppler, &mut sampler, &mut stats)
                    }
                    // Where the camera sees nothing (outside a fisheye's circle) the film is black.
                    None => Rgb::ZERO,
                };
                tile.add_sample(x, y, l, fs.weight);
                samples += 1;
            }
            if end < target {
                more.store(true, Ordering::Relaxed);
            }
        }
        let mut state = self.lock();
        state.film.store_tile(tile);
        state.paths += stats;
        samples
    }

    fn stats(&self, state: &State, outcome: Outcome, elapsed: Duration) -> RenderStats {
        let film = &state.film;
        let pixels = || self.tiles.iter().flat_map(|t| t.pixels());
        let (spp_min, spp_max) =
            pixels().map(|(x, y)| film.taken_at(x, y)).fold((u32::MAX, 0), |(lo, hi), n| (lo.min(n), hi.max(n)));
        RenderStats {
            paths: state.paths,
            samples: pixels().map(|(x, y)| u64::from(film.taken_at(x, y))).sum(),
            nan_samples: film.nan_samples(),
            seconds: self.earlier_seconds + elapsed.as_secs_f64(),
            outcome,
            spp_min: spp_min.min(spp_max),
            spp_max,
            relative_error: noise::estimated_relative_error(film, pixels()),
        }
    }

    fn elapsed(&self) -> Duration {
        self.started.get().map_or(Duration::ZERO, Instant::elapsed)
    }
}

impl Progressive for PathRender<'_> {
    /// Passes until the goal is reached or `cancel` is set (answered within a sample);
    /// `progress` is told the samples done and the total of this part, the total being that of
    /// the pass in progress (with a noise target, later passes may add more).
    fn run(&self, cancel: &AtomicBool, progress: &(dyn Fn(u64, u64) + Sync)) -> RenderStats {
        let start = *self.started.get_or_init(Instant::now);
        let goal = self.goal;
        let integrator = PathIntegrator::new(&self.scene.world, &self.propagator, &self.scene.settings);
        let outcome = loop {
            if !self.pass(&integrator, goal, cancel, progress) {
                break Outcome::Interrupted;
            }
            let next = {
                let mut state = self.lock();
                let State { film, targets, .. } = &mut *state;
                adaptive::next_targets(film, targets, &self.tiles, goal)
            };
            if let Some(outcome) = next {
                break outcome;
            }
        };
        self.stats(&self.lock(), outcome, start.elapsed())
    }

    fn snapshot(&self) -> (Film, RenderStats) {
        let state = self.lock();
        (state.film.clone(), self.stats(&state, Outcome::Interrupted, self.elapsed()))
    }

    fn film(&self) -> Film {
        self.lock().film.clone()
    }

    /// The film, each pixel with exactly the samples its sums hold, and the pass targets, copied
    /// under one lock and written after it is released (the render goes on meanwhile).
    fn write_checkpoint(
        &self,
        path: &Path,
        metadata: &dyn Fn(&RenderStats) -> Metadata,
    ) -> Result<(), ImageWriteError> {
        let (film, targets, stats) = {
            let state = self.lock();
            (state.film.clone(), state.targets.clone(), self.stats(&state, Outcome::Interrupted, self.elapsed()))
        };
        write_checkpoint(path, &film, &targets, &metadata(&stats))
    }

    fn into_film(self: Box<Self>) -> Film {
        self.state.into_inner().unwrap_or_else(|e| e.into_inner()).film
    }

    fn unit(&self) -> Unit {
        Unit::SamplesPerPixel
    }
}

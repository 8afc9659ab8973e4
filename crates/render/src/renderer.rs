//! Renders a scene into a film progressively: in passes over the whole image, each pass taking
//! every pixel on to its sample target, tiles in parallel. Every sample has its own random
//! stream keyed by (seed, pixel, sample) and each pixel's sums grow one sample at a time in
//! sample order (see [`Film::tile`]), so the image is bit-identical whatever the thread count,
//! however the samples fall into passes, and whether or not the render was stopped and resumed
//! on the way. A render stops within one sample of being cancelled, keeping every finished
//! sample; [`Renderer::snapshot`] takes a consistent copy of the state at any moment, for
//! checkpoints.
//!
//! A render's goal is a number of samples per pixel, or a noise target ([`NoiseTarget`]): the
//! passes then stop once the film's estimated relative error (see [`crate::film::noise`]) is
//! below it, and in adaptive mode each pass sends samples only where they lower the error most.
//!
//! A render can be split into [`Part`]s, each a fixed share of the tiles: parts are independent
//! processes, and their films put together are the film of the whole render, bit for bit.

mod adaptive;
mod data;

pub use data::data_layer;

use crate::color::Rgb;
use crate::film::{noise, Film, FilmTooLarge, TileBounds};
use crate::integrator::{photon, PathIntegrator, PathStats};
use crate::propagator::Propagator;
use crate::sampling::Sampler;
use crate::scene::Scene;
use crate::settings::{Connector, IntegratorKind};
use rayon::prelude::*;
use std::sync::atomic::{AtomicBool, AtomicU64, Ordering};
use std::sync::{Mutex, OnceLock};
use std::time::{Duration, Instant};

/// Pixels per tile side: the unit of parallel work and of [`Part`]s.
const TILE: u32 = 16;

/// Samples every pixel takes before a noise target's estimate is trusted.
pub const WARM_UP_SPP: u32 = 16;

/// A pass is split into rounds of at most this long (once the rounds' size has adapted), so
/// that snapshots and the progress bar stay fresh even when a pass takes hours.
const ROUND: Duration = Duration::from_secs(2);

/// Why a render stopped.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Outcome {
    /// Every pixel has its samples.
    #[default]
    Finished,
    /// The noise target was reached.
    Converged,
    /// Cancelled before its goal: continue it from a snapshot.
    Interrupted,
}

/// What a render did.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct RenderStats {
    pub paths: PathStats,
    /// Camera samples taken.
    pub samples: u64,
    /// Samples whose radiance was not finite (rejected by the film and counted here).
    pub nan_samples: u64,
    pub seconds: f64,
    pub outcome: Outcome,
    /// Fewest and most samples of a pixel (iterations, for the photon integrator).
    pub spp_min: u32,
    pub spp_max: u32,
    /// The film's estimated relative error where it can be estimated (see [`noise`]).
    pub relative_error: Option<f64>,
}

impl RenderStats {
    pub fn is_complete(&self) -> bool {
        self.outcome != Outcome::Interrupted
    }
}

/// How far to take a render.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Goal {
    /// Samples per pixel; with a noise target, the most a pixel takes.
    pub spp: u32,
    pub noise: Option<NoiseTarget>,
}

impl Goal {
    pub fn spp(spp: u32) -> Self {
        Self { spp, noise: None }
    }
}

/// Stop once the film's estimated relative error is at most `relative_error`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct NoiseTarget {
    pub relative_error: f64,
    /// Send samples to the pixels that need them (adaptive sampling) instead of all pixels.
    pub adaptive: bool,
}

/// Part `number` of `count` of a render: the tiles whose row-major index is `number − 1`
/// modulo `count`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Part {
    index: u32,
    count: u32,
}

impl Part {
    /// The whole image.
    pub const WHOLE: Part = Part { index: 0, count: 1 };

    /// Part `number` (from 1) of `count`.
    pub fn new(number: u32, count: u32) -> Result<Self, String> {
        if count == 0 || number == 0 || number > count {
            return Err(format!("part {number}/{count} does not exist: write I/N with 1 ≤ I ≤ N"));
        }
        Ok(Self { index: number - 1, count })
    }

    /// `I/N`, as on the command line.
    pub fn parse(text: &str) -> Result<Self, String> {
        let (i, n) = text.split_once('/').ok_or_else(|| format!("\"{text}\" is not a part: write I/N, e.g. 2/7"))?;
        let number =
            |s: &str| s.trim().parse::<u32>().map_err(|_| format!("\"{text}\" is not a part: write I/N, e.g. 2/7"));
        Self::new(number(i)?, number(n)?)
    }

    /// Its number, from 1.
    pub fn number(&self) -> u32 {
        self.index + 1
    }

    pub fn count(&self) -> u32 {
        self.count
    }

    /// The tiles of a `width × height` film that this part renders.
    pub fn tiles(&self, width: u32, height: u32) -> Vec<TileBounds> {
        TileBounds::grid(width, height, TILE)
            .into_iter()
            .enumerate()
            .filter(|(i, _)| *i as u64 % u64::from(self.count) == u64::from(self.index))
            .map(|(_, t)| t)
            .collect()
    }
}

impl std::fmt::Display for Part {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "{}/{}", self.number(), self.count)
    }
}

/// The propagator a scene needs; the escape radius encloses every object and the camera, the
/// chord tolerance is set by the objects (a camera far outside them, as for a disk seen from
/// afar, does not coarsen the hits).
pub fn propagator(scene: &Scene) -> Propagator {
    use spacetime::Region;
    let objects = [Region::Upper, Region::Lower]
        .iter()
        .map(|&r| scene.world.bounds(r))
        .filter(|b| !b.is_empty())
        .map(|b| b.min.abs().max(b.max.abs()).length())
        .fold(0.0f64, f64::max);
    let radius = objects.max(scene.camera.position.length());
    let propagator = Propagator::new(
        scene.spacetime.clone(),
        radius.max(1e-9),
        scene.settings.geodesic_rtol,
        scene.settings.intersection,
    )
    .with_axis(scene.axis)
    .with_camera(scene.camera.region, scene.camera.position);
    let propagator = if objects > 0.0 { propagator.with_chord_scale(objects) } else { propagator };
    match scene.settings.connector {
        Connector::Auto => propagator,
        Connector::Aimed => propagator.with_generic_connector(),
    }
}

/// Renders `scene` to its settings' samples per pixel on the current rayon pool. `cancel` stops
/// it within a sample; `progress` is told `(samples done, samples total)` as passes go.
pub fn render(scene: &Scene, cancel: &AtomicBool, progress: &(dyn Fn(u64, u64) + Sync)) -> (Film, RenderStats) {
    if scene.settings.integrator == IntegratorKind::Photon {
        let renderer = photon::PhotonRenderer::new(scene, None);
        let stats = renderer.run(cancel, progress);
        return (renderer.film(&renderer.snapshot().0), stats);
    }
    let renderer = Renderer::new(scene, Part::WHOLE, None).unwrap_or_else(|e| panic!("{e}"));
    let stats = renderer.run(Goal::spp(scene.settings.spp), cancel, progress);
    (renderer.into_state().0, stats)
}

/// What a render has so far: the film, and each pixel's target in the pass in progress.
struct State {
    film: Film,
    targets: Vec<u32>,
    paths: PathStats,
}

/// A progressive path-tracing render of a scene (or of a part of it): see the module docs. The
/// photon integrator renders by iterations of its own, see [`photon::PhotonRenderer`].
pub struct Renderer<'s> {
    scene: &'s Scene,
    propagator: Propagator,
    /// The tiles of the part this render makes.
    tiles: Vec<TileBounds>,
    state: Mutex<State>,
    /// Seconds of earlier runs that this one continues.
    earlier_seconds: f64,
    /// When [`Renderer::run`] started.
    started: OnceLock<Instant>,
}

/// Where a resumed render starts: the film and targets of a snapshot, what it counted, and how
/// long it had run.
pub struct Resume {
    pub film: Film,
    pub targets: Vec<u32>,
    pub paths: PathStats,
    pub seconds: f64,
}

impl<'s> Renderer<'s> {
    /// A render of `part` of `scene`, from scratch or continuing `resume` (whose film must have
    /// the scene's size). Fails when the film's memory cannot be allocated.
    ///
    /// # Panics
    /// If the scene asks for the photon integrator, or `resume` does not fit the scene.
    pub fn new(scene: &'s Scene, part: Part, resume: Option<Resume>) -> Result<Self, FilmTooLarge> {
        assert_ne!(
            scene.settings.integrator,
            IntegratorKind::Photon,
            "photon mapping renders by photon::PhotonRenderer"
        );
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
            tiles: part.tiles(width, height),
            state: Mutex::new(State { film, targets, paths }),
            earlier_seconds,
            started: OnceLock::new(),
        })
    }

    /// Renders on the current rayon pool until `goal` is reached or `cancel` is set (answered
    /// within a sample); `progress` is told `(samples done, samples total)` of this part, the
    /// total being that of the pass in progress (with a noise target, later passes may add more).
    pub fn run(&self, goal: Goal, cancel: &AtomicBool, progress: &(dyn Fn(u64, u64) + Sync)) -> RenderStats {
        let start = *self.started.get_or_init(Instant::now);
        let settings = &self.scene.settings;
        let integrator = PathIntegrator::new(&self.scene.world, &self.propagator, settings);
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

    /// A copy of the film and the pass targets as they stand, every pixel with exactly the
    /// samples its sums hold, and the statistics so far. Safe to call from another thread while
    /// [`Renderer::run`] works.
    pub fn snapshot(&self) -> (Film, Vec<u32>, RenderStats) {
        let state = self.lock();
        let elapsed = self.started.get().map_or(Duration::ZERO, Instant::elapsed);
        (state.film.clone(), state.targets.clone(), self.stats(&state, Outcome::Interrupted, elapsed))
    }

    /// The film, the pass targets and the path counts.
    pub fn into_state(self) -> (Film, Vec<u32>, PathStats) {
        let state = self.state.into_inner().unwrap_or_else(|e| e.into_inner());
        (state.film, state.targets, state.paths)
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
}

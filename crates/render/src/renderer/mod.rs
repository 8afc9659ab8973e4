//! Renders a scene progressively, by whichever light transport its settings name, behind one
//! interface, [`Progressive`]: run to a [`Goal`] on the current rayon pool, stopped within a
//! sample (a photon chunk) when cancelled, copied as it stands from another thread
//! ([`Progressive::snapshot`]), checkpointed while it runs, and continued from a checkpoint
//! ([`Resume`]) bit for bit. The transports behind it:
//!
//! - path tracing (`path`, [`IntegratorKind::Path`] and [`IntegratorKind::BruteForce`]): passes
//!   of pixel samples, to a number of samples per pixel or to a noise target ([`NoiseTarget`]),
//!   of the whole image or of a [`Part`] of it;
//! - photon mapping (`sppm`, [`IntegratorKind::Photon`]): SPPM iterations over the whole image.
//!
//! Dependencies run one way: the renderer drives the integrators ([`crate::integrator`]), which
//! know nothing of it. [`progressive`] is the one place that picks the transport, and
//! [`Checkpointed::read`] the one that picks a checkpoint's format.
//!
//! A render can be split into [`Part`]s, each a fixed share of the tiles: parts are independent
//! processes, and their films put together are the film of the whole render, bit for bit.

mod adaptive;
mod data;
mod path;
mod report;
mod sppm;

pub use data::{data_layer, requested_data};

use crate::film::{read_checkpoint, CheckpointError, Film, FilmTooLarge, ImageWriteError, Metadata, TileBounds};
use crate::integrator::photon::{self, SppmState};
use crate::integrator::PathStats;
use crate::propagator::Propagator;
use crate::scene::Scene;
use crate::settings::{IntegratorKind, LightConnection};
use path::{PathRender, PathResume};
use sppm::{SppmRender, SppmResume};
use std::path::Path;
use std::sync::atomic::AtomicBool;

/// Pixels per tile side: the unit of parallel work and of [`Part`]s.
const TILE: u32 = 16;

/// Samples every pixel takes before a noise target's estimate is trusted.
pub const WARM_UP_SPP: u32 = 16;

/// Why a render stopped.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Outcome {
    /// Every pixel has its samples (the render its iterations).
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
    /// The film's estimated relative error where it can be estimated (see
    /// [`crate::film::noise`]; never for photon mapping, whose error is mostly bias).
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
    /// Samples per pixel (iterations, for photon mapping: see [`Unit`]); with a noise target,
    /// the most a pixel takes.
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
    match scene.settings.light_connection {
        LightConnection::Auto => propagator,
        LightConnection::Aimed => propagator.with_generic_connector(),
    }
}

/// Renders `scene` to its settings' samples per pixel (iterations, for photon mapping) on the
/// current rayon pool. `cancel` stops it within a sample; `progress` is told `(done, total)` as
/// it goes (see [`Progressive::run`]).
///
/// # Panics
/// If the render cannot start (see [`StartError`]).
pub fn render(scene: &Scene, cancel: &AtomicBool, progress: &(dyn Fn(u64, u64) + Sync)) -> (Film, RenderStats) {
    let renderer =
        progressive(scene, Part::WHOLE, Goal::spp(scene.settings.spp), None).unwrap_or_else(|e| panic!("{e}"));
    let stats = renderer.run(cancel, progress);
    (renderer.into_film(), stats)
}

/// A render in progress, by any light transport: see the module docs. Every method but
/// [`Progressive::run`] may be called from another thread while it runs.
pub trait Progressive: Sync {
    /// Renders on the current rayon pool until the goal is reached or `cancel` is set (answered
    /// within a sample, or a photon chunk: an unfinished iteration is dropped); `progress` is
    /// told `(done, total)` in the render's [`Unit`]s (samples of all the part's pixels, or
    /// iterations), the total being that of the pass in progress.
    fn run(&self, cancel: &AtomicBool, progress: &(dyn Fn(u64, u64) + Sync)) -> RenderStats;

    /// A copy of the image as it stands, every pixel with exactly the samples (iterations) it
    /// has finished, and the statistics so far (their outcome [`Outcome::Interrupted`] unless
    /// the goal is reached).
    fn snapshot(&self) -> (Film, RenderStats);

    /// The image as it stands: [`Progressive::snapshot`]'s film, without the statistics.
    fn film(&self) -> Film;

    /// Writes a consistent copy of the state as it stands to the checkpoint `path` (the render
    /// goes on meanwhile), with the metadata `metadata` makes from the copy's statistics. The
    /// file is what [`Checkpointed::read`] reads back for the same transport.
    fn write_checkpoint(&self, path: &Path, metadata: &dyn Fn(&RenderStats) -> Metadata)
        -> Result<(), ImageWriteError>;

    /// The image, without copying it (the render is done with).
    fn into_film(self: Box<Self>) -> Film;

    /// What the render counts its progress in.
    fn unit(&self) -> Unit;
}

/// What a render counts its progress in: [`RenderStats::spp_min`] and `spp_max`, a [`Goal`]'s
/// `spp` and a checkpoint's [`Checkpointed::reached`] are in it.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Unit {
    /// Camera samples of each pixel (path tracing).
    SamplesPerPixel,
    /// Iterations over the whole image (photon mapping), each one camera path per pixel and a
    /// pass of photons.
    Iterations,
}

impl std::fmt::Display for Unit {
    /// As a sentence says it: "at 64 samples per pixel", "at 64 iterations".
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(match self {
            Unit::SamplesPerPixel => "samples per pixel",
            Unit::Iterations => "iterations",
        })
    }
}

/// Why a render cannot start.
#[derive(Debug)]
pub enum StartError {
    /// The film's memory cannot be allocated.
    FilmTooLarge(FilmTooLarge),
    /// Photon mapping in a spacetime whose light cannot be followed forwards in time (see
    /// [`photon::supports`]); scene files are checked for it when loaded.
    Backwards { spacetime: &'static str },
    /// A goal or a part that photon mapping cannot render: its iterations share every photon
    /// between all pixels, so a part would not be the whole render's part, and its error is mostly
    /// bias, which no noise estimate measures. (The command line refuses both with its own words
    /// before a render starts.)
    WholeIterationsOnly,
}

impl std::fmt::Display for StartError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            StartError::FilmTooLarge(e) => e.fmt(f),
            StartError::Backwards { spacetime } => {
                write!(f, "photon mapping cannot trace light forwards in the {spacetime} spacetime")
            }
            StartError::WholeIterationsOnly => f.write_str(
                "photon mapping renders the whole image to a number of iterations, not a part or a noise target",
            ),
        }
    }
}

impl std::error::Error for StartError {}

/// The state a checkpoint keeps, in its transport's terms: what a render continues from.
pub enum Checkpointed {
    /// The path tracer's: the film, each pixel with the samples its sums hold, and each pixel's
    /// target in the pass in progress.
    Passes { film: Film, targets: Vec<u32> },
    /// Photon mapping's: every pixel's estimate after the iterations finished.
    Iterations(SppmState),
}

impl Checkpointed {
    /// Reads the checkpoint at `path` as `transport` writes it (see
    /// [`Progressive::write_checkpoint`]), and the metadata its render wrote into it; refuses
    /// damaged files and another transport's checkpoints.
    pub fn read(path: &Path, transport: IntegratorKind) -> Result<(Self, Metadata), CheckpointError> {
        match transport {
            IntegratorKind::Path | IntegratorKind::BruteForce => {
                let checkpoint = read_checkpoint(path)?;
                Ok((Checkpointed::Passes { film: checkpoint.film, targets: checkpoint.targets }, checkpoint.metadata))
            }
            IntegratorKind::Photon => {
                let (state, metadata) = SppmState::read(path)?;
                Ok((Checkpointed::Iterations(state), metadata))
            }
        }
    }

    /// Width and height of its image.
    pub fn size(&self) -> (u32, u32) {
        match self {
            Checkpointed::Passes { film, .. } => (film.width(), film.height()),
            Checkpointed::Iterations(state) => (state.width(), state.height()),
        }
    }

    /// The most a pixel has of the render's [`Unit`]: samples (of the pixels that have the
    /// most), or iterations.
    pub fn reached(&self) -> u32 {
        match self {
            Checkpointed::Passes { film, .. } => {
                film.bounds().pixels().map(|(x, y)| film.taken_at(x, y)).max().unwrap_or(0)
            }
            Checkpointed::Iterations(state) => state.iterations(),
        }
    }
}

/// Where a continued render starts: the state of a checkpoint, what its render counted, and how
/// long it had run.
pub struct Resume {
    pub state: Checkpointed,
    pub paths: PathStats,
    pub seconds: f64,
}

/// A render of `part` of `scene` to `goal` by the scene's light transport, from scratch or
/// continuing `resume` (whose image must have the scene's size).
///
/// Fails when the film cannot be allocated, and for photon mapping in a spacetime it cannot
/// trace forwards, of a part, or to a noise target.
///
/// # Panics
/// If `resume` does not fit the scene: of another size, or another transport's (read it with
/// [`Checkpointed::read`] for the scene's transport).
pub fn progressive<'s>(
    scene: &'s Scene,
    part: Part,
    goal: Goal,
    resume: Option<Resume>,
) -> Result<Box<dyn Progressive + 's>, StartError> {
    match scene.settings.integrator {
        IntegratorKind::Path | IntegratorKind::BruteForce => {
            let resume = resume.map(|r| match r.state {
                Checkpointed::Passes { film, targets } => {
                    PathResume { film, targets, paths: r.paths, seconds: r.seconds }
                }
                Checkpointed::Iterations(_) => {
                    panic!("a photon-mapping checkpoint cannot continue a path tracer's render")
                }
            });
            let render = PathRender::new(scene, part, goal, resume).map_err(StartError::FilmTooLarge)?;
            Ok(Box::new(render))
        }
        IntegratorKind::Photon => {
            if part != Part::WHOLE || goal.noise.is_some() {
                return Err(StartError::WholeIterationsOnly);
            }
            if !photon::supports(&scene.spacetime) {
                return Err(StartError::Backwards { spacetime: scene.spacetime.name() });
            }
            let resume = resume.map(|r| match r.state {
                Checkpointed::Iterations(state) => SppmResume { state, paths: r.paths, seconds: r.seconds },
                Checkpointed::Passes { .. } => panic!("a path tracer's checkpoint cannot continue photon mapping"),
            });
            Ok(Box::new(SppmRender::new(scene, goal.spp, resume)))
        }
    }
}

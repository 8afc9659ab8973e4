//! Stochastic progressive photon mapping, SPPM (Hachisuka & Jensen 2009; pbrt-v3 §16.2), in
//! curved spacetime.
//!
//! Every iteration traces one camera path per pixel to its visible point (see `visible`),
//! then a fixed number of photons from the lights and skies (see `emit`, `aim`, `sky`,
//! `trace`), gathered by the visible points within each pixel's radius, which shrinks from
//! iteration to iteration (see `pixel`). Lights that camera paths rarely hit by chance — a lamp
//! in a room seen through a wormhole's throat — are found from their side instead. Emitters of
//! infinite area, which photons cannot start from, and skies over unbounded receivers are
//! gathered by paths continued from the visible points (see `background`). The estimate is
//! consistent: it converges to the path tracer's image as iterations grow.
//!
//! Photons carry RGB power. A blackbody's photons (a lamp's, an accretion disk's gas) carry its
//! temperature and their frequency instead of a colour, and are coloured where a visible point
//! gathers them, at the whole frequency ratio from the emitter to the camera (see `trace`), so
//! gravity and motion shift their colour as the path tracer's. Camera paths see a star field's
//! stars at the shifted temperature too; sky photons carry starlight at its colours at rest,
//! shifted in brightness only.
//!
//! Determinism: camera paths draw from the stream of (seed, pixel, iteration); photons are
//! traced in fixed chunks, each with the stream of (seed, chunk, iteration), and what they
//! deposit is summed chunk by chunk in chunk order. The image does not depend on the threads.
//!
//! Photons follow geodesics forwards in time, which needs a spacetime that says how its light
//! is followed so ([`spacetime::metric::Capabilities::forwards`]): every built-in one does
//! (static ones are time-symmetric, spinning holes are traced through their spin-reversed
//! twins); a metric written in a scene file does not.
//!
//! Statistics: `rays` counts every geodesic segment traced (camera, background and photon
//! paths); the fates are those of the camera paths, which end at their visible points
//! (counted as absorbed) unless they escape, are captured or fail first.

mod aim;
mod background;
mod emit;
mod grid;
mod pixel;
mod sky;
mod state;
mod trace;
mod visible;

use super::stats::PathStats;
use crate::propagator::Propagator;
use crate::rgb::Rgb;
use crate::sampling::{Rng, Sampler};
use crate::scene::Scene;
use crate::world::World;
use background::Background;
use emit::{RegionSplit, Sources};
use grid::{Grid, Sphere};
use rayon::prelude::*;
use spacetime::metric::Forwards;
use spacetime::{Region, Spacetime};
pub use state::SppmState;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::Mutex;
use trace::{Deposit, PhotonPass};
use visible::{CameraPass, CameraSample, VisiblePoint};

/// Photons per chunk: the unit of parallel work and of the fixed summation order.
const CHUNK: u64 = 1024;
/// Mixed into the seed of photon streams, so that they differ from the camera streams.
const PHOTON_STREAMS: u64 = 0x7068_6f74_6f6e_7321;
/// Default initial radius as a fraction of the diagonal of a region's bounding box.
const DEFAULT_RADIUS_FRACTION: f64 = 0.01;

/// Whether photons can be traced forwards in `spacetime` (see the module documentation).
pub fn supports(spacetime: &Spacetime) -> bool {
    match spacetime.capabilities().forwards() {
        Forwards::Reversed | Forwards::SpinTwin(_) => true,
        Forwards::Unsupported => false,
    }
}

/// Photons an iteration of `scene`'s render: as set, or one per pixel.
pub fn photons_per_iteration(scene: &Scene) -> u64 {
    let settings = &scene.settings;
    settings.photon.per_iteration.unwrap_or(u64::from(settings.width) * u64::from(settings.height))
}

/// One render's fixed parts: what every iteration traces from and with. The iterations
/// themselves are driven by the renderer module, which keeps the [`SppmState`] between them,
/// counts them, checkpoints and continues them.
pub struct Sppm<'a> {
    scene: &'a Scene,
    camera: CameraPass<'a>,
    photons: u64,
    /// What photons leave from.
    sources: Sources,
    /// Initial radius of pixels whose first visible point is in the upper, the lower region.
    start_radius: [f64; 2],
}

impl<'a> Sppm<'a> {
    /// The fixed parts of `scene`'s render, tracing with `propagator` (the scene's, as the
    /// renderer's `propagator` makes it).
    ///
    /// # Panics
    /// If the spacetime is not [supported](supports) (scene files are checked for it when
    /// loaded; the renderer refuses it before it gets here).
    pub fn new(scene: &'a Scene, propagator: &'a Propagator) -> Self {
        assert!(
            supports(&scene.spacetime),
            "photon mapping needs a spacetime whose light can be followed forwards, not {:?}",
            scene.spacetime
        );
        let settings = &scene.settings;
        let start_radius = |region| settings.photon.radius.unwrap_or_else(|| default_radius(&scene.world, region));
        let sources = Sources::new(&scene.world, &scene.spacetime, propagator);
        Sppm {
            scene,
            camera: CameraPass {
                world: &scene.world,
                propagator,
                max_depth: settings.max_depth,
                background: Background::new(&scene.world, |region| sources.carry_sky(region)),
            },
            photons: photons_per_iteration(scene),
            sources,
            start_radius: [start_radius(Region::Upper), start_radius(Region::Lower)],
        }
    }

    /// Runs iteration `iteration` into `state`; `None` (and `state` untouched) if cancelled.
    ///
    /// `state` is locked twice, briefly: to read the pixels' radii before the passes, and to add
    /// the iteration after them, so that a snapshot taken meanwhile from another thread sees the
    /// state after the last finished iteration. Only the iteration's driver may change `state`
    /// between the two (the radii read are those the iteration gathers with).
    pub fn iteration(&self, state: &Mutex<(SppmState, PathStats)>, iteration: u32, cancel: &AtomicBool) -> Option<()> {
        let lock = || state.lock().unwrap_or_else(|e| e.into_inner());
        let (samples, camera_stats) = camera_pass(self.scene, &self.camera, iteration);
        let visible: Vec<Option<VisiblePoint>> = samples.iter().map(|(s, _)| s.visible).collect();
        let radii: Vec<f64> = lock()
            .0
            .pixels
            .iter()
            .zip(&visible)
            .map(|(pixel, vp)| vp.as_ref().map_or(0.0, |vp| pixel.radius().unwrap_or(self.start(vp.region))))
            .collect();
        let pass = PhotonPass {
            world: &self.scene.world,
            propagator: self.camera.propagator,
            max_depth: self.scene.settings.max_depth,
            upper: grid(&visible, &radii, Region::Upper),
            lower: grid(&visible, &radii, Region::Lower),
            visible: &visible,
            radii: &radii,
        };
        let split = RegionSplit::new(&self.scene.world, &self.sources, [pass.upper.spheres(), pass.lower.spheres()]);
        let seed = (self.scene.settings.seed, iteration);
        let Gathered { flux, found, paths: photon_stats, mut dropped } =
            photon_pass(&pass, split.map(|s| (s, &self.sources)), seed, self.photons, cancel)?;
        let mut guard = lock();
        let (state, paths) = &mut *guard;
        for ((pixel, (sample, weight)), (&radius, (flux, found))) in
            state.pixels.iter_mut().zip(&samples).zip(radii.iter().zip(flux.into_iter().zip(found)))
        {
            // Non-finite radiance would poison the pixel's sums for good; the path tracer's
            // film drops such samples too.
            let emitted = if sample.emitted.is_finite() { sample.emitted } else { Rgb::ZERO };
            dropped += u64::from(!sample.emitted.is_finite());
            pixel.add_iteration(emitted, *weight, (radius, flux), found);
        }
        *paths += camera_stats;
        *paths += photon_stats;
        state.dropped += dropped;
        state.iterations = iteration + 1;
        Some(())
    }

    fn start(&self, region: Region) -> f64 {
        self.start_radius[slot(region)]
    }
}

/// Where per-region pairs keep `region`'s entry: upper first, lower second.
fn slot(region: Region) -> usize {
    usize::from(region == Region::Lower)
}

/// 1 % of the diagonal of the bounds of `region`'s objects (of the other region's if it has
/// none, 1 in a scene without finite objects): a wormhole's room and the outer space on its
/// other side may differ in size a hundredfold.
fn default_radius(world: &World, region: Region) -> f64 {
    let other = match region {
        Region::Upper => Region::Lower,
        Region::Lower => Region::Upper,
    };
    [region, other]
        .iter()
        .map(|&r| world.bounds(r))
        .filter(|b| !b.is_empty())
        .map(|b| b.diagonal().length())
        .find(|d| d.is_finite() && *d > 0.0)
        .map_or(1.0, |d| DEFAULT_RADIUS_FRACTION * d)
}

/// One camera path per pixel, row-major, with its filter weight.
fn camera_pass(scene: &Scene, camera: &CameraPass<'_>, iteration: u32) -> (Vec<(CameraSample, f64)>, PathStats) {
    let settings = &scene.settings;
    let rows: Vec<(Vec<(CameraSample, f64)>, PathStats)> = (0..settings.height)
        .into_par_iter()
        .map(|y| {
            let mut stats = PathStats::default();
            let row = (0..settings.width)
                .map(|x| {
                    let pixel = u64::from(y) * u64::from(settings.width) + u64::from(x);
                    let mut sampler = Sampler::for_sample(settings.seed, pixel, u64::from(iteration));
                    let fs = settings.filter.sample(sampler.next_2d());
                    let size = [settings.width, settings.height];
                    let sample = match scene.camera.ray([x, y], fs.offset, size, sampler.next_2d()) {
                        Some(ray) => {
                            let beta = Rgb::splat(ray.weight() * fs.weight as f32);
                            let start = (scene.camera.region, ray.origin, ray.direction);
                            camera.trace(start, beta, ray.doppler, &mut sampler, &mut stats)
                        }
                        // Where the camera sees nothing (outside a fisheye's circle): black.
                        None => CameraSample { emitted: Rgb::ZERO, visible: None },
                    };
                    (sample, fs.weight)
                })
                .collect();
            (row, stats)
        })
        .collect();
    let mut stats = PathStats::default();
    let mut samples = Vec::with_capacity(settings.width as usize * settings.height as usize);
    for (row, s) in rows {
        samples.extend(row);
        stats += s;
    }
    (samples, stats)
}

/// The hash grid of the visible points of `region`.
fn grid(visible: &[Option<VisiblePoint>], radii: &[f64], region: Region) -> Grid {
    let spheres: Vec<Sphere> = visible
        .iter()
        .zip(radii)
        .enumerate()
        .filter_map(|(i, (vp, &radius))| {
            let vp = vp.as_ref().filter(|vp| vp.region == region)?;
            Some(Sphere { index: i as u32, centre: vp.p, radius })
        })
        .collect();
    Grid::build(&spheres)
}

/// What one iteration's photons left.
struct Gathered {
    /// Per pixel: the flux sum and the number of photons found.
    flux: Vec<[f64; 3]>,
    found: Vec<u64>,
    paths: PathStats,
    /// Non-finite deposits, dropped.
    dropped: u64,
}

/// Gathers one iteration's photons, chunk by chunk in chunk order; `None` if cancelled.
fn photon_pass(
    pass: &PhotonPass<'_>,
    emitters: Option<(RegionSplit, &Sources)>,
    (seed, iteration): (u64, u32),
    photons: u64,
    cancel: &AtomicBool,
) -> Option<Gathered> {
    let chunks: Vec<Option<(Vec<Deposit>, PathStats)>> = (0..photons.div_ceil(CHUNK))
        .into_par_iter()
        .map(|chunk| {
            if cancel.load(Ordering::Relaxed) {
                return None;
            }
            let mut rng = Rng::for_sample(seed ^ PHOTON_STREAMS, chunk, u64::from(iteration));
            let (mut deposits, mut stats) = (Vec::new(), PathStats::default());
            let Some(emitters) = emitters else { return Some((deposits, stats)) };
            for _ in chunk * CHUNK..((chunk + 1) * CHUNK).min(photons) {
                if let Some(photon) = emit::emit(pass.world, pass.propagator, emitters, &mut rng) {
                    pass.trace(photon, &mut rng, &mut stats, &mut deposits);
                }
            }
            Some((deposits, stats))
        })
        .collect();
    let mut flux = vec![[0.0; 3]; pass.visible.len()];
    let mut found = vec![0; pass.visible.len()];
    let mut stats = PathStats::default();
    let mut dropped = 0;
    for chunk in chunks {
        let (deposits, s) = chunk?;
        for d in deposits {
            let i = d.pixel as usize;
            if !d.flux.is_finite() {
                dropped += 1;
                continue;
            }
            for (f, c) in flux[i].iter_mut().zip(d.flux.to_array()) {
                *f += f64::from(c);
            }
            found[i] += 1;
        }
        stats += s;
    }
    Some(Gathered { flux, found, paths: stats, dropped })
}

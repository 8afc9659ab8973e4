//! Renders a scene into a film: tiles in parallel, every sample with its own random stream keyed
//! by (seed, pixel, sample), so the image is bit-identical whatever the thread count; stoppable
//! at any tile boundary with everything finished so far kept.

use crate::color::Rgb;
use crate::film::{Film, FilmTile, TileBounds};
use crate::integrator::{photon, PathIntegrator, PathStats};
use crate::propagator::Propagator;
use crate::sampling::Sampler;
use crate::scene::Scene;
use crate::settings::IntegratorKind;
use rayon::prelude::*;
use std::sync::atomic::{AtomicBool, AtomicU64, Ordering};
use std::sync::Mutex;
use std::time::Instant;

/// Pixels per tile side.
const TILE: u32 = 16;

/// What a render did.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct RenderStats {
    pub paths: PathStats,
    /// Camera samples taken.
    pub samples: u64,
    /// Samples whose radiance was not finite (rejected by the film and counted here).
    pub nan_samples: u64,
    pub seconds: f64,
    /// Tiles finished out of the total (less than total after an interruption); iterations for
    /// the photon integrator.
    pub tiles_done: u64,
    pub tiles_total: u64,
}

/// The propagator a scene needs; the escape radius encloses every object.
pub fn propagator(scene: &Scene) -> Propagator {
    use spacetime::Region;
    let radius = [Region::Upper, Region::Lower]
        .iter()
        .map(|&r| scene.world.bounds(r))
        .filter(|b| !b.is_empty())
        .map(|b| b.min.abs().max(b.max.abs()).length())
        .chain([scene.camera.position.length()])
        .fold(0.0f64, f64::max);
    Propagator::new(scene.spacetime, radius.max(1e-9), scene.settings.geodesic_rtol, scene.settings.intersection)
        .with_axis(scene.axis)
}

/// Renders one tile.
fn render_tile(scene: &Scene, integrator: &PathIntegrator<'_>, bounds: TileBounds) -> (FilmTile, PathStats, u64) {
    let settings = &scene.settings;
    let mut tile = FilmTile::new(bounds);
    let mut stats = PathStats::default();
    let mut samples = 0;
    for (x, y) in bounds.pixels() {
        let pixel = u64::from(y) * u64::from(settings.width) + u64::from(x);
        for s in 0..settings.spp {
            let mut sampler = Sampler::for_sample(settings.seed, pixel, u64::from(s));
            let fs = settings.filter.sample(sampler.next_2d());
            let size = [settings.width, settings.height];
            let l = match scene.camera.ray([x, y], fs.offset, size, sampler.next_2d()) {
                Some(ray) => {
                    integrator.radiance(scene.camera.region, ray.origin, ray.direction, &mut sampler, &mut stats)
                        * ray.weight
                }
                // Where the camera sees nothing (outside a fisheye's circle) the film is black.
                None => Rgb::ZERO,
            };
            tile.add_sample(x, y, l, fs.weight);
            samples += 1;
        }
    }
    (tile, stats, samples)
}

/// Renders `scene` on the current rayon pool. `cancel` stops it between tiles; `progress` is
/// told `(tiles done, tiles total)` after every tile. The photon integrator works in iterations
/// over the whole image instead, see [`photon::render`].
pub fn render(scene: &Scene, cancel: &AtomicBool, progress: &(dyn Fn(u64, u64) + Sync)) -> (Film, RenderStats) {
    let start = Instant::now();
    let settings = &scene.settings;
    let propagator = propagator(scene);
    if settings.integrator == IntegratorKind::Photon {
        return photon::render(scene, &propagator, cancel, progress);
    }
    let integrator = PathIntegrator::new(
        &scene.world,
        &propagator,
        settings.max_depth,
        settings.integrator == IntegratorKind::BruteForce,
    );
    let film = Mutex::new(Film::new(settings.width, settings.height));
    let tiles = film.lock().map(|f| f.tiles(TILE)).unwrap_or_default();
    let total = tiles.len() as u64;
    let done = AtomicU64::new(0);
    let totals = Mutex::new((PathStats::default(), 0u64));
    tiles.into_par_iter().for_each(|bounds| {
        if cancel.load(Ordering::Relaxed) {
            return;
        }
        let (tile, stats, samples) = render_tile(scene, &integrator, bounds);
        if let Ok(mut f) = film.lock() {
            f.merge_tile(tile);
        }
        if let Ok(mut t) = totals.lock() {
            t.0 += stats;
            t.1 += samples;
        }
        progress(done.fetch_add(1, Ordering::Relaxed) + 1, total);
    });
    let film = film.into_inner().unwrap_or_else(|e| e.into_inner());
    let (paths, samples) = totals.into_inner().unwrap_or_else(|e| e.into_inner());
    let stats = RenderStats {
        paths,
        samples,
        nan_samples: film.nan_samples(),
        seconds: start.elapsed().as_secs_f64(),
        tiles_done: done.load(Ordering::Relaxed),
        tiles_total: total,
    };
    (film, stats)
}

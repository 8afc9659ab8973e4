//! The render behind the page: for each new generation (the view moved, a slider changed, the
//! file changed) a quick frame at a quarter of the preview's resolution and one sample, then the
//! preview's resolution refined to the samples asked for, publishing a frame as samples arrive
//! (a few times a second at most); a newer generation cancels it.
//!
//! Both stages render as `nullpath render` does, with the scene's own integrator: path tracing
//! sample by sample, photon mapping iteration by iteration. (Previewing photon mapping by path
//! tracing, as the preview once did, made the Kerr room six times slower per sample than the
//! render it previews: the path tracer aims every light connection through the curved
//! spacetime, which the photon mapper never does.) A refinement of the preview therefore costs
//! what a render of the same pixels and samples costs: see BENCHMARKS.md.

use super::state::{Shared, Stage};
use image::ImageEncoder;
use render::film::{to_rgb8, Film};
use render::renderer::{progressive, Goal, Part};
use render::scene::Scene;
use std::sync::atomic::{AtomicBool, AtomicU64, Ordering};
use std::sync::mpsc;
use std::time::{Duration, Instant};

/// Longest side of the refined preview, pixels.
const PREVIEW_SIDE: u32 = 640;
/// The first frame after a change is this many times smaller on each side.
const LOW_RESOLUTION_DIVISOR: u32 = 4;
/// How often a refining render is checked for cancellation.
const POLL: Duration = Duration::from_millis(30);
/// How often at most a refining render publishes its film.
const PUBLISH_EVERY: Duration = Duration::from_millis(250);
/// Frames are at least this many times their own cost apart (see [`render_stage`]).
const FRAME_SHARE: u32 = 20;

/// Renders each generation in turn, forever.
pub fn refine_forever(shared: &Shared) {
    let mut seen = u64::MAX;
    loop {
        let (generation, current, spp) = shared.next_job(seen);
        seen = generation;
        let Ok(scene) = current else { continue };
        for (stage, last) in [(low_resolution(&scene), false), (preview(&scene, spp), true)] {
            if !render_stage(shared, generation, &stage, last) {
                break;
            }
        }
    }
}

/// `scene` at `width × height`: the size and, where the scene sets how many photons an
/// iteration traces, that count in proportion to the pixels (the default, one per pixel, is so
/// already), so that an iteration's photons and camera paths keep the scene's balance.
fn resized(scene: &Scene, width: u32, height: u32) -> Scene {
    let mut out = scene.clone();
    let s = &mut out.settings;
    if let Some(photons) = s.photon.per_iteration {
        let share = f64::from(width) * f64::from(height) / (f64::from(s.width) * f64::from(s.height));
        s.photon.per_iteration = Some(((photons as f64 * share).round() as u64).max(1));
    }
    (s.width, s.height) = (width, height);
    out
}

/// The scene at the preview's size (the scene's aspect, longest side at most [`PREVIEW_SIDE`])
/// with `spp` samples per pixel (iterations, for photon mapping), by the scene's integrator.
pub fn preview(scene: &Scene, spp: u32) -> Scene {
    let s = &scene.settings;
    let scale = (f64::from(PREVIEW_SIDE) / f64::from(s.width.max(s.height))).min(1.0);
    let side = |n: u32| ((f64::from(n) * scale).round() as u32).max(1);
    let mut out = resized(scene, side(s.width), side(s.height));
    out.settings.spp = spp;
    out
}

/// The first frame after a change: [`preview`] at a quarter of the size and one sample.
pub fn low_resolution(scene: &Scene) -> Scene {
    let full = preview(scene, 1);
    let s = &full.settings;
    resized(&full, s.width.div_ceil(LOW_RESOLUTION_DIVISOR), s.height.div_ceil(LOW_RESOLUTION_DIVISOR))
}

/// The film as a PNG (tone mapped as the scene says).
pub fn encode_png(film: &Film, scene: &Scene) -> Result<Vec<u8>, String> {
    let rgb = to_rgb8(film, &scene.settings.tonemap);
    let mut png = Vec::new();
    let encoder = image::codecs::png::PngEncoder::new_with_quality(
        &mut png,
        image::codecs::png::CompressionType::Fast,
        image::codecs::png::FilterType::Sub,
    );
    encoder
        .write_image(&rgb, film.width(), film.height(), image::ExtendedColorType::Rgb8)
        .map_err(|e| e.to_string())?;
    Ok(png)
}

/// Renders `scene` progressively to its samples per pixel, publishing frames once every pixel
/// has a sample; false if a newer generation cancelled it (or it could not start).
///
/// A frame is taken only when the render has progressed (for photon mapping, once an iteration),
/// and at most once in [`PUBLISH_EVERY`] and in [`FRAME_SHARE`] times what the last frame cost,
/// so that taking frames — copying the film, tone mapping, encoding the PNG, all on this thread
/// beside the render's — never costs the render more than a small share of the machine.
/// (Taking one every 250 ms whatever happened cost the Kerr room a fifth of its two cores.)
fn render_stage(shared: &Shared, generation: u64, scene: &Scene, last: bool) -> bool {
    // Scene files are checked for a spacetime photon mapping can trace, and the sliders keep
    // the spacetime's type; the refusal is for the spacetimes that slip through all the same.
    let renderer = match progressive(scene, Part::WHOLE, Goal::spp(scene.settings.spp), None) {
        Ok(r) => r,
        Err(e) => {
            eprintln!("nullpath preview: {e}");
            return false;
        }
    };
    let cancel = AtomicBool::new(false);
    // Counts the render's reports of progress: a frame is worth taking only after one.
    let progress = AtomicU64::new(0);
    let (finished_tx, finished) = mpsc::channel();
    std::thread::scope(|s| {
        s.spawn(|| {
            renderer.run(&cancel, &|_, _| {
                progress.fetch_add(1, Ordering::Relaxed);
            });
            // The receiver lives until this scope ends.
            let _ = finished_tx.send(());
        });
        let (mut shown, mut samples, mut next) = (0, 0, Instant::now());
        loop {
            let done = finished.recv_timeout(POLL).is_ok();
            if shared.generation() != generation {
                cancel.store(true, Ordering::Relaxed);
            }
            let reported = progress.load(Ordering::Relaxed);
            let due = reported != shown && Instant::now() >= next;
            if !cancel.load(Ordering::Relaxed) && (done || due) {
                let began = Instant::now();
                let (film, stats) = renderer.snapshot();
                if stats.spp_min >= 1 && (done || stats.samples > samples) {
                    match encode_png(&film, scene) {
                        Ok(png) => {
                            let size = (film.width(), film.height());
                            shared.publish(generation, png, size, Stage { stats, done: done && last });
                        }
                        Err(e) => eprintln!("nullpath preview: cannot encode a frame: {e}"),
                    }
                    samples = stats.samples;
                }
                shown = reported;
                next = Instant::now() + PUBLISH_EVERY.max(began.elapsed() * FRAME_SHARE);
            }
            if done {
                break;
            }
        }
    });
    !cancel.load(Ordering::Relaxed)
}

#[cfg(test)]
mod tests {
    use super::*;
    use render::settings::IntegratorKind;

    #[test]
    fn the_first_frame_is_small_and_the_preview_keeps_the_aspect_and_the_integrator() {
        let text = "[camera]\nposition = [0, 0, 5]\nlook_at = [0, 0, 0]\n[render]\nwidth = 1920\nheight = 1080\n\
                    spp = 500\nintegrator = \"photon\"\nphotons_per_iteration = 2073600\n";
        let scene = scene::parse(text, "t.toml", ".".as_ref()).expect("valid scene");
        let p = preview(&scene, 32).settings;
        assert_eq!((p.width, p.height, p.spp, p.integrator), (640, 360, 32, IntegratorKind::Photon));
        assert_eq!(p.photon.per_iteration, Some(640 * 360), "one photon a pixel, as the scene has");
        let low = low_resolution(&scene).settings;
        assert_eq!((low.width, low.height, low.spp, low.integrator), (160, 90, 1, IntegratorKind::Photon));
        assert_eq!(low.photon.per_iteration, Some(160 * 90));
        // A scene no larger than the preview is previewed at its own size.
        let small = preview(
            &scene::parse(
                "[camera]\nposition = [0, 0, 5]\nlook_at = [0, 0, 0]\n[render]\nwidth = 96\nheight = 72\n",
                "t.toml",
                ".".as_ref(),
            )
            .expect("valid scene"),
            4,
        )
        .settings;
        assert_eq!((small.width, small.height, small.integrator), (96, 72, IntegratorKind::Path));
    }
}

//! The render behind the page: for each new generation (the view moved, a slider changed, the
//! file changed) a quick frame at a quarter of the preview's resolution and one sample, then the
//! preview's resolution refined sample by sample by the progressive renderer, publishing a frame
//! a few times a second; a newer generation cancels it within a sample.

use super::state::Shared;
use image::ImageEncoder;
use render::film::{to_rgb8, Film};
use render::renderer::{Goal, Part, Renderer};
use render::scene::Scene;
use render::settings::IntegratorKind;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::mpsc;
use std::time::{Duration, Instant};

/// Longest side of the refined preview, pixels.
const PREVIEW_SIDE: u32 = 640;
/// The first frame after a change is this many times smaller on each side.
const LOW_RESOLUTION_DIVISOR: u32 = 4;
/// How often a refining render is checked for cancellation.
const POLL: Duration = Duration::from_millis(30);
/// How often a refining render publishes its film.
const PUBLISH_EVERY: Duration = Duration::from_millis(250);

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

/// The scene at the preview's size (the scene's aspect, longest side at most [`PREVIEW_SIDE`])
/// with `spp` samples; photon mapping is previewed by path tracing, which refines per sample.
pub fn preview(scene: &Scene, spp: u32) -> Scene {
    let mut out = scene.clone();
    let s = &mut out.settings;
    let scale = f64::from(PREVIEW_SIDE) / f64::from(s.width.max(s.height));
    if scale < 1.0 {
        s.width = ((f64::from(s.width) * scale).round() as u32).max(1);
        s.height = ((f64::from(s.height) * scale).round() as u32).max(1);
    }
    s.spp = spp;
    if s.integrator == IntegratorKind::Photon {
        s.integrator = IntegratorKind::Path;
    }
    out
}

/// The first frame after a change: [`preview`] at a quarter of the size and one sample.
pub fn low_resolution(scene: &Scene) -> Scene {
    let mut out = preview(scene, 1);
    let s = &mut out.settings;
    s.width = s.width.div_ceil(LOW_RESOLUTION_DIVISOR);
    s.height = s.height.div_ceil(LOW_RESOLUTION_DIVISOR);
    out
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
fn render_stage(shared: &Shared, generation: u64, scene: &Scene, last: bool) -> bool {
    let renderer = match Renderer::new(scene, Part::WHOLE, None) {
        Ok(r) => r,
        Err(e) => {
            eprintln!("nullpath preview: {e}");
            return false;
        }
    };
    let cancel = AtomicBool::new(false);
    let (finished_tx, finished) = mpsc::channel();
    std::thread::scope(|s| {
        s.spawn(|| {
            renderer.run(Goal::spp(scene.settings.spp), &cancel, &|_, _| {});
            // The receiver lives until this scope ends.
            let _ = finished_tx.send(());
        });
        let mut published = (Instant::now(), 0);
        loop {
            let done = finished.recv_timeout(POLL).is_ok();
            if shared.generation() != generation {
                cancel.store(true, Ordering::Relaxed);
            }
            let due = published.0.elapsed() >= PUBLISH_EVERY;
            if cancel.load(Ordering::Relaxed) || !(done || due) {
                if done {
                    break;
                }
                continue;
            }
            let (film, _, stats) = renderer.snapshot();
            if stats.spp_min >= 1 && (done || stats.samples > published.1) {
                match encode_png(&film, scene) {
                    Ok(png) => {
                        shared.publish(generation, png, (film.width(), film.height()), stats.spp_min, done && last)
                    }
                    Err(e) => eprintln!("nullpath preview: cannot encode a frame: {e}"),
                }
                published = (Instant::now(), stats.samples);
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

    #[test]
    fn the_first_frame_is_small_and_the_preview_keeps_the_aspect() {
        let text = "[camera]\nposition = [0, 0, 5]\nlook_at = [0, 0, 0]\n[render]\nwidth = 1920\nheight = 1080\n\
                    spp = 500\nintegrator = \"photon\"\n";
        let scene = scene::parse(text, "t.toml", ".".as_ref()).expect("valid scene");
        let p = preview(&scene, 32).settings;
        assert_eq!((p.width, p.height, p.spp, p.integrator), (640, 360, 32, IntegratorKind::Path));
        let low = low_resolution(&scene).settings;
        assert_eq!((low.width, low.height, low.spp), (160, 90, 1));
    }
}

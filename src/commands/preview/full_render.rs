//! "Render": the preview's view and parameters rendered at the scene file's own settings (size,
//! samples, integrator) in the background, to a named image beside the scene file, with the
//! metadata `nullpath render` writes. One at a time; the page shows its progress and where it went.

use super::state::{RenderJob, Shared};
use crate::commands::provenance::{self, Source};
use render::film::{check_output_path, write_image};
use render::renderer::{render, Goal, Part};
use render::scene::Scene;
use std::path::{Path, PathBuf};
use std::sync::atomic::AtomicBool;
use std::sync::Arc;

/// Longest output file name.
const MAX_NAME: usize = 128;

/// The image file `name` in `directory`: a plain file name (letters, digits, `_`, `-`, `.`, not
/// starting with a dot) ending in .png, .exr or .hdr.
pub fn output_path(directory: &Path, name: &str) -> Result<PathBuf, String> {
    let plain = name.chars().all(|c| c.is_ascii_alphanumeric() || matches!(c, '_' | '-' | '.'));
    if name.is_empty() || name.len() > MAX_NAME || !plain || name.starts_with('.') {
        return Err(format!(
            "an output is a file name of up to {MAX_NAME} letters, digits, '_', '-' or '.', got {name:?}"
        ));
    }
    let path = directory.join(name);
    check_output_path(&path).map_err(|e| e.to_string())?;
    Ok(path)
}

/// Starts rendering `scene` (the preview's scene at the file's settings) to `output`, unless a
/// render is already running.
pub fn start(shared: &Arc<Shared>, scene: Scene, source: Source, output: PathBuf) -> Result<(), String> {
    {
        let mut inner = shared.lock();
        if inner.job.as_ref().is_some_and(|j| j.state == "running") {
            return Err("a render is already running; wait until it has written its image".into());
        }
        inner.job = Some(RenderJob {
            output: output.display().to_string(),
            state: "running",
            progress: 0.0,
            message: String::new(),
        });
    }
    let shared = Arc::clone(shared);
    std::thread::spawn(move || {
        let result = write(&shared, &scene, &source, &output);
        let mut inner = shared.lock();
        if let Some(job) = inner.job.as_mut() {
            (job.state, job.progress, job.message) = match result {
                Ok(summary) => ("done", 1.0, summary),
                Err(e) => ("failed", job.progress, e),
            };
        }
    });
    Ok(())
}

fn write(shared: &Shared, scene: &Scene, source: &Source, output: &Path) -> Result<String, String> {
    let never = AtomicBool::new(false);
    let progress = |done: u64, total: u64| {
        if let Some(job) = shared.lock().job.as_mut() {
            job.progress = done as f64 / total.max(1) as f64;
        }
    };
    let (film, stats) = render(scene, &never, &progress);
    let metadata = provenance::metadata(scene, source, Goal::spp(scene.settings.spp), Part::WHOLE, &stats);
    write_image(&film, output, &scene.settings.tonemap, &metadata).map_err(|e| e.to_string())?;
    Ok(format!("wrote {}: {}", output.display(), crate::commands::render::summary(&stats, scene)))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn outputs_are_plain_image_names() {
        let dir = std::env::temp_dir();
        assert_eq!(output_path(&dir, "view.png"), Ok(dir.join("view.png")));
        for bad in ["", "../x.png", "a/b.png", ".png", "x.txt", "x png", "x.png\n"] {
            assert!(output_path(&dir, bad).is_err(), "{bad:?}");
        }
    }
}

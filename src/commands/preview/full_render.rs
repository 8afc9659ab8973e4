//! "Render": the preview's view and parameters rendered at the scene file's own settings (size,
//! samples, integrator) in the background, to a named image beside the scene file, with the
//! metadata `nullpath render` writes and the spacetime and camera actually rendered (the
//! sliders' and the page's, which the scene text in the metadata does not have). One at a time;
//! the page shows its progress and where it went, or why it failed. An existing file is replaced
//! only when the request says so, and the image appears whole or not at all.

use super::state::{RenderJob, Shared};
use super::view::Eye;
use crate::commands::provenance::{self, Source};
use render::film::{check_output_path, write_image, ImageWriteError};
use render::renderer::{render, Goal, Part};
use render::scene::Scene;
use spacetime::Spacetime;
use std::any::Any;
use std::panic::AssertUnwindSafe;
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
/// render is already running or, without `overwrite`, `output` exists; returns the job's id.
pub fn start(
    shared: &Arc<Shared>,
    scene: Scene,
    source: Source,
    output: PathBuf,
    overwrite: bool,
) -> Result<u64, String> {
    // `symlink_metadata`: a link is something that exists, even one that leads nowhere.
    if !overwrite && output.symlink_metadata().is_ok() {
        return Err(format!(
            "{} already exists: choose another name, or tick \"replace\" (\"overwrite\": true) to replace it",
            output.display()
        ));
    }
    let id = {
        let mut inner = shared.lock();
        if inner.job.as_ref().is_some_and(|j| j.state == "running") {
            return Err("a render is already running; wait until it has written its image".into());
        }
        let id = inner.job.as_ref().map_or(1, |j| j.id + 1);
        inner.job = Some(RenderJob {
            id,
            output: output.display().to_string(),
            state: "running",
            progress: 0.0,
            message: String::new(),
        });
        id
    };
    let shared = Arc::clone(shared);
    std::thread::spawn(move || {
        // A panic in the render (a film too large for the memory, say) must end the job as a
        // failure rather than leave it "running" forever, refusing every later render. (This
        // needs `panic = "unwind"`, the default, which the release profile keeps.)
        let result = std::panic::catch_unwind(AssertUnwindSafe(|| write(&shared, &scene, &source, &output, overwrite)))
            .unwrap_or_else(|panic| Err(format!("the render failed: {}", panic_message(panic.as_ref()))));
        let mut inner = shared.lock();
        if let Some(job) = inner.job.as_mut() {
            (job.state, job.progress, job.message) = match result {
                Ok(summary) => ("done", 1.0, summary),
                Err(e) => ("failed", job.progress, e),
            };
        }
    });
    Ok(id)
}

/// The spacetime's type and parameters, as `[spacetime]` (or `[views.NAME.spacetime]`) writes them.
fn spacetime_json(spacetime: &Spacetime) -> serde_json::Value {
    let mut fields = serde_json::Map::new();
    fields.insert("type".into(), spacetime.name().into());
    for p in spacetime.parameters() {
        fields.insert(p.name.into(), p.value.into());
    }
    serde_json::Value::Object(fields)
}

/// What a panic said, without the thread, file and line the terminal shows.
fn panic_message(panic: &(dyn Any + Send)) -> &str {
    match (panic.downcast_ref::<String>(), panic.downcast_ref::<&str>()) {
        (Some(message), _) => message,
        (None, Some(message)) => message,
        (None, None) => "an internal error",
    }
}

fn write(shared: &Shared, scene: &Scene, source: &Source, output: &Path, overwrite: bool) -> Result<String, String> {
    let never = AtomicBool::new(false);
    let progress = |done: u64, total: u64| {
        if let Some(job) = shared.lock().job.as_mut() {
            job.progress = done as f64 / total.max(1) as f64;
        }
    };
    let (film, stats) = render(scene, &never, &progress);
    let mut metadata = provenance::metadata(scene, source, Goal::spp(scene.settings.spp), Part::WHOLE, &stats);
    metadata.insert("spacetime".into(), spacetime_json(&scene.spacetime).to_string());
    if let Some(eye) = Eye::of(scene) {
        metadata.insert("camera".into(), serde_json::json!(eye).to_string());
    }
    let shown = output.display();
    let cannot = |e: std::io::Error| format!("cannot write image '{shown}': {e}");
    // The image is written whole under a temporary name beside the output (with its extension,
    // which picks the format) and only then takes the output's name, so that no reader ever
    // sees half an image and a failure leaves the folder as it was (the temporary is removed
    // when `temporary` is dropped).
    let (Some(folder), Some(extension)) = (output.parent(), output.extension()) else {
        return Err(format!("cannot write image '{shown}': it names no file in a folder"));
    };
    let mut suffix = std::ffi::OsString::from(".");
    suffix.push(extension);
    let temporary =
        tempfile::Builder::new().prefix(".nullpath-render-").suffix(&suffix).tempfile_in(folder).map_err(cannot)?;
    let temporary = temporary.into_temp_path();
    write_image(&film, &temporary, &scene.settings.tonemap, &metadata).map_err(|e| match e {
        // The error names the temporary; the user knows the output.
        ImageWriteError::Io { source, .. } => cannot(source),
        ImageWriteError::Encode { source, .. } => format!("cannot write image '{shown}': {source}"),
        other => other.to_string(),
    })?;
    let placed = if overwrite { temporary.persist(output) } else { temporary.persist_noclobber(output) };
    placed.map_err(|e| match e.error.kind() {
        std::io::ErrorKind::AlreadyExists => {
            format!("{shown} was created while rendering; it is left as it is and the render is not kept")
        }
        _ => cannot(e.error),
    })?;
    Ok(format!("wrote {shown}: {}", crate::commands::render::summary(&stats, scene)))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_spacetime_is_recorded_as_a_scene_file_writes_it() {
        let kerr = Spacetime::kerr(0.6, 0.5).expect("valid");
        assert_eq!(spacetime_json(&kerr), serde_json::json!({ "type": "kerr", "mass": 0.6, "spin": 0.5 }));
    }

    #[test]
    fn outputs_are_plain_image_names() {
        let dir = std::env::temp_dir();
        assert_eq!(output_path(&dir, "view.png"), Ok(dir.join("view.png")));
        for bad in ["", "../x.png", "a/b.png", ".png", "x.txt", "x png", "x.png\n"] {
            assert!(output_path(&dir, bad).is_err(), "{bad:?}");
        }
    }
}

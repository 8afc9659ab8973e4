//! # nullpath scene files
//!
//! A scene file is TOML: a spacetime, a camera, render settings, skies, named materials and a list
//! of objects. [`load`] and [`parse`] turn one into a ready-to-render [`render::scene::Scene`];
//! the format is documented, element by element, in `docs/scene-format.md`.
//!
//! ```
//! let text = r#"
//! [camera]
//! position = [0, 1, 6]
//! look_at = [0, 1, 0]
//! fov = 40
//!
//! [[objects]]
//! shape = { type = "sphere", center = [0, 1, 0], radius = 1 }
//! material = { type = "diffuse", reflectance = [0.8, 0.2, 0.2] }
//! "#;
//! let scene = scene::parse(text, "example.toml", std::path::Path::new("."))?;
//! assert_eq!(scene.world.objects(spacetime::Region::Upper).len(), 1);
//! # Ok::<(), scene::SceneError>(())
//! ```
//!
//! Every error is a [`SceneError`] naming the file, the line and column, and the field:
//!
//! ```
//! let err = scene::parse("[camera]\nposition = [0, 0, 0]\nlook_at = [0, 0, -1]\nfov = 200\n", "s.toml", ".".as_ref())
//!     .unwrap_err();
//! assert_eq!(err.to_string(), "s.toml:4:7: camera.fov: must be in (0, 180) degrees, got 200");
//! ```
//!
//! Unknown keys are errors everywhere (a misspelt key would otherwise be silently ignored), and no
//! input makes the loader panic.
//!
//! The files a scene names (meshes, images, glTF files and the files those name) are read in one
//! place, [`files`], under one policy ([`files::ReadPolicy`]): inside the scene file's folder
//! tree, or a folder that [`load_allowing`] is given; regular files only, of bounded size.

mod build;
pub mod edit;
mod error;
pub mod files;
mod nesting;
mod reader;

pub use build::spacetime_table;
pub use error::SceneError;

use error::io_message;
use files::ReadPolicy;
use reader::Doc;
use spacetime::metric::{MetricDescriptor, SPACETIMES};
use std::path::{Path, PathBuf};
use toml::de::DeTable;

/// Reads and builds the scene file at `path`. Relative paths inside it (OBJ meshes, image
/// textures, equirectangular skies, glTF files) are resolved against the directory that holds it,
/// and only files inside that directory's tree are read.
pub fn load(path: &Path) -> Result<render::scene::Scene, SceneError> {
    load_view(path, None)
}

/// As [`load`], seen from the scene's view `view` (a `[views.NAME]` camera) instead of its
/// `[camera]` when given.
pub fn load_view(path: &Path, view: Option<&str>) -> Result<render::scene::Scene, SceneError> {
    load_allowing(path, view, &[])
}

/// As [`load_view`], letting the scene read files inside the folders `allow_read` (and below
/// them) too, besides its own folder's tree: the person rendering widens the policy, not the
/// scene file.
pub fn load_allowing(
    path: &Path,
    view: Option<&str>,
    allow_read: &[PathBuf],
) -> Result<render::scene::Scene, SceneError> {
    let text = read_text(path)?;
    parse_allowing(&text, &path.display().to_string(), folder_of(path), view, allow_read)
}

/// The text of the scene file at `path`, or why it cannot be read (not there, not UTF-8: the
/// error names the first invalid byte's line and column).
pub fn read_text(path: &Path) -> Result<String, SceneError> {
    let origin = path.display().to_string();
    let bytes =
        std::fs::read(path).map_err(|e| SceneError::file(&origin, format!("cannot read: {}", io_message(&e))))?;
    String::from_utf8(bytes).map_err(|e| {
        let valid = e.utf8_error().valid_up_to();
        let bytes = e.into_bytes();
        let prefix = String::from_utf8_lossy(&bytes[..valid]);
        SceneError::at(&origin, &prefix, valid, None, "not valid UTF-8 text (TOML files must be UTF-8)")
    })
}

/// The folder the files named by the scene file at `path` are resolved against, and read
/// inside of: the one that holds it.
pub fn folder_of(path: &Path) -> &Path {
    match path.parent() {
        Some(dir) if !dir.as_os_str().is_empty() => dir,
        _ => Path::new("."),
    }
}

/// As [`parse_view`], letting the scene read files inside the folders `allow_read` (and below
/// them) too, besides `base_dir`'s tree: what [`load_allowing`] does with a file's text.
pub fn parse_allowing(
    text: &str,
    origin: &str,
    base_dir: &Path,
    view: Option<&str>,
    allow_read: &[PathBuf],
) -> Result<render::scene::Scene, SceneError> {
    let mut policy = ReadPolicy::new(base_dir);
    for dir in allow_read {
        policy = policy
            .allow(dir)
            .map_err(|e| SceneError::file(origin, format!("cannot allow reading '{}': {e}", dir.display())))?;
    }
    parse_with(text, origin, base_dir, &policy, view, SPACETIMES)
}

/// Builds the scene described by `text`. `origin` names it in error messages (a path, or e.g.
/// `"<default scene>"`); relative paths inside it are resolved against `base_dir`, and only files
/// inside `base_dir`'s tree are read.
pub fn parse(text: &str, origin: &str, base_dir: &Path) -> Result<render::scene::Scene, SceneError> {
    parse_view(text, origin, base_dir, None)
}

/// As [`parse`], seen from the view `view` (a `[views.NAME]` camera) when given.
pub fn parse_view(
    text: &str,
    origin: &str,
    base_dir: &Path,
    view: Option<&str>,
) -> Result<render::scene::Scene, SceneError> {
    parse_with(text, origin, base_dir, &ReadPolicy::new(base_dir), view, SPACETIMES)
}

/// The spacetime of `text`, a document holding only a `[spacetime]` table, read and checked as
/// a scene file's (the same keys, defaults and messages), with its symmetry axis in the world:
/// for programs that want a spacetime, such as the Python package, without a scene.
pub fn parse_spacetime(text: &str, origin: &str) -> Result<(spacetime::Spacetime, render::geometry::Vec3), SceneError> {
    let root = parse_document(text, origin)?;
    build::spacetime_alone(&Doc { origin, text }, &root)
}

/// `text` parsed as TOML, its nesting bounded first.
fn parse_document<'t>(text: &'t str, origin: &str) -> Result<toml::Spanned<DeTable<'t>>, SceneError> {
    if let Some(offset) = nesting::too_deep(text) {
        let message = format!(
            "invalid TOML: brackets nested more than {} levels deep (no scene needs as many)",
            nesting::MAX_NESTING
        );
        return Err(SceneError::at(origin, text, offset, None, message));
    }
    DeTable::parse(text).map_err(|e| {
        let offset = e.span().map_or(0, |s| s.start);
        SceneError::at(origin, text, offset, None, format!("invalid TOML: {}", e.message().trim_end()))
    })
}

/// As [`parse`], the `[spacetime]` type one of `metrics` instead of the built-in metrics
/// ([`SPACETIMES`]) or a metric written in the file: how a test shows that a metric's
/// descriptor is all the reader needs.
pub fn parse_with_metrics(
    text: &str,
    origin: &str,
    base_dir: &Path,
    metrics: &[&MetricDescriptor],
) -> Result<render::scene::Scene, SceneError> {
    parse_with(text, origin, base_dir, &ReadPolicy::new(base_dir), None, metrics)
}

/// As [`parse_view`], reading files under `policy`, the `[spacetime]` type one of `metrics`.
fn parse_with(
    text: &str,
    origin: &str,
    base_dir: &Path,
    policy: &ReadPolicy,
    view: Option<&str>,
    metrics: &[&MetricDescriptor],
) -> Result<render::scene::Scene, SceneError> {
    let root = parse_document(text, origin)?;
    let doc = Doc { origin, text };
    build::scene(&doc, &root, base_dir, policy, view, metrics)
}

/// The names of the `[views.NAME]` cameras in the scene text `text`, in file order; empty when
/// it has none or is not valid TOML (which [`parse`] reports).
pub fn view_names(text: &str) -> Vec<String> {
    if nesting::too_deep(text).is_some() {
        return Vec::new();
    }
    let Ok(root) = DeTable::parse(text) else {
        return Vec::new();
    };
    let Some(toml::de::DeValue::Table(views)) = root.get_ref().get("views").map(|v| v.get_ref()) else {
        return Vec::new();
    };
    let mut names: Vec<_> = views.keys().map(|k| (k.span().start, k.get_ref().to_string())).collect();
    names.sort();
    names.into_iter().map(|(_, name)| name).collect()
}

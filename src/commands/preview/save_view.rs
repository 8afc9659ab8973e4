//! "Save view": writes the preview's camera into the scene file as a `[views.NAME]` table, with
//! the sliders' spacetime parameters as `[views.NAME.spacetime]` where they differ from the
//! file's (docs/scene-format.md), so that `nullpath render --view NAME` renders what the page
//! shows. The edit goes through
//! `scene::edit` (`toml_edit`), which keeps the rest of the file — comments, order, spacing — as the user wrote
//! it; the file is written only if the edited text still loads, from the new view, and it is
//! replaced atomically: a reader (the file watcher, an editor) sees the old file or the new one,
//! never half of one, and a failed write (a full disk) leaves the old one as it was.

use super::view::Eye;
use render::camera::Projection;
use render::scene::Scene;
use scene::edit::{value, Array, Item, Table};
use spacetime::Spacetime;
use std::io::Write as _;
use std::path::Path;

/// Longest view name.
const MAX_NAME: usize = 64;

/// Checks a view name: 1 to 64 ASCII letters, digits, `_` or `-` (a bare TOML key).
pub fn check_name(name: &str) -> Result<(), String> {
    let bare = name.chars().all(|c| c.is_ascii_alphanumeric() || c == '_' || c == '-');
    if name.is_empty() || name.len() > MAX_NAME || !bare {
        return Err(format!("a view name is 1 to {MAX_NAME} letters, digits, '_' or '-', got {name:?}"));
    }
    Ok(())
}

/// A number for the file: rounded to 6 significant decimals, so that a pose reads as written.
fn rounded(x: f64) -> f64 {
    if x == 0.0 {
        return 0.0;
    }
    let scale = 10f64.powi(5 - x.abs().log10().floor() as i32);
    let r = (x * scale).round() / scale;
    if r.is_finite() {
        r
    } else {
        x
    }
}

fn vector(v: [f64; 3]) -> Item {
    value(v.iter().map(|&c| rounded(c)).collect::<Array>())
}

/// `text` (a scene file, whose spacetime is `file`) with the view `name` set to `eye`, seen
/// through `scene`'s projection from the camera's region, in `scene`'s spacetime; an existing
/// view of that name is replaced.
pub fn with_view(text: &str, name: &str, eye: &Eye, scene: &Scene, file: &Spacetime) -> Result<String, String> {
    check_name(name)?;
    let mut view = Table::new();
    view.insert("position", vector(eye.position));
    view.insert("look_at", vector(eye.look_at));
    view.insert("up", vector(eye.up));
    match scene.camera.projection {
        Projection::Perspective(_) => {
            view.insert("fov", value(rounded(eye.fov)));
        }
        Projection::Equirectangular(_) => {
            view.insert("projection", value("equirectangular"));
        }
        Projection::Fisheye(f) => {
            view.insert("projection", value("fisheye"));
            view.insert("fisheye_fov", value(rounded(f.fov_degrees())));
        }
        Projection::Ods(o) => {
            view.insert("projection", value("ods"));
            view.insert("ipd", value(rounded(o.ipd())));
        }
    }
    if scene.camera.region == spacetime::Region::Lower {
        view.insert("region", value("lower"));
    }
    // Every parameter, not only those moved, so that the view shows this spacetime even after
    // `[spacetime]` is edited; exactly, not rounded as the pose is, since a rounded spin may
    // exceed a rounded mass. A view in the file's own spacetime follows `[spacetime]`.
    if scene.spacetime != *file {
        let mut parameters = Table::new();
        for p in scene.spacetime.parameters() {
            parameters.insert(p.name, value(p.value));
        }
        view.insert("spacetime", Item::Table(parameters));
    }
    scene::edit::with_fields(text, &["views"], vec![(name.to_owned(), Some(Item::Table(view)))])
}

/// Why a view was not saved.
#[derive(Debug)]
pub enum SaveError {
    /// Not as asked: a bad name, a file that is not TOML, a view that would not load.
    Refused(String),
    /// The file could not be read or replaced (a full disk, a read-only folder): the machine's
    /// fault, not the request's.
    Io(String),
}

/// Saves `eye` as the view `name` of the scene file at `path`, in `scene`'s spacetime (the
/// file's is `file`); the edited file must load from it. The caller keeps other writers of the
/// file out until it returns.
pub fn save(path: &Path, name: &str, eye: &Eye, scene: &Scene, file: &Spacetime) -> Result<(), SaveError> {
    let shown = path.display();
    let text = std::fs::read_to_string(path).map_err(|e| SaveError::Io(format!("cannot read {shown}: {e}")))?;
    let edited = with_view(&text, name, eye, scene, file).map_err(SaveError::Refused)?;
    let base = match path.parent() {
        Some(dir) if !dir.as_os_str().is_empty() => dir,
        _ => Path::new("."),
    };
    scene::parse_view(&edited, &shown.to_string(), base, Some(name))
        .map_err(|e| SaveError::Refused(format!("the view would not load, so the file is left as it was: {e}")))?;
    replace(path, &edited).map_err(|e| SaveError::Io(format!("cannot write {shown}: {e}; the file is left as it was")))
}

/// Replaces the file at `path` (the file a symbolic link leads to, where it is one) with `text`:
/// written to a temporary in its folder (a rename does not cross file systems) with its
/// permissions, flushed to the disk, then renamed over it. The temporary is removed if anything
/// fails.
fn replace(path: &Path, text: &str) -> std::io::Result<()> {
    let path = std::fs::canonicalize(path)?;
    let (Some(folder), Some(name)) = (path.parent(), path.file_name()) else {
        return Err(std::io::Error::other("the path names no file"));
    };
    let permissions = std::fs::metadata(&path)?.permissions();
    let mut prefix = std::ffi::OsString::from(".");
    prefix.push(name);
    prefix.push(".");
    let mut temporary = tempfile::Builder::new().prefix(&prefix).suffix(".partial").tempfile_in(folder)?;
    temporary.write_all(text.as_bytes())?;
    temporary.as_file().set_permissions(permissions)?;
    temporary.as_file().sync_all()?;
    temporary.persist(&path).map_err(|e| e.error)?;
    // The rename itself is on the disk once the folder is; where folders cannot be synced, the
    // file is replaced all the same.
    if let Ok(folder) = std::fs::File::open(folder) {
        let _ = folder.sync_all();
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::commands::preview::view::Overrides;

    const TEXT: &str = "# my room\n[camera]   # where I stand\nposition = [0, 0, 7]\nlook_at = [0, 0, 0]\n\n\
                        [[objects]]\nshape = { type = \"sphere\", center = [0, 0, 0], radius = 1 }\n";

    fn eye() -> Eye {
        Eye { position: [1.0, 2.0, 3.0000000001], look_at: [0.0; 3], up: [0.0, 1.0, 0.0], fov: 35.0 }
    }

    #[test]
    fn a_view_is_added_and_the_rest_kept() {
        let scene = scene::parse(TEXT, "t.toml", ".".as_ref()).expect("valid");
        let edited = with_view(TEXT, "corner", &eye(), &scene, &scene.spacetime).expect("edits");
        assert!(edited.starts_with(TEXT), "the user's text is kept as written:\n{edited}");
        assert!(edited.contains("[views.corner]\nposition = [1.0, 2.0, 3.0]\n"), "{edited}");
        let seen = scene::parse_view(&edited, "t.toml", ".".as_ref(), Some("corner")).expect("loads");
        assert!((seen.camera.position - render::geometry::Vec3::new(1.0, 2.0, 3.0)).length() < 1e-12);
        let again = with_view(&edited, "corner", &Eye { fov: 20.0, ..eye() }, &scene, &scene.spacetime).expect("edits");
        assert_eq!(scene::view_names(&again), ["corner"], "replaced, not added twice");
        assert!(again.contains("fov = 20.0"), "{again}");
    }

    #[test]
    fn the_sliders_spacetime_is_saved_with_the_view() {
        let text = format!("[spacetime]\ntype = \"kerr\"\nmass = 0.3\nspin = 0.1\n{TEXT}");
        let file = scene::parse(&text, "t.toml", ".".as_ref()).expect("valid");
        let overrides = Overrides {
            eye: Some(eye()),
            parameters: [("mass".to_string(), 0.603), ("spin".to_string(), 0.5)].into(),
            spp: None,
        };
        let shown = overrides.apply(&file).expect("in range");
        let edited = with_view(&text, "heavy", &eye(), &shown, &file.spacetime).expect("edits");
        assert!(edited.contains("[views.heavy.spacetime]\nmass = 0.603\nspin = 0.5\n"), "{edited}");
        let seen = scene::parse_view(&edited, "t.toml", ".".as_ref(), Some("heavy")).expect("loads");
        assert_eq!(seen.spacetime, shown.spacetime, "the view renders the spacetime the page shows");
        assert_eq!(scene::parse(&edited, "t.toml", ".".as_ref()).expect("loads").spacetime, file.spacetime);
        // In the file's own spacetime, the view has none of its own.
        let plain = with_view(&text, "plain", &eye(), &file, &file.spacetime).expect("edits");
        assert!(!plain.contains("[views.plain.spacetime]"), "{plain}");
        // A hand-written view's spacetime is checked as [spacetime] is.
        let spun = edited.replace("spin = 0.5", "spin = 0.7");
        let error = scene::parse(&spun, "t.toml", ".".as_ref()).expect_err("|spin| > mass").to_string();
        assert!(error.contains("views.heavy.spacetime") && error.contains("spin"), "{error}");
    }

    #[test]
    fn bad_names_are_refused() {
        let scene = scene::parse(TEXT, "t.toml", ".".as_ref()).expect("valid");
        for name in ["", "a b", "x]\n[camera", "é", &"v".repeat(65)] {
            assert!(with_view(TEXT, name, &eye(), &scene, &scene.spacetime).is_err(), "{name:?}");
        }
    }

    #[cfg(unix)]
    #[test]
    fn the_file_is_replaced_whole_with_its_permissions_through_links() {
        use std::os::unix::fs::PermissionsExt;
        let dir = std::env::temp_dir().join(format!("nullpath-save-view-replace-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(&dir).expect("temporary directory");
        let file = dir.join("scene.toml");
        std::fs::write(&file, "old, and longer than the new text").expect("written");
        std::fs::set_permissions(&file, std::fs::Permissions::from_mode(0o604)).expect("chmod");
        let link = dir.join("link.toml");
        std::os::unix::fs::symlink("scene.toml", &link).expect("link");

        replace(&link, "new").expect("replaced");
        assert_eq!(std::fs::read_to_string(&file).expect("readable"), "new");
        assert_eq!(std::fs::metadata(&file).expect("exists").permissions().mode() & 0o777, 0o604);
        assert!(std::fs::symlink_metadata(&link).expect("exists").file_type().is_symlink(), "the link is kept");
        let mut names: Vec<_> =
            std::fs::read_dir(&dir).expect("listed").map(|e| e.expect("entry").file_name()).collect();
        names.sort();
        assert_eq!(names, ["link.toml", "scene.toml"], "no temporary is left");
        std::fs::remove_dir_all(&dir).expect("removed");
    }
}

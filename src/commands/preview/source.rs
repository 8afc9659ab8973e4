//! Where the previewed scene comes from (a file, or the built-in default scene) and the watch on
//! the file: it is read again whenever its modification time or size changes.

use super::state::Shared;
use crate::commands::render::{load_scene, DEFAULT_SCENE_NAME};
use render::scene::Scene;
use std::path::{Path, PathBuf};
use std::time::{Duration, SystemTime};

/// How often the file is checked for changes.
const POLL: Duration = Duration::from_millis(200);

pub struct Source {
    /// The scene file; `None` for the default scene.
    pub path: Option<PathBuf>,
}

impl Source {
    /// The name the page shows.
    pub fn name(&self) -> String {
        self.path.as_ref().map_or_else(|| DEFAULT_SCENE_NAME.to_string(), |p| p.display().to_string())
    }

    /// The scene as the file has it now, or the error as the command line prints it.
    pub fn load(&self) -> Result<Scene, String> {
        load_scene(self.path.as_deref(), None)
    }

    /// The directory relative file names are in: the scene file's, else the working directory.
    pub fn directory(&self) -> &Path {
        match self.path.as_deref().and_then(Path::parent) {
            Some(dir) if !dir.as_os_str().is_empty() => dir,
            _ => Path::new("."),
        }
    }

    /// What tells a changed file from the one last read.
    fn stamp(&self) -> Option<(SystemTime, u64)> {
        let metadata = std::fs::metadata(self.path.as_ref()?).ok()?;
        Some((metadata.modified().ok()?, metadata.len()))
    }

    /// Reloads the scene into `shared` whenever the file changes, forever (returns at once for
    /// the default scene, which cannot change).
    pub fn watch(&self, shared: &Shared) {
        if self.path.is_none() {
            return;
        }
        let mut last = self.stamp();
        loop {
            std::thread::sleep(POLL);
            let now = self.stamp();
            if now != last {
                last = now;
                shared.reload(self.load());
            }
        }
    }
}

//! The files a command reads and writes, each in its role (the scene file, `--resume`, the
//! image, the checkpoint, `--stats`, a merge's parts), checked before any work is done: no file
//! it writes may be one it reads or another it writes, since writing it would destroy the
//! other. Paths are compared as files, not as text: `a.exr`, `./a.exr` and `out/../a.exr` are
//! one file, and so are a link (symbolic or hard) and what it links to.

use std::path::{Path, PathBuf};

/// A file's identity: its canonical path (that of its directory, with its name, for a file yet
/// to be made) and, for a file that exists, its device and inode.
#[derive(Debug)]
struct FileId {
    canonical: PathBuf,
    inode: Option<(u64, u64)>,
}

impl FileId {
    fn of(path: &Path) -> Self {
        let canonical = std::fs::canonicalize(path).unwrap_or_else(|_| {
            let directory = path.parent().filter(|d| !d.as_os_str().is_empty()).unwrap_or(Path::new("."));
            match (std::fs::canonicalize(directory), path.file_name()) {
                (Ok(directory), Some(name)) => directory.join(name),
                // No such directory (refused later, as an unwritable path) or no file name
                // (`..`): compared as the path spelled out.
                _ => std::path::absolute(path).unwrap_or_else(|_| path.to_owned()),
            }
        });
        Self { canonical, inode: inode(path) }
    }

    fn is(&self, other: &FileId) -> bool {
        self.canonical == other.canonical || self.inode.is_some_and(|i| other.inode == Some(i))
    }
}

#[cfg(unix)]
fn inode(path: &Path) -> Option<(u64, u64)> {
    use std::os::unix::fs::MetadataExt;
    std::fs::metadata(path).ok().map(|m| (m.dev(), m.ino()))
}

#[cfg(not(unix))]
fn inode(_: &Path) -> Option<(u64, u64)> {
    None
}

/// Whether `a` and `b` name the same file.
pub fn same_file(a: &Path, b: &Path) -> bool {
    FileId::of(a).is(&FileId::of(b))
}

/// One file in its role.
struct Entry {
    role: String,
    path: PathBuf,
    id: FileId,
    written: bool,
}

/// The files of one command, recorded in turn, each written one checked against all before it.
#[derive(Default)]
pub struct Files {
    entries: Vec<Entry>,
}

impl Files {
    /// Records `path`, which the command reads as `role` (e.g. "the scene file"). Reading one
    /// file in two roles harms nothing, so this refuses nothing.
    pub fn reads(&mut self, role: impl Into<String>, path: &Path) {
        self.entries.push(Entry { role: role.into(), path: path.to_owned(), id: FileId::of(path), written: false });
    }

    /// Records `path`, which the command writes as `role` (e.g. "--stats"), refusing it if it is
    /// a file recorded before, read or written, and naming both roles.
    pub fn writes(&mut self, role: impl Into<String>, path: &Path) -> Result<(), String> {
        let entry = Entry { role: role.into(), path: path.to_owned(), id: FileId::of(path), written: true };
        if let Some(other) = self.entries.iter().find(|other| other.id.is(&entry.id)) {
            let consequence = if other.written {
                "one would overwrite the other"
            } else {
                "writing it would destroy what this command reads"
            };
            return Err(format!(
                "{} '{}' is the same file as {} '{}': {consequence}; choose another path for {}",
                entry.role,
                entry.path.display(),
                other.role,
                other.path.display(),
                entry.role
            ));
        }
        self.entries.push(entry);
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A fresh directory, with a subdirectory `sub`, for one test.
    fn temp_dir(name: &str) -> PathBuf {
        let dir = std::env::temp_dir().join(format!("nullpath-files-{}-{name}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(dir.join("sub")).expect("temp directory");
        dir
    }

    #[test]
    fn spellings_and_links_of_one_file_are_one_file() {
        let dir = temp_dir("spellings");
        let scene = dir.join("scene.toml");
        std::fs::write(&scene, "x").expect("scene");
        // Existing and new files, through `.` and `..`.
        assert!(same_file(&scene, &dir.join("sub/../scene.toml")));
        assert!(same_file(&dir.join("new.exr"), &dir.join("./sub/../new.exr")));
        assert!(!same_file(&dir.join("new.exr"), &dir.join("sub/new.exr")));
        // Relative to the current directory, as users type them.
        assert!(same_file(Path::new("a.exr"), Path::new("./a.exr")));
        #[cfg(unix)]
        {
            std::os::unix::fs::symlink(&scene, dir.join("symbolic.toml")).expect("symlink");
            std::fs::hard_link(&scene, dir.join("hard.toml")).expect("hard link");
            assert!(same_file(&dir.join("symbolic.toml"), &scene));
            assert!(same_file(&dir.join("hard.toml"), &scene));
        }
        std::fs::remove_dir_all(&dir).expect("cleaned up");
    }

    #[test]
    fn a_written_file_may_be_no_other_file_and_the_message_names_both_roles() {
        let dir = temp_dir("roles");
        let scene = dir.join("scene.toml");
        std::fs::write(&scene, "x").expect("scene");
        let mut files = Files::default();
        files.reads("the scene file", &scene);
        files.reads("--resume", &dir.join("state.exr"));
        // Two roles reading one file is fine.
        files.reads("a part file", &dir.join("state.exr"));
        files.writes("the image (-o)", &dir.join("image.exr")).expect("a new file");
        let err = files.writes("--stats", &dir.join("sub/../scene.toml")).expect_err("the scene");
        assert!(err.contains("--stats") && err.contains("the scene file") && err.contains("destroy"), "{err}");
        let err = files.writes("--checkpoint", &dir.join("./image.exr")).expect_err("the image");
        assert!(err.contains("--checkpoint") && err.contains("the image (-o)") && err.contains("overwrite"), "{err}");
        let err = files.writes("--stats", &dir.join("state.exr")).expect_err("the checkpoint read");
        assert!(err.contains("--resume"), "{err}");
        std::fs::remove_dir_all(&dir).expect("cleaned up");
    }
}

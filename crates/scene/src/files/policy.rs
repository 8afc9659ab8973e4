//! Files that scene files name (meshes, textures, skies, glTF files and their buffers and
//! images), read under one policy, because whoever wrote the scene may not be whoever renders it.
//!
//! - A path resolves relative to the folder of the file that names it, and the file it reaches
//!   (after `..`, symbolic links and, in glTF URIs, percent-decoding, which the caller does) must
//!   lie inside one of the policy's folders: the scene file's folder tree, and any folder the
//!   person rendering allowed (`nullpath render --allow-read DIR`). An absolute path is held to
//!   the same rule, so it is refused unless it lies in one of those folders.
//! - Only regular files are opened: a directory, device (`/dev/zero`), pipe or socket is refused
//!   from its metadata before it is opened, so that nothing blocks or reads forever.
//! - At most [`MAX_FILE_BYTES`] are read from one file, and a file larger than that is refused
//!   from its size before any of it is read.
//! - Errors say why, never what a file outside the policy holds or how large it is: the caller
//!   names the path as the scene wrote it.
//!
//! [`ReadPolicy::anywhere`] lifts the folder rule (not the others) for paths that the person
//! running nullpath typed themselves.

use std::fmt;
use std::fs::{File, OpenOptions};
use std::io::{self, Read};
use std::path::{Component, Path, PathBuf};

/// The most bytes read from one file: 2 GiB, far beyond any mesh or texture a render can hold
/// many of, and small enough that a file cannot exhaust memory by itself.
pub const MAX_FILE_BYTES: u64 = 1 << 31;

/// Which files may be read: those inside `roots` (all of them when `None`).
#[derive(Clone, Debug)]
pub struct ReadPolicy {
    roots: Option<Vec<PathBuf>>,
}

/// A file as a scene (or a file it names) wrote it, to be read under a [`ReadPolicy`].
#[derive(Clone, Debug)]
pub struct Resource<'p> {
    policy: &'p ReadPolicy,
    /// The folder of the file that names it, joined with the path as written.
    path: PathBuf,
    written: PathBuf,
}

/// Why a file may not or could not be read. Its `Display` is the reason alone: the caller puts
/// the path (as written) in front.
#[derive(Debug)]
pub enum ReadError {
    /// Nothing at that path.
    NotFound,
    /// The path leads outside the folders the policy allows.
    Outside,
    /// A directory, device, pipe or socket.
    NotAFile,
    /// Larger than [`MAX_FILE_BYTES`] (or than the caller's bound).
    TooLarge { limit: u64 },
    /// Shorter than the `needed` bytes the caller was told it holds.
    TooShort { size: u64, needed: u64 },
    /// Any other failure to read it (permissions…).
    Io(io::Error),
}

impl fmt::Display for ReadError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::NotFound => write!(f, "file not found"),
            Self::Outside => write!(
                f,
                "it lies outside the scene's folder, and nullpath reads no file outside it \
                 (to read another folder, allow it with --allow-read DIR)"
            ),
            Self::NotAFile => write!(f, "not a regular file (a folder, device, pipe or socket)"),
            Self::TooLarge { limit } => write!(f, "larger than {limit} bytes, the most nullpath reads from one file"),
            Self::TooShort { size, needed } => write!(f, "holds {size} bytes, fewer than the {needed} declared"),
            Self::Io(e) => write!(f, "{e}"),
        }
    }
}

impl std::error::Error for ReadError {
    fn source(&self) -> Option<&(dyn std::error::Error + 'static)> {
        match self {
            Self::Io(e) => Some(e),
            Self::NotFound | Self::Outside | Self::NotAFile | Self::TooLarge { .. } | Self::TooShort { .. } => None,
        }
    }
}

impl From<io::Error> for ReadError {
    fn from(e: io::Error) -> Self {
        if e.kind() == io::ErrorKind::NotFound {
            Self::NotFound
        } else {
            Self::Io(e)
        }
    }
}

impl ReadPolicy {
    /// Files inside the folder `scene_dir` (that of the scene file) and the folders below it.
    pub fn new(scene_dir: &Path) -> Self {
        Self { roots: Some(vec![scene_dir.to_path_buf()]) }
    }

    /// Any regular file of at most [`MAX_FILE_BYTES`]: for a path typed on the command line, never
    /// for one read from a file.
    pub fn anywhere() -> Self {
        Self { roots: None }
    }

    /// This policy, widened to the folder `dir` and those below it. `dir` must be a folder.
    pub fn allow(mut self, dir: &Path) -> Result<Self, ReadError> {
        if !std::fs::metadata(dir)?.is_dir() {
            return Err(ReadError::Io(io::Error::other("not a folder")));
        }
        if let Some(roots) = &mut self.roots {
            roots.push(dir.to_path_buf());
        }
        Ok(self)
    }

    /// The file `written` (a path as a file wrote it), relative to `dir`, the folder of that file.
    pub fn file(&self, dir: &Path, written: impl AsRef<Path>) -> Resource<'_> {
        let written = written.as_ref().to_path_buf();
        Resource { policy: self, path: dir.join(&written), written }
    }

    /// `path`'s canonical form, if the policy allows it. The lexical test comes first so that a
    /// path outside is refused without looking at it: no error then tells what exists there.
    fn check(&self, path: &Path) -> Result<PathBuf, ReadError> {
        let Some(roots) = &self.roots else {
            return Ok(path.canonicalize()?);
        };
        let named = lexical(path)?;
        let inside_lexically = roots.iter().any(|root| {
            lexical(root).is_ok_and(|r| named.starts_with(r)) || root.canonicalize().is_ok_and(|r| named.starts_with(r))
        });
        if !inside_lexically {
            return Err(ReadError::Outside);
        }
        // Symbolic links may still lead out: the canonical path decides.
        let canonical = path.canonicalize()?;
        if roots.iter().filter_map(|root| root.canonicalize().ok()).any(|root| canonical.starts_with(root)) {
            Ok(canonical)
        } else {
            Err(ReadError::Outside)
        }
    }
}

/// `path` made absolute with `.` and `..` taken away by their names alone, without looking at the
/// file system.
fn lexical(path: &Path) -> io::Result<PathBuf> {
    let mut out = PathBuf::new();
    for component in std::path::absolute(path)?.components() {
        match component {
            Component::ParentDir => {
                out.pop();
            }
            Component::CurDir => {}
            other => out.push(other),
        }
    }
    Ok(out)
}

impl Resource<'_> {
    /// The path as the file that names it wrote it, for messages.
    pub fn written(&self) -> &Path {
        &self.written
    }

    /// The path joined to the naming file's folder: its parent is the folder that paths inside
    /// this file resolve against, and it tells two uses of one file apart from two files.
    pub fn path(&self) -> &Path {
        &self.path
    }

    /// The whole file, at most [`MAX_FILE_BYTES`].
    pub fn read(&self) -> Result<Vec<u8>, ReadError> {
        let (file, size) = self.open()?;
        if size > MAX_FILE_BYTES {
            return Err(ReadError::TooLarge { limit: MAX_FILE_BYTES });
        }
        // The size may change while it is read: read one byte past the limit to notice.
        let mut bytes = Vec::with_capacity(usize::try_from(size).unwrap_or(0));
        file.take(MAX_FILE_BYTES + 1).read_to_end(&mut bytes)?;
        if bytes.len() as u64 > MAX_FILE_BYTES {
            return Err(ReadError::TooLarge { limit: MAX_FILE_BYTES });
        }
        Ok(bytes)
    }

    /// The file's first `needed` bytes; it must hold at least that many, and `needed` is at most
    /// [`MAX_FILE_BYTES`].
    pub fn read_prefix(&self, needed: u64) -> Result<Vec<u8>, ReadError> {
        if needed > MAX_FILE_BYTES {
            return Err(ReadError::TooLarge { limit: MAX_FILE_BYTES });
        }
        let (file, size) = self.open()?;
        if size < needed {
            return Err(ReadError::TooShort { size, needed });
        }
        let mut bytes = Vec::with_capacity(usize::try_from(needed).unwrap_or(0));
        file.take(needed).read_to_end(&mut bytes)?;
        if (bytes.len() as u64) < needed {
            return Err(ReadError::TooShort { size: bytes.len() as u64, needed });
        }
        Ok(bytes)
    }

    /// The file opened for reading, and its size, if the policy allows it and it is a regular
    /// file.
    fn open(&self) -> Result<(File, u64), ReadError> {
        let canonical = self.policy.check(&self.path)?;
        // Checked before opening: opening a pipe with no writer blocks.
        if !std::fs::metadata(&canonical)?.is_file() {
            return Err(ReadError::NotAFile);
        }
        let mut options = OpenOptions::new();
        options.read(true);
        // Should a pipe be put in its place after the check, opening it returns at once.
        #[cfg(unix)]
        std::os::unix::fs::OpenOptionsExt::custom_flags(&mut options, libc::O_NONBLOCK);
        let file = options.open(&canonical)?;
        let metadata = file.metadata()?;
        if !metadata.is_file() {
            return Err(ReadError::NotAFile);
        }
        Ok((file, metadata.len()))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A fresh folder `name` holding `scene/` (the policy's root) and `outside/`, each with a file.
    fn folders(name: &str) -> PathBuf {
        let dir = std::env::temp_dir().join(format!("nullpath-resource-{}-{name}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(dir.join("scene/sub")).unwrap();
        std::fs::create_dir_all(dir.join("outside")).unwrap();
        std::fs::write(dir.join("scene/sub/inside.bin"), b"inside").unwrap();
        std::fs::write(dir.join("outside/secret.bin"), b"secret").unwrap();
        dir
    }

    #[test]
    fn files_inside_the_scene_folder_are_read() {
        let dir = folders("inside");
        let policy = ReadPolicy::new(&dir.join("scene"));
        assert_eq!(policy.file(&dir.join("scene"), "sub/inside.bin").read().unwrap(), b"inside");
        assert_eq!(policy.file(&dir.join("scene/sub"), "../sub/./inside.bin").read().unwrap(), b"inside");
        let absolute = dir.join("scene/sub/inside.bin");
        assert_eq!(policy.file(Path::new("/elsewhere"), &absolute).read().unwrap(), b"inside");
        assert_eq!(policy.file(&dir.join("scene"), "sub/inside.bin").read_prefix(3).unwrap(), b"ins");
        let e = policy.file(&dir.join("scene"), "sub/inside.bin").read_prefix(7).unwrap_err();
        assert!(matches!(e, ReadError::TooShort { size: 6, needed: 7 }), "{e:?}");
        std::fs::remove_dir_all(&dir).ok();
    }

    #[test]
    fn paths_that_leave_the_scene_folder_are_refused() {
        let dir = folders("outside");
        let scene = dir.join("scene");
        let policy = ReadPolicy::new(&scene);
        let outside = dir.join("outside/secret.bin");
        for written in [Path::new("../outside/secret.bin"), Path::new("sub/../../outside/secret.bin"), &outside] {
            let e = policy.file(&scene, written).read().unwrap_err();
            assert!(matches!(e, ReadError::Outside), "{}: {e:?}", written.display());
        }
        // Refused before looking: a missing file outside is no different from one that exists.
        let e = policy.file(&scene, "../outside/missing.bin").read().unwrap_err();
        assert!(matches!(e, ReadError::Outside), "{e:?}");
        assert!(matches!(policy.file(&scene, "/etc/passwd").read().unwrap_err(), ReadError::Outside));
        // A folder that merely starts with the same name is outside too.
        std::fs::create_dir_all(dir.join("scene2")).unwrap();
        std::fs::write(dir.join("scene2/x"), b"x").unwrap();
        assert!(matches!(policy.file(&scene, "../scene2/x").read().unwrap_err(), ReadError::Outside));
        #[cfg(unix)]
        {
            std::os::unix::fs::symlink(&outside, scene.join("link.bin")).unwrap();
            let e = policy.file(&scene, "link.bin").read().unwrap_err();
            assert!(matches!(e, ReadError::Outside), "a link out: {e:?}");
            std::os::unix::fs::symlink(scene.join("sub/inside.bin"), scene.join("in.bin")).unwrap();
            assert_eq!(policy.file(&scene, "in.bin").read().unwrap(), b"inside", "a link within");
        }
        // Allowing the other folder lets it be read, by either path.
        let wider = policy.clone().allow(&dir.join("outside")).unwrap();
        assert_eq!(wider.file(&scene, "../outside/secret.bin").read().unwrap(), b"secret");
        assert_eq!(wider.file(&scene, &outside).read().unwrap(), b"secret");
        assert!(policy.clone().allow(&dir.join("nowhere")).is_err());
        assert!(policy.allow(&outside).is_err(), "a file is not a folder");
        std::fs::remove_dir_all(&dir).ok();
    }

    #[cfg(unix)]
    #[test]
    fn only_regular_files_are_opened() {
        let dir = folders("special");
        let scene = dir.join("scene");
        let fifo = scene.join("pipe");
        let made = std::process::Command::new("mkfifo").arg(&fifo).status().unwrap();
        assert!(made.success());
        let policy = ReadPolicy::new(&scene);
        assert!(matches!(policy.file(&scene, "pipe").read().unwrap_err(), ReadError::NotAFile));
        assert!(matches!(policy.file(&scene, "sub").read().unwrap_err(), ReadError::NotAFile));
        std::os::unix::fs::symlink("/dev/zero", scene.join("zero")).unwrap();
        // A link inside to a device in an allowed folder: refused for what it leads to.
        let e = policy.clone().allow(Path::new("/dev")).unwrap().file(&scene, "zero").read().unwrap_err();
        assert!(matches!(e, ReadError::NotAFile), "{e:?}");
        let anywhere = ReadPolicy::anywhere();
        assert!(matches!(anywhere.file(&scene, "/dev/zero").read().unwrap_err(), ReadError::NotAFile));
        assert!(matches!(anywhere.file(&scene, "pipe").read_prefix(4).unwrap_err(), ReadError::NotAFile));
        assert!(matches!(anywhere.file(&scene, "missing").read().unwrap_err(), ReadError::NotFound));
        let e = anywhere.file(&scene, "sub/inside.bin").read_prefix(MAX_FILE_BYTES + 1).unwrap_err();
        assert!(matches!(e, ReadError::TooLarge { .. }), "{e:?}");
        std::fs::remove_dir_all(&dir).ok();
    }
}

//! The bytes a glTF file's URIs point at: a `data:` URI's own, or a file's, read under the
//! scene's read policy (see [`crate::files::policy`]) relative to the glTF file's folder.
//!
//! A URI that is not `data:` is percent-decoded before the policy sees it, so that `%2E%2E/`
//! is the `../` it means and cannot slip past. `file:` URIs name absolute paths, which the policy
//! refuses unless they lie in a folder it allows; other schemes (`http:`…) are refused.

use super::contained;
use crate::files::policy::{ReadError, ReadPolicy};
use std::path::{Path, PathBuf};

/// Where the files a glTF file names are read from, and under which policy.
#[derive(Clone, Copy)]
pub(super) struct Sources<'a> {
    /// The glTF file's folder.
    pub dir: &'a Path,
    pub policy: &'a ReadPolicy,
}

/// What a URI points at.
enum Target {
    /// A `data:` URI's decoded bytes.
    Data(Vec<u8>),
    /// A file, as a path relative to the glTF file's folder or absolute.
    File(PathBuf),
}

impl Sources<'_> {
    /// All the bytes `uri` points at.
    pub(super) fn read(&self, uri: &str) -> Result<Vec<u8>, String> {
        match target(uri)? {
            Target::Data(bytes) => Ok(bytes),
            Target::File(path) => self.policy.file(self.dir, path).read().map_err(cannot_read),
        }
    }

    /// The first `length` bytes `uri` points at, which must hold at least that many.
    pub(super) fn read_prefix(&self, uri: &str, length: usize) -> Result<Vec<u8>, String> {
        match target(uri)? {
            Target::Data(mut bytes) => {
                if bytes.len() < length {
                    return Err(format!("its data: URI holds {} bytes, fewer than the {length} declared", bytes.len()));
                }
                bytes.truncate(length);
                Ok(bytes)
            }
            Target::File(path) => self.policy.file(self.dir, path).read_prefix(length as u64).map_err(cannot_read),
        }
    }
}

/// `cannot read: why`.
fn cannot_read(e: ReadError) -> String {
    format!("cannot read: {e}")
}

/// What `uri` points at; `data:` URIs are decoded.
fn target(uri: &str) -> Result<Target, String> {
    if uri.starts_with("data:") {
        // The gltf crate decodes it; given no folder, it reads no file whatever the URI says.
        let data = contained(|| gltf::buffer::Data::from_source(gltf::buffer::Source::Uri(uri), None), "a data: URI")?
            .map_err(|e| format!("cannot decode its data: URI: {e}"))?;
        return Ok(Target::Data(data.0));
    }
    let path = if let Some(rest) = uri.strip_prefix("file://") {
        if !rest.starts_with('/') {
            return Err("a file: URI naming a host is not supported".to_string());
        }
        rest
    } else if let Some(rest) = uri.strip_prefix("file:") {
        rest
    } else if has_scheme(uri) {
        return Err("only data: URIs and paths are read, not URIs of other schemes".to_string());
    } else {
        uri
    };
    let decoded = urlencoding::decode(path).map_err(|_| "its URI is not valid percent-encoded UTF-8".to_string())?;
    Ok(Target::File(PathBuf::from(decoded.into_owned())))
}

/// Whether `uri` starts with a scheme (`http:`…): letters, digits, `+`, `-` and `.` from a letter
/// up to a colon (RFC 3986 §3.1).
fn has_scheme(uri: &str) -> bool {
    uri.split_once(':').is_some_and(|(scheme, _)| {
        scheme.starts_with(|c: char| c.is_ascii_alphabetic())
            && scheme.chars().all(|c| c.is_ascii_alphanumeric() || matches!(c, '+' | '-' | '.'))
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn file(uri: &str) -> Result<PathBuf, String> {
        match target(uri)? {
            Target::File(path) => Ok(path),
            Target::Data(_) => Err("data".to_string()),
        }
    }

    #[test]
    fn uris_become_paths_or_bytes() {
        assert_eq!(file("a%20b/c.bin").unwrap(), Path::new("a b/c.bin"));
        assert_eq!(file("%2E%2E/secret.bin").unwrap(), Path::new("../secret.bin"), "decoded before the policy");
        assert_eq!(file("file:///etc/passwd").unwrap(), Path::new("/etc/passwd"));
        assert_eq!(file("file:/etc/passwd").unwrap(), Path::new("/etc/passwd"));
        assert!(file("file://host/share/x.bin").is_err());
        assert!(file("https://example.com/x.bin").is_err());
        assert!(file("%FF.bin").is_err(), "not UTF-8 once decoded");
        assert!(
            matches!(target("data:application/octet-stream;base64,AQID"), Ok(Target::Data(b)) if b[..3] == [1, 2, 3])
        );
        assert!(target("data:application/octet-stream;base64,!!").is_err());
    }
}

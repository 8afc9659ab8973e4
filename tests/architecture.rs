//! ARCHITECTURE.md names only paths that exist: every `code span` in it that looks like a path in
//! the repository (it contains a `/` or ends in a file extension) is checked, so that the map of
//! the code cannot drift from the code unnoticed. docs/physics.md's "Where in the code" lines are
//! held to the same, for the paths it names from the repository's root.

#![allow(clippy::unwrap_used)] // A panic is a failed test.

use std::path::Path;

/// The code spans of `text` that name a path: with a `/`, or a name with an extension, and
/// nothing a path would not hold (spaces, `::`, globs, braces).
fn named_paths(text: &str) -> Vec<&str> {
    let spans = text.split('`').skip(1).step_by(2);
    spans
        .filter(|s| !s.is_empty() && !s.contains([' ', '*', '{', '<', '=', '(']) && !s.contains("::"))
        .filter(|s| {
            s.contains('/') || s.rsplit_once('.').is_some_and(|(stem, ext)| !stem.is_empty() && is_extension(ext))
        })
        .collect()
}

fn is_extension(ext: &str) -> bool {
    ["rs", "md", "toml", "sh", "py", "json", "gltf", "obj", "exr", "png", "html", "js"].contains(&ext)
}

#[test]
fn every_path_architecture_md_names_exists() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let text = std::fs::read_to_string(root.join("ARCHITECTURE.md")).unwrap();
    let paths = named_paths(&text);
    assert!(paths.len() >= 30, "ARCHITECTURE.md names only {} paths: {paths:?}", paths.len());
    let missing: Vec<&&str> = paths.iter().filter(|p| !root.join(p.trim_end_matches('/')).exists()).collect();
    assert!(missing.is_empty(), "ARCHITECTURE.md names paths that do not exist: {missing:?}");
}

#[test]
fn every_path_from_the_root_docs_physics_md_names_exists() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let text = std::fs::read_to_string(root.join("docs/physics.md")).unwrap();
    let from_root: Vec<&str> = named_paths(&text)
        .into_iter()
        .filter(|p| ["crates/", "src/", "tests/", "docs/", "scenes/"].iter().any(|top| p.starts_with(top)))
        .collect();
    assert!(from_root.len() >= 20, "docs/physics.md names only {} paths: {from_root:?}", from_root.len());
    let missing: Vec<&&str> = from_root.iter().filter(|p| !root.join(p.trim_end_matches('/')).exists()).collect();
    assert!(missing.is_empty(), "docs/physics.md names paths that do not exist: {missing:?}");
}

#[test]
fn paths_are_told_from_other_code_spans() {
    let text = "`crates/render/src/` and `Cargo.toml`, not `spacetime::Spacetime`, `a b/c` or `*.rs`; `x.y`";
    assert_eq!(named_paths(text), ["crates/render/src/", "Cargo.toml"]);
}

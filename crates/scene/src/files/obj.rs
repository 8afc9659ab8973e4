//! Wavefront OBJ files, read under the scene's [`ReadPolicy`](super::ReadPolicy) into the
//! renderer's [`TriangleMesh`] and its triangles.
//!
//! tobj parses the file; what it leaves vague (which line a bad face index is on) is found here,
//! and what it may panic on is contained, since the file is untrusted.

use super::policy::{ReadError, Resource};
use render::geometry::Vec3;
use render::shape::{MeshDefect, Shape, TriangleMesh};
use render::transform::Transform;
use std::fmt;
use std::io::{BufRead, Cursor};
use std::path::{Path, PathBuf};
use std::sync::Arc;

/// Why an OBJ file could not be loaded. Every variant names the file, as the scene wrote it.
#[derive(Debug)]
pub enum MeshError {
    /// The file may not be read (see [`super::policy`]) or could not be (missing, a folder…).
    Open { path: PathBuf, source: ReadError },
    /// The OBJ parser rejected the file; `message` is tobj's.
    Parse { path: PathBuf, message: String },
    /// A face refers to a vertex, texture coordinate or normal that does not exist.
    FaceIndex { path: PathBuf, line: usize, index: i64, attribute: &'static str, count: usize },
    /// The parsed data is unusable.
    Invalid { path: PathBuf, defect: MeshDefect },
}

impl fmt::Display for MeshError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::Open { path, source } => {
                write!(f, "cannot open mesh file '{}': {source}", path.display())
            }
            Self::Parse { path, message } => {
                write!(f, "cannot parse OBJ file '{}': {message}", path.display())
            }
            Self::FaceIndex { path, line, index, attribute, count } => write!(
                f,
                "OBJ file '{}', line {line}: face refers to {attribute} {index}, but the file \
                 defines {count} {attribute} entries (1-based; negative counts back)",
                path.display()
            ),
            Self::Invalid { path, defect } => {
                write!(f, "mesh file '{}': {defect}", path.display())
            }
        }
    }
}

impl std::error::Error for MeshError {
    fn source(&self) -> Option<&(dyn std::error::Error + 'static)> {
        match self {
            Self::Open { source, .. } => Some(source),
            Self::Invalid { defect, .. } => Some(defect),
            Self::Parse { .. } | Self::FaceIndex { .. } => None,
        }
    }
}

/// Loads a Wavefront OBJ file as triangles, with `transform` (object to world) baked into the
/// vertex data. Polygons are triangulated as fans; points and lines are ignored; every object and
/// group of the file goes into one shared [`TriangleMesh`]. Normals and uvs are kept when every
/// vertex has them. Materials (`mtllib`, `usemtl`) are ignored: the scene file assigns materials.
/// A mirroring transform reverses the winding so that normals still point outward.
///
/// `file` is read under its policy (see [`super::policy`]); it names no other file.
pub fn load_obj(file: &Resource<'_>, transform: &Transform) -> Result<Vec<Shape>, MeshError> {
    let path = file.written();
    let invalid = |defect| MeshError::Invalid { path: path.to_path_buf(), defect };
    let bytes = file.read().map_err(|source| MeshError::Open { path: path.to_path_buf(), source })?;
    // Other tobj features (merging, reordering) add fields; their defaults (off) are wanted.
    #[allow(clippy::needless_update)]
    let options = tobj::LoadOptions {
        single_index: true,
        triangulate: true,
        ignore_points: true,
        ignore_lines: true,
        ..Default::default()
    };
    // tobj indexes and unwraps in a few places; a malformed file must be an error, not a crash.
    let parsed = std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| {
        // Material libraries are refused unread: the scene file assigns materials.
        tobj::load_obj_buf(&mut Cursor::new(&bytes), &options, |_| Err(tobj::LoadError::GenericFailure))
    }));
    let models = match parsed {
        Ok(Ok((models, _materials))) => models,
        Ok(Err(e)) => return Err(parse_error(path, &bytes, e)),
        Err(_) => {
            return Err(MeshError::Parse {
                path: path.to_path_buf(),
                message: "the OBJ parser failed on malformed input".to_string(),
            })
        }
    };

    let (mut positions, mut normals, mut uvs, mut indices) = (Vec::new(), Vec::new(), Vec::new(), Vec::new());
    let (mut all_normals, mut all_uvs) = (true, true);
    for model in &models {
        let m = &model.mesh;
        let base = positions.len();
        let count = m.positions.len() / 3;
        let raw =
            |v: &[f32], i: usize| Vec3::new(f64::from(v[3 * i]), f64::from(v[3 * i + 1]), f64::from(v[3 * i + 2]));
        for i in 0..count {
            let p = raw(&m.positions, i);
            if !p.is_finite() {
                return Err(invalid(MeshDefect::NonFiniteVertex { vertex: base + i, position: p }));
            }
            positions.push(p);
        }
        all_normals &= m.normals.len() == m.positions.len();
        if all_normals {
            normals.extend((0..count).map(|i| raw(&m.normals, i)));
        }
        all_uvs &= m.texcoords.len() == 2 * count;
        if all_uvs {
            uvs.extend(m.texcoords.chunks_exact(2).map(|t| [f64::from(t[0]), f64::from(t[1])]));
        }
        let base = u32::try_from(base).map_err(|_| invalid(MeshDefect::TooManyVertices { count: base + count }))?;
        indices.extend(m.indices.chunks_exact(3).map(|t| [t[0], t[1], t[2]].map(|i| i.saturating_add(base))));
    }

    let mesh =
        TriangleMesh::placed(positions, all_normals.then_some(normals), all_uvs.then_some(uvs), indices, transform)
            .map_err(invalid)?;
    let shapes = TriangleMesh::shapes(&Arc::new(mesh));
    if shapes.is_empty() {
        return Err(invalid(MeshDefect::NoTriangles));
    }
    Ok(shapes)
}

/// tobj's error, made precise where tobj is vague: for an out-of-range face index, find the line.
fn parse_error(path: &Path, bytes: &[u8], e: tobj::LoadError) -> MeshError {
    use tobj::LoadError as E;
    if matches!(e, E::FaceVertexOutOfBounds | E::FaceTexCoordOutOfBounds | E::FaceNormalOutOfBounds) {
        if let Some(found) = find_bad_face_index(path, bytes) {
            return found;
        }
    }
    MeshError::Parse { path: path.to_path_buf(), message: e.to_string() }
}

/// Goes through the file's `bytes` again to find the first face index that refers past the data:
/// absolute indices (1-based) against the file's totals, relative (negative) ones against the
/// entries so far.
fn find_bad_face_index(path: &Path, bytes: &[u8]) -> Option<MeshError> {
    const ATTRIBUTES: [(&str, &str); 3] = [("v", "vertex"), ("vt", "texture coordinate"), ("vn", "normal")];
    let lines: Vec<String> = bytes.lines().map_while(Result::ok).collect();
    let mut totals = [0usize; 3];
    for line in &lines {
        if let Some(k) = line.split_whitespace().next().and_then(|w| ATTRIBUTES.iter().position(|a| a.0 == w)) {
            totals[k] += 1;
        }
    }
    let mut so_far = [0usize; 3];
    for (number, line) in lines.iter().enumerate() {
        let mut words = line.split_whitespace();
        let keyword = words.next();
        if let Some(k) = keyword.and_then(|w| ATTRIBUTES.iter().position(|a| a.0 == w)) {
            so_far[k] += 1;
            continue;
        }
        if !matches!(keyword, Some("f")) {
            continue;
        }
        for vertex in words {
            for (k, part) in vertex.split('/').enumerate().take(3) {
                let Ok(index) = part.parse::<i64>() else {
                    continue;
                };
                // tobj ignores texture and normal indices of 0, and all of them in a file that
                // defines none of that attribute.
                if k > 0 && (index == 0 || totals[k] == 0) {
                    continue;
                }
                let ok = if index > 0 {
                    (index as u64) <= totals[k] as u64
                } else {
                    index < 0 && index.unsigned_abs() <= so_far[k] as u64
                };
                if !ok {
                    return Some(MeshError::FaceIndex {
                        path: path.to_path_buf(),
                        line: number + 1,
                        index,
                        attribute: ATTRIBUTES[k].1,
                        count: if index > 0 { totals[k] } else { so_far[k] },
                    });
                }
            }
        }
    }
    None
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::files::ReadPolicy;
    use render::geometry::{Aabb, Ray};
    use render::sampling::{uniform_sphere, Rng};

    /// [`load_obj`] of a path typed on the command line (any regular file).
    fn load(path: &Path, transform: &Transform) -> Result<Vec<Shape>, MeshError> {
        load_obj(&ReadPolicy::anywhere().file(Path::new(""), path), transform)
    }

    /// A file in the system temp directory, unique to this test and process, removed on drop.
    struct TempFile(PathBuf);

    impl TempFile {
        fn new(name: &str, contents: &str) -> Self {
            let path = std::env::temp_dir().join(format!("nullpath-mesh-{}-{name}.obj", std::process::id()));
            std::fs::write(&path, contents).unwrap();
            Self(path)
        }
    }

    impl Drop for TempFile {
        fn drop(&mut self) {
            let _ = std::fs::remove_file(&self.0);
        }
    }

    /// A unit cube [0,1]³ with quads, per-face normals and uvs.
    const CUBE: &str = "\
# unit cube
mtllib missing.mtl
o cube
v 0 0 0
v 1 0 0
v 1 1 0
v 0 1 0
v 0 0 1
v 1 0 1
v 1 1 1
v 0 1 1
vt 0 0
vt 1 0
vt 1 1
vt 0 1
vn 0 0 -1
vn 0 0 1
vn 0 -1 0
vn 0 1 0
vn -1 0 0
vn 1 0 0
usemtl white
f 1/1/1 4/2/1 3/3/1 2/4/1
f 5/1/2 6/2/2 7/3/2 8/4/2
f 1/1/3 2/2/3 6/3/3 5/4/3
f 4/1/4 8/2/4 7/3/4 3/4/4
f 1/1/5 5/2/5 8/3/5 4/4/5
f 2/1/6 3/2/6 7/3/6 6/4/6
";

    fn cube_bounds(shapes: &[Shape]) -> Aabb {
        shapes.iter().fold(Aabb::EMPTY, |b, s| b.union(&s.bounds()))
    }

    #[test]
    fn loads_a_cube_with_normals_and_uvs() {
        let file = TempFile::new("cube", CUBE);
        let shapes = load(&file.0, &Transform::IDENTITY).unwrap();
        assert_eq!(shapes.len(), 12);
        assert!((shapes.iter().map(Shape::area).sum::<f64>() - 6.0).abs() < 1e-12);
        // Every outward ray from the centre leaves through a face whose normal points outward.
        let mut rng = Rng::new(9);
        for _ in 0..1000 {
            let dir = uniform_sphere(rng.next_2d());
            let ray = Ray::new(Vec3::splat(0.5), dir, 10.0);
            let (t, s) = shapes
                .iter()
                .filter_map(|s| s.intersect(&ray).map(|t| (t, s)))
                .min_by(|a, b| a.0.total_cmp(&b.0))
                .unwrap();
            let h = s.surface(&ray, t);
            assert!(h.ng.dot(dir) > 0.0 && h.ns.dot(h.ng) > 0.99);
            assert!(h.uv.iter().all(|x| (-1e-12..=1.0 + 1e-12).contains(x)));
        }
    }

    /// The cube without texture coordinates and normals.
    fn positions_only(obj: &str) -> String {
        let mut out = String::new();
        for line in obj.lines().filter(|l| !l.starts_with("vt") && !l.starts_with("vn")) {
            if let Some(face) = line.strip_prefix("f ") {
                let corners: Vec<&str> = face.split_whitespace().filter_map(|c| c.split('/').next()).collect();
                out += &format!("f {}\n", corners.join(" "));
            } else {
                out += line;
                out += "\n";
            }
        }
        out
    }

    #[test]
    fn transform_is_baked_in_and_mirroring_keeps_normals_outward() {
        let file = TempFile::new("mirrored", &positions_only(CUBE));
        let t =
            Transform::scale(Vec3::new(-2.0, 1.0, 1.0)).unwrap().then(&Transform::translate(Vec3::new(5.0, 0.0, 0.0)));
        let shapes = load(&file.0, &t).unwrap();
        let b = cube_bounds(&shapes);
        assert!((b.min - Vec3::new(3.0, 0.0, 0.0)).length() < 1e-12);
        assert!((b.max - Vec3::new(5.0, 1.0, 1.0)).length() < 1e-12);
        for s in &shapes {
            let Shape::Triangle(tri) = s else { unreachable!() };
            assert!(tri.mesh().normals().is_none() && tri.mesh().uvs().is_none());
            let (p, n) = s.sample_area([0.3, 0.3]);
            assert!(n.dot(p - Vec3::new(4.0, 0.5, 0.5)) > 0.0, "outward after mirroring");
        }
    }

    #[test]
    fn missing_file_names_the_file() {
        let path = std::env::temp_dir().join("nullpath-definitely-missing.obj");
        let e = load(&path, &Transform::IDENTITY).unwrap_err();
        let message = e.to_string();
        assert!(matches!(e, MeshError::Open { .. }));
        assert!(message.contains("nullpath-definitely-missing.obj") && message.contains("cannot open"), "{message}");
    }

    #[test]
    fn garbage_is_an_error_not_a_panic() {
        let file = TempFile::new("garbage", "this is not\n an obj file \u{1}\u{2}\n");
        let e = load(&file.0, &Transform::IDENTITY).unwrap_err();
        assert!(e.to_string().contains("contains no triangles"), "{e}");
        let file = TempFile::new("bad-number", "v 1 2 banana\nv 0 0 0\nv 1 1 1\nf 1 2 3\n");
        let e = load(&file.0, &Transform::IDENTITY).unwrap_err();
        assert!(matches!(e, MeshError::Parse { .. }), "{e}");
        assert!(e.to_string().contains("position parse error") && e.to_string().contains("bad-number"), "{e}");
        let file = TempFile::new("binary", "v 1 2 3\n\u{0}\u{ff}\u{fe}f 1 1 1\nvt 0\n");
        assert!(load(&file.0, &Transform::IDENTITY).is_err());
    }

    #[test]
    fn out_of_range_index_points_at_the_line() {
        let file = TempFile::new("range", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\nf 1 2 9\n");
        let e = load(&file.0, &Transform::IDENTITY).unwrap_err();
        let message = e.to_string();
        assert!(matches!(e, MeshError::FaceIndex { line: 5, index: 9, count: 3, .. }), "{message}");
        assert!(message.contains("line 5") && message.contains("vertex 9"), "{message}");
        let file = TempFile::new("relative", "v 0 0 0\nv 1 0 0\nf -1 -2 -4\n");
        let e = load(&file.0, &Transform::IDENTITY).unwrap_err();
        assert!(matches!(e, MeshError::FaceIndex { line: 3, index: -4, count: 2, .. }), "{e}");
        let file = TempFile::new("normal-range", "v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 1\nf 1//1 2//1 3//2\n");
        let e = load(&file.0, &Transform::IDENTITY).unwrap_err();
        assert!(matches!(e, MeshError::FaceIndex { attribute: "normal", index: 2, .. }), "{e}");
    }

    #[test]
    fn non_finite_vertex_and_degenerate_meshes_are_rejected() {
        let file = TempFile::new("nan", "v 0 0 0\nv nan 0 0\nv 0 1 0\nf 1 2 3\n");
        let e = load(&file.0, &Transform::IDENTITY).unwrap_err();
        assert!(e.to_string().contains("non-finite position"), "{e}");
        let file = TempFile::new("flat", "v 0 0 0\nv 1 0 0\nv 2 0 0\nf 1 2 3\n");
        let e = load(&file.0, &Transform::IDENTITY).unwrap_err();
        assert!(e.to_string().contains("no triangles"), "{e}");
    }
}

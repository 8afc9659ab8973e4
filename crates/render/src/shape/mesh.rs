//! Triangle meshes: vertex data shared by the mesh's triangles.
//!
//! Vertex data is baked into world space when the mesh is built (pbrt-v4 §6.5.1): one transform
//! per vertex at load time instead of two per ray per triangle, and the BVH sees world bounds.
//! A [`Triangle`] is an `Arc` to the mesh plus an index.
//!
//! Meshes are built from data in memory; reading them from files (Wavefront OBJ, glTF) is the
//! scene crate's job (its `files` module), so that every file a scene names is read in one place,
//! under one read policy.

use super::{Shape, Triangle};
use crate::digest::{write_f64s, ContentDigest, Hex};
use crate::geometry::Vec3;
use crate::transform::Transform;
use std::fmt;
use std::hash::Hasher;
use std::sync::Arc;

/// World-space vertex data of a triangle mesh. Invariants, checked by [`TriangleMesh::new`]:
/// every index is in range, positions and normals are finite, attribute arrays have one entry per
/// vertex, and (with normals) each triangle's winding agrees with its vertex normals.
///
/// `Debug` shows the counts and a digest of the data, not the data: every triangle refers to
/// its mesh, so a scene's `Debug` text (its identity, see [`crate::digest`]) stays linear in
/// the mesh's size.
pub struct TriangleMesh {
    positions: Vec<Vec3>,
    /// Unit length, or zero where the source gave a zero normal (shading then uses `ng`).
    normals: Option<Vec<Vec3>>,
    uvs: Option<Vec<[f64; 2]>>,
    indices: Vec<[u32; 3]>,
    digest: ContentDigest,
}

impl fmt::Debug for TriangleMesh {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_struct("TriangleMesh")
            .field("vertices", &self.positions.len())
            .field("triangles", &self.indices.len())
            .field("content", &Hex(self.digest()))
            .finish()
    }
}

/// What is wrong with a mesh's data.
#[derive(Clone, Debug, PartialEq)]
pub enum MeshDefect {
    /// No triangle with non-zero area.
    NoTriangles,
    /// A triangle refers to a vertex that does not exist.
    IndexOutOfRange { triangle: usize, index: u32, vertex_count: usize },
    /// A vertex position is NaN or infinite.
    NonFiniteVertex { vertex: usize, position: Vec3 },
    /// A vertex normal is NaN or infinite.
    NonFiniteNormal { vertex: usize, normal: Vec3 },
    /// A per-vertex attribute array does not have one entry per vertex.
    AttributeCount { attribute: &'static str, count: usize, vertex_count: usize },
    /// The transform is not finite or not invertible.
    InvalidTransform,
    /// More vertices than 32-bit indices can address.
    TooManyVertices { count: usize },
}

impl fmt::Display for MeshDefect {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::NoTriangles => write!(f, "contains no triangles (with non-zero area)"),
            Self::IndexOutOfRange { triangle, index, vertex_count } => write!(
                f,
                "triangle {triangle} refers to vertex {index}, but there are only {vertex_count} \
                 vertices (0-based)"
            ),
            Self::NonFiniteVertex { vertex, position } => {
                write!(f, "vertex {vertex} has a non-finite position {position}")
            }
            Self::NonFiniteNormal { vertex, normal } => {
                write!(f, "vertex {vertex} has a non-finite normal {normal}")
            }
            Self::AttributeCount { attribute, count, vertex_count } => {
                write!(f, "{count} {attribute} for {vertex_count} vertices")
            }
            Self::InvalidTransform => write!(f, "transform is not finite or not invertible"),
            Self::TooManyVertices { count } => {
                write!(f, "has {count} vertices, more than 32-bit indices can address")
            }
        }
    }
}

impl std::error::Error for MeshDefect {}

impl TriangleMesh {
    /// A mesh from world-space data: `positions`, optional per-vertex `normals` (normalised here)
    /// and `uvs`, and counter-clockwise triangles `indices`. With normals, a triangle whose winding
    /// disagrees with the sum of its vertex normals is reordered, so that its cross-product normal
    /// `ng` points to the side the normals call outside.
    pub fn new(
        positions: Vec<Vec3>,
        normals: Option<Vec<Vec3>>,
        uvs: Option<Vec<[f64; 2]>>,
        mut indices: Vec<[u32; 3]>,
    ) -> Result<Self, MeshDefect> {
        let vertex_count = positions.len();
        if indices.is_empty() {
            return Err(MeshDefect::NoTriangles);
        }
        for (triangle, tri) in indices.iter().enumerate() {
            if let Some(&index) = tri.iter().find(|&&i| i as usize >= vertex_count) {
                return Err(MeshDefect::IndexOutOfRange { triangle, index, vertex_count });
            }
        }
        if let Some((vertex, &position)) = positions.iter().enumerate().find(|(_, p)| !p.is_finite()) {
            return Err(MeshDefect::NonFiniteVertex { vertex, position });
        }
        let normals = match normals {
            None => None,
            Some(n) if n.len() != vertex_count => {
                return Err(MeshDefect::AttributeCount { attribute: "normals", count: n.len(), vertex_count })
            }
            Some(n) => {
                if let Some((vertex, &normal)) = n.iter().enumerate().find(|(_, n)| !n.is_finite()) {
                    return Err(MeshDefect::NonFiniteNormal { vertex, normal });
                }
                Some(n.into_iter().map(Vec3::normalize_or_zero).collect::<Vec<_>>())
            }
        };
        if let Some(uv) = &uvs {
            if uv.len() != vertex_count {
                return Err(MeshDefect::AttributeCount { attribute: "uvs", count: uv.len(), vertex_count });
            }
        }
        if let Some(n) = &normals {
            for tri in &mut indices {
                let [a, b, c] = tri.map(|i| i as usize);
                let winding = (positions[b] - positions[a]).cross(positions[c] - positions[a]);
                if winding.dot(n[a] + n[b] + n[c]) < 0.0 {
                    tri.swap(1, 2);
                }
            }
        }
        Ok(Self { positions, normals, uvs, indices, digest: ContentDigest::default() })
    }

    /// A digest of the vertex data and the triangles, computed on first use.
    pub fn digest(&self) -> u64 {
        let components = |v: &Vec3| [v.x, v.y, v.z];
        self.digest.get(|h| {
            h.write_usize(self.positions.len());
            write_f64s(h, self.positions.iter().flat_map(components));
            // Which attributes are present is part of the content, not only their values.
            h.write_u8(u8::from(self.normals.is_some()) | u8::from(self.uvs.is_some()) << 1);
            write_f64s(h, self.normals.iter().flatten().flat_map(components));
            write_f64s(h, self.uvs.iter().flatten().flatten().copied());
            for triangle in &self.indices {
                triangle.iter().for_each(|&i| h.write_u32(i));
            }
        })
    }

    /// As [`TriangleMesh::new`], from object-space data with `transform` (object to world) baked
    /// in: positions mapped as points, normals by the inverse transpose, and the winding reversed
    /// by a mirroring transform so that `ng` still points outward.
    pub fn placed(
        mut positions: Vec<Vec3>,
        mut normals: Option<Vec<Vec3>>,
        uvs: Option<Vec<[f64; 2]>>,
        mut indices: Vec<[u32; 3]>,
        transform: &Transform,
    ) -> Result<Self, MeshDefect> {
        if !transform.is_finite() || transform.linear().determinant() == 0.0 {
            return Err(MeshDefect::InvalidTransform);
        }
        for p in &mut positions {
            *p = transform.point(*p);
        }
        for n in normals.iter_mut().flatten() {
            *n = transform.normal(*n);
        }
        if transform.swaps_handedness() {
            for tri in &mut indices {
                tri.swap(1, 2);
            }
        }
        Self::new(positions, normals, uvs, indices)
    }

    /// One [`Shape::Triangle`] per triangle with non-zero area (degenerate triangles can never be
    /// hit and have no normal, so they are left out).
    pub fn shapes(mesh: &Arc<TriangleMesh>) -> Vec<Shape> {
        Self::triangles(mesh).into_iter().map(Shape::Triangle).collect()
    }

    /// The triangles with non-zero area, as [`TriangleMesh::shapes`] lists them.
    pub fn triangles(mesh: &Arc<TriangleMesh>) -> Vec<Triangle> {
        (0..mesh.indices.len())
            .filter(|&i| {
                let [a, b, c] = mesh.indices[i].map(|k| mesh.positions[k as usize]);
                (b - a).cross(c - a).normalize_or_zero() != Vec3::ZERO
            })
            .filter_map(|i| u32::try_from(i).ok())
            .map(|i| Triangle::new(Arc::clone(mesh), i))
            .collect()
    }

    pub fn positions(&self) -> &[Vec3] {
        &self.positions
    }

    pub fn normals(&self) -> Option<&[Vec3]> {
        self.normals.as_deref()
    }

    pub fn uvs(&self) -> Option<&[[f64; 2]]> {
        self.uvs.as_deref()
    }

    pub fn indices(&self) -> &[[u32; 3]] {
        &self.indices
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::Ray;

    #[test]
    fn mesh_data_is_checked() {
        assert_eq!(
            TriangleMesh::new(vec![Vec3::ZERO], None, None, vec![[0, 0, 1]]).unwrap_err(),
            MeshDefect::IndexOutOfRange { triangle: 0, index: 1, vertex_count: 1 }
        );
        assert!(matches!(
            TriangleMesh::new(vec![Vec3::ZERO; 3], Some(vec![Vec3::Z]), None, vec![[0, 1, 2]]),
            Err(MeshDefect::AttributeCount { attribute: "normals", count: 1, vertex_count: 3 })
        ));
    }

    #[test]
    fn vertex_normals_decide_the_outward_side() {
        let positions = vec![Vec3::ZERO, Vec3::X, Vec3::Y];
        // Clockwise as listed, but the normals say +z is outside.
        let mesh = TriangleMesh::new(positions, Some(vec![Vec3::Z * 3.0; 3]), None, vec![[0, 2, 1]]).unwrap();
        let shapes = TriangleMesh::shapes(&Arc::new(mesh));
        let ray = Ray::new(Vec3::new(0.2, 0.2, 1.0), -Vec3::Z, 2.0);
        let h = shapes[0].surface(&ray, shapes[0].intersect(&ray).unwrap());
        assert_eq!(h.ng, Vec3::Z);
        assert_eq!(h.ns, Vec3::Z, "normalised");
    }
}

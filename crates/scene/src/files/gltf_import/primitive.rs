//! One glTF mesh primitive: triangles with their vertex data, in the mesh's own space.

use super::check::{self, INDEX, TEXCOORD, VEC3_FLOAT};
use super::named;
use render::geometry::Vec3;
use render::shape::TriangleMesh;
use render::transform::Transform;

/// A triangle primitive's vertex data (positions, optional normals and uvs of `TEXCOORD_0`,
/// `v` flipped to run up) and its glTF material.
#[derive(Clone, Debug)]
pub(crate) struct Primitive {
    /// `mesh 2 ('chair') primitive 0`, for messages.
    pub name: String,
    positions: Vec<Vec3>,
    normals: Option<Vec<Vec3>>,
    uvs: Option<Vec<[f64; 2]>>,
    indices: Vec<[u32; 3]>,
    /// Index of its glTF material; `None` for glTF's default material.
    pub material: Option<usize>,
}

impl Primitive {
    /// Reads primitive `p` of `mesh` from the buffers' data.
    pub(crate) fn read(mesh: &gltf::Mesh<'_>, p: &gltf::Primitive<'_>, buffers: &[Vec<u8>]) -> Result<Self, String> {
        let name = format!("{} primitive {}", named("mesh", mesh.index(), mesh.name()), p.index());
        if p.mode() != gltf::mesh::Mode::Triangles {
            return Err(format!("{name}: its mode is {:?}; only triangles (mode 4) are supported", p.mode()));
        }
        // The readers below trust these; each is checked first (see `check`).
        let Some(position) = p.get(&gltf::Semantic::Positions) else {
            return Err(format!("{name}: it has no POSITION attribute"));
        };
        let attributes = [
            (Some(position), "POSITION", VEC3_FLOAT),
            (p.get(&gltf::Semantic::Normals), "NORMAL", VEC3_FLOAT),
            (p.get(&gltf::Semantic::TexCoords(0)), "TEXCOORD_0", TEXCOORD),
            (p.indices(), "indices", INDEX),
        ];
        for (accessor, what, kinds) in attributes {
            if let Some(accessor) = accessor {
                check::accessor(&accessor, what, kinds, buffers).map_err(|e| format!("{name}: {e}"))?;
            }
        }
        let reader = p.reader(|b| buffers.get(b.index()).map(Vec::as_slice));
        let out_of_range = |attribute: &str| format!("{name}: the {attribute} data lies outside its buffer");
        let positions: Vec<Vec3> = reader
            .read_positions()
            .ok_or_else(|| out_of_range("POSITION"))?
            .map(|v| Vec3::from_array(v.map(f64::from)))
            .collect();
        if let Some((i, v)) = positions.iter().enumerate().find(|(_, v)| !v.is_finite()) {
            return Err(format!("{name}: vertex {i} has a non-finite position {v}"));
        }
        let normals = match p.get(&gltf::Semantic::Normals) {
            None => None,
            Some(_) => Some(
                reader
                    .read_normals()
                    .ok_or_else(|| out_of_range("NORMAL"))?
                    .map(|v| Vec3::from_array(v.map(f64::from)))
                    .collect::<Vec<_>>(),
            ),
        };
        let uvs = match p.get(&gltf::Semantic::TexCoords(0)) {
            None => None,
            Some(_) => Some(
                reader
                    .read_tex_coords(0)
                    .ok_or_else(|| out_of_range("TEXCOORD_0"))?
                    .into_f32()
                    .map(|[u, v]| [f64::from(u), 1.0 - f64::from(v)])
                    .collect::<Vec<_>>(),
            ),
        };
        let flat: Vec<u32> = match reader.read_indices() {
            Some(indices) => indices.into_u32().collect(),
            None if p.indices().is_some() => return Err(out_of_range("index")),
            None => (0..u32::try_from(positions.len()).map_err(|_| format!("{name}: too many vertices"))?).collect(),
        };
        if flat.len() % 3 != 0 {
            return Err(format!("{name}: {} indices is not a whole number of triangles", flat.len()));
        }
        let indices = flat.chunks_exact(3).map(|t| [t[0], t[1], t[2]]).collect();
        let primitive = Self { name, positions, normals, uvs, indices, material: p.material().index() };
        // Check once here (indices in range, attribute counts, finite normals), so that placing
        // it later cannot fail but for its transform.
        primitive.mesh(&Transform::IDENTITY)?;
        Ok(primitive)
    }

    /// How many triangles it has.
    pub(crate) fn triangle_count(&self) -> usize {
        self.indices.len()
    }

    /// The primitive's triangles placed by `transform` (object to world).
    pub(crate) fn mesh(&self, transform: &Transform) -> Result<TriangleMesh, String> {
        TriangleMesh::placed(
            self.positions.clone(),
            self.normals.clone(),
            self.uvs.clone(),
            self.indices.clone(),
            transform,
        )
        .map_err(|e| format!("{}: {e}", self.name))
    }
}

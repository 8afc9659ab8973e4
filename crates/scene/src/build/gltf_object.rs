//! `[[objects]]` with `gltf = "file.glb"`: the meshes of a glTF file, placed by its node hierarchy
//! and then by the object's `transform`, with the file's materials or the scene's overrides.
//!
//! A primitive that the hierarchy places more than once becomes one [`InstancedMesh`] shared by
//! [`Instance`]s (its triangles and BVH are stored once); one placed once is baked into world
//! triangles, as an OBJ mesh is. Emitting primitives are always baked: lights are sampled
//! triangle by triangle.
//!
//! A `KHR_lights_punctual` point light of radiant intensity `I` becomes a black sphere of radius
//! [`POINT_LIGHT_RADIUS`] and radiance `L = I / (π r²)`: seen from outside, a uniformly bright
//! sphere has intensity `L·π r²` in every direction, so it lights everything farther than its
//! radius as the point would, through the light sampling every area light gets (in curved space
//! too). A spot light becomes a one-sided disk of that radius facing along its axis, with the
//! spot [`Profile`]: intensity `I·s(cos θ)` from the disk's area `π r²`.

use super::Builder;
use crate::files::gltf_import::{self, GltfScene};
use crate::reader::{Node, Result, Table};
use render::geometry::Vec3;
use render::material::Material;
use render::rgb::Rgb;
use render::shape::{Instance, InstancedMesh, Shape, TriangleMesh};
use render::texture::Texture;
use render::transform::Transform;
use render::world::{Emission, Object, Profile, Radiance};
use std::collections::HashMap;
use std::sync::Arc;

/// Radius of the sphere that stands for a point light, in world units (glTF's metres).
const POINT_LIGHT_RADIUS: f64 = 0.01;

/// A glTF file's camera placed in the world: `[camera] gltf_camera = "NAME"` takes its pose.
#[derive(Clone, Debug)]
pub(crate) struct PlacedCamera {
    pub name: String,
    pub position: Vec3,
    /// Unit viewing direction and up.
    pub forward: Vec3,
    pub up: Vec3,
    /// Vertical field of view, degrees.
    pub fov: f64,
}

/// What a glTF material becomes in the scene: a material index and its emission.
type Assigned = (usize, Option<Emission>);

impl Builder<'_> {
    /// The objects of the glTF file named by `file`, placed by `placement`.
    pub(super) fn gltf_objects(
        &mut self,
        t: &Table<'_>,
        file: &Node<'_>,
        placement: &Transform,
    ) -> Result<Vec<Object>> {
        let resource = self.resolve(file.str()?);
        let written = resource.written().display();
        let in_file = |e: String| file.err(format!("glTF file '{written}': {e}"));
        let scene = gltf_import::import(&resource, self.policy).map_err(in_file)?;
        for w in &scene.warnings {
            eprintln!("warning: glTF file '{written}': {w}");
        }
        for camera in &scene.cameras {
            let to_world = camera.transform.then(placement);
            self.gltf_cameras.push(PlacedCamera {
                name: camera.name.clone(),
                position: to_world.point(Vec3::ZERO),
                forward: to_world.vector(Vec3::NEG_Z).normalize_or_zero(),
                up: to_world.vector(Vec3::Y).normalize_or_zero(),
                fov: camera.yfov.to_degrees(),
            });
        }
        let assigned = self.gltf_materials(t, &scene)?;
        let mut uses = vec![0usize; scene.primitives.len()];
        for p in &scene.placements {
            uses[p.primitive] += 1;
        }
        let mut shared: Vec<Option<Arc<InstancedMesh>>> = vec![None; scene.primitives.len()];
        let mut objects = Vec::new();
        for p in &scene.placements {
            let primitive = &scene.primitives[p.primitive];
            let (material, emission) = match primitive.material {
                Some(m) => assigned[m].clone(),
                None => (self.default_material(), None),
            };
            let to_world = p.transform.then(placement);
            if uses[p.primitive] > 1 && emission.is_none() {
                let mesh = match &shared[p.primitive] {
                    Some(mesh) => Arc::clone(mesh),
                    None => match InstancedMesh::new(primitive.mesh(&Transform::IDENTITY).map_err(in_file)?) {
                        Some(mesh) => Arc::clone(shared[p.primitive].insert(Arc::new(mesh))),
                        None => continue,
                    },
                };
                let instance =
                    Instance::new(mesh, &to_world).map_err(|e| in_file(format!("{}: {e}", primitive.name)))?;
                objects.push(Object { shape: Shape::from(instance), material, emission: None });
            } else {
                let mesh = Arc::new(primitive.mesh(&to_world).map_err(in_file)?);
                objects.extend(TriangleMesh::shapes(&mesh).into_iter().map(|shape| Object {
                    shape,
                    material,
                    emission: emission.clone(),
                }));
            }
        }
        if !scene.lights.is_empty() {
            self.materials.push(Material::Diffuse { reflectance: Texture::from(Rgb::ZERO) });
            let black = self.materials.len() - 1;
            let area = std::f64::consts::PI * POINT_LIGHT_RADIUS * POINT_LIGHT_RADIUS;
            for light in &scene.lights {
                let centre = placement.point(light.position);
                let radiance = light.intensity / area as f32;
                let (shape, emission) = match light.spot {
                    None => (
                        Shape::sphere(centre, POINT_LIGHT_RADIUS, &Transform::IDENTITY),
                        Emission::uniform(radiance, false),
                    ),
                    Some(cone) => {
                        let axis = placement.vector(cone.axis).normalize_or_zero();
                        let profile = Profile::Spot { cos_inner: cone.cos_inner, cos_outer: cone.cos_outer };
                        let emission = Emission { radiance: Radiance::Rgb(radiance.into()), two_sided: false, profile };
                        (Shape::disk(centre, axis, POINT_LIGHT_RADIUS, &Transform::IDENTITY), emission)
                    }
                };
                let shape = shape.map_err(|e| in_file(format!("a punctual light: {e}")))?;
                objects.push(Object { shape, material: black, emission: Some(emission) });
            }
        }
        if objects.is_empty() {
            return Err(in_file("its meshes have no triangles with non-zero area".to_string()));
        }
        Ok(objects)
    }

    /// Each glTF material's scene material: `material` (all of them), or an entry of `materials`
    /// (by glTF material name), or the glTF material itself, mapped.
    fn gltf_materials(&mut self, t: &Table<'_>, scene: &GltfScene) -> Result<Vec<Assigned>> {
        if let Some(n) = t.get("material") {
            let all = self.material_ref(&n)?;
            return Ok(vec![(all, None); scene.materials.len()]);
        }
        let mut by_name: HashMap<&str, usize> = HashMap::new();
        if let Some(n) = t.get("materials") {
            let overrides = n.any_table()?;
            for (name, value) in overrides.entries() {
                if !scene.materials.iter().any(|m| m.name.as_deref() == Some(name)) {
                    let mut known: Vec<String> =
                        scene.materials.iter().filter_map(|m| m.name.as_ref()).map(|n| format!("\"{n}\"")).collect();
                    known.sort_unstable();
                    let known = if known.is_empty() { "it names none".to_string() } else { known.join(", ") };
                    return Err(value.err(format!("the glTF file has no material named \"{name}\"; {known}")));
                }
                by_name.insert(name, self.material_ref(&value)?);
            }
        }
        Ok(scene
            .materials
            .iter()
            .map(|m| match m.name.as_deref().and_then(|name| by_name.get(name)) {
                Some(&index) => (index, None),
                None => {
                    self.materials.push(m.material.clone());
                    (self.materials.len() - 1, m.emission.clone())
                }
            })
            .collect())
    }
}

//! glTF 2.0 files (`.gltf` with its buffers and images, or a binary `.glb`), read with the
//! `gltf` crate into what a scene needs: triangle primitives in their mesh's own space, the
//! placements the node hierarchy gives them, and materials mapped onto nullpath's.
//!
//! glTF is y-up, right-handed and in metres, as nullpath's world is, so no axis is converted.
//! A glTF texture's `v` runs down the image; nullpath's runs up, so `v` is stored as `1 − v`.
//!
//! Everything in the file is untrusted: errors name the file and the element (mesh, primitive,
//! node, material, image), and no input panics (the one place in the `gltf` crate that can,
//! decoding a malformed percent-encoded URI or image, is contained).

mod material;
mod primitive;

pub(crate) use material::GltfMaterial;
pub(crate) use primitive::Primitive;

use render::color::Rgb;
use render::geometry::Vec3;
use render::transform::Transform;
use std::path::Path;

/// Extensions whose meaning is imported (see [`material`]). Files that *require* any other are
/// refused; files that merely *use* another get a warning naming it.
const SUPPORTED_EXTENSIONS: &[&str] =
    &["KHR_lights_punctual", "KHR_materials_emissive_strength", "KHR_materials_ior", "KHR_materials_transmission"];

/// A primitive placed by the node hierarchy: `transform` maps the mesh's space to the glTF
/// file's root space.
#[derive(Clone, Debug)]
pub(crate) struct Placement {
    pub primitive: usize,
    pub transform: Transform,
}

/// A `KHR_lights_punctual` point light, at `position` in the file's root space, of radiant
/// intensity `intensity` (colour × intensity, per steradian) in every direction.
#[derive(Clone, Copy, Debug)]
pub(crate) struct PointLight {
    pub position: Vec3,
    pub intensity: Rgb,
}

/// What a glTF file holds, ready for the scene builder.
pub(crate) struct GltfScene {
    pub primitives: Vec<Primitive>,
    pub placements: Vec<Placement>,
    pub lights: Vec<PointLight>,
    pub materials: Vec<GltfMaterial>,
    /// Things ignored that the user may want to know about (unsupported optional extensions…).
    pub warnings: Vec<String>,
}

/// Reads the glTF file at `path`. The error message does not repeat the path: the caller
/// prefixes it.
pub(crate) fn import(path: &Path) -> Result<GltfScene, String> {
    let bytes = std::fs::read(path).map_err(|e| format!("cannot read: {e}"))?;
    let unchecked = contained(|| gltf::Gltf::from_slice_without_validation(&bytes), "the file")?
        .map_err(|e| format!("not a valid glTF file: {e}"))?;
    let mut warnings = Vec::new();
    check_extensions(&unchecked.document, &mut warnings)?;
    drop(unchecked);
    let gltf =
        contained(|| gltf::Gltf::from_slice(&bytes), "the file")?.map_err(|e| format!("not a valid glTF file: {e}"))?;
    let base = path.parent().unwrap_or(Path::new("."));
    let buffers = buffers(&gltf, base)?;
    let document = &gltf.document;
    let mut primitives = Vec::new();
    let mut first_primitive = Vec::new();
    for mesh in document.meshes() {
        first_primitive.push(primitives.len());
        for p in mesh.primitives() {
            primitives.push(Primitive::read(&mesh, &p, &buffers)?);
        }
    }
    let materials = material::materials(document, base, &buffers, &mut warnings)?;
    let mut found = Found { first_primitive, placements: Vec::new(), lights: Vec::new(), warnings };
    let roots: Vec<gltf::Node<'_>> = match document.default_scene().or_else(|| document.scenes().next()) {
        Some(scene) => scene.nodes().collect(),
        None => return Err("has no scene to place (no \"scenes\")".to_string()),
    };
    for node in roots {
        contained(|| place(&node, &Transform::IDENTITY, &mut found, 0), "the node hierarchy")??;
    }
    let Found { placements, lights, mut warnings, .. } = found;
    if placements.is_empty() && lights.is_empty() {
        return Err("its scene places no mesh and no light".to_string());
    }
    if document.cameras().next().is_some() {
        warnings.push("its cameras are not imported (the scene file's [camera] is used)".to_string());
    }
    Ok(GltfScene { primitives, placements, lights, materials, warnings })
}

/// Refuses required extensions that are not supported; warns of used ones.
fn check_extensions(document: &gltf::Document, warnings: &mut Vec<String>) -> Result<(), String> {
    if let Some(name) = document.extensions_required().find(|e| !SUPPORTED_EXTENSIONS.contains(e)) {
        return Err(format!(
            "requires the glTF extension {name}, which nullpath does not support (supported: {})",
            SUPPORTED_EXTENSIONS.join(", ")
        ));
    }
    for name in document.extensions_used().filter(|e| !SUPPORTED_EXTENSIONS.contains(e)) {
        warnings.push(format!("uses the glTF extension {name}, which nullpath ignores"));
    }
    Ok(())
}

/// Runs `f`, turning a panic inside the `gltf` crate into an error about `what`.
fn contained<T>(f: impl FnOnce() -> T, what: &str) -> Result<T, String> {
    std::panic::catch_unwind(std::panic::AssertUnwindSafe(f))
        .map_err(|_| format!("the glTF reader failed on malformed data in {what}"))
}

/// The file's buffers: the `.glb` blob, embedded `data:` URIs or files beside the glTF file.
fn buffers(gltf: &gltf::Gltf, base: &Path) -> Result<Vec<gltf::buffer::Data>, String> {
    let mut blob = gltf.blob.clone();
    let mut data = Vec::new();
    for buffer in gltf.document.buffers() {
        let what = match buffer.source() {
            gltf::buffer::Source::Bin => format!("buffer {} (the .glb's binary chunk)", buffer.index()),
            gltf::buffer::Source::Uri(uri) => format!("buffer {} ('{}')", buffer.index(), short(uri)),
        };
        let read =
            contained(|| gltf::buffer::Data::from_source_and_blob(buffer.source(), Some(base), &mut blob), &what)?
                .map_err(|e| format!("{what}: cannot read: {e}"))?;
        if read.len() < buffer.length() {
            return Err(format!("{what}: holds {} bytes, but the file declares {}", read.len(), buffer.length()));
        }
        data.push(read);
    }
    Ok(data)
}

/// A URI fit for a message: `data:` URIs are cut short.
fn short(uri: &str) -> String {
    if uri.starts_with("data:") {
        format!("{}…", uri.chars().take(24).collect::<String>())
    } else {
        uri.to_string()
    }
}

/// glTF allows no cycles, but a file may have one: deeper than this is refused.
const MAX_DEPTH: usize = 256;

/// What the node hierarchy places, as it is walked.
struct Found {
    /// Each mesh's first primitive in the flat list of primitives.
    first_primitive: Vec<usize>,
    placements: Vec<Placement>,
    lights: Vec<PointLight>,
    warnings: Vec<String>,
}

/// Places `node`'s mesh (each of its primitives), its light and its children under `parent`.
fn place(node: &gltf::Node<'_>, parent: &Transform, found: &mut Found, depth: usize) -> Result<(), String> {
    let name = node_name(node);
    if depth > MAX_DEPTH {
        return Err(format!("{name}: nodes nest deeper than {MAX_DEPTH} levels (a cycle?)"));
    }
    let columns = node.transform().matrix().map(|c| c.map(f64::from));
    let local = glam::DMat4::from_cols_array_2d(&columns);
    let local = Transform::from_affine(glam::DAffine3::from_mat4(local))
        .map_err(|_| format!("{name}: its transform is not finite or not invertible (a zero scale?)"))?;
    let transform = local.then(parent);
    if let Some(mesh) = node.mesh() {
        let first = found.first_primitive[mesh.index()];
        for p in mesh.primitives() {
            found.placements.push(Placement { primitive: first + p.index(), transform });
        }
    }
    if let Some(light) = node.light() {
        let what = named("light", light.index(), light.name());
        match light.kind() {
            gltf::khr_lights_punctual::Kind::Point => {
                let [r, g, b] = light.color().map(|c| c * light.intensity());
                let intensity = Rgb::new(r, g, b);
                if !(intensity.is_finite() && intensity.min_element() >= 0.0) {
                    return Err(format!("{what}: its intensity {intensity} is not a finite non-negative colour"));
                }
                found.lights.push(PointLight { position: transform.point(Vec3::ZERO), intensity });
            }
            gltf::khr_lights_punctual::Kind::Directional => {
                found.warnings.push(format!("{what}: directional lights are not imported"));
            }
            gltf::khr_lights_punctual::Kind::Spot { .. } => {
                found.warnings.push(format!("{what}: spot lights are not imported"));
            }
        }
    }
    for child in node.children() {
        place(&child, &transform, found, depth + 1)?;
    }
    Ok(())
}

/// `node 3 ('chair')`.
fn node_name(node: &gltf::Node<'_>) -> String {
    named("node", node.index(), node.name())
}

/// `kind index ('name')`, or without the name when there is none.
fn named(kind: &str, index: usize, name: Option<&str>) -> String {
    match name {
        Some(n) => format!("{kind} {index} ('{n}')"),
        None => format!("{kind} {index}"),
    }
}

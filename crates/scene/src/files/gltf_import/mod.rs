//! glTF 2.0 files (`.gltf` with its buffers and images, or a binary `.glb`), read with the
//! `gltf` crate into what a scene needs: triangle primitives in their mesh's own space, the
//! placements the node hierarchy gives them, and materials mapped onto nullpath's.
//!
//! glTF is y-up, right-handed and in metres, as nullpath's world is, so no axis is converted.
//! A glTF texture's `v` runs down the image; nullpath's runs up, so `v` is stored as `1 − v`.
//!
//! Everything in the file is untrusted: errors name the file and the element (mesh, primitive,
//! node, material, image), and no input panics: what the `gltf` crate's readers trust is checked
//! first (see [`check`]), and a panic left inside it is contained. The files it names (buffers,
//! images) are read under the scene's read policy (see [`source`]), and what its node hierarchy
//! places is counted before any of it is, against [`MAX_PLACED_PRIMITIVES`], [`MAX_PLACED_NODES`]
//! and [`MAX_PLACED_TRIANGLES`].

mod check;
mod material;
mod primitive;
mod source;

pub(crate) use material::GltfMaterial;
pub(crate) use primitive::Primitive;

use super::{ReadPolicy, Resource};
use render::geometry::Vec3;
use render::rgb::Rgb;
use render::transform::Transform;
use source::Sources;
use std::path::Path;

/// Most primitive placements the node hierarchy of one file may make: each becomes an object.
pub(crate) const MAX_PLACED_PRIMITIVES: u64 = 1 << 20;
/// Most node placements: a node is placed once for each way down to it from the scene's roots, so
/// nodes that list the same children again and again place them exponentially often.
pub(crate) const MAX_PLACED_NODES: u64 = 1 << 20;
/// Most triangles the placements copy into world space: a primitive placed once, or one that emits
/// light (lights are sampled triangle by triangle), is copied at each placement; one placed more
/// often is stored once and instanced.
pub(crate) const MAX_PLACED_TRIANGLES: u64 = 1 << 25;
/// How far from 1 the length of a rotation quaternion may be: writers round it to `f32`.
const UNIT_TOLERANCE: f64 = 1e-3;

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

/// A `KHR_lights_punctual` point or spot light, at `position` in the file's root space, of
/// radiant intensity `intensity` (colour × intensity, per steradian): in every direction, or
/// for a spot along its axis.
#[derive(Clone, Copy, Debug)]
pub(crate) struct PunctualLight {
    pub position: Vec3,
    pub intensity: Rgb,
    pub spot: Option<SpotCone>,
}

/// A spot light's axis (unit, root space) and the cosines of its inner and outer cone angles.
#[derive(Clone, Copy, Debug)]
pub(crate) struct SpotCone {
    pub axis: Vec3,
    pub cos_inner: f64,
    pub cos_outer: f64,
}

/// A perspective camera: its name (the camera's, else its node's), the transform from its own
/// space (looking along −z, y up) to the file's root space, and its vertical field of view in
/// radians.
#[derive(Clone, Debug)]
pub(crate) struct GltfCamera {
    pub name: String,
    pub transform: Transform,
    pub yfov: f64,
}

/// What a glTF file holds, ready for the scene builder.
pub(crate) struct GltfScene {
    pub primitives: Vec<Primitive>,
    pub placements: Vec<Placement>,
    pub lights: Vec<PunctualLight>,
    pub cameras: Vec<GltfCamera>,
    pub materials: Vec<GltfMaterial>,
    /// Things ignored that the user may want to know about (unsupported optional extensions…).
    pub warnings: Vec<String>,
}

/// Reads the glTF file `file`, and the files it names under `policy`. The error message does not
/// repeat the file's path: the caller prefixes it.
pub(crate) fn import(file: &Resource<'_>, policy: &ReadPolicy) -> Result<GltfScene, String> {
    let bytes = file.read().map_err(|e| format!("cannot read: {e}"))?;
    check_glb_header(&bytes)?;
    let unchecked = contained(|| gltf::Gltf::from_slice_without_validation(&bytes), "the file")?
        .map_err(|e| format!("not a valid glTF file: {e}"))?;
    check_version(&unchecked.document)?;
    let mut warnings = Vec::new();
    check_extensions(&unchecked.document, &mut warnings)?;
    drop(unchecked);
    let gltf::Gltf { document, blob } =
        contained(|| gltf::Gltf::from_slice(&bytes), "the file")?.map_err(|e| format!("not a valid glTF file: {e}"))?;
    drop(bytes);
    let sources = Sources { dir: file.path().parent().unwrap_or(Path::new("")), policy };
    let buffers = buffers(&document, blob, sources)?;
    let mut primitives = Vec::new();
    let mut first_primitive = Vec::new();
    for mesh in document.meshes() {
        first_primitive.push(primitives.len());
        for p in mesh.primitives() {
            primitives.push(Primitive::read(&mesh, &p, &buffers)?);
        }
    }
    let materials = material::materials(&document, sources, &buffers, &mut warnings)?;
    let roots: Vec<gltf::Node<'_>> = match document.default_scene().or_else(|| document.scenes().next()) {
        Some(scene) => scene.nodes().collect(),
        None => return Err("has no scene to place (no \"scenes\")".to_string()),
    };
    let placed = placements_per_node(&document, &roots)?;
    check_placements(&document, &placed, &first_primitive, &primitives, &materials)?;
    let mut found =
        Found { first_primitive, placements: Vec::new(), lights: Vec::new(), cameras: Vec::new(), warnings };
    for node in roots {
        contained(|| place(&node, &Transform::IDENTITY, &mut found, 0), "the node hierarchy")??;
    }
    let Found { placements, lights, cameras, warnings, .. } = found;
    if placements.is_empty() && lights.is_empty() {
        return Err("its scene places no mesh and no light".to_string());
    }
    Ok(GltfScene { primitives, placements, lights, cameras, materials, warnings })
}

/// A binary glTF's header: the `gltf` crate reads the chunks but trusts the rest of it.
fn check_glb_header(bytes: &[u8]) -> Result<(), String> {
    if !bytes.starts_with(b"glTF") {
        return Ok(());
    }
    let word = |at: usize| bytes.get(at..at + 4).and_then(|w| w.try_into().ok()).map(u32::from_le_bytes);
    match (word(4), word(8)) {
        (Some(2), Some(length)) if usize::try_from(length).is_ok_and(|l| l == bytes.len()) => Ok(()),
        (Some(2), Some(length)) => Err(format!(
            "not a valid glTF file: its GLB header gives a length of {length} bytes, but the file holds {}",
            bytes.len()
        )),
        (Some(version), Some(_)) => {
            Err(format!("not a valid glTF file: it is GLB version {version}; only version 2 is supported"))
        }
        _ => Err("not a valid glTF file: its GLB header is cut short".to_string()),
    }
}

/// Only glTF 2.x is read: 1.0 has another structure, and a later major version may change meanings.
fn check_version(document: &gltf::Document) -> Result<(), String> {
    let asset = &document.as_json().asset;
    let two = |version: &str| {
        version.split_once('.').is_some_and(|(major, minor)| major == "2" && minor.parse::<u32>().is_ok())
    };
    if !two(&asset.version) {
        return Err(format!("its asset.version is \"{}\"; only glTF 2.x is supported", asset.version));
    }
    match &asset.min_version {
        Some(min) if min != "2.0" => {
            Err(format!("its asset.minVersion is \"{min}\"; nullpath reads what glTF 2.0 defines"))
        }
        _ => Ok(()),
    }
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

/// The data of the file's buffers, each exactly its `byteLength`: from the `.glb`'s binary chunk
/// `blob`, a `data:` URI or a file (see [`source`]).
fn buffers(document: &gltf::Document, mut blob: Option<Vec<u8>>, sources: Sources<'_>) -> Result<Vec<Vec<u8>>, String> {
    document
        .buffers()
        .map(|buffer| {
            let length = buffer.length();
            let what = match buffer.source() {
                gltf::buffer::Source::Bin => format!("buffer {} (the .glb's binary chunk)", buffer.index()),
                gltf::buffer::Source::Uri(uri) => format!("buffer {} ('{}')", buffer.index(), short(uri)),
            };
            if length == 0 {
                return Err(format!("{what}: its byteLength is 0; a buffer holds at least 1 byte"));
            }
            match buffer.source() {
                gltf::buffer::Source::Bin => {
                    let mut data =
                        blob.take().ok_or_else(|| format!("{what}: the file has no binary chunk left for it"))?;
                    if data.len() < length {
                        return Err(format!("{what}: holds {} bytes, but the file declares {length}", data.len()));
                    }
                    data.truncate(length);
                    Ok(data)
                }
                gltf::buffer::Source::Uri(uri) => sources.read_prefix(uri, length).map_err(|e| format!("{what}: {e}")),
            }
        })
        .collect()
}

/// A URI fit for a message: `data:` URIs are cut short.
fn short(uri: &str) -> String {
    if uri.starts_with("data:") {
        format!("{}…", uri.chars().take(24).collect::<String>())
    } else {
        uri.to_string()
    }
}

/// Nodes nested deeper than this are refused: glTF allows no cycles, but a file may have one, and
/// the hierarchy is walked recursively.
const MAX_DEPTH: usize = 256;

/// How a node stands in the walk of [`placements_per_node`].
#[derive(Clone, Copy, PartialEq)]
enum Mark {
    New,
    Open,
    Done,
}

/// How many times each node is placed: once for each way down to it from `roots`, counted (with
/// saturating arithmetic) without placing anything, in time linear in the size of the file.
fn placements_per_node(document: &gltf::Document, roots: &[gltf::Node<'_>]) -> Result<Vec<u64>, String> {
    let mut marks = vec![Mark::New; document.nodes().len()];
    let mut order = Vec::new();
    for root in roots {
        parents_last(root, &mut marks, &mut order, 0)?;
    }
    let mut placed = vec![0u64; marks.len()];
    for root in roots {
        placed[root.index()] = placed[root.index()].saturating_add(1);
    }
    // Every parent before its children: each passes on its count, complete, to each listing.
    for node in order.iter().rev() {
        let here = placed[node.index()];
        for child in node.children() {
            placed[child.index()] = placed[child.index()].saturating_add(here);
        }
    }
    Ok(placed)
}

/// Appends the nodes below `node` that are not yet in `order`, and then `node` itself, each after
/// all of its children (a depth-first post-order); refuses a cycle.
fn parents_last<'a>(
    node: &gltf::Node<'a>,
    marks: &mut [Mark],
    order: &mut Vec<gltf::Node<'a>>,
    depth: usize,
) -> Result<(), String> {
    match marks[node.index()] {
        Mark::Done => return Ok(()),
        Mark::Open => {
            return Err(format!("{}: it is its own descendant (the node hierarchy has a cycle)", node_name(node)))
        }
        Mark::New if depth > MAX_DEPTH => {
            return Err(format!("{}: nodes nest deeper than {MAX_DEPTH} levels", node_name(node)))
        }
        Mark::New => {}
    }
    marks[node.index()] = Mark::Open;
    for child in node.children() {
        parents_last(&child, marks, order, depth + 1)?;
    }
    marks[node.index()] = Mark::Done;
    order.push(node.clone());
    Ok(())
}

/// Refuses a hierarchy that places more than the limits allow ([`MAX_PLACED_PRIMITIVES`],
/// [`MAX_PLACED_NODES`], [`MAX_PLACED_TRIANGLES`]), given how often each node is placed.
fn check_placements(
    document: &gltf::Document,
    placed: &[u64],
    first_primitive: &[usize],
    primitives: &[Primitive],
    materials: &[GltfMaterial],
) -> Result<(), String> {
    let mut uses = vec![0u64; primitives.len()];
    let mut nodes = 0u64;
    for node in document.nodes() {
        let here = placed[node.index()];
        nodes = nodes.saturating_add(here);
        if let Some(mesh) = node.mesh() {
            let first = first_primitive[mesh.index()];
            for u in &mut uses[first..first + mesh.primitives().len()] {
                *u = u.saturating_add(here);
            }
        }
    }
    let total = uses.iter().fold(0u64, |sum, &u| sum.saturating_add(u));
    if total > MAX_PLACED_PRIMITIVES {
        return Err(format!(
            "the node hierarchy places {total} primitives; at most {MAX_PLACED_PRIMITIVES} are supported"
        ));
    }
    if nodes > MAX_PLACED_NODES {
        return Err(format!("the node hierarchy places {nodes} nodes; at most {MAX_PLACED_NODES} are supported"));
    }
    // As `gltf_object` places them: copied at each placement if placed once or emitting, else once.
    let triangles = primitives.iter().zip(&uses).fold(0u64, |sum, (p, &u)| {
        let emits = p.material.and_then(|m| materials.get(m)).is_some_and(|m| m.emission.is_some());
        let copies = if emits { u } else { u.min(1) };
        sum.saturating_add((p.triangle_count() as u64).saturating_mul(copies))
    });
    if triangles > MAX_PLACED_TRIANGLES {
        return Err(format!(
            "the node hierarchy places {triangles} triangles in world space (an emitting primitive's at \
             each placement); at most {MAX_PLACED_TRIANGLES} are supported"
        ));
    }
    Ok(())
}

/// What the node hierarchy places, as it is walked.
struct Found {
    /// Each mesh's first primitive in the flat list of primitives.
    first_primitive: Vec<usize>,
    placements: Vec<Placement>,
    lights: Vec<PunctualLight>,
    cameras: Vec<GltfCamera>,
    warnings: Vec<String>,
}

/// Places `node`'s mesh (each of its primitives), its light and its children under `parent`.
fn place(node: &gltf::Node<'_>, parent: &Transform, found: &mut Found, depth: usize) -> Result<(), String> {
    let name = node_name(node);
    if depth > MAX_DEPTH {
        return Err(format!("{name}: nodes nest deeper than {MAX_DEPTH} levels"));
    }
    if let gltf::scene::Transform::Decomposed { rotation, .. } = node.transform() {
        let length = rotation.iter().map(|&c| f64::from(c) * f64::from(c)).sum::<f64>().sqrt();
        if !((length - 1.0).abs() <= UNIT_TOLERANCE) {
            return Err(format!("{name}: its rotation {rotation:?} is not a unit quaternion (its length is {length})"));
        }
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
        let [r, g, b] = light.color().map(|c| c * light.intensity());
        let intensity = Rgb::new(r, g, b);
        if !(intensity.is_finite() && intensity.min_element() >= 0.0) {
            return Err(format!("{what}: its intensity {intensity} is not a finite non-negative colour"));
        }
        let position = transform.point(Vec3::ZERO);
        match light.kind() {
            gltf::khr_lights_punctual::Kind::Point => {
                found.lights.push(PunctualLight { position, intensity, spot: None });
            }
            gltf::khr_lights_punctual::Kind::Spot { inner_cone_angle, outer_cone_angle } => {
                let (inner, outer) = (f64::from(inner_cone_angle), f64::from(outer_cone_angle));
                if !(0.0 <= inner && inner < outer && outer <= std::f64::consts::FRAC_PI_2) {
                    return Err(format!(
                        "{what}: its cone angles must satisfy 0 ≤ innerConeAngle < outerConeAngle ≤ π/2, \
                         got {inner_cone_angle} and {outer_cone_angle}"
                    ));
                }
                // A spot shines along its node's −z axis.
                let axis = transform.vector(Vec3::NEG_Z).normalize_or_zero();
                let spot = SpotCone { axis, cos_inner: inner.cos(), cos_outer: outer.cos() };
                found.lights.push(PunctualLight { position, intensity, spot: Some(spot) });
            }
            gltf::khr_lights_punctual::Kind::Directional => {
                found.warnings.push(format!("{what}: directional lights are not imported"));
            }
        }
    }
    if let Some(camera) = node.camera() {
        let what = named("camera", camera.index(), camera.name());
        match camera.projection() {
            gltf::camera::Projection::Perspective(p) => {
                let yfov = f64::from(p.yfov());
                if !(yfov > 0.0 && yfov < std::f64::consts::PI) {
                    return Err(format!("{what}: its yfov {} must lie in (0, π) radians", p.yfov()));
                }
                let name = camera.name().or(node.name()).map_or_else(|| what.clone(), str::to_owned);
                found.cameras.push(GltfCamera { name, transform, yfov });
            }
            gltf::camera::Projection::Orthographic(_) => {
                found.warnings.push(format!("{what}: orthographic cameras are not imported"));
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

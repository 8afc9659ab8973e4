//! glTF 2.0 import: small files written by the tests themselves (JSON and a `.bin` buffer, or a
//! `.glb`), placed by scene files; what lands in the world, and how it renders.

#![allow(clippy::unwrap_used)] // A panic is a failed test.

use render::geometry::{Ray, Vec3};
use render::material::{Bsdf, Material};
use render::shape::Shape;
use serde_json::{json, Value};
use spacetime::Region;
use std::path::{Path, PathBuf};
use std::sync::atomic::AtomicBool;
use std::sync::Arc;

/// One mesh of a test file: a single triangle primitive.
struct Mesh {
    positions: Vec<[f32; 3]>,
    uvs: Option<Vec<[f32; 2]>>,
    indices: Vec<u32>,
    material: Option<usize>,
    mode: u32,
}

impl Mesh {
    fn new(positions: Vec<[f32; 3]>, indices: Vec<u32>) -> Self {
        Self { positions, uvs: None, indices, material: None, mode: 4 }
    }

    /// The square `[-a, a]²` in the plane `y = 0`, wound so that it faces −y (down).
    fn square_facing_down(a: f32) -> Self {
        let mut m = Self::new(vec![[-a, 0.0, -a], [a, 0.0, -a], [a, 0.0, a], [-a, 0.0, a]], vec![0, 1, 2, 0, 2, 3]);
        m.uvs = Some(vec![[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]]);
        m
    }

    fn with_material(mut self, material: usize) -> Self {
        self.material = Some(material);
        self
    }
}

/// A fresh directory for one test.
fn temp_dir(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("nullpath-gltf-test-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// The glTF JSON for `meshes` (their data in one buffer, `buffer` bytes long) and the buffer.
fn document(meshes: &[Mesh], nodes: Value, extra: Value) -> (Value, Vec<u8>) {
    let (mut bin, mut views, mut accessors, mut gltf_meshes) = (Vec::new(), Vec::new(), Vec::new(), Vec::new());
    let mut view = |bin: &mut Vec<u8>, bytes: Vec<u8>| {
        views.push(json!({ "buffer": 0, "byteOffset": bin.len(), "byteLength": bytes.len() }));
        bin.extend(bytes);
        views.len() - 1
    };
    for m in meshes {
        let floats: Vec<u8> = m.positions.iter().flatten().flat_map(|x| x.to_le_bytes()).collect();
        let finite = |k: usize| m.positions.iter().map(move |p| p[k]).filter(|x| x.is_finite());
        let min: Vec<f32> = (0..3).map(|k| finite(k).fold(f32::INFINITY, f32::min)).collect();
        let max: Vec<f32> = (0..3).map(|k| finite(k).fold(f32::NEG_INFINITY, f32::max)).collect();
        let v = view(&mut bin, floats);
        accessors.push(json!({ "bufferView": v, "componentType": 5126, "count": m.positions.len(), "type": "VEC3",
                               "min": min, "max": max }));
        let mut attributes = json!({ "POSITION": accessors.len() - 1 });
        if let Some(uvs) = &m.uvs {
            let v = view(&mut bin, uvs.iter().flatten().flat_map(|x| x.to_le_bytes()).collect());
            accessors.push(json!({ "bufferView": v, "componentType": 5126, "count": uvs.len(), "type": "VEC2" }));
            attributes["TEXCOORD_0"] = json!(accessors.len() - 1);
        }
        let v = view(&mut bin, m.indices.iter().flat_map(|i| i.to_le_bytes()).collect());
        accessors.push(json!({ "bufferView": v, "componentType": 5125, "count": m.indices.len(), "type": "SCALAR" }));
        let mut primitive = json!({ "attributes": attributes, "indices": accessors.len() - 1, "mode": m.mode });
        if let Some(material) = m.material {
            primitive["material"] = json!(material);
        }
        gltf_meshes.push(json!({ "primitives": [primitive] }));
    }
    let node_count = nodes.as_array().map_or(0, Vec::len);
    let mut doc = json!({
        "asset": { "version": "2.0" },
        "scene": 0,
        "scenes": [{ "nodes": (0..node_count).filter(|i| !is_child(&nodes, *i)).collect::<Vec<_>>() }],
        "nodes": nodes,
        "meshes": gltf_meshes,
        "accessors": accessors,
        "bufferViews": views,
        "buffers": [{ "byteLength": bin.len() }],
    });
    for (key, value) in extra.as_object().into_iter().flatten() {
        doc[key] = value.clone();
    }
    (doc, bin)
}

/// Whether node `i` is some node's child.
fn is_child(nodes: &Value, i: usize) -> bool {
    nodes.as_array().into_iter().flatten().any(|n| n["children"].as_array().is_some_and(|c| c.contains(&json!(i))))
}

/// Writes `name.gltf` and `name.bin` into `dir`; returns the glTF file's name.
fn write_gltf(dir: &Path, name: &str, meshes: &[Mesh], nodes: Value, extra: Value) -> String {
    let (mut doc, bin) = document(meshes, nodes, extra);
    doc["buffers"][0]["uri"] = json!(format!("{name}.bin"));
    std::fs::write(dir.join(format!("{name}.bin")), bin).unwrap();
    std::fs::write(dir.join(format!("{name}.gltf")), serde_json::to_vec_pretty(&doc).unwrap()).unwrap();
    format!("{name}.gltf")
}

/// Writes `name.glb` (JSON and binary chunks) into `dir`; returns its name.
fn write_glb(dir: &Path, name: &str, meshes: &[Mesh], nodes: Value, extra: Value) -> String {
    let (doc, mut bin) = document(meshes, nodes, extra);
    let mut json = serde_json::to_vec(&doc).unwrap();
    while json.len() % 4 != 0 {
        json.push(b' ');
    }
    while bin.len() % 4 != 0 {
        bin.push(0);
    }
    let total = 12 + 8 + json.len() + 8 + bin.len();
    let mut glb = Vec::new();
    for word in [0x4654_6C67, 2, total as u32, json.len() as u32, 0x4E4F_534A] {
        glb.extend(u32::to_le_bytes(word));
    }
    glb.extend(json);
    glb.extend(u32::to_le_bytes(bin.len() as u32));
    glb.extend(u32::to_le_bytes(0x004E_4942));
    glb.extend(bin);
    std::fs::write(dir.join(format!("{name}.glb")), glb).unwrap();
    format!("{name}.glb")
}

/// Loads a scene file written into `dir`.
fn load(dir: &Path, text: &str) -> Result<render::scene::Scene, scene::SceneError> {
    let path = dir.join("scene.toml");
    std::fs::write(&path, text).unwrap();
    scene::load(&path)
}

const CAMERA: &str = "[camera]\nposition = [0, 0, 10]\nlook_at = [0, 0, 0]\nfov = 40\n";

fn one_triangle() -> Mesh {
    Mesh::new(vec![[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]], vec![0, 1, 2])
}

#[test]
fn a_glb_quad_is_two_triangles() {
    let dir = temp_dir("count");
    let file = write_glb(&dir, "quad", &[Mesh::square_facing_down(1.0)], json!([{ "mesh": 0 }]), json!({}));
    let s = load(&dir, &format!("{CAMERA}[[objects]]\ngltf = \"{file}\"\n")).unwrap();
    let objects = s.world.objects(Region::Upper);
    assert_eq!(objects.len(), 2);
    assert!(objects.iter().all(|o| matches!(o.shape, Shape::Triangle(_))), "placed once: baked");
    assert!((objects.iter().map(|o| o.shape.area()).sum::<f64>() - 4.0).abs() < 1e-9);
}

#[test]
fn a_rotated_scaled_child_node_lands_where_its_transforms_put_it() {
    let dir = temp_dir("transform");
    // Parent: translate (1, 2, 3). Child: scale 2, then 90° about z (quaternion [x, y, z, w]).
    let h = std::f32::consts::FRAC_1_SQRT_2;
    let nodes = json!([
        { "translation": [1.0, 2.0, 3.0], "children": [1] },
        { "rotation": [0.0, 0.0, h, h], "scale": [2.0, 2.0, 2.0], "mesh": 0 },
    ]);
    let file = write_gltf(&dir, "tree", &[one_triangle()], nodes, json!({}));
    // The object's own transform comes after the file's: translate by (0, 0, 10).
    let text = format!("{CAMERA}[[objects]]\ngltf = \"{file}\"\ntransform = {{ translate = [0, 0, 10] }}\n");
    let s = load(&dir, &text).unwrap();
    let objects = s.world.objects(Region::Upper);
    assert_eq!(objects.len(), 1);
    let Shape::Triangle(t) = &objects[0].shape else { panic!("a triangle") };
    // (0,0,0), (1,0,0), (0,1,0) scaled by 2: (0,0,0), (2,0,0), (0,2,0); rotated: (0,0,0),
    // (0,2,0), (−2,0,0); translated by (1, 2, 13).
    let expected = [Vec3::new(1.0, 2.0, 13.0), Vec3::new(1.0, 4.0, 13.0), Vec3::new(-1.0, 2.0, 13.0)];
    for e in expected {
        assert!(t.vertices().iter().any(|v| (*v - e).length() < 1e-6), "{e} not among {:?}", t.vertices());
    }
    // A matrix node means the same as its TRS.
    let m = json!([{ "matrix": [0.0, 2.0, 0.0, 0.0, -2.0, 0.0, 0.0, 0.0, 0.0, 0.0, 2.0, 0.0, 1.0, 2.0, 3.0, 1.0], "mesh": 0 }]);
    let file = write_gltf(&dir, "matrix", &[one_triangle()], m, json!({}));
    let s = load(&dir, &format!("{CAMERA}[[objects]]\ngltf = \"{file}\"\n")).unwrap();
    let Shape::Triangle(t) = &s.world.objects(Region::Upper)[0].shape else { panic!("a triangle") };
    for e in expected.map(|e| e - Vec3::new(0.0, 0.0, 10.0)) {
        assert!(t.vertices().iter().any(|v| (*v - e).length() < 1e-6), "{e} not among {:?}", t.vertices());
    }
}

#[test]
fn two_placements_of_one_mesh_share_its_triangles() {
    let dir = temp_dir("instances");
    let nodes = json!([{ "mesh": 0 }, { "mesh": 0, "translation": [5.0, 0.0, 0.0], "scale": [2.0, 2.0, 2.0] }]);
    let file = write_gltf(&dir, "pair", &[Mesh::square_facing_down(1.0)], nodes, json!({}));
    let s = load(&dir, &format!("{CAMERA}[[objects]]\ngltf = \"{file}\"\n")).unwrap();
    let objects = s.world.objects(Region::Upper);
    assert_eq!(objects.len(), 2, "one object per placement, not per triangle");
    let instance = |i: usize| match &objects[i].shape {
        Shape::Instance(instance) => instance.clone(),
        other => panic!("an instance, not {other:?}"),
    };
    let (a, b) = (instance(0), instance(1));
    assert!(Arc::ptr_eq(a.mesh(), b.mesh()), "one shared mesh");
    assert_eq!(a.mesh().triangle_count(), 2, "stored once: two triangles, not four");
    assert!((a.area() - 4.0).abs() < 1e-9 && (b.area() - 16.0).abs() < 1e-9);
    // Each placement is hit where it stands, seen from below.
    for (x, object) in [(0.5, 0), (5.5, 1)] {
        let ray = Ray::new(Vec3::new(x, -3.0, 0.5), Vec3::Y, 10.0);
        let (hit, t) = s.world.intersect(Region::Upper, &ray).unwrap();
        assert_eq!(hit, object);
        assert!((t - 3.0).abs() < 1e-9);
        let surface = s.world.surface(Region::Upper, hit, &ray, t);
        assert!((surface.ng + Vec3::Y).length() < 1e-9, "faces down: {}", surface.ng);
    }
}

/// Renders `scene` and returns its pixels.
fn render(s: &render::scene::Scene) -> Vec<[f64; 3]> {
    let (film, stats) = render::renderer::render(s, &AtomicBool::new(false), &|_, _| {});
    assert_eq!(stats.nan_samples, 0);
    (0..s.settings.height)
        .flat_map(|y| (0..s.settings.width).map(move |x| (x, y)))
        .map(|(x, y)| film.pixel_f64(x, y))
        .collect()
}

#[test]
fn a_smooth_metal_renders_as_the_mirror_does() {
    let dir = temp_dir("mirror");
    let materials = json!({ "materials": [{ "name": "steel", "pbrMetallicRoughness": {
        "baseColorFactor": [0.9, 0.8, 0.7, 1.0], "metallicFactor": 1.0, "roughnessFactor": 0.0 } }] });
    // A floor mirror (the square faces down; turned over, it faces up) below a red ball.
    let nodes = json!([{ "mesh": 0, "rotation": [1.0, 0.0, 0.0, 0.0], "scale": [3.0, 3.0, 3.0] }]);
    let file = write_gltf(&dir, "mirror", &[Mesh::square_facing_down(1.0).with_material(0)], nodes, materials);
    let scene = |material: &str| {
        format!(
            "[camera]\nposition = [0, 2, 6]\nlook_at = [0, 0, 0]\nfov = 40\n\
             [render]\nwidth = 12\nheight = 8\nspp = 4\n[sky]\ntype = \"constant\"\nradiance = [0.2, 0.3, 0.5]\n\
             [[objects]]\nshape = {{ type = \"sphere\", center = [0, 1, 0], radius = 0.5 }}\n\
             material = {{ type = \"diffuse\", reflectance = [0.8, 0.1, 0.1] }}\n\
             [[objects]]\ngltf = \"{file}\"\n{material}"
        )
    };
    let gltf = load(&dir, &scene("")).unwrap();
    assert!(gltf.world.materials.iter().any(|m| matches!(m, Material::Mirror { .. })));
    let mirror = load(&dir, &scene("material = { type = \"mirror\", reflectance = [0.9, 0.8, 0.7] }\n")).unwrap();
    let (a, b) = (render(&gltf), render(&mirror));
    let spread =
        a.iter().map(|p| p[0]).fold(f64::NEG_INFINITY, f64::max) - a.iter().map(|p| p[0]).fold(f64::INFINITY, f64::min);
    assert!(spread > 0.05, "the picture shows something: spread {spread}");
    for (pa, pb) in a.iter().zip(&b) {
        for k in 0..3 {
            assert!((pa[k] - pb[k]).abs() <= 1e-6 * pb[k].max(1.0), "{pa:?} vs {pb:?}");
        }
    }
}

#[test]
fn a_base_colour_texel_shows_where_its_uv_says() {
    let dir = temp_dir("texture");
    // A 2×1 PNG: orange (255, 128, 0) on the left (u < ½), blue on the right.
    const PNG: [u8; 72] = [
        137, 80, 78, 71, 13, 10, 26, 10, 0, 0, 0, 13, 73, 72, 68, 82, 0, 0, 0, 2, 0, 0, 0, 1, 8, 2, 0, 0, 0, 123, 64,
        232, 221, 0, 0, 0, 15, 73, 68, 65, 84, 120, 156, 99, 248, 223, 192, 192, 192, 240, 31, 0, 9, 128, 2, 127, 23,
        129, 201, 75, 0, 0, 0, 0, 73, 69, 78, 68, 174, 66, 96, 130,
    ];
    std::fs::write(dir.join("tiny.png"), PNG).unwrap();
    let extra = json!({
        "materials": [{ "pbrMetallicRoughness": { "baseColorTexture": { "index": 0 }, "metallicFactor": 0.0 } }],
        "textures": [{ "source": 0 }],
        "images": [{ "uri": "tiny.png" }],
    });
    let file =
        write_gltf(&dir, "textured", &[Mesh::square_facing_down(1.0).with_material(0)], json!([{ "mesh": 0 }]), extra);
    let s = load(&dir, &format!("{CAMERA}[[objects]]\ngltf = \"{file}\"\n")).unwrap();
    // uv (0, 0) is at (−1, 0, −1) and u grows with x: the texel centres (u = ¼, ¾) are at x = ∓½.
    let linear = |c: f32| render::texture::image_data::srgb_to_linear(c / 255.0);
    for (x, expected) in [(-0.5, [linear(255.0), linear(128.0), 0.0]), (0.5, [0.0, 0.0, 1.0])] {
        let ray = Ray::new(Vec3::new(x, -3.0, 0.2), Vec3::Y, 10.0);
        let (object, t) = s.world.intersect(Region::Upper, &ray).unwrap();
        let hit = s.world.surface(Region::Upper, object, &ray, t);
        let material = &s.world.materials[s.world.object(Region::Upper, object).material];
        let Bsdf::RoughPlastic { diffuse, .. } = material.bsdf(hit.uv, hit.p) else { panic!("{material:?}") };
        assert!((diffuse - render::rgb::Rgb::from_array(expected)).abs().max_element() < 1e-6, "at x = {x}: {diffuse}");
    }
}

#[test]
fn a_normal_texture_bends_the_shading_normal_in_the_tangent_frame() {
    let dir = temp_dir("normal-map");
    // The 2×1 PNG above, read as linear data: on the left (1, ½, 0), a normal below the surface,
    // which is not taken; on the right (0, 0, 1), the tangent-space normal (−s, −s, 1) for scale s.
    const PNG: [u8; 72] = [
        137, 80, 78, 71, 13, 10, 26, 10, 0, 0, 0, 13, 73, 72, 68, 82, 0, 0, 0, 2, 0, 0, 0, 1, 8, 2, 0, 0, 0, 123, 64,
        232, 221, 0, 0, 0, 15, 73, 68, 65, 84, 120, 156, 99, 248, 223, 192, 192, 192, 240, 31, 0, 9, 128, 2, 127, 23,
        129, 201, 75, 0, 0, 0, 0, 73, 69, 78, 68, 174, 66, 96, 130,
    ];
    std::fs::write(dir.join("tiny.png"), PNG).unwrap();
    let scale = 0.5;
    let extra = json!({
        "materials": [{ "normalTexture": { "index": 0, "scale": scale }, "pbrMetallicRoughness": { "metallicFactor": 0.0 } }],
        "textures": [{ "source": 0 }],
        "images": [{ "uri": "tiny.png" }],
    });
    let file =
        write_gltf(&dir, "bumpy", &[Mesh::square_facing_down(1.0).with_material(0)], json!([{ "mesh": 0 }]), extra);
    let s = load(&dir, &format!("{CAMERA}[[objects]]\ngltf = \"{file}\"\n")).unwrap();
    // The square faces −y; u grows with x and v with z, so the tangent frame is T = x, B = N × T
    // = z, N = −y, and the right texel's normal is (−s x − s z − y)/|…|.
    let shading_normal = |x: f64| {
        let ray = Ray::new(Vec3::new(x, -3.0, 0.2), Vec3::Y, 10.0);
        let (object, t) = s.world.intersect(Region::Upper, &ray).unwrap();
        s.world.surface(Region::Upper, object, &ray, t).ns
    };
    assert!((shading_normal(-0.5) + Vec3::Y).length() < 1e-9, "{}", shading_normal(-0.5));
    let expected = Vec3::new(-scale, -1.0, -scale).normalize();
    assert!((shading_normal(0.5) - expected).length() < 1e-6, "{} against {expected}", shading_normal(0.5));
}

#[test]
fn an_emissive_square_lights_the_floor_below_to_its_analytic_irradiance() {
    // A square of half-side a and radiance L, facing down at height h above a diffuse floor of
    // reflectance ρ: on the axis, E = 4L·X/√(1+X²)·atan(X/√(1+X²)), X = a/h (four corner
    // rectangles, each with the form factor of Howell's catalogue B-3), and the floor's radiance
    // is ρE/π. The camera looks straight down at the point under the centre.
    let (a, h, radiance, rho) = (1.0f64, 1.0f64, 2.0f64, 0.5f64);
    let x = a / h;
    let s = x / (1.0 + x * x).sqrt();
    let expected = rho * 4.0 * radiance * s * (x / (1.0 + x * x).sqrt()).atan() / std::f64::consts::PI;
    let dir = temp_dir("emissive");
    // Black and metallic: it reflects nothing back at the floor (Schlick f0 = 0).
    let extra = json!({
        "extensionsUsed": ["KHR_materials_emissive_strength"],
        "materials": [{ "name": "panel", "emissiveFactor": [1.0, 1.0, 1.0],
            "extensions": { "KHR_materials_emissive_strength": { "emissiveStrength": radiance } },
            "pbrMetallicRoughness": { "baseColorFactor": [0.0, 0.0, 0.0, 1.0], "metallicFactor": 1.0 } }],
    });
    let nodes = json!([{ "mesh": 0, "translation": [0.0, h, 0.0] }]);
    let file = write_gltf(&dir, "panel", &[Mesh::square_facing_down(a as f32).with_material(0)], nodes, extra);
    let text = format!(
        "[camera]\nposition = [0, 0.5, 0]\nlook_at = [0, 0, 0]\nup = [0, 0, 1]\nfov = 2\n\
         [render]\nwidth = 2\nheight = 2\nspp = 1024\n\
         [[objects]]\nshape = {{ type = \"plane\", point = [0, 0, 0], normal = [0, 1, 0] }}\n\
         material = {{ type = \"diffuse\", reflectance = {rho} }}\n\
         [[objects]]\ngltf = \"{file}\"\n"
    );
    let s = load(&dir, &text).unwrap();
    assert_eq!(s.world.light_count(Region::Upper), 2, "the panel's two triangles are lights");
    let pixels = render(&s);
    let mean = pixels.iter().map(|p| p.iter().sum::<f64>() / 3.0).sum::<f64>() / pixels.len() as f64;
    assert!((mean / expected - 1.0).abs() < 0.02, "floor radiance {mean}, analytic {expected}");
}

#[test]
fn broken_files_are_clear_errors() {
    let dir = temp_dir("errors");
    let message = |text: String| load(&dir, &text).map(|_| ()).unwrap_err().to_string();
    let entry = |file: &str| format!("{CAMERA}[[objects]]\ngltf = \"{file}\"\n");
    let node = || json!([{ "mesh": 0 }]);

    let e = message(entry("missing.glb"));
    assert!(e.contains("missing.glb") && e.contains("cannot read") && e.contains("scene.toml:"), "{e}");

    let file = write_gltf(&dir, "nobin", &[one_triangle()], node(), json!({}));
    std::fs::remove_file(dir.join("nobin.bin")).unwrap();
    let e = message(entry(&file));
    assert!(e.contains("nobin.gltf") && e.contains("buffer 0 ('nobin.bin')"), "{e}");

    let draco = json!({ "extensionsUsed": ["KHR_draco_mesh_compression"], "extensionsRequired": ["KHR_draco_mesh_compression"] });
    let file = write_gltf(&dir, "draco", &[one_triangle()], node(), draco);
    let e = message(entry(&file));
    assert!(e.contains("requires the glTF extension KHR_draco_mesh_compression"), "{e}");
    // Only used, not required: a warning, and the mesh loads.
    let optional = json!({ "extensionsUsed": ["KHR_materials_sheen"] });
    let file = write_gltf(&dir, "sheen", &[one_triangle()], node(), optional);
    assert!(load(&dir, &entry(&file)).is_ok());

    let mut bad = one_triangle();
    bad.indices = vec![0, 1, 7];
    let file = write_gltf(&dir, "index", &[bad], node(), json!({}));
    let e = message(entry(&file));
    assert!(e.contains("mesh 0 primitive 0") && e.contains("vertex 7"), "{e}");

    let mut lines = one_triangle();
    lines.mode = 1;
    let file = write_gltf(&dir, "lines", &[lines], node(), json!({}));
    let e = message(entry(&file));
    assert!(e.contains("mesh 0 primitive 0") && e.contains("only triangles"), "{e}");

    let mut nan = one_triangle();
    nan.positions[1][0] = f32::NAN;
    let file = write_gltf(&dir, "nan", &[nan], node(), json!({}));
    let e = message(entry(&file));
    assert!(e.contains("vertex 1 has a non-finite position"), "{e}");

    std::fs::write(dir.join("garbage.glb"), b"glTF\x02\x00\x00\x00garbage").unwrap();
    let e = message(entry("garbage.glb"));
    assert!(e.contains("garbage.glb") && e.contains("not a valid glTF file"), "{e}");

    let file = write_gltf(
        &dir,
        "ok",
        &[one_triangle().with_material(0)],
        node(),
        json!({ "materials": [{ "name": "wood" }] }),
    );
    let e = message(format!("{}materials = {{ \"oak\" = {{ type = \"diffuse\" }} }}\n", entry(&file)));
    assert!(e.contains("no material named \"oak\"") && e.contains("\"wood\""), "{e}");
    let e = message(format!("{}shape = {{ type = \"sphere\", center = [0, 0, 0], radius = 1 }}\n", entry(&file)));
    assert!(e.contains("not both"), "{e}");
}

#[test]
fn materials_can_be_overridden_by_name_or_all_at_once() {
    let dir = temp_dir("overrides");
    let extra = json!({ "materials": [{ "name": "wood" }, { "name": "brass", "pbrMetallicRoughness": { "roughnessFactor": 0.4 } }] });
    let meshes = [one_triangle().with_material(0), one_triangle().with_material(1)];
    let file =
        write_gltf(&dir, "two", &meshes, json!([{ "mesh": 0 }, { "mesh": 1, "translation": [3.0, 0.0, 0.0] }]), extra);
    let kinds = |s: &render::scene::Scene| -> Vec<&'static str> {
        s.world
            .objects(Region::Upper)
            .iter()
            .map(|o| match &s.world.materials[o.material] {
                Material::Diffuse { .. } => "diffuse",
                Material::Mirror { .. } => "mirror",
                Material::Dielectric { .. } => "dielectric",
                Material::RoughConductor { .. } => "conductor",
                Material::RoughPlastic { .. } => "plastic",
                Material::NormalMapped { .. } => "normal-mapped",
            })
            .collect()
    };
    let base = format!("{CAMERA}[[objects]]\ngltf = \"{file}\"\n");
    // glTF's own: wood is non-metallic (metallicFactor defaults to 1: a metal); brass a rough metal.
    assert_eq!(kinds(&load(&dir, &base).unwrap()), ["conductor", "conductor"]);
    let by_name = format!("{base}materials = {{ wood = {{ type = \"diffuse\" }} }}\n");
    assert_eq!(kinds(&load(&dir, &by_name).unwrap()), ["diffuse", "conductor"]);
    let all = format!("{base}material = {{ type = \"mirror\" }}\n");
    assert_eq!(kinds(&load(&dir, &all).unwrap()), ["mirror", "mirror"]);
}

#[test]
fn a_point_light_lights_the_floor_by_the_inverse_square_law() {
    // A KHR_lights_punctual point light of intensity I at height h above a diffuse floor of
    // reflectance ρ: E = I/h² below it, and the floor's radiance is ρE/π. A directional light
    // is left out (with a warning).
    let (h, intensity, rho) = (2.0f64, 3.0f64, 0.5f64);
    let expected = rho * intensity / (h * h) / std::f64::consts::PI;
    let dir = temp_dir("point-light");
    let extra = json!({
        "extensionsUsed": ["KHR_lights_punctual"],
        "extensions": { "KHR_lights_punctual": { "lights": [
            { "type": "point", "color": [1.0, 1.0, 1.0], "intensity": intensity },
            { "type": "directional", "intensity": 100.0 },
        ] } },
    });
    let nodes = json!([
        { "translation": [0.0, h, 0.0], "extensions": { "KHR_lights_punctual": { "light": 0 } } },
        { "extensions": { "KHR_lights_punctual": { "light": 1 } } },
        { "mesh": 0, "translation": [50.0, 0.0, 0.0] },
    ]);
    let file = write_gltf(&dir, "lamp", &[one_triangle()], nodes, extra);
    let text = format!(
        "[camera]\nposition = [0, 0.5, 0]\nlook_at = [0, 0, 0]\nup = [0, 0, 1]\nfov = 2\n\
         [render]\nwidth = 2\nheight = 2\nspp = 256\n\
         [[objects]]\nshape = {{ type = \"plane\", point = [0, 0, 0], normal = [0, 1, 0] }}\n\
         material = {{ type = \"diffuse\", reflectance = {rho} }}\n\
         [[objects]]\ngltf = \"{file}\"\n"
    );
    let s = load(&dir, &text).unwrap();
    assert_eq!(s.world.light_count(Region::Upper), 1, "the point light only");
    let pixels = render(&s);
    let mean = pixels.iter().map(|p| p.iter().sum::<f64>() / 3.0).sum::<f64>() / pixels.len() as f64;
    assert!((mean / expected - 1.0).abs() < 0.01, "floor radiance {mean}, inverse square law {expected}");
}

#[test]
fn a_spot_light_lights_the_floor_inside_its_cone_with_its_falloff() {
    // A spot of intensity I at height h pointing straight down (its node's −z turned onto −y),
    // inner cone 15°, outer 30°: at angle θ from its axis the floor's irradiance is
    // E = I s(cos θ) cos³θ / h², s the glTF falloff, and its radiance ρE/π.
    let (h, intensity, rho) = (2.0f64, 3.0f64, 0.5f64);
    let (inner, outer) = (15f64.to_radians(), 30f64.to_radians());
    let dir = temp_dir("spot-light");
    let extra = json!({
        "extensionsUsed": ["KHR_lights_punctual"],
        "extensions": { "KHR_lights_punctual": { "lights": [
            { "type": "spot", "color": [1.0, 1.0, 1.0], "intensity": intensity,
              "spot": { "innerConeAngle": inner, "outerConeAngle": outer } },
        ] } },
    });
    let down = std::f64::consts::FRAC_1_SQRT_2;
    let nodes = json!([
        { "translation": [0.0, h, 0.0], "rotation": [-down, 0.0, 0.0, down],
          "extensions": { "KHR_lights_punctual": { "light": 0 } } },
        { "mesh": 0, "translation": [50.0, 0.0, 0.0] },
    ]);
    let file = write_gltf(&dir, "spot", &[one_triangle()], nodes, extra);
    for theta in [0f64, 22.5, 40.0].map(f64::to_radians) {
        let x = h * theta.tan();
        let text = format!(
            "[camera]\nposition = [{x}, 0.5, 0]\nlook_at = [{x}, 0, 0]\nup = [0, 0, 1]\nfov = 1\n\
             [render]\nwidth = 2\nheight = 2\nspp = 256\n\
             [[objects]]\nshape = {{ type = \"plane\", point = [0, 0, 0], normal = [0, 1, 0] }}\n\
             material = {{ type = \"diffuse\", reflectance = {rho} }}\n\
             [[objects]]\ngltf = \"{file}\"\n"
        );
        let s = load(&dir, &text).unwrap();
        let pixels = render(&s);
        let mean = pixels.iter().map(|p| p.iter().sum::<f64>() / 3.0).sum::<f64>() / pixels.len() as f64;
        let s_theta = ((theta.cos() - outer.cos()) / (inner.cos() - outer.cos())).clamp(0.0, 1.0).powi(2);
        let expected = rho * intensity * s_theta * theta.cos().powi(3) / (h * h) / std::f64::consts::PI;
        if expected == 0.0 {
            assert_eq!(mean, 0.0, "outside the cone, at {}°", theta.to_degrees());
        } else {
            let error = (mean / expected - 1.0).abs();
            assert!(error < 0.02, "at {}°: floor radiance {mean}, expected {expected}", theta.to_degrees());
        }
    }
    let extra = json!({
        "extensionsUsed": ["KHR_lights_punctual"],
        "extensions": { "KHR_lights_punctual": { "lights": [
            { "type": "spot", "intensity": 1.0, "spot": { "innerConeAngle": 0.5, "outerConeAngle": 0.4 } },
        ] } },
    });
    let nodes = json!([{ "extensions": { "KHR_lights_punctual": { "light": 0 } } }]);
    let file = write_gltf(&dir, "bad-spot", &[one_triangle()], nodes, extra);
    let text = format!("[camera]\nposition = [0, 1, 3]\nlook_at = [0, 0, 0]\n[[objects]]\ngltf = \"{file}\"\n");
    let err = load(&dir, &text).map(|_| ()).expect_err("inner cone wider than outer").to_string();
    assert!(err.contains("light 0") && err.contains("innerConeAngle < outerConeAngle"), "{err}");
}

#[test]
fn a_gltf_camera_frames_the_picture_as_the_same_camera_written_out_does() {
    // A camera node at (1, 2, 3) turned 90° about y looks along −x with y up; placed by the
    // object's transform (moved by 1 along z) it is the camera at (1, 2, 4) looking at
    // (0, 2, 4), with the file's 0.5 rad vertical field of view.
    let dir = temp_dir("camera");
    let half = std::f64::consts::FRAC_1_SQRT_2;
    let extra = json!({ "cameras": [
        { "name": "overview", "type": "perspective", "perspective": { "yfov": 0.5, "znear": 0.01 } },
        { "name": "plan", "type": "orthographic",
          "orthographic": { "xmag": 1.0, "ymag": 1.0, "znear": 0.01, "zfar": 10.0 } },
    ] });
    let nodes = json!([
        { "mesh": 0, "translation": [-3.0, 2.0, 4.0], "scale": [1.0, 3.0, 3.0] },
        { "camera": 0, "translation": [1.0, 2.0, 3.0], "rotation": [0.0, half, 0.0, half] },
        { "camera": 1 },
    ]);
    let file = write_gltf(&dir, "framed", &[one_triangle()], nodes, extra);
    let scene = |camera: &str| {
        format!(
            "{camera}\n[render]\nwidth = 12\nheight = 8\nspp = 4\n\
             [[objects]]\ngltf = \"{file}\"\ntransform = {{ translate = [0, 0, 1] }}\n\
             material = {{ type = \"diffuse\", reflectance = 0.8 }}\n\
             [[objects]]\nshape = {{ type = \"sphere\", center = [-2, 4, 4], radius = 1 }}\n\
             emission = {{ radiance = [3, 2, 1] }}\n"
        )
    };
    let imported = load(&dir, &scene("[camera]\ngltf_camera = \"overview\"")).unwrap();
    let fov = 0.5f64.to_degrees();
    let written =
        load(&dir, &scene(&format!("[camera]\nposition = [1, 2, 4]\nlook_at = [0, 2, 4]\nfov = {fov}"))).unwrap();
    let (a, b) = (render(&imported), render(&written));
    assert!(a.iter().flatten().any(|&v| v > 0.0), "the camera sees the lamp and the triangle");
    for (p, q) in a.iter().zip(&b) {
        assert!(p.iter().zip(q).all(|(x, y)| (x - y).abs() <= 1e-6 * (1.0 + y.abs())), "{p:?} against {q:?}");
    }
    // Errors: an unknown name lists the known ones (not the orthographic camera); a pose given
    // beside the glTF camera is refused.
    let err = load(&dir, &scene("[camera]\ngltf_camera = \"plan\"")).map(|_| ()).unwrap_err().to_string();
    assert!(err.contains("no camera named \"plan\"") && err.contains("\"overview\""), "{err}");
    let err = load(&dir, &scene("[camera]\ngltf_camera = \"overview\"\nposition = [0, 0, 0]"))
        .map(|_| ())
        .unwrap_err()
        .to_string();
    assert!(err.contains("leave out position"), "{err}");
}

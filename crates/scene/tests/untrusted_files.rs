//! Files named by scene files, glTF files and their URIs are untrusted: they are read only inside
//! the scene's folder tree (or a folder the person rendering allowed), only if they are regular
//! files, and a malformed glTF file is an error, never a panic, a hang or an exhausted memory.
//! The glTF files are written by the tests themselves: JSON, and small binary buffers.

#![allow(clippy::unwrap_used)] // A panic is a failed test.

mod common;

use serde_json::{json, Value};
use std::path::{Path, PathBuf};
use std::sync::mpsc;
use std::time::Duration;

/// A fresh folder holding `scene/` (where the scene file goes) and `outside/` beside it, each with
/// the triangle's buffer, `tri.bin`.
fn folders(name: &str) -> (PathBuf, PathBuf) {
    let dir = common::temp_dir(&format!("untrusted-{name}"));
    let (scene, outside) = (dir.join("scene"), dir.join("outside"));
    for d in [&scene, &outside] {
        std::fs::create_dir_all(d).unwrap();
        std::fs::write(d.join("tri.bin"), triangle().1).unwrap();
    }
    (scene, outside)
}

/// One triangle: three `VEC3` float positions (bytes 0–35) and three `u16` indices (36–41) in a
/// buffer of 44 bytes, `tri.bin`, placed by node 0.
fn triangle() -> (Value, Vec<u8>) {
    let mut bin: Vec<u8> =
        [[0f32, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]].iter().flatten().flat_map(|c| c.to_le_bytes()).collect();
    bin.extend([0u16, 1, 2].iter().flat_map(|i| i.to_le_bytes()));
    bin.extend([0, 0]);
    let doc = json!({
        "asset": { "version": "2.0" },
        "scene": 0,
        "scenes": [{ "nodes": [0] }],
        "nodes": [{ "mesh": 0 }],
        "meshes": [{ "primitives": [{ "attributes": { "POSITION": 0 }, "indices": 1 }] }],
        "accessors": [
            { "bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3", "min": [0, 0, 0], "max": [1, 1, 0] },
            { "bufferView": 1, "componentType": 5123, "count": 3, "type": "SCALAR" },
        ],
        "bufferViews": [
            { "buffer": 0, "byteOffset": 0, "byteLength": 36 },
            { "buffer": 0, "byteOffset": 36, "byteLength": 6 },
        ],
        "buffers": [{ "byteLength": 44, "uri": "tri.bin" }],
    });
    (doc, bin)
}

/// The triangle's document as `change` leaves it.
fn changed(change: impl FnOnce(&mut Value)) -> Value {
    let mut doc = triangle().0;
    change(&mut doc);
    doc
}

/// A scene file in `scene` placing the glTF file `file` (as written).
fn gltf_scene(scene: &Path, file: &str) -> PathBuf {
    scene_file(scene, &format!("{}[[objects]]\ngltf = \"{file}\"\n", common::CAMERA))
}

/// Writes `text` as `scene/scene.toml`; returns its path.
fn scene_file(scene: &Path, text: &str) -> PathBuf {
    let path = scene.join("scene.toml");
    std::fs::write(&path, text).unwrap();
    path
}

/// Writes `doc` as `scene/name.gltf` and loads a scene that places it.
fn load_gltf(scene: &Path, name: &str, doc: &Value) -> Result<render::scene::Scene, String> {
    std::fs::write(scene.join(name), serde_json::to_vec(doc).unwrap()).unwrap();
    scene::load(&gltf_scene(scene, name)).map_err(|e| e.to_string())
}

/// The error of loading `doc` as `name`; fails if it loads.
fn gltf_error(scene: &Path, name: &str, doc: &Value) -> String {
    match load_gltf(scene, name, doc) {
        Ok(_) => panic!("{name} was accepted"),
        Err(e) => e,
    }
}

/// `doc` as a binary glTF: the JSON chunk, and `bin` as the binary chunk.
fn glb(doc: &Value, bin: &[u8]) -> Vec<u8> {
    let mut json = serde_json::to_vec(doc).unwrap();
    json.resize(json.len().next_multiple_of(4), b' ');
    let total = 12 + 8 + json.len() + 8 + bin.len();
    let mut out = Vec::new();
    for word in [0x4654_6C67, 2, total as u32, json.len() as u32, 0x4E4F_534A] {
        out.extend(u32::to_le_bytes(word));
    }
    out.extend(json);
    out.extend(u32::to_le_bytes(bin.len() as u32));
    out.extend(u32::to_le_bytes(0x004E_4942));
    out.extend(bin);
    out
}

/// Runs `f` on another thread and returns what it returns; fails if it takes over 20 seconds
/// (opening a FIFO blocks, reading `/dev/zero` never ends).
fn promptly<T: Send + 'static>(f: impl FnOnce() -> T + Send + 'static) -> T {
    let (send, receive) = mpsc::channel();
    std::thread::spawn(move || send.send(f()));
    receive.recv_timeout(Duration::from_secs(20)).expect("returned promptly")
}

/// Whether `e` says the file named `written` lies outside the scene's folder, and nothing more
/// of it.
fn refused_as_outside(e: &str, written: &str) -> bool {
    e.contains(&format!("'{written}'")) && e.contains("outside the scene's folder") && !e.contains("bytes")
}

#[test]
fn the_triangle_loads_and_is_one_object() {
    let (scene, _) = folders("control");
    let s = load_gltf(&scene, "tri.gltf", &triangle().0).unwrap();
    assert_eq!(s.world.objects(spacetime::Region::Upper).len(), 1);
    std::fs::write(
        scene.join("tri.glb"),
        glb(&changed(|d| d["buffers"][0] = json!({ "byteLength": 44 })), &triangle().1),
    )
    .unwrap();
    scene::load(&gltf_scene(&scene, "tri.glb")).unwrap();
}

#[test]
fn gltf_buffer_uris_that_leave_the_scene_folder_are_refused_with_the_uri_named() {
    let (scene, outside) = folders("traversal");
    let secret = outside.join("tri.bin");
    #[cfg(unix)]
    {
        std::os::unix::fs::symlink(&secret, scene.join("link.bin")).unwrap();
        std::os::unix::fs::symlink(&outside, scene.join("linked")).unwrap();
    }
    let absolute = secret.display().to_string();
    let mut uris = vec![
        "../outside/tri.bin".to_string(),
        "%2E%2E/outside/tri.bin".to_string(),
        "%2e%2e%2Foutside%2Ftri.bin".to_string(),
        absolute.clone(),
        format!("file://{absolute}"),
        "/etc/passwd".to_string(),
        "file:///etc/shadow".to_string(),
        "/proc/self/environ".to_string(),
    ];
    if cfg!(unix) {
        uris.extend(["link.bin".to_string(), "linked/tri.bin".to_string()]);
    }
    for uri in &uris {
        let e = gltf_error(&scene, "tri.gltf", &changed(|d| d["buffers"][0]["uri"] = json!(uri)));
        assert!(refused_as_outside(&e, uri), "{uri}: {e}");
        assert!(e.contains("glTF file 'tri.gltf'") && e.contains("buffer 0"), "{e}");
    }
    // The same file, allowed by the person rendering: read, by any of the forms.
    let path = gltf_scene(&scene, "tri.gltf");
    for uri in ["../outside/tri.bin", "%2E%2E/outside/tri.bin", &absolute, &format!("file://{absolute}")] {
        std::fs::write(scene.join("tri.gltf"), changed(|d| d["buffers"][0]["uri"] = json!(uri)).to_string()).unwrap();
        scene::load_allowing(&path, None, std::slice::from_ref(&outside)).unwrap_or_else(|e| panic!("{uri}: {e}"));
    }
    let e = scene::load_allowing(&path, None, &[outside.join("nowhere")]).map(|_| ()).unwrap_err().to_string();
    assert!(e.contains("cannot allow reading") && e.contains("nowhere"), "{e}");
}

#[test]
fn every_other_file_a_scene_names_is_held_to_the_scene_folder() {
    let (scene, outside) = folders("kinds");
    std::fs::write(outside.join("m.gltf"), triangle().0.to_string()).unwrap();
    std::fs::write(outside.join("m.obj"), "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n").unwrap();
    std::fs::write(outside.join("tex.png"), common::TINY_PNG).unwrap();
    let absolute_png = outside.join("tex.png").display().to_string();
    // (scene text, the path as written)
    let cases = [
        ("[[objects]]\ngltf = \"../outside/m.gltf\"\n".to_string(), "../outside/m.gltf".to_string()),
        (
            "[[objects]]\nshape = { type = \"mesh\", file = \"../outside/m.obj\" }\n".to_string(),
            "../outside/m.obj".into(),
        ),
        (
            format!(
                "[materials.m]\ntype = \"diffuse\"\nreflectance = {{ type = \"image\", file = \"{absolute_png}\" }}\n"
            ),
            absolute_png.clone(),
        ),
        ("[sky]\ntype = \"equirect\"\nfile = \"../outside/tex.png\"\n".to_string(), "../outside/tex.png".into()),
    ];
    for (text, written) in &cases {
        let path = scene_file(&scene, &format!("{}{text}", common::CAMERA));
        let e = scene::load(&path).map(|_| ()).unwrap_err().to_string();
        assert!(refused_as_outside(&e, written), "{written}: {e}");
        scene::load_allowing(&path, None, std::slice::from_ref(&outside)).unwrap_or_else(|e| panic!("{written}: {e}"));
    }
    // A glTF file's image, by a path that leaves the folder.
    let doc = changed(|d| {
        d["materials"] = json!([{ "pbrMetallicRoughness": { "baseColorTexture": { "index": 0 } } }]);
        d["textures"] = json!([{ "source": 0 }]);
        d["images"] = json!([{ "uri": "../outside/tex.png" }]);
        d["meshes"][0]["primitives"][0]["material"] = json!(0);
    });
    let e = gltf_error(&scene, "textured.gltf", &doc);
    assert!(refused_as_outside(&e, "../outside/tex.png") && e.contains("image 0"), "{e}");
}

#[cfg(unix)]
#[test]
fn devices_and_pipes_are_refused_without_being_opened() {
    let (scene, _) = folders("special");
    for name in ["pipe.bin", "pipe.png", "pipe.obj", "pipe.gltf", "pipe.exr"] {
        let made = std::process::Command::new("mkfifo").arg(scene.join(name)).status().unwrap();
        assert!(made.success(), "mkfifo");
    }
    std::os::unix::fs::symlink("/dev/zero", scene.join("zero.bin")).unwrap();
    let dev = PathBuf::from("/dev");
    let image = |file: &str| {
        format!("[materials.m]\ntype = \"diffuse\"\nreflectance = {{ type = \"image\", file = \"{file}\" }}\n")
    };
    let mesh = |file: &str| format!("[[objects]]\nshape = {{ type = \"mesh\", file = \"{file}\" }}\n");
    let sky = |file: &str| format!("[sky]\ntype = \"equirect\"\nfile = \"{file}\"\n");
    let gltf = |file: &str| format!("[[objects]]\ngltf = \"{file}\"\n");
    let texts = [
        (image("pipe.png"), "pipe.png"),
        (mesh("pipe.obj"), "pipe.obj"),
        (sky("pipe.exr"), "pipe.exr"),
        (gltf("pipe.gltf"), "pipe.gltf"),
        (image("/dev/zero"), "/dev/zero"),
        (mesh("/dev/zero"), "/dev/zero"),
        (gltf("/dev/zero"), "/dev/zero"),
    ];
    for (text, written) in texts {
        let path = scene_file(&scene, &format!("{}{text}", common::CAMERA));
        // /dev allowed, so that the device is refused for what it is, not for where it is.
        let e = promptly({
            let dev = dev.clone();
            move || scene::load_allowing(&path, None, &[dev]).map(|_| ()).unwrap_err().to_string()
        });
        assert!(e.contains(&format!("'{written}'")) && e.contains("not a regular file"), "{written}: {e}");
    }
    // As a glTF buffer: a pipe, /dev/zero by path and by a link in the scene's folder.
    for uri in ["pipe.bin", "/dev/zero", "file:///dev/zero", "zero.bin"] {
        let doc = changed(|d| d["buffers"][0]["uri"] = json!(uri));
        std::fs::write(scene.join("tri.gltf"), doc.to_string()).unwrap();
        let path = gltf_scene(&scene, "tri.gltf");
        let e = promptly({
            let dev = dev.clone();
            move || scene::load_allowing(&path, None, &[dev]).map(|_| ()).unwrap_err().to_string()
        });
        assert!(e.contains(&format!("buffer 0 ('{uri}')")) && e.contains("not a regular file"), "{uri}: {e}");
    }
}

#[test]
fn gltf_data_that_panicked_the_gltf_crate_is_an_error() {
    let (scene, _) = folders("panics");
    // A stride of 4 bytes under 12-byte elements: the crate asserted the element fits.
    let e = gltf_error(&scene, "stride.gltf", &changed(|d| d["bufferViews"][0]["byteStride"] = json!(4)));
    assert!(e.contains("mesh 0 primitive 0") && e.contains("byteStride of 4 bytes"), "{e}");
    // Float indices: the crate reached `unreachable!`.
    let e = gltf_error(&scene, "float-index.gltf", &changed(|d| d["accessors"][1]["componentType"] = json!(5126)));
    assert!(e.contains("indices accessor (accessor 1) is SCALAR of FLOAT"), "{e}");
}

#[test]
fn invalid_gltf_that_was_accepted_is_refused() {
    let (scene, _) = folders("invalid");
    let cases: Vec<(&str, Value, &[&str])> = vec![
        (
            "vec2.gltf",
            changed(|d| d["accessors"][0]["type"] = json!("VEC2")),
            &["POSITION accessor (accessor 0) is VEC2 of FLOAT", "must be VEC3 of FLOAT"],
        ),
        ("u8.gltf", changed(|d| d["accessors"][0]["componentType"] = json!(5121)), &["VEC3 of UNSIGNED_BYTE"]),
        ("v1.gltf", changed(|d| d["asset"]["version"] = json!("1.0")), &["asset.version is \"1.0\"", "only glTF 2.x"]),
        ("v3.gltf", changed(|d| d["asset"]["version"] = json!("3.0")), &["asset.version is \"3.0\""]),
        (
            "empty.gltf",
            changed(|d| d["buffers"][0]["byteLength"] = json!(0)),
            &["buffer 0 ('tri.bin')", "byteLength is 0"],
        ),
        (
            "short.gltf",
            changed(|d| d["buffers"][0]["byteLength"] = json!(100)),
            &["holds 44 bytes, fewer than the 100 declared"],
        ),
        (
            "zero-q.gltf",
            changed(|d| d["nodes"][0]["rotation"] = json!([0, 0, 0, 0])),
            &["node 0", "not a unit quaternion"],
        ),
        (
            "long-q.gltf",
            changed(|d| d["nodes"][0]["rotation"] = json!([0, 0, 0, 2])),
            &["node 0", "not a unit quaternion"],
        ),
        (
            "count.gltf",
            changed(|d| d["accessors"][0]["count"] = json!(4)),
            &["POSITION accessor", "do not fit in its bufferView 0"],
        ),
        ("offset.gltf", changed(|d| d["accessors"][0]["byteOffset"] = json!(4)), &["POSITION accessor", "do not fit"]),
        (
            "view.gltf",
            changed(|d| d["bufferViews"][1]["byteOffset"] = json!(40)),
            &["bufferView 1", "past the end of buffer 0 (44 bytes)"],
        ),
        (
            "cycle.gltf",
            changed(|d| d["nodes"] = json!([{ "mesh": 0, "children": [1] }, { "children": [0] }])),
            &["node 0", "cycle"],
        ),
        (
            "scheme.gltf",
            changed(|d| d["buffers"][0]["uri"] = json!("https://example.com/tri.bin")),
            &["buffer 0", "only data: URIs and paths"],
        ),
    ];
    for (name, doc, fragments) in cases {
        let e = gltf_error(&scene, name, &doc);
        assert!(fragments.iter().all(|f| e.contains(f)) && e.contains(name), "{name}: {e}");
    }
    // A GLB whose header misstates its total length.
    let mut bytes = glb(&changed(|d| d["buffers"][0] = json!({ "byteLength": 44 })), &triangle().1);
    let wrong = bytes.len() as u32 + 4;
    bytes[8..12].copy_from_slice(&wrong.to_le_bytes());
    std::fs::write(scene.join("length.glb"), &bytes).unwrap();
    let e = scene::load(&gltf_scene(&scene, "length.glb")).map(|_| ()).unwrap_err().to_string();
    assert!(e.contains("length.glb") && e.contains("GLB header gives a length of"), "{e}");
}

#[test]
fn a_hierarchy_that_places_a_primitive_exponentially_often_is_refused_at_once() {
    // Each of 24 nodes lists the next twice; the last holds the mesh: 2^24 placements of it from a
    // file of a few kilobytes.
    let (scene, _) = folders("exponential");
    let mut nodes: Vec<Value> = (0..24).map(|i| json!({ "children": [i + 1, i + 1] })).collect();
    nodes.push(json!({ "mesh": 0 }));
    let doc = changed(|d| d["nodes"] = json!(nodes));
    // Refused before the walk: 2^24 placements would take minutes and gigabytes.
    let e = promptly({
        let scene = scene.clone();
        move || gltf_error(&scene, "exponential.gltf", &doc)
    });
    assert!(e.contains("places 16777216 primitives; at most 1048576 are supported"), "{e}");
    // Without the mesh the walk alone would be as long: the nodes are counted too.
    let mut nodes: Vec<Value> = (0..24).map(|i| json!({ "children": [i + 1, i + 1] })).collect();
    nodes.push(json!({}));
    nodes.push(json!({ "mesh": 0 }));
    let doc = changed(|d| {
        d["nodes"] = json!(nodes);
        d["scenes"][0]["nodes"] = json!([0, 25]);
    });
    let e = gltf_error(&scene, "nodes.gltf", &doc);
    assert!(e.contains("places 33554432 nodes; at most 1048576 are supported"), "{e}");
    // An emitting primitive is copied at each placement (lights are sampled triangle by
    // triangle): 128 triangles placed 2^19 times, within the limits on placements.
    let mut bin = triangle().1[..36].to_vec();
    bin.extend((0..384u16).flat_map(|i| (i % 3).to_le_bytes()));
    std::fs::write(scene.join("many.bin"), &bin).unwrap();
    let mut nodes: Vec<Value> = (0..19).map(|i| json!({ "children": [i + 1, i + 1] })).collect();
    nodes.push(json!({ "mesh": 0 }));
    let doc = changed(|d| {
        d["nodes"] = json!(nodes);
        d["accessors"][1]["count"] = json!(384);
        d["bufferViews"][1]["byteLength"] = json!(768);
        d["buffers"][0] = json!({ "byteLength": bin.len(), "uri": "many.bin" });
        d["materials"] = json!([{ "emissiveFactor": [1, 1, 1] }]);
        d["meshes"][0]["primitives"][0]["material"] = json!(0);
    });
    let e = promptly({
        let scene = scene.clone();
        move || gltf_error(&scene, "lights.gltf", &doc)
    });
    assert!(e.contains("places 67108864 triangles") && e.contains("at most 33554432 are supported"), "{e}");
}

//! Bad scene files: every error names the file, the line and the field, and no input panics.

mod common;

use common::{scenes_dir, temp_dir, CAMERA};
use scene::SceneError;
use std::path::Path;

fn error_in(text: &str, base_dir: &Path) -> SceneError {
    match scene::parse(text, "bad.toml", base_dir) {
        Ok(_) => panic!("expected an error for:\n{text}"),
        Err(e) => e,
    }
}

/// Asserts that `text` fails with a message that starts with `bad.toml:LINE:` and contains the
/// field path and each of `fragments`.
fn check_in(text: &str, base_dir: &Path, line: usize, field: &str, fragments: &[&str]) -> String {
    let e = error_in(text, base_dir);
    let message = e.to_string();
    assert!(message.starts_with(&format!("bad.toml:{line}:")), "wrong line (want {line}): {message}");
    assert_eq!(e.line(), Some(line));
    assert_eq!(e.field(), Some(field), "{message}");
    assert!(message.contains(&format!(": {field}: ")), "{message}");
    for f in fragments {
        assert!(message.contains(f), "{message:?} lacks {f:?}");
    }
    message
}

fn check(text: &str, line: usize, field: &str, fragments: &[&str]) -> String {
    check_in(text, Path::new("."), line, field, fragments)
}

/// The camera (4 lines) followed by one object with the given shape line and extra lines.
fn object(shape: &str, extra: &str) -> String {
    format!("{CAMERA}[[objects]]\nshape = {shape}\n{extra}")
}

#[test]
fn wrong_type_names_the_expected_type() {
    // Line 6: the shape.
    let text = object("{ type = \"sphere\", center = [0, 0, 0], radius = \"big\" }", "");
    check(&text, 6, "objects[0].shape.radius", &["expected a number", "got a string (\"big\")"]);
    check(
        "[camera]\nposition = 3\n",
        2,
        "camera.position",
        &["expected a vector (an array of 3 numbers)", "an integer (3)"],
    );
    check("[camera]\nposition = [1, 2]\n", 2, "camera.position", &["array of 2 elements"]);
    check(&format!("{CAMERA}[render]\nspp = 2.5\n"), 6, "render.spp", &["expected an integer", "a float (2.5)"]);
}

#[test]
fn unknown_fields_are_named_with_the_expected_ones() {
    let text = object("{ type = \"sphere\", center = [0, 0, 0], raduis = 1 }", "");
    check(&text, 6, "objects[0].shape.raduis", &["unknown field \"raduis\"", "did you mean \"radius\"", "\"center\""]);
    let text = "[camera]\nposition = [0, 0, 5]\nlook_at = [0, 0, 0]\nfov = 40\nzoom = 2\n";
    check(text, 5, "camera.zoom", &["unknown field \"zoom\"", "\"look_at\"", "\"focus_distance\""]);
    check(&format!("{CAMERA}[camera_settings]\n"), 5, "camera_settings", &["unknown field", "\"objects\""]);
    check(
        &object("{ type = \"sphere\", center = [0, 0, 0], radius = 1 }", "colour = 1\n"),
        7,
        "objects[0].colour",
        &["\"material\""],
    );
}

#[test]
fn unknown_shape_type() {
    let text = object("{ type = \"sphear\", center = [0, 0, 0], radius = 1 }", "");
    check(
        &text,
        6,
        "objects[0].shape.type",
        &[
            "unknown shape \"sphear\" (did you mean \"sphere\"?); expected \"sphere\", \"plane\", \"rectangle\", \"disk\", \
             \"box\", \"cylinder\" or \"mesh\"",
        ],
    );
    // A table without its type lists the types too.
    check(&object("{ radius = 1 }", ""), 6, "objects[0].shape.type", &["required field is missing", "\"cylinder\""]);
}

#[test]
fn unknown_material_type() {
    let text = format!("{CAMERA}[materials.m]\ntype = \"difuse\"\n");
    check(
        &text,
        6,
        "materials.m.type",
        &["unknown material \"difuse\" (did you mean \"diffuse\"?); expected \"diffuse\", \"mirror\", \"dielectric\", \
           \"conductor\" or \"plastic\""],
    );
}

#[test]
fn unknown_texture_type() {
    let text = format!("{CAMERA}[materials.m]\ntype = \"diffuse\"\nreflectance = {{ type = \"marble\" }}\n");
    check(
        &text,
        7,
        "materials.m.reflectance.type",
        &["unknown texture \"marble\"; expected \"checker\", \"grid\", \"image\" or \"earth\""],
    );
}

#[test]
fn unknown_sky_type() {
    let text = format!("{CAMERA}[sky]\ntype = \"star\"\n");
    check(
        &text,
        6,
        "sky.type",
        &["unknown sky \"star\" (did you mean \"stars\"?); expected \"constant\", \"gradient\", \"equirect\", \
           \"stars\" or \"grid\""],
    );
}

#[test]
fn unknown_filter_type() {
    let names = "expected \"box\", \"tent\", \"gaussian\", \"mitchell\" or \"blackman-harris\"";
    let text = format!("{CAMERA}[render]\nfilter = \"mitchel\"\n");
    check(&text, 6, "render.filter", &["unknown filter \"mitchel\" (did you mean \"mitchell\"?)", names]);
    let text = format!("{CAMERA}[render]\nfilter = {{ type = \"lanczos\", radius = 2 }}\n");
    check(&text, 6, "render.filter.type", &["unknown filter \"lanczos\"", names]);
    // Each filter takes its own parameters only.
    let text = format!("{CAMERA}[render]\nfilter = {{ type = \"gaussian\", b = 0.3 }}\n");
    check(&text, 6, "render.filter.b", &["unknown field \"b\"; expected \"type\", \"radius\" or \"sigma\""]);
}

#[test]
fn unknown_projection() {
    let text = "[camera]\nposition = [0, 0, 5]\nlook_at = [0, 0, 0]\nprojection = \"fishey\"\n";
    check(
        text,
        4,
        "camera.projection",
        &["unknown projection \"fishey\" (did you mean \"fisheye\"?); expected \"perspective\", \"equirectangular\", \
           \"fisheye\" or \"ods\""],
    );
}

#[test]
fn unknown_integrator_and_render_keywords() {
    let render = |line: &str| format!("{CAMERA}[render]\n{line}\n");
    check(
        &render("integrator = \"bdpt\""),
        6,
        "render.integrator",
        &["unknown integrator \"bdpt\"; expected \"path\", \"brute-force\" or \"photon\""],
    );
    check(
        &render("intersection = \"chords\""),
        6,
        "render.intersection",
        &["unknown intersection \"chords\" (did you mean \"chord\"?); expected \"chord\" or \"poster\""],
    );
    check(
        &render("tonemap = \"aces\""),
        6,
        "render.tonemap",
        &["unknown tone map \"aces\"; expected \"filmic\" or \"linear\""],
    );
    check(
        &render("connector = \"aim\""),
        6,
        "render.connector",
        &["unknown connector \"aim\"", "\"auto\" or \"aimed\""],
    );
}

#[test]
fn missing_required_fields() {
    // Points at the table that lacks it.
    let text = object("{ type = \"sphere\", center = [0, 0, 0] }", "");
    check(&text, 6, "objects[0].shape.radius", &["required field is missing"]);
    check("[camera]\nposition = [0, 0, 5]\n", 1, "camera.look_at", &["required field is missing"]);
    let text = format!("{CAMERA}\n[[objects]]\nmaterial = {{ type = \"mirror\" }}\n");
    check(&text, 6, "objects[0].shape", &["required field is missing"]);
    check(&object("{ center = [0, 0, 0] }", ""), 6, "objects[0].shape.type", &["missing", "\"sphere\""]);
}

#[test]
fn out_of_range_values_point_at_the_value() {
    let text = object("{ type = \"sphere\", center = [0, 0, 0], radius = -1 }", "");
    let m = check(&text, 6, "objects[0].shape.radius", &["must be > 0, got -1"]);
    assert!(m.starts_with("bad.toml:6:57: "), "column of the value: {m}");
    check("[camera]\nposition = [0, 0, 5]\nlook_at = [0, 0, 0]\nfov = 180\n", 4, "camera.fov", &["(0, 180)"]);
    check("[camera]\nposition = [0, 0, 5]\nlook_at = [0, 0, 5]\n", 3, "camera.look_at", &["must differ"]);
    check("[camera]\nposition = [0, 0, 5]\nlook_at = [0, 0, 0]\nup = [0, 0, 2]\n", 4, "camera.up", &["parallel"]);
    check(&format!("{CAMERA}[render]\nwidth = 0\n"), 6, "render.width", &["from 1 to"]);
    let photon = format!("{CAMERA}[render]\nintegrator = \"photon\"\n");
    check(&format!("{photon}photon_radius = 0\n"), 7, "render.photon_radius", &["must be > 0, got 0"]);
    check(&format!("{photon}photons_per_iteration = 0\n"), 7, "render.photons_per_iteration", &["got 0"]);
    check(&format!("{CAMERA}[render]\nphoton_radius = 1\n"), 6, "render.photon_radius", &["only used with"]);
    // Photons are traced forwards; nothing says how a metric written in the file's light is.
    let written = format!(
        "[spacetime]\ntype = \"metric\"\ncoordinates = \"spherical\"\ng_tt = \"-(1 - 2/r)\"\n\
         g_rr = \"1/(1 - 2/r)\"\ng_thetatheta = \"r^2\"\ng_phiphi = \"r^2*sin(theta)^2\"\n{photon}"
    );
    check(&written, 13, "render.integrator", &["forwards", "type \"metric\""]);
    check(
        &format!("{CAMERA}[materials.m]\ntype = \"diffuse\"\nreflectance = [1.5, 0, 0]\n"),
        7,
        "materials.m.reflectance",
        &["[0, 1]"],
    );
    check(
        &object("{ type = \"box\", min = [0, 0, 0], max = [1, 0, 1] }", ""),
        6,
        "objects[0].shape.max",
        &["greater than min"],
    );
    check(
        &object("{ type = \"plane\", point = [0, 0, 0], normal = [0, 0, 0] }", ""),
        6,
        "objects[0].shape.normal",
        &["non-zero"],
    );
    let text = object("{ type = \"rectangle\", corner = [0, 0, 0], edge_u = [1, 0, 0], edge_v = [2, 0, 0] }", "");
    check(&text, 6, "objects[0].shape.edge_v", &["parallel"]);
    let text = object("{ type = \"sphere\", center = [0, 0, 0], radius = 1 }", "transform = { scale = [1, 0, 1] }\n");
    check(&text, 7, "objects[0].transform.scale", &["non-zero"]);
    check(
        &object("{ type = \"sphere\", center = [0, 0, 0], radius = nan }", ""),
        6,
        "objects[0].shape.radius",
        &["finite"],
    );
    let text = object("{ type = \"sphere\", center = [0, 0, 0], radius = 1 }", "emission = [-1, 0, 0]\n");
    check(&text, 7, "objects[0].emission", &["≥ 0"]);
}

/// A camera where no observer can stay at rest is refused at its position, whichever spacetime
/// makes it so: inside a horizon (uncharged or charged), inside Kerr's ergoregion (the spin along y, so the equator is
/// the x–z plane), within a wormhole's throat radius.
#[test]
fn cameras_where_nothing_can_stay_at_rest() {
    let camera = |p: &str| format!("[camera]\nposition = {p}\nlook_at = [5, 3, -10]\nfov = 40\n");
    let hole = "[spacetime]\ntype = \"schwarzschild\"\nmass = 1\n";
    check(&format!("{hole}{}", camera("[0, 0, 1.9]")), 5, "camera.position", &["inside the event horizon"]);
    // A charged hole's outer horizon is at M + √(M² − Q²) = 1.6: inside at 1.55, outside at 1.65.
    let charged = "[spacetime]\ntype = \"reissner-nordstrom\"\nmass = 1\ncharge = 0.8\n";
    check(&format!("{charged}{}", camera("[0, 1.55, 0]")), 6, "camera.position", &["inside the event horizon"]);
    assert!(scene::parse(&format!("{charged}{}", camera("[0, 1.65, 0]")), "ok.toml", Path::new(".")).is_ok());
    let kerr = "[spacetime]\ntype = \"kerr\"\nmass = 1\nspin = 0.9\n";
    check(&format!("{kerr}{}", camera("[1.9, 0, 0]")), 6, "camera.position", &["inside the ergoregion"]);
    check(&format!("{kerr}{}", camera("[1.2, 0, 0]")), 6, "camera.position", &["inside the event horizon"]);
    // Kerr–Newman (a = 0.6, Q = 0.5) on the equator: horizon to x = 1.73, ergoregion to x = 1.96.
    let charged = "[spacetime]\ntype = \"kerr-newman\"\nmass = 1\nspin = 0.6\ncharge = 0.5\n";
    check(&format!("{charged}{}", camera("[1.7, 0, 0]")), 7, "camera.position", &["inside the event horizon"]);
    check(&format!("{charged}{}", camera("[0, 0, 1.9]")), 7, "camera.position", &["inside the ergoregion"]);
    // Above the pole, at the same distance, it is outside the ergoregion.
    assert!(scene::parse(&format!("{kerr}{}", camera("[0, 1.9, 0]")), "ok.toml", Path::new(".")).is_ok());
    let wormhole = "[spacetime]\ntype = \"ellis\"\nthroat = 1\n";
    check(&format!("{wormhole}{}", camera("[0, 0, 0.99]")), 5, "camera.position", &["throat"]);
    // Every view is checked at load, not only when it is rendered (`--view`).
    let view = "[views.inside]\nposition = [0, 0, 1.5]\nlook_at = [0, 0, 5]\nfov = 40\n";
    check(&format!("{hole}{}{view}", camera("[0, 0, 10]")), 9, "views.inside.position", &["inside the event horizon"]);
    let interstellar = "[spacetime]\ntype = \"wormhole\"\nthroat = 1\nlength = 0.01\nlensing_width = 0.05\n";
    check(&format!("{interstellar}{}", camera("[0, 0.99, 0]")), 7, "camera.position", &["throat"]);
    assert!(scene::parse(&format!("{interstellar}{}", camera("[0, 1.01, 0]")), "ok.toml", Path::new(".")).is_ok());
}

#[test]
fn bad_spacetime_parameters() {
    let text = format!("[spacetime]\ntype = \"kerr\"\nmass = 1\nspin = 1.5\n{CAMERA}");
    check(&text, 4, "spacetime.spin", &["|spin| must be ≤ mass = 1, got 1.5"]);
    let text = format!("[spacetime]\ntype = \"schwarzschild\"\nmass = -2\n{CAMERA}");
    check(&text, 3, "spacetime.mass", &["≥ 0"]);
    let text = format!("[spacetime]\ntype = \"reissner-nordstrom\"\nmass = 1\ncharge = -1.2\n{CAMERA}");
    check(&text, 4, "spacetime.charge", &["|charge| must be ≤ mass = 1, got -1.2"]);
    let text = format!("[spacetime]\ntype = \"reissner-nordstrom\"\nmass = 1\n{CAMERA}");
    check(&text, 1, "spacetime.charge", &["missing"]);
    let text = format!("[spacetime]\ntype = \"kerr-newman\"\nmass = 1\nspin = 0.8\ncharge = 0.7\n{CAMERA}");
    check(&text, 5, "spacetime.charge", &["spin² + charge² ≤ mass² = 1, got 0.8² + 0.7²"]);
    let text = format!("[spacetime]\ntype = \"kerr-newman\"\nmass = 1\nspin = 1.1\ncharge = 0\n{CAMERA}");
    check(&text, 4, "spacetime.spin", &["|spin| must be ≤ mass = 1, got 1.1"]);
    let text = format!("[spacetime]\ntype = \"ellis\"\nthroat = 0\n{CAMERA}");
    check(&text, 3, "spacetime.throat", &["> 0"]);
    let text = format!("[spacetime]\ntype = \"wormhole\"\nthroat = 1\nlength = -1\nlensing_width = 0.1\n{CAMERA}");
    check(&text, 4, "spacetime.length", &["≥ 0"]);
    let text = format!("[spacetime]\ntype = \"wormhole\"\nthroat = 1\nlensing_width = 0\n{CAMERA}");
    check(&text, 4, "spacetime.lensing_width", &["> 0"]);
    let text = format!("[spacetime]\ntype = \"wormhole\"\nthroat = 1\n{CAMERA}");
    check(&text, 1, "spacetime.lensing_width", &["missing"]);
    let text = format!("[spacetime]\ntype = \"schwarzschild\"\nmass = 1\nspin = 0.5\n{CAMERA}");
    check(&text, 4, "spacetime.spin", &["unknown field"]);
    // A lower region only exists in a wormhole.
    let text = object("{ type = \"sphere\", center = [0, 0, 0], radius = 1 }", "region = \"lower\"\n");
    check(&text, 7, "objects[0].region", &["wormhole"]);
    check(&format!("{CAMERA}[lower.sky]\ntype = \"constant\"\nradiance = 1\n"), 5, "lower", &["wormhole"]);
}

#[test]
fn unknown_material_name() {
    let text = format!(
        "{CAMERA}[materials.white]\ntype = \"diffuse\"\n[materials.red]\ntype = \"diffuse\"\n\
         [[objects]]\nshape = {{ type = \"sphere\", center = [0, 0, 0], radius = 1 }}\nmaterial = \"whte\"\n"
    );
    check(&text, 11, "objects[0].material", &["unknown material \"whte\"", "did you mean \"white\"", "red, white"]);
    let text = object("{ type = \"sphere\", center = [0, 0, 0], radius = 1 }", "material = \"x\"\n");
    check(&text, 7, "objects[0].material", &["no materials are defined"]);
    let text = format!("{CAMERA}[materials.m]\ntype = \"conductor\"\nmetal = \"gould\"\n");
    check(&text, 7, "materials.m.metal", &["unknown metal \"gould\"", "did you mean \"gold\""]);
}

#[test]
fn missing_obj_file() {
    let dir = temp_dir("missing-obj");
    let text = object("{ type = \"mesh\", file = \"nowhere/teapot.obj\" }", "");
    check_in(&text, &dir, 6, "objects[0].shape.file", &["cannot open mesh file", "nowhere/teapot.obj"]);
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn malformed_obj_file() {
    let dir = temp_dir("bad-obj");
    std::fs::write(dir.join("bad.obj"), "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 7\n").unwrap();
    let text = object("{ type = \"mesh\", file = \"bad.obj\" }", "");
    check_in(&text, &dir, 6, "objects[0].shape.file", &["bad.obj", "line 4", "vertex 7"]);
    std::fs::write(dir.join("garbage.obj"), "v 0 zero 0\nf 1 2 3\n").unwrap();
    let text = object("{ type = \"mesh\", file = \"garbage.obj\" }", "");
    check_in(&text, &dir, 6, "objects[0].shape.file", &["garbage.obj"]);
    std::fs::write(dir.join("empty.obj"), "# nothing\n").unwrap();
    let text = object("{ type = \"mesh\", file = \"empty.obj\" }", "");
    check_in(&text, &dir, 6, "objects[0].shape.file", &["empty.obj", "no triangles"]);
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn missing_texture_image() {
    let dir = temp_dir("missing-image");
    let text = format!(
        "{CAMERA}[materials.wood]\ntype = \"diffuse\"\nreflectance = {{ type = \"image\", file = \"wood.png\" }}\n"
    );
    check_in(&text, &dir, 7, "materials.wood.reflectance.file", &["cannot load image", "wood.png", "not found"]);
    let text = format!("{CAMERA}[sky]\ntype = \"equirect\"\nfile = \"sky.exr\"\n");
    check_in(&text, &dir, 7, "sky.file", &["sky.exr"]);
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn missing_scene_file() {
    let path = Path::new("scenes/does-not-exist.toml");
    let e = scene::load(path).expect_err("an error");
    assert_eq!(e.to_string(), "scenes/does-not-exist.toml: cannot read: No such file or directory");
    assert_eq!(e.line(), None);
}

#[test]
fn empty_file_lacks_a_camera() {
    let m = check("", 1, "camera", &["required field is missing"]);
    assert_eq!(m, "bad.toml:1:1: camera: required field is missing");
    check("# only a comment\n[render]\nspp = 1\n", 1, "camera", &["missing"]);
}

#[test]
fn invalid_toml_syntax() {
    let e = error_in("[camera]\nposition = [0, 1,\nfov = 3\n", Path::new("."));
    assert!(e.to_string().starts_with("bad.toml:3:5: invalid TOML:"), "{e}");
    let e = error_in("[camera]\nfov = 1\nfov = 2\n", Path::new("."));
    assert!(e.to_string().starts_with("bad.toml:3:1: invalid TOML: duplicate key"), "{e}");
}

#[test]
fn objects_must_be_an_array_of_tables() {
    let text = format!("{CAMERA}[objects]\nshape = {{ type = \"sphere\", center = [0, 0, 0], radius = 1 }}\n");
    check(&text, 5, "objects", &["[[objects]]"]);
}

#[test]
fn aliases_may_not_both_be_given() {
    let text = object("{ type = \"sphere\", center = [0, 0, 0], centre = [0, 0, 0], radius = 1 }", "");
    check(&text, 6, "objects[0].shape.centre", &["same field as objects[0].shape.center"]);
}

#[test]
fn non_utf8_files_are_errors() {
    let dir = temp_dir("utf8");
    let path = dir.join("latin1.toml");
    std::fs::write(&path, b"[camera]\n# caf\xe9\n").unwrap();
    let e = scene::load(&path).expect_err("an error");
    assert_eq!(e.line(), Some(2), "{e}");
    assert!(e.to_string().contains("UTF-8"), "{e}");
    std::fs::remove_dir_all(&dir).ok();
}

/// Every prefix of the Cornell box at every 7th byte: an error or a scene, never a panic. Written to
/// files too, so that prefixes ending inside a multi-byte character exercise the UTF-8 check.
#[test]
fn truncated_scenes_never_panic() {
    let path = scenes_dir().join("cornell-box.toml");
    let bytes = std::fs::read(&path).unwrap();
    let dir = temp_dir("truncated");
    let cut = dir.join("cut.toml");
    let mut errors = 0;
    for end in (0..bytes.len()).step_by(7) {
        let prefix = &bytes[..end];
        let text = String::from_utf8_lossy(prefix);
        if let Err(e) = scene::parse(&text, "cut.toml", &dir) {
            assert!(e.to_string().starts_with("cut.toml:"), "{e}");
            errors += 1;
        }
        std::fs::write(&cut, prefix).unwrap();
        let _ = scene::load(&cut);
    }
    assert!(errors > 0);
    std::fs::remove_dir_all(&dir).ok();
}

/// A zoo of malformed documents: each is an error with a position, none panics.
#[test]
fn malformed_documents_are_errors_not_panics() {
    let bodies = [
        "camera = 1",
        "camera = []",
        "[camera]\nposition = [\"a\", 0, 0]\nlook_at = [0, 0, 0]",
        "[camera]\nposition = [1e400, 0, 0]\nlook_at = [0, 0, 0]",
        "[camera]\nposition = [inf, 0, 0]\nlook_at = [0, 0, 0]",
        "[camera]\nposition = [0, 0, 1]\nlook_at = [0, 0, 0]\nfov = -inf",
        "[camera]\nposition = [0, 0, 1]\nlook_at = [0, 0, 0]\naperture = -1",
        "[camera]\nposition = [0, 0, 1]\nlook_at = [0, 0, 0]\nfocus_distance = 0",
        "[camera]\nposition = [0, 0, 1]\nlook_at = [0, 0, 0]\nregion = \"middle\"",
        "[camera]\nposition = [0, 0, 1]\nlook_at = [0, 0, 0]\nup = [0, 0, 0]",
        "[camera]\nposition = [0, 0, 1]\nlook_at = [0, 0, 0]\nfov = 1979-05-27T07:32:00Z",
        "[camera]\nposition = [0, 0, 1]\nlook_at = [1e308, 1e308, 1e308]",
        "[[camera]]\nposition = [0, 0, 1]",
    ];
    // Top-level keys must come before the first table header.
    let before_camera =
        ["spacetime = \"kerr\"", "sky = \"blue\"", "materials = 1", "objects = 1", "objects = [1]", "lower = 1"];
    let after_camera = [
        "[spacetime]\nmass = 1",
        "[spacetime]\ntype = 3",
        "[spacetime]\ntype = \"kerr\"\nmass = 1",
        "[spacetime]\ntype = \"kerr\"\nmass = 1\nspin = nan",
        "[spacetime]\ntype = \"schwarzschild\"\nmass = 1e309",
        "[render]\nwidth = 100000",
        "[render]\nheight = -1",
        "[render]\nspp = 9223372036854775807",
        "[render]\nseed = -1",
        "[render]\nmax_depth = 1e3",
        "[render]\nintegrator = \"bidir\"",
        "[render]\nintersection = 1",
        "[render]\ngeodesic_rtol = 0",
        "[render]\nexposure = 1e10",
        "[render]\ntonemap = \"aces\"",
        "[render]\nfilter = \"lanczos\"",
        "[render]\nfilter = { type = \"box\", radius = 0 }",
        "[render]\nfilter = { type = \"box\", radius = 1e6 }",
        "[render]\nfilter = { type = \"gaussian\", sigma = 0 }",
        "[render]\nfilter = { type = \"gaussian\", sigma = 1e-320 }",
        "[render]\nfilter = { type = \"mitchell\", b = 1e308, c = -1e308 }",
        "[render]\nfilter = { type = \"tent\", radius = [1, 2, 3] }",
        "[render]\nfilter = { radius = 1 }",
        "[render]\nfilter = 3",
        "[render]\nrender = 1",
        "[sky]\ntype = \"constant\"",
        "[sky]\ntype = \"constant\"\nradiance = [-1, 0, 0]",
        "[sky]\ntype = \"constant\"\nradiance = [1e39, 0, 0]",
        "[sky]\ntype = \"gradient\"\nup = [0, 0, 0]",
        "[sky]\ntype = \"equirect\"",
        "[sky]\ntype = \"equirect\"\nfile = \"\"",
        "[sky]\ntype = \"equirect\"\nfile = \".\"",
        "[sky]\ntype = \"equirect\"\nfile = \"x.png\"\nintensity = -1",
        "[sky]\ntype = \"stars\"\ndensity = -1",
        "[sky]\ntype = \"stars\"\ndensity = 1e300",
        "[sky]\ntype = \"stars\"\nstar_radius_deg = 0",
        "[sky]\ntype = \"grid\"\nspacing_deg = 0",
        "[sky]\ntype = \"grid\"\nbackground = [[1, 0, 0], [0, 1, 0]]",
        "[sky]\ntype = \"grid\"\nbackground = []",
        "[sky]\ntype = \"grid\"\nbackground = [[]]",
        "[sky]\ntype = \"grid\"\nwidth_deg = -1",
        "[sky]\ntype = \"grid\"\nrotation_deg = inf",
        "[lower]\nsky = 1",
        "[materials]\nm = 1",
        "[materials.m]\ntype = \"velvet\"",
        "[materials.m]\nreflectance = 1",
        "[materials.m]\ntype = \"diffuse\"\nreflectance = \"red\"",
        "[materials.m]\ntype = \"diffuse\"\nreflectance = { type = \"checker\", a = { type = \"checker\", a = 2 } }",
        "[materials.m]\ntype = \"diffuse\"\nreflectance = { type = \"checker\", uv_scale = [1] }",
        "[materials.m]\ntype = \"diffuse\"\nreflectance = { type = \"grid\", spacing = 0 }",
        "[materials.m]\ntype = \"diffuse\"\nreflectance = { type = \"grid\", width = -1 }",
        "[materials.m]\ntype = \"diffuse\"\nreflectance = { type = \"grid\", highlights = [{ axis = \"w\", index = 1, colour = 1 }] }",
        "[materials.m]\ntype = \"diffuse\"\nreflectance = { type = \"grid\", highlights = [{ axis = \"u\", index = 1 }] }",
        "[materials.m]\ntype = \"diffuse\"\nreflectance = { type = \"grid\", highlights = 1 }",
        "[materials.m]\ntype = \"diffuse\"\nreflectance = { type = \"image\" }",
        "[materials.m]\ntype = \"diffuse\"\nreflectance = { type = \"image\", file = 3 }",
        "[materials.m]\ntype = \"dielectric\"\nior = 0",
        "[materials.m]\ntype = \"dielectric\"\ntransmittance = [2, 2, 2]",
        "[materials.m]\ntype = \"plastic\"\nior = 0.5",
        "[materials.m]\ntype = \"plastic\"\nroughness = 2",
        "[materials.m]\ntype = \"conductor\"\nroughness = -0.1",
        "[materials.m]\ntype = \"conductor\"\nmetal = \"gold\"\nf0 = 1",
        "[materials.m]\ntype = \"conductor\"\neta = 1",
        "[materials.m]\ntype = \"conductor\"\nk = 1",
        "[materials.m]\ntype = \"conductor\"\neta = 0\nk = 0",
        "[materials.m]\ntype = \"conductor\"\neta = -1\nk = 1",
        "[materials.m]\ntype = \"conductor\"\nf0 = 2",
        "[[objects]]",
        "[[objects]]\nshape = 1",
        "[[objects]]\nshape = {}",
        "[[objects]]\nshape = { type = \"disk\", center = [0, 0, 0], normal = [0, 0, 1], radius = 0 }",
        "[[objects]]\nshape = { type = \"cylinder\", base = [0, 0, 0], axis = [0, 0, 0], radius = 1, height = 1 }",
        "[[objects]]\nshape = { type = \"cylinder\", base = [0, 0, 0], axis = [0, 0, 1], radius = 1, height = -1 }",
        "[[objects]]\nshape = { type = \"rectangle\", corner = [0, 0, 0], edge_u = [0, 0, 0], edge_v = [1, 0, 0] }",
        "[[objects]]\nshape = { type = \"rectangle\", corner = [0, 0, 0], edge_u = [1e200, 0, 0], edge_v = [0, 1e200, 0] }",
        "[[objects]]\nshape = { type = \"mesh\" }",
        "[[objects]]\nshape = { type = \"mesh\", file = \"\" }",
        "[[objects]]\nshape = { type = \"mesh\", file = \"/\" }",
        "[[objects]]\nshape = { type = \"sphere\", center = [0, 0, 0], radius = 1 }\nmaterial = 1",
        "[[objects]]\nshape = { type = \"sphere\", center = [0, 0, 0], radius = 1 }\nmaterial = []",
        "[[objects]]\nshape = { type = \"sphere\", center = [0, 0, 0], radius = 1 }\nmaterial = { type = \"mirror\", reflectance = -1 }",
        "[[objects]]\nshape = { type = \"sphere\", center = [0, 0, 0], radius = 1 }\nemission = { two_sided = true }",
        "[[objects]]\nshape = { type = \"sphere\", center = [0, 0, 0], radius = 1 }\nemission = { radiance = 1, two_sided = 1 }",
        "[[objects]]\nshape = { type = \"sphere\", center = [0, 0, 0], radius = 1 }\nemission = \"bright\"",
        "[[objects]]\nshape = { type = \"sphere\", center = [0, 0, 0], radius = 1 }\ntransform = { scale = 1e-200 }",
        "[[objects]]\nshape = { type = \"sphere\", center = [0, 0, 0], radius = 1 }\ntransform = { scale = [1e200, 1e200, 1e200] }",
        "[[objects]]\nshape = { type = \"sphere\", center = [0, 0, 0], radius = 1 }\ntransform = { rotate = { axis = [0, 0, 0], degrees = 1 } }",
        "[[objects]]\nshape = { type = \"sphere\", center = [0, 0, 0], radius = 1 }\ntransform = { rotate = [0, 1, 0] }",
        "[[objects]]\nshape = { type = \"sphere\", center = [0, 0, 0], radius = 1 }\ntransform = { rotate = { axis = [0, 1, 0] } }",
        "[[objects]]\nshape = { type = \"sphere\", center = [0, 0, 0], radius = 1 }\ntransform = { shear = 1 }",
        "[[objects]]\nshape = { type = \"sphere\", center = [0, 0, 0], radius = 1 }\nregion = 1",
    ];
    let mut documents: Vec<String> = bodies.iter().map(|b| b.to_string()).collect();
    documents.extend(before_camera.iter().map(|b| format!("{b}\n{CAMERA}")));
    documents.extend(after_camera.iter().map(|b| format!("{CAMERA}{b}\n")));
    // Syntax errors of every kind.
    for broken in ["[", "[[", "a =", "= 1", "a = [1, 2", "a = {", "a = \"unterminated", "a = 1 2", "[a.]", "\u{0}"] {
        documents.push(broken.to_string());
        documents.push(format!("{CAMERA}{broken}"));
    }
    // Nesting deeper than the TOML parser allows.
    documents.push(format!("{CAMERA}x = {}{}", "[".repeat(100_000), "]".repeat(100_000)));
    documents.push(format!(
        "{CAMERA}[materials.m]\ntype = \"diffuse\"\nreflectance = {}1{}",
        "{ type = \"checker\", a = ".repeat(500),
        " }".repeat(500)
    ));
    for doc in &documents {
        match scene::parse(doc, "zoo.toml", Path::new(".")) {
            Ok(_) => panic!("accepted:\n{doc}"),
            Err(e) => {
                let m = e.to_string();
                assert!(m.starts_with("zoo.toml:") && e.line().is_some(), "{m}");
                assert!(!m.contains('\n'), "one line: {m:?}");
            }
        }
    }
    // Extreme but legal values: a scene or an error, never a panic.
    let extremes = [
        "shape = { type = \"sphere\", center = [0, 0, 0], radius = 1e-320 }",
        "shape = { type = \"sphere\", center = [1e308, 0, 0], radius = 1e308 }",
        "shape = { type = \"sphere\", center = [0, 0, 0], radius = 1 }\ntransform = { translate = [1e308, 1e308, 1e308], scale = 1e10 }",
        "shape = { type = \"box\", min = [-1e308, -1e308, -1e308], max = [1e308, 1e308, 1e308] }",
        "shape = { type = \"cylinder\", base = [0, 0, 0], axis = [1e-300, 0, 0], radius = 1e300, height = 1e-300 }",
        "shape = { type = \"disk\", center = [0, 0, 0], normal = [0, 1e300, 1e300], radius = 1e300 }",
        "shape = { type = \"plane\", point = [0, 0, 0], normal = [1e-320, 0, 0] }\nemission = 1e30",
        "shape = { type = \"sphere\", center = [0, 0, 0], radius = 1 }\ntransform = { scale = [1e-100, 1e100, 1], rotate = { axis = [1, 1e-300, 0], degrees = 1e300 } }",
    ];
    for body in extremes {
        let _ = scene::parse(&format!("{CAMERA}[[objects]]\n{body}\n"), "zoo.toml", Path::new("."));
    }
}

#[test]
fn camera_motion_mistakes_point_at_the_field() {
    let keys = |second: &str| {
        format!(
            "[camera]\nvelocity = \"from-path\"\nspeed_of_light = 10\n\
             [[camera.keyframes]]\ntime = 0\nposition = [0, 0, 5]\nlook_at = [0, 0, 0]\n\
             [[camera.keyframes]]\n{second}\n"
        )
    };
    // Line 9 is the second keyframe's first line.
    check(
        &keys("time = 0\nposition = [1, 0, 5]\nlook_at = [0, 0, 0]"),
        9,
        "camera.keyframes[1].time",
        &["times must increase"],
    );
    check(&keys("time = 1\nposition = [0, 0, 5]\nlook_at = [0, 0, 5]"), 11, "camera.keyframes[1].look_at", &["differ"]);
    check(
        &keys("time = 1\nposition = [0, 0, 5]\nlook_at = [0, 0, 0]\nfov = 0"),
        12,
        "camera.keyframes[1].fov",
        &["(0, 180)"],
    );
    // 40 units in 1 s with c = 10 units/s: four times the speed of light, found when loading.
    check(
        &keys("time = 1\nposition = [0, 0, -35]\nlook_at = [0, 0, -40]"),
        1,
        "camera",
        &["t = ", "not slower than light", "speed_of_light"],
    );
    check(
        "[camera]\nposition = [0, 0, 5]\nlook_at = [0, 0, 0]\nvelocity = \"from-path\"\n",
        1,
        "camera.speed_of_light",
        &["required with velocity = \"from-path\""],
    );
    check(
        "[camera]\nposition = [0, 0, 5]\nlook_at = [0, 0, 0]\nvelocity = [0.6, 0.8, 0]\n",
        4,
        "camera.velocity",
        &["not below the speed of light"],
    );
    check(
        "[camera]\nposition = [0, 0, 5]\nlook_at = [0, 0, 0]\nvelocity = \"fast\"\n",
        4,
        "camera.velocity",
        &["from-path"],
    );
    check(
        "[camera]\nposition = [0, 0, 5]\nlook_at = [0, 0, 0]\n[[camera.keyframes]]\ntime = 0\nposition = [0, 0, 5]\nlook_at = [0, 0, 0]\n",
        2,
        "camera.position",
        &["in each keyframe"],
    );
    check(
        "[camera]\nposition = [0, 0, 5]\nlook_at = [0, 0, 0]\norbit = { center = [0, 0, 0], period = 0 }\n",
        4,
        "camera.orbit.period",
        &["non-zero"],
    );
    check(&format!("{CAMERA}[animation]\nfps = -1\n"), 6, "animation.fps", &["(0, 1000]"]);
    check(&format!("{CAMERA}[animation]\nframes = 0\n"), 6, "animation.frames", &[]);
}

#[test]
fn projection_fields_belong_to_their_projection() {
    const POSE: &str = "[camera]\nposition = [0, 0, 5]\nlook_at = [0, 0, 0]\n";
    let camera = |extra: &str| format!("{POSE}{extra}\n");
    check(&camera("projection = \"equirect\""), 4, "camera.projection", &["unknown projection", "\"equirectangular\""]);
    check(&camera("projection = 3"), 4, "camera.projection", &["expected a string"]);
    // Depth of field and the perspective field of view are the perspective's only.
    check(
        &camera("projection = \"equirectangular\"\naperture = 0.1"),
        5,
        "camera.aperture",
        &["only used with projection = \"perspective\"", "depth of field", "\"equirectangular\""],
    );
    check(&camera("projection = \"fisheye\"\nfov = 90"), 5, "camera.fov", &["\"perspective\"", "\"fisheye\""]);
    check(&camera("focus_distance = 2\nprojection = \"ods\""), 4, "camera.focus_distance", &["\"perspective\""]);
    check(&camera("fisheye_fov = 180"), 4, "camera.fisheye_fov", &["only used with projection = \"fisheye\""]);
    check(&camera("projection = \"fisheye\"\nipd = 0.06"), 5, "camera.ipd", &["projection = \"ods\""]);
    check(&camera("projection = \"fisheye\"\nfisheye_fov = 400"), 5, "camera.fisheye_fov", &["(0, 360]", "400"]);
    check(&camera("projection = \"fisheye\"\nfisheye_fov = 0"), 5, "camera.fisheye_fov", &["(0, 360]"]);
    check(&camera("projection = \"ods\"\nipd = -0.06"), 5, "camera.ipd", &["> 0"]);
    // In a keyframe, and in a view.
    check(
        "[camera]\nprojection = \"ods\"\n[[camera.keyframes]]\ntime = 0\nposition = [0, 0, 5]\nlook_at = [0, 0, 0]\nfov = 60\n",
        7,
        "camera.keyframes[0].fov",
        &["\"perspective\"", "\"ods\""],
    );
    check(
        &format!("{CAMERA}[views.pano]\nposition = [0, 0, 0]\nlook_at = [0, 0, -1]\nprojection = \"equirectangular\"\naperture = 0.2\n"),
        9,
        "views.pano.aperture",
        &["depth of field"],
    );
}
#[test]
fn accretion_disks_and_blackbodies_are_checked_where_they_are_written() {
    // CAMERA is 4 lines; the sections follow.
    let kerr = "[spacetime]\ntype = \"kerr\"\nmass = 1\nspin = 0.9\n";
    check(&format!("{CAMERA}[accretion_disk]\nouter_radius = 20\n"), 5, "accretion_disk", &["orbits a black hole"]);
    check(
        &format!("{CAMERA}{kerr}[accretion_disk]\nouter_radius = 2\n"),
        10,
        "accretion_disk.outer_radius",
        &["innermost stable circular orbit", "2.32"],
    );
    check(
        &format!("{CAMERA}{kerr}[accretion_disk]\nouter_radius = 20\nnormal = [0, 0, 1]\n"),
        11,
        "accretion_disk.normal",
        &["equatorial plane"],
    );
    check(
        &format!("{CAMERA}[render]\nintegrator = \"photon\"\ndoppler = false\n"),
        7,
        "render.doppler",
        &["shows every frequency shift"],
    );
    check(
        &object("{ type = \"sphere\", center = [0, 0, 0], radius = 1 }", "emission = { temperature = 50 }\n"),
        7,
        "objects[0].emission.temperature",
        &["at least 100 K"],
    );
    check(
        &object(
            "{ type = \"sphere\", center = [0, 0, 0], radius = 1 }",
            "emission = { temperature = 3000, radiance = 1 }\n",
        ),
        7,
        "objects[0].emission.temperature",
        &["not both"],
    );
}

#[test]
fn spectral_rendering_and_dispersion_are_checked_where_they_are_written() {
    check(
        &format!("{CAMERA}[render]\nintegrator = \"photon\"\nspectral = true\n"),
        7,
        "render.spectral",
        &["carries RGB power"],
    );
    check(&format!("{CAMERA}[render]\nspectral = 1\n"), 6, "render.spectral", &["expected a bool"]);
    check(
        &object(
            "{ type = \"sphere\", center = [0, 0, 0], radius = 1 }",
            "material = { type = \"dielectric\", ior = 1.5, abbe = -3 }\n",
        ),
        7,
        "objects[0].material.abbe",
        &["positive Abbe number"],
    );
    check(
        &object(
            "{ type = \"sphere\", center = [0, 0, 0], radius = 1 }",
            "material = { type = \"dielectric\", ior = 0.9, abbe = 40 }\n",
        ),
        7,
        "objects[0].material.abbe",
        &["ior > 1"],
    );
}

#[test]
fn spectral_channels_are_checked_where_they_are_written() {
    check(
        &format!("{CAMERA}[render]\nspectrum = {{ min = 700, max = 400 }}\n"),
        6,
        "render.spectrum",
        &["0 < min ≤ max"],
    );
    check(&format!("{CAMERA}[render]\nspectrum = {{ count = 0 }}\n"), 6, "render.spectrum.count", &["from 1 to 4096"]);
    check(&format!("{CAMERA}[render]\nspectrum = {{ step = 5 }}\n"), 6, "render.spectrum.step", &["unknown field"]);
}

/// Values that parse but would give a black or NaN image, or a run thousands of times longer,
/// are refused with the range and the reason.
#[test]
fn extreme_values_are_refused_with_their_range() {
    let stars = "[sky]\ntype = \"stars\"\nbrightness = 1e36\n";
    check(&format!("{CAMERA}{stars}"), 7, "sky.brightness", &["too bright", "at most"]);
    let lamp = "[[objects]]\nshape = { type = \"sphere\", center = [0, 0, 0], radius = 1 }\nemission = 1e30\n";
    check(&format!("{CAMERA}{lamp}"), 7, "objects[0].emission", &["too bright", "at most 1e20"]);
    let wormhole = "[spacetime]\ntype = \"wormhole\"\nthroat = 1\nlensing_width = 1e-300\n";
    check(&format!("{wormhole}{CAMERA}"), 4, "spacetime.lensing_width", &["≥ 1e-9", "double precision"]);
    let metric =
        "[spacetime]\ntype = \"metric\"\nscale = 1e100\ng_tt = \"-1\"\ng_xx = \"1\"\ng_yy = \"1\"\ng_zz = \"1\"\n";
    check(&format!("{metric}{CAMERA}"), 3, "spacetime.scale", &["[1e-12, 1e12]", "1e100"]);
    check(
        &format!("{CAMERA}[render]\ngeodesic_rtol = 1e-300\n"),
        6,
        "render.geodesic_rtol",
        &["[1e-13, 1)", "rounding"],
    );
    // The bounds themselves are accepted.
    let at_bounds = format!("{CAMERA}[render]\ngeodesic_rtol = 1e-13\n[sky]\ntype = \"stars\"\nbrightness = 1e-3\n");
    assert!(scene::parse(&at_bounds, "ok.toml", Path::new(".")).is_ok());
}

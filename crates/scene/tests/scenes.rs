//! Scenes that must load, and what they must contain.

mod common;

use common::{scenes_dir, temp_dir, CAMERA, TINY_PNG};
use render::camera::{Equirectangular, Fisheye, Ods, Projection};
use render::film::{Curve, Filter};
use render::geometry::Vec3;
use render::material::{ConductorFresnel, Material};
use render::rgb::Rgb;
use render::settings::{IntegratorKind, Intersection};
use render::sky::{Sky, SkyFrame, StarFieldParams};
use render::texture::Texture;
use spacetime::{Region, Spacetime};
use std::path::Path;

fn parse(text: &str) -> render::scene::Scene {
    scene::parse(text, "test.toml", Path::new(".")).unwrap_or_else(|e| panic!("{e}"))
}

#[test]
fn every_bundled_scene_loads() {
    let mut count = 0;
    for entry in std::fs::read_dir(scenes_dir()).expect("scenes/ exists") {
        let path = entry.expect("readable entry").path();
        if path.extension().is_some_and(|e| e == "toml") {
            if let Err(e) = scene::load(&path) {
                panic!("{e}");
            }
            count += 1;
        }
    }
    assert!(count >= 1, "no scenes found in {}", scenes_dir().display());
}

#[test]
fn cornell_box_has_its_published_contents() {
    let s = scene::load(&scenes_dir().join("cornell-box.toml")).unwrap_or_else(|e| panic!("{e}"));
    assert!(matches!(s.spacetime, Spacetime::Minkowski(_)), "millimetres only make sense in flat space");
    // Floor, ceiling, back, left, right, light, short block, tall block.
    assert_eq!(s.world.objects(Region::Upper).len(), 8);
    assert!(s.world.objects(Region::Lower).is_empty());
    assert_eq!(s.world.light_count(Region::Upper), 1);
    let light = s.world.objects(Region::Upper).iter().find_map(|o| o.emission.clone()).expect("a light");
    assert_eq!(light.radiance, render::emission::Radiance::Rgb(Rgb::new(17.0, 12.0, 4.0).into()));
    assert!(!light.two_sided);
    let light_object = s.world.objects(Region::Upper).iter().find(|o| o.emission.is_some()).expect("light");
    assert!((light_object.shape.area() - 130.0 * 105.0).abs() < 1e-6);
    // The light faces down into the room.
    let ray =
        render::geometry::Ray::new(render::geometry::Vec3::new(278.0, 273.0, 279.5), render::geometry::Vec3::Y, 1e4);
    let (i, _) = s.world.intersect(Region::Upper, &ray).expect("ceiling above");
    let hit = s.world.surface(Region::Upper, i, &ray, s.world.intersect(Region::Upper, &ray).expect("hit").1);
    assert!(s.world.object(Region::Upper, i).emission.is_some(), "the light hangs below the ceiling");
    assert!(hit.ng.y < -0.999, "light normal {:?}", hit.ng);
    assert_eq!((s.settings.width, s.settings.height, s.settings.spp, s.settings.max_depth), (256, 256, 64, 8));
    assert_eq!(s.camera.position, render::geometry::Vec3::new(278.0, 273.0, -800.0));
    assert_eq!(s.camera.forward(), render::geometry::Vec3::Z);
    // Red, green, white and the light's material.
    assert_eq!(s.world.materials.len(), 4);
}

#[test]
fn defaults_fill_in_everything_but_the_camera() {
    let s = parse(CAMERA);
    assert!(matches!(s.spacetime, Spacetime::Minkowski(_)));
    assert_eq!(s.settings.width, render::settings::RenderSettings::default().width);
    assert!(matches!(s.world.sky(Region::Upper), Sky::Constant(c) if *c == Rgb::ZERO));
    let Projection::Perspective(lens) = s.camera.projection else { panic!("perspective by default") };
    assert_eq!(lens.lens_radius, 0.0);
    assert!((lens.focus_distance - 5.0).abs() < 1e-12, "focus defaults to the look_at distance");
}

#[test]
fn spacetimes_are_built_from_their_tables() {
    let s = parse(&format!("[spacetime]\ntype = \"schwarzschild\"\nmass = 2\n{CAMERA}"));
    assert_eq!(s.spacetime, Spacetime::schwarzschild(2.0).unwrap());
    let s = parse(&format!("[spacetime]\ntype = \"kerr\"\nmass = 1.0\nspin = -0.9\n{CAMERA}"));
    assert_eq!(s.spacetime, Spacetime::kerr(1.0, -0.9).unwrap());
    let s = parse(&format!("[spacetime]\ntype = \"minkowski\"\n{CAMERA}"));
    assert!(matches!(s.spacetime, Spacetime::Minkowski(_)));
}

#[test]
fn a_wormhole_has_two_regions_with_their_own_objects_and_skies() {
    let text = r#"
[spacetime]
type = "ellis"
throat = 1.5

[camera]
position = [0, 0, 10]
look_at = [0, 0, 0]
region = "lower"

[sky]
type = "constant"
radiance = [0.1, 0.2, 0.3]

[lower.sky]
type = "grid"
background = [[1, 0, 0], [0, 1, 0], [0, 0, 1], [1, 1, 0]]
spacing_deg = 15

[[objects]]
shape = { type = "sphere", centre = [0, 0, -5], radius = 1 }

[[objects]]
shape = { type = "disk", center = [0, -2, 0], normal = [0, 1, 0], radius = 3 }
region = "lower"
emission = [1, 1, 1]

[[objects]]
shape = { type = "cylinder", base = [3, 0, 0], axis = [0, 1, 0], radius = 0.5, height = 2 }
region = "lower"
"#;
    let s = parse(text);
    assert_eq!(s.spacetime, Spacetime::ellis(1.5).unwrap());
    assert_eq!(s.camera.region, Region::Lower);
    assert_eq!(s.world.objects(Region::Upper).len(), 1);
    assert_eq!(s.world.objects(Region::Lower).len(), 2);
    assert_eq!(s.world.light_count(Region::Lower), 1);
    assert!(matches!(s.world.sky(Region::Upper), Sky::Constant(c) if *c == Rgb::new(0.1, 0.2, 0.3)));
    match s.world.sky(Region::Lower) {
        Sky::Grid(g) => {
            assert_eq!(g.background[2], Rgb::Z);
            assert_eq!(g.spacing_deg, 15.0);
        }
        other => panic!("{other:?}"),
    }
}

#[test]
fn render_settings_are_read() {
    let text = format!(
        "{CAMERA}[render]\nwidth = 32\nheight = 16\nspp = 4\nmax_depth = 3\nseed = 9\nintegrator = \"brute-force\"\n\
         intersection = \"poster\"\nposter_step = 0.25\nposter_max_iterations = 800\ngeodesic_rtol = 1e-6\nexposure = -1.5\ntonemap = \"filmic\"\n\
         filter = {{ type = \"gaussian\", radius = [1.5, 2], sigma = 0.4 }}\n"
    );
    let s = parse(&text).settings;
    assert_eq!((s.width, s.height, s.spp, s.max_depth, s.seed), (32, 16, 4, 3, 9));
    assert_eq!(s.integrator, IntegratorKind::BruteForce);
    assert_eq!(s.intersection, Intersection::Poster { step: 0.25, max_iterations: 800 });
    assert_eq!(s.geodesic_rtol, 1e-6);
    assert_eq!(s.tonemap.exposure_ev, -1.5);
    assert_eq!(s.tonemap.curve, Curve::Filmic);
    match s.filter {
        Filter::Gaussian(g) => {
            assert_eq!(g.radius(), [1.5, 2.0]);
            assert_eq!(g.sigma(), 0.4);
        }
        other => panic!("{other:?}"),
    }
    let s = parse(&format!(
        "{CAMERA}[render]\nintegrator = \"photon\"\nphotons_per_iteration = 5000\nphoton_radius = 0.05\n"
    ))
    .settings;
    assert_eq!(s.integrator, IntegratorKind::Photon);
    assert_eq!((s.photon.per_iteration, s.photon.radius), (Some(5000), Some(0.05)));
    let s = parse(&format!("[spacetime]\ntype = \"ellis\"\nthroat = 1\n{CAMERA}[render]\nintegrator = \"photon\"\n"))
        .settings;
    assert_eq!((s.integrator, s.photon.per_iteration, s.photon.radius), (IntegratorKind::Photon, None, None));
    for name in ["box", "tent", "gaussian", "mitchell", "blackman-harris"] {
        parse(&format!("{CAMERA}[render]\nfilter = \"{name}\"\n"));
        parse(&format!("{CAMERA}[render]\nfilter = {{ type = \"{name}\", radius = 1 }}\n"));
    }
}

#[test]
fn materials_and_textures_are_read() {
    let text = format!(
        r#"{CAMERA}
[materials.glass]
type = "dielectric"
ior = 1.33

[materials.gold]
type = "conductor"
metal = "gold"
roughness = 0.3

[materials.custom_metal]
type = "conductor"
eta = [0.2, 0.4, 1.3]
k = [3.4, 2.3, 1.7]

[materials.schlick]
type = "conductor"
f0 = [0.9, 0.6, 0.3]

[materials.paint]
type = "plastic"
diffuse = {{ type = "checker", a = [0.9, 0.9, 0.9], b = 0.1, uv_scale = 8 }}
roughness = 0.2

[materials.wall]
type = "diffuse"
[materials.wall.reflectance]
type = "grid"
uv_scale = [8, 4]
spacing = 0.25
highlights = [{{ axis = "v", index = 10, colour = [0.8, 0.05, 0.05] }}, {{ axis = "u", index = -2, color = [0, 1, 0] }}]

[[objects]]
shape = {{ type = "plane", point = [0, -1, 0], normal = [0, 1, 0] }}
material = "wall"

[[objects]]
shape = {{ type = "sphere", center = [0, 0, 0], radius = 1 }}
material = {{ type = "mirror" }}
"#
    );
    let s = parse(&text);
    let m = &s.world.materials;
    // Six named, one inline.
    assert_eq!(m.len(), 7);
    assert!(matches!(m[0], Material::Dielectric { ior, .. } if ior == 1.33));
    assert!(
        matches!(m[1], Material::RoughConductor { roughness, fresnel } if roughness == 0.3 && fresnel == ConductorFresnel::preset("gold").unwrap())
    );
    assert!(matches!(m[2], Material::RoughConductor { fresnel: ConductorFresnel::Complex { .. }, .. }));
    assert!(matches!(m[3], Material::RoughConductor { fresnel: ConductorFresnel::Schlick { .. }, .. }));
    match &m[4] {
        Material::RoughPlastic { diffuse: Texture::Checker { b, uv_scale, .. }, .. } => {
            assert_eq!(*uv_scale, [8.0, 8.0]);
            assert!(matches!(**b, Texture::Constant(c) if c.rgb() == Rgb::splat(0.1)));
        }
        other => panic!("{other:?}"),
    }
    match &m[5] {
        Material::Diffuse { reflectance: Texture::Grid { highlights, spacing, .. } } => {
            assert_eq!(highlights.len(), 2);
            assert_eq!(*spacing, 0.25);
            assert_eq!(highlights[1].colour, Rgb::Y);
        }
        other => panic!("{other:?}"),
    }
    assert!(matches!(m[6], Material::Mirror { .. }));
    assert_eq!(s.world.objects(Region::Upper)[0].material, 5);
    assert_eq!(s.world.objects(Region::Upper)[1].material, 6);
}

#[test]
fn transforms_apply_scale_then_rotations_then_translation() {
    let text = format!(
        "{CAMERA}[[objects]]\nshape = {{ type = \"sphere\", center = [1, 0, 0], radius = 1 }}\n\
         transform = {{ scale = 2, rotate = [{{ axis = [0, 0, 1], degrees = 90 }}, {{ axis = [1, 0, 0], degrees = 90 }}], translate = [0, 0, 10] }}\n"
    );
    let s = parse(&text);
    let b = s.world.objects(Region::Upper)[0].shape.bounds();
    // Centre (1, 0, 0) → scale (2, 0, 0) → about z (0, 2, 0) → about x (0, 0, 2) → (0, 0, 12).
    let centre = b.centroid();
    assert!((centre - render::geometry::Vec3::new(0.0, 0.0, 12.0)).length() < 1e-9, "{centre}");
    assert!((b.diagonal().x - 4.0).abs() < 1e-9, "radius scaled to 2");
}

#[test]
fn meshes_and_images_load_relative_to_the_scene_file() {
    let dir = temp_dir("relative");
    std::fs::create_dir_all(dir.join("assets")).unwrap();
    std::fs::write(dir.join("assets/quad.obj"), "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\n").unwrap();
    std::fs::write(dir.join("assets/tex.png"), TINY_PNG).unwrap();
    let text = format!(
        r#"{CAMERA}
[sky]
type = "equirect"
file = "assets/tex.png"
intensity = 2

[[objects]]
shape = {{ type = "mesh", file = "assets/quad.obj" }}
material = {{ type = "diffuse", reflectance = {{ type = "image", file = "assets/tex.png" }} }}
transform = {{ translate = [0, 0, -1] }}
"#
    );
    let path = dir.join("scene.toml");
    std::fs::write(&path, text).unwrap();
    let s = scene::load(&path).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(s.world.objects(Region::Upper).len(), 2, "a quad is two triangles");
    match &s.world.materials[0] {
        Material::Diffuse { reflectance: Texture::Image { image, .. } } => assert_eq!(image.width(), 2),
        other => panic!("{other:?}"),
    }
    assert!(matches!(s.world.sky(Region::Upper), Sky::Equirect(e) if e.intensity == 2.0));
    std::fs::remove_dir_all(&dir).ok();
}

/// Each sky type builds its own kind of sky, with the parameters the file gives and the
/// documented defaults for the rest.
#[test]
fn all_skies_are_read_with_their_parameters() {
    let sky = |body: &str| parse(&format!("{CAMERA}[sky]\n{body}\n")).world.sky(Region::Upper).clone();
    match sky("type = \"constant\"\nradiance = 0.5") {
        Sky::Constant(c) => assert_eq!(c, Rgb::splat(0.5)),
        other => panic!("{other:?}"),
    }
    match sky("type = \"gradient\"\nzenith = [0.1, 0.2, 0.9]\nup = [0, 0, 1]") {
        Sky::Gradient(g) => {
            assert_eq!(g.zenith, Rgb::new(0.1, 0.2, 0.9));
            assert_eq!((g.horizon, g.nadir), (Rgb::new(0.9, 0.9, 1.0), Rgb::new(0.9, 0.9, 1.0)));
            assert_eq!(g.frame, SkyFrame::new(Vec3::Z, 0.0).unwrap());
        }
        other => panic!("{other:?}"),
    }
    match sky("type = \"gradient\"\nhorizon = 0.2\nnadir = [0, 0, 0.1]") {
        Sky::Gradient(g) => {
            assert_eq!(
                (g.horizon, g.zenith, g.nadir),
                (Rgb::splat(0.2), Rgb::new(0.3, 0.5, 0.9), Rgb::new(0.0, 0.0, 0.1))
            );
            assert_eq!(g.frame, SkyFrame::Y_UP);
        }
        other => panic!("{other:?}"),
    }
    match sky("type = \"stars\"\ndensity = 500\nseed = 3\nbackground = [0.001, 0.001, 0.002]\nstar_radius_deg = 0.1") {
        Sky::StarField(s) => {
            let p = s.params();
            assert_eq!((p.density, p.seed, p.star_radius_deg), (500.0, 3, 0.1));
            assert_eq!(p.background, Rgb::new(0.001, 0.001, 0.002));
            assert_eq!(p.brightness, StarFieldParams::default().brightness);
        }
        other => panic!("{other:?}"),
    }
    match sky("type = \"grid\"\nbackground = 0.1\nequator = [1, 0, 1]\nrotation_deg = 30\nspacing_deg = 15") {
        Sky::Grid(g) => {
            assert_eq!(g.background, [Rgb::splat(0.1); 4]);
            assert_eq!((g.equator, g.prime_meridian), (Some(Rgb::new(1.0, 0.0, 1.0)), None));
            assert_eq!((g.line, g.spacing_deg, g.width_deg), (Rgb::splat(0.9), 15.0, 0.3));
            assert_eq!(g.frame, SkyFrame::new(Vec3::Y, 30.0).unwrap());
        }
        other => panic!("{other:?}"),
    }
    match sky("type = \"grid\"\nbackground = [[1, 0, 0], [0, 1, 0], [0, 0, 1], 0.5]\nup = [1, 0, 0]\nline = 2") {
        Sky::Grid(g) => {
            assert_eq!(g.background, [Rgb::X, Rgb::Y, Rgb::Z, Rgb::splat(0.5)]);
            assert_eq!(g.line, Rgb::splat(2.0));
            assert_eq!(g.frame, SkyFrame::new(Vec3::X, 0.0).unwrap());
        }
        other => panic!("{other:?}"),
    }
}

/// Every TOML example in docs/scene-format.md is valid: whole documents as they are, table
/// fragments after a camera, and one-line fragments (`shape = …`) inside an object. Only files the
/// examples name (images, meshes) may be missing.
#[test]
fn documentation_examples_parse() {
    let doc_path = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../docs/scene-format.md");
    let doc = std::fs::read_to_string(&doc_path).expect("docs/scene-format.md");
    let mut blocks = Vec::new();
    let mut current: Option<String> = None;
    for line in doc.lines() {
        match (&mut current, line.trim_start()) {
            (None, "```toml") => current = Some(String::new()),
            (Some(block), "```") => {
                blocks.push(std::mem::take(block));
                current = None;
            }
            (Some(block), _) => {
                block.push_str(line);
                block.push('\n');
            }
            (None, _) => {}
        }
    }
    assert!(blocks.len() > 20, "found {} examples", blocks.len());
    let sphere = "shape = { type = \"sphere\", center = [0, 0, 0], radius = 1 }";
    let mut documents = Vec::new();
    for block in &blocks {
        let first = block.lines().map(str::trim).find(|l| !l.is_empty() && !l.starts_with('#')).unwrap_or("");
        if first.starts_with('[') {
            let mut text = block.clone();
            if !text.contains("[camera]") {
                text.push_str(CAMERA);
            }
            if text.contains("[lower.") && !text.contains("[spacetime]") {
                text.push_str("[spacetime]\ntype = \"ellis\"\nthroat = 1\n");
            }
            documents.push(text);
        } else {
            for line in block.lines().map(str::trim).filter(|l| !l.is_empty() && !l.starts_with('#')) {
                let text = match line.split_whitespace().next() {
                    Some("shape") => format!("[[objects]]\n{line}\n"),
                    Some("filter") => format!("[render]\n{line}\n"),
                    _ => format!("[[objects]]\n{sphere}\n{line}\n"),
                };
                documents.push(format!("{CAMERA}{text}"));
            }
        }
    }
    for text in documents {
        if let Err(e) = scene::parse(&text, "docs example", Path::new(".")) {
            let m = e.to_string();
            let missing_file = m.contains("cannot load image")
                || m.contains("cannot open mesh file")
                || (m.contains("glTF file") && m.contains("cannot read"));
            assert!(missing_file, "{m}\nin:\n{text}");
        }
    }
}

#[test]
fn views_name_other_cameras() {
    let text = format!("{CAMERA}[views.top]\nposition = [0, 9, 0.1]\nlook_at = [0, 0, 0]\n[views.side]\nposition = [9, 0, 0]\nlook_at = [0, 0, 0]\n");
    assert_eq!(scene::view_names(&text), ["top", "side"]);
    let top = scene::parse_view(&text, "v.toml", Path::new("."), Some("top")).unwrap();
    assert_eq!(top.camera.position, render::geometry::Vec3::new(0.0, 9.0, 0.1));
    assert_eq!(parse(&text).camera.position, render::geometry::Vec3::new(0.0, 0.0, 5.0));
    let err = scene::parse_view(&text, "v.toml", Path::new("."), Some("front")).unwrap_err().to_string();
    assert!(err.contains("no view named \"front\"") && err.contains("\"top\", \"side\""), "{err}");
    // A mistake in a view that is not rendered is still an error, at its line.
    let bad = format!("{CAMERA}[views.top]\nposition = [0, 9, 0.1]\nlook_at = [0, 9, 0.1]\n");
    let err = scene::parse(&bad, "v.toml", Path::new(".")).unwrap_err().to_string();
    assert!(err.starts_with("v.toml:7:") && err.contains("views.top.look_at"), "{err}");
}

#[test]
fn projections_are_chosen_by_name_with_their_defaults() {
    const POSE: &str = "[camera]\nposition = [0, 0, 5]\nlook_at = [0, 0, 0]\n";
    let projection = |extra: &str| parse(&format!("{POSE}{extra}")).camera.projection;
    assert!(matches!(projection(""), Projection::Perspective(_)));
    assert!(matches!(projection("projection = \"perspective\"\nfov = 50\n"), Projection::Perspective(_)));
    assert_eq!(projection("projection = \"equirectangular\""), Projection::Equirectangular(Equirectangular));
    assert_eq!(projection("projection = \"fisheye\""), Projection::Fisheye(Fisheye::new(180.0).unwrap()));
    assert_eq!(
        projection("projection = \"fisheye\"\nfisheye_fov = 220"),
        Projection::Fisheye(Fisheye::new(220.0).unwrap())
    );
    assert_eq!(projection("projection = \"ods\""), Projection::Ods(Ods::new(0.064).unwrap()));
    assert_eq!(projection("projection = \"ods\"\nipd = 0.5"), Projection::Ods(Ods::new(0.5).unwrap()));
    // A view has its own projection; an orbiting or keyframed camera keeps its projection.
    let text = format!(
        "{CAMERA}[views.dome]\nposition = [0, 0, 0]\nlook_at = [0, 1, 0]\nup = [0, 0, -1]\nprojection = \"fisheye\"\n"
    );
    let dome = scene::parse_view(&text, "v.toml", Path::new("."), Some("dome")).unwrap();
    assert!(matches!(dome.camera.projection, Projection::Fisheye(_)));
    assert!(matches!(parse(&text).camera.projection, Projection::Perspective(_)));
    let orbit = format!("{POSE}projection = \"ods\"\norbit = {{ center = [0, 0, 0], period = 4 }}\n");
    let rig = parse(&orbit).animation.unwrap().rig;
    assert_eq!(rig.projection, Projection::Ods(Ods::new(0.064).unwrap()));
    let keyed = "[camera]\nprojection = \"equirectangular\"\n[[camera.keyframes]]\ntime = 0\nposition = [0, 0, 5]\nlook_at = [0, 0, 0]\n";
    assert_eq!(parse(keyed).camera.projection, Projection::Equirectangular(Equirectangular));
}

/// The names a builder's table knows, read from its error for an unknown name
/// (`…; expected "a", "b" or "c"`).
fn known_names(text: &str) -> Vec<String> {
    let message = scene::parse(text, "t.toml", Path::new(".")).map(|_| ()).expect_err("an unknown name").to_string();
    let (_, list) = message.split_once("; expected ").unwrap_or_else(|| panic!("{message}"));
    list.replace(" or ", ", ").split(", ").map(|n| n.trim_matches('"').to_string()).collect()
}

/// A documented default as a TOML value: the text without its backticks, a fraction `a/b`
/// written as the number it is; `None` for prose ("— (required)", "as `line`").
fn toml_value(text: &str) -> Option<String> {
    let text = text.trim().trim_matches('`').trim();
    let value = match text.split_once('/') {
        Some((a, b)) => format!("{:?}", a.trim().parse::<f64>().ok()? / b.trim().parse::<f64>().ok()?),
        None => text.to_string(),
    };
    toml::from_str::<toml::Table>(&format!("v = {value}")).ok().map(|_| value)
}

/// The `key` (default, …) pairs of a "parameters (defaults)" cell: a key in backticks directly
/// followed (past words, not past another key) by a parenthesis whose first item is the default.
fn documented_parameters(cell: &str) -> Vec<(String, String)> {
    let mut out = Vec::new();
    let pieces: Vec<&str> = cell.split('`').collect();
    // Odd pieces are inside backticks; a key is one followed by text with a parenthesis.
    let mut i = 1;
    while i + 1 < pieces.len() {
        let (key, after) = (pieces[i], pieces[i + 1]);
        i += 2;
        let Some(open) = after.find('(') else { continue };
        // The parenthesis's content up to its first top-level comma, backticks rejoined.
        let mut content = after[open + 1..].to_string();
        let mut j = i;
        while !content.contains(')') && j < pieces.len() {
            content.push('`');
            content.push_str(pieces[j]);
            j += 1;
        }
        let mut depth = 0;
        let end = content
            .char_indices()
            .find(|&(_, c)| {
                depth += i32::from(c == '[') - i32::from(c == ']');
                depth == 0 && (c == ',' || c == ')')
            })
            .map_or(content.len(), |(k, _)| k);
        if let Some(value) = toml_value(&content[..end]) {
            out.push((key.to_string(), value));
        }
    }
    out
}

/// Every default docs/scene-format.md gives for a filter, material, texture, sky, camera
/// (projection) or `[render]` key (integrator, …) is the builder's: the scene without the key and
/// the scene with the key set to the documented value build the same thing. And the tables of
/// filters, materials, textures and skies list exactly the types the builder knows.
#[test]
fn documented_defaults_are_the_builders() {
    let dir = temp_dir("defaults");
    std::fs::write(dir.join("tex.png"), TINY_PNG).unwrap();
    let build = |text: &str, what: &dyn Fn(&render::scene::Scene) -> String| {
        scene::parse(text, "defaults.toml", &dir).map(|s| what(&s)).unwrap_or_else(|e| panic!("{e}\nin:\n{text}"))
    };
    let filter = |s: &render::scene::Scene| format!("{:?}", s.settings.filter);
    let material = |s: &render::scene::Scene| format!("{:?}", s.world.materials[0]);
    let sky = |s: &render::scene::Scene| format!("{:?}", s.world.sky(Region::Upper));
    let camera = |s: &render::scene::Scene| format!("{:?} {:?}", s.camera, s.animation);
    let settings = |s: &render::scene::Scene| format!("{:?}", s.settings);
    // The scene of a kind's table (`{}` where the key goes) and what to compare of it.
    type Extract = dyn Fn(&render::scene::Scene) -> String;
    let scene_of = |section: &str, name: &str, key: &str| -> Option<(String, &Extract)> {
        Some(match section {
            "Filters" => (format!("{CAMERA}[render]\nfilter = {{ type = \"{name}\" {{}} }}\n"), &filter as &Extract),
            "Materials" => (format!("{CAMERA}[materials.m]\ntype = \"{name}\"\n{{}}\n"), &material),
            "Textures" => {
                let file = if name == "image" { "file = \"tex.png\"\n" } else { "" };
                let body = format!("type = \"diffuse\"\n[materials.m.reflectance]\ntype = \"{name}\"\n{file}");
                (format!("{CAMERA}[materials.m]\n{body}{{}}\n"), &material)
            }
            "sky" => {
                let file = if name == "equirect" { "file = \"tex.png\"\n" } else { "" };
                (format!("{CAMERA}[sky]\ntype = \"{name}\"\n{file}{{}}\n"), &sky)
            }
            "`[camera]`" => {
                let projection = match key {
                    "fisheye_fov" => "projection = \"fisheye\"\n",
                    "ipd" => "projection = \"ods\"\n",
                    _ => "",
                };
                (format!("[camera]\nposition = [0, 0, 5]\nlook_at = [0, 0, 0]\n{projection}{{}}\n"), &camera)
            }
            "`[render]`" => {
                let poster = if key.starts_with("poster_") { "intersection = \"poster\"\n" } else { "" };
                (format!("{CAMERA}[render]\n{poster}{{}}\n"), &settings)
            }
            _ => return None,
        })
    };
    let doc = std::fs::read_to_string(Path::new(env!("CARGO_MANIFEST_DIR")).join("../../docs/scene-format.md"))
        .expect("docs/scene-format.md");
    let (mut section, mut sky_type) = (String::new(), String::new());
    let mut documented: std::collections::BTreeMap<&str, Vec<String>> = Default::default();
    let mut checked = Vec::new();
    for line in doc.lines() {
        if let Some(heading) = line.strip_prefix('#') {
            section = heading.trim_start_matches('#').trim().to_string();
            if let Some(name) = section.strip_prefix("`type = \"").and_then(|s| s.strip_suffix("\"`")) {
                documented.entry("sky").or_default().push(name.to_string());
                (sky_type, section) = (name.to_string(), "sky".to_string());
            }
            continue;
        }
        let cells: Vec<&str> = line.split('|').map(str::trim).collect();
        if cells.len() < 4 || cells[1].starts_with('-') || ["key", "`type`"].contains(&cells[1]) {
            continue;
        }
        // Tables of types ("parameters (defaults)") and tables of keys (key | type | default).
        let (name, pairs) = match section.as_str() {
            "Filters" | "Materials" | "Textures" => {
                (cells[1].trim_matches('`').trim_matches('"').to_string(), documented_parameters(cells[2]))
            }
            "sky" | "`[camera]`" | "`[render]`" => {
                let name = if section == "sky" { sky_type.clone() } else { String::new() };
                let key = cells[1].trim_matches('`').to_string();
                (name, toml_value(cells[3]).map(|v| (key, v)).into_iter().collect())
            }
            _ => continue,
        };
        if let Some(list) = match section.as_str() {
            "Filters" => Some("filter"),
            "Materials" => Some("material"),
            "Textures" => Some("texture"),
            _ => None,
        } {
            documented.entry(list).or_default().push(name.clone());
        }
        for (key, value) in pairs {
            let Some((text, extract)) = scene_of(&section, &name, &key) else { continue };
            let without = build(&text.replace("{}", ""), extract);
            // A filter's keys are inline-table fields; every other kind's, lines of its table.
            let set = if section == "Filters" { format!(", {key} = {value}") } else { format!("{key} = {value}") };
            let with = build(&text.replace("{}", &set), extract);
            assert_eq!(without, with, "{section} {name}: documented default {key} = {value} is not the builder's");
            checked.push((section.clone(), name.clone(), key));
        }
    }
    for (section, name, key) in [
        ("Filters", "gaussian", "sigma"),
        ("Filters", "mitchell", "b"),
        ("Filters", "blackman-harris", "radius"),
        ("Materials", "conductor", "metal"),
        ("Materials", "plastic", "ior"),
        ("Textures", "checker", "uv_scale"),
        ("Textures", "earth", "clouds"),
        ("sky", "stars", "brightness"),
        ("sky", "grid", "width_deg"),
        ("sky", "equirect", "intensity"),
        ("`[camera]`", "", "fisheye_fov"),
        ("`[camera]`", "", "ipd"),
        ("`[render]`", "", "integrator"),
        ("`[render]`", "", "poster_max_iterations"),
    ] {
        let must = (section.to_string(), name.to_string(), key.to_string());
        assert!(checked.contains(&must), "{must:?} not checked; checked: {checked:#?}");
    }
    // The tables list exactly the types the builder knows, in its order.
    let known = [
        ("filter", format!("{CAMERA}[render]\nfilter = \"?\"\n")),
        ("material", format!("{CAMERA}[materials.m]\ntype = \"?\"\n")),
        ("texture", format!("{CAMERA}[materials.m]\ntype = \"diffuse\"\nreflectance = {{ type = \"?\" }}\n")),
        ("sky", format!("{CAMERA}[sky]\ntype = \"?\"\n")),
    ];
    for (what, text) in known {
        assert_eq!(documented.get(what), Some(&known_names(&text)), "the {what} types documented");
    }
    std::fs::remove_dir_all(&dir).ok();
}

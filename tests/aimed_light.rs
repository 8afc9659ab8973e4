//! Light sampling by aimed rays is unbiased in every curved spacetime it serves: in a small lit
//! room around a spinning hole, and around the mouth of a wormhole, the path integrator (light
//! points joined by rays aimed with Newton's method, MIS with BSDF sampling) and brute force
//! agree within their noise, over the whole image and pixel by pixel; around a charged hole too;
//! around a Schwarzschild hole, the aimed rays agree with Schwarzschild's own connector, and
//! beside a wormhole rays aimed in their plane agree with rays aimed in 4-D.

#![allow(clippy::unwrap_used)] // A panic is a failed test.

mod common;

use common::{assert_agree, replicas, spread};
use render::scene::Scene;
use render::settings::{IntegratorKind, LightConnection};

const REPLICAS: u32 = 16;

/// A 6 × 4 × 8 room with a ceiling lamp (large enough for brute force to find it often), a ball and a red block, around `spacetime` (a
/// `[spacetime]` table) at the origin, seen at 20 × 15 pixels.
fn room(spacetime: &str) -> Scene {
    room_in(spacetime, "upper")
}

/// [`room`] in the spacetime's region `region`.
fn room_in(spacetime: &str, region: &str) -> Scene {
    scene::parse(&room_text(spacetime, region), "aimed-light fixture", std::path::Path::new(".")).unwrap()
}

/// The scene file of [`room_in`].
fn room_text(spacetime: &str, region: &str) -> String {
    format!(
        r#"
{spacetime}
[camera]
region = "{region}"
position = [0.3, 0.5, 3.6]
look_at = [0, -0.3, -4]
fov = 70
[render]
width = 20
height = 15
max_depth = 3
[materials.white]
type = "diffuse"
reflectance = [0.7, 0.7, 0.7]
[materials.red]
type = "diffuse"
reflectance = [0.7, 0.15, 0.1]
[materials.lamp]
type = "diffuse"
reflectance = [0.5, 0.5, 0.5]
[[objects]]
shape = {{ type = "rectangle", corner = [-3, -2, 4], edge_u = [6, 0, 0], edge_v = [0, 0, -8] }}
material = "white"
region = "{region}"
[[objects]]
shape = {{ type = "rectangle", corner = [-3, -2, -4], edge_u = [6, 0, 0], edge_v = [0, 4, 0] }}
material = "white"
region = "{region}"
[[objects]]
shape = {{ type = "rectangle", corner = [-3, -2, 4], edge_u = [0, 0, -8], edge_v = [0, 4, 0] }}
material = "red"
region = "{region}"
[[objects]]
shape = {{ type = "sphere", center = [1.4, -1.4, -1.5], radius = 0.6 }}
material = "white"
region = "{region}"
[[objects]]
shape = {{ type = "rectangle", corner = [-1, 1.95, -2], edge_u = [2, 0, 0], edge_v = [0, 0, 2] }}
material = "lamp"
region = "{region}"
emission = {{ radiance = [5, 5, 5] }}
"#
    )
}

#[test]
fn aimed_light_sampling_agrees_with_brute_force_around_a_spinning_hole() {
    let scene = room("[spacetime]\ntype = \"kerr\"\nmass = 0.25\nspin = 0.225\naxis = [0, 1, 0]");
    let aimed = replicas(&scene, IntegratorKind::Path, 8, 0..REPLICAS);
    let brute = replicas(&scene, IntegratorKind::BruteForce, 64, 0..REPLICAS);
    assert_agree(&aimed, &brute, 0.03, "Kerr room");
    // And it is worth it: at 8 samples per pixel the aimed light leaves far less noise.
    let brute8 = replicas(&scene, IntegratorKind::BruteForce, 8, 0..REPLICAS);
    let ratio = spread(&brute8) / spread(&aimed);
    assert!(ratio > 4.0, "variance ratio brute force ÷ aimed at 8 spp: {ratio}");
}

#[test]
fn aimed_light_sampling_agrees_with_brute_force_beside_a_wormhole() {
    // On both sides: the lower region's world is its chart turned inside out, so directions
    // measured in the chart's frames must be taken to the world's.
    for region in ["upper", "lower"] {
        let scene = room_in("[spacetime]\ntype = \"ellis\"\nthroat = 0.5", region);
        let aimed = replicas(&scene, IntegratorKind::Path, 8, 0..REPLICAS);
        let brute = replicas(&scene, IntegratorKind::BruteForce, 64, 0..REPLICAS);
        assert_agree(&aimed, &brute, 0.03, &format!("wormhole room, {region} region"));
    }
}

/// The wormhole room of [`room_in`] in the upper region with its lamp's radiance `own_lamp`
/// (`""`: dark), and a lamp in the lower region facing the throat, whose light reaches the room
/// only through it.
fn room_lit_through_a_throat(own_lamp: &str) -> Scene {
    let room = room_text("[spacetime]\ntype = \"ellis\"\nthroat = 0.5", "upper");
    let mut text = room.replace("emission = { radiance = [5, 5, 5] }", own_lamp);
    text.push_str(
        r#"
[[objects]]
shape = { type = "rectangle", corner = [-2, 1.2, -2], edge_u = [4, 0, 0], edge_v = [0, 0, 4] }
material = "lamp"
region = "lower"
emission = { radiance = [3, 6, 9] }
"#,
    );
    scene::parse(&text, "aimed-light fixture", std::path::Path::new(".")).unwrap()
}

/// Light aimed through the throat at the other region's lamp is unbiased, and it pays: at
/// equal samples brute force, which finds that lamp only by chance, leaves more noise (2.3×
/// measured; rays through the throat's small opening are costly to aim and their images of the
/// lamp sharp-edged, so the gain is smaller than in one region).
#[test]
fn aimed_light_through_a_throat_agrees_with_brute_force() {
    let scene = room_lit_through_a_throat("");
    let aimed = replicas(&scene, IntegratorKind::Path, 32, 0..REPLICAS);
    // Brute force finds the lamp only through the throat's small opening: it needs more samples.
    let brute = replicas(&scene, IntegratorKind::BruteForce, 256, 0..REPLICAS);
    assert_agree(&aimed, &brute, 0.03, "room lit through a throat");
    let brute32 = replicas(&scene, IntegratorKind::BruteForce, 32, 0..REPLICAS);
    let ratio = spread(&brute32) / spread(&aimed);
    assert!(ratio > 1.5, "variance ratio brute force ÷ aimed at 32 spp: {ratio}");
}

/// Where both regions are lit, each shading point splits its light samples between them by its
/// own estimate of what each gives it: unbiased, with that split in the MIS weights of the
/// emitters BSDF sampling finds in either region.
#[test]
fn aimed_light_from_both_regions_agrees_with_brute_force() {
    let scene = room_lit_through_a_throat("emission = { radiance = [1, 1, 1] }");
    let aimed = replicas(&scene, IntegratorKind::Path, 16, 0..REPLICAS);
    let brute = replicas(&scene, IntegratorKind::BruteForce, 128, 0..REPLICAS);
    assert_agree(&aimed, &brute, 0.03, "room lit in both regions");
}

#[test]
fn aimed_light_sampling_agrees_with_brute_force_around_a_charged_hole() {
    let scene = room("[spacetime]\ntype = \"reissner-nordstrom\"\nmass = 0.25\ncharge = 0.2");
    let aimed = replicas(&scene, IntegratorKind::Path, 8, 0..REPLICAS);
    let brute = replicas(&scene, IntegratorKind::BruteForce, 64, 0..REPLICAS);
    assert_agree(&aimed, &brute, 0.03, "charged-hole room");
}

#[test]
fn rays_aimed_in_their_plane_agree_with_rays_aimed_in_four_dimensions() {
    let mut scene = room("[spacetime]\ntype = \"ellis\"\nthroat = 0.5");
    let in_plane = replicas(&scene, IntegratorKind::Path, 8, 0..REPLICAS);
    scene.settings.light_connection = LightConnection::Aimed;
    let four_d = replicas(&scene, IntegratorKind::Path, 8, REPLICAS..2 * REPLICAS);
    assert_agree(&in_plane, &four_d, 0.03, "wormhole room, in-plane vs 4-D aims");
}

#[test]
fn aimed_rays_agree_with_the_schwarzschild_connector() {
    let mut scene = room("[spacetime]\ntype = \"schwarzschild\"\nmass = 0.25");
    let own = replicas(&scene, IntegratorKind::Path, 8, 0..REPLICAS);
    scene.settings.light_connection = LightConnection::Aimed;
    // Other seeds: the same ones would share camera rays and BSDF samples with the own
    // connector's render, and agree better than independent estimates do.
    let aimed = replicas(&scene, IntegratorKind::Path, 8, REPLICAS..2 * REPLICAS);
    assert_agree(&aimed, &own, 0.03, "Schwarzschild room, aimed vs own connector");
}

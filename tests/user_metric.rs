//! Metrics written in scene files (`[spacetime] type = "metric"`) against the built-in ones they
//! spell: the same rays, so the same image pixel by pixel up to the integrators' tolerance, with
//! the camera on the written chart's polar axis (where spherical coordinates are singular); and
//! load errors that name the field and the column inside the expression.

#![allow(clippy::unwrap_used)] // A panic is a failed test.

use std::path::Path;
use std::sync::atomic::AtomicBool;

const SCHWARZSCHILD: &str = r#"
type = "metric"
coordinates = "spherical"
parameters = { M = 1.0 }
g_tt = "-(1 - 2*M/r)"
g_rr = "1/(1 - 2*M/r)"
g_thetatheta = "r^2"
g_phiphi = "r^2*sin(theta)^2"
axis = [0, 0, 1]
"#;

const REISSNER_NORDSTROM: &str = r#"
type = "metric"
coordinates = "spherical"
parameters = { M = 1.0, Q = 0.9 }
g_tt = "-(1 - 2*M/r + Q^2/r^2)"
g_rr = "1/(1 - 2*M/r + Q^2/r^2)"
g_thetatheta = "r^2"
g_phiphi = "(r*sin(theta))^2"
axis = [0, 0, 1]
"#;

/// A scene of `spacetime` (the `[spacetime]` table's body): a camera on the z axis at r = 30
/// looking at the hole, a grid sky, 20×20 pixels at 1 spp.
fn scene(spacetime: &str) -> String {
    format!(
        "[spacetime]\n{spacetime}\n[camera]\nposition = [0.0, 0.0, 30.0]\nlook_at = [0.0, 0.0, 0.0]\nup = [0, 1, 0]\n\
         fov = 40\n[render]\nwidth = 20\nheight = 20\nspp = 1\nmax_depth = 1\n[sky]\ntype = \"grid\"\n\
         background = [[0.55, 0.12, 0.1], [0.1, 0.4, 0.12], [0.1, 0.12, 0.5], [0.5, 0.42, 0.1]]\n\
         line = [0.95, 0.95, 0.95]\nspacing_deg = 10\nwidth_deg = 0.5\n"
    )
}

/// The image's pixels, with the render's failed-ray and NaN counts checked to be 0.
fn render(spacetime: &str) -> Vec<[f64; 3]> {
    let scene = scene::parse(&scene(spacetime), "test.toml", Path::new(".")).unwrap_or_else(|e| panic!("{e}"));
    let (film, stats) = render::renderer::render(&scene, &AtomicBool::new(false), &|_, _| {});
    assert_eq!((stats.nan_samples, stats.paths.fates.failed), (0, 0));
    (0..20).flat_map(|y| (0..20).map(move |x| (x, y))).map(|(x, y)| film.pixel_f64(x, y)).collect()
}

/// Every pixel within 10⁻³ of the built-in metric's but for at most 2 of 400, which may fall on
/// the other side of a grid line's edge (the 4-D and in-plane tracers meet the integration
/// tolerance differently); the shadow is the same size (black pixels within 2).
fn assert_same_image(written: &str, built_in: &str) {
    let (a, b) = (render(written), render(built_in));
    let differ = a.iter().zip(&b).filter(|(p, q)| (0..3).any(|i| (p[i] - q[i]).abs() > 1e-3)).count();
    assert!(differ <= 2, "{differ} of 400 pixels differ");
    let black = |img: &[[f64; 3]]| img.iter().filter(|p| p.iter().sum::<f64>() == 0.0).count() as i64;
    assert!(black(&a) > 20 && (black(&a) - black(&b)).abs() <= 2, "{} vs {} black", black(&a), black(&b));
}

#[test]
fn spherical_schwarzschild_on_its_axis_is_the_built_in_one() {
    assert_same_image(SCHWARZSCHILD, "type = \"schwarzschild\"\nmass = 1.0");
}

#[test]
fn written_reissner_nordstrom_is_the_built_in_one() {
    assert_same_image(REISSNER_NORDSTROM, "type = \"reissner-nordstrom\"\nmass = 1.0\ncharge = 0.9");
}

/// The error of loading a scene of `spacetime`.
fn error(spacetime: &str) -> String {
    match scene::parse(&scene(spacetime), "test.toml", Path::new(".")) {
        Ok(_) => panic!("loaded: {spacetime}"),
        Err(e) => e.to_string(),
    }
}

#[test]
fn load_errors_name_the_field_and_the_column() {
    // Line 2 of the scene is the table's first line; `g_tt` is its 5th.
    let bad = SCHWARZSCHILD.replace("-(1 - 2*M/r)", "-(1 - 2*M/q)");
    let e = error(&bad);
    assert!(e.contains("test.toml:6:") && e.contains("spacetime.g_tt") && e.contains('q'), "{e}");
    let column = e.split(':').nth(2).unwrap().trim().parse::<usize>().unwrap();
    assert_eq!(column, "g_tt = \"-(1 - 2*M/".len() + 1, "{e}");
    let e = error(&format!("{SCHWARZSCHILD}g_ttheta = \"0\"\ng_thetat = \"0\""));
    assert!(e.contains("spacetime.g_thetat") && e.contains("g_ttheta"), "{e}");
    let e = error(&format!("{SCHWARZSCHILD}g_xy = \"0\""));
    assert!(e.contains("spacetime.g_xy") && e.contains("not a component"), "{e}");
    let e = error(&SCHWARZSCHILD.replace("M = 1.0", "r = 1.0"));
    assert!(e.contains("spacetime.parameters.r"), "{e}");
    // Euclidean signature, and a camera inside the horizon: the camera cannot be at rest.
    let e = error(&SCHWARZSCHILD.replace("-(1 - 2*M/r)", "1"));
    assert!(e.contains("camera") && e.contains("signature"), "{e}");
    let e = error(&SCHWARZSCHILD.replace("M = 1.0", "M = 20.0"));
    assert!(e.contains("camera"), "{e}");
}

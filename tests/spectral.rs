//! Spectral rendering (`[render] spectral = true`): paths carry sampled wavelengths, so a
//! frequency shift changes the colour of every light, RGB lamps and skies included, while scenes
//! whose spectra multiply as their colours do render as they do in RGB.

#![allow(clippy::unwrap_used)] // A panic is a failed test.

use render::film::Film;
use render::renderer::render;
use render::spectrum::{xyz_quadrature, xyz_to_linear_srgb, FrequencyShift, RgbUpsampler};
use std::sync::atomic::AtomicBool;

fn film_of(text: &str) -> Film {
    let scene = scene::parse(text, "spectral.toml", std::path::Path::new(".")).unwrap();
    render(&scene, &AtomicBool::new(false), &|_, _| {}).0
}

/// The mean colour over the film, and the standard error of that mean from the spread of its
/// pixels (each an independent estimate).
fn mean_and_error(film: &Film) -> ([f64; 3], [f64; 3]) {
    let pixels: Vec<[f64; 3]> = (0..film.height())
        .flat_map(|y| (0..film.width()).map(move |x| (x, y)))
        .map(|(x, y)| film.pixel_f64(x, y))
        .collect();
    let n = pixels.len() as f64;
    let mean: [f64; 3] = std::array::from_fn(|c| pixels.iter().map(|p| p[c]).sum::<f64>() / n);
    let error = std::array::from_fn(|c| {
        let variance = pixels.iter().map(|p| (p[c] - mean[c]).powi(2)).sum::<f64>() / (n - 1.0);
        (variance / n).sqrt()
    });
    (mean, error)
}

#[test]
fn an_rgb_lamp_ahead_of_a_moving_camera_turns_bluer_in_spectral_rendering() {
    // Flat space: a camera moving at v towards a lamp straight ahead sees it at D = √((1+v)/(1−v))
    // times the frequency. The lamp's RGB colour, lifted to the spectrum S(λ) of that colour under
    // D65, is seen as D⁵ S(Dλ): computed here by quadrature over the CIE tables, apart from the
    // path tracer. In RGB rendering the same lamp only brightens, by D⁴.
    let colour = [1.0f32, 0.8, 0.6];
    let v = 0.3f64;
    let text = format!(
        "[camera]\nposition = [0, 0, 0]\nlook_at = [0, 0, -1]\nfov = 2\nvelocity = [0, 0, {}]\n\
         [render]\nwidth = 4\nheight = 4\nspp = 64\nmax_depth = 1\nspectral = true\n\
         [[objects]]\nshape = {{ type = \"disk\", center = [0, 0, -10], normal = [0, 0, 1], radius = 3 }}\n\
         material = {{ type = \"diffuse\", reflectance = 0 }}\nemission = {{ radiance = {colour:?} }}\n",
        -v
    );
    let doppler = ((1.0 + v) / (1.0 - v)).sqrt();
    let lamp = RgbUpsampler::get().illuminant(colour);
    let expected = xyz_to_linear_srgb(xyz_quadrature(&FrequencyShift::new(doppler).unwrap().apply(lamp)));
    let (seen, error) = mean_and_error(&film_of(&text));
    for c in 0..3 {
        // Four stratified wavelengths a path, 1024 paths: a fraction of a percent.
        let tolerance = 4.0 * error[c] + 2e-3 * expected[c];
        assert!((seen[c] - expected[c]).abs() < tolerance, "channel {c}: {seen:?} ± {error:?} against {expected}");
    }
    // Bluer, not only brighter: blue over red rises from 0.6.
    assert!(seen[2] / seen[0] > 1.3 * 0.6, "{seen:?}");
    let rgb = mean_and_error(&film_of(&text.replace("spectral = true", "spectral = false"))).0;
    for (c, rest) in colour.iter().enumerate() {
        let want = f64::from(*rest) * doppler.powi(4);
        assert!((rgb[c] / want - 1.0).abs() < 1e-3, "RGB rendering: {rgb:?} against {colour:?} × D⁴");
    }
}

/// A closed box lit by a white ceiling lamp, its walls coloured: what spectral and RGB rendering
/// must agree on, as long as colours only meet white (a colour reflected off a white wall, or a
/// white light off a colour), where the lifted spectra multiply as their RGB colours do.
fn coloured_box(spectral: bool) -> String {
    // The wall at `side` (±1) of axis `axis`, spanning the cube [−1, 1]³ (diffuse is two-sided).
    let wall = |axis: usize, side: f64, colour: [f64; 3]| {
        let mut corner = [-1.0; 3];
        corner[axis] = side;
        let edge = |k: usize| {
            let mut e = [0.0; 3];
            e[(axis + k) % 3] = 2.0;
            e
        };
        format!(
            "[[objects]]\nshape = {{ type = \"rectangle\", corner = {corner:?}, edge_u = {:?}, edge_v = {:?} }}\n\
             material = {{ type = \"diffuse\", reflectance = {colour:?} }}\n",
            edge(1),
            edge(2)
        )
    };
    let white = [0.7, 0.7, 0.7];
    [
        format!(
            "[camera]\nposition = [0, 0, 0.95]\nlook_at = [0, 0, -1]\nfov = 80\n\
             [render]\nwidth = 24\nheight = 24\nspp = 128\nmax_depth = 6\nspectral = {spectral}\n"
        ),
        wall(2, -1.0, white),
        wall(2, 1.0, white),
        wall(1, -1.0, white),
        wall(1, 1.0, white),
        wall(0, -1.0, [0.7, 0.25, 0.2]),
        wall(0, 1.0, [0.2, 0.6, 0.3]),
        "[[objects]]\nshape = { type = \"disk\", center = [0, 0.99, 0], normal = [0, -1, 0], radius = 0.4 }\n\
         material = { type = \"diffuse\", reflectance = 0 }\nemission = { radiance = [3, 3, 3] }\n"
            .to_owned(),
    ]
    .concat()
}

#[test]
fn a_box_whose_colours_meet_only_white_renders_as_in_rgb() {
    // The red and green walls face each other, so some light goes red → green and is a product of
    // two lifted spectra, which differs from the product of the RGB colours; it is a small part of
    // the image, within the 1 % allowed below. The difference of the two renders is averaged per
    // pixel, so the image's own variation cancels and only the noise of each remains.
    let (rgb, spectral) = (film_of(&coloured_box(false)), film_of(&coloured_box(true)));
    let (width, height) = (rgb.width(), rgb.height());
    let pixels: Vec<(u32, u32)> = (0..height).flat_map(|y| (0..width).map(move |x| (x, y))).collect();
    let n = pixels.len() as f64;
    for c in 0..3 {
        let differences: Vec<f64> =
            pixels.iter().map(|&(x, y)| spectral.pixel_f64(x, y)[c] - rgb.pixel_f64(x, y)[c]).collect();
        let mean = differences.iter().sum::<f64>() / n;
        let error = (differences.iter().map(|d| (d - mean).powi(2)).sum::<f64>() / (n - 1.0) / n).sqrt();
        let level = pixels.iter().map(|&(x, y)| rgb.pixel_f64(x, y)[c]).sum::<f64>() / n;
        eprintln!("channel {c}: spectral − RGB = {mean:.5} ± {error:.5} of {level:.4}");
        assert!(
            mean.abs() < 4.0 * error + 0.01 * level,
            "channel {c}: spectral − RGB = {mean} ± {error}, against a level of {level}"
        );
    }
}

#[test]
fn a_star_ahead_of_a_moving_camera_is_the_blackbody_at_the_doppler_shifted_temperature() {
    // The brightest of a sparse star field, straight ahead of a camera moving towards it at v: it
    // stays ahead (no aberration on the axis) and is seen as the blackbody at D·T, D⁴ brighter in
    // total, by the path tracer and photon mapping exactly and in spectral rendering within noise.
    let sky = "[sky]\ntype = \"stars\"\nseed = 3\ndensity = 2\nbrightness = 1\nstar_radius_deg = 1\n";
    let at_rest = scene::parse(
        &format!("[camera]\nposition = [0, 0, 0]\nlook_at = [0, 0, -1]\nfov = 40\n{sky}"),
        "stars.toml",
        std::path::Path::new("."),
    )
    .unwrap();
    let render::sky::Sky::StarField(field) = at_rest.world.sky(spacetime::Region::Upper) else {
        panic!("a star field")
    };
    let mut brightest: Option<render::sky::Star> = None;
    field.for_each_star(|s| {
        if brightest.is_none_or(|b| s.flux > b.flux) {
            brightest = Some(*s);
        }
    });
    let star = brightest.unwrap();
    let v = 0.4f64;
    let doppler = ((1.0 + v) / (1.0 - v)).sqrt();
    let [x, y, z] = star.dir.to_array();
    let velocity = star.dir * v;
    let text = |spectral: bool| {
        format!(
            "[camera]\nposition = [0, 0, 0]\nlook_at = [{x}, {y}, {z}]\nfov = 0.05\nvelocity = {:?}\n\
             [render]\nwidth = 4\nheight = 4\nspp = 64\nmax_depth = 0\nspectral = {spectral}\n{sky}",
            velocity.to_array()
        )
    };
    let expected: render::rgb::Rgb = star.seen((doppler, doppler), &());
    let rgb = mean_and_error(&film_of(&text(false))).0;
    for c in 0..3 {
        assert!((rgb[c] / f64::from(expected[c]) - 1.0).abs() < 1e-3, "RGB: {rgb:?} against {expected}");
    }
    // Photon mapping's camera paths see it the same way.
    let photon =
        mean_and_error(&film_of(&text(false).replace("max_depth = 0", "max_depth = 0\nintegrator = \"photon\""))).0;
    for c in 0..3 {
        assert!((photon[c] / f64::from(expected[c]) - 1.0).abs() < 1e-3, "photon: {photon:?} against {expected}");
    }
    let rest: render::rgb::Rgb = star.seen((1.0, 1.0), &());
    assert!(expected.z / expected.x > 1.3 * rest.z / rest.x, "bluer: {rest} → {expected}");
    let (spectral, error) = mean_and_error(&film_of(&text(true)));
    for c in 0..3 {
        let want = f64::from(expected[c]);
        assert!(
            (spectral[c] - want).abs() < 4.0 * error[c] + 3e-3 * want,
            "spectral: {spectral:?} ± {error:?} against {expected}"
        );
    }
}

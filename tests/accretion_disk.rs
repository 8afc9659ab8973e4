//! Frequency shifts change colour: a blackbody lamp deep in a hole's well is seen as the
//! blackbody at `g T`, and a disk's gas coming towards the camera is bluer and brighter than the
//! gas going away, unless the teaching toggles switch the Doppler shift off.

#![allow(clippy::unwrap_used)] // A panic is a failed test.

use render::emission::BlackbodyLight;
use render::film::Film;
use render::renderer::render;
use std::sync::atomic::AtomicBool;

fn film_of(text: &str) -> Film {
    let scene = scene::parse(text, "disk.toml", std::path::Path::new(".")).unwrap();
    render(&scene, &AtomicBool::new(false), &|_, _| {}).0
}

/// A static lamp at radius `r_source` of a Schwarzschild hole (M = 1), a small disk facing a
/// static camera at radius 30 on the same radial line, whose view it fills.
fn lamp_scene(r_source: f64, temperature: f64) -> String {
    format!(
        "[spacetime]\ntype = \"schwarzschild\"\nmass = 1\n\
         [camera]\nposition = [0, 0, 30]\nlook_at = [0, 0, 0]\nfov = 0.1\n\
         [render]\nwidth = 8\nheight = 8\nspp = 4\nmax_depth = 1\n\
         [[objects]]\nshape = {{ type = \"disk\", center = [0, 0, {r_source}], normal = [0, 0, 1], radius = 0.05 }}\n\
         material = {{ type = \"diffuse\", reflectance = 0 }}\n\
         emission = {{ temperature = {temperature}, luminance = 1 }}\n"
    )
}

#[test]
fn a_lamp_deep_in_the_well_is_seen_as_the_blackbody_at_the_shifted_temperature() {
    // ν_camera / ν_lamp = √(A(r_lamp) / A(r_camera)), A = 1 − 2M/r: the lamp is the blackbody at
    // g T, its Wien peak moved to λ_max / g. The lamp's points lie within 3·10⁻⁴ M of r_lamp.
    let a = |r: f64| 1.0 - 2.0 / r;
    for r_source in [2.5, 4.0, 10.0] {
        let temperature = 6500.0;
        let film = film_of(&lamp_scene(r_source, temperature));
        let g = (a(r_source) / a(30.0)).sqrt();
        let expected = BlackbodyLight::new(temperature, 1.0).unwrap().seen(g);
        for (x, y) in [(3, 3), (4, 4), (2, 5)] {
            let seen = film.pixel_f64(x, y);
            for (channel, want) in seen.iter().zip(expected.to_array()) {
                let want = f64::from(want);
                assert!((channel / want - 1.0).abs() < 2e-3, "r = {r_source}: {seen:?} against {expected}");
            }
        }
        // Redder than at rest: blue over red falls.
        let rest = BlackbodyLight::new(temperature, 1.0).unwrap().seen(1.0);
        assert!(expected.z / expected.x < rest.z / rest.x);
    }
}

#[test]
fn the_wien_peak_of_the_spectral_channels_moves_by_the_gravitational_ratio() {
    // A 12 000 K lamp (Wien peak b/T = 241.5 nm) at r = 2.5, 4 and 10 M seen from 30 M through
    // spectral channels 1 nm apart: the peak of the spectrum the camera receives, located by the
    // parabola through the largest channel and its neighbours, is at b / (g T) with
    // g = √(A(r_lamp)/A(r_camera)), to 3e-5: measured 1.0e-6, 5.8e-6 and 8.2e-6, the limit being
    // the channels' single precision over the parabola's small second difference.
    use render::spectrum::WIEN_DISPLACEMENT;
    let a = |r: f64| 1.0 - 2.0 / r;
    let temperature = 12_000.0;
    for r_source in [2.5, 4.0, 10.0] {
        let text = lamp_scene(r_source, temperature)
            .replace("[render]\n", "[render]\nspectrum = { min = 150, max = 700, count = 551 }\n");
        let scene = scene::parse(&text, "wien.toml", std::path::Path::new(".")).unwrap();
        let layer = render::renderer::data_layer(&scene, &render::renderer::propagator(&scene));
        let n = layer.wavelengths.len();
        let centre = 3 * 8 + 4;
        let s: Vec<f64> = layer.spectra[centre * n..(centre + 1) * n].iter().map(|v| f64::from(*v)).collect();
        let k = (1..n - 1).max_by(|&i, &j| s[i].total_cmp(&s[j])).unwrap();
        let offset = 0.5 * (s[k - 1] - s[k + 1]) / (s[k - 1] - 2.0 * s[k] + s[k + 1]);
        let peak = layer.wavelengths[k] + offset * (layer.wavelengths[1] - layer.wavelengths[0]);
        let g = (a(r_source) / a(30.0)).sqrt();
        let expected = WIEN_DISPLACEMENT / temperature * 1e9 / g;
        assert!((peak / expected - 1.0).abs() < 3e-5, "r = {r_source}: peak at {peak} nm, b/(gT) = {expected} nm");
    }
}

/// The accretion disk about a Kerr hole (a = 0.9 M) seen from 100 M at 80° from its axis, with
/// the toggles `shifts`, on a black sky.
fn disk_scene(shifts: &str) -> String {
    format!(
        "[spacetime]\ntype = \"kerr\"\nmass = 1\nspin = 0.9\naxis = [0, 1, 0]\n\
         [camera]\nposition = [0, 17.365, 98.481]\nlook_at = [0, 0, 0]\nfov = 28\n\
         [render]\nwidth = 48\nheight = 48\nspp = 1\nmax_depth = 1\n{shifts}\n\
         [accretion_disk]\nouter_radius = 20\ntemperature = 9000\n"
    )
}

/// Blue over red and the luminance, summed over the left and the right half of the film.
fn halves(film: &Film) -> [(f64, f64); 2] {
    let (w, h) = (film.width(), film.height());
    let mut sums = [[0.0f64; 3]; 2];
    for y in 0..h {
        for x in 0..w {
            let side = usize::from(x >= w / 2);
            let p = film.pixel_f64(x, y);
            for c in 0..3 {
                sums[side][c] += p[c];
            }
        }
    }
    sums.map(|s| (s[2] / s[0], 0.2126 * s[0] + 0.7152 * s[1] + 0.0722 * s[2]))
}

#[test]
fn the_side_of_the_disk_coming_towards_us_is_bluer_and_brighter() {
    // The gas turns counter-clockwise seen from the spin axis (+y): on the left (−x) it comes
    // towards the camera.
    let [(left_hue, left_y), (right_hue, right_y)] = halves(&film_of(&disk_scene("")));
    assert!(left_hue > 1.5 * right_hue, "blue/red: approaching {left_hue}, receding {right_hue}");
    assert!(left_y > 2.0 * right_y, "luminance: approaching {left_y}, receding {right_y}");
    // Without the Doppler shift and beaming only gravity shifts the light, nearly the same on
    // both sides (the sides differ only by how frame dragging bends the rays).
    let still = "doppler = false\nbeaming = false";
    let [(left_hue, left_y), (right_hue, right_y)] = halves(&film_of(&disk_scene(still)));
    assert!((left_hue / right_hue - 1.0).abs() < 0.1, "blue/red without Doppler: {left_hue}, {right_hue}");
    assert!((left_y / right_y - 1.0).abs() < 0.25, "luminance without beaming: {left_y}, {right_y}");
    // Beaming alone brightens the approaching side.
    let [(_, left_y), (_, right_y)] = halves(&film_of(&disk_scene("doppler = false")));
    assert!(left_y > 2.0 * right_y, "luminance with beaming alone: {left_y}, {right_y}");
}

#[test]
fn a_disks_texture_modulates_its_brightness_not_its_colour() {
    // Face on from its axis, a disk about a Schwarzschild hole with a checker of brightness 1 and
    // 0.25 over half turns of azimuth: the pixels on the bright half are those of the plain
    // disk, those on the other a quarter of them, in every channel.
    let disk = |texture: &str| {
        format!(
            "[spacetime]\ntype = \"schwarzschild\"\nmass = 1\n\
             [camera]\nposition = [0, 200, 0]\nlook_at = [0, 0, 0]\nup = [0, 0, 1]\nfov = 8\n\
             [render]\nwidth = 24\nheight = 24\nspp = 1\nmax_depth = 0\n\
             [accretion_disk]\nouter_radius = 12\n{texture}"
        )
    };
    let plain = film_of(&disk(""));
    let textured = film_of(&disk("texture = { type = \"checker\", a = 1, b = 0.25, uv_scale = [1, 2] }\n"));
    let (mut bright, mut dim) = (0u32, 0u32);
    for y in 0..24 {
        for x in 0..24 {
            let (p, q) = (plain.pixel_f64(x, y), textured.pixel_f64(x, y));
            if p[1] == 0.0 {
                continue;
            }
            let ratio: Vec<f64> = (0..3).map(|c| q[c] / p[c]).collect();
            if ratio.iter().all(|r| (r - 1.0).abs() < 1e-6) {
                bright += 1;
            } else if ratio.iter().all(|r| (r - 0.25).abs() < 1e-6) {
                dim += 1;
            } else {
                // Pixels whose centre lies on a border between the halves.
                assert!(ratio.iter().all(|r| (0.25..=1.0).contains(r)), "({x}, {y}): {ratio:?}");
            }
        }
    }
    assert!(bright > 100 && dim > 100 && bright.abs_diff(dim) < bright / 5, "{bright} bright, {dim} dim");
}

#[test]
fn photon_mapping_sees_the_disk_in_the_path_tracers_colours() {
    // The camera pass of SPPM meets the disk as the path tracer does, and colours its
    // blackbody at the ratio it carries from the camera (the gas's Doppler factor on top).
    let path = film_of(&disk_scene(""));
    let photon = film_of(&disk_scene("integrator = \"photon\""));
    let (mut worst, mut lit) = (0.0f64, 0);
    for y in 0..path.height() {
        for x in 0..path.width() {
            let (p, q) = (path.pixel_f64(x, y), photon.pixel_f64(x, y));
            lit += usize::from(p[1] > 0.0);
            for c in 0..3 {
                worst = worst.max((q[c] - p[c]).abs() / p[1].max(1e-3));
            }
        }
    }
    assert!(lit > 300, "{lit} pixels see the disk");
    assert!(worst < 1e-5, "largest difference {worst} of the pixel's green");
}

#[test]
fn the_redshift_channel_is_cunninghams_g_from_the_rays_constants_of_motion() {
    // For gas on a circular orbit (angular velocity Ω, u^t) and a photon of angular momentum
    // over energy λ = L_z/E reaching a static observer, g = 1/(√(−g_tt) u^t (1 − Ωλ))
    // (Cunningham 1975, with the observer's lapse): conserved quantities only, no local frames.
    // λ is taken from each pixel's ray at the camera, r from the disk_radius channel. The
    // renderer measures g at the disk in the local frames instead, from the ray's direction and
    // energy where it crossed the disk, at the default rtol 1e-7: median 1.1e-8, worst 2.2e-7.
    // (Before the 4-D tracer's crossings of flat objects were solved on the curve, the chord's
    // crossing, up to ε off, made it median 1.5e-5, worst 2.2e-4.)
    use render::film::DataChannel;
    use spacetime::disk::CircularOrbits;
    use spacetime::observer::Tetrad;
    let (inclination, distance) = (75f64.to_radians(), 60.0);
    let camera = [distance * inclination.sin(), 0.0, distance * inclination.cos()];
    let text = format!(
        "[spacetime]\ntype = \"kerr\"\nmass = 1\nspin = 0.7\naxis = [0, 0, 1]\n\
         [camera]\nposition = [{}, 0, {}]\nlook_at = [0, 0, 0]\nup = [0, 0, 1]\nfov = 30\n\
         [render]\nwidth = 40\nheight = 40\nspp = 1\nmax_depth = 0\nchannels = [\"redshift\", \"disk_radius\"]\n\
         [accretion_disk]\nouter_radius = 14\n",
        camera[0], camera[2]
    );
    let scene = scene::parse(&text, "cunningham.toml", std::path::Path::new(".")).unwrap();
    let propagator = render::renderer::propagator(&scene);
    let layer = render::renderer::data_layer(&scene, &propagator);
    assert_eq!(layer.channels, [DataChannel::Redshift, DataChannel::DiskRadius]);
    let metric = scene.spacetime.metric();
    let x = [0.0, camera[0], camera[1], camera[2]];
    let g = metric.metric(&x);
    let observer = Tetrad::local_observer(metric, &x).unwrap();
    let orbits = CircularOrbits::new(1.0, 0.7, 0.0);
    let mut errors = Vec::new();
    for (i, pixel) in layer.pixels.iter().enumerate() {
        if !pixel.disk_radius.is_finite() {
            continue;
        }
        let (px, py) = ((i % 40) as u32, (i / 40) as u32);
        let ray = scene.camera.ray([px, py], [0.0, 0.0], [40, 40], [0.5, 0.5]).unwrap();
        let p = observer.backward_momentum(&g, ray.direction.to_array(), 1.0);
        // The photon's momentum is −p: E = p_t, L_z = −(x p_y − y p_x).
        let lambda = -(x[1] * p[2] - x[2] * p[1]) / p[0];
        let orbit = orbits.orbit(pixel.disk_radius);
        let expected = 1.0 / ((-g[0][0]).sqrt() * orbit.u_t * (1.0 - orbit.omega * lambda));
        errors.push((pixel.redshift / expected - 1.0).abs());
    }
    errors.sort_by(f64::total_cmp);
    let (median, worst) = (errors[errors.len() / 2], errors[errors.len() - 1]);
    assert!(errors.len() > 150, "only {} pixels see the disk", errors.len());
    assert!(median < 1e-7 && worst < 2e-6, "relative difference: median {median}, worst {worst}");
}

#[test]
fn a_lamp_ahead_of_a_moving_camera_is_the_blackbody_at_the_doppler_shifted_temperature() {
    // Flat space: a camera moving at v towards a lamp straight ahead sees its light at
    // D = √((1 + v)/(1 − v)) times the frequency, so the 3000 K lamp is the blackbody at D·3000 K:
    // a bluer colour, not only a brighter one.
    for v in [0.2f64, 0.5] {
        let text = format!(
            "[camera]\nposition = [0, 0, 0]\nlook_at = [0, 0, -1]\nfov = 2\nvelocity = [0, 0, {}]\n\
             [render]\nwidth = 4\nheight = 4\nspp = 2\nmax_depth = 1\n\
             [[objects]]\nshape = {{ type = \"disk\", center = [0, 0, -10], normal = [0, 0, 1], radius = 3 }}\n\
             material = {{ type = \"diffuse\", reflectance = 0 }}\nemission = {{ temperature = 3000 }}\n",
            -v
        );
        let film = film_of(&text);
        let doppler = ((1.0 + v) / (1.0 - v)).sqrt();
        let expected = BlackbodyLight::new(3000.0, 1.0).unwrap().seen(doppler);
        let seen = film.pixel_f64(1, 2);
        for (channel, want) in seen.iter().zip(expected.to_array()) {
            assert!((channel / f64::from(want) - 1.0).abs() < 2e-3, "v = {v}: {seen:?} against {expected}");
        }
        let rest = BlackbodyLight::new(3000.0, 1.0).unwrap().seen(1.0);
        assert!(expected.z / expected.x > 1.5 * rest.z / rest.x, "bluer");
        // Without the Doppler toggle the lamp keeps its colour and only brightens, as D⁴.
        let film = film_of(&text.replace("[render]\n", "[render]\ndoppler = false\n"));
        let seen = film.pixel_f64(1, 2);
        for (channel, want) in seen.iter().zip(rest.to_array()) {
            let want = f64::from(want) * doppler.powi(4);
            assert!((channel / want - 1.0).abs() < 2e-3, "v = {v}, no Doppler: {seen:?} against {rest} × D⁴");
        }
    }
}

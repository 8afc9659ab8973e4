use super::*;
use crate::rgb::luminance;
use crate::sampling::uniform_sphere;

fn field(density: f64, radius_deg: f64, seed: u64) -> StarField {
    StarField::new(StarFieldParams {
        density,
        brightness: 1e-3,
        seed,
        star_radius_deg: radius_deg,
        background: Rgb::splat(1e-4),
    })
    .unwrap()
}

#[test]
fn cube_cells_tile_the_sphere() {
    // The exact cell solid angles of one face sum to 4π/6.
    let f = field(3000.0, 0.05, 1);
    let n = f.n;
    let h = 2.0 / f64::from(n);
    let mut total = 0.0;
    for j in 0..n {
        for i in 0..n {
            let (x0, y0) = (-1.0 + f64::from(i) * h, -1.0 + f64::from(j) * h);
            let (x1, y1) = (x0 + h, y0 + h);
            total += corner_solid_angle(x1, y1) - corner_solid_angle(x0, y1) - corner_solid_angle(x1, y0)
                + corner_solid_angle(x0, y0);
        }
    }
    assert!((total - 4.0 * PI / 6.0).abs() < 1e-10, "{total}");
    // project / face_point round trip, and cells of directions contain them.
    let mut rng = Rng::new(3);
    for _ in 0..1000 {
        let d = uniform_sphere(rng.next_2d());
        let (face, x, y) = project(d);
        assert!(x.abs() <= 1.0 && y.abs() <= 1.0);
        assert!((face_point(face, x, y).normalize() - d).length() < 1e-12);
    }
}

#[test]
fn deterministic_for_a_seed() {
    let (a, b, c) = (field(500.0, 0.2, 42), field(500.0, 0.2, 42), field(500.0, 0.2, 43));
    let mut stars_a = Vec::new();
    a.for_each_star(|s| stars_a.push(*s));
    let mut stars_b = Vec::new();
    b.for_each_star(|s| stars_b.push(*s));
    assert_eq!(stars_a, stars_b);
    let mut stars_c = Vec::new();
    c.for_each_star(|s| stars_c.push(*s));
    assert_ne!(stars_a, stars_c, "another seed, another sky");
    // And lookups agree, in any order.
    for s in stars_a.iter().rev().take(50) {
        assert_eq!(a.radiance(s.dir), b.radiance(s.dir));
    }
}

#[test]
fn star_count_per_steradian_matches_density() {
    // Poisson: the count in a region of solid angle Ω has mean and variance density·Ω. 5σ tolerances.
    for (density, seed) in [(50.0, 1), (400.0, 2), (3000.0, 3)] {
        let f = field(density, 0.05, seed);
        let (mut all, mut cap, mut band) = (0.0, 0.0, 0.0);
        f.for_each_star(|s| {
            all += 1.0;
            // A cap of half-angle 60° around an oblique axis (solid angle π) and a band |z| < 0.1 (0.4π).
            if s.dir.dot(Vec3::new(1.0, 2.0, 3.0).normalize()) > 0.5 {
                cap += 1.0;
            }
            if s.dir.z.abs() < 0.1 {
                band += 1.0;
            }
        });
        for (count, omega, name) in [(all, 4.0 * PI, "sphere"), (cap, PI, "cap"), (band, 0.4 * PI, "band")] {
            let mean = density * omega;
            assert!((count - mean).abs() < 5.0 * mean.sqrt(), "density {density}, {name}: {count} vs {mean}");
        }
    }
}

#[test]
fn mean_flux_is_brightness() {
    let f = field(3000.0, 0.05, 5);
    let (mut n, mut sum, mut sum2) = (0.0, 0.0, 0.0);
    let (mut min_r, mut max_r) = (f64::INFINITY, 0.0f64);
    f.for_each_star(|s| {
        n += 1.0;
        sum += s.flux;
        sum2 += s.flux * s.flux;
        min_r = min_r.min(s.radius);
        max_r = max_r.max(s.radius);
    });
    let mean = sum / n;
    let err = ((sum2 / n - mean * mean) / n).sqrt();
    assert!((mean - 1e-3).abs() < 5.0 * err, "mean flux {mean} ± {err}");
    let r0 = 0.05f64.to_radians();
    assert!(min_r >= r0 && min_r < 1.01 * r0 && max_r <= 4.0 * r0 + 1e-15 && max_r > 2.0 * r0);
}

#[test]
fn search_covers_every_direction_within_the_largest_radius() {
    // Adversarial check of the neighbour search: pairs (d, s) at angular distance up to the largest
    // star radius, half of them pushed next to cube edges and corners; s's cell must be a candidate of d.
    for (density, radius_deg) in [(300.0, 0.25), (5000.0, 0.05), (1.0, 2.0)] {
        let f = field(density, radius_deg, 0);
        let r_max = MAX_RADIUS_FACTOR * radius_deg.to_radians();
        let mut rng = Rng::new(17);
        for k in 0..200_000 {
            let mut d = uniform_sphere(rng.next_2d());
            if k % 2 == 0 {
                // Snap one or two face coordinates to ±1 (a cube edge or corner), then jitter.
                let (face, mut x, mut y) = project(d);
                x = if rng.next_f64() < 0.5 { x.signum() } else { x };
                y = if x.abs() == 1.0 && rng.next_f64() < 0.5 { y } else { y.signum() };
                let jitter = 2.0 * r_max * (rng.next_f64() - 0.5);
                d = face_point(face, x + jitter, y - jitter).normalize();
            }
            let frame = crate::geometry::Frame::from_normal(d);
            let (a, phi) = (r_max * rng.next_f64().sqrt(), 2.0 * PI * rng.next_f64());
            let s = frame.to_world(Vec3::new(a.sin() * phi.cos(), a.sin() * phi.sin(), a.cos()));
            let (face, x, y) = project(s);
            let target = f.cell_at(face, x, y);
            let (cells, count) = f.candidate_cells(d);
            assert!(cells[..count].contains(&target), "radius {radius_deg}°: {s} not searched from {d}");
        }
    }
}

#[test]
fn every_disc_is_found_including_across_cube_edges() {
    // Big stars, many near cube edges and corners: each star's radiance must be seen at its centre and
    // near its rim in eight directions (other stars may add to it, never hide it).
    for seed in 0..3 {
        let f = field(300.0, 0.25, seed);
        let background = f.params().background;
        let mut checked = 0;
        f.for_each_star(|s| {
            let own = s.radiance();
            let frame = crate::geometry::Frame::from_normal(s.dir);
            for k in 0..9 {
                let d = if k == 0 {
                    s.dir
                } else {
                    let phi = f64::from(k) * PI / 4.0;
                    let a = 0.97 * s.radius;
                    frame.to_world(Vec3::new(a.sin() * phi.cos(), a.sin() * phi.sin(), a.cos()))
                };
                let seen = f.radiance(d) - background;
                assert!((seen - own).min_element() > -1e-3 * own.max_element(), "star at {} missed", s.dir);
                checked += 1;
            }
        });
        assert!(checked > 1000);
    }
}

#[test]
fn flux_is_radiance_times_solid_angle() {
    // Integrate the sky's radiance over the sphere by Monte Carlo: ∫ (L − background) dω = Σ flux.
    let f = field(20.0, 1.0, 9);
    let mut total_flux = Rgb::ZERO;
    f.for_each_star(|s| total_flux += s.radiance() * s.solid_angle() as f32);
    let n = 300_000;
    let mut rng = Rng::new(11);
    let (mut sum, mut sum2) = (0.0f64, 0.0f64);
    for _ in 0..n {
        let l = f.radiance(uniform_sphere(rng.next_2d())) - f.params().background;
        let v = f64::from(luminance(l)) * 4.0 * PI;
        sum += v;
        sum2 += v * v;
    }
    let mean = sum / f64::from(n);
    let err = ((sum2 / f64::from(n) - mean * mean) / f64::from(n)).sqrt();
    let expected = f64::from(luminance(total_flux));
    assert!((mean - expected).abs() < 5.0 * err, "{mean} ± {err} vs {expected}");
    // A star's flux is its luminous flux, so the sky's is the sum of fluxes ≈ density·4π·brightness.
    let mut plain = 0.0;
    f.for_each_star(|s| plain += s.flux);
    assert!((expected - plain).abs() < 1e-4 * plain);
}

#[test]
fn stars_are_blackbodies_of_the_naked_eye_classes() {
    // Temperatures: each class's share within binomial noise, within its range.
    let n = 200_000;
    let mut rng = Rng::new(5);
    let mut counts = [0usize; CLASSES.len()];
    for _ in 0..n {
        let t = temperature(rng.next_f64());
        let k = CLASSES.iter().position(|&(_, lo, hi)| (lo..=hi).contains(&t)).unwrap();
        counts[k] += 1;
    }
    for ((share, ..), count) in CLASSES.iter().zip(counts) {
        let sigma = (share * (1.0 - share) / n as f64).sqrt();
        assert!((count as f64 / n as f64 - share).abs() < 5.0 * sigma, "{counts:?}");
    }
    let total: f64 = CLASSES.iter().map(|c| c.0).sum();
    assert!((total - 1.0).abs() < 1e-12);
    // A star's luminance is its flux over its disc; cool ones are red, hot ones blue; seen at
    // frequency ratio g it is the blackbody at g T, g⁴ as bright.
    let star = |temperature| Star { dir: Vec3::Z, flux: 1e-4, radius: 1e-3, temperature };
    let (cool, hot) = (star(3000.0).radiance(), star(20_000.0).radiance());
    for s in [star(3000.0), star(20_000.0)] {
        let y = f64::from(luminance(s.radiance()));
        assert!((y * s.solid_angle() / s.flux - 1.0).abs() < 1e-3, "{y}");
    }
    assert!(cool.x > cool.z && hot.z > hot.x, "{cool} {hot}");
    let g = 1.6;
    let shifted: Rgb = star(3000.0).seen((g, g), &());
    let hotter = Star { temperature: 3000.0 * g, ..star(3000.0) };
    // The hotter star of the same luminance, brightened as the blackbody's luminance grows.
    let y = |t: f64| BlackbodyColours::get().luminance(t);
    let expected = hotter.radiance() * (y(g * 3000.0) / y(3000.0)) as f32;
    assert!(((shifted - expected) / expected).abs().max_element() < 1e-4, "{shifted} vs {expected}");
}

#[test]
fn bad_parameters_are_errors() {
    let ok = StarFieldParams::default();
    assert!(StarField::new(ok).is_ok());
    for bad in [
        StarFieldParams { density: -1.0, ..ok },
        StarFieldParams { density: f64::NAN, ..ok },
        StarFieldParams { brightness: f64::INFINITY, ..ok },
        StarFieldParams { star_radius_deg: 0.0, ..ok },
        StarFieldParams { star_radius_deg: 5.0, ..ok },
        StarFieldParams { density: 1e7, star_radius_deg: 2.0, ..ok },
    ] {
        assert!(StarField::new(bad).is_err(), "{bad:?}");
    }
}

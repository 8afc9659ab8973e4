//! Tests of the Mino-time tracer against the 4-D tracer, of its constants of motion and of its
//! series.

use super::motion::from_chart;
use super::tracer::MinoTracer;
use crate::geodesic::HamiltonianTracer;
use crate::geodesic::{Fate, RayStep, RayTracer, State, Stepping, TraceSettings, Visit};
use crate::metric::Metric;
use crate::metric::{KerrNewman, KerrSchild};
use crate::observer::Tetrad;
use crate::tensor::{norm3, sub3};

/// The backward ray that a camera at rest (the local observer) at `at` sees along `dir`.
fn camera_ray(hole: &KerrNewman, at: [f64; 3], dir: [f64; 3]) -> State {
    let x = [0.0, at[0], at[1], at[2]];
    let frame = Tetrad::local_observer(hole, &x).expect("a camera outside the horizon");
    State { x, p: frame.backward_momentum(&hole.metric(&x), crate::tensor::normalize3(&dir), 1.0) }
}

fn settings(rtol: f64, escape_radius: f64) -> TraceSettings {
    TraceSettings {
        stepping: Stepping::Adaptive { rtol },
        escape_radius,
        max_step_fraction: 0.5,
        max_steps: 100_000,
        check_every_step: true,
    }
}

/// Without `check_every_step` the trace is the same, and its `|H|` is the larger of the
/// start's and the end's; with it, the largest over the step ends, which the steps between
/// can raise (a ray that swings round the hole at a loose tolerance).
#[test]
fn the_hamiltonian_is_checked_at_every_step_only_when_asked() {
    let hole = KerrNewman::new(1.0, 0.9, 0.0);
    let start = camera_ray(&hole, [-40.0, 0.0, 3.0], [1.0, 0.13, -0.05]);
    let each = MinoTracer::new(&hole, start, settings(1e-5, 1e3)).run(|_| Visit::Continue);
    let ends_only = MinoTracer::new(&hole, start, TraceSettings { check_every_step: false, ..settings(1e-5, 1e3) })
        .run(|_| Visit::Continue);
    assert_eq!((each.fate, each.steps, each.end), (ends_only.fate, ends_only.steps, ends_only.end));
    let h = |s: &State| hole.hamiltonian(&s.x, &s.p).abs();
    let ends = h(&start).max(h(&ends_only.end));
    assert!((ends_only.max_abs_hamiltonian - ends).abs() <= 1e-2 * ends, "{} vs {ends}", ends_only.max_abs_hamiltonian);
    assert!(each.max_abs_hamiltonian > 1.5 * ends, "{} vs {ends}", each.max_abs_hamiltonian);
}

/// What a scene sees of a ray: its crossings of the equatorial plane outside the horizon
/// (point and momentum, found on the dense output by bisection) and its fate.
struct Seen {
    crossings: Vec<State>,
    fate: Fate,
}

/// Crossings inside the horizon are left out: a ray is captured at the end of the first step
/// that ends inside, and how far inside that step reaches is the stepper's own (a Taylor
/// step of the Mino tracer may cross the plane there where the 4-D tracer's shorter last
/// step stops before it); nothing outside sees them.
fn seen<T: RayTracer>(hole: &KerrNewman, tracer: T) -> Seen {
    let mut crossings = Vec::new();
    let trace = tracer.run(|step| {
        let z = |theta: f64| step.position_at(theta)[3];
        let (mut lo, mut hi) = (0.0, 1.0);
        if z(lo) * z(hi) < 0.0 {
            for _ in 0..60 {
                let mid = 0.5 * (lo + hi);
                if z(mid) * z(lo) > 0.0 {
                    lo = mid;
                } else {
                    hi = mid;
                }
            }
            let crossing = step.at(0.5 * (lo + hi));
            if hole.radial_coordinate(&crossing.x) > hole.horizon_radius() {
                crossings.push(crossing);
            }
        }
        Visit::Continue
    });
    Seen { crossings, fate: trace.fate }
}

/// The largest differences between two tracings of a ray: of crossing points (relative to
/// the distance from the centre), of crossing momenta (relative to the energy), of escape
/// directions; `None` where the fates or the numbers of crossings differ.
fn differences(a: &Seen, b: &Seen) -> Option<[f64; 3]> {
    if a.crossings.len() != b.crossings.len() {
        return None;
    }
    let mut d = [0.0f64; 3];
    for (s, t) in a.crossings.iter().zip(&b.crossings) {
        let (xs, xt) = (crate::tensor::spatial(&s.x), crate::tensor::spatial(&t.x));
        d[0] = d[0].max(norm3(&sub3(&xs, &xt)) / norm3(&xt));
        let dp = (0..4).map(|i| (s.p[i] - t.p[i]).powi(2)).sum::<f64>().sqrt();
        d[1] = d[1].max(dp / t.p[0].abs());
    }
    match (a.fate, b.fate) {
        (Fate::Escaped { direction: u }, Fate::Escaped { direction: v }) => d[2] = norm3(&sub3(&u, &v)),
        (Fate::Captured, Fate::Captured) => {}
        _ => return None,
    }
    Some(d)
}

/// Rays of a camera 40 M from the hole at inclination 80°, over its field of view, and
/// rays that skim the spin axis or run through it.
fn rays(hole: &KerrNewman) -> Vec<State> {
    let m = hole.mass;
    let (si, ci) = 80f64.to_radians().sin_cos();
    let at = [40.0 * m * si, 0.0, 40.0 * m * ci];
    let mut rays = Vec::new();
    for i in -4..=4 {
        for j in -4..=4 {
            let (a, b) = (0.07 * f64::from(i), 0.07 * f64::from(j));
            // Towards the centre, offset sideways (y) and up.
            let dir = [-si + b * ci, a, -ci - b * si];
            rays.push(camera_ray(hole, at, dir));
        }
    }
    // In the plane of the axis, over the pole (L = 0), and passing about 10⁻⁶ M from it.
    for off in [0.0, 3e-8] {
        for tilt in [0.2, 0.26, 0.35] {
            rays.push(camera_ray(hole, [30.0 * m, 0.0, 0.0], [-1.0, off, tilt]));
        }
    }
    rays
}

/// Equatorial rays a relative `1e-5` inside and outside the edge of the shadow on both
/// sides (prograde and retrograde), found by bisection on the ray's fate: they wind round
/// the photon orbit before they fall in or leave.
fn near_photon_orbit(hole: &KerrNewman) -> Vec<State> {
    let at = [40.0 * hole.mass, 0.0, 0.0];
    let aim = |t: f64| camera_ray(hole, at, [-1.0, t, 0.0]);
    let captured = |t: f64| {
        matches!(
            MinoTracer::new(hole, aim(t), settings(1e-11, 1e3 * hole.mass)).run(|_| Visit::Continue).fate,
            Fate::Captured
        )
    };
    let mut rays = Vec::new();
    for side in [-1.0, 1.0] {
        let (mut inside, mut outside) = (0.0, side * 0.5);
        for _ in 0..50 {
            let mid = 0.5 * (inside + outside);
            if captured(mid) {
                inside = mid;
            } else {
                outside = mid;
            }
        }
        rays.extend([aim(inside * (1.0 - 1e-5)), aim(outside * (1.0 + 1e-5))]);
    }
    rays
}

/// A ray from a camera 10⁶ M away that passes the hole and escapes to twice that distance
/// leaves in a few strides past the hole, not in steps that each double `r` (16 of them from
/// 40 M to 2 × 10⁶ M; aimed at constant `u'`, each stride ended past the pole and was halved,
/// which doubled `r` 4 times more), and along the 4-D tracer's direction (to 10⁻⁸ at
/// tolerance 10⁻¹⁰).
#[test]
fn escaping_rays_stride_to_a_far_escape_radius() {
    let hole = KerrNewman::new(1.0, 0.9, 0.0);
    let (d, inclination) = (1e6, 80f64.to_radians());
    let at = [d * inclination.sin(), 0.0, d * inclination.cos()];
    for b in [8.0, 10.0, 15.0] {
        let start = camera_ray(&hole, at, [-inclination.sin(), b / d, -inclination.cos()]);
        let mut outside = 0;
        MinoTracer::new(&hole, start, settings(1e-7, 2.0 * d)).run(|step| {
            let p = step.end_position();
            outside += usize::from(p[1] * p[1] + p[2] * p[2] + p[3] * p[3] > 1600.0);
            Visit::Continue
        });
        // The first step comes in from 10⁶ M; beyond 40 M on the way out, at most 3 (at the
        // renderer's tolerance).
        assert!(outside <= 4, "b = {b}: {outside} steps end beyond 40 M");
        let s = settings(1e-10, 2.0 * d);
        let mino = MinoTracer::new(&hole, start, s).run(|_| Visit::Continue);
        let ham = HamiltonianTracer::new(&hole, start, s).run(|_| Visit::Continue);
        let (Fate::Escaped { direction: a }, Fate::Escaped { direction: b4 }) = (mino.fate, ham.fate) else {
            panic!("b = {b}: {:?} vs {:?}", mino.fate, ham.fate);
        };
        let miss = (0..3).map(|i| (a[i] - b4[i]).abs()).fold(0.0, f64::max);
        assert!(miss < 1e-8, "b = {b}: directions differ by {miss}");
    }
}

#[test]
fn agrees_with_the_four_d_tracer() {
    for hole in [
        KerrNewman::new(1.0, 0.9, 0.0),
        KerrNewman::new(1.0, 0.998, 0.0),
        KerrNewman::new(1.0, -0.6, 0.0),
        KerrNewman::new(1.0, 0.0, 0.0),
        KerrNewman::new(0.5, 0.3, 0.25),
    ] {
        let mut worst = [0.0f64; 3];
        for (k, start) in rays(&hole).into_iter().enumerate() {
            let s = settings(1e-10, 1e4 * hole.mass);
            let mino = seen(&hole, MinoTracer::new(&hole, start, s));
            let ham = seen(&hole, HamiltonianTracer::new(&hole, start, s));
            let d = differences(&mino, &ham).unwrap_or_else(|| {
                panic!(
                    "{hole:?} ray {k}: {:?} {} vs {:?} {}",
                    mino.fate,
                    mino.crossings.len(),
                    ham.fate,
                    ham.crossings.len()
                )
            });
            for i in 0..3 {
                worst[i] = worst[i].max(d[i]);
            }
        }
        // Points to 10⁻⁶ of their distance, momenta and directions to 10⁻⁷ (worst seen with
        // Taylor steps: 3.2 × 10⁻⁸, 1.1 × 10⁻⁹, 1.4 × 10⁻⁸; with Dormand–Prince 5(4), before
        // them: 1.1 × 10⁻⁷, 1.7 × 10⁻⁹, 1.4 × 10⁻⁸).
        assert!(worst[0] < 1e-6 && worst[1] < 1e-7 && worst[2] < 1e-7, "{hole:?}: {worst:?}");
        // Rays that wind about the photon orbit magnify every error: against the 4-D tracer at
        // 10⁻¹³ (whose own error there, at a = 0.998 M, is 6 × 10⁻⁷ in direction, where at
        // 10⁻¹¹ it is 10⁻⁴ and this tracer's 1.1 × 10⁻⁶) they end alike, at the same points.
        for (k, start) in near_photon_orbit(&hole).into_iter().enumerate() {
            let (s, reference) = (settings(1e-11, 1e4 * hole.mass), settings(1e-13, 1e4 * hole.mass));
            let (mino, ham) = (
                seen(&hole, MinoTracer::new(&hole, start, s)),
                seen(&hole, HamiltonianTracer::new(&hole, start, reference)),
            );
            let d = differences(&mino, &ham)
                .unwrap_or_else(|| panic!("{hole:?} winding ray {k}: {:?} vs {:?}", mino.fate, ham.fate));
            assert!(d[0] < 3e-5 && d[2] < 3e-5, "{hole:?} winding ray {k}: {d:?}");
        }
    }
}

/// Along a ray, the chart momentum's `E = −p_t`, `L = x p_y − y p_x` and Carter's `K`
/// (recovered from the chart state as at the start) stay those of the start, the momentum
/// stays null (`|H|` below 10⁻⁹ of its squared components), and the radial equation `u'² =
/// U(u)` holds, at the end and in the middle of every step (the Taylor polynomial is the
/// dense output the renderer places points with): nothing is re-projected, and the drift
/// stays at the tolerance's level.
#[test]
fn constants_of_motion_are_conserved() {
    for hole in [KerrNewman::new(1.0, 0.9, 0.0), KerrNewman::new(1.0, -0.998, 0.0), KerrNewman::new(0.5, 0.3, 0.25)] {
        for start in rays(&hole).into_iter().chain(near_photon_orbit(&hole)) {
            let (c0, _) = from_chart(&hole, &start);
            let mut tracer = MinoTracer::new(&hole, start, settings(1e-10, 1e3 * hole.mass));
            let scale = c0.carter_k.max(c0.energy * c0.energy);
            let mut worst = [0.0f64; 4];
            while tracer.ended().is_none() {
                let Ok(step) = tracer.step() else { panic!("{hole:?}: the ray failed") };
                for theta in [0.5, 1.0] {
                    let (c, y) = from_chart(&hole, &step.at(theta));
                    let big_a = c.energy + c.b * y[0] * y[0];
                    let u_of = big_a * big_a - (1.0 + y[0] * (c.c * y[0] - 2.0 * c.mass)) * c.carter_k * y[0] * y[0];
                    let drift = [
                        (c.energy - c0.energy).abs() / c0.energy.abs(),
                        (c.axial - c0.axial).abs() / scale.sqrt(),
                        (c.carter_k - c0.carter_k).abs() / scale,
                        (y[1] * y[1] - u_of).abs() / (c0.energy * c0.energy),
                    ];
                    for i in 0..4 {
                        worst[i] = worst[i].max(drift[i]);
                    }
                    let (p, h) = c0.momentum(&step.dense.head::<8>(theta));
                    let p2: f64 = p.iter().map(|c| c * c).sum();
                    assert!(h.abs() < 1e-9 * p2, "{hole:?}: not null at {theta}: H = {h}, |p|² = {p2}");
                }
                assert_eq!(step.dense.head::<8>(1.0), tracer.y, "the polynomial ends at the state");
            }
            assert!(worst.iter().all(|&d| d < 1e-7), "{hole:?}: drifts of E, L, K, U: {worst:?}");
        }
    }
}

/// The series' first coefficients are the right-hand side and half its derivative along
/// the flow (by central differences), for rays of both formulas of `G`: falling in
/// backwards (`A u' < 0`, across the past horizon) and on the way out.
#[test]
fn the_series_is_the_solutions() {
    let hole = KerrNewman::new(1.0, 0.9, 0.2);
    let mut branches = [false; 2];
    for start in rays(&hole) {
        let (c, y0) = from_chart(&hole, &start);
        let mut tracer = MinoTracer::new(&hole, start, settings(1e-8, 1e3));
        let mut y = y0;
        while tracer.ended().is_none() {
            branches[usize::from((c.energy + c.b * y[0] * y[0]) * y[1] < 0.0)] = true;
            let series = c.series(&y);
            let f = c.rhs(&y);
            let eps = 1e-6 / f.iter().map(|v| v.abs()).fold(0.0, f64::max);
            let shifted = |s: f64| c.rhs(&std::array::from_fn(|i| y[i] + s * eps * f[i]));
            let (ahead, behind) = (shifted(1.0), shifted(-1.0));
            for i in 0..8 {
                let size = f.iter().map(|v| v.abs()).fold(y[i].abs(), f64::max);
                assert!((series[i][1] - f[i]).abs() <= 1e-14 * size, "{i}: {} vs {}", series[i][1], f[i]);
                let second = 0.25 * (ahead[i] - behind[i]) / eps;
                assert!((series[i][2] - second).abs() <= 1e-6 * size, "{i}: {} vs {second}", series[i][2]);
            }
            if tracer.step().is_err() {
                break;
            }
            y = tracer.y;
        }
    }
    assert_eq!(branches, [true, true], "both formulas of G");
}

/// RK4 (the poster's fixed steps) still traces the rays, through its Hermite interpolant:
/// with a small step its escapes and crossings are the Taylor steps'.
#[test]
fn rk4_steps_trace_the_same_rays() {
    let hole = KerrNewman::new(1.0, 0.9, 0.0);
    for start in rays(&hole).into_iter().step_by(7) {
        let rk4 = TraceSettings { stepping: Stepping::Rk4 { step: 0.05 }, ..settings(1e-10, 1e3) };
        let (taylor, fixed) = (
            seen(&hole, MinoTracer::new(&hole, start, settings(1e-10, 1e3))),
            seen(&hole, MinoTracer::new(&hole, start, rk4)),
        );
        let d = differences(&fixed, &taylor).unwrap_or_else(|| panic!("{:?} vs {:?}", fixed.fate, taylor.fate));
        assert!(d.iter().all(|&d| d < 1e-4), "{d:?}");
    }
}

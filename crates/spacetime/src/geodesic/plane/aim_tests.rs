//! Tests of [`plane_aim`]: against the 4-D aim, Schwarzschild's connector, flat space's inverse
//! square, and rays traced through a throat.

use super::{plane_aim, PlaneAim, PlaneAimSettings, PlaneMetric, Side, Way};
use crate::geodesic::aim::{aim, AimSettings};
use crate::geodesic::{Stepping, TraceSettings};
use crate::metric::{Ellis, Region, ReissnerNordstrom, Schwarzschild};
use crate::observer::Tetrad;
use crate::tensor::{dot3, norm3, normalize3};

const SETTINGS: PlaneAimSettings = PlaneAimSettings { rtol: 1e-9, tolerance: 1e-9 };

/// Start and target pairs on both sides of a centre of unit length scale, near and far, and
/// nearly opposite each other, where rays between them bend strongly.
fn pairs() -> Vec<([f64; 3], [f64; 3])> {
    let mut pairs = Vec::new();
    for k in 0..6 {
        let t = f64::from(k);
        pairs.push(([2.5 + 0.3 * t, 0.1 * t, 0.3], [-2.6 - 0.2 * t, 0.6 - 0.08 * t, -0.2]));
    }
    for k in 0..12 {
        let t = f64::from(k);
        let x = [4.0 + 0.5 * t, 1.0 - 0.3 * t, 0.4 * (t * 0.7).sin()];
        let y = [-3.0 + 0.6 * (t * 1.3).cos(), 3.5 + 0.2 * t, -1.0 + 0.25 * t];
        pairs.push((x, y));
    }
    pairs
}

/// The unit world tangent at the start of `found`: the static frame's radial component
/// stretched by `1/κ` (world radial length per proper length).
fn start_tangent<M: PlaneMetric>(metric: &M, x: [f64; 3], found: &PlaneAim) -> [f64; 3] {
    let radial = normalize3(&x);
    let kappa = metric.radial_scale(metric.u_of_world_radius(norm3(&x)).unwrap());
    let n_r = dot3(&found.start, &radial);
    normalize3(&std::array::from_fn(|i| found.start[i] + (kappa - 1.0) * n_r * radial[i]))
}

/// The aim agrees with the 4-D aim (a different method on a different tracer, in the
/// chart): start and end tangents to 1e-6, density to 1e-5.
fn agrees_with_the_four_d_aim<M: PlaneMetric>(metric: &M) {
    let trace = TraceSettings {
        stepping: Stepping::Adaptive { rtol: 1e-10 },
        escape_radius: 100.0,
        max_step_fraction: 0.5,
        max_steps: 100_000,
        check_every_step: true,
    };
    let four_d = AimSettings { trace, tolerance: 1e-9, max_shots: 40 };
    let mut compared = 0;
    for (x, y) in pairs() {
        let Some(found) = plane_aim(metric, x, (y, Side::Same), Way::Short, &SETTINGS) else { continue };
        let chart = metric.world_to_chart(Region::Upper, x, 0.0).unwrap();
        let frame = Tetrad::local_observer(metric, &chart).unwrap();
        let guess = std::array::from_fn(|i| y[i] - x[i]);
        let Some(reference) = aim(metric, chart, &frame, y, guess, &four_d) else { continue };
        compared += 1;
        let turn = norm3(&std::array::from_fn(|i| start_tangent(metric, x, &found)[i] - reference.start_tangent[i]));
        assert!(turn < 1e-6, "{x:?} → {y:?}: start tangent off by {turn:e}");
        let density = found.solid_angle_per_area / reference.solid_angle_per_area - 1.0;
        assert!(density.abs() < 1e-5, "{x:?} → {y:?}: density off by {density:e}");
        let tangent = norm3(&std::array::from_fn(|i| found.end_tangent[i] - reference.end_tangent[i]));
        assert!(tangent < 1e-6, "{x:?} → {y:?}: end tangent off by {tangent:e}");
        assert!(found.shots <= 12, "{x:?} → {y:?}: {} shots", found.shots);
    }
    assert!(compared >= 10, "only {compared} pairs compared");
}

#[test]
fn agrees_with_the_four_d_aim_around_a_wormhole() {
    agrees_with_the_four_d_aim(&Ellis::new(1.2));
}

#[test]
fn agrees_with_the_four_d_aim_around_a_charged_hole() {
    agrees_with_the_four_d_aim(&ReissnerNordstrom::new(0.5, 0.4));
}

#[test]
fn agrees_with_the_four_d_aim_around_a_schwarzschild_hole() {
    agrees_with_the_four_d_aim(&Schwarzschild::new(0.5));
}

#[test]
fn density_is_the_inverse_square_far_from_a_light_centre() {
    let metric = Schwarzschild::new(1e-9);
    for (x, y) in pairs() {
        let found = plane_aim(&metric, x, (y, Side::Same), Way::Short, &SETTINGS).unwrap();
        let chord: [f64; 3] = std::array::from_fn(|i| y[i] - x[i]);
        let d2 = dot3(&chord, &chord);
        assert!((found.solid_angle_per_area * d2 - 1.0).abs() < 1e-6, "{}", found.solid_angle_per_area * d2);
        let along = normalize3(&chord);
        assert!(norm3(&std::array::from_fn(|i| found.start[i] - along[i])) < 1e-6);
        assert!(norm3(&std::array::from_fn(|i| found.end[i] - along[i])) < 1e-6);
    }
}

/// Both ways round a Schwarzschild hole, the aim finds the rays Schwarzschild's own
/// connector finds (Binet's equation by Taylor series, Newton on the start slope): start and
/// end directions to 1e-6, density to 1e-5, sweeps that add up to 2π.
#[test]
fn both_ways_agree_with_the_schwarzschild_connector() {
    let hole = Schwarzschild::new(0.5);
    let connector = crate::metric::schwarzschild::connect::Connector::new(hole);
    let close = |a: [f64; 3], b: [f64; 3]| norm3(&std::array::from_fn(|i| a[i] - b[i]));
    let mut compared = [0; 2];
    for (x, y) in pairs() {
        for (k, way) in Way::BOTH.into_iter().enumerate() {
            let (Some(found), Some(own)) =
                (plane_aim(&hole, x, (y, Side::Same), way, &SETTINGS), connector.connect(x, y, way))
            else {
                continue;
            };
            compared[k] += 1;
            assert!(close(found.start, own.start) < 1e-6, "{way:?} {x:?} → {y:?}: start {:?}", found.start);
            assert!(close(found.end, own.end) < 1e-6, "{way:?} {x:?} → {y:?}: end {:?}", found.end);
            let density = found.solid_angle_per_area / own.solid_angle_per_area - 1.0;
            assert!(density.abs() < 1e-5, "{way:?} {x:?} → {y:?}: density off by {density:e}");
        }
    }
    assert!(compared.iter().all(|&n| n >= 15), "compared {compared:?} of {} pairs", pairs().len());
}

/// The long way round a wormhole's throat passes close to it and lands on the target, its
/// direction leaving on the far side of the centre from the short way's.
#[test]
fn the_long_way_round_a_throat_reaches_the_target() {
    let throat = Ellis::new(1.2);
    let mut found_any = 0;
    for (x, y) in pairs() {
        let (Some(short), Some(long)) = (
            plane_aim(&throat, x, (y, Side::Same), Way::Short, &SETTINGS),
            plane_aim(&throat, x, (y, Side::Same), Way::Long, &SETTINGS),
        ) else {
            continue;
        };
        found_any += 1;
        let towards = normalize3(&std::array::from_fn(|i| y[i] - x[i]));
        let across = |d: [f64; 3]| {
            let n = crate::tensor::cross3(&x, &y);
            dot3(&crate::tensor::cross3(&x, &d), &n)
        };
        assert!(across(short.start) > 0.0 && across(long.start) < 0.0, "{x:?} → {y:?}: same side");
        assert!(dot3(&long.start, &towards) < dot3(&short.start, &towards));
        assert!(long.solid_angle_per_area < short.solid_angle_per_area, "a long way's image is smaller");
    }
    assert!(found_any >= 15, "only {found_any} pairs aimed both ways");
}

/// Aims through the throat, each way round: the ray leaving along the aimed direction,
/// traced by the in-plane tracer, passes the target in the other region, arriving along the
/// aimed end direction; the density matches finite differences of neighbouring aims (the
/// solid angle their start directions span per area their targets span across the beam).
fn aims_through_the_throat<M: PlaneMetric>(metric: &M) {
    // A long way through a throat sweeps far: its shots' rounding noise is above 1e-9.
    const SETTINGS: PlaneAimSettings = PlaneAimSettings { rtol: 1e-10, tolerance: 1e-8 };
    use crate::geodesic::plane::{trace_plane, PlaneStart};
    use crate::geodesic::Visit;
    let trace = TraceSettings {
        stepping: Stepping::Adaptive { rtol: 1e-11 },
        escape_radius: 1e3,
        max_step_fraction: 1.0,
        max_steps: 100_000,
        check_every_step: true,
    };
    let mut compared = [0; 2];
    for (x, y) in pairs() {
        for (k, way) in Way::BOTH.into_iter().enumerate() {
            let Some(found) = plane_aim(metric, x, (y, Side::Other), way, &SETTINGS) else { continue };
            compared[k] += 1;
            let start = PlaneStart::from_observer(metric, Region::Upper, x, found.start).unwrap();
            let mut nearest = (f64::INFINITY, [0.0; 3]);
            trace_plane(metric, start, &trace, |step| {
                if step.region() == Region::Lower {
                    let miss = |theta: f64| {
                        let at = step.position(metric, theta);
                        norm3(&std::array::from_fn(|j| at[j] - y[j]))
                    };
                    // The nearest of 64 knots, then the nearest point between its neighbours.
                    let knot = (0..=64).map(|i| f64::from(i) / 64.0).min_by(|a, b| miss(*a).total_cmp(&miss(*b)));
                    let (mut a, mut b) =
                        knot.map_or((0.0, 0.0), |t| ((t - 1.0 / 64.0).max(0.0), (t + 1.0 / 64.0).min(1.0)));
                    for _ in 0..100 {
                        let (p, q) = (a + (b - a) / 3.0, b - (b - a) / 3.0);
                        (a, b) = if miss(p) < miss(q) { (a, q) } else { (p, b) };
                    }
                    if miss(a) < nearest.0 {
                        nearest = (miss(a), step.point(metric, a).direction);
                    }
                }
                Visit::Continue
            });
            let (miss, direction) = nearest;
            // The aim's tolerance is 1e-9, the tracer's 1e-8 relative.
            assert!(miss < 1e-6, "{way:?} {x:?} → {y:?}: passes the target {miss:e} away");
            let turn = norm3(&std::array::from_fn(|i| direction[i] - found.end[i]));
            assert!(turn < 1e-6, "{way:?} {x:?} → {y:?}: arrives along {direction:?}, aimed {:?}", found.end);

            let t = found.end_tangent;
            let e1 = normalize3(&crate::tensor::cross3(&t, &[0.3, 0.5, 0.8]));
            let e2 = crate::tensor::cross3(&t, &e1);
            let delta = 1e-4;
            let beside = |e: [f64; 3], side: f64| {
                let target = std::array::from_fn(|i| y[i] + side * delta * e[i]);
                match plane_aim(metric, x, (target, Side::Other), way, &SETTINGS) {
                    Some(a) => a.start,
                    None => panic!("{way:?} {x:?} → {target:?} not aimed at ({:?})", found.shots),
                }
            };
            // Central differences: the span of start directions per 2δ across the beam.
            let span = |e: [f64; 3]| {
                let (ahead, behind) = (beside(e, 1.0), beside(e, -1.0));
                std::array::from_fn(|i| ahead[i] - behind[i])
            };
            let solid_angle = norm3(&crate::tensor::cross3(&span(e1), &span(e2)));
            let density = solid_angle / (4.0 * delta * delta) / found.solid_angle_per_area - 1.0;
            assert!(density.abs() < 1e-3, "{way:?} {x:?} → {y:?}: density off by {density:e}");
        }
    }
    assert!(compared.iter().all(|&n| n >= 12), "aimed {compared:?} of {} pairs", pairs().len());
}

#[test]
fn aims_through_the_throat_of_an_ellis_wormhole() {
    aims_through_the_throat(&Ellis::new(1.2));
}

#[test]
fn aims_through_the_throat_of_the_interstellar_wormhole() {
    aims_through_the_throat(&crate::metric::MorrisThorne::new(crate::metric::Dneg::new(1.0, 0.5, 0.2)));
}

#[test]
fn points_in_line_with_the_centre_have_no_plane() {
    for way in Way::BOTH {
        assert_eq!(plane_aim(&Ellis::new(1.0), [3.0, 0.0, 0.0], ([-5.0, 0.0, 0.0], Side::Same), way, &SETTINGS), None);
        assert_eq!(plane_aim(&Ellis::new(1.0), [3.0, 0.0, 0.0], ([5.0, 0.0, 0.0], Side::Other), way, &SETTINGS), None);
    }
}

//! The shared conformance suite: every built-in spacetime, at points near and far, in each of
//! its regions, passes [`check_metric`] and [`check_capabilities`]. [`examples`] lists the
//! spacetimes; its match has no wildcard, so a new metric does not compile until it is here.

#![allow(clippy::unwrap_used)] // A panic is a failed test.

use spacetime::metric::conformance::{check_capabilities, check_metric, chosen_tracer};
use spacetime::metric::expression::{Expression, Names};
use spacetime::metric::{Coordinates, NoRest, UserMetric, WrittenMetric};
use spacetime::{Region, Spacetime};

/// A metric written as expressions of `coordinates` with parameters `M = 1`, `Q = 0.6`, `a = 0.7`, `w = 0.05` (no example point lies near their horizons, where finite differences fail).
fn written(coordinates: Coordinates, components: &[(usize, usize, &str)]) -> Spacetime {
    let names = Names { variables: coordinates.names(), constants: &[("M", 1.0), ("Q", 0.6), ("a", 0.7), ("w", 0.05)] };
    let compiled = components.iter().map(|(a, b, text)| (*a, *b, Expression::compile(text, names).unwrap())).collect();
    Spacetime::Written(UserMetric(WrittenMetric::new(coordinates, compiled, None, 1.0).unwrap()))
}

/// One or more parameter sets of every spacetime.
fn examples() -> Vec<Spacetime> {
    let all = [
        Spacetime::Minkowski(spacetime::Minkowski),
        Spacetime::schwarzschild(1.0).unwrap(),
        Spacetime::schwarzschild(0.0).unwrap(),
        Spacetime::kerr(1.0, 0.9).unwrap(),
        Spacetime::kerr(1.0, -0.5).unwrap(),
        Spacetime::ellis(1.0).unwrap(),
        Spacetime::reissner_nordstrom(1.0, 0.8).unwrap(),
        Spacetime::reissner_nordstrom(1.0, 1.0).unwrap(),
        Spacetime::kerr_newman(1.0, 0.6, 0.5).unwrap(),
        Spacetime::kerr_newman(1.0, -0.8, 0.6).unwrap(),
        // Interstellar's proportions (a = 0.005 ρ, 𝒲 = 0.05 ρ), a long one, and one without a cylinder.
        Spacetime::wormhole(1.0, 0.01, 0.05).unwrap(),
        Spacetime::wormhole(1.0, 1.0, 1.0).unwrap(),
        Spacetime::wormhole(1.0, 0.0, 0.5).unwrap(),
        written(
            Coordinates::Spherical,
            &[
                (0, 0, "-(1 - 2*M/r + Q^2/r^2)"),
                (1, 1, "1/(1 - 2*M/r + Q^2/r^2)"),
                (2, 2, "r^2"),
                (3, 3, "r^2*sin(theta)^2"),
            ],
        ),
        // Kerr in Boyer–Lindquist coordinates (a = 0.7).
        written(
            Coordinates::Spherical,
            &[
                (0, 0, "-(1 - 2*M*r/(r^2 + a^2*cos(theta)^2))"),
                (0, 3, "-2*M*a*r*sin(theta)^2/(r^2 + a^2*cos(theta)^2)"),
                (1, 1, "(r^2 + a^2*cos(theta)^2)/(r^2 - 2*M*r + a^2)"),
                (2, 2, "r^2 + a^2*cos(theta)^2"),
                (3, 3, "(r^2 + a^2 + 2*M*r*a^2*sin(theta)^2/(r^2 + a^2*cos(theta)^2))*sin(theta)^2"),
            ],
        ),
        // Flat space in a frame rotating about z, its light cylinder at ρ = 20.
        written(
            Coordinates::Cartesian,
            &[(0, 0, "-(1 - w^2*(x^2 + y^2))"), (0, 1, "-w*y"), (0, 2, "w*x"), (1, 1, "1"), (2, 2, "1"), (3, 3, "1")],
        ),
    ];
    // Compiles only while every variant is listed above.
    for s in &all {
        match s {
            Spacetime::Minkowski(_)
            | Spacetime::Schwarzschild(_)
            | Spacetime::Kerr(_)
            | Spacetime::Ellis(_)
            | Spacetime::ReissnerNordstrom(_)
            | Spacetime::KerrNewman(_)
            | Spacetime::Wormhole(_)
            | Spacetime::Written(_) => {}
        }
    }
    all.to_vec()
}

/// World points from inside the horizons and throats to far out (every example's length scale
/// is 1, or 0 without mass).
const POINTS: [[f64; 3]; 7] = [
    [10.0, 0.0, 0.0],
    [3.0, 1.0, -2.5],
    [0.1, 0.2, 2.1],
    [1.5, 0.5, 0.2],
    [0.2, 0.1, 0.1],
    [-0.9, 1.8, 0.4],
    [40.0, -25.0, 7.0],
];

#[test]
fn every_metric_is_consistent_at_every_point() {
    for s in examples() {
        let m = s.capabilities();
        for p in POINTS {
            for &region in s.regions() {
                if let Some(x) = m.world_to_chart(region, p, 0.3) {
                    check_metric(m, &x);
                }
            }
        }
    }
}

/// [`check_capabilities`] is generic (it asks which tracer a metric chooses): one call per type.
#[test]
fn every_metric_answers_the_renderer_consistently() {
    for s in examples() {
        for p in POINTS {
            for &region in s.regions() {
                match &s {
                    Spacetime::Minkowski(m) => check_capabilities(m, region, p),
                    Spacetime::Schwarzschild(m) => check_capabilities(m, region, p),
                    Spacetime::Kerr(m) => check_capabilities(m, region, p),
                    Spacetime::Ellis(m) => check_capabilities(m, region, p),
                    Spacetime::ReissnerNordstrom(m) => check_capabilities(m, region, p),
                    Spacetime::KerrNewman(m) => check_capabilities(m, region, p),
                    Spacetime::Wormhole(m) => check_capabilities(m, region, p),
                    Spacetime::Written(m) => check_capabilities(m, region, p),
                }
            }
        }
    }
}

/// Observers cannot stay at rest inside a horizon, in Kerr's ergoregion, or off the wormhole's
/// chart; they can just outside.
#[test]
fn where_nothing_can_stay_at_rest() {
    let hole = Spacetime::schwarzschild(1.0).unwrap();
    let rest = |s: &Spacetime, p: [f64; 3]| s.capabilities().rest(Region::Upper, p);
    assert!(matches!(rest(&hole, [1.9, 0.0, 0.0]), Err(NoRest::InsideHorizon { .. })));
    assert_eq!(rest(&hole, [2.1, 0.0, 0.0]), Ok(()));
    // A charged hole's outer horizon r₊ = M + √(M² − Q²) = 1.6 for Q = 0.8 M.
    let charged = Spacetime::reissner_nordstrom(1.0, 0.8).unwrap();
    assert!(matches!(rest(&charged, [0.0, 1.59, 0.0]), Err(NoRest::InsideHorizon { .. })));
    assert_eq!(rest(&charged, [0.0, 1.61, 0.0]), Ok(()));
    let kerr = Spacetime::kerr(1.0, 0.9).unwrap();
    // On the equator the spheroidal radius is √(x² − a²): the ergoregion reaches r = 2M
    // (x = 2.19), the horizon r₊ = 1.436 (x = 1.69).
    assert_eq!(rest(&kerr, [1.9, 0.0, 0.0]), Err(NoRest::InsideErgoregion));
    assert!(matches!(rest(&kerr, [1.2, 0.0, 0.0]), Err(NoRest::InsideHorizon { .. })));
    assert_eq!(rest(&kerr, [2.3, 0.0, 0.0]), Ok(()));
    assert_eq!(rest(&kerr, [0.0, 0.0, 1.9]), Ok(()), "above the pole, outside the ergoregion");
    // Kerr–Newman with a = 0.6, Q = 0.5: on the equator the ergoregion reaches
    // r = M + √(M² − Q²) = 1.866 (x = 1.960), the horizon r₊ = M + √(M² − a² − Q²) = 1.624 (x = 1.732).
    let charged = Spacetime::kerr_newman(1.0, 0.6, 0.5).unwrap();
    assert_eq!(rest(&charged, [1.9, 0.0, 0.0]), Err(NoRest::InsideErgoregion));
    assert!(matches!(rest(&charged, [1.7, 0.0, 0.0]), Err(NoRest::InsideHorizon { .. })));
    assert_eq!(rest(&charged, [2.0, 0.0, 0.0]), Ok(()));
    let wormhole = Spacetime::ellis(1.0).unwrap();
    for region in [Region::Upper, Region::Lower] {
        assert!(matches!(wormhole.capabilities().rest(region, [0.99, 0.0, 0.0]), Err(NoRest::OffChart { .. })));
        assert_eq!(wormhole.capabilities().rest(region, [1.01, 0.0, 0.0]), Ok(()));
    }
    // Interstellar's: world radius ρ is the cylinder's mouth, within it is off the chart.
    let interstellar = Spacetime::wormhole(1.0, 0.01, 0.05).unwrap();
    for region in [Region::Upper, Region::Lower] {
        let rest = |p: [f64; 3]| interstellar.capabilities().rest(region, p);
        assert!(matches!(rest([0.0, 0.999, 0.0]), Err(NoRest::OffChart { .. })));
        assert_eq!(rest([0.0, 1.0, 0.0]), Ok(()));
        assert_eq!(rest([0.0, 0.0, 1.001]), Ok(()));
    }
    assert_eq!(hole.capabilities().rest(Region::Lower, [5.0, 0.0, 0.0]), Err(NoRest::NoSuchRegion));
}

/// Each metric's tracer: straight where flat, in-plane where static and spherically symmetric, its
/// own 4-D stepper for holes of Kerr's family.
#[test]
fn tracers_fit_the_metrics() {
    assert_eq!(chosen_tracer(&spacetime::Minkowski), "straight");
    assert_eq!(chosen_tracer(&spacetime::Schwarzschild::new(1.0)), "in-plane");
    assert_eq!(chosen_tracer(&spacetime::Schwarzschild::new(0.0)), "straight");
    assert_eq!(chosen_tracer(&spacetime::Kerr::new(1.0, 0.5)), "own 4-D");
    assert_eq!(chosen_tracer(&spacetime::Ellis::new(1.0)), "in-plane");
    assert_eq!(chosen_tracer(&spacetime::ReissnerNordstrom::new(1.0, 0.9)), "in-plane");
    assert_eq!(chosen_tracer(&spacetime::ReissnerNordstrom::new(0.0, 0.0)), "straight");
    assert_eq!(chosen_tracer(&spacetime::KerrNewman::new(1.0, 0.6, 0.5)), "own 4-D");
    assert_eq!(chosen_tracer(&spacetime::Wormhole::new(spacetime::Dneg::new(1.0, 0.01, 0.05))), "in-plane");
}

//! Timelike geodesics against exact solutions: the radial plunge's cycloid to the horizon and to
//! the centre, circular orbits' periods over a hundred revolutions, the constants of a generic
//! Kerr orbit, straight lines in flat space, and refused starts.

#![allow(clippy::unwrap_used)] // Test helpers may panic: a panic is a failed test.

use spacetime::geodesic::{angular_momentum_z, energy, State, Stepping, TraceSettings};
use spacetime::metric::{KerrNewman, KerrSchild, Metric, Minkowski, Region, Schwarzschild, Spacetime};
use spacetime::worldline::{
    carter_constant, start, Chart, CircularOrbit, Direction, End, StartError, Until, Worldline,
};

fn settings(rtol: f64) -> TraceSettings {
    TraceSettings { stepping: Stepping::Adaptive { rtol }, max_steps: 1_000_000, ..TraceSettings::default() }
}

/// A body let go from rest at `r₀` falls along the cycloid `r = r₀/2 (1 + cos η)`,
/// `τ = √(r₀³/8M) (η + sin η)` (Misner, Thorne & Wheeler 1973, eq. 31.10): it crosses the
/// horizon at `cos η = 4M/r₀ − 1` and reaches `r = 0` at `τ = π √(r₀³/8M)`. Both times to
/// 1e-8 relative, and the radius along the way, integrated through the horizon in the twin's
/// (ingoing) chart.
#[test]
fn a_radial_plunge_follows_the_cycloid_through_the_horizon_to_the_centre() {
    let (m, r0) = (1.0, 10.0);
    let hole = Spacetime::schwarzschild(m).unwrap();
    let chart = Chart::for_spacetime(&hole);
    let s = start(chart.own_metric(), [0.0, r0, 0.0, 0.0], [0.0; 3]).unwrap();
    let line = Worldline::integrate(chart, s, Until::ProperTime(100.0), &settings(1e-12)).unwrap();
    let scale = (r0 * r0 * r0 / (8.0 * m)).sqrt();
    let tau_of = |eta: f64| scale * (eta + eta.sin());
    assert_eq!(line.end(), End::Centre, "after {} steps", line.steps());
    let to_centre = std::f64::consts::PI * scale;
    let centre_error = (line.proper_time() - to_centre).abs() / to_centre;
    assert!(centre_error < 1e-8, "r = 0 at τ = {} vs {to_centre} ({centre_error:e})", line.proper_time());
    let horizon = tau_of((4.0 * m / r0 - 1.0).acos());
    let crossing = line.horizon_crossing().unwrap();
    let horizon_error = (crossing - horizon).abs() / horizon;
    assert!(horizon_error < 1e-8, "horizon at τ = {crossing} vs {horizon} ({horizon_error:e})");
    let twin = KerrNewman::new(m, 0.0, 0.0);
    for eta in [0.3, 1.0, 2.0, 2.5, 3.0, 3.1] {
        let r = twin.radial_coordinate(&line.state_at(tau_of(eta)).unwrap().x);
        let exact = 0.5 * r0 * (1.0 + eta.cos());
        assert!((r - exact).abs() < 1e-8 * r0, "η = {eta}: r = {r} vs {exact}");
    }
    // Outside the horizon the events are the hole's, at its coordinate times, which grow
    // without bound towards the horizon crossing; inside it the hole's chart has none.
    let before = line.event_at_proper_time(0.999 * horizon).unwrap();
    let r_twin = twin.radial_coordinate(&line.state_at(0.999 * horizon).unwrap().x);
    assert!((Schwarzschild::new(m).radial_coordinate(&before.x) - r_twin).abs() < 1e-12);
    assert!(line.event_at_proper_time(1.001 * horizon).is_none());
    // Seen in the hole's time the body freezes at the horizon: `r − 2M` falls as `e^{−κt}`,
    // `κ = 1/4M` the surface gravity (to 1 % once `r − 2M` is below 1e-3 M).
    let above = |t: f64| {
        let e = line.event_at_time(t).unwrap();
        assert!(e.tau < crossing, "t = {t} at τ = {} before the crossing", e.tau);
        Schwarzschild::new(m).radial_coordinate(&e.x) - 2.0 * m
    };
    let (early, late) = (above(90.0), above(130.0));
    assert!(early < 1e-3 * m && late > 0.0, "r − 2M = {early}, {late}");
    let e_folding = 40.0 / (early / late).ln();
    assert!((e_folding - 4.0 * m).abs() < 0.04 * m, "e-folding time {e_folding}");
    // Far later the body is at the horizon to the last bit: no later proper time than its.
    assert!(line.proper_time_at(1e3).unwrap() <= crossing);
    let t = line.event_at_proper_time(0.5 * horizon).unwrap().x[0];
    assert!((line.proper_time_at(t).unwrap() - 0.5 * horizon).abs() < 1e-10 * horizon);
}

/// In the hole's own chart (outgoing Kerr–Schild, like Schwarzschild's coordinates singular on
/// the future horizon) the worldline ends where the chart does: its time runs away as the
/// horizon nears, and it never gets past the horizon's proper time.
#[test]
fn in_a_chart_singular_on_the_horizon_the_worldline_ends_there() {
    let (m, r0) = (1.0, 10.0);
    let chart = Chart::own(Schwarzschild::new(m));
    let s = start(chart.own_metric(), [0.0, r0, 0.0, 0.0], [0.0; 3]).unwrap();
    let line = Worldline::integrate(chart, s, Until::ProperTime(100.0), &settings(1e-10)).unwrap();
    let scale = (r0 * r0 * r0 / (8.0 * m)).sqrt();
    let eta = (4.0 * m / r0 - 1.0_f64).acos();
    let horizon = scale * (eta + eta.sin());
    assert_eq!(line.end(), End::ChartEnds);
    assert!(line.proper_time() < horizon && horizon - line.proper_time() < 1e-3 * horizon, "{}", line.proper_time());
    let last = line.event_at_proper_time(line.proper_time()).unwrap();
    assert!(last.x[0] > 50.0 * m, "the chart's time runs away: t = {}", last.x[0]);
}

/// Circular orbits integrated from their closed-form start keep their radius and come round in
/// `2π/Ω` of coordinate time: after 100 revolutions the integrated body is where the exact one
/// is, its azimuth within 1e-8 of the angle turned (the period to 1e-8 relative), its radius
/// within 1e-8 relative all along.
#[test]
fn circular_orbits_keep_radius_and_period_over_a_hundred_revolutions() {
    let cases = [
        (Spacetime::schwarzschild(1.0).unwrap(), 8.0, Direction::Prograde),
        (Spacetime::kerr(1.0, 0.9).unwrap(), 6.0, Direction::Prograde),
        (Spacetime::kerr(1.0, 0.9).unwrap(), 10.0, Direction::Retrograde),
    ];
    for (hole, radius, direction) in cases {
        let orbit = CircularOrbit::of_spacetime(&hole, radius, direction, 0.0).unwrap();
        let revolutions = 100.0;
        let until = Until::CoordinateTime(revolutions * orbit.period() * 1.01);
        let line = Worldline::integrate(Chart::for_spacetime(&hole), orbit.start(), until, &settings(1e-12)).unwrap();
        assert_eq!(line.end(), End::Until);
        let bl = |x: &[f64; 4]| KerrNewman::new(1.0, orbit_spin(&hole), 0.0).radial_coordinate(x);
        let samples = 1000;
        for i in 0..=samples {
            let t = revolutions * orbit.period() * f64::from(i) / f64::from(samples);
            let e = line.event_at_time(t).unwrap();
            assert!((bl(&e.x) - radius).abs() < 1e-8 * radius, "{hole:?} {direction:?} t = {t}: r = {}", bl(&e.x));
        }
        let t = revolutions * orbit.period();
        let (got, exact) = (line.event_at_time(t).unwrap(), orbit.event_at_time(t));
        let phase = (got.x[2].atan2(got.x[1]) - exact.x[2].atan2(exact.x[1])).abs();
        let turned = std::f64::consts::TAU * revolutions;
        assert!(phase / turned < 1e-8, "{hole:?} {direction:?}: azimuth off by {phase:e} after {turned} rad");
        let tau_exact = t / orbit.time_dilation();
        assert!((got.tau - tau_exact).abs() < 1e-8 * tau_exact, "proper time {} vs {tau_exact}", got.tau);
    }
}

fn orbit_spin(hole: &Spacetime) -> f64 {
    hole.parameters().iter().find(|p| p.name == "spin").map_or(0.0, |p| p.value)
}

/// A generic bound orbit about a Kerr hole (eccentric, inclined): `E = −p_t`, `L_z = p_φ` and
/// Carter's `Q` stay as they started, to 1e-10 relative, over tens of radial periods, and the
/// mass shell `g^{μν} p_μ p_ν = −1` with them.
#[test]
fn a_generic_kerr_orbit_keeps_its_energy_angular_momentum_and_carter_constant() {
    let hole = Spacetime::kerr(1.0, 0.9).unwrap();
    let kerr = KerrNewman::new(1.0, 0.9, 0.0);
    let chart = Chart::for_spacetime(&hole);
    let s = start(chart.own_metric(), [0.0, 10.0, 0.0, 1.0], [0.05, 0.3, 0.18]).unwrap();
    let line = Worldline::integrate(chart, s, Until::ProperTime(2e4), &settings(1e-13)).unwrap();
    assert_eq!(line.end(), End::Until, "bound");
    let first = line.event_at_proper_time(0.0).unwrap();
    let constants = |e: &spacetime::worldline::Event| {
        let s = State { x: e.x, p: e.p };
        [energy(&e.p), angular_momentum_z(&s), carter_constant(&kerr, &s)]
    };
    let c0 = constants(&first);
    assert!(c0[0] < 1.0 && c0[2] > 1.0, "bound and inclined: E, L, Q = {c0:?}");
    let (mut r_min, mut r_max) = (f64::INFINITY, 0.0f64);
    for i in 0..=2000 {
        let e = line.event_at_proper_time(2e4 * f64::from(i) / 2000.0).unwrap();
        let c = constants(&e);
        for k in 0..3 {
            assert!((c[k] - c0[k]).abs() < 1e-10 * c0[k].abs(), "constant {k} at τ = {}: {} vs {}", e.tau, c[k], c0[k]);
        }
        assert!((2.0 * kerr.hamiltonian(&e.x, &e.p) + 1.0).abs() < 1e-10);
        let r = kerr.radial_coordinate(&e.x);
        (r_min, r_max) = (r_min.min(r), r_max.max(r));
    }
    // Tens of radial periods (each at most 2π a^{3/2}/√M with a the semi-major axis).
    let semi_major = 0.5 * (r_min + r_max);
    let periods = 2e4 / (std::f64::consts::TAU * semi_major.powf(1.5));
    assert!(periods > 20.0 && r_max - r_min > 1.0, "{periods} periods between r = {r_min} and {r_max}");
}

/// Flat space: a straight line at constant velocity, `x = x₀ + γ v τ`, `t = γ τ`, to rounding.
#[test]
fn in_flat_space_a_body_moves_straight_at_constant_velocity() {
    let v = [0.3, -0.4, 0.5];
    let gamma = 1.0 / (1.0 - (0.09 + 0.16 + 0.25f64)).sqrt();
    let x0 = [2.0, 1.0, 2.0, 3.0];
    let s = start(&Minkowski, x0, v).unwrap();
    let line = Worldline::integrate(Chart::own(Minkowski), s, Until::ProperTime(50.0), &settings(1e-8)).unwrap();
    assert_eq!(line.end(), End::Until);
    for tau in [0.0, 0.7, 13.0, 50.0] {
        let e = line.event_at_proper_time(tau).unwrap();
        let exact =
            [x0[0] + gamma * tau, x0[1] + gamma * v[0] * tau, x0[2] + gamma * v[1] * tau, x0[3] + gamma * v[2] * tau];
        let u = [gamma, gamma * v[0], gamma * v[1], gamma * v[2]];
        for k in 0..4 {
            assert!((e.x[k] - exact[k]).abs() < 1e-12 * (1.0 + exact[k].abs()), "τ = {tau}: {:?} vs {exact:?}", e.x);
            assert!((e.u[k] - u[k]).abs() < 1e-13, "τ = {tau}: u = {:?}", e.u);
        }
        let t = e.x[0];
        assert!((line.proper_time_at(t).unwrap() - tau).abs() < 1e-12 * (1.0 + tau));
    }
}

/// A start faster than light, or not a number, is refused with a message that says so; so is a
/// state that is not a body's, and a point with no observer.
#[test]
fn impossible_starts_are_refused() {
    let hole = Spacetime::schwarzschild(1.0).unwrap();
    let metric = hole.metric();
    let x = [0.0, 6.0, 0.0, 0.0];
    for (velocity, says) in [
        ([1.0, 0.0, 0.0], "speed 1 (units of c)"),
        ([0.8, 0.7, 0.0], "a body moves slower than light"),
        ([f64::NAN, 0.0, 0.0], "is not finite"),
        ([0.0, f64::INFINITY, 0.0], "is not finite"),
    ] {
        let err = start(metric, x, velocity).expect_err("refused");
        assert!(err.to_string().contains(says), "{velocity:?}: {err}");
    }
    let centre = start(metric, [0.0; 4], [0.0; 3]);
    assert!(matches!(centre, Err(StartError::NoObserver { .. })), "{centre:?}");
    let light = State { x, p: [-1.0, (1.0f64 - 2.0 / 6.0).recip(), 0.0, 0.0] };
    let refused = Worldline::integrate(Chart::for_spacetime(&hole), light, Until::ProperTime(1.0), &settings(1e-8));
    assert!(matches!(refused, Err(StartError::NotUnitTimelike { .. })), "{refused:?}");
}

/// A satellite sent through the Ellis wormhole's throat comes out in the other region.
#[test]
fn a_satellite_goes_through_the_wormhole() {
    let wormhole = Spacetime::ellis(1.0).unwrap();
    let chart = Chart::for_spacetime(&wormhole);
    let metric = chart.own_metric();
    let x = metric.world_to_chart(Region::Upper, [5.0, 0.0, 0.0], 0.0).unwrap();
    let frame_in = start(metric, x, [-0.5, 0.05, 0.0]).unwrap();
    let line = Worldline::integrate(chart.clone(), frame_in, Until::ProperTime(1e4), &settings(1e-10)).unwrap();
    assert_eq!(line.end(), End::Escaped { region: Region::Lower }, "after τ = {}", line.proper_time());
    let h = line.event_at_proper_time(0.5 * line.proper_time()).unwrap();
    assert!((2.0 * metric.hamiltonian(&h.x, &h.p) + 1.0).abs() < 1e-8);
}

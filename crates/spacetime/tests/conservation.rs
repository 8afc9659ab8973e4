//! Properties of the 4-D Hamiltonian tracer that need no exact solution: the constraint and the
//! constants of motion are kept, time reversal retraces the ray, flat rays are straight, and the
//! in-plane tracer agrees with it.

#![allow(clippy::unwrap_used)] // Test helpers may panic: a panic is a failed test.

use spacetime::geodesic::plane::{trace_plane, PlaneMetric, PlaneStart};
use spacetime::geodesic::{angular_momentum_z, HamiltonianTracer, State, Stepping, TraceSettings, Visit};
use spacetime::metric::Metric;
use spacetime::{Ellis, Fate, Kerr, Minkowski, ReissnerNordstrom, Schwarzschild, Tetrad};

/// Deterministic pseudo-random numbers in [0, 1) (a 64-bit LCG), so the tests need no RNG crate.
struct Lcg(u64);
impl Lcg {
    fn next(&mut self) -> f64 {
        self.0 = self.0.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
        (self.0 >> 11) as f64 / (1u64 << 53) as f64
    }
    fn unit(&mut self) -> [f64; 3] {
        let z = 2.0 * self.next() - 1.0;
        let phi = 2.0 * std::f64::consts::PI * self.next();
        let r = (1.0 - z * z).sqrt();
        [r * phi.cos(), r * phi.sin(), z]
    }
}

/// A camera-like ray: from the static observer at world position `pos` (upper region), along
/// frame direction `n`, energy 1.
fn camera_ray(metric: &dyn Metric, pos: [f64; 3], n: [f64; 3]) -> State {
    let x = metric.world_to_chart(spacetime::Region::Upper, pos, 0.0).unwrap();
    let frame = Tetrad::local_observer(metric, &x).unwrap();
    State { x, p: frame.backward_momentum(&metric.metric(&x), n, 1.0) }
}

/// The constraint and constants are checked at `rtol = 1e-11`; they drift in proportion to the
/// tolerance (about 100× more at the renderer's 1e-8).
const ADAPTIVE: TraceSettings = TraceSettings {
    stepping: Stepping::Adaptive { rtol: 1e-11 },
    escape_radius: 1e3,
    max_step_fraction: 0.5,
    max_steps: 100_000,
    check_every_step: true,
};

fn check_constants(metric: &dyn Metric, rays: usize, seed: u64) {
    let mut rng = Lcg(seed);
    let mut captured = 0;
    for _ in 0..rays {
        let r = 6.0 + 30.0 * rng.next();
        let pos = rng.unit().map(|c| c * r);
        let start = camera_ray(metric, pos, rng.unit());
        let (e0, l0) = (-start.p[0], angular_momentum_z(&start));
        let mut worst = (0.0f64, 0.0f64, 0.0f64);
        let trace = HamiltonianTracer::new(metric, start, ADAPTIVE).run(|step| {
            let s = &step.end;
            if metric.inside_horizon(&s.x) {
                // The last step of a captured ray ends inside, on its way to the singularity.
                return Visit::Continue;
            }
            worst.0 = worst.0.max(metric.hamiltonian(&s.x, &s.p).abs() / (e0 * e0));
            worst.1 = worst.1.max((-s.p[0] - e0).abs() / e0);
            worst.2 = worst.2.max((angular_momentum_z(s) - l0).abs() / (l0.abs() + e0 * metric.length_scale()));
            Visit::Continue
        });
        assert!(!matches!(trace.fate, Fate::Failed(_)), "{:?}", trace.fate);
        captured += usize::from(trace.fate == Fate::Captured);
        assert!(worst.0 < 1e-9, "|H|/E² = {:e}", worst.0);
        assert!(worst.1 < 1e-9, "ΔE/E = {:e}", worst.1);
        assert!(worst.2 < 1e-9, "ΔL_z/L_z = {:e}", worst.2);
    }
    // The sample must include rays that fell in and rays that escaped, or it tested little.
    if metric.length_scale() > 0.0 && !metric.inside_horizon(&[0.0, 1e-3, 0.0, 0.0]) {
        return;
    }
    assert!(captured > 0 && captured < rays, "captured {captured} of {rays}");
}

#[test]
fn schwarzschild_keeps_the_null_constraint_energy_and_angular_momentum() {
    check_constants(&Schwarzschild::new(1.0), 200, 1);
}

#[test]
fn kerr_keeps_the_null_constraint_energy_and_angular_momentum() {
    check_constants(&Kerr::new(1.0, 0.9), 200, 2);
    check_constants(&Kerr::new(1.0, -1.0), 100, 3);
}

#[test]
fn ellis_keeps_the_null_constraint_energy_and_angular_momentum() {
    check_constants(&Ellis::new(2.0), 200, 4);
}

#[test]
fn time_reversal_retraces_the_ray() {
    let metrics: [&dyn Metric; 4] =
        [&Schwarzschild::new(1.0), &Kerr::new(1.0, 0.7), &Ellis::new(1.0), &ReissnerNordstrom::new(1.0, 0.9)];
    let settings = TraceSettings { stepping: Stepping::Adaptive { rtol: 1e-11 }, ..ADAPTIVE };
    for metric in metrics {
        // Passes close to the centre and bends strongly.
        let start = camera_ray(metric, [12.0, 0.0, 1.0], [-0.8, 0.6, 0.0]);
        let length = 25.0;
        let run = |s: State| {
            let mut tracer = HamiltonianTracer::new(metric, s, settings);
            while tracer.lambda() < length {
                tracer.step(length - tracer.lambda()).unwrap();
            }
            tracer.state()
        };
        let mid = run(start);
        let back = run(State { x: mid.x, p: mid.p.map(|c| -c) });
        for k in 0..4 {
            assert!((back.x[k] - start.x[k]).abs() < 1e-7, "x[{k}]: {} vs {}", back.x[k], start.x[k]);
            assert!((back.p[k] + start.p[k]).abs() < 1e-7, "p[{k}]");
        }
    }
}

#[test]
fn minkowski_rays_are_straight_to_rounding() {
    let mut rng = Lcg(5);
    for _ in 0..50 {
        let pos = rng.unit().map(|c| c * 20.0);
        let n = rng.unit();
        let start = camera_ray(&Minkowski, pos, n);
        HamiltonianTracer::new(&Minkowski, start, ADAPTIVE).run(|step| {
            let x = [step.end.x[1] - pos[0], step.end.x[2] - pos[1], step.end.x[3] - pos[2]];
            let along = x[0] * n[0] + x[1] * n[1] + x[2] * n[2];
            let off = (0..3).map(|i| (x[i] - along * n[i]).powi(2)).sum::<f64>().sqrt();
            assert!(off < 1e-12 * (1.0 + along.abs()), "off the line by {off:e}");
            Visit::Continue
        });
    }
}

/// The in-plane tracer and the 4-D tracer send camera rays to the same place.
fn plane_agrees_with_hamiltonian<M: PlaneMetric>(metric: &M, seed: u64) {
    let mut rng = Lcg(seed);
    let far = TraceSettings { stepping: Stepping::Adaptive { rtol: 1e-10 }, escape_radius: 1e6, ..ADAPTIVE };
    let mut escaped = 0;
    for _ in 0..100 {
        let pos = rng.unit().map(|c| c * 15.0);
        let n = rng.unit();
        let four = HamiltonianTracer::new(metric, camera_ray(metric, pos, n), far).run(|_| Visit::Continue);
        let start = PlaneStart::from_observer(metric, spacetime::Region::Upper, pos, n).unwrap();
        let plane = trace_plane(metric, start, &far, |_| Visit::Continue);
        match (four.fate, plane.fate) {
            (Fate::Escaped { direction: a }, Fate::Escaped { direction: b })
            | (Fate::Traversed { direction: a }, Fate::Traversed { direction: b }) => {
                let err = (0..3).map(|i| (a[i] - b[i]).powi(2)).sum::<f64>().sqrt();
                // The 4-D ray stops at 10⁶: its direction there is off the asymptote by ~ M b/R².
                assert!(err < 1e-7, "directions differ by {err:e}");
                escaped += 1;
            }
            (a, b) => assert_eq!(a.name(), b.name()),
        }
    }
    assert!(escaped > 10);
}

#[test]
fn in_plane_tracer_agrees_with_the_hamiltonian_tracer() {
    plane_agrees_with_hamiltonian(&Schwarzschild::new(1.0), 6);
    plane_agrees_with_hamiltonian(&Ellis::new(1.0), 7);
    plane_agrees_with_hamiltonian(&ReissnerNordstrom::new(1.0, 0.9), 8);
}

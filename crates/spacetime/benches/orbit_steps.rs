//! Latency against throughput of the in-plane tracer's Taylor steps (`OrbitStep`, M = 0.3, the
//! black-hole room's hole; steps of at most a radian at rtol 10⁻⁷, as renders take them).
//!
//! Each step's series waits on the last one's end, and inside a step every coefficient waits on
//! the ones before it: one orbit keeps the core waiting on dependent multiply–adds. Two orbits
//! stepped side by side in one loop are independent chains the core overlaps. Both functions take
//! the same number of steps; the gap between them is what tracing several rays interleaved per
//! thread (or SIMD lanes over rays) could win back on this part of the curved render
//! (docs/perf-journal.md, session 18).

use criterion::{criterion_group, criterion_main, Criterion, Throughput};
use spacetime::metric::schwarzschild::binet_taylor::OrbitStep;
use std::hint::black_box;

const MASS: f64 = 0.3;
const RTOL: f64 = 1e-7;
const MAX_STEP: f64 = 1.0;
/// Steps per orbit before it starts over: about a crossing of the room from the camera (r = 7).
const STEPS_PER_ORBIT: usize = 6;
const STEPS: usize = 4096;

/// Starts `(u, u')` at r = 7, from nearly radial to tangential (impact parameters 0.8 to 6).
fn starts() -> Vec<[f64; 2]> {
    let u = 1.0 / 7.0;
    (0..16)
        .map(|i| {
            let b = 0.8 + 5.2 * f64::from(i) / 15.0;
            // (u')² = 1/b² − u² + 2Mu³, inward (u rising).
            [u, (1.0 / (b * b) - u * u + 2.0 * MASS * u * u * u).max(0.0).sqrt()]
        })
        .collect()
}

fn step(state: [f64; 2]) -> [f64; 2] {
    OrbitStep::new(MASS, state[0], state[1], MAX_STEP, RTOL).at(1.0)
}

fn orbit_steps(c: &mut Criterion) {
    let starts = starts();
    let mut group = c.benchmark_group("orbit_steps");
    group.throughput(Throughput::Elements(STEPS as u64));
    group.bench_function("one_chain", |b| {
        b.iter(|| {
            let mut sum = 0.0;
            for orbit in 0..STEPS / STEPS_PER_ORBIT {
                let mut y = black_box(starts[orbit % starts.len()]);
                for _ in 0..STEPS_PER_ORBIT {
                    y = step(y);
                }
                sum += y[0];
            }
            sum
        })
    });
    group.bench_function("two_chains_interleaved", |b| {
        b.iter(|| {
            let mut sum = 0.0;
            for orbit in 0..STEPS / (2 * STEPS_PER_ORBIT) {
                let mut y = black_box(starts[(2 * orbit) % starts.len()]);
                let mut z = black_box(starts[(2 * orbit + 1) % starts.len()]);
                for _ in 0..STEPS_PER_ORBIT {
                    (y, z) = (step(y), step(z));
                }
                sum += y[0] + z[0];
            }
            sum
        })
    });
    group.finish();
}

criterion_group!(benches, orbit_steps);
criterion_main!(benches);

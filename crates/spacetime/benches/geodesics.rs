//! Single-core cost of tracing rays of the standard fan (512², 40°, r = 30 M, Schwarzschild,
//! adaptive rtol 1e-8): a row of the fan through the hole's image, in-plane and in 4-D; and the
//! same row about a Kerr hole (a = 0.9 M) in Mino time; the in-plane and Mino rows again carrying
//! the chart's time.

use criterion::{criterion_group, criterion_main, Criterion, Throughput};
use spacetime::fan::{trace_hamiltonian, trace_in_plane, trace_in_plane_in_time, trace_own, trace_own_in_time, Fan};
use spacetime::{Kerr, Schwarzschild, Stepping, TraceSettings};
use std::hint::black_box;

fn fan_row(c: &mut Criterion) {
    let hole = Schwarzschild::new(1.0);
    let fan = Fan::standard(1.0);
    let settings = TraceSettings { stepping: Stepping::Adaptive { rtol: 1e-8 }, ..TraceSettings::default() };
    // The middle row crosses the shadow, the photon ring and the weakly bent sky.
    let row: Vec<u64> = (0..u64::from(fan.size)).map(|i| u64::from(fan.size) * u64::from(fan.size / 2) + i).collect();
    let mut group = c.benchmark_group("fan_row_512");
    group.throughput(Throughput::Elements(row.len() as u64));
    group.bench_function("in_plane", |b| {
        b.iter(|| row.iter().map(|&i| trace_in_plane(&hole, &fan, black_box(i), &settings).steps).sum::<u32>())
    });
    // The same rays carrying the chart's time, as a moving scene traces them.
    group.bench_function("in_plane_timed", |b| {
        b.iter(|| row.iter().map(|&i| trace_in_plane_in_time(&hole, &fan, black_box(i), &settings).steps).sum::<u32>())
    });
    group.bench_function("hamiltonian_4d", |b| {
        b.iter(|| row.iter().map(|&i| trace_hamiltonian(&hole, &fan, black_box(i), &settings).steps).sum::<u32>())
    });
    // Kerr (a = 0.9 M) in Mino time, the stepper its renders take.
    let kerr = Kerr::new(1.0, 0.9);
    group.bench_function("kerr_mino", |b| {
        b.iter(|| row.iter().map(|&i| trace_own(&kerr, &fan, black_box(i), &settings).steps).sum::<u32>())
    });
    group.bench_function("kerr_mino_timed", |b| {
        b.iter(|| row.iter().map(|&i| trace_own_in_time(&kerr, &fan, black_box(i), &settings).steps).sum::<u32>())
    });
    group.finish();
}

criterion_group!(benches, fan_row);
criterion_main!(benches);

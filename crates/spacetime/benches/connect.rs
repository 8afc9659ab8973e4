//! Single-core cost of joining two points by a light ray, the shooting behind next-event
//! estimation in the black-hole room (`scenes/room-black-hole.toml`): random pairs of points in
//! its 12 × 8 × 16 box around a hole of mass 0.3 at the origin, the short way and the long way.

use criterion::{criterion_group, criterion_main, Criterion, Throughput};
use spacetime::geodesic::plane::Way;
use spacetime::metric::schwarzschild::connect::Connector;
use spacetime::tensor::norm3;
use spacetime::Schwarzschild;
use std::hint::black_box;

const MASS: f64 = 0.3;
const PAIRS: usize = 256;

/// Uniform points in the room outside the photon sphere (`r > 3M`, where both ways exist), from
/// a fixed xorshift64 stream so every run times the same pairs.
fn room_points(count: usize) -> Vec<[f64; 3]> {
    let mut state = 0x9e37_79b9_7f4a_7c15u64;
    let mut uniform = move || {
        state ^= state << 13;
        state ^= state >> 7;
        state ^= state << 17;
        (state >> 11) as f64 / (1u64 << 53) as f64
    };
    let half = [6.0, 4.0, 8.0];
    std::iter::repeat_with(|| std::array::from_fn(|i| half[i] * (2.0 * uniform() - 1.0)))
        .filter(|p| norm3(p) > 3.0 * MASS)
        .take(count)
        .collect()
}

fn connections(c: &mut Criterion) {
    let hole = Connector::new(Schwarzschild::new(MASS));
    let points = room_points(2 * PAIRS);
    let pairs: Vec<_> = points.chunks_exact(2).map(|p| (p[0], p[1])).collect();
    let mut group = c.benchmark_group("connect_room");
    group.throughput(Throughput::Elements(pairs.len() as u64));
    for (name, way) in [("short", Way::Short), ("long", Way::Long)] {
        group.bench_function(name, |b| {
            b.iter(|| pairs.iter().filter_map(|&(x, y)| hole.connect(black_box(x), black_box(y), way)).count())
        });
    }
    group.finish();
}

criterion_group!(benches, connections);
criterion_main!(benches);

//! Single-core cost of one light connection as the path integrator makes it, in the black-hole
//! room's 12 × 8 × 16 box (`scenes/room-black-hole.toml`, mass 0.3): random pairs of points
//! outside r = 3M joined by Schwarzschild's own connector (the short way, in the ray's plane),
//! by the in-plane aim every static, spherically symmetric metric has (Newton on the start angle
//! over the ray and its Jacobi field), by the generic connector (Newton on the start direction
//! over the 4-D tracer, with the ray bundle) around the same hole, and by the generic connector
//! around a Kerr hole of spin 0.9 M, the Kerr room's. A connection that finds no ray counts as
//! one too.

use criterion::{criterion_group, criterion_main, Criterion, Throughput};
use render::geometry::Vec3;
use render::propagator::Propagator;
use render::settings::Intersection;
use spacetime::geodesic::plane::Way;
use spacetime::metric::schwarzschild::connect::Waypoints;
use spacetime::{Region, Spacetime};
use std::hint::black_box;

const MASS: f64 = 0.3;
const PAIRS: usize = 128;
/// The room's half-diagonal, the scene radius its propagator is built with.
const ROOM_RADIUS: f64 = 10.8;
const RTOL: f64 = 1e-7;

/// Uniform points in the room outside r = 3M, from a fixed xorshift64 stream so every run times
/// the same pairs.
fn room_points(count: usize) -> Vec<Vec3> {
    let mut state = 0x9e37_79b9_7f4a_7c15u64;
    let mut uniform = move || {
        state ^= state << 13;
        state ^= state >> 7;
        state ^= state << 17;
        (state >> 11) as f64 / (1u64 << 53) as f64
    };
    let half = Vec3::new(6.0, 4.0, 8.0);
    std::iter::repeat_with(|| half * Vec3::new(2.0 * uniform() - 1.0, 2.0 * uniform() - 1.0, 2.0 * uniform() - 1.0))
        .filter(|p| p.length() > 3.0 * MASS)
        .take(count)
        .collect()
}

fn propagator(spacetime: Spacetime) -> Propagator {
    Propagator::new(spacetime, ROOM_RADIUS, RTOL, Intersection::Chord).with_axis(Vec3::Y)
}

fn connections(c: &mut Criterion) {
    let points = room_points(2 * PAIRS);
    let pairs: Vec<_> = points.chunks_exact(2).map(|p| (p[0], p[1])).collect();
    let schwarzschild = || Spacetime::schwarzschild(MASS).expect("a valid mass");
    let own = propagator(schwarzschild());
    let generic = propagator(schwarzschild()).with_generic_connector();
    let kerr = propagator(Spacetime::kerr(MASS, 0.9 * MASS).expect("a valid spin"));
    let mut group = c.benchmark_group("light_connection");
    group.throughput(Throughput::Elements(pairs.len() as u64));
    group.sample_size(20);
    group.bench_function("schwarzschild_own_short", |b| {
        let mut waypoints = Waypoints::default();
        b.iter(|| {
            pairs
                .iter()
                .filter_map(|&(x, y)| own.connect(black_box(x), black_box(y), Way::Short, None, &mut waypoints))
                .count()
        })
    });
    for (name, p) in [("schwarzschild_in_plane", &own), ("schwarzschild_generic", &generic), ("kerr_generic", &kerr)] {
        group.bench_function(name, |b| {
            b.iter(|| {
                pairs
                    .iter()
                    .filter_map(|&(x, y)| {
                        p.aim((Region::Upper, black_box(x)), (Region::Upper, black_box(y)), Way::Short)
                    })
                    .count()
            })
        });
    }
    group.finish();
}

criterion_group!(benches, connections);
criterion_main!(benches);

//! BVH build time and closest-hit throughput for short finite segments (geodesic step chords),
//! on 100k random triangles and on a Cornell-box-sized scene of analytic shapes.
//!
//! `cargo bench -p nullpath-render --bench bvh`

use criterion::{criterion_group, criterion_main, Criterion, Throughput};
use render::accel::Bvh;
use render::geometry::{Aabb, Ray, Vec3};
use render::sampling::{uniform_sphere, Rng};
use render::shape::{Shape, TriangleMesh};
use render::transform::Transform;
use std::hint::black_box;
use std::sync::Arc;

/// Segments per measured batch.
const SEGMENTS: usize = 4096;

/// `n` small random triangles in the cube [-1, 1]³ (edge lengths around 0.02: a dense mesh).
fn random_triangles(n: usize) -> Vec<Shape> {
    let mut rng = Rng::new(7);
    let mut positions = Vec::with_capacity(3 * n);
    for _ in 0..n {
        let c = Vec3::new(rng.next_f64(), rng.next_f64(), rng.next_f64()) * 2.0 - Vec3::ONE;
        for _ in 0..3 {
            positions.push(c + uniform_sphere(rng.next_2d()) * 0.02);
        }
    }
    let indices = (0..n as u32).map(|i| [3 * i, 3 * i + 1, 3 * i + 2]).collect();
    match TriangleMesh::new(positions, None, None, indices) {
        Ok(mesh) => TriangleMesh::shapes(&Arc::new(mesh)),
        Err(e) => panic!("benchmark mesh: {e}"),
    }
}

/// The Cornell box as analytic shapes: five walls, the light, two rotated boxes and a sphere.
fn cornell_box() -> Result<Vec<Shape>, Box<dyn std::error::Error>> {
    let id = Transform::IDENTITY;
    let (x, y, z) = (Vec3::X * 2.0, Vec3::Y * 2.0, Vec3::Z * 2.0);
    let c = Vec3::new(-1.0, 0.0, -1.0);
    let tall = Transform::rotate_deg(Vec3::Y, 17.0)?.then(&Transform::translate(Vec3::new(-0.35, 0.0, -0.3)));
    let short = Transform::rotate_deg(Vec3::Y, -17.0)?.then(&Transform::translate(Vec3::new(0.35, 0.0, 0.35)));
    // Walls of the box [-1, 1] × [0, 2] × [-1, 1], edges ordered so the normals face inward.
    Ok(vec![
        Shape::rectangle(c, z, x, &id)?,
        Shape::rectangle(c + y, x, z, &id)?,
        Shape::rectangle(c + z, y, x, &id)?,
        Shape::rectangle(c, y, z, &id)?,
        Shape::rectangle(c + x, z, y, &id)?,
        Shape::rectangle(Vec3::new(-0.25, 1.99, -0.25), Vec3::X * 0.5, Vec3::Z * 0.5, &id)?,
        Shape::cuboid(Vec3::new(-0.3, 0.0, -0.3), Vec3::new(0.3, 1.2, 0.3), &tall)?,
        Shape::cuboid(Vec3::new(-0.3, 0.0, -0.3), Vec3::new(0.3, 0.6, 0.3), &short)?,
        Shape::sphere(Vec3::new(0.5, 0.9, 0.4), 0.25, &id)?,
    ])
}

/// Random segments of length `length` starting inside `region`.
fn segments(region: Aabb, length: f64) -> Vec<Ray> {
    let mut rng = Rng::new(11);
    (0..SEGMENTS)
        .map(|_| {
            let u = Vec3::new(rng.next_f64(), rng.next_f64(), rng.next_f64());
            let origin = region.min + region.diagonal() * u;
            Ray::new(origin, uniform_sphere(rng.next_2d()), length)
        })
        .collect()
}

fn bench_scene(c: &mut Criterion, name: &str, shapes: &[Shape], lengths: &[f64]) {
    let bounds: Vec<Aabb> = shapes.iter().map(Shape::bounds).collect();
    let mut group = c.benchmark_group(name);
    group.bench_function("build", |b| b.iter(|| Bvh::build(black_box(&bounds))));
    let bvh = Bvh::build(&bounds);
    group.throughput(Throughput::Elements(SEGMENTS as u64));
    for &length in lengths {
        let rays = segments(bvh.bounds(), length);
        group.bench_function(format!("closest_hit/len{length}"), |b| {
            b.iter(|| {
                let mut hits = 0usize;
                for ray in black_box(&rays) {
                    hits += usize::from(bvh.closest_hit(ray, |i, r| shapes[i].intersect(r)).is_some());
                }
                hits
            })
        });
    }
    group.finish();
}

fn triangles(c: &mut Criterion) {
    bench_scene(c, "bvh/100k_triangles", &random_triangles(100_000), &[0.1, 1.0]);
}

fn cornell(c: &mut Criterion) {
    match cornell_box() {
        Ok(shapes) => bench_scene(c, "bvh/cornell_box", &shapes, &[0.1, 1.0]),
        Err(e) => panic!("cornell box: {e}"),
    }
}

criterion_group!(benches, triangles, cornell);
criterion_main!(benches);

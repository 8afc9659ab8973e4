//! An instance: one placement of a mesh whose triangles and BVH are shared by every placement.
//!
//! A glTF scene may place one mesh many times (chairs round a table); baking each placement into
//! world space would copy its triangles and build a BVH over each copy. An [`InstancedMesh`]
//! holds the triangles once, in the mesh's own object space, with a BVH over them; an
//! [`Instance`] is an `Arc` to it and an object-to-world [`Transform`]. A query maps the segment
//! into object space *without renormalising its direction* (as the analytic shapes do, pbrt-v4
//! §6.1.4), so the segment's parameter, its `t_max` and the distance returned are world
//! distances along the unit world direction, whatever the placement's scale: a chord of a
//! curved step is answered in the mesh's frame exactly as a baked copy would answer it.
//!
//! The surface record is the hit triangle's, found again by the same query clipped at the hit
//! distance (the query is deterministic, so it finds a triangle at that distance), and mapped to
//! world space: points as points, `dpdu` as a vector, normals by the inverse transpose, which
//! keeps `ng` on the side the mesh calls outside even under a mirroring placement.

use super::{SurfaceHit, Triangle, TriangleMesh};
use crate::accel::Bvh;
use crate::geometry::{Aabb, Ray, Vec3};
use crate::sampling::uniform_triangle;
use crate::transform::Transform;
use std::sync::Arc;

/// A mesh's triangles in its object space, with a BVH over them and the cumulative distribution
/// of their (object-space) areas.
pub struct InstancedMesh {
    triangles: Vec<Triangle>,
    bvh: Bvh,
    /// Running sums of the triangles' areas, ending at the mesh's area.
    area_cdf: Vec<f64>,
}

/// The triangles, their BVH and areas follow from the mesh, so `Debug` shows the mesh alone (as
/// its digest: see [`TriangleMesh`]).
impl std::fmt::Debug for InstancedMesh {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("InstancedMesh").field("mesh", self.mesh()).finish()
    }
}

impl InstancedMesh {
    /// The mesh's triangles with non-zero area (see [`TriangleMesh::shapes`]); `None` when there
    /// are none.
    pub fn new(mesh: TriangleMesh) -> Option<Self> {
        let mesh = Arc::new(mesh);
        let triangles = TriangleMesh::triangles(&mesh);
        if triangles.is_empty() {
            return None;
        }
        let bvh = Bvh::build(&triangles.iter().map(Triangle::bounds).collect::<Vec<_>>());
        let area_cdf = triangles
            .iter()
            .scan(0.0, |sum, t| {
                *sum += t.area();
                Some(*sum)
            })
            .collect();
        Some(Self { triangles, bvh, area_cdf })
    }

    /// The vertex data the triangles share.
    pub fn mesh(&self) -> &Arc<TriangleMesh> {
        self.triangles[0].mesh()
    }

    pub fn triangle_count(&self) -> usize {
        self.triangles.len()
    }

    /// The nearest triangle hit by the object-space segment `local`: its index and distance.
    fn closest(&self, local: &Ray) -> Option<(usize, f64)> {
        self.bvh.closest_hit(local, |i, r| self.triangles[i].intersect(r))
    }
}

/// One placement of an [`InstancedMesh`].
#[derive(Clone, Debug)]
pub struct Instance {
    mesh: Arc<InstancedMesh>,
    transform: Transform,
    bounds: Aabb,
    area: f64,
    /// The smallest factor by which the placement stretches a length.
    min_stretch: f64,
}

impl Instance {
    /// `mesh` placed by `transform` (object to world), which must be finite and invertible.
    pub fn new(mesh: Arc<InstancedMesh>, transform: &Transform) -> Result<Self, super::ShapeError> {
        super::check::transform("instance", transform)?;
        let bounds = transform.bounds(&mesh.bvh.bounds());
        let area = mesh.triangles.iter().map(|t| world_area(t, transform)).sum();
        let min_stretch = transform.scale_bounds().0;
        Ok(Self { mesh, transform: *transform, bounds, area, min_stretch })
    }

    /// The shared mesh.
    pub fn mesh(&self) -> &Arc<InstancedMesh> {
        &self.mesh
    }

    pub fn transform(&self) -> &Transform {
        &self.transform
    }

    /// The segment in object space, with the same parameter (its direction is not renormalised).
    fn local(&self, ray: &Ray) -> Ray {
        Ray::new(self.transform.inverse_point(ray.origin), self.transform.inverse_vector(ray.dir), ray.t_max)
    }

    pub fn bounds(&self) -> Aabb {
        self.bounds
    }

    #[inline]
    pub fn intersect(&self, ray: &Ray) -> Option<f64> {
        self.mesh.closest(&self.local(ray)).map(|(_, t)| t)
    }

    pub fn surface(&self, ray: &Ray, t: f64) -> SurfaceHit {
        let local = self.local(ray);
        let clipped = Ray { t_max: t, ..local };
        // The query that found `t` finds it again; the fallback only guards against a caller
        // passing a `t` that no query returned.
        let index = self.mesh.closest(&clipped).or_else(|| self.mesh.closest(&local)).map_or(0, |(i, _)| i);
        let h = self.mesh.triangles[index].surface(&local, t);
        let normal = |n: Vec3| self.transform.normal(n).normalize();
        let ng = normal(h.ng);
        let ns = Some(normal(h.ns)).filter(|ns| ns.dot(ng) > 0.0).unwrap_or(ng);
        SurfaceHit { p: self.transform.point(h.p), ng, ns, uv: h.uv, dpdu: self.transform.vector(h.dpdu) }
    }

    pub fn area(&self) -> f64 {
        self.area
    }

    /// A point on the instance and the outward normal there: a triangle chosen by its share of
    /// the mesh's object-space area, then a uniform point on it. This is uniform by world area
    /// when the placement is a similarity (rotation, uniform scale, translation: every triangle's
    /// area scales alike), which is why the scene builder bakes emitting meshes into world
    /// triangles rather than instancing them.
    pub fn sample_area(&self, u: [f64; 2]) -> (Vec3, Vec3) {
        let cdf = &self.mesh.area_cdf;
        let total = cdf[cdf.len() - 1];
        let target = u[0] * total;
        let k = cdf.partition_point(|&c| c <= target).min(cdf.len() - 1);
        let lo = if k == 0 { 0.0 } else { cdf[k - 1] };
        // Reuse the part of u[0] within the chosen triangle's interval, so that one 2-D sample
        // covers the mesh.
        let u0 = ((target - lo) / (cdf[k] - lo)).clamp(0.0, 1.0 - f64::EPSILON);
        let triangle = &self.mesh.triangles[k];
        let [p0, p1, p2] = triangle.vertices();
        let [b0, b1, b2] = uniform_triangle([u0, u[1]]);
        let n = (p1 - p0).cross(p2 - p0);
        (self.transform.point(p0 * b0 + p1 * b1 + p2 * b2), self.transform.normal(n).normalize())
    }

    /// The surface function of the triangle nearest to `p` (in object space, by a scan of all
    /// triangles: only the poster's sign-change test asks), shrunk by the placement's smallest
    /// stretch so that `|f|` stays below the world distance to the surface.
    pub fn surface_function(&self, p: Vec3) -> f64 {
        let local = self.transform.inverse_point(p);
        let nearest = self
            .mesh
            .triangles
            .iter()
            .map(|t| t.surface_function(local))
            .min_by(|a, b| a.abs().total_cmp(&b.abs()))
            .unwrap_or(f64::INFINITY);
        nearest * self.min_stretch
    }
}

/// A triangle's area once placed: half the length of its placed edges' cross product.
fn world_area(t: &Triangle, transform: &Transform) -> f64 {
    let [a, b, c] = t.vertices().map(|v| transform.point(v));
    0.5 * (b - a).cross(c - a).length()
}

#[cfg(test)]
pub(crate) mod tests {
    use super::*;
    use crate::shape::tests::placed;
    use crate::shape::Shape;

    /// A quad in a tilted plane (two triangles sharing a diagonal) with normals and uvs.
    pub(crate) fn tilted_quad() -> TriangleMesh {
        let corners = [[-0.5, -0.5], [0.5, -0.5], [0.5, 0.5], [-0.6, 0.5]];
        TriangleMesh::new(
            corners.iter().map(|&[x, y]| Vec3::new(x, y, 0.1 * x + 0.2 * y)).collect(),
            Some(vec![Vec3::Z, Vec3::new(0.1, 0.0, 1.0), Vec3::new(0.0, -0.2, 1.0), Vec3::Z]),
            Some(vec![[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]]),
            vec![[0, 1, 2], [0, 2, 3]],
        )
        .unwrap()
    }

    #[test]
    fn an_instance_answers_as_its_baked_copy_does() {
        // Stretched and mirrored placements included: the instance's hits, distances and
        // records must be those of the same triangles baked into world space.
        let mirror = Transform::scale(Vec3::new(-1.0, 1.0, 1.0)).unwrap();
        let mesh = Arc::new(InstancedMesh::new(tilted_quad()).unwrap());
        let mut rng = crate::sampling::Rng::new(21);
        for placement in [placed(false), placed(true), mirror.then(&placed(true))] {
            let instance = Shape::Instance(Box::new(Instance::new(Arc::clone(&mesh), &placement).unwrap()));
            let q = tilted_quad();
            let baked = TriangleMesh::placed(
                q.positions().to_vec(),
                q.normals().map(<[Vec3]>::to_vec),
                q.uvs().map(<[[f64; 2]]>::to_vec),
                q.indices().to_vec(),
                &placement,
            )
            .unwrap();
            let baked = TriangleMesh::shapes(&Arc::new(baked));
            assert!((instance.area() - baked.iter().map(Shape::area).sum::<f64>()).abs() < 1e-12);
            let mut hits = 0;
            for _ in 0..2000 {
                let target = instance.bounds().centroid()
                    + (Vec3::new(rng.next_f64(), rng.next_f64(), rng.next_f64()) - 0.5) * instance.bounds().diagonal();
                let origin = target + crate::sampling::uniform_sphere(rng.next_2d()) * 4.0;
                let ray = Ray::segment(origin, target + (target - origin));
                let expected =
                    baked.iter().filter_map(|s| s.intersect(&ray).map(|t| (t, s))).min_by(|a, b| a.0.total_cmp(&b.0));
                let got = instance.intersect(&ray);
                assert_eq!(got.is_some(), expected.is_some());
                let (Some(t), Some((t_baked, s))) = (got, expected) else { continue };
                hits += 1;
                assert!((t - t_baked).abs() < 1e-9 * t, "{t} vs {t_baked}");
                let (h, hb) = (instance.surface(&ray, t), s.surface(&ray, t_baked));
                assert!((h.p - hb.p).length() < 1e-9 && (h.ng - hb.ng).length() < 1e-9, "{h:?} vs {hb:?}");
                assert!((h.uv[0] - hb.uv[0]).abs() < 1e-9 && (h.uv[1] - hb.uv[1]).abs() < 1e-9, "{h:?} vs {hb:?}");
                // The instance interpolates object-space normals and then maps the result, the
                // baked copy maps each vertex's normal first: the same under rigid placements,
                // within the normals' spread under stretched ones.
                let ns_tolerance = if placement == placed(false) { 1e-9 } else { 0.05 };
                assert!((h.ns - hb.ns).length() < ns_tolerance, "{h:?} vs {hb:?}");
                assert!(h.dpdu.cross(hb.dpdu).length() < 1e-9 * h.dpdu.length() * hb.dpdu.length());
            }
            assert!(hits > 300, "{hits} hits");
        }
    }

    #[test]
    fn placements_share_the_triangles() {
        let mesh = Arc::new(InstancedMesh::new(tilted_quad()).unwrap());
        let a = Instance::new(Arc::clone(&mesh), &placed(false)).unwrap();
        let b = Instance::new(Arc::clone(&mesh), &placed(true)).unwrap();
        assert!(Arc::ptr_eq(a.mesh(), b.mesh()) && Arc::ptr_eq(a.mesh().mesh(), b.mesh().mesh()));
        assert_eq!(Arc::strong_count(&mesh), 3);
    }
}

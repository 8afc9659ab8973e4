//! Triangle of a [`TriangleMesh`]: a shared pointer to the mesh and an index, so a triangle costs
//! 16 bytes and its vertex data is stored once per mesh, in world space.
//!
//! Intersection is the watertight test of Woop, Benthin and Wald (2013), "Watertight ray/triangle
//! intersection" (JCGT 2(1)), as in pbrt-v4 §6.5.3: the ray is sheared onto +z and the hit is
//! decided by the signs of three 2D edge functions, so a ray through a shared edge or vertex hits
//! at least one of the triangles that share it: no cracks between triangles.
//!
//! # Normals
//!
//! `ng` follows the counter-clockwise winding (`(p1 − p0) × (p2 − p0)`). When the mesh has
//! vertex normals, [`TriangleMesh::new`] already reordered each triangle's winding to agree with
//! them, so `ng` is on the side the modeller's normals call outside. `ns` is the interpolated
//! vertex normal, or `ng` where that is degenerate or points into the other hemisphere.
//!
//! # uv
//!
//! The interpolated vertex uvs; without them, the barycentric default of pbrt-v4
//! (`(0,0)`, `(1,0)`, `(1,1)` at the three vertices).

use super::mesh::TriangleMesh;
use super::rectangle::distance_to_segment;
use super::SurfaceHit;
use crate::geometry::{Aabb, Frame, Ray, Vec3};
use crate::sampling::uniform_triangle;
use std::sync::Arc;

#[derive(Clone, Debug)]
pub struct Triangle {
    mesh: Arc<TriangleMesh>,
    index: u32,
}

impl Triangle {
    /// The caller guarantees `index < mesh.indices().len()`; the mesh guarantees that its indices
    /// are in range.
    pub(super) fn new(mesh: Arc<TriangleMesh>, index: u32) -> Self {
        Self { mesh, index }
    }

    /// The mesh this triangle belongs to.
    pub fn mesh(&self) -> &Arc<TriangleMesh> {
        &self.mesh
    }

    /// The triangle's index in its mesh.
    pub fn index(&self) -> usize {
        self.index as usize
    }

    #[inline]
    fn vertex_indices(&self) -> [usize; 3] {
        self.mesh.indices()[self.index as usize].map(|i| i as usize)
    }

    /// World-space corners, in winding order.
    #[inline]
    pub fn vertices(&self) -> [Vec3; 3] {
        let positions = self.mesh.positions();
        self.vertex_indices().map(|i| positions[i])
    }

    /// `None` for a degenerate triangle (no plane).
    pub fn supporting_plane(&self) -> Option<(Vec3, Vec3)> {
        let [a, b, c] = self.vertices();
        let normal = (b - a).cross(c - a).try_normalize()?;
        Some((a, normal))
    }

    pub fn bounds(&self) -> Aabb {
        let [a, b, c] = self.vertices();
        Aabb::new(a, b).grow(c)
    }

    #[inline]
    pub fn intersect(&self, ray: &Ray) -> Option<f64> {
        let [p0, p1, p2] = self.vertices();
        // Translate to the ray origin, permute so the largest direction component is z.
        let d = ray.dir;
        let kz = largest_axis(d.abs());
        let (kx, ky) = ((kz + 1) % 3, (kz + 2) % 3);
        let permute = |v: Vec3| Vec3::new(v[kx], v[ky], v[kz]);
        let d = permute(d);
        let (mut a, mut b, mut c) = (permute(p0 - ray.origin), permute(p1 - ray.origin), permute(p2 - ray.origin));
        // Shear so the ray runs along +z; z is scaled later, only if the 2D test passes.
        let (sx, sy, sz) = (-d.x / d.z, -d.y / d.z, 1.0 / d.z);
        for v in [&mut a, &mut b, &mut c] {
            v.x += sx * v.z;
            v.y += sy * v.z;
        }
        // Edge functions: twice the signed areas of the sub-triangles opposite each vertex.
        let e0 = b.x * c.y - b.y * c.x;
        let e1 = c.x * a.y - c.y * a.x;
        let e2 = a.x * b.y - a.y * b.x;
        if (e0 < 0.0 || e1 < 0.0 || e2 < 0.0) && (e0 > 0.0 || e1 > 0.0 || e2 > 0.0) {
            return None;
        }
        let det = e0 + e1 + e2;
        if det == 0.0 {
            return None;
        }
        // t = t_scaled / det, with t_scaled and det of the same sign when t > 0. The segment
        // bound is checked on t itself, after the division, so that `t_max = t` (as handed back
        // by the BVH) is inclusive to the last bit.
        let t_scaled = (e0 * a.z + e1 * b.z + e2 * c.z) * sz;
        if (det > 0.0) != (t_scaled > 0.0) || t_scaled == 0.0 {
            return None;
        }
        let t = t_scaled / det;
        (t > 0.0 && t <= ray.t_max).then_some(t)
    }

    /// Barycentric coordinates of the projection of `p` onto the triangle's plane.
    fn barycentrics(&self, p: Vec3) -> [f64; 3] {
        let [p0, p1, p2] = self.vertices();
        let (v0, v1, v2) = (p1 - p0, p2 - p0, p - p0);
        let (d00, d01, d11) = (v0.dot(v0), v0.dot(v1), v1.dot(v1));
        let (d20, d21) = (v2.dot(v0), v2.dot(v1));
        let denom = d00 * d11 - d01 * d01;
        let b1 = (d11 * d20 - d01 * d21) / denom;
        let b2 = (d00 * d21 - d01 * d20) / denom;
        [1.0 - b1 - b2, b1, b2]
    }

    /// Unit normal along the winding.
    fn geometric_normal(&self) -> Vec3 {
        let [p0, p1, p2] = self.vertices();
        (p1 - p0).cross(p2 - p0).normalize()
    }

    pub fn surface(&self, ray: &Ray, t: f64) -> SurfaceHit {
        let [p0, p1, p2] = self.vertices();
        let b = self.barycentrics(ray.at(t)).map(|x| x.max(0.0));
        let sum = b[0] + b[1] + b[2];
        let b = b.map(|x| x / sum);
        let ng = self.geometric_normal();
        let idx = self.vertex_indices();
        let ns = self
            .mesh
            .normals()
            .map(|n| (n[idx[0]] * b[0] + n[idx[1]] * b[1] + n[idx[2]] * b[2]).normalize_or_zero())
            .filter(|ns| ns.dot(ng) > 0.0)
            .unwrap_or(ng);
        let uvs = match self.mesh.uvs() {
            Some(uv) => idx.map(|i| uv[i]),
            None => [[0.0, 0.0], [1.0, 0.0], [1.0, 1.0]],
        };
        let uv = [
            b[0] * uvs[0][0] + b[1] * uvs[1][0] + b[2] * uvs[2][0],
            b[0] * uvs[0][1] + b[1] * uvs[1][1] + b[2] * uvs[2][1],
        ];
        SurfaceHit { p: p0 * b[0] + p1 * b[1] + p2 * b[2], ng, ns, uv, dpdu: dpdu([p0, p1, p2], uvs, ng) }
    }

    pub fn area(&self) -> f64 {
        let [p0, p1, p2] = self.vertices();
        0.5 * (p1 - p0).cross(p2 - p0).length()
    }

    pub fn sample_area(&self, u: [f64; 2]) -> (Vec3, Vec3) {
        let [p0, p1, p2] = self.vertices();
        let [b0, b1, b2] = uniform_triangle(u);
        (p0 * b0 + p1 * b1 + p2 * b2, self.geometric_normal())
    }

    /// Signed distance to the plane where the point projects inside the triangle, else the
    /// (positive) distance to the nearest edge.
    pub fn surface_function(&self, p: Vec3) -> f64 {
        let [p0, p1, p2] = self.vertices();
        let b = self.barycentrics(p);
        if b.iter().all(|&x| x >= 0.0) {
            return (p - p0).dot(self.geometric_normal());
        }
        [(p0, p1 - p0), (p1, p2 - p1), (p2, p0 - p2)]
            .into_iter()
            .map(|(start, edge)| distance_to_segment(p, start, edge))
            .fold(f64::INFINITY, f64::min)
    }
}

fn largest_axis(v: Vec3) -> usize {
    if v.x >= v.y && v.x >= v.z {
        0
    } else if v.y >= v.z {
        1
    } else {
        2
    }
}

/// `∂p/∂u` from the vertex uvs (pbrt-v4 §6.5.3): solve `[dp02 dp12] = [duv02 duv12]ᵀ·[dpdu dpdv]`.
/// Degenerate uvs (a zero-area uv triangle) fall back to a tangent of `ng`'s frame.
fn dpdu(p: [Vec3; 3], uv: [[f64; 2]; 3], ng: Vec3) -> Vec3 {
    let duv02 = [uv[0][0] - uv[2][0], uv[0][1] - uv[2][1]];
    let duv12 = [uv[1][0] - uv[2][0], uv[1][1] - uv[2][1]];
    let (dp02, dp12) = (p[0] - p[2], p[1] - p[2]);
    let det = duv02[0] * duv12[1] - duv02[1] * duv12[0];
    let dpdu = (dp02 * duv12[1] - dp12 * duv02[1]) / det;
    let usable = det.abs() > 1e-12 * (duv02[0].abs() + duv02[1].abs()) * (duv12[0].abs() + duv12[1].abs())
        && dpdu.is_finite()
        && dpdu.cross(ng).length_squared() > 1e-24 * dpdu.length_squared();
    if usable {
        dpdu
    } else {
        Frame::from_normal(ng).s
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::shape::Shape;

    fn mesh(positions: Vec<Vec3>, indices: Vec<[u32; 3]>) -> Vec<Shape> {
        TriangleMesh::shapes(&Arc::new(TriangleMesh::new(positions, None, None, indices).unwrap()))
    }

    #[test]
    fn hits_inside_misses_outside_and_reports_t() {
        let tri =
            &mesh(vec![Vec3::new(0.0, 0.0, 1.0), Vec3::new(1.0, 0.0, 1.0), Vec3::new(0.0, 1.0, 1.0)], vec![[0, 1, 2]])
                [0];
        let ray = Ray::new(Vec3::new(0.25, 0.25, 0.0), Vec3::Z, 10.0);
        assert_eq!(tri.intersect(&ray), Some(1.0));
        assert_eq!(tri.intersect(&Ray { t_max: 0.99, ..ray }), None);
        assert_eq!(tri.intersect(&Ray::new(Vec3::new(0.75, 0.75, 0.0), Vec3::Z, 10.0)), None);
        assert_eq!(tri.intersect(&Ray::new(Vec3::new(0.25, 0.25, 2.0), -Vec3::Z, 10.0)), Some(1.0), "two-sided");
        let h = tri.surface(&ray, 1.0);
        assert_eq!(h.ng, Vec3::Z, "counter-clockwise winding");
        assert!((h.uv[0] - 0.5).abs() < 1e-12 && (h.uv[1] - 0.25).abs() < 1e-12, "default uvs: (b1 + b2, b2)");
        assert!((tri.area() - 0.5).abs() < 1e-15);
    }

    #[test]
    fn shared_edges_and_vertices_are_watertight() {
        // A flat hexagonal fan, in a tilted plane, around an interior vertex: rays through the
        // centre and through points of the shared spokes must hit at least one triangle.
        let centre = Vec3::new(0.1, -0.2, 0.3);
        let (a, b) = (Vec3::new(0.9, 0.3, -0.2), Vec3::new(-0.1, 0.5, 0.8));
        let mut positions = vec![centre];
        let corners: Vec<Vec3> = (0..6)
            .map(|k| {
                let (s, c) = (std::f64::consts::TAU * k as f64 / 6.0 + 0.1).sin_cos();
                centre + a * c + b * s
            })
            .collect();
        positions.extend(&corners);
        let fan = mesh(positions, (0..6).map(|k| [0, 1 + k, 1 + (k + 1) % 6]).collect());
        let mut rng = crate::sampling::Rng::new(3);
        for i in 0..20_000 {
            let target = if i % 2 == 0 { centre } else { centre.lerp(corners[i % 6], rng.next_f64()) };
            let origin = target + crate::sampling::uniform_sphere(rng.next_2d()) * 3.0;
            let ray = Ray::segment(origin, target + (target - origin));
            assert!(fan.iter().any(|t| t.intersect(&ray).is_some()), "crack at {target} from {origin}");
        }
    }

    #[test]
    fn surface_function_sees_the_triangle_not_its_plane() {
        let tri = &mesh(vec![Vec3::ZERO, Vec3::X, Vec3::Y], vec![[0, 1, 2]])[0];
        assert_eq!(tri.surface_function(Vec3::new(0.2, 0.2, -0.5)), -0.5);
        assert_eq!(tri.surface_function(Vec3::new(0.2, 0.2, 0.5)), 0.5);
        assert!((tri.surface_function(Vec3::new(-1.0, 0.5, -1.0)) - 2f64.sqrt()).abs() < 1e-15);
    }
}

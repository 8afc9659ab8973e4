//! Rectangle, or any parallelogram `corner + a·edge_u + b·edge_v`, `a, b ∈ [0, 1]`, baked into
//! world space (an affine map keeps a parallelogram a parallelogram, and area sampling uniform).
//!
//! The outward normal is `edge_u × edge_v` (right-hand rule, after the transform).
//!
//! # uv
//!
//! `uv = (a, b) ∈ [0, 1]²`: `u` runs along `edge_u` from the corner, `v` along `edge_v`.

use super::{check, ShapeError, SurfaceHit};
use crate::geometry::{Aabb, Ray, Vec3};
use crate::transform::Transform;

#[derive(Clone, Debug)]
pub struct Rectangle {
    corner: Vec3,
    edge_u: Vec3,
    edge_v: Vec3,
    /// Unit outward normal.
    normal: Vec3,
    /// Dual vectors: `a = (p − corner)·dual_u`, `b = (p − corner)·dual_v` for `p` in the plane.
    dual_u: Vec3,
    dual_v: Vec3,
    area: f64,
}

impl Rectangle {
    /// The parallelogram with a corner at `corner`.
    pub fn new(corner: Vec3, edge_u: Vec3, edge_v: Vec3, transform: &Transform) -> Result<Self, ShapeError> {
        const NAME: &str = "rectangle";
        let corner = check::point(NAME, "corner", corner)?;
        let edge_u = check::point(NAME, "edge_u", edge_u)?;
        let edge_v = check::point(NAME, "edge_v", edge_v)?;
        check::transform(NAME, transform)?;
        let (eu, ev) = (transform.vector(edge_u), transform.vector(edge_v));
        let n = eu.cross(ev);
        let n2 = n.length_squared();
        // Relative test: edges parallel to within rounding leave a meaningless area. Written so
        // that a NaN or infinite product counts as degenerate.
        let has_area = n2.is_finite() && n2 > 1e-24 * eu.length_squared() * ev.length_squared();
        if !has_area {
            return Err(ShapeError::DegenerateRectangle { edge_u, edge_v });
        }
        Ok(Self {
            corner: transform.point(corner),
            edge_u: eu,
            edge_v: ev,
            normal: n / n2.sqrt(),
            // From p − c = a·eu + b·ev: a = (p − c)·(ev × n)/|n|², b = (p − c)·(n × eu)/|n|².
            dual_u: ev.cross(n) / n2,
            dual_v: n.cross(eu) / n2,
            area: n2.sqrt(),
        })
    }

    /// The parallelogram centred on `centre`.
    pub fn centred(centre: Vec3, edge_u: Vec3, edge_v: Vec3, transform: &Transform) -> Result<Self, ShapeError> {
        Self::new(centre - 0.5 * (edge_u + edge_v), edge_u, edge_v, transform)
    }

    pub fn bounds(&self) -> Aabb {
        let (c, u, v) = (self.corner, self.edge_u, self.edge_v);
        Aabb::new(c, c + u).grow(c + v).grow(c + u + v)
    }

    /// The parallelogram coordinates `(a, b)` of a point of the plane.
    #[inline]
    fn coordinates(&self, p: Vec3) -> (f64, f64) {
        let q = p - self.corner;
        (q.dot(self.dual_u), q.dot(self.dual_v))
    }

    #[inline]
    pub fn intersect(&self, ray: &Ray) -> Option<f64> {
        let cos = ray.dir.dot(self.normal);
        if cos == 0.0 {
            return None;
        }
        let t = (self.corner - ray.origin).dot(self.normal) / cos;
        if !(t > 0.0 && t <= ray.t_max) {
            return None;
        }
        let (a, b) = self.coordinates(ray.at(t));
        ((0.0..=1.0).contains(&a) && (0.0..=1.0).contains(&b)).then_some(t)
    }

    pub fn surface(&self, ray: &Ray, t: f64) -> SurfaceHit {
        let (a, b) = self.coordinates(ray.at(t));
        let (a, b) = (a.clamp(0.0, 1.0), b.clamp(0.0, 1.0));
        SurfaceHit {
            p: self.corner + self.edge_u * a + self.edge_v * b,
            ng: self.normal,
            ns: self.normal,
            uv: [a, b],
            dpdu: self.edge_u,
        }
    }

    pub fn area(&self) -> f64 {
        self.area
    }

    pub fn sample_area(&self, u: [f64; 2]) -> (Vec3, Vec3) {
        (self.corner + self.edge_u * u[0] + self.edge_v * u[1], self.normal)
    }

    pub fn supporting_plane(&self) -> (Vec3, Vec3) {
        (self.corner, self.normal)
    }

    /// Signed distance to the plane where the point projects inside, else the (positive) distance
    /// to the nearest edge.
    pub fn surface_function(&self, p: Vec3) -> f64 {
        let h = (p - self.corner).dot(self.normal);
        let (a, b) = self.coordinates(p);
        if (0.0..=1.0).contains(&a) && (0.0..=1.0).contains(&b) {
            return h;
        }
        let (c, u, v) = (self.corner, self.edge_u, self.edge_v);
        [(c, u), (c, v), (c + u, v), (c + v, u)]
            .into_iter()
            .map(|(start, edge)| distance_to_segment(p, start, edge))
            .fold(f64::INFINITY, f64::min)
    }
}

/// Distance from `p` to the segment `start + s·edge`, `s ∈ [0, 1]`.
pub(super) fn distance_to_segment(p: Vec3, start: Vec3, edge: Vec3) -> f64 {
    let s = ((p - start).dot(edge) / edge.length_squared()).clamp(0.0, 1.0);
    (p - start - edge * s).length()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn square() -> Rectangle {
        Rectangle::centred(
            Vec3::new(0.0, 0.0, 2.0),
            Vec3::new(2.0, 0.0, 0.0),
            Vec3::new(0.0, 4.0, 0.0),
            &Transform::IDENTITY,
        )
        .unwrap()
    }

    #[test]
    fn hits_inside_misses_outside() {
        let r = square();
        let ray = Ray::new(Vec3::new(0.5, 1.0, 0.0), Vec3::Z, 10.0);
        assert_eq!(r.intersect(&ray), Some(2.0));
        let h = r.surface(&ray, 2.0);
        assert_eq!(h.uv, [0.75, 0.75]);
        assert_eq!(h.ng, Vec3::Z, "edge_u × edge_v");
        assert_eq!(r.intersect(&Ray::new(Vec3::new(1.01, 0.0, 0.0), Vec3::Z, 10.0)), None);
        assert_eq!(r.intersect(&Ray::new(Vec3::new(0.0, 0.0, 5.0), -Vec3::Z, 10.0)), Some(3.0));
        assert_eq!(r.intersect(&Ray::new(Vec3::new(0.0, 0.0, 0.0), Vec3::X, 10.0)), None, "edge-on");
        assert_eq!(r.area(), 8.0);
    }

    #[test]
    fn surface_function_changes_sign_only_through_the_rectangle() {
        let r = square();
        assert_eq!(r.surface_function(Vec3::new(0.0, 0.0, 1.0)), -1.0);
        assert_eq!(r.surface_function(Vec3::new(0.0, 0.0, 2.5)), 0.5);
        // Beside the rectangle: positive on both sides of its plane.
        assert_eq!(r.surface_function(Vec3::new(4.0, 0.0, 1.0)), 10f64.sqrt());
        assert_eq!(r.surface_function(Vec3::new(4.0, 0.0, 3.0)), 10f64.sqrt());
    }

    #[test]
    fn degenerate_edges_are_rejected() {
        let e = Rectangle::new(Vec3::ZERO, Vec3::X, Vec3::X * 2.0, &Transform::IDENTITY).unwrap_err();
        assert!(e.to_string().contains("parallel"), "{e}");
        assert!(Rectangle::new(Vec3::ZERO, Vec3::ZERO, Vec3::X, &Transform::IDENTITY).is_err());
        assert!(Rectangle::new(Vec3::NAN, Vec3::Y, Vec3::X, &Transform::IDENTITY).is_err());
    }
}

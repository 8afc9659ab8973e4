//! Infinite plane, baked into world space (an affine map keeps a plane a plane).
//!
//! # uv
//!
//! World-length coordinates along two orthonormal tangent axes, measured from the plane's
//! reference point, so a grid texture has scene-unit spacing whatever the transform's scale. The
//! axes are those of [`Frame::from_normal`] in object space, carried by the transform (so rotating
//! the plane about its normal rotates the grid) and re-orthonormalised.
//!
//! The plane has infinite area: it cannot be light-sampled, and its bounds are infinite except
//! along an axis it is perpendicular to. The BVH tests such unbounded shapes on every query.

use super::{check, ShapeError, SurfaceHit};
use crate::geometry::{Aabb, Frame, Ray, Vec3};
use crate::transform::Transform;

#[derive(Clone, Debug)]
pub struct Plane {
    point: Vec3,
    /// Unit outward normal, and the two tangent axes of uv.
    frame: Frame,
}

impl Plane {
    pub fn new(point: Vec3, normal: Vec3, transform: &Transform) -> Result<Self, ShapeError> {
        const NAME: &str = "plane";
        let point = check::point(NAME, "point", point)?;
        let normal = check::direction(NAME, "normal", normal)?;
        check::transform(NAME, transform)?;
        let local = Frame::from_normal(normal);
        let n = transform.normal(normal).normalize();
        let s = transform.vector(local.s);
        let s = (s - n * n.dot(s)).normalize();
        Ok(Self { point: transform.point(point), frame: Frame { s, t: n.cross(s), n } })
    }

    /// The world point with uv coordinates `uv`.
    pub fn point_at(&self, uv: [f64; 2]) -> Vec3 {
        self.point + self.frame.s * uv[0] + self.frame.t * uv[1]
    }

    /// Unit outward normal.
    pub fn normal(&self) -> Vec3 {
        self.frame.n
    }

    /// Infinite except along an axis the plane is perpendicular to, where it is flat.
    pub fn bounds(&self) -> Aabb {
        let mut b = Aabb { min: Vec3::NEG_INFINITY, max: Vec3::INFINITY };
        let n = self.frame.n;
        for axis in 0..3 {
            let others = (0..3).filter(|&k| k != axis);
            if others.into_iter().all(|k| n[k] == 0.0) {
                b.min[axis] = self.point[axis];
                b.max[axis] = self.point[axis];
            }
        }
        b
    }

    #[inline]
    pub fn intersect(&self, ray: &Ray) -> Option<f64> {
        let cos = ray.dir.dot(self.frame.n);
        // A ray parallel to (or lying in) the plane never crosses it.
        if cos == 0.0 {
            return None;
        }
        let t = (self.point - ray.origin).dot(self.frame.n) / cos;
        (t > 0.0 && t <= ray.t_max).then_some(t)
    }

    pub fn surface(&self, ray: &Ray, t: f64) -> SurfaceHit {
        let p = ray.at(t);
        let p = p - self.frame.n * (p - self.point).dot(self.frame.n);
        let local = self.frame.to_local(p - self.point);
        SurfaceHit { p, ng: self.frame.n, ns: self.frame.n, uv: [local.x, local.y], dpdu: self.frame.s }
    }

    pub fn area(&self) -> f64 {
        f64::INFINITY
    }

    /// Not samplable: returns the reference point and the normal. Check `area().is_finite()`.
    pub fn sample_area(&self, _u: [f64; 2]) -> (Vec3, Vec3) {
        (self.point, self.frame.n)
    }

    pub fn supporting_plane(&self) -> (Vec3, Vec3) {
        (self.point, self.frame.n)
    }

    /// The exact signed distance: positive on the normal's side.
    pub fn surface_function(&self, p: Vec3) -> f64 {
        (p - self.point).dot(self.frame.n)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn floor_hits_uv_and_bounds() {
        let floor = Plane::new(Vec3::new(0.0, -1.0, 0.0), Vec3::Y, &Transform::IDENTITY).unwrap();
        let ray = Ray::new(Vec3::new(2.0, 3.0, -5.0), -Vec3::Y, 10.0);
        assert_eq!(floor.intersect(&ray), Some(4.0));
        assert_eq!(floor.intersect(&Ray { t_max: 3.5, ..ray }), None);
        assert_eq!(floor.intersect(&Ray::new(Vec3::ZERO, Vec3::X, 10.0)), None, "parallel");
        assert_eq!(floor.intersect(&Ray::new(Vec3::ZERO, Vec3::Y, 10.0)), None, "facing away");
        let from_below = Ray::new(Vec3::new(0.0, -3.0, 0.0), Vec3::Y, 10.0);
        assert_eq!(floor.intersect(&from_below), Some(2.0), "two-sided");
        // uv moves one unit per scene unit.
        let a = floor.surface(&ray, 4.0);
        let b = floor.surface(&Ray::new(Vec3::new(3.0, 3.0, -5.0), -Vec3::Y, 10.0), 4.0);
        assert!(((a.uv[0] - b.uv[0]).hypot(a.uv[1] - b.uv[1]) - 1.0).abs() < 1e-12);
        assert_eq!(a.ng, Vec3::Y);
        let bounds = floor.bounds();
        assert_eq!((bounds.min.y, bounds.max.y), (-1.0, -1.0));
        assert!(bounds.min.x.is_infinite() && bounds.max.z.is_infinite());
        assert_eq!(floor.surface_function(Vec3::new(5.0, 2.0, 1.0)), 3.0);
    }

    #[test]
    fn scaled_plane_keeps_unit_uv_spacing() {
        let t =
            Transform::scale(Vec3::new(10.0, 10.0, 1.0)).unwrap().then(&Transform::rotate_deg(Vec3::Z, 30.0).unwrap());
        let p = Plane::new(Vec3::ZERO, Vec3::Z, &t).unwrap();
        let hit = |x: f64| p.surface(&Ray::new(Vec3::new(x, 0.0, 1.0), -Vec3::Z, 2.0), 1.0).uv;
        let (a, b) = (hit(0.0), hit(1.0));
        assert!(((a[0] - b[0]).hypot(a[1] - b[1]) - 1.0).abs() < 1e-12);
        // The grid turned with the transform: +x maps to the rotated s axis.
        assert!((p.frame.s - Vec3::new(30f64.to_radians().cos(), 30f64.to_radians().sin(), 0.0)).length() < 1e-12);
        assert!(p.area().is_infinite());
    }
}

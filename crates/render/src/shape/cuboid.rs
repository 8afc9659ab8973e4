//! Cuboid: an axis-aligned box in object space; any orientation, and a parallelepiped under
//! shear, through its transform. Intersected by the slab method (Kay & Kajiya 1986) in object
//! space.
//!
//! # uv
//!
//! Per face, `[0, 1]²` across the face: on the faces perpendicular to object axis `k`, `u` runs
//! from `min` to `max` along axis `k + 1` and `v` along axis `k + 2` (mod 3), so the ±x faces use
//! (y, z), the ±y faces (z, x) and the ±z faces (x, y). `dpdu` is the face's `u` edge.

use super::stretch::AreaStretch;
use super::{check, ShapeError, SurfaceHit};
use crate::geometry::{Aabb, Ray, Vec3};
use crate::transform::Transform;

#[derive(Clone, Debug)]
pub struct Cuboid {
    to_world: Transform,
    min: Vec3,
    max: Vec3,
    min_stretch: f64,
    /// World area of one face perpendicular to each object axis.
    face_area: Vec3,
    /// World distance per unit of object-space distance across the faces perpendicular to each
    /// axis: `1 / |M⁻ᵀ e_k|`. Picks the face a hit is nearest to in world units.
    face_spacing: Vec3,
}

impl Cuboid {
    pub fn new(min: Vec3, max: Vec3, transform: &Transform) -> Result<Self, ShapeError> {
        const NAME: &str = "cuboid";
        let min = check::point(NAME, "min", min)?;
        let max = check::point(NAME, "max", max)?;
        if !min.cmplt(max).all() {
            return Err(ShapeError::EmptyCuboid { min, max });
        }
        check::transform(NAME, transform)?;
        let stretch = AreaStretch::new(transform);
        let size = max - min;
        Ok(Self {
            to_world: *transform,
            min,
            max,
            min_stretch: transform.scale_bounds().0,
            face_area: Vec3::new(
                size.y * size.z * stretch.factor(Vec3::X),
                size.z * size.x * stretch.factor(Vec3::Y),
                size.x * size.y * stretch.factor(Vec3::Z),
            ),
            face_spacing: Vec3::new(
                transform.normal(Vec3::X).length(),
                transform.normal(Vec3::Y).length(),
                transform.normal(Vec3::Z).length(),
            )
            .recip(),
        })
    }

    pub fn bounds(&self) -> Aabb {
        self.to_world.bounds(&Aabb { min: self.min, max: self.max })
    }

    /// The parametric interval `[near, far]` of the line inside the (closed) box. A direction
    /// component of zero makes that slab either everything (origin within it, faces included) or
    /// nothing; handled explicitly because `0·∞` would be NaN. So a ray sliding along a face is
    /// inside the closed box and hits the face it runs into, like a tangent ray grazing a sphere.
    /// The three slabs are computed together (one vector reciprocal) and combined by selects,
    /// with no early exit: a ray's hit or miss is not predictable, so branches per axis cost more
    /// than the arithmetic they would skip.
    #[inline]
    fn slabs(&self, o: Vec3, d: Vec3) -> Option<(f64, f64)> {
        let inv = d.recip();
        let (t0, t1) = ((self.min - o) * inv, (self.max - o) * inv);
        let (mut near, mut far) = (f64::NEG_INFINITY, f64::INFINITY);
        for k in 0..3 {
            let (enter, exit) = if d[k] != 0.0 {
                (t0[k].min(t1[k]), t0[k].max(t1[k]))
            } else if (self.min[k]..=self.max[k]).contains(&o[k]) {
                (f64::NEG_INFINITY, f64::INFINITY)
            } else {
                (f64::INFINITY, f64::NEG_INFINITY)
            };
            near = near.max(enter);
            far = far.min(exit);
        }
        (near <= far).then_some((near, far))
    }

    #[inline]
    pub fn intersect(&self, ray: &Ray) -> Option<f64> {
        let o = self.to_world.inverse_point(ray.origin);
        let d = self.to_world.inverse_vector(ray.dir);
        super::quadratic::nearest_ahead(self.slabs(o, d)?, ray.t_max)
    }

    pub fn surface(&self, ray: &Ray, t: f64) -> SurfaceHit {
        let o = self.to_world.inverse_point(ray.origin);
        let d = self.to_world.inverse_vector(ray.dir);
        let mut q = (o + d * t).clamp(self.min, self.max);
        // The face nearest in world distance.
        let to_min = (q - self.min) * self.face_spacing;
        let to_max = (self.max - q) * self.face_spacing;
        let k = argmin(to_min.min(to_max));
        let outward = if to_max[k] < to_min[k] { 1.0 } else { -1.0 };
        q[k] = if outward > 0.0 { self.max[k] } else { self.min[k] };
        let mut n = Vec3::ZERO;
        n[k] = outward;
        let (i, j) = ((k + 1) % 3, (k + 2) % 3);
        let size = self.max - self.min;
        let mut edge = Vec3::ZERO;
        edge[i] = size[i];
        let ng = self.to_world.normal(n).normalize();
        SurfaceHit {
            p: self.to_world.point(q),
            ng,
            ns: ng,
            uv: [(q[i] - self.min[i]) / size[i], (q[j] - self.min[j]) / size[j]],
            dpdu: self.to_world.vector(edge),
        }
    }

    pub fn area(&self) -> f64 {
        2.0 * (self.face_area.x + self.face_area.y + self.face_area.z)
    }

    /// A face pair chosen in proportion to its area, a side by a bit of the first coordinate, then
    /// a uniform point on it (faces are planar, so uniform in object space is uniform in world).
    pub fn sample_area(&self, u: [f64; 2]) -> (Vec3, Vec3) {
        let total = self.face_area.x + self.face_area.y + self.face_area.z;
        let mut x = u[0] * total;
        let mut k = 0;
        while k < 2 && x >= self.face_area[k] {
            x -= self.face_area[k];
            k += 1;
        }
        // Reuse the remaining fraction of u[0] for the side and the first face coordinate.
        let f = (x / self.face_area[k]).clamp(0.0, 1.0);
        let (side, a) = if f < 0.5 { (-1.0, 2.0 * f) } else { (1.0, 2.0 * f - 1.0) };
        let (i, j) = ((k + 1) % 3, (k + 2) % 3);
        let mut q = Vec3::ZERO;
        q[k] = if side > 0.0 { self.max[k] } else { self.min[k] };
        q[i] = self.min[i] + a.min(1.0) * (self.max[i] - self.min[i]);
        q[j] = self.min[j] + u[1] * (self.max[j] - self.min[j]);
        let mut n = Vec3::ZERO;
        n[k] = side;
        (self.to_world.point(q), self.to_world.normal(n).normalize())
    }

    /// The exact object-space box distance (Quílez), times `σ_min`.
    pub fn surface_function(&self, p: Vec3) -> f64 {
        let q = self.to_world.inverse_point(p);
        let centre = 0.5 * (self.min + self.max);
        let half = 0.5 * (self.max - self.min);
        let e = (q - centre).abs() - half;
        let outside = e.max(Vec3::ZERO).length();
        let inside = e.max_element().min(0.0);
        (outside + inside) * self.min_stretch
    }
}

fn argmin(v: Vec3) -> usize {
    if v.x <= v.y && v.x <= v.z {
        0
    } else if v.y <= v.z {
        1
    } else {
        2
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn cube() -> Cuboid {
        Cuboid::new(Vec3::splat(-1.0), Vec3::splat(1.0), &Transform::IDENTITY).unwrap()
    }

    #[test]
    fn hits_faces_from_outside_and_inside() {
        let c = cube();
        let ray = Ray::new(Vec3::new(0.5, -0.25, -5.0), Vec3::Z, 10.0);
        assert_eq!(c.intersect(&ray), Some(4.0));
        let h = c.surface(&ray, 4.0);
        assert_eq!(h.ng, -Vec3::Z);
        assert_eq!(h.uv, [0.75, 0.375], "±z faces use (x, y)");
        assert_eq!(c.intersect(&Ray::new(Vec3::ZERO, Vec3::X, 10.0)), Some(1.0), "from inside");
        assert_eq!(c.intersect(&Ray::new(Vec3::ZERO, Vec3::X, 0.5)), None, "stops inside");
        assert_eq!(c.intersect(&Ray::new(Vec3::new(1.01, 0.0, -5.0), Vec3::Z, 10.0)), None);
        assert_eq!(c.area(), 24.0);
        assert_eq!(c.surface_function(Vec3::new(0.0, 3.0, 0.0)), 2.0);
        assert_eq!(c.surface_function(Vec3::new(0.0, 0.5, 0.0)), -0.5);
        assert_eq!(c.surface_function(Vec3::new(2.0, 2.0, 0.0)), 2f64.sqrt());
    }

    #[test]
    fn rotated_and_stretched_box() {
        // A 2×2×2 cube stretched to 4 along x, then turned 90° about z: extends 2 along y.
        let t =
            Transform::scale(Vec3::new(2.0, 1.0, 1.0)).unwrap().then(&Transform::rotate_deg(Vec3::Z, 90.0).unwrap());
        let c = Cuboid::new(Vec3::splat(-1.0), Vec3::splat(1.0), &t).unwrap();
        let ray = Ray::new(Vec3::new(0.0, -5.0, 0.0), Vec3::Y, 10.0);
        assert!((c.intersect(&ray).unwrap() - 3.0).abs() < 1e-12);
        assert!((c.surface(&ray, 3.0).ng + Vec3::Y).length() < 1e-12);
        assert!((c.bounds().max - Vec3::new(1.0, 2.0, 1.0)).length() < 1e-12);
        assert!((c.area() - 2.0 * (4.0 * 2.0 + 2.0 * 2.0 + 2.0 * 4.0)).abs() < 1e-12);
    }

    #[test]
    fn ray_in_a_face_plane_grazes_without_nan() {
        let c = cube();
        // Origin exactly in the y = ±1 face planes, moving parallel to them: the closed box is hit.
        assert_eq!(c.intersect(&Ray::new(Vec3::new(-5.0, 1.0, 0.0), Vec3::X, 10.0)), Some(4.0));
        assert_eq!(c.intersect(&Ray::new(Vec3::new(-5.0, -1.0, 0.0), Vec3::X, 10.0)), Some(4.0));
        assert_eq!(c.intersect(&Ray::new(Vec3::new(-5.0, 1.0 + 1e-12, 0.0), Vec3::X, 10.0)), None);
        assert_eq!(c.intersect(&Ray::new(Vec3::new(-5.0, 1.0 - 1e-12, 0.0), Vec3::X, 10.0)), Some(4.0));
        assert!(Cuboid::new(Vec3::ONE, Vec3::ONE, &Transform::IDENTITY).is_err());
    }
}

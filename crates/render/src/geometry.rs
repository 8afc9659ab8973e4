//! Rays (segments), bounding boxes and orthonormal frames in a region's flat world coordinates.

pub use glam::DVec3 as Vec3;

/// A segment `origin + t·dir` for `t ∈ [0, t_max]`; `dir` is unit length. A geodesic step's chord is a
/// ray with a finite `t_max`; a flat-space ray has `t_max = ∞`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Ray {
    pub origin: Vec3,
    pub dir: Vec3,
    pub t_max: f64,
}

impl Ray {
    pub fn new(origin: Vec3, dir: Vec3, t_max: f64) -> Self {
        Self { origin, dir, t_max }
    }

    /// The chord from `a` to `b`.
    pub fn segment(a: Vec3, b: Vec3) -> Self {
        let d = b - a;
        let len = d.length();
        let dir = if len > 0.0 { d / len } else { Vec3::Z };
        Self { origin: a, dir, t_max: len }
    }

    pub fn at(&self, t: f64) -> Vec3 {
        self.origin + self.dir * t
    }
}

/// Axis-aligned bounding box.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Aabb {
    pub min: Vec3,
    pub max: Vec3,
}

impl Aabb {
    pub const EMPTY: Aabb = Aabb { min: Vec3::splat(f64::INFINITY), max: Vec3::splat(f64::NEG_INFINITY) };

    pub fn new(a: Vec3, b: Vec3) -> Self {
        Self { min: a.min(b), max: a.max(b) }
    }

    pub fn union(&self, o: &Aabb) -> Aabb {
        Aabb { min: self.min.min(o.min), max: self.max.max(o.max) }
    }

    pub fn grow(&self, p: Vec3) -> Aabb {
        Aabb { min: self.min.min(p), max: self.max.max(p) }
    }

    pub fn centroid(&self) -> Vec3 {
        0.5 * (self.min + self.max)
    }

    pub fn diagonal(&self) -> Vec3 {
        self.max - self.min
    }

    pub fn is_empty(&self) -> bool {
        self.min.x > self.max.x || self.min.y > self.max.y || self.min.z > self.max.z
    }

    /// Distance from the point `p` to the box (0 inside it).
    pub fn distance_to(&self, p: Vec3) -> f64 {
        (self.min - p).max(p - self.max).max(Vec3::ZERO).length()
    }

    pub fn surface_area(&self) -> f64 {
        if self.is_empty() {
            return 0.0;
        }
        let d = self.diagonal();
        2.0 * (d.x * d.y + d.y * d.z + d.z * d.x)
    }

    /// Slab test: the parametric interval where `ray` is inside the box, clipped to `[0, t_max]`.
    /// `inv_dir` is `1 / ray.dir`, computed once per ray.
    #[inline]
    pub fn hit(&self, origin: Vec3, inv_dir: Vec3, t_max: f64) -> Option<f64> {
        let t0 = (self.min - origin) * inv_dir;
        let t1 = (self.max - origin) * inv_dir;
        let near = t0.min(t1).max_element().max(0.0);
        let far = t0.max(t1).min_element().min(t_max);
        // `<=` keeps flat boxes (a plane's zero-thickness bound) hittable.
        (near <= far).then_some(near)
    }
}

/// Right-handed orthonormal frame `(s, t, n)`: materials work with `n` as local +z.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Frame {
    pub s: Vec3,
    pub t: Vec3,
    pub n: Vec3,
}

impl Frame {
    /// A frame around the unit normal `n` (Duff et al. 2017, "Building an orthonormal basis, revisited").
    pub fn from_normal(n: Vec3) -> Self {
        let sign = 1.0f64.copysign(n.z);
        let a = -1.0 / (sign + n.z);
        let b = n.x * n.y * a;
        let s = Vec3::new(1.0 + sign * n.x * n.x * a, sign * b, -sign * n.x);
        let t = Vec3::new(b, sign + n.y * n.y * a, -n.y);
        Self { s, t, n }
    }

    pub fn to_local(&self, v: Vec3) -> Vec3 {
        Vec3::new(v.dot(self.s), v.dot(self.t), v.dot(self.n))
    }

    pub fn to_world(&self, v: Vec3) -> Vec3 {
        self.s * v.x + self.t * v.y + self.n * v.z
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn frame_is_orthonormal_and_round_trips() {
        for n in [Vec3::Z, -Vec3::Z, Vec3::new(0.3, -0.4, 0.5).normalize(), Vec3::new(0.0, -1.0, 1e-9).normalize()] {
            let f = Frame::from_normal(n);
            assert!((f.s.length() - 1.0).abs() < 1e-12 && (f.t.length() - 1.0).abs() < 1e-12);
            assert!(f.s.dot(f.t).abs() < 1e-12 && f.s.dot(f.n).abs() < 1e-12 && f.t.dot(f.n).abs() < 1e-12);
            assert!((f.s.cross(f.t) - f.n).length() < 1e-12, "right-handed");
            let v = Vec3::new(0.1, 0.7, -0.2);
            assert!((f.to_world(f.to_local(v)) - v).length() < 1e-12);
        }
    }

    #[test]
    fn slab_test_clips_to_segment() {
        let b = Aabb::new(Vec3::splat(-1.0), Vec3::splat(1.0));
        let o = Vec3::new(-5.0, 0.0, 0.0);
        let inv = Vec3::ONE / Vec3::X;
        assert_eq!(b.hit(o, inv, 10.0), Some(4.0));
        assert_eq!(b.hit(o, inv, 3.0), None, "segment ends before the box");
    }
}

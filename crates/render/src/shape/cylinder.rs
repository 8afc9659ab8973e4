//! Capped cylinder: the solid `ρ ≤ r, 0 ≤ z ≤ h` in a frame whose origin is the centre of the
//! base cap and whose z axis is the cylinder's axis; an elliptic cylinder under non-uniform scale.
//!
//! The solid is convex, so a ray's hits are the ends of one interval: the intersection of the
//! infinite cylinder's interval (a quadratic, solved as in [`super::quadratic`]) with the slab
//! between the caps. This handles the caps, rays along the axis, and rays starting inside alike.
//!
//! # uv
//!
//! Side: `u = φ / 2π` around the axis from the first tangent axis of
//! [`Frame::from_normal`](crate::geometry::Frame::from_normal)`(axis)`, `v = z / h` from the base.
//! Caps: as a [`super::Disk`], `u = φ / 2π`, `v = ρ / r`. `dpdu` points along increasing φ
//! everywhere (clamped to a tiny non-zero length at the cap centres).

use super::disk::{ellipse_half_extent, placement};
use super::quadratic::{centred_roots, nearest_ahead};
use super::stretch::AreaStretch;
use super::{azimuth, azimuthal_dpdu, check, ShapeError, SurfaceHit};
use crate::geometry::{Aabb, Ray, Vec3};
use crate::sampling::concentric_disk;
use crate::transform::Transform;
use std::f64::consts::{PI, TAU};

#[derive(Clone, Debug)]
pub struct Cylinder {
    /// The cylinder's frame (base centre at the origin, axis along +z) to world.
    to_world: Transform,
    radius: f64,
    height: f64,
    min_stretch: f64,
    stretch: AreaStretch,
    /// World areas of one cap and of the side.
    cap_area: f64,
    side_area: f64,
    /// World distance per unit object distance across the caps, `1 / |M⁻ᵀ ẑ|`: picks the part a
    /// hit is nearest to in world units. The side's varies with azimuth and is computed per hit.
    cap_spacing: f64,
}

impl Cylinder {
    pub fn new(base: Vec3, axis: Vec3, radius: f64, height: f64, transform: &Transform) -> Result<Self, ShapeError> {
        const NAME: &str = "cylinder";
        let base = check::point(NAME, "base", base)?;
        let axis = check::direction(NAME, "axis", axis)?;
        let radius = check::positive(NAME, "radius", radius)?;
        let height = check::positive(NAME, "height", height)?;
        check::transform(NAME, transform)?;
        let to_world = placement(base, axis).map_err(|_| ShapeError::InvalidTransform { shape: NAME })?.then(transform);
        let stretch = AreaStretch::new(&to_world);
        Ok(Self {
            to_world,
            radius,
            height,
            min_stretch: to_world.scale_bounds().0,
            stretch,
            cap_area: PI * radius * radius * stretch.factor(Vec3::Z),
            side_area: radius * height * stretch.unit_cylinder_side_area(),
            cap_spacing: 1.0 / to_world.normal(Vec3::Z).length(),
        })
    }

    /// Exact: the union of the bounds of the two cap ellipses.
    pub fn bounds(&self) -> Aabb {
        let half = ellipse_half_extent(&self.to_world, self.radius);
        let bottom = self.to_world.point(Vec3::ZERO);
        let top = self.to_world.point(Vec3::Z * self.height);
        Aabb { min: bottom.min(top) - half, max: bottom.max(top) + half }
    }

    /// The interval of the line `o + t·d` inside the solid cylinder.
    #[inline]
    fn interval(&self, o: Vec3, d: Vec3) -> Option<(f64, f64)> {
        // The slab 0 ≤ z ≤ h.
        let (z0, z1) = if d.z == 0.0 {
            if !(0.0..=self.height).contains(&o.z) {
                return None;
            }
            (f64::NEG_INFINITY, f64::INFINITY)
        } else {
            let (a, b) = (-o.z / d.z, (self.height - o.z) / d.z);
            (a.min(b), a.max(b))
        };
        // The infinite cylinder ρ ≤ r: a line along the axis is inside everywhere or nowhere.
        let (o2, d2) = (Vec3::new(o.x, o.y, 0.0), Vec3::new(d.x, d.y, 0.0));
        let (c0, c1) = if d2 == Vec3::ZERO {
            if o2.length_squared() > self.radius * self.radius {
                return None;
            }
            (f64::NEG_INFINITY, f64::INFINITY)
        } else {
            centred_roots(o2, d2, self.radius * self.radius)?
        };
        let (near, far) = (z0.max(c0), z1.min(c1));
        (near <= far).then_some((near, far))
    }

    #[inline]
    pub fn intersect(&self, ray: &Ray) -> Option<f64> {
        let o = self.to_world.inverse_point(ray.origin);
        let d = self.to_world.inverse_vector(ray.dir);
        nearest_ahead(self.interval(o, d)?, ray.t_max)
    }

    pub fn surface(&self, ray: &Ray, t: f64) -> SurfaceHit {
        let o = self.to_world.inverse_point(ray.origin);
        let d = self.to_world.inverse_vector(ray.dir);
        let mut q = o + d * t;
        q.z = q.z.clamp(0.0, self.height);
        let rho = q.x.hypot(q.y);
        let phi = azimuth(q.x, q.y);
        let (sin, cos) = phi.sin_cos();
        let radial = Vec3::new(cos, sin, 0.0);
        // The part nearest in world distance: object distances times world spacing.
        let side_spacing = 1.0 / self.to_world.normal(radial).length();
        let to_side = (self.radius - rho).abs() * side_spacing;
        let to_bottom = q.z * self.cap_spacing;
        let to_top = (self.height - q.z) * self.cap_spacing;
        let (n, uv, rho) = if to_side <= to_bottom.min(to_top) {
            (q.x, q.y) = (cos * self.radius, sin * self.radius);
            (radial, [phi / TAU, q.z / self.height], self.radius)
        } else {
            let rho = rho.min(self.radius);
            (q.x, q.y) = (cos * rho, sin * rho);
            let (z, n) = if to_bottom < to_top { (0.0, -Vec3::Z) } else { (self.height, Vec3::Z) };
            q.z = z;
            (n, [phi / TAU, rho / self.radius], rho)
        };
        let ng = self.to_world.normal(n).normalize();
        SurfaceHit {
            p: self.to_world.point(q),
            ng,
            ns: ng,
            uv,
            dpdu: self.to_world.vector(azimuthal_dpdu(phi, rho, self.radius)),
        }
    }

    pub fn area(&self) -> f64 {
        2.0 * self.cap_area + self.side_area
    }

    /// A part chosen in proportion to its area by the first coordinate (rescaled for reuse), then
    /// a uniform point on it; the side uses rejection when non-uniformly stretched.
    pub fn sample_area(&self, u: [f64; 2]) -> (Vec3, Vec3) {
        let x = u[0] * self.area();
        let (point, n) = if x < self.side_area {
            let u = [x / self.side_area, u[1]];
            self.stretch.sample(u, |u| {
                let (sin, cos) = (TAU * u[0]).sin_cos();
                let n = Vec3::new(cos, sin, 0.0);
                ((n * self.radius + Vec3::Z * (u[1] * self.height), n), n)
            })
        } else {
            let x = x - self.side_area;
            let top = x >= self.cap_area;
            let f = ((x - if top { self.cap_area } else { 0.0 }) / self.cap_area).clamp(0.0, 1.0);
            let [a, b] = concentric_disk([f, u[1]]);
            let (z, n) = if top { (self.height, Vec3::Z) } else { (0.0, -Vec3::Z) };
            (Vec3::new(a * self.radius, b * self.radius, z), n)
        };
        (self.to_world.point(point), self.to_world.normal(n).normalize())
    }

    /// The exact object-space distance to the capped cylinder (Quílez), times `σ_min`.
    pub fn surface_function(&self, p: Vec3) -> f64 {
        let q = self.to_world.inverse_point(p);
        let half = 0.5 * self.height;
        let dr = q.x.hypot(q.y) - self.radius;
        let dz = (q.z - half).abs() - half;
        let outside = dr.max(0.0).hypot(dz.max(0.0));
        let inside = dr.max(dz).min(0.0);
        (outside + inside) * self.min_stretch
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn upright() -> Cylinder {
        Cylinder::new(Vec3::new(0.0, 0.0, 1.0), Vec3::Z, 1.0, 2.0, &Transform::IDENTITY).unwrap()
    }

    #[test]
    fn hits_side_caps_and_from_inside() {
        let c = upright();
        let side = Ray::new(Vec3::new(-5.0, 0.0, 2.0), Vec3::X, 10.0);
        assert_eq!(c.intersect(&side), Some(4.0));
        let h = c.surface(&side, 4.0);
        assert!((h.ng + Vec3::X).length() < 1e-12 && (h.uv[0] - 0.5).abs() < 1e-12 && (h.uv[1] - 0.5).abs() < 1e-12);
        let down = Ray::new(Vec3::new(0.5, 0.0, 10.0), -Vec3::Z, 20.0);
        assert_eq!(c.intersect(&down), Some(7.0), "top cap at z = 3");
        assert_eq!(c.surface(&down, 7.0).ng, Vec3::Z);
        let up = Ray::new(Vec3::new(0.5, 0.0, 2.0), Vec3::Z, 20.0);
        assert_eq!(c.intersect(&up), Some(1.0), "from inside");
        assert_eq!(c.intersect(&Ray::new(Vec3::new(1.5, 0.0, 10.0), -Vec3::Z, 20.0)), None);
        assert_eq!(c.intersect(&Ray::new(Vec3::new(-5.0, 0.0, 3.5), Vec3::X, 10.0)), None, "above");
        // Slanted through the top cap; then from inside out of the side.
        let slanted = Ray::segment(Vec3::new(0.0, 0.0, 4.0), Vec3::new(2.0, 0.0, 1.0));
        let t = c.intersect(&slanted).unwrap();
        assert!((slanted.at(t) - Vec3::new(2.0 / 3.0, 0.0, 3.0)).length() < 1e-12);
        let out = Ray { origin: slanted.at(t + 1e-6), ..slanted };
        let t = c.intersect(&out).unwrap();
        assert!((out.at(t) - Vec3::new(1.0, 0.0, 2.5)).length() < 1e-12, "side");
        assert!((c.area() - (2.0 * PI + 4.0 * PI)).abs() < 1e-12);
    }

    #[test]
    fn surface_function_is_the_distance() {
        let c = upright();
        assert!((c.surface_function(Vec3::new(3.0, 0.0, 2.0)) - 2.0).abs() < 1e-12);
        assert!((c.surface_function(Vec3::new(0.0, 0.0, 2.0)) + 1.0).abs() < 1e-12);
        assert!((c.surface_function(Vec3::new(0.0, 0.0, 2.9)) + 0.1).abs() < 1e-12);
        assert!((c.surface_function(Vec3::new(4.0, 0.0, 7.0)) - 5.0).abs() < 1e-12);
    }

    #[test]
    fn tilted_cylinder_bounds_are_exact() {
        // Axis along +x: the caps are circles in the y–z plane.
        let c = Cylinder::new(Vec3::ZERO, Vec3::X, 0.5, 3.0, &Transform::IDENTITY).unwrap();
        let b = c.bounds();
        assert!((b.min - Vec3::new(0.0, -0.5, -0.5)).length() < 1e-12);
        assert!((b.max - Vec3::new(3.0, 0.5, 0.5)).length() < 1e-12);
        assert!(Cylinder::new(Vec3::ZERO, Vec3::X, 0.5, 0.0, &Transform::IDENTITY).is_err());
    }
}

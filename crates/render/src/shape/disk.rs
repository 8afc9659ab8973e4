//! Disk: in object space the set `r_i ≤ ρ ≤ r` of the plane through `centre` perpendicular to
//! `normal` (an annulus where the inner radius `r_i` is not zero, as pbrt's `innerradius`); an
//! ellipse in world space under non-uniform scale, still sampled uniformly (an affine map has a
//! constant Jacobian on a plane).
//!
//! # uv
//!
//! Polar: `u = φ / 2π`, the angle around the normal measured from the first tangent axis of
//! [`Frame::from_normal`]`(normal)` toward the second; `v = ρ / r`, 0 at the centre and 1 on the
//! rim. `dpdu` points along increasing φ (clamped to a tiny non-zero length at the centre).

use super::stretch::AreaStretch;
use super::{azimuth, azimuthal_dpdu, check, ShapeError, SurfaceHit};
use crate::geometry::{Aabb, Frame, Ray, Vec3};
use crate::sampling::concentric_disk;
use crate::transform::Transform;
use glam::{DAffine3, DMat3};
use std::f64::consts::{PI, TAU};

#[derive(Clone, Debug)]
pub struct Disk {
    /// Object space with the disk in the z = 0 plane, centred at the origin, facing +z, to world.
    to_world: Transform,
    radius: f64,
    /// The hole's radius, 0 for a whole disk.
    inner_radius: f64,
    /// Unit outward world normal.
    normal: Vec3,
    min_stretch: f64,
    area: f64,
}

impl Disk {
    pub fn new(centre: Vec3, normal: Vec3, radius: f64, transform: &Transform) -> Result<Self, ShapeError> {
        Self::annulus(centre, normal, 0.0, radius, transform)
    }

    /// The disk of `radius` with a hole of `inner_radius` (`0 ≤ inner_radius < radius`).
    pub fn annulus(
        centre: Vec3,
        normal: Vec3,
        inner_radius: f64,
        radius: f64,
        transform: &Transform,
    ) -> Result<Self, ShapeError> {
        const NAME: &str = "disk";
        let centre = check::point(NAME, "centre", centre)?;
        let normal = check::direction(NAME, "normal", normal)?;
        let radius = check::positive(NAME, "radius", radius)?;
        if !(inner_radius >= 0.0 && inner_radius < radius) {
            return Err(ShapeError::InvalidInnerRadius { inner_radius, radius });
        }
        check::transform(NAME, transform)?;
        let to_world =
            placement(centre, normal).map_err(|_| ShapeError::InvalidTransform { shape: NAME })?.then(transform);
        let stretch = AreaStretch::new(&to_world);
        Ok(Self {
            to_world,
            radius,
            inner_radius,
            normal: to_world.normal(Vec3::Z).normalize(),
            min_stretch: to_world.scale_bounds().0,
            area: PI * (radius * radius - inner_radius * inner_radius) * stretch.factor(Vec3::Z),
        })
    }

    /// Exact bounds of the ellipse `c + r·(cos φ·M x̂ + sin φ·M ŷ)`: along world axis `i` it
    /// reaches `r·|(M_i0, M_i1)|` from its centre.
    pub fn bounds(&self) -> Aabb {
        let c = self.to_world.point(Vec3::ZERO);
        let half = ellipse_half_extent(&self.to_world, self.radius);
        Aabb { min: c - half, max: c + half }
    }

    #[inline]
    pub fn intersect(&self, ray: &Ray) -> Option<f64> {
        let o = self.to_world.inverse_point(ray.origin);
        let d = self.to_world.inverse_vector(ray.dir);
        if d.z == 0.0 {
            return None;
        }
        let t = -o.z / d.z;
        if !(t > 0.0 && t <= ray.t_max) {
            return None;
        }
        let (x, y) = (o.x + t * d.x, o.y + t * d.y);
        let rho2 = x * x + y * y;
        (rho2 <= self.radius * self.radius && rho2 >= self.inner_radius * self.inner_radius).then_some(t)
    }

    pub fn surface(&self, ray: &Ray, t: f64) -> SurfaceHit {
        let o = self.to_world.inverse_point(ray.origin);
        let d = self.to_world.inverse_vector(ray.dir);
        let (mut x, mut y) = (o.x + t * d.x, o.y + t * d.y);
        let mut rho = x.hypot(y);
        let clamped = rho.clamp(self.inner_radius, self.radius);
        if clamped != rho {
            (x, y) = (x * clamped / rho, y * clamped / rho);
            rho = clamped;
        }
        let phi = azimuth(x, y);
        SurfaceHit {
            p: self.to_world.point(Vec3::new(x, y, 0.0)),
            ng: self.normal,
            ns: self.normal,
            uv: [phi / TAU, rho / self.radius],
            dpdu: self.to_world.vector(azimuthal_dpdu(phi, rho, self.radius)),
        }
    }

    pub fn area(&self) -> f64 {
        self.area
    }

    pub fn sample_area(&self, u: [f64; 2]) -> (Vec3, Vec3) {
        if self.inner_radius == 0.0 {
            let [x, y] = concentric_disk(u);
            return (self.to_world.point(Vec3::new(x, y, 0.0) * self.radius), self.normal);
        }
        // Uniform in area: ρ² uniform between the radii.
        let (inner2, outer2) = (self.inner_radius * self.inner_radius, self.radius * self.radius);
        let rho = (inner2 + u[0] * (outer2 - inner2)).sqrt();
        let (sin, cos) = (TAU * u[1]).sin_cos();
        (self.to_world.point(Vec3::new(rho * cos, rho * sin, 0.0)), self.normal)
    }

    pub fn supporting_plane(&self) -> (Vec3, Vec3) {
        (self.to_world.point(Vec3::ZERO), self.normal)
    }

    /// Object-space signed height above the disk's plane where the point projects inside the
    /// disk, else the distance to the nearer rim; times `σ_min` (a lower bound under
    /// non-uniform scale).
    pub fn surface_function(&self, p: Vec3) -> f64 {
        let q = self.to_world.inverse_point(p);
        let rho = q.x.hypot(q.y);
        let d = if rho > self.radius {
            q.z.hypot(rho - self.radius)
        } else if rho < self.inner_radius {
            q.z.hypot(self.inner_radius - rho)
        } else {
            q.z
        };
        d * self.min_stretch
    }
}

/// The rigid map taking the canonical frame (origin, +z) to `(centre, normal)`, with the other
/// axes from [`Frame::from_normal`].
pub(super) fn placement(centre: Vec3, normal: Vec3) -> Result<Transform, crate::transform::TransformError> {
    let f = Frame::from_normal(normal);
    Transform::from_affine(DAffine3::from_mat3_translation(DMat3::from_cols(f.s, f.t, f.n), centre))
}

/// Half extents along the world axes of the image of the object-space circle of `radius` in the
/// z = 0 plane: `r·|(M_i0, M_i1)|` for row `i`.
pub(super) fn ellipse_half_extent(to_world: &Transform, radius: f64) -> Vec3 {
    let m = to_world.linear();
    let (a, b) = (m.x_axis, m.y_axis);
    Vec3::new(a.x.hypot(b.x), a.y.hypot(b.y), a.z.hypot(b.z)) * radius
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn hits_inside_the_radius_only() {
        let d = Disk::new(Vec3::new(0.0, 0.0, 1.0), Vec3::Z, 2.0, &Transform::IDENTITY).unwrap();
        let ray = Ray::new(Vec3::new(1.0, 1.0, 0.0), Vec3::Z, 10.0);
        assert_eq!(d.intersect(&ray), Some(1.0));
        let h = d.surface(&ray, 1.0);
        assert!((h.uv[1] - 2f64.sqrt() / 2.0).abs() < 1e-12 && h.ng == Vec3::Z);
        assert_eq!(d.intersect(&Ray::new(Vec3::new(1.5, 1.5, 0.0), Vec3::Z, 10.0)), None);
        assert_eq!(d.intersect(&Ray::new(Vec3::new(0.0, 0.0, 3.0), -Vec3::Z, 10.0)), Some(2.0));
        assert_eq!(d.intersect(&Ray::new(Vec3::new(0.0, 0.0, 3.0), -Vec3::Z, 1.5)), None);
        assert!((d.area() - 4.0 * PI).abs() < 1e-12);
        assert_eq!(d.bounds(), Aabb::new(Vec3::new(-2.0, -2.0, 1.0), Vec3::new(2.0, 2.0, 1.0)));
    }

    #[test]
    fn an_annulus_has_a_hole_and_is_sampled_in_its_ring() {
        let d = Disk::annulus(Vec3::ZERO, Vec3::Z, 1.0, 2.0, &Transform::IDENTITY).unwrap();
        assert!((d.area() - 3.0 * PI).abs() < 1e-12);
        assert_eq!(d.intersect(&Ray::new(Vec3::new(0.5, 0.0, 1.0), -Vec3::Z, 10.0)), None);
        assert_eq!(d.intersect(&Ray::new(Vec3::new(1.5, 0.0, 1.0), -Vec3::Z, 10.0)), Some(1.0));
        assert!(d.surface_function(Vec3::new(0.5, 0.0, 0.0)) > 0.0, "the hole is outside");
        // ρ² is uniform: half the samples lie inside ρ² = (1 + 4)/2.
        let inside = (0..1000)
            .filter(|&i| {
                let (p, _) = d.sample_area([(i as f64 + 0.5) / 1000.0, 0.3]);
                assert!((1.0 - 1e-12..=2.0 + 1e-12).contains(&p.length()));
                p.length_squared() < 2.5
            })
            .count();
        assert_eq!(inside, 500);
        assert!(Disk::annulus(Vec3::ZERO, Vec3::Z, 2.0, 2.0, &Transform::IDENTITY).is_err());
    }

    #[test]
    fn stretched_disk_is_an_ellipse() {
        let t = Transform::scale(Vec3::new(3.0, 1.0, 1.0)).unwrap();
        let d = Disk::new(Vec3::ZERO, Vec3::Z, 1.0, &t).unwrap();
        assert!((d.area() - 3.0 * PI).abs() < 1e-12);
        assert!(d.intersect(&Ray::new(Vec3::new(2.9, 0.0, -1.0), Vec3::Z, 10.0)).is_some());
        assert!(d.intersect(&Ray::new(Vec3::new(0.0, 1.1, -1.0), Vec3::Z, 10.0)).is_none());
        // Beside the rim the function stays positive on both sides of the plane.
        assert!(d.surface_function(Vec3::new(4.0, 0.0, -0.5)) > 0.0);
        assert!(d.surface_function(Vec3::new(1.0, 0.0, -0.5)) < 0.0);
    }
}

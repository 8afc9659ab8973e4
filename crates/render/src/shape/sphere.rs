//! Sphere: a ball's boundary in object space, an ellipsoid in world space under non-uniform scale.
//!
//! # uv
//!
//! Equirectangular, matching an equirectangular earth texture: `u = φ / 2π` is the longitude,
//! measured around the object's +z axis from +x toward +y; `v = 1/2 + λ / π` is the latitude,
//! 0 at the south pole (−z), 1 at the north pole (+z). `dpdu` points east.

use super::quadratic::{centred_roots, nearest_ahead};
use super::stretch::AreaStretch;
use super::{azimuth, azimuthal_dpdu, check, ShapeError, SurfaceHit};
use crate::geometry::{Aabb, Ray, Vec3};
use crate::sampling::uniform_sphere;
use crate::transform::Transform;
use std::f64::consts::FRAC_1_PI;

#[derive(Clone, Debug)]
pub struct Sphere {
    /// Object space with the centre at the origin, to world.
    to_world: Transform,
    radius: f64,
    /// `σ_min` of the map: converts object-space distances to lower bounds on world distances.
    min_stretch: f64,
    stretch: AreaStretch,
    area: f64,
}

impl Sphere {
    pub fn new(centre: Vec3, radius: f64, transform: &Transform) -> Result<Self, ShapeError> {
        const NAME: &str = "sphere";
        let centre = check::point(NAME, "centre", centre)?;
        let radius = check::positive(NAME, "radius", radius)?;
        check::transform(NAME, transform)?;
        let to_world = Transform::translate(centre).then(transform);
        let stretch = AreaStretch::new(&to_world);
        Ok(Self {
            to_world,
            radius,
            min_stretch: to_world.scale_bounds().0,
            stretch,
            area: radius * radius * stretch.unit_sphere_area(),
        })
    }

    /// Exact bounds of the ellipsoid `c + M·x`, `|x| ≤ r`: along world axis `i` it reaches
    /// `r·|row i of M|` from its centre.
    pub fn bounds(&self) -> Aabb {
        let m = self.to_world.linear();
        let c = self.to_world.point(Vec3::ZERO);
        let half = Vec3::new(m.row(0).length(), m.row(1).length(), m.row(2).length()) * self.radius;
        Aabb { min: c - half, max: c + half }
    }

    #[inline]
    pub fn intersect(&self, ray: &Ray) -> Option<f64> {
        let o = self.to_world.inverse_point(ray.origin);
        let d = self.to_world.inverse_vector(ray.dir);
        nearest_ahead(centred_roots(o, d, self.radius * self.radius)?, ray.t_max)
    }

    pub fn surface(&self, ray: &Ray, t: f64) -> SurfaceHit {
        let o = self.to_world.inverse_point(ray.origin);
        let d = self.to_world.inverse_vector(ray.dir);
        // Re-project onto the sphere: removes the error of `o + t·d`.
        let q = o + d * t;
        let q = if q == Vec3::ZERO { Vec3::Z * self.radius } else { q * (self.radius / q.length()) };
        let n = q / self.radius;
        let phi = azimuth(q.x, q.y);
        let latitude = n.z.clamp(-1.0, 1.0).asin();
        let ng = self.to_world.normal(n).normalize();
        let rho = q.x.hypot(q.y);
        SurfaceHit {
            p: self.to_world.point(q),
            ng,
            ns: ng,
            uv: [phi / std::f64::consts::TAU, 0.5 + latitude * FRAC_1_PI],
            dpdu: self.to_world.vector(azimuthal_dpdu(phi, rho, self.radius)),
        }
    }

    pub fn area(&self) -> f64 {
        self.area
    }

    pub fn sample_area(&self, u: [f64; 2]) -> (Vec3, Vec3) {
        let n = self.stretch.sample(u, |u| {
            let n = uniform_sphere(u);
            (n, n)
        });
        (self.to_world.point(n * self.radius), self.to_world.normal(n).normalize())
    }

    /// `σ_min · (|x| − r)` in object space: exact for a rigidly placed sphere, a lower bound on
    /// the distance to an ellipsoid (an object-space distance shrinks by at most `σ_min`).
    pub fn surface_function(&self, p: Vec3) -> f64 {
        (self.to_world.inverse_point(p).length() - self.radius) * self.min_stretch
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::PI;

    fn unit() -> Sphere {
        Sphere::new(Vec3::new(1.0, 2.0, 3.0), 2.0, &Transform::IDENTITY).unwrap()
    }

    #[test]
    fn hits_from_outside_and_inside() {
        let s = unit();
        let ray = Ray::new(Vec3::new(1.0, 2.0, -7.0), Vec3::Z, 100.0);
        assert_eq!(s.intersect(&ray), Some(8.0));
        let inside = Ray::new(Vec3::new(1.0, 2.0, 3.0), Vec3::Z, 100.0);
        assert_eq!(s.intersect(&inside), Some(2.0));
        assert_eq!(s.intersect(&Ray { t_max: 7.999, ..ray }), None, "segment stops short");
        assert_eq!(s.intersect(&Ray::new(Vec3::new(1.0, 2.0, 6.0), Vec3::Z, 100.0)), None, "behind");
        assert_eq!(s.intersect(&Ray::new(Vec3::new(1.0, 4.0 + 1e-9, -7.0), Vec3::Z, 100.0)), None);
        let graze = Ray::new(Vec3::new(1.0, 4.0 - 1e-9, -7.0), Vec3::Z, 100.0);
        let t = s.intersect(&graze).unwrap();
        assert!((t - 10.0).abs() < 1e-3, "grazing hit near the tangent point, got {t}");
    }

    #[test]
    fn ellipsoid_hits_and_normals_are_exact() {
        // x²/4 + y² + z²/9 = 1 (radius 1 scaled by (2, 1, 3)), then moved.
        let t =
            Transform::scale(Vec3::new(2.0, 1.0, 3.0)).unwrap().then(&Transform::translate(Vec3::new(0.0, 0.0, 10.0)));
        let s = Sphere::new(Vec3::ZERO, 1.0, &t).unwrap();
        let ray = Ray::new(Vec3::new(-10.0, 0.0, 10.0), Vec3::X, 100.0);
        assert!((s.intersect(&ray).unwrap() - 8.0).abs() < 1e-12);
        let ray = Ray::new(Vec3::new(0.0, 0.0, 0.0), Vec3::Z, 100.0);
        assert!((s.intersect(&ray).unwrap() - 7.0).abs() < 1e-12);
        // A diagonal ray: the world t is the world distance along the unit direction.
        let dir = Vec3::new(1.0, 1.0, 0.0).normalize();
        let ray = Ray::new(Vec3::new(0.0, 0.0, 10.0), dir, 100.0);
        let t = s.intersect(&ray).unwrap();
        let p = ray.at(t);
        assert!((p.x * p.x / 4.0 + p.y * p.y - 1.0).abs() < 1e-12);
        // Normal ∝ gradient (x/4, y, (z−10)/9).
        let h = s.surface(&ray, t);
        let g = Vec3::new(p.x / 4.0, p.y, (p.z - 10.0) / 9.0).normalize();
        assert!((h.ng - g).length() < 1e-12);
        assert!((s.bounds().max - Vec3::new(2.0, 1.0, 13.0)).length() < 1e-12);
    }

    #[test]
    fn uv_is_equirectangular_around_object_z() {
        let s = Sphere::new(Vec3::ZERO, 1.0, &Transform::IDENTITY).unwrap();
        let hit = |dir: Vec3| {
            let ray = Ray::new(-dir * 5.0, dir, 10.0);
            s.surface(&ray, s.intersect(&ray).unwrap())
        };
        let east = hit(-Vec3::X); // hits +x
        assert!((east.uv[0] - 0.0).abs() < 1e-12 && (east.uv[1] - 0.5).abs() < 1e-12);
        assert!((east.dpdu.normalize() - Vec3::Y).length() < 1e-12, "u grows toward +y");
        let y = hit(-Vec3::Y);
        assert!((y.uv[0] - 0.25).abs() < 1e-12);
        let north = hit(-Vec3::Z);
        assert!((north.uv[1] - 1.0).abs() < 1e-12 && north.dpdu.length() > 0.0);
        let south = hit(Vec3::Z);
        assert!(south.uv[1].abs() < 1e-12);
    }

    #[test]
    fn area_and_surface_function() {
        let s = unit();
        assert!((s.area() - 16.0 * PI).abs() < 1e-12);
        assert!((s.surface_function(Vec3::new(1.0, 2.0, 8.0)) - 3.0).abs() < 1e-12);
        assert!((s.surface_function(Vec3::new(1.0, 2.0, 3.0)) + 2.0).abs() < 1e-12);
    }
}

//! The perspective projection: a pinhole, or a thin lens for depth of field.

use super::{Axes, FilmPoint};
use crate::geometry::Vec3;
use crate::sampling::concentric_disk;

/// A pinhole (`lens_radius` 0) or thin-lens camera with a vertical field of view.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Perspective {
    /// `tan(vfov / 2)`.
    tan_half_fov: f64,
    /// Radius of the thin lens (0 for a pinhole).
    pub lens_radius: f64,
    /// Distance to the plane in focus, along the viewing direction.
    pub focus_distance: f64,
}

impl Perspective {
    /// Vertical field of view `vfov_deg` (degrees, in (0, 180)), a lens of radius
    /// `lens_radius ≥ 0` focused at `focus_distance > 0`.
    pub fn new(vfov_deg: f64, lens_radius: f64, focus_distance: f64) -> Result<Perspective, String> {
        if !(vfov_deg > 0.0 && vfov_deg < 180.0) {
            return Err(format!("fov must be in (0, 180) degrees, got {vfov_deg}"));
        }
        if !(lens_radius >= 0.0 && lens_radius.is_finite()) {
            return Err(format!("aperture must be a finite number ≥ 0, got {lens_radius}"));
        }
        if !(focus_distance > 0.0 && focus_distance.is_finite()) {
            return Err(format!("focus distance must be > 0, got {focus_distance}"));
        }
        Ok(Perspective { tan_half_fov: (0.5 * vfov_deg.to_radians()).tan(), lens_radius, focus_distance })
    }

    /// The ray's start and direction through `film`: the image plane at unit distance spans
    /// `±tan(vfov/2)` vertically, the aspect ratio's multiple of it horizontally.
    pub(super) fn ray(&self, position: Vec3, axes: &Axes, film: FilmPoint, lens_u: [f64; 2]) -> (Vec3, Vec3) {
        let aspect = film.width / film.height;
        let sx = (2.0 * film.x / film.width - 1.0) * self.tan_half_fov * aspect;
        let sy = (1.0 - 2.0 * film.y / film.height) * self.tan_half_fov;
        let dir = (axes.forward + sx * axes.right + sy * axes.up).normalize();
        if self.lens_radius == 0.0 {
            return (position, dir);
        }
        // Thin lens: all rays through the lens meet at the focus point of the pinhole ray.
        let focus = position + dir * (self.focus_distance / dir.dot(axes.forward));
        let [lx, ly] = concentric_disk(lens_u);
        let origin = position + self.lens_radius * (lx * axes.right + ly * axes.up);
        (origin, (focus - origin).normalize())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::camera::tests::ray_at;
    use crate::camera::Camera;
    use spacetime::Region;

    #[test]
    fn centre_ray_looks_at_the_target_and_corners_span_the_fov() {
        let c = Camera::new(Region::Upper, Vec3::ZERO, Vec3::new(0.0, 0.0, -1.0), Vec3::Y, 90.0, 0.0, None).unwrap();
        let r = ray_at(&c, 50.0, 50.0, [100, 100], [0.5, 0.5]).unwrap();
        assert!((r.direction - Vec3::new(0.0, 0.0, -1.0)).length() < 1e-12);
        let top_left = ray_at(&c, 0.0, 0.0, [100, 100], [0.5, 0.5]).unwrap().direction;
        // tan 45° = 1: the corner direction is (−1, 1, −1)/√3.
        assert!((top_left - Vec3::new(-1.0, 1.0, -1.0).normalize()).length() < 1e-12);
    }

    #[test]
    fn thin_lens_rays_meet_in_the_focal_plane() {
        let c = Camera::new(Region::Upper, Vec3::ZERO, Vec3::new(0.0, 0.0, -4.0), Vec3::Y, 40.0, 0.2, None).unwrap();
        let a = ray_at(&c, 10.0, 20.0, [64, 64], [0.1, 0.9]).unwrap();
        let b = ray_at(&c, 10.0, 20.0, [64, 64], [0.8, 0.3]).unwrap();
        let at_plane = |r: crate::camera::CameraRay| r.origin + r.direction * ((-4.0 - r.origin.z) / r.direction.z);
        assert!((at_plane(a) - at_plane(b)).length() < 1e-12);
        assert!((a.origin - b.origin).length() > 1e-3);
    }

    #[test]
    fn out_of_range_lenses_are_rejected() {
        assert!(Perspective::new(0.0, 0.0, 1.0).is_err());
        assert!(Perspective::new(40.0, -0.1, 1.0).is_err());
        assert!(Perspective::new(40.0, 0.1, 0.0).is_err());
        assert!(Perspective::new(40.0, 0.1, 1.0).is_ok());
    }
}

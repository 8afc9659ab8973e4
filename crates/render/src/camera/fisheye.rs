//! The fisheye projection, azimuthal equidistant: the angle from the viewing direction is linear
//! in the distance from the image centre. It is the planetarium's dome-master format (a 180°
//! fisheye looking at the zenith), and at 360° it reaches straight behind the camera.

use super::{Axes, FilmPoint};
use crate::geometry::Vec3;

/// An azimuthal equidistant fisheye whose field of view spans the diameter of the circle
/// inscribed in the image (centred, diameter the shorter side). Outside the circle the camera
/// sees nothing: those samples are black.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Fisheye {
    /// Half the field of view, radians: the angle off the axis at the circle's edge.
    half_fov: f64,
}

impl Fisheye {
    /// A fisheye of field of view `fov_deg` (degrees, in (0, 360]).
    pub fn new(fov_deg: f64) -> Result<Fisheye, String> {
        if !(fov_deg > 0.0 && fov_deg <= 360.0) {
            return Err(format!("fisheye_fov must be in (0, 360] degrees, got {fov_deg}"));
        }
        Ok(Fisheye { half_fov: 0.5 * fov_deg.to_radians() })
    }

    /// The direction through `film`: at distance `r` (as a fraction of the circle's radius) from
    /// the centre and at angle `φ` from the image's right towards its up, the angle
    /// `θ = r · fov/2` from `forward` towards `cos φ · right + sin φ · up`; `None` for `r > 1`.
    pub(super) fn direction(&self, axes: &Axes, film: FilmPoint) -> Option<Vec3> {
        let radius = 0.5 * film.width.min(film.height);
        let (px, py) = ((film.x - 0.5 * film.width) / radius, (0.5 * film.height - film.y) / radius);
        let r = px.hypot(py);
        if !(r <= 1.0) {
            return None;
        }
        let theta = r * self.half_fov;
        // sin θ / r, which tends to fov/2 at the centre.
        let scale = if r > 0.0 { theta.sin() / r } else { self.half_fov };
        Some(theta.cos() * axes.forward + scale * (px * axes.right + py * axes.up))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::camera::tests::{looking_down_z, ray_at};
    use crate::camera::{CameraRay, Projection};
    use std::f64::consts::{FRAC_PI_2, PI};

    /// The ray of a `fov_deg` fisheye at `r` (fraction of the circle's radius) and angle
    /// `azimuth` from the centre of a 200 × 100 image.
    fn ray(fov_deg: f64, r: f64, azimuth: f64) -> Option<CameraRay> {
        let camera = looking_down_z(Projection::Fisheye(Fisheye::new(fov_deg).unwrap()));
        let (x, y) = (100.0 + 50.0 * r * azimuth.cos(), 50.0 - 50.0 * r * azimuth.sin());
        ray_at(&camera, x, y, [200, 100], [0.5; 2])
    }

    #[test]
    fn the_angle_off_axis_is_linear_in_the_distance_from_the_centre() {
        for fov in [180.0f64, 120.0, 250.0, 360.0] {
            for (r, azimuths) in [0.0, 0.1, 0.37, 0.5, 0.8, 0.999_999]
                .map(|r| (r, [0.7f64, 2.0, -2.5]))
                .into_iter()
                .chain([(1.0, [0.0, FRAC_PI_2, PI])])
            {
                for azimuth in azimuths {
                    let d = ray(fov, r, azimuth).unwrap().direction;
                    let off_axis = d.dot(Vec3::NEG_Z).clamp(-1.0, 1.0).acos();
                    assert!((off_axis - r * 0.5 * fov.to_radians()).abs() < 1e-9, "fov {fov}, r {r}: {off_axis}");
                    assert!((d.length() - 1.0).abs() < 1e-12);
                    if r > 0.0 && r * fov < 360.0 {
                        // Towards the same side as the film point: right and up are the camera's.
                        let seen = d.y.atan2(d.x);
                        assert!((seen - azimuth).abs() < 1e-9, "fov {fov}, r {r}: azimuth {seen}");
                    }
                }
            }
        }
        // A 180° fisheye's edge is 90° off the axis; a 360° one's looks straight back.
        assert!(ray(180.0, 1.0, FRAC_PI_2).unwrap().direction.z.abs() < 1e-12);
        assert!((ray(360.0, 1.0, 0.0).unwrap().direction - Vec3::Z).length() < 1e-12);
    }

    #[test]
    fn outside_the_circle_there_is_no_ray() {
        assert_eq!(ray(180.0, 1.0001, 0.4), None);
        assert_eq!(ray(360.0, 1.5, 0.0), None);
        let camera = looking_down_z(Projection::Fisheye(Fisheye::new(180.0).unwrap()));
        assert_eq!(ray_at(&camera, 0.0, 0.0, [200, 100], [0.5; 2]), None, "corner");
    }

    #[test]
    fn fields_of_view_out_of_range_are_rejected() {
        for fov in [0.0, -10.0, 360.5, f64::NAN, f64::INFINITY] {
            assert!(Fisheye::new(fov).is_err(), "{fov}");
        }
    }
}

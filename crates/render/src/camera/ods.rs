//! Omni-directional stereo (ODS) for VR headsets: a panorama per eye, left eye on top and right
//! eye below (the usual top/bottom layout of YouTube VR and Blender Cycles' ODS).
//!
//! Each eye's panorama is [`Equirectangular`](super::Equirectangular) in direction; a ray of
//! longitude λ starts on the circle of radius IPD/2 about the camera, in its horizontal plane
//! (the plane of right and forward), tangent to the circle: at `∓ IPD/2` times the horizontal
//! right of its direction, minus for the left eye and plus for the right (Google, "Rendering
//! Omni-directional Stereo Content", 2015; Cycles' panorama ODS without pole merging). So every
//! direction is seen as a head turned towards it would see it, and a point at distance `d` in
//! the horizontal plane shows a disparity of `2 asin(IPD/2 / d)` between the eyes. Near the
//! poles the eyes' views differ in a way no head does, as in every ODS renderer.

use super::{equirectangular, Axes, FilmPoint};
use crate::geometry::Vec3;

/// Omni-directional stereo with interpupillary distance `2 · half_ipd` (scene units).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Ods {
    half_ipd: f64,
}

impl Ods {
    /// ODS with interpupillary distance `ipd > 0` (scene units).
    pub fn new(ipd: f64) -> Result<Ods, String> {
        if !(ipd > 0.0 && ipd.is_finite()) {
            return Err(format!("ipd must be a finite distance > 0, got {ipd}"));
        }
        Ok(Ods { half_ipd: 0.5 * ipd })
    }

    /// The ray's start and direction through `film`: the top half of the image (by the
    /// sample's pixel row) is the left eye's panorama, the bottom half the right eye's.
    pub(super) fn ray(&self, position: Vec3, axes: &Axes, film: FilmPoint) -> (Vec3, Vec3) {
        let left = f64::from(film.row) + 0.5 < 0.5 * film.height;
        let (v, side) = if left { (2.0 * film.y / film.height, -1.0) } else { (2.0 * film.y / film.height - 1.0, 1.0) };
        let (longitude, latitude) = equirectangular::angles(film.x / film.width, v);
        let (sin, cos) = longitude.sin_cos();
        let right_of_view = cos * axes.right - sin * axes.forward;
        (position + side * self.half_ipd * right_of_view, equirectangular::direction(axes, longitude, latitude))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::camera::tests::{looking_down_z, ray_at};
    use crate::camera::{CameraRay, Equirectangular, Projection};
    use std::f64::consts::PI;

    const IPD: f64 = 0.064;
    const SIZE: [u32; 2] = [256, 256];

    /// The ray at film position `(x, y)` of the ODS camera at the origin looking along −z.
    fn ray(x: f64, y: f64) -> CameraRay {
        ray_at(&looking_down_z(Projection::Ods(Ods::new(IPD).unwrap())), x, y, SIZE, [0.5; 2]).unwrap()
    }

    #[test]
    fn rays_start_on_the_eye_circle_tangent_to_it() {
        for (x, y) in [(0.0, 3.0), (17.5, 64.0), (128.0, 64.0), (200.3, 100.0), (64.0, 192.0), (250.0, 255.0)] {
            let r = ray(x, y);
            assert!((r.origin.length() - 0.5 * IPD).abs() < 1e-15, "({x}, {y}): |origin| = {}", r.origin.length());
            assert_eq!(r.origin.y, 0.0, "in the horizontal plane");
            assert!(r.origin.dot(r.direction).abs() < 1e-15, "tangent");
        }
        // Looking ahead, the left eye (top half) sits to the left and the right eye to the right.
        assert!((ray(128.0, 64.0).origin - Vec3::new(-0.5 * IPD, 0.0, 0.0)).length() < 1e-15);
        assert!((ray(128.0, 192.0).origin - Vec3::new(0.5 * IPD, 0.0, 0.0)).length() < 1e-15);
    }

    #[test]
    fn each_eye_looks_where_a_half_height_panorama_does() {
        let panorama = looking_down_z(Projection::Equirectangular(Equirectangular));
        for (x, y) in [(0.5, 0.5), (40.0, 10.25), (128.0, 64.0), (255.5, 127.5)] {
            let expected = ray_at(&panorama, x, y, [SIZE[0], SIZE[1] / 2], [0.5; 2]).unwrap().direction;
            for eye_y in [y, y + 128.0] {
                assert!((ray(x, eye_y).direction - expected).length() < 1e-12, "({x}, {eye_y})");
            }
        }
    }

    /// The longitude (radians) at which the eye whose half starts at row `top` sees the point
    /// `p` of the horizontal plane: bisection on the sign of the ray's offset from `p`, between
    /// longitudes 90° either side of `p`'s.
    fn longitude_of(p: Vec3, top: f64) -> f64 {
        let miss = |longitude: f64| {
            let r = ray((longitude / PI + 1.0) * 0.5 * f64::from(SIZE[0]), top + 64.0);
            (p - r.origin).cross(r.direction).y
        };
        let centre = p.x.atan2(-p.z);
        let (mut lo, mut hi) = (centre - 0.5 * PI, centre + 0.5 * PI);
        assert!(miss(lo) * miss(hi) < 0.0);
        for _ in 0..100 {
            let mid = 0.5 * (lo + hi);
            if miss(mid) * miss(lo) > 0.0 {
                lo = mid;
            } else {
                hi = mid;
            }
        }
        0.5 * (lo + hi)
    }

    #[test]
    fn a_point_at_distance_d_shows_the_parallax_of_two_eyes() {
        // Disparity between the panoramas: 2 asin(IPD/2 / d), the left eye seeing the point
        // further right; 1e-9 rad covers the bisection and the rounding of film positions.
        for d in [0.05, 0.3, 2.0, 40.0] {
            for azimuth in [0.0f64, 0.8, -1.2] {
                let p = d * Vec3::new(azimuth.sin(), 0.0, -azimuth.cos());
                let (left, right) = (longitude_of(p, 0.0), longitude_of(p, 128.0));
                let expected = 2.0 * (0.5 * IPD / d).asin();
                assert!((left - right - expected).abs() < 1e-9, "d {d}, azimuth {azimuth}: {}", left - right);
                assert!(((left + right) * 0.5 - azimuth).abs() < 1e-9, "centred on the point's direction");
            }
        }
    }

    #[test]
    fn an_ipd_must_be_a_positive_distance() {
        for ipd in [0.0, -0.06, f64::NAN, f64::INFINITY] {
            assert!(Ods::new(ipd).is_err(), "{ipd}");
        }
    }
}

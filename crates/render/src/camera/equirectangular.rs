//! The equirectangular projection: the whole sphere of directions as a 2:1 panorama, longitude
//! linear in x and latitude linear in y (the layout of `[sky] type = "equirect"` maps, seen
//! from inside).

use super::{Axes, FilmPoint};
use crate::geometry::Vec3;
use std::f64::consts::PI;

/// A 360° × 180° panorama: the image centre looks along the viewing direction, x runs from
/// behind on the left (longitude −180°) through the camera's right (+90°) to behind again, and
/// y from straight up (latitude +90°) to straight down. Any aspect ratio is accepted; 2:1 gives
/// square pixels at the horizon.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Equirectangular;

impl Equirectangular {
    /// The direction through `film`.
    pub(super) fn direction(&self, axes: &Axes, film: FilmPoint) -> Vec3 {
        let (longitude, latitude) = angles(film.x / film.width, film.y / film.height);
        direction(axes, longitude, latitude)
    }
}

/// Longitude (radians, 0 ahead, positive to the right) and latitude (positive up) of the point
/// a fraction `u` across and `v` down a panorama. Past the edges (a pixel filter's reach) the
/// angles run on, and [`direction`] continues over the poles and round the back.
pub(super) fn angles(u: f64, v: f64) -> (f64, f64) {
    ((2.0 * u - 1.0) * PI, (0.5 - v) * PI)
}

/// The unit direction at `longitude` and `latitude` in the image axes `axes`.
pub(super) fn direction(axes: &Axes, longitude: f64, latitude: f64) -> Vec3 {
    let (sin_lon, cos_lon) = longitude.sin_cos();
    let (sin_lat, cos_lat) = latitude.sin_cos();
    cos_lat * (sin_lon * axes.right + cos_lon * axes.forward) + sin_lat * axes.up
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::camera::tests::{cell_solid_angles, looking_down_z, ray_at};
    use crate::camera::{Camera, Projection};

    fn panorama() -> Camera {
        looking_down_z(Projection::Equirectangular(Equirectangular))
    }

    fn direction_at(x: f64, y: f64, size: [u32; 2]) -> Vec3 {
        ray_at(&panorama(), x, y, size, [0.5; 2]).unwrap().direction
    }

    #[test]
    fn the_centre_looks_ahead_and_the_axes_are_the_cameras() {
        let size = [64, 32];
        let close = |x: f64, y: f64, expected: Vec3| {
            let d = direction_at(x, y, size);
            assert!((d - expected).length() < 1e-12, "({x}, {y}): {d} ≠ {expected}");
        };
        close(32.0, 16.0, Vec3::NEG_Z);
        close(48.0, 16.0, Vec3::X); // right of centre: the camera's right
        close(16.0, 16.0, Vec3::NEG_X);
        close(0.0, 16.0, Vec3::Z); // the edges look backwards
        close(64.0, 16.0, Vec3::Z);
        close(32.0, 0.0, Vec3::Y); // top: up
        close(32.0, 32.0, Vec3::NEG_Y);
        // Longitude and latitude are linear: 45° right and 30° up.
        close(
            40.0,
            16.0 - 32.0 / 6.0,
            Vec3::new(0.5f64.sqrt() * 0.75f64.sqrt(), 0.5, -(0.5f64.sqrt()) * 0.75f64.sqrt()),
        );
    }

    #[test]
    fn the_panorama_covers_every_direction_once() {
        // The pixels, as cells between their corner rays, tile the sphere with one orientation
        // and a total solid angle of 4π: a sum over pixels of a uniform sky's radiance times
        // solid angle, which a double cover, a gap or a fold would change.
        for size in [[64, 32], [30, 24]] {
            let cells = cell_solid_angles(&panorama(), size);
            let total: f64 = cells.iter().sum();
            assert!((total.abs() - 4.0 * std::f64::consts::PI).abs() < 1e-3, "{size:?}: {total}");
            assert!(cells.iter().all(|&c| c * total.signum() >= -1e-15), "{size:?}: a cell folds back");
            // The cells shrink towards the poles as cos(latitude): compare a row's cell with the
            // latitude band's share, Δλ (sin φ₁ − sin φ₂), to the band's flattening.
            let row = size[1] / 4;
            let band = |y: u32| (0.5 - f64::from(y) / f64::from(size[1])) * PI;
            let exact = 2.0 * PI / f64::from(size[0]) * (band(row).sin() - band(row + 1).sin());
            let cell = cells[(row * size[0]) as usize].abs();
            assert!((cell / exact - 1.0).abs() < 0.01, "{size:?}: {cell} vs {exact}");
        }
        // And every direction is seen: random directions, found at their longitude and latitude
        // on the film, are the rays there.
        let mut u = crate::test_scenes::uniform(23);
        for _ in 0..1000 {
            let n = crate::sampling::uniform_sphere([u(), u()]);
            let (x, y) = ((n.x.atan2(-n.z) / PI + 1.0) * 32.0, (0.5 - n.y.asin() / PI) * 32.0);
            assert!((direction_at(x, y, [64, 32]) - n).length() < 1e-12, "{n}");
        }
    }
}

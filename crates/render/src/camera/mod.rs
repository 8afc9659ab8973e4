//! The camera: an observer at its position with a projection from film positions to directions.
//! It is a static observer unless it moves; the directions it produces are in its local
//! orthonormal frame, whose axes are aligned with the world's, and the propagator turns them
//! into null momenta of the spacetime. Every projection goes through the same frame and the same
//! boost, so all of them work in curved spacetime and for a moving camera.

mod equirectangular;
mod fisheye;
mod ods;
mod perspective;

pub use equirectangular::Equirectangular;
pub use fisheye::Fisheye;
pub use ods::Ods;
pub use perspective::Perspective;

use crate::geometry::Vec3;
use glam::{DMat3, DQuat};
use spacetime::tensor::ETA;
use spacetime::{Minkowski, Region, Tetrad};

/// How film positions map to directions; one file per projection.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Projection {
    /// A pinhole or thin lens with a vertical field of view.
    Perspective(Perspective),
    /// A 360° × 180° panorama, longitude and latitude linear in x and y.
    Equirectangular(Equirectangular),
    /// Azimuthal equidistant (a planetarium's dome master): off-axis angle linear in radius.
    Fisheye(Fisheye),
    /// Omni-directional stereo: two equirectangular panoramas, left eye on top.
    Ods(Ods),
}

/// A camera: where it is, which way its image axes point, and how it projects.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Camera {
    pub region: Region,
    pub position: Vec3,
    axes: Axes,
    pub projection: Projection,
    /// The camera's motion relative to the static observer at its position, if it moves.
    motion: Option<Motion>,
}

/// Unit axes of the image in the local frame: right, up, and the viewing direction.
#[derive(Clone, Copy, Debug, PartialEq)]
struct Axes {
    right: Vec3,
    up: Vec3,
    forward: Vec3,
}

/// A camera sample's place on the film: `(x, y)` in pixels (x right, y down) of a
/// `width × height` image, inside or (by the pixel filter's reach) near pixel row `row`.
#[derive(Clone, Copy, Debug, PartialEq)]
struct FilmPoint {
    x: f64,
    y: f64,
    width: f64,
    height: f64,
    row: u32,
}

/// A moving camera's frame: the static frame boosted by the camera's 3-velocity. In the local
/// orthonormal frames the relation is special relativity's, so it is set up once in flat space.
#[derive(Clone, Copy, Debug, PartialEq)]
struct Motion {
    rest: Tetrad,
    moving: Tetrad,
}

/// A camera ray: start point and unit direction in the local frame of the static observer at
/// the camera, and the factor its radiance is seen with by the (possibly moving) camera.
/// Start points off `position` (on a thin lens, an ODS eye's circle) are laid out in the static
/// observer's frame: only directions are boosted, not those small offsets Lorentz-contracted.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CameraRay {
    pub origin: Vec3,
    pub direction: Vec3,
    /// The Doppler factor `D = ν_camera / ν_static` the camera sees light arriving along the
    /// ray with; 1 for a camera at rest.
    pub doppler: f64,
}

impl CameraRay {
    /// `D⁴`: frequency-integrated radiance scales as `ν⁴` (`I_ν/ν³` is invariant), the factor
    /// for renderers that carry RGB light with its brightness shifted alone.
    pub fn weight(&self) -> f32 {
        self.doppler.powi(4) as f32
    }
}

impl Projection {
    /// The ray's start and unit direction (camera's frame) through `film`, with lens sample
    /// `lens_u`; `None` where the film sees nothing (outside a fisheye's circle).
    fn ray(&self, position: Vec3, axes: &Axes, film: FilmPoint, lens_u: [f64; 2]) -> Option<(Vec3, Vec3)> {
        match self {
            Projection::Perspective(p) => Some(p.ray(position, axes, film, lens_u)),
            Projection::Equirectangular(e) => Some((position, e.direction(axes, film))),
            Projection::Fisheye(f) => f.direction(axes, film).map(|d| (position, d)),
            Projection::Ods(o) => Some(o.ray(position, axes, film)),
        }
    }
}

impl Camera {
    /// A perspective camera at `position` looking at `look_at`, with `up` roughly up and
    /// vertical field of view `vfov_deg` (degrees, in (0, 180)). `lens_radius > 0` gives depth
    /// of field focused at `focus_distance` (default: the distance to `look_at`).
    pub fn new(
        region: Region,
        position: Vec3,
        look_at: Vec3,
        up: Vec3,
        vfov_deg: f64,
        lens_radius: f64,
        focus_distance: Option<f64>,
    ) -> Result<Camera, String> {
        if !position.is_finite() || !look_at.is_finite() {
            return Err("position and look_at must be finite".into());
        }
        let orientation = look_rotation(look_at - position, up)?;
        let focus_distance = focus_distance.unwrap_or((look_at - position).length());
        let lens = Perspective::new(vfov_deg, lens_radius, focus_distance)?;
        Camera::oriented(region, position, orientation, Projection::Perspective(lens))
    }

    /// A camera at `position` whose image axes (right, up, backwards) are the world axes rotated
    /// by `orientation` (see [`look_rotation`]), projecting by `projection`.
    pub fn oriented(
        region: Region,
        position: Vec3,
        orientation: DQuat,
        projection: Projection,
    ) -> Result<Camera, String> {
        if !position.is_finite() || !orientation.is_finite() {
            return Err("position and orientation must be finite".into());
        }
        let orientation = orientation.normalize();
        let axes = Axes { right: orientation * Vec3::X, up: orientation * Vec3::Y, forward: orientation * Vec3::NEG_Z };
        Ok(Camera { region, position, axes, projection, motion: None })
    }

    /// The same camera moving with 3-velocity `velocity` (units of c, world axes) relative to the
    /// static observer at its position: aberration and Doppler shift follow from the boost.
    pub fn with_velocity(mut self, velocity: Vec3) -> Result<Camera, String> {
        if velocity == Vec3::ZERO {
            self.motion = None;
            return Ok(self);
        }
        let speed = velocity.length();
        if !(speed < 1.0) {
            return Err(format!("speed must be below the speed of light (1), got {speed}"));
        }
        let rest = Tetrad::static_observer(&Minkowski, &[0.0; 4]).map_err(|e| e.to_string())?;
        let moving = rest.boosted(velocity.to_array()).map_err(|e| e.to_string())?;
        self.motion = Some(Motion { rest, moving });
        Ok(self)
    }

    pub fn forward(&self) -> Vec3 {
        self.axes.forward
    }

    /// The ray of the sample `offset` pixels from the centre of pixel `pixel` (x right, y down)
    /// of an image of `size` (width, height), with lens sample `lens_u`; `None` where the
    /// projection sees nothing there (the film records such a sample as black). The pixel is
    /// given, not only the sample's position, because a filter wider than a pixel reaches across
    /// the seam between the eyes of an [`Ods`] image: a sample belongs to its pixel's eye.
    pub fn ray(&self, pixel: [u32; 2], offset: [f64; 2], size: [u32; 2], lens_u: [f64; 2]) -> Option<CameraRay> {
        let film = FilmPoint {
            x: f64::from(pixel[0]) + 0.5 + offset[0],
            y: f64::from(pixel[1]) + 0.5 + offset[1],
            width: f64::from(size[0]),
            height: f64::from(size[1]),
            row: pixel[1],
        };
        let (origin, direction) = self.projection.ray(self.position, &self.axes, film, lens_u)?;
        Some(match &self.motion {
            None => CameraRay { origin, direction, doppler: 1.0 },
            Some(m) => {
                // The backward ray of unit energy in the camera's frame, seen by the static
                // observer: direction (aberration) and energy E = ν_static/ν_camera.
                let p = m.moving.backward_momentum(&ETA, direction.to_array(), 1.0);
                let (n, energy) = m.rest.backward_direction(&p);
                CameraRay { origin, direction: Vec3::from_array(n), doppler: 1.0 / energy }
            }
        })
    }
}

/// The rotation taking the world axes x, y, −z to the image axes of a camera looking along
/// `forward` with `up` roughly up: right, up, forward.
pub fn look_rotation(forward: Vec3, up: Vec3) -> Result<DQuat, String> {
    let forward = forward.normalize_or_zero();
    if forward == Vec3::ZERO || !forward.is_finite() {
        return Err("look_at must differ from position".into());
    }
    let right = forward.cross(up).normalize_or_zero();
    if right == Vec3::ZERO || !right.is_finite() {
        return Err("up must not be parallel to the viewing direction".into());
    }
    Ok(DQuat::from_mat3(&DMat3::from_cols(right, right.cross(forward), -forward)))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A camera at the origin looking along −z with y up.
    pub(super) fn looking_down_z(projection: Projection) -> Camera {
        Camera::oriented(Region::Upper, Vec3::ZERO, DQuat::IDENTITY, projection).unwrap()
    }

    /// The ray of `camera` through film position `(x, y)` of an image of `size`.
    pub(super) fn ray_at(camera: &Camera, x: f64, y: f64, size: [u32; 2], lens_u: [f64; 2]) -> Option<CameraRay> {
        let pixel = |p: f64, n: u32| (p.floor().max(0.0) as u32).min(n - 1);
        let (px, py) = (pixel(x, size[0]), pixel(y, size[1]));
        camera.ray([px, py], [x - f64::from(px) - 0.5, y - f64::from(py) - 0.5], size, lens_u)
    }

    /// The signed solid angle of the pixels of a `size` image as the cells between the rays of
    /// `camera` through their corners, each cell two spherical triangles (Van Oosterom &
    /// Strackee 1983: tan(Ω/2) = a·(b×c) / (1 + a·b + b·c + c·a)); row-major. The cells tile the
    /// sphere `k` times over, with no fold, exactly when they share one sign and sum to 4πk.
    pub(super) fn cell_solid_angles(camera: &Camera, size: [u32; 2]) -> Vec<f64> {
        let corner = |x: u32, y: u32| {
            ray_at(camera, f64::from(x), f64::from(y), size, [0.5; 2]).map_or(Vec3::NAN, |r| r.direction)
        };
        let triangle = |a: Vec3, b: Vec3, c: Vec3| 2.0 * a.dot(b.cross(c)).atan2(1.0 + a.dot(b) + b.dot(c) + c.dot(a));
        let mut cells = Vec::new();
        for y in 0..size[1] {
            for x in 0..size[0] {
                let [a, b, c, d] = [corner(x, y), corner(x + 1, y), corner(x + 1, y + 1), corner(x, y + 1)];
                cells.push(triangle(a, b, c) + triangle(a, c, d));
            }
        }
        cells
    }

    fn pinhole(vfov_deg: f64) -> Camera {
        Camera::new(Region::Upper, Vec3::ZERO, Vec3::new(0.0, 0.0, -1.0), Vec3::Y, vfov_deg, 0.0, None).unwrap()
    }

    #[test]
    fn a_moving_camera_sees_aberration_and_doppler_shift() {
        // Moving at v towards −z (its viewing direction), a source at angle θ from the direction
        // of motion in the static frame appears at cos θ' = (cos θ + v)/(1 + v cos θ).
        let v = 0.6;
        let c = pinhole(90.0).with_velocity(Vec3::new(0.0, 0.0, -v)).unwrap();
        for x in [0.0, 10.0, 30.0, 49.0] {
            let r = ray_at(&c, x, 50.0, [100, 100], [0.5, 0.5]).unwrap();
            let seen = ray_at(&pinhole(90.0), x, 50.0, [100, 100], [0.5, 0.5]).unwrap().direction;
            let (cos_seen, cos_static) = (-seen.z, -r.direction.z);
            assert!(((cos_static + v) / (1.0 + v * cos_static) - cos_seen).abs() < 1e-12, "x = {x}");
            // Doppler factor D = ν_camera/ν_static = γ(1 + v cos θ) = 1/(γ(1 − v cos θ')).
            let gamma = 1.0 / (1.0 - v * v).sqrt();
            let d = gamma * (1.0 + v * cos_static);
            assert!((d * gamma * (1.0 - v * cos_seen) - 1.0).abs() < 1e-12);
            assert!((f64::from(r.weight()) / d.powi(4) - 1.0).abs() < 1e-6);
        }
        let still = ray_at(&c.with_velocity(Vec3::ZERO).unwrap(), 10.0, 20.0, [100, 100], [0.5, 0.5]).unwrap();
        assert_eq!(still.weight(), 1.0);
        assert!(c.with_velocity(Vec3::new(0.6, 0.8, 0.0)).is_err(), "speed of light");
    }

    #[test]
    fn every_projection_is_boosted_by_the_cameras_motion() {
        // Moving at v along +x (the camera's right), angles measured from +x obey the same
        // aberration and Doppler factor as above, for the rays of every projection.
        let v = 0.5;
        let projections = [
            Projection::Equirectangular(Equirectangular),
            Projection::Fisheye(Fisheye::new(250.0).unwrap()),
            Projection::Ods(Ods::new(0.064).unwrap()),
        ];
        for projection in projections {
            let (still, moving) = (looking_down_z(projection), looking_down_z(projection));
            let moving = moving.with_velocity(Vec3::new(v, 0.0, 0.0)).unwrap();
            for (x, y) in [(30.0, 20.0), (70.0, 45.0), (51.0, 5.0)] {
                let (seen, r) =
                    (ray_at(&still, x, y, [100, 100], [0.5; 2]), ray_at(&moving, x, y, [100, 100], [0.5; 2]));
                let (Some(seen), Some(r)) = (seen, r) else { panic!("{projection:?} at ({x}, {y}): no ray") };
                let (cos_seen, cos_static) = (seen.direction.x, r.direction.x);
                assert!(((cos_static + v) / (1.0 + v * cos_static) - cos_seen).abs() < 1e-12, "{projection:?}");
                assert_eq!(r.origin, seen.origin, "{projection:?}");
                let d = (1.0 + v * cos_static) / (1.0 - v * v).sqrt();
                assert!((f64::from(r.weight()) / d.powi(4) - 1.0).abs() < 1e-6, "{projection:?}");
            }
        }
    }

    #[test]
    fn degenerate_cameras_are_rejected() {
        assert!(Camera::new(Region::Upper, Vec3::ZERO, Vec3::ZERO, Vec3::Y, 40.0, 0.0, None).is_err());
        assert!(Camera::new(Region::Upper, Vec3::ZERO, Vec3::Y, Vec3::Y, 40.0, 0.0, None).is_err());
        assert!(Camera::new(Region::Upper, Vec3::ZERO, Vec3::Z, Vec3::Y, 180.0, 0.0, None).is_err());
        let nowhere = Vec3::new(f64::NAN, 0.0, 0.0);
        assert!(Camera::oriented(
            Region::Upper,
            nowhere,
            DQuat::IDENTITY,
            Projection::Equirectangular(Equirectangular)
        )
        .is_err());
    }
}

//! The pinhole / thin-lens camera. It is a static observer at its position; the directions it
//! produces are in its local orthonormal frame, whose axes are aligned with the world's, and the
//! propagator turns them into null momenta of the spacetime.

use crate::geometry::Vec3;
use crate::sampling::concentric_disk;
use glam::{DMat3, DQuat};
use spacetime::tensor::ETA;
use spacetime::{Minkowski, Region, Tetrad};

/// A camera: where it is, where it looks, and its lens.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Camera {
    pub region: Region,
    pub position: Vec3,
    /// Unit axes of the image: right, up, and the viewing direction.
    right: Vec3,
    up: Vec3,
    forward: Vec3,
    /// `tan(vfov / 2)`.
    tan_half_fov: f64,
    /// Radius of the thin lens (0 for a pinhole).
    pub lens_radius: f64,
    /// Distance to the plane in focus, along `forward`.
    pub focus_distance: f64,
    /// The camera's motion relative to the static observer at its position, if it moves.
    motion: Option<Motion>,
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
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CameraRay {
    pub origin: Vec3,
    pub direction: Vec3,
    /// `D⁴` with `D = ν_camera / ν_static` the Doppler factor (`I_ν/ν³` is invariant, so
    /// frequency-integrated radiance scales as `ν⁴`); 1 for a camera at rest. Colours are not
    /// shifted: RGB has no spectrum to shift, so only the brightness changes.
    pub weight: f32,
}

impl Camera {
    /// A camera at `position` looking at `look_at`, with `up` roughly up and vertical field of
    /// view `vfov_deg` (degrees, in (0, 180)). `lens_radius > 0` gives depth of field focused at
    /// `focus_distance` (default: the distance to `look_at`).
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
        Camera::oriented(region, position, orientation, vfov_deg, lens_radius, focus_distance)
    }

    /// A camera at `position` whose image axes (right, up, backwards) are the world axes rotated
    /// by `orientation`; see [`look_rotation`].
    pub fn oriented(
        region: Region,
        position: Vec3,
        orientation: DQuat,
        vfov_deg: f64,
        lens_radius: f64,
        focus_distance: f64,
    ) -> Result<Camera, String> {
        if !position.is_finite() || !orientation.is_finite() {
            return Err("position and orientation must be finite".into());
        }
        if !(vfov_deg > 0.0 && vfov_deg < 180.0) {
            return Err(format!("fov must be in (0, 180) degrees, got {vfov_deg}"));
        }
        if !(lens_radius >= 0.0 && lens_radius.is_finite()) {
            return Err(format!("aperture must be a finite number ≥ 0, got {lens_radius}"));
        }
        if !(focus_distance > 0.0 && focus_distance.is_finite()) {
            return Err(format!("focus distance must be > 0, got {focus_distance}"));
        }
        let orientation = orientation.normalize();
        Ok(Camera {
            region,
            position,
            right: orientation * Vec3::X,
            up: orientation * Vec3::Y,
            forward: orientation * Vec3::NEG_Z,
            tan_half_fov: (0.5 * vfov_deg.to_radians()).tan(),
            lens_radius,
            focus_distance,
            motion: None,
        })
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
        self.forward
    }

    /// The ray through film position `(x, y)` in pixels of a `width × height` image (x right, y
    /// down), with lens sample `lens_u`.
    pub fn ray(&self, x: f64, y: f64, width: u32, height: u32, lens_u: [f64; 2]) -> CameraRay {
        let aspect = f64::from(width) / f64::from(height);
        let sx = (2.0 * x / f64::from(width) - 1.0) * self.tan_half_fov * aspect;
        let sy = (1.0 - 2.0 * y / f64::from(height)) * self.tan_half_fov;
        let dir = (self.forward + sx * self.right + sy * self.up).normalize();
        let (origin, direction) = if self.lens_radius == 0.0 {
            (self.position, dir)
        } else {
            // Thin lens: all rays through the lens meet at the focus point of the pinhole ray.
            let focus = self.position + dir * (self.focus_distance / dir.dot(self.forward));
            let [lx, ly] = concentric_disk(lens_u);
            let origin = self.position + self.lens_radius * (lx * self.right + ly * self.up);
            (origin, (focus - origin).normalize())
        };
        match &self.motion {
            None => CameraRay { origin, direction, weight: 1.0 },
            Some(m) => {
                // The backward ray of unit energy in the camera's frame, seen by the static
                // observer: direction (aberration) and energy E = ν_static/ν_camera.
                let p = m.moving.backward_momentum(&ETA, direction.to_array(), 1.0);
                let (n, energy) = m.rest.backward_direction(&p);
                CameraRay { origin, direction: Vec3::from_array(n), weight: energy.powi(-4) as f32 }
            }
        }
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

    #[test]
    fn centre_ray_looks_at_the_target_and_corners_span_the_fov() {
        let c = Camera::new(Region::Upper, Vec3::ZERO, Vec3::new(0.0, 0.0, -1.0), Vec3::Y, 90.0, 0.0, None).unwrap();
        let r = c.ray(50.0, 50.0, 100, 100, [0.5, 0.5]);
        assert!((r.direction - Vec3::new(0.0, 0.0, -1.0)).length() < 1e-12);
        let top_left = c.ray(0.0, 0.0, 100, 100, [0.5, 0.5]).direction;
        // tan 45° = 1: the corner direction is (−1, 1, −1)/√3.
        assert!((top_left - Vec3::new(-1.0, 1.0, -1.0).normalize()).length() < 1e-12);
    }

    #[test]
    fn thin_lens_rays_meet_in_the_focal_plane() {
        let c = Camera::new(Region::Upper, Vec3::ZERO, Vec3::new(0.0, 0.0, -4.0), Vec3::Y, 40.0, 0.2, None).unwrap();
        let a = c.ray(10.0, 20.0, 64, 64, [0.1, 0.9]);
        let b = c.ray(10.0, 20.0, 64, 64, [0.8, 0.3]);
        let at_plane = |r: CameraRay| r.origin + r.direction * ((-4.0 - r.origin.z) / r.direction.z);
        assert!((at_plane(a) - at_plane(b)).length() < 1e-12);
        assert!((a.origin - b.origin).length() > 1e-3);
    }

    #[test]
    fn a_moving_camera_sees_aberration_and_doppler_shift() {
        // Moving at v towards −z (its viewing direction), a source at angle θ from the direction
        // of motion in the static frame appears at cos θ' = (cos θ + v)/(1 + v cos θ).
        let v = 0.6;
        let c = Camera::new(Region::Upper, Vec3::ZERO, Vec3::new(0.0, 0.0, -1.0), Vec3::Y, 90.0, 0.0, None)
            .unwrap()
            .with_velocity(Vec3::new(0.0, 0.0, -v))
            .unwrap();
        for x in [0.0, 10.0, 30.0, 49.0] {
            let r = c.ray(x, 50.0, 100, 100, [0.5, 0.5]);
            let seen = Camera::new(Region::Upper, Vec3::ZERO, Vec3::new(0.0, 0.0, -1.0), Vec3::Y, 90.0, 0.0, None)
                .unwrap()
                .ray(x, 50.0, 100, 100, [0.5, 0.5])
                .direction;
            let (cos_seen, cos_static) = (-seen.z, -r.direction.z);
            assert!(((cos_static + v) / (1.0 + v * cos_static) - cos_seen).abs() < 1e-12, "x = {x}");
            // Doppler factor D = ν_camera/ν_static = γ(1 + v cos θ) = 1/(γ(1 − v cos θ')).
            let gamma = 1.0 / (1.0 - v * v).sqrt();
            let d = gamma * (1.0 + v * cos_static);
            assert!((d * gamma * (1.0 - v * cos_seen) - 1.0).abs() < 1e-12);
            assert!((f64::from(r.weight) / d.powi(4) - 1.0).abs() < 1e-6);
        }
        let still = c.with_velocity(Vec3::ZERO).unwrap().ray(10.0, 20.0, 100, 100, [0.5, 0.5]);
        assert_eq!(still.weight, 1.0);
        assert!(c.with_velocity(Vec3::new(0.6, 0.8, 0.0)).is_err(), "speed of light");
    }

    #[test]
    fn degenerate_cameras_are_rejected() {
        assert!(Camera::new(Region::Upper, Vec3::ZERO, Vec3::ZERO, Vec3::Y, 40.0, 0.0, None).is_err());
        assert!(Camera::new(Region::Upper, Vec3::ZERO, Vec3::Y, Vec3::Y, 40.0, 0.0, None).is_err());
        assert!(Camera::new(Region::Upper, Vec3::ZERO, Vec3::Z, Vec3::Y, 180.0, 0.0, None).is_err());
    }
}

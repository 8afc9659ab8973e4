//! Camera motion for animations: keyframes interpolated smoothly, or an orbit, and the velocity
//! of the observer that motion implies.
//!
//! Positions follow a cubic Hermite spline with Catmull–Rom tangents for unevenly spaced keys
//! (`m_i = (p_{i+1} − p_{i−1}) / (t_{i+1} − t_{i−1})`), so position and velocity are continuous;
//! orientations are slerped between keys; field of view and focus distance are linear. Before
//! the first key and after the last the camera holds still.

use crate::camera::{Camera, Perspective, Projection};
use crate::geometry::Vec3;
use crate::propagator::chart_rotation;
use glam::DQuat;
use spacetime::{Region, Spacetime};

/// The camera's pose at one key time (seconds of animation).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Keyframe {
    pub time: f64,
    pub position: Vec3,
    /// Rotation from the world axes x, y, −z to the image's right, up, forward.
    pub orientation: DQuat,
    /// Vertical field of view, degrees.
    pub fov: f64,
    pub focus_distance: f64,
}

/// Where the camera is at a time, and how fast its world position changes.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Pose {
    pub position: Vec3,
    pub orientation: DQuat,
    pub fov: f64,
    pub focus_distance: f64,
    /// `dposition/dt`, scene units per second of animation.
    pub velocity: Vec3,
}

/// How the camera moves.
#[derive(Clone, Debug, PartialEq)]
pub enum CameraPath {
    /// Interpolated keyframes, at strictly increasing times; one key is a still camera.
    Keyframes(Vec<Keyframe>),
    /// The pose `start` (its time is ignored) turned rigidly about the line through `center`
    /// along the unit `axis`, one full turn per `period` seconds (negative: the other way).
    Orbit { start: Keyframe, center: Vec3, axis: Vec3, period: f64 },
}

/// The camera's state of motion, which sets the frame it sees the world in.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Observer {
    /// At rest: the static observer at its position.
    Static,
    /// Moving with a fixed 3-velocity (units of c, world axes) relative to the static observer.
    Velocity(Vec3),
    /// Moving along its own path; `speed_of_light` (scene units per second of animation) turns
    /// the path's speed into a velocity in units of c.
    FromPath { speed_of_light: f64 },
}

/// Everything that makes the camera of a frame: its path, projection, region and state of motion.
#[derive(Clone, Debug, PartialEq)]
pub struct CameraRig {
    pub region: Region,
    pub path: CameraPath,
    /// The projection; a perspective one takes its field of view and focus distance from each
    /// pose (its lens radius is the rig's), the others are the same at every pose.
    pub projection: Projection,
    pub observer: Observer,
}

impl CameraPath {
    /// Keyframes, checked: at least one, times finite and strictly increasing.
    pub fn keyframes(keys: Vec<Keyframe>) -> Result<CameraPath, String> {
        if keys.is_empty() {
            return Err("a camera path needs at least one keyframe".into());
        }
        if let Some(k) = keys.iter().find(|k| !k.time.is_finite()) {
            return Err(format!("keyframe time must be finite, got {}", k.time));
        }
        if let Some(w) = keys.windows(2).find(|w| !(w[1].time > w[0].time)) {
            return Err(format!("keyframe times must increase: {} follows {}", w[1].time, w[0].time));
        }
        Ok(CameraPath::Keyframes(keys))
    }

    /// The time the motion takes: from 0 to the last key, or one turn of an orbit.
    pub fn duration(&self) -> f64 {
        match self {
            CameraPath::Keyframes(keys) => keys.last().map_or(0.0, |k| k.time.max(0.0)),
            CameraPath::Orbit { period, .. } => period.abs(),
        }
    }

    /// The pose at `time` (seconds of animation).
    pub fn pose(&self, time: f64) -> Pose {
        match self {
            CameraPath::Keyframes(keys) => keyframed_pose(keys, time),
            CameraPath::Orbit { start, center, axis, period } => {
                let rate = std::f64::consts::TAU / period;
                let turn = DQuat::from_axis_angle(*axis, rate * time);
                let position = *center + turn * (start.position - *center);
                Pose {
                    position,
                    orientation: turn * start.orientation,
                    fov: start.fov,
                    focus_distance: start.focus_distance,
                    velocity: rate * axis.cross(position - *center),
                }
            }
        }
    }
}

fn still(key: &Keyframe) -> Pose {
    Pose {
        position: key.position,
        orientation: key.orientation,
        fov: key.fov,
        focus_distance: key.focus_distance,
        velocity: Vec3::ZERO,
    }
}

fn keyframed_pose(keys: &[Keyframe], time: f64) -> Pose {
    let (Some(first), Some(last)) = (keys.first(), keys.last()) else {
        unreachable!("CameraPath::keyframes guarantees a key");
    };
    if keys.len() == 1 || !(time > first.time) {
        return still(first);
    }
    if time >= last.time {
        return still(last);
    }
    // The segment [t_i, t_{i+1}) holding `time`.
    let i = keys.partition_point(|k| k.time <= time) - 1;
    let (a, b) = (&keys[i], &keys[i + 1]);
    let tangent = |j: usize| {
        let (lo, hi) = (&keys[j.saturating_sub(1)], &keys[(j + 1).min(keys.len() - 1)]);
        (hi.position - lo.position) / (hi.time - lo.time)
    };
    let h = b.time - a.time;
    let s = (time - a.time) / h;
    let (ma, mb) = (tangent(i) * h, tangent(i + 1) * h);
    // Cubic Hermite basis and its derivative in s.
    let (s2, s3) = (s * s, s * s * s);
    let position = (2.0 * s3 - 3.0 * s2 + 1.0) * a.position
        + (s3 - 2.0 * s2 + s) * ma
        + (3.0 * s2 - 2.0 * s3) * b.position
        + (s3 - s2) * mb;
    let velocity = ((6.0 * s2 - 6.0 * s) * a.position
        + (3.0 * s2 - 4.0 * s + 1.0) * ma
        + (6.0 * s - 6.0 * s2) * b.position
        + (3.0 * s2 - 2.0 * s) * mb)
        / h;
    Pose {
        position,
        orientation: a.orientation.slerp(b.orientation, s),
        fov: a.fov + s * (b.fov - a.fov),
        focus_distance: a.focus_distance + s * (b.focus_distance - a.focus_distance),
        velocity,
    }
}

impl CameraRig {
    /// Whether an observer can stay at rest where the camera is at `time` (its velocity, if any,
    /// is measured against that observer), in `spacetime` with its symmetry axis along the world
    /// vector `axis`; the error says why not and where.
    pub fn at_rest(&self, time: f64, spacetime: &Spacetime, axis: Vec3) -> Result<(), String> {
        let position = self.path.pose(time).position;
        let answers = spacetime.capabilities();
        let chart = if answers.is_spherically_symmetric() { position } else { chart_rotation(axis) * position };
        answers.rest(self.region, chart.to_array()).map_err(|e| format!("the camera at {position} {e}"))
    }

    /// The camera at `time` (seconds of animation) in `spacetime`, whose symmetry axis points
    /// along the world vector `axis`. Errors name the time: a place where nothing can stay at
    /// rest, a pose the camera cannot take, or a motion as fast as light.
    pub fn camera_at(&self, time: f64, spacetime: &Spacetime, axis: Vec3) -> Result<Camera, String> {
        let at = |e: String| format!("camera at t = {time} s: {e}");
        self.at_rest(time, spacetime, axis).map_err(at)?;
        let pose = self.path.pose(time);
        let projection = match self.projection {
            Projection::Perspective(lens) => {
                Projection::Perspective(Perspective::new(pose.fov, lens.lens_radius, pose.focus_distance).map_err(at)?)
            }
            Projection::Equirectangular(_) | Projection::Fisheye(_) | Projection::Ods(_) => self.projection,
        };
        let camera = Camera::oriented(self.region, pose.position, pose.orientation, projection).map_err(at)?;
        let velocity = match self.observer {
            Observer::Static => Vec3::ZERO,
            Observer::Velocity(v) => v,
            Observer::FromPath { speed_of_light } => {
                local_velocity(spacetime, axis, self.region, pose.position, pose.velocity / speed_of_light)
                    .map_err(at)?
            }
        };
        camera.with_velocity(velocity).map_err(at)
    }
}

/// The velocity (units of c) that the static observer at `position` measures for a camera whose
/// world position changes by `dp_dt` per unit coordinate time (c = 1).
fn local_velocity(
    spacetime: &Spacetime,
    axis: Vec3,
    region: Region,
    position: Vec3,
    dp_dt: Vec3,
) -> Result<Vec3, String> {
    let to_chart = chart_rotation(axis);
    let measured = spacetime::observer::local_velocity(
        spacetime.metric(),
        region,
        (to_chart * position).to_array(),
        (to_chart * dp_dt).to_array(),
    );
    match measured {
        None => Err("no observer can be at rest there (inside a throat or horizon)".into()),
        Some(Err(_)) => Err(format!(
            "moving at {:.3} scene units per unit time is not slower than light there; raise speed_of_light",
            dp_dt.length()
        )),
        Some(Ok(v)) => Ok(to_chart.inverse() * Vec3::from_array(v)),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::camera::look_rotation;

    fn key(time: f64, position: Vec3, look_at: Vec3) -> Keyframe {
        let orientation = look_rotation(look_at - position, Vec3::Y).unwrap();
        Keyframe { time, position, orientation, fov: 40.0, focus_distance: 1.0 }
    }

    #[test]
    fn keyframes_are_interpolated_through_with_continuous_velocity() {
        let keys = vec![
            key(0.0, Vec3::new(0.0, 0.0, 5.0), Vec3::ZERO),
            key(1.0, Vec3::new(5.0, 0.0, 0.0), Vec3::ZERO),
            key(3.0, Vec3::new(0.0, 0.0, -5.0), Vec3::ZERO),
        ];
        let path = CameraPath::keyframes(keys.clone()).unwrap();
        for k in &keys {
            let p = path.pose(k.time);
            assert!((p.position - k.position).length() < 1e-12);
            assert!(p.orientation.angle_between(k.orientation) < 1e-6);
        }
        // Velocity is the derivative of position, and continuous across the middle key.
        for t in [0.3, 0.999_999, 1.000_001, 2.2] {
            let h = 1e-6;
            let numeric = (path.pose(t + h).position - path.pose(t - h).position) / (2.0 * h);
            assert!((numeric - path.pose(t).velocity).length() < 1e-6, "t = {t}");
        }
        // Catmull–Rom tangent at the middle key: (p₂ − p₀)/(t₂ − t₀).
        assert!((path.pose(1.0).velocity - Vec3::new(0.0, 0.0, -10.0 / 3.0)).length() < 1e-9);
        // Outside the keys the camera holds still.
        assert_eq!(path.pose(-1.0).velocity, Vec3::ZERO);
        assert_eq!(path.pose(7.0).position, keys[2].position);
        assert!(CameraPath::keyframes(vec![keys[1], keys[0]]).is_err());
        assert!(CameraPath::keyframes(Vec::new()).is_err());
    }

    #[test]
    fn an_orbit_circles_its_centre_looking_the_same_way_relative_to_it() {
        let start = key(0.0, Vec3::new(0.0, 1.0, 4.0), Vec3::new(0.0, 1.0, 0.0));
        let path = CameraPath::Orbit { start, center: Vec3::new(0.0, 1.0, 0.0), axis: Vec3::Y, period: 8.0 };
        let quarter = path.pose(2.0);
        assert!((quarter.position - Vec3::new(4.0, 1.0, 0.0)).length() < 1e-12);
        let forward = quarter.orientation * Vec3::NEG_Z;
        assert!((forward - Vec3::NEG_X).length() < 1e-12);
        assert!((quarter.velocity.length() - std::f64::consts::TAU * 4.0 / 8.0).abs() < 1e-12);
        assert!((path.pose(8.0).position - start.position).length() < 1e-12);
    }

    #[test]
    fn a_camera_moving_along_its_path_is_boosted_by_its_speed() {
        let rig = |observer| CameraRig {
            region: Region::Upper,
            path: CameraPath::keyframes(vec![
                key(0.0, Vec3::new(0.0, 0.0, 10.0), Vec3::ZERO),
                key(1.0, Vec3::new(0.0, 0.0, 4.0), Vec3::ZERO),
            ])
            .unwrap(),
            projection: Projection::Perspective(Perspective::new(40.0, 0.0, 1.0).unwrap()),
            observer,
        };
        let flat = Spacetime::Minkowski(spacetime::Minkowski);
        // Two keys: the spline is the straight line at 6 units/s; with c = 12 units/s, 0.5 c.
        let moving = rig(Observer::FromPath { speed_of_light: 12.0 }).camera_at(0.5, &flat, Vec3::Y).unwrap();
        let fixed = rig(Observer::Velocity(Vec3::new(0.0, 0.0, -0.5))).camera_at(0.5, &flat, Vec3::Y).unwrap();
        let ray = |c: Camera| c.ray([3, 4], [0.0; 2], [10, 10], [0.5; 2]).unwrap();
        let (a, b) = (ray(moving), ray(fixed));
        // Equal up to the finite-difference Jacobian of the world → chart map (~1e-11).
        assert!((a.direction - b.direction).length() < 1e-9 && (a.doppler / b.doppler - 1.0).abs() < 1e-6);
        let err = rig(Observer::FromPath { speed_of_light: 5.0 }).camera_at(0.5, &flat, Vec3::Y).unwrap_err();
        assert!(err.contains("t = 0.5") && err.contains("speed_of_light"), "{err}");
    }
}

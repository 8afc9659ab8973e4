//! `[camera]` and `[animation]`: a still camera, keyframes or an orbit, the observer's motion,
//! and the frames of an animation.

use super::Builder;
use crate::reader::{fmt_vec, num, Kind, Result, Table};
use render::camera::{look_rotation, Equirectangular, Fisheye, Ods, Perspective, Projection};
use render::camera_path::{CameraPath, CameraRig, Keyframe, Observer, Pose};
use render::geometry::Vec3;
use render::scene::Animation;
use spacetime::Spacetime;

pub(super) const CAMERA_KEYS: &[&str] = &[
    "position",
    "look_at",
    "up",
    "fov",
    "aperture",
    "focus_distance",
    "region",
    "projection",
    "fisheye_fov",
    "ipd",
    "velocity",
    "speed_of_light",
    "keyframes",
    "orbit",
    "gltf_camera",
];
const KEYFRAME_KEYS: &[&str] = &["time", "position", "look_at", "up", "fov", "focus_distance"];
const ORBIT_KEYS: &[&str] = &["center", "axis", "period"];
pub(super) const ANIMATION_KEYS: &[&str] = &["fps", "frames"];

/// The index of `"perspective"` in [`PROJECTIONS`], the default.
const PERSPECTIVE: usize = 0;

/// Reads a projection's own fields from `[camera]`; `start` is the pose at time 0.
type ReadProjection = fn(&Table<'_>, &Pose) -> Result<Projection>;

/// The projections by name, each with the fields of `[camera]` only it reads and how it reads
/// them.
const PROJECTIONS: &[Kind<ReadProjection>] = &[
    Kind { name: "perspective", keys: &["fov", "aperture", "focus_distance"], build: perspective },
    Kind { name: "equirectangular", keys: &[], build: |_, _| Ok(Projection::Equirectangular(Equirectangular)) },
    Kind { name: "fisheye", keys: &["fisheye_fov"], build: fisheye },
    Kind { name: "ods", keys: &["ipd"], build: ods },
];

/// The fields a keyframe inherits from `[camera]`.
struct Defaults {
    up: Vec3,
    fov: f64,
    focus_distance: Option<f64>,
}

impl Builder<'_> {
    /// `[camera]`: the camera's rig (its path, projection, region and motion).
    pub(super) fn camera_rig(&self, t: &Table<'_>) -> Result<CameraRig> {
        let defaults = Defaults {
            up: t.or("up", Vec3::Y, |n| n.direction())?,
            fov: t.or("fov", 40.0, |n| n.f64())?,
            focus_distance: t.opt("focus_distance", |n| n.f64())?,
        };
        let names: Vec<&str> = PROJECTIONS.iter().map(|p| p.name).collect();
        let kind = t.get("projection").map(|n| n.keyword("projection", &names)).transpose()?.unwrap_or(PERSPECTIVE);
        only_own_fields(t, kind)?;
        let path = match (t.get("keyframes"), t.get("orbit")) {
            (Some(_), Some(orbit)) => return Err(orbit.err("give either keyframes or an orbit, not both")),
            (Some(keys), None) => keyframes(t, &keys.array()?, &defaults, kind)?,
            (None, orbit) => {
                let start = match t.get("gltf_camera") {
                    Some(n) => self.gltf_keyframe(t, &n)?,
                    None => keyframe(t, 0.0, &defaults)?,
                };
                match orbit {
                    Some(orbit) => orbit_path(&orbit.table(ORBIT_KEYS)?, start)?,
                    None => CameraPath::Keyframes(vec![start]),
                }
            }
        };
        let projection = (PROJECTIONS[kind].build)(t, &path.pose(0.0))?;
        Ok(CameraRig { region: self.region(t)?, path, projection, observer: observer(t)? })
    }

    /// The pose of the glTF camera named by `name` (field `gltf_camera` of `t`), its field of
    /// view unless `t` gives `fov`.
    fn gltf_keyframe(&self, t: &Table<'_>, name: &crate::reader::Node<'_>) -> Result<Keyframe> {
        for key in ["position", "look_at", "up"] {
            if let Some(n) = t.get(key) {
                return Err(n.err("the glTF camera (gltf_camera) gives the pose: leave out position, look_at and up"));
            }
        }
        let wanted = name.str()?;
        let Some(camera) = self.gltf_cameras.iter().find(|c| c.name == wanted) else {
            let mut known: Vec<String> = self.gltf_cameras.iter().map(|c| format!("\"{}\"", c.name)).collect();
            known.sort_unstable();
            let known =
                if known.is_empty() { "they have none".to_owned() } else { format!("they have {}", known.join(", ")) };
            return Err(name.err(format!("no camera named \"{wanted}\" in the scene's glTF objects; {known}")));
        };
        let orientation = look_rotation(camera.forward, camera.up)
            .map_err(|_| name.err(format!("glTF camera \"{wanted}\" has a degenerate transform")))?;
        let fov = t.or("fov", camera.fov, |n| n.f64())?;
        if !(fov > 0.0 && fov < 180.0) {
            return Err(t.loc("fov").err(format!("must be in (0, 180) degrees, got {}", num(fov))));
        }
        let focus_distance = match (t.get("aperture"), t.opt("focus_distance", |n| n.f64())?) {
            (_, Some(d)) if !(d > 0.0 && d.is_finite()) => {
                return Err(t.loc("focus_distance").err(format!("must be > 0, got {}", num(d))))
            }
            (_, Some(d)) => d,
            (Some(n), None) => return Err(n.err("a glTF camera with an aperture needs a focus_distance")),
            // A pinhole is sharp at every distance.
            (None, None) => 1.0,
        };
        Ok(Keyframe { time: 0.0, position: camera.position, orientation, fov, focus_distance })
    }
}

/// An error for a field of table `t` that only another projection than `PROJECTIONS[kind]` reads.
fn only_own_fields(t: &Table<'_>, kind: usize) -> Result<()> {
    for (i, owner) in PROJECTIONS.iter().enumerate().filter(|(i, _)| *i != kind) {
        if let Some(n) = owner.keys.iter().filter(|f| t.allows(f)).find_map(|f| t.get(f)) {
            let what = if i == PERSPECTIVE {
                " (field of view, depth of field and focus are a perspective lens's)"
            } else {
                ""
            };
            return Err(n.err(format!(
                "only used with projection = \"{}\"{what}; this camera's projection is \"{}\"",
                owner.name, PROJECTIONS[kind].name
            )));
        }
    }
    Ok(())
}

/// `projection = "perspective"`: the pose's field of view and focus, and `aperture` (the lens
/// radius, 0 for a pinhole).
fn perspective(t: &Table<'_>, start: &Pose) -> Result<Projection> {
    let aperture = t.or("aperture", 0.0, |n| n.f64())?;
    if !(aperture >= 0.0 && aperture.is_finite()) {
        return Err(t.loc("aperture").err(format!("must be a finite number ≥ 0, got {}", num(aperture))));
    }
    // The pose's field of view and focus were checked where they were read.
    let lens = Perspective::new(start.fov, aperture, start.focus_distance).map_err(|e| t.err(e))?;
    Ok(Projection::Perspective(lens))
}

/// `projection = "fisheye"`: `fisheye_fov`, degrees across the image's inscribed circle.
fn fisheye(t: &Table<'_>, _: &Pose) -> Result<Projection> {
    let fov = t.or("fisheye_fov", 180.0, |n| n.f64())?;
    if !(fov > 0.0 && fov <= 360.0) {
        return Err(t.loc("fisheye_fov").err(format!("must be in (0, 360] degrees, got {}", num(fov))));
    }
    Fisheye::new(fov).map(Projection::Fisheye).map_err(|e| t.loc("fisheye_fov").err(e))
}

/// `projection = "ods"`: `ipd`, the interpupillary distance in scene units.
fn ods(t: &Table<'_>, _: &Pose) -> Result<Projection> {
    let ipd = t.or("ipd", 0.064, |n| n.f64())?;
    if !(ipd > 0.0) {
        return Err(t.loc("ipd").err(format!("must be a distance > 0, got {}", num(ipd))));
    }
    Ods::new(ipd).map(Projection::Ods).map_err(|e| t.loc("ipd").err(e))
}

/// A pose from `position`, `look_at`, `up`, `fov` and `focus_distance` of table `t`, with
/// `[camera]`'s values as defaults.
fn keyframe(t: &Table<'_>, time: f64, defaults: &Defaults) -> Result<Keyframe> {
    let position = t.req("position", |n| n.vec3())?;
    let look_at = t.req("look_at", |n| n.vec3())?;
    let up = t.or("up", defaults.up, |n| n.direction())?;
    let fov = t.or("fov", defaults.fov, |n| n.f64())?;
    let focus_distance = t.opt("focus_distance", |n| n.f64())?.or(defaults.focus_distance);
    let forward = look_at - position;
    if forward.length_squared() == 0.0 || !forward.length_squared().is_finite() {
        return Err(t.loc("look_at").err(format!("must differ from position {}", fmt_vec(position))));
    }
    let orientation = look_rotation(forward, up).map_err(|_| {
        t.loc("up").err(format!("up {} is parallel to the viewing direction {}", fmt_vec(up), fmt_vec(forward)))
    })?;
    if !(fov > 0.0 && fov < 180.0) {
        return Err(t.loc("fov").err(format!("must be in (0, 180) degrees, got {}", num(fov))));
    }
    let focus_distance = focus_distance.unwrap_or(forward.length());
    if !(focus_distance > 0.0 && focus_distance.is_finite()) {
        return Err(t.loc("focus_distance").err(format!("must be > 0, got {}", num(focus_distance))));
    }
    Ok(Keyframe { time, position, orientation, fov, focus_distance })
}

/// `[[camera.keyframes]]`: each with its `time`; `[camera]` then gives no pose of its own.
fn keyframes(
    camera: &Table<'_>,
    elements: &[crate::reader::Node<'_>],
    defaults: &Defaults,
    projection: usize,
) -> Result<CameraPath> {
    for key in ["position", "look_at", "gltf_camera"] {
        if let Some(n) = camera.get(key) {
            return Err(n.err("with keyframes, give position and look_at in each keyframe"));
        }
    }
    if elements.is_empty() {
        return Err(camera.loc("keyframes").err("needs at least one keyframe"));
    }
    let mut keys: Vec<Keyframe> = Vec::with_capacity(elements.len());
    for element in elements {
        let t = element.table(KEYFRAME_KEYS)?;
        only_own_fields(&t, projection)?;
        let time = t.req("time", |n| n.f64())?;
        if let Some(previous) = keys.last().filter(|k| !(time > k.time)) {
            return Err(t.loc("time").err(format!(
                "keyframe times must increase: {} follows {}",
                num(time),
                num(previous.time)
            )));
        }
        keys.push(keyframe(&t, time, defaults)?);
    }
    // Times are finite (`f64` checks) and increasing (checked above, where the error has a line).
    Ok(CameraPath::Keyframes(keys))
}

/// `[camera.orbit]`: the `[camera]` pose turned about an axis through `center`.
fn orbit_path(t: &Table<'_>, start: Keyframe) -> Result<CameraPath> {
    let center = t.req("center", |n| n.vec3())?;
    let axis = t.or("axis", Vec3::Y, |n| n.direction())?;
    let period = t.req("period", |n| n.f64())?;
    if !(period.is_finite() && period != 0.0) {
        return Err(t.loc("period").err(format!("must be a finite, non-zero number of seconds, got {}", num(period))));
    }
    Ok(CameraPath::Orbit { start, center, axis: axis.normalize(), period })
}

/// `velocity`: absent (at rest), a 3-velocity in units of c, or `"from-path"` with
/// `speed_of_light` in scene units per second of animation.
fn observer(t: &Table<'_>) -> Result<Observer> {
    let speed_of_light = t.opt("speed_of_light", |n| n.f64())?;
    let Some(v) = t.get("velocity") else {
        return match speed_of_light {
            Some(_) => Err(t.loc("speed_of_light").err("only used with velocity = \"from-path\"")),
            None => Ok(Observer::Static),
        };
    };
    if v.is_str() {
        v.keyword("velocity", &["from-path"])?;
        let Some(c) = speed_of_light else {
            return Err(t.loc("speed_of_light").err(
                "required with velocity = \"from-path\": the speed of light in scene units per second of animation",
            ));
        };
        if !(c > 0.0 && c.is_finite()) {
            return Err(t.loc("speed_of_light").err(format!("must be > 0, got {}", num(c))));
        }
        return Ok(Observer::FromPath { speed_of_light: c });
    }
    if speed_of_light.is_some() {
        return Err(t.loc("speed_of_light").err("only used with velocity = \"from-path\""));
    }
    let velocity = v.vec3()?;
    if !(velocity.length() < 1.0) {
        return Err(v.err(format!(
            "speed {} is not below the speed of light (velocity is in units of c)",
            num(velocity.length())
        )));
    }
    Ok(Observer::Velocity(velocity))
}

/// `[animation]`: frames per second and, optionally, the number of frames
/// (default: [`Animation::frame_count`]).
pub(super) fn animation(
    t: Option<&Table<'_>>,
    camera: &Table<'_>,
    rig: CameraRig,
    spacetime: &Spacetime,
    axis: Vec3,
) -> Result<Animation> {
    let (fps, frames) = match t {
        None => (24.0, None),
        Some(t) => {
            let fps = t.or("fps", 24.0, |n| n.f64())?;
            if !(fps > 0.0 && fps <= 1000.0) {
                return Err(t.loc("fps").err(format!("must be in (0, 1000], got {}", num(fps))));
            }
            (fps, t.opt("frames", |n| n.u32_in(1, 1_000_000))?)
        }
    };
    let animation = Animation { rig, fps, frames };
    // A path-borne speed can reach c somewhere: find it now rather than frames into a render.
    let moving = matches!(animation.rig.observer, Observer::FromPath { .. });
    for frame in 0..if moving { animation.frame_count().min(1_000_000) } else { 1 } {
        animation.rig.camera_at(animation.time(frame), spacetime, axis).map_err(|e| camera.err(e))?;
    }
    Ok(animation)
}

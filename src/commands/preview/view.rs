//! What the page has changed: the camera's pose (orbit and fly controls), the spacetime's
//! parameters (sliders) and the preview's samples per pixel, each checked as it arrives (the
//! page is untrusted input: numbers must be finite and in range, unknown fields are errors), and
//! applied to the scene file's scene to make the scene the preview renders.

use super::parameters::with_values;
use render::camera::look_rotation;
use render::camera_path::{CameraPath, Keyframe};
use render::geometry::Vec3;
use render::scene::Scene;
use std::collections::BTreeMap;

/// Most samples per pixel a preview refines to.
pub const MAX_SPP: u32 = 4096;
/// Largest coordinate a camera may be given, in scene units.
const MAX_COORDINATE: f64 = 1e6;

/// A camera pose as the page sends it and as `[views.NAME]` stores it.
#[derive(Clone, Copy, Debug, PartialEq, serde::Deserialize, serde::Serialize)]
#[serde(deny_unknown_fields)]
pub struct Eye {
    pub position: [f64; 3],
    pub look_at: [f64; 3],
    pub up: [f64; 3],
    /// Vertical field of view, degrees.
    pub fov: f64,
}

/// `POST /settings`: new parameter values and samples per pixel; absent ones keep theirs.
#[derive(Debug, serde::Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SettingsRequest {
    #[serde(default)]
    pub parameters: BTreeMap<String, f64>,
    pub spp: Option<u32>,
}

/// The page's changes to the scene file's scene.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Overrides {
    pub eye: Option<Eye>,
    pub parameters: BTreeMap<String, f64>,
    pub spp: Option<u32>,
}

impl Eye {
    /// The scene's own camera pose (at time 0).
    pub fn of(scene: &Scene) -> Option<Eye> {
        let pose = scene.animation.as_ref()?.rig.path.pose(0.0);
        let forward = pose.orientation * Vec3::NEG_Z;
        let look_at = pose.position + forward * pose.focus_distance;
        Some(Eye {
            position: pose.position.to_array(),
            look_at: look_at.to_array(),
            up: (pose.orientation * Vec3::Y).to_array(),
            fov: pose.fov,
        })
    }

    /// The pose as a still keyframe, checked: coordinates finite and within ±10⁶, `look_at`
    /// away from `position`, `up` not along the view, field of view in (0°, 180°).
    pub fn keyframe(&self) -> Result<Keyframe, String> {
        let vector = |name: &str, v: [f64; 3]| {
            if v.iter().all(|c| c.is_finite() && c.abs() <= MAX_COORDINATE) {
                Ok(Vec3::from_array(v))
            } else {
                Err(format!("{name} must be three finite numbers within ±{MAX_COORDINATE:e}, got {v:?}"))
            }
        };
        let position = vector("position", self.position)?;
        let forward = vector("look_at", self.look_at)? - position;
        let up = vector("up", self.up)?;
        if !(self.fov > 0.0 && self.fov < 180.0) {
            return Err(format!("fov must be in (0, 180) degrees, got {}", self.fov));
        }
        if forward.length() < 1e-9 {
            return Err("look_at must differ from position".into());
        }
        let orientation = look_rotation(forward, up)?;
        Ok(Keyframe { time: 0.0, position, orientation, fov: self.fov, focus_distance: forward.length() })
    }
}

impl SettingsRequest {
    /// `overrides` with these settings, checked against `scene` (the file's).
    pub fn apply_to(self, overrides: &Overrides, scene: &Scene) -> Result<Overrides, String> {
        if let Some(spp) = self.spp.filter(|s| !(1..=MAX_SPP).contains(s)) {
            return Err(format!("spp must be an integer from 1 to {MAX_SPP}, got {spp}"));
        }
        let mut next = overrides.clone();
        next.parameters.extend(self.parameters);
        next.spp = self.spp.or(overrides.spp);
        with_values(&scene.spacetime, &next.parameters)?;
        Ok(next)
    }
}

impl Overrides {
    /// The scene file's `scene` with these changes: its spacetime's parameters, and its camera
    /// moved to the eye (keeping its projection, region and motion), re-made in the new spacetime.
    pub fn apply(&self, scene: &Scene) -> Result<Scene, String> {
        let mut out = scene.clone();
        out.spacetime = with_values(&scene.spacetime, &self.parameters)?;
        let animation = out.animation.as_mut().ok_or("the scene has no camera rig")?;
        if let Some(eye) = &self.eye {
            animation.rig.path = CameraPath::Keyframes(vec![eye.keyframe()?]);
        }
        out.camera = animation.rig.camera_at(0.0, &out.spacetime, out.axis)?;
        Ok(out)
    }

    /// The samples per pixel to refine to: the page's, else the scene's (at most [`MAX_SPP`]).
    pub fn spp(&self, scene: &Scene) -> u32 {
        self.spp.unwrap_or(scene.settings.spp).clamp(1, MAX_SPP)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn scene() -> Scene {
        let text = "[spacetime]\ntype = \"schwarzschild\"\nmass = 0.3\n[camera]\nposition = [0, 0, 7]\n\
                    look_at = [0, 0, 0]\nfov = 50\n";
        scene::parse(text, "t.toml", ".".as_ref()).expect("valid scene")
    }

    #[test]
    fn the_scene_eye_round_trips() {
        let scene = scene();
        let eye = Eye::of(&scene).expect("a rig");
        assert_eq!(eye.position, [0.0, 0.0, 7.0]);
        assert!(eye.look_at.iter().zip([0.0, 0.0, 0.0]).all(|(a, b)| (a - b).abs() < 1e-12), "{eye:?}");
        let moved = Overrides { eye: Some(eye), ..Overrides::default() }.apply(&scene).expect("applies");
        assert!((moved.camera.position - scene.camera.position).length() < 1e-12);
    }

    #[test]
    fn bad_eyes_are_refused() {
        let good = Eye { position: [0.0, 0.0, 7.0], look_at: [0.0; 3], up: [0.0, 1.0, 0.0], fov: 40.0 };
        assert!(good.keyframe().is_ok());
        for bad in [
            Eye { position: [f64::NAN, 0.0, 0.0], ..good },
            Eye { position: [1e7, 0.0, 0.0], ..good },
            Eye { look_at: good.position, ..good },
            Eye { up: [0.0, 0.0, 1.0], ..good },
            Eye { up: [0.0; 3], ..good },
            Eye { fov: 180.0, ..good },
            Eye { fov: 0.0, ..good },
        ] {
            assert!(bad.keyframe().is_err(), "{bad:?}");
        }
    }

    #[test]
    fn settings_are_checked_against_the_scene() {
        let scene = scene();
        let request = |json: &str| serde_json::from_str::<SettingsRequest>(json);
        let ok = request(r#"{"parameters": {"mass": 0.6}, "spp": 8}"#).expect("parses");
        let next = ok.apply_to(&Overrides::default(), &scene).expect("in range");
        assert_eq!((next.parameters["mass"], next.spp), (0.6, Some(8)));
        assert_eq!(next.apply(&scene).expect("applies").spacetime.length_scale(), 0.6);
        assert!(request(r#"{"colour": 1}"#).is_err(), "unknown field");
        assert!(request(r#"{"spp": 1.5}"#).is_err());
        assert!(request(r#"{"spp": -1}"#).is_err());
        let zero = request(r#"{"spp": 0}"#).expect("parses");
        assert!(zero.apply_to(&Overrides::default(), &scene).is_err());
        let spin = request(r#"{"parameters": {"spin": 0.1}}"#).expect("parses");
        assert!(spin.apply_to(&Overrides::default(), &scene).is_err());
    }
}

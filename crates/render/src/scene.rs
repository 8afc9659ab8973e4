//! A complete scene ready to render: spacetime, camera, world and settings, and how the camera
//! moves in an animation.

use crate::camera::Camera;
use crate::camera_path::{CameraPath, CameraRig};
use crate::geometry::Vec3;
use crate::settings::RenderSettings;
use crate::world::World;
use spacetime::Spacetime;

#[derive(Clone, Debug)]
pub struct Scene {
    pub spacetime: Spacetime,
    /// The spacetime's symmetry axis in world coordinates: a Kerr hole spins about it.
    pub axis: Vec3,
    /// The camera of the frame being rendered.
    pub camera: Camera,
    pub world: World,
    pub settings: RenderSettings,
    /// How the camera moves over time; `None` for a camera that is only ever where `camera` is.
    pub animation: Option<Animation>,
}

/// An animation: the camera's rig and the frames that sample it.
#[derive(Clone, Debug, PartialEq)]
pub struct Animation {
    pub rig: CameraRig,
    /// Frames per second of animation time; frame `n` shows time `n / fps`.
    pub fps: f64,
    /// Number of frames, if the scene fixes it; see [`Animation::frame_count`].
    pub frames: Option<u32>,
}

impl Animation {
    /// The number of frames: as the scene says, or else enough to show the whole motion: the
    /// keyframed path from time 0 to its last key inclusive, or one turn of an orbit (the last
    /// frame just before the first repeats, so that the animation loops); 1 for a still camera.
    pub fn frame_count(&self) -> u32 {
        let spanned = (self.rig.path.duration() * self.fps).round().min(f64::from(u32::MAX - 1)) as u32;
        self.frames.unwrap_or(match self.rig.path {
            CameraPath::Keyframes(_) => spanned + 1,
            CameraPath::Orbit { .. } => spanned.max(1),
        })
    }

    /// The animation time (seconds) that frame `frame` shows.
    pub fn time(&self, frame: u32) -> f64 {
        f64::from(frame) / self.fps
    }
}

impl Scene {
    /// Puts the camera where its rig has it at `time` (seconds of animation).
    pub fn set_time(&mut self, time: f64) -> Result<(), String> {
        if let Some(a) = &self.animation {
            self.camera = a.rig.camera_at(time, &self.spacetime, self.axis)?;
        }
        Ok(())
    }
}

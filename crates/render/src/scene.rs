//! A complete scene ready to render: spacetime, camera, world and settings.

use crate::camera::Camera;
use crate::settings::RenderSettings;
use crate::world::World;
use spacetime::Spacetime;

#[derive(Clone, Debug)]
pub struct Scene {
    pub spacetime: Spacetime,
    pub camera: Camera,
    pub world: World,
    pub settings: RenderSettings,
}

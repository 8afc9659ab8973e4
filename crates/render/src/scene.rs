//! A complete scene ready to render: spacetime, camera, world and settings.

use crate::camera::Camera;
use crate::geometry::Vec3;
use crate::settings::RenderSettings;
use crate::world::World;
use spacetime::Spacetime;

#[derive(Clone, Debug)]
pub struct Scene {
    pub spacetime: Spacetime,
    /// The spacetime's symmetry axis in world coordinates: a Kerr hole spins about it.
    pub axis: Vec3,
    pub camera: Camera,
    pub world: World,
    pub settings: RenderSettings,
}

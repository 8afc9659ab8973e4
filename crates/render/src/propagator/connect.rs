//! The spacetime's own light connector (`docs/physics.md`, "Connecting two points"): the light
//! rays between two world points, found by the spacetime itself where it can (Schwarzschild with
//! mass). Light aimed by Newton's method, where it cannot, is [`super::aim`].

use super::Propagator;
use crate::geometry::Vec3;
use spacetime::geodesic::plane::Way;
use spacetime::metric::schwarzschild::connect::{Connection, Waypoints};

impl Propagator {
    /// Whether [`Propagator::connect`] can join points by geodesics here: where the spacetime
    /// has a light connector (Schwarzschild with mass), and rays are traced by the chord method
    /// (the poster's intersection test would not find the same rays).
    pub fn connects(&self) -> bool {
        self.connector.is_some()
    }

    /// The light ray from world point `from` to world point `to` that goes `way` round the hole,
    /// with its bundle density; `None` where [`Propagator::connects`] is false or there is no
    /// such ray, or, given the world normal `facing` of a one-sided surface at `to`, where the
    /// ray reaches it from behind. `waypoints` receives points along the ray.
    pub fn connect(
        &self,
        from: Vec3,
        to: Vec3,
        way: Way,
        facing: Option<Vec3>,
        waypoints: &mut Waypoints,
    ) -> Option<Connection> {
        let connector = self.connector.as_ref()?;
        connector.connect_along(from.to_array(), to.to_array(), way, facing.map(|n| n.to_array()), waypoints)
    }
}

//! Starting a ray: the state in the spacetime's chart of a ray leaving a world point along a
//! direction its local observer measures (`docs/physics.md`, "Local frames and the time
//! orientation of backward rays"), and the frame worked out once for the point a pinhole
//! camera's rays all leave.

use super::{Propagator, RayEnd};
use crate::geometry::Vec3;
use spacetime::geodesic::State;
use spacetime::metric::Metric;
use spacetime::tensor::{Matrix4, Vector4};
use spacetime::{Region, Tetrad};

/// A point rays leave from, in the chart, with its local observer's frame and the metric there:
/// what [`Propagator::start`] works out for each ray (the frame by an eigen-decomposition of the
/// spatial metric), kept for the one point all of a pinhole camera's rays leave.
#[derive(Clone, Copy, Debug)]
pub(super) struct OriginFrame {
    pub(super) region: Region,
    pub(super) origin: Vec3,
    pub(super) x: Vector4,
    pub(super) frame: Tetrad,
    pub(super) metric: Matrix4,
}

/// How a ray that cannot start ends ([`RayEnd::Failed`] or [`RayEnd::Captured`]), boxed: a
/// hit's arrival, which it never is, makes `RayEnd` large.
pub(super) struct NoStart(pub(super) Box<RayEnd>);

impl Propagator {
    /// The ray leaving world point `origin` of `region` along the local-frame unit direction
    /// `direction` as a state of `metric`'s chart (world vectors rotated in with `to_chart`), or
    /// how it ends at once: failed off the chart, captured where no local observer exists.
    pub(super) fn start<M: Metric>(
        &self,
        metric: &M,
        region: Region,
        origin: Vec3,
        direction: Vec3,
    ) -> Result<State, NoStart> {
        if let Some(c) = self.camera.filter(|c| c.region == region && c.origin == origin) {
            let p = c.frame.backward_momentum(&c.metric, self.to_chart(direction).to_array(), 1.0);
            return Ok(State { x: c.x, p });
        }
        let Some(x) = metric.world_to_chart(region, self.to_chart(origin).to_array(), 0.0) else {
            return Err(NoStart(Box::new(RayEnd::Failed)));
        };
        let Ok(frame) = Tetrad::local_observer(metric, &x) else { return Err(NoStart(Box::new(RayEnd::Captured))) };
        let p = frame.backward_momentum(&metric.metric(&x), self.to_chart(direction).to_array(), 1.0);
        Ok(State { x, p })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::settings::Intersection;
    use spacetime::Spacetime;

    /// Rays from the camera's point start as they would without its frame worked out once, in a
    /// spin's turned chart too.
    #[test]
    fn rays_from_the_camera_start_as_without_it() {
        let hole = Spacetime::Kerr(spacetime::Kerr::new(1.0, 0.9));
        let origin = Vec3::new(30.0, 2.0, 8.0);
        let axis = Vec3::new(0.0, 1.0, 0.2);
        let plain = Propagator::new(hole.clone(), 40.0, 1e-7, Intersection::Chord).with_axis(axis);
        let camera = plain.clone().with_camera(Region::Upper, origin);
        // Turned after the camera's frame was worked out: worked out again.
        let turned =
            Propagator::new(hole, 40.0, 1e-7, Intersection::Chord).with_camera(Region::Upper, origin).with_axis(axis);
        assert!(camera.camera.is_some());
        let Spacetime::Kerr(metric) = &camera.spacetime else { unreachable!() };
        for direction in [Vec3::X, Vec3::new(-1.0, 0.3, -0.2).normalize()] {
            let start = |p: &Propagator| p.start(metric, Region::Upper, origin, direction).ok().map(|s| (s.x, s.p));
            assert!(start(&plain).is_some());
            assert_eq!(start(&camera), start(&plain));
            assert_eq!(start(&turned), start(&plain));
        }
    }
}

//! Light followed forwards in time, from its sources (photon mapping), however the spacetime
//! lets it be traced ([`Capabilities::forwards`]).
//!
//! Static spacetimes are time-symmetric: the ray forwards from a point along `n` is the ray
//! backwards from there along `n`. About a spinning hole it is not — frame dragging turns light
//! one way — and the outgoing chart the hole is traced in is singular on the future horizon that
//! forward light falls through. Such light is the backward light of the hole's spin-reversed
//! twin in the time-reversed ingoing chart ([`SpinTwin`]): it is traced there with the twin's own
//! backward stepper, and its points and momenta are mapped back to the hole's chart to meet the scene and
//! be measured by the hole's local observers.

use super::four_d::{OwnChart, TracedChart};
use super::{Propagator, RayEnd};
use crate::geometry::Vec3;
use crate::world::World;
use spacetime::geodesic::State;
use spacetime::metric::{Forwards, Metric, OwnStepper, SpinTwin};
use spacetime::tensor::Vector4;
use spacetime::{Region, Tetrad};

impl Propagator {
    /// Traces the light that leaves world point `origin` of `region` forwards in time along the
    /// local-frame unit direction `direction`. Its arrival's direction is the light's direction
    /// of travel there, and its energy the local observer's over the energy measured at the
    /// start. A spacetime whose light cannot be followed forwards
    /// ([`Forwards::Unsupported`]; renderers that need it refuse such spacetimes when they are
    /// set up) fails every ray.
    pub fn trace_forward(&self, world: &World, region: Region, origin: Vec3, direction: Vec3) -> RayEnd {
        match self.spacetime.capabilities().forwards() {
            Forwards::Reversed => self.trace(world, region, origin, direction),
            Forwards::SpinTwin(twin) => self.through_twin(&twin, world, region, origin, direction),
            Forwards::Unsupported => RayEnd::Failed,
        }
    }

    /// The forward ray about a spinning hole, traced backwards in its `twin`'s chart.
    fn through_twin(&self, twin: &SpinTwin, world: &World, region: Region, origin: Vec3, direction: Vec3) -> RayEnd {
        let hole = self.spacetime.metric();
        let Some(x) = hole.world_to_chart(region, self.to_chart(origin).to_array(), 0.0) else {
            return RayEnd::Failed;
        };
        let Ok(frame) = Tetrad::local_observer(hole, &x) else { return RayEnd::Captured };
        // A future-directed momentum of energy 1 travelling along `direction`: the negative of
        // the backward momentum that leaves along `−direction`.
        let back = frame.backward_momentum(&hole.metric(&x), (-self.to_chart(direction)).to_array(), 1.0);
        let (y, q) = twin.to_twin(&x, &back.map(|c| -c));
        if !y.iter().chain(q.iter()).all(|c| c.is_finite()) {
            return RayEnd::Failed;
        }
        let start = State { x: y, p: q };
        self.follow(twin.twin().ray_tracer(start, self.trace), &start, &TwinChart { hole, twin }, world, region)
    }
}

/// The twin's chart, mapped to the spinning hole's.
struct TwinChart<'a> {
    hole: &'a dyn Metric,
    twin: &'a SpinTwin,
}

impl TracedChart for TwinChart<'_> {
    /// Points inside the horizon, where the charts do not meet, are NaN: the chord test finds
    /// nothing on a chord that ends there.
    fn point(&self, x: &Vector4) -> [f64; 3] {
        self.twin.point_from_twin(x)
    }

    /// The hole's local observer sees the future-directed momentum: what it measures of the
    /// backward one is travel along the opposite direction, at the opposite energy.
    fn measure(&self, state: &State) -> Option<([f64; 3], f64)> {
        let (x, p) = self.twin.from_twin(&state.x, &state.p);
        let (n, energy) = OwnChart(self.hole).measure(&State { x, p })?;
        Some((n.map(|c| -c), -energy))
    }
}

//! The 4-D tracers: Hamilton's equations for the null geodesic in any metric's chart, or the
//! metric's own stepper (`docs/physics.md`, "Hamiltonian form of null geodesics"). Steps are
//! tested against the scene by their chords ([`super::chords`]); a chart other than the
//! spacetime's own (the spinning hole's twin, [`super::forwards`]) is seen through
//! [`TracedChart`].

use super::chords::{from_chord_side, ChordHit, CurvedStep, Knot};
use super::start::NoStart;
use super::{Arrival, Propagator, RayEnd};
use crate::geometry::Vec3;
use crate::world::World;
use spacetime::geodesic::{HamiltonianTracer, RayStep, RayTracer, State};
use spacetime::metric::{Metric, OwnStepper};
use spacetime::tensor::Vector4;
use spacetime::{Fate, Region, Tetrad, Visit};

impl Propagator {
    /// The 4-D tracer, in the chart's axes: world vectors are rotated in with `to_chart` and
    /// chord points rotated back out.
    pub(super) fn hamiltonian<M: Metric>(
        &self,
        metric: &M,
        world: &World,
        region: Region,
        origin: Vec3,
        direction: Vec3,
    ) -> RayEnd {
        let tracer = |start| HamiltonianTracer::new(metric, start, self.trace);
        self.four_d_ray(metric, tracer, world, region, origin, direction)
    }

    /// The metric's own 4-D stepper, as [`Propagator::hamiltonian`] uses the generic one.
    pub(super) fn own_stepper<M: OwnStepper>(
        &self,
        metric: &M,
        world: &World,
        region: Region,
        origin: Vec3,
        direction: Vec3,
    ) -> RayEnd {
        let tracer = |start| metric.ray_tracer(start, self.trace);
        self.four_d_ray(metric, tracer, world, region, origin, direction)
    }

    /// The ray leaving `origin` along `direction`, followed by the 4-D tracer `tracer` makes
    /// of its start in `metric`'s own chart.
    fn four_d_ray<M: Metric, T: RayTracer>(
        &self,
        metric: &M,
        tracer: impl FnOnce(State) -> T,
        world: &World,
        region: Region,
        origin: Vec3,
        direction: Vec3,
    ) -> RayEnd {
        match self.start(metric, region, origin, direction) {
            Ok(start) => self.follow(tracer(start), &start, &OwnChart(metric), world, region),
            Err(NoStart(end)) => *end,
        }
    }

    /// Follows the ray that `tracer` traces from `start`, in a chart that `chart` relates to the
    /// spacetime's own, to its end. The escaped ray's energy at infinity, over its energy at the
    /// start, is the conserved `p_t` of `start`: its local observer measures energy 1.
    pub(super) fn follow<T: RayTracer, C: TracedChart>(
        &self,
        tracer: T,
        start: &State,
        chart: &C,
        world: &World,
        region: Region,
    ) -> RayEnd {
        let mut arrival: Option<(ChordHit, State)> = None;
        let place = |x: &Vector4, theta: f64| Knot {
            theta,
            at: self.to_world(Vec3::from_array(chart.point(x))),
            tangent: None,
        };
        // The step's ends are its start and end states themselves; a step starts where the
        // previous one ended, so its first knot is that one's last.
        let mut last = place(&start.x, 0.0);
        let trace = tracer.run(|step: &T::Step| {
            let knot = |theta: f64| place(&step.position_at(theta), theta);
            let curved = CurvedStep { knot: &knot, motion: None, axis: None, leaves_origin: false };
            let (from, to) = (Knot { theta: 0.0, ..last }, place(&step.end_position(), 1.0));
            last = to;
            match self.curved(world, region, &curved, from, to) {
                Some(found) => {
                    arrival = Some((found, step.at(found.theta)));
                    Visit::Stop
                }
                None => Visit::Continue,
            }
        });
        match trace.fate {
            Fate::Stopped => {
                let Some((found, state)) = arrival else { return RayEnd::Failed };
                let Some((n, energy)) = chart.measure(&state) else { return RayEnd::Captured };
                let hit = world.surface(region, found.object, &found.chord, found.t);
                let ng_local = self.local_normal(region, hit.p, hit.ng);
                let direction = from_chord_side(&hit, ng_local, found.chord.dir, self.to_world(Vec3::from_array(n)));
                let (object, distance) = (found.object, found.t);
                RayEnd::Hit(Arrival { region, object, hit, ng_local, direction, distance, energy, swept: None })
            }
            // A static observer at infinity measures the conserved `p_t`.
            Fate::Escaped { direction } | Fate::Traversed { direction } => {
                let end = self.to_world(Vec3::from_array(chart.point(&trace.end.x)));
                self.beyond(world, region, end, self.to_world(Vec3::from_array(direction)), false, start.p[0])
            }
            Fate::Captured => RayEnd::Captured,
            Fate::Failed(_) => RayEnd::Failed,
        }
    }
}

/// The chart a 4-D ray is traced in, as the scene sees it: the spacetime's own chart (whose
/// spatial points, rotated by `to_chart`, are world points) or one mapped to it.
pub(super) trait TracedChart {
    /// The spatial point of the spacetime's own chart at traced point `x`.
    fn point(&self, x: &Vector4) -> [f64; 3];
    /// The unit direction of travel and the energy (relative to the start's) that the local
    /// observer at `state` measures; `None` where there is no local observer.
    fn measure(&self, state: &State) -> Option<([f64; 3], f64)>;
}

/// A ray traced backwards in the spacetime's own chart.
pub(super) struct OwnChart<'m>(pub(super) &'m dyn Metric);

impl TracedChart for OwnChart<'_> {
    fn point(&self, x: &Vector4) -> [f64; 3] {
        [x[1], x[2], x[3]]
    }

    fn measure(&self, state: &State) -> Option<([f64; 3], f64)> {
        let local = Tetrad::local_observer(self.0, &state.x).ok()?;
        Some(local.backward_direction(&state.p))
    }
}

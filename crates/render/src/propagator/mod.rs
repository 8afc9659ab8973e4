//! Light through the scene's spacetime: a ray leaves a point along a direction measured in the
//! local frame of the static observer there, follows the null geodesic step by step, and every
//! step's chord is tested against the scene (`docs/physics.md`, "Rays meeting objects (chords and
//! sagitta)").
//!
//! In flat space the geodesic is a single straight step of infinite length, so the flat case
//! costs one BVH query. Spherically symmetric spacetimes use the exact in-plane tracer; others
//! (Kerr) the 4-D Hamiltonian tracer. Curved steps are split where their chord strays more than
//! `epsilon` from the curve, so the chords follow the ray within `epsilon` and a hit on a chord
//! is a hit on the ray to that tolerance. A piece of a step that nothing comes near is not
//! split: in Schwarzschild spacetime, where every ray bends towards the hole, a piece lies in the
//! triangle of its chord and end tangents, and one triangle test clears it; elsewhere a box
//! about the chord, widened by twice the sagitta, does. Pieces inside the ball about the centre
//! that no object reaches into, or whose triangles lie inside such a box (a room's inside), are
//! cleared without asking the scene. Where only flat objects come near such a
//! triangle, the piece is not split either: its crossings of their planes are solved on the curve
//! itself ([`crate::crossing`]), to a hundredth of `epsilon`.
//!
//! Local frames have their axes aligned with the world's: directions handed in and out are in
//! the static observer's orthonormal frame (the normal observer's inside a Kerr ergosphere),
//! which in curved space differs from the world coordinate directions by the metric.
//!
//! This module holds the propagator, its construction, and the choice of tracer for each ray;
//! its parts, one each:
//!
//! - `start`: a ray's starting state in the chart, and the frame worked out once for a camera;
//! - `in_plane`: the in-plane tracer of static, spherically symmetric spacetimes;
//! - `four_d`: the 4-D tracers (Hamilton's equations, or the metric's own stepper);
//! - `chords`: a curved step's chords, split by their sagitta, cleared by tangent triangles;
//! - `empty`: the ball and box about the centre that no object reaches into;
//! - `crossings`: crossings of flat objects' planes, solved on the curve;
//! - `poster`: the poster's sign-change test ([`Intersection::Poster`]);
//! - `leaving`: rays past the escape radius, and straight rays;
//! - `observers`: what the local observer at a point measures (lapse, normals, velocities, areas);
//! - `connect`: the spacetime's own light connector; `aim`: light aimed between points;
//! - `forwards`: light followed forwards in time.

mod aim;
mod chords;
mod connect;
mod crossings;
mod empty;
mod forwards;
mod four_d;
mod in_plane;
mod leaving;
mod observers;
mod poster;
mod start;

pub use aim::Aimed;

use crate::geometry::Vec3;
use crate::settings::Intersection;
use crate::shape::SurfaceHit;
use crate::world::World;
use leaving::straight;
use spacetime::geodesic::plane::PlaneMetric;
use spacetime::geodesic::{Stepping, TraceSettings};
use spacetime::metric::schwarzschild::connect::Connector;
use spacetime::metric::{Metric, OwnStepper, Tracers};
use spacetime::{Region, Spacetime, Tetrad};
use start::OriginFrame;

/// Where a traced ray ended.
#[derive(Clone, Copy, Debug)]
pub enum RayEnd {
    /// It reached a surface.
    Hit(Arrival),
    /// It escaped to infinity in `region` (the other one than it started in if `traversed`).
    Escaped { region: Region, direction: Vec3, traversed: bool, energy: f64 },
    /// It crossed an event horizon.
    Captured,
    /// It failed numerically (counted, never shaded).
    Failed,
}

/// A ray arriving at a surface.
#[derive(Clone, Copy, Debug)]
pub struct Arrival {
    pub region: Region,
    pub object: usize,
    pub hit: SurfaceHit,
    /// The surface's geometric normal as a unit covector in the local frame at the hit.
    pub ng_local: Vec3,
    /// Direction of travel at the hit in the local frame.
    pub direction: Vec3,
    /// Straight-line distance of the last chord segment from its start to the hit.
    pub distance: f64,
    /// Photon energy measured by the local observer at the hit, relative to the energy measured
    /// at the ray's start (1 in flat space).
    pub energy: f64,
    /// Azimuth swept about the centre from the ray's start to the hit, where the in-plane tracer
    /// follows the ray in its plane (`None` for straight and 4-D traced rays).
    pub swept: Option<f64>,
}

/// How rays are propagated; built once per render. Everything it knows of the spacetime it
/// asks the spacetime ([`Capabilities`]); the answers asked along every step are kept here.
#[derive(Clone, Debug)]
pub struct Propagator {
    spacetime: Spacetime,
    /// Whether light goes straight ([`Capabilities::is_flat`]).
    flat: bool,
    /// [`Capabilities::no_turning_beyond`], asked of pieces of every curved step.
    no_turning_beyond: Option<f64>,
    /// The spacetime's light connector, where it has one and rays are traced by chords.
    connector: Option<Connector>,
    /// Whether light is aimed in the ray's plane where the spacetime is static and spherically
    /// symmetric ([`spacetime::geodesic::plane::plane_aim`]), rather than in 4-D.
    aims_in_plane: bool,
    /// The 4-D tracer's settings; its steps move at most half the distance to the centre.
    trace: TraceSettings,
    /// The in-plane tracer's: its steps sweep at most a radian of azimuth (the Taylor series'
    /// own longest step; a piece of ray sweeping up to π still lies in its tangent triangle).
    plane_trace: TraceSettings,
    /// Largest allowed distance between a chord and the curved step it stands for.
    epsilon: f64,
    intersection: Intersection,
    /// Whether curved steps of rays that bend one way are tested by their tangent triangles
    /// (always, except in tests that compare with the tube test alone).
    bound_arcs: bool,
    /// Rotation from world axes to the chart's, for metrics with an axis (Kerr spins about the
    /// chart's z; a scene may point the spin anywhere); `None` for spherically symmetric ones,
    /// whose world points are the chart's as they are.
    to_chart: Option<glam::DQuat>,
    /// The start of every ray from one point (a pinhole camera's), worked out once.
    camera: Option<OriginFrame>,
}

/// The rotation from world axes to the chart's for a spacetime whose symmetry axis points along
/// the world vector `axis`: the chart's z is that axis.
pub fn chart_rotation(axis: Vec3) -> glam::DQuat {
    glam::DQuat::from_rotation_arc(axis.normalize(), Vec3::Z)
}

impl Propagator {
    /// A propagator for `spacetime`; `scene_radius` bounds every object's distance from the
    /// origin (rays beyond it and moving away have escaped).
    pub fn new(spacetime: Spacetime, scene_radius: f64, rtol: f64, intersection: Intersection) -> Self {
        let scale = spacetime.length_scale();
        let escape_radius = (2.0 * scene_radius).max(100.0 * scale);
        let trace = match intersection {
            Intersection::Chord => TraceSettings {
                stepping: Stepping::Adaptive { rtol },
                escape_radius,
                max_step_fraction: 0.5,
                max_steps: 1_000_000,
                check_every_step: false,
            },
            Intersection::Poster { step, max_iterations } => TraceSettings {
                stepping: Stepping::Rk4 { step },
                escape_radius,
                max_step_fraction: f64::INFINITY,
                max_steps: max_iterations,
                check_every_step: false,
            },
        };
        let plane_trace = TraceSettings { max_step_fraction: trace.max_step_fraction.max(1.0), ..trace };
        let epsilon = 1e-4 * scene_radius.max(scale);
        let answers = spacetime.capabilities();
        let connector = answers.light_connector().filter(|_| matches!(intersection, Intersection::Chord));
        let (flat, no_turning_beyond) = (answers.is_flat(), answers.no_turning_beyond());
        let to_chart = (!answers.is_spherically_symmetric()).then_some(glam::DQuat::IDENTITY);
        Self {
            spacetime,
            flat,
            no_turning_beyond,
            connector,
            aims_in_plane: true,
            trace,
            plane_trace,
            epsilon,
            intersection,
            bound_arcs: true,
            to_chart,
            camera: None,
        }
    }

    /// Works out once the start of the rays that leave world point `origin` of `region` (a
    /// pinhole camera's position), which [`Propagator::start`] would for each; nothing where
    /// rays do not start there in a 4-D chart or no local observer exists. The frame is the
    /// spacetime's own metric's, the one every tracer it chooses is handed.
    pub fn with_camera(mut self, region: Region, origin: Vec3) -> Self {
        let metric = self.spacetime.metric();
        self.camera = metric.world_to_chart(region, self.to_chart(origin).to_array(), 0.0).and_then(|x| {
            let frame = Tetrad::local_observer(metric, &x).ok()?;
            Some(OriginFrame { region, origin, x, frame, metric: metric.metric(&x) })
        });
        self
    }

    /// Points the spacetime's symmetry axis (a Kerr hole's spin) along the world vector `axis`
    /// (nothing to point in a spherically symmetric spacetime).
    pub fn with_axis(mut self, axis: Vec3) -> Self {
        if self.to_chart.is_some() {
            self.to_chart = Some(chart_rotation(axis));
        }
        match self.camera {
            Some(c) => self.with_camera(c.region, c.origin),
            None => self,
        }
    }

    /// Sets the chord tolerance ε to 10⁻⁴ of `radius` (the objects' extent) rather than of the
    /// scene radius [`Propagator::new`] was given, which also encloses the camera.
    pub fn with_chord_scale(mut self, radius: f64) -> Self {
        self.epsilon = 1e-4 * radius.max(self.spacetime.length_scale());
        self
    }

    /// World vector `v` in the chart's axes.
    fn to_chart(&self, v: Vec3) -> Vec3 {
        self.rotation().map_or(v, |q| q * v)
    }

    /// Chart vector `v` in the world's axes.
    fn to_world(&self, v: Vec3) -> Vec3 {
        self.rotation().map_or(v, |q| q.inverse() * v)
    }

    /// The rotation between world and chart axes where it turns anything: a spin along the
    /// world's z (the chart's own axis, [`chart_rotation`] exactly the identity) leaves the
    /// points of every step as they are, without a rotation on each one's chain.
    #[inline]
    fn rotation(&self) -> Option<glam::DQuat> {
        self.to_chart.filter(|&q| q != glam::DQuat::IDENTITY)
    }

    /// Chord tolerance ε, in scene units: 10⁻⁴ of the scene's radius.
    pub fn epsilon(&self) -> f64 {
        self.epsilon
    }

    /// Beyond this distance from the origin spacetime counts as flat: rays moving away have escaped.
    pub fn escape_radius(&self) -> f64 {
        self.trace.escape_radius
    }

    pub fn is_flat(&self) -> bool {
        self.flat
    }

    /// The largest impact parameter of a ray from infinity that comes within world radius `radius`
    /// of the centre ([`Capabilities::impact_bound`]); `None` where the spacetime has none.
    pub fn impact_bound(&self, radius: f64) -> Option<f64> {
        self.spacetime.capabilities().impact_bound(radius)
    }

    /// Traces the ray that leaves world point `origin` of `region` along the local-frame unit
    /// direction `direction`, to its end, with the tracer the spacetime chooses.
    pub fn trace(&self, world: &World, region: Region, origin: Vec3, direction: Vec3) -> RayEnd {
        self.spacetime.choose_tracer(Ray4 { propagator: self, world, region, origin, direction })
    }
}

/// A ray to trace, handed to the tracer the spacetime chooses ([`Spacetime::choose_tracer`]).
struct Ray4<'a> {
    propagator: &'a Propagator,
    world: &'a World,
    region: Region,
    origin: Vec3,
    direction: Vec3,
}

impl Tracers for Ray4<'_> {
    type Output = RayEnd;

    fn straight(self) -> RayEnd {
        straight(self.world, self.region, self.origin, self.direction)
    }

    /// The poster integrated Hamilton's equations with RK4 in an affine parameter; a wormhole,
    /// whose rays change region, keeps the in-plane tracer (with RK4 steps in azimuth).
    fn in_plane<M: PlaneMetric>(self, metric: &M) -> RayEnd {
        let Ray4 { propagator, world, region, origin, direction } = self;
        if matches!(propagator.intersection, Intersection::Poster { .. }) && metric.throat_u().is_none() {
            return propagator.hamiltonian(metric, world, region, origin, direction);
        }
        propagator.in_plane(metric, world, region, origin, direction)
    }

    fn four_d<M: Metric>(self, metric: &M) -> RayEnd {
        let Ray4 { propagator, world, region, origin, direction } = self;
        propagator.hamiltonian(metric, world, region, origin, direction)
    }

    /// The poster's RK4 steps are affine, so it keeps the 4-D tracer.
    fn own_stepper<M: OwnStepper>(self, metric: &M) -> RayEnd {
        let Ray4 { propagator, world, region, origin, direction } = self;
        if matches!(propagator.intersection, Intersection::Poster { .. }) {
            return propagator.hamiltonian(metric, world, region, origin, direction);
        }
        propagator.own_stepper(metric, world, region, origin, direction)
    }
}

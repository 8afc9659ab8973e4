//! Null geodesics: the generic machinery of every tracer. Integrators (RK4, Dormand–Prince 5(4)
//! with its dense output, Taylor-series helpers), the step-by-step tracer and the fate of a ray,
//! ray bundles, and aiming a ray at a point.
//!
//! [`HamiltonianTracer`] integrates Hamilton's equations in 4-D for any [`Metric`];
//! [`plane`] integrates static, spherically symmetric spacetimes in the ray's own plane (exactly,
//! cheaper, with no poles) and aims rays there ([`plane::plane_aim`]). Both hand every accepted
//! step to the caller, who tests its chord against a scene and may stop the ray. [`aim`] finds
//! the ray between two given points for any metric, with the ray [`bundle`].
//!
//! Tracers and solvers that serve one metric live beside it: Kerr–Newman's Mino-time stepper in
//! [`crate::metric::kerr_newman::mino`], Schwarzschild's light connector in
//! [`crate::metric::schwarzschild::connect`].
//!
//! [`Metric`]: crate::metric::Metric

pub mod aim;
pub mod bundle;
pub mod dopri5;
pub mod from_observer;
mod hamiltonian;
mod interpolant;
pub mod plane;
pub(crate) mod quadrature;
pub mod rk4;
pub mod tangent_triangle;
pub(crate) mod taylor;

pub use hamiltonian::{angular_momentum_z, energy, trace, Flow, HamiltonianStep, HamiltonianTracer, Ray};
pub use interpolant::Interpolant;

use crate::tensor::{Covector4, Vector4};

/// One accepted step of a 4-D tracer, with the ray anywhere inside it: what a caller testing
/// the ray against a scene needs, whichever stepper took it.
pub trait RayStep {
    /// Chart position `x^μ` at fraction `θ ∈ [0, 1]` of the step. Its time `x⁰` is exact where
    /// the tracer integrates time as part of the ray (the 4-D tracer); a stepper that computes it
    /// only on request (Kerr's Mino stepper) gives the time at the step's start, and
    /// [`RayStep::time_at`] gives it inside.
    fn position_at(&self, theta: f64) -> Vector4;
    /// Chart position at the step's end (`position_at(1)`, without interpolating).
    fn end_position(&self) -> Vector4;
    /// The ray's state (chart position and covariant momentum) at fraction `θ` of the step, its
    /// time as [`RayStep::position_at`]'s.
    fn at(&self, theta: f64) -> State;
    /// The chart's coordinate time at fraction `θ` of the step, where the tracer carries it
    /// ([`RayTracer::carrying_time`]); `None` where it does not. Rays are traced backwards
    /// (past-directed momentum), so it falls along the ray from the start's: the light reaching
    /// the start at `t₀` passed each point at the earlier time given there.
    fn time_at(&self, theta: f64) -> Option<f64>;
}

/// A tracer of one ray in a 4-D chart: the generic [`HamiltonianTracer`], or a stepper a metric
/// provides for itself ([`crate::metric::OwnStepper`]). Both decide the fate by the settings'
/// escape radius and the metric's horizon.
pub trait RayTracer {
    type Step: RayStep;
    /// Traces the ray to its end, showing every accepted step to `visit`.
    fn run(self, visit: impl FnMut(&Self::Step) -> Visit) -> Trace;
    /// The tracer with the chart's coordinate time carried along the ray, for every step's
    /// [`RayStep::time_at`] and the trace's end (`end.x[0]`). A tracer whose ray includes the
    /// time (the 4-D tracer) carries it anyway; one that computes it separately (Kerr's Mino
    /// stepper) spends nothing on it unless asked, and takes the same steps either way.
    fn carrying_time(self) -> Self
    where
        Self: Sized;
}

/// A point on a ray: position `x^μ` and covariant momentum `p_μ`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct State {
    pub x: Vector4,
    pub p: Covector4,
}

/// How rays are integrated.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Stepping {
    /// Classical RK4 with a fixed affine step `step` (further limited by the step cap).
    Rk4 { step: f64 },
    /// Adaptive steps at relative tolerance `rtol`: Dormand–Prince 5(4) with error control, or
    /// Taylor series whose truncation is held to it where a stepper takes them (the in-plane
    /// orbit, [`plane`]; Kerr's family in Mino time, [`mino`](crate::metric::kerr_newman::mino)).
    Adaptive { rtol: f64 },
}

/// Settings shared by every tracer.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TraceSettings {
    pub stepping: Stepping,
    /// A ray further than this from the centre (areal radius) and moving away has escaped.
    pub escape_radius: f64,
    /// Largest coordinate displacement of one step as a fraction of the distance to the centre.
    pub max_step_fraction: f64,
    /// A ray that has not ended after this many accepted steps has failed.
    pub max_steps: u32,
    /// Whether [`Trace::max_abs_hamiltonian`] is the largest `|H|` over every accepted step's
    /// end (a check of the integration, for people and tests) or over the ray's start and end
    /// alone: a renderer reads no such check and need not evaluate `H` at every step.
    pub check_every_step: bool,
}

impl Default for TraceSettings {
    fn default() -> Self {
        Self {
            stepping: Stepping::Adaptive { rtol: 1e-8 },
            escape_radius: 1e3,
            max_step_fraction: 0.5,
            max_steps: 100_000,
            check_every_step: true,
        }
    }
}

/// Why a ray failed numerically.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Failure {
    /// It used up `max_steps`.
    OutOfSteps,
    /// Error control asked for a step too small to make progress.
    StepUnderflow,
    /// The state stopped being finite.
    NonFinite,
}

/// How a ray ended.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Fate {
    /// Reached the escape radius moving outward, in the region it started in; `direction` is its
    /// world direction there (the sky direction).
    Escaped { direction: [f64; 3] },
    /// Escaped into the other region of a wormhole.
    Traversed { direction: [f64; 3] },
    /// Crossed an event horizon.
    Captured,
    /// The caller stopped it (it hit something).
    Stopped,
    /// A numerical failure, counted and reported, never turned into a pixel value.
    Failed(Failure),
}

impl Fate {
    /// Stable lower-case name, as used in statistics and JSON.
    pub fn name(&self) -> &'static str {
        match self {
            Fate::Escaped { .. } => "escaped",
            Fate::Traversed { .. } => "traversed",
            Fate::Captured => "captured",
            Fate::Stopped => "stopped",
            Fate::Failed(_) => "failed",
        }
    }
}

/// What the caller wants after seeing a step.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Visit {
    Continue,
    Stop,
}

/// The outcome of tracing one ray.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Trace {
    pub fate: Fate,
    /// Accepted steps.
    pub steps: u32,
    /// Largest `|H|` at the accepted step ends, or at the start and the end where the settings
    /// do not [`TraceSettings::check_every_step`].
    pub max_abs_hamiltonian: f64,
    pub end: State,
}

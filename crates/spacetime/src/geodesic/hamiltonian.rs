//! The 4-D tracer: Hamilton's equations `dx^μ/dλ = ∂H/∂p_μ`, `dp_μ/dλ = −∂H/∂x^μ` for any metric,
//! with RK4 or Dormand–Prince 5(4), a step cap proportional to the distance from the centre, and
//! the ray's fate decided from the metric's horizon, regions and escape radius (and, for metrics
//! that say so, from a collapsing step: [`Metric::collapse_captures`]).
//!
//! The tracer integrates a [`Flow`]: the ray alone ([`Ray`], the state `(x, p)`), or the ray with
//! fields riding along it ([`super::bundle::Bundle`]), whose first eight components are the ray.
//! Steps are controlled, capped and ended by the ray alone, so a ray traced with its bundle takes
//! the steps it takes without.

use super::{dopri5, Failure, Fate, Interpolant, RayStep, RayTracer, State, Stepping, Trace, TraceSettings, Visit};
use crate::metric::{Metric, Region};
use crate::tensor::{Covector4, Vector4};

/// A system of `N` first-order equations whose first eight components are a ray `(x^μ, p_μ)`
/// obeying Hamilton's equations.
pub trait Flow<const N: usize> {
    /// `dy/dλ` at `y`.
    fn rhs<M: Metric + ?Sized>(metric: &M, y: &[f64; N]) -> [f64; N];
}

/// The ray alone.
#[derive(Clone, Copy, Debug)]
pub struct Ray;

impl Flow<8> for Ray {
    #[inline]
    fn rhs<M: Metric + ?Sized>(metric: &M, y: &[f64; 8]) -> [f64; 8] {
        let (dx, dp) = metric.geodesic_rhs(&[y[0], y[1], y[2], y[3]], &[y[4], y[5], y[6], y[7]]);
        [dx[0], dx[1], dx[2], dx[3], dp[0], dp[1], dp[2], dp[3]]
    }
}

/// The ray's state packed as a flow's first eight components.
#[inline]
pub(super) fn pack(s: &State) -> [f64; 8] {
    [s.x[0], s.x[1], s.x[2], s.x[3], s.p[0], s.p[1], s.p[2], s.p[3]]
}

/// The ray's state from a flow's first eight components.
#[inline]
pub(super) fn unpack<const N: usize>(y: &[f64; N]) -> State {
    State { x: [y[0], y[1], y[2], y[3]], p: [y[4], y[5], y[6], y[7]] }
}

/// One accepted step, with dense output for the state anywhere inside it.
#[derive(Clone, Copy, Debug)]
pub struct HamiltonianStep<const N: usize = 8> {
    pub start: State,
    pub end: State,
    /// Affine parameter length of the step.
    pub h: f64,
    interpolant: Interpolant<N>,
}

impl<const N: usize> HamiltonianStep<N> {
    /// Ray state at fraction `θ ∈ [0, 1]` of the step.
    pub fn at(&self, theta: f64) -> State {
        unpack(&self.interpolant.dense(theta))
    }

    /// Ray position `x^μ` at fraction `θ ∈ [0, 1]` of the step: the part of
    /// [`HamiltonianStep::at`] that placing a point needs, at half its cost.
    #[inline]
    pub fn position_at(&self, theta: f64) -> Vector4 {
        self.interpolant.dense_head(theta)
    }

    /// The whole flow's state at fraction `θ` of the step.
    pub fn flow_at(&self, theta: f64) -> [f64; N] {
        self.interpolant.dense(theta)
    }
}

impl<const N: usize> RayStep for HamiltonianStep<N> {
    #[inline]
    fn position_at(&self, theta: f64) -> Vector4 {
        HamiltonianStep::position_at(self, theta)
    }

    fn end_position(&self) -> Vector4 {
        self.end.x
    }

    fn at(&self, theta: f64) -> State {
        HamiltonianStep::at(self, theta)
    }

    /// `x⁰` of the dense output: the time is part of the ray.
    fn time_at(&self, theta: f64) -> Option<f64> {
        Some(self.interpolant.dense_head::<1>(theta)[0])
    }
}

/// Integrates one ray (with whatever its flow carries) step by step.
pub struct HamiltonianTracer<'m, M: Metric + ?Sized, const N: usize = 8, F: Flow<N> = Ray> {
    metric: &'m M,
    settings: TraceSettings,
    y: [f64; N],
    dy: [f64; N],
    /// The next step to attempt: RK4's fixed affine step, or the adaptive integrator's proposal
    /// in units of the step scale where the step starts ([`HamiltonianTracer::step_scale`]).
    next: f64,
    lambda: f64,
    steps: u32,
    /// `μ² = −g^{μν} p_μ p_ν`: 0 for light, 1 for a body whose momentum is per unit rest mass
    /// ([`HamiltonianTracer::of_body`]); it floors the speed the step scale divides by.
    rest_mass2: f64,
    flow: std::marker::PhantomData<F>,
}

impl<'m, M: Metric + ?Sized> HamiltonianTracer<'m, M> {
    /// The tracer of the ray from `start`.
    pub fn new(metric: &'m M, start: State, settings: TraceSettings) -> Self {
        Self::of_flow(metric, pack(&start), settings)
    }

    /// The tracer of a body (a timelike geodesic) from `start`: Hamilton's equations are light's,
    /// on the mass shell `H = −½μ²` the start is on, and a body at rest, which has no coordinate
    /// speed, takes steps as light of its energy would (the step scale floors its speed at μ).
    pub fn of_body(metric: &'m M, start: State, settings: TraceSettings) -> Self {
        let rest_mass2 = (-2.0 * metric.hamiltonian(&start.x, &start.p)).max(0.0);
        Self { rest_mass2, ..Self::new(metric, start, settings) }
    }
}

impl<'m, M: Metric + ?Sized, const N: usize, F: Flow<N>> HamiltonianTracer<'m, M, N, F> {
    /// The tracer of flow `F` from `y` (its first eight components the ray's start).
    pub fn of_flow(metric: &'m M, y: [f64; N], settings: TraceSettings) -> Self {
        let dy = Self::rhs(metric, &y);
        let next = match settings.stepping {
            Stepping::Rk4 { step } => step,
            // The first attempt is the longest step allowed (one step scale where nothing caps
            // it): error control shrinks a rejected attempt by its own estimate at once, where
            // growing from a cautious guess took several steps.
            Stepping::Adaptive { .. } => settings.max_step_fraction.min(1.0),
        };
        let flow = std::marker::PhantomData;
        Self { metric, settings, y, dy, next, lambda: 0.0, steps: 0, rest_mass2: 0.0, flow }
    }

    #[inline]
    fn rhs(metric: &M, y: &[f64; N]) -> [f64; N] {
        F::rhs(metric, y)
    }

    pub fn state(&self) -> State {
        unpack(&self.y)
    }

    /// Affine parameter travelled so far.
    pub fn lambda(&self) -> f64 {
        self.lambda
    }

    pub fn steps(&self) -> u32 {
        self.steps
    }

    /// Coordinate velocity `dx^μ/dλ` at the current point.
    pub fn velocity(&self) -> Vector4 {
        [self.dy[0], self.dy[1], self.dy[2], self.dy[3]]
    }

    /// The affine step whose coordinate displacement is the distance from the centre (at least
    /// the metric's length scale): the length over which a ray's path changes, so the steps that
    /// error control allows grow and shrink with it. A body's speed counts as at least its rest
    /// mass (`|v|² + μ²`, the speed of light for momenta per unit mass): at rest it has no
    /// coordinate speed, and its steps would be unbounded and their proposals, kept relative to
    /// the scale, would vanish as it starts to fall. For light `μ² = 0` and nothing changes.
    fn step_scale(&self) -> f64 {
        let r = (self.y[1] * self.y[1] + self.y[2] * self.y[2] + self.y[3] * self.y[3]).sqrt();
        let speed2 = self.dy[1] * self.dy[1] + self.dy[2] * self.dy[2] + self.dy[3] * self.dy[3];
        let v = (speed2 + self.rest_mass2).sqrt();
        r.max(self.metric.length_scale()) / v
    }

    /// Scaled error norm of an attempt: rotation-invariant blocks for position, time and
    /// momentum, each relative to its own size.
    fn error_norm(&self, y0: &[f64; N], y1: &[f64; N], error: &[f64; N], rtol: f64) -> f64 {
        let scale = self.metric.length_scale();
        let n3 = |v: &[f64; N], i: usize| (v[i] * v[i] + v[i + 1] * v[i + 1] + v[i + 2] * v[i + 2]).sqrt();
        let n4 = |v: &[f64; N]| (v[4] * v[4] + v[5] * v[5] + v[6] * v[6] + v[7] * v[7]).sqrt();
        let pos = n3(error, 1) / (rtol * (scale + n3(y0, 1).max(n3(y1, 1))));
        let time = error[0].abs() / (rtol * (scale + y0[0].abs().max(y1[0].abs())));
        let mom = n4(error) / (rtol * n4(y0).max(n4(y1)));
        pos.max(time).max(mom)
    }

    /// Advances by one accepted step, no longer than `h_limit`.
    pub fn step(&mut self, h_limit: f64) -> Result<HamiltonianStep<N>, Failure> {
        if self.steps >= self.settings.max_steps {
            return Err(Failure::OutOfSteps);
        }
        let f = |_t: f64, y: &[f64; N]| Self::rhs(self.metric, y);
        // The largest step moves the ray by `max_step_fraction` of its distance from the centre,
        // so rays stride far from masses and creep near them.
        let scale = self.step_scale();
        let cap = (self.settings.max_step_fraction * scale).min(h_limit);
        let mut h = match self.settings.stepping {
            Stepping::Rk4 { .. } => self.next,
            Stepping::Adaptive { .. } => self.next * scale,
        }
        .min(cap);
        let mut rejected = false;
        let interpolant = loop {
            let (step, error) = Interpolant::step(self.settings.stepping, &f, self.lambda, &self.y, &self.dy, h);
            let (Some(error), Stepping::Adaptive { rtol }) = (error, self.settings.stepping) else {
                break step;
            };
            let err = self.error_norm(&self.y, &step.y1(), &error, rtol);
            if err <= 1.0 {
                // The proposal is kept relative to the step scale: a ray falling towards the
                // centre needs shorter steps at every step, and one climbing out longer ones,
                // which a proposal kept in affine length learns only by rejected attempts (or
                // not at all). Right after a rejection it does not grow (Hairer et al. II.4).
                let factor = dopri5::step_factor(err);
                self.next = h * if rejected { factor.min(1.0) } else { factor } / scale;
                break step;
            }
            rejected = true;
            h *= if err.is_finite() { dopri5::step_factor(err).min(1.0) } else { 0.2 };
            if h <= 1e-14 * cap.min(scale) || !h.is_finite() {
                return Err(Failure::StepUnderflow);
            }
        };
        let (y1, d1) = (interpolant.y1(), interpolant.end_derivative());
        if !y1.iter().chain(d1.iter()).all(|v| v.is_finite()) {
            return Err(Failure::NonFinite);
        }
        let step = HamiltonianStep { start: unpack(&self.y), end: unpack(&y1), h, interpolant };
        self.y = y1;
        self.dy = d1;
        self.lambda += h;
        self.steps += 1;
        Ok(step)
    }

    /// The fate of the ray at its current point, if it has ended.
    fn ended(&self, start_region: Region) -> Option<Fate> {
        let x: Vector4 = [self.y[0], self.y[1], self.y[2], self.y[3]];
        if self.metric.inside_horizon(&x) {
            return Some(Fate::Captured);
        }
        let v = self.velocity();
        if self.metric.radius(&x) > self.settings.escape_radius && self.metric.is_outgoing(&x, &v) {
            let w = self.metric.to_world(&x, &v);
            return Some(if w.region == start_region {
                Fate::Escaped { direction: w.direction }
            } else {
                Fate::Traversed { direction: w.direction }
            });
        }
        None
    }

    /// Traces the ray to its end, showing every accepted step to `visit`.
    pub fn run(mut self, mut visit: impl FnMut(&HamiltonianStep<N>) -> Visit) -> Trace {
        let start = unpack(&self.y);
        let start_region = self.metric.region(&start.x);
        let mut max_h: f64 = self.metric.hamiltonian(&start.x, &start.p).abs();
        let fate = loop {
            if let Some(fate) = self.ended(start_region) {
                break fate;
            }
            match self.step(f64::INFINITY) {
                Ok(step) => {
                    if self.settings.check_every_step {
                        max_h = max_h.max(self.metric.hamiltonian(&step.end.x, &step.end.p).abs());
                    }
                    if visit(&step) == Visit::Stop {
                        break Fate::Stopped;
                    }
                }
                Err(Failure::OutOfSteps) => break Fate::Failed(Failure::OutOfSteps),
                Err(_) if self.metric.collapse_captures() => break Fate::Captured,
                Err(failure) => break Fate::Failed(failure),
            }
        };
        let end = self.state();
        let max_abs_hamiltonian = max_h.max(self.metric.hamiltonian(&end.x, &end.p).abs());
        Trace { fate, steps: self.steps, max_abs_hamiltonian, end }
    }
}

impl<M: Metric + ?Sized, const N: usize, F: Flow<N>> RayTracer for HamiltonianTracer<'_, M, N, F> {
    type Step = HamiltonianStep<N>;

    fn run(self, visit: impl FnMut(&HamiltonianStep<N>) -> Visit) -> Trace {
        HamiltonianTracer::run(self, visit)
    }

    /// The time is `x⁰`, integrated with the ray.
    fn carrying_time(self) -> Self {
        self
    }
}

/// Traces a ray from `start` to its end (see [`HamiltonianTracer::run`]).
pub fn trace<M: Metric + ?Sized>(
    metric: &M,
    start: State,
    settings: &TraceSettings,
    visit: impl FnMut(&HamiltonianStep) -> Visit,
) -> Trace {
    HamiltonianTracer::new(metric, start, *settings).run(visit)
}

/// `p_φ = x p_y − y p_x`, conserved in axisymmetric spacetimes.
pub fn angular_momentum_z(s: &State) -> f64 {
    s.x[1] * s.p[2] - s.x[2] * s.p[1]
}

/// Convenience: `−p_t`, the conserved energy of a stationary spacetime.
pub fn energy(p: &Covector4) -> f64 {
    -p[0]
}

//! The Mino-time tracer: step control (Taylor steps held to the tolerance, or RK4's fixed
//! steps), the step the caller sees, and the ray's fate.

use super::motion::{from_chart, Constants};
use super::series::{column, Dense, ORDER};
use super::time::elapsed;
use crate::geodesic::taylor;
use crate::geodesic::{Failure, Fate, Interpolant, RayStep, RayTracer, State, Stepping, Trace, TraceSettings, Visit};
use crate::metric::{KerrNewman, KerrSchild};
use crate::tensor::Vector4;

/// One accepted Mino step, with dense output for the ray anywhere inside it.
#[derive(Clone, Copy, Debug)]
pub struct MinoStep {
    constants: Constants,
    /// The chart time at the step's start.
    time: f64,
    /// Whether the tracer carries the time ([`MinoTracer::carrying_time`]); if not, `time` is the
    /// ray's start's.
    timed: bool,
    pub(super) dense: Dense,
}

/// Positions and states inside a step have the time at the step's start as `x⁰` (placing points
/// for chord tests needs no time, and the time inside a step costs a quadrature): the time
/// anywhere inside is [`RayStep::time_at`].
impl RayStep for MinoStep {
    #[inline]
    fn position_at(&self, theta: f64) -> Vector4 {
        let (u, n) = self.dense.position(theta);
        let [x, y, z] = self.constants.point(u, n);
        [self.time, x, y, z]
    }

    fn end_position(&self) -> Vector4 {
        let y = self.dense.end();
        let [x, p, z] = self.constants.point(y[0], [y[2], y[3], y[4]]);
        [self.time, x, p, z]
    }

    fn at(&self, theta: f64) -> State {
        let y = self.dense.head::<8>(theta);
        let [x, py, z] = self.constants.point(y[0], [y[2], y[3], y[4]]);
        State { x: [self.time, x, py, z], p: self.constants.momentum(&y).0 }
    }

    fn time_at(&self, theta: f64) -> Option<f64> {
        self.timed.then(|| self.time + elapsed(&self.constants, &self.dense, theta))
    }
}

/// Traces one ray about a hole of Kerr's family in Mino time (see the module documentation),
/// with the 4-D tracer's settings: Taylor steps ([`MinoTracer::taylor_step`]) whose truncation
/// is held to the same relative tolerance on the chart position and velocity as the 4-D
/// tracer's error control, steps at most `max_step_fraction` of the step scale
/// ([`MinoTracer::step_scale`]), the same escape radius (in the spheroidal radius, as the chart's
/// [`crate::metric::Metric::radius`]) and the same horizon. RK4 takes Mino steps of the affine
/// length `step` as it is at the ray's start.
#[derive(Clone, Copy, Debug)]
pub struct MinoTracer {
    constants: Constants,
    settings: TraceSettings,
    /// `1/r₊`: a ray with `u` beyond it is inside the horizon.
    horizon_u: f64,
    /// The chart time at `y`: the start's unless the tracer carries it.
    time: f64,
    /// Whether the time is carried ([`MinoTracer::carrying_time`]).
    timed: bool,
    pub(super) y: [f64; 8],
    /// RK4's `dy/dλ_M` at `y` (its next step's first stage; unused by Taylor steps).
    dy: [f64; 8],
    /// RK4's fixed Mino step.
    next: f64,
    steps: u32,
}

impl MinoTracer {
    /// The tracer of the ray from `start`, a state of `hole`'s chart.
    pub fn new(hole: &KerrNewman, start: State, settings: TraceSettings) -> Self {
        let horizon_u = 1.0 / hole.horizon_radius();
        let (constants, y) = from_chart(hole, &start);
        let dy = constants.rhs(&y);
        let next = match settings.stepping {
            Stepping::Rk4 { step } => {
                let r = 1.0 / y[0];
                step / (r * r + hole.spin * hole.spin * y[4] * y[4])
            }
            Stepping::Adaptive { .. } => 0.0,
        };
        Self { constants, settings, horizon_u, time: start.x[0], timed: false, y, dy, next, steps: 0 }
    }

    /// The ray's state now.
    pub fn state(&self) -> State {
        self.state_and_hamiltonian().0
    }

    /// The ray's state now, and its Hamiltonian (both from its chart momentum).
    fn state_and_hamiltonian(&self) -> (State, f64) {
        let [x, y, z] = self.constants.point(self.y[0], [self.y[2], self.y[3], self.y[4]]);
        let (p, h) = self.constants.momentum(&self.y);
        (State { x: [self.time, x, y, z], p }, h)
    }

    /// The Mino step over which the ray's path changes: the time in which `n` turns a radian,
    /// `u` climbs by `1/M` inwards, or falls to 0 outwards (the pole of `r` at infinity, which no
    /// step may pass).
    fn step_scale(&self) -> f64 {
        let [u, w, _, _, _, v0, v1, v2] = self.y;
        let turn = (v0 * v0 + v1 * v1 + v2 * v2).sqrt();
        let climb = if w < 0.0 { -w / u } else { w * self.constants.mass };
        1.0 / turn.max(climb)
    }

    /// Scaled norm of an error `e` of the state over a step `y0 → y1`: the chart position's
    /// error (radial `δr = δu/u²` and transverse `r |δn|`) relative to the distance from the
    /// centre plus the mass, as the 4-D tracer's, and the chart velocity's (`∝ (u', u v)`)
    /// relative to its size. Linear in `e` (its weights are the states'), so a term `cₖhᵏ` of
    /// the series has the norm `hᵏ` times its coefficients'.
    fn error_norm(&self, y0: &[f64; 8], y1: &[f64; 8], e: &[f64; 8], rtol: f64) -> f64 {
        let u = y1[0];
        let far = 1.0 / y0[0].min(y1[0]);
        let dn2 = e[2] * e[2] + e[3] * e[3] + e[4] * e[4];
        let dr = e[0] / (u * u);
        let pos = (dr * dr + dn2 / (u * u)).sqrt() / (rtol * (self.constants.mass + far));
        let speed2 = |y: &[f64; 8]| y[1] * y[1] + u * u * (y[5] * y[5] + y[6] * y[6] + y[7] * y[7]);
        let dv2 = e[1] * e[1] + u * u * (e[5] * e[5] + e[6] * e[6] + e[7] * e[7]);
        let vel = (dv2 / speed2(y0).max(speed2(y1))).sqrt() / rtol;
        pos.max(vel)
    }

    /// Advances by one accepted step.
    pub(super) fn step(&mut self) -> Result<MinoStep, Failure> {
        if self.steps >= self.settings.max_steps {
            return Err(Failure::OutOfSteps);
        }
        let constants = self.constants;
        let scale = self.step_scale();
        let cap = self.settings.max_step_fraction * scale;
        let dense = match self.settings.stepping {
            Stepping::Rk4 { .. } => {
                let f = |_t: f64, y: &[f64; 8]| constants.rhs(y);
                let (step, _) =
                    Interpolant::step(self.settings.stepping, &f, 0.0, &self.y, &self.dy, self.next.min(cap));
                self.dy = step.end_derivative();
                Dense::Rk4(step)
            }
            Stepping::Adaptive { rtol } => self.taylor_step(self.escape_cap(cap), scale, rtol)?,
        };
        // `dy` is RK4's (Taylor steps leave it as it was at the start).
        let y1 = dense.end();
        if !(y1[0] > 0.0 && y1.iter().chain(self.dy.iter()).all(|v| v.is_finite())) {
            return Err(Failure::NonFinite);
        }
        self.y = y1;
        self.steps += 1;
        let time = self.time;
        if self.timed {
            self.time += elapsed(&constants, &dense, 1.0);
        }
        // Built in place: a step (its series) is too large to move for nothing.
        Ok(MinoStep { constants, time, timed: self.timed, dense })
    }

    /// The cap `cap` of a Taylor step, lengthened for an outgoing ray (`u' < 0`) inside the
    /// escape radius to the Mino time in which `u`, at constant `u'` (as it nearly is far out:
    /// `u'' = U'(u)/2 = O(u)`), would fall to half its value at the escape radius (`r` twice
    /// that radius), within `max_step_fraction` of a turning time `1/|v|`. The step scale's
    /// fall to the pole of `r` (the time `u/|u'|`) would make each step at most double `r` on
    /// the way out, which with a distant escape radius (a camera far away sets it) is most of a
    /// ray's steps; a Taylor step cannot pass the pole either way (it is halved while its end
    /// has `u ≤ 0`), and its error control still bounds it.
    fn escape_cap(&self, cap: f64) -> f64 {
        let [u, w, _, _, _, v0, v1, v2] = self.y;
        let escape_u = 1.0 / self.settings.escape_radius;
        if !(w < 0.0 && u > escape_u) {
            return cap;
        }
        let longest = self.settings.max_step_fraction / (v0 * v0 + v1 * v1 + v2 * v2).sqrt();
        if cap >= longest {
            // The turning time binds already (the cap is the least of it and the pole's time).
            return cap;
        }
        // At constant `u'` the time to the target `u − target` over `−u'`. Far out, though,
        // `u'' = −ω² u + O(u²)` with ω² = Q + L² − a²E² (the radial quartic's linear term): `u`
        // oscillates harmonically (in flat space a straight line is u = cos(bλ)/b) and reaches 0
        // at the phase `atan(ω u/(−u'))`, sooner than the line, whose estimate would end each
        // step past the pole, to be halved (so `r` only doubled a step).
        let linear = (u - 0.5 * escape_u) / -w;
        let omega2 = self.constants.sphere - self.constants.a2e2;
        let to_twice_escape = if omega2 > 0.0 {
            let omega = omega2.sqrt();
            (omega * linear).atan() / omega
        } else {
            linear
        };
        cap.max(to_twice_escape.min(longest))
    }

    /// The Taylor step from the current state, at most `cap` long (one step scale where the cap
    /// is infinite): as long as the last two terms of the series, `c₉h⁹` and `c₁₀h¹⁰`, stay
    /// within the tolerance in the error norm ([`MinoTracer::error_norm`], linear in the error,
    /// so each bounds `h` by a root; Jorba & Zou 2005, §3.2.1; the next term, the truncation,
    /// is smaller by about the step over the series' radius of convergence), and halved while
    /// its end is past infinity (`u ≤ 0`, which a polynomial in `u` may reach where `r` does
    /// not).
    fn taylor_step(&self, cap: f64, scale: f64, rtol: f64) -> Result<Dense, Failure> {
        let longest = if cap.is_finite() { cap } else { scale };
        let series = self.constants.series(&self.y);
        let bound = |k: usize| {
            let norm = self.error_norm(&self.y, &self.y, &column(&series, k), rtol);
            (1.0 / (norm * longest.powi(k as i32))).min(1.0)
        };
        let fraction = taylor::shorter_root::<{ ORDER as i32 - 1 }, { ORDER as i32 }>(bound(ORDER - 1), bound(ORDER));
        let mut h = longest * fraction;
        loop {
            let end = std::array::from_fn(|i| taylor::value(&series[i], h));
            if end[0] > 0.0 {
                return Ok(Dense::Taylor { series, h, end });
            }
            if end[0].is_nan() {
                return Err(Failure::NonFinite);
            }
            h *= 0.5;
            if !(h > 1e-14 * longest) {
                return Err(Failure::StepUnderflow);
            }
        }
    }

    /// The fate of the ray at its current point, if it has ended: inside the horizon, or past the
    /// escape radius with `r` growing (`u' < 0`), leaving along its chart velocity there.
    pub(super) fn ended(&self) -> Option<Fate> {
        let [u, w, ..] = self.y;
        if u >= self.horizon_u {
            return Some(Fate::Captured);
        }
        if u * self.settings.escape_radius < 1.0 && w < 0.0 {
            let d = self.constants.velocity(&self.y, &self.constants.rhs(&self.y));
            return Some(Fate::Escaped { direction: crate::tensor::normalize3(&d) });
        }
        None
    }
}

impl RayTracer for MinoTracer {
    type Step = MinoStep;

    /// The tracer with the chart's time integrated along every step (see `time`): the steps'
    /// [`RayStep::time_at`] and the trace's end carry it; everything else is as without, bit
    /// for bit.
    fn carrying_time(self) -> Self {
        Self { timed: true, ..self }
    }

    /// Traces the ray to its end, showing every accepted step to `visit`; the trace's largest
    /// `|H|` is that of the chart momentum at the step ends (or at the start and end).
    fn run(mut self, mut visit: impl FnMut(&MinoStep) -> Visit) -> Trace {
        let mut max_h: f64 = self.constants.momentum(&self.y).1.abs();
        let fate = loop {
            if let Some(fate) = self.ended() {
                break fate;
            }
            // Seen where it was returned: a step (its series) is too large to move for nothing.
            match &self.step() {
                Ok(step) => {
                    if self.settings.check_every_step {
                        max_h = max_h.max(self.constants.momentum(&self.y).1.abs());
                    }
                    if visit(step) == Visit::Stop {
                        break Fate::Stopped;
                    }
                }
                Err(failure) => break Fate::Failed(*failure),
            }
        };
        let (end, end_h) = self.state_and_hamiltonian();
        Trace { fate, steps: self.steps, max_abs_hamiltonian: max_h.max(end_h.abs()), end }
    }
}

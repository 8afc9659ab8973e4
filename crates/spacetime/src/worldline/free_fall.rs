//! Integrating a worldline: the 4-D tracer's accepted steps, kept with their dense output, until
//! the span asked for is done or the worldline ends.

use super::start::{check, StartError};
use super::Chart;
use crate::geodesic::{Failure, HamiltonianStep, HamiltonianTracer, State, TraceSettings};
use crate::metric::{Metric, Region};

/// How far to integrate.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Until {
    /// Until this proper time since the start.
    ProperTime(f64),
    /// Until this coordinate time of the spacetime's own chart: what a renderer showing times
    /// up to it needs. A body that falls into a hole reaches no such time (the own chart's time
    /// grows without bound at the horizon) and goes on to the centre.
    CoordinateTime(f64),
}

/// How a worldline ended.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum End {
    /// The span asked for ([`Until`]) was integrated.
    Until,
    /// Past the escape radius ([`TraceSettings::escape_radius`]) moving outward, in `region`:
    /// through a wormhole's throat where that is not the region it started in.
    Escaped { region: Region },
    /// At the centre `r = 0` of a hole: the singularity of a static one, the disk bounded by
    /// the ring singularity of a spinning one; the chart ends there.
    Centre,
    /// The integration collapsed (error control asked for steps too small to make progress, or
    /// the state stopped being finite): the chart ends on the worldline, at a horizon it does
    /// not cross (a hole's own chart, Schwarzschild's coordinates written by hand), at a
    /// singularity, or at the inner horizon of a charged or spinning hole, whose far side the
    /// twin's chart does not reach.
    ChartEnds,
    /// It used up [`TraceSettings::max_steps`].
    OutOfSteps,
}

impl End {
    /// Stable lower-case name, as in statistics and JSON.
    pub fn name(&self) -> &'static str {
        match self {
            End::Until => "until",
            End::Escaped { .. } => "escaped",
            End::Centre => "centre",
            End::ChartEnds => "chart-ends",
            End::OutOfSteps => "out-of-steps",
        }
    }
}

/// One accepted step and the proper time at its start.
#[derive(Clone, Copy, Debug)]
pub(super) struct Piece {
    pub(super) tau: f64,
    pub(super) step: HamiltonianStep,
}

/// A body's worldline in free fall: a timelike geodesic parametrised by proper time, integrated
/// with error control in a [`Chart`] regular along it, with its events anywhere by proper time
/// or by the own chart's coordinate time (`timeline`).
#[derive(Clone, Debug)]
pub struct Worldline {
    pub(super) chart: Chart,
    /// The start, in the chart integrated in.
    pub(super) start: State,
    /// The own chart's time at the start, as given (mapped back, it is off by rounding).
    pub(super) start_time: f64,
    pub(super) pieces: Vec<Piece>,
    /// The own chart's time at each piece's end (NaN where the own chart does not reach).
    pub(super) end_times: Vec<f64>,
    pub(super) end: End,
    /// Proper time at which it crossed the (outer) future horizon of a hole.
    pub(super) horizon: Option<f64>,
}

impl Worldline {
    /// Integrates the worldline of a body of unit rest mass from `start` (own chart; from
    /// [`super::start`] or [`super::CircularOrbit::start`]) in `chart`, with the settings' steps
    /// and escape radius, until `until` or its end. Refuses a start that is not a body's
    /// (`g^{μν} p_μ p_ν ≠ −1`, past-directed, not finite).
    pub fn integrate(chart: Chart, start: State, until: Until, settings: &TraceSettings) -> Result<Self, StartError> {
        check(chart.own_metric(), &start)?;
        let begin = chart.to_integrated(&start);
        let (pieces, end, horizon) = run(&chart, begin, until, settings);
        let end_times = pieces.iter().map(|p| chart.own_time(&p.step.end.x)).collect();
        Ok(Worldline { chart, start: begin, start_time: start.x[0], pieces, end_times, end, horizon })
    }
}

/// Steps from `begin` (chart integrated in) until `until` or an end: the pieces, the end and
/// the proper time of a horizon crossing.
fn run(chart: &Chart, begin: State, until: Until, settings: &TraceSettings) -> (Vec<Piece>, End, Option<f64>) {
    let metric = chart.integrated();
    let mut tracer = HamiltonianTracer::of_body(metric, begin, *settings);
    let mut pieces = Vec::new();
    let mut horizon = None;
    let end = loop {
        if let Some(end) = ended(chart, &tracer, settings) {
            break end;
        }
        let tau = tracer.lambda();
        let h_limit = match until {
            Until::ProperTime(limit) => limit - tau,
            Until::CoordinateTime(_) => f64::INFINITY,
        };
        if h_limit <= 4.0 * f64::EPSILON * tau.abs() {
            break End::Until;
        }
        match tracer.step(h_limit) {
            Ok(step) => {
                if horizon.is_none() {
                    horizon =
                        chart.horizon().and_then(|r| crossing(metric, &step, r)).map(|theta| tau + theta * step.h);
                }
                pieces.push(Piece { tau, step });
                let past_time = matches!(until, Until::CoordinateTime(t) if chart.own_time(&step.end.x) >= t);
                if past_time {
                    break End::Until;
                }
            }
            Err(Failure::OutOfSteps) => break End::OutOfSteps,
            Err(Failure::StepUnderflow | Failure::NonFinite) => break End::ChartEnds,
        }
    };
    (pieces, end, horizon)
}

/// How the worldline ends at the tracer's current point, if it does there.
fn ended(chart: &Chart, tracer: &HamiltonianTracer<'_, dyn Metric + '_>, settings: &TraceSettings) -> Option<End> {
    let x = tracer.state().x;
    let metric = chart.integrated();
    if chart.at_centre(&x) {
        return Some(End::Centre);
    }
    let outward = metric.is_outgoing(&x, &tracer.velocity());
    (metric.radius(&x) > settings.escape_radius && outward).then(|| End::Escaped { region: metric.region(&x) })
}

/// The fraction of `step` at which its radius falls through `horizon`, if it does: bisection on
/// the dense output to the last bit (a future-directed body crosses once, inwards).
fn crossing(metric: &dyn Metric, step: &HamiltonianStep, horizon: f64) -> Option<f64> {
    let outside = |theta: f64| metric.radius(&step.position_at(theta)) > horizon;
    if !outside(0.0) || outside(1.0) {
        return None;
    }
    let (mut lo, mut hi) = (0.0f64, 1.0f64);
    while hi - lo > f64::EPSILON {
        let mid = 0.5 * (lo + hi);
        if outside(mid) {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    Some(0.5 * (lo + hi))
}

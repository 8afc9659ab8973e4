//! A worldline's events by proper time, and by the own chart's coordinate time: "where is the
//! body at time t", which a renderer asks.

use super::free_fall::{End, Worldline};
use super::{Chart, Event};
use crate::geodesic::State;

impl Worldline {
    /// How it ended.
    pub fn end(&self) -> End {
        self.end
    }

    /// Proper time from the start to the last event integrated.
    pub fn proper_time(&self) -> f64 {
        self.pieces.last().map_or(0.0, |p| p.tau + p.step.h)
    }

    /// Proper time at which the body crossed a hole's (outer) future horizon, if it did: after
    /// it the body has no event in the hole's own chart.
    pub fn horizon_crossing(&self) -> Option<f64> {
        self.horizon
    }

    /// The chart integrated in.
    pub fn chart(&self) -> &Chart {
        &self.chart
    }

    /// Accepted steps.
    pub fn steps(&self) -> usize {
        self.pieces.len()
    }

    /// The state at proper time `tau` in the chart integrated in (which reaches past a hole's
    /// horizon); `None` outside `[0, proper_time()]`.
    pub fn state_at(&self, tau: f64) -> Option<State> {
        if !(0.0..=self.proper_time()).contains(&tau) {
            return None;
        }
        let i = self.pieces.partition_point(|p| p.tau + p.step.h < tau);
        let Some(piece) = self.pieces.get(i) else { return Some(self.start) };
        Some(piece.step.at(((tau - piece.tau) / piece.step.h).clamp(0.0, 1.0)))
    }

    /// The event at proper time `tau`, in the own chart; `None` outside the span integrated and
    /// where the own chart does not reach (past a hole's horizon).
    pub fn event_at_proper_time(&self, tau: f64) -> Option<Event> {
        let (x, u, p) = self.chart.event(&self.state_at(tau)?)?;
        Some(Event { tau, x, u, p })
    }

    /// The proper time at which the own chart's coordinate time is `t`; `None` before the start
    /// and after the last event in the own chart. The time grows along the worldline (its
    /// slices are spacelike wherever it goes), so there is one, found by bisection on the dense
    /// output of the step that holds it.
    pub fn proper_time_at(&self, t: f64) -> Option<f64> {
        if !(t >= self.start_time) {
            return None;
        }
        // NaN (past the horizon) counts as later than any time.
        let i = self.end_times.partition_point(|&end| end < t);
        let piece = self.pieces.get(i)?;
        let later = |theta: f64| !(self.chart.own_time(&piece.step.position_at(theta)) < t);
        let (mut lo, mut hi) = (0.0f64, 1.0f64);
        while hi - lo > f64::EPSILON {
            let mid = 0.5 * (lo + hi);
            if later(mid) {
                hi = mid;
            } else {
                lo = mid;
            }
        }
        Some(piece.tau + 0.5 * (lo + hi) * piece.step.h)
    }

    /// The event at the own chart's coordinate time `t` ([`Worldline::proper_time_at`]).
    pub fn event_at_time(&self, t: f64) -> Option<Event> {
        self.event_at_proper_time(self.proper_time_at(t)?)
    }
}

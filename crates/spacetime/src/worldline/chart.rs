//! The chart a worldline is integrated in, and its events in the spacetime's own chart.
//!
//! A black hole's own chart here is outgoing Kerr–Schild, regular on the past horizon that
//! backward-traced light crosses and singular on the future horizon that a falling body
//! crosses: its time `t` grows without bound as the body nears it, at a finite proper time.
//! Reversed in time, the ingoing chart of the hole is the outgoing chart of its spin twin
//! ([`SpinTwin`]), in which a body's future-directed worldline is a past-directed curve that
//! crosses the horizon like any camera ray and goes on to the centre. Outside the horizon its
//! events map back to the hole's chart, the time included (`t = −t' − H(r)`), and the hole's
//! coordinate time grows monotonically along it (its `t = const` slices are spacelike) towards
//! infinity at the horizon: every time of the hole's chart after the start has its event.

use crate::geodesic::State;
use crate::metric::{KerrNewman, KerrSchild, Metric, Spacetime, SpinTwin};
use crate::tensor::{contract, Covector4, Vector4};
use std::sync::Arc;

/// A hole's centre is reached at this fraction of its mass: a radial plunge gets there
/// `(2/3) r^{3/2}/√(2M)` (5e-10 M) before `r = 0`, the error control's own size.
const CENTRE: f64 = 1e-6;

/// Where a worldline is integrated (see the module documentation).
#[derive(Clone)]
pub struct Chart(Kind);

#[derive(Clone)]
enum Kind {
    /// The metric's own chart, used as it is.
    Own(Arc<dyn Metric>),
    /// A hole of Kerr's family, integrated in its spin twin's chart.
    Twin { map: SpinTwin, hole: KerrNewman, twin: KerrNewman },
}

impl std::fmt::Debug for Chart {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match &self.0 {
            Kind::Own(_) => write!(f, "Chart::Own"),
            Kind::Twin { map, .. } => write!(f, "Chart::Twin({map:?})"),
        }
    }
}

impl Chart {
    /// The metric's own chart, for any metric: a worldline ends where the chart does (a
    /// horizon it does not cross, a singularity), as the integration collapses there.
    pub fn own(metric: impl Metric + 'static) -> Chart {
        Chart(Kind::Own(Arc::new(metric)))
    }

    /// The chart regular along every worldline of `spacetime`: the spin twin's for a hole of
    /// Kerr's family (Schwarzschild and Reissner–Nordström included), its own chart for the
    /// others (flat space, wormholes, written metrics).
    pub fn for_spacetime(spacetime: &Spacetime) -> Chart {
        match spacetime {
            Spacetime::Minkowski(m) => Chart::own(*m),
            Spacetime::Schwarzschild(h) => Chart::hole(h.mass, 0.0, 0.0),
            Spacetime::Kerr(h) => Chart::hole(h.mass, h.spin, 0.0),
            Spacetime::ReissnerNordstrom(h) => Chart::hole(h.mass, 0.0, h.charge),
            Spacetime::KerrNewman(h) => Chart::hole(h.mass, h.spin, h.charge),
            Spacetime::Ellis(m) => Chart::own(*m),
            Spacetime::Wormhole(m) => Chart::own(*m),
            Spacetime::Written(m) => Chart::own(m.clone()),
        }
    }

    /// A hole of Kerr's family: its twin's chart, or flat space's where it has no mass.
    fn hole(mass: f64, spin: f64, charge: f64) -> Chart {
        let hole = KerrNewman::new(mass, spin, charge);
        if mass == 0.0 {
            return Chart::own(hole);
        }
        let map = SpinTwin::new(mass, spin, charge);
        Chart(Kind::Twin { map, hole, twin: map.twin() })
    }

    /// The spacetime's own metric, whose chart events are given in.
    pub fn own_metric(&self) -> &dyn Metric {
        match &self.0 {
            Kind::Own(m) => m.as_ref(),
            Kind::Twin { hole, .. } => hole,
        }
    }

    /// The metric of the chart integrated in.
    pub(super) fn integrated(&self) -> &dyn Metric {
        match &self.0 {
            Kind::Own(m) => m.as_ref(),
            Kind::Twin { twin, .. } => twin,
        }
    }

    /// A state of the own chart in the chart integrated in.
    pub(super) fn to_integrated(&self, s: &State) -> State {
        match &self.0 {
            Kind::Own(_) => *s,
            Kind::Twin { map, .. } => {
                let (x, p) = map.to_twin(&s.x, &s.p);
                State { x, p }
            }
        }
    }

    /// The event, in the own chart, of state `s` of the chart integrated in: position,
    /// 4-velocity and momentum; `None` where the own chart does not reach (inside the horizon).
    pub(super) fn event(&self, s: &State) -> Option<(Vector4, Vector4, Covector4)> {
        let u = contract(&self.integrated().inverse_metric(&s.x), &s.p);
        let (x, u, p) = match &self.0 {
            Kind::Own(_) => (s.x, u, s.p),
            Kind::Twin { map, .. } => {
                let (x, p) = map.from_twin(&s.x, &s.p);
                (x, map.vector_from_twin(&s.x, &u), p)
            }
        };
        x.iter().chain(&u).chain(&p).all(|c| c.is_finite()).then_some((x, u, p))
    }

    /// The own chart's time at point `x` of the chart integrated in (NaN where the own chart
    /// does not reach).
    pub(super) fn own_time(&self, x: &Vector4) -> f64 {
        match &self.0 {
            Kind::Own(_) => x[0],
            Kind::Twin { map, .. } => map.event_from_twin(x)[0],
        }
    }

    /// The radial coordinate of the (outer) event horizon that worldlines cross in the chart
    /// integrated in, where there is one.
    pub(super) fn horizon(&self) -> Option<f64> {
        match &self.0 {
            Kind::Own(_) => None,
            Kind::Twin { twin, .. } => Some(twin.horizon_radius()),
        }
    }

    /// Whether point `x` of the chart integrated in is at a hole's centre `r = 0`: its
    /// singularity, or for a spinning hole the disk its ring bounds, where the chart ends.
    pub(super) fn at_centre(&self, x: &Vector4) -> bool {
        match &self.0 {
            Kind::Own(_) => false,
            Kind::Twin { twin, .. } => twin.radial_coordinate(x) < CENTRE * twin.mass,
        }
    }
}

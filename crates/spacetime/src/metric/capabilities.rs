//! What a renderer asks of a spacetime, answered by each metric: whether it is flat, its regions,
//! its time symmetry, where observers can stay at rest and what they measure, how far rays from
//! infinity reach, and which tracer and light connector fit it. The trait has no defaults: a new
//! metric answers every question, and nothing gets flat space's or Schwarzschild's answer by
//! omission.
//!
//! Points are world points of a region in the chart's axes (a renderer rotates a scene's axis onto
//! the chart's z first); spherically symmetric metrics do not care.

use super::spin_twin::SpinTwin;
use super::{Metric, Region};
use crate::disk::CircularOrbits;
use crate::geodesic::plane::PlaneMetric;
use crate::geodesic::{RayTracer, State, TraceSettings};
use crate::metric::schwarzschild::connect::Connector;
use crate::observer::Tetrad;

/// The frame of the local observer (static where one exists, else the chart's normal observer)
/// at a point, as world vectors map into it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum LocalFrame {
    /// The world's axes, radial lengths scaled: world vectors map by `diag(1/κ, 1, 1)` (radial
    /// first), `κ = dρ/dl` the world (areal) radius per proper radial length. Spherically
    /// symmetric static spacetimes; `κ = 1` in flat space.
    Radial { kappa: f64 },
    /// A general orthonormal frame, in the chart whose point `x` it sits at.
    Tetrad { frame: Tetrad, x: [f64; 4] },
    /// The world's own axes: no observer frame exists at the point (inside a horizon or throat,
    /// where nothing is measured), so directions are taken as they are.
    None,
}

/// Why no observer can stay at rest at a point: where the static observer (`u ∝ ∂_t`) does not
/// exist, a camera at rest has nothing to be.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum NoRest {
    /// Inside an event horizon of (chart) radius `horizon`, at radius `radius`.
    InsideHorizon { radius: f64, horizon: f64 },
    /// Inside the ergoregion of a spinning hole, where everything is dragged round.
    InsideErgoregion,
    /// In a region the spacetime does not have (the lower one of a spacetime with one).
    NoSuchRegion,
    /// Where the chart does not reach (within a wormhole's throat radius `throat`, in world
    /// radius `radius`).
    OffChart { radius: f64, throat: f64 },
    /// Where a written metric's time slices have collapsed (their lapse `1/√(−g^tt)` is
    /// `lapse`, below the horizon criterion, or `g^tt ≥ 0`): rays there are captured.
    Collapsed { lapse: f64 },
    /// Where the metric's time direction `∂_t` is not timelike (`g_tt ≥ 0`), as in an
    /// ergoregion.
    TimeNotTimelike { g_tt: f64 },
    /// Where the metric is not finite.
    NotFinite,
    /// Where the metric does not have the signature (−,+,+,+): `negative` of its eigenvalues
    /// are negative, `zero` vanish.
    NotLorentzian { negative: usize, zero: usize },
}

impl std::fmt::Display for NoRest {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            NoRest::InsideHorizon { radius, horizon } => {
                write!(f, "lies inside the event horizon (radius {radius} ≤ {horizon}), where nothing can stay at rest")
            }
            NoRest::InsideErgoregion => {
                write!(f, "lies inside the ergoregion of the spinning hole, where nothing can stay at rest")
            }
            NoRest::NoSuchRegion => write!(f, "lies in a region this spacetime does not have"),
            NoRest::OffChart { radius, throat } => write!(
                f,
                "lies within the wormhole's throat (world radius {radius} < throat {throat}); points of a \
                 region lie at world radius ≥ throat"
            ),
            NoRest::Collapsed { lapse } => write!(
                f,
                "lies where the metric's time slices have collapsed (lapse 1/√(−g^tt) = {lapse}), at or behind a \
                 horizon, where rays are captured"
            ),
            NoRest::TimeNotTimelike { g_tt } => write!(
                f,
                "lies where the metric's time direction is not timelike (g_tt = {g_tt} ≥ 0), where nothing can stay \
                 at rest"
            ),
            NoRest::NotFinite => write!(f, "lies where the metric is not finite"),
            NoRest::NotLorentzian { negative, zero } => write!(
                f,
                "lies where the metric is not of signature (−,+,+,+): it has {negative} negative and {zero} zero \
                 eigenvalues (one negative, none zero wanted)"
            ),
        }
    }
}

/// How light running forwards in time is traced, for renderers that follow it from its sources
/// (photon mapping): with the backward tracers, which follow light from its receivers.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Forwards {
    /// Time-symmetric: a ray forwards from a point along `n` runs along the backward ray from
    /// there along `n`, seen with the same lapses.
    Reversed,
    /// A spinning hole: rays forwards are the backward rays of its spin-reversed twin, in the
    /// chart [`SpinTwin`] maps to, which is regular on the future horizon they fall through.
    SpinTwin(SpinTwin),
    /// No way to follow light forwards is known: a metric written by the user may depend on time
    /// or rotate, and nothing here can prove it symmetric, so renderers that need forward light
    /// refuse it rather than trace the wrong rays.
    Unsupported,
}

/// A metric that steps its rays with a stepper of its own, cheaper than the 4-D tracer's and as
/// accurate at the same settings (Kerr's family: Mino time with the constants of motion,
/// [`crate::metric::kerr_newman::mino`]). Its steps and states are in the metric's own chart.
pub trait OwnStepper: Metric {
    type Tracer: RayTracer;
    /// The tracer of the ray from `start` with `settings`.
    fn ray_tracer(&self, start: State, settings: TraceSettings) -> Self::Tracer;
}

/// The tracers a renderer offers; a metric picks the one that fits it
/// ([`Capabilities::choose_tracer`]), dispatched once per ray and generic inside.
pub trait Tracers {
    type Output;
    /// Straight lines: flat space.
    fn straight(self) -> Self::Output;
    /// The in-plane tracer of static spherically symmetric metrics, which provide their own
    /// stepper where they have one (Schwarzschild's Taylor series).
    fn in_plane<M: PlaneMetric>(self, metric: &M) -> Self::Output;
    /// The 4-D Hamiltonian tracer, in one region.
    fn four_d<M: Metric>(self, metric: &M) -> Self::Output;
    /// The metric's own 4-D stepper, in one region; what needs Hamilton's equations themselves
    /// (ray bundles) takes the metric as [`Tracers::four_d`] does.
    fn own_stepper<M: OwnStepper>(self, metric: &M) -> Self::Output;
}

/// The questions a renderer asks of a spacetime (see the module documentation).
pub trait Capabilities: Metric {
    /// Whether light goes straight everywhere (flat space, a hole of mass 0).
    fn is_flat(&self) -> bool;

    /// Whether every rotation about the centre is a symmetry: then no axis of a scene matters.
    fn is_spherically_symmetric(&self) -> bool;

    /// The radius of the throat joining two asymptotic regions; `None` for one region.
    fn throat(&self) -> Option<f64>;

    /// How light running forwards in time is traced.
    fn forwards(&self) -> Forwards;

    /// Whether an observer can stay at rest at world point `p` of `region`, and why not.
    fn rest(&self, region: Region, p: [f64; 3]) -> Result<(), NoRest>;

    /// The local observer's frame at world point `p` of `region`.
    fn local_frame(&self, region: Region, p: [f64; 3]) -> LocalFrame;

    /// The local observer's lapse at world point `p` of `region`: it measures the frequency of
    /// light of conserved energy `E` as `E/lapse` (`√(−g_tt)` for the static observer).
    fn observer_lapse(&self, region: Region, p: [f64; 3]) -> f64;

    /// The largest impact parameter of a ray from infinity that comes within world radius
    /// `radius` of the centre; `None` where the spacetime has no such bound (Kerr, whose
    /// bound depends on the ray's inclination; its rays are not traced from infinity).
    fn impact_bound(&self, radius: f64) -> Option<f64>;

    /// A radius beyond which no light ray has a greatest distance from the centre (the photon
    /// sphere), where every ray bends towards the centre; `None` where there is none.
    fn no_turning_beyond(&self) -> Option<f64>;

    /// The solver joining two points by light rays, where there is one (it owns tables: build
    /// it once per render).
    fn light_connector(&self) -> Option<Connector>;

    /// The prograde circular geodesics of the equatorial plane (z = 0 of the chart's axes) that
    /// a thin accretion disk's gas follows, where the spacetime is a hole of Kerr's family;
    /// `None` where it has none a disk could be built on (flat space, wormholes, metrics whose
    /// orbits nothing here can find).
    fn circular_orbits(&self) -> Option<CircularOrbits>;

    /// Calls the tracer of `tracers` that fits this metric.
    fn choose_tracer<T: Tracers>(&self, tracers: T) -> T::Output
    where
        Self: Sized;
}

/// The local frame of a spherically symmetric static metric at `p`: radial scaling by
/// [`PlaneMetric::radial_scale`] (world axes where the radius has no chart point).
pub(super) fn radial_frame<M: PlaneMetric>(metric: &M, p: [f64; 3]) -> LocalFrame {
    let kappa = metric.u_of_world_radius(crate::tensor::norm3(&p)).map_or(1.0, |u| metric.radial_scale(u));
    LocalFrame::Radial { kappa }
}

/// The static observer's lapse of a spherically symmetric static metric at `p`
/// ([`PlaneMetric::lapse`]; 1 where the radius has no chart point).
pub(super) fn radial_lapse<M: PlaneMetric>(metric: &M, p: [f64; 3]) -> f64 {
    metric.u_of_world_radius(crate::tensor::norm3(&p)).map_or(1.0, |u| metric.lapse(u))
}

/// Where an observer can stay at rest around a static hole of one region with its horizon at
/// `horizon` (none for mass 0): anywhere outside it.
pub(super) fn rest_outside_horizon(region: Region, p: [f64; 3], horizon: Option<f64>) -> Result<(), NoRest> {
    if region == Region::Lower {
        return Err(NoRest::NoSuchRegion);
    }
    let radius = crate::tensor::norm3(&p);
    match horizon {
        Some(horizon) if radius <= horizon => Err(NoRest::InsideHorizon { radius, horizon }),
        _ => Ok(()),
    }
}

/// The local observer's frame at world point `p` of `region` of a metric whose chart is not
/// spherical: the static observer's where `∂_t` is timelike, else the normal observer's of the
/// chart's time slices ([`Tetrad::local_observer`]), none where neither exists (inside a
/// horizon, off the chart).
pub(super) fn tetrad_frame<M: Metric>(m: &M, region: Region, p: [f64; 3]) -> LocalFrame {
    let Some(x) = m.world_to_chart(region, p, 0.0) else { return LocalFrame::None };
    match Tetrad::local_observer(m, &x) {
        Ok(frame) => LocalFrame::Tetrad { frame, x },
        Err(_) => LocalFrame::None,
    }
}

/// `1/u^t` of the local observer ([`tetrad_frame`]): `√(−g_tt)` for the static one,
/// `1/√(−g^tt)` for the normal one.
pub(super) fn tetrad_lapse<M: Metric>(m: &M, region: Region, p: [f64; 3]) -> f64 {
    match tetrad_frame(m, region, p) {
        LocalFrame::Tetrad { frame, .. } => 1.0 / frame.e[0][0],
        LocalFrame::Radial { .. } | LocalFrame::None => 1.0,
    }
}

/// Where an observer can stay at rest in a wormhole of throat radius `throat`: at every point
/// its chart reaches (world radius ≥ throat in either region).
pub(super) fn rest_on_chart<M: Metric>(metric: &M, region: Region, p: [f64; 3], throat: f64) -> Result<(), NoRest> {
    match metric.world_to_chart(region, p, 0.0) {
        Some(_) => Ok(()),
        None => Err(NoRest::OffChart { radius: crate::tensor::norm3(&p), throat }),
    }
}

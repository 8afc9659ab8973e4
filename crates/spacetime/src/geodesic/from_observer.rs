//! One photon followed forwards in time from an observer: it leaves a world point along a
//! direction the local observer there measures (the static observer, or the chart's normal
//! observer where none can stay at rest, as for a camera: [`Tetrad::local_observer`]), with unit
//! energy as that observer measures it. This is the physics a user asks of a spacetime — where
//! does light sent this way go — where the renderer asks where light seen this way came from.
//!
//! Every tracer here follows rays backwards ([`crate`] documentation), and forward light is
//! their time reverse ([`Forwards`]). In a time-symmetric spacetime the photon leaving along
//! `n` runs along the backward ray leaving along `n`; about a spinning hole it is the backward
//! ray of the spin-reversed twin ([`SpinTwin`]). Either way the backward ray's chart with its
//! time reversed, `t → −t`, is a chart of the spacetime in which the photon runs forwards along
//! the same affine parameter: the static chart itself, or for holes the *ingoing* Kerr–Schild
//! chart, regular on the future horizon the photon falls through. States handed out
//! ([`Photon::start`], [`Photon::record`]) are in that chart: `t` and `p_t` of the traced state
//! negated, so `E = −p_t > 0`.
//!
//! [`Photon::trace`] runs the tracer the spacetime chooses ([`Spacetime::choose_tracer`]: in the
//! ray's plane for spherical metrics, started as a camera's rays are, Kerr's own stepper, 4-D
//! Hamiltonian otherwise) to the photon's fate; [`Photon::record`] integrates Hamilton's
//! equations in 4-D and keeps every accepted step, the trajectory with its affine parameter and
//! covariant momenta, which the in-plane tracer (parametrised by azimuth, with neither time nor
//! momenta) does not have.

use super::plane::{trace_plane, PlaneMetric, PlaneStart};
use super::{angular_momentum_z, HamiltonianTracer, RayTracer, State, TraceSettings, Visit};
use crate::metric::kerr_newman::mino::carter_q;
use crate::metric::{Forwards, Metric, OwnStepper, Region, Spacetime, SpinTwin, Tracers};
use crate::tensor::{Matrix4, Vector4};
use crate::{Fate, Tetrad};

/// Why a photon cannot be launched.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum NoLaunch {
    /// The spacetime's light cannot be followed forwards in time ([`Forwards::Unsupported`]: a
    /// metric written by a user, which nothing here can prove time-symmetric).
    NotReversible,
    /// The position lies off the chart (within a wormhole's throat, or in a region the
    /// spacetime does not have).
    OffChart,
}

impl std::fmt::Display for NoLaunch {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            NoLaunch::NotReversible => f.write_str(
                "light cannot be followed forwards in time in this spacetime (nothing shows it time-symmetric)",
            ),
            NoLaunch::OffChart => {
                f.write_str("lies off the spacetime's chart (within a throat, or in no region of it)")
            }
        }
    }
}

impl std::error::Error for NoLaunch {}

/// How a photon's ray is traced.
#[derive(Clone, Copy, Debug)]
enum Way {
    /// Flat space: a straight line, nothing to integrate.
    Straight,
    /// Time-symmetric: the backward ray leaving along the same direction, in the own chart.
    Reversed,
    /// A spinning hole: the backward ray of its spin-reversed twin, in the twin's chart.
    Twin(SpinTwin),
}

/// A photon leaving a world point along a direction its local observer measures.
#[derive(Clone, Copy, Debug)]
pub struct Photon<'s> {
    spacetime: &'s Spacetime,
    way: Way,
    region: Region,
    position: [f64; 3],
    direction: [f64; 3],
}

/// How a photon ended.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PhotonTrace {
    /// Its fate; an escaped photon's direction is its world direction of travel at the escape
    /// radius.
    pub fate: Fate,
    /// Accepted steps.
    pub steps: u32,
    /// Largest `|H|` the tracer checked ([`TraceSettings::check_every_step`]).
    pub max_abs_hamiltonian: f64,
}

/// One accepted step's end along a recorded photon.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Recorded {
    /// Affine parameter from the start (with the photon's unit starting energy).
    pub lambda: f64,
    /// Position and covariant momentum in the forward chart (module documentation).
    pub state: State,
    /// World region and position ([`Metric::to_world`] of the traced chart).
    pub region: Region,
    pub position: [f64; 3],
}

/// The constants of motion a spacetime has, of one state; `None` where it lacks the symmetry.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Conserved {
    /// `E = −p_t`, where `∂_t` is a Killing vector.
    pub energy: Option<f64>,
    /// `L_z = x p_y − y p_x`, where rotation about z is a symmetry.
    pub axial: Option<f64>,
    /// Carter's `Q`, for Kerr's family.
    pub carter: Option<f64>,
}

impl<'s> Photon<'s> {
    /// The photon leaving world point `position` of `region` along the unit `direction` its local
    /// observer measures (frame axes aligned with the world's, a spin along z).
    pub fn launch(
        spacetime: &'s Spacetime,
        region: Region,
        position: [f64; 3],
        direction: [f64; 3],
    ) -> Result<Photon<'s>, NoLaunch> {
        let answers = spacetime.capabilities();
        if answers.world_to_chart(region, position, 0.0).is_none() {
            return Err(NoLaunch::OffChart);
        }
        let way = if answers.is_flat() {
            Way::Straight
        } else {
            match answers.forwards() {
                Forwards::Reversed => Way::Reversed,
                Forwards::SpinTwin(twin) => Way::Twin(twin),
                Forwards::Unsupported => return Err(NoLaunch::NotReversible),
            }
        };
        Ok(Photon { spacetime, way, region, position, direction })
    }

    /// The metric the photon's ray is traced in and its backward start state there; `None`
    /// where no local observer exists (inside a horizon): the photon is captured at once.
    fn traced_start(&self) -> Option<(TracedMetric<'s>, State)> {
        match self.way {
            Way::Straight | Way::Reversed => self.own_start().map(|s| (TracedMetric::Own(self.spacetime.metric()), s)),
            Way::Twin(twin) => self.twin_start(&twin).map(|s| (TracedMetric::Twin(twin.twin()), s)),
        }
    }

    /// The local observer's frame at the start, with the chart point and the metric there.
    fn observer(&self) -> Option<(Tetrad, Vector4, Matrix4)> {
        let hole = self.spacetime.metric();
        let x = hole.world_to_chart(self.region, self.position, 0.0)?;
        let frame = Tetrad::local_observer(hole, &x).ok()?;
        Some((frame, x, hole.metric(&x)))
    }

    /// The backward ray leaving along the photon's direction, in the spacetime's chart.
    fn own_start(&self) -> Option<State> {
        let (frame, x, g) = self.observer()?;
        Some(State { x, p: frame.backward_momentum(&g, self.direction, 1.0) })
    }

    /// As the renderer's forward light about a spinning hole: the future-directed momentum
    /// leaving along `n` is the negative of the backward one leaving along `−n`; in the twin's
    /// chart it is a backward ray.
    fn twin_start(&self, twin: &SpinTwin) -> Option<State> {
        let (frame, x, g) = self.observer()?;
        let back = frame.backward_momentum(&g, self.direction.map(|c| -c), 1.0);
        let (y, q) = twin.to_twin(&x, &back.map(|c| -c));
        Some(State { x: y, p: q })
    }

    /// The photon's start, as [`Photon::record`] hands out its steps (at `λ = 0`); `None` where
    /// no local observer exists.
    pub fn start(&self) -> Option<Recorded> {
        let (traced, start) = self.traced_start()?;
        Some(recorded(traced.metric(), 0.0, &start))
    }

    /// Traces the photon to its fate with the tracer the spacetime chooses. A photon with no
    /// observer at its start (inside a horizon) is captured in no steps.
    pub fn trace(&self, settings: &TraceSettings) -> PhotonTrace {
        match self.way {
            Way::Straight => straight(self.region, self.direction),
            Way::Reversed => self.spacetime.choose_tracer(Backward { photon: self, settings }),
            Way::Twin(twin) => match self.twin_start(&twin) {
                Some(start) => ended(twin.twin().ray_tracer(start, *settings).run(|_| Visit::Continue)),
                None => captured(),
            },
        }
    }

    /// Integrates the photon's Hamilton's equations in 4-D, handing every accepted step's end
    /// (after the start, which [`Photon::start`] gives) to `visit`, in the forward chart.
    pub fn record(&self, settings: &TraceSettings, mut visit: impl FnMut(Recorded)) -> PhotonTrace {
        if let Way::Straight = self.way {
            return straight(self.region, self.direction);
        }
        let Some((traced, start)) = self.traced_start() else { return captured() };
        let metric = traced.metric();
        let mut lambda = 0.0;
        ended(HamiltonianTracer::new(metric, start, *settings).run(|step| {
            lambda += step.h;
            visit(recorded(metric, lambda, &step.end));
            Visit::Continue
        }))
    }

    /// `H = ½ g^{μν} p_μ p_ν` of `state`, a state of the forward chart (zero for light).
    pub fn hamiltonian(&self, state: &State) -> f64 {
        let traced = forward_state(state);
        match self.way {
            Way::Straight | Way::Reversed => self.spacetime.metric().hamiltonian(&traced.x, &traced.p),
            Way::Twin(twin) => twin.twin().hamiltonian(&traced.x, &traced.p),
        }
    }

    /// The constants of motion of `state`, a state of the forward chart.
    pub fn conserved(&self, state: &State) -> Conserved {
        let metric = self.spacetime.metric();
        // The twin's chart, time reversed, is the hole's: Q is quadratic in p and even in the
        // spin, so it is the twin's Q of the traced state.
        let carter = match self.way {
            Way::Twin(twin) => Some(carter_q(&twin.twin(), &forward_state(state))),
            Way::Straight | Way::Reversed => None,
        };
        Conserved {
            energy: metric.is_stationary().then(|| -state.p[0]),
            axial: metric.is_axisymmetric().then(|| angular_momentum_z(state)),
            carter,
        }
    }
}

/// The metric a photon is traced in: the spacetime's own, or a spinning hole's twin.
enum TracedMetric<'s> {
    Own(&'s dyn Metric),
    Twin(crate::metric::KerrNewman),
}

impl TracedMetric<'_> {
    fn metric(&self) -> &dyn Metric {
        match self {
            TracedMetric::Own(m) => *m,
            TracedMetric::Twin(twin) => twin,
        }
    }
}

/// A traced state at `lambda` as handed out: in the forward chart, with its world point.
fn recorded(metric: &dyn Metric, lambda: f64, traced: &State) -> Recorded {
    let (dx, _) = metric.geodesic_rhs(&traced.x, &traced.p);
    let world = metric.to_world(&traced.x, &dx);
    Recorded { lambda, state: forward_state(traced), region: world.region, position: world.position }
}

/// `t → −t`: a traced chart's state as the forward photon's, or back (an involution).
fn forward_state(s: &State) -> State {
    State { x: [-s.x[0], s.x[1], s.x[2], s.x[3]], p: [-s.p[0], s.p[1], s.p[2], s.p[3]] }
}

fn ended(t: super::Trace) -> PhotonTrace {
    PhotonTrace { fate: t.fate, steps: t.steps, max_abs_hamiltonian: t.max_abs_hamiltonian }
}

fn captured() -> PhotonTrace {
    PhotonTrace { fate: Fate::Captured, steps: 0, max_abs_hamiltonian: 0.0 }
}

/// Flat space's photon: it escapes along its direction at once.
fn straight(region: Region, direction: [f64; 3]) -> PhotonTrace {
    let fate = match region {
        Region::Upper => Fate::Escaped { direction },
        Region::Lower => Fate::Traversed { direction },
    };
    PhotonTrace { fate, steps: 0, max_abs_hamiltonian: 0.0 }
}

/// A time-symmetric spacetime's photon, handed to the tracer its metric chooses.
struct Backward<'p, 's> {
    photon: &'p Photon<'s>,
    settings: &'p TraceSettings,
}

impl Tracers for Backward<'_, '_> {
    type Output = PhotonTrace;

    fn straight(self) -> PhotonTrace {
        straight(self.photon.region, self.photon.direction)
    }

    /// Started as the renderer starts a camera's rays, with no 4-D frame.
    fn in_plane<M: PlaneMetric>(self, metric: &M) -> PhotonTrace {
        let Photon { region, position, direction, .. } = *self.photon;
        let Some(start) = PlaneStart::from_observer(metric, region, position, direction) else { return captured() };
        let t = trace_plane(metric, start, self.settings, |_| Visit::Continue);
        PhotonTrace { fate: t.fate, steps: t.steps, max_abs_hamiltonian: t.max_abs_hamiltonian }
    }

    fn four_d<M: Metric>(self, metric: &M) -> PhotonTrace {
        let Some(start) = self.photon.own_start() else { return captured() };
        ended(HamiltonianTracer::new(metric, start, *self.settings).run(|_| Visit::Continue))
    }

    fn own_stepper<M: OwnStepper>(self, metric: &M) -> PhotonTrace {
        let Some(start) = self.photon.own_start() else { return captured() };
        ended(metric.ray_tracer(start, *self.settings).run(|_| Visit::Continue))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geodesic::Stepping;
    use crate::tensor::{dot3, normalize3};

    fn settings() -> TraceSettings {
        TraceSettings { stepping: Stepping::Adaptive { rtol: 1e-10 }, ..TraceSettings::default() }
    }

    fn escaped(fate: Fate) -> [f64; 3] {
        match fate {
            Fate::Escaped { direction } => direction,
            other => panic!("not escaped: {other:?}"),
        }
    }

    /// Every recorded state of `photon`, with the start.
    fn trajectory(photon: &Photon, settings: &TraceSettings) -> (PhotonTrace, Vec<Recorded>) {
        let mut points = vec![photon.start().expect("outside the horizon")];
        let trace = photon.record(settings, |r| points.push(r));
        (trace, points)
    }

    /// Along a recorded photon: null, forwards in time (`dt/dλ > 0`), and the constants of motion
    /// the spacetime has kept to `tolerance`.
    fn check_invariants(photon: &Photon, points: &[Recorded], tolerance: f64) {
        let first = photon.conserved(&points[0].state);
        assert!(first.energy.expect("stationary") > 0.0, "E > 0: future-directed");
        let mut previous_t = f64::NEG_INFINITY;
        for r in points {
            let c = photon.conserved(&r.state);
            for (a, b) in [(c.energy, first.energy), (c.axial, first.axial), (c.carter, first.carter)] {
                if let (Some(a), Some(b)) = (a, b) {
                    assert!((a - b).abs() < tolerance * (1.0 + b.abs()), "{a} vs {b} at λ = {}", r.lambda);
                }
            }
            let h = photon.hamiltonian(&r.state);
            assert!(h.abs() < tolerance, "H = {h} at λ = {}", r.lambda);
            assert!(r.state.x[0] > previous_t, "time runs forwards");
            previous_t = r.state.x[0];
        }
    }

    /// A photon sent past a Schwarzschild hole: the in-plane tracer and the recorded 4-D
    /// trajectory agree on where it goes; the trajectory is null with E and L_z kept, and
    /// bends towards the hole.
    #[test]
    fn schwarzschild_photon_escapes_the_same_way_in_plane_and_in_4d() {
        let hole = Spacetime::schwarzschild(1.0).expect("valid");
        let direction = normalize3(&[0.3, 1.0, 0.2]);
        let photon = Photon::launch(&hole, Region::Upper, [10.0, 0.0, 0.0], direction).expect("launches");
        let in_plane = escaped(photon.trace(&settings()).fate);
        let (recorded, points) = trajectory(&photon, &settings());
        let in_4d = escaped(recorded.fate);
        assert!(dot3(&in_plane, &in_4d) > 1.0 - 1e-12, "{in_plane:?} vs {in_4d:?}");
        assert!(points.len() > 10);
        check_invariants(&photon, &points, 1e-8);
        // Bent towards the hole: it ends turned away from its start direction, towards −x.
        assert!(in_plane[0] < direction[0]);
        // The photon leaves its start outwards (its first step moves it away from the centre).
        let first = points[1].position;
        assert!(first[0] > 10.0 && first[1] > 0.0);
    }

    #[test]
    fn radial_photons_fall_in_or_escape_straight() {
        let hole = Spacetime::schwarzschild(1.0).expect("valid");
        let inward = Photon::launch(&hole, Region::Upper, [0.0, 0.0, 20.0], [0.0, 0.0, -1.0]).expect("launches");
        assert_eq!(inward.trace(&settings()).fate, Fate::Captured);
        assert_eq!(inward.record(&settings(), |_| ()).fate, Fate::Captured);
        let outward = Photon::launch(&hole, Region::Upper, [0.0, 0.0, 20.0], [0.0, 0.0, 1.0]).expect("launches");
        let d = escaped(outward.trace(&settings()).fate);
        assert!((d[2] - 1.0).abs() < 1e-12, "{d:?}");
        let inside = Photon::launch(&hole, Region::Upper, [0.0, 1.0, 0.0], [1.0, 0.0, 0.0]).expect("launches");
        assert_eq!(inside.trace(&settings()).fate, Fate::Captured);
        assert_eq!(inside.record(&settings(), |_| ()).fate, Fate::Captured);
    }

    /// About a spinning hole, forward light is traced in the spin-reversed twin's chart: the
    /// own stepper there and the recorded 4-D trajectory agree, Q is kept, and a photon sent
    /// counter-clockwise (with the spin) has L_z > 0 and time running forwards.
    #[test]
    fn kerr_photon_keeps_carters_constant() {
        let hole = Spacetime::kerr(1.0, 0.9).expect("valid");
        let direction = normalize3(&[-0.2, 1.0, 0.4]);
        let photon = Photon::launch(&hole, Region::Upper, [8.0, 0.0, 3.0], direction).expect("launches");
        let stepped = escaped(photon.trace(&settings()).fate);
        let (recorded, points) = trajectory(&photon, &settings());
        let in_4d = escaped(recorded.fate);
        assert!(dot3(&stepped, &in_4d) > 1.0 - 1e-9, "{stepped:?} vs {in_4d:?}");
        check_invariants(&photon, &points, 1e-8);
        let c = photon.conserved(&points[0].state);
        assert!(c.axial.expect("axisymmetric") > 0.0);
        assert!(c.carter.expect("Kerr") > 0.0, "out of the equatorial plane");
    }

    /// Frame dragging makes forward light differ from backward light about a spinning hole:
    /// a photon sent along a direction does not run along the backward ray leaving that way.
    #[test]
    fn forward_light_about_a_spinning_hole_is_not_the_backward_ray() {
        let hole = Spacetime::kerr(1.0, 0.9).expect("valid");
        let direction = normalize3(&[-0.4, 1.0, 0.0]);
        let photon = Photon::launch(&hole, Region::Upper, [10.0, 0.0, 0.0], direction).expect("launches");
        let forward = escaped(photon.trace(&settings()).fate);
        let backward = photon.own_start().map(|s| {
            let Spacetime::Kerr(kerr) = &hole else { unreachable!("a Kerr hole") };
            ended(kerr.ray_tracer(s, settings()).run(|_| Visit::Continue)).fate
        });
        let backward = escaped(backward.expect("outside the horizon"));
        assert!(dot3(&forward, &backward) < 1.0 - 1e-6, "{forward:?} vs {backward:?}");
        // With spin 0 the twin is the hole itself, and both agree.
        let still = Spacetime::kerr(1.0, 0.0).expect("valid");
        let photon = Photon::launch(&still, Region::Upper, [10.0, 0.0, 0.0], direction).expect("launches");
        let schwarzschild = Spacetime::schwarzschild(1.0).expect("valid");
        let same = Photon::launch(&schwarzschild, Region::Upper, [10.0, 0.0, 0.0], direction).expect("launches");
        let (a, b) = (escaped(photon.trace(&settings()).fate), escaped(same.trace(&settings()).fate));
        assert!(dot3(&a, &b) > 1.0 - 1e-9, "{a:?} vs {b:?}");
    }

    /// The photons of the benchmark fan take the fan's own in-plane path, step for step.
    #[test]
    fn fan_rays_are_traced_as_the_benchmark_traces_them() {
        let fan = crate::fan::Fan { size: 16, ..crate::fan::Fan::standard(1.0) };
        let hole = Spacetime::schwarzschild(1.0).expect("valid");
        let Spacetime::Schwarzschild(metric) = &hole else { unreachable!("a Schwarzschild hole") };
        let settings = TraceSettings { stepping: Stepping::Adaptive { rtol: 1e-8 }, ..TraceSettings::default() };
        for i in 0..fan.rays() {
            let photon =
                Photon::launch(&hole, Region::Upper, fan.camera_position(), fan.direction(i)).expect("launches");
            let t = photon.trace(&settings);
            let f = crate::fan::trace_in_plane(metric, &fan, i, &settings);
            assert_eq!((t.fate, t.steps), (f.fate, f.steps), "ray {i}");
        }
    }

    #[test]
    fn flat_space_and_positions_off_the_chart() {
        let flat = Spacetime::Minkowski(crate::Minkowski);
        let photon = Photon::launch(&flat, Region::Upper, [1.0, 2.0, 3.0], [0.0, 1.0, 0.0]).expect("launches");
        assert_eq!(photon.trace(&settings()).fate, Fate::Escaped { direction: [0.0, 1.0, 0.0] });
        assert_eq!(
            Photon::launch(&flat, Region::Lower, [1.0, 2.0, 3.0], [0.0, 1.0, 0.0]).err(),
            Some(NoLaunch::OffChart)
        );
        let wormhole = Spacetime::ellis(2.0).expect("valid");
        assert_eq!(
            Photon::launch(&wormhole, Region::Upper, [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]).err(),
            Some(NoLaunch::OffChart)
        );
    }
}

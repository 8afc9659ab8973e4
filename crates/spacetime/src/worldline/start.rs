//! A body's initial state from what the observer where it starts measures: its 3-velocity.

use crate::geodesic::State;
use crate::metric::Metric;
use crate::observer::{FrameError, Tetrad};
use crate::tensor::{contract, norm3, Vector4};

/// Why a body cannot start as asked.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum StartError {
    /// A velocity component is not finite.
    VelocityNotFinite { velocity: [f64; 3] },
    /// The speed is that of light or more.
    FasterThanLight { velocity: [f64; 3], speed: f64 },
    /// A position component is not finite.
    PositionNotFinite { x: Vector4 },
    /// No observer measures velocities there (inside a horizon, off the chart, where the
    /// metric is degenerate).
    NoObserver { x: Vector4, reason: FrameError },
    /// A given state is not that of a body of unit rest mass: `g^{μν} p_μ p_ν` is not −1.
    NotUnitTimelike { norm: f64 },
    /// A given state runs backwards in time (its energy measured by the local observer is
    /// not positive).
    PastDirected { energy: f64 },
}

impl std::fmt::Display for StartError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let v = |v: &[f64; 3]| format!("[{}, {}, {}]", v[0], v[1], v[2]);
        match self {
            StartError::VelocityNotFinite { velocity } => {
                write!(f, "velocity {} is not finite", v(velocity))
            }
            StartError::FasterThanLight { velocity, speed } => write!(
                f,
                "velocity {} has speed {speed} (units of c): a body moves slower than light, speed < 1",
                v(velocity)
            ),
            StartError::PositionNotFinite { x } => write!(f, "position {x:?} is not finite"),
            StartError::NoObserver { x, reason } => write!(
                f,
                "no observer at {x:?} measures a velocity ({reason}): the point is inside a horizon, off the \
                 chart, or where the metric is degenerate"
            ),
            StartError::NotUnitTimelike { norm } => {
                write!(f, "the momentum is not a body's of unit rest mass: g^μν p_μ p_ν = {norm}, not −1")
            }
            StartError::PastDirected { energy } => {
                write!(f, "the momentum runs backwards in time: the local observer measures energy {energy} ≤ 0")
            }
        }
    }
}

impl std::error::Error for StartError {}

/// The state `(x, p)` of a body of unit rest mass at chart point `x` moving with 3-velocity
/// `velocity` (units of c) along the axes of the local observer there: the static observer
/// where one exists, else the normal observer of the chart's time slices, whose angular
/// momentum is zero ([`Tetrad::local_observer`], the frame cameras and surfaces use). Its
/// 4-velocity is the observer's boosted by `velocity`, `u = γ(e₀ + vⁱ eᵢ)`, and `p = g u`, so
/// `g^{μν} p_μ p_ν = −1`.
pub fn start(metric: &dyn Metric, x: Vector4, velocity: [f64; 3]) -> Result<State, StartError> {
    if !velocity.iter().all(|c| c.is_finite()) {
        return Err(StartError::VelocityNotFinite { velocity });
    }
    let speed = norm3(&velocity);
    if speed >= 1.0 {
        return Err(StartError::FasterThanLight { velocity, speed });
    }
    if !x.iter().all(|c| c.is_finite()) {
        return Err(StartError::PositionNotFinite { x });
    }
    let frame = Tetrad::local_observer(metric, &x).map_err(|reason| StartError::NoObserver { x, reason })?;
    let moving = frame.boosted(velocity).map_err(|reason| StartError::NoObserver { x, reason })?;
    Ok(State { x, p: contract(&metric.metric(&x), &moving.e[0]) })
}

/// Checks that `s` is a body's state of unit rest mass running forwards in time (what
/// [`start`] and [`super::CircularOrbit::start`] give): `|g^{μν} p_μ p_ν + 1| ≤ 1e-9`, and a
/// positive energy measured by the local observer.
pub(super) fn check(metric: &dyn Metric, s: &State) -> Result<(), StartError> {
    if !s.x.iter().all(|c| c.is_finite()) {
        return Err(StartError::PositionNotFinite { x: s.x });
    }
    let norm = 2.0 * metric.hamiltonian(&s.x, &s.p);
    if !((norm + 1.0).abs() <= 1e-9) {
        return Err(StartError::NotUnitTimelike { norm });
    }
    let frame = Tetrad::local_observer(metric, &s.x).map_err(|reason| StartError::NoObserver { x: s.x, reason })?;
    let energy = -crate::tensor::dot(&s.p, &frame.e[0]);
    if !(energy > 0.0) {
        return Err(StartError::PastDirected { energy });
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::metric::{Kerr, Minkowski};

    #[test]
    fn a_body_at_rest_has_the_observers_velocity() {
        let kerr = Kerr::new(1.0, 0.9);
        let x = [0.0, 5.0, 1.0, 2.0];
        let s = start(&kerr, x, [0.0; 3]).expect("outside the ergoregion");
        let frame = Tetrad::static_observer(&kerr, &x).expect("static");
        let u = contract(&kerr.inverse_metric(&x), &s.p);
        assert!((0..4).all(|k| (u[k] - frame.e[0][k]).abs() < 1e-13), "{u:?} vs {:?}", frame.e[0]);
        assert!(check(&kerr, &s).is_ok());
    }

    #[test]
    fn light_speed_and_nan_are_refused_with_the_numbers() {
        let x = [0.0, 1.0, 0.0, 0.0];
        let fast = start(&Minkowski, x, [0.6, 0.8, 0.0]).expect_err("speed 1");
        assert!(fast.to_string().contains("speed 1 (units of c)"), "{fast}");
        let nan = start(&Minkowski, x, [0.1, f64::NAN, 0.0]).expect_err("NaN");
        assert!(nan.to_string().contains("is not finite"), "{nan}");
        let past = State { x, p: [1.0, 0.0, 0.0, 0.0] };
        assert!(matches!(check(&Minkowski, &past), Err(StartError::PastDirected { .. })));
        let light = State { x, p: [-1.0, 1.0, 0.0, 0.0] };
        assert!(matches!(check(&Minkowski, &light), Err(StartError::NotUnitTimelike { .. })));
    }
}

//! Timelike geodesics: bodies in free fall, as the physics of a world that moves.
//!
//! A body of unit rest mass follows Hamilton's equations for the same `H = ½ g^{μν} p_μ p_ν`
//! that light does, on the mass shell `H = −½` instead of `H = 0`: then `p^μ = dx^μ/dτ` is the
//! 4-velocity and the flow's parameter is the body's proper time `τ` (`docs/physics.md`,
//! "Timelike geodesics"). So the 4-D tracer integrates it unchanged
//! ([`crate::geodesic::HamiltonianTracer`], Dormand–Prince 5(4) with error control), and its
//! steps' dense output is the worldline anywhere between them.
//!
//! - [`start`]: the initial state of a body at a point moving with a 3-velocity measured by the
//!   local observer there (static where one exists), refused where that is not a body's motion.
//! - [`Chart`]: where a worldline is integrated. A hole's own chart (outgoing Kerr–Schild) is
//!   singular on the future horizon bodies fall through; the spin twin's chart
//!   ([`crate::metric::SpinTwin`]) is regular there, and events map back to the hole's chart
//!   and its coordinate time outside the horizon.
//! - [`Worldline`]: the integrated worldline and how it ended ([`End`]); events by proper time
//!   or by coordinate time of the spacetime's own chart ([`Event`]).
//! - [`CircularOrbit`]: the circular equatorial orbits of Kerr's family in closed form, prograde
//!   or retrograde, also a start for the integrator.
//! - [`carter_constant`]: Carter's constant, which with `E = −p_t` and `L_z = p_φ`
//!   ([`crate::geodesic::energy`], [`crate::geodesic::angular_momentum_z`]) a geodesic about a
//!   hole of Kerr's family keeps.

mod chart;
mod circular;
mod constants;
mod free_fall;
mod start;
mod timeline;

pub use chart::Chart;
pub use circular::{CircularOrbit, Direction, OrbitError};
pub use constants::carter_constant;
pub use free_fall::{End, Until, Worldline};
pub use start::{start, StartError};

use crate::tensor::{Covector4, Vector4};

/// One event of a body's worldline, in the spacetime's own chart.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Event {
    /// Proper time since the worldline's start.
    pub tau: f64,
    /// Chart position `x^μ` (time first).
    pub x: Vector4,
    /// 4-velocity `u^μ = dx^μ/dτ`.
    pub u: Vector4,
    /// Covariant momentum per unit rest mass `p_μ = g_{μν} u^ν` (`E = −p_t`, `L_z = p_φ`).
    pub p: Covector4,
}

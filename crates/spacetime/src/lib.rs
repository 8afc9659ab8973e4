//! # nullpath-spacetime
//!
//! Null geodesics of curved spacetimes, as a library a physicist can use on its own: metrics in
//! Hamiltonian form, local orthonormal frames of observers, integrators with error control, and the
//! fate of every ray (escaped, captured, through a throat, or failed); and the timelike geodesics
//! of bodies in free fall ([`worldline`]).
//!
//! Conventions: signature (−,+,+,+), G = c = 1, coordinates `x[0] = t`, `p` is the covariant momentum
//! `p_μ`. Rays are traced *backwards* from the camera: the traced momentum is past-directed, and the
//! photon it describes travels the other way. Nothing here knows about rendering.

#[cfg(any(test, feature = "test-answers"))]
pub mod analytic;
pub mod disk;
#[cfg(feature = "bench-workload")]
pub mod fan;
pub mod geodesic;
pub mod metric;
pub mod observer;
pub mod scattering;
pub mod tensor;
pub mod worldline;

pub use geodesic::{Fate, State, Stepping, Trace, TraceSettings, Visit};
pub use metric::{
    Dneg, Ellis, Kerr, KerrNewman, Metric, MetricFunction, Minkowski, MorrisThorne, Region, ReissnerNordstrom,
    Schwarzschild, Spacetime, UserMetric, Wormhole,
};
pub use observer::Tetrad;

//! Spacetime metrics in Hamiltonian form.
//!
//! A geodesic needs only the inverse metric and its first derivatives (`docs/physics.md`,
//! "Hamiltonian form of null geodesics"):
//! `H = ½ g^{μν} p_μ p_ν`, `dx^μ/dλ = g^{μν} p_ν`, `dp_μ/dλ = −½ ∂_μ g^{αβ} p_α p_β`.
//! Each built-in metric lives in its own file, in a chart with no coordinate poles; black holes use
//! outgoing Kerr–Schild coordinates, regular on the horizon that backward-traced rays cross.

mod builtin;
mod capabilities;
pub mod conformance;
mod descriptor;
mod ellis;
pub mod expression;
mod kerr;
pub mod kerr_newman;
mod kerr_schild;
mod minkowski;
mod morris_thorne;
mod reissner_nordstrom;
pub mod schwarzschild;
mod spin_twin;
pub(crate) mod user;
pub(crate) mod written;

pub use builtin::{Spacetime, WRITTEN_NAME};
pub use capabilities::{Capabilities, Forwards, LocalFrame, NoRest, OwnStepper, Tracers};
pub use descriptor::{
    at_most_mass, exactly, non_negative, num, parameters_of, positive, MetricDescriptor, NamedValuesError, Parameter,
    ParameterDescriptor, ParameterError, Range, CHARGE, MASS, SPIN, THROAT,
};
pub use ellis::{Ellis, ELLIS};
pub use kerr::{Kerr, KERR};
pub use kerr_newman::{KerrNewman, KERR_NEWMAN};
pub use kerr_schild::{KerrSchild, KerrSchildPoint};
pub use minkowski::{Minkowski, MINKOWSKI};
pub use morris_thorne::{Dneg, MorrisThorne, Radius, Shape, Wormhole, MIN_RELATIVE_LENSING_WIDTH, WORMHOLE};
pub use reissner_nordstrom::{ReissnerNordstrom, REISSNER_NORDSTROM};
pub use schwarzschild::{Schwarzschild, SCHWARZSCHILD};
pub use spin_twin::SpinTwin;
pub use user::{MetricFunction, Scalar, UserMetric};
pub use written::{Coordinates, WrittenMetric, LAPSE_FLOOR};

use crate::tensor::{contract, invert, quadratic, Covector4, Matrix4, Vector4};

/// The built-in metrics, in the order scene-file errors and help texts list them: a new metric is
/// its own file (its [`MetricDescriptor`]) and one line here.
pub static SPACETIMES: &[&MetricDescriptor] =
    &[&MINKOWSKI, &SCHWARZSCHILD, &KERR, &ELLIS, &REISSNER_NORDSTROM, &KERR_NEWMAN, &WORMHOLE];

/// The built-in metric named `name` in scene files.
pub fn find(name: &str) -> Option<&'static MetricDescriptor> {
    SPACETIMES.iter().copied().find(|d| d.name == name)
}

/// One of the asymptotically flat regions of a spacetime. Black holes and flat space have only
/// `Upper`; a wormhole has `Upper` (l > 0) and `Lower` (l < 0) on the two sides of its throat.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Region {
    Upper,
    Lower,
}

impl Region {
    /// The region on the other side of the throat.
    pub fn other(self) -> Region {
        match self {
            Region::Upper => Region::Lower,
            Region::Lower => Region::Upper,
        }
    }
}

/// A position and direction expressed in a region's flat world coordinates (the Cartesian frame a
/// scene is modelled in), as opposed to the chart the geodesic is integrated in.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct WorldPoint {
    pub region: Region,
    pub position: [f64; 3],
    /// Unit direction of motion along the ray.
    pub direction: [f64; 3],
}

/// A spacetime metric in one chart.
///
/// Implementors provide the metric, its inverse and the inverse's derivatives; the Hamiltonian
/// right-hand side has a default built on them that fast metrics override.
pub trait Metric: Send + Sync {
    /// Covariant components `g_{μν}(x)`.
    fn metric(&self, x: &Vector4) -> Matrix4;

    /// Contravariant components `g^{μν}(x)`.
    fn inverse_metric(&self, x: &Vector4) -> Matrix4 {
        invert(&self.metric(x)).unwrap_or([[f64::NAN; 4]; 4])
    }

    /// `g^{μν}(x)` and its partial derivatives `∂_α g^{μν}` (index α first).
    fn inverse_metric_derivatives(&self, x: &Vector4) -> (Matrix4, [Matrix4; 4]);

    /// Hamilton's equations for `H = ½ g^{μν} p_μ p_ν`: returns `(dx^μ/dλ, dp_μ/dλ)`.
    fn geodesic_rhs(&self, x: &Vector4, p: &Covector4) -> (Vector4, Covector4) {
        let (ginv, d) = self.inverse_metric_derivatives(x);
        let dx = contract(&ginv, p);
        let dp = std::array::from_fn(|a| -0.5 * quadratic(&d[a], p, p));
        (dx, dp)
    }

    /// The super-Hamiltonian `½ g^{μν} p_μ p_ν`; zero for light.
    fn hamiltonian(&self, x: &Vector4, p: &Covector4) -> f64 {
        0.5 * quadratic(&self.inverse_metric(x), p, p)
    }

    /// A length that sets the scale of curvature (mass, throat radius); 1 for flat space.
    fn length_scale(&self) -> f64;

    /// Distance-like radius from the centre in world units (areal radius where one exists), used
    /// to decide that a ray has escaped.
    fn radius(&self, x: &Vector4) -> f64 {
        crate::tensor::norm3(&crate::tensor::spatial(x))
    }

    /// Whether a ray at `x` moving with coordinate velocity `dx` is moving away from the centre.
    fn is_outgoing(&self, x: &Vector4, dx: &Vector4) -> bool {
        x[1] * dx[1] + x[2] * dx[2] + x[3] * dx[3] > 0.0
    }

    /// True inside an event horizon: a ray that gets there is captured.
    fn inside_horizon(&self, _x: &Vector4) -> bool {
        false
    }

    /// Whether a ray whose integration collapses (error control asks for a step too small to make
    /// progress, or the state stops being finite) has met a horizon or singularity and is
    /// captured, rather than failed. Built-in metrics know their horizons and answer no: a
    /// collapse there is a numerical failure. A metric written by a user may have horizons its
    /// chart does not reach (Schwarzschild's coordinates end at `r = 2M`, where `g_rr` is
    /// infinite) or singularities anywhere; they show themselves to the integrator only as a
    /// collapsing step.
    fn collapse_captures(&self) -> bool {
        false
    }

    /// Which asymptotic region `x` belongs to.
    fn region(&self, _x: &Vector4) -> Region {
        Region::Upper
    }

    /// Maps a chart position and coordinate velocity to world coordinates. The default is the
    /// identity on the spatial part, right for Cartesian charts.
    fn to_world(&self, x: &Vector4, dx: &Vector4) -> WorldPoint {
        let d = crate::tensor::spatial(dx);
        WorldPoint {
            region: self.region(x),
            position: crate::tensor::spatial(x),
            direction: crate::tensor::normalize3(&d),
        }
    }

    /// Inverse of [`Metric::to_world`] for positions: the chart point at world position `p` of
    /// `region` at coordinate time `t`; `None` where the chart does not reach (inside a throat).
    fn world_to_chart(&self, region: Region, p: [f64; 3], t: f64) -> Option<Vector4> {
        (region == Region::Upper).then_some([t, p[0], p[1], p[2]])
    }

    /// Whether `∂_t` is a Killing vector (then `p_t` is conserved).
    fn is_stationary(&self) -> bool {
        true
    }

    /// Whether rotation about the z axis is a symmetry (then `p_φ = x p_y − y p_x` is conserved).
    fn is_axisymmetric(&self) -> bool {
        true
    }
}

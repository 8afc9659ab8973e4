//! Spacetime metrics in Hamiltonian form.
//!
//! A geodesic needs only the inverse metric and its first derivatives (physics notes):
//! `H = ½ g^{μν} p_μ p_ν`, `dx^μ/dλ = g^{μν} p_ν`, `dp_μ/dλ = −½ ∂_μ g^{αβ} p_α p_β`.
//! Each built-in metric lives in its own file, in a chart with no coordinate poles; black holes use
//! outgoing Kerr–Schild coordinates, regular on the horizon that backward-traced rays cross.

mod builtin;
mod ellis;
mod kerr;
mod kerr_schild;
mod minkowski;
mod schwarzschild;
pub(crate) mod user;

pub use builtin::{ParameterError, Spacetime};
pub use ellis::Ellis;
pub use kerr::Kerr;
pub use kerr_schild::{KerrSchild, KerrSchildPoint};
pub use minkowski::Minkowski;
pub use schwarzschild::Schwarzschild;
pub use user::{MetricFunction, Scalar, UserMetric};

use crate::tensor::{contract, invert, quadratic, Covector4, Matrix4, Vector4};

/// One of the asymptotically flat regions of a spacetime. Black holes and flat space have only
/// `Upper`; a wormhole has `Upper` (l > 0) and `Lower` (l < 0) on the two sides of its throat.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Region {
    Upper,
    Lower,
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

#[cfg(test)]
pub(crate) mod conformance {
    //! Checks every metric must pass, run by each metric's tests.
    use super::*;
    use crate::tensor::ETA;

    /// `g · g⁻¹ = I` and the derivatives of `g^{μν}` agree with central finite differences.
    pub fn check_metric(m: &dyn Metric, x: &Vector4) {
        let g = m.metric(x);
        let (ginv, d) = m.inverse_metric_derivatives(x);
        let ginv_plain = m.inverse_metric(x);
        for i in 0..4 {
            for j in 0..4 {
                let id: f64 = (0..4).map(|k| g[i][k] * ginv[k][j]).sum();
                let expect = if i == j { 1.0 } else { 0.0 };
                assert!((id - expect).abs() < 1e-12, "g·g⁻¹ at {x:?}: [{i}][{j}] = {id}");
                assert!((ginv[i][j] - ginv_plain[i][j]).abs() < 1e-12 * (1.0 + ginv[i][j].abs()));
                assert!((g[i][j] - g[j][i]).abs() < 1e-14, "metric symmetric");
            }
        }
        let h = 1e-5 * m.length_scale().max(crate::tensor::norm3(&crate::tensor::spatial(x)));
        for a in 0..4 {
            let mut xp = *x;
            let mut xm = *x;
            xp[a] += h;
            xm[a] -= h;
            let (gp, _) = m.inverse_metric_derivatives(&xp);
            let (gm, _) = m.inverse_metric_derivatives(&xm);
            for i in 0..4 {
                for j in 0..4 {
                    let fd = (gp[i][j] - gm[i][j]) / (2.0 * h);
                    let scale = 1.0 + fd.abs() + d[a][i][j].abs();
                    assert!((fd - d[a][i][j]).abs() < 1e-6 * scale, "∂_{a} g^{i}{j}: fd {fd} vs {}", d[a][i][j]);
                }
            }
        }
        // The RHS default and any override agree.
        let p = [-1.0, 0.3, -0.2, 0.5];
        let (dx, dp) = m.geodesic_rhs(x, &p);
        let dx_ref = contract(&ginv, &p);
        for k in 0..4 {
            assert!((dx[k] - dx_ref[k]).abs() < 1e-12 * (1.0 + dx_ref[k].abs()));
            let dp_ref = -0.5 * quadratic(&d[k], &p, &p);
            assert!((dp[k] - dp_ref).abs() < 1e-11 * (1.0 + dp_ref.abs()), "dp_{k}: {} vs {dp_ref}", dp[k]);
        }
        let _ = ETA;
    }
}

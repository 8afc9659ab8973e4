//! Shared algebra of metrics in Kerr–Schild form, `g_{μν} = η_{μν} + f l_μ l_ν` with `l` null for
//! both η and g, whose inverse is exactly `g^{μν} = η^{μν} − f l^μ l^ν` (Kerr & Schild 1965).
//!
//! The metrics here are stationary, so only spatial derivatives appear. `l_μ = (1, −k_i)` in
//! outgoing form: past-directed rays cross the (past) horizon smoothly, which is what backward
//! tracing needs.

use super::Metric;
use crate::tensor::{Covector4, Matrix4, Vector4, ETA};

/// The data of one Kerr–Schild metric at one point: `f`, the spatial unit vector `k` with
/// `l_μ = (1, −k)`, and their spatial derivatives `df[i] = ∂_i f`, `dk[i][j] = ∂_i k_j`.
pub struct KerrSchildPoint {
    pub f: f64,
    pub k: [f64; 3],
    pub df: [f64; 3],
    pub dk: [[f64; 3]; 3],
}

impl KerrSchildPoint {
    /// Covariant null vector `l_μ`.
    fn l_lower(&self) -> Covector4 {
        [1.0, -self.k[0], -self.k[1], -self.k[2]]
    }

    /// Contravariant `l^μ = η^{μν} l_ν`.
    fn l_upper(&self) -> Vector4 {
        [-1.0, -self.k[0], -self.k[1], -self.k[2]]
    }

    pub fn metric(&self) -> Matrix4 {
        let l = self.l_lower();
        std::array::from_fn(|i| std::array::from_fn(|j| ETA[i][j] + self.f * l[i] * l[j]))
    }

    pub fn inverse_metric(&self) -> Matrix4 {
        let l = self.l_upper();
        std::array::from_fn(|i| std::array::from_fn(|j| ETA[i][j] - self.f * l[i] * l[j]))
    }

    /// `∂_α g^{μν} = −∂_α f l^μ l^ν − f (∂_α l^μ l^ν + l^μ ∂_α l^ν)`.
    pub fn inverse_metric_derivatives(&self) -> [Matrix4; 4] {
        let l = self.l_upper();
        let mut d = [[[0.0; 4]; 4]; 4];
        for ((da, dk), df) in d.iter_mut().skip(1).zip(&self.dk).zip(&self.df) {
            let dl: Vector4 = [0.0, -dk[0], -dk[1], -dk[2]];
            for (i, row) in da.iter_mut().enumerate() {
                for (j, v) in row.iter_mut().enumerate() {
                    *v = -df * l[i] * l[j] - self.f * (dl[i] * l[j] + l[i] * dl[j]);
                }
            }
        }
        d
    }

    /// Hamilton's equations ([`hamilton_rhs`]).
    #[inline]
    pub fn geodesic_rhs(&self, p: &Covector4) -> (Vector4, Covector4) {
        let dq = std::array::from_fn(|i| -(self.dk[i][0] * p[1] + self.dk[i][1] * p[2] + self.dk[i][2] * p[3]));
        hamilton_rhs(self.f, &self.k, &self.df, &dq, p)
    }

    pub fn hamiltonian(&self, p: &Covector4) -> f64 {
        let q = -p[0] - (self.k[0] * p[1] + self.k[1] * p[2] + self.k[2] * p[3]);
        0.5 * (-p[0] * p[0] + p[1] * p[1] + p[2] * p[2] + p[3] * p[3]) - 0.5 * self.f * q * q
    }
}

/// Hamilton's equations in closed form from `f`, `k`, `∂_i f` and `∂_i q`: with `q = l^μ p_μ`,
/// `H = ½ η^{μν} p_μ p_ν − ½ f q²`, so `dx^μ = η^{μν} p_ν − f q l^μ` (`l^μ = (−1, −k)`) and
/// `dp_i = ½ ∂_i f q² + f q ∂_i q`, `∂_i q = −∂_i k_j p_j`; `dp_t = 0`.
#[inline]
pub(super) fn hamilton_rhs(f: f64, k: &[f64; 3], df: &[f64; 3], dq: &[f64; 3], p: &Covector4) -> (Vector4, Covector4) {
    let q = -p[0] - (k[0] * p[1] + k[1] * p[2] + k[2] * p[3]);
    let fq = f * q;
    let dx = [-p[0] + fq, p[1] + fq * k[0], p[2] + fq * k[1], p[3] + fq * k[2]];
    let half_q2 = 0.5 * q * q;
    let dp = [0.0, half_q2 * df[0] + fq * dq[0], half_q2 * df[1] + fq * dq[1], half_q2 * df[2] + fq * dq[2]];
    (dx, dp)
}

/// A stationary metric in Kerr–Schild form. Everything [`Metric`] asks for follows from the
/// fields at a point, the mass and the horizon, so the metrics only provide those.
pub trait KerrSchild: Send + Sync {
    /// `f`, `k` and their derivatives at `x`.
    fn fields(&self, x: &Vector4) -> KerrSchildPoint;
    /// Hamilton's equations at `x` ([`KerrSchildPoint::geodesic_rhs`]); a metric whose `∂_i k_j`
    /// contract with the momentum in closed form may skip forming them.
    #[inline]
    fn hamilton(&self, x: &Vector4, p: &Covector4) -> (Vector4, Covector4) {
        self.fields(x).geodesic_rhs(p)
    }
    fn mass(&self) -> f64;
    /// The radial coordinate of the metric (areal for Schwarzschild, spheroidal for Kerr).
    fn radial_coordinate(&self, x: &Vector4) -> f64;
    /// Radius of the (outer) event horizon in that coordinate.
    fn horizon_radius(&self) -> f64;
}

impl<T: KerrSchild> Metric for T {
    fn metric(&self, x: &Vector4) -> Matrix4 {
        self.fields(x).metric()
    }

    fn inverse_metric(&self, x: &Vector4) -> Matrix4 {
        self.fields(x).inverse_metric()
    }

    fn inverse_metric_derivatives(&self, x: &Vector4) -> (Matrix4, [Matrix4; 4]) {
        let pt = self.fields(x);
        (pt.inverse_metric(), pt.inverse_metric_derivatives())
    }

    #[inline]
    fn geodesic_rhs(&self, x: &Vector4, p: &Covector4) -> (Vector4, Covector4) {
        self.hamilton(x, p)
    }

    fn hamiltonian(&self, x: &Vector4, p: &Covector4) -> f64 {
        self.fields(x).hamiltonian(p)
    }

    fn length_scale(&self) -> f64 {
        self.mass().max(f64::MIN_POSITIVE)
    }

    fn radius(&self, x: &Vector4) -> f64 {
        self.radial_coordinate(x)
    }

    fn inside_horizon(&self, x: &Vector4) -> bool {
        self.radial_coordinate(x) <= self.horizon_radius()
    }
}

//! A spacetime given only by its metric `g_{μν}(x)`: derivatives come from forward-mode automatic
//! differentiation (dual numbers), so a user writes one generic function and nothing else.
//!
//! ```
//! use spacetime::metric::{MetricFunction, UserMetric};
//! use spacetime::metric::Scalar;
//!
//! /// Flat space in Cartesian coordinates, written by hand.
//! struct Flat;
//! impl MetricFunction for Flat {
//!     fn metric<D: Scalar>(&self, _x: [D; 4]) -> [[D; 4]; 4] {
//!         let (z, o) = (D::from(0.0), D::from(1.0));
//!         [[-o, z, z, z], [z, o, z, z], [z, z, o, z], [z, z, z, o]]
//!     }
//! }
//! let spacetime = UserMetric(Flat);
//! ```

use super::Metric;
use crate::tensor::{contract, invert, quadratic, Covector4, Matrix4, Vector4};
use num_dual::{DualNum, DualSVec64};

/// The scalar a [`MetricFunction`] is written over: `f64` or a dual number carrying derivatives.
pub trait Scalar: DualNum<Primitive = f64> + Copy {}
impl<D: DualNum<Primitive = f64> + Copy> Scalar for D {}

/// What a user writes for a new spacetime: `g_{μν}(x)` generic over the scalar type, plus the
/// few facts about it the tracer needs.
pub trait MetricFunction: Send + Sync {
    /// Covariant metric components at `x`, symmetric.
    fn metric<D: Scalar>(&self, x: [D; 4]) -> [[D; 4]; 4];

    /// Length scale of the curvature (a mass, a throat radius).
    fn length_scale(&self) -> f64 {
        1.0
    }

    /// True inside an event horizon, where rays are captured.
    fn inside_horizon(&self, _x: &Vector4) -> bool {
        false
    }

    /// Whether a ray whose integration collapses is captured ([`Metric::collapse_captures`]).
    fn collapse_captures(&self) -> bool {
        false
    }

    /// Whether `g` is independent of `t`.
    fn is_stationary(&self) -> bool {
        false
    }

    /// Whether `g` is invariant under rotation about the z axis.
    fn is_axisymmetric(&self) -> bool {
        false
    }
}

/// A [`Metric`] from a [`MetricFunction`], with exact derivatives by automatic differentiation.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct UserMetric<F>(pub F);

impl<F: MetricFunction> UserMetric<F> {
    /// `g_{μν}` and `∂_α g_{μν}` in one dual-number evaluation.
    fn metric_with_derivatives(&self, x: &Vector4) -> (Matrix4, [Matrix4; 4]) {
        let xd: [DualSVec64<4>; 4] = std::array::from_fn(|i| DualSVec64::from_re(x[i]).derivative(i));
        let g = self.0.metric(xd);
        let value = std::array::from_fn(|i| std::array::from_fn(|j| g[i][j].re));
        let grads: [[nalgebra::SVector<f64, 4>; 4]; 4] = std::array::from_fn(|i| {
            std::array::from_fn(|j| g[i][j].eps.unwrap_generic(nalgebra::Const::<4>, nalgebra::U1))
        });
        let d = std::array::from_fn(|a| std::array::from_fn(|i| std::array::from_fn(|j| grads[i][j][a])));
        (value, d)
    }
}

impl<F: MetricFunction> Metric for UserMetric<F> {
    fn metric(&self, x: &Vector4) -> Matrix4 {
        self.0.metric(*x)
    }

    /// `∂_α g^{μν} = −g^{μκ} (∂_α g_{κλ}) g^{λν}`.
    fn inverse_metric_derivatives(&self, x: &Vector4) -> (Matrix4, [Matrix4; 4]) {
        let (g, dg) = self.metric_with_derivatives(x);
        let ginv = invert(&g).unwrap_or([[f64::NAN; 4]; 4]);
        let d = std::array::from_fn(|a| {
            std::array::from_fn(|m| {
                std::array::from_fn(|n| {
                    let mut s = 0.0;
                    for k in 0..4 {
                        for l in 0..4 {
                            s -= ginv[m][k] * dg[a][k][l] * ginv[l][n];
                        }
                    }
                    s
                })
            })
        });
        (ginv, d)
    }

    /// `dx^μ = g^{μν} p_ν` and, as `∂_α g^{μν} = −g^{μκ} (∂_α g_{κλ}) g^{λν}`,
    /// `dp_α = −½ ∂_α g^{μν} p_μ p_ν = ½ (∂_α g_{κλ}) dx^κ dx^λ`: the derivatives of the metric
    /// itself suffice, 64 products where those of the inverse take a thousand.
    fn geodesic_rhs(&self, x: &Vector4, p: &Covector4) -> (Vector4, Covector4) {
        let (g, dg) = self.metric_with_derivatives(x);
        let ginv = invert(&g).unwrap_or([[f64::NAN; 4]; 4]);
        let dx = contract(&ginv, p);
        let dp = std::array::from_fn(|a| 0.5 * quadratic(&dg[a], &dx, &dx));
        (dx, dp)
    }

    fn length_scale(&self) -> f64 {
        self.0.length_scale()
    }

    fn inside_horizon(&self, x: &Vector4) -> bool {
        self.0.inside_horizon(x)
    }

    fn collapse_captures(&self) -> bool {
        self.0.collapse_captures()
    }

    fn is_stationary(&self) -> bool {
        self.0.is_stationary()
    }

    fn is_axisymmetric(&self) -> bool {
        self.0.is_axisymmetric()
    }
}

#[cfg(test)]
pub(crate) mod tests {
    use super::*;
    use crate::metric::Schwarzschild;

    /// Outgoing Kerr–Schild Schwarzschild written the way a user would: only `g_{μν}`.
    pub struct UserSchwarzschild {
        pub mass: f64,
    }

    impl MetricFunction for UserSchwarzschild {
        fn metric<D: Scalar>(&self, x: [D; 4]) -> [[D; 4]; 4] {
            let r = (x[1] * x[1] + x[2] * x[2] + x[3] * x[3]).sqrt();
            let f = r.recip() * (2.0 * self.mass);
            let l = [D::from(1.0), -x[1] / r, -x[2] / r, -x[3] / r];
            std::array::from_fn(|i| {
                std::array::from_fn(|j| {
                    let eta = if i != j {
                        0.0
                    } else if i == 0 {
                        -1.0
                    } else {
                        1.0
                    };
                    f * l[i] * l[j] + eta
                })
            })
        }

        fn length_scale(&self) -> f64 {
            self.mass
        }

        fn inside_horizon(&self, x: &Vector4) -> bool {
            (x[1] * x[1] + x[2] * x[2] + x[3] * x[3]).sqrt() <= 2.0 * self.mass
        }

        fn is_stationary(&self) -> bool {
            true
        }

        fn is_axisymmetric(&self) -> bool {
            true
        }
    }

    #[test]
    fn automatic_derivatives_reproduce_hand_written_schwarzschild() {
        let user = UserMetric(UserSchwarzschild { mass: 1.2 });
        let hand = Schwarzschild::new(1.2);
        for x in [[0.0, 7.0, 1.0, -2.0], [1.0, -2.0, 0.5, 1.5], [0.0, 0.0, 0.0, 30.0]] {
            let (a, da) = user.inverse_metric_derivatives(&x);
            let (b, db) = hand.inverse_metric_derivatives(&x);
            for i in 0..4 {
                for j in 0..4 {
                    assert!((a[i][j] - b[i][j]).abs() < 1e-13, "g^{i}{j}");
                    for k in 0..4 {
                        assert!((da[k][i][j] - db[k][i][j]).abs() < 1e-13, "∂_{k} g^{i}{j}");
                    }
                }
            }
            crate::metric::conformance::check_metric(&user, &x);
        }
    }
}

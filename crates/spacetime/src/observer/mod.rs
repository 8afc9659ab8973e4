//! Observers and their local orthonormal frames (tetrads), and the conversion between what an
//! observer measures (a direction and an energy) and a null covariant momentum.
//!
//! Cameras, surfaces and lights all live in such frames (`docs/physics.md`, "Local frames and the
//! time orientation of backward rays").

use crate::metric::Metric;
use crate::tensor::{contract, quadratic, Covector4, Matrix4, Vector4};

mod inverse_square_root;

/// Orthonormal frame `e_(a)^μ` at one event: `e[0]` is the observer's 4-velocity, `e[1..4]` its
/// spatial axes, right-handed. Components are contravariant, in the metric's chart.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Tetrad {
    pub e: [Vector4; 4],
}

/// Why no frame could be built.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum FrameError {
    /// The requested observer's worldline would not be timelike here (a static observer inside
    /// an ergosphere or horizon, a speed ≥ c).
    NotTimelike,
    /// The metric is degenerate or not finite here.
    Degenerate,
}

impl std::fmt::Display for FrameError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            FrameError::NotTimelike => write!(f, "no timelike observer of that kind exists here"),
            FrameError::Degenerate => write!(f, "the metric is degenerate here"),
        }
    }
}

impl std::error::Error for FrameError {}

impl Tetrad {
    /// Frame of the observer with 4-velocity `u` (any positive multiple; normalised here). Its
    /// spatial axes are the coordinate axes projected orthogonal to `u` and orthonormalised
    /// symmetrically (Löwdin 1950), so the frame depends on no axis order and follows the chart's
    /// x, y, z as closely as the metric allows.
    pub fn with_velocity(metric: &dyn Metric, x: &Vector4, u: Vector4) -> Result<Tetrad, FrameError> {
        let g = metric.metric(x);
        if !g.iter().flatten().all(|v| v.is_finite()) {
            return Err(FrameError::Degenerate);
        }
        let norm2 = quadratic(&g, &u, &u);
        if !norm2.is_finite() || norm2 >= 0.0 {
            return Err(FrameError::NotTimelike);
        }
        let u = u.map(|c| c / (-norm2).sqrt());
        let project = |v: Vector4| {
            let c = quadratic(&g, &v, &u);
            std::array::from_fn::<f64, 4, _>(|k| v[k] + c * u[k])
        };
        let axes: [Vector4; 3] = std::array::from_fn(|i| {
            let mut v = [0.0; 4];
            v[i + 1] = 1.0;
            project(v)
        });
        let s = nalgebra::Matrix3::from_fn(|i, j| quadratic(&g, &axes[i], &axes[j]));
        let inv_sqrt = inverse_square_root::inverse_square_root(&s).ok_or(FrameError::Degenerate)?;
        let spatial: [Vector4; 3] =
            std::array::from_fn(|i| std::array::from_fn(|k| (0..3).map(|j| inv_sqrt[(i, j)] * axes[j][k]).sum()));
        Ok(Tetrad { e: [u, spatial[0], spatial[1], spatial[2]] })
    }

    /// The static observer, at rest in the chart (`u ∝ ∂_t`). Exists where `∂_t` is timelike:
    /// outside horizons, and outside the ergosphere of a spinning hole.
    pub fn static_observer(metric: &dyn Metric, x: &Vector4) -> Result<Tetrad, FrameError> {
        Self::with_velocity(metric, x, [1.0, 0.0, 0.0, 0.0])
    }

    /// The normal (Eulerian) observer of the chart's `t = const` slices, `u^μ ∝ −g^{μt}`. In
    /// Kerr–Schild charts it exists everywhere, the horizon and ergosphere included.
    pub fn normal_observer(metric: &dyn Metric, x: &Vector4) -> Result<Tetrad, FrameError> {
        let ginv = metric.inverse_metric(x);
        Self::with_velocity(metric, x, [-ginv[0][0], -ginv[1][0], -ginv[2][0], -ginv[3][0]])
    }

    /// The static observer where one exists, else the normal observer: the frame nullpath uses
    /// for cameras and surfaces unless told otherwise.
    pub fn local_observer(metric: &dyn Metric, x: &Vector4) -> Result<Tetrad, FrameError> {
        Self::static_observer(metric, x).or_else(|_| Self::normal_observer(metric, x))
    }

    /// The frame of an observer moving with 3-velocity `v` (units of c, `|v| < 1`) as measured in
    /// this frame: a pure Lorentz boost, so aberration and Doppler shift follow.
    pub fn boosted(&self, v: [f64; 3]) -> Result<Tetrad, FrameError> {
        let v2 = v[0] * v[0] + v[1] * v[1] + v[2] * v[2];
        if v2.is_nan() || v2 >= 1.0 {
            return Err(FrameError::NotTimelike);
        }
        let gamma = 1.0 / (1.0 - v2).sqrt();
        let k = if v2 > 0.0 { (gamma - 1.0) / v2 } else { 0.0 };
        let e = &self.e;
        let comb = |c: [f64; 4]| -> Vector4 { std::array::from_fn(|m| (0..4).map(|a| c[a] * e[a][m]).sum()) };
        let u = comb([gamma, gamma * v[0], gamma * v[1], gamma * v[2]]);
        let axis = |j: usize| {
            let mut c = [gamma * v[j], 0.0, 0.0, 0.0];
            for i in 0..3 {
                c[i + 1] = if i == j { 1.0 } else { 0.0 } + k * v[i] * v[j];
            }
            comb(c)
        };
        Ok(Tetrad { e: [u, axis(0), axis(1), axis(2)] })
    }

    /// Covariant momentum of a backward-traced ray that leaves this observer along unit direction
    /// `n` (frame components) with energy `energy`: `p = E(−e_(0) + nⁱ e_(i))`, lowered with `g`.
    /// The photon it describes arrives at the observer travelling along `−n`.
    pub fn backward_momentum(&self, g: &Matrix4, n: [f64; 3], energy: f64) -> Covector4 {
        let v: Vector4 = std::array::from_fn(|m| {
            energy * (-self.e[0][m] + n[0] * self.e[1][m] + n[1] * self.e[2][m] + n[2] * self.e[3][m])
        });
        contract(g, &v)
    }

    /// Inverse of [`Tetrad::backward_momentum`]: the direction `n` and energy `E` this observer
    /// measures for a backward-traced momentum, `E = p_μ e_(0)^μ`, `nⁱ = p_μ e_(i)^μ / E`.
    pub fn backward_direction(&self, p: &Covector4) -> ([f64; 3], f64) {
        let dot = |v: &Vector4| p[0] * v[0] + p[1] * v[1] + p[2] * v[2] + p[3] * v[3];
        let energy = dot(&self.e[0]);
        let n = [dot(&self.e[1]) / energy, dot(&self.e[2]) / energy, dot(&self.e[3]) / energy];
        (n, energy)
    }

    /// Proper area, measured in this frame, per unit chart area of a surface element at rest in
    /// the chart with unit normal `n` (chart components of its gradient covector). The frame maps
    /// a chart displacement `dx` at fixed `t` to its spatial components `J dx`,
    /// `J_{ai} = g(e_(a), ∂_i)`, so by Nanson's formula `da = |det J| · |J⁻ᵀ n| dA`.
    pub fn area_scale(&self, g: &Matrix4, n: [f64; 3]) -> f64 {
        let j = nalgebra::Matrix3::from_fn(|a, i| (0..4).map(|m| g[m][i + 1] * self.e[a + 1][m]).sum::<f64>());
        let Some(inverse) = j.try_inverse() else { return f64::NAN };
        j.determinant().abs() * (inverse.transpose() * nalgebra::Vector3::from(n)).norm()
    }

    /// The 3-velocity (units of c) this observer measures for a body moving with 4-velocity `u`
    /// (any positive multiple): `vⁱ = g(u, e_(i)) / (−g(u, e_(0)))`, the spatial frame
    /// components of `u` over its time component.
    pub fn measured_velocity(&self, g: &Matrix4, u: &Vector4) -> [f64; 3] {
        let time = -quadratic(g, u, &self.e[0]);
        std::array::from_fn(|i| quadratic(g, u, &self.e[i + 1]) / time)
    }

    /// Largest deviation of `g(e_a, e_b)` from `η_ab`.
    pub fn orthonormality_error(&self, g: &Matrix4) -> f64 {
        let mut worst: f64 = 0.0;
        for a in 0..4 {
            for b in 0..4 {
                let eta = if a != b {
                    0.0
                } else if a == 0 {
                    -1.0
                } else {
                    1.0
                };
                worst = worst.max((quadratic(g, &self.e[a], &self.e[b]) - eta).abs());
            }
        }
        worst
    }

    /// Orientation of the spatial triad: `+1` right-handed with respect to the chart's x, y, z.
    pub fn handedness(&self) -> f64 {
        let m = nalgebra::Matrix3::from_fn(|i, j| self.e[i + 1][j + 1]);
        m.determinant().signum()
    }
}

/// The 3-velocity, in units of c, that the local observer (static where one exists) at world
/// position `p` of `region` measures for a body whose world coordinates change at the rate
/// `dp_dt` per unit coordinate time. Components are along the observer's axes as the renderer
/// aligns them with the world's. `None` where the chart does not reach `p`; an error where that
/// motion is not timelike (as fast as light or faster, as the local observer sees it).
pub fn local_velocity(
    metric: &dyn Metric,
    region: crate::Region,
    p: [f64; 3],
    dp_dt: [f64; 3],
) -> Option<Result<[f64; 3], FrameError>> {
    let x = metric.world_to_chart(region, p, 0.0)?;
    let Some(jacobian) = world_to_chart_jacobian(metric, region, p) else {
        return Some(Err(FrameError::Degenerate));
    };
    let v = jacobian * nalgebra::Vector3::from(dp_dt);
    let u: Vector4 = [1.0, v[0], v[1], v[2]];
    let g = metric.metric(&x);
    if !(quadratic(&g, &u, &u) < 0.0) {
        return Some(Err(FrameError::NotTimelike));
    }
    // The frame's axes follow the chart's; the world-aligned axes are their images under the
    // rotation (or reflection) part of the chart map, `R` of its polar decomposition `J = R S`:
    // the identity for Cartesian charts, and a reflection of the tangential directions in a
    // wormhole's lower region, whose chart is an inversion of the world's coordinates.
    let svd = jacobian.svd(true, true);
    let (Some(left), Some(right)) = (svd.u, svd.v_t) else {
        return Some(Err(FrameError::Degenerate));
    };
    let to_world = (left * right).transpose();
    Some(Tetrad::local_observer(metric, &x).map(|frame| {
        let chart_aligned = nalgebra::Vector3::from(frame.measured_velocity(&g, &u));
        (to_world * chart_aligned).into()
    }))
}

/// `∂x^i/∂p^j` of [`Metric::world_to_chart`] by central differences with a step of 1e-6 of the
/// radius (relative error ~1e-10, from rounding; the maps are smooth where the chart reaches).
fn world_to_chart_jacobian(metric: &dyn Metric, region: crate::Region, p: [f64; 3]) -> Option<nalgebra::Matrix3<f64>> {
    let h = 1e-6 * crate::tensor::norm3(&p).max(metric.length_scale());
    let at = |j: usize, sign: f64| {
        let mut q = p;
        q[j] += sign * h;
        metric.world_to_chart(region, q, 0.0)
    };
    let mut jacobian = nalgebra::Matrix3::zeros();
    for j in 0..3 {
        let (ahead, behind) = (at(j, 1.0)?, at(j, -1.0)?);
        for i in 0..3 {
            jacobian[(i, j)] = (ahead[i + 1] - behind[i + 1]) / (2.0 * h);
        }
    }
    Some(jacobian)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::metric::{Ellis, Kerr, Minkowski, Schwarzschild};
    use proptest::prelude::*;

    fn metrics() -> Vec<Box<dyn Metric>> {
        vec![
            Box::new(Minkowski),
            Box::new(Schwarzschild::new(1.0)),
            Box::new(Kerr::new(1.0, 0.9)),
            Box::new(Kerr::new(1.0, -0.5)),
            Box::new(Ellis::new(1.0)),
            Box::new(crate::metric::UserMetric(crate::metric::user::tests::UserSchwarzschild { mass: 1.0 })),
        ]
    }

    fn unit(theta: f64, phi: f64) -> [f64; 3] {
        [theta.sin() * phi.cos(), theta.sin() * phi.sin(), theta.cos()]
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(256))]

        /// Every metric, random places outside horizons, random boosts and directions: the frame
        /// is orthonormal and right-handed, a direction survives the trip to a momentum and
        /// back, and the momentum is null.
        #[test]
        fn frames_and_momenta(r in 3.5f64..80.0, theta in 0.0f64..std::f64::consts::PI, phi in 0.0f64..6.3,
                              dt in 0.0f64..3.2, dp in 0.0f64..6.3, speed in 0.0f64..0.95,
                              vt in 0.0f64..3.2, vp in 0.0f64..6.3, energy in 0.1f64..10.0) {
            for m in metrics() {
                let pos = unit(theta, phi);
                let x = [0.7, r * pos[0], r * pos[1], r * pos[2]];
                let g = m.metric(&x);
                let base = Tetrad::local_observer(m.as_ref(), &x).unwrap();
                let v = unit(vt, vp).map(|c| c * speed);
                for frame in [base, base.boosted(v).unwrap()] {
                    prop_assert!(frame.orthonormality_error(&g) < 1e-11, "orthonormality {}", frame.orthonormality_error(&g));
                    prop_assert!(frame.handedness() > 0.0);
                    let n = unit(dt, dp);
                    let p = frame.backward_momentum(&g, n, energy);
                    let h = m.hamiltonian(&x, &p);
                    prop_assert!(h.abs() < 1e-11 * energy * energy, "H = {h}");
                    let (n2, e2) = frame.backward_direction(&p);
                    prop_assert!((e2 - energy).abs() < 1e-11 * energy);
                    for k in 0..3 {
                        prop_assert!((n2[k] - n[k]).abs() < 1e-11);
                    }
                }
            }
        }
    }

    #[test]
    fn local_velocity_of_world_motion() {
        use crate::Region::{Lower, Upper};
        let v = |m: &dyn Metric, region, p, dp| local_velocity(m, region, p, dp).unwrap().unwrap();
        // Flat space: the world velocity itself.
        let flat = v(&Minkowski, Upper, [1.0, 2.0, 3.0], [0.1, -0.2, 0.3]);
        assert!((0..3).all(|i| (flat[i] - [0.1, -0.2, 0.3][i]).abs() < 1e-9));
        // A circular Schwarzschild geodesic, Ω = √(M/r³), is seen by static observers at
        // v = √(M/(r − 2M)) (Kerr–Schild and Schwarzschild time differ by a function of r).
        let (m, r) = (1.0f64, 7.0f64);
        let omega = (m / (r * r * r)).sqrt();
        let orbit = v(&Schwarzschild::new(m), Upper, [r, 0.0, 0.0], [0.0, 0.0, -r * omega]);
        assert!((orbit[2] + (m / (r - 2.0 * m)).sqrt()).abs() < 1e-9, "{orbit:?}");
        assert!(orbit[0].abs() < 1e-12 && orbit[1].abs() < 1e-12);
        // Ellis: world radius ρ = √(l² + b₀²) is areal, so tangential speed is ρ dφ/dt and radial
        // proper speed dl/dt = (ρ/l) dρ/dt; the lower region's world axes are mirrored.
        let ellis = Ellis::new(1.0);
        for region in [Upper, Lower] {
            let tangential = v(&ellis, region, [0.0, 2.0, 0.0], [0.3, 0.0, 0.0]);
            assert!((tangential[0] - 0.3).abs() < 1e-9, "{region:?} {tangential:?}");
            let radial = v(&ellis, region, [0.0, 2.0, 0.0], [0.0, 0.1, 0.0]);
            assert!((radial[1] - 0.1 * 2.0 / 3f64.sqrt()).abs() < 1e-9, "{region:?} {radial:?}");
        }
        // As fast as light, or outside the chart.
        assert_eq!(local_velocity(&Minkowski, Upper, [0.0; 3], [1.0, 0.0, 0.0]), Some(Err(FrameError::NotTimelike)));
        assert_eq!(local_velocity(&ellis, Upper, [0.0, 0.5, 0.0], [0.1, 0.0, 0.0]), None);
    }

    #[test]
    fn static_observer_fails_in_the_ergosphere_but_normal_observer_exists() {
        let kerr = Kerr::new(1.0, 0.9);
        // On the equator just outside the horizon (r₊ ≈ 1.44) but inside the ergosphere (r = 2).
        let x = [0.0, 1.6, 0.0, 0.0];
        assert_eq!(Tetrad::static_observer(&kerr, &x), Err(FrameError::NotTimelike));
        let n = Tetrad::normal_observer(&kerr, &x).unwrap();
        assert!(n.orthonormality_error(&kerr.metric(&x)) < 1e-12);
    }

    #[test]
    fn boost_at_speed_of_light_is_an_error() {
        let t = Tetrad::static_observer(&Minkowski, &[0.0; 4]).unwrap();
        assert!(t.boosted([1.0, 0.0, 0.0]).is_err());
        assert!(t.boosted([0.6, 0.8, 0.0]).is_err());
    }

    #[test]
    fn boosted_observer_sees_aberration() {
        // Flat space: an observer moving at v along +x sees a source at 90° in the rest frame
        // at cos θ' = v (light aberration).
        let rest = Tetrad::static_observer(&Minkowski, &[0.0; 4]).unwrap();
        let v = 0.6;
        let moving = rest.boosted([v, 0.0, 0.0]).unwrap();
        // Photon arriving from +y in the rest frame: backward ray leaves along +y.
        let p = rest.backward_momentum(&crate::tensor::ETA, [0.0, 1.0, 0.0], 1.0);
        let (n, e) = moving.backward_direction(&p);
        assert!((n[0] - v).abs() < 1e-14, "cos θ' = {}", n[0]);
        // Doppler: E' = γ E for a photon perpendicular in the rest frame.
        assert!((e - 1.25).abs() < 1e-14);
    }

    #[test]
    fn schwarzschild_static_frame_is_radially_stretched() {
        // The static observer measures the radial coordinate direction as stretched by
        // 1/√(1 − 2M/r) relative to the tangential ones; its first axis at (x, 0, 0) is radial.
        let m = Schwarzschild::new(1.0);
        let x = [0.0, 4.0, 0.0, 0.0];
        let t = Tetrad::static_observer(&m, &x).unwrap();
        assert!(t.e[1][2].abs() < 1e-15 && t.e[1][3].abs() < 1e-15);
        assert!((t.e[2][2] - 1.0).abs() < 1e-14 && (t.e[3][3] - 1.0).abs() < 1e-14);
    }
}

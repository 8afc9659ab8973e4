//! The shots of [`plane_aim`](super::plane_aim): one ray and its Jacobi field integrated from the
//! start to the target's azimuth, equations (1) and (2) of the aim's documentation
//! ([`super::aim`]), through a wormhole's throat where the target lies beyond it; and the aim
//! that a shot reaching the target gives, with its density, equation (3).

use super::{PlaneAim, PlaneMetric, Side};
use crate::geodesic::dopri5;
use crate::tensor::{normalize3, scale3};

/// Steps of one shot before it counts as failed.
const MAX_STEPS: u32 = 2_000;
/// Relative step of the central difference for `G_u`: its truncation (~h²) and rounding
/// (~10⁻¹⁶/h) errors are both near 10⁻¹⁰, far below what the density needs.
const DIFFERENCE_STEP: f64 = 1e-5;

/// Where one shot ended, relative to the target.
pub(super) enum Shot {
    /// It reached the target's azimuth with `(u, u', J)`, in the start's region or, `beyond` the
    /// throat, in the other (`u` then the other region's `ũ`).
    Reached { u: f64, du: f64, jacobi: f64, beyond: bool },
    /// It escaped before, in the start's region: `ψ` is too small.
    Below,
    /// A horizon took it before, or a throat the target is not beyond, or it escaped beyond the
    /// throat: `ψ` is too large.
    Above,
}

/// The aim's fixed data: the metric, the start and the target's place in the plane.
pub(super) struct Shooter<'m, M: PlaneMetric + ?Sized> {
    pub(super) metric: &'m M,
    pub(super) rtol: f64,
    pub(super) u_x: f64,
    /// `u_x/σ_x`.
    pub(super) slope_scale: f64,
    /// `1/f(u_x)²`: `β sin²ψ`.
    pub(super) beta_scale: f64,
    pub(super) sweep: f64,
    pub(super) side: Side,
}

/// The fraction of `attempt` at which its `u` reaches `ut` (which it passes by its end), by
/// bisection on the step's dense output.
fn throat_crossing(attempt: &dopri5::Attempt<4>, ut: f64) -> f64 {
    let (mut lo, mut hi) = (0.0, 1.0);
    for _ in 0..48 {
        let mid = 0.5 * (lo + hi);
        if attempt.dense_component(mid, 0) < ut {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    hi
}

/// The state `[u, u', J, J']` of a ray at or past the throat (`u ≥ u_t`) in the other region's
/// variable `ũ = u_t²/u`, at the same azimuth (module docs).
fn through_throat(ut: f64, [u, du, j, dj]: [f64; 4]) -> [f64; 4] {
    let ratio = ut * ut / (u * u);
    [ut * ut / u, -ratio * du, -ratio * j, -ratio * dj + 2.0 * ratio * du * j / u]
}

impl<M: PlaneMetric + ?Sized> Shooter<'_, M> {
    /// Equations (1) and (2) as one system `[u, u', J, J']`.
    #[inline]
    fn rhs(&self, beta: f64, beta_psi: f64, y: &[f64; 4]) -> [f64; 4] {
        let [u, du, j, dj] = *y;
        let g = |u: f64, beta: f64| self.metric.binet_source(u, beta);
        let h = DIFFERENCE_STEP * u.abs().max(f64::MIN_POSITIVE);
        let g_u = (g(u + h, beta) - g(u - h, beta)) / (2.0 * h);
        // Exact for G linear in β (module docs), whatever β's size.
        let g_beta = (g(u, 2.0 * beta) - g(u, 0.0)) / (2.0 * beta);
        [du, -u + g(u, beta), dj, -j + g_u * j + g_beta * beta_psi]
    }

    /// The ray leaving at `ψ`, integrated to the target's azimuth; `None` where it fails.
    pub(super) fn shoot(&self, psi: f64) -> Option<Shot> {
        let (sin, cos) = psi.sin_cos();
        let cot = cos / sin;
        let beta = self.beta_scale / (sin * sin);
        let beta_psi = -2.0 * beta * cot;
        let f = |_: f64, y: &[f64; 4]| self.rhs(beta, beta_psi, y);
        let mut y = [self.u_x, -self.slope_scale * cot, 0.0, self.slope_scale / (sin * sin)];
        let mut k = f(0.0, &y);
        let (mut phi, mut h) = (0.0, 0.1f64.min(self.sweep));
        let mut beyond = false;
        for _ in 0..MAX_STEPS {
            let step = h.min(self.sweep - phi);
            let attempt = dopri5::attempt(&f, phi, &y, &k, step);
            let scale = |a: usize, y0: &[f64; 4], y1: &[f64; 4]| {
                (y0[a].abs() + y0[a + 1].abs()).max(y1[a].abs() + y1[a + 1].abs())
            };
            let norm = |a: usize| {
                let (e0, e1) = (attempt.error[a], attempt.error[a + 1]);
                (e0 * e0 + e1 * e1).sqrt() / (self.rtol * scale(a, &y, &attempt.y1))
            };
            let err = norm(0).max(norm(2));
            if !(err <= 1.0) {
                h = step * if err.is_finite() { dopri5::step_factor(err).min(1.0) } else { 0.2 };
                if h <= 1e-15 {
                    return None;
                }
                continue;
            }
            h = step * dopri5::step_factor(err);
            match self.metric.throat_u().filter(|&ut| attempt.y1[0] >= ut) {
                // Cut the step where it reaches the throat (the chart's equation need not hold
                // past it), and carry on in the other region's variable.
                Some(ut) if !beyond && self.side == Side::Other => {
                    let cut = step * throat_crossing(&attempt, ut);
                    let at_throat = dopri5::attempt(&f, phi, &y, &k, cut).y1;
                    (phi, y, beyond) = (phi + cut, through_throat(ut, at_throat), true);
                    k = f(phi, &y);
                    continue;
                }
                Some(_) => return Some(Shot::Above),
                None => (phi, y, k) = (phi + step, attempt.y1, attempt.end_derivative()),
            }
            if y[0] <= 0.0 {
                return Some(if beyond { Shot::Above } else { Shot::Below });
            }
            if self.metric.capture_u().is_some_and(|uc| y[0] >= uc) {
                return Some(Shot::Above);
            }
            if phi >= self.sweep {
                let [u, du, jacobi, _] = y;
                return Some(Shot::Reached { u, du, jacobi, beyond });
            }
        }
        None
    }

    /// The aim of the ray leaving at `ψ` that reached `(u_y, u'_y)` with Jacobi field `J`, in
    /// world axes from the plane's (`radial` at the start, `across` towards the target).
    pub(super) fn found(
        &self,
        psi: f64,
        [radial, across]: [[f64; 3]; 2],
        (u_y, du, jacobi): (f64, f64, f64),
        shots: u32,
    ) -> Option<PlaneAim> {
        let metric = self.metric;
        let (sin, cos) = psi.sin_cos();
        let start = std::array::from_fn(|i| cos * radial[i] + sin * across[i]);
        let (sin_sweep, cos_sweep) = self.sweep.sin_cos();
        // |sin Δφ| either way: the plane's turn moves the point by ρ_y |sin Δφ|.
        let radial_y: [f64; 3] = std::array::from_fn(|i| cos_sweep * radial[i] + sin_sweep * across[i]);
        let azimuthal_y: [f64; 3] = std::array::from_fn(|i| -sin_sweep * radial[i] + cos_sweep * across[i]);
        let in_plane = |r: f64, a: f64| normalize3(&std::array::from_fn(|i| r * radial_y[i] + a * azimuthal_y[i]));
        let (rho, slope) = (metric.world_radius(u_y), metric.world_radius_slope(u_y));
        // The static observer sees `(n_r, n_φ) ∝ (−σ u', u)`; the world tangent is `dW/dφ`.
        let turned = |v: [f64; 3]| match self.side {
            Side::Same => v,
            Side::Other => scale3(&v, -1.0),
        };
        let end = turned(in_plane(-metric.radial_stretch(u_y) * du, u_y));
        let tangent_phi = rho / (slope * du).hypot(rho);
        let end_tangent = turned(in_plane(slope * du, rho));
        let solid_angle_per_area = sin / ((slope * jacobi).abs() * tangent_phi * rho * sin_sweep.abs());
        (solid_angle_per_area.is_finite() && solid_angle_per_area > 0.0).then_some(PlaneAim {
            start,
            end,
            end_tangent,
            solid_angle_per_area,
            shots,
        })
    }
}

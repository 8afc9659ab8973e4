//! A ray with two neighbours: the variational (Jacobi) equations of Hamilton's system, for any
//! metric.
//!
//! A family of rays `y(λ; α)` through a given start point, `y = (x^μ, p_μ)`, has deviations
//! `δy = ∂y/∂α` obeying the linearised equations `dδy/dλ = (∂f/∂y) δy`, with `f` the Hamiltonian
//! right-hand side. [`Bundle`] carries two deviations beside the ray: the 24 components
//! `(y, δy₁, δy₂)`. The Jacobian-vector products are taken by forward differences of `f` along
//! each deviation, so every metric gets them from its `geodesic_rhs` alone; the perturbation is
//! scaled to 10⁻⁷ of the state's size, balancing truncation (∝ the step) against rounding
//! (∝ 10⁻¹⁶ over the step), both near 10⁻⁸ relative: far below what the bundle serves (a Newton
//! step, a Monte Carlo density).

use super::hamiltonian::{Flow, Ray};
use crate::metric::Metric;

/// The relative size of the finite-difference perturbation (see the module documentation).
const RELATIVE_STEP: f64 = 1e-7;

/// The ray and two deviation fields along it.
#[derive(Clone, Copy, Debug)]
pub struct Bundle;

/// Components of a bundle's state.
pub const BUNDLE: usize = 24;

impl Flow<BUNDLE> for Bundle {
    #[inline]
    fn rhs<M: Metric + ?Sized>(metric: &M, y: &[f64; BUNDLE]) -> [f64; BUNDLE] {
        let ray: [f64; 8] = std::array::from_fn(|i| y[i]);
        let f = Ray::rhs(metric, &ray);
        let mut out = [0.0; BUNDLE];
        out[..8].copy_from_slice(&f);
        for k in 0..2 {
            let delta: [f64; 8] = std::array::from_fn(|i| y[8 + 8 * k + i]);
            let h = step_along(metric, &ray, &delta);
            if h == 0.0 {
                continue;
            }
            let moved: [f64; 8] = std::array::from_fn(|i| ray[i] + h * delta[i]);
            let g = Ray::rhs(metric, &moved);
            for i in 0..8 {
                out[8 + 8 * k + i] = (g[i] - f[i]) / h;
            }
        }
        out
    }
}

/// The finite-difference step along `delta` from `ray`: the displacement `h·δ` is
/// [`RELATIVE_STEP`] of the ray's position (its spatial part, at least the metric's length
/// scale) or of its momentum, whichever part of `δ` is the larger relative to its own; 0 for a
/// zero deviation.
#[inline]
fn step_along<M: Metric + ?Sized>(metric: &M, ray: &[f64; 8], delta: &[f64; 8]) -> f64 {
    let norm = |v: &[f64; 8], range: std::ops::Range<usize>| v[range].iter().map(|c| c * c).sum::<f64>().sqrt();
    let position = norm(ray, 1..4).max(metric.length_scale());
    let momentum = norm(ray, 4..8);
    let relative = (norm(delta, 1..4) / position).max(norm(delta, 4..8) / momentum);
    if relative > 0.0 && relative.is_finite() {
        RELATIVE_STEP / relative
    } else {
        0.0
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geodesic::hamiltonian::pack;
    use crate::geodesic::{HamiltonianTracer, State, Stepping, TraceSettings, Visit};
    use crate::metric::Kerr;

    /// The state after `steps` fixed RK4 steps of flow `F` from `y`.
    fn after<const N: usize, F: Flow<N>>(kerr: &Kerr, y: [f64; N], steps: u32) -> [f64; N] {
        let settings = TraceSettings {
            stepping: Stepping::Rk4 { step: 0.05 },
            escape_radius: 1e3,
            max_step_fraction: f64::INFINITY,
            max_steps: steps,
            check_every_step: true,
        };
        let mut end = y;
        HamiltonianTracer::<_, N, F>::of_flow(kerr, y, settings).run(|step| {
            end = step.flow_at(1.0);
            Visit::Continue
        });
        end
    }

    /// A deviation carried by the bundle matches the difference of two neighbouring rays taken
    /// with the same steps, to the finite differences' accuracy: around a spinning hole, over a
    /// ray that swings round it (impact parameter 6 M, 1200 steps of 0.05).
    #[test]
    fn deviations_match_neighbouring_rays() {
        let kerr = Kerr::new(1.0, 0.9);
        let start = |py: f64| {
            let x = [0.0, -30.0, 0.0, 1.0];
            let g = kerr.inverse_metric(&x);
            // Solve H = 0 for p_x with p = (1, p_x, p_y, 0): the backward ray heads in along +x.
            let (a2, a1) = (g[1][1], 2.0 * (g[0][1] + g[1][2] * py));
            let a0 = g[0][0] + 2.0 * g[0][2] * py + g[2][2] * py * py;
            let px = (-a1 + (a1 * a1 - 4.0 * a2 * a0).sqrt()) / (2.0 * a2);
            pack(&State { x, p: [1.0, px, py, 0.0] })
        };
        let (py, dpy, steps) = (0.2, 1e-6, 1200);
        let (minus, plus) = (start(py - dpy), start(py + dpy));
        let mut y0 = [0.0; BUNDLE];
        y0[..8].copy_from_slice(&start(py));
        for i in 0..8 {
            y0[8 + i] = (plus[i] - minus[i]) / (2.0 * dpy);
        }
        let bundle = after::<BUNDLE, Bundle>(&kerr, y0, steps);
        let (a, b) = (after::<8, Ray>(&kerr, minus, steps), after::<8, Ray>(&kerr, plus, steps));
        let size: f64 = (0..8).map(|i| ((b[i] - a[i]) / (2.0 * dpy)).powi(2)).sum::<f64>().sqrt();
        assert!(size > 10.0, "the ray should spread its neighbours (|δy| = {size})");
        for i in 0..8 {
            let finite = (b[i] - a[i]) / (2.0 * dpy);
            assert!((bundle[8 + i] - finite).abs() < 1e-4 * size, "component {i}: {} vs {finite}", bundle[8 + i]);
            // The second deviation started at zero and stays there.
            assert_eq!(bundle[16 + i], 0.0);
        }
    }
}

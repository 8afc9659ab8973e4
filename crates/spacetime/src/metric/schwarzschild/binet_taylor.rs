//! Taylor-series integration of the Schwarzschild Binet equation with its first and second
//! variations, the system the connection solver shoots ([`connect`](super::connect), equations
//! (1), (2) and (4)), and of the orbit alone, for the in-plane tracer ([`OrbitStep`]):
//!
//! ```text
//! u'' = −u + 3Mu²,   J'' = −J + 6MuJ,   K'' = −K + 6MuK + 6MJ².
//! ```
//!
//! The right-hand sides are polynomials, so the Taylor coefficients of the solution about any
//! point follow from a recurrence (automatic differentiation; Jorba & Zou 2005, "A software
//! package for the numerical integration of ODEs by means of high-order Taylor methods", Exp.
//! Math. 14): with `u = Σ aₖ tᵏ`, `J = Σ bₖ tᵏ`, `K = Σ cₖ tᵏ` and `(p∗q)ₖ = Σᵢ pᵢ qₖ₋ᵢ`,
//!
//! ```text
//! aₖ₊₂ = (−aₖ + 3M (a∗a)ₖ) / ((k+1)(k+2)),
//! bₖ₊₂ = (−bₖ + 6M (a∗b)ₖ) / ((k+1)(k+2)),
//! cₖ₊₂ = (−cₖ + 6M (a∗c)ₖ + 6M (b∗b)ₖ) / ((k+1)(k+2)).
//! ```
//!
//! A step of order `N` costs `O(N²)` flops and no right-hand-side evaluations; its length is set
//! by the last two coefficients so that the terms they stand for stay below the tolerance (ibid.
//! §3.2.1). The solutions are smooth on the scale of a radian away from the hole, so at the
//! tolerances of the connection solver a step spans a good part of a radian, and a connection
//! costs two thirds of what Dormand–Prince 5(4) took.

use crate::geodesic::taylor::{product_without_first, shorter_root, square_from, value, value_and_slope};

/// Order of the series. Jorba & Zou's optimum is about `−ln(tol)/2` (8 at 10⁻⁷), but on the
/// connection benchmark (`cargo bench -p nullpath-spacetime --bench connect`) order 10 was the
/// fastest of 6, 8, 10, 12, 14 and 20 at 10⁻⁷, and faster than 12 at the solver's 10⁻⁸: up to
/// 10, the longer steps more terms allow save more than the terms cost.
const ORDER: usize = 10;
/// Longest step, radians. The step rule trusts the last two coefficients of `u` and `J`; were
/// all four zero at once, this bounds the first neglected term instead: `1/11! ≈ 2.5·10⁻⁸` at one
/// radian for the sine and cosine of flat space. (A cap of 1.6 radians saved little.)
const MAX_STEP: f64 = 1.0;

/// Order of the series of `K`. `K` only sizes Newton's neglected term and carries the Jacobi
/// field across the last, unconfirmed Newton step (`J + K δs`, with `K δs²` below 10⁻⁶ `u_y`), so a
/// relative error of 10⁻³ in it is far below anything it feeds; at order 6 a step of a radian
/// truncates it by `1/7! ≈ 2·10⁻⁴`. Its two products are two thirds of the recurrence's work.
const K_ORDER: usize = 6;

/// `1/((n + 1)(n + 2))`, the recurrence's divisors as factors (a division costs several
/// multiplications).
const RECIPROCALS: [f64; ORDER - 1] = {
    let mut r = [0.0; ORDER - 1];
    let mut n = 0;
    while n < ORDER - 1 {
        r[n] = 1.0 / ((n + 1) * (n + 2)) as f64;
        n += 1;
    }
    r
};

/// Coefficients `0..=ORDER` of `u` and `J`, and `0..=K_ORDER` of `K`, about the current point.
struct Series {
    u: [f64; ORDER + 1],
    j: [f64; ORDER + 1],
    k: [f64; K_ORDER + 1],
}

impl Series {
    /// The series of the solution through `y = (u, u', J, J', K, K')` for mass `mass`.
    fn at(mass: f64, y: &[f64; 6]) -> Self {
        let m6 = 6.0 * mass;
        let mut s = Series { u: orbit_coefficients(mass, y[0], y[1]), j: [0.0; ORDER + 1], k: [0.0; K_ORDER + 1] };
        [s.j[0], s.j[1], s.k[0], s.k[1]] = [y[2], y[3], y[4], y[5]];
        let newest = m6 * s.u[0] - 1.0;
        s.next_jk::<0>(m6, newest);
        s.next_jk::<1>(m6, newest);
        s.next_jk::<2>(m6, newest);
        s.next_jk::<3>(m6, newest);
        s.next_jk::<4>(m6, newest);
        s.next_j::<5>(m6, newest);
        s.next_j::<6>(m6, newest);
        s.next_j::<7>(m6, newest);
        s.next_j::<8>(m6, newest);
        s
    }

    /// `J_{N+2}` from `(u∗J)_N = u₀J_N + Σ uᵢJ_{N−i}`: as for `u` ([`orbit_coefficients`]), the
    /// newest coefficient enters by one multiply–add, `(6Mu₀ − 1) J_N`.
    #[inline(always)]
    fn next_j<const N: usize>(&mut self, m6: f64, newest: f64) {
        self.j[N + 2] = (newest * self.j[N] + m6 * product_without_first::<N>(&self.u, &self.j)) * RECIPROCALS[N];
    }

    /// `J_{N+2}` and `K_{N+2}`, whose recurrence adds `(J∗J)_N`.
    #[inline(always)]
    fn next_jk<const N: usize>(&mut self, m6: f64, newest: f64) {
        let older = product_without_first::<N>(&self.u, &self.k) + square_from::<0, N>(&self.j);
        self.k[N + 2] = (newest * self.k[N] + m6 * older) * RECIPROCALS[N];
        self.next_j::<N>(m6, newest);
    }

    /// The longest step, at most `MAX_STEP`, whose last two terms of `u` and `J` stay within
    /// `tol` times the size of each (with the floors `floor` for components that pass through
    /// zero): `min (tol·size/|cₙ|)^(1/n)` over `n = N − 1, N`.
    fn step_limit(&self, tol: f64, floor: [f64; 2]) -> f64 {
        // Bounds of `hⁿ` for each order, at most 1 (the root of a larger one exceeds MAX_STEP).
        let power_bound = |n: usize| {
            [(&self.u, floor[0]), (&self.j, floor[1])]
                .iter()
                .map(|(c, floor)| tol * (c[0].abs().max(c[1].abs()) + floor) / c[n].abs())
                .fold(1.0, f64::min)
        };
        shorter_root::<{ ORDER as i32 - 1 }, { ORDER as i32 }>(power_bound(ORDER - 1), power_bound(ORDER))
    }

    /// `(u, u', J, J', K, K')` a step `h` on.
    fn state(&self, h: f64) -> [f64; 6] {
        let (u, du) = value_and_slope(&self.u, h);
        let (j, dj) = value_and_slope(&self.j, h);
        let (k, dk) = value_and_slope(&self.k, h);
        [u, du, j, dj, k, dk]
    }
}

/// Coefficients `0..=ORDER` of the orbit `u'' = −u + 3Mu²` through `(u, u')`: its own
/// recurrence, `aₖ₊₂ = (−aₖ + 3M (a∗a)ₖ) / ((k+1)(k+2))`, needs no other series.
///
/// The recurrence is bound by the latency of its chain from `aₖ` to `aₖ₊₂`, not by its
/// operations: with `(a∗a)ₖ = 2a₀aₖ + (the terms without aₖ)`, `aₖ₊₂ = ((6Ma₀ − 1) aₖ + 3M ·
/// (the rest)) / ((k+1)(k+2))`, the newest coefficient enters by one multiply–add and the rest
/// goes ahead of it. Each coefficient is its own instance of [`next_orbit`], so every sum is
/// unrolled (a loop over `k` was not).
fn orbit_coefficients(mass: f64, u: f64, du: f64) -> [f64; ORDER + 1] {
    const _: () = assert!(ORDER == 10 && K_ORDER == 6, "the recurrences are unrolled for these orders");
    let m3 = 3.0 * mass;
    let newest = 2.0 * m3 * u - 1.0;
    let mut c = [0.0; ORDER + 1];
    [c[0], c[1]] = [u, du];
    c[2] = (m3 * u - 1.0) * u * RECIPROCALS[0];
    next_orbit::<1>(&mut c, m3, newest);
    next_orbit::<2>(&mut c, m3, newest);
    next_orbit::<3>(&mut c, m3, newest);
    next_orbit::<4>(&mut c, m3, newest);
    next_orbit::<5>(&mut c, m3, newest);
    next_orbit::<6>(&mut c, m3, newest);
    next_orbit::<7>(&mut c, m3, newest);
    next_orbit::<8>(&mut c, m3, newest);
    c
}

/// `a_{N+2}` of the orbit (`N ≥ 1`), from `(a∗a)_N − 2a₀a_N`.
#[inline(always)]
fn next_orbit<const N: usize>(c: &mut [f64; ORDER + 1], m3: f64, newest: f64) {
    c[N + 2] = (newest * c[N] + m3 * square_from::<1, N>(c)) * RECIPROCALS[N];
}

/// A step of the orbit `u'' = −u + 3Mu²` alone, as the in-plane tracer takes it for the rays of
/// a render: the Taylor polynomial about the step's start is the state anywhere inside it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct OrbitStep {
    u: [f64; ORDER + 1],
    h: f64,
}

impl OrbitStep {
    /// The step from `(u, u')` of at most `h_max` for mass `mass`, as long as the last two terms
    /// of its series stay within `tol` of the larger of `|u|` and `|u'|`.
    pub fn new(mass: f64, u: f64, du: f64, h_max: f64, tol: f64) -> Self {
        let c = orbit_coefficients(mass, u, du);
        let size = tol * u.abs().max(du.abs());
        let bound = |n: usize| (size / c[n].abs()).min(1.0);
        let h = shorter_root::<{ ORDER as i32 - 1 }, { ORDER as i32 }>(bound(ORDER - 1), bound(ORDER))
            .min(MAX_STEP)
            .min(h_max);
        Self { u: c, h }
    }

    /// The same polynomial over the first fraction `theta` of the step only.
    pub fn cut(&self, theta: f64) -> Self {
        Self { h: theta * self.h, ..*self }
    }

    pub fn h(&self) -> f64 {
        self.h
    }

    /// `(u, du/dφ)` at fraction `θ ∈ [0, 1]` of the step.
    #[inline]
    pub fn at(&self, theta: f64) -> [f64; 2] {
        let (value, slope) = value_and_slope(&self.u, theta * self.h);
        [value, slope]
    }

    /// `u` at fraction `θ` of the step.
    #[inline]
    pub fn u(&self, theta: f64) -> f64 {
        value(&self.u, theta * self.h)
    }
}

/// One step from `y` of at most `h_max`, at relative tolerance `tol` (absolute floors `floor`
/// for `u` and `J`): the state at its end and the step taken.
pub fn step(mass: f64, y: &[f64; 6], h_max: f64, tol: f64, floor: [f64; 2]) -> ([f64; 6], f64) {
    let series = Series::at(mass, y);
    let h = series.step_limit(tol, floor).min(MAX_STEP).min(h_max);
    (series.state(h), h)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn without_mass_the_series_is_sine_and_cosine() {
        // u = cos φ, J = sin φ (J(0) = 0, J'(0) = 1), K = 0.
        let mut y = [1.0, 0.0, 0.0, 1.0, 0.0, 0.0];
        let mut phi = 0.0;
        while phi < 3.0 {
            let (next, h) = step(0.0, &y, 3.0 - phi, 1e-12, [1e-3, 1e-3]);
            (y, phi) = (next, phi + h);
        }
        assert!((y[0] - 3f64.cos()).abs() < 1e-11 && (y[1] + 3f64.sin()).abs() < 1e-11, "{y:?}");
        assert!((y[2] - 3f64.sin()).abs() < 1e-11 && (y[3] - 3f64.cos()).abs() < 1e-11, "{y:?}");
        assert_eq!((y[4], y[5]), (0.0, 0.0));
    }

    #[test]
    fn orbit_steps_keep_the_first_integral_inside_and_at_the_end_of_every_step() {
        // (u')² + u² − 2Mu³ = 1/b² along the orbit, here over two radians at the tracer's 10⁻⁷,
        // checked at the ends and in the middle of every step (the polynomial is the dense
        // output the chord tests place points with).
        let (mass, tol) = (0.3, 1e-7);
        let first_integral = |[u, du]: [f64; 2]| du * du + u * u - 2.0 * mass * u.powi(3);
        let (mut state, mut phi, mut steps) = ([0.25, 0.1], 0.0, 0);
        let start = first_integral(state);
        while phi < 2.0 {
            let step = OrbitStep::new(mass, state[0], state[1], 0.5, tol);
            for theta in [0.5, 1.0] {
                let drift = (first_integral(step.at(theta)) - start).abs();
                assert!(drift < tol * start, "drift {drift:e} at φ = {phi} + {theta} h");
            }
            assert_eq!(step.u(0.5), step.at(0.5)[0]);
            (state, phi, steps) = (step.at(1.0), phi + step.h(), steps + 1);
        }
        // Capped at half a radian, as the renderer caps them: 4 steps.
        assert!(steps <= 5, "{steps} steps over 2 radians");
        // A step cut short is the same polynomial over less of the azimuth.
        let step = OrbitStep::new(mass, 0.25, 0.1, 0.5, tol);
        assert_eq!(step.cut(0.5).at(1.0), step.at(0.5));
    }

    #[test]
    fn the_orbit_keeps_its_first_integral_and_steps_are_long() {
        // (u')² + u² − 2Mu³ = 1/b² along the orbit; J and K are checked against finite
        // differences of u in the starting slope.
        let (mass, u0) = (0.3, 0.25);
        let orbit = |s: f64| {
            let (mut y, mut phi, mut steps) = ([u0, s, 0.0, 1.0, 0.0, 0.0], 0.0, 0);
            while phi < 2.0 {
                let (next, h) = step(mass, &y, 2.0 - phi, 1e-12, [1e-3 * u0, 1e-3]);
                (y, phi, steps) = (next, phi + h, steps + 1);
            }
            (y, steps)
        };
        let s = 0.1;
        let (y, steps) = orbit(s);
        let first_integral = |y: &[f64; 6]| y[1] * y[1] + y[0] * y[0] - 2.0 * mass * y[0].powi(3);
        let start = s * s + u0 * u0 - 2.0 * mass * u0.powi(3);
        assert!((first_integral(&y) - start).abs() < 1e-12, "drift {}", first_integral(&y) - start);
        // 13 measured at order 10 and tolerance 1e-12.
        assert!(steps <= 16, "{steps} steps over 2 radians");
        let d = 1e-5;
        let (up, _) = orbit(s + d);
        let (down, _) = orbit(s - d);
        let j = (up[0] - down[0]) / (2.0 * d);
        let k = (up[0] - 2.0 * y[0] + down[0]) / (d * d);
        assert!((j - y[2]).abs() < 1e-8 * j.abs().max(1.0), "J {} vs {j}", y[2]);
        assert!((k - y[4]).abs() < 1e-4 * k.abs().max(1.0), "K {} vs {k}", y[4]);
    }
}

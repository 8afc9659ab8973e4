//! Start slopes of short-way connections, tabulated once for every mass.
//!
//! [`connect`](super::connect) shoots from a first guess correct to first order in `M`; in a room
//! round a hole (`3Mu` up to 0.3) that guess misses by a few per cent, so a coarse shot has to
//! bring it within reach of the fine one. The exact start slope, less that guess, is smooth in
//! the ends' `Mu` and the sweep, and scale-free: with `v = Mu` the Binet equation
//! `u'' = −u + 3Mu²` becomes `v'' = −v + 3v²`, so the slope for mass `M` is the one for mass 1
//! at `(Mu_x, Mu_y)`, divided by `M`. Interpolated trilinearly from a grid of solved connections
//! (built on first use, ~20 000 of them, in about 0.1 s), the correction leaves a miss that the first, fine, shot
//! takes out.

use super::connect::{first_guess, solve, Way};
use crate::metric::Schwarzschild;
use std::f64::consts::PI;
use std::sync::OnceLock;

/// The grid spans `Mu` from `MU_MIN` (r = 100 M, where the first guess needs no help) to the
/// photon sphere, and sweeps from 0 to π.
const MU_MIN: f64 = 0.01;
const MU_MAX: f64 = 1.0 / 3.0;
const CELLS_MU: usize = 24;
const CELLS_SWEEP: usize = 32;

/// `M(s − s₁)` at the grid's nodes: the exact start slope `s` less the first guess `s₁`, for
/// `M = 1`; NaN where there is no short-way ray (or the sweep is 0).
pub(super) struct ShortWayTable {
    values: Vec<f64>,
}

/// The table, built on first use.
pub(super) fn short_way_table() -> &'static ShortWayTable {
    static TABLE: OnceLock<ShortWayTable> = OnceLock::new();
    TABLE.get_or_init(ShortWayTable::build)
}

fn mu_node(i: usize) -> f64 {
    MU_MIN + (MU_MAX - MU_MIN) * i as f64 / CELLS_MU as f64
}

fn index(i: usize, j: usize, k: usize) -> usize {
    (i * (CELLS_MU + 1) + j) * (CELLS_SWEEP + 1) + k
}

impl ShortWayTable {
    fn build() -> Self {
        let unit = Schwarzschild::new(1.0);
        let mut values = vec![f64::NAN; (CELLS_MU + 1) * (CELLS_MU + 1) * (CELLS_SWEEP + 1)];
        for i in 0..=CELLS_MU {
            for j in 0..=CELLS_MU {
                for k in 1..=CELLS_SWEEP {
                    let (ux, uy, sweep) = (mu_node(i), mu_node(j), PI * k as f64 / CELLS_SWEEP as f64);
                    let (sin, cos) = sweep.sin_cos();
                    let (x, y) = ([1.0 / ux, 0.0, 0.0], [cos / uy, sin / uy, 0.0]);
                    let Some(ray) = solve(&unit, x, y, Way::Short, None, false) else { continue };
                    // The ray leaves at ψ from the outward radial x̂ towards ŷ (the plane's e₂).
                    let psi = ray.start[1].atan2(ray.start[0]);
                    let slope = -ux * (1.0 - 2.0 * ux).sqrt() / psi.tan();
                    values[index(i, j, k)] = slope - first_guess(1.0, ux, uy, cos, sin.max(0.0));
                }
            }
        }
        Self { values }
    }

    /// `M(s − s₁)` at `(Mu_x, Mu_y, Δφ)`, where the grid covers it and all eight nodes around it
    /// have a ray.
    pub(super) fn correction(&self, mu_x: f64, mu_y: f64, sweep: f64) -> Option<f64> {
        let cell = |v: f64, low: f64, high: f64, cells: usize| {
            let t = (v - low) / (high - low) * cells as f64;
            (t >= 0.0 && t <= cells as f64).then(|| {
                let i = (t as usize).min(cells - 1);
                (i, t - i as f64)
            })
        };
        let (i, fx) = cell(mu_x, MU_MIN, MU_MAX, CELLS_MU)?;
        let (j, fy) = cell(mu_y, MU_MIN, MU_MAX, CELLS_MU)?;
        let (k, fz) = cell(sweep, 0.0, PI, CELLS_SWEEP)?;
        let lerp = |a: f64, b: f64, t: f64| a + (b - a) * t;
        let at = |di: usize, dj: usize| {
            lerp(self.values[index(i + di, j + dj, k)], self.values[index(i + di, j + dj, k + 1)], fz)
        };
        let value = lerp(lerp(at(0, 0), at(0, 1), fy), lerp(at(1, 0), at(1, 1), fy), fx);
        value.is_finite().then_some(value)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Between its nodes the table gives the start slope far closer than the first guess: within
    /// a miss that the first, fine, shot mostly takes out.
    #[test]
    fn tabulated_slopes_are_close_to_the_exact_ones() {
        let mass = 0.3;
        let hole = Schwarzschild::new(mass);
        let (mut worst_table, mut worst_guess, mut covered) = (0.0f64, 0.0f64, 0);
        for n in 0..400 {
            // Points between r = 1 and 11, sweeps over (0, π), off the grid's nodes.
            let f = |k: u32| (f64::from(n) * [0.754_877_666, 0.569_840_291, 0.362_437_118][k as usize]).fract();
            let (rx, ry, sweep) = (1.0 + 10.0 * f(0), 1.0 + 10.0 * f(1), 0.05 + 3.0 * f(2));
            let (sin, cos) = sweep.sin_cos();
            let Some(ray) = solve(&hole, [rx, 0.0, 0.0], [ry * cos, ry * sin, 0.0], Way::Short, None, false) else {
                continue;
            };
            let (ux, uy) = (1.0 / rx, 1.0 / ry);
            let exact = -ux * (1.0 - 2.0 * mass * ux).sqrt() / ray.start[1].atan2(ray.start[0]).tan();
            let guess = first_guess(mass, ux, uy, cos, sin);
            let Some(correction) = short_way_table().correction(mass * ux, mass * uy, sweep) else { continue };
            covered += 1;
            // The miss at y, to first order, is J δs; J ≈ sin Δφ, and misses count against u_y.
            let miss = |s: f64| (s - exact).abs() * sin / uy;
            worst_table = worst_table.max(miss(guess + correction / mass));
            worst_guess = worst_guess.max(miss(guess));
        }
        assert!(covered > 300, "the table covered {covered} pairs");
        // Measured: 2.3·10⁻³ of u_y at worst from the table, 1.2 from the first guess (near r = 1).
        assert!(
            worst_table < 5e-3 && worst_table * 100.0 < worst_guess,
            "table {worst_table:e}, guess {worst_guess:e}"
        );
    }
}

//! Starts of connections, tabulated once for every mass, by the [`StartTables`] a
//! [`Connector`](super::Connector) owns (not global state: a render builds its own).
//!
//! [`connect`](super) shoots each way from a first guess: the short way's is correct to
//! first order in `M`, the long way's is the strong-deflection limit. In a room round a hole
//! (`3Mu` up to 0.3) both miss by a few per cent, so coarse shots have to bring them within reach
//! of the fine one. The exact [`start_parameter`] (the short way's slope `Ms`, the long way's
//! `ln ε`), less its guess, is smooth in the ends' `Mu` and the sweep, and scale-free: with
//! `v = Mu` the Binet equation `u'' = −u + 3Mu²` becomes `v'' = −v + 3v²`, so the start for
//! mass `M` is the one for mass 1 at `(Mu_x, Mu_y)`. Interpolated trilinearly from a grid of
//! solved connections (built on a way's first use, ~20 000 of them, in about 0.1 s the short
//! way and 0.2 s the long way), the correction leaves a miss that the first, fine, shot takes
//! out.

use super::guess::{guessed_parameter, start_parameter};
use super::{solve, Way, Waypoints};
use crate::metric::Schwarzschild;
use std::f64::consts::PI;
use std::sync::OnceLock;

/// The grid spans `Mu` from `MU_MIN` (r = 100 M, where the first guesses need little help) to the
/// photon sphere, and each way's sweeps: from 0 to π the short way, from π to 2π the long way.
const MU_MIN: f64 = 0.01;
const MU_MAX: f64 = 1.0 / 3.0;
const CELLS_MU: usize = 24;
const CELLS_SWEEP: usize = 32;

/// The exact start parameter less its guess at the grid's nodes, for `M = 1`; NaN where there is
/// no ray that way (or the ends and the centre are aligned).
pub(super) struct StartTable {
    way: Way,
    values: Vec<f64>,
}

/// Both ways' tables, each built on its first use (a render that never connects the long way
/// never pays for its table). They hold for every mass, so one set serves any hole.
#[derive(Default)]
pub(super) struct StartTables {
    short: OnceLock<StartTable>,
    long: OnceLock<StartTable>,
}

impl StartTables {
    /// The table of `way`, built on first use.
    pub(super) fn get(&self, way: Way) -> &StartTable {
        match way {
            Way::Short => self.short.get_or_init(|| StartTable::build(way)),
            Way::Long => self.long.get_or_init(|| StartTable::build(way)),
        }
    }
}

impl std::fmt::Debug for StartTables {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let built = |t: &OnceLock<StartTable>| t.get().is_some();
        f.debug_struct("StartTables").field("short", &built(&self.short)).field("long", &built(&self.long)).finish()
    }
}

fn mu_node(i: usize) -> f64 {
    MU_MIN + (MU_MAX - MU_MIN) * i as f64 / CELLS_MU as f64
}

fn index(i: usize, j: usize, k: usize) -> usize {
    (i * (CELLS_MU + 1) + j) * (CELLS_SWEEP + 1) + k
}

/// The sweeps a way's rays go round.
fn sweeps(way: Way) -> (f64, f64) {
    match way {
        Way::Short => (0.0, PI),
        Way::Long => (PI, 2.0 * PI),
    }
}

impl StartTable {
    fn build(way: Way) -> Self {
        let unit = Schwarzschild::new(1.0);
        let (low, high) = sweeps(way);
        let mut waypoints = Waypoints::default();
        let mut values = vec![f64::NAN; (CELLS_MU + 1) * (CELLS_MU + 1) * (CELLS_SWEEP + 1)];
        for i in 0..=CELLS_MU {
            for j in 0..=CELLS_MU {
                for k in 0..=CELLS_SWEEP {
                    let (ux, uy) = (mu_node(i), mu_node(j));
                    let sweep = low + (high - low) * k as f64 / CELLS_SWEEP as f64;
                    // `y` lies the short way round from `x`, at `Δφ = min(sweep, 2π − sweep)`.
                    let (sin, cos) = sweep.sin_cos();
                    let (x, y) = ([1.0 / ux, 0.0, 0.0], [cos / uy, sin.abs() / uy, 0.0]);
                    let Some(ray) = solve(&unit, x, y, way, None, None, &mut waypoints) else { continue };
                    // The ray leaves at ψ ∈ (0, π) from the outward radial x̂, in the plane of ŷ.
                    let psi = ray.start[1].abs().atan2(ray.start[0]);
                    let guess = guessed_parameter(way, 1.0, ux, uy, cos, sin.abs(), sweep);
                    values[index(i, j, k)] = start_parameter(way, 1.0, ux, psi) - guess;
                }
            }
        }
        Self { way, values }
    }

    /// The start parameter less its guess at `(Mu_x, Mu_y, sweep)`, where the grid covers it and
    /// all eight nodes around it have a ray.
    pub(super) fn correction(&self, mu_x: f64, mu_y: f64, sweep: f64) -> Option<f64> {
        let cell = |v: f64, low: f64, high: f64, cells: usize| {
            let t = (v - low) / (high - low) * cells as f64;
            (t >= 0.0 && t <= cells as f64).then(|| {
                let i = (t as usize).min(cells - 1);
                (i, t - i as f64)
            })
        };
        let (low, high) = sweeps(self.way);
        let (i, fx) = cell(mu_x, MU_MIN, MU_MAX, CELLS_MU)?;
        let (j, fy) = cell(mu_y, MU_MIN, MU_MAX, CELLS_MU)?;
        let (k, fz) = cell(sweep, low, high, CELLS_SWEEP)?;
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

    /// Between its nodes each way's table gives the start far closer than the first guess:
    /// within a miss that the first, fine, shot mostly takes out.
    #[test]
    fn tabulated_starts_are_close_to_the_exact_ones() {
        let mass = 0.3;
        let hole = Schwarzschild::new(mass);
        let tables = StartTables::default();
        for way in Way::BOTH {
            let (low, high) = sweeps(way);
            let (mut worst_table, mut worst_guess, mut covered) = (0.0f64, 0.0f64, 0);
            for n in 0..400 {
                // Points between r = 1 and 11, sweeps over the way's range, off the grid's nodes.
                let f = |k: u32| (f64::from(n) * [0.754_877_666, 0.569_840_291, 0.362_437_118][k as usize]).fract();
                let (rx, ry) = (1.0 + 10.0 * f(0), 1.0 + 10.0 * f(1));
                let sweep = low + 0.02 + (high - low - 0.04) * f(2);
                let (sin, cos) = sweep.sin_cos();
                let (x, y) = ([rx, 0.0, 0.0], [ry * cos, ry * sin.abs(), 0.0]);
                let Some(ray) = solve(&hole, x, y, way, None, None, &mut Waypoints::default()) else { continue };
                let (ux, uy) = (1.0 / rx, 1.0 / ry);
                let exact = start_parameter(way, mass, ux, ray.start[1].abs().atan2(ray.start[0]));
                let guess = guessed_parameter(way, mass, ux, uy, cos, sin.abs(), sweep);
                let Some(correction) = tables.get(way).correction(mass * ux, mass * uy, sweep) else { continue };
                covered += 1;
                // The miss at y counts against u_y. The short way's, to first order, is J δs
                // with J ≈ sin Δφ; the long way's is the sweep's error, about −δ(ln ε), times
                // u', at most about u_y near the photon sphere.
                let miss = |p: f64| match way {
                    Way::Short => (p - exact).abs() / mass * sin.abs() / uy,
                    Way::Long => (p - exact).abs(),
                };
                worst_table = worst_table.max(miss(guess + correction));
                worst_guess = worst_guess.max(miss(guess));
            }
            assert!(covered > 300, "{way:?}: the table covered {covered} pairs");
            // Measured: 2.3·10⁻³ of u_y at worst from the short way's table, 1.2 from its
            // first guess (near r = 1); the long way's 2.5·10⁻² (an end at r = 1.01, just off the
            // photon sphere, sweeping 3.5; all but 4 of 400 within 3·10⁻³), 0.52 from its guess.
            let (bound, gain) = match way {
                Way::Short => (5e-3, 100.0),
                Way::Long => (5e-2, 15.0),
            };
            assert!(
                worst_table < bound && worst_table * gain < worst_guess,
                "{way:?}: table {worst_table:e}, guess {worst_guess:e}"
            );
        }
    }
}

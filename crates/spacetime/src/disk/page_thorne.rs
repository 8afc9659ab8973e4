//! The geometrically thin, optically thick accretion disk of Novikov & Thorne (1973): gas on the
//! prograde circular geodesics from the ISCO outwards, radiating from each face the flux that
//! Page & Thorne (1974, eq. 11b) derived from the conservation of rest mass, energy and angular
//! momentum with no torque at the inner edge:
//!
//! `F(r) = −Ṁ/(4π √(−g)) · Ω_{,r}/(E − ΩL)² · ∫_{r_in}^{r} (E − ΩL) L_{,r} dr`,
//!
//! per unit proper area and proper time of the gas, `√(−g) = r` of the equatorial
//! Boyer–Lindquist metric `(t, r, φ)` of Kerr's family. The flux is given here per unit
//! accretion rate `Ṁ` (in units `1/M²` of the hole's mass): each face radiates as a blackbody
//! at `σT⁴ = F`, so the temperature profile is `T ∝ F^{1/4}`, whatever `Ṁ`.
//!
//! The integral is kept as a table of its values at the ends of panels even in `ln r`, each
//! panel by Gauss–Legendre quadrature; a flux adds the part of its own panel the same way, so it
//! is exact to rounding at any radius.

use super::orbits::CircularOrbits;
use num_dual::first_derivative;
use std::f64::consts::PI;

/// Panels of the integral's table, even in `ln r` from the ISCO to the disk's outer edge.
const PANELS: usize = 256;

/// Gauss–Legendre nodes and weights of order 8 on `[−1, 1]` (positive half; symmetric).
const GAUSS_NODES: [f64; 4] =
    [0.183_434_642_495_649_8, 0.525_532_409_916_329, 0.796_666_477_413_626_7, 0.960_289_856_497_536_3];
const GAUSS_WEIGHTS: [f64; 4] =
    [0.362_683_783_378_362, 0.313_706_645_877_887_3, 0.222_381_034_453_374_5, 0.101_228_536_290_376_26];

/// A Novikov–Thorne disk about one hole, from the ISCO to an outer radius.
#[derive(Clone, Debug)]
pub struct ThinDisk {
    orbits: CircularOrbits,
    inner: f64,
    outer: f64,
    /// `ln(outer/inner) / PANELS`.
    step: f64,
    /// `∫_{r_in}^{r_k} (E − ΩL) L_{,r} dr` at the panels' ends `r_k = r_in e^{k·step}`.
    integral: Vec<f64>,
}

impl ThinDisk {
    /// The disk of `orbits`' hole from its ISCO to Boyer–Lindquist radius `outer` (clamped to
    /// the ISCO: a disk may be empty).
    pub fn new(orbits: CircularOrbits, outer: f64) -> Self {
        let inner = orbits.isco();
        let outer = outer.max(inner);
        let step = (outer / inner).ln() / PANELS as f64;
        let mut disk = Self { orbits, inner, outer, step, integral: Vec::with_capacity(PANELS + 1) };
        let mut total = 0.0;
        disk.integral.push(total);
        for k in 0..PANELS {
            total += disk.integrate(disk.panel_start(k), disk.panel_start(k + 1));
            disk.integral.push(total);
        }
        disk
    }

    pub fn orbits(&self) -> &CircularOrbits {
        &self.orbits
    }

    /// The inner edge: the ISCO's Boyer–Lindquist radius.
    pub fn inner_radius(&self) -> f64 {
        self.inner
    }

    /// The outer edge's Boyer–Lindquist radius.
    pub fn outer_radius(&self) -> f64 {
        self.outer
    }

    fn panel_start(&self, k: usize) -> f64 {
        self.inner * (k as f64 * self.step).exp()
    }

    /// `(E − ΩL) L_{,r}` at `r`.
    fn integrand(&self, r: f64) -> f64 {
        let (orbit, dl) = (self.orbits.orbit(r), first_derivative(|r| self.orbits.orbit(r).angular_momentum, r).1);
        (orbit.energy - orbit.omega * orbit.angular_momentum) * dl
    }

    /// `∫_a^b (E − ΩL) L_{,r} dr` by Gauss–Legendre of order 8.
    fn integrate(&self, a: f64, b: f64) -> f64 {
        let (mid, half) = (0.5 * (a + b), 0.5 * (b - a));
        let sum: f64 = GAUSS_NODES
            .iter()
            .zip(GAUSS_WEIGHTS)
            .map(|(&x, w)| w * (self.integrand(mid - half * x) + self.integrand(mid + half * x)))
            .sum();
        half * sum
    }

    /// `∫_{r_in}^{r} (E − ΩL) L_{,r} dr`, for `r_in ≤ r ≤ r_out`.
    fn torque_integral(&self, r: f64) -> f64 {
        let k = (((r / self.inner).ln() / self.step).floor().max(0.0) as usize).min(PANELS - 1);
        self.integral[k] + self.integrate(self.panel_start(k), r)
    }

    /// Flux from each face per unit accretion rate at Boyer–Lindquist radius `r`: zero off the
    /// disk (inside the ISCO, beyond the outer edge).
    pub fn flux(&self, r: f64) -> f64 {
        if !(r > self.inner && r <= self.outer) {
            return 0.0;
        }
        let (orbit, d_omega) = (self.orbits.orbit(r), first_derivative(|r| self.orbits.orbit(r).omega, r).1);
        let e_minus_omega_l = orbit.energy - orbit.omega * orbit.angular_momentum;
        (-d_omega / (4.0 * PI * r * e_minus_omega_l * e_minus_omega_l) * self.torque_integral(r)).max(0.0)
    }

    /// The radius of the hottest ring, where the flux peaks (golden-section search: the flux
    /// rises from zero at the ISCO to one maximum and falls like `r⁻³`), and the flux there.
    /// At the outer edge where the disk ends before its peak.
    pub fn peak(&self) -> (f64, f64) {
        let ratio = 0.5 * (5f64.sqrt() - 1.0);
        let (mut a, mut b) = (self.inner, self.outer);
        while b - a > 1e-10 * b {
            let (c, d) = (b - ratio * (b - a), a + ratio * (b - a));
            if self.flux(c) < self.flux(d) {
                a = c;
            } else {
                b = d;
            }
        }
        let r = 0.5 * (a + b);
        (r, self.flux(r))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::analytic::{integrate, page_thorne_kerr_flux};

    #[test]
    fn flux_matches_page_thorne_closed_form_about_kerr() {
        for a in [0.3, 0.9, 0.998] {
            let disk = ThinDisk::new(CircularOrbits::new(1.0, a, 0.0), 200.0);
            let isco = disk.inner_radius();
            for r in [isco * 1.001, isco * 1.3, 5.5, 9.5, 60.0, 199.0] {
                let (f, exact) = (disk.flux(r), page_thorne_kerr_flux(1.0, a, r));
                assert!((f - exact).abs() <= 1e-9 * exact.abs() + 1e-16, "a = {a}, r = {r}: {f} vs {exact}");
            }
        }
    }

    #[test]
    fn radiated_energy_balances_the_binding_energy_released() {
        // Page & Thorne's energy law: what both faces radiate inside r, measured at infinity,
        // is the binding energy the gas loses, less what the torque carries outwards:
        // ∫ 4π r F E dr = E(r) − E_in − Ω I/(E − ΩL), I the torque integral.
        for (a, q) in [(0.0, 0.0), (0.9, 0.0), (0.5, 0.6), (0.0, 0.9)] {
            let orbits = CircularOrbits::new(1.0, a, q);
            let disk = ThinDisk::new(orbits, 500.0);
            let inner = disk.inner_radius();
            let r = 80.0;
            let radiated = integrate(&|r| 4.0 * PI * r * disk.flux(r) * orbits.orbit(r).energy, inner, r, 1e-12);
            let (o, o_in) = (orbits.orbit(r), orbits.orbit(inner));
            let carried = o.omega * disk.torque_integral(r) / (o.energy - o.omega * o.angular_momentum);
            let released = o.energy - o_in.energy - carried;
            assert!((radiated - released).abs() < 1e-10, "a = {a}, Q = {q}: {radiated} vs {released}");
        }
    }

    #[test]
    fn efficiency_of_a_large_disk_is_one_minus_the_isco_energy() {
        // 5.72 % about a Schwarzschild hole, 15.58 % at a = 0.9 M; what lies beyond 10⁷ M is
        // 1.5·10⁻⁷.
        for (a, efficiency) in [(0.0, 1.0 - (8.0f64 / 9.0).sqrt()), (0.9, 0.155_753)] {
            let disk = ThinDisk::new(CircularOrbits::new(1.0, a, 0.0), 1e7);
            let orbits = disk.orbits();
            let radiated = integrate(
                &|u: f64| {
                    // r = r_in e^u: the flux falls like r⁻³, so ln r spreads it evenly.
                    let r = disk.inner_radius() * u.exp();
                    4.0 * PI * r * r * disk.flux(r) * orbits.orbit(r).energy
                },
                0.0,
                (1e7 / disk.inner_radius()).ln(),
                1e-12,
            );
            assert!((radiated - efficiency).abs() < 1e-6, "a = {a}: {radiated}");
        }
    }

    #[test]
    fn the_flux_vanishes_at_the_isco_and_peaks_once_outside_it() {
        let disk = ThinDisk::new(CircularOrbits::new(1.0, 0.0, 0.0), 100.0);
        assert_eq!(disk.flux(disk.inner_radius()), 0.0);
        assert!(disk.flux(disk.inner_radius() * (1.0 + 1e-9)) < 1e-12);
        let (r, peak) = disk.peak();
        // Schwarzschild's hottest ring lies at r ≈ 9.55 M.
        assert!((r - 9.55).abs() < 0.01, "{r}");
        assert!(peak > disk.flux(0.9 * r) && peak > disk.flux(1.1 * r));
        assert_eq!(disk.flux(100.5), 0.0);
    }
}

//! Circular equatorial geodesics about a hole of Kerr's family (mass `M`, spin `a`, charge `Q`):
//! the orbits the gas of a thin accretion disk follows (Bardeen, Press & Teukolsky 1972 for Kerr).
//!
//! In Boyer–Lindquist coordinates the equatorial metric has, with `s = 2Mr − Q²`,
//! `g_tt = −(1 − s/r²)`, `g_tφ = −a s/r²`, `g_φφ = r² + a² + a² s/r²`, `g_rr = r²/Δ`. A circular
//! geodesic has `∂_r g_tt + 2Ω ∂_r g_tφ + Ω² ∂_r g_φφ = 0`, whose co-rotating root is
//! `Ω = w/(r² + |a| w)`, `w = √(Mr − Q²)` (Kerr: `√M/(r^{3/2} + a√M)`). Its 4-velocity is
//! `u = u^t (∂_t + Ω ∂_φ)`, and the conserved energy and angular momentum per unit rest mass
//! are `E = −u_t`, `L = u_φ`. The innermost stable orbit (ISCO) is where `E` (and `L`) have
//! their minimum: inside it no circular orbit is stable, and the disk ends.
//!
//! `∂_t` and `∂_φ` are the same Killing vectors in the outgoing Kerr–Schild chart the tracer
//! uses (its `t` and `φ` differ from Boyer–Lindquist's by functions of `r` alone), so the gas
//! turns rigidly about the spin axis at `Ω` there too, and its Boyer–Lindquist `r` is the
//! chart's spheroidal radius: at world radius `ρ` in the equatorial plane, `r = √(ρ² − a²)`.

use crate::metric::{KerrNewman, Scalar};
use num_dual::first_derivative;

/// The circular equatorial geodesics of one hole of Kerr's family turning one way, prograde
/// (with the spin, as a disk's gas does) or retrograde (neutral bodies; the charge enters only
/// through the metric).
///
/// Both families are the prograde family of a hole whose spin is the spin's component along
/// the orbits' sense of turning: `+|a|` prograde, `−|a|` retrograde (Bardeen, Press &
/// Teukolsky 1972, whose upper and lower signs are these), mirrored when they turn about −z.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CircularOrbits {
    mass: f64,
    /// The spin along the orbits' sense: `|a|` prograde, `−|a|` retrograde.
    spin: f64,
    charge: f64,
    /// `+1` where the hole spins about +z (or not at all), `−1` about −z: the sense the gas turns.
    sense: f64,
}

/// One circular orbit: its angular velocity `Ω = dφ/dt`, its energy `E` and angular momentum `L`
/// per unit rest mass (conserved, measured at infinity), and `u^t = dt/dτ`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Orbit<D> {
    pub omega: D,
    pub energy: D,
    pub angular_momentum: D,
    pub u_t: D,
}

impl CircularOrbits {
    /// The orbits about a hole of mass `m > 0`, spin `a` about +z and charge `q`
    /// (`a² + q² ≤ m²`).
    pub fn new(mass: f64, spin: f64, charge: f64) -> Self {
        let sense = if spin < 0.0 { -1.0 } else { 1.0 };
        Self { mass, spin: spin.abs(), charge, sense }
    }

    /// The same hole's orbits turning the other way: retrograde for prograde, and back.
    pub fn reversed(&self) -> Self {
        Self { spin: -self.spin, sense: -self.sense, ..*self }
    }

    /// Whether these orbits turn against the hole's spin (never, about a hole without one).
    pub fn is_retrograde(&self) -> bool {
        self.spin < 0.0
    }

    pub fn mass(&self) -> f64 {
        self.mass
    }

    /// The hole, its spin about +z.
    pub fn hole(&self) -> KerrNewman {
        KerrNewman::new(self.mass, self.sense * self.spin, self.charge)
    }

    /// The sense the gas turns about +z: `+1` counter-clockwise seen from +z.
    pub fn sense(&self) -> f64 {
        self.sense
    }

    /// The orbit at Boyer–Lindquist radius `r`, generic so that its radial derivatives come by
    /// dual numbers. `NaN` where no circular orbit exists (inside the photon orbit, where `u^t`
    /// would be imaginary).
    pub fn orbit<D: Scalar>(&self, r: D) -> Orbit<D> {
        let (m, a, q2) = (self.mass, self.spin, self.charge * self.charge);
        let w = (r * m - q2).sqrt();
        let omega = w / (r * r + w * a);
        let s_over_r2 = (r * (2.0 * m) - q2) / (r * r);
        let g_tt = s_over_r2 - 1.0;
        let g_tphi = -s_over_r2 * a;
        let g_phiphi = r * r + a * a + s_over_r2 * (a * a);
        let u_t = (-(g_tt + omega * g_tphi * 2.0 + omega * omega * g_phiphi)).sqrt().recip();
        let energy = -(g_tt + omega * g_tphi) * u_t;
        let angular_momentum = (g_tphi + omega * g_phiphi) * u_t;
        Orbit { omega: omega * self.sense, energy, angular_momentum: angular_momentum * self.sense, u_t }
    }

    /// `dE/dr` at `r` (`NaN` inside the photon orbit).
    fn energy_slope(&self, r: f64) -> f64 {
        first_derivative(|r| self.orbit(r).energy, r).1
    }

    /// The radius of the innermost stable circular orbit, where `dE/dr = 0`: bisection between
    /// the horizon (below it `E` falls outwards, or no orbit exists) and `12 M` (beyond every
    /// prograde ISCO, where `E` rises), to the last bit.
    pub fn isco(&self) -> f64 {
        let (m, a, q) = (self.mass, self.spin, self.charge);
        let mut inner = m + (m * m - a * a - q * q).max(0.0).sqrt();
        let mut outer = 12.0 * m;
        while outer - inner > 4.0 * f64::EPSILON * outer {
            let mid = 0.5 * (inner + outer);
            if self.energy_slope(mid) > 0.0 {
                outer = mid;
            } else {
                inner = mid;
            }
        }
        outer
    }

    /// The radius of the circular photon orbit turning this way, inside which no circular
    /// geodesic is timelike: the root of `r² − 3Mr + 2Q² + 2a√(Mr − Q²)` (`a` along the
    /// orbits' sense; Bardeen, Press & Teukolsky 1972 eq. 2.18 with the charge), which is
    /// negative at the horizon and not below zero at `4M`, by bisection to the last bit.
    pub fn photon_orbit(&self) -> f64 {
        let (m, a, q2) = (self.mass, self.spin, self.charge * self.charge);
        let f = |r: f64| r * r - 3.0 * m * r + 2.0 * q2 + 2.0 * a * (m * r - q2).max(0.0).sqrt();
        let (mut inner, mut outer) = (m + (m * m - a * a - q2).max(0.0).sqrt(), 4.0 * m);
        while outer - inner > 4.0 * f64::EPSILON * outer {
            let mid = 0.5 * (inner + outer);
            if f(mid) < 0.0 {
                inner = mid;
            } else {
                outer = mid;
            }
        }
        outer
    }

    /// The world radius, in the equatorial plane of the tracer's chart, of Boyer–Lindquist
    /// radius `r`: `√(r² + a²)` (the spheroidal radius's ellipse meets the plane there).
    pub fn world_radius(&self, r: f64) -> f64 {
        (r * r + self.spin * self.spin).sqrt()
    }

    /// Boyer–Lindquist radius at world radius `rho` in the equatorial plane (inverse of
    /// [`world_radius`](Self::world_radius)).
    pub fn radius_at(&self, rho: f64) -> f64 {
        (rho * rho - self.spin * self.spin).max(0.0).sqrt()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::analytic::{kerr_isco, kerr_orbit_energy};

    #[test]
    fn schwarzschild_isco_is_six_masses_with_energy_root_eight_ninths() {
        let orbits = CircularOrbits::new(1.5, 0.0, 0.0);
        let isco = orbits.isco();
        assert!((isco - 9.0).abs() < 1e-12, "{isco}");
        let o = orbits.orbit(isco);
        assert!((o.energy - (8.0f64 / 9.0).sqrt()).abs() < 1e-14);
        // L = 2√3 M, Ω = 1/(6√6 M).
        assert!((o.angular_momentum - 2.0 * 3.0f64.sqrt() * 1.5).abs() < 1e-12);
        assert!((o.omega - 1.0 / (6.0 * 6.0f64.sqrt() * 1.5)).abs() < 1e-14);
    }

    #[test]
    fn kerr_orbits_match_bardeen_press_teukolsky() {
        for a in [0.3, 0.9, 0.998, -0.6] {
            let orbits = CircularOrbits::new(1.0, a, 0.0);
            let isco = orbits.isco();
            assert!((isco - kerr_isco(1.0, a.abs())).abs() < 1e-10, "a = {a}: {isco}");
            for r in [isco, 7.0, 30.0] {
                let o = orbits.orbit(r);
                assert!((o.energy - kerr_orbit_energy(1.0, a.abs(), r)).abs() < 1e-13, "a = {a}, r = {r}");
                let omega = 1.0 / (r.powf(1.5) + a.abs());
                assert!((o.omega - a.signum() * omega).abs() < 1e-15);
            }
        }
    }

    /// Retrograde orbits: `Ω = −√M/(r^{3/2} − a√M)` (Bardeen, Press & Teukolsky 1972 eq. 2.16,
    /// lower sign), the ISCO at 9M and the photon orbit at 4M for an extremal hole, 6M and 3M
    /// without spin, and prograde photon orbits `2M(1 + cos(⅔ arccos(∓a/M)))` (eq. 2.18).
    #[test]
    fn retrograde_orbits_and_photon_orbits_match_bardeen_press_teukolsky() {
        for a in [0.0, 0.5, 0.9, 1.0, -0.7] {
            let prograde = CircularOrbits::new(1.0, a, 0.0);
            let retrograde = prograde.reversed();
            assert!(!prograde.is_retrograde() && retrograde.is_retrograde() == (a != 0.0));
            let r = 7.0f64;
            let omega = -a.signum() / (r.powf(1.5) - a.abs());
            let o = retrograde.orbit(r);
            assert!((o.omega - omega).abs() < 1e-15, "a = {a}: Ω {} vs {omega}", o.omega);
            assert!(o.angular_momentum * o.omega > 0.0, "L turns as Ω does");
            for (orbits, sign) in [(prograde, -1.0), (retrograde, 1.0)] {
                let exact = 2.0 * (1.0 + ((sign * a.abs()).acos() * 2.0 / 3.0).cos());
                let photon = orbits.photon_orbit();
                assert!((photon - exact).abs() < 1e-9, "a = {a}, sign {sign}: {photon} vs {exact}");
            }
        }
        let extremal = CircularOrbits::new(1.0, 1.0, 0.0).reversed();
        assert!((extremal.isco() - 9.0).abs() < 1e-9 && (extremal.photon_orbit() - 4.0).abs() < 1e-9);
        assert!(CircularOrbits::new(1.0, 0.9, 0.0).reversed().orbit(3.0f64).u_t.is_nan(), "inside the photon orbit");
    }

    #[test]
    fn extremal_reissner_nordstrom_isco_is_four_masses() {
        // A(r) = (1 − M/r)²: E² = A²/(A − rA'/2) has its minimum at r = 4M.
        let isco = CircularOrbits::new(1.0, 0.0, 1.0).isco();
        assert!((isco - 4.0).abs() < 1e-9, "{isco}");
    }

    #[test]
    fn the_first_law_of_circular_orbits_holds() {
        // dE = Ω dL along the family of circular geodesics (Bardeen 1970), with the charge too.
        let orbits = CircularOrbits::new(1.0, 0.6, 0.5);
        for r in [orbits.isco() * 1.01, 5.0, 11.0] {
            let de = first_derivative(|r| orbits.orbit(r).energy, r).1;
            let dl = first_derivative(|r| orbits.orbit(r).angular_momentum, r).1;
            let omega = orbits.orbit(r).omega;
            assert!((de - omega * dl).abs() < 1e-14, "r = {r}: {de} vs {}", omega * dl);
        }
    }

    #[test]
    fn world_and_boyer_lindquist_radii_invert() {
        let orbits = CircularOrbits::new(1.0, 0.9, 0.0);
        assert!((orbits.radius_at(orbits.world_radius(3.7)) - 3.7).abs() < 1e-14);
    }
}

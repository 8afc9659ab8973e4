//! Circular equatorial orbits about a hole of Kerr's family in closed form: the exact worldline,
//! and a start for the integrator.
//!
//! On the orbit of Boyer–Lindquist radius `r` a body turns at `Ω = ±w/(r² ± a w)`,
//! `w = √(Mr − Q²)` (Kerr: `±√M/(r^{3/2} ± a√M)`, Bardeen, Press & Teukolsky 1972 eq. 2.16;
//! upper signs prograde), with `u = u^t (∂_t + Ω ∂_φ)` ([`CircularOrbits`]). The hole's
//! outgoing Kerr–Schild `t` and `φ` differ from Boyer–Lindquist's by functions of `r` alone,
//! so in its chart the body turns rigidly at `Ω` too: `x + iy = (r − ia) e^{iφ}`, `z = 0`,
//! `φ = φ₀ + Ω t`, `t = u^t τ`, and `u = u^t (1, −Ω y, Ω x, 0)`.

use super::Event;
use crate::disk::{CircularOrbits, Orbit};
use crate::geodesic::State;
use crate::metric::{KerrNewman, Metric, Spacetime};
use crate::tensor::{contract, Vector4};

/// Which way an orbit turns relative to the hole's spin (prograde turns counter-clockwise
/// about +z where the hole has no spin).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Direction {
    Prograde,
    Retrograde,
}

/// Why there is no circular orbit as asked.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum OrbitError {
    /// The spacetime is not a hole of Kerr's family with a mass (it has no such orbits, or
    /// none that anything here finds).
    NoCircularOrbits { spacetime: &'static str },
    /// The radius is not a finite number.
    RadiusNotFinite { radius: f64 },
    /// At or inside the photon orbit turning that way no circular orbit is timelike.
    InsidePhotonOrbit { radius: f64, photon_orbit: f64, direction: Direction },
}

impl std::fmt::Display for OrbitError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            OrbitError::NoCircularOrbits { spacetime } => write!(
                f,
                "spacetime \"{spacetime}\" has no circular orbits to follow: they are those of a black hole \
                 (schwarzschild, kerr, reissner-nordstrom, kerr-newman) with a mass"
            ),
            OrbitError::RadiusNotFinite { radius } => write!(f, "orbit radius {radius} is not a finite number"),
            OrbitError::InsidePhotonOrbit { radius, photon_orbit, direction } => {
                let way = match direction {
                    Direction::Prograde => "prograde",
                    Direction::Retrograde => "retrograde",
                };
                write!(
                    f,
                    "no {way} circular orbit at radius {radius}: only light circles at the photon orbit, radius \
                     {photon_orbit}, and nothing inside it; a body's orbit needs radius > {photon_orbit}"
                )
            }
        }
    }
}

impl std::error::Error for OrbitError {}

/// One circular equatorial geodesic (see the module documentation), at `t = 0` (`τ = 0`) at
/// azimuth `phase` of the hole's chart.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CircularOrbit {
    hole: KerrNewman,
    radius: f64,
    phase: f64,
    orbit: Orbit<f64>,
}

impl CircularOrbit {
    /// The orbit of Boyer–Lindquist radius `radius` (areal without spin) of `orbits`, at
    /// azimuth `phase` at `t = 0`; refused at or inside the photon orbit.
    pub fn new(orbits: &CircularOrbits, radius: f64, phase: f64) -> Result<Self, OrbitError> {
        if !radius.is_finite() {
            return Err(OrbitError::RadiusNotFinite { radius });
        }
        let photon_orbit = orbits.photon_orbit();
        let orbit = orbits.orbit(radius);
        if !(radius > photon_orbit && orbit.u_t.is_finite() && orbit.u_t > 0.0) {
            let direction = if orbits.is_retrograde() { Direction::Retrograde } else { Direction::Prograde };
            return Err(OrbitError::InsidePhotonOrbit { radius, photon_orbit, direction });
        }
        Ok(Self { hole: orbits.hole(), radius, phase, orbit })
    }

    /// The orbit of radius `radius` turning `direction` about the hole `spacetime` is.
    pub fn of_spacetime(
        spacetime: &Spacetime,
        radius: f64,
        direction: Direction,
        phase: f64,
    ) -> Result<Self, OrbitError> {
        let orbits = spacetime
            .capabilities()
            .circular_orbits()
            .ok_or(OrbitError::NoCircularOrbits { spacetime: spacetime.name() })?;
        let orbits = match direction {
            Direction::Prograde => orbits,
            Direction::Retrograde => orbits.reversed(),
        };
        Self::new(&orbits, radius, phase)
    }

    /// Boyer–Lindquist radius.
    pub fn radius(&self) -> f64 {
        self.radius
    }

    /// `Ω = dφ/dt`, positive counter-clockwise about +z.
    pub fn angular_velocity(&self) -> f64 {
        self.orbit.omega
    }

    /// `E = −u_t`, per unit rest mass.
    pub fn energy(&self) -> f64 {
        self.orbit.energy
    }

    /// `L_z = u_φ`, per unit rest mass, positive counter-clockwise about +z.
    pub fn angular_momentum(&self) -> f64 {
        self.orbit.angular_momentum
    }

    /// `u^t = dt/dτ`.
    pub fn time_dilation(&self) -> f64 {
        self.orbit.u_t
    }

    /// One revolution in coordinate time, `2π/|Ω|`.
    pub fn period(&self) -> f64 {
        std::f64::consts::TAU / self.orbit.omega.abs()
    }

    /// The body's event at coordinate time `t`.
    pub fn event_at_time(&self, t: f64) -> Event {
        let (s, c) = (self.phase + self.orbit.omega * t).sin_cos();
        let (r, a) = (self.radius, self.hole.spin);
        // (r − ia)(cos φ + i sin φ).
        let (x, y) = (r * c + a * s, r * s - a * c);
        let point: Vector4 = [t, x, y, 0.0];
        let (u_t, omega) = (self.orbit.u_t, self.orbit.omega);
        let u = [u_t, -u_t * omega * y, u_t * omega * x, 0.0];
        let p = contract(&self.hole.metric(&point), &u);
        Event { tau: t / u_t, x: point, u, p }
    }

    /// The body's event at proper time `tau`.
    pub fn event_at_proper_time(&self, tau: f64) -> Event {
        self.event_at_time(tau * self.orbit.u_t)
    }

    /// The state at `t = 0`, in the hole's own chart: a start for [`super::Worldline::integrate`].
    pub fn start(&self) -> State {
        let e = self.event_at_time(0.0);
        State { x: e.x, p: e.p }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_orbit_is_a_unit_timelike_geodesic_with_its_constants() {
        for spacetime in
            [Spacetime::schwarzschild(1.0), Spacetime::kerr(1.0, 0.9), Spacetime::kerr_newman(1.0, -0.5, 0.4)]
        {
            let spacetime = spacetime.expect("valid");
            for direction in [Direction::Prograde, Direction::Retrograde] {
                let orbit = CircularOrbit::of_spacetime(&spacetime, 9.0, direction, 0.3).expect("outside");
                let hole = orbit.hole;
                let s = orbit.event_at_proper_time(17.0);
                assert!((2.0 * hole.hamiltonian(&s.x, &s.p) + 1.0).abs() < 1e-13, "unit rest mass");
                assert!((-s.p[0] - orbit.energy()).abs() < 1e-13, "E");
                assert!((s.x[1] * s.p[2] - s.x[2] * s.p[1] - orbit.angular_momentum()).abs() < 1e-12, "L");
                // A geodesic: the momentum does not change along it, dp/dτ = 0 in (t, r, φ)
                // (the chart's Cartesian dp_i/dτ is the rotation of p_i at Ω).
                let (dx, dp) = hole.geodesic_rhs(&s.x, &s.p);
                assert!((0..4).all(|k| (dx[k] - s.u[k]).abs() < 1e-13), "dx/dτ = u");
                let omega_ut = orbit.angular_velocity() * orbit.time_dilation();
                assert!((dp[1] + omega_ut * s.p[2]).abs() < 1e-13 && (dp[2] - omega_ut * s.p[1]).abs() < 1e-13);
                assert!(dp[3].abs() < 1e-13 && dp[0] == 0.0);
                let sense = match direction {
                    Direction::Prograde => 1.0,
                    Direction::Retrograde => -1.0,
                };
                let spin_sense = if hole.spin < 0.0 { -1.0 } else { 1.0 };
                assert!(orbit.angular_velocity() * sense * spin_sense > 0.0, "{direction:?} about {spacetime:?}");
            }
        }
    }

    #[test]
    fn no_orbit_inside_the_photon_orbit_or_without_a_hole() {
        let kerr = Spacetime::kerr(1.0, 0.9).expect("valid");
        let err = CircularOrbit::of_spacetime(&kerr, 3.0, Direction::Retrograde, 0.0).expect_err("inside 3.9");
        assert!(err.to_string().contains("no retrograde circular orbit at radius 3"), "{err}");
        assert!(CircularOrbit::of_spacetime(&kerr, 3.0, Direction::Prograde, 0.0).is_ok(), "prograde 1.56");
        let flat = Spacetime::Minkowski(crate::metric::Minkowski);
        let none = CircularOrbit::of_spacetime(&flat, 6.0, Direction::Prograde, 0.0).expect_err("flat");
        assert!(none.to_string().contains("\"minkowski\" has no circular orbits"), "{none}");
        assert!(CircularOrbit::of_spacetime(&kerr, f64::NAN, Direction::Prograde, 0.0).is_err());
    }
}

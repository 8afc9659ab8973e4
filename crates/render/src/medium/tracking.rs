//! Tracking: sampling where light next interacts with a heterogeneous medium (delta tracking),
//! and estimating how much of it gets through (ratio tracking), by adding fictitious "null"
//! particles that fill the medium up to a majorant `σ̄ ≥ σ_t`, so that free flights can be drawn
//! as in a homogeneous medium of extinction `σ̄` (Woodcock et al. 1965; Novák et al. 2014,
//! "Residual ratio tracking for estimating attenuation in participating media", §3–4;
//! pbrt-v4 §14.1–14.2).
//!
//! # Curved rays
//!
//! A geodesic is followed as a chain of straight chords, and tracking runs chord by chord with
//! its state kept between them: a free flight draws an optical depth `τ ~ Exp(1)` once, and each
//! chord consumes `∫ σ̄ ds` of it until it runs out at a tentative collision. Since the
//! exponential distribution has no memory, this samples the same collisions as one straight
//! segment of the chain's total length would, and it uses no random number at a chord's end
//! (so a path's random numbers do not depend on how finely its geodesic is stepped).
//!
//! Lengths are the medium's rest-frame lengths `s` (the optical depth is `dτ = σ_t ds`, with
//! `ds = (−p·u) dλ` along the geodesic of affine parameter `λ` through gas of 4-velocity `u`).
//! A [`Chord`] gives both its length in the world's coordinates (where density is looked up) and
//! its rest-frame length; rest-frame length is taken as uniform along a chord.

use super::majorant::MajorantSegment;
use super::Medium;
use crate::geometry::Vec3;

/// One straight piece of a ray: `origin + t·dir`, `t ∈ [0, length]`, `dir` a unit vector of the
/// world's coordinates, and `rest_length` the medium's rest-frame length of the piece.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Chord {
    pub origin: Vec3,
    pub dir: Vec3,
    pub length: f64,
    pub rest_length: f64,
}

impl Chord {
    /// A chord through a medium at rest in flat space, where the two lengths agree.
    pub fn flat(origin: Vec3, dir: Vec3, length: f64) -> Self {
        Self { origin, dir, length, rest_length: length }
    }

    /// Rest-frame length per unit of `t`.
    fn stretch(&self) -> f64 {
        if self.length > 0.0 {
            self.rest_length / self.length
        } else {
            0.0
        }
    }

    pub fn at(&self, t: f64) -> Vec3 {
        self.origin + self.dir * t
    }
}

/// Where delta tracking stopped on a chord: `t` along it, `rest_distance` the rest-frame length
/// from its origin, `point` the world point.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Collision {
    pub t: f64,
    pub rest_distance: f64,
    pub point: Vec3,
}

/// What happened to light on a chord.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Event {
    /// Scattered at the collision: the path goes on in a direction drawn from the phase function.
    Scatter(Collision),
    /// Absorbed at the collision: the path ends, gathering the medium's emission there divided by
    /// its absorption coefficient (the absorption estimator of emission).
    Absorb(Collision),
    /// Went through the chord; the free flight goes on along the next one.
    Passed,
}

/// An optical depth drawn from `Exp(1)` with the uniform number `u ∈ [0, 1)`.
fn exponential(u: f64) -> f64 {
    -(1.0 - u).ln()
}

/// The tentative collisions along a chord: walks the majorant intervals (extinction bounds per
/// unit rest-frame length), spending `budget` of optical depth, and calls `collide(t, σ̄)` at each
/// point where it runs out; `collide` returns `Some` to stop there, or the next budget.
fn tentative_collisions<R>(
    budget: &mut f64,
    chord: &Chord,
    walk: impl Iterator<Item = MajorantSegment>,
    mut collide: impl FnMut(f64, f64) -> Result<f64, R>,
) -> Option<R> {
    let stretch = chord.stretch();
    for segment in walk {
        // Optical depth per unit t.
        let rate = segment.sigma_max * stretch;
        if !(rate > 0.0) {
            continue;
        }
        let mut t = segment.t_min;
        loop {
            let depth_left = rate * (segment.t_max - t);
            if *budget >= depth_left {
                *budget -= depth_left;
                break;
            }
            t += *budget / rate;
            match collide(t, segment.sigma_max) {
                Ok(next_budget) => *budget = next_budget,
                Err(stop) => return Some(stop),
            }
        }
    }
    None
}

/// A free flight by delta tracking (Woodcock et al. 1965), three-way at each tentative
/// collision: absorbed with probability `σ_a/σ̄`, scattered with `σ_s/σ̄`, a null collision
/// otherwise (pbrt-v4 §14.2.2). The flight's events follow the medium's real collisions exactly.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FreeFlight {
    /// Optical depth (of the majorant) left before the next tentative collision.
    budget: f64,
}

impl FreeFlight {
    /// A flight of optical depth `−ln(1 − u)`.
    pub fn start(u: f64) -> Self {
        Self { budget: exponential(u) }
    }

    /// Tracks the flight along `chord`, whose majorant intervals are `walk` (from
    /// [`Medium::majorants`]), with uniform numbers from `uniform`.
    pub fn track(
        &mut self,
        medium: &Medium,
        chord: &Chord,
        walk: impl Iterator<Item = MajorantSegment>,
        uniform: &mut impl FnMut() -> f64,
    ) -> Event {
        let stretch = chord.stretch();
        let stop = tentative_collisions(&mut self.budget, chord, walk, |t, sigma_max| {
            let point = chord.at(t);
            let c = medium.coefficients(point);
            let collision = Collision { t, rest_distance: t * stretch, point };
            let u = uniform() * sigma_max;
            if u < c.absorption {
                Err(Event::Absorb(collision))
            } else if u < c.absorption + c.scattering {
                Err(Event::Scatter(collision))
            } else {
                Ok(exponential(uniform()))
            }
        });
        stop.unwrap_or(Event::Passed)
    }
}

/// A transmittance estimate by ratio tracking (Novák et al. 2014, eq. 12): at each tentative
/// collision the estimate is multiplied by the probability `1 − σ_t/σ̄` of a null collision.
/// Unbiased, and never negative since `σ_t ≤ σ̄`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RatioTracker {
    budget: f64,
    transmittance: f64,
}

impl RatioTracker {
    /// An estimate of 1 so far, with a first optical depth `−ln(1 − u)`.
    pub fn start(u: f64) -> Self {
        Self { budget: exponential(u), transmittance: 1.0 }
    }

    /// Multiplies the estimate by that of `chord`'s transmittance.
    pub fn track(
        &mut self,
        medium: &Medium,
        chord: &Chord,
        walk: impl Iterator<Item = MajorantSegment>,
        uniform: &mut impl FnMut() -> f64,
    ) {
        let transmittance = &mut self.transmittance;
        let stop = tentative_collisions(&mut self.budget, chord, walk, |t, sigma_max| {
            *transmittance *= 1.0 - medium.coefficients(chord.at(t)).extinction() / sigma_max;
            // Nothing gets through: no point tracking further.
            if *transmittance <= 0.0 {
                Err(())
            } else {
                Ok(exponential(uniform()))
            }
        });
        if stop.is_some() {
            self.transmittance = 0.0;
        }
    }

    /// The estimate of the transmittance along the chords tracked so far.
    pub fn transmittance(&self) -> f64 {
        self.transmittance
    }
}

#[cfg(test)]
mod tests {
    use super::super::reference;
    use super::super::test_media::{cloud, uniform};
    use super::*;
    use crate::sampling::Rng;

    /// Tracks a flight along `chords` in turn; the rest-frame distance of its first collision
    /// (absorption or scattering), or `None` if it got through them all.
    fn first_collision(medium: &Medium, chords: &[Chord], rng: &mut Rng) -> Option<f64> {
        let mut flight = FreeFlight::start(rng.next_f64());
        let mut before = 0.0;
        for chord in chords {
            let walk = medium.majorants(chord);
            match flight.track(medium, chord, walk, &mut || rng.next_f64()) {
                Event::Scatter(c) | Event::Absorb(c) => return Some(before + c.rest_distance),
                Event::Passed => before += chord.rest_length,
            }
        }
        None
    }

    /// The Kolmogorov–Smirnov statistic `√n · sup |F_n − F|` of `samples` against the CDF `cdf`.
    fn ks(mut samples: Vec<f64>, cdf: impl Fn(f64) -> f64) -> f64 {
        samples.sort_by(f64::total_cmp);
        let n = samples.len() as f64;
        let sup = samples.iter().enumerate().fold(0.0f64, |d, (i, &x)| {
            let f = cdf(x);
            d.max((f - i as f64 / n).abs()).max(((i + 1) as f64 / n - f).abs())
        });
        sup * n.sqrt()
    }

    /// P(√n D > 1.95) ≈ 0.001 (Kolmogorov's distribution).
    const KS_BOUND: f64 = 1.95;

    #[test]
    fn homogeneous_free_flights_are_exponential_in_the_extinction() {
        // σ_t = 1.5 + 0.5 = 2; the majorant is exact, so every collision is real.
        let medium = uniform(1.5, 0.5);
        let mut rng = Rng::new(5);
        let chord = [Chord::flat(Vec3::ZERO, Vec3::X, 1e9)];
        let n = 20_000;
        let distances: Vec<f64> = (0..n).map(|_| first_collision(&medium, &chord, &mut rng).unwrap()).collect();
        let mean = distances.iter().sum::<f64>() / n as f64;
        // Exp(2): mean ½, standard deviation ½, so the mean's σ is ½/√n.
        assert!((mean - 0.5).abs() < 4.0 * 0.5 / (n as f64).sqrt(), "mean {mean}");
        let d = ks(distances, |x| 1.0 - (-2.0 * x).exp());
        assert!(d < KS_BOUND, "KS {d}");
    }

    #[test]
    fn absorption_and_scattering_split_as_their_coefficients() {
        let medium = uniform(1.5, 0.5);
        let mut rng = Rng::new(6);
        let chord = Chord::flat(Vec3::ZERO, Vec3::X, 1e9);
        let n = 20_000;
        let absorbed = (0..n)
            .filter(|_| {
                let mut flight = FreeFlight::start(rng.next_f64());
                let walk = medium.majorants(&chord);
                matches!(flight.track(&medium, &chord, walk, &mut || rng.next_f64()), Event::Absorb(_))
            })
            .count();
        let p = absorbed as f64 / n as f64;
        let sigma = (0.75 * 0.25 / n as f64).sqrt();
        assert!((p - 0.75).abs() < 4.0 * sigma, "P(absorb) = {p}");
    }

    /// The curved-ray property: a flight tracked across 200 short chords, each with its own
    /// stretch between world and rest-frame length, collides as on one segment of the same
    /// rest-frame length, in a heterogeneous medium (whose null collisions then cross chords).
    #[test]
    fn a_budget_spent_across_chords_collides_as_on_one_segment() {
        let medium = cloud();
        let start = Vec3::new(-1.2, -0.1, 0.2);
        let dir = Vec3::new(1.0, 0.1, -0.05).normalize();
        let total = 2.4;
        let one = [Chord::flat(start, dir, total)];
        let pieces = 200;
        let mut chords = Vec::new();
        for i in 0..pieces {
            let length = total / pieces as f64;
            // The rest-frame length is the same on both sides; only its spread differs.
            let stretch = if i % 2 == 0 { 0.5 } else { 1.5 };
            let origin = start + dir * (length * i as f64);
            chords.push(Chord { origin, dir, length, rest_length: length * stretch });
        }
        let (mut rng_one, mut rng_many) = (Rng::new(21), Rng::new(22));
        let n = 20_000;
        let one_distances: Vec<f64> =
            (0..n).map(|_| first_collision(&medium, &one, &mut rng_one).unwrap_or(f64::INFINITY)).collect();
        let many_distances: Vec<f64> =
            (0..n).map(|_| first_collision(&medium, &chords, &mut rng_many).unwrap_or(f64::INFINITY)).collect();
        // Two-sample KS on the rest-frame distance (infinite: through), at a stated level
        // (√(n/2) D > 1.95 with probability 0.001).
        let mut all: Vec<f64> = one_distances.iter().chain(&many_distances).copied().collect();
        all.sort_by(f64::total_cmp);
        let cdf = |v: &[f64], x: f64| v.iter().filter(|&&d| d <= x).count() as f64 / v.len() as f64;
        let d = all
            .iter()
            .step_by(97)
            .map(|&x| (cdf(&one_distances, x) - cdf(&many_distances, x)).abs())
            .fold(0.0, f64::max);
        assert!(d * (n as f64 / 2.0).sqrt() < KS_BOUND, "two-sample KS {d}");
        // And both pass as often as the exact transmittance says, within 4σ.
        let exact = reference::transmittance(&medium, &one[0], 20_000);
        for distances in [&one_distances, &many_distances] {
            let through = distances.iter().filter(|d| d.is_infinite()).count() as f64 / n as f64;
            let sigma = (exact * (1.0 - exact) / n as f64).sqrt();
            assert!((through - exact).abs() < 4.0 * sigma, "through {through}, exact {exact}");
        }
    }

    /// Ratio tracking's mean over 4000 estimates, per seed, against the dense quadrature: each
    /// mean within 4 of its standard errors (a z-score bound that a correct estimator exceeds
    /// with probability 6·10⁻⁵ per seed), across chords split or whole.
    #[test]
    fn ratio_tracking_matches_the_quadrature() {
        let medium = cloud();
        for (seed, (start, dir)) in [
            (Vec3::new(-1.2, 0.0, 0.0), Vec3::X),
            (Vec3::new(-1.0, -0.8, 0.3), Vec3::new(1.0, 0.7, -0.2).normalize()),
            (Vec3::new(0.1, 1.1, -0.9), Vec3::new(-0.2, -1.0, 0.9).normalize()),
        ]
        .into_iter()
        .enumerate()
        {
            let chord = Chord::flat(start, dir, 2.5);
            let exact = reference::transmittance(&medium, &chord, 20_000);
            assert!(0.05 < exact && exact < 0.95, "a test that can tell: T = {exact}");
            let halves = [Chord::flat(start, dir, 1.0), Chord::flat(start + dir, dir, 1.5)];
            for chords in [&[chord][..], &halves[..]] {
                let mut rng = Rng::new(100 + seed as u64);
                let n = 4000;
                let estimates: Vec<f64> = (0..n)
                    .map(|_| {
                        let mut tracker = RatioTracker::start(rng.next_f64());
                        for c in chords {
                            tracker.track(&medium, c, medium.majorants(c), &mut || rng.next_f64());
                        }
                        tracker.transmittance()
                    })
                    .collect();
                let mean = estimates.iter().sum::<f64>() / n as f64;
                let var = estimates.iter().map(|e| (e - mean).powi(2)).sum::<f64>() / (n - 1) as f64;
                let z = (mean - exact) / (var / n as f64).sqrt();
                assert!(z.abs() < 4.0, "seed {seed}: mean {mean}, exact {exact}, z {z}");
            }
        }
    }

    /// In the noise cloud (one constant majorant, many null collisions) delta tracking passes,
    /// and ratio tracking estimates, the quadrature's transmittance, each within 4σ.
    #[test]
    fn delta_and_ratio_tracking_agree_with_the_quadrature_in_noise() {
        let medium = super::super::test_media::noise_cloud();
        let chord = Chord::flat(Vec3::new(-2.0, 0.3, 0.1), Vec3::X, 4.0);
        let exact = reference::transmittance(&medium, &chord, 20_000);
        let mut rng = Rng::new(9);
        let n = 20_000;
        let through =
            (0..n).filter(|_| first_collision(&medium, &[chord], &mut rng).is_none()).count() as f64 / n as f64;
        let sigma = (exact * (1.0 - exact) / n as f64).sqrt();
        assert!((through - exact).abs() < 4.0 * sigma, "delta {through}, exact {exact}");
        let estimates: Vec<f64> = (0..n)
            .map(|_| {
                let mut tracker = RatioTracker::start(rng.next_f64());
                tracker.track(&medium, &chord, medium.majorants(&chord), &mut || rng.next_f64());
                tracker.transmittance()
            })
            .collect();
        let mean = estimates.iter().sum::<f64>() / n as f64;
        let var = estimates.iter().map(|e| (e - mean).powi(2)).sum::<f64>() / (n - 1) as f64;
        assert!((mean - exact).abs() < 4.0 * (var / n as f64).sqrt(), "ratio {mean}, exact {exact}");
    }
}

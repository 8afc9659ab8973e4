//! One pixel's progressive estimate: the shrinking gather radius and the accumulated flux of
//! stochastic progressive photon mapping (Hachisuka & Jensen 2009, eqs. 6–9; pbrt-v3 §16.2.5).
//!
//! After an iteration that found `M` photons in the radius `R` (flux sum `Φ`), with `N` photons
//! kept so far, only a fraction `α` of the new ones is kept: `N' = N + αM`, the radius shrinks to
//! keep the density, `R' = R √(N' / (N + M))`, and the flux is scaled to the smaller disk:
//! `τ' = (τ + Φ) (R'/R)²`. With `α < 1` the radius goes to zero slowly enough that the photon
//! count in it still grows without bound, so the estimate is consistent.

use crate::rgb::Rgb;
use std::f64::consts::PI;

/// Fraction of new photons kept per iteration; 2/3 as recommended by Knaus & Zwicker (2011).
const ALPHA: f64 = 2.0 / 3.0;

#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) struct PixelEstimate {
    /// Set when the pixel first has a visible point.
    radius: Option<f64>,
    /// Photons kept, `N`.
    kept: f64,
    /// Accumulated flux `τ` (camera throughput included).
    tau: [f64; 3],
    /// Sum of the radiance camera paths met directly (emitters, sky), filter weights included.
    emitted: [f64; 3],
    /// Sum of the filter weights of the finished iterations.
    weight: f64,
}

impl PixelEstimate {
    pub fn new() -> Self {
        Self { radius: None, kept: 0.0, tau: [0.0; 3], emitted: [0.0; 3], weight: 0.0 }
    }

    /// The gather radius; `None` before the pixel's first visible point.
    pub fn radius(&self) -> Option<f64> {
        self.radius
    }

    /// Adds a finished iteration: the direct radiance `emitted` (filter weight applied), the
    /// filter weight `weight`, and the flux sum `flux` of the `found` photons within `radius`
    /// (the pixel's radius, or its initial radius at its first visible point).
    pub fn add_iteration(&mut self, emitted: Rgb, weight: f64, (radius, flux): (f64, [f64; 3]), found: u64) {
        for (e, c) in self.emitted.iter_mut().zip(emitted.to_array()) {
            *e += f64::from(c);
        }
        self.weight += weight;
        if found == 0 {
            return;
        }
        let old = *self.radius.get_or_insert(radius);
        let m = found as f64;
        let kept = self.kept + ALPHA * m;
        let radius = old * (kept / (self.kept + m)).sqrt();
        let shrink = (radius / old).powi(2);
        for (t, f) in self.tau.iter_mut().zip(flux) {
            *t = (*t + f) * shrink;
        }
        (self.kept, self.radius) = (kept, Some(radius));
    }

    /// The estimate's exact state: radius (0 before the first visible point; radii are > 0),
    /// photons kept, flux, emitted radiance and filter weight.
    pub fn to_array(self) -> [f64; 9] {
        let [t0, t1, t2] = self.tau;
        let [e0, e1, e2] = self.emitted;
        [self.radius.unwrap_or(0.0), self.kept, t0, t1, t2, e0, e1, e2, self.weight]
    }

    /// The estimate whose [state](Self::to_array) is `a`.
    pub fn from_array(a: [f64; 9]) -> Self {
        let radius = Some(a[0]).filter(|&r| r > 0.0);
        Self { radius, kept: a[1], tau: [a[2], a[3], a[4]], emitted: [a[5], a[6], a[7]], weight: a[8] }
    }

    /// The pixel's radiance after the finished iterations with `photons` photons each:
    /// `L = Σ Le / W + τ / (W · photons · π R²)`, `W` the filter weights' sum; `None` before
    /// the first iteration.
    pub fn radiance(&self, photons: u64) -> Option<Rgb> {
        if self.weight == 0.0 {
            return None;
        }
        let gathered = |k: usize| match self.radius {
            Some(r) => self.tau[k] / (photons as f64 * PI * r * r),
            None => 0.0,
        };
        let [r, g, b] = std::array::from_fn(|k| (self.emitted[k] + gathered(k)) / self.weight);
        Some(Rgb::new(r as f32, g as f32, b as f32))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::sampling::Rng;

    #[test]
    fn a_uniform_photon_density_is_estimated_as_the_radius_shrinks() {
        // Each iteration scatters 4000 photons of flux 1 uniformly over the square [−1, 1]²:
        // irradiance 4000 / 4 per unit area and iteration, i.e. 1/4 per photon and unit area.
        let (photons, iterations) = (4000u64, 400);
        let mut pixel = PixelEstimate::new();
        let mut rng = Rng::new(9);
        for _ in 0..iterations {
            let radius = pixel.radius().unwrap_or(0.2);
            let found = (0..photons)
                .filter(|_| {
                    let [x, y] = rng.next_2d().map(|u| 2.0 * u - 1.0);
                    x * x + y * y < radius * radius
                })
                .count() as u64;
            pixel.add_iteration(Rgb::splat(0.5), 1.0, (radius, [found as f64; 3]), found);
        }
        let radius = pixel.radius().unwrap();
        assert!(radius < 0.1, "radius {radius} must shrink");
        let l = pixel.radiance(photons).unwrap();
        // 0.5 emitted + 0.25; the kept photon count is ~ 10⁴, so the relative error is ~1 %.
        assert!((l.x - 0.75).abs() < 0.25 * 0.04, "radiance {l}");
        assert!(PixelEstimate::new().radiance(10).is_none());
    }
}

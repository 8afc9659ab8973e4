//! Directions drawn from a sky in proportion to its luminance, for light that starts at infinity:
//! photons leaving the sky, as pbrt-v3 (§14.2.4, §16.2.4) emits them from infinite area lights.
//!
//! - a star field: its stars by flux (see [`StarDistribution`]) and its background uniformly, mixed
//!   by their powers, so that the density is the luminance over the total power everywhere;
//! - a panorama: a piecewise-constant distribution over its pixels (see [`EquirectDistribution`]);
//! - the smooth skies (constant, gradient, grid): uniformly over the sphere.
//!
//! A photon's power divides by the density of its direction, so any density that is positive where
//! the sky is bright gives an unbiased estimate; these make photon powers nearly equal.
//!
//! A [`SkyDistribution`] carries the sky it was built from, in the variant of that sky's kind: a
//! distribution cannot be used with another sky, nor a sky with another kind's distribution.

use super::{EquirectDistribution, Gradient, LatLongGrid, Sky, StarDistribution};
use crate::geometry::Vec3;
use crate::rgb::{luminance, Rgb};
use crate::sampling::{uniform_sphere, UNIFORM_SPHERE_PDF};
use std::f64::consts::PI;

/// Latitude × longitude cells of the quadrature that estimates a smooth sky's power.
const POWER_QUADRATURE: (usize, usize) = (64, 128);

/// How to draw directions from one sky, with that sky: one variant per kind of [`Sky`].
#[derive(Clone, Debug)]
pub enum SkyDistribution {
    /// [`Sky::Constant`]: uniformly over the sphere, which is exactly in proportion.
    Constant { radiance: Rgb, power: f64 },
    /// [`Sky::Gradient`]: uniformly over the sphere.
    Gradient { sky: Gradient, power: f64 },
    /// [`Sky::Grid`]: uniformly over the sphere.
    Grid { sky: LatLongGrid, power: f64 },
    /// [`Sky::Equirect`]: piecewise constant over the panorama's pixels.
    Image(EquirectDistribution),
    /// [`Sky::StarField`]: the stars by flux, the background uniformly.
    Stars {
        stars: StarDistribution,
        /// Probability of drawing from the background rather than from the stars.
        background: f64,
        power: f64,
    },
}

/// A direction the sky is seen in, its radiance, and its density per steradian.
#[derive(Clone, Copy, Debug)]
pub struct SkySample {
    pub direction: Vec3,
    pub radiance: Rgb,
    pub pdf: f64,
}

impl SkyDistribution {
    /// The distribution for `sky`, built once per render; it keeps a copy of the sky (sharing a
    /// panorama's image).
    pub fn new(sky: &Sky) -> Self {
        match sky {
            Sky::Equirect(e) => Self::Image(e.distribution()),
            Sky::StarField(s) => {
                let stars = s.distribution();
                let background = 4.0 * PI * f64::from(luminance(s.params().background));
                let power = background + stars.total_flux();
                let background = if power > 0.0 { background / power } else { 1.0 };
                Self::Stars { stars, background, power }
            }
            Sky::Constant(c) => Self::Constant { radiance: *c, power: 4.0 * PI * f64::from(luminance(*c)) },
            Sky::Gradient(g) => Self::Gradient { sky: *g, power: quadrature_power(|d| g.radiance(d)) },
            Sky::Grid(g) => Self::Grid { sky: *g, power: quadrature_power(|d| g.radiance(d)) },
        }
    }

    /// `∫ luminance dω` over the sphere: exact for constant skies, star fields and panoramas, a
    /// 64 × 128 quadrature for gradients and grids (it only shares photons out, so it need not be
    /// exact). 0 for a black sky, which emits nothing.
    pub fn power(&self) -> f64 {
        match self {
            Self::Constant { power, .. }
            | Self::Gradient { power, .. }
            | Self::Grid { power, .. }
            | Self::Stars { power, .. } => *power,
            Self::Image(d) => d.power(),
        }
    }

    /// The radiance of the sky in `direction` (as [`Sky::radiance`]).
    pub fn radiance(&self, direction: Vec3) -> Rgb {
        match self {
            Self::Constant { radiance, .. } => *radiance,
            Self::Gradient { sky, .. } => sky.radiance(direction),
            Self::Grid { sky, .. } => sky.radiance(direction),
            Self::Image(d) => d.sky().radiance(direction),
            Self::Stars { stars, .. } => stars.field().radiance(direction),
        }
    }

    /// A direction drawn with `u`; `None` where the distribution has nothing there.
    pub fn sample(&self, u: [f64; 3]) -> Option<SkySample> {
        let direction = match self {
            Self::Image(d) => d.sample([u[1], u[2]])?.0,
            Self::Stars { stars, background, .. } if u[0] >= *background => {
                stars.sample((u[0] - background) / (1.0 - background), [u[1], u[2]])?
            }
            // The background of a star field, and the smooth skies.
            Self::Stars { .. } | Self::Constant { .. } | Self::Gradient { .. } | Self::Grid { .. } => {
                uniform_sphere([u[1], u[2]])
            }
        };
        let pdf = self.pdf(direction);
        (pdf > 0.0).then(|| SkySample { direction, radiance: self.radiance(direction), pdf })
    }

    /// Density per steradian of `direction`.
    pub fn pdf(&self, direction: Vec3) -> f64 {
        match self {
            Self::Image(d) => d.pdf(direction),
            Self::Stars { stars, background, .. } => {
                background * UNIFORM_SPHERE_PDF + (1.0 - background) * stars.pdf(direction)
            }
            Self::Constant { .. } | Self::Gradient { .. } | Self::Grid { .. } => UNIFORM_SPHERE_PDF,
        }
    }
}

/// `∫ luminance dω` by the midpoint rule over equal-angle latitude–longitude cells.
fn quadrature_power(radiance: impl Fn(Vec3) -> Rgb) -> f64 {
    let (rows, columns) = POWER_QUADRATURE;
    let (d_theta, d_phi) = (PI / rows as f64, 2.0 * PI / columns as f64);
    let mut sum = 0.0;
    for i in 0..rows {
        let theta = (i as f64 + 0.5) * d_theta;
        let (sin, cos) = theta.sin_cos();
        for j in 0..columns {
            let phi = (j as f64 + 0.5) * d_phi;
            let direction = Vec3::new(sin * phi.cos(), cos, sin * phi.sin());
            sum += f64::from(luminance(radiance(direction))) * sin * d_theta * d_phi;
        }
    }
    sum
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::sampling::Rng;
    use crate::sky::{StarField, StarFieldParams};

    fn stars(background: f32) -> Sky {
        let params = StarFieldParams {
            density: 300.0,
            brightness: 1e-3,
            seed: 4,
            star_radius_deg: 0.3,
            background: Rgb::splat(background),
        };
        Sky::StarField(StarField::new(params).unwrap())
    }

    fn gradient() -> Sky {
        let (horizon, zenith, nadir) = (Rgb::splat(0.2), Rgb::new(1.0, 0.8, 0.5), Rgb::splat(0.05));
        Sky::Gradient(crate::sky::Gradient { horizon, zenith, nadir, frame: crate::sky::SkyFrame::Y_UP })
    }

    fn draws(sky: &Sky, n: usize, seed: u64) -> Vec<SkySample> {
        let distribution = SkyDistribution::new(sky);
        let mut rng = Rng::new(seed);
        (0..n).filter_map(|_| distribution.sample([rng.next_f64(), rng.next_f64(), rng.next_f64()])).collect()
    }

    #[test]
    fn star_field_directions_are_drawn_in_proportion_to_luminance() {
        // With stars by flux and the background by its power, the density is luminance over the
        // total power everywhere, so every draw's luminance / density is that power (up to the
        // single-precision colours, and the four-digit Rec. 709 luminance weights against the CIE
        // Y a star's blackbody is scaled by: 5e-5); a star drawn with the wrong probability, or a
        // disc with the wrong solid angle, breaks it.
        for background in [0.0, 2e-3] {
            let sky = stars(background);
            let distribution = SkyDistribution::new(&sky);
            let Sky::StarField(field) = &sky else { unreachable!() };
            let mut flux = 4.0 * PI * f64::from(background);
            field.for_each_star(|s| flux += s.flux);
            assert!((distribution.power() / flux - 1.0).abs() < 1e-12, "{} vs {flux}", distribution.power());
            let samples = draws(&sky, 20_000, 9);
            assert!(samples.len() > 19_990, "{} of 20000 drawn", samples.len());
            for s in &samples {
                let ratio = f64::from(luminance(s.radiance)) / s.pdf / flux;
                assert!((ratio - 1.0).abs() < 1e-4, "L/p = {ratio} × power at {}", s.direction);
                assert!((distribution.pdf(s.direction) / s.pdf - 1.0).abs() < 1e-12);
            }
            // Most draws land on stars, which cover 1 % of the sky.
            let on_stars = samples.iter().filter(|s| luminance(s.radiance) > 10.0 * background).count();
            assert!(on_stars > 19_000 * usize::from(background == 0.0), "{on_stars} on stars");
        }
    }

    #[test]
    fn densities_integrate_to_one() {
        // E[1/p] over draws from p is the measure of where p > 0: the sphere, 4π.
        for sky in [stars(2e-3), Sky::Constant(Rgb::splat(0.5)), gradient()] {
            let samples = draws(&sky, 200_000, 3);
            let measure = samples.iter().map(|s| 1.0 / s.pdf).sum::<f64>() / 200_000.0;
            assert!((measure / (4.0 * PI) - 1.0).abs() < 0.02, "{sky:?}: ∫dω = {measure}");
        }
    }

    #[test]
    fn smooth_sky_power_is_the_luminance_integral() {
        let sky = gradient();
        let mut rng = Rng::new(1);
        let n = 400_000;
        let estimate = (0..n).map(|_| f64::from(luminance(sky.radiance(uniform_sphere(rng.next_2d()))))).sum::<f64>()
            / f64::from(n)
            * 4.0
            * PI;
        let power = SkyDistribution::new(&sky).power();
        assert!((power / estimate - 1.0).abs() < 0.005, "quadrature {power}, Monte Carlo {estimate}");
        assert_eq!(SkyDistribution::new(&Sky::Constant(Rgb::ZERO)).power(), 0.0);
    }
}

//! Fresnel reflectance of a smooth interface, for unpolarised light.
//!
//! - [`dielectric`]: exact reflectance between two dielectrics (glass, water, a plastic's coating).
//! - [`ConductorFresnel`]: a metal, either exact with a complex index of refraction `η + iκ` per RGB channel
//!   (presets for gold, silver, copper and aluminium) or Schlick's approximation from a normal-incidence
//!   colour `F0`.
//! - [`diffuse_reflectance`]: the cosine-weighted hemispherical average of [`dielectric`] (`F_dr`), used to
//!   account for light bouncing between a plastic's coating and its diffuse base.
//!
//! All cosines are measured against the interface normal `+z` of the local shading frame; `eta` is the
//! relative index `n_inside / n_outside`, "outside" being the side the normal points to.

use crate::rgb::Rgb;
use crate::spectrum::Colour;

/// Unpolarised Fresnel reflectance of a smooth dielectric interface (Born & Wolf, *Principles of Optics*,
/// §1.5; pbrt-v4 `FrDielectric`).
///
/// `cos_theta_i` is the cosine between the incident (or, by reciprocity, the outgoing) direction and the
/// normal: positive on the outside, negative on the inside, in which case the relative index seen by the
/// light is `1/eta`. Returns 1 under total internal reflection.
pub fn dielectric(cos_theta_i: f64, eta: f64) -> f64 {
    let (cos_i, eta) = if cos_theta_i < 0.0 { (-cos_theta_i, 1.0 / eta) } else { (cos_theta_i, eta) };
    let cos_i = cos_i.min(1.0);
    // Snell: sin θt = sin θi / η.
    let sin2_t = (1.0 - cos_i * cos_i) / (eta * eta);
    if sin2_t >= 1.0 {
        return 1.0;
    }
    let cos_t = (1.0 - sin2_t).sqrt();
    let r_parallel = (eta * cos_i - cos_t) / (eta * cos_i + cos_t);
    let r_perpendicular = (cos_i - eta * cos_t) / (cos_i + eta * cos_t);
    0.5 * (r_parallel * r_parallel + r_perpendicular * r_perpendicular)
}

/// Hemispherical-cosine average of [`dielectric`] for light arriving from *outside* a medium of relative
/// index `eta ≥ 1`: `F_dr = ∫ F(μ) 2μ dμ` over `μ = cos θ ∈ [0, 1]`, the fraction of uniformly diffuse
/// illumination the interface reflects.
///
/// The classic closed form of the integral for unpolarised light (Walsh 1926; quoted e.g. by Molenaar,
/// ten Bosch and Zijp 1999, *Applied Optics* 38(10)), checked against quadrature in the tests. For
/// `eta < 1` the integral includes total internal reflection and follows from the relation behind
/// [`internal_diffuse_reflectance`]: `1 − F_dr(η) = η²·(1 − F_dr(1/η))`.
pub fn diffuse_reflectance(eta: f64) -> f64 {
    if eta < 1.0 {
        return 1.0 - (1.0 - diffuse_reflectance(1.0 / eta)) * (eta * eta);
    }
    // Near η = 1 the closed form cancels catastrophically; there F_dr ≈ ((η−1)/(η+1))² · (1 + O(η−1)) is
    // below 1e-8 anyway.
    if eta < 1.0 + 1e-4 {
        return 0.0;
    }
    let n = eta;
    let n2 = n * n;
    let n4 = n2 * n2;
    let a = 0.5 + (n - 1.0) * (3.0 * n + 1.0) / (6.0 * (n + 1.0) * (n + 1.0));
    let b = n2 * (n2 - 1.0) * (n2 - 1.0) / ((n2 + 1.0).powi(3)) * ((n - 1.0) / (n + 1.0)).ln();
    let c = 2.0 * n2 * n * (n2 + 2.0 * n - 1.0) / ((n2 + 1.0) * (n4 - 1.0));
    let d = 8.0 * n4 * (n4 + 1.0) / ((n2 + 1.0) * (n4 - 1.0) * (n4 - 1.0)) * n.ln();
    (a + b - c + d).clamp(0.0, 1.0)
}

/// Fraction of uniformly diffuse light *inside* a medium of relative index `eta ≥ 1` that the interface
/// reflects back in, total internal reflection included: `F_dr,int = 1 − (1 − F_dr(η)) / η²` (radiance
/// conservation across the interface; e.g. d'Eon & Irving 2011, "A quantized-diffusion model for rendering
/// translucent materials").
pub fn internal_diffuse_reflectance(eta: f64) -> f64 {
    1.0 - (1.0 - diffuse_reflectance(eta)) / (eta * eta)
}

/// Fresnel reflectance of a metal: as a scene gives it (RGB), or lifted to the colours a path
/// carries ([`ConductorFresnel::lift`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum ConductorFresnel<C: Colour = Rgb> {
    /// Exact unpolarised Fresnel reflectance of a conductor with complex index of refraction `eta + i·k`
    /// per RGB channel (or wavelength), relative to the outside medium (pbrt-v4 `FrComplex`).
    Complex { eta: C, k: C },
    /// Schlick's approximation `F0 + (1 − F0)(1 − cos θ)⁵` (Schlick 1994, *Computer Graphics Forum*
    /// 13(3)), with `f0` the colour at normal incidence. Convenient for artist-picked metal colours.
    Schlick { f0: C },
}

/// Named conductors: `(names, η, κ)` at 650, 550 and 450 nm (R, G, B), from refractiveindex.info's tables
/// (Au, Ag, Cu: Johnson & Christy 1972; Al: Rakić 1995) as sampled by Chaos Group, "Understanding
/// metalness" (2014).
const METALS: [(&[&str], [f32; 3], [f32; 3]); 4] = [
    (&["gold", "au"], [0.18299, 0.42108, 1.3734], [3.4242, 2.3459, 1.7704]),
    (&["silver", "ag"], [0.15943, 0.14512, 0.13547], [3.9291, 3.1900, 2.3808]),
    (&["copper", "cu"], [0.27105, 0.67693, 1.3164], [3.6092, 2.6248, 2.2921]),
    (&["aluminium", "aluminum", "al"], [1.3456, 0.96521, 0.61722], [7.4746, 6.3995, 5.3031]),
];

impl ConductorFresnel<Rgb> {
    /// The names [`ConductorFresnel::preset`] accepts (first spelling of each metal).
    pub const PRESETS: [&'static str; 4] = ["gold", "silver", "copper", "aluminium"];

    /// A named metal: "gold" ("au"), "silver" ("ag"), "copper" ("cu"), "aluminium" ("aluminum", "al");
    /// case-insensitive. `None` for an unknown name.
    pub fn preset(name: &str) -> Option<Self> {
        let name = name.trim().to_ascii_lowercase();
        METALS
            .iter()
            .find(|(names, ..)| names.contains(&name.as_str()))
            .map(|&(_, eta, k)| ConductorFresnel::Complex { eta: Rgb::from_array(eta), k: Rgb::from_array(k) })
    }

    /// The reflectance in the colours `C` carries at `lambda`: η and κ as unbounded spectra,
    /// `f0` as a reflectance.
    pub fn lift<C: Colour>(&self, lambda: &C::Lambda) -> ConductorFresnel<C> {
        match *self {
            ConductorFresnel::Complex { eta, k } => {
                ConductorFresnel::Complex { eta: C::unbounded(eta, lambda), k: C::unbounded(k, lambda) }
            }
            ConductorFresnel::Schlick { f0 } => ConductorFresnel::Schlick { f0: C::reflectance(f0, lambda) },
        }
    }

    /// Checks the parameters a scene file supplies: finite, non-negative, and for [`Complex`] not both
    /// zero in any channel; for [`Schlick`] `f0 ≤ 1`.
    ///
    /// [`Complex`]: ConductorFresnel::Complex
    /// [`Schlick`]: ConductorFresnel::Schlick
    pub fn validate(&self) -> Result<(), String> {
        match *self {
            ConductorFresnel::Complex { eta, k } => {
                let ok = eta.is_finite()
                    && k.is_finite()
                    && eta.min_element() >= 0.0
                    && k.min_element() >= 0.0
                    && (eta + k).min_element() > 0.0;
                if ok {
                    Ok(())
                } else {
                    Err(format!("conductor eta {eta} and k {k} must be finite, ≥ 0 and not both 0"))
                }
            }
            ConductorFresnel::Schlick { f0 } => {
                if f0.is_finite() && f0.min_element() >= 0.0 && f0.max_element() <= 1.0 {
                    Ok(())
                } else {
                    Err(format!("conductor f0 {f0} must lie in [0, 1]"))
                }
            }
        }
    }
}

impl<C: Colour> ConductorFresnel<C> {
    /// Reflectance for an angle of incidence with cosine `cos_theta_i` (clamped to `[0, 1]`).
    pub fn eval(&self, cos_theta_i: f64) -> C {
        let cos_i = cos_theta_i.clamp(0.0, 1.0);
        match *self {
            ConductorFresnel::Complex { eta, k } => {
                eta.zip(k, |eta, k| complex_channel(cos_i, eta.into(), k.into()) as f32)
            }
            ConductorFresnel::Schlick { f0 } => {
                let m = 1.0 - cos_i;
                let m5 = (m * m) * (m * m) * m;
                f0 + (C::ONE - f0) * m5 as f32
            }
        }
    }
}

/// One channel of the conductor Fresnel equations with a complex relative index `η = n + iκ`
/// (pbrt-v4 `FrComplex`): Snell's law and the amplitude coefficients hold unchanged for complex `η`.
fn complex_channel(cos_i: f64, n: f64, k: f64) -> f64 {
    let eta = Complex::new(n, k);
    let sin2_i = 1.0 - cos_i * cos_i;
    let sin2_t = Complex::new(sin2_i, 0.0) / (eta * eta);
    let cos_t = (Complex::new(1.0, 0.0) - sin2_t).sqrt();
    let ci = Complex::new(cos_i, 0.0);
    let r_parallel = (eta * ci - cos_t) / (eta * ci + cos_t);
    let r_perpendicular = (ci - eta * cos_t) / (ci + eta * cos_t);
    0.5 * (r_parallel.norm_sqr() + r_perpendicular.norm_sqr())
}

/// The little complex arithmetic [`complex_channel`] needs.
#[derive(Clone, Copy, Debug)]
struct Complex {
    re: f64,
    im: f64,
}

impl Complex {
    fn new(re: f64, im: f64) -> Self {
        Self { re, im }
    }

    fn norm_sqr(self) -> f64 {
        self.re * self.re + self.im * self.im
    }

    /// Principal square root (branch cut along the negative real axis).
    fn sqrt(self) -> Self {
        let n = self.norm_sqr().sqrt();
        if n == 0.0 {
            return Self::new(0.0, 0.0);
        }
        let t1 = (0.5 * (n + self.re.abs())).sqrt();
        let t2 = 0.5 * self.im / t1;
        if self.re >= 0.0 {
            Self::new(t1, t2)
        } else {
            Self::new(t2.abs(), t1.copysign(self.im))
        }
    }
}

impl std::ops::Add for Complex {
    type Output = Self;
    fn add(self, o: Self) -> Self {
        Self::new(self.re + o.re, self.im + o.im)
    }
}

impl std::ops::Sub for Complex {
    type Output = Self;
    fn sub(self, o: Self) -> Self {
        Self::new(self.re - o.re, self.im - o.im)
    }
}

impl std::ops::Mul for Complex {
    type Output = Self;
    fn mul(self, o: Self) -> Self {
        Self::new(self.re * o.re - self.im * o.im, self.re * o.im + self.im * o.re)
    }
}

impl std::ops::Div for Complex {
    type Output = Self;
    fn div(self, o: Self) -> Self {
        let d = o.norm_sqr();
        Self::new((self.re * o.re + self.im * o.im) / d, (self.im * o.re - self.re * o.im) / d)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Midpoint-rule `∫₀¹ F(μ) 2μ dμ` with 200 000 panels; the integrand is smooth for η > 1.
    fn fdr_quadrature(eta: f64) -> f64 {
        let n = 200_000;
        (0..n)
            .map(|i| {
                let mu = (i as f64 + 0.5) / n as f64;
                dielectric(mu, eta) * 2.0 * mu / n as f64
            })
            .sum()
    }

    #[test]
    fn normal_incidence_matches_closed_form() {
        for eta in [1.0f64, 1.33, 1.5, 2.4, 1.0 / 1.5] {
            let expected = ((eta - 1.0) / (eta + 1.0)).powi(2);
            assert!((dielectric(1.0, eta) - expected).abs() < 1e-12, "eta {eta}");
            // Reciprocity: seen from inside at normal incidence the reflectance is the same.
            assert!((dielectric(-1.0, eta) - expected).abs() < 1e-12, "eta {eta} inside");
        }
    }

    #[test]
    fn total_internal_reflection_beyond_critical_angle() {
        let eta = 1.5f64;
        let cos_critical = (1.0 - 1.0 / (eta * eta)).sqrt();
        assert_eq!(dielectric(-(cos_critical - 1e-6), eta), 1.0, "just beyond the critical angle");
        assert!(dielectric(-(cos_critical + 1e-3), eta) < 1.0, "just inside the escape cone");
        assert!(dielectric(0.3, eta) < 1.0, "no TIR from outside");
    }

    #[test]
    fn grazing_incidence_reflects_everything() {
        for eta in [1.2, 1.5, 3.0] {
            assert!((dielectric(0.0, eta) - 1.0).abs() < 1e-12);
        }
    }

    #[test]
    fn diffuse_reflectance_closed_form_matches_quadrature() {
        for eta in [1.001, 1.05, 1.33, 1.5, 2.0, 3.5] {
            let closed = diffuse_reflectance(eta);
            let numeric = fdr_quadrature(eta);
            assert!((closed - numeric).abs() < 1e-6, "eta {eta}: closed form {closed}, quadrature {numeric}");
        }
        // Known value: F_dr,int of glass (η = 1.5) ≈ 0.596 (Jensen et al. 2001's fit gives 0.5968).
        assert!((internal_diffuse_reflectance(1.5) - 0.5963).abs() < 1e-3);
    }

    #[test]
    fn conductor_with_zero_extinction_is_a_dielectric() {
        let f = ConductorFresnel::Complex { eta: Rgb::splat(1.5), k: Rgb::ZERO };
        for cos in [0.05, 0.3, 0.7, 1.0] {
            let expected = dielectric(cos, 1.5) as f32;
            assert!((f.eval(cos) - Rgb::splat(expected)).abs().max_element() < 1e-6, "cos {cos}");
        }
    }

    #[test]
    fn conductor_normal_incidence_matches_closed_form() {
        // R(0) = ((n−1)² + κ²) / ((n+1)² + κ²) (the normal-incidence limit of the conductor Fresnel equations).
        let gold = ConductorFresnel::preset("Gold").unwrap();
        let ConductorFresnel::Complex { eta, k } = gold else { panic!("gold is complex") };
        let r0 = gold.eval(1.0);
        for c in 0..3 {
            let (n, k) = (eta[c] as f64, k[c] as f64);
            let expected = ((n - 1.0).powi(2) + k * k) / ((n + 1.0).powi(2) + k * k);
            assert!((r0[c] as f64 - expected).abs() < 1e-6);
        }
        // Gold is yellow: red reflects most, blue least.
        assert!(r0.x > 0.9 && r0.y > 0.7 && r0.z < 0.45, "{r0}");
        assert!((gold.eval(0.0) - Rgb::ONE).abs().max_element() < 1e-6, "grazing reflects everything");
        for name in ConductorFresnel::PRESETS {
            let f = ConductorFresnel::preset(name).unwrap();
            f.validate().unwrap();
            let r = f.eval(0.6);
            assert!(r.min_element() > 0.3 && r.max_element() <= 1.0, "{name}: {r}");
        }
        assert!(ConductorFresnel::preset("unobtainium").is_none());
    }

    #[test]
    fn schlick_endpoints() {
        let f = ConductorFresnel::Schlick { f0: Rgb::new(0.9, 0.6, 0.3) };
        assert!((f.eval(1.0) - Rgb::new(0.9, 0.6, 0.3)).abs().max_element() < 1e-7);
        assert!((f.eval(0.0) - Rgb::ONE).abs().max_element() < 1e-7);
        assert!(ConductorFresnel::Schlick { f0: Rgb::splat(1.5) }.validate().is_err());
        assert!(ConductorFresnel::Complex { eta: Rgb::ZERO, k: Rgb::ZERO }.validate().is_err());
    }
}

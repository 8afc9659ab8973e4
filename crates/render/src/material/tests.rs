//! Conformance tests run over every BSDF: χ² of `sample` against `pdf`, `weight = f·|cos|/pdf`,
//! reciprocity, energy bounds, two-sidedness; plus the delta BSDFs' discrete probabilities. The
//! tests of continuous lobes run twice: in RGB, and with the colours lifted to spectra at sampled
//! wavelengths, as spectral rendering resolves them.
//!
//! Statistical tests use fixed seeds and state their tolerance: χ² tests at significance 0.001 after a
//! Šidák correction over all of them; Monte Carlo means at 3σ (bounds) or 5σ (equalities) with σ the
//! standard error estimated from the samples.

use super::chi2::Chi2Test;
use super::*;
use crate::sampling::{uniform_sphere, Rng};
use crate::spectrum::{SampledSpectrum, SampledWavelengths};
use std::f64::consts::PI;

/// Viewing directions: normal, oblique, grazing, nearly tangent, and from below (back faces of opaque
/// BSDFs, inside of dielectrics).
fn wos() -> Vec<Vec3> {
    [(0.0, 0.0), (30.0, 20.0), (60.0, 200.0), (85.0, 75.0), (89.5, 310.0), (120.0, 45.0), (175.0, 160.0)]
        .iter()
        .map(|&(theta, phi): &(f64, f64)| {
            let (t, p) = (theta.to_radians(), phi.to_radians());
            Vec3::new(t.sin() * p.cos(), t.sin() * p.sin(), t.cos())
        })
        .collect()
}

const GOLD: ConductorFresnel =
    ConductorFresnel::Complex { eta: Rgb::new(0.18299, 0.42108, 1.3734), k: Rgb::new(3.4242, 2.3459, 1.7704) };

/// Every BSDF configuration with a density (a continuous lobe), for χ² and the `weight` identity,
/// in the colours `C` at `lambda`.
fn continuous_cases<C: Colour>(lambda: &C::Lambda) -> Vec<(&'static str, Bsdf<C>)> {
    let colour = |rgb: Rgb| C::reflectance(rgb, lambda);
    let red = colour(Rgb::new(0.7, 0.3, 0.1));
    let schlick = ConductorFresnel::Schlick { f0: Rgb::new(0.9, 0.8, 0.5) }.lift::<C>(lambda);
    let gold = GOLD.lift::<C>(lambda);
    vec![
        ("diffuse", Bsdf::Diffuse { reflectance: colour(Rgb::new(0.8, 0.5, 0.2)) }),
        ("conductor α=0.05", Bsdf::RoughConductor { alpha: 0.05, fresnel: gold }),
        ("conductor α=0.3", Bsdf::RoughConductor { alpha: 0.3, fresnel: gold }),
        ("conductor α=1", Bsdf::RoughConductor { alpha: 1.0, fresnel: gold }),
        ("conductor schlick α=0.5", Bsdf::RoughConductor { alpha: 0.5, fresnel: schlick }),
        ("plastic α=0.1", Bsdf::RoughPlastic { diffuse: red, alpha: 0.1, eta: 1.5 }),
        ("plastic α=0.5", Bsdf::RoughPlastic { diffuse: red, alpha: 0.5, eta: 1.5 }),
        ("plastic α=1 η=2", Bsdf::RoughPlastic { diffuse: red, alpha: 1.0, eta: 2.0 }),
        ("plastic smooth", Bsdf::RoughPlastic { diffuse: red, alpha: 0.0, eta: 1.5 }),
        ("plastic black α=0.3", Bsdf::RoughPlastic { diffuse: C::ZERO, alpha: 0.3, eta: 1.5 }),
    ]
}

/// The wavelengths the spectral runs of the suite lift their colours at: a hero in the green and
/// its companions across the range.
fn wavelengths() -> SampledWavelengths {
    SampledWavelengths::sample_visible(0.37)
}

/// `test` run on the RGB cases and on the spectral ones.
fn in_both(
    test: impl Fn(&str, Vec<(&'static str, Bsdf)>),
    spectral: impl Fn(&str, Vec<(&'static str, Bsdf<SampledSpectrum>)>),
) {
    test("RGB", continuous_cases::<Rgb>(&()));
    spectral("spectral", continuous_cases::<SampledSpectrum>(&wavelengths()));
}

/// The components of a colour.
fn components<C: Colour>(c: C) -> Vec<f64> {
    (0..C::COMPONENTS).map(|i| f64::from(c.component(i))).collect()
}

/// Every BSDF, white where it has a colour: for the energy bounds; in the colours `C` at `lambda`.
fn white_cases<C: Colour>(lambda: &C::Lambda) -> Vec<(&'static str, Bsdf<C>)> {
    let white = C::reflectance(Rgb::ONE, lambda);
    let mut cases = vec![
        ("diffuse", Bsdf::Diffuse { reflectance: white }),
        ("mirror", Bsdf::Mirror { reflectance: white }),
        ("dielectric", Bsdf::Dielectric { eta: 1.5, transmittance: white }),
        ("smooth conductor", Bsdf::RoughConductor { alpha: 0.0, fresnel: GOLD.lift::<C>(lambda) }),
        ("white schlick α=0.2", Bsdf::RoughConductor { alpha: 0.2, fresnel: ConductorFresnel::Schlick { f0: white } }),
    ];
    for alpha in [0.0, 0.05, 0.3, 0.6, 1.0] {
        for eta in [1.2, 1.5, 2.5] {
            cases.push(("white plastic", Bsdf::RoughPlastic { diffuse: white, alpha, eta }));
        }
    }
    cases.extend(continuous_cases::<C>(lambda));
    cases
}

fn rel_close(a: f64, b: f64, tol: f64) -> bool {
    (a - b).abs() <= tol * a.abs().max(b.abs()).max(1e-300)
}

// ---------------------------------------------------------------------------------------------------
// χ²

/// Significance 0.001 for the whole family of χ² tests, Šidák-corrected: each of the `n` tests is run at
/// `1 − (1 − 0.001)^(1/n)`.
fn sidak_alpha() -> f64 {
    let n = (2 * continuous_cases::<Rgb>(&()).len() * wos().len() + DELTA_CHI2_TESTS) as f64;
    1.0 - (1.0 - 0.001f64).powf(1.0 / n)
}

fn chi2_family(name_prefix: &str) {
    in_both(|kind, cases| chi2_cases(kind, name_prefix, cases), |kind, cases| chi2_cases(kind, name_prefix, cases));
}

fn chi2_cases<C: Colour>(kind: &str, name_prefix: &str, cases: Vec<(&'static str, Bsdf<C>)>) {
    let alpha = sidak_alpha();
    let test = Chi2Test { cos_bins: 20, phi_bins: 40, samples: 500_000, seed: 0 };
    let mut ran = 0;
    for (name, bsdf) in cases.into_iter().filter(|(n, _)| n.starts_with(name_prefix)) {
        let name = format!("{kind} {name}");
        for (k, wo) in wos().into_iter().enumerate() {
            let test = Chi2Test { seed: k as u64 + 1, ..test };
            let result = test
                .run(
                    |rng| {
                        let uc = rng.next_f64();
                        bsdf.sample(wo, uc, rng.next_2d()).map(|s| (s.wi, s.is_delta))
                    },
                    |wi| bsdf.pdf(wo, wi),
                )
                .unwrap_or_else(|e| panic!("{name}, wo {wo}: {e}"));
            assert!(
                result.p_value > alpha,
                "{name}, wo {wo}: χ² = {:.1} with {} dof, p = {:.2e} < {alpha:.2e}: the sampler does not follow pdf",
                result.statistic,
                result.dof,
                result.p_value
            );
            assert!(result.pdf_integral <= 1.0 + 1e-3, "{name}, wo {wo}: ∫pdf = {}", result.pdf_integral);
            ran += 1;
        }
    }
    assert!(ran > 0);
}

#[test]
fn chi2_diffuse() {
    chi2_family("diffuse");
}

#[test]
fn chi2_rough_conductor() {
    chi2_family("conductor");
}

#[test]
fn chi2_rough_plastic() {
    chi2_family("plastic");
}

/// Number of discrete-outcome χ² tests in [`dielectric_chooses_lobes_by_fresnel`].
const DELTA_CHI2_TESTS: usize = 7;

#[test]
fn dielectric_chooses_lobes_by_fresnel() {
    // Two outcomes, reflection with probability F: Pearson's χ² with 1 degree of freedom.
    let alpha = sidak_alpha();
    let glass = Bsdf::Dielectric { eta: 1.5, transmittance: Rgb::ONE };
    let n = 200_000;
    let wos = wos();
    assert_eq!(wos.len(), DELTA_CHI2_TESTS);
    for (k, wo) in wos.into_iter().enumerate() {
        let f = fresnel::dielectric(wo.z, 1.5);
        let mut rng = Rng::new(100 + k as u64);
        let mut reflected = 0.0;
        for _ in 0..n {
            let s = glass.sample(wo, rng.next_f64(), rng.next_2d()).unwrap();
            assert!(s.is_delta);
            if s.wi.z * wo.z > 0.0 {
                reflected += 1.0;
                assert!((s.wi - Vec3::new(-wo.x, -wo.y, wo.z)).length() < 1e-12);
                assert!(rel_close(s.pdf, f, 1e-12) && s.eta == 1.0);
            } else {
                assert!(rel_close(s.pdf, 1.0 - f, 1e-12));
            }
        }
        if f > 0.0 && f < 1.0 {
            let (er, et) = (n as f64 * f, n as f64 * (1.0 - f));
            let chi2 = (reflected - er).powi(2) / er + (n as f64 - reflected - et).powi(2) / et;
            let p = super::chi2::chi2_survival(chi2, 1.0);
            assert!(p > alpha, "wo {wo}: reflected {reflected} of {n}, expected F = {f}: p = {p:.2e}");
        } else {
            assert_eq!(reflected, n as f64 * f, "wo {wo}: F = {f}");
        }
    }
}

// ---------------------------------------------------------------------------------------------------
// Sample consistency

#[test]
fn sample_weight_is_f_cos_over_pdf() {
    in_both(sample_weights, sample_weights);
}

fn sample_weights<C: Colour>(kind: &str, cases: Vec<(&'static str, Bsdf<C>)>) {
    for (name, bsdf) in cases {
        let name = format!("{kind} {name}");
        for (k, wo) in wos().into_iter().enumerate() {
            let mut rng = Rng::new(7 + k as u64);
            for _ in 0..5_000 {
                let Some(s) = bsdf.sample(wo, rng.next_f64(), rng.next_2d()) else { continue };
                assert!((s.wi.length() - 1.0).abs() < 1e-9, "{name}: unit wi");
                assert!(s.wi.z * wo.z >= 0.0, "{name}: opaque BSDFs reflect to wo's side");
                let weight = components(s.weight);
                assert!(weight.iter().all(|w| w.is_finite() && *w >= 0.0), "{name}: weight {weight:?}");
                if s.is_delta {
                    continue;
                }
                let pdf = bsdf.pdf(wo, s.wi);
                assert!(rel_close(s.pdf, pdf, 1e-6), "{name}, wo {wo}: sample pdf {} vs pdf() {pdf}", s.pdf);
                let expected = components(bsdf.f(wo, s.wi) * (s.wi.z.abs() / pdf) as f32);
                for (w, e) in weight.iter().zip(&expected) {
                    assert!(
                        rel_close(*w, *e, 1e-4),
                        "{name}, wo {wo}, wi {}: weight {weight:?} vs f·cos/pdf {expected:?}",
                        s.wi
                    );
                }
                assert_eq!(s.eta, 1.0);
            }
        }
    }
}

#[test]
fn reflection_is_reciprocal() {
    in_both(reciprocal, reciprocal);
}

fn reciprocal<C: Colour>(kind: &str, cases: Vec<(&'static str, Bsdf<C>)>) {
    let mut rng = Rng::new(3);
    for (name, bsdf) in cases {
        for _ in 0..2_000 {
            let a = uniform_sphere(rng.next_2d());
            let b = uniform_sphere(rng.next_2d());
            let (fa, fb) = (components(bsdf.f(a, b)), components(bsdf.f(b, a)));
            for (x, y) in fa.iter().zip(&fb) {
                assert!(rel_close(*x, *y, 1e-5), "{kind} {name}: f({a}, {b}) = {fa:?} but f(b, a) = {fb:?}");
            }
        }
    }
}

#[test]
fn opaque_bsdfs_are_two_sided() {
    let mut rng = Rng::new(4);
    for (name, bsdf) in white_cases::<Rgb>(&()).into_iter().filter(|(_, b)| !b.has_transmission()) {
        for _ in 0..500 {
            let (wo, wi) = (uniform_sphere(rng.next_2d()), uniform_sphere(rng.next_2d()));
            assert_eq!(bsdf.f(wo, wi), bsdf.f(flip(wo), flip(wi)), "{name}");
            assert_eq!(bsdf.pdf(wo, wi), bsdf.pdf(flip(wo), flip(wi)), "{name}");
            if wo.z * wi.z < 0.0 {
                assert_eq!(bsdf.f(wo, wi), Rgb::ZERO, "{name}: no transmission");
            }
            let (uc, u) = (rng.next_f64(), rng.next_2d());
            let (up, down) = (bsdf.sample(wo, uc, u), bsdf.sample(flip(wo), uc, u));
            assert_eq!(up.map(|s| flip(s.wi)), down.map(|s| s.wi), "{name}: mirrored samples");
        }
    }
}

#[test]
fn delta_flags_and_zero_densities() {
    let (wo, wi) = (Vec3::new(0.3, 0.2, 0.9).normalize(), Vec3::new(-0.3, -0.2, 0.9).normalize());
    for (name, bsdf) in white_cases::<Rgb>(&()) {
        if bsdf.is_delta() {
            assert_eq!(bsdf.f(wo, wi), Rgb::ZERO, "{name}");
            assert_eq!(bsdf.pdf(wo, wi), 0.0, "{name}");
            assert!(bsdf.sample(wo, 0.5, [0.5, 0.5]).unwrap().is_delta, "{name}");
        }
        assert_eq!(bsdf.has_transmission(), matches!(bsdf, Bsdf::Dielectric { .. }), "{name}");
    }
    assert!(Bsdf::Mirror { reflectance: Rgb::ONE }.is_delta());
    assert!(!Bsdf::RoughConductor { alpha: 0.1, fresnel: GOLD }.is_delta());
    assert!(Bsdf::RoughConductor { alpha: 0.0, fresnel: GOLD }.is_delta());
    assert!(!Bsdf::RoughPlastic { diffuse: Rgb::ONE, alpha: 0.0, eta: 1.5 }.is_delta());
}

// ---------------------------------------------------------------------------------------------------
// Energy

/// Monte Carlo albedo `E[weight]` (per component) with its standard error; `scale` multiplies
/// each weight.
fn albedo<C: Colour>(
    bsdf: &Bsdf<C>,
    wo: Vec3,
    n: usize,
    seed: u64,
    scale: impl Fn(&BsdfSample<C>) -> f32,
) -> (Vec<f64>, Vec<f64>) {
    let mut rng = Rng::new(seed);
    let (mut sum, mut sum2) = (vec![0.0; C::COMPONENTS], vec![0.0; C::COMPONENTS]);
    for _ in 0..n {
        if let Some(s) = bsdf.sample(wo, rng.next_f64(), rng.next_2d()) {
            for (i, w) in components(s.weight * scale(&s)).into_iter().enumerate() {
                sum[i] += w;
                sum2[i] += w * w;
            }
        }
    }
    let mean: Vec<f64> = sum.iter().map(|s| s / n as f64).collect();
    let err = sum2.iter().zip(&mean).map(|(s2, m)| ((s2 / n as f64 - m * m).max(0.0) / n as f64).sqrt()).collect();
    (mean, err)
}

#[test]
fn albedo_never_exceeds_one() {
    albedo_bounded("RGB", white_cases::<Rgb>(&()));
    albedo_bounded("spectral", white_cases::<SampledSpectrum>(&wavelengths()));
}

fn albedo_bounded<C: Colour>(kind: &str, cases: Vec<(&'static str, Bsdf<C>)>) {
    for (name, bsdf) in cases {
        for (k, wo) in wos().into_iter().enumerate() {
            // For glass, undo the radiance scaling: it moves radiance, not energy.
            let (mean, err) = albedo(&bsdf, wo, 50_000, 11 + k as u64, |s| (s.eta * s.eta) as f32);
            let exceeds = mean.iter().zip(&err).any(|(m, e)| m - 3.0 * e > 1.0 + 1e-6);
            assert!(!exceeds, "{kind} {name}, wo {wo}: albedo {mean:?} ± {err:?} exceeds 1");
        }
    }
}

#[test]
fn closed_form_albedos() {
    let rho = Rgb::new(0.8, 0.5, 0.2);
    for wo in wos() {
        let (lambert, err) = albedo(&Bsdf::Diffuse { reflectance: rho }, wo, 10_000, 1, |_| 1.0);
        let close = lambert.iter().zip(components(rho)).all(|(l, r)| (l - r).abs() < 1e-6);
        assert!(close && err.iter().all(|e| *e < 1e-6), "Lambert: {lambert:?}");
        let (mirror, _) = albedo(&Bsdf::Mirror { reflectance: Rgb::ONE }, wo, 1_000, 2, |_| 1.0);
        assert_eq!(mirror, [1.0; 3], "white mirror");
        // White glass: every sample carries exactly 1 once the η² radiance factor is undone.
        let glass = Bsdf::Dielectric { eta: 1.5, transmittance: Rgb::ONE };
        let mut rng = Rng::new(5);
        for _ in 0..1_000 {
            let s = glass.sample(wo, rng.next_f64(), rng.next_2d()).unwrap();
            assert!((s.weight * (s.eta * s.eta) as f32 - Rgb::ONE).abs().max_element() < 1e-6);
        }
        // Smooth gold reflects F(cos θ).
        let gold = Bsdf::RoughConductor { alpha: 0.0, fresnel: GOLD };
        let s = gold.sample(wo, 0.5, [0.5, 0.5]).unwrap();
        assert!((s.weight - GOLD.eval(wo.z.abs())).abs().max_element() < 1e-7);
    }
}

#[test]
fn sampled_albedo_matches_integral_of_f_cos() {
    in_both(albedo_integrals, albedo_integrals);
}

/// Two independent estimators of ∫ f |cos| dωi: importance sampling through `sample`, and uniform
/// sphere sampling of `f`. They agree within 5 combined standard errors (plus 1e-3 for numerics).
fn albedo_integrals<C: Colour>(kind: &str, cases: Vec<(&'static str, Bsdf<C>)>) {
    for (name, bsdf) in cases.into_iter().filter(|(n, _)| *n != "plastic smooth") {
        for (k, wo) in wos().into_iter().enumerate() {
            if wo.z.abs() < 0.05 && name.contains("0.05") {
                continue; // a needle-thin lobe at grazing: uniform sampling cannot see it.
            }
            let (is_mean, is_err) = albedo(&bsdf, wo, 50_000, 21 + k as u64, |_| 1.0);
            let mut rng = Rng::new(31 + k as u64);
            let n = 200_000;
            let (mut sum, mut sum2) = (vec![0.0; C::COMPONENTS], vec![0.0; C::COMPONENTS]);
            for _ in 0..n {
                let wi = uniform_sphere(rng.next_2d());
                for (i, v) in components(bsdf.f(wo, wi) * (wi.z.abs() * 4.0 * PI) as f32).into_iter().enumerate() {
                    sum[i] += v;
                    sum2[i] += v * v;
                }
            }
            for i in 0..C::COMPONENTS {
                let mean = sum[i] / n as f64;
                let err = ((sum2[i] / n as f64 - mean * mean) / n as f64).sqrt();
                let tol = 5.0 * (err * err + is_err[i] * is_err[i]).sqrt() + 1e-3;
                assert!(
                    (mean - is_mean[i]).abs() <= tol,
                    "{kind} {name}, wo {wo}, component {i}: sampled {} ± {}, integrated {mean} ± {err}",
                    is_mean[i],
                    is_err[i]
                );
            }
        }
    }
}

// ---------------------------------------------------------------------------------------------------
// Materials

#[test]
fn material_resolves_textures_and_clamps_colours() {
    let m = Material::Diffuse { reflectance: Texture::checker(Rgb::new(2.0, 0.5, -1.0), Rgb::ONE * 0.25, [2.0, 2.0]) };
    assert_eq!(m.bsdf([0.1, 0.1], Vec3::ZERO), Bsdf::Diffuse { reflectance: Rgb::new(1.0, 0.5, 0.0) });
    assert_eq!(m.bsdf([0.6, 0.1], Vec3::ZERO), Bsdf::Diffuse { reflectance: Rgb::splat(0.25) });
    let metal = Material::RoughConductor { roughness: 0.5, fresnel: GOLD };
    assert_eq!(metal.bsdf([0.0, 0.0], Vec3::ZERO), Bsdf::RoughConductor { alpha: 0.25, fresnel: GOLD });
    let glass = Material::Dielectric { ior: 1.33, dispersion: None, transmittance: Rgb::ONE.into() };
    assert!(glass.bsdf([0.0, 0.0], Vec3::ZERO).has_transmission());
}

#[test]
fn material_validation_names_the_problem() {
    let ok = Material::RoughPlastic { diffuse: Rgb::ONE.into(), roughness: 0.2, ior: 1.5 };
    assert!(ok.validate().is_ok());
    let e = Material::RoughPlastic { diffuse: Rgb::ONE.into(), roughness: 1.5, ior: 1.5 }.validate().unwrap_err();
    assert!(e.contains("roughness"), "{e}");
    let e = Material::RoughPlastic { diffuse: Rgb::ONE.into(), roughness: 0.2, ior: 0.8 }.validate().unwrap_err();
    assert!(e.contains("ior"), "{e}");
    let e = Material::Dielectric { ior: f64::NAN, dispersion: None, transmittance: Rgb::ONE.into() }
        .validate()
        .unwrap_err();
    assert!(e.contains("ior"), "{e}");
    let bad_metal = ConductorFresnel::Complex { eta: Rgb::ZERO, k: Rgb::ZERO };
    assert!(Material::RoughConductor { roughness: 0.1, fresnel: bad_metal }.validate().is_err());
    let bad_grid = Texture::Grid {
        background: Rgb::ONE,
        line: Rgb::ZERO,
        spacing: 0.0,
        width: 0.1,
        highlights: vec![],
        uv_scale: [1.0, 1.0],
    };
    let e = Material::Diffuse { reflectance: bad_grid }.validate().unwrap_err();
    assert!(e.contains("spacing"), "{e}");
}

#[test]
fn a_dispersing_glass_refracts_at_the_hero_wavelength_which_alone_goes_on() {
    let flint = Dispersion::from_abbe(1.6, 30.0).unwrap();
    let glass = Material::Dielectric { ior: 1.6, dispersion: Some(flint), transmittance: Rgb::ONE.into() };
    let mut lambda = wavelengths();
    let hero = f64::from(lambda.lambda(0));
    let Bsdf::Dielectric { eta, .. } = glass.resolve::<SampledSpectrum>([0.0; 2], Vec3::ZERO, &mut lambda) else {
        panic!("{glass:?}")
    };
    assert_eq!(eta, flint.ior(hero));
    assert!((eta - 1.6).abs() > 1e-3, "hero at {hero} nm is off the d line");
    assert!((1..crate::spectrum::N_WAVELENGTHS).all(|i| lambda.pdf(i) == 0.0), "{lambda:?}");
    assert_eq!(lambda.pdf(0), wavelengths().pdf(0) / crate::spectrum::N_WAVELENGTHS as f32);
    // RGB rendering refracts at the d line; clear glass leaves the wavelengths alone.
    assert!(matches!(glass.bsdf([0.0; 2], Vec3::ZERO), Bsdf::Dielectric { eta, .. } if eta == 1.6));
    let clear = Material::Dielectric { ior: 1.6, dispersion: None, transmittance: Rgb::ONE.into() };
    let mut untouched = wavelengths();
    let _: Bsdf<SampledSpectrum> = clear.resolve([0.0; 2], Vec3::ZERO, &mut untouched);
    assert_eq!(untouched, wavelengths());
}

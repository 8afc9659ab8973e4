//! The integrators against exact results (`docs/physics.md`, "Analytic results to test against").
//! Exact values come from quadrature of the bending integrals (`spacetime::analytic`).

#![allow(clippy::unwrap_used)] // Test helpers may panic: a panic is a failed test.

use spacetime::analytic;
use spacetime::scattering::scatter;
use spacetime::{Fate, Spacetime, Stepping};

const ADAPTIVE: Stepping = Stepping::Adaptive { rtol: 1e-10 };

#[test]
fn schwarzschild_bending_matches_the_exact_integral() {
    let hole = Spacetime::schwarzschild(1.0).unwrap();
    for b in [5.25, 5.5, 6.0, 8.0, 12.0, 30.0, 100.0, 1e3, 1e4, 1e5] {
        let s = scatter(&hole, b, 0.0, ADAPTIVE);
        assert!(matches!(s.fate, Fate::Escaped { .. }), "b = {b}: {:?}", s.fate);
        let exact = analytic::schwarzschild_deflection(1.0, b);
        let rel = (s.deflection_rad - exact).abs() / exact;
        assert!(rel < 1e-7, "b = {b} M: {} vs exact {exact} (relative error {rel:e})", s.deflection_rad);
        assert!(s.max_abs_hamiltonian < 1e-9, "b = {b}: |H| = {:e}", s.max_abs_hamiltonian);
    }
}

#[test]
fn schwarzschild_bending_scales_with_mass() {
    let exact = analytic::schwarzschild_deflection(2.5, 40.0);
    let s = scatter(&Spacetime::schwarzschild(2.5).unwrap(), 40.0, 0.3, ADAPTIVE);
    assert!(((s.deflection_rad - exact) / exact).abs() < 1e-7);
}

#[test]
fn schwarzschild_captures_below_the_critical_impact_parameter() {
    let hole = Spacetime::schwarzschild(1.0).unwrap();
    let critical = analytic::schwarzschild_critical_impact(1.0);
    for b in [0.0, 0.5, 3.0, 5.0, critical * (1.0 - 1e-6)] {
        assert_eq!(scatter(&hole, b, 0.0, ADAPTIVE).fate, Fate::Captured, "b = {b}");
    }
    assert!(matches!(scatter(&hole, critical * (1.0 + 1e-6), 0.0, ADAPTIVE).fate, Fate::Escaped { .. }));
}

/// A charged hole captures rays from infinity below `b_c` ([`analytic::reissner_nordstrom_critical_impact`],
/// from the photon sphere `r_ph = (3M + √(9M² − 8Q²))/2`) and lets those above it escape, to
/// 10⁻⁶ in `b`, the extremal hole included.
#[test]
fn reissner_nordstrom_captures_below_its_critical_impact_parameter() {
    for (mass, charge) in [(1.0, 0.5), (1.0, 0.9), (2.0, -2.0)] {
        let hole = Spacetime::reissner_nordstrom(mass, charge).unwrap();
        let critical = analytic::reissner_nordstrom_critical_impact(mass, charge);
        for b in [0.0, 0.5 * critical, critical * (1.0 - 1e-6)] {
            assert_eq!(scatter(&hole, b, 0.3, ADAPTIVE).fate, Fate::Captured, "Q = {charge}, b = {b}");
        }
        for b in [critical * (1.0 + 1e-6), 1.5 * critical, 100.0 * critical] {
            let s = scatter(&hole, b, 0.3, ADAPTIVE);
            assert!(matches!(s.fate, Fate::Escaped { .. }), "Q = {charge}, b = {b}: {:?}", s.fate);
            assert!(s.max_abs_hamiltonian < 1e-8, "Q = {charge}, b = {b}: |H| = {:e}", s.max_abs_hamiltonian);
        }
    }
}

/// The bending angle past a charged hole matches the quadrature of its integral
/// ([`analytic::reissner_nordstrom_deflection`]) to 10⁻⁷, from 1 % above the critical impact
/// parameter (where rays wind nearly once round the photon sphere) to the weak field.
#[test]
fn reissner_nordstrom_bending_matches_the_exact_integral() {
    for (mass, charge) in [(1.0, 0.5), (1.0, 0.9), (1.0, 1.0), (2.5, -1.5)] {
        let hole = Spacetime::reissner_nordstrom(mass, charge).unwrap();
        let critical = analytic::reissner_nordstrom_critical_impact(mass, charge);
        for factor in [1.01, 1.05, 1.2, 2.0, 5.0, 20.0, 1e3, 1e5] {
            let b = factor * critical;
            let s = scatter(&hole, b, 0.3, ADAPTIVE);
            assert!(matches!(s.fate, Fate::Escaped { .. }), "Q = {charge}, b = {b}: {:?}", s.fate);
            let exact = analytic::reissner_nordstrom_deflection(mass, charge, b);
            let rel = (s.deflection_rad - exact).abs() / exact;
            assert!(rel < 1e-7, "Q = {charge}, b = {b}: {} vs exact {exact} ({rel:e})", s.deflection_rad);
        }
    }
}

/// The ray from infinity at `b_c (1 + 10⁻⁸)` winds round the photon sphere: its closest approach
/// is the photon sphere's radius to `O(√δ)` (here within 10⁻³ M), far inside that of
/// an uncharged hole (3M).
#[test]
fn reissner_nordstrom_near_critical_rays_graze_the_photon_sphere() {
    use spacetime::geodesic::plane::{trace_plane, PlaneRay, PlaneStart};
    use spacetime::ReissnerNordstrom;
    let hole = ReissnerNordstrom::new(1.0, 0.9);
    let r_ph = analytic::reissner_nordstrom_photon_sphere(1.0, 0.9);
    assert!((hole.photon_sphere() - r_ph).abs() < 1e-15 && (r_ph - 2.2937).abs() < 1e-4);
    let b = analytic::reissner_nordstrom_critical_impact(1.0, 0.9) * (1.0 + 1e-8);
    let ray = PlaneRay::from_infinity(&hole, b, [-1.0, 0.0, 0.0], [0.0, 1.0, 0.0]);
    let mut closest = f64::INFINITY;
    let t = trace_plane(&hole, PlaneStart::Plane(ray), &spacetime::scattering::settings(ADAPTIVE), |step| {
        for k in 0..=16 {
            closest = closest.min(spacetime::tensor::norm3(&step.point(&hole, f64::from(k) / 16.0).position));
        }
        spacetime::Visit::Continue
    });
    assert!(matches!(t.fate, Fate::Escaped { .. }), "{:?}", t.fate);
    assert!((closest - r_ph).abs() < 1e-3, "closest approach {closest}, photon sphere {r_ph}");
}

#[test]
fn ellis_bending_matches_the_exact_integral() {
    let wormhole = Spacetime::ellis(1.0).unwrap();
    for b in [1.01, 1.1, 1.5, 2.0, 5.0, 10.0, 100.0, 1e3, 1e4] {
        let s = scatter(&wormhole, b, 0.0, ADAPTIVE);
        assert!(matches!(s.fate, Fate::Escaped { .. }), "b = {b}: {:?}", s.fate);
        let exact = analytic::ellis_deflection(1.0, b);
        let rel = (s.deflection_rad - exact).abs() / exact;
        assert!(rel < 1e-7, "b = {b} b₀: {} vs exact {exact} (relative error {rel:e})", s.deflection_rad);
    }
}

#[test]
fn ellis_rays_inside_the_throat_traverse_and_sweep_the_exact_azimuth() {
    let wormhole = Spacetime::ellis(2.0).unwrap();
    for b in [0.02, 0.2, 1.0, 1.6, 1.98] {
        let s = scatter(&wormhole, b, 0.7, ADAPTIVE);
        assert!(matches!(s.fate, Fate::Traversed { .. }), "b = {b}: {:?}", s.fate);
        let swept = s.deflection_rad + std::f64::consts::PI;
        let exact = analytic::ellis_deflection(2.0, b) + std::f64::consts::PI;
        assert!(((swept - exact) / exact).abs() < 1e-7, "b = {b}: swept {swept} vs {exact}");
    }
    assert!(matches!(scatter(&wormhole, 0.0, 0.0, ADAPTIVE).fate, Fate::Traversed { .. }));
}

#[test]
fn minkowski_rays_are_not_bent() {
    let flat = Spacetime::Minkowski(spacetime::Minkowski);
    for b in [0.1, 1.0, 1e3] {
        let s = scatter(&flat, b, 0.0, ADAPTIVE);
        assert!(matches!(s.fate, Fate::Escaped { .. }));
        assert!(s.deflection_rad.abs() < 1e-15, "b = {b}: {}", s.deflection_rad);
    }
}

/// Bisects the capture threshold of equatorial rays on one side of a spinning hole of mass 1.
fn equatorial_critical_impact(hole: &Spacetime, side: f64) -> f64 {
    let captured = |b: f64| scatter(hole, side * b, 0.0, ADAPTIVE).fate == Fate::Captured;
    let (mut lo, mut hi) = (1.0, 10.0);
    assert!(captured(lo) && !captured(hi));
    while hi - lo > 1e-9 * hi {
        let mid = 0.5 * (lo + hi);
        if captured(mid) {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    side * 0.5 * (lo + hi)
}

#[test]
fn kerr_shadow_edges_match_bardeens_critical_curve() {
    for spin in [0.5, 0.9] {
        let (pro, retro) = analytic::kerr_equatorial_critical_impacts(1.0, spin);
        let hole = Spacetime::kerr(1.0, spin).unwrap();
        let (found_pro, found_retro) =
            (equatorial_critical_impact(&hole, 1.0), equatorial_critical_impact(&hole, -1.0));
        assert!(((found_pro - pro) / pro).abs() < 1e-6, "a = {spin}: prograde {found_pro} vs {pro}");
        assert!(((found_retro - retro) / retro).abs() < 1e-6, "a = {spin}: retrograde {found_retro} vs {retro}");
    }
}

/// A charged spinning hole captures equatorial rays below the impact parameters of its circular
/// photon orbits, on each side (to 10⁻⁶).
#[test]
fn kerr_newman_shadow_edges_match_its_equatorial_photon_orbits() {
    for (spin, charge) in [(0.6, 0.5), (-0.5, 0.7), (0.8, 0.5)] {
        let (pro, retro) = analytic::kerr_newman_equatorial_critical_impacts(1.0, spin, charge);
        let hole = Spacetime::kerr_newman(1.0, spin, charge).unwrap();
        // Rays with b > 0 orbit with a hole of positive spin, against one of negative spin.
        let (plus, minus) = if spin > 0.0 { (pro, retro) } else { (retro, pro) };
        let (found_plus, found_minus) =
            (equatorial_critical_impact(&hole, 1.0), equatorial_critical_impact(&hole, -1.0));
        let what = format!("a = {spin}, Q = {charge}");
        assert!(((found_plus - plus) / plus).abs() < 1e-6, "{what}: b > 0 side {found_plus} vs {plus}");
        assert!(((found_minus - minus) / minus).abs() < 1e-6, "{what}: b < 0 side {found_minus} vs {minus}");
    }
}

#[test]
fn kerr_with_zero_spin_bends_like_schwarzschild() {
    let exact = analytic::schwarzschild_deflection(1.0, 20.0);
    let s = scatter(&Spacetime::kerr(1.0, 0.0).unwrap(), 20.0, 0.4, ADAPTIVE);
    assert!(((s.deflection_rad - exact) / exact).abs() < 1e-6, "{} vs {exact}", s.deflection_rad);
}

#[test]
fn rk4_is_available_and_converges() {
    let hole = Spacetime::schwarzschild(1.0).unwrap();
    let exact = analytic::schwarzschild_deflection(1.0, 10.0);
    let coarse = scatter(&hole, 10.0, 0.0, Stepping::Rk4 { step: 0.05 });
    let fine = scatter(&hole, 10.0, 0.0, Stepping::Rk4 { step: 0.025 });
    let (ec, ef) = ((coarse.deflection_rad - exact).abs(), (fine.deflection_rad - exact).abs());
    assert!(ef < 1e-5 && ef < ec / 8.0, "RK4 errors {ec:e} → {ef:e}");
}

/// Interstellar's proportions (James et al. 2015: `a = 0.005 ρ`, `𝒲 = 0.05 ρ`), a long
/// wormhole with a wide lens, and one without a cylinder.
fn dneg_wormholes() -> [spacetime::Dneg; 3] {
    [spacetime::Dneg::new(1.0, 0.01, 0.05), spacetime::Dneg::new(2.0, 2.0, 1.5), spacetime::Dneg::new(1.0, 0.0, 0.5)]
}

/// Tolerance of the wormhole tests: their errors are proportional to it, and at the shared
/// 10⁻¹⁰ rays that graze a mouth (`b = 1.001 ρ`), whose bending the orbit amplifies, are off by
/// up to 4·10⁻⁷ (measured; 5·10⁻⁹ at 10⁻¹²).
const WORMHOLE: Stepping = Stepping::Adaptive { rtol: 1e-12 };

/// The tracer's bending past the *Interstellar* wormhole matches the quadrature of its integral
/// ([`analytic::wormhole_deflection`]) to 10⁻⁷, from rays that graze the mouth (`b = 1.001 ρ`,
/// turning just outside the kink of `r(l)` at `|l| = a`, where `r''` jumps: the step-size
/// control resolves it) to the weak field, in the split tracer's range (`b > 64 ρ`) too.
#[test]
fn interstellar_wormhole_bending_matches_the_exact_integral() {
    for shape in dneg_wormholes() {
        let (rho, length, width) = (shape.throat, shape.length, shape.lensing_width);
        let wormhole = Spacetime::wormhole(rho, length, width).unwrap();
        for factor in [1.001, 1.01, 1.1, 1.5, 3.0, 10.0, 100.0, 1e3, 1e4] {
            let b = factor * rho;
            let s = scatter(&wormhole, b, 0.3, WORMHOLE);
            assert!(matches!(s.fate, Fate::Escaped { .. }), "{shape:?}, b = {b}: {:?}", s.fate);
            let exact = analytic::wormhole_deflection(&shape, b);
            let rel = (s.deflection_rad - exact).abs() / exact.abs();
            assert!(rel < 1e-7, "{shape:?}, b = {b}: {} vs exact {exact} ({rel:e})", s.deflection_rad);
            // Measured: |H| ≤ 3·10⁻⁸ up to b = 100 ρ, rising to 8·10⁻⁶ at 10⁴ ρ.
            assert!(s.max_abs_hamiltonian < 1e-5, "{shape:?}, b = {b}: |H| = {:e}", s.max_abs_hamiltonian);
        }
    }
}

/// Rays inside the throat go through, across both kinks and the cylinder, and sweep the
/// quadrature's azimuth to 10⁻⁷.
#[test]
fn interstellar_wormhole_rays_inside_the_throat_traverse_and_sweep_the_exact_azimuth() {
    for shape in dneg_wormholes() {
        let wormhole = Spacetime::wormhole(shape.throat, shape.length, shape.lensing_width).unwrap();
        for factor in [0.01, 0.3, 0.8, 0.99] {
            let b = factor * shape.throat;
            let s = scatter(&wormhole, b, 0.7, WORMHOLE);
            assert!(matches!(s.fate, Fate::Traversed { .. }), "{shape:?}, b = {b}: {:?}", s.fate);
            let swept = s.deflection_rad + std::f64::consts::PI;
            let exact = analytic::wormhole_deflection(&shape, b) + std::f64::consts::PI;
            assert!(((swept - exact) / exact).abs() < 1e-7, "{shape:?}, b = {b}: swept {swept} vs {exact}");
        }
    }
}

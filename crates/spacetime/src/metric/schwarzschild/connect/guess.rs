//! The first guesses of a connection's start, before the start tables' corrections
//! ([`super::start_table`]): the short way's to first order in `M`, the long way's from the
//! strong-deflection limit; and the scale-free parameter each way is shot by.

use crate::geodesic::plane::Way;

/// The start slope `s` of (1) to first order in `M`: with the flat solution
/// `u₀ = u_x cos φ + s sin φ`, the correction `w'' + w = 3Mu₀²`, `w(0) = w'(0) = 0`, is
/// `3M[(u_x² + s²)(1 − cos φ)/2 + (u_x² − s²)(cos φ − cos 2φ)/6 + u_x s (2 sin φ − sin 2φ)/3]`,
/// and `u₀ + w = u_y` at `φ = Δφ` is a quadratic in `s`; its root nearest the flat one. A good
/// guess saves Newton iterations, each a full integration.
pub(super) fn first_guess(mass: f64, ux: f64, uy: f64, cos: f64, sin: f64) -> f64 {
    let (cos2, sin2) = (cos * cos - sin * sin, 2.0 * sin * cos);
    let (even, odd) = ((1.0 - cos) / 2.0, (cos - cos2) / 6.0);
    let a2 = 3.0 * mass * (even - odd);
    let a1 = sin + mass * ux * (2.0 * sin - sin2);
    let a0 = ux * cos - uy + 3.0 * mass * ux * ux * (even + odd);
    let discriminant = a1 * a1 - 4.0 * a2 * a0;
    if a1 > 0.0 && discriminant >= 0.0 {
        // The root that tends to the flat −a0/a1 as M → 0, in cancellation-free form.
        -2.0 * a0 / (a1 + discriminant.sqrt())
    } else {
        (uy - ux * cos) / sin
    }
}

/// `sin ψ_c`, the sine of the critical angle at `u_x` (outside the photon sphere): rays leaving
/// inward at more than `ψ_c` fall into the hole.
pub(super) fn critical_sin(mass: f64, ux: f64) -> f64 {
    3.0 * 3f64.sqrt() * mass * slope_scale(mass, ux)
}

/// `u_x/σ_x = u_x √(1 − 2Mu_x)`: the start slope of (1) is `s = −(u_x/σ_x) cot ψ`.
pub(super) fn slope_scale(mass: f64, ux: f64) -> f64 {
    ux * (1.0 - 2.0 * mass * ux).sqrt()
}

/// The parameter each way is shot, guessed and tabulated by, scale-free in `M`: the short way
/// by `Ms`, `M` times the start slope of (1); the long way by `ln ε`, where
/// `sin ψ = sin ψ_c (1 + ε)`, in which the sweep is nearly linear near the photon sphere.
pub(super) fn start_parameter(way: Way, mass: f64, ux: f64, psi: f64) -> f64 {
    match way {
        Way::Short => -mass * slope_scale(mass, ux) / psi.tan(),
        Way::Long => (psi.sin() / critical_sin(mass, ux) - 1.0).ln(),
    }
}

/// The long way's start slope `s` at [`start_parameter`] `ln ε`: `sin ψ = sin ψ_c (1 + ε)` on the
/// inward side.
pub(super) fn long_start_slope(mass: f64, ux: f64, ln_epsilon: f64) -> f64 {
    inward_slope(mass, ux, (critical_sin(mass, ux) * (1.0 + ln_epsilon.exp())).min(1.0))
}

/// The start slope `s = −(u_x/σ_x) cot ψ` of a ray leaving `u_x` inward (`ψ > π/2`) with
/// `sin ψ = sin`, where `−cot ψ = √(1 − sin²ψ)/sin ψ`.
pub(super) fn inward_slope(mass: f64, ux: f64, sin: f64) -> f64 {
    slope_scale(mass, ux) * (1.0 - sin * sin).sqrt() / sin
}

/// First guess of [`start_parameter`] for the ray from `u_x` to `u_y` sweeping `sweep` (the short
/// way's `Δφ` has cosine `cos` and sine `sin`).
///
/// Short way: [`first_guess`]. Long way: in the strong-deflection limit a ray with
/// `b = b_c(1 + ε)` from infinity to infinity sweeps `−ln ε + ln(216(7 − 4√3))` (Bozza 2002,
/// eq. 36 with π added), less the azimuth the critical ray sweeps between each end and infinity,
/// `S(u) = 2[artanh √(2M(u + 1/6M)) − artanh √(1/3)]` (the critical orbit's integral, since
/// `1/b_c² − u² + 2Mu³ = 2M(u − 1/3M)²(u + 1/6M)`); an end inside the photon sphere has no such
/// limit, and the guess is a little off critical.
pub(super) fn guessed_parameter(way: Way, mass: f64, ux: f64, uy: f64, cos: f64, sin: f64, sweep: f64) -> f64 {
    match way {
        Way::Short => mass * first_guess(mass, ux, uy, cos, sin),
        Way::Long => {
            let to_infinity =
                |u: f64| 2.0 * ((2.0 * mass * u + 1.0 / 3.0).sqrt().atanh() - (1.0f64 / 3.0).sqrt().atanh());
            let ln_epsilon = (216.0 * (7.0 - 4.0 * 3f64.sqrt())).ln() - sweep - to_infinity(ux) - to_infinity(uy);
            if ln_epsilon.is_finite() {
                ln_epsilon
            } else {
                0.05f64.ln()
            }
        }
    }
}

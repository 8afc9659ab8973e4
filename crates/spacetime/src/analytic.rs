//! Exact results that the integrators are checked against: answers for tests, compiled only for
//! them (this crate's unit tests, and the `test-answers` feature that the tests of this crate,
//! the renderer and the binary turn on as a dev-dependency), not part of the library a renderer
//! uses.
//!
//! Bending angles are written as integrals whose flat-space part is subtracted analytically, so
//! that tiny weak-field angles keep full relative precision, and evaluated by adaptive quadrature.

use crate::metric::Shape;
use std::f64::consts::{FRAC_PI_2, PI};

/// Tanh–sinh (double exponential) quadrature of `f` on `[a, b]` to relative tolerance `rel_tol`
/// (Takahasi & Mori 1974). The step is halved until two levels agree; the error falls
/// doubly exponentially, and endpoint peaks (near-critical orbits) cost little.
pub fn integrate(f: &impl Fn(f64) -> f64, a: f64, b: f64, rel_tol: f64) -> f64 {
    const T_MAX: f64 = 3.2;
    let (c, d) = (0.5 * (a + b), 0.5 * (b - a));
    let term = |t: f64| {
        let u = FRAC_PI_2 * t.sinh();
        let w = FRAC_PI_2 * t.cosh() / u.cosh().powi(2);
        d * w * f(c + d * u.tanh())
    };
    let mut h = 0.5;
    let mut sum = term(0.0);
    let mut k = 1.0;
    while k * h <= T_MAX {
        sum += term(k * h) + term(-k * h);
        k += 1.0;
    }
    let mut estimate = h * sum;
    for _ in 0..14 {
        h *= 0.5;
        let mut k = 1.0;
        while k * h <= T_MAX {
            sum += term(k * h) + term(-k * h);
            k += 2.0;
        }
        let refined = h * sum;
        if (refined - estimate).abs() <= rel_tol * refined.abs() {
            return refined;
        }
        estimate = refined;
    }
    estimate
}

/// `a^{-1/2} − b^{-1/2}` without cancellation, given `b − a` directly.
fn inv_sqrt_difference(a: f64, b: f64, b_minus_a: f64) -> f64 {
    let (sa, sb) = (a.sqrt(), b.sqrt());
    b_minus_a / (sa * sb * (sa + sb))
}

/// Critical impact parameter of a Schwarzschild hole, `3√3 M`: smaller ones are captured.
pub fn schwarzschild_critical_impact(mass: f64) -> f64 {
    3.0 * 3f64.sqrt() * mass
}

/// Radius of closest approach for impact parameter `b > 3√3 M`: the largest root of
/// `r³ − b² r + 2 M b² = 0`, `r₀ = (2b/√3) cos(⅓ arccos(−3√3 M / b))`.
pub fn schwarzschild_closest_approach(mass: f64, b: f64) -> f64 {
    2.0 * b / 3f64.sqrt() * ((-schwarzschild_critical_impact(mass) / b).acos() / 3.0).cos()
}

/// Exact bending angle of a light ray with impact parameter `b > 3√3 M` past a Schwarzschild hole,
/// `α = 2∫₀^{u₀} du / √(1/b² − u² + 2Mu³) − π`.
///
/// With `u = u₀ x`, `1/b² = u₀² − 2Mu₀³` and `x = 1 − t²` this becomes
/// `α = 4∫₀¹ [q(x)^{-1/2} − (1+x)^{-1/2}] dt`, `q = 1 + x − ε(1 + x + x²)`, `ε = 2M u₀`: a smooth
/// integrand of the size of the bending itself.
pub fn schwarzschild_deflection(mass: f64, b: f64) -> f64 {
    static_deflection(2.0 * mass / schwarzschild_closest_approach(mass, b), 0.0)
}

/// `α = 4∫₀¹ [q(x)^{-1/2} − (1+x)^{-1/2}] dt`, `x = 1 − t²`,
/// `q = 1 + x − ε(1 + x + x²) + η(1 + x)(1 + x²)`: the bending of a ray whose closest approach
/// `u₀ = 1/r₀` gives `ε = 2Mu₀` and `η = Q²u₀²` ([`reissner_nordstrom_deflection`]; `η = 0`
/// without charge).
fn static_deflection(eps: f64, eta: f64) -> f64 {
    let integrand = |t: f64| {
        let x = 1.0 - t * t;
        let extra = eps * (1.0 + x + x * x) - eta * (1.0 + x) * (1.0 + x * x);
        -inv_sqrt_difference(1.0 + x, 1.0 + x - extra, -extra)
    };
    4.0 * integrate(&integrand, 0.0, 1.0, 1e-13)
}

/// The photon sphere of a Reissner–Nordström hole, `r_ph = (3M + √(9M² − 8Q²))/2`, where
/// `A(r)/r²` (`A = 1 − 2M/r + Q²/r²`) has its maximum (Chandrasekhar 1983, §40).
pub fn reissner_nordstrom_photon_sphere(mass: f64, charge: f64) -> f64 {
    0.5 * (3.0 * mass + (9.0 * mass * mass - 8.0 * charge * charge).sqrt())
}

/// `A(r) = 1 − 2M/r + Q²/r²`, the Reissner–Nordström lapse squared.
fn reissner_nordstrom_a(mass: f64, charge: f64, r: f64) -> f64 {
    1.0 - 2.0 * mass / r + (charge / r).powi(2)
}

/// The critical impact parameter `b_c = r_ph/√A(r_ph)` of a Reissner–Nordström hole: rays from
/// infinity with a smaller one are captured.
pub fn reissner_nordstrom_critical_impact(mass: f64, charge: f64) -> f64 {
    let r = reissner_nordstrom_photon_sphere(mass, charge);
    r / reissner_nordstrom_a(mass, charge, r).sqrt()
}

/// Angular radius of the Reissner–Nordström shadow seen by a static observer at radius
/// `r ≥ r_ph`: `sin α = b_c √A(r) / r`.
pub fn reissner_nordstrom_shadow_angle(mass: f64, charge: f64, r: f64) -> f64 {
    (reissner_nordstrom_critical_impact(mass, charge) * reissner_nordstrom_a(mass, charge, r).sqrt() / r).asin()
}

/// Exact bending angle of a ray with impact parameter `b > b_c` past a Reissner–Nordström hole,
/// `α = 2∫₀^{u₀} du / √(1/b² − u² + 2Mu³ − Q²u⁴) − π`, with `u₀` the smallest root of
/// `u²A(u) = 1/b²` (found by bisection on `[0, 1/r_ph]`, where `u²A` increases), written as
/// [`static_deflection`] with `u = u₀ x`.
pub fn reissner_nordstrom_deflection(mass: f64, charge: f64, b: f64) -> f64 {
    let target = 1.0 / (b * b);
    let f = |u: f64| u * u * reissner_nordstrom_a(mass, charge, 1.0 / u) - target;
    let (mut lo, mut hi) = (0.0, 1.0 / reissner_nordstrom_photon_sphere(mass, charge));
    loop {
        let mid = 0.5 * (lo + hi);
        if mid <= lo || mid >= hi {
            break;
        }
        if f(mid) < 0.0 {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    static_deflection(2.0 * mass * lo, (charge * lo).powi(2))
}

/// Azimuth swept by a ray of impact parameter `b` through an Ellis wormhole of throat `b₀`,
/// minus π: the bending angle for `b > b₀` (the ray turns back),
/// `α = 2∫_{l_min}^∞ b dl / ((l² + b₀²)√(1 − b²/(l² + b₀²))) − π`, and for `b < b₀` (through the
/// throat) the same integrand over all `l`: `2∫₀^∞ … − π`.
///
/// With `ρ = √(l² + b₀²)`, `x = b/ρ` and `x = sin θ` (resp. `y = sin θ` for `b < b₀`):
/// `α = 2∫₀^{π/2} [(1 − β² sin²θ)^{-1/2} − 1] dθ` with `β = b₀/b` for `b > b₀`, and
/// `α = 2k∫₀^{π/2} (1 − k² sin²θ)^{-1/2} dθ − π` with `k = b/b₀` for `b < b₀`.
pub fn ellis_deflection(throat: f64, b: f64) -> f64 {
    if b > throat {
        let beta2 = (throat / b).powi(2);
        let integrand = |theta: f64| {
            let s = beta2 * theta.sin().powi(2);
            inv_sqrt_difference(1.0 - s, 1.0, s)
        };
        2.0 * integrate(&integrand, 0.0, FRAC_PI_2, 1e-13)
    } else {
        let k = b / throat;
        let integrand = |theta: f64| (1.0 - (k * theta.sin()).powi(2)).powf(-0.5);
        2.0 * k * integrate(&integrand, 0.0, FRAC_PI_2, 1e-13) - PI
    }
}

/// Azimuth swept by a ray of impact parameter `b` through a Morris–Thorne wormhole of any
/// [`Shape`] (`Φ = 0`), minus π: `2∫ b dl / (r √(r² − b²)) − π`, from the turning point
/// `r(l_t) = b` outwards for `b > ρ` (the ray turns back), over all `l` for `b < ρ` (it goes
/// through).
///
/// For `b > ρ`, with `r = b/sin θ` the flat part is `π` exactly and
/// `α = 2∫₀^{π/2} (1/r_l − 1) dθ`, `r_l = dr/dl` at `r`: smooth, of the size of the bending, and
/// finite at the turning point where `r_l > 0`. For `b < ρ`, `2∫₀^∞` splits into the part with
/// `r = ρ` (`|l| ≤ a`, where [`Shape::proper_distance`]`(ρ) = a`) and `l = a + ρ tan θ` beyond.
pub fn wormhole_deflection<S: Shape>(shape: &S, b: f64) -> f64 {
    let throat = shape.throat();
    if b > throat {
        let integrand = |theta: f64| {
            let sin = theta.sin();
            if sin <= 0.0 {
                return 0.0;
            }
            let slope = shape.radius(shape.proper_distance(b / sin)).slope;
            (1.0 - slope) / slope
        };
        2.0 * integrate(&integrand, 0.0, FRAC_PI_2, 1e-13)
    } else {
        let a = shape.proper_distance(throat);
        let cylinder = a * b / (throat * ((throat - b) * (throat + b)).sqrt());
        let integrand = |theta: f64| {
            let (sin, cos) = theta.sin_cos();
            let r = shape.radius(a + throat * sin / cos).r;
            let root = ((r - b) * (r + b)).sqrt();
            if cos <= 0.0 || !root.is_finite() {
                return b / throat;
            }
            b * throat / (cos * cos * r * root)
        };
        2.0 * (cylinder + integrate(&integrand, 0.0, FRAC_PI_2, 1e-13)) - PI
    }
}

/// Weak-field Schwarzschild bending, `4M/b + 15πM²/(4b²)`.
pub fn schwarzschild_deflection_weak(mass: f64, b: f64) -> f64 {
    4.0 * mass / b + 15.0 * PI * mass * mass / (4.0 * b * b)
}

/// Angular radius of the Schwarzschild shadow seen by a static observer at radius `r`:
/// `sin α = 3√3 M √(1 − 2M/r) / r` (Synge 1966).
pub fn schwarzschild_shadow_angle(mass: f64, r: f64) -> f64 {
    let s = schwarzschild_critical_impact(mass) * (1.0 - 2.0 * mass / r).sqrt() / r;
    if r < 3.0 * mass {
        PI - s.asin()
    } else {
        s.asin()
    }
}

/// Impact parameters `ξ = L_z/E` of the two circular equatorial photon orbits of a Kerr hole
/// (Bardeen 1973): returns `(prograde, retrograde)`, positive for orbits co-rotating with the hole.
/// Photon orbit radii `r = 2M(1 + cos(⅔ arccos(∓a/M)))`, and
/// `ξ(r) = −(r³ − 3Mr² + a²r + a²M) / (a(r − M))`.
pub fn kerr_equatorial_critical_impacts(mass: f64, spin: f64) -> (f64, f64) {
    if spin == 0.0 {
        let b = schwarzschild_critical_impact(mass);
        return (b, -b);
    }
    let a = spin.abs();
    let radius = |sign: f64| 2.0 * mass * (1.0 + ((2.0 / 3.0) * (sign * a / mass).acos()).cos());
    let xi = |r: f64| -(r * r * r - 3.0 * mass * r * r + a * a * r + a * a * mass) / (a * (r - mass));
    let (pro, retro) = (xi(radius(-1.0)), xi(radius(1.0)));
    if spin > 0.0 {
        (pro, retro)
    } else {
        (-pro, -retro)
    }
}

/// Radii of the two circular equatorial photon orbits of a Kerr–Newman hole of spin `|a|`,
/// `(prograde, retrograde)`: the roots outside the horizon of
/// `r² − 3Mr + 2Q² ± 2a√(Mr − Q²) = 0` (+ prograde), found by bisection on `[r₊, 4M]`.
fn kerr_newman_equatorial_orbit_radii(mass: f64, spin: f64, charge: f64) -> (f64, f64) {
    let (m, a, q2) = (mass, spin.abs(), charge * charge);
    let horizon = m + (m * m - a * a - q2).sqrt();
    let radius = |sign: f64| {
        let f = |r: f64| r * r - 3.0 * m * r + 2.0 * q2 + sign * 2.0 * a * (m * r - q2).sqrt();
        let (mut lo, mut hi) = (horizon, 4.0 * m);
        for _ in 0..200 {
            let mid = 0.5 * (lo + hi);
            if f(mid) < 0.0 {
                lo = mid;
            } else {
                hi = mid;
            }
        }
        0.5 * (lo + hi)
    };
    (radius(1.0), radius(-1.0))
}

/// The constants of motion `(ξ, η) = (L_z/E, Carter's Q/E²)` of the spherical photon orbit of
/// radius `r` around a Kerr–Newman hole of spin `a ≠ 0`: `R(r) = R'(r) = 0` for the radial
/// potential `R = (r² + a² − aξ)² − Δ(η + (ξ − a)²)`, `Δ = r² − 2Mr + a² + Q²`, give
/// `aξ = r² + a² − 4rΔ/Δ'` and `η + (ξ − a)² = 16r²Δ/Δ'²` (Bardeen 1973 at `Q = 0`;
/// de Vries 2000, Class. Quantum Grav. 17, 123, with charge).
fn kerr_newman_spherical_orbit(mass: f64, spin: f64, charge: f64, r: f64) -> (f64, f64) {
    let delta = r * r - 2.0 * mass * r + spin * spin + charge * charge;
    let d_delta = 2.0 * (r - mass);
    let xi = (r * r + spin * spin - 4.0 * r * delta / d_delta) / spin;
    let eta = 16.0 * r * r * delta / (d_delta * d_delta) - (xi - spin).powi(2);
    (xi, eta)
}

/// Impact parameters `ξ = L_z/E` of the two circular equatorial photon orbits of a Kerr–Newman
/// hole, `(prograde, retrograde)` signed as [`kerr_equatorial_critical_impacts`]'s
/// ([`kerr_newman_spherical_orbit`] at the radii of `kerr_newman_equatorial_orbit_radii`; Kerr's
/// formula at `Q = 0`).
pub fn kerr_newman_equatorial_critical_impacts(mass: f64, spin: f64, charge: f64) -> (f64, f64) {
    let (pro, retro) = kerr_newman_equatorial_orbit_radii(mass, spin, charge);
    let xi = |r: f64| kerr_newman_spherical_orbit(mass, spin.abs(), charge, r).0;
    let (pro, retro) = (xi(pro), xi(retro));
    if spin > 0.0 {
        (pro, retro)
    } else {
        (-pro, -retro)
    }
}

/// The shadow's boundary seen by a distant observer at inclination `i` (radians from the spin
/// axis) of a Kerr–Newman hole with `spin > 0`: the generalised Bardeen curve, `n` points
/// `(α, β)` of its upper half (`β ≥ 0`; the lower half is its mirror) in order of the orbit's
/// radius, `α = −ξ/sin i`, `β = √(η + a² cos² i − ξ² cot² i)` for the spherical photon orbits
/// ([`kerr_newman_spherical_orbit`]) between the equatorial ones (clustered at both), where
/// `β² ≥ 0`. `α > 0` is the
/// side where the hole's surface recedes from the observer (retrograde orbits).
pub fn kerr_newman_shadow(mass: f64, spin: f64, charge: f64, inclination: f64, n: usize) -> Vec<(f64, f64)> {
    let (pro, retro) = kerr_newman_equatorial_orbit_radii(mass, spin, charge);
    let (sin, cos) = inclination.sin_cos();
    (0..n)
        .filter_map(|k| {
            // Clustered at the ends, where β rises like the square root of the radius.
            let t = 0.5 * (1.0 - (PI * k as f64 / (n - 1) as f64).cos());
            let r = pro + (retro - pro) * t;
            let (xi, eta) = kerr_newman_spherical_orbit(mass, spin, charge, r);
            let beta2 = eta + (spin * cos).powi(2) - (xi * cos / sin).powi(2);
            (beta2 >= 0.0).then(|| (-xi / sin, beta2.sqrt()))
        })
        .collect()
}

/// Radius of the innermost stable prograde circular orbit of a Kerr hole of spin `0 ≤ a ≤ M`
/// (Bardeen, Press & Teukolsky 1972, eq. 2.21): `r = M(3 + Z₂ − √((3 − Z₁)(3 + Z₁ + 2Z₂)))`,
/// `Z₁ = 1 + ∛(1 − χ²)(∛(1 + χ) + ∛(1 − χ))`, `Z₂ = √(3χ² + Z₁²)`, `χ = a/M`.
pub fn kerr_isco(mass: f64, spin: f64) -> f64 {
    let chi = spin / mass;
    let z1 = 1.0 + (1.0 - chi * chi).cbrt() * ((1.0 + chi).cbrt() + (1.0 - chi).cbrt());
    let z2 = (3.0 * chi * chi + z1 * z1).sqrt();
    mass * (3.0 + z2 - ((3.0 - z1) * (3.0 + z1 + 2.0 * z2)).sqrt())
}

/// Energy per unit rest mass of the prograde circular equatorial orbit of radius `r` about a
/// Kerr hole of spin `0 ≤ a ≤ M` (Bardeen, Press & Teukolsky 1972, eq. 2.12):
/// `E = (r^{3/2} − 2M r^{1/2} + a M^{1/2}) / (r^{3/4} √(r^{3/2} − 3M r^{1/2} + 2a M^{1/2}))`.
pub fn kerr_orbit_energy(mass: f64, spin: f64, r: f64) -> f64 {
    let (sr, sm) = (r.sqrt(), mass.sqrt());
    (r * sr - 2.0 * mass * sr + spin * sm) / (r.powf(0.75) * (r * sr - 3.0 * mass * sr + 2.0 * spin * sm).sqrt())
}

/// Page & Thorne's (1974, eq. 15n) flux per face of a thin disk about a Kerr hole of spin
/// `0 < a ≤ M`, per unit accretion rate, at Boyer–Lindquist radius `r` ≥ the ISCO: with
/// `x = √(r/M)`, `x₀` its value at the ISCO, `a* = a/M` and `x₁,₂,₃ = 2 cos((arccos a* ∓ π)/3)`,
/// `−2 cos(arccos(a*)/3)` the roots of `x³ − 3x + 2a* = 0`,
/// `F = 3/(8πM²) · 1/(x⁴(x³ − 3x + 2a*)) · [x − x₀ − (3/2) a* ln(x/x₀)
/// − Σᵢ 3(xᵢ − a*)²/(xᵢ Πⱼ≠ᵢ(xᵢ − xⱼ)) ln((x − xᵢ)/(x₀ − xᵢ))]`.
pub fn page_thorne_kerr_flux(mass: f64, spin: f64, r: f64) -> f64 {
    let chi = spin / mass;
    let x = (r / mass).sqrt();
    let x0 = (kerr_isco(mass, spin) / mass).sqrt();
    let angle = chi.acos();
    let roots = [2.0 * ((angle - PI) / 3.0).cos(), 2.0 * ((angle + PI) / 3.0).cos(), -2.0 * (angle / 3.0).cos()];
    let mut bracket = x - x0 - 1.5 * chi * (x / x0).ln();
    for (i, &xi) in roots.iter().enumerate() {
        let others: f64 = roots.iter().enumerate().filter(|&(j, _)| j != i).map(|(_, &xj)| xi - xj).product();
        bracket -= 3.0 * (xi - chi).powi(2) / (xi * others) * ((x - xi) / (x0 - xi)).ln();
    }
    3.0 / (8.0 * PI * mass * mass) * bracket / (x.powi(4) * (x.powi(3) - 3.0 * x + 2.0 * chi))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn quadrature_of_known_integrals() {
        assert!((integrate(&|x: f64| x.sin(), 0.0, PI, 1e-13) - 2.0).abs() < 1e-13);
        assert!((integrate(&|x: f64| 1.0 / (1.0 + x * x), 0.0, 1.0, 1e-13) - PI / 4.0).abs() < 1e-14);
    }

    #[test]
    fn schwarzschild_bending_tends_to_weak_field() {
        for b in [1e3, 1e4, 1e5] {
            let exact = schwarzschild_deflection(1.0, b);
            // Next term is O(M³/b³): relative difference below ~ 100/b².
            let weak = schwarzschild_deflection_weak(1.0, b);
            assert!(((exact - weak) / exact).abs() < 100.0 / (b * b), "b = {b}: {exact} vs {weak}");
        }
        // Diverges towards the photon sphere.
        assert!(schwarzschild_deflection(1.0, 5.25) > 3.0);
    }

    /// Without charge the charged hole's results are Schwarzschild's; an extremal hole's photon
    /// sphere is at 2M with `b_c = 4M`; far out the bending is
    /// `4M/b + 15πM²/(4b²) − 3πQ²/(4b²) + O(b⁻³)` (the charge term, 2.4·10⁻⁶ at b = 10³ M, is 50
    /// times the bound on the next order, ~27 M³/b³ for Q = M).
    #[test]
    fn reissner_nordstrom_results_reduce_and_tend_to_weak_field() {
        assert!((reissner_nordstrom_critical_impact(1.0, 0.0) - schwarzschild_critical_impact(1.0)).abs() < 1e-14);
        assert!(
            (reissner_nordstrom_deflection(1.0, 0.0, 8.0) / schwarzschild_deflection(1.0, 8.0) - 1.0).abs() < 1e-12
        );
        assert_eq!(reissner_nordstrom_photon_sphere(1.0, 1.0), 2.0);
        assert!((reissner_nordstrom_critical_impact(1.0, 1.0) - 4.0).abs() < 1e-14);
        for b in [1e3, 1e4] {
            let exact = reissner_nordstrom_deflection(1.0, 1.0, b);
            let weak = schwarzschild_deflection_weak(1.0, b) - 0.75 * PI / (b * b);
            assert!((exact - weak).abs() < 50.0 / (b * b * b), "b = {b}: {exact} vs {weak}");
        }
    }

    #[test]
    fn ellis_bending_matches_elliptic_integral_and_weak_field() {
        // α = 2K(b₀/b) − π with K by the arithmetic–geometric mean.
        let k_agm = |k: f64| {
            let (mut a, mut g) = (1.0f64, (1.0 - k * k).sqrt());
            for _ in 0..30 {
                (a, g) = (0.5 * (a + g), (a * g).sqrt());
            }
            PI / (2.0 * a)
        };
        for b in [1.01, 1.5, 3.0, 10.0] {
            let exact = ellis_deflection(1.0, b);
            assert!((exact - (2.0 * k_agm(1.0 / b) - PI)).abs() < 1e-12, "b = {b}");
        }
        for b in [0.1, 0.5, 0.99] {
            assert!((ellis_deflection(1.0, b) - (2.0 * b * k_agm(b) - PI)).abs() < 1e-12, "b = {b}");
        }
        let b = 1e4;
        assert!((ellis_deflection(1.0, b) / (PI / 4.0 / (b * b)) - 1.0).abs() < 1e-7);
    }

    #[test]
    fn kerr_critical_impacts() {
        let (p, r) = kerr_equatorial_critical_impacts(1.0, 0.9);
        assert!((p - 2.845).abs() < 1e-3 && (r + 6.833).abs() < 1e-3, "{p} {r}");
        let (p, r) = kerr_equatorial_critical_impacts(1.0, 1e-7);
        assert!((p - 27f64.sqrt()).abs() < 1e-6 && (r + 27f64.sqrt()).abs() < 1e-6);
    }

    /// Seen from the equator without spin the shadow is the circle of radius `b_c` (here
    /// Reissner–Nordström's, `Q = 0.6 M`, spin 10⁻⁶ M), and a Kerr hole of spin 0.9 M seen edge-on spans
    /// Bardeen's `α ∈ [−2.85, 6.83]`.
    #[test]
    fn kerr_newman_shadow_reduces_to_known_curves() {
        let b_c = reissner_nordstrom_critical_impact(1.0, 0.6);
        for (alpha, beta) in kerr_newman_shadow(1.0, 1e-6, 0.6, FRAC_PI_2, 200) {
            assert!((alpha.hypot(beta) - b_c).abs() < 1e-5, "({alpha}, {beta}) off the circle {b_c}");
        }
        let curve = kerr_newman_shadow(1.0, 0.9, 0.0, FRAC_PI_2, 2000);
        let (first, last) = (curve[0], curve[curve.len() - 1]);
        assert!((first.0 + 2.845).abs() < 1e-3 && (last.0 - 6.833).abs() < 1e-3, "{first:?} … {last:?}");
        assert!(first.1 < 0.02 && last.1 < 0.02, "{first:?} … {last:?}");
    }

    /// Without charge the Kerr–Newman orbits are Kerr's closed forms.
    #[test]
    fn kerr_newman_critical_impacts_reduce_to_kerrs() {
        for spin in [0.5, -0.9] {
            let (p, r) = kerr_equatorial_critical_impacts(1.0, spin);
            let (pn, rn) = kerr_newman_equatorial_critical_impacts(1.0, spin, 0.0);
            assert!((p - pn).abs() < 1e-12 && (r - rn).abs() < 1e-12, "a = {spin}: {p} {r} vs {pn} {rn}");
        }
    }

    #[test]
    fn shadow_of_a_distant_observer_tends_to_critical_impact_over_r() {
        let r = 1e6;
        assert!((schwarzschild_shadow_angle(1.0, r) * r / 27f64.sqrt() - 1.0).abs() < 1e-5);
    }
}

//! Warps from the unit square to directions and points, each with its density.

use crate::geometry::Vec3;
use std::f64::consts::{FRAC_1_PI, PI};

/// Cosine-weighted direction on the +z hemisphere (Malley's method on a concentric disk).
pub fn cosine_hemisphere(u: [f64; 2]) -> Vec3 {
    let [x, y] = concentric_disk(u);
    let z = (1.0 - x * x - y * y).max(0.0).sqrt();
    Vec3::new(x, y, z)
}

/// Density of [`cosine_hemisphere`] per unit solid angle.
pub fn cosine_hemisphere_pdf(cos_theta: f64) -> f64 {
    cos_theta.max(0.0) * FRAC_1_PI
}

/// Uniform direction on the unit sphere.
pub fn uniform_sphere(u: [f64; 2]) -> Vec3 {
    let z = 1.0 - 2.0 * u[0];
    let r = (1.0 - z * z).max(0.0).sqrt();
    let phi = 2.0 * PI * u[1];
    Vec3::new(r * phi.cos(), r * phi.sin(), z)
}

pub const UNIFORM_SPHERE_PDF: f64 = 0.25 * FRAC_1_PI;

/// Uniform direction in the cone about +z of half-angle `θ_max`, given as `cap = 1 − cos θ_max`
/// (which callers can compute without cancellation for narrow cones): `1 − cos θ` is uniform
/// on `[0, cap]`. Its density is `1 / (2π cap)`.
pub fn uniform_cone(cap: f64, u: [f64; 2]) -> Vec3 {
    let one_minus_cos = u[0] * cap;
    let sin = (one_minus_cos * (2.0 - one_minus_cos)).max(0.0).sqrt();
    let phi = 2.0 * PI * u[1];
    Vec3::new(sin * phi.cos(), sin * phi.sin(), 1.0 - one_minus_cos)
}

/// Uniform point in the unit disk, Shirley–Chiu concentric mapping (area preserving, low distortion).
pub fn concentric_disk(u: [f64; 2]) -> [f64; 2] {
    let a = 2.0 * u[0] - 1.0;
    let b = 2.0 * u[1] - 1.0;
    if a == 0.0 && b == 0.0 {
        return [0.0, 0.0];
    }
    // θ = π/4 · b/a, or π/2 − π/4 · a/b, whose cosine and sine are the sine and cosine of
    // π/4 · a/b: only angles within ±π/4 are needed. Chosen by selects, not branches, as the
    // case is a coin flip per sample.
    let swap = a.abs() <= b.abs();
    let (r, other) = if swap { (b, a) } else { (a, b) };
    let (sin, cos) = sin_cos_within_quarter_pi(PI / 4.0 * (other / r));
    let (x, y) = if swap { (sin, cos) } else { (cos, sin) };
    [r * x, r * y]
}

/// fdlibm's minimax coefficients of sin on [−π/4, π/4], of x³ to x¹³ (`k_sin.c`).
const SIN_COEFFICIENTS: [f64; 6] = [
    -1.666_666_666_666_663_2e-1,
    8.333_333_333_322_49e-3,
    -1.984_126_982_985_795e-4,
    2.755_731_370_707_006_8e-6,
    -2.505_076_025_340_686_3e-8,
    1.589_690_995_211_55e-10,
];
/// fdlibm's minimax coefficients of cos on [−π/4, π/4], of x⁴ to x¹⁴ (`k_cos.c`).
const COS_COEFFICIENTS: [f64; 6] = [
    4.166_666_666_666_66e-2,
    -1.388_888_888_887_411e-3,
    2.480_158_728_947_673e-5,
    -2.755_731_435_139_066_3e-7,
    2.087_572_321_298_175e-9,
    -1.135_964_755_778_819_5e-11,
];

/// (sin x, cos x) for |x| ≤ π/4 with no argument reduction: fdlibm's kernels `__kernel_sin` and
/// `__kernel_cos` (Sun Microsystems 1993, with no tail of a reduced argument), each below one ulp
/// of error there; the two polynomials are independent, so their chains overlap.
fn sin_cos_within_quarter_pi(x: f64) -> (f64, f64) {
    let z = x * x;
    let horner = |c: &[f64; 6]| c[..5].iter().rev().fold(c[5], |sum, &c| sum * z + c);
    let sin = x + x * z * horner(&SIN_COEFFICIENTS);
    // cos x = 1 − z/2 + z² C(z), with 1 − z/2 rounded and its rounding error added back.
    let half_z = 0.5 * z;
    let w = 1.0 - half_z;
    let cos = w + (((1.0 - w) - half_z) + z * z * horner(&COS_COEFFICIENTS));
    (sin, cos)
}

/// Uniform barycentric coordinates on a triangle (Heitz 2019, low-distortion square-to-triangle map).
pub fn uniform_triangle(u: [f64; 2]) -> [f64; 3] {
    let (b0, b1) = if u[0] < u[1] {
        let b0 = u[0] / 2.0;
        (b0, u[1] - b0)
    } else {
        let b1 = u[1] / 2.0;
        (u[0] - b1, b1)
    };
    [b0, b1, 1.0 - b0 - b1]
}

/// Power heuristic with β = 2 (Veach 1997, §9.2.4): the weight of a strategy with density `pdf_a`
/// against one with density `pdf_b`.
pub fn power_heuristic(pdf_a: f64, pdf_b: f64) -> f64 {
    let a = pdf_a * pdf_a;
    let b = pdf_b * pdf_b;
    if a + b == 0.0 {
        0.0
    } else if a.is_infinite() {
        1.0
    } else {
        a / (a + b)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::sampling::Rng;

    #[test]
    fn quarter_pi_sin_cos_is_libms_to_the_last_bits() {
        for k in -10_000..=10_000 {
            let x = std::f64::consts::FRAC_PI_4 * k as f64 / 10_000.0;
            let (sin, cos) = sin_cos_within_quarter_pi(x);
            assert!((sin - x.sin()).abs() <= 2.0 * f64::EPSILON * x.sin().abs().max(f64::MIN_POSITIVE), "sin {x}");
            assert!((cos - x.cos()).abs() <= 2.0 * f64::EPSILON * x.cos(), "cos {x}");
        }
    }

    #[test]
    fn concentric_disk_is_shirley_chius_polar_map() {
        let mut r = Rng::new(11);
        for _ in 0..10_000 {
            let u = r.next_2d();
            let [a, b] = u.map(|v| 2.0 * v - 1.0);
            let (radius, theta) =
                if a.abs() > b.abs() { (a, PI / 4.0 * (b / a)) } else { (b, PI / 2.0 - PI / 4.0 * (a / b)) };
            let [x, y] = concentric_disk(u);
            assert!((x - radius * theta.cos()).abs() < 1e-15 && (y - radius * theta.sin()).abs() < 1e-15, "{u:?}");
        }
    }

    #[test]
    fn cosine_hemisphere_is_unit_and_upper() {
        let mut r = Rng::new(3);
        let mut mean_z = 0.0;
        let n = 50_000;
        for _ in 0..n {
            let d = cosine_hemisphere(r.next_2d());
            assert!((d.length() - 1.0).abs() < 1e-9 && d.z >= 0.0);
            mean_z += d.z;
        }
        // E[cos θ] under a cosine density is 2/3.
        assert!((mean_z / n as f64 - 2.0 / 3.0).abs() < 5e-3);
    }

    #[test]
    fn triangle_barycentrics_are_uniform() {
        let mut r = Rng::new(5);
        let n = 50_000;
        let mut mean = [0.0; 3];
        for _ in 0..n {
            let b = uniform_triangle(r.next_2d());
            assert!(b.iter().all(|&x| (0.0..=1.0).contains(&x)));
            for k in 0..3 {
                mean[k] += b[k] / n as f64;
            }
        }
        for m in mean {
            assert!((m - 1.0 / 3.0).abs() < 5e-3);
        }
    }
}

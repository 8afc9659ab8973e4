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
    let (r, theta) = if a.abs() > b.abs() { (a, PI / 4.0 * (b / a)) } else { (b, PI / 2.0 - PI / 4.0 * (a / b)) };
    [r * theta.cos(), r * theta.sin()]
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

//! χ² goodness-of-fit test of a direction sampler against the density it claims, after Mitsuba 3's
//! `chi2` module (itself after Jakob's Mitsuba 0.5 tests and pbrt-v3's `bsdfs` test):
//!
//! 1. draw `samples` directions and histogram them on a grid uniform in `(cos θ, φ)` (so every cell has
//!    the same solid angle);
//! 2. integrate the density over every cell (adaptive Gauss–Legendre cubature) for the expected counts;
//!    samples that are deltas or failures go to one extra cell whose expected count is what the density
//!    leaves over, `N·(1 − ∫pdf)`;
//! 3. pool the cells with expected counts below 5 (the textbook validity condition of Pearson's test);
//! 4. Pearson's statistic, and its p-value from the χ² distribution with `cells − 1` degrees of freedom.
//!
//! A sample in a cell where the density integrates to zero fails outright.

use crate::geometry::Vec3;
use crate::sampling::Rng;
use std::f64::consts::PI;

pub struct Chi2Test {
    pub cos_bins: usize,
    pub phi_bins: usize,
    pub samples: usize,
    pub seed: u64,
}

#[derive(Debug)]
pub struct Chi2Result {
    pub p_value: f64,
    pub statistic: f64,
    pub dof: usize,
    /// ∫ pdf over the sphere.
    pub pdf_integral: f64,
}

/// Minimum expected count of a cell (Cochran 1952).
const MIN_EXPECTED: f64 = 5.0;

impl Chi2Test {
    /// Runs the test. `sample` returns a direction and whether it came from a delta lobe (or `None` for a
    /// failed sample); `pdf` is the claimed solid-angle density of the non-delta samples.
    pub fn run(
        &self,
        mut sample: impl FnMut(&mut Rng) -> Option<(Vec3, bool)>,
        pdf: impl Fn(Vec3) -> f64,
    ) -> Result<Chi2Result, String> {
        let cells = self.cos_bins * self.phi_bins;
        let mut observed = vec![0.0; cells + 1];
        let mut rng = Rng::new(self.seed);
        for _ in 0..self.samples {
            match sample(&mut rng) {
                Some((w, false)) => observed[self.cell_of(w)] += 1.0,
                _ => observed[cells] += 1.0,
            }
        }
        let mut expected = vec![0.0; cells + 1];
        let mut pdf_integral = 0.0;
        let dcos = 2.0 / self.cos_bins as f64;
        let dphi = 2.0 * PI / self.phi_bins as f64;
        for ic in 0..self.cos_bins {
            for ip in 0..self.phi_bins {
                let c0 = -1.0 + ic as f64 * dcos;
                let p0 = ip as f64 * dphi;
                let f = |c: f64, phi: f64| {
                    let s = (1.0 - c * c).max(0.0).sqrt();
                    pdf(Vec3::new(s * phi.cos(), s * phi.sin(), c))
                };
                let integral = adaptive_cubature(&f, [c0, c0 + dcos], [p0, p0 + dphi], 0);
                pdf_integral += integral;
                expected[ic * self.phi_bins + ip] = integral * self.samples as f64;
            }
        }
        expected[cells] = ((1.0 - pdf_integral) * self.samples as f64).max(0.0);

        let mut table: Vec<(f64, f64)> = expected.iter().copied().zip(observed.iter().copied()).collect();
        if let Some(&(e, o)) = table.iter().find(|(e, o)| *e == 0.0 && *o > 0.0) {
            return Err(format!("{o} samples in a cell where the density integrates to {e}"));
        }
        table.retain(|(e, _)| *e > 0.0);
        table.sort_by(|a, b| a.0.total_cmp(&b.0));
        // Pool the smallest cells until the pool is big enough and everything left is too.
        let (mut pool_e, mut pool_o, mut first) = (0.0, 0.0, 0);
        while first < table.len() && (table[first].0 < MIN_EXPECTED || (pool_e > 0.0 && pool_e < MIN_EXPECTED)) {
            pool_e += table[first].0;
            pool_o += table[first].1;
            first += 1;
        }
        let mut statistic = 0.0;
        let mut used = 0;
        if pool_e > 0.0 {
            statistic += (pool_o - pool_e) * (pool_o - pool_e) / pool_e;
            used += 1;
        }
        for &(e, o) in &table[first..] {
            statistic += (o - e) * (o - e) / e;
            used += 1;
        }
        if used < 2 {
            return Err("fewer than two cells with enough expected samples".into());
        }
        let dof = used - 1;
        Ok(Chi2Result { p_value: chi2_survival(statistic, dof as f64), statistic, dof, pdf_integral })
    }

    fn cell_of(&self, w: Vec3) -> usize {
        let c = w.z.clamp(-1.0, 1.0);
        let ic = (((c + 1.0) * 0.5 * self.cos_bins as f64) as usize).min(self.cos_bins - 1);
        let mut phi = w.y.atan2(w.x);
        if phi < 0.0 {
            phi += 2.0 * PI;
        }
        let ip = ((phi / (2.0 * PI) * self.phi_bins as f64) as usize).min(self.phi_bins - 1);
        ic * self.phi_bins + ip
    }
}

/// 5-point Gauss–Legendre nodes and weights on [−1, 1].
const GL_X: [f64; 5] =
    [-0.906_179_845_938_664, -0.538_469_310_105_683, 0.0, 0.538_469_310_105_683, 0.906_179_845_938_664];
const GL_W: [f64; 5] =
    [0.236_926_885_056_189, 0.478_628_670_499_366, 0.568_888_888_888_889, 0.478_628_670_499_366, 0.236_926_885_056_189];

fn gauss_legendre(f: &impl Fn(f64, f64) -> f64, x: [f64; 2], y: [f64; 2]) -> f64 {
    let (hx, hy) = (0.5 * (x[1] - x[0]), 0.5 * (y[1] - y[0]));
    let (cx, cy) = (0.5 * (x[1] + x[0]), 0.5 * (y[1] + y[0]));
    let mut sum = 0.0;
    for (xi, wx) in GL_X.iter().zip(GL_W) {
        for (yi, wy) in GL_X.iter().zip(GL_W) {
            sum += wx * wy * f(cx + hx * xi, cy + hy * yi);
        }
    }
    sum * hx * hy
}

/// Integral over a rectangle, subdividing in four until the estimate stops changing (absolute 1e-9 or
/// relative 1e-6), at most 10 levels deep.
fn adaptive_cubature(f: &impl Fn(f64, f64) -> f64, x: [f64; 2], y: [f64; 2], depth: u32) -> f64 {
    let coarse = gauss_legendre(f, x, y);
    let (xm, ym) = (0.5 * (x[0] + x[1]), 0.5 * (y[0] + y[1]));
    let quads =
        [([x[0], xm], [y[0], ym]), ([xm, x[1]], [y[0], ym]), ([x[0], xm], [ym, y[1]]), ([xm, x[1]], [ym, y[1]])];
    let fine: f64 = quads.iter().map(|&(qx, qy)| gauss_legendre(f, qx, qy)).sum();
    if depth >= 10 || (fine - coarse).abs() <= 1e-9_f64.max(1e-6 * fine.abs()) {
        return fine;
    }
    quads.iter().map(|&(qx, qy)| adaptive_cubature(f, qx, qy, depth + 1)).sum()
}

/// `P(X ≥ x)` for `X ~ χ²(dof)`: the regularised upper incomplete gamma function `Q(dof/2, x/2)`.
pub fn chi2_survival(x: f64, dof: f64) -> f64 {
    gamma_q(0.5 * dof, 0.5 * x)
}

/// `ln Γ(a)` for `a > 0` (Lanczos approximation, g = 7, n = 9; relative error ~1e-15).
fn ln_gamma(a: f64) -> f64 {
    const G: f64 = 7.0;
    const C: [f64; 9] = [
        0.999_999_999_999_809_9,
        676.520_368_121_885_1,
        -1_259.139_216_722_402_8,
        771.323_428_777_653_1,
        -176.615_029_162_140_6,
        12.507_343_278_686_905,
        -0.138_571_095_265_720_12,
        9.984_369_578_019_572e-6,
        1.505_632_735_149_311_6e-7,
    ];
    if a < 0.5 {
        // Reflection formula.
        return (PI / (PI * a).sin()).ln() - ln_gamma(1.0 - a);
    }
    let a = a - 1.0;
    let t = a + G + 0.5;
    let series: f64 = C[0] + C[1..].iter().enumerate().map(|(i, c)| c / (a + i as f64 + 1.0)).sum::<f64>();
    0.5 * (2.0 * PI).ln() + (a + 0.5) * t.ln() - t + series.ln()
}

/// Regularised upper incomplete gamma `Q(a, x)` (Numerical Recipes §6.2: series for `x < a + 1`,
/// Lentz's continued fraction otherwise).
fn gamma_q(a: f64, x: f64) -> f64 {
    if x <= 0.0 {
        return 1.0;
    }
    let prefactor = (-x + a * x.ln() - ln_gamma(a)).exp();
    if x < a + 1.0 {
        let (mut ap, mut del) = (a, 1.0 / a);
        let mut sum = del;
        for _ in 0..100_000 {
            ap += 1.0;
            del *= x / ap;
            sum += del;
            if del.abs() < sum.abs() * 1e-15 {
                break;
            }
        }
        1.0 - sum * prefactor
    } else {
        const TINY: f64 = 1e-300;
        let mut b = x + 1.0 - a;
        let mut c = 1.0 / TINY;
        let mut d = 1.0 / b;
        let mut h = d;
        for i in 1..100_000 {
            let an = -(i as f64) * (i as f64 - a);
            b += 2.0;
            d = an * d + b;
            if d.abs() < TINY {
                d = TINY;
            }
            c = b + an / c;
            if c.abs() < TINY {
                c = TINY;
            }
            d = 1.0 / d;
            let del = d * c;
            h *= del;
            if (del - 1.0).abs() < 1e-15 {
                break;
            }
        }
        prefactor * h
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::sampling::{cosine_hemisphere, cosine_hemisphere_pdf, uniform_sphere};

    #[test]
    fn survival_function_known_values() {
        // Tables: P(χ²(1) ≥ 3.841) = 0.05, P(χ²(10) ≥ 23.209) = 0.01, P(χ²(2) ≥ x) = e^(−x/2).
        assert!((chi2_survival(3.841_458_820_694_124, 1.0) - 0.05).abs() < 1e-9);
        assert!((chi2_survival(23.209_251_158_954_36, 10.0) - 0.01).abs() < 1e-9);
        assert!((chi2_survival(7.0, 2.0) - (-3.5f64).exp()).abs() < 1e-12);
        // Large dof: mean dof, so the median is close to dof·(1 − 2/(9 dof))³.
        let k = 800.0f64;
        assert!((chi2_survival(k * (1.0 - 2.0 / (9.0 * k)).powi(3), k) - 0.5).abs() < 1e-3);
    }

    #[test]
    fn accepts_a_correct_sampler_and_rejects_a_wrong_one() {
        let test = Chi2Test { cos_bins: 10, phi_bins: 20, samples: 200_000, seed: 1 };
        let good = test.run(|r| Some((cosine_hemisphere(r.next_2d()), false)), |w| cosine_hemisphere_pdf(w.z)).unwrap();
        assert!(good.p_value > 1e-4 && (good.pdf_integral - 1.0).abs() < 1e-6, "{good:?}");
        // Uniform sphere samples against a cosine density.
        let bad = test.run(|r| Some((uniform_sphere(r.next_2d()), false)), |w| cosine_hemisphere_pdf(w.z));
        assert!(bad.is_err(), "samples below the horizon where the density is zero");
        let skewed = test
            .run(
                |r| {
                    let w = uniform_sphere(r.next_2d());
                    Some((Vec3::new(w.x, w.y, w.z.abs()), false))
                },
                |w| cosine_hemisphere_pdf(w.z),
            )
            .unwrap();
        assert!(skewed.p_value < 1e-10, "{skewed:?}");
    }
}

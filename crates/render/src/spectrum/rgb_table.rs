//! The RGB → sigmoid-polynomial table over the RGB cube (Jakob & Hanika 2019, §4.2), optimised once
//! at run time into the object that owns it.
//!
//! Layout (pbrt-v4's `RGBToSpectrumTable`): for each channel l that is the largest, a res³ grid over
//! z = that channel (nodes at smoothstep(smoothstep(k / (res − 1))), dense near 0 and 1) and
//! x, y = the next two channels (cyclically) divided by z, uniform in [0, 1]. Each cell's fit starts
//! from its neighbour's along z, walking outwards from k = res / 5.

use super::fit::Fitter;
use super::SigmoidPolynomial;
use glam::DVec3;
use rayon::prelude::*;

/// Sigmoid-polynomial coefficients of every RGB colour with components in [0, 1], trilinearly
/// interpolated between optimised grid cells.
#[derive(Clone, Debug)]
pub struct RgbToSpectrumTable {
    resolution: usize,
    z_nodes: Vec<f32>,
    /// Coefficients (λ in nm) at cell ((l · res + k) · res + j) · res + i.
    coefficients: Vec<[f32; 3]>,
}

impl RgbToSpectrumTable {
    /// The resolution nullpath uses: 3 × 32³ fits, round trips within 1e-3 in linear RGB.
    pub const DEFAULT_RESOLUTION: usize = 32;

    /// Optimises the table at `resolution` cells per axis (at least 3), in parallel; deterministic
    /// (each (l, j, i) column walks its z cells in a fixed order on one thread).
    pub fn optimise(resolution: usize) -> Self {
        let res = resolution.max(3);
        let z_nodes: Vec<f64> = (0..res).map(|k| smoothstep(smoothstep(k as f64 / (res - 1) as f64))).collect();
        let fitter = Fitter::new();
        let columns: Vec<Vec<[f32; 3]>> =
            (0..3 * res * res).into_par_iter().map(|column| fit_column(&fitter, &z_nodes, res, column)).collect();
        let mut coefficients = vec![[0.0; 3]; 3 * res * res * res];
        for (column, fits) in columns.iter().enumerate() {
            let (l, ji) = (column / (res * res), column % (res * res));
            for (k, c) in fits.iter().enumerate() {
                coefficients[(l * res + k) * res * res + ji] = *c;
            }
        }
        Self { resolution: res, z_nodes: z_nodes.iter().map(|&z| z as f32).collect(), coefficients }
    }

    /// Cells per axis.
    pub fn resolution(&self) -> usize {
        self.resolution
    }

    /// The sigmoid polynomial of `rgb`, each component clamped to [0, 1] (NaN reads as 0).
    pub fn lookup(&self, rgb: [f32; 3]) -> SigmoidPolynomial {
        let rgb = rgb.map(|v| if v >= 0.0 { v.min(1.0) } else { 0.0 });
        if rgb[0] == rgb[1] && rgb[1] == rgb[2] {
            return SigmoidPolynomial::constant(rgb[0]);
        }
        let res = self.resolution;
        let l = if rgb[0] > rgb[1] {
            if rgb[0] > rgb[2] {
                0
            } else {
                2
            }
        } else if rgb[1] > rgb[2] {
            1
        } else {
            2
        };
        let z = rgb[l];
        let scale = (res - 1) as f32 / z;
        let (x, y) = (rgb[(l + 1) % 3] * scale, rgb[(l + 2) % 3] * scale);
        let (xi, yi) = ((x as usize).min(res - 2), (y as usize).min(res - 2));
        let zi = (self.z_nodes.partition_point(|&n| n < z).max(1) - 1).min(res - 2);
        let (dx, dy) = (x - xi as f32, y - yi as f32);
        let dz = (z - self.z_nodes[zi]) / (self.z_nodes[zi + 1] - self.z_nodes[zi]);
        let at = |k: usize, j: usize, i: usize| self.coefficients[((l * res + k) * res + j) * res + i];
        let lerp = |a: [f32; 3], b: [f32; 3], t: f32| std::array::from_fn(|n| a[n] + t * (b[n] - a[n]));
        let plane = |k: usize| {
            let row = |j: usize| lerp(at(k, j, xi), at(k, j, xi + 1), dx);
            lerp(row(yi), row(yi + 1), dy)
        };
        SigmoidPolynomial::new(lerp(plane(zi), plane(zi + 1), dz))
    }
}

/// x²(3 − 2x).
fn smoothstep(x: f64) -> f64 {
    x * x * (3.0 - 2.0 * x)
}

/// The fits of one (l, j, i) column at every z node, walking up and then down from k = res / 5.
fn fit_column(fitter: &Fitter, z_nodes: &[f64], res: usize, column: usize) -> Vec<[f32; 3]> {
    let l = column / (res * res);
    let (j, i) = ((column / res) % res, column % res);
    let (x, y) = (i as f64 / (res - 1) as f64, j as f64 / (res - 1) as f64);
    let rgb_at = |z: f64| {
        let mut rgb = DVec3::ZERO;
        rgb[l] = z;
        rgb[(l + 1) % 3] = x * z;
        rgb[(l + 2) % 3] = y * z;
        rgb
    };
    let mut fits = vec![[0.0; 3]; res];
    let start = res / 5;
    for walk in [(start..res).collect::<Vec<_>>(), (0..=start).rev().collect()] {
        let mut c = DVec3::ZERO;
        for k in walk {
            let (next, nm) = fitter.fit(rgb_at(z_nodes[k]), c);
            c = next;
            fits[k] = nm;
        }
    }
    fits
}

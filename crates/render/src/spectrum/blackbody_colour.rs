//! The linear Rec. 709 colour of Planck's law by temperature, tabulated: emitters whose light is
//! a blackbody (lamps given a temperature, accretion disks) are seen at `gT` after a frequency
//! shift `g` ([`super::shift`]), a different temperature at every vertex, and one quadrature of
//! the colour-matching functions per evaluation (471 wavelengths) would cost more than the ray.
//!
//! The table holds the colour per unit luminance and `ln Y` at temperatures even in `ln T`, both
//! smooth in `ln T`, and interpolates linearly: the relative error is below 2·10⁻⁵ above 800 K
//! (`ln Y` curves most where the blackbody is coolest, as `1/T`). Beyond its hottest
//! entry the blackbody is in its Rayleigh–Jeans limit over the visible (`B_λ ∝ T`, fixed
//! colour); below its coolest it emits nothing visible.

use super::{cie, Blackbody};
use crate::spectrum::xyz_to_linear_srgb;
use std::sync::OnceLock;

/// Coolest tabulated temperature, K: its luminance is ~10⁻¹¹³ of 6500 K's.
const T_MIN: f64 = 100.0;
/// Hottest tabulated temperature, K: far into the Rayleigh–Jeans regime over the visible
/// (`hc/(λkT) ≪ 1` at 360 nm), where `B_λ ∝ T` and the colour no longer changes.
const T_MAX: f64 = 1e8;
/// Entries, even in `ln T`.
const ENTRIES: usize = 8192;

/// Colour over luminance, and `ln Y`, of one temperature.
type Entry = ([f64; 3], f64);

/// Linear Rec. 709 of `B_λ(T)` (W sr⁻¹ m⁻² nm⁻¹, weighted as [`cie::xyz_quadrature`]).
///
/// Each entry is computed the first time it is read: a quadrature per entry makes the whole
/// table costlier than a small render's rays, and a scene reads few of them (a disk's
/// temperatures span a few hundred entries).
#[derive(Debug)]
pub struct BlackbodyColours {
    /// Colour over luminance, and `ln Y`, at `T_MIN e^{k·step}`.
    entries: Vec<OnceLock<Entry>>,
    step: f64,
}

impl BlackbodyColours {
    /// The table, one per process: it depends on nothing but constants of nature and the CIE
    /// observer.
    pub fn get() -> &'static BlackbodyColours {
        static TABLE: OnceLock<BlackbodyColours> = OnceLock::new();
        TABLE.get_or_init(|| BlackbodyColours {
            entries: (0..ENTRIES).map(|_| OnceLock::new()).collect(),
            step: (T_MAX / T_MIN).ln() / (ENTRIES - 1) as f64,
        })
    }

    /// Entry `k`, computed on first use.
    fn entry(&self, k: usize) -> Entry {
        *self.entries[k].get_or_init(|| {
            let t = T_MIN * (k as f64 * self.step).exp();
            let xyz = cie::xyz_quadrature(&Blackbody::new(t).expect("tabulated temperatures are positive"));
            ((xyz_to_linear_srgb(xyz) / xyz.y).to_array(), xyz.y.ln())
        })
    }

    /// Linear Rec. 709 of the blackbody at `temperature` kelvin, and its luminance `Y`.
    pub fn at(&self, temperature: f64) -> ([f64; 3], f64) {
        if !(temperature >= T_MIN) {
            return ([0.0; 3], 0.0);
        }
        if temperature >= T_MAX {
            let (colour, ln_y) = self.entry(ENTRIES - 1);
            return (colour.map(|c| c * ln_y.exp() * temperature / T_MAX), ln_y.exp() * temperature / T_MAX);
        }
        let x = (temperature / T_MIN).ln() / self.step;
        let k = (x as usize).min(ENTRIES - 2);
        let f = x - k as f64;
        let ((c0, y0), (c1, y1)) = (self.entry(k), self.entry(k + 1));
        let y = (y0 + f * (y1 - y0)).exp();
        (std::array::from_fn(|i| (c0[i] + f * (c1[i] - c0[i])) * y), y)
    }

    /// The luminance `Y` of the blackbody at `temperature` kelvin.
    pub fn luminance(&self, temperature: f64) -> f64 {
        self.at(temperature).1
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_table_matches_quadrature_between_its_entries() {
        let table = BlackbodyColours::get();
        for t in [800.0, 1850.5, 3000.0, 6504.0, 12_345.0, 4.2e5, 3e7] {
            let xyz = cie::xyz_quadrature(&Blackbody::new(t).unwrap());
            let exact = xyz_to_linear_srgb(xyz);
            let (rgb, y) = table.at(t);
            assert!((y / xyz.y - 1.0).abs() < 2e-5, "{t} K: Y {y} vs {}", xyz.y);
            for i in 0..3 {
                assert!(
                    (rgb[i] - exact[i]).abs() < 2e-5 * (exact[i].abs() + xyz.y),
                    "{t} K channel {i}: {} vs {}",
                    rgb[i],
                    exact[i]
                );
            }
        }
    }

    #[test]
    fn beyond_the_table_the_colour_is_fixed_and_the_brightness_linear() {
        let table = BlackbodyColours::get();
        let (a, ya) = table.at(2e8);
        let (b, yb) = table.at(4e8);
        assert!((yb / ya - 2.0).abs() < 1e-12);
        assert!((b[2] / a[2] - 2.0).abs() < 1e-12);
        let exact = cie::xyz_quadrature(&Blackbody::new(2e8).unwrap()).y;
        assert!((ya / exact - 1.0).abs() < 1e-3);
        assert_eq!(table.at(50.0), ([0.0; 3], 0.0));
        assert_eq!(table.at(f64::NAN).1, 0.0);
    }
}

//! One pixel's running sums and the estimator that turns them into a value.
//!
//! A pixel's samples `(L_i, w_i)` (radiance and filter weight, drawn by filter importance sampling
//! around that pixel's centre) give the weighted-mean estimate of the filtered image
//! (pbrt-v4 §5.4.3, with the filter folded into the sampling density):
//!
//! ```text
//!     I = Σ w_i L_i / Σ w_i
//! ```
//!
//! For filters that are never negative every `w_i = 1` and this is the plain sample mean. With
//! negative lobes `Σ w_i` can cancel to exactly zero at low sample counts; there the ratio is
//! undefined and the pixel falls back to `Σ w_i L_i / n`, which is unbiased because the weights
//! have expectation 1 (see `filter::sampler`).
//!
//! Sums are `f64` and samples are added in the caller's order, so a pixel's value depends only on
//! which samples it received and in what order — never on threads.

use crate::rgb::{luminance_f64, Rgb};

/// Running sums of one pixel.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub(crate) struct PixelSum {
    /// `Σ w_i L_i` per channel.
    weighted_radiance: [f64; 3],
    /// `Σ w_i`.
    weight: f64,
    /// `Σ w_i Y(L_i)` and `Σ w_i` over the samples of odd index: with the even ones (the rest of
    /// the sums) they make two independent half estimates, whose difference measures the
    /// pixel's error (see `film::noise`).
    odd_luminance: f64,
    odd_weight: f64,
    /// Number of samples accumulated.
    count: u32,
    /// Number of samples drawn, accumulated or rejected: the index of the pixel's next sample.
    taken: u32,
}

/// Everything a [`PixelSum`] holds, in the order checkpoints store it.
pub(crate) type PixelState = ([f64; 6], [u32; 2]);

impl PixelSum {
    /// Adds one sample. The caller has already rejected non-finite input ([`is_valid_sample`]).
    pub(crate) fn add(&mut self, radiance: Rgb, weight: f64) {
        for (sum, l) in self.weighted_radiance.iter_mut().zip(radiance.to_array()) {
            *sum += weight * f64::from(l);
        }
        self.weight += weight;
        if self.taken % 2 == 1 {
            self.odd_luminance += weight * luminance_f64(radiance.to_array().map(f64::from));
            self.odd_weight += weight;
        }
        self.count += 1;
        self.taken += 1;
    }

    /// Counts a drawn sample that was rejected (not finite).
    pub(crate) fn reject(&mut self) {
        self.taken += 1;
    }

    /// Adds another pixel's sums to these (used when merging a tile into the film).
    pub(crate) fn merge(&mut self, other: &PixelSum) {
        for (sum, o) in self.weighted_radiance.iter_mut().zip(other.weighted_radiance) {
            *sum += o;
        }
        self.weight += other.weight;
        self.odd_luminance += other.odd_luminance;
        self.odd_weight += other.odd_weight;
        self.count += other.count;
        self.taken += other.taken;
    }

    pub(crate) fn count(&self) -> u64 {
        u64::from(self.count)
    }

    pub(crate) fn taken(&self) -> u32 {
        self.taken
    }

    /// The pixel estimate in `f64`; black when the pixel has no samples.
    pub(crate) fn value(&self) -> [f64; 3] {
        let denominator = if self.weight != 0.0 {
            self.weight
        } else if self.count > 0 {
            f64::from(self.count)
        } else {
            return [0.0; 3];
        };
        self.weighted_radiance.map(|s| s / denominator)
    }

    /// The luminance estimates of the even and of the odd samples; `None` while either half's
    /// weights sum to zero or less (too few samples, or cancelling negative filter lobes).
    pub(crate) fn half_luminances(&self) -> Option<(f64, f64)> {
        let total = luminance_f64(self.weighted_radiance);
        let even_weight = self.weight - self.odd_weight;
        (even_weight > 0.0 && self.odd_weight > 0.0)
            .then(|| ((total - self.odd_luminance) / even_weight, self.odd_luminance / self.odd_weight))
    }

    /// The exact state, for checkpoints.
    pub(crate) fn state(&self) -> PixelState {
        let [r, g, b] = self.weighted_radiance;
        ([r, g, b, self.weight, self.odd_luminance, self.odd_weight], [self.count, self.taken])
    }

    /// The pixel whose [`PixelSum::state`] this is.
    pub(crate) fn from_state((sums, [count, taken]): PixelState) -> Self {
        let [r, g, b, weight, odd_luminance, odd_weight] = sums;
        Self { weighted_radiance: [r, g, b], weight, odd_luminance, odd_weight, count, taken }
    }
}

/// A sample is accumulated only if its radiance and weight are all finite.
pub(crate) fn is_valid_sample(radiance: Rgb, weight: f64) -> bool {
    radiance.is_finite() && weight.is_finite()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn empty_pixel_is_black() {
        assert_eq!(PixelSum::default().value(), [0.0; 3]);
    }

    #[test]
    fn weighted_mean() {
        let mut p = PixelSum::default();
        p.add(Rgb::new(1.0, 2.0, 4.0), 3.0);
        p.add(Rgb::new(5.0, 6.0, 0.0), 1.0);
        // (3·1 + 5)/4, (3·2 + 6)/4, (3·4 + 0)/4: exact in binary.
        assert_eq!(p.value(), [2.0, 3.0, 3.0]);
        assert_eq!(p.count(), 2);
    }

    #[test]
    fn cancelling_weights_fall_back_to_the_plain_mean_of_weighted_radiance() {
        let mut p = PixelSum::default();
        p.add(Rgb::splat(3.0), 1.25);
        p.add(Rgb::splat(1.0), -1.25);
        // Σw = 0, so value = Σ w L / n = (3.75 - 1.25) / 2.
        assert_eq!(p.value(), [1.25; 3]);
    }

    #[test]
    fn merge_adds_sums() {
        let mut a = PixelSum::default();
        a.add(Rgb::ONE, 1.0);
        let mut b = PixelSum::default();
        b.add(Rgb::splat(3.0), 1.0);
        a.merge(&b);
        assert_eq!(a.value(), [2.0; 3]);
        assert_eq!(a.count(), 2);
        assert_eq!(a.taken(), 2);
    }

    #[test]
    fn halves_split_samples_by_index_and_rejections_keep_the_order() {
        let mut p = PixelSum::default();
        p.add(Rgb::splat(1.0), 1.0); // sample 0: even
        p.reject(); // sample 1 was not finite
        p.add(Rgb::splat(3.0), 1.0); // sample 2: even
        p.add(Rgb::splat(5.0), 2.0); // sample 3: odd
        assert_eq!((p.count(), p.taken()), (3, 4));
        let (even, odd) = p.half_luminances().unwrap();
        assert!((even - 2.0).abs() < 1e-6 && (odd - 5.0).abs() < 1e-6, "{even} {odd}");
        assert_eq!(PixelSum::default().half_luminances(), None);
        assert_eq!(PixelSum::from_state(p.state()), p);
    }

    #[test]
    fn validity() {
        assert!(is_valid_sample(Rgb::ONE, -1.0));
        assert!(!is_valid_sample(Rgb::new(f32::NAN, 0.0, 0.0), 1.0));
        assert!(!is_valid_sample(Rgb::new(0.0, f32::INFINITY, 0.0), 1.0));
        assert!(!is_valid_sample(Rgb::ONE, f64::NAN));
    }
}

//! The numbers behind a camera path: a padded, shuffled, Owen-scrambled Sobol sequence (Burley
//! 2020, "Practical Hash-based Owen Scrambling", §4 — the sampler of Blender Cycles), through
//! the `sobol_burley` crate.
//!
//! Sample `i` of a pixel is point `i` of the sequence. A path's draws (the position in the pixel,
//! the lens, each bounce's BSDF sample, each light sample…) are served in order from groups of
//! four dimensions, each group its own scrambled copy of the sequence's first four dimensions,
//! seeded by the pixel and the group's number; a 2-D draw takes dimensions 0–1 or 2–3 of a
//! group. Each draw's points over a pixel's samples are stratified at every power of two (the
//! first two dimensions form a (0, 2)-sequence): pixel footprints, soft shadows and glossy lobes
//! converge faster than with independent random numbers. The groups are scrambled and shuffled
//! independently ("padding"), so they are uncorrelated, and each sample on its own is a vector
//! of independent uniform numbers: estimates stay unbiased whatever a path does with them. A
//! group is `sobol_burley::sample_4d`'s numbers, bit for bit, computed with byte tables of the
//! Sobol matrices (see [`SobolBytes`]).
//!
//! Everything is keyed by `(seed, pixel, sample)`, never by thread, so images are reproducible.

use super::rng::mix64;
use sobol_burley::parts::{hash, hash_int4, owen_scramble_int4_rev, owen_scramble_rev, sobol_rev, Int4};
use std::sync::OnceLock;

/// Samples per pixel that one sequence provides (`sobol_burley`'s limit); later samples continue
/// in independently scrambled sequences.
const SEQUENCE_LENGTH: u64 = 1 << 16;

/// The draws of one camera sample.
#[derive(Clone, Debug)]
pub struct Sampler {
    /// Index of the sample within its sequence.
    index: u32,
    /// Scrambling key of the pixel (and of the sequence, past [`SEQUENCE_LENGTH`] samples).
    key: u64,
    /// Groups of four dimensions taken so far.
    group: u64,
    /// The current group's numbers, and how many of them are used.
    numbers: [f32; 4],
    used: usize,
}

impl Sampler {
    /// Sample `sample` of pixel `pixel` of a render with the given seed.
    pub fn for_sample(seed: u64, pixel: u64, sample: u64) -> Self {
        let sequence = sample / SEQUENCE_LENGTH;
        let key = mix64(seed ^ mix64(pixel.wrapping_add(0x9e3779b97f4a7c15) ^ mix64(sequence.wrapping_add(1))));
        Self { index: (sample % SEQUENCE_LENGTH) as u32, key, group: 0, numbers: [0.0; 4], used: 4 }
    }

    /// Starts the next group of four dimensions.
    fn refill(&mut self) {
        self.group += 1;
        let seed = mix64(self.key ^ self.group.wrapping_mul(0xd1b54a32d192ed03)) as u32;
        self.numbers = SobolBytes::get().sample_4d(self.index, seed);
        self.used = 0;
    }

    /// Uniform in `[0, 1)`.
    pub fn next_f64(&mut self) -> f64 {
        if self.used == 4 {
            self.refill();
        }
        self.used += 1;
        f64::from(self.numbers[self.used - 1])
    }

    /// Uniform in `[0, 1)²`, stratified with the same draw of the pixel's other samples.
    pub fn next_2d(&mut self) -> [f64; 2] {
        // Pairs start at an even dimension, where the sequence is stratified in two dimensions.
        if self.used > 2 {
            self.refill();
        }
        let first = self.used.next_multiple_of(2);
        self.used = first + 2;
        [f64::from(self.numbers[first]), f64::from(self.numbers[first + 1])]
    }
}

/// Dimensions 0–3 of the Sobol sequence by bytes of the (bit-reversed) index. A Sobol point is
/// linear over GF(2) in its index: the XOR of the direction vectors of the index's set bits.
/// `sobol_burley` loops over those bits (up to 16 of them, as the shuffled index of any sample has
/// random high bits); the XOR over each byte's bits is tabulated here, so a point is two loads.
#[derive(Debug)]
struct SobolBytes {
    /// Point of bits 24–31 of the reversed index (the index's bits 0–7), one entry per byte value.
    high: [[u32; 4]; 256],
    /// Point of bits 16–23 of the reversed index (the index's bits 8–15).
    low: [[u32; 4]; 256],
}

impl SobolBytes {
    /// The tables, built on first use from `sobol_burley`'s own direction vectors.
    fn get() -> &'static Self {
        static TABLES: OnceLock<SobolBytes> = OnceLock::new();
        TABLES.get_or_init(|| {
            let byte = |shift: u32| {
                std::array::from_fn(|value| std::array::from_fn(|d| sobol_rev((value as u32) << shift, d as u32)))
            };
            Self { high: byte(24), low: byte(16) }
        })
    }

    /// `sobol_burley::sample_4d(index, 0, seed)`, bit for bit (the same shuffle of the index and
    /// Owen scrambling of the point; `index` < 2¹⁶).
    fn sample_4d(&self, index: u32, seed: u32) -> [f32; 4] {
        let shuffled_rev = owen_scramble_rev(index.reverse_bits(), hash(seed ^ 0x79c68e4a));
        let sobol_rev = Int4::from(self.high[(shuffled_rev >> 24) as usize])
            ^ Int4::from(self.low[(shuffled_rev >> 16 & 0xff) as usize]);
        let scramble = Int4::from([seed.wrapping_mul(0x9c8f2d3b); 4])
            ^ Int4::from([0x912f69ba, 0x174f18ab, 0x691e72ca, 0xb40cc1b8]);
        owen_scramble_int4_rev(sobol_rev, hash_int4(scramble)).reverse_bits().to_f32_norm()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn byte_tables_give_sobol_burleys_numbers() {
        let tables = SobolBytes::get();
        for index in 0..SEQUENCE_LENGTH as u32 {
            for seed in [0, 1, 0x5bd1e995, u32::MAX, index.wrapping_mul(0x9e3779b9)] {
                assert_eq!(tables.sample_4d(index, seed), sobol_burley::sample_4d(index, 0, seed), "{index} {seed}");
            }
        }
    }

    /// The draws of samples `0..n` of one pixel, `draws` 2-D draws each.
    fn points(pixel: u64, n: u64, draws: usize) -> Vec<Vec<[f64; 2]>> {
        (0..n)
            .map(|s| {
                let mut sampler = Sampler::for_sample(7, pixel, s);
                (0..draws).map(|_| sampler.next_2d()).collect()
            })
            .collect()
    }

    #[test]
    fn every_draw_is_stratified_over_a_pixels_samples() {
        // 64 samples: each draw's points fall one in each cell of an 8 × 8 grid (a (0, 2)-net),
        // and one in each of 64 columns and each of 64 rows.
        let samples = points(3, 64, 5);
        for draw in 0..5 {
            let mut cells = [false; 64];
            let (mut columns, mut rows) = ([false; 64], [false; 64]);
            for sample in &samples {
                let [x, y] = sample[draw];
                assert!((0.0..1.0).contains(&x) && (0.0..1.0).contains(&y));
                cells[(x * 8.0) as usize * 8 + (y * 8.0) as usize] = true;
                columns[(x * 64.0) as usize] = true;
                rows[(y * 64.0) as usize] = true;
            }
            assert!(cells.iter().chain(&columns).chain(&rows).all(|&c| c), "draw {draw}");
        }
    }

    #[test]
    fn draws_samples_and_pixels_are_uncorrelated() {
        // Correlation between draw 0's x and draw 1's x over a pixel's samples, and between two
        // pixels' draw 0: zero up to sampling error (1/√n ≈ 0.016 for n = 4096; 4σ).
        let n = 4096;
        let a = points(1, n, 2);
        let b = points(2, n, 1);
        let correlation = |f: &dyn Fn(usize) -> (f64, f64)| {
            let pairs: Vec<(f64, f64)> = (0..n as usize).map(f).collect();
            let m = n as f64;
            let (mx, my) = pairs.iter().fold((0.0, 0.0), |s, p| (s.0 + p.0 / m, s.1 + p.1 / m));
            let cov = pairs.iter().map(|p| (p.0 - mx) * (p.1 - my)).sum::<f64>() / m;
            cov * 12.0
        };
        assert!(correlation(&|i| (a[i][0][0], a[i][1][0])).abs() < 0.065);
        assert!(correlation(&|i| (a[i][0][1], a[i][1][1])).abs() < 0.065);
        assert!(correlation(&|i| (a[i][0][0], b[i][0][0])).abs() < 0.065);
        assert_ne!(a[0][0], b[0][0]);
    }

    #[test]
    fn samples_are_reproducible_and_continue_past_one_sequence() {
        let draw = |s: u64| Sampler::for_sample(5, 9, s).next_2d();
        assert_eq!(draw(12), draw(12));
        assert_ne!(draw(12), draw(13));
        // Sample 2¹⁶ + 12 comes from another scramble, not a repeat of sample 12.
        assert_ne!(draw(SEQUENCE_LENGTH + 12), draw(12));
        let x = draw(3 * SEQUENCE_LENGTH + 1);
        assert!(x.iter().all(|v| (0.0..1.0).contains(v)));
    }
}

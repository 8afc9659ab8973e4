//! PCG32 (O'Neill 2014, "PCG: a family of simple fast space-efficient statistically good algorithms"),
//! seeded by hashing the stream key so neighbouring pixels get unrelated streams.

/// A small, fast, deterministic random stream.
#[derive(Clone, Debug)]
pub struct Rng {
    state: u64,
    inc: u64,
}

const MULTIPLIER: u64 = 6364136223846793005;

/// SplitMix64 finaliser: a bijective mix of a 64-bit key.
pub(super) fn mix64(mut z: u64) -> u64 {
    z = (z ^ (z >> 30)).wrapping_mul(0xbf58476d1ce4e5b9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94d049bb133111eb);
    z ^ (z >> 31)
}

impl Rng {
    /// The stream for one sample of one pixel of a render with the given seed.
    pub fn for_sample(seed: u64, pixel: u64, sample: u64) -> Self {
        let key = mix64(seed ^ mix64(pixel.wrapping_add(0x9e3779b97f4a7c15) ^ mix64(sample)));
        Self::from_parts(key, mix64(key ^ 0xda3e39cb94b95bdb))
    }

    /// A stream from any 64-bit seed.
    pub fn new(seed: u64) -> Self {
        Self::from_parts(mix64(seed), mix64(seed.wrapping_add(1)))
    }

    fn from_parts(state: u64, stream: u64) -> Self {
        let mut rng = Self { state: 0, inc: (stream << 1) | 1 };
        rng.next_u32();
        rng.state = rng.state.wrapping_add(state);
        rng.next_u32();
        rng
    }

    pub fn next_u32(&mut self) -> u32 {
        let old = self.state;
        self.state = old.wrapping_mul(MULTIPLIER).wrapping_add(self.inc);
        let xorshifted = (((old >> 18) ^ old) >> 27) as u32;
        let rot = (old >> 59) as u32;
        xorshifted.rotate_right(rot)
    }

    /// Uniform in `[0, 1)` with 32 random bits (never returns 1).
    pub fn next_f64(&mut self) -> f64 {
        f64::from(self.next_u32()) * (1.0 / 4294967296.0)
    }

    pub fn next_2d(&mut self) -> [f64; 2] {
        [self.next_f64(), self.next_f64()]
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn streams_are_reproducible_and_distinct() {
        let a: Vec<u32> = (0..8)
            .map({
                let mut r = Rng::for_sample(1, 2, 3);
                move |_| r.next_u32()
            })
            .collect();
        let b: Vec<u32> = (0..8)
            .map({
                let mut r = Rng::for_sample(1, 2, 3);
                move |_| r.next_u32()
            })
            .collect();
        let c: Vec<u32> = (0..8)
            .map({
                let mut r = Rng::for_sample(1, 3, 3);
                move |_| r.next_u32()
            })
            .collect();
        assert_eq!(a, b);
        assert_ne!(a, c);
    }

    #[test]
    fn uniform_mean_and_range() {
        let mut r = Rng::new(7);
        let n = 100_000;
        let mut sum = 0.0;
        for _ in 0..n {
            let x = r.next_f64();
            assert!((0.0..1.0).contains(&x));
            sum += x;
        }
        // Standard error of the mean is 1/sqrt(12 n) ≈ 9e-4; 5σ.
        assert!((sum / n as f64 - 0.5).abs() < 5e-3);
    }
}

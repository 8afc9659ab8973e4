//! atanh of a path's wavelength samples at once, without libm: visible-wavelength sampling maps
//! each of its N samples through atanh, and libm's scalar `log1pf` behind `f32::atanh` was the
//! costliest step of drawing them. Written on whole arrays, with selects rather than branches, so
//! that the compiler keeps the lanes in one SIMD register.

/// ln 2 split in two (Cephes): `LN2_HI` has few significant bits, so `k · LN2_HI` is exact for the
/// exponents `k` of an f32, and `LN2_LO` carries the rest.
const LN2_HI: f32 = 0.693_359_4;
const LN2_LO: f32 = -2.121_944_4e-4;
/// Bits of √½ as an f32: mantissas are reduced to [√½, √2), where ln's polynomial is accurate.
const SQRT_HALF_BITS: u32 = 0x3f35_04f3;
/// Cephes `logf`'s minimax coefficients, highest degree first: ln(1 + f) = f − f²/2 + f³ P(f) for
/// f in [√½ − 1, √2 − 1], to about one ulp (Moshier, Cephes Math Library, `logf.c`).
const LOG_P: [f32; 9] = [
    7.037_683_6e-2,
    -1.151_461e-1,
    1.167_699_9e-1,
    -1.242_014_1e-1,
    1.424_932_3e-1,
    -1.666_805_8e-1,
    2.000_071_4e-1,
    -2.499_999_4e-1,
    3.333_333e-1,
];

/// atanh(t) = ½ ln((1 + t) / (1 − t)) of each of `t`, each in (−1, 1); the quotient is formed in
/// f64, so that its rounding to f32 costs no more than half an ulp of the result's argument.
pub(super) fn atanh<const N: usize>(t: [f64; N]) -> [f32; N] {
    ln(t.map(|t| ((1.0 + t) / (1.0 - t)) as f32)).map(|l| 0.5 * l)
}

/// Natural logarithm of each of `x`, positive, normal and finite: x = 2ᵏ m with m in [√½, √2),
/// ln x = k ln 2 + ln m.
fn ln<const N: usize>(x: [f32; N]) -> [f32; N] {
    x.map(|x| {
        // Subtracting √½'s bits before splitting puts the exponent boundary at √½ rather than 1.
        let shifted = x.to_bits().wrapping_sub(SQRT_HALF_BITS);
        let k = (shifted as i32 >> 23) as f32;
        let m = f32::from_bits((shifted & 0x007f_ffff) + SQRT_HALF_BITS);
        let f = m - 1.0;
        let f2 = f * f;
        let p = LOG_P.iter().fold(0.0, |p, &c| p * f + c);
        let ln_m = f - 0.5 * f2 + f * f2 * p;
        k * LN2_HI + (ln_m + k * LN2_LO)
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ln_is_within_two_ulps_of_f64s() {
        // Every 97th f32 from 2⁻¹²⁶ to 2¹²⁸: all exponents, and mantissas across [√½, √2).
        let mut worst: f64 = 0.0;
        for bits in (0x0080_0000u32..0x7f80_0000).step_by(97) {
            let x = f32::from_bits(bits);
            let exact = f64::from(x).ln();
            let got = f64::from(ln([x])[0]);
            let ulp = f64::from((exact as f32).abs().max(f32::MIN_POSITIVE)) * f64::from(f32::EPSILON);
            worst = worst.max((got - exact).abs() / ulp);
        }
        assert!(worst <= 2.0, "worst error {worst} ulps");
    }

    #[test]
    fn atanh_agrees_with_f64s_over_the_open_interval() {
        for k in 1..2000 {
            let t = -1.0 + k as f64 / 1000.0;
            let exact = t.atanh();
            let got = f64::from(atanh([t])[0]);
            assert!((got - exact).abs() <= 2e-7 * exact.abs().max(1.0), "atanh({t}) = {got}, not {exact}");
        }
    }
}

//! From scene-referred linear radiance to display-referred 8-bit sRGB: exposure, a tone curve, then
//! the sRGB opto-electronic transfer function and rounding.
//!
//! Each channel is mapped independently: `byte = round(255 · oetf(curve(2^EV · L)))`.

use super::Film;

/// How linear radiance is brought to the display range `[0, 1]`.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Curve {
    /// Identity, clamped to `[0, 1]`: anything at or above 1 after exposure is white.
    #[default]
    Linear,
    /// Krzysztof Narkowicz's fit of the ACES RRT + Rec. 709 ODT ("ACES Filmic Tone Mapping Curve",
    /// blog post, 2016-01-06; public domain / MIT): `x(2.51x + 0.03) / (x(2.43x + 0.59) + 0.14)`,
    /// clamped to `[0, 1]`. The fit's input is pre-exposed so that 1 maps to about 0.8; it rolls
    /// highlights off smoothly, reaching white near 7.2. Applied per channel, so very bright
    /// saturated colours drift towards white. Monotone increasing for `x ≥ 0`, `f(0) = 0`.
    Filmic,
}

impl Curve {
    /// Every curve.
    pub const ALL: [Curve; 2] = [Curve::Linear, Curve::Filmic];

    /// Its name in scene files.
    pub fn name(self) -> &'static str {
        match self {
            Curve::Linear => "linear",
            Curve::Filmic => "filmic",
        }
    }

    /// Maps exposed linear radiance to `[0, 1]`. Negative input (possible with negative-lobed
    /// filters) maps to 0; NaN maps to 0.
    pub fn apply(self, x: f64) -> f64 {
        let x = if x.is_nan() { 0.0 } else { x.max(0.0) };
        match self {
            Curve::Linear => x.min(1.0),
            Curve::Filmic => {
                if x.is_infinite() {
                    return 1.0;
                }
                let y = (x * (2.51 * x + 0.03)) / (x * (2.43 * x + 0.59) + 0.14);
                y.clamp(0.0, 1.0)
            }
        }
    }
}

/// Exposure and tone curve for 8-bit output.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct ToneMap {
    /// Exposure in stops: radiance is scaled by `2^exposure_ev` before the curve.
    pub exposure_ev: f64,
    pub curve: Curve,
}

impl ToneMap {
    /// The linear scale `2^exposure_ev`.
    pub fn exposure_scale(&self) -> f64 {
        self.exposure_ev.exp2()
    }

    /// Linear radiance to a display value in `[0, 1]` (before the sRGB OETF).
    pub fn apply(&self, linear: f64) -> f64 {
        self.curve.apply(linear * self.exposure_scale())
    }

    /// Linear radiance to an 8-bit sRGB code value.
    pub fn encode(&self, linear: f64) -> u8 {
        encode_unorm8(srgb_oetf(self.apply(linear)))
    }
}

/// The sRGB OETF (IEC 61966-2-1:1999): linear `[0, 1]` to encoded `[0, 1]`,
/// `12.92 L` for `L ≤ 0.0031308`, else `1.055 L^(1/2.4) − 0.055`. Input is clamped to `[0, 1]`.
pub fn srgb_oetf(linear: f64) -> f64 {
    let l = if linear.is_nan() { 0.0 } else { linear.clamp(0.0, 1.0) };
    if l <= 0.0031308 {
        12.92 * l
    } else {
        1.055 * l.powf(1.0 / 2.4) - 0.055
    }
}

/// `[0, 1]` to the nearest 8-bit code (round half up; out-of-range input is clamped).
fn encode_unorm8(v: f64) -> u8 {
    // The clamp bounds the product to [0, 255], so the cast is exact.
    (v.clamp(0.0, 1.0) * 255.0).round() as u8
}

/// The film as tightly packed 8-bit sRGB, row-major from the top-left pixel, 3 bytes per pixel.
/// Pixels without samples are black.
pub fn to_rgb8(film: &Film, tonemap: &ToneMap) -> Vec<u8> {
    film.bounds().pixels().flat_map(|(x, y)| film.pixel_f64(x, y).map(|c| tonemap.encode(c))).collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::rgb::Rgb;

    #[test]
    fn srgb_oetf_known_values() {
        assert_eq!(srgb_oetf(0.0), 0.0);
        assert!((srgb_oetf(1.0) - 1.0).abs() < 1e-12);
        assert_eq!(encode_unorm8(srgb_oetf(0.0)), 0);
        assert_eq!(encode_unorm8(srgb_oetf(1.0)), 255);
        // 1.055 · 0.5^(1/2.4) − 0.055 = 0.735357 → 187.52 → 188.
        assert!((srgb_oetf(0.5) - 0.735_357).abs() < 1e-6);
        assert_eq!(encode_unorm8(srgb_oetf(0.5)), 188);
        // 18% grey → 117.6 → 118 (the familiar mid-grey code).
        assert_eq!(encode_unorm8(srgb_oetf(0.18)), 118);
        // Out of range and NaN clamp.
        assert_eq!(srgb_oetf(-1.0), 0.0);
        assert!((srgb_oetf(7.0) - 1.0).abs() < 1e-12);
        assert_eq!(srgb_oetf(f64::NAN), 0.0);
    }

    #[test]
    fn srgb_oetf_is_continuous_at_the_breakpoint() {
        // The two branches of IEC 61966-2-1 meet at 0.0031308 to within 1e-7 (the standard's
        // rounded constants leave a jump of a few 1e-8).
        let t = 0.0031308;
        let linear_branch = 12.92 * t;
        let power_branch = 1.055 * f64::powf(t, 1.0 / 2.4) - 0.055;
        assert!((linear_branch - power_branch).abs() < 1e-7);
        let below = srgb_oetf(t * (1.0 - 1e-12));
        let above = srgb_oetf(t * (1.0 + 1e-12));
        assert!((above - below).abs() < 1e-7);
        // Monotone across the whole range.
        let v: Vec<f64> = (0..=10_000).map(|k| srgb_oetf(f64::from(k) / 10_000.0)).collect();
        assert!(v.windows(2).all(|w| w[0] < w[1]));
    }

    #[test]
    fn rounding_is_to_nearest() {
        assert_eq!(encode_unorm8(0.5 / 255.0 - 1e-9), 0);
        assert_eq!(encode_unorm8(0.5 / 255.0 + 1e-9), 1);
        assert_eq!(encode_unorm8(254.49 / 255.0), 254);
        assert_eq!(encode_unorm8(2.0), 255);
    }

    #[test]
    fn filmic_is_monotone_from_zero_to_white() {
        assert_eq!(Curve::Filmic.apply(0.0), 0.0);
        let xs: Vec<f64> = (0..=20_000).map(|k| f64::from(k) * 1e-3).collect();
        let ys: Vec<f64> = xs.iter().map(|&x| Curve::Filmic.apply(x)).collect();
        assert!(ys.windows(2).all(|w| w[0] <= w[1]), "not monotone");
        // Strictly increasing below the white point (≈ 7.24).
        assert!(ys[..7000].windows(2).all(|w| w[0] < w[1]), "flat before white");
        assert!((Curve::Filmic.apply(1.0) - 0.8037).abs() < 1e-3, "pre-exposed: 1 → ~0.8");
        assert_eq!(Curve::Filmic.apply(10.0), 1.0);
        assert_eq!(Curve::Filmic.apply(f64::INFINITY), 1.0);
        assert_eq!(Curve::Filmic.apply(-3.0), 0.0);
        assert_eq!(Curve::Filmic.apply(f64::NAN), 0.0);
    }

    #[test]
    fn linear_clamps_and_exposure_scales() {
        let tm = ToneMap { exposure_ev: 0.0, curve: Curve::Linear };
        assert_eq!(tm.apply(0.25), 0.25);
        assert_eq!(tm.apply(3.0), 1.0);
        assert_eq!(tm.apply(-1.0), 0.0);
        let brighter = ToneMap { exposure_ev: 1.0, ..tm };
        assert_eq!(brighter.apply(0.25), 0.5);
        let darker = ToneMap { exposure_ev: -2.0, ..tm };
        assert_eq!(darker.apply(2.0), 0.5);
        assert_eq!(darker.encode(2.0), 188);
    }

    #[test]
    fn film_to_rgb8_layout_and_empty_pixels() {
        let mut film = Film::new(2, 2);
        film.add_sample(1, 0, Rgb::new(1.0, 0.5, 0.0), 1.0);
        film.add_sample(0, 1, Rgb::splat(4.0), 1.0);
        let bytes = to_rgb8(&film, &ToneMap::default());
        #[rustfmt::skip]
        assert_eq!(bytes, vec![
            0, 0, 0,      255, 188, 0,
            255, 255, 255, 0, 0, 0,
        ]);
    }
}

//! Linear RGB radiance and reflectance (Rec. 709 primaries).

/// Linear RGB triple. Radiance, reflectance and throughput all use it.
pub type Rgb = glam::Vec3;

/// The largest radiance a light or a sky may have (per channel, or as luminance). A sample's
/// radiance is multiplied by a path's throughput, by the frequency ratio's fourth power (g⁴,
/// which near a hole or a fast camera reaches 10⁸ and more) and summed over the samples of a
/// pixel in single precision, whose largest number is 3.4·10³⁸: below 10²⁰ these products stay
/// finite, above it an image could turn to infinities and NaN. No physical scene needs more in
/// any units a scene file uses.
pub const MAX_RADIANCE: f64 = 1e20;

/// ITU-R BT.709 luminance weights of the linear Rec. 709 primaries.
const LUMINANCE_WEIGHTS: [f64; 3] = [0.2126, 0.7152, 0.0722];

/// Relative luminance of a linear Rec. 709 colour (ITU-R BT.709 weights).
pub fn luminance(c: Rgb) -> f32 {
    0.2126 * c.x + 0.7152 * c.y + 0.0722 * c.z
}

/// [`luminance`] of a colour held in `f64` (accumulated sums).
pub fn luminance_f64(c: [f64; 3]) -> f64 {
    c.iter().zip(LUMINANCE_WEIGHTS).map(|(c, w)| c * w).sum()
}

/// True when every channel is finite; a NaN or infinity anywhere is a bug upstream.
pub fn is_finite(c: Rgb) -> bool {
    c.is_finite()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn white_has_unit_luminance() {
        assert!((luminance(Rgb::ONE) - 1.0).abs() < 1e-6);
    }
}

//! Linear RGB radiance and reflectance (Rec. 709 primaries).

/// Linear RGB triple. Radiance, reflectance and throughput all use it.
pub type Rgb = glam::Vec3;

/// Relative luminance of a linear Rec. 709 colour (ITU-R BT.709 weights).
pub fn luminance(c: Rgb) -> f32 {
    0.2126 * c.x + 0.7152 * c.y + 0.0722 * c.z
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

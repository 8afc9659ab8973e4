//! CIE XYZ, chromaticity, and the linear Rec. 709 (sRGB primaries, D65 white) conversions.

/// CIE XYZ tristimulus values.
pub type Xyz = glam::DVec3;

/// Linear Rec. 709 → XYZ, rows X, Y, Z: the ITU-R BT.709 primaries' XYZ scaled so that RGB (1, 1, 1)
/// is the D65 white (0.3127, 0.3290) with Y = 1 (derived to 7 digits, as the test below does).
/// Its middle row is the luminance weights.
const RGB_TO_XYZ: [[f64; 3]; 3] =
    [[0.4123908, 0.3575843, 0.1804808], [0.2126390, 0.7151687, 0.0721923], [0.0193308, 0.1191948, 0.9505322]];

/// XYZ → linear Rec. 709, the inverse of [`RGB_TO_XYZ`].
const XYZ_TO_RGB: [[f64; 3]; 3] =
    [[3.2409699, -1.5373832, -0.4986108], [-0.9692436, 1.8759675, 0.0415551], [0.0556301, -0.2039770, 1.0569715]];

fn apply(m: &[[f64; 3]; 3], v: glam::DVec3) -> glam::DVec3 {
    let row = |r: [f64; 3]| glam::DVec3::from(r).dot(v);
    glam::DVec3::new(row(m[0]), row(m[1]), row(m[2]))
}

/// Linear Rec. 709 RGB of `xyz`.
pub fn xyz_to_linear_srgb(xyz: Xyz) -> glam::DVec3 {
    apply(&XYZ_TO_RGB, xyz)
}

/// XYZ of linear Rec. 709 `rgb`.
pub fn linear_srgb_to_xyz(rgb: glam::DVec3) -> Xyz {
    apply(&RGB_TO_XYZ, rgb)
}

/// Chromaticity (x, y) = (X, Y) / (X + Y + Z).
pub fn chromaticity(xyz: Xyz) -> (f64, f64) {
    let s = xyz.x + xyz.y + xyz.z;
    (xyz.x / s, xyz.y / s)
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::{DMat3, DVec3};

    /// XYZ (Y = 1) of chromaticity (x, y).
    fn xyz_of(x: f64, y: f64) -> DVec3 {
        DVec3::new(x / y, 1.0, (1.0 - x - y) / y)
    }

    #[test]
    fn matrices_follow_from_the_rec709_primaries_and_d65() {
        // ITU-R BT.709: R (0.64, 0.33), G (0.30, 0.60), B (0.15, 0.06), white D65 (0.3127, 0.3290).
        let p = DMat3::from_cols(xyz_of(0.64, 0.33), xyz_of(0.30, 0.60), xyz_of(0.15, 0.06));
        let s = p.inverse() * xyz_of(0.3127, 0.3290);
        let m = p * DMat3::from_diagonal(s);
        for r in 0..3 {
            for c in 0..3 {
                assert!((m.row(r)[c] - RGB_TO_XYZ[r][c]).abs() < 1e-6, "({r},{c})");
                assert!((m.inverse().row(r)[c] - XYZ_TO_RGB[r][c]).abs() < 1e-6, "({r},{c})");
            }
        }
        let white = linear_srgb_to_xyz(DVec3::ONE);
        let (x, y) = chromaticity(white);
        assert!((x - 0.3127).abs() < 1e-6 && (y - 0.3290).abs() < 1e-6 && (white.y - 1.0).abs() < 1e-6);
        let back = xyz_to_linear_srgb(linear_srgb_to_xyz(DVec3::new(0.2, 0.5, 0.9)));
        assert!((back - DVec3::new(0.2, 0.5, 0.9)).abs().max_element() < 1e-6);
    }
}

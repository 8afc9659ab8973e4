//! # Normal maps
//!
//! A tangent-space normal read from an image bends a surface's shading normal, as glTF's
//! `normalTexture` (and Mitsuba's `normalmap`) do: the texel `c ∈ [0, 1]³` (linear, not
//! sRGB-decoded) is the normal `n_t = (s·(2c_x − 1), s·(2c_y − 1), 2c_z − 1)` with the map's
//! `scale` `s`, in the frame of the tangent `T` (`∂p/∂u` made perpendicular to the interpolated
//! normal `N`), the bitangent `B = N × T` (towards increasing `v`, up in the image, for UVs that
//! are not mirrored) and `N`: `n = normalize(n_t,x T + n_t,y B + n_t,z N)`. The image covers the
//! unit square of `uv` and repeats, with `v` up, as image textures do.
//!
//! Only the shading normal changes, so light is still reflected by the BSDF about a unit normal
//! and the geometry (and its geometric normal) stays as it is; a mapped normal that would face
//! away from the geometric side is dropped for the unmapped one, so that no map turns a surface
//! inside out.

use crate::geometry::Vec3;
use crate::shape::SurfaceHit;
use crate::texture::image_data::ImageData;
use std::sync::Arc;

#[derive(Clone, Debug)]
pub struct NormalMap {
    /// Linear texels, `v` up as [`crate::texture::image::eval`] reads them.
    pub image: Arc<ImageData>,
    /// Scales the map's tangential components (glTF `normalTexture.scale`, default 1).
    pub scale: f64,
}

impl NormalMap {
    /// The shading normal of `hit` bent by the map.
    pub fn shading_normal(&self, hit: &SurfaceHit) -> Vec3 {
        let c = crate::texture::image::eval(&self.image, hit.uv);
        let tangent_space = Vec3::new(
            self.scale * (2.0 * f64::from(c.x) - 1.0),
            self.scale * (2.0 * f64::from(c.y) - 1.0),
            2.0 * f64::from(c.z) - 1.0,
        );
        let n = hit.ns;
        let tangent = (hit.dpdu - n * n.dot(hit.dpdu)).normalize_or_zero();
        if tangent == Vec3::ZERO {
            return n;
        }
        let bitangent = n.cross(tangent);
        let bent = (tangent * tangent_space.x + bitangent * tangent_space.y + n * tangent_space.z).normalize_or_zero();
        if bent.dot(hit.ng) > 0.0 && bent.is_finite() {
            bent
        } else {
            n
        }
    }

    /// Checks the scale a file supplied.
    pub fn validate(&self) -> Result<(), String> {
        if self.scale.is_finite() {
            Ok(())
        } else {
            Err(format!("normal map scale {} must be a finite number", self.scale))
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::rgb::Rgb;

    fn map(texel: Rgb, scale: f64) -> NormalMap {
        NormalMap { image: Arc::new(ImageData::new(1, 1, vec![texel]).unwrap()), scale }
    }

    fn hit() -> SurfaceHit {
        // A floor facing up, u along x.
        SurfaceHit { p: Vec3::ZERO, ng: Vec3::Y, ns: Vec3::Y, uv: [0.3, 0.7], dpdu: Vec3::new(2.0, 0.0, 0.0) }
    }

    #[test]
    fn a_flat_texel_keeps_the_normal_and_a_tilted_one_tilts_it_towards_its_tangent() {
        assert!((map(Rgb::new(0.5, 0.5, 1.0), 1.0).shading_normal(&hit()) - Vec3::Y).length() < 1e-6);
        // (1, 0, 1)/√2 in tangent space: halfway between the normal (y) and the tangent (x).
        let n = map(Rgb::new(1.0, 0.5, 1.0), 1.0).shading_normal(&hit());
        assert!((n - Vec3::new(1.0, 1.0, 0.0).normalize()).length() < 1e-6, "{n}");
        // The bitangent is N × T = y × x = −z: a texel pointing along +y in the image leans to −z.
        let n = map(Rgb::new(0.5, 1.0, 1.0), 1.0).shading_normal(&hit());
        assert!((n - Vec3::new(0.0, 1.0, -1.0).normalize()).length() < 1e-6, "{n}");
        // Scale 0 flattens the map.
        assert!((map(Rgb::new(1.0, 0.5, 1.0), 0.0).shading_normal(&hit()) - Vec3::Y).length() < 1e-6);
        // A normal below the surface is not taken.
        assert_eq!(map(Rgb::new(0.5, 0.5, 0.0), 1.0).shading_normal(&hit()), Vec3::Y);
    }
}

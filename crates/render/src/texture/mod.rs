//! Textures: colours that vary over a surface, looked up with the hit's texture coordinates `uv` (as the
//! shape defines them) and position `p` (for solid textures).
//!
//! Every non-constant texture first scales its coordinates, `st = (u·uv_scale[0], v·uv_scale[1])`, so a
//! shape whose `uv` runs over `[0, 1]²` can be given physical units (`uv_scale = [8, 4]` on an 8 m × 4 m
//! wall makes one unit of `st` one metre), then works in `st`:
//!
//! | `type`      | variant               | file        | looks like                                         |
//! |-------------|-----------------------|-------------|----------------------------------------------------|
//! | (a colour)  | [`Texture::Constant`] | —           | one colour                                         |
//! | `"checker"` | [`Texture::Checker`]  | [`checker`] | unit squares of `st` alternating two textures      |
//! | `"grid"`    | [`Texture::Grid`]     | [`grid`]    | lines on a background, optional coloured lines     |
//! | `"image"`   | [`Texture::Image`]    | [`image`]   | a PNG / EXR / HDR file, bilinear, repeating        |
//! | `"earth"`   | [`Texture::Earth`]    | [`earth`]   | a procedural planet for a sphere's `uv`            |
//!
//! Colours are linear RGB. Procedural textures are evaluated at a point (no filtering); path tracing
//! with many samples per pixel antialiases them.
//!
//! [`image_data`] holds the in-memory raster that image textures, environment maps and normal maps
//! look up; the scene crate reads the files into it.

pub mod checker;
pub mod earth;
pub mod grid;
pub mod image;
pub mod image_data;

pub use grid::{GridAxis, GridHighlight};

use crate::geometry::Vec3;
use crate::rgb::Rgb;
use crate::spectrum::LiftedReflectance;
use image_data::ImageData;
use std::sync::Arc;

/// A colour over a surface. See the module documentation and each variant's file.
#[derive(Clone, Debug)]
pub enum Texture {
    /// The same colour everywhere, its reflectance spectrum lifted once (`Texture::from` a colour).
    Constant(LiftedReflectance),
    /// Unit squares of `st` alternate between `a` (the square `[0, 1)²`) and `b`.
    Checker { a: Box<Texture>, b: Box<Texture>, uv_scale: [f64; 2] },
    /// Lines of colour `line` and width `width` every `spacing` along `s` and `t`, over `background`;
    /// `highlights` recolour chosen lines.
    Grid { background: Rgb, line: Rgb, spacing: f64, width: f64, highlights: Vec<GridHighlight>, uv_scale: [f64; 2] },
    /// An image repeating every unit of `st`, bilinearly filtered; `v` runs up the image.
    Image { image: Arc<ImageData>, uv_scale: [f64; 2] },
    /// Oceans, continents, ice and clouds, seamless on a sphere (not scaled by `uv_scale`).
    Earth(Box<earth::Earth>),
}

impl Texture {
    /// The colour at texture coordinates `uv` and position `p`. Allocation-free.
    #[allow(clippy::only_used_in_recursion, reason = "`p` is part of the interface for solid textures")]
    pub fn eval(&self, uv: [f64; 2], p: Vec3) -> Rgb {
        match self {
            Texture::Constant(c) => c.rgb(),
            Texture::Checker { a, b, uv_scale } => {
                if checker::is_first(scale(uv, *uv_scale)) {
                    a.eval(uv, p)
                } else {
                    b.eval(uv, p)
                }
            }
            Texture::Grid { background, line, spacing, width, highlights, uv_scale } => {
                grid::eval(scale(uv, *uv_scale), *background, *line, *spacing, *width, highlights)
            }
            Texture::Image { image, uv_scale } => image::eval(image, scale(uv, *uv_scale)),
            Texture::Earth(earth) => earth.eval(uv),
        }
    }

    /// Checks the numbers a scene file supplied (finite colours and scales, a positive grid spacing); the
    /// message names the offending parameter. [`Texture::eval`] never panics either way.
    pub fn validate(&self) -> Result<(), String> {
        let scale_ok = |s: &[f64; 2]| {
            if s.iter().all(|x| x.is_finite()) {
                Ok(())
            } else {
                Err(format!("uv_scale {s:?} must be finite"))
            }
        };
        match self {
            Texture::Constant(c) => {
                let c = c.rgb();
                if c.is_finite() {
                    Ok(())
                } else {
                    Err(format!("colour {c} must be finite"))
                }
            }
            Texture::Checker { a, b, uv_scale } => {
                scale_ok(uv_scale)?;
                a.validate()?;
                b.validate()
            }
            Texture::Grid { spacing, width, uv_scale, .. } => {
                scale_ok(uv_scale)?;
                if !(spacing.is_finite() && *spacing > 0.0) {
                    Err(format!("grid spacing {spacing} must be a positive number"))
                } else if !(width.is_finite() && *width >= 0.0) {
                    Err(format!("grid line width {width} must be a number ≥ 0"))
                } else {
                    Ok(())
                }
            }
            Texture::Image { uv_scale, .. } => scale_ok(uv_scale),
            Texture::Earth(earth) => earth.validate(),
        }
    }

    /// A checkerboard of two colours with `squares` squares per unit of `u` and `v`.
    pub fn checker(a: Rgb, b: Rgb, squares: [f64; 2]) -> Self {
        Texture::Checker { a: Box::new(a.into()), b: Box::new(b.into()), uv_scale: squares }
    }
}

impl From<Rgb> for Texture {
    fn from(c: Rgb) -> Self {
        Texture::Constant(c.into())
    }
}

fn scale(uv: [f64; 2], s: [f64; 2]) -> [f64; 2] {
    [uv[0] * s[0], uv[1] * s[1]]
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn checker_alternates_and_nests() {
        let t = Texture::checker(Rgb::ONE, Rgb::ZERO, [4.0, 4.0]);
        let at = |u, v| t.eval([u, v], Vec3::ZERO);
        assert_eq!(at(0.1, 0.1), Rgb::ONE, "square (0, 0) is `a`");
        assert_eq!(at(0.3, 0.1), Rgb::ZERO);
        assert_eq!(at(0.3, 0.3), Rgb::ONE);
        assert_eq!(at(-0.1, 0.1), Rgb::ZERO, "negative coordinates continue the pattern");
        assert_eq!(at(-0.1, -0.1), Rgb::ONE);
        // A checker of checkers.
        let fine = Texture::checker(Rgb::X, Rgb::Y, [8.0, 8.0]);
        let nested = Texture::Checker { a: Box::new(fine), b: Box::new(Rgb::Z.into()), uv_scale: [2.0, 2.0] };
        assert_eq!(nested.eval([0.05, 0.05], Vec3::ZERO), Rgb::X);
        assert_eq!(nested.eval([0.2, 0.05], Vec3::ZERO), Rgb::Y);
        assert_eq!(nested.eval([0.7, 0.05], Vec3::ZERO), Rgb::Z);
    }
}

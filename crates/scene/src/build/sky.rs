//! `[sky]` and `[lower.sky]`: the radiance from infinity.

use super::Builder;
use crate::reader::{fmt_rgb, num, Kind, Node, Result, Table};
use render::geometry::Vec3;
use render::rgb::{Rgb, MAX_RADIANCE};
use render::sky::stars::max_brightness;
use render::sky::{Equirect, Gradient, LatLongGrid, Sky, SkyFrame, StarField, StarFieldParams};

/// Reads one sky type's parameters from its table and builds it.
type BuildSky = fn(&mut Builder<'_>, &Table<'_>) -> Result<Sky>;

/// The sky types of scene files: name, keys besides `type`, and builder.
const SKIES: &[Kind<BuildSky>] = &[
    Kind { name: "constant", keys: &["radiance"], build: constant },
    Kind { name: "gradient", keys: &["horizon", "zenith", "nadir", "up"], build: gradient },
    Kind { name: "equirect", keys: &["file", "intensity", "up", "rotation_deg"], build: equirect },
    Kind { name: "stars", keys: &["density", "brightness", "seed", "star_radius_deg", "background"], build: stars },
    Kind {
        name: "grid",
        keys: &["background", "line", "spacing_deg", "width_deg", "equator", "prime_meridian", "up", "rotation_deg"],
        build: grid,
    },
];

/// A radiance: ≥ 0 and at most [`MAX_RADIANCE`] per channel.
pub(super) fn radiance(n: &Node<'_>) -> Result<Rgb> {
    let c = n.colour()?;
    if c.min_element() < 0.0 {
        return Err(n.err(format!("radiance must be ≥ 0 in every channel, got {}", fmt_rgb(c))));
    }
    if f64::from(c.max_element()) > MAX_RADIANCE {
        return Err(n.err(too_bright(f64::from(c.max_element()))));
    }
    Ok(c)
}

/// Why a radiance above [`MAX_RADIANCE`] is refused.
pub(super) fn too_bright(value: f64) -> String {
    format!(
        "{} is too bright: at most {MAX_RADIANCE:e}, above which a path's radiance times its throughput and \
         frequency shift, summed over a pixel's samples, overflows",
        num(value)
    )
}

/// The sky's orientation from `up` and `rotation_deg`.
fn frame(t: &Table<'_>) -> Result<SkyFrame> {
    let up = t.or("up", Vec3::Y, |n| n.direction())?;
    let rotation = t.or("rotation_deg", 0.0, |n| n.f64())?;
    SkyFrame::new(up, rotation).map_err(|e| t.loc("up").err(e))
}

/// A non-negative number.
fn non_negative(t: &Table<'_>, key: &str, default: f64) -> Result<f64> {
    let x = t.or(key, default, |n| n.f64())?;
    if x >= 0.0 {
        Ok(x)
    } else {
        Err(t.loc(key).err(format!("must be ≥ 0, got {}", num(x))))
    }
}

impl Builder<'_> {
    pub(super) fn sky(&mut self, n: &Node<'_>) -> Result<Sky> {
        let (kind, t) = n.kind("sky", SKIES)?;
        (kind.build)(self, &t)
    }
}

fn constant(_: &mut Builder<'_>, t: &Table<'_>) -> Result<Sky> {
    Ok(Sky::Constant(t.req("radiance", radiance)?))
}

/// `nadir` defaults to `horizon`; a gradient turns with `up` only (it is symmetric about it).
fn gradient(_: &mut Builder<'_>, t: &Table<'_>) -> Result<Sky> {
    let horizon = t.or("horizon", Rgb::new(0.9, 0.9, 1.0), radiance)?;
    Ok(Sky::Gradient(Gradient {
        horizon,
        zenith: t.or("zenith", Rgb::new(0.3, 0.5, 0.9), radiance)?,
        nadir: t.or("nadir", horizon, radiance)?,
        frame: SkyFrame::new(t.or("up", Vec3::Y, |n| n.direction())?, 0.0).map_err(|e| t.loc("up").err(e))?,
    }))
}

/// `intensity` scales the image, up to [`MAX_RADIANCE`].
fn equirect(b: &mut Builder<'_>, t: &Table<'_>) -> Result<Sky> {
    let intensity = non_negative(t, "intensity", 1.0)?;
    if intensity > MAX_RADIANCE {
        return Err(t.loc("intensity").err(too_bright(intensity)));
    }
    let frame = frame(t)?;
    let image = b.image(&t.require("file")?)?;
    Ok(Sky::Equirect(Equirect { image, frame, intensity: intensity as f32 }))
}

/// Defaults from [`StarFieldParams::default`]; the brightness bounded by the star size, so that
/// sums of samples cannot overflow.
fn stars(_: &mut Builder<'_>, t: &Table<'_>) -> Result<Sky> {
    let d = StarFieldParams::default();
    let star_radius_deg = t.or("star_radius_deg", d.star_radius_deg, |n| n.f64())?;
    if !(star_radius_deg > 0.0 && star_radius_deg <= 2.0) {
        return Err(t.loc("star_radius_deg").err(format!("must be in (0, 2] degrees, got {}", num(star_radius_deg))));
    }
    let brightness = non_negative(t, "brightness", d.brightness)?;
    if brightness > max_brightness(star_radius_deg) {
        return Err(t.loc("brightness").err(format!(
            "{} is too bright for stars of star_radius_deg = {}: at most {:.3e}, above which \
             the brightest stars' radiance exceeds {MAX_RADIANCE:e} and sums of samples overflow",
            num(brightness),
            num(star_radius_deg),
            max_brightness(star_radius_deg)
        )));
    }
    let params = StarFieldParams {
        density: non_negative(t, "density", d.density)?,
        brightness,
        seed: t.or("seed", d.seed, |n| n.u64())?,
        star_radius_deg,
        background: t.or("background", d.background, radiance)?,
    };
    // What is left to fail is density against star size: point at the density.
    Ok(Sky::StarField(StarField::new(params).map_err(|e| t.loc("density").err(e))?))
}

/// `background` is one colour or four, one per quadrant.
fn grid(_: &mut Builder<'_>, t: &Table<'_>) -> Result<Sky> {
    let background = match t.get("background") {
        Some(n) if n.is_array() && n.array()?.first().is_some_and(|e| e.is_array()) => {
            let quadrants = n.array()?;
            if quadrants.len() != 4 {
                return Err(n.err(format!(
                    "expected one colour or 4 (one per quadrant), got {}",
                    crate::reader::count(quadrants.len(), "colour")
                )));
            }
            let mut out = [Rgb::ZERO; 4];
            for (o, q) in out.iter_mut().zip(&quadrants) {
                *o = radiance(q)?;
            }
            out
        }
        Some(n) => [radiance(&n)?; 4],
        None => [Rgb::splat(0.05); 4],
    };
    let spacing_deg = t.or("spacing_deg", 10.0, |n| n.f64())?;
    if !(spacing_deg > 0.0) {
        return Err(t.loc("spacing_deg").err(format!("must be > 0 degrees, got {}", num(spacing_deg))));
    }
    Ok(Sky::Grid(LatLongGrid {
        frame: frame(t)?,
        background,
        line: t.or("line", Rgb::splat(0.9), radiance)?,
        spacing_deg,
        width_deg: non_negative(t, "width_deg", 0.3)?,
        equator: t.opt("equator", radiance)?,
        prime_meridian: t.opt("prime_meridian", radiance)?,
    }))
}

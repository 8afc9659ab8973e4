//! `[materials.NAME]`, inline materials of objects, and textures.

use super::Builder;
use crate::error::suggest;
use crate::reader::{fmt_rgb, num, Kind, Node, Result, Table};
use render::material::{ConductorFresnel, Dispersion, Material};
use render::rgb::Rgb;
use render::texture::earth::Earth;
use render::texture::image_data::ImageData;
use render::texture::{GridAxis, GridHighlight, Texture};
use std::sync::Arc;

/// Reads one material type's parameters from its table and builds it.
type BuildMaterial = fn(&mut Builder<'_>, &Table<'_>) -> Result<Material>;

/// The material types of scene files: name, keys besides `type`, and builder.
const MATERIALS: &[Kind<BuildMaterial>] = &[
    Kind { name: "diffuse", keys: &["reflectance"], build: diffuse },
    Kind { name: "mirror", keys: &["reflectance"], build: mirror },
    Kind { name: "dielectric", keys: &["ior", "abbe", "transmittance"], build: dielectric },
    Kind { name: "conductor", keys: &["roughness", "metal", "eta", "k", "f0"], build: conductor },
    Kind { name: "plastic", keys: &["diffuse", "roughness", "ior"], build: plastic },
];

/// Reads one texture type's parameters from its table and builds it.
type BuildTexture = fn(&mut Builder<'_>, &Table<'_>) -> Result<Texture>;

/// The texture types of scene files: name, keys besides `type`, and builder.
const TEXTURES: &[Kind<BuildTexture>] = &[
    Kind { name: "checker", keys: &["a", "b", "uv_scale"], build: checker },
    Kind { name: "grid", keys: &["background", "line", "spacing", "width", "highlights", "uv_scale"], build: grid },
    Kind { name: "image", keys: &["file", "uv_scale"], build: image },
    Kind { name: "earth", keys: &["seed", "ocean", "clouds"], build: earth },
];

const HIGHLIGHT_KEYS: &[&str] = &["axis", "index", "colour", "color"];

/// A reflectance-like colour: finite and in `[0, 1]` per channel.
fn albedo(n: &Node<'_>) -> Result<Rgb> {
    let c = n.colour()?;
    if c.min_element() < 0.0 || c.max_element() > 1.0 {
        return Err(n.err(format!("must lie in [0, 1] in every channel, got {}", fmt_rgb(c))));
    }
    Ok(c)
}

/// Roughness in `[0, 1]` (default 0.1).
fn roughness(t: &Table<'_>) -> Result<f64> {
    let r = t.or("roughness", 0.1, |n| n.f64())?;
    if (0.0..=1.0).contains(&r) {
        Ok(r)
    } else {
        Err(t.loc("roughness").err(format!("must lie in [0, 1], got {}", num(r))))
    }
}

impl Builder<'_> {
    /// The `[materials]` table: every entry, in file order, becomes a named material.
    pub(super) fn named_materials(&mut self, t: &Table<'_>) -> Result<()> {
        for (name, n) in t.entries() {
            let material = self.material(&n)?;
            self.materials.push(material);
            self.material_names.insert(name.to_string(), self.materials.len() - 1);
        }
        Ok(())
    }

    /// An object's `material`: a name from `[materials]` or an inline material table; the index
    /// into the world's materials.
    pub(super) fn material_ref(&mut self, n: &Node<'_>) -> Result<usize> {
        if n.is_str() {
            let name = n.str()?;
            return self.material_names.get(name).copied().ok_or_else(|| {
                let mut known: Vec<&str> = self.material_names.keys().map(String::as_str).collect();
                known.sort_unstable();
                let hint = suggest(name, known.iter().copied())
                    .map_or_else(String::new, |s| format!(" (did you mean \"{s}\"?)"));
                let defined = if known.is_empty() {
                    "no materials are defined under [materials]".to_string()
                } else {
                    format!("defined materials: {}", known.join(", "))
                };
                n.err(format!("unknown material \"{name}\"{hint}; {defined}"))
            });
        }
        if !n.is_table() {
            return Err(n.expected("a material name (a string) or a material table { type = \"…\", … }"));
        }
        let material = self.material(n)?;
        self.materials.push(material);
        Ok(self.materials.len() - 1)
    }

    /// A material table.
    pub(super) fn material(&mut self, n: &Node<'_>) -> Result<Material> {
        let (kind, t) = n.kind("material", MATERIALS)?;
        let material = (kind.build)(self, &t)?;
        material.validate().map_err(|e| n.err(e))?;
        Ok(material)
    }

    fn texture_or(&mut self, t: &Table<'_>, key: &str, grey: f32) -> Result<Texture> {
        match t.get(key) {
            Some(n) => self.texture(&n),
            None => Ok(Texture::from(Rgb::splat(grey))),
        }
    }

    /// A colour or a texture table, with colours in `[0, 1]`.
    pub(super) fn texture(&mut self, n: &Node<'_>) -> Result<Texture> {
        if !n.is_table() {
            return albedo(n).map(Texture::from);
        }
        let (kind, t) = n.kind("texture", TEXTURES)?;
        let texture = (kind.build)(self, &t)?;
        texture.validate().map_err(|e| n.err(e))?;
        Ok(texture)
    }

    /// The image named by a `file` value, relative to the scene file; loaded once per path.
    pub(super) fn image(&mut self, file: &Node<'_>) -> Result<Arc<ImageData>> {
        let resource = self.resolve(file.str()?);
        if let Some(image) = self.images.get(resource.path()) {
            return Ok(Arc::clone(image));
        }
        let image = Arc::new(crate::files::load_image(&resource).map_err(|e| file.err(e.to_string()))?);
        self.images.insert(resource.path().to_path_buf(), Arc::clone(&image));
        Ok(image)
    }
}

fn diffuse(b: &mut Builder<'_>, t: &Table<'_>) -> Result<Material> {
    Ok(Material::Diffuse { reflectance: b.texture_or(t, "reflectance", 0.5)? })
}

fn mirror(b: &mut Builder<'_>, t: &Table<'_>) -> Result<Material> {
    Ok(Material::Mirror { reflectance: b.texture_or(t, "reflectance", 1.0)? })
}

/// `ior` (default 1.5, > 0) and, for dispersion, `abbe`.
fn dielectric(b: &mut Builder<'_>, t: &Table<'_>) -> Result<Material> {
    let ior = t.or("ior", 1.5, |n| n.f64())?;
    if !(ior > 0.0) {
        return Err(t.loc("ior").err(format!("must be > 0, got {}", num(ior))));
    }
    let dispersion = match t.get("abbe") {
        Some(abbe) => Some(
            Dispersion::from_abbe(ior, abbe.f64()?)
                .ok_or_else(|| abbe.err("must be a positive Abbe number (BK7 glass: 64.17), with ior > 1"))?,
        ),
        None => None,
    };
    Ok(Material::Dielectric { ior, dispersion, transmittance: b.texture_or(t, "transmittance", 1.0)? })
}

fn conductor(_: &mut Builder<'_>, t: &Table<'_>) -> Result<Material> {
    Ok(Material::RoughConductor { roughness: roughness(t)?, fresnel: conductor_fresnel(t)? })
}

/// `ior` (default 1.5) at least 1: the coating is denser than outside.
fn plastic(b: &mut Builder<'_>, t: &Table<'_>) -> Result<Material> {
    let ior = t.or("ior", 1.5, |n| n.f64())?;
    if !(ior >= 1.0) {
        return Err(t.loc("ior").err(format!("must be ≥ 1 (a coating denser than outside), got {}", num(ior))));
    }
    Ok(Material::RoughPlastic { diffuse: b.texture_or(t, "diffuse", 0.5)?, roughness: roughness(t)?, ior })
}

/// `uv_scale`: a number or `[su, sv]`.
fn uv_scale(t: &Table<'_>, default: [f64; 2]) -> Result<[f64; 2]> {
    t.or("uv_scale", default, |n| n.pair())
}

fn checker(b: &mut Builder<'_>, t: &Table<'_>) -> Result<Texture> {
    Ok(Texture::Checker {
        a: Box::new(b.texture_or(t, "a", 0.8)?),
        b: Box::new(b.texture_or(t, "b", 0.2)?),
        uv_scale: uv_scale(t, [10.0, 10.0])?,
    })
}

fn grid(_: &mut Builder<'_>, t: &Table<'_>) -> Result<Texture> {
    let spacing = t.or("spacing", 0.1, |n| n.f64())?;
    if !(spacing > 0.0) {
        return Err(t.loc("spacing").err(format!("must be > 0, got {}", num(spacing))));
    }
    let width = t.or("width", 0.01, |n| n.f64())?;
    if !(width >= 0.0) {
        return Err(t.loc("width").err(format!("must be ≥ 0, got {}", num(width))));
    }
    let mut highlights = Vec::new();
    if let Some(list) = t.get("highlights") {
        for h in list.array()? {
            highlights.push(highlight(&h.table(HIGHLIGHT_KEYS)?)?);
        }
    }
    Ok(Texture::Grid {
        background: t.or("background", Rgb::splat(0.9), albedo)?,
        line: t.or("line", Rgb::splat(0.05), albedo)?,
        spacing,
        width,
        highlights,
        uv_scale: uv_scale(t, [1.0, 1.0])?,
    })
}

fn image(b: &mut Builder<'_>, t: &Table<'_>) -> Result<Texture> {
    Ok(Texture::Image { image: b.image(&t.require("file")?)?, uv_scale: uv_scale(t, [1.0, 1.0])? })
}

/// `seed`, and `ocean` and `clouds` as fractions of the surface in `[0, 1]`.
fn earth(_: &mut Builder<'_>, t: &Table<'_>) -> Result<Texture> {
    let seed = t.or("seed", 0, |n| n.u32_in(0, u32::MAX))?;
    let fraction = |key: &str, default: f64| {
        let x = t.or(key, default, |n| n.f64())?;
        if (0.0..=1.0).contains(&x) {
            Ok(x)
        } else {
            Err(t.loc(key).err(format!("must be a fraction in [0, 1], got {}", num(x))))
        }
    };
    Ok(Texture::Earth(Box::new(Earth::new(seed, fraction("ocean", 0.65)?, fraction("clouds", 0.35)?))))
}

/// `{ axis = "u" | "v", index = k, colour = [r, g, b] }`.
fn highlight(t: &Table<'_>) -> Result<GridHighlight> {
    let axis = t.req("axis", |n| n.choice("axis", &[("u", GridAxis::U), ("v", GridAxis::V)]))?;
    let index = t.req("index", |n| n.int())?;
    let colour = match t.get_alias(&["colour", "color"])? {
        Some(n) => albedo(&n)?,
        None => return Err(t.missing("colour")),
    };
    Ok(GridHighlight { axis, index, colour })
}

/// A conductor's Fresnel term: `metal = "name"`, or `eta` and `k`, or `f0`; silver by default.
fn conductor_fresnel(t: &Table<'_>) -> Result<ConductorFresnel> {
    let given: Vec<&str> = ["metal", "eta", "f0"].into_iter().filter(|k| t.get(k).is_some()).collect();
    if given.len() > 1 {
        return Err(t
            .loc(given[1])
            .err(format!("give only one of metal, eta and k, or f0 (found {} and {})", given[0], given[1])));
    }
    if let Some(k) = t.get("k") {
        if t.get("eta").is_none() {
            return Err(k.err("k needs eta (the complex index of refraction is eta + i·k)"));
        }
    }
    let fresnel = if let Some(n) = t.get("eta") {
        let k = t.require("k")?;
        let (eta, kk) = (n.colour()?, k.colour()?);
        for (node, c) in [(&n, eta), (&k, kk)] {
            if c.min_element() < 0.0 {
                return Err(node.err(format!("must be ≥ 0 in every channel, got {}", fmt_rgb(c))));
            }
        }
        ConductorFresnel::Complex { eta, k: kk }
    } else if let Some(n) = t.get("f0") {
        ConductorFresnel::Schlick { f0: albedo(&n)? }
    } else {
        let metal = t.or("metal", "silver", |n| n.str())?;
        ConductorFresnel::preset(metal).ok_or_else(|| {
            let hint = suggest(metal, ConductorFresnel::PRESETS)
                .map_or_else(String::new, |s| format!(" (did you mean \"{s}\"?)"));
            t.loc("metal").err(format!(
                "unknown metal \"{metal}\"{hint}; expected {}",
                crate::reader::one_of(&ConductorFresnel::PRESETS)
            ))
        })?
    };
    let about = match fresnel {
        ConductorFresnel::Complex { .. } => "eta",
        ConductorFresnel::Schlick { .. } => "f0",
    };
    fresnel.validate().map_err(|e| t.loc(about).err(e))?;
    Ok(fresnel)
}

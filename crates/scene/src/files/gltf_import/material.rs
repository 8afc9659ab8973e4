//! glTF's metallic–roughness materials as nullpath materials.
//!
//! | glTF material                                           | nullpath material                         |
//! |---------------------------------------------------------|-------------------------------------------|
//! | `KHR_materials_transmission` factor > 0                 | `dielectric`, `ior` from `KHR_materials_ior` (1.5), tinted by the base colour |
//! | metallic ≥ 0.5, roughness < 0.0316 (GGX α < 10⁻³)       | `mirror`, reflectance = base colour (texture × factor) |
//! | metallic ≥ 0.5, rougher                                 | `conductor`, Schlick `f0` = base colour factor |
//! | metallic < 0.5                                          | `plastic`: base colour (texture × factor) under a coating of index 1.5 (glTF's F0 = 0.04) and the same roughness |
//!
//! Roughness means the same in both (GGX `α = roughness²`). Emission is `emissiveFactor` times
//! `KHR_materials_emissive_strength`, constant over the surface (an emissive texture is ignored,
//! with a warning), one-sided unless the material is `doubleSided`. Base-colour textures are
//! decoded from sRGB to linear; a normal texture (read as linear data, with its `scale`) bends
//! the shading normal ([`NormalMap`]); alpha, the metallic–roughness and occlusion textures are
//! ignored (a warning names the material).

use super::check::view_in_buffer;
use super::source::Sources;
use super::{contained, named, short};
use render::material::microfacet::SMOOTH_ALPHA;
use render::material::{ConductorFresnel, Material, NormalMap};
use render::rgb::Rgb;
use render::texture::image_data::{srgb_to_linear, ImageData};
use render::texture::Texture;
use render::world::Emission;
use std::sync::Arc;

/// Index of refraction of glTF's dielectrics: its `F0 = 0.04` is `((n − 1)/(n + 1))²` at 1.5.
const GLTF_IOR: f64 = 1.5;
/// Metallic factors from here up are metals; below, dielectrics.
const METAL_FROM: f32 = 0.5;

/// An image's size and linear pixels.
type Decoded = (usize, usize, Arc<Vec<Rgb>>);

/// A glTF material, mapped.
#[derive(Clone, Debug)]
pub(crate) struct GltfMaterial {
    pub name: Option<String>,
    pub material: Material,
    pub emission: Option<Emission>,
}

/// Every material of the document, in order.
pub(super) fn materials(
    document: &gltf::Document,
    sources: Sources<'_>,
    buffers: &[Vec<u8>],
    warnings: &mut Vec<String>,
) -> Result<Vec<GltfMaterial>, String> {
    let mut images: Vec<Option<Decoded>> = vec![None; document.images().len()];
    let mut mapped = Vec::new();
    for m in document.materials() {
        let name = named("material", m.index().unwrap_or(0), m.name());
        let ignored: Vec<&str> = [
            (m.occlusion_texture().is_some(), "occlusion"),
            (m.pbr_metallic_roughness().metallic_roughness_texture().is_some(), "metallic-roughness"),
            (m.emissive_texture().is_some(), "emissive"),
        ]
        .into_iter()
        .filter_map(|(present, what)| present.then_some(what))
        .collect();
        if !ignored.is_empty() {
            warnings.push(format!("{name}: its {} texture(s) are ignored", ignored.join(", ")));
        }
        let base_colour = base_colour(&m, &name, sources, buffers, &mut images, warnings)?;
        let mut material = surface(&m, base_colour);
        if let Some(map) = normal_map(&m, &name, sources, buffers, warnings)? {
            material = Material::NormalMapped { base: Box::new(material), map };
        }
        mapped.push(GltfMaterial { name: m.name().map(str::to_string), material, emission: emission(&m, &name)? });
    }
    Ok(mapped)
}

/// The nullpath material for `m`, whose base colour (texture × factor) is `base_colour`.
fn surface(m: &gltf::Material<'_>, base_colour: Texture) -> Material {
    let pbr = m.pbr_metallic_roughness();
    let factor = pbr.base_color_factor();
    let colour = Rgb::new(factor[0], factor[1], factor[2]).clamp(Rgb::ZERO, Rgb::ONE);
    let roughness = f64::from(pbr.roughness_factor()).clamp(0.0, 1.0);
    let transmission = m.transmission().map_or(0.0, |t| t.transmission_factor());
    if transmission > 0.0 {
        let ior = m.ior().map_or(GLTF_IOR, f64::from);
        let ior = if ior.is_finite() && ior > 0.0 { ior } else { GLTF_IOR };
        Material::Dielectric { ior, dispersion: None, transmittance: base_colour }
    } else if pbr.metallic_factor() >= METAL_FROM {
        if roughness * roughness < SMOOTH_ALPHA {
            Material::Mirror { reflectance: base_colour }
        } else {
            Material::RoughConductor { roughness, fresnel: ConductorFresnel::Schlick { f0: colour } }
        }
    } else {
        Material::RoughPlastic { diffuse: base_colour, roughness, ior: GLTF_IOR }
    }
}

/// `emissiveFactor × emissive_strength`, if not black.
fn emission(m: &gltf::Material<'_>, name: &str) -> Result<Option<Emission>, String> {
    let strength = m.emissive_strength().unwrap_or(1.0);
    let [r, g, b] = m.emissive_factor().map(|c| c * strength);
    let radiance = Rgb::new(r, g, b);
    if !(radiance.is_finite() && radiance.min_element() >= 0.0) {
        return Err(format!("{name}: its emission {radiance} is not a finite non-negative colour"));
    }
    Ok((radiance.max_element() > 0.0).then_some(Emission::uniform(radiance, m.double_sided())))
}

/// The base colour: its texture's linear pixels times the factor, or the factor alone.
fn base_colour(
    m: &gltf::Material<'_>,
    name: &str,
    sources: Sources<'_>,
    buffers: &[Vec<u8>],
    images: &mut [Option<Decoded>],
    warnings: &mut Vec<String>,
) -> Result<Texture, String> {
    let pbr = m.pbr_metallic_roughness();
    let f = pbr.base_color_factor();
    let factor = Rgb::new(f[0], f[1], f[2]);
    if !(factor.is_finite()) {
        return Err(format!("{name}: its baseColorFactor {factor} is not finite"));
    }
    let Some(info) = pbr.base_color_texture() else {
        return Ok(Texture::from(factor));
    };
    if info.tex_coord() != 0 {
        warnings.push(format!("{name}: its base colour uses TEXCOORD_{}; TEXCOORD_0 is used", info.tex_coord()));
    }
    let image = info.texture().source();
    let (width, height, pixels) = decode(&image, sources, buffers, images)?;
    let scaled: Vec<Rgb> = pixels.iter().map(|&c| c * factor).collect();
    let data = ImageData::new(width, height, scaled)
        .ok_or_else(|| format!("{}: has no pixels", named("image", image.index(), image.name())))?;
    Ok(Texture::Image { image: Arc::new(data), uv_scale: [1.0, 1.0] })
}

/// The normal texture, its texels taken as they are (normal maps are not sRGB-encoded).
fn normal_map(
    m: &gltf::Material<'_>,
    name: &str,
    sources: Sources<'_>,
    buffers: &[Vec<u8>],
    warnings: &mut Vec<String>,
) -> Result<Option<NormalMap>, String> {
    let Some(info) = m.normal_texture() else { return Ok(None) };
    if info.tex_coord() != 0 {
        warnings.push(format!("{name}: its normal texture uses TEXCOORD_{}; TEXCOORD_0 is used", info.tex_coord()));
    }
    let scale = f64::from(info.scale());
    if !scale.is_finite() {
        return Err(format!("{name}: its normalTexture.scale {} is not finite", info.scale()));
    }
    let image = info.texture().source();
    let (width, height, pixels) = load(&image, sources, buffers, Encoding::Linear)?;
    let data = ImageData::new(width, height, pixels)
        .ok_or_else(|| format!("{}: has no pixels", named("image", image.index(), image.name())))?;
    Ok(Some(NormalMap { image: Arc::new(data), scale }))
}

/// How an image's 8- and 16-bit values are meant: colours (sRGB) or data (linear).
#[derive(Clone, Copy)]
enum Encoding {
    Srgb,
    Linear,
}

/// The linear RGB pixels of an sRGB-encoded image, decoded once per image.
fn decode(
    image: &gltf::Image<'_>,
    sources: Sources<'_>,
    buffers: &[Vec<u8>],
    images: &mut [Option<Decoded>],
) -> Result<Decoded, String> {
    if let Some(Some(decoded)) = images.get(image.index()) {
        return Ok(decoded.clone());
    }
    let (width, height, pixels) = load(image, sources, buffers, Encoding::Srgb)?;
    let decoded = (width, height, Arc::new(pixels));
    if let Some(slot) = images.get_mut(image.index()) {
        *slot = Some(decoded.clone());
    }
    Ok(decoded)
}

/// The pixels of `image`, as `encoding` says its values are meant. Its bytes come from a `data:`
/// URI, a file (see [`super::source`]) or a buffer view; PNG and JPEG are decoded.
fn load(
    image: &gltf::Image<'_>,
    sources: Sources<'_>,
    buffers: &[Vec<u8>],
    encoding: Encoding,
) -> Result<(usize, usize, Vec<Rgb>), String> {
    let what = named("image", image.index(), image.name());
    // The gltf crate unwraps a `uri` an image may lack, and a `bufferView` image's `mimeType`,
    // which its validation does not require.
    let (what, bytes, mime_type) = match contained(|| image.source(), &what)? {
        gltf::image::Source::Uri { uri, mime_type } => {
            let what = format!("{what} ('{}')", short(uri));
            let bytes = sources.read(uri).map_err(|e| format!("{what}: {e}"))?;
            (what, bytes, mime_type)
        }
        gltf::image::Source::View { view, mime_type } => {
            view_in_buffer(&view, buffers).map_err(|e| format!("{what}: {e}"))?;
            let bytes = buffers
                .get(view.buffer().index())
                .and_then(|b| b.get(view.offset()..view.offset() + view.length()))
                .ok_or_else(|| format!("{what}: its bufferView lies outside its buffer"))?;
            (what, bytes.to_vec(), Some(mime_type))
        }
    };
    let format = match mime_type {
        Some("image/png") => image::ImageFormat::Png,
        Some("image/jpeg") => image::ImageFormat::Jpeg,
        _ => match image::guess_format(&bytes) {
            Ok(format @ (image::ImageFormat::Png | image::ImageFormat::Jpeg)) => format,
            _ => return Err(format!("{what}: neither PNG nor JPEG, the formats of glTF images")),
        },
    };
    let decoded = contained(|| image::load_from_memory_with_format(&bytes, format), &what)?
        .map_err(|e| format!("{what}: cannot decode: {e}"))?;
    let (width, height) = (decoded.width() as usize, decoded.height() as usize);
    Ok((width, height, linear_pixels(decoded, encoding)))
}

/// The image's pixels as linear RGB, row by row from the top, sRGB-decoded if `encoding` says so;
/// grey is spread to the three channels and alpha dropped.
fn linear_pixels(image: image::DynamicImage, encoding: Encoding) -> Vec<Rgb> {
    let decode = |v: f32| match encoding {
        Encoding::Srgb => srgb_to_linear(v),
        Encoding::Linear => v,
    };
    // 8- and 16-bit values become fractions of their largest value.
    image.into_rgb32f().pixels().map(|p| Rgb::new(decode(p.0[0]), decode(p.0[1]), decode(p.0[2]))).collect()
}

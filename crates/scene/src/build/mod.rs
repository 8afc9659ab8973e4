//! From the document tree to a [`Scene`]: one function per section of the file, each checking its
//! values where it reads them so that errors point at the offending value.

mod accretion_disk;
mod camera;
mod gltf_object;
mod material;
mod metric;
mod object;
mod settings;
mod sky;
mod spacetime;

pub use spacetime::spacetime_table;

use crate::files::{ReadPolicy, Resource};
use crate::reader::{Doc, Result, Table};
use ::spacetime::metric::MetricDescriptor;
use ::spacetime::Region;
use render::material::Material;
use render::scene::Scene;
use render::sky::Sky;
use render::texture::image_data::ImageData;
use render::world::{Object, World};
use std::collections::HashMap;
use std::path::{Path, PathBuf};
use std::sync::Arc;
use toml::de::DeTable;
use toml::Spanned;

/// State shared by the sections: where relative paths start, which files may be read, loaded
/// images, materials so far.
pub(crate) struct Builder<'a> {
    base_dir: &'a Path,
    policy: &'a ReadPolicy,
    /// Images by resolved path, so that a file used twice is loaded once.
    images: HashMap<PathBuf, Arc<ImageData>>,
    materials: Vec<Material>,
    /// Named materials: name → index into `materials`.
    material_names: HashMap<String, usize>,
    /// The material of objects that name none, once one has been needed.
    default_material: Option<usize>,
    /// Which regions the spacetime has: a wormhole has two.
    two_regions: bool,
    /// The cameras of the glTF objects read so far, placed in the world.
    gltf_cameras: Vec<gltf_object::PlacedCamera>,
}

const TOP_LEVEL: &[&str] =
    &["spacetime", "camera", "views", "animation", "render", "sky", "lower", "materials", "objects", "accretion_disk"];

/// The spacetime of the parsed document `root`, which holds a `[spacetime]` table and nothing
/// else, read as a scene file's (flat space without one), with its symmetry axis.
pub(crate) fn spacetime_alone<'a>(
    doc: &'a Doc<'a>,
    root: &'a Spanned<DeTable<'a>>,
) -> Result<(::spacetime::Spacetime, render::geometry::Vec3)> {
    let root = Table::root(doc, root, &["spacetime"])?;
    let file = match root.get("spacetime") {
        Some(n) => spacetime::section(&n, ::spacetime::metric::SPACETIMES)?,
        None => spacetime::FileSpacetime::flat(),
    };
    Ok((file.spacetime, file.axis))
}

/// Builds the scene described by the parsed document `root`, whose relative paths start at
/// `base_dir`, reading files under `policy`, its `[spacetime]` one of `metrics` (or written).
pub(crate) fn scene<'a>(
    doc: &'a Doc<'a>,
    root: &'a Spanned<DeTable<'a>>,
    base_dir: &'a Path,
    policy: &'a ReadPolicy,
    view: Option<&str>,
    metrics: &[&MetricDescriptor],
) -> Result<Scene> {
    let root = Table::root(doc, root, TOP_LEVEL)?;
    let file = match root.get("spacetime") {
        Some(n) => spacetime::section(&n, metrics)?,
        None => spacetime::FileSpacetime::flat(),
    };
    let axis = file.axis;
    let (cameras, chosen) = camera_tables(doc, &root, view)?;
    // Each camera's own spacetime: a view may set the parameters anew (`[views.NAME.spacetime]`,
    // as the preview's Save view writes its sliders), and the scene is in the chosen one's.
    let spacetimes = cameras.iter().map(|t| spacetime::view_spacetime(t, &file)).collect::<Result<Vec<_>>>()?;
    let spacetime = spacetimes[chosen].clone();
    let mut b = Builder {
        base_dir,
        policy,
        images: HashMap::new(),
        materials: Vec::new(),
        material_names: HashMap::new(),
        default_material: None,
        two_regions: spacetime.regions().len() == 2,
        gltf_cameras: Vec::new(),
    };
    if let Some(n) = root.get("materials") {
        b.named_materials(&n.any_table()?)?;
    }
    // Objects before cameras: a camera may be one of their glTF files'.
    let (mut upper, mut lower): (Vec<Object>, Vec<Object>) = (Vec::new(), Vec::new());
    if let Some(n) = root.get("objects") {
        if n.is_table() {
            return Err(n.err("expected an array of tables: write each object as [[objects]], not [objects]"));
        }
        for element in n.array()? {
            let (region, objects) = b.object(&element)?;
            match region {
                Region::Upper => upper.extend(objects),
                Region::Lower => lower.extend(objects),
            }
        }
    }
    if let Some(n) = root.get("accretion_disk") {
        upper.push(b.accretion_disk(&n, &spacetime, axis)?);
    }
    let mut rigs = Vec::with_capacity(cameras.len());
    for (i, (t, seen_in)) in cameras.iter().zip(&spacetimes).enumerate() {
        let rig = b.camera_rig(t)?;
        // Every view is checked at load, not only the one rendered: a view that cannot be
        // rendered (inside a horizon, faster than light) is a mistake in the file.
        rig.at_rest(0.0, seen_in, axis).map_err(|e| t.loc("position").err(e))?;
        if i != chosen {
            rig.camera_at(0.0, seen_in, axis).map_err(|e| t.err(e))?;
        }
        rigs.push(rig);
    }
    let (camera_table, rig) = (&cameras[chosen], rigs.swap_remove(chosen));
    let animation_table = root.get("animation").map(|n| n.table(camera::ANIMATION_KEYS)).transpose()?;
    let animation = camera::animation(animation_table.as_ref(), camera_table, rig, &spacetime, axis)?;
    let camera = animation.rig.camera_at(0.0, &spacetime, axis).map_err(|e| camera_table.err(e))?;
    let settings = match root.get("render") {
        Some(n) => settings::render_settings(&n.table(settings::RENDER_KEYS)?, &spacetime)?,
        None => render::settings::RenderSettings::default(),
    };
    let upper_sky = match root.get("sky") {
        Some(n) => b.sky(&n)?,
        None => Sky::Constant(render::rgb::Rgb::ZERO),
    };
    let lower_sky = match root.get("lower") {
        Some(n) => {
            let lower = n.table(&["sky"])?;
            if !b.two_regions {
                return Err(lower.err(format!(
                    "only a wormhole (type = \"ellis\" or \"wormhole\") has a lower region; this spacetime ({}) has one",
                    spacetime.name()
                )));
            }
            match lower.get("sky") {
                Some(n) => b.sky(&n)?,
                None => Sky::Constant(render::rgb::Rgb::ZERO),
            }
        }
        None => Sky::Constant(render::rgb::Rgb::ZERO),
    };
    let world = World::new(b.materials, (upper, upper_sky), (lower, lower_sky));
    Ok(Scene { spacetime, axis, camera, world, settings, animation: Some(animation) })
}

/// The camera tables, `[camera]` (required) and then the `[views.NAME]`, and the index of
/// `view`'s.
fn camera_tables<'a>(doc: &Doc<'a>, root: &Table<'a>, view: Option<&str>) -> Result<(Vec<Table<'a>>, usize)> {
    let main = root.get("camera").ok_or_else(|| root.missing("camera"))?.table(camera::CAMERA_KEYS)?;
    let views = root.get("views").map(|n| n.any_table()).transpose()?;
    let mut names = vec![None];
    let mut tables = vec![main];
    for (name, v) in views.iter().flat_map(|v| v.entries()) {
        names.push(Some(name));
        tables.push(v.table(&[camera::CAMERA_KEYS, &["spacetime"]].concat())?);
    }
    match names.iter().position(|n| *n == view) {
        Some(i) => Ok((tables, i)),
        None => {
            let name = view.unwrap_or_default();
            let names: Vec<String> = names.iter().flatten().map(|k| format!("\"{k}\"")).collect();
            let known =
                if names.is_empty() { "it has none".to_string() } else { format!("it has {}", names.join(", ")) };
            Err(doc.error(0, "views", format!("no view named \"{name}\" ([views.{name}]); {known}")))
        }
    }
}

impl<'a> Builder<'a> {
    /// A path from the scene file, relative to its folder, to be read under the policy.
    fn resolve(&self, file: &str) -> Resource<'a> {
        self.policy.file(self.base_dir, file)
    }

    /// `region = "upper" | "lower"` of a table (default upper); `lower` only in a wormhole.
    fn region(&self, t: &Table<'_>) -> Result<Region> {
        let Some(n) = t.get("region") else {
            return Ok(Region::Upper);
        };
        let region = [Region::Upper, Region::Lower][n.keyword("region", &["upper", "lower"])?];
        if region == Region::Lower && !self.two_regions {
            return Err(n.err("only a wormhole (spacetime type = \"ellis\" or \"wormhole\") has a lower region"));
        }
        Ok(region)
    }
}

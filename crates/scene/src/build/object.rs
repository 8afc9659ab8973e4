//! `[[objects]]`: shape, material, emission, transform and region of each object.

use super::sky::radiance;
use super::Builder;
use crate::files::load_obj;
use crate::reader::{fmt_vec, num, Kind, Loc, Node, Result, Table};
use render::emission::{BlackbodyLight, Profile, Radiance};
use render::geometry::Vec3;
use render::material::Material;
use render::rgb::Rgb;
use render::shape::{Shape, ShapeError};
use render::texture::Texture;
use render::transform::Transform;
use render::world::{Emission, Object};
use spacetime::Region;

const OBJECT_KEYS: &[&str] = &["shape", "gltf", "material", "materials", "emission", "transform", "region"];

/// What a shape's builder made: its shapes (one, or a mesh's triangles), or a shape
/// constructor's complaint, which [`shape_error`] points at the parameter it names.
type Built = std::result::Result<Vec<Shape>, ShapeError>;

/// Reads one shape type's parameters from its table and builds it, placed by the transform.
type BuildShape = fn(&Builder<'_>, &Table<'_>, &Transform) -> Result<Built>;

/// The shape types of scene files: name, keys besides `type`, and builder.
const SHAPES: &[Kind<BuildShape>] = &[
    Kind { name: "sphere", keys: &["center", "centre", "radius"], build: sphere },
    Kind { name: "plane", keys: &["point", "normal"], build: plane },
    Kind { name: "rectangle", keys: &["corner", "edge_u", "edge_v"], build: rectangle },
    Kind { name: "disk", keys: &["center", "centre", "normal", "radius", "inner_radius"], build: disk },
    Kind { name: "box", keys: &["min", "max"], build: cuboid },
    Kind { name: "cylinder", keys: &["base", "axis", "radius", "height"], build: cylinder },
    Kind { name: "mesh", keys: &["file"], build: mesh },
];

fn sphere(_: &Builder<'_>, t: &Table<'_>, placement: &Transform) -> Result<Built> {
    Ok(one(Shape::sphere(center(t)?, positive(t, "radius")?, placement)))
}

fn plane(_: &Builder<'_>, t: &Table<'_>, placement: &Transform) -> Result<Built> {
    Ok(one(Shape::plane(t.req("point", |n| n.vec3())?, t.req("normal", |n| n.direction())?, placement)))
}

fn rectangle(_: &Builder<'_>, t: &Table<'_>, placement: &Transform) -> Result<Built> {
    Ok(one(Shape::rectangle(
        t.req("corner", |n| n.vec3())?,
        t.req("edge_u", |n| n.vec3())?,
        t.req("edge_v", |n| n.vec3())?,
        placement,
    )))
}

/// A disk, or with `inner_radius` (default 0) an annulus.
fn disk(_: &Builder<'_>, t: &Table<'_>, placement: &Transform) -> Result<Built> {
    Ok(one(Shape::annulus(
        center(t)?,
        t.req("normal", |n| n.direction())?,
        t.or("inner_radius", 0.0, |n| n.f64())?,
        positive(t, "radius")?,
        placement,
    )))
}

/// `type = "box"`: `min < max` on every axis, checked here to point at `max`.
fn cuboid(_: &Builder<'_>, t: &Table<'_>, placement: &Transform) -> Result<Built> {
    let min = t.req("min", |n| n.vec3())?;
    let max = t.req("max", |n| n.vec3())?;
    if !min.cmplt(max).all() {
        return Err(t.loc("max").err(format!(
            "must be greater than min {} on every axis, got {}",
            fmt_vec(min),
            fmt_vec(max)
        )));
    }
    Ok(one(Shape::cuboid(min, max, placement)))
}

fn cylinder(_: &Builder<'_>, t: &Table<'_>, placement: &Transform) -> Result<Built> {
    Ok(one(Shape::cylinder(
        t.req("base", |n| n.vec3())?,
        t.req("axis", |n| n.direction())?,
        positive(t, "radius")?,
        positive(t, "height")?,
        placement,
    )))
}

/// `type = "mesh"`: an OBJ file's triangles; a file that cannot be read is an error at `file`.
fn mesh(b: &Builder<'_>, t: &Table<'_>, placement: &Transform) -> Result<Built> {
    let file = t.require("file")?;
    load_obj(&b.resolve(file.str()?), placement).map(Ok).map_err(|e| file.err(e.to_string()))
}

/// One shape, or its constructor's complaint.
fn one(shape: std::result::Result<Shape, ShapeError>) -> Built {
    shape.map(|s| vec![s])
}

const TRANSFORM_KEYS: &[&str] = &["translate", "rotate", "scale"];
const ROTATION_KEYS: &[&str] = &["axis", "degrees"];
const EMISSION_KEYS: &[&str] = &["radiance", "temperature", "luminance", "two_sided"];

/// A length that must be positive.
fn positive(t: &Table<'_>, key: &str) -> Result<f64> {
    let x = t.req(key, |n| n.f64())?;
    if x > 0.0 {
        Ok(x)
    } else {
        Err(t.loc(key).err(format!("must be > 0, got {}", num(x))))
    }
}

/// `center` (or its spelling `centre`), required.
fn center(t: &Table<'_>) -> Result<Vec3> {
    match t.get_alias(&["center", "centre"])? {
        Some(n) => n.vec3(),
        None => Err(t.missing("center")),
    }
}

/// `transform = { scale, rotate, translate }`: scale, then the rotations in order, then translate.
fn transform(n: &Node<'_>) -> Result<Transform> {
    let t = n.table(TRANSFORM_KEYS)?;
    let mut m = Transform::identity();
    if let Some(s) = t.get("scale") {
        let factors = if s.is_number() { Vec3::splat(s.f64()?) } else { s.vec3()? };
        m = Transform::scale(factors).map_err(|e| s.err(e.to_string()))?;
    }
    if let Some(r) = t.get("rotate") {
        let rotations = if r.is_array() { r.array()? } else { vec![r] };
        for rotation in rotations {
            if !rotation.is_table() {
                return Err(rotation.expected("a rotation { axis = [x, y, z], degrees = a }"));
            }
            let rt = rotation.table(ROTATION_KEYS)?;
            let axis = rt.req("axis", |n| n.direction())?;
            let degrees = rt.req("degrees", |n| n.f64())?;
            let step = Transform::rotate_deg(axis, degrees).map_err(|e| rotation.err(e.to_string()))?;
            m = m.then(&step);
        }
    }
    if let Some(tr) = t.get("translate") {
        m = m.then(&Transform::translate(tr.vec3()?));
    }
    let det = m.linear().determinant();
    if !(m.is_finite() && det != 0.0 && det.is_finite()) {
        return Err(n.err("the transform is not finite or not invertible (a scale too small or too large?)"));
    }
    Ok(m)
}

/// `emission = { radiance = [r, g, b], two_sided = false }`, or just the radiance; or a
/// blackbody, `emission = { temperature = 5800, luminance = 1 }` (kelvin; the luminance at rest,
/// default 1, as bright as radiance 1).
fn emission(n: &Node<'_>) -> Result<Emission> {
    if n.is_number() || n.is_array() {
        return Ok(Emission::uniform(radiance(n)?, false));
    }
    if !n.is_table() {
        return Err(n.expected(
            "a radiance [r, g, b] or a table { radiance = [r, g, b], two_sided = false } or { temperature = 5800 }",
        ));
    }
    let t = n.table(EMISSION_KEYS)?;
    let two_sided = t.or("two_sided", false, |n| n.bool())?;
    let kind = match (t.get("radiance"), t.get("temperature")) {
        (Some(_), Some(_)) => {
            return Err(t.loc("temperature").err("an emitter has a radiance or a temperature, not both"))
        }
        (Some(_), None) => {
            if t.get("luminance").is_some() {
                return Err(t.loc("luminance").err("a luminance scales a temperature's blackbody; scale the radiance"));
            }
            Radiance::Rgb(t.req("radiance", radiance)?.into())
        }
        (None, Some(_)) => {
            let temperature = t.req("temperature", |n| n.f64())?;
            let luminance = t.or("luminance", 1.0, |n| n.f64())?;
            if !(luminance >= 0.0 && luminance.is_finite()) {
                return Err(t.loc("luminance").err(format!("must be ≥ 0, got {}", num(luminance))));
            }
            if luminance > render::rgb::MAX_RADIANCE {
                return Err(t.loc("luminance").err(super::sky::too_bright(luminance)));
            }
            let light = BlackbodyLight::new(temperature, luminance).ok_or_else(|| {
                t.loc("temperature").err(format!(
                    "must be at least 100 K (cooler bodies emit no visible light), got {}",
                    num(temperature)
                ))
            })?;
            Radiance::Blackbody(light)
        }
        (None, None) => return Err(t.missing("radiance")),
    };
    Ok(Emission { radiance: kind, two_sided, profile: Profile::Uniform })
}

impl Builder<'_> {
    /// One `[[objects]]` entry: its region and its objects (one, or one per triangle of a mesh).
    pub(super) fn object(&mut self, n: &Node<'_>) -> Result<(Region, Vec<Object>)> {
        let t = n.table(OBJECT_KEYS)?;
        let region = self.region(&t)?;
        let transform_node = t.get("transform");
        let placement = match &transform_node {
            Some(n) => transform(n)?,
            None => Transform::identity(),
        };
        if let Some(file) = t.get("gltf") {
            return self.gltf_entry(&t, &file, &placement).map(|objects| (region, objects));
        }
        if let Some(n) = t.get("materials") {
            return Err(n.err("`materials` maps a glTF file's materials: it needs `gltf = \"file.glb\"`"));
        }
        let emission = t.opt("emission", emission)?;
        let material = match t.get("material") {
            Some(n) => self.material_ref(&n)?,
            None => self.default_material(),
        };
        let shape = t.require("shape")?;
        let transform_loc = transform_node.as_ref().map(Node::loc);
        let shapes = self.shapes(&shape, &placement, transform_loc)?;
        Ok((region, shapes.into_iter().map(|shape| Object { shape, material, emission: emission.clone() }).collect()))
    }

    /// An object entry with `gltf = "…"` instead of a shape.
    fn gltf_entry(&mut self, t: &Table<'_>, file: &Node<'_>, placement: &Transform) -> Result<Vec<Object>> {
        if let Some(shape) = t.get("shape") {
            return Err(shape.err("an object has a `shape` or a `gltf` file, not both"));
        }
        if let Some(e) = t.get("emission") {
            return Err(e.err("a glTF file's lights are its materials' emissive colours: `emission` is for shapes"));
        }
        self.gltf_objects(t, file, placement)
    }

    /// The material of objects that name none: diffuse grey 0.5.
    pub(super) fn default_material(&mut self) -> usize {
        *self.default_material.get_or_insert_with(|| {
            self.materials.push(Material::Diffuse { reflectance: Texture::from(Rgb::splat(0.5)) });
            self.materials.len() - 1
        })
    }

    fn shapes(&self, n: &Node<'_>, placement: &Transform, transform_loc: Option<Loc<'_>>) -> Result<Vec<Shape>> {
        let (kind, t) = n.kind("shape", SHAPES)?;
        (kind.build)(self, &t, placement)?.map_err(|e| shape_error(&t, e, transform_loc))
    }
}

/// A shape constructor's complaint, pointed at the parameter it names.
fn shape_error(t: &Table<'_>, e: ShapeError, transform_loc: Option<Loc<'_>>) -> crate::SceneError {
    let at = |key: &str| {
        if key == "centre" || key == "center" {
            let spelled = if t.get("centre").is_some() { "centre" } else { "center" };
            t.loc(spelled)
        } else {
            t.loc(key)
        }
    };
    match &e {
        ShapeError::NotFinite { parameter, .. }
        | ShapeError::NotPositive { parameter, .. }
        | ShapeError::ZeroDirection { parameter, .. } => at(parameter).err(e.to_string()),
        ShapeError::DegenerateRectangle { .. } => t.loc("edge_v").err(e.to_string()),
        ShapeError::EmptyCuboid { .. } => t.loc("max").err(e.to_string()),
        ShapeError::InvalidInnerRadius { .. } => t.loc("inner_radius").err(e.to_string()),
        ShapeError::InvalidTransform { .. } => match transform_loc {
            Some(loc) => loc.err(e.to_string()),
            None => t.err(e.to_string()),
        },
    }
}

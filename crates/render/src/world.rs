//! The runtime scene: objects (shape + material + optional emission) in each region of
//! spacetime, their bounding-volume hierarchy, the emitters for light sampling, and the sky.
//!
//! A black hole's spacetime has one region; a wormhole has two, one on each side of its throat,
//! each with its own objects, lights and sky (world coordinates of a region are its own).

use crate::accel::Bvh;
use crate::digest::Hex;
use crate::geometry::{Aabb, Ray, Vec3};
use crate::material::Material;
use crate::shape::{Shape, SurfaceHit, TriangleMesh};
use crate::sky::Sky;
use spacetime::Region;
use std::hash::Hasher;
use std::sync::Arc;

pub use crate::emission::{Emission, Profile, Radiance};

/// A corner of a triangle lies on a surface when it is within this fraction of its coordinates'
/// size of the surface's plane: rounding, far below the offset (`OFFSET_EPSILON`, 10⁻⁹ of the
/// coordinates) that starts a ray off the surface it leaves.
const ON_SURFACE: f64 = 1e-12;

/// One object of the scene.
#[derive(Clone, Debug)]
pub struct Object {
    pub shape: Shape,
    /// Index into [`World::materials`].
    pub material: usize,
    pub emission: Option<Emission>,
}

/// A region's contents.
#[derive(Clone)]
struct RegionScene {
    objects: Vec<Object>,
    /// Each object's bounds, kept because curved ray steps ask for them many times per step.
    bounds: Vec<Aabb>,
    /// Each flat object's supporting plane (a point and the unit normal), kept beside the bounds
    /// for the same reason: triangle tests ask for it as often.
    planes: Vec<Option<(Vec3, Vec3)>>,
    bvh: Bvh,
    /// Emitting objects with finite area, and the cumulative distribution of their power
    /// (radiance luminance × area) for choosing one.
    lights: Vec<usize>,
    light_cdf: Vec<f64>,
    /// The total of those powers (world areas), for choosing between regions.
    light_power: f64,
    /// The lights as one source, for [`World::irradiance_estimate`].
    light_cluster: LightCluster,
    sky: Sky,
    /// Radius of the ball about the world origin that no object reaches into.
    empty_radius: f64,
    /// A box about the world origin that no object reaches into ([`empty_box`]).
    empty_box: Option<Aabb>,
}

/// Everything but the objects and the sky is built from them, so `Debug` (the scene's identity:
/// see [`crate::digest`]) shows those two alone.
impl std::fmt::Debug for RegionScene {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("RegionScene").field("objects", &ObjectList(&self.objects)).field("sky", &self.sky).finish()
    }
}

/// Objects as the scene's identity shows them: each run of triangles of one mesh with one
/// material and emission (a mesh file's triangles) as one entry, the mesh's digest and a digest
/// of the triangles' indices, so that the text grows by a few bytes per mesh, not per triangle.
struct ObjectList<'a>(&'a [Object]);

/// A run of triangle objects of one mesh sharing `material` and `emission`.
#[derive(Debug)]
#[allow(dead_code)] // Read by `Debug` only.
struct TriangleRun<'a> {
    mesh: &'a TriangleMesh,
    count: usize,
    indices: Hex,
    material: usize,
    emission: &'a Option<Emission>,
}

impl std::fmt::Debug for ObjectList<'_> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let mut list = f.debug_list();
        let mut rest = self.0;
        while let Some(first) = rest.first() {
            let Shape::Triangle(triangle) = &first.shape else {
                list.entry(first);
                rest = &rest[1..];
                continue;
            };
            let same_run = |o: &Object| {
                matches!(&o.shape, Shape::Triangle(t) if Arc::ptr_eq(t.mesh(), triangle.mesh()))
                    && o.material == first.material
                    && o.emission == first.emission
            };
            let count = rest.iter().position(|o| !same_run(o)).unwrap_or(rest.len());
            let mut indices = std::hash::DefaultHasher::new();
            for o in &rest[..count] {
                if let Shape::Triangle(t) = &o.shape {
                    indices.write_usize(t.index());
                }
            }
            list.entry(&TriangleRun {
                mesh: triangle.mesh(),
                count,
                indices: Hex(indices.finish()),
                material: first.material,
                emission: &first.emission,
            });
            rest = &rest[count..];
        }
        list.finish()
    }
}

impl RegionScene {
    fn new(objects: Vec<Object>, sky: Sky) -> Self {
        let bounds: Vec<Aabb> = objects.iter().map(|o| o.shape.bounds()).collect();
        let planes: Vec<Option<(Vec3, Vec3)>> = objects.iter().map(|o| o.shape.supporting_plane()).collect();
        let bvh = Bvh::build(&bounds);
        let mut lights = Vec::new();
        let mut light_cdf = Vec::new();
        let mut total = 0.0;
        for (i, o) in objects.iter().enumerate() {
            let power = light_power(o);
            if o.shape.area().is_finite() && power > 0.0 {
                total += power;
                lights.push(i);
                light_cdf.push(total);
            }
        }
        for c in &mut light_cdf {
            *c /= total;
        }
        let light_cluster = LightCluster::new(lights.iter().map(|&i| (&bounds[i], light_power(&objects[i]))), total);
        let empty_radius = bounds
            .iter()
            .zip(&planes)
            .map(|(b, plane)| {
                // Both are lower bounds of the object's distance: its box's, its plane's.
                let to_plane = plane.map_or(0.0, |(point, normal)| point.dot(normal).abs());
                b.distance_to(Vec3::ZERO).max(to_plane)
            })
            .fold(f64::INFINITY, f64::min);
        let empty_box = empty_box(&bounds);
        let light_power = total;
        Self {
            objects,
            bounds,
            planes,
            bvh,
            lights,
            light_cdf,
            light_power,
            light_cluster,
            sky,
            empty_radius,
            empty_box,
        }
    }
}

/// The power an emitting object is chosen by: its radiance's luminance × world area × sides.
fn light_power(object: &Object) -> f64 {
    object.emission.as_ref().map_or(0.0, |e| e.exitance_luminance() * object.shape.area())
}

/// A region's lights seen as one isotropic source of their total power at their power-weighted
/// centre, smeared over their power-weighted spread (as a light BVH's node stands for its
/// lights, Conty Estevez & Kulla 2018).
#[derive(Clone, Copy, Debug, Default)]
struct LightCluster {
    power: f64,
    centre: Vec3,
    /// Power-weighted mean of each light's squared distance from the centre plus its own squared
    /// half-diagonal.
    spread2: f64,
}

impl LightCluster {
    /// The cluster of lights given by their bounds and powers, of total power `total`.
    fn new<'a>(lights: impl Iterator<Item = (&'a Aabb, f64)> + Clone, total: f64) -> Self {
        if total <= 0.0 {
            return Self::default();
        }
        let centre = lights.clone().fold(Vec3::ZERO, |c, (b, power)| c + b.centroid() * (power / total));
        let spread2 = lights
            .map(|(b, power)| {
                ((b.centroid() - centre).length_squared() + (0.5 * b.diagonal()).length_squared()) * power
            })
            .sum::<f64>()
            / total;
        Self { power: total, centre, spread2 }
    }

    /// `Φ / (4π (d² + s²))` at `x`: the cluster's irradiance at distance `d` from its centre,
    /// blind to occlusion and orientation, and bounded near the lights by their spread `s`; 0
    /// without lights.
    fn irradiance(&self, x: Vec3) -> f64 {
        if self.power == 0.0 {
            return 0.0;
        }
        self.power / (4.0 * std::f64::consts::PI * ((x - self.centre).length_squared() + self.spread2))
    }
}

/// A box that holds the world origin strictly inside and none of the boxes `bounds` (faces may
/// touch): where a spacetime's centre sits in a room, the room's inside. Built by cutting space,
/// nearest box first, at the face of each box in its way that lies farthest from the origin;
/// `None` where a box holds the origin.
fn empty_box(bounds: &[Aabb]) -> Option<Aabb> {
    let mut nearest_first: Vec<&Aabb> = bounds.iter().collect();
    nearest_first.sort_by(|a, b| a.distance_to(Vec3::ZERO).total_cmp(&b.distance_to(Vec3::ZERO)));
    let mut empty = Aabb { min: Vec3::NEG_INFINITY, max: Vec3::INFINITY };
    for object in nearest_first {
        if (0..3).any(|k| object.min[k] >= empty.max[k] || object.max[k] <= empty.min[k]) {
            continue;
        }
        // Its faces beyond the origin on each axis: a cut at one keeps the origin inside.
        let beyond = (0..3).filter_map(|k| match (object.min[k], object.max[k]) {
            (low, _) if low > 0.0 => Some((k, low)),
            (_, high) if high < 0.0 => Some((k, high)),
            _ => None,
        });
        let (k, at) = beyond.max_by(|a, b| a.1.abs().total_cmp(&b.1.abs()))?;
        if at > 0.0 {
            empty.max[k] = at;
        } else {
            empty.min[k] = at;
        }
    }
    Some(empty)
}

/// The flat objects in the way of a triangle (indices; a few bytes to return, where their planes
/// would be a few hundred).
#[derive(Clone, Copy, Debug)]
pub struct FlatBlockers {
    objects: [u32; FlatBlockers::CAPACITY],
    len: usize,
}

impl FlatBlockers {
    /// More than this many are not listed: a piece of ray near so many objects is split instead.
    pub const CAPACITY: usize = 8;

    pub fn iter(&self) -> impl Iterator<Item = usize> + '_ {
        self.objects[..self.len].iter().map(|&i| i as usize)
    }
}

/// What may be in the way of a triangle ([`World::triangle_blockers`]).
#[derive(Clone, Copy, Debug)]
pub enum Blockers {
    /// Nothing comes within the margin.
    Clear,
    /// Only these flat objects do.
    Flat(FlatBlockers),
    /// A curved object, or more flat ones than are listed.
    Unknown,
}

/// A light chosen for sampling, with the probability of having chosen it.
#[derive(Clone, Copy, Debug)]
pub struct LightChoice {
    pub object: usize,
    pub probability: f64,
}

/// The scene as the integrator sees it.
#[derive(Clone, Debug)]
pub struct World {
    pub materials: Vec<Material>,
    upper: RegionScene,
    lower: RegionScene,
}

impl World {
    /// A world from the objects and sky of each region. Material indices must be valid.
    pub fn new(materials: Vec<Material>, upper: (Vec<Object>, Sky), lower: (Vec<Object>, Sky)) -> Self {
        Self { materials, upper: RegionScene::new(upper.0, upper.1), lower: RegionScene::new(lower.0, lower.1) }
    }

    fn region(&self, region: Region) -> &RegionScene {
        match region {
            Region::Upper => &self.upper,
            Region::Lower => &self.lower,
        }
    }

    /// The nearest hit of the segment `ray` in `region`: the object index and the distance.
    #[inline]
    pub fn intersect(&self, region: Region, ray: &Ray) -> Option<(usize, f64)> {
        let r = self.region(region);
        r.bvh.closest_hit(ray, |i, ray| r.objects[i].shape.intersect(ray))
    }

    /// Whether anything blocks the segment `ray` in `region`.
    pub fn occluded(&self, region: Region, ray: &Ray) -> bool {
        let r = self.region(region);
        r.bvh.any_hit(ray, |i, ray| r.objects[i].shape.intersect(ray).is_some())
    }

    /// Whether any object of `region` may reach into the box `query` (conservative: bounding
    /// boxes; an unbounded surface counts when the box's corners are not all on one side of it).
    pub fn any_near(&self, region: Region, query: &Aabb) -> bool {
        let r = self.region(region);
        r.bvh.any_near(query, |i| {
            let shape = &r.objects[i].shape;
            let b = &r.bounds[i];
            if b.min.is_finite() && b.max.is_finite() {
                return (0..3).all(|k| b.min[k] <= query.max[k] && b.max[k] >= query.min[k]);
            }
            let corner = |k: usize| {
                Vec3::new(
                    if k & 1 == 0 { query.min.x } else { query.max.x },
                    if k & 2 == 0 { query.min.y } else { query.max.y },
                    if k & 4 == 0 { query.min.z } else { query.max.z },
                )
            };
            let first = shape.surface_function(corner(0)).signum();
            (1..8).any(|k| shape.surface_function(corner(k)).signum() != first)
        })
    }

    /// Whether no object of `region` comes within `margin` of the triangle `corners`, except that
    /// a corner flagged in `touching` may come as close as it likes to a surface, or lie on it,
    /// from the side the rest of the triangle keeps to: a ray known to lie inside the triangle,
    /// leaving a surface at one corner or arriving at one, is then unblocked. (A flagged corner
    /// just off a surface on the far side from the rest, like the origin of a ray that leaves its
    /// surface's offset point straight back into it, or a wall beside the one a ray leaves, does
    /// not count as touching: the ray crosses that surface.)
    ///
    /// Conservative: only flat shapes can be cleared (the triangle must keep strictly to one side
    /// of their plane); any other shape whose bounds reach the triangle's counts as in the way.
    pub fn triangle_is_clear(&self, region: Region, corners: [Vec3; 3], touching: [bool; 3], margin: f64) -> bool {
        !self.scan_triangle(region, corners, touching, margin, |_, _| true)
    }

    /// The objects of `region` that [`World::triangle_is_clear`] finds in the way of a triangle,
    /// when all of them are flat and there are at most [`FlatBlockers::CAPACITY`]: a piece of ray
    /// inside the triangle can then only meet their planes.
    pub fn triangle_blockers(&self, region: Region, corners: [Vec3; 3], touching: [bool; 3], margin: f64) -> Blockers {
        let mut flat = FlatBlockers { objects: [0; FlatBlockers::CAPACITY], len: 0 };
        let stopped = self.scan_triangle(region, corners, touching, margin, |object, flat_object| {
            let Some(slot) = flat.objects.get_mut(flat.len).filter(|_| flat_object) else { return true };
            *slot = object as u32;
            flat.len += 1;
            false
        });
        match (stopped, flat.len) {
            (true, _) => Blockers::Unknown,
            (false, 0) => Blockers::Clear,
            (false, _) => Blockers::Flat(flat),
        }
    }

    /// Calls `found(object, whether it is flat)` for each object in the way of a triangle (as
    /// [`World::triangle_is_clear`] counts them) until it returns true; whether one did.
    fn scan_triangle(
        &self,
        region: Region,
        corners: [Vec3; 3],
        touching: [bool; 3],
        margin: f64,
        mut found: impl FnMut(usize, bool) -> bool,
    ) -> bool {
        let r = self.region(region);
        let reach = Vec3::splat(margin);
        let [a, b, c] = corners;
        let query = Aabb::new(a.min(b).min(c) - reach, a.max(b).max(c) + reach);
        // How far above or below a plane each corner must lie to be clear of it: a corner on
        // the surface the ray leaves only needs to be off it by rounding.
        let gaps = std::array::from_fn::<_, 3, _>(|k| {
            if touching[k] {
                -ON_SURFACE * corners[k].abs().max_element().max(1.0)
            } else {
                margin
            }
        });
        // Each test combines its comparisons by `&` and `|`, not by short-circuits: which
        // objects a piece of ray comes near changes from one piece to the next, and a branch on
        // each comparison was mispredicted often (a tenth fewer mispredictions on the room).
        let in_the_way = |i: usize| {
            let b = &r.bounds[i];
            if (b.min.cmpgt(query.max) | b.max.cmplt(query.min)).any() {
                return false;
            }
            let Some((point, normal)) = r.planes[i] else { return true };
            let heights = corners.map(|corner| (corner - point).dot(normal));
            let above = (heights[0] > gaps[0]) & (heights[1] > gaps[1]) & (heights[2] > gaps[2]);
            let below = (-heights[0] > gaps[0]) & (-heights[1] > gaps[1]) & (-heights[2] > gaps[2]);
            !(above | below)
        };
        r.bvh.any_near(&query, |i| in_the_way(i) && found(i, r.planes[i].is_some()))
    }

    /// Radius of the ball about the world origin (where a spacetime's centre is) that no object
    /// of `region` reaches into: infinite without objects.
    pub fn empty_radius(&self, region: Region) -> f64 {
        self.region(region).empty_radius
    }

    /// A box about the world origin that no object of `region` reaches into (`None` where an
    /// object's box holds the origin): the room round a hole at the origin.
    pub fn empty_box(&self, region: Region) -> Option<Aabb> {
        self.region(region).empty_box
    }

    /// The plane a flat object lies in, as a point and the unit normal ([`Shape::supporting_plane`]).
    pub fn supporting_plane(&self, region: Region, index: usize) -> Option<(Vec3, Vec3)> {
        self.region(region).planes[index]
    }

    pub fn object(&self, region: Region, index: usize) -> &Object {
        &self.region(region).objects[index]
    }

    pub fn objects(&self, region: Region) -> &[Object] {
        &self.region(region).objects
    }

    /// The full surface record of a hit found by [`World::intersect`].
    pub fn surface(&self, region: Region, index: usize, ray: &Ray, t: f64) -> SurfaceHit {
        let object = self.object(region, index);
        let hit = object.shape.surface(ray, t);
        SurfaceHit { ns: self.materials[object.material].shading_normal(&hit), ..hit }
    }

    pub fn sky(&self, region: Region) -> &Sky {
        &self.region(region).sky
    }

    /// Bounds of the finite objects of a region (empty if it has none).
    pub fn bounds(&self, region: Region) -> Aabb {
        self.region(region).bvh.bounds()
    }

    /// Number of light-sampleable emitters in a region.
    pub fn light_count(&self, region: Region) -> usize {
        self.region(region).lights.len()
    }

    /// Total power of a region's emitters as [`World::choose_light`] weighs them (radiance
    /// luminance × world area × sides); 0 without emitters.
    pub fn light_power(&self, region: Region) -> f64 {
        self.region(region).light_power
    }

    /// A rough estimate of the irradiance a region's lights give world point `x` of it, blind to
    /// occlusion, orientation and lensing: for weighing one group of lights against another.
    pub fn irradiance_estimate(&self, region: Region, x: Vec3) -> f64 {
        self.region(region).light_cluster.irradiance(x)
    }

    /// Picks an emitter in proportion to its power.
    pub fn choose_light(&self, region: Region, u: f64) -> Option<LightChoice> {
        let r = self.region(region);
        let k = r.light_cdf.partition_point(|&c| c <= u).min(r.lights.len().checked_sub(1)?);
        let lo = if k == 0 { 0.0 } else { r.light_cdf[k - 1] };
        Some(LightChoice { object: r.lights[k], probability: r.light_cdf[k] - lo })
    }

    /// Probability that [`World::choose_light`] picks `object`.
    pub fn light_probability(&self, region: Region, object: usize) -> f64 {
        let r = self.region(region);
        match r.lights.binary_search(&object) {
            Ok(k) => r.light_cdf[k] - if k == 0 { 0.0 } else { r.light_cdf[k - 1] },
            Err(_) => 0.0,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::rgb::Rgb;
    use crate::texture::Texture;
    use crate::transform::Transform;

    fn world_with_two_lights() -> World {
        let t = Transform::identity();
        let light = |x: f64, r: f32| Object {
            shape: Shape::sphere(Vec3::new(x, 0.0, 0.0), 1.0, &t).unwrap(),
            material: 0,
            emission: Some(Emission::uniform(Rgb::splat(r), false)),
        };
        World::new(
            vec![Material::Diffuse { reflectance: Texture::from(Rgb::splat(0.5)) }],
            (vec![light(0.0, 1.0), light(5.0, 3.0)], Sky::Constant(Rgb::ZERO)),
            (Vec::new(), Sky::Constant(Rgb::ZERO)),
        )
    }

    /// A strip of `n` triangles in the plane z = `z`, as one mesh shared by `n` objects.
    fn strip(n: u32, z: f64) -> Vec<Object> {
        let positions = (0..n + 2).map(|i| Vec3::new(f64::from(i / 2), f64::from(i % 2), z)).collect();
        let indices = (0..n).map(|i| if i % 2 == 0 { [i, i + 1, i + 2] } else { [i + 1, i, i + 2] }).collect();
        let mesh = Arc::new(TriangleMesh::new(positions, None, None, indices).unwrap());
        TriangleMesh::shapes(&mesh).into_iter().map(|shape| Object { shape, material: 0, emission: None }).collect()
    }

    fn identity(objects: Vec<Object>) -> String {
        let grey = Material::Diffuse { reflectance: Texture::from(Rgb::splat(0.5)) };
        let world = World::new(vec![grey], (objects, Sky::Constant(Rgb::ZERO)), (Vec::new(), Sky::Constant(Rgb::ZERO)));
        format!("{world:?}")
    }

    /// The identity of a mesh's objects does not grow with the mesh (it once printed the whole
    /// mesh once per triangle: quadratic), and still tells meshes apart by their content.
    #[test]
    fn a_meshs_identity_does_not_grow_with_it() {
        let small = identity(strip(10, 0.0));
        let large = identity(strip(10_000, 0.0));
        // Only the counts grow, by their digits.
        assert!(large.len() <= small.len() + 16, "{} bytes for 10 triangles, {} for 10 000", small.len(), large.len());
        assert_ne!(identity(strip(10, 0.0)), identity(strip(10, 1.0)), "the vertices are part of it");
        assert_eq!(identity(strip(10, 0.0)), small, "the same content, the same identity");
        let mut part = strip(10, 0.0);
        part.remove(3);
        assert_ne!(identity(part), small, "which triangles are objects is part of it");
    }

    #[test]
    fn lights_are_chosen_by_power() {
        let w = world_with_two_lights();
        assert_eq!(w.light_count(Region::Upper), 2);
        assert!((w.light_probability(Region::Upper, 0) - 0.25).abs() < 1e-12);
        assert!((w.light_probability(Region::Upper, 1) - 0.75).abs() < 1e-12);
        // One-sided spheres of radius 1: 4π × (1 + 3).
        assert!((w.light_power(Region::Upper) - 16.0 * std::f64::consts::PI).abs() < 1e-9);
        assert_eq!(w.light_power(Region::Lower), 0.0);
        assert_eq!(w.choose_light(Region::Upper, 0.1).unwrap().object, 0);
        assert_eq!(w.choose_light(Region::Upper, 0.3).unwrap().object, 1);
        assert!(w.choose_light(Region::Lower, 0.3).is_none());
    }

    /// Far from its lights the estimate is their sum as point sources, `Σ Φᵢ / (4π dᵢ²)`; at a
    /// light it stays finite, bounded by their spread.
    #[test]
    fn irradiance_estimate_is_the_lights_far_off_and_finite_among_them() {
        let w = world_with_two_lights();
        let point_sources = |x: Vec3| {
            let (a, b) = ((x - Vec3::ZERO).length_squared(), (x - Vec3::new(5.0, 0.0, 0.0)).length_squared());
            (4.0 * std::f64::consts::PI / a + 12.0 * std::f64::consts::PI / b) / (4.0 * std::f64::consts::PI)
        };
        for x in [Vec3::new(200.0, 0.0, 0.0), Vec3::new(-150.0, 80.0, 30.0), Vec3::new(3.0, 0.0, -300.0)] {
            let (estimate, exact) = (w.irradiance_estimate(Region::Upper, x), point_sources(x));
            assert!((estimate / exact - 1.0).abs() < 2e-3, "{x:?}: {estimate} against {exact}");
        }
        let at_light = w.irradiance_estimate(Region::Upper, Vec3::new(5.0, 0.0, 0.0));
        assert!(at_light.is_finite() && at_light > 0.0 && at_light < 4.0 / 7.0);
        assert_eq!(w.irradiance_estimate(Region::Lower, Vec3::ZERO), 0.0);
    }

    #[test]
    fn segments_find_the_nearest_object() {
        let w = world_with_two_lights();
        let ray = Ray::new(Vec3::new(-5.0, 0.0, 0.0), Vec3::X, 100.0);
        let (i, t) = w.intersect(Region::Upper, &ray).unwrap();
        assert_eq!(i, 0);
        assert!((t - 4.0).abs() < 1e-9);
        assert!(w.intersect(Region::Upper, &Ray::new(Vec3::new(-5.0, 0.0, 0.0), Vec3::X, 3.0)).is_none());
    }
}

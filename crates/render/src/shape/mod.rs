//! Geometric shapes: the closed set of surfaces a scene is built from.
//!
//! Every query the integrator makes is a *segment* (a geodesic step's chord), so
//! [`Shape::intersect`] answers only "the nearest `t` in `(0, ray.t_max]`", cheaply, and the full
//! [`SurfaceHit`] record is computed once, by [`Shape::surface`], for the winning hit alone.
//!
//! Analytic shapes (sphere, disk, cuboid, cylinder) are stored in their own object space next to a
//! [`Transform`]; a ray is mapped into object space *without renormalising its direction*, so the
//! ray parameter `t` is the same in both spaces and is the world distance along the unit world ray
//! (pbrt-v4 §6.1.4). Non-uniform scale therefore just works: a scaled sphere is an ellipsoid.
//! Planar shapes (plane, rectangle, triangle) are baked into world space, since an affine map
//! keeps them planar. An [`Instance`] keeps a shared mesh in its own space with its placement,
//! like the analytic shapes, so that many placements share one copy of the triangles.
//!
//! # Conventions
//!
//! * `ng` is the unit geometric normal on the shape's *outward* side: away from the inside of a
//!   closed shape, along the stated normal of a plane, disk or rectangle, along the
//!   counter-clockwise winding of a triangle (or the side of its vertex normals, when it has them).
//!   It is never flipped toward the incoming ray: materials decide which side they are on.
//! * `ns` is the unit shading normal, in `ng`'s hemisphere; it equals `ng` except on meshes with
//!   vertex normals.
//! * `dpdu` is `∂p/∂u`, non-zero and tangent to the surface (perpendicular to `ng`); it is not
//!   unit length and, on meshes with vertex normals, not perpendicular to `ns`: orthogonalise it
//!   (Gram–Schmidt) to build a shading frame.
//! * uv coordinates are documented on each shape's type.
//!
//! # Leaving a surface
//!
//! A new segment that starts at a hit point must not find the surface it starts on again. The
//! origin is pushed off the surface along `ng`, to the side the new direction goes, by a distance
//! proportional to the point's magnitude: [`offset_origin`].
//!
//! # Light sampling
//!
//! [`Shape::sample_area`] returns a point distributed uniformly by area, so its density is
//! `1 / area()`. The infinite plane has infinite area and cannot be sampled: emissive planes are
//! not light-sampled and contribute only when a path hits them.

mod cuboid;
mod cylinder;
mod disk;
pub mod instance;
pub mod mesh;
mod plane;
mod quadratic;
mod rectangle;
mod sphere;
mod stretch;
mod triangle;

pub use cuboid::Cuboid;
pub use cylinder::Cylinder;
pub use disk::Disk;
pub use instance::{Instance, InstancedMesh};
pub use mesh::{MeshDefect, TriangleMesh};
pub use plane::Plane;
pub use rectangle::Rectangle;
pub use sphere::Sphere;
pub use triangle::Triangle;

use crate::geometry::{Aabb, Ray, Vec3};
use crate::transform::Transform;
use std::fmt;

/// Everything a material and the integrator need about the winning hit.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SurfaceHit {
    /// The hit point, on the surface.
    pub p: Vec3,
    /// Unit geometric normal, on the shape's outward side (never flipped toward the ray).
    pub ng: Vec3,
    /// Unit shading normal (interpolated on meshes), in `ng`'s hemisphere.
    pub ns: Vec3,
    /// Surface parameterisation, documented per shape.
    pub uv: [f64; 2],
    /// `∂p/∂u`: non-zero, perpendicular to `ng`, not normalised.
    pub dpdu: Vec3,
}

/// A surface of the scene. A closed set: every variant is in this file, and every operation is a
/// `match`, so the compiler checks that each shape implements each query.
///
/// Analytic shapes are boxed so that the enum stays the size of a triangle (a pointer to its mesh
/// and an index): a scene is mostly triangles.
#[derive(Clone, Debug)]
pub enum Shape {
    Sphere(Box<Sphere>),
    Plane(Box<Plane>),
    Rectangle(Box<Rectangle>),
    Disk(Box<Disk>),
    Cuboid(Box<Cuboid>),
    Cylinder(Box<Cylinder>),
    Triangle(Triangle),
    /// A placement of a mesh shared with other placements.
    Instance(Box<Instance>),
}

/// Forwards a method call to whichever shape `self` holds.
macro_rules! dispatch {
    ($self:ident, $s:ident => $e:expr) => {
        match $self {
            Shape::Sphere($s) => $e,
            Shape::Plane($s) => $e,
            Shape::Rectangle($s) => $e,
            Shape::Disk($s) => $e,
            Shape::Cuboid($s) => $e,
            Shape::Cylinder($s) => $e,
            Shape::Triangle($s) => $e,
            Shape::Instance($s) => $e,
        }
    };
}

impl Shape {
    /// A sphere of `radius` about `centre`, in the object space of `transform`.
    pub fn sphere(centre: Vec3, radius: f64, transform: &Transform) -> Result<Shape, ShapeError> {
        Sphere::new(centre, radius, transform).map(Shape::from)
    }

    /// The infinite plane through `point` with outward `normal`, in the object space of `transform`.
    pub fn plane(point: Vec3, normal: Vec3, transform: &Transform) -> Result<Shape, ShapeError> {
        Plane::new(point, normal, transform).map(Shape::from)
    }

    /// The parallelogram `corner + a·edge_u + b·edge_v`, `a, b ∈ [0, 1]`, with outward normal
    /// along `edge_u × edge_v`, in the object space of `transform`.
    pub fn rectangle(corner: Vec3, edge_u: Vec3, edge_v: Vec3, transform: &Transform) -> Result<Shape, ShapeError> {
        Rectangle::new(corner, edge_u, edge_v, transform).map(Shape::from)
    }

    /// A disk of `radius` about `centre`, facing `normal`, in the object space of `transform`.
    pub fn disk(centre: Vec3, normal: Vec3, radius: f64, transform: &Transform) -> Result<Shape, ShapeError> {
        Disk::new(centre, normal, radius, transform).map(Shape::from)
    }

    /// The disk of [`Shape::disk`] with a hole of `inner_radius` about its centre.
    pub fn annulus(
        centre: Vec3,
        normal: Vec3,
        inner_radius: f64,
        radius: f64,
        transform: &Transform,
    ) -> Result<Shape, ShapeError> {
        Disk::annulus(centre, normal, inner_radius, radius, transform).map(Shape::from)
    }

    /// The box `[min, max]`, axis-aligned in the object space of `transform`.
    pub fn cuboid(min: Vec3, max: Vec3, transform: &Transform) -> Result<Shape, ShapeError> {
        Cuboid::new(min, max, transform).map(Shape::from)
    }

    /// A capped cylinder: the base cap is centred on `base`, the axis runs along `axis` (any
    /// non-zero length) for `height`, in the object space of `transform`.
    pub fn cylinder(
        base: Vec3,
        axis: Vec3,
        radius: f64,
        height: f64,
        transform: &Transform,
    ) -> Result<Shape, ShapeError> {
        Cylinder::new(base, axis, radius, height, transform).map(Shape::from)
    }

    /// World-space bounds. Unbounded shapes (the plane) return a box with infinite sides; the
    /// BVH keeps such shapes out of its hierarchy and tests them on every query.
    pub fn bounds(&self) -> Aabb {
        dispatch!(self, s => s.bounds())
    }

    /// The nearest hit distance in `(0, ray.t_max]`, or `None`. `ray.dir` must be unit length.
    #[inline]
    pub fn intersect(&self, ray: &Ray) -> Option<f64> {
        dispatch!(self, s => s.intersect(ray))
    }

    /// The full record of the hit at distance `t` along `ray`, as returned by
    /// [`Shape::intersect`]. The point is projected onto the surface.
    pub fn surface(&self, ray: &Ray, t: f64) -> SurfaceHit {
        dispatch!(self, s => s.surface(ray, t))
    }

    /// World-space surface area; `f64::INFINITY` for the plane.
    pub fn area(&self) -> f64 {
        dispatch!(self, s => s.area())
    }

    /// A point distributed uniformly by area over the surface, and the unit outward normal there;
    /// the density is `1 / area()`. `u` is uniform in `[0, 1)²`. The plane cannot be sampled
    /// (check `area().is_finite()` first): it returns its reference point.
    pub fn sample_area(&self, u: [f64; 2]) -> (Vec3, Vec3) {
        dispatch!(self, s => s.sample_area(u))
    }

    /// A signed function of position for root finding along curved rays (the poster's Algorithm 1:
    /// look for a sign change between a step's two ends, then bisect until `|f| < ε`).
    ///
    /// Negative inside (closed shapes) or behind (open shapes, the side opposite `ng`), positive
    /// outside or in front, zero on the surface; `|f|` never exceeds the distance to the surface,
    /// and equals it for rigidly placed shapes.
    ///
    /// Open bounded shapes (rectangle, disk, triangle) return the signed distance to their
    /// supporting plane where the point projects inside the shape, and the positive distance to
    /// the shape where it projects outside, so that passing beside the shape shows no sign change.
    /// A segment that crosses the supporting plane *outside* the shape but still changes sign
    /// (one end projects inside, the other outside) makes bisection converge to the shape's rim
    /// with `|f|` bounded away from zero: callers must treat "interval exhausted, `|f| ≥ ε`" as
    /// no hit.
    pub fn surface_function(&self, p: Vec3) -> f64 {
        dispatch!(self, s => s.surface_function(p))
    }

    /// The plane an open flat shape lies in, as a point on it and its unit normal; `None` for
    /// curved shapes. Whatever lies strictly on one side of it cannot touch the shape.
    pub fn supporting_plane(&self) -> Option<(Vec3, Vec3)> {
        match self {
            Shape::Plane(s) => Some(s.supporting_plane()),
            Shape::Rectangle(s) => Some(s.supporting_plane()),
            Shape::Disk(s) => Some(s.supporting_plane()),
            Shape::Triangle(s) => s.supporting_plane(),
            Shape::Sphere(_) | Shape::Cuboid(_) | Shape::Cylinder(_) | Shape::Instance(_) => None,
        }
    }

    /// True when the shape encloses a volume (sphere, cuboid, cylinder), so that the sign of
    /// [`Shape::surface_function`] means inside/outside. Planes, rectangles, disks and single
    /// triangles are open.
    pub fn is_closed(&self) -> bool {
        matches!(self, Shape::Sphere(_) | Shape::Cuboid(_) | Shape::Cylinder(_))
    }
}

macro_rules! impl_from_boxed {
    ($($variant:ident),*) => {
        $(impl From<$variant> for Shape {
            fn from(s: $variant) -> Shape {
                Shape::$variant(Box::new(s))
            }
        })*
    };
}

impl_from_boxed!(Sphere, Plane, Rectangle, Disk, Cuboid, Cylinder, Instance);

impl From<Triangle> for Shape {
    fn from(t: Triangle) -> Shape {
        Shape::Triangle(t)
    }
}

/// Relative size of the offset [`offset_origin`] applies. Intersection distances are computed in
/// `f64` with a relative error of a few ulps (≈1e-15) of the coordinates involved; 1e-9 leaves six
/// orders of magnitude of margin, and is still far below any feature size a scene models.
pub const OFFSET_EPSILON: f64 = 1e-9;

/// The origin for a segment leaving the surface point `p` (unit geometric normal `ng`) in
/// direction `dir`: `p` pushed along `ng` to the side `dir` goes, by
/// `OFFSET_EPSILON · max(1, |p|∞)`. The scale grows with the coordinates because rounding error
/// does; the floor of 1 keeps the offset meaningful near the origin.
///
/// Reflection (`dir·ng > 0`) leaves on the outside, transmission on the inside, so the new segment
/// never starts behind the surface it leaves and cannot re-hit it at `t ≈ 0`.
#[inline]
pub fn offset_origin(p: Vec3, ng: Vec3, dir: Vec3) -> Vec3 {
    let scale = OFFSET_EPSILON * p.abs().max_element().max(1.0);
    let offset = ng * scale;
    if dir.dot(ng) >= 0.0 {
        p + offset
    } else {
        p - offset
    }
}

/// Why a shape could not be built from its parameters.
#[derive(Clone, Debug, PartialEq)]
pub enum ShapeError {
    /// A parameter is NaN or infinite.
    NotFinite { shape: &'static str, parameter: &'static str },
    /// A length that must be strictly positive is not.
    NotPositive { shape: &'static str, parameter: &'static str, value: f64 },
    /// A direction (normal, axis) has zero length.
    ZeroDirection { shape: &'static str, parameter: &'static str },
    /// The rectangle's edges are zero or parallel: it has no area.
    DegenerateRectangle { edge_u: Vec3, edge_v: Vec3 },
    /// The cuboid's `min` is not strictly below its `max` on every axis.
    EmptyCuboid { min: Vec3, max: Vec3 },
    /// The transform is not finite or not invertible.
    InvalidTransform { shape: &'static str },
    /// A disk's hole is negative or not smaller than the disk.
    InvalidInnerRadius { inner_radius: f64, radius: f64 },
}

impl fmt::Display for ShapeError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::NotFinite { shape, parameter } => {
                write!(f, "{shape}: {parameter} must be finite")
            }
            Self::NotPositive { shape, parameter, value } => {
                write!(f, "{shape}: {parameter} must be positive, got {value}")
            }
            Self::ZeroDirection { shape, parameter } => {
                write!(f, "{shape}: {parameter} must be a non-zero vector")
            }
            Self::DegenerateRectangle { edge_u, edge_v } => {
                write!(f, "rectangle: edges {edge_u} and {edge_v} are zero or parallel, so it has no area")
            }
            Self::EmptyCuboid { min, max } => {
                write!(f, "cuboid: min {min} must be strictly less than max {max} on every axis")
            }
            Self::InvalidTransform { shape } => {
                write!(f, "{shape}: transform is not finite or not invertible")
            }
            Self::InvalidInnerRadius { inner_radius, radius } => {
                write!(f, "disk: inner_radius {inner_radius} must be at least 0 and less than the radius {radius}")
            }
        }
    }
}

impl std::error::Error for ShapeError {}

/// Parameter checks shared by the constructors.
mod check {
    use super::ShapeError;
    use crate::geometry::Vec3;
    use crate::transform::Transform;

    pub fn point(shape: &'static str, parameter: &'static str, p: Vec3) -> Result<Vec3, ShapeError> {
        if p.is_finite() {
            Ok(p)
        } else {
            Err(ShapeError::NotFinite { shape, parameter })
        }
    }

    /// A finite non-zero vector, normalised.
    pub fn direction(shape: &'static str, parameter: &'static str, v: Vec3) -> Result<Vec3, ShapeError> {
        let v = point(shape, parameter, v)?;
        let unit = v.normalize_or_zero();
        if unit == Vec3::ZERO {
            Err(ShapeError::ZeroDirection { shape, parameter })
        } else {
            Ok(unit)
        }
    }

    pub fn positive(shape: &'static str, parameter: &'static str, x: f64) -> Result<f64, ShapeError> {
        if !x.is_finite() {
            Err(ShapeError::NotFinite { shape, parameter })
        } else if x > 0.0 {
            Ok(x)
        } else {
            Err(ShapeError::NotPositive { shape, parameter, value: x })
        }
    }

    pub fn transform(shape: &'static str, t: &Transform) -> Result<(), ShapeError> {
        let det = t.linear().determinant();
        if t.is_finite() && det != 0.0 && det.is_finite() {
            Ok(())
        } else {
            Err(ShapeError::InvalidTransform { shape })
        }
    }
}

/// `2π · max(ρ, ε)` times the unit azimuthal direction at angle `phi`: the `∂p/∂u` of a polar
/// parameterisation `u = φ / 2π`, clamped away from zero at the pole (`ρ = 0`) where the true
/// derivative vanishes, because [`SurfaceHit::dpdu`] must be usable as a tangent everywhere.
fn azimuthal_dpdu(phi: f64, rho: f64, scale: f64) -> Vec3 {
    let (sin, cos) = phi.sin_cos();
    Vec3::new(-sin, cos, 0.0) * (std::f64::consts::TAU * rho.max(1e-9 * scale))
}

/// The azimuth of `(x, y)` in `[0, 2π)`.
fn azimuth(x: f64, y: f64) -> f64 {
    let phi = y.atan2(x);
    if phi < 0.0 {
        phi + std::f64::consts::TAU
    } else {
        phi
    }
}

/// Shared tests: properties every shape must have, run over a zoo of placed shapes.
#[cfg(test)]
pub(crate) mod tests {
    use super::*;
    use crate::sampling::{uniform_sphere, Rng};

    /// A transform with rotation, translation and (optionally) non-uniform scale.
    pub(crate) fn placed(non_uniform: bool) -> Transform {
        let s = if non_uniform { Vec3::new(1.5, 0.7, 2.2) } else { Vec3::splat(1.3) };
        Transform::scale(s)
            .unwrap()
            .then(&Transform::rotate_deg(Vec3::new(0.3, -1.0, 0.6), 37.0).unwrap())
            .then(&Transform::translate(Vec3::new(0.4, -0.2, 1.1)))
    }

    /// Every kind of shape, each rigidly placed and (where the shape keeps its transform) also
    /// non-uniformly stretched.
    pub(crate) fn zoo() -> Vec<(String, Shape)> {
        let mut shapes = Vec::new();
        for (tag, non_uniform) in [("rigid", false), ("stretched", true)] {
            let t = placed(non_uniform);
            let mut add = |name: &str, s: Result<Shape, ShapeError>| {
                shapes.push((format!("{name}/{tag}"), s.unwrap()));
            };
            add("sphere", Shape::sphere(Vec3::new(0.1, 0.2, -0.1), 0.8, &t));
            add(
                "rectangle",
                Shape::rectangle(Vec3::new(-0.5, -0.4, 0.1), Vec3::new(1.0, 0.2, 0.0), Vec3::new(-0.1, 0.9, 0.3), &t),
            );
            add("disk", Shape::disk(Vec3::new(0.0, 0.1, 0.2), Vec3::new(0.2, 0.3, 1.0), 0.7, &t));
            add("cuboid", Shape::cuboid(Vec3::new(-0.5, -0.3, -0.2), Vec3::new(0.4, 0.6, 0.9), &t));
            add("cylinder", Shape::cylinder(Vec3::new(0.0, -0.2, -0.5), Vec3::new(0.1, 1.0, 0.2), 0.45, 1.2, &t));
            add("plane", Shape::plane(Vec3::new(0.0, 0.0, -1.0), Vec3::new(0.1, 0.2, 1.0), &t));
        }
        let mesh = TriangleMesh::new(
            vec![Vec3::new(-0.3, -0.5, 0.2), Vec3::new(0.9, -0.1, 0.4), Vec3::new(0.1, 0.8, -0.3)],
            Some(vec![Vec3::new(0.1, 0.0, 1.0), Vec3::new(-0.2, 0.1, 1.0), Vec3::new(0.0, -0.3, 1.0)]),
            Some(vec![[0.0, 0.0], [1.0, 0.0], [0.5, 1.0]]),
            vec![[0, 1, 2]],
        )
        .unwrap();
        let mesh = std::sync::Arc::new(mesh);
        shapes.extend(TriangleMesh::shapes(&mesh).into_iter().map(|s| ("triangle".to_string(), s)));
        // Rigid only: an instance samples uniformly by area under similarities (see its docs).
        let quad = std::sync::Arc::new(InstancedMesh::new(instance::tests::tilted_quad()).unwrap());
        shapes.push(("instance".to_string(), Instance::new(quad, &placed(false)).unwrap().into()));
        shapes
    }

    /// A segment aimed through a point of the shape from a random point 5 units away.
    fn ray_at(shape: &Shape, rng: &mut Rng) -> (Ray, Vec3) {
        let target = match shape {
            Shape::Plane(p) => p.point_at([rng.next_f64() * 4.0 - 2.0, rng.next_f64() * 4.0 - 2.0]),
            _ => shape.sample_area(rng.next_2d()).0,
        };
        let origin = target + uniform_sphere(rng.next_2d()) * 5.0;
        (Ray::segment(origin, target + (target - origin) * 0.5), target)
    }

    #[test]
    fn hits_land_on_the_surface_with_well_formed_records() {
        let mut rng = Rng::new(11);
        for (name, shape) in zoo() {
            let mut hits = 0;
            for _ in 0..2000 {
                let (ray, target) = ray_at(&shape, &mut rng);
                let Some(t) = shape.intersect(&ray) else {
                    continue;
                };
                hits += 1;
                // The aimed-at point is on the surface, so the nearest hit is no farther.
                assert!(t <= (target - ray.origin).length() * (1.0 + 1e-9), "{name}");
                assert!(t > 0.0 && t <= ray.t_max);
                let h = shape.surface(&ray, t);
                assert!((h.p - ray.at(t)).length() < 1e-7, "{name}: p is the hit point");
                assert!(shape.surface_function(h.p).abs() < 1e-9, "{name}: p on the surface");
                assert!((h.ng.length() - 1.0).abs() < 1e-12 && (h.ns.length() - 1.0).abs() < 1e-12, "{name}");
                assert!(h.ns.dot(h.ng) > 0.0, "{name}: ns in ng's hemisphere");
                assert!(h.dpdu.length() > 0.0, "{name}: dpdu non-zero");
                assert!(h.dpdu.normalize().dot(h.ng).abs() < 1e-7, "{name}: dpdu tangent");
                if !matches!(shape, Shape::Plane(_)) {
                    assert!(h.uv.iter().all(|x| (-1e-9..=1.0 + 1e-9).contains(x)), "{name}: {:?}", h.uv);
                }
            }
            assert!(hits > 1000, "{name}: {hits} hits of rays aimed at the shape");
        }
    }

    #[test]
    fn t_max_cuts_the_segment_off() {
        let mut rng = Rng::new(12);
        for (name, shape) in zoo() {
            for _ in 0..500 {
                let (ray, _) = ray_at(&shape, &mut rng);
                let Some(t) = shape.intersect(&ray) else {
                    continue;
                };
                let short = Ray { t_max: t * (1.0 - 1e-9), ..ray };
                // The segment ends before the first hit; any other hit would be farther.
                assert_eq!(shape.intersect(&short), None, "{name}");
                let exact = Ray { t_max: t, ..ray };
                assert_eq!(shape.intersect(&exact), Some(t), "{name}: t_max is inclusive");
            }
        }
    }

    #[test]
    fn leaving_a_surface_does_not_hit_it_again_at_once() {
        let mut rng = Rng::new(13);
        for (name, shape) in zoo() {
            for _ in 0..1000 {
                let (ray, _) = ray_at(&shape, &mut rng);
                let Some(t) = shape.intersect(&ray) else {
                    continue;
                };
                let h = shape.surface(&ray, t);
                let out = uniform_sphere(rng.next_2d());
                let next = Ray::new(offset_origin(h.p, h.ng, out), out, f64::INFINITY);
                match shape.intersect(&next) {
                    None => {}
                    // Only a closed shape can be hit again, from inside, at its far side.
                    Some(t2) => {
                        assert!(shape.is_closed() && out.dot(h.ng) < 0.0, "{name}: self-hit at {t2}");
                        assert!(t2 > 1e-6, "{name}: re-hit at {t2}");
                    }
                }
            }
        }
    }

    #[test]
    fn samples_lie_on_the_surface_with_the_surface_normal() {
        let mut rng = Rng::new(14);
        for (name, shape) in zoo() {
            if !shape.area().is_finite() {
                continue;
            }
            for _ in 0..2000 {
                let (p, n) = shape.sample_area(rng.next_2d());
                assert!(shape.surface_function(p).abs() < 1e-9, "{name}");
                assert!((n.length() - 1.0).abs() < 1e-12, "{name}");
                // Shoot at the sample from just in front of it: the hit is the sample, with normal n.
                let ray = Ray::new(p + n * 1e-4, -n, 1.0);
                let t = shape.intersect(&ray).unwrap_or_else(|| panic!("{name}: missed its own sample"));
                if (t - 1e-4).abs() < 1e-9 {
                    let h = shape.surface(&ray, t);
                    assert!((h.ng - n).length() < 1e-6, "{name}: {} vs {}", h.ng, n);
                }
            }
        }
    }

    #[test]
    fn surface_function_is_signed_and_bounded_by_the_distance() {
        let mut rng = Rng::new(15);
        for (name, shape) in zoo() {
            if !shape.area().is_finite() {
                continue;
            }
            let surface: Vec<(Vec3, Vec3)> = (0..4000).map(|_| shape.sample_area(rng.next_2d())).collect();
            let b = shape.bounds();
            for _ in 0..300 {
                let q = b.min - Vec3::splat(0.5)
                    + (b.diagonal() + Vec3::splat(1.0)) * Vec3::new(rng.next_f64(), rng.next_f64(), rng.next_f64());
                let f = shape.surface_function(q);
                let nearest = surface.iter().map(|(s, _)| (q - *s).length()).fold(f64::INFINITY, f64::min);
                assert!(f.abs() <= nearest + 1e-9, "{name}: |f| = {} > distance {}", f.abs(), nearest);
            }
            // Just in front of / behind a surface point.
            for &(p, n) in surface.iter().take(200) {
                let d = 1e-5;
                assert!(shape.surface_function(p + n * d) > 0.0, "{name}: in front");
                assert!(shape.surface_function(p - n * d) < 0.0, "{name}: behind");
            }
        }
    }

    #[test]
    fn uniform_sampling_matches_the_area_of_a_slice() {
        // The fraction of samples beyond a plane off the shape's middle (asymmetric, so that a
        // non-uniform but symmetric sampler fails), times the area, must match that part's area
        // measured independently of both `area()` and `sample_area()`: by Cauchy–Crofton.
        let mut rng = Rng::new(16);
        for (name, shape) in zoo() {
            if !shape.area().is_finite() {
                continue;
            }
            let axis = Vec3::new(0.3, 0.8, -0.5).normalize();
            // The plane leaving about 30% of the surface beyond it.
            let mut heights: Vec<f64> = (0..1000).map(|_| shape.sample_area(rng.next_2d()).0.dot(axis)).collect();
            heights.sort_by(f64::total_cmp);
            let offset = heights[700];
            let beyond = |p: Vec3| p.dot(axis) > offset;
            let n = 400_000;
            let kept = (0..n).filter(|_| beyond(shape.sample_area(rng.next_2d()).0)).count();
            let sampled = shape.area() * kept as f64 / n as f64;
            let (part, total, crossings) = crofton_area(&shape, n, &mut rng, beyond);
            // Four standard deviations of the two estimates (binomial and counting), plus a margin
            // for the quadrature behind `area()`.
            let f = kept as f64 / n as f64;
            let tolerance = 4.0 * ((1.0 - f) / kept as f64 + 1.0 / crossings[0] as f64).sqrt() + 1e-3;
            let whole = 4.0 / (crossings[1] as f64).sqrt() + 1e-3;
            assert!((total / shape.area() - 1.0).abs() < whole, "{name}: area {} vs lines {total}", shape.area());
            assert!((sampled / part - 1.0).abs() < tolerance, "{name}: sampled {sampled} vs lines {part}");
        }
    }

    /// Surface area by the Cauchy–Crofton formula: isotropic uniform random lines meeting a ball
    /// of radius R cross a surface of area A on average A / (2πR²) times (each direction ω sees
    /// ∫|n·ω| dA over the disk πR², and |n·ω| averages 1/2 over directions). Returns the area where
    /// `keep` holds, the whole area, and the two crossing counts.
    fn crofton_area(shape: &Shape, lines: usize, rng: &mut Rng, keep: impl Fn(Vec3) -> bool) -> (f64, f64, [usize; 2]) {
        let b = shape.bounds();
        let (c, radius) = (b.centroid(), 0.5 * b.diagonal().length() * 1.01);
        let (mut kept, mut all) = (0usize, 0usize);
        for _ in 0..lines {
            let w = uniform_sphere(rng.next_2d());
            let frame = crate::geometry::Frame::from_normal(w);
            let [x, y] = crate::sampling::concentric_disk(rng.next_2d());
            let start = c + (frame.s * x + frame.t * y) * radius - w * radius * 1.5;
            let end = start + w * radius * 3.0;
            let mut ray = Ray::segment(start, end);
            while let Some(t) = shape.intersect(&ray) {
                let h = shape.surface(&ray, t);
                all += 1;
                kept += usize::from(keep(h.p));
                ray = Ray::segment(offset_origin(h.p, h.ng, w), end);
            }
        }
        let scale = 2.0 * std::f64::consts::PI * radius * radius / lines as f64;
        (kept as f64 * scale, all as f64 * scale, [kept, all])
    }
}

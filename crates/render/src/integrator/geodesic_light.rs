//! Direct light along geodesics (Schwarzschild): next-event estimation that joins a shading
//! point `x` to a point `y` sampled on an emitter by the light ray between them.
//!
//! The ray is the one that sweeps the short way round the hole (azimuth `Δφ ≤ π`), found by
//! shooting in the plane of `x`, `y` and the centre (`spacetime::geodesic::connect`). Its density
//! in solid angle at `x` follows from the area density on the light through the ray bundle:
//!
//! ```text
//! p_ω = P(light) / (A · |n · t| · dΩ/dA⊥),
//! ```
//!
//! with `A` the light's world area (points are sampled uniformly in it), `n` its world normal, `t`
//! the ray's world tangent at `y` and `dΩ/dA⊥` the bundle factor (`connect`'s equation (3)). The
//! integral over the light in world coordinates is the integral over directions at `x` in the
//! static observer's frame, so no proper areas are needed. Radiance arriving at `x` is the
//! emitted radiance, seen by the static observer at `y`, times the frequency shift `(E_x/E_y)⁴`.
//!
//! Rays reaching a light the long way round (`2π − Δφ`) or after whole windings are never sampled
//! here; BSDF sampling finds them, and their MIS weight is 1 (Veach 1997, ch. 9: a strategy's
//! weight only counts where that strategy can produce the path). The connection is traced
//! against the scene like any ray, so occluders and capture by the hole are seen exactly as
//! BSDF-sampled rays see them.
//!
//! Kerr and the Ellis wormhole have no connection solver: they render with BSDF sampling alone.

use super::path::{leave, shift};
use super::stats::PathStats;
use crate::color::Rgb;
use crate::geometry::Vec3;
use crate::propagator::{Arrival, Propagator, RayEnd};
use crate::world::World;
use spacetime::geodesic::connect::Connection;
use std::f64::consts::PI;

/// A traced connection counts as reaching the sampled point when it hits the light within this
/// many chord tolerances ε of it (the chord test places hits to within ~ε of the curve).
const ARRIVAL_TOLERANCE: f64 = 64.0;

/// A sampled light point joined to the shading point, before the visibility test.
pub(super) struct Candidate {
    /// Direction the ray leaves the shading point in (its static frame).
    pub wi: Vec3,
    /// Emitted radiance towards the shading point, as the static observer at the light sees it.
    pub emitted: Rgb,
    /// Density of `wi` in solid angle at the shading point.
    pub pdf: f64,
    object: usize,
    point: Vec3,
}

/// Samples a light point for the shading point of `at` (`u_choice` picks the light, `u_point`
/// the point) and joins it by the short-way ray; `None` if there is none or it carries nothing.
pub(super) fn sample(
    world: &World,
    propagator: &Propagator,
    at: &Arrival,
    u_choice: f64,
    u_point: [f64; 2],
) -> Option<Candidate> {
    let choice = world.choose_light(at.region, u_choice)?;
    let light = world.object(at.region, choice.object);
    let emission = light.emission?;
    let (point, normal) = light.shape.sample_area(u_point);
    let connection = propagator.connect(at.hit.p, point)?;
    let normal_local = propagator.local_normal(at.region, point, normal);
    let emitted = emission.radiance_towards(normal_local, -Vec3::from_array(connection.end));
    let pdf = density(choice.probability, light.shape.area(), normal, &connection);
    if emitted == Rgb::ZERO || !(pdf > 0.0 && pdf.is_finite()) {
        return None;
    }
    Some(Candidate { wi: Vec3::from_array(connection.start), emitted, pdf, object: choice.object, point })
}

impl Candidate {
    /// Traces the connection from the shading point of `at` (local geometric normal
    /// `ng_local`) against the scene; the radiance factor `(E_x/E_y)⁴` if it reaches the sampled
    /// point unoccluded, else `None`.
    pub(super) fn arrives(
        &self,
        world: &World,
        propagator: &Propagator,
        at: &Arrival,
        ng_local: Vec3,
        stats: &mut PathStats,
    ) -> Option<f32> {
        let origin = leave(at.hit.p, at.hit.ng, ng_local, self.wi);
        stats.rays += 1;
        match propagator.trace(world, at.region, origin, self.wi) {
            RayEnd::Hit(a)
                if a.object == self.object
                    && (a.hit.p - self.point).length() <= ARRIVAL_TOLERANCE * propagator.epsilon() =>
            {
                Some(shift(a.energy))
            }
            RayEnd::Failed => {
                stats.fates.failed += 1;
                None
            }
            _ => None,
        }
    }
}

/// Density in solid angle at `from` with which [`sample`] would have produced the ray that
/// reached the emitter of `arrival`: `None` where it never would (the ray swept more than π, or
/// the emitter is not sampled), so BSDF sampling's MIS weight is then 1.
pub(super) fn emitter_pdf(world: &World, propagator: &Propagator, from: Vec3, arrival: &Arrival) -> Option<f64> {
    // By the uniqueness of the short-way ray (monotone shooting, see `connect`), a ray that swept
    // at most π is exactly the one `connect` finds for its end points.
    if !arrival.swept.is_some_and(|swept| swept <= PI) {
        return None;
    }
    let choice = world.light_probability(arrival.region, arrival.object);
    if choice == 0.0 {
        return None;
    }
    let connection = propagator.connect(from, arrival.hit.p)?;
    let area = world.object(arrival.region, arrival.object).shape.area();
    Some(density(choice, area, arrival.hit.ng, &connection)).filter(|p| *p > 0.0 && p.is_finite())
}

/// `p_ω = P(light) / (A |n · t| dΩ/dA⊥)`.
fn density(choice: f64, area: f64, normal: Vec3, connection: &Connection) -> f64 {
    let cos = normal.dot(Vec3::from_array(connection.end_tangent)).abs();
    choice / (area * cos * connection.solid_angle_per_area)
}

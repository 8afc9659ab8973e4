//! Photons leaving the area lights of both regions, with the power they carry.
//!
//! A photon starts at a point chosen uniformly by world area on an emitter, itself chosen by
//! power (first the region, then the light by the [`World`]'s CDF), and leaves in a
//! cosine-distributed direction about the emitter's normal in the static observer's local frame.
//! Its power is the emitted flux over the density of that choice (pbrt-v3 §16.2.4):
//! `Φ = Le cos θ / (p_light · p_A · p_ω) = Le · π · A · s / p_light`, where the area density is
//! per proper area: `p_A = 1 / (A · s)` with `s` the proper area per world area at the point.

use super::super::path::leave;
use crate::color::Rgb;
use crate::geometry::{Frame, Vec3};
use crate::propagator::Propagator;
use crate::sampling::{cosine_hemisphere, Rng};
use crate::world::World;
use spacetime::Region;
use std::f64::consts::PI;

/// A photon about to be traced.
#[derive(Clone, Copy, Debug)]
pub(super) struct Photon {
    pub region: Region,
    /// World position, just off the emitter.
    pub origin: Vec3,
    /// Direction of travel in the local static frame.
    pub direction: Vec3,
    /// Power measured by the static observer at `origin`.
    pub power: Rgb,
}

/// Samples a photon from the lights; `None` when the scene has no emitter of finite area.
pub(super) fn emit(world: &World, propagator: &Propagator, rng: &mut Rng) -> Option<Photon> {
    let (upper, lower) = (world.light_power(Region::Upper), world.light_power(Region::Lower));
    let total = upper + lower;
    if !(total > 0.0) {
        return None;
    }
    let u_region = rng.next_f64() * total;
    let (region, p_region) =
        if u_region < upper { (Region::Upper, upper / total) } else { (Region::Lower, lower / total) };
    let choice = world.choose_light(region, rng.next_f64())?;
    let light = world.object(region, choice.object);
    let emission = light.emission?;
    let (point, normal) = light.shape.sample_area(rng.next_2d());
    let (u_side, u_dir) = (rng.next_f64(), rng.next_2d());
    let local_normal = propagator.local_normal(region, point, normal);
    // A two-sided emitter picks a side with probability ½, doubling the photon's power.
    let (side, sides) = match (emission.two_sided, u_side < 0.5) {
        (false, _) => (1.0, 1.0),
        (true, front) => (if front { 1.0 } else { -1.0 }, 2.0),
    };
    let direction = Frame::from_normal(side * local_normal).to_world(cosine_hemisphere(u_dir));
    let area = light.shape.area() * propagator.area_scale(point, normal);
    let scale = PI * area * sides / (p_region * choice.probability);
    Some(Photon {
        region,
        origin: leave(point, normal, local_normal, direction),
        direction,
        power: emission.radiance * scale as f32,
    })
}

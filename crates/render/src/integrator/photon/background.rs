//! Light that photons do not carry — skies whose receivers no disk of beams covers (see
//! [`sky`]), and emitters of infinite area (only finite ones can be sampled for photons) —
//! gathered at a visible point by continuing the camera path as a brute-force path tracer that
//! counts only that light. Transport is linear in its sources, so this and the photons together
//! are the whole image.
//!
//! [`sky`]: super::sky

use super::super::path::{leave, shift};
use super::super::stats::PathStats;
use crate::emission::{Emission, Seen, Shift};
use crate::geometry::{Frame, Vec3};
use crate::material::Bsdf;
use crate::propagator::{Propagator, RayEnd};
use crate::rgb::Rgb;
use crate::sampling::Sampler;
use crate::sky::Sky;
use crate::world::World;
use spacetime::Region;

/// Paths start surviving Russian roulette unconditionally for this many bounces (as path.rs).
const ROULETTE_START: u32 = 2;

/// A scattering vertex of a camera path.
#[derive(Clone, Copy, Debug)]
pub(super) struct Vertex {
    pub region: Region,
    pub p: Vec3,
    /// World and local geometric normals.
    pub ng: Vec3,
    pub ng_local: Vec3,
    pub frame: Frame,
    pub wo: Vec3,
    pub bsdf: Bsdf,
    /// Camera throughput to here.
    pub beta: Rgb,
    /// Surface interactions so far, this one included.
    pub depth: u32,
    /// `ν_camera / ν_local` here.
    pub frequency: f64,
}

/// The light background paths gather: the skies of the regions (upper, lower) marked here, and
/// emitters of infinite area.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) struct Background {
    skies: [bool; 2],
}

impl Background {
    /// What is left for background paths in `world` when photons carry the skies of the regions
    /// `carried` says; `None` when nothing is.
    pub fn new(world: &World, carried: impl Fn(Region) -> bool) -> Option<Self> {
        let infinite_emitter =
            |region: Region| world.objects(region).iter().any(|o| o.emission.is_some() && !o.shape.area().is_finite());
        let regions = [Region::Upper, Region::Lower];
        let black = |sky: &Sky| matches!(sky, Sky::Constant(c) if *c == Rgb::ZERO);
        let skies = regions.map(|region| !carried(region) && !black(world.sky(region)));
        (skies.contains(&true) || regions.into_iter().any(infinite_emitter)).then_some(Self { skies })
    }

    fn sky(&self, region: Region) -> bool {
        self.skies[super::slot(region)]
    }
}

/// The radiance `emission` sends a camera path towards `dir`, divided by the brightness `g⁴`
/// of the path's frequency ratio `frequency` to the camera (its throughput holds that): light of
/// one colour as it is at rest, a blackbody in the colour of `g T`.
pub(super) fn emitted(emission: &Emission, ng: Vec3, dir: Vec3, rest: &Seen<'_>, frequency: f64) -> Rgb {
    match emission.blackbody(ng, dir, rest) {
        Some(blackbody) => blackbody.seen(frequency) / frequency.powi(4) as f32,
        None => emission.seen::<Rgb>(ng, dir, rest, &()),
    }
}

/// One path sample of that light scattered at `vertex` towards the camera.
pub(super) fn radiance(
    background: Background,
    world: &World,
    propagator: &Propagator,
    max_depth: u32,
    vertex: Vertex,
    sampler: &mut Sampler,
    stats: &mut PathStats,
) -> Rgb {
    let Vertex {
        mut region,
        mut p,
        mut ng,
        mut ng_local,
        mut frame,
        mut wo,
        mut bsdf,
        mut beta,
        mut depth,
        mut frequency,
    } = vertex;
    let mut radiance = Rgb::ZERO;
    while depth <= max_depth {
        let Some(sample) = bsdf.sample(wo, sampler.next_f64(), sampler.next_2d()) else { return radiance };
        beta *= sample.weight;
        let rr_beta = f64::from(beta.max_element()) * sample.eta * sample.eta;
        if beta == Rgb::ZERO || !beta.is_finite() {
            return radiance;
        }
        if depth >= ROULETTE_START && rr_beta < 1.0 {
            if sampler.next_f64() >= rr_beta {
                return radiance;
            }
            beta /= rr_beta as f32;
        }
        let direction = frame.to_world(sample.wi);
        stats.rays += 1;
        let arrival = match propagator.trace(world, region, leave(p, ng, ng_local, direction), direction) {
            RayEnd::Hit(a) => a,
            RayEnd::Escaped { region, direction, energy, .. } if background.sky(region) => {
                // At the whole ratio to the camera, its brightness divided out as `beta` holds it.
                let g = frequency / energy;
                let sky = world.sky(region).seen::<Rgb>(direction, (g, g), &()) / frequency.powi(4) as f32;
                return radiance + beta * sky;
            }
            RayEnd::Escaped { .. } => return radiance,
            RayEnd::Captured | RayEnd::Failed => return radiance,
        };
        beta *= shift(arrival.energy);
        frequency /= arrival.energy;
        let object = world.object(arrival.region, arrival.object);
        let hit = &arrival.hit;
        ng_local = arrival.ng_local;
        if let Some(emission) = object.emission.as_ref().filter(|_| !object.shape.area().is_finite()) {
            let rest = Seen { region: arrival.region, point: hit.p, shift: Shift::NONE, propagator };
            radiance += beta * emitted(emission, ng_local, -arrival.direction, &rest, frequency);
        }
        (region, p, ng, depth) = (arrival.region, hit.p, hit.ng, depth + 1);
        bsdf = world.materials[object.material].bsdf(hit.uv, hit.p);
        frame = Frame::from_normal(propagator.local_normal(region, hit.p, hit.ns));
        wo = frame.to_local(-arrival.direction);
    }
    radiance
}

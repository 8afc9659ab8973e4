//! Unidirectional path tracing with Russian roulette (Kajiya 1986; pbrt-v4 §13.4).
//!
//! Every segment is a null geodesic found by the [`Propagator`], and every vertex works in the
//! local orthonormal frame of the observer at the hit. A path carries, besides its throughput,
//! the frequency ratio `g = ν_camera / ν_local` between the camera and the local observer at its
//! vertex: the product of the camera's Doppler factor and the shifts between the observers at the
//! ends of its segments (gravitational red- and blueshift). Emitters are asked for their light
//! as seen at that ratio ([`Emission::seen`](crate::emission::Emission::seen)): a blackbody
//! changes colour, an RGB colour brightens as `g⁴` (`I_ν/ν³` is invariant).
//!
//! Direct light is also sampled on the emitters and combined with BSDF sampling by multiple
//! importance sampling (Veach 1997, power heuristic), by whichever strategy joins light points to
//! shading points in the scene's spacetime ([`super::light`]).

use super::light::{Bounce, LightSampling, Lit, Shading};
use super::stats::PathStats;
use crate::color::Rgb;
use crate::emission::{Seen, Shift, Shown};
use crate::geometry::{Frame, Vec3};
use crate::propagator::{Arrival, Propagator, RayEnd};
use crate::sampling::Sampler;
use crate::shape::offset_origin;
use crate::world::World;
use spacetime::Region;

/// Paths start surviving Russian roulette unconditionally for this many bounces.
const ROULETTE_START: u32 = 2;

pub struct PathIntegrator<'a> {
    world: &'a World,
    propagator: &'a Propagator,
    max_depth: u32,
    light_sampling: LightSampling,
    /// The frequency shifts light is shown with (the teaching toggles).
    shown: Shown,
}

impl<'a> PathIntegrator<'a> {
    /// `brute_force` disables light sampling everywhere (the unbiased reference).
    pub fn new(world: &'a World, propagator: &'a Propagator, max_depth: u32, brute_force: bool, shown: Shown) -> Self {
        let light_sampling = LightSampling::new(propagator, brute_force);
        Self { world, propagator, max_depth, light_sampling, shown }
    }

    /// Radiance arriving at `origin` (in `region`) from the local-frame direction `direction`
    /// (the direction the backward ray leaves in), seen by a camera that measures frequencies
    /// `doppler` times the local observer's there.
    pub fn radiance(
        &self,
        (region, origin, direction): (Region, Vec3, Vec3),
        doppler: f64,
        sampler: &mut Sampler,
        stats: &mut PathStats,
    ) -> Rgb {
        let mut radiance = Rgb::ZERO;
        let mut beta = Rgb::ONE;
        // Product of η² over refractions: undoes the radiance scaling for the roulette decision,
        // so a path through clear glass is never killed for having entered it (pbrt-v4 §13.4.4).
        let mut eta_scale = 1.0f64;
        let mut shift = Shift::at_camera(doppler, self.shown);
        let (mut region, mut origin, mut direction) = (region, origin, direction);
        let mut bounce = Bounce { pdf: 0.0, specular: true, from: origin, direction };
        let mut depth = 0;
        loop {
            stats.rays += 1;
            let end = self.propagator.trace(self.world, region, origin, direction);
            let arrival = match segment_end(self.world, end, shift, stats) {
                SegmentEnd::Surface(a) => a,
                SegmentEnd::Sky(sky) => return radiance + beta * sky,
            };
            shift = shift.after(arrival.energy);
            let object = self.world.object(arrival.region, arrival.object);
            let hit = &arrival.hit;
            let ng = arrival.ng_local;
            if let Some(emission) = &object.emission {
                let seen = Seen { region: arrival.region, point: hit.p, shift, propagator: self.propagator };
                let le = emission.seen(ng, -arrival.direction, &seen);
                if le != Rgb::ZERO {
                    let weight = self.light_sampling.emitter_weight(self.lit(), &arrival, ng, &bounce);
                    radiance += beta * le * weight as f32;
                }
            }
            if depth == self.max_depth {
                stats.fates.absorbed += 1;
                return radiance;
            }
            depth += 1;
            let bsdf = self.world.materials[object.material].bsdf(hit.uv, hit.p);
            // Flat shapes shade with their geometric normal, already taken to the local frame.
            let ns = if hit.ns == hit.ng { ng } else { self.propagator.local_normal(arrival.region, hit.p, hit.ns) };
            let frame = Frame::from_normal(ns);
            let wo = frame.to_local(-arrival.direction);
            if !bsdf.is_delta() {
                let shading = Shading { bsdf: &bsdf, frame: &frame, wo, ng, shift };
                radiance += beta * self.light_sampling.direct(self.lit(), &arrival, &shading, sampler, stats);
            }
            let Some(sample) = bsdf.sample(wo, sampler.next_f64(), sampler.next_2d()) else {
                stats.fates.absorbed += 1;
                return radiance;
            };
            beta *= sample.weight;
            if beta == Rgb::ZERO || !beta.is_finite() {
                stats.fates.absorbed += 1;
                return radiance;
            }
            eta_scale *= sample.eta * sample.eta;
            // What the path can still bring the camera scales with g⁴ as well (the brightness
            // of light seen at ratio g), so paths into redshifted depths are cut as before.
            let rr_beta = f64::from(beta.max_element()) * eta_scale * shift.ratio().powi(4);
            if depth >= ROULETTE_START && rr_beta < 1.0 {
                // Survive with probability equal to the throughput: paths that still carry
                // everything are never cut.
                if sampler.next_f64() >= rr_beta {
                    stats.fates.absorbed += 1;
                    return radiance;
                }
                beta /= rr_beta as f32;
            }
            direction = frame.to_world(sample.wi);
            bounce = Bounce { pdf: sample.pdf, specular: sample.is_delta, from: hit.p, direction };
            origin = leave(hit.p, hit.ng, ng, direction);
            region = arrival.region;
        }
    }

    /// The scene light samples are taken in.
    fn lit(&self) -> Lit<'a> {
        Lit { world: self.world, propagator: self.propagator }
    }
}

/// Where a camera path's segment ended: at a surface to shade, or nowhere more, seeing the sky
/// radiance `Sky` (already frequency-shifted; zero when captured or failed).
pub(super) enum SegmentEnd {
    Surface(Arrival),
    Sky(Rgb),
}

/// Sorts a traced segment's end, counting the fate of a path that ends there; the sky is seen
/// with the path's frequency ratio `shift` at the segment's start.
pub(super) fn segment_end(world: &World, end: RayEnd, shift: Shift, stats: &mut PathStats) -> SegmentEnd {
    match end {
        RayEnd::Hit(arrival) => SegmentEnd::Surface(arrival),
        RayEnd::Escaped { region, direction, traversed, energy } => {
            if traversed {
                stats.fates.traversed += 1;
            } else {
                stats.fates.escaped += 1;
            }
            SegmentEnd::Sky(shift.after(energy).brightness_factor() * world.sky(region).radiance(direction))
        }
        RayEnd::Captured => {
            stats.fates.captured += 1;
            SegmentEnd::Sky(Rgb::ZERO)
        }
        RayEnd::Failed => {
            stats.fates.failed += 1;
            SegmentEnd::Sky(Rgb::ZERO)
        }
    }
}

/// Radiance factor of a segment whose far end measures the photon at `energy` (relative to the
/// near end): `(ν_near / ν_far)⁴`.
pub(super) fn shift(energy: f64) -> f32 {
    if energy == 1.0 {
        1.0
    } else {
        energy.powi(-4) as f32
    }
}

/// Start of the next segment from a hit at `p`: off the surface on the side `direction` goes.
/// The side is decided in the local frame (normal covector `ng_local` against the local
/// direction), the offset taken along the world normal `ng`.
pub(super) fn leave(p: Vec3, ng: Vec3, ng_local: Vec3, direction: Vec3) -> Vec3 {
    let side = if direction.dot(ng_local) >= 0.0 { ng } else { -ng };
    offset_origin(p, ng, side)
}

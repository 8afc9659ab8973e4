//! Unidirectional path tracing with Russian roulette (Kajiya 1986; pbrt-v4 §13.4).
//!
//! Every segment is a null geodesic found by the [`Propagator`], and every vertex works in the
//! local orthonormal frame of the observer at the hit. Along a segment, radiance scales with the
//! fourth power of the frequency shift between the observers at its ends (`I_ν/ν³` is invariant;
//! integrated over frequency, `I ∝ ν⁴`), which accounts for gravitational red- and blueshift.
//!
//! Direct light is also sampled on the emitters and combined with BSDF sampling by multiple
//! importance sampling (Veach 1997, power heuristic). In flat space the shadow ray is straight;
//! in Schwarzschild spacetime it is the geodesic found by shooting ([`super::geodesic_light`]).
//! Kerr and the Ellis wormhole have no connection solver yet: there lights are found by BSDF
//! sampling alone.

use super::geodesic_light;
use super::stats::PathStats;
use crate::color::Rgb;
use crate::geometry::{Frame, Ray, Vec3};
use crate::material::Bsdf;
use crate::propagator::{Arrival, Propagator, RayEnd};
use crate::sampling::{power_heuristic, Sampler};
use crate::shape::offset_origin;
use crate::world::World;
use spacetime::geodesic::connect::{short_way_arrives_behind, Way, Waypoints};
use spacetime::Region;

/// Paths start surviving Russian roulette unconditionally for this many bounces.
const ROULETTE_START: u32 = 2;

pub struct PathIntegrator<'a> {
    world: &'a World,
    propagator: &'a Propagator,
    max_depth: u32,
    light_sampling: LightSampling,
}

/// How direct light is sampled at a vertex, besides BSDF sampling.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum LightSampling {
    /// Not at all: brute force, or a spacetime without a connection solver (Kerr, Ellis).
    None,
    /// Straight shadow rays (flat space).
    Straight,
    /// Geodesic connections each way round the hole (Schwarzschild).
    Geodesic,
}

/// Where the previous bounce left from, for the MIS weight of an emitter hit by BSDF sampling.
#[derive(Clone, Copy)]
struct Bounce {
    pdf: f64,
    specular: bool,
    /// The surface point it left (before the offset that starts the next ray).
    from: Vec3,
}

impl<'a> PathIntegrator<'a> {
    /// `brute_force` disables light sampling everywhere (the unbiased reference).
    pub fn new(world: &'a World, propagator: &'a Propagator, max_depth: u32, brute_force: bool) -> Self {
        let light_sampling = if brute_force {
            LightSampling::None
        } else if propagator.is_flat() {
            LightSampling::Straight
        } else if propagator.connects() {
            LightSampling::Geodesic
        } else {
            LightSampling::None
        };
        Self { world, propagator, max_depth, light_sampling }
    }

    /// Radiance arriving at `origin` (in `region`) from the local-frame direction `direction`
    /// (the direction the backward ray leaves in).
    pub fn radiance(
        &self,
        region: Region,
        origin: Vec3,
        direction: Vec3,
        sampler: &mut Sampler,
        stats: &mut PathStats,
    ) -> Rgb {
        let mut radiance = Rgb::ZERO;
        let mut beta = Rgb::ONE;
        // Product of η² over refractions: undoes the radiance scaling for the roulette decision,
        // so a path through clear glass is never killed for having entered it (pbrt-v4 §13.4.4).
        let mut eta_scale = 1.0f64;
        let (mut region, mut origin, mut direction) = (region, origin, direction);
        let mut bounce = Bounce { pdf: 0.0, specular: true, from: origin };
        let mut depth = 0;
        loop {
            stats.rays += 1;
            let arrival =
                match segment_end(self.world, self.propagator.trace(self.world, region, origin, direction), stats) {
                    SegmentEnd::Surface(a) => a,
                    SegmentEnd::Sky(sky) => return radiance + beta * sky,
                };
            beta *= shift(arrival.energy);
            let object = self.world.object(arrival.region, arrival.object);
            let hit = &arrival.hit;
            let ng = arrival.ng_local;
            if let Some(emission) = object.emission {
                let le = emission.radiance_towards(ng, -arrival.direction);
                if le != Rgb::ZERO {
                    radiance += beta * le * self.emitter_weight(&arrival, ng, bounce) as f32;
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
                let shading = Shading { bsdf: &bsdf, frame: &frame, wo, ng };
                radiance += beta * self.direct_light(&arrival, &shading, sampler, stats);
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
            let rr_beta = f64::from(beta.max_element()) * eta_scale;
            if depth >= ROULETTE_START && rr_beta < 1.0 {
                // Survive with probability equal to the throughput: paths that still carry
                // everything are never cut.
                if sampler.next_f64() >= rr_beta {
                    stats.fates.absorbed += 1;
                    return radiance;
                }
                beta /= rr_beta as f32;
            }
            bounce = Bounce { pdf: sample.pdf, specular: sample.is_delta, from: hit.p };
            direction = frame.to_world(sample.wi);
            origin = leave(hit.p, hit.ng, ng, direction);
            region = arrival.region;
        }
    }

    /// MIS weight of an emitter reached by BSDF sampling, against having sampled it directly.
    fn emitter_weight(&self, arrival: &Arrival, ng: Vec3, bounce: Bounce) -> f64 {
        if bounce.specular {
            return 1.0;
        }
        match self.light_sampling {
            LightSampling::None => 1.0,
            LightSampling::Straight => self.straight_emitter_weight(arrival, ng, bounce),
            LightSampling::Geodesic => geodesic_light::emitter_pdf(self.world, self.propagator, bounce.from, arrival)
                .map_or(1.0, |light_pdf| power_heuristic(bounce.pdf, light_pdf)),
        }
    }

    /// [`Self::emitter_weight`] in flat space.
    fn straight_emitter_weight(&self, arrival: &Arrival, ng: Vec3, bounce: Bounce) -> f64 {
        let shape = &self.world.object(arrival.region, arrival.object).shape;
        let cos = ng.dot(arrival.direction).abs();
        let choice = self.world.light_probability(arrival.region, arrival.object);
        if choice == 0.0 || cos == 0.0 {
            return 1.0;
        }
        let light_pdf = choice * arrival.distance * arrival.distance / (cos * shape.area());
        power_heuristic(bounce.pdf, light_pdf)
    }

    /// One light sample, MIS-weighted, joined by the spacetime's kind of shadow ray.
    fn direct_light(&self, at: &Arrival, shading: &Shading<'_>, sampler: &mut Sampler, stats: &mut PathStats) -> Rgb {
        match self.light_sampling {
            LightSampling::None => Rgb::ZERO,
            LightSampling::Straight => self.straight_light(at, shading, sampler, stats),
            LightSampling::Geodesic => self.geodesic_light(at, shading, sampler, stats),
        }
    }

    /// One light point joined by its geodesics, the short way round the hole and, at random, the
    /// long way (Schwarzschild).
    fn geodesic_light(&self, at: &Arrival, shading: &Shading<'_>, sampler: &mut Sampler, stats: &mut PathStats) -> Rgb {
        let (u_choice, u_point, u_way) = (sampler.next_f64(), sampler.next_2d(), sampler.next_f64());
        let Some(point) = geodesic_light::sample_point(self.world, at, u_choice, u_point) else {
            return Rgb::ZERO;
        };
        let (mut sum, mut waypoints) = (Rgb::ZERO, Waypoints::default());
        for way in Way::BOTH {
            let probability = geodesic_light::way_probability(way, at.hit.p, point.position());
            if u_way >= probability || (way == Way::Short && reflects_none(at, shading, &point)) {
                continue;
            }
            if let Some(light) = point.join(self.propagator, at, (way, probability), &mut waypoints) {
                sum += self.connected_light(at, shading, &light, stats);
            }
        }
        sum
    }

    /// A joined light point's MIS-weighted contribution, if it is seen.
    fn connected_light(
        &self,
        at: &Arrival,
        shading: &Shading<'_>,
        light: &geodesic_light::Candidate,
        stats: &mut PathStats,
    ) -> Rgb {
        let wi_local = shading.frame.to_local(light.wi);
        let f = shading.bsdf.f(shading.wo, wi_local) * wi_local.z.abs() as f32;
        if f == Rgb::ZERO {
            return Rgb::ZERO;
        }
        let Some(shift) = light.arrives(self.world, self.propagator, at, shading.ng, stats) else {
            return Rgb::ZERO;
        };
        let weight = power_heuristic(light.pdf, shading.bsdf.pdf(shading.wo, wi_local));
        f * light.emitted * shift * (weight / light.pdf) as f32
    }

    /// One light sample with a straight shadow ray (flat space).
    fn straight_light(&self, at: &Arrival, shading: &Shading<'_>, sampler: &mut Sampler, stats: &mut PathStats) -> Rgb {
        let Shading { bsdf, frame, wo, .. } = *shading;
        let (u_choice, u_point) = (sampler.next_f64(), sampler.next_2d());
        let Some(choice) = self.world.choose_light(at.region, u_choice) else { return Rgb::ZERO };
        let light = self.world.object(at.region, choice.object);
        let (point, normal) = light.shape.sample_area(u_point);
        let to_light = point - at.hit.p;
        let dist2 = to_light.length_squared();
        let wi = to_light / dist2.sqrt();
        let Some(emission) = light.emission else { return Rgb::ZERO };
        let le = emission.radiance_towards(normal, -wi);
        let cos_light = normal.dot(wi).abs();
        let wi_local = frame.to_local(wi);
        let f = bsdf.f(wo, wi_local) * wi_local.z.abs() as f32;
        if le == Rgb::ZERO || cos_light == 0.0 || f == Rgb::ZERO {
            return Rgb::ZERO;
        }
        let origin = offset_origin(at.hit.p, at.hit.ng, wi);
        let to_point = point - origin;
        let length = to_point.length();
        stats.rays += 1;
        // Stop just short of the light so the light itself does not count as a blocker.
        if self.world.occluded(at.region, &Ray::new(origin, to_point / length, length * (1.0 - 1e-6))) {
            return Rgb::ZERO;
        }
        let light_pdf = choice.probability * dist2 / (cos_light * light.shape.area());
        let weight = power_heuristic(light_pdf, bsdf.pdf(wo, wi_local));
        f * le * (weight / light_pdf) as f32
    }
}

/// Whether an opaque surface reflects none of the light coming the short way from `point`: when
/// its front (the side `wo` is on) faces the centre and the point lies on or behind its tangent
/// plane, the short way leaves it into the back ([`short_way_arrives_behind`], reversed). Such
/// points are not joined at all (the surface behind a one-sided light is the other case, dropped
/// by the connection solver).
fn reflects_none(at: &Arrival, shading: &Shading<'_>, point: &geodesic_light::LightPoint) -> bool {
    let front = if shading.wo.z >= 0.0 { at.hit.ns } else { -at.hit.ns };
    !shading.bsdf.has_transmission()
        && short_way_arrives_behind(front.to_array(), point.position().to_array(), at.hit.p.to_array())
}

/// What direct lighting needs of a shading point.
#[derive(Clone, Copy)]
struct Shading<'b> {
    bsdf: &'b Bsdf,
    frame: &'b Frame,
    wo: Vec3,
    /// Geometric normal in the local frame.
    ng: Vec3,
}

/// Radiance factor of a segment whose far end measures the photon at `energy` (relative to the
/// near end): `(ν_near / ν_far)⁴`.
/// Where a camera path's segment ended: at a surface to shade, or nowhere more, seeing the sky
/// radiance `Sky` (already frequency-shifted; zero when captured or failed).
pub(super) enum SegmentEnd {
    Surface(Arrival),
    Sky(Rgb),
}

/// Sorts a traced segment's end, counting the fate of a path that ends there.
pub(super) fn segment_end(world: &World, end: RayEnd, stats: &mut PathStats) -> SegmentEnd {
    match end {
        RayEnd::Hit(arrival) => SegmentEnd::Surface(arrival),
        RayEnd::Escaped { region, direction, traversed, energy } => {
            if traversed {
                stats.fates.traversed += 1;
            } else {
                stats.fates.escaped += 1;
            }
            SegmentEnd::Sky(shift(energy) * world.sky(region).radiance(direction))
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

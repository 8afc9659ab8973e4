//! Unidirectional path tracing with Russian roulette (Kajiya 1986; pbrt-v4 §13.4).
//!
//! Every segment is a null geodesic found by the [`Propagator`], and every vertex works in the
//! local orthonormal frame of the observer at the hit. A path carries, besides its throughput,
//! the frequency ratio `g = ν_camera / ν_local` between the camera and the local observer at its
//! vertex: the product of the camera's Doppler factor and the shifts between the observers at the
//! ends of its segments (gravitational red- and blueshift). Emitters are asked for their light
//! as seen at that ratio ([`Emission::seen`](crate::emission::Emission::seen)): a blackbody
//! changes colour, an RGB colour brightens as `g⁴` (`I_ν/ν³` is invariant) and, in spectral
//! rendering, changes colour too.
//!
//! The throughput and radiance are RGB triples or, in spectral rendering, values at the path's
//! sampled wavelengths ([`Colour`]): one transport written for both, the wavelengths drawn from
//! the sampler at the path's start and converted to RGB at its end.
//!
//! Direct light is also sampled on the emitters and combined with BSDF sampling by multiple
//! importance sampling (Veach 1997, power heuristic), by whichever strategy joins light points to
//! shading points in the scene's spacetime ([`super::light`]).

use super::light::{Bounce, LightSampling, Lit, Shading};
use super::stats::PathStats;
use crate::emission::{Seen, Shift, Shown};
use crate::geometry::{Frame, Vec3};
use crate::propagator::{Arrival, Propagator, RayEnd};
use crate::rgb::Rgb;
use crate::sampling::Sampler;
use crate::settings::{IntegratorKind, RenderSettings};
use crate::shape::offset_origin;
use crate::spectrum::{Colour, SampledSpectrum, SampledWavelengths};
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
    /// Paths carry sampled wavelengths rather than RGB.
    spectral: bool,
}

impl<'a> PathIntegrator<'a> {
    /// The integrator `settings` ask for; brute force disables light sampling everywhere (the
    /// unbiased reference).
    pub fn new(world: &'a World, propagator: &'a Propagator, settings: &RenderSettings) -> Self {
        let light_sampling = LightSampling::new(propagator, settings.integrator == IntegratorKind::BruteForce);
        Self {
            world,
            propagator,
            max_depth: settings.max_depth,
            light_sampling,
            shown: settings.shown,
            spectral: settings.spectral,
        }
    }

    /// Radiance arriving at `origin` (in `region`) from the local-frame direction `direction`
    /// (the direction the backward ray leaves in), seen by a camera that measures frequencies
    /// `doppler` times the local observer's there. A spectral path draws its wavelengths from
    /// the sampler's next number.
    pub fn radiance(
        &self,
        start: (Region, Vec3, Vec3),
        doppler: f64,
        sampler: &mut Sampler,
        stats: &mut PathStats,
    ) -> Rgb {
        if self.spectral {
            let mut lambda = SampledWavelengths::sample_visible(sampler.next_f64() as f32);
            let radiance: SampledSpectrum = self.transport(start, doppler, &mut lambda, sampler, stats);
            radiance.to_rgb(&lambda)
        } else {
            self.transport::<Rgb>(start, doppler, &mut (), sampler, stats)
        }
    }

    /// [`PathIntegrator::radiance`] in the colours `C` at `lambda` (which a dispersing glass may
    /// narrow to the hero wavelength).
    fn transport<C: Colour>(
        &self,
        (region, origin, direction): (Region, Vec3, Vec3),
        doppler: f64,
        lambda: &mut C::Lambda,
        sampler: &mut Sampler,
        stats: &mut PathStats,
    ) -> C {
        let mut radiance = C::ZERO;
        let mut beta = C::ONE;
        // Product of η² over refractions: undoes the radiance scaling for the roulette decision,
        // so a path through clear glass is never killed for having entered it (pbrt-v4 §13.4.4).
        let mut eta_scale = 1.0f64;
        let mut shift = Shift::at_camera(doppler, self.shown);
        let (mut region, mut origin, mut direction) = (region, origin, direction);
        let mut bounce = Bounce { pdf: 0.0, specular: true, from: origin, region, direction };
        let mut depth = 0;
        loop {
            stats.rays += 1;
            let end = self.propagator.trace(self.world, region, origin, direction);
            let arrival = match segment_end::<C>(self.world, end, shift, lambda, stats) {
                SegmentEnd::Surface(a) => a,
                SegmentEnd::Sky(sky) => return radiance + beta * sky,
            };
            shift = shift.after(arrival.energy);
            let object = self.world.object(arrival.region, arrival.object);
            let hit = &arrival.hit;
            let ng = arrival.ng_local;
            if let Some(emission) = &object.emission {
                let seen = Seen { region: arrival.region, point: hit.p, shift, propagator: self.propagator };
                let le: C = emission.seen(ng, -arrival.direction, &seen, lambda);
                if le != C::ZERO {
                    let weight = self.light_sampling.emitter_weight(self.lit(), &arrival, ng, &bounce);
                    radiance += beta * le * weight as f32;
                }
            }
            if depth == self.max_depth {
                stats.fates.absorbed += 1;
                return radiance;
            }
            depth += 1;
            let bsdf = self.world.materials[object.material].resolve::<C>(hit.uv, hit.p, lambda);
            // Flat shapes shade with their geometric normal, already taken to the local frame.
            let ns = if hit.ns == hit.ng { ng } else { self.propagator.local_normal(arrival.region, hit.p, hit.ns) };
            let frame = Frame::from_normal(ns);
            let wo = frame.to_local(-arrival.direction);
            if !bsdf.is_delta() {
                let shading = Shading { bsdf: &bsdf, frame: &frame, wo, ng, shift, lambda: *lambda };
                radiance += beta * self.light_sampling.direct(self.lit(), &arrival, &shading, sampler, stats);
            }
            let Some(sample) = bsdf.sample(wo, sampler.next_f64(), sampler.next_2d()) else {
                stats.fates.absorbed += 1;
                return radiance;
            };
            beta *= sample.weight;
            if beta == C::ZERO || !beta.is_finite() {
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
                beta = beta / rr_beta as f32;
            }
            direction = frame.to_world(sample.wi);
            bounce =
                Bounce { pdf: sample.pdf, specular: sample.is_delta, from: hit.p, region: arrival.region, direction };
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
// Returned once per segment and matched at once: boxing the arrival would allocate in the path
// loop for nothing.
#[allow(clippy::large_enum_variant)]
pub(super) enum SegmentEnd<C: Colour> {
    Surface(Arrival),
    Sky(C),
}

/// Sorts a traced segment's end, counting the fate of a path that ends there; the sky is seen
/// with the path's frequency ratio `shift` at the segment's start, in the colours `C` at `lambda`.
pub(super) fn segment_end<C: Colour>(
    world: &World,
    end: RayEnd,
    shift: Shift,
    lambda: &C::Lambda,
    stats: &mut PathStats,
) -> SegmentEnd<C> {
    match end {
        RayEnd::Hit(arrival) => SegmentEnd::Surface(arrival),
        RayEnd::Escaped { region, direction, traversed, energy } => {
            if traversed {
                stats.fates.traversed += 1;
            } else {
                stats.fates.escaped += 1;
            }
            SegmentEnd::Sky(world.sky(region).seen(direction, shift.after(energy).shown(1.0), lambda))
        }
        RayEnd::Captured => {
            stats.fates.captured += 1;
            SegmentEnd::Sky(C::ZERO)
        }
        RayEnd::Failed => {
            stats.fates.failed += 1;
            SegmentEnd::Sky(C::ZERO)
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

//! The camera pass of stochastic progressive photon mapping (Hachisuka & Jensen 2009; pbrt-v3
//! §16.2.2): a camera path follows perfect specular bounces along geodesics, adding the emitted
//! and sky radiance it meets, and stops at the first surface that scatters diffusely or
//! glossily: its *visible point*, where photons are gathered afterwards. Light that photons do
//! not carry is added there by the path continued from it (see [`background`]).
//!
//! [`background`]: super::background

use super::super::path::{leave, segment_end, shift, SegmentEnd};
use super::super::stats::PathStats;
use super::background::{self, Background, Vertex};
use crate::emission::{Seen, Shift, Shown};
use crate::geometry::{Frame, Vec3};
use crate::material::Bsdf;
use crate::propagator::Propagator;
use crate::rgb::Rgb;
use crate::sampling::Sampler;
use crate::world::World;
use spacetime::Region;

/// Where a camera path meets its first non-specular surface.
#[derive(Clone, Copy, Debug)]
pub(super) struct VisiblePoint {
    pub region: Region,
    /// World position.
    pub p: Vec3,
    /// Shading frame in the static observer's local frame.
    pub frame: Frame,
    /// Direction towards the camera, in `frame`.
    pub wo: Vec3,
    pub bsdf: Bsdf,
    /// Camera throughput to here (filter weight and frequency shifts included), divided by the
    /// proper area per world area at the point, so that photons gathered over a disk of world
    /// radius `r` are divided by the disk's proper area.
    pub beta: Rgb,
    /// Surface interactions used up, this one included: photons that scattered `j` times may
    /// be gathered here only while `depth + j ≤ max_depth`, as the path tracer's depth limit.
    pub depth: u32,
    /// `ν_camera / ν_local`: the frequency ratio light from here is seen with.
    pub frequency: f64,
}

/// What one camera path found.
#[derive(Clone, Copy, Debug)]
pub(super) struct CameraSample {
    /// Emitted and sky radiance met before the visible point, the visible point's own emission
    /// towards the camera, and the background light scattered there.
    pub emitted: Rgb,
    pub visible: Option<VisiblePoint>,
}

/// Traces camera paths to their visible points.
pub(super) struct CameraPass<'a> {
    pub world: &'a World,
    pub propagator: &'a Propagator,
    pub max_depth: u32,
    /// Light that photons do not carry, if any (see [`background`]).
    pub background: Option<Background>,
}

impl CameraPass<'_> {
    /// The camera path leaving `origin` of `region` along the local-frame `direction`, with
    /// starting throughput `beta`, seen by a camera that measures frequencies `doppler` times
    /// the local observer's there.
    pub fn trace(
        &self,
        (region, origin, direction): (Region, Vec3, Vec3),
        beta: Rgb,
        doppler: f64,
        sampler: &mut Sampler,
        stats: &mut PathStats,
    ) -> CameraSample {
        let (mut region, mut origin, mut direction, mut beta) = (region, origin, direction, beta);
        let mut frequency = doppler;
        let mut emitted = Rgb::ZERO;
        let mut depth = 0;
        loop {
            stats.rays += 1;
            // The sky is seen at the whole ratio to the camera (a star field's blackbodies in the
            // colour of g T), its brightness g⁴ divided out as `beta` holds it.
            let so_far = Shift { gravity: frequency, motion: 1.0, shown: Shown::default() };
            let arrival = match segment_end::<Rgb>(
                self.world,
                self.propagator.trace(self.world, region, origin, direction),
                so_far,
                &(),
                stats,
            ) {
                SegmentEnd::Surface(a) => a,
                SegmentEnd::Sky(sky) => {
                    let sky = sky / frequency.powi(4) as f32;
                    return CameraSample { emitted: emitted + beta * sky, visible: None };
                }
            };
            beta *= shift(arrival.energy);
            frequency /= arrival.energy;
            let object = self.world.object(arrival.region, arrival.object);
            let hit = &arrival.hit;
            let ng = arrival.ng_local;
            if let Some(emission) = &object.emission {
                let rest =
                    Seen { region: arrival.region, point: hit.p, shift: Shift::NONE, propagator: self.propagator };
                emitted += beta * background::emitted(emission, ng, -arrival.direction, &rest, frequency);
            }
            // Camera paths end at a visible point or at the depth limit: either way at a surface.
            if depth == self.max_depth {
                stats.fates.absorbed += 1;
                return CameraSample { emitted, visible: None };
            }
            let bsdf = self.world.materials[object.material].bsdf(hit.uv, hit.p);
            let frame = Frame::from_normal(self.propagator.local_normal(arrival.region, hit.p, hit.ns));
            let wo = frame.to_local(-arrival.direction);
            if !bsdf.is_delta() {
                stats.fates.absorbed += 1;
                let vertex = Vertex {
                    region: arrival.region,
                    p: hit.p,
                    ng: hit.ng,
                    ng_local: ng,
                    frame,
                    wo,
                    bsdf,
                    beta,
                    depth: depth + 1,
                    frequency,
                };
                if let Some(light) = self.background {
                    let (world, propagator) = (self.world, self.propagator);
                    emitted += background::radiance(light, world, propagator, self.max_depth, vertex, sampler, stats);
                }
                return CameraSample { emitted, visible: Some(self.visible_point(&vertex)) };
            }
            let Some(sample) = bsdf.sample(wo, sampler.next_f64(), sampler.next_2d()) else {
                stats.fates.absorbed += 1;
                return CameraSample { emitted, visible: None };
            };
            beta *= sample.weight;
            direction = frame.to_world(sample.wi);
            origin = leave(hit.p, hit.ng, ng, direction);
            region = arrival.region;
            depth += 1;
        }
    }

    /// The visible point at a scattering vertex.
    fn visible_point(&self, v: &Vertex) -> VisiblePoint {
        let area = self.propagator.area_scale(v.region, v.p, v.ng);
        VisiblePoint {
            region: v.region,
            p: v.p,
            frame: v.frame,
            wo: v.wo,
            bsdf: v.bsdf,
            beta: v.beta / area as f32,
            depth: v.depth,
            frequency: v.frequency,
        }
    }
}

//! The photon pass: photons follow geodesics forwards from the lights, scatter by the BSDFs in
//! the local static frames, and are gathered by the visible points whose spheres they land in.
//!
//! Photons are traced forwards in time ([`Propagator::trace_forward`]): in static spacetimes
//! along the spatial curve the propagator traces backwards, about a spinning hole through its
//! spin-reversed twin. Between two local observers a photon's power scales by
//! `(ν_receiver / ν_emitter)²`: the radiance law `I/ν⁴` invariant, with the invariance of
//! `ν² dA cos θ dω` (étendue in curved spacetime), gives `dΦ_r = (ν_r/ν_e)² dΦ_e` whatever the
//! observers (for static ones: one factor for each photon's energy, one for their arrival rate).
//! This is the law the path tracer applies, so both estimate the same image.

use super::super::path::leave;
use super::super::stats::PathStats;
use super::emit::Photon;
use super::grid::Grid;
use super::visible::VisiblePoint;
use crate::emission::EmittedBlackbody;
use crate::geometry::{Frame, Vec3};
use crate::propagator::{Propagator, RayEnd};
use crate::rgb::Rgb;
use crate::sampling::Rng;
use crate::world::World;
use spacetime::Region;

/// One photon gathered by one visible point: the pixel and the flux it adds (camera throughput
/// × BSDF × photon power).
#[derive(Clone, Copy, Debug)]
pub(super) struct Deposit {
    pub pixel: u32,
    pub flux: Rgb,
}

/// What a photon brings to a visible point.
#[derive(Clone, Copy, Debug)]
struct Light {
    power: Rgb,
    blackbody: Option<EmittedBlackbody>,
    /// `ν_here / ν_emitted`.
    frequency: f64,
}

impl Light {
    /// The photon's power in the colour the camera sees it in through `vp`. A blackbody's light
    /// is coloured at the whole ratio `g = ν_camera / ν_emitted` (the blackbody at `g T`); its
    /// brightness `g⁴` is divided out, being already in the photon's power and the camera
    /// path's throughput, as for light of one colour.
    fn seen_by(&self, vp: &VisiblePoint) -> Rgb {
        match self.blackbody {
            None => self.power,
            Some(blackbody) => {
                let g = vp.frequency * self.frequency;
                self.power * blackbody.seen(g) / g.powi(4) as f32
            }
        }
    }
}

/// The visible points of an iteration, with their gather radii and a grid per region.
pub(super) struct PhotonPass<'a> {
    pub world: &'a World,
    pub propagator: &'a Propagator,
    pub max_depth: u32,
    /// Per pixel.
    pub visible: &'a [Option<VisiblePoint>],
    pub radii: &'a [f64],
    pub upper: Grid,
    pub lower: Grid,
}

impl PhotonPass<'_> {
    /// Traces one photon, appending what the visible points gather from it to `deposits`.
    pub fn trace(&self, photon: Photon, rng: &mut Rng, stats: &mut PathStats, deposits: &mut Vec<Deposit>) {
        let Photon { mut region, mut origin, mut direction, mut power, blackbody, mut frequency } = photon;
        // `bounce` counts the scatterings before the current segment.
        for bounce in 0..self.max_depth {
            stats.rays += 1;
            let RayEnd::Hit(arrival) = self.propagator.trace_forward(self.world, region, origin, direction) else {
                return;
            };
            // Forward transport: `energy` is ν at the hit over ν at the start.
            power *= (arrival.energy * arrival.energy) as f32;
            frequency *= arrival.energy;
            let hit = &arrival.hit;
            let object = self.world.object(arrival.region, arrival.object);
            let bsdf = self.world.materials[object.material].bsdf(hit.uv, hit.p);
            let towards_source = -arrival.direction;
            if !bsdf.is_delta() {
                let light = Light { power, blackbody, frequency };
                self.gather(arrival.region, hit.p, towards_source, light, bounce, deposits);
            }
            if bounce + 1 == self.max_depth {
                return;
            }
            let ng = arrival.ng_local;
            let frame = Frame::from_normal(self.propagator.local_normal(arrival.region, hit.p, hit.ns));
            let Some(sample) = bsdf.sample(frame.to_local(towards_source), rng.next_f64(), rng.next_2d()) else {
                return;
            };
            // Photons carry importance's adjoint, power: refraction does not compress it by
            // 1/η² as it does radiance (Veach 1997 §5.2), so that factor is undone.
            let weight = sample.weight * (sample.eta * sample.eta) as f32;
            // Russian roulette on the scattering weight keeps photon powers about constant
            // (pbrt-v3 §16.2.4).
            let survive = f64::from(weight.max_element()).min(1.0);
            if !(survive > 0.0) || rng.next_f64() >= survive {
                return;
            }
            power *= weight / survive as f32;
            direction = frame.to_world(sample.wi);
            origin = leave(hit.p, hit.ng, ng, direction);
            region = arrival.region;
        }
    }

    /// Hands a photon at `p` arriving from the local direction `wi` to every visible point of
    /// `region` whose sphere holds it and whose path has depth left for it.
    fn gather(&self, region: Region, p: Vec3, wi: Vec3, light: Light, bounce: u32, deposits: &mut Vec<Deposit>) {
        let grid = match region {
            Region::Upper => &self.upper,
            Region::Lower => &self.lower,
        };
        for &pixel in grid.candidates(p) {
            let Some(vp) = &self.visible[pixel as usize] else { continue };
            let r = self.radii[pixel as usize];
            if vp.depth + bounce > self.max_depth || (vp.p - p).length_squared() >= r * r {
                continue;
            }
            // f(wo, wi) of the visible point's BSDF: photons on the far side of a thin wall or
            // facing away give zero, but still count towards the radius reduction.
            let f = vp.bsdf.f(vp.wo, vp.frame.to_local(wi));
            deposits.push(Deposit { pixel, flux: vp.beta * f * light.seen_by(vp) });
        }
    }
}

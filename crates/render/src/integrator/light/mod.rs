//! Direct light at a path vertex: the seam between the path integrator and the ways a light
//! point is joined to a shading point, as pbrt-v4's `SampleLd` or Mitsuba's
//! `sample_emitter_direction` / `pdf_emitter_direction`. The integrator asks for one
//! MIS-weighted light sample ([`LightSampling::direct`]) and, when BSDF sampling hits an
//! emitter, for the weight of that hit against the light strategy
//! ([`LightSampling::emitter_weight`]); how the light is joined is the strategy's own:
//!
//! - [`straight`]: straight shadow rays (flat space);
//! - [`ways`]: the spacetime's own connector, each way round a Schwarzschild hole;
//! - [`aimed`]: rays aimed by Newton's method with their bundle density, in any other curved
//!   spacetime (in the ray's plane around wormholes and charged holes, in 4-D around Kerr).
//!
//! Each strategy's density is a deterministic function of the shading point and the light
//! point, so MIS weights of BSDF-sampled hits can be evaluated exactly (Veach 1997, ch. 9); a
//! path a strategy never produces has light weight 0 and BSDF weight 1.

mod aimed;
mod point;
mod straight;
mod ways;

use super::stats::PathStats;
use crate::geometry::{Frame, Vec3};
use crate::material::Bsdf;
use crate::propagator::{Arrival, Propagator};
use crate::sampling::{power_heuristic, Sampler};
use crate::spectrum::Colour;
use crate::world::World;

/// How direct light is sampled at a vertex, besides BSDF sampling.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum LightSampling {
    /// Not at all: brute force, or the poster's intersection mode in curved space (whose
    /// rays no connector would reproduce).
    None,
    /// Straight shadow rays (flat space).
    Straight,
    /// The spacetime's own connector (Schwarzschild), each way round the hole.
    Ways,
    /// Rays aimed at light points (every other curved spacetime).
    Aimed,
}

/// The scene a light sample is taken in.
#[derive(Clone, Copy)]
pub(super) struct Lit<'a> {
    pub world: &'a World,
    pub propagator: &'a Propagator,
}

/// What direct lighting needs of a shading point, in the colours `C` its path carries.
#[derive(Clone, Copy)]
pub(super) struct Shading<'b, C: Colour> {
    pub bsdf: &'b Bsdf<C>,
    pub frame: &'b Frame,
    pub wo: Vec3,
    /// Geometric normal in the local frame.
    pub ng: Vec3,
    /// The path's frequency ratio `ν_camera / ν_local` here.
    pub shift: crate::emission::Shift,
    /// What the path's colours are sampled at.
    pub lambda: C::Lambda,
}

/// Where the previous bounce left from, for the MIS weight of an emitter hit by BSDF sampling.
#[derive(Clone, Copy)]
pub(super) struct Bounce {
    pub pdf: f64,
    pub specular: bool,
    /// The surface point it left (before the offset that starts the next ray), and its region.
    pub from: Vec3,
    pub region: spacetime::Region,
    /// The direction it left in, in the local frame there.
    pub direction: Vec3,
}

impl LightSampling {
    /// The strategy for `propagator`'s spacetime; `brute_force` samples no light at all.
    pub(super) fn new(propagator: &Propagator, brute_force: bool) -> Self {
        if brute_force {
            LightSampling::None
        } else if propagator.is_flat() {
            LightSampling::Straight
        } else if propagator.connects() {
            LightSampling::Ways
        } else if propagator.aims() {
            LightSampling::Aimed
        } else {
            LightSampling::None
        }
    }

    /// One light sample at `at`, MIS-weighted against BSDF sampling.
    pub(super) fn direct<C: Colour>(
        self,
        lit: Lit<'_>,
        at: &Arrival,
        shading: &Shading<'_, C>,
        sampler: &mut Sampler,
        stats: &mut PathStats,
    ) -> C {
        match self {
            LightSampling::None => C::ZERO,
            LightSampling::Straight => straight::direct(lit, at, shading, sampler, stats),
            LightSampling::Ways => ways::direct(lit, at, shading, sampler, stats),
            LightSampling::Aimed => aimed::direct(lit, at, shading, sampler, stats),
        }
    }

    /// MIS weight of an emitter reached by BSDF sampling (`arrival`, local geometric normal
    /// `ng`) after `bounce`, against having sampled it directly.
    pub(super) fn emitter_weight(self, lit: Lit<'_>, arrival: &Arrival, ng: Vec3, bounce: &Bounce) -> f64 {
        if bounce.specular {
            return 1.0;
        }
        let light_pdf = match self {
            LightSampling::None => None,
            LightSampling::Straight => straight::emitter_pdf(lit, arrival, ng),
            LightSampling::Ways => ways::emitter_pdf(lit, bounce.from, arrival),
            LightSampling::Aimed => aimed::emitter_pdf(lit, bounce, arrival),
        };
        light_pdf.map_or(1.0, |light_pdf| power_heuristic(bounce.pdf, light_pdf))
    }
}

/// The MIS-weighted contribution of light arriving from local-frame direction `wi` (sampled
/// with solid-angle density `pdf`), if `visible` finds it unblocked and returns the photon's
/// energy at the light relative to the shading point's (`E_light / E_here`, as
/// [`Arrival::energy`]); `emitted` gives the light's radiance seen with the path's frequency
/// ratio at the light. The BSDF is evaluated first, so blocked-or-not is only asked where it
/// reflects anything.
pub(super) fn contribution<C: Colour>(
    shading: &Shading<'_, C>,
    wi: Vec3,
    pdf: f64,
    visible: impl FnOnce() -> Option<f64>,
    emitted: impl FnOnce(crate::emission::Shift) -> C,
) -> C {
    let wi_local = shading.frame.to_local(wi);
    let f = shading.bsdf.f(shading.wo, wi_local) * wi_local.z.abs() as f32;
    if f == C::ZERO || !(pdf > 0.0 && pdf.is_finite()) {
        return C::ZERO;
    }
    let Some(energy) = visible() else { return C::ZERO };
    let le = emitted(shading.shift.after(energy));
    if le == C::ZERO {
        return C::ZERO;
    }
    let weight = power_heuristic(pdf, shading.bsdf.pdf(shading.wo, wi_local));
    f * le * (weight / pdf) as f32
}

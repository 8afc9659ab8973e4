//! Which way photons leave their lights: a mixture of the emitted cosine distribution and a
//! uniform cone towards the bounding sphere of what can receive light in the light's region (its
//! objects that do not emit, and a wormhole's throat, through which light reaches the other
//! region). A far light — a sun — otherwise sends nearly all its photons past everything.
//!
//! The photon's power divides by the mixture's density (Veach 1997 §9.2, the one-sample
//! model), so the choice is unbiased: the cosine lobe still covers every emitted direction. The
//! cone is aimed with world vectors used as local-frame directions; in curved space that aims a
//! little off, which costs efficiency only, since the density of what was sampled is exact.

use crate::geometry::{Frame, Vec3};
use crate::sampling::{cosine_hemisphere, uniform_cone};
use crate::world::World;
use spacetime::{Region, Spacetime};
use std::f64::consts::{FRAC_1_PI, PI};

/// Probability of sampling the cone where there is one.
const CONE: f64 = 0.5;

/// A sphere that bounds the receivers of a region.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) struct Target {
    pub centre: Vec3,
    pub radius: f64,
}

/// The targets of the upper and the lower region: `None` where the receivers are unbounded
/// (an infinite plane) or there are none.
pub(super) fn targets(world: &World, spacetime: &Spacetime) -> [Option<Target>; 2] {
    let throat = spacetime.capabilities().throat();
    [Region::Upper, Region::Lower].map(|region| {
        let receivers = world.objects(region).iter().filter(|o| o.emission.is_none()).map(|o| o.shape.bounds());
        let throat = throat.map(|b| crate::geometry::Aabb::new(Vec3::splat(-b), Vec3::splat(b)));
        let bounds = receivers.chain(throat).reduce(|a, b| a.union(&b))?;
        let radius = 0.5 * bounds.diagonal().length();
        (radius.is_finite() && radius > 0.0).then(|| Target { centre: bounds.centroid(), radius })
    })
}

/// A direction of emission in the local frame, with its density per solid angle.
#[derive(Clone, Copy, Debug)]
pub(super) struct Aimed {
    pub direction: Vec3,
    pub pdf: f64,
}

/// The cone from `from` around the target, as (axis, cos θ_max); `None` from inside it.
fn cone(from: Vec3, target: Option<Target>) -> Option<(Vec3, f64)> {
    let t = target?;
    let to = t.centre - from;
    let d = to.length();
    (d > t.radius).then(|| (to / d, (1.0 - (t.radius / d).powi(2)).max(0.0).sqrt()))
}

/// Samples a direction from an emitter at world point `from` with local unit normal `normal`
/// (emitting on both sides if `two_sided`), using the numbers `u_lobe`, `u_side` and `u`.
pub(super) fn sample(
    from: Vec3,
    normal: Vec3,
    two_sided: bool,
    target: Option<Target>,
    (u_lobe, u_side, u): (f64, f64, [f64; 2]),
) -> Aimed {
    let cone = cone(from, target);
    let direction = match cone {
        Some((axis, cos_max)) if u_lobe < CONE => Frame::from_normal(axis).to_world(uniform_cone(1.0 - cos_max, u)),
        _ => {
            let side = if two_sided && u_side < 0.5 { -normal } else { normal };
            Frame::from_normal(side).to_world(cosine_hemisphere(u))
        }
    };
    Aimed { direction, pdf: pdf(direction, normal, two_sided, cone) }
}

/// The mixture's density of `w`.
fn pdf(w: Vec3, normal: Vec3, two_sided: bool, cone: Option<(Vec3, f64)>) -> f64 {
    let cos = w.dot(normal);
    let cosine = match two_sided {
        true => 0.5 * cos.abs() * FRAC_1_PI,
        false => cos.max(0.0) * FRAC_1_PI,
    };
    match cone {
        Some((axis, cos_max)) => {
            let in_cone = if w.dot(axis) >= cos_max { 1.0 / (2.0 * PI * (1.0 - cos_max)) } else { 0.0 };
            CONE * in_cone + (1.0 - CONE) * cosine
        }
        None => cosine,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::sampling::Rng;

    /// Monte Carlo estimates of ∫ dω and ∫ |cos| dω over the emitting directions.
    fn integrals(normal: Vec3, two_sided: bool, target: Option<Target>) -> (f64, f64) {
        let mut rng = Rng::new(5);
        let n = 400_000;
        let (mut solid, mut projected) = (0.0, 0.0);
        for _ in 0..n {
            let a = sample(Vec3::ZERO, normal, two_sided, target, (rng.next_f64(), rng.next_f64(), rng.next_2d()));
            let cos = a.direction.dot(normal);
            if two_sided || cos > 0.0 {
                solid += 1.0 / a.pdf;
                projected += cos.abs() / a.pdf;
            }
        }
        (solid / f64::from(n), projected / f64::from(n))
    }

    #[test]
    fn the_mixture_density_matches_its_samples() {
        let normal = Vec3::new(0.3, 0.9, -0.2).normalize();
        let centre = Vec3::new(4.0, 1.0, 1.0);
        let target = Some(Target { centre, radius: 1.5 });
        // ∫ dω = 2π per side and ∫ |cos| dω = π per side, whatever the sampling.
        for (two_sided, sides) in [(false, 1.0), (true, 2.0)] {
            for t in [None, target] {
                let (solid, projected) = integrals(normal, two_sided, t);
                assert!((solid / (2.0 * PI * sides) - 1.0).abs() < 0.01, "{two_sided} {t:?}: ∫dω = {solid}");
                assert!((projected / (PI * sides) - 1.0).abs() < 0.01, "{two_sided} {t:?}: ∫cos = {projected}");
            }
        }
        // Half the samples go into the cone towards the target.
        let mut rng = Rng::new(6);
        let hits = (0..10_000)
            .filter(|_| {
                let a = sample(Vec3::ZERO, normal, false, target, (rng.next_f64(), rng.next_f64(), rng.next_2d()));
                let miss = centre - a.direction * centre.dot(a.direction);
                a.direction.dot(centre) > 0.0 && miss.length() < 1.5
            })
            .count();
        assert!(hits > 5000, "{hits} of 10000 aimed at the target");
    }
}

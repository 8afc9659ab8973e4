//! Light emitted by surfaces: how much leaves each way ([`Profile`]), and what it is
//! ([`Radiance`]): an RGB colour, a blackbody, or an accretion disk's gas.
//!
//! Emitted light is asked for as a receiver sees it ([`Emission::seen`]): at the frequency ratio
//! `g = ν_seen / ν_local` between the receiver and the local observer at the emitter (gravity
//! and the receiver's motion; the path tracer multiplies the ratios along a path). Radiance
//! transforms with `I_ν/ν³` invariant: a blackbody at `T` is seen as the blackbody at `gT`,
//! colour and brightness; an RGB colour is lifted to a spectrum and shifted in spectral
//! rendering, and in RGB rendering only brightened, by `g⁴` (frequency-integrated radiance):
//! see [`crate::spectrum::Colour`].

mod accretion_disk;
mod blackbody;
mod shift;

pub use accretion_disk::DiskLight;
pub use blackbody::BlackbodyLight;
pub use shift::{Shift, Shown};

use crate::geometry::Vec3;
use crate::rgb::{luminance, Rgb};
use crate::spectrum::{Colour, LiftedIlluminant};
use spacetime::Region;
use std::sync::Arc;

/// Light emitted by a surface: radiance on its outward side (both sides if `two_sided`),
/// varying with direction as its [`Profile`] says.
#[derive(Clone, Debug, PartialEq)]
pub struct Emission {
    /// What is emitted: for a spot, the radiant intensity along the axis per unit area (see
    /// [`Profile::Spot`]).
    pub radiance: Radiance,
    pub two_sided: bool,
    pub profile: Profile,
}

/// What an emitter emits.
#[derive(Clone, Debug, PartialEq)]
pub enum Radiance {
    /// A linear Rec. 709 colour (`Rgb(colour.into())`), its spectrum lifted once.
    Rgb(LiftedIlluminant),
    /// Planck's law at a temperature.
    Blackbody(BlackbodyLight),
    /// A thin accretion disk's gas, hotter inwards and orbiting the hole.
    Disk(Arc<DiskLight>),
}

/// How emitted radiance varies with the angle `θ` from the surface normal.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Profile {
    /// The same radiance in every direction: a Lambertian emitter.
    Uniform,
    /// A spot light's cone about the normal (glTF `KHR_lights_punctual`): radiant intensity
    /// `radiance · area · s(cos θ)`, full inside the inner cone, none outside the outer, and
    /// between them `s = ((cos θ − cos_outer)/(cos_inner − cos_outer))²`, the smooth falloff the
    /// glTF specification recommends. The radiance is therefore `radiance · s / cos θ`.
    Spot { cos_inner: f64, cos_outer: f64 },
}

/// What leaves an emitter before any shift: a colour, or a blackbody.
enum Leaving {
    Rgb(LiftedIlluminant),
    Blackbody(EmittedBlackbody),
}

/// Planck's law at `temperature`, times `scale`, leaving an emitter whose own motion shifts it
/// by `doppler` towards the receiver (1 at rest).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct EmittedBlackbody {
    pub temperature: f64,
    pub scale: f64,
    pub doppler: f64,
}

impl EmittedBlackbody {
    /// The RGB radiance a receiver sees at frequency ratio `g` to the emitter's local observer
    /// (the emitter's own Doppler factor comes on top): the blackbody at `g δ T`.
    pub fn seen(&self, g: f64) -> Rgb {
        let ratio = g * self.doppler;
        Rgb::blackbody(self.temperature, self.scale, (ratio, ratio), &())
    }
}

/// What an emitter asks of the spacetime where it emits: how the local observer there sees
/// matter move. Emission sees the spacetime through this alone (the propagator answers), so it
/// depends on nothing of how rays are traced; it is asked once per emission evaluation, never
/// along a ray.
pub trait LocalObservers {
    /// The velocity (units of c, in the local frame at world point `p` of `region`) of matter
    /// turning rigidly about the world unit vector `axis` through the centre at angular velocity
    /// `omega` per unit coordinate time; `None` where no local observer exists or the motion is
    /// not slower than light there.
    fn orbital_velocity(&self, region: Region, p: Vec3, axis: Vec3, omega: f64) -> Option<Vec3>;
}

/// Where emitted light is seen from: the emitting point (world, in `region`) and the frequency
/// ratio `g = ν_seen / ν_local` the receiver sees it with, in its parts.
#[derive(Clone, Copy)]
pub struct Seen<'a> {
    pub region: Region,
    pub point: Vec3,
    pub shift: Shift,
    /// Asked for the motion of moving emitters relative to the local observer (the renderer's
    /// propagator, hence the name).
    pub propagator: &'a dyn LocalObservers,
}

impl Profile {
    /// The spot's falloff `s(cos θ)` (1 for a uniform emitter).
    fn falloff(self, cos: f64) -> f64 {
        match self {
            Profile::Uniform => 1.0,
            Profile::Spot { cos_inner, cos_outer } if cos_inner > cos_outer => {
                ((cos - cos_outer) / (cos_inner - cos_outer)).clamp(0.0, 1.0).powi(2)
            }
            Profile::Spot { cos_outer, .. } => f64::from(u8::from(cos >= cos_outer)),
        }
    }

    /// Radiance per unit of the profile's scale towards `cos θ` from the normal (`|cos|`).
    fn factor(self, cos: f64) -> f64 {
        match self {
            Profile::Uniform => 1.0,
            Profile::Spot { .. } => {
                let s = self.falloff(cos);
                if s > 0.0 && cos > 0.0 {
                    s / cos
                } else {
                    0.0
                }
            }
        }
    }
}

impl Emission {
    /// Constant radiance in every direction of the outward side (both if `two_sided`).
    pub fn uniform(radiance: Rgb, two_sided: bool) -> Self {
        Self { radiance: Radiance::Rgb(radiance.into()), two_sided, profile: Profile::Uniform }
    }

    /// Whether light leaves the surface with outward normal `ng` in direction `dir`.
    pub fn faces(&self, ng: Vec3, dir: Vec3) -> bool {
        self.two_sided || ng.dot(dir) > 0.0
    }

    /// Radiance leaving the surface with outward normal `ng` in direction `dir` (unit, in the
    /// same frame as `ng`: the local observer's at the emitter), as seen from `seen`, in the
    /// colours `C` at `lambda`.
    pub fn seen<C: Colour>(&self, ng: Vec3, dir: Vec3, seen: &Seen<'_>, lambda: &C::Lambda) -> C {
        if !self.faces(ng, dir) {
            return C::ZERO;
        }
        let factor = self.profile.factor(ng.dot(dir).abs());
        if factor == 0.0 {
            return C::ZERO;
        }
        let radiance = match self.leaving(dir, seen) {
            Leaving::Rgb(rgb) => C::lifted_illuminant(&rgb, seen.shift.shown(1.0), lambda),
            Leaving::Blackbody(b) => C::blackbody(b.temperature, b.scale, seen.shift.shown(b.doppler), lambda),
        };
        radiance * factor as f32
    }

    /// The blackbody leaving the surface with outward normal `ng` in direction `dir`, for a
    /// renderer that carries power from the lights and colours it where it is seen (photon
    /// mapping); `None` for an RGB colour, or where nothing leaves.
    pub fn blackbody(&self, ng: Vec3, dir: Vec3, seen: &Seen<'_>) -> Option<EmittedBlackbody> {
        let factor = self.profile.factor(ng.dot(dir).abs());
        if !self.faces(ng, dir) || factor == 0.0 {
            return None;
        }
        match self.leaving(dir, seen) {
            Leaving::Rgb(_) => None,
            Leaving::Blackbody(b) => Some(EmittedBlackbody { scale: b.scale * factor, ..b }),
        }
    }

    /// What leaves in direction `dir` at `seen.point`, at the profile's full strength.
    fn leaving(&self, dir: Vec3, seen: &Seen<'_>) -> Leaving {
        match &self.radiance {
            Radiance::Rgb(rgb) => Leaving::Rgb(*rgb),
            Radiance::Blackbody(light) => Leaving::Blackbody(EmittedBlackbody {
                temperature: light.temperature(),
                scale: light.scale(),
                doppler: 1.0,
            }),
            Radiance::Disk(disk) => Leaving::Blackbody(disk.emitted(dir, seen)),
        }
    }

    /// The luminance of the exitance per unit area over π at rest, `∫ L cos θ dω / π`: a
    /// light's power per area, for choosing lights in proportion to it.
    pub fn exitance_luminance(&self) -> f64 {
        let sides = if self.two_sided { 2.0 } else { 1.0 };
        // ∫ L cos θ dω = radiance · 2π ∫₀¹ s(c) dc for a spot; π · radiance for a uniform emitter.
        let shape = match self.profile {
            Profile::Uniform => 1.0,
            Profile::Spot { cos_inner, cos_outer } => {
                let (inner, outer) = (cos_inner.clamp(0.0, 1.0), cos_outer.clamp(0.0, 1.0));
                2.0 * ((inner - outer).max(0.0) / 3.0 + (1.0 - inner.max(outer)))
            }
        };
        let at_rest = match &self.radiance {
            Radiance::Rgb(rgb) => f64::from(luminance(rgb.rgb())),
            Radiance::Blackbody(light) => light.luminance(),
            Radiance::Disk(disk) => disk.mean_luminance(),
        };
        at_rest * sides * shape
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Local observers that see no emitter move (none of these tests' emitters does).
    struct AtRest;

    impl LocalObservers for AtRest {
        fn orbital_velocity(&self, _region: Region, _p: Vec3, _axis: Vec3, _omega: f64) -> Option<Vec3> {
            Some(Vec3::ZERO)
        }
    }

    #[test]
    fn a_spot_emits_its_intensity_in_its_cone_and_its_exitance_integrates() {
        let at = Seen { region: Region::Upper, point: Vec3::ZERO, shift: Shift::NONE, propagator: &AtRest };
        let (inner, outer) = (20f64.to_radians(), 35f64.to_radians());
        let spot = Emission {
            radiance: Radiance::Rgb(Rgb::splat(2.0).into()),
            two_sided: false,
            profile: Profile::Spot { cos_inner: inner.cos(), cos_outer: outer.cos() },
        };
        let intensity = |theta: f64| {
            let dir = Vec3::new(theta.sin(), 0.0, theta.cos());
            f64::from(spot.seen::<Rgb>(Vec3::Z, dir, &at, &()).x) * theta.cos()
        };
        // L·cos θ per unit area is the intensity: 2 inside the inner cone, 0 outside the outer.
        assert!((intensity(0.0) - 2.0).abs() < 1e-6 && (intensity(19f64.to_radians()) - 2.0).abs() < 1e-6);
        assert_eq!(intensity(36f64.to_radians()), 0.0);
        let mid = 27.5f64.to_radians();
        let s = ((mid.cos() - outer.cos()) / (inner.cos() - outer.cos())).powi(2);
        assert!((intensity(mid) - 2.0 * s).abs() < 1e-6, "{} against {}", intensity(mid), 2.0 * s);
        assert_eq!(spot.seen::<Rgb>(Vec3::Z, -Vec3::Z, &at, &()), Rgb::ZERO, "one-sided");
        // ∫ L cos θ dω / π by the midpoint rule over θ.
        let n = 20_000;
        let h = std::f64::consts::FRAC_PI_2 / n as f64;
        let integral: f64 = (0..n)
            .map(|i| {
                let theta = (i as f64 + 0.5) * h;
                intensity(theta) * 2.0 * std::f64::consts::PI * theta.sin() * h
            })
            .sum::<f64>()
            / std::f64::consts::PI;
        let expected = spot.exitance_luminance();
        assert!((integral / expected - 1.0).abs() < 1e-4, "{integral} against {expected}");
        assert_eq!(Emission::uniform(Rgb::ONE, true).exitance_luminance(), 2.0);
    }

    #[test]
    fn rgb_brightens_as_g_to_the_fourth_and_a_blackbody_turns_hotter() {
        let at = |g: f64| Seen {
            region: Region::Upper,
            point: Vec3::ZERO,
            shift: Shift { gravity: g, ..Shift::NONE },
            propagator: &AtRest,
        };
        let lamp = Emission::uniform(Rgb::new(1.0, 0.5, 0.25), false);
        assert_eq!(lamp.seen::<Rgb>(Vec3::Z, Vec3::Z, &at(2.0), &()), Rgb::new(16.0, 8.0, 4.0));
        let light = BlackbodyLight::new(3000.0, 1.0).unwrap();
        let hot = Emission { radiance: Radiance::Blackbody(light), two_sided: false, profile: Profile::Uniform };
        let seen = |g| hot.seen::<Rgb>(Vec3::Z, Vec3::Z, &at(g), &());
        let (rest, shifted) = (seen(1.0), seen(2.0));
        assert!((luminance(rest) - 1.0).abs() < 1e-4, "luminance 1 at rest: {rest}");
        // Seen at twice the frequency it is the 6000 K blackbody, bluer: blue over red rises.
        let expected = light.seen(2.0);
        assert!((shifted - expected).length() < 1e-6);
        assert!(shifted.z / shifted.x > 2.0 * rest.z / rest.x, "{rest} → {shifted}");
    }
}

//! The light of a thin accretion disk (Novikov & Thorne 1973): each ring of the disk radiates as
//! a blackbody at the temperature of its Page–Thorne flux, `T = T_peak (F/F_peak)^{1/4}`
//! ([`spacetime::disk::ThinDisk`]), from gas on prograde circular geodesics.
//!
//! Seen by a receiver at frequency ratio `g` (to the local observer at the disk), the gas, moving
//! at `v` relative to that observer, emits at the Doppler ratio `δ = 1/(γ(1 − v·n))` towards the
//! receiver (`n` the direction the light leaves in): the ring is seen as the blackbody at
//! `g δ T`. The teaching toggles ([`super::Shown`]) take the parts apart: without `doppler` the
//! colour is the one the gas would show at rest (the *Interstellar* disk), without `beaming` its
//! brightness is; without `gravitational_shift` gravity changes neither.
//!
//! An optional artistic texture ([`DiskLight::with_texture`]) modulates the brightness of the
//! gas, never its colour, which stays the blackbody's.

use super::{EmittedBlackbody, Seen};
use crate::geometry::{Frame, Vec3};
use crate::rgb::luminance;
use crate::spectrum::BlackbodyColours;
use crate::texture::Texture;
use spacetime::disk::ThinDisk;
use std::sync::Arc;

/// An accretion disk's emission.
#[derive(Debug)]
pub struct DiskLight {
    disk: ThinDisk,
    /// World unit vector the gas turns about, counter-clockwise at `Ω > 0` (the chart's +z).
    axis: Vec3,
    peak_temperature: f64,
    /// The hottest ring's flux, per unit accretion rate.
    peak_flux: f64,
    /// `luminance / Y(B(T_peak))`: the hottest ring has `luminance` at rest.
    scale: f64,
    /// Luminance at rest averaged over the disk's area (without the texture: what light
    /// sampling weighs the disk by, which a texture only makes less than ideal).
    mean_luminance: f64,
    /// The artistic texture, if any, and the frame its azimuth is measured in (`x` at 0,
    /// counter-clockwise about `axis`).
    texture: Option<(Arc<Texture>, Frame)>,
}

impl PartialEq for DiskLight {
    /// The same disk: the same physics, and the same texture object (textures are not compared
    /// by value).
    fn eq(&self, other: &Self) -> bool {
        let same_texture = match (&self.texture, &other.texture) {
            (None, None) => true,
            (Some((a, _)), Some((b, _))) => Arc::ptr_eq(a, b),
            (Some(_), None) | (None, Some(_)) => false,
        };
        same_texture
            && (self.disk.orbits(), self.disk.outer_radius(), self.axis, self.peak_temperature, self.scale)
                == (other.disk.orbits(), other.disk.outer_radius(), other.axis, other.peak_temperature, other.scale)
    }
}

impl DiskLight {
    /// The disk `disk` turning about the world unit vector `axis`, its hottest ring at
    /// `peak_temperature` kelvin with luminance `luminance` at rest; `None` where the
    /// temperature emits nothing visible (below 100 K) or the luminance is negative.
    pub fn new(disk: ThinDisk, axis: Vec3, peak_temperature: f64, luminance: f64) -> Option<Self> {
        let colours = BlackbodyColours::get();
        let y_peak = colours.luminance(peak_temperature);
        if !(y_peak > 0.0 && peak_temperature.is_finite() && luminance >= 0.0 && luminance.is_finite()) {
            return None;
        }
        let (_, peak_flux) = disk.peak();
        let mut light = Self {
            disk,
            axis,
            peak_temperature,
            peak_flux,
            scale: luminance / y_peak,
            mean_luminance: 0.0,
            texture: None,
        };
        light.mean_luminance = light.average_luminance();
        Some(light)
    }

    /// The disk with `texture` over it: at texture coordinates `u` = how far out from the inner
    /// to the outer edge (0 to 1, in world radius) and `v` = the azimuth over 2π, counter-clockwise
    /// about the axis, the texture's luminance multiplies the gas's brightness.
    pub fn with_texture(self, texture: Texture) -> Self {
        let frame = Frame::from_normal(self.axis);
        Self { texture: Some((Arc::new(texture), frame)), ..self }
    }

    /// The texture's brightness factor at world point `p` of the disk (1 without a texture).
    fn texture_factor(&self, p: Vec3) -> f64 {
        let Some((texture, frame)) = &self.texture else { return 1.0 };
        let local = frame.to_local(p);
        let (inner, outer) = self.world_radii();
        let u = ((local.x.hypot(local.y) - inner) / (outer - inner)).clamp(0.0, 1.0);
        let v = local.y.atan2(local.x).rem_euclid(std::f64::consts::TAU) / std::f64::consts::TAU;
        f64::from(luminance(texture.eval([u, v], p))).max(0.0)
    }

    /// The world radii of the disk's edges (in the chart's equatorial plane).
    pub fn world_radii(&self) -> (f64, f64) {
        let orbits = self.disk.orbits();
        (orbits.world_radius(self.disk.inner_radius()), orbits.world_radius(self.disk.outer_radius()))
    }

    pub fn mean_luminance(&self) -> f64 {
        self.mean_luminance
    }

    /// The gas temperature at Boyer–Lindquist radius `r` (0 off the disk).
    pub fn temperature(&self, r: f64) -> f64 {
        let flux = self.disk.flux(r);
        if flux > 0.0 && self.peak_flux > 0.0 {
            self.peak_temperature * (flux / self.peak_flux).sqrt().sqrt()
        } else {
            0.0
        }
    }

    /// The Boyer–Lindquist radius of world point `p` on the disk.
    pub fn radius(&self, p: Vec3) -> f64 {
        let in_plane = p - p.dot(self.axis) * self.axis;
        self.disk.orbits().radius_at(in_plane.length())
    }

    /// The Doppler factor `δ = ν_gas→receiver / ν_gas = 1/(γ(1 − v·n))` of the gas at
    /// Boyer–Lindquist radius `r` (point `seen.point`) towards local direction `dir`: the
    /// frequency the local observer measures over the one the gas emits. 1 where no local
    /// observer exists.
    pub fn doppler(&self, r: f64, dir: Vec3, seen: &Seen<'_>) -> f64 {
        let omega = self.disk.orbits().orbit(r).omega;
        match seen.propagator.orbital_velocity(seen.region, seen.point, self.axis, omega) {
            Some(v) => (1.0 - v.length_squared()).sqrt() / (1.0 - v.dot(dir)),
            None => 1.0,
        }
    }

    /// The blackbody leaving the disk at `seen.point` in local direction `dir`: the ring's
    /// temperature, and the gas's Doppler factor towards `dir`.
    pub(super) fn emitted(&self, dir: Vec3, seen: &Seen<'_>) -> EmittedBlackbody {
        let r = self.radius(seen.point);
        let temperature = self.temperature(r);
        let doppler = if temperature > 0.0 { self.doppler(r, dir, seen) } else { 1.0 };
        EmittedBlackbody { temperature, scale: self.scale * self.texture_factor(seen.point), doppler }
    }

    /// Luminance at rest averaged over the disk's area (midpoint rule in world radius).
    fn average_luminance(&self) -> f64 {
        const RINGS: usize = 512;
        let (inner, outer) = self.world_radii();
        let colours = BlackbodyColours::get();
        let step = (outer - inner) / RINGS as f64;
        let (mut weighted, mut area) = (0.0, 0.0);
        for k in 0..RINGS {
            let rho = inner + (k as f64 + 0.5) * step;
            let t = self.temperature(self.disk.orbits().radius_at(rho));
            weighted += colours.luminance(t) * rho;
            area += rho;
        }
        if area > 0.0 {
            self.scale * weighted / area
        } else {
            0.0
        }
    }
}

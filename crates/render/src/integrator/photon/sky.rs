//! Photons from a region's sky: light from infinity, emitted as pbrt-v3 emits it from infinite
//! area lights (§16.2.4). A direction `ω` the sky is seen in is drawn from the sky's distribution
//! (see [`SkyDistribution`]), then a point uniformly on a disk of radius `b` perpendicular to `ω`,
//! far out along it; the photon travels `−ω`. The disk covers every ray from infinity that can
//! reach the region's receivers, so the beams through it carry all the sky light they get:
//! `Φ = L(ω) · πb² / p(ω)` per photon, measured at infinity.
//!
//! In flat space the disk is centred on the receivers' bounding sphere and `b` is its radius. In
//! curved space rays bend towards the centre, so the disk is centred there and `b` is the largest
//! impact parameter that comes within the sphere about the centre holding the receivers
//! ([`Propagator::impact_bound`]). The photon starts beyond the escape radius (no object is
//! farther), and at least 1000 `b` away so that the deflection it would have gathered farther
//! out, `O(M b / D²)` for a hole, `O(b₀² / (b D))` for a throat, is below 10⁻⁶: the direction at the
//! start is the direction at infinity. There a static observer measures the power `1/lapse²`
//! times its value at infinity (one factor for the energy of each photon, one for their rate).

use super::aim::Target;
use super::emit::Photon;
use crate::geometry::{Frame, Vec3};
use crate::propagator::Propagator;
use crate::rgb::luminance;
use crate::sampling::{concentric_disk, Rng};
use crate::sky::{Sky, SkyDistribution};
use spacetime::Region;
use std::f64::consts::PI;

/// Start distance in units of the disk's radius (see the module documentation).
const FAR: f64 = 1e3;

/// A region's sky as a source of photons.
#[derive(Clone, Debug)]
pub(super) struct SkySource {
    distribution: SkyDistribution,
    /// Centre and radius of the disk the beams cross.
    centre: Vec3,
    radius: f64,
    /// Distance from `centre` at which photons start.
    distance: f64,
}

impl SkySource {
    /// The sky `sky` of a region whose receivers lie in `target`; `None` for a black sky, or
    /// when the receivers are unbounded (an infinite plane) and no disk covers them (or the
    /// spacetime bounds no impact parameters, as about a spinning hole: the sky then lights the
    /// scene through paths continued from the camera, see `background`).
    pub fn new(sky: &Sky, target: Option<Target>, propagator: &Propagator) -> Option<Self> {
        let target = target?;
        let distribution = SkyDistribution::new(sky);
        if !(distribution.power() > 0.0) {
            return None;
        }
        let (centre, radius) = if propagator.is_flat() {
            (target.centre, target.radius)
        } else {
            (Vec3::ZERO, propagator.impact_bound(target.centre.length() + target.radius)?)
        };
        let distance = (propagator.escape_radius() + centre.length() + radius).max(FAR * radius);
        Some(Self { distribution, centre, radius, distance })
    }

    /// Power in the units of [`World::light_power`](crate::world::World::light_power) (flux over
    /// π): `b² ∫ luminance dω`.
    pub fn power(&self) -> f64 {
        self.radius * self.radius * self.distribution.power()
    }

    /// A photon from the sky of `region` (the sky this source was made for, which its
    /// distribution carries), its power not yet divided by the probability of choosing this
    /// source; `None` where the sky is black in the drawn direction.
    pub fn emit(&self, region: Region, propagator: &Propagator, rng: &mut Rng) -> Option<Photon> {
        let sample = self.distribution.sample([rng.next_f64(), rng.next_f64(), rng.next_f64()])?;
        if luminance(sample.radiance) <= 0.0 {
            return None;
        }
        let w = sample.direction;
        let [x, y] = concentric_disk(rng.next_2d());
        let frame = Frame::from_normal(w);
        let origin = self.centre + w * self.distance + (frame.s * x + frame.t * y) * self.radius;
        let lapse = propagator.lapse(region, origin);
        let scale = PI * self.radius * self.radius / (sample.pdf * lapse * lapse);
        let power = sample.radiance * scale as f32;
        Some(Photon { region, origin, direction: -w, power, blackbody: None, frequency: 1.0 })
    }
}

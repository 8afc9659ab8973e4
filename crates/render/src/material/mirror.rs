//! # Mirror (`type = "mirror"`)
//!
//! A perfect specular reflector: every ray leaves at the mirror angle, `wi = (−wo.x, −wo.y, wo.z)`, scaled
//! by a reflectance colour that does not depend on the angle (an idealised silvered mirror; for the
//! angle-dependent colour of a real metal use `type = "conductor"` with `roughness = 0`).
//!
//! A delta lobe: [`f`](super::Bsdf::f) and [`pdf`](super::Bsdf::pdf) are zero and only
//! [`sample`](super::Bsdf::sample) produces it, with `pdf = 1` (the probability of the only lobe).
//!
//! | parameter     | type              | default | meaning                                   |
//! |---------------|-------------------|---------|-------------------------------------------|
//! | `reflectance` | colour or texture | 1.0     | fraction reflected per channel, `[0, 1]`  |
//!
//! ```toml
//! [objects.material]
//! type = "mirror"
//! reflectance = [0.95, 0.95, 0.95]
//! ```
//!
//! Two-sided: the reflection formula holds on either side.

use super::BsdfSample;
use crate::geometry::Vec3;
use crate::spectrum::Colour;

/// Mirror reflection about the shading normal `+z`.
#[inline]
pub(super) fn reflect_z(w: Vec3) -> Vec3 {
    Vec3::new(-w.x, -w.y, w.z)
}

pub(super) fn sample<C: Colour>(reflectance: C, wo: Vec3) -> Option<BsdfSample<C>> {
    (wo.z != 0.0).then_some(BsdfSample::delta(reflect_z(wo), reflectance, 1.0, 1.0))
}

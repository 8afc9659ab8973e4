//! What the local observer at a world point measures: its lapse (the frequency it measures
//! against infinity's), the unit normal of a surface there, the velocity of orbiting matter, and
//! proper areas. The local frame is the static observer's (the normal observer's inside a Kerr
//! ergosphere), with the world's axes (`docs/physics.md`, "Local frames and the time orientation
//! of backward rays").

use super::Propagator;
use crate::emission::LocalObservers;
use crate::geometry::Vec3;
use spacetime::metric::LocalFrame;
use spacetime::Region;

impl Propagator {
    /// The lapse of the local observer at world point `p` of `region`: it measures frequencies
    /// `1/lapse` times those measured at infinity (1 in flat space and in the Ellis wormhole).
    pub fn lapse(&self, region: Region, p: Vec3) -> f64 {
        self.spacetime.capabilities().observer_lapse(region, self.to_chart(p).to_array())
    }

    /// Unit normal in the local frame at `p` for a surface with world normal `n`: the normal is a
    /// covector (the gradient of the surface function), so its radial component scales by `κ`.
    pub fn local_normal(&self, region: Region, p: Vec3, n: Vec3) -> Vec3 {
        match self.local_frame(region, p) {
            LocalFrame::Radial { kappa } => {
                if kappa == 1.0 || p == Vec3::ZERO {
                    return n;
                }
                // n + (κ − 1)(n · p̂) p̂, with p̂ = p/|p| folded into one factor of p: no square
                // root of p's own (the chain to the result is κ's square roots and the last
                // normalisation).
                (n + ((kappa - 1.0) * n.dot(p) / p.length_squared()) * p).normalize()
            }
            LocalFrame::Tetrad { frame, .. } => {
                // Frame components of the gradient covector (0, n): n_(a) = e_(a)^i n_i.
                let n = self.to_chart(n);
                let c = |a: usize| frame.e[a][1] * n.x + frame.e[a][2] * n.y + frame.e[a][3] * n.z;
                self.to_world(Vec3::new(c(1), c(2), c(3)).normalize())
            }
            LocalFrame::None => self.to_world(self.to_chart(n)),
        }
    }

    /// The velocity (units of c, in the local frame at world point `p` of `region`) of matter
    /// turning rigidly about the world unit vector `axis` through the centre at angular velocity
    /// `omega` per unit coordinate time; `None` where no local observer exists or the motion is
    /// not slower than light there.
    pub fn orbital_velocity(&self, region: Region, p: Vec3, axis: Vec3, omega: f64) -> Option<Vec3> {
        let dp_dt = omega * axis.cross(p);
        let measured = spacetime::observer::local_velocity(
            self.spacetime.metric(),
            region,
            self.to_chart(p).to_array(),
            self.to_chart(dp_dt).to_array(),
        )?;
        measured.ok().map(|v| self.to_world(Vec3::from_array(v)))
    }

    /// The local observer's frame at world point `p` of `region` ([`Capabilities::local_frame`]).
    pub(super) fn local_frame(&self, region: Region, p: Vec3) -> LocalFrame {
        self.spacetime.capabilities().local_frame(region, self.to_chart(p).to_array())
    }

    /// Proper area per unit world area of a surface element at world point `p` of `region` with
    /// world unit normal `n`: the measure of area for density estimation (photon mapping). A radially scaled frame maps world vectors by `J = diag(1/κ, 1, 1)`
    /// (radial first), so by Nanson's formula `da = det J · |J⁻ᵀ n| dA = √(n_t² + κ² n_r²) / κ ·
    /// dA`: 1 for a sphere about the centre, `1/κ` for a surface containing the radial direction.
    /// A general frame's is [`Tetrad::area_scale`].
    pub fn area_scale(&self, region: Region, p: Vec3, n: Vec3) -> f64 {
        match self.local_frame(region, p) {
            LocalFrame::Radial { kappa } => {
                if kappa == 1.0 || p == Vec3::ZERO {
                    return 1.0;
                }
                let radial = n.dot(p.normalize());
                let tangential2 = (n.length_squared() - radial * radial).max(0.0);
                (tangential2 + kappa * kappa * radial * radial).sqrt() / kappa
            }
            LocalFrame::Tetrad { frame, x } => {
                frame.area_scale(&self.spacetime.metric().metric(&x), self.to_chart(n).to_array())
            }
            LocalFrame::None => 1.0,
        }
    }
}

/// Emitters ask the propagator only for the motion of their matter.
impl LocalObservers for Propagator {
    fn orbital_velocity(&self, region: Region, p: Vec3, axis: Vec3, omega: f64) -> Option<Vec3> {
        Propagator::orbital_velocity(self, region, p, axis, omega)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::settings::Intersection;
    use spacetime::{Schwarzschild, Spacetime};

    /// The normal a static observer measures is the gradient covector's: its radial component
    /// is scaled by `κ = √(1 − 2M/r)` against the tangential ones, then normalised. Checked at a
    /// point 1.5 from a hole of mass 0.3 (κ = √0.6) for normals along, across and at a slant to
    /// the radial direction.
    #[test]
    fn local_normals_scale_the_radial_component_by_kappa() {
        let propagator =
            Propagator::new(Spacetime::Schwarzschild(Schwarzschild::new(0.3)), 11.0, 1e-7, Intersection::Chord);
        let p = Vec3::new(0.9, -1.2, 0.0);
        let (radial, across) = (p.normalize(), Vec3::Z);
        let kappa = 0.6f64.sqrt();
        for (n_r, n_t) in [(1.0, 0.0), (0.0, 1.0), (0.6, 0.8), (-0.8, 0.6)] {
            let n = n_r * radial + n_t * across;
            let expected = (kappa * n_r * radial + n_t * across).normalize();
            let local = propagator.local_normal(Region::Upper, p, n);
            assert!((local - expected).length() < 1e-14, "{n}: {local} vs {expected}");
        }
        // Without mass it is the world's.
        let flat = Propagator::new(Spacetime::Schwarzschild(Schwarzschild::new(0.0)), 11.0, 1e-7, Intersection::Chord);
        assert_eq!(flat.local_normal(Region::Upper, p, Vec3::new(0.6, 0.8, 0.0)), Vec3::new(0.6, 0.8, 0.0));
    }
}

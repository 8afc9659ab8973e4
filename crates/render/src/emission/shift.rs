//! The frequency ratio `g = ν_seen / ν_local` a path carries, kept in its two parts, gravity and
//! motion, so that the teaching toggles (`[render] doppler`, `beaming`, `gravitational_shift`)
//! can show each effect alone. Gravity is the product of the shifts between the static (local)
//! observers at a path's vertices; motion is the camera's Doppler factor, times a moving
//! emitter's own (an accretion disk's gas).

/// Which frequency shifts light is seen with.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Shown {
    /// Motion (the camera's, a disk's gas) shifts colour.
    pub doppler: bool,
    /// Motion shifts brightness (relativistic beaming).
    pub beaming: bool,
    /// Gravity shifts colour and brightness.
    pub gravitational: bool,
}

impl Default for Shown {
    fn default() -> Self {
        Self { doppler: true, beaming: true, gravitational: true }
    }
}

/// A path's frequency ratio to the camera at one of its vertices.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Shift {
    /// `ν_camera-static / ν_local`: the product of the segments' shifts.
    pub gravity: f64,
    /// The camera's Doppler factor `ν_camera / ν_camera-static`.
    pub motion: f64,
    pub shown: Shown,
}

impl Shift {
    /// No shift: light as the local observer sees it.
    pub const NONE: Shift =
        Shift { gravity: 1.0, motion: 1.0, shown: Shown { doppler: true, beaming: true, gravitational: true } };

    /// At the camera, moving with Doppler factor `doppler`.
    pub fn at_camera(doppler: f64, shown: Shown) -> Self {
        Self { gravity: 1.0, motion: doppler, shown }
    }

    /// The whole ratio, every effect in: what the light's frequency really is.
    pub fn ratio(&self) -> f64 {
        self.gravity * self.motion
    }

    /// At the far end of a segment whose photon energy there is `energy` times its energy here
    /// ([`crate::propagator::Arrival::energy`]).
    pub fn after(self, energy: f64) -> Self {
        Self { gravity: self.gravity / energy, ..self }
    }

    /// The ratios the colour and the brightness of light emitted here are shown with, by an
    /// emitter whose own Doppler factor towards the receiver is `emitter_doppler` (1 at rest).
    pub fn shown(&self, emitter_doppler: f64) -> (f64, f64) {
        let gravity = if self.shown.gravitational { self.gravity } else { 1.0 };
        let motion = self.motion * emitter_doppler;
        let colour = gravity * if self.shown.doppler { motion } else { 1.0 };
        let brightness = gravity * if self.shown.beaming { motion } else { 1.0 };
        (colour, brightness)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn each_toggle_takes_its_part_out() {
        // Binary fractions, so the products are exact.
        let all = Shift { gravity: 0.5, motion: 1.5, shown: Shown::default() };
        assert_eq!(all.shown(2.0), (1.5, 1.5));
        let no_doppler = Shift { shown: Shown { doppler: false, ..Shown::default() }, ..all };
        assert_eq!(no_doppler.shown(2.0), (0.5, 1.5));
        let no_beaming = Shift { shown: Shown { beaming: false, ..Shown::default() }, ..all };
        assert_eq!(no_beaming.shown(2.0), (1.5, 0.5));
        let no_gravity = Shift { shown: Shown { gravitational: false, ..Shown::default() }, ..all };
        assert_eq!(no_gravity.shown(1.0), (1.5, 1.5));
        assert_eq!(all.after(0.25).ratio(), 3.0);
    }
}

//! # Latitude–longitude grid sky (`type = "grid"`)
//!
//! A celestial sphere for lensing diagrams: lines of constant latitude (parallels) and longitude
//! (meridians) every `spacing_deg`, `width_deg` wide as seen from the centre, over a background painted
//! by quadrant, in the manner of the coloured-sphere diagrams of Riazuelo (2019, "Seeing relativity I",
//! IJMPD 28) and Bohn et al. (2015, "What does a binary black hole merger look like?", CQG 32): with
//! four different quadrant colours every flip that gravitational lensing produces — up/down in the
//! Einstein ring, left/right across it — shows. The equator and the prime meridian (longitude 0, the
//! sky's forward direction) can get colours of their own.
//!
//! Quadrants, looking forward with up up: `[upper right, upper left, lower left, lower right]`, i.e.
//! `(lon ≥ 0, lat ≥ 0)`, `(lon < 0, lat ≥ 0)`, `(lon < 0, lat < 0)`, `(lon ≥ 0, lat < 0)`. Two hemispheres
//! are `[north, north, south, south]`; a plain background repeats one colour four times.
//!
//! Line widths are true angular widths: a meridian is drawn where the angular distance to its great
//! semicircle, `asin(cos(lat)·|sin(Δlon)|)`, is at most `width/2`, so meridians keep their width and
//! converge at the poles. `spacing_deg` should divide 90° and 360° for the pattern to close up.
//!
//! | parameter        | type              | default                  | meaning                                |
//! |------------------|-------------------|--------------------------|----------------------------------------|
//! | `background`     | colour or 4 colours | `[0.05, 0.05, 0.05]`   | one colour, or one per quadrant        |
//! | `line`           | colour            | `[0.9, 0.9, 0.9]`        | ordinary lines                         |
//! | `spacing_deg`    | number > 0        | 10                       | angle between adjacent lines           |
//! | `width_deg`      | number ≥ 0        | 0.3                      | angular line width                     |
//! | `equator`        | colour            | (as `line`)              | colour of latitude 0                   |
//! | `prime_meridian` | colour            | (as `line`)              | colour of longitude 0                  |
//! | `up`, `rotation_deg` | vector, number | `[0, 1, 0]`, 0          | orientation (see [`SkyFrame::new`])    |
//!
//! ```toml
//! [sky]
//! type = "grid"
//! background = [[0.6, 0.1, 0.1], [0.1, 0.5, 0.1], [0.1, 0.1, 0.6], [0.6, 0.5, 0.1]]
//! line = [1, 1, 1]
//! spacing_deg = 15
//! width_deg = 0.4
//! equator = [1, 0, 1]
//! ```

use super::SkyFrame;
use crate::geometry::Vec3;
use crate::rgb::Rgb;
use std::f64::consts::FRAC_PI_2;

#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LatLongGrid {
    pub frame: SkyFrame,
    /// `[upper right, upper left, lower left, lower right]` seen looking forward.
    pub background: [Rgb; 4],
    pub line: Rgb,
    pub spacing_deg: f64,
    pub width_deg: f64,
    pub equator: Option<Rgb>,
    pub prime_meridian: Option<Rgb>,
}

impl LatLongGrid {
    /// Radiance from `dir`. A non-positive or non-finite `spacing_deg` draws no lines.
    pub fn radiance(&self, dir: Vec3) -> Rgb {
        let (lat, lon) = self.frame.lat_long(dir);
        let quadrant = match (lon >= 0.0, lat >= 0.0) {
            (true, true) => 0,
            (false, true) => 1,
            (false, false) => 2,
            (true, false) => 3,
        };
        let spacing = self.spacing_deg.to_radians();
        if !(spacing > 0.0 && spacing.is_finite()) {
            return self.background[quadrant];
        }
        let half_width = 0.5 * self.width_deg.to_radians();
        // Nearest parallel (the poles themselves are points, not lines).
        let k_lat = (lat / spacing).round();
        let on_parallel = (lat - k_lat * spacing).abs() <= half_width && (k_lat * spacing).abs() < FRAC_PI_2 - 1e-9;
        // Nearest meridian, by angular distance to its great semicircle.
        let k_lon = (lon / spacing).round();
        let on_meridian = lat.cos() * (lon - k_lon * spacing).sin().abs() <= half_width.sin();
        if on_parallel && k_lat == 0.0 {
            if let Some(c) = self.equator {
                return c;
            }
        }
        if on_meridian && k_lon == 0.0 {
            if let Some(c) = self.prime_meridian {
                return c;
            }
        }
        if on_parallel || on_meridian {
            self.line
        } else {
            self.background[quadrant]
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const Q: [Rgb; 4] =
        [Rgb::new(1.0, 0.0, 0.0), Rgb::new(0.0, 1.0, 0.0), Rgb::new(0.0, 0.0, 1.0), Rgb::new(1.0, 1.0, 0.0)];
    const LINE: Rgb = Rgb::ONE;
    const EQUATOR: Rgb = Rgb::new(1.0, 0.0, 1.0);
    const PRIME: Rgb = Rgb::new(0.0, 1.0, 1.0);

    fn grid() -> LatLongGrid {
        LatLongGrid {
            frame: SkyFrame::Y_UP,
            background: Q,
            line: LINE,
            spacing_deg: 30.0,
            width_deg: 1.0,
            equator: Some(EQUATOR),
            prime_meridian: Some(PRIME),
        }
    }

    fn at(lat_deg: f64, lon_deg: f64) -> Rgb {
        let g = grid();
        g.radiance(g.frame.direction(lat_deg.to_radians(), lon_deg.to_radians()))
    }

    #[test]
    fn lines_where_expected() {
        assert_eq!(at(30.0, 15.0), LINE, "parallel at 30°");
        assert_eq!(at(30.4, 15.0), LINE, "within the half width 0.5°");
        assert_eq!(at(30.6, 15.0), Q[0], "outside it");
        assert_eq!(at(-60.0, -100.0), LINE, "parallel at −60°");
        assert_eq!(at(15.0, 60.0), LINE, "meridian at 60°");
        assert_eq!(at(15.0, -179.9), LINE, "meridian at ±180°");
        // 0.8° of longitude from a meridian: off it near the equator, on it at 55° where
        // cos(55°)·sin(0.8°) < sin(0.5°): meridians keep their angular width toward the poles.
        assert_eq!(at(15.0, 90.8), Q[0]);
        assert_eq!(at(55.0, 90.8), LINE);
        assert_eq!(at(89.9, 47.0), LINE, "all meridians meet at the pole");
    }

    #[test]
    fn quadrants_and_highlights() {
        assert_eq!(at(15.0, 15.0), Q[0], "upper right");
        assert_eq!(at(15.0, -15.0), Q[1], "upper left");
        assert_eq!(at(-15.0, -15.0), Q[2], "lower left");
        assert_eq!(at(-15.0, 15.0), Q[3], "lower right");
        assert_eq!(at(0.0, 45.0), EQUATOR);
        assert_eq!(at(0.2, -100.0), EQUATOR);
        assert_eq!(at(45.0, 0.0), PRIME);
        assert_eq!(at(-45.0, 0.3), PRIME);
        assert_eq!(at(45.0, 180.0), LINE, "the antimeridian is an ordinary line");
        assert_eq!(at(0.0, 0.0), EQUATOR, "crossing: equator first");
        let plain = LatLongGrid { equator: None, prime_meridian: None, ..grid() };
        assert_eq!(plain.radiance(Vec3::NEG_Z), LINE);
        // The sky's forward direction (−z) is at the centre of the four quadrants.
        let d = Vec3::new(0.1, 0.1, -1.0).normalize();
        assert_eq!(plain.radiance(d), Q[0], "up and to the right of forward");
    }

    #[test]
    fn degenerate_spacing_is_background() {
        let g = LatLongGrid { spacing_deg: 0.0, ..grid() };
        assert_eq!(g.radiance(Vec3::new(0.0, 0.0, -1.0)), Q[0]);
    }
}

//! Thin accretion disks: the circular equatorial geodesics their gas follows about a hole of
//! Kerr's family, and the Novikov–Thorne disk's Page–Thorne flux. A spacetime offers its
//! orbits through [`Capabilities::circular_orbits`](crate::metric::Capabilities::circular_orbits).

mod orbits;
mod page_thorne;

pub use orbits::{CircularOrbits, Orbit};
pub use page_thorne::ThinDisk;

//! What happened to the paths of a render, counted per thread and summed.

use std::ops::AddAssign;

/// How camera paths ended.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct FateCounts {
    /// Escaped to the sky of the region they started in.
    pub escaped: u64,
    /// Fell into a horizon.
    pub captured: u64,
    /// Ended at a surface (absorbed, Russian roulette, depth limit).
    pub absorbed: u64,
    /// Escaped to the sky of the other region, through a wormhole throat.
    pub traversed: u64,
    /// Numerical failure of a geodesic (a path segment, or a light connection's visibility ray).
    pub failed: u64,
}

/// Counters a path integrator keeps.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct PathStats {
    /// Rays traced: geodesic segments between vertices, and shadow rays.
    pub rays: u64,
    pub fates: FateCounts,
}

impl AddAssign for PathStats {
    fn add_assign(&mut self, o: Self) {
        self.rays += o.rays;
        self.fates.escaped += o.fates.escaped;
        self.fates.captured += o.fates.captured;
        self.fates.absorbed += o.fates.absorbed;
        self.fates.traversed += o.fates.traversed;
        self.fates.failed += o.fates.failed;
    }
}

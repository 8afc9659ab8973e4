//! Majorants: upper bounds of a medium's extinction along a straight segment, piecewise
//! constant, for the tracking estimators ([`super::tracking`]). The tighter the bound, the fewer
//! null collisions tracking spends (Novák et al. 2014 §4; pbrt-v4 §11.4.3).
//!
//! A uniform or procedural density has one bound everywhere. A grid has a coarse grid of its
//! own: each brick of `BRICK³` voxels holds the largest sample that can reach any point inside
//! it, and a 3-D DDA (Amanatides & Woo 1987, "A fast voxel traversal algorithm for ray
//! tracing"; pbrt-v4's `DDAMajorantIterator`) walks a segment through the bricks, giving one
//! interval per brick crossed. Outside the grid's box the density is 0 and the walk gives
//! nothing.

use super::density::Density;
use super::grid::Grid;
use crate::geometry::Vec3;
use glam::DAffine3;

/// Voxels along each edge of a brick: coarse enough that walking the bricks costs little next
/// to the density lookups, fine enough that a cloud's empty corners get bounds near 0.
pub const BRICK: usize = 8;

/// The bound of a medium's density, to be scaled by its extinction when walked.
#[derive(Clone, Debug, PartialEq)]
pub enum Majorants {
    /// One bound everywhere.
    Constant(f64),
    /// A bound per brick of a grid.
    Bricks(BrickGrid),
}

/// The largest density reachable in each brick of a grid.
#[derive(Clone, Debug, PartialEq)]
pub struct BrickGrid {
    res: [usize; 3],
    /// `x` fastest, like the grid's samples.
    max: Vec<f64>,
    world_to_unit: DAffine3,
}

/// `[t_min, t_max]` of a segment's parameter, on which the extinction is at most `sigma_max`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MajorantSegment {
    pub t_min: f64,
    pub t_max: f64,
    pub sigma_max: f64,
}

impl Majorants {
    /// The bounds of `density`.
    pub fn of(density: &Density) -> Self {
        match density {
            Density::Uniform | Density::Noise(_) => Self::Constant(density.max()),
            Density::Grid(grid) => Self::Bricks(BrickGrid::new(grid, BRICK)),
        }
    }

    /// The bounds of `scale` times the density along `origin + t·dir`, `t ∈ [0, t_max]`, in
    /// increasing `t`. `dir` need not be a unit vector: `t` is the caller's parameter.
    pub fn walk(&self, origin: Vec3, dir: Vec3, t_max: f64, scale: f64) -> MajorantWalk<'_> {
        match self {
            Self::Constant(max) => MajorantWalk::Constant((t_max > 0.0).then_some(MajorantSegment {
                t_min: 0.0,
                t_max,
                sigma_max: scale * max,
            })),
            Self::Bricks(bricks) => MajorantWalk::Bricks(BrickWalk::new(bricks, origin, dir, t_max, scale)),
        }
    }
}

impl BrickGrid {
    /// Bricks of `brick³` voxels over `grid`; the last along an axis may hold fewer.
    pub fn new(grid: &Grid, brick: usize) -> Self {
        let dims = grid.dims();
        let res = dims.map(|n| n.div_ceil(brick));
        let mut max = Vec::with_capacity(res.iter().product());
        for bz in 0..res[2] {
            for by in 0..res[1] {
                for bx in 0..res[0] {
                    max.push(Self::reachable_max(grid, [bx, by, bz], res));
                }
            }
        }
        Self { res, max, world_to_unit: *grid.world_to_unit() }
    }

    /// The largest sample that trilinear interpolation can reach inside brick `b`: the brick
    /// spans `[b·n/res, (b+1)·n/res]` in voxel coordinates, where sample `i` sits at `i + ½`,
    /// so the samples from `⌊lo − ½⌋` to `⌊hi − ½⌋ + 1` reach it. One more sample on each side
    /// covers a point that rounding puts in the neighbouring brick.
    fn reachable_max(grid: &Grid, b: [usize; 3], res: [usize; 3]) -> f64 {
        let dims = grid.dims();
        let range = |a: usize| {
            let lo = (b[a] * dims[a]) as f64 / res[a] as f64;
            let hi = ((b[a] + 1) * dims[a]) as f64 / res[a] as f64;
            let first = (lo - 0.5).floor() as isize - 1;
            let last = (hi - 0.5).floor() as isize + 2;
            first.max(0)..=last.min(dims[a] as isize - 1)
        };
        let mut max = 0.0f64;
        for k in range(2) {
            for j in range(1) {
                for i in range(0) {
                    max = max.max(grid.sample([i, j, k]));
                }
            }
        }
        max
    }
}

/// The intervals of a [`Majorants::walk`].
#[derive(Clone, Debug)]
pub enum MajorantWalk<'a> {
    Constant(Option<MajorantSegment>),
    Bricks(BrickWalk<'a>),
}

impl Iterator for MajorantWalk<'_> {
    type Item = MajorantSegment;

    fn next(&mut self) -> Option<MajorantSegment> {
        match self {
            Self::Constant(segment) => segment.take(),
            Self::Bricks(walk) => walk.next(),
        }
    }
}

/// A DDA through a [`BrickGrid`] in its unit cube, where `t` is the same parameter as in the world
/// (the map is affine, so the segment stays straight and `t` uniform along it).
#[derive(Clone, Debug)]
pub struct BrickWalk<'a> {
    bricks: &'a BrickGrid,
    scale: f64,
    t: f64,
    t_end: f64,
    brick: [isize; 3],
    step: [isize; 3],
    /// The `t` at which the walk next crosses a brick face along each axis.
    next_crossing: [f64; 3],
    /// The `t` from one brick face to the next along each axis.
    delta: [f64; 3],
}

impl<'a> BrickWalk<'a> {
    fn new(bricks: &'a BrickGrid, origin: Vec3, dir: Vec3, t_max: f64, scale: f64) -> Self {
        let o = bricks.world_to_unit.transform_point3(origin);
        let d = bricks.world_to_unit.transform_vector3(dir);
        // The part of the segment inside the unit cube (slab test).
        let (mut t, mut t_end) = (0.0f64, t_max);
        for a in 0..3 {
            let (t0, t1) = ((0.0 - o[a]) / d[a], (1.0 - o[a]) / d[a]);
            // With d[a] = 0 both are ±∞ (inside the slab) or one is NaN (on its face): the
            // comparisons below ignore NaN, and an origin outside the slab gives an empty range.
            t = t.max(t0.min(t1));
            t_end = t_end.min(t0.max(t1));
        }
        let mut walk = Self {
            bricks,
            scale,
            t,
            t_end,
            brick: [0; 3],
            step: [0; 3],
            next_crossing: [f64::INFINITY; 3],
            delta: [f64::INFINITY; 3],
        };
        if !(t < t_end) {
            walk.t_end = f64::NEG_INFINITY;
            return walk;
        }
        let entry = o + d * t;
        for a in 0..3 {
            let n = bricks.res[a];
            let cell = ((entry[a] * n as f64).floor() as isize).clamp(0, n as isize - 1);
            walk.brick[a] = cell;
            if d[a] > 0.0 {
                walk.step[a] = 1;
                walk.next_crossing[a] = t + ((cell + 1) as f64 / n as f64 - entry[a]) / d[a];
                walk.delta[a] = 1.0 / (n as f64 * d[a]);
            } else if d[a] < 0.0 {
                walk.step[a] = -1;
                walk.next_crossing[a] = t + (cell as f64 / n as f64 - entry[a]) / d[a];
                walk.delta[a] = -1.0 / (n as f64 * d[a]);
            }
        }
        walk
    }
}

impl Iterator for BrickWalk<'_> {
    type Item = MajorantSegment;

    fn next(&mut self) -> Option<MajorantSegment> {
        if !(self.t < self.t_end) {
            return None;
        }
        let res = self.bricks.res;
        let index = self.brick[0] as usize + res[0] * (self.brick[1] as usize + res[1] * self.brick[2] as usize);
        let sigma_max = self.scale * self.bricks.max[index];
        let axis = (0..3).fold(0, |best, a| if self.next_crossing[a] < self.next_crossing[best] { a } else { best });
        let exit = self.next_crossing[axis].min(self.t_end);
        let segment = MajorantSegment { t_min: self.t, t_max: exit, sigma_max };
        self.t = exit;
        self.brick[axis] += self.step[axis];
        self.next_crossing[axis] += self.delta[axis];
        if !(0..res[axis] as isize).contains(&self.brick[axis]) {
            self.t_end = f64::NEG_INFINITY;
        }
        Some(segment)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::Aabb;
    use crate::sampling::Rng;
    use crate::transform::Transform;

    /// A 20×13×9 grid of random samples over a rotated, moved box, with empty corners.
    fn lumpy_grid() -> Grid {
        let dims = [20, 13, 9];
        let mut rng = Rng::new(3);
        let values = (0..dims.iter().product::<usize>())
            .map(|n| {
                let i = n % 20;
                if i < 4 {
                    0.0
                } else {
                    (rng.next_f64() * (i as f64)) as f32
                }
            })
            .collect();
        let bounds = Aabb::new(Vec3::new(-1.0, -0.5, 0.0), Vec3::new(1.0, 0.8, 0.7));
        let placement =
            Transform::rotate_deg(Vec3::new(1.0, 2.0, 0.5), 33.0).unwrap().then(&Transform::translate(Vec3::X));
        Grid::new(dims, values, bounds, &placement).unwrap()
    }

    #[test]
    fn the_walk_bounds_the_density_everywhere_on_the_segment() {
        let grid = lumpy_grid();
        let majorants = Majorants::of(&Density::Grid(grid.clone()));
        let mut rng = Rng::new(11);
        let mut tight = 0usize;
        for _ in 0..300 {
            let origin = Vec3::new(rng.next_f64(), rng.next_f64(), rng.next_f64()) * 4.0 - Vec3::splat(1.5);
            let dir = Vec3::new(rng.next_f64() - 0.5, rng.next_f64() - 0.5, rng.next_f64() - 0.5).normalize();
            let length = 4.0 * rng.next_f64();
            let segments: Vec<_> = majorants.walk(origin, dir, length, 2.0).collect();
            for pair in segments.windows(2) {
                assert!((pair[0].t_max - pair[1].t_min).abs() < 1e-12, "contiguous");
            }
            for s in &segments {
                assert!(0.0 <= s.t_min && s.t_min <= s.t_max && s.t_max <= length);
            }
            // Every point of the segment: inside an interval whose bound holds, or of density 0.
            for i in 0..=2000 {
                let t = length * i as f64 / 2000.0;
                let sigma = 2.0 * grid.at(origin + dir * t);
                match segments.iter().find(|s| s.t_min <= t && t <= s.t_max) {
                    Some(s) => {
                        assert!(sigma <= s.sigma_max, "σ {sigma} above its bound {}", s.sigma_max);
                        tight += usize::from(s.sigma_max < 2.0 * grid.max());
                    }
                    None => assert_eq!(sigma, 0.0, "t = {t}: density outside every interval"),
                }
            }
        }
        assert!(tight > 10_000, "the bricks are tighter than the global bound ({tight} points)");
    }

    #[test]
    fn a_constant_bound_is_one_interval() {
        let walk: Vec<_> = Majorants::Constant(0.5).walk(Vec3::ZERO, Vec3::X, 3.0, 4.0).collect();
        assert_eq!(walk, vec![MajorantSegment { t_min: 0.0, t_max: 3.0, sigma_max: 2.0 }]);
        assert_eq!(Majorants::Constant(0.5).walk(Vec3::ZERO, Vec3::X, 0.0, 4.0).count(), 0);
    }

    #[test]
    fn axis_parallel_and_missing_segments() {
        let grid =
            Grid::new([16, 16, 16], vec![1.0; 4096], Aabb::new(Vec3::ZERO, Vec3::ONE), &Transform::IDENTITY).unwrap();
        let majorants = Majorants::of(&Density::Grid(grid));
        // Along x through the middle: two bricks of 8 voxels, [0.25, 0.75] in t.
        let walk: Vec<_> = majorants.walk(Vec3::new(-0.25, 0.5, 0.5), Vec3::X, 1.0, 1.0).collect();
        assert_eq!(walk.len(), 2);
        assert!((walk[0].t_min - 0.25).abs() < 1e-12 && (walk[0].t_max - 0.75).abs() < 1e-12);
        assert!((walk[1].t_max - 1.0).abs() < 1e-12);
        // Beside the box, and pointing away from it.
        assert_eq!(majorants.walk(Vec3::new(-0.25, 1.5, 0.5), Vec3::X, 2.0, 1.0).count(), 0);
        assert_eq!(majorants.walk(Vec3::new(-0.25, 0.5, 0.5), -Vec3::X, 2.0, 1.0).count(), 0);
    }
}

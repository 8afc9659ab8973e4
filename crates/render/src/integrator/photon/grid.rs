//! A hashed uniform grid over the visible points of one region (pbrt-v3 §16.2.3): each point is
//! listed in every cell its gather sphere overlaps, so a photon looks in the one cell it falls
//! in. Cells are twice the largest radius wide, so a sphere overlaps at most 2 × 2 × 2 cells;
//! cells are hashed into a table as long as the point list (Teschner et al. 2003's hash).
//! Built in point order in one thread: the lists, and so every sum over them, are deterministic.

use crate::geometry::{Aabb, Vec3};

/// A gather sphere: the point's index (its pixel), centre and radius.
#[derive(Clone, Copy, Debug)]
pub(super) struct Sphere {
    pub index: u32,
    pub centre: Vec3,
    pub radius: f64,
}

pub(super) struct Grid {
    bounds: Aabb,
    cell: f64,
    /// `starts[h]..starts[h + 1]` is the range of `entries` of hash bucket `h`.
    starts: Vec<usize>,
    entries: Vec<u32>,
}

impl Grid {
    pub fn build(spheres: &[Sphere]) -> Self {
        let max_radius = spheres.iter().map(|s| s.radius).fold(0.0, f64::max);
        let bounds = spheres.iter().fold(Aabb::EMPTY, |b, s| {
            b.union(&Aabb::new(s.centre - Vec3::splat(s.radius), s.centre + Vec3::splat(s.radius)))
        });
        let mut grid = Grid { bounds, cell: 2.0 * max_radius, starts: vec![0; spheres.len() + 1], entries: Vec::new() };
        if spheres.is_empty() || !(grid.cell > 0.0) {
            return grid;
        }
        // Counting sort: bucket sizes, their prefix sums, then the entries in point order.
        grid.each_cell(spheres, |grid, h, _| grid.starts[h + 1] += 1);
        for h in 1..grid.starts.len() {
            grid.starts[h] += grid.starts[h - 1];
        }
        let mut fill = grid.starts.clone();
        grid.entries = vec![0; grid.starts[spheres.len()]];
        grid.each_cell(spheres, |grid, h, index| {
            grid.entries[fill[h]] = index;
            fill[h] += 1;
        });
        grid
    }

    /// Number of spheres in the grid.
    pub fn spheres(&self) -> usize {
        self.starts.len() - 1
    }

    /// The indices of the spheres that may contain `p` (a superset: check the distance).
    pub fn candidates(&self, p: Vec3) -> &[u32] {
        let inside = (0..3).all(|k| p[k] >= self.bounds.min[k] && p[k] <= self.bounds.max[k]);
        if !inside || self.entries.is_empty() {
            return &[];
        }
        let h = self.hash(self.cell_of(p));
        &self.entries[self.starts[h]..self.starts[h + 1]]
    }

    /// Calls `visit(grid, bucket, index)` once for every bucket holding a cell that a sphere
    /// overlaps (two cells of one sphere may share a bucket: it must be listed there once).
    fn each_cell(&mut self, spheres: &[Sphere], mut visit: impl FnMut(&mut Self, usize, u32)) {
        let mut buckets = Vec::with_capacity(8);
        for s in spheres {
            let lo = self.cell_of(s.centre - Vec3::splat(s.radius));
            let hi = self.cell_of(s.centre + Vec3::splat(s.radius));
            buckets.clear();
            for x in lo[0]..=hi[0] {
                for y in lo[1]..=hi[1] {
                    for z in lo[2]..=hi[2] {
                        buckets.push(self.hash([x, y, z]));
                    }
                }
            }
            buckets.sort_unstable();
            buckets.dedup();
            for &h in &buckets {
                visit(self, h, s.index);
            }
        }
    }

    fn cell_of(&self, p: Vec3) -> [i64; 3] {
        let c = ((p - self.bounds.min) / self.cell).floor();
        [c.x as i64, c.y as i64, c.z as i64]
    }

    fn hash(&self, [x, y, z]: [i64; 3]) -> usize {
        let h = (x.wrapping_mul(73_856_093) ^ y.wrapping_mul(19_349_663) ^ z.wrapping_mul(83_492_791)) as u64;
        (h % (self.starts.len() as u64 - 1)) as usize
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::sampling::Rng;

    #[test]
    fn every_sphere_containing_a_point_is_a_candidate() {
        let mut rng = Rng::new(3);
        let spheres: Vec<Sphere> = (0..200)
            .map(|index| {
                let [a, b] = rng.next_2d();
                let centre = Vec3::new(10.0 * a, 10.0 * b, 5.0 * rng.next_f64());
                Sphere { index, centre, radius: 0.1 + 0.5 * rng.next_f64() }
            })
            .collect();
        let grid = Grid::build(&spheres);
        let mut found = 0;
        for _ in 0..2000 {
            let [a, b] = rng.next_2d();
            let p = Vec3::new(11.0 * a - 0.5, 11.0 * b - 0.5, 6.0 * rng.next_f64() - 0.5);
            let candidates = grid.candidates(p);
            for s in spheres.iter().filter(|s| (s.centre - p).length() < s.radius) {
                let listed = candidates.iter().filter(|&&i| i == s.index).count();
                assert_eq!(listed, 1, "sphere {} listed {listed} times at {p:?}", s.index);
                found += 1;
            }
        }
        assert!(found > 100, "the test must exercise hits, found {found}");
        assert!(Grid::build(&[]).candidates(Vec3::ZERO).is_empty());
    }
}

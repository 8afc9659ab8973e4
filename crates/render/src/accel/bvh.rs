//! Bounding volume hierarchy built with the binned surface area heuristic and flattened into a
//! depth-first array (pbrt-v4 §7.3; Wald 2007, "On fast construction of SAH-based bounding volume
//! hierarchies").
//!
//! # Construction
//!
//! Each node's primitives are split along the axis where their centroids spread most: centroids
//! are binned into [`BUCKETS`] equal intervals, and the boundary between buckets that minimises
//! the SAH cost `C = C_trav + (N_l·A_l + N_r·A_r) / A` (in units of one primitive test) is chosen,
//! unless a leaf (`C = N`) is cheaper and small enough. Below [`SAH_DEPTH`] levels the builder
//! switches to median splits, which halve the count at every level: the tree is therefore at most
//! `SAH_DEPTH + 32` levels deep for any input, which is what lets traversal use a fixed stack.
//!
//! # Unbounded primitives
//!
//! A primitive whose box is not finite (an infinite plane) would give the root an infinite
//! surface area and make every SAH cost infinite or NaN. Such primitives are kept out of the tree,
//! in a separate list that every query tests first (their hits then shrink `t_max` before the
//! tree is entered). Primitives with an empty box can never be hit and are dropped.
//!
//! # Traversal
//!
//! Allocation-free: a fixed-size stack of node indices, the near child first (by the sign of the
//! ray direction along the node's split axis), and the box test clipped to the closest hit so
//! far. Box tests use the robust slab test of pbrt-v4 §6.1.2 (Ize 2013, "Robust BVH ray
//! traversal"): the far distance is enlarged by `1 + 2γ₃` so rounding never culls a box the ray
//! touches.

use crate::geometry::{Aabb, Ray, Vec3};

/// Centroid bins per split decision (pbrt-v4 uses 12; more buys little).
const BUCKETS: usize = 12;
/// Up to this many primitives a box query asks about each one directly ([`Bvh::any_near`]): the
/// nodes of a room's walls all enclose the room, so any box inside it overlaps every node and
/// walking the tree only adds the nodes' tests, on every curved step and connection of a render
/// (each makes a box or triangle query).
const DIRECT_BOX_QUERY: usize = 16;
/// Most primitives in one leaf.
const MAX_LEAF: usize = 8;
/// Cost of visiting a node relative to one primitive test.
const TRAVERSAL_COST: f64 = 0.5;
/// Depth after which splits are by median count, bounding the tree's depth.
const SAH_DEPTH: usize = 32;
/// Traversal stack size: the tree is at most `SAH_DEPTH + 32` levels deep (counts are `u32`), and
/// the stack never holds more entries than the current depth.
const STACK: usize = SAH_DEPTH + 32;

/// `1 + 2γ₃` with `γₙ = nε / (1 − nε)`, `ε = 2⁻⁵³`: enlarges a slab's far distance to cover the
/// rounding of the three operations that computed it (pbrt-v4 §6.8.1).
const SLAB_GUARD: f64 = 1.0 + 2.0 * (3.0 * f64::EPSILON * 0.5) / (1.0 - 3.0 * f64::EPSILON * 0.5);

/// A node of the flattened tree: 32 bytes, two per cache line. Traversal of a large scene is
/// bound by memory latency, so bounds are stored in `f32`, rounded outward (never inward: a box
/// may grow by an ulp of `f32`, never cull a primitive). An interior node's first child follows
/// it directly; `offset` is its second child. A leaf's primitives are
/// `order[offset .. offset + count]`.
#[derive(Clone, Copy, Debug)]
struct Node {
    min: [f32; 3],
    max: [f32; 3],
    offset: u32,
    /// 0 for interior nodes.
    count: u16,
    axis: u8,
}

impl Node {
    fn new(b: &Aabb) -> Self {
        Self {
            min: [b.min.x, b.min.y, b.min.z].map(round_down),
            max: [b.max.x, b.max.y, b.max.z].map(round_up),
            offset: 0,
            count: 0,
            axis: 0,
        }
    }
}

/// The largest `f32` not above `x` (`-∞` below the `f32` range).
fn round_down(x: f64) -> f32 {
    let y = x as f32;
    if f64::from(y) <= x {
        y
    } else {
        next_toward_neg_infinity(y)
    }
}

/// The smallest `f32` not below `x` (`+∞` above the `f32` range).
fn round_up(x: f64) -> f32 {
    -round_down(-x)
}

/// The next `f32` toward −∞ of a finite `y` (`f32::next_down` needs Rust 1.86).
fn next_toward_neg_infinity(y: f32) -> f32 {
    let bits = y.to_bits();
    if y == 0.0 {
        -f32::from_bits(1)
    } else if y > 0.0 {
        f32::from_bits(bits - 1)
    } else {
        f32::from_bits(bits + 1)
    }
}

/// A bounding volume hierarchy over primitive bounds.
#[derive(Clone, Debug)]
pub struct Bvh {
    nodes: Vec<Node>,
    /// The exact (`f64`) bounds of the finite primitives.
    bounds: Aabb,
    /// Leaf slots to the caller's primitive indices.
    order: Vec<u32>,
    /// Primitives with non-finite bounds, tested on every query.
    unbounded: Vec<u32>,
}

impl Default for Bvh {
    /// The empty hierarchy.
    fn default() -> Self {
        Bvh::build(&[])
    }
}

/// A primitive during construction.
#[derive(Clone, Copy)]
struct Item {
    bounds: Aabb,
    centroid: Vec3,
    index: u32,
}

#[derive(Clone, Copy)]
struct Bucket {
    count: usize,
    bounds: Aabb,
}

impl Bvh {
    /// Builds the hierarchy over `bounds[i]`, the world box of primitive `i`. Queries report
    /// primitives by these indices.
    ///
    /// # Panics
    ///
    /// If there are more than `u32::MAX` primitives (a scene that would not fit in memory anyway).
    pub fn build(bounds: &[Aabb]) -> Bvh {
        assert!(u32::try_from(bounds.len()).is_ok(), "a BVH holds at most 2³² − 1 primitives");
        let mut items = Vec::with_capacity(bounds.len());
        let mut unbounded = Vec::new();
        for (i, b) in bounds.iter().enumerate() {
            let index = i as u32;
            if b.min.is_finite() && b.max.is_finite() {
                if !b.is_empty() {
                    items.push(Item { bounds: *b, centroid: b.centroid(), index });
                }
            } else if !b.is_empty() {
                // NaN boxes land here too: test them always, the primitive itself decides.
                unbounded.push(index);
            }
        }
        let bounds = items.iter().fold(Aabb::EMPTY, |b, it| b.union(&it.bounds));
        let mut bvh = Bvh {
            nodes: Vec::with_capacity(2 * items.len()),
            bounds,
            order: Vec::with_capacity(items.len()),
            unbounded,
        };
        if !items.is_empty() {
            bvh.build_node(&mut items, 0);
        }
        bvh.nodes.shrink_to_fit();
        bvh
    }

    /// Appends the subtree over `items` in depth-first order; returns its root's index.
    fn build_node(&mut self, items: &mut [Item], depth: usize) -> usize {
        let index = self.nodes.len();
        let bounds = items.iter().fold(Aabb::EMPTY, |b, it| b.union(&it.bounds));
        self.nodes.push(Node::new(&bounds));
        let n = items.len();
        let centroids = items.iter().fold(Aabb::EMPTY, |b, it| b.grow(it.centroid));
        let axis = largest_axis(centroids.diagonal());
        let spread = centroids.diagonal()[axis];

        let split = if n == 1 {
            None
        } else if spread <= 0.0 || depth >= SAH_DEPTH {
            // Coincident centroids (no position tells them apart) or deep: split by count.
            (n > MAX_LEAF).then(|| median_split(items, axis))
        } else {
            sah_split(items, axis, &bounds, &centroids)
        };

        match split {
            None => {
                let first = self.order.len() as u32;
                self.order.extend(items.iter().map(|it| it.index));
                self.nodes[index].offset = first;
                self.nodes[index].count = n as u16;
            }
            Some(mid) => {
                let (left, right) = items.split_at_mut(mid);
                self.build_node(left, depth + 1);
                let second = self.build_node(right, depth + 1);
                self.nodes[index].offset = second as u32;
                self.nodes[index].axis = axis as u8;
            }
        }
        index
    }

    /// The bounds of the finite primitives (unbounded ones are not included).
    pub fn bounds(&self) -> Aabb {
        self.bounds
    }

    /// Number of primitives the BVH can report, bounded or not.
    pub fn len(&self) -> usize {
        self.order.len() + self.unbounded.len()
    }

    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// Number of nodes in the flattened tree.
    pub fn node_count(&self) -> usize {
        self.nodes.len()
    }

    /// Depth of the deepest leaf (a lone root is depth 0).
    pub fn depth(&self) -> usize {
        fn walk(nodes: &[Node], i: usize) -> usize {
            let n = nodes[i];
            if n.count > 0 {
                0
            } else {
                1 + walk(nodes, i + 1).max(walk(nodes, n.offset as usize))
            }
        }
        if self.nodes.is_empty() {
            0
        } else {
            walk(&self.nodes, 0)
        }
    }

    /// The closest primitive hit by `ray`, as `(primitive index, t)`.
    ///
    /// `hit(i, r)` intersects primitive `i` with `r`, a copy of `ray` whose `t_max` has been
    /// shrunk to the closest hit found so far, and returns a hit distance in `(0, r.t_max]`.
    pub fn closest_hit(&self, ray: &Ray, mut hit: impl FnMut(usize, &Ray) -> Option<f64>) -> Option<(usize, f64)> {
        let mut best: Option<(usize, f64)> = None;
        let mut clipped = *ray;
        let mut test = |i: u32, clipped: &mut Ray| {
            if let Some(t) = hit(i as usize, clipped) {
                // Ties keep the first hit; anything beyond the clipped segment is ignored.
                if t <= clipped.t_max && best.is_none_or(|(_, b)| t < b) {
                    best = Some((i as usize, t));
                    clipped.t_max = t;
                }
            }
        };
        for &i in &self.unbounded {
            test(i, &mut clipped);
        }
        if self.nodes.is_empty() {
            return best;
        }
        let inv_dir = ray.dir.recip();
        let dir_is_neg = [inv_dir.x < 0.0, inv_dir.y < 0.0, inv_dir.z < 0.0];
        // The same signs as bits, for the split axis read from each node: indexing the array by
        // it would keep the array in memory, and reading it back packed stalls store forwarding.
        let neg_bits = dir_is_neg.iter().enumerate().fold(0u32, |bits, (k, &neg)| bits | u32::from(neg) << k);
        let mut stack = [0u32; STACK];
        let mut top = 0;
        let mut node = 0usize;
        loop {
            let n = &self.nodes[node];
            if slab_hit(n, ray.origin, inv_dir, dir_is_neg, clipped.t_max) {
                if n.count > 0 {
                    let first = n.offset as usize;
                    for &i in &self.order[first..first + n.count as usize] {
                        test(i, &mut clipped);
                    }
                } else {
                    // Visit the child on the side the ray comes from first.
                    let (near, far) = if neg_bits >> n.axis & 1 != 0 {
                        (n.offset as usize, node + 1)
                    } else {
                        (node + 1, n.offset as usize)
                    };
                    stack[top] = far as u32;
                    top += 1;
                    node = near;
                    continue;
                }
            }
            if top == 0 {
                break;
            }
            top -= 1;
            node = stack[top] as usize;
        }
        best
    }

    /// Whether any primitive may reach into the box `query`: `near(i)` is asked for every
    /// primitive whose node boxes overlap it (and for every unbounded one; for every primitive
    /// of a small hierarchy) and decides exactly. Used to skip refining curved ray steps far from
    /// everything.
    pub fn any_near(&self, query: &Aabb, mut near: impl FnMut(usize) -> bool) -> bool {
        let primitives = self.order.len() + self.unbounded.len();
        if primitives <= DIRECT_BOX_QUERY {
            return (0..primitives).any(near);
        }
        let overlaps =
            |n: &Node| (0..3).all(|k| f64::from(n.min[k]) <= query.max[k] && f64::from(n.max[k]) >= query.min[k]);
        self.any_primitive(overlaps, &mut near)
    }

    /// Whether any primitive is hit by `ray` (a shadow or visibility query): stops at the first
    /// `hit(i, ray)` that returns true.
    pub fn any_hit(&self, ray: &Ray, mut hit: impl FnMut(usize, &Ray) -> bool) -> bool {
        let inv_dir = ray.dir.recip();
        let dir_is_neg = [inv_dir.x < 0.0, inv_dir.y < 0.0, inv_dir.z < 0.0];
        self.any_primitive(|n| slab_hit(n, ray.origin, inv_dir, dir_is_neg, ray.t_max), |i| hit(i, ray))
    }

    /// Depth-first search, in any order, for a primitive `accept` approves, among the unbounded
    /// ones and those in the leaves of nodes `enter` lets in.
    #[inline(always)]
    fn any_primitive(&self, enter: impl Fn(&Node) -> bool, mut accept: impl FnMut(usize) -> bool) -> bool {
        if self.unbounded.iter().any(|&i| accept(i as usize)) {
            return true;
        }
        if self.nodes.is_empty() {
            return false;
        }
        let mut stack = [0u32; STACK];
        let mut top = 0;
        let mut node = 0usize;
        loop {
            let n = &self.nodes[node];
            if enter(n) {
                if n.count > 0 {
                    let first = n.offset as usize;
                    if self.order[first..first + n.count as usize].iter().any(|&i| accept(i as usize)) {
                        return true;
                    }
                } else {
                    stack[top] = n.offset;
                    top += 1;
                    node += 1;
                    continue;
                }
            }
            if top == 0 {
                return false;
            }
            top -= 1;
            node = stack[top] as usize;
        }
    }
}

/// Robust slab test (pbrt-v4 `Bounds3::IntersectP`): does the segment `[0, t_max]` of the ray
/// overlap the node's box? The comparisons are written so that a NaN slab distance (a zero
/// direction component with the origin on the slab's plane) leaves the interval unchanged:
/// conservative. `neg[k]` selects which bound is entered first along axis `k`.
///
/// No early exit per axis: the entry is the latest of the slabs' entries and the exit the
/// earliest of their exits, taken by selects, and one test decides, so traversal pays one
/// unpredictable branch per node rather than up to three. The answer is pbrt's: its per-axis
/// exits test every pair of one slab's entry and another's exit, which `t0 <= t1` tests too,
/// besides each slab against itself, and a slab's entry passes its own (guarded, rounded
/// monotonically) exit unless that exit is negative, when `t1 >= 0` fails in both.
#[inline(always)]
fn slab_hit(n: &Node, origin: Vec3, inv_dir: Vec3, neg: [bool; 3], t_max: f64) -> bool {
    let slab = |k: usize, o: f64, inv: f64| {
        let (lo, hi) = if neg[k] { (n.max[k], n.min[k]) } else { (n.min[k], n.max[k]) };
        ((f64::from(lo) - o) * inv, (f64::from(hi) - o) * inv * SLAB_GUARD)
    };
    let (x, y, z) = (slab(0, origin.x, inv_dir.x), slab(1, origin.y, inv_dir.y), slab(2, origin.z, inv_dir.z));
    // Each select keeps the running bound when the new distance is NaN.
    let later = |t: f64, near: f64| if near > t { near } else { t };
    let earlier = |t: f64, far: f64| if far < t { far } else { t };
    let t0 = later(later(x.0, y.0), z.0);
    let t1 = earlier(earlier(x.1, y.1), z.1);
    (t0 <= t1) & (t0 <= t_max) & (t1 >= 0.0)
}

fn largest_axis(v: Vec3) -> usize {
    if v.x >= v.y && v.x >= v.z {
        0
    } else if v.y >= v.z {
        1
    } else {
        2
    }
}

/// Partitions around the median centroid along `axis`; returns the split index.
fn median_split(items: &mut [Item], axis: usize) -> usize {
    let mid = items.len() / 2;
    items.select_nth_unstable_by(mid, |a, b| a.centroid[axis].total_cmp(&b.centroid[axis]));
    mid
}

/// The binned-SAH split of `items` along `axis`, or `None` when a leaf is cheaper (and allowed).
fn sah_split(items: &mut [Item], axis: usize, bounds: &Aabb, centroids: &Aabb) -> Option<usize> {
    let n = items.len();
    let (lo, spread) = (centroids.min[axis], centroids.diagonal()[axis]);
    let bucket_of = |c: Vec3| (((c[axis] - lo) / spread * BUCKETS as f64) as usize).min(BUCKETS - 1);
    let mut buckets = [Bucket { count: 0, bounds: Aabb::EMPTY }; BUCKETS];
    for it in items.iter() {
        let b = &mut buckets[bucket_of(it.centroid)];
        b.count += 1;
        b.bounds = b.bounds.union(&it.bounds);
    }
    // costs[i]: split after bucket i. Sweep from the right for the upper sides, then from the
    // left, so each cost is O(1) (pbrt-v4 §7.3.2).
    let mut above = [0.0; BUCKETS - 1];
    let (mut count, mut b) = (0, Aabb::EMPTY);
    for i in (1..BUCKETS).rev() {
        count += buckets[i].count;
        b = b.union(&buckets[i].bounds);
        above[i - 1] = if count == 0 { f64::INFINITY } else { count as f64 * b.surface_area() };
    }
    let (mut best, mut best_cost) = (0, f64::INFINITY);
    let (mut count, mut b) = (0, Aabb::EMPTY);
    for i in 0..BUCKETS - 1 {
        count += buckets[i].count;
        b = b.union(&buckets[i].bounds);
        // An empty side is no split at all.
        let cost = if count == 0 || count == n { f64::INFINITY } else { count as f64 * b.surface_area() + above[i] };
        if cost < best_cost {
            (best, best_cost) = (i, cost);
        }
    }
    let area = bounds.surface_area();
    let split_cost = if area > 0.0 { TRAVERSAL_COST + best_cost / area } else { f64::INFINITY };
    if n <= MAX_LEAF && split_cost >= n as f64 {
        return None;
    }
    if !split_cost.is_finite() {
        // A flat or degenerate set (zero area): the SAH cannot rank splits, the count can.
        return Some(median_split(items, axis));
    }
    let mid = partition(items, |it| bucket_of(it.centroid) <= best);
    Some(mid)
}

/// Moves the items satisfying `left` to the front; returns how many there are.
fn partition(items: &mut [Item], left: impl Fn(&Item) -> bool) -> usize {
    let mut mid = 0;
    for i in 0..items.len() {
        if left(&items[i]) {
            items.swap(i, mid);
            mid += 1;
        }
    }
    mid
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::sampling::{uniform_sphere, Rng};
    use crate::shape::{Shape, TriangleMesh};
    use crate::transform::Transform;
    use std::sync::Arc;

    fn random_scene(rng: &mut Rng, spheres: usize, triangles: usize, plane: bool) -> Vec<Shape> {
        let r3 = |rng: &mut Rng| Vec3::new(rng.next_f64(), rng.next_f64(), rng.next_f64()) * 10.0 - 5.0;
        let mut shapes = Vec::new();
        for _ in 0..spheres {
            let c = r3(rng);
            shapes.push(Shape::sphere(c, 0.05 + rng.next_f64() * 0.5, &Transform::IDENTITY).unwrap());
        }
        let mut positions = Vec::new();
        for _ in 0..triangles {
            let c = r3(rng);
            let size = 0.05 + rng.next_f64();
            for _ in 0..3 {
                positions.push(c + uniform_sphere(rng.next_2d()) * size);
            }
        }
        if triangles > 0 {
            let indices = (0..triangles as u32).map(|i| [3 * i, 3 * i + 1, 3 * i + 2]).collect();
            let mesh = Arc::new(TriangleMesh::new(positions, None, None, indices).unwrap());
            shapes.extend(TriangleMesh::shapes(&mesh));
        }
        if plane {
            shapes.push(
                Shape::plane(Vec3::new(0.0, -3.0, 0.0), Vec3::new(0.1, 1.0, 0.05), &Transform::IDENTITY).unwrap(),
            );
        }
        shapes
    }

    fn brute_force(shapes: &[Shape], ray: &Ray) -> Option<(usize, f64)> {
        shapes
            .iter()
            .enumerate()
            .filter_map(|(i, s)| s.intersect(ray).map(|t| (i, t)))
            .min_by(|a, b| a.1.total_cmp(&b.1))
    }

    fn random_ray(rng: &mut Rng, finite: bool) -> Ray {
        let origin = Vec3::new(rng.next_f64(), rng.next_f64(), rng.next_f64()) * 14.0 - 7.0;
        let dir = uniform_sphere(rng.next_2d());
        let t_max = if finite { rng.next_f64() * 4.0 } else { f64::INFINITY };
        Ray::new(origin, dir, t_max)
    }

    #[test]
    fn closest_and_any_hit_match_brute_force() {
        let mut rng = Rng::new(21);
        for scene in 0..12 {
            let shapes = random_scene(&mut rng, scene * 20, 1 + scene * 150, scene % 3 != 1);
            let bvh = Bvh::build(&shapes.iter().map(Shape::bounds).collect::<Vec<_>>());
            assert_eq!(bvh.len(), shapes.len());
            for k in 0..3000 {
                let ray = random_ray(&mut rng, k % 2 == 0);
                let expected = brute_force(&shapes, &ray);
                let got = bvh.closest_hit(&ray, |i, r| shapes[i].intersect(r));
                match (expected, got) {
                    (None, None) => {}
                    (Some((_, te)), Some((i, tg))) => {
                        assert_eq!(te, tg, "scene {scene} ray {k}");
                        assert_eq!(shapes[i].intersect(&ray), Some(tg));
                    }
                    _ => panic!("scene {scene} ray {k}: brute force {expected:?}, BVH {got:?}"),
                }
                assert_eq!(bvh.any_hit(&ray, |i, r| shapes[i].intersect(r).is_some()), expected.is_some());
            }
        }
    }

    #[test]
    fn callback_sees_the_shrinking_segment() {
        let mut rng = Rng::new(22);
        let shapes = random_scene(&mut rng, 200, 500, true);
        let bvh = Bvh::build(&shapes.iter().map(Shape::bounds).collect::<Vec<_>>());
        for _ in 0..500 {
            let ray = random_ray(&mut rng, false);
            let mut last = f64::INFINITY;
            bvh.closest_hit(&ray, |i, r| {
                assert!(r.t_max <= last && r.origin == ray.origin && r.dir == ray.dir);
                last = r.t_max;
                shapes[i].intersect(r)
            });
        }
    }

    #[test]
    fn unbounded_primitives_stay_out_of_the_tree() {
        let plane = Shape::plane(Vec3::ZERO, Vec3::Y, &Transform::IDENTITY).unwrap();
        let sphere = Shape::sphere(Vec3::new(0.0, 5.0, 0.0), 1.0, &Transform::IDENTITY).unwrap();
        let shapes = [plane, sphere];
        let bvh = Bvh::build(&shapes.iter().map(Shape::bounds).collect::<Vec<_>>());
        assert_eq!(bvh.bounds(), shapes[1].bounds(), "finite part only");
        assert_eq!(bvh.node_count(), 1);
        let down = Ray::new(Vec3::new(0.0, 10.0, 0.0), -Vec3::Y, f64::INFINITY);
        assert_eq!(bvh.closest_hit(&down, |i, r| shapes[i].intersect(r)), Some((1, 4.0)));
        let beside = Ray::new(Vec3::new(3.0, 10.0, 0.0), -Vec3::Y, f64::INFINITY);
        assert_eq!(bvh.closest_hit(&beside, |i, r| shapes[i].intersect(r)), Some((0, 10.0)));
        assert!(!bvh.any_hit(&Ray { t_max: 9.0, ..beside }, |i, r| shapes[i].intersect(r).is_some()));
        let empty = Bvh::build(&[]);
        assert!(empty.is_empty() && empty.closest_hit(&down, |_, _| Some(1.0)).is_none());
        assert_eq!(empty.bounds(), Aabb::EMPTY);
    }

    #[test]
    fn pathological_inputs_keep_the_depth_bounded() {
        // Exponentially spaced boxes defeat SAH balance; coincident ones defeat any position split.
        let spaced: Vec<Aabb> = (0..3000)
            .map(|i| {
                let x = 1.01f64.powi(i);
                Aabb::new(Vec3::new(x, 0.0, 0.0), Vec3::new(x * 1.001, 1.0, 1.0))
            })
            .collect();
        let coincident = vec![Aabb::new(Vec3::ZERO, Vec3::ONE); 1000];
        for boxes in [spaced, coincident] {
            let bvh = Bvh::build(&boxes);
            assert!(bvh.depth() < STACK, "depth {}", bvh.depth());
            let ray = Ray::new(Vec3::new(-1.0, 0.5, 0.5), Vec3::X, f64::INFINITY);
            let mut seen = 0;
            bvh.closest_hit(&ray, |_, _| {
                seen += 1;
                None
            });
            assert_eq!(seen, boxes.len(), "a ray through every box tests every primitive once");
        }
    }

    #[test]
    fn f32_node_bounds_round_outward() {
        for x in [0.1, -0.1, 1e-40, -1e-40, 0.0, 1.0 / 3.0, 1e39, -1e39, 16777217.0] {
            assert!(f64::from(round_down(x)) <= x && f64::from(round_up(x)) >= x, "{x}");
        }
        assert_eq!(round_down(0.5), 0.5);
        assert_eq!(round_up(-0.5), -0.5);
    }

    #[test]
    fn flat_and_degenerate_boxes_are_found() {
        // Axis-aligned triangles have zero-thickness boxes; a ray along a box face still sees it.
        let boxes = [
            Aabb::new(Vec3::new(0.0, 0.0, 1.0), Vec3::new(1.0, 1.0, 1.0)),
            Aabb::new(Vec3::new(2.0, 0.0, 0.0), Vec3::new(2.0, 0.0, 0.0)),
            Aabb::EMPTY,
        ];
        let bvh = Bvh::build(&boxes);
        assert_eq!(bvh.len(), 2, "the empty box is dropped");
        let ray = Ray::new(Vec3::new(0.5, 0.5, 0.0), Vec3::Z, 2.0);
        assert_eq!(bvh.closest_hit(&ray, |i, _| Some(if i == 0 { 1.0 } else { 1.5 })), Some((0, 1.0)));
        let along = Ray::new(Vec3::new(0.0, 0.0, 0.0), Vec3::X, 5.0);
        assert!(bvh.any_hit(&along, |i, _| i == 1), "point box on the ray");
    }
}

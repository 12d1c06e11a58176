//! A bounding volume hierarchy over the bounded shapes of a scene (every
//! kind but planes, which are infinite and stay outside), so that a ray
//! meets a few dozen boxes instead of every shape. Built on the CPU whenever the
//! scene changes, traversed by the reference here and by the shader in
//! `shaders/intersect.wgsl` (the same tree, packed by `gpu::layout`). The
//! same builder makes the tree over a loaded geometry's triangles
//! ([`triangle_bvh`]), once per geometry.
//!
//! Construction is top-down with the surface area heuristic over binned
//! centroids (Wald 2007, "On fast Construction of SAH-based Bounding Volume
//! Hierarchies"): it costs O(n log n) and gives trees close to a full SAH sweep.

use glam::DVec3;

use std::sync::Arc;
use web_time::{Duration, Instant};

use rayon::prelude::*;

use crate::scene::{Geometry, Scene, ShapeId};

/// An axis-aligned box.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Aabb {
    pub min: DVec3,
    pub max: DVec3,
}

impl Aabb {
    const EMPTY: Aabb = Aabb {
        min: DVec3::INFINITY,
        max: DVec3::NEG_INFINITY,
    };

    fn union(self, other: Aabb) -> Aabb {
        Aabb {
            min: self.min.min(other.min),
            max: self.max.max(other.max),
        }
    }

    fn centroid(&self) -> DVec3 {
        0.5 * (self.min + self.max)
    }

    /// Half the surface area (the SAH only needs ratios).
    fn half_area(&self) -> f64 {
        let e = (self.max - self.min).max(DVec3::ZERO);
        e.x * e.y + e.y * e.z + e.z * e.x
    }

    /// Whether the ray `o + t d` meets the box for some `0 <= t < t_max`
    /// (`inv_d` = [`safe_inverse`]`(d)`). An axis the ray runs parallel to is
    /// decided by a branch, inside the slab or not, so a ray lying in a face
    /// plane still counts as touching the box, and nothing forms 0 * inf.
    /// The far bound is widened by `1 + 2 gamma(3)` as in pbrt-v4, so
    /// rounding never makes a ray miss a box that holds its hit.
    pub fn hit(&self, o: DVec3, d: DVec3, inv_d: DVec3, t_max: f64) -> bool {
        let (mut near, mut far) = (0.0f64, t_max);
        for i in 0..3 {
            if d[i].abs() < PARALLEL {
                if o[i] < self.min[i] || o[i] > self.max[i] {
                    return false;
                }
                continue;
            }
            let t0 = (self.min[i] - o[i]) * inv_d[i];
            let t1 = (self.max[i] - o[i]) * inv_d[i];
            near = near.max(t0.min(t1));
            far = far.min(t0.max(t1) * (1.0 + 2.0 * GAMMA_3));
        }
        near <= far
    }
}

/// Direction components below this count as zero: the ray is parallel to
/// that axis's slabs for any distance a scene can have.
const PARALLEL: f64 = 1e-20;

/// pbrt-v4's gamma(3) for f64.
const GAMMA_3: f64 = 3.0 * (f64::EPSILON / 2.0) / (1.0 - 3.0 * (f64::EPSILON / 2.0));

/// 1 / d per component, 0 where the ray is parallel to an axis (those
/// components are never used, see [`Aabb::hit`]), so no inf is formed.
pub fn safe_inverse(d: DVec3) -> DVec3 {
    let inv = |x: f64| if x.abs() < PARALLEL { 0.0 } else { 1.0 / x };
    DVec3::new(inv(d.x), inv(d.y), inv(d.z))
}

/// A node: an inner node (`count == 0`) has its two children at `first` and
/// `first + 1`; a leaf holds `prims[first .. first + count]`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Node {
    pub bounds: Aabb,
    pub first: u32,
    pub count: u32,
}

/// The hierarchy: `nodes[0]` is the root (absent when there are no bounded
/// shapes). `P` is what the leaves hold: scene shapes, or the triangle
/// indices of a mesh ([`triangle_bvh`]).
#[derive(Debug, Clone, PartialEq)]
pub struct Bvh<P = ShapeId> {
    pub nodes: Vec<Node>,
    pub prims: Vec<P>,
}

impl<P> Default for Bvh<P> {
    fn default() -> Self {
        Bvh {
            nodes: Vec::new(),
            prims: Vec::new(),
        }
    }
}

/// Leaves hold at most this many shapes unless the tree is too deep.
const MAX_LEAF: usize = 4;
/// Deepest level (the root is level 0).
pub const MAX_DEPTH: usize = 30;
/// Entries a nearest-first traversal stack needs: visiting an inner node
/// pops one entry and pushes its two children, so while a node of level d
/// is being visited at most one sibling per level above it waits, and
/// pushing the children of an inner node of the deepest inner level,
/// `MAX_DEPTH - 1`, fills `MAX_DEPTH + 1` entries. The shader's `BVH_STACK`
/// is generated from this (src/gpu/shaders.rs).
pub const TRAVERSAL_STACK: usize = MAX_DEPTH + 1;
const BINS: usize = 16;
/// Cost of visiting a node relative to intersecting one shape.
const TRAVERSAL_COST: f64 = 1.0;

/// The bounding box of each bounded shape of `scene` (every kind whose
/// `Shape::bounds` is not `None`).
pub fn prim_bounds(scene: &Scene) -> Vec<(ShapeId, Aabb)> {
    scene
        .shape_bounds()
        .into_iter()
        .map(|(id, [min, max])| (id, Aabb { min, max }))
        .collect()
}

impl Bvh {
    /// Builds the hierarchy over the bounded shapes of `scene`.
    pub fn build(scene: &Scene) -> Bvh {
        Bvh::from_items(prim_bounds(scene))
    }
}

/// The boxes of a mesh's triangles, in its own coordinates.
fn triangle_bounds(geometry: &Geometry) -> Vec<(u32, Aabb)> {
    let p = &geometry.positions;
    geometry
        .triangles
        .par_iter()
        .enumerate()
        .map(|(i, t)| {
            let [a, b, c] = t.map(|v| p[v as usize]);
            let bounds = Aabb {
                min: a.min(b).min(c),
                max: a.max(b).max(c),
            };
            (i as u32, bounds)
        })
        .collect()
}

/// A triangle BVH as built for one geometry, with what the viewer's panel
/// shows of it.
#[derive(Debug, Clone)]
pub struct TriangleBvh {
    pub bvh: Arc<Bvh<u32>>,
    /// [`Bvh::depth`], kept: it walks the whole tree.
    pub depth: usize,
    /// Wall-clock time of the build (rayon threads included).
    pub build_time: Duration,
}

/// The BVH over a mesh's triangles (leaves hold triangle indices) in the
/// mesh's own coordinates. It is built once per loaded geometry, which
/// keeps it ([`Geometry::derived`]) for every copy of the scene: moving,
/// turning or scaling a mesh changes only its placement, which renderers
/// apply to the ray, never this tree.
pub fn triangle_bvh(geometry: &Geometry) -> Arc<Bvh<u32>> {
    triangle_bvh_built(geometry).bvh
}

/// [`triangle_bvh`] with its depth and build time.
pub fn triangle_bvh_built(geometry: &Geometry) -> TriangleBvh {
    let built = geometry.derived(|| {
        let start = Instant::now();
        let bvh = build_triangle_bvh(geometry);
        let build_time = start.elapsed();
        TriangleBvh {
            depth: bvh.depth(),
            bvh: Arc::new(bvh),
            build_time,
        }
    });
    TriangleBvh::clone(&built)
}

/// A new BVH over the triangles of `geometry`, in its own coordinates,
/// bypassing the cache of [`triangle_bvh`] (the benchmark times builds).
pub fn build_triangle_bvh(geometry: &Geometry) -> Bvh<u32> {
    Bvh::from_items(triangle_bounds(geometry))
}

/// Below this many items a subtree is built on one thread: splitting the
/// work further costs more than it gains.
const PARALLEL_MIN: usize = 4096;

impl<P: Copy + Send> Bvh<P> {
    /// Builds the hierarchy over `items` (each with its box). Subtrees of
    /// more than [`PARALLEL_MIN`] items are built in parallel (rayon).
    pub fn from_items(mut items: Vec<(P, Aabb)>) -> Bvh<P> {
        if items.is_empty() {
            return Bvh::default();
        }
        let nodes = build_nodes(&mut items, 0, 0);
        Bvh {
            nodes,
            prims: items.into_iter().map(|(p, _)| p).collect(),
        }
    }

    /// The deepest level of the tree (the root is level 0).
    pub fn depth(&self) -> usize {
        fn level(nodes: &[Node], i: usize) -> usize {
            let n = nodes[i];
            if n.count > 0 {
                return 0;
            }
            let first = n.first as usize;
            1 + level(nodes, first).max(level(nodes, first + 1))
        }
        if self.nodes.is_empty() {
            0
        } else {
            level(&self.nodes, 0)
        }
    }

    /// Fills node `node` with `items` (which start at `offset` in the final
    /// prim list), splitting it where the SAH says it pays.
    fn split(&mut self, node: usize, items: &mut [(P, Aabb)], offset: usize, depth: usize) {
        let bounds = items.iter().fold(Aabb::EMPTY, |b, (_, a)| b.union(*a));
        let leaf = Node {
            bounds,
            first: offset as u32,
            count: items.len() as u32,
        };
        self.nodes[node] = leaf;
        if items.len() <= 1 || depth >= MAX_DEPTH {
            return;
        }
        let Some(mid) = sah_split(items, bounds)
            .or_else(|| (items.len() > MAX_LEAF).then(|| median_split(items)))
        else {
            return;
        };
        let left = self.nodes.len();
        self.nodes.push(leaf);
        self.nodes.push(leaf);
        self.nodes[node] = Node {
            bounds,
            first: left as u32,
            count: 0,
        };
        let (a, b) = items.split_at_mut(mid);
        self.split(left, a, offset, depth + 1);
        self.split(left + 1, b, offset + mid, depth + 1);
    }

    /// Calls `visit(prim, t_max)` for every shape in a leaf whose box the ray
    /// meets before `t_max`, nearest-first, where `visit` returns the new
    /// `t_max` (smaller after a hit) or `None` to stop (any-hit queries).
    pub fn traverse(
        &self,
        o: DVec3,
        d: DVec3,
        mut t_max: f64,
        mut visit: impl FnMut(P, f64) -> Option<f64>,
    ) {
        if self.nodes.is_empty() {
            return;
        }
        let inv_d = safe_inverse(d);
        let mut stack = Vec::with_capacity(TRAVERSAL_STACK);
        stack.push(0usize);
        while let Some(index) = stack.pop() {
            let node = &self.nodes[index];
            if !node.bounds.hit(o, d, inv_d, t_max) {
                continue;
            }
            if node.count > 0 {
                for &prim in &self.prims[node.first as usize..(node.first + node.count) as usize] {
                    match visit(prim, t_max) {
                        Some(t) => t_max = t,
                        None => return,
                    }
                }
                continue;
            }
            // Visit the nearer child first: push it last.
            let (a, b) = (node.first as usize, node.first as usize + 1);
            let axis = longest_axis(node.bounds);
            if d[axis] >= 0.0 {
                stack.extend([b, a]);
            } else {
                stack.extend([a, b]);
            }
        }
    }
}

/// The nodes of the subtree over `items` (which start at `offset` in the
/// final prim list), its root first; inner nodes point at children inside
/// the returned list. Large subtrees split their two halves across
/// threads, and the halves' lists are appended after the root's children.
fn build_nodes<P: Copy + Send>(items: &mut [(P, Aabb)], offset: usize, depth: usize) -> Vec<Node> {
    let count = items.len() as u32;
    let leaf = |bounds| Node {
        bounds,
        first: offset as u32,
        count,
    };
    let bounds = items.iter().fold(Aabb::EMPTY, |b, (_, a)| b.union(*a));
    if items.len() < PARALLEL_MIN || depth >= MAX_DEPTH {
        let mut bvh = Bvh::<P> {
            nodes: vec![leaf(bounds)],
            prims: Vec::new(),
        };
        bvh.split(0, items, offset, depth);
        return bvh.nodes;
    }
    let mid = sah_split(items, bounds).unwrap_or_else(|| median_split(items));
    let (a, b) = items.split_at_mut(mid);
    let (left, right) = rayon::join(
        || build_nodes(a, offset, depth + 1),
        || build_nodes(b, offset + mid, depth + 1),
    );
    // Root, left root, right root, then the rest of left, then of right.
    let left_base = 3 - 1;
    let right_base = 3 + (left.len() - 1) - 1;
    let moved = |n: &Node, base: usize| {
        let mut n = *n;
        if n.count == 0 {
            n.first += base as u32;
        }
        n
    };
    let mut nodes = Vec::with_capacity(1 + left.len() + right.len());
    nodes.push(Node {
        bounds,
        first: 1,
        count: 0,
    });
    nodes.push(moved(&left[0], left_base));
    nodes.push(moved(&right[0], right_base));
    nodes.extend(left[1..].iter().map(|n| moved(n, left_base)));
    nodes.extend(right[1..].iter().map(|n| moved(n, right_base)));
    nodes
}

fn longest_axis(b: Aabb) -> usize {
    let e = b.max - b.min;
    if e.x >= e.y && e.x >= e.z {
        0
    } else if e.y >= e.z {
        1
    } else {
        2
    }
}

/// The binned SAH split: sorts `items` into two groups along the longest
/// axis of the centroids and returns the size of the first, or `None` when
/// keeping them in one leaf is cheaper (or they cannot be told apart).
fn sah_split<P>(items: &mut [(P, Aabb)], bounds: Aabb) -> Option<usize> {
    let centroids = items.iter().fold(Aabb::EMPTY, |b, (_, a)| {
        let c = a.centroid();
        b.union(Aabb { min: c, max: c })
    });
    let axis = longest_axis(centroids);
    let (lo, hi) = (centroids.min[axis], centroids.max[axis]);
    if hi <= lo {
        return None;
    }
    let bin_of =
        |a: &Aabb| (((a.centroid()[axis] - lo) / (hi - lo) * BINS as f64) as usize).min(BINS - 1);
    let mut bins = [(Aabb::EMPTY, 0usize); BINS];
    for (_, a) in items.iter() {
        let bin = &mut bins[bin_of(a)];
        *bin = (bin.0.union(*a), bin.1 + 1);
    }
    // Cost of splitting after bin i: sweep from the left and from the right.
    let mut right = [(0.0, 0usize); BINS];
    let mut acc = (Aabb::EMPTY, 0usize);
    for i in (1..BINS).rev() {
        acc = (acc.0.union(bins[i].0), acc.1 + bins[i].1);
        right[i] = (acc.0.half_area(), acc.1);
    }
    let mut best = (f64::INFINITY, 0usize);
    let mut left = (Aabb::EMPTY, 0usize);
    for i in 0..BINS - 1 {
        left = (left.0.union(bins[i].0), left.1 + bins[i].1);
        let (right_area, right_count) = right[i + 1];
        if left.1 == 0 || right_count == 0 {
            continue;
        }
        let cost = left.0.half_area() * left.1 as f64 + right_area * right_count as f64;
        if cost < best.0 {
            best = (cost, i);
        }
    }
    let split_cost = TRAVERSAL_COST + best.0 / bounds.half_area().max(f64::MIN_POSITIVE);
    if !best.0.is_finite() || (split_cost >= items.len() as f64 && items.len() <= MAX_LEAF) {
        return None;
    }
    let mid = partition(items, |a| bin_of(a) <= best.1);
    (mid > 0 && mid < items.len()).then_some(mid)
}

/// Splits at the median centroid along the longest axis (for shapes the
/// bins cannot separate, e.g. many at the same place).
fn median_split<P>(items: &mut [(P, Aabb)]) -> usize {
    let bounds = items.iter().fold(Aabb::EMPTY, |b, (_, a)| b.union(*a));
    let axis = longest_axis(bounds);
    let mid = items.len() / 2;
    items.select_nth_unstable_by(mid, |a, b| {
        a.1.centroid()[axis].total_cmp(&b.1.centroid()[axis])
    });
    mid
}

/// Moves the items for which `left` holds to the front; returns their count.
fn partition<P>(items: &mut [(P, Aabb)], left: impl Fn(&Aabb) -> bool) -> usize {
    let mut mid = 0;
    for i in 0..items.len() {
        if left(&items[i].1) {
            items.swap(i, mid);
            mid += 1;
        }
    }
    mid
}

#[cfg(test)]
mod tests {
    use super::*;

    fn spheres_scene(n: usize, seed: u64) -> Scene {
        let mut text = String::from("[camera]\nfrom = [0, 0, 50]\nto = [0, 0, 0]\n");
        let mut x = seed;
        let mut rand = || {
            // xorshift: deterministic positions without a crate.
            x ^= x << 13;
            x ^= x >> 7;
            x ^= x << 17;
            (x % 10_000) as f64 / 100.0 - 50.0
        };
        for _ in 0..n {
            text += &format!(
                "[[spheres]]\ncenter = [{}, {}, {}]\nradius = {}\n",
                rand(),
                rand(),
                rand(),
                0.2 + rand().abs() / 100.0
            );
        }
        for i in 0..n / 4 {
            text += &format!(
                "[[cubes]]\ncenter = [{}, {}, {}]\nsize = [1, 2, 0.5]\nrotation = [{i}, {}, 10]\n",
                rand(),
                rand(),
                rand(),
                i * 7
            );
        }
        Scene::from_toml_str(&text, None).expect("valid scene")
    }

    #[test]
    fn every_shape_is_in_exactly_one_leaf_inside_its_node_bounds() {
        let scene = spheres_scene(500, 7);
        let bvh = Bvh::build(&scene);
        let bounds: std::collections::HashMap<ShapeId, Aabb> =
            prim_bounds(&scene).into_iter().collect();
        let mut seen = std::collections::HashSet::new();
        let mut stack = vec![(0usize, 0usize)];
        while let Some((index, depth)) = stack.pop() {
            let node = bvh.nodes[index];
            assert!(depth <= MAX_DEPTH);
            if node.count == 0 {
                for child in [node.first as usize, node.first as usize + 1] {
                    let c = bvh.nodes[child].bounds;
                    assert!(
                        c.min.cmpge(node.bounds.min).all() && c.max.cmple(node.bounds.max).all()
                    );
                    stack.push((child, depth + 1));
                }
            } else {
                for prim in &bvh.prims[node.first as usize..(node.first + node.count) as usize] {
                    let b = bounds[prim];
                    assert!(
                        b.min.cmpge(node.bounds.min).all() && b.max.cmple(node.bounds.max).all()
                    );
                    assert!(seen.insert(*prim), "{prim:?} in two leaves");
                }
            }
        }
        assert_eq!(seen.len(), scene.spheres.len() + scene.cubes.len());
    }

    #[test]
    fn rotated_box_bounds_contain_its_corners() {
        let scene = spheres_scene(8, 3);
        for (prim, b) in prim_bounds(&scene) {
            if let ShapeId::Cube(i) = prim {
                let c = &scene.cubes[i].placement;
                let m = c.rotation_matrix();
                let h = c.scale.edges() * 0.5;
                for corner in 0..8 {
                    let s = DVec3::new(
                        if corner & 1 == 0 { -1.0 } else { 1.0 },
                        if corner & 2 == 0 { -1.0 } else { 1.0 },
                        if corner & 4 == 0 { -1.0 } else { 1.0 },
                    );
                    let p = c.translate + m * (s * h);
                    assert!(p.cmpge(b.min - 1e-12).all() && p.cmple(b.max + 1e-12).all());
                }
            }
        }
    }

    #[test]
    fn traversal_visits_every_shape_a_ray_can_hit() {
        // Brute force: every shape whose box the ray meets must be visited.
        let scene = spheres_scene(300, 11);
        let bvh = Bvh::build(&scene);
        let bounds = prim_bounds(&scene);
        for k in 0..200 {
            let a = k as f64 * 0.731;
            let o = DVec3::new(a.sin() * 60.0, a.cos() * 40.0, 60.0);
            let d =
                (DVec3::new((a * 3.1).sin() * 20.0, (a * 1.7).cos() * 20.0, 0.0) - o).normalize();
            let inv = safe_inverse(d);
            let mut visited = std::collections::HashSet::new();
            bvh.traverse(o, d, f64::MAX, |p, t| {
                visited.insert(p);
                Some(t)
            });
            for (p, b) in &bounds {
                if b.hit(o, d, inv, f64::MAX) {
                    assert!(visited.contains(p), "ray {k} missed {p:?}");
                }
            }
        }
    }

    #[test]
    fn axis_parallel_rays_and_origins_on_slab_planes_give_no_nan() {
        let b = Aabb {
            min: DVec3::splat(-1.0),
            max: DVec3::splat(1.0),
        };
        let (d, inv) = (DVec3::X, safe_inverse(DVec3::X));
        assert!(b.hit(DVec3::new(-5.0, 0.0, 0.0), d, inv, f64::MAX));
        assert!(
            b.hit(DVec3::new(-5.0, 1.0, 1.0), d, inv, f64::MAX),
            "along an edge"
        );
        assert!(!b.hit(DVec3::new(-5.0, 1.5, 0.0), d, inv, f64::MAX));
        assert!(
            !b.hit(DVec3::new(-5.0, 0.0, 0.0), d, inv, 3.0),
            "beyond t_max"
        );
        assert!(b.hit(DVec3::ZERO, -d, safe_inverse(-d), 0.5), "from inside");
    }

    #[test]
    fn shapes_at_one_place_still_build_a_shallow_tree() {
        let mut text = String::from("[camera]\nfrom = [0, 0, 5]\nto = [0, 0, 0]\n");
        for _ in 0..1000 {
            text += "[[spheres]]\ncenter = [1, 2, 3]\nradius = 1\n";
        }
        let bvh = Bvh::build(&Scene::from_toml_str(&text, None).unwrap());
        assert_eq!(bvh.prims.len(), 1000);
        assert!(
            bvh.nodes.len() < 1000,
            "median splits keep it a tree: {}",
            bvh.nodes.len()
        );
    }

    /// Spheres at x = 4^i: every split peels off the farthest one, so the
    /// tree is a chain as deep as the builder allows.
    fn chain_scene(n: usize) -> Scene {
        let mut text = String::from("[camera]\nfrom = [0, 0, 5]\nto = [0, 0, 0]\n");
        for i in 0..n {
            let x = 4f64.powi(i as i32);
            text += &format!("[[spheres]]\ncenter = [{x:e}, 0, 0]\nradius = 0.25\n");
        }
        Scene::from_toml_str(&text, None).expect("valid scene")
    }

    #[test]
    fn the_traversal_stack_holds_the_deepest_tree() {
        let bvh = Bvh::build(&chain_scene(4 * MAX_DEPTH));
        // The shader's discipline: pop one node, push both children of an
        // inner node (every box is hit, the worst case).
        let (mut deepest, mut most) = (0, 0);
        let mut stack = vec![(0usize, 0usize)];
        while let Some((index, depth)) = stack.pop() {
            deepest = deepest.max(depth);
            let node = bvh.nodes[index];
            if node.count == 0 {
                let first = node.first as usize;
                stack.extend([(first + 1, depth + 1), (first, depth + 1)]);
                most = most.max(stack.len());
            }
        }
        assert_eq!(deepest, MAX_DEPTH, "the chain reaches the depth limit");
        assert_eq!(most, TRAVERSAL_STACK, "and fills the stack exactly");
    }

    #[test]
    fn empty_scene_has_no_nodes() {
        let scene =
            Scene::from_toml_str("[camera]\nfrom = [0, 0, 5]\nto = [0, 0, 0]\n", None).unwrap();
        let bvh = Bvh::build(&scene);
        assert!(bvh.nodes.is_empty());
        bvh.traverse(DVec3::ZERO, DVec3::Z, 1.0, |_, _| {
            panic!("nothing to visit")
        });
    }
}

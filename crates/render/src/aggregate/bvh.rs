//! [`Bvh`]: the one bounding-volume hierarchy of the tracer, over any items that have boxes —
//! the scene's bounded primitives and a Bézier mesh's sub-patches alike.
//!
//! Built top-down as a binary tree with the surface area heuristic over [`SAH_BINS`] centroid
//! bins per node (Wald 2007, "On fast construction of SAH-based bounding volume hierarchies";
//! pbrt-v4 §7.3.2), the two halves of a large node in parallel (rayon), each subtree written in
//! place into its own share of one node array (`2m − 1` slots for `m` items). That tree is then
//! collapsed into a 4-wide one for traversal (Wald et al. 2008, "Getting rid of packets";
//! Embree's BVH4): each node takes its binary node's two children and repeatedly opens the
//! inner child of largest surface area until it has four (or none is inner), and stores the
//! child boxes side by side ([`Bounds4`]) so that one fetch tests them all. Traversal visits the children a ray
//! crosses in the binary tree's order (near child first by the sign of the ray direction along
//! each split axis, a per-node table over the eight direction octants) and skips every node
//! that starts beyond the nearest hit found so far; at most [`FLAT_MAX_ITEMS`] items are a flat
//! list. See `paper-notes/bvh.md`.

use std::ops::Range;
use std::sync::atomic::{AtomicU32, Ordering};
use std::time::{Duration, Instant};

use glam::DVec3;
use rayon::prelude::*;
use smallvec::SmallVec;

use crate::geometry::{Bounds3, Bounds4, Ray, SlabRay};

/// Centroid bins per axis of the binned SAH: 16 finds splits within a few percent of the
/// full sweep's cost at a fraction of its time (Wald 2007, §3: 8–32 bins).
pub const SAH_BINS: usize = 16;

/// Cost of visiting a node relative to testing one item, in the SAH. A node costs one slab
/// test; an item costs at least its own slab test and a closed-form root (spheres), usually
/// a polynomial root search: 1/8 keeps leaves small, which pays when items are expensive.
pub const TRAVERSAL_COST: f64 = 0.125;

/// Items per leaf at most, unless the items cannot be separated (equal centroids) or the
/// depth limit is reached.
pub const MAX_LEAF_ITEMS: usize = 4;

/// Depth limit of the binary tree the SAH builds (the root has depth 1): a node this deep
/// becomes a leaf whatever it holds. Each level of the 4-wide tree takes at least one binary
/// level, so its depth is bounded too, and with it the fixed traversal stack (`STACK` entries).
pub const MAX_DEPTH: usize = 64;

/// Children of a node of the traversed tree at most.
const WIDTH: usize = 4;

/// Entries of the traversal stack: a node on the path from the root leaves at most
/// `WIDTH − 1` children on the stack (the other is visited next), over at most [`MAX_DEPTH`]
/// levels, and a node's children are all written before the first is taken back.
const STACK: usize = (WIDTH - 1) * MAX_DEPTH + 1;

/// Levels of nodes a tree may have for its traversal to use the short stack
/// ([`SHORT_STACK`] entries) instead of the [`STACK`]-entry one. Safe Rust zeroes a stack
/// array on every traversal, and zeroing the full one was a `memset` call per ray, a
/// measurable share of the small SPD scenes (`paper-notes/bvh.md` §3, eighth pass); their
/// trees, the 66 430-sphere one included, are well within this depth, and deeper trees keep
/// the full stack.
const SHORT_STACK_LEVELS: usize = 15;

/// Entries of the short traversal stack: [`STACK`]'s bound for [`SHORT_STACK_LEVELS`] levels.
const SHORT_STACK: usize = (WIDTH - 1) * SHORT_STACK_LEVELS + 1;

/// Hierarchies over at most this many items are a flat list: one leaf holding the items in
/// index order, whose box is not tested. Every user's items test their own box first (an
/// implicit surface clips the ray to its bounding volume, a polygon to its padded box, a
/// sub-patch to its hull's box), so on such a list the root's slab test only repeats the
/// items' own, and the traversal loop around it cost more than a loop over the items (issue 10:
/// the Whitted torus's one-object BVH took 35 M of its 858 M instructions). Equal to
/// [`MAX_LEAF_ITEMS`]: the SAH keeps most sets this small in one leaf anyway.
pub const FLAT_MAX_ITEMS: usize = MAX_LEAF_ITEMS;

/// Nodes with more items than this build their two halves in parallel: below it, the
/// fork-join overhead of rayon exceeds the work.
const PARALLEL_MIN_ITEMS: usize = 4096;

/// Relative slack of the pruning test: a node is skipped when its entry distance exceeds the
/// nearest hit so far by more than `PRUNE_SLACK_REL × (|entry| + chord)` (chord = length of
/// the ray's path through the node). Items may report hits slightly before their own box
/// entry — an implicit surface starts its root search `ENTRY_MARGIN_REL × (|t0| + chord)`
/// before the entry (`surface::ENTRY_MARGIN_REL`, 10⁻⁹) so that a hit on the entry face is
/// kept — and such a hit must not be pruned by a farther one it ties with. Twice that margin
/// (asserted where the scene builds its hierarchy) keeps the traversal's nearest hit exactly
/// the brute-force one.
pub const PRUNE_SLACK_REL: f64 = 2e-9;

/// A node of the binary tree the SAH build writes (pbrt-v4 `LinearBVHNode`); it lives only
/// until the 4-wide tree is collapsed from it.
#[derive(Clone, Copy, Debug)]
struct BinaryNode {
    bounds: Bounds3,
    /// Leaf: first item in [`Bvh::order`]. Inner: index of the second child (the first child
    /// is the next node).
    offset: u32,
    /// Items in the leaf; 0 for an inner node.
    count: u32,
    /// Split axis of an inner node.
    axis: u8,
}

/// A node of the traversed 4-wide tree: the boxes of its 2–4 children side by side, so that
/// one fetch (four aligned cache lines, 232 bytes of data) tests them all; a leaf child is
/// described here, in its parent, not by a node of its own.
#[derive(Clone, Copy, Debug)]
#[repr(align(64))]
struct Node {
    /// Child `i`'s box in lane `i`; the lanes after the last child are empty.
    bounds: Bounds4,
    /// Child `i`: a leaf's first item in [`Bvh::order`] (`count[i] > 0`) or an inner node's
    /// index (`count[i] == 0`).
    child: [u32; WIDTH],
    /// Items of leaf child `i`; 0 for an inner child.
    count: [u32; WIDTH],
    /// The lanes in visiting order for a ray in direction octant `o` (bit `k` set: the
    /// direction is negative along axis `k`), two bits a lane, the first visited in the low
    /// bits: the order of the binary tree's traversal over the binary nodes this node replaces
    /// ([`Opened::orders`]), then the empty lanes.
    order: [u8; 8],
    /// The used lanes, one bit each (the first `len` bits): the only lanes a ray may cross.
    /// An empty lane's box is `(+∞, −∞)`, which the slab test misses — unless the ray's
    /// numbers are NaN, which the test counts as crossed (so that a NaN end loses no hit),
    /// and an empty lane taken for a child sent the traversal back to the root until its
    /// stack overflowed (a fuzzed camera 1e308 away, every ray NaN).
    used: u8,
}

const _: () = assert!(size_of::<Node>() == 256, "a node is four cache lines");

impl Node {
    /// The children (the lanes before the first empty one).
    #[cfg(test)]
    fn len(&self) -> usize {
        (0..WIDTH)
            .take_while(|&lane| self.bounds.get(lane) != EMPTY)
            .count()
    }
}

/// What `--stats` reports about a hierarchy.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct BvhInfo {
    /// Items (primitives or sub-patches).
    pub items: usize,
    /// Nodes of the 4-wide tree (a leaf is a child slot of its parent, not a node; a flat list
    /// has none).
    pub nodes: usize,
    /// Depth of the deepest leaf, counting the nodes above it and the leaf (a flat list has
    /// depth 1, a root whose children are all leaves depth 2; 0 when empty).
    pub depth: usize,
    /// Wall time of the build (binary tree and collapse).
    pub build: Duration,
}

/// A 4-wide BVH over items `0..n`, item `i` having box `boxes[i]`.
#[derive(Clone, Debug, Default)]
pub struct Bvh {
    /// The 4-wide tree, root first; empty for a flat list.
    nodes: Vec<Node>,
    /// Item indices in leaf order.
    order: Vec<u32>,
    info: BvhInfo,
}

/// An item during the build: its index and box (56 bytes; the centre is recomputed where
/// needed rather than stored, which kept 24 more bytes per item alive during the build).
#[derive(Clone, Copy, Debug)]
struct Item {
    index: u32,
    bounds: Bounds3,
}

impl Item {
    /// The centre of the item's box.
    fn centre(&self) -> DVec3 {
        (self.bounds.min + self.bounds.max) * 0.5
    }
}

/// A slot of the build's node array not written: a subtree over `m` items is given `2m − 1`
/// slots, and one with leaves of several items leaves some of them unused (the collapse never
/// reaches them).
const UNUSED: BinaryNode = BinaryNode {
    bounds: EMPTY,
    offset: 0,
    count: u32::MAX,
    axis: 0,
};

const EMPTY: Bounds3 = Bounds3 {
    min: DVec3::INFINITY,
    max: DVec3::NEG_INFINITY,
};

/// The union of two boxes for the build, by `<` selects: `f64::min`/`max` also order NaNs,
/// which costs a few instructions per component (a fifth of the sphereflake's build time went
/// to them); build boxes are finite or [`EMPTY`], so the answer is the same (up to the sign of
/// a zero corner, which no slab test can tell from the other).
#[inline(always)]
fn grow(a: &Bounds3, b: &Bounds3) -> Bounds3 {
    let lo = |x: f64, y: f64| if y < x { y } else { x };
    let hi = |x: f64, y: f64| if y > x { y } else { x };
    Bounds3 {
        min: DVec3::new(
            lo(a.min.x, b.min.x),
            lo(a.min.y, b.min.y),
            lo(a.min.z, b.min.z),
        ),
        max: DVec3::new(
            hi(a.max.x, b.max.x),
            hi(a.max.y, b.max.y),
            hi(a.max.z, b.max.z),
        ),
    }
}

/// Half the surface area of `b` (the SAH only compares ratios); 0 for an empty box.
fn half_area(b: &Bounds3) -> f64 {
    let d = (b.max - b.min).max(DVec3::ZERO);
    d.x * d.y + d.y * d.z + d.z * d.x
}

/// The build's items: `(id, box)` pairs, each box taken as the box between its two corners, as
/// the slab test reads a box; so every node box has `min ≤ max`, which
/// [`Bounds3::slab_by_sign`] and [`Bounds4::slab_by_sign`] need.
///
/// # Panics
/// If the ids are not strictly increasing (see [`Bvh::with_ids`]).
fn items_of(items: impl IntoIterator<Item = (u32, Bounds3)>) -> Vec<Item> {
    let items = items.into_iter();
    // Reserved for the most items there may be (the aggregate's filter keeps all but the
    // unbounded ones), not grown by doubling: pages reserved and never written cost nothing.
    let (least, most) = items.size_hint();
    let mut out: Vec<Item> = Vec::with_capacity(most.unwrap_or(least));
    for (index, b) in items {
        assert!(
            out.last().is_none_or(|last| last.index < index),
            "ids strictly increasing"
        );
        out.push(Item {
            index,
            bounds: Bounds3::new(b.min.min(b.max), b.min.max(b.max)),
        });
    }
    out
}

/// The binary tree over `items` (reordered into leaf order), its root at index 0. Needs at
/// least one item.
fn build_binary(items: &mut [Item]) -> Vec<BinaryNode> {
    // A binary tree with leaves of at least one item has at most 2n − 1 nodes: each subtree
    // is written in place into its share of them; slots left unused are never reached.
    // Filled in parallel, as the build writes it (first touches of fresh pages, see `collapse`).
    let mut nodes = Vec::with_capacity(2 * items.len() - 1);
    nodes.par_extend(rayon::iter::repeat_n(UNUSED, 2 * items.len() - 1));
    build(items, 0, 1, &mut nodes, 0);
    nodes
}

impl Bvh {
    /// Builds the hierarchy over items `0..boxes.len()`, item `i` in box `boxes[i]`. Boxes must
    /// be finite (the caller keeps unbounded items out); a flat box (zero extent on an axis) is
    /// fine.
    ///
    /// # Panics
    /// If the 4-wide tree would have 2³⁰ nodes or more (a traversal stack entry names a node
    /// and a child in 32 bits): over a billion items.
    pub fn new(boxes: &[Bounds3]) -> Self {
        Self::with_ids((0..).zip(boxes.iter().copied()))
    }

    /// Builds the hierarchy over the items `(id, box)`: every answer (`visit`, `hit`, `blocked`
    /// and the returned item) names an item by its id. The aggregate names its bounded items by
    /// their scene index this way, instead of mapping each item the traversal reaches through a
    /// second table (a random access per item test). Boxes as in [`Bvh::new`].
    ///
    /// # Panics
    /// If the ids are not strictly increasing (ties in [`Bvh::nearest`] go to the lower item,
    /// which must be the lower id), or as [`Bvh::new`].
    pub fn with_ids(items: impl IntoIterator<Item = (u32, Bounds3)>) -> Self {
        let start = Instant::now();
        let mut items = items_of(items);
        let mut bvh = Bvh::default();
        if items.is_empty() {
            return bvh;
        }
        let count = items.len();
        let depth = if items.len() <= FLAT_MAX_ITEMS {
            // The flat list: no node, items in id order (see `traverse`).
            bvh.order = items.iter().map(|it| it.index).collect();
            1
        } else {
            let binary = build_binary(&mut items);
            bvh.order = items.iter().map(|it| it.index).collect();
            // The build's item copies go before the 4-wide nodes are allocated (peak memory).
            drop(items);
            let (nodes, depth) = collapse(&binary);
            bvh.nodes = nodes;
            depth
        };
        bvh.info = BvhInfo {
            items: count,
            nodes: bvh.nodes.len(),
            depth,
            build: start.elapsed(),
        };
        bvh
    }

    /// Whether the items are a flat list (at most [`FLAT_MAX_ITEMS`], no node) rather than a
    /// tree.
    pub fn is_flat(&self) -> bool {
        self.nodes.is_empty()
    }

    /// Nodes, depth and build time.
    pub fn info(&self) -> BvhInfo {
        self.info
    }

    /// Calls `visit(item, t_max)` for the items of every leaf whose box the ray crosses before
    /// the nearest hit so far, in the binary tree's order: near children first, by the sign of
    /// the ray direction along each split axis. `visit` returns the new `t_max` (the nearest hit
    /// so far, pruning farther nodes) or `None` to stop. A flat list (at most
    /// [`FLAT_MAX_ITEMS`] items) calls `visit` for every item, in index order, without a box
    /// test: `visit` must test the item's own box, as every user does. Counts in `visits` the
    /// nodes whose children's boxes are tested, and the single boxes tested again. Allocates
    /// nothing.
    ///
    /// All children of a node are tested there, side by side, and only those the ray crosses
    /// before `t_max` are pushed; a pushed child's box is tested again when it is popped only
    /// if `t_max` fell since it was pushed (a shadow ray's never falls). So the leaves visited,
    /// and their order, are those of the binary tree's traversal testing each node when it pops
    /// it: a child's box lies in every box of the binary nodes the collapse removed above it,
    /// and the slab test is monotone in the box, so those tests could only repeat a yes.
    pub fn traverse(
        &self,
        ray: &Ray,
        range: Range<f64>,
        visits: &mut u64,
        visit: impl FnMut(u32, f64) -> Option<f64>,
    ) {
        self.traverse_with::<true>(ray, range, visits, visit);
    }

    /// [`Bvh::traverse`]; with `PRUNE = false` for a `visit` that never lowers `t_max` (the
    /// any-hit query), whose pruning test would always pass: a box the slab test admits is
    /// entered before the range's end, which `t_max` then stays at.
    ///
    /// The first child in order of a node is visited next without going through the stack: it
    /// was tested at the current `t_max` a moment ago, as it would have been when popped
    /// straight away, so the leaves and their order are unchanged. A stack entry names a child
    /// by its parent and lane (`parent << 2 | lane`), so that a leaf child needs no node of its
    /// own and a stale entry's box is read back from its parent.
    #[inline(always)]
    fn traverse_with<const PRUNE: bool>(
        &self,
        ray: &Ray,
        range: Range<f64>,
        visits: &mut u64,
        mut visit: impl FnMut(u32, f64) -> Option<f64>,
    ) {
        if self.is_flat() {
            // A flat list (or nothing).
            let mut t_max = range.end;
            for &item in &self.order {
                match visit(item, t_max) {
                    Some(t) => t_max = t,
                    None => return,
                }
            }
        } else {
            self.traverse_tree::<PRUNE>(ray, range, visits, visit);
        }
    }

    /// [`Bvh::traverse_with`] on a tree. Not inlined into the queries, so that they stay small
    /// enough to be inlined into their callers, where a flat list (the one-object scenes of
    /// issue 10) then costs no call.
    #[inline(never)]
    fn traverse_tree<const PRUNE: bool>(
        &self,
        ray: &Ray,
        range: Range<f64>,
        visits: &mut u64,
        mut visit: impl FnMut(u32, f64) -> Option<f64>,
    ) {
        let mut t_max = range.end;
        let slab_ray = SlabRay::new(ray);
        let octant = usize::from(ray.dir.x < 0.0)
            | usize::from(ray.dir.y < 0.0) << 1
            | usize::from(ray.dir.z < 0.0) << 2;
        let (start, end) = (range.start, range.end);
        // The children of `node` the ray crosses before `t_max`, one bit a lane.
        let crossed = |node: &Node, t_max: f64| -> u32 {
            let (t0, t1) = node.bounds.slab_by_sign(&slab_ray, start, end);
            let mut mask = 0;
            for lane in 0..WIDTH {
                let (near, far) = (t0[lane], t1[lane]);
                // `crosses` on each lane, without branches: missed when `near > far` (not
                // `near <= far`, which a NaN end would fail), else pruned beyond `t_max`.
                let missed = near > far;
                let hit = if PRUNE {
                    !missed & (near <= t_max + PRUNE_SLACK_REL * (near.abs() + (far - near)))
                } else {
                    !missed
                };
                mask |= u32::from(hit) << lane;
            }
            mask & u32::from(node.used)
        };
        // A tree of `depth − 1` levels of nodes needs `3·(depth − 1) + 1` entries (see `STACK`).
        let mut short = [0u32; SHORT_STACK];
        let mut long;
        let stack: &mut [u32] = if self.info.depth <= SHORT_STACK_LEVELS + 1 {
            &mut short
        } else {
            long = [0u32; STACK];
            &mut long
        };
        let mut top = 0;
        // Entries below `stale` were pushed before `t_max` last fell: retested when popped.
        let mut stale = 0;
        // The node whose children are tested next.
        let mut expand = Some(0usize);
        loop {
            // The child visited next: the first in order of the node just tested, else popped.
            let mut next = None;
            if let Some(index) = expand.take() {
                let node = &self.nodes[index];
                *visits += 1;
                let mask = crossed(node, t_max);
                if mask & mask.wrapping_sub(1) == 0 {
                    // One child crossed or none (the common cases near the leaves): no order.
                    if mask != 0 {
                        next = Some((index as u32) << 2 | mask.trailing_zeros());
                    }
                } else {
                    // Every lane written, the crossed ones kept (an empty lane never is): the
                    // last in order first, so the first crossed one ends on top and is taken
                    // straight back.
                    let order = node.order[octant];
                    for position in (0..WIDTH).rev() {
                        let lane = u32::from(order >> (2 * position)) & 3;
                        stack[top] = (index as u32) << 2 | lane;
                        top += ((mask >> lane) & 1) as usize;
                    }
                    top -= 1;
                    next = Some(stack[top]);
                }
            }
            let entry = match next {
                Some(entry) => entry,
                None => {
                    if top == 0 {
                        return;
                    }
                    top -= 1;
                    let entry = stack[top];
                    if top < stale {
                        stale = top;
                        *visits += 1;
                        let parent = &self.nodes[(entry >> 2) as usize];
                        let bounds = parent.bounds.get((entry & 3) as usize);
                        if !crosses(&bounds, &slab_ray, start..end, t_max) {
                            continue;
                        }
                    }
                    entry
                }
            };
            let parent = &self.nodes[(entry >> 2) as usize];
            let lane = (entry & 3) as usize;
            let count = parent.count[lane];
            if count > 0 {
                let first = parent.child[lane] as usize;
                let before = t_max;
                for &item in &self.order[first..first + count as usize] {
                    match visit(item, t_max) {
                        Some(t) => t_max = t,
                        None => return,
                    }
                }
                if t_max != before {
                    stale = top;
                }
            } else {
                expand = Some(parent.child[lane] as usize);
            }
        }
    }

    /// The nearest hit: `hit(item, t_max)` is each item's own nearest hit over the whole
    /// `range` (`(t, data)`), and the result is the least `(t, item)` over all items — the hit
    /// a loop over every item would keep, ties going to the lower index — with its item. Items
    /// are queried over the whole range, not up to the nearest hit so far, so that each item's
    /// answer does not depend on the visiting order; `t_max` (the nearest hit so far, or the
    /// range's end) lets `hit` skip an item that certainly has no hit at or before it, as the
    /// traversal skips nodes.
    pub fn nearest<H>(
        &self,
        ray: &Ray,
        range: Range<f64>,
        visits: &mut u64,
        mut hit: impl FnMut(u32, f64) -> Option<(f64, H)>,
    ) -> Option<(u32, f64, H)> {
        let mut best: Option<(u32, f64, H)> = None;
        self.traverse(ray, range, visits, |item, t_max| {
            if let Some((t, h)) = hit(item, t_max)
                && precedes(item, t, &best, t_max)
            {
                best = Some((item, t, h));
                return Some(t);
            }
            Some(t_max)
        });
        best
    }

    /// Whether `blocked(item)` holds for any item whose box the ray crosses in `range`; stops
    /// at the first blocker.
    pub fn any(
        &self,
        ray: &Ray,
        range: Range<f64>,
        visits: &mut u64,
        mut blocked: impl FnMut(u32) -> bool,
    ) -> bool {
        let mut found = false;
        self.traverse_with::<false>(ray, range, visits, |item, t_max| {
            if blocked(item) {
                found = true;
                None
            } else {
                Some(t_max)
            }
        });
        found
    }
}

/// Whether the ray enters `bounds` in `range` before `t_max`, the nearest hit so far, up to
/// [`PRUNE_SLACK_REL`] (the pruning test of [`Bvh::traverse`], which tests four boxes at once
/// the same way, lane by lane).
#[inline(always)]
fn crosses(bounds: &Bounds3, ray: &SlabRay, range: Range<f64>, t_max: f64) -> bool {
    bounds
        .slab_by_sign(ray, range.start, range.end)
        .is_some_and(|(near, far)| near <= t_max + PRUNE_SLACK_REL * (near.abs() + (far - near)))
}

/// Whether a hit of `item` at `t` replaces `best` (`None`: the first hit, kept when below
/// `end`): the order of a loop over all items, least `t` first and ties to the lower index.
pub(super) fn precedes<H>(item: u32, t: f64, best: &Option<(u32, f64, H)>, end: f64) -> bool {
    match best {
        None => t < end,
        Some((b, bt, _)) => t < *bt || (t == *bt && item < *b),
    }
}

/// Writes the subtree of `items` (which start at `first` in the final item order) at `depth`
/// into `out`, its `2·items.len() − 1` slots, depth-first from `out[0]`, which is node `base`
/// of the whole array: the first child of an inner node follows it, the second starts the
/// second half of its slots (`2·m − 1` slots for a child over `m` items). The two halves of a
/// large node are built in parallel into their disjoint slots, so nothing is copied and no
/// temporary node array exists.
fn build(items: &mut [Item], first: usize, depth: usize, out: &mut [BinaryNode], base: usize) {
    // The node's box and the box of its items' centres, in one pass.
    let (bounds, centres) = items.iter().fold((EMPTY, EMPTY), |(b, c), it| {
        let centre = it.centre();
        (
            grow(&b, &it.bounds),
            grow(&c, &Bounds3::new(centre, centre)),
        )
    });
    let n = items.len();
    let leaf = BinaryNode {
        bounds,
        offset: first as u32,
        count: n as u32,
        axis: 0,
    };
    if n == 1 || depth >= MAX_DEPTH {
        out[0] = leaf;
        return;
    }
    let ext = centres.max - centres.min;
    let axis = if ext.x >= ext.y && ext.x >= ext.z {
        0
    } else if ext.y >= ext.z {
        1
    } else {
        2
    };
    let mid = if ext[axis] > 0.0 && ext[axis].is_finite() {
        match sah_split(items, &bounds, centres.min[axis], ext[axis], axis) {
            Some(mid) => mid,
            None => {
                out[0] = leaf;
                return;
            }
        }
    } else if n <= MAX_LEAF_ITEMS {
        out[0] = leaf;
        return;
    } else {
        // Equal centres: no split separates them; halve by count so leaves stay small.
        n / 2
    };
    let second = base + 2 * mid;
    out[0] = BinaryNode {
        bounds,
        offset: second as u32,
        count: 0,
        axis: axis as u8,
    };
    let (lo, hi) = items.split_at_mut(mid);
    let (left, right) = out[1..].split_at_mut(2 * mid - 1);
    if n > PARALLEL_MIN_ITEMS {
        rayon::join(
            || build(lo, first, depth + 1, left, base + 1),
            || build(hi, first + mid, depth + 1, right, second),
        );
    } else {
        build(lo, first, depth + 1, left, base + 1);
        build(hi, first + mid, depth + 1, right, second);
    }
}

/// The children of the 4-wide node standing for a binary node: binary nodes, each with the
/// path that leads to it from there (the split axis and side, first or second child, of each
/// binary node the collapse removed above it).
#[derive(Clone, Copy, Debug, PartialEq)]
struct Opened {
    /// The children's binary nodes; `slots[..len]` are used.
    slots: [usize; WIDTH],
    /// The slots of each child's binary subtree (`2m − 1` for `m` items, see [`build`]).
    spans: [usize; WIDTH],
    len: usize,
    /// `(axis, side)` of each step from the opened node to child `i`, `steps[i]` of them.
    path: [[(u8, u8); WIDTH - 1]; WIDTH],
    steps: [usize; WIDTH],
}

impl Opened {
    /// For each direction octant `o` (bit `k`: negative along axis `k`, where the near child of
    /// a split along `k` is the second), the children in the order the binary traversal
    /// reaches them, packed two bits each, the first in the low bits, then the unused lanes.
    /// A child's rank is its path read as a binary number, a step's bit being 1 when it goes
    /// to the far side: no path is the beginning of another, so the first step where two paths
    /// differ decides, as in the binary traversal. Its rank for octant `o` is its rank for
    /// octant 0 with the bits of the steps along the axes negative in `o` flipped.
    fn orders(&self) -> [u8; 8] {
        let mut base = [0usize; WIDTH];
        let mut flip = [[0usize; 3]; WIDTH];
        for lane in 0..WIDTH {
            if lane >= self.len {
                // After every used lane (ranks below 2^(WIDTH − 1)).
                base[lane] = (1 << (WIDTH - 1)) + lane;
                continue;
            }
            for (d, &(axis, side)) in self.path[lane][..self.steps[lane]].iter().enumerate() {
                let bit = 1 << (WIDTH - 2 - d);
                base[lane] |= usize::from(side) * bit;
                flip[lane][usize::from(axis)] |= bit;
            }
        }
        std::array::from_fn(|octant| {
            let rank: [usize; WIDTH] = std::array::from_fn(|lane| {
                (0..3).fold(base[lane], |r, k| r ^ (flip[lane][k] * ((octant >> k) & 1)))
            });
            // Each lane's position: the lanes ranked before it (ranks are distinct).
            let mut packed = 0;
            for (lane, &r) in rank.iter().enumerate() {
                let position = rank.iter().filter(|&&other| other < r).count();
                packed |= (lane as u8) << (2 * position);
            }
            packed
        })
    }
}

/// The children of the 4-wide node standing for binary node `b`: starting from `b` itself, the
/// inner one of largest surface area is replaced by its two children until there are
/// [`WIDTH`] or no inner one is left (Wald et al. 2008, §3.1; Embree's collapse of a binary
/// tree into a wide one). Opening the largest boxes first removes the binary levels a ray is
/// most likely to pass through. The first of equal areas is opened.
fn open(binary: &[BinaryNode], b: usize, span: usize) -> Opened {
    let mut opened = Opened {
        slots: [b; WIDTH],
        spans: [span; WIDTH],
        len: 1,
        path: [[(0, 0); WIDTH - 1]; WIDTH],
        steps: [0; WIDTH],
    };
    // Half the surface area of each inner child, −1 for a leaf (never opened).
    let area = |s: usize| {
        let node = &binary[s];
        if node.count == 0 {
            half_area(&node.bounds)
        } else {
            -1.0
        }
    };
    let mut areas = [area(b), 0.0, 0.0, 0.0];
    while opened.len < WIDTH {
        let mut widest: Option<(usize, f64)> = None;
        for (i, &a) in areas[..opened.len].iter().enumerate() {
            if a >= 0.0 && widest.is_none_or(|(_, w)| a > w) {
                widest = Some((i, a));
            }
        }
        let Some((i, _)) = widest else {
            break;
        };
        let (s, new) = (opened.slots[i], opened.len);
        let axis = binary[s].axis;
        let second = binary[s].offset as usize;
        // The first child's subtree fills the slots between the node and the second child.
        let first_span = second - s - 1;
        opened.spans[new] = opened.spans[i] - 1 - first_span;
        opened.spans[i] = first_span;
        opened.slots[i] = s + 1;
        opened.slots[new] = second;
        opened.path[new] = opened.path[i];
        opened.steps[new] = opened.steps[i] + 1;
        opened.path[i][opened.steps[i]] = (axis, 0);
        opened.path[new][opened.steps[i]] = (axis, 1);
        opened.steps[i] += 1;
        areas[i] = area(s + 1);
        areas[new] = area(opened.slots[new]);
        opened.len += 1;
    }
    opened
}

/// The 4-wide tree standing for the binary tree `binary` (root at 0), root first, each node
/// before its subtrees (depth-first, a node's inner children's subtrees in lane order), and its
/// depth ([`BvhInfo::depth`]). Two passes over the binary tree: the first counts the 4-wide
/// nodes of every subtree, so that the node array is allocated once at its size (reserving for
/// the most nodes there can be and shrinking at the end raised the peak memory of the largest
/// sphereflake: `paper-notes/bvh.md`, seventh pass) and so that the second can write the
/// subtrees of a large node in parallel, each into its own share of the array, as [`build`]
/// writes the binary tree (`paper-notes/bvh.md`, nineteenth session).
fn collapse(binary: &[BinaryNode]) -> (Vec<Node>, usize) {
    let sizes: Vec<AtomicU32> = (0..binary.len()).map(|_| AtomicU32::new(0)).collect();
    let n = count_nodes(binary, 0, binary.len(), &sizes) as usize;
    assert!(n < 1 << 30, "a 4-wide tree of {n} nodes: fewer than 2^30");
    // Filled in parallel: the first touch of fresh pages is most of the cost of a large array.
    let mut nodes = Vec::with_capacity(n);
    nodes.par_extend(rayon::iter::repeat_n(EMPTY_NODE, n));
    let depth = write_nodes(binary, 0, binary.len(), 0, &mut nodes, &sizes);
    (nodes, depth)
}

/// A node before it is written.
const EMPTY_NODE: Node = Node {
    bounds: Bounds4::EMPTY,
    child: [0; WIDTH],
    count: [0; WIDTH],
    order: [0; 8],
    used: 0,
};

/// Whether a binary subtree of `span` slots is large enough for its children to be collapsed
/// in parallel (as [`build`] builds its halves: [`PARALLEL_MIN_ITEMS`]).
fn collapse_in_parallel(span: usize) -> bool {
    span > 2 * PARALLEL_MIN_ITEMS
}

/// The 4-wide nodes standing for the binary subtree of `b` (an inner node or the root, its
/// subtree `span` slots), also stored in `sizes[b]` (and those of the subtrees below).
fn count_nodes(binary: &[BinaryNode], b: usize, span: usize, sizes: &[AtomicU32]) -> u32 {
    let opened = open(binary, b, span);
    let inner = (0..opened.len).filter(|&lane| binary[opened.slots[lane]].count == 0);
    let below: u32 = if collapse_in_parallel(span) {
        inner
            .collect::<Vec<_>>()
            .into_par_iter()
            .map(|lane| count_nodes(binary, opened.slots[lane], opened.spans[lane], sizes))
            .sum()
    } else {
        inner
            .map(|lane| count_nodes(binary, opened.slots[lane], opened.spans[lane], sizes))
            .sum()
    };
    sizes[b].store(1 + below, Ordering::Relaxed);
    1 + below
}

/// Writes the 4-wide node standing for binary node `b` (its subtree `span` slots) at `out[0]`,
/// which is node `base` of the whole array, and its subtrees after it; `out` holds exactly
/// them (`sizes[b]` nodes). Returns the subtree's depth.
fn write_nodes(
    binary: &[BinaryNode],
    b: usize,
    span: usize,
    base: usize,
    out: &mut [Node],
    sizes: &[AtomicU32],
) -> usize {
    let opened = open(binary, b, span);
    let slots = &opened.slots[..opened.len];
    let (node, rest) = out.split_first_mut().expect("a node's share holds it");
    *node = Node {
        bounds: Bounds4::EMPTY,
        child: [0; WIDTH],
        count: [0; WIDTH],
        order: opened.orders(),
        used: (1u8 << slots.len()) - 1,
    };
    // Each inner child's share of `rest`, in lane order (on the stack: this runs once a node).
    let mut tasks: SmallVec<[_; WIDTH]> = SmallVec::new();
    let mut rest = rest;
    let mut next = base + 1;
    for (lane, &s) in slots.iter().enumerate() {
        let child = &binary[s];
        node.bounds.set(lane, &child.bounds);
        if child.count == 0 {
            let size = sizes[s].load(Ordering::Relaxed) as usize;
            let (share, after) = rest.split_at_mut(size);
            rest = after;
            node.child[lane] = next as u32;
            tasks.push((s, opened.spans[lane], next, share));
            next += size;
        } else {
            // A leaf's items.
            node.child[lane] = child.offset;
            node.count[lane] = child.count;
        }
    }
    let below = if collapse_in_parallel(span) {
        tasks
            .into_vec()
            .into_par_iter()
            .map(|(s, span, at, share)| write_nodes(binary, s, span, at, share, sizes))
            .max()
    } else {
        tasks
            .into_iter()
            .map(|(s, span, at, share)| write_nodes(binary, s, span, at, share, sizes))
            .max()
    };
    below.map_or(2, |d| 2.max(1 + d))
}

/// The cheapest binned SAH split of `items` along `axis` (centres spanning `lo .. lo + ext`):
/// partitions `items` and returns the size of the lower part, or `None` when a leaf is cheaper
/// (only for at most [`MAX_LEAF_ITEMS`] items).
fn sah_split(
    items: &mut [Item],
    bounds: &Bounds3,
    lo: f64,
    ext: f64,
    axis: usize,
) -> Option<usize> {
    let scale = SAH_BINS as f64 / ext;
    let bin_of = |it: &Item| -> usize {
        // A float-to-int `as` saturates (NaN → 0): any centre lands in some bin.
        (((it.centre()[axis] - lo) * scale) as usize).min(SAH_BINS - 1)
    };
    let mut counts = [0usize; SAH_BINS];
    let mut boxes = [EMPTY; SAH_BINS];
    for it in items.iter() {
        let b = bin_of(it);
        counts[b] += 1;
        // `f64::min`/`max` here, not `grow`'s `<` selects: a select written back to the
        // array it read became a masked store (`vmaskmovpd`), slow on this machine's AMD
        // cores and not forwarded to the next item's load of the same bin — a quarter of
        // `sah_split`'s samples (`paper-notes/bvh.md`, twenty-first session). Build boxes hold
        // no NaN, so the union is the same (up to the sign of a zero corner, as in `grow`).
        let bin = &mut boxes[b];
        bin.min = bin.min.min(it.bounds.min);
        bin.max = bin.max.max(it.bounds.max);
    }
    // Only the non-empty bins are swept: a split between two empty bins has the same items
    // on each side, so the same cost, as the split just after the last non-empty bin below
    // it, and that one comes first (the first of equal costs is kept): the same split as a
    // sweep over all bins, without the empty ones' work (most nodes near the leaves hold a
    // few items in as many bins).
    let mut used = [0usize; SAH_BINS];
    let mut m = 0;
    for (b, &count) in counts.iter().enumerate() {
        if count > 0 {
            used[m] = b;
            m += 1;
        }
    }
    // Sweep from above: the area and count of the used bins `used[k..]` for each k.
    let mut above = [(0.0, 0usize); SAH_BINS];
    let (mut acc, mut cnt) = (EMPTY, 0);
    for k in (1..m).rev() {
        acc = grow(&acc, &boxes[used[k]]);
        cnt += counts[used[k]];
        above[k] = (half_area(&acc), cnt);
    }
    // Costs are left multiplied by the node's area, so a degenerate (zero-area) node compares
    // without dividing by zero.
    let area = half_area(bounds);
    let (mut acc, mut cnt) = (EMPTY, 0);
    let mut best = (f64::INFINITY, 0);
    for k in 0..m.saturating_sub(1) {
        acc = grow(&acc, &boxes[used[k]]);
        cnt += counts[used[k]];
        let (area_hi, cnt_hi) = above[k + 1];
        let cost = TRAVERSAL_COST * area + cnt as f64 * half_area(&acc) + cnt_hi as f64 * area_hi;
        if cost < best.0 {
            best = (cost, used[k]);
        }
    }
    let n = items.len();
    if n <= MAX_LEAF_ITEMS && n as f64 * area <= best.0 {
        return None;
    }
    // Partition in place: bins ≤ best first.
    let mut mid = 0;
    for i in 0..n {
        if bin_of(&items[i]) <= best.1 {
            items.swap(i, mid);
            mid += 1;
        }
    }
    if mid == 0 || mid == n {
        // Unreachable with a positive centre extent (the lowest and highest centres fall in
        // the first and last bins); halve by count rather than recurse forever.
        return Some(n / 2);
    }
    Some(mid)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn unit_box(x: f64) -> Bounds3 {
        Bounds3::new(DVec3::new(x, 0.0, 0.0), DVec3::new(x + 1.0, 1.0, 1.0))
    }

    /// A ray whose numbers are NaN crosses every used lane (the slab test keeps NaN ends),
    /// so the traversal visits every item once — and no empty lane: it used to take one for
    /// a child, go back to the root and overflow its stack (caught by the scene fuzzer: a
    /// camera looking at a point 1e308 away made every ray NaN).
    #[test]
    fn a_nan_ray_visits_every_item_once_and_no_empty_lane() {
        // 4-wide nodes over 2–3 children have empty lanes: 7, 9 and 50 items.
        for n in [7u32, 9, 50] {
            let boxes: Vec<Bounds3> = (0..n).map(|i| unit_box(f64::from(i) * 1.5)).collect();
            let bvh = Bvh::new(&boxes);
            assert!(!bvh.nodes.is_empty(), "{n} items make a tree");
            for dir in [DVec3::NAN, DVec3::new(f64::NAN, 0.0, 1.0), DVec3::ZERO] {
                let ray = Ray::new(DVec3::new(0.5, 0.5, -3.0), dir);
                let mut seen = vec![0u32; n as usize];
                bvh.traverse(&ray, 0.0..f64::INFINITY, &mut 0, |i, t_max| {
                    seen[i as usize] += 1;
                    Some(t_max)
                });
                assert!(seen.iter().all(|&k| k <= 1), "{n} items, {dir}: {seen:?}");
            }
        }
    }

    #[test]
    fn visits_exactly_the_crossed_boxes_front_to_back() {
        // A row of unit boxes along x at x = 0, 2, 4, …, 18.
        let boxes: Vec<Bounds3> = (0..10).map(|i| unit_box(2.0 * i as f64)).collect();
        let bvh = Bvh::new(&boxes);
        let mut visits = 0;
        // A vertical ray through box 3 only.
        let ray = Ray::new(DVec3::new(6.5, 0.5, 5.0), DVec3::new(0.0, 0.0, -1.0));
        let mut seen = Vec::new();
        bvh.traverse(&ray, 0.0..f64::INFINITY, &mut visits, |i, t| {
            seen.push(i);
            Some(t)
        });
        assert_eq!(seen, vec![3], "only the box under the ray");
        // Along +x: all ten, in order; along −x: in reverse order.
        for (dir, origin) in [(DVec3::X, -1.0), (DVec3::NEG_X, 30.0)] {
            let ray = Ray::new(DVec3::new(origin, 0.5, 0.5), dir);
            seen.clear();
            bvh.traverse(&ray, 0.0..f64::INFINITY, &mut visits, |i, t| {
                seen.push(i);
                Some(t)
            });
            let mut expected: Vec<u32> = (0..10).collect();
            if dir.x < 0.0 {
                expected.reverse();
            }
            assert_eq!(seen, expected, "front to back along {dir}");
        }
        // Pruning: a hit at t = 4 stops the boxes beyond it.
        let ray = Ray::new(DVec3::new(-1.0, 0.5, 0.5), DVec3::X);
        seen.clear();
        bvh.traverse(&ray, 0.0..f64::INFINITY, &mut visits, |i, _| {
            seen.push(i);
            Some(4.0)
        });
        assert_eq!(seen, vec![0, 1], "pruned after the hit: {seen:?}");
        assert!(visits > 0, "visits are counted");
    }

    /// An item box given with a corner swapped is the box between its corners, as the slab
    /// test reads it: the node boxes, tested by `slab_by_sign`, need `min ≤ max` (without the
    /// ordering in `Bvh::new` the ray below misses the leaf of box 3).
    #[test]
    fn an_inverted_item_box_is_found() {
        let mut boxes: Vec<Bounds3> = (0..10).map(|i| unit_box(2.0 * i as f64)).collect();
        let b = boxes[3];
        boxes[3] = Bounds3::new(
            DVec3::new(b.max.x, b.min.y, b.max.z),
            DVec3::new(b.min.x, b.max.y, b.min.z),
        );
        let bvh = Bvh::new(&boxes);
        for d in [DVec3::NEG_Z, DVec3::new(0.01, 0.02, -1.0)] {
            let ray = Ray::new(DVec3::new(6.5, 0.5, 5.0), d);
            let mut seen = Vec::new();
            bvh.traverse(&ray, 0.0..f64::INFINITY, &mut 0, |i, t| {
                seen.push(i);
                Some(t)
            });
            assert_eq!(seen, vec![3], "the box under the ray along {d}");
        }
    }

    #[test]
    fn relabelled_items_answer_by_their_ids() {
        // The row of boxes along x, items renamed 3k + 1: a ray along +x meets them in order,
        // the nearest (every item "hit" at 1) is the lowest id, the blocker any id.
        let boxes: Vec<Bounds3> = (0..10).map(|i| unit_box(2.0 * i as f64)).collect();
        let ids: Vec<u32> = (0..10).map(|k| 3 * k + 1).collect();
        let bvh = Bvh::with_ids(ids.iter().copied().zip(boxes.iter().copied()));
        let ray = Ray::new(DVec3::new(-1.0, 0.5, 0.5), DVec3::X);
        let mut seen = Vec::new();
        bvh.traverse(&ray, 0.0..f64::INFINITY, &mut 0, |i, t| {
            seen.push(i);
            Some(t)
        });
        assert_eq!(seen, ids, "ids in traversal order");
        let hit = bvh.nearest(&ray, 0.0..f64::INFINITY, &mut 0, |i, _| Some((1.0, i)));
        assert_eq!(hit.map(|h| h.0), Some(1), "the tie goes to the lowest id");
        assert!(
            bvh.any(&ray, 0.0..f64::INFINITY, &mut 0, |i| i == 28),
            "id 28 blocks"
        );
    }

    #[test]
    #[should_panic(expected = "ids strictly increasing")]
    fn ids_out_of_order_are_refused() {
        let boxes: Vec<Bounds3> = (0..6).map(|i| unit_box(2.0 * i as f64)).collect();
        Bvh::with_ids([0, 1, 2, 4, 3, 5].into_iter().zip(boxes));
    }

    #[test]
    fn equal_boxes_split_to_small_leaves_within_the_depth_limit() {
        // 1000 copies of one box: no split separates them, yet leaves stay small.
        let boxes = vec![unit_box(0.0); 1000];
        let bvh = Bvh::new(&boxes);
        assert!(bvh.info().depth <= MAX_DEPTH);
        assert!(
            bvh.nodes
                .iter()
                .all(|n| n.count.iter().all(|&c| c as usize <= MAX_LEAF_ITEMS)),
            "leaves of at most {MAX_LEAF_ITEMS}"
        );
        let ray = Ray::new(DVec3::new(0.5, 0.5, 5.0), DVec3::NEG_Z);
        let mut n = 0;
        let mut visits = 0;
        assert!(!bvh.any(&ray, 0.0..f64::INFINITY, &mut visits, |_| {
            n += 1;
            false
        }));
        assert_eq!(n, 1000, "every copy visited once");
    }

    #[test]
    fn nearest_breaks_ties_by_the_lower_index() {
        // Boxes 0 and 1 sharing the face x = 1; a ray from +x hits box 1 first, box 0 at the
        // same t (both report the shared face).
        let boxes = [
            unit_box(0.0),
            Bounds3::new(DVec3::new(1.0, 0.0, 0.0), DVec3::ONE),
        ];
        let bvh = Bvh::new(&boxes);
        let ray = Ray::new(DVec3::new(5.0, 0.5, 0.5), DVec3::NEG_X);
        let mut visits = 0;
        let hit = bvh.nearest(&ray, 0.0..f64::INFINITY, &mut visits, |i, _| Some((4.0, i)));
        assert_eq!(hit.map(|h| h.0), Some(0), "the tie goes to item 0");
    }

    /// The binary tree the SAH build writes over `boxes` and its item order, as [`Bvh::new`]
    /// builds it before the collapse.
    fn binary_tree(boxes: &[Bounds3]) -> (Vec<BinaryNode>, Vec<u32>) {
        let mut items = items_of((0..).zip(boxes.iter().copied()));
        let binary = build_binary(&mut items);
        (binary, items.iter().map(|it| it.index).collect())
    }

    /// The binary tree's traversal before children were tested at their parent (issue 12,
    /// third pass): pop a node, test its box, prune, and push both children of an inner node,
    /// the far one (by the sign of the direction along the split axis) first. The leaves it
    /// visits and their order are what [`Bvh::traverse`] on the collapsed tree must reproduce.
    fn pop_then_test(
        binary: &[BinaryNode],
        order: &[u32],
        ray: &Ray,
        range: Range<f64>,
        mut visit: impl FnMut(u32, f64) -> Option<f64>,
    ) {
        let slab_ray = SlabRay::new(ray);
        let mut t_max = range.end;
        let mut stack = vec![0u32];
        while let Some(index) = stack.pop() {
            let node = &binary[index as usize];
            let Some((near, far)) = node.bounds.slab(&slab_ray, range.start, range.end) else {
                continue;
            };
            if near > t_max + PRUNE_SLACK_REL * (near.abs() + (far - near)) {
                continue;
            }
            if node.count > 0 {
                let first = node.offset as usize;
                for &item in &order[first..first + node.count as usize] {
                    match visit(item, t_max) {
                        Some(t) => t_max = t,
                        None => return,
                    }
                }
            } else {
                let (first, second) = (index + 1, node.offset);
                if ray.dir[node.axis as usize] < 0.0 {
                    stack.extend([first, second]);
                } else {
                    stack.extend([second, first]);
                }
            }
        }
    }

    /// A traversal's callback: an item and the `t_max` it sees, the new `t_max` back.
    type Visit<'a> = dyn FnMut(u32, f64) -> Option<f64> + 'a;

    #[test]
    fn the_4_wide_traversal_visits_the_leaves_of_the_binary_pop_then_test() {
        // Random boxes (some flat, some sharing faces on a unit grid); random rays; each item
        // "hit" at its box entry plus a per-item offset, so `t_max` falls during the traversal
        // and the retest of stale stack entries is exercised. The calls to `visit` — items,
        // order and the `t_max` each saw — must be those of the binary tree's pop-then-test
        // traversal, on trees whose nodes have 2, 3 and 4 children, leaves mixed with inner
        // children among them; the last tree is large enough to be collapsed in parallel.
        use rand::{Rng, SeedableRng};
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(12);
        let mut widths = [0usize; WIDTH + 1];
        let mut mixed = 0;
        for round in 0..21 {
            let n = if round == 20 {
                PARALLEL_MIN_ITEMS + 1000
            } else {
                5 + round * 13
            };
            assert_eq!(collapse_in_parallel(2 * n - 1), round == 20);
            let boxes: Vec<Bounds3> = (0..n)
                .map(|_| {
                    let lo = DVec3::new(
                        f64::from(rng.gen_range(-6..6)),
                        f64::from(rng.gen_range(-6..6)),
                        rng.gen_range(-6.0..6.0),
                    );
                    let size = DVec3::new(
                        1.0,
                        1.0,
                        rng.gen_range(0.0..2.0) * f64::from(rng.gen_range(0..2)),
                    );
                    Bounds3::new(lo, lo + size)
                })
                .collect();
            let bvh = Bvh::new(&boxes);
            let (binary, order) = binary_tree(&boxes);
            assert_eq!(bvh.order, order, "the collapse keeps the leaf order");
            assert!(!bvh.nodes.is_empty(), "a tree, not a flat list");
            for node in &bvh.nodes {
                let len = node.len();
                widths[len] += 1;
                let leaves = node.count[..len].iter().filter(|&&c| c > 0).count();
                mixed += usize::from(leaves > 0 && leaves < len);
            }
            for k in 0..200 {
                let mut o = DVec3::new(
                    rng.gen_range(-10.0..10.0),
                    rng.gen_range(-10.0..10.0),
                    rng.gen_range(-10.0..10.0),
                );
                let mut d = DVec3::new(
                    rng.gen_range(-1.0..1.0),
                    rng.gen_range(-1.0..1.0),
                    rng.gen_range(-1.0..1.0),
                );
                if k % 4 == 0 {
                    // In a grid plane x = const, which boxes share as faces: NaN slabs.
                    d.x = 0.0;
                    o.x = f64::from(rng.gen_range(-6..6));
                }
                let ray = Ray::new(o, d);
                let stop_at = if k % 5 == 0 {
                    Some(rng.gen_range(0..n) as u32)
                } else {
                    None
                };
                let calls = |traversal: &dyn Fn(&mut Visit<'_>)| {
                    let mut seen = Vec::new();
                    traversal(&mut |item, t_max| {
                        seen.push((item, t_max));
                        if Some(item) == stop_at {
                            return None;
                        }
                        let entry = boxes[item as usize].intersect_ray(&ray, 0.0..f64::INFINITY);
                        Some(
                            entry.map_or(t_max, |e| t_max.min(e.start + 0.1 * f64::from(item % 7))),
                        )
                    });
                    seen
                };
                let fast = calls(&|f| bvh.traverse(&ray, 0.0..f64::INFINITY, &mut 0, f));
                let slow = calls(&|f| pop_then_test(&binary, &order, &ray, 0.0..f64::INFINITY, f));
                assert_eq!(fast, slow, "visits of {ray:?} over {n} boxes");
                // The any-hit traversal reaches the same leaves in the same order.
                let mut any = Vec::new();
                bvh.any(&ray, 0.0..f64::INFINITY, &mut 0, |i| {
                    any.push(i);
                    Some(i) == stop_at
                });
                let mut all = Vec::new();
                pop_then_test(&binary, &order, &ray, 0.0..f64::INFINITY, |i, t| {
                    all.push(i);
                    (Some(i) != stop_at).then_some(t)
                });
                assert_eq!(any, all, "any-hit visits of {ray:?} over {n} boxes");
            }
        }
        assert!(
            widths[2] > 0 && widths[3] > 0 && widths[4] > 0 && mixed > 0,
            "nodes of 2, 3 and 4 children ({widths:?}), {mixed} mixing leaves and inner nodes"
        );
    }

    #[test]
    fn a_flat_list_visits_every_item_in_index_order_without_a_box_test() {
        // FLAT_MAX_ITEMS boxes far from the ray: each item is still offered (it tests its own
        // box), in index order, and no node box is tested.
        let boxes: Vec<Bounds3> = (0..FLAT_MAX_ITEMS)
            .rev()
            .map(|i| unit_box(2.0 * i as f64))
            .collect();
        let bvh = Bvh::new(&boxes);
        assert_eq!(
            (bvh.info().nodes, bvh.info().depth),
            (0, 1),
            "no node, one leaf"
        );
        let ray = Ray::new(DVec3::new(0.5, 50.0, 0.5), DVec3::Y);
        let (mut visits, mut seen) = (0, Vec::new());
        bvh.traverse(&ray, 0.0..f64::INFINITY, &mut visits, |i, t| {
            seen.push(i);
            Some(t)
        });
        assert_eq!(seen, (0..FLAT_MAX_ITEMS as u32).collect::<Vec<_>>());
        assert_eq!(visits, 0, "no box tested");
        // One more item makes a tree, whose boxes the same ray misses.
        let boxes: Vec<Bounds3> = (0..=FLAT_MAX_ITEMS)
            .map(|i| unit_box(2.0 * i as f64))
            .collect();
        let bvh = Bvh::new(&boxes);
        assert!(bvh.info().nodes > 0, "a tree");
        seen.clear();
        bvh.traverse(&ray, 0.0..f64::INFINITY, &mut visits, |i, t| {
            seen.push(i);
            Some(t)
        });
        assert!(seen.is_empty(), "the tree prunes at its root: {seen:?}");
        assert_eq!(visits, 1, "the root's children only");
    }

    /// Checks the subtree of node `i` and returns its node count and depth: every lane up to
    /// `len` holds its child's boxes (a leaf's items, an inner node's lanes), the lanes beyond
    /// are empty, inner children come after their parent, and each octant's order lists every
    /// child once. Marks the items seen.
    fn check_subtree(bvh: &Bvh, boxes: &[Bounds3], i: usize, seen: &mut [bool]) -> (usize, usize) {
        let node = &bvh.nodes[i];
        let holds = |outer: &Bounds3, inner: &Bounds3| {
            outer.min.cmple(inner.min).all() && outer.max.cmpge(inner.max).all()
        };
        let len = node.len();
        assert!((2..=WIDTH).contains(&len), "node {i}: {len} children");
        for order in node.order {
            let mut lanes: Vec<u8> = (0..len).map(|p| (order >> (2 * p)) & 3).collect();
            lanes.sort_unstable();
            assert_eq!(lanes, (0..len as u8).collect::<Vec<_>>(), "node {i}: order");
        }
        let (mut count, mut depth) = (1, 2);
        for lane in 0..WIDTH {
            let b = node.bounds.get(lane);
            if lane >= len {
                assert_eq!(b, EMPTY, "node {i}: lane {lane} empty");
                continue;
            }
            if node.count[lane] > 0 {
                let first = node.child[lane] as usize;
                for &item in &bvh.order[first..first + node.count[lane] as usize] {
                    assert!(!seen[item as usize], "item {item} in two leaves");
                    seen[item as usize] = true;
                    assert!(holds(&b, &boxes[item as usize]), "node {i} holds {item}");
                }
            } else {
                let c = node.child[lane] as usize;
                assert!(c > i, "node {i}: child {c} after its parent");
                for inner in 0..bvh.nodes[c].len() {
                    assert!(holds(&b, &bvh.nodes[c].bounds.get(inner)), "{i} holds {c}");
                }
                let (n, d) = check_subtree(bvh, boxes, c, seen);
                count += n;
                depth = depth.max(1 + d);
            }
        }
        (count, depth)
    }

    #[test]
    fn the_collapsed_tree_holds_every_item_once() {
        // Above the parallel threshold, with single-item leaves (distinct boxes) and with
        // leaves of several items (groups of equal boxes: unused slots of the binary build
        // never reached), and a few items (sequential).
        use rand::{Rng, SeedableRng};
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(12);
        let distinct: Vec<Bounds3> = (0..PARALLEL_MIN_ITEMS + 3000)
            .map(|_| {
                let lo = DVec3::new(
                    rng.gen_range(-50.0..50.0),
                    rng.gen_range(-50.0..50.0),
                    rng.gen_range(-50.0..50.0),
                );
                Bounds3::new(lo, lo + DVec3::splat(rng.gen_range(0.0..2.0)))
            })
            .collect();
        let grouped: Vec<Bounds3> = (0..PARALLEL_MIN_ITEMS + 3000)
            .map(|i| unit_box((i / 7) as f64 * 0.5))
            .collect();
        let few: Vec<Bounds3> = distinct[..40].to_vec();
        for (name, boxes) in [("distinct", distinct), ("grouped", grouped), ("few", few)] {
            let bvh = Bvh::new(&boxes);
            let mut seen = vec![false; boxes.len()];
            let (count, depth) = check_subtree(&bvh, &boxes, 0, &mut seen);
            assert_eq!(count, bvh.nodes.len(), "{name}: every node reached once");
            assert!(seen.iter().all(|&s| s), "{name}: every item in a leaf");
            assert_eq!(
                (bvh.info().nodes, bvh.info().depth),
                (count, depth),
                "{name}: info"
            );
            // A node has fewer than four children only when its binary subtree ran out of
            // inner nodes to open: all its children are leaves.
            for (i, node) in bvh.nodes.iter().enumerate() {
                let len = node.len();
                assert!(
                    len == WIDTH || node.count[..len].iter().all(|&c| c > 0),
                    "{name}: node {i} has {len} children, not all leaves"
                );
            }
        }
    }

    /// A binary node for the hand-written trees below: an inner node with its second child at
    /// `second` along `axis`, or a leaf of one item.
    fn inner(bounds: Bounds3, second: u32, axis: u8) -> BinaryNode {
        BinaryNode {
            bounds,
            offset: second,
            count: 0,
            axis,
        }
    }

    fn leaf(bounds: Bounds3, item: u32) -> BinaryNode {
        BinaryNode {
            bounds,
            offset: item,
            count: 1,
            axis: 0,
        }
    }

    fn cube(lo: [f64; 3], hi: [f64; 3]) -> Bounds3 {
        Bounds3::new(DVec3::from_array(lo), DVec3::from_array(hi))
    }

    /// The binary tree root(x) → A(y) → (A1(x) → (a, b), c); B(z) → (d, e), depth-first, with
    /// `b_box` as B's box and its two leaves inside it.
    fn hand_tree(b_box: Bounds3) -> Vec<BinaryNode> {
        let a1 = cube([0.0; 3], [8.0, 4.0, 4.0]);
        let a = cube([0.0; 3], [8.0, 5.0, 4.0]);
        let (blo, bhi) = (b_box.min, b_box.max);
        let bmid = (blo.z + bhi.z) / 2.0;
        vec![
            inner(a.union(&b_box), 6, 0),
            inner(a, 5, 1),
            inner(a1, 4, 0),
            leaf(cube([0.0; 3], [4.0; 3]), 0),
            leaf(cube([4.0, 0.0, 0.0], [8.0, 4.0, 4.0]), 1),
            leaf(cube([0.0, 4.0, 0.0], [1.0, 5.0, 1.0]), 2),
            inner(b_box, 8, 2),
            leaf(Bounds3::new(blo, DVec3::new(bhi.x, bhi.y, bmid)), 3),
            leaf(Bounds3::new(DVec3::new(blo.x, blo.y, bmid), bhi), 4),
        ]
    }

    /// The packed visiting order of lanes `lanes` (first visited first).
    fn packed(lanes: [u8; 4]) -> u8 {
        lanes[0] | lanes[1] << 2 | lanes[2] << 4 | lanes[3] << 6
    }

    #[test]
    fn the_collapse_opens_the_child_of_largest_area_and_keeps_the_binary_order() {
        // B small (half area 7 < A1's 80): A is opened, then A1; B stays a child.
        let small = hand_tree(cube([10.0, 0.0, 0.0], [11.0, 3.0, 1.0]));
        let opened = open(&small, 0, small.len());
        assert_eq!((opened.slots, opened.len), ([3, 6, 5, 4], 4), "a, B, c, b");
        assert_eq!(opened.spans, [1, 3, 1, 1], "B's subtree is B, d and e");
        // All directions positive: A before B, A1 before c, a before b.
        assert_eq!(opened.orders()[0], packed([0, 3, 2, 1]));
        // x negative: B first, then A; in A1 (split along x) b before a; then c.
        assert_eq!(opened.orders()[1], packed([1, 3, 0, 2]));
        // y negative: in A (split along y) c before A1.
        assert_eq!(opened.orders()[2], packed([2, 0, 3, 1]));
        // z only: as all positive (no split of these four along z).
        assert_eq!(opened.orders()[4], packed([0, 3, 2, 1]));
        // B large (half area 800 > A's 92): B is opened first, then A; A1 stays a child.
        let large = hand_tree(cube([10.0, 0.0, 0.0], [30.0, 20.0, 10.0]));
        let opened = open(&large, 0, large.len());
        assert_eq!((opened.slots, opened.len), ([2, 7, 8, 5], 4), "A1, d, e, c");
        assert_eq!(opened.orders()[0], packed([0, 3, 1, 2]));
        // z negative: e before d.
        assert_eq!(opened.orders()[4], packed([0, 3, 2, 1]));
        // A node over leaves only keeps fewer children: B alone opens into d and e; the
        // empty lanes come last in every order.
        let opened = open(&large, 6, 3);
        assert_eq!((&opened.slots[..2], opened.len), (&[7, 8][..], 2), "d, e");
        assert_eq!(opened.orders()[0], packed([0, 1, 2, 3]));
        assert_eq!(opened.orders()[4], packed([1, 0, 2, 3]));
        let (nodes, depth) = collapse(&small);
        assert_eq!((nodes.len(), depth), (2, 3), "root and B; leaves under B");
        assert_eq!(
            (nodes[0].child, nodes[0].count),
            ([0, 1, 2, 1], [1, 0, 1, 1]),
            "items a, c, b in the root, B its node 1"
        );
    }

    #[test]
    fn a_tree_at_the_depth_limit_stays_within_the_stack() {
        // Boxes at x = 2^k: the SAH splits one box off the top at each level, so the binary
        // tree reaches MAX_DEPTH, and a ray along x crosses every box, leaving children on the
        // stack at every level.
        let boxes: Vec<Bounds3> = (0..200).map(|k| unit_box(2f64.powi(k))).collect();
        let bvh = Bvh::new(&boxes);
        let (binary, order) = binary_tree(&boxes);
        let ray = Ray::new(DVec3::new(-1.0, 0.5, 0.5), DVec3::X);
        let mut seen = Vec::new();
        bvh.traverse(&ray, 0.0..f64::INFINITY, &mut 0, |i, t| {
            seen.push(i);
            Some(t)
        });
        let mut expected = Vec::new();
        pop_then_test(&binary, &order, &ray, 0.0..f64::INFINITY, |i, t| {
            expected.push(i);
            Some(t)
        });
        assert_eq!(seen, expected, "the binary order");
        seen.sort_unstable();
        assert_eq!(seen, (0..200).collect::<Vec<_>>(), "every box once");
        assert!(
            bvh.info().depth >= MAX_DEPTH / 3,
            "a deep tree: {:?}",
            bvh.info()
        );
    }

    /// A tree of `levels` nodes in a chain that fills the traversal stack as far as it can:
    /// every node's four children are the unit cube, lane 0 the next node (visited first) and
    /// lanes 1–3 leaves of one item each, which stay on the stack while the chain goes down;
    /// the last node has four leaves.
    fn stack_filling_chain(levels: usize) -> Bvh {
        let cube = unit_box(0.0);
        let mut nodes = Vec::new();
        let mut item = 0;
        for level in 0..levels {
            let mut node = Node {
                bounds: Bounds4::EMPTY,
                child: [0; WIDTH],
                count: [0; WIDTH],
                order: [packed([0, 1, 2, 3]); 8],
                used: 0b1111,
            };
            for lane in 0..WIDTH {
                node.bounds.set(lane, &cube);
                if lane == 0 && level + 1 < levels {
                    node.child[0] = (level + 1) as u32;
                } else {
                    (node.child[lane], node.count[lane]) = (item, 1);
                    item += 1;
                }
            }
            nodes.push(node);
        }
        Bvh {
            nodes,
            order: (0..item).collect(),
            info: BvhInfo {
                items: item as usize,
                nodes: levels,
                depth: levels + 1,
                build: Duration::ZERO,
            },
        }
    }

    #[test]
    fn trees_filling_the_short_stack_stay_within_it() {
        // At the short stack's limit the last node writes its four children at entries
        // 3·(levels − 1) to 3·levels, the short stack's last; one level more takes the long
        // stack. A stack one entry short panics here on an index out of bounds.
        for levels in [
            1,
            2,
            SHORT_STACK_LEVELS,
            SHORT_STACK_LEVELS + 1,
            MAX_DEPTH - 1,
        ] {
            let bvh = stack_filling_chain(levels);
            let n = bvh.info().items as u32;
            let ray = Ray::new(DVec3::new(-1.0, 0.5, 0.5), DVec3::X);
            let mut seen = Vec::new();
            bvh.traverse(&ray, 0.0..f64::INFINITY, &mut 0, |i, t| {
                seen.push(i);
                Some(t)
            });
            seen.sort_unstable();
            assert_eq!(
                seen,
                (0..n).collect::<Vec<_>>(),
                "every leaf once, {levels} levels"
            );
            let mut tested = 0;
            let found = bvh.any(&ray, 0.0..f64::INFINITY, &mut 0, |_| {
                tested += 1;
                tested == n
            });
            assert!(
                found,
                "the any-hit traversal reaches the last leaf, {levels} levels"
            );
        }
    }

    /// The split of the sweep over every bin, empty ones included (before issue 12's fifth
    /// pass): the best bin and its cost, `None` when no split has items on both sides.
    fn full_sweep_split(items: &[Item], bounds: &Bounds3, axis: usize) -> Option<(usize, f64)> {
        let centres = items.iter().fold(EMPTY, |c, it| {
            Bounds3::new(c.min.min(it.centre()), c.max.max(it.centre()))
        });
        let (lo, ext) = (centres.min[axis], centres.max[axis] - centres.min[axis]);
        let scale = SAH_BINS as f64 / ext;
        let mut counts = [0usize; SAH_BINS];
        let mut boxes = [EMPTY; SAH_BINS];
        for it in items {
            let b = (((it.centre()[axis] - lo) * scale) as usize).min(SAH_BINS - 1);
            counts[b] += 1;
            boxes[b] = boxes[b].union(&it.bounds);
        }
        let area = half_area(bounds);
        let mut best: Option<(usize, f64)> = None;
        for b in 0..SAH_BINS - 1 {
            let below = boxes[..=b].iter().fold(EMPTY, |a, x| a.union(x));
            let above = boxes[b + 1..].iter().fold(EMPTY, |a, x| a.union(x));
            let (n_lo, n_hi): (usize, usize) =
                (counts[..=b].iter().sum(), counts[b + 1..].iter().sum());
            if n_lo == 0 || n_hi == 0 {
                continue;
            }
            let cost = TRAVERSAL_COST * area
                + n_lo as f64 * half_area(&below)
                + n_hi as f64 * half_area(&above);
            if best.is_none_or(|(_, c)| cost < c) {
                best = Some((b, cost));
            }
        }
        best
    }

    #[test]
    fn sah_split_over_the_used_bins_is_the_full_sweeps_split() {
        // Random sets of 5–40 boxes (few items in many bins, the case the skipped empty bins
        // are for), some sharing centres: the partition must be the full sweep's best bin.
        use rand::{Rng, SeedableRng};
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(12);
        for round in 0..400 {
            let n = 5 + round % 36;
            let mut items: Vec<Item> = (0..n)
                .map(|i| {
                    let lo = DVec3::new(
                        f64::from(rng.gen_range(-20..20)) * 0.5,
                        rng.gen_range(-10.0..10.0),
                        rng.gen_range(-10.0..10.0),
                    );
                    Item {
                        index: i as u32,
                        bounds: Bounds3::new(lo, lo + DVec3::splat(rng.gen_range(0.1..3.0))),
                    }
                })
                .collect();
            let bounds = items.iter().fold(EMPTY, |b, it| b.union(&it.bounds));
            let axis = 0;
            let centres = items.iter().fold(EMPTY, |c, it| {
                Bounds3::new(c.min.min(it.centre()), c.max.max(it.centre()))
            });
            let (lo, ext) = (centres.min[axis], centres.max[axis] - centres.min[axis]);
            let (best, _) = full_sweep_split(&items, &bounds, axis).expect("a split");
            let scale = SAH_BINS as f64 / ext;
            let expected = items
                .iter()
                .filter(|it| {
                    (((it.centre()[axis] - lo) * scale) as usize).min(SAH_BINS - 1) <= best
                })
                .count();
            let mid = sah_split(&mut items, &bounds, lo, ext, axis).expect("n > 4: a split");
            assert_eq!(
                mid, expected,
                "round {round}: items below the full sweep's best bin"
            );
        }
    }

    #[test]
    fn sah_separates_clusters() {
        // Two clusters far apart: the root splits between them, so a ray through one cluster
        // never visits the other's items.
        let mut boxes: Vec<Bounds3> = (0..8).map(|i| unit_box(0.1 * i as f64)).collect();
        boxes.extend((0..8).map(|i| unit_box(100.0 + 0.1 * i as f64)));
        let bvh = Bvh::new(&boxes);
        let ray = Ray::new(DVec3::new(0.5, 0.5, 5.0), DVec3::NEG_Z);
        let mut visits = 0;
        let mut seen = Vec::new();
        bvh.traverse(&ray, 0.0..f64::INFINITY, &mut visits, |i, t| {
            seen.push(i);
            Some(t)
        });
        assert!(
            seen.iter().all(|&i| i < 8),
            "only the near cluster: {seen:?}"
        );
        assert!(!seen.is_empty());
    }
}

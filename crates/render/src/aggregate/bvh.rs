//! [`Bvh`]: the one bounding-volume hierarchy of the tracer, over any items that have boxes —
//! the scene's bounded primitives and a Bézier mesh's sub-patches alike.
//!
//! Built top-down with the surface area heuristic over [`SAH_BINS`] centroid bins per node
//! (Wald 2007, "On fast construction of SAH-based bounding volume hierarchies"; pbrt-v4
//! §7.3.2), the two halves of a large node in parallel (rayon), each subtree written in place
//! into its own share of one node array (`2m − 1` slots for `m` items), depth-first, so that a
//! node's first child follows it and only the second child's index is stored (pbrt-v4
//! `LinearBVHNode`; no intermediate tree, no copies); unused slots are squeezed out at the end.
//! Traversal tests both children at their parent, visits the near one first (by the sign of
//! the ray direction along the node's split axis) and skips every node that starts beyond the
//! nearest hit found so far; at most [`FLAT_MAX_ITEMS`] items are a flat list. See
//! `paper-notes/bvh.md`.

use std::ops::Range;
use std::time::{Duration, Instant};

use glam::DVec3;

use crate::geometry::{Bounds3, Ray, SlabRay};

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

/// Depth limit of the tree (the root has depth 1): a node this deep becomes a leaf whatever
/// it holds, so the fixed traversal stack of this many entries never overflows.
pub const MAX_DEPTH: usize = 64;

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

/// One node of the flattened tree: 57 bytes of data in one 64-byte cache line, aligned so
/// that no node straddles two lines (a traversal step then fetches one line per node; the
/// 132 861 nodes of the largest sphereflake, 8.5 MB, do not fit in cache).
#[derive(Clone, Copy, Debug)]
#[repr(align(64))]
struct Node {
    bounds: Bounds3,
    /// Leaf: first item in [`Bvh::order`]. Inner: index of the second child (the first child
    /// is the next node).
    offset: u32,
    /// Items in the leaf; 0 for an inner node.
    count: u32,
    /// Split axis of an inner node.
    axis: u8,
}

const _: () = assert!(size_of::<Node>() == 64, "a node is one cache line");

/// What `--stats` reports about a hierarchy.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct BvhInfo {
    /// Items (primitives or sub-patches).
    pub items: usize,
    /// Nodes, inner and leaf.
    pub nodes: usize,
    /// Depth of the deepest leaf (the root alone has depth 1; 0 when empty).
    pub depth: usize,
    /// Wall time of the build.
    pub build: Duration,
}

/// A flattened binary BVH over items `0..n`, item `i` having box `boxes[i]`.
#[derive(Clone, Debug, Default)]
pub struct Bvh {
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

/// A slot of the build's node array not (yet) written: a subtree over `m` items is given
/// `2m − 1` slots, and one with leaves of several items leaves some of them unused.
const UNUSED: Node = Node {
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

impl Bvh {
    /// Builds the hierarchy over `boxes`. Boxes must be finite (the caller keeps unbounded
    /// items out); a flat box (zero extent on an axis) is fine.
    pub fn new(boxes: &[Bounds3]) -> Self {
        let start = Instant::now();
        let mut items: Vec<Item> = boxes
            .iter()
            .enumerate()
            .map(|(i, b)| Item {
                index: i as u32,
                // The box between the two corners, as the slab test reads a box; so every
                // node box has `min ≤ max`, which `Bounds3::slab_by_sign` needs.
                bounds: Bounds3::new(b.min.min(b.max), b.min.max(b.max)),
            })
            .collect();
        let mut bvh = Bvh::default();
        if items.is_empty() {
            return bvh;
        }
        let depth = if items.len() <= FLAT_MAX_ITEMS {
            // The flat list: one leaf, items in index order (see `traverse`).
            let bounds = items.iter().fold(EMPTY, |b, it| b.union(&it.bounds));
            bvh.nodes.push(Node {
                bounds,
                offset: 0,
                count: items.len() as u32,
                axis: 0,
            });
            1
        } else {
            // A binary tree with leaves of at least one item has at most 2n − 1 nodes: each
            // subtree is written in place into its share of them, then the unused slots are
            // squeezed out.
            bvh.nodes = vec![UNUSED; 2 * items.len() - 1];
            let (used, depth) = build(&mut items, 0, 1, &mut bvh.nodes, 0);
            compact(&mut bvh.nodes, used);
            depth
        };
        bvh.order = items.iter().map(|it| it.index).collect();
        bvh.info = BvhInfo {
            items: boxes.len(),
            nodes: bvh.nodes.len(),
            depth,
            build: start.elapsed(),
        };
        bvh
    }

    /// Renames the items: item `k` becomes `ids[k]` in every answer (`visit`, `hit`, `blocked`
    /// and the returned item). The aggregate names its bounded items by their scene index this
    /// way, instead of mapping each item the traversal reaches through a second table (a
    /// random access per item test).
    ///
    /// # Panics
    /// If `ids` does not have one entry per item or is not strictly increasing: ties in
    /// [`Bvh::nearest`] go to the lower item, which must stay the lower id.
    pub fn relabel(&mut self, ids: &[u32]) {
        assert_eq!(ids.len(), self.info.items, "one id per item");
        assert!(
            ids.windows(2).all(|w| w[0] < w[1]),
            "ids strictly increasing"
        );
        for item in &mut self.order {
            *item = ids[*item as usize];
        }
    }

    /// Nodes, depth and build time.
    pub fn info(&self) -> BvhInfo {
        self.info
    }

    /// The box of everything, `None` when empty.
    pub fn bounds(&self) -> Option<Bounds3> {
        self.nodes.first().map(|n| n.bounds)
    }

    /// Calls `visit(item, t_max)` for the items of every leaf whose box the ray crosses before
    /// the nearest hit so far, near children first (by the sign of the ray direction along the
    /// node's split axis). `visit` returns the new `t_max` (the nearest hit so far, pruning
    /// farther nodes) or `None` to stop. A flat list (at most [`FLAT_MAX_ITEMS`] items) calls
    /// `visit` for every item, in index order, without a box test: `visit` must test the
    /// item's own box, as every user does. Counts the boxes tested in `visits`. Allocates
    /// nothing.
    ///
    /// Both children of an inner node are tested there, and only those the ray crosses before
    /// `t_max` are pushed; a pushed node's box is tested again when it is popped only if `t_max`
    /// fell since it was pushed (a shadow ray's never falls). So the leaves visited, and their
    /// order, are those of a traversal that tests each node when it pops it; missed children
    /// are never pushed, popped or fetched again.
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
    /// The near child of an inner node is visited next without going through the stack (the
    /// far one is pushed): it was tested at the current `t_max` a moment ago, as it would have
    /// been when popped straight away, so the leaves and their order are unchanged.
    fn traverse_with<const PRUNE: bool>(
        &self,
        ray: &Ray,
        range: Range<f64>,
        visits: &mut u64,
        mut visit: impl FnMut(u32, f64) -> Option<f64>,
    ) {
        let Some(root) = self.nodes.first() else {
            return;
        };
        let mut t_max = range.end;
        if self.nodes.len() == 1 {
            // One leaf: a flat list, or a single item.
            let first = root.offset as usize;
            for &item in &self.order[first..first + root.count as usize] {
                match visit(item, t_max) {
                    Some(t) => t_max = t,
                    None => return,
                }
            }
            return;
        }
        let slab_ray = SlabRay::new(ray);
        let dir_neg = [ray.dir.x < 0.0, ray.dir.y < 0.0, ray.dir.z < 0.0];
        let (start, end) = (range.start, range.end);
        let crosses = |node: &Node, t_max: f64| {
            if PRUNE {
                crosses(node, &slab_ray, start..end, t_max)
            } else {
                node.bounds.slab_by_sign(&slab_ray, start, end).is_some()
            }
        };
        *visits += 1;
        if !crosses(root, t_max) {
            return;
        }
        let mut stack = [0u32; MAX_DEPTH];
        let mut top = 0;
        // Entries below `stale` were pushed before `t_max` last fell: retested when popped.
        let mut stale = 0;
        // The node to visit next, already tested at the current `t_max`; else pop one.
        let mut next = Some(0u32);
        loop {
            let index = match next.take() {
                Some(index) => index as usize,
                None => {
                    if top == 0 {
                        return;
                    }
                    top -= 1;
                    let index = stack[top] as usize;
                    if top < stale {
                        stale = top;
                        *visits += 1;
                        if !crosses(&self.nodes[index], t_max) {
                            continue;
                        }
                    }
                    index
                }
            };
            let node = &self.nodes[index];
            if node.count > 0 {
                let first = node.offset as usize;
                let before = t_max;
                for &item in &self.order[first..first + node.count as usize] {
                    match visit(item, t_max) {
                        Some(t) => t_max = t,
                        None => return,
                    }
                }
                if t_max != before {
                    stale = top;
                }
            } else {
                // Push the far child, go on with the near one. The depth limit bounds the
                // stack: each level leaves at most one child on it.
                let (first, second) = (index as u32 + 1, node.offset);
                let (near_child, far_child) = if dir_neg[node.axis as usize] {
                    (second, first)
                } else {
                    (first, second)
                };
                *visits += 2;
                if crosses(&self.nodes[far_child as usize], t_max) {
                    stack[top] = far_child;
                    top += 1;
                }
                if crosses(&self.nodes[near_child as usize], t_max) {
                    next = Some(near_child);
                }
            }
        }
    }

    /// The nearest hit: `hit(item)` is each item's own nearest hit over the whole `range`
    /// (`(t, data)`), and the result is the least `(t, item)` over all items — the hit a loop
    /// over every item would keep, ties going to the lower index — with its item. Items are
    /// queried over the whole range, not up to the nearest hit so far, so that each item's
    /// answer does not depend on the visiting order.
    pub fn nearest<H>(
        &self,
        ray: &Ray,
        range: Range<f64>,
        visits: &mut u64,
        mut hit: impl FnMut(u32) -> Option<(f64, H)>,
    ) -> Option<(u32, f64, H)> {
        let mut best: Option<(u32, f64, H)> = None;
        self.traverse(ray, range, visits, |item, t_max| {
            if let Some((t, h)) = hit(item)
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

/// Whether the ray enters `node` in `range` before `t_max`, the nearest hit so far, up to
/// [`PRUNE_SLACK_REL`] (the pruning test of [`Bvh::traverse`]). Always inlined: it is the
/// traversal's inner loop, and as a call it cost more than the slab test itself.
#[inline(always)]
fn crosses(node: &Node, ray: &SlabRay, range: Range<f64>, t_max: f64) -> bool {
    node.bounds
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
/// temporary node array exists. Returns the slots used and the subtree's depth.
fn build(
    items: &mut [Item],
    first: usize,
    depth: usize,
    out: &mut [Node],
    base: usize,
) -> (usize, usize) {
    // The node's box and the box of its items' centres, in one pass.
    let (bounds, centres) = items.iter().fold((EMPTY, EMPTY), |(b, c), it| {
        let centre = it.centre();
        (
            grow(&b, &it.bounds),
            grow(&c, &Bounds3::new(centre, centre)),
        )
    });
    let n = items.len();
    let leaf = Node {
        bounds,
        offset: first as u32,
        count: n as u32,
        axis: 0,
    };
    if n == 1 || depth >= MAX_DEPTH {
        out[0] = leaf;
        return (1, 1);
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
                return (1, 1);
            }
        }
    } else if n <= MAX_LEAF_ITEMS {
        out[0] = leaf;
        return (1, 1);
    } else {
        // Equal centres: no split separates them; halve by count so leaves stay small.
        n / 2
    };
    let second = base + 2 * mid;
    out[0] = Node {
        bounds,
        offset: second as u32,
        count: 0,
        axis: axis as u8,
    };
    let (lo, hi) = items.split_at_mut(mid);
    let (left, right) = out[1..].split_at_mut(2 * mid - 1);
    let ((ul, dl), (ur, dr)) = if n > PARALLEL_MIN_ITEMS {
        rayon::join(
            || build(lo, first, depth + 1, left, base + 1),
            || build(hi, first + mid, depth + 1, right, second),
        )
    } else {
        (
            build(lo, first, depth + 1, left, base + 1),
            build(hi, first + mid, depth + 1, right, second),
        )
    };
    (1 + ul + ur, 1 + dl.max(dr))
}

/// Squeezes the [`UNUSED`] slots out of the node array written by [`build`] (`used` slots are
/// nodes), keeping the depth-first order and renumbering the second-child indices. In place:
/// a node only moves down, so each is read before any write reaches its slot.
fn compact(nodes: &mut Vec<Node>, used: usize) {
    if used < nodes.len() {
        // The new index of each slot: the nodes before it.
        let mut new_index = Vec::with_capacity(nodes.len());
        let mut k = 0u32;
        for node in nodes.iter() {
            new_index.push(k);
            k += u32::from(node.count != UNUSED.count);
        }
        let mut at = 0;
        for i in 0..nodes.len() {
            let mut node = nodes[i];
            if node.count == UNUSED.count {
                continue;
            }
            if node.count == 0 {
                node.offset = new_index[node.offset as usize];
            }
            nodes[at] = node;
            at += 1;
        }
        nodes.truncate(used);
        nodes.shrink_to_fit();
    }
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
        boxes[b] = grow(&boxes[b], &it.bounds);
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
        let mut bvh = Bvh::new(&boxes);
        bvh.relabel(&ids);
        let ray = Ray::new(DVec3::new(-1.0, 0.5, 0.5), DVec3::X);
        let mut seen = Vec::new();
        bvh.traverse(&ray, 0.0..f64::INFINITY, &mut 0, |i, t| {
            seen.push(i);
            Some(t)
        });
        assert_eq!(seen, ids, "ids in traversal order");
        let hit = bvh.nearest(&ray, 0.0..f64::INFINITY, &mut 0, |i| Some((1.0, i)));
        assert_eq!(hit.map(|h| h.0), Some(1), "the tie goes to the lowest id");
        assert!(
            bvh.any(&ray, 0.0..f64::INFINITY, &mut 0, |i| i == 28),
            "id 28 blocks"
        );
    }

    #[test]
    #[should_panic(expected = "ids strictly increasing")]
    fn relabel_refuses_ids_out_of_order() {
        let boxes: Vec<Bounds3> = (0..6).map(|i| unit_box(2.0 * i as f64)).collect();
        Bvh::new(&boxes).relabel(&[0, 1, 2, 4, 3, 5]);
    }

    #[test]
    fn equal_boxes_split_to_small_leaves_within_the_depth_limit() {
        // 1000 copies of one box: no split separates them, yet leaves stay small.
        let boxes = vec![unit_box(0.0); 1000];
        let bvh = Bvh::new(&boxes);
        assert!(bvh.info().depth <= MAX_DEPTH);
        assert!(
            bvh.nodes.iter().all(|n| n.count as usize <= MAX_LEAF_ITEMS),
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
        let hit = bvh.nearest(&ray, 0.0..f64::INFINITY, &mut visits, |i| Some((4.0, i)));
        assert_eq!(hit.map(|h| h.0), Some(0), "the tie goes to item 0");
    }

    /// A traversal's callback: an item and the `t_max` it sees, the new `t_max` back.
    type Visit<'a> = dyn FnMut(u32, f64) -> Option<f64> + 'a;

    /// The traversal before children were tested at their parent (issue 12, third pass): pop a
    /// node, test its box, prune, and push both children of an inner node. The leaves it visits
    /// and their order are what [`Bvh::traverse`] must reproduce.
    fn pop_then_test(
        bvh: &Bvh,
        ray: &Ray,
        range: Range<f64>,
        mut visit: impl FnMut(u32, f64) -> Option<f64>,
    ) {
        let slab_ray = SlabRay::new(ray);
        let mut t_max = range.end;
        let mut stack = vec![0u32];
        while let Some(index) = stack.pop() {
            let node = &bvh.nodes[index as usize];
            let Some((near, far)) = node.bounds.slab(&slab_ray, range.start, range.end) else {
                continue;
            };
            if near > t_max + PRUNE_SLACK_REL * (near.abs() + (far - near)) {
                continue;
            }
            if node.count > 0 {
                let first = node.offset as usize;
                for &item in &bvh.order[first..first + node.count as usize] {
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

    #[test]
    fn children_tested_at_the_parent_visit_the_leaves_of_pop_then_test() {
        // Random boxes (some flat, some sharing faces on a unit grid); random rays; each item
        // "hit" at its box entry plus a per-item offset, so `t_max` falls during the traversal
        // and the retest of stale stack entries is exercised. The calls to `visit` — items,
        // order and the `t_max` each saw — must be those of the pop-then-test traversal.
        use rand::{Rng, SeedableRng};
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(12);
        for round in 0..20 {
            let n = 5 + round * 13;
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
            assert!(bvh.nodes.len() > 1, "a tree, not a flat list");
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
                let slow = calls(&|f| pop_then_test(&bvh, &ray, 0.0..f64::INFINITY, f));
                assert_eq!(fast, slow, "visits of {ray:?} over {n} boxes");
            }
        }
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
        assert_eq!(bvh.info().nodes, 1, "one leaf");
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
        assert!(bvh.info().nodes > 1, "a tree");
        seen.clear();
        bvh.traverse(&ray, 0.0..f64::INFINITY, &mut visits, |i, t| {
            seen.push(i);
            Some(t)
        });
        assert!(seen.is_empty(), "the tree prunes at its root: {seen:?}");
        assert_eq!(visits, 1, "the root's box only");
    }

    /// Checks the subtree at `i` and returns its node count: an inner node's first child is
    /// `i + 1` and its second child follows the first's subtree; boxes hold their children's
    /// and items' boxes; leaves list their items in `order`. Marks the items seen.
    fn check_subtree(bvh: &Bvh, boxes: &[Bounds3], i: usize, seen: &mut [bool]) -> usize {
        let node = &bvh.nodes[i];
        let holds = |outer: &Bounds3, inner: &Bounds3| {
            outer.min.cmple(inner.min).all() && outer.max.cmpge(inner.max).all()
        };
        if node.count > 0 {
            assert_ne!(node.count, UNUSED.count, "an unused slot at {i}");
            let first = node.offset as usize;
            for &item in &bvh.order[first..first + node.count as usize] {
                assert!(!seen[item as usize], "item {item} in two leaves");
                seen[item as usize] = true;
                assert!(
                    holds(&node.bounds, &boxes[item as usize]),
                    "leaf {i} holds {item}"
                );
            }
            return 1;
        }
        for child in [i + 1, node.offset as usize] {
            assert!(
                holds(&node.bounds, &bvh.nodes[child].bounds),
                "{i} holds {child}"
            );
        }
        let left = check_subtree(bvh, boxes, i + 1, seen);
        assert_eq!(node.offset as usize, i + 1 + left, "second child of {i}");
        1 + left + check_subtree(bvh, boxes, node.offset as usize, seen)
    }

    #[test]
    fn the_in_place_build_writes_a_compact_depth_first_tree() {
        // Above the parallel threshold, with single-item leaves (distinct boxes: every slot
        // used) and with leaves of several items (groups of equal boxes: unused slots squeezed
        // out), and a few items (sequential).
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
            let count = check_subtree(&bvh, &boxes, 0, &mut seen);
            assert_eq!(count, bvh.nodes.len(), "{name}: every node reached once");
            assert!(seen.iter().all(|&s| s), "{name}: every item in a leaf");
            assert_eq!(bvh.info().nodes, bvh.nodes.len(), "{name}: info");
            if name == "grouped" {
                assert!(
                    bvh.nodes.len() < 2 * boxes.len() - 1,
                    "leaves of several items"
                );
            }
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

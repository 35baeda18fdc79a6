//! Aggregates: the acceleration structure that lets a ray test only the items whose boxes it
//! crosses. One [`Bvh`] serves the scene's bounded primitives (the integrator) and the
//! sub-patches of a Bézier mesh (a surface); it knows items only by their boxes, so it sits
//! below both. See `paper-notes/bvh.md`.

mod bvh;

use std::ops::Range;

use crate::geometry::{Bounds3, Ray};

pub use bvh::{
    Bvh, BvhInfo, FLAT_MAX_ITEMS, MAX_DEPTH, MAX_LEAF_ITEMS, PRUNE_SLACK_REL, SAH_BINS,
    TRAVERSAL_COST,
};

/// A set of items split by whether they have a finite box: the bounded ones in a [`Bvh`],
/// the unbounded ones (planes, unclipped algebraic surfaces) tested by every ray after it.
/// Queries answer as a loop over all items in index order would.
#[derive(Clone, Debug, Default)]
pub struct Aggregate {
    /// The bounded items, named by their item index ([`Bvh::with_ids`]).
    bvh: Bvh,
    /// Items without a finite box, ascending.
    unbounded: Vec<u32>,
}

impl Aggregate {
    /// The aggregate of items `0, 1, …`, item `i` bounded by the `i`-th box of `boxes` (`None`,
    /// or a box with a non-finite corner: unbounded).
    pub fn new(boxes: impl IntoIterator<Item = Option<Bounds3>>) -> Self {
        let mut unbounded = Vec::new();
        // The bounded items go to the build as they come: no copy of their boxes is kept.
        let bounded = (0u32..).zip(boxes).filter_map(|(i, b)| match b {
            Some(b) if b.min.is_finite() && b.max.is_finite() => Some((i, b)),
            _ => {
                unbounded.push(i);
                None
            }
        });
        let bvh = Bvh::with_ids(bounded);
        Aggregate { bvh, unbounded }
    }

    /// The hierarchy's size and build time.
    pub fn bvh_info(&self) -> BvhInfo {
        self.bvh.info()
    }

    /// Whether the bounded items are a flat list (at most [`FLAT_MAX_ITEMS`], no box tested
    /// before each item's own) rather than a tree.
    pub fn is_flat(&self) -> bool {
        self.bvh.is_flat()
    }

    /// Items tested outside the hierarchy.
    pub fn unbounded(&self) -> &[u32] {
        &self.unbounded
    }

    /// The least `(t, item)` over every item's own nearest hit `hit(item, t_max)` in `range`
    /// (see [`Bvh::nearest`]: `t_max` is the nearest hit so far), with its item; counts BVH
    /// nodes visited in `visits`.
    pub fn nearest<H>(
        &self,
        ray: &Ray,
        range: Range<f64>,
        visits: &mut u64,
        mut hit: impl FnMut(u32, f64) -> Option<(f64, H)>,
    ) -> Option<(u32, f64, H)> {
        let mut best = self.bvh.nearest(ray, range.clone(), visits, &mut hit);
        for &i in &self.unbounded {
            let t_max = best.as_ref().map_or(range.end, |b| b.1);
            if let Some((t, h)) = hit(i, t_max)
                && bvh::precedes(i, t, &best, range.end)
            {
                best = Some((i, t, h));
            }
        }
        best
    }

    /// Whether `blocked(item)` holds for any item (bounded ones only when the ray crosses
    /// their box in `range`); stops at the first blocker.
    pub fn any(
        &self,
        ray: &Ray,
        range: Range<f64>,
        visits: &mut u64,
        mut blocked: impl FnMut(u32) -> bool,
    ) -> bool {
        self.bvh.any(ray, range, visits, &mut blocked) || self.unbounded.iter().any(|&i| blocked(i))
    }
}

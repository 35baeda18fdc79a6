//! [`PatchBvh`]: a bounding-volume hierarchy over the boxes of a mesh's sub-patches, so a ray
//! tests only the pieces whose boxes it crosses (article §4: "some patches have been selected
//! by their bounding volumes").

use glam::DVec3;

use crate::geometry::{Bounds3, Ray};

/// Items per leaf at most.
const LEAF_SIZE: usize = 1;

/// Depth of the traversal stack. A median split halves the item count at each level, so the
/// depth is `⌈log2(items / LEAF_SIZE)⌉ + 1`: 48 allows 2⁴⁷ items.
pub(crate) const STACK_DEPTH: usize = 48;

#[derive(Clone, Copy, Debug)]
enum Node {
    /// Items `first .. first + count` of the item order.
    Leaf { first: u32, count: u32 },
    /// Children at `left` and `right`, split along `axis`.
    Inner { left: u32, right: u32, axis: u8 },
}

/// A binary BVH, built by median splits of the box centres along the widest axis.
#[derive(Clone, Debug)]
pub(crate) struct PatchBvh {
    nodes: Vec<(Bounds3, Node)>,
    /// Item indices in leaf order.
    order: Vec<u32>,
}

impl PatchBvh {
    /// Builds the hierarchy over `boxes` (item `i` has box `boxes[i]`).
    pub(crate) fn new(boxes: &[Bounds3]) -> Self {
        let mut bvh = PatchBvh {
            nodes: Vec::with_capacity(2 * boxes.len()),
            order: (0..boxes.len() as u32).collect(),
        };
        if !boxes.is_empty() {
            let mut order = std::mem::take(&mut bvh.order);
            bvh.build(boxes, &mut order, 0);
            bvh.order = order;
        }
        bvh
    }

    /// Builds the node for `order[offset..offset + items.len()]`, returns its index.
    fn build(&mut self, boxes: &[Bounds3], items: &mut [u32], offset: usize) -> u32 {
        let bounds = items.iter().fold(
            Bounds3::new(DVec3::INFINITY, DVec3::NEG_INFINITY),
            |b, &i| b.union(&boxes[i as usize]),
        );
        let index = self.nodes.len() as u32;
        if items.len() <= LEAF_SIZE {
            self.nodes.push((
                bounds,
                Node::Leaf {
                    first: offset as u32,
                    count: items.len() as u32,
                },
            ));
            return index;
        }
        let centre = |i: u32| {
            let b = &boxes[i as usize];
            (b.min + b.max) * 0.5
        };
        let c = items.iter().fold(
            Bounds3::new(DVec3::INFINITY, DVec3::NEG_INFINITY),
            |b, &i| b.union(&Bounds3::new(centre(i), centre(i))),
        );
        let ext = c.max - c.min;
        let axis = if ext.x >= ext.y && ext.x >= ext.z {
            0
        } else if ext.y >= ext.z {
            1
        } else {
            2
        };
        items.sort_by(|&a, &b| centre(a)[axis].total_cmp(&centre(b)[axis]));
        let mid = items.len() / 2;
        // Placeholder, patched once the children exist.
        self.nodes.push((bounds, Node::Leaf { first: 0, count: 0 }));
        let (lo, hi) = items.split_at_mut(mid);
        let left = self.build(boxes, lo, offset);
        let right = self.build(boxes, hi, offset + mid);
        self.nodes[index as usize].1 = Node::Inner {
            left,
            right,
            axis: axis as u8,
        };
        index
    }

    /// Calls `visit(item, t_max)` for every item whose leaf box the ray crosses within
    /// `t_min..t_max`, nearer nodes first. `visit` returns the new `t_max` (the nearest hit so
    /// far, pruning farther boxes) or `None` to stop the traversal. Counts every box missed in
    /// `box_misses`. Allocates nothing.
    pub(crate) fn traverse(
        &self,
        ray: &Ray,
        t_min: f64,
        mut t_max: f64,
        box_misses: &mut u64,
        mut visit: impl FnMut(u32, f64) -> Option<f64>,
    ) {
        if self.nodes.is_empty() {
            return;
        }
        let mut stack = [0u32; STACK_DEPTH];
        let mut top = 1;
        while top > 0 {
            top -= 1;
            let (bounds, node) = &self.nodes[stack[top] as usize];
            if bounds.intersect_ray(ray, t_min..t_max).is_none() {
                *box_misses += 1;
                continue;
            }
            match *node {
                Node::Leaf { first, count } => {
                    for &item in &self.order[first as usize..(first + count) as usize] {
                        match visit(item, t_max) {
                            Some(t) => t_max = t,
                            None => return,
                        }
                    }
                }
                Node::Inner { left, right, axis } => {
                    // Push the far child first so the near one is visited first: by where the
                    // ray enters each box (ties and misses by the split axis), so that the
                    // nearest hit is found early and prunes the rest.
                    let entry = |n: u32| {
                        self.nodes[n as usize]
                            .0
                            .intersect_ray(ray, t_min..t_max)
                            .map_or(f64::INFINITY, |r| r.start)
                    };
                    let (tl, tr) = (entry(left), entry(right));
                    let left_first = if tl == tr {
                        ray.dir[axis as usize] >= 0.0
                    } else {
                        tl < tr
                    };
                    let (near, far) = if left_first {
                        (left, right)
                    } else {
                        (right, left)
                    };
                    if top + 2 > STACK_DEPTH {
                        // Unreachable for median splits (see STACK_DEPTH); visit depth-first.
                        stack[top] = near;
                        top += 1;
                        continue;
                    }
                    stack[top] = far;
                    stack[top + 1] = near;
                    top += 2;
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn visits_exactly_the_crossed_boxes() {
        // A row of unit boxes along x at x = 0, 2, 4, …, 18.
        let boxes: Vec<Bounds3> = (0..10)
            .map(|i| {
                let x = 2.0 * i as f64;
                Bounds3::new(DVec3::new(x, 0.0, 0.0), DVec3::new(x + 1.0, 1.0, 1.0))
            })
            .collect();
        let bvh = PatchBvh::new(&boxes);
        // A vertical ray through box 3 only.
        let ray = Ray::new(DVec3::new(6.5, 0.5, 5.0), DVec3::new(0.0, 0.0, -1.0));
        let mut seen = Vec::new();
        let mut misses = 0;
        bvh.traverse(&ray, 0.0, f64::INFINITY, &mut misses, |i, t| {
            seen.push(i);
            Some(t)
        });
        assert_eq!(seen, vec![3], "only the box under the ray");
        // A ray along +x visits all ten, in order.
        let ray = Ray::new(DVec3::new(-1.0, 0.5, 0.5), DVec3::X);
        seen.clear();
        bvh.traverse(&ray, 0.0, f64::INFINITY, &mut misses, |i, t| {
            seen.push(i);
            Some(t)
        });
        assert_eq!(seen, (0..10).collect::<Vec<_>>(), "front to back");
        // Pruning: a hit at t = 4 stops boxes beyond it.
        seen.clear();
        bvh.traverse(&ray, 0.0, f64::INFINITY, &mut misses, |i, _| {
            seen.push(i);
            Some(4.0)
        });
        assert!(
            seen.len() <= 4 && seen[0] == 0,
            "pruned after the hit: {seen:?}"
        );
    }
}

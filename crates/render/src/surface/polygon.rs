//! [`Polygon`]: a planar polygon (Stam's four-sided `POLYGON`, Kuchkuda's `TRIANGLE`).
//!
//! A planar test, not a root query: the ray is clipped to the polygon's (padded) box and its
//! origin moved to the box entry as on the shared implicit path, then the plane
//! `n·(p − v₀) = 0` restricted to it, `c₀ + c₁s`, has its one root `s = −c₀/c₁`, computed by
//! `poly`'s linear closed form ([`poly::linear_root_in`], correctly rounded; the rare root within
//! an ulp of the segment's ends goes to the general certified query) without the query's
//! set-up, which dominated the cost of a polygon test (`paper-notes/bvh.md` §3). The hit is kept when it
//! lies inside the polygon (crossing-number test in the plane's dominant projection, which
//! handles convex and concave simple polygons); normals and error bounds come from the
//! plane's implicit `F` as before.
//!
//! Scene syntax:
//! ```text
//! #object
//! Type = POLYGON          // or TRIANGLE with a, b, c
//! a = (0,0,0)  b = (1,0,0)  c = (1,1,0)  d = (0,1,0)
//! ```

use std::ops::Range;

use glam::{DVec2, DVec3};
use smallvec::SmallVec;

use super::implicit::{Implicit, clip, search_start};
use super::{Hit, Plane, Surface, SurfaceGeometry, SurfaceKind};
use crate::geometry::{Bounds3, Ray, gamma, polygon_normal};
use crate::workspace::Workspace;

/// A planar polygon with at least three vertices.
#[derive(Debug)]
pub struct Polygon {
    plane: Implicit<Plane>,
    /// Vertices projected on the two coordinates kept by the dominant projection; a
    /// triangle's in the polygon itself, not in an allocation of their own.
    projected: SmallVec<[DVec2; 3]>,
    /// The dropped coordinate (the normal's largest component).
    drop_axis: usize,
}

impl Polygon {
    /// The polygon through `vertices` (in order; at least three, non-zero area). `None` for a
    /// degenerate polygon.
    pub fn new(vertices: &[DVec3]) -> Option<Self> {
        let n = polygon_normal(vertices)?;
        let kind = if vertices.len() == 3 {
            SurfaceKind::Triangle
        } else {
            SurfaceKind::Polygon
        };
        let a = n.abs();
        let drop_axis = if a.x >= a.y && a.x >= a.z {
            0
        } else if a.y >= a.z {
            1
        } else {
            2
        };
        let keep = |v: DVec3| match drop_axis {
            0 => DVec2::new(v.y, v.z),
            1 => DVec2::new(v.z, v.x),
            _ => DVec2::new(v.x, v.y),
        };
        let b = Bounds3::from_points(vertices.iter().copied());
        // Pad the flat box by the rounding of a point computed on the plane, so the slab test
        // never clips a hit on the polygon itself.
        let pad = DVec3::splat(gamma(4) * b.min.abs().max(b.max.abs()).max_element());
        let bounds = Bounds3::new(b.min - pad, b.max + pad);
        let plane = Implicit::new(Plane::with_kind(vertices[0], n, kind), Some(bounds));
        Some(Polygon {
            plane,
            projected: vertices.iter().map(|&v| keep(v)).collect(),
            drop_axis,
        })
    }

    /// Where the ray meets the plane inside the polygon's box, over `t_range` (open at both
    /// ends): `(t, point)`. The search starts at the box entry as [`Implicit`]'s does
    /// ([`search_start`]), so a hit on the entry face is kept.
    fn plane_hit(
        &self,
        ray: &Ray,
        t_range: Range<f64>,
        ws: &mut Workspace,
    ) -> Option<(f64, DVec3)> {
        let range_start = t_range.start;
        let seg = clip(
            self.plane.bounds_ref(),
            ray,
            t_range.clone(),
            ws,
            self.plane.kind(),
        )?;
        let entry = seg.start;
        let t0 = entry + search_start(range_start, entry, seg.end - entry);
        let o = ray.at(t0);
        let [c0, c1] = self.plane.function().restricted(o, ray.dir);
        match poly::linear_root_in(c0, c1, 0.0, seg.end - t0) {
            Some(Some(s)) => Some((t0 + s, o + ray.dir * s)),
            Some(None) => None,
            // The root within an ulp of the segment's ends, or the ray lying in the plane:
            // the general certified query on the same restriction decides.
            None => self.plane.nearest(ray, t_range, ws, false),
        }
    }

    fn project(&self, v: DVec3) -> DVec2 {
        match self.drop_axis {
            0 => DVec2::new(v.y, v.z),
            1 => DVec2::new(v.z, v.x),
            _ => DVec2::new(v.x, v.y),
        }
    }

    /// Crossing-number point-in-polygon test in the projection.
    fn contains(&self, p: DVec3) -> bool {
        let q = self.project(p);
        let mut inside = false;
        // One slice for the loop: indexing the `SmallVec` asks where its data lives at every
        // access, and gears' many-sided polygons traced 5.6 % slower (`paper-notes/bvh.md`,
        // twenty-first session).
        let pts: &[DVec2] = &self.projected;
        let n = pts.len();
        for i in 0..n {
            let a = pts[i];
            let b = pts[(i + 1) % n];
            if (a.y > q.y) != (b.y > q.y) {
                let x = a.x + (q.y - a.y) * (b.x - a.x) / (b.y - a.y);
                if q.x < x {
                    inside = !inside;
                }
            }
        }
        inside
    }
}

impl Surface for Polygon {
    fn kind(&self) -> SurfaceKind {
        self.plane.kind()
    }

    fn bounds(&self) -> Option<Bounds3> {
        self.plane.bounds()
    }

    fn intersect(&self, ray: &Ray, t_range: Range<f64>, ws: &mut Workspace) -> Option<Hit> {
        let (t, p) = self.plane_hit(ray, t_range, ws)?;
        self.contains(p).then_some(Hit {
            t,
            local: p,
            uv: None,
            tag: 0,
        })
    }

    fn shading(&self, hit: &Hit) -> SurfaceGeometry {
        self.plane.shading(hit)
    }

    /// A part of its plane, with the plane's normal.
    fn convex(&self) -> bool {
        self.plane.convex()
    }
}

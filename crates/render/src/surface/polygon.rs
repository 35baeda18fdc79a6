//! [`Polygon`]: a planar polygon (Stam's four-sided `POLYGON`, Kuchkuda's `TRIANGLE`).
//!
//! The supporting plane is intersected through the shared implicit path (degree 1); the hit
//! is kept when it lies inside the polygon (crossing-number test in the plane's dominant
//! projection, which handles convex and concave simple polygons).
//!
//! Scene syntax:
//! ```text
//! #object
//! Type = POLYGON          // or TRIANGLE with a, b, c
//! a = (0,0,0)  b = (1,0,0)  c = (1,1,0)  d = (0,1,0)
//! ```

use std::ops::Range;

use glam::{DVec2, DVec3};

use super::implicit::Implicit;
use super::{Hit, Plane, Surface, SurfaceGeometry, SurfaceKind};
use crate::geometry::{Bounds3, Ray, gamma, polygon_normal};
use crate::methods::RootMethods;
use crate::workspace::Workspace;

/// A planar polygon with at least three vertices.
#[derive(Debug)]
pub struct Polygon {
    plane: Implicit<Plane>,
    /// Vertices projected on the two coordinates kept by the dominant projection.
    projected: Vec<DVec2>,
    /// The dropped coordinate (the normal's largest component).
    drop_axis: usize,
    bounds: Bounds3,
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
            bounds,
        })
    }

    /// Finds the plane's root with `roots` instead of the default methods.
    pub fn with_root_methods(mut self, roots: RootMethods) -> Self {
        self.plane = self.plane.with_root_methods(roots);
        self
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
        let n = self.projected.len();
        for i in 0..n {
            let a = self.projected[i];
            let b = self.projected[(i + 1) % n];
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
        Some(self.bounds)
    }

    fn intersect(&self, ray: &Ray, t_range: Range<f64>, ws: &mut Workspace) -> Option<Hit> {
        let (t, p) = self.plane.nearest(ray, t_range, ws, false)?;
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
}

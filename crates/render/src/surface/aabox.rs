//! [`AaBox`]: an axis-aligned box (Kuchkuda §3.3), intersected by the slab test.
//!
//! A box is not a polynomial surface, so it does not use the implicit path; its faces are
//! planes and the slab test finds them directly.
//!
//! Scene syntax:
//! ```text
//! #object
//! Type = BOX
//! Min = (-1,-1,-1)
//! Max = (1,1,1)
//! ```

use std::ops::Range;

use glam::{DVec2, DVec3};

use super::implicit::clip;
use super::{Hit, Surface, SurfaceGeometry, SurfaceKind};
use crate::geometry::{Bounds3, Ray, gamma};
use crate::workspace::Workspace;

/// A solid axis-aligned box.
#[derive(Clone, Debug)]
pub struct AaBox {
    b: Bounds3,
}

impl AaBox {
    /// The box `[min, max]` (`min < max` componentwise).
    pub fn new(min: DVec3, max: DVec3) -> Self {
        AaBox {
            b: Bounds3::new(min, max),
        }
    }

    /// Which face (`2·axis + (0 for min, 1 for max)`) is nearest to `p`.
    fn face_of(&self, p: DVec3) -> u32 {
        let mut best = (f64::INFINITY, 0);
        for k in 0..3 {
            let dmin = (p[k] - self.b.min[k]).abs();
            let dmax = (p[k] - self.b.max[k]).abs();
            if dmin < best.0 {
                best = (dmin, 2 * k as u32);
            }
            if dmax < best.0 {
                best = (dmax, 2 * k as u32 + 1);
            }
        }
        best.1
    }
}

impl Surface for AaBox {
    fn kind(&self) -> SurfaceKind {
        SurfaceKind::Box
    }

    fn bounds(&self) -> Option<Bounds3> {
        Some(self.b)
    }

    fn intersect(&self, ray: &Ray, t_range: Range<f64>, ws: &mut Workspace) -> Option<Hit> {
        let start = t_range.start;
        let seg = clip(Some(&self.b), ray, t_range, ws, SurfaceKind::Box)?;
        // Entering the box: the near slab distance; starting inside: the far one.
        let t = if seg.start > start {
            seg.start
        } else {
            seg.end
        };
        if t <= start || !t.is_finite() {
            return None;
        }
        let mut p = ray.at(t);
        let face = self.face_of(p);
        // Snap the face coordinate onto the face plane: it is known exactly.
        let k = (face / 2) as usize;
        p[k] = if face.is_multiple_of(2) {
            self.b.min[k]
        } else {
            self.b.max[k]
        };
        Some(Hit {
            t,
            local: p,
            uv: None,
            tag: face,
        })
    }

    fn shading(&self, hit: &Hit) -> SurfaceGeometry {
        let face = hit.tag;
        let k = (face / 2) as usize;
        let mut n = DVec3::ZERO;
        n[k] = if face.is_multiple_of(2) { -1.0 } else { 1.0 };
        let p = hit.local;
        // The two in-face coordinates carry the rounding of o + t·d and of the slab distance
        // (pbrt-v4 uses γ(5)·|p| for the analogous bilinear-patch case); the face coordinate
        // is exact after snapping.
        let mut p_err = p.abs() * gamma(7);
        p_err[k] = 0.0;
        let (u, v) = ((k + 1) % 3, (k + 2) % 3);
        let uv = DVec2::new(p[u] - self.b.min[u], p[v] - self.b.min[v]);
        SurfaceGeometry {
            p,
            p_err,
            normal: Some(n),
            uv: Some(uv),
        }
    }
}

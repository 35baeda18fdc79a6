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

    /// The box is convex and each face's normal points out of it: a ray leaving a face with
    /// `n·d > 0` is beyond that face's plane, and the box lies behind it.
    fn convex(&self) -> bool {
        true
    }
}

#[cfg(test)]
mod tests {
    use rand::{Rng, SeedableRng};
    use rand_chacha::ChaCha8Rng;

    use super::*;
    use crate::surface::leaving_ray_misses;

    /// The fact `Surface::convex` rests on, for boxes: from a point just outside a face
    /// (where `offset_ray_origin` puts a shadow ray's origin), a ray leaving along the face's
    /// normal (`n·d > 0`) never meets the box, whatever else its direction, edges and corners
    /// included.
    #[test]
    fn a_ray_leaving_a_face_never_meets_the_box() {
        let mut rng = ChaCha8Rng::seed_from_u64(5);
        let mut ws = Workspace::new();
        let mut rays = 0;
        for _ in 0..4000 {
            let min = DVec3::new(
                rng.gen_range(-5.0..5.0),
                rng.gen_range(-5.0..5.0),
                rng.gen_range(-5.0..5.0),
            );
            let size = DVec3::new(
                rng.gen_range(0.1..4.0),
                rng.gen_range(0.1..4.0),
                rng.gen_range(0.1..4.0),
            );
            let b = AaBox::new(min, min + size);
            let face = rng.gen_range(0..6u32);
            let k = (face / 2) as usize;
            // A point of the face, on an edge or a corner one time in four.
            let mut p = min + size * DVec3::new(rng.r#gen(), rng.r#gen(), rng.r#gen());
            if rng.gen_bool(0.25) {
                let j = (k + 1) % 3;
                p[j] = if rng.r#gen() {
                    min[j]
                } else {
                    min[j] + size[j]
                };
            }
            let mut n = DVec3::ZERO;
            n[k] = if face.is_multiple_of(2) { -1.0 } else { 1.0 };
            p[k] = if face.is_multiple_of(2) {
                min[k]
            } else {
                min[k] + size[k]
            };
            let hit = Hit {
                t: 1.0,
                local: p,
                uv: None,
                tag: face,
            };
            assert_eq!(b.shading(&hit).normal, Some(n), "the outward normal");
            let origin = p + n * (1e-9 * (1.0 + p.abs().max_element()));
            rays += usize::from(leaving_ray_misses(&b, origin, n, &mut rng, &mut ws));
        }
        assert!(rays > 1500, "{rays} rays");
    }
}

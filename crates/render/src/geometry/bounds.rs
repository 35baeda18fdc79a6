//! [`Bounds3`]: axis-aligned boxes and the slab test (Stam Annexe B `IntBoundBox`).

use std::ops::Range;

use glam::DVec3;

use super::{Ray, Transform, gamma};

/// An axis-aligned box `[min, max]`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Bounds3 {
    /// Lowest corner.
    pub min: DVec3,
    /// Highest corner.
    pub max: DVec3,
}

impl Bounds3 {
    /// The box with the given corners (`min ≤ max` componentwise is the caller's business; an
    /// inverted box is empty for [`Bounds3::intersect_ray`]).
    pub fn new(min: DVec3, max: DVec3) -> Self {
        Bounds3 { min, max }
    }

    /// The smallest box holding every point of `points`.
    pub fn from_points(points: impl IntoIterator<Item = DVec3>) -> Self {
        let mut b = Bounds3::new(DVec3::INFINITY, DVec3::NEG_INFINITY);
        for p in points {
            b.min = b.min.min(p);
            b.max = b.max.max(p);
        }
        b
    }

    /// The box holding both.
    pub fn union(&self, other: &Bounds3) -> Bounds3 {
        Bounds3::new(self.min.min(other.min), self.max.max(other.max))
    }

    /// The overlap of both boxes (possibly empty: some `min > max`).
    pub fn intersection(&self, other: &Bounds3) -> Bounds3 {
        Bounds3::new(self.min.max(other.min), self.max.min(other.max))
    }

    /// Length of the diagonal.
    pub fn diagonal(&self) -> f64 {
        (self.max - self.min).length()
    }

    /// The eight corners.
    pub fn corners(&self) -> [DVec3; 8] {
        let (a, b) = (self.min, self.max);
        [
            DVec3::new(a.x, a.y, a.z),
            DVec3::new(b.x, a.y, a.z),
            DVec3::new(a.x, b.y, a.z),
            DVec3::new(b.x, b.y, a.z),
            DVec3::new(a.x, a.y, b.z),
            DVec3::new(b.x, a.y, b.z),
            DVec3::new(a.x, b.y, b.z),
            DVec3::new(b.x, b.y, b.z),
        ]
    }

    /// The box of the transformed corners: a conservative box of the transformed box.
    pub fn transformed(&self, t: &Transform) -> Bounds3 {
        let b = Bounds3::from_points(self.corners().map(|c| t.apply_point(c)));
        // Cover the rounding of the corner transforms (3 products and 3 sums per coordinate).
        let pad = b.min.abs().max(b.max.abs()) * gamma(4);
        Bounds3::new(b.min - pad, b.max + pad)
    }

    /// Whether `p` lies in the closed box.
    pub fn contains(&self, p: DVec3) -> bool {
        p.cmpge(self.min).all() && p.cmple(self.max).all()
    }

    /// The parameter interval where `ray` is inside the box, clipped to `range`, or `None`
    /// when they do not overlap (the slab test; Kay & Kajiya; Stam `IntBoundBox`).
    ///
    /// # Accuracy
    /// Conservative: the far distance of each slab is enlarged by `1 + 2γ(3)` (pbrt-v4
    /// §6.8.2), so rounding never rejects a ray that touches the box. A zero direction
    /// component gives infinite slab distances, handled by IEEE arithmetic; `0·∞` (origin on a
    /// slab plane) yields NaN and the comparisons below then keep the other slabs' values.
    pub fn intersect_ray(&self, ray: &Ray, range: Range<f64>) -> Option<Range<f64>> {
        self.intersect_ray_inv(ray.origin, DVec3::ONE / ray.dir, range)
    }

    /// [`Bounds3::intersect_ray`] for the ray from `origin` with reciprocal direction `inv`
    /// (`1/dir` componentwise), which a hierarchy computes once per ray.
    #[inline]
    pub fn intersect_ray_inv(
        &self,
        origin: DVec3,
        inv: DVec3,
        range: Range<f64>,
    ) -> Option<Range<f64>> {
        let mut t0 = range.start;
        let mut t1 = range.end;
        for k in 0..3 {
            let mut near = (self.min[k] - origin[k]) * inv[k];
            let mut far = (self.max[k] - origin[k]) * inv[k];
            if near > far {
                std::mem::swap(&mut near, &mut far);
            }
            far *= 1.0 + 2.0 * gamma(3);
            // NaN-tolerant: a NaN slab (origin on the plane, direction zero) does not clip.
            if near > t0 {
                t0 = near;
            }
            if far < t1 {
                t1 = far;
            }
            if t0 > t1 {
                return None;
            }
        }
        Some(t0..t1)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn slab_test_clips_and_rejects() {
        let b = Bounds3::new(DVec3::splat(-1.0), DVec3::splat(1.0));
        let ray = Ray::new(DVec3::new(-5.0, 0.0, 0.0), DVec3::X);
        let r = b.intersect_ray(&ray, 0.0..f64::INFINITY).expect("hits");
        assert!(
            (r.start - 4.0).abs() < 1e-12 && (r.end - 6.0).abs() < 1e-12,
            "{r:?}"
        );
        let miss = Ray::new(DVec3::new(-5.0, 2.0, 0.0), DVec3::X);
        assert_eq!(
            b.intersect_ray(&miss, 0.0..f64::INFINITY),
            None,
            "parallel, outside"
        );
        assert_eq!(b.intersect_ray(&ray, 0.0..3.0), None, "ends before the box");
        let inside = Ray::new(DVec3::ZERO, DVec3::new(0.0, 0.0, -1.0));
        let r = b
            .intersect_ray(&inside, 0.0..f64::INFINITY)
            .expect("starts inside");
        assert_eq!(r.start, 0.0, "clipped to the range start");
    }
}

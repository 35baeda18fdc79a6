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
    /// The box with the given corners (`min ≤ max` componentwise is the caller's business: the
    /// slab tests [`Bounds3::intersect_ray`] and [`Bounds3::slab`] order each slab's two
    /// distances, so they read an inverted box as the box between its corners;
    /// [`Bounds3::slab_by_sign`] needs `min ≤ max`).
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
    /// slab plane with a zero direction component) yields NaN, and that slab does not clip:
    /// the ray is inside the box where the other slabs say.
    pub fn intersect_ray(&self, ray: &Ray, range: Range<f64>) -> Option<Range<f64>> {
        self.slab(&ray.slab_ray(), range.start, range.end)
            .map(|(t0, t1)| t0..t1)
    }

    /// The slab test against a [`SlabRay`] (prepared once per ray by a hierarchy): the
    /// interval `(t0, t1)` where the ray is inside the box, clipped to `start..end`, or `None`.
    /// Same accuracy as [`Bounds3::intersect_ray`].
    ///
    /// Without a branch per slab, one comparison at the end: each slab's ends are ordered, and
    /// the running `max`/`min` taken, by `if a > b` selects, which keep the first value when
    /// the other is NaN (origin on a slab plane with a zero direction component), so a NaN
    /// slab does not clip. The answer is that of a loop stopping at the first slab that
    /// empties the interval (the interval only narrows from slab to slab), without that
    /// loop's data-dependent branches (issue 12: 5 % of the CPU time of the sphereflake).
    #[inline(always)]
    pub fn slab(&self, ray: &SlabRay, start: f64, end: f64) -> Option<(f64, f64)> {
        let lo = (self.min - ray.origin) * ray.inv;
        let hi = (self.max - ray.origin) * ray.inv;
        let (mut t0, mut t1) = (start, end);
        for k in 0..3 {
            let (a, b) = (lo[k], hi[k]);
            // Swapped when `a > b` (a negative direction); a NaN end is not swapped, and then
            // neither end clips below.
            let (near, far) = if a > b { (b, a) } else { (a, b) };
            let far = far * FAR_SCALE;
            t0 = if near > t0 { near } else { t0 };
            t1 = if far < t1 { far } else { t1 };
        }
        // Written as `t0 > t1` (not `t0 <= t1`), so a NaN range answers as the loop did.
        if t0 > t1 { None } else { Some((t0, t1)) }
    }

    /// [`Bounds3::slab`] for a box with `min ≤ max` on every axis, bit for bit, without
    /// ordering each slab's two distances: the near plane of each slab is picked by the sign
    /// of the ray's direction, computed once per ray in the [`SlabRay`] (Williams et al. 2005,
    /// "An efficient and robust ray–box intersection algorithm"; pbrt-v4 `Bounds3::IntersectP`
    /// with `dirIsNeg`). The hierarchy's node boxes are such boxes (unions of its items' boxes,
    /// which it orders), and the comparison and two selects per slab were a third of the
    /// sphereflake's slab-test instructions (issue 12, sixth pass).
    ///
    /// Same answer: with `1/d ≥ 0` (`+∞` for a zero component, as a `SlabRay` stores it)
    /// `(min − o)/d ≤ (max − o)/d` (rounding is monotone) or one of them is NaN, and
    /// [`Bounds3::slab`] keeps that order; with `1/d < 0` (finite) it swaps them, or they are
    /// equal — the same value, so the same bits.
    #[inline(always)]
    pub fn slab_by_sign(&self, ray: &SlabRay, start: f64, end: f64) -> Option<(f64, f64)> {
        let (mut t0, mut t1) = (start, end);
        for k in 0..3 {
            let (lo, hi) = if ray.neg[k] {
                (self.max[k], self.min[k])
            } else {
                (self.min[k], self.max[k])
            };
            let near = (lo - ray.origin[k]) * ray.inv[k];
            let far = (hi - ray.origin[k]) * ray.inv[k] * FAR_SCALE;
            t0 = if near > t0 { near } else { t0 };
            t1 = if far < t1 { far } else { t1 };
        }
        if t0 > t1 { None } else { Some((t0, t1)) }
    }
}

/// `1 + 2γ(3)`: the enlargement of each slab's far distance (pbrt-v4 §6.8.2), as a constant
/// (`γ(3) = 3u/(1 − 3u)`, `u = ε/2`; checked against [`gamma`] in the tests).
pub(super) const FAR_SCALE: f64 =
    1.0 + 2.0 * (3.0 * (f64::EPSILON / 2.0) / (1.0 - 3.0 * (f64::EPSILON / 2.0)));

/// A ray prepared for many slab tests ([`Bounds3::slab`]): its origin and reciprocal
/// direction, with an infinite component (a zero direction component) always `+∞`, so that a
/// direction of `−0` answers as `+0` does (a NaN slab then never clips, whichever side of
/// the slab the origin lies on).
#[derive(Clone, Copy, Debug)]
pub struct SlabRay {
    pub(super) origin: DVec3,
    pub(super) inv: DVec3,
    /// `inv < 0` per axis: the slab's near plane is the box's `max` there.
    pub(super) neg: [bool; 3],
}

impl SlabRay {
    /// The ray from `origin` along `dir` ([`Ray::slab_ray`]).
    #[inline]
    pub fn new(ray: &Ray) -> Self {
        ray.slab_ray()
    }

    /// The ray from `origin` with reciprocal direction `inv` whose infinite components are
    /// already `+∞` (as [`Ray::new`] stores it).
    #[inline]
    pub(crate) fn from_unsigned_inv(origin: DVec3, inv: DVec3) -> Self {
        SlabRay {
            origin,
            inv,
            neg: [inv.x < 0.0, inv.y < 0.0, inv.z < 0.0],
        }
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

    /// A ray lying in a face plane of the box (origin on the plane, zero direction component)
    /// is inside the box whatever the sign of that zero: the slab test used to reject it for
    /// `−0` (the NaN of `0·(−∞)` landed on the far side) and accept it for `+0`, so a box
    /// hierarchy could answer differently from a mirrored scene.
    #[test]
    fn ray_in_a_face_plane_is_inside_for_either_signed_zero() {
        let b = Bounds3::new(DVec3::ZERO, DVec3::ONE);
        for zero in [0.0, -0.0] {
            let ray = Ray::new(DVec3::new(-1.0, 0.5, 0.0), DVec3::new(1.0, 0.0, zero));
            let r = b.intersect_ray(&ray, 0.0..f64::INFINITY);
            let r = r.unwrap_or_else(|| panic!("dir.z = {zero:?}: in the face z = 0"));
            assert!(
                (r.start - 1.0).abs() < 1e-12 && (r.end - 2.0).abs() < 1e-12,
                "{r:?}"
            );
        }
    }

    /// The slab test by sign is the general one bit for bit on boxes with `min ≤ max`:
    /// random rays through a grid of boxes (flat ones included), rays in face planes (NaN
    /// slabs, either signed zero), ranges starting before and after the origin.
    #[test]
    fn slab_by_sign_is_the_slab_test_bit_for_bit() {
        use rand::{Rng, SeedableRng};
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(12);
        let boxes: Vec<Bounds3> = (0..40)
            .map(|i| {
                let lo = DVec3::new(
                    f64::from(rng.gen_range(-3..3)),
                    f64::from(rng.gen_range(-3..3)),
                    rng.gen_range(-3.0..3.0),
                );
                Bounds3::new(lo, lo + DVec3::new(1.0, f64::from(i % 3), 0.5))
            })
            .collect();
        let bits = |s: Option<(f64, f64)>| s.map(|(a, b)| (a.to_bits(), b.to_bits()));
        let (mut hits, mut misses) = (0, 0);
        for k in 0..8000 {
            let mut o = DVec3::from_array(std::array::from_fn(|_| rng.gen_range(-6.0..6.0)));
            let mut d = DVec3::from_array(std::array::from_fn(|_| rng.gen_range(-1.0..1.0)));
            let b = &boxes[k % boxes.len()];
            if k % 4 != 0 {
                // Aimed near the box: many of these hit it.
                let jitter = DVec3::from_array(std::array::from_fn(|_| rng.gen_range(-1.0..1.0)));
                d = (b.min + b.max) * 0.5 + jitter - o;
            }
            if k % 3 == 0 {
                // In a face plane of the grid: NaN slabs, with either signed zero.
                d.x = if k % 2 == 0 { 0.0 } else { -0.0 };
                o.x = f64::from(rng.gen_range(-3..3));
            }
            let ray = Ray::new(o, d).slab_ray();
            let (start, end) = (rng.gen_range(-2.0..1.0), rng.gen_range(1.0..20.0));
            let general = b.slab(&ray, start, end);
            assert_eq!(
                bits(b.slab_by_sign(&ray, start, end)),
                bits(general),
                "{b:?} {ray:?}"
            );
            if general.is_some() {
                hits += 1;
            } else {
                misses += 1;
            }
        }
        assert!(
            hits > 1000 && misses > 1000,
            "both answers: {hits} {misses}"
        );
    }

    /// The slab test reads a box with `min > max` on an axis as the box between its corners
    /// (the old documentation said such a box was empty, which the test never did): the
    /// hierarchy orders its items' corners on that reading before using `slab_by_sign`.
    #[test]
    fn an_inverted_box_is_the_box_between_its_corners() {
        let inverted = Bounds3::new(DVec3::new(1.0, 0.0, 1.0), DVec3::new(0.0, 1.0, 0.0));
        let ordered = Bounds3::new(DVec3::ZERO, DVec3::ONE);
        for (o, d) in [
            (DVec3::new(-5.0, 0.5, 0.5), DVec3::X),
            (DVec3::new(0.5, 0.5, 9.0), DVec3::new(0.1, -0.2, -1.0)),
            (DVec3::new(-5.0, 2.0, 0.5), DVec3::X),
        ] {
            let ray = Ray::new(o, d);
            let range = 0.0..f64::INFINITY;
            assert_eq!(
                inverted.intersect_ray(&ray, range.clone()),
                ordered.intersect_ray(&ray, range),
                "{o} {d}"
            );
        }
        let hit = inverted.intersect_ray(&Ray::new(DVec3::new(-5.0, 0.5, 0.5), DVec3::X), 0.0..9.0);
        assert!(hit.is_some(), "not empty");
    }

    #[test]
    fn far_scale_is_one_plus_two_gamma_3() {
        assert_eq!(FAR_SCALE, 1.0 + 2.0 * gamma(3), "the constant matches γ(3)");
    }
}

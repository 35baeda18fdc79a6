//! [`Bounds4`]: four axis-aligned boxes side by side (structure of arrays), tested against one
//! ray at once — the child boxes of a 4-wide hierarchy node (`paper-notes/bvh.md` §2).

use glam::DVec3;

use super::{Bounds3, SlabRay, bounds::FAR_SCALE};

/// Four boxes stored plane by plane: `planes[k][lane]` is the lower corner of box `lane` on
/// axis `k` for `k < 3` and its upper corner on axis `k − 3` for `k ≥ 3`. A lane holding no box
/// is [`Bounds4::EMPTY`]'s (`+∞` lower, `−∞` upper corners), which every ray misses.
///
/// Stored in `f64`, the precision of [`Bounds3`] and of the slab test the hierarchy used
/// before: the four-lane test is then [`Bounds3::slab_by_sign`] on each lane, bit for bit.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Bounds4 {
    planes: [[f64; 4]; 6],
}

impl Bounds4 {
    /// Four empty lanes.
    pub const EMPTY: Bounds4 = Bounds4 {
        planes: [
            [f64::INFINITY; 4],
            [f64::INFINITY; 4],
            [f64::INFINITY; 4],
            [f64::NEG_INFINITY; 4],
            [f64::NEG_INFINITY; 4],
            [f64::NEG_INFINITY; 4],
        ],
    };

    /// Puts `b` in `lane`.
    ///
    /// # Panics
    /// If `lane ≥ 4`.
    pub fn set(&mut self, lane: usize, b: &Bounds3) {
        for k in 0..3 {
            self.planes[k][lane] = b.min[k];
            self.planes[k + 3][lane] = b.max[k];
        }
    }

    /// The box in `lane`.
    ///
    /// # Panics
    /// If `lane ≥ 4`.
    pub fn get(&self, lane: usize) -> Bounds3 {
        let p = &self.planes;
        Bounds3::new(
            DVec3::new(p[0][lane], p[1][lane], p[2][lane]),
            DVec3::new(p[3][lane], p[4][lane], p[5][lane]),
        )
    }

    /// [`Bounds3::slab_by_sign`] on each lane, for boxes with `min ≤ max` (or empty lanes):
    /// lane `i`'s `(t0[i], t1[i])` are that test's interval, bit for bit, and the ray misses
    /// box `i` in `start..end` exactly when `t0[i] > t1[i]` (or either is NaN, as there).
    ///
    /// The same operations in the same order on each lane (two subtractions, three
    /// multiplications and the `if a > b` selects, which keep the first operand when the other
    /// is NaN: x86's `maxpd`/`minpd`), written over arrays so that the compiler tests the lanes
    /// side by side without `unsafe` intrinsics. The plane of each slab's near and far side is
    /// picked by the direction's sign once per axis, not per lane. An empty lane gives
    /// `t0 = +∞ > t1 = −∞`: `±∞ − o` keeps its sign and the reciprocal direction is never zero.
    #[inline(always)]
    pub fn slab_by_sign(&self, ray: &SlabRay, start: f64, end: f64) -> ([f64; 4], [f64; 4]) {
        let mut t0 = [start; 4];
        let mut t1 = [end; 4];
        for k in 0..3 {
            let neg = usize::from(ray.neg[k]);
            let lo = &self.planes[k + 3 * neg];
            let hi = &self.planes[k + 3 * (1 - neg)];
            let (o, inv) = (ray.origin[k], ray.inv[k]);
            for lane in 0..4 {
                let near = (lo[lane] - o) * inv;
                let far = (hi[lane] - o) * inv * FAR_SCALE;
                t0[lane] = if near > t0[lane] { near } else { t0[lane] };
                t1[lane] = if far < t1[lane] { far } else { t1[lane] };
            }
        }
        (t0, t1)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::Ray;

    /// Each lane of the four-lane test is the one-box test by sign bit for bit, on random
    /// boxes of a unit grid (flat ones and ones sharing faces included), rays in face planes
    /// (NaN slabs, either signed zero) and empty lanes, which every ray misses.
    #[test]
    fn each_lane_is_the_one_box_test_bit_for_bit() {
        use rand::{Rng, SeedableRng};
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(12);
        let bits = |s: Option<(f64, f64)>| s.map(|(a, b)| (a.to_bits(), b.to_bits()));
        let (mut hits, mut misses) = (0, 0);
        for k in 0..4000 {
            let mut quad = Bounds4::EMPTY;
            let lanes = 1 + k % 4;
            let boxes: Vec<Bounds3> = (0..lanes)
                .map(|i| {
                    let lo = DVec3::new(
                        f64::from(rng.gen_range(-3..3)),
                        f64::from(rng.gen_range(-3..3)),
                        rng.gen_range(-3.0..3.0),
                    );
                    Bounds3::new(lo, lo + DVec3::new(1.0, (i % 3) as f64, 0.5))
                })
                .collect();
            for (i, b) in boxes.iter().enumerate() {
                quad.set(i, b);
                assert_eq!(quad.get(i), *b, "lane {i} round trip");
            }
            let mut o = DVec3::from_array(std::array::from_fn(|_| rng.gen_range(-6.0..6.0)));
            let mut d = DVec3::from_array(std::array::from_fn(|_| rng.gen_range(-1.0..1.0)));
            if k % 3 != 0 {
                let b = &boxes[k % lanes];
                let jitter = DVec3::from_array(std::array::from_fn(|_| rng.gen_range(-1.0..1.0)));
                d = (b.min + b.max) * 0.5 + jitter - o;
            }
            if k % 5 < 2 {
                d.x = if k % 2 == 0 { 0.0 } else { -0.0 };
                o.x = f64::from(rng.gen_range(-3..3));
            }
            let ray = Ray::new(o, d).slab_ray();
            let (start, end) = (rng.gen_range(-2.0..1.0), rng.gen_range(1.0..20.0));
            let (t0, t1) = quad.slab_by_sign(&ray, start, end);
            for lane in 0..4 {
                let four = if t0[lane] > t1[lane] {
                    None
                } else {
                    Some((t0[lane], t1[lane]))
                };
                if lane < lanes {
                    let one = boxes[lane].slab_by_sign(&ray, start, end);
                    assert_eq!(bits(four), bits(one), "lane {lane} of {boxes:?}, {ray:?}");
                    if one.is_some() {
                        hits += 1;
                    } else {
                        misses += 1;
                    }
                } else {
                    assert_eq!(four, None, "an empty lane is missed: {ray:?}");
                }
            }
        }
        assert!(hits > 400 && misses > 1000, "both answers: {hits} {misses}");
    }
}

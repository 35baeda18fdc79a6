//! [`Ray`]: `R(t) = origin + t·dir` (Stam eq. 2.1).

use glam::DVec3;

use poly::UNIT_ROUNDOFF;

use super::{SlabRay, gamma};

/// A ray `R(t) = origin + t·dir` (Stam eq. 2.1). `dir` need not be unit length: a
/// [`Transformed`](crate::surface) surface sees the ray in object space with the same `t`.
///
/// The reciprocal direction is computed once, here, for every slab test the ray meets (the
/// BVH's nodes, then each surface's own box): three divisions a test were 4 % of the
/// sphereflake's time (issue 12). The fields are read, never written, after [`Ray::new`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Ray {
    /// The origin `R_o`.
    pub origin: DVec3,
    /// The direction `V`.
    pub dir: DVec3,
    /// `1/dir` componentwise, an infinite component always `+∞` (see [`SlabRay`]).
    inv_dir: DVec3,
}

impl Ray {
    /// The ray from `origin` along `dir`.
    pub fn new(origin: DVec3, dir: DVec3) -> Self {
        let unsigned_inf = |x: f64| if x.is_infinite() { f64::INFINITY } else { x };
        let inv = DVec3::ONE / dir;
        Ray {
            origin,
            dir,
            inv_dir: DVec3::new(
                unsigned_inf(inv.x),
                unsigned_inf(inv.y),
                unsigned_inf(inv.z),
            ),
        }
    }

    /// The ray prepared for slab tests: its origin and `1/dir`.
    #[inline]
    pub fn slab_ray(&self) -> SlabRay {
        SlabRay::from_unsigned_inv(self.origin, self.inv_dir)
    }

    /// The point `origin + t·dir`.
    pub fn at(&self, t: f64) -> DVec3 {
        self.origin + self.dir * t
    }

    /// A componentwise bound on the rounding error of [`Ray::at`]:
    /// `γ(2)·(|origin| + |t·dir|)` (one product and one sum per component).
    pub fn at_err(&self, t: f64) -> DVec3 {
        (self.origin.abs() + (self.dir * t).abs()) * gamma(2)
    }
}

/// Moves a hit point `p`, known to within the componentwise error box `p_err`, off the surface
/// with unit normal `n` to the side that `w` points to, so that a ray leaving along `w` starts
/// on the correct side of the surface (after pbrt-v4 `OffsetRayOrigin`).
///
/// # Accuracy
/// The offset along `n` is `d = |n|·p_err`, the largest extent of the error box along the
/// normal, enlarged to `d' = d + 4u(|p|∞ + d)` (`u` = [`UNIT_ROUNDOFF`] = ε/2). Rounding the sum
/// `p + d'n` moves the point along `n` by at most `u·|n|₁·|p + d'n|∞ ≤ √3·u(|p|∞ + d')`, less
/// than the enlargement, so
/// the returned origin lies outside the box of possible true hit points, on `w`'s side of the
/// tangent plane (pbrt rounds each component away instead; this bound avoids the bit
/// manipulation). It does not guard against a surface that curves back within that distance;
/// the error boxes are a few ulps, far below any curvature radius the scenes use.
pub fn offset_ray_origin(p: DVec3, p_err: DVec3, n: DVec3, w: DVec3) -> DVec3 {
    let d = n.abs().dot(p_err);
    let d = d + 4.0 * UNIT_ROUNDOFF * (p.abs().max_element() + d);
    if w.dot(n) < 0.0 { p - n * d } else { p + n * d }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn offset_moves_to_the_side_of_w() {
        let p = DVec3::new(1.0, 2.0, 3.0);
        let err = DVec3::splat(1e-9);
        let n = DVec3::Z;
        let up = offset_ray_origin(p, err, n, DVec3::new(0.3, 0.0, 1.0));
        let down = offset_ray_origin(p, err, n, DVec3::new(0.3, 0.0, -1.0));
        assert!(
            up.z > p.z + 1e-9 * 0.999,
            "moved above by at least the error: {}",
            up.z - p.z
        );
        assert!(down.z < p.z - 1e-9 * 0.999, "moved below: {}", p.z - down.z);
        assert_eq!(up.x, p.x, "no motion along a zero offset component");
        // A zero error box still moves off a point far from the origin by more than rounding.
        let far = DVec3::new(1e6, -3e5, 7.0);
        let n = DVec3::new(0.6, 0.0, 0.8);
        let q = offset_ray_origin(far, DVec3::ZERO, n, n);
        assert!(
            (q - far).dot(n) > 0.0,
            "strictly on w's side: {:e}",
            (q - far).dot(n)
        );
    }
}

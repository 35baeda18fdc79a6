//! [`Plane`]: `F = n·(p − origin)` (Stam §3.1.1).
//!
//! Scene syntax:
//! ```text
//! #object
//! Type = PLANE
//! Origin = (0,0,-1.5)
//! Normal = (0,0,1)
//! ```

use glam::{DVec2, DVec3};

use super::SurfaceKind;
use super::implicit::ImplicitFn;
use crate::geometry::Bounds3;
use crate::trivariate::{Eval3, Poly3, RestrictScratch};

/// A two-sided plane, traced through the shared implicit path (degree 1).
#[derive(Clone, Debug)]
pub struct Plane {
    origin: DVec3,
    normal: DVec3,
    u_axis: DVec3,
    v_axis: DVec3,
    poly: Poly3,
    kind: SurfaceKind,
}

impl Plane {
    /// The plane through `origin` with normal `normal` (non-zero and finite, of any length:
    /// normalised here by [`crate::geometry::unit`]; the zero vector leaves NaN coefficients, a
    /// plane no ray hits, and [`crate::scene::ShapeKind::validate`] refuses it first).
    pub fn new(origin: DVec3, normal: DVec3) -> Self {
        Self::with_kind(origin, normal, SurfaceKind::Plane)
    }

    /// The same, reported under another kind (polygons and triangles use a plane).
    pub(crate) fn with_kind(origin: DVec3, normal: DVec3, kind: SurfaceKind) -> Self {
        let n = crate::geometry::unit(normal).unwrap_or(DVec3::NAN);
        // Texture axes: Stam's textured plane is parallel to z = 0 and indexes the texture by
        // x and y (Annexe B `ColTexture`); other planes get any orthonormal pair.
        let (u_axis, v_axis) = if n.x == 0.0 && n.y == 0.0 {
            (DVec3::X, DVec3::Y)
        } else {
            n.any_orthonormal_pair()
        };
        let poly = Poly3::from_terms([
            (n.x, [1, 0, 0]),
            (n.y, [0, 1, 0]),
            (n.z, [0, 0, 1]),
            (-n.dot(origin), [0, 0, 0]),
        ]);
        Plane {
            origin,
            normal: n,
            u_axis,
            v_axis,
            poly,
            kind,
        }
    }

    /// The unit normal.
    pub fn normal(&self) -> DVec3 {
        self.normal
    }

    /// A point of the plane.
    pub fn origin(&self) -> DVec3 {
        self.origin
    }

    /// The plane restricted to the line `o + t·d`: `[c0, c1]` with `F = c0 + c1·t`,
    /// `c0 = n·(o − origin)`, `c1 = n·d` (lowest coefficient first).
    pub fn restricted(&self, o: DVec3, d: DVec3) -> [f64; 2] {
        [self.normal.dot(o - self.origin), self.normal.dot(d)]
    }
}

impl ImplicitFn for Plane {
    fn kind(&self) -> SurfaceKind {
        self.kind
    }

    fn poly(&self) -> &Poly3 {
        &self.poly
    }

    /// `n·(p − origin)` is negative exactly in the half-space behind the plane.
    fn convex(&self) -> bool {
        true
    }

    /// `n·(o − origin) + (n·d)·t`.
    fn restrict(&self, o: DVec3, d: DVec3, _: &mut RestrictScratch, out: &mut Vec<f64>) {
        out.clear();
        out.extend_from_slice(&self.restricted(o, d));
    }

    fn bounds(&self) -> Option<Bounds3> {
        None
    }

    fn uv(&self, p: DVec3) -> Option<DVec2> {
        let v = p - self.origin;
        Some(DVec2::new(v.dot(self.u_axis), v.dot(self.v_axis)))
    }

    /// [`Poly3::eval_grad`] of the stored polynomial without its power tables: the terms in
    /// their stored order (constant, `z`, `y`, `x`, the zero ones dropped), each adding
    /// `c·p_k` to `F`, `|c|·|p_k|` to its scale and `c`, `|c|` to the gradient's component —
    /// the generic evaluation's products with their factors `1` left out (multiplying by 1
    /// is exact), summed in the same order, so the same values (test
    /// `eval_grad_is_the_generic_evaluation`): the normal and the hit point's error bound are
    /// unchanged. The generic one zeroes and fills six power tables for every shaded hit of a
    /// polygon or triangle (`paper-notes/bvh.md` §3, eighth pass).
    fn eval_grad(&self, p: DVec3) -> Eval3 {
        let mut out = Eval3::default();
        for t in self.poly.terms() {
            let c = t.coeff;
            match t.exps.iter().position(|&e| e == 1) {
                Some(k) => {
                    out.f += c * p[k];
                    out.f_abs += c.abs() * p[k].abs();
                    out.grad[k] += c;
                    out.grad_abs[k] += c.abs();
                }
                None => {
                    out.f += c;
                    out.f_abs += c.abs();
                }
            }
        }
        out
    }
}

#[cfg(test)]
mod tests {
    use rand::{Rng, SeedableRng};

    use super::*;

    #[test]
    fn eval_grad_is_the_generic_evaluation() {
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(12);
        let mut r = |s: f64| rng.gen_range(-s..s);
        for k in 0..3000i32 {
            let origin = DVec3::new(r(100.0), r(100.0), r(100.0));
            let mut normal = DVec3::new(r(1.0), r(1.0), r(1.0));
            // Axis planes (SPD floors, boxes' faces) drop terms; a plane through the origin
            // drops the constant.
            if k % 3 == 0 {
                normal[(k % 4 % 3) as usize] = 0.0;
            }
            if k % 5 == 0 {
                normal = [DVec3::X, DVec3::NEG_Y, DVec3::Z][(k % 3) as usize];
            }
            let origin = if k % 7 == 0 { DVec3::ZERO } else { origin };
            let plane = Plane::new(origin, normal);
            let p = origin + DVec3::new(r(10.0), r(10.0), r(10.0)) * 10f64.powi(k % 9 - 4);
            let (fast, full) = (plane.eval_grad(p), plane.poly().eval_grad(p));
            assert_eq!(fast, full, "plane {origin} n {normal} at {p}");
            // `==` takes -0 for +0: the signs must match too.
            let bits = |e: Eval3| {
                [
                    e.f,
                    e.f_abs,
                    e.grad.x,
                    e.grad.y,
                    e.grad.z,
                    e.grad_abs.x,
                    e.grad_abs.y,
                    e.grad_abs.z,
                ]
                .map(f64::to_bits)
            };
            assert_eq!(
                bits(fast),
                bits(full),
                "plane {origin} n {normal} at {p}, bit for bit"
            );
        }
    }
}

//! [`Plane`]: `F = n·(p − origin)` (Stam §3.1.1).
//!
//! Scene syntax:
//! ```text
//! #object
//! Type = PLANE
//! Origin = (0,0,-1.5)
//! Normal = (0,0,1)
//! ```

use std::sync::OnceLock;

use glam::{DVec2, DVec3};

use super::SurfaceKind;
use super::implicit::ImplicitFn;
use crate::geometry::Bounds3;
use crate::trivariate::{Eval3, Poly3, RestrictScratch};

/// A two-sided plane, traced through the shared implicit path (degree 1).
#[derive(Clone, Debug)]
pub struct Plane {
    origin: DVec3,
    /// The unit normal `n`.
    normal: DVec3,
    /// `F`'s constant term, `−n·origin`.
    constant: f64,
    /// `F` as a [`Poly3`], built on first use, as the sphere's: the plane's restriction,
    /// gradient and texture axes are computed from `n` and the constant, and a polynomial per
    /// polygon was a fifth of the memory of a scene of triangles (130 050 of them, 96 bytes
    /// and an allocation each; `paper-notes/bvh.md`, twenty-first session). `--isolation exact`
    /// and the tests ask.
    poly: OnceLock<Poly3>,
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
        Plane {
            origin,
            normal: n,
            constant: -n.dot(origin),
            poly: OnceLock::new(),
            kind,
        }
    }

    /// The texture axes: Stam's textured plane is parallel to z = 0 and indexes the texture by
    /// x and y (Annexe B `ColTexture`); other planes get any orthonormal pair.
    fn texture_axes(&self) -> (DVec3, DVec3) {
        let n = self.normal;
        if n.x == 0.0 && n.y == 0.0 {
            (DVec3::X, DVec3::Y)
        } else {
            n.any_orthonormal_pair()
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
        self.poly.get_or_init(|| {
            let n = self.normal;
            Poly3::from_terms([
                (n.x, [1, 0, 0]),
                (n.y, [0, 1, 0]),
                (n.z, [0, 0, 1]),
                (self.constant, [0, 0, 0]),
            ])
        })
    }

    fn degree(&self) -> u32 {
        1
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
        let (u_axis, v_axis) = self.texture_axes();
        Some(DVec2::new(v.dot(u_axis), v.dot(v_axis)))
    }

    /// [`Poly3::eval_grad`] of the plane's polynomial without building it or its power
    /// tables: the terms in their stored order (constant, `z`, `y`, `x`, the zero ones
    /// dropped), each adding `c·p_k` to `F`, `|c|·|p_k|` to its scale and `c`, `|c|` to the
    /// gradient's component — the generic evaluation's products with their factors `1` left
    /// out (multiplying by 1 is exact), summed in the same order, so the same values (test
    /// `eval_grad_is_the_generic_evaluation`): the normal and the hit point's error bound are
    /// unchanged. The generic one zeroes and fills six power tables for every shaded hit of a
    /// polygon or triangle (`paper-notes/bvh.md` §3, eighth pass).
    fn eval_grad(&self, p: DVec3) -> Eval3 {
        let mut out = Eval3::default();
        let c = self.constant;
        if c != 0.0 {
            out.f += c;
            out.f_abs += c.abs();
        }
        // Written out term by term: a loop over the terms with a variable axis took about 90
        // instructions a shaded hit more (`paper-notes/bvh.md`, twenty-first session).
        let mut linear = |c: f64, x: f64, g: &mut f64, g_abs: &mut f64| {
            if c != 0.0 {
                out.f += c * x;
                out.f_abs += c.abs() * x.abs();
                *g += c;
                *g_abs += c.abs();
            }
        };
        let (mut grad, mut grad_abs) = (DVec3::ZERO, DVec3::ZERO);
        let n = self.normal;
        linear(n.z, p.z, &mut grad.z, &mut grad_abs.z);
        linear(n.y, p.y, &mut grad.y, &mut grad_abs.y);
        linear(n.x, p.x, &mut grad.x, &mut grad_abs.x);
        out.grad = grad;
        out.grad_abs = grad_abs;
        out
    }
}

#[cfg(test)]
mod tests {
    use rand::{Rng, SeedableRng};

    use super::*;

    /// The polynomial built on demand, and the texture axes computed on demand, are those the
    /// plane stored when it built them at construction (before the twenty-first session): the
    /// `f64` terms of `n·p − n·origin`, zeros dropped, and Stam's axes for a plane parallel to
    /// z = 0, any orthonormal pair otherwise. Fails if a term, its order or an axis changes.
    #[test]
    fn the_plane_built_on_demand_is_the_former_one() {
        let cases = [
            (DVec3::new(1.5, -2.0, 0.25), DVec3::new(0.0, 0.0, 2.0)),
            (DVec3::new(0.0, 3.0, 0.0), DVec3::new(1.0, -2.0, 0.5)),
            (DVec3::ZERO, DVec3::new(0.0, -1.0, 0.0)),
            (DVec3::new(1e6, -1e-6, 7.0), DVec3::new(-3.0, 0.0, 4.0)),
        ];
        for (origin, normal) in cases {
            let plane = Plane::new(origin, normal);
            let n = crate::geometry::unit(normal).unwrap();
            let former = Poly3::from_terms([
                (n.x, [1, 0, 0]),
                (n.y, [0, 1, 0]),
                (n.z, [0, 0, 1]),
                (-n.dot(origin), [0, 0, 0]),
            ]);
            assert_eq!(plane.poly(), &former, "plane {origin} n {normal}");
            assert_eq!(plane.degree(), former.degree(), "plane {origin} n {normal}");
            let (u, v) = if n.x == 0.0 && n.y == 0.0 {
                (DVec3::X, DVec3::Y)
            } else {
                n.any_orthonormal_pair()
            };
            let p = origin + u * 2.5 - v * 0.75;
            let uv = plane.uv(p).unwrap();
            let want = DVec2::new((p - origin).dot(u), (p - origin).dot(v));
            assert_eq!(uv, want, "plane {origin} n {normal}");
        }
    }

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

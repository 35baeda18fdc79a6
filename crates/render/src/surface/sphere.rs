//! [`Sphere`]: `F = |p − c|² − r²` (Stam eq. 2.2).
//!
//! Scene syntax:
//! ```text
//! #object
//! Type = SPHERE
//! Center = (0,0,1)
//! Radius = 1          // or Stam's  Radius^2 = 1
//! ```

use std::sync::OnceLock;

use glam::DVec3;

use super::SurfaceKind;
use super::implicit::ImplicitFn;
use crate::geometry::Bounds3;
use crate::trivariate::{Eval3, Poly3, RestrictScratch};

/// Relative widening of the sphere's own bounding ball ([`ImplicitFn::bounding_sphere`]):
/// large enough that the chord it clips holds both roots with room for the closed form's
/// certifying intervals (which must not reach the range's ends: a root closer to an end than
/// that defers to the general path), small enough that hardly a ray that misses the sphere
/// passes the ball. 2⁻²⁰ ≈ 1e-6.
pub(super) const BALL_MARGIN_REL: f64 = 1.0 / (1u64 << 20) as f64;

/// A sphere, traced through the shared implicit path.
#[derive(Clone, Debug)]
pub struct Sphere {
    center: DVec3,
    radius: f64,
    /// `F` as a [`Poly3`], built on first use: the sphere's own restriction (eq. 2.4), closed
    /// form and gradient never read it, and one per sphere was 11 MB and 66 430 allocations
    /// of the 66 430-sphere scene's set-up (issue 12). `--isolation exact` and the tests ask.
    poly: OnceLock<Poly3>,
}

impl Sphere {
    /// The sphere of radius `radius` (positive, finite) about `center`.
    pub fn new(center: DVec3, radius: f64) -> Self {
        Sphere {
            center,
            radius,
            poly: OnceLock::new(),
        }
    }
}

/// `|p − c|² − r²` expanded, listed in the polynomial's own order (exponents ascending), so
/// that building it sorts nothing (the reversed list took ≈ 420 instructions a sphere to
/// sort).
fn sphere_poly(center: DVec3, radius: f64) -> Poly3 {
    let [c0, cx, cy, cz] = coefficients(center, radius);
    Poly3::from_terms([
        (c0, [0, 0, 0]),
        (cz, [0, 0, 1]),
        (1.0, [0, 0, 2]),
        (cy, [0, 1, 0]),
        (1.0, [0, 2, 0]),
        (cx, [1, 0, 0]),
        (1.0, [2, 0, 0]),
    ])
}

impl ImplicitFn for Sphere {
    fn kind(&self) -> SurfaceKind {
        SurfaceKind::Sphere
    }

    fn poly(&self) -> &Poly3 {
        self.poly
            .get_or_init(|| sphere_poly(self.center, self.radius))
    }

    fn degree(&self) -> u32 {
        2
    }

    /// `|d|²t² + 2d·(o − c)t + |o − c|² − r²` (Stam eq. 2.4).
    fn restrict(&self, o: DVec3, d: DVec3, _: &mut RestrictScratch, out: &mut Vec<f64>) {
        let oc = o - self.center;
        out.clear();
        out.extend_from_slice(&[
            oc.length_squared() - self.radius * self.radius,
            2.0 * d.dot(oc),
            d.length_squared(),
        ]);
    }

    /// The sphere itself, widened by `BALL_MARGIN_REL` (2⁻²⁰): a ray that misses it is rejected
    /// by a distance test before any polynomial is built (among many overlapping spheres most
    /// rays that reach a sphere's box miss it: `paper-notes/bvh.md`, eighteenth session), and
    /// the root search covers the chord inside it.
    fn bounding_sphere(&self) -> Option<(DVec3, f64)> {
        Some((self.center, self.radius * (1.0 + BALL_MARGIN_REL)))
    }

    /// `|p − c|² − r²` is negative exactly inside the ball.
    fn convex(&self) -> bool {
        true
    }

    fn bounds(&self) -> Option<Bounds3> {
        let r = DVec3::splat(self.radius);
        Some(Bounds3::new(self.center - r, self.center + r))
    }

    /// [`Poly3::eval_grad`] of the stored polynomial, written out: the same products summed in
    /// the same order (its terms sorted by exponents: constant, `z`, `z²`, `y`, `y²`, `x`,
    /// `x²`), so the values are those of the generic evaluation (test
    /// `eval_grad_is_the_generic_evaluation`) — the normal and the hit point's error bound
    /// unchanged — at a twentieth of its cost: the generic one built power tables and looped
    /// over the terms, ≈ 550 instructions per shaded hit, 3 % of the SPD sphereflake
    /// (issue 12).
    fn eval_grad(&self, p: DVec3) -> Eval3 {
        let [c0, cx, cy, cz] = coefficients(self.center, self.radius);
        let a = p.abs();
        Eval3 {
            f: c0 + cz * p.z + p.z * p.z + cy * p.y + p.y * p.y + cx * p.x + p.x * p.x,
            f_abs: c0.abs()
                + cz.abs() * a.z
                + a.z * a.z
                + cy.abs() * a.y
                + a.y * a.y
                + cx.abs() * a.x
                + a.x * a.x,
            grad: DVec3::new(cx + 2.0 * p.x, cy + 2.0 * p.y, cz + 2.0 * p.z),
            grad_abs: DVec3::new(
                cx.abs() + 2.0 * a.x,
                cy.abs() + 2.0 * a.y,
                cz.abs() + 2.0 * a.z,
            ),
        }
    }
}

/// The coefficients of `|p − c|² − r²` expanded: the constant, `x`, `y` and `z` terms (the
/// quadratic ones are 1).
fn coefficients(c: DVec3, r: f64) -> [f64; 4] {
    [
        c.length_squared() - r * r,
        -2.0 * c.x,
        -2.0 * c.y,
        -2.0 * c.z,
    ]
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The polynomial listed in sorted order is the one built from the former list (the
    /// quadratic terms first), term for term, centres with zero coordinates included.
    #[test]
    fn sorted_term_list_builds_the_same_polynomial() {
        for (c, r) in [
            (DVec3::new(1.5, -2.0, 0.25), 0.5),
            (DVec3::new(0.0, 3.0, 0.0), 2.0),
            (DVec3::ZERO, 1.0),
            (DVec3::new(1.0, 1.0, 1.0), 3f64.sqrt()),
        ] {
            let [c0, cx, cy, cz] = coefficients(c, r);
            let former = Poly3::from_terms([
                (1.0, [2, 0, 0]),
                (1.0, [0, 2, 0]),
                (1.0, [0, 0, 2]),
                (cx, [1, 0, 0]),
                (cy, [0, 1, 0]),
                (cz, [0, 0, 1]),
                (c0, [0, 0, 0]),
            ]);
            let sphere = Sphere::new(c, r);
            assert_eq!(sphere.poly(), &former, "sphere {c} r {r}");
            // The degree it states without building the polynomial is the polynomial's.
            assert_eq!(
                Sphere::new(c, r).degree(),
                former.degree(),
                "sphere {c} r {r}"
            );
        }
    }

    /// The written-out gradient is the generic evaluation of the stored polynomial, value for
    /// value, at random points about random spheres — centres with zero coordinates (whose
    /// terms the polynomial drops), points on, inside and outside the sphere, far and near.
    #[test]
    fn eval_grad_is_the_generic_evaluation() {
        use rand::{Rng, SeedableRng};
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(12);
        for k in 0..2000 {
            let mut c = DVec3::new(
                rng.gen_range(-50.0..50.0),
                rng.gen_range(-50.0..50.0),
                rng.gen_range(-50.0..50.0),
            );
            if k % 3 == 0 {
                c[k % 4 % 3] = 0.0;
            }
            if k % 7 == 0 {
                c = DVec3::ZERO;
            }
            let r = rng.gen_range(1e-3..20.0);
            let s = Sphere::new(c, r);
            let dir = DVec3::new(
                rng.gen_range(-1.0..1.0),
                rng.gen_range(-1.0..1.0),
                rng.gen_range(-1.0..1.0),
            )
            .normalize_or(DVec3::X);
            let p = c + dir * r * rng.gen_range(0.0..3.0);
            let (fast, full) = (s.eval_grad(p), s.poly().eval_grad(p));
            assert_eq!(fast, full, "sphere {c} r {r} at {p}");
        }
    }
}

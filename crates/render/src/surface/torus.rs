//! [`Torus`]: the quartic `(|p|² + R² − r²)² − 4R²(x² + y²)` about the `z` axis.
//!
//! Scene syntax (the centre and axis are applied by a [`Transformed`](super::Transformed)
//! frame, so the shape itself is canonical):
//! ```text
//! #object
//! Type = TORUS
//! Center = (0,0,0)
//! Axis = (0,0,1)
//! MajorRadius = 2
//! MinorRadius = 1
//! ```
//! See `paper-notes/implicit-surfaces.md` §3 for the restriction's coefficients.

use glam::DVec3;
use poly::{Dd, QPoly, Rat};

use super::SurfaceKind;
use super::implicit::ImplicitFn;

use crate::geometry::Bounds3;
use crate::trivariate::{Eval3, Poly3, RestrictScratch};

/// A torus centred at the origin with axis `z`, traced through the shared implicit path as
/// its quartic.
#[derive(Clone, Debug)]
pub struct Torus {
    major: f64,
    minor: f64,
    poly: Poly3,
}

impl Torus {
    /// The torus with centre-circle radius `major` and tube radius `minor` (both positive).
    pub fn new(major: f64, minor: f64) -> Self {
        let k = major * major - minor * minor;
        let m = 4.0 * major * major;
        // (x² + y² + z² + k)² − m(x² + y²), expanded.
        let poly = Poly3::from_terms([
            (1.0, [4, 0, 0]),
            (1.0, [0, 4, 0]),
            (1.0, [0, 0, 4]),
            (2.0, [2, 2, 0]),
            (2.0, [2, 0, 2]),
            (2.0, [0, 2, 2]),
            (2.0 * k - m, [2, 0, 0]),
            (2.0 * k - m, [0, 2, 0]),
            (2.0 * k, [0, 0, 2]),
            (k * k, [0, 0, 0]),
        ]);
        Torus { major, minor, poly }
    }

    /// The major radius `R`.
    pub fn major(&self) -> f64 {
        self.major
    }

    /// The minor radius `r`.
    pub fn minor(&self) -> f64 {
        self.minor
    }
}

impl ImplicitFn for Torus {
    fn kind(&self) -> SurfaceKind {
        SurfaceKind::Torus
    }

    fn poly(&self) -> &Poly3 {
        &self.poly
    }

    /// With `a = d·d`, `b = 2o·d`, `c = o·o + R² − r²`, `F(o + td) = (at² + bt + c)² −
    /// 4R²((o_x + t d_x)² + (o_y + t d_y)²)`, whose coefficients are written out below.
    fn restrict(&self, o: DVec3, d: DVec3, _: &mut RestrictScratch, out: &mut Vec<f64>) {
        let r2 = self.major * self.major;
        let a = d.length_squared();
        let b = 2.0 * o.dot(d);
        let c = o.length_squared() + r2 - self.minor * self.minor;
        let m = 4.0 * r2;
        out.clear();
        out.extend_from_slice(&[
            c * c - m * (o.x * o.x + o.y * o.y),
            2.0 * b * c - 2.0 * m * (o.x * d.x + o.y * d.y),
            b * b + 2.0 * a * c - m * (d.x * d.x + d.y * d.y),
            2.0 * a * b,
            a * a,
        ]);
    }

    /// `K` of the closed form in [`Torus::restrict`] (the surface as written is the torus of
    /// radii `R`, `r`; Higham's standard model, counting each product's factors' roundings
    /// plus its own): `a = d·d`, `b = 2o·d` carry 3 each, `c = o·o + R·R − r·r` 5; `c₀ =
    /// c·c − m(o_x² + o_y²)` then `5 + 5 + 1 + 1 = 12`, `c₁ = 2bc − …` 10, `c₂ = b² + 2ac − …`
    /// 11, `c₃ = 2ab` and `c₄ = a²` 7.
    fn restriction_rounding_steps(&self) -> u32 {
        12
    }

    /// `G(y) = (y·y + R² + r²)² + 4R²(y_x² + y_y²)`: the closed form on absolute values, summed
    /// over `t` at `y = |o| + t|d|` (it expands to `Σ c̃ₘtᵐ` term by term), and at least the
    /// torus polynomial with absolute-value coefficients. Six roundings on any path, and the
    /// squares of sums one more each: inflated by `2γ(12)`.
    fn restriction_abs(&self, y: DVec3) -> f64 {
        let (r2, q2) = (self.major * self.major, self.minor * self.minor);
        let s = y.length_squared() + r2 + q2;
        (s * s + 4.0 * r2 * (y.x * y.x + y.y * y.y)) * (1.0 + 2.0 * crate::geometry::gamma(12))
    }

    /// `C` of the closed form's underflowing roundings (see
    /// [`Poly3::restriction_underflow_weight`] for the general program): it has fewer than 40
    /// products (`a`, `b`, `c`, `m` and the five coefficients), and an error of `η` in one is
    /// carried to the `R`-weighted output by at most two more factors among `a`, `b`, `c`,
    /// `m = 4R²` and 2, each at most `2·max(1, 4R²)·(1 + R² + r²)·(1 + R + Y)²`, with the
    /// powers of `t` inside `(1 + R + Y)⁴`. The 4 covers the later relative roundings.
    fn restriction_underflow_weight(&self) -> f64 {
        let (r2, q2) = (self.major * self.major, self.minor * self.minor);
        let factor = 2.0 * (4.0 * r2).max(1.0) * (1.0 + r2 + q2);
        4.0 * f64::from_bits(1) * 40.0 * factor * factor
    }

    /// None: the torus's `Poly3` has rounded coefficients (`(R² − r²)²` and the like), so its
    /// double-double restriction is not the surface as written; slack-limited rays go to the
    /// exact tier ([`Torus::restrict_exact`]).
    fn restrict_dd(
        &self,
        _: [Dd; 3],
        _: DVec3,
        _: &mut RestrictScratch<Dd>,
        _: &mut Vec<Dd>,
    ) -> bool {
        false
    }

    /// `(|o + td|² + R² − r²)² − 4R²((o_x + td_x)² + (o_y + td_y)²)` over the rationals.
    fn restrict_exact(&self, o: &[Rat; 3], d: &[Rat; 3]) -> QPoly {
        let rat = |x: f64| poly::rat_from_f64(x).expect("finite radii");
        let (r2, q2) = (
            rat(self.major) * rat(self.major),
            rat(self.minor) * rat(self.minor),
        );
        let line = |k: usize| QPoly::new(vec![o[k].clone(), d[k].clone()]);
        let sq = |k: usize| &line(k) * &line(k);
        let rho2 = &sq(0) + &sq(1);
        let s = &(&rho2 + &sq(2)) + &QPoly::new(vec![&r2 - &q2]);
        let m = QPoly::new(vec![Rat::from_integer(4.into()) * &r2]);
        &(&s * &s) - &(&m * &rho2)
    }

    /// The factored form `F = s² − mρ²` with `s = |p|² + R² − r²`, `m = 4R²`,
    /// `ρ² = x² + y²`: `∇F = 4s·p − 2m·(x, y, 0)`. The absolute sums replace every signed
    /// quantity by its magnitude (`|s| ≤ |p|² + |R² − r²|`), which bounds the rounding of this
    /// evaluation as [`Poly3::eval_grad`]'s sums bound the expanded one.
    fn eval_grad(&self, p: DVec3) -> Eval3 {
        let k = self.major * self.major - self.minor * self.minor;
        let m = 4.0 * self.major * self.major;
        let p2 = p.length_squared();
        let s = p2 + k;
        let s_abs = p2 + k.abs();
        let rho2 = p.x * p.x + p.y * p.y;
        let a = p.abs();
        Eval3 {
            f: s * s - m * rho2,
            f_abs: s_abs * s_abs + m * rho2,
            grad: DVec3::new(
                4.0 * s * p.x - 2.0 * m * p.x,
                4.0 * s * p.y - 2.0 * m * p.y,
                4.0 * s * p.z,
            ),
            grad_abs: DVec3::new(
                4.0 * s_abs * a.x + 2.0 * m * a.x,
                4.0 * s_abs * a.y + 2.0 * m * a.y,
                4.0 * s_abs * a.z,
            ),
        }
    }

    fn bounding_sphere(&self) -> Option<(DVec3, f64)> {
        Some((DVec3::ZERO, self.major + self.minor))
    }

    fn bounds(&self) -> Option<Bounds3> {
        let e = self.major + self.minor;
        Some(Bounds3::new(
            DVec3::new(-e, -e, -self.minor),
            DVec3::new(e, e, self.minor),
        ))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn factored_gradient_matches_the_expanded_polynomial() {
        let t = Torus::new(2.0, 0.7);
        for p in [
            DVec3::new(2.7, 0.0, 0.0),
            DVec3::new(0.3, -1.9, 0.6),
            DVec3::new(1.0, 1.0, -0.2),
        ] {
            let fast = t.eval_grad(p);
            let full = t.poly().eval_grad(p);
            let close = |a: f64, b: f64| (a - b).abs() <= 1e-12 * (1.0 + b.abs());
            assert!(close(fast.f, full.f), "F at {p}: {} vs {}", fast.f, full.f);
            for k in 0..3 {
                assert!(close(fast.grad[k], full.grad[k]), "∂F/∂x{k} at {p}");
            }
            assert!(fast.f_abs >= fast.f.abs(), "the scale bounds the value");
        }
    }

    #[test]
    fn restriction_matches_the_expanded_polynomial() {
        let t = Torus::new(2.0, 1.0);
        let (o, d) = (DVec3::new(0.5, -7.0, 4.0), DVec3::new(-0.05, 0.8, -0.5));
        let mut out = Vec::new();
        t.restrict(o, d, &mut RestrictScratch::default(), &mut out);
        let generic = t.poly().restrict_to_line(o, d);
        for (m, (a, b)) in out.iter().zip(generic.coeffs()).enumerate() {
            assert!((a - b).abs() <= 1e-10 * (1.0 + b.abs()), "c{m}: {a} vs {b}");
        }
    }
}

//! The vocabulary of [`solve`](crate::solve): the elimination [`Method`], the
//! [`SolveOptions`] and their defaults, and what a solve returns ([`Root`], [`Verdict`],
//! [`SolveStats`], [`Solution`]).

use crate::error::Error;

/// Default [`SolveOptions::x_tol`]: roots are located to `1e-10` in `u` and `v` (a Bézier
/// patch spans `[0, 1]²`, so this is 1e-10 of the patch's parameter width).
pub const DEFAULT_X_TOL: f64 = 1e-10;

/// Default [`SolveOptions::f_tol_rel`], `2⁻³⁰ ≈ 9.3e-10`.
///
/// A true root, polished by Newton's method on `F1`, `F2`, leaves a residual near the
/// evaluation round-off `γ(2(deg_u + deg_v) + 2)·A ≈ 1.6e-15·A` for a bicubic (`A` the sum of
/// the absolute values of the terms at the point). Near a tangency (a double root) the residual
/// only falls quadratically with the position error, so the margin is wide: 2⁻³⁰ accepts
/// tangential hits located to about `√(2⁻³⁰) ≈ 3e-5` and rejects a candidate whose curves are
/// apart by more. Extraneous candidates (a `u`-root whose common `v` is complex or at infinity)
/// have residuals of order `A` and fail by many orders of magnitude.
pub const DEFAULT_F_TOL_REL: f64 = 1.0 / (1u64 << 30) as f64;

/// How `v` is eliminated.
///
/// All four are exact over `Rat`. Over `f64` they differ sharply: Gröbner elimination is a
/// long chain of cancellations (a polynomial remainder sequence in `u`) that round-off turns
/// into noise beyond eliminant degree ~6 — the instability Stam reports (article §5). So over
/// `f64` the Gröbner methods keep, for every basis element, a bound on its distance to the
/// ideal (the `tracked` module), and use the basis only where that bound *certifies* it: a
/// constant larger than its bound (no root in the box), or an eliminant whose near-zero set
/// `{u : |ê(u)| ≤ bound}` is a few narrow intervals, each searched from its midpoint with `v`
/// from `F1`, `F2`. Otherwise they solve the Bézout resultant instead
/// ([`SolveStats::fallback`]). Measured on the teapot (`paper-notes/groebner.md` §5) the
/// certificate holds on ~7% of the ray/piece systems that pass the tracer's hull test (Stam's
/// loop per ray, stopped at its first eliminant: `per_ray.rs`); the result always matches the
/// resultant's. The resultants are determinants of matrices of low-degree coefficients and
/// stay accurate to degree 18. Hence the default, [`Method::BezoutResultant`].
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
#[non_exhaustive]
pub enum Method {
    /// Stam's simplified two-polynomial Gröbner loop ([`stam_basis`](crate::stam_basis)).
    Stam,
    /// Buchberger's algorithm and the reduced basis ([`buchberger`](crate::buchberger)).
    Buchberger,
    /// Kajiya's approach: `Res_v(F1, F2)` by Sylvester's matrix
    /// ([`sylvester_resultant_v`](crate::sylvester_resultant_v)).
    Resultant,
    /// As [`Method::Resultant`] with Bézout's smaller matrix
    /// ([`bezout_resultant_v`](crate::bezout_resultant_v)): 3 × 3 instead of 6 × 6 for a
    /// bicubic. The default.
    #[default]
    BezoutResultant,
}

impl Method {
    /// Whether the method eliminates by a Gröbner basis (Stam's loop or Buchberger's).
    pub(crate) fn is_groebner(self) -> bool {
        matches!(self, Method::Stam | Method::Buchberger)
    }
}

/// Options of [`solve`](crate::solve).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SolveOptions {
    /// The elimination method.
    pub method: Method,
    /// The `u`-interval searched (closed). Default `[0, 1]`.
    pub u_range: [f64; 2],
    /// The `v`-interval searched (closed). Default `[0, 1]`.
    pub v_range: [f64; 2],
    /// Tolerance on root positions (absolute, in `u` and `v` units): `u`-roots are refined to
    /// it, the box is widened by it (so a root on a patch edge is not lost to round-off), and
    /// the residual test allows for it. Default [`DEFAULT_X_TOL`].
    pub x_tol: f64,
    /// Relative residual accepted at a root, see [`Root`] and [`DEFAULT_F_TOL_REL`].
    pub f_tol_rel: f64,
}

impl Default for SolveOptions {
    fn default() -> Self {
        SolveOptions {
            method: Method::default(),
            u_range: [0.0, 1.0],
            v_range: [0.0, 1.0],
            x_tol: DEFAULT_X_TOL,
            f_tol_rel: DEFAULT_F_TOL_REL,
        }
    }
}

/// A verified common root `(u, v)`.
///
/// Verified means: for both `k = 1, 2`,
/// `|F_k(u, v)| ≤ f_tol_rel · A_k(u, v) + (|∂F_k/∂u| + |∂F_k/∂v|) · x_tol`,
/// where `A_k(u, v) = Σ|a_ij||u|^i|v|^j` is the size of `F_k`'s terms at the point (the scale of
/// its evaluation round-off) and the gradient term allows for the position tolerance.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Root {
    /// The `u` coordinate.
    pub u: f64,
    /// The `v` coordinate.
    pub v: f64,
}

/// What the elimination says about the complex common roots (article Theorems 1–3).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
#[non_exhaustive]
pub enum Verdict {
    /// No common root at all, real or complex (`1 ∈ G`, Theorem 1; or a non-zero constant
    /// resultant): the ray misses. From an `f64` Gröbner basis: a constant element certified
    /// larger than its error bound over the box, which proves only that no common root lies in
    /// the box (see [`Method`]).
    NoCommonRoot,
    /// Finitely many common roots; the real ones in the box are in [`Solution::roots`].
    Finite,
    /// The curves share a whole component (infinitely many common roots: the ray runs inside
    /// the surface, e.g. along a ruling); no points are reported.
    Infinite,
}

/// Per-solve statistics (the article's table reports the first three per image, §5).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub struct SolveStats {
    /// Number of basis elements (Gröbner methods); 0 for the resultant methods.
    pub basis_size: usize,
    /// Degree of the univariate polynomial in `u` (eliminant or resultant); 0 if none.
    pub u_degree: usize,
    /// `v`-degree of the first polynomial substituted into (the basis element of lowest
    /// positive `Deg_v`, article §4.4; `min Deg_v(F1, F2)` for resultants); 0 if none.
    pub v_degree: usize,
    /// Exact mode only: the largest coefficient, in bits, of the basis elements or resultant,
    /// each scaled to a primitive integer polynomial (coprime integer coefficients).
    pub coeff_bits: Option<u64>,
    /// `u` candidates: real roots of the `u`-polynomial in the (widened) `u`-range, plus, in
    /// `f64` mode, its near-double roots.
    pub u_roots: usize,
    /// `(u, v)` candidates rejected by the residual test (extraneous factors, complex `v`).
    pub rejected: usize,
    /// `f64` Gröbner methods only: the basis could not be certified (see [`Method`]) and the
    /// Bézout resultant was solved instead; `u_degree` is then the resultant's.
    pub fallback: bool,
}

/// The outcome of [`solve`](crate::solve).
#[derive(Clone, Debug, PartialEq)]
pub struct Solution {
    /// Verified roots in the box, sorted by `u` then `v`.
    pub roots: Vec<Root>,
    /// What the algebra says about all complex roots.
    pub verdict: Verdict,
    /// Statistics of this solve.
    pub stats: SolveStats,
}

/// Refuses ranges that are empty or not finite and tolerances that are not finite and
/// positive ([`Error::InvalidRange`], [`Error::InvalidTolerance`]).
pub(crate) fn check_options(opts: &SolveOptions) -> Result<(), Error> {
    for (which, r) in [("u", opts.u_range), ("v", opts.v_range)] {
        if !(r[0].is_finite() && r[1].is_finite() && r[0] <= r[1]) {
            return Err(Error::InvalidRange {
                which,
                lo: r[0],
                hi: r[1],
            });
        }
    }
    for (name, value) in [("x_tol", opts.x_tol), ("f_tol_rel", opts.f_tol_rel)] {
        if !(value.is_finite() && value > 0.0) {
            return Err(Error::InvalidTolerance { name, value });
        }
    }
    Ok(())
}

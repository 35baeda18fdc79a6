//! Bivariate polynomial systems `F1(u, v) = F2(u, v) = 0`, the equations of a ray meeting a
//! polynomial patch: Stam's two-polynomial Gröbner reduction, Buchberger's algorithm and
//! Kajiya-style resultants, over exact rationals and over `f64`.
//!
//! Sources: J. Stam, *Ray tracing polynomial patches using Groebner bases* (1988; seed
//! `001_…`, Annexe A §2–4, and `ray3.c` in Annexe B) and J. Kajiya, *Ray tracing parametric
//! patches* (1982). The mathematics is restated in `paper-notes/groebner.md` and
//! `paper-notes/resultant.md`; every algorithm cites its section there.
//!
//! * Reduction in Stam's total-lexicographic order ([`poly::Monomial`]): [`reduction_step`],
//!   [`normal_form`], [`s_polynomial`], the mutual reduction [`r2`].
//! * Gröbner bases: Stam's loop [`stam_basis`], Buchberger's [`buchberger`],
//!   [`reduce_basis`], [`is_groebner_basis`], and the theorems as queries on a [`Basis`].
//! * Resultants in `v`: [`sylvester_resultant_v`], [`bezout_resultant_v`].
//! * Solving in a box: [`solve`] with [`SolveOptions`], giving verified [`Root`]s, a [`Verdict`]
//!   and per-solve [`SolveStats`].
//! * The ray / patch equations: [`ray_patch_system`]; the tracer's per-ray call
//!   [`solve_ray_patch`] in a reusable [`SolveWorkspace`].
//!
//! # Exact and `f64` modes
//! Every algorithm is generic over [`SolveScalar`]: [`poly::Rat`] (exact, no thresholds) or
//! `f64`. In `f64` a coefficient is treated as zero when a running bound on its round-off
//! error cannot certify it is non-zero (relative to the whole computation that formed it, not
//! a fixed constant such as Stam's `1e-9`; details in the `tracked` module docs and
//! `paper-notes/groebner.md` §5). `f64` Gröbner elimination is nevertheless unstable beyond
//! eliminant degree ~6: [`solve`] uses an `f64` basis only where its error bounds certify it
//! and otherwise falls back to the resultant ([`Method`]), and [`Method::BezoutResultant`] is
//! the default method.
//!
//! # Layers
//! Modules read top-down; each uses only the ones below it (checked by
//! `.ci/module_graph.py`). The algebra needs only [`poly::Scalar`]; solving adds
//! [`SolveScalar`] (the bridge to `poly`'s root finders).
//!
//! ```text
//! solving     solve.rs           solve, solve_ray_patch; the general path's elimination
//!             per_ray.rs         the fixed-size (bicubic, f64) elimination, SolveWorkspace
//!             driver.rs          the steps after elimination, one copy for both paths
//!             options.rs         Method, SolveOptions, Root, Verdict, SolveStats, Solution
//!             scalar.rs          SolveScalar (f64 | Rat)
//! ray/patch   ray_patch.rs       F1, F2 of a ray and a patch (article §2)
//! resultants  resultant.rs       Sylvester, Bézout, division-free determinant
//!             bezout_bicubic.rs  the Bézout determinant in fixed-size arrays
//!             mod_p.rs           residues mod 2³¹ − 1: a quick proof that a common root exists
//! algebra     stam_grid.rs       Stam's loop on fixed grids (per ray)
//!             stam_loop.rs       Stam's loop (article §4.2)
//!             buchberger.rs      Buchberger's algorithm, reduced bases
//!             reduction.rs       →F, normal forms, S-polynomials, R2
//!             tracked.rs         polynomials with ideal-distance bounds, the certificate bound
//!             basis.rs           Basis and Theorems 1–3; bicubic.rs, error.rs
//! ```
//!
//! # Tolerances
//! Every threshold of the crate in one table (each constant is documented where it is
//! defined; `paper-notes/groebner.md` §5 has the measurements behind the speed heuristics).
//! Exact mode (`Rat`) uses none of them but the solve options and the work limits.
//!
//! | Name | Bounds | Kind | Why this value |
//! |---|---|---|---|
//! | `ZERO_ERR_FACTOR` = 4 (`tracked.rs`) | an `f64` coefficient is zero when `abs(c) ≤ 4·d`, `d` its running error bound | relative to `d` | `d` is first order; 4 covers the second-order terms and drops nothing certified by more than two bits |
//! | `NOISE_ABORT_REL` = 1e-4 (`tracked.rs`) | a new Stam element whose error bound reaches this fraction of its size ends the `f64` run | relative | speed heuristic measured on the teapot; soundness comes from the certificate |
//! | `CERT_SAFETY` = 2 (`tracked.rs`) | factor on the certificate bound | relative | covers the neglected second-order terms |
//! | `CERT_WIDTH_REL` = 1e-6 (`driver.rs`) | widest component of `abs(ê) ≤ Ē` accepted | relative to the `u`-range | its midpoint is then well within Newton's reach |
//! | `VANISH_REL` = 2⁻²⁶ (`driver.rs`) | a coefficient of `g(u_r, v)` counts as zero | relative to its terms | `u_r` is known to `x_tol`; `√ε` leaves room for `x_tol` up to ~1e-9 |
//! | `NEAR_PAIR_REL` = 1e-6 (`driver.rs`) | two `u`-candidates this close are the halves of a split double root, each known only to their gap | relative to the `u`-range | as `CERT_WIDTH_REL`; rounding splits a double root by about `√ε` of the scale |
//! | `NEAR_DOUBLE_REL` = 2⁻²⁶ (`driver.rs`) | a critical point of the `f64` eliminant is a candidate double root | relative to its terms | far above a double root's rounding; spurious candidates are verified |
//! | `NEWTON_MAX_STEP_REL` = 1e-3, `NEWTON_STEPS` = 4 (`driver.rs`) | largest polish step; polish iterations | relative to the box; count | a larger step means the candidate was not near this root |
//! | `MERGE_X_TOLS` = 4, `U_ERR_X_TOLS` = 2 (`driver.rs`) | roots merged within `4·x_tol`; a `u`-candidate's error `2·x_tol` | multiples of `x_tol` | refinement to `x_tol` plus the polish's movement |
//! | `SHARPEN_BITS` = 96, 192, 384 (`driver.rs`) | exact mode: precisions of a narrowed `u`-root | absolute (bits) | `h'` reached 2⁶⁰ on the teapot, `x_tol` ≈ 2⁻³³ |
//! | `EXTREME_SCALE_EXP` = 64 (`driver.rs`) | `f64` inputs beyond `2^±64` are scaled by a power of two | absolute (exponent) | six-fold products stay in range; scene systems are untouched |
//! | [`DEFAULT_X_TOL`] = 1e-10 | root positions | absolute (parameter units) | 1e-10 of a patch's `[0, 1]²` |
//! | [`DEFAULT_F_TOL_REL`] = 2⁻³⁰ | residual accepted at a root | relative to the terms | accepts tangential hits to ~3e-5, rejects extraneous candidates by orders of magnitude |
//! | `poly::F64_NEGLIGIBLE_REL` (`ray_patch.rs`, `Poly::trim_negligible`) | the first cancellation of `F1`, `F2`; trailing resultant coefficients | relative | `poly`'s own rule |
//! | [`STAM_MAX_ROUNDS`], [`R2_MAX_STEPS`], [`BUCHBERGER_MAX_BASIS`], [`BUCHBERGER_MAX_REMAINDERS`], [`MAX_MATRIX_SIZE`]; `MAX_ELEMENTS`, `CAP_U` (`stam_grid.rs`) | work and capacity limits | counts | far above what bicubic systems need; they bound every loop |
//!
//! Unit round-off is [`poly::UNIT_ROUNDOFF`], `γ(k)` is [`poly::gamma`].
//!
//! # Examples
//! ```
//! use groebner::{ray_patch_system, solve, Method, SolveOptions};
//! // The bilinear patch S(u, v) = (u, v, u·v) and a ray straight down through (0.3, 0.6).
//! let z = [0.0; 3];
//! let points = [z, [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]]; // 1, u, v, uv
//! let sys = ray_patch_system(&points, 2, 2, &[0.3, 0.6, 2.0], &[0.0, 0.0, -1.0])?;
//! for method in [Method::Stam, Method::Buchberger, Method::Resultant, Method::BezoutResultant] {
//!     let sol = solve(&sys.f1, &sys.f2, &SolveOptions { method, ..SolveOptions::default() })?;
//!     let hit = sol.roots[0];
//!     assert!((hit.u - 0.3).abs() < 1e-12 && (hit.v - 0.6).abs() < 1e-12);
//!     assert!((sys.t_at(&hit.u, &hit.v) - (2.0 - 0.18)).abs() < 1e-12);
//! }
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

#![warn(unused_crate_dependencies)]

mod basis;
mod bezout_bicubic;
mod bicubic;
mod buchberger;
mod driver;
mod error;
mod mod_p;
mod options;
mod per_ray;
mod ray_patch;
mod reduction;
mod resultant;
mod scalar;
mod solve;
mod stam_grid;
mod stam_loop;
#[cfg(test)]
mod testutil;
mod tracked;

pub use crate::basis::Basis;
pub use crate::buchberger::{
    BUCHBERGER_MAX_BASIS, BUCHBERGER_MAX_REMAINDERS, buchberger, is_groebner_basis, reduce_basis,
};
pub use crate::error::Error;
pub use crate::options::{
    DEFAULT_F_TOL_REL, DEFAULT_X_TOL, Method, Root, Solution, SolveOptions, SolveStats, Verdict,
};
pub use crate::per_ray::SolveWorkspace;
pub use crate::ray_patch::{RayPatchSystem, ray_patch_system};
pub use crate::reduction::{R2_MAX_STEPS, normal_form, r2, reduction_step, s_polynomial};
pub use crate::resultant::{
    MAX_MATRIX_SIZE, bezout_matrix_v, bezout_resultant_v, poly_matrix_det, sylvester_matrix_v,
    sylvester_resultant_v,
};
pub use crate::scalar::SolveScalar;
pub use crate::solve::{RayPatchSolution, solve, solve_ray_patch};
pub use crate::stam_loop::{STAM_MAX_ROUNDS, stam_basis};

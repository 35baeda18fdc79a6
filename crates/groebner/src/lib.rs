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
//! * The ray / patch equations: [`ray_patch_system`].
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

// Layers, top-down (a module uses only the ones below it; `.ci/module_graph.py` checks it):
//   solving   solve → per_ray → driver → options, scalar
//   ray/patch ray_patch
//   resultant resultant → bezout_bicubic
//   algebra   stam_grid, stam_loop, buchberger → reduction → tracked; basis; bicubic; error
mod basis;
mod bezout_bicubic;
mod bicubic;
mod buchberger;
mod driver;
mod error;
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

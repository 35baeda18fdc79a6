//! Univariate and bivariate polynomials over `f64` and exact rationals, with certified real-root
//! isolation: Sturm sequences, Descartes/Bernstein subdivision, and safeguarded refinement.
//!
//! Coefficients are always stored lowest degree first. Every algorithm runs over exact
//! rationals ([`Rat`], the oracle) and over `f64`.
//!
//! # Quick start
//! ```
//! use poly::{Poly, PolyRef, RootError, RootOptions};
//! // (x − 1)(x − 2)(x − 3): every real root, each within 1e-12.
//! let p = Poly::new(vec![-6.0, 11.0, -6.0, 1.0]);
//! let roots = p.real_roots(f64::NEG_INFINITY, f64::INFINITY, 1e-12)?;
//! assert_eq!(roots.len(), 3);
//! // The smallest root in (1.5, 10] — a ray tracer's question.
//! assert!((p.smallest_root(1.5, 10.0, 1e-12).unwrap() - 2.0).abs() <= 1e-12);
//! // A double root is one root (multiplicities are not reported), found all the same.
//! let q = Poly::<f64>::from_roots(&[0.5, 0.5, 4.0]);
//! assert_eq!(q.real_roots(0.0, 10.0, 0.0)?, vec![0.5, 4.0]);
//! // Twelve significant digits of roots of any size (a mixed tolerance), on coefficients
//! // borrowed from the caller's buffer.
//! let c = Poly::<f64>::from_roots(&[1e-3, 1e9]).coeffs().to_vec();
//! let r = PolyRef::new(&c).roots(0.0, 1e10, &RootOptions::relative(0.0, 1e-12)).all()?;
//! assert!((r[0] - 1e-3).abs() <= 1e-15 && (r[1] - 1e9).abs() <= 1e-3);
//! // Bad input is an error, never a panic or a guess.
//! let bad = PolyRef::new(&[1.0, f64::NAN]).roots(0.0, 1.0, &RootOptions::new(1e-9)).all();
//! assert!(matches!(bad, Err(RootError::NonFiniteCoefficient { index: 1 })));
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```
//!
//! # What "certified" means
//! For the default method ([`IsolationMethod::Bernstein`]) and [`IsolationMethod::Exact`],
//! every answer is a theorem about the polynomial as stored (its `f64` coefficients taken as
//! exact): each distinct real root in the range is returned once and none is missed, no value
//! is returned where there is no root, and each value is within the tolerance of its root.
//! Every sign the search uses is proven, in `f64` with a rigorous rounding-error bound, and
//! where that bound is too wide, in double-double, in 237-bit `binary256` or in 256–1024-bit
//! floats, and only then in exact rational arithmetic on that piece alone; every loop has a
//! bound (below), so every query terminates. [`RootStats`] counts each escalation. The two
//! heuristic methods ([`IsolationMethod::Sturm`], [`IsolationMethod::StamSturm`], Stam's 1988
//! code) compute their root counts in `f64` without bounds: they answer
//! [`RootError::Unresolved`] where their own checks see rounding decide a sign, and can
//! still be wrong where no check sees it (`paper-notes/sturm.md`).
//!
//! # Layers
//! `scalar` (the [`Scalar`] trait over `f64` and [`Rat`]) → `univariate` ([`Poly`], the unit
//! roundoff, Horner's rule, root bounds) and `ops` → `rescale` (exact power-of-two rescaling,
//! for evaluation beyond the `f64` range) → `eval_bound` (evaluation with rigorous error
//! bounds) → `sturm`, `stam`, `bernstein`, `descartes` (root counting and isolation in `f64`)
//! → `double_double`, `dd_bernstein`, `shifted`, `octuple`, `multiprec` (the
//! adaptive-precision tiers) → `int_poly`, `exact_oracle`, `exact_bisection` (exact
//! isolation: Descartes or Sturm) → `certified`, `closed_form`, `guess`, `inclusion`,
//! `refine` (the searches, the closed forms, guess and verify, the all-roots inclusion discs,
//! refinement) → `stored`, `isolate` (the queries on [`Poly`]) → `query` ([`PolyRef`] and
//! [`RootQuery`]: the same queries on borrowed coefficients). `near_zero` serves `groebner`'s
//! certificates; `bivariate` builds on `univariate` only.
//!
//! # Tolerances
//! The tolerances that bound an answer or an error, in one table; the thresholds that only
//! choose a path (when to try a guess, a closed form, a wider tier, or to give a heuristic's
//! answer up) are documented where they are defined, and cannot change a certified answer.
//! *Relative* means "times the magnitude it is compared with", *absolute* "in the units of
//! the quantity".
//!
//! | name | bounds | kind | why this value |
//! | --- | --- | --- | --- |
//! | [`UNIT_ROUNDOFF`] `u = 2^-53` | error of one rounded `f64` operation | relative | round-to-nearest (Higham §2.2); every bound below is a multiple of it |
//! | `ETA` `η = 2^-1074` (`univariate.rs`) | error of one rounding that underflows | absolute | the smallest subnormal; the absolute term of every error bound |
//! | [`DD_UNIT`] `= 8u²` | error of one double-double operation | relative | covers the proven `3u²`, `2u²`, `5u²` of Joldes, Muller & Popescu (2017) for sum, scalar product and product |
//! | `OCT_UNIT` `= 2^-236` (`octuple.rs`) | error of one `binary256` operation | relative | twice its unit roundoff `2^-237`, as the wider tiers take `2^(1 − bits)`; underflow is flagged, not bounded |
//! | `OCT_BOUND_WIDEN_EXP` `= −200` (`multiprec.rs`) | widening `1 + 2^-200` of a bound formed in `binary256` | relative | covers its four roundings of `≤ 2^-237`; exact in `binary256` |
//! | [`gamma`]`(k)` | error of `k` chained operations | relative | Higham §3.1 |
//! | [`RootOptions::x_tol`], [`DEFAULT_X_TOL`] `= 1e-10` | distance of a returned root from the true one | absolute | the caller's; the default suits unit-sized geometry |
//! | [`RootOptions::rel_tol`] (default 0) | the same, over `|root|`, combined as `max(x_tol, rel_tol·|root|)` | relative | the caller's; `< 1` so that 0 is never an answer for every root |
//! | [`ROOT_BOUND_MARGIN`] `= 1 + 16u` | widening of Cauchy's and Fujiwara's root bounds | relative | covers the few roundings (division, `powf`) many times over |
//! | [`ROOT_BOUND_UNDERFLOW_PAD`] `= 4η` | the same, for roundings in the subnormal range | absolute | a relative margin means nothing there |
//! | `CAUCHY_ROUNDING_MARGIN` `= 1 + 8u` (`isolate.rs`) | Cauchy's bound replacing an infinite end of a smallest-root query | relative | `n` divisions and one addition, each `≤ u` |
//! | `DISC_REL_ERR` `= 8u`, `DISC_UNDERFLOW_ERR` `= 1e-322` (`closed_form.rs`) | error of the quadratic's discriminant | relative to `c1² + |4c0c2|`; absolute | three roundings per product path, doubled; ≈ 20η for underflow |
//! | `(1 + 8ε)` factors in `eval_bound.rs`, `bernstein.rs` | the roundings of forming an error bound itself | relative | a handful of operations, bounded generously |
//! | `half_tol` `= x_tol/2·(1 − 4ε)` (`refine.rs`) | probe distance around a trial point | relative to `x_tol` | keeps `x ± δ` within `x_tol` after rounding |
//! | [`F64_NEGLIGIBLE_REL`] `= 2^-40` | a coefficient taken as zero in the `f64` algebra (gcd, remainders) | relative to the operands | 12 bits above `ε` for the round-off of a remainder sequence; a heuristic, never used by the certified paths |
//! | `MIN_MAG_GAIN` `= 1/4` (`certified.rs`) | when a fresh Bernstein run on a stuck piece may restart again | relative to the parent's magnitude bound | a run no tighter than that cannot decide more |
//!
//! Loop bounds (every loop has one, so every query terminates): `MAX_RUNS = 16` Bernstein runs
//! and `MAX_SPLITS = 4000` subdivisions per query, `MAX_DEPTH = 52` (a relative width of
//! `2^-52` is one rounding step), `MAX_ITERATIONS = 2200` refinement steps (≈ 2100 halvings
//! take the widest `f64` interval to adjacent numbers), `MAX_HEURISTIC_BISECTIONS = 200` and
//! Stam's `MAX_ISOLATION_STEPS = 200`, `MAX_REFINE_STEPS = 2200`; exact Descartes isolation
//! splits at `f64` points only (finitely many) and spends at most `MAX_SUBULP_TESTS = 400`
//! tests inside one `f64` spacing before the exact Sturm count takes over.
//!
//! # Examples
//! ```
//! use poly::Poly;
//! // (x − 1)(x − 2)(x − 3)
//! let p = Poly::new(vec![-6.0, 11.0, -6.0, 1.0]);
//! assert_eq!(p.eval(&2.0), 0.0);
//! assert_eq!(p.derivative().degree(), 2);
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

// Normal dependencies only: a test build also links the dev-dependencies, which the unit
// tests need not all use.
#![cfg_attr(not(test), warn(unused_crate_dependencies))]

mod bernstein;
mod bivariate;
mod certified;
mod closed_form;
mod dd_bernstein;
mod descartes;
mod double_double;
mod eval_bound;
mod exact_bisection;
mod exact_oracle;
mod guess;
mod inclusion;
mod int_poly;
mod isolate;
mod multiprec;
mod near_zero;
mod octuple;
mod ops;
mod query;
mod refine;
mod rescale;
mod root_error;
mod root_interval;
mod root_options;
mod scalar;
mod shifted;
mod stam;
mod stats;
mod stored;
mod sturm;
#[cfg(any(test, feature = "testutil"))]
pub mod testutil;
mod univariate;

pub use crate::bivariate::{BiPoly, Monomial, QBiPoly};
pub use crate::closed_form::linear_root_in;
pub use crate::double_double::{DD_UNIT, Dd};
pub use crate::near_zero::{
    NearZeroBuffers, near_double_roots_into, near_zero_components_into, real_roots_of_coeffs_into,
};
pub use crate::query::{PolyRef, RootQuery};
pub use crate::root_error::RootError;
pub use crate::root_interval::RootInterval;
pub use crate::root_options::{DEFAULT_X_TOL, IsolationMethod, RefineMethod, RootOptions};
pub use crate::scalar::{F64_NEGLIGIBLE_REL, Rat, Scalar, f64_dyadic, rat_from_f64, rat_to_f64};
pub use crate::stam::StamSturm;
pub use crate::stats::{RootStats, STATS_DEGREES};
pub use crate::sturm::SturmSequence;
pub use crate::univariate::{
    Bounded, Poly, QPoly, ROOT_BOUND_MARGIN, ROOT_BOUND_UNDERFLOW_PAD, UNIT_ROUNDOFF, gamma,
};

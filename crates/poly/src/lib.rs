//! Univariate and bivariate polynomials over `f64` and exact rationals, with certified real-root
//! isolation: Sturm sequences, Descartes/Bernstein subdivision, and safeguarded refinement.
//!
//! Coefficients are always stored lowest degree first. Every algorithm runs over exact
//! rationals ([`Rat`], the oracle) and over `f64`.
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

mod bernstein;
mod bivariate;
mod certified;
mod closed_form;
mod eval_bound;
mod int_poly;
mod isolate;
mod multiprec;
mod ops;
mod refine;
mod root_error;
mod root_interval;
mod root_options;
mod scalar;
mod stam;
mod stats;
mod sturm;
pub mod testutil;
mod univariate;

pub use crate::bivariate::{BiPoly, Monomial, QBiPoly};
pub use crate::root_error::RootError;
pub use crate::root_interval::RootInterval;
pub use crate::root_options::{IsolationMethod, RefineMethod, RootOptions};
pub use crate::scalar::{F64_NEGLIGIBLE_REL, Rat, Scalar, rat_from_f64, rat_to_f64};
pub use crate::stam::StamSturm;
pub use crate::stats::{RootStats, STATS_DEGREES};
pub use crate::sturm::SturmSequence;
pub use crate::univariate::{Bounded, Poly, QPoly, UNIT_ROUNDOFF, gamma};

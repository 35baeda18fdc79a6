//! [`Error`]: what the Gröbner and resultant algorithms refuse to do, and why.

use poly::{BiPoly, Scalar};

/// Errors of the `groebner` crate.
///
/// Numerical trouble in `f64` mode is *not* an error: a solve that finds nothing reports an
/// empty root set with its statistics. Errors are bad input (non-finite coefficients, a zero
/// ray direction, an empty search box) and exceeded work limits, which protect callers from the
/// coefficient swell of exact Gröbner computations.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum Error {
    /// A coefficient of an input polynomial is NaN or infinite.
    #[error("non-finite coefficient in {what}")]
    NonFinite {
        /// Which input ("F1", "F2", "ray origin", …).
        what: &'static str,
    },
    /// The ray direction is the zero vector, so `t` cannot be eliminated (article §2).
    #[error("ray direction is the zero vector")]
    ZeroDirection,
    /// A control-point grid does not have `stride × rows` entries.
    #[error("patch grid has {len} coefficients, expected {stride}×{rows}")]
    GridShape {
        /// Number of coefficients given.
        len: usize,
        /// Expected row length (powers of `u`).
        stride: usize,
        /// Expected number of rows (powers of `v`).
        rows: usize,
    },
    /// A search interval is empty or not finite.
    #[error("invalid {which} range [{lo}, {hi}]")]
    InvalidRange {
        /// `"u"` or `"v"`.
        which: &'static str,
        /// Lower end.
        lo: f64,
        /// Upper end.
        hi: f64,
    },
    /// A tolerance is not a finite positive number.
    #[error("invalid tolerance {name} = {value}")]
    InvalidTolerance {
        /// The option's name.
        name: &'static str,
        /// The value given.
        value: f64,
    },
    /// A Gröbner computation grew past its work limit (basis size or rounds).
    #[error("{algorithm} exceeded its limit of {limit} {what}")]
    LimitExceeded {
        /// `"stam"` or `"buchberger"`.
        algorithm: &'static str,
        /// What was counted ("basis elements", "rounds", "reductions").
        what: &'static str,
        /// The limit that was hit.
        limit: usize,
    },
    /// An `f64` computation produced a non-finite coefficient (an intermediate result beyond
    /// the range of `f64`, from finite input of very wide range). The solver then uses the
    /// resultant instead.
    #[error("{algorithm}: an intermediate coefficient is not finite")]
    Overflow {
        /// `"r2"`, `"stam"` or `"buchberger"`.
        algorithm: &'static str,
    },
    /// The resultant's matrix is too large for the division-free determinant.
    #[error("resultant matrix of size {size} exceeds the limit {limit}")]
    MatrixTooLarge {
        /// Matrix dimension.
        size: usize,
        /// Largest supported dimension.
        limit: usize,
    },
}

impl Error {
    /// [`Error::NonFinite`] naming `what` when a coefficient is NaN or infinite (`f64` input;
    /// exact values always pass). Every public entry of the crate refuses such input before
    /// any work: a NaN leading term is never cancelled, so reduction would loop or hand NaN
    /// back (issue 10; issue 13, item 16).
    pub(crate) fn check_finite<T: Scalar>(coeffs: &[T], what: &'static str) -> Result<(), Error> {
        if T::EXACT || coeffs.iter().all(|c| c.nearest_f64().is_finite()) {
            Ok(())
        } else {
            Err(Error::NonFinite { what })
        }
    }

    /// [`Error::check_finite`] on every polynomial of `polys`.
    pub(crate) fn check_all_finite<T: Scalar>(
        polys: &[BiPoly<T>],
        what: &'static str,
    ) -> Result<(), Error> {
        polys
            .iter()
            .try_for_each(|p| Error::check_finite(p.coeffs(), what))
    }
}

//! [`RootError`]: why a root query was refused.

use std::fmt;

/// Why a root-finding query could not be answered.
///
/// Root finders never panic on bad input and never return a wrong count: a query whose answer
/// is not a finite set of numbers (the zero polynomial), or whose input is not a set of real
/// numbers (NaN, infinite coefficients, NaN bounds), gets one of these instead; a heuristic
/// method that cannot stand by its answer says so ([`RootError::Unresolved`]).
#[derive(Clone, Copy, Debug, PartialEq)]
#[non_exhaustive]
pub enum RootError {
    /// A coefficient is NaN or infinite; `index` is its power of `x`.
    NonFiniteCoefficient {
        /// The power of `x` whose coefficient is not finite.
        index: usize,
    },
    /// The zero polynomial: every number is a root, so there is no finite answer.
    ZeroPolynomial,
    /// An interval bound is NaN (infinite bounds are accepted where documented).
    NanBound,
    /// A tolerance is NaN, negative or infinite, or a relative tolerance is 1 or more.
    InvalidTolerance,
    /// A heuristic method ([`IsolationMethod::Sturm`](crate::IsolationMethod::Sturm),
    /// [`IsolationMethod::StamSturm`](crate::IsolationMethod::StamSturm)) cannot stand by
    /// its answer on `(lo, hi]`: it counted a root there that no certified sign change
    /// confirms (a wrong floating-point count, or a root of even multiplicity), its count
    /// there is provably wrong or unknown (a sign within its rounding bound, a sequence that
    /// overflowed or underflowed), or a root it found has a certified sign change before it.
    /// The certified methods never return this.
    Unresolved {
        /// Lower end of the interval the counts gave.
        lo: f64,
        /// Upper end.
        hi: f64,
    },
    /// A query with a value slack ([`RootQuery::value_slack`](crate::RootQuery::value_slack))
    /// met a sign in `(lo, hi]` that lies within the slack of zero: the answer depends on
    /// digits the stored coefficients do not hold, so no precision of the isolation can
    /// decide it. The caller must compute the polynomial more accurately (e.g. exactly).
    SlackLimited {
        /// Lower end of the undecided part of the range.
        lo: f64,
        /// Upper end.
        hi: f64,
    },
}

impl fmt::Display for RootError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            RootError::NonFiniteCoefficient { index } => {
                write!(f, "coefficient of x^{index} is not finite")
            }
            RootError::ZeroPolynomial => {
                write!(
                    f,
                    "the zero polynomial vanishes everywhere, so its roots are not isolated"
                )
            }
            RootError::NanBound => write!(f, "an interval bound is NaN"),
            RootError::InvalidTolerance => {
                write!(
                    f,
                    "tolerance must be a finite non-negative number (a relative one below 1)"
                )
            }
            RootError::Unresolved { lo, hi } => write!(
                f,
                "a heuristic method counted a root in ({lo}, {hi}] that no sign change confirms"
            ),
            RootError::SlackLimited { lo, hi } => write!(
                f,
                "a sign in ({lo}, {hi}] lies within the value slack of zero: the coefficients are not accurate enough"
            ),
        }
    }
}

impl std::error::Error for RootError {}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn messages_are_lower_case_without_full_stop() {
        let all = [
            RootError::NonFiniteCoefficient { index: 3 },
            RootError::ZeroPolynomial,
            RootError::NanBound,
            RootError::InvalidTolerance,
            RootError::Unresolved { lo: 1.0, hi: 2.0 },
        ];
        for e in all {
            let s = e.to_string();
            assert!(s.chars().next().is_some_and(char::is_lowercase), "{s}");
            assert!(!s.ends_with('.'), "{s}");
        }
        assert!(
            RootError::NonFiniteCoefficient { index: 3 }
                .to_string()
                .contains("x^3"),
            "names the coefficient"
        );
    }
}

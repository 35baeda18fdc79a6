//! [`RootError`]: why a root query was refused.

use std::fmt;

/// Why a root-finding query could not be answered.
///
/// Root finders never panic on bad input and never return a wrong count: a query whose answer
/// is not a finite set of numbers (the zero polynomial), or whose input is not a set of real
/// numbers (NaN, infinite coefficients, NaN bounds), gets one of these instead.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
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
    /// A tolerance is NaN, negative or infinite.
    InvalidTolerance,
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
                write!(f, "tolerance must be a finite non-negative number")
            }
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

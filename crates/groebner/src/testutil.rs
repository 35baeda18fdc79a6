//! Test helpers: exact polynomials from integer triples and the article's worked examples.

use poly::{BiPoly, QBiPoly, Rat};

// `unused_crate_dependencies` hygiene: proptest is a dev-dependency for `tests/systems.rs`
// only, not for the unit tests.
use proptest as _;

/// The integer `n` as a rational.
pub(crate) fn q(n: i64) -> Rat {
    Rat::from_integer(n.into())
}

/// `Σ c·u^i·v^j` from `(c, i, j)` triples.
pub(crate) fn qb(terms: &[(i64, usize, usize)]) -> QBiPoly {
    BiPoly::from_terms(terms.iter().map(|&(c, i, j)| (q(c), i, j)))
}

/// Article §3: `F1 = uv + uv² − u³`, `F2 = −u² + 1 + u³v`.
pub(crate) fn article_pair() -> (QBiPoly, QBiPoly) {
    (
        qb(&[(1, 1, 1), (1, 1, 2), (-1, 3, 0)]),
        qb(&[(-1, 2, 0), (1, 0, 0), (1, 3, 1)]),
    )
}

/// The reduced Gröbner basis of the article's pair in TLO (lex with `v > u`), largest leading
/// monomial first: `{v + u⁷ + u⁵ − u⁴ − u³ + u + 1, u⁸ − u⁵ − u⁴ + u³ + 2u² − 1}`
/// (independently computed with sympy's `groebner(…, v, u, order='lex')`).
pub(crate) fn article_reduced_basis() -> Vec<QBiPoly> {
    vec![
        qb(&[
            (1, 0, 1),
            (1, 7, 0),
            (1, 5, 0),
            (-1, 4, 0),
            (-1, 3, 0),
            (1, 1, 0),
            (1, 0, 0),
        ]),
        qb(&[
            (1, 8, 0),
            (-1, 5, 0),
            (-1, 4, 0),
            (1, 3, 0),
            (2, 2, 0),
            (-1, 0, 0),
        ]),
    ]
}

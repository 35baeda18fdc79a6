//! Stam's simplified `GB0` for exactly two polynomials (article §4.2, `Groebner()` in
//! `ray3.c`). See `paper-notes/groebner.md` §4.

use poly::{BiPoly, Scalar};

use crate::basis::Basis;
use crate::error::Error;
use crate::reduction::{r2_tracked, s_poly_tracked};

use crate::tracked::Tracked;

/// Upper bound on the rounds of Stam's loop.
///
/// Each round normally lowers the `v`-degree of the newest element (article §4.2) or, once it
/// is univariate, runs one Euclid step on the `u`-eliminant, so a system of `v`-degrees ≤ 3 and
/// `u`-degrees ≤ 3 needs a few rounds, far below this bound. The bound only stops a
/// pathological `f64` case where round-off keeps a leading term alive.
pub const STAM_MAX_ROUNDS: usize = 256;

/// Stam's Gröbner loop for two polynomials (article §4.2):
///
/// ```text
/// R2(F1, F2); i := 1;
/// while F_{i+1} ≠ 0 do
///     F_{i+2} := SP(F_i, F_{i+1});  R2(F_i, F_{i+2});  R2(F_{i+1}, F_{i+2});
///     i := i + 1;
/// end while
/// ```
///
/// with `ray3.c`'s exchanges, so that `LM(F_1) > LM(F_2) > …`. Returns the non-zero
/// `F_1 … F_N`, monic. When the system has finitely many common roots the last element is
/// normally the `u`-eliminant (or the constant 1 when there are none, Theorem 1): query it with
/// [`Basis::univariate_u`] and [`Basis::contains_unit`].
///
/// Every step replaces polynomials by combinations that generate the same ideal, so the result
/// always generates `(F1, F2)`. The article presents the result as a Gröbner basis; it is one
/// on the article's examples and on the random systems of the tests, but only consecutive pairs
/// are ever examined, so [`is_groebner_basis`](crate::is_groebner_basis) is the check when it
/// matters.
///
/// # Exactness
/// Exact over `Rat`. Over `f64` each step applies the crate's relative zero rule (the running
/// magnitude of every coefficient, see the crate docs), replacing Stam's absolute `1e-9`.
///
/// # Complexity
/// A few rounds for bicubic systems; each round is two `R2` reductions and one S-polynomial,
/// O(terms²) coefficient operations. Exact coefficients can grow to hundreds of bits.
///
/// # Errors
/// [`Error::NonFinite`] for a NaN or infinite input coefficient; [`Error::Overflow`] when an
/// `f64` step leaves the range of `f64`; [`Error::LimitExceeded`] after [`STAM_MAX_ROUNDS`]
/// rounds or [`R2_MAX_STEPS`](crate::R2_MAX_STEPS) steps of one `R2`.
///
/// # Examples
/// ```
/// use groebner::stam_basis;
/// use poly::{BiPoly, Rat};
/// let r = |c: i64, i, j| (Rat::from_integer(c.into()), i, j);
/// // Article §3: F1 = uv + uv² − u³, F2 = −u² + 1 + u³v.
/// let f1 = BiPoly::from_terms([r(1, 1, 1), r(1, 1, 2), r(-1, 3, 0)]);
/// let f2 = BiPoly::from_terms([r(-1, 2, 0), r(1, 0, 0), r(1, 3, 1)]);
/// let g = stam_basis(&f1, &f2)?;
/// let e = g.eliminant().ok_or("finitely many roots")?;
/// assert_eq!(e.degree(), 8); // u⁸ − u⁵ − u⁴ + u³ + 2u² − 1
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn stam_basis<T: Scalar>(f1: &BiPoly<T>, f2: &BiPoly<T>) -> Result<Basis<T>, Error> {
    Error::check_finite(f1.coeffs(), "F1")?;
    Error::check_finite(f2.coeffs(), "F2")?;
    let (t1, t2) = (Tracked::new(f1.clone()), Tracked::new(f2.clone()));
    let mut g = stam_tracked(t1, t2)?;
    for t in &mut g {
        t.make_monic();
    }
    Ok(Basis::from_tracked(g))
}

/// The loop on tracked polynomials; returns the non-zero elements.
pub(crate) fn stam_tracked<T: Scalar>(
    f1: Tracked<T>,
    f2: Tracked<T>,
) -> Result<Vec<Tracked<T>>, Error> {
    stam_tracked_until(f1, f2, |_| false).map(|g| g.expect("never aborted"))
}

/// [`stam_tracked`] that gives up (`Ok(None)`) as soon as `abort` holds for a new element:
/// the `f64` solver stops a run whose elements are already dominated by their error bounds.
pub(crate) fn stam_tracked_until<T: Scalar>(
    f1: Tracked<T>,
    f2: Tracked<T>,
    abort: impl Fn(&Tracked<T>) -> bool,
) -> Result<Option<Vec<Tracked<T>>>, Error> {
    let (a, b) = r2_tracked(f1, f2)?;
    let mut g = vec![a, b];
    let mut i = 0;
    // Invariant: g[i+1] is the newest element and LM(g[i]) > LM(g[i+1]) unless g[i+1] = 0.
    while !g[i + 1].is_zero() {
        if i >= STAM_MAX_ROUNDS {
            return Err(Error::LimitExceeded {
                algorithm: "stam",
                what: "rounds",
                limit: STAM_MAX_ROUNDS,
            });
        }
        let mut s = s_poly_tracked(&g[i], &g[i + 1]);
        s.make_monic();
        // R2(F_i, F_{i+2}) then R2(F_{i+1}, F_{i+2}): the larger stays in place, the smaller
        // (lower Deg_v) becomes the new element. The new polynomial goes first, as in
        // `Reduce_2(i+2, i)`: when both leading monomials are equal it is the one reduced, so
        // the older element is kept rather than replaced by a longer equivalent.
        let gi = std::mem::replace(&mut g[i], Tracked::zero());
        s.check_finite("stam")?;
        let (gi, s) = r2_tracked(s, gi)?;
        g[i] = gi;
        let gi1 = std::mem::replace(&mut g[i + 1], Tracked::zero());
        let (gi1, s) = r2_tracked(s, gi1)?;
        g[i + 1] = gi1;
        if abort(&s) {
            return Ok(None);
        }
        g.push(s);
        i += 1;
    }
    g.retain(|t| !t.is_zero());
    Ok(Some(g))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::testutil::{article_pair, article_reduced_basis, qb};
    use crate::{buchberger, is_groebner_basis, reduce_basis};

    #[test]
    fn article_pair_gives_the_eliminant() {
        let (f1, f2) = article_pair();
        let g = stam_basis(&f1, &f2).unwrap();
        let (idx, e) = g.univariate_u().expect("finitely many roots");
        assert_eq!(idx, g.len() - 1, "the eliminant is the last element F_N");
        assert_eq!(
            *e,
            article_reduced_basis()[1],
            "u⁸ − u⁵ − u⁴ + u³ + 2u² − 1"
        );
        assert!(
            is_groebner_basis(g.elements()).unwrap(),
            "Stam's output is a Gröbner basis here: {g:?}"
        );
        assert_eq!(
            reduce_basis(g.elements()).unwrap(),
            article_reduced_basis(),
            "reduced lex basis"
        );
        assert!(!g.contains_unit(), "common roots exist");
        assert!(g.has_finitely_many_roots(), "finitely many (Theorem 2)");
    }

    #[test]
    fn article_r2_pair_is_a_basis_after_r2() {
        // Article §4.2: after R2 the pair {v + u³ + u, u⁴ − 2} is already a Gröbner basis.
        let p = qb(&[(1, 2, 1), (-1, 0, 1), (1, 1, 0)]);
        let q = qb(&[(1, 1, 1), (1, 2, 0), (2, 0, 0)]);
        let g = stam_basis(&p, &q).unwrap();
        assert_eq!(
            g.elements(),
            &[
                qb(&[(1, 0, 1), (1, 3, 0), (1, 1, 0)]),
                qb(&[(1, 4, 0), (-2, 0, 0)])
            ],
            "basis {{v + u³ + u, u⁴ − 2}}"
        );
    }

    #[test]
    fn no_common_root_gives_the_unit() {
        // u·v − 1 and u: no common root (Theorem 1).
        let g = stam_basis(&qb(&[(1, 1, 1), (-1, 0, 0)]), &qb(&[(1, 1, 0)])).unwrap();
        assert!(g.contains_unit(), "1 ∈ G: {g:?}");
        // Two parallel lines v = u and v = u + 1.
        let g = stam_basis(
            &qb(&[(1, 0, 1), (-1, 1, 0)]),
            &qb(&[(1, 0, 1), (-1, 1, 0), (-1, 0, 0)]),
        )
        .unwrap();
        assert!(g.contains_unit(), "parallel lines: {g:?}");
    }

    #[test]
    fn common_factor_has_no_eliminant() {
        // F1 = (v − u)(u + 1), F2 = (v − u)(v + 2): the line v = u is common.
        let l = qb(&[(1, 0, 1), (-1, 1, 0)]);
        let f1 = &l * &qb(&[(1, 1, 0), (1, 0, 0)]);
        let f2 = &l * &qb(&[(1, 0, 1), (2, 0, 0)]);
        let g = stam_basis(&f1, &f2).unwrap();
        assert!(!g.has_finitely_many_roots(), "infinitely many roots: {g:?}");
        assert_eq!(
            reduce_basis(&buchberger(g.elements()).unwrap().into_elements()).unwrap(),
            reduce_basis(&buchberger(&[f1, f2]).unwrap().into_elements()).unwrap(),
            "same ideal as Buchberger's"
        );
    }

    #[test]
    fn f64_matches_exact_on_the_article_pair() {
        let (f1, f2) = article_pair();
        let g = stam_basis(&f1.to_f64(), &f2.to_f64()).unwrap();
        let exact = stam_basis(&f1, &f2).unwrap();
        assert_eq!(g.len(), exact.len(), "same basis size: {g:?}");
        for (a, b) in g.elements().iter().zip(exact.elements()) {
            assert_eq!(a.leading_monomial(), b.leading_monomial(), "same LMs");
            assert_eq!(
                a.term_count(),
                b.term_count(),
                "no noise terms survive in {a}"
            );
            let diff = (a - &b.to_f64()).max_abs_coeff();
            assert!(diff < 1e-13, "f64 element {a} vs exact {b}: {diff:e}");
        }
    }
}

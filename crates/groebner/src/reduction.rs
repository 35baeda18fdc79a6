//! The reduction relation `→F`, normal forms, S-polynomials and Stam's mutual reduction `R2`
//! (article §3 defs. 4–6 and §4.2; `Reduce`, `S_Polynomial` and `Reduce_2` in `ray3.c`).
//! All in Stam's total-lexicographic order ([`Monomial`]). See `paper-notes/groebner.md` §2–3.
//!
//! Over [`Rat`](poly::Rat) everything is exact. Over `f64` the zero rule of the crate docs
//! (coefficients negligible relative to the running size of what formed them) is applied after
//! every step; the functions here treat their arguments as exact input data.

use poly::{BiPoly, Scalar};

use crate::error::Error;
use crate::tracked::Tracked;

/// One step of the reduction relation `p →F q` (article §3 def. 4): the highest term of `p`
/// that is a multiple `λ·LM(F_i)·m` of a leading monomial is removed by `p − λ·m·F_i`
/// (`F_i` taken in order of the slice when several qualify). `None` when `p` is irreducible
/// (it is its own normal form).
///
/// # Exactness
/// Exact over `Rat`. Over `f64` the cancelled term is set to exactly zero and other
/// coefficients follow the crate's relative zero rule.
///
/// # Errors
/// [`Error::NonFinite`] for a NaN or infinite coefficient of `p` or `basis`.
///
/// # Examples
/// ```
/// use groebner::reduction_step;
/// use poly::{BiPoly, Rat};
/// let r = |c: i64, i, j| (Rat::from_integer(c.into()), i, j);
/// // Article §3: F1 = uv + uv² − u³, F2 = −u² + 1 + u³v, p = u²v² + uv + 1.
/// let f1 = BiPoly::from_terms([r(1, 1, 1), r(1, 1, 2), r(-1, 3, 0)]);
/// let f2 = BiPoly::from_terms([r(-1, 2, 0), r(1, 0, 0), r(1, 3, 1)]);
/// let p = BiPoly::from_terms([r(1, 2, 2), r(1, 1, 1), r(1, 0, 0)]);
/// let q = reduction_step(&p, &[f1.clone(), f2.clone()])?.ok_or("reducible")?;
/// // q = p − u·F1 = −u²v + uv + u⁴ + 1, and q is irreducible.
/// assert_eq!(q, BiPoly::from_terms([r(-1, 2, 1), r(1, 1, 1), r(1, 4, 0), r(1, 0, 0)]));
/// assert!(reduction_step(&q, &[f1, f2])?.is_none());
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn reduction_step<T: Scalar>(
    p: &BiPoly<T>,
    basis: &[BiPoly<T>],
) -> Result<Option<BiPoly<T>>, Error> {
    Error::check_finite(p.coeffs(), "p")?;
    Error::check_all_finite(basis, "basis")?;
    let basis = track_all(basis);
    let mut p = Tracked::new(p.clone());
    Ok(p.reduce_step(&basis, None).map(|_| p.poly))
}

/// The normal form `NF(p, F)` (article §3 def. 5): `p` reduced by `→F` until no term is a
/// multiple of any `LM(F_i)`. Zero polynomials in `basis` are ignored.
///
/// The result depends on the order of `basis` unless `basis` is a Gröbner basis, in which case
/// it is the unique remainder and `NF(p, G) = 0 ⇔ p ∈ (G)` (def. 7).
///
/// # Exactness
/// Exact over `Rat`; over `f64` see [`reduction_step`].
///
/// # Errors
/// [`Error::NonFinite`] for a NaN or infinite coefficient of `p` or `basis` (it would be
/// returned as NaN).
///
/// # Complexity
/// One top-down sweep: each term of `p` and of the subtracted multiples is visited once, each
/// visit tries every basis element (O(|F|) divisibility tests).
pub fn normal_form<T: Scalar>(p: &BiPoly<T>, basis: &[BiPoly<T>]) -> Result<BiPoly<T>, Error> {
    Error::check_finite(p.coeffs(), "p")?;
    Error::check_all_finite(basis, "basis")?;
    let basis = track_all(basis);
    let mut p = Tracked::new(p.clone());
    p.reduce_fully(&basis);
    Ok(p.poly)
}

/// The S-polynomial `SP(f, g)` (article §3 def. 6) of the monic versions of `f` and `g`:
/// with `L = lcm(LM(f), LM(g))`,
/// `SP(f, g) = (L / LM(f))·f / lc(f) − (L / LM(g))·g / lc(g)`,
/// so the two copies of `L` cancel. Zero if `f` or `g` is zero. (The article takes leading
/// coefficients to be one, def. 1; dividing by them here gives the same polynomial.)
///
/// # Exactness
/// Exact over `Rat`; over `f64` the `L` term is exactly zero and the relative zero rule applies.
///
/// # Errors
/// [`Error::NonFinite`] for a NaN or infinite coefficient of `f` or `g`.
///
/// # Examples
/// ```
/// use groebner::s_polynomial;
/// use poly::BiPoly;
/// // Article §3: SP(F1, F2) = u²F1 − vF2 = u³v + u²v − v − u⁵.
/// let f1 = BiPoly::from_terms([(1.0, 1, 1), (1.0, 1, 2), (-1.0, 3, 0)]);
/// let f2 = BiPoly::from_terms([(-1.0, 2, 0), (1.0, 0, 0), (1.0, 3, 1)]);
/// let sp = s_polynomial(&f1, &f2)?;
/// assert_eq!(sp, BiPoly::from_terms([(1.0, 3, 1), (1.0, 2, 1), (-1.0, 0, 1), (-1.0, 5, 0)]));
/// # Ok::<(), groebner::Error>(())
/// ```
pub fn s_polynomial<T: Scalar>(f: &BiPoly<T>, g: &BiPoly<T>) -> Result<BiPoly<T>, Error> {
    Error::check_finite(f.coeffs(), "f")?;
    Error::check_finite(g.coeffs(), "g")?;
    Ok(Tracked::s_poly(&Tracked::new(f.clone()), &Tracked::new(g.clone())).poly)
}

/// Stam's mutual reduction `R2(p, q)` (article §4.2, `Reduce_2` in `ray3.c`):
///
/// ```text
/// while LM(p) = λ·LM(q) do
///     p := p − λ·q;
///     if LM(p) < LM(q) then exchange p and q;
/// end while
/// ```
///
/// (`λ` a term), starting with `LM(p) ≥ LM(q)` (the arguments are exchanged first if
/// needed; when the leading monomials are equal, `p` is the one reduced). Both polynomials are kept monic, as Stam's
/// `Scale` does. Returns `(p, q)` with `LM(q) < LM(p)` and `Deg_v(q) < Deg_v(p)`, or with
/// `q = 0` when one of them reduced to zero (then `p` is the survivor, possibly zero too).
/// The pair generates the same ideal as the input.
///
/// `Deg_v(q) < Deg_v(p)` at the end because, were the `v`-degrees equal, `LM(p) ≥ LM(q)`
/// would give `Deg_u(p) ≥ Deg_u(q)`, so `LM(q)` would divide `LM(p)` and the loop would go on.
/// For univariate inputs this is Euclid's algorithm (article §4.2).
///
/// # Exactness
/// Exact over `Rat` (monic results). Over `f64` the relative zero rule applies at every step.
///
/// # Errors
/// [`Error::NonFinite`] for a NaN or infinite input coefficient; [`Error::Overflow`] when an
/// `f64` step leaves the range of `f64` (inputs of very wide range); [`Error::LimitExceeded`]
/// after [`R2_MAX_STEPS`] steps.
///
/// # Examples
/// ```
/// use groebner::r2;
/// use poly::BiPoly;
/// // Article §4.2: p = u²v − v + u, q = uv + u² + 2 end as −v − u³ − u and −u⁴ + 2.
/// let p = BiPoly::from_terms([(1.0, 2, 1), (-1.0, 0, 1), (1.0, 1, 0)]);
/// let q = BiPoly::from_terms([(1.0, 1, 1), (1.0, 2, 0), (2.0, 0, 0)]);
/// let (p, q) = r2(&p, &q)?;
/// assert_eq!(p, BiPoly::from_terms([(1.0, 0, 1), (1.0, 3, 0), (1.0, 1, 0)])); // monic
/// assert_eq!(q, BiPoly::from_terms([(1.0, 4, 0), (-2.0, 0, 0)]));
/// # Ok::<(), groebner::Error>(())
/// ```
pub fn r2<T: Scalar>(p: &BiPoly<T>, q: &BiPoly<T>) -> Result<(BiPoly<T>, BiPoly<T>), Error> {
    Error::check_finite(p.coeffs(), "p")?;
    Error::check_finite(q.coeffs(), "q")?;
    let (p, q) = (Tracked::new(p.clone()), Tracked::new(q.clone()));
    let (mut p, mut q) = r2_tracked(p, q)?;
    p.make_monic();
    q.make_monic();
    Ok((p.poly, q.poly))
}

/// Most reduction steps one [`r2`] may take before [`Error::LimitExceeded`]. Each step lowers
/// one of the two leading monomials, so the loop ends in exact arithmetic; for a ray/bicubic
/// system (`Deg_v ≤ 3`, eliminant degree ≤ 18) it is Euclid's algorithm on a few remainders,
/// a few hundred steps at most. The bound stops an `f64` run whose round-off residues keep
/// long remainder sequences alive, at a cost far below a second.
pub const R2_MAX_STEPS: usize = 1 << 16;

pub(crate) fn track_all<T: Scalar>(basis: &[BiPoly<T>]) -> Vec<Tracked<T>> {
    basis
        .iter()
        .filter(|g| !g.is_zero())
        .map(|g| Tracked::new(g.clone()))
        .collect()
}

/// `SP(f, g)` on tracked polynomials (see [`s_polynomial`]).
pub(crate) fn s_poly_tracked<T: Scalar>(f: &Tracked<T>, g: &Tracked<T>) -> Tracked<T> {
    Tracked::s_poly(f, g)
}

/// `R2` on tracked polynomials (see [`r2`]), results monic.
pub(crate) fn r2_tracked<T: Scalar>(
    mut p: Tracked<T>,
    mut q: Tracked<T>,
) -> Result<(Tracked<T>, Tracked<T>), Error> {
    p.make_monic();
    q.make_monic();
    p.check_finite("r2")?;
    q.check_finite("r2")?;
    if p.lm() < q.lm() {
        std::mem::swap(&mut p, &mut q);
    }
    // Invariant: LM(p) ≥ LM(q) (None, the zero polynomial, is below everything).
    for _ in 0..R2_MAX_STEPS {
        let (Some(lp), Some(lq)) = (p.lm(), q.lm()) else {
            return Ok((p, q));
        };
        if !lq.divides(lp) {
            return Ok((p, q));
        }
        // p := p − λ·q with λ = (lc(p)/lc(q))·LM(p)/LM(q).
        p.cancel_with(lp, &q);
        if p.is_zero() {
            return Ok((q, p));
        }
        p.make_monic();
        p.check_finite("r2")?;
        if p.lm() < q.lm() {
            std::mem::swap(&mut p, &mut q);
        }
    }
    Err(Error::LimitExceeded {
        algorithm: "r2",
        what: "steps",
        limit: R2_MAX_STEPS,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::testutil::{article_pair, q, qb};
    use poly::Monomial;

    #[test]
    fn article_normal_form_example() {
        // Article §3: p = u²v² + uv + 1 reduces by F1 to q = −u²v + uv + u⁴ + 1, which is
        // already irreducible: LM(F1) = uv² and LM(F2) = u³v divide none of its terms. The
        // article's second step "q + u·F2 = uv + u⁴ − u³ + u + 1" is an erratum (u³v ∤ u²v, and
        // the printed value is not even ≡ p modulo (F1, F2); see below).
        let (f1, f2) = article_pair();
        let p = qb(&[(1, 2, 2), (1, 1, 1), (1, 0, 0)]);
        let nf = normal_form(&p, &[f1.clone(), f2.clone()]).unwrap();
        assert_eq!(
            nf,
            qb(&[(-1, 2, 1), (1, 1, 1), (1, 4, 0), (1, 0, 0)]),
            "NF(p, F)"
        );
        let printed = qb(&[(1, 1, 1), (1, 4, 0), (-1, 3, 0), (1, 1, 0), (1, 0, 0)]);
        // Modulo the reduced Gröbner basis (article's basis, checked in buchberger.rs), p and
        // the printed value have different normal forms, so they differ modulo the ideal.
        let g = [
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
        ];
        assert_ne!(
            normal_form(&p, &g).unwrap(),
            normal_form(&printed, &g).unwrap(),
            "erratum: not congruent"
        );
        // And NF(p, F) ≡ p, as a normal form must be.
        assert_eq!(
            normal_form(&p, &g).unwrap(),
            normal_form(&nf, &g).unwrap(),
            "NF(p, F) ≡ p mod (F1, F2)"
        );
        // NF(p, G) computed by hand with sympy's reduced(): u⁷ − u⁶ + 2u².
        assert_eq!(
            normal_form(&p, &g).unwrap(),
            qb(&[(1, 7, 0), (-1, 6, 0), (2, 2, 0)]),
            "NF(p, G)"
        );
    }

    #[test]
    fn reduction_removes_every_reducible_term() {
        let (f1, f2) = article_pair();
        // A polynomial with many reducible terms: NF must leave none, and p − NF ∈ (F1, F2)
        // is checked by reducing to the same normal form modulo the Gröbner basis above.
        let p = qb(&[(3, 4, 3), (-2, 5, 2), (1, 3, 1), (7, 1, 2), (1, 0, 0)]);
        let nf = normal_form(&p, &[f1.clone(), f2.clone()]).unwrap();
        let lms = [
            f1.leading_monomial().unwrap(),
            f2.leading_monomial().unwrap(),
        ];
        for (m, _) in nf.terms() {
            assert!(
                !lms.iter().any(|l| l.divides(m)),
                "term {m:?} of {nf} is reducible"
            );
        }
        // Repeated single steps reach the same normal form.
        let mut r = p.clone();
        let mut steps = 0;
        while let Some(next) = reduction_step(&r, &[f1.clone(), f2.clone()]).unwrap() {
            r = next;
            steps += 1;
        }
        assert_eq!(r, nf, "steps of →F end at NF");
        assert!(steps >= 3, "several steps were needed ({steps})");
    }

    #[test]
    fn article_s_polynomial() {
        let (f1, f2) = article_pair();
        let sp = s_polynomial(&f1, &f2).unwrap();
        assert_eq!(
            sp,
            qb(&[(1, 3, 1), (1, 2, 1), (-1, 0, 1), (-1, 5, 0)]),
            "SP(F1, F2)"
        );
        // Non-monic inputs give the S-polynomial of their monic versions.
        let sp3 = s_polynomial(&f1.scale(&q(3)), &f2.scale(&q(-5))).unwrap();
        assert_eq!(sp3, sp, "scaling the inputs does not change SP");
        assert!(
            s_polynomial(&f1, &BiPoly::zero()).unwrap().is_zero(),
            "SP with zero"
        );
    }

    #[test]
    fn article_r2_example() {
        // Article §4.2: ends as p = −v − u³ − u, q = −u⁴ + 2 (here monic).
        let p = qb(&[(1, 2, 1), (-1, 0, 1), (1, 1, 0)]);
        let qq = qb(&[(1, 1, 1), (1, 2, 0), (2, 0, 0)]);
        let (a, b) = r2(&p, &qq).unwrap();
        assert_eq!(
            a,
            qb(&[(-1, 0, 1), (-1, 3, 0), (-1, 1, 0)]).make_monic(),
            "p = −v − u³ − u"
        );
        assert_eq!(b, qb(&[(-1, 4, 0), (2, 0, 0)]).make_monic(), "q = −u⁴ + 2");
        assert!(a.deg_v() > b.deg_v(), "Deg_v(q) < Deg_v(p)");
        // Symmetric in its arguments.
        assert_eq!(r2(&qq, &p).unwrap(), (a, b), "R2(q, p) = R2(p, q)");
    }

    #[test]
    fn r2_is_euclid_on_univariate_input() {
        // gcd((u−1)(u−2)(u+3), (u−1)(u+3)(u+4)) = (u−1)(u+3) = u² + 2u − 3.
        let a = qb(&[(6, 0, 0), (-7, 1, 0), (0, 2, 0), (1, 3, 0)]);
        let b = qb(&[(-12, 0, 0), (5, 1, 0), (6, 2, 0), (1, 3, 0)]);
        let (g, z) = r2(&a, &b).unwrap();
        assert!(z.is_zero(), "the second polynomial reduces to zero: {z}");
        assert_eq!(g, qb(&[(-3, 0, 0), (2, 1, 0), (1, 2, 0)]), "monic gcd");
    }

    #[test]
    fn f64_reduction_cancels_relative_to_the_operands() {
        // Scaled by 1e12, the article's example must behave exactly as over Rat: a fixed
        // absolute threshold such as Stam's 1e-9 would keep or drop the wrong terms.
        // q' = 0.3·s·(q + 0.37·p) generates the same ideal with p; the inexact combination
        // leaves rounding residues where terms cancel.
        for s in [1e-12, 1.0, 1e12] {
            let p = BiPoly::from_terms([(s, 2, 1), (-s, 0, 1), (s, 1, 0)]);
            let qq = BiPoly::from_terms([(1.0, 1, 1), (1.0, 2, 0), (2.0, 0, 0)]);
            let qq = (&qq + &p.scale(&(0.37 / s))).scale(&(0.3 * s));
            let (a, b) = r2(&p, &qq).unwrap();
            assert_eq!(
                a.leading_monomial(),
                Some(Monomial::new(0, 1)),
                "scale {s}: {a}"
            );
            assert_eq!(
                b.leading_monomial(),
                Some(Monomial::new(4, 0)),
                "scale {s}: {b}"
            );
            assert_eq!(
                b.term_count(),
                2,
                "u⁴ − 2 has no noise terms at scale {s}: {b}"
            );
            assert!(
                (b.coeff(0, 0) + 2.0).abs() < 1e-14,
                "constant −2 at scale {s}: {b}"
            );
            assert_eq!(
                a.term_count(),
                3,
                "v + u³ + u has no noise terms at scale {s}: {a}"
            );
        }
    }
}

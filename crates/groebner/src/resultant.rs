//! Kajiya-style elimination: the resultant `Res_v(F1, F2)`, a polynomial in `u` alone whose
//! roots include the `u`-coordinates of every common root (J. Kajiya, "Ray tracing parametric
//! patches", SIGGRAPH 1982, the article's ref. [6]). See `paper-notes/resultant.md`.
//!
//! Both matrices (Sylvester and Bézout) have entries in `K[u]`; their determinant is computed
//! without division, so the same code is exact over `Rat` and plain arithmetic over `f64`.

use poly::{BiPoly, Poly, Scalar};

use crate::bezout_bicubic::bezout_bicubic_resultant;
use crate::error::Error;

/// Largest matrix [`poly_matrix_det`] accepts. The division-free expansion costs
/// O(n·2ⁿ) polynomial products (see its `# Complexity`); 16 allows `v`-degrees up to 8 in each
/// equation with Sylvester's matrix, far above the bicubic case (6).
pub const MAX_MATRIX_SIZE: usize = 16;

/// The Sylvester matrix of `f` and `g` as polynomials in `v` with coefficients in `K[u]`:
/// with `m = deg_v f`, `n = deg_v g`, the first `n` rows hold `f`'s coefficients from `v^m`
/// down to `v^0`, each row shifted one column right of the previous, then `m` rows of `g`'s.
/// Its determinant is `Res_v(f, g)`.
///
/// # Errors
/// [`Error::NonFinite`] for a NaN or infinite coefficient.
pub fn sylvester_matrix_v<T: Scalar>(
    f: &BiPoly<T>,
    g: &BiPoly<T>,
) -> Result<Vec<Vec<Poly<T>>>, Error> {
    Error::check_finite(f.coeffs(), "f")?;
    Error::check_finite(g.coeffs(), "g")?;
    let (a, b) = (f.coeffs_in_v(), g.coeffs_in_v());
    let (m, n) = (f.deg_v(), g.deg_v());
    let size = m + n;
    let mut rows = Vec::with_capacity(size);
    for (count, coeffs, deg) in [(n, &a, m), (m, &b, n)] {
        for r in 0..count {
            let mut row = vec![Poly::zero(); size];
            for k in 0..=deg {
                row[r + k] = coeffs[deg - k].clone();
            }
            rows.push(row);
        }
    }
    Ok(rows)
}

/// The resultant `Res_v(f, g)` by Sylvester's matrix: a polynomial in `u` that vanishes at `u0`
/// iff `f(u0, v)` and `g(u0, v)` have a common root `v` (possibly complex), or both leading
/// coefficients in `v` vanish at `u0` (a common root "at `v = ∞`"). For two bicubic equations
/// its degree is at most 18 (Kajiya's Bézout bound: 6 rows of degree 3 in `u`).
///
/// Conventions: `Res = 0` if `f` or `g` is zero; if `f` does not involve `v`, `Res = f^{deg_v g}`
/// (and symmetrically), so `Res = 1` when neither involves `v`.
///
/// # Exactness
/// Exact over `Rat` (division-free determinant). Over `f64` it is a sum of products of the
/// coefficients, with the usual round-off of such sums; no threshold is applied.
///
/// # Errors
/// [`Error::NonFinite`] for a NaN or infinite coefficient; [`Error::MatrixTooLarge`] when
/// `deg_v f + deg_v g >` [`MAX_MATRIX_SIZE`].
///
/// # Examples
/// ```
/// use groebner::sylvester_resultant_v;
/// use poly::{BiPoly, Poly, Rat};
/// let r = |c: i64, i, j| (Rat::from_integer(c.into()), i, j);
/// let n = |c: i64| Rat::from_integer(c.into());
/// // Article §3 pair: Res_v = −u·(u⁸ − u⁵ − u⁴ + u³ + 2u² − 1).
/// let f1 = BiPoly::from_terms([r(1, 1, 1), r(1, 1, 2), r(-1, 3, 0)]);
/// let f2 = BiPoly::from_terms([r(-1, 2, 0), r(1, 0, 0), r(1, 3, 1)]);
/// let res = sylvester_resultant_v(&f1, &f2)?;
/// let e = Poly::new(vec![n(-1), n(0), n(2), n(1), n(-1), n(-1), n(0), n(0), n(1)]);
/// assert_eq!(res, &e * &Poly::new(vec![n(0), n(-1)]));
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn sylvester_resultant_v<T: Scalar>(f: &BiPoly<T>, g: &BiPoly<T>) -> Result<Poly<T>, Error> {
    Error::check_finite(f.coeffs(), "f")?;
    Error::check_finite(g.coeffs(), "g")?;
    if f.is_zero() || g.is_zero() {
        return Ok(Poly::zero());
    }
    poly_matrix_det(&sylvester_matrix_v(f, g)?)
}

/// The Bézout (Cayley) matrix of `f` and `g` in `v`: with `N = max(deg_v f, deg_v g)` and
/// `f = Σ a_k v^k`, `g = Σ b_k v^k`,
/// `(f(v)g(w) − f(w)g(v)) / (v − w) = Σ_{i,j<N} B_ij v^i w^j`, so
/// `B_ij = Σ_{q ≤ min(i,j), p = i+j+1−q ≤ N} (a_p b_q − a_q b_p)`.
/// It is `N × N` (half of Sylvester's size) with entries of twice the `u`-degree.
///
/// # Errors
/// [`Error::NonFinite`] for a NaN or infinite coefficient.
pub fn bezout_matrix_v<T: Scalar>(
    f: &BiPoly<T>,
    g: &BiPoly<T>,
) -> Result<Vec<Vec<Poly<T>>>, Error> {
    Error::check_finite(f.coeffs(), "f")?;
    Error::check_finite(g.coeffs(), "g")?;
    let (a, b) = (f.coeffs_in_v(), g.coeffs_in_v());
    let n = f.deg_v().max(g.deg_v());
    let at = |v: &[Poly<T>], k: usize| v.get(k).cloned().unwrap_or_else(Poly::zero);
    let mut m = vec![vec![Poly::zero(); n]; n];
    for (i, row) in m.iter_mut().enumerate() {
        for (j, entry) in row.iter_mut().enumerate() {
            let mut s = Poly::zero();
            for q in 0..=i.min(j) {
                let p = i + j + 1 - q;
                if p > n {
                    continue;
                }
                s = s + &at(&a, p) * &at(&b, q) - &at(&a, q) * &at(&b, p);
            }
            *entry = s;
        }
    }
    Ok(m)
}

/// The resultant by Bézout's matrix, `(−1)^{N(N−1)/2} · det B` with `N = max(deg_v)`.
///
/// When `deg_v f = deg_v g` (the bicubic case) this equals [`sylvester_resultant_v`] exactly.
/// When the degrees differ, it is `±lc_v^{|m−n|}` times it, `lc_v` the leading coefficient (in
/// `v`) of the higher-degree polynomial: an extra factor whose roots are not intersections and
/// that the solver's verification step rejects like the other extraneous factors.
///
/// # Exactness
/// As [`sylvester_resultant_v`].
///
/// # Errors
/// [`Error::NonFinite`] for a NaN or infinite coefficient; [`Error::MatrixTooLarge`] when
/// `N >` [`MAX_MATRIX_SIZE`].
pub fn bezout_resultant_v<T: Scalar>(f: &BiPoly<T>, g: &BiPoly<T>) -> Result<Poly<T>, Error> {
    Error::check_finite(f.coeffs(), "f")?;
    Error::check_finite(g.coeffs(), "g")?;
    if f.is_zero() || g.is_zero() {
        return Ok(Poly::zero());
    }
    let n = f.deg_v().max(g.deg_v());
    if n == 0 {
        return Ok(Poly::constant(T::one()));
    }
    // The ray/bicubic case, per ray: the same determinant in fixed-size arrays.
    if let Some(r) = bezout_bicubic_resultant(f, g) {
        return Ok(r);
    }
    let det = poly_matrix_det(&bezout_matrix_v(f, g)?)?;
    Ok(if (n * (n - 1) / 2) % 2 == 1 {
        -det
    } else {
        det
    })
}

/// The determinant of a square matrix of polynomials, without division: Laplace expansion
/// along the rows with every minor computed once (minors of the last `k` rows indexed by their
/// column set). The empty matrix has determinant 1.
///
/// # Exactness
/// Only ring operations: exact over `Rat`.
///
/// # Complexity
/// `Σ_k C(n, k)·k ≤ n·2ⁿ⁻¹` polynomial products (192 for `n = 6`), zero entries skipped;
/// memory `2ⁿ` polynomials.
///
/// # Errors
/// [`Error::MatrixTooLarge`] when `n >` [`MAX_MATRIX_SIZE`]; [`Error::NonFinite`] for a NaN
/// or infinite coefficient.
///
/// # Panics
/// If the matrix is not square (a caller bug).
pub fn poly_matrix_det<T: Scalar>(m: &[Vec<Poly<T>>]) -> Result<Poly<T>, Error> {
    m.iter()
        .flatten()
        .try_for_each(|p| Error::check_finite(p.coeffs(), "matrix"))?;
    let n = m.len();
    if n > MAX_MATRIX_SIZE {
        return Err(Error::MatrixTooLarge {
            size: n,
            limit: MAX_MATRIX_SIZE,
        });
    }
    assert!(
        m.iter().all(|r| r.len() == n),
        "poly_matrix_det needs a square matrix"
    );
    if n == 0 {
        return Ok(Poly::constant(T::one()));
    }
    // minors[mask] = det(rows n−k.., columns in mask) for |mask| = k, filled level by level.
    let mut minors: Vec<Poly<T>> = vec![Poly::zero(); 1 << n];
    minors[0] = Poly::constant(T::one());
    for k in 1..=n {
        let r = n - k;
        for mask in 1usize..(1 << n) {
            if mask.count_ones() as usize != k {
                continue;
            }
            let mut acc = Poly::zero();
            let mut position = 0; // index of column c within the mask
            for (c, entry) in m[r].iter().enumerate() {
                if mask & (1 << c) == 0 {
                    continue;
                }
                let sub = &minors[mask ^ (1 << c)];
                if !entry.is_zero() && !sub.is_zero() {
                    let term = entry * sub;
                    acc = if position % 2 == 0 {
                        acc + term
                    } else {
                        acc - term
                    };
                }
                position += 1;
            }
            minors[mask] = acc;
        }
    }
    Ok(minors.swap_remove((1 << n) - 1))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::testutil::{article_pair, article_reduced_basis, q, qb};
    use num_traits::{One, Zero};
    use poly::Rat;

    /// Determinant of a rational matrix by Gaussian elimination (the naive oracle).
    fn det_gauss(mut a: Vec<Vec<Rat>>) -> Rat {
        let n = a.len();
        let mut det = Rat::one();
        for col in 0..n {
            let Some(p) = (col..n).find(|&r| !a[r][col].is_zero()) else {
                return Rat::zero();
            };
            if p != col {
                a.swap(p, col);
                det = -det;
            }
            det *= a[col][col].clone();
            let (top, rest) = a.split_at_mut(col + 1);
            let pivot = &top[col];
            for row in rest {
                let f = row[col].clone() / pivot[col].clone();
                for (x, p) in row.iter_mut().zip(pivot).skip(col) {
                    *x -= p.clone() * &f;
                }
            }
        }
        det
    }

    #[test]
    fn article_resultant_has_the_extra_factor_u() {
        let (f1, f2) = article_pair();
        let res = sylvester_resultant_v(&f1, &f2).unwrap();
        let e = article_reduced_basis()[1].to_poly_u().unwrap();
        assert_eq!(res, &e * &Poly::new(vec![q(0), q(-1)]), "Res = −u·(u⁸ − …)");
        // Why u: both leading coefficients in v (u for v², u³ for v) vanish at u = 0, and
        // F1(0, v) ≡ 0 while F2(0, v) = 1: no common v, a root "at infinity".
        assert!(f1.subst_u(&q(0)).is_zero(), "F1(0, v) ≡ 0");
        assert_eq!(f2.subst_u(&q(0)), Poly::constant(q(1)), "F2(0, v) = 1");
        // Bézout: N = 2 ≠ 1, so an extra factor lc_v(F1) = u appears (up to sign).
        let bez = bezout_resultant_v(&f1, &f2).unwrap();
        let u = Poly::new(vec![q(0), q(1)]);
        assert!(
            bez == &res * &u || bez == -(&res * &u),
            "Bézout = ±u·Res: {bez:?}"
        );
    }

    #[test]
    fn resultant_matches_scalar_determinants() {
        // Evaluating the polynomial resultant at u0 equals the determinant of the Sylvester
        // matrix of F1(u0, v), F2(u0, v) computed by Gaussian elimination — when the v-degrees
        // do not drop at u0.
        let f = qb(&[
            (2, 0, 0),
            (-1, 1, 1),
            (3, 2, 2),
            (1, 0, 3),
            (-2, 3, 1),
            (1, 1, 3),
        ]);
        let g = qb(&[(1, 1, 0), (5, 0, 1), (-1, 2, 2), (4, 3, 3), (1, 0, 0)]);
        let res = sylvester_resultant_v(&f, &g).unwrap();
        assert_eq!(res.degree(), 18 - 2, "degree of this pair: {res:?}");
        for u0 in [-3, 2, 5, 7] {
            let u0 = q(u0);
            let (a, b) = (f.subst_u(&u0), g.subst_u(&u0));
            assert_eq!((a.degree(), b.degree()), (3, 3), "no degree drop at {u0}");
            let fs = BiPoly::from_poly_v(&a);
            let gs = BiPoly::from_poly_v(&b);
            let scalar: Vec<Vec<Rat>> = sylvester_matrix_v(&fs, &gs)
                .unwrap()
                .into_iter()
                .map(|row| row.into_iter().map(|p| p.coeff(0)).collect())
                .collect();
            assert_eq!(res.eval(&u0), det_gauss(scalar), "Res(u0) at u0 = {u0}");
        }
        // Equal v-degrees: Bézout equals Sylvester exactly.
        assert_eq!(
            bezout_resultant_v(&f, &g).unwrap(),
            res,
            "Bézout = Sylvester"
        );
        // Res(f, g) = (−1)^{mn} Res(g, f) with m = n = 3.
        assert_eq!(sylvester_resultant_v(&g, &f).unwrap(), -res, "antisymmetry");
    }

    #[test]
    fn degenerate_resultants() {
        let f = qb(&[(1, 2, 0), (-4, 0, 0)]); // u² − 4, no v
        let g = qb(&[(1, 0, 2), (1, 1, 0)]); // v² + u
        let r = sylvester_resultant_v(&f, &g).unwrap();
        assert_eq!(
            r,
            f.to_poly_u().map(|p| &p * &p).unwrap(),
            "Res = f^{{deg_v g}}"
        );
        assert!(
            sylvester_resultant_v(&f, &BiPoly::zero())
                .unwrap()
                .is_zero(),
            "with zero"
        );
        assert_eq!(
            sylvester_resultant_v(&f, &f).unwrap(),
            Poly::constant(q(1)),
            "neither involves v: empty determinant"
        );
        let big = qb(&[(1, 0, 9)]);
        assert!(
            matches!(
                sylvester_resultant_v(&big, &big),
                Err(Error::MatrixTooLarge { size: 18, .. })
            ),
            "18 × 18 refused"
        );
    }

    #[test]
    fn f64_resultant_is_close_to_exact() {
        let f = qb(&[
            (2, 0, 0),
            (-1, 1, 1),
            (3, 2, 2),
            (1, 0, 3),
            (-2, 3, 1),
            (1, 1, 3),
        ]);
        let g = qb(&[(1, 1, 0), (5, 0, 1), (-1, 2, 2), (4, 3, 3), (1, 0, 0)]);
        let exact = sylvester_resultant_v(&f, &g).unwrap();
        let approx = sylvester_resultant_v(&f.to_f64(), &g.to_f64()).unwrap();
        let scale = exact.to_f64().max_abs_coeff();
        for (k, c) in approx.coeffs().iter().enumerate() {
            let e = poly::rat_to_f64(&exact.coeff(k));
            assert!(
                (c - e).abs() <= 1e-13 * scale,
                "coefficient {k}: {c} vs {e}"
            );
        }
    }
}

//! [`Basis`]: the output of the Gröbner algorithms, and the article's Theorems 1–3 as queries.

use poly::{BiPoly, Monomial, Poly, Scalar};

use crate::tracked::Tracked;

/// A list of non-zero, monic polynomials generating the ideal `(F1, F2, …)`, as produced by
/// [`stam_basis`](crate::stam_basis) or [`buchberger`](crate::buchberger).
///
/// The theorem queries assume the list is a Gröbner basis for Stam's order (TLO, article §3).
/// [`buchberger`](crate::buchberger) guarantees it; Stam's simplified loop is not proven to
/// (its output is checked against Buchberger's in the tests, and the solver completes it with
/// Buchberger when a query would otherwise be answered wrongly). The queries are about common
/// roots over the complex numbers: a ray can miss a patch whose equations have complex common
/// roots only.
///
/// # `f64` bases and their certificate
/// Over `f64` the algorithms decide which remainders vanish by a rounding-error bound, and
/// can return `{1}` for an ideal with common roots (or miss a unit) when the data are
/// ill-conditioned. A basis they return therefore carries, per element, a bound on its
/// distance to the ideal of the inputs (the `tracked` module); only
/// [`proves_no_root_in`](Basis::proves_no_root_in) turns a unit into a proof. The structural
/// queries ([`contains_unit`](Basis::contains_unit) and the others) are exact statements
/// about an exact basis and describe the computed polynomials only in `f64`.
#[derive(Clone, Debug)]
pub struct Basis<T> {
    elements: Vec<BiPoly<T>>,
    /// The elements with their ideal-distance bounds (zero for data given to [`Basis::new`]).
    tracked: Vec<Tracked<T>>,
}

impl<T: PartialEq> PartialEq for Basis<T> {
    /// Equal elements (the bounds are bookkeeping, not part of the basis).
    fn eq(&self, other: &Self) -> bool {
        self.elements == other.elements
    }
}

impl<T: Scalar> Basis<T> {
    /// Wraps the given polynomials (zero polynomials are dropped, the rest kept in order),
    /// taken as exact data: their error bounds are zero.
    pub fn new(elements: Vec<BiPoly<T>>) -> Self {
        Basis::from_tracked(elements.into_iter().map(Tracked::new).collect())
    }

    /// The basis of computed elements, keeping their bounds.
    pub(crate) fn from_tracked(mut tracked: Vec<Tracked<T>>) -> Self {
        tracked.retain(|t| !t.is_zero());
        Basis {
            elements: tracked.iter().map(|t| t.poly.clone()).collect(),
            tracked,
        }
    }

    /// Whether the basis proves that `F1 = F2 = 0` has no common root in the box
    /// `u_range × v_range` (Theorem 1 with the certificate of the solver, see
    /// [`Method`](crate::Method)): exactly, a non-zero constant element; over `f64`, a
    /// constant element larger than its certificate bound on the box (its distance to the
    /// ideal there plus its rounding, doubled). `false` for non-finite ranges.
    ///
    /// # Examples
    /// ```
    /// use groebner::buchberger;
    /// use poly::BiPoly;
    /// // u·v − 1 and u: no common root; Buchberger's f64 basis is {1}, and it is a proof.
    /// let g = buchberger(&[
    ///     BiPoly::from_terms([(1.0, 1, 1), (-1.0, 0, 0)]),
    ///     BiPoly::from_terms([(1.0, 1, 0)]),
    /// ])?;
    /// assert!(g.contains_unit() && g.proves_no_root_in([-2.0, 2.0], [-2.0, 2.0]));
    /// # Ok::<(), groebner::Error>(())
    /// ```
    pub fn proves_no_root_in(&self, u_range: [f64; 2], v_range: [f64; 2]) -> bool {
        let corner = |r: [f64; 2]| r[0].abs().max(r[1].abs());
        let (u_max, v_max) = (corner(u_range), corner(v_range));
        if !(u_max.is_finite() && v_max.is_finite()) {
            return false;
        }
        self.tracked.iter().any(|t| {
            t.poly.is_constant()
                && (T::EXACT
                    || t.poly.coeff(0, 0).nearest_f64().abs() > t.certificate_bound(u_max, v_max))
        })
    }

    /// The elements, in the order the algorithm produced them.
    pub fn elements(&self) -> &[BiPoly<T>] {
        &self.elements
    }

    /// The elements, by value.
    pub fn into_elements(self) -> Vec<BiPoly<T>> {
        self.elements
    }

    /// The number of elements (the "size of Groebner basis" column of the article's table).
    pub fn len(&self) -> usize {
        self.elements.len()
    }

    /// True for the empty basis (the zero ideal: every point is a common root).
    pub fn is_empty(&self) -> bool {
        self.elements.is_empty()
    }

    /// Theorem 1 (article §3): `F1 = F2 = 0` has no common root, real or complex, iff the basis
    /// contains a non-zero constant (`1 ∈ G` after making it monic). This is Stam's miss test
    /// (condition C1). Over `f64` this describes the computed basis only: see
    /// [`proves_no_root_in`](Basis::proves_no_root_in).
    pub fn contains_unit(&self) -> bool {
        self.elements
            .iter()
            .any(|g| g.leading_monomial() == Some(Monomial::ONE))
    }

    /// Theorem 3 (article §3): the element of the basis that is a polynomial in `u` alone and
    /// not constant, with its index (the last such element when there are several). Its roots
    /// are the `u`-coordinates of the common roots.
    ///
    /// # Correctness note
    /// The article states "finitely many solutions ⇔ `G` contains a polynomial in `u`". The
    /// "⇐" direction needs Theorem 2's second condition as well: `G = {uv − u, u²}` is a Gröbner
    /// basis containing `u²`, yet every point `(0, v)` is a solution. Use
    /// [`has_finitely_many_roots`](Basis::has_finitely_many_roots) to decide finiteness.
    pub fn univariate_u(&self) -> Option<(usize, &BiPoly<T>)> {
        self.elements
            .iter()
            .enumerate()
            .rev()
            .find(|(_, g)| g.is_univariate_u() && !g.is_constant())
    }

    /// The univariate polynomial of [`univariate_u`](Basis::univariate_u) as a [`Poly`] in `u`.
    pub fn eliminant(&self) -> Option<Poly<T>> {
        self.univariate_u().and_then(|(_, g)| g.to_poly_u())
    }

    /// Theorem 2 (article §3): finitely many common roots (over the complex numbers) iff some
    /// leading monomial is a pure power `u^I` and some leading monomial is a pure power `v^J`.
    /// False when the basis contains a unit (no roots at all is "finitely many", but the
    /// question is then moot: see [`contains_unit`](Basis::contains_unit)).
    pub fn has_finitely_many_roots(&self) -> bool {
        if self.contains_unit() {
            return false;
        }
        let lms = || self.elements.iter().filter_map(BiPoly::leading_monomial);
        lms().any(|m| m.v == 0 && m.u > 0) && lms().any(|m| m.u == 0 && m.v > 0)
    }

    /// The elements that involve `v`, lowest `v`-degree first (ties: earlier first). Stam
    /// substitutes the root `u_i` into `F_{N−1}`, the one with the smallest non-zero `Deg_v`
    /// (article §4.4); the solver tries them in this order.
    pub fn v_elements(&self) -> Vec<&BiPoly<T>> {
        let mut out: Vec<&BiPoly<T>> = self.elements.iter().filter(|g| g.deg_v() > 0).collect();
        out.sort_by_key(|g| g.deg_v());
        out
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::testutil::qb;

    #[test]
    fn theorem_queries() {
        let unit = Basis::new(vec![qb(&[(1, 0, 0)]), qb(&[(1, 1, 1)])]);
        assert!(unit.contains_unit(), "1 ∈ G: no common root (Theorem 1)");
        assert!(!unit.has_finitely_many_roots(), "moot when 1 ∈ G");
        // Article basis: {v + u⁷ + …, u⁸ − …}: finite.
        let g = Basis::new(vec![
            qb(&[(1, 0, 1), (1, 7, 0), (1, 0, 0)]),
            qb(&[(1, 8, 0), (-1, 0, 0)]),
        ]);
        assert!(!g.contains_unit(), "no unit");
        assert_eq!(
            g.univariate_u().map(|(i, _)| i),
            Some(1),
            "element 1 is in K[u]"
        );
        assert_eq!(
            g.eliminant().map(|p| p.degree()),
            Some(8),
            "degree 8 eliminant"
        );
        assert!(
            g.has_finitely_many_roots(),
            "LMs v and u⁸: finite (Theorem 2)"
        );
        assert_eq!(g.v_elements().len(), 1, "one element involves v");
    }

    #[test]
    fn theorem_3_needs_theorem_2s_second_condition() {
        // {uv − u, u²} is a Gröbner basis with a univariate element, but the line u = 0 is a
        // common root set: Theorem 3's "⇐" fails, Theorem 2 gets it right.
        let g = Basis::new(vec![qb(&[(1, 1, 1), (-1, 1, 0)]), qb(&[(1, 2, 0)])]);
        assert!(g.univariate_u().is_some(), "u² is univariate");
        assert!(
            !g.has_finitely_many_roots(),
            "but (0, v) is a root for every v"
        );
        assert!(
            crate::is_groebner_basis(g.elements()).unwrap(),
            "and it is a Gröbner basis: SP = −u² reduces to 0"
        );
    }
}

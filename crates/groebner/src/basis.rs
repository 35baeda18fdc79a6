//! [`Basis`]: the output of the Gröbner algorithms, and the article's Theorems 1–3 as queries.

use poly::{BiPoly, Monomial, Poly, Scalar};

/// A list of non-zero, monic polynomials generating the ideal `(F1, F2, …)`, as produced by
/// [`stam_basis`](crate::stam_basis) or [`buchberger`](crate::buchberger).
///
/// The theorem queries assume the list is a Gröbner basis for Stam's order (TLO, article §3).
/// [`buchberger`](crate::buchberger) guarantees it; Stam's simplified loop is not proven to
/// (its output is checked against Buchberger's in the tests, and the solver completes it with
/// Buchberger when a query would otherwise be answered wrongly). The queries are about common
/// roots over the complex numbers: a ray can miss a patch whose equations have complex common
/// roots only.
#[derive(Clone, Debug, PartialEq)]
pub struct Basis<T> {
    elements: Vec<BiPoly<T>>,
}

impl<T: Scalar> Basis<T> {
    /// Wraps the given polynomials (zero polynomials are dropped, the rest kept in order).
    pub fn new(elements: Vec<BiPoly<T>>) -> Self {
        Basis {
            elements: elements.into_iter().filter(|g| !g.is_zero()).collect(),
        }
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
    /// (condition C1).
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
            crate::is_groebner_basis(g.elements()),
            "and it is a Gröbner basis: SP = −u² reduces to 0"
        );
    }
}

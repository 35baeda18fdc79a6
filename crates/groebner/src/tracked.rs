//! [`Tracked`]: a polynomial under reduction together with a running bound on the round-off
//! error of each of its coefficients, so that `f64` cancellation is recognised relative to the
//! computation that produced it.
//!
//! # The zero rule (`f64`)
//! Stam treated `|x| < 1e-9` as zero (article §5, `ZERO()` in `ray3.c`), whatever the size of
//! the polynomials. Here every coefficient `c` carries a first-order bound `e` on its absolute
//! round-off error (running error analysis, Higham, *Accuracy and Stability of Numerical
//! Algorithms*, §3.3), propagated through every operation since the input:
//!
//! * input coefficients are taken as exact data: `e = 0`;
//! * a scalar `λ` formed as `a / b` has error `|λ|·(e_a/|a| + e_b/|b| + u)`, `u = 2⁻⁵³`;
//! * a step `p ← p − λ·x·q` (`x` a monomial) gives each touched coefficient
//!   `e_p + |λ|·e_q + e_λ·|q_k| + u·(|p_k| + 2|λ·q_k|)` (one product and one subtraction);
//! * dividing by the leading coefficient `lc` divides the bounds by `|lc|` and adds
//!   `|c/lc|·(e_lc/|lc| + u)`.
//!
//! A coefficient is set to exactly zero when `|c| ≤ ZERO_ERR_FACTOR · e`, that is when the
//! bound cannot certify that it is non-zero (with a factor 4 of slack for the neglected
//! second-order terms). Leading coefficients obtained by cancellation are the critical case:
//! a residue kept as a leading term would be divided by and would turn the whole polynomial
//! into noise. The rule is scale-invariant, follows cancellation through the whole
//! computation, and also propagates the error of the multipliers (a quotient of two cancelled
//! leading coefficients can be inaccurate in every digit). The monomial that a reduction step
//! cancels is set to zero by construction. Over exact [`Rat`] there is no threshold and no
//! bounds are kept.
//!
//! [`Rat`]: poly::Rat

use poly::{BiPoly, Monomial, Scalar};

use crate::roots::SolveScalar;

/// Slack factor of the zero rule (see the module docs): a coefficient is zero when
/// `|c| ≤ ZERO_ERR_FACTOR · e`. The bound `e` is first-order; 4 covers the neglected
/// second-order terms many times over while dropping nothing the bound would certify by more
/// than two bits.
pub(crate) const ZERO_ERR_FACTOR: f64 = 4.0;

/// Unit round-off of `f64`, `2⁻⁵³`.
const UNIT_ROUNDOFF: f64 = f64::EPSILON / 2.0;

/// A dense grid of error bounds indexed like a [`BiPoly`] (`i` power of `u`, `j` of `v`),
/// growing on demand; entries outside are zero.
#[derive(Clone, Debug)]
struct ErrGrid<T> {
    stride: usize,
    data: Vec<T>,
}

impl<T: Scalar> ErrGrid<T> {
    fn empty() -> Self {
        ErrGrid {
            stride: 0,
            data: Vec::new(),
        }
    }

    fn get(&self, i: usize, j: usize) -> T {
        if i >= self.stride {
            return T::zero();
        }
        self.data
            .get(j * self.stride + i)
            .cloned()
            .unwrap_or_else(T::zero)
    }

    /// Makes room for `u^i v^j` with `i < stride`, `j < rows`.
    fn ensure(&mut self, stride: usize, rows: usize) {
        let cur_rows = self.data.len().checked_div(self.stride).unwrap_or(0);
        if stride <= self.stride && rows <= cur_rows {
            return;
        }
        let (ns, nr) = (stride.max(self.stride), rows.max(cur_rows));
        let mut data = vec![T::zero(); ns * nr];
        for (j, row) in self.data.chunks_exact(self.stride.max(1)).enumerate() {
            data[j * ns..j * ns + row.len()].clone_from_slice(row);
        }
        self.stride = ns;
        self.data = data;
    }

    fn add(&mut self, i: usize, j: usize, x: T) {
        self.ensure(i + 1, j + 1);
        let k = j * self.stride + i;
        self.data[k] = self.data[k].clone() + x;
    }

    fn set(&mut self, i: usize, j: usize, x: T) {
        self.ensure(i + 1, j + 1);
        let k = j * self.stride + i;
        self.data[k] = x;
    }

    fn scale(&mut self, c: &T) {
        for e in &mut self.data {
            *e = e.clone() * c;
        }
    }

    fn shifted(&self, m: Monomial, c: &T) -> Self {
        let rows = self.data.len().checked_div(self.stride).unwrap_or(0);
        let mut out = ErrGrid::empty();
        if rows == 0 {
            return out;
        }
        out.ensure(self.stride + m.u, rows + m.v);
        for j in 0..rows {
            for i in 0..self.stride {
                out.data[(j + m.v) * out.stride + i + m.u] = self.get(i, j) * c;
            }
        }
        out
    }
}

/// A polynomial and, for inexact scalars, its error bounds (see the module docs).
#[derive(Clone, Debug)]
pub(crate) struct Tracked<T> {
    /// The polynomial.
    pub(crate) poly: BiPoly<T>,
    /// Running error bounds; empty for exact scalars.
    err: ErrGrid<T>,
}

impl<T: SolveScalar> Tracked<T> {
    /// An input polynomial: its coefficients are exact data (error bound 0).
    pub(crate) fn new(poly: BiPoly<T>) -> Self {
        Tracked {
            poly,
            err: ErrGrid::empty(),
        }
    }

    /// The zero polynomial.
    pub(crate) fn zero() -> Self {
        Tracked::new(BiPoly::zero())
    }

    pub(crate) fn is_zero(&self) -> bool {
        self.poly.is_zero()
    }

    pub(crate) fn lm(&self) -> Option<Monomial> {
        self.poly.leading_monomial()
    }

    /// The coefficient of the leading monomial (zero for the zero polynomial).
    pub(crate) fn lc(&self) -> T {
        self.poly.leading_coeff().cloned().unwrap_or_else(T::zero)
    }

    /// The relative error bound `e/|c|` of the coefficient at `m` (0 for exact scalars).
    fn rel_err_at(&self, m: Monomial) -> T {
        if T::EXACT {
            return T::zero();
        }
        let c = self.poly.coeff(m.u, m.v).abs();
        if c.is_zero() {
            return T::zero();
        }
        self.err.get(m.u, m.v) / c
    }

    /// `a / b` and its absolute error bound, given the relative error bounds of `a` and `b`.
    fn quotient(a: T, rel_a: T, b: &T, rel_b: T) -> (T, T) {
        let q = a / b;
        if T::EXACT {
            return (q, T::zero());
        }
        let e = q.abs() * (rel_a + rel_b + unit_roundoff::<T>());
        (q, e)
    }

    /// `(c ± e_c) · x · self`.
    fn mul_term(&self, c: &T, c_err: &T, x: Monomial) -> Self {
        let poly = self.poly.mul_term(c, x);
        if T::EXACT {
            return Tracked::new(poly);
        }
        // e = |c|·e_self + e_c·|self| + u·|c·self|.
        let mut err = self.err.shifted(x, &c.abs());
        err.ensure(self.poly.stride() + x.u, self.poly.rows() + x.v);
        let u = unit_roundoff::<T>();
        for (m, a) in self.poly.terms() {
            let a = a.abs();
            err.add(
                m.u + x.u,
                m.v + x.v,
                c_err.clone() * &a + u.clone() * c.abs() * &a,
            );
        }
        Tracked { poly, err }
    }

    /// `self ← self − (c ± e_c)·x·q`, the term at `cancels` being zero by construction; then
    /// the zero rule.
    fn sub_term(&mut self, c: &T, c_err: &T, x: Monomial, q: &Tracked<T>, cancels: Monomial) {
        if !T::EXACT {
            // e_k += |c|·e_q + e_c·|q_k| + u·(|p_k| + 2|c·q_k|), with the old p_k.
            self.err.ensure(
                self.poly.stride().max(q.poly.stride() + x.u),
                self.poly.rows().max(q.poly.rows() + x.v),
            );
            let (ac, u) = (c.abs(), unit_roundoff::<T>());
            let two = T::one() + T::one();
            let q_rows = q.poly.rows();
            let q_err_rows = q.err.data.len().checked_div(q.err.stride).unwrap_or(0);
            for j in 0..q_rows.max(q_err_rows) {
                for i in 0..q.poly.stride().max(q.err.stride) {
                    let qk = q.poly.coeff(i, j).abs();
                    let eq = q.err.get(i, j);
                    if qk.is_zero() && eq.is_zero() {
                        continue;
                    }
                    let (ti, tj) = (i + x.u, j + x.v);
                    let pk = self.poly.coeff(ti, tj).abs();
                    let e = ac.clone() * eq
                        + c_err.clone() * &qk
                        + u.clone() * (pk + two.clone() * &ac * qk);
                    self.err.add(ti, tj, e);
                }
            }
        }
        self.poly.add_scaled_term_assign(&-c.clone(), x, &q.poly);
        if T::EXACT {
            return;
        }
        let err = &self.err;
        let factor = T::from_f64(ZERO_ERR_FACTOR).expect("a small constant");
        self.poly.zero_where(|i, j, c| {
            cancels == Monomial::new(i, j) || c.abs() <= factor.clone() * err.get(i, j)
        });
    }

    /// Cancels the term of `self` at `t` with `q` (`LM(q)` must divide `t`):
    /// `self ← self − (c_t / lc(q))·(t / LM(q))·q`. A reduction step (article §3 def. 4).
    pub(crate) fn cancel_with(&mut self, t: Monomial, q: &Tracked<T>) {
        let lq = q.lm().expect("a reducer is non-zero");
        let x = lq.quotient_of(t).expect("LM(q) divides t");
        let (c, c_err) = Self::quotient(
            self.poly.coeff(t.u, t.v),
            self.rel_err_at(t),
            &q.lc(),
            q.rel_err_at(lq),
        );
        self.sub_term(&c, &c_err, x, q, t);
    }

    /// The S-polynomial `(L/LM(f))·f/lc(f) − (L/LM(g))·g/lc(g)` (article §3 def. 6).
    pub(crate) fn s_poly(f: &Tracked<T>, g: &Tracked<T>) -> Tracked<T> {
        let (Some(lf), Some(lg)) = (f.lm(), g.lm()) else {
            return Tracked::zero();
        };
        let l = lf.lcm(lg);
        let (cf, ef) = Self::quotient(T::one(), T::zero(), &f.lc(), f.rel_err_at(lf));
        let (cg, eg) = Self::quotient(T::one(), T::zero(), &g.lc(), g.rel_err_at(lg));
        let mut s = f.mul_term(&cf, &ef, lf.quotient_of(l).expect("LM(f) | lcm"));
        s.sub_term(&cg, &eg, lg.quotient_of(l).expect("LM(g) | lcm"), g, l);
        s
    }

    /// Divides by the leading coefficient (Stam's `Scale`); the leading term becomes exactly 1.
    pub(crate) fn make_monic(&mut self) {
        if T::EXACT {
            self.poly.make_monic_in_place();
            return;
        }
        let Some(lm) = self.lm() else {
            return;
        };
        let rel_lc = self.rel_err_at(lm);
        let Some(lc) = self.poly.make_monic_in_place() else {
            return;
        };
        if T::EXACT {
            return;
        }
        // e ← e/|lc| + |c/lc|·(e_lc/|lc| + u); the new leading 1 is exact.
        let inv = T::one() / lc.abs();
        self.err.scale(&inv);
        let r = rel_lc + unit_roundoff::<T>();
        for (m, c) in self.poly.terms() {
            self.err.add(m.u, m.v, c.abs() * &r);
        }
        self.err.set(lm.u, lm.v, T::zero());
    }

    /// One top-down reduction step (article §3 def. 4) on the highest term of `self` that lies
    /// strictly below `below` (`None`: no bound) and is a multiple of a leading monomial of
    /// `basis`; returns the reduced monomial, or `None` when there is no such term.
    pub(crate) fn reduce_step(
        &mut self,
        basis: &[Tracked<T>],
        below: Option<Monomial>,
    ) -> Option<Monomial> {
        let (t, k) = self.poly.terms().rev().find_map(|(t, _)| {
            if below.is_some_and(|b| t >= b) {
                return None;
            }
            basis
                .iter()
                .position(|g| g.lm().is_some_and(|lm| lm.divides(t)))
                .map(|k| (t, k))
        })?;
        self.cancel_with(t, &basis[k]);
        Some(t)
    }

    /// Top reduction: reduces the leading term while it is a multiple of some `LM(g)`. The
    /// result is zero iff the normal form is, which is all Buchberger's loop needs; the tails
    /// are reduced once at the end ([`reduce_basis`](crate::reduce_basis)).
    pub(crate) fn reduce_leading(&mut self, basis: &[Tracked<T>]) {
        while let Some(t) = self.lm() {
            let Some(g) = basis
                .iter()
                .find(|g| g.lm().is_some_and(|lm| lm.divides(t)))
            else {
                return;
            };
            self.cancel_with(t, g);
        }
    }

    /// The normal form `NF(self, basis)` (article §3 def. 5): reduces every term, top down.
    /// Terms above a reduced monomial never change again (every term of `x·g` is at most
    /// `x·LM(g)`), so one downward sweep suffices.
    pub(crate) fn reduce_fully(&mut self, basis: &[Tracked<T>]) {
        let mut below = None;
        while let Some(t) = self.reduce_step(basis, below) {
            below = Some(t);
        }
    }
}

fn unit_roundoff<T: SolveScalar>() -> T {
    T::from_f64(UNIT_ROUNDOFF).expect("representable")
}

#[cfg(test)]
mod tests {
    use super::*;
    use num_traits::Signed;
    use poly::Rat;

    #[test]
    fn error_bound_covers_the_true_error() {
        // p = (1/3)·u + 0.1·v reduced by q = v + (1/7)·u: the u-coefficient of the result,
        // 1/3 − 0.1/7, computed in f64, must be within its bound of the exact value.
        let p = BiPoly::from_terms([(1.0 / 3.0, 1, 0), (0.1, 0, 1)]);
        let q = BiPoly::from_terms([(1.0, 0, 1), (1.0 / 7.0, 1, 0)]);
        let mut t = Tracked::new(p.clone());
        t.cancel_with(Monomial::new(0, 1), &Tracked::new(q.clone()));
        let exact = |x: f64| Rat::from_f64_exact(x).unwrap();
        let truth = exact(1.0 / 3.0) - exact(0.1) * exact(1.0 / 7.0);
        let got = t.poly.coeff(1, 0);
        let err = (exact(got) - truth).abs();
        let bound = exact(t.err.get(1, 0));
        assert!(err <= bound, "error {err} exceeds its bound {bound}");
        assert!(
            bound > Rat::from_integer(0.into()),
            "a rounded result has a positive bound"
        );
        assert_eq!(
            t.poly.coeff(0, 1),
            0.0,
            "the cancelled term is exactly zero"
        );
    }

    #[test]
    fn residue_of_an_inexact_quotient_is_zeroed() {
        // p = 0.1·v + 0.3·u and q = 0.3·v + 0.9·u are proportional up to the rounding of the
        // decimal constants: the u-term left by p − (0.1/0.3)·q is round-off residue, and it
        // must vanish at every scale (a fixed threshold such as Stam's 1e-9 would keep it at
        // scale 1e20 and would wipe out the whole polynomial at scale 1e-20).
        for s in [1e-20, 1.0, 1e20] {
            let p = BiPoly::from_terms([(0.1 * s, 0, 1), (0.3 * s, 1, 0)]);
            let q = BiPoly::from_terms([(0.3 * s, 0, 1), (0.9 * s, 1, 0)]);
            let mut t = Tracked::new(p);
            t.cancel_with(Monomial::new(0, 1), &Tracked::new(q));
            assert!(t.is_zero(), "scale {s}: residue {} survived", t.poly);
        }
    }
}

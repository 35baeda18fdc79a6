//! [`Tracked`]: a polynomial under reduction together with a bound, per coefficient, on its
//! distance to the ideal of the input polynomials, so that `f64` cancellation is recognised
//! relative to the computation that produced it, and an `f64` basis element can be used as a
//! certificate.
//!
//! # The ideal-distance bound (`f64`)
//! Every step of the Gröbner algorithms (`p ← p − λ·x·q`, S-polynomials, division by a leading
//! coefficient) maps elements of the ideal `(F1, F2)` to elements of the ideal *whatever the
//! scalar `λ`*: a multiplier computed inaccurately is still a multiplier. So instead of the
//! error with respect to the exact run of the same algorithm (which `f64` need not follow: one
//! coefficient judged zero and the runs take different branches), each coefficient carries a
//! first-order bound `d` on `|p̂_ij − p*_ij|` for *some* exact element `p*` of the ideal
//! (running error analysis, Higham, *Accuracy and Stability of Numerical Algorithms*, §3.3):
//!
//! * input coefficients are exact: `d = 0`;
//! * `p ← p − λ·x·q` (`x` a monomial) adds `|λ|·d_q + u·(|p_k| + 2|λ·q_k|)` to each touched
//!   coefficient, `u = 2⁻⁵³` (one product and one subtraction);
//! * dividing by the leading coefficient `lc` divides the bounds by `|lc|` and adds
//!   `u·|c/lc|`;
//! * setting a coefficient `c` to zero adds `|c|`.
//!
//! # The zero rule (`f64`)
//! Stam treated `|x| < 1e-9` as zero (article §5, `ZERO()` in `ray3.c`), whatever the size of
//! the polynomials. Here a coefficient is set to exactly zero when `|c| ≤ ZERO_ERR_FACTOR · d`,
//! i.e. when it is indistinguishable from the rounding that formed it (a factor 4 of slack for
//! the neglected second-order terms). Leading coefficients obtained by cancellation are the
//! critical case: a residue kept as a leading term would be divided by and would turn the whole
//! polynomial into noise. The rule is scale-invariant; the monomial that a reduction step
//! cancels is set to zero by construction.
//!
//! # The certificate
//! At a common root `(u_r, v_r)` of the inputs every `p*` vanishes, so
//! `|p̂(u_r, v_r)| ≤ Σ d_ij |u_r|^i |v_r|^j` ([`Tracked::ideal_distance_at`]): an `f64`
//! eliminant larger than that bound at `u` proves that no root has this `u`, and a constant
//! larger than its bound proves the ray misses ([`certificate_bound`], used by the solver). An earlier version
//! also propagated the multipliers' own errors into a bound on the distance to the exact run
//! (and zeroed against that); on the teapot view of `paper-notes/groebner.md` §5 it zeroed more
//! coefficients and certified 1% of the systems, against 13% with this bound.
//!
//! Over exact [`Rat`] there is no threshold and no bounds are kept.
//!
//! [`Rat`]: poly::Rat

use num_traits::Signed;
use poly::{BiPoly, Monomial, Scalar, UNIT_ROUNDOFF, gamma};

use crate::error::Error;

/// Slack factor of the zero rule (see the module docs): a coefficient is zero when
/// `|c| ≤ ZERO_ERR_FACTOR · d`. The bound `d` is first-order; 4 covers the neglected
/// second-order terms many times over while dropping nothing the bound would certify by more
/// than two bits.
pub(crate) const ZERO_ERR_FACTOR: f64 = 4.0;

/// A new element of Stam's `f64` loop whose ideal-distance bound on the box reaches this
/// fraction of the size of its terms ends the run early ([`Tracked::is_noise`]): the solver
/// falls back to the resultant anyway in such runs, and the later rounds are the expensive
/// ones. A speed heuristic only (correctness comes from the final certificate). Measured on
/// the teapot view (`paper-notes/groebner.md` §5): with `1e-4` no run that would have been
/// certified with hits was stopped, and the `f64` Stam solve took ~40% less time than with `1`.
pub(crate) const NOISE_ABORT_REL: f64 = 1e-4;

/// Safety factor of the certificate ([`certificate_bound`]): the ideal-distance bound and the
/// evaluation bound are first order in the unit round-off; doubling them covers the neglected
/// second-order terms for any run short enough to be certified at all (a bound that is not
/// small against the element is useless anyway).
pub(crate) const CERT_SAFETY: f64 = 2.0;

/// The certificate's bound on `|ĝ(u, v)|` at a common root in the box `|u| ≤ u_max`,
/// `|v| ≤ v_max` for a basis element `ĝ` computed in `f64`: its ideal distance there
/// ([`Tracked::ideal_distance_at`]), plus the rounding of evaluating `ĝ` itself (`γ(2n)` times
/// the size of its terms `Σ|c_ij| u_max^i v_max^j`, `n = stride + rows` of its grid), times
/// [`CERT_SAFETY`]. One formula for the general and the per-ray (fixed-grid) loops.
pub(crate) fn certificate_bound(ideal_distance: f64, size: f64, extent: usize) -> f64 {
    CERT_SAFETY * (ideal_distance + gamma(2 * extent) * size)
}

/// A dense grid of bounds indexed like a [`BiPoly`] (`i` power of `u`, `j` of `v`), growing on
/// demand; entries outside are zero.
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

    fn rows(&self) -> usize {
        self.data.len().checked_div(self.stride).unwrap_or(0)
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
        let cur_rows = self.rows();
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
        if i >= self.stride || (j + 1) * self.stride > self.data.len() {
            self.ensure(i + 1, j + 1);
        }
        let k = j * self.stride + i;
        self.data[k] = self.data[k].clone() + x;
    }

    fn scale(&mut self, c: &T) {
        for e in &mut self.data {
            *e = e.clone() * c;
        }
    }

    fn shifted(&self, m: Monomial, c: &T) -> Self {
        let rows = self.rows();
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

/// A polynomial and, for inexact scalars, its ideal-distance bounds (see the module docs).
#[derive(Clone, Debug)]
pub(crate) struct Tracked<T> {
    /// The polynomial.
    pub(crate) poly: BiPoly<T>,
    /// Ideal-distance bounds; empty for exact scalars and for exact inputs.
    dist: ErrGrid<T>,
}

impl<T: Scalar> Tracked<T> {
    /// An input polynomial: its coefficients are exact data (bound 0).
    pub(crate) fn new(poly: BiPoly<T>) -> Self {
        Tracked {
            poly,
            dist: ErrGrid::empty(),
        }
    }

    /// The zero polynomial.
    pub(crate) fn zero() -> Self {
        Tracked::new(BiPoly::zero())
    }

    pub(crate) fn is_zero(&self) -> bool {
        self.poly.is_zero()
    }

    /// `Err(Error::Overflow)` when a coefficient is not finite (`f64` only): NaN and infinity
    /// break the invariants the loops rely on (a NaN leading term is never cancelled, so `R2`
    /// would spin forever).
    pub(crate) fn check_finite(&self, algorithm: &'static str) -> Result<(), Error> {
        if T::EXACT
            || self
                .poly
                .coeffs()
                .iter()
                .all(|c| c.nearest_f64().is_finite())
        {
            Ok(())
        } else {
            Err(Error::Overflow { algorithm })
        }
    }

    pub(crate) fn lm(&self) -> Option<Monomial> {
        self.poly.leading_monomial()
    }

    /// The coefficient of the leading monomial (zero for the zero polynomial).
    pub(crate) fn lc(&self) -> T {
        self.poly.leading_coeff().cloned().unwrap_or_else(T::zero)
    }

    /// `c · x · self` (rounding of the products added to the bounds).
    fn mul_term(&self, c: &T, x: Monomial) -> Self {
        let poly = self.poly.mul_term(c, x);
        if T::EXACT {
            return Tracked::new(poly);
        }
        let mut dist = self.dist.shifted(x, &c.abs());
        dist.ensure(self.poly.stride() + x.u, self.poly.rows() + x.v);
        let u = unit_roundoff::<T>();
        for (m, a) in self.poly.terms() {
            dist.add(m.u + x.u, m.v + x.v, u.clone() * c.abs() * a.abs());
        }
        Tracked { poly, dist }
    }

    /// `self ← self − c·x·q`, the term at `cancels` being zero by construction; then the zero
    /// rule.
    fn sub_term(&mut self, c: &T, x: Monomial, q: &Tracked<T>, cancels: Monomial) {
        if !T::EXACT {
            // d_k += |c|·d_q + u·(|p_k| + 2|c·q_k|), with the old p_k.
            let rows = q.poly.rows().max(q.dist.rows());
            let stride = q.poly.stride().max(q.dist.stride);
            self.dist.ensure(
                self.poly.stride().max(stride + x.u),
                self.poly.rows().max(rows + x.v),
            );
            let (ac, u) = (c.abs(), unit_roundoff::<T>());
            let two_ac = (T::one() + T::one()) * &ac;
            let ds = self.dist.stride;
            let (qs, ps) = (q.poly.stride(), self.poly.stride());
            let (qc, pc) = (q.poly.coeffs(), self.poly.coeffs());
            for j in 0..rows {
                for i in 0..stride {
                    let qk = if i < qs {
                        qc.get(j * qs + i).map_or_else(T::zero, Signed::abs)
                    } else {
                        T::zero()
                    };
                    let dq = q.dist.get(i, j);
                    if qk.is_zero() && dq.is_zero() {
                        continue;
                    }
                    let (ti, tj) = (i + x.u, j + x.v);
                    let pk = if ti < ps {
                        pc.get(tj * ps + ti).map_or_else(T::zero, Signed::abs)
                    } else {
                        T::zero()
                    };
                    let add = ac.clone() * dq + u.clone() * (pk + two_ac.clone() * qk);
                    let slot = &mut self.dist.data[tj * ds + ti];
                    *slot = slot.clone() + add;
                }
            }
        }
        self.poly.add_scaled_term_assign(&-c.clone(), x, &q.poly);
        if T::EXACT {
            return;
        }
        let dist = &mut self.dist;
        let factor = T::from_f64(ZERO_ERR_FACTOR).expect("a small constant");
        self.poly.zero_where(|i, j, c| {
            let zero = cancels == Monomial::new(i, j) || c.abs() <= factor.clone() * dist.get(i, j);
            if zero {
                // Dropping a term moves the polynomial away from the ideal by |c|.
                dist.add(i, j, c.abs());
            }
            zero
        });
    }

    /// Cancels the term of `self` at `t` with `q` (`LM(q)` must divide `t`):
    /// `self ← self − (c_t / lc(q))·(t / LM(q))·q`. A reduction step (article §3 def. 4).
    pub(crate) fn cancel_with(&mut self, t: Monomial, q: &Tracked<T>) {
        let lq = q.lm().expect("a reducer is non-zero");
        let x = lq.quotient_of(t).expect("LM(q) divides t");
        let c = self.poly.coeff(t.u, t.v) / q.lc();
        self.sub_term(&c, x, q, t);
    }

    /// The S-polynomial `(L/LM(f))·f/lc(f) − (L/LM(g))·g/lc(g)` (article §3 def. 6).
    pub(crate) fn s_poly(f: &Tracked<T>, g: &Tracked<T>) -> Tracked<T> {
        let (Some(lf), Some(lg)) = (f.lm(), g.lm()) else {
            return Tracked::zero();
        };
        let l = lf.lcm(lg);
        let cf = T::one() / f.lc();
        let cg = T::one() / g.lc();
        let mut s = f.mul_term(&cf, lf.quotient_of(l).expect("LM(f) | lcm"));
        s.sub_term(&cg, lg.quotient_of(l).expect("LM(g) | lcm"), g, l);
        s
    }

    /// Divides by the leading coefficient (Stam's `Scale`); the leading term becomes exactly 1.
    pub(crate) fn make_monic(&mut self) {
        let Some(lc) = self.poly.make_monic_in_place() else {
            return;
        };
        if T::EXACT {
            return;
        }
        // d ← d/|lc| + u·|c/lc| (p*/lc is in the ideal for any lc).
        self.dist.scale(&(T::one() / lc.abs()));
        self.dist.ensure(self.poly.stride(), self.poly.rows());
        let u = unit_roundoff::<T>();
        let (ds, ps) = (self.dist.stride, self.poly.stride());
        for (k, c) in self.poly.coeffs().iter().enumerate() {
            if !c.is_zero() {
                let slot = &mut self.dist.data[(k / ps) * ds + k % ps];
                *slot = slot.clone() + u.clone() * c.abs();
            }
        }
    }

    /// Bound on the distance from this polynomial to the ideal of the inputs, at the corner
    /// `(u_max, v_max)`: `Σ d_ij u_max^i v_max^j`. For some exact element `p*` of the ideal,
    /// `|p̂(u, v) − p*(u, v)|` is at most this for all `|u| ≤ u_max`, `|v| ≤ v_max`; hence at a
    /// common root of the inputs in that box, `|p̂(u_r, v_r)|` is at most this (module docs).
    /// First order in the unit round-off. Zero for exact scalars.
    pub(crate) fn ideal_distance_at(&self, u_max: &T, v_max: &T) -> T {
        let mut total = T::zero();
        for j in (0..self.dist.rows()).rev() {
            let mut row = T::zero();
            for i in (0..self.dist.stride).rev() {
                row = row * u_max + self.dist.get(i, j);
            }
            total = total * v_max + row;
        }
        total
    }

    /// [`certificate_bound`] of this element on the box `|u| ≤ u_max`, `|v| ≤ v_max` (finite).
    pub(crate) fn certificate_bound(&self, u_max: f64, v_max: f64) -> f64 {
        let corner = |x: f64| T::from_f64(x).expect("a finite box corner");
        let distance = self.ideal_distance_at(&corner(u_max), &corner(v_max));
        let size = self.poly.map(Scalar::nearest_f64).eval_abs(u_max, v_max);
        certificate_bound(
            distance.nearest_f64(),
            size,
            self.poly.stride() + self.poly.rows(),
        )
    }

    /// Whether the ideal-distance bound at `(u_max, v_max)` reaches [`NOISE_ABORT_REL`] of the
    /// size of the polynomial's terms there (`Σ|c_ij| u_max^i v_max^j`). False for exact
    /// scalars.
    pub(crate) fn is_noise(&self, u_max: &T, v_max: &T) -> bool {
        if T::EXACT || self.is_zero() {
            return false;
        }
        let mut size = T::zero();
        for row in self.poly.rows_iter().rev() {
            let r = row.iter().rev().fold(T::zero(), |a, c| a * u_max + c.abs());
            size = size * v_max + r;
        }
        let rel = T::from_f64(NOISE_ABORT_REL).expect("a small constant");
        self.ideal_distance_at(u_max, v_max) >= size * rel
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
    pub(crate) fn reduce_leading(&mut self, basis: &[Tracked<T>]) -> Result<(), Error> {
        // Each step lowers the leading monomial, a descent in a well-order (finite); a
        // non-finite coefficient is refused before it can stall the descent.
        while let Some(t) = self.lm() {
            self.check_finite("buchberger")?;
            let Some(g) = basis
                .iter()
                .find(|g| g.lm().is_some_and(|lm| lm.divides(t)))
            else {
                return Ok(());
            };
            self.cancel_with(t, g);
        }
        Ok(())
    }

    /// The normal form `NF(self, basis)` (article §3 def. 5): reduces every term, top down.
    /// Terms above a reduced monomial never change again (every term of `x·g` is at most
    /// `x·LM(g)`), so one downward sweep suffices.
    ///
    /// The reduced monomial strictly decreases (a descent in a well-order, so finite) and the
    /// loop also stops at a non-finite coefficient (`f64`), which then stays in the result.
    pub(crate) fn reduce_fully(&mut self, basis: &[Tracked<T>]) {
        let mut below = None;
        while let Some(t) = self.reduce_step(basis, below) {
            below = Some(t);
            if self.check_finite("normal form").is_err() {
                return;
            }
        }
    }
}

fn unit_roundoff<T: Scalar>() -> T {
    T::from_f64(UNIT_ROUNDOFF).expect("2⁻⁵³ is representable")
}

#[cfg(test)]
mod tests {
    use super::*;
    use num_traits::Signed;
    use poly::Rat;

    #[test]
    fn bound_covers_the_distance_to_the_exact_combination() {
        // p = (1/3)·u + 0.1·v reduced by q = v + (1/7)·u with the computed multiplier
        // c = 0.1: the u-coefficient of the result must be within its bound of the exact
        // combination p − c·q (an element of the ideal (p, q) whatever c is).
        let p = BiPoly::from_terms([(1.0 / 3.0, 1, 0), (0.1, 0, 1)]);
        let q = BiPoly::from_terms([(1.0, 0, 1), (1.0 / 7.0, 1, 0)]);
        let mut t = Tracked::new(p.clone());
        t.cancel_with(Monomial::new(0, 1), &Tracked::new(q.clone()));
        let exact = |x: f64| Rat::from_f64_exact(x).unwrap();
        let truth = exact(1.0 / 3.0) - exact(0.1) * exact(1.0 / 7.0);
        let got = t.poly.coeff(1, 0);
        let err = (exact(got) - truth).abs();
        let bound = exact(t.dist.get(1, 0));
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
            assert!(
                t.ideal_distance_at(&1.0, &1.0) > 0.0,
                "scale {s}: the dropped residue is in the bound"
            );
        }
    }
}

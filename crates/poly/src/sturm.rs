//! [`SturmSequence`]: counting distinct real roots in an interval (seed §3.5.1, eq. 3.16–3.22).
//!
//! The sequence starts `V₀ = P`, `V₁ = P'` (eq. 3.18–3.19) and continues with negated
//! remainders, `V_{k−2} = Q_{k−1}·V_{k−1} − V_k` (eq. 3.20), until a remainder vanishes. With
//! `σ(x)` the number of sign changes in `V₀(x), …, V_q(x)`, zeros omitted (eq. 3.21),
//! `σ(a) − σ(b)` is the number of distinct real roots in `(a, b]` (eq. 3.22, with the endpoint
//! convention made precise below). See `paper-notes/sturm.md`.
//!
//! Two changes from the seed, both explained in the notes:
//! * Over [`Rat`] every member is multiplied by a *positive* constant to get coprime integer
//!   coefficients (a primitive remainder sequence). Positive factors never change a sign, so
//!   the counts are those of eq. 3.22, while coefficient growth stays polynomial.
//! * When `P` has multiple roots the last member `g = gcd(P, P')` is not constant, and every
//!   member is divided by it. The quotient sequence is a Sturm sequence of the square-free part
//!   `P/g`, so counts are of *distinct* roots and stay right at the multiple roots themselves
//!   (where the undivided sequence vanishes entirely).

use num_bigint::BigInt;
use num_traits::{One, Signed, Zero};
use smallvec::SmallVec;

use crate::eval_bound::{certified_sign, horner_bounded};
use crate::int_poly::IntPoly;
use crate::rescale::{exponent, ldexp};
use crate::root_error::RootError;
use crate::scalar::{Rat, Scalar};
use crate::univariate::{Poly, QPoly, UNIT_ROUNDOFF, gamma};

/// A Sturm sequence `V₀, V₁, …, V_q` (seed eq. 3.17): `σ(a) − σ(b)` counts distinct real roots.
///
/// Built by [`Poly::<Rat>::sturm`](Poly::sturm) (exact, certified) or
/// [`Poly::<f64>::sturm`](Poly::sturm) (normalised floating point, heuristic).
#[derive(Clone, Debug, PartialEq)]
pub struct SturmSequence<T> {
    polys: Vec<Poly<T>>,
    multiple_roots: bool,
    /// `f64` only (empty for [`Rat`]): a bound on the rounding of each member coefficient in
    /// the step that computed it (`P'`'s products, or the remainder's division; not the
    /// errors carried from earlier members: see [`neg_rem_f64`]).
    errs: Vec<Vec<f64>>,
    /// `f64` only: the sequence cannot stand for the stored polynomial's — a value overflowed
    /// or underflowed below the normal range while it was built, or a remainder coefficient
    /// was dropped as rounding noise (issue 11; see [`neg_rem_f64`]).
    lossy: bool,
}

impl<T> SturmSequence<T> {
    /// The members `V₀, …, V_q`, lowest degree first each. `V₀` is the square-free part of the
    /// polynomial up to a positive factor (exact) or the normalised polynomial (`f64`).
    pub fn polys(&self) -> &[Poly<T>] {
        &self.polys
    }

    /// True when the polynomial had a repeated root (its gcd with the derivative was not
    /// constant). Exact for [`Rat`]; for `f64` it means the remainder sequence ended early.
    pub fn had_multiple_roots(&self) -> bool {
        self.multiple_roots
    }
}

impl QPoly {
    /// The exact Sturm sequence of the square-free part (seed eq. 3.17–3.20).
    ///
    /// # Exactness
    /// Exact: members are integer polynomials (positive multiples of the seed's `V_k`, divided
    /// by `gcd(P, P')` when `P` has repeated roots), so [`SturmSequence::count_roots`] is a
    /// certified count of distinct real roots.
    ///
    /// # Errors
    /// [`RootError::ZeroPolynomial`] for the zero polynomial (every number is a root).
    ///
    /// # Complexity
    /// `O(n)` pseudo-divisions of integer polynomials; coefficient sizes grow polynomially with
    /// the degree (primitive remainder sequence).
    ///
    /// # Examples
    /// ```
    /// use poly::{QPoly, Rat};
    /// let q = |n: i64| Rat::from_integer(n.into());
    /// // (x − 1)²(x − 2)(x − 3): distinct roots 1, 2, 3.
    /// let p = QPoly::from_roots(&[q(1), q(1), q(2), q(3)]);
    /// let s = p.sturm()?;
    /// assert_eq!(s.count_roots(&q(0), &q(3)), 3); // (0, 3] includes the root 3
    /// assert_eq!(s.count_roots(&q(1), &q(2)), 1); // (1, 2] excludes the root 1
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn sturm(&self) -> Result<SturmSequence<Rat>, RootError> {
        if self.is_zero() {
            return Err(RootError::ZeroPolynomial);
        }
        let p = IntPoly::from_qpoly(self);
        let mut seq = vec![p.clone()];
        if p.degree() > 0 {
            seq.push(p.derivative());
            // Subresultant PRS (Brown and Traub 1971; Knuth, TAOCP vol. 2, §4.6.1), in
            // magnitudes: member k + 1 is `±prem(V_{k−1}, V_k)/|β_k|`, an exact division by a
            // positive integer, so it stays a positive multiple of `−rem` (a Sturm member).
            // Why not the primitive PRS: removing each member's content took a gcd of
            // thousands-of-bits coefficients per member, seconds at degree 33 with
            // coefficients up to f64::MAX (issue 13 follow-up); the subresultant divisor is
            // known in advance and the members' sizes grow as slowly.
            // |ψ₁| = 1, |β₁| = 1; |ψ_k| = |lc(V_{k−1})|^{d_{k−1}} / |ψ_{k−1}|^{d_{k−1}−1} and
            // |β_k| = |lc(V_{k−1})|·|ψ_k|^{d_k}, with d_k = deg V_{k−1} − deg V_k.
            let mut psi = BigInt::one();
            let mut beta = BigInt::one();
            loop {
                let n = seq.len();
                let r = seq[n - 2].neg_prem(&seq[n - 1]).div_scalar_exact(&beta);
                if r.is_zero() {
                    break;
                }
                let d_prev = seq[n - 2].degree() - seq[n - 1].degree();
                let d_next = seq[n - 1].degree() - r.degree();
                let lc = seq[n - 1].lc_abs();
                psi = if d_prev == 1 {
                    lc.clone()
                } else {
                    lc.pow(d_prev as u32) / psi.pow(d_prev as u32 - 1)
                };
                beta = lc * psi.pow(d_next as u32);
                seq.push(r);
            }
        }
        let g = seq.last().expect("sequence starts with p").clone();
        let multiple_roots = g.degree() > 0;
        if multiple_roots {
            // Divide by gcd(P, P') (eq. 3.20 stops at it): the sequence of P/g.
            seq = seq.iter().map(|v| v.div_exact(&g)).collect();
        }
        Ok(SturmSequence {
            polys: seq.iter().map(IntPoly::to_qpoly).collect(),
            multiple_roots,
            errs: Vec::new(),
            lossy: false,
        })
    }
}

impl SturmSequence<Rat> {
    /// `σ(x)`: sign changes in `V₀(x), …, V_q(x)`, zeros omitted (seed eq. 3.21).
    ///
    /// # Exactness
    /// Exact (integer evaluation of every member at the rational `x`).
    pub fn sign_changes_at(&self, x: &Rat) -> usize {
        count_changes(self.polys.iter().map(|v| int_sign_at(v, x)))
    }

    /// Sign changes at `−∞` (`to_plus = false`) or `+∞`.
    ///
    /// # Exactness
    /// Exact (signs of the leading coefficients and parities of the degrees).
    pub fn sign_changes_at_infinity(&self, to_plus: bool) -> usize {
        count_changes(self.polys.iter().map(|v| sign_at_infinity(v, to_plus)))
    }

    /// The number of distinct real roots in the half-open interval `(a, b]`.
    ///
    /// # Exactness
    /// Exact and certified, including when `a` or `b` is itself a root (a root at `a` is not
    /// counted, a root at `b` is) and at multiple roots (each distinct root counts once).
    /// An empty or reversed interval (`a ≥ b`) holds no roots and gives 0.
    ///
    /// # Complexity
    /// Two evaluations of every member at a rational point, in integer arithmetic.
    pub fn count_roots(&self, a: &Rat, b: &Rat) -> usize {
        if a >= b {
            return 0;
        }
        self.sign_changes_at(a)
            .saturating_sub(self.sign_changes_at(b))
    }

    /// The number of distinct real roots on the whole real line.
    ///
    /// # Exactness
    /// Exact and certified, multiple roots counted once.
    pub fn count_real_roots(&self) -> usize {
        self.sign_changes_at_infinity(false)
            .saturating_sub(self.sign_changes_at_infinity(true))
    }

    /// The exact sign (−1, 0 or 1) of the square-free part `V₀` at `x`; it vanishes exactly at
    /// the distinct roots of the polynomial and changes sign across each of them.
    ///
    /// # Exactness
    /// Exact.
    pub fn sign_of_square_free_at(&self, x: &Rat) -> i8 {
        int_sign_at(&self.polys[0], x)
    }
}

impl Poly<f64> {
    /// A Sturm sequence in floating point, normalised for stability: every member is scaled by
    /// the power of two that brings its largest coefficient magnitude into `[1, 2)` (a positive
    /// factor, exact unless a coefficient leaves the normal range, so signs are unchanged),
    /// and a remainder's leading coefficient is dropped when it is no larger than its own
    /// rounding bound (`γ(4k + 2)·Σ|terms|`), so degrees fall when the exact remainder's would.
    /// Coefficients are never dropped for being small relative to the others (Wilkinson's
    /// polynomial has a leading 1 next to 20!). Issue 11: the members carry that rounding
    /// bound per coefficient, and the sequence is marked unusable when a value
    /// overflowed or fell below the normal range on the way (`1e±300` coefficients), so the
    /// checked counts of the root queries can refuse instead of counting noise.
    ///
    /// # Accuracy
    /// A heuristic. Each remainder is rounded, so [`SturmSequence::count_roots`] can be wrong
    /// when roots are clustered or the degree is high (the seed reports instability above
    /// degree 8 for an unnormalised version). For certified counts use
    /// `self.to_rat()` and [`Poly::<Rat>::sturm`](Poly::sturm); the root finders
    /// ([`Poly::smallest_root`]) are certified without it.
    ///
    /// # Errors
    /// [`RootError::NonFiniteCoefficient`] and [`RootError::ZeroPolynomial`].
    pub fn sturm(&self) -> Result<SturmSequence<f64>, RootError> {
        check_finite(self.coeffs())?;
        if self.is_zero() {
            return Err(RootError::ZeroPolynomial);
        }
        let mut lossy = false;
        let (p, _) = normalise(self.clone(), Vec::new(), &mut lossy);
        let mut seq = vec![p.clone()];
        // V₀ is the stored polynomial times an exact power of two: no coefficient error.
        let mut errs = vec![vec![0.0; p.coeffs().len()]];
        if p.degree() > 0 {
            let d = p.derivative();
            // P' has one rounding per coefficient (i·cᵢ): u·|i·cᵢ|.
            let d_err = d.coeffs().iter().map(|c| c.abs() * UNIT_ROUNDOFF).collect();
            let (d, d_err) = normalise(d, d_err, &mut lossy);
            seq.push(d);
            errs.push(d_err);
            while seq.last().is_some_and(|v| v.degree() > 0) && !lossy {
                let n = seq.len();
                let (r, r_err) = neg_rem_f64(&seq[n - 2], &seq[n - 1], &mut lossy);
                if r.is_zero() {
                    break;
                }
                let (r, r_err) = normalise(r, r_err, &mut lossy);
                seq.push(r);
                errs.push(r_err);
            }
        }
        let multiple_roots = seq.last().is_some_and(|g| g.degree() > 0);
        Ok(SturmSequence {
            polys: seq,
            multiple_roots,
            errs,
            lossy,
        })
    }
}

impl SturmSequence<f64> {
    /// `σ(x)` in floating point (zeros omitted); `x` may be ±∞.
    ///
    /// # Accuracy
    /// Heuristic: each member is evaluated by plain Horner; a value that rounding pushed
    /// across zero changes the count. No bound is attempted.
    pub fn sign_changes_at(&self, x: f64) -> usize {
        if x.is_infinite() {
            return count_changes(self.polys.iter().map(|v| f64_sign_at_infinity(v, x > 0.0)));
        }
        count_changes(self.polys.iter().map(|v| {
            let y = v.eval(&x);
            if y > 0.0 {
                1
            } else if y < 0.0 {
                -1
            } else {
                0
            }
        }))
    }

    /// The number of distinct real roots in `(a, b]`, evaluated in floating point; `a` and `b`
    /// may be infinite.
    ///
    /// # Accuracy
    /// Heuristic (see [`Poly::<f64>::sturm`](Poly::sturm)): exact arithmetic on the same
    /// sequence would give the true count, rounding in the sequence and in the evaluations can
    /// change it. An empty or reversed interval gives 0; a NaN bound gives 0.
    pub fn count_roots(&self, a: f64, b: f64) -> usize {
        if a.is_nan() || b.is_nan() || a >= b {
            return 0;
        }
        self.sign_changes_at(a)
            .saturating_sub(self.sign_changes_at(b))
    }

    /// [`count_roots`](Self::count_roots), or `None` when the evaluation itself cannot be
    /// trusted: at an end, a member `V_k` (`k ≥ 1`) has a value within its own rounding
    /// bound ([`horner_bounded`]) and changing its sign could change `σ` — it is last, or its
    /// nearest certain neighbours do not have opposite signs, or a neighbour is uncertain
    /// too. (A lone uncertain member between certain opposite neighbours cannot change `σ`:
    /// that is eq. 3.21's own argument for zeros inside the sequence.) `V₀` is exempt: near
    /// a root of `P` the count is only ambiguous about which side of the end the root lies.
    ///
    /// # Accuracy
    /// Still a heuristic: the members' coefficients carry the remainder sequence's rounding,
    /// which no bound here covers. This catches rounding in the evaluation only.
    pub(crate) fn count_roots_checked(&self, a: f64, b: f64) -> Option<usize> {
        if a.is_nan() || b.is_nan() || a >= b {
            return Some(0);
        }
        let (va, vb) = (self.sign_changes_checked(a)?, self.sign_changes_checked(b)?);
        Some(va.saturating_sub(vb))
    }

    /// `σ(x)`, or `None` when an uncertain member sign could change it (see
    /// [`count_roots_checked`](Self::count_roots_checked)), or when the sequence is unusable
    /// (built with an overflow or an underflow) or a member's value is not finite.
    fn sign_changes_checked(&self, x: f64) -> Option<usize> {
        if self.lossy {
            return None;
        }
        if x.is_infinite() {
            return Some(self.sign_changes_at(x));
        }
        // Signs with 2 for "uncertain"; V₀'s is certified.
        let mut signs = CheckedSigns::from_elem(0, self.polys.len());
        for (k, (v, e)) in self.polys.iter().zip(&self.errs).enumerate() {
            let (value, err) = horner_bounded(v.coeffs(), x);
            if !value.is_finite() || !err.is_finite() {
                return None;
            }
            // The member's coefficient errors at |x| (zero for V₀), raised for the rounding
            // of this sum as Horner's bound is (n + 1 terms).
            let ax = x.abs();
            let coeff_err =
                e.iter().rev().fold(0.0, |acc, &ej| acc * ax + ej) * (1.0 + gamma(2 * e.len() + 2));
            let err = err + coeff_err;
            if k == 0 && value == 0.0 {
                signs[k] = v0_sign_at_zero_value(v.coeffs(), x)?;
                continue;
            }
            signs[k] = if k > 0 && value.abs() <= err && err > 0.0 {
                2
            } else if value > 0.0 {
                1
            } else if value < 0.0 {
                -1
            } else {
                0
            };
        }
        changes_with_uncertain(&signs)
    }
}

/// The sign to count for `V₀` (the stored polynomial `c`, up to a positive factor) at `x`
/// where its computed value is exactly 0: the certified sign (compensated, then rescaled past
/// an underflow or overflow: `eval_bound.rs`), 0 when `x` is an exact root, `None` when
/// neither can be shown. A 0 counted where `P` is not zero hides roots: `2.04x²` on a range
/// narrowed to a few subnormals around 0 underflowed to 0 at both ends and its double root
/// was counted as none (issue 11). A non-zero value within rounding keeps its computed sign:
/// the count is then only unsure which side of `x` a root near it lies, as at any end.
pub(crate) fn v0_sign_at_zero_value(c: &[f64], x: f64) -> Option<i8> {
    match certified_sign(c, x, 0.0) {
        0 => exact_zero_at(c, x).then_some(0),
        s => Some(s),
    }
}

/// Sign changes in `signs` (−1, 0, 1, or 2 for "uncertain"), zeros omitted (eq. 3.21), or
/// `None` when an uncertain sign could change the count: it is first or last among the
/// non-zero signs, or its nearest non-zero neighbours are not certain and opposite. (A lone
/// uncertain sign between certain opposite neighbours adds one change whichever it is.)
pub(crate) fn changes_with_uncertain(signs: &[i8]) -> Option<usize> {
    for (k, &s) in signs.iter().enumerate() {
        if s != 2 {
            continue;
        }
        let before = signs[..k].iter().rev().find(|&&t| t != 0);
        let after = signs[k + 1..].iter().find(|&&t| t != 0);
        match (before, after) {
            (Some(&l), Some(&r)) if l != 2 && r != 2 && l == -r => {}
            _ => return None,
        }
    }
    Some(count_changes(signs.iter().copied().filter(|&s| s != 2)))
}

/// True when the polynomial with coefficients `c` vanishes exactly at the finite `x`
/// (rational evaluation: the rare path where no `f64` bound can sign `p(x)`).
pub(crate) fn exact_zero_at(c: &[f64], x: f64) -> bool {
    let (Some(q), Some(xq)) = (
        Poly::new(c.to_vec()).to_rat(),
        crate::scalar::rat_from_f64(x),
    ) else {
        return false;
    };
    q.eval(&xq).is_zero()
}

/// The checked signs of a sequence's members at one point (2 for "uncertain"), on the stack
/// up to 64 members (longer sequences allocate): 64 covers every degree below 64, all the
/// renderer and the stability suite ask.
pub(crate) type CheckedSigns = SmallVec<[i8; 64]>;

/// Scales `p` and its coefficient errors `err` (empty: none yet, filled with zeros) by the
/// power of two `2^-e` that brings the largest coefficient magnitude into `[1, 2)`: a
/// positive factor, exact for every coefficient that stays in the normal range
/// (`rescale.rs`'s [`ldexp`]). Sets `lossy` when a non-zero coefficient leaves the normal
/// range (the member would no longer be the sequence's member up to a positive factor) or
/// a coefficient or error is not finite.
fn normalise(p: Poly<f64>, mut err: Vec<f64>, lossy: &mut bool) -> (Poly<f64>, Vec<f64>) {
    err.resize(p.coeffs().len(), 0.0);
    let m = p.max_abs_coeff();
    if !m.is_finite() || err.iter().any(|e| !e.is_finite()) {
        *lossy = true;
        return (p, err);
    }
    if m == 0.0 {
        return (p, err);
    }
    let e = -exponent(m);
    let mut c = p.into_coeffs();
    for x in &mut c {
        let y = ldexp(*x, e);
        if *x != 0.0 && y.abs() < f64::MIN_POSITIVE {
            *lossy = true;
        }
        *x = y;
    }
    for x in &mut err {
        // Rounded up: an error that underflows is kept at the smallest subnormal.
        *x = ldexp(*x, e).max(if *x > 0.0 { f64::from_bits(1) } else { 0.0 });
    }
    (Poly::new_raw(c), err)
}

/// `−rem(a, d)` in floating point, with a bound on the rounding of each of its coefficients,
/// dropping leading coefficients that are within that bound of zero.
///
/// The bound, per coefficient `j` of the remainder, is `γ(4k + 2)·Σ|terms|` for the
/// division's own rounding over its `k` steps (Higham §5.1's argument for a sum of products).
/// It is the member's *own* rounding only: the errors `a` and `d` carry from earlier members
/// are not propagated. A first-order propagation of them (each quotient digit `c = r_top/lc`
/// carrying `(|err r_top| + |c|·err lc)/|lc|`, each update `|c|·err d_j + err c·|d_j|`) was
/// tried for issue 11 and refused every planted-roots polynomial from degree 8 on, where the
/// sequence in fact counted right (the worst case adds every error with the same sign). It
/// is what lets a member whose value at a point is below it be called "uncertain"
/// ([`SturmSequence::count_roots_checked`]): a heuristic's warning light, not a proof. Sets
/// `lossy` when a value is not finite, a non-zero remainder coefficient falls below the
/// normal range, or a leading coefficient is dropped as noise (within its bound but not an
/// exact zero with a zero bound): that is a decision the arithmetic cannot back, whether the
/// degree then falls by more than one or the whole remainder goes (a multiple root claimed
/// where two roots may be close). So does a *kept* coefficient within its bound: its sign is
/// noise, and the roots it places are then guessed (issue 11: coefficients 1e-296 … 1e-60
/// beside ones of order 1 placed roots within 1e-59 of 0 that such a sequence never counted).
fn neg_rem_f64(a: &Poly<f64>, d: &Poly<f64>, lossy: &mut bool) -> (Poly<f64>, Vec<f64>) {
    let (ac, dc) = (a.coeffs(), d.coeffs());
    let dn = dc.len() - 1;
    if ac.len() <= dn {
        return (-a, vec![0.0; ac.len()]);
    }
    let lc = dc[dn];
    let mut r = ac.to_vec();
    let mut mag: Vec<f64> = ac.iter().map(|x| x.abs()).collect();
    let steps = ac.len() - dn;
    for k in (0..steps).rev() {
        let c = r[k + dn] / lc;
        for (j, dj) in dc.iter().enumerate().take(dn) {
            r[k + j] -= c * dj;
            mag[k + j] += (c * dj).abs();
        }
    }
    r.truncate(dn);
    mag.truncate(dn);
    let g = crate::univariate::gamma(4 * steps + 2);
    while let (Some(x), Some(m)) = (r.last(), mag.last()) {
        let own = g * m;
        if x.abs() > own {
            break;
        }
        // A coefficient dropped as rounding noise (not an exact zero with no error): the
        // degree now falls by a decision, not by arithmetic, and the members that follow need
        // not approximate the exact sequence's (a pair of roots 1.1e-28 apart was read as a
        // double root and counted as none; issue 11). Exact zeros (`x⁴ − 1`'s remainder) are
        // structural and keep the sequence.
        if *x != 0.0 || own > 0.0 {
            *lossy = true;
        }
        r.pop();
        mag.pop();
    }
    let err: Vec<f64> = mag.iter().map(|m| g * m).collect();
    // A coefficient kept but within its own rounding: its sign is noise.
    if r.iter().zip(&err).any(|(x, e)| *e > 0.0 && x.abs() <= *e) {
        *lossy = true;
    }
    if r.iter().chain(&err).any(|x| !x.is_finite())
        || r.iter().any(|&x| x != 0.0 && x.abs() < f64::MIN_POSITIVE)
    {
        *lossy = true;
    }
    (Poly::new(r.into_iter().map(|x| -x).collect()), err)
}

pub(crate) fn check_finite(c: &[f64]) -> Result<(), RootError> {
    match c.iter().position(|c| !c.is_finite()) {
        Some(index) => Err(RootError::NonFiniteCoefficient { index }),
        None => Ok(()),
    }
}

/// Sign changes in a sequence of signs, zeros omitted (eq. 3.21).
fn count_changes(signs: impl Iterator<Item = i8>) -> usize {
    let mut last = 0i8;
    let mut count = 0;
    for s in signs {
        if s == 0 {
            continue;
        }
        if last != 0 && s != last {
            count += 1;
        }
        last = s;
    }
    count
}

/// Exact sign of an integer-coefficient `QPoly` at `x` (homogeneous Horner in integers: with
/// `x = n/d`, `d > 0`, the sign of `Σ cᵢ nⁱ d^(deg−i)`).
fn int_sign_at(p: &QPoly, x: &Rat) -> i8 {
    let Some(top) = p.coeffs().last() else {
        return 0;
    };
    debug_assert!(
        p.coeffs().iter().all(|c| c.is_integer()),
        "Sturm members are integral"
    );
    let (n, d) = (x.numer(), x.denom());
    let mut acc = top.numer().clone();
    // Points from f64 numbers have a power-of-two denominator 2^k: then d^j is a shift.
    let k = d.trailing_zeros().filter(|&k| d.bits() == k + 1);
    if let Some(k) = k {
        let mut shift = 0u64;
        for c in p.coeffs().iter().rev().skip(1) {
            shift += k;
            acc = acc * n + (c.numer() << shift);
        }
    } else {
        let mut dpow = num_bigint::BigInt::from(1);
        for c in p.coeffs().iter().rev().skip(1) {
            dpow *= d;
            acc = acc * n + c.numer() * &dpow;
        }
    }
    if acc.is_zero() {
        0
    } else if acc.is_positive() {
        1
    } else {
        -1
    }
}

fn sign_at_infinity<T: Scalar>(p: &Poly<T>, to_plus: bool) -> i8 {
    let Some(lc) = p.leading_coeff() else {
        return 0;
    };
    let s = if lc.is_zero() {
        0
    } else if lc.is_positive() {
        1
    } else {
        -1
    };
    if !to_plus && p.degree() % 2 == 1 {
        -s
    } else {
        s
    }
}

fn f64_sign_at_infinity(p: &Poly<f64>, to_plus: bool) -> i8 {
    sign_at_infinity(p, to_plus)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn q(n: i64) -> Rat {
        Rat::from_integer(n.into())
    }
    fn qq(n: i64, d: i64) -> Rat {
        Rat::new(n.into(), d.into())
    }

    #[test]
    fn exact_counts_with_endpoint_and_multiple_roots() {
        // (x + 2)³ (x − 1/2) (x − 3)²
        let p = QPoly::from_roots(&[q(-2), q(-2), q(-2), qq(1, 2), q(3), q(3)]);
        let s = p.sturm().unwrap();
        assert!(s.had_multiple_roots(), "gcd is (x+2)²(x−3)");
        assert_eq!(s.count_real_roots(), 3, "three distinct roots");
        assert_eq!(s.count_roots(&q(-10), &q(10)), 3, "all");
        assert_eq!(s.count_roots(&q(-2), &q(3)), 2, "(−2, 3]: 1/2 and 3");
        assert_eq!(
            s.count_roots(&q(-3), &q(-2)),
            1,
            "(−3, −2]: the triple root"
        );
        assert_eq!(s.count_roots(&qq(1, 2), &qq(1, 2)), 0, "empty interval");
        assert_eq!(s.count_roots(&q(3), &q(-3)), 0, "reversed interval");
        assert_eq!(s.count_roots(&qq(1, 2), &q(3)), 1, "(1/2, 3]");
        assert_eq!(
            s.sign_of_square_free_at(&q(3)),
            0,
            "square-free part vanishes at 3"
        );
    }

    #[test]
    fn constants_have_no_roots_and_zero_is_refused() {
        let s = QPoly::constant(q(-4)).sturm().unwrap();
        assert_eq!(s.count_roots(&q(-1), &q(1)), 0, "constant");
        assert_eq!(
            QPoly::zero().sturm(),
            Err(RootError::ZeroPolynomial),
            "zero polynomial"
        );
        assert_eq!(
            Poly::new(vec![f64::NAN, 1.0]).sturm(),
            Err(RootError::NonFiniteCoefficient { index: 0 }),
            "NaN coefficient"
        );
    }

    /// Issue 11, "heuristic methods never lie silently": the checked count refuses a member
    /// sign within its rounding bound when the sign decides `σ`. Hand-made sequences: `V₁ =
    /// x − 1` is 0 at 1 with a non-zero bound; with `V₀ = 1 + x` and `V₂ = 1` (both positive
    /// there) its sign decides between 0 and 2 changes, with `V₂ = −1` it cannot matter.
    #[test]
    fn checked_count_refuses_a_sign_below_its_rounding_bound_that_decides() {
        let seq = |last: f64| SturmSequence {
            polys: vec![
                Poly::new(vec![1.0, 1.0]),
                Poly::new(vec![-1.0, 1.0]),
                Poly::new(vec![last]),
            ],
            multiple_roots: false,
            errs: vec![vec![0.0; 2], vec![0.0; 2], vec![0.0]],
            lossy: false,
        };
        let same = seq(1.0);
        assert_eq!(
            same.count_roots_checked(0.0, 1.0),
            None,
            "V₁(1) decides σ(1)"
        );
        assert_eq!(
            same.count_roots_checked(-0.5, 0.5),
            Some(0),
            "certain at ±0.5"
        );
        let opposite = seq(-1.0);
        assert_eq!(
            opposite.count_roots_checked(0.0, 1.0),
            Some(opposite.count_roots(0.0, 1.0)),
            "a lone uncertain sign between + and − cannot change σ"
        );
    }

    #[test]
    fn f64_sequence_counts_well_separated_roots() {
        let p = Poly::<f64>::from_roots(&[-3.0, -0.5, 0.25, 2.0, 7.0]);
        let s = p.sturm().unwrap();
        assert_eq!(
            s.count_roots(f64::NEG_INFINITY, f64::INFINITY),
            5,
            "all five"
        );
        assert_eq!(s.count_roots(-1.0, 2.5), 3, "(−1, 2.5]: −0.5, 0.25 and 2");
        assert_eq!(s.count_roots(0.0, 1.0), 1, "0.25");
        assert_eq!(s.count_roots(1.0, f64::NAN), 0, "NaN bound");
    }
}

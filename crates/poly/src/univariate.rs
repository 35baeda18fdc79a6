//! [`Poly`]: dense univariate polynomials, coefficients stored low → high.

use num_traits::{One, Signed, Zero};

use crate::scalar::{Rat, Scalar};

/// A dense univariate polynomial `c0 + c1·x + … + cn·x^n`.
///
/// Index `i` of [`coeffs`](Poly::coeffs) holds the coefficient of `x^i` (lowest degree first;
/// papers that list the highest term first are converted where they are read). The invariant,
/// kept by every constructor and operation, is that the last stored coefficient is not exactly
/// zero, so the zero polynomial stores no coefficients at all.
///
/// # Examples
/// ```
/// use poly::Poly;
/// // x^2 - 2, lowest coefficient first.
/// let p = Poly::new(vec![-2.0, 0.0, 1.0]);
/// assert_eq!(p.degree(), 2);
/// assert_eq!(p.eval(&3.0), 7.0);
/// ```
#[derive(Clone, Debug, PartialEq, Eq, Hash)]
pub struct Poly<T> {
    coeffs: Vec<T>,
}

/// Polynomials with exact rational coefficients.
pub type QPoly = Poly<Rat>;

impl<T> Poly<T> {
    /// The coefficients, lowest degree first; empty for the zero polynomial.
    pub fn coeffs(&self) -> &[T] {
        &self.coeffs
    }

    /// The coefficient vector, lowest degree first.
    pub fn into_coeffs(self) -> Vec<T> {
        self.coeffs
    }

    /// The degree. Constants and the zero polynomial both have degree 0: use
    /// [`is_zero`](Poly::is_zero) to tell them apart.
    pub fn degree(&self) -> usize {
        self.coeffs.len().saturating_sub(1)
    }

    /// True for the zero polynomial.
    pub fn is_zero(&self) -> bool {
        self.coeffs.is_empty()
    }

    /// The coefficient of the highest power, `None` for the zero polynomial.
    pub fn leading_coeff(&self) -> Option<&T> {
        self.coeffs.last()
    }
}

impl<T: Scalar> Poly<T> {
    /// Builds `c0 + c1·x + … + cn·x^n` from `coeffs = [c0, c1, …, cn]` (lowest degree first),
    /// trimming trailing coefficients that are exactly zero.
    ///
    /// No coefficient is rejected here (an `f64` polynomial may hold NaN); the solvers check
    /// finiteness and report it (see [`Poly::<f64>::is_finite`]).
    pub fn new(mut coeffs: Vec<T>) -> Self {
        while coeffs.last().is_some_and(Zero::is_zero) {
            coeffs.pop();
        }
        Poly { coeffs }
    }

    /// Builds a polynomial from coefficients that should already satisfy the invariant (no
    /// trailing zero coefficient), for callers that know they do.
    ///
    /// It trims trailing zeros all the same, as [`Poly::new`] does: when the promise holds
    /// that is one comparison, and a broken promise used to leave a zero leading coefficient
    /// that made later checked calls (root queries, exact Sturm sequences, `make_monic`)
    /// divide by zero inside `num-rational` (issue 13).
    pub fn new_raw(coeffs: Vec<T>) -> Self {
        Self::new(coeffs)
    }

    /// The zero polynomial.
    pub fn zero() -> Self {
        Poly { coeffs: Vec::new() }
    }

    /// The constant `c`.
    pub fn constant(c: T) -> Self {
        Self::new(vec![c])
    }

    /// The monomial `c·x^k`.
    pub fn monomial(c: T, k: usize) -> Self {
        let mut coeffs = vec![T::zero(); k + 1];
        coeffs[k] = c;
        Self::new(coeffs)
    }

    /// The polynomial `∏ (x − rᵢ)` with the given roots (repeated roots give multiplicities).
    pub fn from_roots(roots: &[T]) -> Self {
        let mut p = Self::constant(T::one());
        for r in roots {
            p = &p * &Self::new(vec![-r.clone(), T::one()]);
        }
        p
    }

    /// The coefficient of `x^i` (zero beyond the degree).
    pub fn coeff(&self, i: usize) -> T {
        self.coeffs.get(i).cloned().unwrap_or_else(T::zero)
    }

    /// The largest coefficient magnitude (zero for the zero polynomial).
    pub fn max_abs_coeff(&self) -> T {
        self.coeffs.iter().fold(T::zero(), |m, c| {
            let a = c.abs();
            if a > m { a } else { m }
        })
    }

    /// `p(x)` by Horner's rule.
    ///
    /// # Accuracy
    /// Exact for [`Rat`]. For `f64` the usual Horner bound holds,
    /// `|computed − p(x)| ≤ γ(2n)·Σ|cᵢ||x|^i` with `γ(k) = kε/(1−kε)`; use
    /// [`Poly::<f64>::eval_with_error`] to get that bound alongside the value.
    pub fn eval(&self, x: &T) -> T {
        horner(&self.coeffs, x)
    }

    /// The derivative `p'`.
    pub fn derivative(&self) -> Self {
        if self.coeffs.len() <= 1 {
            return Self::zero();
        }
        let coeffs = self
            .coeffs
            .iter()
            .enumerate()
            .skip(1)
            .map(|(i, c)| c.clone() * T::from_usize(i).expect("small integers are representable"))
            .collect();
        Self::new(coeffs)
    }

    /// `c·p`.
    pub fn scale(&self, c: &T) -> Self {
        Self::new(self.coeffs.iter().map(|a| a.clone() * c).collect())
    }

    /// `p / lc(p)`, so the leading coefficient is one; the zero polynomial stays zero.
    pub fn make_monic(&self) -> Self {
        match self.leading_coeff() {
            None => Self::zero(),
            Some(lc) => {
                let lc = lc.clone();
                let mut coeffs: Vec<T> = self.coeffs.iter().map(|a| a.clone() / &lc).collect();
                // The leading term is exactly one, whatever rounding did.
                if let Some(last) = coeffs.last_mut() {
                    *last = T::one();
                }
                Self::new_raw(coeffs)
            }
        }
    }

    /// Drops trailing coefficients that are negligible relative to the largest coefficient
    /// (see [`Scalar::is_negligible`]). Exact types only drop exact zeros, which the invariant
    /// already excludes, so this is the identity over [`Rat`].
    pub fn trim_negligible(mut self) -> Self {
        let scale = self.max_abs_coeff();
        while self.coeffs.last().is_some_and(|c| c.is_negligible(&scale)) {
            self.coeffs.pop();
        }
        self
    }

    /// Division with remainder over a field: `(q, r)` with `self = q·d + r` and
    /// `deg r < deg d` (or `r = 0`). `None` when `d` is the zero polynomial.
    ///
    /// # Exactness
    /// Exact over [`Rat`]. Over `f64` every step rounds; the remainder's leading terms that are
    /// negligible relative to the dividend's size are dropped so the degree falls as it should.
    pub fn div_rem(&self, d: &Self) -> Option<(Self, Self)> {
        let lc = d.leading_coeff()?.clone();
        let dn = d.degree();
        if self.is_zero() || self.degree() < dn {
            return Some((Self::zero(), self.clone()));
        }
        let scale = self.max_abs_coeff();
        let mut r = self.coeffs.clone();
        let mut q = vec![T::zero(); self.degree() - dn + 1];
        for k in (0..q.len()).rev() {
            let c = r[k + dn].clone() / &lc;
            for (j, dj) in d.coeffs.iter().enumerate() {
                let t = c.clone() * dj;
                r[k + j] = r[k + j].clone() - t;
            }
            // The cancelled term is zero by construction, not by rounding luck.
            r[k + dn] = T::zero();
            q[k] = c;
        }
        r.truncate(dn);
        let r = Self::new(r);
        let r = if T::EXACT {
            r
        } else {
            trim_relative(r, &scale)
        };
        Some((Self::new(q), r))
    }

    /// Pseudo-remainder `prem(self, d)`: the remainder of `lc(d)^(deg self − deg d + 1)·self`
    /// divided by `d`, computed without division. `None` when `d` is zero.
    pub fn pseudo_rem(&self, d: &Self) -> Option<Self> {
        let lc = d.leading_coeff()?.clone();
        let dn = d.degree();
        if self.is_zero() || self.degree() < dn {
            return Some(self.clone());
        }
        let mut r = self.coeffs.clone();
        let steps = self.degree() - dn + 1;
        let mut top = self.degree();
        for _ in 0..steps {
            let c = r[top].clone();
            for x in r.iter_mut().take(top + 1) {
                *x = x.clone() * &lc;
            }
            for (j, dj) in d.coeffs.iter().enumerate() {
                let idx = top - dn + j;
                r[idx] = r[idx].clone() - c.clone() * dj;
            }
            r[top] = T::zero();
            if top == 0 {
                break;
            }
            top -= 1;
        }
        r.truncate(dn);
        Some(Self::new(r))
    }

    /// The monic greatest common divisor (Euclid's algorithm); `gcd(0, 0) = 0`.
    ///
    /// # Exactness
    /// Exact over [`Rat`]. Over `f64` this is a heuristic: remainders whose coefficients are
    /// negligible relative to the operands are taken as zero, so nearly-common roots may be
    /// merged. Certified answers use the `Rat` version.
    pub fn gcd(&self, other: &Self) -> Self {
        let (mut a, mut b) = (self.clone(), other.clone());
        while !b.is_zero() {
            let (_, r) = a.div_rem(&b).expect("b is not zero inside the loop");
            let r = if T::EXACT {
                r
            } else {
                // Normalise to keep f64 remainders from drifting towards under/overflow.
                r.make_monic()
            };
            a = b;
            b = r;
        }
        a.make_monic()
    }

    /// The square-free part `p / gcd(p, p')`: same distinct roots, each simple. Monic unless
    /// `p` is zero.
    pub fn square_free(&self) -> Self {
        if self.degree() == 0 {
            return self.make_monic();
        }
        let g = self.gcd(&self.derivative());
        let (q, _) = self
            .div_rem(&g)
            .expect("the gcd of a non-zero polynomial is non-zero");
        q.make_monic()
    }

    /// Composition with an affine map, `x ↦ p(a + b·x)` (a Taylor shift by `a` followed by a
    /// scaling by `b`). Restricting a surface to a ray and moving an interval to `[0, 1]` are
    /// both this operation.
    ///
    /// # Complexity
    /// O(n²) scalar operations (Horner's rule on polynomials).
    pub fn compose_affine(&self, a: &T, b: &T) -> Self {
        let n = self.coeffs.len();
        let mut out = vec![T::zero(); n];
        // Horner: out ← out·(a + b·x) + c_k, from the top coefficient down.
        for (k, c) in self.coeffs.iter().enumerate().rev() {
            let len = n - k; // out currently has degree n - k - 2 at most
            for i in (0..len).rev() {
                let shifted = if i > 0 {
                    out[i - 1].clone() * b
                } else {
                    T::zero()
                };
                out[i] = out[i].clone() * a + shifted;
            }
            out[0] = out[0].clone() + c;
        }
        Self::new(out)
    }

    /// Number of sign changes in the coefficient sequence, zeros skipped (Descartes' rule of
    /// signs: the number of positive real roots is this count minus an even number).
    pub fn sign_variations(&self) -> usize {
        sign_variations(&self.coeffs)
    }

    /// Cauchy's bound: every complex root `z` has `|z| < 1 + max_{i<n} |cᵢ / cₙ|`.
    /// `None` for constants and the zero polynomial (no roots, or every number a root).
    ///
    /// # Accuracy
    /// Exact over [`Rat`]. Over `f64` the division rounds; use
    /// [`Poly::<f64>::root_bound`] for a bound rounded outwards.
    pub fn cauchy_bound(&self) -> Option<T> {
        cauchy_bound_of(&self.coeffs)
    }
}

/// [`Poly::cauchy_bound`] of the coefficients `c` (lowest first, no trailing zero), the one
/// implementation behind it and the borrowed smallest-root query's.
pub(crate) fn cauchy_bound_of<T: Scalar>(c: &[T]) -> Option<T> {
    let n = c.len().checked_sub(1).filter(|&n| n > 0)?;
    let lc = c[n].abs();
    let m = c[..n].iter().fold(T::zero(), |m, x| {
        let q = x.abs() / &lc;
        if q > m { q } else { m }
    });
    Some(T::one() + m)
}

/// Horner's rule on coefficients stored lowest power first: the one plain evaluation of the
/// crate (error bounds: `eval_bound.rs`).
#[inline]
pub(crate) fn horner<T: Scalar>(c: &[T], x: &T) -> T {
    c.iter().rev().fold(T::zero(), |acc, ci| acc * x + ci)
}

/// Sign changes in a sequence, zeros skipped.
pub(crate) fn sign_variations<T: Signed>(seq: &[T]) -> usize {
    let mut last: Option<bool> = None;
    let mut count = 0;
    for c in seq {
        if c.is_zero() {
            continue;
        }
        let pos = c.is_positive();
        if last.is_some_and(|l| l != pos) {
            count += 1;
        }
        last = Some(pos);
    }
    count
}

/// Drops trailing coefficients negligible relative to `scale` (f64 remainders).
fn trim_relative<T: Scalar>(mut p: Poly<T>, scale: &T) -> Poly<T> {
    while p.coeffs.last().is_some_and(|c| c.is_negligible(scale)) {
        p.coeffs.pop();
    }
    p
}

/// The unit roundoff `u = ε/2 = 2^-53` of `f64` round-to-nearest: one correctly rounded
/// operation has relative error at most `u` (Higham, *Accuracy and Stability of Numerical
/// Algorithms*, §2.2). The one home of this constant for every crate of the workspace.
pub const UNIT_ROUNDOFF: f64 = f64::EPSILON / 2.0;

/// `η = 2^-1074`, the smallest positive subnormal `f64`: the largest absolute error of one
/// rounding that underflows (Higham §2.1), the absolute term of every error bound here.
pub(crate) const ETA: f64 = f64::from_bits(1);

/// The unit-roundoff multiple `γ(k) = k·u / (1 − k·u)`, `u` = [`UNIT_ROUNDOFF`] (Higham,
/// *Accuracy and Stability of Numerical Algorithms*, §3.1): the relative error bound of `k`
/// chained floating-point operations.
pub fn gamma(k: usize) -> f64 {
    let ku = k as f64 * UNIT_ROUNDOFF;
    ku / (1.0 - ku)
}

/// Relative widening of [`Poly::root_bound`]'s Cauchy and Fujiwara bounds: `16u = 8ε`
/// covers the division, the `k`-th root (`powf`, or up to three `sqrt`/`cbrt`, each within
/// one ulp) and the products of each term several times over; a bound a few ulps too loose
/// costs nothing.
pub const ROOT_BOUND_MARGIN: f64 = 1.0 + 16.0 * UNIT_ROUNDOFF;

/// Absolute allowance added to Fujiwara's bound in [`Poly::root_bound`]: 4 × 2^-1074, the
/// error of the few roundings that may land in the subnormal range (each at most 2^-1075),
/// where a relative margin means nothing. Roots below it are not representable anyway.
pub const ROOT_BOUND_UNDERFLOW_PAD: f64 = 4.0 * ETA;

/// A value computed in `f64` together with a bound on its absolute error.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Bounded {
    /// The computed value.
    pub value: f64,
    /// An upper bound on `|value − exact|`.
    pub err: f64,
}

impl Bounded {
    /// The sign of the exact value when the bound proves it: `Some(1)`, `Some(-1)`, or `None`
    /// when `|value| ≤ err` (the exact value may be zero or of either sign). NaN gives `None`.
    pub fn certain_sign(&self) -> Option<i8> {
        if self.value > self.err {
            Some(1)
        } else if -self.value > self.err {
            Some(-1)
        } else {
            None
        }
    }
}

impl Poly<f64> {
    /// True when every coefficient is finite (no NaN or infinity).
    pub fn is_finite(&self) -> bool {
        self.coeffs.iter().all(|c| c.is_finite())
    }

    /// The exact rational polynomial with the same coefficients; `None` if any coefficient is
    /// NaN or infinite.
    pub fn to_rat(&self) -> Option<QPoly> {
        let coeffs = self
            .coeffs
            .iter()
            .map(|&c| Rat::from_f64_exact(c))
            .collect::<Option<Vec<_>>>()?;
        Some(Poly::new_raw(coeffs))
    }

    /// A bound `B` with every real root in `[−B, B]`: the smaller of Cauchy's and Fujiwara's
    /// bounds, rounded outwards. `None` for constants, the zero polynomial, and non-finite
    /// coefficients.
    ///
    /// # Accuracy
    /// Rigorous for the stored coefficients: each quotient and root is inflated by a relative
    /// [`ROOT_BOUND_MARGIN`], well above the few roundings involved, and Fujiwara's bound by
    /// an absolute [`ROOT_BOUND_UNDERFLOW_PAD`]. A quotient `|cᵢ/cₙ|` that underflows (as in
    /// `1e300·x² − 1e-300`, roots `±1e-300`) is not taken as zero: its root is formed as
    /// `|cᵢ|^{1/k} / |cₙ|^{1/k}`, which does not underflow, so the bound never excludes a
    /// root (it was 0 there, and every method answered "no root").
    pub fn root_bound(&self) -> Option<f64> {
        root_bound_of(&self.coeffs)
    }
}

/// [`Poly::root_bound`] of the coefficients `c` (lowest first, no trailing zero), the one
/// implementation behind it and [`PolyRef::root_bound`](crate::PolyRef::root_bound).
pub(crate) fn root_bound_of(c: &[f64]) -> Option<f64> {
    let n = c.len().saturating_sub(1);
    if n == 0 || !c.iter().all(|x| x.is_finite()) {
        return None;
    }
    let lc = c[n].abs();
    let mut cauchy: f64 = 0.0;
    let mut fujiwara: f64 = 0.0;
    for (i, ci) in c[..n].iter().enumerate() {
        let q = ci.abs() / lc;
        cauchy = cauchy.max(q);
        let k = n - i;
        // Fujiwara: 2·max |c_{n−k}/c_n|^{1/k}, with the constant term halved.
        let half = if i == 0 { 0.5 } else { 1.0 };
        let root = if q >= f64::MIN_POSITIVE || *ci == 0.0 {
            kth_root(q * half, k)
        } else {
            // The quotient underflowed: scale before dividing.
            kth_root(ci.abs() * half, k) / kth_root(lc, k)
        };
        fujiwara = fujiwara.max(root);
    }
    let cauchy = (1.0 + cauchy) * ROOT_BOUND_MARGIN;
    let fujiwara = 2.0 * fujiwara * ROOT_BOUND_MARGIN + ROOT_BOUND_UNDERFLOW_PAD;
    let b = cauchy.min(fujiwara);
    b.is_finite().then_some(b)
}

/// `x^{1/k}` for `x ≥ 0`, by `sqrt` and `cbrt` where they serve (`k` = 2, 3, 4, 6, 8; each
/// within an ulp or two, as libm's `powf`, which costs ten times more and does the rest).
fn kth_root(x: f64, k: usize) -> f64 {
    match k {
        1 => x,
        2 => x.sqrt(),
        3 => x.cbrt(),
        4 => x.sqrt().sqrt(),
        6 => x.cbrt().sqrt(),
        8 => x.sqrt().sqrt().sqrt(),
        _ => x.powf(1.0 / k as f64),
    }
}

impl QPoly {
    /// The polynomial with each coefficient rounded to the nearest `f64`.
    pub fn to_f64(&self) -> Poly<f64> {
        Poly::new(self.coeffs.iter().map(Scalar::nearest_f64).collect())
    }

    /// Multiplies by the least common multiple of the denominators and divides by the gcd of
    /// the numerators, giving an integer polynomial with the same roots and a positive leading
    /// coefficient (keeps exact remainder sequences from growing needlessly).
    pub fn primitive_integer(&self) -> Self {
        use num_integer::Integer;
        if self.is_zero() {
            return Self::zero();
        }
        let lcm = self
            .coeffs
            .iter()
            .fold(num_bigint::BigInt::one(), |l, c| l.lcm(c.denom()));
        let ints: Vec<num_bigint::BigInt> = self
            .coeffs
            .iter()
            .map(|c| (c * Rat::from_integer(lcm.clone())).to_integer())
            .collect();
        let g = ints
            .iter()
            .fold(num_bigint::BigInt::zero(), |g, c| g.gcd(c));
        let sign = if ints.last().is_some_and(Signed::is_negative) {
            -num_bigint::BigInt::one()
        } else {
            num_bigint::BigInt::one()
        };
        let g = g * sign;
        Poly::new_raw(
            ints.into_iter()
                .map(|c| Rat::from_integer(c / &g))
                .collect(),
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn q(n: i64) -> Rat {
        Rat::from_integer(n.into())
    }
    fn qp(c: &[i64]) -> QPoly {
        Poly::new(c.iter().map(|&n| q(n)).collect())
    }

    #[test]
    fn new_trims_trailing_zeros_only() {
        let p = Poly::new(vec![0.0, 1.0, 0.0, 0.0]);
        assert_eq!(
            p.coeffs(),
            &[0.0, 1.0],
            "trailing zeros trimmed, leading kept"
        );
        assert!(
            Poly::<f64>::new(vec![0.0, -0.0]).is_zero(),
            "all-zero is the zero poly"
        );
        assert_eq!(
            Poly::<f64>::zero().degree(),
            0,
            "zero has degree 0 by convention"
        );
    }

    #[test]
    fn arithmetic_identities_hold_exactly() {
        let a = qp(&[1, -3, 0, 2]);
        let b = qp(&[-1, 1]);
        let (quo, rem) = a.div_rem(&b).unwrap();
        assert_eq!(&(&quo * &b) + &rem, a, "a = q·b + r");
        assert_eq!(rem, qp(&[0]), "x = 1 is a root of 2x³ − 3x + 1");
        assert_eq!(quo, qp(&[-1, 2, 2]), "2x³ − 3x + 1 = (x−1)(2x² + 2x − 1)");
        assert!(
            a.div_rem(&QPoly::zero()).is_none(),
            "division by zero is refused"
        );
    }

    #[test]
    fn pseudo_remainder_matches_scaled_remainder() {
        let a = qp(&[3, 1, 4, 1, 5]);
        let b = qp(&[2, 7, 3]);
        let prem = a.pseudo_rem(&b).unwrap();
        let lc_pow = q(3).pow(3);
        let (_, r) = a.scale(&lc_pow).div_rem(&b).unwrap();
        assert_eq!(prem, r, "prem = rem(lc^(m-n+1)·a, b)");
    }

    #[test]
    fn gcd_and_square_free_recover_multiplicities() {
        // (x−1)²(x+2)³(x−5)
        let p = QPoly::from_roots(&[q(1), q(1), q(-2), q(-2), q(-2), q(5)]);
        assert_eq!(
            p.square_free(),
            QPoly::from_roots(&[q(1), q(-2), q(5)]),
            "square-free part"
        );
        let g = p.gcd(&p.derivative());
        assert_eq!(g, QPoly::from_roots(&[q(1), q(-2), q(-2)]), "gcd(p, p')");
        let f = Poly::<f64>::from_roots(&[1.0, 1.0, 3.0]);
        let sf = f.square_free();
        assert_eq!(
            sf.degree(),
            2,
            "f64 square-free part of (x−1)²(x−3): {sf:?}"
        );
    }

    #[test]
    fn compose_affine_is_substitution() {
        let p = qp(&[5, -1, 2, 1]); // x³ + 2x² − x + 5
        let (a, b) = (q(3), Rat::new(1.into(), 2.into()));
        let c = p.compose_affine(&a, &b);
        for x in [-3, 0, 1, 7] {
            let x = q(x);
            assert_eq!(
                c.eval(&x),
                p.eval(&(a.clone() + b.clone() * x.clone())),
                "at {x}"
            );
        }
        assert_eq!(c.degree(), 3, "degree preserved when b ≠ 0");
        assert_eq!(
            p.compose_affine(&q(2), &q(0)),
            qp(&[19]),
            "b = 0 gives the constant p(a)"
        );
    }

    #[test]
    fn derivative_and_sign_variations() {
        let p = qp(&[1, -3, 0, 2]);
        assert_eq!(p.derivative(), qp(&[-3, 0, 6]), "d/dx (2x³ − 3x + 1)");
        assert_eq!(p.sign_variations(), 2, "+1, −3, +2: two variations");
        assert_eq!(qp(&[1, 0, 0, 1]).sign_variations(), 0, "zeros are skipped");
    }

    #[test]
    fn eval_error_bound_contains_exact_value() {
        // Wilkinson-like cancellation near the roots of (x − 1)^8 expanded.
        let p = Poly::<f64>::from_roots(&[1.0; 8]);
        let exact = p.to_rat().unwrap();
        for &x in &[0.99, 1.0, 1.001, 1.01, 1.5] {
            let b = p.eval_with_error(x);
            let truth = exact.eval(&Rat::from_f64_exact(x).unwrap()).nearest_f64();
            assert!(
                (b.value - truth).abs() <= b.err,
                "x = {x}: value {} truth {truth} err {}",
                b.value,
                b.err
            );
        }
        // Far from the root the sign is certain; at the root it cannot be.
        assert_eq!(
            p.eval_with_error(1.5).certain_sign(),
            Some(1),
            "(0.5)^8 > 0"
        );
        assert_eq!(
            p.eval_with_error(1.0001).certain_sign(),
            None,
            "lost in round-off"
        );
    }

    #[test]
    fn root_bound_contains_roots() {
        let p = Poly::<f64>::from_roots(&[-7.0, 0.5, 3.0, 1e3]);
        let b = p.root_bound().unwrap();
        assert!(b >= 1e3, "bound {b} must contain 1000");
        assert!(b <= 4e3, "Fujiwara keeps the bound within 4× here: {b}");
        assert!(
            Poly::new(vec![2.0]).root_bound().is_none(),
            "constants have no roots"
        );
        assert!(
            Poly::new(vec![f64::NAN, 1.0]).root_bound().is_none(),
            "NaN refused"
        );
        let c = qp(&[-6, 1, 1]).cauchy_bound().unwrap();
        assert_eq!(c, q(7), "Cauchy bound of x² + x − 6 is 1 + 6");
    }

    #[test]
    fn primitive_integer_clears_denominators() {
        let p = Poly::new(vec![
            Rat::new(1.into(), 2.into()),
            Rat::new((-3).into(), 4.into()),
        ]);
        assert_eq!(
            p.primitive_integer(),
            qp(&[-2, 3]),
            "(1/2 − 3/4 x) ~ 3x − 2"
        );
    }
}

//! [`IntPoly`]: integer polynomials, the working form of exact Sturm sequences.
//!
//! Every exact root computation in this crate multiplies a rational polynomial by a *positive*
//! constant to clear denominators and removes the *positive* content. Positive scalings keep
//! the sign of the polynomial at every point, which is all a Sturm sequence needs, and integer
//! coefficients make evaluation at a rational point a gcd-free integer computation.

use num_bigint::{BigInt, Sign};
use num_integer::Integer;
use num_traits::{One, Signed, Zero};

use crate::scalar::Rat;
use crate::univariate::QPoly;

/// A polynomial with integer coefficients, lowest degree first, no trailing zero.
#[derive(Clone, Debug, PartialEq, Eq)]
pub(crate) struct IntPoly {
    c: Vec<BigInt>,
}

impl IntPoly {
    fn trimmed(mut c: Vec<BigInt>) -> Self {
        while c.last().is_some_and(Zero::is_zero) {
            c.pop();
        }
        IntPoly { c }
    }

    /// `k·p` for the positive rational `k` that makes the coefficients coprime integers.
    /// Same sign as `p` everywhere.
    pub(crate) fn from_qpoly(p: &QPoly) -> Self {
        let lcm = p
            .coeffs()
            .iter()
            .fold(BigInt::one(), |l, c| l.lcm(c.denom()));
        let ints = p
            .coeffs()
            .iter()
            .map(|c| c.numer() * (&lcm / c.denom()))
            .collect();
        IntPoly::trimmed(ints).primitive()
    }

    /// Divides by the positive gcd of the coefficients.
    ///
    /// The gcd is accumulated from the smallest coefficient up, and each larger one is first
    /// reduced modulo the running gcd (`gcd(g, c) = gcd(g, c mod g)`): one division instead of
    /// a binary gcd over all of `c`'s bits, which dominated exact Sturm construction. Stops
    /// as soon as the gcd is 1.
    fn primitive(mut self) -> Self {
        let mut order: Vec<&BigInt> = self.c.iter().filter(|c| !c.is_zero()).collect();
        order.sort_by_key(|c| c.bits());
        let mut g = BigInt::zero();
        for c in order {
            g = if g.is_zero() {
                c.abs()
            } else {
                g.gcd(&(c % &g))
            };
            if g.is_one() {
                break;
            }
        }
        if !g.is_zero() && !g.is_one() {
            for x in &mut self.c {
                *x /= &g;
            }
        }
        self
    }

    pub(crate) fn is_zero(&self) -> bool {
        self.c.is_empty()
    }

    pub(crate) fn degree(&self) -> usize {
        self.c.len().saturating_sub(1)
    }

    /// The coefficients, lowest degree first, no trailing zero.
    pub(crate) fn coeffs(&self) -> &[BigInt] {
        &self.c
    }

    /// True when `gcd(p, p')` is certainly constant, i.e. `p` has no repeated complex root:
    /// for one of [`SQUARE_FREE_PRIMES`] that does not divide `lc(p)`, the images of `p` and
    /// `p'` modulo that prime are coprime. Exact: a common factor `h` of `p` and `p'` over
    /// the integers (primitive, by Gauss's lemma) has `lc(h) | lc(p)`, so its image keeps its
    /// degree and divides both images. False means "not certified" (almost always a repeated
    /// factor), never "not square-free" for sure. Constants and the zero polynomial give
    /// false.
    pub(crate) fn is_certainly_square_free(&self) -> bool {
        if self.degree() == 0 {
            return false;
        }
        SQUARE_FREE_PRIMES.iter().any(|&q| {
            let image: Vec<u64> = self.c.iter().map(|x| residue(x, q)).collect();
            if image.last() == Some(&0) {
                return false;
            }
            let derivative: Vec<u64> = image
                .iter()
                .enumerate()
                .skip(1)
                .map(|(i, &x)| x * (i as u64 % q) % q)
                .collect();
            gcd_degree_mod(image, derivative, q) == Some(0)
        })
    }

    pub(crate) fn to_qpoly(&self) -> QPoly {
        QPoly::new_raw(self.c.iter().cloned().map(Rat::from_integer).collect())
    }

    /// `p'` with its positive content removed.
    pub(crate) fn derivative(&self) -> Self {
        let c = self
            .c
            .iter()
            .enumerate()
            .skip(1)
            .map(|(i, x)| x * BigInt::from(i))
            .collect();
        IntPoly::trimmed(c).primitive()
    }

    /// `±prem(self, d)`, the sign chosen to make it a positive multiple of `−rem(self, d)`:
    /// the next member of a Sturm sequence (seed eq. 3.20, `V_k = Q_{k−1}·V_{k−1} − V_{k−2}`
    /// up to a positive factor), not reduced (the caller divides by the subresultant
    /// factor). `d` must be non-zero.
    ///
    /// The pseudo-remainder `r = lc(d)^(m−n+1)·self mod d` differs from the true remainder by
    /// the factor `lc(d)^(m−n+1)`, whose sign is corrected so the result keeps the sign of
    /// `−rem`.
    pub(crate) fn neg_prem(&self, d: &IntPoly) -> Self {
        let n = d.degree();
        let lc = d.c.last().expect("divisor is non-zero");
        if self.is_zero() || self.degree() < n {
            return IntPoly::trimmed(self.c.iter().map(|x| -x).collect());
        }
        let mut r = self.c.clone();
        let steps = self.degree() - n + 1;
        for k in (n..=self.degree()).rev() {
            let top = r[k].clone();
            if top.is_zero() {
                for x in r.iter_mut().take(k) {
                    *x *= lc;
                }
                continue;
            }
            for x in r.iter_mut().take(k) {
                *x *= lc;
            }
            for (j, dj) in d.c.iter().enumerate().take(n) {
                r[k - n + j] -= &top * dj;
            }
            r[k] = BigInt::zero();
        }
        r.truncate(n);
        // r = lc^steps · rem; we want a positive multiple of −rem.
        let flip = lc.is_negative() && steps % 2 == 1;
        let r = if flip {
            r
        } else {
            r.into_iter().map(|x| -x).collect()
        };
        IntPoly::trimmed(r)
    }

    /// Divides every coefficient by the positive `b`, which must divide each exactly.
    pub(crate) fn div_scalar_exact(mut self, b: &BigInt) -> Self {
        debug_assert!(b.is_positive(), "a positive divisor keeps the signs");
        if !b.is_one() {
            for x in &mut self.c {
                debug_assert!((&*x % b).is_zero(), "{b} divides every coefficient");
                *x /= b;
            }
        }
        self
    }

    /// `|lc|`, the magnitude of the leading coefficient (0 for the zero polynomial).
    pub(crate) fn lc_abs(&self) -> BigInt {
        self.c.last().map_or_else(BigInt::zero, Signed::abs)
    }

    /// Exact quotient by `g`, assumed to divide `self`, rescaled by a positive constant to
    /// coprime integers (`g` need not be monic).
    ///
    /// Pseudo-division in integers: `lc(g)^(m−n+1)·self = Q·g` with an integer `Q` and, since
    /// `g` divides `self`, no remainder; `Q` is negated when that factor is negative, then made
    /// primitive. (The first version divided as rationals, which spent most of an exact
    /// fallback on gcds of fractions.)
    pub(crate) fn div_exact(&self, g: &IntPoly) -> Self {
        let n = g.degree();
        let lc = g.c.last().expect("divisor is non-zero");
        if self.is_zero() || self.degree() < n {
            return IntPoly { c: Vec::new() };
        }
        let m = self.degree();
        let mut r = self.c.clone();
        let mut q = vec![BigInt::zero(); m - n + 1];
        for k in (n..=m).rev() {
            let top = std::mem::take(&mut r[k]);
            for x in q.iter_mut().skip(k - n + 1) {
                *x *= lc;
            }
            for x in r.iter_mut().take(k) {
                *x *= lc;
            }
            if !top.is_zero() {
                for (j, gj) in g.c.iter().enumerate().take(n) {
                    r[k - n + j] -= &top * gj;
                }
            }
            q[k - n] = top;
        }
        debug_assert!(r.iter().all(Zero::is_zero), "g divides self");
        let negative = lc.is_negative() && (m - n + 1) % 2 == 1;
        if negative {
            for x in &mut q {
                *x = -std::mem::take(x);
            }
        }
        IntPoly::trimmed(q).primitive()
    }

    /// Whether `(x − r)^m` divides `self` exactly (`r` a root of multiplicity at least `m`;
    /// `m = 0` is always true). `m` divisions by the primitive linear factor `d·x − n`
    /// (`r = n/d` in lowest terms, `d > 0`), each required to leave no remainder: by Gauss's
    /// lemma a primitive integer divisor leaves an integer quotient, so every step stays in
    /// integers (`d·q_{k−1} = a_k + n·q_k`, exact division or not a divisor). Cost: `m`
    /// passes of `deg` integer products and divisions.
    pub(crate) fn has_root_of_multiplicity(&self, r: &Rat, m: usize) -> bool {
        let (n, d) = (r.numer(), r.denom());
        let mut a = self.c.clone();
        for _ in 0..m {
            let Some(top) = a.len().checked_sub(1).filter(|&t| t > 0) else {
                // A non-zero constant has no root; the zero polynomial is trimmed to `[]`.
                return a.is_empty();
            };
            // q has degree top − 1: q_{k−1} = (a_k + n·q_k)/d from the top, q_top = 0.
            let mut q = vec![BigInt::zero(); top];
            let mut next = BigInt::zero();
            for k in (1..=top).rev() {
                let (quot, rem) = (&a[k] + n * &next).div_rem(d);
                if !rem.is_zero() {
                    return false;
                }
                q[k - 1] = quot.clone();
                next = quot;
            }
            // The constant term: −n·q₀ = a₀.
            if a[0] != -(n * &next) {
                return false;
            }
            a = q;
        }
        true
    }

    /// The exact sign (−1, 0, 1) of `p(x)`.
    ///
    /// With `x = n/d`, `d > 0`, this is the sign of `d^deg·p(x) = Σ cᵢ nⁱ d^(deg−i)`, computed
    /// by a homogeneous Horner scheme in integers (no gcds).
    pub(crate) fn sign_at(&self, x: &Rat) -> i8 {
        let Some(top) = self.c.last() else {
            return 0;
        };
        let (n, d) = (x.numer(), x.denom());
        let mut acc = top.clone();
        // Points from f64 numbers have a power-of-two denominator 2^k: then d^j is a shift.
        if let Some(k) = d.trailing_zeros().filter(|&k| d.bits() == k + 1) {
            let mut shift = 0u64;
            for c in self.c.iter().rev().skip(1) {
                shift += k;
                acc = acc * n + (c << shift);
            }
        } else {
            let mut dpow = BigInt::one();
            for c in self.c.iter().rev().skip(1) {
                dpow *= d;
                acc = acc * n + c * &dpow;
            }
        }
        sign_of(&acc)
    }
}

/// Primes below `2^31` (products of two residues fit a `u64`) for the modular square-free
/// test; three, so that a prime dividing the leading coefficient or a discriminant by chance
/// leaves two more.
const SQUARE_FREE_PRIMES: [u64; 3] = [2_147_483_647, 2_147_483_629, 2_147_483_587];

/// `x mod q` in `[0, q)`.
fn residue(x: &BigInt, q: u64) -> u64 {
    use num_traits::ToPrimitive;
    x.mod_floor(&BigInt::from(q))
        .to_u64()
        .expect("a residue is below q")
}

/// `b^e mod q`.
fn pow_mod(mut b: u64, mut e: u64, q: u64) -> u64 {
    let mut r = 1;
    while e > 0 {
        if e & 1 == 1 {
            r = r * b % q;
        }
        b = b * b % q;
        e >>= 1;
    }
    r
}

/// The degree of `gcd(a, b)` over the integers modulo the prime `q` (coefficients lowest
/// first, reduced), by Euclid's algorithm; `None` when both are zero.
fn gcd_degree_mod(mut a: Vec<u64>, mut b: Vec<u64>, q: u64) -> Option<usize> {
    let trim = |v: &mut Vec<u64>| {
        while v.last() == Some(&0) {
            v.pop();
        }
    };
    trim(&mut a);
    trim(&mut b);
    // Each pass lowers the degree of b: at most deg(a) + deg(b) + 1 passes.
    while !b.is_empty() {
        let inv = pow_mod(*b.last().expect("non-empty"), q - 2, q);
        while a.len() >= b.len() {
            let f = a.last().expect("non-empty") * inv % q;
            let off = a.len() - b.len();
            for (j, &bj) in b.iter().enumerate() {
                a[off + j] = (a[off + j] + q - f * bj % q) % q;
            }
            trim(&mut a);
        }
        std::mem::swap(&mut a, &mut b);
    }
    a.len().checked_sub(1)
}

fn sign_of(x: &BigInt) -> i8 {
    match x.sign() {
        Sign::Minus => -1,
        Sign::NoSign => 0,
        Sign::Plus => 1,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn ip(c: &[i64]) -> IntPoly {
        IntPoly::trimmed(c.iter().map(|&x| BigInt::from(x)).collect())
    }
    fn q(n: i64, d: i64) -> Rat {
        Rat::new(n.into(), d.into())
    }

    #[test]
    fn root_multiplicity_is_exact() {
        // (2x − 3)³(x + 1) = 8x⁴ − 28x³ + 18x² + 27x − 27.
        let p = ip(&[-27, 27, 18, -28, 8]);
        let r = q(3, 2);
        assert!(p.has_root_of_multiplicity(&r, 3), "3/2 is a triple root");
        assert!(!p.has_root_of_multiplicity(&r, 4), "not a quadruple one");
        assert!(p.has_root_of_multiplicity(&q(-1, 1), 1), "−1 is a root");
        assert!(!p.has_root_of_multiplicity(&q(-1, 1), 2), "a simple one");
        assert!(!p.has_root_of_multiplicity(&q(1, 1), 1), "1 is no root");
        assert!(!p.has_root_of_multiplicity(&q(3, 4), 1), "3/4 is no root");
        // x²(x − 1): 0 is a double root.
        let z = ip(&[0, 0, -1, 1]);
        assert!(z.has_root_of_multiplicity(&q(0, 1), 2), "double root 0");
        assert!(!z.has_root_of_multiplicity(&q(0, 1), 3), "not triple");
    }

    #[test]
    fn sign_at_matches_rational_horner() {
        let p = ip(&[-6, 11, -6, 1]); // (x−1)(x−2)(x−3)
        let qp = p.to_qpoly();
        for (n, d) in [(1, 1), (3, 2), (5, 2), (7, 3), (-1, 5), (4, 1)] {
            let x = q(n, d);
            let v = qp.eval(&x);
            let expect = if v.is_zero() {
                0
            } else if v.is_positive() {
                1
            } else {
                -1
            };
            assert_eq!(p.sign_at(&x), expect, "sign at {x}");
        }
    }

    #[test]
    fn neg_rem_is_a_positive_multiple_of_minus_remainder() {
        // Leading coefficient of the divisor negative, odd number of steps: sign must flip.
        let a = ip(&[1, 0, 3, 2]);
        let d = ip(&[5, 1, -3]);
        let got = a.neg_prem(&d).to_qpoly();
        let (_, r) = a.to_qpoly().div_rem(&d.to_qpoly()).unwrap();
        let minus_r = -r;
        // got = k·(−r) with k > 0: compare after making both monic and checking a sign.
        assert_eq!(got.make_monic(), minus_r.make_monic(), "same line");
        let x = q(7, 3);
        let (sg, sr) = (got.eval(&x), minus_r.eval(&x));
        assert!(
            sg.is_positive() == sr.is_positive(),
            "positive multiple: {sg} vs {sr}"
        );
    }

    #[test]
    fn div_exact_is_a_positive_multiple_of_the_quotient() {
        // g with a negative leading coefficient and an odd number of steps (sign flip), and
        // with a positive one; the quotient has a content to remove.
        for (g, h) in [
            (ip(&[3, -2]), ip(&[-7, 5, 1])),
            (ip(&[3, -2]), ip(&[4, 0, -6, 2])),
            (ip(&[-1, 0, 4]), ip(&[6, -3, 9])),
        ] {
            let a = IntPoly::from_qpoly(&(g.to_qpoly() * h.to_qpoly()));
            let got = a.div_exact(&g).to_qpoly();
            let want = a.to_qpoly().div_rem(&g.to_qpoly()).unwrap().0;
            assert_eq!(
                got.clone().make_monic(),
                want.clone().make_monic(),
                "same line"
            );
            for x in [q(7, 3), q(-5, 2), q(11, 1)] {
                let (sg, sw) = (got.eval(&x), want.eval(&x));
                assert!(
                    sg.is_positive() == sw.is_positive(),
                    "positive multiple at {x}"
                );
            }
            let content = got
                .coeffs()
                .iter()
                .fold(BigInt::zero(), |g, c| g.gcd(c.numer()));
            assert!(content.is_one(), "primitive: {got:?}");
        }
    }

    #[test]
    fn square_free_test_certifies_simple_roots_and_refuses_repeated_ones() {
        let cubic = ip(&[-6, 11, -6, 1]); // (x−1)(x−2)(x−3)
        assert!(cubic.is_certainly_square_free(), "distinct roots");
        let double = ip(&[4, -12, 13, -6, 1]); // (x−1)²(x−2)²
        assert!(!double.is_certainly_square_free(), "repeated real roots");
        let complex = ip(&[1, 0, 2, 0, 1]); // (x² + 1)²
        assert!(
            !complex.is_certainly_square_free(),
            "repeated complex roots"
        );
        // 2147483647·x² − 1: the leading coefficient vanishes modulo the first prime, the
        // others certify it.
        let lead = IntPoly::trimmed(vec![
            BigInt::from(-1),
            BigInt::zero(),
            BigInt::from(2_147_483_647),
        ]);
        assert!(lead.is_certainly_square_free(), "another prime decides");
        assert!(
            !ip(&[5]).is_certainly_square_free(),
            "constants are not certified"
        );
    }

    #[test]
    fn from_qpoly_keeps_signs() {
        let p = QPoly::new(vec![q(-1, 2), q(0, 1), q(-3, 4)]);
        let i = IntPoly::from_qpoly(&p);
        assert_eq!(
            i,
            ip(&[-2, 0, -3]),
            "scaled by +4, not normalised to a positive lead"
        );
    }
}

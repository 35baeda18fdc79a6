//! [`Poly::<Rat>::root_near`]: a real root of an exact polynomial, narrowed to a requested
//! number of bits by bisection on dyadic rationals `m / 2^k` (no `BigRational`
//! normalisation, no Sturm sequence when the bracket has a sign change).
//!
//! Why a caller needs it: a root located in `f64` (say within `x_tol` by
//! [`Poly::real_roots`]) is not precise enough to substitute into an ill-conditioned
//! expression of it, e.g. the shape element `v + h(u)` of a Gröbner basis, whose `|h'|` can be
//! 1e18 at a root (`paper-notes/groebner.md` §5). The exact root is there to be had; this
//! narrows it.

use num_bigint::{BigInt, Sign};
use num_traits::{One, Signed, Zero};

use crate::scalar::{Rat, Scalar};
use crate::univariate::Poly;

impl Poly<Rat> {
    /// A rational within `2^-bits` (absolute) of a real root of `self` lying in the bracket
    /// `[x − radius, x + radius]`; `None` when there is none there (or `x`, `radius` are not
    /// finite, or `self` is constant).
    ///
    /// With a sign change across the bracket, bisection on the sign of `self` itself (exact
    /// Horner on the primitive integer form, one evaluation per bit). Without one (a root of
    /// even multiplicity, or two roots), exact Sturm isolation of the distinct roots in the
    /// bracket; the one nearest `x` is refined.
    ///
    /// # Accuracy
    /// Exact: the returned rational is within `2^-bits` of a true root of the stored
    /// polynomial (when the bracket holds several, the one nearest `x`).
    ///
    /// # Complexity
    /// `bits` exact evaluations, each `O(n)` big-integer operations of `O(n·(bits + k))` bits
    /// (`k` the bits of the bracket's ends).
    ///
    /// # Examples
    /// ```
    /// use poly::{Poly, Rat};
    /// let n = |c: i64| Rat::from_integer(c.into());
    /// let p = Poly::new(vec![n(-2), n(0), n(1)]); // x² − 2
    /// let r = p.root_near(1.4142, 1e-3, 100).ok_or("a root near 1.4142")?;
    /// let err = &r * &r - n(2); // |r − √2| ≤ 2^-100, so |r² − 2| ≤ 2^-98
    /// assert!(err.abs() < Rat::new(1.into(), BigInt::from(1) << 97));
    /// # use num_bigint::BigInt; use num_traits::Signed;
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn root_near(&self, x: f64, radius: f64, bits: u32) -> Option<Rat> {
        if self.degree() == 0 || !x.is_finite() || !radius.is_finite() {
            return None;
        }
        let p = self.primitive_integer();
        let ints: Vec<BigInt> = p.coeffs().iter().map(|c| c.numer().clone()).collect();
        let lo = Dyadic::from_f64(x - radius)?;
        let hi = Dyadic::from_f64(x + radius)?;
        let (s_lo, s_hi) = (lo.sign_of(&ints), hi.sign_of(&ints));
        if s_lo == 0 {
            return Some(lo.to_rat());
        }
        if s_hi == 0 {
            return Some(hi.to_rat());
        }
        if s_lo != s_hi {
            let (mut lo, mut hi) = (lo, hi);
            // Each pass halves the bracket, whose width is a dyadic 2^-k·m: at most
            // bits + log2(width) passes.
            while hi.minus(&lo).exceeds(bits) {
                let mid = lo.midpoint(&hi);
                let s = mid.sign_of(&ints);
                if s == 0 {
                    return Some(mid.to_rat());
                }
                if s == s_lo {
                    lo = mid;
                } else {
                    hi = mid;
                }
            }
            return Some(lo.midpoint(&hi).to_rat());
        }
        let (a, b) = (lo.to_rat(), hi.to_rat());
        let seq = p.sturm().ok()?;
        let xq = Rat::from_f64_exact(x)?;
        let half = |lo: &Rat, hi: &Rat| (lo + hi) / Rat::from_integer(2.into());
        let iv = p
            .isolate_roots(&a, &b)
            .ok()?
            .into_iter()
            .min_by_key(|iv| (half(&iv.lo, &iv.hi) - &xq).abs())?;
        let iv = seq.refine_interval(&iv, bits);
        Some(half(&iv.lo, &iv.hi))
    }
}

/// A dyadic rational `m / 2^k`.
#[derive(Clone, Debug)]
struct Dyadic {
    m: BigInt,
    k: u32,
}

impl Dyadic {
    /// The exact value of a finite `f64` (whose denominator is a power of two).
    fn from_f64(x: f64) -> Option<Self> {
        let r = Rat::from_f64_exact(x)?;
        let k = r.denom().bits().checked_sub(1)?;
        Some(Dyadic {
            m: r.numer().clone(),
            k: u32::try_from(k).ok()?,
        })
    }

    fn to_rat(&self) -> Rat {
        Rat::new(self.m.clone(), BigInt::one() << self.k as usize)
    }

    fn rescaled(&self, k: u32) -> BigInt {
        &self.m << (k - self.k) as usize
    }

    fn midpoint(&self, other: &Dyadic) -> Dyadic {
        let k = self.k.max(other.k) + 1;
        Dyadic {
            m: self.rescaled(k - 1) + other.rescaled(k - 1),
            k,
        }
    }

    fn minus(&self, other: &Dyadic) -> Dyadic {
        let k = self.k.max(other.k);
        Dyadic {
            m: self.rescaled(k) - other.rescaled(k),
            k,
        }
    }

    /// Whether `|self| > 2^-bits`: `|m| · 2^bits > 2^k`.
    fn exceeds(&self, bits: u32) -> bool {
        (self.m.abs() << bits as usize) > (BigInt::one() << self.k as usize)
    }

    /// The sign of `Σ c_i x^i` at `x = m / 2^k`: that of `Σ c_i m^i 2^{k(n−i)}`, by Horner.
    fn sign_of(&self, coeffs: &[BigInt]) -> i8 {
        let mut acc = BigInt::zero();
        let mut scale = BigInt::one(); // 2^{k·j} at the j-th step from the top
        for c in coeffs.iter().rev() {
            acc = acc * &self.m + c * &scale;
            scale <<= self.k as usize;
        }
        match acc.sign() {
            Sign::Minus => -1,
            Sign::NoSign => 0,
            Sign::Plus => 1,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn q(n: i64) -> Rat {
        Rat::from_integer(n.into())
    }

    fn within(r: &Rat, truth: f64, bits: u32) -> bool {
        // |r − truth| ≤ 2^-bits + the rounding of the f64 truth.
        let err = (r - Rat::from_f64_exact(truth).unwrap()).abs();
        err <= Rat::new(1.into(), BigInt::one() << bits as usize)
            + Rat::from_f64_exact(truth.abs() * f64::EPSILON).unwrap()
    }

    #[test]
    fn sign_change_bracket_is_bisected_to_the_requested_bits() {
        // (x − 1/3)(x + 5): the root 1/3 is not dyadic, so bisection must run all the way.
        let p = Poly::new(vec![q(-5), q(14), q(3)]); // 3x² + 14x − 5
        let r = p.root_near(0.3333, 1e-3, 80).unwrap();
        let third = q(1) / q(3);
        assert!(
            (&r - &third).abs() <= Rat::new(1.into(), BigInt::one() << 80),
            "{r} is not within 2^-80 of 1/3"
        );
        assert!(
            (&r - &third).abs() > Rat::new(1.into(), BigInt::one() << 200),
            "and it is a dyadic approximation, not 1/3 itself"
        );
    }

    #[test]
    fn double_root_without_sign_change_uses_sturm() {
        // (x − 0.5)²: no sign change around the root; exact isolation still finds it.
        let p = Poly::new(vec![q(1), q(-4), q(4)]); // 4x² − 4x + 1
        let r = p.root_near(0.4999, 1e-3, 60).unwrap();
        assert!(within(&r, 0.5, 60), "{r}");
    }

    #[test]
    fn no_root_in_the_bracket_and_bad_input_give_none() {
        let p = Poly::new(vec![q(-2), q(0), q(1)]); // x² − 2
        assert_eq!(p.root_near(0.0, 0.5, 40), None, "no root in [−0.5, 0.5]");
        assert_eq!(p.root_near(f64::NAN, 0.5, 40), None, "NaN centre");
        assert_eq!(
            Poly::constant(q(3)).root_near(0.0, 1.0, 40),
            None,
            "constant"
        );
        // An end of the bracket that is a root is returned exactly.
        let r = Poly::new(vec![q(-1), q(1)]).root_near(0.5, 0.5, 40);
        assert_eq!(r, Some(q(1)), "the root x = 1 on the bracket's end");
    }
}

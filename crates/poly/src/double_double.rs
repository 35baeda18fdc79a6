//! Double-double arithmetic (`hi + lo`, 106 bits) by error-free transformations on `f64`,
//! with the proven error bounds of Joldes, Muller & Popescu, "Tight and rigorous error bounds
//! for basic building blocks of double-word arithmetic" (ACM TOMS 44, 2017): the first tier of
//! adaptive precision (`multiprec.rs`, `dd_bernstein.rs`; `paper-notes/isolation.md`).

use crate::univariate::ETA;

/// Unit roundoff of the double-double operations used here, as a bound valid for all of
/// them: `8u²` with `u = 2^-53`. Joldes, Muller & Popescu, "Tight and rigorous error bounds
/// for basic building blocks of double-word arithmetic" (ACM TOMS 44, 2017) prove relative
/// errors `3u²/(1 − 4u)` for the sum of two double-words (their Algorithm 6), `2u²` for a
/// double-word times a double (Algorithm 9) and `5u²` for the product of two double-words
/// (Algorithm 12); `8u²` covers each with room for the `(1 − 4u)` factors.
pub const DD_UNIT: f64 = 8.0 * (0.5 * f64::EPSILON) * (0.5 * f64::EPSILON);

/// Absolute error allowed per double-double operation for underflow: each uses at most four
/// `f64` products or fused multiply–adds, whose error terms are exact only when no underflow
/// occurs; an underflowing rounding errs by at most `2^-1075` absolutely. (Sums of `f64`
/// numbers never err by underflow.) So `4·2^-1075 < 2^-1072`, rounded up to a power of two.
pub(crate) const DD_UNDERFLOW: f64 = 4.0 * ETA;

/// Magnitude from which a double-double product is within [`DD_UNIT`] relatively, without
/// underflow: `2^-900`, so that even its error term `2^-106` below stays a normal number
/// (`≥ 2^-1022`).
pub(crate) const DD_MIN_EXACT: f64 = f64::from_bits((1023 - 900) << 52);

/// `γ(k) = k·u/(1 − k·u)` for unit roundoff `u`, rounded up; infinite when `k·u ≥ 1/2`.
pub(crate) fn gamma_u(k: usize, u: f64) -> f64 {
    let ku = k as f64 * u;
    if ku >= 0.5 {
        f64::INFINITY
    } else {
        ku / (1.0 - ku) * (1.0 + 4.0 * f64::EPSILON)
    }
}

/// `v[j]` ← the coefficients of `p(e + u)` for the stored `c` (lowest first; `v.len() =
/// c.len()`), by Horner's rule on polynomials in double-double: `2n` operations on any path
/// from an input to an output, so each is within `γ_dd(2n)·Aⱼ` of the exact value, `Aⱼ` the
/// same shift of `|c|` by `|e|` (every operation within [`DD_UNIT`] relatively; underflow
/// aside). Shared by `dd_bernstein.rs` and `shifted.rs`.
pub(crate) fn taylor_shift_into(c: &[f64], e: f64, v: &mut [Dd]) {
    let n = c.len() - 1;
    debug_assert_eq!(v.len(), n + 1, "one output per coefficient");
    if e == 0.0 {
        for (vj, &cj) in v.iter_mut().zip(c) {
            *vj = Dd::from_f64(cj);
        }
        return;
    }
    v[0] = Dd::from_f64(c[n]);
    // Exclusive ranges, as in `bernstein::bernstein_on` (unrolled loops).
    for k in (0..n).rev() {
        for i in (1..n - k + 1).rev() {
            v[i] = v[i].mul_f(e).add(v[i - 1]);
        }
        v[0] = v[0].mul_f(e).add_f(c[k]);
    }
}

/// A double-double number `hi + lo`, `|lo| ≤ ulp(hi)/2` (about 106 bits). Each of `+` and
/// `·` between two of them or with an `f64` is within [`DD_UNIT`] of the exact result,
/// relatively, when nothing underflows or overflows.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Dd {
    pub(crate) hi: f64,
    pub(crate) lo: f64,
}

/// Knuth's TwoSum: `s + e = a + b` exactly (no overflow).
#[inline]
pub(crate) fn two_sum(a: f64, b: f64) -> (f64, f64) {
    let s = a + b;
    let bb = s - a;
    (s, (a - (s - bb)) + (b - bb))
}

/// Dekker's Fast2Sum (`|a| ≥ |b|` or `a = 0`): `s + e = a + b` exactly.
#[inline]
pub(crate) fn fast_two_sum(a: f64, b: f64) -> (f64, f64) {
    let s = a + b;
    (s, b - (s - a))
}

/// TwoProduct by fused multiply–add: `p + e = a·b` exactly without underflow.
#[inline]
pub(crate) fn two_prod(a: f64, b: f64) -> (f64, f64) {
    let p = a * b;
    (p, a.mul_add(b, -p))
}

impl Dd {
    /// 0.
    pub const ZERO: Dd = Dd { hi: 0.0, lo: 0.0 };
    /// 1.
    pub const ONE: Dd = Dd { hi: 1.0, lo: 0.0 };

    /// `x` exactly.
    #[inline]
    pub fn from_f64(x: f64) -> Dd {
        Dd { hi: x, lo: 0.0 }
    }

    /// `hi + lo` as given (a TwoSum pair, or any pair with `|lo| ≤ ulp(hi)/2`).
    #[inline]
    pub(crate) fn from_pair(hi: f64, lo: f64) -> Dd {
        Dd { hi, lo }
    }

    /// Half of `self`: exact unless a part underflows (then off by at most `η` absolutely).
    #[inline]
    pub(crate) fn half(self) -> Dd {
        Dd {
            hi: 0.5 * self.hi,
            lo: 0.5 * self.lo,
        }
    }

    /// The sum of two double-words, halved: one de Casteljau average.
    #[inline]
    pub(crate) fn average(self, y: Dd) -> Dd {
        self.add(y).half()
    }

    /// Double-word divided by a double (Joldes et al., §6, `DWDivFP`: relative error below
    /// `3.5u²`, within [`DD_UNIT`]): the quotient's `f64` approximation, its exact remainder
    /// by an error-free product, and the correction from that remainder.
    #[inline]
    pub(crate) fn div_f(self, y: f64) -> Dd {
        let th = self.hi / y;
        let (ph, pl) = two_prod(th, y);
        let dh = self.hi - ph;
        let dt = dh - pl;
        let d = dt + self.lo;
        let tl = d / y;
        let (hi, lo) = fast_two_sum(th, tl);
        Dd { hi, lo }
    }

    /// `a·b` exactly (TwoProduct), unless the product underflows.
    #[inline]
    pub fn product(a: f64, b: f64) -> Dd {
        let (hi, lo) = two_prod(a, b);
        Dd { hi, lo }
    }

    /// The nearest `f64` (`hi`: within half an ulp of `hi + lo`).
    #[inline]
    pub fn to_f64(self) -> f64 {
        self.hi
    }

    /// Algorithm 6 of Joldes et al. (accurate double-word sum).
    #[inline]
    pub(crate) fn add(self, y: Dd) -> Dd {
        let (sh, sl) = two_sum(self.hi, y.hi);
        let (th, tl) = two_sum(self.lo, y.lo);
        let c = sl + th;
        let (vh, vl) = fast_two_sum(sh, c);
        let w = tl + vl;
        let (hi, lo) = fast_two_sum(vh, w);
        Dd { hi, lo }
    }

    /// Algorithm 4 of Joldes et al. (double-word plus double).
    #[inline]
    pub(crate) fn add_f(self, y: f64) -> Dd {
        let (sh, sl) = two_sum(self.hi, y);
        let v = self.lo + sl;
        let (hi, lo) = fast_two_sum(sh, v);
        Dd { hi, lo }
    }

    /// Algorithm 9 of Joldes et al. (double-word times double).
    #[inline]
    pub(crate) fn mul_f(self, y: f64) -> Dd {
        let (ch, cl1) = two_prod(self.hi, y);
        let cl2 = self.lo * y;
        let (th, tl1) = fast_two_sum(ch, cl2);
        let tl2 = tl1 + cl1;
        let (hi, lo) = fast_two_sum(th, tl2);
        Dd { hi, lo }
    }

    /// Algorithm 12 of Joldes et al. (double-word times double-word).
    #[inline]
    pub(crate) fn mul(self, y: Dd) -> Dd {
        let (ch, cl1) = two_prod(self.hi, y.hi);
        let tl0 = self.lo * y.lo;
        let tl1 = self.hi.mul_add(y.lo, tl0);
        let cl2 = self.lo.mul_add(y.hi, tl1);
        let cl3 = cl1 + cl2;
        let (hi, lo) = fast_two_sum(ch, cl3);
        Dd { hi, lo }
    }

    /// The sign of the exact value when `|value| > bound` is certain, else 0. `|lo| ≤
    /// ulp(hi)/2 ≤ 2^-53·|hi|`, so `|value| ≥ |hi|·(1 − 2^-53)`.
    #[inline]
    pub(crate) fn sign_beyond(self, bound: f64) -> i8 {
        if !(self.hi.is_finite() && self.lo.is_finite()) {
            return 0;
        }
        let lower = self.hi.abs() * (1.0 - f64::EPSILON);
        if lower > bound {
            if self.hi > 0.0 { 1 } else { -1 }
        } else {
            0
        }
    }
}

impl std::ops::Add for Dd {
    type Output = Dd;
    /// Algorithm 6 of Joldes et al. (within [`DD_UNIT`]).
    #[inline]
    fn add(self, y: Dd) -> Dd {
        Dd::add(self, y)
    }
}

impl std::ops::Add<f64> for Dd {
    type Output = Dd;
    /// Algorithm 4 of Joldes et al. (within [`DD_UNIT`]).
    #[inline]
    fn add(self, y: f64) -> Dd {
        self.add_f(y)
    }
}

impl std::ops::Mul for Dd {
    type Output = Dd;
    /// Algorithm 12 of Joldes et al. (within [`DD_UNIT`]).
    #[inline]
    fn mul(self, y: Dd) -> Dd {
        Dd::mul(self, y)
    }
}

impl std::ops::Mul<f64> for Dd {
    type Output = Dd;
    /// Algorithm 9 of Joldes et al. (within [`DD_UNIT`]).
    #[inline]
    fn mul(self, y: f64) -> Dd {
        self.mul_f(y)
    }
}

//! The one numeric trait the polynomial code is generic over, and the exact/float boundary.
//!
//! `poly` runs the same algorithms over `f64` (fast, heuristic unless a certified path says
//! otherwise) and over [`Rat`] (exact, the oracle). Everything that differs between the two —
//! what "zero" means, and how to cross between them — lives here, so generic code has exactly
//! one place where it tests for zero: [`Scalar::is_negligible`].

use std::fmt::{Debug, Display};

use num_bigint::BigInt;
use num_rational::BigRational;
use num_traits::{FromPrimitive, Num, NumOps, One, Signed, ToPrimitive, Zero};

/// Exact rational numbers, the oracle type of this crate.
pub type Rat = BigRational;

/// Relative size below which an `f64` result is treated as a cancellation residue.
///
/// [`Scalar::is_negligible`] for `f64` answers `|x| <= F64_NEGLIGIBLE_REL * |scale|`. The value,
/// 2^-40 (about 9.1e-13), leaves 12 bits (a factor 4096) of headroom above `f64::EPSILON` for
/// the round-off that a polynomial remainder sequence of moderate degree accumulates; anything
/// smaller than that relative to the operands of the operation is indistinguishable from zero.
/// It is a heuristic threshold for the `f64` algebra (gcd, Gröbner reduction); certified paths
/// use explicit error bounds instead.
pub const F64_NEGLIGIBLE_REL: f64 = 1.0 / (1u64 << 40) as f64;

/// The scalar field the polynomial algorithms are generic over: `f64` or [`Rat`].
///
/// Built from `num-traits` pieces; arithmetic works by value and with a borrowed right operand.
pub trait Scalar:
    Num + Signed + Clone + PartialOrd + Debug + Display + FromPrimitive + for<'a> NumOps<&'a Self>
{
    /// True when arithmetic over this type is exact (no rounding, no threshold).
    const EXACT: bool;

    /// Whether `self` should be treated as zero in an operation whose operands have size
    /// `scale` (for example the largest coefficient magnitude involved).
    ///
    /// # Exactness
    /// For [`Rat`] this is `self == 0`, whatever `scale` is. For `f64` it is
    /// `|self| <= F64_NEGLIGIBLE_REL * |scale|` (relative to `scale`; a non-finite `self` is
    /// never negligible). See [`F64_NEGLIGIBLE_REL`].
    fn is_negligible(&self, scale: &Self) -> bool;

    /// The nearest `f64` (round to nearest for [`Rat`]; identity for `f64`). Values beyond the
    /// `f64` range become ±infinity.
    fn nearest_f64(&self) -> f64;

    /// `x` as this type, exactly: every finite `f64` is a dyadic rational. `None` for NaN and
    /// infinities.
    fn from_f64_exact(x: f64) -> Option<Self>;
}

impl Scalar for f64 {
    const EXACT: bool = false;

    fn is_negligible(&self, scale: &Self) -> bool {
        self.abs() <= F64_NEGLIGIBLE_REL * scale.abs()
    }

    fn nearest_f64(&self) -> f64 {
        *self
    }

    fn from_f64_exact(x: f64) -> Option<Self> {
        x.is_finite().then_some(x)
    }
}

impl Scalar for Rat {
    const EXACT: bool = true;

    fn is_negligible(&self, _scale: &Self) -> bool {
        self.is_zero()
    }

    fn nearest_f64(&self) -> f64 {
        rat_to_f64(self)
    }

    fn from_f64_exact(x: f64) -> Option<Self> {
        rat_from_f64(x)
    }
}

/// `x = m·2^e` exactly, for a finite `x`: the integer mantissa `m` (`|m| < 2⁵³`, signed, 0 for
/// ±0) and the exponent `e` (`−1074` for subnormals and zero). The one decomposition of an
/// `f64` into a dyadic rational, shared by the exact conversions here, the exact Descartes
/// isolation, the renderer's exact restriction and the modular gcd.
///
/// # Examples
/// ```
/// assert_eq!(poly::f64_dyadic(-0.75), (-(3 << 51), -53));
/// assert_eq!(poly::f64_dyadic(5e-324), (1, -1074));
/// assert_eq!(poly::f64_dyadic(0.0), (0, -1074));
/// ```
pub fn f64_dyadic(x: f64) -> (i64, i64) {
    debug_assert!(x.is_finite(), "a finite f64");
    let bits = x.to_bits();
    let biased = ((bits >> 52) & 0x7ff) as i64;
    let fraction = (bits & ((1u64 << 52) - 1)) as i64;
    // IEEE 754 binary64: (2⁵² + fraction)·2^(biased − 1075), subnormals fraction·2^−1074.
    let (m, e) = if biased == 0 {
        (fraction, -1074)
    } else {
        (fraction | (1 << 52), biased - 1075)
    };
    (if bits >> 63 != 0 { -m } else { m }, e)
}

/// `⌊log₂|x|⌋` of a finite non-zero `x`, subnormals included (`−1074` for the smallest).
pub(crate) fn binary_exponent(x: f64) -> i32 {
    let (m, e) = f64_dyadic(x);
    e as i32 + (63 - m.unsigned_abs().leading_zeros() as i32)
}

/// Significand bits that hold `hi + lo` exactly (a TwoSum pair, both finite and non-zero):
/// from the carry above `hi`'s leading bit down to `lo`'s last bit, `|e(hi) − e(lo)| + 54`
/// (an over-count when `lo` is subnormal, whose last bit lies above `e(lo) − 52`). The wide
/// tiers size their exact node widths by it (`multiprec.rs`, `octuple.rs`).
pub(crate) fn pair_span_bits(hi: f64, lo: f64) -> u32 {
    (binary_exponent(hi) - binary_exponent(lo)).unsigned_abs() + 54
}

/// The exact rational value of a finite `f64` (`None` for NaN or ±infinity).
///
/// # Exactness
/// Exact: a finite `f64` is `m·2^e` with integer `m`, and that is what is returned.
///
/// # Examples
/// ```
/// use poly::{rat_from_f64, Rat};
/// let r = rat_from_f64(0.1).unwrap();
/// // 0.1 is not 1/10 in binary: the exact value of the double is returned.
/// assert_ne!(r, Rat::new(1.into(), 10.into()));
/// assert_eq!(poly::rat_to_f64(&r), 0.1);
/// ```
pub fn rat_from_f64(x: f64) -> Option<Rat> {
    if !x.is_finite() {
        return None;
    }
    if x == 0.0 {
        return Some(Rat::zero());
    }
    let (signed, exponent) = f64_dyadic(x);
    let (negative, mantissa) = (signed < 0, signed.unsigned_abs());
    // An odd mantissa over a power of two is already in lowest terms: no gcd needed (this
    // conversion runs at every point where an exact Sturm sequence is evaluated).
    let tz = mantissa.trailing_zeros();
    let (mantissa, exponent) = (mantissa >> tz, exponent + i64::from(tz));
    let m = BigInt::from(mantissa);
    let m = if negative { -m } else { m };
    let r = if exponent >= 0 {
        Rat::from_integer(m << exponent as usize)
    } else {
        Rat::new_raw(m, BigInt::one() << (-exponent) as usize)
    };
    Some(r)
}

/// The `f64` nearest to `r` (ties to even); ±infinity beyond the `f64` range.
///
/// # Accuracy
/// Correctly rounded: the result is the `f64` nearest the exact rational.
pub fn rat_to_f64(r: &Rat) -> f64 {
    // num-rational's conversion for big ratios is correctly rounded and saturates to ±inf.
    ToPrimitive::to_f64(r).unwrap_or_else(|| {
        if r.is_negative() {
            f64::NEG_INFINITY
        } else {
            f64::INFINITY
        }
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn f64_round_trips_exactly_through_rat() {
        let samples = [
            0.0,
            -0.0,
            1.0,
            -1.5,
            0.1,
            1e-300,
            5e-324,
            f64::MAX,
            f64::MIN_POSITIVE,
            -123456.789e10,
        ];
        for x in samples {
            let r = rat_from_f64(x).expect("finite");
            assert_eq!(rat_to_f64(&r), x, "round trip of {x:e} gave {r}");
        }
        assert_eq!(
            rat_from_f64(0.5),
            Some(Rat::new(1.into(), 2.into())),
            "0.5 = 1/2"
        );
        assert_eq!(
            rat_from_f64(-3.0),
            Some(Rat::from_integer((-3).into())),
            "-3"
        );
        assert_eq!(rat_from_f64(f64::NAN), None, "NaN has no rational value");
        assert_eq!(
            rat_from_f64(f64::INFINITY),
            None,
            "inf has no rational value"
        );
    }

    #[test]
    fn rat_to_f64_rounds_to_nearest() {
        // 1/3 is not representable; the nearest double is 1.0/3.0.
        let third = Rat::new(1.into(), 3.into());
        assert_eq!(rat_to_f64(&third), 1.0 / 3.0, "nearest double to 1/3");
        let huge = Rat::from_integer(BigInt::one() << 2000usize);
        assert_eq!(rat_to_f64(&huge), f64::INFINITY, "saturates");
    }

    #[test]
    fn negligibility_is_relative_for_f64_and_exact_for_rat() {
        assert!(1e-14_f64.is_negligible(&10.0), "1e-14 is below 2^-40 * 10");
        assert!(!1e-10_f64.is_negligible(&10.0), "1e-10 is above 2^-40 * 10");
        assert!(!f64::NAN.is_negligible(&1.0), "NaN is never negligible");
        let tiny = Rat::new(1.into(), BigInt::one() << 500usize);
        assert!(
            !tiny.is_negligible(&Rat::one()),
            "exact: only zero is negligible"
        );
        assert!(Rat::zero().is_negligible(&Rat::one()), "zero is");
    }
}

//! The octuple-precision tier's arithmetic: IEEE 754 `binary256` numbers (237-bit
//! significands, the [`f256`] crate), between double-double (106 bits) and the allocating
//! `astro-float` tiers of `multiprec.rs`. Why this format: a `binary256` number is 32 bytes on
//! the stack and its operations are correctly rounded, so the standard model
//! `fl(x ∘ y) = (x ∘ y)(1 + δ)`, `|δ| ≤ 2^-237`, holds as it does for `f64` — and a Horner step
//! cost about half of `astro-float`'s at 256 bits (`paper-notes/isolation.md`, "An octuple
//! tier").
//!
//! Underflow is not modelled by a bound: [`Oct`] flags every product that lands below the
//! normal range (sums of floating-point numbers never err there, IEEE's gradual underflow
//! makes them exact), and the tier's answer is discarded when the flag is set. Values from
//! `f64` inputs reach that range (`2^-262142`) only with hundreds of factors near `f64`'s
//! smallest numbers.

use std::cell::Cell;

use f256::f256;

use crate::double_double::{Dd, two_sum};
use crate::scalar::pair_span_bits;

/// Unit roundoff bound of the tier: `binary256` rounds to nearest with a 237-bit significand,
/// so `|δ| ≤ 2^-237`; `2^-236` (as the wide tiers take `2^(1 − bits)`) leaves a factor 2.
pub(crate) const OCT_UNIT: f64 = 1.0 / (1u128 << 118) as f64 / (1u128 << 118) as f64;

/// Bits of the stored fraction of a `binary256` number (its significand has one more).
const FRACTION_BITS: u32 = 236;

/// Fraction bits held in the upper 128-bit word of the encoding (below the sign and the 19
/// exponent bits).
const HI_FRACTION_BITS: u32 = FRACTION_BITS - 128;

/// The exponent bias of `binary256`.
const EXP_BIAS: i32 = 262_143;

/// The octuple tier's operations, with the flag that records an underflowing product.
#[derive(Default)]
pub(crate) struct Oct {
    underflowed: Cell<bool>,
}

impl Oct {
    /// `x·y` rounded; flags an underflow (a subnormal result, or 0 from non-zero factors).
    #[inline]
    pub(crate) fn mul(&self, x: f256, y: f256) -> f256 {
        let p = x * y;
        if p.is_subnormal() || (p.eq_zero() && !x.eq_zero() && !y.eq_zero()) {
            self.underflowed.set(true);
        }
        p
    }

    /// Whether no product underflowed since this value was made: only then do the standard
    /// model's bounds hold for what was computed with it.
    pub(crate) fn clean(&self) -> bool {
        !self.underflowed.get()
    }
}

/// `x` exactly (every `f64`, subnormals included, is a `binary256` number).
#[inline]
pub(crate) fn oct(x: f64) -> f256 {
    f256::from(x)
}

/// `hi + lo` exactly, when the pair's bits ([`pair_span_bits`]) fit the 237-bit significand
/// (with one bit to spare); `None` otherwise.
pub(crate) fn oct_pair(hi: f64, lo: f64) -> Option<f256> {
    let fits = hi == 0.0 || lo == 0.0 || pair_span_bits(hi, lo) <= FRACTION_BITS;
    fits.then(|| oct(hi) + oct(lo))
}

/// The sign, unbiased exponent and 237-bit significand (as `(top 109 bits, low 128 bits)`)
/// of a finite non-zero normal `x`; `None` for zero, subnormals, infinities and NaN.
fn decode(x: f256) -> Option<(bool, i32, u128, u128)> {
    if !x.is_normal() {
        return None;
    }
    let (hi, lo) = x.to_bits();
    let negative = hi >> 127 == 1;
    let biased = ((hi >> HI_FRACTION_BITS) & ((1 << 19) - 1)) as i32;
    let top = (hi & ((1u128 << HI_FRACTION_BITS) - 1)) | (1u128 << HI_FRACTION_BITS);
    Some((negative, biased - EXP_BIAS, top, lo))
}

/// `x` truncated to its leading 53 bits, exactly an `f64` — relative error below `2^-52` —
/// when that is a normal `f64` (or `x` is 0); `None` otherwise.
pub(crate) fn oct_to_f64_trunc(x: f256) -> Option<f64> {
    if x.eq_zero() {
        return Some(0.0);
    }
    let (negative, e, top, _) = decode(x)?;
    if !(-1022..=1023).contains(&e) {
        return None;
    }
    // The significand's leading 53 bits: top has HI_FRACTION_BITS + 1 = 109 bits.
    let mantissa = (top >> (HI_FRACTION_BITS - 52)) as u64 & ((1u64 << 52) - 1);
    let bits = (u64::from(negative) << 63) | (((e + 1023) as u64) << 52) | mantissa;
    Some(f64::from_bits(bits))
}

/// `x` as a double-double within `2^-104·|x|`: its leading 53 bits, then the leading 53 of
/// the (exact) rest, each truncated. `None` when either part is outside `f64`'s normal range
/// (the rest may be 0).
pub(crate) fn oct_to_dd(x: f256) -> Option<Dd> {
    let hi = oct_to_f64_trunc(x)?;
    // x − hi is exact: hi is x's own leading bits.
    let lo = oct_to_f64_trunc(x - oct(hi))?;
    let (h, l) = two_sum(hi, lo);
    Some(Dd::from_pair(h, l))
}

/// An approximate `f64` value of `x` for placing trial points (never certified): NaN when it
/// is outside `f64`'s normal range.
pub(crate) fn oct_approx(x: f256) -> f64 {
    oct_to_f64_trunc(x).unwrap_or(f64::NAN)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_unit_is_two_to_the_minus_236() {
        assert_eq!(OCT_UNIT, 2f64.powi(-236));
    }

    /// Every `f64`, subnormals included, converts to `binary256` and back unchanged.
    #[test]
    fn f64_values_convert_exactly() {
        for x in [
            1.0,
            -0.1,
            f64::MAX,
            -f64::MIN_POSITIVE,
            1.5e-300,
            123_456.789,
            2f64.powi(1023),
        ] {
            assert_eq!(oct_to_f64_trunc(oct(x)), Some(x), "{x:e}");
        }
        // A subnormal is exact in binary256 (its double is, and doubling is exact).
        let s = 5e-324;
        assert_eq!(oct(s) * oct(2f64.powi(600)), oct(s * 2f64.powi(600)));
    }

    /// The double-double of `a + b` (a TwoSum pair of two `f64`) is the pair itself, and of
    /// `1/3` it is within `2^-104`.
    #[test]
    fn double_double_conversion_is_within_its_bound() {
        let (hi, lo) = two_sum(1.0, 2f64.powi(-70) / 3.0);
        let dd = oct_to_dd(oct_pair(hi, lo).expect("fits")).expect("in range");
        assert_eq!((dd.hi, dd.lo), (hi, lo));
        let third = oct(1.0) / oct(3.0);
        let dd = oct_to_dd(third).expect("in range");
        let err = (third - oct(dd.hi) - oct(dd.lo)).abs();
        assert!(err <= third * oct(2f64.powi(-104)), "{dd:?}");
        // Truncation: the parts sum to at most |x|.
        assert!(oct(dd.hi) + oct(dd.lo) <= third);
    }

    /// A pair is exact when its bits fit 237, refused when they do not.
    #[test]
    fn pairs_beyond_the_significand_are_refused() {
        assert!(oct_pair(1.0, 2f64.powi(-150)).is_some());
        assert!(oct_pair(1.0, 2f64.powi(-300)).is_none());
        assert_eq!(
            oct_pair(1.0, 2f64.powi(-150)).expect("fits") - oct(1.0),
            oct(2f64.powi(-150))
        );
    }

    /// A product below the normal range sets the flag; ordinary products do not.
    #[test]
    fn underflowing_products_are_flagged() {
        let o = Oct::default();
        let tiny = oct(1e-300);
        let mut v = tiny;
        for _ in 0..200 {
            v = o.mul(v, tiny);
            assert!(o.clean(), "1e-300^k stays normal up to k = 201");
        }
        let mut v = tiny;
        for _ in 0..300 {
            v = o.mul(v, tiny);
        }
        assert!(!o.clean(), "1e-90000 is below binary256's normal range");
        assert!(oct_approx(v).is_nan() || oct_approx(v) == 0.0);
    }
}

//! Exact power-of-two rescaling of a polynomial and its argument, so that evaluation never
//! overflows: `p(x) = 2^s·q(y)` with `x = 2^k·y`, `|y| < 1`, and `q`'s coefficients
//! `cᵢ·2^{k·i − s}` at most 2 in magnitude (`paper-notes/isolation.md`, "Extended exponent
//! range").
//!
//! Why: a polynomial whose coefficients reach `10³⁰⁷` and whose roots reach `10¹⁵⁴` has
//! `Σ|cᵢ||x|ⁱ` beyond the `f64` range at its own roots, so Horner's rule, its error bound and
//! the Aberth iteration overflow, and every sign there was left to the 256-bit tier. The
//! extended-exponent evaluation (the value as an `f64` mantissa times `2^s`) needs no new
//! arithmetic: scaling by a power of two is exact in binary floating point except where the
//! result underflows, so `q` is `p` up to that underflow, which is counted
//! ([`with_rescaled`]'s accuracy), and the existing rigorous Horner bounds apply to `q` at `y`.
//! The scale `s` is the largest `log₂|cᵢ·xⁱ|`: the upper vertex of the Newton polygon at the
//! scale of `|x|`.

use std::cell::Cell;

/// The binary exponent of a finite non-zero `x`: `2^e ≤ |x| < 2^{e+1}` (subnormals too).
#[inline]
pub(crate) fn exponent(x: f64) -> i64 {
    let bits = x.abs().to_bits();
    let biased = (bits >> 52) as i64;
    if biased == 0 {
        // Subnormal: |x| = bits·2^-1074 with bits < 2^52.
        63 - i64::from(bits.leading_zeros()) - 1074
    } else {
        biased - 1023
    }
}

/// `2^e` for `−1074 ≤ e ≤ 1023` (subnormal below −1022), exactly.
fn pow2(e: i64) -> f64 {
    debug_assert!((-1074..=1023).contains(&e), "2^{e} is not an f64");
    if e >= -1022 {
        f64::from_bits(((e + 1023) as u64) << 52)
    } else {
        f64::from_bits(1u64 << (e + 1074))
    }
}

/// `x·2^e`, rounded once: exact when the result is normal (or `x` is 0), within `η/2` when
/// it is subnormal, `0` (an error below `η = 2^-1074`) when it is smaller still, and `±∞`
/// when it overflows. Any finite `x` and any `e`.
#[inline]
pub(crate) fn ldexp(x: f64, e: i64) -> f64 {
    // A normal `x` with a normal result: add `e` to the exponent field (exact).
    let bits = x.to_bits();
    let biased = ((bits >> 52) & 0x7ff) as i64;
    if biased != 0 && biased != 0x7ff && (1..=2046).contains(&(biased + e)) {
        return f64::from_bits(bits.wrapping_add((e << 52) as u64));
    }
    ldexp_general(x, e)
}

/// [`ldexp`] where the input or the result is not normal.
fn ldexp_general(x: f64, e: i64) -> f64 {
    if x == 0.0 || !x.is_finite() {
        return x;
    }
    let t = exponent(x) + e;
    if t > 1023 {
        return f64::INFINITY.copysign(x);
    }
    // m = x·2^-exponent(x) ∈ [1, 2) exactly (scaling a subnormal up is exact too).
    let ex = exponent(x);
    let m = if ex >= -1022 {
        x * pow2(-ex)
    } else {
        x * pow2(1023) * pow2(-ex - 1023)
    };
    if t >= -1074 {
        // One product by an exact power of two: exact when normal, else one rounding.
        m * pow2(t)
    } else {
        // |m·2^t| < 2^{t+1} ≤ 2^-1074.
        0.0f64.copysign(x)
    }
}

/// The scales of one rescaling: `x = 2^k·y`, `p(x) = 2^s·q(y)`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct Rescaling {
    /// `x = 2^k·y`.
    pub(crate) k: i64,
    /// `p(x) = 2^s·q(y)`.
    pub(crate) s: i64,
}

/// Most coefficients rescaled into a stack buffer; longer polynomials use a per-thread
/// buffer (the quartics and the renderer's degrees fit on the stack, which costs no
/// thread-local access per evaluation).
const STACK_LEN: usize = 32;

thread_local! {
    /// Reused buffer for polynomials longer than [`STACK_LEN`]: used only where plain `f64`
    /// evaluation overflows, so it allocates at most once per thread and degree.
    static RESCALED: Cell<Vec<f64>> = const { Cell::new(Vec::new()) };
}

/// Calls `f(q, y, r)` with `y = (re + i·im)·2^-k` and the coefficients `q` of
/// `p(x) = 2^s·q(y)` (lowest degree first), where `2^k` is the smallest power of two above
/// `max(|re|, |im|)` (so `|Re y|, |Im y| < 1`) and `s` the largest `exponent(cᵢ) + k·i`
/// (so `|qᵢ| < 2`, and the largest `|qᵢ||y|ⁱ` is at least `2^{-i}` times the largest
/// `|qᵢ|·max(|Re y|, |Im y|)ⁱ`). `None` when `re = im = 0`, a part of `y` is not exact (an
/// imaginary part so small against the real part that it underflows), or the input is not
/// finite.
///
/// # Accuracy
/// `y` is exact. Each `qᵢ` is `cᵢ·2^{k·i − s}` rounded once ([`ldexp`]): exact unless it is
/// below the normal range, and then within `η = 2^-1074` of it. So for every `w`,
/// `|q(w) − 2^-s·p(2^k·w)| ≤ η·Σ|w|ⁱ`, which a caller adds to any bound on `q`'s own
/// evaluation (`η·(n + 1)` for a real `|w| < 1`).
pub(crate) fn with_rescaled<R>(
    c: &[f64],
    re: f64,
    im: f64,
    f: impl FnOnce(&[f64], f64, f64, Rescaling) -> R,
) -> Option<R> {
    let top = re.abs().max(im.abs());
    if top == 0.0 || !top.is_finite() {
        return None;
    }
    let k = exponent(top) + 1;
    let (yr, yi) = (ldexp(re, -k), ldexp(im, -k));
    if ldexp(yr, k) != re || ldexp(yi, k) != im {
        return None;
    }
    let mut s = i64::MIN;
    for (i, &ci) in c.iter().enumerate() {
        if ci != 0.0 {
            s = s.max(exponent(ci) + k * i as i64);
        }
    }
    if s == i64::MIN {
        return None;
    }
    let r = Rescaling { k, s };
    let fill = |q: &mut [f64]| {
        for (i, (qi, &ci)) in q.iter_mut().zip(c).enumerate() {
            *qi = ldexp(ci, k * i as i64 - s);
        }
    };
    if c.len() <= STACK_LEN {
        let mut buf = [0.0; STACK_LEN];
        let q = &mut buf[..c.len()];
        fill(q);
        return Some(f(q, yr, yi, r));
    }
    let mut q = RESCALED.take();
    q.clear();
    q.resize(c.len(), 0.0);
    fill(&mut q);
    let out = f(&q, yr, yi, r);
    RESCALED.set(q);
    Some(out)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scalar::Rat;
    use crate::univariate::ETA;
    use num_traits::Signed;

    #[test]
    fn exponent_brackets_the_magnitude() {
        for x in [
            1.0,
            1.5,
            2.0,
            1e-300,
            1e300,
            f64::MAX,
            f64::MIN_POSITIVE,
            ETA,
            3.0 * ETA,
        ] {
            let e = exponent(x);
            let lo = Rat::from_float(2.0).unwrap().pow(e as i32);
            let v = Rat::from_float(x).unwrap();
            assert!(
                lo <= v && v < &lo * Rat::from_integer(2.into()),
                "{x:e}: {e}"
            );
            assert_eq!(exponent(-x), e, "sign ignored");
        }
    }

    #[test]
    fn ldexp_fast_path_agrees_with_the_general_one() {
        for x in [1.0, -1.5, 3e-300, -7e300, f64::MIN_POSITIVE, f64::MAX, 0.1] {
            for e in [
                -2100, -1100, -1074, -1000, -52, -1, 0, 1, 52, 600, 1023, 2000,
            ] {
                let (a, b) = (ldexp(x, e), ldexp_general(x, e));
                assert_eq!(a.to_bits(), b.to_bits(), "{x:e}·2^{e}");
            }
        }
    }

    #[test]
    fn ldexp_is_exact_in_range_and_rounds_once_below() {
        assert_eq!(ldexp(3.0, 1000), 3.0 * 2f64.powi(1000), "normal result");
        assert_eq!(
            ldexp(1e300, -2000),
            1e300 * 2f64.powi(-1000) * 2f64.powi(-1000)
        );
        assert_eq!(ldexp(ETA, 1074), 1.0, "a subnormal scaled up");
        assert_eq!(ldexp(1.0, -1074), ETA, "the smallest subnormal");
        assert_eq!(ldexp(1.0, -1076), 0.0, "below it: 0");
        assert_eq!(
            ldexp(-1.0, 1024),
            f64::NEG_INFINITY,
            "overflow keeps the sign"
        );
        // 1.75·2^-1074 rounds once to 2η (double rounding through 2^-1073 would give the same
        // here; the error is at most η/2 either way).
        assert_eq!(ldexp(1.75, -1074), 2.0 * ETA);
        for (x, e) in [(1.3, -1060), (-1.7e-5, -1040), (0.9, -1074)] {
            let exact = Rat::from_float(x).unwrap() * Rat::from_float(2.0).unwrap().pow(e as i32);
            let got = Rat::from_float(ldexp(x, e)).unwrap();
            // Within η/2 when rounded to a subnormal, below η when flushed to 0 (0.9·2^-1074).
            let err = (got - exact).abs();
            assert!(err < Rat::from_float(ETA).unwrap(), "{x} 2^{e}: within η");
        }
    }
}

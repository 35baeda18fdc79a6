//! Certified truth: the exact distinct real roots of a polynomial as stored.
//!
//! Every finite `f64` is a dyadic rational `m·2^e`, so an `f64` polynomial *is* a rational
//! polynomial, and its exact Sturm sequence ([`poly::QPoly::sturm`]) counts its distinct real
//! roots without error. Isolating each root by exact bisection and narrowing the interval to
//! width `2^-TRUTH_BITS` gives every root to far better than `f64` precision. This is the
//! truth for "the polynomial as stored": rounding that happened while *building* the
//! coefficients is not undone (see [`crate::rays`] for the construction error of ray
//! polynomials).

use num_traits::{Signed, Zero};
use poly::{Poly, QPoly, Rat, RootInterval, SturmSequence, rat_from_f64, rat_to_f64};

/// Width (as a power of two, absolute) to which every true root is narrowed: `2^-80`.
pub const TRUTH_BITS: u32 = 80;

/// The distinct real roots in `(lo, hi]` of one polynomial, certified.
#[derive(Clone, Debug)]
pub struct Truth {
    /// Each root to within `2^-(TRUTH_BITS + 1)` (the midpoint of a certified interval of
    /// width at most `2^-TRUTH_BITS`), increasing.
    pub roots: Vec<Rat>,
    /// The same roots rounded to `f64`.
    pub approx: Vec<f64>,
}

impl Truth {
    /// The smallest root, if any.
    pub fn smallest(&self) -> Option<&Rat> {
        self.roots.first()
    }
}

/// The certified distinct real roots of `p` (exact coefficients) in `(lo, hi]`.
///
/// Panics on the zero polynomial (a caller bug: the suites never build one).
pub fn exact_roots(p: &QPoly, lo: &Rat, hi: &Rat) -> Truth {
    let seq = p.sturm().expect("test polynomials are never zero");
    let mut roots = Vec::new();
    for iv in isolate(&seq, lo, hi) {
        let narrow = if iv.is_point() {
            iv
        } else {
            seq.refine_interval(&iv, TRUTH_BITS)
        };
        let two = Rat::from_integer(2.into());
        roots.push((&narrow.lo + &narrow.hi) / two);
    }
    // A point interval and its right neighbour can share a lower end: sort the roots.
    roots.sort();
    let approx = roots.iter().map(rat_to_f64).collect();
    Truth { roots, approx }
}

/// [`exact_roots`] of the stored `f64` polynomial on `(lo, hi]` (finite bounds).
pub fn stored_truth(p: &Poly<f64>, lo: f64, hi: f64) -> Truth {
    let q = p
        .to_rat()
        .expect("test polynomials have finite coefficients");
    let lo = rat_from_f64(lo).expect("finite bound");
    let hi = rat_from_f64(hi).expect("finite bound");
    exact_roots(&q, &lo, &hi)
}

/// Exact bisection on Sturm counts (Stam §3.5.2), each interval holding one distinct root:
/// the open interval `(lo, hi)`, or the point `lo == hi` when a midpoint is the root.
fn isolate(seq: &SturmSequence<Rat>, a: &Rat, b: &Rat) -> Vec<RootInterval<Rat>> {
    let mut out = Vec::new();
    if a >= b {
        return out;
    }
    let two = Rat::from_integer(2.into());
    let mut stack = vec![(
        a.clone(),
        b.clone(),
        seq.sign_changes_at(a),
        seq.sign_changes_at(b),
    )];
    while let Some((lo, hi, vlo, vhi)) = stack.pop() {
        let n = vlo.saturating_sub(vhi);
        if n == 0 {
            continue;
        }
        if n == 1 {
            // The root is in (lo, hi]; a root exactly at hi becomes a point interval so that
            // the refinement below always starts from an open interval.
            if seq.sign_of_square_free_at(&hi) == 0 {
                out.push(RootInterval { lo: hi.clone(), hi });
            } else {
                out.push(RootInterval { lo, hi });
            }
            continue;
        }
        let mid = (&lo + &hi) / &two;
        let vm = seq.sign_changes_at(&mid);
        stack.push((lo, mid.clone(), vlo, vm));
        stack.push((mid, hi, vm, vhi));
    }
    out
}

/// `|x − r|` computed exactly and rounded to `f64`.
pub fn abs_error(x: f64, r: &Rat) -> f64 {
    match rat_from_f64(x) {
        Some(xr) => rat_to_f64(&(xr - r).abs()),
        None => f64::INFINITY,
    }
}

/// `|x − r| / |r|` (exact difference, rounded); `None` when `r` is zero.
pub fn rel_error(x: f64, r: &Rat) -> Option<f64> {
    if r.is_zero() {
        return None;
    }
    match rat_from_f64(x) {
        Some(xr) => Some(rat_to_f64(&((xr - r) / r).abs())),
        None => Some(f64::INFINITY),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use poly::testutil::{planted, rat};

    #[test]
    fn planted_roots_are_recovered_to_truth_precision() {
        let roots = [rat(1, 3), rat(-2, 7), rat(1, 3), rat(5, 2)];
        let t = exact_roots(&planted(&roots), &rat(-1, 1), &rat(5, 2));
        assert_eq!(
            t.roots.len(),
            3,
            "distinct roots in (−1, 5/2]: {:?}",
            t.approx
        );
        let want = [rat(-2, 7), rat(1, 3), rat(5, 2)];
        let eps = Rat::new(1.into(), num_bigint::BigInt::from(1) << 81usize);
        for (got, want) in t.roots.iter().zip(&want) {
            assert!((got - want).abs() <= eps, "{got} vs {want}");
        }
        // A root on the first bisection point: the point interval and its neighbour share a
        // lower end; the roots still come out sorted.
        let t = exact_roots(
            &planted(&[rat(1, 2), rat(0, 1), rat(-1, 2)]),
            &rat(-2, 1),
            &rat(2, 1),
        );
        assert_eq!(t.approx, vec![-0.5, 0.0, 0.5], "sorted, zero exact");
        assert_eq!(abs_error(0.5, &rat(1, 4)), 0.25, "exact difference");
        assert_eq!(rel_error(0.5, &rat(1, 4)), Some(1.0), "relative to 1/4");
        assert_eq!(
            rel_error(0.5, &rat(0, 1)),
            None,
            "zero root has no relative error"
        );
    }
}

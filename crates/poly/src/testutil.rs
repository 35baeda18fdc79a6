//! Test polynomials with known roots, shared by the unit tests, the integration tests and the
//! stability suite: planted rational roots, Wilkinson's polynomial, Chebyshev polynomials.
//!
//! Everything here is exact: the polynomials are built over [`Rat`], and the `f64` versions
//! are the coefficient-wise nearest doubles (so their roots differ slightly from the planted
//! ones — compare `f64` results with the exact roots of the *stored* polynomial, via
//! [`Poly::to_rat`], or allow for the conditioning).

use num_bigint::BigInt;

use crate::root_interval::RootInterval;
use crate::scalar::{Rat, rat_from_f64, rat_to_f64};
use crate::sturm::SturmSequence;
use crate::univariate::{Poly, QPoly};

/// `n/d` as a rational. Panics if `d == 0` (a caller bug).
pub fn rat(n: i64, d: i64) -> Rat {
    Rat::new(BigInt::from(n), BigInt::from(d))
}

/// `∏ (x − rᵢ)` over the rationals: roots exactly `rᵢ`, multiplicities from repetition.
pub fn planted(roots: &[Rat]) -> QPoly {
    QPoly::from_roots(roots)
}

/// Wilkinson's polynomial `∏_{k=1}^{n} (x − k)` (n = 20 is the classic ill-conditioned case:
/// its coefficients reach 20! ≈ 2.4e18, beyond exact `f64` integers).
pub fn wilkinson(n: u32) -> QPoly {
    let roots: Vec<Rat> = (1..=i64::from(n)).map(|k| rat(k, 1)).collect();
    QPoly::from_roots(&roots)
}

/// The Chebyshev polynomial of the first kind `T_n` (`T₀ = 1`, `T₁ = x`,
/// `T_{k+1} = 2x·T_k − T_{k−1}`): `n` simple roots `cos((2k − 1)π / 2n)` in `(−1, 1)`.
pub fn chebyshev(n: u32) -> QPoly {
    let two_x = QPoly::new(vec![rat(0, 1), rat(2, 1)]);
    let (mut prev, mut cur) = (
        QPoly::constant(rat(1, 1)),
        QPoly::new(vec![rat(0, 1), rat(1, 1)]),
    );
    if n == 0 {
        return prev;
    }
    for _ in 1..n {
        let next = &(&two_x * &cur) - &prev;
        prev = cur;
        cur = next;
    }
    cur
}

/// The roots of [`chebyshev`]`(n)` in increasing order, as `f64`.
pub fn chebyshev_roots(n: u32) -> Vec<f64> {
    let mut r: Vec<f64> = (1..=n)
        .map(|k| ((2 * k - 1) as f64 * std::f64::consts::PI / (2 * n) as f64).cos())
        .collect();
    r.sort_by(f64::total_cmp);
    r
}

/// The distinct values of `roots`, sorted.
pub fn distinct_sorted(roots: &[Rat]) -> Vec<Rat> {
    let mut r = roots.to_vec();
    r.sort();
    r.dedup();
    r
}

/// The number of distinct values of `roots` in the half-open interval `(a, b]` — the oracle
/// for Sturm counts on planted polynomials.
pub fn planted_count(roots: &[Rat], a: &Rat, b: &Rat) -> usize {
    distinct_sorted(roots)
        .iter()
        .filter(|r| *r > a && *r <= b)
        .count()
}

/// `∏ (x − rᵢ)` in `f64` from `f64` roots (rounded at every step; its exact roots are those
/// of the stored coefficients, near but not equal to `rᵢ`).
pub fn planted_f64(roots: &[f64]) -> Poly<f64> {
    Poly::from_roots(roots)
}

/// The distinct real roots of the *stored* `f64` polynomial in `(lo, hi]` (finite ends), by
/// exact Sturm isolation refined to `2^-80` and rounded: the oracle for `f64` results.
pub fn stored_roots(p: &Poly<f64>, lo: f64, hi: f64) -> Vec<f64> {
    let q = p.to_rat().expect("finite coefficients");
    let seq = q.sturm().expect("a non-zero polynomial");
    let (a, b) = (
        rat_from_f64(lo).expect("finite"),
        rat_from_f64(hi).expect("finite"),
    );
    q.isolate_roots(&a, &b)
        .expect("finite ends")
        .iter()
        .map(|iv| rat_to_f64(&refined_relative(&seq, iv).lo))
        .collect()
}

/// `iv` refined to within `2⁻⁶⁰` of its root *relatively* (or to a point): 80 bits absolute
/// first, then 64 more at a time while the interval still reaches 0 or is wider than that.
/// (Refining to 80 bits absolute alone returned 0 for the root 9.0e-81.)
fn refined_relative(seq: &SturmSequence<Rat>, iv: &RootInterval<Rat>) -> RootInterval<Rat> {
    let zero = Rat::from_integer(0.into());
    let mut bits = 80;
    loop {
        let r = seq.refine_interval(iv, bits);
        let same_side = (r.lo > zero && r.hi > zero) || (r.lo < zero && r.hi < zero);
        let tight = r.lo == r.hi
            || (same_side && {
                let scale = if r.lo > zero {
                    r.lo.clone()
                } else {
                    -r.hi.clone()
                };
                (&r.hi - &r.lo) * Rat::from_integer((1i64 << 60).into()) <= scale
            });
        if tight || bits >= 1200 {
            return r;
        }
        bits += 64;
    }
}

/// The torus `(x² + y² + z² + R² − r²)² − 4R²(x² + y²)` (`R = 2`, `r = 1`, axis `z`) along
/// the ray from `(x0, 0.1, 0.05)` in direction `(1, 0, 0)`: with `x = x0 + t`,
/// `((x0 + t)² + k)² − 16((x0 + t)² + 0.01)`, `k = 0.01 + 0.0025 + 3`. Its roots are where the
/// ray crosses the tube, near `x = ±1, ±3`; from `x0 = −10⁴` they cluster far from 0 against
/// their spread.
pub fn torus_ray(x0: f64) -> Poly<f64> {
    let (oy, oz) = (0.1, 0.05);
    let sq = Poly::new(vec![x0 * x0, 2.0 * x0, 1.0]);
    let s = &sq + &Poly::new(vec![oy * oy + oz * oz + 3.0]);
    &(&s * &s) - &(&(&sq + &Poly::new(vec![oy * oy])) * &Poly::new(vec![16.0]))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn stored_roots_are_accurate_relatively_for_tiny_roots() {
        // Regression: refined to 80 bits absolute only, the oracle returned 0 for a root near
        // 9e-81 (found by a far-cluster test at scale 1e-80), and a correct answer was
        // reported as wrong.
        let p = Poly::new(vec![9e-81, -1.0, 1.0]); // roots ≈ 9e-81 and ≈ 1
        let r = stored_roots(&p, 0.0, 0.5);
        assert_eq!(r.len(), 1);
        assert!((r[0] - 9e-81).abs() <= 1e-12 * 9e-81, "{r:?}");
    }

    #[test]
    fn constructors_have_the_planted_roots() {
        let w = wilkinson(20);
        assert_eq!(w.degree(), 20, "degree 20");
        assert_eq!(w.eval(&rat(7, 1)), rat(0, 1), "7 is a root");
        assert_eq!(w.coeff(19), rat(-210, 1), "−(1 + … + 20)");
        let t4 = chebyshev(4);
        assert_eq!(
            t4,
            QPoly::new(vec![rat(1, 1), rat(0, 1), rat(-8, 1), rat(0, 1), rat(8, 1)]),
            "T4 = 8x⁴ − 8x² + 1"
        );
        let roots = [rat(1, 2), rat(-3, 1), rat(1, 2)];
        assert_eq!(
            planted_count(&roots, &rat(-3, 1), &rat(1, 2)),
            1,
            "(−3, 1/2] holds 1/2 once"
        );
        assert_eq!(chebyshev_roots(3).len(), 3, "three roots");
    }
}

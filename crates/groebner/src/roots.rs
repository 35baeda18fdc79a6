//! [`SolveScalar`]: the two coefficient fields [`solve`](crate::solve) runs over, and their
//! bridge to `poly`'s certified real-root finders (the crate has no root finder of its own).

use num_bigint::{BigInt, Sign};
use num_traits::{One, Signed, Zero};
use poly::{BiPoly, Poly, Rat, Scalar};

use crate::error::Error;
use crate::solve::{Solution, SolveOptions};

mod sealed {
    pub trait Sealed {}
    impl Sealed for f64 {}
    impl Sealed for poly::Rat {}
}

/// A scalar type [`solve`](crate::solve) accepts: `f64` (fast mode) or [`Rat`] (exact mode).
/// Sealed: the two implementations are the only ones.
pub trait SolveScalar: Scalar + sealed::Sealed {
    /// The distinct real roots of `p` in `(range[0], range[1]]`, sorted, each within `x_tol`,
    /// by `poly`'s certified isolation (Bernstein/Descartes for `f64`, exact Sturm for `Rat`).
    /// Zero or constant polynomials have none here (the callers treat those cases first).
    fn real_roots_in(p: &Poly<Self>, range: [f64; 2], x_tol: f64) -> Vec<f64>;

    /// Exact mode: the bit size of the largest coefficient of `p` scaled to a primitive
    /// integer polynomial; `None` for `f64`.
    fn coeff_bits(p: &BiPoly<Self>) -> Option<u64>;

    /// Exact mode: a rational within `2^-bits` (absolute) of a real root of `p` that lies within
    /// `2·x_tol` of `u`, a value returned by [`real_roots_in`](SolveScalar::real_roots_in)
    /// with the same `x_tol`. `None` in `f64` mode, or when no root is found there.
    ///
    /// Why: back-substituting `u` into a basis element `v + h(u)` is only as accurate as
    /// `|h'(u)|·|u − u_r|`, and `h'` can be enormous (1.5e18 on a teapot piece, see
    /// `paper-notes/groebner.md` §5), so the `f64` value of the root is not enough even though
    /// the basis is exact.
    fn sharpen_root(p: &Poly<Self>, u: f64, x_tol: f64, bits: u32) -> Option<Self>;

    /// `f64`: [`solve`](crate::solve) on the allocation-free path of `fast.rs` when it applies
    /// (degree ≤ 3 in `u` and `v`, Stam or Bézout); `None` otherwise and for exact scalars.
    #[doc(hidden)]
    fn solve_fast(
        f1: &BiPoly<Self>,
        f2: &BiPoly<Self>,
        opts: &SolveOptions,
    ) -> Option<Result<Solution, Error>>;
}

impl SolveScalar for f64 {
    fn real_roots_in(p: &Poly<f64>, range: [f64; 2], x_tol: f64) -> Vec<f64> {
        if p.degree() == 0 {
            return Vec::new();
        }
        // Errors are impossible here: finite coefficients and bounds, a positive x_tol and a
        // non-zero polynomial are checked by the caller.
        p.real_roots(range[0], range[1], x_tol).unwrap_or_default()
    }

    fn coeff_bits(_: &BiPoly<f64>) -> Option<u64> {
        None
    }

    fn sharpen_root(_: &Poly<f64>, _: f64, _: f64, _: u32) -> Option<f64> {
        None
    }

    fn solve_fast(
        f1: &BiPoly<f64>,
        f2: &BiPoly<f64>,
        opts: &SolveOptions,
    ) -> Option<Result<Solution, Error>> {
        crate::fast::solve_f64(f1, f2, opts)
    }
}

impl SolveScalar for Rat {
    fn solve_fast(
        _: &BiPoly<Rat>,
        _: &BiPoly<Rat>,
        _: &SolveOptions,
    ) -> Option<Result<Solution, Error>> {
        None
    }

    fn real_roots_in(p: &Poly<Rat>, range: [f64; 2], x_tol: f64) -> Vec<f64> {
        if p.degree() == 0 {
            return Vec::new();
        }
        let (Some(a), Some(b)) = (Rat::from_f64_exact(range[0]), Rat::from_f64_exact(range[1]))
        else {
            return Vec::new();
        };
        // Coefficients of many hundred bits make the Sturm sequence expensive; the primitive
        // integer form has the same roots and smaller entries.
        p.primitive_integer()
            .real_roots(&a, &b, x_tol)
            .unwrap_or_default()
    }

    fn coeff_bits(p: &BiPoly<Rat>) -> Option<u64> {
        if p.is_zero() {
            return None;
        }
        let flat = Poly::new(p.coeffs().to_vec()).primitive_integer();
        flat.coeffs().iter().map(|c| c.numer().bits()).max()
    }

    fn sharpen_root(p: &Poly<Rat>, u: f64, x_tol: f64, bits: u32) -> Option<Rat> {
        if p.degree() == 0 || !u.is_finite() {
            return None;
        }
        let p = p.primitive_integer();
        let ints: Vec<BigInt> = p.coeffs().iter().map(|c| c.numer().clone()).collect();
        // The bracket [u − 2·x_tol, u + 2·x_tol] as dyadic rationals m / 2^k.
        let lo = Dyadic::from_f64(u - 2.0 * x_tol)?;
        let hi = Dyadic::from_f64(u + 2.0 * x_tol)?;
        let (s_lo, s_hi) = (lo.sign_of(&ints), hi.sign_of(&ints));
        if s_lo == 0 {
            return Some(lo.to_rat());
        }
        if s_hi == 0 {
            return Some(hi.to_rat());
        }
        if s_lo != s_hi {
            // A sign change: bisect on the sign of p itself (exact, no Sturm sequence).
            let (mut lo, mut hi) = (lo, hi);
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
        // No sign change: a root of even multiplicity (or two roots) in the bracket. Exact
        // Sturm isolation of the distinct roots there, the one nearest u refined.
        let (a, b) = (lo.to_rat(), hi.to_rat());
        let seq = p.sturm().ok()?;
        let uq = Rat::from_f64_exact(u)?;
        let iv = p.isolate_roots(&a, &b).ok()?.into_iter().min_by_key(|iv| {
            let mid = (&iv.lo + &iv.hi) / Rat::from_integer(2.into());
            (mid - &uq).abs()
        })?;
        let iv = seq.refine_interval(&iv, bits);
        Some((&iv.lo + &iv.hi) / Rat::from_integer(2.into()))
    }
}

/// A dyadic rational `m / 2^k`, for exact bisection without `BigRational` normalisation.
#[derive(Clone, Debug)]
struct Dyadic {
    m: BigInt,
    k: u32,
}

impl Dyadic {
    /// The exact value of a finite `f64`.
    fn from_f64(x: f64) -> Option<Self> {
        let r = Rat::from_f64_exact(x)?;
        let k = r.denom().bits().checked_sub(1)?; // denominators of f64 values are 2^k
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

    /// Whether `|self| > 2^-bits`.
    fn exceeds(&self, bits: u32) -> bool {
        // |m| / 2^k > 2^-bits  ⇔  |m| · 2^bits > 2^k.
        let lhs = self.m.abs() << bits as usize;
        lhs > (BigInt::one() << self.k as usize)
    }

    /// The sign of `Σ c_i x^i` at `x = m / 2^k`: of `Σ c_i m^i 2^{k(n−i)}`, by Horner.
    fn sign_of(&self, coeffs: &[BigInt]) -> i8 {
        let mut acc = BigInt::zero();
        let mut scale = BigInt::one(); // 2^{k·j} for the j-th step from the top
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

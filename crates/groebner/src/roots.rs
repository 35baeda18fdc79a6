//! [`SolveScalar`]: the two coefficient fields [`solve`](crate::solve) runs over, and their
//! bridge to `poly`'s certified real-root finders (the crate has no root finder of its own).

use poly::{BiPoly, Poly, Rat, Scalar};

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
}

impl SolveScalar for Rat {
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
}

//! [`SolveScalar`]: the two coefficient fields [`solve`](crate::solve) runs over, and their
//! bridge to `poly`'s certified real-root finders (the crate has no root finder of its own).

use poly::{Poly, Rat, RootStats, Scalar, real_roots_of_coeffs_into};

mod sealed {
    pub trait Sealed {}
    impl Sealed for f64 {}
    impl Sealed for poly::Rat {}
}

/// A scalar type [`solve`](crate::solve) accepts: `f64` (fast mode) or [`Rat`] (exact mode).
/// Sealed: the two implementations are the only ones. The algebra (reduction, Gröbner bases,
/// resultants) needs only [`poly::Scalar`]; this adds what solving needs from `poly`.
pub trait SolveScalar: Scalar + sealed::Sealed {
    /// Appends to `out` the distinct real roots in `[range[0], range[1]]` of the polynomial
    /// with coefficients `coeffs` (lowest power first), sorted, each within `x_tol`, by
    /// `poly`'s certified isolation (Bernstein/Descartes for `f64`, exact Sturm for `Rat`).
    /// `coeffs` is given back trimmed of trailing zeros. A constant polynomial has none.
    fn real_roots_into(
        coeffs: &mut Vec<Self>,
        range: [f64; 2],
        x_tol: f64,
        stats: &mut RootStats,
        out: &mut Vec<f64>,
    );

    /// Exact mode: the bit size of the largest coefficient of the polynomial with these
    /// coefficients (in any layout) scaled to a primitive integer polynomial; `None` for
    /// `f64`.
    fn coeff_bits(coeffs: &[Self]) -> Option<u64>;

    /// Exact mode: a rational within `2^-bits` (absolute) of a real root of the polynomial
    /// with coefficients `coeffs` that lies within `2·x_tol` of `u`, a value returned by
    /// [`real_roots_into`](SolveScalar::real_roots_into) with the same `x_tol`
    /// ([`Poly::<Rat>::root_near`]). `None` in `f64` mode, or when no root is found there.
    ///
    /// Why: back-substituting `u` into a basis element `v + h(u)` is only as accurate as
    /// `|h'(u)|·|u − u_r|`, and `h'` can be enormous (1.5e18 on a teapot piece, see
    /// `paper-notes/groebner.md` §5), so the `f64` value of the root is not enough even though
    /// the basis is exact.
    fn sharpen_root(coeffs: &[Self], u: f64, x_tol: f64, bits: u32) -> Option<Self>;

    /// The exact value, as a rational (`None` for a non-finite `f64`).
    fn to_rat(&self) -> Option<Rat>;
}

impl SolveScalar for f64 {
    fn real_roots_into(
        coeffs: &mut Vec<f64>,
        range: [f64; 2],
        x_tol: f64,
        stats: &mut RootStats,
        out: &mut Vec<f64>,
    ) {
        real_roots_of_coeffs_into(coeffs, range, x_tol, stats, out);
    }

    fn coeff_bits(_: &[f64]) -> Option<u64> {
        None
    }

    fn sharpen_root(_: &[f64], _: f64, _: f64, _: u32) -> Option<f64> {
        None
    }

    fn to_rat(&self) -> Option<Rat> {
        Rat::from_f64_exact(*self)
    }
}

impl SolveScalar for Rat {
    fn real_roots_into(
        coeffs: &mut Vec<Rat>,
        range: [f64; 2],
        x_tol: f64,
        _: &mut RootStats,
        out: &mut Vec<f64>,
    ) {
        let p = Poly::new(std::mem::take(coeffs));
        if let (true, Some(a), Some(b)) = (
            p.degree() > 0,
            Rat::from_f64_exact(range[0]),
            Rat::from_f64_exact(range[1]),
        ) {
            // Coefficients of many hundred bits make the Sturm sequence expensive; the
            // primitive integer form has the same roots and smaller entries. Errors are
            // impossible (finite ends, x_tol > 0, p non-constant); on one, no roots.
            out.extend(
                p.primitive_integer()
                    .real_roots(&a, &b, x_tol)
                    .unwrap_or_default(),
            );
        }
        *coeffs = p.into_coeffs();
    }

    fn coeff_bits(coeffs: &[Rat]) -> Option<u64> {
        let flat = Poly::new(coeffs.to_vec());
        if flat.is_zero() {
            return None;
        }
        flat.primitive_integer()
            .coeffs()
            .iter()
            .map(|c| c.numer().bits())
            .max()
    }

    fn sharpen_root(coeffs: &[Rat], u: f64, x_tol: f64, bits: u32) -> Option<Rat> {
        Poly::new(coeffs.to_vec()).root_near(u, 2.0 * x_tol, bits)
    }

    fn to_rat(&self) -> Option<Rat> {
        Some(self.clone())
    }
}

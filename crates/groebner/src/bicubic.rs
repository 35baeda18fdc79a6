//! [`Bicubic`]: a polynomial of degree ≤ 3 in `u` and in `v` in a fixed-size array, the shape
//! of one equation of a ray against a bicubic (or smaller) patch (article §2 eq. 5). The
//! per-ray path of the solver works on these, with no allocation.

use poly::{BiPoly, Scalar};

/// Coefficients per row (powers `u⁰ … u³`) and rows (powers `v⁰ … v³`) of a [`Bicubic`].
pub(crate) const BICUBIC_SIDE: usize = 4;

/// A polynomial of degree ≤ 3 in `u` and in `v`: `c[4 * j + i]` is the coefficient of
/// `u^i v^j`.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub(crate) struct Bicubic {
    pub(crate) c: [f64; BICUBIC_SIDE * BICUBIC_SIDE],
}

impl Bicubic {
    /// The `f64` values of a [`BiPoly`] that fits (stride and rows ≤ 4); `None` otherwise.
    pub(crate) fn from_bipoly<T: Scalar>(p: &BiPoly<T>) -> Option<Self> {
        if p.stride() > BICUBIC_SIDE || p.rows() > BICUBIC_SIDE {
            return None;
        }
        let mut c = [0.0; BICUBIC_SIDE * BICUBIC_SIDE];
        for (j, row) in p.rows_iter().enumerate() {
            for (i, a) in row.iter().enumerate() {
                c[BICUBIC_SIDE * j + i] = a.nearest_f64();
            }
        }
        Some(Bicubic { c })
    }

    /// The rows (coefficients of `v^j`, lowest power of `u` first), lowest `j` first.
    pub(crate) fn rows(&self) -> std::slice::ChunksExact<'_, f64> {
        self.c.chunks_exact(BICUBIC_SIDE)
    }

    /// The value at `(u, v)` by nested Horner (as [`BiPoly::eval`]).
    pub(crate) fn eval(&self, u: f64, v: f64) -> f64 {
        self.rows().rev().fold(0.0, |acc, row| {
            acc * v + row.iter().rev().fold(0.0, |a, c| a * u + c)
        })
    }

    /// The coefficients in `v`, each a polynomial in `u` (`bezout_bicubic`'s layout).
    pub(crate) fn coeffs_in_v(&self) -> [[f64; BICUBIC_SIDE]; BICUBIC_SIDE] {
        std::array::from_fn(|j| std::array::from_fn(|i| self.c[BICUBIC_SIDE * j + i]))
    }
}

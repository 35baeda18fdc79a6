//! The polynomial a root query runs on: [`Stored`], its coefficients as stored (owned or
//! borrowed), and [`Slack`], the caller's bound on how far the true polynomial may lie from
//! them. Both are read by every layer of the isolation (`isolate`, `certified`, `shifted`),
//! so they live here, below the public query types of `query.rs`.

use std::cell::Cell;
use std::thread::LocalKey;

use crate::univariate::Poly;

/// A caller's bound on how far the true polynomial may lie from the stored one, as a
/// function of the radius: `slack(R) ≥ Σₖ |Δcₖ|·Rᵏ`, where `Δcₖ` is the difference between
/// the true and the stored coefficient of `xᵏ`. It must be non-decreasing in `R` (any such
/// sum is). See [`RootQuery::value_slack`](crate::RootQuery::value_slack).
///
/// Why a function and not one number for the whole range: on a run over `[a, b]` the
/// isolator needs the bound only at `R = max(|a|, |b|)`, and the certified search's fresh runs
/// on pieces near 0 (and the refinement of a bracket) then get a smaller one. One number taken
/// at the far end of a wide range grows like `Rᴺ` and, at degree 32, swamps the values near
/// the roots (`paper-notes/implicit-surfaces.md` §6).
#[derive(Clone, Copy)]
pub(crate) struct Slack<'a>(Option<&'a dyn Fn(f64) -> f64>);

/// Relative widening of the radius at which [`Slack`] is asked: a run on `(lo, hi]` works on
/// `[lo, lo + w]` with `w = hi − lo` rounded up, which reaches at most `2u·max(|lo|, |hi|)`
/// past `hi`; `4ε = 8u` covers that and the rounding of the product.
const SLACK_RADIUS_MARGIN: f64 = 1.0 + 4.0 * f64::EPSILON;

impl<'a> Slack<'a> {
    /// No slack: the stored polynomial is the true one.
    pub(crate) const NONE: Slack<'static> = Slack(None);

    /// The slack `f(r)` on `[−r, r]`.
    pub(crate) fn new(f: &'a dyn Fn(f64) -> f64) -> Self {
        Slack(Some(f))
    }

    /// True when a slack function was given.
    #[inline]
    pub(crate) fn is_some(&self) -> bool {
        self.0.is_some()
    }

    /// The slack valid on `[−r, r]` (widened by [`SLACK_RADIUS_MARGIN`]); 0 without a slack
    /// function, `+∞` for an infinite `r` or a NaN answer (nothing can then be certified).
    #[inline]
    pub(crate) fn at(&self, r: f64) -> f64 {
        match self.0 {
            None => 0.0,
            Some(f) => {
                let s = f(r.abs() * SLACK_RADIUS_MARGIN);
                if s >= 0.0 { s } else { f64::INFINITY }
            }
        }
    }
}

impl std::fmt::Debug for Slack<'_> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(if self.0.is_some() {
            "Slack(fn)"
        } else {
            "Slack(none)"
        })
    }
}

thread_local! {
    /// The per-thread copy of a borrowed polynomial's coefficients, reused across queries.
    static BORROWED: Cell<Vec<f64>> = const { Cell::new(Vec::new()) };
}

/// Runs `f` on the polynomial with coefficients `coeffs` (trailing zeros trimmed), built in
/// the per-thread buffer `buf` and handed back to it afterwards, so repeated calls allocate
/// nothing. A nested call on the same buffer finds it taken and
/// allocates a fresh one: correct, only slower.
pub(crate) fn with_scratch_poly<R>(
    buf: &'static LocalKey<Cell<Vec<f64>>>,
    coeffs: &[f64],
    f: impl FnOnce(&Poly<f64>) -> R,
) -> R {
    let mut v = buf.take();
    v.clear();
    v.extend_from_slice(coeffs);
    let p = Poly::new_raw(v);
    let r = f(&p);
    buf.set(p.into_coeffs());
    r
}

/// The polynomial a query runs on: its coefficients (lowest first, last one not zero), and
/// the [`Poly`] holding them when the query was made from one.
///
/// Why: the certified `f64` path reads only the coefficients, so a query on a caller's
/// buffer ([`PolyRef`](crate::PolyRef)) runs on the slice itself; only the rare paths that
/// need a `Poly` (exact rationals, the Sturm heuristics) get one, from [`Stored::with_poly`].
/// The per-query copy into a per-thread `Poly` it replaces was ≈ 130 instructions of a torus
/// ray's ≈ 1 100 (`docs/speed.md`, "Where the teapots' slowdown came from").
#[derive(Clone, Copy, Debug)]
pub(crate) struct Stored<'a> {
    coeffs: &'a [f64],
    owned: Option<&'a Poly<f64>>,
}

impl<'a> Stored<'a> {
    /// The coefficients of `p`.
    pub(crate) fn owned(p: &'a Poly<f64>) -> Self {
        Stored {
            coeffs: p.coeffs(),
            owned: Some(p),
        }
    }

    /// Borrowed coefficients, trailing zeros already trimmed (as
    /// [`PolyRef::new`](crate::PolyRef::new) does).
    pub(crate) fn borrowed(coeffs: &'a [f64]) -> Self {
        debug_assert!(coeffs.last() != Some(&0.0), "trimmed");
        Stored {
            coeffs,
            owned: None,
        }
    }

    /// The coefficients, lowest degree first; empty for the zero polynomial.
    #[inline]
    pub(crate) fn coeffs(&self) -> &'a [f64] {
        self.coeffs
    }

    /// The degree, as [`Poly::degree`].
    #[inline]
    pub(crate) fn degree(&self) -> usize {
        self.coeffs.len().saturating_sub(1)
    }

    /// `p / x^k` when the `k` lowest coefficients are zero: the rest of the slice, no copy.
    pub(crate) fn without_lowest(&self, k: usize) -> Stored<'a> {
        Stored {
            coeffs: &self.coeffs[k..],
            owned: None,
        }
    }

    /// Runs `f` on the polynomial as a [`Poly`]: the caller's own, or a copy in the per-thread
    /// buffer (see [`with_scratch_poly`]).
    pub(crate) fn with_poly<R>(&self, f: impl FnOnce(&Poly<f64>) -> R) -> R {
        match self.owned {
            Some(p) => f(p),
            None => with_scratch_poly(&BORROWED, self.coeffs, f),
        }
    }
}

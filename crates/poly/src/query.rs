//! [`PolyRef`] and [`RootQuery`]: root queries on borrowed coefficients, with optional
//! statistics.
//!
//! A caller that keeps its coefficients in its own buffer (a ray tracer's per-thread scratch
//! vector, a stack array) wraps them in a [`PolyRef`] and asks for roots, without lending a
//! `Vec` to [`Poly::new`] and taking it back:
//!
//! ```
//! use poly::{PolyRef, RootOptions};
//! let c = [-2.0, 0.0, 1.0, 0.0]; // x² − 2, with a trailing zero the view trims
//! let r = PolyRef::new(&c).roots(0.0, f64::INFINITY, &RootOptions::new(1e-12)).smallest()?;
//! assert!(r.is_some_and(|r| (r - 2f64.sqrt()).abs() <= 1e-12));
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```
//!
//! The query is a small builder in the manner of kurbo's and polycool's slice-based solvers:
//! the range and [`RootOptions`] first, [`RootStats`] only when the caller wants them
//! ([`RootQuery::stats`]), then one of [`smallest`](RootQuery::smallest),
//! [`all`](RootQuery::all), [`all_into`](RootQuery::all_into) or
//! [`isolate`](RootQuery::isolate). The answers and their guarantees are those of the
//! [`Poly`] methods of the same purpose (`try_smallest_root`, `real_roots_with`,
//! `real_roots_into`, `isolate_roots_with`), which are the one implementation.

use std::cell::Cell;
use std::thread::LocalKey;

use crate::root_error::RootError;
use crate::root_interval::RootInterval;
use crate::root_options::RootOptions;
use crate::stats::RootStats;
use crate::univariate::{Poly, root_bound_of};

/// A polynomial over `f64` whose coefficients (lowest degree first) live in a borrowed slice.
///
/// [`PolyRef::new`] drops trailing exact zeros by narrowing the slice (no copy), so a view
/// always satisfies the invariant of [`Poly`]: the last coefficient is not zero.
///
/// # Examples
/// ```
/// use poly::{Poly, PolyRef};
/// let buf = [1.0, -3.0, 2.0, 0.0, 0.0];
/// let p = PolyRef::new(&buf);
/// assert_eq!(p.degree(), 2);
/// assert_eq!(p.coeffs(), &[1.0, -3.0, 2.0]);
/// assert_eq!(Poly::new(buf.to_vec()).as_poly_ref(), p);
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PolyRef<'a> {
    coeffs: &'a [f64],
}

impl<'a> PolyRef<'a> {
    /// A view of `c0 + c1·x + … + cn·x^n` with `coeffs = [c0, c1, …, cn]`, trailing exact
    /// zeros (`0.0` and `-0.0`) excluded. No coefficient is rejected here; the queries check
    /// finiteness ([`RootError::NonFiniteCoefficient`]).
    pub fn new(coeffs: &'a [f64]) -> Self {
        let n = coeffs.iter().rposition(|&c| c != 0.0).map_or(0, |i| i + 1);
        PolyRef {
            coeffs: &coeffs[..n],
        }
    }

    /// The coefficients, lowest degree first; empty for the zero polynomial.
    pub fn coeffs(&self) -> &'a [f64] {
        self.coeffs
    }

    /// The degree (0 for constants and for the zero polynomial, as [`Poly::degree`]).
    pub fn degree(&self) -> usize {
        self.coeffs.len().saturating_sub(1)
    }

    /// True for the zero polynomial.
    pub fn is_zero(&self) -> bool {
        self.coeffs.is_empty()
    }

    /// [`Poly::root_bound`] of the viewed polynomial, without copying it.
    pub fn root_bound(&self) -> Option<f64> {
        root_bound_of(self.coeffs)
    }

    /// A root query on `(lo, hi]` with `opts` and no statistics (see [`RootQuery`]).
    /// Infinite ends are accepted.
    pub fn roots(self, lo: f64, hi: f64, opts: &RootOptions) -> RootQuery<'a, 'static> {
        RootQuery {
            coeffs: self.coeffs,
            owned: None,
            range: (lo, hi),
            opts: *opts,
            stats: None,
        }
    }
}

impl Poly<f64> {
    /// A borrowed view of the coefficients.
    pub fn as_poly_ref(&self) -> PolyRef<'_> {
        PolyRef::new(self.coeffs())
    }

    /// A root query on `(lo, hi]` with `opts` and no statistics (see [`RootQuery`]): the
    /// same answers as the `Poly` methods, with the statistics optional.
    ///
    /// # Examples
    /// ```
    /// use poly::{Poly, RootOptions, RootStats};
    /// let p = Poly::<f64>::from_roots(&[-1.0, 0.5, 2.0]);
    /// let opts = RootOptions::new(1e-12);
    /// assert_eq!(p.roots(-10.0, 10.0, &opts).all()?.len(), 3);
    /// let mut stats = RootStats::default();
    /// let first = p.roots(0.0, 10.0, &opts).stats(&mut stats).smallest()?;
    /// assert!(first.is_some_and(|r| (r - 0.5).abs() <= 1e-12));
    /// assert_eq!(stats.queries, 1);
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn roots(&self, lo: f64, hi: f64, opts: &RootOptions) -> RootQuery<'_, 'static> {
        let mut q = self.as_poly_ref().roots(lo, hi, opts);
        q.owned = Some(self);
        q
    }
}

/// A root query being built: polynomial, range `(lo, hi]`, options, and optionally the
/// statistics to fill in. Made by [`PolyRef::roots`] or [`Poly::roots`].
///
/// # Accuracy
/// Each answer is that of the [`Poly`] method of the same purpose with the same options:
/// certified for [`IsolationMethod::Bernstein`](crate::IsolationMethod::Bernstein) (the
/// default) and [`IsolationMethod::Exact`](crate::IsolationMethod::Exact), heuristic for the
/// two Sturm methods (which report [`RootError::Unresolved`] rather than a guess when their
/// refinement stalls).
///
/// # Cost
/// A query on a [`PolyRef`] copies the `n + 1` coefficients once into a per-thread buffer
/// that is reused across queries (the isolation machinery works on a [`Poly`]), so it
/// allocates nothing once the buffer has grown to size.
#[derive(Debug)]
#[must_use = "a query does nothing until one of `smallest`, `all`, `all_into` or `isolate` runs it"]
pub struct RootQuery<'p, 's> {
    coeffs: &'p [f64],
    /// The polynomial itself, when the query was made from a [`Poly`] (no copy needed).
    owned: Option<&'p Poly<f64>>,
    range: (f64, f64),
    opts: RootOptions,
    stats: Option<&'s mut RootStats>,
}

thread_local! {
    /// The per-thread copy of a borrowed polynomial's coefficients, reused across queries.
    static BORROWED: Cell<Vec<f64>> = const { Cell::new(Vec::new()) };
}

/// Runs `f` on the polynomial with coefficients `coeffs` (trailing zeros trimmed), built in the per-thread buffer `buf` and handed back to it afterwards, so
/// repeated calls allocate nothing. A nested call on the same buffer finds it taken and
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

impl<'p, 's> RootQuery<'p, 's> {
    /// Fills in `stats` (counters are added to, never reset).
    pub fn stats<'t>(self, stats: &'t mut RootStats) -> RootQuery<'p, 't> {
        RootQuery {
            coeffs: self.coeffs,
            owned: self.owned,
            range: self.range,
            opts: self.opts,
            stats: Some(stats),
        }
    }

    /// Runs `f` on the polynomial, the range, the options and the statistics (the caller's,
    /// or a throw-away set).
    fn run<R>(
        self,
        f: impl FnOnce(&Poly<f64>, (f64, f64), &RootOptions, &mut RootStats) -> R,
    ) -> R {
        // Zeroed only when the caller keeps no statistics: `RootStats` is ~300 bytes, and
        // clearing it on every query was a measurable share of a torus ray (a memset per
        // query; docs/speed.md, "Redesign before/after").
        let mut local;
        let stats = match self.stats {
            Some(s) => s,
            None => {
                local = RootStats::default();
                &mut local
            }
        };
        match self.owned {
            Some(p) => f(p, self.range, &self.opts, stats),
            None => with_scratch_poly(&BORROWED, self.coeffs, |p| {
                f(p, self.range, &self.opts, stats)
            }),
        }
    }

    /// The smallest distinct real root in `(lo, hi]`, as
    /// [`Poly::try_smallest_root`] (the ray tracer's query). An infinite end is first replaced
    /// by Cauchy's bound (see [`Poly::smallest_root`]).
    ///
    /// # Errors
    /// As [`Poly::try_smallest_root`].
    pub fn smallest(self) -> Result<Option<f64>, RootError> {
        self.run(|p, (lo, hi), o, s| p.try_smallest_root(lo, hi, o, s))
    }

    /// Every distinct real root in `(lo, hi]`, sorted, as [`Poly::real_roots_with`].
    ///
    /// # Errors
    /// As [`Poly::real_roots_with`].
    pub fn all(self) -> Result<Vec<f64>, RootError> {
        let mut out = Vec::new();
        self.all_into(&mut out)?;
        Ok(out)
    }

    /// [`all`](Self::all) appended to a caller's buffer, as [`Poly::real_roots_into`] (on an
    /// error `out` is left as it was).
    ///
    /// # Errors
    /// As [`Poly::real_roots_into`].
    pub fn all_into(self, out: &mut Vec<f64>) -> Result<(), RootError> {
        self.run(|p, (lo, hi), o, s| p.real_roots_into(lo, hi, o, s, out))
    }

    /// Isolating intervals of every distinct real root in `(lo, hi]`, as
    /// [`Poly::isolate_roots_with`].
    ///
    /// # Errors
    /// As [`Poly::isolate_roots_with`].
    pub fn isolate(self) -> Result<Vec<RootInterval<f64>>, RootError> {
        self.run(|p, (lo, hi), o, s| p.isolate_roots_with(lo, hi, o, s))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn borrowed_and_owned_queries_agree_and_stats_are_optional() {
        let p = Poly::<f64>::from_roots(&[-3.0, 0.25, 1.5, 7.0]);
        let buf: Vec<f64> = p.coeffs().iter().copied().chain([0.0, -0.0]).collect();
        let view = PolyRef::new(&buf);
        assert_eq!(view.coeffs(), p.coeffs(), "trailing zeros excluded");
        let o = RootOptions::new(1e-13);
        let want = p.real_roots(-10.0, 10.0, 1e-13).unwrap();
        assert_eq!(view.roots(-10.0, 10.0, &o).all().unwrap(), want, "all");
        let mut s = RootStats::default();
        let first = view.roots(0.0, 10.0, &o).stats(&mut s).smallest().unwrap();
        assert_eq!(first, p.smallest_root(0.0, 10.0, 1e-13), "smallest");
        assert_eq!((s.queries, s.with_root), (1, 1), "stats filled in");
        let ivs = view.roots(-10.0, 10.0, &o).isolate().unwrap();
        assert_eq!(ivs, p.isolate_roots(-10.0, 10.0).unwrap(), "isolate");
        let mut out = vec![99.0];
        view.roots(-10.0, 0.0, &o).all_into(&mut out).unwrap();
        assert_eq!(out, vec![99.0, want[0]], "appended");
        assert_eq!(
            PolyRef::new(&[0.0, 0.0]).roots(0.0, 1.0, &o).smallest(),
            Err(RootError::ZeroPolynomial),
            "all-zero buffer is the zero polynomial"
        );
    }
}

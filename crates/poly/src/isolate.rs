//! Root queries (seed §3.5.2–3.5.3): [`Poly::smallest_root`], [`Poly::isolate_roots`] and
//! [`Poly::real_roots`] for `f64` and [`Rat`] polynomials, with the method dispatch.
//!
//! The default `f64` path is certified at `f64` speed: signs at the interval ends are
//! certified with a rigorous Horner bound, the roots are isolated by Descartes' rule in the
//! Bernstein basis with rigorous coefficient error bounds ([`IsolationMethod::Bernstein`]),
//! and refined inside certified brackets. An exact factor `x^k` is divided out first; a piece
//! where a sign cannot be certified gets a fresh run with its own error bound, and what `f64`
//! still cannot decide goes to adaptive precision (double-double, then 256 … 1024-bit floats,
//! with rigorous bounds: [`RootStats::adaptive_pieces`]; `multiprec.rs`). Only a node that even
//! that cannot decide — a multiple root, roots within one `f64` spacing — is isolated with
//! exact rational arithmetic on the same stored polynomial, on that node
//! ([`RootStats::exact_fallbacks`]; `certified.rs`). See `paper-notes/isolation.md`.

use std::cell::Cell;

use crate::bernstein::{Bracket, few_roots_likely};
use crate::certified::{CertifiedSearch, Found, end_signs};
use crate::closed_form::{linear_smallest, quadratic_smallest};
use crate::eval_bound::certified_sign;
use crate::exact_oracle::{ExactOracle, SquareFreeSign};
use crate::guess::{GUESS_DEGREES, Guess, smallest_by_guess};
use crate::inclusion::{INCLUSION_MIN_DEGREE, Piece, real_pieces};
use crate::multiprec::refine_wide;
use crate::refine::{
    Refined, bisect_rational_to_f64, half_tol, probe_by, refine_bracket, refine_exact_f64,
};
use crate::root_error::RootError;
use crate::root_interval::RootInterval;
use crate::root_options::{IsolationMethod, RefineMethod, RootOptions, Tolerance};
use crate::scalar::{Rat, rat_from_f64, rat_to_f64};
use crate::stam::StamSturm;
use crate::stats::RootStats;
use crate::stored::{Slack, Stored, with_scratch_poly};
use crate::sturm::{SturmSequence, check_finite, exact_zero_at};
use crate::univariate::{
    Poly, QPoly, ROOT_BOUND_MARGIN, UNIT_ROUNDOFF, cauchy_bound_of, root_bound_of,
};

/// Most bisections of a heuristic (floating-point Sturm) isolation before it gives up: the
/// interval is then narrower than 2^-200 of the original, far below `f64` resolution.
const MAX_HEURISTIC_BISECTIONS: u32 = 200;

/// A validated `f64` query range.
enum Range {
    /// Nothing to search: empty interval or a non-zero constant.
    Empty,
    /// Search `(lo, hi]`; both finite unless no finite root bound exists.
    Search { lo: f64, hi: f64 },
}

/// Validates a query: `Ok(false)` when there is nothing to search (empty interval or a
/// non-zero constant).
fn validate(c: &[f64], t_min: f64, t_max: f64, opts: &RootOptions) -> Result<bool, RootError> {
    check_finite(c)?;
    if c.is_empty() {
        return Err(RootError::ZeroPolynomial);
    }
    if t_min.is_nan() || t_max.is_nan() {
        return Err(RootError::NanBound);
    }
    if !opts.tolerance_is_valid() {
        return Err(RootError::InvalidTolerance);
    }
    Ok(c.len() > 1 && t_min < t_max)
}

/// Validates a query and narrows `(t_min, t_max]` to the root bound.
fn prepare(c: &[f64], t_min: f64, t_max: f64, opts: &RootOptions) -> Result<Range, RootError> {
    if !validate(c, t_min, t_max, opts)? {
        return Ok(Range::Empty);
    }
    let (mut lo, mut hi) = (t_min, t_max);
    // Cauchy's bound first (divisions only); the tighter `root_bound` (with Fujiwara's, which
    // takes n `powf`s) only when the range reaches beyond it.
    let n = c.len() - 1;
    let inv_lc = 1.0 / c[n].abs();
    let cauchy = c[..n].iter().fold(0.0f64, |m, x| m.max(x.abs() * inv_lc));
    let cauchy = (1.0 + cauchy) * ROOT_BOUND_MARGIN;
    // An infinite Cauchy bound (a quotient overflowed) bounds nothing: `root_bound` may.
    if !(cauchy.is_finite() && lo >= -cauchy && hi <= cauchy)
        && let Some(b) = root_bound_of(c)
    {
        // Every real root is in [−B, B]: the open end moves just below −B.
        if lo < -b {
            lo = (-b).next_down();
        }
        if hi > b {
            hi = b;
        }
    }
    if lo >= hi {
        return Ok(Range::Empty);
    }
    Ok(Range::Search { lo, hi })
}

/// An answer of an all-roots query placed on the line: a root, or an isolating interval.
trait Placed {
    /// Its lowest and highest points.
    fn ends(&self) -> (f64, f64);
}

impl Placed for f64 {
    fn ends(&self) -> (f64, f64) {
        (*self, *self)
    }
}

impl Placed for RootInterval<f64> {
    fn ends(&self) -> (f64, f64) {
        (self.lo, self.hi)
    }
}

/// Every root in `(lo, hi]` of `p = x^k·q` (`q(0) ≠ 0`), appended to `out` in order: those
/// of `q` below 0, the root 0 itself (`zero`) when it lies in the range, then those of `q`
/// above 0.
///
/// First `whole` answers `q` on the whole range in one go — the inclusion discs
/// ([`inclusion_first`]), which approximate every complex root of `q` whatever the range, so
/// asking them once per side did their work twice (Chebyshev and Legendre polynomials of odd
/// degree took 2–2.8× the subdivision's time at degrees 5–11) — and 0 goes in between. If
/// `whole` declines, or one of its answers reaches 0 (a root of `q` closer to 0 than its
/// bracket's width, which would not sort), `side` answers each sub-range alone, as before.
/// One query for the statistics: at most one exact fallback, though each part may have
/// needed one.
fn around_zero<V: Placed>(
    q: &Poly<f64>,
    (lo, hi): (f64, f64),
    zero: V,
    stats: &mut RootStats,
    out: &mut Vec<V>,
    whole: impl FnOnce(&Poly<f64>, f64, f64, &mut RootStats, &mut Vec<V>) -> Result<bool, RootError>,
    mut side: impl FnMut(&Poly<f64>, f64, f64, &mut RootStats, &mut Vec<V>) -> Result<(), RootError>,
) -> Result<(), RootError> {
    let fallbacks = stats.exact_fallbacks;
    let start = out.len();
    if whole(q, lo, hi, stats, out)? {
        let answers = &out[start..];
        if answers.iter().all(|v| {
            let (a, b) = v.ends();
            b < 0.0 || a > 0.0
        }) {
            if lo < 0.0 && 0.0 <= hi {
                let at = start + answers.partition_point(|v| v.ends().1 < 0.0);
                out.insert(at, zero);
            }
            stats.exact_fallbacks = stats.exact_fallbacks.min(fallbacks + 1);
            return Ok(());
        }
        out.truncate(start);
    }
    side(q, lo, hi.min(0.0), stats, out)?;
    if lo < 0.0 && 0.0 <= hi {
        out.push(zero);
    }
    side(q, lo.max(0.0), hi, stats, out)?;
    stats.exact_fallbacks = stats.exact_fallbacks.min(fallbacks + 1);
    Ok(())
}

/// `part(lo, hi)` on `(lo, hi]`, or on `(lo, 0]` and then `(0, hi]` when `split` and the
/// range holds 0 inside: the subdivision of a part the discs left undecided around an exact
/// root 0 of `p = x^k·q`, on each side as [`around_zero`]'s sides would run it — the run's
/// rounding bound, `γ·Σ|cᵢ|(|a| + w)ⁱ` on `[a, a + w]`, is tightest from 0 outwards (the
/// peers bench's planted degree 160, where such a part crosses 0: 162 ms a query with the part
/// whole, 133–140 ms split, as with the sides alone before the discs ran once).
fn at_zero(
    lo: f64,
    hi: f64,
    split: bool,
    mut part: impl FnMut(f64, f64) -> Result<(), RootError>,
) -> Result<(), RootError> {
    if split && lo < 0.0 && 0.0 < hi {
        part(lo, 0.0)?;
        part(0.0, hi)
    } else {
        part(lo, hi)
    }
}

/// The order `k ≥ 1` of the root 0 when the `k` lowest coefficients of `p` are exactly zero,
/// so that `p = x^k·q` with `q(0) ≠ 0`, exactly; else 0. Every method divides the factor out;
/// none does with a value slack.
///
/// Why: the `k`-fold root at 0 is a multiple root, which Descartes' rule can never isolate
/// (every node around it keeps sign changes), so the certified query used to end in the
/// exact fallback. Resultants of ray/patch systems have this factor whenever a patch edge
/// collapses to a point (the teapot's lid apex and bottom): measured on the teapot corpus,
/// every exact fallback was such a factor (`paper-notes/isolation.md`). The `f64` Sturm
/// heuristics counted through the noise of `p`'s values near 0 and silently lost the root 0
/// or roots next to it (test `heuristics_missed_roots_next_to_an_exact_root_0`); on `q` the
/// value at 0 is an exact non-zero coefficient. The exact method, whose Descartes isolation
/// needs a square-free polynomial, took the exact Sturm sequence of `p`'s square-free part
/// instead — 45 s a query on a degree-31 fuzz case with coefficients to 5e297 (test
/// `exact_method_on_a_double_root_0_took_the_square_free_path`). Dividing by `x^k` is exact,
/// so the answer stays that of the stored polynomial.
fn zero_root_order(c: &[f64], slack: Slack<'_>) -> usize {
    // With a value slack the stored zeros are not the true polynomial's.
    if slack.is_some() {
        return 0;
    }
    let k = c.iter().take_while(|x| **x == 0.0).count();
    if k < c.len() { k } else { 0 }
}

thread_local! {
    /// The coefficients of the last quotient `p/x^k` built on this thread, kept for the next
    /// one: the tracer's per-ray queries then allocate nothing after the first.
    static QUOTIENT: Cell<Vec<f64>> = const { Cell::new(Vec::new()) };
}

/// Runs `f` on `q = p/x^k` (the coefficients of `p` from index `k` on), built in a per-thread
/// buffer that is reused across queries.
fn with_quotient<R>(p: &Poly<f64>, k: usize, f: impl FnOnce(&Poly<f64>) -> R) -> R {
    with_scratch_poly(&QUOTIENT, &p.coeffs()[k..], f)
}

/// Relative widening of Cauchy's bound `1 + max|cᵢ/cₙ|` computed in `f64` (`n` divisions,
/// one addition, each rounded by at most `u`): `8u = 4ε` covers them with room to spare, so
/// every root lies strictly inside `(−B, B)`.
const CAUCHY_ROUNDING_MARGIN: f64 = 1.0 + 8.0 * UNIT_ROUNDOFF;

/// The smallest-root query's range with an infinite end replaced by Cauchy's bound, widened
/// by [`CAUCHY_ROUNDING_MARGIN`]. Why Cauchy's and not [`Poly::root_bound`]: it takes `n`
/// divisions where Fujiwara's takes `n` `powf`s, and for the first root the looser end costs
/// nothing measurable (the ray tracer's unbounded surfaces query `(0, ∞]` on every ray;
/// `paper-notes/implicit-surfaces.md`). The range is unchanged when both ends are finite or
/// there is no bound (constants, the zero polynomial).
fn cauchy_narrowed(c: &[f64], lo: f64, hi: f64) -> (f64, f64) {
    if lo.is_finite() && hi.is_finite() {
        return (lo, hi);
    }
    let Some(b) = cauchy_bound_of(c).filter(|b| b.is_finite()) else {
        // No bound, or one that overflowed: `prepare` narrows with `root_bound` (the
        // all-roots queries do the same, so both answer on the same range).
        return (lo, hi);
    };
    let b = b * CAUCHY_ROUNDING_MARGIN;
    let lo = if lo == f64::NEG_INFINITY { -b } else { lo };
    let hi = if hi == f64::INFINITY { b } else { hi };
    (lo, hi)
}

/// For the all-roots queries: validates `(a, b]` and, when [`zero_root_order`] is `k ≥ 1`
/// and the range is not empty, returns `k` with the narrowed range. The caller then answers
/// `q = p/x^k` ([`with_quotient`]) on `(lo, min(hi, 0)]`, adds the root 0 when
/// `lo < 0 ≤ hi`, and answers `q` on `(max(lo, 0), hi]` — sorted and disjoint since
/// `q(0) ≠ 0`.
fn zero_root_split(
    p: &Poly<f64>,
    a: f64,
    b: f64,
    opts: &RootOptions,
    slack: Slack<'_>,
) -> Result<Option<(usize, f64, f64)>, RootError> {
    if p.coeffs().first() != Some(&0.0) {
        // The common case, without validating twice (the caller's path validates).
        return Ok(None);
    }
    let Range::Search { lo, hi } = prepare(p.coeffs(), a, b, opts)? else {
        return Ok(None);
    };
    let k = zero_root_order(p.coeffs(), slack);
    Ok((k > 0).then_some((k, lo, hi)))
}

impl Poly<f64> {
    /// The smallest distinct real root in `(t_min, t_max]`, within `x_tol` — the ray tracer's
    /// query. `None` when there is no root there, and also for refused input (see
    /// [`try_smallest_root`](Poly::try_smallest_root) for the reason).
    ///
    /// Runs the default certified method ([`IsolationMethod::Bernstein`] +
    /// [`RefineMethod::NewtonBisection`], closed forms for degrees 1–2). It stops at the first root:
    /// roots further along are never isolated.
    ///
    /// # Accuracy
    /// Certified for the stored coefficients, whatever the rounding:
    /// * let `ρ` be the smallest distinct real root of the stored polynomial in
    ///   `(t_min, t_max]` (a root exactly at `t_min` is excluded, one exactly at `t_max`
    ///   included); the value returned is within `x_tol` of `ρ` (absolute), or within one
    ///   `f64` spacing of it when `x_tol` is smaller than that spacing;
    /// * the returned value itself may lie up to `x_tol` outside `(t_min, t_max]` when `ρ` is
    ///   that close to an end;
    /// * `None` means there is certainly no root in `(t_min, t_max]`.
    ///
    /// Multiple roots are found (a tangent ray's double root is a root); the multiplicity is
    /// not reported. `t_min = −∞` and `t_max = +∞` are accepted. Roots are those of the
    /// polynomial *as stored*: rounding that happened while building the coefficients is not
    /// undone. `x_tol = 0` asks for the root to one `f64` spacing. Cost grows like
    /// `log(1/x_tol)` with the default refinement; where `f64` cannot certify a sign the
    /// piece is redone in double-double and then in 256 … 1024-bit floats
    /// ([`RootStats::adaptive_pieces`]), still certified. Only a multiple root of the stored
    /// polynomial, two roots within one `f64` spacing, or a root exactly on an interval end
    /// can need exact rational arithmetic on a tiny piece ([`RootStats::exact_fallbacks`]),
    /// which is much slower; the answer is the same.
    ///
    /// # Examples
    /// ```
    /// use poly::Poly;
    /// // (t − 1)(t − 2)(t − 3)(t − 4): the first root after t = 1.5 is 2.
    /// let p = Poly::<f64>::from_roots(&[1.0, 2.0, 3.0, 4.0]);
    /// let t = p.smallest_root(1.5, 10.0, 1e-12).unwrap();
    /// assert!((t - 2.0).abs() <= 1e-12);
    /// assert_eq!(p.smallest_root(4.0, 10.0, 1e-12), None); // the root at 4 is excluded
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn smallest_root(&self, t_min: f64, t_max: f64, x_tol: f64) -> Option<f64> {
        let mut stats = RootStats::default();
        self.smallest_root_with(t_min, t_max, &RootOptions::new(x_tol), &mut stats)
    }

    /// [`smallest_root`](Poly::smallest_root) with explicit options and statistics.
    ///
    /// # Accuracy
    /// As for [`smallest_root`](Poly::smallest_root) with `opts.x_tol` when
    /// `opts.isolation` is [`IsolationMethod::Bernstein`] or [`IsolationMethod::Exact`].
    /// [`IsolationMethod::Sturm`] and [`IsolationMethod::StamSturm`] are heuristics: their
    /// counts can be wrong, so they can miss a root or report a wrong one.
    pub fn smallest_root_with(
        &self,
        t_min: f64,
        t_max: f64,
        opts: &RootOptions,
        stats: &mut RootStats,
    ) -> Option<f64> {
        self.try_smallest_root(t_min, t_max, opts, stats)
            .ok()
            .flatten()
    }

    /// [`smallest_root_with`](Poly::smallest_root_with), telling refused input apart from
    /// "no root".
    ///
    /// # Errors
    /// [`RootError::NonFiniteCoefficient`], [`RootError::ZeroPolynomial`],
    /// [`RootError::NanBound`], [`RootError::InvalidTolerance`]. An empty or reversed
    /// interval is not an error: it holds no root (`Ok(None)`).
    pub fn try_smallest_root(
        &self,
        t_min: f64,
        t_max: f64,
        opts: &RootOptions,
        stats: &mut RootStats,
    ) -> Result<Option<f64>, RootError> {
        self.try_smallest_root_slack(t_min, t_max, opts, Slack::NONE, stats)
    }

    /// [`try_smallest_root`](Poly::try_smallest_root) for every polynomial within `slack`
    /// of the stored one ([`RootQuery::value_slack`](crate::RootQuery::value_slack)).
    pub(crate) fn try_smallest_root_slack(
        &self,
        t_min: f64,
        t_max: f64,
        opts: &RootOptions,
        slack: Slack<'_>,
        stats: &mut RootStats,
    ) -> Result<Option<f64>, RootError> {
        try_smallest(Stored::owned(self), t_min, t_max, opts, slack, stats)
    }

    /// Isolating intervals of every distinct real root in `(a, b]`, sorted and disjoint, by
    /// the default certified method.
    ///
    /// # Accuracy
    /// Certified: each [`RootInterval`] holds exactly one distinct root of the stored
    /// polynomial (in the open interval, or exactly at a point interval), and no root of
    /// `(a, b]` is missed. The intervals are not narrowed beyond what isolation needed; use
    /// [`real_roots`](Poly::real_roots) for values. One caveat: two distinct roots closer than
    /// one `f64` spacing cannot be separated by `f64` numbers; their intervals may then
    /// overlap by that spacing.
    ///
    /// # Errors
    /// As [`try_smallest_root`](Poly::try_smallest_root); an empty or reversed interval gives
    /// an empty vector.
    ///
    /// # Examples
    /// ```
    /// use poly::Poly;
    /// let p = Poly::<f64>::from_roots(&[-1.5, 0.25, 3.0]);
    /// let ivs = p.isolate_roots(-10.0, 10.0)?;
    /// assert_eq!(ivs.len(), 3);
    /// assert!(ivs[1].lo <= 0.25 && 0.25 <= ivs[1].hi);
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn isolate_roots(&self, a: f64, b: f64) -> Result<Vec<RootInterval<f64>>, RootError> {
        let mut stats = RootStats::default();
        self.isolate_roots_with(a, b, &RootOptions::default(), &mut stats)
    }

    /// [`isolate_roots`](Poly::isolate_roots) with explicit options (the isolation method is
    /// used, the refinement options are not) and statistics.
    ///
    /// # Accuracy
    /// Certified for [`IsolationMethod::Bernstein`] and [`IsolationMethod::Exact`]; the two
    /// Sturm methods are heuristics and their intervals are half-open `(lo, hi]` by their
    /// counts.
    pub fn isolate_roots_with(
        &self,
        a: f64,
        b: f64,
        opts: &RootOptions,
        stats: &mut RootStats,
    ) -> Result<Vec<RootInterval<f64>>, RootError> {
        let mut out = Vec::new();
        stats.record_all(self.degree(), |s| {
            self.isolate_roots_push(a, b, opts, s, &mut out)?;
            Ok(out.len())
        })?;
        Ok(out)
    }

    /// Appends the isolating intervals of the roots in `(a, b]` to `out`.
    fn isolate_roots_push(
        &self,
        a: f64,
        b: f64,
        opts: &RootOptions,
        stats: &mut RootStats,
        out: &mut Vec<RootInterval<f64>>,
    ) -> Result<(), RootError> {
        if let Some((k, lo, hi)) = zero_root_split(self, a, b, opts, Slack::NONE)? {
            let zero = RootInterval { lo: 0.0, hi: 0.0 };
            return with_quotient(self, k, |q| {
                around_zero(
                    q,
                    (lo, hi),
                    zero,
                    stats,
                    out,
                    |q, lo, hi, s, out| q.isolate_roots_by_discs(lo, hi, opts, true, s, out),
                    |q, lo, hi, s, out| q.isolate_roots_push(lo, hi, opts, s, out),
                )
            });
        }
        if self.isolate_roots_by_discs(a, b, opts, false, stats, out)? {
            return Ok(());
        }
        self.isolate_roots_subdivide(a, b, opts, stats, out)
    }

    /// [`inclusion_first`] for [`Poly::isolate_roots_push`]: `Ok(true)` when the budgeted
    /// subdivision or the discs answered (the discs' undecided parts subdivided, each split at
    /// 0 when `split_at_zero`: see [`around_zero`]).
    fn isolate_roots_by_discs(
        &self,
        a: f64,
        b: f64,
        opts: &RootOptions,
        split_at_zero: bool,
        stats: &mut RootStats,
        out: &mut Vec<RootInterval<f64>>,
    ) -> Result<bool, RootError> {
        inclusion_first(
            self,
            a,
            b,
            opts,
            Slack::NONE,
            stats,
            |_, b, _| RootInterval { lo: b.lo, hi: b.hi },
            |r| RootInterval { lo: r, hi: r },
            |search, _, out| {
                out.extend(found_intervals(search));
                Ok(())
            },
            |lo, hi, s, out| {
                at_zero(lo, hi, split_at_zero, |lo, hi| {
                    self.isolate_roots_subdivide(lo, hi, opts, s, out)
                })
            },
            out,
        )
    }

    /// The isolating intervals of the roots in `(a, b]` by subdivision (the certified
    /// search, or the method `opts` names), appended to `out`.
    fn isolate_roots_subdivide(
        &self,
        a: f64,
        b: f64,
        opts: &RootOptions,
        stats: &mut RootStats,
        out: &mut Vec<RootInterval<f64>>,
    ) -> Result<(), RootError> {
        match self.isolate_inner(a, b, opts, Slack::NONE, stats)? {
            Isolation::Certified(search) => out.extend(found_intervals(&search)),
            Isolation::Exact(_, ivs) | Isolation::Heuristic(ivs) => out.extend(ivs),
        }
        Ok(())
    }

    /// Every distinct real root in `(a, b]`, sorted, each within `x_tol`, by the default
    /// certified method.
    ///
    /// # Accuracy
    /// Certified: one value per distinct root of the stored polynomial in `(a, b]`, none
    /// missed, each within `x_tol` of its root (absolute; within one `f64` spacing when
    /// `x_tol` is smaller: no `f64` lies strictly between the value and its root).
    /// Multiplicities are not reported. Cost: isolation plus `O(log(1/x_tol))` evaluations
    /// per root. `x_tol = 0` (full `f64` accuracy) stays in `f64` and double-double for
    /// simple roots and for roots that are exact `f64` numbers of any multiplicity (a
    /// multiple one is certified by its cluster of inclusion discs and an exact divisibility
    /// check, `paper-notes/isolation.md`, "Full precision"); a multiple root of the stored
    /// polynomial that is not an `f64` number (`(3x − 1)²`) is still answered exactly, by
    /// exact arithmetic on its piece alone ([`RootStats::exact_fallbacks`]).
    ///
    /// # Errors
    /// As [`try_smallest_root`](Poly::try_smallest_root).
    ///
    /// # Examples
    /// ```
    /// use poly::Poly;
    /// let p = Poly::new(vec![-2.0, 0.0, 1.0]); // x² − 2
    /// let r = p.real_roots(f64::NEG_INFINITY, f64::INFINITY, 1e-14)?;
    /// assert_eq!(r.len(), 2);
    /// assert!((r[1] - 2f64.sqrt()).abs() <= 1e-14);
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn real_roots(&self, a: f64, b: f64, x_tol: f64) -> Result<Vec<f64>, RootError> {
        let mut stats = RootStats::default();
        self.real_roots_with(a, b, &RootOptions::new(x_tol), &mut stats)
    }

    /// [`real_roots`](Poly::real_roots) with explicit options and statistics.
    ///
    /// # Accuracy
    /// As [`real_roots`](Poly::real_roots) for the certified methods; heuristic for the two
    /// Sturm methods.
    pub fn real_roots_with(
        &self,
        a: f64,
        b: f64,
        opts: &RootOptions,
        stats: &mut RootStats,
    ) -> Result<Vec<f64>, RootError> {
        let mut out = Vec::new();
        self.real_roots_into(a, b, opts, stats, &mut out)?;
        Ok(out)
    }

    /// [`real_roots_with`](Poly::real_roots_with) into a caller's buffer: the roots are
    /// appended to `out` (sorted among themselves; `out` is not cleared). With a buffer reused
    /// across queries, the default certified path allocates nothing once the buffer (and this
    /// thread's scratch for an exact `x^k` factor) has grown to size — what the ray tracer's
    /// per-ray algebra needs. The exact fallback, when a query needs it
    /// ([`RootStats::exact_fallbacks`]), does allocate.
    ///
    /// # Accuracy
    /// As [`real_roots`](Poly::real_roots).
    ///
    /// # Errors
    /// As [`try_smallest_root`](Poly::try_smallest_root); on an error `out` is left as it was.
    ///
    /// # Examples
    /// ```
    /// use poly::{Poly, RootOptions, RootStats};
    /// let mut roots = Vec::with_capacity(8);
    /// let mut stats = RootStats::default();
    /// let p = Poly::new(vec![0.0, 0.0, -2.0, 0.0, 1.0]); // x²(x² − 2)
    /// p.real_roots_into(-2.0, 2.0, &RootOptions::new(1e-14), &mut stats, &mut roots)?;
    /// assert_eq!(roots.len(), 3);
    /// assert_eq!(roots[1], 0.0);
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn real_roots_into(
        &self,
        a: f64,
        b: f64,
        opts: &RootOptions,
        stats: &mut RootStats,
        out: &mut Vec<f64>,
    ) -> Result<(), RootError> {
        self.real_roots_into_slack(a, b, opts, Slack::NONE, stats, out)
    }

    /// [`real_roots_into`](Poly::real_roots_into) for every polynomial within `slack` of
    /// the stored one ([`RootQuery::value_slack`](crate::RootQuery::value_slack)).
    pub(crate) fn real_roots_into_slack(
        &self,
        a: f64,
        b: f64,
        opts: &RootOptions,
        slack: Slack<'_>,
        stats: &mut RootStats,
        out: &mut Vec<f64>,
    ) -> Result<(), RootError> {
        let before = out.len();
        let found = stats.record_all(self.degree(), |s| {
            refuse_inapplicable_slack(self.coeffs(), a, b, opts, slack)?;
            self.real_roots_push(a, b, opts, slack, s, out)?;
            Ok(out.len() - before)
        });
        if found.is_err() {
            out.truncate(before);
        }
        found.map(|_| ())
    }

    fn real_roots_push(
        &self,
        a: f64,
        b: f64,
        opts: &RootOptions,
        slack: Slack<'_>,
        stats: &mut RootStats,
        out: &mut Vec<f64>,
    ) -> Result<(), RootError> {
        if let Some((k, lo, hi)) = zero_root_split(self, a, b, opts, slack)? {
            return with_quotient(self, k, |q| {
                around_zero(
                    q,
                    (lo, hi),
                    0.0,
                    stats,
                    out,
                    |q, lo, hi, s, out| q.real_roots_by_discs(lo, hi, opts, slack, true, s, out),
                    |q, lo, hi, s, out| q.real_roots_push(lo, hi, opts, slack, s, out),
                )
            });
        }
        if self.real_roots_by_discs(a, b, opts, slack, false, stats, out)? {
            return Ok(());
        }
        self.real_roots_subdivide(a, b, opts, slack, stats, out)
    }

    /// [`inclusion_first`] for [`Poly::real_roots_push`]: `Ok(true)` when the budgeted
    /// subdivision or the discs answered (roots refined, the discs' undecided parts
    /// subdivided, each split at 0 when `split_at_zero`: see [`around_zero`]).
    #[allow(
        clippy::too_many_arguments,
        reason = "the query's parts, passed through"
    )]
    fn real_roots_by_discs(
        &self,
        a: f64,
        b: f64,
        opts: &RootOptions,
        slack: Slack<'_>,
        split_at_zero: bool,
        stats: &mut RootStats,
        out: &mut Vec<f64>,
    ) -> Result<bool, RootError> {
        let refine = |p: &Poly<f64>, b, s: &mut RootStats| {
            refine_certified(Stored::owned(p), b, opts.tolerance(), opts.refine, s)
        };
        let subdivide = |lo, hi, s: &mut RootStats, out: &mut Vec<f64>| {
            at_zero(lo, hi, split_at_zero, |lo, hi| {
                self.real_roots_subdivide(lo, hi, opts, slack, s, out)
            })
        };
        inclusion_first(
            self,
            a,
            b,
            opts,
            slack,
            stats,
            refine,
            |r| r,
            |search, s, out| self.push_refined(search, opts, slack, s, out),
            subdivide,
            out,
        )
    }

    /// The roots the certified search `search` of `self` found, refined and appended to
    /// `out`.
    fn push_refined(
        &self,
        search: &CertifiedSearch<'_>,
        opts: &RootOptions,
        slack: Slack<'_>,
        stats: &mut RootStats,
        out: &mut Vec<f64>,
    ) -> Result<(), RootError> {
        if let Some((lo, hi)) = search.slack_limited {
            return Err(RootError::SlackLimited { lo, hi });
        }
        for f in &search.found {
            out.push(refine_found(
                Stored::owned(self),
                search,
                f,
                opts,
                slack,
                stats,
            )?);
        }
        Ok(())
    }

    /// The roots in `(a, b]` by subdivision (the certified search, or the method `opts`
    /// names), refined and appended to `out`.
    fn real_roots_subdivide(
        &self,
        a: f64,
        b: f64,
        opts: &RootOptions,
        slack: Slack<'_>,
        stats: &mut RootStats,
        out: &mut Vec<f64>,
    ) -> Result<(), RootError> {
        match self.isolate_inner(a, b, opts, slack, stats)? {
            Isolation::Certified(search) => self.push_refined(&search, opts, slack, stats, out)?,
            Isolation::Exact(seq, ivs) => {
                out.extend(
                    ivs.iter()
                        .map(|iv| refine_exact_interval(&seq, iv, opts.tolerance())),
                );
            }
            Isolation::Heuristic(ivs) => {
                for iv in &ivs {
                    out.push(refine_heuristic(self, iv, opts, stats)?);
                }
            }
        }
        Ok(())
    }

    fn isolate_inner<'p>(
        &'p self,
        a: f64,
        b: f64,
        opts: &RootOptions,
        slack: Slack<'p>,
        stats: &mut RootStats,
    ) -> Result<Isolation<'p>, RootError> {
        let (lo, hi) = match prepare(self.coeffs(), a, b, opts)? {
            // Nothing to search: no roots (any variant with an empty list says so).
            Range::Empty => return Ok(Isolation::Heuristic(Vec::new())),
            Range::Search { lo, hi } => (lo, hi),
        };
        Ok(match opts.isolation {
            IsolationMethod::Bernstein => {
                if lo.is_finite() && hi.is_finite() {
                    Isolation::Certified(CertifiedSearch::run(
                        self.coeffs(),
                        lo,
                        hi,
                        false,
                        slack,
                        stats,
                    ))
                } else {
                    stats.exact_fallbacks += 1;
                    exact_isolation(self, lo, hi, false, stats)
                }
            }
            IsolationMethod::Exact => exact_isolation(self, lo, hi, false, stats),
            IsolationMethod::Sturm => {
                let seq = self.sturm()?;
                Isolation::Heuristic(bisect_isolate(
                    self.coeffs(),
                    |x, y| seq.count_roots_checked(x, y),
                    lo,
                    hi,
                    false,
                    stats,
                )?)
            }
            IsolationMethod::StamSturm => match StamSturm::new(self) {
                Some(s) => Isolation::Heuristic(bisect_isolate(
                    self.coeffs(),
                    |x, y| s.count_roots_checked(x, y),
                    lo,
                    hi,
                    false,
                    stats,
                )?),
                None => Isolation::Heuristic(Vec::new()),
            },
        })
    }
}

/// Splits a degree that the subdivision tried before the inclusion discs may make
/// ([`inclusion_first`]): `2n` for degree `n`. A polynomial with few real roots far apart
/// (a ray's, a random one's) is isolated in a few splits; one with many real roots or exact
/// roots on dyadic points (Wilkinson's, multiple and clustered roots) gives up early, the
/// waste bounded by one `f64` run of at most `2n` de Casteljau splits. Measured against
/// `n`, `4n` and `8n` in `paper-notes/isolation.md`, "Subdivision first, on a budget": the
/// larger budgets gained little where the attempt answers and cost more where it gives up.
const SUBDIVISION_FIRST_SPLITS: u32 = 2;

/// Highest degree whose all-roots queries try the budgeted subdivision first. Above it a
/// single `f64` run within the budget answered few of the measured queries (the whole
/// range's error bound grows with the degree), and the attempt cost the others 4–8 %.
const SUBDIVISION_FIRST_MAX_DEGREE: usize = 10;

/// The all-roots queries' first try (issue 11): inclusion discs around simultaneous
/// approximations of every root (`inclusion.rs`), for the default certified method without
/// a value slack from degree [`INCLUSION_MIN_DEGREE`] on. `Ok(true)` when they answered the
/// query: each root an isolated disc decided went through `emit` into `out`, each exact
/// multiple root a cluster of discs certified (`inclusion.rs`, step 4) through `point`, and
/// each part of the range they left undecided through `subdivide` (on that part alone), all
/// in order.
/// Before the discs, a subdivision in `f64` with a budget of [`SUBDIVISION_FIRST_SPLITS`]
/// splits a degree ([`CertifiedSearch::run_budgeted`]): when it answers, its search goes
/// through `answer` and the discs are not computed (counted in
/// [`RootStats::subdivided_first`]); few real roots far apart, as on a ray or a random
/// polynomial, take it a few splits, where the discs approximate every complex root.
/// `Ok(false)` leaves `out` alone and the caller answers by subdivision. Counted in
/// [`RootStats::inclusion_decided`] (no part left), [`RootStats::inclusion_undecided`]
/// (some or all of the range subdivided) and [`RootStats::inclusion_subranges`].
#[allow(
    clippy::too_many_arguments,
    reason = "the query's parts, passed through"
)]
fn inclusion_first<V>(
    p: &Poly<f64>,
    a: f64,
    b: f64,
    opts: &RootOptions,
    slack: Slack<'_>,
    stats: &mut RootStats,
    mut emit: impl FnMut(&Poly<f64>, Bracket, &mut RootStats) -> V,
    point: impl Fn(f64) -> V,
    answer: impl FnOnce(&CertifiedSearch<'_>, &mut RootStats, &mut Vec<V>) -> Result<(), RootError>,
    mut subdivide: impl FnMut(f64, f64, &mut RootStats, &mut Vec<V>) -> Result<(), RootError>,
    out: &mut Vec<V>,
) -> Result<bool, RootError> {
    if opts.isolation != IsolationMethod::Bernstein
        || slack.is_some()
        || p.degree() < INCLUSION_MIN_DEGREE
    {
        return Ok(false);
    }
    let Range::Search { lo, hi } = prepare(p.coeffs(), a, b, opts)? else {
        return Ok(false);
    };
    if few_roots_likely(p.coeffs(), lo, hi) {
        // A narrow range with one root or none (the Gröbner path's eliminants on a
        // sub-patch): the subdivision's first classification is cheaper than the discs.
        return Ok(false);
    }
    // Not at full precision (`x_tol = rel_tol = 0`): the discs' approximations come polished
    // to the last bit, where a subdivision's bracket must be refined to it, near a cluster
    // with adaptive signs (the Orellana–De Michele quartics, `paper-notes/isolation.md`).
    let full_precision = opts.x_tol == 0.0 && opts.rel_tol == 0.0;
    if p.degree() <= SUBDIVISION_FIRST_MAX_DEGREE
        && !full_precision
        && let Some(search) = CertifiedSearch::run_budgeted(
            p.coeffs(),
            lo,
            hi,
            SUBDIVISION_FIRST_SPLITS * p.degree() as u32,
            stats,
        )
    {
        stats.subdivided_first += 1;
        answer(&search, stats, out)?;
        return Ok(true);
    }
    // One query for the statistics: at most one exact fallback, though several parts may
    // have needed one (as around an exact root 0).
    let fallbacks = stats.exact_fallbacks;
    let (mut parts, mut failed) = (0u64, Ok(()));
    let answered = real_pieces(p.coeffs(), lo, hi, |piece| {
        if failed.is_err() {
            return;
        }
        match piece {
            Piece::Root(br) => out.push(emit(p, br, stats)),
            Piece::Multiple(r) => out.push(point(r)),
            Piece::Undecided(l, h) => {
                parts += 1;
                failed = subdivide(l, h, stats, out);
            }
        }
    });
    failed?;
    stats.exact_fallbacks = stats.exact_fallbacks.min(fallbacks + 1);
    stats.inclusion_subranges += parts;
    if answered && parts == 0 {
        stats.inclusion_decided += 1;
    } else {
        stats.inclusion_undecided += 1;
    }
    Ok(answered)
}

/// The isolating intervals of the roots the certified search `search` found, in order.
fn found_intervals<'a>(
    search: &'a CertifiedSearch<'_>,
) -> impl Iterator<Item = RootInterval<f64>> + 'a {
    search.found.iter().map(|f| match f {
        Found::Bracket(b) => RootInterval { lo: b.lo, hi: b.hi },
        Found::Exact(iv) => iv.clone(),
        Found::Shifted(i, b) => search.shifts[*i as usize].interval(b),
    })
}

/// The isolation result, before conversion or refinement.
#[allow(
    clippy::large_enum_variant,
    reason = "a short-lived return value; boxing the search would allocate on every query"
)]
enum Isolation<'p> {
    /// The default certified search: `f64` brackets, and exact intervals where it needed them.
    Certified(CertifiedSearch<'p>),
    /// Exact isolation: the exact oracle (for refinement) and intervals with `f64` ends.
    Exact(ExactOracle, Vec<RootInterval<f64>>),
    /// Floating-point Sturm counts: intervals `(lo, hi]` by the counts.
    Heuristic(Vec<RootInterval<f64>>),
}

/// Descartes' rule of signs on the stored coefficients: with `lo ≥ 0`, no sign change
/// among the non-zero coefficients means no root in `(lo, hi] ⊂ (0, ∞)`; with `hi < 0`, none
/// among those of `p(−x)` means none in `(lo, hi] ⊂ (−∞, 0)`, and with `hi = 0` the same
/// holds when `p(0) = c₀ ≠ 0`. Exact: it reads stored signs only. It decides at once what
/// the Bernstein run, whose error bound is the whole range's `Σ|cᵢ||x|ⁱ`, can take many
/// subdivisions to see: a shadow ray leaving the plane `x = 1` of `x³² − 1` meets
/// `(1 + d·s)³² − 1 + δ` on `(0, B]`, all coefficients positive (issue 11; `docs/speed.md`,
/// "High-degree surfaces").
///
/// With a value slack `slack > 0` valid on `[−R, R]`, `R = max(|lo|, |hi|)`, each true
/// coefficient differs from the stored one by at most `slack/Rⁱ`; a coefficient's sign is
/// then used only when `|cᵢ|Rⁱ` (rounded down) exceeds the slack, and any coefficient within
/// it makes the rule say nothing (a true zero or either sign is possible).
fn no_root_by_descartes(c: &[f64], lo: f64, hi: f64, slack: f64) -> bool {
    let r = lo.abs().max(hi.abs());
    let changes = |flip: bool| {
        let mut last = 0i8;
        let mut r_i = 1.0f64;
        for (i, &ci) in c.iter().enumerate() {
            let mut s = if ci > 0.0 {
                1
            } else if ci < 0.0 {
                -1
            } else {
                0
            };
            if slack > 0.0 {
                // r_i = Rⁱ with i roundings; the product one more: (1 − 2(i + 2)ε) makes the
                // computed |cᵢ|Rⁱ a lower bound.
                let low = ci.abs() * r_i * (1.0 - 2.0 * (i + 2) as f64 * f64::EPSILON);
                // (A NaN is not above the slack either.)
                if low.partial_cmp(&slack) != Some(std::cmp::Ordering::Greater) {
                    return true;
                }
                r_i *= r;
            }
            if flip && i % 2 == 1 {
                s = -s;
            }
            if s != 0 {
                if last != 0 && s != last {
                    return true;
                }
                last = s;
            }
        }
        false
    };
    if lo >= 0.0 {
        !changes(false)
    } else if hi < 0.0 || (hi == 0.0 && c.first().is_some_and(|&c0| c0 != 0.0)) {
        !changes(true)
    } else {
        false
    }
}

/// How many radii [`no_root_past_start`] tries for the slack of each shifted coefficient:
/// `T = (hi − lo)·4⁻ʲ`, `j < 12`, a span of 4¹¹ ≈ 4·10⁶ (the slack is asked once per radius,
/// and only while some coefficient is undecided).
const PAST_START_RADII: usize = 12;

/// Descartes' rule at the range's start: with `lo ≥ 0`, the sign `s` of the true `p(lo)`
/// certified, and every stored coefficient `cₖ`, `k ≥ 1`, of that sign, the true `p(lo + t)`
/// has only coefficients of sign `s` — so no root in `(lo, ∞)`.
///
/// Why: the stored `qₖ = Σ_{j≥k} C(j, k)·cⱼ·lo^(j−k)` of `p(lo + t)` sum terms of one sign,
/// so `|qₖ| ≥ |cₖ|`, exactly (nothing is computed); the true ones differ by `Δqₖ`, the shift
/// of the slack's `Δc`, with `Σ|Δqₖ|Tᵏ ≤ Σ|Δcₖ|(lo + T)ᵏ ≤ slack(lo + T)` for *every*
/// `T > 0`, so `|Δqₖ| ≤ slack(lo + T)/Tᵏ` at the `T` of our choice, one per coefficient; and
/// `q₀ = p(lo)`. (The slack's contract includes that the true polynomial has no higher degree
/// than the stored one.) This decides the shadow rays leaving a high-degree surface, where
/// `c₀ = p(start)` is within the slack of zero and [`no_root_by_descartes`] says nothing: a
/// ray leaving the plane `x = 1` of `x³² − 1` meets `(1 + d·s)³² − 1 + δ`, and its search over
/// `(lo, 4B]` took a dozen Bernstein runs of degree 32 (issue 11, `docs/speed.md`).
fn no_root_past_start(c: &[f64], lo: f64, hi: f64, s_lo: i8, slack: Slack<'_>) -> bool {
    if !(lo >= 0.0 && s_lo != 0 && lo < hi) || c.len() < 2 {
        return false;
    }
    let same = |x: f64| if s_lo > 0 { x > 0.0 } else { x < 0.0 };
    if !c[1..].iter().all(|&x| same(x)) {
        return false;
    }
    if !slack.is_some() {
        return true;
    }
    // Bit k set: coefficient k shown to keep its sign. Degrees above 63 are not tried.
    let n = c.len() - 1;
    if n > 63 {
        return false;
    }
    let all = (u64::MAX >> (63 - n)) & !1;
    let mut decided = 0u64;
    let mut t = hi - lo;
    for _ in 0..PAST_START_RADII {
        let s = slack.at(lo + t);
        let mut t_k = 1.0f64;
        for (k, &ck) in c.iter().enumerate().skip(1) {
            t_k *= t;
            // |cₖ|·Tᵏ with k + 1 roundings, taken down by (1 − 2(k + 2)ε).
            let low = ck.abs() * t_k * (1.0 - 2.0 * (k + 2) as f64 * f64::EPSILON);
            if low > s {
                decided |= 1 << k;
            }
        }
        if decided == all {
            return true;
        }
        t *= 0.25;
    }
    false
}

/// Whether a value slack can apply to a query on `(lo, hi]`: not with an infinite end (no
/// finite radius bounds the difference), nor with the methods that certify only the stored
/// coefficients (exact) or nothing (the Sturm heuristics). Such queries are refused as
/// [`RootError::SlackLimited`] on the whole range (after the usual validation).
fn slack_applies(lo: f64, hi: f64, opts: &RootOptions) -> bool {
    opts.isolation == IsolationMethod::Bernstein && lo.is_finite() && hi.is_finite()
}

/// The refusal [`slack_applies`] describes, for the smallest-root and all-roots queries alike:
/// `Err` for a query with a value slack that cannot apply to it, after the usual validation.
fn refuse_inapplicable_slack(
    c: &[f64],
    lo: f64,
    hi: f64,
    opts: &RootOptions,
    slack: Slack<'_>,
) -> Result<(), RootError> {
    if slack.is_some() && !slack_applies(lo, hi, opts) {
        validate(c, lo, hi, opts)?;
        return Err(RootError::SlackLimited { lo, hi });
    }
    Ok(())
}

/// The smallest-root query on the stored polynomial `p`, owned or borrowed: counts it in
/// `stats` and runs [`smallest_inner`]. The one implementation behind
/// [`Poly::try_smallest_root`] and [`RootQuery::smallest`](crate::RootQuery::smallest).
pub(crate) fn try_smallest(
    p: Stored<'_>,
    t_min: f64,
    t_max: f64,
    opts: &RootOptions,
    slack: Slack<'_>,
    stats: &mut RootStats,
) -> Result<Option<f64>, RootError> {
    stats.count_query(p.degree());
    let result = smallest_inner(p, t_min, t_max, opts, slack, stats);
    match &result {
        Err(e) => stats.count_error(e),
        Ok(Some(_)) => stats.with_root += 1,
        Ok(None) => {}
    }
    result
}

fn smallest_inner(
    p: Stored<'_>,
    t_min: f64,
    t_max: f64,
    opts: &RootOptions,
    slack: Slack<'_>,
    stats: &mut RootStats,
) -> Result<Option<f64>, RootError> {
    refuse_inapplicable_slack(p.coeffs(), t_min, t_max, opts, slack)?;
    // Evaluated only for degrees 1 and 2 (every torus and Barth query passes here). With
    // a slack the closed forms do not apply (they certify against the stored polynomial).
    let closed_form = |opts: &RootOptions| {
        !slack.is_some() && opts.closed_form && opts.isolation == IsolationMethod::Bernstein
    };
    let degree = p.degree();
    if degree == 2 && closed_form(opts) {
        // The quadratic closed form first, on the range as it is (it takes infinite ends
        // as they come): when it decides, the root bound, the range narrowing and the
        // `x^k` check of the general path below are not needed (issue 12: they were a
        // fifth of a sphere query on the SPD sphereflakes). Undecided, the general path
        // runs as before.
        if !validate(p.coeffs(), t_min, t_max, opts)? {
            return Ok(None);
        }
        if let Some(answer) = quadratic_smallest(p.coeffs(), t_min, t_max, opts.tolerance()) {
            stats.closed_form += 1;
            return Ok(answer);
        }
    }
    let (lo, hi) = if degree == 1 && closed_form(opts) {
        // The linear closed form decides the root against the range as it is, infinite
        // ends included: a root bound would only cost divisions (the tracer queries a
        // plane on every ray). Only the certified method has closed forms: the others
        // need a finite range.
        if !validate(p.coeffs(), t_min, t_max, opts)? {
            return Ok(None);
        }
        (t_min, t_max)
    } else {
        let (t_min, t_max) = cauchy_narrowed(p.coeffs(), t_min, t_max);
        match prepare(p.coeffs(), t_min, t_max, opts)? {
            Range::Empty => return Ok(None),
            Range::Search { lo, hi } => (lo, hi),
        }
    };
    let k = zero_root_order(p.coeffs(), slack);
    if k > 0 {
        // p = x^k·q exactly: the roots are 0 and those of q, and q(0) ≠ 0.
        let q = p.without_lowest(k);
        return Ok(if lo < 0.0 && 0.0 <= hi {
            smallest_inner(q, lo, 0.0, opts, slack, stats)?.or(Some(0.0))
        } else {
            smallest_inner(q, lo, hi, opts, slack, stats)?
        });
    }
    match opts.isolation {
        IsolationMethod::Bernstein => certified_smallest(p, lo, hi, opts, slack, stats),
        IsolationMethod::Exact => {
            Ok(p.with_poly(|p| exact_smallest(p, lo, hi, opts.tolerance(), stats)))
        }
        IsolationMethod::Sturm => p.with_poly(|p| sturm_smallest(p, lo, hi, opts, stats)),
        IsolationMethod::StamSturm => p.with_poly(|p| match StamSturm::new(p) {
            Some(s) => match s.smallest_root(lo, hi, opts.x_tol)? {
                None if count_contradicted(p.coeffs(), lo, hi) => {
                    Err(RootError::Unresolved { lo, hi })
                }
                None => Ok(None),
                Some(t) => confirm_stam_root(p, t, lo, opts.x_tol).map(Some),
            },
            None => Ok(None),
        }),
    }
}

/// The default certified query: closed form, then Bernstein isolation, then refinement; with
/// a value slack, no closed form and no escalation beyond `f64` ([`RootError::SlackLimited`]).
fn certified_smallest(
    p: Stored<'_>,
    lo: f64,
    hi: f64,
    opts: &RootOptions,
    slack: Slack<'_>,
    stats: &mut RootStats,
) -> Result<Option<f64>, RootError> {
    let c = p.coeffs();
    if opts.closed_form && !slack.is_some() {
        // First: the closed forms take infinite ends as they come.
        let decided = match c.len() {
            2 => linear_smallest(c, lo, hi),
            3 => quadratic_smallest(c, lo, hi, opts.tolerance()),
            _ => None,
        };
        if let Some(answer) = decided {
            stats.closed_form += 1;
            return Ok(answer);
        }
    }
    let range_slack = slack.at(lo.abs().max(hi.abs()));
    if no_root_by_descartes(c, lo, hi, range_slack) {
        return Ok(None);
    }
    if !(lo.is_finite() && hi.is_finite()) {
        stats.exact_fallbacks += 1;
        return Ok(p.with_poly(|p| exact_smallest(p, lo, hi, opts.tolerance(), stats)));
    }
    let signs = end_signs(c, lo, hi, slack, range_slack);
    if no_root_past_start(c, lo, hi, signs.0, slack) {
        return Ok(None);
    }
    if hi - lo <= opts.tolerance().on(lo, hi) && signs.0 * signs.1 < 0 {
        // Every point of the interval is within x_tol of any root in it, and opposite end
        // signs prove one: no isolation needed (a shadow ray's "is anything in the way").
        return Ok(Some(lo + 0.5 * (hi - lo)));
    }
    if opts.refine == RefineMethod::NewtonBisection
        && GUESS_DEGREES.contains(&(c.len() - 1))
        && signs.0 != 0
    {
        match smallest_by_guess(c, lo, hi, signs, opts.tolerance(), (slack, range_slack)) {
            Guess::Root(x) => {
                stats.guessed += 1;
                return Ok(Some(x));
            }
            Guess::NoRoot => return Ok(None),
            Guess::Declined => {}
        }
    }
    let search =
        CertifiedSearch::run_with_signs(c, (lo, hi), signs, true, (slack, range_slack), stats);
    match (search.found.first(), search.slack_limited) {
        (Some(first), _) => refine_found(p, &search, first, opts, slack, stats).map(Some),
        (None, Some((lo, hi))) => Err(RootError::SlackLimited { lo, hi }),
        (None, None) => Ok(None),
    }
}

/// Refines one root of a certified search: a bracket in `f64` (exact finish if needed); an
/// exact interval also in `f64` when its end signs certify it as a bracket (it holds one
/// distinct root, so opposite signs make it one of odd multiplicity), else with the exact
/// sequence.
///
/// With a value slack only `f64` brackets occur (the search stops before any exact piece),
/// and a refinement that the slack stops is [`RootError::SlackLimited`] on its bracket.
fn refine_found(
    p: Stored<'_>,
    search: &CertifiedSearch<'_>,
    found: &Found,
    opts: &RootOptions,
    slack: Slack<'_>,
    stats: &mut RootStats,
) -> Result<f64, RootError> {
    if let (Found::Bracket(b), true) = (found, slack.is_some()) {
        // The slack is taken at the bracket's radius; when refinement stops, at the narrower
        // stuck bracket's (a slack of degree N falls like Rᴺ), and refinement goes on from
        // there; last, point by point.
        let (mut b, mut s) = (*b, search.top_slack.1);
        for _ in 0..MAX_SLACK_RETRIES {
            match refine_bracket(p.coeffs(), b, opts.tolerance(), opts.refine, s, stats) {
                Refined::Root(r) => return Ok(r),
                Refined::Stuck(stuck) => {
                    let tighter = slack.at(stuck.lo.abs().max(stuck.hi.abs()));
                    b = stuck;
                    if tighter.partial_cmp(&(MIN_SLACK_GAIN * s)) != Some(std::cmp::Ordering::Less)
                    {
                        break;
                    }
                    s = tighter;
                }
            }
        }
        return refine_pointwise(p.coeffs(), b, opts.tolerance(), slack);
    }
    let bracket = match found {
        Found::Shifted(i, b) => {
            let shift = &search.shifts[*i as usize];
            return Ok(shift.refine(p, b, opts.tolerance(), opts.refine, stats));
        }
        Found::Bracket(b) => Some(*b),
        Found::Exact(iv) if !iv.is_point() => {
            let c = p.coeffs();
            let s_lo = certified_sign(c, iv.lo, 0.0);
            (s_lo != 0 && certified_sign(c, iv.hi, 0.0) == -s_lo)
                .then(|| Bracket::new(iv.lo, iv.hi, s_lo))
        }
        Found::Exact(_) => None,
    };
    Ok(match (bracket, found, search.exact_sequence()) {
        (Some(b), _, _) => refine_certified(p, b, opts.tolerance(), opts.refine, stats),
        (None, Found::Bracket(_) | Found::Shifted(..), _) => {
            unreachable!("brackets are refined in f64")
        }
        (None, Found::Exact(iv), Some(seq)) => refine_exact_interval(seq, iv, opts.tolerance()),
        (None, Found::Exact(iv), None) => unreachable!("exact interval {iv:?} without a sequence"),
    })
}

/// Most restarts of a slack-limited refinement with the slack of its narrower bracket.
const MAX_SLACK_RETRIES: u32 = 4;

/// A restart of a slack-limited refinement is worth it only when the narrower bracket's
/// slack is below this fraction of the one that stopped it.
const MIN_SLACK_GAIN: f64 = 0.5;

/// Bisection of a bracket that the refinement's bracket-wide slack stopped, with each
/// midpoint's sign tested against the slack at that point's own radius (a value at `x` needs
/// only `slack(|x|)`, far below the bracket's when it reaches past the root of a high-degree
/// restriction). A midpoint within its slack of zero is the answer when the points `x_tol/2`
/// either side have the bracket's signs (the root is then within `x_tol/2` of it), else
/// [`RootError::SlackLimited`] on the bracket reached.
fn refine_pointwise(
    c: &[f64],
    b: Bracket,
    tol: Tolerance,
    slack: Slack<'_>,
) -> Result<f64, RootError> {
    let (mut lo, mut hi) = (b.lo, b.hi);
    while hi - lo > tol.on(lo, hi) * (1.0 - f64::EPSILON) && lo.next_up() < hi {
        let m = lo + 0.5 * (hi - lo);
        let m = if m > lo && m < hi { m } else { lo.next_up() };
        match certified_sign(c, m, slack.at(m)) {
            0 => {
                // The same probe as the `f64` refinement's (neighbouring doubles when
                // `x_tol/2` is lost in rounding), each point with the slack at its radius.
                let bracket = Bracket::new(lo, hi, b.s_lo);
                let delta = half_tol(tol.on(lo, hi));
                return probe_by(bracket, m, delta, |x| certified_sign(c, x, slack.at(x)))
                    .ok_or(RootError::SlackLimited { lo, hi });
            }
            s if s == b.s_lo => lo = m,
            _ => hi = m,
        }
    }
    Ok(lo + 0.5 * (hi - lo))
}

/// Refines a certified bracket; where `f64` gets stuck, finishes in adaptive precision, and
/// with exact signs only if even that cannot sign a point.
fn refine_certified(
    p: Stored<'_>,
    b: Bracket,
    tol: Tolerance,
    method: RefineMethod,
    stats: &mut RootStats,
) -> f64 {
    match refine_bracket(p.coeffs(), b, tol, method, 0.0, stats) {
        Refined::Root(r) => r,
        Refined::Stuck(b) => refine_wide(p.coeffs(), b, tol, stats).unwrap_or_else(|| {
            stats.refine_fallbacks += 1;
            p.with_poly(|p| refine_exact_f64(p, b, tol))
        }),
    }
}

/// Exact answer to the smallest-root query on `(lo, hi]` (bounds may be infinite).
fn exact_smallest(
    p: &Poly<f64>,
    lo: f64,
    hi: f64,
    tol: Tolerance,
    stats: &mut RootStats,
) -> Option<f64> {
    match exact_isolation(p, lo, hi, true, stats) {
        Isolation::Exact(seq, ivs) => ivs.first().map(|iv| refine_exact_interval(&seq, iv, tol)),
        _ => None,
    }
}

/// Exact isolation of the stored polynomial on `(lo, hi]` with `f64` interval ends: Descartes
/// bisection when it is certified square-free, else Sturm counts (seed §3.5.2), both exact
/// ([`ExactOracle`]).
fn exact_isolation(
    p: &Poly<f64>,
    lo: f64,
    hi: f64,
    first_only: bool,
    stats: &mut RootStats,
) -> Isolation<'static> {
    let q = p.to_rat().expect("finite coefficients were checked");
    let oracle = ExactOracle::new(&q);
    // Infinite ends: the exact Cauchy bound holds every root strictly inside (−B, B).
    let bound = q
        .cauchy_bound()
        .map(|b| rat_to_f64(&b).next_up())
        .unwrap_or(f64::MAX);
    let lo = if lo.is_finite() {
        lo
    } else {
        -bound.min(f64::MAX)
    };
    let hi = if hi.is_finite() {
        hi
    } else {
        bound.min(f64::MAX)
    };
    let out = oracle.isolate(lo, hi, first_only, stats);
    Isolation::Exact(oracle, out)
}

/// Refines an exact-isolation interval with exact signs and rounds to `f64`.
///
/// # Accuracy
/// Within `max(tol.abs, tol.rel·|root|)` of the root, or one `f64` spacing when that is
/// smaller.
fn refine_exact_interval(seq: &impl SquareFreeSign, iv: &RootInterval<f64>, tol: Tolerance) -> f64 {
    if iv.is_point() {
        return iv.lo;
    }
    let lo = rat_from_f64(iv.lo).expect("finite");
    let hi = rat_from_f64(iv.hi).expect("finite");
    refine_rat_to_f64(seq, lo, hi, tol)
}

/// Bisection with exact signs of the square-free part, from an open interval `(lo, hi)` with
/// one root (signs only at `hi` and midpoints), to `f64` accuracy `tol`.
fn refine_rat_to_f64(seq: &impl SquareFreeSign, lo: Rat, hi: Rat, tol: Tolerance) -> f64 {
    let s_hi = seq.sign_of_square_free_at(&hi);
    if s_hi == 0 {
        return rat_to_f64(&hi);
    }
    bisect_rational_to_f64(|x| seq.sign_of_square_free_at(x), lo, hi, s_hi, tol)
}

/// Stam's isolation algorithm (seed §3.5.2) with a floating-point count: keep halving
/// `(a, b]` until each piece holds one root by the count.
///
/// # Errors
/// [`RootError::Unresolved`] for a piece whose count is unknown (`count` gave `None`) or
/// provably wrong: zero while the stored polynomial `c` has certified opposite signs at the
/// piece's ends ([`count_contradicted`]); one while its end signs are not certified opposite
/// (nor `b` an exact root: [`confirmed_single`]), so the piece may hold no root or two; or
/// more than one in a piece too narrow to split. Issue 11: a heuristic never answers "no
/// root" against that evidence, nor hands out an interval that nothing confirms.
fn bisect_isolate(
    c: &[f64],
    count: impl Fn(f64, f64) -> Option<usize>,
    lo: f64,
    hi: f64,
    first_only: bool,
    stats: &mut RootStats,
) -> Result<Vec<RootInterval<f64>>, RootError> {
    let mut out = Vec::new();
    let mut stack = vec![(lo, hi, 0u32)];
    while let Some((a, b, depth)) = stack.pop() {
        let n = count(a, b).ok_or(RootError::Unresolved { lo: a, hi: b })?;
        if n == 0 {
            if count_contradicted(c, a, b) {
                return Err(RootError::Unresolved { lo: a, hi: b });
            }
            continue;
        }
        let m = 0.5 * a + 0.5 * b;
        if n == 1 || depth >= MAX_HEURISTIC_BISECTIONS || !(m > a && m < b) {
            if n != 1 || !confirmed_single(c, a, b) {
                return Err(RootError::Unresolved { lo: a, hi: b });
            }
            out.push(RootInterval { lo: a, hi: b });
            if first_only {
                break;
            }
            continue;
        }
        stats.subdivisions += 1;
        stack.push((m, b, depth + 1));
        stack.push((a, m, depth + 1));
    }
    Ok(out)
}

/// True when the stored polynomial `c` has certified, non-zero, opposite signs at `a` and
/// `b` (signs at an infinite end from the leading term): then `(a, b)` holds a root of odd
/// multiplicity, whatever a floating-point count says. Costs two bounded evaluations.
fn count_contradicted(c: &[f64], a: f64, b: f64) -> bool {
    // The degree past any stored zeros (`Poly::new_raw`).
    let n = c.iter().rposition(|&x| x != 0.0).unwrap_or(0);
    n > 0 && end_sign(c, a) * end_sign(c, b) < 0
}

/// True when the heuristic interval `(a, b]` is confirmed to hold a root: the stored
/// polynomial `c` has certified opposite signs at its ends (an infinite end signed by the
/// leading term, as in [`count_contradicted`]), or a certified sign at `a` and an exact zero
/// at `b` ([`exact_zero_at`]). Costs two bounded evaluations (and an exact one, rarely).
fn confirmed_single(c: &[f64], a: f64, b: f64) -> bool {
    if count_contradicted(c, a, b) {
        return true;
    }
    b.is_finite() && certified_sign(c, b, 0.0) == 0 && end_sign(c, a) != 0 && exact_zero_at(c, b)
}

/// Confirms the root `t` that Stam's search returned on `(lo, …]` with tolerance `x_tol`
/// (issue 11): the stored polynomial must change sign, by certified signs, between
/// `t − max(x_tol, one spacing)` (or `lo`, if later) and `t`, or vanish exactly at `t` — so a
/// root lies within `x_tol` (or one spacing) below `t`; and it must not change sign between
/// `lo` and that lower point, which would prove a smaller root his counts missed. Anything
/// else is [`RootError::Unresolved`] on `(lo, t]`. His value is returned unchanged.
fn confirm_stam_root(p: &Poly<f64>, t: f64, lo: f64, x_tol: f64) -> Result<f64, RootError> {
    let c = p.coeffs();
    let below = (t - x_tol).min(t.next_down()).max(lo);
    let s_below = end_sign(c, below);
    let s_t = certified_sign(c, t, 0.0);
    let brackets = s_below != 0 && (s_t == -s_below || (s_t == 0 && exact_zero_at(c, t)));
    if brackets && !count_contradicted(c, lo, below) {
        Ok(t)
    } else {
        Err(RootError::Unresolved { lo, hi: t })
    }
}

/// The certified sign of the stored polynomial `c` at `x`; at an infinite `x`, the sign of
/// the leading term there (0 for a NaN `x`).
fn end_sign(c: &[f64], x: f64) -> i8 {
    let Some(n) = c.iter().rposition(|&v| v != 0.0) else {
        return 0;
    };
    if x.is_nan() {
        0
    } else if x.is_finite() {
        certified_sign(c, x, 0.0)
    } else {
        let lead = if c[n] > 0.0 { 1 } else { -1 };
        if x < 0.0 && n % 2 == 1 { -lead } else { lead }
    }
}

/// Floating-point Sturm query (heuristic): leftmost interval by counts, then refinement.
fn sturm_smallest(
    p: &Poly<f64>,
    lo: f64,
    hi: f64,
    opts: &RootOptions,
    stats: &mut RootStats,
) -> Result<Option<f64>, RootError> {
    let Ok(seq) = p.sturm() else {
        return Ok(None);
    };
    let ivs = bisect_isolate(
        p.coeffs(),
        |x, y| seq.count_roots_checked(x, y),
        lo,
        hi,
        true,
        stats,
    )?;
    ivs.first()
        .map(|iv| refine_heuristic(p, iv, opts, stats))
        .transpose()
}

/// Refines a heuristic interval `(lo, hi]`. With certified opposite end signs it is a
/// certified bracket, refined as the certified path refines one (with an exact finish when
/// `f64` stalls); a certified-zero-free `lo` and an undecidable `hi` give `hi` when the
/// stored polynomial vanishes exactly there ([`exact_zero_at`]). Otherwise the
/// counts promised a root that no sign change confirms (a wrong count, or a root of even
/// multiplicity): the interval is reported as [`RootError::Unresolved`], never its midpoint
/// as a root (issue 11: roots 1e6 and 1e9 came back as 878 417.97 and 887 500 000).
fn refine_heuristic(
    p: &Poly<f64>,
    iv: &RootInterval<f64>,
    opts: &RootOptions,
    stats: &mut RootStats,
) -> Result<f64, RootError> {
    let c = p.coeffs();
    let (lo, hi) = (iv.lo.max(-f64::MAX), iv.hi.min(f64::MAX));
    let (s_lo, s_hi) = (certified_sign(c, lo, 0.0), certified_sign(c, hi, 0.0));
    if s_lo != 0 && s_hi == -s_lo {
        let b = Bracket::new(lo, hi, s_lo);
        Ok(refine_certified(
            Stored::owned(p),
            b,
            opts.tolerance(),
            opts.refine,
            stats,
        ))
    } else if s_hi == 0 && s_lo != 0 && exact_zero_at(c, hi) {
        // `p(hi)` is exactly zero. Within rounding of zero is not enough: `6.61x³ − … −
        // f64::MAX` got the Cauchy bound 2.72e307 as a root (issue 13 follow-up), and a
        // subnormal-coefficient case got 4.5e-13 for roots at ±1e-308 and 0 (issue 11).
        Ok(hi)
    } else {
        Err(RootError::Unresolved { lo, hi })
    }
}

impl QPoly {
    /// Isolating intervals of every distinct real root in `(a, b]`, exactly (seed §3.5.2:
    /// bisection driven by exact Sturm counts).
    ///
    /// # Exactness
    /// Exact and certified: each interval holds exactly one distinct root (open interval, or
    /// the point itself when `lo == hi`), intervals are disjoint and sorted, and no root in
    /// `(a, b]` is missed. A root at `a` is excluded, one at `b` included. An empty or
    /// reversed interval gives an empty vector.
    ///
    /// # Errors
    /// [`RootError::ZeroPolynomial`].
    ///
    /// # Complexity
    /// One exact Sturm sequence, then two evaluations of it per bisection; the number of
    /// bisections grows with `log(1/separation)` of the closest roots.
    ///
    /// # Examples
    /// ```
    /// use poly::{QPoly, Rat};
    /// let q = |n: i64, d: i64| Rat::new(n.into(), d.into());
    /// let p = QPoly::from_roots(&[q(1, 3), q(1, 2), q(2, 1)]);
    /// let ivs = p.isolate_roots(&q(0, 1), &q(2, 1))?;
    /// assert_eq!(ivs.len(), 3);
    /// assert!(ivs[2].is_point() && ivs[2].lo == q(2, 1)); // the end b = 2 is a root
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn isolate_roots(&self, a: &Rat, b: &Rat) -> Result<Vec<RootInterval<Rat>>, RootError> {
        let seq = self.sturm()?;
        Ok(isolate_rat(&seq, a, b, false))
    }

    /// Every distinct real root in `(a, b]`, sorted, as `f64` approximations.
    ///
    /// # Accuracy
    /// Each value is within `x_tol` of its exact root (absolute), or within one `f64` spacing
    /// when `x_tol` is smaller (refinement is exact; only the final rounding is inexact).
    ///
    /// # Errors
    /// [`RootError::ZeroPolynomial`], [`RootError::InvalidTolerance`].
    pub fn real_roots(&self, a: &Rat, b: &Rat, x_tol: f64) -> Result<Vec<f64>, RootError> {
        check_tol(x_tol)?;
        let seq = self.sturm()?;
        Ok(isolate_rat(&seq, a, b, false)
            .into_iter()
            .map(|iv| rat_interval_to_f64(&seq, iv, x_tol))
            .collect())
    }

    /// The smallest distinct real root in `(a, b]` as an `f64` within `x_tol`; `None` when
    /// there is none, for the zero polynomial, or for a NaN or negative `x_tol`.
    ///
    /// # Accuracy
    /// As [`real_roots`](Poly::real_roots); only the first root is isolated.
    pub fn smallest_root(&self, a: &Rat, b: &Rat, x_tol: f64) -> Option<f64> {
        check_tol(x_tol).ok()?;
        let seq = self.sturm().ok()?;
        isolate_rat(&seq, a, b, true)
            .into_iter()
            .next()
            .map(|iv| rat_interval_to_f64(&seq, iv, x_tol))
    }
}

impl SturmSequence<Rat> {
    /// Narrows an isolating interval of this sequence's polynomial to width at most
    /// `2^-bits`, exactly (bisection on the sign of the square-free part, seed §3.5.3).
    ///
    /// # Exactness
    /// Exact: the result holds the same root, in the open interval or as a point. The
    /// interval must come from [`Poly::<Rat>::isolate_roots`](Poly::isolate_roots) of the
    /// same polynomial (one root in the open interval).
    ///
    /// # Complexity
    /// About `bits + log2(width)` exact evaluations of `V₀`.
    pub fn refine_interval(&self, iv: &RootInterval<Rat>, bits: u32) -> RootInterval<Rat> {
        let width = Rat::new(1.into(), num_bigint::BigInt::from(1) << bits as usize);
        let (lo, hi) = crate::refine::refine_rational(self, &iv.lo, &iv.hi, &width);
        RootInterval { lo, hi }
    }
}

fn check_tol(x_tol: f64) -> Result<(), RootError> {
    if x_tol.is_nan() || x_tol < 0.0 || x_tol.is_infinite() {
        Err(RootError::InvalidTolerance)
    } else {
        Ok(())
    }
}

/// Exact isolation on rational bounds; intervals in the crate convention.
fn isolate_rat(
    seq: &SturmSequence<Rat>,
    a: &Rat,
    b: &Rat,
    first_only: bool,
) -> Vec<RootInterval<Rat>> {
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
            let iv = if seq.sign_of_square_free_at(&hi) == 0 {
                RootInterval { lo: hi.clone(), hi }
            } else {
                RootInterval { lo, hi }
            };
            out.push(iv);
            if first_only {
                break;
            }
            continue;
        }
        let mid = (&lo + &hi) / &two;
        let vm = seq.sign_changes_at(&mid);
        stack.push((mid.clone(), hi, vm, vhi));
        stack.push((lo, mid, vlo, vm));
    }
    out
}

fn rat_interval_to_f64(seq: &SturmSequence<Rat>, iv: RootInterval<Rat>, x_tol: f64) -> f64 {
    if iv.is_point() {
        rat_to_f64(&iv.lo)
    } else {
        refine_rat_to_f64(seq, iv.lo, iv.hi, Tolerance::absolute(x_tol))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::testutil::{planted, rat};

    /// The exact smallest root of the stored polynomial in (lo, hi], as an interval.
    fn oracle(p: &Poly<f64>, lo: f64, hi: f64) -> Option<RootInterval<Rat>> {
        let q = p.to_rat().unwrap();
        let (lo, hi) = (rat_from_f64(lo).unwrap(), rat_from_f64(hi).unwrap());
        let seq = q.sturm().unwrap();
        isolate_rat(&seq, &lo, &hi, true)
            .into_iter()
            .next()
            .map(|iv| seq.refine_interval(&iv, 80))
    }

    fn check(p: &Poly<f64>, lo: f64, hi: f64, x_tol: f64, opts: &RootOptions) {
        let mut stats = RootStats::default();
        let got = p.smallest_root_with(lo, hi, opts, &mut stats);
        let want = oracle(p, lo, hi);
        match (got, want) {
            (None, None) => {}
            (Some(r), Some(iv)) => {
                let truth = rat_to_f64(&iv.lo);
                let allowed = x_tol.max(truth.abs() * f64::EPSILON) * (1.0 + 1e-12);
                assert!(
                    (r - truth).abs() <= allowed,
                    "{p:?} on ({lo}, {hi}]: got {r}, exact {truth}, {opts:?}"
                );
            }
            (g, w) => panic!("{p:?} on ({lo}, {hi}]: got {g:?}, exact {w:?}, {opts:?}"),
        }
    }

    #[test]
    fn smallest_root_matches_exact_oracle_on_planted_and_awkward_cases() {
        let opts = RootOptions::new(1e-12);
        let cases: Vec<(Poly<f64>, f64, f64)> = vec![
            (Poly::from_roots(&[1.0, 2.0, 3.0, 4.0]), 0.0, 10.0),
            (Poly::from_roots(&[1.0, 2.0, 3.0, 4.0]), 1.0, 10.0), // root on the open end
            (Poly::from_roots(&[1.0, 2.0, 3.0, 4.0]), 0.5, 1.0),  // root on the closed end
            (Poly::from_roots(&[1.0, 1.0, 3.0, 4.0]), 0.0, 10.0), // double root first
            (Poly::from_roots(&[0.3, 0.3000001, 0.7, 5.0]), 0.0, 10.0), // cluster
            (Poly::new(vec![1.0, 0.0, 1.0, 0.0, 1.0]), -10.0, 10.0), // no real root
            (
                Poly::new(vec![-1.0, 0.0, 0.0, 0.0, 0.0, 0.0, 1.0]),
                -2.0,
                2.0,
            ), // x⁶ − 1
            (
                planted(&[rat(1, 3), rat(2, 7), rat(-5, 11)]).to_f64(),
                -1.0,
                1.0,
            ),
            (Poly::new(vec![-2.0, 1.0]), 0.0, 2.0),
            (Poly::new(vec![2.0, -3.0, 1.0]), 0.0, 1.0),
        ];
        for (p, lo, hi) in &cases {
            for method in [IsolationMethod::Bernstein, IsolationMethod::Exact] {
                for refine in [
                    RefineMethod::Bisection,
                    RefineMethod::Illinois,
                    RefineMethod::NewtonBisection,
                ] {
                    let o = RootOptions {
                        isolation: method,
                        refine,
                        ..opts
                    };
                    check(p, *lo, *hi, opts.x_tol, &o);
                }
            }
        }
    }

    #[test]
    fn any_root_query_answers_from_end_signs_without_isolation() {
        // Three roots in (0, 4]: with x_tol the whole width, any point of the interval is a
        // valid answer, and the odd sign change proves a root: no subdivision, no refinement.
        let p = Poly::from_roots(&[0.5, 1.5, 3.0]);
        let mut s = RootStats::default();
        let r = p.smallest_root_with(0.0, 4.0, &RootOptions::new(4.0), &mut s);
        assert!(r.is_some_and(|r| r > 0.0 && r <= 4.0), "{r:?}");
        assert_eq!(
            (s.subdivisions, s.refine_evals),
            (0, 0),
            "no isolation work"
        );
        // An even count gives no shortcut: both roots of (x − 1)(x − 2) are found by isolation.
        let q = Poly::from_roots(&[1.0, 2.0]);
        let r = q.smallest_root_with(0.0, 4.0, &RootOptions::new(4.0), &mut s);
        assert!(r.is_some_and(|r| r > 0.0 && r <= 4.0), "{r:?}");
        // And none is still none.
        let none = Poly::from_roots(&[5.0, 6.0, 7.0]);
        assert_eq!(
            none.smallest_root_with(0.0, 4.0, &RootOptions::new(4.0), &mut s),
            None
        );
    }

    #[test]
    fn newton_starts_at_the_control_polygon_zero() {
        // Ray–torus quartics as the tracer builds them (R = 2, r = 1, origin on the bounding
        // box): (|p|² + R² − r²)² − 4R²(x² + y²) along p = o + s·d.
        let torus = |o: [f64; 3], d: [f64; 3]| {
            let line = |k: usize| Poly::new(vec![o[k], d[k]]);
            let (x, y, z) = (line(0), line(1), line(2));
            let rho2 = &(&x * &x) + &(&y * &y);
            let s = &(&rho2 + &(&z * &z)) + &Poly::new(vec![3.0]);
            &(&s * &s) - &(&rho2 * &Poly::new(vec![16.0]))
        };
        let rays = [
            ([-3.0, -0.5, 0.3], [1.0, 0.1, -0.05], 6.0),
            ([-3.0, 0.2, 0.9], [0.8, 0.3, -0.4], 5.0),
            ([0.5, -3.0, 1.0], [0.1, 0.9, -0.5], 4.0),
            ([2.9, -0.3, 1.0], [-0.4, 0.1, -0.9], 2.2),
            ([-1.0, -3.0, -0.2], [0.3, 0.95, 0.05], 6.0),
        ];
        let o = RootOptions::new(1e-10);
        let mut s = RootStats::default();
        for (org, dir, hi) in rays {
            let p = torus(org, dir);
            check(&p, 0.0, hi, 1e-10, &o);
            assert!(
                p.smallest_root_with(0.0, hi, &o, &mut s).is_some(),
                "each ray hits"
            );
        }
        // Measured: 28 evaluations; 35 when Newton starts from the secant or midpoint.
        assert!(
            s.refine_evals <= 30,
            "{} refinement evaluations",
            s.refine_evals
        );
    }

    #[test]
    fn exact_zero_factor_is_deflated_without_fallback() {
        // x³·(x − 1/2)(x + 1/4): a triple root at 0, as in resultants of collapsed patch edges.
        let p = Poly::new(vec![0.0, 0.0, 0.0, -0.125, -0.25, 1.0]);
        let o = RootOptions::new(1e-12);
        let mut s = RootStats::default();
        let r = p.real_roots_with(-1.0, 1.0, &o, &mut s).unwrap();
        assert_eq!(r.len(), 3, "−1/4, 0, 1/2: {r:?}");
        assert!((r[0] + 0.25).abs() <= 1e-12 && r[1] == 0.0 && (r[2] - 0.5).abs() <= 1e-12);
        let ivs = p.isolate_roots_with(-1.0, 1.0, &o, &mut s).unwrap();
        assert_eq!(
            ivs[1],
            RootInterval { lo: 0.0, hi: 0.0 },
            "0 is a point interval"
        );
        assert!(ivs[0].hi <= 0.0 && ivs[2].lo >= 0.0, "disjoint: {ivs:?}");
        let first = |lo, hi, s: &mut RootStats| p.smallest_root_with(lo, hi, &o, s);
        assert!(
            (first(-1.0, 1.0, &mut s).unwrap() + 0.25).abs() <= 1e-12,
            "−1/4 first"
        );
        assert_eq!(first(-0.1, 1.0, &mut s), Some(0.0), "then 0");
        assert!(
            (first(0.0, 1.0, &mut s).unwrap() - 0.5).abs() <= 1e-12,
            "0 excluded"
        );
        assert_eq!(first(0.6, 1.0, &mut s), None, "none");
        assert_eq!(s.exact_fallbacks, 0, "no exact fallback");
        for (lo, hi) in [(-1.0, 1.0), (-0.1, 1.0), (0.0, 1.0), (-1.0, 0.0)] {
            check(&p, lo, hi, 1e-12, &o);
        }
    }

    /// `(1 + s/2)³²` expanded: a shadow ray leaving the plane `x = 1` of `x³² − 1` along
    /// `x(s) = 1 + s/2`, before `−1` and the offset `δ` go into `c₀`.
    fn plane_power_32() -> Vec<f64> {
        let mut c = vec![0.0; 33];
        let mut binom = 1.0;
        for (k, ck) in c.iter_mut().enumerate() {
            *ck = binom * 0.5f64.powi(k as i32);
            binom = binom * (32 - k) as f64 / (k + 1) as f64;
        }
        c
    }

    #[test]
    fn shadow_ray_off_a_high_degree_plane_is_decided_by_the_coefficient_signs() {
        // Issue 11 (x^32 − 1 took 25× Barth's time, most of it in shadow rays): a shadow ray
        // leaving the plane x = 1 of x^32 − 1 along x(s) = 1 + s/2, offset by δ, meets
        // (1 + s/2)^32 − 1 + δ on (0, 20]: every coefficient positive, no root. The
        // Bernstein run bounds its rounding by the whole range's magnitude and subdivided
        // before seeing that; Descartes' rule on the stored signs sees it at once.
        let mut c = plane_power_32();
        c[0] = 1e-9; // 1 − 1 + δ
        let p = Poly::new(c.clone());
        let mut stats = RootStats::default();
        let r = p.smallest_root_with(0.0, 20.0, &RootOptions::new(1e-12), &mut stats);
        assert_eq!(r, None);
        assert_eq!(
            (
                stats.subdivisions,
                stats.adaptive_pieces,
                stats.exact_fallbacks
            ),
            (0, 0, 0),
            "decided without isolating: {stats:?}"
        );
        // The mirror image p(−x) on (−20, 0], and a sign change still searched.
        let mirrored: Vec<f64> = c
            .iter()
            .enumerate()
            .map(|(i, &ci)| if i % 2 == 1 { -ci } else { ci })
            .collect();
        assert!(
            no_root_by_descartes(&mirrored, -20.0, 0.0, 0.0),
            "p(−x): no negative root"
        );
        assert!(
            !no_root_by_descartes(&mirrored, -20.0, 1.0, 0.0),
            "a range across 0: maybe"
        );
        assert!(
            !no_root_by_descartes(&[0.0, 1.0, 1.0], -20.0, 0.0, 0.0),
            "0 is a root"
        );
        c[0] = -1e-9;
        let p = Poly::new(c);
        assert!(
            p.smallest_root(0.0, 20.0, 1e-12).is_some(),
            "one sign change: a root"
        );
    }

    #[test]
    fn shadow_ray_off_a_high_degree_plane_is_decided_with_a_value_slack() {
        // Issue 11 (x^32 − 1 at 15× Barth's cost a pixel once its restriction was certified):
        // the renderer's shadow ray leaving x = 1 meets (1 + s/2)^32 − 1 + δ with a slack
        // growing like γ·(1 + r/2)^32, and the stored c₀ = δ is within it, so Descartes' rule
        // on the stored signs says nothing and the Bernstein runs over (lo, 20] subdivided.
        // With the sign of p(lo) in place of c₀ and a radius of its own for each coefficient's
        // slack, no search is needed.
        let mut c = plane_power_32();
        c[0] = -1e-15; // δ, within the slack of 0
        let slack = |r: f64| 1e-13 * (1.0 + 0.5 * r).powi(32);
        let p = Poly::new(c.clone());
        let o = RootOptions::new(1e-12);
        let lo = 1e-8; // p(lo) ≈ 16·lo, beyond the slack there (the spawn offset)
        let mut stats = RootStats::default();
        let r = p
            .roots(lo, 20.0, &o)
            .value_slack(&slack)
            .stats(&mut stats)
            .smallest();
        assert_eq!(r, Ok(None));
        assert_eq!(
            stats.subdivisions, 0,
            "decided without isolating: {stats:?}"
        );
        // A coefficient the slack may flip is not read: 1e-12 + 1e-20·t + 1e-20·t² may be
        // 1e-12 − 4e-14·t + … within a slack of 1e-14·(1 + r)², a root near t = 25.
        let q = Poly::new(vec![1e-12, 1e-20, 1e-20]);
        let slack = |r: f64| 1e-14 * (1.0 + r) * (1.0 + r);
        let r = q.roots(0.0, 100.0, &o).value_slack(&slack).smallest();
        assert!(matches!(r, Err(RootError::SlackLimited { .. })), "{r:?}");
    }

    #[test]
    fn bad_input_is_refused_not_miscounted() {
        let p = Poly::new(vec![-1.0, 1.0]);
        let mut s = RootStats::default();
        let o = RootOptions::new(1e-9);
        assert_eq!(
            p.try_smallest_root(f64::NAN, 1.0, &o, &mut s),
            Err(RootError::NanBound),
            "NaN"
        );
        assert_eq!(
            p.try_smallest_root(2.0, 0.0, &o, &mut s),
            Ok(None),
            "reversed: no root"
        );
        assert_eq!(p.try_smallest_root(1.0, 1.0, &o, &mut s), Ok(None), "empty");
        let z = Poly::<f64>::zero();
        assert_eq!(
            z.try_smallest_root(0.0, 1.0, &o, &mut s),
            Err(RootError::ZeroPolynomial),
            "0"
        );
        let nan = Poly::new(vec![1.0, f64::INFINITY]);
        assert_eq!(
            nan.try_smallest_root(0.0, 1.0, &o, &mut s),
            Err(RootError::NonFiniteCoefficient { index: 1 }),
            "inf coefficient"
        );
        let bad_tol = RootOptions::new(-1.0);
        assert_eq!(
            p.try_smallest_root(0.0, 2.0, &bad_tol, &mut s),
            Err(RootError::InvalidTolerance),
            "tol"
        );
        assert_eq!(
            Poly::new(vec![3.0]).smallest_root(-1.0, 1.0, 1e-9),
            None,
            "constant"
        );
        assert_eq!(s.rejected, 4, "four refusals counted");
        assert_eq!(
            p.smallest_root(f64::NEG_INFINITY, f64::INFINITY, 1e-12),
            Some(1.0),
            "infinite ends"
        );
    }

    /// Regression (left open by the full-precision work of session 7, which fixed the same
    /// check in the `f64` and wide refinements): with `x_tol = 0` the point-by-point
    /// refinement of a slack query that lands exactly on an exact `f64` root probed
    /// `m ± x_tol/2`, the point itself, whose sign no slack can certify, and gave up as
    /// `SlackLimited` on a root that its neighbouring doubles pin down.
    #[test]
    fn pointwise_refinement_at_zero_tolerance_probes_the_neighbours() {
        let c = [-0.5, 1.0];
        let tiny = |_: f64| 1e-300;
        let got = refine_pointwise(
            &c,
            Bracket::new(0.0, 1.0, -1),
            Tolerance::absolute(0.0),
            Slack::new(&tiny),
        );
        assert_eq!(got, Ok(0.5), "the root 1/2, pinned by its neighbours");
    }

    /// Regression (session 22): a polynomial with the exact root 0 (`p = x·q`, here the odd
    /// Chebyshev polynomials) had its quotient's inclusion discs computed twice, once for each
    /// side of 0, at twice the cost. They are now asked once over the whole range, and the
    /// answer is still the exact oracle's: every root in order, 0 in its place, and the
    /// intervals isolating.
    #[test]
    fn the_discs_run_once_around_an_exact_root_0() {
        for n in [5u32, 7, 9, 21] {
            let p = crate::testutil::chebyshev(n).to_f64();
            assert_eq!(p.coeffs()[0], 0.0, "T{n}(0) = 0");
            let (values, intervals) = all_roots_against_the_oracle(&p, -2.0, 2.0, 1e-12);
            for (stats, what) in [(values, "values"), (intervals, "intervals")] {
                assert_eq!(
                    stats.inclusion_decided + stats.inclusion_undecided + stats.subdivided_first,
                    1,
                    "T{n}, {what}: one query of the quotient (the discs, or the subdivision \
                     first), not one a side"
                );
            }
        }
    }

    /// The exact roots of the stored `p` in `(lo, hi]` against an all-roots query's values
    /// (within `x_tol`, or one `f64` spacing where that is wider, as `real_roots` promises)
    /// and its isolating intervals; the statistics of the two queries.
    fn all_roots_against_the_oracle(
        p: &Poly<f64>,
        lo: f64,
        hi: f64,
        x_tol: f64,
    ) -> (RootStats, RootStats) {
        let want = crate::testutil::stored_roots(p, lo, hi);
        let mut values = RootStats::default();
        let got = p
            .real_roots_with(lo, hi, &RootOptions::new(x_tol), &mut values)
            .expect("an answer");
        assert_eq!(got.len(), want.len(), "{got:?} against {want:?}");
        for (g, w) in got.iter().zip(&want) {
            let allowed = x_tol.max(w.abs() * f64::EPSILON);
            assert!((g - w).abs() <= allowed, "{g} against {w}");
        }
        let mut intervals = RootStats::default();
        let ivs = p
            .isolate_roots_with(lo, hi, &RootOptions::new(x_tol), &mut intervals)
            .expect("an answer");
        assert_eq!(ivs.len(), want.len(), "{ivs:?} against {want:?}");
        for (iv, w) in ivs.iter().zip(&want) {
            assert!(iv.lo <= *w && *w <= iv.hi, "{iv:?} against {w}");
        }
        (values, intervals)
    }

    /// Few real roots far apart — a ray through a torus, restricted at its bounding sphere's
    /// entry — take the budgeted subdivision a few splits: it answers the all-roots queries,
    /// values and intervals, within its `2n` splits, and the inclusion discs are not computed.
    /// Restricted 10⁴ units away, the four roots cluster far from 0 and are answered from
    /// their centroid (the range re-expanded there), within the same budget. (That the
    /// re-expansion's search spends that budget is
    /// `certified::tests::a_far_clusters_search_spends_the_attempts_budget`.) Fails if the
    /// attempt is not made or gives up.
    #[test]
    fn few_real_roots_are_answered_by_the_budgeted_subdivision() {
        // (start of the ray, end of the range, far-cluster re-expansions)
        for (x0, hi, shifts) in [(-3.2, 8.0, 0), (-1e4, 1e4 + 8.0, 1)] {
            let p = crate::testutil::torus_ray(x0);
            let (values, intervals) = all_roots_against_the_oracle(&p, 0.0, hi, 1e-12);
            for (stats, what) in [(values, "values"), (intervals, "intervals")] {
                assert_eq!(
                    (
                        stats.subdivided_first,
                        stats.inclusion_decided,
                        stats.inclusion_undecided,
                        stats.cluster_shifts
                    ),
                    (1, 0, 0, shifts),
                    "from {x0}, {what}: {stats:?}"
                );
                assert!(
                    stats.subdivisions <= u64::from(SUBDIVISION_FIRST_SPLITS) * 4,
                    "from {x0}, {what}: within the budget: {stats:?}"
                );
            }
        }
    }

    /// Integer roots on a power-of-two range sit on the subdivision's dyadic points, where
    /// no `f64` sign is certain: the budgeted subdivision gives up after at most its budget of
    /// splits, and the discs answer — exactly, as before it was tried. Fails if the attempt
    /// outruns its budget or leaves its partial answer in the result.
    #[test]
    fn roots_on_dyadic_points_give_the_budget_up_for_the_discs() {
        let p = crate::testutil::wilkinson(4).to_f64();
        let (values, intervals) = all_roots_against_the_oracle(&p, -32.0, 32.0, 1e-12);
        for (stats, what) in [(values, "values"), (intervals, "intervals")] {
            assert_eq!(
                (stats.subdivided_first, stats.inclusion_decided),
                (0, 1),
                "{what}: {stats:?}"
            );
            assert!(
                stats.subdivisions <= u64::from(SUBDIVISION_FIRST_SPLITS) * 4,
                "{what}: the attempt stopped at its budget: {stats:?}"
            );
        }
        let exact = p.real_roots(-32.0, 32.0, 1e-12).expect("an answer");
        assert_eq!(exact, [1.0, 2.0, 3.0, 4.0], "the discs' exact answer");
    }

    /// Above [`SUBDIVISION_FIRST_MAX_DEGREE`] the subdivision is not tried first, however
    /// few the real roots: `x¹¹ − 2` has one.
    #[test]
    fn high_degrees_go_to_the_discs_first() {
        let mut c = vec![0.0; 12];
        c[0] = -2.0;
        c[11] = 1.0;
        let p = Poly::new(c);
        let (values, _) = all_roots_against_the_oracle(&p, -4.0, 4.0, 1e-12);
        assert_eq!(values.subdivided_first, 0, "{values:?}");
        assert_eq!(
            values.inclusion_decided + values.inclusion_undecided,
            1,
            "{values:?}"
        );
    }

    /// A part the discs leave undecided around an exact root 0 is subdivided on each side of
    /// 0, as the sides alone did before the discs ran once (the rounding bound is tightest
    /// from 0 outwards); elsewhere, or not around a root 0, it is subdivided whole.
    #[test]
    fn undecided_parts_around_a_root_0_are_subdivided_on_each_side() {
        let calls = |lo: f64, hi: f64, split: bool| {
            let mut seen = vec![];
            at_zero(lo, hi, split, |a, b| {
                seen.push((a, b));
                Ok(())
            })
            .expect("no error");
            seen
        };
        assert_eq!(calls(-1.0, 2.0, true), vec![(-1.0, 0.0), (0.0, 2.0)]);
        assert_eq!(calls(-1.0, 2.0, false), vec![(-1.0, 2.0)]);
        assert_eq!(calls(0.0, 2.0, true), vec![(0.0, 2.0)], "0 is the open end");
        assert_eq!(
            calls(-1.0, 0.0, true),
            vec![(-1.0, 0.0)],
            "0 is the closed end"
        );
    }

    /// When an answer of the whole-range query reaches 0 (a root of the quotient closer to 0
    /// than its bracket is wide, where 0 could not be put in order), [`around_zero`] answers
    /// each side alone instead.
    #[test]
    fn an_answer_reaching_0_sends_around_zero_to_the_sides() {
        // The whole-range query answers `whole`; each side answers its midpoint.
        let around = |whole: &[f64]| {
            let q = Poly::new(vec![1.0, 1.0]);
            let (mut out, mut stats) = (vec![], RootStats::default());
            around_zero(
                &q,
                (-1.0, 1.0),
                0.0,
                &mut stats,
                &mut out,
                |_, _, _, _, out| {
                    out.extend_from_slice(whole);
                    Ok(true)
                },
                |_, lo, hi, _, out| {
                    out.push((lo + hi) / 2.0);
                    Ok(())
                },
            )
            .expect("no error");
            out
        };
        assert_eq!(
            around(&[-0.5, 0.0]),
            vec![-0.5, 0.0, 0.5],
            "an answer at 0: the sides' answers around 0"
        );
        assert_eq!(
            around(&[-0.5, 0.25, 0.75]),
            vec![-0.5, 0.0, 0.25, 0.75],
            "the whole range's answers, 0 put in order"
        );
    }
}

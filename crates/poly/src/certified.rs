//! [`CertifiedSearch`]: the default `f64` isolation ([`IsolationMethod::Bernstein`]) as a
//! sequence of Bernstein runs, each with its own fresh error bound, and exact arithmetic only
//! on the pieces that `f64` could not decide.
//!
//! A run of [`bernstein::run`] on `(lo, hi]` either answers the whole interval or stops at a
//! node where a sign could not be certified, having answered `(lo, t_a]` and certified the
//! signs at `t_a` and at a point `t_b` past the node ([`Stuck`]). The search then starts a
//! *fresh* run on `(t_a, t_b]` and another on `(t_b, hi]`. A fresh run helps in two ways:
//! its error bound `γ(k)·M` starts again from the few roundings of one Taylor shift, with
//! `M = Σ|cᵢ|(|t_a| + |t_b − t_a|)ⁱ`, which is far smaller than the parent's when the piece
//! lies near 0 and the roots there are tiny (eliminants whose roots cluster near `u = 0`); and
//! its subdivision points are no longer the parent's dyadic points, so a root sitting exactly
//! on one of those (odd Chebyshev polynomials at 0) is now inside a node. When a fresh run's
//! `M` would not be [`MIN_MAG_GAIN`] of the stuck run's, or after [`MAX_RUNS`] runs, the stuck
//! piece (after the budget: everything left) goes to adaptive precision: first re-expanded at
//! its end in double-double and searched in `f64` with the re-expansion's radii as a value
//! slack ([`Shift`]); if that leaves anything undecided, [`PieceIsolator`] (double-double
//! de Casteljau, then wider binary floats, rigorous bounds throughout). Only its nodes that
//! even [`MAX_BITS`](crate::multiprec::MAX_BITS) cannot decide (multiple roots, roots within
//! one `f64` spacing) are isolated by exact Sturm counts on the stored polynomial (the
//! sequence is built once per query, counted in [`RootStats::exact_fallbacks`]). See
//! `paper-notes/isolation.md`, "Restarts and local exact isolation" and "Adaptive precision".
//! [`CertifiedSearch::run_budgeted`] is that search's first run alone, with a budget of
//! splits and nothing after it: the all-roots queries' cheap first try ("Subdivision first,
//! on a budget").
//!
//! [`IsolationMethod::Bernstein`]: crate::IsolationMethod::Bernstein

use smallvec::SmallVec;

use crate::bernstein::{self, Bracket, Brackets, Stuck};
use crate::eval_bound::{certified_sign, certified_sign_pair};
use crate::exact_oracle::ExactOracle;
use crate::multiprec::{Outcome, PieceIsolator, Tier, point_sign};
use crate::root_interval::RootInterval;
use crate::shifted::{Shift, far_centroid};
use crate::stats::RootStats;
use crate::stored::Slack;
use crate::univariate::Poly;

/// Most Bernstein runs in one query (the first included) before the remaining pieces go
/// straight to exact isolation. Each run costs one Taylor shift, `O(n²)` flops.
const MAX_RUNS: u32 = 16;

/// [`MAX_RUNS`] for a query with a value slack, which cannot escalate to higher precision:
/// each stuck run is replaced by runs on narrower pieces, whose slack (taken at their own
/// radius) is smaller; a degree-32 ray whose range reaches twice the root's radius needs about
/// twenty (`paper-notes/implicit-surfaces.md` §6).
const MAX_SLACK_RUNS: u32 = 48;

/// A piece where a run was stuck gets a fresh `f64` run only if that run's magnitude bound
/// `M` ([`bernstein::run_magnitude`]) is at most this fraction of the stuck run's; otherwise
/// its error bounds are no tighter, it would be stuck the same way, and the piece goes to
/// adaptive precision at once.
const MIN_MAG_GAIN: f64 = 0.25;

/// Non-dyadic fractions of an interval at which it is split when a run is stuck on all of it
/// (`√2 − 1`, `2 − √2`, golden-section points): a root exactly at a dyadic point of the
/// interval, as odd Chebyshev polynomials have at 0, is not hit again.
const SPLIT_FRACTIONS: [f64; 4] = [
    0.414_213_562_373_095_1,
    0.585_786_437_626_904_9,
    0.309_016_994_374_947_4,
    0.690_983_005_625_052_6,
];

/// One isolated root of the stored polynomial.
#[derive(Clone, Debug, PartialEq)]
pub(crate) enum Found {
    /// A certified `f64` bracket (refined in `f64`).
    Bracket(Bracket),
    /// An interval from exact isolation: refined in `f64` when its end signs are certified
    /// opposite, else with the exact sequence.
    Exact(RootInterval<f64>),
    /// A bracket in the variable `u = t − e` of a piece re-expanded at `e`
    /// ([`CertifiedSearch::shifts`] at this index), certified against the shift's slack
    /// (refined in `f64` on the shifted coefficients).
    Shifted(u32, Bracket),
}

/// The certified search of one query (see the module docs).
pub(crate) struct CertifiedSearch<'p> {
    /// The stored polynomial's coefficients (lowest first).
    c: &'p [f64],
    first_only: bool,
    runs_left: u32,
    /// Some piece of this query went to adaptive precision: the rest of the query goes there
    /// too (its de Casteljau run costs little more than an `f64` run that would get stuck
    /// the same way; `paper-notes/isolation.md`).
    went_adaptive: bool,
    /// Subdivisions so far, over all runs (a budgeted search starts its count at
    /// `MAX_SPLITS` less its budget).
    splits: u32,
    /// A budgeted search ([`CertifiedSearch::run_budgeted`]): one run, and it gives up where
    /// the plain search would go to adaptive precision or exact arithmetic.
    budgeted: bool,
    /// The budgeted search gave up; what it found is incomplete.
    gave_up: bool,
    /// The exact oracle of the stored polynomial, built on first need.
    /// (Boxed: it is rare, and the search is returned by value on every query.)
    exact: Option<Box<ExactOracle>>,
    /// The caller's value slack (none: the stored polynomial is the true one).
    slack: Slack<'p>,
    /// The slack at the radius of the query's range, `(radius, slack)`: asked once, and valid
    /// on every piece (a slack is non-decreasing in the radius).
    pub(crate) top_slack: (f64, f64),
    /// With a slack, the piece where `f64` could not decide and the search stopped: more
    /// precision of the stored coefficients cannot help there ([`RootError::SlackLimited`]).
    ///
    /// [`RootError::SlackLimited`]: crate::RootError::SlackLimited
    pub(crate) slack_limited: Option<(f64, f64)>,
    /// The roots found, sorted.
    pub(crate) found: SmallVec<[Found; 2]>,
    /// The re-expanded pieces that [`Found::Shifted`] brackets refer to.
    pub(crate) shifts: Vec<Shift>,
}

impl<'p> CertifiedSearch<'p> {
    /// Isolates the roots of `p` in `(lo, hi]` (both finite, `lo < hi`), or only the first
    /// one with `first_only`.
    pub(crate) fn run(
        c: &'p [f64],
        lo: f64,
        hi: f64,
        first_only: bool,
        slack: Slack<'p>,
        stats: &mut RootStats,
    ) -> Self {
        let range_slack = slack.at(lo.abs().max(hi.abs()));
        let signs = end_signs(c, lo, hi, slack, range_slack);
        Self::run_with_signs(c, (lo, hi), signs, first_only, (slack, range_slack), stats)
    }

    /// As [`run`](Self::run), with the caller's [`certified_sign`]s of `p(lo)`, `p(hi)` (0
    /// where not certain).
    // Inlined so the search is built in the caller's frame, not copied out on return.
    #[inline(always)]
    pub(crate) fn run_with_signs(
        c: &'p [f64],
        range: (f64, f64),
        signs: (i8, i8),
        first_only: bool,
        slacks: (Slack<'p>, f64),
        stats: &mut RootStats,
    ) -> Self {
        Self::search(c, range, signs, first_only, slacks, None, stats)
    }

    /// The roots of `p` in `(lo, hi]` (both finite, `lo < hi`) by one `f64` run with at most
    /// `budget` subdivisions: `None` when that does not answer the query — the budget spent,
    /// or a node whose sign `f64` cannot certify, which the plain search would give a fresh
    /// run, adaptive precision or exact arithmetic — having done no other work (but a far
    /// cluster's re-expansion, whose `f64` search spends the same budget). The all-roots
    /// queries try it before the inclusion discs (`paper-notes/isolation.md`, "Subdivision
    /// first, on a budget").
    pub(crate) fn run_budgeted(
        c: &'p [f64],
        lo: f64,
        hi: f64,
        budget: u32,
        stats: &mut RootStats,
    ) -> Option<Self> {
        let signs = end_signs(c, lo, hi, Slack::NONE, 0.0);
        let slacks = (Slack::NONE, 0.0);
        let search = Self::search(c, (lo, hi), signs, false, slacks, Some(budget), stats);
        (!search.gave_up).then_some(search)
    }

    #[inline(always)]
    fn search(
        c: &'p [f64],
        (lo, hi): (f64, f64),
        signs: (i8, i8),
        first_only: bool,
        (slack, range_slack): (Slack<'p>, f64),
        budget: Option<u32>,
        stats: &mut RootStats,
    ) -> Self {
        let mut search = CertifiedSearch {
            c,
            first_only,
            runs_left: if budget.is_some() {
                1
            } else if slack.is_some() {
                MAX_SLACK_RUNS
            } else {
                MAX_RUNS
            },
            went_adaptive: false,
            splits: budget.map_or(0, |b| bernstein::MAX_SPLITS.saturating_sub(b)),
            budgeted: budget.is_some(),
            gave_up: false,
            exact: None,
            slack,
            top_slack: (lo.abs().max(hi.abs()), range_slack),
            slack_limited: None,
            found: SmallVec::new(),
            shifts: Vec::new(),
        };
        search.start(lo, hi, signs, stats);
        search
    }

    /// The slack at radius `r` (the query's own without asking again).
    fn slack_at(&self, r: f64) -> f64 {
        if r == self.top_slack.0 {
            self.top_slack.1
        } else {
            self.slack.at(r)
        }
    }

    /// The exact oracle, when some piece needed it.
    pub(crate) fn exact_sequence(&self) -> Option<&ExactOracle> {
        self.exact.as_deref()
    }

    /// Certifies the end signs (in adaptive precision when `f64` cannot); an end whose sign
    /// no precision up to [`MAX_BITS`](crate::multiprec::MAX_BITS) decides (a root at the
    /// end, or within `2^-1000` of the scale of it) gets a short exact piece next to it.
    fn start(&mut self, lo: f64, hi: f64, (s_lo, s_hi): (i8, i8), stats: &mut RootStats) {
        if self.slack.is_some() && (s_lo == 0 || s_hi == 0) {
            // An end within the slack of zero: no precision of the stored polynomial helps.
            self.slack_limited = Some((lo, hi));
            return;
        }
        let c = self.c;
        let s_lo = if s_lo == 0 {
            point_sign(c, lo, Tier::Dd).0
        } else {
            s_lo
        };
        let s_hi = if s_hi == 0 {
            point_sign(c, hi, Tier::Dd).0
        } else {
            s_hi
        };
        let (mut a, mut s_a) = (lo, s_lo);
        if s_lo == 0 {
            let Some((x, s)) = near_end(c, lo, hi, lo, 1.0) else {
                self.exact(lo, hi, stats);
                return;
            };
            if self.exact(lo, x, stats) {
                return;
            }
            (a, s_a) = (x, s);
        }
        let (mut b, mut s_b) = (hi, s_hi);
        if s_hi == 0 {
            let Some((y, s)) = near_end(c, a, hi, hi, -1.0) else {
                self.exact(a, hi, stats);
                return;
            };
            (b, s_b) = (y, s);
        }
        // Roots clustered far from 0 against their spread (a ray polynomial restricted far
        // from its surface): the whole range re-expanded at their centroid at once.
        // (Not with a slack: the stored polynomial is not the true one, and a re-expansion
        // would not make it so; that also skips the test in the shifted sub-searches.)
        let cluster = if self.slack.is_some() {
            None
        } else {
            far_centroid(c, a, b).and_then(|e| {
                let (shift, signs) = Shift::around_cluster(c, e, (a, b), (s_a, s_b))?;
                self.search_shift(shift, signs, stats)
            })
        };
        let done = match cluster {
            Some(done) => {
                stats.cluster_shifts += 1;
                done
            }
            None => self.range(a, b, (s_a, s_b), f64::INFINITY, stats),
        };
        if done {
            return;
        }
        if b < hi {
            self.exact(b, hi, stats);
        }
    }

    /// Answers `(lo, hi]` (certified non-zero end signs `s`); true when the search is over
    /// (the first root is found in `first_only` mode).
    fn range(
        &mut self,
        lo: f64,
        hi: f64,
        s: (i8, i8),
        parent_mag: f64,
        stats: &mut RootStats,
    ) -> bool {
        if lo >= hi {
            return false;
        }
        if self.goes_adaptive(lo, hi, parent_mag) {
            return self.adaptive(lo, hi, s, stats);
        }
        self.runs_left -= 1;
        let mut out = Brackets::new();
        let result = bernstein::run(
            self.c,
            (lo, hi),
            s,
            self.slack_at(lo.abs().max(hi.abs())),
            self.first_only,
            &mut out,
            &mut self.splits,
            stats,
        );
        let any = !out.is_empty();
        self.found.extend(out.drain(..).map(Found::Bracket));
        let stuck = match result {
            Ok(()) => return self.first_only && any,
            Err(stuck) => stuck,
        };
        if self.first_only && any {
            return true;
        }
        let Stuck {
            t_a,
            s_a,
            t_b,
            s_b,
            mag,
        } = stuck;
        // A fresh run on a piece no tighter than this one goes to adaptive precision instead
        // (the check on entry to `range`); with a value slack a narrower piece always gains:
        // the slack is taken at the piece's own radius, and it is what usually leaves a sign
        // undecided (the runs left bound it).
        if t_a == lo && t_b == hi {
            // Stuck on the whole interval: split it at a non-dyadic point and try fresh runs
            // on the parts.
            let slack = self.slack_at(lo.abs().max(hi.abs()));
            let Some((m, s_m)) = split_point(self.c, lo, hi, slack) else {
                return self.adaptive(lo, hi, s, stats);
            };
            return self.range(lo, m, (s.0, s_m), mag, stats)
                || self.range(m, hi, (s_m, s.1), mag, stats);
        }
        // (lo, t_a] is answered; (t_a, t_b] holds the stuck node; (t_b, hi] is untouched and
        // gets a run of its own — unless, looking for the first root only, the stuck piece
        // goes to adaptive precision: then so does everything after it, and one piece
        // (t_a, hi] costs one re-expansion, not two (the far-eye torus rays: 8.3 M → 6.9 M
        // instructions; for all roots the one wider piece cost more, planted degree 40 +4 %).
        if self.first_only && self.goes_adaptive(t_a, t_b, mag) {
            return self.adaptive(t_a, hi, (s_a, s.1), stats);
        }
        let done = self.range(t_a, t_b, (s_a, s_b), mag, stats);
        done || (t_b < hi && self.range(t_b, hi, (s_b, s.1), f64::INFINITY, stats))
    }

    /// True when the piece `(lo, hi]` goes to adaptive precision rather than to a fresh
    /// `f64` run: the run budget is spent, some piece went there already, or (without a
    /// slack) the fresh run would be no tighter than the stuck parent, whose bound `M` was
    /// `parent_mag` — its error bound would start from about the same `M` (a piece far from
    /// 0 against its width, as the roots of a ray polynomial restricted far from its
    /// surface), so it would be stuck the same way.
    fn goes_adaptive(&self, lo: f64, hi: f64, parent_mag: f64) -> bool {
        self.runs_left == 0
            || self.went_adaptive
            || (!self.slack.is_some()
                && parent_mag.is_finite()
                && bernstein::run_magnitude(self.c, lo, hi) > MIN_MAG_GAIN * parent_mag)
    }

    /// Adaptive-precision isolation of `(lo, hi]` (finite ends, certified non-zero signs `s`):
    /// double-double, then arbitrary precision ([`PieceIsolator`]); what even that cannot
    /// decide is isolated exactly. True when the search is over.
    /// With a slack, the search stops here instead ([`Self::slack_limited`]).
    fn adaptive(&mut self, lo: f64, hi: f64, s: (i8, i8), stats: &mut RootStats) -> bool {
        if self.budgeted {
            self.gave_up = true;
            return true;
        }
        if self.slack.is_some() {
            self.slack_limited = Some((lo, hi));
            return true;
        }
        self.went_adaptive = true;
        if let Some(done) = self.shifted(lo, hi, s, stats) {
            return done;
        }
        let mut piece = PieceIsolator::new(self.c, (lo, hi), s, stats);
        while let Some(outcome) = piece.next(stats) {
            let done = match outcome {
                Outcome::Bracket(b) => {
                    self.found.push(Found::Bracket(b));
                    self.first_only
                }
                Outcome::Undecided(x, y) => self.exact(x, y, stats),
            };
            if done {
                return true;
            }
        }
        false
    }

    /// The piece `(lo, hi]` (certified non-zero end signs `s`) re-expanded at its end nearer
    /// 0 in double-double ([`Shift`]) and searched in `f64` with the shift's radii as value
    /// slack: the first tier of [`adaptive`](Self::adaptive). `None` when the shift does not
    /// apply or its search left something undecided (then nothing of it is kept, and the
    /// piece goes on to [`PieceIsolator`]); else true when the search is over.
    fn shifted(&mut self, lo: f64, hi: f64, s: (i8, i8), stats: &mut RootStats) -> Option<bool> {
        let shift = Shift::new(self.c, (lo, hi))?;
        self.search_shift(shift, s, stats)
    }

    /// The `f64` search of a re-expanded piece, with its radii as value slack and the
    /// certified signs `s` of `p` at its ends: `None` when the search left something
    /// undecided (then nothing of it is kept), else true when the search is over.
    fn search_shift(&mut self, shift: Shift, s: (i8, i8), stats: &mut RootStats) -> Option<bool> {
        let (u_lo, u_hi) = shift.range;
        let slack_fn = |r: f64| shift.slack(r);
        let slack = Slack::new(&slack_fn);
        let range_slack = slack.at(u_lo.abs().max(u_hi.abs()));
        // A budgeted search's re-expansion spends the same budget (its split count starts at
        // this search's and is carried back).
        let budget = self
            .budgeted
            .then(|| bernstein::MAX_SPLITS.saturating_sub(self.splits));
        let sub = CertifiedSearch::search(
            &shift.q,
            (u_lo, u_hi),
            s,
            self.first_only,
            (slack, range_slack),
            budget,
            stats,
        );
        if self.budgeted {
            self.splits = sub.splits;
        }
        if sub.slack_limited.is_some() || sub.gave_up {
            return None;
        }
        // At most one re-expansion per adaptive piece, and the run budget bounds those.
        let index = u32::try_from(self.shifts.len()).expect("few shifts per query");
        let any = !sub.found.is_empty();
        self.found.extend(sub.found.into_iter().map(|f| match f {
            Found::Bracket(b) => Found::Shifted(index, b),
            _ => unreachable!("a search with a slack finds only brackets"),
        }));
        stats.adaptive_pieces += 1;
        stats.shifted_pieces += 1;
        self.shifts.push(shift);
        Some(self.first_only && any)
    }

    /// Exact isolation of `(lo, hi]` (finite `f64` ends, [`ExactOracle`]); true when the
    /// search is over. With a slack, the search stops here instead ([`Self::slack_limited`]).
    fn exact(&mut self, lo: f64, hi: f64, stats: &mut RootStats) -> bool {
        if self.budgeted {
            self.gave_up = true;
            return true;
        }
        if self.slack.is_some() {
            self.slack_limited = Some((lo, hi));
            return true;
        }
        let c = self.c;
        let oracle = self.exact.get_or_insert_with(|| {
            stats.exact_fallbacks += 1;
            let p = Poly::new(c.to_vec());
            Box::new(ExactOracle::new(
                &p.to_rat().expect("finite coefficients were checked"),
            ))
        });
        let ivs = oracle.isolate(lo, hi, self.first_only, stats);
        let any = !ivs.is_empty();
        self.found.extend(ivs.into_iter().map(Found::Exact));
        self.first_only && any
    }
}

/// The certified signs of `p(lo)` and `p(hi)` (0 where not certain) with `range_slack`, the
/// slack at `max(|lo|, |hi|)`; an end it leaves undecided is tried again with the slack at its
/// own radius (a value at `x` needs only `slack(|x|)`, which near the expansion point of a
/// high-degree restriction is far below the slack at the range's far end).
#[inline(always)]
pub(crate) fn end_signs(
    c: &[f64],
    lo: f64,
    hi: f64,
    slack: Slack<'_>,
    range_slack: f64,
) -> (i8, i8) {
    let (mut s_lo, mut s_hi) = certified_sign_pair(c, lo, hi, range_slack);
    if slack.is_some() {
        if s_lo == 0 && lo.abs() < hi.abs() {
            s_lo = certified_sign(c, lo, slack.at(lo));
        }
        if s_hi == 0 && hi.abs() < lo.abs() {
            s_hi = certified_sign(c, hi, slack.at(hi));
        }
    }
    (s_lo, s_hi)
}

/// A point strictly inside `(lo, hi)` with a certified sign (adaptive precision), near `end`
/// (`lo` with `dir = 1`, `hi` with `dir = −1`): `end + dir·(hi − lo)·2^-k` for
/// `k = 40, 30, 20, 10, 4`, the first whose sign is certified.
fn near_end(c: &[f64], lo: f64, hi: f64, end: f64, dir: f64) -> Option<(f64, i8)> {
    let width = hi - lo;
    [40, 30, 20, 10, 4].into_iter().find_map(|k| {
        let x = end + dir * width * 2f64.powi(-k);
        let s = if x > lo && x < hi {
            point_sign(c, x, Tier::Dd).0
        } else {
            0
        };
        (s != 0).then_some((x, s))
    })
}

/// A point strictly inside `(lo, hi)` at one of [`SPLIT_FRACTIONS`] with a certified sign
/// (with the value slack `slack` valid on the interval).
fn split_point(c: &[f64], lo: f64, hi: f64, slack: f64) -> Option<(f64, i8)> {
    SPLIT_FRACTIONS.into_iter().find_map(|f| {
        let m = lo + (hi - lo) * f;
        let s = if m > lo && m < hi {
            certified_sign(c, m, slack)
        } else {
            0
        };
        (s != 0).then_some((m, s))
    })
}

#[cfg(test)]
impl Poly<f64> {
    /// How many roots the subdivision path alone isolates on `(lo, hi]`, its statistics in
    /// `stats`: for tests of its tiers, since the all-roots queries try inclusion discs
    /// first (`inclusion.rs`) and these decide many polynomials without any tier.
    pub(crate) fn subdivision_root_count(&self, lo: f64, hi: f64, stats: &mut RootStats) -> usize {
        CertifiedSearch::run(self.coeffs(), lo, hi, false, Slack::NONE, stats)
            .found
            .len()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::root_options::RootOptions;
    use crate::testutil::{chebyshev, planted_f64, stored_roots};

    /// The budgeted search answers a far cluster from its centroid, and the re-expansion's
    /// own search spends the attempt's budget: with a budget of one split both give up, where
    /// a search with a budget of its own would answer. Fails if the re-expansion's search is
    /// not held to the budget.
    #[test]
    fn a_far_clusters_search_spends_the_attempts_budget() {
        let p = crate::testutil::torus_ray(-1e4);
        let (lo, hi) = (0.0, 1e4 + 8.0);
        let mut stats = RootStats::default();
        let search = CertifiedSearch::run_budgeted(p.coeffs(), lo, hi, 8, &mut stats)
            .expect("answered within 8 splits");
        assert_eq!(search.found.len(), 4, "four roots: {stats:?}");
        assert!(
            stats.subdivisions >= 2,
            "the re-expansion's search needs more than one split: {stats:?}"
        );
        let mut stats = RootStats::default();
        assert!(
            CertifiedSearch::run_budgeted(p.coeffs(), lo, hi, 1, &mut stats).is_none(),
            "one split is not enough: {stats:?}"
        );
        assert!(stats.subdivisions <= 1, "at most the budget: {stats:?}");
    }

    fn assert_matches_exact(p: &Poly<f64>, lo: f64, hi: f64, stats: &mut RootStats) {
        let x_tol = 1e-12;
        let opts = RootOptions::new(x_tol);
        let got = p.real_roots_with(lo, hi, &opts, stats).unwrap();
        let want = stored_roots(p, lo, hi);
        assert_eq!(got.len(), want.len(), "{p:?}: {got:?} vs {want:?}");
        for (g, w) in got.iter().zip(&want) {
            assert!((g - w).abs() <= x_tol + 1e-20, "{p:?}: {g} vs {w}");
        }
        let first = p.smallest_root_with(lo, hi, &opts, stats);
        assert_eq!(
            first.is_some(),
            !want.is_empty(),
            "{p:?}: smallest {first:?}"
        );
        if let (Some(g), Some(w)) = (first, want.first()) {
            assert!((g - w).abs() <= x_tol + 1e-20, "{p:?}: smallest {g} vs {w}");
        }
    }

    #[test]
    fn odd_chebyshev_root_on_the_split_point_needs_no_exact_arithmetic() {
        // T_n for odd n has the root 0: the first dyadic split point of (−1, 1]. The old path
        // ended every such query exactly; a fresh run with non-dyadic ends resolves it.
        let mut stats = RootStats::default();
        for n in [5, 9, 15, 21] {
            assert_matches_exact(&chebyshev(n).to_f64(), -1.0, 1.0, &mut stats);
        }
        for n in [6, 10, 16] {
            assert_matches_exact(&chebyshev(n).to_f64(), -0.75, 1.0, &mut stats);
        }
        assert_eq!(stats.exact_fallbacks, 0, "no exact fallback");
    }

    #[test]
    fn tiny_roots_near_zero_get_fresh_error_bounds() {
        // A recorded Gröbner-path eliminant: a complex pair at 3e-8 ± 3e-9i. The top run's
        // error bound (relative to Σ|cᵢ| ≈ 1) swamps the values near 0; a run on a short
        // piece near 0 has M ≈ 1e-15 and decides.
        let p = Poly::new(vec![9.065534198266913e-16, -5.99503305044977e-8, 1.0]);
        let mut stats = RootStats::default();
        let opts = RootOptions {
            closed_form: false,
            ..RootOptions::new(1e-10)
        };
        let r = p.real_roots_with(-1e-10, 1.0000000001, &opts, &mut stats);
        assert_eq!(r, Ok(vec![]), "no real root");
        // The same with two real roots 2.4e-9 apart near 3e-8.
        let q = planted_f64(&[2.9e-8, 3.14e-8, 0.6]);
        assert_matches_exact(&q, -1e-10, 1.0, &mut stats);
        assert_eq!(stats.exact_fallbacks, 0, "no exact fallback");
    }

    #[test]
    fn close_cluster_is_decided_in_adaptive_precision_without_exact_arithmetic() {
        // Three roots within 2e-9 of 0.4 with O(1) coefficients (two real ones once the
        // coefficients are rounded): f64 cannot separate them; the piece around the cluster
        // used to be isolated exactly. Now double-double decides it, while (0, 0.39] is
        // answered in f64.
        let p = planted_f64(&[0.4, 0.400000001, 0.400000002, 0.9]);
        let mut stats = RootStats::default();
        assert_matches_exact(&p, 0.0, 1.0, &mut stats);
        assert_eq!(stats.exact_fallbacks, 0, "no exact arithmetic");
        assert!(
            stats.adaptive_pieces >= 2,
            "real_roots and smallest_root each took the adaptive path: {stats:?}"
        );
        let search = CertifiedSearch::run(p.coeffs(), 0.0, 1.0, false, Slack::NONE, &mut stats);
        assert!(search.exact_sequence().is_none(), "no exact sequence built");
    }
}

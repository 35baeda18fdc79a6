//! [`RootStats`]: counters a root solver fills in, mergeable across threads.

use std::ops::AddAssign;

use crate::root_error::RootError;

/// Number of per-degree buckets in [`RootStats::by_degree`]; the last bucket collects every
/// degree at or above `STATS_DEGREES - 1`.
pub const STATS_DEGREES: usize = 25;

/// What the root solvers did: how many queries, of which degrees, and how often the certified
/// `f64` path had to fall back to exact rational arithmetic.
///
/// Each thread keeps its own `RootStats` and the totals are summed with [`RootStats::merge`].
///
/// # Examples
/// ```
/// use poly::{Poly, RootOptions, RootStats};
/// let mut a = RootStats::default();
/// let mut b = RootStats::default();
/// let p = Poly::new(vec![-1.0, 0.0, 1.0]); // x² − 1
/// p.smallest_root_with(0.0, 2.0, &RootOptions::new(1e-9), &mut a);
/// p.smallest_root_with(-5.0, 2.0, &RootOptions::new(1e-9), &mut b);
/// a.merge(&b);
/// assert_eq!(a.queries, 2);
/// assert_eq!(a.by_degree[2], 2);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct RootStats {
    /// Root queries answered (including those refused for bad input).
    pub queries: u64,
    /// Queries by degree of the stored polynomial (last bucket: that degree and above).
    pub by_degree: [u64; STATS_DEGREES],
    /// Queries refused: non-finite coefficients, zero polynomial, NaN bounds or tolerance.
    pub rejected: u64,
    /// Queries a heuristic method could not answer ([`RootError::Unresolved`]); always 0
    /// for the certified methods.
    pub unresolved: u64,
    /// Queries that returned at least one root.
    pub with_root: u64,
    /// Queries answered by a certified closed form (degree 1 or 2).
    pub closed_form: u64,
    /// Smallest-root queries answered by guess and verify: a Newton guess from the range's
    /// start, proved by certified signs either side of it and a Bernstein test of the range
    /// before it, with no subdivision or certified refinement (`paper-notes/isolation.md`,
    /// "Guess and verify").
    pub guessed: u64,
    /// Queries whose certified isolation could not decide some sign in `f64` and built the
    /// exact Sturm sequence of the stored polynomial (at most once per query; it is then used
    /// only on the pieces `f64` could not decide). This is the statistic the renderer reports.
    pub exact_fallbacks: u64,
    /// Refinement reached the `f64` noise floor above the tolerance and finished the bracket
    /// with exact rational signs.
    pub refine_fallbacks: u64,
    /// Pieces of an isolation that `f64` could not decide and that went to adaptive precision
    /// (double-double first, then arbitrary-precision floats; `paper-notes/isolation.md`,
    /// "Adaptive precision"). Only what that still cannot decide reaches
    /// [`exact_fallbacks`](Self::exact_fallbacks).
    pub adaptive_pieces: u64,
    /// Of the [`adaptive_pieces`](Self::adaptive_pieces), those decided in `f64` after a
    /// double-double re-expansion at the piece's end (`paper-notes/isolation.md`, "Shifted
    /// `f64` tier"), with no double-double subdivision.
    pub shifted_pieces: u64,
    /// Of the [`shifted_pieces`](Self::shifted_pieces), whole query ranges re-expanded at
    /// the centroid of a cluster of roots far from 0 against its spread, before any `f64`
    /// run (a ray polynomial restricted far from its surface; `paper-notes/isolation.md`,
    /// "Far clusters").
    pub cluster_shifts: u64,
    /// Of the [`adaptive_pieces`](Self::adaptive_pieces), those that needed more than
    /// double-double precision somewhere.
    pub multiprecision_pieces: u64,
    /// Refinements that `f64` could not finish and that were finished with adaptive-precision
    /// signs (before any exact refinement, [`refine_fallbacks`](Self::refine_fallbacks)).
    pub adaptive_refines: u64,
    /// Queries with a value slack ([`RootQuery::value_slack`](crate::RootQuery::value_slack))
    /// that a sign within the slack left undecided ([`RootError::SlackLimited`]).
    pub slack_limited: u64,
    /// Interval subdivisions (de Casteljau splits or Sturm bisections) during isolation.
    pub subdivisions: u64,
    /// Polynomial evaluations during refinement.
    pub refine_evals: u64,
    /// All-roots queries (and their pieces around an exact root 0) whose real roots the
    /// inclusion discs decided (`inclusion.rs`; `paper-notes/isolation.md`, "Inclusion
    /// discs"), without any subdivision.
    pub inclusion_decided: u64,
    /// All-roots queries (or pieces) that tried the inclusion discs and were left undecided
    /// in some part of the range (overlapping discs, a non-real disc meeting the range, an
    /// uncertain sign) or in all of it (no convergence, overflow): those parts were answered
    /// by subdivision.
    pub inclusion_undecided: u64,
    /// Parts of a query range that the inclusion discs left undecided and that subdivision
    /// answered on that part alone (the union of the shadows of the discs that decided
    /// nothing; `paper-notes/isolation.md`, "Undecided parts"). A query the discs could not
    /// narrow at all is subdivided whole and counts none here.
    pub inclusion_subranges: u64,
    /// All-roots queries (or pieces) answered by a subdivision in `f64` with a budget of
    /// splits, tried before the inclusion discs, which were then not needed
    /// (`paper-notes/isolation.md`, "Subdivision first, on a budget"). A query whose budgeted
    /// subdivision gave up goes on to the discs and is counted there; its subdivisions stay
    /// in [`subdivisions`](Self::subdivisions).
    pub subdivided_first: u64,
}

impl RootStats {
    /// Adds every counter of `other` into `self`.
    pub fn merge(&mut self, other: &RootStats) {
        self.queries += other.queries;
        for (a, b) in self.by_degree.iter_mut().zip(other.by_degree.iter()) {
            *a += b;
        }
        self.rejected += other.rejected;
        self.unresolved += other.unresolved;
        self.with_root += other.with_root;
        self.closed_form += other.closed_form;
        self.guessed += other.guessed;
        self.exact_fallbacks += other.exact_fallbacks;
        self.refine_fallbacks += other.refine_fallbacks;
        self.adaptive_pieces += other.adaptive_pieces;
        self.shifted_pieces += other.shifted_pieces;
        self.cluster_shifts += other.cluster_shifts;
        self.multiprecision_pieces += other.multiprecision_pieces;
        self.adaptive_refines += other.adaptive_refines;
        self.slack_limited += other.slack_limited;
        self.subdivisions += other.subdivisions;
        self.refine_evals += other.refine_evals;
        self.inclusion_decided += other.inclusion_decided;
        self.inclusion_undecided += other.inclusion_undecided;
        self.inclusion_subranges += other.inclusion_subranges;
        self.subdivided_first += other.subdivided_first;
    }

    /// Fraction of queries that fell back to exact isolation (0 when there were no queries).
    pub fn fallback_rate(&self) -> f64 {
        if self.queries == 0 {
            0.0
        } else {
            self.exact_fallbacks as f64 / self.queries as f64
        }
    }

    /// Records one query of a polynomial of degree `degree`.
    pub(crate) fn count_query(&mut self, degree: usize) {
        self.queries += 1;
        self.by_degree[degree.min(STATS_DEGREES - 1)] += 1;
    }

    /// Records a query that ended in `e`: unresolved by a heuristic, or refused.
    pub(crate) fn count_error(&mut self, e: &RootError) {
        match e {
            RootError::Unresolved { .. } => self.unresolved += 1,
            RootError::SlackLimited { .. } => self.slack_limited += 1,
            _ => self.rejected += 1,
        }
    }

    /// Runs one all-roots query of a polynomial of degree `degree` and records it: counted,
    /// refused or unresolved, or with at least one root. The query returns how many roots it
    /// found.
    pub(crate) fn record_all(
        &mut self,
        degree: usize,
        query: impl FnOnce(&mut RootStats) -> Result<usize, RootError>,
    ) -> Result<usize, RootError> {
        self.count_query(degree);
        let result = query(self);
        match &result {
            Err(e) => self.count_error(e),
            Ok(found) if *found > 0 => self.with_root += 1,
            Ok(_) => {}
        }
        result
    }
}

impl AddAssign<&RootStats> for RootStats {
    fn add_assign(&mut self, rhs: &RootStats) {
        self.merge(rhs);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn merge_adds_every_counter() {
        let mut a = RootStats::default();
        a.count_query(4);
        a.count_query(40);
        a.exact_fallbacks = 1;
        a.guessed = 9;
        a.inclusion_decided = 5;
        a.inclusion_undecided = 6;
        a.shifted_pieces = 2;
        a.cluster_shifts = 3;
        a.inclusion_subranges = 8;
        a.subdivided_first = 11;
        let mut b = a.clone();
        b.subdivisions = 7;
        b.refine_evals = 3;
        b.adaptive_pieces = 2;
        b.multiprecision_pieces = 1;
        b.adaptive_refines = 4;
        b.merge(&a);
        assert_eq!(b.queries, 4, "2 + 2 queries");
        assert_eq!(b.by_degree[4], 2, "degree 4 twice");
        assert_eq!(
            b.by_degree[STATS_DEGREES - 1],
            2,
            "degree 40 lands in the last bucket"
        );
        assert_eq!(b.exact_fallbacks, 2, "fallbacks summed");
        assert_eq!(b.guessed, 18, "guesses summed");
        assert_eq!(b.subdivisions, 7, "only b had subdivisions");
        assert_eq!(
            (
                b.adaptive_pieces,
                b.multiprecision_pieces,
                b.adaptive_refines
            ),
            (2, 1, 4),
            "adaptive counters kept"
        );
        assert_eq!(b.shifted_pieces, 4, "shifted pieces summed");
        assert_eq!(b.cluster_shifts, 6, "cluster shifts summed");
        assert_eq!(
            (
                b.inclusion_decided,
                b.inclusion_undecided,
                b.inclusion_subranges
            ),
            (10, 12, 16),
            "inclusion counters summed"
        );
        assert_eq!(b.subdivided_first, 22, "subdivisions first summed");
        assert_eq!(b.fallback_rate(), 0.5, "2 of 4");
        let mut c = RootStats::default();
        c += &b;
        assert_eq!(c, b, "+= is merge");
    }
}

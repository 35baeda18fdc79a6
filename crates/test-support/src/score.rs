//! Scoring a solver's answer against the certified truth: matched, missed and phantom roots,
//! and the error of each matched root.

use crate::truth::{Truth, abs_error, rel_error};

/// A reported value matches a true root `r` only when it is within
/// `MATCH_RADIUS_REL · max(1, |r|)` of it (relative for large roots, absolute below 1).
/// Farther than that the value is not an approximation of that root at all: the root counts as
/// *missed* and the value as a *phantom*. `1e-3` is loose on purpose — anything between `x_tol`
/// and this shows up in the error columns, not as a count failure.
pub const MATCH_RADIUS_REL: f64 = 1e-3;

/// How a list of reported roots relates to the true ones.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Matching {
    /// `(true index, reported index)` pairs, in increasing order.
    pub pairs: Vec<(usize, usize)>,
    /// True roots with no reported value within the match radius.
    pub missed: usize,
    /// Reported values not matched to a distinct true root (including duplicates of one root).
    pub phantom: usize,
}

/// The one-to-one, order-preserving matching of `found` to `truth` with the most pairs within
/// the match radius, and among those the least total error (dynamic programming; on the real
/// line an optimal matching never crosses).
pub fn match_roots(truth: &Truth, found: &[f64]) -> Matching {
    let mut found: Vec<f64> = found.to_vec();
    found.sort_by(f64::total_cmp);
    let (n, m) = (truth.approx.len(), found.len());
    // best[i][j] = (pairs, −error) for the first i true roots and j values.
    let mut best = vec![vec![(0usize, 0.0f64); m + 1]; n + 1];
    let better = |a: (usize, f64), b: (usize, f64)| a.0 > b.0 || (a.0 == b.0 && a.1 > b.1);
    for i in 0..=n {
        for j in 0..=m {
            if i == 0 && j == 0 {
                continue;
            }
            let mut cell = (0usize, f64::NEG_INFINITY);
            if i > 0 && better(best[i - 1][j], cell) {
                cell = best[i - 1][j];
            }
            if j > 0 && better(best[i][j - 1], cell) {
                cell = best[i][j - 1];
            }
            if i > 0 && j > 0 {
                let r = truth.approx[i - 1];
                let e = (found[j - 1] - r).abs();
                if e <= MATCH_RADIUS_REL * r.abs().max(1.0) {
                    let prev = best[i - 1][j - 1];
                    let cand = (prev.0 + 1, prev.1 - e);
                    if better(cand, cell) {
                        cell = cand;
                    }
                }
            }
            best[i][j] = cell;
        }
    }
    // Walk back.
    let mut pairs = Vec::new();
    let (mut i, mut j) = (n, m);
    while i > 0 && j > 0 {
        if best[i][j] == best[i - 1][j] {
            i -= 1;
        } else if best[i][j] == best[i][j - 1] {
            j -= 1;
        } else {
            pairs.push((i - 1, j - 1));
            i -= 1;
            j -= 1;
        }
    }
    pairs.reverse();
    Matching {
        missed: n - pairs.len(),
        phantom: m - pairs.len(),
        pairs,
    }
}

/// Totals for one (family, parameter, method) cell of the report.
#[derive(Clone, Debug, Default)]
pub struct Score {
    /// Polynomials solved.
    pub cases: usize,
    /// Distinct true roots over all cases.
    pub true_roots: usize,
    /// Values reported over all cases.
    pub reported: usize,
    /// True roots missed.
    pub missed: usize,
    /// Phantom values.
    pub phantom: usize,
    /// Cases with at least one missed or phantom root.
    pub failed_cases: usize,
    /// Absolute error `|x − r|` of every matched root.
    pub abs_err: Vec<f64>,
    /// Relative error `|x − r|/|r|` of every matched non-zero root.
    pub rel_err: Vec<f64>,
    /// Sum over cases of the time per solve, in nanoseconds.
    pub nanos: f64,
    /// `poly`'s exact-arithmetic fallbacks (isolation and refinement) over all cases.
    pub fallbacks: u64,
}

impl Score {
    /// Adds one solved case: the truth, the values reported and the time per solve.
    pub fn add(&mut self, truth: &Truth, found: &[f64], nanos: f64) {
        let mtch = match_roots(truth, found);
        self.cases += 1;
        self.true_roots += truth.roots.len();
        self.reported += found.len();
        self.missed += mtch.missed;
        self.phantom += mtch.phantom;
        if mtch.missed + mtch.phantom > 0 {
            self.failed_cases += 1;
        }
        let mut sorted = found.to_vec();
        sorted.sort_by(f64::total_cmp);
        for (i, j) in mtch.pairs {
            let r = &truth.roots[i];
            self.abs_err.push(abs_error(sorted[j], r));
            if let Some(e) = rel_error(sorted[j], r) {
                self.rel_err.push(e);
            }
        }
        self.nanos += nanos;
    }

    /// Mean time per solve in nanoseconds (0 with no cases).
    pub fn mean_nanos(&self) -> f64 {
        if self.cases == 0 {
            0.0
        } else {
            self.nanos / self.cases as f64
        }
    }

    /// Whether every root of every case was found with no phantom.
    pub fn counts_ok(&self) -> bool {
        self.missed == 0 && self.phantom == 0
    }
}

/// The largest value (0 for none; NaN-free inputs).
pub fn max(v: &[f64]) -> f64 {
    v.iter().copied().fold(0.0, f64::max)
}

/// The median (0 for none).
pub fn median(v: &[f64]) -> f64 {
    if v.is_empty() {
        return 0.0;
    }
    let mut s = v.to_vec();
    s.sort_by(f64::total_cmp);
    let k = s.len() / 2;
    if s.len() % 2 == 1 {
        s[k]
    } else {
        0.5 * (s[k - 1] + s[k])
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::truth::stored_truth;
    use poly::Poly;

    #[test]
    fn matching_counts_missed_phantom_and_duplicates() {
        let p = Poly::<f64>::from_roots(&[0.25, 0.5, 2.0]);
        let t = stored_truth(&p, -4.0, 4.0);
        assert_eq!(t.roots.len(), 3, "three roots");
        let m = match_roots(&t, &[0.5, 0.25 + 1e-12, 3.0]);
        assert_eq!(m.pairs, vec![(0, 0), (1, 1)], "sorted pairs");
        assert_eq!((m.missed, m.phantom), (1, 1), "2.0 missed, 3.0 phantom");
        let m = match_roots(&t, &[0.5, 0.5, 0.25, 2.0]);
        assert_eq!((m.missed, m.phantom), (0, 1), "a duplicate is a phantom");
        let mut s = Score::default();
        s.add(&t, &[0.25, 0.5 + 2.0f64.powi(-40), 2.0], 10.0);
        assert!(s.counts_ok(), "all found");
        assert_eq!(
            max(&s.abs_err),
            2.0f64.powi(-40),
            "largest error is the perturbed root"
        );
        assert_eq!(median(&[3.0, 1.0, 2.0]), 2.0, "median of three");
        assert_eq!(median(&[4.0, 1.0, 2.0, 3.0]), 2.5, "median of four");
    }
}

//! [`PatchStats`]: what the Bézier patch intersector did — Stam's per-image table (article §5:
//! size of the Gröbner basis, degree of the polynomial in `u`, degree of the polynomial in `v`)
//! as histograms over every algebraic solve, and where candidates were rejected.

use std::fmt;

/// Histogram bins: values `0..HIST_BINS - 1` each have a bin, larger values share the last.
/// 32 covers the bicubic Bézout bound (eliminant degree 18) with room to spare.
pub const HIST_BINS: usize = 32;

/// Counters of the patch intersector, one set per worker thread, merged at the end.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct PatchStats {
    /// Ray/sub-patch pairs that reached the algebra (bounding boxes passed).
    pub solves: u64,
    /// Ray/sub-patch pairs rejected by a box of the patch BVH before any algebra.
    pub bbox_rejects: u64,
    /// Nodes of the mesh's [`Bvh`](crate::aggregate::Bvh) visited.
    pub bvh_node_visits: u64,
    /// Ray/sub-patch pairs whose box the ray crosses but whose control-point hull lies on one
    /// side of a plane through the ray (no algebra needed).
    pub hull_rejects: u64,
    /// Histogram of the Gröbner basis size (0 for the resultant method).
    pub basis_size: [u64; HIST_BINS],
    /// Histogram of the degree of the `u`-polynomial (eliminant or resultant; 0 when the
    /// elimination decided without one).
    pub u_degree: [u64; HIST_BINS],
    /// Histogram of the `v`-degree of the polynomial solved for `v` (0 when none).
    pub v_degree: [u64; HIST_BINS],
    /// Solves where the algebra proved there is no common root (`1 ∈ G`, Theorem 1).
    pub no_common_root: u64,
    /// Solves where the curves share a component (the ray lies in the surface): no hit.
    pub infinite: u64,
    /// `(u, v)` candidates rejected by the solver's residual test on `F1`, `F2`.
    pub rejected_by_solver: u64,
    /// Verified `(u, v)` roots rejected by the 3-D residual test
    /// ([`HIT_RESIDUAL_REL`](crate::surface::HIT_RESIDUAL_REL)).
    pub rejected_by_residual: u64,
    /// Verified roots whose `t` lay outside the query range (behind the origin, or beyond
    /// the nearest hit so far).
    pub outside_range: u64,
    /// Solves that returned an error (limits exceeded); the sub-patch is treated as missed.
    pub errors: u64,
    /// `GROEBNER` solves whose `f64` basis could not be certified, so the Bézout resultant
    /// was solved instead (`groebner::SolveStats::fallback`; paper-notes/groebner.md §5).
    pub groebner_fallbacks: u64,
    /// Nanoseconds in ray/sub-patch tests (building `F1`, `F2`, solving, verifying).
    pub test_nanos: u64,
    /// Of which nanoseconds in the elimination and root finding ([`groebner::solve`]).
    pub solve_nanos: u64,
}

fn bin(value: usize) -> usize {
    value.min(HIST_BINS - 1)
}

impl PatchStats {
    /// Records one solve's basis size and degrees.
    pub fn record_degrees(&mut self, basis_size: usize, u_degree: usize, v_degree: usize) {
        self.basis_size[bin(basis_size)] += 1;
        self.u_degree[bin(u_degree)] += 1;
        self.v_degree[bin(v_degree)] += 1;
    }

    /// Adds every counter of `o`.
    pub fn merge(&mut self, o: &PatchStats) {
        self.solves += o.solves;
        self.bbox_rejects += o.bbox_rejects;
        self.bvh_node_visits += o.bvh_node_visits;
        self.hull_rejects += o.hull_rejects;
        for (a, b) in [
            (&mut self.basis_size, &o.basis_size),
            (&mut self.u_degree, &o.u_degree),
            (&mut self.v_degree, &o.v_degree),
        ] {
            for (x, y) in a.iter_mut().zip(b) {
                *x += y;
            }
        }
        self.no_common_root += o.no_common_root;
        self.infinite += o.infinite;
        self.rejected_by_solver += o.rejected_by_solver;
        self.rejected_by_residual += o.rejected_by_residual;
        self.outside_range += o.outside_range;
        self.errors += o.errors;
        self.groebner_fallbacks += o.groebner_fallbacks;
        self.test_nanos += o.test_nanos;
        self.solve_nanos += o.solve_nanos;
    }

    /// The values seen in a histogram with their counts, smallest value first.
    pub fn nonzero(hist: &[u64; HIST_BINS]) -> impl Iterator<Item = (usize, u64)> + '_ {
        hist.iter()
            .enumerate()
            .filter(|(_, n)| **n > 0)
            .map(|(v, n)| (v, *n))
    }
}

impl fmt::Display for PatchStats {
    /// Stam's table (article §5) as histograms, then rejections and time per test.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        writeln!(f, "Bezier patches (Stam's table, article 5)")?;
        writeln!(
            f,
            "  ray/sub-patch solves               {:>12}",
            self.solves
        )?;
        writeln!(
            f,
            "  BVH box rejections                 {:>12}",
            self.bbox_rejects
        )?;
        writeln!(
            f,
            "  BVH node visits                    {:>12}",
            self.bvh_node_visits
        )?;
        writeln!(
            f,
            "  control-hull rejections            {:>12}",
            self.hull_rejects
        )?;
        for (name, hist) in [
            ("basis size", &self.basis_size),
            ("degree in u", &self.u_degree),
            ("degree in v", &self.v_degree),
        ] {
            let mut line = String::new();
            for (value, n) in PatchStats::nonzero(hist) {
                let plus = if value == HIST_BINS - 1 { "+" } else { "" };
                line.push_str(&format!(" {value}{plus}:{n}"));
            }
            writeln!(f, "  {name:<12}{line}")?;
        }
        writeln!(
            f,
            "  no common root (1 in G)            {:>12}",
            self.no_common_root
        )?;
        writeln!(
            f,
            "  ray inside the surface (infinite)  {:>12}",
            self.infinite
        )?;
        writeln!(
            f,
            "  rejected by F1,F2 residual         {:>12}",
            self.rejected_by_solver
        )?;
        writeln!(
            f,
            "  rejected by 3-D residual           {:>12}",
            self.rejected_by_residual
        )?;
        writeln!(
            f,
            "  t outside the range                {:>12}",
            self.outside_range
        )?;
        writeln!(
            f,
            "  solver errors (treated as miss)    {:>12}",
            self.errors
        )?;
        writeln!(
            f,
            "  Groebner basis not certified (f64), resultant used {:>8}",
            self.groebner_fallbacks
        )?;
        if self.solves > 0 {
            let per = self.test_nanos as f64 / self.solves as f64 / 1e3;
            let share = 100.0 * self.solve_nanos as f64 / (self.test_nanos.max(1)) as f64;
            writeln!(
                f,
                "  time per test {per:>9.2} us ({share:.0}% in elimination + roots)"
            )?;
        }
        Ok(())
    }
}

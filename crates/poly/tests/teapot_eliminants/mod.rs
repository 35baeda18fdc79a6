//! The teapot corpus (`tests/data/teapot_eliminants.txt`): real-root queries recorded from the
//! Bézier-patch ray tracer (resultant eliminants of degree 8–17, their derivatives, and the
//! cubics in `v`), answered by the default certified path and checked against exact Sturm
//! counts on the stored polynomials; and the design assertion that none of them needs the
//! exact fallback (`paper-notes/isolation.md`, "Teapot eliminants").

use poly::{QPoly, Rat, RootInterval, RootOptions, RootStats, SturmSequence, rat_from_f64};

mod corpus;

use corpus::{Query, corpus};

fn q(x: f64) -> Rat {
    rat_from_f64(x).expect("finite")
}

/// Checks with exact Sturm counts that `got` (sorted) are the first `got.len()` distinct roots
/// of the stored polynomial in `(lo, hi]` (all of them when `all`, at least one if any when
/// not), the `i`-th within `x_tol` of the `i`-th root: at most `i` roots lie in
/// `(lo, gᵢ − x_tol]` and at least `i + 1` in `(lo, gᵢ + x_tol]`.
fn check_roots(seq: &SturmSequence<Rat>, qy: &Query, got: &[f64], all: bool, what: &str) {
    let (lo, tol) = (q(qy.lo), q(qy.x_tol));
    let total = seq.count_roots(&lo, &q(qy.hi));
    let want = if all { total } else { total.min(1) };
    assert_eq!(
        got.len(),
        want,
        "{what}: {got:?}, exact count {total}, {:?}",
        qy.p
    );
    for (i, &g) in got.iter().enumerate() {
        let below = seq.count_roots(&lo, &(q(g) - &tol));
        let upto = seq.count_roots(&lo, &(q(g) + &tol));
        assert!(
            below <= i && upto > i,
            "{what}: root {i} = {g} is not within x_tol of the exact one ({below}, {upto}), {:?}",
            qy.p
        );
    }
}

#[test]
fn teapot_corpus_matches_exact_sturm_without_exact_fallbacks() {
    let corpus = corpus();
    assert!(
        corpus.len() >= 300,
        "the fixture holds a few hundred queries"
    );
    let mut stats = RootStats::default();
    let mut with_zero_factor = 0;
    for qy in &corpus {
        let opts = RootOptions::new(qy.x_tol);
        let exact: QPoly = qy.p.to_rat().expect("finite coefficients");
        let seq = exact.sturm().expect("non-zero");
        with_zero_factor += usize::from(qy.p.coeff(0) == 0.0);

        let roots =
            qy.p.real_roots_with(qy.lo, qy.hi, &opts, &mut stats)
                .expect("valid query");
        check_roots(&seq, qy, &roots, true, "real_roots");

        let first = qy.p.smallest_root_with(qy.lo, qy.hi, &opts, &mut stats);
        let first: Vec<f64> = first.into_iter().collect();
        check_roots(&seq, qy, &first, false, "smallest_root");

        // Isolating intervals: each holds exactly one distinct exact root.
        let ivs =
            qy.p.isolate_roots_with(qy.lo, qy.hi, &opts, &mut stats)
                .expect("valid query");
        assert_eq!(ivs.len(), roots.len(), "{} isolate_roots count", qy.tag);
        for RootInterval { lo, hi } in &ivs {
            let n = if lo == hi {
                usize::from(seq.sign_of_square_free_at(&q(*lo)) == 0)
            } else {
                // The open interval (lo, hi): (lo, hi] minus a root at hi.
                seq.count_roots(&q(*lo), &q(*hi))
                    - usize::from(seq.sign_of_square_free_at(&q(*hi)) == 0)
            };
            assert_eq!(n, 1, "interval ({lo}, {hi}) of {:?}", qy.p);
        }
    }
    // The corpus over-represents eliminants with an exact factor u^k (collapsed patch edges):
    // before they were deflated, each of those (100 of 374 queries) took the exact fallback.
    assert!(with_zero_factor >= 100, "fixture still has the u^k cases");
    assert_eq!(
        stats.exact_fallbacks, 0,
        "design: every teapot query is certified in f64 (measured: 0 of 374)"
    );
    assert_eq!(
        stats.refine_fallbacks, 0,
        "no refinement reached the f64 floor"
    );
}

//! Exact rational Sturm isolation on the classic hard cases (issue 6 §3): every root of
//! Wilkinson's polynomial of degree 20 and of the Chebyshev polynomial T₃₀, each in its own
//! interval, in order, none missed.

use num_traits::Signed;
use poly::testutil::{chebyshev, chebyshev_roots, rat, wilkinson};
use poly::{Rat, rat_from_f64, rat_to_f64};

#[test]
fn exact_sturm_isolates_wilkinson_20() {
    let w = wilkinson(20);
    let ivs = w.isolate_roots(&rat(0, 1), &rat(21, 1)).expect("non-zero");
    assert_eq!(ivs.len(), 20, "twenty distinct roots in (0, 21]");
    for (k, iv) in (1..=20).zip(&ivs) {
        let r = rat(k, 1);
        let inside = if iv.is_point() {
            iv.lo == r
        } else {
            iv.lo < r && r < iv.hi
        };
        assert!(inside, "root {k} in interval {k}: ({}, {})", iv.lo, iv.hi);
    }
    for pair in ivs.windows(2) {
        assert!(pair[0].hi <= pair[1].lo, "disjoint and sorted");
    }
}

#[test]
fn exact_sturm_isolates_chebyshev_30() {
    let t = chebyshev(30);
    let seq = t.sturm().expect("non-zero");
    assert_eq!(seq.count_real_roots(), 30, "T30 has 30 real roots");
    let ivs = t.isolate_roots(&rat(-1, 1), &rat(1, 1)).expect("non-zero");
    assert_eq!(ivs.len(), 30, "all in (−1, 1]");
    // Narrow each to 2^-60 and compare with cos((2k − 1)π/60), accurate to a few ulps.
    let tol = 1e-15;
    for (iv, want) in ivs.iter().zip(chebyshev_roots(30)) {
        let narrow = seq.refine_interval(iv, 60);
        let mid = (&narrow.lo + &narrow.hi) / rat(2, 1);
        let err: Rat = (&mid - rat_from_f64(want).expect("finite")).abs();
        assert!(
            rat_to_f64(&err) <= tol,
            "root near {want}: exact interval ({}, {}) is {} away",
            rat_to_f64(&narrow.lo),
            rat_to_f64(&narrow.hi),
            rat_to_f64(&err)
        );
    }
}

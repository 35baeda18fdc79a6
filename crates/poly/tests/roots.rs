//! Root finding against exact oracles: planted rational roots, Sturm counts, Wilkinson's
//! polynomial, agreement of the methods, and agreement of the `f64` path with exact
//! arithmetic on the *stored* polynomial.
//!
//! Oracles: the distinct planted roots (for polynomials built exactly over the rationals), and
//! the exact Sturm isolation of `p.to_rat()` refined to 2^-80 (for `f64` polynomials, whose
//! roots are not the planted ones once the coefficients are rounded).

use num_traits::{Signed, Zero};
use poly::testutil::{chebyshev, chebyshev_roots, planted, planted_count, rat, wilkinson};
use poly::{
    IsolationMethod, Poly, QPoly, Rat, RefineMethod, RootError, RootOptions, RootStats,
    rat_from_f64, rat_to_f64,
};
use proptest::prelude::*;

/// Exact distinct roots of the stored `f64` polynomial in `(a, b]`, each to within 2^-80.
fn exact_roots(p: &Poly<f64>, a: f64, b: f64) -> Vec<f64> {
    let q = p.to_rat().expect("finite");
    let (a, b) = (rat_from_f64(a).unwrap(), rat_from_f64(b).unwrap());
    let seq = q.sturm().expect("non-zero");
    q.isolate_roots(&a, &b)
        .expect("non-zero")
        .iter()
        .map(|iv| rat_to_f64(&seq.refine_interval(iv, 80).lo))
        .collect()
}

/// `|got − want| ≤ x_tol`, or within one ulp (the documented floor) plus the oracle's 2^-80.
fn close(got: f64, want: f64, x_tol: f64) -> bool {
    (got - want).abs() <= x_tol.max(2.0 * f64::EPSILON * want.abs()) + 1e-24
}

fn all_methods() -> Vec<RootOptions> {
    let mut v = Vec::new();
    for isolation in [IsolationMethod::Bernstein, IsolationMethod::Exact] {
        for refine in [
            RefineMethod::Bisection,
            RefineMethod::Illinois,
            RefineMethod::NewtonBisection,
        ] {
            v.push(RootOptions {
                isolation,
                refine,
                ..RootOptions::new(1e-11)
            });
        }
    }
    v
}

#[test]
fn planted_rational_roots_are_recovered_exactly() {
    let roots = [
        rat(-7, 3),
        rat(-1, 2),
        rat(1, 7),
        rat(1, 6),
        rat(5, 4),
        rat(5, 4),
        rat(9, 1),
    ];
    let p = planted(&roots);
    let ivs = p.isolate_roots(&rat(-10, 1), &rat(9, 1)).unwrap();
    let distinct = poly::testutil::distinct_sorted(&roots);
    assert_eq!(
        ivs.len(),
        distinct.len(),
        "one interval per distinct root: {ivs:?}"
    );
    let seq = p.sturm().unwrap();
    for (iv, r) in ivs.iter().zip(&distinct) {
        // Narrow to 2^-200: a rational with small denominator is then the only candidate,
        // and it must be inside (or be the point).
        let fine = seq.refine_interval(iv, 200);
        let inside = if fine.is_point() {
            fine.lo == *r
        } else {
            fine.lo < *r && *r < fine.hi
        };
        assert!(inside, "root {r} not in {fine:?}");
    }
    assert!(
        ivs.last().unwrap().is_point(),
        "the end b = 9 is a root: a point interval"
    );
    // Rounded to f64: the 7 planted roots are recovered within x_tol by real_roots.
    let got = p.real_roots(&rat(-10, 1), &rat(10, 1), 1e-13).unwrap();
    assert_eq!(got.len(), 6, "six distinct roots");
    for (g, r) in got.iter().zip(&distinct) {
        assert!(close(*g, rat_to_f64(r), 1e-13), "{g} vs {r}");
    }
}

#[test]
fn planted_dyadic_roots_in_f64_within_tolerance() {
    // Dyadic roots with few bits: the f64 product of (x − rᵢ) is exact, so the stored
    // polynomial's roots are exactly the planted ones.
    let roots = [-3.5, -0.25, 0.125, 0.75, 2.0, 6.5];
    let p = Poly::<f64>::from_roots(&roots);
    let exact = QPoly::from_roots(&roots.map(|r| rat_from_f64(r).unwrap()));
    assert_eq!(p.to_rat().unwrap(), exact, "the f64 product is exact here");
    for opts in all_methods() {
        let mut stats = RootStats::default();
        let got = p.real_roots_with(-10.0, 10.0, &opts, &mut stats).unwrap();
        assert_eq!(got.len(), roots.len(), "{opts:?}");
        for (g, r) in got.iter().zip(&roots) {
            assert!(close(*g, *r, opts.x_tol), "{opts:?}: {g} vs {r}");
        }
        // Smallest root after each planted root is the next one (open left end).
        for w in roots.windows(2) {
            let s = p.smallest_root_with(w[0], 10.0, &opts, &mut stats).unwrap();
            assert!(
                close(s, w[1], opts.x_tol),
                "{opts:?}: after {} got {s}",
                w[0]
            );
        }
    }
}

#[test]
fn wilkinson_20_exact_path_finds_all_twenty() {
    let w = wilkinson(20);
    let ivs = w.isolate_roots(&rat(0, 1), &rat(21, 1)).unwrap();
    assert_eq!(ivs.len(), 20, "twenty distinct roots");
    let seq = w.sturm().unwrap();
    for (k, iv) in (1..=20).zip(&ivs) {
        let fine = seq.refine_interval(iv, 60);
        let r = rat(k, 1);
        let inside = if fine.is_point() {
            fine.lo == r
        } else {
            fine.lo < r && r < fine.hi
        };
        assert!(inside, "root {k} not in {fine:?}");
    }
    let got = w.real_roots(&rat(0, 1), &rat(21, 1), 0.0).unwrap();
    assert_eq!(
        got,
        (1..=20).map(f64::from).collect::<Vec<_>>(),
        "exact roots, exactly"
    );
}

#[test]
fn wilkinson_20_f64_path_finds_the_roots_of_the_stored_polynomial() {
    // The coefficients of ∏(x − k) reach 20! ≈ 2.4e18 and are rounded to f64. The stored
    // polynomial is a different polynomial: its real roots are not the integers. The certified
    // f64 path must return exactly the real roots of the *stored* polynomial; what it
    // measures about the rounding is checked here too (how far the roots moved).
    let w = wilkinson(20).to_f64();
    let exact = exact_roots(&w, 0.0, 25.0);
    let mut stats = RootStats::default();
    let got = w
        .real_roots_with(0.0, 25.0, &RootOptions::new(1e-9), &mut stats)
        .unwrap();
    assert_eq!(
        got.len(),
        exact.len(),
        "same number of real roots as the stored polynomial"
    );
    for (g, e) in got.iter().zip(&exact) {
        assert!(close(*g, *e, 1e-9), "{g} vs exact {e}");
    }
    // Rounding the coefficients moved the roots near 14–16 far more than the others
    // (Wilkinson 1959); a few real roots may have merged into complex pairs.
    let moved = exact
        .iter()
        .map(|r| (r - r.round()).abs())
        .fold(0.0f64, f64::max);
    assert!(
        moved > 1e-6,
        "the stored polynomial's roots are not integers: {moved:e}"
    );
    assert!(exact.len() <= 20, "at most twenty real roots");
    // What the f64 path does here: the certified Bernstein isolation cannot certify the
    // signs of this degree-20 polynomial with 19-digit coefficients and redoes the query
    // exactly, once (the whole query, not per root).
    assert!(stats.exact_fallbacks <= 1, "{stats:?}");
    // The floating-point Sturm sequence (a heuristic) counted all of them here by luck: near
    // the moved roots some member's sign is below its own rounding bound and decides the
    // count, and since issue 11 ("heuristic methods never lie silently") it says so instead
    // of answering. Either way it never answers wrongly.
    let opts = RootOptions {
        isolation: IsolationMethod::Sturm,
        ..RootOptions::new(1e-9)
    };
    match w.real_roots_with(0.0, 25.0, &opts, &mut stats) {
        Ok(sturm) => assert_eq!(sturm.len(), exact.len(), "normalised f64 Sturm: {sturm:?}"),
        Err(RootError::Unresolved { lo, hi }) => assert!(
            exact.iter().any(|&r| lo < r && r <= hi),
            "the unresolved piece ({lo}, {hi}] holds stored roots: {exact:?}"
        ),
        Err(e) => panic!("normalised f64 Sturm: {e}"),
    }
    // The first few roots are well conditioned and stay close to the integers.
    assert!(
        (got[0] - 1.0).abs() < 1e-9 && (got[1] - 2.0).abs() < 1e-9,
        "{got:?}"
    );
}

#[test]
fn chebyshev_roots_by_every_certified_method() {
    let t = chebyshev(9).to_f64();
    let want = chebyshev_roots(9);
    for opts in all_methods() {
        let mut stats = RootStats::default();
        let got = t.real_roots_with(-1.0, 1.0, &opts, &mut stats).unwrap();
        assert_eq!(got.len(), 9, "{opts:?}");
        for (g, w) in got.iter().zip(&want) {
            // The stored T9 is exact (integer coefficients), so only x_tol and the oracle's
            // own rounding of cos() (a few ulps) separate the two.
            assert!((g - w).abs() <= 1e-11 + 1e-15, "{opts:?}: {g} vs {w}");
        }
    }
}

#[test]
fn heuristic_sturm_methods_agree_on_an_easy_case() {
    let p = Poly::<f64>::from_roots(&[0.3, 1.7, 2.2, 4.1]);
    for isolation in [IsolationMethod::Sturm, IsolationMethod::StamSturm] {
        let opts = RootOptions {
            isolation,
            ..RootOptions::new(1e-10)
        };
        let mut stats = RootStats::default();
        let got = p.real_roots_with(0.0, 5.0, &opts, &mut stats).unwrap();
        assert_eq!(got.len(), 4, "{isolation:?}: {got:?}");
        let r = p.smallest_root_with(1.0, 5.0, &opts, &mut stats).unwrap();
        assert!((r - 1.7).abs() <= 1e-9, "{isolation:?}: {r}");
    }
}

#[test]
fn bad_input_gives_typed_errors() {
    let mut stats = RootStats::default();
    let opts = RootOptions::new(1e-9);
    let nan = Poly::new(vec![1.0, f64::NAN, 1.0]);
    assert_eq!(
        nan.real_roots(0.0, 1.0, 1e-9),
        Err(RootError::NonFiniteCoefficient { index: 1 }),
        "NaN coefficient"
    );
    assert_eq!(nan.smallest_root(0.0, 1.0, 1e-9), None, "documented None");
    assert_eq!(
        Poly::<f64>::zero().isolate_roots(0.0, 1.0),
        Err(RootError::ZeroPolynomial),
        "zero"
    );
    assert_eq!(
        QPoly::zero().isolate_roots(&rat(0, 1), &rat(1, 1)),
        Err(RootError::ZeroPolynomial),
        "zero"
    );
    let p = Poly::new(vec![-1.0, 0.0, 1.0]);
    assert_eq!(
        p.real_roots(f64::NAN, 1.0, 1e-9),
        Err(RootError::NanBound),
        "NaN bound"
    );
    assert_eq!(
        p.real_roots(0.0, 1.0, f64::NAN),
        Err(RootError::InvalidTolerance),
        "NaN tol"
    );
    assert_eq!(
        p.real_roots(0.0, 1.0, f64::INFINITY),
        Err(RootError::InvalidTolerance),
        "infinite tol"
    );
    assert_eq!(
        p.real_roots(3.0, -3.0, 1e-9),
        Ok(vec![]),
        "reversed interval holds nothing"
    );
    assert_eq!(
        p.sturm().unwrap().count_roots(3.0, -3.0),
        0,
        "reversed: count 0"
    );
    assert_eq!(
        p.try_smallest_root(-3.0, 3.0, &opts, &mut stats),
        Ok(Some(-1.0)),
        "−1 first"
    );
    let q = planted(&[rat(1, 2)]);
    assert_eq!(
        q.real_roots(&rat(0, 1), &rat(1, 1), -1.0),
        Err(RootError::InvalidTolerance),
        "tol"
    );
    assert_eq!(
        q.smallest_root(&rat(1, 1), &rat(0, 1), 1e-9),
        None,
        "reversed rational interval"
    );
}

#[test]
fn double_roots_and_tangencies_are_found() {
    // A tangent ray: (t − 2)²(t − 5)(t + 1). f64 cannot certify a sign near t = 2; the query
    // falls back to exact arithmetic and still answers 2.
    let p = Poly::<f64>::from_roots(&[2.0, 2.0, 5.0, -1.0]);
    let mut stats = RootStats::default();
    let r = p
        .smallest_root_with(0.0, 10.0, &RootOptions::new(1e-12), &mut stats)
        .unwrap();
    assert!((r - 2.0).abs() <= 1e-12, "double root: {r}");
    assert_eq!(stats.exact_fallbacks, 1, "the fallback is counted");
    // Nearly tangent, no real root near 2: (t − 2)² + 1e-12, times (t − 5).
    let near = &(&Poly::<f64>::from_roots(&[2.0, 2.0]) + &Poly::constant(1e-12))
        * &Poly::new(vec![-5.0, 1.0]);
    let r = near.smallest_root(0.0, 10.0, 1e-12).unwrap();
    assert!(
        (r - 5.0).abs() <= 1e-12,
        "the complex pair near 2 is not a root: {r}"
    );
}

/// Rationals p/q with small q, in a range.
fn small_rat(range: i64) -> impl Strategy<Value = Rat> {
    (
        -range * 8..=range * 8,
        prop::sample::select(vec![1i64, 2, 3, 4, 8]),
    )
        .prop_map(|(n, d)| rat(n, 8 * d))
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 48, ..ProptestConfig::default() })]

    /// Sturm counts equal planted counts, with interval ends chosen among the roots (so ends
    /// that are roots, and double roots, are exercised) or at random.
    #[test]
    fn sturm_counts_match_planted_counts(
        roots in prop::collection::vec(small_rat(4), 1..7),
        doubles in prop::collection::vec(any::<bool>(), 7),
        ends in (any::<prop::sample::Index>(), any::<prop::sample::Index>(), small_rat(5), small_rat(5), 0u8..3),
    ) {
        let mut all = roots.clone();
        for (r, d) in roots.iter().zip(&doubles) {
            if *d { all.push(r.clone()); }
        }
        let p = planted(&all);
        let seq = p.sturm().unwrap();
        let (i, j, x, y, mode) = ends;
        let (a, b) = match mode {
            0 => (i.get(&all).clone(), j.get(&all).clone()),
            1 => (i.get(&all).clone(), y),
            _ => (x, y),
        };
        prop_assert_eq!(seq.count_roots(&a, &b), planted_count(&all, &a, &b));
        prop_assert_eq!(seq.count_roots(&b, &a), planted_count(&all, &b, &a));
        // Isolation agrees with the count, and each interval holds one planted root.
        let ivs = p.isolate_roots(&a, &b).unwrap();
        prop_assert_eq!(ivs.len(), planted_count(&all, &a, &b));
        for iv in &ivs {
            let hits = poly::testutil::distinct_sorted(&all)
                .into_iter()
                .filter(|r| if iv.is_point() { *r == iv.lo } else { iv.lo < *r && *r < iv.hi })
                .count();
            prop_assert_eq!(hits, 1, "interval {:?}", iv);
        }
        // The f64 certified path on the same polynomial (exact in f64 when it rounds
        // exactly) agrees with the exact count of its stored coefficients.
        let pf = p.to_f64();
        let (af, bf) = (rat_to_f64(&a), rat_to_f64(&b));
        let got = pf.real_roots(af, bf, 1e-10).unwrap();
        let want = exact_roots(&pf, af, bf);
        prop_assert_eq!(got.len(), want.len());
        for (g, w) in got.iter().zip(&want) {
            prop_assert!(close(*g, *w, 1e-10), "{} vs {}", g, w);
        }
    }

    /// Random f64 polynomials up to degree 12: the certified f64 answers equal the exact
    /// answers for the stored coefficients, for every certified method.
    #[test]
    fn f64_agrees_with_exact_on_random_polynomials(
        coeffs in prop::collection::vec(-8.0f64..8.0, 2..14),
        lo in -4.0f64..1.0,
        width in 0.01f64..6.0,
    ) {
        prop_assume!(coeffs.last().is_some_and(|c| c.abs() > 1e-3));
        let p = Poly::new(coeffs);
        let hi = lo + width;
        let want = exact_roots(&p, lo, hi);
        for opts in all_methods() {
            let mut stats = RootStats::default();
            let got = p.real_roots_with(lo, hi, &opts, &mut stats).unwrap();
            prop_assert_eq!(got.len(), want.len(), "{:?}", opts);
            for (g, w) in got.iter().zip(&want) {
                prop_assert!(close(*g, *w, opts.x_tol), "{:?}: {} vs {}", opts, g, w);
            }
            let first = p.smallest_root_with(lo, hi, &opts, &mut stats);
            match (first, want.first()) {
                (None, None) => {}
                (Some(g), Some(w)) => prop_assert!(close(g, *w, opts.x_tol), "{:?}: {} vs {}", opts, g, w),
                (g, w) => prop_assert!(false, "{:?}: smallest {:?} vs exact {:?}", opts, g, w),
            }
        }
    }

    /// Clusters (gaps down to 2^-40), roots on dyadic split points and an exact factor x^k:
    /// the default path's restarts and local exact pieces give the exact answers for the
    /// stored coefficients (count, each root within x_tol, first root, isolating intervals).
    #[test]
    fn certified_search_agrees_with_exact_on_clusters_and_split_points(
        centre in -0.9f64..0.9,
        dyadic in any::<bool>(),
        gaps in prop::collection::vec(1i32..40, 1..4),
        others in prop::collection::vec(-1.0f64..1.0, 0..4),
        zeros in 0usize..3,
        lo in -1.0f64..0.0,
    ) {
        let c = if dyadic { (centre * 8.0).round() / 8.0 } else { centre };
        let mut roots = vec![c];
        for g in &gaps {
            let last = *roots.last().unwrap();
            roots.push(last + 2f64.powi(-g));
        }
        roots.extend(&others);
        let mut coeffs = vec![0.0; zeros];
        coeffs.extend(Poly::<f64>::from_roots(&roots).coeffs());
        let p = Poly::new(coeffs);
        let x_tol = 1e-11;
        let opts = RootOptions::new(x_tol);
        for (a, b) in [(-1.0, 1.0), (lo, 1.0), (-1.0, c)] {
            let want = exact_roots(&p, a, b);
            let mut stats = RootStats::default();
            let got = p.real_roots_with(a, b, &opts, &mut stats).unwrap();
            prop_assert_eq!(got.len(), want.len(), "({}, {}]: {:?} vs {:?}", a, b, got, want);
            for (g, w) in got.iter().zip(&want) {
                prop_assert!(close(*g, *w, x_tol), "{} vs {}", g, w);
            }
            let first = p.smallest_root_with(a, b, &opts, &mut stats);
            prop_assert_eq!(first.is_some(), !want.is_empty());
            if let (Some(g), Some(w)) = (first, want.first()) {
                prop_assert!(close(g, *w, x_tol), "first {} vs {}", g, w);
            }
            let ivs = p.isolate_roots_with(a, b, &opts, &mut stats).unwrap();
            prop_assert_eq!(ivs.len(), want.len());
            for (iv, w) in ivs.iter().zip(&want) {
                // The oracle value is within 2^-80 below its root, which is in the interval
                // (or is the point).
                prop_assert!(iv.lo - 1e-24 <= *w && *w <= iv.hi, "{:?} vs {}", iv, w);
            }
            prop_assert!(stats.exact_fallbacks <= 3, "at most one per query");
        }
    }

    /// Stam's bisection and the fast refinements return the same root (within tolerance).
    #[test]
    fn refinement_methods_agree(
        roots in prop::collection::vec(-5.0f64..5.0, 1..9),
        x_tol_exp in 4i32..14,
    ) {
        let p = Poly::<f64>::from_roots(&roots);
        let x_tol = 10f64.powi(-x_tol_exp);
        let mut answers = Vec::new();
        for refine in [RefineMethod::Bisection, RefineMethod::Illinois, RefineMethod::NewtonBisection] {
            let opts = RootOptions { refine, ..RootOptions::new(x_tol) };
            let mut stats = RootStats::default();
            answers.push(p.real_roots_with(-6.0, 6.0, &opts, &mut stats).unwrap());
        }
        for other in &answers[1..] {
            prop_assert_eq!(other.len(), answers[0].len());
            for (a, b) in answers[0].iter().zip(other) {
                prop_assert!((a - b).abs() <= 2.0 * x_tol + 4.0 * f64::EPSILON * a.abs(), "{} vs {}", a, b);
            }
        }
    }
}

#[test]
fn exact_refinement_reaches_width_two_to_the_minus_k() {
    let p = QPoly::new(vec![rat(-2, 1), rat(0, 1), rat(1, 1)]); // x² − 2
    let seq = p.sturm().unwrap();
    let iv = &p.isolate_roots(&rat(0, 1), &rat(2, 1)).unwrap()[0];
    for k in [1u32, 10, 64, 150] {
        let fine = seq.refine_interval(iv, k);
        let width = &fine.hi - &fine.lo;
        assert!(
            width <= Rat::new(1.into(), num_bigint::BigInt::from(1) << k as usize),
            "k = {k}"
        );
        // √2 is inside: lo² < 2 < hi².
        assert!(
            &fine.lo * &fine.lo < rat(2, 1) && &fine.hi * &fine.hi > rat(2, 1),
            "k = {k}"
        );
        assert!(
            !width.is_zero() && width.is_positive(),
            "irrational root: never a point"
        );
    }
}

/// Real queries recorded from the Bézier-patch tracer (separate file for its fixture parser).
mod teapot_eliminants;

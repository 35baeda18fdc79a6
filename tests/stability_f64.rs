//! The certified `f64` default (Bernstein isolation + Illinois refinement) against certified
//! exact roots of the stored polynomial (issue 6 §3), at the small sizes CI can afford; the full
//! sweep to degree 40 is `cargo run --release -p toolkit-benches --bin stability`
//! (docs/stability.md).

use poly::{Poly, RootStats};
use test_support::families::{Family, degree_cases};
use test_support::methods::Method;
use test_support::score::match_roots;
use test_support::truth::{abs_error, stored_truth};

/// The tolerance asked for (absolute).
const X_TOL: f64 = 1e-12;

/// Asserts that `method` finds every distinct root of `p` in `(lo, hi]`, no phantom, each
/// within the documented bound `max(x_tol, one f64 spacing at the root)`.
fn assert_all_roots(method: Method, p: &Poly<f64>, lo: f64, hi: f64, what: &str) {
    let truth = stored_truth(p, lo, hi);
    let mut stats = RootStats::default();
    let found = method.all_roots(p, lo, hi, X_TOL, &mut stats);
    let m = match_roots(&truth, &found);
    assert_eq!(
        (m.missed, m.phantom),
        (0, 0),
        "{what}: {} missed, {} phantom; truth {:?}, found {found:?}",
        m.missed,
        m.phantom,
        truth.approx
    );
    let mut sorted = found.clone();
    sorted.sort_by(f64::total_cmp);
    for (i, j) in m.pairs {
        let r = truth.approx[i];
        let allowed = X_TOL.max(r.abs() * f64::EPSILON);
        let e = abs_error(sorted[j], &truth.roots[i]);
        assert!(
            e <= allowed,
            "{what}: root {r}: got {}, error {e:e} > {allowed:e}",
            sorted[j]
        );
    }
}

#[test]
fn default_method_finds_planted_roots_up_to_degree_16() {
    let best = Method::Bernstein(poly::RefineMethod::Illinois);
    for d in 2..=16 {
        for (s, c) in degree_cases(Family::Planted, d, 2, 16).iter().enumerate() {
            assert_all_roots(
                best,
                &c.poly,
                c.lo,
                c.hi,
                &format!("planted d={d} sample {s}"),
            );
            // The tracer's query agrees with the first root.
            let truth = stored_truth(&c.poly, c.lo, c.hi);
            let first = c.poly.smallest_root(c.lo, c.hi, X_TOL).expect("has roots");
            let r = truth.smallest().expect("has roots");
            assert!(
                abs_error(first, r) <= X_TOL,
                "planted d={d}: smallest {first} vs {}",
                truth.approx[0]
            );
        }
    }
}

/// The claim of the README's "Accuracy and speed" section, at small size: the certified
/// default never misses a root nor reports a phantom on any test family (Wilkinson, scaled
/// Wilkinson, Chebyshev, Legendre, planted, Kac, clustered, multiple roots).
#[test]
fn default_method_is_exact_in_count_on_every_family_to_degree_10() {
    let best = Method::Bernstein(poly::RefineMethod::Illinois);
    for f in Family::BY_DEGREE {
        for d in 2..=10 {
            for c in degree_cases(f, d, 1, 10) {
                assert_all_roots(best, &c.poly, c.lo, c.hi, &format!("{} d={d}", f.name()));
            }
        }
    }
}

/// The baseline's breakdown quoted in docs/stability.md: Stam's 1988 floating-point Sturm
/// code loses the clustered pair of x⁵ − 2(10x − 1)² that the certified method finds.
#[test]
fn stam_1988_miscounts_a_clustered_quintic() {
    let c = &degree_cases(Family::Clustered, 5, 1, 0)[0];
    let truth = stored_truth(&c.poly, c.lo, c.hi);
    let mut stats = RootStats::default();
    let stam = Method::Stam.all_roots(&c.poly, c.lo, c.hi, X_TOL, &mut stats);
    let m = match_roots(&truth, &stam);
    assert!(
        m.missed > 0,
        "Stam finds {stam:?}, truth {:?}",
        truth.approx
    );
    assert_all_roots(
        Method::Bernstein(poly::RefineMethod::Illinois),
        &c.poly,
        c.lo,
        c.hi,
        "clustered d=5",
    );
}

//! Regression tests, one per bug, each named after what it caught (in the style of ripgrep's
//! `tests/regression.rs`). Issue 10 lists the wrong verdicts (checked against sympy and
//! python-flint), issue 13 the loops that did not end and the inputs that were not refused.

use std::time::{Duration, Instant};

use groebner::{
    Error, Method, SolveOptions, SolveWorkspace, Verdict, bezout_matrix_v, bezout_resultant_v,
    buchberger, is_groebner_basis, normal_form, poly_matrix_det, r2, reduce_basis, reduction_step,
    s_polynomial, solve, solve_ray_patch, stam_basis, sylvester_matrix_v, sylvester_resultant_v,
};
use poly::{BiPoly, Poly, QBiPoly, Rat};

const METHODS: [Method; 4] = [
    Method::Stam,
    Method::Buchberger,
    Method::Resultant,
    Method::BezoutResultant,
];

fn q(n: i64) -> Rat {
    Rat::from_integer(n.into())
}

/// `Σ c·u^i·v^j` from `(c, i, j)` integer triples.
fn qb(terms: &[(i64, usize, usize)]) -> QBiPoly {
    BiPoly::from_terms(terms.iter().map(|&(c, i, j)| (q(c), i, j)))
}

fn boxed(method: Method, lo: f64, hi: f64) -> SolveOptions {
    SolveOptions {
        method,
        u_range: [lo, hi],
        v_range: [lo, hi],
        ..SolveOptions::default()
    }
}

/// Every method, exact and `f64`, gives `verdict` on `f1`, `f2` in the box `[lo, hi]²`.
fn assert_verdict(f1: &QBiPoly, f2: &QBiPoly, lo: f64, hi: f64, verdict: Verdict, what: &str) {
    for m in METHODS {
        let opts = boxed(m, lo, hi);
        let exact = solve(f1, f2, &opts).unwrap();
        assert_eq!(exact.verdict, verdict, "{what}: exact {m:?}: {exact:?}");
        let float = solve(&f1.to_f64(), &f2.to_f64(), &opts).unwrap();
        assert_eq!(float.verdict, verdict, "{what}: f64 {m:?}: {float:?}");
    }
}

/// Issue 10, item 1. Caught: `uv − u, u²` share the line `u = 0`, which crosses the box; the
/// resultant methods (exact and `f64`) and `f64` Stam/Buchberger said `Finite` (no roots).
#[test]
fn common_factor_in_u_alone_is_infinite() {
    let f1 = qb(&[(1, 1, 1), (-1, 1, 0)]);
    let f2 = qb(&[(1, 2, 0)]);
    assert_verdict(&f1, &f2, 0.0, 1.0, Verdict::Infinite, "uv − u, u²");
}

/// Issue 10, item 1, second case. Caught: the factor `u + 1` of both equations (the line
/// `u = −1` crosses `[−2, 2]²`) was reported as `Finite`.
#[test]
fn common_factor_u_plus_one_is_infinite() {
    let f1 = qb(&[
        (-5, 2, 1),
        (-5, 2, 0),
        (-1, 1, 2),
        (-2, 1, 1),
        (-7, 1, 0),
        (-1, 0, 2),
        (3, 0, 1),
        (-2, 0, 0),
    ]);
    let f2 = qb(&[
        (-4, 3, 0),
        (-5, 2, 1),
        (-4, 2, 0),
        (-5, 1, 2),
        (-7, 1, 1),
        (-5, 0, 2),
        (-2, 0, 1),
    ]);
    assert_verdict(&f1, &f2, -2.0, 2.0, Verdict::Infinite, "factor u + 1");
}

/// Issue 10, item 2. Caught: `f64` Stam and Buchberger said `Finite` when an input is zero
/// (`0, u² − 1`: the lines `u = ±1`) or both are free of `v` (`4u − 4, −12u² + 32u − 20`:
/// the common factor `u − 1`).
#[test]
fn zero_or_v_free_inputs_are_infinite_for_every_method() {
    assert_verdict(
        &BiPoly::zero(),
        &qb(&[(1, 2, 0), (-1, 0, 0)]),
        -2.0,
        2.0,
        Verdict::Infinite,
        "0, u² − 1",
    );
    assert_verdict(
        &qb(&[(4, 1, 0), (-4, 0, 0)]),
        &qb(&[(-12, 2, 0), (32, 1, 0), (-20, 0, 0)]),
        -2.0,
        2.0,
        Verdict::Infinite,
        "4u − 4, −12u² + 32u − 20",
    );
}

/// Issue 10, item 2, the ray case. Caught: a ray along a ruling of `S(u, v) = (u, v, u²)`
/// gives `u − 1/2, u² − 1/4`, and `solve_ray_patch` by Stam said `Finite` with no roots.
#[test]
fn ray_along_a_ruling_is_infinite() {
    // Power basis, stride 3 (u⁰, u¹, u²), rows 2 (v⁰, v¹): x = u, y = v, z = u².
    let z = [0.0; 3];
    let points = [z, [1.0, 0.0, 0.0], [0.0, 0.0, 1.0], [0.0, 1.0, 0.0], z, z];
    let (origin, dir) = ([0.5, -1.0, 0.25], [0.0, 1.0, 0.0]);
    let mut ws = SolveWorkspace::new();
    for method in [Method::Stam, Method::BezoutResultant, Method::Buchberger] {
        let opts = SolveOptions {
            method,
            ..SolveOptions::default()
        };
        let sol = solve_ray_patch(&mut ws, &points, 3, 2, &origin, &dir, &opts).unwrap();
        assert_eq!(sol.verdict, Verdict::Infinite, "{method:?}: {sol:?}");
        assert!(
            sol.roots.is_empty(),
            "{method:?}: a curve is not a list of points"
        );
    }
}

/// Issue 10, item 3. Caught: the public `f64` `buchberger()` returned `{1}` for an ideal with
/// two real common roots in `[−2, 2]²` (exact eliminant of degree 6), with no warning. The
/// basis now carries its certificate: the unit is not a proof on that box.
#[test]
fn f64_unit_basis_is_not_a_proof_of_no_root() {
    let f1 = BiPoly::from_terms([
        (q(2), 2, 0),
        (q(-9), 1, 1),
        (q(1), 1, 0),
        (q(-2), 0, 2),
        (q(-15) / q(2), 0, 1),
    ]);
    let f2 = qb(&[
        (-1, 2, 1),
        (1, 1, 2),
        (-4, 1, 1),
        (-2, 1, 0),
        (-1, 0, 3),
        (2, 0, 2),
        (4, 0, 1),
        (-1, 0, 0),
    ]);
    let exact = buchberger(&[f1.clone(), f2.clone()]).unwrap();
    assert!(!exact.contains_unit(), "exact: not the unit ideal");
    let roots = solve(&f1, &f2, &boxed(Method::Buchberger, -2.0, 2.0)).unwrap();
    assert_eq!(roots.roots.len(), 2, "two real common roots: {roots:?}");
    let float = buchberger(&[f1.to_f64(), f2.to_f64()]).unwrap();
    assert!(
        !float.proves_no_root_in([-2.0, 2.0], [-2.0, 2.0]),
        "the f64 basis {float:?} must not prove that there is no root"
    );
    assert!(exact.proves_no_root_in([-2.0, 2.0], [-2.0, 2.0]) == exact.contains_unit());
}

/// Issue 10, item 4. Caught: exact `buchberger()` gave `LimitExceeded` on a generic degree-6
/// pair whose reduced basis has 2–3 elements (the cap counted every remainder ever added).
/// The exact run takes over a minute in a test build (coefficients of many hundred bits), so
/// it is opt-in; `buchberger.rs`' unit test checks the cap on the article's pair.
#[test]
#[ignore = "exact degree-6 Buchberger: over a minute; run with --ignored"]
fn exact_buchberger_on_a_degree_six_pair_finishes() {
    let f1 = qb(&[
        (-5, 5, 1),
        (-2, 2, 1),
        (4, 1, 0),
        (-3, 0, 5),
        (-4, 0, 4),
        (1, 0, 3),
    ]);
    let f2 = qb(&[
        (-3, 6, 0),
        (4, 5, 1),
        (3, 4, 2),
        (2, 2, 0),
        (-1, 0, 6),
        (-1, 0, 3),
    ]);
    let g = buchberger(&[f1, f2]).unwrap();
    assert!((2..=3).contains(&g.len()), "reduced basis size {}", g.len());
    assert!(is_groebner_basis(g.elements()).unwrap(), "a Gröbner basis");
}

/// Issue 10, item 5. Caught: `−u² + 3uv + v, 2u² − 6uv − 2v − 2` (`F2 = −2·F1 − 2`) have no
/// common root at all, but the resultant methods said `Finite` with 0 roots: their resultant
/// `−2(3u + 1)` vanishes only where both leading coefficients in `v` do ("at `v = ∞`").
#[test]
fn no_common_root_behind_a_nonconstant_resultant() {
    let f1 = qb(&[(-1, 2, 0), (3, 1, 1), (1, 0, 1)]);
    let f2 = qb(&[(2, 2, 0), (-6, 1, 1), (-2, 0, 1), (-2, 0, 0)]);
    for (lo, hi) in [(0.0, 1.0), (-2.0, 2.0)] {
        assert_verdict(&f1, &f2, lo, hi, Verdict::NoCommonRoot, "F2 = −2·F1 − 2");
    }
}

/// Issue 10, item 5, in `f64`. Caught: the `f64` `solve` still said `Finite` with 0 roots for
/// the system above (the exact decision was skipped there because it cost milliseconds per
/// system); it now decides after a quick modular proof that ordinary systems have a root. The
/// same leading coefficients with a different constant term (`F2 = −2·F1 − 2 + 4v`) do have
/// a common root (outside the box) and must stay `Finite` with no roots.
#[test]
fn f64_solve_says_no_common_root_at_infinity_only() {
    let f1 = qb(&[(-1, 2, 0), (3, 1, 1), (1, 0, 1)]).to_f64();
    let f2 = qb(&[(2, 2, 0), (-6, 1, 1), (-2, 0, 1), (-2, 0, 0)]).to_f64();
    let f2_root = qb(&[(2, 2, 0), (-6, 1, 1), (2, 0, 1), (-2, 0, 0)]).to_f64();
    for m in METHODS {
        let opts = boxed(m, 0.0, 1.0);
        let none = solve(&f1, &f2, &opts).unwrap();
        assert_eq!(none.verdict, Verdict::NoCommonRoot, "f64 {m:?}: {none:?}");
        let outside = solve(&f1, &f2_root, &opts).unwrap();
        assert_eq!(
            (outside.verdict, outside.roots.len()),
            (Verdict::Finite, 0),
            "f64 {m:?}: a common root outside the box: {outside:?}"
        );
    }
}

/// A system of degree 3 in `u` and `v` with coefficients spread over `1e±300` (finite).
fn wide_range_pair() -> (BiPoly<f64>, BiPoly<f64>) {
    // The case of issue 13 that sent `r2_tracked` into an endless loop: an overflow to
    // infinity, then NaN, and a NaN leading term is never cancelled.
    let a = [
        4.367076254124915e-262,
        -3.3320635129756793e-102,
        -4.95145713074639e151,
        1.7884290915863137e-204,
        4.854018596767668e283,
        6.0683315847556205e-227,
        -8.253777932057458e-139,
        -2.970428437931773e-71,
        -9.492839384692995e264,
        4.433793879854408e-100,
        4.82484427554586e99,
        4.062041600497779e-288,
        -1.402011209850257e-252,
        -3.7953055964410433e-29,
        -1.2569394831215637e-173,
        -2.9827264750652464e-82,
    ];
    let b = [
        6.801043071154548e-37,
        4.118352249473182e231,
        -8.405442793875992e-68,
        2.4626006871269797e-291,
        -2.1954122888767268e-267,
        -9.34588756472017e-115,
        9.401125065672242e153,
        5.3064108612842444e-95,
        8.311471109730437e-280,
        5.148434498187109e238,
        1.7782743589350988e-69,
        3.2414606224495644e-176,
        5.397604821110284e186,
        3.891448950306568e222,
        -4.4992766505436135e281,
        4.965275845564723e238,
    ];
    (
        BiPoly::from_grid(4, 4, a.to_vec()),
        BiPoly::from_grid(4, 4, b.to_vec()),
    )
}

/// How long any of these may take: the other methods answer in well under a millisecond, a
/// hung loop never does.
const FAST: Duration = Duration::from_secs(2);

fn timed<R>(what: &str, f: impl FnOnce() -> R) -> R {
    let t = Instant::now();
    let r = f();
    assert!(t.elapsed() < FAST, "{what} took {:?}", t.elapsed());
    r
}

/// Issue 13 (the libraries): `r2`, `stam_basis`, `solve(Method::Stam)` and `solve_ray_patch`
/// looped forever in `r2_tracked` on finite coefficients of wide range. Caught: every one of
/// them must now end quickly, with a typed error or an answer.
#[test]
fn wide_range_coefficients_end_quickly_everywhere() {
    let (a, b) = wide_range_pair();
    let r = timed("r2", || r2(&a, &b));
    assert!(
        matches!(
            r,
            Err(Error::Overflow { .. } | Error::LimitExceeded { .. }) | Ok(_)
        ),
        "{r:?}"
    );
    timed("stam_basis", || {
        let _ = stam_basis(&a, &b);
    });
    timed("buchberger", || {
        let _ = buchberger(&[a.clone(), b.clone()]);
    });
    for m in METHODS {
        let sol = timed("solve", || solve(&a, &b, &boxed(m, 0.0, 1.0)));
        assert!(sol.is_ok(), "{m:?}: finite input is solved: {sol:?}");
    }
    // The same coefficients as a ray/patch system: F1 = D_y·S_x − D_x·S_y with D = (1, 1, 0)
    // … simply a patch whose x-coordinates are a, y-coordinates b, and z zero.
    let points: Vec<[f64; 3]> = a
        .coeffs()
        .iter()
        .zip(b.coeffs())
        .map(|(&x, &y)| [x, y, 0.0])
        .collect();
    let mut ws = SolveWorkspace::new();
    for m in [Method::Stam, Method::BezoutResultant] {
        let opts = SolveOptions {
            method: m,
            ..SolveOptions::default()
        };
        let r = timed("solve_ray_patch", || {
            solve_ray_patch(&mut ws, &points, 4, 4, &[0.0; 3], &[0.0, 0.0, 1.0], &opts)
                .map(|s| s.roots.len())
        });
        assert!(r.is_ok(), "{m:?}: {r:?}");
    }
}

/// Issue 13, item 16. Caught: NaN and infinite coefficients ran for more than 10 s in `r2`,
/// `stam_basis` and the solve; they are refused up front with a typed error.
#[test]
fn nan_and_infinite_coefficients_are_refused() {
    for bad in [f64::NAN, f64::INFINITY, f64::NEG_INFINITY] {
        let p = BiPoly::from_terms([(1.0, 1, 1), (bad, 2, 0), (1.0, 0, 0)]);
        let ok = BiPoly::from_terms([(1.0, 0, 1), (-1.0, 1, 0)]);
        assert!(
            matches!(timed("r2", || r2(&p, &ok)), Err(Error::NonFinite { .. })),
            "r2 {bad}"
        );
        assert!(
            matches!(
                timed("stam", || stam_basis(&ok, &p)),
                Err(Error::NonFinite { .. })
            ),
            "stam_basis {bad}"
        );
        assert!(
            matches!(
                timed("buchberger", || buchberger(&[ok.clone(), p.clone()])),
                Err(Error::NonFinite { .. })
            ),
            "buchberger {bad}"
        );
        for m in METHODS {
            assert_eq!(
                solve(&p, &ok, &boxed(m, 0.0, 1.0)),
                Err(Error::NonFinite { what: "F1" }),
                "solve {m:?} {bad}"
            );
        }
    }
}

/// Issue 10 (closing note). Caught: `normal_form` and `s_polynomial` took NaN and infinite
/// coefficients and returned NaN polynomials (the other public entries refused them). Every
/// public algebra entry now refuses them with `Error::NonFinite`.
#[test]
fn algebra_entries_refuse_non_finite_coefficients() {
    let ok = BiPoly::from_terms([(1.0, 0, 1), (-1.0, 1, 0)]);
    let circle = BiPoly::from_terms([(1.0, 2, 0), (1.0, 0, 2), (-0.5, 0, 0)]);
    let refused = |r: Result<(), Error>, what: &str| {
        assert!(matches!(r, Err(Error::NonFinite { .. })), "{what}: {r:?}");
    };
    for bad in [f64::NAN, f64::INFINITY, f64::NEG_INFINITY] {
        let p = BiPoly::from_terms([(1.0, 1, 1), (bad, 2, 0), (1.0, 0, 0)]);
        let pair = [ok.clone(), p.clone()];
        refused(
            normal_form(&p, std::slice::from_ref(&ok)).map(drop),
            "normal_form p",
        );
        refused(normal_form(&circle, &pair).map(drop), "normal_form basis");
        refused(s_polynomial(&p, &ok).map(drop), "s_polynomial f");
        refused(s_polynomial(&ok, &p).map(drop), "s_polynomial g");
        refused(
            reduction_step(&p, std::slice::from_ref(&ok)).map(drop),
            "reduction_step p",
        );
        refused(
            reduction_step(&circle, &pair).map(drop),
            "reduction_step basis",
        );
        refused(reduce_basis(&pair).map(drop), "reduce_basis");
        refused(is_groebner_basis(&pair).map(drop), "is_groebner_basis");
        refused(sylvester_matrix_v(&ok, &p).map(drop), "sylvester_matrix_v");
        refused(bezout_matrix_v(&p, &ok).map(drop), "bezout_matrix_v");
        refused(
            sylvester_resultant_v(&p, &ok).map(drop),
            "sylvester_resultant_v",
        );
        refused(bezout_resultant_v(&ok, &p).map(drop), "bezout_resultant_v");
        let m = vec![vec![Poly::new(vec![bad])]];
        refused(poly_matrix_det(&m).map(drop), "poly_matrix_det");
    }
    // The same calls on finite input succeed: the refusal is about the NaN, not the call.
    assert!(
        normal_form(&circle, std::slice::from_ref(&ok)).is_ok(),
        "finite normal form"
    );
    assert!(s_polynomial(&circle, &ok).is_ok(), "finite S-polynomial");
}

/// Issue 13, item 16. Caught: NaN ranges and tolerances must be refused before any work.
#[test]
fn nan_ranges_and_tolerances_are_refused() {
    let p = BiPoly::from_terms([(1.0, 2, 0), (1.0, 0, 2), (-0.5, 0, 0)]);
    let l = BiPoly::from_terms([(1.0, 0, 1), (-1.0, 1, 0)]);
    for m in METHODS {
        let bad_range = SolveOptions {
            v_range: [f64::NAN, 1.0],
            ..boxed(m, 0.0, 1.0)
        };
        assert!(
            matches!(
                solve(&p, &l, &bad_range),
                Err(Error::InvalidRange { which: "v", .. })
            ),
            "{m:?}"
        );
        let bad_tol = SolveOptions {
            f_tol_rel: f64::INFINITY,
            ..boxed(m, 0.0, 1.0)
        };
        assert!(
            matches!(
                solve(&p, &l, &bad_tol),
                Err(Error::InvalidTolerance {
                    name: "f_tol_rel",
                    ..
                })
            ),
            "{m:?}"
        );
    }
}

/// Issue 13, item 16. Caught: extreme but uniform magnitudes (a system scaled by 1e300 or
/// 1e-300) must finish, and with the roots of the unscaled system: `u² + v² = 1/2` and
/// `v = u` meet at `(1/2, 1/2)`.
#[test]
fn extreme_magnitudes_finish_with_the_right_roots() {
    for s in [1e300, 1e-300] {
        let circle = BiPoly::from_terms([(s, 2, 0), (s, 0, 2), (-0.5 * s, 0, 0)]);
        let line = BiPoly::from_terms([(s, 0, 1), (-s, 1, 0)]);
        for m in METHODS {
            let sol = timed("solve", || solve(&circle, &line, &boxed(m, 0.0, 1.0))).unwrap();
            assert_eq!(sol.verdict, Verdict::Finite, "{m:?} at scale {s}");
            assert_eq!(sol.roots.len(), 1, "{m:?} at scale {s}: {sol:?}");
            let r = sol.roots[0];
            assert!(
                (r.u - 0.5).abs() < 1e-12 && (r.v - 0.5).abs() < 1e-12,
                "{m:?} at scale {s}: {r:?}"
            );
        }
    }
}

//! A fuzzer over polynomial coefficients on stable Rust (issue 13, "In the tree").
//!
//! Each case draws a coefficient vector — ordinary values, magnitudes across `1e±300`,
//! subnormals, zero high coefficients kept by [`Poly::new_raw`], all zeros, NaN and ±∞ — a
//! range (finite, unbounded, reversed, subnormal, NaN ends) and a tolerance (0, −0, 1e-12,
//! NaN, ∞), and asks every public `f64` query under every [`IsolationMethod`]:
//! `try_smallest_root`, `real_roots_with`, `real_roots_into`, `isolate_roots_with`, the
//! borrowed [`PolyRef`] query (`smallest`, `all`, `isolate`), `root_bound`, `cauchy_bound`
//! and `to_rat`. Every case must end as one of:
//!
//! - **answered**: every query returned `Ok`; where the coefficients are finite, not all
//!   zero, of degree at most [`ORACLE_DEGREE`], the range has finite ends and the tolerance
//!   is 0 or 1e-12, every method's roots equal the exact [`QPoly`] oracle's (within the
//!   tolerance or two ulps) — counted as **checked against the oracle**;
//! - **typed error**: some query returned a [`RootError`];
//!
//! and fails on a panic, on a certified answer that differs from the oracle (or a certified
//! refusal), on a heuristic answer that differs from it (issue 11: the heuristics may refuse
//! with [`RootError::Unresolved`], never answer wrong; their `all` roots, smallest root and
//! isolating intervals are each checked), or on a case slower than [`CASE_BUDGET`] (a hang).
//!
//! Smoke run (part of `cargo test`): [`SMOKE_CASES`] cases of degree at most
//! [`SMOKE_MAX_DEGREE`], deterministic. Longer run, degrees up to 40:
//! `FUZZ_CASES=100000 FUZZ_SEED=7 FUZZ_MAX_DEGREE=40 cargo test --release -p poly --test
//! fuzz_coeffs -- --nocapture`. With `FUZZ_TRACE=1` each case is printed before it runs, so
//! a hang shows its input.

use std::panic::{AssertUnwindSafe, catch_unwind};
use std::time::{Duration, Instant};

use poly::{IsolationMethod, Poly, PolyRef, RootInterval, RootOptions, RootStats, rat_from_f64};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;

/// Cases of the smoke run (a few seconds in a debug build on a loaded machine).
const SMOKE_CASES: usize = 300;

/// The highest degree the smoke run draws (see [`fuzz_coefficients_smoke`]).
const SMOKE_MAX_DEGREE: usize = ORACLE_DEGREE;

/// The largest degree compared with the exact oracle (`QPoly::real_roots`, exact Sturm —
/// independent of the `Exact` method's Descartes isolation): the rational Sturm sequence of
/// a degree-19 polynomial with coefficients from 1e-180 to 1e154 took over a minute (issue
/// 13, item 17), and the oracle has no budget of its own.
const ORACLE_DEGREE: usize = 8;

/// The most time one case (every query under every method) may take: item 17 asks for an
/// answer within a second per query; this allows the debug build and a loaded machine.
const CASE_BUDGET: Duration = Duration::from_secs(10);

const METHODS: [IsolationMethod; 4] = [
    IsolationMethod::Bernstein,
    IsolationMethod::Exact,
    IsolationMethod::Sturm,
    IsolationMethod::StamSturm,
];

/// The classes of outcome.
#[derive(Debug, Default)]
struct Tally {
    answered: usize,
    checked_against_oracle: usize,
    typed_error: usize,
    slowest: Duration,
    /// The stored degree and the range of the slowest case.
    slowest_case: Option<(usize, f64, f64)>,
}

/// One coefficient of a class chosen at random.
fn coefficient(rng: &mut ChaCha8Rng) -> f64 {
    let sign = if rng.gen_bool(0.5) { 1.0 } else { -1.0 };
    match rng.gen_range(0..20) {
        0..=7 => rng.gen_range(-10.0..10.0),
        8..=10 => sign * 10f64.powf(rng.gen_range(-300.0..300.0)),
        11 => sign * f64::from_bits(rng.gen_range(1..1u64 << 52)),
        12..=14 => 0.0,
        15 => f64::from(rng.gen_range(-5i8..=5)),
        16 => sign * f64::MAX,
        17 => sign * f64::MIN_POSITIVE,
        18 => f64::NAN,
        _ => sign * f64::INFINITY,
    }
}

/// Coefficients of a degree up to [`ORACLE_DEGREE`], or (one case in ten, when
/// `max_degree` allows) up to `max_degree`.
fn coefficients(rng: &mut ChaCha8Rng, max_degree: usize) -> Vec<f64> {
    let degree = if rng.gen_bool(0.9) || max_degree <= ORACLE_DEGREE {
        rng.gen_range(0..=ORACLE_DEGREE)
    } else {
        rng.gen_range(0..=max_degree)
    };
    let mut c: Vec<f64> = (0..=degree).map(|_| coefficient(rng)).collect();
    // Rarely non-finite: most cases should reach the root finders.
    if rng.gen_bool(0.8) {
        for x in &mut c {
            if !x.is_finite() {
                *x = rng.gen_range(-1.0..1.0);
            }
        }
    }
    match rng.gen_range(0..8) {
        0 => c.extend(std::iter::repeat_n(0.0, rng.gen_range(1..5))),
        1 => c.iter_mut().for_each(|x| *x = 0.0),
        _ => {}
    }
    c
}

fn range(rng: &mut ChaCha8Rng) -> (f64, f64) {
    match rng.gen_range(0..10) {
        0..=3 => (-10.0, 10.0),
        4 => (0.0, f64::INFINITY),
        5 => (f64::NEG_INFINITY, f64::INFINITY),
        6 => (-1e300, 1e300),
        7 => (5e-324, 1e-300),
        8 => (1.0, -1.0),
        _ => (f64::NAN, 1.0),
    }
}

fn tolerance(rng: &mut ChaCha8Rng) -> f64 {
    [0.0, -0.0, 1e-12, 1e-12, 0.0, f64::NAN, f64::INFINITY][rng.gen_range(0..7)]
}

/// Runs every query on one case; `Err` describes a failure.
fn run_case(coeffs: &[f64], lo: f64, hi: f64, x_tol: f64, tally: &mut Tally) -> Result<(), String> {
    let mut errors = 0;
    let mut count = |ok: bool| errors += usize::from(!ok);
    let stored = Poly::new_raw(coeffs.to_vec());
    let trimmed = Poly::new(coeffs.to_vec());
    count(stored.root_bound().is_some());
    let _ = stored.cauchy_bound();
    let exact = stored.to_rat();
    let comparable = exact.is_some()
        && !trimmed.is_zero()
        && trimmed.degree() <= ORACLE_DEGREE
        && lo.is_finite()
        && hi.is_finite()
        && lo < hi
        && (x_tol == 0.0 || x_tol == 1e-12);
    let oracle = if comparable {
        let q = exact.expect("finite");
        let (a, b) = (rat_from_f64(lo).unwrap(), rat_from_f64(hi).unwrap());
        Some(
            q.real_roots(&a, &b, 0.0)
                .map_err(|e| format!("oracle: {e}"))?,
        )
    } else {
        None
    };
    for method in METHODS {
        let opts = RootOptions {
            isolation: method,
            ..RootOptions::new(x_tol)
        };
        for p in [&stored, &trimmed] {
            let mut stats = RootStats::default();
            let first = p.try_smallest_root(lo, hi, &opts, &mut stats);
            let all = p.real_roots_with(lo, hi, &opts, &mut stats);
            let mut into = vec![f64::NAN];
            let into_ok = p.real_roots_into(lo, hi, &opts, &mut stats, &mut into);
            let isolated = p.isolate_roots_with(lo, hi, &opts, &mut stats);
            let q = PolyRef::new(p.coeffs());
            let borrowed = q.roots(lo, hi, &opts).stats(&mut stats).all();
            let _ = q.roots(lo, hi, &opts).smallest();
            let _ = q.roots(lo, hi, &opts).isolate();
            count(first.is_ok() && all.is_ok() && into_ok.is_ok() && isolated.is_ok());
            if let (Ok(all), Ok(borrowed)) = (&all, &borrowed) {
                if all != borrowed {
                    return Err(format!("{method:?}: Poly {all:?} but PolyRef {borrowed:?}"));
                }
                if into_ok.is_ok() && into[1..] != all[..] {
                    return Err(format!("{method:?}: real_roots_into {into:?} vs {all:?}"));
                }
                // The two queries refine separately: each within the tolerance of the root.
                if let Ok(Some(f)) = first
                    && !all
                        .first()
                        .is_some_and(|a| (a - f).abs() <= 2.0 * x_tol.max(ulps(*a)))
                {
                    return Err(format!("{method:?}: smallest {f:e} vs all {all:?}"));
                }
            }
            let certified = matches!(method, IsolationMethod::Bernstein | IsolationMethod::Exact);
            if let Some(want) = &oracle {
                if certified {
                    let got = all.map_err(|e| format!("{method:?}: refused a finite case: {e}"))?;
                    matches_oracle(&got, want, x_tol).map_err(|e| format!("{method:?}: {e}"))?;
                } else {
                    // Issue 11: a heuristic may refuse (a typed error), never answer wrong.
                    if let Ok(got) = &all {
                        matches_oracle(got, want, x_tol)
                            .map_err(|e| format!("{method:?} all: {e}"))?;
                    }
                    if let Ok(ivs) = &isolated {
                        brackets_match_oracle(ivs, want)
                            .map_err(|e| format!("{method:?} isolate: {e}"))?;
                    }
                    if let Ok(first) = first {
                        matches_oracle(first.as_slice(), &want[..want.len().min(1)], x_tol)
                            .map_err(|e| format!("{method:?} smallest: {e}"))?;
                    }
                }
            }
        }
    }
    if oracle.is_some() {
        tally.checked_against_oracle += 1;
    }
    if errors == 0 {
        tally.answered += 1;
    } else {
        tally.typed_error += 1;
    }
    Ok(())
}

/// Two ulps of `x`, at least the smallest subnormal.
fn ulps(x: f64) -> f64 {
    (2.0 * x.abs() * f64::EPSILON).max(f64::from_bits(2))
}

/// `got` equals the oracle's `want` root for root, within `x_tol` or two ulps.
fn matches_oracle(got: &[f64], want: &[f64], x_tol: f64) -> Result<(), String> {
    if got.len() != want.len() {
        return Err(format!("got {got:?}, exact {want:?}"));
    }
    for (g, w) in got.iter().zip(want) {
        let allowed = x_tol.max(ulps(*w));
        if (g - w).abs() > allowed {
            return Err(format!("got {g:e}, exact {w:e} (allowed {allowed:e})"));
        }
    }
    Ok(())
}

/// Each of `ivs` holds exactly one of the oracle's roots `want` (in the closed interval:
/// a heuristic's `(lo, hi]` by its counts, a certified one's open or point interval), and
/// every root is held by one.
fn brackets_match_oracle(ivs: &[RootInterval<f64>], want: &[f64]) -> Result<(), String> {
    if ivs.len() != want.len() {
        return Err(format!("{} intervals {ivs:?}, exact {want:?}", ivs.len()));
    }
    for (iv, w) in ivs.iter().zip(want) {
        if !(iv.lo <= *w && *w <= iv.hi) {
            return Err(format!("interval {iv:?} misses the root {w:e}"));
        }
    }
    Ok(())
}

/// Runs one case under [`catch_unwind`] and the clock: `None` when it passed within
/// [`CASE_BUDGET`], else what went wrong.
fn timed_case(coeffs: &[f64], lo: f64, hi: f64, x_tol: f64, tally: &mut Tally) -> Option<String> {
    let start = Instant::now();
    let result = catch_unwind(AssertUnwindSafe(|| run_case(coeffs, lo, hi, x_tol, tally)));
    let elapsed = start.elapsed();
    if elapsed > tally.slowest {
        tally.slowest = elapsed;
        tally.slowest_case = Some((coeffs.len().saturating_sub(1), lo, hi));
    }
    match result {
        Ok(Ok(())) if elapsed <= CASE_BUDGET => None,
        Ok(Ok(())) => Some(format!("took {elapsed:?}")),
        Ok(Err(why)) => Some(why),
        Err(_) => Some("panicked".to_string()),
    }
}

/// Fails with every failure listed.
fn assert_no_failures(failures: &[String]) {
    assert!(
        failures.is_empty(),
        "{} failures:\n{}",
        failures.len(),
        failures.join("\n")
    );
}

/// Runs `cases` fuzz cases from `seed` with degrees up to `max_degree`; panics with every
/// failing input.
fn fuzz(seed: u64, cases: usize, max_degree: usize) -> Tally {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let mut tally = Tally::default();
    let mut failures = Vec::new();
    let trace = std::env::var_os("FUZZ_TRACE").is_some();
    for case in 0..cases {
        let coeffs = coefficients(&mut rng, max_degree);
        let (lo, hi) = range(&mut rng);
        let x_tol = tolerance(&mut rng);
        if trace {
            eprintln!(
                "fuzz_coeffs seed {seed}: case {case}: {coeffs:?} on ({lo:e}, {hi:e}] x_tol {x_tol:e}"
            );
        }
        let Some(failure) = timed_case(&coeffs, lo, hi, x_tol, &mut tally) else {
            continue;
        };
        let failure = format!(
            "case {case}: coefficients {coeffs:?} on ({lo:e}, {hi:e}] x_tol {x_tol:e}: {failure}"
        );
        // At once, so that a long campaign shows its failures while it runs.
        eprintln!("fuzz_coeffs seed {seed}: {failure}");
        failures.push(failure);
    }
    eprintln!("fuzz_coeffs seed {seed}: {cases} cases, {tally:?}");
    assert_no_failures(&failures);
    tally
}

/// The bounded smoke run; `FUZZ_CASES`, `FUZZ_SEED` and `FUZZ_MAX_DEGREE` make it longer or
/// different.
///
/// The smoke run draws degrees up to [`ORACLE_DEGREE`] only ([`SMOKE_MAX_DEGREE`]): a
/// high-degree draw with coefficients up to `f64::MAX` takes up to a second per case in a
/// release build (the certified path's adaptive tiers; the `Exact` method's Sturm sequences
/// took seconds until it moved to Descartes' rule), far more in a debug one. The bugs the fuzzer found (issue 13 follow-up) have their named regression
/// tests in `tests/regression.rs`. Long campaign: `FUZZ_CASES=100000 FUZZ_SEED=7
/// FUZZ_MAX_DEGREE=40 cargo test --release -p poly --test fuzz_coeffs -- --nocapture`.
#[test]
fn fuzz_coefficients_smoke() {
    let tally = fuzz(
        env_or("FUZZ_SEED", 13),
        env_or("FUZZ_CASES", SMOKE_CASES),
        env_or("FUZZ_MAX_DEGREE", SMOKE_MAX_DEGREE),
    );
    assert!(tally.answered > 0, "ordinary cases are answered: {tally:?}");
    assert!(tally.typed_error > 0, "bad cases are refused: {tally:?}");
    assert!(
        tally.checked_against_oracle > 0,
        "and some are checked: {tally:?}"
    );
}

/// Coefficients of `s·Π(x − rᵢ)` (rounded in `f64`) for one to four roots `rᵢ` near `1e-156`
/// (`±[1, 10)·10^e`, `e ∈ [−159, −153]`), sometimes a repeated one or one ordinary root in
/// `(−5, 5)`, and a scale `s = 10^k`, `k ∈ [−5, 5]`: the products of the tiny roots are
/// subnormal or zero, which is where bug 2 of the issue 13 follow-up (a root near 2e-156 off
/// by 3e-13 relative at `x_tol = 0`) was seen once.
fn tiny_root_coefficients(rng: &mut ChaCha8Rng) -> Vec<f64> {
    let mut c = vec![10f64.powi(rng.gen_range(-5..=5))];
    let times_root = |c: &mut Vec<f64>, r: f64| {
        c.push(0.0);
        for i in (0..c.len()).rev() {
            let below = if i > 0 { c[i - 1] } else { 0.0 };
            c[i] = below - r * c[i];
        }
    };
    let mut last = 0.0;
    for _ in 0..rng.gen_range(1..=4) {
        let r = if last != 0.0 && rng.gen_bool(0.2) {
            last
        } else {
            let sign = if rng.gen_bool(0.5) { 1.0 } else { -1.0 };
            sign * rng.gen_range(1.0..10.0) * 10f64.powi(rng.gen_range(-159..=-153))
        };
        times_root(&mut c, r);
        last = r;
    }
    if rng.gen_bool(0.3) {
        times_root(&mut c, rng.gen_range(-5.0..5.0));
    }
    c
}

/// Cases of the tiny-root smoke run (about 0.1 s each in a release build: the exact oracle
/// bisects to the correctly rounded root through subnormal denominators).
const TINY_SMOKE_CASES: usize = 12;

/// Bug 2's targeted generator ([`tiny_root_coefficients`]) on ranges around the tiny roots,
/// `x_tol = 0`, every method and query, the certified ones against the exact oracle. Smoke
/// run here; long run: `FUZZ_TINY_CASES=200000 cargo test --release -p poly --test
/// fuzz_coeffs tiny -- --nocapture`.
#[test]
fn fuzz_tiny_roots_against_the_oracle() {
    let cases = env_or("FUZZ_TINY_CASES", TINY_SMOKE_CASES);
    let mut rng = ChaCha8Rng::seed_from_u64(env_or("FUZZ_SEED", 156));
    let mut tally = Tally::default();
    let mut failures = Vec::new();
    let ranges = [
        (-1e-150, 1e-150),
        (0.0, 1e-150),
        (-1e-150, 0.0),
        (1e-160, 1e-150),
        (-10.0, 10.0),
        (-1e300, 1e300),
    ];
    for case in 0..cases {
        let coeffs = tiny_root_coefficients(&mut rng);
        let (lo, hi) = ranges[rng.gen_range(0..ranges.len())];
        let Some(failure) = timed_case(&coeffs, lo, hi, 0.0, &mut tally) else {
            continue;
        };
        let failure =
            format!("case {case}: coefficients {coeffs:?} on ({lo:e}, {hi:e}]: {failure}");
        eprintln!("fuzz_tiny_roots: {failure}");
        failures.push(failure);
    }
    eprintln!("fuzz_tiny_roots: {cases} cases, {tally:?}");
    assert_no_failures(&failures);
    assert!(
        tally.checked_against_oracle > cases / 2,
        "most cases reach the oracle: {tally:?}"
    );
}

/// The value of the environment variable `name`, else `default`.
fn env_or<T: std::str::FromStr>(name: &str, default: T) -> T {
    std::env::var(name)
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(default)
}

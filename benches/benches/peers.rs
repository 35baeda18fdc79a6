//! `poly`'s certified queries side by side with peer root finders on the same inputs, in one
//! process, solvers interleaved: polycool 0.4, kurbo 0.13 (quartics only), roots 0.0.8 (its
//! quartic closed form, and its Sturm solver for higher degrees). Each row counts the wrong
//! answers against the exact oracle of the stored polynomial (`toolkit_benches::truth`).
//!
//! `cargo bench -p toolkit-benches --bench peers` (add `PEERS_FULL=1` for degree 160; each
//! timing is the best of [`ROUNDS`] interleaved passes of at least [`MIN_PASS`] each, so a
//! loaded machine inflates every row about equally). The report goes to stdout; `paper-notes/isolation.md` keeps a copy.
//!
//! The growth-with-degree corpora (Kac, Chebyshev, planted at degree 40, 80, 160) also show
//! `poly`'s own `Sturm` heuristic, and with `PEERS_FLINT=1` python-flint's certified
//! `complex_roots` on the same stored polynomials (`benches/flint_roots.py`, run by
//! `python3` in the same bench run; flint is a reference, never a dependency: without it the
//! row says why it is missing).
//!
//! `PEERS_PROFILE=<corpus>` (`entry`, `eye`, `wilkinson`, `planted`, `quartics`, or a growth
//! corpus `kac<d>`, `cheb<d>`, `planted<d>`) runs only `poly` on that corpus, once, and
//! prints its statistics (`PEERS_METHOD=sturm` or `stam`: `poly`'s heuristic methods
//! instead of the certified one, with their refusals in the `unresolved` count): the
//! load-independent instruction count comes from running that under
//! `valgrind --tool=callgrind --toggle-collect='*run_poly_only*'`.

#![allow(clippy::print_stdout, reason = "a report binary")]
#![allow(missing_docs, reason = "a bench binary")]

use std::time::Instant;

use std::path::Path;
use std::process::Command;

use poly::{Poly, RefineMethod, RootStats};
use toolkit_benches::families::{Family, degree_cases, ray_cases};
use toolkit_benches::methods::Method;
use toolkit_benches::score::match_roots;
use toolkit_benches::truth::{Truth, stored_truth};

/// Interleaved timing passes per (corpus, solver); the best is reported.
const ROUNDS: usize = 7;

/// Shortest timing pass: a corpus that one solver answers faster is repeated within the pass
/// until it lasts this long. A pass of the 500 entry rays is ≈ 0.1 ms, short enough that the
/// best of seven still moved the ratio to polycool by ±10 % between runs (frequency steps,
/// interrupts); 2 ms passes average over those.
const MIN_PASS: std::time::Duration = std::time::Duration::from_millis(2);

/// Tolerance of every query (absolute, in `t` or `x`).
const X_TOL: f64 = 1e-12;

/// A smallest-root answer farther than this from the true smallest root (relative to
/// `max(1, |root|)`) is counted wrong: it is another root or no root at all (`X_TOL` is far
/// smaller, so a correct answer is never near this radius).
const WRONG_REL: f64 = 1e-6;

/// `poly`'s default certified method (Bernstein isolation, the default refinement: the
/// options of `RootOptions::new`).
const POLY: Method = Method::Bernstein(RefineMethod::NewtonBisection);

/// `poly`'s heuristic `f64` Sturm method (uncertified; the growth target compares with it).
const POLY_STURM: Method = Method::SturmF64(RefineMethod::NewtonBisection);

/// The name of a row.
fn name(m: Method) -> String {
    match m {
        POLY => "poly (certified)".to_owned(),
        POLY_STURM => "poly (sturm heuristic)".to_owned(),
        _ => m.name(),
    }
}

/// One query of a corpus: polynomial, range, and the exact answer.
struct Query {
    p: Poly<f64>,
    lo: f64,
    hi: f64,
    truth: Truth,
}

/// A corpus: its queries, whether only the smallest root is asked for, and the tolerance.
struct Corpus {
    title: String,
    queries: Vec<Query>,
    smallest: bool,
    x_tol: f64,
}

impl Corpus {
    fn new(title: impl Into<String>, queries: Vec<Query>, smallest: bool) -> Self {
        Corpus {
            title: title.into(),
            queries,
            smallest,
            x_tol: X_TOL,
        }
    }

    /// The wrong answers of `solver` to query `q`: 0 or 1 for a smallest-root query, the
    /// missed and phantom roots for an all-roots query.
    fn wrong(&self, solver: Method, q: &Query, stats: &mut RootStats) -> usize {
        let args = (q.lo, q.hi, self.x_tol);
        if self.smallest {
            let got = solver.smallest_root(&q.p, args.0, args.1, args.2, stats);
            usize::from(match (got, q.truth.approx.first()) {
                (None, None) => false,
                (Some(x), Some(&t)) => (x - t).abs() > WRONG_REL * t.abs().max(1.0),
                _ => true,
            })
        } else {
            let m = match_roots(
                &q.truth,
                &solver.all_roots(&q.p, args.0, args.1, args.2, stats),
            );
            m.missed + m.phantom
        }
    }
}

/// A row: mean time per query, wrong answers, and `poly`'s statistics.
struct Row {
    solver: Method,
    ns: f64,
    wrong: usize,
    stats: RootStats,
}

fn run(corpus: &Corpus, solvers: &[Method]) -> Vec<Row> {
    let mut rows: Vec<(Row, u32)> = solvers
        .iter()
        .map(|&solver| {
            let mut stats = RootStats::default();
            let start = Instant::now();
            let wrong = corpus
                .queries
                .iter()
                .map(|q| corpus.wrong(solver, q, &mut stats))
                .sum();
            // Repetitions of the corpus in a pass: enough for `MIN_PASS`, judged by this
            // first pass (which also scores the answers, so it is an upper bound).
            let once = start.elapsed().max(std::time::Duration::from_nanos(1));
            let reps = MIN_PASS.as_nanos().div_ceil(once.as_nanos()).max(1) as u32;
            let row = Row {
                solver,
                ns: f64::INFINITY,
                wrong,
                stats,
            };
            (row, reps)
        })
        .collect();
    let n = corpus.queries.len() as f64;
    for _ in 0..ROUNDS {
        for (row, reps) in &mut rows {
            let mut s = RootStats::default();
            let start = Instant::now();
            for _ in 0..*reps {
                for q in &corpus.queries {
                    let args = (q.lo, q.hi, corpus.x_tol);
                    if corpus.smallest {
                        std::hint::black_box(
                            row.solver
                                .smallest_root(&q.p, args.0, args.1, args.2, &mut s),
                        );
                    } else {
                        std::hint::black_box(
                            row.solver.all_roots(&q.p, args.0, args.1, args.2, &mut s),
                        );
                    }
                }
            }
            let per_query = start.elapsed().as_nanos() as f64 / (n * f64::from(*reps));
            row.ns = row.ns.min(per_query);
        }
    }
    rows.into_iter().map(|(row, _)| row).collect()
}

/// python-flint's certified `complex_roots` on the corpus's stored polynomials: mean time
/// per query (best of [`ROUNDS`] passes, timed in Python) and the queries whose count of
/// distinct real roots in `(lo, hi]` differs from the oracle's. `Err` says why there is no
/// row (no `python3`, no flint).
fn flint_row(corpus: &Corpus) -> Result<(f64, usize), String> {
    let mut input = String::new();
    for q in &corpus.queries {
        let coeffs: Vec<String> = q.p.coeffs().iter().map(f64::to_string).collect();
        input += &format!("{} {} {}\n", q.lo, q.hi, coeffs.join(" "));
    }
    let file = std::env::temp_dir().join(format!("peers-flint-{}.txt", std::process::id()));
    std::fs::write(&file, input).map_err(|e| format!("writing {}: {e}", file.display()))?;
    let script = Path::new(env!("CARGO_MANIFEST_DIR")).join("flint_roots.py");
    let out = Command::new("python3")
        .arg(&script)
        .arg(&file)
        .arg(ROUNDS.to_string())
        .output();
    let _ = std::fs::remove_file(&file);
    let out = out.map_err(|e| format!("python3: {e}"))?;
    if !out.status.success() {
        let err = String::from_utf8_lossy(&out.stderr);
        return Err(err.lines().last().unwrap_or("failed").to_string());
    }
    let text = String::from_utf8_lossy(&out.stdout);
    let mut lines = text.lines();
    let ns: f64 = lines
        .next()
        .and_then(|l| l.trim().parse().ok())
        .ok_or("no time in the output")?;
    let counts: Vec<usize> = lines
        .next()
        .unwrap_or("")
        .split_whitespace()
        .map(|c| c.parse().map_err(|e| format!("root count {c:?}: {e}")))
        .collect::<Result<_, String>>()?;
    if counts.len() != corpus.queries.len() {
        return Err(format!(
            "{} root counts for {} queries",
            counts.len(),
            corpus.queries.len()
        ));
    }
    let wrong = corpus
        .queries
        .iter()
        .zip(&counts)
        .filter(|&(q, &n)| q.truth.approx.len() != n)
        .count();
    Ok((ns, wrong))
}

fn report(corpus: &Corpus, solvers: &[Method], flint: bool) {
    let rows = run(corpus, solvers);
    let base = rows
        .iter()
        .find(|r| r.solver == Method::Polycool)
        .map(|r| r.ns);
    println!(
        "\n{} ({} queries, x_tol = {:e})\n",
        corpus.title,
        corpus.queries.len(),
        corpus.x_tol
    );
    println!(
        "| solver | time / query | × polycool | wrong | poly (certified): adaptive pieces (re-expanded in f64, of them far clusters) / multiprecision / adaptive refines / exact fallbacks / inclusion discs decided:undecided (undecided parts); poly's heuristics: queries refused |"
    );
    println!("|---|---|---|---|---|");
    for r in &rows {
        let ratio = base.map_or(String::new(), |b| format!("{:.2}", r.ns / b));
        let st = if r.solver == POLY {
            stats_cell(&r.stats)
        } else if r.stats.unresolved > 0 {
            // A heuristic of `poly`'s that says it cannot answer (`RootError::Unresolved`):
            // its wrong roots are the ones it did not return, and its time is a refusal's.
            format!(
                "refused {} of {} queries (`Unresolved`)",
                r.stats.unresolved,
                corpus.queries.len()
            )
        } else {
            String::new()
        };
        println!(
            "| {} | {:.2} µs | {ratio} | {} | {st} |",
            name(r.solver),
            r.ns / 1e3,
            r.wrong
        );
    }
    if flint {
        match flint_row(corpus) {
            Ok((ns, wrong)) => {
                let ratio = base.map_or(String::new(), |b| format!("{:.2}", ns / b));
                let poly = rows.iter().find(|r| r.solver == POLY);
                let vs = poly.map_or(String::new(), |p| {
                    format!("poly (certified) / flint = {:.2}", p.ns / ns)
                });
                println!(
                    "| python-flint `complex_roots` (all complex roots; wrong = queries with another real-root count) | {:.2} µs | {ratio} | {wrong} | {vs} |",
                    ns / 1e3
                );
            }
            Err(why) => println!("| python-flint | — | | | not run: {why} |"),
        }
    }
}

fn stats_cell(s: &RootStats) -> String {
    format!(
        "{} ({} re-expanded, {} clusters) / {} / {} / {} / {}:{} ({} parts)",
        s.adaptive_pieces,
        s.shifted_pieces,
        s.cluster_shifts,
        s.multiprecision_pieces,
        s.adaptive_refines,
        s.exact_fallbacks + s.refine_fallbacks,
        s.inclusion_decided,
        s.inclusion_undecided,
        s.inclusion_subranges
    )
}

fn queries(cases: Vec<toolkit_benches::families::Case>) -> Vec<Query> {
    cases
        .into_iter()
        .map(|c| Query {
            truth: stored_truth(&c.poly, c.lo, c.hi),
            p: c.poly,
            lo: c.lo,
            hi: c.hi,
        })
        .collect()
}

/// `(x − x₁)(x − x₂)(x − x₃)(x − x₄)` by Vieta's formulas in `f64`, as Orellana and De
/// Michele build their test quartics (the stored coefficients are the rounded ones; the
/// oracle answers for those).
fn vieta([x1, x2, x3, x4]: [f64; 4]) -> Poly<f64> {
    let a = -(x1 + x2 + x3 + x4);
    let b = x1 * (x2 + x3) + x2 * (x3 + x4) + x4 * (x1 + x3);
    let c = -x1 * x2 * (x3 + x4) - x3 * x4 * (x1 + x2);
    let d = x1 * x2 * x3 * x4;
    Poly::new(vec![d, c, b, a, 1.0])
}

/// The quartics of Orellana and De Michele (ACM TOMS 46(2), 2020, Table 1) that have real
/// roots, as kurbo 0.13's `test_solve_quartic` writes them (coefficients in decreasing order
/// there): all real roots on `(−∞, ∞)`.
fn orellana_de_michele() -> Vec<Query> {
    let monic = |[a, b, c, d]: [f64; 4]| Poly::new(vec![d, c, b, a, 1.0]);
    let s = 1e30;
    let polys = vec![
        vieta([1., 1e3, 1e6, 1e9]),
        vieta([2., 2.001, 2.002, 2.003]),
        vieta([1e47, 1e49, 1e50, 1e53]),
        vieta([-1., 1., 2., 1e14]),
        vieta([-2e7, -1., 1., 1e7]),
        monic([-9000002.0, -9999981999998.0, 19999982e6, -2e13]),
        monic([2000011.0, 1010022000028.0, 11110056e6, 2828e10]),
        monic([-100002011.0, 201101022001.0, -102200111000011.0, 11000011e8]),
        vieta([1000., 1000., 1000., 1000.]),
        vieta([1e-15, 1000., 1000., 1000.]),
        vieta([10000., 10001., 10010., 10100.]),
        vieta([1., 1e30, 1e30, 1e44]),
        vieta([1., 1e7, 1e7, 1e14]),
        vieta([1., 10., 1e152, 1e154]),
        monic([1., 1., 3. / 8., 1e-3]),
        monic([-(1. + 1. / s), 1. / s - s * s, s * s + s, -s]),
    ];
    polys
        .into_iter()
        .map(|p| {
            // Every real root lies within the root bound: the truth on (−2B, 2B] is the
            // truth on (−∞, ∞).
            let b = 2.0 * p.root_bound().expect("a root bound");
            Query {
                truth: stored_truth(&p, -b, b),
                p,
                lo: f64::NEG_INFINITY,
                hi: f64::INFINITY,
            }
        })
        .collect()
}

/// The named corpora of the targets of issue 11 (`PEERS_PROFILE` names).
fn target_corpus(name: &str) -> Option<Corpus> {
    Some(match name {
        "entry" => Corpus::new(
            "Torus rays restricted at the bounding-sphere entry, smallest root",
            queries(ray_cases(Family::TorusEntry, 8.0, 500, 11)),
            true,
        ),
        "eye" => Corpus::new(
            "Torus rays restricted at the eye, distance 1e4, smallest root",
            queries(ray_cases(Family::TorusEye, 1e4, 500, 12)),
            true,
        ),
        "wilkinson" => Corpus::new(
            "Wilkinson-20, all roots on its range",
            queries(degree_cases(Family::Wilkinson, 20, 1, 1)),
            false,
        ),
        "planted" => Corpus::new(
            "Planted rational roots, degree 3–20 (6 each), all roots",
            queries(
                (3..=20)
                    .flat_map(|d| degree_cases(Family::Planted, d, 6, 13))
                    .collect(),
            ),
            false,
        ),
        "quartics" => Corpus {
            x_tol: 0.0,
            ..Corpus::new(
                "Orellana–De Michele quartics with real roots, all roots on (−∞, ∞)",
                orellana_de_michele(),
                false,
            )
        },
        _ => return growth_corpus(name),
    })
}

/// A growth-with-degree corpus by name: `kac<d>`, `cheb<d>` or `planted<d>` (the same
/// polynomials as the growth tables: 3 samples, Chebyshev 1, seed 14).
fn growth_corpus(name: &str) -> Option<Corpus> {
    let (family, samples, digits) = [
        ("kac", Family::Kac, 3),
        ("cheb", Family::Chebyshev, 1),
        ("planted", Family::Planted, 3),
    ]
    .into_iter()
    .find_map(|(prefix, family, samples)| Some((family, samples, name.strip_prefix(prefix)?)))?;
    let d: usize = digits.parse().ok().filter(|&d| d >= 1)?;
    Some(Corpus::new(
        format!("{} degree {d}, all roots", family.name()),
        queries(degree_cases(family, d, samples, 14)),
        false,
    ))
}

/// `poly` alone on one corpus, once (the function callgrind's `--toggle-collect` selects),
/// by `method` (the certified default unless `PEERS_METHOD` names a heuristic).
#[inline(never)]
fn run_poly_only(corpus: &Corpus, method: Method) -> (usize, RootStats) {
    let mut stats = RootStats::default();
    let wrong = corpus
        .queries
        .iter()
        .map(|q| corpus.wrong(method, q, &mut stats))
        .sum();
    (wrong, stats)
}

/// The method `PEERS_PROFILE` runs: `PEERS_METHOD=sturm` or `stam` for `poly`'s heuristics
/// (issue 11: their cost before and after the honesty checks), else the certified default.
fn profile_method() -> Method {
    match std::env::var("PEERS_METHOD").as_deref() {
        Ok("sturm") => POLY_STURM,
        Ok("stam") => Method::Stam,
        _ => POLY,
    }
}

fn main() {
    if let Some(name) = std::env::var_os("PEERS_PROFILE") {
        let name = name.to_string_lossy();
        let Some(corpus) = target_corpus(&name) else {
            eprintln!(
                "PEERS_PROFILE: unknown corpus {name:?} (entry, eye, wilkinson, planted, quartics, kac<d>, cheb<d>, planted<d>)"
            );
            std::process::exit(2);
        };
        let (wrong, stats) = run_poly_only(&corpus, profile_method());
        println!(
            "{}: {} queries, {wrong} wrong, {} unresolved, adaptive (re-expanded, clusters) / mp / refines / exact / discs decided:undecided (undecided parts): {}",
            corpus.title,
            corpus.queries.len(),
            stats.unresolved,
            stats_cell(&stats)
        );
        return;
    }
    let full = std::env::var_os("PEERS_FULL").is_some();
    let quartic = [POLY, Method::Polycool, Method::Kurbo, Method::Roots];
    let general = [POLY, Method::Polycool, Method::Roots];
    println!("best of {ROUNDS} interleaved passes");
    for name in ["entry", "eye", "wilkinson", "planted", "quartics"] {
        let corpus = target_corpus(name).expect("a named corpus");
        let quartics = corpus.queries.iter().all(|q| q.p.degree() == 4);
        report(&corpus, if quartics { &quartic } else { &general }, false);
    }
    // No width cliff: the same polynomials on a tight range and on (−∞, ∞).
    let cheb12 = degree_cases(Family::Chebyshev, 12, 1, 1).remove(0).poly;
    let planted12: Vec<_> = degree_cases(Family::Planted, 12, 6, 15)
        .into_iter()
        .map(|c| c.poly)
        .collect();
    for (lo, hi) in [(-1.0, 1.0), (-2.0, 2.0), (f64::NEG_INFINITY, f64::INFINITY)] {
        let mut polys = vec![cheb12.clone()];
        polys.extend(planted12.iter().cloned());
        let qs: Vec<Query> = polys
            .into_iter()
            .map(|p| Query {
                // Every root is in [0, 1] (planted) or (−1, 1) (Chebyshev): the same truth.
                truth: stored_truth(&p, -1.0, 1.0),
                p,
                lo,
                hi,
            })
            .collect();
        let title =
            format!("Width: Chebyshev T12 and planted degree 12, all roots on ({lo}, {hi}]");
        report(&Corpus::new(title, qs, false), &general, false);
    }
    // Growth with degree: the certified path against its own heuristic and against flint.
    let flint = std::env::var_os("PEERS_FLINT").is_some();
    let growth = [POLY, POLY_STURM, Method::Polycool, Method::Roots];
    let degrees: &[usize] = if full { &[40, 80, 160] } else { &[40, 80] };
    for &d in degrees {
        for family in [Family::Kac, Family::Chebyshev, Family::Planted] {
            let samples = if family == Family::Chebyshev { 1 } else { 3 };
            let title = format!("{} degree {d}, all roots", family.name());
            report(
                &Corpus::new(title, queries(degree_cases(family, d, samples, 14)), false),
                &growth,
                flint,
            );
        }
    }
}

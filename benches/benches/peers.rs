//! `poly`'s certified queries side by side with peer root finders on the same inputs, in one
//! process, solvers interleaved: polycool 0.4, kurbo 0.13 (quartics only), roots 0.0.8 (its
//! quartic closed form, and its Sturm solver for higher degrees). Each row counts the wrong
//! answers against the exact oracle of the stored polynomial (`toolkit_benches::truth`).
//!
//! `cargo bench -p toolkit-benches --bench peers` (add `PEERS_FULL=1` for degree 160; each
//! timing is the best of [`ROUNDS`] interleaved passes, so a loaded machine inflates every
//! row about equally). The report goes to stdout; `paper-notes/isolation.md` keeps a copy.
//!
//! `PEERS_PROFILE=<corpus>` (`entry`, `eye`, `wilkinson`, `planted`, `quartics`) runs only
//! `poly` on that corpus, once, and prints its statistics: the load-independent
//! instruction count comes from running that under
//! `valgrind --tool=callgrind --toggle-collect='*run_poly_only*'`.

#![allow(clippy::print_stdout, reason = "a report binary")]
#![allow(missing_docs, reason = "a bench binary")]

use std::time::Instant;

use poly::{Poly, RootOptions, RootStats};
use toolkit_benches::families::{Family, degree_cases, ray_cases};
use toolkit_benches::score::match_roots;
use toolkit_benches::truth::{Truth, stored_truth};

/// Interleaved timing passes per (corpus, solver); the best is reported.
const ROUNDS: usize = 7;

/// Tolerance of every query (absolute, in `t` or `x`).
const X_TOL: f64 = 1e-12;

/// A smallest-root answer farther than this from the true smallest root (relative to
/// `max(1, |root|)`) is counted wrong: it is another root or no root at all (`X_TOL` is far
/// smaller, so a correct answer is never near this radius).
const WRONG_REL: f64 = 1e-6;

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Solver {
    /// `poly`'s default certified method.
    Poly,
    Polycool,
    /// kurbo's `solve_quartic` (degree ≤ 4 only).
    Kurbo,
    /// roots' closed forms up to degree 4, its `find_roots_sturm` above.
    Roots,
}

impl Solver {
    fn name(self) -> &'static str {
        match self {
            Solver::Poly => "poly (certified)",
            Solver::Polycool => "polycool 0.4",
            Solver::Kurbo => "kurbo 0.13",
            Solver::Roots => "roots 0.0.8",
        }
    }

    /// Every real root in `(lo, hi]`, sorted (what the solver reports there).
    fn all_roots(
        self,
        p: &Poly<f64>,
        (lo, hi, x_tol): (f64, f64, f64),
        stats: &mut RootStats,
    ) -> Vec<f64> {
        let c = p.coeffs();
        let mut r = match self {
            Solver::Poly => {
                return p
                    .real_roots_with(lo, hi, &RootOptions::new(x_tol), stats)
                    .unwrap_or_default();
            }
            Solver::Polycool => {
                if c.len() == 5 {
                    polycool::Poly::<5>::new([c[0], c[1], c[2], c[3], c[4]])
                        .roots_between(lo, hi, x_tol)
                        .to_vec()
                } else {
                    polycool::PolyDyn::new(c.iter().copied()).roots_between(lo, hi, x_tol)
                }
            }
            Solver::Kurbo => match c.len() {
                5 => kurbo::common::solve_quartic(c[0], c[1], c[2], c[3], c[4]).to_vec(),
                _ => return Vec::new(),
            },
            Solver::Roots => {
                if c.len() == 5 {
                    roots::find_roots_quartic(c[4], c[3], c[2], c[1], c[0])
                        .as_ref()
                        .to_vec()
                } else {
                    let n = c.len() - 1;
                    let monic: Vec<f64> = (0..n).rev().map(|i| c[i] / c[n]).collect();
                    roots::find_roots_sturm(&monic, &mut 1e-14f64)
                        .into_iter()
                        .filter_map(Result::ok)
                        .collect()
                }
            }
        };
        r.retain(|&x| x > lo && x <= hi);
        r.sort_by(f64::total_cmp);
        r
    }

    fn smallest_root(
        self,
        p: &Poly<f64>,
        (lo, hi, x_tol): (f64, f64, f64),
        stats: &mut RootStats,
    ) -> Option<f64> {
        match self {
            Solver::Poly => p.smallest_root_with(lo, hi, &RootOptions::new(x_tol), stats),
            _ => self.all_roots(p, (lo, hi, x_tol), stats).first().copied(),
        }
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
    fn wrong(&self, solver: Solver, q: &Query, stats: &mut RootStats) -> usize {
        let args = (q.lo, q.hi, self.x_tol);
        if self.smallest {
            let got = solver.smallest_root(&q.p, args, stats);
            usize::from(match (got, q.truth.approx.first()) {
                (None, None) => false,
                (Some(x), Some(&t)) => (x - t).abs() > WRONG_REL * t.abs().max(1.0),
                _ => true,
            })
        } else {
            let m = match_roots(&q.truth, &solver.all_roots(&q.p, args, stats));
            m.missed + m.phantom
        }
    }
}

/// A row: mean time per query, wrong answers, and `poly`'s statistics.
struct Row {
    solver: Solver,
    ns: f64,
    wrong: usize,
    stats: RootStats,
}

fn run(corpus: &Corpus, solvers: &[Solver]) -> Vec<Row> {
    let mut rows: Vec<Row> = solvers
        .iter()
        .map(|&solver| {
            let mut stats = RootStats::default();
            let wrong = corpus
                .queries
                .iter()
                .map(|q| corpus.wrong(solver, q, &mut stats))
                .sum();
            Row {
                solver,
                ns: f64::INFINITY,
                wrong,
                stats,
            }
        })
        .collect();
    let n = corpus.queries.len() as f64;
    for _ in 0..ROUNDS {
        for row in &mut rows {
            let mut s = RootStats::default();
            let start = Instant::now();
            for q in &corpus.queries {
                let args = (q.lo, q.hi, corpus.x_tol);
                if corpus.smallest {
                    std::hint::black_box(row.solver.smallest_root(&q.p, args, &mut s));
                } else {
                    std::hint::black_box(row.solver.all_roots(&q.p, args, &mut s));
                }
            }
            row.ns = row.ns.min(start.elapsed().as_nanos() as f64 / n);
        }
    }
    rows
}

fn report(corpus: &Corpus, solvers: &[Solver]) {
    let rows = run(corpus, solvers);
    let base = rows
        .iter()
        .find(|r| r.solver == Solver::Polycool)
        .map(|r| r.ns);
    println!(
        "\n{} ({} queries, x_tol = {:e})\n",
        corpus.title,
        corpus.queries.len(),
        corpus.x_tol
    );
    println!(
        "| solver | time / query | × polycool | wrong | poly: adaptive pieces / multiprecision / adaptive refines / exact fallbacks |"
    );
    println!("|---|---|---|---|---|");
    for r in &rows {
        let ratio = base.map_or(String::new(), |b| format!("{:.2}", r.ns / b));
        let st = if r.solver == Solver::Poly {
            stats_cell(&r.stats)
        } else {
            String::new()
        };
        println!(
            "| {} | {:.2} µs | {ratio} | {} | {st} |",
            r.solver.name(),
            r.ns / 1e3,
            r.wrong
        );
    }
}

fn stats_cell(s: &RootStats) -> String {
    format!(
        "{} / {} / {} / {}",
        s.adaptive_pieces,
        s.multiprecision_pieces,
        s.adaptive_refines,
        s.exact_fallbacks + s.refine_fallbacks
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
        _ => return None,
    })
}

/// `poly` alone on one corpus, once (the function callgrind's `--toggle-collect` selects).
#[inline(never)]
fn run_poly_only(corpus: &Corpus) -> (usize, RootStats) {
    let mut stats = RootStats::default();
    let wrong = corpus
        .queries
        .iter()
        .map(|q| corpus.wrong(Solver::Poly, q, &mut stats))
        .sum();
    (wrong, stats)
}

fn main() {
    if let Some(name) = std::env::var_os("PEERS_PROFILE") {
        let name = name.to_string_lossy();
        let Some(corpus) = target_corpus(&name) else {
            eprintln!(
                "PEERS_PROFILE: unknown corpus {name:?} (entry, eye, wilkinson, planted, quartics)"
            );
            std::process::exit(2);
        };
        let (wrong, stats) = run_poly_only(&corpus);
        println!(
            "{}: {} queries, {wrong} wrong, adaptive / mp / refines / exact: {}",
            corpus.title,
            corpus.queries.len(),
            stats_cell(&stats)
        );
        return;
    }
    let full = std::env::var_os("PEERS_FULL").is_some();
    let quartic = [Solver::Poly, Solver::Polycool, Solver::Kurbo, Solver::Roots];
    let general = [Solver::Poly, Solver::Polycool, Solver::Roots];
    println!("best of {ROUNDS} interleaved passes");
    for name in ["entry", "eye", "wilkinson", "planted", "quartics"] {
        let corpus = target_corpus(name).expect("a named corpus");
        let quartics = corpus.queries.iter().all(|q| q.p.degree() == 4);
        report(&corpus, if quartics { &quartic } else { &general });
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
        report(&Corpus::new(title, qs, false), &general);
    }
    let degrees: &[usize] = if full { &[40, 80, 160] } else { &[40, 80] };
    for &d in degrees {
        for family in [Family::Kac, Family::Chebyshev] {
            let samples = if family == Family::Kac { 3 } else { 1 };
            let title = format!("{} degree {d}, all roots", family.name());
            report(
                &Corpus::new(title, queries(degree_cases(family, d, samples, 14)), false),
                &general,
            );
        }
    }
}

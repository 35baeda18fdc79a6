//! `poly`'s certified queries side by side with peer root finders on the same inputs, in one
//! process, solvers interleaved: polycool 0.4, kurbo 0.13 (quartics only), roots 0.0.8 (its
//! quartic closed form, and its Sturm solver for higher degrees). Each row counts the wrong
//! answers against the exact oracle of the stored polynomial (`toolkit_benches::truth`).
//!
//! `cargo bench -p toolkit-benches --bench peers` (add `PEERS_FULL=1` for degree 160; each
//! timing is the best of [`ROUNDS`] interleaved passes, so a loaded machine inflates every
//! row about equally). The report goes to stdout; `paper-notes/isolation.md` keeps a copy.

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
    fn all_roots(self, p: &Poly<f64>, lo: f64, hi: f64, stats: &mut RootStats) -> Vec<f64> {
        let c = p.coeffs();
        let mut r = match self {
            Solver::Poly => {
                return p
                    .real_roots_with(lo, hi, &RootOptions::new(X_TOL), stats)
                    .unwrap_or_default();
            }
            Solver::Polycool => {
                if c.len() == 5 {
                    polycool::Poly::<5>::new([c[0], c[1], c[2], c[3], c[4]])
                        .roots_between(lo, hi, X_TOL)
                        .to_vec()
                } else {
                    polycool::PolyDyn::new(c.iter().copied()).roots_between(lo, hi, X_TOL)
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

    fn smallest_root(self, p: &Poly<f64>, lo: f64, hi: f64, stats: &mut RootStats) -> Option<f64> {
        match self {
            Solver::Poly => p.smallest_root_with(lo, hi, &RootOptions::new(X_TOL), stats),
            _ => self.all_roots(p, lo, hi, stats).first().copied(),
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

/// A row: mean time per query, wrong answers, and `poly`'s statistics.
struct Row {
    solver: Solver,
    ns: f64,
    wrong: usize,
    stats: RootStats,
}

fn run(queries: &[Query], solvers: &[Solver], smallest: bool) -> Vec<Row> {
    let mut rows: Vec<Row> = solvers
        .iter()
        .map(|&solver| {
            let mut stats = RootStats::default();
            let mut wrong = 0;
            for q in queries {
                if smallest {
                    let got = solver.smallest_root(&q.p, q.lo, q.hi, &mut stats);
                    let ok = match (got, q.truth.approx.first()) {
                        (None, None) => true,
                        (Some(x), Some(&t)) => (x - t).abs() <= WRONG_REL * t.abs().max(1.0),
                        _ => false,
                    };
                    wrong += usize::from(!ok);
                } else {
                    let got = solver.all_roots(&q.p, q.lo, q.hi, &mut stats);
                    let m = match_roots(&q.truth, &got);
                    wrong += m.missed + m.phantom;
                }
            }
            Row {
                solver,
                ns: f64::INFINITY,
                wrong,
                stats,
            }
        })
        .collect();
    for _ in 0..ROUNDS {
        for row in &mut rows {
            let mut s = RootStats::default();
            let start = Instant::now();
            for q in queries {
                if smallest {
                    std::hint::black_box(row.solver.smallest_root(&q.p, q.lo, q.hi, &mut s));
                } else {
                    std::hint::black_box(row.solver.all_roots(&q.p, q.lo, q.hi, &mut s));
                }
            }
            let ns = start.elapsed().as_nanos() as f64 / queries.len() as f64;
            row.ns = row.ns.min(ns);
        }
    }
    rows
}

fn report(title: &str, queries: &[Query], solvers: &[Solver], smallest: bool) {
    let rows = run(queries, solvers, smallest);
    let base = rows
        .iter()
        .find(|r| r.solver == Solver::Polycool)
        .map(|r| r.ns);
    println!("\n{title} ({} queries)\n", queries.len());
    println!(
        "| solver | time / query | × polycool | wrong | poly: adaptive pieces / multiprecision / adaptive refines / exact fallbacks |"
    );
    println!("|---|---|---|---|---|");
    for r in &rows {
        let ratio = base.map_or("".to_owned(), |b| format!("{:.2}", r.ns / b));
        let st = if r.solver == Solver::Poly {
            format!(
                "{} / {} / {} / {}",
                r.stats.adaptive_pieces,
                r.stats.multiprecision_pieces,
                r.stats.adaptive_refines,
                r.stats.exact_fallbacks + r.stats.refine_fallbacks
            )
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

fn main() {
    let full = std::env::var_os("PEERS_FULL").is_some();
    let quartic = [Solver::Poly, Solver::Polycool, Solver::Kurbo, Solver::Roots];
    let general = [Solver::Poly, Solver::Polycool, Solver::Roots];
    println!("x_tol = {X_TOL:e}; best of {ROUNDS} interleaved passes");
    report(
        "Torus rays restricted at the bounding-sphere entry, smallest root",
        &queries(ray_cases(Family::TorusEntry, 8.0, 500, 11)),
        &quartic,
        true,
    );
    report(
        "Torus rays restricted at the eye, distance 1e4, smallest root",
        &queries(ray_cases(Family::TorusEye, 1e4, 500, 12)),
        &quartic,
        true,
    );
    report(
        "Wilkinson-20, all roots on its range",
        &queries(degree_cases(Family::Wilkinson, 20, 1, 1)),
        &general,
        false,
    );
    let planted: Vec<_> = (3..=20)
        .flat_map(|d| degree_cases(Family::Planted, d, 6, 13))
        .collect();
    report(
        "Planted rational roots, degree 3–20 (6 each), all roots",
        &queries(planted),
        &general,
        false,
    );
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
        report(
            &format!("Width: Chebyshev T12 and planted degree 12, all roots on ({lo}, {hi}]"),
            &qs,
            &general,
            false,
        );
    }
    let degrees: &[usize] = if full { &[40, 80, 160] } else { &[40, 80] };
    for &d in degrees {
        for family in [Family::Kac, Family::Chebyshev] {
            let samples = if family == Family::Kac { 3 } else { 1 };
            report(
                &format!("{} degree {d}, all roots", family.name()),
                &queries(degree_cases(family, d, samples, 14)),
                &general,
                false,
            );
        }
    }
}

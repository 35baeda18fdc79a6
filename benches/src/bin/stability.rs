//! The numerical-stability suite: every root finder on every test family, degree 2 … 40 and
//! camera distance 10 … 10 000, scored against certified exact roots.
//!
//! `cargo run --release -p toolkit-benches --bin stability` writes `docs/stability.md`,
//! `docs/stability-error.svg` and `docs/stability-time.svg`; `--quick` runs a reduced suite.

use std::fmt::Write as _;
use std::io::Write as _;
use std::path::PathBuf;
use std::time::{Duration, Instant};

use anyhow::Result;
use clap::Parser;
use poly::RootStats;
use std::sync::atomic::Ordering;
use toolkit_benches::families::{Case, Family, degree_cases, ray_cases};
use toolkit_benches::methods::{COMPANION_FAILURES, COMPANION_IMAG_TOL, COMPANION_RETRIES, Method};
use toolkit_benches::plot::{Panel, Series, grid_svg};
use toolkit_benches::rays::CAMERA_DISTANCES;
use toolkit_benches::report::{git_commit, sci, table, write_atomically};
use toolkit_benches::score::{MATCH_RADIUS_REL, Score, max, median};
use toolkit_benches::timing::{human_nanos, load_average, load_note, machine, nanos_per_call};
use toolkit_benches::truth::{TRUTH_BITS, exact_roots, stored_truth};

/// Root tolerance of the suite, relative to the search range: every method is asked for
/// `x_tol = STABILITY_X_TOL_REL · max(1, |lo|, |hi|)` (absolute), close to what `f64` can
/// resolve, so that the errors measured are the methods' own and not the tolerance.
const STABILITY_X_TOL_REL: f64 = 1e-14;

/// Relative error above which a root is "inaccurate" in the summary: 1e-6, far above every
/// tolerance asked, far below the match radius.
const INACCURATE_REL: f64 = 1e-6;

/// Plot floor for exact answers on the log error axis.
const ERROR_FLOOR: f64 = 1e-18;

/// Where a count failure (missed or phantom root) is drawn on the error plot.
const COUNT_FAILURE_Y: f64 = 10.0;

/// Run every root finder on every test family and compare with certified exact roots.
#[derive(Debug, Parser)]
#[command(name = "stability", about)]
struct Args {
    /// Highest degree of the polynomial families (from 2).
    #[arg(long, default_value_t = 40, value_parser = clap::value_parser!(u32).range(2..=200))]
    max_degree: u32,
    /// Reduced suite: degrees up to 12, 3 samples, 8 rays, 1 ms timing budget.
    #[arg(long)]
    quick: bool,
    /// Polynomials per degree for the random families.
    #[arg(long, default_value_t = 8)]
    samples: usize,
    /// Rays per camera distance for the ray families.
    #[arg(long, default_value_t = 32)]
    rays: usize,
    /// Minimum wall time spent timing each (polynomial, method), in milliseconds.
    #[arg(long, default_value_t = 5)]
    budget_ms: u64,
    /// Seed of the random families.
    #[arg(long, default_value_t = 6)]
    seed: u64,
    /// Directory for stability.md and the SVG plots.
    #[arg(long, default_value = concat!(env!("CARGO_MANIFEST_DIR"), "/../docs"))]
    out_dir: PathBuf,
}

/// Marks the end of the generated part of `docs/stability.md`; what follows is kept.
const GENERATED_END: &str = "<!-- generated above; hand-written below is kept -->";

/// One (family, parameter) row: a score per method, and for the torus the construction error.
struct Row {
    family: Family,
    param: f64,
    scores: Vec<Score>,
    construction: Option<Score>,
}

fn run_cases(cases: &[Case], budget: Duration) -> (Vec<Score>, Option<Score>) {
    let mut scores = vec![Score::default(); Method::STABILITY.len()];
    let mut construction: Option<Score> = None;
    for c in cases {
        let truth = stored_truth(&c.poly, c.lo, c.hi);
        if let Some(exact) = &c.exact {
            let lo = poly::rat_from_f64(c.lo).expect("finite");
            let hi = poly::rat_from_f64(c.hi).expect("finite");
            let geometric = exact_roots(exact, &lo, &hi);
            construction
                .get_or_insert_with(Score::default)
                .add(&geometric, &truth.approx, 0.0);
        }
        let x_tol = STABILITY_X_TOL_REL * c.lo.abs().max(c.hi.abs()).max(1.0);
        for (m, score) in Method::STABILITY.iter().zip(scores.iter_mut()) {
            if !m.supports(c.poly.degree()) {
                continue;
            }
            let mut stats = RootStats::default();
            let retries = COMPANION_RETRIES.load(Ordering::Relaxed);
            let found = m.all_roots(&c.poly, c.lo, c.hi, x_tol, &mut stats);
            // For the companion baseline the fallback column counts shifted Schur retries.
            score.fallbacks += COMPANION_RETRIES.load(Ordering::Relaxed) - retries;
            let ns = nanos_per_call(budget, || {
                let mut s = RootStats::default();
                m.all_roots(&c.poly, c.lo, c.hi, x_tol, &mut s)
            });
            score.fallbacks += stats.exact_fallbacks + stats.refine_fallbacks;
            score.add(&truth, &found, ns);
        }
    }
    (scores, construction)
}

fn param_label(family: Family, param: f64) -> String {
    if family.is_ray() {
        format!("D={param}")
    } else {
        format!("d={param}")
    }
}

/// `"3m 1p"` for count failures, or the max relative error; "—" where the method took no
/// case (kurbo above degree 4).
fn compact_cell(s: &Score) -> String {
    if s.cases == 0 {
        return "—".to_owned();
    }
    let counts = if s.counts_ok() {
        String::new()
    } else {
        format!("**{}m {}p** · ", s.missed, s.phantom)
    };
    format!(
        "{counts}{} · {}",
        sci(max(&s.rel_err)),
        human_nanos(s.mean_nanos())
    )
}

/// The summary cell of one (family, method): first parameter with a count failure and first
/// with an inaccurate root, and the worst relative error where counts were right.
fn summary_cell(all_rows: &[&Row], mi: usize) -> String {
    let rows: Vec<&Row> = all_rows
        .iter()
        .copied()
        .filter(|r| r.scores[mi].cases > 0)
        .collect();
    let Some(first) = rows.first() else {
        return "—".to_owned();
    };
    // A method that took only some rows (kurbo: degree ≤ 4) says which.
    let only = if rows.len() < all_rows.len() {
        let params: Vec<f64> = rows.iter().map(|r| r.param).collect();
        format!(" [{} only]", ranges(first.family, &params))
    } else {
        String::new()
    };
    format!("{}{only}", summary_of(&rows, mi))
}

/// [`summary_cell`] over the rows the method took.
fn summary_of(rows: &[&Row], mi: usize) -> String {
    let first_count = rows.iter().find(|r| !r.scores[mi].counts_ok());
    let first_inacc = rows
        .iter()
        .find(|r| max(&r.scores[mi].rel_err) > INACCURATE_REL);
    let failing = rows.iter().filter(|r| !r.scores[mi].counts_ok()).count();
    let worst_ok = rows
        .iter()
        .filter(|r| r.scores[mi].counts_ok())
        .map(|r| max(&r.scores[mi].rel_err))
        .fold(0.0, f64::max);
    match (first_count, first_inacc) {
        (None, None) => format!("ok everywhere (max rel {})", sci(worst_ok)),
        _ => {
            let mut s = String::new();
            if let Some(r) = first_count {
                let sc = &r.scores[mi];
                let _ = write!(
                    s,
                    "**counts wrong from {}** ({}m {}p there; {}/{} rows)",
                    param_label(r.family, r.param),
                    sc.missed,
                    sc.phantom,
                    failing,
                    rows.len()
                );
            }
            if let Some(r) = first_inacc {
                if !s.is_empty() {
                    s.push_str("; ");
                }
                let _ = write!(
                    s,
                    "rel err > {} from {}",
                    sci(INACCURATE_REL),
                    param_label(r.family, r.param)
                );
            }
            s
        }
    }
}

/// `d=3, 5, 7-40` style list of parameters (consecutive degrees merged).
fn ranges(family: Family, params: &[f64]) -> String {
    if family.is_ray() {
        return params
            .iter()
            .map(|p| format!("D={p}"))
            .collect::<Vec<_>>()
            .join(", ");
    }
    let mut parts: Vec<String> = Vec::new();
    let mut i = 0;
    while i < params.len() {
        let mut j = i;
        while j + 1 < params.len() && params[j + 1] == params[j] + 1.0 {
            j += 1;
        }
        parts.push(if j > i + 1 {
            format!("{}–{}", params[i], params[j])
        } else if j == i + 1 {
            format!("{}, {}", params[i], params[j])
        } else {
            format!("{}", params[i])
        });
        i = j + 1;
    }
    format!("d={}", parts.join(", "))
}

fn full_rows(rows: &[&Row]) -> Vec<Vec<String>> {
    let mut out = Vec::new();
    for r in rows {
        for (m, s) in Method::STABILITY.iter().zip(&r.scores) {
            if s.cases == 0 {
                continue;
            }
            out.push(vec![
                param_label(r.family, r.param),
                m.name(),
                s.cases.to_string(),
                s.true_roots.to_string(),
                s.missed.to_string(),
                s.phantom.to_string(),
                sci(max(&s.abs_err)),
                sci(median(&s.abs_err)),
                sci(max(&s.rel_err)),
                sci(median(&s.rel_err)),
                human_nanos(s.mean_nanos()),
                s.fallbacks.to_string(),
            ]);
        }
        if let Some(c) = &r.construction {
            out.push(vec![
                param_label(r.family, r.param),
                "*construction*".to_owned(),
                c.cases.to_string(),
                c.true_roots.to_string(),
                c.missed.to_string(),
                c.phantom.to_string(),
                sci(max(&c.abs_err)),
                sci(median(&c.abs_err)),
                sci(max(&c.rel_err)),
                sci(median(&c.rel_err)),
                "—".to_owned(),
                "—".to_owned(),
            ]);
        }
    }
    out
}

fn families_in(rows: &[Row]) -> Vec<Family> {
    let mut fams: Vec<Family> = Vec::new();
    for r in rows {
        if !fams.contains(&r.family) {
            fams.push(r.family);
        }
    }
    fams
}

fn markdown(args: &Args, cmd: &str, rows: &[Row], elapsed: Duration, load: Option<f64>) -> String {
    let names: Vec<String> = Method::STABILITY.iter().map(|m| m.name()).collect();
    let mut md = String::new();
    let _ = writeln!(md, "# Numerical stability of the root finders, by degree\n");
    let _ = writeln!(
        md,
        "Generated by `{cmd}` (commit `{}`, {:.0} s) on a **{}** machine ({}): times \
         are noisy, compare ratios within a column set, not absolute values across runs. \
         Plots: [error vs degree](stability-error.svg), [time vs degree](stability-time.svg).\n",
        git_commit(),
        elapsed.as_secs_f64(),
        machine(),
        load_note(load)
    );
    let _ = writeln!(
        md,
        "**Truth is exact.** Every `f64` coefficient is a dyadic rational, so the polynomial \
         as stored is a rational polynomial; its exact rational Sturm sequence isolates its \
         distinct real roots without error, and exact bisection narrows each to width \
         2^-{TRUTH_BITS}. Every method is scored against these certified roots of the *stored* \
         polynomial, so rounding while building the coefficients (Wilkinson's 20! is not an \
         `f64`) is not blamed on a solver; for the ray families the row *construction* shows \
         that rounding separately (stored-polynomial roots vs. the roots of the exact \
         restriction of the same ray; errors there are construction errors, not solver \
         errors). At large camera distances the eye-restricted polynomial can lose or gain \
         roots before any solver runs: its `roots` column is the stored polynomial's.\n"
    );
    let _ = writeln!(
        md,
        "**Scoring.** Each method is asked for every distinct real root in the search range \
         `(lo, hi]` (polynomial families: `(−B, B]`, `B` a power of two above the root bound; \
         rays: the range a tracer searches) with `x_tol = {} · max(1, |lo|, |hi|)` \
         (absolute). Reported values are matched one-to-one, in order, to true roots within \
         `{} · max(1, |r|)`; an unmatched true root is *missed* (m), an unmatched value a \
         *phantom* (p; a duplicate report of one root counts as a phantom). Errors are over \
         matched roots: absolute `|x − r|`, relative `|x − r|/|r|` (zero roots excluded). \
         Time is wall time per solve of the whole polynomial (mean over the cases, each timed \
         for at least {} ms). Random families: {} polynomials per degree; ray families: {} \
         rays per camera distance. *fallbacks* counts `poly`'s switches to exact arithmetic \
         (isolation or refinement).\n",
        sci(STABILITY_X_TOL_REL),
        sci(MATCH_RADIUS_REL),
        args.budget_ms,
        args.samples,
        args.rays,
    );
    let _ = writeln!(md, "**Methods.**\n");
    let ci = Method::STABILITY
        .iter()
        .position(|m| *m == Method::Companion)
        .expect("the companion baseline is in the suite");
    let _ = writeln!(
        md,
        "Companion solves that needed a shifted retry because nalgebra's Schur iteration \
         did not converge (its *fallbacks* column): {} of {}; solves (timing repetitions \
         included) that failed even so and reported no roots: {}.\n",
        rows.iter().map(|r| r.scores[ci].fallbacks).sum::<u64>(),
        rows.iter().map(|r| r.scores[ci].cases).sum::<usize>(),
        COMPANION_FAILURES.load(Ordering::Relaxed)
    );
    for (m, n) in Method::STABILITY.iter().zip(&names) {
        let what = match m {
            Method::Stam => {
                "Stam's 1988 `ray2.c` (the seed's algorithm, the baseline): unnormalised `f64` Sturm recurrence, count-driven bisection, bisection on the sign of P; all roots by restarting his smallest-root search after each root. A sequence the library's honesty checks reject gives no roots, which this suite scores as every root missed"
            }
            Method::SturmF64(_) => {
                "our `f64` Sturm sequence (remainders normalised, negligible leading terms dropped), bisection isolation, certified-bracket Illinois refinement: a heuristic, which refuses (`RootError::Unresolved`) where its checks find the sequence unreliable; this suite scores a refusal as every root missed, so its *m* counts refusals and wrong answers together"
            }
            Method::Bernstein(_) if n.ends_with("bisect") => {
                "certified: Descartes/Bernstein isolation with rounding-error bounds (exact fallback when a sign is uncertain), bisection refinement"
            }
            Method::Bernstein(_) if n.ends_with("illinois") => {
                "certified: Bernstein isolation, Illinois (regula falsi) refinement"
            }
            Method::Bernstein(_) => {
                "certified, the library default: Bernstein isolation, safeguarded Newton refinement"
            }
            Method::Exact => {
                "exact rational Sturm isolation and exact bisection, rounded to `f64` (certified, slow)"
            }
            Method::Companion => {
                "peer baseline: real eigenvalues of the balanced companion matrix (nalgebra real Schur), eigenvalues with `|Im λ| ≤ tol·max(1, |λ|)` taken as real, tol ="
            }
            Method::Polycool => {
                "peer: polycool 0.4's `roots_between` with the same tolerance (recursion on the derivative's roots; its docs say a double root without a sign change can be missed)"
            }
            Method::Kurbo => {
                "peer: kurbo 0.13's closed forms (`solve_quadratic`, `solve_cubic`, `solve_quartic`), degrees 1–4 only (— elsewhere), no tolerance"
            }
            Method::Roots => {
                "peer: roots 0.0.8, its closed forms to degree 4 and `find_roots_sturm` (with the tolerance as its convergence bound) above"
            }
        };
        let tail = if *m == Method::Companion {
            format!(" {}", sci(COMPANION_IMAG_TOL))
        } else {
            String::new()
        };
        let _ = writeln!(md, "- `{n}`: {what}{tail}.");
    }
    let _ = writeln!(md);

    // Summary.
    let _ = writeln!(md, "## Where each method breaks down\n");
    let _ = writeln!(
        md,
        "First degree (or camera distance) at which a method miscounts (missed or phantom \
         roots) and first at which a found root has relative error above {}; otherwise the \
         worst relative error seen. Bold marks count failures.\n",
        sci(INACCURATE_REL)
    );
    let fams = families_in(rows);
    let mut header: Vec<&str> = vec!["family"];
    header.extend(names.iter().map(String::as_str));
    let summary: Vec<Vec<String>> = fams
        .iter()
        .map(|&f| {
            let fr: Vec<&Row> = rows.iter().filter(|r| r.family == f).collect();
            let mut cells = vec![format!("{} ({})", f.name(), f.description())];
            cells.extend((0..names.len()).map(|mi| summary_cell(&fr, mi)));
            cells
        })
        .collect();
    md.push_str(&table(&header, &summary));
    let _ = writeln!(md);

    // Exact fallbacks of the default certified method.
    let default_mi = Method::STABILITY
        .iter()
        .position(|m| *m == Method::Bernstein(poly::RefineMethod::NewtonBisection))
        .expect("the default method is in the suite");
    let _ = writeln!(
        md,
        "### When the certified `f64` path needs exact arithmetic\n\n\
         `bernstein+*` never returns a wrong count because, when the rounding-error bound \
         cannot certify a sign, it first restarts the undecided piece with a fresh bound and \
         non-dyadic splits, then isolates it in wider arithmetic with rigorous bounds \
         (double-double, then 256–1024-bit floats; `paper-notes/isolation.md`), and only what \
         those still cannot decide is isolated by exact Sturm on that piece (an exact factor \
         `x^k` is divided out first): correct, and slow only there. This happens for \
         multiple roots and clusters closer than the widest format resolves. *fallbacks* \
         counts these exact pieces and the refinements finished in exact arithmetic, so it \
         can exceed the number of cases. Parameters at which `{}` \
         fell back at least once:\n",
        names[default_mi]
    );
    let fb_rows: Vec<Vec<String>> = fams
        .iter()
        .map(|&f| {
            let fr: Vec<&Row> = rows.iter().filter(|r| r.family == f).collect();
            let hit: Vec<&&Row> = fr
                .iter()
                .filter(|r| r.scores[default_mi].fallbacks > 0)
                .collect();
            let (fb, cases) = fr.iter().fold((0, 0), |(a, b), r| {
                (
                    a + r.scores[default_mi].fallbacks,
                    b + r.scores[default_mi].cases,
                )
            });
            vec![
                f.name().to_owned(),
                if hit.is_empty() {
                    "none".to_owned()
                } else {
                    ranges(f, &hit.iter().map(|r| r.param).collect::<Vec<_>>())
                },
                format!("{fb} / {cases}"),
            ]
        })
        .collect();
    md.push_str(&table(
        &["family", "falls back at", "fallbacks / cases"],
        &fb_rows,
    ));
    let _ = writeln!(md);

    let _ = writeln!(
        md,
        "![max relative error vs degree](stability-error.svg)\n\n\
         ![time per solve vs degree](stability-time.svg)\n"
    );

    // Per family.
    let _ = writeln!(
        md,
        "[Reading the results](#reading-the-results) (hand-written, at the end) says why each \
         method breaks where it does.\n"
    );
    let _ = writeln!(md, "## Per family\n");
    let _ = writeln!(
        md,
        "Each cell: count failures (**m**issed, **p**hantom) if any · max relative error · \
         mean time per solve. The collapsed table under each has every number.\n"
    );
    for &f in &fams {
        let fr: Vec<&Row> = rows.iter().filter(|r| r.family == f).collect();
        let _ = writeln!(md, "### {} — {}\n", f.name(), f.description());
        let mut header: Vec<&str> = vec![if f.is_ray() { "camera" } else { "degree" }, "roots"];
        header.extend(names.iter().map(String::as_str));
        let compact: Vec<Vec<String>> = fr
            .iter()
            .map(|r| {
                let mut cells = vec![
                    param_label(r.family, r.param),
                    r.scores[0].true_roots.to_string(),
                ];
                cells.extend(r.scores.iter().map(compact_cell));
                cells
            })
            .collect();
        md.push_str(&table(&header, &compact));
        let _ = writeln!(md, "\n<details><summary>all numbers</summary>\n");
        md.push_str(&table(
            &[
                "param",
                "method",
                "cases",
                "roots",
                "missed",
                "phantom",
                "max abs",
                "median abs",
                "max rel",
                "median rel",
                "time/solve",
                "fallbacks",
            ],
            &full_rows(&fr),
        ));
        let _ = writeln!(md, "\n</details>\n");
    }
    md
}

fn plots(args: &Args, rows: &[Row]) -> Result<()> {
    let names: Vec<String> = Method::STABILITY.iter().map(|m| m.name()).collect();
    let fams = families_in(rows);
    let mut err_panels = Vec::new();
    let mut time_panels = Vec::new();
    for &f in &fams {
        let fr: Vec<&Row> = rows.iter().filter(|r| r.family == f).collect();
        let x_desc = if f.is_ray() {
            "camera distance"
        } else {
            "degree"
        };
        let series = |value: &dyn Fn(&Score) -> f64| -> Vec<Series> {
            names
                .iter()
                .enumerate()
                .map(|(mi, n)| Series {
                    name: n.clone(),
                    points: fr.iter().map(|r| (r.param, value(&r.scores[mi]))).collect(),
                })
                .collect()
        };
        err_panels.push(Panel {
            title: f.name().to_owned(),
            x_desc: x_desc.to_owned(),
            y_desc: "max rel error (10 = miscount)".to_owned(),
            x_log: f.is_ray(),
            y_log: true,
            y_floor: ERROR_FLOOR,
            series: series(&|s: &Score| {
                if s.counts_ok() {
                    max(&s.rel_err)
                } else {
                    COUNT_FAILURE_Y
                }
            }),
        });
        time_panels.push(Panel {
            title: f.name().to_owned(),
            x_desc: x_desc.to_owned(),
            y_desc: "time per solve (ns)".to_owned(),
            x_log: f.is_ray(),
            y_log: true,
            y_floor: 1.0,
            series: series(&|s: &Score| s.mean_nanos()),
        });
    }
    let rows_n = err_panels.len().div_ceil(3) as u32;
    grid_svg(
        &args.out_dir.join("stability-error.svg"),
        &err_panels,
        3,
        (1500, 380 * rows_n),
    )?;
    grid_svg(
        &args.out_dir.join("stability-time.svg"),
        &time_panels,
        3,
        (1500, 380 * rows_n),
    )?;
    Ok(())
}

fn main() -> Result<()> {
    let mut args = Args::parse();
    let mut cmd = "cargo run --release -p toolkit-benches --bin stability".to_owned();
    let raw: Vec<String> = std::env::args().skip(1).collect();
    if !raw.is_empty() {
        cmd.push_str(" -- ");
        cmd.push_str(&raw.join(" "));
    }
    if args.quick {
        args.max_degree = args.max_degree.min(12);
        args.samples = args.samples.min(3);
        args.rays = args.rays.min(8);
        args.budget_ms = args.budget_ms.min(1);
    }
    let budget = Duration::from_millis(args.budget_ms);
    let load = load_average();
    let start = Instant::now();
    let mut rows = Vec::new();
    let mut err = std::io::stderr().lock();
    for f in Family::BY_DEGREE {
        for d in 2..=args.max_degree as usize {
            let samples = if f.is_random() { args.samples } else { 1 };
            let cases = degree_cases(f, d, samples, args.seed);
            if cases.is_empty() {
                continue; // recorded families hold only the degrees the tracer met
            }
            let t = Instant::now();
            let (scores, construction) = run_cases(&cases, budget);
            let _ = writeln!(
                err,
                "{:>18} d={d:<3} {:>6.2} s  {}",
                f.name(),
                t.elapsed().as_secs_f64(),
                scores
                    .iter()
                    .map(compact_cell)
                    .collect::<Vec<_>>()
                    .join(" | ")
            );
            rows.push(Row {
                family: f,
                param: d as f64,
                scores,
                construction,
            });
        }
    }
    for f in Family::RAYS {
        for dist in CAMERA_DISTANCES {
            let cases = ray_cases(f, dist, args.rays, args.seed);
            let t = Instant::now();
            let (scores, construction) = run_cases(&cases, budget);
            let _ = writeln!(
                err,
                "{:>18} D={dist:<6} {:>6.2} s  {}",
                f.name(),
                t.elapsed().as_secs_f64(),
                scores
                    .iter()
                    .map(compact_cell)
                    .collect::<Vec<_>>()
                    .join(" | ")
            );
            rows.push(Row {
                family: f,
                param: dist,
                scores,
                construction,
            });
        }
    }
    let md = markdown(&args, &cmd, &rows, start.elapsed(), load);
    let path = args.out_dir.join("stability.md");
    // Keep the hand-written notes after the generated part.
    let kept = std::fs::read_to_string(&path)
        .ok()
        .and_then(|old| {
            old.split_once(GENERATED_END)
                .map(|(_, rest)| rest.to_owned())
        })
        .unwrap_or_else(|| "\n".to_owned());
    write_atomically(&path, &format!("{md}{GENERATED_END}{kept}"))?;
    plots(&args, &rows)?;
    let mut out = std::io::stdout().lock();
    writeln!(out, "wrote {}", path.display())?;
    Ok(())
}

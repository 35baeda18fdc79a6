//! Run time against error at the solver level: every refinement method and tolerance
//! 1e-2 … 1e-14 on corpora of real ray polynomials (torus and Barth's sextic, restricted at
//! the bounding-volume entry as `render` does; the teapot's recorded ray/patch resultants),
//! scored against the certified smallest root.
//!
//! Then the image level: per-pixel hits and shadows of torus.scene (also from 1000× farther)
//! and barth.scene for each solver setting against an exact reference
//! (`toolkit_benches::image`).
//!
//! `cargo run --release -p toolkit-benches --bin speed` writes `docs/speed.md` (the generated
//! sections; hand-written text after them is kept) and `docs/speed-pareto.svg`.

use std::fmt::Write as _;
use std::io::Write as _;
use std::path::PathBuf;
use std::time::{Duration, Instant};

use anyhow::Result;
use clap::Parser;
use poly::{Rat, RefineMethod, RootStats, rat_from_f64};
use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;
use render::scene::{CameraSpec, LookAtCamera};
use toolkit_benches::families::teapot_eliminant_queries;
use toolkit_benches::image::{
    ImageScene, Origin, SHADOW_EPS_REL, SHADOW_EPS_TOLS, Setting, Shape, diff, trace_image,
};
use toolkit_benches::methods::{Method, REFINE_METHODS};
use toolkit_benches::plot::{Panel, Series, grid_svg};
use toolkit_benches::rays::{self, RayPoly, SCENE_TORUS};
use toolkit_benches::report::{git_commit, sci, table, write_atomically};
use toolkit_benches::score::{max, median};
use toolkit_benches::timing::{human_nanos, load_average, load_note, machine};
use toolkit_benches::truth::{abs_error, exact_roots};

/// The tolerances swept: `1e-2, 1e-3, …, 1e-14` (absolute, in `t`; the rays have unit
/// direction so `t` is a distance, and the objects have size ≈ 6).
const TOLERANCES: [f64; 13] = [
    1e-2, 1e-3, 1e-4, 1e-5, 1e-6, 1e-7, 1e-8, 1e-9, 1e-10, 1e-11, 1e-12, 1e-13, 1e-14,
];

/// Tolerances at which the (slow) exact method is timed.
const EXACT_TOLERANCES: [f64; 3] = [1e-2, 1e-8, 1e-14];

/// Measure time per smallest-root query against achieved error, per method and tolerance.
#[derive(Debug, Parser)]
#[command(name = "speed", about)]
struct Args {
    /// Rays per corpus.
    #[arg(long, default_value_t = 400)]
    rays: usize,
    /// Minimum wall time per (corpus, method, tolerance), in milliseconds.
    #[arg(long, default_value_t = 200)]
    budget_ms: u64,
    /// Smaller run: 100 rays, 30 ms budget.
    #[arg(long)]
    quick: bool,
    /// Seed of the ray directions.
    #[arg(long, default_value_t = 6)]
    seed: u64,
    /// Side of the images of the image-level comparison (0 skips it).
    #[arg(long, default_value_t = 64)]
    image_size: u32,
    /// Directory for speed.md and speed-pareto.svg.
    #[arg(long, default_value = concat!(env!("CARGO_MANIFEST_DIR"), "/../docs"))]
    out_dir: PathBuf,
}

/// A corpus: ray polynomials with their certified smallest roots.
struct Corpus {
    name: &'static str,
    what: &'static str,
    rays: Vec<RayPoly>,
    truth: Vec<Option<Rat>>,
}

fn corpus(name: &'static str, what: &'static str, rays: Vec<RayPoly>) -> Corpus {
    let truth = rays
        .iter()
        .map(|r| {
            let q = r.poly.to_rat().expect("finite");
            let (lo, hi) = (
                rat_from_f64(r.lo).expect("finite"),
                rat_from_f64(r.hi).expect("finite"),
            );
            exact_roots(&q, &lo, &hi).roots.into_iter().next()
        })
        .collect();
    Corpus {
        name,
        what,
        rays,
        truth,
    }
}

/// One measured point.
struct Point {
    method: Method,
    tol: f64,
    ns: f64,
    wrong: usize,
    max_err: f64,
    med_err: f64,
    over_tol: usize,
    fallbacks: u64,
}

fn measure(c: &Corpus, method: Method, tol: f64, budget: Duration) -> Point {
    let mut stats = RootStats::default();
    let mut errs = Vec::new();
    let (mut wrong, mut over_tol) = (0, 0);
    for (r, t) in c.rays.iter().zip(&c.truth) {
        let got = method.smallest_root(&r.poly, r.lo, r.hi, tol, &mut stats);
        match (got, t) {
            (None, None) => {}
            (Some(x), Some(t)) => {
                let e = abs_error(x, t);
                // A different root (not the smallest) is a wrong answer, not a large error:
                // it is farther than any tolerance swept.
                if e > 1e-1 {
                    wrong += 1;
                } else {
                    if e > tol.max(x.abs() * f64::EPSILON) {
                        over_tol += 1;
                    }
                    errs.push(e);
                }
            }
            _ => wrong += 1,
        }
    }
    let start = Instant::now();
    let mut queries = 0u64;
    while start.elapsed() < budget || queries == 0 {
        let mut s = RootStats::default();
        for r in &c.rays {
            std::hint::black_box(method.smallest_root(&r.poly, r.lo, r.hi, tol, &mut s));
        }
        queries += c.rays.len() as u64;
    }
    Point {
        method,
        tol,
        ns: start.elapsed().as_nanos() as f64 / queries as f64,
        wrong,
        max_err: max(&errs),
        med_err: median(&errs),
        over_tol,
        fallbacks: stats.exact_fallbacks + stats.refine_fallbacks,
    }
}

fn plan() -> Vec<(Method, Vec<f64>)> {
    let mut v: Vec<(Method, Vec<f64>)> = Vec::new();
    v.push((Method::Stam, TOLERANCES.to_vec()));
    v.push((
        Method::SturmF64(RefineMethod::Illinois),
        TOLERANCES.to_vec(),
    ));
    for r in REFINE_METHODS {
        v.push((Method::Bernstein(r), TOLERANCES.to_vec()));
    }
    v.push((Method::Exact, EXACT_TOLERANCES.to_vec()));
    v.push((Method::Companion, vec![f64::NAN]));
    // The peers: polycool takes a tolerance; kurbo's and roots' closed forms have none
    // (roots' Sturm solver above degree 4 runs to its convergence bound ε).
    v.push((Method::Polycool, TOLERANCES.to_vec()));
    v.push((Method::Kurbo, vec![f64::NAN]));
    v.push((Method::Roots, vec![f64::NAN]));
    v
}

/// Marks the end of the generated part of `docs/speed.md`; what follows is kept on rewrite.
const GENERATED_END: &str = "<!-- generated above; hand-written below is kept -->";

/// The camera and first light of a scene file (look-at cameras only).
fn scene_view(file: &str) -> Result<(LookAtCamera, glam::DVec3)> {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../scenes")
        .join(file);
    let scene = render::scene::load(&path)?;
    let CameraSpec::LookAt(cam) = scene.camera.clone() else {
        anyhow::bail!("{file}: expected an Eye/LookAt camera");
    };
    let light = scene
        .lights
        .first()
        .ok_or_else(|| anyhow::anyhow!("{file}: no light"))?
        .source;
    Ok((cam, light))
}

/// The image-level comparison (see `toolkit_benches::image`).
fn image_section(size: u32, err: &mut impl std::io::Write) -> Result<String> {
    let (tcam, tlight) = scene_view("torus.scene")?;
    let (bcam, blight) = scene_view("barth.scene")?;
    let torus = ImageScene {
        name: "torus.scene".to_owned(),
        shape: Shape::Torus(SCENE_TORUS),
        camera: tcam,
        light: tlight,
    };
    let far = torus.farther(1000.0, "torus.scene seen from 1000× farther (D ≈ 9 430)");
    let barth = ImageScene {
        name: "barth.scene".to_owned(),
        shape: Shape::Algebraic(rays::barth_sextic(), rays::BARTH_BOX),
        camera: bcam,
        light: blight,
    };
    let mut md = String::new();
    let _ = writeln!(
        md,
        "## Image level: what the solver changes in a picture\n\n\
         `render --isolation/--refine` renders whole images with any solver (its \
         `--isolation exact` solves the `f64`-restricted polynomial exactly); this table needs \
         a stricter reference and per-pixel scoring, so it traces, for every pixel of a \
         {size}×{size} image, the two queries that decide what the pixel shows — the primary \
         hit and the shadow ray to the first light — with `render`'s camera and the same \
         restrictions and bounding volumes (`toolkit_benches::image`), swapping only the \
         solver. The reference is **exact**: each ray's restriction computed in rationals from \
         the `f64` ray data, smallest root by exact Sturm to one `f64` spacing. *hit/miss*: \
         pixels hit in one image and missed in the other; *shadow*: pixels hit in both whose \
         shadow state differs; *speckles*: differing pixels none of whose 8 neighbours \
         differ; *max depth err*: largest `|t − t_ref|` where both hit. `tol` is absolute in \
         `t`; the renderer's is `ROOT_X_TOL_REL · size` = {} of the bounding-box diagonal. \
         *eye* rows restrict the primary ray at the eye (the naive tracer), *entry* rows at the \
         bounding-volume entry (`render`). Shadow rays start `max({} · size, {}·tol)` past \
         the hit point (the reference: {1} · size). Single thread; times include restriction and both queries.\n",
        sci(render::surface::ROOT_X_TOL_REL),
        sci(SHADOW_EPS_REL),
        SHADOW_EPS_TOLS
    );
    for scene in [&torus, &far, &barth] {
        let size_obj = scene.shape.size();
        let renderer_tol = render::surface::ROOT_X_TOL_REL * size_obj;
        let mut settings: Vec<(String, Setting)> = Vec::new();
        let entry = |method, x_tol| Setting {
            method,
            x_tol,
            origin: Origin::Entry,
        };
        for m in [
            Method::Stam,
            Method::SturmF64(RefineMethod::Illinois),
            Method::Bernstein(RefineMethod::Bisection),
            Method::Bernstein(RefineMethod::Illinois),
            Method::Bernstein(RefineMethod::NewtonBisection),
            Method::Exact,
            Method::Companion,
            Method::Polycool,
        ] {
            settings.push(("entry".to_owned(), entry(m, renderer_tol)));
        }
        for rel in [1e-3, 1e-6] {
            settings.push((
                "entry".to_owned(),
                entry(Method::Bernstein(RefineMethod::Illinois), rel * size_obj),
            ));
        }
        for m in [
            Method::Stam,
            Method::SturmF64(RefineMethod::Illinois),
            Method::Bernstein(RefineMethod::Illinois),
            Method::Companion,
            Method::Polycool,
        ] {
            settings.push((
                "eye".to_owned(),
                Setting {
                    method: m,
                    x_tol: renderer_tol,
                    origin: Origin::Eye,
                },
            ));
        }
        let (reference, ref_time) = trace_image(scene, size, None);
        let hits = reference.iter().filter(|p| p.depth.is_finite()).count();
        let _ = writeln!(
            md,
            "### {}\n\nReference: {hits} of {} pixels hit; exact reference traced in {:.2} s.\n",
            scene.name,
            size * size,
            ref_time
        );
        let mut rows = Vec::new();
        for (origin, s) in &settings {
            let (img, secs) = trace_image(scene, size, Some(s));
            let d = diff(&img, &reference, size);
            let _ = writeln!(
                err,
                "image {:>40} {:>20} {origin:>5} tol {:>7} {:>8.3} s  hit/miss {} shadow {} speckles {} depth {}",
                scene.name,
                s.method.name(),
                sci(s.x_tol),
                secs,
                d.hit_miss,
                d.shadow,
                d.speckles,
                sci(d.max_depth_err)
            );
            rows.push(vec![
                s.method.name(),
                origin.clone(),
                if s.method == Method::Companion {
                    "—".to_owned()
                } else {
                    sci(s.x_tol)
                },
                format!("{:.3} s", secs),
                format!(
                    "{} ({:.2} %)",
                    d.hit_miss,
                    100.0 * d.hit_miss as f64 / f64::from(size * size)
                ),
                d.shadow.to_string(),
                sci(d.max_depth_err),
                d.speckles.to_string(),
            ]);
        }
        md.push_str(&table(
            &[
                "method",
                "restricted at",
                "tol",
                "time",
                "hit/miss",
                "shadow",
                "max depth err",
                "speckles",
            ],
            &rows,
        ));
        let _ = writeln!(md);
    }
    Ok(md)
}

fn main() -> Result<()> {
    let mut args = Args::parse();
    if args.quick {
        args.rays = args.rays.min(100);
        args.budget_ms = args.budget_ms.min(30);
        args.image_size = args.image_size.min(24);
    }
    let mut cmd = "cargo run --release -p toolkit-benches --bin speed".to_owned();
    let raw: Vec<String> = std::env::args().skip(1).collect();
    if !raw.is_empty() {
        cmd.push_str(" -- ");
        cmd.push_str(&raw.join(" "));
    }
    let load = load_average();
    let start = Instant::now();
    let mut rng = ChaCha8Rng::seed_from_u64(args.seed);
    let torus_dist = glam::DVec3::new(0.0, -8.0, 5.0).length();
    let barth_dist = glam::DVec3::new(5.0, -9.0, 6.0).length();
    let corpora = [
        corpus(
            "torus",
            "torus.scene's torus (R = 2, r = 1) from its camera, restricted at the bounding-sphere entry (quartics)",
            rays::torus_rays(SCENE_TORUS, torus_dist, args.rays, true, &mut rng),
        ),
        corpus(
            "barth",
            "barth.scene's sextic from its camera, restricted at the bounding-box entry (sextics)",
            rays::barth_rays(&rays::barth_sextic(), barth_dist, args.rays, true, &mut rng),
        ),
        corpus(
            "teapot",
            "the teapot's Kajiya resultants Res_v(F1, F2)(u), degree 8–17, recorded by the tracer (crates/poly/tests/data/teapot_eliminants.txt), smallest root in the piece's u-range",
            teapot_eliminant_queries()
                .into_iter()
                .take(args.rays)
                .map(|(poly, lo, hi)| RayPoly {
                    poly,
                    lo,
                    hi,
                    exact: None,
                })
                .collect(),
        ),
    ];
    let budget = Duration::from_millis(args.budget_ms);
    let mut err = std::io::stderr().lock();
    let mut results: Vec<Vec<Point>> = Vec::new();
    for c in &corpora {
        let mut pts = Vec::new();
        for (m, tols) in plan() {
            if !c.rays.iter().all(|r| m.supports(r.poly.degree())) {
                continue;
            }
            for tol in tols {
                let p = measure(c, m, if tol.is_nan() { 0.0 } else { tol }, budget);
                let _ = writeln!(
                    err,
                    "{:>6} {:>20} tol {:>7}  {:>10}/query  max err {:>8}  wrong {}",
                    c.name,
                    m.name(),
                    sci(tol),
                    human_nanos(p.ns),
                    sci(p.max_err),
                    p.wrong
                );
                pts.push(Point { tol, ..p });
            }
        }
        results.push(pts);
    }

    // Markdown.
    let mut md = String::new();
    let _ = writeln!(md, "# Run time against error\n");
    let _ = writeln!(
        md,
        "Solver section generated by `{cmd}` (commit `{}`, {:.0} s) on a **{}** machine \
         ({}): absolute times are noisy; ratios within one table were measured in the same \
         run. Single thread.\n",
        git_commit(),
        start.elapsed().as_secs_f64(),
        machine(),
        load_note(load)
    );
    let _ = writeln!(
        md,
        "## Solver level: smallest root of a ray polynomial\n\n\
         Each corpus is {} seeded rays; each query is the tracer's: the smallest root in \
         `(0, chord]` of `t ↦ F(o + t·d)` with `o` at the bounding-volume entry and `|d| = 1`, \
         asked with absolute tolerance `tol`. The achieved error is `|returned − r|` against \
         the certified smallest root `r` of the stored polynomial (exact rational Sturm, \
         width 2^-80). *wrong*: a root reported where there is none, none where there is \
         one, or a different root (error > 0.1). *> tol*: answers farther than `max(tol, \
         ε|x|)` from the truth. *fallbacks*: queries `poly` finished in exact arithmetic. \
         Time per query is the mean over repeated passes of the corpus (≥ {} ms per row). \
         `companion-eig` has no tolerance (eigenvalues to working precision), nor have the \
         closed forms of the peers `kurbo-0.13` (quartics only) and `roots-0.0.8` (its Sturm \
         solver, above degree 4, runs to ε); `polycool-0.4` takes the tolerance. \
         Plot: [speed-pareto.svg](speed-pareto.svg) (error against ns/query, one line per \
         method through its tolerances).\n",
        args.rays, args.budget_ms
    );
    for (c, pts) in corpora.iter().zip(&results) {
        let hits = c.truth.iter().filter(|t| t.is_some()).count();
        let _ = writeln!(
            md,
            "### {} — {}\n\n{} rays, {} with a root.\n",
            c.name,
            c.what,
            c.rays.len(),
            hits
        );
        let rows: Vec<Vec<String>> = pts
            .iter()
            .map(|p| {
                vec![
                    p.method.name(),
                    if p.tol.is_nan() {
                        "—".to_owned()
                    } else {
                        sci(p.tol)
                    },
                    human_nanos(p.ns),
                    sci(p.max_err),
                    sci(p.med_err),
                    if p.tol.is_nan() {
                        "—".to_owned()
                    } else {
                        p.over_tol.to_string()
                    },
                    p.wrong.to_string(),
                    p.fallbacks.to_string(),
                ]
            })
            .collect();
        md.push_str(&table(
            &[
                "method",
                "tol",
                "time/query",
                "max err",
                "median err",
                "> tol",
                "wrong",
                "fallbacks",
            ],
            &rows,
        ));
        let _ = writeln!(md);
    }
    let _ = writeln!(md, "![error against time per query](speed-pareto.svg)\n");
    if args.image_size > 0 {
        md.push_str(&image_section(args.image_size, &mut err)?);
    }
    let _ = writeln!(md, "{GENERATED_END}");
    let path = args.out_dir.join("speed.md");
    // Keep the hand-written sections after the generated ones.
    let kept = std::fs::read_to_string(&path)
        .ok()
        .and_then(|old| {
            old.split_once(GENERATED_END)
                .map(|(_, rest)| rest.to_owned())
        })
        .unwrap_or_else(|| "\n".to_owned());
    write_atomically(&path, &format!("{md}{kept}"))?;

    // Pareto plot: one panel per corpus.
    let panels: Vec<Panel> = corpora
        .iter()
        .zip(&results)
        .map(|(c, pts)| {
            let mut series: Vec<Series> = Vec::new();
            for p in pts {
                let name = p.method.name();
                let y = if p.wrong > 0 { 1.0 } else { p.max_err };
                match series.iter_mut().find(|s| s.name == name) {
                    Some(s) => s.points.push((p.ns, y)),
                    None => series.push(Series {
                        name,
                        points: vec![(p.ns, y)],
                    }),
                }
            }
            Panel {
                title: format!("{} rays: max error vs time (1 = wrong answer)", c.name),
                x_desc: "ns per smallest-root query".to_owned(),
                y_desc: "max |t − t_exact|".to_owned(),
                x_log: true,
                y_log: true,
                y_floor: 1e-17,
                series,
            }
        })
        .collect();
    grid_svg(
        &args.out_dir.join("speed-pareto.svg"),
        &panels,
        3,
        (2100, 560),
    )?;
    let mut out = std::io::stdout().lock();
    writeln!(out, "wrote {}", path.display())?;
    Ok(())
}

//! The ray tracer's query — the smallest root of a ray polynomial — for a torus quartic and a
//! Barth sextic: `f64` (certified default and each refinement, tolerance sweep) against exact
//! rationals, side by side.
#![allow(missing_docs, reason = "criterion emits undocumented functions")]

use std::hint::black_box;

use criterion::{BenchmarkId, Criterion, criterion_group, criterion_main};
use poly::{IsolationMethod, Poly, RefineMethod, RootOptions, RootStats, rat_from_f64};
use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;
use toolkit_benches::rays::{self, RayPoly, SCENE_TORUS};

/// A ray that hits: the first ray of a seeded batch whose polynomial has a root in range.
fn hitting_ray(batch: Vec<RayPoly>) -> RayPoly {
    batch
        .into_iter()
        .find(|r| r.poly.smallest_root(r.lo, r.hi, 1e-12).is_some())
        .expect("some ray of the batch hits")
}

fn smallest_root(c: &mut Criterion) {
    let mut rng = ChaCha8Rng::seed_from_u64(6);
    let quartic = hitting_ray(rays::torus_rays(SCENE_TORUS, 9.43, 16, true, &mut rng));
    let sextic = hitting_ray(rays::barth_rays(
        &rays::barth_sextic(),
        11.9,
        16,
        true,
        &mut rng,
    ));
    for (name, ray) in [("torus_quartic", &quartic), ("barth_sextic", &sextic)] {
        let mut g = c.benchmark_group(format!("smallest_root_{name}"));
        // f64 vs Rat at the renderer's accuracy.
        g.bench_function("f64_default_1e-10", |b| {
            b.iter(|| black_box(&ray.poly).smallest_root(ray.lo, ray.hi, 1e-10))
        });
        let q = ray.poly.to_rat().expect("finite");
        let (lo, hi) = (
            rat_from_f64(ray.lo).expect("finite"),
            rat_from_f64(ray.hi).expect("finite"),
        );
        g.bench_function("rat_exact_1e-10", |b| {
            b.iter(|| black_box(&q).smallest_root(&lo, &hi, 1e-10))
        });
        g.bench_function("f64_stam_1988_1e-10", |b| {
            let o = RootOptions {
                isolation: IsolationMethod::StamSturm,
                ..RootOptions::new(1e-10)
            };
            b.iter(|| {
                let mut s = RootStats::default();
                black_box(&ray.poly).smallest_root_with(ray.lo, ray.hi, &o, &mut s)
            })
        });
        // Tolerance sweep per refinement method: the cost of accuracy.
        for (rname, refine) in [
            ("bisection", RefineMethod::Bisection),
            ("illinois", RefineMethod::Illinois),
            ("newton", RefineMethod::NewtonBisection),
        ] {
            for tol in [1e-2, 1e-6, 1e-10, 1e-14] {
                let o = RootOptions {
                    refine,
                    ..RootOptions::new(tol)
                };
                g.bench_with_input(BenchmarkId::new(rname, tol), &o, |b, o| {
                    b.iter(|| {
                        let mut s = RootStats::default();
                        black_box(&ray.poly).smallest_root_with(ray.lo, ray.hi, o, &mut s)
                    })
                });
            }
        }
        g.finish();
    }
}

/// The Bézier-patch tracer's root queries: the 374 recorded teapot queries of
/// `crates/poly/tests/data/teapot_eliminants.txt` (resultant eliminants of degree 8–17, their
/// derivatives, cubics in `v`), each answered as the solver does (`real_roots`), and as a
/// smallest-root query; one iteration is the whole set.
fn teapot_eliminants(c: &mut Criterion) {
    let text = include_str!("../../crates/poly/tests/data/teapot_eliminants.txt");
    let queries: Vec<(Poly<f64>, f64, f64, f64)> = text
        .lines()
        .filter(|l| !l.starts_with('#') && !l.trim().is_empty())
        .map(|l| {
            let f: Vec<f64> = l
                .split_whitespace()
                .skip(1)
                .map(|s| s.parse().expect("a number"))
                .collect();
            (Poly::new(f[4..].to_vec()), f[0], f[1], f[2])
        })
        .collect();
    let mut g = c.benchmark_group("teapot_eliminants_374");
    g.bench_function("real_roots", |b| {
        b.iter(|| {
            let mut s = RootStats::default();
            for (p, lo, hi, x_tol) in &queries {
                let o = RootOptions::new(*x_tol);
                black_box(black_box(p).real_roots_with(*lo, *hi, &o, &mut s).ok());
            }
            s
        })
    });
    g.bench_function("smallest_root", |b| {
        b.iter(|| {
            let mut s = RootStats::default();
            for (p, lo, hi, x_tol) in &queries {
                let o = RootOptions::new(*x_tol);
                black_box(black_box(p).smallest_root_with(*lo, *hi, &o, &mut s));
            }
            s
        })
    });
    g.finish();
}

criterion_group!(benches, smallest_root, teapot_eliminants);
criterion_main!(benches);

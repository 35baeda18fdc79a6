//! The ray tracer's query — the smallest root of a ray polynomial — for a torus quartic and a
//! Barth sextic: `f64` (certified default and each refinement, tolerance sweep) against exact
//! rationals, side by side.
#![allow(missing_docs, reason = "criterion emits undocumented functions")]

use std::hint::black_box;

use criterion::{BenchmarkId, Criterion, criterion_group, criterion_main};
use poly::{IsolationMethod, RefineMethod, RootOptions, RootStats, rat_from_f64};
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

criterion_group!(benches, smallest_root);
criterion_main!(benches);

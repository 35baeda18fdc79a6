//! Restriction of `F(x, y, z)` to a ray, `t ↦ F(o + t·d)` (Stam eq. 3.7–3.8): the torus in
//! closed form and through the generic `Poly3` path, Barth's sextic, and the exact rational
//! restriction used as the construction-error oracle.
#![allow(missing_docs, reason = "criterion emits undocumented functions")]

use std::hint::black_box;

use criterion::{Criterion, criterion_group, criterion_main};
use glam::DVec3;
use render::{Poly3, RestrictScratch};
use toolkit_benches::rays::{
    SCENE_TORUS, barth_sextic, poly3_restriction_exact, torus_restriction, torus_restriction_exact,
};

/// The torus of `SCENE_TORUS` as a trivariate polynomial, `(|p|² + R² − r²)² − 4R²(x² + y²)`.
fn torus_poly3() -> Poly3 {
    let (x, y, z) = (Poly3::x(), Poly3::y(), Poly3::z());
    let radial = &(&x * &x) + &(&y * &y);
    let k = SCENE_TORUS.major * SCENE_TORUS.major - SCENE_TORUS.minor * SCENE_TORUS.minor;
    let s = &(&radial + &(&z * &z)) + &Poly3::constant(k);
    &(&s * &s) - &(&radial * (4.0 * SCENE_TORUS.major * SCENE_TORUS.major))
}

fn restrict(c: &mut Criterion) {
    let o = DVec3::new(0.3, -2.9, 0.8);
    let d = DVec3::new(0.05, 0.9, -0.43).normalize();
    let torus = torus_poly3();
    let barth = barth_sextic();
    let mut g = c.benchmark_group("restrict_to_ray");
    g.bench_function("torus_closed_form_f64", |b| {
        b.iter(|| torus_restriction(SCENE_TORUS, black_box(o), black_box(d)))
    });
    let mut scratch = RestrictScratch::default();
    let mut out = Vec::new();
    g.bench_function("torus_poly3_f64", |b| {
        b.iter(|| torus.restrict_into(black_box(o), black_box(d), &mut scratch, &mut out))
    });
    g.bench_function("barth_poly3_f64", |b| {
        b.iter(|| barth.restrict_into(black_box(o), black_box(d), &mut scratch, &mut out))
    });
    g.bench_function("torus_exact_rat", |b| {
        b.iter(|| torus_restriction_exact(SCENE_TORUS, black_box(o), black_box(d)))
    });
    g.bench_function("barth_exact_rat", |b| {
        b.iter(|| poly3_restriction_exact(&barth, black_box(o), black_box(d)))
    });
    g.finish();
}

criterion_group!(benches, restrict);
criterion_main!(benches);

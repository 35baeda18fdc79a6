//! Sign-variation counts: `σ(x)` of a Sturm sequence (Stam eq. 3.21) in `f64` and in exact
//! rationals, and Descartes' coefficient sign variations, by degree.
#![allow(missing_docs, reason = "criterion emits undocumented functions")]

use std::hint::black_box;

use criterion::{BenchmarkId, Criterion, criterion_group, criterion_main};
use poly::testutil::{planted, rat};
use poly::{Poly, Rat, StamSturm, rat_from_f64};

fn planted_f64(d: i64) -> Poly<f64> {
    let roots: Vec<Rat> = (1..=d).map(|k| rat(3 * k - 1, 3 * (d + 1))).collect();
    planted(&roots).to_f64()
}

fn sign_variations(c: &mut Criterion) {
    let mut g = c.benchmark_group("sign_variations");
    // An irrational-looking point inside (0, 1), between roots.
    let x = 0.618_033_988_749_894_9;
    let xr = rat_from_f64(x).expect("finite");
    for d in [4i64, 6, 10, 20] {
        let p = planted_f64(d);
        let f = p.sturm().expect("non-zero");
        let stam = StamSturm::new(&p).expect("non-constant");
        let q = p.to_rat().expect("finite").sturm().expect("non-zero");
        g.bench_with_input(BenchmarkId::new("sturm_f64", d), &x, |b, &x| {
            b.iter(|| f.sign_changes_at(black_box(x)))
        });
        g.bench_with_input(BenchmarkId::new("sturm_stam_1988", d), &x, |b, &x| {
            b.iter(|| stam.sign_changes_at(black_box(x)))
        });
        g.bench_with_input(BenchmarkId::new("sturm_rat", d), &xr, |b, xr| {
            b.iter(|| q.sign_changes_at(black_box(xr)))
        });
        g.bench_with_input(BenchmarkId::new("descartes_coeffs_f64", d), &p, |b, p| {
            b.iter(|| black_box(p).sign_variations())
        });
    }
    g.finish();
}

criterion_group!(benches, sign_variations);
criterion_main!(benches);

//! Sturm sequence construction (Stam §3.5.1, eq. 3.17–3.20): our normalised `f64` sequence,
//! Stam's 1988 recurrence, and the exact rational sequence, side by side by degree.
#![allow(missing_docs, reason = "criterion emits undocumented functions")]

use std::hint::black_box;

use criterion::{BenchmarkId, Criterion, criterion_group, criterion_main};
use poly::testutil::{planted, rat};
use poly::{Poly, Rat, StamSturm};

/// Planted roots `k/(d+1)` plus a shift, rounded to `f64`: `d` simple roots in `(0, 1)`.
fn planted_f64(d: i64) -> Poly<f64> {
    let roots: Vec<Rat> = (1..=d).map(|k| rat(3 * k - 1, 3 * (d + 1))).collect();
    planted(&roots).to_f64()
}

fn sturm_construction(c: &mut Criterion) {
    let mut g = c.benchmark_group("sturm_construction");
    for d in [4i64, 6, 10, 20] {
        let p = planted_f64(d);
        let q = p.to_rat().expect("finite");
        g.bench_with_input(BenchmarkId::new("f64_normalised", d), &p, |b, p| {
            b.iter(|| black_box(p).sturm())
        });
        g.bench_with_input(BenchmarkId::new("f64_stam_1988", d), &p, |b, p| {
            b.iter(|| StamSturm::new(black_box(p)))
        });
        g.bench_with_input(BenchmarkId::new("rat_exact", d), &q, |b, q| {
            b.iter(|| black_box(q).sturm())
        });
    }
    g.finish();
}

criterion_group!(benches, sturm_construction);
criterion_main!(benches);

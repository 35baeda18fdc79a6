//! One full primary ray of `scenes/torus.scene` through `render`'s public API: camera ray,
//! bounding tests, restriction, certified smallest root, shading with a shadow ray.
#![allow(missing_docs, reason = "criterion emits undocumented functions")]

use std::hint::black_box;
use std::path::Path;

use criterion::{Criterion, criterion_group, criterion_main};
use render::whitted::trace_primary;
use render::{Camera, PreparedScene, Workspace};

fn torus_ray(c: &mut Criterion) {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("../scenes/torus.scene");
    let scene = render::scene::load(&path).expect("scenes/torus.scene loads");
    let prepared = PreparedScene::new(&scene).expect("valid scene");
    let (w, h) = (840, 840);
    let camera = Camera::new(&scene.camera, w, h);
    let mut ws = Workspace::new();
    let mut g = c.benchmark_group("torus_primary_ray");
    // A pixel on the torus (lit, casts a shadow ray) and one through the hole (bounding
    // sphere passed, no root).
    for (name, x, y, hits) in [("hit", 420.5, 300.5, true), ("hole", 420.5, 420.5, false)] {
        let ray = camera.ray(x, y);
        let depth = trace_primary(&prepared, &ray, &mut ws).depth;
        assert_eq!(depth.is_finite(), hits, "pixel ({x}, {y}) depth {depth}");
        g.bench_function(name, |b| {
            b.iter(|| trace_primary(&prepared, black_box(&ray), &mut ws))
        });
    }
    g.finish();
}

criterion_group!(benches, torus_ray);
criterion_main!(benches);

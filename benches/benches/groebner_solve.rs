//! `groebner::solve` on the ray/piece systems of the teapot (the `tests/bezier_teapot.rs` view
//! at 32×32, 16×16 pieces per patch, every piece whose box the ray crosses, no hull test), per
//! method; the tracer's per-ray call `solve_ray_patch` in a reused workspace (Stam, Bézout);
//! and the two resultant determinants alone. Times are per system (throughput in
//! elements). See `paper-notes/groebner.md` §5 and `paper-notes/resultant.md`.
#![allow(missing_docs, reason = "criterion emits undocumented functions")]

use std::hint::black_box;
use std::path::Path;

use criterion::{Criterion, Throughput, criterion_group, criterion_main};
use glam::DVec3;
use groebner::{
    Method, RayPatchSystem, SolveOptions, SolveWorkspace, bezout_resultant_v, ray_patch_system,
    solve, solve_ray_patch, sylvester_resultant_v,
};
use render::Camera;
use render::scene::{CameraSpec, LookAtCamera, parse_bpt};
use render::surface::BezierPatch;

/// Per piece: power-basis points about the centre of its box, the box, the centre (as the
/// tracer builds them, `bezier_mesh.rs`).
fn pieces(k: usize) -> Vec<(Vec<[f64; 3]>, [DVec3; 2], DVec3)> {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("../scenes/teapot.bpt");
    let text = std::fs::read_to_string(path).expect("scenes/teapot.bpt is readable");
    let patches = parse_bpt(&text).expect("teapot.bpt parses");
    let mut out = Vec::new();
    let step = 1.0 / k as f64;
    for net in &patches {
        let patch = BezierPatch::new(net);
        for a in 0..k {
            for b in 0..k {
                let u = [a as f64 * step, ((a + 1) as f64 * step).min(1.0)];
                let v = [b as f64 * step, ((b + 1) as f64 * step).min(1.0)];
                let piece = patch.sub_patch(u, v);
                let bounds = piece.bounds();
                let centre = (bounds.min + bounds.max) * 0.5;
                let mut power: Vec<[f64; 3]> =
                    piece.power_coeffs().iter().map(|c| c.to_array()).collect();
                for (axis, c) in power[0].iter_mut().enumerate() {
                    *c -= centre[axis];
                }
                out.push((power, [bounds.min, bounds.max], centre));
            }
        }
    }
    out
}

/// One ray/piece pair: the piece's power-basis points, the ray origin (about the piece's
/// centre, at the box entry) and direction.
type RayPiece = (Vec<[f64; 3]>, [f64; 3], [f64; 3]);

/// Every primary ray of a `size`² view against every crossed piece box.
fn teapot_ray_pieces(size: u32) -> Vec<RayPiece> {
    let spec = CameraSpec::LookAt(LookAtCamera {
        eye: DVec3::new(5.5, -8.0, 6.0),
        look_at: DVec3::new(0.45, 0.0, 1.35),
        up: DVec3::Z,
        view_field_deg: 34.0,
    });
    let cam = Camera::new(&spec, size, size);
    let pieces = pieces(16);
    let mut out = Vec::new();
    for y in 0..size {
        for x in 0..size {
            let ray = cam.ray(f64::from(x) + 0.5, f64::from(y) + 0.5);
            for (power, [lo, hi], centre) in &pieces {
                // Slab test against the (unpadded) box.
                let (mut t0, mut t1) = (0.0f64, f64::INFINITY);
                for k in 0..3 {
                    let inv = 1.0 / ray.dir[k];
                    let (mut n, mut f) =
                        ((lo[k] - ray.origin[k]) * inv, (hi[k] - ray.origin[k]) * inv);
                    if n > f {
                        std::mem::swap(&mut n, &mut f);
                    }
                    t0 = t0.max(n);
                    t1 = t1.min(f);
                }
                if t0 > t1 {
                    continue;
                }
                let o = ray.at(t0) - *centre;
                out.push((power.clone(), o.to_array(), ray.dir.to_array()));
            }
        }
    }
    out
}

fn groebner_solve(c: &mut Criterion) {
    let pairs = teapot_ray_pieces(32);
    let systems: Vec<RayPatchSystem<f64>> = pairs
        .iter()
        .filter_map(|(power, o, d)| ray_patch_system(power, 4, 4, o, d).ok())
        .collect();
    let mut g = c.benchmark_group("teapot_ray_piece_systems");
    g.throughput(Throughput::Elements(systems.len() as u64));
    g.sample_size(10);
    for method in [
        Method::BezoutResultant,
        Method::Resultant,
        Method::Stam,
        Method::Buchberger,
    ] {
        let opts = SolveOptions {
            method,
            ..SolveOptions::default()
        };
        g.bench_function(format!("solve_{method:?}"), |b| {
            b.iter(|| {
                systems
                    .iter()
                    .map(|s| {
                        solve(black_box(&s.f1), black_box(&s.f2), &opts)
                            .map_or(0, |x| x.roots.len())
                    })
                    .sum::<usize>()
            })
        });
    }
    // The tracer's per-ray call: the system built and solved in a reused workspace (no
    // allocation), with t per root.
    for method in [Method::BezoutResultant, Method::Stam] {
        let opts = SolveOptions {
            method,
            ..SolveOptions::default()
        };
        let mut ws = SolveWorkspace::new();
        g.bench_function(format!("solve_ray_patch_{method:?}"), |b| {
            b.iter(|| {
                pairs
                    .iter()
                    .map(|(power, o, d)| {
                        solve_ray_patch(&mut ws, black_box(power), 4, 4, o, d, &opts)
                            .map_or(0, |x| x.roots.len())
                    })
                    .sum::<usize>()
            })
        });
    }
    g.bench_function("bezout_determinant", |b| {
        b.iter(|| {
            systems
                .iter()
                .map(|s| {
                    bezout_resultant_v(black_box(&s.f1), black_box(&s.f2)).map_or(0, |p| p.degree())
                })
                .sum::<usize>()
        })
    });
    g.bench_function("sylvester_determinant", |b| {
        b.iter(|| {
            systems
                .iter()
                .map(|s| {
                    sylvester_resultant_v(black_box(&s.f1), black_box(&s.f2))
                        .map_or(0, |p| p.degree())
                })
                .sum::<usize>()
        })
    });
    g.finish();
}

criterion_group!(benches, groebner_solve);
criterion_main!(benches);

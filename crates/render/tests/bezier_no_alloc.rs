//! The per-ray algebra of the Bézier patches allocates nothing on the heap: a counting global
//! allocator watches this thread while primary rays of the teapot view are traced through
//! `BezierMesh::nearest_hit_in` (BVH, hull test, `groebner::solve_ray_patch`: the ray/patch
//! system, elimination by Stam's `f64` loop or the Bézout resultant, certificate, root finding,
//! back-substitution, polish), after a warm-up on other rays of the same view has grown the
//! solver workspace's buffers. Both `f64` methods. `allocation-counter` counts the
//! allocations of this thread.

use std::path::Path;

use groebner::SolveWorkspace;
use render::glam::DVec3;
use render::scene::{CameraSpec, LookAtCamera, parse_bpt};
use render::surface::BezierMesh;
use render::{Camera, PatchMethod, PatchStats};

/// The teapot mesh (`scenes/teapot.bpt`, 16×16 pieces per patch) and the camera of
/// `scenes/teapot.scene` at `size`².
fn teapot(method: PatchMethod, size: u32) -> (BezierMesh, Camera) {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../scenes/teapot.bpt");
    let text = std::fs::read_to_string(path).expect("scenes/teapot.bpt is readable");
    let patches = parse_bpt(&text).expect("teapot.bpt parses");
    let mesh = BezierMesh::new(&patches, method).expect("32 patches");
    let spec = CameraSpec::LookAt(LookAtCamera {
        eye: DVec3::new(5.5, -8.0, 6.0),
        look_at: DVec3::new(0.45, 0.0, 1.35),
        up: DVec3::Z,
        view_field_deg: 34.0,
    });
    (mesh, Camera::new(&spec, size, size))
}

/// Traces the pixel centres `(x + offset, y + offset)` of the `size`² view; returns the hits.
fn trace(
    mesh: &BezierMesh,
    cam: &Camera,
    size: u32,
    offset: f64,
    stats: &mut PatchStats,
    solver: &mut SolveWorkspace,
) -> usize {
    let mut hits = 0;
    for y in 0..size {
        for x in 0..size {
            let ray = cam.ray(f64::from(x) + offset, f64::from(y) + offset);
            hits += usize::from(
                mesh.nearest_hit_in(&ray, 0.0..f64::INFINITY, stats, solver, false)
                    .is_some(),
            );
        }
    }
    hits
}

#[test]
fn per_ray_patch_algebra_allocates_nothing_after_warm_up() {
    const SIZE: u32 = 40;
    for method in [PatchMethod::Groebner, PatchMethod::Resultant] {
        let (mesh, cam) = teapot(method, SIZE);
        let mut solver = SolveWorkspace::new();
        let mut warm = PatchStats::default();
        // Warm-up: the pixel centres; the counted pass: the pixel corners (other rays).
        trace(&mesh, &cam, SIZE, 0.5, &mut warm, &mut solver);
        let mut stats = PatchStats::default();
        let mut hits = 0;
        let info = allocation_counter::measure(|| {
            hits = trace(&mesh, &cam, SIZE, 0.0, &mut stats, &mut solver);
        });
        let count = info.count_total;
        assert!(
            stats.solves > 200 && hits > 200,
            "{method:?}: the view reaches the algebra ({hits} hits): {stats}"
        );
        if method == PatchMethod::Groebner {
            assert!(
                stats.basis_size[1..].iter().sum::<u64>() > 0,
                "{method:?}: Stam's loop ran: {stats}"
            );
        }
        assert_eq!(
            count, 0,
            "{method:?}: {count} allocations in {} solves",
            stats.solves
        );
    }
}

//! Stam's table (article §5) for the single-patch scenes: every ray that reaches the algebra
//! reports a `u`-polynomial of degree 2, 4 or 6 and a `v`-polynomial of degree 1; the saddle's
//! degree collapses from Kajiya's 18 to 2; a generic random bicubic keeps degree 18 and its
//! hits agree with the Newton reference.

use std::path::Path;

use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use render::geometry::Ray;
use render::glam::DVec3;
use render::scene::{ControlNet, ShapeKind, load};
use render::surface::BezierMesh;
use render::{Camera, HIST_BINS, PatchMethod, PatchStats};

/// The patch and camera of `scenes/NAME.scene`.
fn scene_patch(name: &str) -> (ControlNet, Camera) {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join(format!("../scenes/{name}.scene"));
    let scene = load(&path).unwrap_or_else(|e| panic!("{e}"));
    let patch = scene
        .objects
        .iter()
        .find_map(|o| match &o.shape {
            ShapeKind::BezierPatches { patches, .. } => Some(patches[0].clone()),
            _ => None,
        })
        .expect("the scene has a Bézier patch");
    (patch, Camera::new(&scene.camera, 24, 24))
}

/// Traces a 24×24 view of the patch with `method`; returns the statistics, the hit count and
/// the rays (pixel centres) whose solves did not all report `u_degree`.
fn trace(
    patch: &ControlNet,
    cam: &Camera,
    method: PatchMethod,
    u_degree: usize,
) -> (PatchStats, usize, Vec<(f64, f64)>) {
    let mesh = BezierMesh::new(std::slice::from_ref(patch), method).expect("one patch");
    let mut stats = PatchStats::default();
    let mut hits = 0;
    let mut odd = Vec::new();
    for y in 0..24 {
        for x in 0..24 {
            let (px, py) = (x as f64 + 0.5, y as f64 + 0.5);
            let ray = cam.ray(px, py);
            let mut ray_stats = PatchStats::default();
            hits += usize::from(
                mesh.nearest_hit(&ray, 0.0..f64::INFINITY, &mut ray_stats, false)
                    .is_some(),
            );
            if ray_stats.u_degree[u_degree] != ray_stats.solves {
                odd.push((px, py));
            }
            stats.merge(&ray_stats);
        }
    }
    (stats, hits, odd)
}

/// The only non-empty bin of a histogram.
fn only_bin(hist: &[u64; HIST_BINS], total: u64) -> Option<usize> {
    let bins: Vec<usize> = (0..HIST_BINS).filter(|&b| hist[b] > 0).collect();
    (bins.len() == 1 && hist[bins[0]] == total).then(|| bins[0])
}

/// Stam's table: every ray that reaches the algebra has a `u`-polynomial of degree `u_degree`
/// and a `v`-polynomial of degree 1. Exactly so for the resultant and for the exact Gröbner
/// basis; the `f64` Gröbner run may, on a few grazing rays, certify a shorter eliminant (its
/// leading coefficients were rounding noise: those roots lie far outside the box) or a miss, or
/// fall back to the resultant. Such rays are re-traced in exact arithmetic, which must give
/// the table's degree, and may be at most 5% of the solves.
fn check_degrees(name: &str, u_degree: usize) {
    let (patch, cam) = scene_patch(name);
    let mut hit_counts = Vec::new();
    for method in [PatchMethod::Groebner, PatchMethod::Resultant] {
        let (stats, hits, odd) = trace(&patch, &cam, method, u_degree);
        hit_counts.push(hits);
        assert!(
            // (Since the control-hull test rejects by any plane through the ray, nearly every
            // solve here is a hit: 55-94 solves.)
            stats.solves > 40 && hits > 40,
            "{name} {method:?}: {hits} hits, {stats}"
        );
        if method == PatchMethod::Resultant {
            assert_eq!(
                only_bin(&stats.u_degree, stats.solves),
                Some(u_degree),
                "{name} {method:?}: {stats}"
            );
            assert_eq!(
                only_bin(&stats.basis_size, stats.solves),
                Some(0),
                "no basis: {stats}"
            );
        } else {
            assert!(
                odd.len() as u64 * 20 <= stats.solves,
                "{name} {method:?}: {} rays off the table: {odd:?}\n{stats}",
                odd.len()
            );
            let exact = BezierMesh::new(std::slice::from_ref(&patch), PatchMethod::GroebnerExact)
                .expect("one patch");
            for &(px, py) in &odd {
                let mut ray_stats = PatchStats::default();
                exact.nearest_hit(&cam.ray(px, py), 0.0..f64::INFINITY, &mut ray_stats, false);
                assert_eq!(
                    only_bin(&ray_stats.u_degree, ray_stats.solves),
                    Some(u_degree),
                    "{name}: exact Gröbner basis on ray ({px}, {py}): {ray_stats}"
                );
            }
        }
        assert_eq!(
            only_bin(&stats.v_degree, stats.solves),
            Some(1),
            "{name} {method:?}: {stats}"
        );
    }
    assert_eq!(
        hit_counts[0], hit_counts[1],
        "{name}: both methods hit the same pixels"
    );
}

#[test]
fn patch_deg2_has_u_degree_2_for_every_ray() {
    check_degrees("patch-deg2", 2);
}

#[test]
fn patch_deg4_has_u_degree_4_for_every_ray() {
    check_degrees("patch-deg4", 4);
}

#[test]
fn patch_deg6_has_u_degree_6_for_every_ray() {
    check_degrees("patch-deg6", 6);
}

#[test]
fn saddle_collapses_from_18_to_2() {
    check_degrees("saddle", 2);
}

#[test]
fn generic_random_bicubic_keeps_degree_18_and_matches_newton() {
    let mut rng = ChaCha8Rng::seed_from_u64(5);
    let pts: Vec<DVec3> = (0..16)
        .map(|k| {
            let (i, j) = ((k / 4) as f64, (k % 4) as f64);
            DVec3::new(i, j, 0.0)
                + DVec3::new(
                    rng.gen_range(-0.4..0.4),
                    rng.gen_range(-0.4..0.4),
                    rng.gen_range(-1.5..1.5),
                )
        })
        .collect();
    let patch = ControlNet::new(3, 3, pts).expect("finite net");
    let mesh =
        BezierMesh::with_subdivision(std::slice::from_ref(&patch), PatchMethod::Resultant, 1)
            .expect("one patch");
    let mut stats = PatchStats::default();
    let mut hits = 0;
    for k in 0..40 {
        let target = DVec3::new(rng.gen_range(0.2..2.8), rng.gen_range(0.2..2.8), 0.0);
        let eye = DVec3::new(1.5 + 3.0 * (k as f64).cos(), -6.0, 7.0);
        let ray = Ray::new(eye, (target - eye).normalize());
        let hit = mesh
            .nearest_hit(&ray, 0.0..f64::INFINITY, &mut stats, false)
            .map(|h| h.0.t);
        let reference = crate::bezier_teapot::newton_reference(std::slice::from_ref(&patch), &ray);
        match (hit, reference) {
            (None, None) => {}
            (Some(a), Some(b)) => {
                hits += 1;
                assert!((a - b).abs() < 1e-6 * b, "ray {k}: t = {a} vs Newton {b}");
            }
            _ => panic!("ray {k}: algebra {hit:?} vs Newton {reference:?}"),
        }
        assert!(hit.is_none_or(f64::is_finite), "no NaN");
    }
    assert!(hits > 10, "{hits} hits");
    assert!(stats.u_degree[18] > 0, "Kajiya's bound is reached: {stats}");
    assert_eq!(
        stats.u_degree[19..].iter().sum::<u64>(),
        0,
        "never above 18: {stats}"
    );
}

/// The exact-rational reference modes agree with the `f64` methods on a few rays of the
/// degree-6 patch (exact elimination is slow, hence few rays and a low-degree patch).
#[test]
fn exact_reference_modes_agree_with_f64() {
    let (patch, cam) = scene_patch("patch-deg6");
    let meshes = [
        PatchMethod::Groebner,
        PatchMethod::Resultant,
        PatchMethod::GroebnerExact,
        PatchMethod::ResultantExact,
    ]
    .map(|m| BezierMesh::new(std::slice::from_ref(&patch), m).expect("one patch"));
    let mut hits = 0;
    for (x, y) in [
        (12.5, 12.5),
        (9.5, 14.5),
        (15.5, 10.5),
        (11.5, 17.5),
        (1.5, 1.5),
    ] {
        let ray = cam.ray(x, y);
        let ts: Vec<Option<f64>> = meshes
            .iter()
            .map(|m| {
                m.nearest_hit(&ray, 0.0..f64::INFINITY, &mut PatchStats::default(), false)
                    .map(|h| h.0.t)
            })
            .collect();
        hits += usize::from(ts[3].is_some());
        for (i, t) in ts.iter().enumerate() {
            assert_eq!(
                t.is_some(),
                ts[3].is_some(),
                "ray ({x}, {y}) method {i}: {ts:?}"
            );
            if let (Some(a), Some(b)) = (t, ts[3]) {
                assert!(
                    (a - b).abs() <= 1e-9 * b,
                    "ray ({x}, {y}) method {i}: {ts:?}"
                );
            }
        }
    }
    assert!(hits >= 3, "most of these rays hit the patch: {hits}");
}

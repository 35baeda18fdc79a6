//! The scene BVH against brute force: on random scenes of mixed primitives (spheres, tori,
//! boxes sharing faces, triangles, clipped algebraic surfaces, a Bézier patch, a plane, cones)
//! every nearest hit and every shadow verdict through the hierarchy equals a loop over all
//! primitives; and the bare aggregate on flat (zero-thickness) boxes.

use std::ops::Range;

use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use render::aggregate::Aggregate;
use render::geometry::{Bounds3, Ray};
use render::glam::DVec3;
use render::scene::{BoundingVolume, ControlNet, Object, Scene, ShapeKind, ValidScene};
use render::surface::Hit;
use render::whitted::{nearest_hit, occluded};
use render::{PatchMethod, Poly3, PreparedScene, Workspace};

/// The reference: every primitive asked over the whole range, the least `(t, index)` kept.
fn brute_nearest(
    scene: &PreparedScene,
    ray: &Ray,
    range: Range<f64>,
    ws: &mut Workspace,
) -> Option<(usize, Hit)> {
    let mut best: Option<(usize, Hit)> = None;
    for (i, s) in scene.surfaces.iter().enumerate() {
        if let Some(h) = s.intersect(ray, range.clone(), ws)
            && best.is_none_or(|(_, b)| h.t < b.t)
        {
            best = Some((i, h));
        }
    }
    best
}

/// Asserts that the BVH's nearest hit of `ray` over `(0, ∞)` is the brute-force loop's, and
/// so are its shadow verdicts over the whole ray and up to half the nearest hit; returns the
/// hit. `what` is appended to the failure messages.
fn assert_agrees_with_brute_force(
    prepared: &PreparedScene,
    ray: &Ray,
    ws: &mut Workspace,
    what: &str,
) -> Option<(usize, Hit)> {
    let range = 0.0..f64::INFINITY;
    let fast = nearest_hit(prepared, ray, range.clone(), ws);
    let slow = brute_nearest(prepared, ray, range.clone(), ws);
    assert_eq!(fast, slow, "nearest hit of {ray:?}{what}");
    let reach = fast.map_or(30.0, |(_, h)| h.t * 0.5);
    for r in [range, 0.0..reach] {
        assert_eq!(
            occluded(prepared, ray, r.clone(), ws),
            brute_occluded(prepared, ray, r.clone(), ws),
            "shadow verdict of {ray:?} over {r:?}{what}"
        );
    }
    fast
}

fn brute_occluded(scene: &PreparedScene, ray: &Ray, range: Range<f64>, ws: &mut Workspace) -> bool {
    scene
        .surfaces
        .iter()
        .any(|s| s.occluded(ray, range.clone(), ws))
}

fn random_scene(rng: &mut ChaCha8Rng) -> Scene {
    let mut scene = Scene::default();
    let v = |rng: &mut ChaCha8Rng, s: f64| {
        DVec3::new(
            rng.gen_range(-s..s),
            rng.gen_range(-s..s),
            rng.gen_range(-s..s),
        )
    };
    for _ in 0..25 {
        scene.objects.push(Object::new(ShapeKind::Sphere {
            center: v(rng, 8.0),
            radius: rng.gen_range(0.2..1.5),
        }));
    }
    for _ in 0..6 {
        scene.objects.push(Object::new(ShapeKind::Torus {
            center: v(rng, 8.0),
            axis: v(rng, 1.0) + DVec3::splat(0.01),
            major: rng.gen_range(0.8..1.5),
            minor: rng.gen_range(0.1..0.5),
        }));
    }
    // A row of unit boxes sharing faces (x = 0, 1, 2, 3), and a few loose ones.
    for i in 0..4 {
        let x = i as f64;
        scene.objects.push(Object::new(ShapeKind::Box {
            min: DVec3::new(x, 0.0, 0.0),
            max: DVec3::new(x + 1.0, 1.0, 1.0),
        }));
    }
    for _ in 0..4 {
        let c = v(rng, 8.0);
        scene.objects.push(Object::new(ShapeKind::Box {
            min: c,
            max: c + DVec3::new(1.0, 0.5, 2.0),
        }));
    }
    // Triangles, some in the axis plane z = 2 (flat boxes).
    for k in 0..12 {
        let a = v(rng, 8.0);
        let (mut b, mut c) = (a + v(rng, 1.5), a + v(rng, 1.5));
        if k % 2 == 0 {
            for p in [&mut b, &mut c] {
                p.z = 2.0;
            }
            let mut a2 = a;
            a2.z = 2.0;
            scene.objects.push(Object::new(ShapeKind::Triangle {
                vertices: [a2, b, c],
            }));
        } else {
            scene.objects.push(Object::new(ShapeKind::Triangle {
                vertices: [a, b, c],
            }));
        }
    }
    // A clipped algebraic surface (a hyperboloid x² + y² − z² = 1/4 in a box) and a cone.
    let mut hyper = Object::new(ShapeKind::Algebraic {
        poly: Poly3::from_terms([
            (1.0, [2, 0, 0]),
            (1.0, [0, 2, 0]),
            (-1.0, [0, 0, 2]),
            (-0.25, [0, 0, 0]),
        ]),
    });
    hyper.bounding = BoundingVolume::Box {
        min: DVec3::splat(-1.0),
        max: DVec3::splat(1.0),
    };
    hyper.transform.translate = v(rng, 6.0);
    scene.objects.push(hyper);
    scene.objects.push(Object::new(ShapeKind::Cone {
        base: v(rng, 6.0),
        base_radius: 1.0,
        apex: v(rng, 6.0),
        apex_radius: 0.3,
        caps: true,
    }));
    // A bicubic Bézier patch with random heights.
    let mut points = Vec::new();
    for i in 0..4 {
        for j in 0..4 {
            points.push(DVec3::new(
                i as f64 - 1.5,
                j as f64 - 1.5,
                rng.gen_range(-0.5..0.5),
            ));
        }
    }
    let mut patch = Object::new(ShapeKind::BezierPatches {
        patches: vec![ControlNet::new(3, 3, points).expect("valid net")],
        method: PatchMethod::default(),
    });
    patch.transform.translate = v(rng, 6.0);
    scene.objects.push(patch);
    // An unbounded plane, tested outside the hierarchy.
    scene.objects.push(Object::new(ShapeKind::Plane {
        origin: DVec3::new(0.0, 0.0, -9.0),
        normal: DVec3::Z,
    }));
    scene
}

#[test]
fn bvh_nearest_hits_and_shadow_verdicts_equal_brute_force() {
    let mut rng = ChaCha8Rng::seed_from_u64(12);
    let mut rays = 0;
    let mut hits = 0;
    for _ in 0..4 {
        let scene = random_scene(&mut rng);
        let prepared =
            PreparedScene::new(&ValidScene::new(scene.clone()).unwrap()).expect("valid scene");
        assert_eq!(prepared.aggregate.unbounded().len(), 1, "only the plane");
        let mut ws = Workspace::new();
        let centres: Vec<DVec3> = prepared
            .surfaces
            .iter()
            .filter_map(|s| s.bounds())
            .map(|b| (b.min + b.max) * 0.5)
            .collect();
        for k in 0..1000 {
            let origin = DVec3::new(
                rng.gen_range(-12.0..12.0),
                rng.gen_range(-12.0..12.0),
                rng.gen_range(-12.0..12.0),
            );
            let ray = match k % 4 {
                // At a primitive's box centre (mostly hits).
                0 | 1 => Ray::new(origin, centres[rng.gen_range(0..centres.len())] - origin),
                // Within a shared face of the box row (x = 1, 2 or 3), along the face.
                2 => {
                    let x = f64::from(rng.gen_range(1..4));
                    let o = DVec3::new(x, rng.gen_range(-3.0..4.0), -5.0);
                    Ray::new(o, DVec3::new(0.0, rng.gen_range(-0.3..0.3), 1.0))
                }
                // Anywhere.
                _ => Ray::new(
                    origin,
                    DVec3::new(
                        rng.gen_range(-1.0..1.0),
                        rng.gen_range(-1.0..1.0),
                        rng.gen_range(-1.0..1.0),
                    ),
                ),
            };
            let fast = assert_agrees_with_brute_force(&prepared, &ray, &mut ws, "");
            hits += usize::from(fast.is_some());
            rays += 1;
        }
        assert!(
            ws.stats.bvh_node_visits > 0,
            "the traversal went through the BVH"
        );
    }
    assert!(hits > rays / 3, "the rays do hit things: {hits} of {rays}");
}

/// Scenes of one to five objects (a flat list up to `FLAT_MAX_ITEMS` bounded ones, a tree
/// above; issue 10): through the aggregate, the same nearest hits and shadow verdicts as a loop
/// over all primitives, on rays at each primitive and through the shared face of two boxes.
#[test]
fn tiny_scenes_flat_or_not_equal_brute_force() {
    let mut rng = ChaCha8Rng::seed_from_u64(10);
    for n in 1..=5 {
        let mut scene = Scene::default();
        // Two unit boxes sharing the face x = 1, then spheres and a torus.
        for i in 0..n.min(2) {
            let x = i as f64;
            scene.objects.push(Object::new(ShapeKind::Box {
                min: DVec3::new(x, 0.0, 0.0),
                max: DVec3::new(x + 1.0, 1.0, 1.0),
            }));
        }
        for k in 2..n {
            scene.objects.push(Object::new(if k == 4 {
                ShapeKind::Torus {
                    center: DVec3::new(0.0, 3.0, 0.5),
                    axis: DVec3::Z,
                    major: 1.0,
                    minor: 0.3,
                }
            } else {
                ShapeKind::Sphere {
                    center: DVec3::new(3.0 * k as f64, 0.5, 0.5),
                    radius: 0.8,
                }
            }));
        }
        scene.objects.push(Object::new(ShapeKind::Plane {
            origin: DVec3::new(0.0, 0.0, -2.0),
            normal: DVec3::Z,
        }));
        let prepared = PreparedScene::new(&ValidScene::new(scene).unwrap()).expect("valid scene");
        let bounded = prepared.surfaces.len() - 1;
        assert_eq!(
            prepared.aggregate.bvh_info().nodes == 0,
            bounded <= render::aggregate::FLAT_MAX_ITEMS,
            "a flat list exactly up to FLAT_MAX_ITEMS bounded objects ({bounded})"
        );
        let mut ws = Workspace::new();
        for k in 0..400 {
            let target = match k % 3 {
                // The shared face x = 1 of the two boxes.
                0 => DVec3::new(1.0, rng.gen_range(0.0..1.0), rng.gen_range(0.0..1.0)),
                _ => prepared.surfaces[rng.gen_range(0..bounded)]
                    .bounds()
                    .map(|b| (b.min + b.max) * 0.5)
                    .unwrap_or_default(),
            };
            let origin = DVec3::new(
                rng.gen_range(-8.0..8.0),
                rng.gen_range(-8.0..8.0),
                rng.gen_range(-1.0..8.0),
            );
            let ray = Ray::new(origin, target - origin);
            assert_agrees_with_brute_force(
                &prepared,
                &ray,
                &mut ws,
                &format!(" among {n} objects"),
            );
        }
    }
}

/// Rays through a grid of flat boxes (zero thickness in z, sharing edges): the aggregate
/// finds the same least `(t, item)` and the same any-hit verdict as a loop over all boxes.
#[test]
fn aggregate_on_flat_boxes_equals_brute_force() {
    let mut boxes = Vec::new();
    for i in 0..10 {
        for j in 0..10 {
            let (x, y) = (i as f64, j as f64);
            boxes.push(Some(Bounds3::new(
                DVec3::new(x, y, 0.5 * (i % 3) as f64),
                DVec3::new(x + 1.0, y + 1.0, 0.5 * (i % 3) as f64),
            )));
        }
    }
    boxes.push(None); // an unbounded item: never hit here
    let agg = Aggregate::new(boxes.iter().copied());
    let entry = |i: u32, ray: &Ray| -> Option<(f64, ())> {
        let b = boxes[i as usize]?;
        b.intersect_ray(ray, 0.0..f64::INFINITY)
            .map(|r| (r.start, ()))
    };
    let mut rng = ChaCha8Rng::seed_from_u64(7);
    let mut visits = 0;
    let mut hit_count = 0;
    for k in 0..3000 {
        let o = DVec3::new(
            rng.gen_range(-2.0..12.0),
            rng.gen_range(-2.0..12.0),
            if k % 3 == 0 { 0.5 } else { 5.0 },
        );
        // Down onto the grid, or (k % 3 == 0) within the plane z = 0.5 of the middle layer.
        let d = if k % 3 == 0 {
            DVec3::new(rng.gen_range(-1.0..1.0), rng.gen_range(-1.0..1.0), 0.0)
        } else {
            DVec3::new(rng.gen_range(-0.5..0.5), rng.gen_range(-0.5..0.5), -1.0)
        };
        let ray = Ray::new(o, d);
        let fast = agg.nearest(&ray, 0.0..f64::INFINITY, &mut visits, |i, _| entry(i, &ray));
        let mut slow: Option<(u32, f64, ())> = None;
        for i in 0..boxes.len() as u32 {
            if let Some((t, ())) = entry(i, &ray)
                && slow.is_none_or(|(_, bt, _)| t < bt)
            {
                slow = Some((i, t, ()));
            }
        }
        assert_eq!(fast, slow, "nearest flat box for {ray:?}");
        hit_count += usize::from(fast.is_some());
        let any = agg.any(&ray, 0.0..f64::INFINITY, &mut visits, |i| {
            entry(i, &ray).is_some()
        });
        assert_eq!(any, slow.is_some(), "any-hit verdict for {ray:?}");
    }
    assert!(hit_count > 1000, "rays hit the grid: {hit_count}");
}

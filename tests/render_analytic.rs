//! Analytic checks of the tracer: pixel coverage of a sphere against its projected disc, torus
//! depths against exact rational roots, no self-intersection of spawned rays, and the torus
//! traced as `TORUS` and as the equivalent `ALGEBRAIC_SURFACE`.

use num_traits::Zero;
use poly::{QPoly, Rat, rat_from_f64};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use render::geometry::{Ray, offset_ray_origin};
use render::glam::DVec3;
use render::scene::{
    CameraSpec, Illumination, Light, LookAtCamera, Object, Scene, ShapeKind, ValidScene,
};
use render::surface::{Algebraic, Implicit, Sphere, Superquadric, Surface, Torus, Transformed};
use render::whitted::nearest_hit;
use render::{Camera, Poly3, PreparedScene, RenderSettings, Workspace, render};

fn look_at(eye: DVec3, fov: f64) -> CameraSpec {
    CameraSpec::LookAt(LookAtCamera {
        eye,
        look_at: DVec3::ZERO,
        up: DVec3::Z,
        view_field_deg: fov,
    })
}

fn torus_scene() -> Scene {
    let mut scene = Scene {
        camera: look_at(DVec3::new(0.0, -8.0, 5.0), 50.0),
        ..Scene::default()
    };
    scene.world.background = DVec3::splat(0.2);
    scene.lights.push(Light {
        source: DVec3::new(5.0, -5.0, 10.0),
        color: DVec3::ONE,
    });
    let mut torus = Object::new(ShapeKind::Torus {
        center: DVec3::ZERO,
        axis: DVec3::Z,
        major: 2.0,
        minor: 1.0,
    });
    let material = std::sync::Arc::make_mut(&mut torus.material);
    material.illumination = Illumination::Specular;
    material.cs = DVec3::new(0.8, 0.3, 0.2);
    material.ka = 0.1;
    material.kd = 0.7;
    material.ks = 0.5;
    material.n = 40.0;
    scene.objects.push(torus);
    scene
}

/// A sphere of radius `r` at distance `D` on the view axis subtends a cone of half-angle
/// `asin(r/D)`; on the image plane at unit distance that is a disc of radius
/// `tan(asin(r/D))`. With 4×4 stratified samples the summed alpha estimates the covered area
/// to within a small fraction of the boundary pixels.
#[test]
fn sphere_coverage_matches_projected_disc() {
    let (size, fov, dist, r) = (96u32, 40.0f64, 10.0f64, 2.0f64);
    let mut scene = Scene {
        camera: look_at(DVec3::new(0.0, -dist, 0.0), fov),
        ..Scene::default()
    };
    scene.objects.push(Object::new(ShapeKind::Sphere {
        center: DVec3::ZERO,
        radius: r,
    }));
    let prepared = PreparedScene::new(&ValidScene::new(scene.clone()).unwrap()).unwrap();
    let settings = RenderSettings {
        size: [size, size],
        resolution: [1, 1],
        samples: 4,
        depth: false,
    };
    let out = render(&prepared, &scene.camera, &settings, &|_| {});
    let covered: f64 = out.film.pixels.iter().map(|p| f64::from(p[3])).sum();

    let disc_radius = (r / dist).asin().tan();
    let pixel = 2.0 * (fov.to_radians() / 2.0).tan() / f64::from(size);
    let expected = std::f64::consts::PI * (disc_radius / pixel).powi(2);
    // Stated tolerance: 0.5% of the area (the boundary is ~180 pixels long; 16 samples per
    // pixel leave an estimation error well below one pixel-area per 10 boundary pixels).
    let rel = (covered - expected).abs() / expected;
    assert!(
        rel < 0.005,
        "covered {covered:.1} px², disc {expected:.1} px², relative error {rel:.4}"
    );
    // The coverage really is the sphere: with the sphere twice as far the area drops 4×.
    assert!(covered > 1000.0, "a disc of {expected:.0} px² is visible");
}

/// The exact smallest positive root of the torus quartic restricted to `ray`, computed over
/// the rationals from the exact values of the `f64` origin and direction.
fn exact_torus_root(ray: &Ray, major: f64, minor: f64) -> Option<f64> {
    let q = |x: f64| rat_from_f64(x).expect("finite");
    let (o, d) = (ray.origin, ray.dir);
    let (ox, oy, oz, dx, dy, dz) = (q(o.x), q(o.y), q(o.z), q(d.x), q(d.y), q(d.z));
    let r2 = q(major) * q(major);
    let m = Rat::from_integer(4.into()) * &r2;
    let two = Rat::from_integer(2.into());
    let a = &dx * &dx + &dy * &dy + &dz * &dz;
    let b = &two * (&ox * &dx + &oy * &dy + &oz * &dz);
    let c = &ox * &ox + &oy * &oy + &oz * &oz + &r2 - q(minor) * q(minor);
    // (a t² + b t + c)² − m((ox + t dx)² + (oy + t dy)²), low → high.
    let coeffs = vec![
        &c * &c - &m * (&ox * &ox + &oy * &oy),
        &two * &b * &c - &two * &m * (&ox * &dx + &oy * &dy),
        &b * &b + &two * &a * &c - &m * (&dx * &dx + &dy * &dy),
        &two * &a * &b,
        &a * &a,
    ];
    let p = QPoly::new(coeffs);
    let roots = p
        .real_roots(&Rat::zero(), &Rat::from_integer(100.into()), 1e-15)
        .ok()?;
    roots.into_iter().find(|&t| t > 0.0)
}

#[test]
fn torus_depth_matches_exact_root() {
    let scene = torus_scene();
    let size = 48u32;
    let prepared = PreparedScene::new(&ValidScene::new(scene.clone()).unwrap()).unwrap();
    let settings = RenderSettings {
        size: [size, size],
        resolution: [1, 1],
        samples: 1,
        depth: true,
    };
    let out = render(&prepared, &scene.camera, &settings, &|_| {});
    let depth = out.film.depth.as_ref().unwrap();
    let camera = Camera::new(&scene.camera, size, size);
    let mut ws = Workspace::new();
    let mut checked = 0;
    // A grid of pixels including silhouette and hole pixels.
    for py in (0..size).step_by(2) {
        for px in (0..size).step_by(3) {
            let ray = camera.ray(f64::from(px) + 0.5, f64::from(py) + 0.5);
            let exact = exact_torus_root(&ray, 2.0, 1.0);
            let film = depth[(py * size + px) as usize];
            let direct =
                nearest_hit(&prepared, &ray, 0.0..f64::INFINITY, &mut ws).map(|(_, h)| h.t);
            match exact {
                None => {
                    assert!(
                        film.is_infinite(),
                        "pixel ({px},{py}): no root but depth {film}"
                    );
                    assert_eq!(direct, None, "pixel ({px},{py}): no root");
                }
                Some(t) => {
                    checked += 1;
                    let tol = 1e-8 * t; // ROOT_X_TOL_REL × diagonal ≈ 1e-9 in t, plus rounding
                    let got = direct.expect("a hit where the exact root exists");
                    assert!(
                        (got - t).abs() <= tol,
                        "pixel ({px},{py}): t {got} vs exact {t}"
                    );
                    // The PFM channel is f32: within its rounding.
                    let f32_tol = f64::from(f32::EPSILON) * t;
                    assert!(
                        (f64::from(film) - t).abs() <= f32_tol,
                        "pixel ({px},{py}): film {film} vs {t}"
                    );
                }
            }
        }
    }
    assert!(checked > 100, "enough pixels hit the torus: {checked}");
}

/// pbrt's `Reintersect` test: a ray spawned from a hit, offset by the hit's error bound, must
/// not find the same surface again at a tiny distance. Directions keep `|w·n| ≥ 0.1` so that
/// legitimate re-hits of the concave torus stay at a fair fraction of its tube radius, many
/// orders of magnitude above the hit-point error bounds (~1e-10 of the size) a self-hit would
/// show; the threshold is 1e-6 of the object's size.
#[test]
fn spawned_rays_do_not_reintersect() {
    let mut rng = ChaCha8Rng::seed_from_u64(0x5eed);
    let scaled = render::scene::ObjectTransform {
        translate: DVec3::new(1e3, -2e3, 5e2),
        rotate_deg: DVec3::new(10.0, 20.0, 30.0),
        scale: DVec3::new(3.0, 0.5, 1.5),
    }
    .world_from_object()
    .unwrap();
    let surfaces: Vec<(&str, Box<dyn Surface>, f64)> = vec![
        (
            "sphere",
            Box::new(Implicit::new(
                Sphere::new(DVec3::new(0.3, -0.2, 0.1), 1.3),
                None,
            )),
            1.3,
        ),
        (
            "torus",
            Box::new(Implicit::new(Torus::new(2.0, 0.5), None)),
            2.5,
        ),
        (
            // Stam's quartic (Annexe B `Polynomial`) through the general restriction.
            "algebraic",
            Box::new(Implicit::new(
                Algebraic::new(stam_quartic()),
                Some(stam_box()),
            )),
            6.0,
        ),
        (
            "superquadric p=4",
            Box::new(Superquadric::new(DVec3::new(1.0, 2.0, 0.5), 4)),
            2.3,
        ),
        (
            "superquadric p=5",
            Box::new(Superquadric::new(DVec3::new(1.0, 2.0, 0.5), 5)),
            2.3,
        ),
        (
            "transformed torus",
            Box::new(Transformed::new(
                Implicit::new(Torus::new(2.0, 0.5), None),
                scaled,
            )),
            7.5,
        ),
    ];
    let mut ws = Workspace::new();
    for (name, surface, scale) in &surfaces {
        let b = surface.bounds().unwrap();
        let centre = (b.min + b.max) / 2.0;
        let mut hits = 0;
        for _ in 0..3000 {
            let dir = random_unit(&mut rng);
            let origin =
                centre - dir * (4.0 * b.diagonal()) + random_unit(&mut rng) * b.diagonal() * 0.3;
            let ray = Ray::new(origin, dir);
            let Some(hit) = surface.intersect(&ray, 0.0..f64::INFINITY, &mut ws) else {
                continue;
            };
            hits += 1;
            let g = surface.shading(&hit);
            let n = g.normal.expect("regular point");
            for _ in 0..4 {
                let mut w = random_unit(&mut rng);
                if w.dot(n).abs() < 0.1 {
                    continue;
                }
                if rng.r#gen::<bool>() {
                    w = -w; // both sides: reflection and refraction
                }
                let o = offset_ray_origin(g.p, g.p_err, n, w);
                let again = surface.intersect(&Ray::new(o, w), 0.0..f64::INFINITY, &mut ws);
                if let Some(h) = again {
                    let dist = h.t * w.length();
                    assert!(
                        dist > 1e-6 * scale,
                        "{name}: spawned ray re-hit at distance {dist:e} (p {:?}, err {:?})",
                        g.p,
                        g.p_err
                    );
                }
            }
        }
        assert!(hits > 300, "{name}: enough hits to mean something ({hits})");
    }
}

/// Stam's torus `(x²+y²−1)(x²+y²−9) + 15z²` as a general polynomial.
fn stam_quartic() -> Poly3 {
    let (x, y, z) = (Poly3::x(), Poly3::y(), Poly3::z());
    let r2 = &(&x * &x) + &(&y * &y);
    let a = &r2 - &Poly3::constant(1.0);
    let b = &r2 - &Poly3::constant(9.0);
    &(&a * &b) + &(&(&z * &z) * 15.0)
}

fn stam_box() -> render::geometry::Bounds3 {
    render::geometry::Bounds3::new(DVec3::new(-3.1, -3.1, -1.1), DVec3::new(3.1, 3.1, 1.1))
}

fn random_unit(rng: &mut ChaCha8Rng) -> DVec3 {
    loop {
        let v = DVec3::new(
            rng.gen_range(-1.0..1.0),
            rng.gen_range(-1.0..1.0),
            rng.gen_range(-1.0..1.0),
        );
        let l = v.length();
        if l > 0.1 && l <= 1.0 {
            return v / l;
        }
    }
}

/// A convex surface: a ray leaving the outside never hits it again at all.
#[test]
fn rays_leaving_a_sphere_never_hit_it() {
    let mut rng = ChaCha8Rng::seed_from_u64(7);
    let sphere = Implicit::new(Sphere::new(DVec3::new(1e4, 0.0, 0.0), 0.25), None);
    let mut ws = Workspace::new();
    for _ in 0..2000 {
        let dir = random_unit(&mut rng);
        let ray = Ray::new(
            DVec3::new(1e4, 0.0, 0.0) - dir * 50.0 + random_unit(&mut rng) * 0.1,
            dir,
        );
        let Some(hit) = sphere.intersect(&ray, 0.0..f64::INFINITY, &mut ws) else {
            continue;
        };
        let g = sphere.shading(&hit);
        let n = g.normal.unwrap();
        let mut w = random_unit(&mut rng);
        if w.dot(n) < 0.0 {
            w = -w;
        }
        let o = offset_ray_origin(g.p, g.p_err, n, w);
        assert_eq!(
            sphere.intersect(&Ray::new(o, w), 0.0..f64::INFINITY, &mut ws),
            None,
            "left the sphere at {:?}",
            g.p
        );
    }
}

/// The torus `(x²+y²+z²+R²−r²)² − 4R²(x²+y²)` written as an algebraic surface renders the
/// same image as the `TORUS` shape: only the restriction code differs.
#[test]
fn torus_and_equivalent_algebraic_surface_agree() {
    let scene = torus_scene();
    let mut alg = scene.clone();
    let (x, y, z) = (Poly3::x(), Poly3::y(), Poly3::z());
    let rho2 = &(&x * &x) + &(&y * &y);
    let s = &(&rho2 + &(&z * &z)) + &Poly3::constant(3.0);
    let f = &s.pow(2) - &(&rho2 * 16.0);
    alg.objects[0].shape = ShapeKind::Algebraic { poly: f };
    alg.objects[0].bounding = render::scene::BoundingVolume::Box {
        min: DVec3::new(-3.0, -3.0, -1.0),
        max: DVec3::new(3.0, 3.0, 1.0),
    };
    let settings = RenderSettings {
        size: [64, 64],
        resolution: [1, 1],
        samples: 1,
        depth: true,
    };
    let a = render(
        &PreparedScene::new(&ValidScene::new(scene.clone()).unwrap()).unwrap(),
        &scene.camera,
        &settings,
        &|_| {},
    );
    let b = render(
        &PreparedScene::new(&ValidScene::new(alg.clone()).unwrap()).unwrap(),
        &alg.camera,
        &settings,
        &|_| {},
    );
    let mut differing = 0;
    for (pa, pb) in a.film.pixels.iter().zip(&b.film.pixels) {
        let diff = (0..4).map(|c| (pa[c] - pb[c]).abs()).fold(0.0f32, f32::max);
        if diff > 1.0 / 255.0 {
            differing += 1;
        }
    }
    // Stated tolerance: no pixel differs by more than 1/255 in any channel, except at most
    // 0.2% of pixels (silhouette pixels where a grazing root is within the tolerance).
    assert!(
        differing * 500 <= a.film.pixels.len(),
        "{differing} pixels differ"
    );
    let (da, db) = (a.film.depth.unwrap(), b.film.depth.unwrap());
    let hits = da.iter().filter(|d| d.is_finite()).count();
    assert!(
        hits > 1000,
        "the torus fills part of the image ({hits} pixels)"
    );
    for (i, (ta, tb)) in da.iter().zip(&db).enumerate() {
        assert!(
            ta == tb || (ta - tb).abs() <= 1e-5 * ta.abs(),
            "pixel {i}: torus depth {ta} vs algebraic {tb}"
        );
    }
}

/// `Bounding volume = SPHERE (c) r` clips an implicit surface to the ball, in the object's
/// coordinates (it moves with `Translate`) and through a shape's internal frame (a torus about
/// the x axis).
#[test]
fn a_bounding_sphere_clips_the_surface() {
    let text = "#camera Eye = (0,-8,5) LookAt = (0,0,0) ViewField = 50\n\
                #object Type = ALGEBRAIC_SURFACE Equation = z\n\
                Bounding volume = SPHERE (0.5, 0, 0) 1  Translate = (0, 0, 1)\n\
                #object Type = TORUS Center = (0,0,0) Axis = (1,0,0) MajorRadius = 2\n\
                MinorRadius = 0.5  Bounding volume = SPHERE (0, 2, 0) 1\n";
    let scene = render::scene::parse(text, std::path::Path::new("clip.scene")).unwrap();
    let prepared = PreparedScene::new(&scene).unwrap();
    let mut ws = Workspace::new();
    let t_of = |object: usize, o: DVec3, d: DVec3, ws: &mut Workspace| {
        prepared.surfaces[object]
            .intersect(&Ray::new(o, d), 0.0..f64::INFINITY, ws)
            .map(|h| h.t)
    };
    // The plane z = 1 inside the disc |x − 0.5| < 1 (the ball moved up with the plane).
    let down = DVec3::NEG_Z;
    for (x, hit) in [(-0.4, true), (-0.6, false), (1.45, true), (1.55, false)] {
        let t = t_of(0, DVec3::new(x, 0.0, 5.0), down, &mut ws);
        match (hit, t) {
            (true, Some(t)) => assert!((t - 4.0).abs() < 1e-9, "x = {x}: t = {t}"),
            (false, None) => {}
            _ => panic!("x = {x}: expected hit {hit}, got {t:?}"),
        }
    }
    // Along +y through the torus's ring (the circle y² + z² = 4 in x = 0): the first three
    // crossings (y = −2.5, −1.5, 1.5 … ) lie outside the ball about (0, 2, 0) except y = 1.5.
    let t = t_of(1, DVec3::new(0.0, -5.0, 0.0), DVec3::Y, &mut ws).expect("hits at y = 1.5");
    assert!((t - 6.5).abs() < 1e-9, "t = {t}");
    let t = t_of(1, DVec3::new(0.0, 5.0, 0.0), DVec3::NEG_Y, &mut ws).expect("hits at y = 2.5");
    assert!((t - 2.5).abs() < 1e-9, "t = {t}");
}

/// A ray that meets a surface exactly where it enters the surface's bounding box (head-on at
/// the extreme point of a sphere or torus, the centre pixel of an axis-aligned camera) hits
/// there, not at the far side.
#[test]
fn a_hit_on_the_bounding_box_face_is_found() {
    let mut ws = Workspace::new();
    let sphere = Implicit::new(Sphere::new(DVec3::ZERO, 1.0), None);
    let down = Ray::new(DVec3::new(0.0, 0.0, 5.0), DVec3::NEG_Z);
    let hit = sphere
        .intersect(&down, 0.0..f64::INFINITY, &mut ws)
        .expect("hits");
    assert!(
        (hit.t - 4.0).abs() < 1e-9,
        "front of the sphere at t = 4, got {}",
        hit.t
    );
    let torus = Implicit::new(Torus::new(2.0, 0.5), None);
    let inward = Ray::new(DVec3::new(5.0, 0.0, 0.0), DVec3::NEG_X);
    let hit = torus
        .intersect(&inward, 0.0..f64::INFINITY, &mut ws)
        .expect("hits");
    assert!(
        (hit.t - 2.5).abs() < 1e-9,
        "outer equator at t = 2.5, got {}",
        hit.t
    );
}

/// The same for a superquadric (its own piecewise restriction): a ray along an axis meets the
/// `p = 4` superellipsoid at the centre of a box face.
#[test]
fn a_superquadric_hit_on_its_box_face_is_found() {
    let mut ws = Workspace::new();
    let sq = Superquadric::new(DVec3::new(1.0, 2.0, 0.5), 4);
    let ray = Ray::new(DVec3::new(0.0, -6.0, 0.0), DVec3::Y);
    let hit = sq
        .intersect(&ray, 0.0..f64::INFINITY, &mut ws)
        .expect("hits");
    assert!(
        (hit.t - 4.0).abs() < 1e-9,
        "face centre y = −2 at t = 4, got {}",
        hit.t
    );
}

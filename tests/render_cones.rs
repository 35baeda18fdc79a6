//! Cones and cylinders against closed forms: pixel coverage of a capped and an open cylinder
//! and of a cone seen end-on against their projected discs and annuli, and depths against the
//! quadric's root.

use render::geometry::Ray;
use render::glam::DVec3;
use render::scene::{CameraSpec, LookAtCamera, Object, Scene, ShapeKind, ValidScene};
use render::whitted::nearest_hit;
use render::{Camera, PreparedScene, RenderSettings, Workspace, render};

const SIZE: u32 = 96;
const FOV: f64 = 40.0;
/// Eye distance from the origin along −y.
const DIST: f64 = 10.0;

fn end_on(shape: ShapeKind) -> Scene {
    let mut scene = Scene {
        camera: CameraSpec::LookAt(LookAtCamera {
            eye: DVec3::new(0.0, -DIST, 0.0),
            look_at: DVec3::ZERO,
            up: DVec3::Z,
            view_field_deg: FOV,
        }),
        ..Scene::default()
    };
    scene.objects.push(Object::new(shape));
    scene
}

/// Covered area in pixels (summed alpha, 4×4 samples per pixel).
fn coverage(scene: &Scene) -> f64 {
    let prepared = PreparedScene::new(&ValidScene::new(scene.clone()).unwrap()).unwrap();
    let settings = RenderSettings {
        size: [SIZE, SIZE],
        resolution: [1, 1],
        samples: 4,
        depth: false,
    };
    let out = render(&prepared, &scene.camera, &settings, &|_| {});
    out.film.pixels.iter().map(|p| f64::from(p[3])).sum()
}

/// Area in pixels of a disc of radius `r` perpendicular to the view axis at distance `d`: it
/// projects to a disc of radius `r/d` on the image plane at unit distance.
fn disc_px(r: f64, d: f64) -> f64 {
    let pixel = 2.0 * (FOV.to_radians() / 2.0).tan() / f64::from(SIZE);
    std::f64::consts::PI * (r / d / pixel).powi(2)
}

fn cylinder(caps: bool) -> ShapeKind {
    // Axis along the view direction, from y = −1 (near) to y = 3 (far), radius 1.5.
    ShapeKind::Cone {
        base: DVec3::new(0.0, -1.0, 0.0),
        base_radius: 1.5,
        apex: DVec3::new(0.0, 3.0, 0.0),
        apex_radius: 1.5,
        caps,
    }
}

/// Capped, the cylinder seen end-on covers its near cap's disc. Open, the rays inside the far
/// rim's cone pass through the tube: it covers the annulus between the near and far rims.
/// Tolerance 1% of the area: 16 samples per pixel leave well under a pixel-area of error per
/// 10 boundary pixels.
#[test]
fn cylinder_coverage_matches_the_projected_rims() {
    let (near, far) = (DIST - 1.0, DIST + 3.0);
    let capped = coverage(&end_on(cylinder(true)));
    let disc = disc_px(1.5, near);
    assert!(
        (capped - disc).abs() < 0.01 * disc,
        "capped: {capped:.1} px² vs disc {disc:.1}"
    );
    let open = coverage(&end_on(cylinder(false)));
    let annulus = disc - disc_px(1.5, far);
    assert!(
        (open - annulus).abs() < 0.01 * annulus,
        "open: {open:.1} px² vs annulus {annulus:.1}"
    );
    assert!(open < 0.7 * capped, "the hole is visible");
}

/// A cone with its apex towards the eye (eye on the axis beyond the apex): the whole side is
/// seen, bounded by the base rim.
#[test]
fn cone_coverage_matches_the_base_rim() {
    let cone = ShapeKind::Cone {
        base: DVec3::new(0.0, 2.0, 0.0),
        base_radius: 2.0,
        apex: DVec3::new(0.0, -1.0, 0.0),
        apex_radius: 0.0,
        caps: false,
    };
    let got = coverage(&end_on(cone));
    let disc = disc_px(2.0, DIST + 2.0);
    assert!(
        (got - disc).abs() < 0.01 * disc,
        "cone: {got:.1} px² vs disc {disc:.1}"
    );
}

/// The nearest root of `(o + td)_x² + (o + td)_z² = (r₀ + k((o + td)_y − y₀))²` with the hit's
/// `y` in the segment, in closed form (the citardauq form for the smaller root).
fn exact_cone_t(ray: &Ray, y0: f64, y1: f64, r0: f64, r1: f64) -> Option<f64> {
    let k = (r1 - r0) / (y1 - y0);
    let (o, d) = (ray.origin, ray.dir);
    let rho = r0 + k * (o.y - y0);
    let a = d.x * d.x + d.z * d.z - k * k * d.y * d.y;
    let b = 2.0 * (o.x * d.x + o.z * d.z - k * d.y * rho);
    let c = o.x * o.x + o.z * o.z - rho * rho;
    let disc = b * b - 4.0 * a * c;
    if disc < 0.0 {
        return None;
    }
    let q = -0.5 * (b + b.signum() * disc.sqrt());
    let mut roots = [q / a, c / q];
    roots.sort_by(f64::total_cmp);
    roots
        .into_iter()
        .find(|&t| t > 0.0 && (y0..=y1).contains(&(o.y + t * d.y)))
}

#[test]
fn cone_depth_matches_the_closed_form_root() {
    // Seen from the side and above: the rays cross the side at all heights.
    let (y0, y1, r0, r1) = (-2.0, 1.5, 1.2, 0.4);
    let mut scene = end_on(ShapeKind::Cone {
        base: DVec3::new(0.0, y0, 0.0),
        base_radius: r0,
        apex: DVec3::new(0.0, y1, 0.0),
        apex_radius: r1,
        caps: false,
    });
    scene.camera = CameraSpec::LookAt(LookAtCamera {
        eye: DVec3::new(7.0, -3.0, 4.0),
        look_at: DVec3::ZERO,
        up: DVec3::Z,
        view_field_deg: 35.0,
    });
    let prepared = PreparedScene::new(&ValidScene::new(scene.clone()).unwrap()).unwrap();
    let camera = Camera::new(&scene.camera, 48, 48);
    let mut ws = Workspace::new();
    let mut checked = 0;
    for py in 0..48 {
        for px in 0..48 {
            let ray = camera.ray(f64::from(px) + 0.5, f64::from(py) + 0.5);
            let exact = exact_cone_t(&ray, y0, y1, r0, r1);
            let got = nearest_hit(&prepared, &ray, 0.0..f64::INFINITY, &mut ws).map(|(_, h)| h.t);
            match (exact, got) {
                (None, None) => {}
                (Some(t), Some(g)) => {
                    checked += 1;
                    // ROOT_X_TOL_REL × diagonal ≈ 1e-9 in t, plus the rounding of both forms.
                    assert!((g - t).abs() <= 1e-8 * t, "pixel ({px},{py}): {g} vs {t}");
                }
                // A ray grazing the rims may fall either way within the tolerance.
                (e, g) => {
                    let t = e.or(g).unwrap();
                    let p = ray.at(t);
                    let at_rim = (p.y - y0).abs() < 1e-6 || (p.y - y1).abs() < 1e-6;
                    assert!(at_rim, "pixel ({px},{py}): exact {e:?}, traced {g:?}");
                }
            }
        }
    }
    assert!(checked > 200, "enough pixels hit the cone: {checked}");
}

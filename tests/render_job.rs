//! `render::render_scene`, the library call behind the `render` binary: option overrides,
//! PNG and PFM outputs, atomic writes, errors that name the file.

use render::glam::DVec3;
use render::scene::{Object, Scene, ShapeKind, ValidScene};
use render::{Gamma, PngOptions, RenderOptions, read_pfm, render_scene};

fn sphere_scene() -> ValidScene {
    let mut scene = Scene::default();
    scene.objects.push(Object::new(ShapeKind::Sphere {
        center: DVec3::ZERO,
        radius: 1.5,
    }));
    scene.lights.push(render::scene::Light {
        source: DVec3::new(3.0, -4.0, 6.0),
        color: DVec3::ONE,
    });
    ValidScene::new(scene).expect("a valid scene")
}

#[test]
fn writes_png_with_size_override_alpha_and_depth() {
    let dir = tempfile::tempdir().unwrap();
    let png = dir.path().join("out.png");
    let pfm = dir.path().join("depth.pfm");
    let opts = RenderOptions {
        output: Some(png.clone()),
        size: Some([40, 30]),
        depth: Some(pfm.clone()),
        png: PngOptions {
            bits: 16,
            alpha: true,
            gamma: Gamma::Srgb,
        },
        threads: Some(2),
        ..RenderOptions::default()
    };
    let report = render_scene(&sphere_scene(), None, &opts, &|_, _| {}).unwrap();
    assert_eq!(report.png_path, png, "-o wins");
    let img = image::open(&png).unwrap();
    assert_eq!(
        (img.width(), img.height()),
        (40, 30),
        "--size overrides the viewport"
    );
    assert_eq!(img.color(), image::ColorType::Rgba16, "16-bit RGBA");
    let rgba = img.to_rgba16();
    assert_eq!(
        rgba.get_pixel(0, 0)[3],
        0,
        "background corner is transparent"
    );
    assert_eq!(
        rgba.get_pixel(20, 15)[3],
        65535,
        "the sphere in the middle is opaque"
    );
    let (w, h, d) = read_pfm(&std::fs::read(&pfm).unwrap()).unwrap();
    assert_eq!((w, h), (40, 30), "depth map size");
    assert!(d[0].is_infinite(), "miss → +inf");
    // The ray through pixel (20, 15) hits the radius-1.5 sphere at the smaller root of
    // t² + 2(o·d)t + |o|² − r² (unit d): compare with the closed form, to f32 precision.
    let scene = sphere_scene();
    let ray = render::Camera::new(&scene.camera, 40, 30).ray(20.5, 15.5);
    let (b, c) = (ray.origin.dot(ray.dir), ray.origin.length_squared() - 2.25);
    let exact = -b - (b * b - c).sqrt();
    let centre = f64::from(d[15 * 40 + 20]);
    assert!(
        (centre - exact).abs() <= 1e-6 * exact,
        "centre depth {centre} vs {exact}"
    );
    assert_eq!(
        report.output.stats.primary_rays,
        40 * 30,
        "one primary ray per pixel"
    );
}

#[test]
fn failures_keep_existing_files_and_name_the_path() {
    let dir = tempfile::tempdir().unwrap();
    let png = dir.path().join("keep.png");
    std::fs::write(&png, b"precious").unwrap();
    // An invalid scene cannot reach `render_scene`: `ValidScene::new` refuses it, naming the
    // object and key.
    let mut bad: Scene = sphere_scene().into_scene();
    bad.objects.push(Object::new(ShapeKind::Sphere {
        center: DVec3::ZERO,
        radius: -1.0,
    }));
    let err = ValidScene::new(bad).unwrap_err();
    let msg = format!("{:#}", anyhow::Error::from(err));
    assert!(
        msg.contains("object 2") && msg.contains("Radius"),
        "names the object and key: {msg}"
    );

    let missing = dir.path().join("no/such/dir/out.png");
    let opts = RenderOptions {
        output: Some(missing.clone()),
        size: Some([8, 8]),
        ..RenderOptions::default()
    };
    let err = render_scene(&sphere_scene(), None, &opts, &|_, _| {}).unwrap_err();
    let msg = format!("{:#}", anyhow::Error::from(err));
    assert!(
        msg.contains("no/such/dir/out.png"),
        "names the output path: {msg}"
    );
    let zero = RenderOptions {
        output: Some(png.clone()),
        samples: 0,
        ..RenderOptions::default()
    };
    assert!(
        render_scene(&sphere_scene(), None, &zero, &|_, _| {}).is_err(),
        "samples 0 refused"
    );
    assert_eq!(
        std::fs::read(&png).unwrap(),
        b"precious",
        "nothing overwritten by the failed render"
    );
}

#[test]
fn output_is_deterministic_across_thread_counts() {
    let dir = tempfile::tempdir().unwrap();
    let render_with = |threads: usize| {
        let path = dir.path().join(format!("t{threads}.png"));
        let opts = RenderOptions {
            output: Some(path.clone()),
            size: Some([33, 21]),
            samples: 3,
            threads: Some(threads),
            ..RenderOptions::default()
        };
        let report = render_scene(&sphere_scene(), None, &opts, &|_, _| {}).unwrap();
        (
            std::fs::read(&path).unwrap(),
            report.output.stats.primary_rays,
        )
    };
    let (one, rays1) = render_with(1);
    let (two, rays2) = render_with(2);
    assert_eq!(one, two, "same bytes with 1 and 2 threads");
    assert_eq!(rays1, 33 * 21 * 9, "3×3 samples per pixel");
    assert_eq!(rays1, rays2, "same work");
}

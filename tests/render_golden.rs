//! Golden images: the scenes in `scenes/` rendered at 64×64 and compared with committed PNGs
//! in `tests/golden/`. `TOOLKIT_BLESS=1 cargo test -p toolkit-tests render_golden` rewrites
//! them. On a mismatch the actual image and a diff image are written under
//! `target/golden-failures/`.

use std::path::{Path, PathBuf};

use render::{PngOptions, PreparedScene, RenderSettings, render, write_png};

/// Largest per-channel difference (8-bit codes) a pixel may show and still count as equal:
/// covers libm differences in `pow`/`sin` between platforms.
const MAX_CHANNEL_DIFF: u8 = 2;
/// Largest fraction of pixels allowed to differ by more than [`MAX_CHANNEL_DIFF`]: a handful
/// of silhouette pixels whose root sits within the tolerance of a pixel-centre ray.
const MAX_DIFFERING_FRACTION: f64 = 0.005;
/// Golden image side in pixels (≤ 128, so committed PNGs stay under 16 KiB).
const SIDE: u32 = 64;

fn workspace_root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .parent()
        .expect("tests/ has a parent")
        .to_path_buf()
}

fn check(scene_name: &str) {
    check_file(&format!("{scene_name}.scene"), scene_name);
}

/// [`check`] for the scene file `scenes/FILE` (any format) against `tests/golden/NAME.png`.
fn check_file(file: &str, scene_name: &str) {
    let root = workspace_root();
    let scene_path = root.join("scenes").join(file);
    let scene = render::scene::load(&scene_path).unwrap_or_else(|e| panic!("{e}"));
    let prepared = PreparedScene::new(&scene).expect("valid scene");
    let settings = RenderSettings {
        size: [SIDE, SIDE],
        resolution: [1, 1],
        samples: 1,
        depth: false,
    };
    let out = render(&prepared, &scene.camera, &settings, &|_| {});
    let tmp = tempfile::tempdir().unwrap();
    let actual_path = tmp.path().join("actual.png");
    write_png(&out.film, &actual_path, &PngOptions::default()).unwrap();
    let golden = root.join("tests/golden").join(format!("{scene_name}.png"));
    if std::env::var_os("TOOLKIT_BLESS").is_some() {
        std::fs::copy(&actual_path, &golden).unwrap();
        return;
    }
    let actual = image::open(&actual_path).unwrap().to_rgb8();
    let expected = image::open(&golden)
        .unwrap_or_else(|e| {
            panic!(
                "{}: {e} (run with TOOLKIT_BLESS=1 to create)",
                golden.display()
            )
        })
        .to_rgb8();
    assert_eq!(
        actual.dimensions(),
        expected.dimensions(),
        "{scene_name}: size"
    );
    let mut diff = image::RgbImage::new(SIDE, SIDE);
    let mut differing = 0usize;
    let mut worst = 0u8;
    for (x, y, a) in actual.enumerate_pixels() {
        let e = expected.get_pixel(x, y);
        let d = (0..3).map(|c| a[c].abs_diff(e[c])).max().unwrap_or(0);
        worst = worst.max(d);
        if d > MAX_CHANNEL_DIFF {
            differing += 1;
        }
        let v = d.saturating_mul(8);
        diff.put_pixel(x, y, image::Rgb([v, v, v]));
    }
    let fraction = differing as f64 / f64::from(SIDE * SIDE);
    if fraction > MAX_DIFFERING_FRACTION {
        let dir = root.join("target/golden-failures");
        std::fs::create_dir_all(&dir).unwrap();
        let a = dir.join(format!("{scene_name}.actual.png"));
        let d = dir.join(format!("{scene_name}.diff.png"));
        std::fs::copy(&actual_path, &a).unwrap();
        diff.save(&d).unwrap();
        panic!(
            "{scene_name}: {differing} pixels ({:.2}%) differ by more than {MAX_CHANNEL_DIFF} \
             (worst {worst}); wrote {} and {}",
            fraction * 100.0,
            a.display(),
            d.display()
        );
    }
}

#[test]
fn golden_torus() {
    check("torus");
}

#[test]
fn golden_whitted_torus() {
    check("whitted-torus");
}

#[test]
fn golden_stam_torus() {
    check("stam-torus");
}

#[test]
fn golden_barth() {
    check("barth");
}

#[test]
fn golden_spheres() {
    check("spheres");
}

/// The smallest SPD sphereflake (10 spheres over a polygon, 3 lights), read from NFF.
#[test]
fn golden_spd_balls_s1() {
    check_file("spd/balls-s1.nff", "spd-balls-s1");
}

/// Every scene in `scenes/` renders at a small size, and each golden file is small.
#[test]
fn every_scene_renders_small_and_goldens_stay_small() {
    let root = workspace_root();
    for entry in std::fs::read_dir(root.join("scenes")).unwrap() {
        let path = entry.unwrap().path();
        if path.extension().is_some_and(|e| e == "scene") {
            let scene = render::scene::load(&path).unwrap_or_else(|e| panic!("{e}"));
            let prepared =
                PreparedScene::new(&scene).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
            let settings = RenderSettings {
                size: [24, 24],
                resolution: [1, 1],
                samples: 1,
                depth: true,
            };
            let out = render(&prepared, &scene.camera, &settings, &|_| {});
            let hits = out
                .film
                .depth
                .unwrap()
                .iter()
                .filter(|d| d.is_finite())
                .count();
            assert!(hits > 0, "{}: something is visible", path.display());
        }
    }
    for entry in std::fs::read_dir(root.join("tests/golden")).unwrap() {
        let path = entry.unwrap().path();
        let len = std::fs::metadata(&path).unwrap().len();
        assert!(
            len <= 16 * 1024,
            "{} is {len} bytes (limit 16 KiB)",
            path.display()
        );
    }
}

//! Every `--isolation` method on every scene of `scenes/` (issue 13, "the libraries": `render
//! --isolation stam` lost every plane — the floor of `stam-torus.scene` vanished — because
//! the Sturm methods answered `inf` for a line over `(0, ∞]`). The CLI holds no rendering
//! logic: `--isolation` sets [`RootMethods::isolation`] of the options rendered here.

use std::path::{Path, PathBuf};

use poly::IsolationMethod;
use render::scene::{ShapeKind, load};
use render::{RenderOptions, RootMethods, prepare_render, render};

/// Depths agree to this relative difference: the renderer's root tolerance is `2^-33` of an
/// object's box diagonal (about 1e-10 relative at these depths), far below it; a lost or
/// absurd root (`inf`, `1.797e308`) is a miss or a depth off by orders of magnitude.
const DEPTH_REL: f64 = 1e-6;

fn scenes() -> Vec<PathBuf> {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../scenes");
    let mut files = Vec::new();
    for (dir, ext) in [(root.clone(), "scene"), (root.join("spd"), "nff")] {
        files.extend(
            std::fs::read_dir(dir)
                .expect("scenes/ exists")
                .map(|e| e.expect("a directory entry").path())
                .filter(|p| p.extension().is_some_and(|e| e == ext)),
        );
    }
    files.sort();
    files
}

/// The 12 × 9 depth map of `file` rendered with `isolation`, and how many root queries the
/// method refused ([`poly::RootStats::unresolved`]).
fn depths(file: &Path, isolation: IsolationMethod) -> (Vec<f32>, u64) {
    let scene = load(file).unwrap_or_else(|e| panic!("{e}"));
    let opts = RenderOptions {
        size: Some([12, 9]),
        depth: Some(PathBuf::from("unused.pfm")),
        roots: RootMethods {
            isolation,
            ..RootMethods::default()
        },
        ..RenderOptions::default()
    };
    let (prepared, settings) = prepare_render(&scene, &opts).unwrap();
    let out = render(&prepared, &scene.camera, &settings, &|_| {});
    let refused = out.stats.roots.unresolved;
    (out.film.depth.expect("asked for depth"), refused)
}

#[test]
fn every_isolation_method_renders_every_scene_as_the_exact_reference() {
    let mut checked = 0;
    for file in scenes() {
        let scene = load(&file).unwrap_or_else(|e| panic!("{e}"));
        // Bézier patches eliminate with their own `Method`; `--isolation` does not reach them.
        if scene
            .objects
            .iter()
            .all(|o| matches!(o.shape, ShapeKind::BezierPatches { .. }))
        {
            continue;
        }
        // The exact reference restricts each ray exactly (issue 11): at degree 64 (153 terms)
        // that is 0.17 s a ray in release, minutes here. That scene's certified hits are
        // checked against its quartic instead (`r11_degree_64_power_matches_its_quartic`);
        // against the true reference the Sturm heuristics miss it (pixel 88: depth 12.13 vs
        // 11.62), which the rounded-restriction reference used to hide.
        if file.file_stem().is_some_and(|s| s == "quartic-power64") {
            continue;
        }
        let (reference, _) = depths(&file, IsolationMethod::Exact);
        assert!(
            reference.iter().any(|d| d.is_finite()),
            "{}: something is hit",
            file.display()
        );
        for method in [
            IsolationMethod::Bernstein,
            IsolationMethod::Sturm,
            IsolationMethod::StamSturm,
        ] {
            let (got, refused) = depths(&file, method);
            let mut differing = Vec::new();
            for (i, (g, r)) in got.iter().zip(&reference).enumerate() {
                let same = (g.is_infinite() && r.is_infinite())
                    || f64::from((g - r).abs()) <= DEPTH_REL * f64::from(r.abs()).max(1.0);
                if !same {
                    differing.push(format!("pixel {i}: depth {g} vs exact {r}"));
                }
            }
            // The certified method must match everywhere. A heuristic may refuse a query it
            // cannot count (`RootError::Unresolved`, counted in the statistics; issue 11: the
            // Sturm methods now refuse where rounding decides a sign, e.g. a degree-16 sheet
            // ray of `torus-sheets16.scene`), and such a ray is a miss; but every differing
            // pixel must be covered by a refusal, so a silent wrong answer still fails.
            let allowed = if method == IsolationMethod::Bernstein {
                0
            } else {
                refused
            };
            assert!(
                differing.len() as u64 <= allowed,
                "{} {method:?}: {} pixels differ from the exact reference, {refused} queries \
                 refused: {differing:?}",
                file.display(),
                differing.len()
            );
        }
        checked += 1;
    }
    assert!(checked >= 8, "{checked} scenes checked");
}

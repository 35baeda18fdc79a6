//! Every scene in `scenes/` parses, round-trips through the printer, and `torus.scene` holds
//! exactly the parameters of the `render` issue.

use std::path::{Path, PathBuf};

use glam::DVec3;
use render::scene::{
    BoundingVolume, CameraSpec, Illumination, LookAtCamera, ShapeKind, Texture, load, parse_syntax,
    print,
};

fn scenes_dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../scenes")
}

/// All `*.scene` files directly in `scenes/`, sorted.
fn scene_files() -> Vec<PathBuf> {
    let mut files: Vec<PathBuf> = std::fs::read_dir(scenes_dir())
        .expect("scenes/ exists")
        .map(|e| e.expect("readable directory entry").path())
        .filter(|p| p.extension().is_some_and(|e| e == "scene"))
        .collect();
    files.sort();
    files
}

#[test]
fn every_scene_parses_and_round_trips() {
    let files = scene_files();
    for name in [
        "torus",
        "whitted-torus",
        "stam-torus",
        "stam-torus-transparent",
        "barth",
        "spheres",
    ] {
        assert!(
            files
                .iter()
                .any(|f| f.file_stem().is_some_and(|s| s == name)),
            "scenes/{name}.scene is missing"
        );
    }
    for file in &files {
        let scene = load(file).unwrap_or_else(|e| panic!("{e}"));
        assert!(!scene.objects.is_empty(), "{} has objects", file.display());
        let text = std::fs::read_to_string(file).expect("readable scene");
        let ast = parse_syntax(&text, file).expect("parses");
        let printed = print(&ast);
        let again = parse_syntax(&printed, file)
            .unwrap_or_else(|e| panic!("printed {}: {e}\n{printed}", file.display()));
        assert_eq!(
            again,
            ast,
            "{} round-trips through the printer",
            file.display()
        );
    }
}

#[test]
fn torus_scene_matches_the_issue() {
    let scene = load(&scenes_dir().join("torus.scene")).expect("torus.scene loads");
    assert_eq!(scene.world.background, DVec3::splat(0.2), "background 0.2");
    assert!(scene.world.shadows, "Shadows ON");
    assert_eq!(
        scene.camera,
        CameraSpec::LookAt(LookAtCamera {
            eye: DVec3::new(0.0, -8.0, 5.0),
            look_at: DVec3::ZERO,
            up: DVec3::Z,
            view_field_deg: 50.0,
        }),
        "camera"
    );
    assert_eq!(scene.lights.len(), 1, "one light");
    assert_eq!(
        scene.lights[0].source,
        DVec3::new(5.0, -5.0, 10.0),
        "light position"
    );
    assert_eq!(scene.lights[0].color, DVec3::ONE, "light colour 1");
    assert_eq!(scene.objects.len(), 1, "one object");
    let torus = &scene.objects[0];
    assert_eq!(
        torus.shape,
        ShapeKind::Torus {
            center: DVec3::ZERO,
            axis: DVec3::Z,
            major: 2.0,
            minor: 1.0
        },
        "torus"
    );
    let m = &torus.material;
    assert_eq!(m.cs, DVec3::new(0.8, 0.3, 0.2), "Cs");
    assert_eq!(m.cr, DVec3::ONE, "Cr");
    assert_eq!(
        [m.ka, m.kd, m.ks, m.kt, m.n],
        [0.1, 0.7, 0.5, 0.0, 40.0],
        "Ka Kd Ks Kt n"
    );
    assert_eq!(scene.viewport.size, [840, 840], "840×840");
    assert_eq!(scene.viewport.resolution, [1, 1], "every pixel traced");
}

#[test]
fn whitted_torus_is_the_glass_torus_over_a_checkered_mirror() {
    let scene = load(&scenes_dir().join("whitted-torus.scene")).expect("loads");
    let torus = load(&scenes_dir().join("torus.scene"))
        .expect("loads")
        .into_scene()
        .objects
        .remove(0);
    assert_eq!(scene.world.max_depth, 5, "MaxDepth 5");
    let glass = &scene.objects[0];
    assert_eq!(glass.shape, torus.shape, "the same torus");
    assert_eq!(
        glass.material.illumination,
        Illumination::Transparent,
        "transparent"
    );
    assert_eq!(
        (glass.material.kt, glass.material.kn),
        (0.7, 1.5),
        "Kt 0.7, Kn 1.5"
    );
    let floor = &scene.objects[1];
    assert_eq!(
        floor.shape,
        ShapeKind::Plane {
            origin: DVec3::new(0.0, 0.0, -1.5),
            normal: DVec3::Z
        },
        "z = -1.5"
    );
    assert_eq!(
        floor.material.illumination,
        Illumination::Mirror,
        "reflective"
    );
    let index = floor.material.texture.expect("textured floor");
    assert!(
        matches!(scene.textures[index], Texture::Checker(_)),
        "checkered"
    );
}

#[test]
fn stam_and_barth_equations_expand_to_the_papers_polynomials() {
    for name in ["stam-torus", "stam-torus-transparent"] {
        let scene = load(&scenes_dir().join(format!("{name}.scene"))).expect("loads");
        let ShapeKind::Algebraic { poly } = &scene.objects[0].shape else {
            panic!("{name}: algebraic")
        };
        // Annexe B `Polynomial`: F = (x²+y²)² − 10(x²+y²) + 9 + 15z².
        let want = render::Poly3::from_terms([
            (1.0, [4, 0, 0]),
            (2.0, [2, 2, 0]),
            (1.0, [0, 4, 0]),
            (-10.0, [2, 0, 0]),
            (-10.0, [0, 2, 0]),
            (15.0, [0, 0, 2]),
            (9.0, [0, 0, 0]),
        ]);
        assert_eq!(*poly, want, "{name}: Stam's quartic");
        assert!(
            matches!(scene.camera, CameraSpec::Stam(_)),
            "{name} uses Stam's camera"
        );
    }
    let scene = load(&scenes_dir().join("barth.scene")).expect("loads");
    let ShapeKind::Algebraic { poly } = &scene.objects[0].shape else {
        panic!("barth: algebraic")
    };
    assert_eq!(poly.degree(), 6, "a sextic");
    let phi = (1.0 + 5f64.sqrt()) / 2.0;
    // 4(φ⁶ − 1) x²y²z² from the product; −(1 + 2φ) constant from the square.
    let coeff = |e: [u32; 3]| {
        poly.terms()
            .iter()
            .find(|t| t.exps == e)
            .map_or(0.0, |t| t.coeff)
    };
    let close = |a: f64, b: f64| (a - b).abs() <= 1e-12 * b.abs();
    assert!(
        close(coeff([2, 2, 2]), 4.0 * (phi.powi(6) - 1.0)),
        "x²y²z²: {}",
        coeff([2, 2, 2])
    );
    assert!(
        close(coeff([0, 0, 0]), -(1.0 + 2.0 * phi)),
        "constant: {}",
        coeff([0, 0, 0])
    );
    assert_eq!(
        scene.objects[0].bounding,
        BoundingVolume::Box {
            min: DVec3::splat(-2.0),
            max: DVec3::splat(2.0)
        },
        "clipped to the radius-2 box"
    );
}

#[test]
fn unreadable_file_names_the_path_and_the_reason() {
    let missing = scenes_dir().join("no-such.scene");
    let err = load(&missing).expect_err("no such file");
    assert_eq!(
        err.to_string(),
        format!("cannot read {}", missing.display()),
        "message"
    );
    let source = std::error::Error::source(&err).expect("the io error is the source");
    assert!(source.to_string().contains("No such file"), "{source}");
    assert!(err.span().is_none(), "no place in a text");
}

/// The patch of `saddle.pts`, given three ways: Stam's `Control points in FILE`, the `=` form,
/// and the 16 points inline (over two lines); all three build the same patch.
#[test]
fn bezier_patch_points_from_a_file_stam_form_or_inline() {
    let dir = scenes_dir();
    let pts = std::fs::read_to_string(dir.join("saddle.pts")).expect("saddle.pts");
    let points: Vec<String> = pts
        .lines()
        .filter(|l| !l.trim().is_empty() && !l.trim_start().starts_with("//"))
        .map(|l| {
            let xyz: Vec<&str> = l.split_whitespace().collect();
            format!("({})", xyz.join(", "))
        })
        .collect();
    assert_eq!(points.len(), 16, "saddle.pts holds a bicubic net");
    let camera = "#camera Eye = (30,-40,35) LookAt = (0,0,0) ViewField = 45\n";
    let object = |control: &str| {
        format!("{camera}#object Type = BEZIER_PATCH\n{control}\nIllumination = DIFFUSE\n")
    };
    let patch_of = |control: &str| {
        let scene = render::scene::parse(&object(control), &dir.join("inline.scene"))
            .unwrap_or_else(|e| panic!("{control}: {e}"));
        match &scene.objects[0].shape {
            ShapeKind::BezierPatches { patches, .. } => patches.clone(),
            other => panic!("not a patch: {other:?}"),
        }
    };
    let from_file = patch_of("Control points = saddle.pts");
    assert_eq!(from_file.len(), 1);
    assert_eq!(
        patch_of("Control points in saddle.pts"),
        from_file,
        "Stam's form"
    );
    let inline = format!(
        "Control points = {}\n  {}",
        points[..8].join(" "),
        points[8..].join(" ")
    );
    assert_eq!(patch_of(&inline), from_file, "inline points");
    // The inline form round-trips through the printer.
    let ast = parse_syntax(&object(&inline), Path::new("inline.scene")).expect("parses");
    let again = parse_syntax(&print(&ast), Path::new("inline.scene")).expect("printed parses");
    assert_eq!(print(&again), print(&ast));
}

#[test]
fn inline_control_points_errors_name_the_place() {
    let dir = scenes_dir();
    let camera = "#camera Eye = (30,-40,35) LookAt = (0,0,0) ViewField = 45\n";
    let error = |object: &str| {
        render::scene::parse(&format!("{camera}{object}"), &dir.join("bad.scene"))
            .expect_err(object)
            .to_string()
    };
    let fifteen = vec!["(0, 0, 0)"; 15].join(" ");
    let e = error(&format!(
        "#object Type = BEZIER_PATCH\nControl points = {fifteen}"
    ));
    assert!(
        e.starts_with(&format!("{}:3:18:", dir.join("bad.scene").display())),
        "{e}"
    );
    assert!(e.contains("16 control points, found 15"), "{e}");
    let e = error("#object Type = BEZIER_PATCH\nControl points = (0, 0, 0) (1, 2)");
    assert!(e.contains(":3:28:") && e.contains("2 components"), "{e}");
    let e = error(&format!(
        "#object Type = BEZIER_MESH\nControl points = {fifteen} (0,0,0)"
    ));
    assert!(e.contains(".bpt file"), "{e}");
}

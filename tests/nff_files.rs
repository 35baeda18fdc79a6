//! NFF input: every entity read from a small file into the scene model, malformed lines
//! reported at `file:line:col`, the format chosen by extension and by content, and the SPD
//! scenes in `scenes/spd/` read whole.

use std::path::{Path, PathBuf};

use render::glam::DVec3;
use render::scene::{CameraSpec, Illumination, ShapeKind, is_nff, load, parse_nff};

fn workspace_root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .parent()
        .expect("tests/ has a parent")
        .to_path_buf()
}

const ALL_ENTITIES: &str = "\
# every entity once
v
from 1 2 3
at 0 0 0
up 0 0 1
angle 40
hither 0.5
resolution 320 200
b 0.1 0.2 0.3
l 4 5 6
l -4 5 6 0.5 0.25 1   # a coloured light
f 1 0.5 0.25 0.6 0.3 12 0 1
s 0 0 1 0.75
f 0.2 0.4 0.6 0.2 0 5 0.8 1.5
p 3
0 0 0
1 0 0
0 1 0
p 4
0 0 1
1 0 1
1 1 1
0 1 1
pp 3
0 0 2 0 0 1
1 0 2 0 0.1 1
0 1 2 0.1 0 1
c
0 0 0 1
0 0 2 0.5
";

#[test]
fn every_entity_reaches_the_scene_model() {
    let scene = parse_nff(ALL_ENTITIES, Path::new("all.nff")).expect("valid NFF");
    let CameraSpec::LookAt(cam) = &scene.camera else {
        panic!("a look-at camera");
    };
    assert_eq!(cam.eye, DVec3::new(1.0, 2.0, 3.0));
    assert_eq!(cam.up, DVec3::Z);
    assert_eq!(cam.view_field_deg, 40.0);
    assert_eq!(scene.viewport.size, [320, 200]);
    assert_eq!(scene.world.background, DVec3::new(0.1, 0.2, 0.3));
    assert_eq!(scene.lights.len(), 2);
    // One uncoloured light: it gets the whole unit intensity (1/√1); the other keeps its own.
    assert_eq!(scene.lights[0].color, DVec3::ONE);
    assert_eq!(scene.lights[1].color, DVec3::new(0.5, 0.25, 1.0));
    let kinds: Vec<&str> = scene.objects.iter().map(|o| o.shape.type_name()).collect();
    assert_eq!(
        kinds,
        ["SPHERE", "TRIANGLE", "POLYGON", "POLYGON_PATCH", "CONE"]
    );
    // `f` applies to the objects after it: the sphere is mirror-like, the rest transparent.
    let m = &scene.objects[0].material;
    assert_eq!(m.illumination, Illumination::Mirror);
    assert_eq!((m.kd, m.ks, m.n, m.kt), (0.6, 0.3, 12.0, 0.0));
    assert!((m.ka - 0.1).abs() < 1e-15, "k_a = 1 − Kd − Ks: {}", m.ka);
    let glass = &scene.objects[1].material;
    assert_eq!(glass.illumination, Illumination::Transparent);
    assert_eq!((glass.kt, glass.kn, glass.ka), (0.8, 1.5, 0.0));
    match &scene.objects[3].shape {
        ShapeKind::SmoothPolygon { vertices, normals } => {
            assert_eq!(vertices.len(), 3);
            assert_eq!(normals[1], DVec3::new(0.0, 0.1, 1.0));
        }
        other => panic!("pp read as {other:?}"),
    }
    match &scene.objects[4].shape {
        ShapeKind::Cone {
            base_radius,
            apex,
            apex_radius,
            caps,
            ..
        } => {
            assert_eq!((*base_radius, *apex_radius, *caps), (1.0, 0.5, false));
            assert_eq!(*apex, DVec3::new(0.0, 0.0, 2.0));
        }
        other => panic!("c read as {other:?}"),
    }
    assert!(scene.validate().is_ok());
}

/// The SPD's gears write index 0 for opaque materials (`f … 0 0`): read as 1, not refused.
#[test]
fn opaque_material_with_index_zero_is_accepted() {
    let scene = parse_nff(
        "f 1 0.85 0.7 0.3 0.6 3.0827 0 0\ns 0 0 0 1\n",
        Path::new("g.nff"),
    )
    .expect("gears' materials are valid");
    assert_eq!(scene.objects[0].material.kn, 1.0);
    assert!(scene.validate().is_ok());
}

#[test]
fn uncoloured_lights_share_a_unit_intensity() {
    let scene = parse_nff("l 0 0 5\nl 1 0 5\nl 2 0 5\nl 3 0 5\n", Path::new("l.nff")).unwrap();
    assert!(scene.lights.iter().all(|l| l.color == DVec3::splat(0.5)));
}

#[test]
fn malformed_lines_name_file_line_and_column() {
    let cases: &[(&str, &str)] = &[
        (
            "s 0 0 0\n",
            "x.nff:1:8: expected the sphere's radius (a number), found end of line",
        ),
        (
            "s 0 0 0 1 2\n",
            "x.nff:1:11: expected end of line, found `2`",
        ),
        (
            "\n# c\ns 0 0 x 1\n",
            "x.nff:3:7: expected the sphere's centre (a number), found `x`",
        ),
        (
            "q 1 2\n",
            "x.nff:1:1: expected an NFF entity (v, b, l, f, c, s, p, pp or # comment), found `q`",
        ),
        (
            "p 3\n0 0 0\n1 0 0\n",
            "x.nff:3:6: expected a line with a vertex, found end of file",
        ),
        (
            "p 3\n0 0 0\n1 0\n0 1 0\n",
            "x.nff:3:4: expected a vertex (a number), found end of line",
        ),
        (
            "p -2\n",
            "x.nff:1:3: expected a whole number from 0 to 65536, found `-2`",
        ),
        (
            "v\nfrom 0 0 5\nup 0 0 1\n",
            "x.nff:3:1: expected `at` in the view entity, found `up`",
        ),
        (
            "s 0 0 0 0\n",
            "x.nff:1:1: invalid `sphere`: radius must be a positive finite number",
        ),
        (
            "f 1 1 1 0.5 0.5 3 0\n",
            "x.nff:1:20: expected the index of refraction (a number), found end of line",
        ),
        (
            "f 1 1 1 0.5 0 3 0.5 0\n",
            "x.nff:1:21: invalid `f`: the index of refraction of a transparent material must be positive, found 0",
        ),
        (
            "p 3\n0 0 0\n1 1 1\n2 2 2\n",
            "x.nff:1:1: invalid `triangle`: the triangle has zero area",
        ),
    ];
    for (text, expected) in cases {
        let err = parse_nff(text, Path::new("x.nff")).expect_err(text);
        assert_eq!(err.to_string(), *expected, "for {text:?}");
    }
}

/// Issue 10 (validation once per load). Caught: an NFF file's scene-level invariants (here a
/// view whose `from` equals its `at`) were checked only when the render prepared the scene,
/// a second validation that could not say where the problem was. The loader now runs the
/// checks once, at the end of the load, and names the `v` line; the renderer takes the
/// checked scene (`ValidScene`) without checking it again.
#[test]
fn r10_nff_view_is_checked_by_the_loader_at_its_line() {
    let text = "s 0 0 0 1\nv\nfrom 1 1 1\nat 1 1 1\nup 0 0 1\nangle 40\nhither 1\nresolution 8 8\n";
    let err = parse_nff(text, Path::new("x.nff")).expect_err("from = at");
    assert_eq!(
        err.to_string(),
        "x.nff:2:1: camera: Eye and LookAt must differ",
        "located at the view entity"
    );
}

#[test]
fn format_is_chosen_by_extension_then_by_content() {
    let nff = "# a comment\nv\nfrom 0 0 5\n";
    let stam = "#camera\nEye = (0, -8, 5)\n";
    assert!(is_nff(Path::new("a.nff"), stam), "the extension decides");
    assert!(!is_nff(Path::new("a.scene"), nff), "the extension decides");
    assert!(is_nff(Path::new("noext"), nff), "NFF content");
    assert!(!is_nff(Path::new("noext"), stam), "scene-language content");
    // A scene-language polygon key `b = (…)` is not NFF's `b` entity.
    assert!(!is_nff(
        Path::new("noext"),
        "#object Type = TRIANGLE\nb = (1, 0, 0)\n"
    ));
    // Both formats reach the same model: a file without extension is read as NFF.
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("sphere");
    std::fs::write(&path, "s 0 0 0 2\n").unwrap();
    let scene = load(&path).expect("loads as NFF");
    assert!(matches!(
        scene.objects[0].shape,
        ShapeKind::Sphere { radius: 2.0, .. }
    ));
}

#[test]
fn spd_scenes_read_whole() {
    let dir = workspace_root().join("scenes/spd");
    for (name, objects, lights) in [("balls-s1.nff", 11, 3), ("balls-s2.nff", 92, 3)] {
        let scene = load(&dir.join(name)).unwrap_or_else(|e| panic!("{e}"));
        assert_eq!(scene.objects.len(), objects, "{name}: objects");
        assert_eq!(scene.lights.len(), lights, "{name}: lights");
        assert_eq!(scene.viewport.size, [512, 512], "{name}: SPD resolution");
    }
}

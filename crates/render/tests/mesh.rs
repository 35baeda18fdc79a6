//! `Type = MESH`: a Wavefront OBJ file traced as one object, the same image as its triangles
//! written as `TRIANGLE` objects, and errors in the file located by file, line and column.

use render::scene::{ValidScene, parse};
use render::{PreparedScene, RenderSettings, render};

const CAMERA: &str = "#camera Eye = (3,-8,5) LookAt = (0,0,0) ViewField = 40\n\
                      #light Source = (5,-5,10) Color = (1,1,1)\n";

/// A non-convex 12-triangle shape: a unit cube's faces, the top face's centre raised to a
/// peak (a pyramid on a box).
const SHAPE: &str = "v -1 -1 -1\nv 1 -1 -1\nv 1 1 -1\nv -1 1 -1\n\
                     v -1 -1 1\nv 1 -1 1\nv 1 1 1\nv -1 1 1\nv 0 0 2\n\
                     f 1 4 3 2\nf 1 2 6 5\nf 2 3 7 6\nf 3 4 8 7\nf 4 1 5 8\n\
                     f 5 6 9\nf 6 7 9\nf 7 8 9\nf 8 5 9\n";

/// The object keys both renderings share: a placement and a material.
const KEYS: &str = "Translate = (0.3, -0.2, 0.1) Rotate = (10, 20, 30) Scale = (1, 1.2, 0.8) \
                    Illumination = SPECULAR Kd = 0.7 Ks = 0.3 N = 20 Cs = (0.9, 0.5, 0.2)";

fn image(scene: &ValidScene) -> Vec<[f32; 4]> {
    let prepared = PreparedScene::new(scene).unwrap();
    let settings = RenderSettings {
        size: [64, 48],
        resolution: [1, 1],
        samples: 1,
        depth: true,
    };
    render(&prepared, &scene.camera, &settings, &|_| {})
        .film
        .pixels
}

/// The mesh renders pixel for pixel as its 14 triangles (the quads cut into the same fans)
/// given one by one, placed and lit alike; most pixels are covered.
#[test]
fn a_mesh_renders_as_its_triangles() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join("shape.obj"), SHAPE).unwrap();
    let scene_path = dir.path().join("m.scene");
    let mesh = parse(
        &format!("{CAMERA}#object Type = MESH File Name = shape.obj {KEYS}\n"),
        &scene_path,
    )
    .unwrap();
    let data = render::scene::parse_obj(SHAPE).unwrap();
    let mut triangles = String::from(CAMERA);
    for t in &data.triangles {
        let [a, b, c] = t.map(|i| data.positions[i as usize]);
        triangles += &format!(
            "#object Type = TRIANGLE a = ({}, {}, {}) b = ({}, {}, {}) c = ({}, {}, {}) {KEYS}\n",
            a.x, a.y, a.z, b.x, b.y, b.z, c.x, c.y, c.z
        );
    }
    let separate = parse(&triangles, &scene_path).unwrap();
    assert_eq!(separate.objects.len(), 14);
    let (m, s) = (image(&mesh), image(&separate));
    let covered = m.iter().filter(|p| p[3] > 0.0).count();
    assert!(covered > m.len() / 10, "only {covered} pixels covered");
    for (i, (a, b)) in m.iter().zip(&s).enumerate() {
        assert_eq!(a, b, "pixel {i}");
    }
}

/// Errors in the OBJ file name the scene's key, the file, and the line and column in it; a
/// missing file and a missing key are named too.
#[test]
fn obj_errors_name_the_file_line_and_column() {
    let dir = tempfile::tempdir().unwrap();
    let scene_path = dir.path().join("m.scene");
    std::fs::write(dir.path().join("bad.obj"), "v 0 0 0\nv 1 0 0\n\nf 1 2 7\n").unwrap();
    let err = |text: &str| {
        parse(&format!("{CAMERA}{text}"), &scene_path)
            .expect_err(text)
            .to_string()
    };
    let e = err("#object Type = MESH File Name = bad.obj\n");
    assert!(
        e.contains("m.scene:3:33")
            && e.contains("bad.obj")
            && e.contains("line 4, column 7: vertex 7 does not exist (2 read so far)"),
        "{e}"
    );
    let e = err("#object Type = MESH File Name = nothing.obj\n");
    assert!(
        e.contains("m.scene:3:33") && e.contains("nothing.obj"),
        "{e}"
    );
    let e = err("#object Type = MESH\n");
    assert!(e.contains("File Name"), "{e}");
    // The flat case: every triangle of zero area leaves no surface.
    std::fs::write(
        dir.path().join("flat.obj"),
        "v 0 0 0\nv 1 0 0\nv 2 0 0\nf 1 2 3\n",
    )
    .unwrap();
    let scene = parse(
        &format!("{CAMERA}#object Type = MESH File Name = flat.obj\n"),
        &scene_path,
    );
    let e = match scene {
        Err(e) => e.to_string(),
        Ok(s) => PreparedScene::new(&s).expect_err("no surface").to_string(),
    };
    assert!(e.contains("degenerate"), "{e}");
}

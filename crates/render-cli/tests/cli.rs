//! Tests of the `render` binary itself, run in a temporary directory. They live in the
//! `render-cli` package because Cargo gives `CARGO_BIN_EXE_render` only to the package that owns
//! the binary; everything else about rendering is tested in the workspace's `tests/` crate.

use std::path::Path;
use std::process::{Command, Output};

const SCENE: &str = "\
#world
BackGnd = (0.2,0.2,0.2)
Shadows = ON
#camera
Eye = (0,-8,5)
LookAt = (0,0,0)
Up = (0,0,1)
ViewField = 50
#light
Source = (5,-5,10)
Color = (1,1,1)
#object
Type = TORUS
Center = (0,0,0)
Axis = (0,0,1)
MajorRadius = 2
MinorRadius = 1
Illumination = SPECULAR
Cs = (0.8,0.3,0.2)
Cr = (1,1,1)
Ka = 0.1 Kd = 0.7 Ks = 0.5 Kt = 0
n = 40 Kn = 1
#viewport
Size = (24,16)
Resolution = (1,1)
#save
File Name = saved.png
";

/// Runs `render` with `args` in `dir`.
fn run(dir: &Path, args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_render"))
        .args(args)
        .current_dir(dir)
        .output()
        .expect("the render binary runs")
}

#[test]
fn renders_scene_to_its_save_file_and_prints_stats() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join("t.scene"), SCENE).unwrap();
    let out = run(dir.path(), &["t.scene", "--stats"]);
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(
        out.status.success(),
        "exit {:?}, stderr {}",
        out.status,
        String::from_utf8_lossy(&out.stderr)
    );
    let img = image::open(dir.path().join("saved.png")).expect("#save names the output");
    assert_eq!(
        (img.width(), img.height()),
        (24, 16),
        "the scene's viewport size"
    );
    assert!(
        stdout.contains("primary") && stdout.contains("384"),
        "stats list 24×16 primary rays: {stdout}"
    );
    assert!(
        stdout.contains("degree  4"),
        "quartic solves are listed: {stdout}"
    );
    assert!(
        out.stderr.is_empty(),
        "no progress bar when stderr is not a terminal"
    );
}

#[test]
fn options_override_the_scene() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join("t.scene"), SCENE).unwrap();
    let args = [
        "t.scene",
        "-o",
        "o.png",
        "--size",
        "10x6",
        "--samples",
        "2",
        "--threads",
        "1",
        "--depth",
        "d.pfm",
        "--bits",
        "16",
        "--alpha",
    ];
    let out = run(dir.path(), &args);
    assert!(
        out.status.success(),
        "stderr {}",
        String::from_utf8_lossy(&out.stderr)
    );
    let img = image::open(dir.path().join("o.png")).unwrap();
    assert_eq!((img.width(), img.height()), (10, 6), "--size");
    assert_eq!(img.color(), image::ColorType::Rgba16, "--bits 16 --alpha");
    assert!(!dir.path().join("saved.png").exists(), "-o replaces #save");
    let pfm = std::fs::read(dir.path().join("d.pfm")).unwrap();
    assert!(pfm.starts_with(b"Pf\n10 6\n"), "PFM header");
}

#[test]
fn bad_input_is_an_error_not_a_panic() {
    let dir = tempfile::tempdir().unwrap();
    let broken = SCENE.replace("MinorRadius = 1", "MinorRadius = -1");
    std::fs::write(dir.path().join("bad.scene"), broken).unwrap();
    std::fs::write(dir.path().join("saved.png"), b"old").unwrap();
    let out = run(dir.path(), &["bad.scene"]);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(
        out.status.code(),
        Some(1),
        "failure exit code; stderr {stderr}"
    );
    assert!(
        stderr.starts_with("render: error:"),
        "one error line: {stderr}"
    );
    assert!(
        stderr.contains("bad.scene:17:") && stderr.contains("MinorRadius"),
        "names file, line and key: {stderr}"
    );
    assert!(!stderr.contains("panicked"), "no panic: {stderr}");
    assert_eq!(
        std::fs::read(dir.path().join("saved.png")).unwrap(),
        b"old",
        "old image kept"
    );

    let out = run(dir.path(), &["missing.scene"]);
    assert_eq!(out.status.code(), Some(1), "missing file");
    assert!(
        String::from_utf8_lossy(&out.stderr).contains("missing.scene"),
        "names the file"
    );

    for bad in [
        ["--size", "10"],
        ["--size", "0x5"],
        ["--samples", "0"],
        ["--bits", "12"],
        ["--gamma", "zero"],
        ["--isolation", "fast"],
        ["--refine", "secant"],
    ] {
        std::fs::write(dir.path().join("t.scene"), SCENE).unwrap();
        let out = run(dir.path(), &["t.scene", bad[0], bad[1]]);
        assert_eq!(out.status.code(), Some(2), "{bad:?} is a usage error");
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert!(
            stderr.contains(bad[0]),
            "{bad:?}: names the option: {stderr}"
        );
    }
}

/// `--isolation` and `--refine` change only the root finder: every solver setting gives the
/// exact reference's depth map (rational Sturm on the stored polynomials) to within the
/// renderer's root tolerance (`2^-33` of the torus's box diagonal) plus the PFM's `f32`
/// rounding (one step is `9.5e-7` at the depths here, below 16).
#[test]
fn root_finder_options_agree_with_the_exact_reference_render() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join("t.scene"), SCENE).unwrap();
    let depth = |name: &str, extra: &[&str]| {
        let mut args = vec!["t.scene", "-o", "x.png", "--depth", name];
        args.extend_from_slice(extra);
        let out = run(dir.path(), &args);
        assert!(
            out.status.success(),
            "{extra:?}: {}",
            String::from_utf8_lossy(&out.stderr)
        );
        let bytes = std::fs::read(dir.path().join(name)).unwrap();
        render::read_pfm(&bytes).expect("a PFM").2
    };
    let reference = depth(
        "exact.pfm",
        &["--isolation", "exact", "--refine", "bisection"],
    );
    // The options reach the solver: `--stats` names it and its work differs.
    let stats = |extra: &[&str]| {
        let mut args = vec!["t.scene", "-o", "x.png", "--stats"];
        args.extend_from_slice(extra);
        let out = String::from_utf8_lossy(&run(dir.path(), &args).stdout).into_owned();
        let line = |name: &str| {
            out.lines()
                .find(|l| l.trim_start().starts_with(name))
                .unwrap_or_else(|| panic!("no `{name}` in {out}"))
                .to_owned()
        };
        (
            line("isolation, refinement"),
            line("refinement evaluations"),
        )
    };
    let (default_name, default_evals) = stats(&[]);
    let (exact_name, exact_evals) = stats(&["--isolation", "exact", "--refine", "bisection"]);
    assert!(
        default_name.contains("certified Bernstein, Newton-bisection"),
        "{default_name}"
    );
    assert!(
        exact_name.contains("exact rational Sturm, bisection"),
        "{exact_name}"
    );
    assert_ne!(
        default_evals, exact_evals,
        "different refinement, different work"
    );
    let hits = reference.iter().filter(|d| d.is_finite()).count();
    assert!(
        hits > 50 && hits < reference.len(),
        "{hits} of {} pixels hit",
        reference.len()
    );
    for extra in [
        &[][..],
        &["--refine", "illinois"][..],
        &["--isolation", "sturm", "--refine", "bisection"][..],
        &["--isolation", "stam"][..],
    ] {
        let d = depth("d.pfm", extra);
        for (i, (a, b)) in d.iter().zip(&reference).enumerate() {
            let same = (a.is_infinite() && b.is_infinite()) || (a - b).abs() <= 1e-6;
            assert!(same, "{extra:?}: pixel {i}: {a} vs exact {b}");
        }
    }
}

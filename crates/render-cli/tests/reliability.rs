//! Regression tests of issue 13 (hostile inputs) against the `render` binary: output files
//! are never lost or damaged, limits are refused with a message, unreadable inputs never
//! block, and a signal leaves no temporary file.

use std::path::Path;
use std::process::{Command, Output};

/// A small scene: renders in milliseconds at its 8 × 6 viewport.
const SCENE: &str = "\
#camera
Eye = (0,-8,5)
LookAt = (0,0,0)
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
#viewport
Size = (8,6)
";

fn run(dir: &Path, args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_render"))
        .args(args)
        .current_dir(dir)
        .output()
        .expect("the render binary runs")
}

fn stderr(out: &Output) -> String {
    String::from_utf8_lossy(&out.stderr).into_owned()
}

fn setup() -> tempfile::TempDir {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join("t.scene"), SCENE).unwrap();
    dir
}

/// Files in `dir` whose name ends in `.tmp` (the outputs' temporaries).
fn temporaries(dir: &Path) -> Vec<String> {
    std::fs::read_dir(dir)
        .unwrap()
        .filter_map(|e| e.ok()?.file_name().into_string().ok())
        .filter(|n| n.ends_with(".tmp"))
        .collect()
}

/// Waits until `child` (a render writing into `dir`) has created its temporary, i.e. has
/// prepared its outputs and started tracing, waits `settle` more, sends `signal` (`"-TERM"`,
/// `"-INT"`) and asserts what an interrupted run must do: exit within `limit` of the signal,
/// with status 130, leaving no temporary.
#[cfg(unix)]
fn interrupt_once_started(
    child: &mut std::process::Child,
    dir: &Path,
    signal: &str,
    settle: std::time::Duration,
    limit: std::time::Duration,
) {
    use std::time::{Duration, Instant};
    let start = Instant::now();
    while temporaries(dir).is_empty() && start.elapsed() < Duration::from_secs(60) {
        std::thread::sleep(Duration::from_millis(20));
    }
    assert!(!temporaries(dir).is_empty(), "the render started");
    std::thread::sleep(settle);
    let killed = Command::new("kill")
        .args([signal, &child.id().to_string()])
        .status()
        .unwrap();
    assert!(killed.success(), "kill ran");
    let stopped = Instant::now();
    let status = child.wait().unwrap();
    let elapsed = stopped.elapsed();
    assert!(elapsed < limit, "stopped promptly: {elapsed:?}");
    assert_eq!(
        status.code(),
        Some(130),
        "exit status of an interrupted run"
    );
    assert!(temporaries(dir).is_empty(), "temporaries removed");
}

/// Caught: `-o copy.scene` and `--depth copy.scene` overwrote the scene, and `-o` and
/// `--depth` naming one file silently replaced one output by the other (issue 13 item 1).
#[test]
fn output_naming_the_scene_or_the_other_output_is_refused() {
    let dir = setup();
    for args in [
        &["t.scene", "-o", "t.scene"][..],
        &["t.scene", "--depth", "t.scene"],
        &["t.scene", "-o", "./t.scene"],
        &["t.scene", "-o", "a.png", "--depth", "a.png"],
    ] {
        let out = run(dir.path(), args);
        assert!(!out.status.success(), "{args:?} must fail");
        assert!(
            stderr(&out).contains("is the same file as the"),
            "{args:?}: {}",
            stderr(&out)
        );
        assert_eq!(
            std::fs::read_to_string(dir.path().join("t.scene")).unwrap(),
            SCENE,
            "{args:?} left the scene intact"
        );
        assert!(!dir.path().join("a.png").exists(), "{args:?} wrote nothing");
    }
}

/// Caught: with `--depth no-such-dir/d.pfm` the PNG was replaced and then the run failed
/// (item 2), and an unwritable `-o` was reported only after the whole render (item 3).
#[test]
fn a_bad_output_path_fails_before_rendering_and_changes_no_file() {
    let dir = setup();
    std::fs::write(dir.path().join("keep.png"), b"old").unwrap();
    let out = run(
        dir.path(),
        &[
            "t.scene",
            "-o",
            "keep.png",
            "--depth",
            "no-such-dir/d.pfm",
            "--stats",
        ],
    );
    assert!(!out.status.success(), "a missing directory is an error");
    assert!(
        stderr(&out).contains("no-such-dir/d.pfm") && stderr(&out).contains("does not exist"),
        "names the path and the reason: {}",
        stderr(&out)
    );
    assert!(
        out.stdout.is_empty(),
        "failed before rendering: no statistics printed"
    );
    assert_eq!(
        std::fs::read(dir.path().join("keep.png")).unwrap(),
        b"old",
        "the existing PNG survives"
    );
    assert!(temporaries(dir.path()).is_empty(), "no temporary left");
}

/// Caught: `-o link.png` replaced the symbolic link by a regular file (item 4).
#[cfg(unix)]
#[test]
fn output_through_a_symlink_replaces_the_target_and_keeps_the_link() {
    let dir = setup();
    std::fs::create_dir(dir.path().join("real")).unwrap();
    std::os::unix::fs::symlink("real/target.png", dir.path().join("link.png")).unwrap();
    let out = run(dir.path(), &["t.scene", "-o", "link.png"]);
    assert!(out.status.success(), "{}", stderr(&out));
    let meta = std::fs::symlink_metadata(dir.path().join("link.png")).unwrap();
    assert!(meta.file_type().is_symlink(), "the link is still a link");
    let img = image::open(dir.path().join("real/target.png")).expect("the target is the PNG");
    assert_eq!((img.width(), img.height()), (8, 6), "the scene's size");
    assert!(
        temporaries(&dir.path().join("real")).is_empty(),
        "no temporary left"
    );
}

/// Caught: `-o` naming a character device or FIFO replaced the node by a regular file
/// (item 4). `/dev/null` is a device every Unix has.
#[cfg(unix)]
#[test]
fn output_to_a_device_writes_it_and_keeps_it_a_device() {
    use std::os::unix::fs::FileTypeExt;
    let dir = setup();
    let out = run(dir.path(), &["t.scene", "-o", "/dev/null"]);
    assert!(out.status.success(), "{}", stderr(&out));
    let meta = std::fs::metadata("/dev/null").unwrap();
    assert!(
        meta.file_type().is_char_device(),
        "/dev/null is still a device"
    );
    assert!(
        temporaries(Path::new("/dev")).is_empty(),
        "no temporary in /dev"
    );
}

/// Caught: `--size 65536x65536` passed validation and then aborted on allocation (item 7).
#[test]
fn an_image_beyond_the_pixel_limit_is_refused_with_the_limit() {
    let dir = setup();
    let out = run(dir.path(), &["t.scene", "--size", "65536x65536"]);
    assert!(!out.status.success(), "refused");
    assert!(
        stderr(&out).contains("67108864"),
        "names the pixel limit: {}",
        stderr(&out)
    );
    let big = SCENE.replace("Size = (8,6)", "Size = (65536,2048)");
    std::fs::write(dir.path().join("big.scene"), big).unwrap();
    let out = run(dir.path(), &["big.scene"]);
    assert!(
        stderr(&out).contains("big.scene:15:1: invalid `Size`"),
        "the viewport's limit is located: {}",
        stderr(&out)
    );
}

/// Caught: a FIFO as the scene blocked forever, `/dev/zero` was read until memory ran out
/// (item 8).
#[cfg(unix)]
#[test]
fn special_files_as_the_scene_are_refused_without_blocking() {
    let dir = setup();
    let fifo = dir.path().join("f.scene");
    let made = Command::new("mkfifo").arg(&fifo).status();
    let mut inputs = vec!["/dev/zero".to_string()];
    if made.is_ok_and(|s| s.success()) {
        inputs.push("f.scene".to_string());
    }
    for input in &inputs {
        let out = run(dir.path(), &[input]);
        assert!(!out.status.success(), "{input} refused");
        assert!(
            stderr(&out).contains("not a regular file"),
            "{input}: {}",
            stderr(&out)
        );
    }
}

/// Caught: error messages echoed an ESC sequence from the scene to the terminal (item 14).
#[test]
fn control_characters_from_the_scene_are_escaped_in_messages() {
    let dir = setup();
    let bad = SCENE.replace("MajorRadius = 2", "Major\u{1b}]0;pwned\u{7}Radius = 2");
    std::fs::write(dir.path().join("esc.scene"), bad).unwrap();
    let out = run(dir.path(), &["esc.scene"]);
    assert!(!out.status.success(), "an unknown key");
    let err = stderr(&out);
    assert!(
        !err.contains('\u{1b}') && !err.contains('\u{7}'),
        "raw: {err:?}"
    );
    assert!(err.contains("\\u{1b}"), "shown escaped: {err}");
}

/// Caught: SIGTERM during a render left `.NAME.PID.tmp` behind (item 5), and Ctrl-C had no
/// clean way to stop a long render (item 10): the signal cancels it, removes the
/// temporaries, keeps the old output and exits with 130.
#[cfg(unix)]
#[test]
fn a_signal_stops_the_render_and_leaves_no_temporary() {
    use std::time::Duration;
    let dir = setup();
    std::fs::write(dir.path().join("keep.png"), b"old").unwrap();
    // Slow on purpose: 4000² pixels × 64 samples on one thread take minutes.
    let mut child = Command::new(env!("CARGO_BIN_EXE_render"))
        .args([
            "t.scene",
            "-o",
            "keep.png",
            "--size",
            "4000x4000",
            "--samples",
            "8",
        ])
        .args(["--threads", "1"])
        .current_dir(dir.path())
        .stderr(std::process::Stdio::piped())
        .spawn()
        .unwrap();
    interrupt_once_started(
        &mut child,
        dir.path(),
        "-TERM",
        Duration::ZERO,
        Duration::from_secs(30),
    );
    assert_eq!(
        std::fs::read(dir.path().join("keep.png")).unwrap(),
        b"old",
        "the old output is kept"
    );
}

/// Caught: a render whose every ray is slow (the exact-arithmetic fallback of `x^32 − 1`,
/// about 60 ms per ray in the issue; far less since issue 11, but still a high-degree query
/// per ray and per shadow ray) could not be stopped promptly (item 10). SIGINT stops it
/// within one cell's rays: well under the time the whole image takes, leaving no temporary
/// and exiting with 130.
#[cfg(unix)]
#[test]
fn ctrl_c_stops_a_render_of_slow_rays_promptly() {
    use std::time::Duration;
    let dir = tempfile::tempdir().unwrap();
    let scene = SCENE.replace(
        "Type = TORUS\nCenter = (0,0,0)\nAxis = (0,0,1)\nMajorRadius = 2\nMinorRadius = 1\n",
        "Type = ALGEBRAIC_SURFACE\nEquation = x^32 - 1\n",
    );
    assert!(scene.contains("x^32"), "the torus was replaced");
    std::fs::write(dir.path().join("t.scene"), scene).unwrap();
    // 512² rays of degree 32 on one thread: tens of seconds in a debug build (x^32 − 1 at
    // 840² took 3.9 s CPU in release after issue 11), far past the signal at 200 ms.
    let mut child = Command::new(env!("CARGO_BIN_EXE_render"))
        .args([
            "t.scene",
            "-o",
            "x.png",
            "--size",
            "512x512",
            "--threads",
            "1",
        ])
        .current_dir(dir.path())
        .stderr(std::process::Stdio::piped())
        .spawn()
        .unwrap();
    // One cell is one ray here; 5 s allows a loaded machine, while finishing the image takes
    // far longer.
    interrupt_once_started(
        &mut child,
        dir.path(),
        "-INT",
        Duration::from_millis(200),
        Duration::from_secs(5),
    );
    assert!(!dir.path().join("x.png").exists(), "no partial output");
}

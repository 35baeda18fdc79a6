//! A fuzzer over the `render` command line on stable Rust (issue 13, "In the tree").
//!
//! Each case builds an argument vector from the real flag set (`-o`, `--size`, `--threads`,
//! `--samples`, `--stats`, `--depth`, `--bits`, `--alpha`, `--gamma`, `--patch-method`,
//! `--isolation`, `--refine`), each flag with a value drawn from valid ones, edge values
//! (0, 65536, `1e9x1`, negative numbers, NaN) and garbage (empty, control characters, a
//! directory, `/dev/zero`, the scene itself as an output, a long string), in random order and
//! number, with the scene or a missing, empty or binary scene file; it runs the binary with
//! stdin closed. Every case must end as one of:
//!
//! - **rendered**: exit status 0;
//! - **usage error**: exit status 2 with a message on stderr naming the argument;
//! - **refused**: exit status 1 with a `render: error:` message;
//! - **slow**: still running after [`CASE_BUDGET`] (a legitimately large render), killed;
//!
//! and fails on any other status (a panic exits with 101, an abort by signal), on `panicked`
//! in stderr, or on a failure with an empty message.
//!
//! Smoke run (part of `cargo test`): [`SMOKE_CASES`] cases, deterministic. Longer run:
//! `FUZZ_CASES=2000 FUZZ_SEED=7 cargo test --release -p render-cli --test fuzz_cli -- --nocapture`.

use std::path::Path;
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;

/// Cases of the smoke run (each one process; a few seconds in a debug build).
const SMOKE_CASES: usize = 60;

/// How long one run may take before it counts as slow and is killed.
const CASE_BUDGET: Duration = Duration::from_secs(10);

/// A small scene: a torus at 8 × 6 pixels renders in milliseconds.
const SCENE: &str = "#camera Eye = (0,-8,5) LookAt = (0,0,0) ViewField = 50\n\
                     #light Source = (5,-5,10) Color = (1,1,1)\n\
                     #object Type = TORUS Center = (0,0,0) Axis = (0,0,1) MajorRadius = 2 \
                     MinorRadius = 1\n#viewport Size = (8,6)\n";

/// Values no flag accepts, or that name things no output may be.
const GARBAGE: &[&str] = &[
    "",
    "-",
    "--",
    "\u{1b}[2J",
    "\u{7f}",
    "NaN",
    "-1",
    "0",
    "18446744073709551616",
    "1e9x1",
    "x",
    ".",
    "/",
    "/dev/zero",
    "t.scene",
    "no-such-dir/o.png",
    "--size",
    "-o",
];

/// The flags and values they may take (valid ones first, then edge values).
fn flag_value(rng: &mut ChaCha8Rng) -> Vec<String> {
    let pick = |rng: &mut ChaCha8Rng, xs: &[&str]| xs[rng.gen_range(0..xs.len())].to_string();
    let garbage = |rng: &mut ChaCha8Rng| {
        if rng.gen_bool(0.1) {
            "y".repeat(rng.gen_range(1000..5000))
        } else {
            pick(rng, GARBAGE)
        }
    };
    let (flag, values): (&str, &[&str]) = match rng.gen_range(0..12) {
        0 => (
            "-o",
            &[
                "o.png",
                "sub/o.png",
                "o.png",
                "t.scene",
                "/dev/null",
                "d.pfm",
            ],
        ),
        1 => (
            "--size",
            &[
                "4x3",
                "1x1",
                "16x16",
                "0x5",
                "65536x65536",
                "5",
                "3X2",
                " 4x4",
            ],
        ),
        2 => ("--threads", &["1", "2", "0", "1024", "1025", "-3"]),
        3 => ("--samples", &["1", "2", "3", "0", "65", "-1"]),
        4 => ("--stats", &[]),
        5 => ("--depth", &["d.pfm", "o.png", "t.scene", "sub/d.pfm"]),
        6 => ("--bits", &["8", "16", "12", "0"]),
        7 => ("--alpha", &[]),
        8 => (
            "--gamma",
            &["srgb", "2.2", "1", "0", "-1", "inf", "NaN", "1e308"],
        ),
        9 => (
            "--patch-method",
            &["groebner", "resultant", "groebner-exact", "stam"],
        ),
        10 => (
            "--isolation",
            &["bernstein", "sturm", "stam", "exact", "EXACT", "fast"],
        ),
        _ => ("--refine", &["newton", "illinois", "bisection", "secant"]),
    };
    let mut out = vec![flag.to_string()];
    if !values.is_empty() || rng.gen_bool(0.1) {
        out.push(if values.is_empty() || rng.gen_bool(0.2) {
            garbage(rng)
        } else {
            pick(rng, values)
        });
    }
    out
}

fn arguments(rng: &mut ChaCha8Rng) -> Vec<String> {
    let mut args = Vec::new();
    for _ in 0..rng.gen_range(0..6) {
        args.extend(flag_value(rng));
    }
    let scene = [
        "t.scene",
        "t.scene",
        "t.scene",
        "missing.scene",
        "empty.scene",
        "bin.scene",
        ".",
    ][rng.gen_range(0..7)];
    let at = rng.gen_range(0..=args.len());
    if rng.gen_bool(0.95) {
        args.insert(at, scene.to_string());
    }
    if rng.gen_bool(0.05) {
        args.push(GARBAGE[rng.gen_range(0..GARBAGE.len())].to_string());
    }
    args
}

/// The classes of outcome.
#[derive(Debug, Default)]
struct Tally {
    rendered: usize,
    usage_error: usize,
    refused: usize,
    slow: usize,
}

/// Runs one argument vector in `dir`; `Err` describes a failure.
fn run_case(dir: &Path, args: &[String], tally: &mut Tally) -> Result<(), String> {
    let mut child = Command::new(env!("CARGO_BIN_EXE_render"))
        .args(args)
        .current_dir(dir)
        .stdin(Stdio::null())
        .stdout(Stdio::null())
        .stderr(Stdio::piped())
        .spawn()
        .map_err(|e| format!("spawn: {e}"))?;
    // Read stderr on a thread so a chatty child never blocks on a full pipe.
    let mut pipe = child.stderr.take().expect("piped");
    let reader = std::thread::spawn(move || {
        let mut s = String::new();
        let _ = std::io::Read::read_to_string(&mut pipe, &mut s);
        s
    });
    let start = Instant::now();
    let status = loop {
        if let Some(status) = child.try_wait().map_err(|e| e.to_string())? {
            break Some(status);
        }
        if start.elapsed() > CASE_BUDGET {
            let _ = child.kill();
            let _ = child.wait();
            break None;
        }
        std::thread::sleep(Duration::from_millis(5));
    };
    let stderr = reader.join().unwrap_or_default();
    if stderr.contains("panicked") {
        return Err(format!("panicked: {stderr}"));
    }
    let Some(status) = status else {
        tally.slow += 1;
        return Ok(());
    };
    match status.code() {
        Some(0) => tally.rendered += 1,
        Some(2) if !stderr.trim().is_empty() => tally.usage_error += 1,
        Some(1) if stderr.contains("render: error:") => tally.refused += 1,
        code => return Err(format!("exit {code:?} ({status}), stderr: {stderr}")),
    }
    Ok(())
}

/// Runs `cases` fuzz cases from `seed`; panics with every failing input.
fn fuzz(seed: u64, cases: usize) -> Tally {
    let dir = tempfile::tempdir().unwrap();
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let mut tally = Tally::default();
    let mut failures = Vec::new();
    for case in 0..cases {
        // Fresh inputs each time: a case may have overwritten or removed them.
        let p = dir.path();
        std::fs::write(p.join("t.scene"), SCENE).unwrap();
        std::fs::write(p.join("empty.scene"), "").unwrap();
        std::fs::write(p.join("bin.scene"), b"\xff\xfe\x00#object\x80").unwrap();
        let _ = std::fs::create_dir(p.join("sub"));
        let args = arguments(&mut rng);
        if let Err(why) = run_case(p, &args, &mut tally) {
            let shown: Vec<String> = args.iter().map(|a| format!("{a:.80?}")).collect();
            failures.push(format!("case {case}: render {}: {why}", shown.join(" ")));
        }
        // The scene must survive every run (issue 13, item 1).
        let kept = std::fs::read_to_string(p.join("t.scene")).unwrap_or_default();
        if kept != SCENE {
            failures.push(format!("case {case}: {args:?} changed the scene file"));
        }
    }
    eprintln!("fuzz_cli seed {seed}: {cases} cases, {tally:?}");
    assert!(
        failures.is_empty(),
        "{} failures:\n{}",
        failures.len(),
        failures.join("\n")
    );
    tally
}

/// The bounded smoke run; `FUZZ_CASES` and `FUZZ_SEED` make it longer or different.
#[test]
fn fuzz_cli_arguments_smoke() {
    let tally = fuzz(env_or("FUZZ_SEED", 13), env_or("FUZZ_CASES", SMOKE_CASES));
    assert!(tally.rendered > 0, "some vectors render: {tally:?}");
    assert!(tally.usage_error > 0, "some are usage errors: {tally:?}");
}

/// The value of the environment variable `name`, else `default`.
fn env_or<T: std::str::FromStr>(name: &str, default: T) -> T {
    std::env::var(name)
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(default)
}

//! A mutation fuzzer over the scene language and NFF, on stable Rust (issue 13 "In the
//! tree").
//!
//! The corpus is every `scenes/*.scene` for the scene language, and every `scenes/spd/*.nff`
//! plus [`NFF_SEED`] (one of each NFF entity) for NFF; each case applies a few random mutations (byte
//! flips, deleted or duplicated ranges, swapped lines, and insertions of tokens that found
//! bugs before: huge, tiny and zero numbers, huge exponents, zero vectors, deep nesting,
//! control characters, lone `\r`, bytes that are not UTF-8) and then parses, prepares and
//! renders the result at 2 × 2 pixels. Every case must end as one of:
//!
//! - **rendered**: the scene is valid and renders;
//! - **located error**: a [`SceneError`] with a `file:line:col`;
//! - **slow render**: valid, but its 2 × 2 render took longer than [`RENDER_BUDGET`] and was
//!   stopped through its `Cancel` token (slow exact-arithmetic rays are the speed issue's
//!   subject; counted, not failed);
//!
//! and fails on a panic, on a parse slower than [`PARSE_BUDGET`], or on a scene that parses
//! but that `PreparedScene::new` refuses without a location.
//!
//! Smoke run (part of `cargo test`): [`SMOKE_CASES`] cases per language, deterministic.
//! Longer run (both languages):
//! `FUZZ_CASES=100000 FUZZ_SEED=7 cargo test --release -p render --test fuzz_scenes -- --nocapture`.

use std::panic::{AssertUnwindSafe, catch_unwind};
use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};

use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use render::scene::{SceneError, parse, parse_nff};
use render::{Cancel, PreparedScene, RenderSettings, render_with_cancel};

/// Cases of the smoke run (about ten seconds in a debug build on a loaded machine).
const SMOKE_CASES: usize = 400;

/// The most time one parse may take: the parser is linear in the text, and the corpus files
/// parse in milliseconds.
const PARSE_BUDGET: Duration = Duration::from_secs(2);

/// How long a 2 × 2 render of a fuzzed scene may run before it is cancelled.
const RENDER_BUDGET: Duration = Duration::from_millis(500);

/// Tokens that found bugs before, inserted at random places.
const INTERESTING: &[&str] = &[
    "1e308",
    "-1e308",
    "1e-320",
    "0",
    "-0",
    "4294967295",
    "18446744073709551616",
    "1e10",
    "(0,0,0)",
    "(1e-200,0,0)",
    "(1e200,1e200,1e200)",
    "Scale = 1e150",
    "Power = 1000",
    "Power = 513",
    "x^1e308",
    "x^32",
    "MaxDepth = 64",
    "Kt = 1",
    "((((((((((",
    "))))",
    "#object",
    "#world",
    "Type = SUPERQUADRIC",
    "Type = ALGEBRAIC_SURFACE",
    "Equation = ",
    "\r",
    "\r\n",
    "\u{1b}[31m",
    "\u{0}",
    "\u{202e}",
    "\"",
    "//",
    "=",
    "Size = (65536,65536)",
    "File Name = /dev/zero",
    "sqrt(-1)",
    "1/0",
];

/// One of each NFF entity (viewpoint, background, light, fill, cone, sphere, polygon, patch),
/// so mutations reach every reader.
const NFF_SEED: &str = "v\nfrom 0 -8 5\nat 0 0 0\nup 0 0 1\nangle 40\nhither 1\nresolution 4 4\n\
                        b 0.1 0.2 0.3\nl 5 -5 10\nl 0 0 9 1 1 1\nf 1 0 0 1 0 0 0 0\n\
                        c\n0 0 0 1\n0 0 2 0.5\ns 0 0 0 1\np 3\n0 0 0\n1 0 0\n0 1 0\n\
                        pp 3\n0 0 1 0 0 1\n1 0 1 0 0 1\n0 1 1 0 0 1\n";

/// The input languages.
#[derive(Clone, Copy, Debug)]
enum Language {
    Scene,
    Nff,
}

/// The classes of outcome.
#[derive(Debug, Default)]
struct Tally {
    rendered: usize,
    located: usize,
    slow: usize,
}

fn corpus(language: Language) -> Vec<(PathBuf, Vec<u8>)> {
    let scenes = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../scenes");
    let (dir, ext) = match language {
        Language::Scene => (scenes, "scene"),
        Language::Nff => (scenes.join("spd"), "nff"),
    };
    let mut files: Vec<_> = std::fs::read_dir(&dir)
        .expect("the corpus folder exists")
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| p.extension().is_some_and(|e| e == ext))
        .collect();
    files.sort();
    let mut corpus: Vec<_> = files
        .into_iter()
        .map(|p| {
            let bytes = std::fs::read(&p).unwrap();
            (p, bytes)
        })
        .collect();
    if let Language::Nff = language {
        corpus.push((PathBuf::from("seed.nff"), NFF_SEED.as_bytes().to_vec()));
    }
    corpus
}

fn mutate(rng: &mut ChaCha8Rng, bytes: &mut Vec<u8>) {
    for _ in 0..rng.gen_range(1..=4) {
        let len = bytes.len().max(1);
        let at = rng.gen_range(0..len).min(bytes.len());
        match rng.gen_range(0..6) {
            0 if !bytes.is_empty() => {
                let i = rng.gen_range(0..bytes.len());
                bytes[i] ^= 1 << rng.gen_range(0..8);
            }
            1 => {
                let end = (at + rng.gen_range(0..32)).min(bytes.len());
                bytes.drain(at..end);
            }
            2 => {
                let end = (at + rng.gen_range(0..64)).min(bytes.len());
                let copy = bytes[at..end].to_vec();
                bytes.splice(at..at, copy);
            }
            3 => {
                let text = String::from_utf8_lossy(bytes).into_owned();
                let mut lines: Vec<&str> = text.split('\n').collect();
                if lines.len() > 1 {
                    let (i, j) = (rng.gen_range(0..lines.len()), rng.gen_range(0..lines.len()));
                    lines.swap(i, j);
                }
                *bytes = lines.join("\n").into_bytes();
            }
            4 => bytes.insert(at, [0xFF, 0xC0, 0x80, 0xE2][rng.gen_range(0..4)]),
            _ => {
                let token = INTERESTING[rng.gen_range(0..INTERESTING.len())];
                let spaced = format!(" {token} ");
                bytes.splice(at..at, spaced.bytes());
            }
        }
    }
}

/// Parses, prepares and renders one case; `Err` describes a failure.
fn run_case(
    language: Language,
    path: &Path,
    bytes: &[u8],
    tally: &mut Tally,
) -> Result<(), String> {
    // Non-UTF-8 input goes through `load`'s check; the text itself through `parse`.
    let text = match std::str::from_utf8(bytes) {
        Ok(t) => t.to_owned(),
        Err(_) => {
            let dir = tempfile::tempdir().unwrap();
            let file = dir
                .path()
                .join(path.file_name().unwrap_or("case.scene".as_ref()));
            std::fs::write(&file, bytes).unwrap();
            let e = render::scene::load(&file).expect_err("not UTF-8");
            return located(&e, tally);
        }
    };
    let start = Instant::now();
    let parsed = match language {
        Language::Scene => parse(&text, path),
        Language::Nff => parse_nff(&text, path),
    };
    if start.elapsed() > PARSE_BUDGET {
        return Err(format!("parse took {:?}", start.elapsed()));
    }
    let scene = match parsed {
        Ok(s) => s,
        Err(e) => return located(&e, tally),
    };
    let prepared = PreparedScene::new(&scene)
        .map_err(|e| format!("parsed, but PreparedScene refused it unlocated: {e:#?}"))?;
    let settings = RenderSettings {
        size: [2, 2],
        resolution: [1, 1],
        samples: 1,
        depth: true,
    };
    let cancel = Cancel::new();
    let watchdog = {
        let cancel = cancel.clone();
        let (tx, rx) = std::sync::mpsc::channel::<()>();
        std::thread::spawn(move || {
            if rx.recv_timeout(RENDER_BUDGET).is_err() {
                cancel.cancel();
            }
        });
        tx
    };
    let out = render_with_cancel(&prepared, &scene.camera, &settings, &|_| {}, &cancel);
    drop(watchdog);
    match out {
        Ok(_) => tally.rendered += 1,
        Err(render::Cancelled) => tally.slow += 1,
    }
    Ok(())
}

fn located(e: &SceneError, tally: &mut Tally) -> Result<(), String> {
    match e.span() {
        Some(_) => {
            tally.located += 1;
            Ok(())
        }
        None => Err(format!("error without a place: {e}")),
    }
}

/// Runs `cases` fuzz cases from `seed`; panics with every failing input.
fn fuzz(language: Language, seed: u64, cases: usize) -> Tally {
    let corpus = corpus(language);
    assert!(!corpus.is_empty(), "the corpus has scenes");
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let mut tally = Tally::default();
    let mut failures = Vec::new();
    for case in 0..cases {
        let (path, seed_bytes) = &corpus[rng.gen_range(0..corpus.len())];
        let mut bytes = seed_bytes.clone();
        mutate(&mut rng, &mut bytes);
        let result = catch_unwind(AssertUnwindSafe(|| {
            run_case(language, path, &bytes, &mut tally)
        }));
        let failure = match result {
            Ok(Ok(())) => continue,
            Ok(Err(why)) => why,
            Err(_) => "panicked".to_string(),
        };
        failures.push(format!(
            "case {case} from {}: {failure}\n---\n{}\n---",
            path.display(),
            String::from_utf8_lossy(&bytes).escape_debug()
        ));
    }
    eprintln!("fuzz_scenes {language:?} seed {seed}: {cases} cases, {tally:?}");
    assert!(
        failures.is_empty(),
        "{} failures:\n{}",
        failures.len(),
        failures.join("\n")
    );
    tally
}

/// Fuzz targets by input language.
mod targets {
    use super::Language;

    /// `(seed, cases)` from `FUZZ_SEED` and `FUZZ_CASES`, else the smoke run's.
    fn run() -> (u64, usize) {
        let var = |name: &str| std::env::var(name).ok().and_then(|v| v.parse().ok());
        (
            var("FUZZ_SEED").unwrap_or(13),
            var("FUZZ_CASES").map_or(super::SMOKE_CASES, |c: u64| c as usize),
        )
    }

    /// The scene language: the bounded smoke run, every outcome rendered or located.
    #[test]
    fn fuzz_scene_language_smoke() {
        let (seed, cases) = run();
        let tally = super::fuzz(Language::Scene, seed, cases);
        assert!(tally.located > 0, "mutations produce errors: {tally:?}");
        assert!(tally.rendered > 0, "and valid scenes: {tally:?}");
    }

    /// NFF: the same classes of outcome.
    #[test]
    fn fuzz_nff_smoke() {
        let (seed, cases) = run();
        let tally = super::fuzz(Language::Nff, seed, cases);
        assert!(tally.located > 0, "mutations produce errors: {tally:?}");
        assert!(tally.rendered > 0, "and valid scenes: {tally:?}");
    }
}

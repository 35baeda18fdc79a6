//! The `render` command line: `render SCENE [-o OUT.png] [--size WxH] [--threads N]
//! [--samples N] [--stats] [--depth OUT.pfm] [--bits 8|16] [--alpha] [--gamma G]
//! [--patch-method groebner|resultant] [--isolation METHOD] [--refine METHOD]`.
//!
//! Arguments are parsed into a raw struct, converted to `RenderOptions`, and handed to the
//! library; no rendering logic lives here.

mod serve;

use std::io::{IsTerminal, Write};
use std::path::PathBuf;
use std::process::ExitCode;
use std::sync::atomic::{AtomicBool, Ordering};
use std::time::{Duration, Instant};

use anyhow::Context;
use clap::Parser;
use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};
use poly::{IsolationMethod, RefineMethod};
use render::{Cancel, Gamma, PatchMethod, PngOptions, RenderOptions, RootMethods, StatsReport};

mod signals;

/// Delay before the progress bar appears: renders shorter than this show nothing.
const PROGRESS_DELAY: Duration = Duration::from_secs(1);

/// Render a scene file (Stam's command language) to a PNG.
#[derive(Debug, Parser)]
#[command(
    name = "render",
    version,
    about,
    after_help = "`render serve [SCENE]` starts the explorer in the browser (see `render serve --help`)."
)]
struct RawArgs {
    /// The scene file.
    scene: PathBuf,
    /// Output PNG (default: the scene's `#save`, else SCENE's name with `.png`).
    #[arg(short, long, value_name = "OUT.png")]
    output: Option<PathBuf>,
    /// Image size, overriding the scene's `#viewport`, e.g. `640x480`.
    #[arg(long, value_name = "WxH", value_parser = parse_size)]
    size: Option<[u32; 2]>,
    /// Worker threads (default: all cores).
    #[arg(long, value_name = "N", value_parser = clap::value_parser!(u32).range(1..=1024))]
    threads: Option<u32>,
    /// N×N stratified samples per pixel.
    #[arg(long, value_name = "N", default_value_t = 1, value_parser = clap::value_parser!(u32).range(1..=64))]
    samples: u32,
    /// Print ray, intersection, root-solver and timing statistics.
    #[arg(long)]
    stats: bool,
    /// Also write the primary-hit distance of every pixel as a PFM (+inf for a miss).
    #[arg(long, value_name = "OUT.pfm")]
    depth: Option<PathBuf>,
    /// Bits per PNG channel.
    #[arg(long, default_value_t = 8, value_parser = parse_bits)]
    bits: u8,
    /// Write an alpha channel: background pixels get alpha 0.
    #[arg(long)]
    alpha: bool,
    /// Output transfer function: `srgb` or a power-law gamma such as `2.2` (`1` for linear).
    #[arg(long, default_value = "srgb", value_parser = parse_gamma)]
    gamma: Gamma,
    /// Elimination method for every Bézier patch (`groebner`, `resultant`, or the exact-rational
    /// references `groebner-exact`, `resultant-exact`), overriding the scene's `Method`.
    #[arg(long, value_name = "METHOD", value_parser = parse_patch_method)]
    patch_method: Option<PatchMethod>,
    /// Root isolation for implicit surfaces: `bernstein` (certified, the default), `sturm`
    /// (f64 Sturm, not certified), `stam` (Stam's 1988 Sturm, the baseline), or `exact`
    /// (rational Sturm on the stored polynomial: a slow reference render).
    #[arg(long, value_name = "METHOD", default_value = "bernstein", value_parser = parse_isolation)]
    isolation: IsolationMethod,
    /// Root refinement for implicit surfaces: `newton` (Newton–bisection, the default),
    /// `illinois` (regula falsi) or `bisection`.
    #[arg(long, value_name = "METHOD", default_value = "newton", value_parser = parse_refine)]
    refine: RefineMethod,
}

fn parse_isolation(s: &str) -> Result<IsolationMethod, String> {
    match s.to_ascii_lowercase().as_str() {
        "bernstein" => Ok(IsolationMethod::Bernstein),
        "sturm" => Ok(IsolationMethod::Sturm),
        "stam" => Ok(IsolationMethod::StamSturm),
        "exact" => Ok(IsolationMethod::Exact),
        _ => Err(format!(
            "expected bernstein, sturm, stam or exact, got `{s}`"
        )),
    }
}

fn parse_refine(s: &str) -> Result<RefineMethod, String> {
    match s.to_ascii_lowercase().as_str() {
        "newton" => Ok(RefineMethod::NewtonBisection),
        "illinois" => Ok(RefineMethod::Illinois),
        "bisection" => Ok(RefineMethod::Bisection),
        _ => Err(format!("expected newton, illinois or bisection, got `{s}`")),
    }
}

fn parse_patch_method(s: &str) -> Result<PatchMethod, String> {
    PatchMethod::parse(s).ok_or_else(|| {
        format!("expected groebner, resultant, groebner-exact or resultant-exact, got `{s}`")
    })
}

fn parse_size(s: &str) -> Result<[u32; 2], String> {
    let (w, h) = s
        .split_once(['x', 'X'])
        .ok_or_else(|| format!("expected WIDTHxHEIGHT, e.g. 640x480, got `{s}`"))?;
    let side = |v: &str| -> Result<u32, String> {
        match v.trim().parse::<u32>() {
            Ok(n) if (1..=render::scene::MAX_IMAGE_SIDE).contains(&n) => Ok(n),
            _ => Err(format!(
                "`{v}` is not a side length between 1 and {}",
                render::scene::MAX_IMAGE_SIDE
            )),
        }
    };
    let size = [side(w)?, side(h)?];
    render::scene::check_image_size(size)?;
    Ok(size)
}

fn parse_bits(s: &str) -> Result<u8, String> {
    match s {
        "8" => Ok(8),
        "16" => Ok(16),
        _ => Err(format!("expected 8 or 16, got `{s}`")),
    }
}

fn parse_gamma(s: &str) -> Result<Gamma, String> {
    if s.eq_ignore_ascii_case("srgb") {
        return Ok(Gamma::Srgb);
    }
    match s.parse::<f64>() {
        Ok(g) if g.is_finite() && g > 0.0 => Ok(Gamma::Power(g)),
        _ => Err(format!("expected `srgb` or a positive number, got `{s}`")),
    }
}

impl RawArgs {
    fn to_options(&self) -> RenderOptions {
        RenderOptions {
            output: self.output.clone(),
            size: self.size,
            threads: self.threads.map(|t| t as usize),
            samples: self.samples,
            depth: self.depth.clone(),
            png: PngOptions {
                bits: self.bits,
                alpha: self.alpha,
                gamma: self.gamma,
            },
            patch_method: self.patch_method,
            roots: RootMethods {
                isolation: self.isolation,
                refine: self.refine,
            },
        }
    }
}

fn run(args: &RawArgs, cancel: &Cancel) -> anyhow::Result<()> {
    let opts = args.to_options();
    // One pool for the whole run: a large NFF file is read on its threads, then traced.
    let pool = render::thread_pool(opts.threads)?;
    let parse_start = Instant::now();
    let scene = pool.install(|| render::scene::load(&args.scene))?;
    let parse = parse_start.elapsed();

    let bar = ProgressBar::with_draw_target(None, ProgressDrawTarget::hidden());
    let show = std::io::stderr().is_terminal();
    let shown = AtomicBool::new(false);
    let start = Instant::now();
    let progress = |done: u32, total: u32| {
        if !show {
            return;
        }
        if !shown.load(Ordering::Relaxed)
            && start.elapsed() > PROGRESS_DELAY
            && !shown.swap(true, Ordering::Relaxed)
        {
            bar.set_length(u64::from(total));
            if let Ok(style) = ProgressStyle::with_template("{bar:40} {pos}/{len} rows, {eta} left")
            {
                bar.set_style(style);
            }
            bar.set_draw_target(ProgressDrawTarget::stderr());
        }
        bar.set_position(u64::from(done));
    };
    let report =
        render::render_scene_in(&pool, &scene, Some(&args.scene), &opts, &progress, cancel)
            .with_context(|| format!("cannot render {}", args.scene.display()));
    bar.finish_and_clear();
    let mut report = report?;
    report.times.parse = parse;

    if args.stats {
        let stats = StatsReport {
            stats: &report.output.stats,
            times: report.times,
            size: [report.output.film.width, report.output.film.height],
            samples_per_pixel: opts.samples * opts.samples,
            threads: report.threads,
            roots: opts.roots,
        };
        let mut out = std::io::stdout().lock();
        write!(out, "{stats}")?;
        writeln!(out, "Wrote {}", report.png_path.display())?;
    }
    Ok(())
}

fn main() -> ExitCode {
    // `render serve …` is the explorer; anything else is `render SCENE …` as before (a scene
    // file named `serve` is still reachable as `./serve`).
    if std::env::args_os().nth(1).is_some_and(|a| a == "serve") {
        return serve::main(std::env::args_os().skip(1));
    }
    let args = RawArgs::parse();
    let cancel = Cancel::new();
    signals::install(&cancel);
    match run(&args, &cancel) {
        Ok(()) => ExitCode::SUCCESS,
        Err(_) if cancel.is_cancelled() => {
            let _ = writeln!(
                std::io::stderr(),
                "render: interrupted; no file was written"
            );
            ExitCode::from(signals::INTERRUPTED_EXIT)
        }
        Err(e) => {
            let _ = writeln!(
                std::io::stderr(),
                "render: error: {}",
                render::scene::escape_message(&format!("{e:#}"))
            );
            ExitCode::FAILURE
        }
    }
}

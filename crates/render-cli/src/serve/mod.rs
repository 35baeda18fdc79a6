//! `render serve [SCENE] [--port N] [--bind ADDR]`: the explorer, a local HTTP server with
//! one embedded page that edits a scene (or just an equation), shows its render
//! progressively and turns the camera with the mouse. Every image is rendered here, with the
//! render library and the CLI's options (`render::prepare_render`), so a downloaded PNG has
//! the pixels `render SCENE` writes.
//!
//! Work is bounded: renders run on one shared rayon pool, at most `--render-slots` at once;
//! each browser tab (a *session*) has at most one render in flight, and a newer request of the
//! same tab cancels the older one at once (`render::render_with_cancel`). Limits on request
//! size, image pixels, equation degree and render time are flags ([`Limits`]).

mod api;
mod equation;
mod scene_info;

use std::io::Write;
use std::net::{IpAddr, Ipv4Addr, SocketAddr};
use std::path::PathBuf;
use std::process::ExitCode;
use std::sync::Arc;
use std::time::Duration;

use anyhow::Context;
use clap::Parser;

/// Largest request body accepted by default: a scene text is a few kilobytes; 1 MiB leaves
/// room for a hand-written scene with hundreds of inline Bézier patches.
const DEFAULT_MAX_REQUEST_BYTES: usize = 1 << 20;

/// Largest image (width × height) rendered by default: 4096², a 64 MiB film of `[f32; 4]`
/// pixels, well above the scenes' 840² and far below a size that exhausts memory.
const DEFAULT_MAX_PIXELS: u64 = 4096 * 4096;

/// Highest equation degree rendered by default: above every classical surface of SURFER's
/// gallery (Sarti's dodecic has degree 12); the scene language itself accepts up to
/// `render::scene::MAX_EQUATION_DEGREE`.
const DEFAULT_MAX_DEGREE: u32 = 16;

/// Longest render allowed by default, in seconds; a longer one is cancelled with a message so
/// a hostile scene cannot hold a render slot.
const DEFAULT_MAX_RENDER_SECONDS: u64 = 120;

/// The explorer: an interactive view of a scene in the browser.
#[derive(Debug, Parser)]
#[command(name = "render serve", bin_name = "render serve", version)]
pub(crate) struct ServeArgs {
    /// A scene file to open first; its directory is the scene directory unless --scenes.
    scene: Option<PathBuf>,
    /// TCP port (0: any free port; the URL printed says which).
    #[arg(long, default_value_t = 8080)]
    port: u16,
    /// Address to listen on. The default accepts connections from this machine only.
    #[arg(long, default_value_t = IpAddr::V4(Ipv4Addr::LOCALHOST))]
    bind: IpAddr,
    /// The scene directory: the gallery lists its `.scene` files, and texture and
    /// control-point files are read only from inside it (default: SCENE's directory, else
    /// `./scenes`, else the current directory).
    #[arg(long, value_name = "DIR")]
    scenes: Option<PathBuf>,
    /// Renders that may run at once (default: the number of cores).
    #[arg(long, value_name = "N", value_parser = clap::value_parser!(u32).range(1..=256))]
    render_slots: Option<u32>,
    /// Worker threads shared by all renders (default: the number of cores).
    #[arg(long, value_name = "N", value_parser = clap::value_parser!(u32).range(1..=1024))]
    threads: Option<u32>,
    /// Largest request body, in bytes.
    #[arg(long, value_name = "BYTES", default_value_t = DEFAULT_MAX_REQUEST_BYTES)]
    max_request_bytes: usize,
    /// Largest image, in pixels (width × height).
    #[arg(long, value_name = "N", default_value_t = DEFAULT_MAX_PIXELS)]
    max_pixels: u64,
    /// Highest degree of an algebraic surface's equation.
    #[arg(long, value_name = "D", default_value_t = DEFAULT_MAX_DEGREE)]
    max_degree: u32,
    /// Longest render, in seconds, before it is cancelled.
    #[arg(long, value_name = "S", default_value_t = DEFAULT_MAX_RENDER_SECONDS)]
    max_render_seconds: u64,
}

/// The server's limits (documented in the README's "Explorer" section).
#[derive(Clone, Debug, serde::Serialize)]
pub(crate) struct Limits {
    pub(crate) max_request_bytes: usize,
    pub(crate) max_pixels: u64,
    pub(crate) max_degree: u32,
    pub(crate) max_render_seconds: u64,
    pub(crate) render_slots: usize,
    pub(crate) threads: usize,
}

/// Runs `render serve` with the arguments after `serve`.
pub(crate) fn main(args: impl Iterator<Item = std::ffi::OsString>) -> ExitCode {
    let args = ServeArgs::parse_from(args);
    match run(args) {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            let _ = writeln!(std::io::stderr(), "render serve: error: {e:#}");
            ExitCode::FAILURE
        }
    }
}

fn run(args: ServeArgs) -> anyhow::Result<()> {
    let cores = std::thread::available_parallelism().map_or(1, |n| n.get());
    let limits = Limits {
        max_request_bytes: args.max_request_bytes,
        max_pixels: args.max_pixels,
        max_degree: args.max_degree,
        max_render_seconds: args.max_render_seconds,
        render_slots: args.render_slots.map_or(cores, |n| n as usize),
        threads: args.threads.map_or(cores, |n| n as usize),
    };
    let scenes_dir = match (&args.scenes, &args.scene) {
        (Some(d), _) => d.clone(),
        (None, Some(s)) => s
            .parent()
            .filter(|p| !p.as_os_str().is_empty())
            .map_or_else(|| PathBuf::from("."), PathBuf::from),
        (None, None) if std::path::Path::new("scenes").is_dir() => PathBuf::from("scenes"),
        (None, None) => PathBuf::from("."),
    };
    let scenes_dir = scenes_dir
        .canonicalize()
        .with_context(|| format!("cannot open the scene directory {}", scenes_dir.display()))?;
    let initial = match &args.scene {
        Some(path) => {
            let text = std::fs::read_to_string(path)
                .with_context(|| format!("cannot read {}", path.display()))?;
            let name = path
                .file_name()
                .map(|n| n.to_string_lossy().into_owned())
                .unwrap_or_default();
            Some((name, text))
        }
        None => None,
    };
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(limits.threads)
        .thread_name(|i| format!("render-{i}"))
        .build()
        .context("cannot start the render threads")?;
    let state = Arc::new(api::AppState::new(limits, scenes_dir, initial, pool));

    let runtime = tokio::runtime::Builder::new_multi_thread()
        .worker_threads(2)
        .enable_all()
        .build()
        .context("cannot start the server runtime")?;
    runtime.block_on(async move {
        let addr = SocketAddr::new(args.bind, args.port);
        let listener = tokio::net::TcpListener::bind(addr)
            .await
            .with_context(|| format!("cannot listen on {addr}"))?;
        let local = listener.local_addr().context("no local address")?;
        // One write, and a closed stdout does not stop the server.
        let banner = format!(
            "render serve: explorer at http://{local}/\nrender serve: scenes from {}; Ctrl-C stops\n",
            state.scenes_dir.display()
        );
        let mut out = std::io::stdout().lock();
        let _ = out.write_all(banner.as_bytes()).and_then(|()| out.flush());
        drop(out);
        axum::serve(listener, api::router(state))
            .await
            .context("the server stopped")
    })?;
    runtime.shutdown_timeout(Duration::from_secs(1));
    Ok(())
}

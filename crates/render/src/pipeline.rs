//! [`render_scene`]: prepare, trace and write — one call for the CLI and for tests.

use std::path::{Path, PathBuf};
use std::time::Instant;

use crate::cancel::{Cancel, Cancelled};
use crate::film::{RenderOutput, RenderSettings, render_with_cancel};
use crate::options::RenderOptions;
use crate::output::{OutputError, PendingOutputs, encode_pfm, encode_png};
use crate::prepared::PreparedScene;
use crate::scene::{SceneInvalid, ValidScene, check_image_size};
use crate::stats::PhaseTimes;

/// Why a render failed.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum RenderError {
    /// The scene breaks an invariant.
    #[error("invalid scene")]
    Invalid(#[from] SceneInvalid),
    /// An option is out of range.
    #[error("{0}")]
    Option(String),
    /// Writing an output file failed, or an output path was refused before rendering.
    #[error(transparent)]
    Output(#[from] OutputError),
    /// The render was stopped through its [`Cancel`] token; no output was written.
    #[error(transparent)]
    Cancelled(#[from] Cancelled),
    /// The worker pool could not start.
    #[error("cannot start {threads} worker threads")]
    Threads {
        /// The requested count.
        threads: usize,
        /// The cause.
        #[source]
        source: rayon::ThreadPoolBuildError,
    },
}

/// The result of [`render_scene`].
#[derive(Debug)]
pub struct RenderReport {
    /// The image, depths and statistics.
    pub output: RenderOutput,
    /// Where the PNG was written.
    pub png_path: PathBuf,
    /// Time per phase (`parse` is left for the caller to fill in).
    pub times: PhaseTimes,
    /// Worker threads used.
    pub threads: usize,
}

/// Checks `opts` against `scene` and builds what [`render_with_cancel`] takes: the prepared
/// scene (with `opts`' patch method and root finder) and the settings (size, preview
/// resolution, samples, depth). [`render_scene`] renders exactly this; other front ends (the
/// `render serve` explorer) call it to get the same pixels without writing files. The
/// surfaces and the hierarchy are built in parallel on the current rayon pool: call it inside
/// the pool that will trace ([`rayon::ThreadPool::install`]), as [`render_scene`] does.
///
/// # Errors
/// [`RenderError::Option`] for a size beyond the pixel limit or zero samples,
/// [`RenderError::Invalid`] when the scene breaks an invariant.
pub fn prepare_render(
    scene: &ValidScene,
    opts: &RenderOptions,
) -> Result<(PreparedScene, RenderSettings), RenderError> {
    let size = opts.image_size(scene);
    check_image_size(size).map_err(RenderError::Option)?;
    if opts.samples == 0 {
        return Err(RenderError::Option("--samples must be at least 1".into()));
    }
    let prepared = PreparedScene::with_methods(scene, opts.roots, opts.patch_method)?;
    let settings = RenderSettings {
        size,
        resolution: scene.viewport.resolution,
        samples: opts.samples,
        depth: opts.depth.is_some(),
    };
    Ok((prepared, settings))
}

/// Renders `scene` with `opts` and writes the PNG (and the PFM depth map when asked).
/// `scene_path` names the default output file, and no output may overwrite it.
/// `progress` receives the number of finished rows and the total.
///
/// Every output path is checked before the render starts (see [`PendingOutputs`]), and the
/// files are replaced only when all of them were written: a failed run changes no file.
pub fn render_scene(
    scene: &ValidScene,
    scene_path: Option<&Path>,
    opts: &RenderOptions,
    progress: &(dyn Fn(u32, u32) + Sync),
) -> Result<RenderReport, RenderError> {
    render_scene_with_cancel(scene, scene_path, opts, progress, &Cancel::new())
}

/// [`render_scene`] that stops, writing nothing, when `cancel` is cancelled (see
/// [`render_with_cancel`]).
pub fn render_scene_with_cancel(
    scene: &ValidScene,
    scene_path: Option<&Path>,
    opts: &RenderOptions,
    progress: &(dyn Fn(u32, u32) + Sync),
    cancel: &Cancel,
) -> Result<RenderReport, RenderError> {
    let pool = thread_pool(opts.threads)?;
    render_scene_in(&pool, scene, scene_path, opts, progress, cancel)
}

/// The worker pool of a render: `threads` threads (all cores when `None`). A front end that
/// loads the scene too builds it first and loads inside it ([`rayon::ThreadPool::install`]),
/// so that a large NFF file is read on the render's threads
/// ([`parse_nff`](crate::scene::parse_nff)), then renders with [`render_scene_in`]: one pool
/// per render, and never rayon's global one.
///
/// # Errors
/// [`RenderError::Threads`] when the threads cannot start.
pub fn thread_pool(threads: Option<usize>) -> Result<rayon::ThreadPool, RenderError> {
    let mut builder = rayon::ThreadPoolBuilder::new();
    if let Some(t) = threads {
        builder = builder.num_threads(t);
    }
    builder.build().map_err(|source| RenderError::Threads {
        threads: threads.unwrap_or(0),
        source,
    })
}

/// [`render_scene_with_cancel`] on the worker pool `pool` ([`thread_pool`]) instead of one of
/// its own; `opts.threads` is not read.
pub fn render_scene_in(
    pool: &rayon::ThreadPool,
    scene: &ValidScene,
    scene_path: Option<&Path>,
    opts: &RenderOptions,
    progress: &(dyn Fn(u32, u32) + Sync),
    cancel: &Cancel,
) -> Result<RenderReport, RenderError> {
    if !matches!(opts.png.bits, 8 | 16) {
        return Err(OutputError::BitDepth(opts.png.bits).into());
    }
    let png_path = opts.output_path(scene, scene_path);
    let mut targets = vec![png_path.as_path()];
    targets.extend(opts.depth.as_deref());
    let inputs: Vec<&Path> = scene_path.into_iter().collect();
    let mut outputs = PendingOutputs::prepare(&targets, &inputs)?;
    let setup_start = Instant::now();
    // The set-up's parallel parts (surfaces, BVH) run on the render's threads too: on rayon's
    // global pool they ignored `--threads` and started a second pool.
    let (prepared, settings) = pool.install(|| prepare_render(scene, opts))?;
    let size = settings.size;
    let setup = setup_start.elapsed();

    let trace_start = Instant::now();
    let total = size[1];
    let output = pool.install(|| {
        render_with_cancel(
            &prepared,
            &scene.camera,
            &settings,
            &|done| progress(done, total),
            cancel,
        )
    })?;
    let trace = trace_start.elapsed();

    let write_start = Instant::now();
    outputs.write(0, |out| encode_png(&output.film, out, &opts.png, &png_path))?;
    if let Some(depth_path) = &opts.depth {
        outputs.write(1, |out| encode_pfm(&output.film, depth_path, out))?;
    }
    outputs.commit()?;
    let write = write_start.elapsed();
    Ok(RenderReport {
        output,
        png_path,
        times: PhaseTimes {
            parse: Default::default(),
            setup,
            trace,
            write,
        },
        threads: pool.current_num_threads(),
    })
}

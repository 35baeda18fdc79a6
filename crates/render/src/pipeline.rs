//! [`render_scene`]: validate, prepare, trace and write — one call for the CLI and for tests.

use std::path::{Path, PathBuf};
use std::time::Instant;

use crate::film::{RenderOutput, RenderSettings, render};
use crate::options::RenderOptions;
use crate::output::{OutputError, write_pfm, write_png};
use crate::prepared::PreparedScene;
use crate::scene::{Scene, SceneInvalid};
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
    /// Writing an output file failed.
    #[error(transparent)]
    Output(#[from] OutputError),
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

/// Checks `opts` against `scene` and builds what [`render`] takes: the prepared scene (with
/// `opts`' patch method and root finder) and the settings (size, preview resolution, samples,
/// depth). [`render_scene`] renders exactly this; other front ends (the `render serve`
/// explorer) call it to get the same pixels without writing files.
///
/// # Errors
/// [`RenderError::Option`] for a zero size or zero samples, [`RenderError::Invalid`] when
/// the scene breaks an invariant.
pub fn prepare_render(
    scene: &Scene,
    opts: &RenderOptions,
) -> Result<(PreparedScene, RenderSettings), RenderError> {
    let size = opts.image_size(scene);
    if size.contains(&0) {
        return Err(RenderError::Option(format!(
            "image size {}x{} must be positive",
            size[0], size[1]
        )));
    }
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
/// `scene_path` only names the default output file. `progress` receives the number of
/// finished rows and the total.
pub fn render_scene(
    scene: &Scene,
    scene_path: Option<&Path>,
    opts: &RenderOptions,
    progress: &(dyn Fn(u32, u32) + Sync),
) -> Result<RenderReport, RenderError> {
    let setup_start = Instant::now();
    let (prepared, settings) = prepare_render(scene, opts)?;
    let size = settings.size;
    let mut builder = rayon::ThreadPoolBuilder::new();
    if let Some(t) = opts.threads {
        builder = builder.num_threads(t);
    }
    let requested = opts.threads.unwrap_or(0);
    let pool = builder.build().map_err(|source| RenderError::Threads {
        threads: requested,
        source,
    })?;
    let setup = setup_start.elapsed();

    let trace_start = Instant::now();
    let total = size[1];
    let output = pool.install(|| {
        render(&prepared, &scene.camera, &settings, &|done| {
            progress(done, total)
        })
    });
    let trace = trace_start.elapsed();

    let write_start = Instant::now();
    let png_path = opts.output_path(scene, scene_path);
    write_png(&output.film, &png_path, &opts.png)?;
    if let Some(depth_path) = &opts.depth {
        write_pfm(&output.film, depth_path)?;
    }
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

//! [`render`]: the pixel loop — camera rays, stratified supersampling, Stam's preview
//! resolution, rayon over rows with per-thread statistics.

use std::sync::atomic::{AtomicU32, Ordering};
use std::time::{Duration, Instant};

use glam::DVec3;
use rayon::prelude::*;

use crate::camera::Camera;
use crate::cancel::{Cancel, Cancelled};
use crate::prepared::PreparedScene;
use crate::scene::{CameraSpec, Rgb};
use crate::stats::{Escalations, SlowObject, SlowestCell, TraceStats};
use crate::whitted::{nearest_hit, trace_primary};
use crate::workspace::Workspace;

/// What to render: size, sampling and whether to keep depths.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct RenderSettings {
    /// Image width and height in pixels (positive).
    pub size: [u32; 2],
    /// Stam's preview resolution: one cell of `rx × ry` pixels shares its samples (`[1, 1]`
    /// for every pixel).
    pub resolution: [u32; 2],
    /// `N` for `N × N` stratified samples per cell (`1`: one ray through the cell centre).
    pub samples: u32,
    /// Record the distance of the primary hit through each cell centre.
    pub depth: bool,
}

/// A rendered image: linear colours and coverage, plus optional depths.
#[derive(Clone, Debug, PartialEq)]
pub struct Film {
    /// Width in pixels.
    pub width: u32,
    /// Height in pixels.
    pub height: u32,
    /// Row-major linear RGB and alpha (coverage: the fraction of samples that hit an object),
    /// first row at the top.
    pub pixels: Vec<[f32; 4]>,
    /// Row-major primary-hit distances (`+∞` for a miss), when requested.
    pub depth: Option<Vec<f32>>,
}

impl Film {
    /// The pixel at column `x`, row `y` (row 0 at the top).
    ///
    /// # Panics
    /// If `(x, y)` is outside the image.
    pub fn pixel(&self, x: u32, y: u32) -> [f32; 4] {
        assert!(
            x < self.width && y < self.height,
            "pixel ({x}, {y}) outside the image"
        );
        self.pixels[(y * self.width + x) as usize]
    }
}

/// A finished render: the film and the merged statistics.
#[derive(Clone, Debug)]
pub struct RenderOutput {
    /// The image.
    pub film: Film,
    /// Counters merged over all threads.
    pub stats: TraceStats,
}

/// Renders `scene` seen by `camera` on the current rayon pool. `progress` is called with the
/// number of image rows finished so far (from worker threads, in no particular order).
///
/// Output is deterministic whatever the number of threads: every sample position comes from a
/// hash of its pixel and stratum, and no pixel depends on another.
pub fn render(
    scene: &PreparedScene,
    camera: &CameraSpec,
    settings: &RenderSettings,
    progress: &(dyn Fn(u32) + Sync),
) -> RenderOutput {
    match render_with_cancel(scene, camera, settings, progress, &Cancel::new()) {
        Ok(out) => out,
        Err(Cancelled) => unreachable!("a token nobody holds is never cancelled"),
    }
}

/// [`render`] that stops when `cancel` is cancelled: every worker checks the token before
/// each cell, so the call returns within one cell's rays per thread.
///
/// # Errors
/// [`Cancelled`] when the token was cancelled before the last cell was done.
pub fn render_with_cancel(
    scene: &PreparedScene,
    camera: &CameraSpec,
    settings: &RenderSettings,
    progress: &(dyn Fn(u32) + Sync),
    cancel: &Cancel,
) -> Result<RenderOutput, Cancelled> {
    let [width, height] = settings.size;
    let [rx, ry] = settings.resolution.map(|r| r.max(1));
    let camera = Camera::new(camera, width, height);
    let n = settings.samples.max(1);
    let (w, h) = (width as usize, height as usize);
    let mut pixels = vec![[0.0f32; 4]; w * h];
    let mut depth = vec![f32::INFINITY; if settings.depth { w * h } else { 0 }];
    let rows_done = AtomicU32::new(0);
    let band = w * ry as usize;

    let render_band =
        |ws: &mut Workspace, cy: usize, band_px: &mut [[f32; 4]], band_depth: &mut [f32]| {
            let y0 = cy * ry as usize;
            let rows = band_px.len() / w;
            // The clock is read per band, not per cell: two reads per pixel cost a tenth of
            // a torus render. The slowest band's cells are timed one by one after the render.
            let started = Instant::now();
            let before = (Escalations::of(&ws.stats.roots), ws.stats.total_rays());
            let mut cx = 0;
            while cx * (rx as usize) < w {
                if cancel.is_cancelled() {
                    return;
                }
                let x0 = cx * rx as usize;
                let cols = (rx as usize).min(w - x0);
                let cell = [x0 as f64, y0 as f64, cols as f64, rows as f64];
                let (color, alpha, centre_depth) = render_cell(scene, &camera, cell, n, ws);
                let px = [color.x as f32, color.y as f32, color.z as f32, alpha as f32];
                let d = match (settings.depth, centre_depth) {
                    (false, _) => 0.0,
                    (true, Some(d)) => d as f32,
                    (true, None) => {
                        let (cxm, cym) = (cell[0] + cell[2] / 2.0, cell[1] + cell[3] / 2.0);
                        cell_depth(scene, &camera, cxm, cym, ws) as f32
                    }
                };
                for r in 0..rows {
                    for c in 0..cols {
                        band_px[r * w + x0 + c] = px;
                        if settings.depth {
                            band_depth[r * w + x0 + c] = d;
                        }
                    }
                }
                cx += 1;
            }
            let elapsed = started.elapsed();
            if ws.stats.slowest.is_none_or(|s| elapsed > s.elapsed) {
                ws.stats.slowest = Some(SlowestCell {
                    pixel: [0, y0 as u32],
                    size: [w as u32, rows as u32],
                    elapsed,
                    rays: ws.stats.total_rays() - before.1,
                    escalations: Escalations::of(&ws.stats.roots).since(&before.0),
                    object: None,
                });
            }
            let done = rows_done.fetch_add(rows as u32, Ordering::Relaxed) + rows as u32;
            progress(done);
        };

    let mut stats = if settings.depth {
        pixels
            .par_chunks_mut(band)
            .zip(depth.par_chunks_mut(band))
            .enumerate()
            .fold(Workspace::new, |mut ws, (cy, (bp, bd))| {
                render_band(&mut ws, cy, bp, bd);
                ws
            })
            .map(|ws| ws.stats)
            .reduce(TraceStats::default, |mut a, b| {
                a.merge(&b);
                a
            })
    } else {
        pixels
            .par_chunks_mut(band)
            .enumerate()
            .fold(Workspace::new, |mut ws, (cy, bp)| {
                render_band(&mut ws, cy, bp, &mut []);
                ws
            })
            .map(|ws| ws.stats)
            .reduce(TraceStats::default, |mut a, b| {
                a.merge(&b);
                a
            })
    };
    stats.bvh = scene.aggregate.bvh_info();
    cancel.check()?;
    if let Some(band) = stats.slowest {
        let mut cell = slowest_cell_of_band(scene, &camera, &band, rx, n);
        cell.object = slowest_object(scene, &camera, &cell);
        stats.slowest = Some(cell);
    }
    let film = Film {
        width,
        height,
        pixels,
        depth: settings.depth.then_some(depth),
    };
    Ok(RenderOutput { film, stats })
}

/// Colour and coverage of one cell `[x, y, w, h]` (pixel units) from `n × n` stratified
/// samples: one per stratum, jittered inside it by a hash of the cell and stratum (`n = 1`:
/// the centre, no jitter). The third value is the centre ray's hit distance when a sample
/// went through the centre.
fn render_cell(
    scene: &PreparedScene,
    camera: &Camera,
    cell: [f64; 4],
    n: u32,
    ws: &mut Workspace,
) -> (Rgb, f64, Option<f64>) {
    let [x, y, cw, ch] = cell;
    if n == 1 {
        let ray = camera.ray(x + cw / 2.0, y + ch / 2.0);
        let s = trace_primary(scene, &ray, ws);
        return (
            s.color,
            if s.depth.is_finite() { 1.0 } else { 0.0 },
            Some(s.depth),
        );
    }
    let mut sum = DVec3::ZERO;
    let mut hits = 0u32;
    let inv = 1.0 / f64::from(n);
    for j in 0..n {
        for i in 0..n {
            let key = ((x as u64) << 40) ^ ((y as u64) << 16) ^ u64::from(j * n + i);
            let (ju, jv) = jitter(key);
            let sx = x + cw * (f64::from(i) + ju) * inv;
            let sy = y + ch * (f64::from(j) + jv) * inv;
            let s = trace_primary(scene, &camera.ray(sx, sy), ws);
            sum += s.color;
            if s.depth.is_finite() {
                hits += 1;
            }
        }
    }
    let count = f64::from(n * n);
    (sum / count, f64::from(hits) / count, None)
}

/// The slowest cell of the slowest band (`band`: its rows, the whole image width), found by
/// tracing the band's cells again one by one on a fresh workspace after the render; its time,
/// rays and escalations are those of the re-trace.
fn slowest_cell_of_band(
    scene: &PreparedScene,
    camera: &Camera,
    band: &SlowestCell,
    rx: u32,
    n: u32,
) -> SlowestCell {
    let [_, y0] = band.pixel;
    let [width, rows] = band.size;
    let mut slowest = *band;
    slowest.elapsed = Duration::ZERO;
    let mut ws = Workspace::new();
    for x0 in (0..width).step_by(rx as usize) {
        let cols = rx.min(width - x0);
        let cell = [
            f64::from(x0),
            f64::from(y0),
            f64::from(cols),
            f64::from(rows),
        ];
        let before = (Escalations::of(&ws.stats.roots), ws.stats.total_rays());
        let started = Instant::now();
        let _ = render_cell(scene, camera, cell, n, &mut ws);
        let elapsed = started.elapsed();
        if elapsed >= slowest.elapsed {
            slowest = SlowestCell {
                pixel: [x0, y0],
                size: [cols, rows],
                elapsed,
                rays: ws.stats.total_rays() - before.1,
                escalations: Escalations::of(&ws.stats.roots).since(&before.0),
                object: None,
            };
        }
    }
    slowest
}

/// The object whose nearest-hit query on the centre camera ray of `cell` takes longest, each
/// object queried alone with fresh counters (one ray per object, after the render).
///
/// Only the objects the scene's aggregate offers that ray are queried (those whose boxes it
/// crosses, and the unbounded ones): any other is rejected by its box before its surface is
/// asked anything. Querying every object, with two clock reads each, cost the 66 430-sphere
/// SPD sphereflake 40 M instructions at any image size (`docs/speed.md`, issue 12, twelfth
/// session).
///
/// One workspace serves every object, its counters reset before each: a fresh workspace per
/// object zeroed the Bézier solver's buffers each time, which cost more than the whole render
/// of the 66 430-sphere SPD scene at 128² (`docs/speed.md`, "BVH traversal, third pass").
fn slowest_object(
    scene: &PreparedScene,
    camera: &Camera,
    cell: &SlowestCell,
) -> Option<SlowObject> {
    let [x, y] = cell.pixel.map(f64::from);
    let [w, h] = cell.size.map(f64::from);
    let ray = camera.ray(x + w / 2.0, y + h / 2.0);
    let mut slowest: Option<SlowObject> = None;
    let mut ws = Workspace::new();
    let mut visits = 0;
    scene
        .aggregate
        .any(&ray, 0.0..f64::INFINITY, &mut visits, |item| {
            let index = item as usize;
            let surface = &scene.surfaces[index];
            ws.stats = TraceStats::default();
            let started = Instant::now();
            let _ = surface.intersect(&ray, 0.0..f64::INFINITY, &mut ws);
            let elapsed = started.elapsed();
            if slowest.is_none_or(|s| elapsed > s.elapsed) {
                slowest = Some(SlowObject {
                    index,
                    kind: surface.kind(),
                    elapsed,
                    escalations: Escalations::of(&ws.stats.roots),
                });
            }
            // Never a blocker: every object the ray reaches is queried.
            false
        });
    slowest
}

/// Distance to the first hit through image position `(x, y)`, `+∞` for a miss.
fn cell_depth(scene: &PreparedScene, camera: &Camera, x: f64, y: f64, ws: &mut Workspace) -> f64 {
    let ray = camera.ray(x, y);
    match nearest_hit(scene, &ray, 0.0..f64::INFINITY, ws) {
        Some((_, hit)) => hit.t * ray.dir.length(),
        None => f64::INFINITY,
    }
}

/// Two numbers in `[0, 1)` from a 64-bit key (SplitMix64 finaliser): a deterministic
/// per-sample jitter, independent of thread scheduling.
fn jitter(key: u64) -> (f64, f64) {
    let mut z = key.wrapping_add(0x9E37_79B9_7F4A_7C15);
    z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
    z ^= z >> 31;
    let a = (z >> 40) as f64 / (1u64 << 24) as f64;
    let b = ((z >> 8) & 0xFF_FFFF) as f64 / (1u64 << 24) as f64;
    (a, b)
}

//! The HTTP API of the explorer and the static page.
//!
//! - `GET /` (and `/app.js`, `/style.css`): the page, embedded in the binary.
//! - `GET /api/scenes`: the gallery, `{ "scenes": [names], "initial": name }`;
//!   `GET /api/scenes/{name}`: a scene's text.
//! - `GET /api/limits`: the server's limits.
//! - `POST /api/render`: a render of `{ session, scene | equation, params, camera, name,
//!   scale }` as JSON (PNG in base64, stats, `Let` sliders, camera places); `409` when a newer
//!   request of the same session cancelled it, `422` with `line`/`col` for a scene error,
//!   `413` for an oversized request, `400` for a refused size, `503` for a render over time.
//! - `POST /api/png`: the same request at full size, answered with the PNG file itself.
//! - `POST /api/cancel`: `{ session }` cancels that session's render.

use std::collections::{BTreeMap, HashMap};
use std::path::{Path, PathBuf};
use std::sync::{Arc, Mutex};
use std::time::{Duration, Instant};

use axum::Json;
use axum::Router;
use axum::body::{Body, Bytes};
use axum::extract::{DefaultBodyLimit, Path as UrlPath, Request, State};
use axum::http::{StatusCode, header};
use axum::response::{IntoResponse, Response};
use axum::routing::{get, post};
use base64::Engine as _;
use render::scene::{SceneError, build, parse_syntax};
use render::{Cancel, PhaseTimes, RenderOptions, StatsReport};
use serde::{Deserialize, Serialize};
use serde_json::json;

use super::Limits;
use super::equation::{self, CameraIn, EquationScene};
use super::scene_info::{self, CameraInfo, LetInfo, Refusal};

const INDEX_HTML: &str = include_str!("../../assets/index.html");
const APP_JS: &str = include_str!("../../assets/app.js");
const STYLE_CSS: &str = include_str!("../../assets/style.css");

/// Longest session id accepted: the page sends a random 16-character id.
const MAX_SESSION_LEN: usize = 64;

/// The largest preview reduction: a 1/64 image of an 840² scene is 14² pixels, the
/// coarsest that still shows a shape.
const MAX_SCALE: u32 = 64;

/// The shared state: limits, the scene directory, the render pool and slots, and the cancel
/// flag of each session's render in flight.
pub(crate) struct AppState {
    limits: Limits,
    pub(crate) scenes_dir: PathBuf,
    initial: Option<(String, String)>,
    pool: rayon::ThreadPool,
    slots: Arc<tokio::sync::Semaphore>,
    sessions: Mutex<HashMap<String, Cancel>>,
}

impl AppState {
    pub(crate) fn new(
        limits: Limits,
        scenes_dir: PathBuf,
        initial: Option<(String, String)>,
        pool: rayon::ThreadPool,
    ) -> Self {
        let slots = Arc::new(tokio::sync::Semaphore::new(limits.render_slots));
        AppState {
            limits,
            scenes_dir,
            initial,
            pool,
            slots,
            sessions: Mutex::new(HashMap::new()),
        }
    }

    /// Registers a new render for `session`, cancelling the one in flight.
    fn begin(&self, session: &str) -> Cancel {
        let flag = Cancel::new();
        let mut sessions = self.sessions.lock().unwrap_or_else(|e| e.into_inner());
        if let Some(old) = sessions.insert(session.to_owned(), flag.clone()) {
            old.cancel();
        }
        flag
    }

    /// Forgets `session`'s render if `flag` is still its latest.
    fn end(&self, session: &str, flag: &Cancel) {
        let mut sessions = self.sessions.lock().unwrap_or_else(|e| e.into_inner());
        if sessions.get(session).is_some_and(|f| f.is_same(flag)) {
            sessions.remove(session);
        }
    }

    fn cancel(&self, session: &str) -> bool {
        let sessions = self.sessions.lock().unwrap_or_else(|e| e.into_inner());
        sessions.get(session).inspect(|f| f.cancel()).is_some()
    }
}

/// Builds the router.
pub(crate) fn router(state: Arc<AppState>) -> Router {
    Router::new()
        .route(
            "/",
            get(|| async { page(INDEX_HTML, "text/html; charset=utf-8") }),
        )
        .route(
            "/app.js",
            get(|| async { page(APP_JS, "text/javascript; charset=utf-8") }),
        )
        .route(
            "/style.css",
            get(|| async { page(STYLE_CSS, "text/css; charset=utf-8") }),
        )
        .route("/api/scenes", get(scenes))
        .route("/api/scenes/{name}", get(scene_text))
        .route("/api/limits", get(limits))
        .route("/api/render", post(render_json))
        .route("/api/png", post(render_png))
        .route("/api/cancel", post(cancel))
        // Bodies are read by `read_json` with the server's own limit and message.
        .layer(DefaultBodyLimit::disable())
        .with_state(state)
}

fn page(body: &'static str, kind: &'static str) -> Response {
    ([(header::CONTENT_TYPE, kind)], body).into_response()
}

/// A failed request: status and a JSON body `{ error, line?, col? }`.
#[derive(Debug)]
pub(crate) struct Failure {
    status: StatusCode,
    message: String,
    at: Option<(u32, u32)>,
}

impl Failure {
    fn new(status: StatusCode, message: impl Into<String>) -> Self {
        Failure {
            status,
            message: message.into(),
            at: None,
        }
    }
}

impl IntoResponse for Failure {
    fn into_response(self) -> Response {
        let mut body = json!({ "error": self.message });
        if let Some((line, col)) = self.at {
            body["line"] = json!(line);
            body["col"] = json!(col);
        }
        if self.status == StatusCode::CONFLICT {
            body["cancelled"] = json!(true);
        }
        (self.status, Json(body)).into_response()
    }
}

/// The error and its causes, `a: b: c` (as the CLI prints them).
fn chain(e: &dyn std::error::Error) -> String {
    let mut s = e.to_string();
    let mut cause = e.source();
    while let Some(c) = cause {
        s.push_str(": ");
        s.push_str(&c.to_string());
        cause = c.source();
    }
    s
}

/// Bytes of an oversized request body read and discarded before the `413` answer, beyond the
/// limit: answering before the body is read and closing the connection left a client that was
/// still sending with a broken pipe instead of the answer (test
/// `an_oversized_body_is_answered_413_not_a_reset_connection`). A body larger still is not
/// drained (a flood, not a mistake): the answer is sent at once and the connection closed.
const DRAIN_MAX_BYTES: u64 = 64 << 20;

async fn read_json<T: for<'de> Deserialize<'de>>(
    state: &AppState,
    request: Request,
) -> Result<T, Failure> {
    let limit = state.limits.max_request_bytes;
    let bytes = read_body(request.into_body(), limit).await?;
    serde_json::from_slice(&bytes)
        .map_err(|e| Failure::new(StatusCode::BAD_REQUEST, format!("malformed request: {e}")))
}

/// The request body, at most `limit` bytes; a larger one is drained (up to
/// [`DRAIN_MAX_BYTES`] more) and refused with `413`.
async fn read_body(mut body: Body, limit: usize) -> Result<Bytes, Failure> {
    use http_body_util::BodyExt as _;
    let too_large = || {
        Failure::new(
            StatusCode::PAYLOAD_TOO_LARGE,
            format!(
                "the request is larger than this server's limit of {limit} bytes (--max-request-bytes)"
            ),
        )
    };
    let drain_to = (limit as u64).saturating_add(DRAIN_MAX_BYTES);
    if axum::body::HttpBody::size_hint(&body).lower() > drain_to {
        return Err(too_large());
    }
    let mut kept = Vec::new();
    let mut seen: u64 = 0;
    while let Some(frame) = body.frame().await {
        let frame = frame.map_err(|e| {
            Failure::new(
                StatusCode::BAD_REQUEST,
                format!("the request body could not be read: {e}"),
            )
        })?;
        let Ok(data) = frame.into_data() else {
            continue; // trailers
        };
        seen += data.len() as u64;
        if seen <= limit as u64 {
            kept.extend_from_slice(&data);
        } else if seen > drain_to {
            break;
        }
    }
    if seen > limit as u64 {
        return Err(too_large());
    }
    Ok(Bytes::from(kept))
}

async fn scenes(State(state): State<Arc<AppState>>) -> Response {
    let mut names: Vec<String> = std::fs::read_dir(&state.scenes_dir)
        .into_iter()
        .flatten()
        .flatten()
        .filter_map(|e| e.file_name().into_string().ok())
        .filter(|n| n.ends_with(".scene"))
        .collect();
    names.sort();
    let initial = state
        .initial
        .as_ref()
        .map(|(n, t)| json!({"name": n, "text": t}));
    Json(json!({ "scenes": names, "initial": initial })).into_response()
}

/// A gallery name: a plain `.scene` file name in the scene directory.
fn gallery_path(state: &AppState, name: &str) -> Option<PathBuf> {
    let plain = !name.is_empty()
        && name.ends_with(".scene")
        && !name.starts_with('.')
        && !name.contains(['/', '\\']);
    plain.then(|| state.scenes_dir.join(name))
}

async fn scene_text(
    State(state): State<Arc<AppState>>,
    UrlPath(name): UrlPath<String>,
) -> Response {
    let Some(path) = gallery_path(&state, &name) else {
        return Failure::new(
            StatusCode::NOT_FOUND,
            format!("no scene `{name}` in the gallery"),
        )
        .into_response();
    };
    match std::fs::read_to_string(&path) {
        Ok(text) => ([(header::CONTENT_TYPE, "text/plain; charset=utf-8")], text).into_response(),
        Err(e) => Failure::new(
            StatusCode::NOT_FOUND,
            format!("cannot read scene `{name}`: {e}"),
        )
        .into_response(),
    }
}

async fn limits(State(state): State<Arc<AppState>>) -> Response {
    Json(&state.limits).into_response()
}

#[derive(Debug, Deserialize)]
struct CancelRequest {
    session: String,
}

async fn cancel(State(state): State<Arc<AppState>>, request: Request) -> Response {
    match read_json::<CancelRequest>(&state, request).await {
        Ok(r) => Json(json!({ "cancelled": state.cancel(&r.session) })).into_response(),
        Err(f) => f.into_response(),
    }
}

/// What the page asks to render.
#[derive(Debug, Deserialize)]
pub(crate) struct RenderRequest {
    /// The tab: a newer request of the same session cancels this one.
    session: String,
    /// The full scene text (scene mode).
    #[serde(default)]
    scene: Option<String>,
    /// The gallery file the text came from (names the text in messages).
    #[serde(default)]
    name: Option<String>,
    /// The equation (simple mode).
    #[serde(default)]
    equation: Option<String>,
    /// Simple mode: values of the equation's parameters.
    #[serde(default)]
    params: BTreeMap<String, f64>,
    /// Simple mode: the camera.
    #[serde(default)]
    camera: Option<CameraIn>,
    /// Reduction of the preview: `1` full size, `8` one eighth of each side.
    #[serde(default = "full_scale")]
    scale: u32,
}

fn full_scale() -> u32 {
    1
}

/// A finished render.
#[derive(Debug, Serialize)]
struct Rendered {
    #[serde(skip)]
    png: Vec<u8>,
    #[serde(skip)]
    file_name: String,
    width: u32,
    height: u32,
    scale: u32,
    /// The `--stats` report.
    stats: String,
    lets: Vec<LetInfo>,
    camera: CameraInfo,
    /// The scene text rendered (simple mode: the generated scene).
    scene: Option<String>,
    /// Server-side milliseconds per phase.
    times_ms: BTreeMap<&'static str, f64>,
}

fn ms(d: Duration) -> f64 {
    d.as_secs_f64() * 1e3
}

/// Parses, checks and renders one request on the shared pool; `None` when cancelled.
fn render_job(
    state: &AppState,
    req: &RenderRequest,
    cancel: &Cancel,
) -> Result<Option<Rendered>, Failure> {
    if cancel.is_cancelled() {
        return Ok(None);
    }
    let parse_start = Instant::now();
    let (text, file, equation): (&str, PathBuf, Option<EquationScene>) =
        match (&req.scene, &req.equation) {
            (Some(text), None) => {
                let name = req.name.as_deref().unwrap_or("untitled.scene");
                let file = gallery_path(state, name)
                    .unwrap_or_else(|| state.scenes_dir.join("untitled.scene"));
                (text, file, None)
            }
            (None, Some(eq)) => {
                let s = equation::scene(eq, &req.params, req.camera.as_ref());
                ("", state.scenes_dir.join("equation.scene"), Some(s))
            }
            _ => {
                return Err(Failure::new(
                    StatusCode::BAD_REQUEST,
                    "send either `scene` or `equation`",
                ));
            }
        };
    let text = equation.as_ref().map_or(text, |e| e.text.as_str());
    // A place in the generated scene of the simple mode is reported inside the equation.
    let place = |line: u32, col: u32| match &equation {
        Some(e) => e.to_equation(line, col),
        None => Some((line, col)),
    };
    let located = |e: SceneError| {
        let at = e.span().and_then(|s| place(s.line, s.col));
        let message = match (e.kind(), at) {
            (Some(kind), Some((line, col))) => format!("{line}:{col}: {kind}"),
            _ => chain(&e),
        };
        Failure {
            status: StatusCode::UNPROCESSABLE_ENTITY,
            message,
            at,
        }
    };
    let refused = |r: Refusal| {
        let at = r.at.and_then(|(l, c)| place(l, c));
        Failure {
            status: StatusCode::UNPROCESSABLE_ENTITY,
            message: match at {
                Some((l, c)) => format!("{l}:{c}: {}", r.message),
                None => r.message,
            },
            at,
        }
    };
    let ast = parse_syntax(text, &file).map_err(located)?;
    scene_info::confine_files(&ast, &state.scenes_dir).map_err(refused)?;
    let scene = build(&ast, &file).map_err(located)?;
    scene_info::check_degree(&ast, &scene, state.limits.max_degree).map_err(refused)?;
    let parse = parse_start.elapsed();

    let [w, h] = scene.viewport.size;
    let pixels = u64::from(w) * u64::from(h);
    if pixels > state.limits.max_pixels {
        return Err(Failure::new(
            StatusCode::BAD_REQUEST,
            format!(
                "the image is {w}x{h} = {pixels} pixels; this server renders at most {} pixels (--max-pixels)",
                state.limits.max_pixels
            ),
        ));
    }
    let scale = req.scale.clamp(1, MAX_SCALE);
    let mut opts = RenderOptions::default();
    if scale > 1 {
        opts.size = Some([w.div_ceil(scale), h.div_ceil(scale)]);
    }
    let setup_start = Instant::now();
    // On the shared pool, as the trace: the set-up is parallel too (surfaces, BVH), and on
    // rayon's global pool it would run beside the bounded one.
    let (prepared, mut settings) = state
        .pool
        .install(|| render::prepare_render(&scene, &opts))
        .map_err(|e| Failure::new(StatusCode::UNPROCESSABLE_ENTITY, chain(&e)))?;
    if scale > 1 {
        // A preview traces every pixel of the small image: Stam's `Resolution` cells would
        // coarsen it a second time.
        settings.resolution = [1, 1];
    }
    let setup = setup_start.elapsed();
    let trace_start = Instant::now();
    let output = state.pool.install(|| {
        render::render_with_cancel(&prepared, &scene.camera, &settings, &|_| {}, cancel).ok()
    });
    let Some(output) = output else {
        return Ok(None);
    };
    let trace = trace_start.elapsed();
    let encode_start = Instant::now();
    let file_name = opts
        .output_path(&scene, Some(file.as_path()))
        .file_name()
        .map_or_else(|| "render.png".into(), |n| n.to_string_lossy().into_owned());
    let mut png = Vec::new();
    render::encode_png(&output.film, &mut png, &opts.png, Path::new(&file_name))
        .map_err(|e| Failure::new(StatusCode::INTERNAL_SERVER_ERROR, chain(&e)))?;
    let write = encode_start.elapsed();
    let report = StatsReport {
        stats: &output.stats,
        times: PhaseTimes {
            parse,
            setup,
            trace,
            write,
        },
        size: settings.size,
        samples_per_pixel: opts.samples * opts.samples,
        threads: state.pool.current_num_threads(),
        roots: opts.roots,
    };
    let times_ms = BTreeMap::from([
        ("parse", ms(parse)),
        ("setup", ms(setup)),
        ("trace", ms(trace)),
        ("encode", ms(write)),
    ]);
    Ok(Some(Rendered {
        png,
        file_name,
        width: settings.size[0],
        height: settings.size[1],
        scale,
        stats: report.to_string(),
        lets: scene_info::lets(&ast, text),
        camera: scene_info::camera(&ast, &scene, text),
        scene: equation.map(|e| e.text),
        times_ms,
    }))
}

/// Sets a render's cancel flag when the request is dropped (the client went away) or done.
struct CancelOnDrop(Cancel);

impl Drop for CancelOnDrop {
    fn drop(&mut self) {
        self.0.cancel();
    }
}

/// Runs [`render_job`] in a render slot, under the session's cancel flag and the time limit.
async fn render_request(state: Arc<AppState>, req: RenderRequest) -> Result<Rendered, Failure> {
    if req.session.is_empty() || req.session.len() > MAX_SESSION_LEN {
        return Err(Failure::new(
            StatusCode::BAD_REQUEST,
            format!("`session` must be 1 to {MAX_SESSION_LEN} bytes"),
        ));
    }
    let session = req.session.clone();
    let flag = state.begin(&session);
    let _guard = CancelOnDrop(flag.clone());
    let result = async {
        let permit = Arc::clone(&state.slots)
            .acquire_owned()
            .await
            .map_err(|_| Failure::new(StatusCode::SERVICE_UNAVAILABLE, "the server is stopping"))?;
        let job = {
            let (state, flag) = (Arc::clone(&state), flag.clone());
            tokio::task::spawn_blocking(move || {
                let _permit = permit;
                render_job(&state, &req, &flag)
            })
        };
        let limit = Duration::from_secs(state.limits.max_render_seconds);
        let mut job = std::pin::pin!(job);
        let joined = match tokio::time::timeout(limit, &mut job).await {
            Ok(j) => j,
            Err(_) => {
                flag.cancel();
                let _ = job.await;
                return Err(Failure::new(
                    StatusCode::SERVICE_UNAVAILABLE,
                    format!(
                        "the render took longer than this server's limit of {} s (--max-render-seconds)",
                        state.limits.max_render_seconds
                    ),
                ));
            }
        };
        let rendered = joined
            .map_err(|e| Failure::new(StatusCode::INTERNAL_SERVER_ERROR, format!("the render failed: {e}")))??;
        rendered.ok_or_else(|| {
            Failure::new(StatusCode::CONFLICT, "cancelled by a newer request of this page")
        })
    }
    .await;
    state.end(&session, &flag);
    result
}

async fn render_json(State(state): State<Arc<AppState>>, request: Request) -> Response {
    let req = match read_json::<RenderRequest>(&state, request).await {
        Ok(r) => r,
        Err(f) => return f.into_response(),
    };
    match render_request(state, req).await {
        Ok(r) => {
            let mut body = serde_json::to_value(&r).unwrap_or_default();
            body["png"] = json!(base64::engine::general_purpose::STANDARD.encode(&r.png));
            Json(body).into_response()
        }
        Err(f) => f.into_response(),
    }
}

async fn render_png(State(state): State<Arc<AppState>>, request: Request) -> Response {
    let mut req = match read_json::<RenderRequest>(&state, request).await {
        Ok(r) => r,
        Err(f) => return f.into_response(),
    };
    req.scale = 1;
    match render_request(state, req).await {
        Ok(r) => Response::builder()
            .header(header::CONTENT_TYPE, "image/png")
            .header(
                header::CONTENT_DISPOSITION,
                format!("attachment; filename=\"{}\"", r.file_name.replace('"', "")),
            )
            .body(Body::from(r.png))
            .unwrap_or_else(|_| StatusCode::INTERNAL_SERVER_ERROR.into_response()),
        Err(f) => f.into_response(),
    }
}

//! Eric Haines' Neutral File Format (NFF, version 3.9; the Standard Procedural Databases'
//! scene format): `v` view, `b` background, `l` light, `f` material, `c` cone/cylinder,
//! `s` sphere, `p` polygon, `pp` polygon with vertex normals, `#` comments. The reader builds
//! the same [`Scene`] model as the scene language; `f` is mapped onto Stam's illumination
//! model as `paper-notes/nff.md` explains ([`nff_material`]).
//!
//! The format is line-based: every entity's numbers sit on the lines the specification gives
//! them, and a missing, extra or malformed number is an error naming `file:line:column`
//! ([`Span`]) like the scene language's. The reader makes no allocation per number, and reads
//! a large text in parts on the caller's thread pool, so the 66 430-sphere `balls-s5.nff`
//! (2.7 MB) reads in a few tens of milliseconds (`docs/speed.md`).

use std::path::Path;
use std::sync::Arc;

use glam::DVec3;
use rayon::prelude::*;
use smallvec::SmallVec;

use super::error::{ErrorKind, SceneError, Span};
use super::lexer::{TextLines, end_position, text_lines};
use super::model::{
    BoundingVolume, CameraSpec, Illumination, InvalidModel, Light, LookAtCamera, Material, Object,
    ObjectTransform, Rgb, Scene, ShapeKind, Viewport,
};
use super::valid_scene::{SceneSpans, ValidScene};

/// Most vertices a `p` or `pp` entity may declare: far above any SPD polygon (the gears'
/// 144-gons), and low enough that a corrupt count cannot ask for gigabytes.
pub const MAX_NFF_VERTICES: usize = 1 << 16;

/// The SPD's resolution, used when a file has no `v` entity.
const DEFAULT_RESOLUTION: u32 = 512;

/// Whether `path` / `text` is NFF rather than Stam's scene language: by the extension
/// (`.nff`, or `.scene` for the scene language), and for any other name by the content — the
/// first line that is neither blank nor a `#` line starts with an NFF entity keyword that is
/// not followed by `=` (the scene language's lines outside `#` commands are `Key = value`).
pub fn is_nff(path: &Path, text: &str) -> bool {
    match path.extension().and_then(|e| e.to_str()) {
        Some(e) if e.eq_ignore_ascii_case("nff") => return true,
        Some(e) if e.eq_ignore_ascii_case("scene") => return false,
        _ => {}
    }
    for line in text_lines(text) {
        let line = line.trim_start();
        if line.is_empty() || line.starts_with('#') {
            continue;
        }
        let mut words = line.split_ascii_whitespace();
        let first = words.next().unwrap_or("");
        let second = words.next().unwrap_or("");
        return is_entity(first) && !second.starts_with('=');
    }
    false
}

/// The illumination parameters of an NFF `f` entity: colour `(r, g, b)`, `Kd`, `Ks`, `Shine`,
/// transmittance `T` and index of refraction.
///
/// Stam's model (eq. 2.6–2.16) has one coefficient per term, and NFF gives each of them:
/// `C_s` = the colour, `k_d = Kd`, `k_s = Ks` (weighting both the highlight, eq. 2.9, and the
/// reflected ray, eq. 2.11, as NFF's `Ks` does), `n = Shine`, `k_t = T`, `k_n` = the index,
/// `C_r` = white (an NFF highlight has the light's colour). NFF has no ambient term; `k_a` is
/// what `Kd`, `Ks` and `T` leave of 1, `max(0, 1 − Kd − Ks − T)`, which is what the SPD's own
/// POV-Ray writer puts in its `ambient` (the `.pov` twins). The level is the least that shows
/// every non-zero term: `TRANSPARENT` when `T > 0`, `MIRROR` when `Ks > 0`, else `DIFFUSE`.
pub fn nff_material(color: Rgb, kd: f64, ks: f64, shine: f64, t: f64, ior: f64) -> Material {
    let illumination = if t > 0.0 {
        Illumination::Transparent
    } else if ks > 0.0 {
        Illumination::Mirror
    } else {
        Illumination::Diffuse
    };
    Material {
        illumination,
        cs: color,
        cr: Rgb::ONE,
        ka: (1.0 - kd - ks - t).max(0.0),
        kd,
        ks,
        kt: t,
        n: shine,
        kn: ior,
        texture: None,
    }
}

/// Reads an NFF scene. `file` names the text in error messages. Called on a thread of a rayon
/// pool (the render's, [`thread_pool`](crate::thread_pool)), a large text is read in parts on
/// that pool's threads; elsewhere in one pass. The scene and the errors are the same.
///
/// # Errors
/// [`SceneError::At`] at the offending token: an unknown entity, a missing, extra or
/// malformed number, a `v` sub-line out of order, a vertex count above
/// [`MAX_NFF_VERTICES`], or a degenerate shape (zero radius, zero-area polygon).
///
/// # Examples
/// ```
/// use std::path::Path;
/// use render::scene::{ShapeKind, parse_nff};
/// let scene = parse_nff("l 1 2 3\ns 0 0 0 1.5\n", Path::new("x.nff"))?;
/// assert!(matches!(scene.objects[0].shape, ShapeKind::Sphere { radius: 1.5, .. }));
/// let err = parse_nff("s 0 0 zero 1\n", Path::new("x.nff")).unwrap_err();
/// assert_eq!(err.to_string(), "x.nff:1:7: expected the sphere's centre (a number), found `zero`");
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn parse_nff(text: &str, file: &Path) -> Result<ValidScene, SceneError> {
    // In parts only on a pool's thread: `current_num_threads` elsewhere would start rayon's
    // global pool, whatever threads the caller asked its own pool for.
    let parts = if text.len() >= PARALLEL_MIN_BYTES && rayon::current_thread_index().is_some() {
        rayon::current_num_threads()
    } else {
        1
    };
    parse_nff_in(text, file, parts)
}

/// Texts from this size on are read in parts, one a thread of the current rayon pool: the
/// 10.7 MB of `sombrero-s4.nff` took about 85 ms on one thread and 60–75 ms on two
/// (`docs/speed.md`, twentieth session), and below a few hundred kilobytes a part would cost
/// more to start than it saves.
const PARALLEL_MIN_BYTES: usize = 1 << 18;

/// [`parse_nff`] reading `text` in up to `parts` parts side by side (one part: one pass).
///
/// Each part starts on a line whose first word is an entity keyword ([`is_entity`]): no such
/// line is ever a data line of a valid file (data lines hold numbers; the view's sub-lines
/// start with their own names), so the parts split no entity. What crosses a boundary is the
/// material in force (an `f` lights every object after it), the uncoloured lights' shared
/// intensity and the last `v` and `b`; [`Part`] records them and the merge applies them in
/// order, so the scene is the one a single pass builds (test
/// `reading_in_parts_builds_the_scene_of_one_pass`). When a part fails, the text is read
/// again in one pass for its first error, so errors do not depend on the split either.
fn parse_nff_in(text: &str, file: &Path, parts: usize) -> Result<ValidScene, SceneError> {
    let file: Arc<Path> = Arc::from(file);
    let starts = part_starts(text, parts);
    if starts.len() == 1 {
        let part = parse_part(text, 0, &file, Objects::own(object_capacity(text)))?;
        return merge(text, &file, (Vec::new(), Vec::new()), vec![part]);
    }
    let texts: Vec<(&str, u32)> = starts
        .iter()
        .enumerate()
        .map(|(k, &(at, first_line))| {
            let end = starts.get(k + 1).map_or(text.len(), |&(next, _)| next);
            (&text[at..end], first_line)
        })
        .collect();
    // Each part writes its objects and their spans into its own shares of the scene's
    // arrays, counted first: arrays of their own, appended afterwards, held every part's
    // objects twice at the peak (10 MB more on balls-s5). A name of its own per part: every
    // span holds a reference, and two threads counting references on one `Arc` fought over
    // its cache line.
    let counts: Vec<usize> = texts.par_iter().map(|&(t, _)| object_lines(t)).collect();
    let files: Vec<Arc<Path>> = texts.iter().map(|_| Arc::from(&*file)).collect();
    let total = counts.iter().sum();
    let mut objects = Vec::with_capacity(total);
    // A placeholder of its own (and so a material of its own) for each job that fills the
    // array: clones of one placeholder had both threads counting references on one material's
    // cache line, when filled and again when each part overwrote its slots.
    objects.par_extend((0..total).into_par_iter().map_init(
        || Object::new(PLACEHOLDER),
        |placeholder, _| placeholder.clone(),
    ));
    let mut spans = Vec::with_capacity(total);
    for (f, &count) in files.iter().zip(&counts) {
        let placeholder = Span {
            file: f.clone(),
            line: 0,
            col: 0,
        };
        spans.extend(std::iter::repeat_n(placeholder, count));
    }
    let mut shares = Vec::with_capacity(counts.len());
    let (mut rest, mut rest_spans) = (objects.as_mut_slice(), spans.as_mut_slice());
    for &count in &counts {
        let (share, after) = rest.split_at_mut(count);
        let (span_share, spans_after) = rest_spans.split_at_mut(count);
        shares.push(Objects::Share {
            objects: share,
            spans: span_share,
            len: 0,
        });
        (rest, rest_spans) = (after, spans_after);
    }
    let read = texts
        .par_iter()
        .zip(&files)
        .zip(shares)
        .map(|((&(part, first_line), file), share)| parse_part(part, first_line, file, share))
        .collect::<Result<Vec<Part>, SceneError>>();
    match read {
        Ok(read) => merge(text, &file, (objects, spans), read),
        Err(_) => {
            let own = Objects::own(object_capacity(text));
            Err(parse_part(text, 0, &file, own).err().unwrap_or_else(|| {
                // A part failed where the whole text does not: impossible when the parts split
                // no entity (see above); reported rather than asserted.
                SceneError::at(
                    &end_position(text, file.clone()),
                    ErrorKind::Expected {
                        expected: "a text the parallel reader splits between entities".into(),
                        found: "a part it could not read".into(),
                    },
                )
            }))
        }
    }
}

/// The shape of the objects a part's share holds until the part writes them.
const PLACEHOLDER: ShapeKind = ShapeKind::Sphere {
    center: DVec3::ZERO,
    radius: 1.0,
};

/// The scene of the parts `read`, in order: their objects and spans in the two arrays given
/// (the parts' shares, written in place) or, read in one pass, in the part's own arrays; then
/// the scene-level checks, at the parts' spans.
fn merge(
    text: &str,
    file: &Arc<Path>,
    (mut objects, object_spans): (Vec<Object>, Vec<Span>),
    read: Vec<Part>,
) -> Result<ValidScene, SceneError> {
    let mut scene = Scene::default();
    scene.world.background = Rgb::ZERO;
    scene.viewport = Viewport {
        size: [DEFAULT_RESOLUTION; 2],
        resolution: [1, 1],
    };
    let mut spans = SceneSpans {
        objects: object_spans,
        ..SceneSpans::default()
    };
    let mut material = Arc::new(Material::default());
    let mut uncoloured = Vec::new();
    let mut offset = 0;
    for part in read {
        let Part {
            objects: own,
            count,
            inherited,
            material: last_material,
            lights,
            light_spans,
            uncoloured: part_uncoloured,
            view,
            background,
        } = part;
        if let Some((own, own_spans)) = own {
            objects = own;
            spans.objects = own_spans;
        }
        for object in &mut objects[offset..offset + inherited] {
            object.material = material.clone();
        }
        offset += count;
        if let Some(m) = last_material {
            material = m;
        }
        uncoloured.extend(part_uncoloured.iter().map(|i| i + scene.lights.len()));
        scene.lights.extend(lights);
        spans.lights.extend(light_spans);
        if let Some((camera, size, span)) = view {
            scene.camera = camera;
            scene.viewport.size = size;
            spans.camera = Some(span);
            spans.viewport = spans.camera.clone();
        }
        if let Some((color, span)) = background {
            scene.world.background = color;
            spans.world = Some(span);
        }
    }
    scene.objects = objects;
    // Lights without a colour share a unit total intensity, 1/√n each (as the SPD's POV-Ray
    // writer does), set once all are read.
    let share = 1.0 / (uncoloured.len().max(1) as f64).sqrt();
    for i in uncoloured {
        scene.lights[i].color = Rgb::splat(share);
    }
    spans.validate(scene, &end_position(text, file.clone()))
}

/// The lines of `text` that begin an object (`s`, `c`, `p`, `pp`): in a valid file, its
/// objects — the share of the scene's array a part writes ([`parse_nff_in`]).
fn object_lines(text: &str) -> usize {
    text_lines(text)
        .filter(|line| {
            let word = comment_free(line).split_ascii_whitespace().next();
            matches!(word, Some("s" | "c" | "p" | "pp"))
        })
        .count()
}

/// Where a part's objects and their spans go: arrays of its own (a text read in one pass),
/// or its shares of the scene's arrays, counted before ([`object_lines`]; `len` written so
/// far).
enum Objects<'s> {
    Own(Vec<Object>, Vec<Span>),
    Share {
        objects: &'s mut [Object],
        spans: &'s mut [Span],
        len: usize,
    },
}

impl Objects<'_> {
    /// Arrays of its own, reserved for `capacity` objects.
    fn own(capacity: usize) -> Self {
        Objects::Own(Vec::with_capacity(capacity), Vec::with_capacity(capacity))
    }

    /// The objects so far.
    fn len(&self) -> usize {
        match self {
            Objects::Own(own, _) => own.len(),
            Objects::Share { len, .. } => *len,
        }
    }

    /// Adds `object`, read at `span`; gives the span back when the share is full (the count
    /// was wrong: a malformed text).
    fn push(&mut self, object: Object, span: Span) -> Result<(), Span> {
        match self {
            Objects::Own(own, spans) => {
                own.push(object);
                spans.push(span);
            }
            Objects::Share {
                objects,
                spans,
                len,
            } => match (objects.get_mut(*len), spans.get_mut(*len)) {
                (Some(slot), Some(span_slot)) => {
                    *slot = object;
                    *span_slot = span;
                    *len += 1;
                }
                _ => return Err(span),
            },
        }
        Ok(())
    }
}

/// What one part of an NFF text holds, in the order read ([`parse_nff_in`]).
struct Part {
    /// Its objects and their spans when it has arrays of its own (else they are in its shares
    /// of the scene's arrays); objects before its first `f` carry a placeholder material.
    objects: Option<(Vec<Object>, Vec<Span>)>,
    /// How many objects it read.
    count: usize,
    /// How many objects come before its first `f`: they take the material in force where the
    /// part begins.
    inherited: usize,
    /// The material in force at its end, when it has an `f`.
    material: Option<Arc<Material>>,
    lights: Vec<Light>,
    light_spans: Vec<Span>,
    /// Its lights without a colour (indices into `lights`).
    uncoloured: Vec<usize>,
    /// Its last `v`: the camera, the image size and the entity's span.
    view: Option<(CameraSpec, [u32; 2], Span)>,
    /// Its last `b`: the colour and the entity's span.
    background: Option<(Rgb, Span)>,
}

/// Where the parts of [`parse_nff_in`] begin: byte offsets and the number of lines before
/// each (so that spans keep the file's line numbers), the first part at 0. A part begins at
/// the first line at or after its share of the text whose first word is an entity keyword;
/// fewer parts when there is no such line.
fn part_starts(text: &str, parts: usize) -> Vec<(usize, u32)> {
    let mut starts = vec![(0, 0)];
    for k in 1..parts.max(1) {
        let target = text.len() / parts * k;
        let (last, _) = starts[starts.len() - 1];
        // From the start of the line after the one holding `target`.
        let Some(end) = memchr::memchr2(b'\n', b'\r', &text.as_bytes()[target.max(last)..]) else {
            break;
        };
        let mut at = target.max(last) + end;
        at += if text[at..].starts_with("\r\n") { 2 } else { 1 };
        let mut found = None;
        let mut offset = at;
        for line in text_lines(&text[at..]) {
            let word = comment_free(line).split_ascii_whitespace().next();
            if word.is_some_and(is_entity) {
                found = Some(offset);
                break;
            }
            // The line and its end (`\r\n` counts two bytes).
            offset += line.len();
            offset += if text[offset..].starts_with("\r\n") {
                2
            } else {
                1
            };
        }
        let Some(at) = found else {
            break;
        };
        let lines = text_lines(&text[..at]).count();
        let Ok(lines) = u32::try_from(lines) else {
            break;
        };
        starts.push((at, lines));
    }
    starts
}

/// Whether `word` begins an NFF entity.
fn is_entity(word: &str) -> bool {
    matches!(word, "v" | "b" | "l" | "f" | "c" | "s" | "p" | "pp")
}

/// Reads one part of an NFF text, whose first line is line `first_line + 1` of the file, its
/// objects into `objects`.
fn parse_part(
    text: &str,
    first_line: u32,
    file: &Arc<Path>,
    mut objects: Objects<'_>,
) -> Result<Part, SceneError> {
    let mut r = Reader {
        lines: text_lines(text).enumerate(),
        first_line,
        file,
    };
    let mut part = Part {
        objects: None,
        count: 0,
        inherited: 0,
        material: None,
        lights: Vec::new(),
        light_spans: Vec::new(),
        uncoloured: Vec::new(),
        view: None,
        background: None,
    };
    // Until the part's first `f`, objects take a placeholder, replaced when the parts merge.
    let mut material = Arc::new(Material::default());
    while let Some(mut line) = r.next_line() {
        let Some((keyword, at)) = line.word() else {
            continue; // unreachable: `next_line` skips lines without words
        };
        match keyword {
            "v" => {
                line.finish()?;
                let (camera, size) = read_view(&mut r, &line)?;
                part.view = Some((camera, size, r.span(&line, at)));
            }
            "b" => {
                let color = line.vector("the background colour")?;
                part.background = Some((color, r.span(&line, at)));
                line.finish()?;
            }
            "l" => {
                let source = line.vector("the light position")?;
                let color = if line.peek().is_some() {
                    line.vector("the light colour")?
                } else {
                    part.uncoloured.push(part.lights.len());
                    Rgb::ONE
                };
                line.finish()?;
                part.lights.push(Light { source, color });
                part.light_spans.push(r.span(&line, at));
            }
            "f" => {
                let color = line.vector("the fill colour")?;
                let kd = line.number("Kd")?;
                let ks = line.number("Ks")?;
                let shine = line.number("Shine")?;
                let t = line.number("the transmittance T")?;
                let at_ior = line.peek_offset();
                let mut ior = line.number("the index of refraction")?;
                line.finish()?;
                if ior <= 0.0 {
                    // Opaque materials may carry any index (the SPD's gears write 0): it is
                    // never used, so it is read as 1. A transparent one needs a real index.
                    if t > 0.0 {
                        return Err(SceneError::at(
                            &line.span_at(at_ior),
                            ErrorKind::InvalidValue {
                                key: "f".into(),
                                reason: format!(
                                    "the index of refraction of a transparent material must be positive, found {ior}"
                                ),
                            },
                        ));
                    }
                    ior = 1.0;
                }
                material = Arc::new(nff_material(color, kd, ks, shine, t, ior));
                if part.material.is_none() {
                    part.inherited = objects.len();
                }
                part.material = Some(material.clone());
            }
            "s" => {
                let center = line.vector("the sphere's centre")?;
                // A negative radius shows only the inside; this tracer's surfaces are
                // two-sided, so the magnitude is the sphere.
                let radius = line.number("the sphere's radius")?.abs();
                line.finish()?;
                let shape = ShapeKind::Sphere { center, radius };
                push(&mut objects, shape, &material, r.span(&line, at))?;
            }
            "c" => {
                line.finish()?;
                let mut base = r.data_line(&line, "the cone's base")?;
                let b = base.vector("the cone's base")?;
                let rb = base.number("the base radius")?.abs();
                base.finish()?;
                let mut apex = r.data_line(&base, "the cone's apex")?;
                let a = apex.vector("the cone's apex")?;
                let ra = apex.number("the apex radius")?.abs();
                apex.finish()?;
                let shape = ShapeKind::Cone {
                    base: b,
                    base_radius: rb,
                    apex: a,
                    apex_radius: ra,
                    caps: false,
                };
                push(&mut objects, shape, &material, r.span(&line, at))?;
            }
            "p" | "pp" => {
                let smooth = keyword == "pp";
                let n = line.count()?;
                line.finish()?;
                // A triangle's vertices on the stack: no allocation for the commonest polygon
                // (a mesh file's every entity).
                let mut vertices: SmallVec<[DVec3; 3]> = SmallVec::with_capacity(n);
                let mut normals = Vec::with_capacity(if smooth { n } else { 0 });
                let mut last = line.clone();
                for _ in 0..n {
                    let mut v = r.data_line(&last, "a vertex")?;
                    vertices.push(v.vector("a vertex")?);
                    if smooth {
                        normals.push(v.vector("a vertex normal")?);
                    }
                    v.finish()?;
                    last = v;
                }
                let shape = match (smooth, vertices.into_inner()) {
                    (false, Ok(vertices)) => ShapeKind::Triangle { vertices },
                    (true, vertices) => ShapeKind::SmoothPolygon {
                        vertices: vertices.map_or_else(|v| v.into_vec(), Vec::from),
                        normals,
                    },
                    (false, Err(vertices)) => ShapeKind::Polygon {
                        vertices: vertices.into_vec(),
                    },
                };
                push(&mut objects, shape, &material, r.span(&line, at))?;
            }
            other => {
                return Err(SceneError::at(
                    &r.span(&line, at),
                    ErrorKind::Expected {
                        expected: "an NFF entity (v, b, l, f, c, s, p, pp or # comment)".into(),
                        found: format!("`{other}`"),
                    },
                ));
            }
        }
    }
    if part.material.is_none() {
        part.inherited = objects.len();
    }
    part.count = objects.len();
    match objects {
        Objects::Own(own, spans) => part.objects = Some((own, spans)),
        Objects::Share { objects, len, .. } if len < objects.len() => {
            // Fewer objects than counted: a malformed text (the caller reads it in one pass).
            return Err(SceneError::at(
                &end_position(text, file.clone()),
                ErrorKind::Expected {
                    expected: format!("{} objects", objects.len()),
                    found: format!("{len}"),
                },
            ));
        }
        Objects::Share { .. } => {}
    }
    Ok(part)
}

/// An upper bound on the objects of an NFF text, for reserving the object arrays once: every
/// object takes at least one line. Grown by doubling instead, balls-s5's 66 431 objects took
/// 16 reallocations, 82 MiB allocated and each object copied about once more (issue 12). The
/// line-end bytes plus one bound the lines; a `\r\n` pair counts twice, which only reserves
/// address space that is never touched.
fn object_capacity(text: &str) -> usize {
    1 + memchr::memchr2_iter(b'\n', b'\r', text.as_bytes()).count()
}

/// Adds an object after checking its shape and its placement (the cone's frame), reporting a
/// degenerate one at `span`, and records `span` for the scene-level checks at the end of the
/// load.
fn push(
    objects: &mut Objects<'_>,
    shape: ShapeKind,
    material: &Arc<Material>,
    span: Span,
) -> Result<(), SceneError> {
    // The name is spelled only for an error: lower-casing it for every object was a tenth of
    // the NFF parse (issue 12).
    let type_name = shape.type_name();
    let located = |e: InvalidModel| {
        let name = type_name.to_lowercase();
        // The model names the scene-language key; NFF has none, so say what it is.
        let reason = if e.reason.starts_with("the ") || e.reason.starts_with("a ") {
            e.reason.to_owned()
        } else {
            format!("{} {}", e.key.to_lowercase(), e.reason)
        };
        SceneError::at(&span, ErrorKind::InvalidValue { key: name, reason })
    };
    shape.validate().map_err(located)?;
    // Built whole: `Object::new` would allocate a default material only to drop it.
    let object = Object {
        shape,
        material: material.clone(),
        bounding: BoundingVolume::None,
        transform: ObjectTransform::default(),
    };
    object.placement().map_err(located)?;
    objects.push(object, span).map_err(|span| {
        // More objects than counted: a malformed text (the caller reads it in one pass).
        SceneError::at(
            &span,
            ErrorKind::Expected {
                expected: "no more objects in this part".into(),
                found: type_name.to_lowercase(),
            },
        )
    })
}

/// The `v` entity's six sub-lines, in the specification's order.
fn read_view<'a>(r: &mut Reader<'a>, v: &Line<'a>) -> Result<(CameraSpec, [u32; 2]), SceneError> {
    let mut last = v.clone();
    let mut from = view_line(r, &mut last, "from")?;
    let eye = from.vector("the eye position")?;
    from.finish()?;
    let mut at = view_line(r, &mut last, "at")?;
    let look_at = at.vector("the look-at point")?;
    at.finish()?;
    let mut up = view_line(r, &mut last, "up")?;
    let up_v = up.vector("the up vector")?;
    up.finish()?;
    let mut angle = view_line(r, &mut last, "angle")?;
    let fov = angle.number("the view angle")?;
    angle.finish()?;
    // The hither plane clips nothing in a ray tracer whose rays start at the eye; it is read
    // and checked, not used.
    let mut hither = view_line(r, &mut last, "hither")?;
    hither.number("the hither distance")?;
    hither.finish()?;
    let mut res = view_line(r, &mut last, "resolution")?;
    let w = res.count()?;
    let h = res.count()?;
    res.finish()?;
    let side = |n: usize, line: &Line<'_>| {
        u32::try_from(n)
            .ok()
            .filter(|&s| (1..=super::MAX_IMAGE_SIDE).contains(&s))
            .ok_or_else(|| {
                SceneError::at(
                    &line.end_span(),
                    ErrorKind::InvalidValue {
                        key: "resolution".into(),
                        reason: format!("sides must be 1 to {}", super::MAX_IMAGE_SIDE),
                    },
                )
            })
    };
    let size = [side(w, &res)?, side(h, &res)?];
    // NFF's angle spans the image from the top row to the bottom row: the vertical field.
    let camera = CameraSpec::LookAt(LookAtCamera {
        eye,
        look_at,
        up: up_v,
        view_field_deg: fov,
    });
    Ok((camera, size))
}

/// The next sub-line of a `v` entity, which must start with `name`.
fn view_line<'a>(
    r: &mut Reader<'a>,
    last: &mut Line<'a>,
    name: &'static str,
) -> Result<Line<'a>, SceneError> {
    let mut line = r.data_line(last, name)?;
    let word = line.word();
    if word.map(|(w, _)| w) != Some(name) {
        return Err(line.expected(&format!("`{name}` in the view entity"), word));
    }
    *last = line.clone();
    Ok(line)
}

/// `line` up to its first `#` (a comment runs to the end of the line).
fn comment_free(line: &str) -> &str {
    // The `#` is ASCII, so the byte before it ends a character.
    memchr::memchr(b'#', line.as_bytes()).map_or(line, |i| &line[..i])
}

/// The lines of the text, numbered from 1, with comments and blank lines skipped.
struct Reader<'a> {
    lines: std::iter::Enumerate<TextLines<'a>>,
    /// The lines of the file before the text read (a part's, [`parse_nff_in`]).
    first_line: u32,
    file: &'a Arc<Path>,
}

/// One line's remaining words.
#[derive(Clone)]
struct Line<'a> {
    /// The whole line as written (for columns).
    raw: &'a str,
    /// 1-based line number.
    no: u32,
    words: std::str::SplitAsciiWhitespace<'a>,
    /// Borrowed, and shared into a [`Span`] only when one is made: a reference count per
    /// line was an atomic increment and decrement on each of balls-s5's 66 448 lines.
    file: &'a Arc<Path>,
}

impl<'a> Reader<'a> {
    /// The next line with a word on it (a `#` starts a comment to the end of the line).
    fn next_line(&mut self) -> Option<Line<'a>> {
        for (i, raw) in self.lines.by_ref() {
            let body = comment_free(raw);
            if body.trim_ascii().is_empty() {
                continue;
            }
            return Some(Line {
                raw,
                no: self.first_line + i as u32 + 1,
                words: body.split_ascii_whitespace(),
                file: self.file,
            });
        }
        None
    }

    /// The next line, which must exist: the data of the entity begun on or before `prev`.
    fn data_line(&mut self, prev: &Line<'a>, what: &str) -> Result<Line<'a>, SceneError> {
        self.next_line().ok_or_else(|| {
            SceneError::at(
                &prev.end_span(),
                ErrorKind::Expected {
                    expected: format!("a line with {what}"),
                    found: "end of file".into(),
                },
            )
        })
    }

    /// The span of byte offset `at` in `line`.
    fn span(&self, line: &Line<'a>, at: usize) -> Span {
        line.span_at(at)
    }
}

/// The `f64` nearest the decimal `s` (the syntax of `str::parse::<f64>`), or `None`. By
/// `fast-float2` (Eisel–Lemire, with Clinger's exact fast path first): correctly rounded like
/// `str::parse` and bit for bit the same value (test `numbers_are_read_as_str_parse_reads_them`),
/// at a fraction of its cost on the SPD files' short decimals (`str::parse` spent ≈ 330
/// instructions on each of balls-s5's 265 771 numbers; issue 12).
fn decimal(s: &str) -> Option<f64> {
    fast_float2::parse::<f64, _>(s).ok()
}

impl<'a> Line<'a> {
    /// The next word and its byte offset in the line.
    fn word(&mut self) -> Option<(&'a str, usize)> {
        let w = self.words.next()?;
        Some((w, w.as_ptr() as usize - self.raw.as_ptr() as usize))
    }

    fn peek(&self) -> Option<&'a str> {
        self.words.clone().next()
    }

    /// The byte offset of the next word (or of the end of the line).
    fn peek_offset(&self) -> usize {
        self.peek().map_or(self.raw.len(), |w| {
            w.as_ptr() as usize - self.raw.as_ptr() as usize
        })
    }

    fn span_at(&self, at: usize) -> Span {
        let col = self.raw.get(..at).map_or(at, |s| s.chars().count()) as u32 + 1;
        Span {
            file: self.file.clone(),
            line: self.no,
            col,
        }
    }

    /// Just past the last character of the line's content (before any comment).
    fn end_span(&self) -> Span {
        let body = comment_free(self.raw).trim_ascii_end();
        self.span_at(body.len())
    }

    fn expected(&self, what: &str, found: Option<(&str, usize)>) -> SceneError {
        let (found, span) = match found {
            Some((w, at)) => (format!("`{w}`"), self.span_at(at)),
            None => ("end of line".into(), self.end_span()),
        };
        SceneError::at(
            &span,
            ErrorKind::Expected {
                expected: what.into(),
                found,
            },
        )
    }

    /// A finite number: `what` names it in the error.
    fn number(&mut self, what: &str) -> Result<f64, SceneError> {
        let w = self.word();
        match w.map(|(s, _)| decimal(s)) {
            Some(Some(x)) if x.is_finite() => Ok(x),
            _ => Err(self.expected(&format!("{what} (a number)"), w)),
        }
    }

    fn vector(&mut self, what: &str) -> Result<DVec3, SceneError> {
        Ok(DVec3::new(
            self.number(what)?,
            self.number(what)?,
            self.number(what)?,
        ))
    }

    /// A whole count of vertices or pixels, at most [`MAX_NFF_VERTICES`].
    fn count(&mut self) -> Result<usize, SceneError> {
        let w = self.word();
        match w.map(|(s, _)| s.parse::<usize>()) {
            Some(Ok(n)) if n <= MAX_NFF_VERTICES => Ok(n),
            _ => Err(self.expected(&format!("a whole number from 0 to {MAX_NFF_VERTICES}"), w)),
        }
    }

    /// Nothing may follow the entity's numbers on its line.
    fn finish(&mut self) -> Result<(), SceneError> {
        match self.word() {
            None => Ok(()),
            Some(w) => Err(self.expected("end of line", Some(w))),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The objects' arrays are reserved once from [`object_capacity`], which must bound the
    /// objects whatever the line ends: one object a line, the last without a line end, `\r`
    /// alone, `\r\n`, and entities spanning several lines.
    #[test]
    fn object_capacity_bounds_the_objects() {
        for text in [
            "s 0 0 0 1",
            "s 0 0 0 1\ns 1 0 0 1\ns 2 0 0 1\n",
            "s 0 0 0 1\rs 1 0 0 1\rs 2 0 0 1",
            "s 0 0 0 1\r\ns 1 0 0 1\r\n",
            "p 3\n0 0 0\n1 0 0\n0 1 0\ns 0 0 5 1",
        ] {
            let scene = parse_nff(text, Path::new("t.nff")).expect("a valid scene");
            let n = scene.objects.len();
            assert!(
                n >= 1 && n <= object_capacity(text),
                "{text:?}: {n} objects"
            );
        }
        assert_eq!(object_capacity("s 0 0 0 1\ns 1 0 0 1"), 2);
    }

    /// The objects an `f` line lights share its one material, whether the text is read in one
    /// pass or in parts (objects before a part's first `f` included), and the objects of two
    /// `f` lines do not: a copy per object was a third of a parsed object (balls-s5's peak
    /// memory 64.4 against 57.2 MB, `paper-notes/nff.md` §1). Fails if the reader goes back to
    /// copying the material into each object.
    #[test]
    fn the_objects_an_f_line_lights_share_its_material() {
        let mut text = String::from("l 0 10 0\nf 1 0 0 1 0 1 0 1\n");
        for k in 0..200 {
            text.push_str(&format!("s {k} 0 0 0.4\n"));
        }
        text.push_str("f 0 1 0 1 0 1 0 1\n");
        for k in 0..200 {
            text.push_str(&format!("p 3\n{k} 1 0\n{k} 2 0\n{k}.5 1 0\n"));
        }
        for parts in [1, 2, 3, 5] {
            let scene = parse_nff_in(&text, Path::new("t.nff"), parts).expect("a valid scene");
            let objects = &scene.objects;
            assert_eq!(objects.len(), 400, "{parts} parts");
            let (red, green) = (&objects[0].material, &objects[200].material);
            assert!(
                !Arc::ptr_eq(red, green),
                "{parts} parts: two f lines, two materials"
            );
            for (i, object) in objects.iter().enumerate() {
                let own = if i < 200 { red } else { green };
                assert!(
                    Arc::ptr_eq(&object.material, own),
                    "{parts} parts: object {i} holds a material of its own"
                );
            }
        }
    }

    /// Reading a text in 2 to 9 parts builds the scene a single pass builds — objects with
    /// their materials across `f` lines on either side of a boundary, uncoloured lights
    /// sharing one intensity, the last `v` and `b` — on the committed SPD scenes and on a text
    /// with every entity, comments, blank lines and `\r\n` line ends; and a part boundary
    /// always falls on an entity's first line (a split inside a polygon or a view would fail
    /// to read, and the comparison with it).
    #[test]
    fn reading_in_parts_builds_the_scene_of_one_pass() {
        let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../scenes/spd");
        let mut texts: Vec<String> = [
            "balls-s1.nff",
            "balls-s2.nff",
            "jacks-s2.nff",
            "rings-s1.nff",
        ]
        .iter()
        .map(|name| std::fs::read_to_string(dir.join(name)).expect("a committed scene"))
        .collect();
        let mut mixed = String::from("# every entity\r\nl 0 10 0\r\n\r\n");
        for k in 0..40 {
            if k % 7 == 0 {
                let c = f64::from(k) / 40.0;
                mixed.push_str(&format!("f {c} {c} 1 0.5 0.5 3 0 1\r\n"));
            }
            if k % 11 == 5 {
                mixed.push_str(&format!("l {k} 5 -3\r\nl 1 {k} 2 0.5 0.5 0.5\r\n"));
            }
            if k == 23 {
                mixed.push_str("b 0.1 0.2 0.3\r\nv\r\nfrom 0 1 -9\r\nat 0 0 0\r\nup 0 1 0\r\n");
                mixed.push_str("angle 40\r\nhither 0.01\r\nresolution 64 48\r\n");
            }
            let x = f64::from(k);
            mixed.push_str(&format!("s {x} 0 0 0.4 # sphere {k}\r\n"));
            mixed.push_str(&format!("p 3\r\n{x} 1 0\r\n{x} 2 0\r\n{} 1 0\r\n", x + 0.5));
            mixed.push_str(&format!(
                "pp 3\r\n{x} 3 0 0 0 1\r\n{x} 4 0 0 0 1\r\n{} 3 0 0 0 1\r\n",
                x + 0.5
            ));
            mixed.push_str(&format!("c\r\n{x} 5 0 0.2\r\n{x} 6 0 0.1\r\n"));
        }
        texts.push(mixed);
        for (t, text) in texts.iter().enumerate() {
            let file = Path::new("t.nff");
            let whole = parse_nff_in(text, file, 1).expect("a valid scene");
            for parts in 2..=9 {
                let starts = part_starts(text, parts);
                assert!(starts.len() > 1, "text {t}: {parts} parts made one");
                for &(at, lines) in &starts[1..] {
                    let word = comment_free(text_lines(&text[at..]).next().unwrap_or(""))
                        .split_ascii_whitespace()
                        .next();
                    assert!(word.is_some_and(is_entity), "text {t}: a part at byte {at}");
                    assert_eq!(lines as usize, text_lines(&text[..at]).count(), "text {t}");
                }
                let split = parse_nff_in(text, file, parts).expect("a valid scene in parts");
                assert!(*split == *whole, "text {t} in {parts} parts");
            }
        }
    }

    /// Errors do not depend on the split: an error in a later part, one that the last
    /// step's checks find (a degenerate camera, at its `v`), and a polygon missing a vertex
    /// line (which a part would see as a different error), each named at the same place as
    /// in one pass.
    #[test]
    fn errors_read_in_parts_are_the_errors_of_one_pass() {
        let spheres: String = (0..200).map(|k| format!("s {k} 0 0 0.5\n")).collect();
        for bad in [
            "s 1 2 zero 1\n",
            "v\nfrom 0 0 0\nat 0 0 0\nup 0 1 0\nangle 40\nhither 0.01\nresolution 8 8\n",
            "p 3\n0 0 0\n1 0 0\n",
            "f 1 1 1 0.5 0.5 3 0.5 -1\n",
        ] {
            let text = format!("{spheres}{bad}{spheres}");
            let file = Path::new("e.nff");
            let whole = parse_nff_in(&text, file, 1)
                .expect_err("an invalid scene")
                .to_string();
            for parts in 2..=5 {
                let split = parse_nff_in(&text, file, parts)
                    .expect_err("invalid")
                    .to_string();
                assert_eq!(split, whole, "{bad:?} in {parts} parts");
            }
        }
    }

    /// On texts mutated at random — a line deleted, doubled or moved, a word replaced, a
    /// polygon's count raised — reading in 2 to 4 parts gives what one pass gives: the same
    /// scene, or the same error at the same place.
    #[test]
    fn mutated_texts_read_in_parts_as_in_one_pass() {
        use rand::{Rng, SeedableRng};
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(20261205);
        let mut base = String::from("l 0 10 0\n");
        for k in 0..60 {
            if k % 9 == 0 {
                base.push_str(&format!("f {} 0.5 1 0.5 0.5 3 0 1\n", f64::from(k) / 60.0));
            }
            base.push_str(&format!(
                "s {k} 0 0 0.4\np 3\n{k} 1 0\n{k} 2 0\n{k}.5 1 0\n"
            ));
            base.push_str(&format!("c\n{k} 5 0 0.2\n{k} 6 0 0.1\nl {k} 9 9\n"));
        }
        let (mut valid, mut invalid) = (0, 0);
        for case in 0..300 {
            let mut lines: Vec<String> = base.lines().map(str::to_owned).collect();
            for _ in 0..rng.gen_range(1..4) {
                let i = rng.gen_range(0..lines.len());
                match rng.gen_range(0..5) {
                    0 => {
                        lines.remove(i);
                    }
                    1 => lines.insert(i, lines[i].clone()),
                    2 => {
                        let line = lines.remove(i);
                        let j = rng.gen_range(0..lines.len());
                        lines.insert(j, line);
                    }
                    3 => {
                        let mut words: Vec<&str> = lines[i].split(' ').collect();
                        let w = rng.gen_range(0..words.len());
                        words[w] = ["x", "s", "p", "1e999", "-0"][rng.gen_range(0..5)];
                        lines[i] = words.join(" ");
                    }
                    _ => lines.insert(i, "p 4".into()),
                }
            }
            let text = lines.join("\n");
            let file = Path::new("m.nff");
            let whole = parse_nff_in(&text, file, 1).map_err(|e| e.to_string());
            for parts in 2..=4 {
                let split = parse_nff_in(&text, file, parts).map_err(|e| e.to_string());
                match (&whole, &split) {
                    (Ok(a), Ok(b)) => assert!(**a == **b, "case {case}, {parts} parts"),
                    (a, b) => assert_eq!(
                        a.as_ref().err(),
                        b.as_ref().err(),
                        "case {case}, {parts} parts"
                    ),
                }
            }
            if whole.is_ok() {
                valid += 1;
            } else {
                invalid += 1;
            }
        }
        // Measured: 14 valid, 286 invalid (most mutations break an entity).
        assert!(
            valid >= 10 && invalid >= 100,
            "{valid} valid, {invalid} invalid"
        );
    }

    /// Every decimal gets the bits `str::parse::<f64>` gives it, and what it refuses is
    /// refused: random decimals of 1–20 digits with the point anywhere (or none), either
    /// sign, with and without an exponent, and the edge cases.
    #[test]
    fn numbers_are_read_as_str_parse_reads_them() {
        use rand::{Rng, SeedableRng};
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(12);
        for _ in 0..200_000 {
            let n = rng.gen_range(1..=20);
            let mut s: String = match rng.gen_range(0..4) {
                0 => "-".into(),
                1 => "+".into(),
                _ => String::new(),
            };
            let point = rng.gen_range(0..=n + 1);
            for k in 0..n {
                if k == point {
                    s.push('.');
                }
                s.push(char::from(b'0' + rng.gen_range(0..10u8)));
            }
            if point == n {
                s.push('.');
            }
            if rng.gen_bool(0.25) {
                s.push_str(&format!("e{}", rng.gen_range(-330..=330)));
            }
            let want = s.parse::<f64>().expect("a valid decimal");
            let got = decimal(&s).unwrap_or_else(|| panic!("{s} is refused"));
            assert_eq!(
                got.to_bits(),
                want.to_bits(),
                "{s}: {got:e} against {want:e}"
            );
        }
        for s in [
            "0",
            "-0",
            "-0.0",
            "+1.5",
            "1.",
            ".5",
            "0.1",
            "0.3",
            "9007199254740993",
            "1e5",
            "1E-3",
            "0.0362949",
            "-0.193744",
            "12",
            "1e400",
            "1e-400",
            "4.9e-324",
        ] {
            let want = s.parse::<f64>().expect("valid");
            assert_eq!(decimal(s).map(f64::to_bits), Some(want.to_bits()), "{s}");
        }
        for s in [
            "", "-", ".", "+.", "1.2.3", "1,5", "0x10", "--1", "-.", "1e", "e5", "1 2",
        ] {
            assert!(s.parse::<f64>().is_err(), "{s} is not a number");
            assert_eq!(decimal(s), None, "{s}");
        }
    }
}

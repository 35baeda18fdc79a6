//! Eric Haines' Neutral File Format (NFF, version 3.9; the Standard Procedural Databases'
//! scene format): `v` view, `b` background, `l` light, `f` material, `c` cone/cylinder,
//! `s` sphere, `p` polygon, `pp` polygon with vertex normals, `#` comments. The reader builds
//! the same [`Scene`] model as the scene language; `f` is mapped onto Stam's illumination
//! model as `paper-notes/nff.md` explains ([`nff_material`]).
//!
//! The format is line-based: every entity's numbers sit on the lines the specification gives
//! them, and a missing, extra or malformed number is an error naming `file:line:column`
//! ([`Span`]) like the scene language's. The reader is a single pass over the text with no
//! allocation per number, so the 66 430-sphere `balls-s5.nff` (2.7 MB) reads in a few tens of
//! milliseconds (`docs/speed.md`).

use std::path::Path;
use std::sync::Arc;

use glam::DVec3;

use super::error::{ErrorKind, SceneError, Span};
use super::lexer::{TextLines, end_position, text_lines};
use super::model::{
    CameraSpec, Illumination, InvalidModel, Light, LookAtCamera, Material, Object, Rgb, Scene,
    ShapeKind, Viewport,
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
        return matches!(first, "v" | "b" | "l" | "f" | "c" | "s" | "p" | "pp")
            && !second.starts_with('=');
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

/// Reads an NFF scene. `file` names the text in error messages.
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
    let file: Arc<Path> = Arc::from(file);
    let mut r = Reader {
        lines: text_lines(text).enumerate(),
        file: &file,
    };
    let mut scene = Scene::default();
    scene.world.background = Rgb::ZERO;
    scene.viewport = Viewport {
        size: [DEFAULT_RESOLUTION; 2],
        resolution: [1, 1],
    };
    let mut material = Material::default();
    // Lights without a colour share a unit total intensity, 1/√n each (as the SPD's POV-Ray
    // writer does), set once all are read.
    let mut uncoloured = Vec::new();
    let mut spans = SceneSpans::default();
    let capacity = object_capacity(text);
    scene.objects.reserve(capacity);
    spans.objects.reserve(capacity);
    while let Some(mut line) = r.next_line() {
        let Some((keyword, at)) = line.word() else {
            continue; // unreachable: `next_line` skips lines without words
        };
        match keyword {
            "v" => {
                line.finish()?;
                read_view(&mut r, &line, &mut scene)?;
                spans.camera = Some(r.span(&line, at));
                spans.viewport = spans.camera.clone();
            }
            "b" => {
                scene.world.background = line.vector("the background colour")?;
                spans.world = Some(r.span(&line, at));
                line.finish()?;
            }
            "l" => {
                let source = line.vector("the light position")?;
                let color = if line.peek().is_some() {
                    line.vector("the light colour")?
                } else {
                    uncoloured.push(scene.lights.len());
                    Rgb::ONE
                };
                line.finish()?;
                scene.lights.push(Light { source, color });
                spans.lights.push(r.span(&line, at));
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
                material = nff_material(color, kd, ks, shine, t, ior);
            }
            "s" => {
                let center = line.vector("the sphere's centre")?;
                // A negative radius shows only the inside; this tracer's surfaces are
                // two-sided, so the magnitude is the sphere.
                let radius = line.number("the sphere's radius")?.abs();
                line.finish()?;
                let shape = ShapeKind::Sphere { center, radius };
                push(&mut scene, &mut spans, shape, &material, r.span(&line, at))?;
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
                push(&mut scene, &mut spans, shape, &material, r.span(&line, at))?;
            }
            "p" | "pp" => {
                let smooth = keyword == "pp";
                let n = line.count()?;
                line.finish()?;
                let mut vertices = Vec::with_capacity(n);
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
                let shape = match (smooth, vertices.len()) {
                    (true, _) => ShapeKind::SmoothPolygon { vertices, normals },
                    (false, 3) => ShapeKind::Triangle {
                        vertices: [vertices[0], vertices[1], vertices[2]],
                    },
                    (false, _) => ShapeKind::Polygon { vertices },
                };
                push(&mut scene, &mut spans, shape, &material, r.span(&line, at))?;
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
    let share = 1.0 / (uncoloured.len().max(1) as f64).sqrt();
    for i in uncoloured {
        scene.lights[i].color = Rgb::splat(share);
    }
    spans.validate(scene, &end_position(text, file.clone()))
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
    scene: &mut Scene,
    spans: &mut SceneSpans,
    shape: ShapeKind,
    material: &Material,
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
    let mut object = Object::new(shape);
    object.placement().map_err(located)?;
    object.material = material.clone();
    scene.objects.push(object);
    spans.objects.push(span);
    Ok(())
}

/// The `v` entity's six sub-lines, in the specification's order.
fn read_view<'a>(r: &mut Reader<'a>, v: &Line<'a>, scene: &mut Scene) -> Result<(), SceneError> {
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
    scene.viewport.size = [side(w, &res)?, side(h, &res)?];
    // NFF's angle spans the image from the top row to the bottom row: the vertical field.
    scene.camera = CameraSpec::LookAt(LookAtCamera {
        eye,
        look_at,
        up: up_v,
        view_field_deg: fov,
    });
    Ok(())
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
                no: i as u32 + 1,
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

    /// Every decimal gets the bits `str::parse::<f64>` gives it, and what it refuses is
    /// refused: random decimals of 1–20 digits with the point anywhere (or none), either
    /// sign, with and without an exponent, and the edge cases.
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

//! What the page needs to know about a scene text besides its image: where each `Let`
//! constant and the camera's `Eye`, `LookAt` and `Up` are written (so sliders and the mouse
//! can rewrite them), and the checks a server adds to the scene language's own (files outside
//! the scene directory, the equation degree).
//!
//! Places are sent as UTF-16 code-unit offsets into the text, the unit of JavaScript strings,
//! so the page can splice without re-parsing.

use std::path::{Component, Path};

use render::scene::{
    CameraSpec, Command, Entry, Expr, ExprKind, Key, Scene, SceneAst, ShapeKind, Span, Value,
};
use serde::Serialize;

/// A `[start, end)` range of UTF-16 code units in the scene text.
pub(crate) type Range16 = [usize; 2];

/// One `Let` constant: a slider.
#[derive(Debug, Serialize, PartialEq)]
pub(crate) struct LetInfo {
    /// The name as written.
    pub(crate) name: String,
    /// Its value.
    pub(crate) value: f64,
    /// Where its defining expression is written.
    pub(crate) range: Range16,
    /// 1-based line of the name.
    pub(crate) line: u32,
}

/// The camera, with where its parts are written (look-at form), for the mouse.
#[derive(Debug, Serialize, PartialEq)]
pub(crate) struct CameraInfo {
    /// Eye position.
    pub(crate) eye: [f64; 3],
    /// The point the mouse orbits about.
    pub(crate) look_at: [f64; 3],
    /// Up direction.
    pub(crate) up: [f64; 3],
    /// Vertical field of view in degrees (a look-at `ViewField`).
    pub(crate) view_field: f64,
    /// Where `Eye`'s tuple is written, if the text has a look-at `#camera`.
    pub(crate) eye_range: Option<Range16>,
    /// Where `LookAt`'s tuple is written.
    pub(crate) look_at_range: Option<Range16>,
    /// Where `Up`'s tuple is written (absent: the default up, and the page inserts one).
    pub(crate) up_range: Option<Range16>,
    /// Where the `#camera` block is (Stam's form, or no block: `[0, 0]`); the page replaces
    /// it with a look-at block on the first drag.
    pub(crate) block_range: Range16,
}

/// Line starts of a text, to turn a [`Span`] into offsets.
pub(crate) struct TextIndex<'a> {
    text: &'a str,
    /// Byte offset of the start of each line (index 0 is line 1).
    line_starts: Vec<usize>,
}

impl<'a> TextIndex<'a> {
    pub(crate) fn new(text: &'a str) -> Self {
        // The lexer ends lines at `\n`; a `\r` before it is a character of the line.
        let line_starts = std::iter::once(0)
            .chain(text.match_indices('\n').map(|(i, _)| i + 1))
            .collect();
        TextIndex { text, line_starts }
    }

    /// Byte offset of a 1-based line and character column (clamped to the text).
    pub(crate) fn byte_of(&self, line: u32, col: u32) -> usize {
        let Some(&start) = self.line_starts.get(line.saturating_sub(1) as usize) else {
            return self.text.len();
        };
        self.text[start..]
            .char_indices()
            .nth(col.saturating_sub(1) as usize)
            .map_or(self.text.len(), |(i, _)| start + i)
    }

    fn byte_of_span(&self, span: &Span) -> usize {
        self.byte_of(span.line, span.col)
    }

    /// The UTF-16 offset of a byte offset.
    pub(crate) fn utf16(&self, byte: usize) -> usize {
        self.text[..byte].encode_utf16().count()
    }
}

/// Byte offset just past the parenthesised tuple starting at `start` (at its `(`), or past
/// the expression starting at `start` for a bare expression.
fn tuple_end(text: &str, start: usize) -> usize {
    let mut depth = 0i32;
    for (i, c) in text[start..].char_indices() {
        match c {
            '(' => depth += 1,
            ')' => {
                depth -= 1;
                if depth <= 0 {
                    return start + i + 1;
                }
            }
            '\n' if depth <= 0 => return start + i,
            _ => {}
        }
    }
    text.len()
}

/// The spans of every token an expression records (operands and operators).
fn expr_spans<'e>(e: &'e Expr, out: &mut Vec<&'e Span>) {
    out.push(&e.span);
    match &e.kind {
        ExprKind::Number(_) | ExprKind::Var(_) | ExprKind::Name(_) => {}
        ExprKind::Neg(a) | ExprKind::Sqrt(a) => expr_spans(a, out),
        ExprKind::Binary { op, lhs, rhs } => {
            out.push(&op.span);
            expr_spans(lhs, out);
            expr_spans(rhs, out);
        }
    }
}

/// Byte range of an expression's text: from its first token to the end of its last token,
/// including the closing parentheses the tree does not record.
fn expr_bytes(index: &TextIndex<'_>, e: &Expr) -> [usize; 2] {
    let text = index.text;
    let start = index.byte_of_span(&e.span);
    let mut spans = Vec::new();
    expr_spans(e, &mut spans);
    let last = spans
        .iter()
        .map(|s| index.byte_of_span(s))
        .max()
        .unwrap_or(start);
    // The last recorded token: a number, a name, an operator or `sqrt`.
    let mut end = last;
    let rest = &text[last..];
    let mut chars = rest.char_indices().peekable();
    if let Some(&(_, c)) = chars.peek() {
        if c.is_ascii_alphanumeric() || c == '.' || c == '_' {
            let mut prev = ' ';
            for (i, c) in rest.char_indices() {
                let exponent_sign = (c == '+' || c == '-') && matches!(prev, 'e' | 'E');
                if c.is_ascii_alphanumeric() || c == '.' || c == '_' || exponent_sign {
                    end = last + i + c.len_utf8();
                    prev = c;
                } else {
                    break;
                }
            }
        } else {
            end = last + c.len_utf8();
        }
    }
    // Close the parentheses opened inside the expression.
    let mut depth: i32 = text[start..end]
        .chars()
        .map(|c| match c {
            '(' => 1,
            ')' => -1,
            _ => 0,
        })
        .sum();
    while depth > 0 {
        match text[end..].find(')') {
            Some(i) => {
                end += i + 1;
                depth -= 1;
            }
            None => break,
        }
    }
    [start, end]
}

/// Every `Let` of the scene with its value and where it is written. A `Let` whose value
/// cannot be computed (the build step reports it) is left out.
pub(crate) fn lets(ast: &SceneAst, text: &str) -> Vec<LetInfo> {
    let index = TextIndex::new(text);
    let mut out = Vec::new();
    for block in &ast.blocks {
        // A `Let` is visible for the rest of its block (syntax.rs `Entry::Let`).
        let mut defined: Vec<(String, f64)> = Vec::new();
        for entry in &block.entries {
            let Entry::Let { name, value } = entry else {
                continue;
            };
            let Ok(v) = value.const_value(&defined) else {
                continue;
            };
            defined.push((name.value.clone(), v));
            let [s, e] = expr_bytes(&index, value);
            out.push(LetInfo {
                name: name.value.clone(),
                value: v,
                range: [index.utf16(s), index.utf16(e)],
                line: name.span.line,
            });
        }
    }
    out
}

/// The camera of `scene`, seen as eye / look-at / up, and where the text writes it.
pub(crate) fn camera(ast: &SceneAst, scene: &Scene, text: &str) -> CameraInfo {
    let index = TextIndex::new(text);
    let block = ast
        .blocks
        .iter()
        .position(|b| b.command.value == Command::Camera);
    let block_range = match block {
        Some(i) => {
            let start = index.byte_of_span(&ast.blocks[i].command.span);
            let end = ast
                .blocks
                .get(i + 1)
                .map_or(text.len(), |b| index.byte_of_span(&b.command.span));
            [index.utf16(start), index.utf16(end)]
        }
        None => [0, 0],
    };
    let range_of = |key: Key| -> Option<Range16> {
        let b = &ast.blocks[block?];
        b.entries.iter().find_map(|e| match e {
            Entry::Set { key: k, value } if k.value == key => {
                let s = index.byte_of_span(&value.span);
                Some([index.utf16(s), index.utf16(tuple_end(text, s))])
            }
            _ => None,
        })
    };
    let (eye, look_at, up, view_field) = match &scene.camera {
        CameraSpec::LookAt(c) => (c.eye, c.look_at, c.up, c.view_field_deg),
        CameraSpec::Stam(_) => {
            // Stam's camera as eye / look-at: the eye and the centre of the view (the image
            // centre's ray, to the distance of Stam's `Center`), up from the image's top edge.
            let [w, h] = scene.viewport.size;
            let cam = render::Camera::new(&scene.camera, w, h);
            let centre = cam.ray(f64::from(w) / 2.0, f64::from(h) / 2.0);
            let top = cam.ray(f64::from(w) / 2.0, 0.0);
            let bottom = cam.ray(f64::from(w) / 2.0, f64::from(h));
            let dist = match &scene.camera {
                CameraSpec::Stam(s) => (s.center - cam.eye()).length(),
                CameraSpec::LookAt(_) => 1.0,
            };
            let dir = centre.dir.normalize_or_zero();
            let up = (top.dir.normalize_or_zero() - dir).normalize_or_zero();
            let view_field = top.dir.angle_between(bottom.dir).to_degrees();
            (cam.eye(), cam.eye() + dir * dist, up, view_field)
        }
    };
    let lookat_form = matches!(scene.camera, CameraSpec::LookAt(_)) && block.is_some();
    CameraInfo {
        eye: eye.to_array(),
        look_at: look_at.to_array(),
        up: up.to_array(),
        view_field,
        eye_range: if lookat_form {
            range_of(Key::Eye)
        } else {
            None
        },
        look_at_range: if lookat_form {
            range_of(Key::LookAt)
        } else {
            None
        },
        up_range: if lookat_form { range_of(Key::Up) } else { None },
        block_range,
    }
}

/// Why a scene is refused by the server on top of the scene language's own checks, with the
/// place it is about.
#[derive(Debug, PartialEq)]
pub(crate) struct Refusal {
    /// Line and column, when the problem has a place.
    pub(crate) at: Option<(u32, u32)>,
    /// The message.
    pub(crate) message: String,
}

/// Refuses file names (texture files, control-point files, mesh files) that leave `dir`: absolute paths,
/// `..` that climbs out, and links pointing outside. `#save` is ignored: the server writes no
/// files.
pub(crate) fn confine_files(ast: &SceneAst, dir: &Path) -> Result<(), Refusal> {
    let root = dir.canonicalize().map_err(|e| Refusal {
        at: None,
        message: format!("the scene directory {} is unusable: {e}", dir.display()),
    })?;
    for block in ast
        .blocks
        .iter()
        .filter(|b| b.command.value != Command::Save)
    {
        for entry in &block.entries {
            let Entry::Set { value, .. } = entry else {
                continue;
            };
            let Value::Path(name) = &value.value else {
                continue;
            };
            let refuse = |why: &str| Refusal {
                at: Some((value.span.line, value.span.col)),
                message: format!(
                    "file `{name}` {why}: the explorer reads only files inside the scene directory"
                ),
            };
            let p = Path::new(name);
            if p.is_absolute() || p.components().any(|c| matches!(c, Component::Prefix(_))) {
                return Err(refuse("is an absolute path"));
            }
            // Lexically first: `..` that climbs above the directory is refused even when the
            // file does not exist.
            let mut depth = 0i32;
            for c in p.components() {
                match c {
                    Component::ParentDir => depth -= 1,
                    Component::Normal(_) => depth += 1,
                    _ => {}
                }
                if depth < 0 {
                    return Err(refuse("is outside the scene directory"));
                }
            }
            // Then through links: where the file really is.
            if let Ok(real) = root.join(p).canonicalize()
                && !real.starts_with(&root)
            {
                return Err(refuse("links outside the scene directory"));
            }
        }
    }
    Ok(())
}

/// Refuses an algebraic surface of degree above `max_degree`, at its object.
pub(crate) fn check_degree(ast: &SceneAst, scene: &Scene, max_degree: u32) -> Result<(), Refusal> {
    let mut object_blocks = ast
        .blocks
        .iter()
        .filter(|b| b.command.value == Command::Object);
    for object in &scene.objects {
        let block = object_blocks.next();
        if let ShapeKind::Algebraic { poly } = &object.shape
            && poly.degree() > max_degree
        {
            let at = block.map(|b| {
                let span = b
                    .entries
                    .iter()
                    .find_map(|e| match e {
                        Entry::Set { key, value } if key.value == Key::Equation => {
                            Some(&value.span)
                        }
                        _ => None,
                    })
                    .unwrap_or(&b.command.span);
                (span.line, span.col)
            });
            return Err(Refusal {
                at,
                message: format!(
                    "the equation has degree {}; this server renders degree at most {max_degree} (--max-degree)",
                    poly.degree()
                ),
            });
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use render::scene::{parse, parse_syntax};

    fn ast(text: &str) -> SceneAst {
        parse_syntax(text, Path::new("t.scene")).expect("the test scene parses")
    }

    fn slice16(text: &str, r: Range16) -> String {
        let units: Vec<u16> = text.encode_utf16().collect();
        String::from_utf16(&units[r[0]..r[1]]).expect("a range on char boundaries")
    }

    #[test]
    fn let_ranges_cover_the_whole_expression() {
        let text = "#object Type = ALGEBRAIC_SURFACE\n\
                    Let phi = (1 + sqrt(5))/2   // comment\n\
                    Let a = -0.25e-1 Let b = a*(phi)\n\
                    Equation = x^2 + y^2 + z^2 - a - b";
        let lets = lets(&ast(text), text);
        let names: Vec<_> = lets.iter().map(|l| l.name.as_str()).collect();
        assert_eq!(names, ["phi", "a", "b"], "every Let, in order");
        assert_eq!(slice16(text, lets[0].range), "(1 + sqrt(5))/2");
        assert_eq!(slice16(text, lets[1].range), "-0.25e-1");
        assert_eq!(slice16(text, lets[2].range), "a*(phi)");
        assert!(
            (lets[0].value - 1.618_033_988_749_895).abs() < 1e-15,
            "phi's value"
        );
        assert!(
            (lets[2].value + 0.025 * lets[0].value).abs() < 1e-15,
            "b uses a and phi"
        );
    }

    #[test]
    fn offsets_count_utf16_units_after_non_ascii_text() {
        // `é` is one UTF-16 unit but two bytes; `𝑥` two units and four bytes.
        let text = "// é 𝑥\n#object Type = ALGEBRAIC_SURFACE Let a = 2\nEquation = x - a";
        let lets = lets(&ast(text), text);
        assert_eq!(
            slice16(text, lets[0].range),
            "2",
            "the range lands on the value"
        );
    }

    #[test]
    fn camera_ranges_point_at_the_tuples() {
        let text = "#camera Eye = (0, -8, 5)  LookAt = (0,0,(1))\nViewField = 50\n\
                    #object Type = TORUS Center = (0,0,0) Axis = (0,0,1) MajorRadius = 2 MinorRadius = 1";
        let a = ast(text);
        let scene = parse(text, Path::new("t.scene")).expect("the scene builds");
        let cam = camera(&a, &scene, text);
        assert_eq!(cam.eye, [0.0, -8.0, 5.0]);
        assert_eq!(slice16(text, cam.eye_range.expect("Eye")), "(0, -8, 5)");
        assert_eq!(
            slice16(text, cam.look_at_range.expect("LookAt")),
            "(0,0,(1))"
        );
        assert_eq!(cam.up_range, None, "no Up written");
        assert!(
            slice16(text, cam.block_range).starts_with("#camera"),
            "the block"
        );
        assert!(
            slice16(text, cam.block_range).ends_with("50\n"),
            "up to the next block"
        );
    }

    #[test]
    fn files_outside_the_scene_directory_are_refused() {
        let dir = tempfile::tempdir().expect("a temporary directory");
        let inside = "#object Type = BEZIER_PATCH Control points = sub/../p.pts";
        assert_eq!(confine_files(&ast(inside), dir.path()), Ok(()));
        for name in ["../p.pts", "/etc/passwd", "sub/../../p.pts"] {
            let text = format!("#world\n#object Type = BEZIER_PATCH Control points = {name}");
            let err = confine_files(&ast(&text), dir.path()).expect_err(name);
            assert_eq!(err.at, Some((2, 46)), "{name}: at the file name");
            assert!(err.message.contains(name), "{}", err.message);
        }
        // A mesh's OBJ file too (`Type = MESH`, session 18).
        let text = "#object Type = MESH File Name = /etc/passwd";
        let err = confine_files(&ast(text), dir.path()).expect_err("a mesh outside");
        assert_eq!(err.at, Some((1, 33)), "at the mesh's file name");
    }

    #[test]
    fn the_degree_limit_names_the_equation() {
        let text = "#camera Eye = (0,-8,5) LookAt = (0,0,0) ViewField = 50\n#object Type = ALGEBRAIC_SURFACE\n\
                    Equation = x^7 + y - 1";
        let scene = parse(text, Path::new("t.scene")).expect("the scene builds");
        assert_eq!(check_degree(&ast(text), &scene, 7), Ok(()));
        let err = check_degree(&ast(text), &scene, 6).expect_err("degree 7 > 6");
        assert_eq!(err.at, Some((3, 12)));
        assert!(err.message.contains("degree 7"), "{}", err.message);
    }
}

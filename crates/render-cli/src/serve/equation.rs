//! The simple mode: one algebraic surface given by its equation, set in a scene with a
//! default camera, lights and clipping sphere (as SURFER shows one surface), and every name
//! in the equation other than `x`, `y`, `z` made a `Let` parameter (SURFER's `a`, `b`, …).

use std::collections::BTreeMap;
use std::fmt::Write;
use std::path::Path;

use render::scene::{Entry, Expr, ExprKind, Key, parse_syntax};
use serde::Deserialize;

/// The value a parameter starts at when the page has not set it: the middle of SURFER's
/// `[0, 1]` parameter sliders.
pub(crate) const DEFAULT_PARAMETER: f64 = 0.5;

/// A camera sent by the page (the mouse moved it).
#[derive(Clone, Debug, Deserialize, PartialEq)]
pub(crate) struct CameraIn {
    pub(crate) eye: [f64; 3],
    pub(crate) look_at: [f64; 3],
    pub(crate) up: [f64; 3],
}

/// The default camera: the view of `scenes/barth.scene`, which frames the clipping sphere.
const DEFAULT_CAMERA: CameraIn = CameraIn {
    eye: [5.0, -9.0, 6.0],
    look_at: [0.0, 0.0, 0.0],
    up: [0.0, 0.0, 1.0],
};

/// A scene built around an equation, and where the equation sits in it.
#[derive(Debug)]
pub(crate) struct EquationScene {
    /// The scene text.
    pub(crate) text: String,
    /// The 1-based line of the scene text on which the equation starts.
    line: u32,
    /// How many characters precede the equation on that line.
    prefix: u32,
}

impl EquationScene {
    /// Maps a place in the scene text back into the equation (1-based line and column);
    /// `None` for a place outside it.
    pub(crate) fn to_equation(&self, line: u32, col: u32) -> Option<(u32, u32)> {
        match line.checked_sub(self.line)? {
            0 => Some((1, col.checked_sub(self.prefix)?)),
            d => Some((d + 1, col)),
        }
    }
}

/// Formats a coordinate the way a person writes it: at most 4 decimals, no trailing zeros.
pub(crate) fn number(v: f64) -> String {
    let s = format!("{v:.4}");
    let s = s.trim_end_matches('0').trim_end_matches('.');
    if s == "-0" { "0".into() } else { s.into() }
}

fn tuple(v: [f64; 3]) -> String {
    format!("({}, {}, {})", number(v[0]), number(v[1]), number(v[2]))
}

fn names_in(e: &Expr, out: &mut Vec<String>) {
    match &e.kind {
        ExprKind::Name(n) => {
            if !out.iter().any(|m| m.eq_ignore_ascii_case(n)) {
                out.push(n.clone());
            }
        }
        ExprKind::Number(_) | ExprKind::Var(_) => {}
        ExprKind::Neg(a) | ExprKind::Sqrt(a) => names_in(a, out),
        ExprKind::Binary { lhs, rhs, .. } => {
            names_in(lhs, out);
            names_in(rhs, out);
        }
    }
}

/// The parameter names of an equation, in order of appearance; `None` if the equation does
/// not parse (the full scene's parse reports where).
fn parameters(equation: &str) -> Option<Vec<String>> {
    let probe = format!("#object Type = ALGEBRAIC_SURFACE\nEquation = {equation}");
    let ast = parse_syntax(&probe, Path::new("equation")).ok()?;
    let mut names = Vec::new();
    for block in &ast.blocks {
        for entry in &block.entries {
            if let Entry::Set { key, value } = entry
                && key.value == Key::Equation
                && let render::scene::Value::Number(e) = &value.value
            {
                names_in(e, &mut names);
            }
        }
    }
    Some(names)
}

/// The scene of the simple mode for `equation`, with `params` values for its parameters and
/// `camera` (default: [`DEFAULT_CAMERA`]).
pub(crate) fn scene(
    equation: &str,
    params: &BTreeMap<String, f64>,
    camera: Option<&CameraIn>,
) -> EquationScene {
    let camera = camera.unwrap_or(&DEFAULT_CAMERA);
    let mut text = String::new();
    let _ = write!(
        text,
        "// The explorer's simple mode: one algebraic surface, clipped to a sphere of radius 2.\n\
         #world\nBackGnd = (0.05, 0.05, 0.1)\nShadows = ON\n\
         #camera\nEye = {}  LookAt = {}  Up = {}\nViewField = 30\n\
         #light\nSource = (10, -10, 20)  Color = 0.8\n\
         #light\nSource = (-10, -5, 5)  Color = (0.3, 0.3, 0.4)\n\
         #object\nType = ALGEBRAIC_SURFACE\n",
        tuple(camera.eye),
        tuple(camera.look_at),
        tuple(camera.up)
    );
    for name in parameters(equation).unwrap_or_default() {
        let v = params
            .iter()
            .find(|(n, _)| n.eq_ignore_ascii_case(&name))
            .map_or(DEFAULT_PARAMETER, |(_, &v)| v);
        let _ = writeln!(text, "Let {name} = {}", number(v));
    }
    let line = text.lines().count() as u32 + 1;
    let prefix = "Equation = ";
    let _ = write!(
        text,
        "{prefix}{equation}\n\
         Illumination = SPECULAR\nCs = (0.9, 0.75, 0.3)  Cr = 1\nKa = 0.15  Kd = 0.7  Ks = 0.4\nn = 30\n\
         Bounding volume = SPHERE (0, 0, 0) 2\n\
         #viewport\nSize = (512, 512)\n"
    );
    EquationScene {
        text,
        line,
        prefix: prefix.chars().count() as u32,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use render::scene::parse;

    #[test]
    fn parameters_become_lets_and_the_scene_builds() {
        let mut params = BTreeMap::new();
        params.insert("A".to_string(), 0.25);
        let s = scene("x^2 + y^2 - z^2 - a*b", &params, None);
        assert!(s.text.contains("Let a = 0.25\n"), "{}", s.text);
        assert!(s.text.contains("Let b = 0.5\n"), "{}", s.text);
        let built = parse(&s.text, Path::new("equation.scene"));
        assert!(built.is_ok(), "{built:?}");
    }

    #[test]
    fn errors_map_back_into_the_equation() {
        let s = scene("x^2 +\n  y^2 ) - 1", &BTreeMap::new(), None);
        let err = parse(&s.text, Path::new("e.scene")).expect_err("a stray `)`");
        let span = err.span().expect("a located error");
        assert_eq!(s.to_equation(span.line, span.col), Some((2, 7)), "{err}");
        assert_eq!(
            s.to_equation(1, 1),
            None,
            "the template is not the equation"
        );
    }

    #[test]
    fn numbers_are_written_briefly() {
        assert_eq!(number(2.0), "2");
        assert_eq!(number(-0.000_01), "0");
        assert_eq!(number(1.234_56), "1.2346");
    }
}

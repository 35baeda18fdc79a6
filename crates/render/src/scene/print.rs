//! The printer: a [`SceneAst`] back to scene-language text.
//!
//! The output uses canonical key spellings, one entry per line and the fewest parentheses
//! that keep the tree, so parsing the printed text gives back an equal tree (STYLE.md §7,
//! "scene files round-trip"). Comments and layout are not kept.

use std::fmt::Write as _;

use super::expr::{BinOp, Expr, ExprKind};
use super::syntax::{Block, Entry, SceneAst, Value, illumination_name};

/// Renders a syntax tree as scene-language text that [`crate::scene::parse_syntax`] reads
/// back into an equal tree.
///
/// A file name containing both a blank (or `//`) and a `"` cannot be written in the
/// language; such a name is written quoted up to its first `"`, which changes it (the
/// parser never produces one from a quoted name, and raw names stop at blanks).
///
/// # Examples
/// ```
/// use std::path::Path;
/// use render::scene::{parse_syntax, print};
/// let ast = parse_syntax("#object Type = SPHERE Center=(0,0,0) Radius^2 = 2*2", Path::new("s"))?;
/// let text = print(&ast);
/// assert_eq!(text, "#object\nType = SPHERE\nCenter = (0, 0, 0)\nRadius^2 = 2 * 2\n");
/// assert_eq!(parse_syntax(&text, Path::new("s"))?, ast);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn print(ast: &SceneAst) -> String {
    let mut out = String::new();
    for (i, block) in ast.blocks.iter().enumerate() {
        if i > 0 {
            out.push('\n');
        }
        print_block(&mut out, block);
    }
    out
}

fn print_block(out: &mut String, block: &Block) {
    out.push('#');
    out.push_str(block.command.value.name());
    out.push('\n');
    for entry in &block.entries {
        match entry {
            Entry::Set { key, value } => {
                out.push_str(key.value.name());
                out.push_str(" = ");
                print_value(out, &value.value);
            }
            Entry::Let { name, value } => {
                out.push_str("Let ");
                out.push_str(&name.value);
                out.push_str(" = ");
                print_expr(out, value);
            }
        }
        out.push('\n');
    }
}

fn print_value(out: &mut String, value: &Value) {
    match value {
        Value::Number(e) => print_expr(out, e),
        Value::Tuple(items) => {
            out.push('(');
            for (i, e) in items.iter().enumerate() {
                if i > 0 {
                    out.push_str(", ");
                }
                print_expr(out, e);
            }
            out.push(')');
        }
        Value::Switch(on) => out.push_str(if *on { "ON" } else { "OFF" }),
        Value::Shape(s) => out.push_str(s.name()),
        Value::TextureType(t) => out.push_str(t.name()),
        Value::Illumination(i) => out.push_str(illumination_name(*i)),
        Value::Bounds(None) => out.push_str("NONE"),
        Value::Bounds(Some(ranges)) => {
            out.push_str("BOX ");
            for (i, [lo, hi]) in ranges.iter().enumerate() {
                if i > 0 {
                    out.push('x');
                }
                out.push('[');
                print_expr(out, lo);
                out.push_str(", ");
                print_expr(out, hi);
                out.push(']');
            }
        }
        Value::Path(p) => {
            let raw_ok = !p.is_empty()
                && !p.starts_with('"')
                && !p.contains("//")
                && !p.chars().any(char::is_whitespace);
            if raw_ok {
                out.push_str(p);
            } else {
                let quoted = p.split('"').next().unwrap_or_default();
                out.push('"');
                out.push_str(quoted);
                out.push('"');
            }
        }
        Value::Word(w) => out.push_str(w),
    }
}

/// Binding strength of an expression's top operator; atoms bind tightest.
fn prec(e: &Expr) -> u8 {
    match &e.kind {
        ExprKind::Binary { op, .. } => match op.value {
            BinOp::Add | BinOp::Sub => 1,
            BinOp::Mul | BinOp::Div => 2,
            BinOp::Pow => 4,
        },
        ExprKind::Neg(_) => 3,
        ExprKind::Number(_) | ExprKind::Var(_) | ExprKind::Name(_) | ExprKind::Sqrt(_) => 5,
    }
}

/// Writes `e`, in parentheses when `wrap`.
fn print_sub(out: &mut String, e: &Expr, wrap: bool) {
    if wrap {
        out.push('(');
        print_expr(out, e);
        out.push(')');
    } else {
        print_expr(out, e);
    }
}

/// Writes an expression with the parentheses the parser needs to rebuild the same tree:
/// left-associative `+ - * /` wrap a right operand of equal strength, right-associative `^`
/// wraps a left one; a unary minus is accepted wherever an operand starts, except as the
/// base of `^` (`-x^2` is `-(x^2)`).
pub(crate) fn print_expr(out: &mut String, e: &Expr) {
    match &e.kind {
        ExprKind::Number(v) => {
            // `{}` is the shortest text that reads back as the same `f64`.
            let _ = write!(out, "{v}");
        }
        ExprKind::Var(axis) => out.push_str(axis.name()),
        ExprKind::Name(n) => out.push_str(n),
        ExprKind::Sqrt(inner) => {
            out.push_str("sqrt(");
            print_expr(out, inner);
            out.push(')');
        }
        ExprKind::Neg(inner) => {
            out.push('-');
            print_sub(out, inner, prec(inner) < 4);
        }
        ExprKind::Binary { op, lhs, rhs } => {
            let p = prec(e);
            match op.value {
                BinOp::Pow => {
                    print_sub(out, lhs, prec(lhs) <= 4);
                    out.push('^');
                    print_sub(out, rhs, prec(rhs) < 3);
                }
                _ => {
                    print_sub(out, lhs, prec(lhs) < p);
                    let _ = write!(out, " {} ", op.value.symbol());
                    print_sub(out, rhs, prec(rhs) <= p && prec(rhs) != 3);
                }
            }
        }
    }
}

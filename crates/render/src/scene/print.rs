//! The printer: a [`SceneAst`] back to scene-language text.
//!
//! The output uses canonical key spellings, one entry per line and the fewest parentheses
//! that keep the tree, so parsing the printed text gives back an equal tree (STYLE.md §7,
//! "scene files round-trip"). Comments and layout are not kept.

use super::expr::{Expr, print_expr};
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

fn print_tuple(out: &mut String, items: &[Expr]) {
    out.push('(');
    for (i, e) in items.iter().enumerate() {
        if i > 0 {
            out.push_str(", ");
        }
        print_expr(out, e);
    }
    out.push(')');
}

fn print_value(out: &mut String, value: &Value) {
    match value {
        Value::Number(e) => print_expr(out, e),
        Value::Tuple(items) => print_tuple(out, items),
        Value::Points(points) => {
            for (i, p) in points.iter().enumerate() {
                if i > 0 {
                    out.push(' ');
                }
                print_tuple(out, p);
            }
        }
        Value::Switch(on) => out.push_str(if *on { "ON" } else { "OFF" }),
        Value::Shape(s) => out.push_str(s.name()),
        Value::TextureType(t) => out.push_str(t.name()),
        Value::Illumination(i) => out.push_str(illumination_name(*i)),
        Value::Bounds(None) => out.push_str("NONE"),
        Value::BoundingSphere(s) => {
            out.push_str("SPHERE ");
            print_tuple(out, &s[..3]);
            out.push(' ');
            print_expr(out, &s[3]);
        }
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
                && !p.starts_with('(')
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

#[cfg(test)]
mod tests {
    use std::path::Path;
    use std::sync::Arc;

    use proptest::prelude::*;

    use super::*;
    use crate::scene::error::Span;
    use crate::scene::expr::{Axis, BinOp, ExprKind, Spanned};
    use crate::scene::model::Illumination;
    use crate::scene::syntax::{
        Command, Key, KeyUse, ShapeType, TextureType, ValueKind, key_use, parse_syntax,
    };

    fn span() -> Span {
        Span {
            file: Arc::from(Path::new("gen")),
            line: 1,
            col: 1,
        }
    }

    fn e(kind: ExprKind) -> Expr {
        Expr { kind, span: span() }
    }

    fn spanned<T>(value: T) -> Spanned<T> {
        Spanned {
            value,
            span: span(),
        }
    }

    /// Names that the parser reads as names (not variables, functions or keywords of `Let`).
    fn name() -> impl Strategy<Value = String> {
        "[a-wA-W_][a-zA-Z0-9_]{0,5}"
            .prop_filter("not a function", |n| !n.eq_ignore_ascii_case("sqrt"))
    }

    fn number() -> impl Strategy<Value = f64> {
        prop_oneof![
            (0u32..1000).prop_map(f64::from),
            0.0..1e3f64,
            prop::sample::select(vec![
                0.1,
                1e-300,
                5e-324,
                1e300,
                f64::MAX,
                0.5,
                2.0f64.sqrt()
            ]),
        ]
    }

    fn expr() -> impl Strategy<Value = Expr> {
        let leaf = prop_oneof![
            number().prop_map(|v| e(ExprKind::Number(v))),
            prop::sample::select(vec![Axis::X, Axis::Y, Axis::Z]).prop_map(|a| e(ExprKind::Var(a))),
            name().prop_map(|n| e(ExprKind::Name(n))),
        ];
        leaf.prop_recursive(5, 48, 2, |inner| {
            let ops = prop::sample::select(vec![
                BinOp::Add,
                BinOp::Sub,
                BinOp::Mul,
                BinOp::Div,
                BinOp::Pow,
            ]);
            prop_oneof![
                inner.clone().prop_map(|x| e(ExprKind::Neg(Box::new(x)))),
                inner.clone().prop_map(|x| e(ExprKind::Sqrt(Box::new(x)))),
                (ops, inner.clone(), inner).prop_map(|(op, l, r)| e(ExprKind::Binary {
                    op: spanned(op),
                    lhs: Box::new(l),
                    rhs: Box::new(r),
                })),
            ]
        })
    }

    fn tuple(n: usize) -> impl Strategy<Value = Value> {
        prop::collection::vec(expr(), n).prop_map(Value::Tuple)
    }

    fn value(kind: ValueKind) -> BoxedStrategy<Value> {
        match kind {
            ValueKind::Number => expr().prop_map(Value::Number).boxed(),
            ValueKind::Vector => tuple(3).boxed(),
            ValueKind::VectorOrScalar => {
                prop_oneof![tuple(3), expr().prop_map(Value::Number)].boxed()
            }
            ValueKind::Pair => tuple(2).boxed(),
            ValueKind::Switch => any::<bool>().prop_map(Value::Switch).boxed(),
            ValueKind::Shape => prop::sample::select(ShapeType::ALL.to_vec())
                .prop_map(Value::Shape)
                .boxed(),
            ValueKind::TextureType => {
                prop::sample::select(vec![TextureType::Image, TextureType::Checker])
                    .prop_map(Value::TextureType)
                    .boxed()
            }
            ValueKind::Illumination => prop::sample::select(vec![
                Illumination::Blackbody,
                Illumination::Ambient,
                Illumination::Diffuse,
                Illumination::Texture,
                Illumination::Specular,
                Illumination::Mirror,
                Illumination::Transparent,
            ])
            .prop_map(Value::Illumination)
            .boxed(),
            ValueKind::Bounds => prop_oneof![
                Just(Value::Bounds(None)),
                prop::collection::vec(expr(), 4).prop_map(|v| {
                    let four: [Expr; 4] = v.try_into().unwrap_or_else(|_| unreachable!());
                    Value::BoundingSphere(Box::new(four))
                }),
                prop::collection::vec(expr(), 6).prop_map(|v| {
                    let mut it = v.into_iter();
                    let mut pair = || {
                        [
                            it.next().unwrap_or_else(|| unreachable!()),
                            it.next().unwrap_or_else(|| unreachable!()),
                        ]
                    };
                    Value::Bounds(Some(Box::new([pair(), pair(), pair()])))
                }),
            ]
            .boxed(),
            ValueKind::Path => prop_oneof!["[a-zA-Z0-9_./=#()-]{1,12}", "[a-z ]{1,6}/[a-z. ]{1,6}"]
                .prop_map(Value::Path)
                .boxed(),
            ValueKind::ControlPoints => prop_oneof![
                value(ValueKind::Path),
                prop::collection::vec(prop::collection::vec(expr(), 3), 1..18)
                    .prop_map(Value::Points),
            ]
            .boxed(),
            ValueKind::Word => "[a-zA-Z_][a-zA-Z0-9_]{0,6}".prop_map(Value::Word).boxed(),
        }
    }

    /// An entry allowed in `command` (for objects, of type `shape`).
    fn entry(command: Command, shape: Option<ShapeType>) -> BoxedStrategy<Entry> {
        let keys: Vec<(Key, ValueKind)> = Key::ALL
            .iter()
            .filter_map(|&k| match key_use(command, shape, k) {
                KeyUse::Allowed(kind) if k != Key::Type || command == Command::Texture => {
                    Some((k, kind))
                }
                _ => None,
            })
            .collect();
        let set = prop::sample::select(keys).prop_flat_map(|(k, kind)| {
            value(kind).prop_map(move |v| Entry::Set {
                key: spanned(k),
                value: spanned(v),
            })
        });
        let let_ = (
            name().prop_filter("a Let name", |n| {
                !matches!(n.to_ascii_lowercase().as_str(), "x" | "y" | "z")
            }),
            expr(),
        )
            .prop_map(|(n, v)| Entry::Let {
                name: spanned(n),
                value: v,
            });
        prop_oneof![4 => set, 1 => let_].boxed()
    }

    fn block() -> impl Strategy<Value = Block> {
        prop::sample::select(Command::ALL.to_vec()).prop_flat_map(|command| {
            if command == Command::Object {
                prop::sample::select(ShapeType::ALL.to_vec())
                    .prop_flat_map(move |shape| {
                        prop::collection::vec(entry(command, Some(shape)), 0..6).prop_map(
                            move |mut entries| {
                                let ty = Entry::Set {
                                    key: spanned(Key::Type),
                                    value: spanned(Value::Shape(shape)),
                                };
                                entries.insert(0, ty);
                                Block {
                                    command: spanned(command),
                                    entries,
                                }
                            },
                        )
                    })
                    .boxed()
            } else {
                prop::collection::vec(entry(command, None), 0..6)
                    .prop_map(move |entries| Block {
                        command: spanned(command),
                        entries,
                    })
                    .boxed()
            }
        })
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(200))]

        /// STYLE.md §7: parse → print → parse gives the same tree, for random trees.
        #[test]
        fn printed_trees_parse_back_equal(blocks in prop::collection::vec(block(), 0..5)) {
            let ast = SceneAst { blocks, end: span() };
            let text = print(&ast);
            let again = parse_syntax(&text, Path::new("printed"));
            prop_assert!(again.is_ok(), "printed text does not parse: {:?}\n{}", again.err().map(|e| e.to_string()), text);
            let again = again.unwrap_or_else(|_| unreachable!());
            prop_assert_eq!(&again, &ast, "round trip changed the tree; text:\n{}", text);
            prop_assert_eq!(print(&again), text, "printing is stable");
        }
    }

    /// The case kept in `proptest-regressions/scene/print.txt` (shrunk: one `#object` whose
    /// only entry is `Type = BEZIER_PATCH`). Caught: the printed block did not parse back.
    /// The seed was committed with b7dd811, which added `BEZIER_PATCH` to the shape types and
    /// removed the parser's `` `BEZIER_PATCH` is not supported yet `` refusal, so that refusal
    /// is what failed the round trip. Every shape type is checked the same way (issue 10: a
    /// named test for each regression kept only as a seed).
    #[test]
    fn bare_bezier_patch_object_round_trips() {
        for shape in ShapeType::ALL {
            let ast = SceneAst {
                blocks: vec![Block {
                    command: spanned(Command::Object),
                    entries: vec![Entry::Set {
                        key: spanned(Key::Type),
                        value: spanned(Value::Shape(shape)),
                    }],
                }],
                end: span(),
            };
            let text = print(&ast);
            assert_eq!(
                text,
                format!("#object\nType = {}\n", shape.name()),
                "printed {shape:?}"
            );
            let again = parse_syntax(&text, Path::new("printed"))
                .unwrap_or_else(|e| panic!("{shape:?}: printed text does not parse: {e}"));
            assert_eq!(again, ast, "{shape:?} round trip");
        }
    }

    #[test]
    fn minimal_parentheses() {
        let text = "#world\nLet a = -(1 + 2) * 3^-2^2 - (4 - 5) / -(-x)^2 + sqrt(2)\n";
        let ast = parse_syntax(text, Path::new("p")).unwrap();
        assert_eq!(
            print(&ast),
            text,
            "printing keeps the needed parentheses and no others"
        );
    }
}

//! Expressions of the scene language, and their meaning: constant values (`f64`) and
//! polynomials in x, y, z ([`Poly3`]).
//!
//! Every numeric value in a scene file is an [`Expr`]: `0.5`, `-8`, `3/2`, `sqrt(2)/2`, or a
//! name defined earlier in the block with `Let name = …`. The `Equation` of an
//! `ALGEBRAIC_SURFACE` is an expression in the variables `x`, `y`, `z` as well, and is
//! expanded here into the sum of monomials `Σ a_ijk x^i y^j z^k` the tracer restricts to each
//! ray (Stam §3.2.1, which had to hard-code `F`; `paper-notes/scene-language.md` §5).
//!
//! The expansion refuses anything that is not a polynomial, naming the offending token:
//! division by an expression in x, y, z, a negative or fractional exponent of one, `sqrt` of
//! one, an exponent that is not a constant. Constant sub-expressions follow ordinary `f64`
//! arithmetic (any real exponent, `sqrt`), and must stay finite and real.

use super::error::{ErrorKind, SceneError, Span};
use super::print::print_expr;
use super::syntax::Spanned;
use crate::poly3::Poly3;

/// The highest total degree an `Equation` may have.
///
/// Derivation: expanding a product of two polynomials of degrees `a` and `b` costs
/// `C(a+3,3)·C(b+3,3)` term products; with `a + b ≤ 32` the worst case (`a = b = 16`) is
/// about 10⁶, a fraction of a second even for adversarial input. Stam's Sturm code was stable
/// only below degree 9 (§5); degree 32 is far beyond anything that renders cleanly in `f64`,
/// so the limit costs no real scene anything.
pub const MAX_EQUATION_DEGREE: u32 = 32;

/// A binary operator.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum BinOp {
    /// `+`
    Add,
    /// `-`
    Sub,
    /// `*`
    Mul,
    /// `/`
    Div,
    /// `^`
    Pow,
}

impl BinOp {
    /// The operator as written.
    pub fn symbol(self) -> &'static str {
        match self {
            BinOp::Add => "+",
            BinOp::Sub => "-",
            BinOp::Mul => "*",
            BinOp::Div => "/",
            BinOp::Pow => "^",
        }
    }
}

/// One of the three variables of an `Equation`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Axis {
    /// `x`
    X,
    /// `y`
    Y,
    /// `z`
    Z,
}

impl Axis {
    /// The variable's name.
    pub fn name(self) -> &'static str {
        match self {
            Axis::X => "x",
            Axis::Y => "y",
            Axis::Z => "z",
        }
    }
}

/// An expression: a kind and the place of its first token.
///
/// Equality compares what the expressions say, not where they were written (see
/// [`Spanned`]).
#[derive(Clone, Debug)]
pub struct Expr {
    /// What the expression is.
    pub kind: ExprKind,
    /// Where its first token is.
    pub span: Span,
}

impl PartialEq for Expr {
    fn eq(&self, other: &Self) -> bool {
        self.kind == other.kind
    }
}

/// The kinds of expression. Parentheses leave no trace: the tree records the grouping.
#[derive(Clone, Debug, PartialEq)]
pub enum ExprKind {
    /// A literal, always non-negative and finite (a leading `-` is [`ExprKind::Neg`]).
    Number(f64),
    /// `x`, `y` or `z`.
    Var(Axis),
    /// A constant defined with `Let`, as written (names compare case-insensitively).
    Name(String),
    /// `-e`
    Neg(Box<Expr>),
    /// `lhs op rhs`; the operator keeps its own span for messages.
    Binary {
        /// The operator.
        op: Spanned<BinOp>,
        /// Left operand.
        lhs: Box<Expr>,
        /// Right operand.
        rhs: Box<Expr>,
    },
    /// `sqrt(e)`
    Sqrt(Box<Expr>),
}

/// The `Let` constants visible at a point of a block, in definition order.
#[derive(Clone, Debug, Default)]
pub(crate) struct Constants {
    defs: Vec<(String, f64)>,
}

impl Constants {
    /// The value of `name` (case-insensitive), if defined.
    pub(crate) fn get(&self, name: &str) -> Option<f64> {
        self.defs
            .iter()
            .rev()
            .find(|(n, _)| n.eq_ignore_ascii_case(name))
            .map(|&(_, v)| v)
    }

    /// Defines `name`; the caller has checked it is new.
    pub(crate) fn define(&mut self, name: &str, value: f64) {
        self.defs.push((name.to_owned(), value));
    }
}

/// Evaluates a constant expression (no x, y, z) to a finite `f64`.
pub(crate) fn eval_const(e: &Expr, env: &Constants) -> Result<f64, SceneError> {
    let p = expand_in(e, env, false)?;
    // With variables refused, the expansion is a constant.
    Ok(constant_value(&p).unwrap_or(0.0))
}

/// Expands an `Equation` into `Σ a_ijk x^i y^j z^k`, refusing non-polynomial input and any
/// total degree above [`MAX_EQUATION_DEGREE`].
///
/// # Accuracy
/// Coefficients are computed in `f64` in the order the expression dictates; integer and
/// dyadic coefficients of moderate size (as in every scene in `scenes/`) come out exact,
/// others carry the usual rounding of a few operations each.
pub(crate) fn expand(e: &Expr, env: &Constants) -> Result<Poly3, SceneError> {
    expand_in(e, env, true)
}

/// The value of a polynomial of degree 0 (the zero polynomial has no terms).
fn constant_value(p: &Poly3) -> Option<f64> {
    (p.degree() == 0).then(|| p.terms().first().map_or(0.0, |t| t.coeff))
}

fn arithmetic(span: &Span, reason: impl Into<String>) -> SceneError {
    SceneError::at(
        span,
        ErrorKind::Arithmetic {
            reason: reason.into(),
        },
    )
}

fn not_polynomial(span: &Span, reason: impl Into<String>) -> SceneError {
    SceneError::at(
        span,
        ErrorKind::NotPolynomial {
            reason: reason.into(),
        },
    )
}

fn degree_check(span: &Span, degree: u64, e: &Expr) -> Result<(), SceneError> {
    if degree > u64::from(MAX_EQUATION_DEGREE) {
        return Err(SceneError::at(
            span,
            ErrorKind::DegreeTooHigh {
                degree,
                max: MAX_EQUATION_DEGREE,
                expr: quote(e),
            },
        ));
    }
    Ok(())
}

/// A finite result, or an overflow error at `span` quoting `e`.
fn finite(p: Poly3, span: &Span, e: &Expr) -> Result<Poly3, SceneError> {
    if p.is_finite() {
        Ok(p)
    } else {
        Err(arithmetic(
            span,
            format!("overflow: `{}` is not finite", quote(e)),
        ))
    }
}

/// The expression as the printer writes it, shortened to about 40 characters, for messages.
fn quote(e: &Expr) -> String {
    const MAX_CHARS: usize = 40;
    let mut text = String::new();
    print_expr(&mut text, e);
    if text.chars().count() > MAX_CHARS {
        let kept: String = text.chars().take(MAX_CHARS - 1).collect();
        text = format!("{}…", kept.trim_end());
    }
    text
}

/// Divides every coefficient by `d` (dividing rather than multiplying by `1/d` keeps `x/3`
/// correctly rounded).
fn divide(p: &Poly3, d: f64) -> Poly3 {
    Poly3::from_terms(p.terms().iter().map(|t| (t.coeff / d, t.exps)))
}

fn expand_in(e: &Expr, env: &Constants, vars: bool) -> Result<Poly3, SceneError> {
    match &e.kind {
        ExprKind::Number(v) => Ok(Poly3::constant(*v)),
        ExprKind::Var(axis) => {
            if !vars {
                return Err(SceneError::at(
                    &e.span,
                    ErrorKind::VariableInConstant {
                        name: axis.name().to_owned(),
                    },
                ));
            }
            Ok(match axis {
                Axis::X => Poly3::x(),
                Axis::Y => Poly3::y(),
                Axis::Z => Poly3::z(),
            })
        }
        ExprKind::Name(name) => match env.get(name) {
            Some(v) => Ok(Poly3::constant(v)),
            None => Err(SceneError::at(
                &e.span,
                ErrorKind::UnknownName { name: name.clone() },
            )),
        },
        ExprKind::Neg(inner) => Ok(-expand_in(inner, env, vars)?),
        ExprKind::Sqrt(inner) => {
            let p = expand_in(inner, env, vars)?;
            let Some(v) = constant_value(&p) else {
                return Err(not_polynomial(
                    &inner.span,
                    format!("`sqrt` of `{}`, an expression in x, y, z", quote(inner)),
                ));
            };
            if v < 0.0 {
                return Err(arithmetic(
                    &inner.span,
                    format!(
                        "square root of a negative number: `{}` is {v}",
                        quote(inner)
                    ),
                ));
            }
            Ok(Poly3::constant(v.sqrt()))
        }
        ExprKind::Binary { op, lhs, rhs } => {
            let a = expand_in(lhs, env, vars)?;
            let b = expand_in(rhs, env, vars)?;
            let span = &op.span;
            match op.value {
                BinOp::Add => finite(&a + &b, span, e),
                BinOp::Sub => finite(&a - &b, span, e),
                BinOp::Mul => {
                    degree_check(span, u64::from(a.degree()) + u64::from(b.degree()), e)?;
                    let p = match (constant_value(&a), constant_value(&b)) {
                        (Some(c), _) => b.scale(c),
                        (_, Some(c)) => a.scale(c),
                        (None, None) => &a * &b,
                    };
                    finite(p, span, e)
                }
                BinOp::Div => {
                    let Some(d) = constant_value(&b) else {
                        return Err(not_polynomial(
                            &rhs.span,
                            format!("division by `{}`, an expression in x, y, z", quote(rhs)),
                        ));
                    };
                    if d == 0.0 {
                        return Err(arithmetic(
                            &rhs.span,
                            format!("division by zero in `{}`", quote(e)),
                        ));
                    }
                    finite(divide(&a, d), span, e)
                }
                BinOp::Pow => {
                    let Some(k) = constant_value(&b) else {
                        return Err(not_polynomial(
                            &rhs.span,
                            format!("the exponent `{}` is not a constant", quote(rhs)),
                        ));
                    };
                    if let Some(base) = constant_value(&a) {
                        let v = base.powf(k);
                        if v.is_nan() {
                            return Err(arithmetic(
                                span,
                                format!("`{}` is not a real number", quote(e)),
                            ));
                        }
                        return finite(Poly3::constant(v), span, e);
                    }
                    if k < 0.0 {
                        return Err(not_polynomial(
                            &rhs.span,
                            format!("negative exponent {k} of an expression in x, y, z"),
                        ));
                    }
                    if k.fract() != 0.0 {
                        return Err(not_polynomial(
                            &rhs.span,
                            format!(
                                "exponent {k} of an expression in x, y, z is not a whole number"
                            ),
                        ));
                    }
                    // `a` has degree ≥ 1 here, so k ≤ degree(a)·k is checked against the limit
                    // before it is converted.
                    let degree = f64::from(a.degree()) * k;
                    if degree > f64::from(MAX_EQUATION_DEGREE) {
                        // Up to 2⁵³ the degree is an exact integer; beyond, name the exponent
                        // instead of a saturated, meaningless degree.
                        if degree >= 9_007_199_254_740_992.0 {
                            return Err(SceneError::at(
                                span,
                                ErrorKind::ExponentTooLarge {
                                    exponent: k,
                                    max: MAX_EQUATION_DEGREE,
                                    expr: quote(e),
                                },
                            ));
                        }
                        degree_check(span, degree as u64, e)?;
                    }
                    finite(a.pow(k as u32), span, e)
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use std::path::Path;

    use glam::DVec3;

    use super::*;
    use crate::scene::syntax::{Entry, Key, Value, parse_syntax};

    /// Parses `lines` inside an `ALGEBRAIC_SURFACE` block and expands its `Equation`, with
    /// the block's `Let` constants.
    fn equation(lines: &str) -> Result<Poly3, SceneError> {
        let text = format!("#object Type = ALGEBRAIC_SURFACE\n{lines}");
        let ast = parse_syntax(&text, Path::new("e.scene"))?;
        let mut env = Constants::default();
        let mut result = None;
        for entry in &ast.blocks[0].entries {
            match entry {
                Entry::Let { name, value } => {
                    let v = eval_const(value, &env)?;
                    env.define(&name.value, v);
                }
                Entry::Set { key, value } if key.value == Key::Equation => {
                    let Value::Number(e) = &value.value else {
                        panic!("an expression")
                    };
                    result = Some(expand(e, &env)?);
                }
                Entry::Set { .. } => {}
            }
        }
        Ok(result.expect("the test text has an Equation"))
    }

    /// `Σ c x^i y^j z^k` from `(c, [i, j, k])`.
    fn poly(terms: &[(f64, [u32; 3])]) -> Poly3 {
        Poly3::from_terms(terms.iter().copied())
    }

    #[test]
    fn products_and_powers_expand_coefficient_by_coefficient() {
        // Hand-worked: (x + y)^2 = x^2 + 2xy + y^2.
        type Terms = &'static [(f64, [u32; 3])];
        let cases: &[(&str, Terms)] = &[
            (
                "(x + y)^2",
                &[(1.0, [2, 0, 0]), (2.0, [1, 1, 0]), (1.0, [0, 2, 0])],
            ),
            // (x - 2y + 3)(x + z) = x^2 + xz - 2xy - 2yz + 3x + 3z.
            (
                "(x - 2*y + 3)*(x + z)",
                &[
                    (1.0, [2, 0, 0]),
                    (1.0, [1, 0, 1]),
                    (-2.0, [1, 1, 0]),
                    (-2.0, [0, 1, 1]),
                    (3.0, [1, 0, 0]),
                    (3.0, [0, 0, 1]),
                ],
            ),
            // (x + 1)^3 = x^3 + 3x^2 + 3x + 1.
            (
                "(x + 1)^3",
                &[
                    (1.0, [3, 0, 0]),
                    (3.0, [2, 0, 0]),
                    (3.0, [1, 0, 0]),
                    (1.0, [0, 0, 0]),
                ],
            ),
            // (x + y + z)^2: squares once, cross terms twice.
            (
                "(x + y + z)^2",
                &[
                    (1.0, [2, 0, 0]),
                    (1.0, [0, 2, 0]),
                    (1.0, [0, 0, 2]),
                    (2.0, [1, 1, 0]),
                    (2.0, [1, 0, 1]),
                    (2.0, [0, 1, 1]),
                ],
            ),
            // -x^2 is -(x^2); (-x)^2 is x^2; x*y^2*z^3 is one monomial.
            ("-x^2 + (-y)^2", &[(-1.0, [2, 0, 0]), (1.0, [0, 2, 0])]),
            ("2*x*y^2*z^3", &[(2.0, [1, 2, 3])]),
            // Rational and decimal constants: 3/2 x + x/4 + 2^-1 y + 0.25 z.
            (
                "3/2*x + x/4 + 2^-1*y + 0.25*z",
                &[(1.75, [1, 0, 0]), (0.5, [0, 1, 0]), (0.25, [0, 0, 1])],
            ),
            // Cancellation leaves nothing of x: (x + 1)^2 - x^2 - 2x = 1, plus z.
            (
                "(x + 1)^2 - x^2 - 2*x + z",
                &[(1.0, [0, 0, 0]), (1.0, [0, 0, 1])],
            ),
            // Stam's torus (Annexe B `Polynomial`: a4 = u8(u8 - 10) + 15 oz^2 + 9 with
            // u8 = ox^2 + oy^2): x^4 + 2x^2y^2 + y^4 - 10x^2 - 10y^2 + 15z^2 + 9.
            (
                "(x^2 + y^2 - 1)*(x^2 + y^2 - 9) + 15*z^2",
                &[
                    (1.0, [4, 0, 0]),
                    (2.0, [2, 2, 0]),
                    (1.0, [0, 4, 0]),
                    (-10.0, [2, 0, 0]),
                    (-10.0, [0, 2, 0]),
                    (15.0, [0, 0, 2]),
                    (9.0, [0, 0, 0]),
                ],
            ),
        ];
        for (src, terms) in cases {
            let got = equation(&format!("Equation = {src}")).unwrap();
            assert_eq!(got, poly(terms), "expanding {src}: got {got}");
        }
    }

    #[test]
    fn constants_are_evaluated_in_order() {
        let got =
            equation("Let a = 3/2\nLet b = a*2 + sqrt(16)\nLet B2 = b^0.5\nEquation = b*x - B2")
                .unwrap();
        assert_eq!(
            got,
            poly(&[(7.0, [1, 0, 0]), (-(7f64.sqrt()), [0, 0, 0])]),
            "b = 7, B2 = sqrt 7"
        );
    }

    /// Barth's sextic written directly, for comparison with the expansion.
    fn barth_direct(p: DVec3) -> f64 {
        let phi = (1.0 + 5f64.sqrt()) / 2.0;
        let (x2, y2, z2) = (p.x * p.x, p.y * p.y, p.z * p.z);
        let p2 = phi * phi;
        4.0 * (p2 * x2 - y2) * (p2 * y2 - z2) * (p2 * z2 - x2)
            - (1.0 + 2.0 * phi) * (x2 + y2 + z2 - 1.0).powi(2)
    }

    #[test]
    fn barth_sextic_has_degree_six_and_the_right_values() {
        let f = equation(
            "Let phi = (1 + sqrt(5))/2\n\
             Equation = 4*(phi^2*x^2 - y^2)*(phi^2*y^2 - z^2)*(phi^2*z^2 - x^2)\n\
             - (1 + 2*phi)*(x^2 + y^2 + z^2 - 1)^2",
        )
        .unwrap();
        assert_eq!(f.degree(), 6, "Barth's sextic");
        // F(0) = -(1 + 2 phi) = -(2 + sqrt 5); the axis points and (1, 1, 1) lie on the
        // surface (phi^2 - 1 = phi and phi^3 = 2 phi + 1 make both terms cancel).
        let phi = (1.0 + 5f64.sqrt()) / 2.0;
        let known = [
            (DVec3::ZERO, -(2.0 + 5f64.sqrt())),
            (DVec3::X, 0.0),
            (DVec3::Y, 0.0),
            (DVec3::Z, 0.0),
            (DVec3::ONE, 0.0),
            (
                DVec3::new(0.3, -0.7, 1.1),
                barth_direct(DVec3::new(0.3, -0.7, 1.1)),
            ),
            (
                DVec3::new(-1.5, 0.25, phi),
                barth_direct(DVec3::new(-1.5, 0.25, phi)),
            ),
        ];
        for (p, want) in known {
            let got = f.eval(p);
            // Both sides round a few dozen operations of terms bounded by eval_abs.
            let tol = 64.0 * f64::EPSILON * f.eval_abs(p);
            assert!(
                (got - want).abs() <= tol,
                "F({p}) = {got}, expected {want} within {tol}"
            );
        }
        // No x^6 term: every sextic monomial of the product has two or three variables.
        assert!(
            f.terms()
                .iter()
                .all(|t| t.exps.iter().filter(|&&e| e > 0).count() >= 2 || t.degree() < 6),
            "{f}"
        );
    }

    #[test]
    fn non_polynomials_are_refused_at_the_offending_token() {
        let cases: &[(&str, &str)] = &[
            (
                "Equation = 1/x",
                "e.scene:2:14: not a polynomial: division by `x`, an expression in x, y, z",
            ),
            (
                "Equation = x/(y + 1)",
                "e.scene:2:14: not a polynomial: division by `y + 1`, an expression in x, y, z",
            ),
            (
                "Equation = x^-2",
                "e.scene:2:14: not a polynomial: negative exponent -2 of an expression in x, y, z",
            ),
            (
                "Equation = (x + y)^1.5",
                "e.scene:2:20: not a polynomial: exponent 1.5 of an expression in x, y, z is not a whole number",
            ),
            (
                "Equation = 2^x",
                "e.scene:2:14: not a polynomial: the exponent `x` is not a constant",
            ),
            (
                "Equation = sqrt(x*x)",
                "e.scene:2:17: not a polynomial: `sqrt` of `x * x`, an expression in x, y, z",
            ),
            (
                "Equation = x + phi",
                "e.scene:2:16: unknown name `phi` (define it earlier in the block with `Let phi = …`)",
            ),
            (
                "Equation = x/(2 - 2)",
                "e.scene:2:14: division by zero in `x / (2 - 2)`",
            ),
            (
                "Equation = (x + y + z)^40",
                "e.scene:2:23: degree 40 of `(x + y + z)^40` exceeds the maximum 32",
            ),
            (
                "Equation = (x^16 + 1)*(y^17 + 1)",
                "e.scene:2:22: degree 33 of `(x^16 + 1) * (y^17 + 1)` exceeds the maximum 32",
            ),
            (
                "Equation = 10^400*x",
                "e.scene:2:14: overflow: `10^400` is not finite",
            ),
            (
                "Equation = (-8)^(1/3)*x",
                "e.scene:2:16: `(-8)^(1 / 3)` is not a real number",
            ),
            (
                "Let a = sqrt(2 - 3)\nEquation = x",
                "e.scene:2:14: square root of a negative number: `2 - 3` is -1",
            ),
            (
                "Let a = 2*y\nEquation = x",
                "e.scene:2:11: `y` is a variable: only `Equation` may use x, y and z",
            ),
            (
                "Equation = x^2 + (1 + 2 + 3 + 4 + 5 + 6 + 7 + 8 + 9 + 10 + 11 + 12 + 13 + 14)/0",
                "e.scene:2:79: division by zero in `(1 + 2 + 3 + 4 + 5 + 6 + 7 + 8 + 9 + 10…`",
            ),
            (
                "Equation = (x + 1 + 2 + 3 + 4 + 5 + 6 + 7 + 8 + 9 + 10 + 11 + 12 + 13)^33",
                "e.scene:2:71: degree 33 of `(x + 1 + 2 + 3 + 4 + 5 + 6 + 7 + 8 + 9…` exceeds the maximum 32",
            ),
        ];
        for (src, message) in cases {
            let err = equation(src).unwrap_err();
            assert_eq!(err.to_string(), *message, "expanding {src:?}");
        }
    }

    #[test]
    fn degree_limit_allows_exactly_the_maximum() {
        let f = equation("Equation = (x^16 + 1)*(y^16 - z) + x^31*(2 + 1)*z").unwrap();
        assert_eq!(f.degree(), MAX_EQUATION_DEGREE, "degree 32 is accepted");
        assert_eq!(f.terms().len(), 5, "{f}");
        let err = equation("Equation = x^32*y").unwrap_err();
        assert!(
            matches!(
                err.kind(),
                Some(ErrorKind::DegreeTooHigh { degree: 33, .. })
            ),
            "{err}"
        );
    }
}

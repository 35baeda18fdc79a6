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

use std::fmt::Write as _;

use super::error::{ErrorKind, SceneError, Span};
use crate::trivariate::Poly3;

/// The highest total degree an `Equation` may have.
///
/// Derivation: the scene language promises any degree a surface needs; 128 is twice the
/// degree of the highest example (`scenes/quartic-power64.scene`) and keeps every structure
/// sized by the degree small: at most `C(131, 3) = 366 145` monomials (about 9 MB of terms),
/// ray polynomials of 129 coefficients, restriction tables of `129·130/2` entries. Expansion
/// time is bounded separately, by [`MAX_TERM_PRODUCTS`].
pub const MAX_EQUATION_DEGREE: u32 = 128;

/// The most term products one multiplication of an `Equation`'s expansion may take
/// (`terms(a) · terms(b)`), checked before it starts: 2²⁵ ≈ 3.4·10⁷.
///
/// Derivation: [`Poly3::checked_mul`] sums into a dense array, a few flops per product, so
/// an adversarial equation at the limit parses in well under a second (measured in
/// `paper-notes/scene-language.md` §5). It admits `(x + y + z)^128` (8 385 terms, its last
/// squaring 2 145² = 4.6·10⁶ products) and dense equations at least to degree 48
/// (`(x + y + z + 1)^48`), and refuses `(x + y + z + 1)^128` (366 145 terms; its last
/// squaring alone needs 2.3·10⁹ products) at its operator.
pub const MAX_TERM_PRODUCTS: usize = 1 << 25;

/// A value and where it was written. Equality compares the values only, so two trees that
/// say the same thing are equal wherever their text sits (as `toml::Spanned` does).
#[derive(Clone, Debug)]
pub struct Spanned<T> {
    /// The value.
    pub value: T,
    /// Where its first token is.
    pub span: Span,
}

impl<T: PartialEq> PartialEq for Spanned<T> {
    fn eq(&self, other: &Self) -> bool {
        self.value == other.value
    }
}

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

impl Expr {
    /// The value of a constant expression (no x, y, z), with `lets` the `Let` constants
    /// defined before it, in order: what the build step computes for a `Let` (the `render
    /// serve` explorer uses it to place its sliders).
    ///
    /// # Errors
    /// As the build step: an undefined name, a variable, a non-finite result.
    pub fn const_value(&self, lets: &[(String, f64)]) -> Result<f64, SceneError> {
        let mut env = Constants::default();
        for (name, value) in lets {
            env.define(name, *value);
        }
        eval_const(self, &env)
    }
}

/// Evaluates a constant expression (no x, y, z) to a finite `f64`.
pub(crate) fn eval_const(e: &Expr, env: &Constants) -> Result<f64, SceneError> {
    let p = expand_in(e, env, false)?;
    // With variables refused, the expansion is a constant.
    Ok(constant_value(&p).unwrap_or(0.0))
}

/// Expands an `Equation` into `Σ a_ijk x^i y^j z^k`, refusing non-polynomial input, any
/// total degree above [`MAX_EQUATION_DEGREE`] and any multiplication of more than
/// [`MAX_TERM_PRODUCTS`] term products.
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

/// The error for an expansion step that would take more than [`MAX_TERM_PRODUCTS`].
fn too_many_products(span: &Span, e: &Expr) -> SceneError {
    SceneError::at(
        span,
        ErrorKind::ExpansionTooLarge {
            max: MAX_TERM_PRODUCTS,
            expr: quote(e),
        },
    )
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
                        (None, None) => a
                            .checked_mul(&b, MAX_TERM_PRODUCTS)
                            .ok_or_else(|| too_many_products(span, e))?,
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
                    let p = a
                        .checked_pow(k as u32, MAX_TERM_PRODUCTS)
                        .ok_or_else(|| too_many_products(span, e))?;
                    finite(p, span, e)
                }
            }
        }
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

//! Tests of the expression layer through the parser: equations and constants as written in
//! scene files (a sibling of `expr` and `syntax`, so that `expr` does not depend on the parser).

use std::path::Path;

use glam::DVec3;

use super::error::{ErrorKind, SceneError};
use super::expr::*;
use crate::scene::syntax::{Entry, Key, Value, parse_syntax};
use crate::trivariate::Poly3;

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
    let got = equation("Let a = 3/2\nLet b = a*2 + sqrt(16)\nLet B2 = b^0.5\nEquation = b*x - B2")
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
            "Equation = (x + y + z)^130",
            "e.scene:2:23: degree 130 of `(x + y + z)^130` exceeds the maximum 128",
        ),
        (
            "Equation = (x^64 + 1)*(y^65 + 1)",
            "e.scene:2:22: degree 129 of `(x^64 + 1) * (y^65 + 1)` exceeds the maximum 128",
        ),
        (
            "Equation = (x + y + z + 1)^128",
            "e.scene:2:27: expanding `(x + y + z + 1)^128` needs more than 33554432 term \
             products; write it with fewer terms or in a lower degree",
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
            "Equation = (x + 1 + 2 + 3 + 4 + 5 + 6 + 7 + 8 + 9 + 10 + 11 + 12 + 13)^129",
            "e.scene:2:71: degree 129 of `(x + 1 + 2 + 3 + 4 + 5 + 6 + 7 + 8 + 9…` exceeds the maximum 128",
        ),
    ];
    for (src, message) in cases {
        let err = equation(src).unwrap_err();
        assert_eq!(err.to_string(), *message, "expanding {src:?}");
    }
}

#[test]
fn degree_limit_allows_exactly_the_maximum() {
    let f = equation("Equation = (x^64 + 1)*(y^64 - z) + x^127*(2 + 1)*z").unwrap();
    assert_eq!(f.degree(), MAX_EQUATION_DEGREE, "degree 128 is accepted");
    assert_eq!(f.terms().len(), 5, "{f}");
    let err = equation("Equation = x^128*y").unwrap_err();
    assert!(
        matches!(
            err.kind(),
            Some(ErrorKind::DegreeTooHigh { degree: 129, .. })
        ),
        "{err}"
    );
}

/// Issue 11: the degree cap was 32; `(x + y + z)^128` now expands (8 385 terms, its largest
/// multiplication 2 145² term products, within `MAX_TERM_PRODUCTS`).
#[test]
fn r11_degree_128_expands_within_the_product_limit() {
    let f = equation("Equation = (x + y + z)^128").unwrap();
    assert_eq!(f.degree(), 128, "degree");
    assert_eq!(
        f.terms().len(),
        130 * 129 / 2,
        "C(130, 2) monomials of degree 128"
    );
    let middle = f
        .terms()
        .iter()
        .find(|t| t.exps == [64, 64, 0])
        .expect("x^64 y^64 is a term");
    // C(128, 64) = 2.395...e37, computed as a product of ratios.
    let binomial = (1..=64).fold(1.0f64, |c, i| c * f64::from(64 + i) / f64::from(i));
    assert!(
        (middle.coeff - binomial).abs() <= 1e-12 * binomial,
        "coefficient of x^64 y^64: {} against C(128, 64) = {binomial}",
        middle.coeff
    );
}

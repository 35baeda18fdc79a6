//! Operator impls for [`Poly`]: `+ - *` and unary `-`, by value and by reference.
//!
//! All four operand forms (`a op b`, `&a op b`, `a op &b`, `&a op &b`) are generated from the
//! reference–reference implementation by a macro, so they cannot disagree.

use std::ops::{Add, Mul, Neg, Sub};

use crate::scalar::Scalar;
use crate::univariate::Poly;

fn add_sub<T: Scalar>(a: &Poly<T>, b: &Poly<T>, subtract: bool) -> Poly<T> {
    let (ac, bc) = (a.coeffs(), b.coeffs());
    let n = ac.len().max(bc.len());
    let out = (0..n)
        .map(|i| {
            let x = ac.get(i).cloned().unwrap_or_else(T::zero);
            match bc.get(i) {
                None => x,
                Some(y) if subtract => x - y,
                Some(y) => x + y,
            }
        })
        .collect();
    Poly::new(out)
}

fn mul<T: Scalar>(a: &Poly<T>, b: &Poly<T>) -> Poly<T> {
    if a.is_zero() || b.is_zero() {
        return Poly::zero();
    }
    let (ac, bc) = (a.coeffs(), b.coeffs());
    let mut out = vec![T::zero(); ac.len() + bc.len() - 1];
    for (i, x) in ac.iter().enumerate() {
        for (j, y) in bc.iter().enumerate() {
            out[i + j] = out[i + j].clone() + x.clone() * y;
        }
    }
    Poly::new(out)
}

macro_rules! forward_binop {
    ($Trait:ident, $method:ident, $body:expr) => {
        impl<T: Scalar> $Trait<&Poly<T>> for &Poly<T> {
            type Output = Poly<T>;
            fn $method(self, rhs: &Poly<T>) -> Poly<T> {
                $body(self, rhs)
            }
        }
        impl<T: Scalar> $Trait<Poly<T>> for &Poly<T> {
            type Output = Poly<T>;
            fn $method(self, rhs: Poly<T>) -> Poly<T> {
                $body(self, &rhs)
            }
        }
        impl<T: Scalar> $Trait<&Poly<T>> for Poly<T> {
            type Output = Poly<T>;
            fn $method(self, rhs: &Poly<T>) -> Poly<T> {
                $body(&self, rhs)
            }
        }
        impl<T: Scalar> $Trait<Poly<T>> for Poly<T> {
            type Output = Poly<T>;
            fn $method(self, rhs: Poly<T>) -> Poly<T> {
                $body(&self, &rhs)
            }
        }
    };
}

forward_binop!(Add, add, |a, b| add_sub(a, b, false));
forward_binop!(Sub, sub, |a, b| add_sub(a, b, true));
forward_binop!(Mul, mul, mul);

impl<T: Scalar> Neg for &Poly<T> {
    type Output = Poly<T>;
    fn neg(self) -> Poly<T> {
        Poly::new_raw(self.coeffs().iter().map(|c| -c.clone()).collect())
    }
}

impl<T: Scalar> Neg for Poly<T> {
    type Output = Poly<T>;
    fn neg(self) -> Poly<T> {
        -&self
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scalar::Rat;

    fn qp(c: &[i64]) -> Poly<Rat> {
        Poly::new(c.iter().map(|&n| Rat::from_integer(n.into())).collect())
    }

    #[test]
    fn every_operand_form_agrees() {
        let (a, b) = (qp(&[1, 2, 3]), qp(&[-1, 0, -3]));
        let sum = qp(&[0, 2]);
        assert_eq!(&a + &b, sum, "&a + &b");
        assert_eq!(a.clone() + &b, sum, "a + &b");
        assert_eq!(&a + b.clone(), sum, "&a + b");
        assert_eq!(a.clone() + b.clone(), sum, "a + b");
        let diff = qp(&[2, 2, 6]);
        assert_eq!(&a - &b, diff, "&a - &b");
        assert_eq!(a.clone() - b.clone(), diff, "a - b");
        let prod = qp(&[-1, -2, -6, -6, -9]);
        assert_eq!(&a * &b, prod, "&a * &b");
        assert_eq!(a.clone() * b.clone(), prod, "a * b");
        assert_eq!(a.clone() * &b, prod, "a * &b");
        assert_eq!(&a * b.clone(), prod, "&a * b");
        assert_eq!(-&a, qp(&[-1, -2, -3]), "-&a");
        assert_eq!(-a.clone() + a, Poly::zero(), "a − a = 0, trimmed");
    }

    #[test]
    fn product_with_zero_is_zero() {
        assert!((&qp(&[1, 1]) * &Poly::zero()).is_zero(), "p·0 = 0");
    }
}

//! The Bézout resultant of two polynomials of degree ≤ 3 in `u` and in `v` (a ray against a
//! bicubic patch, article §2 eq. 5) in fixed-size arrays (a matrix of at most 3 × 3 entries of
//! degree ≤ 6 in `u`): [`bezout_resultant_v`](crate::bezout_resultant_v) for small degrees,
//! with no allocation but the result, and the per-ray solver's determinant.
//!
//! Same formula as [`bezout_matrix_v`](crate::bezout_matrix_v): with `f = Σ a_k(u) v^k`,
//! `g = Σ b_k(u) v^k` and `N = max(deg_v)`, the Bézout matrix is
//! `B_ij = Σ_{q ≤ min(i,j), p = i+j+1−q ≤ N} (a_p b_q − a_q b_p)` and the resultant is
//! `(−1)^{N(N−1)/2} det B`. Every `a_p b_q − a_q b_p` has degree ≤ 6 in `u`, so `B` (at most
//! `3 × 3`) holds degree-6 entries and `det B` has degree ≤ 18 (Kajiya's bound). Only ring
//! operations are used, so over `Rat` the result is exactly the general path's.

use poly::{BiPoly, Poly, Scalar};

/// The largest degree in `u` and in `v` this path handles.
pub(crate) const BICUBIC_DEGREE: usize = 3;

/// A polynomial in `u` of degree `< L`, lowest power first.
pub(crate) type UPoly<T, const L: usize> = [T; L];

fn zeros<T: Scalar, const L: usize>() -> UPoly<T, L> {
    std::array::from_fn(|_| T::zero())
}

/// `x · y` truncated to `L` coefficients (callers size `L` so nothing is lost).
fn mul<T: Scalar, const A: usize, const B: usize, const L: usize>(
    x: &UPoly<T, A>,
    y: &UPoly<T, B>,
) -> UPoly<T, L> {
    let mut out = zeros::<T, L>();
    for (i, xi) in x.iter().enumerate() {
        if xi.is_zero() {
            continue;
        }
        for (j, yj) in y.iter().enumerate() {
            if i + j < L {
                out[i + j] = out[i + j].clone() + xi.clone() * yj;
            }
        }
    }
    out
}

fn sub_assign<T: Scalar, const L: usize>(x: &mut UPoly<T, L>, y: &UPoly<T, L>) {
    for (a, b) in x.iter_mut().zip(y) {
        *a = a.clone() - b;
    }
}

fn add_assign<T: Scalar, const L: usize>(x: &mut UPoly<T, L>, y: &UPoly<T, L>) {
    for (a, b) in x.iter_mut().zip(y) {
        *a = a.clone() + b;
    }
}

/// The coefficients in `v` of `p`, each a polynomial in `u` of degree ≤ 3.
fn rows<T: Scalar>(p: &BiPoly<T>) -> [UPoly<T, 4>; 4] {
    std::array::from_fn(|j| std::array::from_fn(|i| p.coeff(i, j)))
}

/// `Res_v(f, g)` by the Bézout determinant when both have degree ≤ [`BICUBIC_DEGREE`] in `u`
/// and in `v` and at least one has positive degree in `v`; `None` otherwise (the general path
/// applies). Neither may be zero (the caller handles that).
pub(crate) fn bezout_bicubic_resultant<T: Scalar>(f: &BiPoly<T>, g: &BiPoly<T>) -> Option<Poly<T>> {
    let n = f.deg_v().max(g.deg_v());
    if n == 0 || n > BICUBIC_DEGREE || f.deg_u() > BICUBIC_DEGREE || g.deg_u() > BICUBIC_DEGREE {
        return None;
    }
    Some(Poly::new(
        bezout_bicubic_det(&rows(f), &rows(g), n).to_vec(),
    ))
}

/// The Bézout resultant `(−1)^{N(N−1)/2} det B` of the polynomials whose coefficients in `v`
/// are `a` and `b` (each a polynomial in `u`, lowest power first), `N = n ≥ 1` their largest
/// `v`-degree: 19 coefficients, lowest power first (trailing ones may be zero). No allocation.
pub(crate) fn bezout_bicubic_det<T: Scalar>(
    a: &[UPoly<T, 4>; 4],
    b: &[UPoly<T, 4>; 4],
    n: usize,
) -> UPoly<T, 19> {
    debug_assert!((1..=BICUBIC_DEGREE).contains(&n), "1 ≤ N ≤ 3");
    // d[p][q] = a_p b_q − a_q b_p for q < p ≤ n (antisymmetric; only these are used).
    let mut d: [[UPoly<T, 7>; 4]; 4] = std::array::from_fn(|_| std::array::from_fn(|_| zeros()));
    for p in 1..=n {
        for q in 0..p {
            let mut e: UPoly<T, 7> = mul(&a[p], &b[q]);
            sub_assign(&mut e, &mul(&a[q], &b[p]));
            d[p][q] = e;
        }
    }
    let mut m: [[UPoly<T, 7>; 3]; 3] = std::array::from_fn(|_| std::array::from_fn(|_| zeros()));
    for (i, row) in m.iter_mut().enumerate().take(n) {
        for (j, entry) in row.iter_mut().enumerate().take(n) {
            // q = i + j + 1 − p ≤ min(i, j)  ⇔  p ≥ max(i, j) + 1; and p ≤ N.
            let last = n.min(i + j + 1);
            for (p, dp) in d.iter().enumerate().take(last + 1).skip(i.max(j) + 1) {
                add_assign(entry, &dp[i + j + 1 - p]);
            }
        }
    }
    let det: UPoly<T, 19> = match n {
        1 => {
            let mut out = zeros();
            for (o, x) in out.iter_mut().zip(&m[0][0]) {
                *o = x.clone();
            }
            out
        }
        2 => {
            let mut out: UPoly<T, 19> = mul(&m[0][0], &m[1][1]);
            sub_assign(&mut out, &mul(&m[0][1], &m[1][0]));
            out
        }
        _ => {
            // Cofactor expansion along the first row.
            let minor = |r: [usize; 2], c: [usize; 2]| -> UPoly<T, 13> {
                let mut x: UPoly<T, 13> = mul(&m[r[0]][c[0]], &m[r[1]][c[1]]);
                sub_assign(&mut x, &mul(&m[r[0]][c[1]], &m[r[1]][c[0]]));
                x
            };
            let mut out: UPoly<T, 19> = mul(&m[0][0], &minor([1, 2], [1, 2]));
            sub_assign(&mut out, &mul(&m[0][1], &minor([1, 2], [0, 2])));
            add_assign(&mut out, &mul(&m[0][2], &minor([1, 2], [0, 1])));
            out
        }
    };
    if (n * (n - 1) / 2) % 2 == 1 {
        det.map(|c| -c)
    } else {
        det
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{bezout_matrix_v, poly_matrix_det};
    use poly::Rat;

    /// A pseudo-random generator (xorshift) so the test needs no seed handling.
    struct Rng(u64);
    impl Rng {
        fn next(&mut self) -> i64 {
            self.0 ^= self.0 << 13;
            self.0 ^= self.0 >> 7;
            self.0 ^= self.0 << 17;
            (self.0 % 19) as i64 - 9
        }
    }

    fn random(rng: &mut Rng, du: usize, dv: usize) -> BiPoly<Rat> {
        BiPoly::from_fn(du + 1, dv + 1, |_, _| Rat::from_integer(rng.next().into()))
    }

    /// The general path, written out: `(−1)^{N(N−1)/2} det B` over polynomial entries.
    fn general(f: &BiPoly<Rat>, g: &BiPoly<Rat>) -> Poly<Rat> {
        let n = f.deg_v().max(g.deg_v());
        let det = poly_matrix_det(&bezout_matrix_v(f, g).unwrap()).unwrap();
        if (n * (n - 1) / 2) % 2 == 1 {
            -det
        } else {
            det
        }
    }

    #[test]
    fn equals_the_general_bezout_determinant_exactly() {
        let mut rng = Rng(0x9e37_79b9_7f4a_7c15);
        for du in 0..=3 {
            for dv in 1..=3 {
                for other_dv in 0..=3 {
                    let f = random(&mut rng, du, dv);
                    let g = random(&mut rng, 3 - du.min(2), other_dv);
                    let fast = bezout_bicubic_resultant(&f, &g).expect("small degrees");
                    assert_eq!(fast, general(&f, &g), "du {du} dv {dv}/{other_dv}");
                }
            }
        }
    }

    #[test]
    fn bicubic_pair_has_degree_eighteen_and_matches_in_f64() {
        let mut rng = Rng(12345);
        let f = random(&mut rng, 3, 3);
        let g = random(&mut rng, 3, 3);
        let exact = bezout_bicubic_resultant(&f, &g).unwrap();
        assert_eq!(
            exact.degree(),
            18,
            "Kajiya's bound, reached by a generic pair"
        );
        let to_f64 = |p: &BiPoly<Rat>| {
            BiPoly::from_fn(p.stride(), p.rows(), |i, j| p.coeff(i, j).nearest_f64())
        };
        let fast = bezout_bicubic_resultant(&to_f64(&f), &to_f64(&g)).unwrap();
        for (x, e) in fast.coeffs().iter().zip(exact.coeffs()) {
            // Integer inputs of size ≤ 9: every product is an integer far below 2^53.
            assert_eq!(*x, e.nearest_f64());
        }
    }

    #[test]
    fn declines_what_it_does_not_handle() {
        let mut rng = Rng(7);
        let cubic = random(&mut rng, 3, 3);
        assert!(
            bezout_bicubic_resultant(&random(&mut rng, 4, 1), &cubic).is_none(),
            "deg_u 4"
        );
        assert!(
            bezout_bicubic_resultant(&random(&mut rng, 1, 4), &cubic).is_none(),
            "deg_v 4"
        );
        let constant_in_v = random(&mut rng, 2, 0);
        assert!(
            bezout_bicubic_resultant(&constant_in_v, &constant_in_v).is_none(),
            "N = 0"
        );
    }
}

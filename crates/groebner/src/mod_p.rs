//! Arithmetic modulo the Mersenne prime `p = 2³¹ − 1`, and with it a cheap proof that two
//! `f64` equations have a common root (real or complex, with `lc_v` not both zero there):
//! [`proves_common_root`]. The `f64` [`solve`](crate::solve) runs it before the exact test of
//! "no common root at all" (`driver.rs`, issue 10 item 5), which costs milliseconds: on an
//! ordinary system the proof succeeds in a few thousand word operations and the exact test
//! is skipped. See `paper-notes/resultant.md` §5 ("Roots at infinity").

use std::slice::ChunksExact;

/// The modulus, `2³¹ − 1` (prime). Every `f64` is a dyadic rational `m·2^e`, and `2³¹ ≡ 1`,
/// so an `f64` reduces exactly in a few operations ([`from_f64`]); products of two residues fit
/// in a `u64`.
const P: u64 = (1 << 31) - 1;

/// `x mod p` for any `x < 2⁶⁴`, by folding (`2³¹ ≡ 1`).
fn reduce(x: u64) -> u64 {
    let x = (x & P) + (x >> 31); // < 2³¹ + 2³³
    let x = (x & P) + (x >> 31); // < 2³¹ + 8
    if x >= P { x - P } else { x }
}

fn mul(a: u64, b: u64) -> u64 {
    reduce(a * b)
}

fn sub(a: u64, b: u64) -> u64 {
    if a >= b { a - b } else { a + P - b }
}

/// The residue of a finite `f64`: the exact rational `±m·2^e` modulo `p`.
fn from_f64(x: f64) -> u64 {
    debug_assert!(x.is_finite(), "the solver refuses non-finite input");
    if x == 0.0 {
        return 0;
    }
    let (m, e) = poly::f64_dyadic(x);
    let r = mul(reduce(m.unsigned_abs()), 1 << e.rem_euclid(31));
    if m < 0 { sub(0, r) } else { r }
}

/// A dual number `a + b·ε` (`ε² = 0`) over the residues: a value and its derivative.
#[derive(Clone, Copy, Debug)]
struct Dual {
    a: u64,
    b: u64,
}

impl Dual {
    fn mul(self, o: Dual) -> Dual {
        Dual {
            a: mul(self.a, o.a),
            b: reduce(self.a * o.b + self.b * o.a),
        }
    }

    fn sub(self, o: Dual) -> Dual {
        Dual {
            a: sub(self.a, o.a),
            b: sub(self.b, o.b),
        }
    }
}

/// A polynomial in `u` (residues, lowest power first) and its derivative at `t` (Horner).
fn eval_dual(c: &[u64], t: u64) -> Dual {
    let (mut a, mut b) = (0, 0);
    for &x in c.iter().rev() {
        b = reduce(b * t + a);
        a = reduce(a * t + x);
    }
    Dual { a, b }
}

/// `Res'/Res` at `t` as a fraction `(N, D)`, `D ≠ 0`, for the Sylvester matrix of `f` and
/// `g` in `v` (rows of residues, `v`-degrees `rows.len() − 1`), or `None` when `Res(t) ≡ 0`.
///
/// Division-free elimination over dual numbers: step `i` multiplies the rows below the pivot
/// by the pivot `U_ii`, so `∏ U_ii = Res·∏ U_ii^(n−1−i)` (up to sign) and
/// `Res'/Res = Σ (i + 2 − n)·U_ii'/U_ii`, summed as one fraction (no inversion).
fn log_derivative(f: &[Vec<u64>], g: &[Vec<u64>], t: u64, m: &mut Vec<Dual>) -> Option<(u64, u64)> {
    let (d1, d2) = (f.len() - 1, g.len() - 1);
    let n = d1 + d2;
    m.clear();
    m.resize(n * n, Dual { a: 0, b: 0 });
    let fv: Vec<Dual> = f.iter().map(|r| eval_dual(r, t)).collect();
    let gv: Vec<Dual> = g.iter().map(|r| eval_dual(r, t)).collect();
    for i in 0..d2 {
        m[i * n + i..i * n + i + d1 + 1].copy_from_slice(&fv);
    }
    for i in 0..d1 {
        let row = (d2 + i) * n;
        m[row + i..row + i + d2 + 1].copy_from_slice(&gv);
    }
    let (mut num, mut den) = (0, 1);
    for i in 0..n {
        let r = (i..n).find(|&r| m[r * n + i].a != 0)?;
        if r != i {
            for c in i..n {
                m.swap(i * n + c, r * n + c);
            }
        }
        let piv = m[i * n + i];
        for j in i + 1..n {
            let lead = m[j * n + i];
            for c in i + 1..n {
                m[j * n + c] = piv.mul(m[j * n + c]).sub(lead.mul(m[i * n + c]));
            }
        }
        // weight (i + 2 − n) mod p
        let w = sub(reduce(i as u64 + 2), reduce(n as u64));
        num = reduce(mul(num, piv.a) + mul(mul(w, piv.b), den));
        den = mul(den, piv.a);
    }
    Some((num, den))
}

/// The binomial coefficient `C(k, j)` modulo `p` (`k` small: the `u`-degree of a leading
/// coefficient).
fn binomial(k: usize, j: usize) -> u64 {
    // Pascal's triangle: no inversion.
    let mut row = vec![1u64];
    for _ in 0..k {
        let mut next = Vec::with_capacity(row.len() + 1);
        next.push(1);
        next.extend(row.windows(2).map(|w| reduce(w[0] + w[1])));
        next.push(1);
        row = next;
    }
    row[j]
}

/// Whether `F1 = F2 = 0` certainly has a common root `(u, v) ∈ ℂ²` at which the leading
/// coefficients in `v` are not both zero — which rules out [`Verdict::NoCommonRoot`]
/// (crate::Verdict). `false` means "not proven" (the exact test decides).
///
/// # Exactness
/// The proof is exact: with `Res = Res_v(F1, F2)` (Sylvester, the actual `v`-degrees) and `G`
/// the leading coefficient in `v` of smaller `u`-degree `k`, if every root of `Res` were a
/// root of `gcd(lc_v F1, lc_v F2)` (the only case without such a common root), then modulo `p`
/// too every root of `Res` is a root of `G` (Gauss's lemma: the gcd's reduction divides both
/// reduced leading coefficients), so `G·Res'/Res` is a polynomial of degree below `k` and its
/// `k`-th difference at `k + 1` consecutive points vanishes. A non-zero difference is the
/// proof. Unlucky primes or points (probability about `deg Res / p`) only make it fail to
/// prove, never prove wrongly.
///
/// # Complexity
/// `k + 1` eliminations of the `(d1 + d2)²` Sylvester matrix over dual numbers, no inversion.
pub(crate) fn proves_common_root(f: [ChunksExact<'_, f64>; 2]) -> bool {
    let residues = |rows: ChunksExact<'_, f64>| -> Vec<Vec<u64>> {
        let mut r: Vec<Vec<u64>> = rows
            .map(|row| {
                let mut c: Vec<u64> = row.iter().map(|&x| from_f64(x)).collect();
                while c.last() == Some(&0) {
                    c.pop();
                }
                c
            })
            .collect();
        while r.last().is_some_and(Vec::is_empty) {
            r.pop();
        }
        r
    };
    let (f1, f2) = (residues(f[0].clone()), residues(f[1].clone()));
    if f1.len() < 2 || f2.len() < 2 {
        return false; // a zero or v-free equation: decided elsewhere
    }
    let lc = [&f1[f1.len() - 1], &f2[f2.len() - 1]];
    let g = if lc[0].len() <= lc[1].len() {
        lc[0]
    } else {
        lc[1]
    };
    let k = g.len() - 1;
    let mut m = Vec::new();
    // Runs of points away from small integers such as the patch corners 0 and 1, where a
    // collapsed patch edge can make Res vanish.
    for start in FIRST_POINTS {
        let mut terms = Vec::with_capacity(k + 1);
        for j in 0..=k {
            let t = reduce(start + j as u64);
            let Some((num, den)) = log_derivative(&f1, &f2, t, &mut m) else {
                break;
            };
            terms.push((mul(eval_dual(g, t).a, num), den));
        }
        if terms.len() < k + 1 {
            continue; // Res vanished at a point: try others
        }
        // Σ_j (−1)^(k−j)·C(k, j)·R_j with R_j = terms[j].0 / terms[j].1, times Π_j den_j.
        let mut sum = 0;
        for (j, &(r, _)) in terms.iter().enumerate() {
            let mut x = mul(binomial(k, j), r);
            for (l, &(_, den)) in terms.iter().enumerate() {
                if l != j {
                    x = mul(x, den);
                }
            }
            // sign (−1)^(k−j)
            sum = if (k - j) & 1 == 0 {
                reduce(sum + x)
            } else {
                sub(sum, x)
            };
        }
        return sum != 0;
    }
    false
}

/// First points of the runs of `k + 1` consecutive evaluation points (arbitrary residues, far
/// from small integers); a run at which `Res` vanishes is replaced by the next.
const FIRST_POINTS: [u64; 3] = [1_000_003, 123_456_791, 987_654_319];

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn residues_of_floats_are_exact() {
        // 0.75 = 3/4: 4·r ≡ 3.
        assert_eq!(mul(from_f64(0.75), 4), 3, "3/4");
        assert_eq!(reduce(from_f64(-0.75) + from_f64(0.75)), 0, "negation");
        // 2^-40 · 2^40 = 1 and a subnormal times its inverse power of two.
        assert_eq!(
            mul(from_f64(2f64.powi(-40)), from_f64(2f64.powi(40))),
            1,
            "2^±40"
        );
        let tiny = f64::from_bits(3); // 3·2^-1074
        assert_eq!(
            mul(from_f64(tiny), 1 << 1074_i32.rem_euclid(31)),
            3,
            "subnormal"
        );
    }

    fn rows(p: &[&[f64]]) -> Vec<f64> {
        p.iter().flat_map(|r| r.iter().copied()).collect()
    }

    #[test]
    fn proves_ordinary_systems_and_not_the_roots_at_infinity() {
        // Circle u² + v² − 1/2 and line v − u (rows: coefficients of v^j, stride 3).
        let circle = rows(&[&[-0.5, 0.0, 1.0], &[0.0, 0.0, 0.0], &[1.0, 0.0, 0.0]]);
        let line = rows(&[&[0.0, -1.0, 0.0], &[1.0, 0.0, 0.0]]);
        assert!(
            proves_common_root([circle.chunks_exact(3), line.chunks_exact(3)]),
            "circle and line meet"
        );
        // Issue 10, item 5: −u² + 3uv + v and 2u² − 6uv − 2v − 2 have no common root.
        let f1 = rows(&[&[0.0, 0.0, -1.0], &[1.0, 3.0, 0.0]]);
        let f2 = rows(&[&[-2.0, 0.0, 2.0], &[-2.0, -6.0, 0.0]]);
        assert!(
            !proves_common_root([f1.chunks_exact(3), f2.chunks_exact(3)]),
            "no common root: nothing to prove"
        );
    }
}

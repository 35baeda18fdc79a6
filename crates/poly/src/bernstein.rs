//! [`BernsteinIsolator`]: certified root isolation by Descartes' rule in the Bernstein basis,
//! in `f64` with a rigorous bound on every rounding error.
//!
//! The interval `[t_min, t_max]` is mapped to `[0, 1]` by `t = a + w·u` (`a = t_min`, `w` the
//! difference rounded *up*, so `a + w ≥ t_max`). The Bernstein coefficients `bᵢ` of
//! `q(u) = p(a + w·u)` on `[0, 1]` have the property that the number of sign changes in
//! `b₀, …, bₙ` bounds the number of roots in `(0, 1)` and has the same parity (Descartes' rule
//! in the Bernstein basis). So no change means no root, one change means exactly one root;
//! otherwise the interval is halved with de Casteljau's algorithm, leftmost half first, so the
//! smallest root is found without isolating the others (Collins–Akritas, "Polynomial real root
//! isolation using Descartes' rule of signs", 1976; see `paper-notes/isolation.md`).
//!
//! Every coefficient is carried with the same computation applied to absolute values, `mᵢ`.
//! For a straight-line program of `k` roundings along any path the computed value satisfies
//! `|b̂ᵢ − bᵢ| ≤ γ(k)·mᵢ*` (Higham, *Accuracy and Stability*, §3.1, the standard model), and the
//! computed `m̂ᵢ ≥ (1 − γ(k))·mᵢ*`. A sign is used only when `|b̂ᵢ|` exceeds that bound, so the
//! sign changes counted are those of the exact Bernstein coefficients of the stored polynomial
//! on the exact sub-interval. When a needed sign cannot be certified the isolator reports
//! failure and the caller switches to exact rational arithmetic.

use smallvec::{SmallVec, smallvec};

use crate::stats::RootStats;
use crate::univariate::gamma;

/// Coefficients stay on the stack up to degree 24 (the renderer's sextics and Bézier-patch
/// polynomials of degree 18 included).
const INLINE: usize = 25;
type Coeffs = SmallVec<[f64; INLINE]>;

/// Deepest subdivision tried before giving up on `f64`: intervals of relative width 2^-52
/// are a single rounding step of the map `a + w·u`, so no sign below that can be certified.
const MAX_DEPTH: u32 = 52;

/// Most subdivisions tried in one query before giving up on `f64` (a polynomial with many
/// clustered roots is cheaper to isolate exactly than to subdivide for ever).
const MAX_SPLITS: u32 = 4000;

/// 2^-1074, the smallest subnormal: the largest absolute error of one rounding that
/// underflows.
const ETA: f64 = f64::from_bits(1);

/// A sub-interval `[u0, u1]` of `[0, 1]` with the Bernstein coefficients of `q` on it.
#[derive(Clone, Debug)]
struct Node {
    /// Computed Bernstein coefficients.
    v: Coeffs,
    /// The same computation on absolute values (the error-bound weights).
    m: Coeffs,
    u0: f64,
    u1: f64,
    depth: u32,
}

/// A bracket `(lo, hi)` holding exactly one distinct real root, of odd multiplicity, with
/// certified signs: `p(lo)` has sign `s_lo` and `p(hi)` sign `−s_lo`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Bracket {
    pub(crate) lo: f64,
    pub(crate) hi: f64,
    pub(crate) s_lo: i8,
}

/// The outcome of a certified search.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) enum Search {
    /// No root in the half-open interval `(t_min, t_max]`.
    NoRoot,
    /// The smallest root of `(t_min, t_max]` is the only root in this bracket, and no root
    /// lies in `(t_min, lo]`.
    Found(Bracket),
    /// A sign could not be certified in `f64`; the answer needs exact arithmetic.
    Uncertain,
}

/// Certified Bernstein-basis isolation of the roots of one `f64` polynomial in `(t_min, t_max]`.
#[derive(Debug)]
pub(crate) struct BernsteinIsolator<'p> {
    p: &'p [f64],
    n: usize,
    a: f64,
    w: f64,
    w_exact: bool,
    t_max: f64,
    /// Certified signs of `p(t_min)` and `p(t_max)` (non-zero).
    s_min: i8,
    s_max: i8,
    /// Rounding steps along any path to a top-level coefficient.
    base_ops: u32,
    /// Bound on the accumulated underflow error per rounding step (see [`Self::tiny`]).
    underflow_unit: f64,
    top: Node,
}

impl<'p> BernsteinIsolator<'p> {
    /// Sets up the search on `(t_min, t_max]` for the polynomial with coefficients `p` (lowest
    /// first, finite, degree ≥ 1, last one non-zero). The caller has certified the signs
    /// `s_min` of `p(t_min)` and `s_max` of `p(t_max)` (both non-zero) and checked
    /// `t_min < t_max`, both finite. `None` when the map to `[0, 1]` overflows.
    pub(crate) fn new(p: &'p [f64], t_min: f64, t_max: f64, s_min: i8, s_max: i8) -> Option<Self> {
        let n = p.len() - 1;
        let (w, w_exact) = diff_rounded_up(t_max, t_min);
        if !w.is_finite() {
            return None;
        }
        let a = t_min;
        // Step 1: Taylor shift and scaling, q(u) = p(a + w·u), by Horner's rule on
        // polynomials: out ← out·(a + w·u) + c_k. Per step a path meets one product and at
        // most two sums: 3 roundings per step.
        let mut v: Coeffs = smallvec![0.0; n + 1];
        let mut m: Coeffs = smallvec![0.0; n + 1];
        v[0] = p[n];
        m[0] = p[n].abs();
        let (aa, aw) = (a.abs(), w.abs());
        for k in (0..n).rev() {
            let len = n - k;
            for i in (1..=len).rev() {
                v[i] = v[i] * a + v[i - 1] * w;
                m[i] = m[i] * aa + m[i - 1] * aw;
            }
            v[0] = v[0] * a + p[k];
            m[0] = m[0] * aa + p[k].abs();
        }
        // Step 2: power basis on [0, 1] → Bernstein basis: bᵢ = Σ_{j≤i} C(i,j)/C(n,j)·q_j,
        // as a division by C(n,j) (two roundings: the binomial and the quotient) followed by
        // n passes of neighbour sums (one rounding each).
        let binom_ops = binomial_row_into(n, &mut m, &mut v);
        for r in 1..=n {
            for i in (r..=n).rev() {
                v[i] += v[i - 1];
                m[i] += m[i - 1];
            }
        }
        let base_ops = 3 * n as u32 + binom_ops + n as u32;
        // Underflow: each rounding may add up to ETA absolutely; later steps multiply such an
        // error by at most (|a| + |w|) per Horner step and by at most n + 1 in the basis
        // change (de Casteljau only averages). Each output depends on at most (n+1)² roundings
        // per stage.
        let amp = (1.0 + aa + aw).powi(n as i32) * (n + 1) as f64;
        let underflow_unit = ETA * amp * ((n + 1) * (n + 1)) as f64;
        Some(BernsteinIsolator {
            p,
            n,
            a,
            w,
            w_exact,
            t_max,
            s_min,
            s_max,
            base_ops,
            underflow_unit,
            top: Node {
                v,
                m,
                u0: 0.0,
                u1: 1.0,
                depth: 0,
            },
        })
    }

    /// Rounding steps along any path to a coefficient of a node at this depth (each
    /// de Casteljau halving adds one addition per level, `n` levels; the halving is exact).
    fn ops(&self, depth: u32) -> u32 {
        self.base_ops + depth * self.n as u32
    }

    /// The absolute underflow allowance of a node at this depth.
    fn tiny(&self, depth: u32) -> f64 {
        self.underflow_unit * f64::from(4 + depth)
    }

    /// Certified signs of the node's coefficients (0 = not certain). The end coefficients of
    /// nodes touching `u = 0` (and `u = 1` when `w` is exact) are the values `p(t_min)`,
    /// `p(t_max)`, whose signs the caller certified directly.
    fn classify(&self, node: &Node) -> Class {
        let k = self.ops(node.depth) as usize;
        let g = gamma(k);
        // γ(k)·m*/… with m* ≤ m̂/(1−γ(k)); the factor (1 + 8ε) covers the roundings of this
        // bound itself.
        let fac = g / (1.0 - g) * (1.0 + 8.0 * f64::EPSILON);
        let tiny = self.tiny(node.depth);
        let mut last = 0i8;
        let mut changes = 0u32;
        let mut uncertain = false;
        for i in 0..=self.n {
            let s = if i == 0 && node.u0 == 0.0 {
                self.s_min
            } else if i == self.n && node.u1 == 1.0 && self.w_exact {
                self.s_max
            } else {
                let err = fac * node.m[i] + tiny;
                let x = node.v[i];
                if x > err {
                    1
                } else if -x > err {
                    -1
                } else {
                    0
                }
            };
            if s == 0 {
                uncertain = true;
                continue;
            }
            if last != 0 && s != last {
                changes += 1;
            }
            last = s;
        }
        match (uncertain, changes) {
            (false, 0) => Class::Empty,
            (false, 1) => Class::One,
            _ => Class::Split,
        }
    }

    /// Halves a node with de Casteljau's algorithm at `u = 1/2`: returns (left, right).
    fn split(&self, node: Node) -> (Node, Node) {
        let n = self.n;
        let mut lv = node.v.clone();
        let mut lm = node.m.clone();
        let mut rv = node.v;
        let mut rm = node.m;
        for r in 1..=n {
            for i in 0..=(n - r) {
                rv[i] = (rv[i] + rv[i + 1]) * 0.5;
                rm[i] = (rm[i] + rm[i + 1]) * 0.5;
            }
            lv[r] = rv[0];
            lm[r] = rm[0];
        }
        let mid = 0.5 * (node.u0 + node.u1);
        let depth = node.depth + 1;
        (
            Node {
                v: lv,
                m: lm,
                u0: node.u0,
                u1: mid,
                depth,
            },
            Node {
                v: rv,
                m: rm,
                u0: mid,
                u1: node.u1,
                depth,
            },
        )
    }

    /// Certified bracket in `t` for a node holding exactly one root, or `Err(())` when the
    /// root sits within a rounding step of the node's ends. `Ok(None)` when the root lies
    /// beyond `t_max` (possible only when `w` was rounded up).
    ///
    /// The node ends `a + w·u` are not `f64` numbers in general. The bracket ends are moved
    /// one step *inwards* from the correctly rounded `fma(w, u, a)`, so they lie strictly
    /// inside the node, where there is exactly one root; the signs of `p` there are then
    /// checked with [`horner_bounded`] to prove the root was not skipped.
    fn bracket(&self, node: &Node) -> Result<Option<Bracket>, ()> {
        let s_lo = if node.u0 == 0.0 {
            self.s_min
        } else if node.v[0] > 0.0 {
            1
        } else {
            -1
        };
        let lo = if node.u0 == 0.0 {
            self.a
        } else {
            w_u_a(self.w, node.u0, self.a).next_up()
        };
        if lo >= self.t_max {
            // The node starts within a rounding step of t_max: its root may or may not be
            // ≤ t_max, and only exact arithmetic can tell.
            return Err(());
        }
        let mut hi = if node.u1 == 1.0 && self.w_exact {
            self.t_max
        } else {
            w_u_a(self.w, node.u1, self.a).next_down()
        };
        if node.u0 != 0.0 && certified_sign(self.p, lo) != s_lo {
            return Err(());
        }
        if hi > self.t_max {
            // The single root of the node is ≤ t_max iff p changes sign on (lo, t_max].
            if self.s_max == s_lo {
                return Ok(None);
            }
            hi = self.t_max;
        } else if !(node.u1 == 1.0 && self.w_exact) && certified_sign(self.p, hi) != -s_lo {
            return Err(());
        }
        if lo >= hi {
            return Err(());
        }
        Ok(Some(Bracket { lo, hi, s_lo }))
    }

    /// The smallest root in `(t_min, t_max]`: depth-first, left half first, stopping at the
    /// first node that holds exactly one root.
    pub(crate) fn first_root(&self, stats: &mut RootStats) -> Search {
        let mut stack: SmallVec<[Node; 8]> = SmallVec::new();
        stack.push(self.top.clone());
        let mut splits = 0u32;
        while let Some(node) = stack.pop() {
            if node.u0 > 0.0 && w_u_a(self.w, node.u0, self.a) > self.t_max {
                // Entirely beyond t_max (w rounded up), and everything left of it is empty.
                return Search::NoRoot;
            }
            match self.classify(&node) {
                Class::Empty => {}
                Class::One => {
                    return match self.bracket(&node) {
                        Ok(Some(b)) => Search::Found(b),
                        Ok(None) => Search::NoRoot,
                        Err(()) => Search::Uncertain,
                    };
                }
                Class::Split => {
                    if node.depth >= MAX_DEPTH || splits >= MAX_SPLITS {
                        return Search::Uncertain;
                    }
                    splits += 1;
                    stats.subdivisions += 1;
                    let (l, r) = self.split(node);
                    stack.push(r);
                    stack.push(l);
                }
            }
        }
        Search::NoRoot
    }

    /// Every root in `(t_min, t_max]`, as sorted disjoint brackets; `None` when a sign could
    /// not be certified.
    pub(crate) fn all_roots(&self, stats: &mut RootStats) -> Option<Vec<Bracket>> {
        let mut out = Vec::new();
        let mut stack: SmallVec<[Node; 8]> = SmallVec::new();
        stack.push(self.top.clone());
        let mut splits = 0u32;
        while let Some(node) = stack.pop() {
            if node.u0 > 0.0 && w_u_a(self.w, node.u0, self.a) > self.t_max {
                break;
            }
            match self.classify(&node) {
                Class::Empty => {}
                Class::One => match self.bracket(&node) {
                    Ok(Some(b)) => out.push(b),
                    Ok(None) => break,
                    Err(()) => return None,
                },
                Class::Split => {
                    if node.depth >= MAX_DEPTH || splits >= MAX_SPLITS {
                        return None;
                    }
                    splits += 1;
                    stats.subdivisions += 1;
                    let (l, r) = self.split(node);
                    stack.push(r);
                    stack.push(l);
                }
            }
        }
        Some(out)
    }
}

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Class {
    Empty,
    One,
    Split,
}

/// `t = a + w·u` rounded once (fused multiply-add), so within half an ulp of the exact value.
fn w_u_a(w: f64, u: f64, a: f64) -> f64 {
    w.mul_add(u, a)
}

/// `hi − lo` rounded up, and whether the subtraction was exact (Knuth's TwoSum gives the
/// rounding error exactly).
fn diff_rounded_up(hi: f64, lo: f64) -> (f64, bool) {
    let s = hi - lo;
    let bb = s - hi;
    let err = (hi - (s - bb)) + (-lo - bb);
    if !s.is_finite() {
        (s, false)
    } else if err > 0.0 {
        (s.next_up(), false)
    } else {
        (s, err == 0.0)
    }
}

/// Divides `v[j]` (and `m[j]`) by `C(n, j)`; returns the roundings this adds on any path.
fn binomial_row_into(n: usize, m: &mut [f64], v: &mut [f64]) -> u32 {
    if n <= 60 {
        // Exact in u128 (C(60, 30) ≈ 1.2e17; the running product C(n, j)·(n − j) < 2^70).
        let mut c: u128 = 1;
        for j in 0..=n {
            if j > 0 {
                c = c * (n - j + 1) as u128 / j as u128;
            }
            let cf = c as f64;
            v[j] /= cf;
            m[j] /= cf;
        }
        2
    } else {
        // Multiplicative recurrence in f64: two roundings per step for the binomial.
        let mut c = 1.0f64;
        for j in 0..=n {
            if j > 0 {
                c = c * (n - j + 1) as f64 / j as f64;
            }
            v[j] /= c;
            m[j] /= c;
        }
        2 * n as u32 + 1
    }
}

/// `p(x)` by Horner's rule with a rigorous absolute error bound, as in
/// [`Poly::eval_with_error`](crate::Poly::eval_with_error), plus an underflow allowance that
/// follows the growth of `|x|^i`.
///
/// # Accuracy
/// `|value − p(x)| ≤ err` for the stored coefficients and `x`: `err = γ(2n)·S/(1 − γ(2n))·(1 +
/// 8ε) + ETA·Σ|x|^i`, `S = Σ|cᵢ||x|^i` computed alongside (Higham eq. 5.3). Needs finite input.
#[inline]
pub(crate) fn horner_bounded(c: &[f64], x: f64) -> (f64, f64) {
    let ax = x.abs();
    let mut v = 0.0;
    let mut s = 0.0;
    let mut z = 0.0;
    for &ci in c.iter().rev() {
        v = v * x + ci;
        s = s * ax + ci.abs();
        z = z * ax + 1.0;
    }
    let g = gamma(2 * c.len());
    let err = g / (1.0 - g) * s * (1.0 + 8.0 * f64::EPSILON) + 2.0 * ETA * z;
    (v, err)
}

/// The certified sign of `p(x)` (0 when not certain).
#[inline]
pub(crate) fn certified_sign(c: &[f64], x: f64) -> i8 {
    let (v, err) = horner_bounded(c, x);
    if v > err {
        1
    } else if -v > err {
        -1
    } else {
        0
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scalar::Rat;
    use crate::univariate::Poly;
    use num_traits::Signed;

    fn exact_bernstein(p: &Poly<f64>, a: f64, w: f64) -> Vec<Rat> {
        // q(u) = p(a + w u) exactly, then the exact basis change.
        let pr = p.to_rat().unwrap();
        let q = pr.compose_affine(&Rat::from_float(a).unwrap(), &Rat::from_float(w).unwrap());
        let n = p.degree();
        let binom = |n: usize, k: usize| -> Rat {
            let mut c = Rat::from_integer(1.into());
            for j in 0..k {
                c = c * Rat::from_integer(((n - j) as i64).into())
                    / Rat::from_integer(((j + 1) as i64).into());
            }
            c
        };
        (0..=n)
            .map(|i| {
                (0..=i).fold(Rat::from_integer(0.into()), |acc, j| {
                    acc + binom(i, j) / binom(n, j) * q.coeff(j)
                })
            })
            .collect()
    }

    #[test]
    fn bernstein_error_bound_contains_exact_coefficients() {
        let p = Poly::new(vec![-1.3e3, 2.7, 0.41, -7.9, 1.0, 0.031]);
        let iso = BernsteinIsolator::new(p.coeffs(), -3.7, 11.3, 1, 1).unwrap();
        let exact = exact_bernstein(&p, iso.a, iso.w);
        let g = gamma(iso.ops(0) as usize);
        for (i, e) in exact.iter().enumerate() {
            let err = g / (1.0 - g) * iso.top.m[i];
            let diff = (Rat::from_float(iso.top.v[i]).unwrap() - e).abs();
            assert!(
                diff <= Rat::from_float(err).unwrap(),
                "coefficient {i}: computed {} exact {} err bound {err}",
                iso.top.v[i],
                crate::scalar::rat_to_f64(e)
            );
        }
        // The bound is not vacuous: well below the coefficient sizes.
        assert!(
            g * iso.top.m[2] < 1e-10 * iso.top.m[2].max(1.0),
            "bound is tight"
        );
    }

    #[test]
    fn subtraction_rounded_up() {
        let (w, exact) = diff_rounded_up(1.0, 0.25);
        assert_eq!((w, exact), (0.75, true), "exact difference");
        let (w, exact) = diff_rounded_up(1.0, 1e-30);
        assert!(
            !exact && w >= 1.0,
            "1 − 1e-30 rounds to 1 and is bumped up: {w}"
        );
    }

    #[test]
    fn horner_bound_contains_exact_value() {
        let p = Poly::<f64>::from_roots(&[0.1, 0.2, 0.3, 0.4]);
        let pr = p.to_rat().unwrap();
        for x in [0.1, 0.15, 0.3000001, 2.0, -5.0] {
            let (v, err) = horner_bounded(p.coeffs(), x);
            let exact = pr.eval(&Rat::from_float(x).unwrap());
            let diff = (Rat::from_float(v).unwrap() - exact).abs();
            assert!(
                diff <= Rat::from_float(err).unwrap(),
                "x = {x}: v {v} err {err}"
            );
        }
    }
}

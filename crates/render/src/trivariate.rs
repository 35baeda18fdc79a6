//! [`Poly3`]: sparse trivariate polynomials `F(x, y, z)` with `f64` coefficients, and their
//! restriction to a line, `t ↦ F(o + t·d)`, as a univariate [`poly::Poly`].
//!
//! This is the `F` of Stam's eq. 3.2, `F = Σ a_ijk x^i y^j z^k`. Restricting it to a ray
//! (Stam §3.2.1, eq. 3.7–3.8, done there by a coordinate change) is the one step every implicit
//! surface shares; see `paper-notes/implicit-surfaces.md`.

use std::fmt;
use std::ops::{Add, Mul, Neg, Sub};

use glam::DVec3;
use num_bigint::BigInt;
use num_traits::{One, Zero};
use poly::{Dd, Poly, QPoly, Rat};

/// One monomial `coeff · x^e[0] · y^e[1] · z^e[2]`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Term3 {
    /// The coefficient, non-zero in a normalised [`Poly3`].
    pub coeff: f64,
    /// Exponents of `x`, `y`, `z`.
    pub exps: [u32; 3],
}

impl Term3 {
    /// Total degree `e[0] + e[1] + e[2]`.
    pub fn degree(&self) -> u32 {
        self.exps.iter().sum()
    }
}

/// A sparse trivariate polynomial with `f64` coefficients.
///
/// Invariant (kept by every constructor and operation): terms are sorted by exponent triple
/// (lexicographic on `(x, y, z)` exponents), no two terms share an exponent triple, and no
/// coefficient is exactly zero. The zero polynomial has no terms.
///
/// # Examples
/// ```
/// use render::Poly3;
/// use glam::DVec3;
/// // Stam's torus (Annexe B `Polynomial`): (x²+y²−1)(x²+y²−9) + 15z².
/// let (x, y, z) = (Poly3::x(), Poly3::y(), Poly3::z());
/// let r2 = &(&x * &x) + &(&y * &y);
/// let f = &(&(&r2 - &Poly3::constant(1.0)) * &(&r2 - &Poly3::constant(9.0)))
///     + &(&(&z * &z) * 15.0);
/// assert_eq!(f.degree(), 4);
/// assert_eq!(f.eval(DVec3::new(1.0, 0.0, 0.0)), 0.0);
/// // Along the x axis from the origin: (t² − 1)(t² − 9).
/// let line = f.restrict_to_line(DVec3::ZERO, DVec3::X);
/// assert_eq!(line.coeffs(), &[9.0, 0.0, -10.0, 0.0, 1.0]);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
#[derive(Clone, Debug, PartialEq, Default)]
pub struct Poly3 {
    terms: Vec<Term3>,
}

impl Poly3 {
    /// Builds `Σ coeff · x^i y^j z^k` from `(coeff, [i, j, k])` pairs in any order: equal
    /// exponent triples are summed and zero coefficients dropped.
    pub fn from_terms(terms: impl IntoIterator<Item = (f64, [u32; 3])>) -> Self {
        let mut v: Vec<Term3> = terms
            .into_iter()
            .map(|(coeff, exps)| Term3 { coeff, exps })
            .collect();
        v.sort_by_key(|a| a.exps);
        // Equal exponents merged in place, each run summed left to right (`dedup_by` hands
        // the later term first and the kept one second), without a second vector.
        v.dedup_by(|later, kept| {
            let same = later.exps == kept.exps;
            if same {
                kept.coeff += later.coeff;
            }
            same
        });
        v.retain(|t| t.coeff != 0.0);
        Poly3 { terms: v }
    }

    /// The zero polynomial.
    pub fn zero() -> Self {
        Poly3 { terms: Vec::new() }
    }

    /// The constant `c`.
    pub fn constant(c: f64) -> Self {
        Self::from_terms([(c, [0, 0, 0])])
    }

    /// The variable `x`.
    pub fn x() -> Self {
        Self::from_terms([(1.0, [1, 0, 0])])
    }

    /// The variable `y`.
    pub fn y() -> Self {
        Self::from_terms([(1.0, [0, 1, 0])])
    }

    /// The variable `z`.
    pub fn z() -> Self {
        Self::from_terms([(1.0, [0, 0, 1])])
    }

    /// The terms, sorted by exponent triple, coefficients non-zero.
    pub fn terms(&self) -> &[Term3] {
        &self.terms
    }

    /// True for the zero polynomial.
    pub fn is_zero(&self) -> bool {
        self.terms.is_empty()
    }

    /// True when every coefficient is finite.
    pub fn is_finite(&self) -> bool {
        self.terms.iter().all(|t| t.coeff.is_finite())
    }

    /// Total degree (0 for constants and for the zero polynomial).
    pub fn degree(&self) -> u32 {
        self.terms.iter().map(Term3::degree).max().unwrap_or(0)
    }

    /// Highest exponent of each variable.
    pub fn partial_degrees(&self) -> [u32; 3] {
        let mut d = [0; 3];
        for t in &self.terms {
            for (dk, ek) in d.iter_mut().zip(t.exps) {
                *dk = (*dk).max(ek);
            }
        }
        d
    }

    /// The highest degree in `t` that `F(o + t·d)` can have for any `o` and any `d` whose
    /// non-zero components are those flagged in `moving`: each term `x^i y^j z^k` contributes
    /// the exponents of its moving axes (an axis with `d_k = 0` contributes a constant).
    pub fn restriction_degree_bound(&self, moving: [bool; 3]) -> u32 {
        self.terms
            .iter()
            .map(|t| (0..3).filter(|&k| moving[k]).map(|k| t.exps[k]).sum())
            .max()
            .unwrap_or(0)
    }

    /// [`Poly3::restriction_degree_bound`] for every set of moving axes at once, indexed by
    /// their bits (x: 1, y: 2, z: 4): one pass over the terms instead of eight (a prepared
    /// surface keeps all eight; with this pass `Implicit::new` fell from ≈ 1 920 to ≈ 1 480
    /// instructions a sphere of the 66 430-sphere SPD scene's set-up; issue 12).
    pub fn restriction_degree_bounds(&self) -> [u32; 8] {
        let mut bounds = [0u32; 8];
        for t in &self.terms {
            let [i, j, k] = t.exps;
            // The term's degree in the axes of each set, by the bits of its index.
            let degrees = [0, i, j, i + j, k, i + k, j + k, i + j + k];
            for (b, d) in bounds.iter_mut().zip(degrees) {
                *b = (*b).max(d);
            }
        }
        bounds
    }

    /// `self^k` by repeated squaring (`self^0 = 1`).
    pub fn pow(&self, k: u32) -> Self {
        self.checked_pow(k, usize::MAX)
            .expect("no limit on the term products")
    }

    /// [`Poly3::pow`], or `None` as soon as one of its multiplications would take more than
    /// `max_products` term products (see [`Poly3::checked_mul`]).
    pub fn checked_pow(&self, k: u32, max_products: usize) -> Option<Self> {
        let mut result = Poly3::constant(1.0);
        let mut base = self.clone();
        let mut k = k;
        while k > 0 {
            if k & 1 == 1 {
                result = result.checked_mul(&base, max_products)?;
            }
            k >>= 1;
            if k > 0 {
                base = base.checked_mul(&base, max_products)?;
            }
        }
        Some(result)
    }

    /// `self · rhs`, or `None` when that takes more than `max_products` term products
    /// (`terms(self) · terms(rhs)`), checked before any work.
    ///
    /// The products are summed into a dense array over the exponent box of the result, in the
    /// order `self`'s terms × `rhs`'s terms, so each coefficient is the same left-to-right
    /// sum as a sort-and-merge would give; memory is the box (at most `(N + 1)³` for total
    /// degree `N`), not the number of products.
    ///
    /// # Complexity
    /// `O(terms(self)·terms(rhs) + box)`.
    pub fn checked_mul(&self, rhs: &Poly3, max_products: usize) -> Option<Self> {
        if self.terms.len().checked_mul(rhs.terms.len())? > max_products {
            return None;
        }
        if self.is_zero() || rhs.is_zero() {
            return Some(Poly3::zero());
        }
        let (da, db) = (self.partial_degrees(), rhs.partial_degrees());
        let side = [0, 1, 2].map(|k| (da[k] + db[k]) as usize + 1);
        let index =
            |e: [u32; 3]| (e[0] as usize * side[1] + e[1] as usize) * side[2] + e[2] as usize;
        let mut dense = vec![0.0f64; side[0] * side[1] * side[2]];
        for a in &self.terms {
            for b in &rhs.terms {
                let e = [
                    a.exps[0] + b.exps[0],
                    a.exps[1] + b.exps[1],
                    a.exps[2] + b.exps[2],
                ];
                dense[index(e)] += a.coeff * b.coeff;
            }
        }
        let mut terms = Vec::new();
        for (n, &coeff) in dense.iter().enumerate() {
            if coeff != 0.0 {
                let z = n % side[2];
                let y = (n / side[2]) % side[1];
                let x = n / (side[1] * side[2]);
                terms.push(Term3 {
                    coeff,
                    exps: [x as u32, y as u32, z as u32],
                });
            }
        }
        Some(Poly3 { terms })
    }

    /// `∂F/∂x_axis` (`axis` 0, 1, 2 for x, y, z).
    ///
    /// # Panics
    /// If `axis > 2` (a caller bug).
    pub fn derivative(&self, axis: usize) -> Self {
        assert!(axis < 3, "axis must be 0, 1 or 2, got {axis}");
        Self::from_terms(self.terms.iter().filter(|t| t.exps[axis] > 0).map(|t| {
            let mut e = t.exps;
            e[axis] -= 1;
            (t.coeff * f64::from(t.exps[axis]), e)
        }))
    }

    /// The gradient `∇F` as three polynomials (Stam eq. 3.24).
    pub fn gradient_polys(&self) -> [Poly3; 3] {
        [self.derivative(0), self.derivative(1), self.derivative(2)]
    }

    /// `F(p)`, term by term with `powi`.
    ///
    /// # Accuracy
    /// Each term rounds a few times; the absolute error is at most about
    /// `γ(d + 2)·Σ|a_ijk||x|^i|y|^j|z|^k` for total degree `d` (see [`Poly3::eval_abs`] for
    /// the sum).
    pub fn eval(&self, p: DVec3) -> f64 {
        self.terms
            .iter()
            .map(|t| {
                t.coeff
                    * p.x.powi(t.exps[0] as i32)
                    * p.y.powi(t.exps[1] as i32)
                    * p.z.powi(t.exps[2] as i32)
            })
            .sum()
    }

    /// `Σ|a_ijk||x|^i|y|^j|z|^k`: the scale against which `F(p)` is negligible or not.
    pub fn eval_abs(&self, p: DVec3) -> f64 {
        self.terms
            .iter()
            .map(|t| {
                t.coeff.abs()
                    * p.x.abs().powi(t.exps[0] as i32)
                    * p.y.abs().powi(t.exps[1] as i32)
                    * p.z.abs().powi(t.exps[2] as i32)
            })
            .sum()
    }

    /// `F(p)`, `∇F(p)` and the matching absolute sums in one pass over the terms, with
    /// power tables instead of `powi` — what shading needs at an accepted hit.
    ///
    /// # Accuracy
    /// With `S = Σ|a_ijk||x|^i|y|^j|z|^k` (returned as `f_abs`), the value's absolute error is
    /// at most `γ(d + 3)·S` for total degree `d` (each term is a product of at most `d + 1`
    /// factors, then summed); likewise each gradient component against `grad_abs`.
    pub fn eval_grad(&self, p: DVec3) -> Eval3 {
        let deg = self.partial_degrees();
        let width = deg.iter().max().map_or(0, |&d| d as usize) + 1;
        if width <= STACK_POWERS {
            let mut tables = [[0.0f64; STACK_POWERS]; 6];
            let mut rows = tables.each_mut().map(|t| &mut t[..]);
            self.eval_grad_with(p, deg, &mut rows)
        } else {
            // Degree-64 and higher surfaces: one allocation per shaded hit.
            let mut heap = vec![0.0f64; 6 * width];
            let mut chunks = heap.chunks_mut(width);
            let mut rows: [&mut [f64]; 6] =
                std::array::from_fn(|_| chunks.next().expect("six rows of the table"));
            self.eval_grad_with(p, deg, &mut rows)
        }
    }

    /// [`Poly3::eval_grad`] with power tables `tables[k][e] = p_k^e`, `tables[k + 3][e] =
    /// |p_k|^e`, each row at least `partial_degrees[k] + 1` long.
    fn eval_grad_with(&self, p: DVec3, deg: [u32; 3], tables: &mut [&mut [f64]; 6]) -> Eval3 {
        let mut out = Eval3::default();
        for k in 0..3 {
            let (v, a) = (p[k], p[k].abs());
            tables[k][0] = 1.0;
            tables[k + 3][0] = 1.0;
            for e in 1..=deg[k] as usize {
                tables[k][e] = tables[k][e - 1] * v;
                tables[k + 3][e] = tables[k + 3][e - 1] * a;
            }
        }
        for t in &self.terms {
            let [i, j, k] = t.exps.map(|e| e as usize);
            let (xi, yj, zk) = (tables[0][i], tables[1][j], tables[2][k]);
            let (axi, ayj, azk) = (tables[3][i], tables[4][j], tables[5][k]);
            let c = t.coeff;
            let ac = c.abs();
            out.f += c * xi * yj * zk;
            out.f_abs += ac * axi * ayj * azk;
            if i > 0 {
                let e = i as f64;
                out.grad.x += c * e * tables[0][i - 1] * yj * zk;
                out.grad_abs.x += ac * e * tables[3][i - 1] * ayj * azk;
            }
            if j > 0 {
                let e = j as f64;
                out.grad.y += c * e * xi * tables[1][j - 1] * zk;
                out.grad_abs.y += ac * e * axi * tables[4][j - 1] * azk;
            }
            if k > 0 {
                let e = k as f64;
                out.grad.z += c * e * xi * yj * tables[2][k - 1];
                out.grad_abs.z += ac * e * axi * ayj * tables[5][k - 1];
            }
        }
        out
    }

    /// `G(x, y, z) = F(A·(x, y, z) + b)` for a 3×3 matrix `A` (columns) and offset `b`:
    /// the same surface seen through an affine change of coordinates.
    pub fn compose_affine(&self, a: glam::DMat3, b: DVec3) -> Self {
        let lin = |row: usize| {
            let r = a.row(row);
            &(&(&Poly3::x() * r.x) + &(&Poly3::y() * r.y))
                + &(&(&Poly3::z() * r.z) + &Poly3::constant(b[row]))
        };
        let subs = [lin(0), lin(1), lin(2)];
        let mut pows: [Vec<Poly3>; 3] = Default::default();
        let deg = self.partial_degrees();
        for k in 0..3 {
            pows[k].push(Poly3::constant(1.0));
            for e in 1..=deg[k] as usize {
                let next = &pows[k][e - 1] * &subs[k];
                pows[k].push(next);
            }
        }
        let mut out = Poly3::zero();
        for t in &self.terms {
            let m = &(&pows[0][t.exps[0] as usize] * &pows[1][t.exps[1] as usize])
                * &pows[2][t.exps[2] as usize];
            out = &out + &(&m * t.coeff);
        }
        out
    }

    /// The restriction `t ↦ F(o + t·d)` as a univariate polynomial, coefficients low → high
    /// (Stam eq. 3.7–3.8). Allocates; the tracer uses [`Poly3::restrict_into`].
    pub fn restrict_to_line(&self, o: DVec3, d: DVec3) -> Poly<f64> {
        let mut scratch = RestrictScratch::default();
        let mut out = Vec::new();
        self.restrict_into(o, d, &mut scratch, &mut out);
        Poly::new(out)
    }

    /// [`Poly3::restrict_to_line`] into a caller-owned buffer (cleared first; trailing zeros
    /// are not trimmed), reusing `scratch` so the hot loop does not allocate.
    ///
    /// # Accuracy
    /// Each coefficient is a sum of products of `a_ijk` with binomial terms
    /// `C(e, m)·o^(e−m)·d^m`; the rounding error of coefficient `c_m` is a few `γ(d + 3)` times
    /// the same sum taken in absolute values. It is small when `o` is near the surface, which is
    /// why callers move the ray origin to the bounding-box entry first
    /// (`paper-notes/implicit-surfaces.md` §2).
    ///
    /// # Complexity
    /// `O(g·d + p·d²)` for `g` distinct `(i, j)` exponent pairs, `p` distinct `x` exponents
    /// and total degree `d` (`O(n·d²)` at worst for `n` terms).
    pub fn restrict_into(
        &self,
        o: DVec3,
        d: DVec3,
        scratch: &mut RestrictScratch,
        out: &mut Vec<f64>,
    ) {
        self.restrict_generic(o.to_array(), d.to_array(), scratch, out);
    }

    /// [`Poly3::restrict_into`] in double-double arithmetic, from a restriction point given as
    /// double-doubles: the same program, each operation within [`poly::DD_UNIT`] instead of
    /// `u`, so the coefficients' error is `γ_dd(K)·c̃ₘ` with the same `K`
    /// ([`Poly3::restriction_rounding_steps`]) — the renderer's tier between the `f64`
    /// restriction and the exact one (`paper-notes/implicit-surfaces.md` §6).
    pub fn restrict_dd_into(
        &self,
        o: [Dd; 3],
        d: DVec3,
        scratch: &mut RestrictScratch<Dd>,
        out: &mut Vec<Dd>,
    ) {
        self.restrict_generic(o, d.to_array(), scratch, out);
    }

    /// The restriction program of [`Poly3::restrict_into`] over `T` (`f64` or [`Dd`]).
    fn restrict_generic<T: RestrictNum>(
        &self,
        o: [T; 3],
        d: [f64; 3],
        scratch: &mut RestrictScratch<T>,
        out: &mut Vec<T>,
    ) {
        let deg = self.partial_degrees();
        let total = self.degree() as usize;
        out.clear();
        out.resize(total + 1, T::ZERO);
        // Power tables: row e of axis k holds the coefficients of (o_k + d_k t)^e, stored
        // flat at offset e(e+1)/2 (row e has e + 1 entries).
        for k in 0..3 {
            linear_powers(o[k], d[k], deg[k] as usize, &mut scratch.powers[k]);
        }
        // Group the sorted terms by x exponent: for each i, the y and z parts
        // are summed into Y_i(t) = Σ_j (o_y + d_y t)^j · Z_ij(t), with Z_ij(t) =
        // Σ_k a_ijk (o_z + d_z t)^k; then F(t) = Σ_i (o_x + d_x t)^i · Y_i(t). Multiplying by
        // the x row once per i (not once per (i, j) pair, with a second product by the z
        // sum) costs Σ_(i,j) (j + 1)(k_max + 1) + Σ_i (i + 1)(deg Y_i + 1) products: a third
        // of the former count on a dense degree-64 polynomial (issue 11).
        let terms = &self.terms;
        let zdeg = deg[2] as usize;
        let mut start = 0;
        while start < terms.len() {
            let i = terms[start].exps[0];
            scratch.ysum.clear();
            scratch.ysum.resize(total + 1 - i as usize, T::ZERO);
            let mut ymax = 0;
            while start < terms.len() && terms[start].exps[0] == i {
                let j = terms[start].exps[1];
                scratch.zsum.clear();
                scratch.zsum.resize(zdeg + 1, T::ZERO);
                let mut zmax = 0;
                while start < terms.len() && terms[start].exps[0] == i && terms[start].exps[1] == j
                {
                    let t = terms[start];
                    let zr = row(&scratch.powers[2], t.exps[2]);
                    for (s, c) in scratch.zsum.iter_mut().zip(zr) {
                        *s = s.add(c.mul_f(t.coeff));
                    }
                    zmax = zmax.max(t.exps[2] as usize);
                    start += 1;
                }
                let yr = row(&scratch.powers[1], j);
                for (a, yb) in yr.iter().enumerate() {
                    for (b, zc) in scratch.zsum[..=zmax].iter().enumerate() {
                        scratch.ysum[a + b] = scratch.ysum[a + b].add(yb.mul(*zc));
                    }
                }
                ymax = ymax.max(j as usize + zmax);
            }
            let xr = row(&scratch.powers[0], i);
            for (a, xa) in xr.iter().enumerate() {
                for (b, yb) in scratch.ysum[..=ymax].iter().enumerate() {
                    out[a + b] = out[a + b].add(xa.mul(*yb));
                }
            }
        }
    }

    /// `K`: the most roundings on any path of [`Poly3::restrict_into`] from the stored
    /// coefficients and the ray's `o`, `d` to one restricted coefficient, so that (Higham's
    /// standard model, §3.1) each computed coefficient `ĉₘ` satisfies
    /// `|ĉₘ − cₘ| ≤ γ(K)·c̃ₘ` with `c̃ₘ` the same program run on absolute values: the
    /// coefficient of `tᵐ` in `F_abs(|o| + t|d|)`, `F_abs` being `F` with absolute-value
    /// coefficients (`paper-notes/implicit-surfaces.md` §6).
    ///
    /// The count: a power row `(o + d t)^e` takes two roundings per level (a product and a
    /// sum), `2e`; the products `a·z`, `y·z`, `x·y` one each; and a sum of `n` terms computed
    /// left to right puts its first term through `n − 1` additions. The sums are the `z`
    /// sums (at most the size of an `(i, j)` group), the `y` sums (`Σ_j (j + 1)` over a
    /// group of `x` exponent `i`) and the output sums (`Σ_i (i + 1)`), so
    /// `K = 2N + 3 + Z + Y + X`.
    pub fn restriction_rounding_steps(&self) -> u32 {
        let (mut z_max, mut y_max, mut x_sum) = (0u32, 0u32, 0u32);
        let terms = &self.terms;
        let mut start = 0;
        while start < terms.len() {
            let i = terms[start].exps[0];
            let mut y_sum = 0;
            while start < terms.len() && terms[start].exps[0] == i {
                let j = terms[start].exps[1];
                let mut group = 0;
                while start < terms.len() && terms[start].exps[0] == i && terms[start].exps[1] == j
                {
                    group += 1;
                    start += 1;
                }
                z_max = z_max.max(group);
                y_sum += j + 1;
            }
            y_max = y_max.max(y_sum);
            x_sum += i + 1;
        }
        2 * self.degree() + 3 + z_max + y_max + x_sum
    }

    /// `C` of the restriction's underflow term: `Σₘ |ĉₘ − cₘ|·Rᵐ` exceeds Higham's relative
    /// bound `γ(K)·G` by at most `C·(1 + R + Y)^N` (`Y` the largest component of
    /// `|o| + R|d|`), covering every product of [`Poly3::restrict_into`] (and of
    /// [`Poly3::eval_abs_upper`], and of the restriction point `o + t0·d`) that lands in the
    /// subnormal range, where a rounding errs by up to `η = 2⁻¹⁰⁷⁴` absolutely, not
    /// relatively (`paper-notes/implicit-surfaces.md` §6, underflow).
    ///
    /// Each such error is carried to the output by later products with power-row entries
    /// (`≤ (|o_k| + R|d_k|)^e`), with a coefficient (`≤ A = max|a|`) and with the row's own
    /// power of `t` (`≤ Rᵐ`), and summed over at most `T` terms: at most
    /// `max(1, A)·T·(1 + R + Y)^N` in the `R`-weighted sum. The products number at most
    /// `P = (N + 1)(N + 2)(3 + 3T)` (power tables `3(N + 1)(N + 2)`, the `a·z`, `y·z` and
    /// `x·y` products `≤ T(N + 1) + 2T(N + 1)²`), plus `N` for the restriction point's three
    /// roundings as seen through a degree-`N` polynomial; the factor 4 covers the later
    /// relative roundings of each error (`(1 + u)^K ≤ 2`) and the rounding of the power.
    pub fn restriction_underflow_weight(&self) -> f64 {
        let n = f64::from(self.degree());
        let t = self.terms.len() as f64;
        let a = self.terms.iter().fold(1.0f64, |m, t| m.max(t.coeff.abs()));
        let products = (n + 1.0) * (n + 2.0) * (3.0 + 3.0 * t) + n;
        4.0 * f64::from_bits(1) * products * t * a
    }

    /// An upper bound on `F_abs(y) = Σ|a_ijk| y_x^i y_y^j y_z^k` for `y ≥ 0` componentwise:
    /// each power by repeated multiplication (`e − 1` roundings), each term three products
    /// more, the sum one rounding per term, and the result inflated by `2γ(N + 3 + terms)`
    /// (`1/(1 − γ) ≤ 1 + 2γ`). `+∞` on overflow.
    pub fn eval_abs_upper(&self, y: DVec3) -> f64 {
        // The powers tabulated for every exponent below `TABLE` before the sum, the three axes
        // side by side (the same products in the same order as computing each power afresh,
        // so the same values): this runs in every slack evaluation, ten times a ray on the
        // degree-20 sheets, where filling the tables lazily inside the sum cost 41
        // instructions a term (`docs/speed.md`, "High-degree surfaces: the slack's
        // evaluation").
        const TABLE: usize = 33;
        let y = y.to_array();
        let mut table = [[1.0f64; TABLE]; 3];
        for e in 1..TABLE {
            for k in 0..3 {
                table[k][e] = table[k][e - 1] * y[k];
            }
        }
        let [tx, ty, tz] = &table;
        let mut sum = 0.0;
        let mut degree = 0;
        for t in &self.terms {
            let [i, j, k] = t.exps.map(|e| e as usize);
            let term = if i.max(j).max(k) < TABLE {
                t.coeff.abs() * tx[i] * ty[j] * tz[k]
            } else {
                let at = |k: usize, e: usize| match table[k].get(e) {
                    Some(&p) => p,
                    None => (0..e).fold(1.0, |p, _| p * y[k]),
                };
                t.coeff.abs() * at(0, i) * at(1, j) * at(2, k)
            };
            sum += term;
            degree = degree.max(i + j + k);
        }
        let steps = degree + 3 + self.terms.len();
        sum * (1.0 + 2.0 * crate::geometry::gamma(steps))
    }

    /// The restriction `t ↦ F(o + t·d)` in exact rational arithmetic, from the stored `f64`
    /// coefficients and the exact `o`, `d`: the reference the rounded restriction is
    /// certified against (`--isolation exact`, and the renderer's fallback when the rounding
    /// bound is too wide to decide a ray).
    ///
    /// # Complexity
    /// Every `f64` is a dyadic rational `m·2^e`, and so is every `o + t0·d` the renderer
    /// passes: with `o_k = O_k/2^E`, `d_k = D_k/2^E` and each coefficient `A/2^F`, the whole
    /// restriction is an integer polynomial over the one denominator `2^(F_max + E·N)`, built
    /// with big-integer products and shifts and normalised once per coefficient at the end
    /// (exact rational arithmetic step by step spent most of its time in gcds: ~5 ms a
    /// Barth ray). Non-dyadic `o`, `d` take the rational path.
    pub fn restrict_exact(&self, o: &[Rat; 3], d: &[Rat; 3]) -> QPoly {
        let dyadic_exp = |r: &Rat| {
            let den = r.denom();
            let k = den.bits().saturating_sub(1);
            (*den == BigInt::one() << k).then_some(k)
        };
        let exps: Option<Vec<u64>> = o.iter().chain(d).map(dyadic_exp).collect();
        let Some(exps) = exps else {
            return self.restrict_rational(o, d);
        };
        let e_max = exps.iter().copied().max().unwrap_or(0);
        let scaled = |r: &Rat, k: u64| r.numer() << (e_max - k) as usize;
        let total = self.degree() as usize;
        let deg = self.partial_degrees();
        // rows[k][e] = (O_k + D_k t)^e with integer coefficients.
        let rows: Vec<Vec<Vec<BigInt>>> = (0..3)
            .map(|k| {
                let line = [scaled(&o[k], exps[k]), scaled(&d[k], exps[k + 3])];
                let mut row = vec![vec![BigInt::one()]];
                for e in 1..=deg[k] as usize {
                    let next = int_mul(&row[e - 1], &line);
                    row.push(next);
                }
                row
            })
            .collect();
        // Coefficients A·2^(−F): F per term; the common scale is F_max.
        let coeffs: Vec<(BigInt, i64)> = self
            .terms
            .iter()
            .map(|t| {
                let (m, e) = f64_mantissa_exp(t.coeff);
                (m, -e)
            })
            .collect();
        let f_max = coeffs.iter().map(|c| c.1).max().unwrap_or(0).max(0);
        let mut acc = vec![BigInt::zero(); total + 1];
        for (t, (a, f)) in self.terms.iter().zip(&coeffs) {
            let [i, j, k] = t.exps.map(|e| e as usize);
            let p = int_mul(&int_mul(&rows[0][i], &rows[1][j]), &rows[2][k]);
            let shift = (f_max - f) as u64 + e_max * (total - t.degree() as usize) as u64;
            for (c, pc) in acc.iter_mut().zip(&p) {
                *c += (a * pc) << shift as usize;
            }
        }
        let scale = -(f_max + (e_max * total as u64) as i64);
        QPoly::new(acc.into_iter().map(|c| dyadic(c, scale)).collect())
    }

    /// [`Poly3::restrict_exact`] step by step in rationals (for non-dyadic `o`, `d`).
    fn restrict_rational(&self, o: &[Rat; 3], d: &[Rat; 3]) -> QPoly {
        let deg = self.partial_degrees();
        let rows: Vec<Vec<QPoly>> = (0..3)
            .map(|k| {
                let line = QPoly::new(vec![o[k].clone(), d[k].clone()]);
                let mut row = vec![QPoly::new(vec![Rat::from_integer(1.into())])];
                for e in 1..=deg[k] as usize {
                    let next = &row[e - 1] * &line;
                    row.push(next);
                }
                row
            })
            .collect();
        let mut out = QPoly::new(vec![]);
        for t in &self.terms {
            let a = poly::rat_from_f64(t.coeff).expect("finite coefficients were checked");
            let m = &(&rows[0][t.exps[0] as usize] * &rows[1][t.exps[1] as usize])
                * &rows[2][t.exps[2] as usize];
            out = &out + &(&m * &QPoly::new(vec![a]));
        }
        out
    }

    /// `c·F`.
    pub fn scale(&self, c: f64) -> Self {
        Self::from_terms(self.terms.iter().map(|t| (t.coeff * c, t.exps)))
    }
}

/// The product of two integer polynomials (coefficients low → high).
fn int_mul(a: &[BigInt], b: &[BigInt]) -> Vec<BigInt> {
    let mut out = vec![BigInt::zero(); a.len() + b.len() - 1];
    for (i, x) in a.iter().enumerate() {
        for (j, y) in b.iter().enumerate() {
            out[i + j] += x * y;
        }
    }
    out
}

/// `m·2^e` as a normalised rational: a power-of-two denominator shares only factors of 2
/// with `m`, so dropping the common trailing zeros normalises it without a gcd (which cost
/// more than the whole restriction, `num-rational`'s `Ratio::new` on 300-bit numbers).
fn dyadic(m: BigInt, e: i64) -> Rat {
    if e >= 0 || m.is_zero() {
        return Rat::from_integer(m << e.max(0) as usize);
    }
    let tz = m.trailing_zeros().unwrap_or(0).min(e.unsigned_abs());
    let k = e.unsigned_abs() - tz;
    Rat::new_raw(m >> tz as usize, BigInt::one() << k as usize)
}

/// `origin + dir·t`, exactly, as a rational (the restriction point of a ray, finite input).
pub(crate) fn exact_point(origin: f64, dir: f64, t: f64) -> Rat {
    let ((mo, eo), (md, ed), (mt, et)) = (
        f64_mantissa_exp(origin),
        f64_mantissa_exp(dir),
        f64_mantissa_exp(t),
    );
    let (mp, ep) = (md * mt, ed + et);
    let e = eo.min(ep);
    dyadic((mo << (eo - e) as usize) + (mp << (ep - e) as usize), e)
}

/// `x = m·2^e` exactly, `m` an integer (finite `x`; [`poly::f64_dyadic`]).
fn f64_mantissa_exp(x: f64) -> (BigInt, i64) {
    let (m, e) = poly::f64_dyadic(x);
    (BigInt::from(m), e)
}

/// Partial degrees below this use stack power tables in [`Poly3::eval_grad`] (higher ones a
/// heap table of the same layout).
const STACK_POWERS: usize = 24;

/// `F`, `∇F` and their absolute-value sums at a point (see [`Poly3::eval_grad`]).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Eval3 {
    /// `F(p)`.
    pub f: f64,
    /// `Σ|a_ijk||x|^i|y|^j|z|^k`, the scale of `F(p)`'s rounding error.
    pub f_abs: f64,
    /// `∇F(p)`.
    pub grad: DVec3,
    /// The same sums for each component of `∇F`.
    pub grad_abs: DVec3,
}

/// Reusable buffers for [`Poly3::restrict_into`] (and, over [`Dd`],
/// [`Poly3::restrict_dd_into`]).
#[derive(Clone, Debug, Default)]
pub struct RestrictScratch<T = f64> {
    powers: [Vec<T>; 3],
    zsum: Vec<T>,
    ysum: Vec<T>,
}

/// The arithmetic of the restriction program: `f64`, and [`Dd`] for the double-double tier.
/// The `f64` operations are the plain ones, so its results are those of writing the program
/// in `f64` directly.
pub(crate) trait RestrictNum: Copy {
    /// 0.
    const ZERO: Self;
    /// 1.
    const ONE: Self;
    /// `self + y`, one rounding.
    fn add(self, y: Self) -> Self;
    /// `self·y`, one rounding.
    fn mul(self, y: Self) -> Self;
    /// `self·y` for an `f64` `y`, one rounding.
    fn mul_f(self, y: f64) -> Self;
}

impl RestrictNum for f64 {
    const ZERO: f64 = 0.0;
    const ONE: f64 = 1.0;
    #[inline]
    fn add(self, y: f64) -> f64 {
        self + y
    }
    #[inline]
    fn mul(self, y: f64) -> f64 {
        self * y
    }
    #[inline]
    fn mul_f(self, y: f64) -> f64 {
        self * y
    }
}

impl RestrictNum for Dd {
    const ZERO: Dd = Dd::ZERO;
    const ONE: Dd = Dd::ONE;
    #[inline]
    fn add(self, y: Dd) -> Dd {
        self + y
    }
    #[inline]
    fn mul(self, y: Dd) -> Dd {
        self * y
    }
    #[inline]
    fn mul_f(self, y: f64) -> Dd {
        self * y
    }
}

/// Row `e` of a power table built by [`linear_powers`].
fn row<T>(table: &[T], e: u32) -> &[T] {
    let e = e as usize;
    let start = e * (e + 1) / 2;
    &table[start..start + e + 1]
}

/// Rows `(o + d·t)^e` for `e = 0..=max`, flat, row `e` at offset `e(e+1)/2`, low → high.
fn linear_powers<T: RestrictNum>(o: T, d: f64, max: usize, table: &mut Vec<T>) {
    // Every entry is written below: only a change of size touches the memory.
    table.resize((max + 1) * (max + 2) / 2, T::ZERO);
    table[0] = T::ONE;
    for e in 1..=max {
        // (o + d t)·row_{e−1}: c_m = o·p_m + d·p_{m−1}, with p_{−1} = p_e = 0 written into the
        // same expression (`o·0 + d·p` is not simplified: the values are those of one formula).
        let (done, rest) = table.split_at_mut(e * (e + 1) / 2);
        let (prev, cur) = (&done[(e - 1) * e / 2..], &mut rest[..=e]);
        cur[0] = prev[0].mul(o).add(T::ZERO.mul_f(d));
        for (c, w) in cur[1..e].iter_mut().zip(prev[..e].windows(2)) {
            *c = w[1].mul(o).add(w[0].mul_f(d));
        }
        cur[e] = T::ZERO.mul(o).add(prev[e - 1].mul_f(d));
    }
}

impl Add for &Poly3 {
    type Output = Poly3;
    fn add(self, rhs: &Poly3) -> Poly3 {
        Poly3::from_terms(
            self.terms
                .iter()
                .chain(&rhs.terms)
                .map(|t| (t.coeff, t.exps)),
        )
    }
}

impl Sub for &Poly3 {
    type Output = Poly3;
    fn sub(self, rhs: &Poly3) -> Poly3 {
        Poly3::from_terms(
            self.terms
                .iter()
                .map(|t| (t.coeff, t.exps))
                .chain(rhs.terms.iter().map(|t| (-t.coeff, t.exps))),
        )
    }
}

impl Mul for &Poly3 {
    type Output = Poly3;
    fn mul(self, rhs: &Poly3) -> Poly3 {
        self.checked_mul(rhs, usize::MAX)
            .expect("no limit on the term products")
    }
}

impl Mul<f64> for &Poly3 {
    type Output = Poly3;
    fn mul(self, rhs: f64) -> Poly3 {
        self.scale(rhs)
    }
}

impl Neg for &Poly3 {
    type Output = Poly3;
    fn neg(self) -> Poly3 {
        self.scale(-1.0)
    }
}

macro_rules! forward_owned_binop {
    ($tr:ident, $m:ident) => {
        impl $tr for Poly3 {
            type Output = Poly3;
            fn $m(self, rhs: Poly3) -> Poly3 {
                (&self).$m(&rhs)
            }
        }
        impl $tr<&Poly3> for Poly3 {
            type Output = Poly3;
            fn $m(self, rhs: &Poly3) -> Poly3 {
                (&self).$m(rhs)
            }
        }
        impl $tr<Poly3> for &Poly3 {
            type Output = Poly3;
            fn $m(self, rhs: Poly3) -> Poly3 {
                self.$m(&rhs)
            }
        }
    };
}
forward_owned_binop!(Add, add);
forward_owned_binop!(Sub, sub);
forward_owned_binop!(Mul, mul);

impl Mul<f64> for Poly3 {
    type Output = Poly3;
    fn mul(self, rhs: f64) -> Poly3 {
        self.scale(rhs)
    }
}

impl Neg for Poly3 {
    type Output = Poly3;
    fn neg(self) -> Poly3 {
        self.scale(-1.0)
    }
}

impl fmt::Display for Poly3 {
    /// Highest-degree terms first, e.g. `x^2*y + 3*z - 1`; `0` for the zero polynomial.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        if self.terms.is_empty() {
            return write!(f, "0");
        }
        let mut sorted: Vec<&Term3> = self.terms.iter().collect();
        sorted.sort_by(|a, b| b.degree().cmp(&a.degree()).then(b.exps.cmp(&a.exps)));
        for (n, t) in sorted.iter().enumerate() {
            let (sign, c) = if t.coeff < 0.0 {
                ("-", -t.coeff)
            } else {
                ("+", t.coeff)
            };
            if n == 0 {
                if sign == "-" {
                    write!(f, "-")?;
                }
            } else {
                write!(f, " {sign} ")?;
            }
            let mut factors: Vec<String> = Vec::new();
            if c != 1.0 || t.degree() == 0 {
                factors.push(format!("{c}"));
            }
            for (name, e) in ["x", "y", "z"].iter().zip(t.exps) {
                match e {
                    0 => {}
                    1 => factors.push((*name).to_string()),
                    _ => factors.push(format!("{name}^{e}")),
                }
            }
            write!(f, "{}", factors.join("*"))?;
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn torus(major: f64, minor: f64) -> Poly3 {
        // (x²+y²+z²+R²−r²)² − 4R²(x²+y²)
        let (x, y, z) = (Poly3::x(), Poly3::y(), Poly3::z());
        let rho2 = &(&x * &x) + &(&y * &y);
        let s = &(&rho2 + &(&z * &z)) + &Poly3::constant(major * major - minor * minor);
        &s.pow(2) - &(&rho2 * (4.0 * major * major))
    }

    #[test]
    fn from_terms_merges_and_drops_zeros() {
        let p = Poly3::from_terms([(1.0, [1, 0, 0]), (2.0, [0, 0, 1]), (-1.0, [1, 0, 0])]);
        assert_eq!(p.terms().len(), 1, "x − x cancels: {p}");
        assert_eq!(p.to_string(), "2*z", "display");
        assert_eq!(Poly3::zero().degree(), 0, "zero has degree 0");
        // A run of equal exponents is summed left to right, in the order given (merged in
        // place since issue 12's ninth pass): (0.1 + 0.2) + 0.3, not 0.1 + (0.2 + 0.3).
        let p = Poly3::from_terms([
            (0.1, [0, 1, 0]),
            (7.0, [0, 0, 0]),
            (0.2, [0, 1, 0]),
            (0.3, [0, 1, 0]),
        ]);
        let y = p
            .terms()
            .iter()
            .find(|t| t.exps == [0, 1, 0])
            .expect("the y term");
        assert_eq!(y.coeff, (0.1 + 0.2) + 0.3, "left to right");
        assert_ne!(y.coeff, 0.1 + (0.2 + 0.3), "the other order differs");
        assert_eq!(p.terms().len(), 2, "{p}");
    }

    /// The one-pass bounds are the per-set bounds, for every set of moving axes, on
    /// polynomials with terms in one, two and three variables and a constant (a torus, a
    /// sphere, `x³y + z⁵`, `x²`, the zero polynomial).
    #[test]
    fn restriction_degree_bounds_are_the_per_set_bounds() {
        let (x, y, z) = (Poly3::x(), Poly3::y(), Poly3::z());
        let sphere = &(&(&(&x * &x) + &(&y * &y)) + &(&z * &z)) - &Poly3::constant(4.0);
        let mixed = &(&x.pow(3) * &y) + &z.pow(5);
        for p in [torus(2.0, 1.0), sphere, mixed, x.pow(2), Poly3::zero()] {
            let all = p.restriction_degree_bounds();
            for (bits, &b) in all.iter().enumerate() {
                let moving = [bits & 1 != 0, bits & 2 != 0, bits & 4 != 0];
                assert_eq!(
                    b,
                    p.restriction_degree_bound(moving),
                    "{p}, moving {moving:?}"
                );
            }
        }
    }

    #[test]
    fn torus_expansion_has_ten_terms() {
        let t = torus(2.0, 1.0);
        assert_eq!(t.degree(), 4, "quartic");
        assert_eq!(t.terms().len(), 10, "{t}");
        assert_eq!(t.eval(DVec3::new(3.0, 0.0, 0.0)), 0.0, "outer equator");
        assert_eq!(t.eval(DVec3::new(0.0, 2.0, 1.0)), 0.0, "top of the tube");
    }

    #[test]
    fn restriction_matches_pointwise_evaluation() {
        let f = torus(2.0, 0.5);
        let (o, d) = (DVec3::new(0.3, -6.0, 2.5), DVec3::new(0.1, 1.0, -0.4));
        let line = f.restrict_to_line(o, d);
        assert_eq!(line.degree(), 4, "a quartic along a generic line");
        for t in [-1.0, 0.0, 0.5, 2.0, 7.5] {
            let direct = f.eval(o + d * t);
            let via = line.eval(&t);
            let scale = f.eval_abs(o + d * t).max(1.0);
            assert!(
                (direct - via).abs() <= 1e-12 * scale,
                "t = {t}: direct {direct}, restricted {via}"
            );
        }
    }

    /// `eval_abs_upper` bounds the exact `F_abs(y)` from above, within its stated factor
    /// `1 + 2γ(N + 3 + terms)` plus the roundings it covers, on random sparse polynomials whose
    /// exponents reach past the power table (33 entries) and on points with components below
    /// and above 1 (where the powers shrink or grow).
    #[test]
    fn eval_abs_upper_bounds_the_exact_absolute_sum() {
        use rand::{Rng, SeedableRng};
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(33);
        let r = |x: f64| poly::rat_from_f64(x).unwrap();
        for case in 0..300 {
            let top = if case % 3 == 0 { 40 } else { 12 };
            let f = Poly3::from_terms((0..rng.gen_range(1..30)).map(|_| {
                let coeff = rng.gen_range(-2.0..2.0) * 10f64.powi(rng.gen_range(-5..5));
                let exps = [0; 3].map(|_| rng.gen_range(0..=top));
                (coeff, exps)
            }));
            // Dyadic points with few bits keep the exact powers small.
            let y = DVec3::from_array(
                [0; 3].map(|_| f64::from(rng.gen_range(0..32u8)) / 16.0 + 1.0 / 1024.0),
            );
            let exact = f.terms().iter().fold(r(0.0), |acc, t| {
                let mut term = r(t.coeff.abs());
                for k in 0..3 {
                    for _ in 0..t.exps[k] {
                        term *= r(y[k]);
                    }
                }
                acc + term
            });
            let bound = f.eval_abs_upper(y);
            assert!(
                r(bound) >= exact,
                "case {case}: {bound:e} below the exact sum of {f}"
            );
            let steps = f.degree() as usize + 3 + f.terms().len();
            let factor = 1.0 + 4.0 * crate::geometry::gamma(steps);
            assert!(
                bound <= poly::rat_to_f64(&exact) * factor,
                "case {case}: {bound:e} above the exact sum by more than the stated factor"
            );
        }
    }

    #[test]
    fn exact_restriction_agrees_with_rationals_and_bounds_the_rounded_one() {
        // Irrational-looking coefficients (a torus with R = 1.3, r = 0.4) and a tiny one.
        let f = &torus(1.3, 0.4) + &Poly3::from_terms([(1e-300, [1, 1, 1]), (3.0e7, [0, 0, 1])]);
        let (o, d) = (DVec3::new(0.3, -6.1, 2.5), DVec3::new(0.1, 1.0, -0.4));
        let rat = |v: DVec3| [v.x, v.y, v.z].map(|x| poly::rat_from_f64(x).unwrap());
        let (or, dr) = (rat(o), rat(d));
        let fast = f.restrict_exact(&or, &dr);
        assert_eq!(
            fast,
            f.restrict_rational(&or, &dr),
            "dyadic integers = rationals"
        );
        let (a, b, t) = (0.1, -3.7e-5, 1.0 / 3.0);
        let r = |x: f64| poly::rat_from_f64(x).unwrap();
        assert_eq!(
            exact_point(a, b, t),
            r(a) + r(b) * r(t),
            "origin + dir·t exactly"
        );
        // The rounded restriction is within γ(K)·F_abs(|o| + t|d|) of it (Σ over t = 1).
        let rounded = f.restrict_to_line(o, d);
        let k = f.restriction_rounding_steps() as usize;
        let bound = crate::geometry::gamma(k) * f.eval_abs_upper(o.abs() + d.abs());
        let diff: f64 = fast
            .coeffs()
            .iter()
            .zip(rounded.coeffs())
            .map(|(a, b)| (poly::rat_to_f64(a) - b).abs())
            .sum();
        assert!(
            diff <= bound,
            "Σ|Δc| = {diff:e} within γ(K)·F_abs = {bound:e}"
        );
    }

    #[test]
    fn derivative_and_compose_affine() {
        let f = torus(2.0, 1.0);
        let g = f.gradient_polys();
        let p = DVec3::new(3.0, 0.0, 0.0);
        assert_eq!(
            g[0].eval(p),
            4.0 * 3.0 * (9.0 + 3.0) - 8.0 * 4.0 * 3.0,
            "∂F/∂x at (3,0,0)"
        );
        // Shift by (1, 2, 3): G(p) = F(p + b).
        let b = DVec3::new(1.0, 2.0, 3.0);
        let shifted = f.compose_affine(glam::DMat3::IDENTITY, b);
        let q = DVec3::new(0.25, -0.5, 0.75);
        assert!(
            (shifted.eval(q) - f.eval(q + b)).abs() < 1e-9,
            "G(q) = F(q + b)"
        );
        assert_eq!((&f - &f).terms().len(), 0, "F − F = 0");
        assert_eq!(Poly3::x().pow(3).degree(), 3, "x³");
        let e = f.eval_grad(q);
        assert!((e.f - f.eval(q)).abs() < 1e-12, "one-pass value");
        for (k, gk) in g.iter().enumerate() {
            assert!((e.grad[k] - gk.eval(q)).abs() < 1e-12, "one-pass ∂F/∂x{k}");
            assert!(
                (e.grad_abs[k] - gk.eval_abs(q)).abs() < 1e-12,
                "one-pass |∂F/∂x{k}|"
            );
        }
        let big = Poly3::x().pow(30);
        let slow = big.eval_grad(DVec3::new(1.1, 0.0, 0.0));
        assert!(
            (slow.grad.x - 30.0 * 1.1f64.powi(29)).abs() < 1e-9,
            "degree 30 uses the heap tables"
        );
        assert!(
            (slow.f - 1.1f64.powi(30)).abs() < 1e-12 * slow.f_abs,
            "and F from the same table: {}",
            slow.f
        );
    }
}

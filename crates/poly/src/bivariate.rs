//! [`BiPoly`]: dense bivariate polynomials in `u` and `v`, ordered by Stam's total-lexicographic
//! order ([`Monomial`]).
//!
//! This is the ring `K[u, v]` that the Gröbner reduction of `groebner` works in (J. Stam 1988,
//! "Ray tracing polynomial patches using Groebner bases", seed `001_…`, Annexe A §3). The ray /
//! patch equations `F1(u, v) = F2(u, v) = 0` (article §2, eq. 5) are built per ray from a bicubic
//! grid of coefficients, so the storage is a dense grid that costs one allocation.

use std::cmp::Ordering;
use std::fmt;
use std::ops::{Add, Mul, Neg, Sub};

use crate::scalar::{Rat, Scalar};
use crate::univariate::{Poly, horner};

/// The monomial `u^u · v^v`, ordered by Stam's total-lexicographic order (TLO): compare the
/// `v`-degree first, then the `u`-degree,
///
/// `1 < u < u² < … < v < uv < u²v < … < v² < uv² < …`
///
/// (article §3). The order is *acceptable* (`f < g ⇒ h·f < h·g`), and every pure power of `u`
/// is below `v`, which is why a Gröbner basis in this order contains a polynomial in `u` alone
/// whenever the system has finitely many solutions (Theorem 3).
///
/// # Examples
/// ```
/// use poly::Monomial;
/// let (uv2, u3v) = (Monomial::new(1, 2), Monomial::new(3, 1));
/// assert!(uv2 > u3v, "the v-degree decides first");
/// assert!(Monomial::new(7, 0) < Monomial::new(0, 1), "u^7 < v");
/// assert_eq!(uv2.lcm(u3v), Monomial::new(3, 2));
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Default)]
pub struct Monomial {
    /// The power of `u`.
    pub u: usize,
    /// The power of `v`.
    pub v: usize,
}

impl Monomial {
    /// The monomial `1`.
    pub const ONE: Monomial = Monomial { u: 0, v: 0 };

    /// `u^u · v^v`.
    pub const fn new(u: usize, v: usize) -> Self {
        Monomial { u, v }
    }

    /// True when `self` divides `other` (both exponents are at most those of `other`).
    pub fn divides(self, other: Monomial) -> bool {
        self.u <= other.u && self.v <= other.v
    }

    /// `other / self` when `self` divides `other`.
    pub fn quotient_of(self, other: Monomial) -> Option<Monomial> {
        Some(Monomial::new(
            other.u.checked_sub(self.u)?,
            other.v.checked_sub(self.v)?,
        ))
    }

    /// The least common multiple (exponent-wise maximum).
    pub fn lcm(self, other: Monomial) -> Monomial {
        Monomial::new(self.u.max(other.u), self.v.max(other.v))
    }

    /// The product (exponent-wise sum).
    pub fn times(self, other: Monomial) -> Monomial {
        Monomial::new(self.u + other.u, self.v + other.v)
    }

    /// True when `self` and `other` share no variable (their lcm is their product); Buchberger's
    /// first criterion skips such pairs.
    pub fn is_coprime(self, other: Monomial) -> bool {
        (self.u == 0 || other.u == 0) && (self.v == 0 || other.v == 0)
    }
}

impl Ord for Monomial {
    fn cmp(&self, other: &Self) -> Ordering {
        // TLO (article §3): v-degree first, then u-degree.
        (self.v, self.u).cmp(&(other.v, other.u))
    }
}

impl PartialOrd for Monomial {
    fn partial_cmp(&self, other: &Self) -> Option<Ordering> {
        Some(self.cmp(other))
    }
}

/// A dense bivariate polynomial `Σ c_ij · u^i · v^j`.
///
/// # Layout
/// The coefficients form a row-major grid with one row per power of `v`:
/// [`coeffs`](BiPoly::coeffs)`[j * stride + i]` is the coefficient of `u^i v^j`, where
/// `stride = deg_u + 1` ([`stride`](BiPoly::stride)) and there are `deg_v + 1` rows. Because
/// `i < stride`, increasing flat index is increasing [`Monomial`] order (TLO), so the leading
/// monomial is the last non-zero entry.
///
/// The invariant, kept by every constructor and operation, is that the grid is tight: its last
/// row and its last column each hold a non-zero coefficient (exact zero test, as for [`Poly`]).
/// The zero polynomial has stride 0 and no coefficients. Equal polynomials therefore have equal
/// grids, and `==` compares them.
///
/// # Examples
/// ```
/// use poly::{BiPoly, Monomial};
/// // F1 = uv + uv² − u³ (article §3): grid rows are v⁰, v¹, v², each lowest u-power first.
/// #[rustfmt::skip]
/// let f1 = BiPoly::from_grid(4, 3, vec![
///     0.0, 0.0, 0.0, -1.0, // −u³
///     0.0, 1.0, 0.0,  0.0, // u·v
///     0.0, 1.0, 0.0,  0.0, // u·v²
/// ]);
/// assert_eq!(f1.leading_monomial(), Some(Monomial::new(1, 2)));
/// assert_eq!(f1.eval(&2.0, &1.0), 2.0 + 2.0 - 8.0);
/// assert_eq!(f1.subst_u(&1.0).coeffs(), &[-1.0, 1.0, 1.0]); // v² + v − 1
/// ```
#[derive(Clone, Debug, PartialEq, Eq, Hash)]
pub struct BiPoly<T> {
    /// Row length: `deg_u + 1`, or 0 for the zero polynomial.
    stride: usize,
    /// `coeffs[j * stride + i]` = coefficient of `u^i v^j`.
    coeffs: Vec<T>,
}

/// Bivariate polynomials with exact rational coefficients.
pub type QBiPoly = BiPoly<Rat>;

impl<T> BiPoly<T> {
    /// The coefficient grid (see the type's `# Layout`): `coeffs()[j * stride() + i]` is the
    /// coefficient of `u^i v^j`. Empty for the zero polynomial.
    pub fn coeffs(&self) -> &[T] {
        &self.coeffs
    }

    /// The row length of the grid, `deg_u + 1` (0 for the zero polynomial).
    pub fn stride(&self) -> usize {
        self.stride
    }

    /// The number of rows, `deg_v + 1` (0 for the zero polynomial).
    pub fn rows(&self) -> usize {
        self.coeffs.len().checked_div(self.stride).unwrap_or(0)
    }

    /// True for the zero polynomial.
    pub fn is_zero(&self) -> bool {
        self.coeffs.is_empty()
    }

    /// The largest power of `u` in any term (0 for constants and for the zero polynomial).
    pub fn deg_u(&self) -> usize {
        self.stride.saturating_sub(1)
    }

    /// The largest power of `v` in any term, which is also the `v`-power of the leading monomial
    /// (`Deg_v` of article §3 def. 2). 0 for polynomials in `u` alone and for zero.
    pub fn deg_v(&self) -> usize {
        self.rows().saturating_sub(1)
    }

    /// The coefficient of `u^i v^j`, `None` outside the grid.
    pub fn coeff_ref(&self, i: usize, j: usize) -> Option<&T> {
        if i >= self.stride {
            return None;
        }
        self.coeffs.get(j * self.stride + i)
    }

    /// The rows of the grid: `rows_iter().nth(j)` holds the coefficients of `v^j`, lowest power
    /// of `u` first.
    pub fn rows_iter(&self) -> std::slice::ChunksExact<'_, T> {
        self.coeffs.chunks_exact(self.stride.max(1))
    }
}

impl<T: Scalar> BiPoly<T> {
    /// Builds the polynomial whose coefficient of `u^i v^j` is `coeffs[j * stride + i]`, for
    /// `i < stride` and `j < rows` (a row per power of `v`, each lowest `u`-power first), then
    /// trims zero rows and columns so the grid is tight.
    ///
    /// # Panics
    /// If `coeffs.len() != stride * rows` (a caller bug).
    pub fn from_grid(stride: usize, rows: usize, coeffs: Vec<T>) -> Self {
        assert_eq!(
            coeffs.len(),
            stride * rows,
            "a {stride}×{rows} grid needs {} coefficients",
            stride * rows
        );
        let mut p = BiPoly { stride, coeffs };
        p.normalize();
        p
    }

    /// The polynomial with coefficient `f(i, j)` for `u^i v^j`, `i < stride`, `j < rows`.
    pub fn from_fn(stride: usize, rows: usize, mut f: impl FnMut(usize, usize) -> T) -> Self {
        let mut coeffs = Vec::with_capacity(stride * rows);
        for j in 0..rows {
            for i in 0..stride {
                coeffs.push(f(i, j));
            }
        }
        Self::from_grid(stride, rows, coeffs)
    }

    /// The sum of the given terms (repeated monomials add up).
    ///
    /// # Examples
    /// ```
    /// use poly::{BiPoly, Monomial};
    /// // F2 = −u² + 1 + u³v (article §3)
    /// let f2 = BiPoly::from_terms([(-1.0, 2, 0), (1.0, 0, 0), (1.0, 3, 1)]);
    /// assert_eq!(f2.leading_monomial(), Some(Monomial::new(3, 1)));
    /// ```
    pub fn from_terms(terms: impl IntoIterator<Item = (T, usize, usize)>) -> Self {
        let terms: Vec<(T, usize, usize)> = terms.into_iter().collect();
        let stride = terms.iter().map(|t| t.1 + 1).max().unwrap_or(0);
        let rows = terms.iter().map(|t| t.2 + 1).max().unwrap_or(0);
        let mut coeffs = vec![T::zero(); stride * rows];
        for (c, i, j) in terms {
            let k = j * stride + i;
            coeffs[k] = coeffs[k].clone() + c;
        }
        Self::from_grid(stride, rows, coeffs)
    }

    /// The zero polynomial.
    pub fn zero() -> Self {
        BiPoly {
            stride: 0,
            coeffs: Vec::new(),
        }
    }

    /// The constant `c`.
    pub fn constant(c: T) -> Self {
        Self::from_grid(1, 1, vec![c])
    }

    /// The term `c · m`.
    pub fn monomial(c: T, m: Monomial) -> Self {
        Self::from_terms([(c, m.u, m.v)])
    }

    /// `p(u)` seen as a bivariate polynomial (a single row).
    pub fn from_poly_u(p: &Poly<T>) -> Self {
        Self::from_grid(p.coeffs().len(), 1, p.coeffs().to_vec())
    }

    /// `p(v)` seen as a bivariate polynomial (a single column).
    pub fn from_poly_v(p: &Poly<T>) -> Self {
        Self::from_grid(1, p.coeffs().len(), p.coeffs().to_vec())
    }

    /// The coefficient of `u^i v^j` (zero outside the grid).
    pub fn coeff(&self, i: usize, j: usize) -> T {
        self.coeff_ref(i, j).cloned().unwrap_or_else(T::zero)
    }

    /// The non-zero terms `(monomial, coefficient)` in increasing TLO order.
    pub fn terms(&self) -> impl DoubleEndedIterator<Item = (Monomial, &T)> + '_ {
        let stride = self.stride.max(1);
        self.coeffs
            .iter()
            .enumerate()
            .filter(|(_, c)| !c.is_zero())
            .map(move |(k, c)| (Monomial::new(k % stride, k / stride), c))
    }

    /// The number of non-zero terms.
    pub fn term_count(&self) -> usize {
        self.coeffs.iter().filter(|c| !c.is_zero()).count()
    }

    /// The leading monomial `LM(p)` in TLO (article §3 def. 1); `None` for zero.
    pub fn leading_monomial(&self) -> Option<Monomial> {
        let j = self.rows().checked_sub(1)?;
        let row = &self.coeffs[j * self.stride..];
        let i = row.iter().rposition(|c| !c.is_zero())?;
        Some(Monomial::new(i, j))
    }

    /// The coefficient of the leading monomial; `None` for zero.
    pub fn leading_coeff(&self) -> Option<&T> {
        let m = self.leading_monomial()?;
        self.coeff_ref(m.u, m.v)
    }

    /// True when the polynomial does not involve `v` (it lies in `K[u]`; zero included).
    pub fn is_univariate_u(&self) -> bool {
        self.rows() <= 1
    }

    /// True when the polynomial is a constant (zero included).
    pub fn is_constant(&self) -> bool {
        self.coeffs.len() <= 1
    }

    /// The polynomial in `u` when [`is_univariate_u`](BiPoly::is_univariate_u), else `None`.
    pub fn to_poly_u(&self) -> Option<Poly<T>> {
        self.is_univariate_u()
            .then(|| Poly::new(self.coeffs.clone()))
    }

    /// The coefficients in `v`: element `j` is the polynomial in `u` multiplying `v^j`, so
    /// `p = Σ_j out[j](u) · v^j` (the view used by resultants in `v`).
    pub fn coeffs_in_v(&self) -> Vec<Poly<T>> {
        self.rows_iter().map(|r| Poly::new(r.to_vec())).collect()
    }

    /// The largest coefficient magnitude (zero for the zero polynomial).
    pub fn max_abs_coeff(&self) -> T {
        self.coeffs.iter().fold(T::zero(), |m, c| {
            let a = c.abs();
            if a > m { a } else { m }
        })
    }

    /// `p(u, v)`, by Horner's rule in `u` inside Horner's rule in `v`.
    ///
    /// # Accuracy
    /// Exact for [`Rat`]. For `f64` the nested Horner bound applies: the error is at most
    /// `γ(2(deg_u + deg_v) + 2) · Σ|c_ij||u|^i|v|^j` (Higham §5.1 applied twice).
    pub fn eval(&self, u: &T, v: &T) -> T {
        self.rows_iter()
            .rev()
            .fold(T::zero(), |acc, row| acc * v + horner(row, u))
    }

    /// The polynomial in `v` obtained by substituting `u = u0` (article §4.4: "substitute `u` in
    /// `F_{N−1}` with an `u_i`"). Coefficient `j` is `Σ_i c_ij u0^i`.
    pub fn subst_u(&self, u0: &T) -> Poly<T> {
        Poly::new(self.rows_iter().map(|row| horner(row, u0)).collect())
    }

    /// The polynomial in `u` obtained by substituting `v = v0`: coefficient `i` is
    /// `Σ_j c_ij v0^j`.
    pub fn subst_v(&self, v0: &T) -> Poly<T> {
        let mut out = vec![T::zero(); self.stride];
        for row in self.rows_iter().rev() {
            for (o, c) in out.iter_mut().zip(row) {
                *o = o.clone() * v0 + c;
            }
        }
        Poly::new(out)
    }

    /// `c · p`.
    pub fn scale(&self, c: &T) -> Self {
        let mut out = BiPoly {
            stride: self.stride,
            coeffs: self.coeffs.iter().map(|a| a.clone() * c).collect(),
        };
        out.normalize();
        out
    }

    /// `p ← c · p` in place (no allocation).
    pub fn scale_assign(&mut self, c: &T) {
        for a in &mut self.coeffs {
            *a = a.clone() * c;
        }
        self.normalize();
    }

    /// `p / lc(p)`, so the leading coefficient is exactly one (article §3 def. 1 takes the
    /// leading coefficient to be 1); zero stays zero.
    pub fn make_monic(&self) -> Self {
        let mut out = self.clone();
        out.make_monic_in_place();
        out
    }

    /// In-place [`make_monic`](BiPoly::make_monic): divides by the leading coefficient and
    /// returns that coefficient (`None` for zero).
    pub fn make_monic_in_place(&mut self) -> Option<T> {
        let m = self.leading_monomial()?;
        let k = m.v * self.stride + m.u;
        let lc = self.coeffs[k].clone();
        for c in &mut self.coeffs {
            *c = c.clone() / &lc;
        }
        // The leading term is exactly one, whatever rounding did.
        self.coeffs[k] = T::one();
        Some(lc)
    }

    /// `c · m · p`, multiplication by the term `c·u^m.u·v^m.v`.
    pub fn mul_term(&self, c: &T, m: Monomial) -> Self {
        if self.is_zero() || c.is_zero() {
            return Self::zero();
        }
        let stride = self.stride + m.u;
        let rows = self.rows() + m.v;
        let mut coeffs = vec![T::zero(); stride * rows];
        for (j, row) in self.rows_iter().enumerate() {
            let base = (j + m.v) * stride + m.u;
            for (o, a) in coeffs[base..base + row.len()].iter_mut().zip(row) {
                *o = a.clone() * c;
            }
        }
        Self::from_grid(stride, rows, coeffs)
    }

    /// `self += c · m · q` in place (a reduction step `p − λ·F_i` of article §3 def. 4 is this
    /// with `c = −λ`). Reuses `self`'s buffer when the result fits in its grid.
    ///
    /// # Complexity
    /// O(terms of `q`) when the grid is large enough, otherwise one reallocation of the grid;
    /// plus the O(grid) tightening scan.
    pub fn add_scaled_term_assign(&mut self, c: &T, m: Monomial, q: &BiPoly<T>) {
        if q.is_zero() || c.is_zero() {
            return;
        }
        let need_stride = self.stride.max(q.stride + m.u);
        let need_rows = self.rows().max(q.rows() + m.v);
        if need_stride != self.stride || need_rows != self.rows() {
            self.reshape(need_stride, need_rows);
        }
        let stride = self.stride;
        for (j, row) in q.rows_iter().enumerate() {
            let base = (j + m.v) * stride + m.u;
            for (o, a) in self.coeffs[base..base + row.len()].iter_mut().zip(row) {
                if !a.is_zero() {
                    *o = o.clone() + a.clone() * c;
                }
            }
        }
        self.normalize();
    }

    /// Sets to zero every coefficient for which `pred(i, j, c)` holds (`c` the coefficient of
    /// `u^i v^j`), then tightens the grid. This is how callers apply their own zero test, such as
    /// the relative test of `groebner`'s `f64` reduction.
    pub fn zero_where(&mut self, mut pred: impl FnMut(usize, usize, &T) -> bool) {
        let stride = self.stride.max(1);
        for (k, c) in self.coeffs.iter_mut().enumerate() {
            if !c.is_zero() && pred(k % stride, k / stride, c) {
                *c = T::zero();
            }
        }
        self.normalize();
    }

    /// The polynomial with `f` applied to every coefficient of the grid (zeros included), for
    /// example `|c|` or a change of scalar type.
    pub fn map<S: Scalar>(&self, f: impl FnMut(&T) -> S) -> BiPoly<S> {
        BiPoly::from_grid(
            self.stride,
            self.rows(),
            self.coeffs.iter().map(f).collect(),
        )
    }

    /// `∂p/∂u`.
    pub fn d_du(&self) -> Self {
        if self.stride <= 1 {
            return Self::zero();
        }
        let stride = self.stride - 1;
        let coeffs = self
            .rows_iter()
            .flat_map(|row| {
                row.iter()
                    .enumerate()
                    .skip(1)
                    .map(|(i, c)| c.clone() * small::<T>(i))
            })
            .collect();
        Self::from_grid(stride, self.rows(), coeffs)
    }

    /// `∂p/∂v`.
    pub fn d_dv(&self) -> Self {
        if self.rows() <= 1 {
            return Self::zero();
        }
        let coeffs = self
            .rows_iter()
            .enumerate()
            .skip(1)
            .flat_map(|(j, row)| row.iter().map(move |c| c.clone() * small::<T>(j)))
            .collect();
        Self::from_grid(self.stride, self.rows() - 1, coeffs)
    }

    /// Grows (or shrinks, dropping what falls outside) the grid to `stride × rows`.
    fn reshape(&mut self, stride: usize, rows: usize) {
        let mut coeffs = vec![T::zero(); stride * rows];
        let w = self.stride.min(stride);
        for (j, row) in self.rows_iter().take(rows).enumerate() {
            coeffs[j * stride..j * stride + w].clone_from_slice(&row[..w]);
        }
        self.stride = stride;
        self.coeffs = coeffs;
    }

    /// Restores the invariant: drop zero rows at the top and zero columns on the right.
    fn normalize(&mut self) {
        if self.stride == 0 {
            self.coeffs.clear();
            return;
        }
        // Trailing zero rows (highest powers of v).
        let last = self.coeffs.iter().rposition(|c| !c.is_zero());
        let Some(last) = last else {
            self.coeffs.clear();
            self.stride = 0;
            return;
        };
        let rows = last / self.stride + 1;
        self.coeffs.truncate(rows * self.stride);
        // Trailing zero columns (highest powers of u): the widest row decides.
        let used = self
            .rows_iter()
            .map(|row| row.iter().rposition(|c| !c.is_zero()).map_or(0, |i| i + 1))
            .max()
            .unwrap_or(0);
        if used < self.stride {
            // Repack in place: destinations never pass their sources (j·used + i ≤ j·stride + i),
            // and every source is read before any later destination overwrites it.
            for j in 0..rows {
                for i in 0..used {
                    self.coeffs.swap(j * used + i, j * self.stride + i);
                }
            }
            self.coeffs.truncate(rows * used);
            self.stride = used;
        }
    }
}

/// A small exponent as a scalar (derivatives).
fn small<T: Scalar>(k: usize) -> T {
    T::from_usize(k).expect("polynomial degrees are representable in every scalar type")
}

impl BiPoly<f64> {
    /// True when every coefficient is finite.
    pub fn is_finite(&self) -> bool {
        self.coeffs.iter().all(|c| c.is_finite())
    }

    /// The exact rational polynomial with the same coefficients (every finite `f64` is a dyadic
    /// rational); `None` if a coefficient is NaN or infinite.
    pub fn to_rat(&self) -> Option<QBiPoly> {
        let coeffs = self
            .coeffs
            .iter()
            .map(|&c| Rat::from_f64_exact(c))
            .collect::<Option<Vec<_>>>()?;
        Some(BiPoly {
            stride: self.stride,
            coeffs,
        })
    }

    /// `Σ|c_ij|·|u|^i·|v|^j`: the size of the terms of `p` at `(u, v)`, the scale against which a
    /// residual `p(u, v)` is judged (the Horner error bound of [`BiPoly::eval`] is
    /// `γ(k)` times this).
    pub fn eval_abs(&self, u: f64, v: f64) -> f64 {
        let (au, av) = (u.abs(), v.abs());
        self.rows_iter().rev().fold(0.0, |acc, row| {
            acc * av + row.iter().rev().fold(0.0, |a, c| a * au + c.abs())
        })
    }
}

impl QBiPoly {
    /// The polynomial with each coefficient rounded to the nearest `f64` (correctly rounded;
    /// out-of-range coefficients become ±infinity). Coefficients that round to zero are
    /// dropped.
    pub fn to_f64(&self) -> BiPoly<f64> {
        self.map(Scalar::nearest_f64)
    }
}

impl<T: Scalar> fmt::Display for BiPoly<T> {
    /// Highest term first, e.g. `u^3*v - u^2 + 1`.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        if self.is_zero() {
            return write!(f, "0");
        }
        for (n, (m, c)) in self.terms().rev().enumerate() {
            let neg = c.is_negative();
            let a = c.abs();
            match (n, neg) {
                (0, true) => write!(f, "-")?,
                (0, false) => {}
                (_, true) => write!(f, " - ")?,
                (_, false) => write!(f, " + ")?,
            }
            let unit = a.is_one() && m != Monomial::ONE;
            if !unit {
                write!(f, "{a}")?;
            }
            let mut first = unit;
            for (name, e) in [("u", m.u), ("v", m.v)] {
                if e == 0 {
                    continue;
                }
                if !first {
                    write!(f, "*")?;
                }
                first = false;
                match e {
                    1 => write!(f, "{name}")?,
                    _ => write!(f, "{name}^{e}")?,
                }
            }
        }
        Ok(())
    }
}

fn add_sub<T: Scalar>(a: &BiPoly<T>, b: &BiPoly<T>, subtract: bool) -> BiPoly<T> {
    let mut out = a.clone();
    let sign = if subtract { -T::one() } else { T::one() };
    out.add_scaled_term_assign(&sign, Monomial::ONE, b);
    out
}

fn mul<T: Scalar>(a: &BiPoly<T>, b: &BiPoly<T>) -> BiPoly<T> {
    if a.is_zero() || b.is_zero() {
        return BiPoly::zero();
    }
    let stride = a.stride + b.stride - 1;
    let rows = a.rows() + b.rows() - 1;
    let mut coeffs = vec![T::zero(); stride * rows];
    for (ja, ra) in a.rows_iter().enumerate() {
        for (ia, x) in ra.iter().enumerate() {
            if x.is_zero() {
                continue;
            }
            for (jb, rb) in b.rows_iter().enumerate() {
                let base = (ja + jb) * stride + ia;
                for (o, y) in coeffs[base..base + rb.len()].iter_mut().zip(rb) {
                    *o = o.clone() + x.clone() * y;
                }
            }
        }
    }
    BiPoly::from_grid(stride, rows, coeffs)
}

/// Generates the four operand forms (`a op b`, `&a op b`, `a op &b`, `&a op &b`) from the
/// reference–reference function, as `ops.rs` does for [`Poly`], so they cannot disagree.
macro_rules! forward_binop {
    ($Trait:ident, $method:ident, $body:expr) => {
        impl<T: Scalar> $Trait<&BiPoly<T>> for &BiPoly<T> {
            type Output = BiPoly<T>;
            fn $method(self, rhs: &BiPoly<T>) -> BiPoly<T> {
                $body(self, rhs)
            }
        }
        impl<T: Scalar> $Trait<BiPoly<T>> for &BiPoly<T> {
            type Output = BiPoly<T>;
            fn $method(self, rhs: BiPoly<T>) -> BiPoly<T> {
                $body(self, &rhs)
            }
        }
        impl<T: Scalar> $Trait<&BiPoly<T>> for BiPoly<T> {
            type Output = BiPoly<T>;
            fn $method(self, rhs: &BiPoly<T>) -> BiPoly<T> {
                $body(&self, rhs)
            }
        }
        impl<T: Scalar> $Trait<BiPoly<T>> for BiPoly<T> {
            type Output = BiPoly<T>;
            fn $method(self, rhs: BiPoly<T>) -> BiPoly<T> {
                $body(&self, &rhs)
            }
        }
    };
}

forward_binop!(Add, add, |a, b| add_sub(a, b, false));
forward_binop!(Sub, sub, |a, b| add_sub(a, b, true));
forward_binop!(Mul, mul, mul);

impl<T: Scalar> Mul<&T> for &BiPoly<T> {
    type Output = BiPoly<T>;
    /// Scalar multiple, `p · c`.
    fn mul(self, c: &T) -> BiPoly<T> {
        self.scale(c)
    }
}

impl<T: Scalar> Mul<&T> for BiPoly<T> {
    type Output = BiPoly<T>;
    /// Scalar multiple, `p · c`.
    fn mul(self, c: &T) -> BiPoly<T> {
        self.scale(c)
    }
}

impl<T: Scalar> Neg for &BiPoly<T> {
    type Output = BiPoly<T>;
    fn neg(self) -> BiPoly<T> {
        BiPoly {
            stride: self.stride,
            coeffs: self.coeffs.iter().map(|c| -c.clone()).collect(),
        }
    }
}

impl<T: Scalar> Neg for BiPoly<T> {
    type Output = BiPoly<T>;
    fn neg(mut self) -> BiPoly<T> {
        for c in &mut self.coeffs {
            *c = -c.clone();
        }
        self
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn q(n: i64) -> Rat {
        Rat::from_integer(n.into())
    }

    /// `Σ c·u^i·v^j` from integer `(c, i, j)` triples.
    fn qb(terms: &[(i64, usize, usize)]) -> QBiPoly {
        BiPoly::from_terms(terms.iter().map(|&(c, i, j)| (q(c), i, j)))
    }

    /// Article §3 example: F1 = uv + uv² − u³, F2 = −u² + 1 + u³v.
    fn article_pair() -> (QBiPoly, QBiPoly) {
        (
            qb(&[(1, 1, 1), (1, 1, 2), (-1, 3, 0)]),
            qb(&[(-1, 2, 0), (1, 0, 0), (1, 3, 1)]),
        )
    }

    #[test]
    fn tlo_orders_v_degree_first() {
        // 1 < u < u² < … < v < uv < u²v < … < v² < uv² (article §3)
        let chain = [
            (0, 0),
            (1, 0),
            (2, 0),
            (9, 0),
            (0, 1),
            (1, 1),
            (2, 1),
            (0, 2),
            (1, 2),
        ];
        for w in chain.windows(2) {
            let (a, b) = (Monomial::new(w[0].0, w[0].1), Monomial::new(w[1].0, w[1].1));
            assert!(a < b, "{a:?} < {b:?} in TLO");
        }
        // Acceptable: multiplying by a monomial keeps the order.
        let h = Monomial::new(3, 2);
        for w in chain.windows(2) {
            let (a, b) = (Monomial::new(w[0].0, w[0].1), Monomial::new(w[1].0, w[1].1));
            assert!(a.times(h) < b.times(h), "h·{a:?} < h·{b:?}");
        }
        assert!(Monomial::new(1, 1).divides(Monomial::new(2, 1)), "uv | u²v");
        assert!(
            !Monomial::new(0, 2).divides(Monomial::new(5, 1)),
            "v² ∤ u⁵v"
        );
        assert_eq!(
            Monomial::new(1, 1).quotient_of(Monomial::new(3, 2)),
            Some(Monomial::new(2, 1)),
            "u³v² / uv"
        );
        assert!(
            Monomial::new(4, 0).is_coprime(Monomial::new(0, 1)),
            "u⁴, v coprime"
        );
        assert!(
            !Monomial::new(4, 0).is_coprime(Monomial::new(1, 1)),
            "u⁴, uv share u"
        );
    }

    #[test]
    fn article_leading_monomials() {
        let (f1, f2) = article_pair();
        assert_eq!(
            f1.leading_monomial(),
            Some(Monomial::new(1, 2)),
            "LM(F1) = uv²"
        );
        assert_eq!(
            f2.leading_monomial(),
            Some(Monomial::new(3, 1)),
            "LM(F2) = u³v"
        );
        // Deg_u, Deg_v of the leading monomials (def. 2) and the grid degrees.
        assert_eq!((f1.deg_u(), f1.deg_v()), (3, 2), "F1 grid degrees");
        assert_eq!((f2.deg_u(), f2.deg_v()), (3, 1), "F2 grid degrees");
        assert_eq!(f1.leading_coeff(), Some(&q(1)), "lc(F1)");
        assert_eq!(
            f1.to_string(),
            "u*v^2 + u*v - u^3",
            "display, highest first"
        );
        assert_eq!(f2.to_string(), "u^3*v - u^2 + 1", "display, highest first");
        assert_eq!(
            BiPoly::<Rat>::zero().leading_monomial(),
            None,
            "zero has no LM"
        );
    }

    #[test]
    fn article_s_polynomial_by_hand() {
        // SP(F1, F2) = u²·F1 − v·F2 = u³v + u²v − v − u⁵ (article §3, def. 6 example).
        let (f1, f2) = article_pair();
        let sp = f1.mul_term(&q(1), Monomial::new(2, 0)) - f2.mul_term(&q(1), Monomial::new(0, 1));
        assert_eq!(
            sp,
            qb(&[(1, 3, 1), (1, 2, 1), (-1, 0, 1), (-1, 5, 0)]),
            "SP(F1, F2)"
        );
    }

    #[test]
    fn article_normal_form_steps_by_hand() {
        // p = u²v² + uv + 1; q = p − u·F1 = −u²v + uv + u⁴ + 1 (article §3, first step).
        let (f1, f2) = article_pair();
        let p = qb(&[(1, 2, 2), (1, 1, 1), (1, 0, 0)]);
        let q1 = &p - &f1.mul_term(&q(1), Monomial::new(1, 0));
        assert_eq!(
            q1,
            qb(&[(-1, 2, 1), (1, 1, 1), (1, 4, 0), (1, 0, 0)]),
            "p − uF1"
        );
        // Erratum: the article's second step "q + u·F2" is not a reduction, since
        // LM(F2) = u³v divides no term of q. Done honestly it adds u⁴v − u³ + u, not the
        // printed uv + u⁴ − u³ + u + 1 (see paper-notes/groebner.md).
        let mut q2 = q1.clone();
        q2.add_scaled_term_assign(&q(1), Monomial::new(1, 0), &f2);
        let expected = qb(&[
            (1, 4, 1),
            (1, 4, 0),
            (-1, 3, 0),
            (-1, 2, 1),
            (1, 1, 1),
            (1, 1, 0),
            (1, 0, 0),
        ]);
        assert_eq!(q2, expected, "q + uF2, in place");
        assert_eq!(
            &q1 + &f2.mul_term(&q(1), Monomial::new(1, 0)),
            expected,
            "same by operators"
        );
    }

    #[test]
    fn every_operand_form_agrees() {
        let (a, b) = article_pair();
        let sum = qb(&[
            (1, 1, 1),
            (1, 1, 2),
            (-1, 3, 0),
            (-1, 2, 0),
            (1, 0, 0),
            (1, 3, 1),
        ]);
        assert_eq!(&a + &b, sum, "&a + &b");
        assert_eq!(a.clone() + &b, sum, "a + &b");
        assert_eq!(&a + b.clone(), sum, "&a + b");
        assert_eq!(a.clone() + b.clone(), sum, "a + b");
        let diff = &a - &b;
        assert_eq!(a.clone() - b.clone(), diff, "a − b");
        assert_eq!(a.clone() - &b, diff, "a − &b");
        assert_eq!(&a - b.clone(), diff, "&a − b");
        assert_eq!(&diff + &b, a, "(a − b) + b = a");
        // (uv + uv² − u³)(−u² + 1 + u³v), expanded by hand.
        let prod = qb(&[
            (-1, 3, 1),
            (1, 1, 1),
            (1, 4, 2),
            (-1, 3, 2),
            (1, 1, 2),
            (1, 4, 3),
            (1, 5, 0),
            (-1, 3, 0),
            (-1, 6, 1),
        ]);
        assert_eq!(&a * &b, prod, "&a * &b");
        assert_eq!(a.clone() * b.clone(), prod, "a * b");
        assert_eq!(a.clone() * &b, prod, "a * &b");
        assert_eq!(&a * b.clone(), prod, "&a * b");
        assert_eq!(-&a + a.clone(), BiPoly::zero(), "−a + a = 0, grid emptied");
        assert_eq!(-a.clone(), a.scale(&q(-1)), "−a = (−1)·a");
        assert_eq!(&a * &q(3), a.scale(&q(3)), "scalar operator");
        assert!((&a * &BiPoly::zero()).is_zero(), "a·0 = 0");
    }

    #[test]
    fn grid_stays_tight_after_cancellation() {
        let (a, _) = article_pair();
        // Cancel the uv² term: the v² row must disappear.
        let b = &a - &qb(&[(1, 1, 2)]);
        assert_eq!(
            b.leading_monomial(),
            Some(Monomial::new(1, 1)),
            "LM drops to uv"
        );
        assert_eq!((b.stride(), b.rows()), (4, 2), "rows trimmed");
        // Cancel −u³: the widest column disappears.
        let c = &b + &qb(&[(1, 3, 0)]);
        assert_eq!((c.stride(), c.rows()), (2, 2), "columns trimmed: {c}");
        assert_eq!(c, qb(&[(1, 1, 1)]), "only uv left");
        assert_eq!(c.coeffs(), &[q(0), q(0), q(0), q(1)], "grid of uv");
    }

    #[test]
    fn evaluation_and_substitution_agree() {
        let (f1, f2) = article_pair();
        let prod = &f1 * &f2;
        for (u, v) in [(0, 0), (2, -1), (-3, 5), (1, 1)] {
            let (u, v) = (q(u), q(v));
            let direct = prod.eval(&u, &v);
            assert_eq!(
                direct,
                f1.eval(&u, &v) * f2.eval(&u, &v),
                "eval is a ring map"
            );
            assert_eq!(prod.subst_u(&u).eval(&v), direct, "subst_u then eval");
            assert_eq!(prod.subst_v(&v).eval(&u), direct, "subst_v then eval");
        }
        assert_eq!(
            f1.subst_u(&q(1)),
            Poly::new(vec![q(-1), q(1), q(1)]),
            "F1(1, v) = v² + v − 1"
        );
        assert_eq!(
            f2.subst_v(&q(0)),
            Poly::new(vec![q(1), q(0), q(-1)]),
            "F2(u, 0) = 1 − u²"
        );
        let cols = f1.coeffs_in_v();
        assert_eq!(cols.len(), 3, "three powers of v");
        assert_eq!(
            cols[2],
            Poly::new(vec![q(0), q(1)]),
            "coefficient of v² is u"
        );
    }

    #[test]
    fn derivatives_monic_and_univariate() {
        let (f1, f2) = article_pair();
        assert_eq!(f1.d_du(), qb(&[(1, 0, 1), (1, 0, 2), (-3, 2, 0)]), "∂F1/∂u");
        assert_eq!(f2.d_dv(), qb(&[(1, 3, 0)]), "∂F2/∂v = u³");
        let g = qb(&[(2, 2, 1), (4, 0, 0)]).make_monic();
        assert_eq!(g, qb(&[(1, 2, 1), (2, 0, 0)]), "monic: divide by 2");
        let e = qb(&[(1, 8, 0), (-1, 5, 0), (3, 0, 0)]);
        assert!(
            e.is_univariate_u() && !f1.is_univariate_u(),
            "univariate in u"
        );
        assert_eq!(e.to_poly_u().map(|p| p.degree()), Some(8), "as a Poly in u");
        assert_eq!(
            BiPoly::from_poly_u(&e.to_poly_u().unwrap()),
            e,
            "round trip"
        );
        let pv = Poly::new(vec![q(1), q(0), q(3)]);
        assert_eq!(
            BiPoly::from_poly_v(&pv),
            qb(&[(1, 0, 0), (3, 0, 2)]),
            "1 + 3v²"
        );
        assert_eq!(f1.term_count(), 3, "three terms");
    }

    #[test]
    fn f64_rat_conversions_are_exact_and_nearest() {
        let p = BiPoly::from_grid(2, 2, vec![0.1, -2.5, 0.0, 1e-300]);
        let r = p.to_rat().expect("finite");
        assert_eq!(r.to_f64(), p, "f64 → Rat → f64 round trip");
        assert_eq!(r.coeff(1, 0), q(-5) / q(2), "−2.5 exactly");
        assert!(
            BiPoly::from_grid(1, 1, vec![f64::NAN]).to_rat().is_none(),
            "NaN refused"
        );
        let third = BiPoly::constant(q(1) / q(3));
        assert_eq!(third.to_f64().coeffs(), &[1.0 / 3.0], "nearest double");
        let x = BiPoly::from_terms([(2.0, 1, 0), (-3.0, 0, 1)]); // 2u − 3v
        assert_eq!(x.eval_abs(-1.0, 2.0), 8.0, "|2||−1| + |−3||2|");
    }

    #[test]
    fn zero_where_applies_a_caller_zero_test() {
        let mut p = BiPoly::from_terms([(1.0, 0, 0), (1e-20, 2, 3), (5.0, 1, 1)]);
        p.zero_where(|_, _, c| c.abs() < 1e-12);
        assert_eq!(
            p,
            BiPoly::from_terms([(1.0, 0, 0), (5.0, 1, 1)]),
            "tiny term gone"
        );
        assert_eq!((p.stride(), p.rows()), (2, 2), "grid tightened");
    }

    mod laws {
        use super::*;
        use num_traits::Zero;
        use proptest::prelude::*;

        fn arb_poly() -> impl Strategy<Value = QBiPoly> {
            prop::collection::vec((-5i64..=5, 0usize..4, 0usize..4), 0..7)
                .prop_map(|t| BiPoly::from_terms(t.into_iter().map(|(c, i, j)| (q(c), i, j))))
        }

        proptest! {
            #![proptest_config(ProptestConfig::with_cases(64))]
            #[test]
            fn ring_laws_and_evaluation(a in arb_poly(), b in arb_poly(), c in arb_poly(),
                                        u in -3i64..=3, v in -3i64..=3) {
                prop_assert_eq!(&(&a + &b) * &c, &(&a * &c) + &(&b * &c), "distributive");
                prop_assert_eq!(&a * &b, &b * &a, "commutative");
                prop_assert_eq!(&(&a - &b) + &b, a.clone(), "a − b + b = a");
                let (u, v) = (q(u), q(v));
                prop_assert_eq!((&a * &b).eval(&u, &v), a.eval(&u, &v) * b.eval(&u, &v), "eval");
                // The leading monomial of a product is the product of the leading monomials.
                if let (Some(ma), Some(mb)) = (a.leading_monomial(), b.leading_monomial()) {
                    prop_assert_eq!((&a * &b).leading_monomial(), Some(ma.times(mb)), "LM(ab)");
                }
                // The grid is tight: last row and last column hold a non-zero coefficient.
                let s = &a * &b - &c;
                if !s.is_zero() {
                    let last_row = s.rows_iter().last().unwrap();
                    prop_assert!(last_row.iter().any(|x| !x.is_zero()), "top row non-zero");
                    prop_assert!(s.rows_iter().any(|r| !r[s.stride() - 1].is_zero()), "last column");
                }
            }
        }
    }
}

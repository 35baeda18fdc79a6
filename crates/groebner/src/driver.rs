//! The steps of [`solve`](crate::solve) after elimination, one copy for every representation
//! of the system (article §4.3–4.4; `Roots`, `VPol`, `VRoots` in `ray3.c`;
//! `paper-notes/groebner.md` §5, `paper-notes/resultant.md` §3):
//!
//! 1. the degenerate inputs every method treats alike ([`eliminate_degenerate`]: a zero
//!    equation, equations free of `v`) and the certificate of an `f64` Gröbner element
//!    ([`certify`]);
//! 2. `u`-candidates: the real roots of the `u`-polynomial (and, in `f64`, its near-double
//!    roots), unless the certificate already gave them;
//! 3. `v`-candidates from the first source that does not vanish at `u` ([`v_candidates`]);
//!    both equations vanishing identically at `u` is a common line `u = const`
//!    ([`Verdict::Infinite`]);
//! 4. Newton polish and the residual test of [`Root`] ([`polish_and_verify`]), then duplicates
//!    merged and the roots sorted ([`merge_and_sort`]).
//!
//! The system is seen through [`Rows`]: a [`BiPoly`] on the general path, a
//! [`Bicubic`](crate::bicubic::Bicubic) on the per-ray path, whose buffers ([`Buffers`]) are
//! reused so that nothing is allocated after warm-up. The two paths differ only in how they
//! eliminate (`solve.rs` and `per_ray.rs`).

use std::slice::ChunksExact;

use poly::{
    BiPoly, NearZeroBuffers, Poly, Rat, RootStats, near_double_roots_into,
    near_zero_components_into,
};

use crate::bicubic::Bicubic;
use crate::buchberger::buchberger;
use crate::mod_p::proves_common_root;
use crate::options::{Root, SolveOptions, SolveStats, Verdict};
use crate::resultant::sylvester_resultant_v;
use crate::scalar::SolveScalar;

/// Relative size below which a coefficient of `g(u_r, v)` counts as vanished, `2⁻²⁶ ≈ 1.5e-8`
/// (about `√ε`).
///
/// `u_r` is known to `x_tol`, so a coefficient `c_j(u)` that is exactly zero at the true root
/// evaluates to about `c_j'(u)·x_tol`, relative `deg·x_tol`, far above `ε`; `√ε` leaves room
/// for `x_tol` up to ~1e-9. Declaring a small coefficient zero is harmless here: every `v`
/// candidate is verified on `F1`, `F2`, and a leading coefficient this small only carries roots
/// of size ≳ 1/`VANISH_REL`, far outside the box.
pub(crate) const VANISH_REL: f64 = 1.0 / (1u64 << 26) as f64;

/// Relative size of `|p(c)|` at a critical point `c` below which `c` is treated as a possible
/// double root of the eliminant, `2⁻²⁶ ≈ 1.5e-8` (about `√ε`): the rounding of a degree-18
/// eliminant's coefficients leaves `|p(c)|` at a double root near `γ(k)` times the size of its
/// terms, many orders below this, while the margin costs only spurious candidates, which the
/// residual test rejects ([`poly::near_double_roots_into`]).
pub(crate) const NEAR_DOUBLE_REL: f64 = 1.0 / (1u64 << 26) as f64;

/// Largest width of a component of `{u : |ê(u)| ≤ Ē}` accepted by [`certify`], relative to the
/// `u`-range: `1e-6`. A component this narrow is covered by its midpoint (Newton on `F1`,
/// `F2` converges from within 5e-7 of the box in one or two steps, far inside
/// [`NEWTON_MAX_STEP_REL`]); a wider one means the `f64` eliminant has lost the roots'
/// positions.
pub(crate) const CERT_WIDTH_REL: f64 = 1e-6;

/// Exact mode: precisions (bits after the binary point) to which a `u`-root is narrowed, in
/// turn, when the `v` obtained from a derived basis element at the `f64` value of the root does
/// not verify. A shape element `v + h(u)` turns an error `δu` into `|h'(u)|·δu`; `h'` reached
/// 1.5e18 (2⁶⁰) on a teapot piece, and `x_tol` is about 2⁻³³, so 96 bits leave margin there and
/// the larger levels cover worse cases at growing cost (exact bisection, one evaluation per bit).
const SHARPEN_BITS: [u32; 3] = [96, 192, 384];

/// Newton iterations used to polish a candidate on the original equations.
///
/// Candidates start within `x_tol` (or the eliminant's conditioning) of the root, so one step
/// reaches round-off for simple roots; the others cover slow, linear convergence near
/// tangencies. A step is kept only if it lowers the residual.
const NEWTON_STEPS: usize = 4;

/// Largest Newton step, relative to the box's size: a larger step means the candidate was not
/// near a root of this system, and polishing must not jump to a different root.
pub(crate) const NEWTON_MAX_STEP_REL: f64 = 1e-3;

/// Roots closer than this many `x_tol` in both `u` and `v` are one root (merged): two
/// candidates of one root are each within `x_tol` of it after refinement, and the polish
/// moves each by at most a few `x_tol` more.
const MERGE_X_TOLS: f64 = 4.0;

/// `u`-candidates of an `f64` eliminant closer than this, relative to the `u`-range, are taken
/// as the two halves of a split double root: `1e-6`, as [`CERT_WIDTH_REL`] (rounding splits a
/// double root by about `√ε` of the scale, far below it; distinct simple roots this close are
/// beyond what the `f64` eliminant resolves anyway). Each is then known only to the pair's gap.
const NEAR_PAIR_REL: f64 = 1e-6;

/// A `u`-candidate stands for a root within this many `x_tol` ([`Poly::real_roots`] locates
/// each root to `x_tol`; the factor 2 covers the candidate's own rounding).
const U_ERR_X_TOLS: f64 = 2.0;

/// A bivariate polynomial seen as its rows: the coefficients of `v^j`, lowest `j` first, each
/// a polynomial in `u` (lowest power first). Implemented by [`BiPoly`] and
/// [`Bicubic`](crate::bicubic::Bicubic), so that the steps of this module run on either.
pub(crate) trait Rows<T> {
    /// The rows, lowest `j` first.
    fn rows(&self) -> ChunksExact<'_, T>;
    /// All coefficients, in any fixed layout (for coefficient sizes).
    fn flat(&self) -> &[T];
}

impl<T: poly::Scalar> Rows<T> for BiPoly<T> {
    fn rows(&self) -> ChunksExact<'_, T> {
        self.rows_iter()
    }
    fn flat(&self) -> &[T] {
        self.coeffs()
    }
}

impl Rows<f64> for Bicubic {
    fn rows(&self) -> ChunksExact<'_, f64> {
        Bicubic::rows(self)
    }
    fn flat(&self) -> &[f64] {
        &self.c
    }
}

/// `Deg_v`: the highest `j` whose row is not all zero (0 for the zero polynomial).
pub(crate) fn deg_v<T: poly::Scalar>(p: &impl Rows<T>) -> usize {
    p.rows()
        .rposition(|row| row.iter().any(|c| !c.is_zero()))
        .unwrap_or(0)
}

fn is_zero<T: poly::Scalar>(p: &impl Rows<T>) -> bool {
    p.flat().iter().all(|c| c.is_zero())
}

/// Whether `p` is a constant (zero included).
fn is_constant<T: poly::Scalar>(p: &impl Rows<T>) -> bool {
    p.rows().enumerate().all(|(j, row)| {
        row.iter()
            .enumerate()
            .all(|(i, c)| i + j == 0 || c.is_zero())
    })
}

/// The row of `v⁰` (the whole polynomial when it is free of `v`).
fn row0<T: poly::Scalar>(p: &impl Rows<T>) -> &[T] {
    p.rows().next().unwrap_or(&[])
}

/// The reusable buffers of one solve (a workspace's, or fresh ones on the general path).
#[derive(Debug)]
pub(crate) struct Buffers<T> {
    /// The `u`-polynomial (eliminant or resultant), lowest power first.
    pub(crate) elim: Vec<T>,
    /// Its `f64` values (the eliminant itself in `f64` mode).
    elim_f64: Vec<f64>,
    /// A `v`-polynomial `g(u_r, ·)`.
    v_poly: Vec<T>,
    /// `u`-candidates.
    pub(crate) u_roots: Vec<f64>,
    /// Certified candidates: the largest half-width of their components.
    u_radius: f64,
    /// `v`-candidates.
    v_roots: Vec<f64>,
    /// Verified roots, and the merged ones.
    pub(crate) roots: Vec<Root>,
    merged: Vec<Root>,
    /// Scratch of the near-zero and near-double searches.
    near: NearZeroBuffers,
    /// The root finder's counters (not reported; `poly` needs somewhere to count).
    root_stats: RootStats,
}

impl<T> Buffers<T> {
    /// Buffers sized for a `u`-polynomial of degree `degree` (18 for a bicubic system).
    pub(crate) fn with_degree(degree: usize) -> Self {
        Buffers {
            elim: Vec::with_capacity(degree + 1),
            elim_f64: Vec::with_capacity(degree + 1),
            v_poly: Vec::with_capacity(8),
            u_roots: Vec::with_capacity(degree + 1),
            u_radius: 0.0,
            v_roots: Vec::with_capacity(8),
            roots: Vec::with_capacity(16),
            merged: Vec::with_capacity(16),
            near: NearZeroBuffers::with_degree(degree),
            root_stats: RootStats::default(),
        }
    }
}

/// What the elimination left to solve.
pub(crate) enum Elimination<T> {
    /// Decided without roots to find.
    Verdict(Verdict),
    /// The `u`-polynomial is in [`Buffers::elim`].
    Eliminant {
        /// [`Buffers::u_roots`] already holds the certified `u`-candidates ([`certify`]).
        candidates: bool,
        /// Derived polynomials giving `v` (exact Gröbner bases), tried first, lowest `Deg_v`
        /// first.
        derived: Vec<BiPoly<T>>,
        /// The input equations giving `v` next, by index (0 for `F1`, 1 for `F2`), in order.
        originals: [Option<usize>; 2],
        /// The `u`-polynomial is a resultant (or a power of a `v`-free equation): its roots
        /// can all be "at `v = ∞`" ([`no_common_root_at_all`] decides when no root verifies).
        resultant: bool,
    },
}

/// `F1`, `F2` with `Deg_v > 0`, lowest `Deg_v` first (stable): the sources of `v` after a
/// resultant or a certified `f64` basis.
pub(crate) fn originals<T: poly::Scalar>(f: [&impl Rows<T>; 2]) -> [Option<usize>; 2] {
    let (d1, d2) = (deg_v(f[0]), deg_v(f[1]));
    match ((d1 > 0).then_some(0), (d2 > 0).then_some(1)) {
        (Some(a), Some(b)) if d2 < d1 => [Some(b), Some(a)],
        (None, b) => [b, None],
        (a, b) => [a, b],
    }
}

/// The verdicts and eliminants of degenerate inputs, for every method: a zero equation (the
/// other one's zero set: a curve, the plane, or nothing for a non-zero constant), both
/// equations free of `v` (whole lines `u = const` where their gcd vanishes, or nothing), one
/// free of `v` (its own roots, simple, rather than the resultant's power of it, whose multiple
/// roots `f64` root finding can lose; `v` from the other) — the last only for the resultant
/// methods (`groebner_method` false): a Gröbner basis also decides Theorem 1 there (`uv − 1`
/// and `u` have no common root, real or complex). `None`: the method's own elimination
/// applies.
pub(crate) fn eliminate_degenerate<T: SolveScalar>(
    f: [&impl Rows<T>; 2],
    groebner_method: bool,
    buf: &mut Buffers<T>,
    stats: &mut SolveStats,
) -> Option<Elimination<T>> {
    let verdict = |v| Some(Elimination::Verdict(v));
    if is_zero(f[0]) || is_zero(f[1]) {
        let other = if is_zero(f[0]) { f[1] } else { f[0] };
        if is_zero(other) || !is_constant(other) {
            return verdict(Verdict::Infinite);
        }
        return verdict(Verdict::NoCommonRoot);
    }
    let (d1, d2) = (deg_v(f[0]), deg_v(f[1]));
    if d1 == 0 && d2 == 0 {
        // Degenerate: a gcd of the two univariate polynomials (allocates).
        let a = Poly::new(row0(f[0]).to_vec());
        let g = a.gcd(&Poly::new(row0(f[1]).to_vec()));
        return verdict(if g.degree() > 0 {
            Verdict::Infinite
        } else {
            Verdict::NoCommonRoot
        });
    }
    if (d1 > 0 && d2 > 0) || groebner_method {
        return None;
    }
    let (pu, other) = if d1 == 0 { (0, 1) } else { (1, 0) };
    buf.elim.clear();
    buf.elim.extend_from_slice(row0(f[pu]));
    trim_zeros(&mut buf.elim);
    stats.coeff_bits = T::coeff_bits(f[pu].flat());
    if buf.elim.len() <= 1 {
        return verdict(Verdict::NoCommonRoot);
    }
    stats.v_degree = deg_v(f[other]);
    Some(Elimination::Eliminant {
        candidates: false,
        derived: Vec::new(),
        originals: [Some(other), None],
        resultant: true,
    })
}

/// After a resultant in `buf.elim`: trailing coefficients negligible against the largest are
/// dropped (`f64`; the buffer is lent to a [`Poly`], no allocation), then a zero resultant is a
/// common factor involving `v` ([`Verdict::Infinite`]), a constant one no common root.
pub(crate) fn finish_resultant<T: SolveScalar>(
    buf: &mut Buffers<T>,
    f: [&impl Rows<T>; 2],
    stats: &mut SolveStats,
) -> Elimination<T> {
    buf.elim = Poly::new(std::mem::take(&mut buf.elim))
        .trim_negligible()
        .into_coeffs();
    stats.coeff_bits = T::coeff_bits(&buf.elim);
    match buf.elim.len() {
        0 => return Elimination::Verdict(Verdict::Infinite),
        1 => return Elimination::Verdict(Verdict::NoCommonRoot),
        _ => {}
    }
    let sources = originals(f);
    stats.v_degree = sources[0].map_or(0, |g| deg_v(f[g]));
    Elimination::Eliminant {
        candidates: false,
        derived: Vec::new(),
        originals: sources,
        resultant: true,
    }
}

/// Inputs whose largest coefficient lies outside `[2^-EXTREME_SCALE_EXP, 2^EXTREME_SCALE_EXP]`
/// are first scaled by a power of two (exact in `f64`, same roots) to a largest coefficient in
/// `[1, 2)`: a bicubic resultant multiplies six coefficients and Stam's loop divides by
/// leading ones, so inputs near `1e±300` would overflow to infinity or underflow to zero long
/// before their roots were found. `2^64` keeps every product of six coefficients (`2^384`)
/// far inside the range of `f64`, and leaves the systems of real scenes (coefficients of
/// patches and rays in scene units) unscaled, so their arithmetic is unchanged.
pub(crate) const EXTREME_SCALE_EXP: i32 = 64;

/// The power of two [`EXTREME_SCALE_EXP`] asks for on these coefficients: `1.0` (no scaling)
/// when the largest `|c|` is inside the range or zero, else `2^k` with `2^k·max|c| ∈ [1, 2)`.
pub(crate) fn extreme_scale(coeffs: &[f64]) -> f64 {
    let max = coeffs.iter().fold(0.0f64, |m, c| m.max(c.abs()));
    if max == 0.0 || !max.is_finite() {
        return 1.0;
    }
    let e = max.log2().floor() as i32;
    if e.abs() <= EXTREME_SCALE_EXP {
        return 1.0;
    }
    // 2^-e in two factors, so that neither over- nor underflows for |e| up to 1074.
    let half = -e / 2;
    (f64::from(half)).exp2() * (f64::from(-e - half)).exp2()
}

/// Drops trailing exact zeros (as [`Poly::new`]).
pub(crate) fn trim_zeros<T: poly::Scalar>(c: &mut Vec<T>) {
    while c.last().is_some_and(|x| x.is_zero()) {
        c.pop();
    }
}

/// An element of an `f64` Gröbner basis offered to the certificate, with its bound `Ē` on
/// `|ĝ|` at the common roots in the box (`tracked::certificate_bound`).
pub(crate) enum Certifiable<'a> {
    /// A non-zero constant `c`.
    Constant { c: f64, bound: f64 },
    /// A non-constant element in `u` alone, coefficients lowest power first.
    Univariate { e: &'a [f64], bound: f64 },
}

/// `f64` Gröbner elimination accepted only where it is certified (`paper-notes/groebner.md`
/// §5): at every common root in the box `|ĝ(u_r)| ≤ Ē`.
///
/// * A constant `c` with `|c| > Ē` certifies that no common root lies in the box.
/// * A univariate `ê` certifies that every common root's `u` lies in
///   `Z = {u : |ê(u)| ≤ Ē}`; if each component of `Z` is narrower than [`CERT_WIDTH_REL`] of
///   the box ([`poly::near_zero_components_into`]), its midpoint is a `u`-candidate from which
///   the polish on `F1`, `F2` reaches any root in it.
///
/// `None` otherwise: the basis says nothing reliable and the caller solves the resultant.
/// `v` is taken from `F1`, `F2` themselves (`originals`): the `f64` elements involving `v`
/// are not trusted.
pub(crate) fn certify<T>(
    element: Certifiable<'_>,
    ub: [f64; 2],
    x_tol: f64,
    originals: [Option<usize>; 2],
    buf: &mut Buffers<T>,
    stats: &mut SolveStats,
) -> Option<Elimination<T>> {
    match element {
        Certifiable::Constant { c, bound } => {
            (c.abs() > bound).then_some(Elimination::Verdict(Verdict::NoCommonRoot))
        }
        Certifiable::Univariate { e, bound } => {
            let max_width = CERT_WIDTH_REL * (ub[1] - ub[0]).max(x_tol);
            buf.u_radius = near_zero_components_into(
                e,
                bound,
                ub,
                x_tol,
                max_width,
                &mut buf.near,
                &mut buf.u_roots,
            )?;
            stats.u_degree = e.len() - 1;
            Some(Elimination::Eliminant {
                candidates: true,
                derived: Vec::new(),
                originals,
                resultant: false,
            })
        }
    }
}

/// Steps 2–4 of the module docs on the elimination's result: the verified roots go to
/// `buf.roots` (sorted by `u` then `v`), the verdict is returned.
pub(crate) fn find_roots<T: SolveScalar, P: Rows<T>, Q: Rows<f64>>(
    system: [&P; 2],
    system_f64: [&Q; 2],
    elimination: Elimination<T>,
    opts: &SolveOptions,
    buf: &mut Buffers<T>,
    stats: &mut SolveStats,
) -> Verdict {
    buf.roots.clear();
    let (candidates, derived, originals, resultant) = match elimination {
        Elimination::Verdict(v) => return v,
        Elimination::Eliminant {
            candidates,
            derived,
            originals,
            resultant,
        } => (candidates, derived, originals, resultant),
    };
    let (ub, vb) = (widened(opts.u_range, opts), widened(opts.v_range, opts));
    if !candidates {
        trim_zeros(&mut buf.elim);
        stats.u_degree = buf.elim.len().saturating_sub(1);
        buf.u_roots.clear();
        T::real_roots_into(
            &mut buf.elim,
            ub,
            opts.x_tol,
            &mut buf.root_stats,
            &mut buf.u_roots,
        );
        if !T::EXACT {
            // Exact isolation sees multiple roots exactly; f64 coefficients can split one.
            buf.elim_f64.clear();
            buf.elim_f64
                .extend(buf.elim.iter().map(poly::Scalar::nearest_f64));
            near_double_roots_into(
                &buf.elim_f64,
                ub,
                opts.x_tol,
                NEAR_DOUBLE_REL,
                &mut buf.near,
                &mut buf.u_roots,
            );
        }
    }
    if !candidates {
        buf.u_radius = 0.0;
    }
    stats.u_roots = buf.u_roots.len();
    // v-candidates are searched a Newton step beyond the box: a u-candidate off by δ moves
    // the v of F1(u, ·) by ~|dv/du|·δ, which near an edge can leave the box although the
    // polished root is inside (the box test applies after polishing).
    let margin = NEWTON_MAX_STEP_REL * (vb[1] - vb[0]).max(opts.x_tol);
    let v_search = [vb[0] - margin, vb[1] + margin];
    let u_err_f64 = U_ERR_X_TOLS * opts.x_tol;
    let pair_gap = NEAR_PAIR_REL * (ub[1] - ub[0]);
    for k in 0..buf.u_roots.len() {
        let u = buf.u_roots[k];
        let before = buf.roots.len();
        // A candidate with a neighbour this close is one of a split double root of the `f64`
        // eliminant (two hits sharing one `u`, or a tangency): it is only known to about that
        // distance, not to `x_tol`, and a source that vanishes identically at the true `u`
        // must be seen to vanish here too (else its lone `v` hides the other hits at `u`).
        let gap = [k.wrapping_sub(1), k + 1]
            .iter()
            .filter_map(|&j| buf.u_roots.get(j))
            .map(|&w| (w - u).abs())
            .fold(f64::INFINITY, f64::min);
        let u_err_k = if !T::EXACT && gap < pair_gap {
            u_err_f64.max(gap)
        } else {
            u_err_f64
        };
        // Step 3: the first source that does not vanish at u gives the candidates; if none of
        // them verifies (an ill-conditioned element, or an extraneous u-root), the next
        // sources, ending with F1 and F2 (the gcd of F1(u, ·), F2(u, ·)), are tried.
        for g in derived.iter() {
            // In exact mode a derived element is retried at u-roots narrowed exactly to
            // SHARPEN_BITS: its v can be arbitrarily sensitive to u.
            let mut rejected = 0;
            for level in std::iter::once(None).chain(SHARPEN_BITS.iter().copied().map(Some)) {
                let (ut, u_err) = match level {
                    None => (T::from_f64_exact(u), u_err_k),
                    Some(bits) => (
                        T::sharpen_root(&buf.elim, u, opts.x_tol, bits),
                        (-f64::from(bits)).exp2(),
                    ),
                };
                let (Some(ut), Some(u_err)) = (ut, T::from_f64(u_err)) else {
                    continue;
                };
                if !v_candidates(g, &ut, &u_err, v_search, opts.x_tol, buf) {
                    continue; // g(u, v) ≡ 0
                }
                rejected = verify_candidates(system_f64, ut.nearest_f64(), opts, [ub, vb], buf);
                if buf.roots.len() > before {
                    break;
                }
            }
            stats.rejected += rejected;
            if buf.roots.len() > before {
                break;
            }
        }
        if buf.roots.len() > before {
            continue;
        }
        let (Some(ut), Some(u_err)) = (T::from_f64_exact(u), T::from_f64(u_err_k)) else {
            continue;
        };
        for &g in originals.iter().flatten() {
            if !v_candidates(system[g], &ut, &u_err, v_search, opts.x_tol, buf) {
                continue; // g(u, ·) ≡ 0
            }
            stats.rejected += verify_candidates(system_f64, u, opts, [ub, vb], buf);
            if buf.roots.len() > before {
                break;
            }
        }
        // No root at u. If F1(u, ·) and F2(u, ·) both vanish identically there (to first
        // order in the candidate's error), the line u = u_r is common to both curves: a
        // factor in u alone of F1 and F2, whose points Newton cannot polish (the Jacobian
        // vanishes on it).
        let Some(u_err) = T::from_f64(u_err_f64 + buf.u_radius) else {
            continue;
        };
        if buf.roots.len() == before && system.iter().all(|g| vanishes_at(*g, &ut, &u_err)) {
            buf.roots.clear();
            return Verdict::Infinite;
        }
    }
    merge_and_sort(&mut buf.roots, &mut buf.merged, opts.x_tol);
    if T::EXACT && resultant && buf.roots.is_empty() && no_common_root_at_all(system) {
        return Verdict::NoCommonRoot;
    }
    Verdict::Finite
}

/// Whether `F1 = F2 = 0` has no common root at all, real or complex — the resultant's roots
/// all "at `v = ∞`" (issue 10, item 5). Exact, on the exact values of the inputs: with
/// `g = gcd(lc_v F1, lc_v F2)`, every root of `Res_v` must be a root of `g` (the resultant
/// stripped of `g`'s factors is constant), and then the common roots all have `g(u) = 0`, so
/// `1 ∈ (F1, F2, g)` (Buchberger, Theorem 1) decides. That costs milliseconds, so `f64` inputs
/// first try the modular proof that a common root exists ([`proves_common_root`]), which
/// settles ordinary systems in microseconds. The per-ray path does not ask (a miss is a miss
/// to the tracer); exact solves ask in [`find_roots`], `f64` ones in [`solve`](crate::solve).
pub(crate) fn no_common_root_at_all<T: SolveScalar, P: Rows<T>>(f: [&P; 2]) -> bool {
    if !T::EXACT {
        let as_f64 = |p: &P| -> (Vec<f64>, usize) {
            let stride = p.rows().next().map_or(0, <[T]>::len);
            (
                p.flat().iter().map(poly::Scalar::nearest_f64).collect(),
                stride,
            )
        };
        let ((c1, s1), (c2, s2)) = (as_f64(f[0]), as_f64(f[1]));
        if s1 == 0 || s2 == 0 {
            return false;
        }
        if proves_common_root([c1.chunks_exact(s1), c2.chunks_exact(s2)]) {
            return false;
        }
    }
    let exact = |p: &P| -> Option<BiPoly<Rat>> {
        let stride = p.rows().next().map_or(0, <[T]>::len);
        let coeffs = p
            .flat()
            .iter()
            .map(SolveScalar::to_rat)
            .collect::<Option<Vec<_>>>()?;
        let rows = coeffs.len().checked_div(stride).unwrap_or(0);
        Some(BiPoly::from_grid(stride, rows, coeffs))
    };
    let (Some(f1), Some(f2)) = (exact(f[0]), exact(f[1])) else {
        return false;
    };
    let lc_q = |p: &BiPoly<Rat>| Poly::new(p.rows_iter().nth(p.deg_v()).unwrap_or(&[]).to_vec());
    let g = lc_q(&f1).gcd(&lc_q(&f2));
    if g.degree() == 0 {
        return false;
    }
    let Ok(mut rest) = sylvester_resultant_v(&f1, &f2) else {
        return false;
    };
    if rest.is_zero() {
        return false;
    }
    loop {
        let h = rest.gcd(&g);
        if h.degree() == 0 {
            break;
        }
        rest = rest.div_rem(&h).map_or(rest, |(q, _)| q);
    }
    if rest.degree() > 0 {
        return false;
    }
    buchberger(&[f1, f2, BiPoly::from_poly_u(&g)]).is_ok_and(|b| b.contains_unit())
}

/// The search range widened by `x_tol` on both sides (a root on a patch edge must not be lost
/// to round-off).
pub(crate) fn widened(r: [f64; 2], opts: &SolveOptions) -> [f64; 2] {
    [r[0] - opts.x_tol, r[1] + opts.x_tol]
}

/// Polishes every `v`-candidate in `buf.v_roots` at `u` and keeps the verified ones in
/// `buf.roots`; returns how many were rejected.
fn verify_candidates<T, Q: Rows<f64>>(
    system_f64: [&Q; 2],
    u: f64,
    opts: &SolveOptions,
    [ub, vb]: [[f64; 2]; 2],
    buf: &mut Buffers<T>,
) -> usize {
    let mut rejected = 0;
    for i in 0..buf.v_roots.len() {
        let v = buf.v_roots[i];
        match polish_and_verify(
            |k, u, v| eval_grad_rows(system_f64[k].rows(), u, v),
            u,
            v,
            opts,
            ub,
            vb,
        ) {
            Some(r) => buf.roots.push(r),
            None => rejected += 1,
        }
    }
    rejected
}

/// The coefficient `c` of one row of `g` at `ut` (Horner), the size `s` of its terms and a
/// bound `ds` on the size of its derivative over `|u| ≤ |ut| + u_err`.
fn row_at<T: SolveScalar>(row: &[T], ut: &T, u_err: &T) -> (T, T, T) {
    let au_wide = ut.abs() + u_err;
    let (mut c, mut s, mut ds) = (T::zero(), T::zero(), T::zero());
    for a in row.iter().rev() {
        c = c * ut + a;
        ds = ds * &au_wide + &s;
        s = s * &au_wide + a.abs();
    }
    (c, s, ds)
}

/// Whether `|c| ≤ 2·u_err·ds`: the first-order bound on `|c(ut) − c(u_r)|` cannot certify
/// `c(u_r) ≠ 0` ([`v_candidates`]).
fn within_first_order<T: SolveScalar>(c: &T, u_err: &T, ds: T) -> bool {
    c.abs() <= (T::one() + T::one()) * u_err * ds
}

/// Whether every coefficient of `g(u_r, ·)` may vanish: [`v_candidates`]' test, or (`f64`)
/// the first-order test, which also holds for coefficients that vanish linearly at a root
/// near `u = 0` (where the relative test cannot).
fn vanishes_at<T: SolveScalar>(g: &impl Rows<T>, ut: &T, u_err: &T) -> bool {
    let vanish = T::from_f64(VANISH_REL).expect("a small constant");
    g.rows().all(|row| {
        let (c, s, ds) = row_at(row, ut, u_err);
        (!T::EXACT && c.abs() <= vanish.clone() * s) || within_first_order(&c, u_err, ds)
    })
}

/// Candidate `v` values at `u` from one source `g`: the real roots of `g(u, ·)` in `vb`, into
/// `buf.v_roots`; `false` when `g(u, ·)` vanishes identically.
///
/// "Vanishes" is decided per coefficient `c_j(u)` of `v^j`:
/// * `f64` sources: `|c_j(u)|` below [`VANISH_REL`] times the size of its terms, or, for a
///   candidate of a near pair (`u_err` above `U_ERR_X_TOLS·x_tol`, [`NEAR_PAIR_REL`]), within
///   the first-order bound below;
/// * exact sources, evaluated exactly at the rational `ut` that lies within `u_err` of the true
///   root `u_r`: `|c_j(ut)| ≤ 2·u_err·Σ i|a_i|(|ut| + u_err)^{i−1}`, i.e. when the first-order
///   bound on `|c_j(ut) − c_j(u_r)|` cannot certify `c_j(u_r) ≠ 0`. No fixed threshold: a
///   coefficient that is small only because its terms cancel (a shape element `v + h(u)` with
///   huge `h` at a root, `paper-notes/groebner.md` §5) is kept once `ut` is close enough.
fn v_candidates<T: SolveScalar>(
    g: &impl Rows<T>,
    ut: &T,
    u_err: &T,
    vb: [f64; 2],
    x_tol: f64,
    buf: &mut Buffers<T>,
) -> bool {
    buf.v_poly.clear();
    buf.v_roots.clear();
    let vanish = T::from_f64(VANISH_REL).expect("a small constant");
    // An f64 candidate known only to a near pair's gap ([`find_roots`]): the first-order test
    // too, with that error.
    let pair = T::from_f64(U_ERR_X_TOLS * x_tol).is_some_and(|e| *u_err > e);
    let mut significant = false;
    for row in g.rows() {
        let (c, s, ds) = row_at(row, ut, u_err);
        let vanished = if T::EXACT {
            within_first_order(&c, u_err, ds)
        } else {
            c.abs() <= vanish.clone() * s || (pair && within_first_order(&c, u_err, ds))
        };
        significant |= !vanished;
        buf.v_poly.push(if vanished { T::zero() } else { c });
    }
    if !significant {
        return false;
    }
    trim_zeros(&mut buf.v_poly);
    match buf.v_poly.len() {
        0 | 1 => {}
        2 => {
            let v = (-buf.v_poly[0].clone() / &buf.v_poly[1]).nearest_f64();
            if v >= vb[0] && v <= vb[1] {
                buf.v_roots.push(v);
            }
        }
        _ => T::real_roots_into(
            &mut buf.v_poly,
            vb,
            x_tol,
            &mut buf.root_stats,
            &mut buf.v_roots,
        ),
    }
    true
}

/// Merges duplicates (closer than [`MERGE_X_TOLS`]` · x_tol` in `u` and `v`) against every
/// kept root — after sorting by `u`, two copies of one root need not be adjacent (another
/// root's `u` can fall between theirs) — then sorts by `u`, then `v`. `scratch` is a reusable
/// buffer; nothing is allocated once it has grown.
pub(crate) fn merge_and_sort(roots: &mut Vec<Root>, scratch: &mut Vec<Root>, x_tol: f64) {
    let merge = MERGE_X_TOLS * x_tol;
    scratch.clear();
    for &r in roots.iter() {
        if !scratch
            .iter()
            .any(|a| (a.u - r.u).abs() <= merge && (a.v - r.v).abs() <= merge)
        {
            scratch.push(r);
        }
    }
    std::mem::swap(roots, scratch);
    // Equal keys under total_cmp are equal bits, so an unstable sort gives the stable order
    // (and, unlike the stable sort, never allocates).
    roots.sort_unstable_by(|a, b| a.u.total_cmp(&b.u).then(a.v.total_cmp(&b.v)));
}

/// Value, gradient and term size `A = Σ|a_ij||u|^i|v|^j` at `(u, v)` of the polynomial whose
/// rows (coefficients of `v^j`, each lowest power of `u` first) are `rows`, lowest `j` first,
/// in one nested Horner pass (no allocation).
pub(crate) fn eval_grad_rows<'a>(
    rows: impl DoubleEndedIterator<Item = &'a [f64]>,
    u: f64,
    v: f64,
) -> (f64, f64, f64, f64) {
    let (au, av) = (u.abs(), v.abs());
    let (mut f, mut fu, mut fv, mut a) = (0.0, 0.0, 0.0, 0.0);
    for row in rows.rev() {
        let (mut r, mut dr, mut ar) = (0.0, 0.0, 0.0);
        for &c in row.iter().rev() {
            dr = dr * u + r;
            r = r * u + c;
            ar = ar * au + c.abs();
        }
        fv = fv * v + f;
        f = f * v + r;
        fu = fu * v + dr;
        a = a * av + ar;
    }
    (f, fu, fv, a)
}

/// Newton-polishes `(u, v)` on the system and applies the residual test of [`Root`].
/// `eval_grad(k, u, v)` gives `(F_k, ∂F_k/∂u, ∂F_k/∂v, Σ|terms|)` of equation `k` (0 or 1).
pub(crate) fn polish_and_verify(
    eval_grad: impl Fn(usize, f64, f64) -> (f64, f64, f64, f64),
    mut u: f64,
    mut v: f64,
    opts: &SolveOptions,
    ub: [f64; 2],
    vb: [f64; 2],
) -> Option<Root> {
    let max_step = NEWTON_MAX_STEP_REL * (ub[1] - ub[0]).max(vb[1] - vb[0]).max(opts.x_tol);
    // Residual measure: the worse of the two relative residuals.
    let measure = |e: &[(f64, f64, f64, f64); 2]| {
        e.iter()
            .map(|&(f, _, _, a)| f.abs() / a.max(f64::MIN_POSITIVE))
            .fold(0.0, f64::max)
    };
    let mut e = [eval_grad(0, u, v), eval_grad(1, u, v)];
    let mut r = measure(&e);
    for _ in 0..NEWTON_STEPS {
        let ((f, fu, fv, _), (g, gu, gv, _)) = (e[0], e[1]);
        let det = fu * gv - fv * gu;
        if det == 0.0
            || !det.is_finite()
            || det.abs() <= f64::EPSILON * (fu * gv).abs().max((fv * gu).abs())
        {
            break;
        }
        let du = (f * gv - g * fv) / det;
        let dv = (g * fu - f * gu) / det;
        if !(du.abs() <= max_step && dv.abs() <= max_step) {
            break;
        }
        let (nu, nv) = (u - du, v - dv);
        let ne = [eval_grad(0, nu, nv), eval_grad(1, nu, nv)];
        let nr = measure(&ne);
        if nr.is_nan() || nr >= r {
            break;
        }
        (u, v, e, r) = (nu, nv, ne, nr);
    }
    let ok = e
        .iter()
        .all(|&(f, fu, fv, a)| f.abs() <= opts.f_tol_rel * a + (fu.abs() + fv.abs()) * opts.x_tol);
    let inside = u >= ub[0] && u <= ub[1] && v >= vb[0] && v <= vb[1];
    (ok && inside).then_some(Root { u, v })
}

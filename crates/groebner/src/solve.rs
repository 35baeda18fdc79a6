//! Solving `F1(u, v) = F2(u, v) = 0` in a box: eliminate `v` (Gröbner basis or resultant),
//! find the real roots of the `u`-polynomial with `poly`, back-substitute for `v`, polish on the
//! original equations and verify (article §4.3–4.4; `Roots`, `VPol`, `VRoots` in `ray3.c`).
//! See `paper-notes/groebner.md` §5 and `paper-notes/resultant.md` §3.

use poly::{BiPoly, Poly, RootOptions, RootStats, Scalar};

use crate::basis::Basis;
use crate::buchberger::{buchberger_tracked, reduce_tracked_keep};
use crate::error::Error;
use crate::resultant::{bezout_resultant_v, sylvester_resultant_v};
use crate::roots::SolveScalar;
use crate::stam::stam_tracked_until;
use crate::tracked::Tracked;

/// Default [`SolveOptions::x_tol`]: roots are located to `1e-10` in `u` and `v` (a Bézier
/// patch spans `[0, 1]²`, so this is 1e-10 of the patch's parameter width).
pub const DEFAULT_X_TOL: f64 = 1e-10;

/// Default [`SolveOptions::f_tol_rel`], `2⁻³⁰ ≈ 9.3e-10`.
///
/// A true root, polished by Newton's method on `F1`, `F2`, leaves a residual near the
/// evaluation round-off `γ(2(deg_u + deg_v) + 2)·A ≈ 1.6e-15·A` for a bicubic (`A` the sum of
/// the absolute values of the terms at the point). Near a tangency (a double root) the residual
/// only falls quadratically with the position error, so the margin is wide: 2⁻³⁰ accepts
/// tangential hits located to about `√(2⁻³⁰) ≈ 3e-5` and rejects a candidate whose curves are
/// apart by more. Extraneous candidates (a `u`-root whose common `v` is complex or at infinity)
/// have residuals of order `A` and fail by many orders of magnitude.
pub const DEFAULT_F_TOL_REL: f64 = 1.0 / (1u64 << 30) as f64;

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
/// residual test rejects (see `near_double_roots`).
pub(crate) const NEAR_DOUBLE_REL: f64 = 1.0 / (1u64 << 26) as f64;

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

/// How `v` is eliminated.
///
/// All four are exact over `Rat`. Over `f64` they differ sharply: Gröbner elimination is a
/// long chain of cancellations (a polynomial remainder sequence in `u`) that round-off turns
/// into noise beyond eliminant degree ~6 — the instability Stam reports (article §5). So over
/// `f64` the Gröbner methods keep, for every basis element, a bound on its distance to the
/// ideal (the `tracked` module), and use the basis only where that bound *certifies* it: a
/// constant larger than its bound (no root in the box), or an eliminant whose near-zero set
/// `{u : |ê(u)| ≤ bound}` is a few narrow intervals, each searched from its midpoint with `v`
/// from `F1`, `F2`. Otherwise they solve the Bézout resultant instead
/// ([`SolveStats::fallback`]). Measured on the teapot (`paper-notes/groebner.md` §5) the
/// certificate holds on ~7% of the ray/piece systems that pass the tracer's hull test (Stam's
/// loop per ray, stopped at its first eliminant: `fast.rs`); the result always matches the
/// resultant's. The resultants are determinants of matrices of low-degree coefficients and
/// stay accurate to degree 18. Hence the default, [`Method::BezoutResultant`].
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
#[non_exhaustive]
pub enum Method {
    /// Stam's simplified two-polynomial Gröbner loop ([`stam_basis`](crate::stam_basis)).
    Stam,
    /// Buchberger's algorithm and the reduced basis ([`buchberger`](crate::buchberger)).
    Buchberger,
    /// Kajiya's approach: `Res_v(F1, F2)` by Sylvester's matrix
    /// ([`sylvester_resultant_v`](crate::sylvester_resultant_v)).
    Resultant,
    /// As [`Method::Resultant`] with Bézout's smaller matrix
    /// ([`bezout_resultant_v`](crate::bezout_resultant_v)): 3 × 3 instead of 6 × 6 for a
    /// bicubic. The default.
    #[default]
    BezoutResultant,
}

/// Options of [`solve`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SolveOptions {
    /// The elimination method.
    pub method: Method,
    /// The `u`-interval searched (closed). Default `[0, 1]`.
    pub u_range: [f64; 2],
    /// The `v`-interval searched (closed). Default `[0, 1]`.
    pub v_range: [f64; 2],
    /// Tolerance on root positions (absolute, in `u` and `v` units): `u`-roots are refined to
    /// it, the box is widened by it (so a root on a patch edge is not lost to round-off), and
    /// the residual test allows for it. Default [`DEFAULT_X_TOL`].
    pub x_tol: f64,
    /// Relative residual accepted at a root, see [`Root`] and [`DEFAULT_F_TOL_REL`].
    pub f_tol_rel: f64,
}

impl Default for SolveOptions {
    fn default() -> Self {
        SolveOptions {
            method: Method::default(),
            u_range: [0.0, 1.0],
            v_range: [0.0, 1.0],
            x_tol: DEFAULT_X_TOL,
            f_tol_rel: DEFAULT_F_TOL_REL,
        }
    }
}

/// A verified common root `(u, v)`.
///
/// Verified means: for both `k = 1, 2`,
/// `|F_k(u, v)| ≤ f_tol_rel · A_k(u, v) + (|∂F_k/∂u| + |∂F_k/∂v|) · x_tol`,
/// where `A_k(u, v) = Σ|a_ij||u|^i|v|^j` is the size of `F_k`'s terms at the point (the scale of
/// its evaluation round-off) and the gradient term allows for the position tolerance.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Root {
    /// The `u` coordinate.
    pub u: f64,
    /// The `v` coordinate.
    pub v: f64,
}

/// What the elimination says about the complex common roots (article Theorems 1–3).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
#[non_exhaustive]
pub enum Verdict {
    /// No common root at all, real or complex (`1 ∈ G`, Theorem 1; or a non-zero constant
    /// resultant): the ray misses. From an `f64` Gröbner basis: a constant element certified
    /// larger than its error bound over the box, which proves only that no common root lies in
    /// the box (see [`Method`]).
    NoCommonRoot,
    /// Finitely many common roots; the real ones in the box are in [`Solution::roots`].
    Finite,
    /// The curves share a whole component (infinitely many common roots: the ray runs inside
    /// the surface, e.g. along a ruling); no points are reported.
    Infinite,
}

/// Per-solve statistics (the article's table reports the first three per image, §5).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub struct SolveStats {
    /// Number of basis elements (Gröbner methods); 0 for the resultant methods.
    pub basis_size: usize,
    /// Degree of the univariate polynomial in `u` (eliminant or resultant); 0 if none.
    pub u_degree: usize,
    /// `v`-degree of the first polynomial substituted into (the basis element of lowest
    /// positive `Deg_v`, article §4.4; `min Deg_v(F1, F2)` for resultants); 0 if none.
    pub v_degree: usize,
    /// Exact mode only: the largest coefficient, in bits, of the basis elements or resultant,
    /// each scaled to a primitive integer polynomial (coprime integer coefficients).
    pub coeff_bits: Option<u64>,
    /// `u` candidates: real roots of the `u`-polynomial in the (widened) `u`-range, plus, in
    /// `f64` mode, its near-double roots.
    pub u_roots: usize,
    /// `(u, v)` candidates rejected by the residual test (extraneous factors, complex `v`).
    pub rejected: usize,
    /// `f64` Gröbner methods only: the basis could not be certified (see [`Method`]) and the
    /// Bézout resultant was solved instead; `u_degree` is then the resultant's.
    pub fallback: bool,
}

/// The outcome of [`solve`].
#[derive(Clone, Debug, PartialEq)]
pub struct Solution {
    /// Verified roots in the box, sorted by `u` then `v`.
    pub roots: Vec<Root>,
    /// What the algebra says about all complex roots.
    pub verdict: Verdict,
    /// Statistics of this solve.
    pub stats: SolveStats,
}

/// Solves `F1(u, v) = F2(u, v) = 0` for the real roots in `u_range × v_range`.
///
/// 1. Eliminate `v` with `opts.method`: the `u`-eliminant of a Gröbner basis (Theorem 3) or the
///    resultant `Res_v(F1, F2)`. `1 ∈ G`, or a non-zero constant resultant, means no common
///    root (Theorem 1).
/// 2. Real roots `u_r` of that polynomial in the `u`-range widened by `x_tol`, by
///    `poly`'s certified isolation and refinement (exact rational isolation in exact mode).
///    In `f64` mode, critical points where the polynomial nearly vanishes are added as
///    candidates: two hits with the same `u` make a double root, which rounding can turn into
///    a complex pair (see `NEAR_DOUBLE_REL`).
/// 3. For each `u_r`, candidates `v`: the real roots in the widened `v`-range of the first of
///    the basis elements involving `v` (lowest `Deg_v` first, then `F1` and `F2`; for
///    resultants `F1`, `F2`) that does not vanish identically at `u_r`. The roots of the common
///    part `gcd(F1(u_r, ·), F2(u_r, ·))` are among them, and the basis element is not assumed
///    to be linear in `v` (shape form fails, e.g. on the teapot rim). In exact mode a derived
///    element whose candidates do not verify is retried at the `u`-root narrowed exactly (to
///    `SHARPEN_BITS`): a shape element `v + h(u)` can have `|h'| ~ 1e18` at a root, so the
///    `f64` value of `u_r` is not precise enough to substitute into it.
/// 4. Each candidate is polished by Newton's method on `F1`, `F2` and kept if it passes the
///    residual test of [`Root`] and lies in the widened box; duplicates closer than `4·x_tol`
///    are merged. This is where extraneous factors (a `u`-root with only complex `v`, the
///    factor `u^k` of a resultant when both leading coefficients in `v` vanish) are rejected.
///
/// # Accuracy
/// Roots returned satisfy the residual test of [`Root`]; for a simple root (transversal
/// intersection) the position error is then about the residual divided by the smallest singular
/// value of the Jacobian. Not promised: tangential (double) roots may be reported once, or
/// missed when the residual stays above the test; two roots closer than `4·x_tol` are merged.
/// Over `f64` the elimination is a heuristic (see the crate's zero rule): a root is lost if
/// round-off moves the eliminant's root by more than the Newton polish can recover
/// (`NEWTON_MAX_STEP_REL` of the box). In exact mode (`T = Rat`) the eliminant and its real
/// roots are exact, and only steps 3–4 use `f64`. Smaller `x_tol` costs a few more refinement
/// steps per root (logarithmic).
///
/// # Errors
/// [`Error::NonFinite`] for NaN/infinite coefficients, [`Error::InvalidRange`] and
/// [`Error::InvalidTolerance`] for bad options, [`Error::LimitExceeded`] /
/// [`Error::MatrixTooLarge`] from the elimination.
///
/// # Examples
/// ```
/// use groebner::{solve, SolveOptions, Verdict};
/// use poly::BiPoly;
/// // Circle u² + v² = 1/2 and line v = u meet in [0, 1]² at (1/2, 1/2).
/// let circle = BiPoly::from_terms([(1.0, 2, 0), (1.0, 0, 2), (-0.5, 0, 0)]);
/// let line = BiPoly::from_terms([(1.0, 0, 1), (-1.0, 1, 0)]);
/// let sol = solve(&circle, &line, &SolveOptions::default())?;
/// assert_eq!(sol.verdict, Verdict::Finite);
/// assert_eq!(sol.roots.len(), 1);
/// assert!((sol.roots[0].u - 0.5).abs() < 1e-12 && (sol.roots[0].v - 0.5).abs() < 1e-12);
/// // Resultant: u_degree 2 (u² = 1/4); with Method::Stam the basis has 2 elements.
/// assert_eq!((sol.stats.u_degree, sol.stats.v_degree), (2, 1));
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn solve<T: SolveScalar>(
    f1: &BiPoly<T>,
    f2: &BiPoly<T>,
    opts: &SolveOptions,
) -> Result<Solution, Error> {
    // Systems of degree ≤ 3 over f64 by Stam or Bézout: the allocation-free path (`fast.rs`),
    // the same arithmetic in fixed-size buffers.
    if let Some(found) = T::solve_fast(f1, f2, opts) {
        return found;
    }
    solve_general(f1, f2, opts)
}

/// [`solve`] by the general path (any degree, any method, exact or `f64`).
pub(crate) fn solve_general<T: SolveScalar>(
    f1: &BiPoly<T>,
    f2: &BiPoly<T>,
    opts: &SolveOptions,
) -> Result<Solution, Error> {
    check_options(opts)?;
    if !T::EXACT {
        if !f1.coeffs().iter().all(|c| c.nearest_f64().is_finite()) {
            return Err(Error::NonFinite { what: "F1" });
        }
        if !f2.coeffs().iter().all(|c| c.nearest_f64().is_finite()) {
            return Err(Error::NonFinite { what: "F2" });
        }
    }
    let mut stats = SolveStats::default();
    let widen = |r: [f64; 2]| [r[0] - opts.x_tol, r[1] + opts.x_tol];
    let (ub, vb) = (widen(opts.u_range), widen(opts.v_range));
    let elim = match opts.method {
        Method::Stam | Method::Buchberger => {
            eliminate_groebner(f1, f2, opts.method, [ub, vb], opts.x_tol, &mut stats)?
        }
        Method::Resultant | Method::BezoutResultant => {
            eliminate_resultant(f1, f2, opts.method, &mut stats)?
        }
    };
    let (eliminant, v_sources, originals, u_candidates) = match elim {
        Elimination::Verdict(verdict) => {
            return Ok(Solution {
                roots: Vec::new(),
                verdict,
                stats,
            });
        }
        Elimination::Eliminant {
            eliminant,
            v_sources,
            originals,
            u_candidates,
        } => (eliminant, v_sources, originals, u_candidates),
    };
    stats.u_degree = eliminant.degree();
    let u_roots = match u_candidates {
        Some(c) => c,
        None => {
            let mut u_roots = T::real_roots_in(&eliminant, ub, opts.x_tol);
            if !T::EXACT {
                near_double_roots(&eliminant, ub, opts.x_tol, &mut u_roots);
            }
            u_roots
        }
    };
    stats.u_roots = u_roots.len();

    let system = [f1.map(Scalar::nearest_f64), f2.map(Scalar::nearest_f64)];
    // v-candidates are searched a Newton step beyond the box: a u-candidate off by δ moves
    // the v of F1(u, ·) by ~|dv/du|·δ, which near an edge can leave the box although the
    // polished root is inside (the box test applies after polishing).
    let margin = NEWTON_MAX_STEP_REL * (vb[1] - vb[0]).max(opts.x_tol);
    let v_search = [vb[0] - margin, vb[1] + margin];
    let mut roots: Vec<Root> = Vec::new();
    for &u in &u_roots {
        // Step 3: the first source that does not vanish at u gives the candidates; if none of
        // them verifies (an ill-conditioned element, or an extraneous u-root), the next
        // sources, ending with F1 and F2 (the gcd of F1(u, ·), F2(u, ·)), are tried.
        for (index, g) in v_sources.iter().enumerate() {
            // In exact mode a derived element (not F1, F2) is retried at u-roots narrowed
            // exactly to SHARPEN_BITS: its v can be arbitrarily sensitive to u.
            let derived = T::EXACT && index + originals < v_sources.len();
            let levels: &[u32] = if derived { &SHARPEN_BITS } else { &[] };
            let mut rejected = 0;
            let before = roots.len();
            for level in std::iter::once(None).chain(levels.iter().copied().map(Some)) {
                // ut within u_err of the root: 2·x_tol covers real_roots_in's x_tol.
                let (ut, u_err) = match level {
                    None => (T::from_f64_exact(u), 2.0 * opts.x_tol),
                    Some(bits) => (
                        T::sharpen_root(&eliminant, u, opts.x_tol, bits),
                        (-f64::from(bits)).exp2(),
                    ),
                };
                let (Some(ut), Some(u_err)) = (ut, T::from_f64(u_err)) else {
                    continue;
                };
                let Some(candidates) = v_candidates(g, &ut, &u_err, v_search, opts.x_tol) else {
                    continue; // g(u, v) ≡ 0
                };
                let uf = ut.nearest_f64();
                rejected = 0;
                for v in candidates {
                    match polish_and_verify(
                        |k, u, v| eval_grad(&system[k], u, v),
                        uf,
                        v,
                        opts,
                        ub,
                        vb,
                    ) {
                        Some(r) => roots.push(r),
                        None => rejected += 1,
                    }
                }
                if roots.len() > before {
                    break;
                }
            }
            stats.rejected += rejected;
            if roots.len() > before {
                break;
            }
        }
    }
    // Merge duplicates against every kept root: after sorting by u, two copies of one root
    // need not be adjacent (another root's u can fall between theirs).
    let merge = 4.0 * opts.x_tol;
    let mut unique: Vec<Root> = Vec::with_capacity(roots.len());
    for r in roots {
        if !unique
            .iter()
            .any(|a| (a.u - r.u).abs() <= merge && (a.v - r.v).abs() <= merge)
        {
            unique.push(r);
        }
    }
    let mut roots = unique;
    roots.sort_by(|a, b| a.u.total_cmp(&b.u).then(a.v.total_cmp(&b.v)));
    Ok(Solution {
        roots,
        verdict: Verdict::Finite,
        stats,
    })
}

pub(crate) fn check_options(opts: &SolveOptions) -> Result<(), Error> {
    for (which, r) in [("u", opts.u_range), ("v", opts.v_range)] {
        if !(r[0].is_finite() && r[1].is_finite() && r[0] <= r[1]) {
            return Err(Error::InvalidRange {
                which,
                lo: r[0],
                hi: r[1],
            });
        }
    }
    for (name, value) in [("x_tol", opts.x_tol), ("f_tol_rel", opts.f_tol_rel)] {
        if !(value.is_finite() && value > 0.0) {
            return Err(Error::InvalidTolerance { name, value });
        }
    }
    Ok(())
}

/// Result of the elimination step.
enum Elimination<T> {
    /// Decided without roots to find.
    Verdict(Verdict),
    /// A univariate polynomial in `u` and the polynomials (ordered) that give `v`.
    Eliminant {
        eliminant: Poly<T>,
        v_sources: Vec<BiPoly<T>>,
        /// How many of the last `v_sources` are the input polynomials themselves.
        originals: usize,
        /// Certified `u`-candidates replacing the eliminant's roots (`f64` Gröbner path).
        u_candidates: Option<Vec<f64>>,
    },
}

fn eliminate_groebner<T: SolveScalar>(
    f1: &BiPoly<T>,
    f2: &BiPoly<T>,
    method: Method,
    boxes: [[f64; 2]; 2],
    x_tol: f64,
    stats: &mut SolveStats,
) -> Result<Elimination<T>, Error> {
    if !T::EXACT {
        return eliminate_groebner_f64(f1, f2, method, boxes, x_tol, stats);
    }
    let (_, basis) = tracked_basis(f1, f2, method, |_| false)?.expect("never abandoned");
    stats.basis_size = basis.len();
    stats.coeff_bits = basis.elements().iter().filter_map(T::coeff_bits).max();
    stats.v_degree = basis.v_elements().first().map_or(0, |g| g.deg_v());
    if basis.contains_unit() {
        return Ok(Elimination::Verdict(Verdict::NoCommonRoot));
    }
    let Some(eliminant) = basis.eliminant() else {
        return Ok(Elimination::Verdict(Verdict::Infinite));
    };
    if !basis.has_finitely_many_roots() && is_groebner(&basis) {
        return Ok(Elimination::Verdict(Verdict::Infinite));
    }
    let mut v_sources: Vec<BiPoly<T>> = basis.v_elements().into_iter().cloned().collect();
    v_sources.push(f1.clone());
    v_sources.push(f2.clone());
    Ok(Elimination::Eliminant {
        eliminant,
        v_sources,
        originals: 2,
        u_candidates: None,
    })
}

/// A basis with its error-tracked elements, and the same basis untracked.
type TrackedBasis<T> = (Vec<Tracked<T>>, Basis<T>);

/// The tracked basis of `F1`, `F2` by `method` — Stam's loop, abandoned (`Ok(None)`) as soon
/// as `abort` holds for a new element, or Buchberger's reduced basis — and the same basis
/// untracked. Stam's loop is not proven to give a Gröbner basis, so a list with neither a
/// unit nor a univariate element is completed by Buchberger before anyone concludes that the
/// roots are not finite (Theorem 3 needs a Gröbner basis); the error bounds are carried over.
fn tracked_basis<T: SolveScalar>(
    f1: &BiPoly<T>,
    f2: &BiPoly<T>,
    method: Method,
    abort: impl Fn(&Tracked<T>) -> bool,
) -> Result<Option<TrackedBasis<T>>, Error> {
    let (t1, t2) = (Tracked::new(f1.clone()), Tracked::new(f2.clone()));
    let mut tracked = match method {
        Method::Stam => match stam_tracked_until(t1, t2, abort)? {
            Some(g) => g,
            None => return Ok(None),
        },
        _ => reduce_tracked_keep(buchberger_tracked(vec![t1, t2])?),
    };
    let as_basis = |t: &[Tracked<T>]| Basis::new(t.iter().map(|t| t.poly.clone()).collect());
    let mut basis = as_basis(&tracked);
    if !basis.contains_unit() && basis.univariate_u().is_none() {
        tracked.retain(|t| !t.is_zero());
        tracked = reduce_tracked_keep(buchberger_tracked(tracked)?);
        basis = as_basis(&tracked);
    }
    Ok(Some((tracked, basis)))
}

/// The `f64` Gröbner path: the basis, then [`certify_f64`]. A Stam run is abandoned as soon as
/// a new element is pure noise on the box ([`Tracked::is_noise`]), and a run that exceeds its
/// limits falls back like an uncertified one (neither says anything about the roots).
fn eliminate_groebner_f64<T: SolveScalar>(
    f1: &BiPoly<T>,
    f2: &BiPoly<T>,
    method: Method,
    boxes: [[f64; 2]; 2],
    x_tol: f64,
    stats: &mut SolveStats,
) -> Result<Elimination<T>, Error> {
    let [ub, vb] = boxes;
    let um = T::from_f64(ub[0].abs().max(ub[1].abs())).expect("finite");
    let vm = T::from_f64(vb[0].abs().max(vb[1].abs())).expect("finite");
    let (tracked, basis) = match tracked_basis(f1, f2, method, |t| t.is_noise(&um, &vm)) {
        Ok(Some(found)) => found,
        Ok(None) | Err(Error::LimitExceeded { .. }) => return fallback(f1, f2, stats),
        Err(e) => return Err(e),
    };
    stats.basis_size = basis.len();
    stats.v_degree = basis.v_elements().first().map_or(0, |g| g.deg_v());
    certify_f64(f1, f2, &tracked, &basis, boxes, x_tol, stats)
}

/// The Bézout resultant in place of an uncertified `f64` Gröbner basis.
fn fallback<T: SolveScalar>(
    f1: &BiPoly<T>,
    f2: &BiPoly<T>,
    stats: &mut SolveStats,
) -> Result<Elimination<T>, Error> {
    stats.fallback = true;
    eliminate_resultant(f1, f2, Method::BezoutResultant, stats)
}

/// `f64` Gröbner elimination, accepted only where it is certified (see `paper-notes/groebner.md`
/// §5): each basis element `ĝ` carries a bound `Ē` on its distance to the ideal
/// ([`Tracked::ideal_distance_at`]), so at every common root in the box `|ĝ(u_r)| ≤ Ē`.
///
/// * A constant element `c` with `|c| > Ē` certifies that no common root lies in the box.
/// * A univariate element `ê` certifies that every common root's `u` lies in
///   `Z = {u : |ê(u)| ≤ Ē}`. The components of `Z` are delimited by the real roots of `ê ∓ Ē`
///   (certified isolation by `poly`); if each is narrower than [`CERT_WIDTH_REL`] of the box,
///   its midpoint is a `u`-candidate from which the polish on `F1`, `F2` reaches any root in it.
///
/// Otherwise (a wide component, no univariate element, or a constant below its bound) the
/// `f64` basis says nothing reliable and the Bézout resultant of the same system is used
/// instead ([`SolveStats::fallback`]). `v` is taken from `F1`, `F2` themselves: the `f64`
/// basis elements involving `v` are not trusted.
fn certify_f64<T: SolveScalar>(
    f1: &BiPoly<T>,
    f2: &BiPoly<T>,
    tracked: &[Tracked<T>],
    basis: &Basis<T>,
    boxes: [[f64; 2]; 2],
    x_tol: f64,
    stats: &mut SolveStats,
) -> Result<Elimination<T>, Error> {
    let [ub, vb] = boxes;
    let u_max = ub[0].abs().max(ub[1].abs());
    let v_max = vb[0].abs().max(vb[1].abs());
    let bound_of = |t: &Tracked<T>| {
        let (um, vm) = (
            T::from_f64(u_max).expect("finite"),
            T::from_f64(v_max).expect("finite"),
        );
        // The ideal distance, plus the rounding of evaluating ĝ itself (γ(2n) of its terms),
        // times 2 for the neglected second-order terms.
        let n = t.poly.stride() + t.poly.rows();
        let eval = poly::gamma(2 * n) * t.poly.map(Scalar::nearest_f64).eval_abs(u_max, v_max);
        2.0 * (t.ideal_distance_at(&um, &vm).nearest_f64() + eval)
    };
    let certified = |stats: &mut SolveStats| -> Option<Elimination<T>> {
        if let Some(t) = tracked
            .iter()
            .find(|t| t.poly.is_constant() && !t.is_zero())
        {
            let c = t.poly.coeff(0, 0).nearest_f64().abs();
            return (c > bound_of(t)).then_some(Elimination::Verdict(Verdict::NoCommonRoot));
        }
        let (k, _) = basis.univariate_u()?;
        let t = tracked.iter().filter(|t| !t.is_zero()).nth(k)?;
        let e: Poly<f64> = Poly::new(
            t.poly
                .to_poly_u()?
                .coeffs()
                .iter()
                .map(Scalar::nearest_f64)
                .collect(),
        );
        let bound = bound_of(t);
        let candidates = certified_candidates(&e, bound, ub, x_tol)?;
        stats.u_degree = e.degree();
        let mut v_sources = vec![f1.clone(), f2.clone()];
        v_sources.retain(|g| g.deg_v() > 0);
        v_sources.sort_by_key(BiPoly::deg_v);
        let originals = v_sources.len();
        Some(Elimination::Eliminant {
            eliminant: t.poly.to_poly_u()?,
            v_sources,
            originals,
            u_candidates: Some(candidates),
        })
    };
    if let Some(elim) = certified(stats) {
        return Ok(elim);
    }
    fallback(f1, f2, stats)
}

/// Largest width of a component of `{u : |ê(u)| ≤ Ē}` accepted by [`certify_f64`], relative to
/// the `u`-range: `1e-6`. A component this narrow is covered by its midpoint (Newton on `F1`,
/// `F2` converges from within 5e-7 of the box in one or two steps, far inside
/// `NEWTON_MAX_STEP_REL`); a wider one means the `f64` eliminant has lost the roots' positions.
pub(crate) const CERT_WIDTH_REL: f64 = 1e-6;

/// The midpoints of the components of `{u ∈ ub : |e(u)| ≤ bound}`, or `None` if one is wider
/// than [`CERT_WIDTH_REL`] of `ub` ([`certified_candidates_into`] with fresh buffers).
fn certified_candidates(e: &Poly<f64>, bound: f64, ub: [f64; 2], x_tol: f64) -> Option<Vec<f64>> {
    let mut out = Vec::new();
    let (mut scratch, mut cuts, mut stats) = (Vec::new(), Vec::new(), RootStats::default());
    certified_candidates_into(
        e.coeffs(),
        bound,
        ub,
        x_tol,
        &mut scratch,
        &mut cuts,
        &mut stats,
        &mut out,
    )
    .then_some(out)
}

/// The real roots in `range` of the polynomial in `coeffs` (lowest degree first), appended to
/// `out` as [`SolveScalar::real_roots_in`] finds them; `coeffs` is lent to a [`Poly`] and
/// given back, so nothing is allocated once the buffers have grown.
pub(crate) fn real_roots_into(
    coeffs: &mut Vec<f64>,
    range: [f64; 2],
    x_tol: f64,
    stats: &mut RootStats,
    out: &mut Vec<f64>,
) {
    let p = Poly::new(std::mem::take(coeffs));
    if p.degree() > 0 {
        // Errors are impossible here (finite coefficients and bounds, x_tol > 0, p ≠ 0), and
        // on an error `out` is left as it was, i.e. no roots.
        let _ = p.real_roots_into(range[0], range[1], &RootOptions::new(x_tol), stats, out);
    }
    *coeffs = p.into_coeffs();
}

/// [`certified_candidates`] of the eliminant with coefficients `e`, into `out` (cleared
/// first); `false` when a component is wider than [`CERT_WIDTH_REL`] of `ub`. `scratch` and
/// `cuts` are reusable buffers (nothing is allocated once they have grown).
#[allow(
    clippy::too_many_arguments,
    reason = "the buffers are the caller's workspace fields"
)]
pub(crate) fn certified_candidates_into(
    e: &[f64],
    bound: f64,
    ub: [f64; 2],
    x_tol: f64,
    scratch: &mut Vec<f64>,
    cuts: &mut Vec<f64>,
    stats: &mut RootStats,
    out: &mut Vec<f64>,
) -> bool {
    out.clear();
    if !bound.is_finite() {
        return false;
    }
    let max_width = CERT_WIDTH_REL * (ub[1] - ub[0]).max(x_tol);
    cuts.clear();
    cuts.push(ub[0]);
    cuts.push(ub[1]);
    for shift in [-bound, bound] {
        scratch.clear();
        scratch.extend_from_slice(e);
        scratch[0] += shift;
        real_roots_into(scratch, ub, x_tol, stats, cuts);
    }
    cuts.sort_unstable_by(f64::total_cmp);
    cuts.dedup();
    let inside = |x: f64| horner(e, x).abs() <= bound;
    // Components: maximal runs of sub-intervals [cuts[k], cuts[k+1]] whose midpoint is in Z;
    // a cut is itself on the boundary of Z (|e| = bound there, up to x_tol).
    let mut start: Option<f64> = None;
    let close = |a: f64, b: f64, out: &mut Vec<f64>| -> bool {
        if b - a > max_width + 2.0 * x_tol {
            return false;
        }
        out.push(0.5 * (a + b));
        true
    };
    for w in cuts.windows(2) {
        let (a, b) = (w[0], w[1]);
        if inside(0.5 * (a + b)) {
            start.get_or_insert(a);
        } else if let Some(s) = start.take() {
            if !close(s, a, out) {
                return false;
            }
        } else if a > ub[0] && !close(a, a, out) {
            // An isolated boundary point (Z touches it from no side at this resolution).
            return false;
        }
    }
    let closed = match start {
        Some(s) => close(s, ub[1], out),
        None if inside(ub[1]) => close(ub[1], ub[1], out),
        None => true,
    };
    out.dedup_by(|b, a| (*b - *a).abs() <= 4.0 * x_tol);
    closed
}

/// `Σ c_i x^i` by Horner's rule (as `Poly::eval`).
pub(crate) fn horner(c: &[f64], x: f64) -> f64 {
    c.iter().rev().fold(0.0, |acc, &a| acc * x + a)
}

/// Whether a basis that lacks Theorem 2's `v^J` leading monomial can be trusted to say
/// "infinite": only if it is a Gröbner basis.
fn is_groebner<T: SolveScalar>(basis: &Basis<T>) -> bool {
    crate::is_groebner_basis(basis.elements())
}

/// The verdict when `F1` or `F2` is the zero polynomial: the other one's zero set, a whole
/// curve (or the plane), or nothing for a non-zero constant.
pub(crate) fn verdict_with_zero(other_is_zero: bool, other_is_constant: bool) -> Verdict {
    if other_is_zero || !other_is_constant {
        Verdict::Infinite
    } else {
        Verdict::NoCommonRoot
    }
}

fn eliminate_resultant<T: SolveScalar>(
    f1: &BiPoly<T>,
    f2: &BiPoly<T>,
    method: Method,
    stats: &mut SolveStats,
) -> Result<Elimination<T>, Error> {
    if f1.is_zero() || f2.is_zero() {
        let other = if f1.is_zero() { f2 } else { f1 };
        return Ok(Elimination::Verdict(verdict_with_zero(
            other.is_zero(),
            other.is_constant(),
        )));
    }
    if f1.deg_v() == 0 && f2.deg_v() == 0 {
        // Both in u alone: common roots are whole lines u = const, or none.
        let (a, b) = (f1.to_poly_u(), f2.to_poly_u());
        let g = a.zip(b).map(|(a, b)| a.gcd(&b)).unwrap_or_else(Poly::zero);
        let verdict = if g.degree() > 0 {
            Verdict::Infinite
        } else {
            Verdict::NoCommonRoot
        };
        return Ok(Elimination::Verdict(verdict));
    }
    if f1.deg_v() == 0 || f2.deg_v() == 0 {
        // One equation is in u alone: Res_v = (that polynomial)^{Deg_v(other)}, whose roots
        // are all multiple, which f64 root finding can lose (a double root may split into a
        // complex pair under rounding). Its own roots are the same set, simple.
        let (pu, other) = if f1.deg_v() == 0 { (f1, f2) } else { (f2, f1) };
        let eliminant = pu.to_poly_u().expect("Deg_v = 0");
        stats.coeff_bits = T::coeff_bits(pu);
        if eliminant.degree() == 0 {
            return Ok(Elimination::Verdict(Verdict::NoCommonRoot));
        }
        stats.v_degree = other.deg_v();
        return Ok(Elimination::Eliminant {
            eliminant,
            v_sources: vec![other.clone()],
            originals: 1,
            u_candidates: None,
        });
    }
    let res = match method {
        Method::BezoutResultant => bezout_resultant_v(f1, f2)?,
        _ => sylvester_resultant_v(f1, f2)?,
    };
    let res = if T::EXACT { res } else { res.trim_negligible() };
    if T::EXACT {
        stats.coeff_bits = T::coeff_bits(&BiPoly::from_poly_u(&res));
    }
    if res.is_zero() {
        // A common factor involving v.
        return Ok(Elimination::Verdict(Verdict::Infinite));
    }
    if res.degree() == 0 {
        return Ok(Elimination::Verdict(Verdict::NoCommonRoot));
    }
    let mut v_sources = vec![f1.clone(), f2.clone()];
    v_sources.retain(|g| g.deg_v() > 0);
    v_sources.sort_by_key(BiPoly::deg_v);
    stats.v_degree = v_sources.first().map_or(0, BiPoly::deg_v);
    let originals = v_sources.len();
    Ok(Elimination::Eliminant {
        eliminant: res,
        v_sources,
        originals,
        u_candidates: None,
    })
}

/// Adds to `roots` (the eliminant's real roots in `range`, sorted) the real critical points
/// `c` of `p` (roots of `p'`) in `range` where `p` nearly vanishes,
/// `|p(c)| ≤ NEAR_DOUBLE_REL · Σ|p_i||c|^i`, that are not already within `4·x_tol` of a root,
/// except a critical point that is the only one between two adjacent roots.
///
/// Why: two intersections with the same `u` (a ray across a surface of revolution at the
/// height of a profile parameter, for instance) make a double root of the eliminant, and the
/// rounding of `f64` coefficients can split a double root into a complex pair, which a real
/// root finder then rightly does not report. The critical point remains, with a value at the
/// rounding level. Spurious candidates cost one `v`-step and are almost always rejected by the
/// residual test — but not between two close simple roots, where the two curves run within
/// the residual tolerance of each other (two planted roots 2.4e-4 apart in `u` gave a third
/// "root" midway). Such a critical point is never a double root: a (near-)double root `d`
/// between two roots `r1 < d < r2` keeps three critical points in `(r1, r2)` — one near `d`,
/// one on each side by Rolle — under any small perturbation, so one that is alone there is a
/// simple hump between two roots already found, and is skipped. Exact mode does not need any
/// of this: exact isolation sees multiple roots exactly.
fn near_double_roots<T: SolveScalar>(
    p: &Poly<T>,
    range: [f64; 2],
    x_tol: f64,
    roots: &mut Vec<f64>,
) {
    let pf: Vec<f64> = p.coeffs().iter().map(Scalar::nearest_f64).collect();
    let (mut scratch, mut crit, mut stats) = (Vec::new(), Vec::new(), RootStats::default());
    near_double_roots_into(
        &pf,
        range,
        x_tol,
        &mut scratch,
        &mut crit,
        &mut stats,
        roots,
    );
}

/// [`near_double_roots`] of the `f64` polynomial with coefficients `e`, added to `roots`;
/// `scratch` and `crit` are reusable buffers.
pub(crate) fn near_double_roots_into(
    e: &[f64],
    range: [f64; 2],
    x_tol: f64,
    scratch: &mut Vec<f64>,
    crit: &mut Vec<f64>,
    stats: &mut RootStats,
    roots: &mut Vec<f64>,
) {
    if e.len() < 3 {
        return; // degree < 2
    }
    scratch.clear();
    scratch.extend(e.iter().enumerate().skip(1).map(|(i, &c)| c * i as f64));
    crit.clear();
    real_roots_into(scratch, range, x_tol, stats, crit);
    let merge = 4.0 * x_tol;
    let found = roots.len();
    for &c in crit.iter() {
        // The eliminant's adjacent roots around c (the candidates added here do not count).
        let below = roots[..found]
            .iter()
            .copied()
            .filter(|&r| r < c)
            .fold(f64::NEG_INFINITY, f64::max);
        let above = roots[..found]
            .iter()
            .copied()
            .filter(|&r| r > c)
            .fold(f64::INFINITY, f64::min);
        let alone = below.is_finite()
            && above.is_finite()
            && crit.iter().all(|&d| d == c || d <= below || d >= above);
        if alone {
            continue;
        }
        let (value, size) = e
            .iter()
            .rev()
            .fold((0.0, 0.0), |(v, s), &a| (v * c + a, s * c.abs() + a.abs()));
        if value.abs() <= NEAR_DOUBLE_REL * size && !roots.iter().any(|r| (r - c).abs() <= merge) {
            roots.push(c);
        }
    }
    roots.sort_unstable_by(f64::total_cmp);
}

/// Candidate `v` values at `u` from one source `g`: the real roots of `g(u, ·)` in `vb`, or
/// `None` when `g(u, ·)` vanishes identically.
///
/// "Vanishes" is decided per coefficient `c_j(u)` of `v^j`:
/// * `f64` sources: `|c_j(u)|` below [`VANISH_REL`] times the size of its terms;
/// * exact sources, evaluated exactly at the rational `ut` that lies within `u_err` of the true
///   root `u_r`: `|c_j(ut)| ≤ 2·u_err·Σ i|a_i|(|ut| + u_err)^{i−1}`, i.e. when the first-order
///   bound on `|c_j(ut) − c_j(u_r)|` cannot certify `c_j(u_r) ≠ 0`. No fixed threshold: a
///   coefficient that is small only because its terms cancel (a shape element `v + h(u)` with
///   huge `h` at a root, `paper-notes/groebner.md` §5) is kept once `ut` is close enough.
fn v_candidates<T: SolveScalar>(
    g: &BiPoly<T>,
    ut: &T,
    u_err: &T,
    vb: [f64; 2],
    x_tol: f64,
) -> Option<Vec<f64>> {
    let au = ut.abs();
    let au_wide = au.clone() + u_err;
    let two = T::one() + T::one();
    let vanish = T::from_f64(VANISH_REL).expect("a small constant");
    let mut coeffs: Vec<T> = Vec::with_capacity(g.rows());
    let mut significant = false;
    for row in g.rows_iter() {
        // Value, size of the terms, and bound on the derivative's size over the u interval.
        let (mut c, mut s, mut ds) = (T::zero(), T::zero(), T::zero());
        for a in row.iter().rev() {
            c = c * ut + a;
            ds = ds * &au_wide + &s;
            s = s * &au_wide + a.abs();
        }
        let vanished = if T::EXACT {
            c.abs() <= two.clone() * u_err * ds
        } else {
            c.abs() <= vanish.clone() * s
        };
        significant |= !vanished;
        coeffs.push(if vanished { T::zero() } else { c });
    }
    if !significant {
        return None;
    }
    let p = Poly::new(coeffs);
    Some(match p.degree() {
        0 => Vec::new(),
        1 => {
            let v = (-p.coeff(0) / p.coeff(1)).nearest_f64();
            if v >= vb[0] && v <= vb[1] {
                vec![v]
            } else {
                Vec::new()
            }
        }
        _ => T::real_roots_in(&p, vb, x_tol),
    })
}

/// Value, gradient and term size `A = Σ|a_ij||u|^i|v|^j` of `p` at `(u, v)`, in one nested
/// Horner pass (no allocation).
fn eval_grad(p: &BiPoly<f64>, u: f64, v: f64) -> (f64, f64, f64, f64) {
    eval_grad_rows(p.rows_iter(), u, v)
}

/// [`eval_grad`] of the polynomial whose rows (coefficients of `v^j`, each lowest power of
/// `u` first) are `rows`, lowest `j` first.
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
/// `eval_grad(k, u, v)` gives `(F_k, ∂F_k/∂u, ∂F_k/∂v, Σ|terms|)` of equation `k` (0 or 1), so
/// the general and the per-ray (fixed-size) systems share this one polish.
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::testutil::{article_pair, q, qb};
    use poly::Rat;

    /// The article pair's real common roots (sympy, 10 digits; groebner.md §2).
    const ARTICLE_ROOTS: [(f64, f64); 2] =
        [(-0.8435323370, 0.4805849293), (0.7116194175, -1.3697138583)];

    const METHODS: [Method; 4] = [
        Method::Stam,
        Method::Buchberger,
        Method::Resultant,
        Method::BezoutResultant,
    ];

    fn wide(method: Method) -> SolveOptions {
        SolveOptions {
            method,
            u_range: [-2.0, 2.0],
            v_range: [-2.0, 2.0],
            ..SolveOptions::default()
        }
    }

    fn assert_roots(sol: &Solution, expected: &[(f64, f64)], tol: f64, what: &str) {
        assert_eq!(sol.roots.len(), expected.len(), "{what}: {:?}", sol.roots);
        for (r, &(u, v)) in sol.roots.iter().zip(expected) {
            assert!(
                (r.u - u).abs() <= tol && (r.v - v).abs() <= tol,
                "{what}: got ({}, {}), expected ({u}, {v})",
                r.u,
                r.v
            );
        }
    }

    #[test]
    fn article_roots_by_every_method() {
        let (f1, f2) = article_pair();
        let (g1, g2) = (f1.to_f64(), f2.to_f64());
        for m in METHODS {
            let exact = solve(&f1, &f2, &wide(m)).unwrap();
            assert_roots(&exact, &ARTICLE_ROOTS, 1e-10, &format!("{m:?} exact"));
            assert_eq!(exact.verdict, Verdict::Finite, "{m:?}");
            assert!(
                exact.stats.coeff_bits.is_some(),
                "{m:?}: exact mode reports bits"
            );
            let float = solve(&g1, &g2, &wide(m)).unwrap();
            assert_roots(&float, &ARTICLE_ROOTS, 1e-10, &format!("{m:?} f64"));
            assert_eq!(float.stats.coeff_bits, None, "{m:?}: no bits in f64");
        }
        // The Gröbner methods eliminate to u⁸ − … and substitute into v + u⁷ + … (article §3).
        let s = solve(&f1, &f2, &wide(Method::Buchberger)).unwrap().stats;
        assert_eq!((s.basis_size, s.u_degree, s.v_degree), (2, 8, 1), "{s:?}");
        assert_eq!(
            s.coeff_bits,
            Some(2),
            "largest coefficient 2 (in 2u²): {s:?}"
        );
        // The resultant carries the extra factor u: degree 9, F2 (Deg_v 1) substituted.
        let s = solve(&f1, &f2, &wide(Method::Resultant)).unwrap().stats;
        assert_eq!((s.u_degree, s.v_degree), (9, 1), "{s:?}");
    }

    #[test]
    fn resultant_extra_factor_is_not_a_hit() {
        // In [0, 1]², Res = −u·(u⁸ − …) has the roots u = 0 (extraneous: F1(0, v) ≡ 0 and
        // F2(0, v) = 1) and u ≈ 0.7116 (its v ≈ −1.37 is outside): no hit at all.
        let (f1, f2) = article_pair();
        for m in [Method::Resultant, Method::BezoutResultant] {
            let opts = SolveOptions {
                method: m,
                ..SolveOptions::default()
            };
            for sol in [
                solve(&f1, &f2, &opts).unwrap(),
                solve(&f1.to_f64(), &f2.to_f64(), &opts).unwrap(),
            ] {
                assert!(sol.roots.is_empty(), "{m:?}: {:?}", sol.roots);
                assert_eq!(
                    sol.stats.u_roots, 2,
                    "{m:?}: u = 0 and u ≈ 0.71 were candidates"
                );
            }
        }
    }

    #[test]
    fn verdicts_follow_theorems_1_to_3() {
        // uv − 1 = 0 and u = 0 have no common root: 1 ∈ G (Theorem 1).
        let (a, b) = (qb(&[(1, 1, 1), (-1, 0, 0)]), qb(&[(1, 1, 0)]));
        // (v − u)(u + 1) and (v − u)(v + 2) share the line v = u.
        let l = qb(&[(1, 0, 1), (-1, 1, 0)]);
        let c = &l * &qb(&[(1, 1, 0), (1, 0, 0)]);
        let d = &l * &qb(&[(1, 0, 1), (2, 0, 0)]);
        for m in METHODS {
            let opts = SolveOptions {
                method: m,
                ..SolveOptions::default()
            };
            let miss = solve(&a, &b, &opts).unwrap();
            assert!(miss.roots.is_empty(), "{m:?}");
            if matches!(m, Method::Stam | Method::Buchberger) {
                assert_eq!(miss.verdict, Verdict::NoCommonRoot, "{m:?}");
            } else {
                // Res_v = u: the common root is at v = ∞ over u = 0, which a resultant cannot
                // tell from a finite one; the candidate u = 0 has no v (F1(0, v) = −1).
                assert_eq!(miss.stats.u_roots, 1, "{m:?}: {:?}", miss.stats);
            }
            let line = solve(&c.to_f64(), &d.to_f64(), &opts).unwrap();
            assert_eq!(line.verdict, Verdict::Infinite, "{m:?}");
            assert!(
                line.roots.is_empty(),
                "{m:?}: a curve is not a list of points"
            );
        }
    }

    #[test]
    fn v_element_of_degree_two() {
        // v² = u and u = 1/4: the reduced basis {v² − 1/4, u − 1/4} is not in shape form.
        let f1 = qb(&[(1, 0, 2), (-1, 1, 0)]);
        let f2 = BiPoly::from_terms([(q(1), 1, 0), (-(q(1) / q(4)), 0, 0)]);
        for exact in [true, false] {
            let sol = if exact {
                solve(&f1, &f2, &wide(Method::Buchberger)).unwrap()
            } else {
                solve(&f1.to_f64(), &f2.to_f64(), &wide(Method::Stam)).unwrap()
            };
            assert_roots(&sol, &[(0.25, -0.5), (0.25, 0.5)], 1e-14, "two v for one u");
            assert_eq!(
                (sol.stats.u_degree, sol.stats.v_degree),
                (1, 2),
                "{:?}",
                sol.stats
            );
        }
    }

    /// Two circles of radius 0.3 centred at `(0.4, 0.5)` and `(0.7, 0.5 + δ)`: two crossings
    /// `(u, v)` whose `u` differ by only about `δ`, while their `v` differ by ~0.52.
    fn near_vertical_pair(delta: &Rat) -> (BiPoly<Rat>, BiPoly<Rat>, [(f64, f64); 2]) {
        let r = |n: i64, d: i64| Rat::new(n.into(), d.into());
        let circle = |cu: Rat, cv: Rat| {
            // (u − cu)² + (v − cv)² − 9/100
            BiPoly::from_terms([
                (q(1), 2, 0),
                (-(q(2) * &cu), 1, 0),
                (q(1), 0, 2),
                (-(q(2) * &cv), 0, 1),
                (&cu * &cu + &cv * &cv - r(9, 100), 0, 0),
            ])
        };
        let f1 = circle(r(2, 5), r(1, 2));
        let f2 = circle(r(7, 10), r(1, 2) + delta);
        // Crossings: on the perpendicular bisector of the centres, 0.2598… from their midpoint.
        let d = delta.nearest_f64();
        let (mu, mv, len) = (0.55, 0.5 + d / 2.0, (0.09 + d * d).sqrt());
        let h = (0.09 - len * len / 4.0).sqrt();
        let (nu, nv) = (-d / len, 0.3 / len);
        let roots = [(mu - h * nu, mv - h * nv), (mu + h * nu, mv + h * nv)];
        (f1, f2, roots)
    }

    #[test]
    fn exact_back_substitution_into_an_ill_conditioned_shape_element() {
        // The reduced basis is {v + h(u), e(u)} with h' ≈ 0.3/δ ≈ 3e11 at the roots: the
        // f64 value of a u-root (within x_tol = 1e-10) put into v + h(u) gives a v off by ~30,
        // so the Gröbner element's candidate was rejected and only the F1/F2 fallback found
        // the root (the teapot case of paper-notes/groebner.md §5: h' ≈ 1.5e18). In exact mode
        // the u-root is now narrowed exactly before the substitution.
        let delta = Rat::new(1.into(), (1i64 << 40).into());
        let (f1, f2, expected) = near_vertical_pair(&delta);
        let mut expected = expected.to_vec();
        expected.sort_by(|a, b| a.0.total_cmp(&b.0));
        for m in [Method::Stam, Method::Buchberger] {
            let sol = solve(
                &f1,
                &f2,
                &SolveOptions {
                    method: m,
                    ..SolveOptions::default()
                },
            )
            .unwrap();
            assert_roots(&sol, &expected, 1e-9, &format!("{m:?}"));
            assert_eq!(
                (sol.stats.u_degree, sol.stats.v_degree),
                (2, 1),
                "{m:?}: shape form {{v + h(u), e(u)}}: {:?}",
                sol.stats
            );
            assert_eq!(
                sol.stats.rejected, 0,
                "{m:?}: the basis element's v verified at both roots: {:?}",
                sol.stats
            );
        }
    }

    /// Two teapot ray/piece systems (power-basis points about the piece's centre, ray origin,
    /// direction; from `tests/bezier_teapot.rs`' view): patch 22 on [0, ¼]² (4×4 pieces,
    /// the lead's reproducer) and patch 20 piece of a 16×16 cut.
    type RayPiece = ([[f64; 3]; 16], [f64; 3], [f64; 3]);
    const TEAPOT_CASES: [RayPiece; 2] = [
        (
            [
                [
                    0.17031250000000003,
                    -0.06702563476562502,
                    0.024609375000000266,
                ],
                [-0.6000000000000001, 0.0, 0.0],
                [0.30000000000000004, 0.0, -0.056250000000000355],
                [-0.04062500000000002, 0.0, 0.007031249999999822],
                [0.0, 0.0, 0.0],
                [0.0, 0.253125, 0.0],
                [0.0, -0.12656249999999997, 0.0],
                [0.0, 0.01713281250000001, 0.0],
                [0.0, 0.0, 0.0],
                [0.049218749999999645, -0.014062499999999922, 0.0],
                [-0.024609374999999822, 0.007031249999999933, 0.0],
                [0.0033339843750000986, -0.0009492187500000915, 0.0],
                [0.0, 0.0, 0.0],
                [-0.002929687499999667, -0.0029296875, 0.0],
                [0.001464843749999778, 0.00146484375, 0.0],
                [-0.00019873046875018563, -0.00019873046874996358, 0.0],
            ],
            [
                -0.017054880694892527,
                -0.054353337878157285,
                0.024609375000006484,
            ],
            [
                -0.5559003198125779,
                0.7831825859381882,
                -0.27856753492725295,
            ],
        ),
        (
            [
                [
                    0.01878793287277221,
                    -0.009158003747463173,
                    0.01708374023437509,
                ],
                [
                    -0.003928776741027817,
                    0.018808367729187037,
                    -0.03306884765624929,
                ],
                [
                    -0.0011089353561401505,
                    0.0053121843338010954,
                    -0.0012084960937510658,
                ],
                [
                    0.00012975406646728582,
                    -0.0006221303939819012,
                    0.00010986328125017764,
                ],
                [-0.0344373536109924, -0.006838804721832403, 0.0],
                [0.0018957209587096013, 0.00037528181076096345, 0.0],
                [0.000535175800323695, 0.00010609102249103941, 0.0],
                [-6.263494491581811e-5, -1.2441158294573817e-5, 0.0],
                [-0.0006701438426971462, 0.0016297352313998648, 0.0],
                [3.72354984284895e-5, -8.946776390184041e-5, 0.0],
                [1.0469198226725762e-5, -2.5287866590950614e-5, 0.0],
                [-1.2180805206152279e-6, 2.96473503103023e-6, 0.0],
                [2.6655316352840186e-5, 2.6655316352541814e-5, 0.0],
                [-1.4508962630777056e-6, -1.4508962626891275e-6, 0.0],
                [-4.1162967684416074e-7, -4.116296768996719e-7, 0.0],
                [4.8518180868761807e-8, 4.8518181028356366e-8, 0.0],
            ],
            [
                0.011661505398105468,
                -0.014340417921548387,
                0.001175481522686983,
            ],
            [
                -0.5515909420098845,
                0.7765592714968523,
                -0.30447188793865104,
            ],
        ),
    ];

    #[test]
    fn f64_groebner_keeps_teapot_roots() {
        // Before the certificate: Stam over f64 returned no root on the first system (its f64
        // eliminant, of degree 8 instead of 15, was noise), and a first version of the
        // certificate declared a miss on the second (Buchberger's early stop on a constant
        // dropped the error bounds). Both roots are those of the resultant (u ≈ 0.4499,
        // v ≈ 0.4923 and u ≈ 0.6689, v ≈ 0.4875).
        for (k, (points, o, d)) in TEAPOT_CASES.iter().enumerate() {
            let sys = crate::ray_patch_system(points, 4, 4, o, d).unwrap();
            let opts = |method| SolveOptions {
                method,
                ..SolveOptions::default()
            };
            let reference = solve(&sys.f1, &sys.f2, &opts(Method::BezoutResultant)).unwrap();
            assert_eq!(reference.roots.len(), 1, "case {k}: {reference:?}");
            for m in [Method::Stam, Method::Buchberger] {
                let sol = solve(&sys.f1, &sys.f2, &opts(m)).unwrap();
                let expected = [(reference.roots[0].u, reference.roots[0].v)];
                assert_roots(&sol, &expected, 1e-9, &format!("case {k} {m:?}"));
            }
        }
    }

    #[test]
    fn edge_roots_are_kept() {
        // (u − 1)(v) … roots exactly on the box edges u = 1 and v = 0.
        let f1 = qb(&[(1, 1, 0), (-1, 0, 0)]);
        let f2 = qb(&[(1, 0, 1), (-1, 1, 1)]); // v·(1 − u) + … vanishes on v = 0
        let f2 = &f2 + &qb(&[(1, 0, 1)]);
        let sol = solve(&f1.to_f64(), &f2.to_f64(), &SolveOptions::default()).unwrap();
        assert_roots(&sol, &[(1.0, 0.0)], 0.0, "corner (1, 0)");
    }

    #[test]
    fn bad_options_and_input_are_errors() {
        let (f1, f2) = article_pair();
        let (g1, g2) = (f1.to_f64(), f2.to_f64());
        let bad_range = SolveOptions {
            u_range: [1.0, 0.0],
            ..SolveOptions::default()
        };
        assert!(
            matches!(
                solve(&g1, &g2, &bad_range),
                Err(Error::InvalidRange { which: "u", .. })
            ),
            "reversed range"
        );
        let bad_tol = SolveOptions {
            x_tol: f64::NAN,
            ..SolveOptions::default()
        };
        assert!(
            matches!(
                solve(&g1, &g2, &bad_tol),
                Err(Error::InvalidTolerance { name: "x_tol", .. })
            ),
            "NaN tolerance"
        );
        let nan = BiPoly::from_terms([(f64::NAN, 1, 1)]);
        assert_eq!(
            solve(&nan, &g2, &SolveOptions::default()),
            Err(Error::NonFinite { what: "F1" }),
            "NaN coefficient"
        );
    }

    #[test]
    fn eval_grad_matches_derivatives() {
        let (f1, _) = article_pair();
        let p = (&f1 * &f1).to_f64();
        let (u, v) = (0.3, -1.7);
        let (f, fu, fv, a) = eval_grad(&p, u, v);
        assert!((f - p.eval(&u, &v)).abs() <= 1e-12, "value");
        assert!((fu - p.d_du().eval(&u, &v)).abs() <= 1e-12, "∂/∂u");
        assert!((fv - p.d_dv().eval(&u, &v)).abs() <= 1e-12, "∂/∂v");
        assert_eq!(a, p.eval_abs(u, v), "term size");
        let _ = Rat::from_integer(0.into());
    }
}

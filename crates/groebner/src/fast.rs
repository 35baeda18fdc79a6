//! The per-ray `f64` path of [`solve`](crate::solve) for systems of degree ≤ 3 in `u` and in
//! `v` (a ray against a bicubic or smaller patch), in a reusable [`SolveWorkspace`]: the same
//! steps as the general path (`solve.rs`; `paper-notes/groebner.md` §5,
//! `paper-notes/resultant.md` §3), with fixed-size polynomials and buffers that are reused
//! from one solve to the next, so that after a warm-up a solve allocates nothing.
//!
//! Methods: [`Method::Stam`] (the dense tracked loop of the `dense` module, then the
//! certificate of `certify_f64`, else the Bézout resultant) and [`Method::BezoutResultant`]
//! (the fixed-size determinant of `small_resultant`). The other methods, larger degrees and
//! exact scalars go through the general path.
//!
//! Departures from the general path, all in the Stam method and all for speed (none affects
//! soundness: the certificate is checked as before, and an uncertified run falls back):
//! * when Stam's list has neither a constant nor a univariate element, the general path
//!   completes it by Buchberger's algorithm before trying the certificate; here the resultant
//!   is solved directly (on `teapot.scene` at 420², before the other changes, 282 of 189 730
//!   systems, 0.15%, were certified by the general path and not here), and
//! * the loop stops at its first eliminant and does not rescale after every `R2` step, and
//!   bounds beyond the grid (and, at every `R2`, beyond each row's coefficients) are folded
//!   into one weighted scalar (the `dense` module docs).
//!
//! The Bézout path is the same arithmetic as the general one (identical solutions, tested).
//!
//! Allocation: none after warm-up, except in degenerate inputs (both equations free of `v`:
//! a gcd) and in `poly`'s exact root-isolation fallback when a query needs it
//! ([`poly::RootStats::exact_fallbacks`]).

use poly::{BiPoly, Poly, RootStats, gamma};

use crate::dense::{Corner, DensePoly, MAX_ELEMENTS, SLOTS, Variant, stam_dense};
use crate::error::Error;
use crate::ray_patch::ray_patch_small;
use crate::small_resultant::small_bezout_det;
use crate::solve::{
    Method, NEWTON_MAX_STEP_REL, Root, Solution, SolveOptions, SolveStats, VANISH_REL, Verdict,
    certified_candidates_into, check_options, eval_grad_rows, near_double_roots_into,
    polish_and_verify, real_roots_into, verdict_with_zero,
};

/// A polynomial of degree ≤ 3 in `u` and in `v`: `c[4 * j + i]` is the coefficient of
/// `u^i v^j`.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub(crate) struct Small {
    pub(crate) c: [f64; 16],
}

impl Small {
    /// The polynomial of a [`BiPoly`] that fits (stride and rows ≤ 4).
    pub(crate) fn from_bipoly(p: &BiPoly<f64>) -> Option<Self> {
        if p.stride() > 4 || p.rows() > 4 {
            return None;
        }
        let mut c = [0.0; 16];
        for (j, row) in p.rows_iter().enumerate() {
            c[4 * j..4 * j + row.len()].copy_from_slice(row);
        }
        Some(Small { c })
    }

    fn to_bipoly(self) -> BiPoly<f64> {
        BiPoly::from_grid(4, 4, self.c.to_vec())
    }

    fn is_zero(&self) -> bool {
        self.c.iter().all(|&c| c == 0.0)
    }

    /// `Deg_v`: the highest `j` with a non-zero coefficient (0 for zero).
    fn deg_v(&self) -> usize {
        (0..4)
            .rev()
            .find(|&j| self.c[4 * j..4 * j + 4].iter().any(|&c| c != 0.0))
            .unwrap_or(0)
    }

    fn is_constant(&self) -> bool {
        self.c[1..].iter().all(|&c| c == 0.0)
    }

    /// The value at `(u, v)` by nested Horner (as `BiPoly::eval`).
    pub(crate) fn eval(&self, u: f64, v: f64) -> f64 {
        self.c.chunks_exact(4).rev().fold(0.0, |acc, row| {
            acc * v + row.iter().rev().fold(0.0, |a, c| a * u + c)
        })
    }

    /// Value, gradient and term size at `(u, v)` (`solve.rs`' `eval_grad`).
    fn eval_grad(&self, u: f64, v: f64) -> (f64, f64, f64, f64) {
        eval_grad_rows(self.c.chunks_exact(4), u, v)
    }
}

/// Reusable buffers for [`solve_ray_patch`] (and the `f64` path of [`solve`](crate::solve)):
/// one per thread. After the first few solves have grown its buffers, a solve of a system of
/// degree ≤ 3 in `u` and `v` by [`Method::Stam`] or [`Method::BezoutResultant`] allocates
/// nothing (see the module docs of `fast.rs` for the rare exceptions).
#[derive(Debug)]
pub struct SolveWorkspace {
    /// Stam's elements (dense, with bounds).
    slots: Vec<DensePoly>,
    order: [usize; MAX_ELEMENTS],
    /// The `u`-polynomial (eliminant or resultant), lowest power first.
    elim: Vec<f64>,
    /// Scratch for shifted / derived univariate polynomials.
    scratch: Vec<f64>,
    /// `u`-candidates.
    u_roots: Vec<f64>,
    /// Cuts of the certificate, critical points.
    cuts: Vec<f64>,
    /// `v`-candidates.
    v_roots: Vec<f64>,
    /// Verified roots (before and after merging).
    roots: Vec<Root>,
    merged: Vec<Root>,
    /// `t` of each root ([`solve_ray_patch`]).
    ts: Vec<f64>,
    /// The root finder's counters (not reported; `poly` needs somewhere to count).
    root_stats: RootStats,
}

impl Default for SolveWorkspace {
    fn default() -> Self {
        SolveWorkspace {
            slots: vec![DensePoly::default(); SLOTS],
            order: [0; MAX_ELEMENTS],
            elim: Vec::with_capacity(32),
            scratch: Vec::with_capacity(32),
            u_roots: Vec::with_capacity(32),
            cuts: Vec::with_capacity(64),
            v_roots: Vec::with_capacity(8),
            roots: Vec::with_capacity(16),
            merged: Vec::with_capacity(16),
            ts: Vec::with_capacity(16),
            root_stats: RootStats::default(),
        }
    }
}

impl SolveWorkspace {
    /// A workspace with buffers sized for bicubic systems.
    pub fn new() -> Self {
        SolveWorkspace::default()
    }
}

/// The outcome of [`solve_ray_patch`], borrowing the workspace's buffers.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RayPatchSolution<'w> {
    /// Verified roots in the box, sorted by `u` then `v` (as [`Solution::roots`]).
    pub roots: &'w [Root],
    /// The ray parameter of each root, `(S_k(u, v) − O_k) / D_k`
    /// ([`RayPatchSystem::t_at`](crate::RayPatchSystem::t_at)).
    pub ts: &'w [f64],
    /// As [`Solution::verdict`].
    pub verdict: Verdict,
    /// As [`Solution::stats`].
    pub stats: SolveStats,
}

/// [`ray_patch_system`](crate::ray_patch_system) and [`solve`](crate::solve) in one call over
/// `f64`, in `ws`'s buffers, with the `t` of each root: the ray tracer's per-ray algebra.
///
/// For patches of degree ≤ 3 in `u` and `v` solved by [`Method::Stam`] or
/// [`Method::BezoutResultant`] it allocates nothing once `ws` has warmed up; the other cases
/// run the general path and copy its result into `ws`. The roots, verdict and statistics are
/// those of `solve(&sys.f1, &sys.f2, opts)` on the same system.
///
/// # Errors
/// As [`ray_patch_system`](crate::ray_patch_system) and [`solve`](crate::solve).
pub fn solve_ray_patch<'w>(
    ws: &'w mut SolveWorkspace,
    points: &[[f64; 3]],
    stride: usize,
    rows: usize,
    origin: &[f64; 3],
    dir: &[f64; 3],
    opts: &SolveOptions,
) -> Result<RayPatchSolution<'w>, Error> {
    let small = stride <= 4
        && rows <= 4
        && points.len() == stride * rows
        && matches!(opts.method, Method::Stam | Method::BezoutResultant);
    if !small {
        let sys = crate::ray_patch_system(points, stride, rows, origin, dir)?;
        let sol = crate::solve(&sys.f1, &sys.f2, opts)?;
        ws.roots.clear();
        ws.roots.extend_from_slice(&sol.roots);
        ws.ts.clear();
        ws.ts.extend(sol.roots.iter().map(|r| sys.t_at(&r.u, &r.v)));
        return Ok(RayPatchSolution {
            roots: &ws.roots,
            ts: &ws.ts,
            verdict: sol.verdict,
            stats: sol.stats,
        });
    }
    let sys = ray_patch_small(points, stride, origin, dir)?;
    let (verdict, stats) = solve_small(ws, &sys.f1, &sys.f2, opts)?;
    ws.ts.clear();
    for r in &ws.roots {
        ws.ts
            .push((sys.s_pivot.eval(r.u, r.v) - sys.origin_pivot) / sys.dir_pivot);
    }
    Ok(RayPatchSolution {
        roots: &ws.roots,
        ts: &ws.ts,
        verdict,
        stats,
    })
}

/// The `f64` path of [`solve`](crate::solve) for small systems; `None` when it does not
/// apply (larger degrees, other methods).
pub(crate) fn solve_f64(
    f1: &BiPoly<f64>,
    f2: &BiPoly<f64>,
    opts: &SolveOptions,
) -> Option<Result<Solution, Error>> {
    if !matches!(opts.method, Method::Stam | Method::BezoutResultant) {
        return None;
    }
    let (a, b) = (Small::from_bipoly(f1)?, Small::from_bipoly(f2)?);
    thread_local! {
        static WS: std::cell::RefCell<SolveWorkspace> = std::cell::RefCell::new(SolveWorkspace::new());
    }
    Some(WS.with(|ws| {
        let ws = &mut ws.borrow_mut();
        let (verdict, stats) = solve_small(ws, &a, &b, opts)?;
        Ok(Solution {
            roots: ws.roots.clone(),
            verdict,
            stats,
        })
    }))
}

/// What the elimination left to solve.
enum Elim {
    Verdict(Verdict),
    /// The `u`-polynomial is in `ws.elim`; `candidates`: `ws.u_roots` already holds the
    /// certified `u`-candidates. `sources`: the polynomials giving `v`, in order (0 for
    /// `F1`, 1 for `F2`).
    Eliminant {
        candidates: bool,
        sources: [Option<usize>; 2],
    },
}

/// `solve` on `f1`, `f2` (degree ≤ 3 in each variable) into `ws.roots`.
fn solve_small(
    ws: &mut SolveWorkspace,
    f1: &Small,
    f2: &Small,
    opts: &SolveOptions,
) -> Result<(Verdict, SolveStats), Error> {
    check_options(opts)?;
    if !f1.c.iter().all(|c| c.is_finite()) {
        return Err(Error::NonFinite { what: "F1" });
    }
    if !f2.c.iter().all(|c| c.is_finite()) {
        return Err(Error::NonFinite { what: "F2" });
    }
    ws.roots.clear();
    let mut stats = SolveStats::default();
    let widen = |r: [f64; 2]| [r[0] - opts.x_tol, r[1] + opts.x_tol];
    let (ub, vb) = (widen(opts.u_range), widen(opts.v_range));
    let elim = match opts.method {
        Method::Stam => eliminate_stam(ws, f1, f2, [ub, vb], opts.x_tol, &mut stats)?,
        _ => eliminate_resultant(ws, f1, f2, &mut stats)?,
    };
    let (candidates, sources) = match elim {
        Elim::Verdict(v) => return Ok((v, stats)),
        Elim::Eliminant {
            candidates,
            sources,
        } => (candidates, sources),
    };
    stats.u_degree = ws.elim.len().saturating_sub(1);
    if !candidates {
        ws.u_roots.clear();
        real_roots_into(
            &mut ws.elim,
            ub,
            opts.x_tol,
            &mut ws.root_stats,
            &mut ws.u_roots,
        );
        near_double_roots_into(
            &ws.elim,
            ub,
            opts.x_tol,
            &mut ws.scratch,
            &mut ws.cuts,
            &mut ws.root_stats,
            &mut ws.u_roots,
        );
    }
    stats.u_roots = ws.u_roots.len();

    let system = [*f1, *f2];
    let margin = NEWTON_MAX_STEP_REL * (vb[1] - vb[0]).max(opts.x_tol);
    let v_search = [vb[0] - margin, vb[1] + margin];
    for k in 0..ws.u_roots.len() {
        let u = ws.u_roots[k];
        // Step 3 (general path): the first source that does not vanish at u gives the
        // candidates; the next ones are tried if none of them verifies.
        for &g in sources.iter().flatten() {
            let g = &system[g];
            let before = ws.roots.len();
            let mut rejected = 0;
            if v_candidates(ws, g, u, 2.0 * opts.x_tol, v_search, opts.x_tol) {
                for i in 0..ws.v_roots.len() {
                    match polish_and_verify(
                        |k, u, v| system[k].eval_grad(u, v),
                        u,
                        ws.v_roots[i],
                        opts,
                        ub,
                        vb,
                    ) {
                        Some(r) => ws.roots.push(r),
                        None => rejected += 1,
                    }
                }
            }
            stats.rejected += rejected;
            if ws.roots.len() > before {
                break;
            }
        }
    }
    // Merge duplicates against every kept root (as the general path).
    let merge = 4.0 * opts.x_tol;
    ws.merged.clear();
    for &r in &ws.roots {
        if !ws
            .merged
            .iter()
            .any(|a| (a.u - r.u).abs() <= merge && (a.v - r.v).abs() <= merge)
        {
            ws.merged.push(r);
        }
    }
    std::mem::swap(&mut ws.roots, &mut ws.merged);
    // Equal keys under total_cmp are equal bits, so an unstable sort gives the stable order
    // (and, unlike the stable sort, never allocates).
    ws.roots
        .sort_unstable_by(|a, b| a.u.total_cmp(&b.u).then(a.v.total_cmp(&b.v)));
    Ok((Verdict::Finite, stats))
}

/// The sources of `v` after a resultant or a certified basis: `F1`, `F2` with `Deg_v > 0`,
/// lowest `Deg_v` first (stable).
fn originals(f1: &Small, f2: &Small) -> [Option<usize>; 2] {
    let (a, b) = ((f1.deg_v() > 0).then_some(0), (f2.deg_v() > 0).then_some(1));
    match (a, b) {
        (Some(a), Some(b)) if f2.deg_v() < f1.deg_v() => [Some(b), Some(a)],
        (None, b) => [b, None],
        (a, b) => [a, b],
    }
}

/// As `solve.rs`' `eliminate_resultant` with the Bézout method.
fn eliminate_resultant(
    ws: &mut SolveWorkspace,
    f1: &Small,
    f2: &Small,
    stats: &mut SolveStats,
) -> Result<Elim, Error> {
    if f1.is_zero() || f2.is_zero() {
        let other = if f1.is_zero() { f2 } else { f1 };
        return Ok(Elim::Verdict(verdict_with_zero(
            other.is_zero(),
            other.is_constant(),
        )));
    }
    let (d1, d2) = (f1.deg_v(), f2.deg_v());
    if d1 == 0 && d2 == 0 {
        // Degenerate (both free of v): a gcd, on the general path (allocates).
        let (a, b) = (f1.to_bipoly(), f2.to_bipoly());
        let g = a
            .to_poly_u()
            .zip(b.to_poly_u())
            .map(|(a, b)| a.gcd(&b))
            .unwrap_or_else(Poly::zero);
        let verdict = if g.degree() > 0 {
            Verdict::Infinite
        } else {
            Verdict::NoCommonRoot
        };
        return Ok(Elim::Verdict(verdict));
    }
    if d1 == 0 || d2 == 0 {
        // One equation in u alone: its own roots (see the general path).
        let (pu, other, which) = if d1 == 0 { (f1, f2, 1) } else { (f2, f1, 0) };
        set_trimmed(&mut ws.elim, &pu.c[..4]);
        if ws.elim.len() <= 1 {
            return Ok(Elim::Verdict(Verdict::NoCommonRoot));
        }
        stats.v_degree = other.deg_v();
        return Ok(Elim::Eliminant {
            candidates: false,
            sources: [Some(which), None],
        });
    }
    let det = small_bezout_det(&rows(f1), &rows(f2), d1.max(d2));
    set_trimmed(&mut ws.elim, &det);
    // As the general path: trailing coefficients negligible against the largest are dropped
    // (the buffer is lent to a `Poly`, no allocation).
    ws.elim = Poly::new(std::mem::take(&mut ws.elim))
        .trim_negligible()
        .into_coeffs();
    if ws.elim.is_empty() {
        return Ok(Elim::Verdict(Verdict::Infinite));
    }
    if ws.elim.len() == 1 {
        return Ok(Elim::Verdict(Verdict::NoCommonRoot));
    }
    let sources = originals(f1, f2);
    stats.v_degree = sources[0].map_or(0, |g| [f1, f2][g].deg_v());
    Ok(Elim::Eliminant {
        candidates: false,
        sources,
    })
}

/// The coefficients in `v` of `p`, each a polynomial in `u` (`small_resultant`'s layout).
fn rows(p: &Small) -> [[f64; 4]; 4] {
    std::array::from_fn(|j| std::array::from_fn(|i| p.c[4 * j + i]))
}

/// `out ← c` without trailing exact zeros (as `Poly::new`).
fn set_trimmed(out: &mut Vec<f64>, c: &[f64]) {
    out.clear();
    out.extend_from_slice(c);
    *out = Poly::new(std::mem::take(out)).into_coeffs();
}

/// The `f64` Stam path (as `eliminate_groebner_f64` + `certify_f64`): the dense loop, then the
/// certificate, else the Bézout resultant.
fn eliminate_stam(
    ws: &mut SolveWorkspace,
    f1: &Small,
    f2: &Small,
    boxes: [[f64; 2]; 2],
    x_tol: f64,
    stats: &mut SolveStats,
) -> Result<Elim, Error> {
    let [ub, vb] = boxes;
    let u_max = ub[0].abs().max(ub[1].abs());
    let v_max = vb[0].abs().max(vb[1].abs());
    ws.slots[0].set_input(&f1.c);
    ws.slots[1].set_input(&f2.c);
    let found = stam_dense(
        &mut ws.slots,
        &mut ws.order,
        &Corner::new(u_max, v_max),
        Variant::SOLVER,
    );
    let Ok(len) = found else {
        // Abandoned (noise or capacity): says nothing about the roots.
        return fallback(ws, f1, f2, stats);
    };
    let order = ws.order;
    let elements = &order[..len];
    stats.basis_size = len;
    stats.v_degree = elements
        .iter()
        .map(|&k| ws.slots[k].grid_extent().1.saturating_sub(1))
        .filter(|&d| d > 0)
        .min()
        .unwrap_or(0);
    let bound_of = |t: &DensePoly| {
        // The ideal distance, plus the rounding of evaluating ĝ itself, times 2 (as
        // `certify_f64`).
        let (stride, rows) = t.grid_extent();
        let eval = gamma(2 * (stride + rows)) * t.size_at(u_max, v_max);
        2.0 * (t.ideal_distance_at(u_max, v_max) + eval)
    };
    if let Some(&k) = elements
        .iter()
        .find(|&&k| ws.slots[k].is_nonzero_constant())
    {
        let t = &ws.slots[k];
        if t.c[0].abs() > bound_of(t) {
            return Ok(Elim::Verdict(Verdict::NoCommonRoot));
        }
        return fallback(ws, f1, f2, stats);
    }
    let Some(&k) = elements
        .iter()
        .rev()
        .find(|&&k| ws.slots[k].is_univariate_nonconstant())
    else {
        // Neither a unit nor an eliminant: the general path would complete the list by
        // Buchberger first; see the module docs.
        return fallback(ws, f1, f2, stats);
    };
    let bound = bound_of(&ws.slots[k]);
    {
        let (slots, elim) = (&ws.slots, &mut ws.elim);
        elim.clear();
        elim.extend_from_slice(slots[k].row0());
    }
    let certified = certified_candidates_into(
        &ws.elim,
        bound,
        ub,
        x_tol,
        &mut ws.scratch,
        &mut ws.cuts,
        &mut ws.root_stats,
        &mut ws.u_roots,
    );
    if !certified {
        return fallback(ws, f1, f2, stats);
    }
    stats.u_degree = ws.elim.len() - 1;
    Ok(Elim::Eliminant {
        candidates: true,
        sources: originals(f1, f2),
    })
}

/// The resultant in place of an uncertified basis.
fn fallback(
    ws: &mut SolveWorkspace,
    f1: &Small,
    f2: &Small,
    stats: &mut SolveStats,
) -> Result<Elim, Error> {
    stats.fallback = true;
    eliminate_resultant(ws, f1, f2, stats)
}

/// As `solve.rs`' `v_candidates` for `f64`, into `ws.v_roots`; `false` when `g(u, ·)`
/// vanishes identically.
fn v_candidates(
    ws: &mut SolveWorkspace,
    g: &Small,
    u: f64,
    u_err: f64,
    vb: [f64; 2],
    x_tol: f64,
) -> bool {
    let au_wide = u.abs() + u_err;
    let mut coeffs = [0.0; 4];
    let mut significant = false;
    for (j, row) in g.c.chunks_exact(4).enumerate() {
        let (mut c, mut s) = (0.0, 0.0);
        for &a in row.iter().rev() {
            c = c * u + a;
            s = s * au_wide + a.abs();
        }
        let vanished = c.abs() <= VANISH_REL * s;
        significant |= !vanished;
        coeffs[j] = if vanished { 0.0 } else { c };
    }
    ws.v_roots.clear();
    if !significant {
        return false;
    }
    set_trimmed(&mut ws.scratch, &coeffs);
    match ws.scratch.len() {
        0 | 1 => {}
        2 => {
            let v = -ws.scratch[0] / ws.scratch[1];
            if v >= vb[0] && v <= vb[1] {
                ws.v_roots.push(v);
            }
        }
        _ => real_roots_into(
            &mut ws.scratch,
            vb,
            x_tol,
            &mut ws.root_stats,
            &mut ws.v_roots,
        ),
    }
    true
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::solve::solve_general;
    use rand::{Rng, SeedableRng};
    use rand_chacha::ChaCha8Rng;

    /// A random system of degree ≤ 3 in `u` and `v` with a planted common root in `[0, 1]²`
    /// (`F_k = A_k − A_k(u0, v0)`), coefficients spread over `scale`.
    fn planted(rng: &mut ChaCha8Rng, scale: f64) -> (BiPoly<f64>, BiPoly<f64>) {
        let (u0, v0) = (rng.r#gen::<f64>(), rng.r#gen::<f64>());
        let mut one = || {
            let (du, dv) = (rng.gen_range(1..=3), rng.gen_range(1..=3));
            let p = BiPoly::from_fn(du + 1, dv + 1, |i, j| {
                rng.gen_range(-1.0..1.0) * scale.powi((i + j) as i32)
            });
            &p - &BiPoly::constant(p.eval(&u0, &v0))
        };
        (one(), one())
    }

    #[test]
    fn same_solutions_as_the_general_path() {
        // The Bézout path is the same arithmetic: identical solutions. The Stam path differs
        // from the general one only in two documented speed choices (no Buchberger completion;
        // bounds beyond the grid folded), so its roots must agree and its verdicts match.
        let mut rng = ChaCha8Rng::seed_from_u64(0x5eed);
        let (mut stam_certified, mut stam_total) = (0, 0);
        for k in 0..400 {
            let scale = [1.0, 0.3, 0.05][k % 3];
            let (f1, f2) = planted(&mut rng, scale);
            for method in [Method::BezoutResultant, Method::Stam] {
                let opts = SolveOptions {
                    method,
                    ..SolveOptions::default()
                };
                let general = solve_general(&f1, &f2, &opts).unwrap();
                let fast = solve_f64(&f1, &f2, &opts).expect("small system").unwrap();
                if method == Method::BezoutResultant {
                    assert_eq!(fast, general, "system {k}: {f1} / {f2}");
                    continue;
                }
                stam_total += 1;
                stam_certified += usize::from(!fast.stats.fallback);
                assert_eq!(fast.verdict, general.verdict, "system {k}");
                assert_eq!(
                    fast.roots.len(),
                    general.roots.len(),
                    "system {k}: {fast:?}"
                );
                for (a, b) in fast.roots.iter().zip(&general.roots) {
                    assert!(
                        (a.u - b.u).abs() <= 1e-9 && (a.v - b.v).abs() <= 1e-9,
                        "system {k}: {a:?} vs {b:?}"
                    );
                }
            }
        }
        assert!(
            stam_certified * 10 > stam_total,
            "the Stam path certified {stam_certified} of {stam_total}"
        );
    }

    #[test]
    fn workspace_path_equals_system_then_solve() {
        // solve_ray_patch = ray_patch_system + solve, with t from the pivot equation.
        let mut rng = ChaCha8Rng::seed_from_u64(7);
        let mut ws = SolveWorkspace::new();
        for _ in 0..50 {
            let points: Vec<[f64; 3]> = (0..16)
                .map(|_| std::array::from_fn(|_| rng.gen_range(-1.0..1.0)))
                .collect();
            let origin: [f64; 3] = std::array::from_fn(|_| rng.gen_range(-0.5..0.5));
            let dir: [f64; 3] = std::array::from_fn(|_| rng.gen_range(-1.0..1.0));
            for method in [Method::BezoutResultant, Method::Stam] {
                let opts = SolveOptions {
                    method,
                    ..SolveOptions::default()
                };
                let sys = crate::ray_patch_system(&points, 4, 4, &origin, &dir).unwrap();
                let sol = crate::solve(&sys.f1, &sys.f2, &opts).unwrap();
                let got = solve_ray_patch(&mut ws, &points, 4, 4, &origin, &dir, &opts).unwrap();
                assert_eq!(got.roots, sol.roots.as_slice());
                assert_eq!((got.verdict, got.stats), (sol.verdict, sol.stats));
                for (t, r) in got.ts.iter().zip(&sol.roots) {
                    assert_eq!(*t, sys.t_at(&r.u, &r.v), "t by the pivot equation");
                }
            }
        }
    }
}

//! [`solve`] and [`solve_ray_patch`], the crate's two entries into solving `F1 = F2 = 0` in a
//! box, and the general path's elimination (any degree, any method, exact or `f64`): Stam's
//! loop or Buchberger's basis (Theorems 1–3, and the `f64` certificate) or a resultant. The
//! steps after elimination are `driver.rs`'; systems of degree ≤ 3 over `f64` by Stam or
//! Bézout go to the per-ray specialisation (`per_ray.rs`). See `paper-notes/groebner.md` §5
//! and `paper-notes/resultant.md` §3.

use std::cell::RefCell;

use poly::{BiPoly, Scalar};

use crate::basis::Basis;
use crate::bicubic::Bicubic;
use crate::buchberger::{buchberger_tracked, reduce_tracked_keep};
use crate::driver::{
    Buffers, Certifiable, Elimination, certify, eliminate_degenerate, extreme_scale, find_roots,
    finish_resultant, no_common_root_at_all, originals, widened,
};
use crate::error::Error;
use crate::options::{Method, Root, Solution, SolveOptions, SolveStats, Verdict, check_options};
use crate::per_ray::{SolveWorkspace, per_ray_method, solve_bicubic};
use crate::ray_patch::{ray_patch_bicubic, ray_patch_system};
use crate::resultant::{bezout_resultant_v, sylvester_resultant_v};
use crate::scalar::SolveScalar;
use crate::stam_loop::stam_tracked_until;
use crate::tracked::Tracked;

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
///    are merged. A `u`-root at which `F1(u_r, ·)` and `F2(u_r, ·)` both vanish identically
///    is a common line `u = u_r`: [`Verdict::Infinite`]. This is where extraneous factors (a `u`-root with only complex `v`, the
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
/// [`Error::NonFinite`] for NaN/infinite coefficients (refused before any work), [`Error::InvalidRange`] and
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
    check_options(opts)?;
    for (what, f) in [("F1", f1), ("F2", f2)] {
        if !f.coeffs().iter().all(|c| c.nearest_f64().is_finite()) && !T::EXACT {
            return Err(Error::NonFinite { what });
        }
    }
    if !T::EXACT && per_ray_method(opts.method) {
        // Degree ≤ 3 over f64 by Stam or Bézout: the per-ray specialisation, in this
        // thread's workspace.
        if let (Some(a), Some(b)) = (Bicubic::from_bipoly(f1), Bicubic::from_bipoly(f2)) {
            thread_local! {
                static WS: RefCell<SolveWorkspace> = RefCell::new(SolveWorkspace::new());
            }
            let sol = WS.with(|ws| {
                let ws = &mut ws.borrow_mut();
                let (verdict, stats) = solve_bicubic(ws, &a, &b, opts)?;
                Ok::<_, Error>(Solution {
                    roots: ws.buf.roots.clone(),
                    verdict,
                    stats,
                })
            })?;
            return Ok(roots_at_infinity(f1, f2, sol));
        }
    }
    if !T::EXACT {
        // Extreme magnitudes: the same system scaled by powers of two (driver.rs).
        let factor = |f: &BiPoly<T>| {
            extreme_scale(
                &f.coeffs()
                    .iter()
                    .map(Scalar::nearest_f64)
                    .collect::<Vec<_>>(),
            )
        };
        let (s1, s2) = (factor(f1), factor(f2));
        if s1 != 1.0 || s2 != 1.0 {
            let by = |f: &BiPoly<T>, s: f64| f.scale(&T::from_f64(s).expect("a power of two"));
            let sol = solve_general(&by(f1, s1), &by(f2, s2), opts)?;
            return Ok(roots_at_infinity(f1, f2, sol));
        }
    }
    let sol = solve_general(f1, f2, opts)?;
    Ok(if T::EXACT {
        sol // decided in find_roots
    } else {
        roots_at_infinity(f1, f2, sol)
    })
}

/// An `f64` solve that found no root: [`Verdict::NoCommonRoot`] when the system has no common
/// root at all (issue 10, item 5: a non-constant resultant whose roots are all "at
/// `v = ∞`"), decided exactly by `no_common_root_at_all` (driver.rs), which first tries the
/// quick modular proof that a root exists. Only here, in the public `solve`: the per-ray
/// [`solve_ray_patch`] keeps `Finite` with no roots, which the tracer reads the same way.
fn roots_at_infinity<T: SolveScalar>(
    f1: &BiPoly<T>,
    f2: &BiPoly<T>,
    mut sol: Solution,
) -> Solution {
    if sol.verdict == Verdict::Finite && sol.roots.is_empty() && no_common_root_at_all([f1, f2]) {
        sol.verdict = Verdict::NoCommonRoot;
    }
    sol
}

/// [`solve`] by the general path (any degree, any method, exact or `f64`), on checked input.
pub(crate) fn solve_general<T: SolveScalar>(
    f1: &BiPoly<T>,
    f2: &BiPoly<T>,
    opts: &SolveOptions,
) -> Result<Solution, Error> {
    let mut stats = SolveStats::default();
    let mut buf = Buffers::with_degree(f1.deg_u() * f2.deg_v() + f1.deg_v() * f2.deg_u());
    let f = [f1, f2];
    let elimination = match eliminate_degenerate(f, opts.method.is_groebner(), &mut buf, &mut stats)
    {
        Some(e) => e,
        None => match opts.method {
            Method::Stam | Method::Buchberger if T::EXACT => {
                eliminate_groebner_exact(f, opts.method, &mut buf, &mut stats)?
            }
            Method::Stam | Method::Buchberger => {
                eliminate_groebner_f64(f, opts, &mut buf, &mut stats)?
            }
            Method::Resultant | Method::BezoutResultant => {
                eliminate_resultant(f, opts.method, &mut buf, &mut stats)?
            }
        },
    };
    let system_f64 = [f1.map(Scalar::nearest_f64), f2.map(Scalar::nearest_f64)];
    let verdict = find_roots(
        f,
        [&system_f64[0], &system_f64[1]],
        elimination,
        opts,
        &mut buf,
        &mut stats,
    );
    Ok(Solution {
        roots: buf.roots,
        verdict,
        stats,
    })
}

/// Exact Gröbner elimination: Theorems 1–3 on the basis; `v` from the basis elements
/// involving it (lowest `Deg_v` first), then `F1`, `F2`.
fn eliminate_groebner_exact<T: SolveScalar>(
    [f1, f2]: [&BiPoly<T>; 2],
    method: Method,
    buf: &mut Buffers<T>,
    stats: &mut SolveStats,
) -> Result<Elimination<T>, Error> {
    let (_, basis) = tracked_basis(f1, f2, method, |_| false)?.expect("never abandoned");
    stats.basis_size = basis.len();
    stats.coeff_bits = basis
        .elements()
        .iter()
        .filter_map(|g| T::coeff_bits(g.coeffs()))
        .max();
    stats.v_degree = basis.v_elements().first().map_or(0, |g| g.deg_v());
    if basis.contains_unit() {
        return Ok(Elimination::Verdict(Verdict::NoCommonRoot));
    }
    let Some(eliminant) = basis.eliminant() else {
        return Ok(Elimination::Verdict(Verdict::Infinite));
    };
    if !basis.has_finitely_many_roots()
        && crate::buchberger::satisfies_buchberger_criterion(basis.elements())
    {
        return Ok(Elimination::Verdict(Verdict::Infinite));
    }
    buf.elim = eliminant.into_coeffs();
    Ok(Elimination::Eliminant {
        candidates: false,
        derived: basis.v_elements().into_iter().cloned().collect(),
        originals: [Some(0), Some(1)],
        resultant: false,
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

/// The `f64` Gröbner path: the basis, then the certificate ([`certify`]). A Stam run is
/// abandoned as soon as a new element is pure noise on the box ([`Tracked::is_noise`]), and a
/// run that exceeds its limits falls back like an uncertified one (neither says anything about
/// the roots).
fn eliminate_groebner_f64<T: SolveScalar>(
    f: [&BiPoly<T>; 2],
    opts: &SolveOptions,
    buf: &mut Buffers<T>,
    stats: &mut SolveStats,
) -> Result<Elimination<T>, Error> {
    let (ub, vb) = (widened(opts.u_range, opts), widened(opts.v_range, opts));
    let u_max = ub[0].abs().max(ub[1].abs());
    let v_max = vb[0].abs().max(vb[1].abs());
    let corner = |x: f64| T::from_f64(x).expect("a finite box corner");
    let (um, vm) = (corner(u_max), corner(v_max));
    let (tracked, basis) = match tracked_basis(f[0], f[1], opts.method, |t| t.is_noise(&um, &vm)) {
        Ok(Some(found)) => found,
        Ok(None) | Err(Error::LimitExceeded { .. } | Error::Overflow { .. }) => {
            return fallback(f, buf, stats);
        }
        Err(e) => return Err(e),
    };
    stats.basis_size = basis.len();
    stats.v_degree = basis.v_elements().first().map_or(0, |g| g.deg_v());
    let e: Vec<f64>;
    let element = if let Some(t) = tracked
        .iter()
        .find(|t| t.poly.is_constant() && !t.is_zero())
    {
        Certifiable::Constant {
            c: t.poly.coeff(0, 0).nearest_f64(),
            bound: t.certificate_bound(u_max, v_max),
        }
    } else if let Some(t) = basis
        .univariate_u()
        .and_then(|(k, _)| tracked.iter().filter(|t| !t.is_zero()).nth(k))
    {
        e = t.poly.rows_iter().next().map_or_else(Vec::new, |row| {
            poly::Poly::new(row.iter().map(Scalar::nearest_f64).collect()).into_coeffs()
        });
        Certifiable::Univariate {
            e: &e,
            bound: t.certificate_bound(u_max, v_max),
        }
    } else {
        return fallback(f, buf, stats);
    };
    match certify(element, ub, opts.x_tol, originals(f), buf, stats) {
        Some(elim) => Ok(elim),
        None => fallback(f, buf, stats),
    }
}

/// The Bézout resultant in place of an uncertified `f64` Gröbner basis.
fn fallback<T: SolveScalar>(
    f: [&BiPoly<T>; 2],
    buf: &mut Buffers<T>,
    stats: &mut SolveStats,
) -> Result<Elimination<T>, Error> {
    stats.fallback = true;
    eliminate_resultant(f, Method::BezoutResultant, buf, stats)
}

/// `Res_v(F1, F2)` of two equations that both involve `v`, by Sylvester's or Bézout's matrix.
fn eliminate_resultant<T: SolveScalar>(
    f: [&BiPoly<T>; 2],
    method: Method,
    buf: &mut Buffers<T>,
    stats: &mut SolveStats,
) -> Result<Elimination<T>, Error> {
    let res = match method {
        Method::BezoutResultant => bezout_resultant_v(f[0], f[1])?,
        _ => sylvester_resultant_v(f[0], f[1])?,
    };
    buf.elim = res.into_coeffs();
    Ok(finish_resultant(buf, f, stats))
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

/// [`ray_patch_system`](crate::ray_patch_system) and [`solve`] in one call over `f64`, in
/// `ws`'s buffers, with the `t` of each root: the ray tracer's per-ray algebra.
///
/// For patches of degree ≤ 3 in `u` and `v` solved by [`Method::Stam`] or
/// [`Method::BezoutResultant`] it allocates nothing once `ws` has warmed up; the other cases
/// run the general path and copy its result into `ws`. The roots, verdict and statistics are
/// those of `solve(&sys.f1, &sys.f2, opts)` on the same system, except that the fixed-size
/// path does not decide whether a system without roots has no common root at all: it says
/// [`Verdict::Finite`] with no roots where `solve` may say [`Verdict::NoCommonRoot`] (the
/// tracer reads both as a miss; the decision costs more than the solve).
///
/// # Errors
/// As [`ray_patch_system`](crate::ray_patch_system) and [`solve`].
pub fn solve_ray_patch<'w>(
    ws: &'w mut SolveWorkspace,
    points: &[[f64; 3]],
    stride: usize,
    rows: usize,
    origin: &[f64; 3],
    dir: &[f64; 3],
    opts: &SolveOptions,
) -> Result<RayPatchSolution<'w>, Error> {
    let bicubic = stride <= crate::bicubic::BICUBIC_SIDE
        && rows <= crate::bicubic::BICUBIC_SIDE
        && points.len() == stride * rows
        && per_ray_method(opts.method);
    ws.ts.clear();
    let (verdict, stats) = if bicubic {
        let sys = ray_patch_bicubic(points, stride, origin, dir)?;
        let (verdict, stats) = solve_bicubic(ws, &sys.f1, &sys.f2, opts)?;
        for r in &ws.buf.roots {
            ws.ts
                .push((sys.s_pivot.eval(r.u, r.v) - sys.origin_pivot) / sys.dir_pivot);
        }
        (verdict, stats)
    } else {
        let sys = ray_patch_system(points, stride, rows, origin, dir)?;
        let sol = solve(&sys.f1, &sys.f2, opts)?;
        ws.buf.roots.clear();
        ws.buf.roots.extend_from_slice(&sol.roots);
        ws.ts.extend(sol.roots.iter().map(|r| sys.t_at(&r.u, &r.v)));
        (sol.verdict, sol.stats)
    };
    Ok(RayPatchSolution {
        roots: &ws.buf.roots,
        ts: &ws.ts,
        verdict,
        stats,
    })
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
        let (f, fu, fv, a) = crate::driver::eval_grad_rows(p.rows_iter(), u, v);
        assert!((f - p.eval(&u, &v)).abs() <= 1e-12, "value");
        assert!((fu - p.d_du().eval(&u, &v)).abs() <= 1e-12, "∂/∂u");
        assert!((fv - p.d_dv().eval(&u, &v)).abs() <= 1e-12, "∂/∂v");
        assert_eq!(a, p.eval_abs(u, v), "term size");
        let _ = Rat::from_integer(0.into());
    }

    // The per-ray specialisation against the general path.
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
                let fast = solve(&f1, &f2, &opts).unwrap();
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

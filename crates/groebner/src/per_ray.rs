//! The per-ray `f64` specialisation of [`solve`](crate::solve) for systems of degree ≤ 3 in
//! `u` and in `v` (a ray against a bicubic or smaller patch), in a reusable
//! [`SolveWorkspace`]: the elimination step on fixed-size [`Bicubic`] grids — Stam's loop on
//! dense grids (`stam_grid`) with the certificate, or the fixed-size Bézout determinant
//! (`bezout_bicubic`) — followed by the shared steps of `driver.rs`. After a warm-up a solve
//! allocates nothing.
//!
//! Departures from the general path, all in the Stam method and all for speed (none affects
//! soundness: the certificate is checked as before, and an uncertified run falls back):
//! * when Stam's list has neither a constant nor a univariate element, the general path
//!   completes it by Buchberger's algorithm before trying the certificate; here the resultant
//!   is solved directly (`paper-notes/groebner.md` §5 gives the share of systems this costs),
//!   and
//! * the loop stops at its first eliminant and does not rescale after every `R2` step, and
//!   bounds beyond the grid (and, at every `R2`, beyond each row's coefficients) are folded
//!   into one weighted scalar (the `stam_grid` module docs).
//!
//! The Bézout path is the same arithmetic as the general one (identical solutions, tested).
//!
//! Allocation: none after warm-up, except in degenerate inputs (both equations free of `v`:
//! a gcd) and in `poly`'s exact root-isolation fallback when a query needs it
//! ([`poly::RootStats::exact_fallbacks`]).

use crate::bezout_bicubic::{BICUBIC_DEGREE, bezout_bicubic_det};
use crate::bicubic::Bicubic;
use crate::driver::{
    Buffers, Certifiable, Elimination, certify, deg_v, eliminate_degenerate, extreme_scale,
    find_roots, finish_resultant, originals, widened,
};
use crate::error::Error;
use crate::options::{Method, SolveOptions, SolveStats, Verdict, check_options};
use crate::stam_grid::{Corner, DensePoly, MAX_ELEMENTS, SLOTS, Variant, stam_dense};

/// Degree of the resultant of two bicubic equations (Kajiya's bound), the size the buffers
/// start at.
const BICUBIC_RESULTANT_DEGREE: usize = 2 * BICUBIC_DEGREE * BICUBIC_DEGREE;

/// Reusable buffers for [`solve_ray_patch`](crate::solve_ray_patch) (and the `f64` bicubic
/// path of [`solve`](crate::solve)): one per thread. After the first few solves have grown
/// its buffers, a solve of a system of degree ≤ 3 in `u` and `v` by [`Method::Stam`] or
/// [`Method::BezoutResultant`] allocates nothing (see the `per_ray` module docs for the rare
/// exceptions).
#[derive(Debug)]
pub struct SolveWorkspace {
    /// Stam's elements (dense, with bounds).
    slots: Vec<DensePoly>,
    order: [usize; MAX_ELEMENTS],
    /// The shared steps' buffers.
    pub(crate) buf: Buffers<f64>,
    /// `t` of each root ([`solve_ray_patch`](crate::solve_ray_patch)).
    pub(crate) ts: Vec<f64>,
}

impl Default for SolveWorkspace {
    fn default() -> Self {
        SolveWorkspace {
            slots: vec![DensePoly::default(); SLOTS],
            order: [0; MAX_ELEMENTS],
            buf: Buffers::with_degree(BICUBIC_RESULTANT_DEGREE),
            ts: Vec::with_capacity(16),
        }
    }
}

impl SolveWorkspace {
    /// A workspace with buffers sized for bicubic systems.
    pub fn new() -> Self {
        SolveWorkspace::default()
    }
}

/// Whether the per-ray path handles `method` (the other methods run the general path).
pub(crate) fn per_ray_method(method: Method) -> bool {
    matches!(method, Method::Stam | Method::BezoutResultant)
}

/// The one entry into the fixed-size path: `solve` on `f1`, `f2` (degree ≤ 3 in each
/// variable) by [`Method::Stam`] or [`Method::BezoutResultant`], roots into `ws.buf.roots`.
pub(crate) fn solve_bicubic(
    ws: &mut SolveWorkspace,
    f1: &Bicubic,
    f2: &Bicubic,
    opts: &SolveOptions,
) -> Result<(Verdict, SolveStats), Error> {
    debug_assert!(per_ray_method(opts.method), "a per-ray method");
    check_options(opts)?;
    for (what, f) in [("F1", f1), ("F2", f2)] {
        if !f.c.iter().all(|c| c.is_finite()) {
            return Err(Error::NonFinite { what });
        }
    }
    let scaled = |f: &Bicubic| {
        let s = extreme_scale(&f.c);
        Bicubic {
            c: f.c.map(|c| c * s),
        }
    };
    let (f1, f2) = (&scaled(f1), &scaled(f2));
    let mut stats = SolveStats::default();
    let f = [f1, f2];
    let elimination =
        match eliminate_degenerate(f, opts.method.is_groebner(), &mut ws.buf, &mut stats) {
            Some(e) => e,
            None if opts.method == Method::Stam => eliminate_stam(ws, f, opts, &mut stats),
            None => eliminate_resultant(ws, f, &mut stats),
        };
    let verdict = find_roots(f, f, elimination, opts, &mut ws.buf, &mut stats);
    Ok((verdict, stats))
}

/// The Bézout resultant of two bicubics that both involve `v`, in `ws.buf.elim`.
fn eliminate_resultant(
    ws: &mut SolveWorkspace,
    f: [&Bicubic; 2],
    stats: &mut SolveStats,
) -> Elimination<f64> {
    let n = deg_v(f[0]).max(deg_v(f[1]));
    let det = bezout_bicubic_det(&f[0].coeffs_in_v(), &f[1].coeffs_in_v(), n);
    ws.buf.elim.clear();
    ws.buf.elim.extend_from_slice(&det);
    finish_resultant(&mut ws.buf, f, stats)
}

/// The `f64` Stam path: the dense loop, then the certificate, else the Bézout resultant.
fn eliminate_stam(
    ws: &mut SolveWorkspace,
    f: [&Bicubic; 2],
    opts: &SolveOptions,
    stats: &mut SolveStats,
) -> Elimination<f64> {
    let (ub, vb) = (widened(opts.u_range, opts), widened(opts.v_range, opts));
    let u_max = ub[0].abs().max(ub[1].abs());
    let v_max = vb[0].abs().max(vb[1].abs());
    ws.slots[0].set_input(&f[0].c);
    ws.slots[1].set_input(&f[1].c);
    let found = stam_dense(
        &mut ws.slots,
        &mut ws.order,
        &Corner::new(u_max, v_max),
        Variant::SOLVER,
    );
    let Ok(len) = found else {
        // Abandoned (noise or capacity): says nothing about the roots.
        return fallback(ws, f, stats);
    };
    let elements = &ws.order[..len];
    stats.basis_size = len;
    stats.v_degree = elements
        .iter()
        .map(|&k| ws.slots[k].grid_extent().1.saturating_sub(1))
        .filter(|&d| d > 0)
        .min()
        .unwrap_or(0);
    let slots = &ws.slots;
    let element = if let Some(&k) = elements.iter().find(|&&k| slots[k].is_nonzero_constant()) {
        let t = &slots[k];
        Certifiable::Constant {
            c: t.c[0],
            bound: t.certificate_bound(u_max, v_max),
        }
    } else if let Some(&k) = elements
        .iter()
        .rev()
        .find(|&&k| slots[k].is_univariate_nonconstant())
    {
        let t = &slots[k];
        Certifiable::Univariate {
            e: t.row0(),
            bound: t.certificate_bound(u_max, v_max),
        }
    } else {
        // Neither a unit nor an eliminant: the general path would complete the list by
        // Buchberger first; see the module docs.
        return fallback(ws, f, stats);
    };
    match certify(element, ub, opts.x_tol, originals(f), &mut ws.buf, stats) {
        Some(e) => e,
        None => fallback(ws, f, stats),
    }
}

/// The resultant in place of an uncertified basis.
fn fallback(ws: &mut SolveWorkspace, f: [&Bicubic; 2], stats: &mut SolveStats) -> Elimination<f64> {
    stats.fallback = true;
    eliminate_resultant(ws, f, stats)
}

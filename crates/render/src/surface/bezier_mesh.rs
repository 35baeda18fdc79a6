//! [`BezierMesh`]: Bézier patches traced exactly — every ray/patch intersection is a common
//! root of two algebraic curves `F1(u, v) = F2(u, v) = 0` (J. Stam 1988, "Ray tracing
//! polynomial patches using Groebner bases", article §2–4; `ray3.c`), solved by
//! [`groebner::solve`] with Stam's Gröbner reduction or Kajiya's resultant.
//!
//! Scene syntax (`paper-notes/bezier-patches.md`):
//! ```text
//! #object
//! Type = BEZIER_PATCH
//! Control points = saddle.pts   // Stam's form: 16 lines `x y z`, P[0][0] P[0][1] … P[3][3]
//! Method = GROEBNER             // or RESULTANT; GROEBNER_EXACT, RESULTANT_EXACT for
//!                               // exact-rational reference renders (default GROEBNER)
//!
//! #object
//! Type = BEZIER_MESH
//! Control points = teapot.bpt   // count, then per patch `n m` and (n+1)(m+1) lines `x y z`
//! Method = RESULTANT
//! ```
//!
//! Per frame (here: at construction) each patch is cut into `k × k` sub-patches by de
//! Casteljau's algorithm (the article's §4 "partial subdivision … with tight bounds"), each
//! converted once to the power basis (Stam `CalcCoef`, §4.1) about the centre of its box, and a
//! BVH is built over the sub-patch boxes. Per ray and sub-patch whose box the ray crosses:
//! 1. move the ray origin to where it enters the box and express it about the box centre
//!    (small numbers near the surface, as for implicit surfaces);
//! 2. build `F1`, `F2` by eliminating `t` with the largest direction component as pivot
//!    ([`groebner::ray_patch_system`], article §2 eq. 2–5);
//! 3. eliminate `v` and solve ([`groebner::solve`] over the sub-patch's `[0, 1]²`): Gröbner
//!    eliminant or resultant, real `u`-roots by `poly`, back-substitution, residual check;
//! 4. each root gives `t` by the pivot equation (article §4.4); it is kept if the 3-D residual
//!    `|S(u, v) − R(t)|` passes [`HIT_RESIDUAL_REL`] and `t` is the nearest in range.

use std::ops::Range;
use std::time::Instant;

use glam::{DVec2, DVec3};
use groebner::{SolveOptions, SolveWorkspace, Verdict, ray_patch_system, solve, solve_ray_patch};
use poly::{Rat, Scalar};

use super::bezier_patch::BezierPatch;
use super::{Hit, Surface, SurfaceGeometry, SurfaceKind};
use crate::aggregate::Bvh;
use crate::geometry::{Bounds3, Ray, gamma};
use crate::methods::PatchMethod;
use crate::scene::ControlNet;
use crate::stats::PatchStats;
use crate::workspace::Workspace;

/// Accepted 3-D residual of a hit, relative to the size of the numbers involved:
/// `|S(u, v) − R(t)| ≤ HIT_RESIDUAL_REL · (diag + |O'| + |t'·D|)`, with `diag` the diagonal of
/// the sub-patch's box and `O'`, `t'` the ray origin and parameter about the box (so the bound
/// scales with the sub-patch, not with the distance to the camera).
///
/// Derivation: the solver accepts `(u, v)` whose relative residual on `F1`, `F2` is at most
/// about 2⁻³⁰ ≈ 1e-9 (`groebner::DEFAULT_F_TOL_REL`), and `F_a = D_k·(S_a − R_a(t))` by the
/// construction of article eq. 5, so a true root leaves `|S − R(t)|` of order 1e-9 of the terms'
/// size. `1e-7` leaves a factor 100 for the conditioning of the pivot division (`|D_k| ≥
/// |D|/√3`); an extraneous candidate (a root of an eliminant factor with no common `v`) is off
/// by a macroscopic fraction of the patch and fails by many orders of magnitude.
pub const HIT_RESIDUAL_REL: f64 = 1e-7;

/// Relative size of the error box reported for a hit point (`SurfaceGeometry::p_err`), per
/// unit of the sub-patch diagonal plus the point's magnitude. It must exceed both the accepted
/// residual ([`HIT_RESIDUAL_REL`]) and the solver's root tolerance (`x_tol = 1e-10` in the
/// parameters, times `|∂S|`), so that a spawned ray moved off the surface by it does not find
/// the same point again.
pub const HIT_P_ERR_REL: f64 = 4e-7;

// The derivations above, against the solver's defaults that the mesh solves with
// (`SolveOptions::default()`): the residual bound leaves a factor 100 over groebner's accepted
// residual, and the error box exceeds both the residual bound and the root tolerance.
const _: () = assert!(
    HIT_RESIDUAL_REL >= 100.0 * groebner::DEFAULT_F_TOL_REL,
    "the 3-D residual bound must leave a factor 100 over the solver's residual"
);
const _: () = assert!(
    HIT_P_ERR_REL > HIT_RESIDUAL_REL && HIT_P_ERR_REL > groebner::DEFAULT_X_TOL,
    "a hit's error box must exceed the accepted residual and the root tolerance"
);

/// Default number of sub-patches per patch side (the teapot's 32 patches become 8192 pieces).
/// Smaller pieces reject more rays by their boxes and hulls before any algebra, and the
/// algebra of a small piece is cheaper (its eliminant is better conditioned, so `poly` needs
/// its exact fallback less often); the price is setup time and memory per frame. 16 is where
/// the trace time stops falling fast while setup stays small: the measurements per
/// subdivision are in `paper-notes/bezier-patches.md` §4.
pub const DEFAULT_SUBDIVISION: usize = 16;

/// Largest subdivision accepted per side (64² pieces per patch).
pub const MAX_SUBDIVISION: usize = 64;

/// Relative `|∂S/∂u × ∂S/∂v|` below which the normal is taken as degenerate (compared with
/// `|∂S/∂u|·|∂S/∂v|`, i.e. the sine of the angle between the partials): a collapsed edge such
/// as the teapot's lid apex, where `∂S/∂u = 0`, or a fold where the partials are parallel.
const DEGENERATE_NORMAL_REL: f64 = 1e-10;

/// First parameter step of the fallback normal at a degenerate point: the normal is taken at a
/// point moved this far (then 10×, 100×, …) towards the patch centre, which converges to the
/// limit normal along the collapsed edge.
const NORMAL_FALLBACK_STEP: f64 = 1e-6;

/// Points tried for the fallback normal: `(u, v)` itself, then the steps
/// [`NORMAL_FALLBACK_STEP`] · 10^k, k = 0…4, the last 2% of the way to the patch centre —
/// still next to the degenerate point, where the limit normal is approached.
const NORMAL_FALLBACK_TRIES: usize = 6;

/// Control points closer than this, relative to the patch size plus its coordinates'
/// magnitude, count as one point when detecting a collapsed edge (the `.bpt` data repeat the
/// apex exactly; the margin covers de Casteljau rounding in sub-patches).
const COLLAPSED_EDGE_REL: f64 = 1e-12;

/// One piece of a patch, ready for the per-ray algebra.
#[derive(Clone, Debug)]
struct SubPatch {
    /// Index of the patch it comes from.
    parent: u32,
    /// Its parameter window in the parent: `u0 + (u1 − u0)·s`.
    u: [f64; 2],
    /// `v0 + (v1 − v0)·r`.
    v: [f64; 2],
    /// Centre of its box: the origin of `power`.
    centre: DVec3,
    /// Power-basis coefficients about `centre` (`u^i v^j` at `j * (n + 1) + i`).
    power: Vec<[f64; 3]>,
    /// `n + 1`.
    stride: usize,
    /// `m + 1`.
    rows: usize,
    /// The control-point box, slightly padded.
    bounds: Bounds3,
    /// Its diagonal.
    diag: f64,
    /// Collapsed edges: a point (about `centre`) that a whole edge maps to, with the local
    /// parameters of the edge's midpoint (the teapot's lid apex and bottom centre).
    collapsed: Vec<(DVec3, f64, f64)>,
    /// The control points about `centre` (the Bernstein coefficients, for the hull test).
    control: Vec<DVec3>,
}

impl SubPatch {
    fn new(parent: u32, patch: &BezierPatch, u: [f64; 2], v: [f64; 2]) -> Self {
        let piece = patch.sub_patch(u, v);
        let b = piece.bounds();
        let centre = (b.min + b.max) * 0.5;
        let diag = b.diagonal();
        // Pad by the rounding of the de Casteljau steps (a flat patch's box has zero width,
        // and the slab test must still see it).
        let pad = DVec3::splat(gamma(16) * (b.min.abs().max(b.max.abs()).max_element() + diag));
        let mut power: Vec<[f64; 3]> = piece.power_coeffs().iter().map(|c| c.to_array()).collect();
        for k in 0..3 {
            power[0][k] -= centre[k];
        }
        let [n, m] = piece.degree();
        let collapsed = collapsed_edges(&piece)
            .into_iter()
            .map(|(c, s, r)| (c - centre, s, r))
            .collect();
        SubPatch {
            parent,
            u,
            v,
            centre,
            power,
            stride: n + 1,
            rows: m + 1,
            bounds: Bounds3::new(b.min - pad, b.max + pad),
            diag,
            collapsed,
            control: piece.control_points().iter().map(|p| *p - centre).collect(),
        }
    }

    /// `S(s, r)` about `centre`, with partials, by nested Horner.
    fn eval(&self, s: f64, r: f64) -> (DVec3, DVec3, DVec3) {
        let (mut p, mut ps, mut pr) = (DVec3::ZERO, DVec3::ZERO, DVec3::ZERO);
        for row in self.power.chunks_exact(self.stride).rev() {
            let (mut a, mut da) = (DVec3::ZERO, DVec3::ZERO);
            for c in row.iter().rev() {
                da = da * s + a;
                a = a * s + DVec3::from_array(*c);
            }
            pr = pr * r + p;
            p = p * r + a;
            ps = ps * r + da;
        }
        (p, ps, pr)
    }

    /// Parent parameters of local `(s, r)`.
    fn to_parent(&self, s: f64, r: f64) -> (f64, f64) {
        let u = self.u[0] + (self.u[1] - self.u[0]) * s;
        let v = self.v[0] + (self.v[1] - self.v[0]) * r;
        (u.clamp(0.0, 1.0), v.clamp(0.0, 1.0))
    }
}

/// The edges of `patch` whose control points all coincide (to [`COLLAPSED_EDGE_REL`] of the
/// patch size), as `(point, s, r)` with `(s, r)` the edge's midpoint parameters.
///
/// Such an edge maps to one point, so a ray through that point meets the patch along a whole
/// parameter line: `F1`, `F2` share the factor of that line (a factor `u^k` of the resultant),
/// the algebra reports infinitely many roots or a `u`-root with no isolated `v`, and the point
/// must be found directly.
fn collapsed_edges(patch: &BezierPatch) -> Vec<(DVec3, f64, f64)> {
    let [n, m] = patch.degree();
    let pts = patch.control_points();
    let size = patch.bounds().diagonal();
    let tol =
        COLLAPSED_EDGE_REL * (size + pts.iter().fold(0.0f64, |a, p| a.max(p.abs().max_element())));
    let mut out = Vec::new();
    let mut edge = |idx: Vec<usize>, s: f64, r: f64| {
        let first = pts[idx[0]];
        if idx
            .iter()
            .all(|&k| (pts[k] - first).abs().max_element() <= tol)
        {
            out.push((first, s, r));
        }
    };
    edge((0..=m).collect(), 0.0, 0.5); // u = 0: row i = 0
    edge((0..=m).map(|j| n * (m + 1) + j).collect(), 1.0, 0.5); // u = 1
    edge((0..=n).map(|i| i * (m + 1)).collect(), 0.5, 0.0); // v = 0: column j = 0
    edge((0..=n).map(|i| i * (m + 1) + m).collect(), 0.5, 1.0); // v = 1
    out
}

/// Whether the ray `o + t·d` (about the piece's centre) certainly misses the piece: it misses
/// the convex hull of the control points.
///
/// The planes containing the ray are those with a normal `α·n_1 + β·n_2`, where
/// `n_a = D_k e_a − D_a e_k` are the normals of `F1 = 0` and `F2 = 0` of article eq. 5 in space
/// (`F_a(u, v) = n_a·(S(u, v) − o)`, so `n_a·(P_ij − o)` are `F_a`'s Bernstein coefficients).
/// Projecting along the ray, control point `P_ij` goes to `p_ij = (n_1·(P_ij − o),
/// n_2·(P_ij − o))`, and the ray meets the hull iff the origin lies in the convex hull of the
/// `p_ij`. When all `p_ij` lie strictly on one side of a line through the origin, the
/// combination `α F1 + β F2` has Bernstein coefficients of one strict sign, so (convex-hull
/// property) it has no zero on `[0, 1]²` and `F1`, `F2` have no common root there. The line
/// is found from the angular extremes of the `p_ij` (seen from the first one), and then
/// verified on every point with the margin [`HULL_MARGIN_REL`], so rounding only ever keeps a
/// borderline piece for the algebra. The axis lines (`α β = 0`) were the whole test before;
/// with the general line, `teapot.scene` at 420² rejects 121,119 ray/piece pairs instead of
/// 43,901 and solves 112,512 systems instead of 189,730 (the same image).
fn misses_hull(piece: &SubPatch, o: DVec3, d: DVec3) -> bool {
    let a = d.abs();
    let k = if a.x >= a.y && a.x >= a.z {
        0
    } else if a.y >= a.z {
        1
    } else {
        2
    };
    let (ia, ib) = match k {
        0 => (1, 2),
        1 => (0, 2),
        _ => (0, 1),
    };
    let normal = |axis: usize| {
        let mut n = DVec3::ZERO;
        n[axis] = d[k];
        n[k] = -d[axis];
        n
    };
    let (n1, n2) = (normal(ia), normal(ib));
    let scale = HULL_MARGIN_REL * (piece.diag + o.length()) * d.length();
    let mut pts = [DVec2::ZERO; 16];
    let count = piece.control.len().min(16);
    let (mut lo, mut hi) = (DVec2::INFINITY, DVec2::NEG_INFINITY);
    for (p, c) in pts.iter_mut().zip(&piece.control) {
        let r = *c - o;
        *p = DVec2::new(n1.dot(r), n2.dot(r));
        lo = lo.min(*p);
        hi = hi.max(*p);
    }
    // The axis lines first (cheap, and most rejections).
    if lo.x > scale || hi.x < -scale || lo.y > scale || hi.y < -scale {
        return true;
    }
    if piece.control.len() > 16 {
        return false;
    }
    let pts = &pts[..count];
    // Angular extremes seen from p0: rotate every point by −angle(p0) (multiply by conj(p0))
    // and compare pseudo-angles, monotone in the angle in (−π, π].
    let p0 = pts[0];
    if p0.length() <= 2.0 * scale {
        return false;
    }
    let pseudo = |q: DVec2| {
        let s = q.x.abs() + q.y.abs();
        if s == 0.0 {
            return f64::NAN;
        }
        let t = 1.0 - q.x / s; // 0 at angle 0, 2 at ±π
        if q.y >= 0.0 { t } else { -t }
    };
    let (mut amin, mut amax) = (0.0f64, 0.0f64);
    let (mut pmin, mut pmax) = (p0, p0);
    for &q in &pts[1..] {
        let r = DVec2::new(q.x * p0.x + q.y * p0.y, q.y * p0.x - q.x * p0.y);
        let a = pseudo(r);
        if a.is_nan() {
            return false;
        }
        if a < amin {
            (amin, pmin) = (a, q);
        }
        if a > amax {
            (amax, pmax) = (a, q);
        }
    }
    // Within an open half-plane iff the extremes are less than π apart.
    if amax - amin >= 2.0 || pmin.perp_dot(pmax) <= 0.0 && amax > amin {
        return false;
    }
    // The bisector of the extremes as the line's normal, verified on every point.
    let n = pmin.normalize_or_zero() + pmax.normalize_or_zero();
    let len = n.length();
    if len.is_nan() || len <= 0.0 {
        return false;
    }
    let n = n / len;
    pts.iter().all(|q| q.dot(n) > 2.0 * scale)
}

/// Margin of the hull test, relative to the piece size plus the origin's distance times `|D|`:
/// a plane that passes within this of a control point does not reject (rounding of the dot
/// products is about `γ(4)` of the same scale).
const HULL_MARGIN_REL: f64 = 1e-9;

/// The reference path: the same system and solve over exact rationals (every `f64` input is
/// a rational, so nothing is rounded until the roots are refined to `x_tol`), with `t` from the
/// pivot equation evaluated exactly at the `f64` roots.
fn solve_exact(
    piece: &SubPatch,
    o: DVec3,
    d: DVec3,
    opts: &SolveOptions,
) -> Result<(groebner::Solution, Vec<f64>), groebner::Error> {
    let q = |x: f64| Rat::from_f64_exact(x).ok_or(groebner::Error::NonFinite { what: "patch" });
    let q3 =
        |v: [f64; 3]| -> Result<[Rat; 3], groebner::Error> { Ok([q(v[0])?, q(v[1])?, q(v[2])?]) };
    let pts = piece
        .power
        .iter()
        .map(|c| q3(*c))
        .collect::<Result<Vec<_>, _>>()?;
    let sys = ray_patch_system(
        &pts,
        piece.stride,
        piece.rows,
        &q3(o.to_array())?,
        &q3(d.to_array())?,
    )?;
    let sol = solve(&sys.f1, &sys.f2, opts)?;
    let mut ts = Vec::with_capacity(sol.roots.len());
    for r in &sol.roots {
        ts.push(sys.t_at(&q(r.u)?, &q(r.v)?).nearest_f64());
    }
    Ok((sol, ts))
}

/// The nearest intersection of a ray with one patch of a mesh.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PatchHit {
    /// Ray parameter.
    pub t: f64,
    /// Index of the patch in the mesh.
    pub patch: usize,
    /// Patch parameters of the hit.
    pub uv: DVec2,
}

/// A set of Bézier patches traced as one surface, through a BVH of sub-patches.
#[derive(Clone, Debug)]
pub struct BezierMesh {
    patches: Vec<BezierPatch>,
    pieces: Vec<SubPatch>,
    bvh: Bvh,
    bounds: Bounds3,
    method: PatchMethod,
    solve_opts: SolveOptions,
}

impl BezierMesh {
    /// The mesh of the patches with control nets `nets` traced with `method`, each patch cut
    /// into [`DEFAULT_SUBDIVISION`]² pieces. `None` for an empty list.
    pub fn new(nets: &[ControlNet], method: PatchMethod) -> Option<Self> {
        Self::with_subdivision(nets, method, DEFAULT_SUBDIVISION)
    }

    /// As [`BezierMesh::new`] with `k × k` pieces per patch (`k` clamped to
    /// `1..=MAX_SUBDIVISION`).
    pub fn with_subdivision(nets: &[ControlNet], method: PatchMethod, k: usize) -> Option<Self> {
        if nets.is_empty() {
            return None;
        }
        let patches: Vec<BezierPatch> = nets.iter().map(BezierPatch::new).collect();
        let k = k.clamp(1, MAX_SUBDIVISION);
        let step = 1.0 / k as f64;
        let mut pieces = Vec::with_capacity(patches.len() * k * k);
        for (index, patch) in patches.iter().enumerate() {
            for a in 0..k {
                for b in 0..k {
                    let u = [
                        a as f64 * step,
                        if a + 1 == k {
                            1.0
                        } else {
                            (a + 1) as f64 * step
                        },
                    ];
                    let v = [
                        b as f64 * step,
                        if b + 1 == k {
                            1.0
                        } else {
                            (b + 1) as f64 * step
                        },
                    ];
                    pieces.push(SubPatch::new(index as u32, patch, u, v));
                }
            }
        }
        let boxes: Vec<Bounds3> = pieces.iter().map(|p| p.bounds).collect();
        let bounds = boxes.iter().skip(1).fold(boxes[0], |a, b| a.union(b));
        let solve_opts = SolveOptions {
            method: method.solver_method(),
            ..SolveOptions::default()
        };
        Some(BezierMesh {
            bvh: Bvh::new(&boxes),
            patches,
            pieces,
            bounds,
            method,
            solve_opts,
        })
    }

    /// The patches.
    pub fn patches(&self) -> &[BezierPatch] {
        &self.patches
    }

    /// The elimination method.
    pub fn method(&self) -> PatchMethod {
        self.method
    }

    /// The same mesh traced with another method.
    pub fn set_method(&mut self, method: PatchMethod) {
        self.method = method;
        self.solve_opts.method = method.solver_method();
    }

    /// The nearest hit with `t` in `t_range` (open), with its patch and parameters; counts in
    /// `stats`. With `any`, stops at the first hit found (shadow rays). A fresh solver
    /// workspace per call: the tracer uses [`BezierMesh::nearest_hit_in`] with its thread's.
    pub fn nearest_hit(
        &self,
        ray: &Ray,
        t_range: Range<f64>,
        stats: &mut PatchStats,
        any: bool,
    ) -> Option<(PatchHit, u32)> {
        self.nearest_hit_in(ray, t_range, stats, &mut SolveWorkspace::new(), any)
    }

    /// [`BezierMesh::nearest_hit`] solving in `solver`'s buffers: no allocation per ray in the
    /// `f64` modes once `solver` has warmed up.
    pub fn nearest_hit_in(
        &self,
        ray: &Ray,
        t_range: Range<f64>,
        stats: &mut PatchStats,
        solver: &mut SolveWorkspace,
        any: bool,
    ) -> Option<(PatchHit, u32)> {
        let mut best: Option<(PatchHit, u32)> = None;
        let mut visits = 0;
        self.bvh
            .traverse(ray, t_range.clone(), &mut visits, |item, t_max| {
                let piece = &self.pieces[item as usize];
                if let Some((t, s, r)) =
                    self.test_piece(piece, ray, t_range.start..t_max, stats, solver)
                {
                    let (u, v) = piece.to_parent(s, r);
                    best = Some((
                        PatchHit {
                            t,
                            patch: piece.parent as usize,
                            uv: DVec2::new(u, v),
                        },
                        item,
                    ));
                    if any {
                        return None;
                    }
                    return Some(t);
                }
                Some(t_max)
            });
        stats.bvh_node_visits += visits;
        best
    }

    /// One ray/sub-patch test: `(t, s, r)` of the nearest verified root in range.
    fn test_piece(
        &self,
        piece: &SubPatch,
        ray: &Ray,
        range: Range<f64>,
        stats: &mut PatchStats,
        solver: &mut SolveWorkspace,
    ) -> Option<(f64, f64, f64)> {
        let Some(seg) = piece.bounds.intersect_ray(ray, range.clone()) else {
            stats.bbox_rejects += 1;
            return None;
        };
        let start = Instant::now();
        let found = self.solve_piece(piece, ray, seg.start, range, stats, solver);
        stats.test_nanos += start.elapsed().as_nanos() as u64;
        found
    }

    fn solve_piece(
        &self,
        piece: &SubPatch,
        ray: &Ray,
        t0: f64,
        range: Range<f64>,
        stats: &mut PatchStats,
        solver: &mut SolveWorkspace,
    ) -> Option<(f64, f64, f64)> {
        // Step 1: origin at the box entry, about the box centre.
        let o = ray.at(t0) - piece.centre;
        let d = ray.dir;
        if misses_hull(piece, o, d) {
            stats.hull_rejects += 1;
            return None;
        }
        stats.solves += 1;
        // Step 2: F1, F2 (article eq. 5), pivot = largest |D_k|; step 3: eliminate v and
        // solve in [0, 1]² (over exact rationals in the reference modes). The f64 modes run in
        // the thread's solver workspace and allocate nothing.
        let solve_start = Instant::now();
        let exact = if self.method.is_exact() {
            Some(solve_exact(piece, o, d, &self.solve_opts))
        } else {
            None
        };
        let solved = if let Some(found) = &exact {
            found
                .as_ref()
                .map_err(Clone::clone)
                .map(|(sol, ts)| (sol.roots.as_slice(), ts.as_slice(), sol.verdict, sol.stats))
        } else {
            solve_ray_patch(
                solver,
                &piece.power,
                piece.stride,
                piece.rows,
                &o.to_array(),
                &d.to_array(),
                &self.solve_opts,
            )
            .map(|sol| (sol.roots, sol.ts, sol.verdict, sol.stats))
        };
        stats.solve_nanos += solve_start.elapsed().as_nanos() as u64;
        let (roots, ts, verdict, st) = match solved {
            Ok(x) => x,
            Err(_) => {
                stats.errors += 1;
                return None;
            }
        };
        stats.record_degrees(st.basis_size, st.u_degree, st.v_degree);
        stats.rejected_by_solver += st.rejected as u64;
        stats.groebner_fallbacks += u64::from(st.fallback);
        match verdict {
            Verdict::NoCommonRoot => stats.no_common_root += 1,
            Verdict::Infinite => stats.infinite += 1,
            _ => {}
        }
        // Step 4: t by the pivot equation, 3-D residual, nearest in range.
        let mut best: Option<(f64, f64, f64)> = None;
        for (root, &s) in roots.iter().zip(ts) {
            let t = t0 + s;
            let t_max = best.map_or(range.end, |b| b.0);
            if !(t > range.start && t < t_max) {
                stats.outside_range += 1;
                continue;
            }
            let (p, _, _) = piece.eval(root.u, root.v);
            let q = o + d * s;
            let scale = piece.diag + o.length() + (d * s).length();
            let residual = (p - q).length();
            if residual.is_nan() || residual > HIT_RESIDUAL_REL * scale {
                stats.rejected_by_residual += 1;
                continue;
            }
            best = Some((t, root.u, root.v));
        }
        // A ray through a collapsed edge's point: the algebra sees a whole common line there
        // and reports no isolated root (see `collapsed_edges`), so test the point itself.
        for &(c, cs, cr) in &piece.collapsed {
            let s = (c - o).dot(d) / d.length_squared();
            let q = o + d * s;
            let t = t0 + s;
            let scale = piece.diag + o.length() + (d * s).length();
            let t_max = best.map_or(range.end, |b| b.0);
            if (q - c).length() <= HIT_RESIDUAL_REL * scale && t > range.start && t < t_max {
                best = Some((t, cs, cr));
            }
        }
        best
    }

    /// The unit normal `∂S/∂u × ∂S/∂v` of patch `index` at `(u, v)`, moved towards the patch
    /// centre at a collapsed edge (a step of `NORMAL_FALLBACK_STEP` = 1e-6, then 10×, …);
    /// `None` if no nearby point has a normal either.
    pub fn normal(&self, index: usize, u: f64, v: f64) -> Option<DVec3> {
        let patch = &self.patches[index];
        let mut step = 0.0;
        for _ in 0..NORMAL_FALLBACK_TRIES {
            let (uu, vv) = (u + (0.5 - u) * step * 2.0, v + (0.5 - v) * step * 2.0);
            let (_, su, sv) = patch.eval_with_partials(uu, vv);
            let n = su.cross(sv);
            let len = n.length();
            if len.is_finite()
                && len > DEGENERATE_NORMAL_REL * su.length() * sv.length()
                && len > 0.0
            {
                return Some(n / len);
            }
            step = if step == 0.0 {
                NORMAL_FALLBACK_STEP
            } else {
                step * 10.0
            };
        }
        None
    }
}

impl Surface for BezierMesh {
    fn kind(&self) -> SurfaceKind {
        SurfaceKind::BezierPatch
    }

    fn bounds(&self) -> Option<Bounds3> {
        Some(self.bounds)
    }

    fn intersect(&self, ray: &Ray, t_range: Range<f64>, ws: &mut Workspace) -> Option<Hit> {
        let (hit, item) =
            self.nearest_hit_in(ray, t_range, &mut ws.stats.patches, &mut ws.solver, false)?;
        Some(Hit {
            t: hit.t,
            local: ray.at(hit.t),
            uv: Some(hit.uv),
            tag: item,
        })
    }

    fn occluded(&self, ray: &Ray, t_range: Range<f64>, ws: &mut Workspace) -> bool {
        self.nearest_hit_in(ray, t_range, &mut ws.stats.patches, &mut ws.solver, true)
            .is_some()
    }

    fn shading(&self, hit: &Hit) -> SurfaceGeometry {
        let p = hit.local;
        let item = (hit.tag as usize).min(self.pieces.len() - 1);
        let piece = &self.pieces[item];
        // The solver's (u, v) of the parent patch (a `Hit` from `intersect` always has it).
        let (u, v) = hit.uv.map_or((0.5, 0.5), |uv| (uv.x, uv.y));
        let size = piece.diag + p.abs().max_element();
        SurfaceGeometry {
            p,
            p_err: DVec3::splat(HIT_P_ERR_REL * size),
            normal: self.normal(piece.parent as usize, u, v),
            uv: Some(DVec2::new(u, v)),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Regression (issue 10): shading threw away the solver's `(u, v)` and recomputed it by
    /// Gauss–Newton from the hit point. The `Hit` now carries the solver's parameters and
    /// shading uses exactly them; the hit point is the surface point there.
    #[test]
    fn shading_uses_the_solvers_patch_parameters() {
        // The bilinear saddle z = (2u − 1)(2v − 1) over [−1, 1]².
        let pts = [
            (-1.0, -1.0, 1.0),
            (-1.0, 1.0, -1.0),
            (1.0, -1.0, -1.0),
            (1.0, 1.0, 1.0),
        ]
        .map(|(x, y, z)| DVec3::new(x, y, z));
        let net = ControlNet::new(1, 1, pts.to_vec()).unwrap();
        let mesh = BezierMesh::new(std::slice::from_ref(&net), PatchMethod::Resultant).unwrap();
        let ray = Ray::new(DVec3::new(0.3, -0.4, 5.0), DVec3::new(0.01, 0.02, -1.0));
        let (patch_hit, _) = mesh
            .nearest_hit(&ray, 0.0..f64::INFINITY, &mut PatchStats::default(), false)
            .expect("the ray crosses the saddle");
        let hit = mesh
            .intersect(&ray, 0.0..f64::INFINITY, &mut Workspace::new())
            .expect("the same hit through the Surface trait");
        assert_eq!(
            hit.uv,
            Some(patch_hit.uv),
            "the hit carries the solver's (u, v)"
        );
        let g = mesh.shading(&hit);
        assert_eq!(
            g.uv, hit.uv,
            "shading reports the solver's (u, v), not a recomputed one"
        );
        let on_patch = mesh.patches()[0].eval(patch_hit.uv.x, patch_hit.uv.y);
        assert!(
            (on_patch - g.p).length() < 1e-9,
            "S(u, v) = {on_patch} is the hit point {}",
            g.p
        );
    }
}

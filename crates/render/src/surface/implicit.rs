//! The one intersection path of every implicit surface (Stam §3.2.1, eq. 3.7–3.8):
//! clip the ray to the bounding box, move its origin to the box entry, restrict `F` to the
//! ray, and ask `poly` for the smallest root in range. Normals are `∇F` (Stam eq. 3.24).
//! See `paper-notes/implicit-surfaces.md`.

use std::ops::Range;

use glam::{DVec2, DVec3};
use poly::{PolyRef, RootOptions};

use crate::methods::RootMethods;

use super::{Hit, Surface, SurfaceGeometry, SurfaceKind};
use crate::geometry::{Bounds3, Ray, gamma};
use crate::trivariate::{Eval3, Poly3, RestrictScratch};
use crate::workspace::Workspace;

/// Root tolerance relative to the extent of the search: a nearest-hit query asks `poly` for
/// the root to within `ROOT_X_TOL_REL × (bounding-box diagonal / |d|)` in `t`, i.e. about
/// 2⁻³³ ≈ 1.2·10⁻¹⁰ of the object's size along the ray. That is far below a pixel at any
/// distance, and cheap: refinement converges superlinearly, so halving it costs a fraction of
/// one evaluation. (Absolute in `t`; the bound `poly` guarantees for an isolated simple root.)
pub const ROOT_X_TOL_REL: f64 = 1.0 / (1u64 << 33) as f64;

/// The degree from which a bounded surface, too, is restricted at the centred expansion point
/// of [`expansion_point`] (with the split query of [`smallest_root_split`]) rather than at
/// its bounding-volume entry; unbounded surfaces always are.
///
/// Why 9: restricted at the entry, the rounding of the restriction at a root can reach
/// `3^N` times `F`'s own scale there (entry and root anywhere in the box, `|o'_k| + |d_k s*|`
/// up to three half-widths), i.e. `u·3^N` relative: 10⁻¹² for the sextic Barth surface, but
/// 10⁻⁸ at degree 16 and 10¹⁴ at degree 64, where the stored polynomial no longer holds the
/// surface. Below 9 the entry keeps its speed (no Taylor shift in `poly`, one query) and the
/// golden images of the torus and Barth scenes are unchanged.
pub(crate) const CENTRED_MIN_DEGREE: u32 = 9;

/// Relative error assumed for a hit at a singular point (`∇F` indistinguishable from zero),
/// where the residual bound `|F|/|∇F|` is meaningless: the spawned ray is offset by this
/// fraction of the object's size. A heuristic, used only at singular points (counted in the
/// statistics as `singular_normals`).
pub const SINGULAR_P_ERR_REL: f64 = 1e-9;

/// An implicit surface `F(x, y, z) = 0` as the shared path needs it.
pub trait ImplicitFn: Send + Sync + std::fmt::Debug {
    /// The kind, for statistics.
    fn kind(&self) -> SurfaceKind;

    /// `F` as a trivariate polynomial (evaluated only at accepted hits, for the normal and the
    /// residual error bound).
    fn poly(&self) -> &Poly3;

    /// Writes the coefficients of `t ↦ F(o + t·d)`, low → high, into `out` (cleared first).
    /// Shapes with a closed-form restriction (sphere eq. 2.4, plane, torus) write it directly;
    /// the general case is [`Poly3::restrict_into`].
    fn restrict(&self, o: DVec3, d: DVec3, scratch: &mut RestrictScratch, out: &mut Vec<f64>);

    /// A box holding the surface, `None` if unbounded.
    fn bounds(&self) -> Option<Bounds3>;

    /// `F`, `∇F` and their rounding-error scales at `p` ([`Poly3::eval_grad`]); shapes with a
    /// cheaper factored form (torus) override it, with sums that bound *their* evaluation's
    /// rounding in the same way.
    fn eval_grad(&self, p: DVec3) -> Eval3 {
        self.poly().eval_grad(p)
    }

    /// A sphere `(centre, radius)` holding the surface, intersected before the box when the
    /// shape is rounder than its box (torus): rays passing the box corners are rejected without
    /// building a polynomial, and the root search covers only the part of the ray inside both.
    fn bounding_sphere(&self) -> Option<(DVec3, f64)> {
        None
    }

    /// Surface parameters at `p`, where the shape defines them.
    fn uv(&self, _p: DVec3) -> Option<DVec2> {
        None
    }
}

/// An implicit surface ready for tracing: `F` and its bounds.
#[derive(Debug)]
pub struct Implicit<F> {
    f: F,
    degree: u32,
    /// Diagonal of `bounds` (0 when unbounded).
    diagonal: f64,
    bounds: Option<Bounds3>,
    /// A user bounding sphere `(centre, radius)` (`Bounding volume = SPHERE …`): only the
    /// part of the surface inside it is traced.
    clip_sphere: Option<(DVec3, f64)>,
    /// How the ray polynomial's smallest root is found (set once per render).
    roots: RootMethods,
    /// The partial degrees of `F`, the metric of an unbounded surface's expansion point
    /// ([`expansion_point`]).
    weights: DVec3,
}

impl<F: ImplicitFn> Implicit<F> {
    /// Wraps `f`; `user_bounds` (a scene `Bounding volume`) tightens the
    /// shape's own bounds, or is the only bound of an unbounded shape.
    pub fn new(f: F, user_bounds: Option<Bounds3>) -> Self {
        let degree = f.poly().degree();
        let bounds = match (f.bounds(), user_bounds) {
            (Some(a), Some(b)) => Some(a.intersection(&b)),
            (a, b) => a.or(b),
        };
        let diagonal = bounds.map_or(0.0, |b| b.diagonal());
        let weights = DVec3::from_array(f.poly().partial_degrees().map(f64::from));
        Implicit {
            f,
            weights,
            degree,
            diagonal,
            bounds,
            clip_sphere: None,
            roots: RootMethods::default(),
        }
    }

    /// Finds roots with `roots` instead of the default methods.
    pub fn with_root_methods(mut self, roots: RootMethods) -> Self {
        self.roots = roots;
        self
    }

    /// Clips the surface to the sphere of centre `c` and radius `r` (in the shape's
    /// coordinates), and tightens the bounding box to the sphere's.
    pub fn with_clip_sphere(mut self, c: DVec3, r: f64) -> Self {
        let ball = Bounds3::new(c - DVec3::splat(r), c + DVec3::splat(r));
        let bounds = self.bounds.map_or(ball, |b| b.intersection(&ball));
        self.bounds = Some(bounds);
        self.diagonal = bounds.diagonal();
        self.clip_sphere = Some((c, r));
        self
    }

    /// The wrapped function.
    pub fn function(&self) -> &F {
        &self.f
    }

    /// The root tolerance in `t` for a ray with direction `d` (see [`ROOT_X_TOL_REL`]): relative
    /// to the box diagonal, or for an unbounded surface to the search length (when finite) or
    /// else to the origin's distance from the coordinate origin plus one unit. Always finite.
    fn x_tol(&self, d: DVec3, o: DVec3, range_len: f64) -> f64 {
        let size = match &self.bounds {
            Some(_) => self.diagonal,
            None if range_len.is_finite() => range_len * d.length(),
            None => o.abs().max_element() + 1.0,
        };
        ROOT_X_TOL_REL * size / d.length()
    }
}

/// The smallest root of the polynomial held in `ws.coeffs` in `(lo, hi]`, found by `poly`'s
/// query with `opts` (tolerance and methods) on the borrowed coefficients (an infinite `hi` of
/// an unbounded surface is narrowed by `poly`, with Cauchy's bound); `None` also for a
/// polynomial that vanishes identically along the ray (the ray lies in the surface).
pub(crate) fn smallest_root_in(
    ws: &mut Workspace,
    lo: f64,
    hi: f64,
    opts: &RootOptions,
) -> Option<f64> {
    let query = PolyRef::new(&ws.coeffs).roots(lo, hi, opts);
    query.stats(&mut ws.stats.roots).smallest().ok().flatten()
}

/// The smallest root in `(lo, hi]` of the polynomial in `ws.coeffs` (`lo ≤ 0 < hi`, `hi`
/// possibly infinite), restricted at the expansion point `s = 0`: the query of an unbounded
/// surface of degree 3 or more, and of every surface of degree [`CENTRED_MIN_DEGREE`] or
/// more.
///
/// Two things keep it at `f64` speed where one query over `(lo, hi]` was not (issue 11,
/// `x^32 − 1`: 45 µs a ray, most in double-double, after the expansion point had fixed the
/// restriction itself):
/// - Both ends are cut to `poly`'s root bound `B` ([`PolyRef::root_bound`], Fujiwara's), which
///   `poly` applies only to an infinite end, and then as Cauchy's bound — for `(d_x s)^32 − 1`
///   10¹², where the polynomial overflows, so its end sign could not be certified and the query
///   fell to exact rational isolation; a far finite `lo` (the eye) is kept as it is.
/// - The range is split at the expansion point `s = 0` into `(0, hi]` and, reflected
///   (`u = −s`, odd coefficients negated, exactly), `[0, −lo)`. `poly`'s certified run bounds
///   its rounding by `γ·Σ|c_i|(|a| + w)^i` for a run on `[a, a + w]`; on `[−B, B]` that is
///   `Σ|c_i|(3B)^i`, `3^N` times the size of the polynomial there, so the search stalled near
///   the roots. From 0 outwards it is `Σ|c_i|B^i`, the polynomial's own scale.
///
/// The reflected half wants its *largest* root (the smallest `s`): all its roots are found and
/// the largest kept. A root exactly at `s = 0` is one of the stored polynomial (`c₀ = 0`).
fn smallest_root_split(ws: &mut Workspace, lo: f64, hi: f64, opts: &RootOptions) -> Option<f64> {
    let (lo, hi) = match PolyRef::new(&ws.coeffs).root_bound() {
        Some(b) => (lo.max((-b).next_down()), hi.min(b)),
        None => (lo, hi),
    };
    if lo < 0.0 {
        reflect(&mut ws.coeffs);
        ws.roots.clear();
        let found = PolyRef::new(&ws.coeffs)
            .roots(0.0, -lo, opts)
            .stats(&mut ws.stats.roots)
            .all_into(&mut ws.roots);
        reflect(&mut ws.coeffs);
        // `(lo, …]` is open at `lo`: a root at `u = −lo` exactly is the range start.
        let left = ws
            .roots
            .iter()
            .map(|&u| -u)
            .filter(|&s| s > lo)
            .reduce(f64::min);
        if found.is_ok()
            && let Some(s) = left
        {
            return Some(s);
        }
    }
    if ws.coeffs.first() == Some(&0.0) && lo < 0.0 && 0.0 <= hi {
        return Some(0.0);
    }
    if hi > 0.0 {
        return smallest_root_in(ws, lo.max(0.0), hi, opts);
    }
    None
}

/// `p(x) → p(−x)`: negates the odd coefficients (exact).
fn reflect(coeffs: &mut [f64]) {
    for c in coeffs.iter_mut().skip(1).step_by(2) {
        *c = -*c;
    }
}

/// Relative margin by which [`sphere_segment`] widens the bounding sphere and the interval, far
/// above the few roundings of the computation, so a ray touching the sphere is never clipped.
const SPHERE_CLIP_MARGIN: f64 = 1e-9;

/// The parameter interval where the line of `ray` is inside the sphere `(c, r)`, slightly
/// enlarged ([`SPHERE_CLIP_MARGIN`]), or `None` when the line passes outside it.
fn sphere_segment(ray: &Ray, c: DVec3, r: f64) -> Option<Range<f64>> {
    let a = ray.dir.length_squared();
    let oc = ray.origin - c;
    let r2 = r * r * (1.0 + SPHERE_CLIP_MARGIN);
    // Distance² from c to the line times |d|², computed without cancellation: |oc × d|².
    // Compared before any division: most rays that reach here are rejected by it.
    let d2a = oc.cross(ray.dir).length_squared();
    if d2a > r2 * a {
        return None;
    }
    let inv_a = 1.0 / a;
    let b = oc.dot(ray.dir) * inv_a; // half the linear coefficient, over a
    let half = (r2 * a - d2a).sqrt() * inv_a;
    let pad = SPHERE_CLIP_MARGIN * (b.abs() + half) + f64::MIN_POSITIVE;
    Some((-b - half - pad)..(-b + half + pad))
}

/// How far below the moved origin (`s = 0`, a bounding-volume entry) the root search starts,
/// relative to `|t0| + chord`: well above the few roundings of the slab entry, so a hit exactly
/// on the entry face is kept (a head-on ray at a sphere's pole, the centre pixel of an
/// axis-aligned camera); a clipped surface is admitted at most this far outside its volume.
pub const ENTRY_MARGIN_REL: f64 = 1e-9;

/// The lower end of the root search in `s = t − t0` after the origin moved to `t0`. When `t0`
/// is the range's own start the search is open at `0`, as the range is (a spawned ray must not
/// re-hit the surface it leaves); when `t0` is a bounding-volume entry past the start, the
/// search starts [`ENTRY_MARGIN_REL`] before it (but never before the range), so the entry
/// point itself is searched.
pub(crate) fn search_start(range_start: f64, t0: f64, chord: f64) -> f64 {
    if t0 > range_start {
        (range_start - t0).max(-ENTRY_MARGIN_REL * (t0.abs() + chord))
    } else {
        0.0
    }
}

/// Where an unbounded surface of degree 3 or more (or any of degree [`CENTRED_MIN_DEGREE`] or
/// more) is restricted to `ray`: the point of the ray nearest the
/// coordinate origin in the metric `Σ w_k x_k²` (`w` the partial degrees of `F`), clamped to
/// the search range `[start, end]`; `start` when `F` does not vary along the ray's axes.
///
/// Why: `F = Σ a_ijk x^i y^j z^k` is written about the origin, and the rounding error of its
/// restriction at `o'`, at a root `s*`, scales like `Σ|a_ijk| Π(|o'_k| + |d_k s*|)^e_k`
/// (`Poly3::restrict_into`). Restricted at the eye, that is `|eye_x|^N` against a surface of
/// size 1: for `x^32 − 1` seen from 12 units, 10³⁰ times the values near the roots, so the
/// stored polynomial had lost the surface (hits off by a third of the distance, rays missed)
/// and its isolation fell to exact arithmetic (issue 11). The weights put the point where
/// the axes of high degree are small: for `x^32 − 1` on the plane `x = 0`, where the
/// restriction `(d_x s)^32 − 1` is exact; with equal weights (Barth, a power of a sphere) it is
/// the Euclidean nearest point, where `|o'| ≤ |p*|` and `|p* − o'| ≤ |p*|` for every root point
/// `p*` (`paper-notes/implicit-surfaces.md` §2).
fn expansion_point(ray: &Ray, w: DVec3, start: f64, end: f64) -> f64 {
    let wd = w * ray.dir;
    let nearest = -wd.dot(ray.origin) / wd.dot(ray.dir);
    if nearest.is_nan() {
        return start;
    }
    nearest.max(start).min(end)
}

/// Clips `t_range` to `bounds` (counting a rejection for `kind`), or passes it through for an
/// unbounded surface.
pub(crate) fn clip(
    bounds: Option<&Bounds3>,
    ray: &Ray,
    t_range: Range<f64>,
    ws: &mut Workspace,
    kind: SurfaceKind,
) -> Option<Range<f64>> {
    match bounds {
        None => Some(t_range),
        Some(b) => {
            let r = b.intersect_ray(ray, t_range);
            if r.is_none() {
                ws.stats.per_kind[kind.index()].bbox_rejects += 1;
            }
            r
        }
    }
}

impl<F: ImplicitFn> Implicit<F> {
    /// The shared query: restrict at the (moved) origin and solve. Returns `(t, point)`.
    pub(crate) fn nearest(
        &self,
        ray: &Ray,
        t_range: Range<f64>,
        ws: &mut Workspace,
        any_root: bool,
    ) -> Option<(f64, DVec3)> {
        // The shape's own bounding sphere (torus), then the user's clipping sphere.
        let mut t_range = t_range;
        for (c, r) in [self.f.bounding_sphere(), self.clip_sphere]
            .into_iter()
            .flatten()
        {
            t_range = match sphere_segment(ray, c, r) {
                Some(s) if s.start < t_range.end && s.end > t_range.start => {
                    t_range.start.max(s.start)..t_range.end.min(s.end)
                }
                _ => {
                    ws.stats.per_kind[self.f.kind().index()].bbox_rejects += 1;
                    return None;
                }
            };
        }
        let range_start = t_range.start;
        let seg = clip(self.bounds.as_ref(), ray, t_range, ws, self.f.kind())?;
        // Move the origin to where the ray enters the box (or to the range start): the
        // restricted polynomial is then built from small numbers near the surface, which is
        // what keeps hits exact far from the camera (paper-notes/implicit-surfaces.md §2).
        let entry = seg.start;
        let start = entry + search_start(range_start, entry, seg.end - entry);
        // Degrees 1–2 keep the range start: their closed forms lose at most `|o|²/size²`
        // there, and their range stays open exactly at the start.
        let centred =
            self.degree >= 3 && (self.bounds.is_none() || self.degree >= CENTRED_MIN_DEGREE);
        let t0 = if centred {
            expansion_point(ray, self.weights, start, seg.end)
        } else {
            // The search then starts at s = 0 of the restriction (the isolator's first node
            // needs no Taylor shift there).
            start
        };
        let o = ray.at(t0);
        self.f
            .restrict(o, ray.dir, &mut ws.restrict, &mut ws.coeffs);
        let hi = seg.end - t0;
        let lo = start - t0;
        let x_tol = if any_root && hi.is_finite() {
            // Any root proves occlusion: any point of the range will do as its value.
            hi - lo
        } else {
            self.x_tol(ray.dir, o, hi - lo)
        };
        let opts = self.roots.options(x_tol);
        let s = if centred {
            smallest_root_split(ws, lo, hi, &opts)?
        } else {
            smallest_root_in(ws, lo, hi, &opts)?
        };
        Some((t0 + s, o + ray.dir * s))
    }
}

impl<F: ImplicitFn> Surface for Implicit<F> {
    fn kind(&self) -> SurfaceKind {
        self.f.kind()
    }

    fn bounds(&self) -> Option<Bounds3> {
        self.bounds
    }

    fn intersect(&self, ray: &Ray, t_range: Range<f64>, ws: &mut Workspace) -> Option<Hit> {
        let (t, p) = self.nearest(ray, t_range, ws, false)?;
        Some(Hit {
            t,
            local: p,
            uv: None,
            tag: 0,
        })
    }

    fn occluded(&self, ray: &Ray, t_range: Range<f64>, ws: &mut Workspace) -> bool {
        self.nearest(ray, t_range, ws, true).is_some()
    }

    fn shading(&self, hit: &Hit) -> SurfaceGeometry {
        let p = hit.local;
        let (normal, p_err) =
            gradient_normal(self.f.eval_grad(p), self.degree).unwrap_or_else(|| {
                let size = self
                    .bounds
                    .map_or(0.0, |b| b.diagonal())
                    .max(p.abs().max_element());
                (None, DVec3::splat(SINGULAR_P_ERR_REL * size))
            });
        SurfaceGeometry {
            p,
            p_err,
            normal,
            uv: self.f.uv(p),
        }
    }
}

/// The unit normal `∇F/|∇F|` at `p` and an error box for `p`, or `None` at a singular point
/// (`∇F` not distinguishable from zero).
///
/// # Accuracy
/// The error box is the first-order distance from `p` to the surface,
/// `(|F(p)| + e_F) / |∇F(p)|` with `e_F = γ(d + 3)·Σ|a_ijk||x|^i|y|^j|z|^k` bounding the
/// evaluation error of `F` of total degree `d`. It measures the residual actually left at the
/// stored point, so it covers the root tolerance, the rounding of the restricted coefficients
/// and of `p = o + s·d` together. It is a first-order bound: valid where `F` is close to
/// linear over that distance, which holds away from singular points.
pub(crate) fn gradient_normal(e: Eval3, degree: u32) -> Option<(Option<DVec3>, DVec3)> {
    let g = e.grad;
    let g_err = e.grad_abs * gamma(degree as usize + 2);
    let glen = g.length();
    // `glen <= g_err` also refuses NaN through `!is_finite`.
    if glen <= g_err.length() || !glen.is_finite() {
        return None;
    }
    let f_err = gamma(degree as usize + 3) * e.f_abs;
    let dist = (e.f.abs() + f_err) / glen;
    Some((Some(g / glen), DVec3::splat(dist)))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::surface::{Algebraic, Plane, Sphere};
    use crate::trivariate::Poly3;

    /// `n × n` rays from `eye` through a square of half-width `half` about the origin, in
    /// the plane through the origin facing the eye.
    fn camera_rays(eye: DVec3, half: f64, n: usize) -> Vec<Ray> {
        let w = (-eye).normalize();
        let u = w.cross(DVec3::Z).normalize();
        let v = u.cross(w);
        let at = |k: usize| ((k as f64 + 0.5) / n as f64 * 2.0 - 1.0) * half;
        (0..n * n)
            .map(|k| Ray::new(eye, u * at(k % n) + v * at(k / n) - eye))
            .collect()
    }

    /// Issue 11: `x^32 − 1 = 0` (the planes `x = ±1`, no bounding volume) was restricted at
    /// the eye, where its rounding is 10³⁰ times the surface's values: hits came out at the
    /// wrong depth or not at all, and every query ended in exact rational isolation. Restricted
    /// at the plane `x = 0` of the ray, each hit is the plane's to 1e-9 relative, in `f64`.
    #[test]
    fn r11_unbounded_x32_minus_1_hits_its_planes_in_f64() {
        let f = &Poly3::x().pow(32) - &Poly3::constant(1.0);
        let surface = Implicit::new(Algebraic::new(f), None);
        let eye = DVec3::new(5.0, -9.0, 6.0);
        let mut ws = Workspace::new();
        for ray in camera_rays(eye, 3.2, 12) {
            let hit = surface.intersect(&ray, 0.0..f64::INFINITY, &mut ws);
            // Coming from x = 5, the first plane crossed is x = 1 (when moving towards it).
            let want = (ray.dir.x < 0.0).then(|| (1.0 - eye.x) / ray.dir.x);
            match (hit, want) {
                (Some(h), Some(t)) => {
                    assert!((h.t - t).abs() <= 1e-9 * t, "ray {ray:?}: t {} vs {t}", h.t)
                }
                (h, t) => assert_eq!(h.map(|h| h.t), t, "hit/miss of {ray:?}"),
            }
        }
        let roots = &ws.stats.roots;
        assert_eq!(
            (roots.exact_fallbacks, roots.adaptive_pieces),
            (0, 0),
            "decided in f64: {roots:?}"
        );
    }

    /// Issue 11: a degree-64 surface, `g^16 − 2^-16` with the well-conditioned quartic
    /// `g = x⁴ + y⁴ + z⁴` (`scenes/quartic-power64.scene`), has the real set of `g = 1/2`. Traced
    /// in a box, it must hit and miss where the quartic does, at the same depth; restricted at
    /// the box entry, its restriction's rounding was 10¹⁴ times its values.
    #[test]
    fn r11_degree_64_power_matches_its_quartic() {
        let g = &(&Poly3::x().pow(4) + &Poly3::y().pow(4)) + &Poly3::z().pow(4);
        let half = Poly3::constant(0.5);
        let power = &g.pow(16) - &half.pow(16);
        assert_eq!(power.degree(), 64, "degree");
        let bounds = Some(Bounds3::new(DVec3::splat(-0.9), DVec3::splat(0.9)));
        let high = Implicit::new(Algebraic::new(power), bounds);
        let low = Implicit::new(Algebraic::new(&g - &half), bounds);
        let eye = DVec3::new(5.0, -9.0, 6.0);
        let mut ws = Workspace::new();
        let mut hits = 0;
        for ray in camera_rays(eye, 1.0, 12) {
            let a = high.intersect(&ray, 0.0..f64::INFINITY, &mut ws);
            let b = low.intersect(&ray, 0.0..f64::INFINITY, &mut ws);
            match (a, b) {
                (Some(a), Some(b)) => {
                    hits += 1;
                    assert!(
                        (a.t - b.t).abs() <= 1e-9 * b.t,
                        "{ray:?}: {} vs {}",
                        a.t,
                        b.t
                    );
                }
                (a, b) => assert_eq!(a.map(|h| h.t), b.map(|h| h.t), "hit/miss of {ray:?}"),
            }
        }
        assert!(hits > 30, "the rays cover the surface: {hits} hits of 144");
        assert_eq!(ws.stats.roots.exact_fallbacks, 0, "{:?}", ws.stats.roots);
    }

    #[test]
    fn unbounded_plane_is_hit_over_an_infinite_range() {
        let plane = Implicit::new(Plane::new(DVec3::new(0.0, 0.0, -1.5), DVec3::Z), None);
        let mut ws = Workspace::new();
        let ray = Ray::new(DVec3::new(0.3, 0.2, 4.0), DVec3::new(0.1, 0.0, -1.0));
        let hit = plane
            .intersect(&ray, 0.0..f64::INFINITY, &mut ws)
            .expect("hits the floor");
        assert!((hit.t - 5.5).abs() < 1e-12, "t = {}", hit.t);
        assert!(
            plane.occluded(&ray, 0.0..f64::INFINITY, &mut ws),
            "blocks over (0, ∞)"
        );
        assert!(!plane.occluded(&ray, 0.0..5.0, &mut ws), "not before t = 5");
        let up = Ray::new(ray.origin, DVec3::Z);
        assert_eq!(
            plane.intersect(&up, 0.0..f64::INFINITY, &mut ws),
            None,
            "moving away"
        );
        assert_eq!(ws.stats.roots.rejected, 0, "no query refused");
    }

    #[test]
    fn bounding_sphere_segment_contains_the_sphere_chord() {
        let ray = Ray::new(DVec3::new(-10.0, 0.5, 0.0), DVec3::new(2.0, 0.0, 0.0));
        let s = sphere_segment(&ray, DVec3::ZERO, 1.0).expect("crosses");
        let half = (1.0f64 - 0.25).sqrt();
        assert!(
            s.start <= (10.0 - half) / 2.0 && s.end >= (10.0 + half) / 2.0,
            "{s:?}"
        );
        assert!(s.end - s.start < half + 1e-6, "and is tight: {s:?}");
        let miss = Ray::new(DVec3::new(-10.0, 1.01, 0.0), DVec3::X);
        assert_eq!(
            sphere_segment(&miss, DVec3::ZERO, 1.0),
            None,
            "passes outside"
        );
        let sphere = Implicit::new(Sphere::new(DVec3::ZERO, 1.0), None);
        assert_eq!(
            sphere.bounds().map(|b| b.max),
            Some(DVec3::ONE),
            "sphere box"
        );
    }
}

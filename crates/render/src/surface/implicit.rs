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
        Implicit {
            f,
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
        let lo = search_start(range_start, entry, seg.end - entry);
        // The search then starts at s = 0 of the restriction (the isolator's first node needs
        // no Taylor shift there).
        let t0 = entry + lo;
        let o = ray.at(t0);
        self.f
            .restrict(o, ray.dir, &mut ws.restrict, &mut ws.coeffs);
        let hi = seg.end - t0;
        let lo = 0.0;
        let x_tol = if any_root && hi.is_finite() {
            // Any root proves occlusion: any point of the range will do as its value.
            hi - lo
        } else {
            self.x_tol(ray.dir, o, hi)
        };
        let s = smallest_root_in(ws, lo, hi, &self.roots.options(x_tol))?;
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
    use crate::surface::{Plane, Sphere};

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

//! The one intersection path of every implicit surface (Stam §3.2.1, eq. 3.7–3.8):
//! clip the ray to the bounding box, move its origin to the box entry, restrict `F` to the
//! ray, and ask `poly` for the smallest root in range. Normals are `∇F` (Stam eq. 3.24).
//! See `paper-notes/implicit-surfaces.md`.

use std::ops::Range;

use glam::{DVec2, DVec3};
use poly::{Dd, IsolationMethod, PolyRef, QPoly, Rat, RootError, RootOptions, UNIT_ROUNDOFF};

use crate::methods::RootMethods;

use super::{Hit, Surface, SurfaceGeometry, SurfaceKind};
use crate::geometry::{Bounds3, Ray, gamma};
use crate::trivariate::{Eval3, Poly3, RestrictScratch, exact_point};
use crate::workspace::Workspace;

/// Root tolerance relative to the extent of the search: a nearest-hit query asks `poly` for
/// the root to within `ROOT_X_TOL_REL × (bounding-box diagonal / |d|)` in `t`, i.e. about
/// 2⁻³³ ≈ 1.2·10⁻¹⁰ of the object's size along the ray. That is far below a pixel at any
/// distance, and cheap: refinement converges superlinearly, so halving it costs a fraction of
/// one evaluation. (Absolute in `t`; the bound `poly` guarantees for an isolated simple root.)
pub const ROOT_X_TOL_REL: f64 = 1.0 / (1u64 << 33) as f64;

/// Root tolerance of the last certified try at a ray above [`EXACT_RESTRICTION_MAX_DEGREE`]
/// that neither the `f64` nor the double-double restriction certifies to [`ROOT_X_TOL_REL`]:
/// the double-double restriction's query again, to `REDUCED_ROOT_X_TOL_REL × (bounding-box
/// diagonal / |d|)` in `t` (absolute in `t`, relative to the object's size, like
/// `ROOT_X_TOL_REL`). 2⁻²³ ≈ 1.2·10⁻⁷ of the object's size is still four orders of magnitude
/// below a pixel whenever the object spans fewer than 10⁴ pixels; it is a certified answer,
/// where the alternative was one for the rounded polynomial (counted as undecided), and
/// `render --stats` counts it ("decided at reduced precision"). On the degree-20 sheets seen
/// from 9 430 units it decides 310 of 311 such rays at 48² (`docs/speed.md`, "High-degree
/// surfaces: the slack's evaluation and the undecided rays"): most are limited only in the
/// refinement of a certified bracket, which a tolerance 2¹⁰ times wider ends; the one left
/// is limited in the existence of a root, which no tolerance settles.
pub const REDUCED_ROOT_X_TOL_REL: f64 = 1.0 / (1u64 << 23) as f64;

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

    /// The total degree of `F` ([`Poly3::degree`]); a shape that knows it without building
    /// [`poly`](Self::poly) says so (the sphere builds it only when asked).
    fn degree(&self) -> u32 {
        self.poly().degree()
    }

    /// Writes the coefficients of `t ↦ F(o + t·d)`, low → high, into `out` (cleared first).
    /// Shapes with a closed-form restriction (sphere eq. 2.4, plane, torus) write it directly;
    /// the general case is [`Poly3::restrict_into`].
    fn restrict(&self, o: DVec3, d: DVec3, scratch: &mut RestrictScratch, out: &mut Vec<f64>);

    /// A box holding the surface, `None` if unbounded.
    fn bounds(&self) -> Option<Bounds3>;

    /// `K`, the most roundings on any path of [`ImplicitFn::restrict`] from the surface's
    /// data and `o`, `d` to one restricted coefficient (Higham's standard model): the default
    /// is that of [`Poly3::restrict_into`] ([`Poly3::restriction_rounding_steps`]); a shape
    /// with its own closed form overrides it with the count of that program.
    fn restriction_rounding_steps(&self) -> u32 {
        self.poly().restriction_rounding_steps()
    }

    /// An upper bound on `G(y)` for `y ≥ 0` componentwise, where `G(|o| + t|d|)` is
    /// [`ImplicitFn::restrict`] run on absolute values, summed over powers of `t` — so that
    /// `Σₘ |ĉₘ − cₘ|·tᵐ ≤ γ(K)·G(|o| + t|d|)` — and `G` is at least `F` with absolute-value
    /// coefficients (for the rounding of the restriction point). The default, for
    /// [`Poly3::restrict_into`], is `F_abs` itself ([`Poly3::eval_abs_upper`]).
    fn restriction_abs(&self, y: DVec3) -> f64 {
        self.poly().eval_abs_upper(y)
    }

    /// `C` such that the underflowing roundings of [`ImplicitFn::restrict`] (and of
    /// [`ImplicitFn::restriction_abs`]) add at most `C·(1 + R + Y)^N` to the slack at radius
    /// `R`, `Y` the largest component of `|o| + R|d|`: the default is that of
    /// [`Poly3::restrict_into`] ([`Poly3::restriction_underflow_weight`]); a shape with its own
    /// closed form overrides it with a bound for that program.
    fn restriction_underflow_weight(&self) -> f64 {
        self.poly().restriction_underflow_weight()
    }

    /// `t ↦ F(o + t·d)` in double-double arithmetic from a double-double point `o`, by the
    /// program of [`Poly3::restrict_into`] on [`ImplicitFn::poly`], whose coefficients must be
    /// the surface as written; `false` when that is not the case (a shape whose `Poly3` is
    /// itself rounded, such as the torus's expansion), and the ray goes to the exact tier.
    fn restrict_dd(
        &self,
        o: [Dd; 3],
        d: DVec3,
        scratch: &mut RestrictScratch<Dd>,
        out: &mut Vec<Dd>,
    ) -> bool {
        self.poly().restrict_dd_into(o, d, scratch, out);
        true
    }

    /// `t ↦ F(o + t·d)` in exact rational arithmetic for the surface as written (its `f64`
    /// data taken exactly); the default expands [`ImplicitFn::poly`]
    /// ([`Poly3::restrict_exact`]).
    fn restrict_exact(&self, o: &[Rat; 3], d: &[Rat; 3]) -> QPoly {
        self.poly().restrict_exact(o, d)
    }

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

    /// Whether `F < 0` exactly on the inside of a convex body whose boundary is `F = 0`, so
    /// that `∇F` points out of it (see [`Surface::convex`]); a bounding volume keeps a part of
    /// that boundary, which is still convex in this sense.
    fn convex(&self) -> bool {
        false
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
    /// `K` of the shape's restriction ([`ImplicitFn::restriction_rounding_steps`]).
    rounding_steps: u32,
    /// The relative factor of the restriction's slack ([`slack_rel`]).
    slack_rel: f64,
    /// The restriction's underflow weight ([`ImplicitFn::restriction_underflow_weight`]).
    underflow_weight: f64,
    /// The highest degree in `t` of a restriction along a direction whose non-zero
    /// components are flagged by the bits of the index (x: 1, y: 2, z: 4)
    /// ([`Poly3::restriction_degree_bounds`]; [`Implicit::dropped_degree`]).
    ray_degree: [u32; 8],
    /// The relative factor of the double-double tier's slack ([`dd_slack_rel`]).
    dd_rel: f64,
    /// The double-double tier's underflow weight: four times
    /// [`Poly3::restriction_underflow_weight`] (a double-double operation has up to four
    /// underflowing roundings).
    dd_underflow_weight: f64,
}

impl<F: ImplicitFn> Implicit<F> {
    /// Wraps `f`; `user_bounds` (a scene `Bounding volume`) tightens the
    /// shape's own bounds, or is the only bound of an unbounded shape.
    pub fn new(f: F, user_bounds: Option<Bounds3>) -> Self {
        let degree = f.degree();
        let bounds = match (f.bounds(), user_bounds) {
            (Some(a), Some(b)) => Some(a.intersection(&b)),
            (a, b) => a.or(b),
        };
        let diagonal = bounds.map_or(0.0, |b| b.diagonal());
        let mut implicit = Implicit {
            weights: DVec3::ZERO,
            rounding_steps: 0,
            slack_rel: 0.0,
            underflow_weight: 0.0,
            ray_degree: [0; 8],
            dd_rel: 0.0,
            dd_underflow_weight: 0.0,
            f,
            degree,
            diagonal,
            bounds,
            clip_sphere: None,
            roots: RootMethods::default(),
        };
        if degree < 3 {
            // Degrees 1–2 keep their closed forms: never certified against the restriction
            // ([`Implicit::certifies`]) nor restricted at a centred point, so the data of both
            // stays zero. Computing it was ≈ 1.2 K instructions a sphere, a third of the
            // 66 430-sphere scene's surface set-up (`docs/speed.md`, eleventh session).
            return implicit;
        }
        let (f, poly) = (&implicit.f, implicit.f.poly());
        let rounding_steps = f.restriction_rounding_steps();
        let weights = DVec3::from_array(poly.partial_degrees().map(f64::from));
        let slack = slack_rel(rounding_steps, degree);
        let underflow_weight = f.restriction_underflow_weight();
        let dd_rel = dd_slack_rel(poly.restriction_rounding_steps(), degree);
        let dd_underflow_weight = 4.0 * poly.restriction_underflow_weight();
        let ray_degree = poly.restriction_degree_bounds();
        implicit.weights = weights;
        implicit.rounding_steps = rounding_steps;
        implicit.slack_rel = slack;
        implicit.underflow_weight = underflow_weight;
        implicit.dd_rel = dd_rel;
        implicit.dd_underflow_weight = dd_underflow_weight;
        implicit.ray_degree = ray_degree;
        implicit
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

    /// The box the surface is traced in (the shape's own, tightened by the user's), `None`
    /// when unbounded; [`Surface::bounds`] without the copy.
    pub(crate) fn bounds_ref(&self) -> Option<&Bounds3> {
        self.bounds.as_ref()
    }

    /// True when the rounded restriction in `coeffs` has a lower degree than the exact one
    /// may have along `d` (its top coefficients rounded, underflowed or cancelled to zero).
    /// The value slack then certifies nothing: `poly` reads a Bernstein coefficient of the
    /// difference as a blossom of the *stored* degree (`paper-notes/implicit-surfaces.md` §6),
    /// which a difference of higher degree does not have. Exact zeros along an axis with
    /// `d_k = 0` are not a drop: no power of `t` comes from that axis.
    fn dropped_degree(&self, coeffs: &[f64], d: DVec3) -> bool {
        let bits =
            usize::from(d.x != 0.0) | usize::from(d.y != 0.0) << 1 | usize::from(d.z != 0.0) << 2;
        let stored = coeffs.iter().rposition(|&c| c != 0.0).unwrap_or(0);
        (stored as u32) < self.ray_degree[bits]
    }

    /// Whether rays are certified against the surface as written (§6): degrees 1–2 keep their
    /// closed forms, whose restriction loses a few ulps (§2); the heuristic methods certify
    /// nothing, and the exact one restricts exactly.
    fn certifies(&self) -> bool {
        self.degree >= 3 && self.roots.isolation == IsolationMethod::Bernstein
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
    certified_smallest(ws, lo, hi, opts, None).ok().flatten()
}

/// A bound on how far the true ray polynomial lies from the one in `ws.coeffs`:
/// `slack(R) ≥ Σₘ |Δcₘ|·Rᵐ` ([`poly::RootQuery::value_slack`]; [`restriction_slack`]).
type SlackFn<'a> = &'a dyn Fn(f64) -> f64;

/// [`smallest_root_in`] certified for every polynomial within `slack` of the stored one;
/// errors are `poly`'s, [`RootError::SlackLimited`] among them.
fn certified_smallest(
    ws: &mut Workspace,
    lo: f64,
    hi: f64,
    opts: &RootOptions,
    slack: Option<SlackFn<'_>>,
) -> Result<Option<f64>, RootError> {
    let query = PolyRef::new(&ws.coeffs).roots(lo, hi, opts);
    let query = match slack {
        Some(f) => query.value_slack(f),
        None => query,
    };
    query.stats(&mut ws.stats.roots).smallest()
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
///   fell to exact rational isolation; a far finite `lo` (the eye) is kept as it is. With a
///   value slack the caller has already cut the range to a bound valid for the true
///   polynomial ([`PolyRef::root_radius_within`]), and `B` (the stored polynomial's) is not used.
/// - The range is split at the expansion point `s = 0` into `(0, hi]` and, reflected
///   (`u = −s`, odd coefficients negated, exactly), `[0, −lo)`. `poly`'s certified run bounds
///   its rounding by `γ·Σ|c_i|(|a| + w)^i` for a run on `[a, a + w]`; on `[−B, B]` that is
///   `Σ|c_i|(3B)^i`, `3^N` times the size of the polynomial there, so the search stalled near
///   the roots. From 0 outwards it is `Σ|c_i|B^i`, the polynomial's own scale. (The slack,
///   `Σ|Δcₘ|Rᵐ`, is unchanged by the reflection.)
///
/// The reflected half wants its *largest* root (the smallest `s`): all its roots are found and
/// the largest kept. A root exactly at `s = 0` is one of the stored polynomial (`c₀ = 0`).
fn smallest_root_split(
    ws: &mut Workspace,
    lo: f64,
    hi: f64,
    opts: &RootOptions,
    slack: Option<SlackFn<'_>>,
) -> Result<Option<f64>, RootError> {
    // (The bound is Fujiwara's, `n` powers: asked only when it is used.)
    let bound = || PolyRef::new(&ws.coeffs).root_bound();
    let (lo, hi) = match slack.is_none().then(bound).flatten() {
        Some(b) => (lo.max((-b).next_down()), hi.min(b)),
        None => (lo, hi),
    };
    if lo < 0.0 {
        reflect(&mut ws.coeffs);
        ws.roots.clear();
        let query = PolyRef::new(&ws.coeffs).roots(0.0, -lo, opts);
        let query = match slack {
            Some(f) => query.value_slack(f),
            None => query,
        };
        let found = query.stats(&mut ws.stats.roots).all_into(&mut ws.roots);
        reflect(&mut ws.coeffs);
        if let Err(e @ RootError::SlackLimited { .. }) = found {
            return Err(e);
        }
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
            return Ok(Some(s));
        }
    }
    if slack.is_none() && ws.coeffs.first() == Some(&0.0) && lo < 0.0 && 0.0 <= hi {
        return Ok(Some(0.0));
    }
    if hi > 0.0 {
        return certified_smallest(ws, lo.max(0.0), hi, opts, slack);
    }
    Ok(None)
}

/// `slack_rel` of [`restriction_slack`] for a restriction program with `steps` roundings
/// (`K`) of a surface of total degree `degree`: `γ(K) + N·η` with `η = u(1 + 4ε)`, both
/// rounded up (`paper-notes/implicit-surfaces.md` §6).
fn slack_rel(steps: u32, degree: u32) -> f64 {
    let eta = UNIT_ROUNDOFF * (1.0 + 4.0 * f64::EPSILON);
    (gamma(steps as usize) + f64::from(degree) * eta) * (1.0 + 2.0 * f64::EPSILON)
}

/// The relative factor of the double-double tier's slack: `γ_dd(K) + N·u_dd` for
/// [`Poly3::restrict_dd_into`]'s `K` roundings of [`poly::DD_UNIT`] each and the restriction
/// point's one (`o = t0·dir + origin`: an exact product and one double-double addition), as
/// [`slack_rel`] for `f64`; rounded up.
fn dd_slack_rel(steps: u32, degree: u32) -> f64 {
    let ku = f64::from(steps) * poly::DD_UNIT;
    (ku / (1.0 - ku) + f64::from(degree) * poly::DD_UNIT) * (1.0 + 4.0 * f64::EPSILON)
}

/// The bound on the rounding of a restriction at `o` (`origin + t0·dir` rounded once per
/// axis, so within `o_err = u·|o|` of the exact point) as `poly` asks for it:
/// `slack(R) ≥ Σₘ |c_true,m − ĉₘ|·Rᵐ`, where `c_true` is the exact restriction of the surface
/// as written along the exact ray.
///
/// Two parts, both read off one evaluation of `G` ([`ImplicitFn::restriction_abs`]) at
/// `Y = |o| + o_err + R|d|` (`paper-notes/implicit-surfaces.md` §6):
/// - the restriction's own rounding, `γ(K)·G(|o| + R|d|) ≤ γ(K)·G(Y)` (Higham's standard
///   model, `K` = [`ImplicitFn::restriction_rounding_steps`]);
/// - the rounding of the restriction point: the exact polynomials at `o + e` and at `o`,
///   `|e| ≤ o_err`, differ coefficientwise by at most those of
///   `F_abs(|o| + o_err + t|d|) − F_abs(|o| + t|d|)`, which at `t = R` is at most
///   `(1 − (1 − η)^N)·F_abs(Y) ≤ N·η·G(Y)` with `η = maxₖ o_errₖ / Yₖ ≤ u` (each monomial of
///   degree `≤ N` loses at least the factor `(1 − η)^N` when `Y` shrinks by `o_err`).
///
/// So `slack(R) = slack_rel·G(Y)` ([`slack_rel`]); `o_abs` is `|o|·(1 + ε) ≥ |o| + o_err`, and
/// the factors `(1 + 2ε)`, `(1 + 4ε)` cover the roundings of `Y` and of the product.
///
/// Both parts assume no rounding underflows. Those that do err by up to `η` absolutely, which
/// the standard model does not bound (a direction component near `1e-27` makes `d_x¹²` of a
/// degree-12 surface subnormal or zero); the absolute term `C·(1 + R + Y_max)^N`
/// ([`ImplicitFn::restriction_underflow_weight`]) covers them, far below the relative part
/// unless the polynomial's own values are near the underflow threshold.
fn restriction_slack(g: impl Fn(DVec3) -> f64, s: &RestrictionSlack, r: f64) -> f64 {
    let y = (s.o_abs + s.d_abs * r) * (1.0 + 2.0 * f64::EPSILON);
    (s.rel * g(y) + s.underflow(r, y)) * (1.0 + 4.0 * f64::EPSILON)
}

impl RestrictionSlack {
    /// The underflow term `C·(1 + R + Y_max)^N` at radius `r`, `y = |o| + r|d|` rounded up.
    #[inline]
    fn underflow(&self, r: f64, y: DVec3) -> f64 {
        // Repeated squaring written out: `powi` is a library call, and this runs twice a query.
        let (mut under, mut base, mut e) = (
            self.underflow_weight,
            1.0 + r + y.max_element(),
            self.degree,
        );
        while e > 0 {
            if e & 1 == 1 {
                under *= base;
            }
            base *= base;
            e >>= 1;
        }
        under
    }
}

/// The per-ray data of [`restriction_slack`].
struct RestrictionSlack {
    /// [`slack_rel`] of the surface.
    rel: f64,
    /// [`ImplicitFn::restriction_underflow_weight`] of the surface.
    underflow_weight: f64,
    /// The surface's total degree `N`.
    degree: u32,
    /// `|o|·(1 + ε)`, at least `|o|` plus the rounding of the restriction point.
    o_abs: DVec3,
    /// `|d|`.
    d_abs: DVec3,
}

/// Degree up to which a ray that neither the rounded restriction nor the double-double one
/// ([`Implicit`]'s first tier, at any degree) can certify is restricted in exact arithmetic
/// (and, if need be, isolated exactly). The exact restriction's coefficients
/// have about `53·N` bits and its cost grows like `terms·N²` big-integer products: measured
/// in release, tens of µs a Barth (degree 6) ray, but 0.17 s a ray of the degree-64
/// `scenes/quartic-power64.scene` (153 terms), which made a 32 × 32 render take 46 s instead
/// of 0.1 s; and about 0.9 ms a ray plus exact Sturm on a tenth of them for the degree-16
/// `scenes/torus-sheets16.scene` (165 terms), where most hit rays need it because the
/// renderer's depth tolerance is finer than the rounded restriction can certify: 9 s for
/// 100 × 100 pixels, minutes at 840². 12 keeps the degree-12 powers of the tests and every
/// classic scene (Barth, degree 6: 409 rays of 40 318 at 200², now all decided by the
/// double-double tier). Above this degree such a ray gets a last try at
/// [`REDUCED_ROOT_X_TOL_REL`] instead, and one that even that leaves is counted as undecided
/// (`TraceStats::surface_certification`) and answered for the rounded restriction.
pub const EXACT_RESTRICTION_MAX_DEGREE: u32 = 12;

/// What [`Implicit::dd_tier`] made of a slack-limited ray.
enum DdTier {
    /// Certified: the smallest root in the range, or none.
    Decided(Option<f64>),
    /// Not decided; `kept` when `ws.coeffs` holds the double-double restriction rounded to
    /// `f64` (the shape has one, and it was computed), for an uncertified answer.
    Undecided { kept: bool },
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
/// enlarged ([`SPHERE_CLIP_MARGIN`]), or `None` when the line certainly passes outside it:
/// the test and the interval allow for the rounding of the distance computed (below), so a
/// ray that touches the sphere is neither rejected nor clipped short however far its origin
/// is from the sphere.
#[inline(always)]
fn sphere_segment(ray: &Ray, c: DVec3, r: f64) -> Option<Range<f64>> {
    let a = ray.dir.length_squared();
    let oc = ray.origin - c;
    let r2a = r * r * (1.0 + SPHERE_CLIP_MARGIN) * a;
    // Distance² from c to the line times |d|², computed without cancellation: |oc × d|².
    let d2a = oc.cross(ray.dir).length_squared();
    // Its rounding: each component of `oc × d` (with `oc`'s own rounding) is within
    // 3ε·|oc|·|d| of the exact one, so the sum of squares is within 2·√3·3ε·√d2a·|oc||d| +
    // 27ε²·|oc|²|d|² of |oc × d|², and `r2a` within 4ε of its value (`SPHERE_CLIP_MARGIN`
    // dwarfs that). The margin alone covers the first term while |oc|/r stays below ~10⁵;
    // the bound keeps far rays right beyond that.
    let l2 = oc.length_squared() * a;
    let (e1, e2) = (11.0 * f64::EPSILON, 32.0 * f64::EPSILON * f64::EPSILON * l2);
    // Compared before any square root or division: most rays that reach here are rejected
    // by it (squared: `excess > e1·√(d2a·l2)`).
    let excess = d2a - r2a - e2 - 4.0 * f64::EPSILON * r2a;
    if excess > 0.0 && excess * excess > e1 * e1 * d2a * l2 {
        return None;
    }
    if !l2.is_finite() {
        // Overflow (`d2a ≤ l2`): nothing is decided here.
        return Some(f64::NEG_INFINITY..f64::INFINITY);
    }
    // √(d2a·l2) ≤ l2, as |oc × d| ≤ |oc|·|d|: no second square root on the way to the chord
    // (looser only when the origin is far, where it widens the chord by a sliver of `r`).
    let err = e1 * l2 + e2 + 4.0 * f64::EPSILON * r2a;
    let inv_a = 1.0 / a;
    let b = oc.dot(ray.dir) * inv_a; // half the linear coefficient, over a
    let half = (r2a - d2a + err).max(0.0).sqrt() * inv_a;
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
        for ball in [self.f.bounding_sphere(), self.clip_sphere] {
            let Some((c, r)) = ball else { continue };
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
        // `origin + t0·dir` with one rounding per axis (fused multiply-add), so the restriction
        // point is within `u·|o|` of the exact one (the slack's origin term, §6).
        let o = DVec3::new(
            ray.dir.x.mul_add(t0, ray.origin.x),
            ray.dir.y.mul_add(t0, ray.origin.y),
            ray.dir.z.mul_add(t0, ray.origin.z),
        );
        let hi = seg.end - t0;
        let lo = start - t0;
        let x_tol = if any_root && hi.is_finite() {
            // Any root proves occlusion: any point of the range will do as its value.
            hi - lo
        } else {
            self.x_tol(ray.dir, o, hi - lo)
        };
        let opts = self.roots.options(x_tol);
        if self.roots.isolation == IsolationMethod::Exact && self.degree >= 3 {
            // The reference: restricted and isolated exactly (no rounded polynomial at all).
            let s = exact_smallest(&restrict_exact_at(&self.f, ray, t0), (lo, hi), x_tol)?;
            return Some((t0 + s, o + ray.dir * s));
        }
        self.f
            .restrict(o, ray.dir, &mut ws.restrict, &mut ws.coeffs);
        if !self.certifies() {
            let s = if centred {
                smallest_root_split(ws, lo, hi, &opts, None)
                    .ok()
                    .flatten()?
            } else {
                smallest_root_in(ws, lo, hi, &opts)?
            };
            return Some((t0 + s, o + ray.dir * s));
        }
        // `o` = fl(origin + dir·t0), one rounding: within u·|o| of the exact point.
        let data = RestrictionSlack {
            rel: self.slack_rel,
            underflow_weight: self.underflow_weight,
            degree: self.degree,
            o_abs: o.abs() * (1.0 + f64::EPSILON),
            d_abs: ray.dir.abs(),
        };
        let slack = |r: f64| restriction_slack(|y| self.f.restriction_abs(y), &data, r);
        let (mut lo, mut hi) = (lo, hi);
        let mut answer = Err(RootError::SlackLimited { lo, hi });
        if !(lo.is_finite() && hi.is_finite()) {
            // An unbounded surface: cut the range where no true root can lie.
            if let Some(t) = PolyRef::new(&ws.coeffs).root_radius_within(&slack) {
                (lo, hi) = (lo.max(-t), hi.min(t));
            }
        }
        if lo.is_finite() && hi.is_finite() && !self.dropped_degree(&ws.coeffs, ray.dir) {
            answer = if centred {
                smallest_root_split(ws, lo, hi, &opts, Some(&slack))
            } else {
                certified_smallest(ws, lo, hi, &opts, Some(&slack))
            };
        }
        let s = match answer {
            Ok(s) => s?,
            Err(RootError::SlackLimited { .. }) => {
                let (lo, hi) = (start - t0, seg.end - t0);
                // Above the exact degree the double-double restriction gets a last try at
                // the reduced tolerance (not for a shadow ray, whose tolerance is its range).
                let reduced =
                    (!any_root && self.degree > EXACT_RESTRICTION_MAX_DEGREE).then(|| {
                        self.roots
                            .options(x_tol * (REDUCED_ROOT_X_TOL_REL / ROOT_X_TOL_REL))
                    });
                let both = [&opts, reduced.as_ref().unwrap_or(&opts)];
                let tries = &both[..1 + usize::from(reduced.is_some())];
                let dd_kept = match self.dd_tier(ws, ray, t0, (lo, hi), tries, centred) {
                    DdTier::Decided(s) => return s.map(|s| (t0 + s, o + ray.dir * s)),
                    DdTier::Undecided { kept } => kept,
                };
                if self.degree <= EXACT_RESTRICTION_MAX_DEGREE {
                    // The rounded restriction cannot decide this ray: restrict it exactly.
                    ws.stats.surface_certification.exact_restrictions += 1;
                    let exact = restrict_exact_at(&self.f, ray, t0);
                    if let Some(s) = self.rounded_exact(ws, &exact, (lo, hi), &opts, centred) {
                        return s.map(|s| (t0 + s, o + ray.dir * s));
                    }
                    ws.stats.surface_certification.exact_isolations += 1;
                    exact_smallest(&exact, (lo, hi), x_tol)?
                } else {
                    // Visible, never silent: counted, and answered for the rounded polynomial.
                    ws.stats.surface_certification.undecided_rays += 1;
                    // The double-double restriction, rounded, is the nearer to the surface
                    // as written: answered for it when the tier left it in `ws.coeffs`, which
                    // also saves restricting the ray a third time.
                    if !dd_kept || ws.coeffs.iter().any(|c| !c.is_finite()) {
                        self.f
                            .restrict(o, ray.dir, &mut ws.restrict, &mut ws.coeffs);
                    }
                    if centred {
                        smallest_root_split(ws, lo, hi, &opts, None)
                            .ok()
                            .flatten()?
                    } else {
                        smallest_root_in(ws, lo, hi, &opts)?
                    }
                }
            }
            Err(_) => return None,
        };
        Some((t0 + s, o + ray.dir * s))
    }

    /// The first tier of a slack-limited ray: the restriction computed again in double-double
    /// arithmetic from the restriction point `t0·dir + origin` in double-double, rounded to
    /// `f64`, and certified by [`Implicit::rounded_tier`] with the double-double rounding,
    /// `(γ_dd(K) + N·u_dd)·G(Y)` and four times the underflow term, as its extra slack
    /// (`paper-notes/implicit-surfaces.md` §6), at each tolerance of `tries` in turn (the
    /// query's own, then [`REDUCED_ROOT_X_TOL_REL`]'s when given). [`DdTier::Undecided`] when it
    /// decides nothing or the shape has no double-double restriction.
    fn dd_tier(
        &self,
        ws: &mut Workspace,
        ray: &Ray,
        t0: f64,
        range: (f64, f64),
        tries: &[&RootOptions],
        centred: bool,
    ) -> DdTier {
        let o: [Dd; 3] = std::array::from_fn(|k| Dd::product(t0, ray.dir[k]) + ray.origin[k]);
        let (mut scratch, mut coeffs) = (
            std::mem::take(&mut ws.restrict_dd),
            std::mem::take(&mut ws.coeffs_dd),
        );
        let restricted = self.f.restrict_dd(o, ray.dir, &mut scratch, &mut coeffs);
        ws.coeffs.clear();
        ws.coeffs.extend(coeffs.iter().map(|c| c.to_f64()));
        (ws.restrict_dd, ws.coeffs_dd) = (scratch, coeffs);
        if !restricted {
            return DdTier::Undecided { kept: false };
        }
        if self.dropped_degree(&ws.coeffs, ray.dir) {
            return DdTier::Undecided { kept: true };
        }
        ws.stats.surface_certification.dd_restrictions += 1;
        // |o| ≤ |hi|(1 + 2⁻⁵³), and the point's own error is in `dd_rel`.
        let data = RestrictionSlack {
            rel: self.dd_rel,
            underflow_weight: self.dd_underflow_weight,
            degree: self.degree,
            o_abs: DVec3::from_array(o.map(|x| x.to_f64().abs())) * (1.0 + 2.0 * f64::EPSILON),
            d_abs: ray.dir.abs(),
        };
        let poly3 = self.f.poly();
        let extra = |r: f64| restriction_slack(|y| poly3.eval_abs_upper(y), &data, r);
        match self.rounded_tier(ws, &extra, range, tries, centred) {
            Some((try_index, answer)) => {
                let c = &mut ws.stats.surface_certification;
                if try_index == 0 {
                    c.dd_decided += 1;
                } else {
                    c.reduced_precision += 1;
                }
                DdTier::Decided(answer)
            }
            None => DdTier::Undecided { kept: true },
        }
    }

    /// The second tier of a slack-limited ray: the exact restriction rounded to the nearest
    /// `f64` coefficients, certified by [`Implicit::rounded_tier`] with no extra slack.
    fn rounded_exact(
        &self,
        ws: &mut Workspace,
        exact: &QPoly,
        range: (f64, f64),
        opts: &RootOptions,
        centred: bool,
    ) -> Option<Option<f64>> {
        ws.coeffs.clear();
        ws.coeffs
            .extend(exact.coeffs().iter().map(poly::rat_to_f64));
        self.rounded_tier(ws, &|_| 0.0, range, &[opts], centred)
            .map(|(_, answer)| answer)
    }

    /// The coefficients in `ws.coeffs`, each the nearest `f64` to a restriction known to
    /// within `extra(R)` (`Σₘ|Δcₘ|Rᵐ`), certified with the slack of their own rounding —
    /// `2u·Σ|ĉₘ|Rᵐ`, the polynomial's own scale, not `F_abs`'s — plus `extra`, by the same
    /// query, at each tolerance of `tries` in turn (the slack and the range built once).
    /// `None` when that slack decides nothing at any of them; otherwise the index of the try
    /// that decided and its answer (`None`: no root).
    fn rounded_tier(
        &self,
        ws: &mut Workspace,
        extra: &dyn Fn(f64) -> f64,
        (lo, hi): (f64, f64),
        tries: &[&RootOptions],
        centred: bool,
    ) -> Option<(usize, Option<f64>)> {
        // A top coefficient below the subnormals rounds to 0: the degree drops, and with it
        // the blossom argument of the slack (see `dropped_degree`).
        if ws.coeffs.iter().any(|c| !c.is_finite()) || ws.coeffs.last() == Some(&0.0) {
            return None;
        }
        let abs: Vec<f64> = ws.coeffs.iter().map(|c| c.abs()).collect();
        let n = abs.len();
        // Correct rounding errs by at most u·|ĉ| (and 2^-1074 in the subnormal range) per
        // coefficient; Horner on non-negative numbers, inflated for its 2n roundings.
        let slack = move |r: f64| {
            let r_up = r * (1.0 + 2.0 * f64::EPSILON);
            let (sum, powers) = abs
                .iter()
                .rev()
                .fold((0.0, 0.0), |(s, z), &c| (s * r_up + c, z * r_up + 1.0));
            (2.0 * UNIT_ROUNDOFF * sum + 5e-324 * powers) * (1.0 + 2.0 * gamma(2 * n + 2))
                + extra(r)
        };
        let (mut lo, mut hi) = (lo, hi);
        if !(lo.is_finite() && hi.is_finite()) {
            let t = PolyRef::new(&ws.coeffs).root_radius_within(&slack)?;
            (lo, hi) = (lo.max(-t), hi.min(t));
        }
        tries.iter().enumerate().find_map(|(i, opts)| {
            let answer = if centred {
                smallest_root_split(ws, lo, hi, opts, Some(&slack))
            } else {
                certified_smallest(ws, lo, hi, opts, Some(&slack))
            };
            match answer {
                Ok(s) => Some((i, s)),
                Err(RootError::SlackLimited { .. }) => None,
                Err(_) => Some((i, None)),
            }
        })
    }
}

/// The exact restriction of `f` to `ray` at `t0`: the restriction point `origin + t0·dir` and
/// the polynomial are exact rationals, so this is the surface as written along the `f64` ray.
fn restrict_exact_at<F: ImplicitFn>(f: &F, ray: &Ray, t0: f64) -> QPoly {
    let o: [Rat; 3] = std::array::from_fn(|k| exact_point(ray.origin[k], ray.dir[k], t0));
    let d: [Rat; 3] = std::array::from_fn(|k| exact_point(0.0, ray.dir[k], 1.0));
    f.restrict_exact(&o, &d)
}

/// The smallest root in `(lo, hi]` of the exact polynomial `p`, within `x_tol` (exact Sturm
/// isolation, `poly`'s [`QPoly::smallest_root`]). Infinite ends become the exact Cauchy
/// bound; `None` also when `p` vanishes (the ray lies in the surface).
fn exact_smallest(p: &QPoly, (lo, hi): (f64, f64), x_tol: f64) -> Option<f64> {
    if p.is_zero() {
        return None;
    }
    let rat = |x: f64| poly::rat_from_f64(x).expect("finite range");
    let bound = p
        .cauchy_bound()
        .unwrap_or_else(|| Rat::from_integer(1.into()));
    let end = |x: f64, inf: Rat| if x.is_finite() { rat(x) } else { inf };
    let (a, b) = (end(lo, -bound.clone()), end(hi, bound));
    p.smallest_root(&a, &b, x_tol)
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

    /// The ray's chord through the shape's own bounding sphere, widened by the margin by
    /// which the root search may start before an entry ([`ENTRY_MARGIN_REL`], twice over, at
    /// both ends); `None` when the ray passes outside it. Shapes without such a sphere leave
    /// it to their box.
    fn hit_interval(&self, ray: &Ray) -> Option<Range<f64>> {
        let Some((c, r)) = self.f.bounding_sphere() else {
            return Some(f64::NEG_INFINITY..f64::INFINITY);
        };
        let s = sphere_segment(ray, c, r)?;
        let m = 2.0 * ENTRY_MARGIN_REL * (s.start.abs().max(s.end.abs()) + (s.end - s.start));
        Some(s.start - m..s.end + m)
    }

    fn convex(&self) -> bool {
        self.f.convex()
    }

    fn shading(&self, hit: &Hit) -> SurfaceGeometry {
        let p = hit.local;
        let e = self.f.eval_grad(p);
        let (normal, p_err) = match gradient_normal(e, self.degree) {
            // A ray spawned here is restricted at its origin, where the certified query needs
            // the sign of the true polynomial beyond the restriction's slack `γ(K)·G(|o|)`
            // (§6): move the origin twice that far in value past the surface, or every shadow
            // ray would start undecided.
            Some((n, err)) if self.certifies() => {
                let slack = gamma(self.rounding_steps as usize) * self.f.restriction_abs(p.abs());
                (n, err + DVec3::splat(2.0 * slack / e.grad.length()))
            }
            Some(found) => found,
            None => {
                let size = self
                    .bounds
                    .map_or(0.0, |b| b.diagonal())
                    .max(p.abs().max_element());
                (None, DVec3::splat(SINGULAR_P_ERR_REL * size))
            }
        };
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
    use crate::trivariate::{Poly3, RestrictScratch};
    use poly::IsolationMethod;

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

    /// Issue 11 (underflow of the restriction): along a direction with `d_x = 8.3e-28`, the
    /// restriction of `x¹² − 10⁻¹⁸` at `x = 0` has the leading coefficient `d_x¹² ≈ 1e-325`,
    /// which underflows to 0: the rounded ray polynomial was the constant `−10⁻¹⁸`, and the
    /// ray missed the sheet `x = 10^-1.5` (at `t ≈ 3.8e25`), certified. A restriction whose
    /// degree dropped below the one its direction allows is not certified from the rounded
    /// polynomial (`Implicit::dropped_degree`): it is restricted exactly (degree 12) and hits.
    #[test]
    fn r11_restriction_whose_degree_underflowed_is_not_certified_from_it() {
        let eps = 1e-18;
        let f = &Poly3::x().pow(12) - &Poly3::constant(eps);
        let surface = Implicit::new(Algebraic::new(f), None);
        let mut ws = Workspace::new();
        // `d_x¹²` is below half the smallest subnormal.
        let d_x = 8.3e-28;
        let ray = Ray::new(DVec3::new(0.0, -5.0, 0.0), DVec3::new(d_x, 1.0, 0.0));
        assert_eq!(ray.dir.x, d_x, "the direction is already of unit length");
        let want = eps.powf(1.0 / 12.0) / d_x;
        let hit = surface
            .intersect(&ray, 0.0..2.0 * want, &mut ws)
            .expect("the ray crosses x = ε^(1/12)");
        assert!(
            (hit.t - want).abs() <= DEPTH_REL * want,
            "t {} vs {want}: {:?}",
            hit.t,
            ws.stats.surface_certification
        );
        assert!(
            ws.stats.surface_certification.exact_restrictions > 0,
            "decided by the exact restriction: {:?}",
            ws.stats.surface_certification
        );
    }

    /// Issue 11 (underflow of the restriction): the slack bounds `Σₘ |cₘ − ĉₘ|·Rᵐ` also where
    /// a product of the restriction lands in the subnormal range. Along `d_x ≈ 3.2e-27` the
    /// leading coefficient of `x¹² − 10⁻¹⁸`, `d_x¹² ≈ 1e-318`, is off by 2.4e-6 relative,
    /// which Higham's relative term (`γ(K)·G ≈ 1e-14·G`) alone does not cover.
    #[test]
    fn r11_restriction_slack_covers_underflowing_products() {
        let f = Algebraic::new(&Poly3::x().pow(12) - &Poly3::constant(1e-18));
        let (o, d) = (
            DVec3::new(0.0, -5.0, 0.0),
            DVec3::new(3.1654399378285475e-27, 1.0, 0.0),
        );
        let mut coeffs = Vec::new();
        f.restrict(o, d, &mut RestrictScratch::default(), &mut coeffs);
        let rat = |x: f64| poly::rat_from_f64(x).expect("finite");
        let exact = f.restrict_exact(&o.to_array().map(rat), &d.to_array().map(rat));
        let surface = Implicit::new(f, None);
        let data = RestrictionSlack {
            rel: surface.slack_rel,
            underflow_weight: surface.underflow_weight,
            degree: surface.degree,
            o_abs: o.abs() * (1.0 + f64::EPSILON),
            d_abs: d.abs(),
        };
        for r in [1.0f64, 1e10, 1e25, 1e26] {
            let err: f64 = exact
                .coeffs()
                .iter()
                .enumerate()
                .map(|(m, c)| {
                    let stored = coeffs.get(m).copied().unwrap_or(0.0);
                    let weight = num_traits::pow(rat(r), m);
                    poly::rat_to_f64(&((c - rat(stored)) * weight)).abs()
                })
                .sum();
            let slack = restriction_slack(|y| surface.f.restriction_abs(y), &data, r);
            assert!(err <= slack, "R = {r:e}: error {err:e} > slack {slack:e}");
            assert!(
                r < 1e10 || err > 0.0,
                "the rounding is not exact: {coeffs:?}"
            );
        }
    }

    /// Issue 11 (double-double tier): Barth's sextic has rays its `f64` restriction cannot
    /// decide (near the nodes and silhouettes: 409 of 40 318 at 200²), which were restricted
    /// exactly at about 0.7 M instructions each. Restricted again in double-double, every one
    /// is decided there, and each hit agrees with the exact reference.
    #[test]
    fn r11_barth_rays_the_f64_restriction_cannot_decide_are_decided_in_double_double() {
        let (x, y, z) = (Poly3::x(), Poly3::y(), Poly3::z());
        let phi = (1.0 + 5f64.sqrt()) / 2.0;
        let p2 = Poly3::constant(phi * phi);
        let sq = |a: &Poly3| a * a;
        let factor = |a: &Poly3, b: &Poly3| &(&p2 * &sq(a)) - &sq(b);
        let quartic = sq(&(&(&(&sq(&x) + &sq(&y)) + &sq(&z)) - &Poly3::constant(1.0)));
        let f = &(&(&Poly3::constant(4.0) * &factor(&x, &y))
            * &(&factor(&y, &z) * &factor(&z, &x)))
            - &(&Poly3::constant(1.0 + 2.0 * phi) * &quartic);
        assert_eq!(f.degree(), 6, "Barth's sextic");
        let bounds = Some(Bounds3::new(DVec3::splat(-2.0), DVec3::splat(2.0)));
        let surface = Implicit::new(Algebraic::new(f.clone()), bounds);
        let exact = Implicit::new(Algebraic::new(f), bounds).with_root_methods(RootMethods {
            isolation: IsolationMethod::Exact,
            ..RootMethods::default()
        });
        let mut ws = Workspace::new();
        let mut reference = Workspace::new();
        let mut hits = 0;
        for ray in camera_rays(DVec3::new(5.0, -9.0, 6.0), 2.2, 30) {
            let got = surface
                .intersect(&ray, 0.0..f64::INFINITY, &mut ws)
                .map(|h| h.t);
            let want = exact
                .intersect(&ray, 0.0..f64::INFINITY, &mut reference)
                .map(|h| h.t);
            match (got, want) {
                (Some(g), Some(w)) => {
                    hits += 1;
                    assert!((g - w).abs() <= DEPTH_REL * w, "{ray:?}: {g} vs {w}");
                }
                (g, w) => assert_eq!(g, w, "hit/miss of {ray:?}"),
            }
        }
        assert!(hits > 200, "the rays cover the surface: {hits} hits of 900");
        let c = ws.stats.surface_certification;
        assert!(c.dd_restrictions > 0, "some rays need more than f64: {c:?}");
        assert_eq!(
            (c.dd_decided, c.exact_restrictions, c.undecided_rays),
            (c.dd_restrictions, 0, 0),
            "all decided in double-double"
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

    /// `x² + y² + z² − 1`.
    fn unit_sphere() -> Poly3 {
        let (x, y, z) = (Poly3::x(), Poly3::y(), Poly3::z());
        &(&(&x * &x) + &(&y * &y)) + &(&(&z * &z) - &Poly3::constant(1.0))
    }

    /// The first `t > 0` where `ray` meets the sphere `|p|² = r2` about the origin, by the
    /// cancellation-free quadratic formula (relative error a few ulps), or `None` when the ray
    /// misses it or grazes it within `GRAZE_REL` (where hit/miss is not a stable fact).
    fn sphere_hit(ray: &Ray, r2: f64) -> Option<Option<f64>> {
        /// Relative margin of the discriminant below which a ray counts as grazing.
        const GRAZE_REL: f64 = 1e-6;
        let (a, b, c) = (
            ray.dir.length_squared(),
            ray.origin.dot(ray.dir),
            ray.origin.length_squared() - r2,
        );
        let disc = b * b - a * c;
        if disc.abs() <= GRAZE_REL * b * b {
            return None;
        }
        if disc < 0.0 {
            return Some(None);
        }
        let q = -(b + b.signum() * disc.sqrt());
        let (t1, t2) = (q / a, c / q);
        Some([t1.min(t2), t1.max(t2)].into_iter().find(|&t| t > 0.0))
    }

    /// Depth agreement of a certified hit with an analytic one (relative), the 1e-9.
    const DEPTH_REL: f64 = 1e-9;

    /// Traces `rays` through `surface` and compares each with `want(ray)` (`None`: grazing,
    /// skipped): hit/miss must agree and depths within [`DEPTH_REL`]. Returns the hits.
    fn assert_matches(
        surface: &dyn Surface,
        rays: &[Ray],
        ws: &mut Workspace,
        want: impl Fn(&Ray) -> Option<Option<f64>>,
    ) -> usize {
        let mut hits = 0;
        for ray in rays {
            let Some(want) = want(ray) else { continue };
            let got = surface.intersect(ray, 0.0..f64::INFINITY, ws).map(|h| h.t);
            match (got, want) {
                (Some(g), Some(w)) => {
                    hits += 1;
                    assert!(
                        (g - w).abs() <= DEPTH_REL * w,
                        "{ray:?}: t {g} vs {w} (relative {:e})",
                        (g - w).abs() / w
                    );
                }
                (g, w) => assert_eq!(g, w, "hit/miss of {ray:?}"),
            }
        }
        hits
    }

    /// Issue 11: the thin shell `(x² + y² + z² − 1)² − 2⁻⁵²`, whose coefficients are exact
    /// (the constant is `1 − 2⁻⁵²`) and whose sheets are the spheres of radii
    /// `√(1 ± 2⁻²⁶)`, 7.5e-9 apart. Between them `|F| ≤ 2⁻⁵²`, below the rounding of its
    /// restriction to a ray (`γ(K)·F_abs ≈ 1e-14`), so the rounded ray polynomial has lost
    /// the shell: before this fix hits came out on either sheet or not at all, silently.
    /// Every hit must be on the outer sheet, for the certified and the exact methods alike,
    /// and the rays the rounding cannot decide must have been restricted exactly.
    #[test]
    fn r11_thin_shell_hits_its_outer_sheet() {
        let eps = 2f64.powi(-52);
        let f = &unit_sphere().pow(2) - &Poly3::constant(eps);
        assert_eq!(
            f.terms()
                .iter()
                .find(|t| t.exps == [0, 0, 0])
                .map(|t| t.coeff),
            Some(1.0 - eps),
            "the constant is exact"
        );
        let bounds = Some(Bounds3::new(DVec3::splat(-1.25), DVec3::splat(1.25)));
        let outer = 1.0 + 2f64.powi(-26);
        // Few rays: each hit is isolated in exact rational arithmetic (about 0.2 s a ray in
        // the dev profile on a loaded machine).
        let rays = camera_rays(DVec3::new(5.0, -9.0, 6.0), 0.9, 3);
        for isolation in [IsolationMethod::Bernstein, IsolationMethod::Exact] {
            let methods = RootMethods {
                isolation,
                ..RootMethods::default()
            };
            let shell = Implicit::new(Algebraic::new(f.clone()), bounds).with_root_methods(methods);
            let mut ws = Workspace::new();
            let hits = assert_matches(&shell, &rays, &mut ws, |r| sphere_hit(r, outer));
            assert!(
                hits >= 5,
                "{isolation:?}: the rays cover the shell: {hits} hits"
            );
            let c = ws.stats.surface_certification;
            if isolation == IsolationMethod::Bernstein {
                assert!(
                    c.exact_restrictions > 0 && ws.stats.roots.slack_limited > 0,
                    "the slack-limited rays were restricted exactly: {c:?}"
                );
            }
            assert_eq!(c.undecided_rays, 0, "{isolation:?}: nothing undecided");
        }
    }

    /// Issue 11: `(x² + y² + z²)^16 − 1`, the unit sphere written with degree 32, restricted
    /// in `f64` with its rounding bounded: depth agrees with the sphere's to 1e-9 relative,
    /// no holes, and no ray left undecided.
    #[test]
    fn r11_degree_32_sphere_matches_the_unit_sphere() {
        let (x, y, z) = (Poly3::x(), Poly3::y(), Poly3::z());
        let r2 = &(&(&x * &x) + &(&y * &y)) + &(&z * &z);
        let f = &r2.pow(16) - &Poly3::constant(1.0);
        assert_eq!(f.degree(), 32, "degree");
        let bounds = Some(Bounds3::new(DVec3::splat(-1.25), DVec3::splat(1.25)));
        let sphere = Implicit::new(Algebraic::new(f), bounds);
        let mut ws = Workspace::new();
        let rays = camera_rays(DVec3::new(5.0, -9.0, 6.0), 1.2, 10);
        let hits = assert_matches(&sphere, &rays, &mut ws, |r| sphere_hit(r, 1.0));
        assert!(hits > 30, "the rays cover the sphere: {hits} hits");
        assert_eq!(
            ws.stats.surface_certification.undecided_rays, 0,
            "{:?}",
            ws.stats.surface_certification
        );
    }

    /// Issue 11: the family `g^k − ε` has the real set of `g = ε^(1/k)` and, for even `k`,
    /// of `g = −ε^(1/k)` too; with `ε = 2^(−k·m)` both constants are exact. For the unit
    /// sphere's `g` and the quartic `g = x⁴ + y⁴ + z⁴ − 1/2`, hit/miss and depth must match
    /// the first hit of those low-degree surfaces.
    #[test]
    fn r11_powers_minus_epsilon_match_their_low_degree_sheets() {
        let quartic = &(&(&Poly3::x().pow(4) + &Poly3::y().pow(4)) + &Poly3::z().pow(4))
            - &Poly3::constant(0.5);
        let bounds = Some(Bounds3::new(DVec3::splat(-1.25), DVec3::splat(1.25)));
        // Few rays: near a root of g^k − ε the derivative is k·ε^((k−1)/k)·g', so the rounded
        // restriction cannot place the root to the tolerance and most hits are isolated in
        // exact rational arithmetic (slow in the dev profile).
        let rays = camera_rays(DVec3::new(5.0, -9.0, 6.0), 1.2, 3);
        let mut ws = Workspace::new();
        for (g, ks) in [(unit_sphere(), [2, 3, 4]), (quartic, [2, 3, 3])] {
            for k in ks {
                let level = 2f64.powi(-8);
                let eps = level.powi(k);
                let high = Implicit::new(
                    Algebraic::new(&g.pow(k as u32) - &Poly3::constant(eps)),
                    bounds,
                );
                let sheet =
                    |c: f64| Implicit::new(Algebraic::new(&g - &Poly3::constant(c)), bounds);
                let (outer, inner) = (sheet(level), sheet(-level));
                for ray in &rays {
                    let mut first = outer
                        .intersect(ray, 0.0..f64::INFINITY, &mut ws)
                        .map(|h| h.t);
                    if k % 2 == 0
                        && let Some(t) = inner.intersect(ray, 0.0..f64::INFINITY, &mut ws)
                    {
                        first = Some(first.map_or(t.t, |f: f64| f.min(t.t)));
                    }
                    let got = high
                        .intersect(ray, 0.0..f64::INFINITY, &mut ws)
                        .map(|h| h.t);
                    match (got, first) {
                        (Some(a), Some(b)) => assert!(
                            (a - b).abs() <= DEPTH_REL * b,
                            "k = {k}, {ray:?}: {a} vs {b}"
                        ),
                        (a, b) => assert_eq!(a, b, "k = {k}: hit/miss of {ray:?}"),
                    }
                }
            }
        }
        assert_eq!(
            ws.stats.surface_certification.undecided_rays, 0,
            "all decided"
        );
    }

    /// A thin shell of degree 20, `((x² + y² + z²)^5 − 1)² − 2⁻⁵²`, is above
    /// [`EXACT_RESTRICTION_MAX_DEGREE`]: its slack-limited rays are not restricted exactly
    /// but counted as undecided — visible in `--stats`, never silent.
    #[test]
    fn undecided_rays_are_counted_above_the_exact_degree_limit() {
        let (x, y, z) = (Poly3::x(), Poly3::y(), Poly3::z());
        let r2 = &(&(&x * &x) + &(&y * &y)) + &(&z * &z);
        let g = &r2.pow(5) - &Poly3::constant(1.0);
        let f = &g.pow(2) - &Poly3::constant(2f64.powi(-52));
        assert!(f.degree() > EXACT_RESTRICTION_MAX_DEGREE, "above the limit");
        let bounds = Some(Bounds3::new(DVec3::splat(-1.25), DVec3::splat(1.25)));
        let shell = Implicit::new(Algebraic::new(f), bounds);
        let mut ws = Workspace::new();
        for ray in camera_rays(DVec3::new(5.0, -9.0, 6.0), 0.5, 4) {
            shell.intersect(&ray, 0.0..f64::INFINITY, &mut ws);
        }
        let c = ws.stats.surface_certification;
        assert!(c.undecided_rays > 0, "counted: {c:?}");
        assert_eq!(c.exact_restrictions, 0, "none restricted exactly: {c:?}");
    }

    /// Issue 11: on the degree-20 sheets seen from 9 430 units (`benches/vs-povray.sh`'s
    /// far-sheets20), above [`EXACT_RESTRICTION_MAX_DEGREE`], rays that neither the `f64` nor
    /// the double-double restriction certifies to [`ROOT_X_TOL_REL`] were answered for the
    /// `f64` restriction, uncertified, up to 1.7e-10 relative from the exact reference's hit.
    /// Now the double-double restriction decides them at [`REDUCED_ROOT_X_TOL_REL`]: each hit
    /// within that tolerance of the exact reference's. Any ray still undecided is answered for
    /// the double-double restriction, within 1e-11 of the reference on this view.
    #[test]
    fn r11_undecided_rays_are_answered_for_the_double_double_restriction() {
        let (x, y, z) = (Poly3::x(), Poly3::y(), Poly3::z());
        let rho2 = &(&x * &x) + &(&y * &y);
        let s = &(&rho2 + &(&z * &z)) + &Poly3::constant(3.0);
        let g = &s.pow(2) - &(&rho2 * 16.0);
        let f = &g.pow(5) - &Poly3::constant(1.0 / 32.0);
        let bounds = Bounds3::new(DVec3::new(-3.1, -3.1, -1.1), DVec3::new(3.1, 3.1, 1.1));
        let fast = Implicit::new(Algebraic::new(f.clone()), Some(bounds));
        let exact = Implicit::new(Algebraic::new(f), Some(bounds)).with_root_methods(RootMethods {
            isolation: IsolationMethod::Exact,
            ..RootMethods::default()
        });
        let mut ws = Workspace::new();
        let (mut reduced, mut undecided) = (0, 0);
        for ray in camera_rays(DVec3::new(0.0, -8000.0, 5000.0), 3.2, 12) {
            let before = ws.stats.surface_certification;
            let hit = fast.nearest(&ray, 0.0..f64::INFINITY, &mut ws, false);
            let after = ws.stats.surface_certification;
            let tol = if after.reduced_precision > before.reduced_precision {
                reduced += 1;
                REDUCED_ROOT_X_TOL_REL * bounds.diagonal() / ray.dir.length()
            } else if after.undecided_rays > before.undecided_rays {
                undecided += 1;
                1e-11 * hit.map_or(0.0, |(t, _)| t)
            } else {
                continue;
            };
            let reference = exact.nearest(&ray, 0.0..f64::INFINITY, &mut ws, false);
            match (hit, reference) {
                (Some((t, _)), Some((t_ref, _))) => assert!(
                    (t - t_ref).abs() <= tol,
                    "{ray:?}: hit at {t}, the exact reference at {t_ref}"
                ),
                (hit, reference) => panic!("{ray:?}: hit {hit:?}, reference {reference:?}"),
            }
        }
        assert!(reduced >= 10, "decided at reduced precision: {reduced}");
        assert!(undecided <= 1, "left undecided: {undecided}");
    }

    /// `Implicit::new` leaves the certification data of degrees 1–2 at zero (it was a third of
    /// the 66 430-sphere scene's surface set-up): no query of such a surface may read it. It is
    /// read only by certified queries and centred restrictions, neither of which a degree-1 or
    /// degree-2 surface takes under any root method; a change that let one would make this
    /// test fail before it made hits wrong.
    #[test]
    fn degree_one_and_two_surfaces_never_read_the_certification_data() {
        let (x, y, z) = (Poly3::x(), Poly3::y(), Poly3::z());
        let paraboloid = &(&(&x * &x) + &(&y * &y)) - &z;
        for isolation in [
            IsolationMethod::Bernstein,
            IsolationMethod::Exact,
            IsolationMethod::Sturm,
            IsolationMethod::StamSturm,
        ] {
            let roots = RootMethods {
                isolation,
                ..RootMethods::default()
            };
            let sphere =
                Implicit::new(Sphere::new(DVec3::ZERO, 1.0), None).with_root_methods(roots);
            let plane =
                Implicit::new(Plane::new(DVec3::ZERO, DVec3::Z), None).with_root_methods(roots);
            let quadric =
                Implicit::new(Algebraic::new(paraboloid.clone()), None).with_root_methods(roots);
            assert!(!sphere.certifies() && !plane.certifies() && !quadric.certifies());
            assert_eq!(sphere.slack_rel, 0.0, "left at zero");
            assert!(
                [sphere.degree, plane.degree, quadric.degree]
                    .iter()
                    .all(|&d| d < 3)
            );
        }
        // A cubic gets its data.
        let cubic = Implicit::new(Algebraic::new(&(&x * &paraboloid) - &y), None);
        assert!(cubic.certifies() && cubic.slack_rel > 0.0 && cubic.ray_degree[7] == 3);
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

    /// Every hit of a sphere and of a torus lies in the interval `hit_interval` gives, and
    /// a ray it says misses has no hit: 4 000 random rays aimed around them, from near and far
    /// (the nearest-hit query skips surfaces by this interval, so a hit outside it would be
    /// lost).
    #[test]
    fn hits_lie_in_the_hit_interval() {
        use rand::{Rng, SeedableRng};
        let sphere = Implicit::new(Sphere::new(DVec3::new(0.3, -0.2, 0.1), 1.3), None);
        let torus = Implicit::new(crate::surface::Torus::new(2.0, 0.5), None);
        let surfaces: [&dyn Surface; 2] = [&sphere, &torus];
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(43);
        let mut ws = Workspace::new();
        let mut hits = 0;
        for k in 0..4000 {
            let surface = surfaces[k % 2];
            let far = if k % 4 < 2 { 4.0 } else { 1e4 };
            let o = DVec3::new(
                rng.gen_range(-1.0..1.0),
                rng.gen_range(-1.0..1.0),
                rng.gen_range(-1.0..1.0),
            )
            .normalize()
                * far;
            let target = DVec3::new(
                rng.gen_range(-2.6..2.6),
                rng.gen_range(-2.6..2.6),
                rng.gen_range(-1.5..1.5),
            );
            let ray = Ray::new(o, target - o);
            let range = rng.gen_range(-0.5..0.5)..f64::INFINITY;
            let interval = surface.hit_interval(&ray);
            if let Some(h) = surface.intersect(&ray, range, &mut ws) {
                hits += 1;
                let i = interval.unwrap_or_else(|| panic!("ray {k}: a hit at {} on a miss", h.t));
                assert!(i.contains(&h.t), "ray {k}: hit at {} outside {i:?}", h.t);
            }
        }
        assert!(hits > 1000, "only {hits} hits");
    }

    /// A unit sphere 10¹² units away, off every axis, and rays from near the origin towards it
    /// passing its centre at distances 0 … 1.5 (many within 10⁻⁴ and 10⁻⁹ of the rim):
    /// `oc × d` then cancels to a quantity whose rounding (≈ 10⁻⁴) dwarfs the clip margin. Against exact rational arithmetic on
    /// the stored ray, every line that meets the sphere keeps a segment holding its whole chord
    /// (both ends outside the sphere, the closest point inside the segment). Without the
    /// rounding bound (the clip margin alone, 10⁻⁹) rays up to 10⁻⁴ inside the rim were
    /// rejected: the first here is ray 22, passing 0.99993 from the centre.
    #[test]
    fn a_far_sphere_keeps_every_chord_of_the_exact_ray() {
        use rand::{Rng, SeedableRng};
        let q = |x: f64| poly::rat_from_f64(x).expect("finite");
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(41);
        let (mut meeting, mut kept_short) = (0, 0);
        for k in 0..3000 {
            // A direction and a perpendicular with digits in every place, new for each ray,
            // so that the cross product's terms cancel and their roundings vary in sign.
            let along = DVec3::new(
                rng.gen_range(0.6..0.7),
                rng.gen_range(0.7..0.8),
                rng.gen_range(0.1..0.2),
            )
            .normalize();
            let across = along.cross(DVec3::new(0.3, -0.2, 0.9)).normalize();
            let c = along * 1e12;
            let miss = match k % 3 {
                0 => rng.gen_range(0.0..1.5),
                1 => 1.0 + rng.gen_range(-1e-4..1e-4),
                _ => 1.0 + rng.gen_range(-1e-9..1e-9),
            };
            // The origin moved across the line of centres (finely: it is near 0), the
            // direction fixed.
            let ray = Ray::new(across * miss, along);
            let (o, d) = (ray.origin, ray.dir);
            // |o + t·d − c|² − 1 for the stored ray, exactly, at a rational t.
            let f = |t: &Rat| -> Rat {
                [(o.x, d.x, c.x), (o.y, d.y, c.y), (o.z, d.z, c.z)]
                    .into_iter()
                    .map(|(oi, di, ci)| {
                        let v = q(oi) + t * q(di) - q(ci);
                        &v * &v
                    })
                    .fold(Rat::from_integer(0.into()), |s, v| s + v)
                    - Rat::from_integer(1.into())
            };
            let dd = q(d.x) * q(d.x) + q(d.y) * q(d.y) + q(d.z) * q(d.z);
            let closest = (q(d.x) * (q(c.x) - q(o.x))
                + q(d.y) * (q(c.y) - q(o.y))
                + q(d.z) * (q(c.z) - q(o.z)))
                / dd;
            if f(&closest) > Rat::from_integer(0.into()) {
                continue;
            }
            meeting += 1;
            let Some(seg) = sphere_segment(&ray, c, 1.0) else {
                panic!("ray {k} (passing at {miss}) meets the sphere but was rejected");
            };
            let inside = |t: f64| f(&q(t)) < Rat::from_integer(0.into());
            if !(q(seg.start) < closest && closest < q(seg.end))
                || inside(seg.start)
                || inside(seg.end)
            {
                kept_short += 1;
            }
        }
        assert!(meeting > 500, "only {meeting} rays meet the sphere");
        assert_eq!(kept_short, 0, "segments shorter than the chord");
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

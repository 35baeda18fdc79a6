//! [`TraceStats`]: what the tracer did, counted per thread and merged at the end.

use std::fmt;
use std::ops::AddAssign;
use std::time::Duration;

use poly::{IsolationMethod, RefineMethod, RootStats, STATS_DEGREES};

use crate::methods::RootMethods;

mod patch;
mod slowest;

use crate::aggregate::BvhInfo;
pub use patch::{HIST_BINS, PatchStats};
pub use slowest::{Escalations, SlowObject, SlowestCell};

/// Counters filled in while tracing. Each worker thread owns one (inside its
/// [`Workspace`](crate::Workspace)); the totals are summed with [`TraceStats::merge`].
#[derive(Clone, Debug, Default, PartialEq)]
pub struct TraceStats {
    /// Camera rays.
    pub primary_rays: u64,
    /// Shadow rays traced (one per light per shaded hit, when shadows are on and the light is
    /// above the surface).
    pub shadow_rays: u64,
    /// Reflected rays (eq. 2.11–2.13).
    pub reflected_rays: u64,
    /// Refracted rays (eq. 2.14–2.16), including those redirected by total internal reflection.
    pub refracted_rays: u64,
    /// Per surface kind (indexed by [`SurfaceKind::index`]): nearest-hit tests, hits, shadow
    /// (occlusion) tests, occlusions, and bounding-box rejections (before any polynomial).
    pub per_kind: [KindStats; SurfaceKind::COUNT],
    /// Skipped shadow rays: `Shadows = OFF`.
    pub shadow_skipped_off: u64,
    /// Skipped light contributions: the light is below the surface (`N·L ≤ 0`), no shadow ray.
    pub light_below_surface: u64,
    /// Shadow rays stopped at the first blocker (counted in `per_kind[..].occlusions` too).
    pub shadow_blocked: u64,
    /// Of those, shadow rays blocked by the shadow cache's primitive (the last blocker
    /// towards the same light on this thread), without a BVH traversal.
    pub shadow_cache_hits: u64,
    /// Secondary rays not traced because the material has no reflection or transmission
    /// (illumination below `MIRROR`, or `k_s = 0` / `k_t = 0`).
    pub secondary_skipped_material: u64,
    /// Secondary rays not traced because `MaxDepth` was reached.
    pub secondary_skipped_depth: u64,
    /// Secondary rays not traced because their weight fell below
    /// [`ADC_BAILOUT`](crate::whitted::ADC_BAILOUT).
    pub secondary_skipped_weight: u64,
    /// Transmissions turned into reflections by total internal reflection.
    pub total_internal_reflections: u64,
    /// Of those, rays not traced because the reflected ray (same origin, same direction) was
    /// traced anyway and carried the transmitted weight too.
    pub tir_merged: u64,
    /// Hits at a singular point (`∇F = 0`) shaded with the fallback normal.
    pub singular_normals: u64,
    /// Root queries of the polynomial solver (by degree, exact fallbacks…).
    pub roots: RootStats,
    /// Implicit-surface rays whose rounded restriction could not be certified against the
    /// surface as written (`paper-notes/implicit-surfaces.md` §6).
    pub surface_certification: CertificationStats,
    /// Bézier patch intersections: Stam's table (basis size, degrees) and rejections.
    pub patches: PatchStats,
    /// Nodes of the scene's BVH visited by nearest-hit and shadow queries.
    pub bvh_node_visits: u64,
    /// The scene's BVH as built (recorded once per render by [`render`](crate::render); kept,
    /// not summed, by [`TraceStats::merge`]).
    pub bvh: BvhInfo,
    /// The cell that took longest, with its root-query escalations (kept, not summed, by
    /// [`TraceStats::merge`]: the slower of the two).
    pub slowest: Option<SlowestCell>,
}

/// Rays of implicit surfaces (degree 3 and more) that the value slack of their rounded
/// restriction left undecided ([`poly::RootError::SlackLimited`]; the queries are counted in
/// `roots.slack_limited`).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct CertificationStats {
    /// Slack-limited rays restricted again in double-double arithmetic (then rounded to
    /// `f64` with a slack of the polynomial's own scale plus the double-double rounding):
    /// the first tier, at any degree.
    pub dd_restrictions: u64,
    /// Of those, rays the double-double restriction decided.
    pub dd_decided: u64,
    /// Of those it did not, rays above `EXACT_RESTRICTION_MAX_DEGREE` it decided at the
    /// reduced tolerance `REDUCED_ROOT_X_TOL_REL` of the implicit-surface module (certified,
    /// to about 10⁻⁷ of the object's size instead of 10⁻¹⁰).
    pub reduced_precision: u64,
    /// Rays restricted again in exact rational arithmetic (then rounded to `f64` with a
    /// slack of the polynomial's own scale, which decides most), up to the degree
    /// `EXACT_RESTRICTION_MAX_DEGREE` of the implicit-surface module.
    pub exact_restrictions: u64,
    /// Of those, rays whose rounded exact restriction still decided nothing, isolated with
    /// exact Sturm sequences.
    pub exact_isolations: u64,
    /// Slack-limited rays above that degree, answered for the rounded restriction: the pixel
    /// may be wrong, and this says how many.
    pub undecided_rays: u64,
}

/// Counters for one kind of surface.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct KindStats {
    /// Nearest-hit queries.
    pub tests: u64,
    /// Nearest-hit queries that returned a hit (each primitive is asked over the whole range).
    pub hits: u64,
    /// Occlusion (shadow) queries.
    pub shadow_tests: u64,
    /// Occlusion queries that found a blocker.
    pub occlusions: u64,
    /// Queries rejected by a bounding volume (the box, or a torus's bounding sphere) before
    /// any polynomial was built.
    pub bbox_rejects: u64,
}

impl KindStats {
    fn merge(&mut self, o: &KindStats) {
        self.tests += o.tests;
        self.hits += o.hits;
        self.shadow_tests += o.shadow_tests;
        self.occlusions += o.occlusions;
        self.bbox_rejects += o.bbox_rejects;
    }
}

impl TraceStats {
    /// Adds every counter of `o`.
    pub fn merge(&mut self, o: &TraceStats) {
        self.primary_rays += o.primary_rays;
        self.shadow_rays += o.shadow_rays;
        self.reflected_rays += o.reflected_rays;
        self.refracted_rays += o.refracted_rays;
        for (a, b) in self.per_kind.iter_mut().zip(&o.per_kind) {
            a.merge(b);
        }
        self.shadow_skipped_off += o.shadow_skipped_off;
        self.light_below_surface += o.light_below_surface;
        self.shadow_blocked += o.shadow_blocked;
        self.shadow_cache_hits += o.shadow_cache_hits;
        self.secondary_skipped_material += o.secondary_skipped_material;
        self.secondary_skipped_depth += o.secondary_skipped_depth;
        self.secondary_skipped_weight += o.secondary_skipped_weight;
        self.total_internal_reflections += o.total_internal_reflections;
        self.tir_merged += o.tir_merged;
        self.singular_normals += o.singular_normals;
        self.surface_certification.dd_restrictions += o.surface_certification.dd_restrictions;
        self.surface_certification.dd_decided += o.surface_certification.dd_decided;
        self.surface_certification.reduced_precision += o.surface_certification.reduced_precision;
        self.surface_certification.exact_restrictions += o.surface_certification.exact_restrictions;
        self.surface_certification.exact_isolations += o.surface_certification.exact_isolations;
        self.surface_certification.undecided_rays += o.surface_certification.undecided_rays;
        self.roots.merge(&o.roots);
        self.patches.merge(&o.patches);
        self.bvh_node_visits += o.bvh_node_visits;
        if o.bvh.nodes > 0 {
            self.bvh = o.bvh;
        }
        if let Some(b) = o.slowest
            && self.slowest.is_none_or(|a| b.elapsed > a.elapsed)
        {
            self.slowest = Some(b);
        }
    }

    /// All rays traced.
    pub fn total_rays(&self) -> u64 {
        self.primary_rays + self.shadow_rays + self.reflected_rays + self.refracted_rays
    }

    /// Root queries that ended without a certified answer: those `poly` refused (non-finite
    /// coefficients from overflow, or a restriction that vanishes identically because the ray
    /// lies in the surface), and those a heuristic `--isolation` method could not resolve. The
    /// ray then counts as missing that surface. With the certified methods every other query
    /// is certified (an `f64` sign `poly` cannot decide is redone exactly, see
    /// `roots.exact_fallbacks`), so this should be 0.
    pub fn unresolved_roots(&self) -> u64 {
        self.roots.rejected + self.roots.unresolved
    }
}

impl AddAssign<&TraceStats> for TraceStats {
    fn add_assign(&mut self, rhs: &TraceStats) {
        self.merge(rhs);
    }
}

/// The kinds of surface, for statistics.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum SurfaceKind {
    /// [`Sphere`](crate::surface::Sphere).
    Sphere,
    /// [`Plane`](crate::surface::Plane).
    Plane,
    /// [`Polygon`](crate::surface::Polygon) with more than three vertices.
    Polygon,
    /// [`Polygon`](crate::surface::Polygon) with three vertices.
    Triangle,
    /// [`AaBox`](crate::surface::AaBox).
    Box,
    /// [`Superquadric`](crate::surface::Superquadric).
    Superquadric,
    /// [`Torus`](crate::surface::Torus).
    Torus,
    /// [`Algebraic`](crate::surface::Algebraic).
    Algebraic,
    /// [`BezierMesh`](crate::surface::BezierMesh) (one or more Bézier patches).
    BezierPatch,
    /// [`Cone`](crate::surface::Cone) with different end radii.
    Cone,
    /// [`Cone`](crate::surface::Cone) with equal end radii.
    Cylinder,
    /// [`SmoothPolygon`](crate::surface::SmoothPolygon) (NFF's polygonal patch: vertex normals).
    PolygonPatch,
    /// [`TriangleMesh`](crate::surface::TriangleMesh) (an OBJ file's triangles).
    Mesh,
}

impl SurfaceKind {
    /// Number of kinds.
    pub const COUNT: usize = 13;
    /// Every kind, in [`SurfaceKind::index`] order.
    pub const ALL: [SurfaceKind; SurfaceKind::COUNT] = [
        SurfaceKind::Sphere,
        SurfaceKind::Plane,
        SurfaceKind::Polygon,
        SurfaceKind::Triangle,
        SurfaceKind::Box,
        SurfaceKind::Superquadric,
        SurfaceKind::Torus,
        SurfaceKind::Algebraic,
        SurfaceKind::BezierPatch,
        SurfaceKind::Cone,
        SurfaceKind::Cylinder,
        SurfaceKind::PolygonPatch,
        SurfaceKind::Mesh,
    ];

    /// Position in [`SurfaceKind::ALL`] and in per-kind statistics arrays.
    pub fn index(self) -> usize {
        self as usize
    }

    /// The scene-file type name.
    pub fn name(self) -> &'static str {
        match self {
            SurfaceKind::Sphere => "SPHERE",
            SurfaceKind::Plane => "PLANE",
            SurfaceKind::Polygon => "POLYGON",
            SurfaceKind::Triangle => "TRIANGLE",
            SurfaceKind::Box => "BOX",
            SurfaceKind::Superquadric => "SUPERQUADRIC",
            SurfaceKind::Torus => "TORUS",
            SurfaceKind::Algebraic => "ALGEBRAIC",
            SurfaceKind::BezierPatch => "BEZIER_PATCH",
            SurfaceKind::Cone => "CONE",
            SurfaceKind::Cylinder => "CYLINDER",
            SurfaceKind::PolygonPatch => "POLYGON_PATCH",
            SurfaceKind::Mesh => "MESH",
        }
    }
}

/// Wall time of each phase of a render.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct PhaseTimes {
    /// Reading and building the scene.
    pub parse: Duration,
    /// Preparing surfaces (bounds, transforms, polynomials).
    pub setup: Duration,
    /// Tracing all rays.
    pub trace: Duration,
    /// Encoding and writing the image files.
    pub write: Duration,
}

/// The statistics report printed by `render --stats`.
#[derive(Clone, Debug)]
pub struct StatsReport<'a> {
    /// The counters.
    pub stats: &'a TraceStats,
    /// The phase times.
    pub times: PhaseTimes,
    /// Image size.
    pub size: [u32; 2],
    /// Samples per pixel.
    pub samples_per_pixel: u32,
    /// Worker threads.
    pub threads: usize,
    /// The implicit surfaces' root finder.
    pub roots: RootMethods,
}

impl fmt::Display for StatsReport<'_> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let s = self.stats;
        writeln!(
            f,
            "Render statistics: {}x{} pixels, {} samples/pixel, {} threads",
            self.size[0], self.size[1], self.samples_per_pixel, self.threads
        )?;
        writeln!(f, "Rays")?;
        writeln!(f, "  primary              {:>12}", s.primary_rays)?;
        writeln!(f, "  shadow               {:>12}", s.shadow_rays)?;
        writeln!(f, "  reflected            {:>12}", s.reflected_rays)?;
        writeln!(f, "  refracted            {:>12}", s.refracted_rays)?;
        writeln!(f, "  total                {:>12}", s.total_rays())?;
        writeln!(
            f,
            "Intersections        tests         hits  shadow tests   occlusions  bbox rejects"
        )?;
        for kind in SurfaceKind::ALL {
            let k = &s.per_kind[kind.index()];
            if k.tests + k.shadow_tests == 0 {
                continue;
            }
            writeln!(
                f,
                "  {:<17} {:>10} {:>12} {:>13} {:>12} {:>13}",
                kind.name(),
                k.tests,
                k.hits,
                k.shadow_tests,
                k.occlusions,
                k.bbox_rejects
            )?;
        }
        let b = &s.bvh;
        writeln!(
            f,
            "Scene BVH: {} items, {} nodes, depth {}, built in {:.1} ms",
            b.items,
            b.nodes,
            b.depth,
            b.build.as_secs_f64() * 1e3
        )?;
        writeln!(
            f,
            "  node visits per ray               {:>12.2}",
            s.bvh_node_visits as f64 / s.total_rays().max(1) as f64
        )?;
        writeln!(f, "Work skipped")?;
        writeln!(
            f,
            "  shadow rays, Shadows = OFF        {:>12}",
            s.shadow_skipped_off
        )?;
        writeln!(
            f,
            "  lights below the surface (N.L<=0) {:>12}",
            s.light_below_surface
        )?;
        writeln!(
            f,
            "  shadow rays stopped at a blocker  {:>12}",
            s.shadow_blocked
        )?;
        writeln!(
            f,
            "    by the cached blocker           {:>12}",
            s.shadow_cache_hits
        )?;
        writeln!(
            f,
            "  secondary rays, material ks=kt=0  {:>12}",
            s.secondary_skipped_material
        )?;
        writeln!(
            f,
            "  secondary rays, MaxDepth reached  {:>12}",
            s.secondary_skipped_depth
        )?;
        writeln!(
            f,
            "  secondary rays, weight < bailout  {:>12}",
            s.secondary_skipped_weight
        )?;
        writeln!(
            f,
            "  total internal reflections        {:>12}",
            s.total_internal_reflections
        )?;
        writeln!(
            f,
            "    merged with the reflected ray   {:>12}",
            s.tir_merged
        )?;
        writeln!(
            f,
            "  singular points (fallback normal) {:>12}",
            s.singular_normals
        )?;
        let r = &s.roots;
        let isolation = match self.roots.isolation {
            IsolationMethod::Bernstein => "certified Bernstein",
            IsolationMethod::Sturm => "f64 Sturm",
            IsolationMethod::StamSturm => "Stam's 1988 Sturm",
            IsolationMethod::Exact => "exact rational Sturm",
            _ => "other",
        };
        let refine = match self.roots.refine {
            RefineMethod::NewtonBisection => "Newton-bisection",
            RefineMethod::Illinois => "Illinois",
            RefineMethod::Bisection => "bisection",
            _ => "other",
        };
        writeln!(f, "Polynomial root queries              {:>12}", r.queries)?;
        writeln!(f, "  isolation, refinement     {isolation}, {refine}")?;
        for (deg, n) in r.by_degree.iter().enumerate() {
            if *n > 0 {
                let plus = if deg == STATS_DEGREES - 1 { "+" } else { " " };
                writeln!(f, "  degree {deg:>2}{plus}                         {n:>12}")?;
            }
        }
        writeln!(
            f,
            "  with a root in range               {:>12}",
            r.with_root
        )?;
        writeln!(
            f,
            "  closed form (degree 1-2)           {:>12}",
            r.closed_form
        )?;
        writeln!(f, "  guess and verify                   {:>12}", r.guessed)?;
        writeln!(
            f,
            "  exact-rational fallbacks           {:>12}",
            r.exact_fallbacks
        )?;
        writeln!(
            f,
            "  refinement fallbacks               {:>12}",
            r.refine_fallbacks
        )?;
        writeln!(
            f,
            "  limited by the restriction's slack {:>12}",
            r.slack_limited
        )?;
        let c = &s.surface_certification;
        writeln!(
            f,
            "    rays restricted in double-double {:>12}",
            c.dd_restrictions
        )?;
        writeln!(
            f,
            "      decided there                  {:>12}",
            c.dd_decided
        )?;
        writeln!(
            f,
            "      decided at reduced precision   {:>12}",
            c.reduced_precision
        )?;
        writeln!(
            f,
            "    rays restricted exactly          {:>12}",
            c.exact_restrictions
        )?;
        writeln!(
            f,
            "      isolated exactly               {:>12}",
            c.exact_isolations
        )?;
        writeln!(
            f,
            "    undecided rays (high degree)     {:>12}",
            c.undecided_rays
        )?;
        writeln!(
            f,
            "  adaptive-precision pieces          {:>12}",
            r.adaptive_pieces
        )?;
        writeln!(
            f,
            "    re-expanded, decided in f64      {:>12}",
            r.shifted_pieces
        )?;
        writeln!(
            f,
            "      whole ranges at a far cluster  {:>12}",
            r.cluster_shifts
        )?;
        writeln!(
            f,
            "    beyond double-double             {:>12}",
            r.multiprecision_pieces
        )?;
        writeln!(
            f,
            "  refinements finished adaptively    {:>12}",
            r.adaptive_refines
        )?;
        writeln!(
            f,
            "  isolation subdivisions             {:>12}",
            r.subdivisions
        )?;
        writeln!(
            f,
            "  refinement evaluations             {:>12}",
            r.refine_evals
        )?;
        writeln!(
            f,
            "  unresolved roots                   {:>12}",
            s.unresolved_roots()
        )?;
        if s.patches.solves > 0 {
            write!(f, "{}", s.patches)?;
        }
        if let Some(slowest) = &s.slowest {
            write!(f, "{slowest}")?;
        }
        let ms = |d: Duration| d.as_secs_f64() * 1e3;
        let t = &self.times;
        writeln!(f, "Time (ms)")?;
        writeln!(
            f,
            "  parse {:>9.1}   setup {:>9.1}   trace {:>9.1}   write {:>9.1}",
            ms(t.parse),
            ms(t.setup),
            ms(t.trace),
            ms(t.write)
        )?;
        Ok(())
    }
}

//! Surfaces: the [`Surface`] trait and every shape the tracer knows.
//!
//! The object-space contract (STYLE.md §6, after pbrt-v4 `BasicIntersect` /
//! `InteractionFromIntersection`): [`Surface::intersect`] is cheap and returns only `t` and the
//! local point; [`Surface::shading`] runs once, for the accepted hit, and computes the normal,
//! surface parameters and the error bound of the hit point. [`Surface::occluded`] answers
//! shadow queries and may stop early.
//!
//! Every implicit surface (sphere, plane, torus, algebraic surface, and the superquadric's
//! octant pieces) goes through the same path in `implicit.rs` ([`Implicit`]): restrict `F` to the ray, then ask
//! `poly` for the smallest root in range (`paper-notes/implicit-surfaces.md`). No shape owns a
//! solver.

use std::ops::Range;

use glam::{DVec2, DVec3};

use crate::geometry::{Bounds3, Ray};
/// The kinds of surface (defined with the statistics that count per kind).
pub use crate::stats::SurfaceKind;
use crate::workspace::Workspace;

mod aabox;
mod algebraic;
mod bezier_mesh;
mod bezier_patch;
mod cone;
mod implicit;
mod plane;
mod polygon;
mod smooth_polygon;
mod sphere;
mod superquadric;
mod torus;
mod transformed;
mod triangle_mesh;

pub use aabox::AaBox;
pub use algebraic::Algebraic;
pub use bezier_mesh::{
    BezierMesh, DEFAULT_SUBDIVISION, HIT_P_ERR_REL, HIT_RESIDUAL_REL, MAX_SUBDIVISION, PatchHit,
};
pub use bezier_patch::{BezierPatch, POWER_ZERO_REL};
pub use cone::{Cone, ConeSide};
pub use implicit::{
    ENTRY_MARGIN_REL, EXACT_RESTRICTION_MAX_DEGREE, Implicit, ImplicitFn, REDUCED_ROOT_X_TOL_REL,
    ROOT_X_TOL_REL, SINGULAR_P_ERR_REL,
};
pub use plane::Plane;
pub use polygon::Polygon;
pub use smooth_polygon::SmoothPolygon;
pub use sphere::Sphere;
pub use superquadric::{MAX_SUPERQUADRIC_POWER, Superquadric};
pub use torus::Torus;
pub use transformed::Transformed;
pub use triangle_mesh::TriangleMesh;

/// The result of a nearest-hit query: cheap, no normal yet.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Hit {
    /// Ray parameter of the hit (the same in every coordinate system: [`Transformed`] does not
    /// normalise directions).
    pub t: f64,
    /// The hit point in the innermost surface's own coordinates; [`Surface::shading`] maps
    /// what it derives from it to the query ray's coordinates.
    pub local: DVec3,
    /// The surface parameters the intersector solved for, where it solves for them (a Bézier
    /// patch's `(u, v)`, exact roots of the ray/patch system), handed to shading so that they
    /// are not recomputed; `None` for shapes that intersect in `t` alone.
    pub uv: Option<DVec2>,
    /// Shape-specific data for [`Surface::shading`] (box face, superquadric octant, patch
    /// piece…).
    pub tag: u32,
}

/// Geometry at an accepted hit, computed by [`Surface::shading`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SurfaceGeometry {
    /// The hit point (in the coordinates of the query ray).
    pub p: DVec3,
    /// A componentwise bound on `|p − true hit point|`: spawned rays are offset by it
    /// ([`offset_ray_origin`](crate::geometry::offset_ray_origin)).
    pub p_err: DVec3,
    /// The unit geometric normal (not flipped towards the viewer); `None` at a singular point
    /// where `∇F = 0` (Stam §3.6.1), where the integrator falls back to facing the ray.
    pub normal: Option<DVec3>,
    /// Surface parameters where the shape defines them (plane, polygon, triangle and box
    /// faces: coordinates in the face's own basis), used by textures.
    pub uv: Option<DVec2>,
}

/// A shape in its own coordinates.
///
/// The queries take the thread's [`Workspace`] (scratch buffers and counters) in addition to
/// STYLE.md's `intersect(&Ray, Range<f64>)`, so that the hot loop allocates nothing and counts
/// without sharing.
pub trait Surface: Send + Sync + std::fmt::Debug {
    /// Which kind of surface this is (statistics).
    fn kind(&self) -> SurfaceKind;

    /// A box holding the surface, `None` for unbounded surfaces (planes, unbounded algebraic
    /// surfaces).
    fn bounds(&self) -> Option<Bounds3>;

    /// The nearest hit with `t` in `t_range` (open at both ends), if any.
    fn intersect(&self, ray: &Ray, t_range: Range<f64>, ws: &mut Workspace) -> Option<Hit>;

    /// Whether anything blocks the ray within `t_range`; may stop at the first blocker.
    fn occluded(&self, ray: &Ray, t_range: Range<f64>, ws: &mut Workspace) -> bool {
        self.intersect(ray, t_range, ws).is_some()
    }

    /// An interval of `t` holding every hit of `ray` on the surface, `None` when the ray
    /// certainly misses it, found more cheaply than by [`Surface::intersect`]: the nearest-hit
    /// query skips a surface whose interval starts beyond the nearest hit found so far (as it
    /// skips a hierarchy node whose box does) or ends before the query's range, so the answer
    /// stays the one a loop over every surface gives. The whole line (the default) when the
    /// surface has no cheaper bound than its box, which the hierarchy already tests.
    fn hit_interval(&self, _ray: &Ray) -> Option<Range<f64>> {
        Some(f64::NEG_INFINITY..f64::INFINITY)
    }

    /// Normal, surface parameters and error bound at a hit returned by
    /// [`Surface::intersect`] on this surface.
    fn shading(&self, hit: &Hit) -> SurfaceGeometry;

    /// Whether the surface is part of the boundary of a convex body and the normal of
    /// [`Surface::shading`] points out of that body. A ray that starts on such a surface and
    /// leaves it with a positive component along that normal stays in the open half-space
    /// beyond the tangent plane, which the body lies behind, so it never meets the surface
    /// again: the tracer does not test a shadow or reflected ray against the surface it leaves
    /// (`paper-notes/bvh.md` §2). `false` unless the shape proves it.
    fn convex(&self) -> bool {
        false
    }
}

impl<S: Surface + ?Sized> Surface for Box<S> {
    fn kind(&self) -> SurfaceKind {
        (**self).kind()
    }
    fn bounds(&self) -> Option<Bounds3> {
        (**self).bounds()
    }
    fn intersect(&self, ray: &Ray, t_range: Range<f64>, ws: &mut Workspace) -> Option<Hit> {
        (**self).intersect(ray, t_range, ws)
    }
    fn occluded(&self, ray: &Ray, t_range: Range<f64>, ws: &mut Workspace) -> bool {
        (**self).occluded(ray, t_range, ws)
    }
    fn hit_interval(&self, ray: &Ray) -> Option<Range<f64>> {
        (**self).hit_interval(ray)
    }
    fn shading(&self, hit: &Hit) -> SurfaceGeometry {
        (**self).shading(hit)
    }
    fn convex(&self) -> bool {
        (**self).convex()
    }
}

/// Test support for [`Surface::convex`]: draws a direction `d` in `[−1, 1]³` and, when it
/// leaves along the outward normal `n` (`n·d > 0`), asserts that the ray from `origin` (just
/// outside the surface) along `d` never meets `surface`. True when a ray was tested.
#[cfg(test)]
pub(crate) fn leaving_ray_misses(
    surface: &dyn Surface,
    origin: DVec3,
    n: DVec3,
    rng: &mut impl rand::Rng,
    ws: &mut Workspace,
) -> bool {
    let d = DVec3::new(
        rng.gen_range(-1.0..1.0),
        rng.gen_range(-1.0..1.0),
        rng.gen_range(-1.0..1.0),
    );
    if n.dot(d) <= 0.0 {
        return false;
    }
    assert!(
        !surface.occluded(&Ray::new(origin, d), 0.0..f64::INFINITY, ws),
        "a ray leaving {surface:?} from {origin} along {d} (normal {n}) meets it"
    );
    true
}

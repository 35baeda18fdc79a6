//! [`Plane`]: `F = n·(p − origin)` (Stam §3.1.1).
//!
//! Scene syntax:
//! ```text
//! #object
//! Type = PLANE
//! Origin = (0,0,-1.5)
//! Normal = (0,0,1)
//! ```

use glam::{DVec2, DVec3};

use super::SurfaceKind;
use super::implicit::ImplicitFn;
use crate::geometry::Bounds3;
use crate::trivariate::{Poly3, RestrictScratch};

/// A two-sided plane, traced through the shared implicit path (degree 1).
#[derive(Clone, Debug)]
pub struct Plane {
    origin: DVec3,
    normal: DVec3,
    u_axis: DVec3,
    v_axis: DVec3,
    poly: Poly3,
    kind: SurfaceKind,
}

impl Plane {
    /// The plane through `origin` with normal `normal` (non-zero and finite, of any length:
    /// normalised here by [`crate::geometry::unit`]; the zero vector leaves NaN coefficients, a
    /// plane no ray hits, and [`crate::scene::ShapeKind::validate`] refuses it first).
    pub fn new(origin: DVec3, normal: DVec3) -> Self {
        Self::with_kind(origin, normal, SurfaceKind::Plane)
    }

    /// The same, reported under another kind (polygons and triangles use a plane).
    pub(crate) fn with_kind(origin: DVec3, normal: DVec3, kind: SurfaceKind) -> Self {
        let n = crate::geometry::unit(normal).unwrap_or(DVec3::NAN);
        // Texture axes: Stam's textured plane is parallel to z = 0 and indexes the texture by
        // x and y (Annexe B `ColTexture`); other planes get any orthonormal pair.
        let (u_axis, v_axis) = if n.x == 0.0 && n.y == 0.0 {
            (DVec3::X, DVec3::Y)
        } else {
            n.any_orthonormal_pair()
        };
        let poly = Poly3::from_terms([
            (n.x, [1, 0, 0]),
            (n.y, [0, 1, 0]),
            (n.z, [0, 0, 1]),
            (-n.dot(origin), [0, 0, 0]),
        ]);
        Plane {
            origin,
            normal: n,
            u_axis,
            v_axis,
            poly,
            kind,
        }
    }

    /// The unit normal.
    pub fn normal(&self) -> DVec3 {
        self.normal
    }

    /// A point of the plane.
    pub fn origin(&self) -> DVec3 {
        self.origin
    }

    /// The plane restricted to the line `o + t·d`: `[c0, c1]` with `F = c0 + c1·t`,
    /// `c0 = n·(o − origin)`, `c1 = n·d` (lowest coefficient first).
    pub fn restricted(&self, o: DVec3, d: DVec3) -> [f64; 2] {
        [self.normal.dot(o - self.origin), self.normal.dot(d)]
    }
}

impl ImplicitFn for Plane {
    fn kind(&self) -> SurfaceKind {
        self.kind
    }

    fn poly(&self) -> &Poly3 {
        &self.poly
    }

    /// `n·(o − origin) + (n·d)·t`.
    fn restrict(&self, o: DVec3, d: DVec3, _: &mut RestrictScratch, out: &mut Vec<f64>) {
        out.clear();
        out.extend_from_slice(&self.restricted(o, d));
    }

    fn bounds(&self) -> Option<Bounds3> {
        None
    }

    fn uv(&self, p: DVec3) -> Option<DVec2> {
        let v = p - self.origin;
        Some(DVec2::new(v.dot(self.u_axis), v.dot(self.v_axis)))
    }
}

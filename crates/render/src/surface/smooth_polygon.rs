//! [`SmoothPolygon`]: a planar polygon with a normal at each vertex (NFF's `pp`, "polygonal
//! patch"), hit as its [`Polygon`] and shaded with the vertex normals interpolated across it
//! (Phong shading; Gouraud's interpolation applied to normals).
//!
//! The polygon is cut into the fan of triangles `(v₀, vᵢ, vᵢ₊₁)`; at a hit, the barycentric
//! coordinates of the triangle holding it weight its three vertex normals. The geometric
//! normal still decides which side the ray came from (the integrator flips the shading normal
//! with it), so an interpolated normal never turns a surface inside out. See
//! `paper-notes/nff.md` §4.

use std::ops::Range;

use glam::DVec3;

use super::{Hit, Polygon, Surface, SurfaceGeometry, SurfaceKind};
use crate::geometry::{Bounds3, Ray, unit};
use crate::workspace::Workspace;

/// A polygon with per-vertex normals.
#[derive(Debug)]
pub struct SmoothPolygon {
    polygon: Polygon,
    vertices: Vec<DVec3>,
    /// Unit vertex normals, oriented to the polygon's side.
    normals: Vec<DVec3>,
}

impl SmoothPolygon {
    /// The polygon through `vertices` with vertex normals `normals` (same length, non-zero).
    /// `None` when the polygon is degenerate, the lengths differ or a normal is zero.
    pub fn new(vertices: &[DVec3], normals: &[DVec3]) -> Option<Self> {
        if vertices.len() != normals.len() {
            return None;
        }
        let polygon = Polygon::new(vertices)?;
        let normals = normals
            .iter()
            .map(|&n| unit(n))
            .collect::<Option<Vec<_>>>()?;
        Some(SmoothPolygon {
            polygon,
            vertices: vertices.to_vec(),
            normals,
        })
    }

    /// The interpolated unit normal at `p` (a point of the polygon's plane).
    fn normal_at(&self, p: DVec3, face: DVec3) -> Option<DVec3> {
        // The fan triangle whose barycentric coordinates are least negative holds `p` (all
        // three ≥ 0 inside; rounding may leave a point on a shared edge slightly outside both).
        let v0 = self.vertices[0];
        let mut best: Option<(f64, DVec3)> = None;
        for i in 1..self.vertices.len() - 1 {
            let (a, b) = (self.vertices[i], self.vertices[i + 1]);
            let area = (a - v0).cross(b - v0).dot(face);
            if area == 0.0 {
                continue;
            }
            let w1 = (p - v0).cross(b - v0).dot(face) / area;
            let w2 = (a - v0).cross(p - v0).dot(face) / area;
            let w0 = 1.0 - w1 - w2;
            let worst = w0.min(w1).min(w2);
            if best.is_none_or(|(w, _)| worst > w) {
                let n = self.normals[0] * w0 + self.normals[i] * w1 + self.normals[i + 1] * w2;
                best = Some((worst, n));
            }
        }
        best.and_then(|(_, n)| {
            let u = n.normalize();
            u.is_finite().then_some(u)
        })
    }
}

impl Surface for SmoothPolygon {
    fn kind(&self) -> SurfaceKind {
        SurfaceKind::PolygonPatch
    }

    fn bounds(&self) -> Option<Bounds3> {
        self.polygon.bounds()
    }

    fn intersect(&self, ray: &Ray, t_range: Range<f64>, ws: &mut Workspace) -> Option<Hit> {
        self.polygon.intersect(ray, t_range, ws)
    }

    fn shading(&self, hit: &Hit) -> SurfaceGeometry {
        let mut g = self.polygon.shading(hit);
        if let Some(face) = g.normal {
            let n = self.normal_at(g.p, face).unwrap_or(face);
            // Keep the shading normal on the face normal's side, so the integrator's
            // inside/outside decision (by the sign of N·V) stays the geometric one.
            g.normal = Some(if n.dot(face) < 0.0 { -n } else { n });
        }
        g
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn normals_are_interpolated_across_the_fan() {
        // A unit square in z = 0 whose corner normals lean outwards.
        let v = [
            DVec3::new(0.0, 0.0, 0.0),
            DVec3::new(1.0, 0.0, 0.0),
            DVec3::new(1.0, 1.0, 0.0),
            DVec3::new(0.0, 1.0, 0.0),
        ];
        let n = v.map(|p| DVec3::new(p.x - 0.5, p.y - 0.5, 1.0));
        let s = SmoothPolygon::new(&v, &n).expect("valid");
        let mut ws = Workspace::new();
        let centre = Ray::new(DVec3::new(0.5, 0.5, 3.0), DVec3::NEG_Z);
        let h = s
            .intersect(&centre, 0.0..f64::INFINITY, &mut ws)
            .expect("hit");
        let g = s.shading(&h);
        assert!(
            (g.normal.unwrap() - DVec3::Z).length() < 1e-12,
            "centre: straight up"
        );
        let corner = Ray::new(DVec3::new(0.999, 0.999, 3.0), DVec3::NEG_Z);
        let h = s
            .intersect(&corner, 0.0..f64::INFINITY, &mut ws)
            .expect("hit");
        let nn = s.shading(&h).normal.unwrap();
        let expected = DVec3::new(0.5, 0.5, 1.0).normalize();
        assert!((nn - expected).length() < 1e-2, "near the corner: {nn}");
        assert!(
            SmoothPolygon::new(&v, &n[..3]).is_none(),
            "lengths must agree"
        );
    }
}

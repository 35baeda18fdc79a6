//! [`Cone`]: a truncated cone or a cylinder (NFF's `c` entity), the quadric
//! `F = x² + y² − (r₀ + k·z)²`, `k = (r₁ − r₀)/h`, about the `z` axis between `z = 0` (base,
//! radius `r₀`) and `z = h` (apex, radius `r₁`), with optional flat end caps.
//!
//! The side goes through the shared implicit path: restricted to the ray it is a quadratic,
//! solved by `poly` (closed form) over the part of the ray inside the box
//! `[−R, R]² × [0, h]`, `R = max(r₀, r₁)` — the quadric's two roots clipped to the segment.
//! Inside that box only one nappe of the double cone exists (its vertex `z = −r₀/k` lies
//! outside `(0, h)` when both radii are ≥ 0), so the box is the exact clip. Caps are disks in
//! the planes `z = 0` and `z = h`, each traced as a plane clipped to the disk.
//!
//! Placed by a rigid frame taking `z` to the base → apex direction (as the torus is).
//!
//! Scene syntax (`CYLINDER` takes `Radius` for both ends):
//! ```text
//! #object
//! Type = CONE
//! Base = (0,0,0)   BaseRadius = 1
//! Apex = (0,0,2)   ApexRadius = 0.5
//! Caps = ON        // default OFF: open ends, as NFF's cones
//! ```
//! See `paper-notes/cones.md`.

use std::ops::Range;

use glam::DVec3;

use super::implicit::{Implicit, ImplicitFn};
use super::{Hit, Plane, Surface, SurfaceGeometry, SurfaceKind};
use crate::geometry::{Bounds3, Ray};
use crate::methods::RootMethods;
use crate::trivariate::{Poly3, RestrictScratch};
use crate::workspace::Workspace;

/// The side of a canonical cone: `x² + y² − (r₀ + k·z)²`.
#[derive(Clone, Debug)]
pub struct ConeSide {
    r0: f64,
    k: f64,
    height: f64,
    poly: Poly3,
    kind: SurfaceKind,
}

impl ConeSide {
    /// The side between `z = 0` (radius `r0`) and `z = height` (radius `r1`); radii ≥ 0, not
    /// both 0, `height > 0`.
    pub fn new(r0: f64, r1: f64, height: f64) -> Self {
        let k = (r1 - r0) / height;
        let poly = Poly3::from_terms([
            (1.0, [2, 0, 0]),
            (1.0, [0, 2, 0]),
            (-k * k, [0, 0, 2]),
            (-2.0 * r0 * k, [0, 0, 1]),
            (-r0 * r0, [0, 0, 0]),
        ]);
        let kind = if r0 == r1 {
            SurfaceKind::Cylinder
        } else {
            SurfaceKind::Cone
        };
        ConeSide {
            r0,
            k,
            height,
            poly,
            kind,
        }
    }
}

impl ImplicitFn for ConeSide {
    fn kind(&self) -> SurfaceKind {
        self.kind
    }

    fn poly(&self) -> &Poly3 {
        &self.poly
    }

    /// With `ρ(t) = r₀ + k(o_z + t d_z)`: `F(o + td) = (d_x² + d_y² − k²d_z²)t²
    /// + 2(o_x d_x + o_y d_y − k d_z ρ(0))t + o_x² + o_y² − ρ(0)²`.
    fn restrict(&self, o: DVec3, d: DVec3, _: &mut RestrictScratch, out: &mut Vec<f64>) {
        let rho = self.r0 + self.k * o.z;
        let kd = self.k * d.z;
        out.clear();
        out.extend_from_slice(&[
            o.x * o.x + o.y * o.y - rho * rho,
            2.0 * (o.x * d.x + o.y * d.y - kd * rho),
            d.x * d.x + d.y * d.y - kd * kd,
        ]);
    }

    fn bounds(&self) -> Option<Bounds3> {
        let r = self.r0.max(self.r0 + self.k * self.height);
        Some(Bounds3::new(
            DVec3::new(-r, -r, 0.0),
            DVec3::new(r, r, self.height),
        ))
    }
}

/// A flat end cap: the plane `z = z0` inside the disk of radius `radius`.
#[derive(Debug)]
struct Cap {
    plane: Implicit<Plane>,
    radius: f64,
}

impl Cap {
    fn new(z0: f64, radius: f64, kind: SurfaceKind) -> Self {
        let c = DVec3::new(0.0, 0.0, z0);
        let r = DVec3::new(radius, radius, 0.0);
        let plane = Plane::with_kind(c, DVec3::Z, kind);
        Cap {
            plane: Implicit::new(plane, Some(Bounds3::new(c - r, c + r))),
            radius,
        }
    }

    fn with_root_methods(self, roots: RootMethods) -> Self {
        Cap {
            plane: self.plane.with_root_methods(roots),
            radius: self.radius,
        }
    }

    fn hit(&self, ray: &Ray, range: Range<f64>, ws: &mut Workspace) -> Option<(f64, DVec3)> {
        let (t, p) = self.plane.nearest(ray, range, ws, false)?;
        (p.x * p.x + p.y * p.y <= self.radius * self.radius).then_some((t, p))
    }
}

/// A cone or cylinder with optional caps, in its canonical frame.
#[derive(Debug)]
pub struct Cone {
    side: Implicit<ConeSide>,
    /// Base cap (`z = 0`) and apex cap (`z = h`), when closed; a zero-radius end has none.
    caps: Vec<Cap>,
    bounds: Bounds3,
}

/// [`Hit::tag`] of a hit on the side; caps are `1 + index`.
const SIDE_TAG: u32 = 0;

impl Cone {
    /// The cone between `z = 0` (radius `r0`) and `z = height` (radius `r1`), closed by
    /// flat caps when `caps`.
    pub fn new(r0: f64, r1: f64, height: f64, caps: bool) -> Self {
        let f = ConeSide::new(r0, r1, height);
        let kind = f.kind;
        let side = Implicit::new(f, None);
        let mut list = Vec::new();
        if caps {
            for (z, r) in [(0.0, r0), (height, r1)] {
                if r > 0.0 {
                    list.push(Cap::new(z, r, kind));
                }
            }
        }
        let bounds = side
            .bounds()
            .unwrap_or(Bounds3::new(DVec3::ZERO, DVec3::ZERO));
        Cone {
            side,
            caps: list,
            bounds,
        }
    }

    /// The same cone solving its side and caps with `roots` (`render --isolation/--refine`),
    /// as every implicit surface does.
    pub fn with_root_methods(self, roots: RootMethods) -> Self {
        Cone {
            side: self.side.with_root_methods(roots),
            caps: self
                .caps
                .into_iter()
                .map(|c| c.with_root_methods(roots))
                .collect(),
            bounds: self.bounds,
        }
    }
}

impl Surface for Cone {
    fn kind(&self) -> SurfaceKind {
        self.side.kind()
    }

    fn bounds(&self) -> Option<Bounds3> {
        Some(self.bounds)
    }

    fn intersect(&self, ray: &Ray, t_range: Range<f64>, ws: &mut Workspace) -> Option<Hit> {
        let mut best = self
            .side
            .nearest(ray, t_range.clone(), ws, false)
            .map(|(t, p)| (t, p, SIDE_TAG));
        for (i, cap) in self.caps.iter().enumerate() {
            let end = best.map_or(t_range.end, |b| b.0);
            if let Some((t, p)) = cap.hit(ray, t_range.start..end, ws) {
                best = Some((t, p, 1 + i as u32));
            }
        }
        best.map(|(t, p, tag)| Hit {
            t,
            local: p,
            uv: None,
            tag,
        })
    }

    fn occluded(&self, ray: &Ray, t_range: Range<f64>, ws: &mut Workspace) -> bool {
        self.side.nearest(ray, t_range.clone(), ws, true).is_some()
            || self
                .caps
                .iter()
                .any(|c| c.hit(ray, t_range.clone(), ws).is_some())
    }

    fn shading(&self, hit: &Hit) -> SurfaceGeometry {
        match hit.tag {
            SIDE_TAG => self.side.shading(hit),
            i => self.caps[(i - 1) as usize].plane.shading(hit),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn restriction_matches_the_expanded_polynomial() {
        let f = ConeSide::new(1.0, 0.25, 3.0);
        let (o, d) = (DVec3::new(0.5, -7.0, 4.0), DVec3::new(-0.05, 0.8, -0.5));
        let mut out = Vec::new();
        f.restrict(o, d, &mut RestrictScratch::default(), &mut out);
        let generic = f.poly().restrict_to_line(o, d);
        for (m, (a, b)) in out.iter().zip(generic.coeffs()).enumerate() {
            assert!((a - b).abs() <= 1e-12 * (1.0 + b.abs()), "c{m}: {a} vs {b}");
        }
    }

    #[test]
    fn side_is_clipped_to_the_segment_and_caps_close_it() {
        let mut ws = Workspace::new();
        // A cylinder of radius 1 from z = 0 to z = 2; a ray along x at z = 1 hits x = −1.
        let open = Cone::new(1.0, 1.0, 2.0, false);
        let ray = Ray::new(DVec3::new(-5.0, 0.0, 1.0), DVec3::X);
        let h = open
            .intersect(&ray, 0.0..f64::INFINITY, &mut ws)
            .expect("side");
        assert!((h.t - 4.0).abs() < 1e-12, "t = {}", h.t);
        // Above the segment (z = 3): the infinite cylinder is there, the clipped one is not.
        let above = Ray::new(DVec3::new(-5.0, 0.0, 3.0), DVec3::X);
        assert!(
            open.intersect(&above, 0.0..f64::INFINITY, &mut ws)
                .is_none()
        );
        // Down the axis: open ends let the ray through, caps stop it at z = 2.
        let down = Ray::new(DVec3::new(0.0, 0.0, 5.0), DVec3::NEG_Z);
        assert!(open.intersect(&down, 0.0..f64::INFINITY, &mut ws).is_none());
        let closed = Cone::new(1.0, 1.0, 2.0, true);
        let h = closed
            .intersect(&down, 0.0..f64::INFINITY, &mut ws)
            .expect("apex cap");
        assert!((h.t - 3.0).abs() < 1e-12 && h.tag == 2, "{h:?}");
        let n = closed.shading(&h).normal.expect("cap normal");
        assert!((n.z.abs() - 1.0).abs() < 1e-15, "cap normal along z: {n}");
        // A cone to a point: at z = 1 of a cone from r = 1 (z = 0) to r = 0 (z = 2) the
        // radius is 1/2; the normal leans up by atan(1/2).
        let cone = Cone::new(1.0, 0.0, 2.0, false);
        let h = cone
            .intersect(&ray, 0.0..f64::INFINITY, &mut ws)
            .expect("cone");
        assert!((h.t - 4.5).abs() < 1e-12, "t = {}", h.t);
        let n = cone.shading(&h).normal.expect("side normal");
        let expected = DVec3::new(-2.0, 0.0, 1.0).normalize();
        assert!(
            (n - expected).length() < 1e-12 || (n + expected).length() < 1e-12,
            "{n}"
        );
    }
}

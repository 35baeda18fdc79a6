//! [`Sphere`]: `F = |p − c|² − r²` (Stam eq. 2.2).
//!
//! Scene syntax:
//! ```text
//! #object
//! Type = SPHERE
//! Center = (0,0,1)
//! Radius = 1          // or Stam's  Radius^2 = 1
//! ```

use glam::DVec3;

use super::SurfaceKind;
use super::implicit::ImplicitFn;
use crate::geometry::Bounds3;
use crate::trivariate::{Poly3, RestrictScratch};

/// A sphere, traced through the shared implicit path.
#[derive(Clone, Debug)]
pub struct Sphere {
    center: DVec3,
    radius: f64,
    poly: Poly3,
}

impl Sphere {
    /// The sphere of radius `radius` (positive, finite) about `center`.
    pub fn new(center: DVec3, radius: f64) -> Self {
        let c = center;
        let poly = Poly3::from_terms([
            (1.0, [2, 0, 0]),
            (1.0, [0, 2, 0]),
            (1.0, [0, 0, 2]),
            (-2.0 * c.x, [1, 0, 0]),
            (-2.0 * c.y, [0, 1, 0]),
            (-2.0 * c.z, [0, 0, 1]),
            (c.length_squared() - radius * radius, [0, 0, 0]),
        ]);
        Sphere {
            center,
            radius,
            poly,
        }
    }
}

impl ImplicitFn for Sphere {
    fn kind(&self) -> SurfaceKind {
        SurfaceKind::Sphere
    }

    fn poly(&self) -> &Poly3 {
        &self.poly
    }

    /// `|d|²t² + 2d·(o − c)t + |o − c|² − r²` (Stam eq. 2.4).
    fn restrict(&self, o: DVec3, d: DVec3, _: &mut RestrictScratch, out: &mut Vec<f64>) {
        let oc = o - self.center;
        out.clear();
        out.extend_from_slice(&[
            oc.length_squared() - self.radius * self.radius,
            2.0 * d.dot(oc),
            d.length_squared(),
        ]);
    }

    fn bounds(&self) -> Option<Bounds3> {
        let r = DVec3::splat(self.radius);
        Some(Bounds3::new(self.center - r, self.center + r))
    }
}

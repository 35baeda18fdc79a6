//! [`Torus`]: the quartic `(|p|² + R² − r²)² − 4R²(x² + y²)` about the `z` axis.
//!
//! Scene syntax (the centre and axis are applied by a [`Transformed`](super::Transformed)
//! frame, so the shape itself is canonical):
//! ```text
//! #object
//! Type = TORUS
//! Center = (0,0,0)
//! Axis = (0,0,1)
//! MajorRadius = 2
//! MinorRadius = 1
//! ```
//! See `paper-notes/implicit-surfaces.md` §3 for the restriction's coefficients.

use glam::DVec3;

use super::SurfaceKind;
use super::implicit::ImplicitFn;
use crate::geometry::Bounds3;
use crate::poly3::{Poly3, RestrictScratch};

/// A torus centred at the origin with axis `z`, traced through the shared implicit path as
/// its quartic.
#[derive(Clone, Debug)]
pub struct Torus {
    major: f64,
    minor: f64,
    poly: Poly3,
}

impl Torus {
    /// The torus with centre-circle radius `major` and tube radius `minor` (both positive).
    pub fn new(major: f64, minor: f64) -> Self {
        let k = major * major - minor * minor;
        let m = 4.0 * major * major;
        // (x² + y² + z² + k)² − m(x² + y²), expanded.
        let poly = Poly3::from_terms([
            (1.0, [4, 0, 0]),
            (1.0, [0, 4, 0]),
            (1.0, [0, 0, 4]),
            (2.0, [2, 2, 0]),
            (2.0, [2, 0, 2]),
            (2.0, [0, 2, 2]),
            (2.0 * k - m, [2, 0, 0]),
            (2.0 * k - m, [0, 2, 0]),
            (2.0 * k, [0, 0, 2]),
            (k * k, [0, 0, 0]),
        ]);
        Torus { major, minor, poly }
    }

    /// The major radius `R`.
    pub fn major(&self) -> f64 {
        self.major
    }

    /// The minor radius `r`.
    pub fn minor(&self) -> f64 {
        self.minor
    }
}

impl ImplicitFn for Torus {
    fn kind(&self) -> SurfaceKind {
        SurfaceKind::Torus
    }

    fn poly(&self) -> &Poly3 {
        &self.poly
    }

    /// With `a = d·d`, `b = 2o·d`, `c = o·o + R² − r²`, `F(o + td) = (at² + bt + c)² −
    /// 4R²((o_x + t d_x)² + (o_y + t d_y)²)`, whose coefficients are written out below.
    fn restrict(&self, o: DVec3, d: DVec3, _: &mut RestrictScratch, out: &mut Vec<f64>) {
        let r2 = self.major * self.major;
        let a = d.length_squared();
        let b = 2.0 * o.dot(d);
        let c = o.length_squared() + r2 - self.minor * self.minor;
        let m = 4.0 * r2;
        out.clear();
        out.extend_from_slice(&[
            c * c - m * (o.x * o.x + o.y * o.y),
            2.0 * b * c - 2.0 * m * (o.x * d.x + o.y * d.y),
            b * b + 2.0 * a * c - m * (d.x * d.x + d.y * d.y),
            2.0 * a * b,
            a * a,
        ]);
    }

    fn bounding_sphere(&self) -> Option<(DVec3, f64)> {
        Some((DVec3::ZERO, self.major + self.minor))
    }

    fn bounds(&self) -> Option<Bounds3> {
        let e = self.major + self.minor;
        Some(Bounds3::new(
            DVec3::new(-e, -e, -self.minor),
            DVec3::new(e, e, self.minor),
        ))
    }
}

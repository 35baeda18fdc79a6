//! [`Algebraic`]: the surface `F(x, y, z) = 0` for any polynomial `F` (Stam eq. 3.1–3.2).
//!
//! Scene syntax (the equation is parsed, not hard-coded as in Stam's `ray2.c`):
//! ```text
//! #object
//! Type = ALGEBRAIC_SURFACE
//! Let phi = (1+sqrt(5))/2
//! Equation = (x^2+y^2-1)*(x^2+y^2-9) + 15*z^2
//! Bounding volume = BOX [-3.2,3.2]x[-3.2,3.2]x[-1,1]
//! ```

use glam::DVec3;

use super::SurfaceKind;
use super::implicit::ImplicitFn;
use crate::geometry::Bounds3;
use crate::trivariate::{Poly3, RestrictScratch};

/// A general algebraic surface. Its bounds come from the scene's `Bounding volume`; without
/// one it is unbounded and the search range is cut by a root bound of each restriction.
#[derive(Clone, Debug)]
pub struct Algebraic {
    poly: Poly3,
}

impl Algebraic {
    /// The surface `poly = 0` (degree ≥ 1, finite coefficients).
    pub fn new(poly: Poly3) -> Self {
        Algebraic { poly }
    }
}

impl ImplicitFn for Algebraic {
    fn kind(&self) -> SurfaceKind {
        SurfaceKind::Algebraic
    }

    fn poly(&self) -> &Poly3 {
        &self.poly
    }

    fn restrict(&self, o: DVec3, d: DVec3, scratch: &mut RestrictScratch, out: &mut Vec<f64>) {
        self.poly.restrict_into(o, d, scratch, out);
    }

    fn bounds(&self) -> Option<Bounds3> {
        None
    }
}

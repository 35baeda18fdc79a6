//! A Whitted ray tracer for exact algebraic surfaces: spheres, planes, polygons, boxes,
//! superquadrics, tori and algebraic surfaces `F(x, y, z) = 0` of any degree, read from Stam's
//! scene command files.

mod poly3;
pub mod scene;

pub use crate::poly3::{Poly3, RestrictScratch, Term3};
pub use crate::scene::Scene;

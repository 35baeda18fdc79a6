//! Test oracles shared by the integration tests (`tests/`) and the measurements
//! (`benches/`), so that neither depends on the other.
//!
//! * [`families`]: the test polynomials (Wilkinson, Chebyshev, Legendre, planted rational roots,
//!   Kac, Mignotte-like clusters, multiple roots) and [`rays`]: real ray polynomials (torus and
//!   Barth's sextic restricted to camera rays).
//! * [`truth`]: certified roots of the polynomial *as stored*. Every `f64` coefficient is a
//!   dyadic rational, so exact rational Sturm isolation refined to width 2^-80 is the truth.
//! * [`methods`]: every solver compared — Stam's 1988 `f64` Sturm, our `f64` Sturm, the
//!   certified Bernstein/Descartes path with each refinement, exact rational Sturm, and a
//!   companion-matrix eigenvalue baseline (`nalgebra`).
//! * [`score`]: missed and phantom roots and errors against the truth.
#![cfg_attr(not(test), warn(unused_crate_dependencies))]

pub mod families;
pub mod methods;
pub mod rays;
pub mod score;
pub mod truth;

//! Measurements of `poly`'s root finders: the numerical-stability suite by degree, run time
//! against error, and the inputs the criterion benches share.
//!
//! * [`families`]: the test polynomials (Wilkinson, Chebyshev, Legendre, planted rational roots,
//!   Kac, Mignotte-like clusters, multiple roots) and [`rays`]: real ray polynomials (torus and
//!   Barth's sextic restricted to camera rays).
//! * [`truth`]: certified roots of the polynomial *as stored*. Every `f64` coefficient is a
//!   dyadic rational, so exact rational Sturm isolation refined to width 2^-80 is the truth.
//! * [`methods`]: every solver compared — Stam's 1988 `f64` Sturm, our `f64` Sturm, the
//!   certified Bernstein/Descartes path with each refinement, exact rational Sturm, and a
//!   companion-matrix eigenvalue baseline (`nalgebra`).
//! * [`score`]: missed and phantom roots and errors against the truth; [`image`]: pixel-level
//!   comparison of solver settings against an exact reference; [`timing`];
//!   [`report`] (Markdown) and [`plot`] (SVG).
//!
//! The binaries `stability` and `speed` write `docs/stability.md` and `docs/speed.md`.

pub mod families;
pub mod image;
pub mod methods;
pub mod plot;
pub mod rays;
pub mod report;
pub mod score;
pub mod timing;
pub mod truth;

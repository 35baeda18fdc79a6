//! Measurements of `poly`'s root finders: the numerical-stability suite by degree, run time
//! against error, and the inputs the criterion benches share.
//!
//! * [`families`], [`rays`], [`truth`], [`methods`], [`score`]: the test oracles, which live in
//!   the `test-support` crate (shared with `tests/`) and are re-exported here.
//! * [`image`]: pixel-level comparison of solver settings against an exact reference;
//!   [`timing`]; [`report`] (Markdown) and [`plot`] (SVG).
//!
//! The binaries `stability` and `speed` write `docs/stability.md` and `docs/speed.md`.

pub mod image;
pub mod plot;
pub mod report;
pub mod timing;

pub use test_support::{families, methods, rays, score, truth};

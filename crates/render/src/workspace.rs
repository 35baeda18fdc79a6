//! [`Workspace`]: per-thread scratch buffers and counters for the hot loop.

use crate::stats::TraceStats;
use crate::trivariate::RestrictScratch;
use poly::Dd;

/// Per-thread state of the tracer: the buffer that receives the restricted polynomial
/// `F(o + t·d)`, scratch for [`Poly3::restrict_into`](crate::Poly3::restrict_into), and the
/// statistics. One per worker, so tracing neither allocates per ray nor shares counters.
#[derive(Debug, Default)]
pub struct Workspace {
    /// Coefficients of the current restricted polynomial, low → high.
    pub(crate) coeffs: Vec<f64>,
    /// Roots of one half of an unbounded surface's split query (`surface/implicit.rs`).
    pub(crate) roots: Vec<f64>,
    /// Scratch for the trivariate restriction.
    pub(crate) restrict: RestrictScratch,
    /// The same for the double-double restriction of a ray the `f64` one cannot decide, and
    /// its coefficients.
    pub(crate) restrict_dd: RestrictScratch<Dd>,
    pub(crate) coeffs_dd: Vec<Dd>,
    /// Buffers of the Bézier patches' per-ray algebra (`groebner::solve_ray_patch`).
    pub(crate) solver: groebner::SolveWorkspace,
    /// Per light, the primitive that blocked this thread's last blocked shadow ray towards it
    /// (`NO_BLOCKER` for none yet): the shadow cache of `whitted::occluded_towards`.
    pub(crate) shadow_blockers: Vec<u32>,
    /// Bypasses the shadow cache (every shadow ray traverses the BVH): for the tests that
    /// check the cache changes no verdict and no pixel.
    #[cfg(test)]
    pub(crate) shadow_cache_off: bool,
    /// Tests a shadow or reflected ray against the convex surface it leaves too: for the tests
    /// that check skipping that surface changes no verdict and no pixel.
    #[cfg(test)]
    pub(crate) test_the_surface_left: bool,
    /// Counters.
    pub stats: TraceStats,
}

impl Workspace {
    /// A fresh workspace with zeroed counters.
    pub fn new() -> Self {
        Workspace::default()
    }
}

//! [`Workspace`]: per-thread scratch buffers and counters for the hot loop.

use poly::{IsolationMethod, RefineMethod};

use crate::poly3::RestrictScratch;
use crate::stats::TraceStats;

/// How implicit surfaces (torus, algebraic surfaces, superquadrics) find the smallest root of
/// their ray polynomial: `poly`'s isolation and refinement methods (`render --isolation`,
/// `--refine`). The default is the certified Bernstein isolation with Newton–bisection; the
/// others are there to compare solvers on whole images (`docs/speed.md`). Bézier patches have
/// their own choice ([`PatchMethod`](crate::surface::PatchMethod)).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct RootMethods {
    /// How roots are isolated.
    pub isolation: IsolationMethod,
    /// How an isolated root is refined.
    pub refine: RefineMethod,
}

/// Per-thread state of the tracer: the buffer that receives the restricted polynomial
/// `F(o + t·d)`, scratch for [`Poly3::restrict_into`](crate::Poly3::restrict_into), and the
/// statistics. One per worker, so tracing neither allocates per ray nor shares counters.
#[derive(Debug, Default)]
pub struct Workspace {
    /// Coefficients of the current restricted polynomial, low → high.
    pub(crate) coeffs: Vec<f64>,
    /// Scratch for the trivariate restriction.
    pub(crate) restrict: RestrictScratch,
    /// The root finder's methods.
    pub(crate) roots: RootMethods,
    /// Buffers of the Bézier patches' per-ray algebra (`groebner::solve_ray_patch`).
    pub(crate) solver: groebner::SolveWorkspace,
    /// Counters.
    pub stats: TraceStats,
}

impl Workspace {
    /// A fresh workspace with zeroed counters and the default root finder.
    pub fn new() -> Self {
        Workspace::default()
    }

    /// A fresh workspace whose implicit surfaces use `roots`.
    pub fn with_roots(roots: RootMethods) -> Self {
        Workspace {
            roots,
            ..Workspace::default()
        }
    }
}

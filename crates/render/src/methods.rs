//! How the tracer solves: the one home of the solver choices, read once per render when the
//! prepared scene builds its surfaces (each surface keeps what it needs; the per-thread
//! [`Workspace`](crate::Workspace) holds scratch only).
//!
//! - Implicit surfaces (sphere, plane, torus, algebraic surfaces, superquadrics) find the
//!   smallest root of their ray polynomial with `poly`: [`RootMethods`], turned into
//!   [`poly::RootOptions`] by [`RootMethods::options`].
//! - Bézier patches eliminate `v` from the ray/patch system with `groebner`: [`PatchMethod`]
//!   (the scene's `Method =`, `render --patch-method`). It maps onto `groebner::Method` and
//!   the arithmetic as follows (the only place that mapping is written):
//!
//! | `PatchMethod`      | `groebner::Method`   | arithmetic                      |
//! |--------------------|----------------------|---------------------------------|
//! | `Groebner`         | `Stam`               | `f64` (`groebner::solve_ray_patch`) |
//! | `Resultant`        | `BezoutResultant`    | `f64` (`groebner::solve_ray_patch`) |
//! | `GroebnerExact`    | `Stam`               | exact rationals (`groebner::solve`) |
//! | `ResultantExact`   | `BezoutResultant`    | exact rationals (`groebner::solve`) |

use groebner::Method;
use poly::{IsolationMethod, RefineMethod, RootOptions};

/// How implicit surfaces (torus, algebraic surfaces, superquadrics) find the smallest root of
/// their ray polynomial: `poly`'s isolation and refinement methods (`render --isolation`,
/// `--refine`). The default is the certified Bernstein isolation with Newton–bisection; the
/// others are there to compare solvers on whole images (`docs/speed.md`). Bézier patches have
/// their own choice ([`PatchMethod`]).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct RootMethods {
    /// How roots are isolated.
    pub isolation: IsolationMethod,
    /// How an isolated root is refined.
    pub refine: RefineMethod,
}

impl RootMethods {
    /// The options of one root query with tolerance `x_tol` (absolute, in the ray parameter).
    pub(crate) fn options(self, x_tol: f64) -> RootOptions {
        RootOptions {
            isolation: self.isolation,
            refine: self.refine,
            ..RootOptions::new(x_tol)
        }
    }
}

/// How `v` is eliminated for every ray (`Method =` in the scene, `--patch-method` on the CLI).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum PatchMethod {
    /// Stam's two-polynomial Gröbner reduction (article §4.2, `groebner::Method::Stam`).
    #[default]
    Groebner,
    /// Kajiya's resultant `Res_v(F1, F2)`, as the determinant of the `3 × 3` Bézout matrix
    /// (`groebner::Method::BezoutResultant`): for a bicubic `F1`, `F2` (both of degree 3 in
    /// `v`) it equals the `6 × 6` Sylvester determinant exactly and costs 12 polynomial
    /// products instead of 192, the same image bit for bit (timings in
    /// `paper-notes/bezier-patches.md`, "What made the resultant fast").
    Resultant,
    /// [`PatchMethod::Groebner`] over exact rationals: reference renders (slow; see
    /// `paper-notes/bezier-patches.md` §3).
    GroebnerExact,
    /// [`PatchMethod::Resultant`] over exact rationals: reference renders (slow; see
    /// `paper-notes/bezier-patches.md` §3).
    ResultantExact,
}

impl PatchMethod {
    /// The scene-file spelling.
    pub fn name(self) -> &'static str {
        match self {
            PatchMethod::Groebner => "GROEBNER",
            PatchMethod::Resultant => "RESULTANT",
            PatchMethod::GroebnerExact => "GROEBNER_EXACT",
            PatchMethod::ResultantExact => "RESULTANT_EXACT",
        }
    }

    /// Whether the algebra runs over exact rationals.
    pub fn is_exact(self) -> bool {
        matches!(
            self,
            PatchMethod::GroebnerExact | PatchMethod::ResultantExact
        )
    }

    /// Parses a scene-file or CLI spelling (case-insensitive).
    pub fn parse(s: &str) -> Option<Self> {
        [
            PatchMethod::Groebner,
            PatchMethod::Resultant,
            PatchMethod::GroebnerExact,
            PatchMethod::ResultantExact,
        ]
        .into_iter()
        .find(|m| {
            m.name().eq_ignore_ascii_case(s) || m.name().replace('_', "-").eq_ignore_ascii_case(s)
        })
    }

    /// The `groebner` method that eliminates `v` (the table in the module docs).
    pub(crate) fn solver_method(self) -> Method {
        match self {
            PatchMethod::Groebner | PatchMethod::GroebnerExact => Method::Stam,
            PatchMethod::Resultant | PatchMethod::ResultantExact => Method::BezoutResultant,
        }
    }
}

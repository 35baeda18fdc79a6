//! [`RootOptions`]: which isolation and refinement methods a root query uses, and its tolerance.

/// How real roots are isolated (separated into intervals holding one distinct root each).
///
/// Every method is reachable so that the stability suite can compare them degree by degree;
/// [`IsolationMethod::Bernstein`] is the default because it is the only one that is both
/// certified and runs at `f64` speed (see `paper-notes/isolation.md`).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
#[non_exhaustive]
pub enum IsolationMethod {
    /// Descartes' rule of signs in the Bernstein basis with de Casteljau subdivision
    /// (Vincent–Collins–Akritas style), in `f64` with a rigorous rounding-error bound on every
    /// Bernstein coefficient. An exact factor `x^k` (zero low coefficients) is divided out
    /// first. When a sign cannot be certified (a root on a subdivision point, tiny roots near
    /// 0, clustered roots) a fresh run with its own error bound takes the undecided piece; what
    /// `f64` still cannot decide (near-multiple roots of the stored polynomial) is isolated by
    /// exact Sturm counts on that piece only, counted in
    /// [`RootStats::exact_fallbacks`](crate::RootStats::exact_fallbacks).
    ///
    /// Certified: the answer is that of the stored polynomial, whatever the rounding.
    #[default]
    Bernstein,
    /// A Sturm sequence computed in `f64` with normalised remainders (each scaled to unit
    /// maximum coefficient, negligible leading terms dropped), then Stam's bisection isolation
    /// (seed §3.5.2). A heuristic: counts can be wrong when the remainder sequence loses
    /// accuracy (clustered roots, high degree).
    Sturm,
    /// Stam's 1988 procedure as written in `ray2.c` (Annexe B): his cross-multiplied Sturm
    /// recurrence normalised by the absolute value of each remainder's leading coefficient, his
    /// count-driven bisection, and his bisection refinement. Kept for comparison; the thesis
    /// reports it unstable above degree 8 (seed §4, p. 30).
    StamSturm,
    /// Exact rational Sturm sequence of the stored polynomial (converted exactly with
    /// [`Poly::to_rat`](crate::Poly::to_rat)), bisection on rationals. Certified and slow;
    /// this is also the fallback of [`IsolationMethod::Bernstein`].
    Exact,
}

/// How an isolating bracket is shrunk to the requested tolerance (seed §3.5.3).
///
/// Every method keeps a bracket whose endpoint signs are certified with
/// [`Poly::eval_with_error`](crate::Poly::eval_with_error), so the iterate never leaves the
/// isolating interval. The default is [`RefineMethod::NewtonBisection`]: on ray–torus and
/// ray–Barth polynomials it needs about 40% fewer evaluations than Illinois and the fewest
/// instructions per query (see `paper-notes/refinement.md` for the measurements).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
#[non_exhaustive]
pub enum RefineMethod {
    /// Halve the bracket until it is narrow enough (Stam, seed §3.5.3): one bit per
    /// evaluation, about `log2(width / x_tol)` evaluations.
    Bisection,
    /// Regula falsi with the Illinois modification (halve the retained end's value when the
    /// same end is kept twice), falling back to bisection when a step makes too little
    /// progress. Superlinear (order ≈ 1.44) on simple roots.
    Illinois,
    /// Newton's method safeguarded by the bracket: a Newton step that leaves the bracket or
    /// does not halve it every two steps is replaced by a bisection. Quadratic on simple
    /// roots; needs the derivative (one more Horner pass per step). Starts from the secant
    /// point of the bracket when both end values are known.
    #[default]
    NewtonBisection,
}

/// The options of a root query: tolerance and methods.
///
/// # Examples
/// ```
/// use poly::{IsolationMethod, Poly, RefineMethod, RootOptions, RootStats};
/// let p = Poly::new(vec![-2.0, 0.0, 1.0]); // x² − 2
/// let opts = RootOptions { refine: RefineMethod::Bisection, ..RootOptions::new(1e-12) };
/// let mut stats = RootStats::default();
/// let r = p.smallest_root_with(0.0, 10.0, &opts, &mut stats).unwrap();
/// assert!((r - 2f64.sqrt()).abs() <= 1e-12);
/// assert_eq!(stats.queries, 1);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RootOptions {
    /// Bound on `|returned − true root|` (absolute, in the variable's units); must be finite
    /// and non-negative ([`RootError::InvalidTolerance`](crate::RootError) otherwise). Zero
    /// asks for the best `f64` answer (within one unit in the last place of the root).
    pub x_tol: f64,
    /// How roots are isolated.
    pub isolation: IsolationMethod,
    /// How an isolated root is refined.
    pub refine: RefineMethod,
    /// Answer degrees 1 and 2 in closed form (certified: the closed-form root is checked by a
    /// sign change before it is returned, and the general path runs when the check fails).
    pub closed_form: bool,
}

impl RootOptions {
    /// The default methods with root tolerance `x_tol` (absolute).
    pub fn new(x_tol: f64) -> Self {
        RootOptions {
            x_tol,
            isolation: IsolationMethod::default(),
            refine: RefineMethod::default(),
            closed_form: true,
        }
    }
}

impl Default for RootOptions {
    /// The default methods with `x_tol = 1e-10`.
    fn default() -> Self {
        RootOptions::new(1e-10)
    }
}

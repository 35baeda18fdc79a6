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
    ///
    /// What it promises (issue 11, "heuristic methods never lie silently"): every root it
    /// returns is bracketed by certified opposite signs of the stored polynomial (or is an
    /// exact root) and refined as the certified path refines, so it is within `x_tol` of a
    /// true root; every interval [`Poly::isolate_roots_with`](crate::Poly::isolate_roots_with)
    /// returns has certified opposite end signs. A count it can tell is wrong or unknown — a
    /// member's sign within its rounding bound (the members carry a running bound on their
    /// coefficient errors) that decides the count, a sequence that overflowed, underflowed
    /// or needed a remainder coefficient dropped as noise, "no root" between certified
    /// opposite signs — is [`RootError::Unresolved`](crate::RootError::Unresolved), never an
    /// answer. What it does not promise: that no root is missed. A count off by an even
    /// number between ends of equal sign, from rounding the first-order bound does not see,
    /// stays invisible (the fuzzer's seed 7 finds four in 6 000 cases:
    /// `paper-notes/sturm.md`, "What the `f64` heuristics check"). Most multiple roots are
    /// `Unresolved`.
    Sturm,
    /// Stam's 1988 procedure as written in `ray2.c` (Annexe B): his cross-multiplied Sturm
    /// recurrence normalised by the absolute value of each remainder's leading coefficient, his
    /// count-driven bisection, and his bisection refinement. Kept for comparison; the thesis
    /// reports it unstable above degree 8 (seed §4, p. 30).
    ///
    /// Its promises are those of [`IsolationMethod::Sturm`]: his recurrence is kept as
    /// written and carries no error bound, but a sequence where it visibly failed (left the
    /// normal case of degrees dropping by one, overflowed, went below the normal range, or
    /// produced a leading coefficient below the rounding of its member's others), a member
    /// sign within its evaluation bound that decides the count, and an underflowed product
    /// in his sign test are [`RootError::Unresolved`](crate::RootError::Unresolved); a root
    /// returned is confirmed by a certified sign change within `x_tol` below it and none
    /// before it. An even number of roots between ends of equal sign can still be missed.
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
/// # Accuracy
/// A root `ρ` is returned as `r` with `|r − ρ| ≤ max(x_tol, rel_tol·|ρ|)` (the mixed form:
/// absolute near 0, relative away from it), or within one `f64` spacing of `ρ` when that is
/// larger. With `rel_tol = 0` (the default) the tolerance is absolute; with `x_tol = 0` and
/// `rel_tol > 0` it is purely relative. For the certified methods this holds for every root
/// of the stored polynomial; the Sturm methods are heuristics.
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
    /// asks for the best `f64` answer: no `f64` strictly between the value returned and the
    /// root (within one unit in the last place: a faithful rounding, not always the nearest
    /// `f64`). Its cost: [`Poly::real_roots`](crate::Poly::real_roots), `# Accuracy`.
    pub x_tol: f64,
    /// Bound on `|returned − true root| / |true root|` (relative), combined with `x_tol` as
    /// `max(x_tol, rel_tol·|root|)` (see `# Accuracy`); must be finite with
    /// `0 ≤ rel_tol < 1` ([`RootError::InvalidTolerance`](crate::RootError) otherwise: from 1
    /// on, 0 would be an answer for every root). Default 0: absolute tolerance only.
    pub rel_tol: f64,
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
            rel_tol: 0.0,
            isolation: IsolationMethod::default(),
            refine: RefineMethod::default(),
            closed_form: true,
        }
    }
}

impl RootOptions {
    /// The default methods with the mixed tolerance `max(x_tol, rel_tol·|root|)`.
    ///
    /// # Examples
    /// ```
    /// use poly::{Poly, RootOptions};
    /// // Roots 1e-3 and 1e9: twelve significant digits of each, whatever its size.
    /// let p = Poly::<f64>::from_roots(&[1e-3, 1e9]);
    /// let r = p.roots(0.0, 1e10, &RootOptions::relative(0.0, 1e-12)).all()?;
    /// assert!((r[0] - 1e-3).abs() <= 1e-15 && (r[1] - 1e9).abs() <= 1e-3);
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn relative(x_tol: f64, rel_tol: f64) -> Self {
        RootOptions {
            rel_tol,
            ..RootOptions::new(x_tol)
        }
    }

    /// True when both tolerances are valid (see the fields).
    pub(crate) fn tolerance_is_valid(&self) -> bool {
        let abs_ok = self.x_tol.is_finite() && self.x_tol >= 0.0;
        abs_ok && self.rel_tol.is_finite() && (0.0..1.0).contains(&self.rel_tol)
    }

    /// The tolerance as the refinement uses it.
    pub(crate) fn tolerance(&self) -> Tolerance {
        Tolerance {
            abs: self.x_tol,
            rel: self.rel_tol,
        }
    }
}

/// The mixed tolerance `max(abs, rel·|root|)` of [`RootOptions`], for refinement.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Tolerance {
    /// Absolute part (`x_tol`).
    pub(crate) abs: f64,
    /// Relative part (`rel_tol`, in `[0, 1)`).
    pub(crate) rel: f64,
}

impl Tolerance {
    /// An absolute tolerance only.
    pub(crate) fn absolute(abs: f64) -> Self {
        Tolerance { abs, rel: 0.0 }
    }

    /// An absolute tolerance valid for every root in the bracket `(lo, hi)`: `abs`, or
    /// `rel·min(|lo|, |hi|)` rounded down when larger and the bracket does not contain 0 (then
    /// every root `ρ` in it has `|ρ| ≥ min(|lo|, |hi|)`).
    #[inline]
    pub(crate) fn on(&self, lo: f64, hi: f64) -> f64 {
        if self.rel == 0.0 || (lo < 0.0 && hi > 0.0) {
            return self.abs;
        }
        // One rounding of the product, relative u ≤ ε: (1 − ε) makes it a lower bound.
        let r = self.rel * lo.abs().min(hi.abs()) * (1.0 - f64::EPSILON);
        self.abs.max(r)
    }

    /// An absolute tolerance `t` such that a value within `t/2` of `x` of a root `ρ` (a
    /// closed-form root certified in `[x − t/2, x + t/2]`) meets `max(abs, rel·|ρ|)`:
    /// `abs`, or `rel·|x|/2` when larger. Why that suffices: `|ρ − x| ≤ rel·|x|/4` gives
    /// `|ρ| ≥ ¾|x|` for `rel < 1`, so `rel·|x|/4 < rel·|ρ|`.
    #[inline]
    pub(crate) fn near(&self, x: f64) -> f64 {
        if self.rel == 0.0 {
            return self.abs;
        }
        self.abs.max(0.5 * self.rel * x.abs())
    }
}

/// The root tolerance of [`RootOptions::default`] (absolute): `1e-10`, ten digits of a root of
/// unit size, far below what the renderer's geometry resolves and cheap for the refinement.
pub const DEFAULT_X_TOL: f64 = 1e-10;

impl Default for RootOptions {
    /// The default methods with `x_tol =` [`DEFAULT_X_TOL`].
    fn default() -> Self {
        RootOptions::new(DEFAULT_X_TOL)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{Poly, RootError, RootStats};

    #[test]
    fn relative_tolerance_is_met_and_used() {
        // Roots of very different sizes: an absolute x_tol cannot suit all of them.
        let roots = [-2e7, 1e-3, 1.0, 3e5, 1e9];
        let p = Poly::<f64>::from_roots(&roots);
        let rel = 1e-6;
        for isolation in [IsolationMethod::Bernstein, IsolationMethod::Exact] {
            for refine in [
                RefineMethod::Bisection,
                RefineMethod::Illinois,
                RefineMethod::NewtonBisection,
            ] {
                let base = RootOptions {
                    isolation,
                    refine,
                    ..RootOptions::new(0.0)
                };
                let relative = RootOptions {
                    rel_tol: rel,
                    ..base
                };
                let (mut s_rel, mut s_full) = (RootStats::default(), RootStats::default());
                let got = p
                    .real_roots_with(-1e10, 1e10, &relative, &mut s_rel)
                    .unwrap();
                let full = p.real_roots_with(-1e10, 1e10, &base, &mut s_full).unwrap();
                assert_eq!(got.len(), roots.len(), "{isolation:?} {refine:?}: {got:?}");
                for (g, t) in got.iter().zip(&full) {
                    assert!(
                        (g - t).abs() <= rel * t.abs(),
                        "{isolation:?} {refine:?}: {g:e} vs {t:e}"
                    );
                }
                if isolation == IsolationMethod::Bernstein {
                    assert!(
                        s_rel.refine_evals < s_full.refine_evals,
                        "{refine:?}: the relative tolerance stops refinement earlier ({} vs {})",
                        s_rel.refine_evals,
                        s_full.refine_evals
                    );
                }
                let first = p
                    .try_smallest_root(0.0, 1e10, &relative, &mut s_rel)
                    .unwrap();
                assert!(
                    first.is_some_and(|r| (r - 1e-3).abs() <= rel * 1e-3),
                    "{isolation:?} {refine:?}: {first:?}"
                );
            }
        }
        // Degree 2: the closed form honours it too.
        let q = Poly::<f64>::from_roots(&[3e8, 7e8]);
        let r = q
            .roots(0.0, 1e9, &RootOptions::relative(0.0, 1e-9))
            .smallest();
        assert!(
            r.unwrap().is_some_and(|r| (r - 3e8).abs() <= 0.3),
            "quadratic"
        );
        for bad in [1.0, -1e-3, f64::NAN, f64::INFINITY] {
            assert_eq!(
                p.roots(0.0, 1.0, &RootOptions::relative(0.0, bad)).all(),
                Err(RootError::InvalidTolerance),
                "rel_tol {bad}"
            );
        }
    }
}

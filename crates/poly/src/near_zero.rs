//! Where an `f64` polynomial nearly vanishes: the components of `{x : |e(x)| ≤ bound}`
//! ([`near_zero_components_into`]) and the critical points at which it almost touches zero
//! ([`near_double_roots_into`]), both on top of the certified real-root finder.
//!
//! Why: a polynomial known only within an error bound (an eliminant computed in `f64`, with
//! a running bound on its distance to the exact one) has its true roots inside the first set;
//! and rounding can split a double root into a complex pair, which a real-root finder then
//! rightly does not report, while the critical point between them remains.
//!
//! Buffers are the caller's ([`NearZeroBuffers`]); once they have grown nothing is allocated
//! (except by the exact fallback of the root finder, [`RootStats::exact_fallbacks`]).

use crate::eval_bound::horner_bounded;
use crate::root_options::RootOptions;
use crate::stats::RootStats;
use crate::univariate::Poly;

/// Reusable scratch for the functions of this module.
#[derive(Clone, Debug, Default)]
pub struct NearZeroBuffers {
    /// A shifted or derived polynomial.
    scratch: Vec<f64>,
    /// Cuts between components, critical points.
    cuts: Vec<f64>,
    /// The root finder's counters.
    stats: RootStats,
}

impl NearZeroBuffers {
    /// Buffers sized for polynomials of degree `degree`.
    pub fn with_degree(degree: usize) -> Self {
        NearZeroBuffers {
            scratch: Vec::with_capacity(degree + 1),
            cuts: Vec::with_capacity(2 * degree + 2),
            stats: RootStats::default(),
        }
    }
}

/// The real roots in `range` of the polynomial with coefficients `coeffs` (lowest power first),
/// appended to `out` (sorted among themselves) by [`Poly::real_roots_into`] with its default
/// certified method. `coeffs` is lent to a [`Poly`] and given back (trailing zeros trimmed),
/// so nothing is allocated. A constant (or zero) polynomial, non-finite input and any other
/// error leave `out` as it was.
///
/// # Accuracy
/// As [`Poly::real_roots`]: every root of the stored polynomial, each within `x_tol`.
pub fn real_roots_of_coeffs_into(
    coeffs: &mut Vec<f64>,
    range: [f64; 2],
    x_tol: f64,
    stats: &mut RootStats,
    out: &mut Vec<f64>,
) {
    let p = Poly::new(std::mem::take(coeffs));
    if p.degree() > 0 {
        // Documented: on an error `out` is left as it was, which is "no roots" here.
        let _ = p.real_roots_into(range[0], range[1], &RootOptions::new(x_tol), stats, out);
    }
    *coeffs = p.into_coeffs();
}

/// The midpoints of the components of `Z = {x ∈ range : |e(x)| ≤ bound}`, into `out`
/// (cleared first), and the largest half-width of a component; `None` when `bound` is not
/// finite or a component is wider than `max_width + 2·x_tol` (then `out` is partial and must
/// not be used).
///
/// The components are delimited by the real roots of `e − bound` and `e + bound` in `range`
/// (certified isolation, each within `x_tol`); between two consecutive cuts `|e| − bound` has
/// one sign, tested at the midpoint. Midpoints closer than `4·x_tol` are merged.
///
/// # Accuracy
/// Every point of `Z` lies within the returned half-width (at most `max_width/2 + x_tol`)
/// plus `x_tol` of a returned midpoint: the cuts are the true boundary points of `Z` to within `x_tol`
/// (the midpoint test is a plain Horner evaluation, which can only misjudge a sub-interval
/// whose `|e|` is within rounding of `bound` everywhere, i.e. a boundary point).
///
/// # Examples
/// ```
/// use poly::{near_zero_components_into, NearZeroBuffers};
/// let e = [-0.25, 0.0, 1.0]; // x² − 1/4: near zero around ±1/2
/// let (mut buf, mut out) = (NearZeroBuffers::default(), Vec::new());
/// let half_width = near_zero_components_into(&e, 1e-9, [0.0, 1.0], 1e-12, 1e-6, &mut buf, &mut out);
/// assert!(half_width.is_some_and(|w| w < 1e-8));
/// assert_eq!(out.len(), 1);
/// assert!((out[0] - 0.5).abs() < 1e-8);
/// // A loose bound makes a component wider than allowed:
/// assert_eq!(near_zero_components_into(&e, 1e-2, [0.0, 1.0], 1e-12, 1e-6, &mut buf, &mut out), None);
/// ```
pub fn near_zero_components_into(
    e: &[f64],
    bound: f64,
    range: [f64; 2],
    x_tol: f64,
    max_width: f64,
    buf: &mut NearZeroBuffers,
    out: &mut Vec<f64>,
) -> Option<f64> {
    out.clear();
    if !bound.is_finite() || e.is_empty() {
        return None;
    }
    let NearZeroBuffers {
        scratch,
        cuts,
        stats,
    } = buf;
    cuts.clear();
    cuts.push(range[0]);
    cuts.push(range[1]);
    for shift in [-bound, bound] {
        scratch.clear();
        scratch.extend_from_slice(e);
        scratch[0] += shift;
        real_roots_of_coeffs_into(scratch, range, x_tol, stats, cuts);
    }
    cuts.sort_unstable_by(f64::total_cmp);
    cuts.dedup();
    let inside = |x: f64| horner_bounded(e, x).0.abs() <= bound;
    let mut start: Option<f64> = None;
    let mut half_width = 0.0f64;
    let mut close = |a: f64, b: f64, out: &mut Vec<f64>| -> bool {
        if b - a > max_width + 2.0 * x_tol {
            return false;
        }
        out.push(0.5 * (a + b));
        half_width = half_width.max(0.5 * (b - a));
        true
    };
    for w in cuts.windows(2) {
        let (a, b) = (w[0], w[1]);
        if inside(0.5 * (a + b)) {
            start.get_or_insert(a);
        } else if let Some(s) = start.take() {
            if !close(s, a, out) {
                return None;
            }
        } else if a > range[0] && !close(a, a, out) {
            // An isolated boundary point (Z touches it from no side at this resolution).
            return None;
        }
    }
    let closed = match start {
        Some(s) => close(s, range[1], out),
        None if inside(range[1]) => close(range[1], range[1], out),
        None => true,
    };
    out.dedup_by(|b, a| (*b - *a).abs() <= 4.0 * x_tol);
    closed.then_some(half_width)
}

/// Adds to `roots` (the real roots in `range` of the polynomial with coefficients `e`, sorted)
/// the real critical points `c` of `e` in `range` where it nearly vanishes,
/// `|e(c)| ≤ rel · Σ|e_i||c|^i`, that are not already within `4·x_tol` of a root — except a
/// critical point that is the only one between two adjacent roots. `roots` is sorted at the
/// end.
///
/// Why the exception: between two close simple roots a polynomial has a hump whose top can be
/// below `rel` (two roots 2.4e-4 apart gave a third "root" midway, `git show fafaf90`). Such a
/// critical point is never a double root: a (near-)double root `d` between two roots
/// `r1 < d < r2` keeps three critical points in `(r1, r2)` — one near `d`, one on each side by
/// Rolle — under any small perturbation, so one that is alone there is a simple hump.
///
/// # Accuracy
/// Heuristic by design: the candidates are points where a double root may have been split by
/// rounding, to be verified by the caller. Every real critical point with `|e(c)|` below the
/// threshold (within `x_tol`) is returned, but for the exception above.
///
/// # Examples
/// ```
/// use poly::{near_double_roots_into, NearZeroBuffers};
/// // (x − 1/2)² + 1e-20: a double root split into a complex pair by a tiny perturbation.
/// let e = [0.25 + 1e-20, -1.0, 1.0];
/// let mut roots = Vec::new(); // the real roots: none
/// near_double_roots_into(&e, [0.0, 1.0], 1e-12, 1e-8, &mut NearZeroBuffers::default(), &mut roots);
/// assert_eq!(roots.len(), 1);
/// assert!((roots[0] - 0.5).abs() < 1e-10);
/// ```
pub fn near_double_roots_into(
    e: &[f64],
    range: [f64; 2],
    x_tol: f64,
    rel: f64,
    buf: &mut NearZeroBuffers,
    roots: &mut Vec<f64>,
) {
    if e.len() < 3 {
        return; // degree < 2
    }
    let NearZeroBuffers {
        scratch,
        cuts: crit,
        stats,
    } = buf;
    scratch.clear();
    scratch.extend(e.iter().enumerate().skip(1).map(|(i, &c)| c * i as f64));
    crit.clear();
    real_roots_of_coeffs_into(scratch, range, x_tol, stats, crit);
    let merge = 4.0 * x_tol;
    let found = roots.len();
    for &c in crit.iter() {
        // The adjacent roots around c (the candidates added here do not count).
        let below = roots[..found]
            .iter()
            .copied()
            .filter(|&r| r < c)
            .fold(f64::NEG_INFINITY, f64::max);
        let above = roots[..found]
            .iter()
            .copied()
            .filter(|&r| r > c)
            .fold(f64::INFINITY, f64::min);
        let alone = below.is_finite()
            && above.is_finite()
            && crit.iter().all(|&d| d == c || d <= below || d >= above);
        if alone {
            continue;
        }
        let (value, size) = e
            .iter()
            .rev()
            .fold((0.0, 0.0), |(v, s), &a| (v * c + a, s * c.abs() + a.abs()));
        if value.abs() <= rel * size && !roots.iter().any(|r| (r - c).abs() <= merge) {
            roots.push(c);
        }
    }
    roots.sort_unstable_by(f64::total_cmp);
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn components_of_a_cubic_band() {
        // e = (x − 0.2)(x − 0.5)(x − 0.8): three narrow components for a small bound.
        let e = [-0.08, 0.66, -1.5, 1.0];
        let (mut buf, mut out) = (NearZeroBuffers::default(), Vec::new());
        assert!(
            near_zero_components_into(&e, 1e-12, [0.0, 1.0], 1e-14, 1e-6, &mut buf, &mut out)
                .is_some()
        );
        assert_eq!(out.len(), 3, "{out:?}");
        for (m, r) in out.iter().zip([0.2, 0.5, 0.8]) {
            assert!((m - r).abs() < 1e-9, "midpoint {m} vs root {r}");
        }
        assert_eq!(
            near_zero_components_into(&e, f64::NAN, [0.0, 1.0], 1e-14, 1e-6, &mut buf, &mut out),
            None,
            "a NaN bound certifies nothing"
        );
    }

    #[test]
    fn a_component_reaching_the_range_end_is_closed_there() {
        // |x − 1| ≤ 1e-9 near the right end of [0, 1]: the component is [1 − 1e-9, 1].
        let e = [-1.0, 1.0];
        let (mut buf, mut out) = (NearZeroBuffers::default(), Vec::new());
        let w = near_zero_components_into(&e, 1e-9, [0.0, 1.0], 1e-13, 1e-6, &mut buf, &mut out);
        assert!(
            w.is_some_and(|w| (w - 0.5e-9).abs() < 1e-12),
            "half-width {w:?}"
        );
        assert_eq!(out.len(), 1);
        assert!((out[0] - (1.0 - 0.5e-9)).abs() < 1e-12, "{out:?}");
    }

    #[test]
    fn regression_fafaf90_hump_between_two_close_roots_is_not_a_candidate() {
        // Caught: the critical point midway between two simple roots 2.4e-4 apart has |e| far
        // below 1e-8 of the term size, and was added as a "near-double root" (a spurious third
        // hit once verified on the system). Roots 0.5 and 0.5 + 2.4e-4.
        let (r1, r2) = (0.5, 0.5 + 2.4e-4);
        let e = [r1 * r2, -(r1 + r2), 1.0];
        let mut roots = vec![r1, r2];
        near_double_roots_into(
            &e,
            [0.0, 1.0],
            1e-10,
            1e-8,
            &mut NearZeroBuffers::default(),
            &mut roots,
        );
        assert_eq!(roots, vec![r1, r2], "no candidate between the two roots");
    }

    #[test]
    fn merged_and_far_critical_points_are_skipped() {
        // x³ − x: critical points ±1/√3 with |e| ≈ 0.38, far from zero.
        let e = [0.0, -1.0, 0.0, 1.0];
        let mut roots = vec![-1.0, 0.0, 1.0];
        near_double_roots_into(
            &e,
            [-2.0, 2.0],
            1e-12,
            1e-8,
            &mut NearZeroBuffers::default(),
            &mut roots,
        );
        assert_eq!(roots, vec![-1.0, 0.0, 1.0]);
    }
}

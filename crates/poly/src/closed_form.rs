//! Certified closed forms for degrees 1 and 2.
//!
//! The quadratic uses the cancellation-free pair `q = −(b + sign(b)·√Δ)/2`, `x₁ = q/a`,
//! `x₂ = c/q` (Numerical Recipes §5.6; Higham §1.8), never `(−b ± √Δ)/2a`. Each root found
//! is then *certified* by a sign change of the stored polynomial across `[r − δ, r + δ]`,
//! evaluated with a rigorous error bound, so a closed-form answer is as trustworthy as the
//! general path. When a sign, the discriminant or an interval end cannot be decided, the
//! function answers `None` ("undecided") and the caller runs the general certified path.
//!
//! Degrees 3 and 4 have no closed form here on purpose: Cardano and Ferrari lose accuracy to
//! cancellation on exactly the hard cases (POV-Ray's quartic is off by ±0.1 at scale 1e7),
//! and the Bernstein path is certified and fast enough (see `paper-notes/isolation.md`).

use crate::eval_bound::{certified_sign, horner_bounded, sign_if_certain};
use crate::refine::half_tol;
use crate::root_options::Tolerance;
use crate::univariate::UNIT_ROUNDOFF;

/// Relative error bound of the computed discriminant `c1² − 4·c0·c2`: three roundings on each
/// product path and one for the difference, `≤ 4u` relative to `c1² + |4·c0·c2|` (each within
/// `(1 + u)³ − 1 < 3.01u`, the difference one more `u`), doubled for margin: `8u = 4ε`.
const DISC_REL_ERR: f64 = 8.0 * UNIT_ROUNDOFF;

/// Absolute allowance in the discriminant's error bound for underflow: every rounding that
/// lands in the subnormal range errs by at most 2^-1075, and the few of the discriminant
/// (≤ 4) are covered by `1e-322` ≈ 20 × 2^-1074 with room to spare.
const DISC_UNDERFLOW_ERR: f64 = 1e-322;

/// The smallest root of `c0 + c1·x` in `(t_min, t_max]`: `Some(Some(r))`, `Some(None)` when
/// there is certainly none, `None` when undecided. Requires `c1 ≠ 0`, finite input.
///
/// # Accuracy
/// `r = fl(−c0/c1)` is correctly rounded, so `|r − root| ≤ ½ ulp(root)`; membership of the
/// interval is decided only with a margin of one ulp.
pub(crate) fn linear_smallest(c: &[f64], t_min: f64, t_max: f64) -> Option<Option<f64>> {
    let r = -c[0] / c[1];
    if !r.is_finite() {
        return None;
    }
    // |r − root| ≤ u·|root| + underflow, well inside one ulp on each side.
    let (below, above) = (r.next_down(), r.next_up());
    if below > t_min && above <= t_max {
        Some(Some(r))
    } else if above <= t_min || below > t_max {
        Some(None)
    } else {
        None
    }
}

/// The root of the line `c0 + c1·x` when it lies in `(t_min, t_max]`, for callers that
/// restrict a plane to a ray and need no query set-up (polygon meshes).
///
/// Returns `Some(Some(r))` with the root, `Some(None)` when there is certainly no root in
/// the interval (also for `c1 = 0` with `c0 ≠ 0`: a line parallel to the plane), and `None`
/// when undecided — the root within one ulp of an interval end, `c0 = c1 = 0`, or non-finite
/// input — in which case the caller runs the general certified query ([`crate::PolyRef`]).
///
/// # Accuracy
/// `r = fl(−c0/c1)` is correctly rounded: `|r − root| ≤ ½ ulp(root)` for the line as stored.
/// Membership of `(t_min, t_max]` is decided with a margin of one ulp on each side.
///
/// # Examples
/// ```
/// // 2x − 3 = 0 at x = 1.5.
/// assert_eq!(poly::linear_root_in(-3.0, 2.0, 0.0, 2.0), Some(Some(1.5)));
/// assert_eq!(poly::linear_root_in(-3.0, 2.0, 2.0, 3.0), Some(None));
/// ```
#[inline]
pub fn linear_root_in(c0: f64, c1: f64, t_min: f64, t_max: f64) -> Option<Option<f64>> {
    if !(c0.is_finite() && c1.is_finite()) || (c0 == 0.0 && c1 == 0.0) {
        return None;
    }
    if c1 == 0.0 {
        return Some(None);
    }
    linear_smallest(&[c0, c1], t_min, t_max)
}

/// [`certified_sign`] of the quadratic `c` at `x`: its first tier (Horner with a rigorous
/// bound, [`horner_bounded`]) compiled here for three coefficients, and the whole function,
/// which starts with the same evaluation, only when that tier cannot decide. So the sign is
/// `certified_sign`'s bit for bit; the general function is not inlined and loops over a slice,
/// ≈ 74 instructions a call against ≈ 25 (issue 12, ninth pass: two to four calls a sphere
/// query).
#[inline(always)]
fn certified_sign3(c: &[f64; 3], x: f64) -> i8 {
    let (v, err) = horner_bounded(c, x);
    match sign_if_certain(v, err) {
        0 => certified_sign(c, x, 0.0),
        s => s,
    }
}

/// The smallest root of `c0 + c1·x + c2·x²` in `(t_min, t_max]`: `Some(Some(r))` with
/// `|r − root| ≤ max(tol.abs, tol.rel·|root|)`, `Some(None)` when there is certainly none,
/// `None` when undecided (near-double root, a root within the tolerance of an interval end,
/// or a tolerance below what `f64` can certify there, and for a slice that is not three
/// coefficients). Requires `c2 ≠ 0`, finite input.
pub(crate) fn quadratic_smallest(
    c: &[f64],
    t_min: f64,
    t_max: f64,
    tol: Tolerance,
) -> Option<Option<f64>> {
    // As an array, so that the evaluations below are compiled for three coefficients
    // (unrolled, their error bounds' constants folded).
    let c: &[f64; 3] = c.try_into().ok()?;
    let (c0, c1, c2) = (c[0], c[1], c[2]);
    // Δ = c1² − 4·c0·c2 with an error bound relative to the sum of the magnitudes; the
    // discriminant only decides "no real root" here.
    let disc = c1 * c1 - 4.0 * c0 * c2;
    let disc_err = DISC_REL_ERR * (c1 * c1 + (4.0 * c0 * c2).abs()) + DISC_UNDERFLOW_ERR;
    if !disc.is_finite() {
        return None;
    }
    if disc < -disc_err {
        return Some(None);
    }
    if disc <= disc_err {
        return None;
    }
    let sq = disc.sqrt();
    let q = -0.5 * (c1 + if c1 >= 0.0 { sq } else { -sq });
    let (x1, x2) = (q / c2, c0 / q);
    let (r1, r2) = if x1 <= x2 { (x1, x2) } else { (x2, x1) };
    if !(r1.is_finite() && r2.is_finite()) || r1 == r2 {
        return None;
    }
    // Sign of p left of both roots and right of both: that of c2; between them: −c2.
    let s_out: i8 = if c2 > 0.0 { 1 } else { -1 };
    for (k, r) in [r1, r2].into_iter().enumerate() {
        // The certifying interval (r − δ, r + δ) also stays on one side of each end of the
        // range, so that it decides membership: with a wide tolerance (a shadow ray's "any
        // root") δ would otherwise reach past an end near the root and leave the query
        // undecided, to the general path (issue 12: most sphere shadow rays on the SPD
        // sphereflakes). A δ of 0 (the root on an end) still defers, below.
        let delta = half_tol(tol.near(r))
            .min(0.25 * (r2 - r1))
            .min(0.5 * (r - t_min).abs())
            .min(0.5 * (t_max - r).abs());
        let (lo, hi) = (r - delta, r + delta);
        if !(lo < r && r < hi) {
            return None;
        }
        // Certify: the smaller root has p(lo) = s_out, p(hi) = −s_out (lo lies left of both
        // roots, hi between them); the larger root the mirror image.
        let (want_lo, want_hi) = if k == 0 {
            (s_out, -s_out)
        } else {
            (-s_out, s_out)
        };
        if certified_sign3(c, lo) != want_lo || certified_sign3(c, hi) != want_hi {
            return None;
        }
        // Now the root is certainly in (lo, hi), and (for the larger root) the smaller one
        // was certainly at or below t_min.
        if hi <= t_min {
            continue;
        }
        if lo > t_max {
            return Some(None);
        }
        if lo > t_min && hi <= t_max {
            return Some(Some(r));
        }
        return None;
    }
    Some(None)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn quadratic_without_cancellation() {
        // x² − 1e8·x + 1: roots ≈ 1e-8 and 1e8. The textbook formula loses the small root.
        let c = [1.0, -1e8, 1.0];
        let r = quadratic_smallest(&c, 0.0, 1.0, Tolerance::absolute(1e-20))
            .unwrap()
            .unwrap();
        assert!((r - 1e-8).abs() <= 1e-20, "small root {r:e}");
        let naive = (1e8 - (1e16f64 - 4.0).sqrt()) / 2.0;
        assert!(
            (naive - 1e-8).abs() > 1e-10,
            "the naive formula is wrong here: {naive:e}"
        );
        let r = quadratic_smallest(&c, 1.0, 1e9, Tolerance::absolute(1e-6))
            .unwrap()
            .unwrap();
        assert!((r - 1e8).abs() <= 1e-6, "large root {r:e}");
    }

    /// A wide tolerance (a shadow ray's "any root": the whole range) with the smaller root
    /// closer to the range's start than a quarter of the root gap: the certifying interval
    /// used to reach below the start, so the closed form deferred to Bernstein isolation on
    /// most sphere shadow rays of the SPD scenes (issue 12). It now decides.
    #[test]
    fn wide_tolerance_root_near_the_start_is_decided() {
        // (x − 0.1)(x − 2): roots 0.1 and 2, the range (0, 3] and x_tol = 3.
        let c = [0.2, -2.1, 1.0];
        let r = quadratic_smallest(&c, 0.0, 3.0, Tolerance::absolute(3.0));
        let r = r.expect("decided").expect("a root");
        assert!((r - 0.1).abs() < 1e-12, "the smaller root: {r}");
        // The larger root only, when the range starts between them near 2.
        let r = quadratic_smallest(&c, 1.9, 3.0, Tolerance::absolute(1.1));
        assert!(
            (r.expect("decided").expect("a root") - 2.0).abs() < 1e-12,
            "the larger root"
        );
        // No root when the range ends just before the smaller one.
        assert_eq!(
            quadratic_smallest(&c, -1.0, 0.09, Tolerance::absolute(1.09)),
            Some(None),
            "decided: none"
        );
    }

    #[test]
    fn quadratic_decides_or_defers() {
        let c = [2.0, 0.0, 1.0]; // x² + 2: no real root
        assert_eq!(
            quadratic_smallest(&c, -10.0, 10.0, Tolerance::absolute(1e-9)),
            Some(None),
            "complex roots"
        );
        let c = [1.0, -2.0, 1.0]; // (x − 1)²: double root, undecidable in f64
        assert_eq!(
            quadratic_smallest(&c, -10.0, 10.0, Tolerance::absolute(1e-9)),
            None,
            "defers to exact"
        );
        let c = [-1.0, 0.0, 1.0]; // roots ±1; the interval end sits on a root
        assert_eq!(
            quadratic_smallest(&c, -1.0, 0.5, Tolerance::absolute(1e-9)),
            None,
            "root at t_min: defers"
        );
        assert_eq!(
            quadratic_smallest(&c, -0.5, 0.5, Tolerance::absolute(1e-9)),
            Some(None),
            "none inside"
        );
        assert_eq!(
            quadratic_smallest(&c, -2.0, 0.5, Tolerance::absolute(1e-9)),
            Some(Some(-1.0)),
            "−1"
        );
    }

    #[test]
    fn linear_root_in_handles_parallel_and_degenerate_lines() {
        assert_eq!(linear_root_in(1.0, 0.0, 0.0, 10.0), Some(None), "parallel");
        assert_eq!(linear_root_in(0.0, 0.0, 0.0, 10.0), None, "in the plane");
        assert_eq!(linear_root_in(f64::NAN, 1.0, 0.0, 10.0), None, "NaN");
        assert_eq!(linear_root_in(-4.0, 2.0, 0.0, 10.0), Some(Some(2.0)), "2");
    }

    #[test]
    fn linear_membership_margins() {
        assert_eq!(
            linear_smallest(&[-3.0, 2.0], 0.0, 2.0),
            Some(Some(1.5)),
            "1.5 inside"
        );
        assert_eq!(
            linear_smallest(&[-3.0, 2.0], 1.5, 2.0),
            None,
            "root on the open end"
        );
        assert_eq!(
            linear_smallest(&[-3.0, 2.0], 2.0, 3.0),
            Some(None),
            "outside"
        );
    }
}

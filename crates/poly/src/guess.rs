//! The smallest root by guess and verify: an uncertified `f64` Newton iteration from the
//! range's start proposes the root, and three certified facts prove it — the polynomial keeps
//! its start sign on `(lo, x − δ]` (Bernstein coefficients there, all of that sign with the
//! rigorous bound of [`crate::bernstein`]), and the signs at `x ∓ δ` are opposite. Then the
//! smallest root in `(lo, hi]` lies within `δ` of `x`, whatever the iteration did to get
//! there. When any of the three fails, nothing is claimed and the caller isolates as before
//! (`paper-notes/isolation.md`, "Guess and verify").
//!
//! Why it pays: a ray that meets a surface usually meets it where Newton's iteration from the
//! ray's entry goes (the polynomial falls monotonically to its first root), and the proof
//! costs one basis change and two evaluations, where subdivision and a certified refinement
//! evaluate with bounds at every step.

use crate::bernstein::no_root_on;
use crate::eval_bound::certified_value_pair;
use crate::refine::{half_tol, probe_points};
use crate::root_options::Tolerance;
use crate::shifted::far_centroid;
use crate::stored::Slack;

/// Newton steps from the range's start before the guess is given up (the caller then
/// isolates). Far from a cluster of `k` roots a step gains only a factor `(k − 1)/k`, so a
/// quartic's entry rays may need a dozen; a guess that has not settled by then is rarely the
/// smallest root.
const MAX_GUESS_STEPS: u32 = 12;

/// A step below this fraction of the tolerance (absolute, `tol.near(x)`) has settled: near a
/// simple root Newton's error after such a step is far below it, and the proof's points
/// `x ∓ δ` lie half a tolerance out, so the guess is inside with room to spare. A quarter
/// keeps the last step well inside `δ` without asking for one more.
const SETTLED_TOL_FRACTION: f64 = 0.25;

/// A step below this fraction of `|x|` (relative: four units of `f64` rounding) has settled
/// whatever the tolerance: Newton's iteration cannot get closer in `f64`, and the proof's
/// points `x ∓ δ` (neighbouring doubles when `δ` is below their spacing) then decide.
const SETTLED_REL: f64 = 4.0 * f64::EPSILON;

/// An iterate has settled, one step early, when quadratic convergence predicts the next step
/// below this fraction of the tolerance (absolute, `tol.near(x)`). In Newton's quadratic
/// regime each step is `s_{k+1} ≈ C·s_k²`, so two steps give `C ≈ s_k/s_{k−1}²` and the error
/// of the current iterate, about the step not taken, `s_k³/s_{k−1}²`. The proof's points
/// `x ∓ δ` lie half a tolerance out: a sixteenth leaves a factor eight for a misprediction
/// (the proof then declines; nothing wrong is claimed). Linear convergence (a step ratio near
/// `(k − 1)/k` at a `k`-fold cluster) never predicts such a small step, nor does `x_tol = 0`.
const PREDICTED_TOL_FRACTION: f64 = 1.0 / 16.0;

/// Degrees the guess is tried for: cubics and quartics (tori, the quartic surfaces). The
/// proof works to degree 10 (the sizes [`no_root_on`] certifies without allocating), but on
/// Barth's sextic it proved only 47 % of the hits, and there the wasted iterations — chains
/// of dependent operations — cost more time than the proofs saved (840², two threads: user
/// time +3 % median, though 1.1 % fewer instructions; `paper-notes/isolation.md`).
pub(crate) const GUESS_DEGREES: std::ops::RangeInclusive<usize> = 3..=4;

/// What [`smallest_by_guess`] proved.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) enum Guess {
    /// The smallest root in the range is within the tolerance of this point.
    Root(f64),
    /// The range holds no root: Newton's iteration stepped past its end, and the Bernstein
    /// test of the whole range found no sign variation.
    NoRoot,
    /// Nothing proved: the caller isolates.
    Declined,
}

/// The smallest root of `c` in `(lo, hi]` within the tolerance `tol`, when Newton's iteration
/// from `lo` finds it and the three certificates of the module docs hold, or the proof that
/// there is none when the iteration steps past `hi`; [`Guess::Declined`] otherwise (a root
/// the iteration skipped, a sign no `f64` tier certifies, a range Descartes' rule cannot
/// clear). `(s_lo, s_hi)` are the certified signs of `p(lo)` (non-zero) and `p(hi)`; `slack`
/// bounds the true polynomial's distance from the stored one, as for the isolator, and
/// `range_slack` is its value on the whole range (`slack.at(max(|lo|, |hi|))`, which the
/// caller has already computed: a slack is a function evaluation per ray).
pub(crate) fn smallest_by_guess(
    c: &[f64],
    lo: f64,
    hi: f64,
    (s_lo, s_hi): (i8, i8),
    tol: Tolerance,
    (slack, range_slack): (Slack<'_>, f64),
) -> Guess {
    if !slack.is_some() && far_centroid(c, lo, hi).is_some() {
        // Roots clustered far away (a ray polynomial restricted far from its surface): each
        // Newton step gains only a factor (n − 1)/n there, and the search re-expands the
        // range at the cluster's centroid anyway.
        return Guess::Declined;
    }
    let x = match newton_from(c, lo, hi, tol) {
        Newton::Settled(x) => x,
        Newton::Beyond => {
            return if no_root_on(c, lo, hi, (s_lo, s_hi), range_slack) {
                Guess::NoRoot
            } else {
                Guess::Declined
            };
        }
        Newton::Failed => return Guess::Declined,
    };
    let delta = half_tol(tol.near(x));
    let (l, h) = probe_points(x, delta);
    if !(l > lo && h < hi) {
        return Guess::Declined;
    }
    let ((_, s_l), (_, s_h)) = certified_value_pair(c, l, h, slack.at(l.abs().max(h.abs())));
    if s_l != s_lo || s_h != -s_lo {
        return Guess::Declined;
    }
    let before_slack = slack.at(lo.abs().max(l.abs()));
    if no_root_on(c, lo, l, (s_lo, s_l), before_slack) {
        Guess::Root(x)
    } else {
        Guess::Declined
    }
}

/// How [`newton_from`] ended.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Newton {
    /// A step settled at this point.
    Settled(f64),
    /// A step went to `hi` or beyond (a hint that no root lies before `hi`).
    Beyond,
    /// A step went to `lo` or below, or was not finite, or none settled.
    Failed,
}

/// Newton's iteration from `lo`, while it stays inside `(lo, hi)`, until a step is below a
/// quarter of the tolerance there: the proposal [`smallest_by_guess`] then tries to prove.
/// From a start where the polynomial falls (or rises) monotonically to its first root the
/// iterates never leave the range; where it does not, they may jump past that root or out of
/// the range, and the proof or this function declines.
fn newton_from(c: &[f64], lo: f64, hi: f64, tol: Tolerance) -> Newton {
    // A compile-time length per degree, so that each Horner pass is unrolled.
    match c.len() {
        4 => newton_fixed::<4>(c, lo, hi, tol),
        5 => newton_fixed::<5>(c, lo, hi, tol),
        6 => newton_fixed::<6>(c, lo, hi, tol),
        7 => newton_fixed::<7>(c, lo, hi, tol),
        8 => newton_fixed::<8>(c, lo, hi, tol),
        9 => newton_fixed::<9>(c, lo, hi, tol),
        10 => newton_fixed::<10>(c, lo, hi, tol),
        11 => newton_fixed::<11>(c, lo, hi, tol),
        _ => Newton::Failed,
    }
}

/// [`newton_from`] for `N` coefficients.
fn newton_fixed<const N: usize>(c: &[f64], lo: f64, hi: f64, tol: Tolerance) -> Newton {
    let Ok(c) = <&[f64; N]>::try_from(c) else {
        return Newton::Failed;
    };
    let mut x = lo;
    // The previous step's length (0 before the first: no prediction).
    let mut last = 0.0f64;
    for _ in 0..MAX_GUESS_STEPS {
        let (v, d) = value_and_derivative(c, x);
        let step = v / d;
        let next = x - step;
        if next >= hi {
            return Newton::Beyond;
        }
        // (A NaN step fails here too.)
        if next.partial_cmp(&lo) != Some(std::cmp::Ordering::Greater) {
            return Newton::Failed;
        }
        x = next;
        // Settled: a step below a quarter of the tolerance, or at the rounding noise of `x`
        // (all `x_tol = 0` can ask for).
        let (length, near) = (step.abs(), tol.near(x));
        if length <= (SETTLED_TOL_FRACTION * near).max(SETTLED_REL * x.abs())
            || length * length * length <= PREDICTED_TOL_FRACTION * near * last * last
        {
            return Newton::Settled(x);
        }
        last = length;
    }
    Newton::Failed
}

/// `p(x)` and `p'(x)` with fused multiply–adds, the iteration's time being the latency of
/// their chain of dependent operations, not its instruction count: for cubics and quartics
/// (the degrees guessed) by Estrin's scheme, in powers of `x²` — three dependent operations
/// for the value instead of Horner's four, two for the derivative — and by Horner's rule
/// above.
#[inline(always)]
fn value_and_derivative(c: &[f64], x: f64) -> (f64, f64) {
    let x2 = x * x;
    match *c {
        // (c0 + c1·x) + x²·(c2 + c3·x); (c1 + 2c2·x) + x²·3c3.
        [c0, c1, c2, c3] => (
            x2.mul_add(c3.mul_add(x, c2), c1.mul_add(x, c0)),
            x2.mul_add(3.0 * c3, (2.0 * c2).mul_add(x, c1)),
        ),
        // (c0 + c1·x) + x²·((c2 + c3·x) + x²·c4); (c1 + 2c2·x) + x²·(3c3 + 4c4·x).
        [c0, c1, c2, c3, c4] => (
            x2.mul_add(x2.mul_add(c4, c3.mul_add(x, c2)), c1.mul_add(x, c0)),
            x2.mul_add((4.0 * c4).mul_add(x, 3.0 * c3), (2.0 * c2).mul_add(x, c1)),
        ),
        _ => horner_and_derivative(c, x),
    }
}

/// `p(x)` and `p'(x)` by Horner's rule with fused multiply–adds.
#[inline(always)]
fn horner_and_derivative(c: &[f64], x: f64) -> (f64, f64) {
    let (mut v, mut d) = (0.0f64, 0.0f64);
    for &ci in c.iter().rev() {
        d = d.mul_add(x, v);
        v = v.mul_add(x, ci);
    }
    (v, d)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::eval_bound::certified_sign;
    use crate::testutil::stored_roots;
    use crate::univariate::Poly;
    use rand::{Rng, SeedableRng};

    /// `c·(x² − 2a·x + a² + b²)`: a factor with the roots `a ± ib`.
    fn times_pair(c: &[f64], a: f64, b: f64) -> Vec<f64> {
        let q = [a * a + b * b, -2.0 * a, 1.0];
        let mut out = vec![0.0; c.len() + 2];
        for (i, &ci) in c.iter().enumerate() {
            for (j, &qj) in q.iter().enumerate() {
                out[i + j] += ci * qj;
            }
        }
        out
    }

    /// Every answer of the guess is the stored polynomial's smallest root in `(lo, hi]` (the
    /// exact Sturm oracle's), within half the tolerance: on 4 000 random polynomials of
    /// degrees 3–10 with real roots on both sides of the range's start, close pairs and
    /// complex pairs near the axis (where Newton's iteration from the start jumps past the
    /// first root or wanders), at an absolute tolerance of 1e-12 and of 0; and every range
    /// it proves empty is empty. The guess must also answer a share of them, or the path
    /// would be dead.
    #[test]
    fn guessed_roots_are_the_smallest_roots() {
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(311);
        let (mut answered, mut with_root, mut misses) = ([0; 2], [0; 2], 0);
        for k in 0..4000 {
            let degree = rng.gen_range(3..=10);
            let pairs = rng.gen_range(0..=degree / 2);
            let mut real: Vec<f64> = (0..degree - 2 * pairs)
                .map(|_| rng.gen_range(-2.0..6.0))
                .collect();
            if k % 5 == 0 && !real.is_empty() {
                // A close pair: a ray grazing a sheet.
                let r = real[0] + 1e-7 * rng.gen_range(-1.0..1.0);
                real.push(r);
                real.remove(1.min(real.len() - 1));
            }
            let mut c = Poly::from_roots(&real).coeffs().to_vec();
            for _ in 0..pairs {
                let b = 10f64.powf(rng.gen_range(-6.0..0.0));
                c = times_pair(&c, rng.gen_range(-2.0..6.0), b);
            }
            let lo = rng.gen_range(-1.0..1.0);
            let hi = lo + rng.gen_range(0.5..8.0);
            let tol = if k % 2 == 0 { 1e-12 } else { 0.0 };
            let s_lo = certified_sign(&c, lo, 0.0);
            if s_lo == 0 {
                continue;
            }
            let p = Poly::new(c.clone());
            let roots = stored_roots(&p, lo, hi);
            with_root[k % 2] += usize::from(!roots.is_empty());
            let s_hi = certified_sign(&c, hi, 0.0);
            let tol_abs = Tolerance::absolute(tol);
            let x = match smallest_by_guess(&c, lo, hi, (s_lo, s_hi), tol_abs, (Slack::NONE, 0.0)) {
                Guess::Root(x) => x,
                Guess::NoRoot => {
                    misses += 1;
                    assert!(
                        roots.is_empty(),
                        "case {k}: no root claimed for {c:?} on ({lo}, {hi}], oracle {roots:?}"
                    );
                    continue;
                }
                Guess::Declined => continue,
            };
            answered[k % 2] += 1;
            let first = *roots
                .first()
                .unwrap_or_else(|| panic!("case {k}: claimed {x} for {c:?} on ({lo}, {hi}]"));
            let allowed = (0.5 * tol).max(2.0 * f64::EPSILON * first.abs());
            assert!(
                (x - first).abs() <= allowed,
                "case {k}: {x} is not within {allowed} of the smallest root {first} of {c:?} on ({lo}, {hi}]"
            );
        }
        // Measured: 545 of 1 391 at 1e-12 and 256 of 1 339 at 0 (whose proof needs the
        // neighbouring doubles of the root decided), and 221 misses; the renderer's torus
        // rays, which start outside the surface, fare far better (344 of 373 hits,
        // `paper-notes/isolation.md`).
        assert!(
            answered[0] * 10 >= with_root[0] * 3 && answered[1] * 10 >= with_root[1] && misses > 0,
            "the guess answered only {answered:?} of {with_root:?} queries with a root \
             (tolerance 1e-12, 0) and proved {misses} misses"
        );
    }

    /// Estrin's scheme for cubics and quartics agrees with Horner's rule up to rounding: on
    /// random coefficients and points, both within `8ε·Σ|cᵢ||x|ⁱ` (value) and
    /// `8ε·Σ i|cᵢ||x|ⁱ⁻¹` (derivative) of each other — a misplaced coefficient or factor
    /// would be off by the size of a term.
    #[test]
    fn estrin_matches_horner_up_to_rounding() {
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(17);
        for _ in 0..2000 {
            let n = rng.gen_range(4..=5);
            let c: Vec<f64> = (0..n).map(|_| rng.gen_range(-10.0..10.0)).collect();
            let x = rng.gen_range(-4.0..4.0);
            let (v, d) = value_and_derivative(&c, x);
            let (hv, hd) = horner_and_derivative(&c, x);
            let mag = |k: usize| -> f64 {
                (k..n)
                    .map(|i| (i as f64).powi(k as i32) * c[i].abs() * x.abs().powi((i - k) as i32))
                    .sum()
            };
            assert!(
                (v - hv).abs() <= 8.0 * f64::EPSILON * mag(0),
                "{c:?} at {x}: {v} vs {hv}"
            );
            assert!(
                (d - hd).abs() <= 8.0 * f64::EPSILON * mag(1),
                "{c:?} at {x}: {d} vs {hd}"
            );
        }
    }

    /// Where Newton's iteration settles on a simple root — by a small step or by the step that
    /// quadratic convergence predicts — it is within a sixteenth of the tolerance of that root
    /// (up to what `f64` resolves there), well inside the proof's `δ` = half the tolerance: on 2 000
    /// random real-rooted cubics and quartics with roots at least 0.05 apart, started left of
    /// them all, measured against the exact roots of the stored coefficients. A prediction from steps not yet in the quadratic regime would stop far out.
    #[test]
    fn a_settled_iterate_is_well_inside_the_proofs_margin() {
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(29);
        let mut settled = 0;
        for _ in 0..2000 {
            let degree = rng.gen_range(3..=4);
            let mut roots: Vec<f64> = Vec::new();
            while roots.len() < degree {
                let r = rng.gen_range(0.5..5.0);
                if roots.iter().all(|&q: &f64| (q - r).abs() >= 0.05) {
                    roots.push(r);
                }
            }
            let p = Poly::from_roots(&roots);
            let c = p.coeffs().to_vec();
            // The stored polynomial's roots (its coefficients are rounded), exactly.
            let roots = stored_roots(&p, 0.0, 6.0);
            for tol in [1e-12, 1e-8] {
                let Newton::Settled(x) = newton_from(&c, 0.0, 6.0, Tolerance::absolute(tol)) else {
                    continue;
                };
                settled += 1;
                let err = roots
                    .iter()
                    .map(|r| (x - r).abs())
                    .fold(f64::INFINITY, f64::min);
                // What `f64` can resolve: the evaluation's rounding over the slope.
                let magnitude: f64 = c.iter().rev().fold(0.0, |m, ci| m * x.abs() + ci.abs());
                let slope = horner_and_derivative(&c, x).1.abs();
                let noise = 8.0 * f64::EPSILON * magnitude / slope + 4.0 * f64::EPSILON * x.abs();
                assert!(
                    err <= tol / 16.0 + noise,
                    "settled at {x}, {err} from the nearest of {roots:?} (tol {tol})"
                );
            }
        }
        assert!(settled >= 3000, "only {settled} of 4000 runs settled");
    }

    /// Newton's iteration from 0 on `(x − 2.8)(x − 5)(x² − 0.8x + 0.41)` (found by a search:
    /// the complex pair 0.4 ± 0.5i throws the first step past 2.8) settles on the root 5;
    /// the Bernstein test of `(0, 5 − δ]` sees the root 2.8 and the guess is declined, so the
    /// query answers 2.8. Without that test the guess would return 5.
    #[test]
    fn a_guess_past_the_first_root_is_declined() {
        let c = [5.74, -14.398, 20.65, -8.6, 1.0];
        let tol = Tolerance::absolute(1e-12);
        let Newton::Settled(x) = newton_from(&c, 0.0, 10.0, tol) else {
            panic!("Newton did not settle");
        };
        assert!((x - 5.0).abs() < 1e-6, "Newton went to {x}");
        let s_lo = certified_sign(&c, 0.0, 0.0);
        assert_eq!(
            smallest_by_guess(&c, 0.0, 10.0, (s_lo, 1), tol, (Slack::NONE, 0.0)),
            Guess::Declined
        );
        let r = Poly::new(c.to_vec())
            .smallest_root_with(
                0.0,
                10.0,
                &crate::RootOptions::new(1e-12),
                &mut Default::default(),
            )
            .expect("a root");
        assert!((r - 2.8).abs() < 1e-9, "the query answered {r}");
    }
}

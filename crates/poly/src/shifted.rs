//! [`Shift`]: a piece that `f64` could not decide, re-expanded at its end nearer 0 in
//! double-double and rounded back to `f64` coefficients, each with a rigorous radius — so the
//! piece is isolated and refined by the `f64` machinery with a value slack, instead of by
//! double-double de Casteljau and compensated evaluations.
//!
//! Why it works: the `f64` search on the stored coefficients fails where `|p|` is below the
//! rounding error of the *expansion at 0*, `γ·Σ|cₖ||t|ᵏ` — for a ray polynomial restricted
//! 10⁴ units from a torus, 10¹⁶ times the values near the roots. Re-expanded at a point `e` of
//! the piece, `q(u) = p(e + u)` has coefficients of the size of the values there, and its
//! `f64` rounding costs `u·Σ|qⱼ||u|ʲ`, which is small against `|q|` away from the roots. The
//! Taylor shift itself is done in double-double, so its own error (`γ_dd(2n)` times the shift
//! of `|c|` by `|e|`) is negligible.
//!
//! Guarantee: with `q̂` the rounded coefficients and `ρⱼ` the radii, `|q(u) − q̂(u)| ≤ Σρⱼ|u|ʲ`
//! for every real `u` ([`Shift::slack`]), and `q` has the stored polynomial's degree with the
//! same leading coefficient, as the slack argument of `bernstein.rs` requires. A search on `q̂`
//! with that slack certifies the roots of the stored `p` on `(e + u_lo, e + u_hi]`. See
//! `paper-notes/isolation.md`, "Shifted `f64` tier".

use smallvec::SmallVec;

use crate::bernstein::Bracket;
use crate::double_double::{DD_UNDERFLOW, DD_UNIT, Dd, gamma_u, taylor_shift_into, two_sum};
use crate::multiprec::{Tier, point_sign, refine_wide};
use crate::refine::{Refined, refine_bracket, refine_exact_offset};
use crate::root_interval::RootInterval;
use crate::root_options::{RefineMethod, Tolerance};
use crate::stats::RootStats;
use crate::stored::Stored;

/// Highest degree shifted: the double-double shift costs `n²/2` products, and above this
/// the per-node tiers of `multiprec.rs` are no dearer (the same bound as `dd_bernstein.rs`).
const MAX_DEGREE: usize = 56;

/// Most neighbouring `f64` numbers [`Shift::pin`] steps across to find the sign change: the
/// refined value is within two spacings of the root (half a tolerance below one spacing, one
/// spacing of the shifted variable, and half a spacing of rounding `e + u`), and one more
/// covers a binade boundary, where the spacing halves.
const PIN_STEPS: u32 = 4;

/// A piece `(lo, hi]` of the stored polynomial `p`, re-expanded at its end `at` nearer 0.
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct Shift {
    /// The expansion point `e`: an end of the piece.
    pub(crate) at: f64,
    /// The piece in the shifted variable `u = t − e`: `(0, hi − lo]` or `(lo − hi, 0]`,
    /// exact.
    pub(crate) range: (f64, f64),
    /// `q̂`: the coefficients of `p(e + u)`, rounded to `f64` (lowest first).
    pub(crate) q: SmallVec<[f64; 8]>,
    /// `ρⱼ ≥ |qⱼ − q̂ⱼ|`, `qⱼ` the exact coefficients of the stored `p(e + u)`.
    radii: SmallVec<[f64; 8]>,
}

impl Shift {
    /// The shift of the piece `(lo, hi]` of `c` (finite ends on one side of 0, the end nearer
    /// 0 not 0 itself: there the shift changes nothing), or `None` when it does not apply:
    /// the width is not exact in `f64`, the degree is outside `2..=MAX_DEGREE`, or something
    /// overflows.
    pub(crate) fn new(c: &[f64], (lo, hi): (f64, f64)) -> Option<Shift> {
        let n = c.len() - 1;
        if !(2..=MAX_DEGREE).contains(&n)
            || lo.is_nan()
            || hi.is_nan()
            || lo >= hi
            || (lo < 0.0 && hi > 0.0)
        {
            return None;
        }
        // The end nearer 0: every |u| in the piece is then at most |t|, so a spacing of u is
        // at most a spacing of t, and the refinement in u loses nothing.
        let (at, other) = if lo >= 0.0 { (lo, hi) } else { (hi, lo) };
        if at == 0.0 {
            return None;
        }
        let (w, w_err) = two_sum(other, -at);
        if w_err != 0.0 {
            return None;
        }
        let mut v: SmallVec<[Dd; 8]> = SmallVec::from_elem(Dd::ZERO, n + 1);
        taylor_shift_into(c, at, &mut v);
        // The shift of |c| by |e| in f64 (non-negative operands: each of its 2n roundings
        // per path is relative u downwards at most, so (1 + γ(2n)) makes it an upper bound),
        // times γ_dd(2n), bounds the double-double shift's error per coefficient.
        let mut a: SmallVec<[f64; 8]> = SmallVec::from_elem(0.0, n + 1);
        let e = at.abs();
        a[0] = c[n].abs();
        for k in (0..n).rev() {
            for i in (1..=n - k).rev() {
                a[i] = a[i] * e + a[i - 1];
            }
            a[0] = a[0] * e + c[k].abs();
        }
        let gamma_f = gamma_u(2 * n, 0.5 * f64::EPSILON);
        let gamma_dd = gamma_u(2 * n, DD_UNIT);
        // Underflow: at most DD_UNDERFLOW per operation, each amplified by at most (1 + |e|)
        // per remaining Horner step; at most (n + 1)² operations feed a coefficient.
        let tiny = DD_UNDERFLOW * (1.0 + e).powi(n as i32) * ((n + 1) * (n + 1)) as f64;
        let mut q = SmallVec::with_capacity(n + 1);
        let mut radii = SmallVec::with_capacity(n + 1);
        for (vj, aj) in v.iter().zip(&a) {
            // Rounding the double-double to its high part errs by exactly |lo|.
            let r =
                (vj.lo.abs() + gamma_dd * aj * (1.0 + gamma_f) + tiny) * (1.0 + 4.0 * f64::EPSILON);
            if !(vj.hi.is_finite() && r.is_finite()) {
                return None;
            }
            q.push(vj.hi);
            radii.push(r);
        }
        // w = other − e: positive from lo, negative from hi.
        let range = if at == lo { (0.0, w) } else { (w, 0.0) };
        Some(Shift {
            at,
            range,
            q,
            radii,
        })
    }

    /// `Σρⱼrʲ` rounded up: a bound on `|p(e + u) − q̂(u)|` for every `|u| ≤ r`.
    pub(crate) fn slack(&self, r: f64) -> f64 {
        let r = r.abs() * (1.0 + 2.0 * f64::EPSILON);
        let s = self.radii.iter().rev().fold(0.0, |s, &rho| s * r + rho);
        s * (1.0 + gamma_u(2 * self.radii.len(), 0.5 * f64::EPSILON))
    }

    /// The bracket `b` (in `u`) as an interval of `t` with `f64` ends rounded outwards.
    pub(crate) fn interval(&self, b: &Bracket) -> RootInterval<f64> {
        RootInterval {
            lo: sum_down(self.at, b.lo),
            hi: sum_up(self.at, b.hi),
        }
    }

    /// Refines the root of the stored polynomial `p` in the shifted bracket `b` (certified
    /// against [`slack`](Self::slack)) to the tolerance `tol` in `t`.
    ///
    /// # Accuracy
    /// As [`refine_bracket`]: within `tol` of the root, or within one `f64` spacing of it when
    /// the tolerance is below that (then the lower of the two adjacent `f64` numbers around
    /// the root, each sign certified on the stored polynomial). Refinement in `u` goes to half
    /// the tolerance; rounding `e + u` adds at most half a spacing, which is checked; when the
    /// sum is not within the tolerance, [`pin`] walks to the sign change. When the slack stops
    /// the refinement in `u`, the bracket reached is rounded outwards to `f64` ends in `t` and
    /// refined with adaptive-precision signs of the stored polynomial (`refine_wide`; a root of
    /// the stored polynomial within one spacing outside the shifted bracket could then be the
    /// one returned, which the accuracy above allows); if its end signs are not certified, or
    /// the walk fails, it is finished with exact signs on its exact ends `e + u` (counted in
    /// [`RootStats::refine_fallbacks`]).
    pub(crate) fn refine(
        &self,
        p: Stored<'_>,
        b: &Bracket,
        tol: Tolerance,
        method: RefineMethod,
        stats: &mut RootStats,
    ) -> f64 {
        let c = p.coeffs();
        let iv = self.interval(b);
        let x_tol = tol.on(iv.lo, iv.hi);
        let slack = self.slack(b.lo.abs().max(b.hi.abs()));
        let half = Tolerance::absolute(0.5 * x_tol);
        let stuck = match refine_bracket(&self.q, *b, half, method, slack, stats) {
            Refined::Root(u) => {
                let (r, err) = two_sum(self.at, u);
                // |u − u*| ≤ max(x_tol/2, one spacing of u); then the rounding of e + u.
                let spacing_u = u.abs().next_up() - u.abs();
                if (0.5 * x_tol).max(spacing_u) + err.abs() <= x_tol * (1.0 - f64::EPSILON) {
                    return r;
                }
                if let Some(r) = pin(c, r, b.s_lo) {
                    return r;
                }
                *b
            }
            Refined::Stuck(stuck) => stuck,
        };
        // The slack stopped the refinement (an ill-conditioned root, as of a ray grazing the
        // surface): the bracket mapped outwards to t, refined with adaptive-precision signs
        // of the stored polynomial, when its end signs certify it.
        let iv = self.interval(&stuck);
        let ends_certified = point_sign(c, iv.lo, Tier::Dd).0 == stuck.s_lo
            && point_sign(c, iv.hi, Tier::Dd).0 == -stuck.s_lo;
        if ends_certified
            && let Some(r) = refine_wide(c, Bracket::new(iv.lo, iv.hi, stuck.s_lo), tol, stats)
        {
            return r;
        }
        stats.refine_fallbacks += 1;
        p.with_poly(|p| refine_exact_offset(p, self.at, stuck, tol))
    }
}

/// `a + b` rounded down (the exact sum's error term tells the direction).
fn sum_down(a: f64, b: f64) -> f64 {
    let (s, e) = two_sum(a, b);
    if e < 0.0 { s.next_down() } else { s }
}

/// `a + b` rounded up.
fn sum_up(a: f64, b: f64) -> f64 {
    let (s, e) = two_sum(a, b);
    if e > 0.0 { s.next_up() } else { s }
}

/// The lower of the two adjacent `f64` numbers whose certified signs on the stored `c` change
/// from `s_lo` to `−s_lo`, found by stepping from `r` (within [`PIN_STEPS`] spacings of the
/// root); `None` when a sign cannot be certified or no change is met. (Were another root of
/// the stored polynomial within those few spacings, the change found could be its: the
/// answer is then within a few spacings of the bracketed root.)
fn pin(c: &[f64], r: f64, s_lo: i8) -> Option<f64> {
    let sign = |x: f64| point_sign(c, x, Tier::Dd).0;
    let s = sign(r);
    if s == 0 {
        return None;
    }
    let mut x = r;
    for _ in 0..PIN_STEPS {
        if s == s_lo {
            let up = x.next_up();
            match sign(up) {
                t if t == -s_lo => return Some(x),
                t if t == s_lo => x = up,
                _ => return None,
            }
        } else {
            let down = x.next_down();
            match sign(down) {
                t if t == s_lo => return Some(down),
                t if t == -s_lo => x = down,
                _ => return None,
            }
        }
    }
    None
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::root_options::RootOptions;
    use crate::scalar::{rat_from_f64, rat_to_f64};
    use crate::testutil::{planted_f64, stored_roots};
    use crate::univariate::Poly;

    /// The exact coefficients of `p(e + u)` for the stored `c`.
    fn exact_shift(c: &[f64], e: f64) -> Vec<crate::scalar::Rat> {
        let n = c.len() - 1;
        let e = rat_from_f64(e).unwrap();
        let mut v = vec![crate::scalar::Rat::from_integer(0.into()); n + 1];
        for k in (0..=n).rev() {
            for i in (1..=n - k).rev() {
                v[i] = &v[i] * &e + &v[i - 1];
            }
            v[0] = &v[0] * &e + rat_from_f64(c[k]).unwrap();
        }
        v
    }

    #[test]
    fn radii_bound_the_exact_re_expansion() {
        // Ray-like quartics and sextics re-expanded far from 0, and a degree-20 product near
        // its roots: every rounded coefficient is within its radius of the exact one, and
        // the radius is not vacuous (within 10⁻¹² of the coefficients' scale there).
        let cases: [(Poly<f64>, f64); 4] = [
            (planted_f64(&[9997.25, 9999.5, 10001.0, 10003.75]), 9996.0),
            (planted_f64(&[-1e4, -9999.0, -9998.5]), -9997.75),
            (planted_f64(&[0.1, 0.3, 0.35, 0.7, 0.9, 1.3]), 0.33),
            (
                planted_f64(&(1..=20).map(|k| k as f64).collect::<Vec<_>>()),
                10.5,
            ),
        ];
        for (p, e) in cases {
            let c = p.coeffs();
            let (lo, hi) = if e > 0.0 { (e, 2.0 * e) } else { (2.0 * e, e) };
            let shift = Shift::new(c, (lo, hi)).expect("applies");
            assert_eq!(shift.at, e, "expanded at the end nearer 0");
            let exact = exact_shift(c, e);
            let scale = shift.q.iter().fold(0.0f64, |m, q| m.max(q.abs()));
            for (j, (q, want)) in shift.q.iter().zip(&exact).enumerate() {
                let err = rat_to_f64(&(rat_from_f64(*q).unwrap() - want)).abs();
                assert!(
                    err <= shift.radii[j],
                    "{p:?} at {e}: coefficient {j} off by {err}, radius {}",
                    shift.radii[j]
                );
                assert!(
                    shift.radii[j] <= 1e-12 * scale,
                    "radius {j} is {}",
                    shift.radii[j]
                );
            }
        }
    }

    /// The product of two coefficient lists (lowest first).
    fn product(a: &[f64], b: &[f64]) -> Vec<f64> {
        let mut out = vec![0.0; a.len() + b.len() - 1];
        for (i, x) in a.iter().enumerate() {
            for (j, y) in b.iter().enumerate() {
                out[i + j] += x * y;
            }
        }
        out
    }

    #[test]
    fn far_root_cluster_is_decided_in_f64_after_re_expansion() {
        // A ray polynomial restricted 10⁴ from its surface: two real roots and a complex pair
        // near t = 10⁴, where the stored expansion's rounding (~10¹⁶·u) swamps every value. The
        // piece is re-expanded once and decided in f64, with no double-double subdivision and
        // no exact arithmetic; the mirror image on the negative side (expanded at its upper
        // end: the orientation a first version got wrong, missing two roots) likewise.
        let real = [9998.125, 9999.5];
        let pair = [10001.0 * 10001.0 + 0.25, -2.0 * 10001.0, 1.0];
        let c = product(planted_f64(&real).coeffs(), &pair);
        for sign in [1.0, -1.0] {
            // p(sign·t): the roots mirrored.
            let coeffs = c
                .iter()
                .enumerate()
                .map(|(k, &ck)| if k % 2 == 1 { sign * ck } else { ck })
                .collect();
            let q = Poly::new(coeffs);
            let (lo, hi) = if sign > 0.0 {
                (0.0, 10005.0)
            } else {
                (-10005.0, 0.0)
            };
            // The stored coefficients' own roots (rounding moved them by ~0.03).
            let want = stored_roots(&q, lo, hi);
            assert_eq!(want.len(), 2, "{sign}: two real roots stored");
            let mut stats = RootStats::default();
            let opts = RootOptions::new(1e-9);
            let roots = q.real_roots_with(lo, hi, &opts, &mut stats).unwrap();
            assert_eq!(roots.len(), 2, "{sign}: {roots:?}");
            for (r, w) in roots.iter().zip(&want) {
                assert!((r - w).abs() <= 1e-9, "{sign}: {r} vs {w}");
            }
            let first = q.smallest_root_with(lo, hi, &opts, &mut stats).unwrap();
            assert!((first - want[0]).abs() <= 1e-9, "{sign}: smallest {first}");
            assert!(stats.shifted_pieces >= 1, "{sign}: re-expanded: {stats:?}");
            assert_eq!(stats.multiprecision_pieces, 0, "{sign}: {stats:?}");
            assert_eq!(
                stats.exact_fallbacks + stats.refine_fallbacks,
                0,
                "{sign}: {stats:?}"
            );
        }
    }
}

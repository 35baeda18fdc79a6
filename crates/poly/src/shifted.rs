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
use crate::univariate::root_bound_of;

/// Highest degree shifted: the double-double shift costs `n²/2` products, and above this
/// the per-node tiers of `multiprec.rs` are no dearer (the same bound as `dd_bernstein.rs`).
const MAX_DEGREE: usize = 56;

/// Most neighbouring `f64` numbers [`Shift::pin`] steps across to find the sign change: the
/// refined value is within two spacings of the root (half a tolerance below one spacing, one
/// spacing of the shifted variable, and half a spacing of rounding `e + u`), and one more
/// covers a binade boundary, where the spacing halves.
const PIN_STEPS: u32 = 4;

/// [`far_centroid`] sends a query to [`Shift::around_cluster`] when `|p(e)|` at the roots'
/// centroid `e` is at most this fraction of `Σ|cₖ||e|ᵏ`: within `2^21` of `f64`'s rounding
/// error bound `~2n·u·Σ|cₖ||e|ᵏ` for a quartic. Values nearer the roots, smaller still, are
/// then within a few error bounds of zero, where the search of the expansion at 0 gets stuck
/// and its piece is re-expanded anyway. Measured on the peers bench's corpora: the far-eye
/// torus rays cancel to 10⁻¹⁷–10⁻¹⁶ (23 of 500 exactly to 0); of the torus rays restricted at
/// the bounding sphere, 489 of 500 stop at [`FAR_CLUSTER_SPREAD`] and the other 11 cancel
/// only to 10⁻³–10⁻².
const FAR_CLUSTER_CANCELLATION: f64 = 1.0 / 4_294_967_296.0;

/// [`far_centroid`]'s first test: `|Σdᵢ²|`, the sum of the roots' squared offsets from their
/// centroid `e` (as far as the coefficients show it), is at most this fraction of
/// `n(n−1)e²`: an rms offset within about `√((n−1)/256)·|e|`, `0.11|e|` for a quartic. The
/// cancellation test that follows needs offsets near `2⁻⁸|e|` for a quartic, so this only
/// spares the Horner pass to queries whose roots spread as far as they lie from 0, as the
/// renderer's do.
const FAR_CLUSTER_SPREAD: f64 = 1.0 / 256.0;

/// A piece `(lo, hi]` of the stored polynomial `p`, re-expanded at its end `at` nearer 0
/// ([`Shift::new`]) or at the centroid of a far cluster of roots ([`Shift::around_cluster`]).
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct Shift {
    /// The expansion point `e`: an end of the piece, or a point inside it with every `|u|`
    /// of the piece at most `|e|/2` (so, as from the end nearer 0, `|u| ≤ |t|`).
    pub(crate) at: f64,
    /// The piece in the shifted variable `u = t − e`: `(0, hi − lo]` or `(lo − hi, 0]`, or
    /// around 0 for a cluster; the roots of `p` in it are those of the query's range.
    pub(crate) range: (f64, f64),
    /// `q̂`: the coefficients of `p(e + u)`, rounded to `f64` (lowest first).
    pub(crate) q: Coeffs,
    /// `ρⱼ ≥ |qⱼ − q̂ⱼ|`, `qⱼ` the exact coefficients of the stored `p(e + u)`.
    radii: Coeffs,
}

/// Coefficients or their radii, lowest first (inline up to degree 7).
type Coeffs = SmallVec<[f64; 8]>;

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
        let (q, radii) = expand(c, at)?;
        // w = other − e: positive from lo, negative from hi.
        let range = if at == lo { (0.0, w) } else { (w, 0.0) };
        Some(Shift {
            at,
            range,
            q,
            radii,
        })
    }

    /// The far-cluster re-expansion of a whole query range `(lo, hi]` (finite, certified
    /// non-zero end signs `s`) at `e` = [`far_centroid`]`(c, lo, hi)`: a radius `r` with
    /// every real root within `r` of `e` is certified for the exact `p(e + u)`
    /// ([`cluster_radius`]), and the piece becomes `(lo, hi] ∩ (e − r, e + r)` in `u` —
    /// everything outside holds no root. Returns the shift and the certified signs of `p` at
    /// its ends in `u`, or `None` when this does not apply (a cluster wider than `|e|/2`, an
    /// end `lo − e` or `hi − e` inside the cluster that is not exact in `f64`, overflow).
    ///
    /// Why: a ray polynomial restricted 10⁴ units from a torus has its four roots, complex
    /// ones included, within a few units of the ray's closest approach to the torus's
    /// centre, which is `e`. The `f64` search of the expansion at 0 can only close in on them
    /// until its error bound swamps the values, and the piece it is stuck on is re-expanded
    /// anyway; this skips that search (`paper-notes/isolation.md`, "Far clusters").
    #[inline(never)]
    pub(crate) fn around_cluster(
        c: &[f64],
        e: f64,
        (lo, hi): (f64, f64),
        (s_lo, s_hi): (i8, i8),
    ) -> Option<(Shift, (i8, i8))> {
        let n = c.len() - 1;
        let (q, radii) = expand(c, e)?;
        let r = cluster_radius(&q, &radii)?;
        if r > 0.5 * e.abs() {
            return None;
        }
        // Signs of p(e + u) beyond the cluster: that of the leading coefficient to the
        // right, times (−1)ⁿ to the left.
        let s_right: i8 = if c[n] > 0.0 { 1 } else { -1 };
        let s_left = if n.is_multiple_of(2) {
            s_right
        } else {
            -s_right
        };
        // An end outside the cluster is replaced by the cluster's edge. (Rounding is
        // monotone: a rounded `lo − e` below the `f64` number −r means the exact one is.)
        let (d_lo, d_lo_err) = two_sum(lo, -e);
        let (u_lo, su_lo) = if d_lo < -r {
            (-r, s_left)
        } else if d_lo_err == 0.0 {
            (d_lo, s_lo)
        } else {
            return None;
        };
        let (d_hi, d_hi_err) = two_sum(hi, -e);
        let (u_hi, su_hi) = if d_hi > r {
            (r, s_right)
        } else if d_hi_err == 0.0 {
            (d_hi, s_hi)
        } else {
            return None;
        };
        let shift = Shift {
            at: e,
            range: (u_lo, u_hi),
            q,
            radii,
        };
        Some((shift, (su_lo, su_hi)))
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

/// The centroid `e = −c_{n−1}/(n·c_n)` of the roots of `c` (complex ones included) when it
/// lies in `(lo, hi)` and the values there cancel to [`FAR_CLUSTER_CANCELLATION`] of
/// `Σ|cₖ||e|ᵏ` — roots clustered far from 0 against their spread — for
/// [`Shift::around_cluster`]; else `None`. Degrees `3..=MAX_DEGREE` (lower ones have closed
/// forms). Cheap, because every query of the certified search without a value slack asks:
/// a few products, and the Horner pass only for the rare query that passes them.
#[inline]
pub(crate) fn far_centroid(c: &[f64], lo: f64, hi: f64) -> Option<f64> {
    let n = c.len().wrapping_sub(1);
    if !(3..=MAX_DEGREE).contains(&n) {
        return None;
    }
    // First, cheaply: with dᵢ the roots' offsets from e, Σdᵢ² = n(n−1)e² − 2c_{n−2}/c_n,
    // which is ((n−1)c²_{n−1} − 2n·c_{n−2}c_n)/(n·c_n²); |Σdᵢ²| ≤ Σ|dᵢ|², so a sum far from
    // 0 against n(n−1)e² rules a tight cluster out (complex offsets can cancel in it, hence
    // the Horner test after). No division until it passes.
    let (a, b, lead) = (c[n - 1], c[n - 2], c[n]);
    let m = (n - 1) as f64 * a * a;
    // (NaN from an overflow passes on to the Horner test, which refuses it.)
    if (m - 2.0 * n as f64 * b * lead).abs() > FAR_CLUSTER_SPREAD * m {
        return None;
    }
    let e = -a / (n as f64 * lead);
    // (Also false for NaN.)
    if !(e > lo && e < hi) {
        return None;
    }
    let ae = e.abs();
    let (mut v, mut s) = (0.0f64, 0.0f64);
    for &ck in c.iter().rev() {
        v = v * e + ck;
        s = s * ae + ck.abs();
    }
    (v.abs() <= FAR_CLUSTER_CANCELLATION * s).then_some(e)
}

/// `q̂`, the coefficients of `p(e + u)` for the stored `c` computed in double-double and
/// rounded to `f64`, and their radii `ρⱼ ≥ |qⱼ − q̂ⱼ|`; `None` when something overflows.
fn expand(c: &[f64], at: f64) -> Option<(Coeffs, Coeffs)> {
    let n = c.len() - 1;
    // (Plain slices of the small vectors in the loops: indexing a `SmallVec` checks where
    // it lives on every access, a third of this function's instructions on quartics.)
    let mut v: SmallVec<[Dd; 8]> = SmallVec::from_elem(Dd::ZERO, n + 1);
    let v = v.as_mut_slice();
    taylor_shift_into(c, at, v);
    // The shift of |c| by |e| in f64 (non-negative operands: each of its 2n roundings
    // per path is relative u downwards at most, so (1 + γ(2n)) makes it an upper bound),
    // times γ_dd(2n), bounds the double-double shift's error per coefficient.
    let mut a: Coeffs = SmallVec::from_elem(0.0, n + 1);
    let a = a.as_mut_slice();
    let e = at.abs();
    a[0] = c[n].abs();
    // Exclusive ranges, as in `bernstein::bernstein_on` (unrolled loops).
    for k in (0..n).rev() {
        for i in (1..n - k + 1).rev() {
            a[i] = a[i] * e + a[i - 1];
        }
        a[0] = a[0] * e + c[k].abs();
    }
    let gamma_f = gamma_u(2 * n, 0.5 * f64::EPSILON);
    let gamma_dd = gamma_u(2 * n, DD_UNIT);
    // Underflow: at most DD_UNDERFLOW per operation, each amplified by at most (1 + |e|)
    // per remaining Horner step; at most (n + 1)² operations feed a coefficient.
    let tiny = DD_UNDERFLOW * (1.0 + e).powi(n as i32) * ((n + 1) * (n + 1)) as f64;
    let mut q: Coeffs = SmallVec::from_elem(0.0, n + 1);
    let mut radii: Coeffs = SmallVec::from_elem(0.0, n + 1);
    let mut finite = true;
    for (((vj, aj), qj), rj) in v
        .iter()
        .zip(&*a)
        .zip(q.as_mut_slice())
        .zip(radii.as_mut_slice())
    {
        // Rounding the double-double to its high part errs by exactly |lo|.
        let r = (vj.lo.abs() + gamma_dd * aj * (1.0 + gamma_f) + tiny) * (1.0 + 4.0 * f64::EPSILON);
        finite &= vj.hi.is_finite() && r.is_finite();
        *qj = vj.hi;
        *rj = r;
    }
    finite.then_some((q, radii))
}

/// A radius `r` (an `f64`) with every real root of the exact `q` (coefficients within
/// `radii` of `q̂`) strictly within `r` of 0, or `None` when the leading coefficient is not
/// certainly non-zero or something overflows.
///
/// Cauchy's and Fujiwara's bounds grow with every `|qⱼ|`, `j < n`, and shrink with `|qₙ|`, so
/// [`root_bound_of`] taken on the magnitudes `Bⱼ = |q̂ⱼ| + ρⱼ` and `L = |q̂ₙ| − ρₙ > 0` bounds
/// the roots of every polynomial within the radii (the rounding of `Bⱼ` and `L` themselves is
/// one unit each, inside [`ROOT_BOUND_MARGIN`](crate::univariate::ROOT_BOUND_MARGIN)); its margin makes the
/// bound strict.
fn cluster_radius(q: &[f64], radii: &[f64]) -> Option<f64> {
    let n = q.len() - 1;
    let lead = q[n].abs() - radii[n];
    if lead <= 0.0 {
        return None;
    }
    let mut m: Coeffs = SmallVec::from_elem(lead, n + 1);
    for ((mj, qj), rj) in m.as_mut_slice()[..n].iter_mut().zip(q).zip(radii) {
        *mj = qj.abs() + rj;
    }
    root_bound_of(&m)
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
            assert_eq!(
                stats.cluster_shifts, 2,
                "{sign}: both queries went to the centroid at once: {stats:?}"
            );
            assert_eq!(stats.multiprecision_pieces, 0, "{sign}: {stats:?}");
            assert_eq!(
                stats.exact_fallbacks + stats.refine_fallbacks,
                0,
                "{sign}: {stats:?}"
            );
        }
    }

    /// The exact sign of the stored `c` at `e + u` (both `f64`, summed exactly).
    fn exact_sign_at(c: &[f64], e: f64, u: f64) -> i8 {
        let x = rat_from_f64(e).unwrap() + rat_from_f64(u).unwrap();
        let mut v = crate::scalar::Rat::from_integer(0.into());
        for &ck in c.iter().rev() {
            v = v * &x + rat_from_f64(ck).unwrap();
        }
        match v.cmp(&crate::scalar::Rat::from_integer(0.into())) {
            std::cmp::Ordering::Less => -1,
            std::cmp::Ordering::Equal => 0,
            std::cmp::Ordering::Greater => 1,
        }
    }

    #[test]
    fn a_far_cluster_piece_holds_every_root_with_certified_end_signs() {
        // Ray-like polynomials whose roots (complex pairs included) cluster far from 0, on
        // ranges that start at 0 and end past, or inside, the cluster: the piece kept holds
        // every stored root of the range, its end signs are the exact ones, and it is no
        // wider than a few spreads of the cluster (Fujiwara's radius is within 2n of it).
        let pair = |m: f64, im: f64| vec![m * m + im * im, -2.0 * m, 1.0];
        let cases: Vec<(Vec<f64>, f64, f64)> = vec![
            // Two real roots and a pair near 10⁴, as a torus seen from 10⁴ units.
            (
                product(
                    planted_f64(&[9998.125, 9999.5]).coeffs(),
                    &pair(10001.0, 0.5),
                ),
                0.0,
                10004.0,
            ),
            // The range ends inside the cluster, past its centroid 9999.906.
            (
                product(
                    planted_f64(&[9998.125, 9999.5]).coeffs(),
                    &pair(10001.0, 0.5),
                ),
                0.0,
                9999.9375,
            ),
            // No real root: two pairs.
            (product(&pair(1e4, 1.5), &pair(1e4 + 1.0, 0.25)), 0.0, 1.1e4),
            // Mirrored: the cluster on the negative side.
            (
                planted_f64(&[-8000.0, -7998.0, -7997.5, -7994.0])
                    .coeffs()
                    .to_vec(),
                -2e4,
                0.0,
            ),
            // Odd degree: the signs left and right of the cluster differ.
            (
                product(
                    planted_f64(&[2999.0, 3000.0, 3001.5]).coeffs(),
                    &pair(3000.25, 1.0),
                ),
                0.0,
                3100.0,
            ),
            // Degree 6, odd leading sign, an end inside the cluster.
            (
                product(
                    planted_f64(&[4999.0, 5000.0, 5001.5, 5002.0]).coeffs(),
                    &pair(5000.5, 2.0),
                )
                .iter()
                .map(|x| -x)
                .collect(),
                4000.0,
                5001.75,
            ),
        ];
        for (c, lo, hi) in cases {
            let p = Poly::new(c.clone());
            let want = stored_roots(&p, lo, hi);
            let s_lo = exact_sign_at(&c, lo, 0.0);
            let s_hi = exact_sign_at(&c, hi, 0.0);
            let e = far_centroid(&c, lo, hi)
                .unwrap_or_else(|| panic!("a far cluster: {c:?} on ({lo}, {hi}]"));
            let (shift, (su_lo, su_hi)) =
                Shift::around_cluster(&c, e, (lo, hi), (s_lo, s_hi)).expect("applies");
            let (u_lo, u_hi) = shift.range;
            assert_eq!(shift.at, e);
            for r in &want {
                assert!(
                    *r > e + u_lo - 1e-9 && *r <= e + u_hi + 1e-9,
                    "root {r} outside ({}, {}]",
                    e + u_lo,
                    e + u_hi
                );
            }
            assert_eq!(su_lo, exact_sign_at(&c, e, u_lo), "sign at the lower end");
            assert_eq!(su_hi, exact_sign_at(&c, e, u_hi), "sign at the upper end");
            assert!(
                u_hi - u_lo <= 60.0,
                "{c:?}: piece ({u_lo}, {u_hi}] is not vacuous"
            );
            // And the queries answer from it alike.
            let mut stats = RootStats::default();
            let opts = RootOptions::new(1e-9);
            let got = p.real_roots_with(lo, hi, &opts, &mut stats).unwrap();
            assert_eq!(got.len(), want.len(), "{got:?} vs {want:?}");
            for (g, w) in got.iter().zip(&want) {
                assert!((g - w).abs() <= 1e-9, "{g} vs {w}");
            }
            let first = p.smallest_root_with(lo, hi, &opts, &mut stats);
            assert_eq!(first.is_some(), !want.is_empty());
            assert!(stats.cluster_shifts >= 1, "{stats:?}");
        }
    }

    #[test]
    fn spread_roots_are_not_taken_for_a_far_cluster() {
        // The renderer's queries (roots spread as far as they lie from 0), a cluster with an
        // outlier near 0, and a cluster outside the range: no centroid is offered.
        let cases = [
            (planted_f64(&[0.5, 1.5, 2.5, 4.0]), 0.0, 6.0),
            (planted_f64(&[1.0, 9999.0, 10000.0, 10001.0]), 0.0, 10005.0),
            (
                planted_f64(&[9999.0, 10000.0, 10001.0, 10002.0]),
                0.0,
                9000.0,
            ),
            (planted_f64(&[9999.0, 10000.0]), 0.0, 10005.0),
        ];
        for (p, lo, hi) in cases {
            assert_eq!(far_centroid(p.coeffs(), lo, hi), None, "{p:?}");
        }
    }

    #[test]
    fn random_far_clusters_answer_as_the_exact_oracle() {
        // Clusters of real roots and complex pairs (spread up to 8) at centres from 10² to
        // 10⁵ on either side of 0, degrees 3 to 8, searched on ranges that reach from the
        // near side of 0 to past the cluster or into it: every root of the stored polynomial
        // (coefficients rounded by the product) is found, within the tolerance, as the exact
        // Sturm oracle has them.
        use rand::{Rng, SeedableRng};
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(13);
        let mut clustered = 0;
        for case in 0..300 {
            let side = if rng.gen_bool(0.5) { 1.0 } else { -1.0 };
            let centre = side * 10f64.powf(rng.gen_range(2.0..5.0));
            let spread = rng.gen_range(0.01..8.0);
            let degree = rng.gen_range(3..=8);
            let mut c = vec![1.0];
            let mut left = degree;
            while left > 0 {
                let m = centre + spread * rng.gen_range(-1.0..1.0);
                if left >= 2 && rng.gen_bool(0.4) {
                    let im: f64 = spread * rng.gen_range(0.0..1.0);
                    c = product(&c, &[m * m + im * im, -2.0 * m, 1.0]);
                    left -= 2;
                } else {
                    c = product(&c, &[-m, 1.0]);
                    left -= 1;
                }
            }
            let far = centre + side * spread * rng.gen_range(-1.0..3.0);
            let (lo, hi) = if side > 0.0 { (0.0, far) } else { (far, 0.0) };
            let p = Poly::new(c.clone());
            let want = stored_roots(&p, lo, hi);
            let mut stats = RootStats::default();
            let opts = RootOptions::new(1e-9);
            let got = p.real_roots_with(lo, hi, &opts, &mut stats).unwrap();
            assert_eq!(
                got.len(),
                want.len(),
                "case {case}: {c:?} on ({lo}, {hi}]: {got:?} vs {want:?}"
            );
            for (g, w) in got.iter().zip(&want) {
                assert!((g - w).abs() <= 1e-9 * 1.01, "case {case}: {g} vs {w}");
            }
            let first = p.smallest_root_with(lo, hi, &opts, &mut stats);
            match (first, want.first()) {
                (Some(g), Some(w)) => assert!(
                    (g - w).abs() <= 1e-9 * 1.01,
                    "case {case}: first {g} vs {w}"
                ),
                (None, None) => {}
                (g, w) => panic!("case {case}: first {g:?} vs {w:?}"),
            }
            clustered += usize::from(stats.cluster_shifts > 0);
        }
        assert!(
            clustered >= 100,
            "the centroid path was taken in {clustered} cases only"
        );
    }

    #[test]
    fn clusters_at_extreme_scales_answer_as_the_exact_oracle() {
        // Where the radius test's sums underflow (10⁻⁸⁰: rⁿ near 10⁻³²⁰) or the coefficients
        // near overflow (10⁷⁰), whichever path the query takes, its roots are the stored ones.
        for scale in [1e-80, 1e-40, 1e40, 1e70] {
            let p = planted_f64(&[scale, 1.001 * scale, 1.002 * scale, 1.004 * scale]);
            let (lo, hi) = (0.0, 2.0 * scale);
            let want = stored_roots(&p, lo, hi);
            let mut stats = RootStats::default();
            let opts = RootOptions::new(1e-6 * scale);
            let got = p.real_roots_with(lo, hi, &opts, &mut stats).unwrap();
            assert_eq!(got.len(), want.len(), "{scale}: {got:?} vs {want:?}");
            for (g, w) in got.iter().zip(&want) {
                assert!((g - w).abs() <= 1.01e-6 * scale, "{scale}: {g} vs {w}");
            }
            let first = p.smallest_root_with(lo, hi, &opts, &mut stats);
            assert_eq!(first.is_some(), !want.is_empty(), "{scale}");
            if let (Some(g), Some(w)) = (first, want.first()) {
                assert!(
                    (g - w).abs() <= 1.01e-6 * scale,
                    "{scale}: first {g} vs {w}"
                );
            }
        }
    }
}

//! [`StamSturm`]: Stam's 1988 Sturm-sequence root finder, as written in `ray2.c` (seed,
//! Annexe B: `Sturm`, `V`, `W`, `IntAlgSurf`, `Isolate`, `Zero`), kept for comparison.
//!
//! The port keeps his arithmetic on purpose — the cross-multiplied remainder recurrence, the
//! division by the absolute value of each new leading coefficient, the test `f·g < 0` for a
//! sign change, the exact-zero test on leading coefficients — so the stability suite measures
//! *his* method. Only the shape changes: no global arrays, coefficients are converted from the
//! crate's low → high order at the boundary, and every loop has an iteration cap (his
//! `while (n1 − n2 != 1)` never ends when rounding makes the counts inconsistent).
//! See `paper-notes/sturm.md` for what each step computes.
//!
//! Two departures, because a baseline may be inaccurate but not absurd (issue 13): a zero
//! member value is skipped in the sign count, as eq. 3.21 says (his code let it break the
//! chain, which lost the root of `x² − 1` on `(0, 10]`: `V₁(0) = 0`); and where his search
//! would return a point that no sign change supports (inconsistent counts, the isolation cap,
//! a bisection that never saw `P` change sign) the query reports
//! [`RootError::Unresolved`] instead.

use crate::eval_bound::horner_bounded_from_top;
use crate::root_error::RootError;
use crate::sturm::{CheckedSigns, changes_with_uncertain, v0_sign_at_zero_value};
use crate::univariate::Poly;

/// Most bisections in [`StamSturm::smallest_root`]'s isolation loop (the original has none):
/// 200 halvings take any `f64` interval below the spacing of its numbers.
const MAX_ISOLATION_STEPS: u32 = 200;

/// Most bisections in [`StamSturm::smallest_root`]'s refinement loop: about 2100 halvings go
/// from the widest `f64` interval to adjacent numbers.
const MAX_REFINE_STEPS: u32 = 2200;

/// The largest ratio of a member's other coefficients to its leading one, after his
/// normalisation, that [`StamSturm::count_roots_checked`] accepts: `1/ε`. Each coefficient of
/// a member carries at least a rounding of `u = ε/2` relative to the largest one, so past
/// this ratio the leading coefficient is below that rounding, and the next remainder (whose
/// quotient divides by it) is decided by noise (issue 11: `−0.376x⁴ − 3.6e-121x² + 7.6x −
/// 0.094` lost its roots 0.0123 and 2.72 this way). A relative bound, on one member. `P`
/// itself is held to it too: its leading coefficient and `P' = V₁`'s enter every member his
/// recurrence computes (a leading 1.1e-57 lost a pair of roots of a degree-7 `P`).
const MAX_TAIL_OVER_LEAD: f64 = 1.0 / f64::EPSILON;

/// A coefficient of a member his recurrence computes is rounding noise when it is within
/// this fraction of the sum of the magnitudes it was formed from (about six roundings, each
/// at most `ε/2` relative, with room to spare): its sign, and the roots it places, are then
/// guessed.
const NOISE_REL: f64 = 4.0 * f64::EPSILON;

/// Whether a member's (highest power first) other coefficients exceed its leading one by more
/// than [`MAX_TAIL_OVER_LEAD`].
fn tail_over_lead(member: &[f64]) -> bool {
    member
        .iter()
        .skip(1)
        .any(|c| c.abs() > MAX_TAIL_OVER_LEAD * member[0].abs())
}

/// Stam's Sturm sequence: member `k` stored highest power first, as in his `STURM_SERIE`.
#[derive(Clone, Debug, PartialEq)]
pub struct StamSturm {
    /// `members[k][0]` is the leading coefficient of `V_k`.
    members: Vec<Vec<f64>>,
    /// `P`'s coefficients, lowest degree first (for its certified sign).
    low: Vec<f64>,
    /// A member's leading coefficient came out exactly zero (his shift loop ran: his
    /// recurrence gives `−rem` only when each degree drops by one, so past that point the
    /// members are not a Sturm sequence), a coefficient of `P` or of a member is below the
    /// normal range or not finite, a member's leading coefficient is below the rounding of
    /// its others ([`MAX_TAIL_OVER_LEAD`]), or a computed coefficient is rounding noise
    /// ([`NOISE_REL`]): [`StamSturm::count_roots_checked`] refuses.
    abnormal: bool,
}

impl StamSturm {
    /// Builds the sequence as `Sturm(deg)` does in `ray2.c`: `V₁ = P'`, then for each `j`
    /// `V_j = (c₀·V_{j−1} − b₀·(b₀·V_{j−2} − a₀·V_{j−1}·x))/|lead|`, a positive multiple of
    /// `−rem(V_{j−2}, V_{j−1})` when the degrees drop by one at each step (the normal case).
    /// A member whose leading coefficient is exactly zero is shifted down, as in his loop.
    ///
    /// # Accuracy
    /// No guarantee: plain `f64`, no scaling of `P`. `None` for the zero polynomial, constants
    /// or non-finite coefficients.
    pub fn new(p: &Poly<f64>) -> Option<Self> {
        if p.degree() == 0 || !p.is_finite() {
            return None;
        }
        let deg = p.degree();
        let s0: Vec<f64> = p.coeffs().iter().rev().copied().collect();
        let mut members: Vec<Vec<f64>> = vec![s0];
        // V1 = P', highest first: (n0 − i)·a[i].
        let s1: Vec<f64> = (0..deg).map(|i| (deg - i) as f64 * members[0][i]).collect();
        members.push(s1);
        let mut n0 = deg;
        let mut abnormal = members
            .iter()
            .flatten()
            .any(|c| *c != 0.0 && c.abs() < f64::MIN_POSITIVE)
            || tail_over_lead(&members[0]);
        let mut j = 2;
        while j <= n0 {
            let (s0, s1) = (&members[members.len() - 2], &members[members.len() - 1]);
            let at = |v: &Vec<f64>, i: usize| v.get(i).copied().unwrap_or(0.0);
            let (a0, b0) = (at(s0, 0), at(s1, 0));
            let c0 = b0 * at(s0, 1) - a0 * at(s1, 1);
            let c0_mag = (b0 * at(s0, 1)).abs() + (a0 * at(s1, 1)).abs();
            let len = n0 - j + 1;
            let mut s2 = vec![0.0; len];
            let mut x = 1.0;
            for i in 1..=len {
                let v = c0 * at(s1, i) - b0 * (b0 * at(s0, i + 1) - a0 * at(s1, i + 1));
                let mag = c0_mag * at(s1, i).abs()
                    + b0.abs() * ((b0 * at(s0, i + 1)).abs() + (a0 * at(s1, i + 1)).abs());
                abnormal |= mag > 0.0 && v.abs() <= NOISE_REL * mag;
                s2[i - 1] = v / x;
                if i == 1 {
                    x = s2[0].abs();
                    // The original divides by this even when it is zero, producing NaNs that
                    // defeat its own zero-leading-coefficient loop below; we skip the scaling.
                    if x == 0.0 {
                        x = 1.0;
                    }
                }
            }
            s2[0] /= x;
            // His recurrence multiplies coefficients together: one that left the normal range
            // (or overflowed) no longer carries the digits the signs need (issue 11: roots
            // 0.78 and 5.4 of a quartic with a 1.6e-308 coefficient were both lost).
            abnormal |= s2
                .iter()
                .any(|c| !c.is_finite() || (*c != 0.0 && c.abs() < f64::MIN_POSITIVE));
            // After his division by |lead| the leading coefficient is ±1: a tail beyond
            // MAX_TAIL_OVER_LEAD means the unscaled lead was below the others' rounding.
            abnormal |= tail_over_lead(&s2);
            members.push(s2);
            // while (S1->a[0] == 0.0): shift the coefficients left and append a zero, keeping
            // the stored degree (so the member is evaluated as x times the shifted one, as in
            // the original), and lower the working degree n0.
            loop {
                let last = members.last_mut().expect("just pushed");
                if last.first().is_none_or(|&c| c != 0.0) {
                    break;
                }
                abnormal = true;
                last.rotate_left(1);
                if let Some(z) = last.last_mut() {
                    *z = 0.0;
                }
                n0 -= 1;
                if n0 <= j {
                    // His `return n0`: members V_0 … V_n0 are used.
                    members.truncate(n0 + 1);
                    return Some(StamSturm {
                        members,
                        low: p.coeffs().to_vec(),
                        abnormal,
                    });
                }
            }
            j += 1;
        }
        Some(StamSturm {
            members,
            low: p.coeffs().to_vec(),
            abnormal,
        })
    }

    /// `V(i, x)`: member `i` at `x` by Horner's rule.
    fn value(&self, i: usize, x: f64) -> f64 {
        self.members[i].iter().fold(0.0, |v, &c| v * x + c)
    }

    /// `W(x)`: the number of sign changes `V_k(x)·V_j(x) < 0` between consecutive non-zero
    /// member values, zeros skipped as in eq. 3.21 (the original let a zero break the chain,
    /// see the module docs).
    ///
    /// # Accuracy
    /// None promised: plain `f64` products of rounded values.
    pub fn sign_changes_at(&self, x: f64) -> usize {
        let mut f = 0.0;
        let mut nb = 0;
        for i in 0..self.members.len() {
            let g = self.value(i, x);
            if g == 0.0 {
                continue;
            }
            if f * g < 0.0 {
                nb += 1;
            }
            f = g;
        }
        nb
    }

    /// `W(a) − W(b)`, Stam's root count for `[a, b]` (no guarantee; 0 for `a ≥ b` or NaN).
    pub fn count_roots(&self, a: f64, b: f64) -> usize {
        if a.is_nan() || b.is_nan() || a >= b {
            return 0;
        }
        self.sign_changes_at(a)
            .saturating_sub(self.sign_changes_at(b))
    }

    /// [`count_roots`](Self::count_roots), or `None` when his arithmetic visibly failed at an
    /// end (issue 11, "heuristic methods never lie silently"): his recurrence left its normal
    /// case (a leading coefficient exactly zero, so a degree dropped by more than one and the
    /// members are no longer `−rem`s), a member coefficient or value is not finite (his
    /// recurrence overflowed, or a value at `x` did), a member's value at an end is within
    /// its rounding bound (`eval_bound.rs`) where its sign could change the count (the rule
    /// of the `f64` Sturm sequence's checked count), `P`'s value is 0 where it is neither
    /// certified non-zero (its certified sign is then counted) nor an exact root, or the
    /// product
    /// `f·g` of two non-zero values underflowed to zero, so his test `f·g < 0` cannot see the
    /// sign change it is there to count. His count itself is kept as written otherwise.
    pub(crate) fn count_roots_checked(&self, a: f64, b: f64) -> Option<usize> {
        if a.is_nan() || b.is_nan() || a >= b {
            return Some(0);
        }
        let (wa, wb) = (self.sign_changes_checked(a)?, self.sign_changes_checked(b)?);
        Some(wa.saturating_sub(wb))
    }

    /// `W(x)` with the checks of [`count_roots_checked`](Self::count_roots_checked).
    fn sign_changes_checked(&self, x: f64) -> Option<usize> {
        if self.abnormal {
            return None;
        }
        // Signs with 2 for "uncertain", as in the f64 Sturm sequence's checked count.
        let mut signs = CheckedSigns::from_elem(0, self.members.len());
        let mut f = 0.0;
        for ((i, m), sign) in self.members.iter().enumerate().zip(signs.iter_mut()) {
            // His value `V(i, x)` (the same Horner steps), with the rounding bound of
            // `eval_bound.rs` computed alongside.
            let (g, err) = horner_bounded_from_top(m.iter(), m.len(), x);
            if !g.is_finite() || !err.is_finite() {
                return None;
            }
            let his = if g > 0.0 {
                1
            } else if g < 0.0 {
                -1
            } else {
                0
            };
            *sign = his;
            if i == 0 && g == 0.0 {
                // P's value 0: its certified sign, or an exact root (`c·x` on (−η, η]
                // underflowed to 0 at both ends and the root between was lost; issue 11).
                // The count then takes that sign (his next product sees ±1 for it).
                let s = v0_sign_at_zero_value(&self.low, x)?;
                *sign = s;
                f = f64::from(s);
                continue;
            } else if i > 0 && g.abs() <= err && err > 0.0 {
                *sign = 2;
            }
            if g == 0.0 {
                continue;
            }
            if f != 0.0 && f * g == 0.0 {
                // His test `f·g < 0` would miss this change.
                return None;
            }
            f = g;
        }
        changes_with_uncertain(&signs)
    }

    /// `IntAlgSurf`'s search: halve `[t1, t2]` (keeping the left half when it holds a root
    /// by the counts) until the count is one, then bisect on the sign of `P` until the width
    /// is at most `precision`, and return the right end `t2`, as the original does.
    ///
    /// # Accuracy
    /// None promised (heuristic counts and uncertified signs); `Ok(None)` when the counts say
    /// no root.
    ///
    /// # Errors
    /// [`RootError::Unresolved`] with the interval the counts gave when the counts become
    /// inconsistent or visibly fail (the checked counts'
    /// overflow and underflow checks), the isolation loop hits its cap, or `P` never changed
    /// sign in the isolated interval (no value is returned that nothing supports).
    pub fn smallest_root(
        &self,
        t1: f64,
        t2: f64,
        precision: f64,
    ) -> Result<Option<f64>, RootError> {
        let (mut t1, mut t2) = (t1, t2);
        let unresolved = |lo, hi| Err(RootError::Unresolved { lo, hi });
        let (Some(mut n1), Some(mut n2)) =
            (self.sign_changes_checked(t1), self.sign_changes_checked(t2))
        else {
            return unresolved(t1, t2);
        };
        if n1 <= n2 {
            return Ok(None);
        }
        let mut steps = 0;
        while n1 - n2 != 1 {
            steps += 1;
            if steps > MAX_ISOLATION_STEPS {
                return unresolved(t1, t2);
            }
            let m = 0.5 * (t1 + t2);
            let Some(n) = self.sign_changes_checked(m) else {
                return unresolved(t1, t2);
            };
            if n1 == n {
                t1 = m;
                n1 = n;
            } else {
                t2 = m;
                n2 = n;
            }
            if n1 <= n2 {
                return unresolved(t1, t2);
            }
        }
        let (a, b) = (t1, t2);
        let mut guard = 0;
        while t2 - t1 > precision && guard < MAX_REFINE_STEPS {
            guard += 1;
            let m = 0.5 * (t1 + t2);
            if m <= t1 || m >= t2 {
                break;
            }
            if self.value(0, t1) * self.value(0, m) < 0.0 {
                t2 = m;
            } else {
                t1 = m;
            }
        }
        let (f1, f2) = (self.value(0, t1), self.value(0, t2));
        if f2 == 0.0 || f1 * f2 < 0.0 {
            Ok(Some(t2))
        } else {
            unresolved(a, b)
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn stam_counts_and_finds_a_low_degree_root() {
        let p = Poly::<f64>::from_roots(&[0.3, 1.7, 2.2, 4.1]);
        let s = StamSturm::new(&p).unwrap();
        assert_eq!(s.count_roots(0.0, 5.0), 4, "all four roots");
        assert_eq!(s.count_roots(1.0, 3.0), 2, "1.7 and 2.2");
        let r = s.smallest_root(1.0, 5.0, 1e-12).unwrap().unwrap();
        assert!(
            (r - 1.7).abs() <= 1e-11,
            "smallest root after 1 is 1.7: {r}"
        );
        assert!(
            s.smallest_root(5.0, 9.0, 1e-9) == Ok(None),
            "no root beyond 4.1"
        );
        assert!(StamSturm::new(&Poly::new(vec![3.0])).is_none(), "constant");
    }
}

//! Exact real-root isolation of a square-free integer polynomial by Descartes' rule of signs
//! (Collins and Akritas 1976, "Polynomial real root isolation using Descartes' rule of
//! signs"): the fast path of [`IsolationMethod::Exact`](crate::IsolationMethod::Exact).
//!
//! Why not Sturm: the exact Sturm sequence of a degree-33 polynomial whose `f64` coefficients
//! span the exponent range (2 000-bit integers) has members of 130 000 bits, and building it
//! took 1–2 s (issue 13, item 17). Descartes' test on an interval needs only the polynomial
//! itself moved to that interval — two Taylor shifts, integer additions and multiplications
//! by the interval's ends — whose coefficients grow by a few bits per degree and per bit of
//! the ends. See `paper-notes/isolation.md`, "Exact isolation".
//!
//! Every decision is exact: the counts are sign variations of integer coefficients, and a
//! count other than 0 or 1 only asks for a split. No floating-point value decides anything;
//! `f64` appears only as the interval ends (exact dyadics) the caller wants.

use num_bigint::{BigInt, Sign};
use num_traits::{Signed, Zero};

use crate::root_interval::RootInterval;
use crate::scalar::{binary_exponent, f64_dyadic};
use crate::stats::RootStats;

/// Most Descartes tests spent counting the roots inside one interval whose ends are adjacent
/// `f64` numbers (roots closer than one `f64` spacing, or a complex pair that close to the
/// axis): past it the caller counts with the exact Sturm sequence. Each level halves the
/// interval; 400 tests resolve separations down to about `2^-100` of an `f64` spacing in the
/// worst (two-way) case and far below it for a single cluster.
const MAX_SUBULP_TESTS: usize = 400;

/// A dyadic rational `m·2^e`.
#[derive(Clone, Debug)]
struct Dyadic {
    m: BigInt,
    e: i64,
}

impl Dyadic {
    /// The exact value of a finite `f64`.
    fn from_f64(x: f64) -> Self {
        debug_assert!(x.is_finite(), "interval ends are finite");
        if x == 0.0 {
            return Dyadic {
                m: BigInt::zero(),
                e: 0,
            };
        }
        let (m, e) = f64_dyadic(x);
        Dyadic {
            m: BigInt::from(m),
            e,
        }
    }

    /// The midpoint, exactly.
    fn midpoint(&self, other: &Dyadic) -> Dyadic {
        let e = self.e.min(other.e);
        Dyadic {
            m: self.at(e) + other.at(e),
            e: e - 1,
        }
    }

    /// The mantissa for the exponent `e ≤ self.e`.
    fn at(&self, e: i64) -> BigInt {
        &self.m << (self.e - e) as usize
    }
}

/// A square-free integer polynomial (coefficients lowest degree first, no trailing zero)
/// whose real roots are isolated by Descartes' rule.
pub(crate) struct Descartes<'a> {
    c: &'a [BigInt],
}

impl<'a> Descartes<'a> {
    /// `c` must be square-free (no repeated complex root): then the bisection ends (Vincent's
    /// theorem; Collins–Akritas). With a repeated real root it would not, which is why the
    /// caller certifies square-freeness first.
    pub(crate) fn new(c: &'a [BigInt]) -> Self {
        debug_assert!(c.last().is_some_and(|x| !x.is_zero()), "trimmed");
        Descartes { c }
    }

    /// Isolating intervals of the roots in `(lo, hi]` (finite `f64` ends, `lo < hi`), sorted,
    /// in the convention of the exact Sturm isolation they replace: one root in the open
    /// interval `(a, b)` and none at `b`, or the point `a == b` for a root at an `f64` split
    /// point or at `hi`;
    /// `n` copies of an interval whose ends are adjacent `f64` numbers when it holds `n`
    /// roots. `None` when such an interval's roots could not be counted within
    /// [`MAX_SUBULP_TESTS`] (the caller then uses the exact Sturm sequence).
    ///
    /// Intervals are split at `f64` points: at 0 when they straddle it, at a power of two
    /// halfway in exponent when their ends are more than a binade apart (a range of `1e±300`
    /// takes 11 splits, not 2 000, to reach the binade of a root), else at the midpoint.
    ///
    /// # Exactness
    /// Exact: the counts are sign variations of integer polynomials, and a point root is
    /// found by an exact sign.
    pub(crate) fn isolate(
        &self,
        lo: f64,
        hi: f64,
        first_only: bool,
        stats: &mut RootStats,
    ) -> Option<Vec<RootInterval<f64>>> {
        enum Item {
            /// The open interval `(a, b)`, and whether `b` is a root.
            Open(f64, f64, bool),
            Point(f64),
        }
        let root_at = |x: f64| self.sign_at(&Dyadic::from_f64(x)) == 0;
        let hi_is_root = root_at(hi);
        let mut out = Vec::new();
        let mut stack = vec![Item::Open(lo, hi, hi_is_root)];
        while let Some(item) = stack.pop() {
            let (a, b, b_root) = match item {
                Item::Point(x) => {
                    out.push(RootInterval { lo: x, hi: x });
                    if first_only {
                        return Some(out);
                    }
                    continue;
                }
                Item::Open(a, b, b_root) => (a, b, b_root),
            };
            let (da, db) = (Dyadic::from_f64(a), Dyadic::from_f64(b));
            let v = self.variations(&da, &db);
            if v == 0 {
                continue;
            }
            // One root inside, and `b` not a root: an isolating interval. (With a root at
            // `b`, exact refinement, which reads the sign at `b`, needs a split first.)
            if v == 1 && !b_root {
                out.push(self.narrowed(a, b));
                if first_only {
                    return Some(out);
                }
                continue;
            }
            let Some(m) = split_point(a, b) else {
                let n = self.count_open(&da, &db)?;
                out.extend(std::iter::repeat_n(RootInterval { lo: a, hi: b }, n));
                if first_only && n > 0 {
                    return Some(out);
                }
                continue;
            };
            stats.subdivisions += 1;
            let m_root = root_at(m);
            stack.push(Item::Open(m, b, b_root));
            if m_root {
                stack.push(Item::Point(m));
            }
            stack.push(Item::Open(a, m, m_root));
        }
        // With `first_only`, every earlier find has returned: `out` is empty here.
        if hi_is_root {
            out.push(RootInterval { lo: hi, hi });
        }
        Some(out)
    }

    /// The isolating interval `(a, b)` (one simple root inside, none at `b`) narrowed by exact
    /// signs to ends at most a binade apart (or a point): at most ~11 evaluations of `p`
    /// instead of ~2 000 steps of the exact refinement's arithmetic bisection from, say,
    /// `(−1e202, −1e-60)` to a root at `−1e-98`.
    fn narrowed(&self, mut a: f64, mut b: f64) -> RootInterval<f64> {
        let s_b = self.sign_at(&Dyadic::from_f64(b));
        debug_assert_ne!(s_b, 0, "no root at b");
        while let Some(m) = geometric_split(a, b) {
            match self.sign_at(&Dyadic::from_f64(m)) {
                0 => return RootInterval { lo: m, hi: m },
                s if s == s_b => b = m,
                _ => a = m,
            }
        }
        RootInterval { lo: a, hi: b }
    }

    /// The number of roots in the open interval `(a, b)` by Descartes bisection at exact
    /// midpoints, or `None` past [`MAX_SUBULP_TESTS`] tests.
    fn count_open(&self, a: &Dyadic, b: &Dyadic) -> Option<usize> {
        let mut count = 0;
        let mut tests = 0;
        let mut stack = vec![(a.clone(), b.clone())];
        while let Some((a, b)) = stack.pop() {
            tests += 1;
            if tests > MAX_SUBULP_TESTS {
                return None;
            }
            match self.variations(&a, &b) {
                0 => {}
                1 => count += 1,
                _ => {
                    let m = a.midpoint(&b);
                    count += usize::from(self.sign_at(&m) == 0);
                    stack.push((m.clone(), b));
                    stack.push((a, m));
                }
            }
        }
        Some(count)
    }

    /// Sign variations of `(1 + x)^n·p((a + b·x)/(1 + x))` (zeros skipped): an upper bound on
    /// the number of roots in the open interval `(a, b)`, exact when it is 0 or 1 (Descartes'
    /// rule; Collins–Akritas §2). The transformed polynomial is formed in integers:
    /// `p(2^g·z)` scaled by a positive power of two, shifted by the integer `A = a/2^g`, the
    /// variable scaled by `W = (b − a)/2^g`, reversed and shifted by 1.
    fn variations(&self, a: &Dyadic, b: &Dyadic) -> usize {
        let g = a.e.min(b.e);
        let mut am = a.at(g);
        let mut w = b.at(g) - &am;
        debug_assert!(w.is_positive(), "a < b");
        // A common power of two of A and W goes into 2^g: smaller integers below.
        let tz = match am.trailing_zeros() {
            Some(t) => t.min(w.trailing_zeros().unwrap_or(0)),
            None => w.trailing_zeros().unwrap_or(0),
        };
        am >>= tz as usize;
        w >>= tz as usize;
        let g = g + tz as i64;
        let n = self.c.len() - 1;
        // p(2^g·z)·2^{max(0, −g)·n}: coefficient i times 2^{g·i} (g ≥ 0) or 2^{−g(n−i)}.
        let mut t: Vec<BigInt> = self
            .c
            .iter()
            .enumerate()
            .map(|(i, c)| {
                let shift = if g >= 0 {
                    g as u64 * i as u64
                } else {
                    g.unsigned_abs() * (n - i) as u64
                };
                c << shift as usize
            })
            .collect();
        taylor_shift(&mut t, &am);
        let mut wpow = w.clone();
        for x in t.iter_mut().skip(1) {
            *x *= &wpow;
            wpow *= &w;
        }
        remove_power_of_two(&mut t);
        t.reverse();
        taylor_shift_by_one(&mut t);
        sign_variations(&t)
    }

    /// The exact sign of `p(x)`: that of `Σ cᵢ mⁱ 2^{e·i}`, by Horner on integers with the
    /// power of two as a shift.
    fn sign_at(&self, x: &Dyadic) -> i8 {
        let n = self.c.len() - 1;
        let mut acc = BigInt::zero();
        // With e < 0: the sign of Σ cᵢ mⁱ 2^{−e(n−i)}.
        for (i, c) in self.c.iter().enumerate().rev() {
            acc *= &x.m;
            if x.e >= 0 {
                acc += c << (x.e as u64 * i as u64) as usize;
            } else {
                acc += c << (x.e.unsigned_abs() * (n - i) as u64) as usize;
            }
        }
        match acc.sign() {
            Sign::Minus => -1,
            Sign::NoSign => 0,
            Sign::Plus => 1,
        }
    }
}

/// `p(x + s)` in place, by repeated synthetic division: `O(n²)` multiplications by `s` (none
/// when `s = 0`).
fn taylor_shift(c: &mut [BigInt], s: &BigInt) {
    if s.is_zero() {
        return;
    }
    let n = c.len();
    for i in 0..n {
        for j in (i..n - 1).rev() {
            let t = &c[j + 1] * s;
            c[j] += t;
        }
    }
}

/// `p(x + 1)` in place: `O(n²)` additions.
fn taylor_shift_by_one(c: &mut [BigInt]) {
    let n = c.len();
    for i in 0..n {
        for j in (i..n - 1).rev() {
            let (lo, hi) = c.split_at_mut(j + 1);
            lo[j] += &hi[0];
        }
    }
}

/// Divides every coefficient by the largest power of two dividing all: a positive factor.
fn remove_power_of_two(c: &mut [BigInt]) {
    if let Some(tz) = c.iter().filter_map(BigInt::trailing_zeros).min()
        && tz > 0
    {
        for x in c.iter_mut() {
            *x >>= tz as usize;
        }
    }
}

/// Sign changes in the coefficient sequence, zeros skipped.
fn sign_variations(c: &[BigInt]) -> usize {
    let mut last = Sign::NoSign;
    let mut count = 0;
    for x in c {
        let s = x.sign();
        if s == Sign::NoSign {
            continue;
        }
        if last != Sign::NoSign && s != last {
            count += 1;
        }
        last = s;
    }
    count
}

/// An `f64` strictly inside `(a, b)` to split at (see [`Descartes::isolate`]); `None` when
/// the ends are adjacent `f64` numbers.
fn split_point(a: f64, b: f64) -> Option<f64> {
    geometric_split(a, b).or_else(|| {
        let m = 0.5 * a + 0.5 * b;
        (m > a && m < b).then_some(m)
    })
}

/// 0 when `(a, b)` straddles it, a power of two halfway in exponent when the ends are two
/// or more binades apart; else `None`.
fn geometric_split(a: f64, b: f64) -> Option<f64> {
    if a < 0.0 && b > 0.0 {
        return Some(0.0);
    }
    // Binade indices: floor(log2 |x|), with 0 below every subnormal.
    let binade = |x: f64| -> i32 { if x == 0.0 { -1075 } else { binary_exponent(x) } };
    let (la, lb) = (binade(a), binade(b));
    if la.abs_diff(lb) >= 2 {
        // Strictly between the binades: |a| < 2^{j} < |b| (or the reverse for negative
        // ends), a power of two of the same sign.
        let (small, large) = (la.min(lb), la.max(lb));
        let j = small + (large - small) / 2;
        let m = pow2(j);
        let m = if b <= 0.0 { -m } else { m };
        debug_assert!(a < m && m < b, "{a} < {m} < {b}");
        return (a < m && m < b).then_some(m);
    }
    None
}

/// `2^j` exactly, for `−1074 ≤ j ≤ 1023` (`powi` is not exact: `2f64.powi(-1047)` is 0).
fn pow2(j: i32) -> f64 {
    debug_assert!(
        (-1074..=1023).contains(&j),
        "2^{j} is a finite non-zero f64"
    );
    if j >= -1022 {
        f64::from_bits(((j + 1023) as u64) << 52)
    } else {
        f64::from_bits(1u64 << (j + 1074))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn ints(c: &[i64]) -> Vec<BigInt> {
        c.iter().map(|&x| BigInt::from(x)).collect()
    }

    #[test]
    fn variations_count_roots_in_open_intervals() {
        // (x − 1)(x − 2)(x − 3) = x³ − 6x² + 11x − 6
        let c = ints(&[-6, 11, -6, 1]);
        let d = Descartes::new(&c);
        let v = |a: f64, b: f64| d.variations(&Dyadic::from_f64(a), &Dyadic::from_f64(b));
        assert_eq!(v(0.0, 1.5), 1, "one root in (0, 1.5)");
        assert_eq!(
            v(1.0, 2.0),
            0,
            "roots at the ends are outside the open interval"
        );
        assert_eq!(v(3.5, 1e300), 0, "none above 3");
        assert_eq!(v(-1e-300, 0.5), 0, "none near 0");
        assert!(
            v(0.0, 10.0) >= 2,
            "three in (0, 10): at least two variations"
        );
    }

    /// The integer polynomial `Π (2^k·x − mᵢ)` with the roots `mᵢ/2^k`.
    fn from_dyadic_roots(roots: &[(i64, u32)], k: u32) -> Vec<BigInt> {
        let mut c = vec![BigInt::from(1)];
        for &(m, j) in roots {
            // The factor 2^k·x − m·2^{k−j}.
            let (lin, con) = (BigInt::from(1) << k, -(BigInt::from(m) << (k - j)));
            let mut next = vec![BigInt::zero(); c.len() + 1];
            for (i, x) in c.iter().enumerate() {
                next[i] += x * &con;
                next[i + 1] += x * &lin;
            }
            c = next;
        }
        c
    }

    #[test]
    fn isolates_roots_at_split_points_ends_and_across_binades() {
        // Roots −1, 0 (the first split point), 2^-600, 2^-60 + 2^-70, 3 (= hi): far apart in
        // magnitude, two of them on interval ends.
        let k = 700;
        let c = from_dyadic_roots(&[(-1, 0), (0, 0), (1, 600), ((1 << 10) + 1, 70), (3, 0)], k);
        let d = Descartes::new(&c);
        let ivs = d
            .isolate(-10.0, 3.0, false, &mut RootStats::default())
            .unwrap();
        assert_eq!(ivs.len(), 5, "{ivs:?}");
        assert_eq!(
            ivs[0],
            RootInterval { lo: -1.0, hi: -1.0 },
            "−1, a power of two, found as a split point"
        );
        assert!(
            ivs[1].is_point() && ivs[1].lo == 0.0,
            "0 as a point: {ivs:?}"
        );
        let tiny = 2f64.powi(-600);
        assert!(
            ivs[2].lo == tiny || (ivs[2].lo < tiny && tiny < ivs[2].hi),
            "2^-600 in {:?}",
            ivs[2]
        );
        let small = 2f64.powi(-60) + 2f64.powi(-70);
        assert!(
            ivs[3].lo < small && small < ivs[3].hi,
            "{small} in {:?}",
            ivs[3]
        );
        assert!(ivs[4].is_point() && ivs[4].lo == 3.0, "hi = 3 as a point");
        for pair in ivs.windows(2) {
            assert!(pair[0].hi <= pair[1].lo, "sorted and disjoint: {ivs:?}");
        }
        for iv in ivs.iter().filter(|iv| !iv.is_point()) {
            assert_ne!(
                d.sign_at(&Dyadic::from_f64(iv.hi)),
                0,
                "no root at the end of {iv:?}"
            );
        }
        let first = d
            .isolate(-0.5, 3.0, true, &mut RootStats::default())
            .unwrap();
        assert_eq!(first, vec![RootInterval { lo: 0.0, hi: 0.0 }], "first only");
        let none = d
            .isolate(3.5, 1e300, false, &mut RootStats::default())
            .unwrap();
        assert!(none.is_empty(), "no root above 3: {none:?}");
        // The tiny roots' intervals were narrowed to within a binade by exact signs (the
        // exact refinement then bisects ~60 times, not ~2 000).
        for iv in &ivs[2..4] {
            assert!(
                iv.is_point() || (iv.lo > 0.0 && iv.hi <= 4.0 * iv.lo),
                "narrowed: {iv:?}"
            );
        }
    }

    #[test]
    fn counts_roots_closer_than_an_ulp() {
        // Roots 1 + 2^-60 and 1 + 2^-59: both inside (1, 1 + 2^-52), adjacent f64 ends.
        let c = from_dyadic_roots(&[((1 << 60) + 1, 60), ((1 << 59) + 1, 59)], 60);
        let d = Descartes::new(&c);
        let ivs = d
            .isolate(0.0, 4.0, false, &mut RootStats::default())
            .unwrap();
        assert_eq!(ivs.len(), 2, "two roots counted: {ivs:?}");
        assert_eq!(ivs[0], ivs[1], "in one unsplittable interval");
        assert_eq!(
            (ivs[0].lo, ivs[0].hi),
            (1.0, 1f64.next_up()),
            "adjacent ends"
        );
    }

    #[test]
    fn split_points_are_inside_and_geometric_across_binades() {
        assert_eq!(split_point(-1.0, 2.0), Some(0.0), "straddling 0");
        assert_eq!(
            split_point(0.0, 1.0),
            Some(2f64.powi(-538)),
            "halfway in exponent"
        );
        assert_eq!(
            split_point(-1e300, -1e-300).map(f64::is_sign_negative),
            Some(true)
        );
        assert_eq!(
            split_point(1.0, 1.5),
            Some(1.25),
            "midpoint within a binade"
        );
        assert_eq!(split_point(1.0, 1f64.next_up()), None, "adjacent");
        assert_eq!(split_point(0.0, 5e-324), None, "adjacent at 0");
        let m = split_point(5e-324, 1e-300).unwrap();
        assert!(5e-324 < m && m < 1e-300, "subnormal range: {m}");
        // 2^-1047 (powi gives 0 there, and an endless split at −0 followed).
        let m = split_point(-7.12e-307, 0.0).unwrap();
        assert!(-7.12e-307 < m && m < 0.0, "towards zero from below: {m}");
        assert_eq!(pow2(-1074), 5e-324, "smallest subnormal");
        assert_eq!(pow2(-1022), f64::MIN_POSITIVE, "smallest normal");
        assert_eq!(pow2(1023), 2f64.powi(1023), "largest");
    }
}

//! [`PolyRef`] and [`RootQuery`]: root queries on borrowed coefficients, with optional
//! statistics.
//!
//! A caller that keeps its coefficients in its own buffer (a ray tracer's per-thread scratch
//! vector, a stack array) wraps them in a [`PolyRef`] and asks for roots, without lending a
//! `Vec` to [`Poly::new`] and taking it back:
//!
//! ```
//! use poly::{PolyRef, RootOptions};
//! let c = [-2.0, 0.0, 1.0, 0.0]; // x² − 2, with a trailing zero the view trims
//! let r = PolyRef::new(&c).roots(0.0, f64::INFINITY, &RootOptions::new(1e-12)).smallest()?;
//! assert!(r.is_some_and(|r| (r - 2f64.sqrt()).abs() <= 1e-12));
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```
//!
//! The query is a small builder in the manner of kurbo's and polycool's slice-based solvers:
//! the range and [`RootOptions`] first, [`RootStats`] only when the caller wants them
//! ([`RootQuery::stats`]), then one of [`smallest`](RootQuery::smallest),
//! [`all`](RootQuery::all), [`all_into`](RootQuery::all_into) or
//! [`isolate`](RootQuery::isolate). The answers and their guarantees are those of the
//! [`Poly`] methods of the same purpose (`try_smallest_root`, `real_roots_with`,
//! `real_roots_into`, `isolate_roots_with`), which are the one implementation.

use crate::isolate::try_smallest;
use crate::root_error::RootError;
use crate::root_interval::RootInterval;
use crate::root_options::RootOptions;
use crate::scalar::binary_exponent;
use crate::stats::RootStats;
use crate::stored::{Slack, Stored};
use crate::univariate::{Poly, root_bound_of};

/// A polynomial over `f64` whose coefficients (lowest degree first) live in a borrowed slice.
///
/// [`PolyRef::new`] drops trailing exact zeros by narrowing the slice (no copy), so a view
/// always satisfies the invariant of [`Poly`]: the last coefficient is not zero.
///
/// # Examples
/// ```
/// use poly::{Poly, PolyRef};
/// let buf = [1.0, -3.0, 2.0, 0.0, 0.0];
/// let p = PolyRef::new(&buf);
/// assert_eq!(p.degree(), 2);
/// assert_eq!(p.coeffs(), &[1.0, -3.0, 2.0]);
/// assert_eq!(Poly::new(buf.to_vec()).as_poly_ref(), p);
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PolyRef<'a> {
    coeffs: &'a [f64],
}

impl<'a> PolyRef<'a> {
    /// A view of `c0 + c1·x + … + cn·x^n` with `coeffs = [c0, c1, …, cn]`, trailing exact
    /// zeros (`0.0` and `-0.0`) excluded. No coefficient is rejected here; the queries check
    /// finiteness ([`RootError::NonFiniteCoefficient`]).
    pub fn new(coeffs: &'a [f64]) -> Self {
        let n = coeffs.iter().rposition(|&c| c != 0.0).map_or(0, |i| i + 1);
        PolyRef {
            coeffs: &coeffs[..n],
        }
    }

    /// The coefficients, lowest degree first; empty for the zero polynomial.
    pub fn coeffs(&self) -> &'a [f64] {
        self.coeffs
    }

    /// The degree (0 for constants and for the zero polynomial, as [`Poly::degree`]).
    pub fn degree(&self) -> usize {
        self.coeffs.len().saturating_sub(1)
    }

    /// True for the zero polynomial.
    pub fn is_zero(&self) -> bool {
        self.coeffs.is_empty()
    }

    /// [`Poly::root_bound`] of the viewed polynomial, without copying it.
    pub fn root_bound(&self) -> Option<f64> {
        root_bound_of(self.coeffs)
    }

    /// A radius `T` such that every root of *every* polynomial within `slack` of this one lies
    /// in `(−T, T)` (`slack` as in [`RootQuery::value_slack`]: `slack(R) ≥ Σₖ|Δcₖ|Rᵏ`, and the
    /// true polynomial of degree at most this one's), or `None` when no radius up to about
    /// eight times the root bound can be shown (a zero or constant polynomial, an overflow, or
    /// a slack too wide).
    ///
    /// # Accuracy
    /// `T` passes Cauchy's test with the slack, `|c_N|Tᴺ > Σ_{k<N}|cₖ|Tᵏ + slack(T)`, each side
    /// rounded the safe way. For `|s| ≥ T`, `|p_true(s)| ≥ |s|ᴺ(|c_N| − Σ_{k<N}|cₖ||s|^(k−N) −
    /// slack(|s|)/|s|ᴺ)`, and every subtracted term is non-increasing in `|s|` (so is
    /// `slack(R)/Rᴺ` for the sum `Σ|Δcₖ|Rᵏ` of degree `≤ N`): positive at `T`, positive beyond.
    /// The candidates are `T₀·2^(i/4)`, `i = −8 … 12`, from the power-of-two majorant `T₀` of
    /// Fujiwara's bound; the first to pass is returned, so `T` is within `2^(1/4)` of the
    /// smallest radius the test can show on that grid. (The former radius, four times
    /// Fujiwara's bound, made the certified search of `x³² − 1`'s rays run over 8/|d|
    /// where the roots are at 1/|d|: `4³²` times the rounding, a dozen Bernstein runs a ray.)
    pub fn root_radius_within(&self, slack: &dyn Fn(f64) -> f64) -> Option<f64> {
        let c = self.coeffs;
        let n = self.degree();
        if n == 0 || !c.iter().all(|x| x.is_finite()) {
            return None;
        }
        let lead = c[n].abs();
        // |x| < 2^e(x); Fujiwara: every root is below 2·maxₖ |cₖ/c_N|^(1/(N−k)) ≤ 2^(1 + s0).
        let e_n = binary_exponent(lead);
        let s0 = c[..n]
            .iter()
            .enumerate()
            .filter(|(_, x)| **x != 0.0)
            .map(|(k, &x)| {
                let span = (binary_exponent(x) + 1 - e_n) as f64;
                (span / (n - k) as f64).ceil() as i32
            })
            .max()?;
        let t0 = 2f64.powi(s0 + 1);
        // Relative rounding of n products and sums, doubled, on each side of the test.
        let margin = 2.0 * (n + 2) as f64 * f64::EPSILON;
        (-8..=12)
            .map(|i| t0 * 2f64.powf(f64::from(i) / 4.0))
            .find(|&t| {
                let (mut rest, mut t_k) = (0.0f64, 1.0f64);
                for &ck in &c[..n] {
                    rest += ck.abs() * t_k;
                    t_k *= t;
                }
                let lhs = lead * t_k * (1.0 - margin);
                t.is_finite() && lhs > rest * (1.0 + margin) + slack(t)
            })
    }

    /// A root query on `(lo, hi]` with `opts` and no statistics (see [`RootQuery`]).
    /// Infinite ends are accepted.
    pub fn roots(self, lo: f64, hi: f64, opts: &RootOptions) -> RootQuery<'a, 'static> {
        RootQuery {
            poly: Stored::borrowed(self.coeffs),
            range: (lo, hi),
            opts: *opts,
            stats: None,
            slack: Slack::NONE,
        }
    }
}

impl Poly<f64> {
    /// A borrowed view of the coefficients.
    pub fn as_poly_ref(&self) -> PolyRef<'_> {
        PolyRef::new(self.coeffs())
    }

    /// A root query on `(lo, hi]` with `opts` and no statistics (see [`RootQuery`]): the
    /// same answers as the `Poly` methods, with the statistics optional.
    ///
    /// # Examples
    /// ```
    /// use poly::{Poly, RootOptions, RootStats};
    /// let p = Poly::<f64>::from_roots(&[-1.0, 0.5, 2.0]);
    /// let opts = RootOptions::new(1e-12);
    /// assert_eq!(p.roots(-10.0, 10.0, &opts).all()?.len(), 3);
    /// let mut stats = RootStats::default();
    /// let first = p.roots(0.0, 10.0, &opts).stats(&mut stats).smallest()?;
    /// assert!(first.is_some_and(|r| (r - 0.5).abs() <= 1e-12));
    /// assert_eq!(stats.queries, 1);
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn roots(&self, lo: f64, hi: f64, opts: &RootOptions) -> RootQuery<'_, 'static> {
        RootQuery {
            poly: Stored::owned(self),
            ..self.as_poly_ref().roots(lo, hi, opts)
        }
    }
}

/// A root query being built: polynomial, range `(lo, hi]`, options, and optionally the
/// statistics to fill in and a value slack. Made by [`PolyRef::roots`] or [`Poly::roots`].
///
/// # Accuracy
/// Each answer is that of the [`Poly`] method of the same purpose with the same options:
/// certified for [`IsolationMethod::Bernstein`](crate::IsolationMethod::Bernstein) (the
/// default) and [`IsolationMethod::Exact`](crate::IsolationMethod::Exact), heuristic for the
/// two Sturm methods (which report [`RootError::Unresolved`] rather than a guess when their
/// refinement stalls).
///
/// # Cost
/// [`smallest`](Self::smallest) runs on the borrowed coefficients themselves. The all-roots
/// queries, and the exact and heuristic methods, copy the `n + 1` coefficients of a
/// [`PolyRef`] once into a per-thread buffer reused across queries (that machinery works on
/// a [`Poly`]), so they too allocate nothing once the buffer has grown to size.
#[derive(Debug)]
#[must_use = "a query does nothing until one of `smallest`, `all`, `all_into` or `isolate` runs it"]
pub struct RootQuery<'p, 's> {
    poly: Stored<'p>,
    range: (f64, f64),
    opts: RootOptions,
    stats: Option<&'s mut RootStats>,
    slack: Slack<'p>,
}

impl<'p, 's> RootQuery<'p, 's> {
    /// Fills in `stats` (counters are added to, never reset).
    pub fn stats<'t>(self, stats: &'t mut RootStats) -> RootQuery<'p, 't> {
        RootQuery {
            poly: self.poly,
            range: self.range,
            opts: self.opts,
            stats: Some(stats),
            slack: self.slack,
        }
    }

    /// Certifies the answer for every polynomial within `slack` of the stored one, instead
    /// of for the stored coefficients alone: `slack(R)` must bound `Σₖ |Δcₖ|·Rᵏ` for the
    /// differences `Δcₖ` between the true coefficients and the stored ones, for every `R ≥ 0`,
    /// and be non-decreasing in `R`; the true polynomial must not have a higher degree than
    /// the stored one (a Bernstein coefficient of the difference is read as a blossom of the
    /// stored degree). A ray tracer that computed the coefficients in floating point passes
    /// its bound on their rounding here.
    ///
    /// # Accuracy
    /// Every sign the certified path uses — Bernstein coefficients on each sub-interval
    /// (blossom values, each bounded by `Σ|Δcₖ|Rᵏ` on `[−R, R]`), the values at the ends, at
    /// refinement points — must exceed its rounding bound *plus* `slack(R)`. Each answer is
    /// then that of the *true* polynomial, with the guarantees of the query without slack.
    /// Where a sign stays undecided because of the slack, no precision of the stored
    /// coefficients can help, so the query does not escalate to double-double, wide floats or
    /// exact arithmetic: it answers [`RootError::SlackLimited`] (counted in
    /// [`RootStats::slack_limited`]), and the caller must tighten the coefficients (compute
    /// them more accurately, or exactly). The same answer for an infinite end, for the
    /// heuristic and exact isolation methods (which certify only stored coefficients), and
    /// for a root the slack leaves closer to the range's start than it can separate.
    ///
    /// # Cost
    /// `slack` is called once per Bernstein run and once per refinement (usually twice a
    /// query); the sign tests add one addition each. Closed forms (degrees 1–2) and the
    /// `x^k` deflation are skipped: they read the stored coefficients as exact.
    pub fn value_slack(self, slack: &'p dyn Fn(f64) -> f64) -> Self {
        RootQuery {
            slack: Slack::new(slack),
            ..self
        }
    }

    /// Runs `f` on the polynomial, the range, the options, the slack and the statistics (the
    /// caller's, or a throw-away set).
    fn run<R>(
        self,
        f: impl FnOnce(Stored<'p>, (f64, f64), &RootOptions, Slack<'p>, &mut RootStats) -> R,
    ) -> R {
        // Zeroed only when the caller keeps no statistics: `RootStats` is ~300 bytes, and
        // clearing it on every query was a measurable share of a torus ray (a memset per
        // query; docs/speed.md, "Redesign before/after").
        let mut local;
        let stats = match self.stats {
            Some(s) => s,
            None => {
                local = RootStats::default();
                &mut local
            }
        };
        f(self.poly, self.range, &self.opts, self.slack, stats)
    }

    /// The smallest distinct real root in `(lo, hi]`, as
    /// [`Poly::try_smallest_root`] (the ray tracer's query). An infinite end is first replaced
    /// by Cauchy's bound (see [`Poly::smallest_root`]).
    ///
    /// # Errors
    /// As [`Poly::try_smallest_root`].
    pub fn smallest(self) -> Result<Option<f64>, RootError> {
        // On the coefficients as they are, borrowed or owned: no copy (see `stored::Stored`).
        self.run(|p, (lo, hi), o, sl, s| try_smallest(p, lo, hi, o, sl, s))
    }

    /// Every distinct real root in `(lo, hi]`, sorted, as [`Poly::real_roots_with`].
    ///
    /// # Errors
    /// As [`Poly::real_roots_with`].
    pub fn all(self) -> Result<Vec<f64>, RootError> {
        let mut out = Vec::new();
        self.all_into(&mut out)?;
        Ok(out)
    }

    /// [`all`](Self::all) appended to a caller's buffer, as [`Poly::real_roots_into`] (on an
    /// error `out` is left as it was).
    ///
    /// # Errors
    /// As [`Poly::real_roots_into`].
    pub fn all_into(self, out: &mut Vec<f64>) -> Result<(), RootError> {
        self.run(|p, (lo, hi), o, sl, s| {
            p.with_poly(|p| p.real_roots_into_slack(lo, hi, o, sl, s, out))
        })
    }

    /// Isolating intervals of every distinct real root in `(lo, hi]`, as
    /// [`Poly::isolate_roots_with`].
    ///
    /// # Errors
    /// As [`Poly::isolate_roots_with`].
    pub fn isolate(self) -> Result<Vec<RootInterval<f64>>, RootError> {
        self.run(|p, (lo, hi), o, sl, s| {
            if sl.is_some() {
                // Intervals are not refined, so they certify nothing about a true polynomial.
                s.slack_limited += 1;
                return Err(RootError::SlackLimited { lo, hi });
            }
            p.with_poly(|p| p.isolate_roots_with(lo, hi, o, s))
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Issue 11: a value slack is folded into every sign test, and a sign it leaves undecided
    /// is reported, never escalated to higher precision of the stored coefficients.
    #[test]
    fn value_slack_certifies_nearby_polynomials_or_says_it_cannot() {
        let o = RootOptions::new(1e-12);
        // x² + 1e-10: no real root as stored, but x² − 1e-10 (two roots ±1e-5) is within a
        // slack of 1e-9: the answer depends on it.
        let tight = |_r: f64| 1e-12;
        let wide = |_r: f64| 1e-9;
        let p = PolyRef::new(&[1e-10, 0.0, 1.0]);
        let mut s = RootStats::default();
        assert_eq!(p.roots(-1.0, 1.0, &o).smallest(), Ok(None), "as stored");
        let q = p.roots(-1.0, 1.0, &o).value_slack(&tight).stats(&mut s);
        assert_eq!(q.smallest(), Ok(None), "a small slack keeps the answer");
        let q = p.roots(-1.0, 1.0, &o).value_slack(&wide).stats(&mut s);
        assert!(
            matches!(q.smallest(), Err(RootError::SlackLimited { .. })),
            "a wide slack is reported"
        );
        assert_eq!(s.slack_limited, 1, "{s:?}");
        assert_eq!(
            (s.adaptive_pieces, s.exact_fallbacks, s.closed_form),
            (0, 0, 0),
            "no escalation, no closed form: {s:?}"
        );
        // Well-separated roots: the same answers with a slack growing like the degree.
        let r = Poly::<f64>::from_roots(&[-0.75, 0.125, 0.5, 0.875]);
        // (A root moves by about slack/|p'| ≈ 1e-12 here: the tolerance is above that.)
        let grow = |r: f64| 1e-13 * (1.0 + r).powi(4);
        let o = RootOptions::new(1e-10);
        let with = r.roots(-1.0, 1.0, &o).value_slack(&grow).all().unwrap();
        assert_eq!(with.len(), 4, "{with:?}");
        for (a, b) in with.iter().zip(r.real_roots(-1.0, 1.0, 1e-10).unwrap()) {
            assert!((a - b).abs() <= 2e-10, "{a} vs {b}");
        }
        assert!(
            matches!(
                r.roots(0.0, f64::INFINITY, &o)
                    .value_slack(&grow)
                    .smallest(),
                Err(RootError::SlackLimited { .. })
            ),
            "no slack holds on an infinite range"
        );
    }

    /// Issue 11: the radius beyond which no polynomial within a slack has a root is Cauchy's
    /// test with the slack, within a quarter octave of the smallest such radius on its grid,
    /// where four times Fujiwara's bound was 8× the roots' modulus for `(d·u)³² − 1`.
    #[test]
    fn root_radius_within_a_slack_is_tight_and_refuses_a_wide_slack() {
        let d = 0.3f64;
        let mut c = vec![0.0; 33];
        c[0] = -1.0;
        c[32] = d.powi(32);
        let p = PolyRef::new(&c);
        let tiny = |r: f64| 1e-14 * (1.0 + (d * r).powi(32));
        let t = p.root_radius_within(&tiny).expect("a radius");
        // The roots have modulus 1/d; Cauchy's test passes once (dT)³² > 1 + slack.
        assert!(t > 1.0 / d && t < 1.25 / d, "T = {t}, 1/d = {}", 1.0 / d);
        // Past T even the worst polynomial within the slack keeps away from zero.
        for s in [t, 2.0 * t, 10.0 * t] {
            assert!((d * s).powi(32) - 1.0 > tiny(s), "s = {s}");
        }
        let wide = |r: f64| (d * r).powi(32) * 2.0;
        assert_eq!(
            p.root_radius_within(&wide),
            None,
            "a slack above the leading term"
        );
        assert_eq!(
            PolyRef::new(&[3.0]).root_radius_within(&tiny),
            None,
            "a constant"
        );
    }

    /// A quadratic on borrowed coefficients, answered on the slice itself (issue 12, ninth
    /// pass; since the tenth, every smallest-root query of a [`PolyRef`] runs on its slice:
    /// [`Stored`]), gives the owned query's answer, error and statistics on
    /// random quadratics and ranges (roots inside, outside, at the ends, double roots the
    /// closed form leaves to the general path, no real roots), empty and infinite ranges, NaN
    /// ends, invalid tolerances, other methods and the closed form switched off.
    #[test]
    fn borrowed_quadratic_answers_as_the_owned_query() {
        use rand::{Rng, SeedableRng};
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(12);
        let mut decided_by_closed_form = 0;
        for k in 0..20_000 {
            let (r1, r2) = (rng.gen_range(-4.0..4.0f64), rng.gen_range(-4.0..4.0f64));
            let a = rng.gen_range(0.1..3.0f64) * if k % 2 == 0 { 1.0 } else { -1.0 };
            let c = match k % 5 {
                // No real roots.
                0 => [a * (r1 * r1 + 1.0), 0.0, a],
                // A double root.
                1 => [a * r1 * r1, -2.0 * a * r1, a],
                _ => [a * r1 * r2, -a * (r1 + r2), a],
            };
            let (mut lo, mut hi) = (rng.gen_range(-5.0..5.0f64), rng.gen_range(-5.0..5.0f64));
            match k % 11 {
                0 => lo = r1,
                1 => hi = r2,
                2 => hi = f64::INFINITY,
                3 => lo = f64::NEG_INFINITY,
                4 => lo = f64::NAN,
                _ => {}
            }
            let mut o = RootOptions::new(10f64.powi(-rng.gen_range(0..15)));
            match k % 13 {
                0 => o.x_tol = -1.0,
                1 => o.closed_form = false,
                2 => o.isolation = crate::IsolationMethod::Sturm,
                3 => o.x_tol = hi - lo,
                _ => {}
            }
            let (mut borrowed, mut owned) = (RootStats::default(), RootStats::default());
            let got = PolyRef::new(&c)
                .roots(lo, hi, &o)
                .stats(&mut borrowed)
                .smallest();
            let p = Poly::new(c.to_vec());
            let want = p.try_smallest_root(lo, hi, &o, &mut owned);
            assert_eq!(got, want, "{c:?} on ({lo}, {hi}] with {o:?}");
            assert_eq!(borrowed, owned, "statistics of {c:?} on ({lo}, {hi}]");
            decided_by_closed_form += owned.closed_form;
        }
        assert!(
            decided_by_closed_form > 5_000,
            "the closed form decides most: {decided_by_closed_form}"
        );
    }

    #[test]
    fn borrowed_and_owned_queries_agree_and_stats_are_optional() {
        let p = Poly::<f64>::from_roots(&[-3.0, 0.25, 1.5, 7.0]);
        let buf: Vec<f64> = p.coeffs().iter().copied().chain([0.0, -0.0]).collect();
        let view = PolyRef::new(&buf);
        assert_eq!(view.coeffs(), p.coeffs(), "trailing zeros excluded");
        let o = RootOptions::new(1e-13);
        let want = p.real_roots(-10.0, 10.0, 1e-13).unwrap();
        assert_eq!(view.roots(-10.0, 10.0, &o).all().unwrap(), want, "all");
        let mut s = RootStats::default();
        let first = view.roots(0.0, 10.0, &o).stats(&mut s).smallest().unwrap();
        assert_eq!(first, p.smallest_root(0.0, 10.0, 1e-13), "smallest");
        assert_eq!((s.queries, s.with_root), (1, 1), "stats filled in");
        let ivs = view.roots(-10.0, 10.0, &o).isolate().unwrap();
        assert_eq!(ivs, p.isolate_roots(-10.0, 10.0).unwrap(), "isolate");
        let mut out = vec![99.0];
        view.roots(-10.0, 0.0, &o).all_into(&mut out).unwrap();
        // Another range, so possibly another path (one root on (−10, 0] goes to subdivision,
        // four on (−10, 10) to the discs): the same root within the tolerance.
        assert_eq!((out.len(), out[0]), (2, 99.0), "appended");
        assert!(
            (out[1] - want[0]).abs() <= o.x_tol,
            "{out:?} against {want:?}"
        );
        assert_eq!(
            PolyRef::new(&[0.0, 0.0]).roots(0.0, 1.0, &o).smallest(),
            Err(RootError::ZeroPolynomial),
            "all-zero buffer is the zero polynomial"
        );
    }
}

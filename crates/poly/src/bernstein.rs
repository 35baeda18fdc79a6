//! [`BernsteinIsolator`]: certified root isolation by Descartes' rule in the Bernstein basis,
//! in `f64` with a rigorous bound on every rounding error.
//!
//! The interval `[t_min, t_max]` is mapped to `[0, 1]` by `t = a + w·u` (`a = t_min`, `w` the
//! difference rounded *up*, so `a + w ≥ t_max`). The Bernstein coefficients `bᵢ` of
//! `q(u) = p(a + w·u)` on `[0, 1]` have the property that the number of sign changes in
//! `b₀, …, bₙ` bounds the number of roots in `(0, 1)` and has the same parity (Descartes' rule
//! in the Bernstein basis). So no change means no root, one change means exactly one root;
//! otherwise the interval is halved with de Casteljau's algorithm, leftmost half first, so the
//! smallest root is found without isolating the others (Collins–Akritas, "Polynomial real root
//! isolation using Descartes' rule of signs", 1976; see `paper-notes/isolation.md`).
//!
//! Error bound. For a straight-line program of `+` and `×` with at most `k` roundings along any
//! path, `|b̂ᵢ − bᵢ| ≤ γ(k)·mᵢ` where `mᵢ` is the same program run exactly on absolute values
//! (Higham, *Accuracy and Stability*, §3.1, the standard model). Here that program computes the
//! Bernstein coefficients of `q̃(u) = Σ|c_k|(|a| + |w|·u)^k`, whose power coefficients are all
//! non-negative; a Bernstein coefficient of such a polynomial is `Σ_j C(i,j)/C(n,j)·q̃_j ≤ q̃(1)`,
//! and de Casteljau's averages never exceed their inputs. So one number bounds every `mᵢ` of
//! every node: `M = q̃(1) = Σ|c_k|(|a| + |w|)^k`, computed once by Horner's rule and inflated
//! for its own rounding. A sign is used only when `|b̂ᵢ| > γ(k)·M + (underflow allowance)`, so
//! the sign changes counted are those of the exact Bernstein coefficients of the stored
//! polynomial on the exact sub-interval. When a needed sign cannot be certified the isolator
//! reports failure and the caller switches to exact rational arithmetic.

use smallvec::SmallVec;

use crate::eval_bound::{
    certified_sign, certified_value, certified_value_pair, chain_underflow_weight,
    gamma_ratio_upper,
};
use crate::stats::RootStats;
use crate::univariate::ETA;

/// Storage for one node's coefficients: a fixed array (no heap allocation; only the first
/// `n + 1` entries are used) for the degrees a renderer meets, a `Vec` above.
pub(crate) trait Coeffs: Clone + std::fmt::Debug {
    /// `Some(n + 1)` when the storage length *is* the number of coefficients, so loops over
    /// them have compile-time bounds (unrolled, no bounds checks).
    const EXACT_LEN: Option<usize>;
    fn zeroed(len: usize) -> Self;
    fn at(&self) -> &[f64];
    fn at_mut(&mut self) -> &mut [f64];
}

impl<const N: usize> Coeffs for [f64; N] {
    const EXACT_LEN: Option<usize> = Some(N);
    #[inline]
    fn zeroed(_len: usize) -> Self {
        [0.0; N]
    }
    #[inline]
    fn at(&self) -> &[f64] {
        self
    }
    #[inline]
    fn at_mut(&mut self) -> &mut [f64] {
        self
    }
}

/// A fixed array with room for up to `N` coefficients (degrees without an exact-size array).
#[derive(Clone, Copy, Debug)]
pub(crate) struct Cap<const N: usize>([f64; N]);

impl<const N: usize> Coeffs for Cap<N> {
    const EXACT_LEN: Option<usize> = None;
    #[inline]
    fn zeroed(_len: usize) -> Self {
        Cap([0.0; N])
    }
    #[inline]
    fn at(&self) -> &[f64] {
        &self.0
    }
    #[inline]
    fn at_mut(&mut self) -> &mut [f64] {
        &mut self.0
    }
}

impl Coeffs for Vec<f64> {
    const EXACT_LEN: Option<usize> = None;
    fn zeroed(len: usize) -> Self {
        vec![0.0; len]
    }
    fn at(&self) -> &[f64] {
        self
    }
    fn at_mut(&mut self) -> &mut [f64] {
        self
    }
}

/// Deepest subdivision tried before giving up on `f64`: intervals of relative width 2^-52
/// are a single rounding step of the map `a + w·u`, so no sign below that can be certified.
const MAX_DEPTH: u16 = 52;

/// Most subdivisions tried in one query, over all its runs, before giving up on `f64` (a
/// polynomial with many clustered roots is cheaper to isolate exactly than to subdivide for
/// ever).
pub(crate) const MAX_SPLITS: u32 = 4000;

/// A sub-interval `[u0, u1]` of `[0, 1]` with the Bernstein coefficients of `q` on it.
#[derive(Clone, Debug)]
struct Node<S> {
    /// Computed Bernstein coefficients.
    v: S,
    u0: f64,
    u1: f64,
    /// Number of cuts (halvings or jumps) from the top node.
    depth: u16,
    /// Rounding steps along any path from the stored coefficients to these.
    ops: u32,
    /// `log₂ N` of the node's jump ratio: a cluster jump ([`BernsteinIsolator::jump_cut`])
    /// keeps `1/N` of the node's width as a margin before the predicted cluster.
    jump: u8,
}

/// A bracket `(lo, hi)` holding exactly one distinct real root, of odd multiplicity, with
/// certified signs: `p(lo)` has sign `s_lo` and `p(hi)` sign `−s_lo`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Bracket {
    pub(crate) lo: f64,
    pub(crate) hi: f64,
    pub(crate) s_lo: i8,
    /// `p(lo)` and `p(hi)` as computed when their signs were certified (NaN: not computed);
    /// the secant-based refinements start from them instead of evaluating again.
    pub(crate) f_lo: f64,
    pub(crate) f_hi: f64,
    /// A first trial point for the refinement (NaN: none): where the node's control polygon
    /// crosses zero, usually far closer to the root than the bracket's midpoint.
    pub(crate) guess: f64,
}

impl Bracket {
    /// A bracket whose end values are not known yet.
    pub(crate) fn new(lo: f64, hi: f64, s_lo: i8) -> Self {
        Bracket {
            lo,
            hi,
            s_lo,
            f_lo: f64::NAN,
            f_hi: f64::NAN,
            guess: f64::NAN,
        }
    }
}

/// Brackets found by one isolator run (sorted, disjoint).
pub(crate) type Brackets = SmallVec<[Bracket; 4]>;

/// Where an isolator run got stuck: a sign it needed could not be certified in `f64` in the
/// node `[u0, u1]`. Everything in `(t_min, t_a]` has been answered (the brackets found so far,
/// and no other root); the stuck node lies within `(t_a, t_b]`. Both ends are `f64` numbers
/// with certified non-zero signs `s_a`, `s_b` (`t_b = t_max` when the node reaches it), so the
/// caller can go on with fresh, tighter work on `(t_a, t_b]` and then `(t_b, t_max]`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Stuck {
    pub(crate) t_a: f64,
    pub(crate) s_a: i8,
    pub(crate) t_b: f64,
    pub(crate) s_b: i8,
    /// The run's magnitude bound `M` (see the module docs): a fresh run on a narrower
    /// interval helps only when its own `M` is much smaller.
    pub(crate) mag: f64,
}

/// Certified Bernstein-basis isolation of the roots of one `f64` polynomial in `(t_min, t_max]`.
#[derive(Debug)]
pub(crate) struct BernsteinIsolator<'p, S> {
    p: &'p [f64],
    n: usize,
    a: f64,
    w: f64,
    w_exact: bool,
    t_max: f64,
    /// Nodes with `u0 > u_beyond` lie entirely beyond `t_max` (only when `w` was rounded up).
    u_beyond: f64,
    /// Certified signs of `p(t_min)` and `p(t_max)` (non-zero).
    s_min: i8,
    s_max: i8,
    /// Bound on the accumulated underflow error per rounding step (see [`Self::tiny`]).
    underflow_unit: f64,
    /// `M`, a bound on the absolute-value weight of every coefficient of every node.
    mag: f64,
    /// The caller's bound on every Bernstein coefficient, and every value, of the difference
    /// between the true polynomial and the stored one on this run's interval (0 for the
    /// stored polynomial; see [`Slack`](crate::stored::Slack)). Added to every error bound.
    slack: f64,
    top: Node<S>,
}

impl<'p, S: Coeffs> BernsteinIsolator<'p, S> {
    /// Sets up the search on `(t_min, t_max]` for the polynomial with coefficients `p` (lowest
    /// first, finite, degree ≥ 1, last one non-zero). The caller has certified the signs
    /// `s_min` of `p(t_min)` and `s_max` of `p(t_max)` (both non-zero) and checked
    /// `t_min < t_max`, both finite. `None` when the map to `[0, 1]` overflows.
    ///
    /// `slack` bounds `Σ|Δcₖ|Rᵏ` for the difference `Δ` between the true and the stored
    /// coefficients and `R = max(|t_min|, |a + w|)`: then every Bernstein coefficient of `Δ`
    /// on every node is at most `slack` (they are blossom values, each a convex combination of
    /// products of numbers of modulus at most `R`), and so is `|Δ(t)|` at every point.
    #[inline(always)]
    pub(crate) fn new(
        p: &'p [f64],
        t_min: f64,
        t_max: f64,
        (s_min, s_max): (i8, i8),
        slack: f64,
    ) -> Option<Self> {
        let n = S::EXACT_LEN.map_or(p.len() - 1, |len| len - 1);
        debug_assert_eq!(n + 1, p.len(), "storage matches the degree");
        let (w, w_exact) = diff_rounded_up(t_max, t_min);
        if !w.is_finite() {
            return None;
        }
        let a = t_min;
        let mut vs = S::zeroed(n + 1);
        let base_ops = bernstein_on(p, n, a, w, vs.at_mut());
        let (aa, aw) = (a.abs(), w.abs());
        // Underflow: each rounding may add up to ETA absolutely; later steps multiply such an
        // error by at most (|a| + |w|) per Horner step and by at most n + 1 in the basis
        // change (de Casteljau only averages). Each output depends on at most (n+1)² roundings
        // per stage.
        // Without a shift, the chain wʲ's own underflow errors are multiplied by |c_j|
        // (`chain_underflow_weight`); with one, the coefficients only add.
        let amp = (1.0 + aa + aw).powi(n as i32) * (n + 1) as f64;
        let chain = if a == 0.0 {
            chain_underflow_weight(p, 0.0, w, f64::MIN_POSITIVE) * (n + 1) as f64
        } else {
            0.0
        };
        let underflow_unit = ETA * (amp + chain) * ((n + 1) * (n + 1)) as f64;
        let mag = magnitude(p, aa + aw);
        if !mag.is_finite() {
            return None;
        }
        Some(BernsteinIsolator {
            p,
            n,
            a,
            w,
            w_exact,
            t_max,
            s_min,
            s_max,
            underflow_unit,
            mag,
            slack,
            // (t_max − a)/w rounded up: two roundings, each within a relative u.
            u_beyond: if w_exact {
                1.0
            } else {
                (t_max - a) / w * (1.0 + 4.0 * f64::EPSILON)
            },
            top: Node {
                v: vs,
                u0: 0.0,
                u1: 1.0,
                depth: 0,
                ops: base_ops,
                jump: MIN_JUMP,
            },
        })
    }

    /// The degree: a compile-time constant for exact-size storage.
    #[inline]
    fn n(&self) -> usize {
        match S::EXACT_LEN {
            Some(len) => len - 1,
            None => self.n,
        }
    }

    /// The absolute underflow allowance of a node at this depth (each cut adds at most two
    /// roundings per level, none of which amplifies an earlier error).
    fn tiny(&self, depth: u16) -> f64 {
        self.underflow_unit * f64::from(4 + 2 * u32::from(depth))
    }

    /// The error bound shared by every coefficient of `node`: `γ(k)·M + tiny`.
    fn threshold(&self, node: &Node<S>) -> f64 {
        // The factor (1 + 8ε) covers the roundings of this bound itself.
        gamma_ratio_upper(node.ops as usize) * self.mag * (1.0 + 8.0 * f64::EPSILON)
            + self.tiny(node.depth)
            + self.slack
    }

    /// Certified signs of the node's coefficients (0 = not certain). The end coefficients of
    /// nodes touching `u = 0` (and `u = 1` when `w` is exact) are the values `p(t_min)`,
    /// `p(t_max)`, whose signs the caller certified directly.
    #[inline(always)]
    fn classify(&self, node: &Node<S>) -> Class {
        let err = self.threshold(node);
        let v = node.v.at();
        let n = self.n();
        let sign = |i: usize| -> i8 { i8::from(v[i] > err) - i8::from(-v[i] > err) };
        // Called only when some sign is uncertain (off the common path).
        let undecided = || {
            if v[..=n].iter().all(|x| x.abs() <= err) {
                // Every coefficient is within its error bound: halving only averages them,
                // so no descendant can be decided in this run.
                Class::Hopeless
            } else {
                Class::Split { changes: 0, err }
            }
        };
        let first = if node.u0 == 0.0 { self.s_min } else { sign(0) };
        let last = if node.u1 == 1.0 && self.w_exact {
            self.s_max
        } else {
            sign(n)
        };
        if first == 0 || last == 0 {
            return undecided();
        }
        let mut prev = first;
        let mut changes = 0u32;
        for i in 1..n {
            let s = sign(i);
            if s == 0 {
                return undecided();
            }
            changes += u32::from(s != prev);
            prev = s;
        }
        changes += u32::from(last != prev);
        match changes {
            0 => Class::Empty,
            1 => Class::One,
            changes => Class::Split { changes, err },
        }
    }

    /// Cuts a node with de Casteljau's algorithm at `λ` of its width (`λ = 1/2`: halving;
    /// else a jump, whose `u` is exact, [`Self::jump_cut`]): returns (left, right).
    #[allow(
        clippy::needless_range_loop,
        reason = "two arrays indexed together; with exact-size storage the range form unrolls"
    )]
    fn split(&self, node: Node<S>, cut: Cut) -> (Node<S>, Node<S>) {
        let n = self.n();
        let mut lvs = node.v.clone();
        let mut rvs = node.v;
        let (lv, rv) = (lvs.at_mut(), rvs.at_mut());
        // Halving: one rounded addition per level (the halving is exact). A jump at `λ`:
        // `(1 − λ)·x + λ·y`, with `1 − λ` exact (`λ` has few bits), is two products and a
        // sum, three roundings per level; its weights are convex, so the magnitude bound `M`
        // still bounds every absolute-value weight (module docs) and earlier errors are not
        // amplified, and its two products add at most two underflow units per level, the
        // allowance per cut in `tiny` (a halving's product by 1/2 adds one).
        // (Exclusive ranges, for the reason given in `bernstein_on`.)
        let (mid, per_level, (left_jump, right_jump)) = match cut {
            Cut::Half => {
                for r in 1..n + 1 {
                    for i in 0..n + 1 - r {
                        rv[i] = (rv[i] + rv[i + 1]) * 0.5;
                    }
                    lv[r] = rv[0];
                }
                let jump = (node.jump / 2).max(MIN_JUMP);
                (0.5 * (node.u0 + node.u1), 1, (jump, jump))
            }
            Cut::Unresolvable => unreachable!("an unresolvable node is not split"),
            Cut::Jump { lambda, u, jump } => {
                let mu = 1.0 - lambda;
                for r in 1..n + 1 {
                    for i in 0..n + 1 - r {
                        rv[i] = mu * rv[i] + lambda * rv[i + 1];
                    }
                    lv[r] = rv[0];
                }
                (u, 3, (MIN_JUMP, (2 * jump).min(MAX_JUMP)))
            }
        };
        let depth = node.depth + 1;
        let ops = node.ops + per_level * n as u32;
        (
            Node {
                v: lvs,
                u0: node.u0,
                u1: mid,
                depth,
                ops,
                jump: left_jump,
            },
            Node {
                v: rvs,
                u0: mid,
                u1: node.u1,
                depth,
                ops,
                jump: right_jump,
            },
        )
    }

    /// Where to cut a node whose roots may cluster in its right part: a jump towards the
    /// cluster in the manner of ANewDsc's Newton steps (Sagraloff–Mehlhorn 2016), in the
    /// Bernstein basis; else halving; or not at all (`Unresolvable`, see below).
    ///
    /// The estimate is Laguerre's step from the node's left end, `s*`, from `q(0) = b₀`,
    /// `q'(0) = n(b₁ − b₀)`, `q''(0) = n(n − 1)(b₂ − 2b₁ + b₀)`: exact for `(s − r)ⁿ`, and
    /// for a polynomial with real roots never past the first one. The cut is `λ ≤ s* − 1/N`
    /// on the grid of `1/(4N)`, so the left part is usually empty (one classification) and
    /// the right part holds the cluster in `1/N + (1 − s*)` of the width. `N` squares after
    /// each jump and falls back to `√N` after each halving ([`Node::jump`]): a search
    /// converging on a cluster jumps quadratically. Jumps are tried only when every sign
    /// change may belong to one cluster (`n` of them, or some sign undecided) and past the
    /// middle; `N` is lowered until the cluster model `q(s) ≈ b₀(1 − s/s*)ⁿ` keeps the cut's
    /// coefficients [`JUMP_CLEARANCE`] above the error bound `err` (else the left part would
    /// be undecided too). The cut's `u` must be exact in `f64`, so the node ends stay the
    /// exact interval of the coefficients. A wrong guess only cuts the node off-centre: both
    /// parts are searched as always.
    ///
    /// `Unresolvable`: some sign is undecided and, by the same model, `|q|` is below
    /// `JUMP_CLEARANCE·err` already halfway to the cluster, so the halvings left would only
    /// narrow the stuck node by the few widths `f64` can still tell apart; the run stops
    /// there, as it does on a hopeless node, and the search's next tier takes the piece.
    /// Not with a value slack: those runs have no higher tier, only narrower runs.
    fn jump_cut(&self, node: &Node<S>, changes: u32, err: f64) -> Cut {
        let n = self.n();
        let b = node.v.at();
        if n < 2 {
            // No second derivative (an undecided linear node): halve.
            return Cut::Half;
        }
        if changes != 0 && (changes as usize != n || (b[0] + b[1]) * b[0] <= 0.0) {
            // Fewer sign changes than the degree: not one cluster (on the renderer's entry
            // rays such jumps mostly failed). Or the first leg of the control polygon crosses
            // zero before the middle (the `n`-fold Newton step, not below Laguerre's for real
            // roots): halve, without the divisions below.
            return Cut::Half;
        }
        let nf = n as f64;
        // Laguerre's step from s = 0 on q(s) = Σ bᵢ·Bᵢ(s): q(0) = b₀, q'(0) = n(b₁ − b₀),
        // q''(0) = n(n − 1)(b₂ − 2b₁ + b₀).
        let g = nf * (b[1] - b[0]) / b[0];
        let h = g * g - nf * (nf - 1.0) * (b[2] - 2.0 * b[1] + b[0]) / b[0];
        let root = ((nf - 1.0) * (nf * h - g * g)).max(0.0).sqrt();
        let s = (-nf / (g - root)).min(1.0);
        let need = JUMP_CLEARANCE * err / b[0].abs();
        if changes == 0 && self.slack == 0.0 && s > 0.0 && 0.5f64.powi(n as i32) < need {
            return Cut::Unresolvable;
        }
        // (A NaN `s`, from a zero denominator, halves too.)
        if s.is_nan() || s <= 0.5 {
            return Cut::Half;
        }
        // The left part is decided only where |q| clears the error bound: under the cluster
        // model q(s) ≈ b₀(1 − s/s*)ⁿ, at a cut λ that needs |b₀|(1 − λ/s*)ⁿ ≥ c·err. N
        // shrinks (by 4) until it does, or the cut would fall before the middle.
        let mut jump = node.jump;
        let lambda = loop {
            let grid = f64::from(1u32 << (jump + 2));
            let lambda = ((s * grid).floor() - 4.0) / grid;
            if lambda <= 0.5 {
                return Cut::Half;
            }
            if (1.0 - lambda / s).powi(n as i32) >= need {
                break lambda;
            }
            if jump < MIN_JUMP + 2 {
                return Cut::Half;
            }
            jump -= 2;
        };
        let (h, h_exact) = diff_rounded_up(node.u1, node.u0);
        let du = lambda * h;
        let u = node.u0 + du;
        if h_exact && lambda.mul_add(h, -du) == 0.0 && sum_is_exact(node.u0, du, u) && u < node.u1 {
            Cut::Jump { lambda, u, jump }
        } else {
            Cut::Half
        }
    }

    /// Certified bracket in `t` for a node holding exactly one root, or `Err(())` when the
    /// root sits within a rounding step of the node's ends. `Ok(None)` when the root lies
    /// beyond `t_max` (possible only when `w` was rounded up).
    ///
    /// The node ends `a + w·u` are not `f64` numbers in general. The bracket ends are moved
    /// one step *inwards* from the correctly rounded `fma(w, u, a)`, so they lie strictly
    /// inside the node, where there is exactly one root; the signs of `p` there are then
    /// checked with [`horner_bounded`] to prove the root was not skipped.
    fn bracket(&self, node: &Node<S>) -> Result<Option<Bracket>, ()> {
        let s_lo = if node.u0 == 0.0 {
            self.s_min
        } else if node.v.at()[0] > 0.0 {
            1
        } else {
            -1
        };
        let lo = if node.u0 == 0.0 {
            self.a
        } else {
            w_u_a(self.w, node.u0, self.a).next_up()
        };
        if lo >= self.t_max {
            // The node starts within a rounding step of t_max: its root may or may not be
            // ≤ t_max, and only exact arithmetic can tell.
            return Err(());
        }
        let mut hi = if node.u1 == 1.0 && self.w_exact {
            self.t_max
        } else {
            w_u_a(self.w, node.u1, self.a).next_down()
        };
        let (mut f_lo, mut f_hi) = (f64::NAN, f64::NAN);
        let check_lo = node.u0 != 0.0;
        let check_hi = hi <= self.t_max && !(node.u1 == 1.0 && self.w_exact);
        if check_lo && check_hi {
            // An interior node: both end signs, in one interleaved evaluation.
            let ((fl, sl), (fh, sh)) = certified_value_pair(self.p, lo, hi, self.slack);
            if sl != s_lo || sh != -s_lo {
                return Err(());
            }
            (f_lo, f_hi) = (fl, fh);
        } else if check_lo {
            let (f, s) = certified_value(self.p, lo, self.slack);
            if s != s_lo {
                return Err(());
            }
            f_lo = f;
        } else if check_hi {
            let (f, s) = certified_value(self.p, hi, self.slack);
            if s != -s_lo {
                return Err(());
            }
            f_hi = f;
        }
        if hi > self.t_max {
            // The single root of the node is ≤ t_max iff p changes sign on (lo, t_max].
            if self.s_max == s_lo {
                return Ok(None);
            }
            hi = self.t_max;
        }
        if lo >= hi {
            return Err(());
        }
        Ok(Some(Bracket {
            lo,
            hi,
            s_lo,
            f_lo,
            f_hi,
            guess: self.polygon_crossing(node),
        }))
    }

    /// Where the control polygon of `node` first crosses zero, as a `t` (NaN if it touches
    /// zero only at a coefficient). The Bernstein coefficients are the ordinates of the
    /// polygon at `u0 + (u1 − u0)·k/n`, and the polygon converges to the graph of `p`
    /// quadratically as nodes shrink, so on a node with one sign variation this is a cheap,
    /// good first trial point for Newton's method — at the top node (the whole interval,
    /// where the tracer's brackets mostly come from) much better than the midpoint. It is only
    /// a starting point: the refinement keeps its certified bracket whatever the guess.
    fn polygon_crossing(&self, node: &Node<S>) -> f64 {
        let b = &node.v.at()[..=self.n];
        let Some(k) = (0..self.n).find(|&k| b[k] * b[k + 1] < 0.0) else {
            return f64::NAN;
        };
        let frac = (k as f64 + b[k] / (b[k] - b[k + 1])) / self.n as f64;
        w_u_a(self.w, node.u0 + (node.u1 - node.u0) * frac, self.a)
    }

    /// Replaces an undecided node by its two halves on the stack (left half on top). Gives
    /// the node back when the budget is spent or the node is too narrow to halve exactly.
    ///
    /// (Rigorous Bézier clipping — cutting away the parts where the convex hull of the
    /// control polygon proves there is no root — was tried here and removed: on ray–torus
    /// and ray–Barth polynomials it almost never removed half a node, and cost more than the
    /// halvings it saved; see `paper-notes/isolation.md`.)
    fn expand(
        &self,
        node: Node<S>,
        (changes, err): (u32, f64),
        stack: &mut SmallVec<[Node<S>; 8]>,
        splits: &mut u32,
        stats: &mut RootStats,
    ) -> Result<(), Node<S>> {
        if node.depth >= MAX_DEPTH || *splits >= MAX_SPLITS {
            return Err(node);
        }
        *splits += 1;
        stats.subdivisions += 1;
        if 0.5 * (node.u0 + node.u1) <= node.u0 {
            return Err(node);
        }
        let cut = self.jump_cut(&node, changes, err);
        if cut == Cut::Unresolvable {
            return Err(node);
        }
        let (l, r) = self.split(node, cut);
        stack.push(r);
        stack.push(l);
        Ok(())
    }

    fn take_top(&mut self) -> Node<S> {
        let empty = Node {
            v: S::zeroed(0),
            u0: 0.0,
            u1: 1.0,
            depth: 0,
            ops: 0,
            jump: MIN_JUMP,
        };
        std::mem::replace(&mut self.top, empty)
    }

    /// The roots in `(t_min, t_max]`, depth-first and left half first, appended to `out` as
    /// sorted disjoint brackets; with `first_only`, stops at the first. `Err` when a sign could
    /// not be certified: the brackets already in `out` stand, and [`Stuck`] says where to go on.
    pub(crate) fn run(
        mut self,
        first_only: bool,
        out: &mut Brackets,
        splits: &mut u32,
        stats: &mut RootStats,
    ) -> Result<(), Stuck> {
        let mut stack: SmallVec<[Node<S>; 8]> = SmallVec::new();
        stack.push(self.take_top());
        while let Some(node) = stack.pop() {
            if node.u0 > self.u_beyond {
                // Entirely beyond t_max (w rounded up), and everything left of it is done.
                return Ok(());
            }
            match self.classify(&node) {
                Class::Empty => {}
                Class::One => match self.bracket(&node) {
                    Ok(Some(b)) => {
                        out.push(b);
                        if first_only {
                            return Ok(());
                        }
                    }
                    Ok(None) => return Ok(()),
                    Err(()) => return Err(self.stuck(&node, out)),
                },
                Class::Split { changes, err } => {
                    if let Err(node) = self.expand(node, (changes, err), &mut stack, splits, stats)
                    {
                        return Err(self.stuck(&node, out));
                    }
                }
                Class::Hopeless => return Err(self.stuck(&node, out)),
            }
        }
        Ok(())
    }

    /// The certified ends `(t_a, t_b]` around a stuck node (see [`Stuck`]).
    ///
    /// `t_a`: the interval left of the node holds no root other than those bracketed in
    /// `out`, whose last bracket ends at a certified sign; so the floor `max(t_min, last hi)`
    /// is a valid `t_a`, and `fma(w, u0, a)` moved one step down (strictly below the node's
    /// exact start) is a closer one when its sign is certified. `t_b`: the first point at or
    /// beyond the node's exact end `fma(w, u1, a)` one step up, then further out by fractions
    /// of the node's width, whose sign is certified; `t_max` when none is.
    fn stuck(&self, node: &Node<S>, out: &Brackets) -> Stuck {
        let (floor, s_floor) = out.last().map_or((self.a, self.s_min), |b| (b.hi, -b.s_lo));
        let (mut t_a, mut s_a) = (floor, s_floor);
        if node.u0 > 0.0 {
            let x = w_u_a(self.w, node.u0, self.a).next_down();
            if x > floor && x < self.t_max {
                let s = certified_sign(self.p, x, self.slack);
                if s != 0 {
                    (t_a, s_a) = (x, s);
                }
            }
        }
        let (mut t_b, mut s_b) = (self.t_max, self.s_max);
        if node.u1 < 1.0 {
            let end = w_u_a(self.w, node.u1, self.a).next_up();
            let width = self.w * (node.u1 - node.u0);
            for step in [0.0, 1.0 / 64.0, 1.0 / 16.0, 0.25, 1.0] {
                let x = end + width * step;
                if x.is_nan() || x >= self.t_max {
                    break;
                }
                let s = certified_sign(self.p, x, self.slack);
                if s != 0 && x > t_a {
                    (t_b, s_b) = (x, s);
                    break;
                }
            }
        }
        Stuck {
            t_a,
            s_a,
            t_b,
            s_b,
            mag: self.mag,
        }
    }
}

/// The magnitude bound `M` of a run on `(t_min, t_max]` (see the module docs), without the
/// run: a search decides from it whether a fresh run on a piece can be any tighter than its
/// parent's.
pub(crate) fn run_magnitude(p: &[f64], t_min: f64, t_max: f64) -> f64 {
    let (w, _) = diff_rounded_up(t_max, t_min);
    magnitude(p, t_min.abs() + w.abs())
}

/// `M = q̃(1) = Σ|c_k|·rᵏ` with `r = |a| + |w|`, rounded up: it bounds every absolute-value
/// weight of a run (module docs). Horner on non-negative numbers is increasing in `r`, so `r`
/// is rounded up first; the computed sum is inflated for its `2n + 2` roundings.
fn magnitude(p: &[f64], r: f64) -> f64 {
    let x = r * (1.0 + 2.0 * f64::EPSILON);
    let sum = p.iter().rev().fold(0.0, |s, c| s * x + c.abs());
    sum * (1.0 + 2.0 * gamma_ratio_upper(2 * p.len()))
}

/// `$go::<[f64; N]>(args…)` for `$len = N` coefficients from 2 to 11 — exact-size storage,
/// so that every loop over a node's coefficients is unrolled (degrees 1 to 10) — else
/// `$other`. One home for which degrees get it: the search ([`run`]) and the one-node test
/// ([`no_root_on`]).
macro_rules! exact_size {
    ($len:expr, $go:ident($($arg:expr),* $(,)?), $other:expr $(,)?) => {
        match $len {
            2 => $go::<[f64; 2]>($($arg),*),
            3 => $go::<[f64; 3]>($($arg),*),
            4 => $go::<[f64; 4]>($($arg),*),
            5 => $go::<[f64; 5]>($($arg),*),
            6 => $go::<[f64; 6]>($($arg),*),
            7 => $go::<[f64; 7]>($($arg),*),
            8 => $go::<[f64; 8]>($($arg),*),
            9 => $go::<[f64; 9]>($($arg),*),
            10 => $go::<[f64; 10]>($($arg),*),
            11 => $go::<[f64; 11]>($($arg),*),
            _ => $other,
        }
    };
}

/// [`BernsteinIsolator::run`] on `(t_min, t_max]` with coefficient storage sized to the
/// degree: fixed arrays of exactly `n + 1` entries up to degree 10 (loops with constant
/// bounds), a fixed 25-entry array up to degree 24 (no heap allocation), `Vec` above. The
/// caller has certified the non-zero signs `s_min` of `p(t_min)` and `s_max` of `p(t_max)`;
/// `splits` counts the subdivisions of the whole query (see [`MAX_SPLITS`]).
/// When the map to `[0, 1]` overflows, the whole interval is reported stuck. `slack` is the
/// run's value slack (see [`BernsteinIsolator::new`]; 0 for the stored polynomial).
#[allow(
    clippy::too_many_arguments,
    reason = "the run's inputs and its three outputs; a struct would only rename them"
)]
pub(crate) fn run(
    p: &[f64],
    (t_min, t_max): (f64, f64),
    (s_min, s_max): (i8, i8),
    slack: f64,
    first_only: bool,
    out: &mut Brackets,
    splits: &mut u32,
    stats: &mut RootStats,
) -> Result<(), Stuck> {
    fn go<S: Coeffs>(
        p: &[f64],
        (t_min, t_max, s_min, s_max, slack): (f64, f64, i8, i8, f64),
        first_only: bool,
        out: &mut Brackets,
        splits: &mut u32,
        stats: &mut RootStats,
    ) -> Result<(), Stuck> {
        match BernsteinIsolator::<S>::new(p, t_min, t_max, (s_min, s_max), slack) {
            Some(iso) => iso.run(first_only, out, splits, stats),
            None => Err(Stuck {
                t_a: t_min,
                s_a: s_min,
                t_b: t_max,
                s_b: s_max,
                mag: f64::INFINITY,
            }),
        }
    }
    let args = (t_min, t_max, s_min, s_max, slack);
    exact_size!(
        p.len(),
        go(p, args, first_only, out, splits, stats),
        match p.len() {
            12..=25 => go::<Cap<25>>(p, args, first_only, out, splits, stats),
            _ => go::<Vec<f64>>(p, args, first_only, out, splits, stats),
        }
    )
}

/// How [`BernsteinIsolator::split`] cuts a node.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Cut {
    /// At the middle.
    Half,
    /// At `λ` of the node's width, `u = u0 + λ·(u1 − u0)` exactly.
    Jump { lambda: f64, u: f64, jump: u8 },
    /// Not at all: the node is stuck.
    Unresolvable,
}

/// Smallest `log₂ N` of a cluster jump (`N = 4`, as in ANewDsc).
const MIN_JUMP: u8 = 2;

/// A factor, relative to the node's absolute error bound `err`: a jump's cut is kept where the
/// cluster model of [`BernsteinIsolator::jump_cut`] predicts `|q| ≥ JUMP_CLEARANCE·err`, and a
/// run stops when the model puts `|q|` below it halfway to the cluster. A cut where the left
/// part's coefficients would be undecided would only move the stuck node. It bounds a
/// heuristic, not a result (the classification still certifies every sign), so it needs only
/// margin for the model's error: 4 leaves two bits; 2 and 8 were not tried.
const JUMP_CLEARANCE: f64 = 4.0;

/// Largest `log₂ N`: the cut's grid, `1/(4N)`, stays within the bits a node's `u` can spare.
const MAX_JUMP: u8 = 24;

#[derive(Clone, Copy, Debug, PartialEq)]
enum Class {
    Empty,
    One,
    /// Two or more sign changes (their number), or some sign undecided (0); `err` is the
    /// node's error bound.
    Split {
        changes: u32,
        err: f64,
    },
    /// Every coefficient is within its error bound: no descendant can be decided.
    Hopeless,
}

/// `t = a + w·u` rounded once (fused multiply-add), so within half an ulp of the exact value.
fn w_u_a(w: f64, u: f64, a: f64) -> f64 {
    w.mul_add(u, a)
}

/// Whether `a + b` was computed exactly as `s = fl(a + b)` (Knuth's TwoSum error is 0).
fn sum_is_exact(a: f64, b: f64, s: f64) -> bool {
    let bb = s - a;
    (a - (s - bb)) + (b - bb) == 0.0
}

/// `hi − lo` rounded up, and whether the subtraction was exact (Knuth's TwoSum gives the
/// rounding error exactly).
fn diff_rounded_up(hi: f64, lo: f64) -> (f64, bool) {
    let s = hi - lo;
    let bb = s - hi;
    let err = (hi - (s - bb)) + (-lo - bb);
    if !s.is_finite() {
        (s, false)
    } else if err > 0.0 {
        (s.next_up(), false)
    } else {
        (s, err == 0.0)
    }
}

/// Degrees with a precomputed row of reciprocal binomials.
const RECIP_ROWS: usize = 25;

/// `RECIP_BINOM[n][j] = 1/C(n, j)` rounded to nearest, for `n < RECIP_ROWS` (computed at
/// compile time from exact integer binomials; one rounding each).
const RECIP_BINOM: [[f64; RECIP_ROWS]; RECIP_ROWS] = {
    let mut t = [[0.0; RECIP_ROWS]; RECIP_ROWS];
    let mut n = 0;
    while n < RECIP_ROWS {
        let mut c: u64 = 1;
        let mut j = 0;
        while j <= n {
            if j > 0 {
                c = c * (n - j + 1) as u64 / j as u64;
            }
            t[n][j] = 1.0 / c as f64;
            j += 1;
        }
        n += 1;
    }
    t
};

/// The Bernstein coefficients of `p` (lowest first, degree `n = p.len() − 1`) on
/// `[a, a + w]`, written into `v` (`n + 1` slots), in plain `f64`; returns the number of
/// roundings on any path ([`BernsteinIsolator::new`] bounds the error with it). The degree is
/// passed in so that callers with exact-size storage, where it is a compile-time constant,
/// get every loop unrolled.
#[inline(always)]
fn bernstein_on(p: &[f64], n: usize, a: f64, w: f64, v: &mut [f64]) -> u32 {
    debug_assert_eq!(n + 1, p.len(), "the degree of p");
    let (p, v) = (&p[..=n], &mut v[..=n]);
    // Every loop here runs over an exclusive range (`1..n + 1`, not `1..=n`): the iterator of
    // an inclusive range carries an "exhausted" flag that the compiler did not fold away, and
    // the loops were then neither unrolled nor freed of bounds checks at the exact-size
    // degrees — a tenth of the torus entry queries' instructions (`paper-notes/isolation.md`,
    // "Exclusive ranges in the inner loops"). The same holds for every basis-change loop of
    // this crate.
    // Step 1: Taylor shift and scaling, q(u) = p(a + w·u), by Horner's rule on
    // polynomials: out ← out·(a + w·u) + c_k. Per step a path meets one product and at
    // most two sums: 3 roundings per step.
    v[0] = p[n];
    if a == 0.0 {
        // No shift, only the scaling q_j = c_j·w^j: at most j + 1 ≤ n + 1 roundings on
        // any path, within the 3n the bound allows for this step (the tracer restricts
        // its polynomials at the search start, so this is its common case).
        let mut wj = 1.0;
        for (vj, &c) in v.iter_mut().zip(p) {
            *vj = c * wj;
            wj *= w;
        }
    } else {
        for k in (0..n).rev() {
            let len = n - k;
            for i in (1..len + 1).rev() {
                v[i] = v[i] * a + v[i - 1] * w;
            }
            v[0] = v[0] * a + p[k];
        }
    }
    // Step 2: power basis on [0, 1] → Bernstein basis: bᵢ = Σ_{j≤i} C(i,j)/C(n,j)·q_j,
    // as a division by C(n,j) (two roundings: the binomial and the quotient) followed by
    // n passes of neighbour sums (one rounding each).
    let binom_ops = binomial_row_into(n, v);
    for r in 1..n + 1 {
        for i in (r..n + 1).rev() {
            v[i] += v[i - 1];
        }
    }
    3 * n as u32 + binom_ops + n as u32
}

/// Whether `p` certainly has no root on `[t_min, t_max]`: its Bernstein coefficients there,
/// with the rigorous bound of [`BernsteinIsolator`] (and the value slack `slack`, as there),
/// all have the certified sign of the ends, `s_min` at `t_min` and `s_max` at `t_max` (both
/// certified by the caller). The top node's classification only — no subdivision — for the
/// degrees with exact-size storage (3 to 10); `false` for any other degree, an overflowing
/// map or any sign variation or uncertain sign (Descartes' rule then proves nothing).
pub(crate) fn no_root_on(p: &[f64], t_min: f64, t_max: f64, ends: (i8, i8), slack: f64) -> bool {
    fn go<S: Coeffs>(p: &[f64], t_min: f64, t_max: f64, ends: (i8, i8), slack: f64) -> bool {
        BernsteinIsolator::<S>::new(p, t_min, t_max, ends, slack)
            .is_some_and(|iso| matches!(iso.classify(&iso.top), Class::Empty))
    }
    let ordered = t_min.partial_cmp(&t_max) == Some(std::cmp::Ordering::Less);
    if !ordered || ends.0 == 0 || ends.0 != ends.1 || p.len() < 4 {
        return false;
    }
    exact_size!(p.len(), go(p, t_min, t_max, ends, slack), false)
}

/// Whether `p` has few roots on `(lo, hi]` by a rough count: at most one sign variation of
/// its Bernstein coefficients there, computed in plain `f64` without an error bound
/// (Descartes' rule bounds the roots by the variations in exact arithmetic). A heuristic
/// for choosing a path ([`crate::isolate`]'s all-roots queries: one or no root is found
/// by a subdivision's first classification far more cheaply than by approximating every
/// complex root), never for an answer; `false` for an infinite end or a non-finite
/// coefficient.
pub(crate) fn few_roots_likely(p: &[f64], lo: f64, hi: f64) -> bool {
    let w = hi - lo;
    if p.len() < 2 || !(lo.is_finite() && w.is_finite()) {
        return false;
    }
    let mut v: SmallVec<[f64; 64]> = SmallVec::from_elem(0.0, p.len());
    bernstein_on(p, p.len() - 1, lo, w, &mut v);
    let mut changes = 0;
    let mut last = 0.0f64;
    for &b in &v {
        if !b.is_finite() {
            return false;
        }
        if b != 0.0 {
            changes += usize::from(last != 0.0 && (b > 0.0) != (last > 0.0));
            last = b;
        }
    }
    changes <= 1
}

/// Divides `v[j]` by `C(n, j)`; returns the roundings this adds on any path.
#[inline(always)]
fn binomial_row_into(n: usize, v: &mut [f64]) -> u32 {
    if n < RECIP_ROWS {
        // Multiplication by the rounded reciprocal: two roundings (the table entry and the
        // product), and no division in the hot path.
        for (x, r) in v.iter_mut().zip(&RECIP_BINOM[n]).take(n + 1) {
            *x *= r;
        }
        2
    } else if n <= 60 {
        // Exact in u64: C(60, 30) ≈ 1.2e17 and the running product C(n, j−1)·(n − j + 1)
        // stays below 60·1.2e17 < 2^63. One rounding to f64, one for the quotient.
        let mut c: u64 = 1;
        for (j, x) in v.iter_mut().enumerate().take(n + 1) {
            if j > 0 {
                c = c * (n - j + 1) as u64 / j as u64;
            }
            *x /= c as f64;
        }
        2
    } else {
        // Multiplicative recurrence in f64: two roundings per step for the binomial.
        let mut c = 1.0f64;
        for (j, x) in v.iter_mut().enumerate().take(n + 1) {
            if j > 0 {
                c = c * (n - j + 1) as f64 / j as f64;
            }
            *x /= c;
        }
        2 * n as u32 + 1
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scalar::Rat;
    use crate::univariate::Poly;
    use num_traits::Signed;

    fn exact_bernstein(p: &Poly<f64>, a: &Rat, w: &Rat) -> Vec<Rat> {
        // q(u) = p(a + w u) exactly, then the exact basis change.
        let q = p.to_rat().unwrap().compose_affine(a, w);
        let n = p.degree();
        let binom = |n: usize, k: usize| -> Rat {
            let mut c = Rat::from_integer(1.into());
            for j in 0..k {
                c = c * Rat::from_integer(((n - j) as i64).into())
                    / Rat::from_integer(((j + 1) as i64).into());
            }
            c
        };
        (0..=n)
            .map(|i| {
                (0..=i).fold(Rat::from_integer(0.into()), |acc, j| {
                    acc + binom(i, j) / binom(n, j) * q.coeff(j)
                })
            })
            .collect()
    }

    #[test]
    fn bernstein_error_bound_contains_exact_coefficients() {
        let p = Poly::new(vec![-1.3e3, 2.7, 0.41, -7.9, 1.0, 0.031]);
        // A shifted interval (Taylor shift) and one starting at 0 (scaling only).
        for t_min in [-3.7, 0.0] {
            check_node_bounds::<6>(&p, t_min, 11.3, 1e-11);
        }
    }

    /// Issue 13 follow-up: scaling by `wʲ` with `w²` subnormal, where the chain's underflow
    /// error reaches a coefficient times `|c₂| = 72295` (the fuzzer's cubic, mirrored onto a
    /// range from 0); the allowance without `chain_underflow_weight` is twenty times too small.
    #[test]
    fn bernstein_error_bound_covers_an_underflowing_scaling_chain() {
        let p = Poly::new(vec![
            -5.007317793518e-311,
            3.8052843920488434e-153,
            -72295.13834290397,
            -100000.0,
        ]);
        // Subnormal values: the bound is 3e-6 of M there, still far below the coefficients.
        check_node_bounds::<4>(&p, 0.0, 2.6317912686010282e-158, 1e-5);
    }

    /// `max_rel`: the bound must stay below `max_rel·M` (not vacuous).
    fn check_node_bounds<const N: usize>(p: &Poly<f64>, t_min: f64, t_max: f64, max_rel: f64) {
        let iso =
            BernsteinIsolator::<[f64; N]>::new(p.coeffs(), t_min, t_max, (1, 1), 0.0).unwrap();
        let (a, w) = (
            Rat::from_float(iso.a).unwrap(),
            Rat::from_float(iso.w).unwrap(),
        );
        // The top node, the nodes reached by halving left, right, left, and those reached by
        // jumps (three roundings per level instead of one) at 11/16, then 59/64 of the right
        // part, then halving, left of a jump.
        let mut nodes = vec![iso.top.clone()];
        for path in [
            [(true, 0.5), (false, 0.5), (true, 0.5)],
            [(false, 0.6875), (false, 0.921875), (true, 0.5)],
            [(false, 0.6875), (true, 0.921875), (false, 0.5)],
        ] {
            let mut node = iso.top.clone();
            for (go_left, lambda) in path {
                let cut = if lambda == 0.5 {
                    Cut::Half
                } else {
                    let u = node.u0 + lambda * (node.u1 - node.u0);
                    assert!(
                        sum_is_exact(node.u0, lambda * (node.u1 - node.u0), u),
                        "the test's cut is exact"
                    );
                    Cut::Jump {
                        lambda,
                        u,
                        jump: MIN_JUMP,
                    }
                };
                let (l, r) = iso.split(node, cut);
                node = if go_left { l } else { r };
                nodes.push(node.clone());
            }
        }
        for node in &nodes {
            let (u0, u1) = (
                Rat::from_float(node.u0).unwrap(),
                Rat::from_float(node.u1).unwrap(),
            );
            let exact = exact_bernstein(p, &(&a + &w * &u0), &(&w * (&u1 - &u0)));
            let err = iso.threshold(node);
            for (i, e) in exact.iter().enumerate() {
                let diff = (Rat::from_float(node.v[i]).unwrap() - e).abs();
                assert!(
                    diff <= Rat::from_float(err).unwrap(),
                    "[{}, {}] coefficient {i}: computed {} exact {} bound {err}",
                    node.u0,
                    node.u1,
                    node.v[i],
                    crate::scalar::rat_to_f64(e)
                );
            }
            // Not vacuous: far below the size of the coefficients.
            assert!(err < max_rel * iso.mag, "bound {err} vs M {}", iso.mag);
        }
    }

    /// A cluster of four roots in the last `3·10⁻⁴` of `(0, 10⁴ + 3]` (a torus seen from
    /// 10⁴ units, restricted at the eye): halving needs eleven levels to come near it, jumps
    /// towards it (`jump_cut`) four. The brackets are those of the stored polynomial.
    #[test]
    fn far_cluster_is_reached_by_jumps() {
        let p = crate::testutil::planted_f64(&[9998.7, 9999.1, 10000.3, 10001.2]);
        let c = p.coeffs();
        let (lo, hi) = (0.0, 1e4 + 3.0);
        let run = |p: &[f64], lo: f64, hi: f64, stats: &mut RootStats| {
            let mut out = Brackets::new();
            let signs = (1, 1);
            let result = run(p, (lo, hi), signs, 0.0, false, &mut out, &mut 0, stats);
            (result, out)
        };
        let mut stats = RootStats::default();
        let (result, out) = run(c, lo, hi, &mut stats);
        // f64 cannot separate roots 0.4 apart at 10⁴ (the error bound is about
        // (|t| + 10⁴)⁴·γ ≈ 10³ there): the run is stuck near the cluster.
        let stuck = result.expect_err("stuck near the cluster");
        assert!(out.is_empty(), "no root before the cluster: {out:?}");
        assert!(
            stuck.t_a > 9990.0 && stuck.t_a < 9998.7,
            "everything up to near the cluster answered: {stuck:?}"
        );
        assert!(
            stats.subdivisions <= 6,
            "{} cuts (halving alone takes 11 to reach a node 10 wide)",
            stats.subdivisions
        );
        // The same cluster moved near 0 is well conditioned: the jumps cut off-centre and
        // every root is still bracketed, each bracket holding its exact root.
        let near = crate::testutil::planted_f64(&[0.95, 0.96, 0.975, 0.99]);
        let before = stats.subdivisions;
        let (result, out) = run(near.coeffs(), 0.0, 1.0, &mut stats);
        assert!(result.is_ok(), "decided in f64: {result:?}");
        assert!(stats.subdivisions > before, "subdivided");
        let exact = crate::testutil::stored_roots(&near, 0.0, 1.0);
        assert_eq!(out.len(), exact.len(), "{out:?} vs {exact:?}");
        for (b, r) in out.iter().zip(&exact) {
            assert!(b.lo < *r && *r <= b.hi, "{b:?} holds {r}");
        }
    }

    #[test]
    fn subtraction_rounded_up() {
        let (w, exact) = diff_rounded_up(1.0, 0.25);
        assert_eq!((w, exact), (0.75, true), "exact difference");
        let (w, exact) = diff_rounded_up(1.0, 1e-30);
        assert!(
            !exact && w >= 1.0,
            "1 − 1e-30 rounds to 1 and is bumped up: {w}"
        );
    }
}

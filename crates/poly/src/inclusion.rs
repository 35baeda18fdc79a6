//! Certified isolation of all real roots by simultaneous iteration and inclusion discs (the
//! MPSolve approach: Bini & Fiorentino, "Design, analysis, and implementation of a
//! multiprecision polynomial rootfinder", Numer. Algorithms 23, 2000), tried before the
//! Bernstein subdivision for the all-roots queries (`paper-notes/isolation.md`, "Inclusion
//! discs").
//!
//! Three steps, only the last of which must be right for the answer to be right:
//! 1. *Approximate* every complex root at once: Aberth–Ehrlich iteration in `f64` complex
//!    arithmetic from starting points on the circles of the Newton polygon (Bini, "Numerical
//!    computation of polynomial zeros by means of Aberth's method", Numer. Algorithms 13,
//!    1996); approximations that end near the real axis are made exactly real and polished by
//!    Newton's method with the compensated Horner value (twice the working precision).
//! 2. *Enclose*: with `z₁ … zₙ` pairwise distinct, every root of `p` lies in the union of the
//!    discs `D(zᵢ, rᵢ)`, `rᵢ ≥ n·|p(zᵢ)| / (|aₙ|·∏_{j≠i}|zᵢ − zⱼ|)`, and each connected
//!    component of `m` discs holds exactly `m` roots counted with multiplicity (Bini &
//!    Fiorentino 2000, Theorem 9; Neumaier, "Enclosing clusters of zeros of polynomials",
//!    J. Comput. Appl. Math. 156, 2003). The radii here are *upper* bounds: every rounding of
//!    `|p(zᵢ)|`, of the distances and of the product is bounded explicitly.
//! 3. *Decide the real roots*: a disc with a real centre that meets no other disc holds
//!    exactly one root, and it is real (a non-real root would bring its conjugate into the
//!    same disc, which is symmetric about the axis). Every real root lies in the real shadow
//!    `[Re zᵢ − rᵢ, Re zᵢ + rᵢ]` of some disc meeting the axis; when every shadow that meets
//!    the query range belongs to such a disc and meets no other shadow, the roots in the range
//!    are exactly those shadows' roots, and certified end signs turn each into a bracket.
//!    Anything else (overlapping discs, a non-real disc touching the range, a sign that
//!    cannot be certified) is *undecided*: those shadows, cut to the range and merged, are
//!    the parts the caller answers by subdivision, each alone (`Piece::Undecided`).
//! 4. *Exact multiple roots*: a cluster of `m` overlapping discs apart from all others holds
//!    exactly `m` roots counted with multiplicity (the theorem of step 2); when the mean of
//!    its centres, an `f64` `r`, is exactly a root of multiplicity `m` of the stored
//!    polynomial (`(x − r)^m` divides it, checked in integers), those `m` roots are all `r`,
//!    and `r` is the only real root in the cluster's shadow (`Piece::Multiple`). Descartes'
//!    rule cannot isolate a multiple root at any precision; without this the subdivision
//!    ended in exact Sturm isolation (issue 11: `(x − 1000)⁴`).

use std::cell::Cell;

use crate::bernstein::Bracket;
use crate::double_double::{DD_UNDERFLOW, DD_UNIT, Dd, gamma_u, two_prod, two_sum};
use crate::eval_bound::{
    certified_sign, comp_horner_bounded, comp_horner_bounded_and_derivative, horner_bounded,
    horner_derivative_and_bound,
};
use crate::int_poly::IntPoly;
use crate::rescale::{ldexp, with_rescaled};
use crate::scalar::rat_from_f64;
use crate::univariate::{ETA, Poly, UNIT_ROUNDOFF};

/// Lowest degree for which the all-roots queries try inclusion discs before subdivision.
/// Why this value: measured on whole corpora only (callgrind, `paper-notes/isolation.md`,
/// "Inclusion discs before subdivision"): the planted corpus of degree 3–20 takes 0.86 of
/// its instructions with the discs tried from degree 3 on; no per-degree split was measured,
/// so the threshold is the lowest degree without a closed form or a one-node Bernstein run
/// (lines and quadratics), not a measured crossover.
pub(crate) const INCLUSION_MIN_DEGREE: usize = 3;

/// Most Aberth sweeps over the approximations before the path gives up (the query then goes
/// to subdivision). Aberth's iteration converges cubically to simple roots once close; from
/// the Newton-polygon start the measured corpora (Kac, Chebyshev, planted to degree 160,
/// Wilkinson-20) need at most a few tens of sweeps, so 80 only cuts off the hopeless
/// cases (clusters, multiple roots, polynomials whose `f64` values are all noise).
const MAX_ABERTH_SWEEPS: u32 = 80;

/// Most Newton steps of the polish of one real approximation with compensated Horner values.
/// Convergence from an `f64`-accurate start to the compensated noise floor takes 1–3 steps
/// for a simple root; the rest allows a linear start (Wilkinson-20's middle roots start
/// ≈ 0.1 off, with `p'` good to ~10 %).
const MAX_POLISH_STEPS: u32 = 8;

/// Steps of the real polish ([`polish_real`]) before an approximation whose step no longer
/// shrinks by [`POLISH_CONTRACTION`] is given up as wandering. A real root's steps shrink from
/// the first or second on (quadratically near the root; from Wilkinson-20's starts ≈ 0.1 off,
/// linearly but by more than that factor). A real approximation standing for one of a
/// near-real conjugate pair has no real root to converge to and used to wander for all
/// [`MAX_POLISH_STEPS`] before [`unreal_near_pairs`] polished it as a complex root. Measured
/// (`paper-notes/isolation.md`, "Wandering approximations"): planted degree 40 and 80 and
/// Chebyshev T₁₆₀ −7 to −8 % of their instructions; giving up from the second step on (a step
/// longer than the first) cost Wilkinson-20 34 %.
const POLISH_WANDERING_AFTER: u32 = 2;

/// The factor by which each step of the real polish must shrink from the third on, relative
/// (a step's length against the one before; a heuristic for stopping, never for an answer)
/// ([`POLISH_WANDERING_AFTER`]); 0.5 cost Wilkinson-20 31 % and saved at most 0.5 % more
/// elsewhere.
const POLISH_CONTRACTION: f64 = 0.9;

/// Most Aberth sweeps of the complex polish of the near-real pairs ([`polish_complex`]),
/// with `p` and `p'` in twice the working precision from the approximations the `f64`
/// iteration left. Why 16, measured (`paper-notes/isolation.md`, "Near-real pairs: the
/// derivative in twice the precision"): the polish of planted degree 40 ends after 9–12
/// sweeps, of planted 80 after 15, of planted 3–20 after 6–9 (with `p'` in double-double,
/// 8 sweeps left two of the three degree-40 queries undecided); an approximation that has
/// converged costs nothing in the later sweeps (it is `done`).
const MAX_COMPLEX_POLISH_STEPS: u32 = 16;

/// The complex polish stops moving an approximation whose last step `w` was this many times
/// inside its gap: `POLISH_SETTLED·n·|w|` below both `|Im z|` and the distance to every
/// other approximation ([`polish_complex`]) — a relative factor (the step against the gap),
/// scale-free like both sides. Its disc radius is about `n·|w|` (the
/// Weierstrass correction times `n`), and the step already taken squared that error, so
/// further steps would not change what the certificate decides; and if they would, only the
/// certificate decides (an undecided part goes to subdivision). A heuristic: why 4, measured
/// (callgrind, `paper-notes/isolation.md`, "Near-real pairs: the derivative in twice the
/// precision"): planted 40 −6.6 % of its instructions, planted 80 −6.2 %, every query still
/// decided; 1000 saved half as much.
const POLISH_SETTLED: f64 = 4.0;

/// Lowest degree for which [`unreal_near_pairs`] runs. Why 5, measured (callgrind,
/// `paper-notes/isolation.md`, "All-roots queries: near-real pairs"): on the two
/// Orellana–De Michele quartics it fires for (degree 4, a pair near a double root) the stage
/// cost 29.6 K instructions where their subdivision cost 21.5 K; on planted degree 14–20 it
/// pays. Degrees 5–13 were not measured: the stage runs there (the test pair of degree 5).
const NEAR_REAL_MIN_DEGREE: usize = 5;

/// A real value whose rigorous `f64` error bound is more than `1/COMPENSATE_BELOW` of its
/// magnitude is recomputed by the compensated Horner scheme (relative). Why 16: above it the
/// `f64` bound adds at most 6 % to `|p(x)|` (to the disc radius, or to the Newton step's
/// error), which the compensated value would not improve enough to pay for its fused
/// multiply–adds (software-emulated on the baseline x86-64 target).
const COMPENSATE_BELOW: f64 = 16.0;

/// Largest degree handled: the scratch of the iteration and of the certificate is `O(n)`,
/// the work `O(n²)` per sweep; beyond this subdivision (and its exact fallbacks) answers.
/// Why 1024: the disc radii carry a rounding factor `(1 + (4n + 16)ε)`, which must stay
/// near 1, and the product of `n − 1` distances is renormalised each step so any `n` works;
/// the bound only keeps one query's work within milliseconds.
const MAX_DEGREE: usize = 1024;

/// Smallest distance between two centres (each coordinate difference) that the certificate
/// uses: `2^-900`. Below it products of distances could leave the normal range, where the
/// relative rounding bounds used for them fail; such approximations are treated as not
/// distinct (undecided).
const MIN_DISTANCE: f64 = f64::from_bits((1023 - 900) << 52);

/// Largest `m·n` (cluster size times degree) for which a cluster of `m` discs is checked
/// for an exact root of multiplicity `m` ([`multiple_root`]): the check is `m` exact
/// divisions of the degree-`n` integer polynomial, `m·n` big-integer products, and this
/// keeps it to a few thousand (below the cost of one exact Sturm sequence, which the
/// subdivision would otherwise build for a multiple root); larger clusters go to
/// subdivision as before.
const MAX_MULTIPLE_WORK: usize = 4096;

/// Squared moduli `|z|²` for which the iteration's shortcuts (`√(re² + im²)`, `conj(z)/|z|²`)
/// are used: `[2^-1000, 2^1000]`, far enough inside the normal range that neither square
/// underflowed to lose more than a few ulps of the sum nor overflowed, and the reciprocal
/// `1/|z|²` is normal too. Outside, `hypot` and Smith's division take over.
const FAST_NORM_RANGE: std::ops::RangeInclusive<f64> =
    f64::from_bits((1023 - 1000) << 52)..=f64::from_bits((1023 + 1000) << 52);

/// The starting circles are centred at the roots' centroid `g` when their largest radius
/// about `g` is below this multiple of `|g|` ([`starting_points`]). Why 2: the Newton
/// polygon overestimates the spread of real roots spaced evenly about `g` (Wilkinson-20
/// shifted by 10.5: radius 18.2 for roots within 9.5), and measured on the whole corpora
/// (sweeps summed, `paper-notes/isolation.md`, "Starting points"): ratio 1 left Wilkinson-20
/// at 17 sweeps (2: 8) and planted 3–20 at 1 389 (2: 935); 4 and above made the quartics
/// 1, 10³, 10⁶, 10⁹ kind slower (113 → 251) and planted 80 (116 → 146).
const CENTRED_START_RATIO: f64 = 2.0;

/// A complex number in `f64`, for the approximations.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
struct C {
    re: f64,
    im: f64,
}

impl C {
    fn new(re: f64, im: f64) -> C {
        C { re, im }
    }
    fn add(self, o: C) -> C {
        C::new(self.re + o.re, self.im + o.im)
    }
    fn sub(self, o: C) -> C {
        C::new(self.re - o.re, self.im - o.im)
    }
    fn mul(self, o: C) -> C {
        C::new(
            self.re * o.re - self.im * o.im,
            self.re * o.im + self.im * o.re,
        )
    }
    /// `1/self`, for the iteration (a heuristic: not used by the certificate). As
    /// `conj(self)/|self|²` with one division where `|self|²` is comfortably normal
    /// ([`FAST_NORM_RANGE`]; the Aberth sum takes `n − 1` reciprocals per approximation, and
    /// a division costs several multiplications); else by scaling with the larger part
    /// (Smith's rule), so that neither the square of a tiny nor of a huge part over- or
    /// underflows.
    fn recip(self) -> C {
        let q = self.re * self.re + self.im * self.im;
        if FAST_NORM_RANGE.contains(&q) {
            let r = 1.0 / q;
            return C::new(self.re * r, -self.im * r);
        }
        if self.re.abs() >= self.im.abs() {
            let t = self.im / self.re;
            let d = self.re + self.im * t;
            C::new(1.0 / d, -t / d)
        } else {
            let t = self.re / self.im;
            let d = self.re * t + self.im;
            C::new(t / d, -1.0 / d)
        }
    }
    fn div(self, o: C) -> C {
        self.mul(o.recip())
    }
    /// `|self|` to within an ulp (`hypot`), for the certificate's bounds.
    fn abs(self) -> f64 {
        self.re.hypot(self.im)
    }
    /// `|self|` to within a few ulps, for the iteration's heuristics: `√(re² + im²)` where the
    /// sum of squares is comfortably normal ([`FAST_NORM_RANGE`]), else `hypot`, which the
    /// iteration would otherwise call `O(n)` times per sweep at several times the cost.
    fn abs_fast(self) -> f64 {
        let q = self.re * self.re + self.im * self.im;
        if FAST_NORM_RANGE.contains(&q) {
            q.sqrt()
        } else {
            self.abs()
        }
    }
    fn is_finite(self) -> bool {
        self.re.is_finite() && self.im.is_finite()
    }
}

/// Reused per-thread buffers, so that the tracer's per-ray all-roots queries allocate
/// nothing once they have grown.
#[derive(Default)]
struct Scratch {
    /// The approximations `zᵢ`.
    z: Vec<C>,
    /// Whether `zᵢ` has stopped moving (converged or at the noise floor).
    done: Vec<bool>,
    /// An upper bound on `|p(zᵢ)|` that the polish computed at the final `zᵢ` (rigorous, as
    /// [`abs_p_upper`]'s), or NaN: the certificate uses it instead of evaluating again.
    p_bound: Vec<f64>,
    /// Upper bounds on the inclusion radii.
    radius: Vec<f64>,
    /// Real shadows `[lo, hi]` of the discs meeting the real axis (NaN ends: none).
    shadow: Vec<(f64, f64)>,
    /// Whether disc `i` is isolated ([`isolated`]): its one root is real and simple.
    isolated: Vec<bool>,
    /// The brackets found, before they are handed to the caller.
    brackets: Vec<Bracket>,
    /// The undecided parts `(lo, hi]` of the range, sorted and disjoint.
    undecided: Vec<(f64, f64)>,
    /// Exact multiple roots certified for clusters of discs ([`multiple_root`]).
    multiple: Vec<f64>,
    /// The answer, in order, before it is handed to the caller.
    pieces: Vec<Piece>,
    /// Union–find parents of the discs' clusters (components of discs not certainly apart).
    parent: Vec<usize>,
    /// The real centres of the isolated discs, sorted ([`decide`]'s implied signs).
    isolated_centres: Vec<f64>,
    /// Per cluster (indexed by its root in `parent`): not tried yet (`None`), or the exact
    /// multiple root certified for it (`Some(Some(r))`) or not (`Some(None)`).
    cluster: Vec<Option<Option<f64>>>,
    /// Indices of the Newton polygon's vertices, with their `log₂|aᵢ|`.
    hull: Vec<(usize, f64)>,
    /// The coefficients of `p(g + y)` for the starting points ([`starting_points`]).
    shifted: Vec<f64>,
    /// The approximation `zᵢ` as the `f64` iteration left it, before it was made real
    /// (`Im = 0` when it was not): where the real polish cannot converge, a near-real pair
    /// goes back to it ([`unreal_near_pairs`]).
    before_real: Vec<C>,
    /// Whether `zᵢ` went back to its complex value ([`unreal_near_pairs`]).
    restored: Vec<bool>,
    /// The length of `zᵢ`'s last step in [`polish_real`].
    step: Vec<f64>,
}

impl Scratch {
    /// Capacity for degree `max(n, SCRATCH_MIN_DEGREE)` in every buffer, so that a later,
    /// larger query up to that degree does not allocate (the tracer's per-ray queries, whose
    /// degrees vary from ray to ray, must not allocate after a warm-up:
    /// `crates/render/tests/bezier_no_alloc.rs`).
    fn reserve(&mut self, n: usize) {
        let m = n.max(SCRATCH_MIN_DEGREE) + 1;
        self.z.reserve(m.saturating_sub(self.z.len()));
        self.done.reserve(m.saturating_sub(self.done.len()));
        self.p_bound.reserve(m.saturating_sub(self.p_bound.len()));
        self.radius.reserve(m.saturating_sub(self.radius.len()));
        self.shadow.reserve(m.saturating_sub(self.shadow.len()));
        self.isolated.reserve(m.saturating_sub(self.isolated.len()));
        self.brackets.reserve(m.saturating_sub(self.brackets.len()));
        self.undecided
            .reserve(m.saturating_sub(self.undecided.len()));
        self.multiple.reserve(m.saturating_sub(self.multiple.len()));
        self.pieces
            .reserve((3 * m).saturating_sub(self.pieces.len()));
        self.parent.reserve(m.saturating_sub(self.parent.len()));
        self.isolated_centres
            .reserve(m.saturating_sub(self.isolated_centres.len()));
        self.cluster.reserve(m.saturating_sub(self.cluster.len()));
        self.hull.reserve(m.saturating_sub(self.hull.len()));
        self.shifted.reserve(m.saturating_sub(self.shifted.len()));
        self.before_real
            .reserve(m.saturating_sub(self.before_real.len()));
        self.restored.reserve(m.saturating_sub(self.restored.len()));
        self.step.reserve(m.saturating_sub(self.step.len()));
    }
}

/// Degree for which the per-thread buffers are sized at their first use: above the degrees
/// of the tracer's per-ray polynomials (Kajiya resultants of bicubic patches: 18), so that
/// their queries never grow a buffer after the first.
const SCRATCH_MIN_DEGREE: usize = 64;

thread_local! {
    static SCRATCH: Cell<Scratch> = Cell::new(Scratch::default());
}

/// What the discs say about one part of the query range ([`real_pieces`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) enum Piece {
    /// Exactly one root of the range, simple, in this certified bracket.
    Root(Bracket),
    /// `(lo, hi]`: a part of the range where the discs decide nothing (a cluster, a
    /// non-real disc meeting the axis, an uncertain sign); its roots are for subdivision.
    Undecided(f64, f64),
    /// Exactly one distinct root of the range in a cluster's shadow: this `f64` itself, an
    /// exact root of the stored polynomial of multiplicity at least 2 ([`multiple_root`]).
    Multiple(f64),
}

impl Piece {
    /// Where the piece starts, for ordering.
    fn start(&self) -> f64 {
        match *self {
            Piece::Root(b) => b.lo,
            Piece::Undecided(l, _) => l,
            Piece::Multiple(r) => r,
        }
    }
}

/// The real roots of `c` (coefficients lowest degree first) in `(lo, hi]` by inclusion
/// discs, as [`Piece`]s handed to `emit` in increasing order: a bracket for each root that
/// an isolated disc decides, and the parts of the range that the discs leave undecided.
/// Returns `false`, having emitted nothing, when the discs say nothing at all (no
/// approximations, overflow, centres too close for the certificate): the caller then
/// answers the whole range by subdivision.
///
/// # Accuracy
/// Certified, when it returns `true`: each bracket `(lo', hi')` holds exactly one root of
/// the stored polynomial, simple, with certified opposite signs at its ends (`s_lo` that of
/// `p(lo')`); the roots of `(lo, hi]` are exactly those of the brackets and those of the
/// undecided parts `(lo'', hi'']`, which are disjoint from the brackets and from each other
/// (every real root lies in the real shadow of some disc, and an undecided part is a union
/// of shadows cut to the range). `lo < hi`, finite coefficients, `c[n] ≠ 0` and `n ≥ 1` are
/// assumed by the caller's validation; anything else returns `false`.
///
/// # Complexity
/// `O(n²)` per Aberth sweep, at most [`MAX_ABERTH_SWEEPS`] sweeps; `O(n²)` for the
/// certificate.
pub(crate) fn real_pieces(c: &[f64], lo: f64, hi: f64, mut emit: impl FnMut(Piece)) -> bool {
    let n = c.len().saturating_sub(1);
    if !(1..=MAX_DEGREE).contains(&n)
        || c[n] == 0.0
        || lo.partial_cmp(&hi) != Some(std::cmp::Ordering::Less)
    {
        return false;
    }
    let mut s = SCRATCH.take();
    s.reserve(n);
    let decided = approximate(c, &mut s) && certify(c, &mut s);
    if decided {
        decide(c, lo, hi, &mut s);
        collect_pieces(&mut s);
        if !s.undecided.is_empty() && unreal_near_pairs(c, &mut s) && certify(c, &mut s) {
            decide(c, lo, hi, &mut s);
            // Either answer is certified. The second is kept when it decides everything:
            // a narrower undecided part is not always cheaper to subdivide (Chebyshev
            // T₈₀'s cost 2.1× the first answer's; `paper-notes/isolation.md`, "Near-real
            // pairs: the derivative in twice the precision").
            if s.undecided.is_empty() {
                collect_pieces(&mut s);
            }
        }
        for &piece in &s.pieces {
            emit(piece);
        }
    }
    SCRATCH.set(s);
    decided
}

/// The answer of [`decide`] as [`Piece`]s in `s.pieces`, in order.
fn collect_pieces(s: &mut Scratch) {
    // The three lists are disjoint from each other: merge them by their starts.
    s.pieces.clear();
    s.pieces.extend(s.brackets.iter().map(|&b| Piece::Root(b)));
    s.pieces
        .extend(s.undecided.iter().map(|&(a, b)| Piece::Undecided(a, b)));
    s.pieces
        .extend(s.multiple.iter().map(|&r| Piece::Multiple(r)));
    s.pieces
        .sort_unstable_by(|x, y| x.start().total_cmp(&y.start()));
}

/// Starting points on the circles of the Newton polygon (Bini 1996, §3): the upper convex
/// hull of the points `(i, log₂|aᵢ|)`; an edge from `i` to `j` holds `j − i` roots of
/// modulus about `(|aᵢ|/|aⱼ|)^{1/(j−i)}`, spread evenly on that circle with an offset angle.
/// A heuristic: only the certificate's radii matter for correctness. `false` when a circle's
/// radius is not a positive finite number or `a₀ = 0` (fewer than `n` points). The circles
/// are centred at `centre`: `c` holds the coefficients of `p(centre + y)`.
fn initial_points(c: &[f64], centre: f64, hull: &mut Vec<(usize, f64)>, z: &mut Vec<C>) -> bool {
    let n = c.len() - 1;
    // Andrew's monotone chain, upper part, over the non-zero coefficients; each vertex keeps
    // its `log₂|aᵢ|` (one logarithm per coefficient).
    hull.clear();
    for i in (0..=n).filter(|&i| c[i] != 0.0) {
        let li = c[i].abs().log2();
        while let [.., (a, la), (b, lb)] = hull[..] {
            // Drop b when it lies on or below the segment from a to i.
            if (b - a) as f64 * (li - la) - (i - a) as f64 * (lb - la) >= 0.0 {
                hull.pop();
            } else {
                break;
            }
        }
        hull.push((i, li));
    }
    // Offset angle σ = 0.7 (Bini 1996): keeps the starting points off the real axis, where
    // conjugate-symmetric starts would never leave it.
    const SIGMA: f64 = 0.7;
    let tau = std::f64::consts::TAU;
    z.clear();
    for e in hull.windows(2) {
        let ((i, li), (j, lj)) = (e[0], e[1]);
        let k = j - i;
        let radius = ((li - lj) / k as f64).exp2();
        if !(radius.is_finite() && radius > 0.0) {
            return false;
        }
        for l in 0..k {
            let angle = tau * l as f64 / k as f64 + tau * i as f64 / n as f64 + SIGMA;
            z.push(C::new(centre + radius * angle.cos(), radius * angle.sin()));
        }
    }
    z.len() == n
}

/// The starting points: Newton-polygon circles around 0 ([`initial_points`]), or around the
/// centroid of the roots `g = −aₙ₋₁/(n·aₙ)` when the roots lie off to one side of 0.
/// Circles around 0 of the moduli of roots clustered at `g` (Wilkinson's `1 … 20`, a
/// cluster at 2, planted roots in `[0, 1]`) put the starts at distances of order `|g|` from
/// the roots, and Aberth's iteration approaches them only linearly (the error halving per
/// sweep) until it is close. Centred at `g` (the Newton polygon of `p(g + y)`, whose
/// coefficients `shifted` gets by Horner's Taylor shift), the circles match the spread of
/// the roots about `g`. Used when that spread, the largest circle's radius, is below
/// [`CENTRED_START_RATIO`]`·|g|`: otherwise the roots surround 0 (Kac, Chebyshev) or span
/// many scales (roots 1, 10³, 10⁶, 10⁹, whose centroid 2.5·10⁸ is no centre of the small
/// ones), and the circles around 0 stay. A heuristic, as the circles are.
fn starting_points(c: &[f64], s: &mut Scratch) -> bool {
    let n = c.len() - 1;
    let g = -c[n - 1] / (n as f64 * c[n]);
    if g != 0.0 && g.is_finite() {
        // Taylor shift: the coefficients of p(g + y) (Horner's scheme n times, O(n²)).
        s.shifted.clear();
        s.shifted.extend_from_slice(c);
        for i in 0..n {
            for j in (i..n).rev() {
                let t = s.shifted[j] + g * s.shifted[j + 1];
                s.shifted[j] = t;
            }
        }
        if s.shifted.iter().all(|v| v.is_finite())
            && initial_points(&s.shifted, g, &mut s.hull, &mut s.z)
        {
            let spread =
                s.z.iter()
                    .map(|z| z.sub(C::new(g, 0.0)).abs_fast())
                    .fold(0.0, f64::max);
            if spread < CENTRED_START_RATIO * g.abs() {
                return true;
            }
        }
    }
    initial_points(c, 0.0, &mut s.hull, &mut s.z)
}

/// [`horner_c`] where its values overflow: the same three on the rescaled polynomial
/// (`p(z) = 2^s·q(w)`, `z = 2^k·w`; `rescale.rs`), each divided by `2^s` (`p'` also by the
/// `2^-k` of the chain rule), so the ratios the iteration uses (`p/p'`, `|p|` against the
/// noise, `|p|/|p'|`) are unchanged; non-finite values when it cannot be rescaled.
#[cold]
#[inline(never)]
fn horner_c_rescaled(c: &[f64], z: C) -> (C, C, f64) {
    with_rescaled(c, z.re, z.im, |q, wr, wi, r| {
        let (p, dp, noise) = horner_c(q, C::new(wr, wi));
        let dp = C::new(ldexp(dp.re, -r.k), ldexp(dp.im, -r.k));
        (p, dp, noise)
    })
    .unwrap_or((C::new(f64::NAN, 0.0), C::new(f64::NAN, 0.0), f64::NAN))
}

/// `p(z)`, `p'(z)` by Horner's rule (complex, or real for a real `z`), plain values for the
/// iteration, and an estimate of the rounding error of `p(z)`: Horner's bound
/// `γ(2n)·Σ|cᵢ||z|ⁱ` (Higham eq. 5.3), doubled (in the index for complex products). Below it
/// the iteration cannot improve `z` in `f64` (the noise floor).
#[inline]
fn horner_c(c: &[f64], z: C) -> (C, C, f64) {
    if z.im == 0.0 {
        let (v, d, err) = horner_derivative_and_bound(c, z.re, z.re);
        return (C::new(v, 0.0), C::new(d, 0.0), 2.0 * err);
    }
    let az = z.abs_fast();
    let (mut v, mut d, mut s) = (C::default(), C::default(), 0.0);
    for &ci in c.iter().rev() {
        d = d.mul(z).add(v);
        v = v.mul(z);
        v.re += ci;
        s = s * az + ci.abs();
    }
    (v, d, gamma_ratio(4 * c.len()) * s)
}

/// An upper bound on `|p(z)|` for the stored coefficients and the stored `z`, or a
/// non-finite number when overflow makes it useless.
///
/// # Accuracy
/// Real `z`: the compensated Horner value and its rigorous bound (`eval_bound.rs`),
/// `|v| + err`, rounded up. Non-real `z`: complex Horner, where each step is a complex
/// product, `fl(x·y) = x·y(1 + δ)`, `|δ| ≤ √2·γ₂ < 3u` (Higham, *Accuracy and Stability of
/// Numerical Algorithms*, 2nd ed., Lemma 3.5; no fused operations), and the addition of a
/// real coefficient, which rounds the real part only: `(t + c)(1 + η)`, `|η| ≤ u`. The term
/// `cᵢzⁱ` so carries at most `(1 + u)^{4n+1}` relative error, and
/// `|v − p(z)| ≤ γ(4n + 1)·Σ|cᵢ||z|ⁱ`; with `len = n + 1` the bound below uses
/// `γ(6·len)/(1 − γ(6·len))` (the ratio covers the rounding of `S` itself, computed with `|z|`
/// rounded up), `(1 + 8ε)` the roundings of the bound, and `8η·Σ|z|ⁱ` the underflow of the
/// four real products per step (each off by at most `η/2` absolutely, carried forward by
/// powers of `|z|`). `|v|` is bounded by `|Re v| + |Im v|`.
///
/// Returned as `(b, e)`, the bound being `b·2^e`: where the bound on `p` itself overflows
/// (`e = 0` otherwise), it is the same bound on the rescaled `q` at `w` (`p(z) = 2^e·q(w)`,
/// `z = 2^k·w`; `rescale.rs`) plus `η·Σ|w|ⁱ` for the rounding of `q`'s coefficients.
#[inline]
fn abs_p_upper(c: &[f64], z: C) -> (f64, i64) {
    let b = abs_p_upper_plain::<false>(c, z);
    if b.is_finite() {
        return (b, 0);
    }
    abs_p_upper_rescaled(c, z)
}

/// [`abs_p_upper`] of the rescaled polynomial; `(∞, 0)` when it cannot be rescaled.
#[cold]
#[inline(never)]
fn abs_p_upper_rescaled(c: &[f64], z: C) -> (f64, i64) {
    with_rescaled(c, z.re, z.im, |q, wr, wi, r| {
        (abs_p_upper_plain::<true>(q, C::new(wr, wi)), r.s)
    })
    .unwrap_or((f64::INFINITY, 0))
}

/// [`abs_p_upper`] without the rescaling; for `RESCALED` coefficients (each known only to
/// within `η`) with `η·Σ|z|ⁱ` added.
#[inline(always)]
fn abs_p_upper_plain<const RESCALED: bool>(c: &[f64], z: C) -> f64 {
    const EPS: f64 = f64::EPSILON;
    let coeff_eta = if RESCALED { 1.0 } else { 0.0 };
    if z.im == 0.0 {
        let (v, err) = horner_bounded(c, z.re);
        let (v, err) = if v.abs() > COMPENSATE_BELOW * err {
            (v, err)
        } else {
            comp_horner_bounded(c, z.re)
        };
        // Σ|z|ⁱ ≤ n + 1 for the rescaled |z| < 1 (the only caller with coeff_eta > 0); the
        // product is exact in units of η.
        debug_assert!(!RESCALED || z.re.abs() < 1.0, "rescaled point");
        let coeff_err = coeff_eta * ETA * c.len() as f64;
        return real_abs_upper(v, err + coeff_err);
    }
    let az = z.abs() * (1.0 + 2.0 * EPS);
    let (mut v, mut s, mut w) = (C::default(), 0.0f64, 0.0f64);
    for &ci in c.iter().rev() {
        v = v.mul(z);
        v.re += ci;
        s = s * az + ci.abs();
        w = w * az + 1.0;
    }
    let err = gamma_ratio(6 * c.len()) * s * (1.0 + 8.0 * EPS) + (8.0 + coeff_eta) * ETA * w;
    (v.re.abs() + v.im.abs() + err) * (1.0 + 4.0 * EPS)
}

/// `|v| + err` rounded up: an upper bound on `|p(x)|` from a computed value `v` with a
/// rigorous bound `err` on its error (the one home of this rounding for [`abs_p_upper`] and
/// the polish's cached bounds, [`polish_real`]). The addition (two when `err` is itself a
/// sum of two terms, as for rescaled coefficients) rounds within `(1 + u)` each: `(1 + 2ε)`
/// covers both.
#[inline(always)]
fn real_abs_upper(v: f64, err: f64) -> f64 {
    (v.abs() + err) * (1.0 + 2.0 * f64::EPSILON)
}

/// `γ(k)/(1 − γ(k))` rounded up, `γ(k) = k·u/(1 − k·u)` (Higham §3.1), infinite when
/// `k·u ≥ 1/4` (no bound).
fn gamma_ratio(k: usize) -> f64 {
    let ku = k as f64 * UNIT_ROUNDOFF;
    if ku >= 0.25 {
        return f64::INFINITY;
    }
    ku / (1.0 - 2.0 * ku) * (1.0 + 4.0 * f64::EPSILON)
}

/// Step 1: Aberth–Ehrlich iteration (Gauss–Seidel sweeps), then the real polish. `false`
/// when a value overflowed or the start failed; convergence itself is not required (the
/// certificate judges the result).
fn approximate(c: &[f64], s: &mut Scratch) -> bool {
    if !starting_points(c, s) {
        return false;
    }
    let n = s.z.len();
    s.done.clear();
    s.done.resize(n, false);
    // Whether some approximation is beyond `FAR_COORDINATE` (kept up to date as they move).
    let mut far = s.z.iter().any(|&z| is_far(z));
    for _ in 0..MAX_ABERTH_SWEEPS {
        let mut moving = false;
        for i in 0..n {
            if s.done[i] {
                continue;
            }
            let zi = s.z[i];
            let (mut p, mut dp, mut noise) = horner_c(c, zi);
            if !(p.is_finite() && dp.is_finite() && noise.is_finite()) {
                (p, dp, noise) = horner_c_rescaled(c, zi);
                if !(p.is_finite() && dp.is_finite() && noise.is_finite()) {
                    return false;
                }
            }
            if p.abs_fast() <= noise {
                s.done[i] = true;
                continue;
            }
            // Aberth's correction w = N/(1 − N·Σ 1/(zᵢ − zⱼ)), N = p/p' (Bini 1996, eq. 6).
            let newton = p.div(dp);
            let sum = aberth_sum(zi, &s.z[..i], &s.z[i + 1..], far);
            let w = newton.div(C::new(1.0, 0.0).sub(newton.mul(sum)));
            if !w.is_finite() {
                return false;
            }
            let next = zi.sub(w);
            s.z[i] = next;
            far |= is_far(next);
            if w.abs_fast() <= 2.0 * f64::EPSILON * next.abs_fast() {
                s.done[i] = true;
            } else {
                moving = true;
            }
        }
        if !moving {
            break;
        }
    }
    s.before_real.clear();
    s.before_real.extend_from_slice(&s.z);
    for i in 0..n {
        let z = s.z[i];
        if z.im != 0.0 {
            // Made real when the imaginary part is within the approximation's own Newton
            // radius `n·max(|p|, noise)/|p'|`: a real root's approximation ends there; a
            // non-real root so close to the axis is caught by the certificate (its disc and
            // its conjugate's overlap, or the two real approximations coincide).
            let (mut p, mut dp, mut noise) = horner_c(c, z);
            if !(p.is_finite() && dp.is_finite() && noise.is_finite()) {
                (p, dp, noise) = horner_c_rescaled(c, z);
            }
            let reach = n as f64 * p.abs_fast().max(noise) / dp.abs_fast();
            if z.im.abs() <= reach {
                s.z[i] = C::new(z.re, 0.0);
            }
        }
    }
    s.p_bound.clear();
    s.p_bound.resize(n, f64::NAN);
    for i in 0..n {
        s.done[i] = s.z[i].im != 0.0;
    }
    polish_real(c, s);
    true
}

/// Aberth sweeps over the real approximations not `done` (the caller marks them and sets
/// their `s.p_bound` to NaN) with compensated Horner values (as accurate
/// as Horner in twice the working precision; `eval_bound.rs`), until each value is within
/// its own error bound or its step vanishes: what the `f64` iteration cannot resolve
/// (Wilkinson-20's middle roots, where `f64` values are noise within ±0.1 of the root).
/// Aberth's sum, not Newton's step alone, keeps two approximations from settling on the
/// same root; its real part is the sum over the conjugate-symmetrised set, so a real
/// approximation stays real.
///
/// Where the last compensated evaluation of an approximation was at its final value (it
/// stopped there: within its error bound, or a step that did not move it), the rigorous
/// bound `|v| + err` on `|p(xᵢ)|` is kept in `s.p_bound` for the certificate, which would
/// otherwise evaluate `p` again at the same point (the compensated scheme, for values that
/// small).
///
/// Returns the number of evaluations made (the tests count them).
fn polish_real(c: &[f64], s: &mut Scratch) -> usize {
    let n = s.z.len();
    let mut evaluations = 0;
    let mut far = s.z.iter().any(|&z| is_far(z));
    s.step.clear();
    s.step.resize(n, f64::INFINITY);
    for sweep in 0..MAX_POLISH_STEPS {
        let mut moving = false;
        for i in 0..n {
            if s.done[i] {
                continue;
            }
            let x = s.z[i].re;
            evaluations += 1;
            let (v, err, d) = comp_horner_bounded_and_derivative(c, x);
            if v.abs() <= err && err.is_finite() {
                s.done[i] = true;
                s.p_bound[i] = real_abs_upper(v, err);
                continue;
            }
            let plain = err.is_finite() && d.is_finite();
            let (v, err, d) = if plain {
                (v, err, d)
            } else {
                polish_values_rescaled(c, x)
            };
            if v.abs() <= err {
                s.done[i] = true;
                continue;
            }
            let newton = v / d;
            let sum = aberth_sum(C::new(x, 0.0), &s.z[..i], &s.z[i + 1..], far).re;
            let next = x - newton / (1.0 - newton * sum);
            if !next.is_finite() || next == x {
                // Stopped at x, where (v, err) was just computed (and is p's own, unless it
                // came from the rescaled polynomial).
                s.done[i] = true;
                if plain {
                    s.p_bound[i] = real_abs_upper(v, err);
                }
                continue;
            }
            // Given up when its steps stop shrinking (`POLISH_WANDERING_AFTER`): its disc
            // stays unisolated, and `unreal_near_pairs` takes it up as a complex root.
            let step = (next - x).abs();
            if sweep >= POLISH_WANDERING_AFTER && step > POLISH_CONTRACTION * s.step[i] {
                s.done[i] = true;
                continue;
            }
            s.step[i] = step;
            s.z[i] = C::new(next, 0.0);
            far |= next.abs() > FAR_COORDINATE;
            moving = true;
        }
        if !moving {
            break;
        }
    }
    evaluations
}

/// For the polish where `p(x)` or `p'(x)` overflows: the compensated value of the rescaled
/// polynomial with its error bound, and its derivative, all divided by the same `2^s`
/// (`rescale.rs`; `p'` also by the `2^-k` of the chain rule), which leaves Newton's step and
/// the stop test unchanged (a heuristic); NaN when it cannot be rescaled.
#[cold]
#[inline(never)]
fn polish_values_rescaled(c: &[f64], x: f64) -> (f64, f64, f64) {
    with_rescaled(c, x, 0.0, |q, y, _, r| {
        let (v, err) = comp_horner_bounded(q, y);
        let (_, d, _) = horner_derivative_and_bound(q, y, y);
        (v, err + ETA * q.len() as f64, ldexp(d, -r.k))
    })
    .unwrap_or((f64::NAN, f64::NAN, f64::NAN))
}

/// Second chance for a query the discs left partly undecided (`paper-notes/isolation.md`,
/// "All-roots queries: near-real pairs"): the approximations that were made real
/// ([`approximate`]) whose real polish did not converge (no bound kept: `s.p_bound` NaN)
/// and whose disc is not isolated go back to their complex values and are polished as
/// complex roots with `p` and `p'` in twice the working precision ([`polish_complex`]),
/// whatever their number (the stage's cost, `O(k·n)` a sweep for `k` restored
/// approximations, was once capped at `k·n ≤ 512`: with `p'` in `f64` it did not decide
/// planted degree 40; it now does, cheaper than the subdivision). Those are the
/// near-real conjugate pairs of the stored polynomial (rounding made two close real roots
/// complex) and the real roots next to them: a real approximation cannot converge to a
/// non-real root, and its wandering keeps its neighbours' polish from converging too. A
/// restored approximation that ends within its own (now double-double) Newton reach of the
/// axis is a real root's, as in [`approximate`]: made real again and polished as such. Only
/// the certificate decides: a disc with `|Im zᵢ| > rᵢ` holds no real point. `false` when
/// there is nothing to restore.
fn unreal_near_pairs(c: &[f64], s: &mut Scratch) -> bool {
    let n = s.z.len();
    s.restored.clear();
    for i in 0..n {
        let restore = s.z[i].im == 0.0
            && s.before_real[i].im != 0.0
            && s.p_bound[i].is_nan()
            && !s.isolated[i];
        s.restored.push(restore);
        s.done[i] = !restore;
        if restore {
            s.z[i] = s.before_real[i];
        }
    }
    let restored = s.restored.iter().filter(|&&r| r).count();
    if restored == 0 || n < NEAR_REAL_MIN_DEGREE {
        return false;
    }
    polish_complex(c, s);
    let mut real_again = false;
    for i in 0..n {
        s.done[i] = true;
        if !s.restored[i] || s.z[i].im == 0.0 {
            continue;
        }
        let (_, dp, _) = horner_c(c, s.z[i]);
        let reach = n as f64 * s.p_bound[i] / dp.abs_fast();
        // A NaN reach (no bound, or no derivative) is not off the axis: real again.
        let off_axis = s.z[i].im.abs() > reach;
        if !off_axis {
            s.z[i] = C::new(s.z[i].re, 0.0);
            s.p_bound[i] = f64::NAN;
            s.done[i] = false;
            real_again = true;
        }
    }
    if real_again {
        polish_real(c, s);
    }
    true
}

/// Aberth sweeps over the restored approximations (`s.restored`, the ones not `done` on
/// entry), with `p(zᵢ)` and `p'(zᵢ)` by the compensated complex Horner scheme
/// ([`comp_horner_c_and_derivative`]: as accurate as Horner's rule in twice the working
/// precision), until `p(zᵢ)` is within its estimated
/// error or the step does not move `zᵢ`; at most [`MAX_COMPLEX_POLISH_STEPS`] sweeps. The
/// derivative needs only a few correct digits, but near a cluster its `f64` value has none:
/// it is noise of the size of the `f64` error of `p` over the cluster's spread, and
/// Newton's step with it wanders (planted degree 40 stayed undecided after 40 sweeps with
/// `p'` in `f64`; `paper-notes/isolation.md`, "Near-real pairs: the derivative in twice the
/// precision"). Every approximation polished here then gets the rigorous double-double
/// bound on `|p(zᵢ)|` at its final point ([`dd_horner_c`]) in `s.p_bound`, for the
/// certificate: its `f64` bound ([`abs_p_upper`]) is the noise that hid the pair's
/// imaginary parts. The iteration's own values carry no rigorous bound: they only steer.
fn polish_complex(c: &[f64], s: &mut Scratch) {
    let n = s.z.len();
    let far = s.z.iter().any(|&z| is_far(z));
    for _ in 0..MAX_COMPLEX_POLISH_STEPS {
        let mut moving = false;
        for i in 0..n {
            if s.done[i] {
                continue;
            }
            let z = s.z[i];
            let (v, dp, noise) = comp_horner_c_and_derivative(c, z);
            if !(v.is_finite() && dp.is_finite() && noise.is_finite()) || v.abs() <= noise {
                // |p(z)| is within the value's own error: z is as good as this precision gets.
                s.done[i] = true;
                continue;
            }
            let newton = v.div(dp);
            let sum = aberth_sum(z, &s.z[..i], &s.z[i + 1..], far);
            let w = newton.div(C::new(1.0, 0.0).sub(newton.mul(sum)));
            let next = z.sub(w);
            if !next.is_finite() || next == z {
                s.done[i] = true;
                continue;
            }
            s.z[i] = next;
            // Converging quadratically and this far inside its gap: the next steps cannot
            // change what the certificate decides (module docs; the radius is about `n·|w|`).
            let reach = n as f64 * w.abs_fast() * POLISH_SETTLED;
            if reach < next.im.abs()
                && s.z
                    .iter()
                    .enumerate()
                    .all(|(j, &zj)| j == i || zj.sub(next).abs_fast() > reach)
            {
                s.done[i] = true;
                continue;
            }
            moving = true;
        }
        if !moving {
            break;
        }
    }
    for i in 0..n {
        if s.restored[i] {
            let bound = dd_horner_c(c, s.z[i]).1;
            s.p_bound[i] = if bound.is_finite() { bound } else { f64::NAN };
        }
    }
}

/// `p(z)` and `p'(z)` by the compensated Horner scheme in complex arithmetic (Graillat &
/// Ménissier-Morain, "Accurate polynomial evaluation in floating point complex arithmetic",
/// 2008): each complex product `v·z` and each addition of a coefficient is split by
/// error-free transformations (TwoProduct by fused multiply–add, TwoSum) into its rounded
/// value and its exact error, and the errors are carried by Horner's rule of their own in
/// `f64`; the derivative's recurrence `p' ← p'·z + p` the same way, the value's error
/// entering it. The result is as accurate as Horner's rule in twice the working precision,
/// with about half the operations of double-double Horner ([`dd_horner_c`]). Also an
/// *estimate* (not a bound) of the value's remaining error, `2ε|v| + γ(4·len)²·Σ|cᵢ||z|ⁱ`
/// after the paper's a-priori bound, for the iteration's stop test only.
fn comp_horner_c_and_derivative(c: &[f64], z: C) -> (C, C, f64) {
    /// `a·b + c·d` for `f64`s: the rounded value and its error (exact up to the rounding of
    /// the error terms' sum, which the iteration does not care about).
    #[inline(always)]
    fn dot2(a: f64, b: f64, c: f64, d: f64) -> (f64, f64) {
        let (p, e) = two_prod(a, b);
        let (q, f) = two_prod(c, d);
        let (s, g) = two_sum(p, q);
        (s, e + f + g)
    }
    let az = z.abs_fast();
    let (mut v, mut ev) = (C::default(), C::default());
    let (mut d, mut ed) = (C::default(), C::default());
    let mut sum = 0.0;
    for &ci in c.iter().rev() {
        // p' ← p'·z + p, with p's rounded value and its carried error.
        let (d_re, e_re) = dot2(d.re, z.re, -d.im, z.im);
        let (d_re, f_re) = two_sum(d_re, v.re);
        let (d_im, e_im) = dot2(d.re, z.im, d.im, z.re);
        let (d_im, f_im) = two_sum(d_im, v.im);
        ed = ed.mul(z).add(ev).add(C::new(e_re + f_re, e_im + f_im));
        d = C::new(d_re, d_im);
        // p ← p·z + cᵢ.
        let (v_re, e_re) = dot2(v.re, z.re, -v.im, z.im);
        let (v_re, f_re) = two_sum(v_re, ci);
        let (v_im, e_im) = dot2(v.re, z.im, v.im, z.re);
        ev = ev.mul(z).add(C::new(e_re + f_re, e_im));
        v = C::new(v_re, v_im);
        sum = sum * az + ci.abs();
    }
    let value = v.add(ev);
    let g = gamma_ratio(4 * c.len());
    (
        value,
        d.add(ed),
        2.0 * f64::EPSILON * value.abs_fast() + g * g * sum,
    )
}

/// `p(z)` by Horner's rule in double-double complex arithmetic (rounded to an `f64` complex
/// value, for the iteration) and a rigorous upper bound on `|p(z)|` for the stored
/// coefficients and the stored `z` (infinite or NaN on overflow).
///
/// # Accuracy
/// Every double-double operation (`Dd::mul_f`, `Dd::add`, `Dd::add_f`) is within
/// [`DD_UNIT`] `= U` of its exact result, relatively (Joldes, Muller & Popescu 2017), so the
/// standard model holds with `U` for `u` and the argument of [`abs_p_upper`] carries over:
/// a complex product errs by `|δ| ≤ √2·γ_U(2) < 3U` (Higham, Lemma 3.5), the addition of a
/// real coefficient by `U` on the real part, and `|v − p(z)| ≤ γ_U(4n + 1)·Σ|cᵢ||z|ⁱ`; the
/// code takes `γ_U(6·len)`, with `S = Σ|cᵢ||z|ⁱ` computed in `f64` from `|z|` rounded up and
/// multiplied by `1 + γ(2·len)` for its own `2·len` roundings. Underflow: each of the seven
/// double-double operations per step errs by at most [`DD_UNDERFLOW`] absolutely beyond the
/// relative bound, carried forward by powers of `|z|`: `8·DD_UNDERFLOW·Σ|z|ⁱ` covers them.
/// `|v|` is bounded by the sum of the moduli of the four parts; the final additions round
/// within `(1 + 8ε)`.
fn dd_horner_c(c: &[f64], z: C) -> (C, f64) {
    const EPS: f64 = f64::EPSILON;
    let az = z.abs() * (1.0 + 2.0 * EPS);
    let (mut re, mut im) = (Dd::ZERO, Dd::ZERO);
    let (mut s, mut w) = (0.0f64, 0.0f64);
    for &ci in c.iter().rev() {
        let r = re.mul_f(z.re).add(im.mul_f(-z.im));
        im = re.mul_f(z.im).add(im.mul_f(z.re));
        re = r.add_f(ci);
        s = s * az + ci.abs();
        w = w * az + 1.0;
    }
    let len = c.len();
    let g = gamma_u(6 * len, DD_UNIT);
    let err = g / (1.0 - g) * s * (1.0 + gamma_u(2 * len, UNIT_ROUNDOFF)) * (1.0 + 8.0 * EPS)
        + 8.0 * DD_UNDERFLOW * w * (1.0 + gamma_u(2 * len, UNIT_ROUNDOFF));
    let modulus = re.hi.abs() + re.lo.abs() + im.hi.abs() + im.lo.abs();
    (
        C::new(re.hi + re.lo, im.hi + im.lo),
        (modulus + err) * (1.0 + 8.0 * EPS),
    )
}

/// Aberth's sum `Σ_j 1/(z − zⱼ)` over the other approximations (`before` and `after` `zᵢ`),
/// for the iteration only. Each term as `conj(d)·(1/|d|²)`: one division, no test per term;
/// where some `|d|²` over- or underflowed the sum is not finite, or (for `|d|² > 2^1000`)
/// a term that is negligible anyway came out 0, and a non-finite sum is recomputed with
/// [`C::recip`] (Smith's rule where needed).
///
/// `far` says that some approximation has a coordinate beyond [`FAR_COORDINATE`]: then a
/// `|d|²` may overflow and its term come out 0, which is not negligible when `z` is as
/// large as `d` (a cubic with roots near `10⁻⁶`, `10⁵⁹` and `10²⁰¹` saw the sum of its
/// largest approximation vanish, and Aberth's step became Newton's, which halved that
/// approximation towards 0 for 80 sweeps); the sum is then taken with [`C::recip`] alone.
fn aberth_sum(z: C, before: &[C], after: &[C], far: bool) -> C {
    if far {
        return aberth_sum_recip(z, before, after);
    }
    // Two plain loops, not `before.iter().chain(after)`: the chained iterator's per-item
    // branch was a sixth of the iteration's instructions (same terms, same order).
    let mut sum = add_reciprocals(z, before, C::default());
    sum = add_reciprocals(z, after, sum);
    if !sum.is_finite() {
        sum = aberth_sum_recip(z, before, after);
    }
    sum
}

/// `sum + Σ_j conj(z − zⱼ)/|z − zⱼ|²` over `zs`, in order: [`aberth_sum`]'s terms.
#[inline(always)]
fn add_reciprocals(z: C, zs: &[C], mut sum: C) -> C {
    for &zj in zs {
        let d = z.sub(zj);
        let r = 1.0 / (d.re * d.re + d.im * d.im);
        sum = C::new(sum.re + d.re * r, sum.im - d.im * r);
    }
    sum
}

/// [`aberth_sum`] with a reciprocal ([`C::recip`], Smith's rule where `|d|²` leaves the
/// normal range) per term.
#[cold]
#[inline(never)]
fn aberth_sum_recip(z: C, before: &[C], after: &[C]) -> C {
    let mut sum = C::default();
    for &zj in before.iter().chain(after) {
        sum = sum.add(z.sub(zj).recip());
    }
    sum
}

/// A coordinate of an approximation beyond which [`aberth_sum`]'s shortcut may overflow:
/// `2^500`. Below it every coordinate difference is at most `2^501` and its square finite.
const FAR_COORDINATE: f64 = f64::from_bits((1023 + 500) << 52);

/// Whether `z` has a coordinate beyond [`FAR_COORDINATE`].
fn is_far(z: C) -> bool {
    z.re.abs().max(z.im.abs()) > FAR_COORDINATE
}

/// A positive normal number as `m·2^e`, `m ∈ [1, 2)` (exact), for products of many factors
/// that would over- or underflow in `f64`.
fn split(x: f64) -> (f64, i64) {
    let bits = x.to_bits();
    let e = ((bits >> 52) & 0x7ff) as i64 - 1023;
    (f64::from_bits((bits & !(0x7ff << 52)) | (1023 << 52)), e)
}

/// `2^e` for `−1022 ≤ e ≤ 1023`.
fn pow2(e: i64) -> f64 {
    f64::from_bits(((e + 1023) as u64) << 52)
}

/// The computed `|a − b|²` of two centres as `m·2^e` (`m ∈ [1, 2)`), or `None` when it is
/// below [`MIN_DISTANCE`] or a difference is not finite. The true value is at least this
/// times `(1 + u)^-4`: each coordinate difference rounds once (`|d| ≥ |d̂|/(1 + u)`), the
/// squares and their sum once each; an underflowing square errs by at most
/// `η/2 ≤ 2^-174·MIN_DISTANCE` absolutely, within the margins taken by the callers. Centres
/// more than `2^511` apart (roots spread over more than `10¹⁵⁴`, whose squared distance
/// overflows) are compared through [`scaled_diff`], which keeps that bound.
#[inline]
fn dist_sq(a: C, b: C) -> Option<(f64, i64)> {
    let d = a.sub(b);
    let q = d.re * d.re + d.im * d.im;
    if q.is_finite() {
        return (q >= MIN_DISTANCE).then(|| split(q));
    }
    dist_sq_far(a, b)
}

/// [`dist_sq`] of centres whose squared distance overflowed (a coordinate difference above
/// `2^511`), through [`scaled_diff`].
#[cold]
#[inline(never)]
fn dist_sq_far(a: C, b: C) -> Option<(f64, i64)> {
    let (d, e) = scaled_diff(a, b)?;
    let q = d.re * d.re + d.im * d.im;
    if e == 0 {
        // Not finite after all: a non-finite centre.
        return None;
    }
    let (m, qe) = split(q);
    Some((m, qe + 2 * e))
}

/// Exponent above which [`scaled_diff`] scales a difference down: `2^500`, so that its
/// square (below `2^1002` after the scaling by `2^-600`) is finite.
const BIG_DIFFERENCE: f64 = f64::from_bits((1023 + 500) << 52);

/// `a − b` as `d·2^e`, `d` the computed difference (`e = 0`), or, when a coordinate of it
/// exceeds [`BIG_DIFFERENCE`], that difference times `2^-600` (`e = 600`): exact for the larger
/// coordinate (then above `2^-100`); the other one may underflow to a value smaller in
/// magnitude, whose square is then below `2^-1022`, less than `u·2^-200` against the larger
/// square, so the computed sum of squares is still at least the true one times
/// `(1 + u)^-4` up to the margin that [`dist_sq`]'s callers take. `None` when a difference is
/// not finite.
fn scaled_diff(a: C, b: C) -> Option<(C, i64)> {
    let d = a.sub(b);
    if !d.is_finite() {
        return None;
    }
    if d.re.abs().max(d.im.abs()) <= BIG_DIFFERENCE {
        return Some((d, 0));
    }
    Some((C::new(ldexp(d.re, -600), ldexp(d.im, -600)), 600))
}

/// Step 2: upper bounds `rᵢ ≥ n·|p(zᵢ)|/(|aₙ|·∏_{j≠i}|zᵢ − zⱼ|)`. `false` when the centres
/// are not distinct enough or a radius overflows.
///
/// # Accuracy
/// `|p(zᵢ)|` is bounded above by [`abs_p_upper`]; `∏|zᵢ − zⱼ|²` below by the computed product
/// of [`dist_sq`] (each `(1 + u)^4` low at worst) with its `n − 2` roundings, kept in
/// `m·2^e` form so that no step leaves the normal range (scaling by powers of two is exact);
/// the quotient, the square root and the final product with `n` take four more roundings.
/// Together `(1 + u)^{2.5n + 6} ≤ 1 + (5n + 12)u`, covered by the factor `1 + (4n + 16)ε`.
fn certify(c: &[f64], s: &mut Scratch) -> bool {
    let n = s.z.len();
    let (an_m, an_e) = split(c[n].abs().max(f64::MIN_POSITIVE));
    if c[n].abs() < f64::MIN_POSITIVE {
        // A subnormal leading coefficient: relative bounds on it do not hold.
        return false;
    }
    s.radius.clear();
    let margin = 1.0 + (4 * n + 16) as f64 * f64::EPSILON;
    for i in 0..n {
        let zi = s.z[i];
        // The polish's bound where it stopped at zᵢ, else a fresh one.
        let (p_up, p_scale) = match s.p_bound[i] {
            b if b.is_finite() => (b, 0),
            _ => abs_p_upper(c, zi),
        };
        if !p_up.is_finite() {
            return false;
        }
        let (p_m, p_e) = split(p_up.max(f64::MIN_POSITIVE));
        let p_e = p_e + p_scale;
        let (mut prod, mut prod_e) = (1.0f64, 0i64);
        for (j, &zj) in s.z.iter().enumerate() {
            if j == i {
                continue;
            }
            let Some((q_m, q_e)) = dist_sq(zi, zj) else {
                return false;
            };
            let (m, e) = split(prod * q_m);
            prod = m;
            prod_e += e + q_e;
        }
        if prod_e % 2 != 0 {
            prod *= 2.0;
            prod_e -= 1;
        }
        let mant = n as f64 * p_m / (an_m * prod.sqrt());
        let e = p_e - an_e - prod_e / 2;
        let r = if e > 900 {
            return false;
        } else if e < -1000 {
            // mant < 2n·2 ≤ 2^12: r < 2^-988.
            pow2(-980)
        } else {
            mant * pow2(e) * margin
        };
        s.radius.push(r);
    }
    true
}

/// Whether the closed discs `D(a, ra)` and `D(b, rb)` are certainly disjoint:
/// `|a − b| > ra + rb` with the distance bounded below ([`dist_sq`], `(1 − 4ε)` covering its
/// `(1 + u)^-4`) and the sum of radii above (two roundings of the sum and square, each
/// covered by `(1 + 2ε)`).
///
/// Centres whose squared distance overflows are compared at the scale of [`scaled_diff`], the radii
/// scaled by the same `2^-600` and rounded up (by `η`, which covers an underflowing
/// quotient; one more rounding of the sum is within the `(1 + 2ε)`).
#[inline]
fn discs_apart(a: C, ra: f64, b: C, rb: f64) -> bool {
    let d = a.sub(b);
    let q = d.re * d.re + d.im * d.im;
    if !q.is_finite() {
        return discs_apart_far(a, ra, b, rb);
    }
    // Too close to tell: not certainly apart.
    if q < MIN_DISTANCE {
        return false;
    }
    let t = (ra + rb) * (1.0 + 2.0 * f64::EPSILON);
    q * (1.0 - 4.0 * f64::EPSILON) > t * t * (1.0 + 2.0 * f64::EPSILON)
}

/// [`discs_apart`] for centres whose squared distance overflowed, at the scale of
/// [`scaled_diff`].
#[cold]
#[inline(never)]
fn discs_apart_far(a: C, ra: f64, b: C, rb: f64) -> bool {
    let Some((d, e)) = scaled_diff(a, b) else {
        return false;
    };
    let q = d.re * d.re + d.im * d.im;
    // A non-finite centre, or a distance still too large: not certainly apart.
    if e == 0 || !q.is_finite() {
        return false;
    }
    let (ra, rb) = (ldexp(ra, -e) + ETA, ldexp(rb, -e) + ETA);
    let t = (ra + rb) * (1.0 + 2.0 * f64::EPSILON);
    q * (1.0 - 4.0 * f64::EPSILON) > t * t * (1.0 + 2.0 * f64::EPSILON)
}

/// Step 3: the real roots of `(lo, hi]` from the discs (module docs): brackets in
/// `s.brackets` for the shadows that an isolated real-centred disc decides, and in
/// `s.undecided` the other shadows meeting the range, cut to it and merged where they
/// overlap; both sorted.
fn decide(c: &[f64], lo: f64, hi: f64, s: &mut Scratch) {
    let n = s.z.len();
    s.shadow.clear();
    s.brackets.clear();
    s.undecided.clear();
    s.multiple.clear();
    let mut clusters = false;
    for i in 0..n {
        let (z, r) = (s.z[i], s.radius[i]);
        // The disc meets the axis only if |Im z| ≤ r (exact comparison of stored numbers);
        // its real points lie in [Re z − r, Re z + r], rounded outward.
        s.shadow.push(if z.im.abs() <= r {
            ((z.re - r).next_down(), (z.re + r).next_up())
        } else {
            (f64::NAN, f64::NAN)
        });
    }
    s.isolated.clear();
    let mut every_real_root_isolated = true;
    for i in 0..n {
        let on_axis = !s.shadow[i].0.is_nan();
        let iso = on_axis && isolated(s, i);
        every_real_root_isolated &= iso || !on_axis;
        s.isolated.push(iso);
    }
    // The implied signs below count the isolated real centres right of each disc: from
    // the sorted centres, `O(log n)` per disc instead of a pass over all of them.
    s.isolated_centres.clear();
    if every_real_root_isolated {
        s.isolated_centres
            .extend((0..n).filter(|&j| s.isolated[j]).map(|j| s.z[j].re));
        s.isolated_centres.sort_unstable_by(f64::total_cmp);
    }
    for i in 0..n {
        let (a, b) = s.shadow[i];
        // No real point of this disc in [lo, hi] (NaN: none at all).
        if a.is_nan() || b < lo || a > hi {
            continue;
        }
        // With every real root in an isolated disc, the real roots are exactly one simple root
        // per real-centred disc, so the sign right of a shadow is `sign(aₙ)` times −1 per
        // real disc further right (the shadows are disjoint): no evaluation near the root.
        let right_sign = every_real_root_isolated.then(|| {
            let centre = s.z[i].re;
            let right =
                s.isolated_centres.len() - s.isolated_centres.partition_point(|&x| x <= centre);
            let lead = if c[n] > 0.0 { 1 } else { -1 };
            if right.is_multiple_of(2) { lead } else { -lead }
        });
        if decide_shadow(c, lo, hi, i, right_sign, s) {
            continue;
        }
        if !clusters {
            find_clusters(s);
            clusters = true;
        }
        let k = cluster_of(&mut s.parent, i);
        let multiple = match s.cluster[k] {
            Some(known) => known,
            None => {
                let r = multiple_root(c, k, s);
                s.cluster[k] = Some(r);
                if let Some(r) = r.filter(|&r| lo < r && r <= hi) {
                    s.multiple.push(r);
                }
                r
            }
        };
        if multiple.is_none() {
            // Its roots, if any, lie in the open (a, b): the part (a, b] of the range.
            let (l, h) = (a.max(lo), b.min(hi));
            if l < h {
                s.undecided.push((l, h));
            }
        }
    }
    s.brackets.sort_unstable_by(|x, y| x.lo.total_cmp(&y.lo));
    s.undecided.sort_unstable_by(|x, y| x.0.total_cmp(&y.0));
    // Merge overlapping or touching parts, in place.
    let mut k = 0;
    for j in 0..s.undecided.len() {
        let (l, h) = s.undecided[j];
        if k > 0 && l <= s.undecided[k - 1].1 {
            s.undecided[k - 1].1 = s.undecided[k - 1].1.max(h);
        } else {
            s.undecided[k] = (l, h);
            k += 1;
        }
    }
    s.undecided.truncate(k);
}

/// Whether disc `i` is isolated: a real centre, and its disc and its shadow certainly apart
/// from every other disc and shadow. Such a disc is a component of one disc, so it holds
/// exactly one root, simple, and real (a non-real root would bring its conjugate into the
/// same disc); no other disc has a real point in its shadow.
fn isolated(s: &Scratch, i: usize) -> bool {
    let (a, b) = s.shadow[i];
    let (z, r) = (s.z[i], s.radius[i]);
    if z.im != 0.0 {
        return false;
    }
    (0..s.z.len()).all(|j| {
        let (sa, sb) = s.shadow[j];
        let shadows_apart = sa.is_nan() || sb < a || sa > b;
        j == i || (shadows_apart && discs_apart(z, r, s.z[j], s.radius[j]))
    })
}

/// Whether discs `i` and `j` may share a root's neighbourhood: their discs or their shadows
/// are not certainly apart (the relation [`decide_shadow`] requires of an isolated disc).
fn touching(s: &Scratch, i: usize, j: usize) -> bool {
    let (a, b) = s.shadow[i];
    let (sa, sb) = s.shadow[j];
    let shadows_apart = a.is_nan() || sa.is_nan() || sb < a || sa > b;
    !(shadows_apart && discs_apart(s.z[i], s.radius[i], s.z[j], s.radius[j]))
}

/// The clusters: connected components of the discs under [`touching`], as union–find
/// parents in `s.parent`; `s.cluster` reset (nothing tried). `O(n²)` pairs, run only when
/// some disc meeting the range is undecided.
fn find_clusters(s: &mut Scratch) {
    let n = s.z.len();
    s.parent.clear();
    s.parent.extend(0..n);
    s.cluster.clear();
    s.cluster.resize(n, None);
    for i in 0..n {
        for j in i + 1..n {
            if touching(s, i, j) {
                let (ri, rj) = (cluster_of(&mut s.parent, i), cluster_of(&mut s.parent, j));
                if ri != rj {
                    s.parent[ri.max(rj)] = ri.min(rj);
                }
            }
        }
    }
}

/// The root of `i`'s cluster in the union–find `parent` (with path halving).
fn cluster_of(parent: &mut [usize], mut i: usize) -> usize {
    while parent[i] != i {
        parent[i] = parent[parent[i]];
        i = parent[i];
    }
    i
}

/// The exact multiple root of cluster `k` (module docs, step 4), or `None`.
///
/// # Accuracy
/// Certified: with `m ≥ 2` discs in the cluster and every other disc apart from each of
/// them, the union of the cluster's discs holds exactly `m` roots counted with multiplicity
/// (Bini & Fiorentino 2000, Theorem 9: it is a union of whole components). Every other
/// disc's shadow is required to miss the hull `[A, B]` of the cluster's shadows. When
/// `(x − r)^m` divides the stored polynomial exactly for an `f64` `r` in `(A, B)`, `r` lies
/// in some disc (every root does), whose shadow holds `r`, so a disc of the cluster; its `m`
/// roots are then `r` alone, and every real root in `[A, B]`, lying in the shadow of some
/// disc, is `r`. The candidate `r` ([`derivative_root`]) and its two neighbouring `f64` are
/// tried. Not certified (`None`): a multiple root that is not an `f64` (the
/// stored polynomial `(3x − 1)²`), a cluster of distinct roots, `m·n >`
/// [`MAX_MULTIPLE_WORK`].
fn multiple_root(c: &[f64], k: usize, s: &mut Scratch) -> Option<f64> {
    let n = s.z.len();
    let (mut m, mut sum) = (0usize, 0.0f64);
    let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
    for i in 0..n {
        if cluster_of(&mut s.parent, i) == k {
            m += 1;
            sum += s.z[i].re;
            let (a, b) = s.shadow[i];
            if !a.is_nan() {
                lo = lo.min(a);
                hi = hi.max(b);
            }
        }
    }
    if m < 2 || m * n > MAX_MULTIPLE_WORK || lo >= hi {
        return None;
    }
    for j in 0..n {
        let (a, b) = s.shadow[j];
        if cluster_of(&mut s.parent, j) != k && !a.is_nan() && !(b < lo || a > hi) {
            return None;
        }
    }
    let r = derivative_root(c, m - 1, sum / m as f64, &mut s.shifted);
    // A candidate where p has a certified sign is no root: only the others are checked
    // exactly (the integer polynomial is built for the first of them).
    let mut exact: Option<IntPoly> = None;
    [r, r.next_down(), r.next_up()]
        .into_iter()
        .filter(|&r| lo < r && r < hi && certified_sign(c, r, 0.0) == 0)
        .find(|&r| {
            let Some(x) = rat_from_f64(r) else {
                return false;
            };
            let p = match &exact {
                Some(p) => p,
                None => match Poly::new(c.to_vec()).to_rat() {
                    Some(q) => exact.insert(IntPoly::from_qpoly(&q)),
                    None => return false,
                },
            };
            p.has_root_of_multiplicity(&x, m)
        })
}

/// A candidate for a root of multiplicity `k + 1` near `x`: Newton's iteration on the `k`-th
/// derivative, of which such a root is a simple root (its `f64` values are not lost in the
/// noise that hides `p` itself near a multiple root: the approximations of the cluster at
/// `(x − 1000)⁴` end up to `0.02` apart, so their mean is no candidate). A heuristic: the
/// exact check decides. `d` is scratch for the derivative's coefficients.
fn derivative_root(c: &[f64], k: usize, mut x: f64, d: &mut Vec<f64>) -> f64 {
    d.clear();
    d.extend(c.iter().enumerate().skip(k).map(|(i, &ci)| {
        // cᵢ·i!/(i − k)!, the coefficient of x^(i−k) in the k-th derivative.
        (i - k + 1..=i).fold(ci, |v, f| v * f as f64)
    }));
    for _ in 0..MAX_POLISH_STEPS {
        // Value and derivative by plain Horner (a heuristic, no bound needed; a call of
        // `horner_derivative_and_bound` here changed how it is inlined into the Aberth
        // sweeps and slowed them: `paper-notes/isolation.md`, "Full precision").
        let (mut v, mut dv) = (0.0, 0.0);
        for &di in d.iter().rev() {
            dv = dv * x + v;
            v = v * x + di;
        }
        let next = x - v / dv;
        if !next.is_finite() || next == x {
            break;
        }
        x = next;
    }
    x
}

/// Whether the disc `i`, whose shadow `(a, b)` meets `[lo, hi]`, decides its part of the
/// range: [`isolated`] (exactly one simple root in `(a, b)`, and no other real root there),
/// with opposite signs at `a` and `b` — certified by evaluation, or, given `right_sign`
/// (the sign of `p` right of the shadow, known when every real root is in an isolated
/// disc), implied: `p` changes sign exactly once in `(a, b)`, and not at the ends, which lie
/// outside every disc. Its bracket, cut to the range with the certified sign at a cut end,
/// goes to `s.brackets` when the root is in `(lo, hi]`; equal signs at the cut put the root
/// outside the range.
fn decide_shadow(
    c: &[f64],
    lo: f64,
    hi: f64,
    i: usize,
    right_sign: Option<i8>,
    s: &mut Scratch,
) -> bool {
    let (a, b) = s.shadow[i];
    if !s.isolated[i] {
        return false;
    }
    let (s_a, s_b) = match right_sign {
        Some(s_b) => {
            debug_assert!(
                certified_sign(c, b, 0.0) != -s_b && certified_sign(c, a, 0.0) != s_b,
                "a derived shadow sign contradicts a certified one"
            );
            (-s_b, s_b)
        }
        None => (certified_sign(c, a, 0.0), certified_sign(c, b, 0.0)),
    };
    if s_a == 0 || s_b != -s_a {
        return false;
    }
    let (l, s_l) = if a < lo {
        (lo, certified_sign(c, lo, 0.0))
    } else {
        (a, s_a)
    };
    let (h, s_h) = if b > hi {
        (hi, certified_sign(c, hi, 0.0))
    } else {
        (b, s_b)
    };
    if s_l == 0 || s_h == 0 {
        return false;
    }
    if s_l == -s_h {
        s.brackets.push(Bracket::new(l, h, s_l));
    }
    true
}

#[cfg(test)]
mod tests {
    use rand::{Rng, SeedableRng};
    use rand_chacha::ChaCha8Rng;

    use super::*;
    use crate::testutil::{chebyshev, planted, rat, wilkinson};
    use crate::{IsolationMethod, Poly, Rat, RootOptions, RootStats};

    /// Tolerance of the answers compared here (absolute, on roots of size ≤ 21).
    const X_TOL: f64 = 1e-12;

    /// The query of `stats` was answered by the discs alone: decided, nothing left undecided
    /// or subdivided after them, and not by the budgeted subdivision tried before them
    /// (whose given-up splits may count in `subdivisions`).
    fn assert_decided_by_discs(stats: &RootStats, what: &str) {
        assert_eq!(
            (
                stats.inclusion_decided,
                stats.inclusion_undecided,
                stats.inclusion_subranges,
                stats.subdivided_first
            ),
            (1, 0, 0, 0),
            "{what}: decided by the discs alone: {stats:?}"
        );
    }

    /// The certified answer on `(lo, hi]` with its statistics, checked root for root against
    /// the exact oracle (exact isolation and refinement of the same stored polynomial).
    fn check(p: &Poly<f64>, lo: f64, hi: f64) -> RootStats {
        let mut stats = RootStats::default();
        let got = p
            .real_roots_with(lo, hi, &RootOptions::new(X_TOL), &mut stats)
            .expect("valid query");
        let exact = RootOptions {
            isolation: IsolationMethod::Exact,
            ..RootOptions::new(X_TOL)
        };
        let want = p
            .real_roots_with(lo, hi, &exact, &mut RootStats::default())
            .expect("valid query");
        assert_eq!(got.len(), want.len(), "got {got:?}, exact {want:?}");
        for (g, w) in got.iter().zip(&want) {
            // Within the tolerance or two f64 spacings (the promise for huge roots).
            assert!(
                (g - w).abs() <= (2.0 * X_TOL).max(4.0 * f64::EPSILON * w.abs()),
                "got {g:e}, exact {w:e}: {got:?}"
            );
        }
        let mut intervals = RootStats::default();
        let ivs = p
            .isolate_roots_with(lo, hi, &RootOptions::default(), &mut intervals)
            .expect("valid query");
        assert_eq!(ivs.len(), want.len(), "isolating intervals {ivs:?}");
        for (iv, w) in ivs.iter().zip(&want) {
            let slop = (2.0 * X_TOL).max(4.0 * f64::EPSILON * w.abs());
            assert!(
                iv.lo - slop <= *w && *w <= iv.hi + slop,
                "{iv:?} misses the exact root {w:e}"
            );
        }
        assert_eq!(
            stats.inclusion_decided, intervals.inclusion_decided,
            "both queries take the same path"
        );
        stats
    }

    /// Seeded Kac polynomial: independent standard normal coefficients (Box–Muller).
    fn kac(degree: usize, seed: u64) -> Poly<f64> {
        let mut rng = ChaCha8Rng::seed_from_u64(seed);
        Poly::new(
            (0..=degree)
                .map(|_| {
                    let (u, v): (f64, f64) = (rng.gen_range(f64::EPSILON..1.0), rng.r#gen());
                    (-2.0 * u.ln()).sqrt() * (std::f64::consts::TAU * v).cos()
                })
                .collect(),
        )
    }

    #[test]
    fn wilkinson_20_all_roots_by_the_discs() {
        let p = wilkinson(20).to_f64();
        let stats = check(&p, 0.0, 21.0);
        assert_eq!(
            (stats.inclusion_decided, stats.inclusion_undecided),
            (1, 0),
            "decided by the discs: {stats:?}"
        );
        assert_eq!(stats.subdivisions, 0, "no subdivision ran");
    }

    /// Where every real root is in an isolated disc, the signs at a bracket's ends are
    /// implied (counted from `sign(aₙ)`), not evaluated: they must be the exact signs of the
    /// stored polynomial there, checked in rational arithmetic.
    #[test]
    fn implied_bracket_signs_are_the_exact_signs() {
        let mut polys = vec![(wilkinson(20).to_f64(), 0.0, 21.0)];
        polys.extend((0..3).map(|seed| (kac(40, seed), -2.0, 2.0)));
        polys.push((chebyshev(12).to_f64(), -1.5, 1.5));
        let mut checked = 0;
        for (p, lo, hi) in polys {
            let c = p.coeffs();
            let exact = p.to_rat().expect("finite coefficients");
            let exact_sign = |x: f64| {
                let v = exact.eval(&rat_from_f64(x).expect("finite"));
                i8::from(v > Rat::from_integer(0.into()))
                    - i8::from(v < Rat::from_integer(0.into()))
            };
            let mut brackets = Vec::new();
            assert!(real_pieces(c, lo, hi, |piece| match piece {
                Piece::Root(b) => brackets.push(b),
                other => panic!("degree {}: not decided by the discs: {other:?}", p.degree()),
            }));
            checked += brackets.len();
            for b in brackets {
                assert_eq!(exact_sign(b.lo), b.s_lo, "degree {}: {b:?}", p.degree());
                assert_eq!(exact_sign(b.hi), -b.s_lo, "degree {}: {b:?}", p.degree());
            }
        }
        assert!(
            checked >= 32,
            "Wilkinson's 20 roots and T₁₂'s 12 at least: {checked}"
        );
    }

    /// The certificate takes `|p(zᵢ)|` from the polish where it stopped at `zᵢ`
    /// (`Scratch::p_bound`): each such bound must be the compensated bound at the final,
    /// real `zᵢ` (not one computed before a last step, which the exact value alone would
    /// rarely catch: a step towards the root makes `|p|` smaller) and hold for the exact value
    /// of the stored polynomial there, and the path must be taken for most real roots.
    #[test]
    fn polish_bounds_kept_for_the_certificate_hold_exactly() {
        let mut rng = ChaCha8Rng::seed_from_u64(11);
        let mut polys = vec![wilkinson(20).to_f64(), chebyshev(12).to_f64(), kac(40, 1)];
        for degree in [8, 14, 20] {
            let roots: Vec<Rat> = (0..degree)
                .map(|_| {
                    let m = rng.gen_range(2..=1024i64);
                    rat(rng.gen_range(0..=m), m)
                })
                .collect();
            polys.push(planted(&roots).to_f64());
        }
        let (mut kept, mut real) = (0, 0);
        for p in &polys {
            let c = p.coeffs();
            let exact = p.to_rat().expect("finite coefficients");
            let mut s = Scratch::default();
            s.reserve(p.degree());
            assert!(approximate(c, &mut s), "degree {}", p.degree());
            real += s.z.iter().filter(|z| z.im == 0.0).count();
            for (z, &b) in s.z.iter().zip(&s.p_bound) {
                if b.is_nan() {
                    continue;
                }
                kept += 1;
                assert_eq!(z.im, 0.0, "a bound kept for a non-real centre {z:?}");
                // Computed at the final point, not before a last step.
                let (v, err) = comp_horner_bounded(c, z.re);
                assert_eq!(
                    b,
                    real_abs_upper(v, err),
                    "degree {}: at {:e}",
                    p.degree(),
                    z.re
                );
                let v = exact.eval(&rat_from_f64(z.re).expect("finite"));
                let v = if v < Rat::default() { -v } else { v };
                assert!(
                    v <= rat_from_f64(b).expect("finite"),
                    "degree {}: |p({:e})| above the kept bound {b:e}",
                    p.degree(),
                    z.re
                );
            }
        }
        assert!(
            2 * kept >= real,
            "bounds kept for {kept} of {real} real approximations"
        );
    }

    /// A range holding one root of Wilkinson-20, or none, is answered by subdivision
    /// without the discs (`few_roots_likely`), and agrees with the oracle; the whole range
    /// still goes to the discs.
    #[test]
    fn ranges_with_one_root_or_none_skip_the_discs() {
        let p = wilkinson(20).to_f64();
        for (lo, hi) in [(4.5, 5.5), (4.9, 5.1), (5.2, 5.8), (0.0, 0.5)] {
            let stats = check(&p, lo, hi);
            assert_eq!(
                (stats.inclusion_decided, stats.inclusion_undecided),
                (0, 0),
                "({lo}, {hi}]: {stats:?}"
            );
        }
        assert_eq!(
            check(&p, 0.0, 21.0).inclusion_decided,
            1,
            "all twenty: the discs"
        );
    }

    #[test]
    fn kac_planted_and_chebyshev_degree_40_agree_with_the_oracle() {
        for seed in 0..3 {
            let p = kac(40, seed);
            let stats = check(&p, -2.0, 2.0);
            assert_eq!(stats.inclusion_decided, 1, "Kac seed {seed}: {stats:?}");
        }
        let mut rng = ChaCha8Rng::seed_from_u64(40);
        let roots: Vec<Rat> = (0..40).map(|_| rat(rng.gen_range(-64..=64), 16)).collect();
        // Repeated rationals are double roots: whichever path answers, the answer is exact.
        check(&planted(&roots).to_f64(), -5.0, 5.0);
        check(&chebyshev(40).to_f64(), -1.5, 1.5);
    }

    #[test]
    fn query_ends_inside_a_disc_are_decided_by_signs() {
        // Ends at, just below and just above the roots 3 and 7 of a degree-8 polynomial.
        let p = Poly::from_roots(&[1.0, 2.0, 3.0, 4.5, 5.0, 6.0, 7.0, 8.0]);
        for (lo, hi) in [
            (3.0, 7.0),
            (3f64.next_down(), 7f64.next_down()),
            (3f64.next_up(), 7f64.next_up()),
            (2.9999999, 7.0000001),
        ] {
            check(&p, lo, hi);
        }
    }

    #[test]
    fn clusters_and_double_roots_fall_through_and_are_still_right() {
        // A double root off the f64 grid: (3x − 1)², exact coefficients, root 1/3.
        let double = &Poly::new(vec![1.0, -6.0, 9.0]) * &Poly::from_roots(&[2.0, -1.0, 3.0]);
        let stats = check(&double, -10.0, 10.0);
        assert_eq!(
            (stats.inclusion_decided, stats.inclusion_undecided),
            (0, 1),
            "undecided, answered by subdivision: {stats:?}"
        );
        // The discs of −1, 2 and 3 decide those roots; only the shadows of the pair go to
        // subdivision, as one part.
        assert_eq!(
            stats.inclusion_subranges, 1,
            "one undecided part: {stats:?}"
        );
    }

    /// Roots 0.5 and 0.5 + 4ε, rounded into the stored coefficients, become a conjugate pair
    /// near the axis (the exact oracle finds 3 real roots): the `f64` values cannot tell it
    /// from two real roots and left it undecided (one part, to subdivision, before session 12); polished as complex roots in
    /// double-double ([`unreal_near_pairs`]) its discs lie off the axis, and the discs decide
    /// the query: exactly −1, 2 and 3, as the exact oracle says.
    #[test]
    fn pair_four_ulps_apart_is_certified_non_real() {
        let close = Poly::from_roots(&[0.5, 0.5 + 4.0 * f64::EPSILON, 2.0, -1.0, 3.0]);
        assert_decided_by_discs(&check(&close, -10.0, 10.0), "four ulps apart");
        let roots = close.real_roots(-10.0, 10.0, 1e-15).expect("valid query");
        assert_eq!(roots.len(), 3, "{roots:?}");
    }

    #[test]
    fn query_ends_at_a_multiple_root_keep_the_half_open_range() {
        // A double root at 0.25 (its discs overlap; exact in f64, so its cluster certifies
        // it, step 4) and simple roots the discs decide; the ranges end at, just below and
        // just above 0.25.
        let p = Poly::from_roots(&[0.25, 0.25, -1.0, 2.0, 3.0, 5.0]);
        for (lo, hi) in [
            (-10.0, 0.25),
            (0.25, 10.0),
            (0.25f64.next_down(), 0.25f64.next_up()),
            (-0.5, 0.25f64.next_down()),
            (0.25f64.next_up(), 2.5),
        ] {
            let stats = check(&p, lo, hi);
            assert!(
                stats.inclusion_subranges <= 1 && stats.exact_fallbacks <= 1,
                "({lo}, {hi}]: {stats:?}"
            );
        }
        let stats = check(&p, -10.0, 10.0);
        assert_eq!(
            (stats.inclusion_subranges, stats.exact_fallbacks),
            (0, 0),
            "the double root certified by its cluster: {stats:?}"
        );
    }

    #[test]
    fn query_ends_inside_an_undecided_part_keep_the_half_open_range() {
        // (3x − 1)² has exact coefficients and a double root 1/3, which is no f64: its
        // cluster cannot be certified (step 4), an undecided part around it goes to
        // subdivision. The ranges end at 1/3 rounded and its neighbours.
        let third = 1.0f64 / 3.0;
        let p = &Poly::new(vec![1.0, -6.0, 9.0]) * &Poly::from_roots(&[-1.0, 2.0, 3.0]);
        for (lo, hi) in [
            (-10.0, third),
            (third, 10.0),
            (third.next_down(), third.next_up()),
            (-0.5, third.next_down()),
            (third.next_up(), 2.5),
        ] {
            let stats = check(&p, lo, hi);
            assert!(stats.inclusion_subranges <= 1, "({lo}, {hi}]: {stats:?}");
        }
        let stats = check(&p, -10.0, 10.0);
        assert_eq!(
            stats.inclusion_subranges, 1,
            "one undecided part: {stats:?}"
        );
    }

    /// Issue 11: `(x − 1000)⁴` (Orellana & De Michele, ACM TOMS 46(2), 2020, Table 1),
    /// stored exactly, at `x_tol = 0`. Its four discs overlap; Descartes' rule cannot isolate
    /// a multiple root at any precision, and the query ended in exact Sturm isolation
    /// (`exact_fallbacks` 1, about 4 M instructions). Its cluster certifies `1000` exactly.
    #[test]
    fn exact_quadruple_root_is_certified_by_its_cluster() {
        let p = Poly::from_roots(&[1000.0; 4]);
        let (roots, stats) = all_roots_full_precision(&p);
        assert_eq!(roots, vec![1000.0], "{stats:?}");
        assert_eq!(
            (
                stats.exact_fallbacks,
                stats.adaptive_pieces,
                stats.inclusion_decided
            ),
            (0, 0, 1),
            "decided by the discs: {stats:?}"
        );
        let ivs = p.isolate_roots(-1e4, 1e4).expect("valid query");
        assert_eq!(
            ivs,
            vec![crate::RootInterval {
                lo: 1000.0,
                hi: 1000.0
            }]
        );
        for (lo, hi, want) in [(999.0, 1000.0, 1), (1000.0, 2000.0, 0), (0.0, 999.0, 0)] {
            let n = p.real_roots(lo, hi, 0.0).expect("valid query").len();
            assert_eq!(n, want, "({lo}, {hi}]");
        }
    }

    #[test]
    fn conjugate_pair_near_the_axis_is_not_taken_for_real_roots() {
        // (x² − x + 0.25 + δ²)(x − 2)(x + 1)(x − 3): roots 0.5 ± δi, −1, 2, 3. Its stored
        // coefficients round, so the oracle of the stored polynomial is the judge.
        for delta in [1e-3, 1e-6, 1e-9] {
            let pair = Poly::new(vec![0.25 + delta * delta, -1.0, 1.0]);
            let p = &pair * &Poly::from_roots(&[2.0, -1.0, 3.0]);
            let stats = check(&p, -10.0, 10.0);
            assert_eq!(stats.queries, 1, "one query");
        }
        // δ = 1e-3 is far enough from the axis for the discs to decide, and the pair is not
        // counted: three real roots.
        let pair = Poly::new(vec![0.25 + 1e-6, -1.0, 1.0]);
        let p = &pair * &Poly::from_roots(&[2.0, -1.0, 3.0]);
        let mut stats = RootStats::default();
        let roots = p
            .real_roots_with(-10.0, 10.0, &RootOptions::new(X_TOL), &mut stats)
            .expect("valid query");
        assert_eq!(roots.len(), 3, "{roots:?}");
        assert_eq!(stats.inclusion_decided, 1, "{stats:?}");
    }

    #[test]
    fn coefficients_spanning_1e300_neither_panic_nor_mislead() {
        let cases = [
            vec![1e-300, 1.0, 1e300, -1.0],
            vec![1e300, -3e300, 1e-300, 0.5, 1e-300],
            vec![-1e300, 1e-300, 1e-300, 1e-300, 1.0],
            vec![f64::MIN_POSITIVE, 1.0, -2.0, 1.0e-310],
        ];
        for c in cases {
            let p = Poly::new(c);
            let b = p.root_bound().unwrap_or(1e300).min(1e300);
            check(&p, -b, b);
        }
        assert!(
            !real_pieces(&[1.0, 2.0, 0.0], -1.0, 1.0, |_| {}),
            "a zero leading coefficient is refused"
        );
        assert!(
            !real_pieces(&[1.0, f64::NAN, 1.0], -1.0, 1.0, |_| {}),
            "NaN is refused"
        );
    }

    /// The real roots of `p` on `(−∞, ∞)` at `x_tol = 0`, with the query's statistics.
    fn all_roots_full_precision(p: &Poly<f64>) -> (Vec<f64>, RootStats) {
        let mut stats = RootStats::default();
        let roots = p
            .real_roots_with(
                f64::NEG_INFINITY,
                f64::INFINITY,
                &RootOptions::new(0.0),
                &mut stats,
            )
            .expect("valid query");
        (roots, stats)
    }

    /// The real roots of the stored `p` on `(−∞, ∞)` at `x_tol = 0`, checked against the
    /// exact oracle: as many as exact isolation finds ([`crate::testutil::stored_roots`]),
    /// each near the oracle's and a faithful rounding of a root (the exact
    /// sign of `p` changes between it and one of its neighbouring `f64`, or is 0 there).
    fn full_precision_roots(p: &Poly<f64>) -> (Vec<f64>, RootStats) {
        let (got, stats) = all_roots_full_precision(p);
        // Every real root is finite: (−MAX, MAX] holds them all.
        let want = crate::testutil::stored_roots(p, -f64::MAX, f64::MAX);
        assert_eq!(got.len(), want.len(), "got {got:?}, exact {want:?}");
        let q = p.to_rat().expect("finite");
        let sign = |x: f64| {
            let v = q.eval(&rat_from_f64(x).expect("finite"));
            i8::from(v > Rat::default()) - i8::from(v < Rat::default())
        };
        for (&g, &w) in got.iter().zip(&want) {
            // The oracle is refined to 2^-80 absolutely (`stored_roots`).
            assert!(
                (g - w).abs() <= (4.0 * f64::EPSILON * w.abs()).max(2f64.powi(-79)),
                "got {g:e}, exact {w:e}: {got:?}"
            );
            let s = sign(g);
            assert!(
                s == 0 || sign(g.next_down()) == -s || sign(g.next_up()) == -s,
                "{g:e} is not a faithful rounding of a root of {p:?}"
            );
        }
        (got, stats)
    }

    #[test]
    fn quartic_with_roots_up_to_1e154_is_decided_without_wide_tiers() {
        // Orellana–De Michele's (x − 1)(x − 10)(x − 10¹⁵²)(x − 10¹⁵⁴), coefficients by
        // Vieta's formulas in f64 as they build it: Σ|cᵢ||x|ⁱ overflows beyond |x| ≈ 10⁷⁷
        // (and at 10 already), so every sign, the iteration and the certificate use the
        // rescaled polynomial. Before: the discs overflowed, and the whole range was
        // isolated and refined with 256-bit signs.
        let (x1, x2, x3, x4) = (1.0, 10.0, 1e152, 1e154);
        let p = Poly::new(vec![
            x1 * x2 * x3 * x4,
            -x1 * x2 * (x3 + x4) - x3 * x4 * (x1 + x2),
            x1 * (x2 + x3) + x2 * (x3 + x4) + x4 * (x1 + x3),
            -(x1 + x2 + x3 + x4),
            1.0,
        ]);
        let (roots, stats) = full_precision_roots(&p);
        assert_eq!(roots.len(), 4, "{roots:?}");
        assert_eq!(
            (
                stats.inclusion_decided,
                stats.inclusion_undecided,
                stats.adaptive_pieces,
                stats.adaptive_refines,
                stats.multiprecision_pieces,
                stats.exact_fallbacks,
                stats.refine_fallbacks,
            ),
            (1, 0, 0, 0, 0, 0, 0),
            "decided by the discs, refined in f64: {stats:?}"
        );
    }

    #[test]
    fn roots_spread_over_more_than_1e200_are_decided_and_exact() {
        // Random signs and decimal exponents, spread ≥ 10²⁰⁰, with the products of the large
        // (and of the small) roots kept inside the f64 range so that the stored
        // coefficients are finite and non-zero.
        let mut rng = ChaCha8Rng::seed_from_u64(200);
        let mut cases = 0;
        while cases < 12 {
            let degree = rng.gen_range(3..=7);
            let exps: Vec<i32> = (0..degree).map(|_| rng.gen_range(-150..=250)).collect();
            let (lo, hi) = (exps.iter().min().unwrap(), exps.iter().max().unwrap());
            let up: i32 = exps.iter().filter(|&&e| e > 0).sum();
            let down: i32 = exps.iter().filter(|&&e| e < 0).sum();
            let mut sorted = exps.clone();
            sorted.sort_unstable();
            if hi - lo < 200 || up > 290 || down < -290 || sorted.windows(2).any(|w| w[0] == w[1]) {
                continue;
            }
            cases += 1;
            let roots: Vec<f64> = exps
                .iter()
                .map(|&e| {
                    let m: f64 = rng.gen_range(1.0..9.0);
                    let r = m * 10f64.powi(e);
                    if rng.r#gen::<bool>() { r } else { -r }
                })
                .collect();
            let p = Poly::from_roots(&roots);
            let (got, stats) = full_precision_roots(&p);
            assert_eq!(got.len(), degree, "{roots:?}: {got:?}");
            // Simple roots far apart: the discs decide, and the refinement ends in f64.
            assert_eq!(
                (
                    stats.inclusion_decided,
                    stats.multiprecision_pieces,
                    stats.adaptive_refines,
                    stats.exact_fallbacks,
                    stats.refine_fallbacks
                ),
                (1, 0, 0, 0, 0),
                "{roots:?}: {stats:?}"
            );
        }
    }

    #[test]
    fn aberth_sum_keeps_the_terms_of_approximations_beyond_2_500() {
        // Regression: the shortcut `conj(d)/|d|²` of Aberth's sum gave 0 for every term of
        // the approximation near 1.7·10²⁰¹ (`|d|²` overflowed), so its step was Newton's,
        // which halved it towards 0 in every sweep; the discs then decided nothing and the
        // query went to 17 multiprecision pieces.
        let p = Poly::from_roots(&[
            1.6888162361460415e201,
            7.249935932614283e-6,
            -4.921500301235755e59,
        ]);
        let (roots, stats) = full_precision_roots(&p);
        assert_eq!(roots.len(), 3, "{roots:?}");
        assert_eq!(
            (stats.inclusion_decided, stats.multiprecision_pieces),
            (1, 0),
            "decided by the discs: {stats:?}"
        );
    }

    #[test]
    fn coefficients_that_underflow_when_rescaled_keep_exact_answers() {
        // At the scale of the large roots the rescaled constant (and lower) coefficients
        // fall below the normal range or to 0; their rounding is counted in the bound.
        for c in [
            vec![1e-300, -1e-150, 3e-10, -1e100, 1.0],
            vec![-7e-320, 1e-200, -2.0, 5e150, 1e-100],
            vec![1e300, -1e300, 1e-300, 0.0, -1e-250, 1e-300],
            vec![2.5e-310, 0.0, -1e5, 0.0, 0.0, 0.0, 1e-290],
        ] {
            let p = Poly::new(c);
            full_precision_roots(&p);
        }
    }

    /// The stored `f64` polynomial with planted roots `k/m` (`m ≤ 1024`) of degree 12–20
    /// drawn from `seed`, and its degree (the seeds below give degrees 13–19 with near-real
    /// pairs).
    fn near_real_planted(seed: u64) -> (Poly<f64>, usize) {
        planted_of_degree(seed, 12..=20)
    }

    /// A planted polynomial of a degree drawn from `degrees`, roots `k/m` in `[0, 1]`,
    /// `m ≤ 1024`, stored in `f64`.
    fn planted_of_degree(
        seed: u64,
        degrees: std::ops::RangeInclusive<usize>,
    ) -> (Poly<f64>, usize) {
        let mut rng = ChaCha8Rng::seed_from_u64(seed);
        let d = rng.gen_range(degrees);
        let roots: Vec<_> = (0..d)
            .map(|_| {
                let m = rng.gen_range(2..=1024i64);
                rat(rng.gen_range(0..=m), m)
            })
            .collect();
        (planted(&roots).to_f64(), d)
    }

    /// Planted polynomials of degree 13–19 (roots `k/m`, `m ≤ 1024`, drawn as in the bench's
    /// planted corpus) whose stored `f64` polynomial has near-real conjugate pairs: the first
    /// decision leaves a part undecided (the pair's approximations were made real and could
    /// not converge); the pairs polished as complex roots ([`unreal_near_pairs`]) decide the
    /// whole range, the query subdivides nothing, and the answer is the exact oracle's.
    #[test]
    fn near_real_pairs_are_decided_by_the_discs() {
        for seed in [0u64, 2, 18, 89] {
            let (p, d) = near_real_planted(seed);
            let c = p.coeffs();
            let (lo, hi) = (-0.5, 1.5);
            let mut s = Scratch::default();
            s.reserve(d);
            assert!(approximate(c, &mut s) && certify(c, &mut s), "seed {seed}");
            decide(c, lo, hi, &mut s);
            assert!(
                !s.undecided.is_empty(),
                "seed {seed}: the f64 discs alone decide"
            );
            assert!(
                unreal_near_pairs(c, &mut s) && certify(c, &mut s),
                "seed {seed}: nothing restored"
            );
            decide(c, lo, hi, &mut s);
            assert!(s.undecided.is_empty(), "seed {seed}: {:?}", s.undecided);
            assert_decided_by_discs(&check(&p, lo, hi), &format!("seed {seed}"));
        }
    }

    /// Planted polynomials of degree 40 (as the bench's growth corpus): the stored `f64`
    /// polynomial has a dozen or more near-real pairs, whose `f64` derivative is noise; with
    /// `p` and `p'` compensated ([`polish_complex`]) every query is decided by the discs
    /// alone — no subdivision — and agrees with the exact oracle. Caught: with `p'` in
    /// `f64` the polish wandered and each of these queries left parts to the double-double
    /// subdivision (`inclusion_undecided = 1`).
    #[test]
    fn planted_degree_forty_is_decided_by_the_discs() {
        for seed in [1u64, 5, 11] {
            let (p, _) = planted_of_degree(seed, 40..=40);
            assert_decided_by_discs(&check(&p, -0.5, 1.5), &format!("seed {seed}"));
        }
    }

    /// The real polish gives up an approximation whose steps stop shrinking
    /// ([`POLISH_WANDERING_AFTER`]): planted degree 40 makes about 34 of its 40 approximations
    /// real where the stored polynomial has near-real pairs, and their polish, which cannot
    /// converge, took all [`MAX_POLISH_STEPS`] — 291 to 299 evaluations a query before the
    /// rule. The query's answer is checked by `planted_degree_forty_is_decided_by_the_discs`.
    #[test]
    fn the_real_polish_gives_up_wandering_approximations() {
        for seed in [1u64, 5, 11] {
            let (p, _) = planted_of_degree(seed, 40..=40);
            let c = p.coeffs();
            let mut s = Scratch::default();
            s.reserve(40);
            assert!(approximate(c, &mut s), "seed {seed}");
            // The polish again from where `approximate` started it: each approximation as
            // the `f64` iteration left it, made real where `approximate` made it real.
            for i in 0..s.z.len() {
                let before = s.before_real[i];
                let real = s.z[i].im == 0.0;
                s.z[i] = if real { C::new(before.re, 0.0) } else { before };
                s.done[i] = !real;
                s.p_bound[i] = f64::NAN;
            }
            let evaluations = polish_real(c, &mut s);
            assert!(
                evaluations < 200,
                "seed {seed}: {evaluations} evaluations in the real polish"
            );
        }
    }

    /// The double-double bound on `|p(z)|` ([`dd_horner_c`]) at the complex approximations
    /// the near-real polish ends at (where `p` is tiny and its `f64` value is noise) is at
    /// least the exact modulus of the stored polynomial there (rational arithmetic), and
    /// far below the `f64` bound ([`abs_p_upper`]) that could not decide these pairs.
    #[test]
    fn double_double_complex_bound_holds_exactly() {
        let mut checked = 0;
        for seed in [0u64, 2, 18, 89] {
            let (p, d) = near_real_planted(seed);
            let c = p.coeffs();
            let exact = p.to_rat().expect("finite coefficients");
            let mut s = Scratch::default();
            s.reserve(d);
            assert!(approximate(c, &mut s) && certify(c, &mut s), "seed {seed}");
            decide(c, -0.5, 1.5, &mut s);
            assert!(unreal_near_pairs(c, &mut s), "seed {seed}");
            for (i, &z) in s.z.iter().enumerate() {
                if !s.restored[i] || z.im == 0.0 {
                    continue;
                }
                let (_, bound) = dd_horner_c(c, z);
                // Exact p(x + iy) = Σ aₖ (x + iy)^k, real and imaginary parts in rationals.
                let (x, y) = (rat_from_f64(z.re).unwrap(), rat_from_f64(z.im).unwrap());
                let (mut re, mut im) = (Rat::from_integer(0.into()), Rat::from_integer(0.into()));
                for a in exact.coeffs().iter().rev() {
                    let nre = &re * &x - &im * &y + a;
                    im = &re * &y + &im * &x;
                    re = nre;
                }
                let b = rat_from_f64(bound).expect("finite bound");
                assert!(
                    re.clone() * &re + im.clone() * &im <= &b * &b,
                    "seed {seed}: {z:?}"
                );
                let (f64_bound, e) = abs_p_upper(c, z);
                assert!(
                    e == 0 && bound * 1e6 < f64_bound,
                    "seed {seed}: {bound:e} vs {f64_bound:e}"
                );
                checked += 1;
            }
        }
        assert!(checked >= 8, "{checked} complex approximations checked");
    }
}
#[cfg(test)]
mod debug_tmp {
    use super::*;
    #[test]
    fn dbg_spread() {
        let p = Poly::<f64>::from_roots(&[
            1.6888162361460415e201,
            7.249935932614283e-6,
            -4.921500301235755e59,
        ]);
        let c = p.coeffs();
        eprintln!("c = {c:?}");
        let mut s = Scratch::default();
        s.reserve(3);
        let a = approximate(c, &mut s);
        eprintln!("approx {a} z = {:?}", s.z);
        let ce = certify(c, &mut s);
        eprintln!("certify {ce} r = {:?}", s.radius);
        for &z in &s.z {
            eprintln!("abs_p_upper {:?} = {:?}", z, abs_p_upper(c, z));
        }
        decide(c, f64::NEG_INFINITY, f64::INFINITY, &mut s);
        eprintln!(
            "brackets {:?} undecided {:?} shadows {:?}",
            s.brackets, s.undecided, s.shadow
        );
    }
}

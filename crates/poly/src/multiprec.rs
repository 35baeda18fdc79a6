//! Adaptive precision for the pieces `f64` cannot decide: Descartes' rule in the Bernstein
//! basis and certified point signs in double-double arithmetic, then in arbitrary-precision
//! binary floating point ([`astro_float`]), the precision doubled until the sign is decided.
//!
//! Every evaluation carries a rigorous error bound, so a sign is certified, never guessed.
//! The model (Higham, *Accuracy and Stability of Numerical Algorithms*, §2.2 and §3.1):
//! each `+` or `×` of a [`Tier`] returns `(x∘y)(1 + δ) + η` with `|δ| ≤ u` (the tier's unit
//! roundoff) and `|η| ≤` [`DD_UNDERFLOW`] (double-double only: its error-free products are
//! exact only without underflow; arbitrary-precision floats have an unbounded exponent range
//! here, `η = 0`). A straight-line program of such operations with at most `k` roundings on
//! any path then has absolute error at most `γ(k)·m + (underflow term)`, where `m` is the same
//! program run exactly on absolute values. `f64` → wide conversion is exact (53 bits fit in
//! every tier), and so are the interval ends and widths used here (`TwoSum` gives the
//! difference of two `f64` exactly as a double-double).
//!
//! Isolation ([`PieceIsolator`]) bisects `(lo, hi]` at `f64` points, and each node `[x, y]`
//! gets its Bernstein coefficients computed afresh from the stored coefficients by a Taylor
//! shift at the tier of that node (no error carried over from a parent): its error bound uses
//! `M = Σ|cₖ|·max(|x|, |y|)ᵏ`, the shift starting at the end nearer 0. A node whose interior
//! coefficients are all within their bound moves to the next tier; a node that cannot be
//! split in `f64` (two roots closer than one `f64` spacing, a multiple root) or is still
//! undecided at [`MAX_BITS`] is left to the caller's exact isolation (the rare case, see
//! `paper-notes/isolation.md`, "Adaptive precision").

use astro_float::{BigFloat, RoundingMode};
use f256::f256;

use smallvec::SmallVec;

use crate::bernstein::Bracket;
use crate::dd_bernstein::{DdBernstein, DdOutcome};
use crate::double_double::{DD_MIN_EXACT, DD_UNDERFLOW, DD_UNIT, Dd, gamma_u, two_sum};
use crate::eval_bound::{abs_weights, certified_sign, certified_value, chain_underflow_weight};
use crate::octuple::{OCT_UNIT, Oct, oct, oct_approx, oct_pair, oct_to_dd};
use crate::refine::{IllinoisEnd, illinois_by, probe_by};
use crate::root_options::Tolerance;
use crate::scalar::{pair_span_bits, rat_from_f64};
use crate::stats::RootStats;
use crate::univariate::Poly;
use num_traits::Zero;

/// Precision of the first arbitrary-precision tier, in bits (the next after the octuple
/// tier's 237); each further tier doubles it. 256 though it is only 19 bits above the octuple
/// tier: planted degree 160's points need between the two, and with 512 next that query
/// saved 3 % instead of paying 256 bits (`paper-notes/isolation.md`, "An octuple tier").
const FIRST_BITS: usize = 256;

/// The precision cap. A node still undecided here holds a multiple root or a cluster tighter
/// than anything `f64` ends can separate (separation far below `2^-200` of the coefficient
/// scale); it goes to exact isolation. The tiers 256, 512, 1024 cost a few times more each.
pub(crate) const MAX_BITS: usize = 1024;

/// Most nodes one piece may visit over all tiers before the rest of it is left to exact
/// isolation (each node costs one Taylor shift, `O(n²)` wide operations).
const MAX_NODES: u32 = 4096;

/// Deepest bisection of one piece: 64 halvings cover any `f64` interval of one binade down to
/// adjacent numbers; past that the node is left to exact isolation.
const MAX_DEPTH: u32 = 96;

/// How many times the rest of a segment that a double-double de Casteljau run could not
/// finish is halved into fresh runs (each halving can shrink the bound `M` by up to `2ⁿ`)
/// before the per-node tiers take over.
const SEGMENT_HALVINGS: u32 = 6;

/// Non-dyadic fractions tried when a midpoint's sign is undecided at every tier (`√2 − 1`
/// and its complement): a root sitting exactly on the midpoint is then avoided.
const SPLIT_FRACTIONS: [f64; 2] = [0.414_213_562_373_095_1, 0.585_786_437_626_904_9];

/// A precision above `f64`: double-double, or binary floats of `bits` bits of mantissa.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord)]
pub(crate) enum Tier {
    /// Double-double (`hi + lo`, 106 bits), error-free transformations on `f64`.
    Dd,
    /// IEEE `binary256` (237 bits, `octuple.rs`), on the stack.
    Oct,
    /// [`astro_float::BigFloat`] with this many bits (round to nearest, even).
    Big(usize),
}

impl Tier {
    /// The next, more precise tier, `None` above [`MAX_BITS`].
    fn next(self) -> Option<Tier> {
        match self {
            Tier::Dd => Some(Tier::Oct),
            Tier::Oct => Some(Tier::Big(FIRST_BITS)),
            Tier::Big(b) if 2 * b <= MAX_BITS => Some(Tier::Big(2 * b)),
            Tier::Big(_) => None,
        }
    }
}

// ---------------------------------------------------------------------------------------
// The tier-generic operations.

/// The operations a tier provides for the Taylor shift, the basis change and Horner's rule.
trait Arith {
    type T: Clone;
    /// `x` exactly.
    fn exact_f64(&self, x: f64) -> Self::T;
    /// `hi + lo` (a TwoSum pair) exactly; `None` when the tier cannot hold it.
    fn exact_pair(&self, hi: f64, lo: f64) -> Option<Self::T>;
    fn add(&self, x: &Self::T, y: &Self::T) -> Self::T;
    fn add_f(&self, x: &Self::T, y: f64) -> Self::T;
    fn mul(&self, x: &Self::T, y: &Self::T) -> Self::T;
    /// An `f64` multiplier prepared once for [`Arith::mul_by`] (exactly `y`): the wide tier
    /// would otherwise convert it at every product of a Taylor shift or Horner loop.
    type F;
    fn factor(&self, y: f64) -> Self::F;
    fn mul_by(&self, x: &Self::T, y: &Self::F) -> Self::T;
    /// Whether the tier's exponent range is unbounded, so that it can use a [`Mag::Wide`]
    /// magnitude (one that overflows `f64`).
    const WIDE_RANGE: bool;
    /// The sign of the exact value of `x` when `|x|` exceeds `γ(k)·mag·mult + tiny` (the
    /// program's bound; `mag` and `mult ≥ 0` computed rounded up), else 0.
    fn sign_beyond(&self, x: &Self::T, k: usize, mag: &Mag, mult: f64, tiny: f64) -> i8;
    /// The absolute underflow error of one operation (0 without underflow).
    fn underflow(&self) -> f64;
    /// Whether the bounds hold for what this value computed: `false` when an operation
    /// erred in a way the standard model with [`Arith::underflow`] does not cover.
    fn clean(&self) -> bool {
        true
    }
    /// `x` rounded to `f64` (NaN outside its range): a value to place trial points by, never
    /// a certified one.
    fn approx(&self, x: &Self::T) -> f64;
}

struct DdArith;

impl Arith for DdArith {
    type T = Dd;
    fn exact_f64(&self, x: f64) -> Dd {
        Dd::from_f64(x)
    }
    fn exact_pair(&self, hi: f64, lo: f64) -> Option<Dd> {
        Some(Dd::from_pair(hi, lo))
    }
    fn add(&self, x: &Dd, y: &Dd) -> Dd {
        x.add(*y)
    }
    fn add_f(&self, x: &Dd, y: f64) -> Dd {
        x.add_f(y)
    }
    fn mul(&self, x: &Dd, y: &Dd) -> Dd {
        x.mul(*y)
    }
    type F = f64;
    fn factor(&self, y: f64) -> f64 {
        y
    }
    fn mul_by(&self, x: &Dd, y: &f64) -> Dd {
        x.mul_f(*y)
    }
    const WIDE_RANGE: bool = false;
    fn sign_beyond(&self, x: &Dd, k: usize, mag: &Mag, mult: f64, tiny: f64) -> i8 {
        let Mag::F64(scale) = mag else {
            return 0;
        };
        let bound = gamma_u(k, DD_UNIT) * (scale * mult) * (1.0 + 4.0 * f64::EPSILON) + tiny;
        if bound.is_finite() {
            x.sign_beyond(bound)
        } else {
            0
        }
    }
    fn underflow(&self) -> f64 {
        DD_UNDERFLOW
    }
    fn approx(&self, x: &Dd) -> f64 {
        x.hi
    }
}

/// The octuple tier widens a bound it forms by `1 + 2^OCT_BOUND_WIDEN_EXP` (relative): the
/// bound takes four roundings of at most `2^-237` each, which `2^-200` covers many times over,
/// and `1 + 2^-200` is exact in `binary256` (not in `f64`).
const OCT_BOUND_WIDEN_EXP: i32 = -200;

impl Arith for Oct {
    type T = f256;
    fn exact_f64(&self, x: f64) -> f256 {
        oct(x)
    }
    fn exact_pair(&self, hi: f64, lo: f64) -> Option<f256> {
        oct_pair(hi, lo)
    }
    fn add(&self, x: &f256, y: &f256) -> f256 {
        *x + *y
    }
    fn add_f(&self, x: &f256, y: f64) -> f256 {
        *x + oct(y)
    }
    fn mul(&self, x: &f256, y: &f256) -> f256 {
        Oct::mul(self, *x, *y)
    }
    type F = f256;
    fn factor(&self, y: f64) -> f256 {
        oct(y)
    }
    fn mul_by(&self, x: &f256, y: &f256) -> f256 {
        Oct::mul(self, *x, *y)
    }
    // Its exponent range (to 2^262143) is not unbounded: a magnitude that overflows `f64`
    // goes to the astro-float tiers.
    const WIDE_RANGE: bool = false;
    fn sign_beyond(&self, x: &f256, k: usize, mag: &Mag, mult: f64, tiny: f64) -> i8 {
        let Mag::F64(scale) = mag else {
            return 0;
        };
        if !x.is_finite() || (k as f64) * OCT_UNIT >= 0.5 {
            return 0;
        }
        // γ(k)·mag·mult ≤ 2k·u·mag·mult for k·u ≤ 1/2, formed in binary256 (its range holds
        // it whatever f64 would underflow to) from exact factors (2k·u is an integer times a
        // power of two), then widened by `1 + 2^OCT_BOUND_WIDEN_EXP`.
        let widen = oct(1.0) + oct(2f64.powi(OCT_BOUND_WIDEN_EXP));
        let bound = (oct(2.0 * k as f64 * OCT_UNIT) * oct(*scale) * oct(mult) + oct(tiny)) * widen;
        if !bound.is_finite() {
            return 0;
        }
        // Comparisons are exact.
        if x.abs() > bound {
            if x.is_sign_negative() { -1 } else { 1 }
        } else {
            0
        }
    }
    // No underflow bound: an underflowing product is flagged instead (`clean`).
    fn underflow(&self) -> f64 {
        0.0
    }
    fn clean(&self) -> bool {
        Oct::clean(self)
    }
    fn approx(&self, x: &f256) -> f64 {
        oct_approx(*x)
    }
}

/// Arbitrary-precision binary floats of `bits` bits, round to nearest.
struct BigArith {
    bits: usize,
}

/// Precision that holds any sum of two `f64` numbers exactly: their exponents differ by at
/// most `2098`, plus 53 bits of mantissa and a carry.
const EXACT_PAIR_BITS: usize = 2176;

/// Precision, in bits (a multiple of 64, at most [`EXACT_PAIR_BITS`]), that holds
/// `hi + lo` exactly ([`pair_span_bits`] rounded up to whole words). Why not always [`EXACT_PAIR_BITS`]: the node width `w` is such a
/// pair and multiplies every coefficient of a Taylor shift, and a product with a 2 176-bit
/// operand cost astro-float several times one of the tier's own width (issue 11:
/// Chebyshev T₈₀'s isolation spent a fifth of its time in those products).
fn exact_pair_bits(hi: f64, lo: f64) -> usize {
    if hi == 0.0 || lo == 0.0 {
        return 64;
    }
    let span = pair_span_bits(hi, lo) as usize;
    span.div_ceil(64).saturating_mul(64).min(EXACT_PAIR_BITS)
}

impl BigArith {
    /// The unit roundoff: `astro_float` rounds the exact result to `bits` bits (rounded up to
    /// whole 64-bit words); `2^(1 − bits)` is a bound even for a faithful rounding.
    fn unit(&self) -> f64 {
        2f64.powi(1 - self.bits as i32)
    }
}

const RM: RoundingMode = RoundingMode::ToEven;

/// `2^64`: scales any subnormal `f64` (at least `2^-1074`) into the normal range exactly.
const SUBNORMAL_LIFT: f64 = 18_446_744_073_709_551_616.0;

/// `x` as a [`BigFloat`], exactly. Why not `BigFloat::from_f64` alone: in astro-float 0.9.6
/// it converts a subnormal to *half* its value (the exponent of a subnormal is taken as
/// `−1023` instead of `−1022`), which made the certified path return roots of
/// `1.877e-308·x² − 3.83` that were `√2` too large (issue 13 follow-up). A subnormal is
/// therefore converted as the normal `x·2^64` (exact) with its exponent lowered by 64.
fn big_from_f64(x: f64) -> BigFloat {
    if !x.is_subnormal() {
        return BigFloat::from_f64(x, 64);
    }
    let mut b = BigFloat::from_f64(x * SUBNORMAL_LIFT, 64);
    if let Some(e) = b.exponent() {
        b.set_exponent(e - 64);
    }
    b
}

impl Arith for BigArith {
    type T = BigFloat;
    fn exact_f64(&self, x: f64) -> BigFloat {
        big_from_f64(x)
    }
    fn exact_pair(&self, hi: f64, lo: f64) -> Option<BigFloat> {
        Some(big_from_f64(hi).add(&big_from_f64(lo), exact_pair_bits(hi, lo), RM))
    }
    fn add(&self, x: &BigFloat, y: &BigFloat) -> BigFloat {
        x.add(y, self.bits, RM)
    }
    fn add_f(&self, x: &BigFloat, y: f64) -> BigFloat {
        x.add(&big_from_f64(y), self.bits, RM)
    }
    fn mul(&self, x: &BigFloat, y: &BigFloat) -> BigFloat {
        x.mul(y, self.bits, RM)
    }
    type F = BigFloat;
    fn factor(&self, y: f64) -> BigFloat {
        big_from_f64(y)
    }
    fn mul_by(&self, x: &BigFloat, y: &BigFloat) -> BigFloat {
        x.mul(y, self.bits, RM)
    }
    const WIDE_RANGE: bool = true;
    fn sign_beyond(&self, x: &BigFloat, k: usize, mag: &Mag, mult: f64, _tiny: f64) -> i8 {
        if x.is_nan() || x.is_inf() {
            return 0;
        }
        // γ(k)·mag·mult ≤ 2k·u·mag·mult for k·u ≤ 1/2: the bound is formed in the wide
        // format (u far below f64's range, and mag possibly beyond it), rounded up.
        let u = self.unit();
        if (k as f64) * u >= 0.5 {
            return 0;
        }
        let factor = big_from_f64(mult * (2.0 * k as f64) * (1.0 + 4.0 * f64::EPSILON));
        let mut bound = match mag {
            Mag::F64(scale) => big_from_f64(*scale).mul(&factor, 128, RoundingMode::Up),
            Mag::Wide(scale) => scale.mul(&factor, 128, RoundingMode::Up),
        };
        if let Some(e) = bound.exponent() {
            bound.set_exponent(e - (self.bits as i32 - 1));
        } else if !bound.is_zero() {
            return 0;
        }
        // The sign of the difference `|x| − bound`: a correctly rounded difference has the
        // sign of the exact one (no underflow here). (`BigFloat::abs_cmp` is not used: in astro-float 0.9.6
        // it answered |−0.9| < 3.5e-76 for operands of different precisions.)
        let margin = x.abs().sub(&bound, self.bits, RM);
        if margin.is_positive() && !margin.is_zero() {
            if x.is_negative() { -1 } else { 1 }
        } else {
            0
        }
    }
    fn underflow(&self) -> f64 {
        0.0
    }
    fn approx(&self, x: &BigFloat) -> f64 {
        big_to_dd(x).map_or(f64::NAN, |d| d.hi)
    }
}

/// `M = Σ|cᵢ|·rⁱ`, the magnitude in the error bounds, computed rounded up: in `f64`
/// ([`abs_weights`]), or, when that overflows and the tier has an unbounded exponent range,
/// as a [`BigFloat`] rounded up at every step. Why the wide form: with coefficients up to
/// `f64::MAX`, `M` overflows at any `|x| > 1`, so no tier could certify a sign and every such
/// query went to exact Sturm isolation, seconds to minutes at degree 33 (issue 13 follow-up).
enum Mag {
    F64(f64),
    Wide(BigFloat),
}

/// [`Mag`] of `c` at `r ≥ 0` for a tier whose exponent range is unbounded (`wide`) or not,
/// with `Σ rⁱ` (`f64`, possibly infinite) for the underflow terms; `None` when it overflows
/// `f64` and the tier is not wide.
fn magnitude(c: &[f64], r: f64, wide: bool) -> Option<(Mag, f64)> {
    let (s, z) = abs_weights(c, r);
    if s.is_finite() {
        return Some((Mag::F64(s), z));
    }
    if !wide || !r.is_finite() {
        return None;
    }
    // Horner's rule on non-negative numbers, every operation rounded up: an upper bound.
    let up = RoundingMode::Up;
    let x = big_from_f64(r);
    let m = c.iter().rev().fold(big_from_f64(0.0), |acc, ci| {
        acc.mul(&x, 128, up).add(&big_from_f64(ci.abs()), 128, up)
    });
    Some((Mag::Wide(m), z))
}

// ---------------------------------------------------------------------------------------
// Certified point signs.

/// The sign of `p(x)` at one tier by Horner's rule (`2n` roundings), certified, or 0; with
/// the computed value rounded to `f64` ([`Arith::approx`]).
fn horner_sign<A: Arith>(ar: &A, c: &[f64], x: f64) -> (i8, f64) {
    let n = c.len() - 1;
    let mut v = ar.exact_f64(c[n]);
    let xf = ar.factor(x);
    for &ci in c[..n].iter().rev() {
        v = ar.add_f(&ar.mul_by(&v, &xf), ci);
    }
    let Some((s, z)) = magnitude(c, x.abs(), A::WIDE_RANGE) else {
        return (0, ar.approx(&v));
    };
    // Underflow errors are amplified by at most |x| per later step: Σ|x|ⁱ per operation.
    // (A wide tier has no underflow; its `z` may be infinite and is then not used.)
    let tiny = if A::WIDE_RANGE {
        0.0
    } else {
        2.0 * ar.underflow() * z
    };
    if !ar.clean() {
        return (0, ar.approx(&v));
    }
    (ar.sign_beyond(&v, 2 * n, &s, 1.0, tiny), ar.approx(&v))
}

/// [`point_sign`] from double-double up, as the sign function of [`DdBernstein`].
fn dd_sign(c: &[f64], x: f64) -> i8 {
    point_sign(c, x, Tier::Dd).0
}

/// The certified sign of `p(x)`: the `f64` tiers of [`certified_sign`], then each wide tier
/// from `from` up to [`MAX_BITS`]; 0 when none decides (then `p(x)` is zero or within
/// `2^-1000` of the scale `Σ|cᵢ||x|ⁱ`). Returns the tier that decided (`from` when `f64` did).
pub(crate) fn point_sign(c: &[f64], x: f64, from: Tier) -> (i8, Tier) {
    let s = certified_sign(c, x, 0.0);
    if s != 0 {
        return (s, from);
    }
    let (s, t, _) = wide_sign(c, x, from);
    (s, t)
}

/// [`point_sign`] with an approximate value of `p(x)` (NaN when unknown), for placing the
/// next trial point of a refinement.
fn point_sign_value(c: &[f64], x: f64, from: Tier) -> (i8, Tier, f64) {
    let (v, s) = certified_value(c, x, 0.0);
    if s != 0 {
        return (s, from, v);
    }
    wide_sign(c, x, from)
}

/// The tiers of [`point_sign`] above `f64`, from `from` up.
fn wide_sign(c: &[f64], x: f64, from: Tier) -> (i8, Tier, f64) {
    let mut tier = Some(from);
    let mut value = f64::NAN;
    while let Some(t) = tier {
        let (s, v) = match t {
            Tier::Dd => horner_sign(&DdArith, c, x),
            Tier::Oct => horner_sign(&Oct::default(), c, x),
            Tier::Big(bits) => horner_sign(&BigArith { bits }, c, x),
        };
        if s != 0 {
            return (s, t, v);
        }
        value = v;
        tier = t.next();
    }
    (0, Tier::Big(MAX_BITS), value)
}

// ---------------------------------------------------------------------------------------
// Bernstein coefficients of one node.

/// `C(n, ⌊n/2⌋)`, the largest binomial coefficient of degree `n`, rounded up (infinite from
/// `n ≈ 1030`).
fn central_binomial(n: usize) -> f64 {
    (1..=n / 2).fold(1.0f64, |b, i| {
        b * (n - i + 1) as f64 / i as f64 * (1.0 + 2.0 * f64::EPSILON)
    })
}

/// What Descartes' rule says about a node at one tier.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Class {
    /// No root in the open node.
    Empty,
    /// Exactly one root (simple) in the open node.
    One,
    /// More sign changes, or some coefficient undecided: halve.
    Split,
    /// Every interior coefficient is within its error bound: this tier cannot decide the
    /// node or any part of it.
    Hopeless,
}

/// Classifies the node `[x, y]` (`x < y`, on one side of 0 or with `x = 0` or `y = 0`), given
/// the certified non-zero signs `s_x`, `s_y` of `p` at its ends, by the signs of the scaled
/// Bernstein coefficients `Bᵢ = C(n, i)·bᵢ` of `p` on it, computed at this tier.
///
/// The shift starts at the end `a` nearer 0 and runs towards the other, `t = a + w·u` with
/// `w = other − a` exact (a double-double pair), so the absolute-value program is bounded by
/// `M = Σ|cₖ|(|a| + |w|)ᵏ = Σ|cₖ|·max(|x|, |y|)ᵏ`. Taylor shift by `a` by Horner's rule on
/// polynomials (2 roundings per step, `2n`), each `q_j` then scaled by `wʲ` (`wʲ` by repeated
/// products, at most `n` roundings with the scaling; the products by `w` are `n`, not the
/// `n²/2` of shifting by `a + w·u` directly), then `Bᵢ = Σ_{j≤i} C(n−j, i−j)·q_j` as the
/// Horner-like scheme `A_j = A_{j−1}·(1 + u) + q_j·uʲ` (one rounding per coefficient and step,
/// `n + 1`). With `k = 4n + 1` roundings: `|B̂ᵢ − Bᵢ| ≤ γ(k)·C(n, i)·M`, since the absolute
/// program's `B̃ᵢ = Σ_j C(n−j, i−j)·q̃_j ≤ C(n, i)·Σ_j q̃_j = C(n, i)·M` (as
/// `C(n−j, i−j) = C(n, i)·C(i, j)/C(n, j) ≤ C(n, i)`).
fn classify<A: Arith>(
    ar: &A,
    c: &[f64],
    (x, y): (f64, f64),
    (s_x, s_y): (i8, i8),
    q: &mut Vec<A::T>,
    b: &mut Vec<A::T>,
) -> Class {
    let n = c.len() - 1;
    let (a, other, s_a, s_other) = if x >= 0.0 {
        (x, y, s_x, s_y)
    } else {
        (y, x, s_y, s_x)
    };
    let (wh, wl) = two_sum(other, -a);
    let Some(w) = ar.exact_pair(wh, wl) else {
        return Class::Hopeless;
    };
    let r = a.abs().max(other.abs());
    let Some((mag, zr)) = magnitude(c, r, A::WIDE_RANGE) else {
        return Class::Hopeless;
    };
    // Every shifted and Bernstein value is at most `C(n, i)·M` in magnitude: where that
    // leaves `f64`'s range, a tier with that range cannot classify the node at all (its
    // bounds on the middle coefficients are infinite, so the node would be split until the
    // node budget sends the piece to exact isolation), so it goes up a tier.
    if let Mag::F64(m) = mag
        && !A::WIDE_RANGE
        && !(m * central_binomial(n)).is_finite()
    {
        return Class::Hopeless;
    }
    q.clear();
    if a == 0.0 {
        q.extend(c.iter().map(|&ck| ar.exact_f64(ck)));
    } else {
        q.push(ar.exact_f64(c[n]));
        q.resize(n + 1, ar.exact_f64(0.0));
        let af = ar.factor(a);
        for k in (0..n).rev() {
            for i in (1..=n - k).rev() {
                q[i] = ar.add(&ar.mul_by(&q[i], &af), &q[i - 1]);
            }
            q[0] = ar.add_f(&ar.mul_by(&q[0], &af), c[k]);
        }
    }
    // `q_j ← q_j·wʲ`: the coefficients of `p(a + w·u)`.
    let mut wj = w.clone();
    for qj in q.iter_mut().skip(1) {
        *qj = ar.mul(qj, &wj);
        wj = ar.mul(&wj, &w);
    }
    b.clear();
    b.push(q[0].clone());
    for j in 1..=n {
        b.push(b[j - 1].clone());
        for i in (1..j).rev() {
            b[i] = ar.add(&b[i], &b[i - 1]);
        }
        b[j] = ar.add(&b[j], &q[j]);
    }
    if !ar.clean() {
        return Class::Hopeless;
    }
    let k = 4 * n + 1;
    // Underflow: each operation may add `η`; a later Horner step multiplies such an error by
    // at most |a| + |w| = r, the basis change by at most C(n, i) ≤ 2ⁿ; at most (n + 1)²
    // operations feed each output.
    // The scaling chain wʲ multiplies its underflow errors by the shifted coefficients
    // (`chain_underflow_weight`).
    let tiny = if A::WIDE_RANGE {
        0.0
    } else {
        let chain = chain_underflow_weight(c, a, wh, DD_MIN_EXACT);
        ar.underflow() * (zr + chain) * 2f64.powi(n as i32) * ((n + 1) * (n + 1)) as f64
    };
    let mut binom = 1.0f64;
    let mut prev = s_a;
    let mut changes = 0u32;
    let mut undecided = 0usize;
    for (i, bi) in b.iter().enumerate().take(n).skip(1) {
        // C(n, i) from C(n, i − 1), rounded up (exact while it fits 53 bits).
        binom = (binom * (n - i + 1) as f64 / i as f64) * (1.0 + 2.0 * f64::EPSILON);
        let s = ar.sign_beyond(bi, k, &mag, binom, tiny);
        if s == 0 {
            undecided += 1;
            continue;
        }
        changes += u32::from(s != prev);
        prev = s;
    }
    if undecided > 0 {
        return if undecided == n - 1 {
            Class::Hopeless
        } else {
            Class::Split
        };
    }
    changes += u32::from(s_other != prev);
    match changes {
        0 => Class::Empty,
        1 => Class::One,
        _ => Class::Split,
    }
}

/// Per-tier scratch for [`classify`].
#[derive(Default)]
struct Scratch {
    dd: (Vec<Dd>, Vec<Dd>),
    oct: (Vec<f256>, Vec<f256>),
    big: (Vec<BigFloat>, Vec<BigFloat>),
}

fn classify_at(tier: Tier, c: &[f64], xy: (f64, f64), s: (i8, i8), sc: &mut Scratch) -> Class {
    match tier {
        Tier::Dd => classify(&DdArith, c, xy, s, &mut sc.dd.0, &mut sc.dd.1),
        Tier::Oct => classify(&Oct::default(), c, xy, s, &mut sc.oct.0, &mut sc.oct.1),
        Tier::Big(bits) => classify(&BigArith { bits }, c, xy, s, &mut sc.big.0, &mut sc.big.1),
    }
}

// ---------------------------------------------------------------------------------------
// Isolation of a piece.

/// One result of [`PieceIsolator::next`].
#[derive(Clone, Debug, PartialEq)]
pub(crate) enum Outcome {
    /// A certified bracket holding exactly one simple root.
    Bracket(Bracket),
    /// A sub-piece `(lo, hi]` that even [`MAX_BITS`] could not decide (a multiple root, or
    /// roots closer than one `f64` spacing): the caller isolates it exactly.
    Undecided(f64, f64),
}

/// A node of the bisection: `(x, y]`, the certified signs of `p` at its ends, the tier it
/// starts at, its depth, and whether a wide tier's split of it may descend to double-double
/// ([`descend`]): not within the rest a descended run handed back (a cluster double-double
/// cannot resolve would otherwise be descended into again at every level).
type Node = (f64, f64, i8, i8, Tier, u32, bool);

/// A double-double de Casteljau run with its segment's end `y`, the sign there, the
/// segment's halvings, and for a descended run the tier and depth of its node.
type FastRun<'c> = (DdBernstein<'c>, f64, i8, u32, Option<(Tier, u32)>);

/// A segment of a piece: `(x, y]`, the certified signs at its ends, and how many halvings
/// of a de Casteljau run's rest made it.
type Segment = (f64, f64, i8, i8, u32);

/// Isolation of the roots of `p` (coefficients `c`, degree ≥ 1) in `(lo, hi]`, where `p(lo)`
/// and `p(hi)` have certified non-zero signs, by bisection at `f64` points with each node
/// classified afresh at its own tier, starting at double-double. [`next`](Self::next) yields
/// the outcomes in increasing order, so a smallest-root query stops at the first root (an
/// undecided piece may hold none: the caller decides it exactly and asks for more).
///
/// Each segment (the piece, or its two sides of 0) is first given to the double-double de
/// Casteljau run ([`DdBernstein`], one Taylor shift for the whole segment); only what that
/// run hands back is bisected here with a fresh shift per node.
pub(crate) struct PieceIsolator<'c> {
    c: &'c [f64],
    /// Segments not started yet, the next on top: `(x, y]` with the signs at the ends and
    /// the number of halvings that made it.
    segments: SmallVec<[Segment; 4]>,
    /// The de Casteljau run on the current segment, with that segment's end, its sign and
    /// halvings; a descended run ([`descend`]) also carries the tier and depth its node had,
    /// where the rest it hands back resumes.
    fast: Option<FastRun<'c>>,
    stack: SmallVec<[Node; 16]>,
    nodes: u32,
    /// Nodes classified at a wide tier (a wide Taylor shift each, the costly ones).
    wide_nodes: u32,
    used_wide: bool,
    sc: Scratch,
}

impl<'c> PieceIsolator<'c> {
    /// Starts on `(lo, hi]` with the certified signs `(s_lo, s_hi)`; counts the piece in
    /// [`RootStats::adaptive_pieces`].
    pub(crate) fn new(
        c: &'c [f64],
        (lo, hi): (f64, f64),
        (s_lo, s_hi): (i8, i8),
        stats: &mut RootStats,
    ) -> Self {
        stats.adaptive_pieces += 1;
        let mut segments = SmallVec::new();
        // A piece straddling 0 is split there first (p(0) = c₀ exactly), so that every node
        // has `max(|x|, |y|)` no larger than needed in its bound `M`.
        if lo < 0.0 && 0.0 < hi && c[0] != 0.0 {
            let s0 = if c[0] > 0.0 { 1 } else { -1 };
            segments.push((0.0, hi, s0, s_hi, 0));
            segments.push((lo, 0.0, s_lo, s0, 0));
        } else {
            segments.push((lo, hi, s_lo, s_hi, 0));
        }
        PieceIsolator {
            c,
            segments,
            fast: None,
            stack: SmallVec::new(),
            nodes: 0,
            wide_nodes: 0,
            used_wide: false,
            sc: Scratch::default(),
        }
    }

    /// The next outcome, left to right; `None` when the piece is done. Counts
    /// [`RootStats::multiprecision_pieces`] once when a tier above double-double was used.
    pub(crate) fn next(&mut self, stats: &mut RootStats) -> Option<Outcome> {
        loop {
            if let Some((run, y, s_y, halvings, descended)) = &mut self.fast {
                match run.next(stats) {
                    Some(DdOutcome::Bracket(b)) => return Some(Outcome::Bracket(b)),
                    Some(DdOutcome::Handoff { t_a, s_a }) => {
                        let (y, s_y, halvings, descended) = (*y, *s_y, *halvings, *descended);
                        self.fast = None;
                        if let Some((tier, depth)) = descended {
                            if t_a < y {
                                self.stack.push((t_a, y, s_a, s_y, tier, depth, false));
                            }
                            continue;
                        }
                        // A fresh run on each half of the rest: its bound M shrinks with the
                        // segment's distance from 0 (as the f64 path's restarts do), up to
                        // SEGMENT_HALVINGS times; then the per-node tiers take the rest.
                        let split = (halvings < SEGMENT_HALVINGS && t_a < y)
                            .then(|| split_point(self.c, t_a, y, Tier::Dd, 0))
                            .flatten();
                        match split {
                            Some((m, s_m, _)) => {
                                self.segments.push((m, y, s_m, s_y, halvings + 1));
                                self.segments.push((t_a, m, s_a, s_m, halvings + 1));
                            }
                            None if t_a < y => {
                                self.stack.push((t_a, y, s_a, s_y, Tier::Dd, 0, true))
                            }
                            None => {}
                        }
                    }
                    None => self.fast = None,
                }
            }
            if let Some(outcome) = self.next_node(stats) {
                return Some(outcome);
            }
            if self.fast.is_some() || !self.stack.is_empty() {
                continue;
            }
            let (x, y, s_x, s_y, halvings) = self.segments.pop()?;
            match DdBernstein::new(self.c, (x, y), (s_x, s_y), dd_sign) {
                Some(run) => self.fast = Some((run, y, s_y, halvings, None)),
                None => self.stack.push((x, y, s_x, s_y, Tier::Dd, 0, true)),
            }
        }
    }

    /// The per-node bisection of the stack: the next outcome, or `None` when the stack is
    /// empty.
    fn next_node(&mut self, stats: &mut RootStats) -> Option<Outcome> {
        let c = self.c;
        while let Some((x, y, s_x, s_y, tier, depth, may_descend)) = self.stack.pop() {
            if self.nodes >= MAX_NODES || depth >= MAX_DEPTH {
                return Some(Outcome::Undecided(x, y));
            }
            self.nodes += 1;
            if tier > Tier::Dd {
                self.wide_nodes += 1;
                if !self.used_wide {
                    self.used_wide = true;
                    stats.multiprecision_pieces += 1;
                }
            }
            let class = if c.len() == 2 {
                // Degree 1: the end signs decide.
                if s_x == s_y { Class::Empty } else { Class::One }
            } else {
                classify_at(tier, c, (x, y), (s_x, s_y), &mut self.sc)
            };
            match class {
                Class::Empty => {}
                Class::One => return Some(Outcome::Bracket(Bracket::new(x, y, s_x))),
                Class::Hopeless => match tier.next() {
                    Some(t) => self.stack.push((x, y, s_x, s_y, t, depth, may_descend)),
                    None => return Some(Outcome::Undecided(x, y)),
                },
                Class::Split => {
                    let wide = match tier {
                        Tier::Dd => None,
                        Tier::Oct => Some(Wide::Oct(&self.sc.oct.1)),
                        Tier::Big(bits) => Some(Wide::Big(bits, &self.sc.big.1)),
                    };
                    if may_descend
                        && let Some(wide) = wide
                        && let Some(run) = descend(c, (x, y), (s_x, s_y), wide)
                    {
                        // The caller's loop drains the run before this stack.
                        self.fast = Some((run, y, s_y, SEGMENT_HALVINGS, Some((tier, depth))));
                        return None;
                    }
                    stats.subdivisions += 1;
                    match split_point(c, x, y, tier, depth) {
                        Some((m, s_m, t_m)) => {
                            let t = tier.max(t_m);
                            self.stack.push((m, y, s_m, s_y, t, depth + 1, may_descend));
                            self.stack.push((x, m, s_x, s_m, t, depth + 1, may_descend));
                        }
                        None => return Some(Outcome::Undecided(x, y)),
                    }
                }
            }
        }
        None
    }
}

/// The double-double de Casteljau run on a node a wide tier has just split (`bernstein` its
/// scaled Bernstein coefficients `B̂ᵢ` from [`classify`], from the end nearer 0), so that the
/// node's subtree costs additions in double-double instead of a wide Taylor shift per node.
/// `bᵢ = B̂ᵢ / C(n, i)` in the wide format (`C(n, i)` exact), rounded to double-double.
/// Error handed down, per coefficient: [`classify`]'s bound `γ(k)·C(n, i)·M` divided by
/// `C(n, i)`, the division's rounding (`u·|bᵢ|`) and the conversion's (`2^-104·|bᵢ|`), with
/// `u` the tier's unit. `None` when `M` or a coefficient leaves `f64`'s range (or, at the
/// octuple tier, a binomial coefficient its significand).
fn descend<'c>(
    c: &'c [f64],
    (x, y): (f64, f64),
    s: (i8, i8),
    bernstein: Wide<'_>,
) -> Option<DdBernstein<'c>> {
    let n = c.len() - 1;
    if bernstein.len() != n + 1 {
        return None;
    }
    let (Mag::F64(mag), _) = magnitude(c, x.abs().max(y.abs()), true)? else {
        return None;
    };
    let (mut b, unit): (SmallVec<[Dd; 64]>, f64) = match bernstein {
        Wide::Big(bits, big) => (big_bernstein_to_dd(n, bits, big)?, BigArith { bits }.unit()),
        Wide::Oct(coeffs) => (oct_bernstein_to_dd(n, coeffs)?, OCT_UNIT),
    };
    let largest = b.iter().fold(0.0f64, |m, v| m.max(v.hi.abs() + v.lo.abs()));
    if x < 0.0 {
        // Shifted from y towards x: coefficient i belongs to t = y + (x − y)·i/n.
        b.reverse();
    }
    let k = 4 * n + 1;
    let e0 = (2.0 * k as f64 * unit * mag + (unit + 2f64.powi(-104)) * largest)
        * (1.0 + 8.0 * f64::EPSILON)
        + DD_UNDERFLOW;
    DdBernstein::from_bernstein(c, (x, y), s, b, e0, dd_sign)
}

/// The scaled Bernstein coefficients a wide tier computed, for [`descend`].
enum Wide<'a> {
    /// An astro-float tier of this many bits.
    Big(usize, &'a [BigFloat]),
    /// The octuple tier.
    Oct(&'a [f256]),
}

impl Wide<'_> {
    fn len(&self) -> usize {
        match self {
            Wide::Big(_, b) => b.len(),
            Wide::Oct(b) => b.len(),
        }
    }
}

/// `B̂ᵢ / C(n, i)` at `bits` bits, each rounded to double-double ([`big_to_dd`]).
fn big_bernstein_to_dd(n: usize, bits: usize, big: &[BigFloat]) -> Option<SmallVec<[Dd; 64]>> {
    // C(n, i) exactly: every intermediate C(n, i − 1)·(n − i + 1) < 2^(n + 64).
    let exact_bits = (n + 128).div_ceil(64) * 64;
    let mut binom = big_from_f64(1.0);
    let mut b = SmallVec::with_capacity(n + 1);
    for (i, bi) in big.iter().enumerate() {
        if i > 0 {
            binom = binom
                .mul(&big_from_f64((n - i + 1) as f64), exact_bits, RM)
                .div(&big_from_f64(i as f64), exact_bits, RM);
        }
        b.push(big_to_dd(&bi.div(&binom, bits, RM))?);
    }
    Some(b)
}

/// Degrees whose binomial coefficients the octuple tier computes exactly: every intermediate
/// `C(n, i − 1)·(n − i + 1)` of the recurrence stays below `2^237` up to `n = 200` (`C(200,
/// 100) < 2^196`).
const OCT_EXACT_BINOMIAL_DEGREE: usize = 200;

/// `B̂ᵢ / C(n, i)` in `binary256` (one rounding), each to double-double ([`oct_to_dd`]).
fn oct_bernstein_to_dd(n: usize, coeffs: &[f256]) -> Option<SmallVec<[Dd; 64]>> {
    if n > OCT_EXACT_BINOMIAL_DEGREE {
        return None;
    }
    let mut binom = oct(1.0);
    let mut b = SmallVec::with_capacity(n + 1);
    for (i, bi) in coeffs.iter().enumerate() {
        if i > 0 {
            // Exact: an integer below 2^237 (OCT_EXACT_BINOMIAL_DEGREE), then an exact quotient.
            binom = binom * oct((n - i + 1) as f64) / oct(i as f64);
        }
        b.push(oct_to_dd(*bi / binom)?);
    }
    Some(b)
}

/// `v` rounded to a double-double within `2^-104·|v|` (plus underflow, counted by the caller as
/// [`DD_UNDERFLOW`]): the top 128 bits of the mantissa, the upper word rounded to `f64` and
/// the exact remainder rounded to `f64`. `None` outside `f64`'s exponent range.
fn big_to_dd(v: &BigFloat) -> Option<Dd> {
    if v.is_zero() {
        return Some(Dd::from_f64(0.0));
    }
    // astro-float: |v| = (m_top·2^64 + m_next + …)·2^(e − 128), words least significant first.
    let (m, _, sign, e, _) = v.as_raw_parts()?;
    let top = *m.last()?;
    let next = if m.len() >= 2 { m[m.len() - 2] } else { 0 };
    let scale_exp = e - 64;
    if !(-900..=900).contains(&scale_exp) {
        return None;
    }
    let hi = top as f64;
    // hi ≤ 2^64 is an integer, so the remainder is exact in i128 (|rem| ≤ 2^75).
    let whole = (u128::from(top) << 64) | u128::from(next);
    let rem = whole as i128 - ((hi as u128) << 64) as i128;
    let lo = rem as f64 * 2f64.powi(-64);
    let scale = 2f64.powi(scale_exp);
    let (h, l) = two_sum(hi * scale, lo * scale);
    Some(if sign == astro_float::Sign::Neg {
        Dd::from_pair(-h, -l)
    } else {
        Dd::from_pair(h, l)
    })
}

/// A point strictly inside `(x, y)` with a certified sign at some tier from `tier` up: the
/// midpoint, else one of [`SPLIT_FRACTIONS`]. `None` when no such `f64` point exists or none
/// is decided at [`MAX_BITS`].
fn split_point(c: &[f64], x: f64, y: f64, tier: Tier, depth: u32) -> Option<(f64, i8, Tier)> {
    let mid = binade_mid(x, y, depth).unwrap_or(0.5 * x + 0.5 * y);
    std::iter::once(mid)
        .chain(SPLIT_FRACTIONS.iter().map(|f| x + (y - x) * f))
        .filter(|&m| m > x && m < y)
        .find_map(|m| {
            let (s, t) = point_sign(c, m, tier);
            (s != 0).then_some((m, s, t))
        })
}

/// Binades (powers of two) a node `(x, y]` with `0 < x < y` must span before it is split at
/// the geometric rather than the arithmetic midpoint.
const WIDE_SPAN_BINADES: i32 = 8;

/// The binade of `y` above which a node `(0, y]` is split at `2^(e/2)` (`e` the exponent of
/// `y`) rather than at `y/2`. Nodes from 0 to a moderate `y` — the tracer's and the usual
/// queries' — keep the arithmetic midpoint until [`DEEP_FROM_ZERO`] halvings: a geometric
/// one at once would first descend towards `2^-1074` (it cost the planted bench 60 % more
/// instructions when tried).
const WIDE_FROM_ZERO_BINADE: i32 = 64;

/// Bisection depth from which a node `(0, y]` is split at the geometric midpoint of
/// `2^-1074` and `y`: a root far below `y` (`1e-62` in `(0, 10]`) is then reached in about
/// ten more levels instead of two hundred (past [`MAX_DEPTH`]).
const DEEP_FROM_ZERO: u32 = 16;

/// For a very wide node on one side of 0 (see [`WIDE_SPAN_BINADES`] and
/// [`WIDE_FROM_ZERO_BINADE`]), a power of two halfway between the exponents of its ends. Why:
/// arithmetic halving of `(0, 1e300]` needs about a thousand levels to reach a root near 1,
/// far past [`MAX_DEPTH`], so such nodes were left to exact isolation (seconds per query at
/// degree 33, issue 13 follow-up); halving the exponent range needs about ten.
fn binade_mid(x: f64, y: f64, depth: u32) -> Option<f64> {
    let (lo, hi, sign) = if x >= 0.0 {
        (x, y, 1.0)
    } else if y <= 0.0 {
        (-y, -x, -1.0)
    } else {
        return None;
    };
    let exponent = |v: f64| v.log2().floor() as i32;
    let e_hi = exponent(hi);
    let e = if lo == 0.0 {
        if e_hi > WIDE_FROM_ZERO_BINADE {
            e_hi / 2
        } else if depth >= DEEP_FROM_ZERO {
            (e_hi - 1074) / 2
        } else {
            return None;
        }
    } else {
        let e_lo = exponent(lo);
        if e_hi - e_lo <= WIDE_SPAN_BINADES {
            return None;
        }
        e_lo + (e_hi - e_lo) / 2
    };
    let m = if e >= -1022 {
        f64::from_bits(((e + 1023) as u64) << 52)
    } else {
        f64::from_bits(1u64 << (e + 1074))
    };
    (m > lo && m < hi).then_some(sign * m)
}

// ---------------------------------------------------------------------------------------
// Refinement.

/// Refinement in adaptive precision of a bracket on which the `f64` refinement got stuck,
/// to the tolerance `tol` (or adjacent `f64` numbers): the Illinois loop of `refine.rs`
/// ([`illinois_by`]) with signs certified at the tiers of [`point_sign`] and approximate
/// values from the same evaluations placing the trial points. Why not bisection: a bracket
/// from isolation is ~`10⁻⁴` wide and needs ~30 halvings to `10⁻¹²`, each a wide Horner
/// evaluation; regula falsi converges superlinearly on the simple roots these brackets hold
/// (Chebyshev T₈₀: 63 % of the query's instructions were this bisection). A trial point no
/// tier can sign costs one bisection step at [`split_point`]'s alternatives. `None` when
/// some midpoint and its neighbours cannot be signed even at [`MAX_BITS`] (then the caller
/// refines exactly). Counts [`RootStats::adaptive_refines`].
///
/// # Accuracy
/// The bracket keeps certified opposite end signs, so the root stays inside; the value
/// returned is within `tol.on(lo, hi)` of the root, as [`illinois_by`] promises.
pub(crate) fn refine_wide(
    c: &[f64],
    b: Bracket,
    tol: Tolerance,
    stats: &mut RootStats,
) -> Option<f64> {
    stats.adaptive_refines += 1;
    let mut tier = Tier::Dd;
    let mut b = b;
    loop {
        // Values at the ends, for the first trial point (their signs are certified already).
        stats.refine_evals += 2;
        b.f_lo = point_sign_value(c, b.lo, tier).2;
        b.f_hi = point_sign_value(c, b.hi, tier).2;
        let eval = |x: f64| {
            let (s, t, v) = point_sign_value(c, x, tier);
            tier = tier.max(t);
            (v, s)
        };
        let bracket = match illinois_by(b, tol, stats, eval) {
            IllinoisEnd::Root(r) => return Some(r),
            // Regula falsi converges *onto* a root: when no tier signs the trial point, it
            // is often the root itself, exact in f64 (Vieta-built polynomials). Signs at
            // `x ± δ` (its neighbours when δ is below a spacing) settle it as in the f64
            // refinement; else one exact evaluation tells (the bracket holds one distinct
            // root, so a zero is that root).
            IllinoisEnd::Undecided {
                bracket, x, delta, ..
            } => {
                stats.refine_evals += 2;
                let probed = probe_by(bracket, x, delta, |y| point_sign(c, y, tier).0);
                if let Some(r) = probed.or_else(|| is_exact_root(c, x).then_some(x)) {
                    return Some(r);
                }
                bracket
            }
            IllinoisEnd::Exhausted(bracket) => bracket,
        };
        let Bracket { lo, hi, s_lo, .. } = bracket;
        let Some((m, s, t)) = split_point(c, lo, hi, tier, 0) else {
            // No point is signed even at MAX_BITS: the midpoint may be the root itself (a
            // stored polynomial with an exact f64 root, as Vieta's products of f64 roots
            // have). One exact evaluation there (n rational operations, no Sturm sequence)
            // tells; the bracket holds one distinct root, so a zero is that root.
            let mid = lo + 0.5 * (hi - lo);
            return (mid > lo && mid < hi && is_exact_root(c, mid)).then_some(mid);
        };
        stats.refine_evals += 1;
        tier = t;
        b = if s == s_lo {
            Bracket::new(m, hi, s_lo)
        } else {
            Bracket::new(lo, m, s_lo)
        };
    }
}

/// Whether `p(x) = 0` exactly (Horner's rule in rationals on the stored coefficients).
fn is_exact_root(c: &[f64], x: f64) -> bool {
    let (Some(xr), Some(poly)) = (rat_from_f64(x), Poly::new(c.to_vec()).to_rat()) else {
        return false;
    };
    poly.eval(&xr).is_zero()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scalar::{Rat, rat_from_f64};
    use crate::univariate::Poly;
    use num_traits::Signed;

    /// `big_to_dd` keeps `2^-104` relative accuracy: wide values that are not double-doubles
    /// (products of `f64` at 256 bits, thirds), of both signs, across the exponent range it
    /// accepts, come back within `2^-104·|v|` (checked in the wide format).
    #[test]
    fn wide_values_round_to_double_double_within_their_bound() {
        let third = big_from_f64(1.0).div(&big_from_f64(3.0), 256, RM);
        for (k, scale) in [
            1.0,
            -1.0,
            7.5e250,
            -3.3e-250,
            2f64.powi(63),
            1.0 - f64::EPSILON / 4.0,
        ]
        .into_iter()
        .enumerate()
        {
            for factor in [
                third.clone(),
                big_from_f64(0.1).mul(&big_from_f64(1.0 / 7.0), 256, RM),
            ] {
                let v = factor.mul(&big_from_f64(scale), 256, RM);
                let d = big_to_dd(&v).expect("in range");
                let back = big_from_f64(d.hi).add(&big_from_f64(d.lo), EXACT_PAIR_BITS, RM);
                let err = back.sub(&v, 512, RM).abs();
                let allowed = v.abs().mul(&big_from_f64(2f64.powi(-104)), 512, RM);
                assert!(err.sub(&allowed, 512, RM).is_negative(), "case {k}: {v}");
            }
        }
        assert_eq!(big_to_dd(&big_from_f64(0.0)), Some(Dd::from_f64(0.0)));
        assert!(big_to_dd(&big_from_f64(1e300).mul(&big_from_f64(1e300), 256, RM)).is_none());
    }

    /// The octuple tier (session 16) signs T₈₀ 1e-9 away from its roots near ±1, where
    /// double-double's bound cannot (about `γ(160)·Σ|cᵢ| ≈ 160·2^-103·2^100.7 ≈ 30`, against
    /// `|T₈₀| ≈ 80²·10⁻⁹ ≈ 6·10⁻⁶` there), and its signs are the exact ones.
    #[test]
    fn octuple_tier_signs_chebyshev_80_where_double_double_cannot() {
        let t = crate::testutil::chebyshev(80);
        let c = t.to_f64();
        assert_eq!(c.to_rat().as_ref(), Some(&t), "coefficients exact in f64");
        let c = c.coeffs();
        let (mut points, mut dd_undecided) = (0, 0);
        for r in crate::testutil::chebyshev_roots(80)
            .into_iter()
            .filter(|r| r.abs() > 0.9)
        {
            for x in [r - 1e-9, r + 1e-9] {
                let v = t.eval(&rat_from_f64(x).expect("finite"));
                let exact = if v.is_positive() { 1 } else { -1 };
                let (dd, _) = horner_sign(&DdArith, c, x);
                let octuple = Oct::default();
                let (o, approx) = horner_sign(&octuple, c, x);
                assert!(octuple.clean());
                assert_eq!(o, exact, "octuple sign at {x}");
                assert!(dd == 0 || dd == exact, "double-double sign at {x}");
                // The approximate value is T₈₀'s own to many digits.
                let want = crate::scalar::rat_to_f64(&v);
                assert!(
                    (approx - want).abs() <= 1e-6 * want.abs(),
                    "{approx} vs {want}"
                );
                points += 1;
                dd_undecided += usize::from(dd == 0);
            }
        }
        assert!(points >= 20, "{points} points");
        assert_eq!(dd_undecided, points, "double-double decides none of them");
    }

    /// Issue 11: Chebyshev `T₈₀`'s power-basis coefficients reach `2⁷⁹`, so near ±1 its
    /// nodes need a tier above double-double (the octuple one since session 16); the
    /// descent hands each split node's subtree to double-double. Every root is certified in its bracket (the exact roots
    /// `cos((2k − 1)π/160)`, all coefficients being exact in `f64`), and the wide tier
    /// classifies a handful of nodes, not one per node of the tree (fails if the descent is
    /// removed: each of the pieces' nodes is then classified wide). Then each bracket is
    /// refined in adaptive precision with a few certified signs per root.
    #[test]
    fn chebyshev_80_descends_from_the_wide_tier_and_refines_by_regula_falsi() {
        let n = 80;
        let t = crate::testutil::chebyshev(n);
        let c = t.to_f64();
        assert_eq!(c.to_rat().as_ref(), Some(&t), "coefficients exact in f64");
        let c = c.coeffs();
        let mut stats = RootStats::default();
        let (mut brackets, mut wide_nodes) = (Vec::new(), 0);
        // The two sides of 0 separately, as the certified driver's pieces are.
        for (lo, hi) in [(-1.5, -0.25), (0.25, 1.5)] {
            let s = |x: f64| point_sign(c, x, Tier::Dd).0;
            let mut piece = PieceIsolator::new(c, (lo, hi), (s(lo), s(hi)), &mut stats);
            while let Some(outcome) = piece.next(&mut stats) {
                match outcome {
                    Outcome::Bracket(b) => brackets.push(b),
                    Outcome::Undecided(x, y) => panic!("undecided ({x}, {y}]"),
                }
            }
            wide_nodes += piece.wide_nodes;
        }
        let want: Vec<f64> = crate::testutil::chebyshev_roots(n)
            .into_iter()
            .filter(|r| r.abs() > 0.25)
            .collect();
        assert_eq!(brackets.len(), want.len());
        for (b, r) in brackets.iter().zip(&want) {
            // The f64 root is within 2 ulp of the exact cos((2k − 1)π/160).
            let slack = 4.0 * f64::EPSILON;
            assert!(
                b.lo - slack <= *r && *r <= b.hi + slack,
                "{r} outside {b:?}"
            );
        }
        assert!(stats.multiprecision_pieces >= 1, "{stats:?}");
        assert!(
            wide_nodes <= 8,
            "{wide_nodes} nodes classified at a wide tier"
        );

        // Refinement in adaptive precision (issue 11): regula falsi on these simple roots,
        // not bisection (which needs ~30 signs per root from these brackets to 1e-12).
        let tol = Tolerance::absolute(1e-12);
        let mut refine = RootStats::default();
        for (b, r) in brackets.iter().zip(&want) {
            let got = refine_wide(c, *b, tol, &mut refine).expect("refined");
            assert!(
                (got - r).abs() <= 1e-12 + 4.0 * f64::EPSILON,
                "{got} vs {r}"
            );
        }
        let per_root = refine.refine_evals as f64 / brackets.len() as f64;
        assert!(per_root <= 12.0, "{per_root} signs per root");
    }

    /// The right-sized precision of a node width (issue 11) still holds `hi + lo` exactly:
    /// equal to the sum formed at [`EXACT_PAIR_BITS`], which holds any two `f64`, across
    /// exponent gaps of 0 to 2 098 binades, a carry out of `hi`'s leading bit, subnormal
    /// parts and `|lo| > |hi|`.
    #[test]
    fn node_width_pairs_convert_exactly_at_their_own_precision() {
        let two_pow = |e: i32| 2f64.powi(e);
        let mut pairs = vec![
            (1.0, 1e-17),
            (2.0f64.next_down(), two_pow(-53).next_down()),
            (1.0 + f64::EPSILON, -3.0 * two_pow(-60)),
            (two_pow(1000), 5e-324),
            (-3.0, 7.0 * 5e-324),
            (1e300, -1e-300),
            (f64::MAX, -5e-324),
            (5e-324, 1e-323),
            (1e-300, 1e300),
            (0.1, 0.0),
        ];
        for k in 0..200 {
            let (a, b) = (1.0 + k as f64 / 7.0, -(k as f64).exp2() / 3.0);
            let (hi, lo) = two_sum(a, b);
            pairs.push((hi, lo));
        }
        let ar = BigArith { bits: 256 };
        for (hi, lo) in pairs {
            let sized = ar
                .exact_pair(hi, lo)
                .expect("the astro-float tier holds any pair");
            let full = big_from_f64(hi).add(&big_from_f64(lo), EXACT_PAIR_BITS, RM);
            let diff = sized.sub(&full, EXACT_PAIR_BITS, RM);
            assert!(
                diff.is_zero(),
                "{hi:e} + {lo:e} at {} bits",
                exact_pair_bits(hi, lo)
            );
        }
    }

    /// Issue 13 follow-up: astro-float's `BigFloat::from_f64` halves subnormals, which made
    /// the certified path return the roots of `1.877e-308·x² − 3.83` `√2` too large. The
    /// conversion used here is exact: a subnormal times `2^600` (exact in `f64`, a normal
    /// number) equals its conversion times `2^600` in the wide format.
    #[test]
    fn subnormal_f64_converts_to_bigfloat_exactly() {
        let lift = 2f64.powi(600);
        for x in [
            5e-324,
            -5e-324,
            1.877_230_785_675_903_7e-308,
            f64::MIN_POSITIVE.next_down(),
            -3.1e-320,
            f64::MIN_POSITIVE,
            1.5,
        ] {
            let wide = big_from_f64(x).mul(&big_from_f64(lift), 256, RM);
            assert_eq!(wide, big_from_f64(x * lift), "{x:e}·2^600");
        }
    }

    /// `|computed − exact| ≤ bound` for the double-double operations on awkward operands.
    #[test]
    fn double_double_operations_meet_their_error_bounds() {
        let r = |d: Dd| rat_from_f64(d.hi).unwrap() + rat_from_f64(d.lo).unwrap();
        let xs = [
            Dd::from_f64(1.0).add_f(1e-17),
            Dd::from_f64(-3.0).add_f(2f64.powi(-60)),
            Dd::from_f64(0.1).mul_f(3.0),
            Dd::from_f64(7.0e30).add_f(-1.3e14),
        ];
        for x in xs {
            for y in xs {
                let exact = r(x) * r(y);
                let got = r(x.mul(y));
                let bound = exact.abs() * rat_from_f64(DD_UNIT).unwrap();
                assert!((got - &exact).abs() <= bound, "mul {x:?} {y:?}");
                let exact = r(x) + r(y);
                let got = r(x.add(y));
                let bound = exact.abs() * rat_from_f64(DD_UNIT).unwrap();
                assert!((got - &exact).abs() <= bound, "add {x:?} {y:?}");
            }
        }
    }

    /// The wide Bernstein coefficients are within their bound of the exact ones, at every
    /// tier: the bound is what makes each certified sign true.
    #[test]
    fn wide_bernstein_signs_agree_with_exact_coefficients() {
        let p = Poly::<f64>::from_roots(&[0.1, 0.2, 0.2000001, 0.9, -0.4]);
        let c = p.coeffs();
        let q = p.to_rat().unwrap();
        for (x, y) in [(0.15, 0.25), (-0.5, -0.3), (0.0, 0.19)] {
            let (xr, yr) = (rat_from_f64(x).unwrap(), rat_from_f64(y).unwrap());
            let shifted = q.compose_affine(&xr, &(&yr - &xr));
            let n = c.len() - 1;
            // Exact B_i = Σ_j C(n−j, i−j) q_j (orientation from x).
            let binom = |n: usize, k: usize| -> Rat {
                (0..k).fold(Rat::from_integer(1.into()), |acc, j| {
                    acc * Rat::from_integer(((n - j) as i64).into())
                        / Rat::from_integer(((j + 1) as i64).into())
                })
            };
            let exact: Vec<Rat> = (0..=n)
                .map(|i| {
                    (0..=i).fold(Rat::from_integer(0.into()), |s, j| {
                        s + binom(n - j, i - j) * shifted.coeff(j)
                    })
                })
                .collect();
            let sx = q.eval(&xr).signum();
            let sy = q.eval(&yr).signum();
            let s = (
                sx.to_integer().try_into().unwrap(),
                sy.to_integer().try_into().unwrap(),
            );
            let mut changes = 0;
            for i in 1..=n {
                changes += usize::from(exact[i].is_positive() != exact[i - 1].is_positive());
            }
            for tier in [Tier::Dd, Tier::Oct, Tier::Big(256)] {
                let mut sc = Scratch::default();
                let class = classify_at(tier, c, (x, y), s, &mut sc);
                match class {
                    Class::Empty => assert_eq!(changes, 0, "({x}, {y}] {tier:?}"),
                    Class::One => assert_eq!(changes, 1, "({x}, {y}] {tier:?}"),
                    Class::Split | Class::Hopeless => {
                        assert!(
                            changes >= 2,
                            "({x}, {y}] {tier:?}: {class:?} with {changes}"
                        )
                    }
                }
            }
        }
    }

    use crate::root_options::RootOptions;
    use crate::testutil::{planted, rat, wilkinson};
    use proptest::prelude::*;
    use rand::{Rng, SeedableRng};
    use rand_chacha::ChaCha8Rng;

    /// The distinct roots of the stored polynomial in `(lo, hi]` by exact Sturm isolation
    /// (the oracle), correctly rounded to `f64`. (It was refined to `2^-90` relative to the
    /// range's scale, 4e-28 off for the root `2^-47` of a random cluster, 250 ulps: the
    /// certified answer, exactly `2^-47`, failed against it.)
    fn oracle(p: &Poly<f64>, lo: f64, hi: f64) -> Vec<f64> {
        let q = p.to_rat().unwrap();
        let (a, b) = (rat_from_f64(lo).unwrap(), rat_from_f64(hi).unwrap());
        q.real_roots(&a, &b, 0.0).unwrap()
    }

    /// Every root of the oracle is found within `x_tol` (or one `f64` spacing), none is
    /// added, and the smallest-root query agrees.
    fn check_all(p: &Poly<f64>, lo: f64, hi: f64, x_tol: f64, stats: &mut RootStats) {
        let opts = RootOptions::new(x_tol);
        let got = p.real_roots_with(lo, hi, &opts, stats).unwrap();
        let want = oracle(p, lo, hi);
        assert_eq!(
            got.len(),
            want.len(),
            "{p:?} on ({lo}, {hi}]: {got:?} vs {want:?}"
        );
        for (g, w) in got.iter().zip(&want) {
            let allowed = x_tol.max(2.0 * f64::EPSILON * w.abs()) + f64::from_bits(1);
            assert!((g - w).abs() <= allowed, "{p:?}: {g:e} vs {w:e}");
        }
        let first = p.smallest_root_with(lo, hi, &opts, stats);
        match (first, want.first()) {
            (None, None) => {}
            (Some(g), Some(w)) => {
                let allowed = x_tol.max(2.0 * f64::EPSILON * w.abs()) + f64::from_bits(1);
                assert!((g - w).abs() <= allowed, "{p:?}: smallest {g:e} vs {w:e}");
            }
            (g, w) => panic!("{p:?}: smallest {g:?} vs {w:?}"),
        }
    }

    /// The product of `(x − rᵢ)` when every coefficient is exact in `f64` (dyadic roots with
    /// few bits), else `None`.
    fn exact_product(roots: &[f64]) -> Option<Poly<f64>> {
        let rs: Vec<Rat> = roots.iter().map(|&r| rat_from_f64(r).unwrap()).collect();
        let q = crate::univariate::QPoly::from_roots(&rs);
        let p = q.to_f64();
        (p.to_rat()? == q).then_some(p)
    }

    /// Kac polynomial: independent standard normal coefficients (Box–Muller, seeded).
    fn kac(d: usize, seed: u64) -> Poly<f64> {
        let mut rng = ChaCha8Rng::seed_from_u64(seed);
        let c = (0..=d)
            .map(|_| {
                let (u, v): (f64, f64) = (rng.r#gen::<f64>().max(1e-300), rng.r#gen());
                (-2.0 * u.ln()).sqrt() * (std::f64::consts::TAU * v).cos()
            })
            .collect();
        Poly::new(c)
    }

    /// Wilkinson-20 and Kac polynomials of degree 20 used to need exact Sturm counts on
    /// pieces (`docs/stability.md`: Wilkinson-20 ~0.7 ms, Kac-20 "fallback 0.8 ms"): now
    /// the adaptive tiers decide them and no exact arithmetic runs.
    #[test]
    fn wilkinson_and_kac_take_the_adaptive_path_not_the_exact_one() {
        let mut stats = RootStats::default();
        let w = wilkinson(20).to_f64();
        check_all(&w, 0.0, 21.0, 1e-10, &mut stats);
        assert_eq!(
            w.subdivision_root_count(0.0, 21.0, &mut stats),
            20,
            "subdivision isolates the 20 roots"
        );
        assert!(
            stats.adaptive_pieces > 0,
            "Wilkinson-20 went adaptive: {stats:?}"
        );
        assert_eq!(
            (stats.exact_fallbacks, stats.refine_fallbacks),
            (0, 0),
            "Wilkinson-20: no exact arithmetic"
        );
        let mut stats = RootStats::default();
        for seed in 0..12 {
            let p = kac(20, seed);
            let b = p.root_bound().unwrap();
            check_all(&p, -b, b, 1e-12, &mut stats);
            let mut truth = RootStats::default();
            let want = p
                .real_roots_with(-b, b, &RootOptions::new(1e-12), &mut truth)
                .unwrap()
                .len();
            assert_eq!(
                p.subdivision_root_count(-b, b, &mut stats),
                want,
                "Kac-20 seed {seed}: subdivision agrees"
            );
        }
        assert!(
            stats.adaptive_pieces > 0,
            "some Kac-20 went adaptive: {stats:?}"
        );
        assert_eq!(
            (stats.exact_fallbacks, stats.refine_fallbacks),
            (0, 0),
            "Kac-20: no exact arithmetic"
        );
    }

    /// Two roots `2^-50 ≈ 8.9e-16` apart (closer than 1e-15) in a polynomial whose stored
    /// coefficients are exact: double-double cannot separate them at this scale, the
    /// arbitrary-precision tier does; no exact arithmetic.
    #[test]
    fn cluster_closer_than_1e_15_is_separated_in_multiprecision() {
        let eps = 2f64.powi(-50);
        let p = exact_product(&[1.0, 1.0 + eps, -2.0]).expect("exact coefficients");
        let mut stats = RootStats::default();
        check_all(&p, -3.0, 4.0, 0.0, &mut stats);
        assert_eq!(oracle(&p, -3.0, 4.0).len(), 3, "three distinct roots");
        assert!(stats.adaptive_pieces > 0, "{stats:?}");
        assert_eq!(stats.exact_fallbacks, 0, "decided without exact isolation");
    }

    /// A genuine double root of the stored polynomial: no precision isolates it by
    /// Descartes' rule, so its tiny piece (one `f64` spacing) is decided exactly, once per
    /// query, and the answer is still right.
    #[test]
    fn multiple_root_terminates_with_the_right_answer() {
        let p = exact_product(&[0.5, 0.5, 0.25, -1.5]).expect("exact coefficients");
        let mut stats = RootStats::default();
        check_all(&p, -2.0, 2.0, 1e-12, &mut stats);
        // The all-roots query is answered by the inclusion discs (the double root 0.5 is
        // exact in f64, its cluster certifies it); the subdivision meets it alone.
        assert_eq!(p.subdivision_root_count(-2.0, 2.0, &mut stats), 3);
        assert!(stats.adaptive_pieces > 0, "{stats:?}");
        assert!(
            stats.exact_fallbacks <= 2,
            "at most one exact sequence per query: {stats:?}"
        );
    }

    /// `x = 2^s·y` scales the coefficients by `2^(s·i)` exactly: the same roots scaled, with
    /// coefficients spanning up to `2^±900`.
    #[test]
    fn wide_coefficient_ranges_are_certified() {
        let base = planted(&[rat(1, 3), rat(2, 7), rat(-5, 11), rat(9, 10), rat(3, 8)]).to_f64();
        let mut stats = RootStats::default();
        for s in [-180, -60, 60, 180] {
            let c: Vec<f64> = base
                .coeffs()
                .iter()
                .enumerate()
                .map(|(i, &c)| c * 2f64.powi(-s * i as i32))
                .collect();
            let p = Poly::new(c);
            let r = 2f64.powi(s);
            check_all(&p, -2.0 * r, 2.0 * r, 0.0, &mut stats);
        }
    }

    /// Kac polynomials of degree 60 and 100 (the Bernstein run's `Vec` storage and wide
    /// Taylor shifts) against the oracle.
    #[test]
    fn high_degree_kac_matches_the_oracle() {
        let mut stats = RootStats::default();
        for (d, seed) in [(60, 3), (100, 4)] {
            let p = kac(d, seed);
            check_all(&p, -3.0, 3.0, 1e-12, &mut stats);
        }
    }

    /// Orellana–De Michele's case 1, `(x − 1)(x − 1e3)(x − 1e6)(x − 1e9)` by Vieta's
    /// formulas: the stored coefficients are exact, so every root is an exact `f64` where no
    /// precision can sign `p`. With `x_tol = 0` the refinement used to finish each root with
    /// the exact Sturm sequence; one exact evaluation at the root now suffices.
    #[test]
    fn exact_f64_roots_refine_to_full_precision_without_a_sturm_sequence() {
        let p = exact_product(&[1.0, 1e3, 1e6, 1e9]).expect("exact coefficients");
        let mut stats = RootStats::default();
        check_all(&p, -2.0, 2e9, 0.0, &mut stats);
        let roots = p.real_roots(-2.0, 2e9, 0.0).unwrap();
        assert_eq!(roots, vec![1.0, 1e3, 1e6, 1e9], "each root exactly");
        assert_eq!(
            (stats.exact_fallbacks, stats.refine_fallbacks),
            (0, 0),
            "no exact sequence: {stats:?}"
        );
    }

    /// Regression (issue 11, degree growth): `x^160 − 2^872`, roots `±2^(109/20) ≈ ±43.71`.
    /// There the bound `C(160, i)·Σ|cᵢ||x|ⁱ` exceeds `f64`'s range while every value is
    /// finite: the double-double tier classified nodes as "split" forever (4 096 nodes) and
    /// the piece went to exact Sturm (6.8 s in release; a Kac polynomial of degree 160 took
    /// a minute). Such nodes now go up to the wide tiers, whose bounds have no such limit.
    #[test]
    fn degree_160_roots_where_the_f64_bound_overflows_stay_off_the_exact_path() {
        let mut c = vec![0.0; 161];
        c[0] = -(2f64.powi(872));
        c[160] = 1.0;
        let p = Poly::new(c);
        for (lo, hi) in [(-64.0, 64.0), (-256.0, 256.0)] {
            // On (−256, 256] the end values (≈ 2^1280) themselves leave f64's range, and
            // no tier could sign the ends before the wide magnitude.
            let mut stats = RootStats::default();
            let roots = p
                .real_roots_with(lo, hi, &RootOptions::new(1e-12), &mut stats)
                .unwrap();
            // 2^(109/20) to 30 digits (mpmath): 43.7132882161406566032393579293.
            let r = 43.713_288_216_140_66;
            assert_eq!(roots.len(), 2, "two real roots on ({lo}, {hi}]: {roots:?}");
            assert!(
                (roots[0] + r).abs() <= 1e-12 && (roots[1] - r).abs() <= 1e-12,
                "{roots:?}"
            );
            assert_eq!(
                p.subdivision_root_count(lo, hi, &mut stats),
                2,
                "subdivision isolates both roots on ({lo}, {hi}]"
            );
            assert_eq!(stats.exact_fallbacks, 0, "no exact sequence: {stats:?}");
            assert!(
                stats.multiprecision_pieces > 0,
                "the wide tiers decided: {stats:?}"
            );
        }
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(24))]

        /// Random clusters: roots `c`, `c + k·2^-e` (e up to 56, so down to 1.4e-17 apart
        /// relative), with two further roots, as exact dyadic products when they fit.
        #[test]
        fn random_clusters_match_the_oracle(
            c in -64i32..64, k in 1i32..8, e in 30i32..57, r3 in -32i32..32, r4 in -32i32..32
        ) {
            let c = f64::from(c) / 16.0;
            let roots = [c, c + f64::from(k) * 2f64.powi(-e), f64::from(r3) / 8.0, f64::from(r4) / 4.0];
            if let Some(p) = exact_product(&roots) {
                let mut stats = RootStats::default();
                check_all(&p, -10.0, 10.0, 0.0, &mut stats);
            }
        }
    }
}

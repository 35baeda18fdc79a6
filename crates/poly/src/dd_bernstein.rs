//! [`DdBernstein`]: Descartes' rule in the Bernstein basis in double-double arithmetic, with
//! de Casteljau halving — the first, cheap attempt on a piece that `f64` could not decide.
//!
//! The piece `[x, y]` (`f64` ends with certified signs, on one side of 0) gets its Bernstein
//! coefficients once, from the stored coefficients: a Taylor shift to the end `e` nearer 0
//! (Horner's rule on polynomials, `2n` roundings on any path), the scaling `q_j = r_j·wʲ` by
//! the exact width `w` (a TwoSum pair, at most `n` roundings), the division by `C(n, j)` (one)
//! and `n` passes of neighbour sums (`n`): `k₀ = 4n + 1` roundings. Each de Casteljau halving
//! adds `n` (the halving itself is exact). With `M = Σ|cₖ|·max(|x|, |y|)ᵏ` every computed
//! coefficient of every node is within `γ(k)·M` of the exact Bernstein coefficient of the stored
//! polynomial on the exact sub-interval, by the argument of `bernstein.rs` (the absolute-value
//! program computes Bernstein coefficients of a polynomial with non-negative power
//! coefficients, each at most its value at 1, which is `M`; averages never exceed their
//! inputs), with `γ` of the double-double unit [`DD_UNIT`].
//!
//! Against the fresh Taylor shift per node of `multiprec.rs` (`O(n²)` double-double products
//! per node), a node costs `n(n + 1)/2` double-double additions. Anything this run cannot
//! decide — a node whose coefficients are all within their bound, a node too deep or too
//! narrow for `f64` bracket ends, a bracket end whose sign disagrees — ends the run with a
//! [`DdOutcome::Handoff`] of the rest of the piece, which the caller gives to the per-node
//! tiers of `multiprec.rs`. See `paper-notes/isolation.md`, "Double-double de Casteljau".

use smallvec::SmallVec;

use crate::bernstein::Bracket;
use crate::double_double::{
    DD_MIN_EXACT, DD_UNDERFLOW, DD_UNIT, Dd, gamma_u, taylor_shift_into, two_sum,
};
use crate::eval_bound::{abs_weights, chain_underflow_weight};
use crate::stats::RootStats;

/// Highest degree handled: `C(n, j)` must be exact in `f64` (`C(56, 28) < 2^53`).
pub(crate) const MAX_DEGREE: usize = 56;

/// Deepest halving: the node ends `u` are dyadic with at most this many bits, so they and
/// their midpoints stay exact in `f64`; deeper nodes go to the per-node tiers (which split
/// at `f64` points).
const MAX_DEPTH: u32 = 52;

/// Most nodes of one run before the rest of the piece is handed off.
const MAX_NODES: u32 = 2048;

/// One result of [`DdBernstein::next`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) enum DdOutcome {
    /// A certified bracket holding exactly one simple root.
    Bracket(Bracket),
    /// Everything up to `t_a` is answered; `(t_a, y]` (certified sign `s_a` at `t_a`) is
    /// left to the caller.
    Handoff { t_a: f64, s_a: i8 },
}

/// A node: the dyadic sub-interval `[u0, u1]` of `[0, 1]` (`t = x + (y − x)·u`), its depth,
/// and where its `n + 1` coefficients start in the arena.
#[derive(Clone, Copy, Debug)]
struct Node {
    u0: f64,
    u1: f64,
    depth: u32,
    at: usize,
}

/// The de Casteljau run on one piece (see the module docs). [`next`](Self::next) yields the
/// outcomes left to right.
pub(crate) struct DdBernstein<'c> {
    c: &'c [f64],
    n: usize,
    x: f64,
    y: f64,
    s_x: i8,
    s_y: i8,
    /// `y − x` exactly.
    d: Dd,
    /// `M` rounded up (see the module docs).
    mag: f64,
    /// Roundings on any path to the top node's coefficients (`4n + 1` from the Taylor shift,
    /// 0 for coefficients handed down by [`Self::from_bernstein`]).
    k0: usize,
    /// Absolute error of the top node's coefficients that the run did not make itself (0, or
    /// the bound handed down with them).
    e0: f64,
    /// Absolute underflow allowance of the top node; each level adds [`Self::level_tiny`].
    tiny0: f64,
    level_tiny: f64,
    /// Coefficients of the nodes on the stack, in stack order.
    arena: SmallVec<[Dd; 64]>,
    stack: SmallVec<[Node; 24]>,
    nodes: u32,
    /// The end of the last bracket (or `x`) and the certified sign there.
    floor: (f64, i8),
    /// A certified sign of `p` at a point, 0 when undecided (`multiprec`'s tiers).
    sign_at: fn(&[f64], f64) -> i8,
}

impl<'c> DdBernstein<'c> {
    /// Sets up the run on `(x, y]` (`x < y`, finite, both `≥ 0` or both `≤ 0`) with the
    /// certified non-zero signs `s_x`, `s_y`; `sign_at` certifies the signs of bracket ends
    /// (0 when it cannot). `None` for a degree outside `2..=`[`MAX_DEGREE`]
    /// or when the magnitude bound overflows.
    pub(crate) fn new(
        c: &'c [f64],
        (x, y): (f64, f64),
        (s_x, s_y): (i8, i8),
        sign_at: fn(&[f64], f64) -> i8,
    ) -> Option<Self> {
        let n = c.len() - 1;
        if !(2..=MAX_DEGREE).contains(&n)
            || x >= y
            || x.is_nan()
            || y.is_nan()
            || (x < 0.0 && y > 0.0)
        {
            return None;
        }
        // Orientation: shift to the end nearer 0, so M uses max(|x|, |y|).
        let (e, other) = if x >= 0.0 { (x, y) } else { (y, x) };
        let (wh, wl) = two_sum(other, -e);
        let w = Dd::from_pair(wh, wl);
        let r = y.abs().max(x.abs());
        let (mag, zr) = abs_weights(c, r);
        if !mag.is_finite() {
            return None;
        }
        let mut arena: SmallVec<[Dd; 64]> = SmallVec::from_elem(Dd::default(), n + 1);
        let v = &mut arena[..];
        // Step 1: r(s) = p(e + s), Horner's rule on polynomials (one product and one sum per
        // step on any path).
        taylor_shift_into(c, e, v);
        // Step 2: q_j = r_j·wʲ (wʲ by j − 1 products, then one more).
        let mut wj = w;
        for vj in v.iter_mut().skip(1) {
            *vj = if wj.lo == 0.0 {
                vj.mul_f(wj.hi)
            } else {
                vj.mul(wj)
            };
            wj = if wl == 0.0 { wj.mul_f(wh) } else { wj.mul(w) };
        }
        // Step 3: power basis on [0, 1] → Bernstein: bᵢ = Σ_{j≤i} C(i,j)/C(n,j)·q_j, as a
        // division by the exact integer C(n, j), then n passes of neighbour sums.
        let mut binom: u64 = 1;
        for (j, vj) in v.iter_mut().enumerate() {
            if j > 0 {
                // Exact in u64: C(n, j − 1)·(n − j + 1) < 56·C(56, 28) < 2^63; the quotient
                // C(n, j) < 2^53 converts to f64 exactly.
                binom = binom * (n - j + 1) as u64 / j as u64;
            }
            *vj = vj.div_f(binom as f64);
        }
        // Exclusive ranges, as in `bernstein::bernstein_on` (unrolled loops).
        for pass in 1..n + 1 {
            for i in (pass..n + 1).rev() {
                v[i] = v[i].add(v[i - 1]);
            }
        }
        if e != x {
            // Shifted from y towards x: coefficient i belongs to t = y + (x − y)·i/n.
            v.reverse();
        }
        // Underflow: at most DD_UNDERFLOW per operation, amplified by at most r per Horner
        // step and by powers of |w| ≤ r, by at most 2ⁿ in the basis change; at most (n + 1)²
        // operations feed each output (doubled for the scaling step). Averages only add.
        // The chain wʲ of step 2 (its errors multiplied by the shifted coefficients):
        // `chain_underflow_weight`.
        let chain = chain_underflow_weight(c, e, wh, DD_MIN_EXACT);
        let tiny0 =
            2.0 * DD_UNDERFLOW * (zr + chain) * 2f64.powi(n as i32) * ((n + 1) * (n + 1)) as f64;
        Some(Self::top(
            (c, n),
            (x, y),
            (s_x, s_y),
            (mag, 4 * n + 1, 0.0, tiny0),
            arena,
            sign_at,
        ))
    }

    /// The run on `(x, y]` from Bernstein coefficients computed elsewhere: `b` in order from
    /// `x` to `y`, each within `e0` of the exact Bernstein coefficient of the stored
    /// polynomial on `[x, y]` (the descent from a wide tier, `multiprec.rs`). Why: a node the
    /// wide tier had to classify (power-basis coefficients far larger than the polynomial's
    /// values, Chebyshev T₈₀'s `2⁷⁹`) usually has Bernstein coefficients that double-double
    /// resolves easily, so its subtree needs no further wide Taylor shift. The bound: the
    /// exact averages of the handed-down values are within `e0` of the exact ones (averages
    /// of errors at most `e0`), and the run's own roundings are at most `γ(n·depth)·M` with
    /// `M` the largest `|b̂ᵢ|` (the absolute-value program of de Casteljau's averages never
    /// exceeds its inputs). `None` when the ends are not as [`Self::new`] requires.
    pub(crate) fn from_bernstein(
        c: &'c [f64],
        (x, y): (f64, f64),
        (s_x, s_y): (i8, i8),
        b: SmallVec<[Dd; 64]>,
        e0: f64,
        sign_at: fn(&[f64], f64) -> i8,
    ) -> Option<Self> {
        let n = c.len() - 1;
        if b.len() != n + 1
            || n < 2
            || x >= y
            || x.is_nan()
            || y.is_nan()
            || (x < 0.0 && y > 0.0)
            || !e0.is_finite()
        {
            return None;
        }
        let mag = b
            .iter()
            .map(|v| v.hi.abs() + v.lo.abs())
            .fold(0.0f64, f64::max)
            * (1.0 + 4.0 * f64::EPSILON);
        if !mag.is_finite() {
            return None;
        }
        Some(Self::top(
            (c, n),
            (x, y),
            (s_x, s_y),
            (mag, 0, e0, 0.0),
            b,
            sign_at,
        ))
    }

    /// The run with its top node's coefficients in `arena`, and their bound's parts
    /// `(M, k₀, e₀, underflow)` (see [`Self::bound`]).
    fn top(
        (c, n): (&'c [f64], usize),
        (x, y): (f64, f64),
        (s_x, s_y): (i8, i8),
        (mag, k0, e0, tiny0): (f64, usize, f64, f64),
        arena: SmallVec<[Dd; 64]>,
        sign_at: fn(&[f64], f64) -> i8,
    ) -> Self {
        let (dh, dl) = two_sum(y, -x);
        DdBernstein {
            c,
            n,
            x,
            y,
            s_x,
            s_y,
            d: Dd::from_pair(dh, dl),
            mag,
            k0,
            e0,
            tiny0,
            level_tiny: 2.0 * n as f64 * DD_UNDERFLOW,
            arena,
            stack: SmallVec::from_elem(
                Node {
                    u0: 0.0,
                    u1: 1.0,
                    depth: 0,
                    at: 0,
                },
                1,
            ),
            nodes: 0,
            floor: (x, s_x),
            sign_at,
        }
    }

    /// The bound on every coefficient of a node at `depth`.
    fn bound(&self, depth: u32) -> f64 {
        let levels = self.n * depth as usize;
        self.e0 * (1.0 + gamma_u(levels, DD_UNIT))
            + gamma_u(self.k0 + levels, DD_UNIT) * self.mag * (1.0 + 4.0 * f64::EPSILON)
            + self.tiny0
            + self.level_tiny * f64::from(depth)
    }

    /// The next outcome, left to right; `None` when the piece is done.
    pub(crate) fn next(&mut self, stats: &mut RootStats) -> Option<DdOutcome> {
        let n = self.n;
        while let Some(node) = self.stack.pop() {
            self.nodes += 1;
            let class = self.classify(&node);
            match class {
                Class::Empty => self.arena.truncate(node.at),
                Class::One(s_left) => {
                    self.arena.truncate(node.at);
                    return Some(match self.bracket(&node, s_left) {
                        Some(b) => {
                            self.floor = (b.hi, -b.s_lo);
                            DdOutcome::Bracket(b)
                        }
                        None => self.handoff(),
                    });
                }
                Class::Split if node.depth < MAX_DEPTH && self.nodes < MAX_NODES => {
                    stats.subdivisions += 1;
                    // De Casteljau at u = 1/2: the right half in place, the left half above
                    // it (popped first).
                    let at = node.at;
                    halve(&mut self.arena, at, n);
                    let mid = 0.5 * (node.u0 + node.u1);
                    let depth = node.depth + 1;
                    self.stack.push(Node {
                        u0: mid,
                        u1: node.u1,
                        depth,
                        at,
                    });
                    self.stack.push(Node {
                        u0: node.u0,
                        u1: mid,
                        depth,
                        at: at + n + 1,
                    });
                }
                Class::Split | Class::Hopeless => return Some(self.handoff()),
            }
        }
        None
    }

    /// Ends the run: the rest of the piece, from the last certified point, goes back.
    fn handoff(&mut self) -> DdOutcome {
        self.stack.clear();
        let (t_a, s_a) = self.floor;
        DdOutcome::Handoff { t_a, s_a }
    }

    /// Descartes' rule on the node's certified coefficient signs; `One` carries the sign of
    /// `p` just inside the node's left end.
    fn classify(&self, node: &Node) -> Class {
        let err = self.bound(node.depth);
        let v = &self.arena[node.at..node.at + self.n + 1];
        let sign = |b: &Dd| b.sign_beyond(err);
        let first = if node.u0 == 0.0 {
            self.s_x
        } else {
            sign(&v[0])
        };
        let last = if node.u1 == 1.0 {
            self.s_y
        } else {
            sign(&v[self.n])
        };
        let mut undecided = 0usize;
        let mut prev = first;
        let mut changes = 0u32;
        for b in &v[1..self.n] {
            match sign(b) {
                0 => undecided += 1,
                s => {
                    changes += u32::from(prev != 0 && s != prev);
                    prev = s;
                }
            }
        }
        if first == 0 || last == 0 || undecided > 0 {
            return if v.iter().all(|b| sign(b) == 0) {
                Class::Hopeless
            } else {
                Class::Split
            };
        }
        changes += u32::from(last != prev);
        match changes {
            0 => Class::Empty,
            1 => Class::One(first),
            _ => Class::Split,
        }
    }

    /// `t = x + (y − x)·u` in double-double, and a bound on its error.
    fn t_at(&self, u: f64) -> (Dd, f64) {
        let t = self.d.mul_f(u).add_f(self.x);
        let err = 3.0 * DD_UNIT * (self.x.abs() + self.d.hi.abs()) * (1.0 + 4.0 * f64::EPSILON)
            + 4.0 * DD_UNDERFLOW;
        (t, err)
    }

    /// The first `f64` strictly above the exact node end `x + (y − x)·u` (`dir = 1`), or
    /// strictly below it (`dir = −1`).
    fn beyond(&self, u: f64, dir: f64) -> f64 {
        let (t, err) = self.t_at(u);
        // The exact end lies within t.lo + err of t.hi; step away from t.hi until past that.
        let gap = t.lo.abs() + err;
        let gap = gap * (1.0 + 4.0 * f64::EPSILON);
        let mut z = t.hi;
        for _ in 0..8 {
            z = if dir > 0.0 {
                z.next_up()
            } else {
                z.next_down()
            };
            // |z − t.hi| is exact (a few ulps apart).
            if (z - t.hi).abs() > gap {
                return z;
            }
        }
        f64::NAN
    }

    /// A certified `f64` bracket strictly inside the node (which holds exactly one simple
    /// root, with `p` of sign `s_left` just inside its left end), or `None` when the node
    /// is too narrow or a sign disagrees (the root is within a rounding of a node end).
    fn bracket(&self, node: &Node, s_left: i8) -> Option<Bracket> {
        let c = self.c;
        let lo = if node.u0 == 0.0 {
            self.x
        } else {
            self.beyond(node.u0, 1.0)
        };
        let hi = if node.u1 == 1.0 {
            self.y
        } else {
            self.beyond(node.u1, -1.0)
        };
        if lo.is_nan() || hi.is_nan() || lo >= hi {
            return None;
        }
        if node.u0 > 0.0 && (self.sign_at)(c, lo) != s_left {
            return None;
        }
        if node.u1 < 1.0 && (self.sign_at)(c, hi) != -s_left {
            return None;
        }
        Some(Bracket::new(lo, hi, s_left))
    }
}

/// De Casteljau at `u = 1/2` on the node whose `n + 1` coefficients start at `at` (the top
/// of the arena): the right half stays in place, the left half is written above it.
#[allow(
    clippy::needless_range_loop,
    reason = "two halves indexed together, as in bernstein.rs"
)]
fn halve(arena: &mut SmallVec<[Dd; 64]>, at: usize, n: usize) {
    arena.resize(at + 2 * (n + 1), Dd::default());
    let (right, left) = arena[at..].split_at_mut(n + 1);
    left[0] = right[0];
    // Exclusive ranges, as in `bernstein::bernstein_on` (unrolled loops).
    for r in 1..n + 1 {
        for i in 0..n + 1 - r {
            right[i] = right[i].average(right[i + 1]);
        }
        left[r] = right[0];
    }
}

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Class {
    Empty,
    /// One root; the sign of `p` just inside the left end.
    One(i8),
    Split,
    /// Every coefficient within its bound: no descendant can be decided at this precision.
    Hopeless,
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scalar::{Rat, rat_from_f64};
    use crate::univariate::Poly;
    use num_traits::Signed;
    use proptest::prelude::*;

    /// The exact sign of `p(x)` for the stored coefficients (the test oracle; also the
    /// run's sign function here).
    fn exact_sign(c: &[f64], x: f64) -> i8 {
        let v = Poly::new(c.to_vec())
            .to_rat()
            .unwrap()
            .eval(&rat_from_f64(x).unwrap());
        if v.is_positive() {
            1
        } else if v.is_negative() {
            -1
        } else {
            0
        }
    }

    /// Exact Bernstein coefficients of `p` on `[x, y]`.
    fn exact_bernstein(p: &Poly<f64>, xr: &Rat, yr: &Rat) -> Vec<Rat> {
        let q = p.to_rat().unwrap().compose_affine(xr, &(yr - xr));
        let n = p.degree();
        let binom = |n: usize, k: usize| -> Rat {
            (0..k).fold(Rat::from_integer(1.into()), |acc, j| {
                acc * Rat::from_integer(((n - j) as i64).into())
                    / Rat::from_integer(((j + 1) as i64).into())
            })
        };
        (0..=n)
            .map(|i| {
                (0..=i).fold(Rat::from_integer(0.into()), |acc, j| {
                    acc + binom(i, j) / binom(n, j) * q.coeff(j)
                })
            })
            .collect()
    }

    fn dd_rat(d: &Dd) -> Rat {
        rat_from_f64(d.hi).unwrap() + rat_from_f64(d.lo).unwrap()
    }

    /// The top node's coefficients, and those after halving left then right, are within
    /// the run's bound of the exact ones, for a piece right of 0 and one left of 0 (the
    /// shift from the end nearer 0, reversed).
    #[test]
    fn coefficients_are_within_their_bound_in_both_orientations() {
        let p = Poly::new(vec![-1.3e3, 2.7, 0.41, -7.9, 1.0, 0.031, -2.2e-3]);
        let mut stats = RootStats::default();
        for (x, y) in [(0.37, 11.3), (-9.1, -0.2), (0.0, 3.3), (-2.5, 0.0)] {
            let mut run = DdBernstein::new(p.coeffs(), (x, y), (1, 1), exact_sign).unwrap();
            let n = p.degree();
            let check = |run: &DdBernstein<'_>, node: &Node| {
                let (u0, u1) = (node.u0, node.u1);
                // The exact node ends x + (y − x)·u.
                let (xr, yr) = (rat_from_f64(x).unwrap(), rat_from_f64(y).unwrap());
                let at = |u: f64| &xr + (&yr - &xr) * rat_from_f64(u).unwrap();
                let exact = exact_bernstein(&p, &at(u0), &at(u1));
                let err = rat_from_f64(run.bound(node.depth)).unwrap();
                for (i, e) in exact.iter().enumerate() {
                    let got = dd_rat(&run.arena[node.at + i]);
                    assert!(
                        (got - e).abs() <= err,
                        "({x}, {y}) node {u0}..{u1}, coefficient {i}"
                    );
                }
                assert!(run.bound(node.depth) < 1e-25 * run.mag, "bound not vacuous");
                n
            };
            let top = run.stack[0];
            check(&run, &top);
            // Force two halvings (left child, then its right child) by hand.
            for pick_left in [true, false] {
                let node = run.stack.pop().unwrap();
                let at = node.at;
                run.arena.truncate(at + n + 1);
                halve(&mut run.arena, at, n);
                let mid = 0.5 * (node.u0 + node.u1);
                let depth = node.depth + 1;
                let (l, r) = (
                    Node {
                        u0: node.u0,
                        u1: mid,
                        depth,
                        at: at + n + 1,
                    },
                    Node {
                        u0: mid,
                        u1: node.u1,
                        depth,
                        at,
                    },
                );
                check(&run, &l);
                check(&run, &r);
                if pick_left {
                    // Keep the left child on top: move its coefficients down.
                    let left: Vec<Dd> = run.arena[at + n + 1..at + 2 * (n + 1)].to_vec();
                    run.arena.truncate(at);
                    run.arena.extend(left);
                    run.stack.push(Node { at, ..l });
                } else {
                    run.arena.truncate(at + n + 1);
                    run.stack.push(r);
                }
            }
            let _ = run.next(&mut stats);
        }
    }

    /// `DWDivFP` against exact rationals: within `DD_UNIT` relative.
    #[test]
    fn double_word_division_meets_its_bound() {
        for (hi, lo) in [
            (1.0, 1e-17),
            (-3.0, 2f64.powi(-60)),
            (7.0e30, -1.3e14),
            (0.1, 0.0),
        ] {
            let (h, l) = two_sum(hi, lo);
            let x = Dd::from_pair(h, l);
            for y in [3.0, 7.0, 184_756.0, 7.648_690_600_760_44e15, -0.3] {
                let exact = dd_rat(&x) / rat_from_f64(y).unwrap();
                let got = dd_rat(&x.div_f(y));
                let bound = exact.abs() * rat_from_f64(DD_UNIT).unwrap();
                assert!((got - &exact).abs() <= bound, "{x:?} / {y}");
            }
        }
    }

    /// Exact root count of `p` in the open interval `(a, b)`.
    fn exact_count(p: &Poly<f64>, a: f64, b: f64) -> usize {
        let seq = p.to_rat().unwrap().sturm().unwrap();
        let (ar, br) = (rat_from_f64(a).unwrap(), rat_from_f64(b).unwrap());
        let at_b = usize::from(seq.sign_of_square_free_at(&br) == 0);
        seq.sign_changes_at(&ar) - seq.sign_changes_at(&br) - at_b
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(48))]

        /// On random polynomials with planted roots (some clustered), every bracket holds
        /// exactly one root with the certified signs, and no root is skipped: the roots in
        /// `(x, t]` are exactly the brackets found, where `t` is the handoff point or `y`.
        #[test]
        fn brackets_and_handoff_account_for_every_root(
            roots in proptest::collection::vec(-64i32..64, 2..9),
            gap in 1u32..40,
            left in proptest::bool::ANY,
        ) {
            let mut rs: Vec<f64> = roots.iter().map(|&r| f64::from(r) / 16.0 + 0.01).collect();
            rs.push(rs[0] + 2f64.powi(-(gap as i32)));
            let p = Poly::<f64>::from_roots(&rs);
            let (x, y) = if left { (-5.0, 0.0) } else { (0.0, 5.0) };
            let c = p.coeffs();
            let (sx, sy) = (exact_sign(c, x), exact_sign(c, y));
            prop_assume!(sx != 0 && sy != 0 && p.degree() <= MAX_DEGREE);
            let mut run = DdBernstein::new(c, (x, y), (sx, sy), exact_sign).unwrap();
            let mut stats = RootStats::default();
            let mut found = 0;
            let mut end = y;
            while let Some(o) = run.next(&mut stats) {
                match o {
                    DdOutcome::Bracket(b) => {
                        prop_assert_eq!(exact_count(&p, b.lo, b.hi), 1, "{:?}", b);
                        prop_assert_eq!(exact_sign(c, b.lo), b.s_lo);
                        prop_assert_eq!(exact_sign(c, b.hi), -b.s_lo);
                        found += 1;
                    }
                    DdOutcome::Handoff { t_a, s_a } => {
                        prop_assert_eq!(exact_sign(c, t_a), s_a);
                        end = t_a;
                    }
                }
            }
            let on_end = usize::from(end < y && exact_sign(c, end) == 0);
            prop_assert_eq!(exact_count(&p, x, end) + on_end, found, "{:?} on ({}, {}]", rs, x, end);
        }
    }
}

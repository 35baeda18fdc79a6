//! [`ExactOracle`]: the exact isolation behind [`IsolationMethod::Exact`] and the certified
//! path's infinite ranges — Descartes' rule on the stored polynomial when a modular gcd
//! certifies it square-free, the exact Sturm sequence of its square-free part otherwise.
//!
//! [`IsolationMethod::Exact`]: crate::IsolationMethod::Exact

use crate::descartes::Descartes;
use crate::int_poly::IntPoly;
use crate::root_interval::RootInterval;
use crate::scalar::{Rat, rat_from_f64};
use crate::stats::RootStats;
use crate::sturm::SturmSequence;
use crate::univariate::QPoly;

/// The exact sign of a polynomial's square-free part: what exact refinement bisects on.
pub(crate) trait SquareFreeSign {
    /// The sign (−1, 0 or 1) at `x`; zero exactly at the distinct roots.
    fn sign_of_square_free_at(&self, x: &Rat) -> i8;
}

impl SquareFreeSign for SturmSequence<Rat> {
    fn sign_of_square_free_at(&self, x: &Rat) -> i8 {
        SturmSequence::sign_of_square_free_at(self, x)
    }
}

/// Exact root isolation of one rational polynomial.
pub(crate) enum ExactOracle {
    /// Certified square-free (a modular gcd with its derivative is 1): Descartes' rule on
    /// the primitive integer polynomial, which is then its own square-free part.
    SquareFree(IntPoly),
    /// A repeated factor is possible: the exact Sturm sequence of the square-free part.
    Sturm(SturmSequence<Rat>),
}

impl ExactOracle {
    /// The oracle of the non-zero `q`.
    ///
    /// # Panics
    /// When `q` is the zero polynomial (callers check it first).
    pub(crate) fn new(q: &QPoly) -> Self {
        let p = IntPoly::from_qpoly(q);
        if p.is_certainly_square_free() {
            ExactOracle::SquareFree(p)
        } else {
            ExactOracle::Sturm(q.sturm().expect("non-zero polynomial was checked"))
        }
    }

    /// Isolating intervals of the distinct roots in `(lo, hi]` (finite `f64` ends), sorted:
    /// one root in each open interval or a point, `n` copies of an interval between adjacent
    /// `f64` numbers holding `n` roots (the convention of [`exact_isolate`]).
    ///
    /// # Exactness
    /// Exact and certified, by either method.
    pub(crate) fn isolate(
        &self,
        lo: f64,
        hi: f64,
        first_only: bool,
        stats: &mut RootStats,
    ) -> Vec<RootInterval<f64>> {
        match self {
            ExactOracle::SquareFree(p) => Descartes::new(p.coeffs())
                .isolate(lo, hi, first_only, stats)
                .unwrap_or_else(|| {
                    // Roots closer than an f64 spacing that Descartes did not separate in its
                    // budget: the exact Sturm count settles them.
                    let seq = p.to_qpoly().sturm().expect("non-zero polynomial");
                    exact_isolate(&seq, lo, hi, first_only, stats)
                }),
            ExactOracle::Sturm(seq) => exact_isolate(seq, lo, hi, first_only, stats),
        }
    }
}

impl SquareFreeSign for ExactOracle {
    fn sign_of_square_free_at(&self, x: &Rat) -> i8 {
        match self {
            ExactOracle::SquareFree(p) => p.sign_at(x),
            ExactOracle::Sturm(seq) => seq.sign_of_square_free_at(x),
        }
    }
}

/// Exact Sturm isolation of the stored polynomial on `(lo, hi]` (finite ends), bisecting at
/// `f64` points so that every interval end is an `f64` (seed §3.5.2 with exact counts).
/// Roots closer than one `f64` spacing share an interval, listed once per root (documented
/// on [`Poly::isolate_roots`](crate::Poly::isolate_roots)).
fn exact_isolate(
    seq: &SturmSequence<Rat>,
    lo: f64,
    hi: f64,
    first_only: bool,
    stats: &mut RootStats,
) -> Vec<RootInterval<f64>> {
    let count_at = |x: f64| seq.sign_changes_at(&rat_from_f64(x).expect("finite"));
    let mut out = Vec::new();
    let mut stack = vec![(lo, hi, count_at(lo), count_at(hi))];
    while let Some((a, b, va, vb)) = stack.pop() {
        let n = va.saturating_sub(vb);
        if n == 0 {
            continue;
        }
        let m = 0.5 * a + 0.5 * b;
        let splittable = m > a && m < b;
        if n == 1 || !splittable {
            let at_b = seq.sign_of_square_free_at(&rat_from_f64(b).expect("finite")) == 0;
            for _ in 0..n {
                out.push(if at_b && n == 1 {
                    RootInterval { lo: b, hi: b }
                } else {
                    RootInterval { lo: a, hi: b }
                });
            }
            if first_only {
                break;
            }
            continue;
        }
        stats.subdivisions += 1;
        let vm = count_at(m);
        stack.push((m, b, vm, vb));
        stack.push((a, m, va, vm));
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::univariate::Poly;

    /// Issue 13, item 17: case 396 of the coefficient fuzzer (seed 13, degree ≤ 40), degree 39
    /// with coefficients from subnormals to `f64::MAX`. Its exact Sturm sequence has members
    /// of 139 000 bits and took 2.5 s to build in a release build (the `Exact` method's whole
    /// query); the oracle now certifies it square-free and isolates by Descartes' rule, with no
    /// Sturm sequence. The two roots in `(−10, 10]` (9.1e-25 and 3.8e-4, agreed by the
    /// Bernstein method) are each in an interval with opposite exact end signs.
    #[test]
    fn exact_isolation_of_2000_bit_coefficients_builds_no_sturm_sequence() {
        let c = vec![
            -0.5024187312387625,
            0.0,
            -0.9094546417829834,
            0.0,
            0.0,
            -1.7433028472052011e89,
            5.082162864513933,
            3.2505543275004722,
            -0.9310455584331905,
            1.1471796560887233e216,
            -5.0,
            -1.127538868221194,
            0.0,
            -1.9631877291002464,
            0.0,
            5.991732031751296,
            0.0,
            -0.2712933704055902,
            -2.2250738585072014e-308,
            -0.9264970896710216,
            0.0,
            -0.381338923160488,
            7.411353838404207,
            -8.270600484184905e-309,
            5.194759342476999,
            1.1408940265230438e244,
            3.0,
            -1.1436619299152109e164,
            35958319949.70362,
            -6.87057282992205,
            -4.9701190586038235,
            4.3794061379201,
            0.0,
            -3.8944048807878584e-118,
            -6.164529032870458,
            -1.634616278281835e181,
            -1.7976931348623157e308,
            0.9946425927992841,
            0.0,
            0.8783809865883412,
        ];
        let q = Poly::new(c).to_rat().expect("finite");
        let oracle = ExactOracle::new(&q);
        assert!(
            matches!(oracle, ExactOracle::SquareFree(_)),
            "certified square-free: no Sturm sequence"
        );
        let ivs = oracle.isolate(-10.0, 10.0, false, &mut RootStats::default());
        assert_eq!(ivs.len(), 2, "{ivs:?}");
        let sign = |x: f64| oracle.sign_of_square_free_at(&crate::rat_from_f64(x).expect("finite"));
        for (iv, root) in ivs
            .iter()
            .zip([9.123_455_880_096_18e-25, 3.849_171_439_377_682e-4])
        {
            assert!(iv.lo < root && root < iv.hi, "{root:e} in {iv:?}");
            assert_eq!(sign(iv.lo) * sign(iv.hi), -1, "a sign change across {iv:?}");
        }
    }
}

//! The solvers the suites compare, behind one interface: all real roots in `(lo, hi]`, and the
//! smallest one (the ray tracer's query).

use std::sync::atomic::{AtomicU64, Ordering};

use nalgebra::{DMatrix, Schur};
use poly::{IsolationMethod, Poly, RefineMethod, RootOptions, RootStats, StamSturm};

/// Largest `|Im λ| / max(1, |λ|)` for which an eigenvalue of the companion matrix is taken as
/// a real root: `2^-26 ≈ 1.5e-8 ≈ √ε`. A simple real root comes out of the real Schur form
/// with an imaginary part of exactly zero; this threshold only matters for near-multiple
/// roots, which rounding turns into complex pairs of size about `ε^{1/k}`.
pub const COMPANION_IMAG_TOL: f64 = 1.0 / (1u64 << 26) as f64;

/// Sweeps of the Parlett–Reinsch balancing applied to the companion matrix before the QR
/// iteration (what LAPACK's `dgeev` and NumPy's `roots` do; unbalanced companion matrices of
/// polynomials with widely ranging coefficients lose most of their accuracy).
const BALANCE_SWEEPS: usize = 20;

/// QR sweeps allowed per eigenvalue before the Schur iteration is declared stuck (LAPACK's
/// `dhseqr` allows 30).
const SCHUR_SWEEPS_PER_EIGENVALUE: usize = 30;

/// Shifts (as fractions of the root bound) tried in turn when `nalgebra`'s real Schur
/// iteration does not converge. Its Francis double-shift QR has no exceptional shifts and can
/// cycle on companion matrices whose roots come in `±` pairs (Chebyshev, Legendre); the
/// eigenvalues of `C − σI` are `λ − σ`, and an off-centre `σ` breaks the symmetry.
const RETRY_SHIFTS: [f64; 3] = [0.0, 0.3125, -0.2734375];

/// Number of companion solves that needed a shifted retry (at the shifts `RETRY_SHIFTS`), and number
/// that failed even so, since the start of the process.
pub static COMPANION_RETRIES: AtomicU64 = AtomicU64::new(0);
/// See [`COMPANION_RETRIES`].
pub static COMPANION_FAILURES: AtomicU64 = AtomicU64::new(0);

/// A root finder under test.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Method {
    /// Stam's 1988 `ray2.c` algorithm: unnormalised `f64` Sturm sequence, count-driven
    /// bisection, bisection on the sign of `P` ([`StamSturm`]); the baseline.
    Stam,
    /// Our `f64` Sturm sequence (normalised remainders) with bisection isolation and the given
    /// refinement ([`IsolationMethod::Sturm`]): a heuristic.
    SturmF64(RefineMethod),
    /// The certified default path: Descartes' rule in the Bernstein basis with rounding-error
    /// bounds and exact fallback ([`IsolationMethod::Bernstein`]), with the given refinement.
    Bernstein(RefineMethod),
    /// Exact rational Sturm isolation and exact bisection ([`IsolationMethod::Exact`]).
    Exact,
    /// Real eigenvalues of the balanced companion matrix (`nalgebra` real Schur form): the
    /// peer baseline.
    Companion,
    /// polycool 0.4's `roots_between` (its fixed-size cubic and quartic, `PolyDyn` otherwise):
    /// a peer, uncertified.
    Polycool,
    /// kurbo 0.13's closed forms `solve_quadratic`, `solve_cubic`, `solve_quartic`: a peer,
    /// degrees 1–4 only (see [`Method::supports`]).
    Kurbo,
    /// roots 0.0.8: its closed forms to degree 4, `find_roots_sturm` above: a peer.
    Roots,
}

/// The refinement methods of `poly`, in display order.
pub const REFINE_METHODS: [RefineMethod; 3] = [
    RefineMethod::Bisection,
    RefineMethod::Illinois,
    RefineMethod::NewtonBisection,
];

impl Method {
    /// Every method of the stability suite, baseline first, the peers last.
    pub const STABILITY: [Method; 10] = [
        Method::Stam,
        Method::SturmF64(RefineMethod::Illinois),
        Method::Bernstein(RefineMethod::Bisection),
        Method::Bernstein(RefineMethod::Illinois),
        Method::Bernstein(RefineMethod::NewtonBisection),
        Method::Exact,
        Method::Companion,
        Method::Polycool,
        Method::Kurbo,
        Method::Roots,
    ];

    /// Whether the method answers polynomials of this degree at all (kurbo has closed forms
    /// only); the suites show "—" where it does not.
    pub fn supports(self, degree: usize) -> bool {
        self != Method::Kurbo || (1..=4).contains(&degree)
    }

    /// Short name for tables and plots.
    pub fn name(self) -> String {
        let refine = |r: RefineMethod| match r {
            RefineMethod::Bisection => "bisect",
            RefineMethod::Illinois => "illinois",
            RefineMethod::NewtonBisection => "newton",
            _ => "other",
        };
        match self {
            Method::Stam => "stam-1988".to_owned(),
            Method::SturmF64(r) => format!("sturm-f64+{}", refine(r)),
            Method::Bernstein(r) => format!("bernstein+{}", refine(r)),
            Method::Exact => "exact-sturm".to_owned(),
            Method::Companion => "companion-eig".to_owned(),
            Method::Polycool => "polycool-0.4".to_owned(),
            Method::Kurbo => "kurbo-0.13".to_owned(),
            Method::Roots => "roots-0.0.8".to_owned(),
        }
    }

    /// Whether the method promises its answer (certified isolation of the stored polynomial).
    pub fn is_certified(self) -> bool {
        matches!(self, Method::Bernstein(_) | Method::Exact)
    }

    fn options(self, x_tol: f64) -> RootOptions {
        let (isolation, refine) = match self {
            Method::Stam => (IsolationMethod::StamSturm, RefineMethod::Bisection),
            Method::SturmF64(r) => (IsolationMethod::Sturm, r),
            Method::Bernstein(r) => (IsolationMethod::Bernstein, r),
            Method::Exact
            | Method::Companion
            | Method::Polycool
            | Method::Kurbo
            | Method::Roots => (IsolationMethod::Exact, RefineMethod::Bisection),
        };
        RootOptions {
            isolation,
            refine,
            closed_form: true,
            ..RootOptions::new(x_tol)
        }
    }

    /// Every distinct real root in `(lo, hi]` (finite bounds), increasing, each meant to be
    /// within `x_tol` (absolute). Refused input gives no roots.
    pub fn all_roots(
        self,
        p: &Poly<f64>,
        lo: f64,
        hi: f64,
        x_tol: f64,
        stats: &mut RootStats,
    ) -> Vec<f64> {
        match self {
            Method::Stam => stam_all_roots(p, lo, hi, x_tol),
            Method::Companion => companion_roots(p, lo, hi),
            Method::Polycool | Method::Kurbo | Method::Roots => peer_roots(self, p, lo, hi, x_tol),
            _ => p
                .real_roots_with(lo, hi, &self.options(x_tol), stats)
                .unwrap_or_default(),
        }
    }

    /// The smallest distinct real root in `(lo, hi]`, meant to be within `x_tol`.
    pub fn smallest_root(
        self,
        p: &Poly<f64>,
        lo: f64,
        hi: f64,
        x_tol: f64,
        stats: &mut RootStats,
    ) -> Option<f64> {
        match self {
            Method::Companion => companion_roots(p, lo, hi).first().copied(),
            Method::Polycool | Method::Kurbo | Method::Roots => {
                peer_roots(self, p, lo, hi, x_tol).first().copied()
            }
            _ => p.smallest_root_with(lo, hi, &self.options(x_tol), stats),
        }
    }
}

/// All roots by Stam's own search, as his tracer would enumerate them: `IntAlgSurf`'s
/// smallest-root search on `(t, hi]`, restarted just after each root found. His search returns
/// the right end of the final bracket, which is at or above the root, so the next search
/// starts past it. At most `degree` roots.
fn stam_all_roots(p: &Poly<f64>, lo: f64, hi: f64, x_tol: f64) -> Vec<f64> {
    let Some(seq) = StamSturm::new(p) else {
        return Vec::new();
    };
    let mut out: Vec<f64> = Vec::new();
    let mut t = lo;
    while out.len() < p.degree() {
        match seq.smallest_root(t, hi, x_tol) {
            Ok(Some(r)) if r > t => {
                out.push(r);
                t = r;
            }
            _ => break,
        }
    }
    out
}

/// A peer's real roots in `(lo, hi]`, increasing, as the peer reports them (no deduplication:
/// a repeated value is a phantom in the scoring). Polynomials a peer cannot take (degree 0,
/// non-finite coefficients, kurbo above degree 4) give no roots.
fn peer_roots(method: Method, p: &Poly<f64>, lo: f64, hi: f64, x_tol: f64) -> Vec<f64> {
    let c = p.coeffs();
    if p.degree() == 0 || !p.is_finite() || !method.supports(p.degree()) {
        return Vec::new();
    }
    let mut r: Vec<f64> = match (method, c.len()) {
        (Method::Polycool, 4) => polycool::Poly::<4>::new([c[0], c[1], c[2], c[3]])
            .roots_between(lo, hi, x_tol)
            .to_vec(),
        (Method::Polycool, 5) => polycool::Poly::<5>::new([c[0], c[1], c[2], c[3], c[4]])
            .roots_between(lo, hi, x_tol)
            .to_vec(),
        (Method::Polycool, _) => {
            polycool::PolyDyn::new(c.iter().copied()).roots_between(lo, hi, x_tol)
        }
        (Method::Kurbo, 2) => vec![-c[0] / c[1]],
        (Method::Kurbo, 3) => kurbo::common::solve_quadratic(c[0], c[1], c[2]).to_vec(),
        (Method::Kurbo, 4) => kurbo::common::solve_cubic(c[0], c[1], c[2], c[3]).to_vec(),
        (Method::Kurbo, 5) => kurbo::common::solve_quartic(c[0], c[1], c[2], c[3], c[4]).to_vec(),
        (Method::Roots, 2) => roots::find_roots_linear(c[1], c[0]).as_ref().to_vec(),
        (Method::Roots, 3) => roots::find_roots_quadratic(c[2], c[1], c[0])
            .as_ref()
            .to_vec(),
        (Method::Roots, 4) => roots::find_roots_cubic(c[3], c[2], c[1], c[0])
            .as_ref()
            .to_vec(),
        (Method::Roots, 5) => roots::find_roots_quartic(c[4], c[3], c[2], c[1], c[0])
            .as_ref()
            .to_vec(),
        (Method::Roots, n) => {
            let monic: Vec<f64> = (0..n - 1).rev().map(|i| c[i] / c[n - 1]).collect();
            roots::find_roots_sturm(&monic, &mut x_tol.max(f64::EPSILON))
                .into_iter()
                .filter_map(Result::ok)
                .collect()
        }
        _ => Vec::new(),
    };
    r.retain(|&x| x > lo && x <= hi);
    r.sort_by(f64::total_cmp);
    r
}

/// The real eigenvalues in `(lo, hi]` of the balanced companion matrix of `p`, increasing
/// (one per eigenvalue: a multiple root that stays real appears several times).
pub fn companion_roots(p: &Poly<f64>, lo: f64, hi: f64) -> Vec<f64> {
    let n = p.degree();
    let c = p.coeffs();
    if n == 0 || !p.is_finite() {
        return Vec::new();
    }
    // Frobenius companion matrix of the monic polynomial: ones on the subdiagonal, the
    // negated monic coefficients in the last column.
    let lead = c[n];
    let mut m = DMatrix::<f64>::zeros(n, n);
    for i in 1..n {
        m[(i, i - 1)] = 1.0;
    }
    for i in 0..n {
        m[(i, n - 1)] = -c[i] / lead;
    }
    balance(&mut m);
    let bound = p.root_bound().unwrap_or(1.0).max(1.0);
    let mut eig = None;
    for (k, frac) in RETRY_SHIFTS.iter().enumerate() {
        let sigma = frac * bound;
        let mut shifted = m.clone();
        for i in 0..n {
            shifted[(i, i)] -= sigma;
        }
        if let Some(s) = Schur::try_new(shifted, f64::EPSILON, SCHUR_SWEEPS_PER_EIGENVALUE * n) {
            if k == 1 {
                COMPANION_RETRIES.fetch_add(1, Ordering::Relaxed);
            }
            eig = Some((s, sigma));
            break;
        }
    }
    let Some((schur, sigma)) = eig else {
        COMPANION_FAILURES.fetch_add(1, Ordering::Relaxed);
        return Vec::new();
    };
    let mut roots: Vec<f64> = schur
        .complex_eigenvalues()
        .iter()
        .filter(|z| z.im.abs() <= COMPANION_IMAG_TOL * (z.re + sigma).abs().max(1.0))
        .map(|z| z.re + sigma)
        .filter(|&x| x > lo && x <= hi)
        .collect();
    roots.sort_by(f64::total_cmp);
    roots
}

/// Parlett–Reinsch balancing by powers of two (exact scalings, eigenvalues unchanged): make
/// each row and column of the off-diagonal part have comparable norms.
fn balance(m: &mut DMatrix<f64>) {
    let n = m.nrows();
    for _ in 0..BALANCE_SWEEPS {
        let mut changed = false;
        for i in 0..n {
            let (mut col, mut row) = (0.0, 0.0);
            for j in 0..n {
                if j != i {
                    col += m[(j, i)].abs();
                    row += m[(i, j)].abs();
                }
            }
            if col == 0.0 || row == 0.0 {
                continue;
            }
            let mut f = 1.0;
            let s = col + row;
            let (mut c, mut r) = (col, row);
            while c < r / 2.0 {
                c *= 2.0;
                r /= 2.0;
                f *= 2.0;
            }
            while c >= r * 2.0 {
                c /= 2.0;
                r *= 2.0;
                f /= 2.0;
            }
            if (c + r) < 0.95 * s {
                changed = true;
                for j in 0..n {
                    m[(i, j)] /= f;
                    m[(j, i)] *= f;
                }
            }
        }
        if !changed {
            break;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_method_finds_well_separated_roots() {
        // Roots away from the dyadic bisection points of (−4, 4]: Stam's bisection loses a root
        // that a midpoint hits exactly (it tests P(t1)·P(m) < 0, and P(m) = 0 fails the test).
        let roots = [-1.3, 0.2, 2.9];
        let p = Poly::<f64>::from_roots(&roots);
        let mut stats = RootStats::default();
        for m in Method::STABILITY {
            let r = m.all_roots(&p, -4.0, 4.0, 1e-12, &mut stats);
            assert_eq!(r.len(), 3, "{}: {r:?}", m.name());
            for (got, want) in r.iter().zip(roots) {
                assert!((got - want).abs() < 1e-9, "{}: {got} vs {want}", m.name());
            }
            let s = m.smallest_root(&p, 0.0, 4.0, 1e-12, &mut stats);
            assert!(
                s.is_some_and(|s| (s - 0.2).abs() < 1e-9),
                "{}: smallest {s:?}",
                m.name()
            );
        }
    }

    #[test]
    fn stam_loses_a_root_on_a_bisection_point() {
        // (x + 1.5)(x − 0.25)(x − 3) on (−4, 4]: bisection visits −2, −1, −1.5 = the root, and
        // his test P(t1)·P(m) < 0 fails there. His search then returned a point no sign change
        // supports; it now says so (`Unresolved`), and the enumeration stops without a root.
        let p = Poly::<f64>::from_roots(&[-1.5, 0.25, 3.0]);
        let s = StamSturm::new(&p).expect("degree 3");
        let first = s.smallest_root(-4.0, 4.0, 1e-12);
        assert!(
            matches!(first, Err(poly::RootError::Unresolved { .. })),
            "Stam's search cannot confirm −1.5: {first:?}"
        );
        let r = stam_all_roots(&p, -4.0, 4.0, 1e-12);
        assert!(
            r.first().is_none_or(|r| (r + 1.5).abs() > 0.25),
            "Stam's first root is not −1.5: {r:?}"
        );
    }

    #[test]
    fn balancing_keeps_eigenvalues() {
        // Coefficients spanning 1e-6 … 1e6: roots 1e-3, 1, 1e3.
        let p = Poly::<f64>::from_roots(&[1e-3, 1.0, 1e3]);
        let r = companion_roots(&p, -1e4, 1e4);
        assert_eq!(r.len(), 3, "{r:?}");
        for (got, want) in r.iter().zip([1e-3, 1.0, 1e3]) {
            assert!(((got - want) / want).abs() < 1e-10, "{got} vs {want}");
        }
    }
}

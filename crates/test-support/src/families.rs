//! The test polynomials of the stability suite, by family and degree (or camera distance).
//!
//! Polynomial families are built exactly over the rationals where they have a closed form and
//! then rounded coefficient-wise to `f64`; the suite compares every method with the exact roots
//! of the *rounded* polynomial ([`crate::truth`]), so rounding during construction is not
//! counted as a solver error.

use num_bigint::BigInt;
use poly::testutil::{chebyshev, planted, rat, wilkinson};
use poly::{Poly, QPoly, Rat};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;

use crate::rays::{self, SCENE_TORUS};

/// `a` in the clustered family `x^d − 2(a·x − 1)²` (Mignotte-like): two real roots within
/// about `a^{−d/2}/(√2·a)` of `1/a`.
pub const MIGNOTTE_A: i64 = 10;

/// Where the multiple root of the multiple-roots family is: `x = 1/2`.
pub const MULTIPLE_ROOT: (i64, i64) = (1, 2);

/// A family of test polynomials.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Family {
    /// `∏_{k=1}^{d} (x − k)`.
    Wilkinson,
    /// `∏_{k=1}^{d} (x − k/d)`: roots evenly spaced in `(0, 1]`.
    ScaledWilkinson,
    /// Chebyshev `T_d`.
    Chebyshev,
    /// Legendre `P_d`.
    Legendre,
    /// `d` random rationals `n/m` in `[0, 1]`, `2 ≤ m ≤ 1024` (seeded).
    Planted,
    /// Kac polynomials: independent `N(0, 1)` coefficients (seeded).
    Kac,
    /// `x^d − 2(10x − 1)²`: a pair of roots clustered near `1/10`.
    Clustered,
    /// `(x − 1/2)^k · q(x)`, `k = max(2, ⌊d/3⌋)`, `q` with simple roots `(3j − 1)/(3(d − k))`.
    Multiple,
    /// Kajiya resultants `Res_v(F1, F2)(u)` of real teapot ray/sub-patch systems, recorded by
    /// the tracer ([`TEAPOT_ELIMINANTS`]), searched on the piece's `u`-range: the bicubic-patch
    /// eliminants of the suite (degree 8–17; many carry an exact factor `u³` from a collapsed
    /// patch edge).
    TeapotEliminant,
    /// The torus (`R = 2`, `r = 1`) restricted to rays at the eye (camera distance `D`).
    TorusEye,
    /// The same rays restricted at the bounding-sphere entry, as `render` does.
    TorusEntry,
    /// Barth's sextic restricted to rays at the eye (camera distance `D`).
    BarthEye,
    /// The same rays restricted at the bounding-box entry, as `render` does.
    BarthEntry,
}

impl Family {
    /// The polynomial families, indexed by degree.
    pub const BY_DEGREE: [Family; 9] = [
        Family::Wilkinson,
        Family::ScaledWilkinson,
        Family::Chebyshev,
        Family::Legendre,
        Family::Planted,
        Family::Kac,
        Family::Clustered,
        Family::Multiple,
        Family::TeapotEliminant,
    ];

    /// The ray families, indexed by camera distance.
    pub const RAYS: [Family; 4] = [
        Family::TorusEye,
        Family::TorusEntry,
        Family::BarthEye,
        Family::BarthEntry,
    ];

    /// Short name, used in tables and on the command line.
    pub fn name(self) -> &'static str {
        match self {
            Family::Wilkinson => "wilkinson",
            Family::ScaledWilkinson => "scaled-wilkinson",
            Family::Chebyshev => "chebyshev",
            Family::Legendre => "legendre",
            Family::Planted => "planted",
            Family::Kac => "kac",
            Family::Clustered => "clustered",
            Family::Multiple => "multiple",
            Family::TeapotEliminant => "teapot-eliminant",
            Family::TorusEye => "torus-eye",
            Family::TorusEntry => "torus-entry",
            Family::BarthEye => "barth-eye",
            Family::BarthEntry => "barth-entry",
        }
    }

    /// One-line description for the report.
    pub fn description(self) -> &'static str {
        match self {
            Family::Wilkinson => "Wilkinson ∏(x − k), k = 1…d",
            Family::ScaledWilkinson => "scaled Wilkinson ∏(x − k/d), k = 1…d",
            Family::Chebyshev => "Chebyshev T_d",
            Family::Legendre => "Legendre P_d",
            Family::Planted => "planted random rational roots n/m in [0, 1], m ≤ 1024",
            Family::Kac => "Kac: N(0, 1) coefficients",
            Family::Clustered => "clustered (Mignotte-like) x^d − 2(10x − 1)²",
            Family::Multiple => "multiple root (x − 1/2)^k·q(x), k = max(2, ⌊d/3⌋)",
            Family::TeapotEliminant => {
                "teapot ray/sub-patch resultants Res_v(F1, F2)(u), recorded by the tracer"
            }
            Family::TorusEye => "torus R=2, r=1, rays restricted at the eye",
            Family::TorusEntry => "torus R=2, r=1, rays restricted at the bounding-sphere entry",
            Family::BarthEye => "Barth sextic, rays restricted at the eye",
            Family::BarthEntry => "Barth sextic, rays restricted at the bounding-box entry",
        }
    }

    /// Whether the family is indexed by camera distance rather than degree.
    pub fn is_ray(self) -> bool {
        Family::RAYS.contains(&self)
    }

    /// Whether the family is random (several seeded samples per degree).
    pub fn is_random(self) -> bool {
        matches!(
            self,
            Family::Planted | Family::Kac | Family::TeapotEliminant
        ) || self.is_ray()
    }
}

/// One polynomial of the suite and where to look for its roots.
#[derive(Clone, Debug)]
pub struct Case {
    /// Its family.
    pub family: Family,
    /// Degree (polynomial families) or camera distance (ray families), as the table key.
    pub param: f64,
    /// The polynomial as stored.
    pub poly: Poly<f64>,
    /// Search range `(lo, hi]`.
    pub lo: f64,
    /// Search range end.
    pub hi: f64,
    /// The exact polynomial before rounding to `f64`, when there is one (for the
    /// construction-error statistic of the torus families).
    pub exact: Option<QPoly>,
}

/// Legendre `P_n` exactly, by Bonnet's recurrence `(k + 1)P_{k+1} = (2k + 1)x·P_k − k·P_{k−1}`.
pub fn legendre(n: u32) -> QPoly {
    let x = Poly::new(vec![rat(0, 1), rat(1, 1)]);
    let (mut prev, mut cur) = (Poly::constant(rat(1, 1)), x.clone());
    if n == 0 {
        return prev;
    }
    for k in 1..n {
        let k = i64::from(k);
        let next = (&(&x * &cur).scale(&rat(2 * k + 1, 1)) - &prev.scale(&rat(k, 1)))
            .scale(&rat(1, k + 1));
        prev = cur;
        cur = next;
    }
    cur
}

/// The clustered family `x^d − 2(a x − 1)²` (exact integer coefficients).
pub fn mignotte(d: usize, a: i64) -> QPoly {
    let mut c = vec![Rat::from_integer(BigInt::from(0)); d.max(2) + 1];
    c[0] = rat(-2, 1);
    c[1] = rat(4 * a, 1);
    c[2] = rat(-2 * a * a, 1);
    c[d] = &c[d] + rat(1, 1);
    Poly::new(c)
}

/// The multiple-root family of degree `d` (see [`Family::Multiple`]).
pub fn multiple_root(d: usize) -> QPoly {
    let k = (d / 3).max(2).min(d);
    let m = (d - k) as i64;
    let mut roots = vec![rat(MULTIPLE_ROOT.0, MULTIPLE_ROOT.1); k];
    roots.extend((1..=m).map(|j| rat(3 * j - 1, 3 * m)));
    planted(&roots)
}

/// A standard normal sample (Box–Muller on two uniform draws).
fn normal(rng: &mut impl Rng) -> f64 {
    let u1: f64 = 1.0 - rng.r#gen::<f64>(); // (0, 1]
    let u2: f64 = rng.r#gen();
    (-2.0 * u1.ln()).sqrt() * (std::f64::consts::TAU * u2).cos()
}

/// `(−B, B]` with `B` the power of two at or above `p`'s root bound: holds every real root.
fn symmetric_range(p: &Poly<f64>) -> (f64, f64) {
    let b = p.root_bound().unwrap_or(1.0).max(1.0);
    let b = 2f64.powi(b.log2().ceil() as i32);
    (-b, b)
}

fn case(family: Family, param: f64, exact: QPoly) -> Case {
    let poly = exact.to_f64();
    let (lo, hi) = symmetric_range(&poly);
    Case {
        family,
        param,
        poly,
        lo,
        hi,
        exact: None,
    }
}

/// The tracer's recorded root queries (`crates/poly/tests/data/teapot_eliminants.txt`, whose
/// header says how they were made): lines `TAG lo hi x_tol n c0 … cn`.
pub const TEAPOT_ELIMINANTS: &str = include_str!("../../poly/tests/data/teapot_eliminants.txt");

/// Every recorded eliminant (tag `E`) with its recorded range `(lo, hi]`, in file order.
pub fn teapot_eliminant_queries() -> Vec<(Poly<f64>, f64, f64)> {
    TEAPOT_ELIMINANTS
        .lines()
        .filter_map(|line| {
            let mut fields = line.split_whitespace();
            if fields.next() != Some("E") {
                return None;
            }
            let nums: Vec<f64> = fields
                .map(|x| x.parse().expect("fixture numbers"))
                .collect();
            Some((Poly::new(nums[4..].to_vec()), nums[0], nums[1]))
        })
        .collect()
}

/// The recorded eliminants of degree `d`, each on its recorded range.
fn teapot_eliminants(d: usize) -> Vec<Case> {
    teapot_eliminant_queries()
        .into_iter()
        .filter(|(poly, _, _)| poly.degree() == d)
        .map(|(poly, lo, hi)| Case {
            family: Family::TeapotEliminant,
            param: d as f64,
            poly,
            lo,
            hi,
            exact: None,
        })
        .collect()
}

/// The cases of a degree-indexed family at degree `d` (`samples` draws for random families).
pub fn degree_cases(family: Family, d: usize, samples: usize, seed: u64) -> Vec<Case> {
    let param = d as f64;
    let mut rng = ChaCha8Rng::seed_from_u64(seed ^ ((d as u64) << 32) ^ family as u64);
    match family {
        Family::Wilkinson => vec![case(family, param, wilkinson(d as u32))],
        Family::ScaledWilkinson => {
            let roots: Vec<Rat> = (1..=d as i64).map(|k| rat(k, d as i64)).collect();
            vec![case(family, param, planted(&roots))]
        }
        Family::Chebyshev => vec![case(family, param, chebyshev(d as u32))],
        Family::Legendre => vec![case(family, param, legendre(d as u32))],
        Family::Clustered => vec![case(family, param, mignotte(d, MIGNOTTE_A))],
        Family::Multiple => vec![case(family, param, multiple_root(d))],
        Family::TeapotEliminant => teapot_eliminants(d),
        Family::Planted => (0..samples)
            .map(|_| {
                let roots: Vec<Rat> = (0..d)
                    .map(|_| {
                        let m = rng.gen_range(2..=1024i64);
                        rat(rng.gen_range(0..=m), m)
                    })
                    .collect();
                case(family, param, planted(&roots))
            })
            .collect(),
        Family::Kac => (0..samples)
            .map(|_| {
                let mut c: Vec<f64> = (0..=d).map(|_| normal(&mut rng)).collect();
                // A zero leading coefficient has probability 0; keep the degree regardless.
                if c[d] == 0.0 {
                    c[d] = 1.0;
                }
                let poly = Poly::new(c);
                let (lo, hi) = symmetric_range(&poly);
                Case {
                    family,
                    param,
                    poly,
                    lo,
                    hi,
                    exact: None,
                }
            })
            .collect(),
        _ => Vec::new(),
    }
}

/// The cases of a ray family at camera distance `dist`: `n` seeded rays.
pub fn ray_cases(family: Family, dist: f64, n: usize, seed: u64) -> Vec<Case> {
    let mut rng = ChaCha8Rng::seed_from_u64(seed ^ dist.to_bits() ^ family as u64);
    let rays = match family {
        Family::TorusEye => rays::torus_rays(SCENE_TORUS, dist, n, false, &mut rng),
        Family::TorusEntry => rays::torus_rays(SCENE_TORUS, dist, n, true, &mut rng),
        Family::BarthEye => rays::barth_rays(&rays::barth_sextic(), dist, n, false, &mut rng),
        Family::BarthEntry => rays::barth_rays(&rays::barth_sextic(), dist, n, true, &mut rng),
        _ => Vec::new(),
    };
    rays.into_iter()
        .map(|r| Case {
            family,
            param: dist,
            poly: r.poly,
            lo: r.lo,
            hi: r.hi,
            exact: r.exact,
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn legendre_matches_the_closed_forms() {
        // P_2 = (3x² − 1)/2, P_3 = (5x³ − 3x)/2 (Abramowitz & Stegun Table 22.9).
        assert_eq!(
            legendre(2),
            Poly::new(vec![rat(-1, 2), rat(0, 1), rat(3, 2)]),
            "P_2"
        );
        assert_eq!(
            legendre(3),
            Poly::new(vec![rat(0, 1), rat(-3, 2), rat(0, 1), rat(5, 2)]),
            "P_3"
        );
        assert_eq!(legendre(7).eval(&rat(1, 1)), rat(1, 1), "P_n(1) = 1");
    }

    #[test]
    fn clustered_and_multiple_families_have_the_planned_shape() {
        let m = mignotte(6, 10);
        assert_eq!(
            m,
            Poly::new(vec![
                rat(-2, 1),
                rat(40, 1),
                rat(-200, 1),
                rat(0, 1),
                rat(0, 1),
                rat(0, 1),
                rat(1, 1)
            ]),
            "x^6 − 2(10x − 1)²"
        );
        let q = multiple_root(9);
        assert_eq!(q.degree(), 9, "degree 9");
        assert_eq!(q.eval(&rat(1, 2)), rat(0, 1), "1/2 is a root");
        let dq = q.derivative().derivative();
        assert_eq!(dq.eval(&rat(1, 2)), rat(0, 1), "of multiplicity at least 3");
        // The recorded teapot eliminants cover the degrees the tracer met, on [0, 1] widened.
        let recorded: usize = (2..=18)
            .map(|d| {
                let cases = degree_cases(Family::TeapotEliminant, d, 1, 0);
                assert!(
                    cases
                        .iter()
                        .all(|c| c.poly.degree() == d && c.lo < 0.0 && c.hi > 1.0)
                );
                cases.len()
            })
            .sum();
        assert!(recorded > 100, "{recorded} recorded eliminants");
        assert!(
            !degree_cases(Family::TeapotEliminant, 17, 1, 0).is_empty(),
            "degree 17"
        );
        let cases = degree_cases(Family::Planted, 5, 3, 7);
        assert_eq!(cases.len(), 3, "three samples");
        assert!(
            cases
                .iter()
                .all(|c| c.poly.degree() == 5 && c.lo < 0.0 && c.hi >= 1.0),
            "degree 5, range covers [0, 1]"
        );
    }
}

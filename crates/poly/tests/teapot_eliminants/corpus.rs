//! The parser of `tests/data/teapot_eliminants.txt` (shared by the test binaries that use it).

use poly::Poly;

/// One recorded query: `p.real_roots(lo, hi, x_tol)`.
pub(crate) struct Query {
    pub(crate) tag: char,
    pub(crate) lo: f64,
    pub(crate) hi: f64,
    pub(crate) x_tol: f64,
    pub(crate) p: Poly<f64>,
}

pub(crate) fn corpus() -> Vec<Query> {
    let text = include_str!("../data/teapot_eliminants.txt");
    text.lines()
        .filter(|l| !l.starts_with('#') && !l.trim().is_empty())
        .map(|l| {
            let f: Vec<&str> = l.split_whitespace().collect();
            let num = |s: &str| s.parse::<f64>().expect("a number");
            let n: usize = f[4].parse().expect("a degree");
            let c: Vec<f64> = f[5..].iter().map(|s| num(s)).collect();
            assert_eq!(
                c.len(),
                n + 1,
                "degree {n} needs {} coefficients: {l}",
                n + 1
            );
            Query {
                tag: f[0].chars().next().expect("a tag"),
                lo: num(f[1]),
                hi: num(f[2]),
                x_tol: num(f[3]),
                p: Poly::new(c),
            }
        })
        .collect()
}

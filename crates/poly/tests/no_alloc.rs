//! The root queries a ray tracer makes per ray allocate nothing on the heap once their buffers
//! have grown: `Poly::real_roots_into` with a reused buffer and `Poly::smallest_root_with`,
//! over the teapot corpus (recorded eliminants of degree 8–17, more than 100 of them with an
//! exact factor `u^k`, plus their derivatives and cubics). `allocation-counter` counts the
//! allocations of this thread.

use poly::{RootOptions, RootStats};

#[path = "teapot_eliminants/corpus.rs"]
mod corpus;

#[test]
fn per_ray_root_queries_allocate_nothing_after_warm_up() {
    let corpus = corpus::corpus();
    let with_zero_factor = corpus.iter().filter(|q| q.p.coeff(0) == 0.0).count();
    assert!(
        with_zero_factor >= 100,
        "the x^k deflation path is exercised"
    );
    for tag in ['E', 'D', 'V'] {
        assert!(
            corpus.iter().any(|q| q.tag == tag),
            "query kind {tag} present"
        );
    }
    let mut roots = Vec::with_capacity(32);
    let mut stats = RootStats::default();
    let pass = |roots: &mut Vec<f64>, stats: &mut RootStats| {
        let mut found = 0;
        for qy in &corpus {
            let opts = RootOptions::new(qy.x_tol);
            roots.clear();
            qy.p.real_roots_into(qy.lo, qy.hi, &opts, stats, roots)
                .expect("valid query");
            found += roots.len();
            found += usize::from(
                qy.p.smallest_root_with(qy.lo, qy.hi, &opts, stats)
                    .is_some(),
            );
        }
        found
    };
    let warm = pass(&mut roots, &mut stats);
    let mut again = 0;
    let info = allocation_counter::measure(|| again = pass(&mut roots, &mut stats));
    assert_eq!(again, warm, "same answers");
    assert!(
        warm > corpus.len() / 2,
        "the corpus has roots to find: {warm}"
    );
    assert_eq!(
        stats.exact_fallbacks, 0,
        "the exact fallback (which allocates) was not needed"
    );
    assert_eq!(
        info.count_total,
        0,
        "heap allocations in {} queries",
        2 * corpus.len()
    );
}

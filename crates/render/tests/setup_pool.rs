//! The set-up of a render (surfaces, BVH) runs on the render's own thread pool, as the trace
//! does. It used to run on rayon's global pool: `--threads 1` still built a large scene's
//! hierarchy on every core, and a second pool of threads was started for it. This file holds
//! one test so that it runs in a process of its own, where nothing else starts the global pool.

use std::fmt::Write;
use std::path::Path;

use render::scene::parse_nff;
use render::{RenderOptions, render_scene};

/// A render with `threads = Some(1)` of a scene large enough to build its hierarchy's halves
/// in parallel leaves rayon's global pool unstarted: it can still be built afterwards.
#[test]
fn a_render_never_starts_the_global_pool() {
    let mut nff = String::from(
        "v\nfrom 0 0 60\nat 0 0 0\nup 0 1 0\nangle 40\nhither 1\nresolution 16 16\n\
         l 10 10 80\nf 1 0.5 0.2 0.8 0 0 0 1\n",
    );
    // 6 000 small spheres on a grid: above the build's parallel threshold (4 096 items).
    for i in 0..6000 {
        let (x, y, z) = (i % 20, (i / 20) % 20, i / 400);
        writeln!(nff, "s {x} {y} {z} 0.3").unwrap();
    }
    let scene = parse_nff(&nff, Path::new("grid.nff")).unwrap();
    let dir = tempfile::tempdir().unwrap();
    let opts = RenderOptions {
        output: Some(dir.path().join("grid.png")),
        threads: Some(1),
        ..RenderOptions::default()
    };
    let report = render_scene(&scene, None, &opts, &|_, _| {}).unwrap();
    assert_eq!(report.threads, 1);
    assert!(
        rayon::ThreadPoolBuilder::new()
            .num_threads(1)
            .build_global()
            .is_ok(),
        "the render started rayon's global pool"
    );
}

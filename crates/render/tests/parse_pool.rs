//! A large NFF text is read in parts on the thread pool it is loaded in, and in one pass
//! elsewhere: reading it outside any pool must not start rayon's global pool (which would
//! ignore `--threads`, as the set-up once did: `setup_pool.rs`). This file holds one test so
//! that it runs in a process of its own, where nothing else starts the global pool.

use std::fmt::Write;
use std::path::Path;

use render::scene::parse_nff;

/// A 20 000-sphere text (over the size read in parts) read outside any pool leaves the global
/// pool unstarted, and read inside a two-thread pool — in parts — gives the same scene.
#[test]
fn nff_is_read_in_parts_only_on_a_pool() {
    let mut nff = String::from(
        "v\nfrom 0 0 60\nat 0 0 0\nup 0 1 0\nangle 40\nhither 1\nresolution 16 16\nl 10 10 80\n",
    );
    for i in 0..20_000 {
        if i % 5000 == 0 {
            writeln!(nff, "f {} 0.5 0.2 0.8 0 0 0 1", f64::from(i) / 20_000.0).unwrap();
        }
        let (x, y, z) = (i % 20, (i / 20) % 20, i / 400);
        writeln!(nff, "s {x}.25 {y}.5 {z}.75 0.3").unwrap();
    }
    assert!(
        nff.len() > 1 << 18,
        "{} bytes: below the parts' threshold",
        nff.len()
    );
    let file = Path::new("grid.nff");
    let one_pass = parse_nff(&nff, file).unwrap();
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(2)
        .build()
        .unwrap();
    let in_parts = pool.install(|| parse_nff(&nff, file)).unwrap();
    assert!(*in_parts == *one_pass, "the scene read in parts differs");
    assert_eq!(in_parts.objects.len(), 20_000);
    assert!(
        rayon::ThreadPoolBuilder::new()
            .num_threads(1)
            .build_global()
            .is_ok(),
        "reading outside a pool started rayon's global pool"
    );
}

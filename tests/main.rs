//! Integration tests across `poly`, `groebner` and `render`: one test binary, one `mod` per
//! topic, to keep link time down (STYLE.md §7).

// Scene language: every file in scenes/ parses and round-trips; torus.scene matches the issue.
mod scene_files;
// Scene language: malformed inputs name line, column and key; fuzzed input never panics.
mod scene_errors;
// Tracer: sphere coverage vs projected disc, torus depth vs exact rational root, no re-hit of
// spawned rays, TORUS vs the equivalent ALGEBRAIC_SURFACE.
mod render_analytic;
// Tracer: golden 64×64 images of every scene (TOOLKIT_BLESS=1 re-blesses).
mod render_golden;
// The library entry point behind the CLI: atomic output, PFM depth, option overrides.
mod render_job;
// Bézier patches: the teapot by Gröbner and resultant, Newton reference, seams, lid apex.
mod bezier_teapot;
// Bézier patches: Stam's table (degrees 2, 4, 6 in u, 1 in v), the saddle's collapse 18 → 2,
// a random bicubic at degree 18.
mod bezier_degrees;
// Stability (issue 6): exact Sturm on Wilkinson-20 and Chebyshev-30.
mod stability_exact;
// Stability (issue 6): the certified f64 default on planted roots (d ≤ 16) and every family.
mod stability_f64;
// Stability (issue 6): torus and Barth ray polynomials at camera distance 10 000.
mod stability_rays;
// Scene BVH (issue 12): traversal equals brute force on random mixed scenes and flat boxes.
mod aggregate_bvh;
// NFF input (issue 12): every entity, file:line:col errors, format detection, SPD scenes.
mod nff_files;
// Cones and cylinders (issue 12): coverage and depth against closed forms; an SPD golden image.
mod render_cones;
// Every --isolation method on every scene of scenes/ agrees with the exact reference (issue 13).
mod isolation_scenes;

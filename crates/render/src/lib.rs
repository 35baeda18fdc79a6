//! A Whitted ray tracer for exact algebraic surfaces: spheres, planes, polygons, boxes,
//! superquadrics, tori and algebraic surfaces `F(x, y, z) = 0` of any degree, read from Stam's
//! scene command files (J. Stam 1988, thesis §2.3 and §4.2).
//!
//! Every implicit surface takes one path: restrict `F` to the ray, giving a polynomial in `t`
//! ([`Poly3::restrict_into`]), and ask [`poly`] for its smallest root in range. Shading is
//! Stam's illumination model, eq. 2.6–2.16 ([`whitted`]).
//!
//! # Layers
//!
//! Each module uses only the ones above it (checked by `.ci/module_graph.py`):
//!
//! ```text
//! trivariate, methods        F(x, y, z) and its restriction to a ray; how roots are solved
//!     │                      (RootMethods, PatchMethod and its groebner::Method mapping)
//! geometry                   rays, boxes, transforms, polygon normals, error bounds
//!     │
//! scene                      plain data (the model: control nets, PatchMethod, transforms)
//!     │                      and the scene language (lexer → syntax → build; expr, print)
//! stats, workspace           per-thread counters (per SurfaceKind) and scratch buffers
//!     │
//! surface                    the Surface trait and every shape (implicit path, Bézier mesh)
//!     │
//! aggregate                  the one bounding-volume hierarchy (scene objects, patch pieces)
//!     │
//! prepared                   the scene turned into primitives, solvers chosen once
//!     │
//! whitted, material, camera  the integrator: Stam's illumination model, textures, rays
//!     │
//! film, output               the pixel loop and its Film; PNG and PFM files
//!     │
//! options, pipeline          RenderOptions and render_scene: prepare, trace, write
//! ```
//!
//! # Tolerances
//!
//! Every tolerance of the crate, in one place (each constant's docs give the derivation).
//! "rel" is relative to the scale named; `u` is [`poly::UNIT_ROUNDOFF`], `γ(n)` Higham's
//! [`geometry::gamma`].
//!
//! | name | bounds | abs/rel | why this value |
//! |------|--------|---------|----------------|
//! | [`surface::ROOT_X_TOL_REL`] = 2⁻³³ | root of the ray polynomial, in `t` | rel. to the box diagonal / `\|d\|` | far below a pixel at any distance; refinement is superlinear, so it is cheap |
//! | [`surface::REDUCED_ROOT_X_TOL_REL`] = 2⁻²³ | root of a ray that only the double-double restriction decides, above the exact-restriction degree | rel. to the box diagonal / `\|d\|` | the last certified try before "undecided"; still far below a pixel; counted in `--stats` |
//! | [`surface::ENTRY_MARGIN_REL`] = 1e-9 | how far before a bounding-volume entry the root search starts | rel. to `\|t0\| + chord` | far above the slab test's rounding, so a hit on the entry face is kept |
//! | `PRUNE_SLACK_REL` = 2e-9 (`aggregate/bvh.rs`) | how far beyond the nearest hit so far a hierarchy node may start and still be visited | rel. to `\|entry\| + chord` | twice `ENTRY_MARGIN_REL` (asserted), so a hit reported just before its box's entry is never pruned by one it ties with |
//! | [`surface::SINGULAR_P_ERR_REL`] = 1e-9 | error box of a hit at a singular point (`∇F ≈ 0`) | rel. to the object's size | heuristic, only where `\|F\|/\|∇F\|` is meaningless (counted) |
//! | `SPHERE_CLIP_MARGIN` = 1e-9 | widening of a bounding/clipping sphere and its interval | rel. | far above the few roundings, so a touching ray is never clipped; the test also subtracts a bound on the rounding of `\|oc × d\|²`, which the margin alone does not cover once the origin is ~10⁵ radii away |
//! | `BALL_MARGIN_REL` = 2⁻²⁰ (`surface/sphere.rs`) | widening of a sphere's own bounding ball | rel. to the radius | room for the closed form's certifying intervals inside the clipped chord; few rays that miss the sphere pass the ball |
//! | [`surface::HIT_RESIDUAL_REL`] = 1e-7 | accepted 3-D residual `\|S(u, v) − R(t)\|` of a patch hit | rel. to piece diagonal + `\|O'\|` + `\|t'D\|` | 100 × groebner's `DEFAULT_F_TOL_REL` (asserted at compile time) |
//! | [`surface::HIT_P_ERR_REL`] = 4e-7 | error box of a patch hit point | rel. to piece diagonal + `\|p\|` | above the residual bound and the solver's `x_tol` (asserted) |
//! | [`surface::POWER_ZERO_REL`] = 1e-12 | power-basis coefficients snapped to zero | rel. to the net's largest coordinate | round-off residue of degree elevation and subdivision; moves the surface far less than the hit residual |
//! | `HULL_MARGIN_REL` = 1e-9 | the hull test's separating-plane margin | rel. to piece size + `\|O\|\|D\|` | above the `γ(4)` rounding of the dot products |
//! | `COLLAPSED_EDGE_REL` = 1e-12 | control points counted as one (collapsed edge) | rel. to patch size + coordinates | the data repeat the apex exactly; covers de Casteljau rounding |
//! | `DEGENERATE_NORMAL_REL` = 1e-10 | `\|S_u × S_v\|` taken as zero | rel. to `\|S_u\|\|S_v\|` (sine of the angle) | collapsed edges and folds only |
//! | `NORMAL_FALLBACK_STEP` = 1e-6 | first step of the fallback normal towards the patch centre | abs., in `(u, v)` | converges to the limit normal; `NORMAL_FALLBACK_TRIES` = 6 steps up to 2% |
//! | `offset_ray_origin`: `4u(\|p\|∞ + d)` | enlargement of a spawned ray's offset | rel. | exceeds the rounding of `p + d·n` (see its docs) |
//! | error boxes of hit points | `\|p − true hit\|` | abs., from `γ(n)` | residual `(\|F\| + γ(d+3)Σ\|a\|\|x\|^i…)/\|∇F\|` (implicit), pbrt-v4 §6.8 (transforms) |
//!
//! # Examples
//! ```
//! use glam::DVec3;
//! use render::scene::{Light, Object, Scene, ShapeKind, ValidScene};
//! use render::{PreparedScene, RenderSettings, render};
//!
//! let mut scene = Scene::default();
//! scene.objects.push(Object::new(ShapeKind::Torus {
//!     center: DVec3::ZERO,
//!     axis: DVec3::Z,
//!     major: 2.0,
//!     minor: 1.0,
//! }));
//! scene.lights.push(Light { source: DVec3::new(5.0, -5.0, 10.0), color: DVec3::ONE });
//! let scene = ValidScene::new(scene)?;
//! let prepared = PreparedScene::new(&scene)?;
//! let settings = RenderSettings { size: [32, 32], resolution: [1, 1], samples: 1, depth: true };
//! let out = render(&prepared, &scene.camera, &settings, &|_| {});
//! let centre_depth = out.film.depth.as_ref().unwrap()[16 * 32 + 16];
//! assert!(centre_depth.is_finite(), "the torus is in the middle of the view");
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

#![warn(unused_crate_dependencies)]

// The allocation counter and the random generators are dev-dependencies of the integration
// tests `tests/bezier_no_alloc.rs` and `tests/fuzz_scenes.rs` only; the unit-test build of the
// library sees them too.
#[cfg(test)]
use allocation_counter as _;
#[cfg(test)]
use rand as _;
#[cfg(test)]
use rand_chacha as _;

pub mod aggregate;
mod camera;
mod cancel;
mod film;
pub mod geometry;
mod material;
mod methods;
mod options;
mod output;
mod pipeline;
mod prepared;
pub mod scene;
mod stats;
pub mod surface;
mod trivariate;
pub mod whitted;
mod workspace;

/// The vector types of the public API (`DVec3` points, `Rgb` colours).
pub use glam;

pub use crate::camera::Camera;
pub use crate::cancel::{Cancel, Cancelled};
pub use crate::film::{Film, RenderOutput, RenderSettings, render, render_with_cancel};
pub use crate::methods::{PatchMethod, RootMethods};
pub use crate::options::RenderOptions;
pub use crate::output::{
    Gamma, OutputError, PendingOutputs, PngOptions, abandon_pending_outputs, encode_png, read_pfm,
    write_atomically, write_pfm, write_png,
};
pub use crate::pipeline::{
    RenderError, RenderReport, prepare_render, render_scene, render_scene_in,
    render_scene_with_cancel, thread_pool,
};
pub use crate::prepared::PreparedScene;
pub use crate::scene::Scene;
pub use crate::stats::{
    CertificationStats, Escalations, HIST_BINS, KindStats, PatchStats, PhaseTimes, SlowObject,
    SlowestCell, StatsReport, TraceStats,
};
pub use crate::trivariate::{Eval3, Poly3, RestrictScratch, Term3};
pub use crate::workspace::Workspace;

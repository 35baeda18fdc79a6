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
//! (aggregate)                the scene's acceleration structure (to come)
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
//! # Examples
//! ```
//! use glam::DVec3;
//! use render::scene::{Light, Object, Scene, ShapeKind};
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
//! let prepared = PreparedScene::new(&scene)?;
//! let settings = RenderSettings { size: [32, 32], resolution: [1, 1], samples: 1, depth: true };
//! let out = render(&prepared, &scene.camera, &settings, &|_| {});
//! let centre_depth = out.film.depth.as_ref().unwrap()[16 * 32 + 16];
//! assert!(centre_depth.is_finite(), "the torus is in the middle of the view");
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

pub mod aggregate;
mod camera;
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
pub use crate::film::{Film, RenderOutput, RenderSettings, render};
pub use crate::material::{surface_color, texture_color};
pub use crate::methods::{PatchMethod, RootMethods};
pub use crate::options::RenderOptions;
pub use crate::output::{
    Gamma, OutputError, PngOptions, read_pfm, write_atomically, write_pfm, write_png,
};
pub use crate::pipeline::{RenderError, RenderReport, render_scene};
pub use crate::prepared::{PreparedScene, Primitive};
pub use crate::scene::Scene;
pub use crate::stats::{HIST_BINS, KindStats, PatchStats, PhaseTimes, StatsReport, TraceStats};
pub use crate::trivariate::{Eval3, Poly3, RestrictScratch, Term3};
pub use crate::workspace::Workspace;

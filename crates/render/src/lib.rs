//! A Whitted ray tracer for exact algebraic surfaces: spheres, planes, polygons, boxes,
//! superquadrics, tori and algebraic surfaces `F(x, y, z) = 0` of any degree, read from Stam's
//! scene command files (J. Stam 1988, thesis §2.3 and §4.2).
//!
//! Every implicit surface takes one path: restrict `F` to the ray, giving a polynomial in `t`
//! ([`Poly3::restrict_into`]), and ask [`poly`] for its smallest root in range. Shading is
//! Stam's illumination model, eq. 2.6–2.16 ([`whitted`]).
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

mod camera;
mod cancel;
pub mod geometry;
mod job;
mod material;
mod options;
mod output;
mod poly3;
mod prepared;
mod renderer;
pub mod scene;
mod stats;
pub mod surface;
pub mod whitted;
mod workspace;

/// The vector types of the public API (`DVec3` points, `Rgb` colours).
pub use glam;

pub use crate::camera::Camera;
pub use crate::cancel::{Cancel, Cancelled};
pub use crate::job::{RenderError, RenderReport, render_scene, render_scene_with_cancel};
pub use crate::material::{surface_color, texture_color};
pub use crate::options::RenderOptions;
pub use crate::output::{
    Gamma, OutputError, PendingOutputs, PngOptions, abandon_pending_outputs, read_pfm,
    write_atomically, write_pfm, write_png,
};
pub use crate::poly3::{Eval3, Poly3, RestrictScratch, Term3};
pub use crate::prepared::{PreparedScene, Primitive};
pub use crate::renderer::{Film, RenderOutput, RenderSettings, render, render_with_cancel};
pub use crate::scene::Scene;
pub use crate::stats::{KindStats, PhaseTimes, StatsReport, TraceStats};
pub use crate::workspace::{RootMethods, Workspace};

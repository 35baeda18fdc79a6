//! Scenes: the typed model the tracer consumes ([`Scene`] and its parts), and the
//! scene-language front end that builds it from Stam's command files (§4.2).
//!
//! The model is plain data with public fields; build one in Rust or load a `.scene` file.

mod build;
mod error;
mod expr;
mod lexer;
mod model;
mod nff;
mod print;
mod syntax;

#[allow(unused_imports, reason = "used by the polygon surface")]
pub(crate) use model::polygon_normal;
pub use model::{
    BoundingVolume, CameraSpec, CheckerTexture, Illumination, ImageTexture, InvalidModel, Light,
    LookAtCamera, Material, Object, ObjectTransform, Rgb, Scene, SceneInvalid, ShapeKind,
    StamCamera, Texture, Viewport, World,
};

// The scene language (text → tokens → syntax tree → `Scene`); see
// `paper-notes/scene-language.md`.
pub use build::{MAX_IMAGE_SIDE, MAX_RECURSION_DEPTH, build, load, parse};
pub use error::{ErrorKind, SceneError, Span};
pub use expr::{Axis, BinOp, Expr, ExprKind, MAX_EQUATION_DEGREE};
pub use nff::{MAX_NFF_VERTICES, is_nff, nff_material, parse_nff};
pub use print::print;
pub use syntax::{
    Block, Command, Entry, Key, MAX_EXPR_DEPTH, MAX_NESTING, SceneAst, ShapeType, Spanned,
    TextureType, Value, parse_syntax,
};

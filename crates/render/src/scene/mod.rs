//! Scenes: the typed model the tracer consumes ([`Scene`] and its parts), and the
//! scene-language front end that builds it from Stam's command files (§4.2).
//!
//! The model is plain data with public fields; build one in Rust or load a `.scene` file.

mod build;
mod error;
mod expr;
mod lexer;
mod model;
mod print;
mod source;
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
pub use build::{
    MAX_IMAGE_PIXELS, MAX_IMAGE_SIDE, MAX_RECURSION_DEPTH, build, check_image_size, load, parse,
};
pub use error::{ErrorKind, MAX_MESSAGE_CHARS, MAX_QUOTED_CHARS, SceneError, Span, escape_message};
pub use expr::{Axis, BinOp, Expr, ExprKind, MAX_EQUATION_DEGREE};
pub use print::print;
pub use source::{MAX_CONTROL_POINT_BYTES, MAX_SCENE_BYTES, MAX_TEXTURE_BYTES, MAX_TEXTURE_TEXELS};
pub use syntax::{
    Block, Command, Entry, Key, MAX_EXPR_DEPTH, MAX_NESTING, SceneAst, ShapeType, Spanned,
    TextureType, Value, parse_syntax,
};

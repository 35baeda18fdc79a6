//! Scenes: the typed model the tracer consumes ([`Scene`] and its parts), and the
//! scene-language front end that builds it from Stam's command files (§4.2).
//!
//! The model is plain data with public fields; build one in Rust or load a `.scene` file.

mod bpt;
mod build;
mod control_net;
mod error;
mod expr;
#[cfg(test)]
mod expr_tests;
mod lexer;
mod model;
mod nff;
mod obj;
mod placement;
mod print;
mod source;
mod syntax;
mod valid_scene;

pub use bpt::{BptError, MAX_BPT_PATCHES, parse_bpt};
pub use control_net::{ControlNet, MAX_PATCH_DEGREE, PatchError};
pub use model::{
    BoundingVolume, CameraSpec, CheckerTexture, Illumination, ImageTexture, InvalidModel, Light,
    LookAtCamera, Material, MeshData, Object, ObjectTransform, Rgb, Scene, SceneInvalid, ShapeKind,
    StamCamera, Texture, Viewport, World,
};

// The scene language (text → tokens → syntax tree → `Scene`); see
// `paper-notes/scene-language.md`.
pub use build::{
    MAX_IMAGE_PIXELS, MAX_IMAGE_SIDE, MAX_RECURSION_DEPTH, build, check_image_size, load, parse,
};
pub use error::{ErrorKind, MAX_MESSAGE_CHARS, MAX_QUOTED_CHARS, SceneError, Span, escape_message};
pub use expr::{Axis, BinOp, Expr, ExprKind, MAX_EQUATION_DEGREE, MAX_TERM_PRODUCTS, Spanned};
pub use model::MAX_SUPERQUADRIC_POWER;
pub use nff::{MAX_NFF_VERTICES, is_nff, nff_material, parse_nff};
pub use obj::{ObjError, parse_obj};
pub use placement::Placement;
pub(crate) use placement::cone_axis;
pub use print::print;
pub use source::{
    MAX_CONTROL_POINT_BYTES, MAX_MESH_BYTES, MAX_SCENE_BYTES, MAX_TEXTURE_BYTES, MAX_TEXTURE_TEXELS,
};
pub use syntax::{
    Block, Command, Entry, Key, MAX_EXPR_DEPTH, MAX_NESTING, SceneAst, ShapeType, TextureType,
    Value, parse_syntax,
};
pub use valid_scene::ValidScene;

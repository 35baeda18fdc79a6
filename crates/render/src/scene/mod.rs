//! Scenes: the typed model the tracer consumes ([`Scene`] and its parts), and the
//! scene-language front end that builds it from Stam's command files (§4.2).
//!
//! The model is plain data with public fields; build one in Rust or load a `.scene` file.

mod model;

#[allow(unused_imports, reason = "used by the polygon surface")]
pub(crate) use model::polygon_normal;
pub use model::{
    BoundingVolume, CameraSpec, CheckerTexture, Illumination, ImageTexture, InvalidModel, Light,
    LookAtCamera, Material, Object, ObjectTransform, Rgb, Scene, SceneInvalid, ShapeKind,
    StamCamera, Texture, Viewport, World,
};

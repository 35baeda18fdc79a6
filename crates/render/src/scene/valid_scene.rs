//! [`ValidScene`]: a [`Scene`] that passed its checks, so that a loaded scene is validated
//! exactly once — by its loader, which can point at the offending text — and the renderer
//! ([`PreparedScene`](crate::PreparedScene)) takes it without checking it again (issue 10).

use std::ops::Deref;

use super::error::{ErrorKind, SceneError, Span};
use super::model::{Scene, SceneInvalid};

/// A [`Scene`] that passed [`Scene::validate`]. The loaders ([`parse`](super::parse),
/// [`load`](super::load), [`build`](super::build), [`parse_nff`](super::parse_nff)) return one;
/// a scene built in Rust becomes one through [`ValidScene::new`].
///
/// Reading goes through `Deref<Target = Scene>`; there is no mutable access, so the checks
/// stay true. To change a scene, take it out with [`ValidScene::into_scene`] and check it
/// again with [`ValidScene::new`].
///
/// # Examples
/// ```
/// use render::scene::{Object, Scene, ShapeKind, ValidScene};
/// use render::glam::DVec3;
///
/// let mut scene = Scene::default();
/// scene.objects.push(Object::new(ShapeKind::Sphere { center: DVec3::ZERO, radius: 1.0 }));
/// let valid = ValidScene::new(scene)?;
/// assert_eq!(valid.objects.len(), 1);
///
/// let mut broken = valid.into_scene();
/// broken.world.max_depth = 0;
/// assert!(ValidScene::new(broken).is_err());
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
#[derive(Clone, Debug, PartialEq)]
pub struct ValidScene(Scene);

impl ValidScene {
    /// Checks `scene` ([`Scene::validate`]) and wraps it.
    ///
    /// # Errors
    /// The first invariant `scene` breaks, naming the object or block.
    pub fn new(scene: Scene) -> Result<Self, SceneInvalid> {
        scene.validate()?;
        Ok(ValidScene(scene))
    }

    /// The scene, for changing it (check it again with [`ValidScene::new`]).
    pub fn into_scene(self) -> Scene {
        self.0
    }
}

impl Deref for ValidScene {
    type Target = Scene;

    fn deref(&self) -> &Scene {
        &self.0
    }
}

/// Where a loader read each part of a scene, so that the scene-level checks, run once at the
/// end of the load, report a failure at the block (or NFF line) it concerns.
#[derive(Debug, Default)]
pub(super) struct SceneSpans {
    /// One per object, in [`Scene::objects`] order.
    pub objects: Vec<Span>,
    /// One per light, in [`Scene::lights`] order.
    pub lights: Vec<Span>,
    /// The camera's block.
    pub camera: Option<Span>,
    /// The viewport's block.
    pub viewport: Option<Span>,
    /// The world block.
    pub world: Option<Span>,
}

impl SceneSpans {
    /// The loader's last step: [`Scene::validate`] without the shapes' own checks (the loader
    /// ran [`ShapeKind::validate`](super::ShapeKind::validate) on each shape as it read it, to
    /// point at the offending key), so no check runs twice. A failure is reported at the span
    /// of the part it concerns, else at `end`.
    pub(super) fn validate(&self, scene: Scene, end: &Span) -> Result<ValidScene, SceneError> {
        match scene.validate_except_shapes() {
            Ok(()) => Ok(ValidScene(scene)),
            Err(e) => {
                let span = match &e {
                    SceneInvalid::Object { index, .. } => self.objects.get(*index),
                    SceneInvalid::Light { index, .. } => self.lights.get(*index),
                    SceneInvalid::Camera { .. } => self.camera.as_ref(),
                    SceneInvalid::Viewport { .. } => self.viewport.as_ref(),
                    SceneInvalid::World { .. } => self.world.as_ref(),
                };
                Err(SceneError::at(
                    span.unwrap_or(end),
                    ErrorKind::Model {
                        reason: e.to_string(),
                    },
                ))
            }
        }
    }
}

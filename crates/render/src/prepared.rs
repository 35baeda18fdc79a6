//! [`PreparedScene`]: the scene turned into traceable primitives (surfaces built, transforms
//! composed, polynomials precomputed) — what the integrator reads.

use crate::geometry::{Bounds3, Transform};
use crate::scene::{
    BoundingVolume, Light, Material, Scene, SceneInvalid, ShapeKind, Texture, World,
};
use crate::surface::{
    AaBox, Algebraic, Implicit, ImplicitFn, Plane, Polygon, Sphere, Superquadric, Surface, Torus,
    Transformed,
};
use crate::workspace::RootMethods;

/// A surface with its material: Surface + Material = Object (STYLE.md §6).
#[derive(Debug)]
pub struct Primitive {
    /// The geometry, in world space.
    pub surface: Box<dyn Surface>,
    /// How it is lit.
    pub material: Material,
}

/// Everything the integrator needs, built once per render.
#[derive(Debug)]
pub struct PreparedScene {
    /// The objects.
    pub primitives: Vec<Primitive>,
    /// The lights.
    pub lights: Vec<Light>,
    /// World settings.
    pub world: World,
    /// Textures referenced by materials.
    pub textures: Vec<Texture>,
    /// The root finder of the implicit surfaces (default: certified Bernstein).
    pub roots: RootMethods,
}

impl PreparedScene {
    /// Validates `scene` and builds its surfaces.
    pub fn new(scene: &Scene) -> Result<Self, SceneInvalid> {
        scene.validate()?;
        let mut primitives = Vec::with_capacity(scene.objects.len());
        for (index, object) in scene.objects.iter().enumerate() {
            let bad = |key, reason| SceneInvalid::Object {
                index,
                error: crate::scene::InvalidModel::new(key, reason),
            };
            let world_from_object = Transform::from_object(&object.transform)
                .ok_or_else(|| bad("Transform", "is singular"))?;
            let surface = build_surface(&object.shape, &object.bounding, &world_from_object)
                .ok_or_else(|| bad("Type", "has degenerate geometry"))?;
            primitives.push(Primitive {
                surface,
                material: object.material.clone(),
            });
        }
        Ok(PreparedScene {
            primitives,
            lights: scene.lights.clone(),
            world: scene.world.clone(),
            textures: scene.textures.clone(),
            roots: RootMethods::default(),
        })
    }
}

/// Places `s` with `m`, skipping the wrapper for the identity.
fn place<S: Surface + 'static>(s: S, m: &Transform) -> Box<dyn Surface> {
    if m.is_identity() {
        Box::new(s)
    } else {
        Box::new(Transformed::new(s, *m))
    }
}

/// An implicit surface clipped by the scene's `Bounding volume` (in the shape's coordinates).
fn implicit<F: ImplicitFn>(f: F, bounding: &BoundingVolume) -> Implicit<F> {
    match *bounding {
        BoundingVolume::None => Implicit::new(f, None),
        BoundingVolume::Box { min, max } => Implicit::new(f, Some(Bounds3::new(min, max))),
        BoundingVolume::Sphere { center, radius } => {
            Implicit::new(f, None).with_clip_sphere(center, radius)
        }
    }
}

/// Builds the world-space surface of one shape. `bounding` is in the shape's coordinates;
/// shapes placed by an internal frame (torus) get it through the same frame. `None` for
/// degenerate geometry (the scene builder calls it to locate that error).
pub(crate) fn build_surface(
    shape: &ShapeKind,
    bounding: &BoundingVolume,
    world_from_object: &Transform,
) -> Option<Box<dyn Surface>> {
    Some(match shape {
        ShapeKind::Sphere { center, radius } => place(
            implicit(Sphere::new(*center, *radius), bounding),
            world_from_object,
        ),
        ShapeKind::Plane { origin, normal } => place(
            implicit(Plane::new(*origin, *normal), bounding),
            world_from_object,
        ),
        ShapeKind::Polygon { vertices } => place(Polygon::new(vertices)?, world_from_object),
        ShapeKind::Triangle { vertices } => place(Polygon::new(vertices)?, world_from_object),
        ShapeKind::Box { min, max } => place(AaBox::new(*min, *max), world_from_object),
        ShapeKind::Superquadric {
            center,
            size,
            power,
        } => {
            let frame = Transform::new(glam::DAffine3::from_translation(*center))?;
            let m = world_from_object.compose(&frame)?;
            place(Superquadric::new(*size, *power), &m)
        }
        ShapeKind::Torus {
            center,
            axis,
            major,
            minor,
        } => {
            // Canonical torus about z, placed by a rigid frame; the user box is expressed in
            // the object's coordinates, so map it into the frame's.
            let frame = if axis.x == 0.0 && axis.y == 0.0 && axis.z > 0.0 {
                Transform::new(glam::DAffine3::from_translation(*center))?
            } else {
                Transform::frame(*center, *axis)?
            };
            let inverse = frame.inverse();
            let local = match *bounding {
                BoundingVolume::None => BoundingVolume::None,
                BoundingVolume::Box { min, max } => {
                    let b = inverse.apply_bounds(&Bounds3::new(min, max));
                    BoundingVolume::Box {
                        min: b.min,
                        max: b.max,
                    }
                }
                // The frame is rigid: the sphere keeps its radius.
                BoundingVolume::Sphere { center, radius } => BoundingVolume::Sphere {
                    center: inverse.apply_point(center),
                    radius,
                },
            };
            let m = world_from_object.compose(&frame)?;
            place(implicit(Torus::new(*major, *minor), &local), &m)
        }
        ShapeKind::Algebraic { poly } => place(
            implicit(Algebraic::new(poly.clone()), bounding),
            world_from_object,
        ),
        ShapeKind::BezierPatches { patches, method } => place(
            crate::surface::BezierMesh::new(patches.clone(), *method)?,
            world_from_object,
        ),
    })
}

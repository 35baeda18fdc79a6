//! [`PreparedScene`]: the scene turned into traceable primitives (surfaces built, transforms
//! composed, polynomials precomputed) — what the integrator reads.

use rayon::prelude::*;

use crate::aggregate::{Aggregate, PRUNE_SLACK_REL};
use crate::geometry::{Bounds3, Transform};
use crate::methods::{PatchMethod, RootMethods};
use crate::scene::{
    BoundingVolume, Light, Material, Object, Placement, SceneInvalid, ShapeKind, Texture,
    ValidScene, World, cone_axis,
};
use crate::surface::{
    AaBox, Algebraic, BezierMesh, Implicit, ImplicitFn, Plane, Polygon, Sphere, Superquadric,
    Surface, Torus, Transformed,
};

/// Everything the integrator needs, built once per render.
#[derive(Debug)]
pub struct PreparedScene {
    /// The objects' geometry, in world space: object `i` is `surfaces[i]` lit by
    /// [`material(i)`](Self::material) (Surface + Material = Object, STYLE.md §6). Separate
    /// arrays, not one of pairs: a ray's item tests reach only the surfaces, and a dense array
    /// of them (16 bytes an object) stays in cache where one with the materials (136 bytes an
    /// object) missed it on every test of the 66 430-sphere scene (issue 12).
    pub surfaces: Vec<Box<dyn Surface>>,
    /// The distinct materials, as [`material_of`](Self::material_of) indexes them.
    pub materials: Vec<Material>,
    /// Object `i`'s index into [`materials`](Self::materials). Objects in a row with equal
    /// materials share one entry (an NFF `f` line lights every object after it): balls-s5's
    /// 66 431 objects have 2, and a copy per object was 8 MB of its peak memory (issue 12).
    pub material_of: Vec<u32>,
    /// The lights.
    pub lights: Vec<Light>,
    /// World settings.
    pub world: World,
    /// Textures referenced by materials.
    pub textures: Vec<Texture>,
    /// The primitives' BVH (bounded ones) and the list of unbounded ones, built once here.
    pub aggregate: Aggregate,
}

// The BVH's pruning slack covers the implicit surfaces' search below their box entry, so the
// traversal finds exactly the brute-force nearest hit (aggregate::PRUNE_SLACK_REL).
const _: () = assert!(
    PRUNE_SLACK_REL >= 2.0 * crate::surface::ENTRY_MARGIN_REL,
    "the BVH could prune a hit the surface finds below its box entry"
);

impl PreparedScene {
    /// Builds the surfaces of `scene` with the default solvers (certified Bernstein isolation
    /// with Newton–bisection; each Bézier object's own `Method`). The scene was validated when
    /// it became a [`ValidScene`] and is not checked again.
    ///
    /// # Errors
    /// [`SceneInvalid::Object`] for geometry that passed the model's checks but cannot be
    /// placed (a singular transform) or built (degenerate geometry).
    pub fn new(scene: &ValidScene) -> Result<Self, SceneInvalid> {
        Self::with_methods(scene, RootMethods::default(), None)
    }

    /// Builds the surfaces of `scene`: implicit surfaces find roots with `roots`, Bézier
    /// objects eliminate with `patch_method` when given (`render --patch-method`), else with
    /// their own `Method`. This is where the solver choices reach the surfaces, once per render
    /// (`crate::methods`).
    ///
    /// # Errors
    /// As [`PreparedScene::new`].
    pub fn with_methods(
        scene: &ValidScene,
        roots: RootMethods,
        patch_method: Option<PatchMethod>,
    ) -> Result<Self, SceneInvalid> {
        let methods = Methods {
            roots,
            patch_method,
        };
        // Each object's surface is built on its own, on the current rayon pool: a large scene's
        // surfaces are tens of thousands of allocations, whose first touches of fresh memory
        // are most of the work (`paper-notes/bvh.md`, nineteenth session).
        let surfaces = match scene
            .objects
            .par_iter()
            .enumerate()
            .map(|(index, object)| surface_of(index, object, &methods))
            .collect::<Result<Vec<_>, _>>()
        {
            Ok(surfaces) => surfaces,
            // The error of the first failing object, whichever the parallel build met first.
            Err(met) => {
                let first = scene
                    .objects
                    .iter()
                    .enumerate()
                    .find_map(|(index, object)| surface_of(index, object, &methods).err());
                return Err(first.unwrap_or(met));
            }
        };
        let mut materials: Vec<Material> = Vec::new();
        let mut material_of = Vec::with_capacity(scene.objects.len());
        for (index, object) in scene.objects.iter().enumerate() {
            if materials.last() != Some(&*object.material) {
                materials.push(Material::clone(&object.material));
            }
            material_of.push(u32::try_from(materials.len() - 1).map_err(|_| {
                SceneInvalid::Object {
                    index,
                    error: crate::scene::InvalidModel::new(
                        "Type",
                        "is beyond 2³² distinct materials",
                    ),
                }
            })?);
        }
        Ok(PreparedScene {
            aggregate: Aggregate::new(surfaces.iter().map(|s| s.bounds())),
            surfaces,
            materials,
            material_of,
            lights: scene.lights.clone(),
            world: scene.world.clone(),
            textures: scene.textures.clone(),
        })
    }

    /// How object `index` is lit.
    #[inline]
    pub fn material(&self, index: usize) -> &Material {
        &self.materials[self.material_of[index] as usize]
    }
}

/// The solver choices of one render, as [`PreparedScene::with_methods`] received them.
struct Methods {
    roots: RootMethods,
    patch_method: Option<PatchMethod>,
}

/// The world-space surface of object `index`.
///
/// # Errors
/// As [`PreparedScene::new`].
fn surface_of(
    index: usize,
    object: &Object,
    methods: &Methods,
) -> Result<Box<dyn Surface>, SceneInvalid> {
    let bad = |error| SceneInvalid::Object { index, error };
    // The builder checked the same placement where the keys have places.
    let placement = object.placement().map_err(bad)?;
    build_surface(object, &placement, methods).ok_or_else(|| {
        bad(crate::scene::InvalidModel::new(
            "Type",
            "has degenerate geometry",
        ))
    })
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
fn implicit<F: ImplicitFn>(f: F, bounding: &BoundingVolume, roots: RootMethods) -> Implicit<F> {
    let clipped = match *bounding {
        BoundingVolume::None => Implicit::new(f, None),
        BoundingVolume::Box { min, max } => Implicit::new(f, Some(Bounds3::new(min, max))),
        BoundingVolume::Sphere { center, radius } => {
            Implicit::new(f, None).with_clip_sphere(center, radius)
        }
    };
    clipped.with_root_methods(roots)
}

/// Builds the world-space surface of one object placed by `placement`. The shape's bounding
/// volume is in the object's coordinates; shapes with a frame of their own (torus) get it
/// through that frame. `None` only for a shape [`ShapeKind::validate`] refuses.
fn build_surface(
    object: &Object,
    placement: &Placement,
    methods: &Methods,
) -> Option<Box<dyn Surface>> {
    let roots = methods.roots;
    let bounding = &object.bounding;
    // The identity frame for shapes given in object coordinates: then this is
    // `world_from_object`.
    let world_from_shape = &placement.world_from_shape;
    Some(match &object.shape {
        ShapeKind::Sphere { center, radius } => place(
            implicit(Sphere::new(*center, *radius), bounding, roots),
            world_from_shape,
        ),
        ShapeKind::Plane { origin, normal } => place(
            implicit(Plane::new(*origin, *normal), bounding, roots),
            world_from_shape,
        ),
        ShapeKind::Polygon { vertices } => place(Polygon::new(vertices)?, world_from_shape),
        ShapeKind::Triangle { vertices } => place(Polygon::new(vertices)?, world_from_shape),
        ShapeKind::Box { min, max } => place(AaBox::new(*min, *max), world_from_shape),
        ShapeKind::Superquadric { size, power, .. } => place(
            Superquadric::new(*size, *power).with_root_methods(roots),
            world_from_shape,
        ),
        ShapeKind::Torus { major, minor, .. } => {
            // The canonical torus about z; the user box is in the object's coordinates, so
            // map it into the frame's.
            let inverse = placement.object_from_shape.inverse();
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
            place(
                implicit(Torus::new(*major, *minor), &local, roots),
                world_from_shape,
            )
        }
        ShapeKind::Algebraic { poly } => place(
            implicit(Algebraic::new(poly.clone()), bounding, roots),
            world_from_shape,
        ),
        ShapeKind::BezierPatches { patches, method } => place(
            BezierMesh::new(patches, methods.patch_method.unwrap_or(*method))?,
            world_from_shape,
        ),
        ShapeKind::Cone {
            base,
            base_radius,
            apex,
            apex_radius,
            caps,
        } => {
            // The canonical cone along z from the base, placed by its frame (as the torus).
            let (height, _) = cone_axis(*base, *apex).ok()?;
            let cone = crate::surface::Cone::new(*base_radius, *apex_radius, height, *caps)
                .with_root_methods(methods.roots);
            place(cone, world_from_shape)
        }
        ShapeKind::SmoothPolygon { vertices, normals } => place(
            crate::surface::SmoothPolygon::new(vertices, normals)?,
            world_from_shape,
        ),
        ShapeKind::Mesh { mesh } => {
            place(crate::surface::TriangleMesh::new(mesh)?, world_from_shape)
        }
    })
}

#[cfg(test)]
mod tests {
    use glam::DVec3;

    use super::*;
    use crate::geometry::Ray;
    use crate::scene::{ControlNet, Object, Scene};
    use crate::workspace::Workspace;

    /// Objects in a row with one material share its entry, and every object is lit by its
    /// own material whatever the sharing (a dedup that compared with the wrong entry would
    /// light the last sphere red).
    #[test]
    fn objects_in_a_row_share_their_material() {
        let sphere = |x: f64| ShapeKind::Sphere {
            center: DVec3::new(x, 0.0, 0.0),
            radius: 0.5,
        };
        let red = Material {
            cs: crate::scene::Rgb::new(1.0, 0.0, 0.0),
            ..Material::default()
        };
        let mut scene = Scene::default();
        for (x, material) in [
            (0.0, Material::default()),
            (1.0, Material::default()),
            (2.0, red.clone()),
            (3.0, Material::default()),
        ] {
            let mut object = Object::new(sphere(x));
            object.material = material.into();
            scene.objects.push(object);
        }
        let valid = ValidScene::new(scene.clone()).unwrap();
        let prepared = PreparedScene::new(&valid).unwrap();
        assert_eq!(
            prepared.materials.len(),
            3,
            "two runs of white around the red one"
        );
        assert_eq!(prepared.material_of, vec![0, 0, 1, 2]);
        for (i, object) in scene.objects.iter().enumerate() {
            assert_eq!(prepared.material(i), &*object.material, "object {i}");
        }
    }

    /// `render --isolation` reaches cones and cylinders: they were built with the default
    /// root methods whatever the render asked for (found merging the scene BVH branch), so the
    /// exact reference render still traced them by Bernstein isolation. The same ray through
    /// a closed cylinder must leave different solver statistics under `Exact` and the default.
    #[test]
    fn isolation_method_reaches_cones() {
        let mut scene = Scene::default();
        scene.objects.push(Object::new(ShapeKind::Cone {
            base: DVec3::ZERO,
            base_radius: 1.0,
            apex: DVec3::new(0.0, 0.0, 2.0),
            apex_radius: 0.5,
            caps: true,
        }));
        let scene = ValidScene::new(scene).unwrap();
        let ray = Ray::new(DVec3::new(0.1, -5.0, 1.0), DVec3::new(0.0, 1.0, 0.05));
        let stats_with = |isolation| {
            let roots = RootMethods {
                isolation,
                ..RootMethods::default()
            };
            let prepared = PreparedScene::with_methods(&scene, roots, None).unwrap();
            let mut ws = Workspace::new();
            let hit = prepared.surfaces[0].intersect(&ray, 0.0..f64::INFINITY, &mut ws);
            assert!(hit.is_some(), "the ray crosses the cone");
            ws.stats.roots.clone()
        };
        assert_ne!(
            stats_with(poly::IsolationMethod::Exact),
            stats_with(poly::IsolationMethod::Bernstein),
            "the cone solved with the render's isolation method"
        );
    }

    /// `render --patch-method` reaches the surfaces through `with_methods` (it used to be applied
    /// by cloning the whole scene in `render_scene`): a Gröbner object prepared with a resultant
    /// override solves by the resultant, which reports no basis (`basis_size` 0), while without
    /// the override every solve reports Stam's basis.
    #[test]
    fn patch_method_override_reaches_the_mesh() {
        let saddle = [
            (-1.0, -1.0, 1.0),
            (-1.0, 1.0, -1.0),
            (1.0, -1.0, -1.0),
            (1.0, 1.0, 1.0),
        ]
        .map(|(x, y, z)| DVec3::new(x, y, z));
        let mut scene = Scene::default();
        scene.objects.push(Object::new(ShapeKind::BezierPatches {
            patches: vec![ControlNet::new(1, 1, saddle.to_vec()).unwrap()],
            method: PatchMethod::Groebner,
        }));
        let scene = ValidScene::new(scene).unwrap();
        let ray = Ray::new(DVec3::new(0.3, -0.4, 5.0), DVec3::new(0.01, 0.02, -1.0));
        let basis_free_solves = |patch_method| {
            let prepared =
                PreparedScene::with_methods(&scene, RootMethods::default(), patch_method).unwrap();
            let mut ws = Workspace::new();
            let hit = prepared.surfaces[0].intersect(&ray, 0.0..f64::INFINITY, &mut ws);
            assert!(hit.is_some(), "the ray crosses the saddle");
            let p = &ws.stats.patches;
            assert!(p.solves > 0, "the algebra ran");
            (p.basis_size[0], p.solves)
        };
        let (without_basis, solves) = basis_free_solves(Some(PatchMethod::Resultant));
        assert_eq!(without_basis, solves, "every solve by the resultant");
        let (without_basis, _) = basis_free_solves(None);
        assert_eq!(
            without_basis, 0,
            "the object's own Gröbner method otherwise"
        );
    }
}

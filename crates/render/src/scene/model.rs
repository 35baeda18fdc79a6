//! The scene model: typed, validated, plain data that the tracer consumes.
//!
//! The scene-language front end (`scene::syntax` → `scene::build`) produces a [`Scene`]; tests
//! and library users may also build one directly in Rust. Every field is public and documented;
//! nothing here does I/O or rendering. Shapes are an enum with typed fields (STYLE.md §6), so
//! strings are dispatched once, in the parser.
//!
//! Vectors and points are `glam::DVec3`. Colours are [`Rgb`], linear RGB with each component
//! nominally in `[0, 1]` (Stam §2.3.6).
//!
//! # Examples
//! ```
//! use render::scene::{Object, Scene, ShapeKind};
//! use glam::{DAffine3, DMat3, DVec3};
//! let mut scene = Scene::default();
//! scene.objects.push(Object::new(ShapeKind::Sphere { center: DVec3::ZERO, radius: 1.0 }));
//! assert!(scene.validate().is_ok());
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

use std::path::PathBuf;
use std::sync::Arc;

use glam::{DAffine3, DMat3, DVec3};

use super::control_net::ControlNet;
use crate::geometry::{Transform, polygon_normal, unit};
use crate::methods::PatchMethod;
use crate::trivariate::Poly3;

/// Derivation, measured: up to 640 the certified f64 isolation renders a box-filling
/// superquadric as fast as a torus per root degree; from about 700 its bounds stop
/// certifying and every ray falls back to exact rational arithmetic on a degree-`p`
/// polynomial (minutes per pixel), and from 1030 `C(p, p/2)` overflows `f64` and the surface
/// vanishes. 512, the power of two below the cliff, leaves a margin for rays that graze an
/// edge; a power above ~100 is already indistinguishable from a box at any image size.
pub const MAX_SUPERQUADRIC_POWER: u32 = 512;

/// A linear RGB colour: `x` is red, `y` green, `z` blue; nominally each in `[0, 1]`.
pub type Rgb = DVec3;

/// A complete scene: world settings, camera, lights, objects, viewport and output.
#[derive(Clone, Debug, PartialEq)]
pub struct Scene {
    /// Background, shadows, recursion depth, attenuation (`#world`).
    pub world: World,
    /// The camera (`#camera`).
    pub camera: CameraSpec,
    /// The point lights (`#light`, any number).
    pub lights: Vec<Light>,
    /// The objects (`#object`), in file order.
    pub objects: Vec<Object>,
    /// Image size and Stam's preview resolution (`#viewport`).
    pub viewport: Viewport,
    /// Where to save the image (`#save File Name = …`), relative to the current directory;
    /// the build step resolves it. `None` when the scene names no file.
    pub output: Option<PathBuf>,
    /// Textures referenced by [`Material::texture`] (`#texture`), already loaded by the build
    /// step.
    pub textures: Vec<Texture>,
}

impl Default for Scene {
    /// An empty scene: default world, a camera at `(0, −8, 5)` looking at the origin with
    /// `z` up and a 50° field, no lights, no objects, a 256×256 viewport, no output file.
    fn default() -> Self {
        Scene {
            world: World::default(),
            camera: CameraSpec::LookAt(LookAtCamera {
                eye: DVec3::new(0.0, -8.0, 5.0),
                look_at: DVec3::ZERO,
                up: DVec3::Z,
                view_field_deg: 50.0,
            }),
            lights: Vec::new(),
            objects: Vec::new(),
            viewport: Viewport::default(),
            output: None,
            textures: Vec::new(),
        }
    }
}

/// Global settings (`#world`, Stam §4.2.1).
#[derive(Clone, Debug, PartialEq)]
pub struct World {
    /// Colour of rays that hit nothing (`BackGnd`).
    pub background: Rgb,
    /// Whether shadow rays are traced (`Shadows = ON|OFF`).
    pub shadows: bool,
    /// Maximum recursion depth: a primary ray has depth 1 and no ray deeper than this is
    /// traced (`MaxDepth`, Stam's `MAX_NB_RECUR = 5`).
    pub max_depth: u32,
    /// Whether intensities are attenuated with distance (`Attenuation = ON|OFF`, Stam §2.3.6).
    pub attenuation: bool,
}

impl Default for World {
    /// Black background, shadows on, depth 5, no attenuation.
    fn default() -> Self {
        World {
            background: Rgb::ZERO,
            shadows: true,
            max_depth: 5,
            attenuation: false,
        }
    }
}

/// How the camera is specified (`#camera`): either of the two forms.
#[derive(Clone, Debug, PartialEq)]
pub enum CameraSpec {
    /// Stam's form (Annexe B `ProjectPlane`).
    Stam(StamCamera),
    /// Eye / look-at / up form.
    LookAt(LookAtCamera),
}

/// Stam's camera (§4.2.1, figure 4.2; Annexe B `GetCamera`, `ProjectPlane`).
///
/// The eye sits at `center + R·(0, 0, distance + focal)` and looks along `−R·z` through a
/// square projection window at `center + R·(0, 0, distance)`, where `R` is built from the
/// three rotation angles.
#[derive(Clone, Debug, PartialEq)]
pub struct StamCamera {
    /// Distance from the eye to the projection window (`Focal`).
    pub focal: f64,
    /// Distance from the centre to the projection window (`Distance`).
    pub distance: f64,
    /// Full opening angle of the window's diagonal, in degrees (`ViewField`).
    pub view_field_deg: f64,
    /// `Rotation = (a1, a2, a3)` in degrees, read as Stam's `GetCamera` does:
    /// `(balance, left_right, top_bottom)`.
    pub rotation_deg: DVec3,
    /// The point the camera turns around (`Center`).
    pub center: DVec3,
}

/// The eye / look-at camera.
#[derive(Clone, Debug, PartialEq)]
pub struct LookAtCamera {
    /// Eye position (`Eye`).
    pub eye: DVec3,
    /// A point on the view axis (`LookAt`).
    pub look_at: DVec3,
    /// Up direction; need not be orthogonal to the view axis but must not be parallel (`Up`).
    pub up: DVec3,
    /// Vertical field of view in degrees (`ViewField`).
    pub view_field_deg: f64,
}

/// A point light (`#light`).
#[derive(Clone, Debug, PartialEq)]
pub struct Light {
    /// Position (`Source`).
    pub source: DVec3,
    /// Intensity per channel, `I_j` in Stam eq. 2.8–2.9 (`Color`).
    pub color: Rgb,
}

/// The image raster (`#viewport`).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Viewport {
    /// Width and height in pixels (`Size = (w, h)`).
    pub size: [u32; 2],
    /// Stam's preview resolution (`Resolution = (rx, ry)`): one primary ray per `rx × ry`
    /// block of pixels; `[1, 1]` traces every pixel.
    pub resolution: [u32; 2],
}

impl Default for Viewport {
    /// 256×256, full resolution.
    fn default() -> Self {
        Viewport {
            size: [256, 256],
            resolution: [1, 1],
        }
    }
}

/// One object: a shape, how it is lit, an optional bounding box and a placement.
#[derive(Clone, Debug, PartialEq)]
pub struct Object {
    /// The geometry, in the object's own coordinates.
    pub shape: ShapeKind,
    /// The illumination parameters, shared by reference: the objects an NFF `f` line lights
    /// hold one material, not a 120-byte copy each (a third of a parsed object; issue 12,
    /// `paper-notes/nff.md` §1).
    pub material: Arc<Material>,
    /// An optional bounding volume, in the same coordinates as the shape parameters (before
    /// [`Object::transform`]). The tracer always computes a box for bounded shapes itself;
    /// a user box only tightens it (and is required for no shape).
    pub bounding: BoundingVolume,
    /// Placement in the world: scale, then rotate, then translate.
    pub transform: ObjectTransform,
}

impl Object {
    /// An object with the given shape, the default material, no bounding volume and the
    /// identity transform.
    pub fn new(shape: ShapeKind) -> Self {
        Object {
            shape,
            material: Arc::default(),
            bounding: BoundingVolume::None,
            transform: ObjectTransform::default(),
        }
    }
}

/// The geometry of an object, with typed parameters. Every surface module documents its
/// scene-file syntax.
///
/// `#[non_exhaustive]`: Bézier patches and meshes will be added here.
#[derive(Clone, Debug, PartialEq)]
#[non_exhaustive]
pub enum ShapeKind {
    /// `|p − center|² = radius²` (`Center`, `Radius` or `Radius^2`).
    Sphere {
        /// Centre.
        center: DVec3,
        /// Radius, positive.
        radius: f64,
    },
    /// The plane through `origin` with normal `normal` (`Origin`, `Normal`); two-sided.
    Plane {
        /// A point of the plane.
        origin: DVec3,
        /// Normal direction, non-zero (need not be unit length).
        normal: DVec3,
    },
    /// A planar convex polygon, vertices in order (Stam's four-sided `a b c d`).
    Polygon {
        /// At least three coplanar vertices, in order around the boundary.
        vertices: Vec<DVec3>,
    },
    /// A triangle (`a b c`).
    Triangle {
        /// The three vertices.
        vertices: [DVec3; 3],
    },
    /// An axis-aligned box (`Min`, `Max`).
    Box {
        /// The lowest corner.
        min: DVec3,
        /// The highest corner, `max > min` componentwise.
        max: DVec3,
    },
    /// Kuchkuda's superquadric (§3.5), `|x/sx|^p + |y/sy|^p + |z/sz|^p = 1` about `center`.
    Superquadric {
        /// Centre.
        center: DVec3,
        /// Half-extents `(sx, sy, sz)`, positive: the shape fills the box `center ± size`.
        size: DVec3,
        /// The exponent `p`, an integer ≥ 1 (so each octant piece is a polynomial).
        power: u32,
    },
    /// A torus: the points at distance `minor` from the circle of radius `major` about
    /// `axis` through `center`.
    Torus {
        /// Centre.
        center: DVec3,
        /// Axis of revolution, non-zero (need not be unit length).
        axis: DVec3,
        /// Radius of the centre circle, positive.
        major: f64,
        /// Radius of the tube, positive.
        minor: f64,
    },
    /// The algebraic surface `F(x, y, z) = 0`, any degree ≥ 1.
    Algebraic {
        /// The polynomial `F`.
        poly: Poly3,
    },
    /// Bézier patches (`BEZIER_PATCH`: one; `BEZIER_MESH`: a `.bpt` file), traced exactly.
    BezierPatches {
        /// The control nets of the patches, at least one.
        patches: Vec<ControlNet>,
        /// How `v` is eliminated for each ray.
        method: PatchMethod,
    },
    /// A truncated cone, or a cylinder when the radii are equal (NFF `c`; `CONE`,
    /// `CYLINDER`): the surface between the circles about `base` and `apex` in the planes
    /// normal to the axis `apex − base`.
    Cone {
        /// Centre of the base circle.
        base: DVec3,
        /// Radius at the base, ≥ 0.
        base_radius: f64,
        /// Centre of the apex circle, not `base`.
        apex: DVec3,
        /// Radius at the apex, ≥ 0 (not both radii 0).
        apex_radius: f64,
        /// Whether flat disks close the ends (NFF's cones are open).
        caps: bool,
    },
    /// A triangle mesh read from a Wavefront OBJ file (`MESH`, `File Name`), flat triangles or
    /// triangles shaded with interpolated vertex normals.
    Mesh {
        /// Positions, normals and triangles (boxed: every object pays for the largest shape,
        /// and four vectors would make each sphere of an NFF scene 24 bytes larger).
        mesh: Box<MeshData>,
    },
    /// A planar polygon with a normal at each vertex (NFF `pp`), shaded with the normals
    /// interpolated across it.
    SmoothPolygon {
        /// At least three coplanar vertices, in order around the boundary.
        vertices: Vec<DVec3>,
        /// One non-zero normal per vertex.
        normals: Vec<DVec3>,
    },
}

// Every object of a scene holds a `ShapeKind`, so its size is paid 66 430 times by the largest
// sphereflake (its peak memory is one of issue 12's targets): large shapes go behind a box.
const _: () = assert!(size_of::<ShapeKind>() <= 80, "a shape fits in 80 bytes");

/// The geometry of a triangle mesh (`Type = MESH`, [`parse_obj`](super::parse_obj)):
/// triangles indexing positions and, for smooth triangles, vertex normals.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct MeshData {
    /// Vertex positions.
    pub positions: Vec<DVec3>,
    /// Vertex normals (any length, not zero where a triangle uses them).
    pub normals: Vec<DVec3>,
    /// Each triangle's three indices into `positions`.
    pub triangles: Vec<[u32; 3]>,
    /// Each triangle's three indices into `normals`, or `None` for a flat triangle (shaded
    /// with its own normal); one entry per triangle.
    pub triangle_normals: Vec<Option<[u32; 3]>>,
}

impl MeshData {
    /// At least one triangle; one normal entry per triangle; every index in range; positions
    /// finite; used normals finite and non-zero. Triangles of zero area are allowed (meshes
    /// often have them): they have no surface, and the tracer leaves them out.
    pub fn validate(&self) -> Result<(), InvalidModel> {
        if self.triangles.is_empty() {
            return Err(InvalidModel::new("File Name", "the mesh has no triangle"));
        }
        if self.triangle_normals.len() != self.triangles.len() {
            return Err(InvalidModel::new(
                "File Name",
                "the mesh needs one normal entry per triangle",
            ));
        }
        if !self.positions.iter().all(|p| p.is_finite()) {
            return Err(InvalidModel::new(
                "File Name",
                "a mesh position is not finite",
            ));
        }
        let np = self.positions.len();
        for (t, n) in self.triangles.iter().zip(&self.triangle_normals) {
            if t.iter().any(|&i| i as usize >= np) {
                return Err(InvalidModel::new(
                    "File Name",
                    "a mesh triangle names a vertex that does not exist",
                ));
            }
            for &i in n.iter().flatten() {
                let normal = self.normals.get(i as usize).ok_or(InvalidModel::new(
                    "File Name",
                    "a mesh triangle names a normal that does not exist",
                ))?;
                if !normal.is_finite() || *normal == DVec3::ZERO {
                    return Err(InvalidModel::new(
                        "File Name",
                        "a mesh normal is zero or not finite",
                    ));
                }
            }
        }
        Ok(())
    }
}

impl ShapeKind {
    /// A short upper-case name, as written after `Type =` (used in statistics and errors).
    pub fn type_name(&self) -> &'static str {
        match self {
            ShapeKind::Sphere { .. } => "SPHERE",
            ShapeKind::Plane { .. } => "PLANE",
            ShapeKind::Polygon { .. } => "POLYGON",
            ShapeKind::Triangle { .. } => "TRIANGLE",
            ShapeKind::Box { .. } => "BOX",
            ShapeKind::Superquadric { .. } => "SUPERQUADRIC",
            ShapeKind::Torus { .. } => "TORUS",
            ShapeKind::Algebraic { .. } => "ALGEBRAIC_SURFACE",
            ShapeKind::BezierPatches { patches, .. } if patches.len() == 1 => "BEZIER_PATCH",
            ShapeKind::BezierPatches { .. } => "BEZIER_MESH",
            ShapeKind::Cone {
                base_radius,
                apex_radius,
                ..
            } if base_radius == apex_radius => "CYLINDER",
            ShapeKind::Cone { .. } => "CONE",
            ShapeKind::SmoothPolygon { .. } => "POLYGON_PATCH",
            ShapeKind::Mesh { .. } => "MESH",
        }
    }

    /// Checks the shape's invariants (finite values, positive radii, non-zero normals,
    /// non-degenerate polygons…). The scene builder calls this and attaches the span of the
    /// object to the error.
    pub fn validate(&self) -> Result<(), InvalidModel> {
        let finite = |v: DVec3, key: &'static str| {
            if v.is_finite() {
                Ok(())
            } else {
                Err(InvalidModel::new(key, "must be finite"))
            }
        };
        let positive = |x: f64, key: &'static str| {
            if x.is_finite() && x > 0.0 {
                Ok(())
            } else {
                Err(InvalidModel::new(key, "must be a positive finite number"))
            }
        };
        match self {
            ShapeKind::Sphere { center, radius } => {
                finite(*center, "Center")?;
                positive(*radius, "Radius")
            }
            ShapeKind::Plane { origin, normal } => {
                finite(*origin, "Origin")?;
                finite(*normal, "Normal")?;
                nonzero(*normal, "Normal")
            }
            ShapeKind::Polygon { vertices } => {
                if vertices.len() < 3 {
                    return Err(InvalidModel::new("vertices", "a polygon needs at least 3"));
                }
                for v in vertices {
                    finite(*v, "vertices")?;
                }
                polygon_normal(vertices)
                    .map(|_| ())
                    .ok_or(InvalidModel::new("vertices", "the polygon has zero area"))
            }
            ShapeKind::Triangle { vertices } => {
                for v in vertices {
                    finite(*v, "vertices")?;
                }
                polygon_normal(vertices)
                    .map(|_| ())
                    .ok_or(InvalidModel::new("vertices", "the triangle has zero area"))
            }
            ShapeKind::Box { min, max } => {
                finite(*min, "Min")?;
                finite(*max, "Max")?;
                if min.cmplt(*max).all() {
                    Ok(())
                } else {
                    Err(InvalidModel::new(
                        "Max",
                        "must exceed Min in every coordinate",
                    ))
                }
            }
            ShapeKind::Superquadric {
                center,
                size,
                power,
            } => {
                finite(*center, "Center")?;
                positive(size.x, "Size")?;
                positive(size.y, "Size")?;
                positive(size.z, "Size")?;
                if !(1..=MAX_SUPERQUADRIC_POWER).contains(power) {
                    return Err(InvalidModel::new(
                        "Power",
                        "must be an integer from 1 to MAX_SUPERQUADRIC_POWER (512)",
                    ));
                }
                Ok(())
            }
            ShapeKind::Torus {
                center,
                axis,
                major,
                minor,
            } => {
                finite(*center, "Center")?;
                finite(*axis, "Axis")?;
                nonzero(*axis, "Axis")?;
                positive(*major, "MajorRadius")?;
                positive(*minor, "MinorRadius")
            }
            ShapeKind::Algebraic { poly } => {
                if !poly.is_finite() {
                    return Err(InvalidModel::new(
                        "Equation",
                        "has a non-finite coefficient",
                    ));
                }
                if poly.degree() == 0 {
                    return Err(InvalidModel::new("Equation", "must have degree at least 1"));
                }
                Ok(())
            }
            ShapeKind::BezierPatches { patches, .. } => {
                if patches.is_empty() {
                    return Err(InvalidModel::new("Control points", "holds no patch"));
                }
                Ok(())
            }
            ShapeKind::Cone {
                base,
                base_radius,
                apex,
                apex_radius,
                ..
            } => {
                finite(*base, "Base")?;
                finite(*apex, "Apex")?;
                nonzero(*apex - *base, "Apex")?;
                for (r, key) in [(*base_radius, "BaseRadius"), (*apex_radius, "ApexRadius")] {
                    if !(r.is_finite() && r >= 0.0) {
                        return Err(InvalidModel::new(key, "must be a finite number ≥ 0"));
                    }
                }
                if *base_radius == 0.0 && *apex_radius == 0.0 {
                    return Err(InvalidModel::new("BaseRadius", "and ApexRadius are both 0"));
                }
                Ok(())
            }
            ShapeKind::Mesh { mesh } => mesh.validate(),
            ShapeKind::SmoothPolygon { vertices, normals } => {
                if vertices.len() < 3 {
                    return Err(InvalidModel::new("vertices", "a polygon needs at least 3"));
                }
                if normals.len() != vertices.len() {
                    return Err(InvalidModel::new("normals", "must be one per vertex"));
                }
                for (v, n) in vertices.iter().zip(normals) {
                    finite(*v, "vertices")?;
                    finite(*n, "normals")?;
                    nonzero(*n, "normals")?;
                }
                polygon_normal(vertices)
                    .map(|_| ())
                    .ok_or(InvalidModel::new("vertices", "the polygon has zero area"))
            }
        }
    }
}

fn nonzero(v: DVec3, key: &'static str) -> Result<(), InvalidModel> {
    // Zero means zero: a tiny direction is normalised by `geometry::unit`, not refused.
    if v.abs().max_element() > 0.0 {
        Ok(())
    } else {
        Err(InvalidModel::new(key, "must not be the zero vector"))
    }
}

/// Which terms of Stam's illumination model an object gets (eq. 2.6; Annexe B `Intensity`).
///
/// The variants are ordered as Stam's numeric codes: each level adds terms to the previous
/// ones. `Texture` is `Diffuse` with `Cs` read from the texture.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub enum Illumination {
    /// Black: `I = 0` (`BLACKBODY`).
    Blackbody,
    /// `I = I_a` (`AMBIANT`).
    Ambient,
    /// `I = I_a + I_d` (`DIFFUSE`).
    Diffuse,
    /// `I = I_a + I_d` with `C_s` from the object's texture (`TEXTURE`).
    Texture,
    /// `I = I_a + I_d + I_s` (`SPECULAR`).
    Specular,
    /// `I = I_a + I_d + I_s + I_r` (`MIRROR`, `k_t` ignored).
    Mirror,
    /// `I = I_a + I_d + I_s + I_r + I_t` (`TRANSPARENT`).
    Transparent,
}

/// Illumination parameters of an object (Stam §2.3, §4.2.1).
#[derive(Clone, Debug, PartialEq)]
pub struct Material {
    /// Which terms of eq. 2.6 apply (`Illumination`).
    pub illumination: Illumination,
    /// Surface colour `C_s`, used by the ambient and diffuse terms (`Cs`).
    pub cs: Rgb,
    /// Reflective colour `C_r`, used by the specular term (`Cr`).
    pub cr: Rgb,
    /// Ambient coefficient `k_a` (`Ka`).
    pub ka: f64,
    /// Diffuse coefficient `k_d` (`Kd`).
    pub kd: f64,
    /// Specular coefficient `k_s`, also weighting the reflected ray (eq. 2.11) (`Ks`).
    pub ks: f64,
    /// Transmission coefficient `k_t` (eq. 2.14) (`Kt`).
    pub kt: f64,
    /// Specular exponent `n` (eq. 2.9) (`n`).
    pub n: f64,
    /// Relative refractive index `k_n = n₂/n₁` of the object's inside (eq. 2.16) (`Kn`).
    pub kn: f64,
    /// Index into [`Scene::textures`]: the texture replaces `C_s` wherever the shape defines
    /// surface parameters (required by [`Illumination::Texture`], allowed with any level).
    pub texture: Option<usize>,
}

impl Default for Material {
    /// A white diffuse material: `Ka = 0.1`, `Kd = 0.9`, `Ks = Kt = 0`, `n = 1`, `Kn = 1`.
    fn default() -> Self {
        Material {
            illumination: Illumination::Diffuse,
            cs: Rgb::ONE,
            cr: Rgb::ONE,
            ka: 0.1,
            kd: 0.9,
            ks: 0.0,
            kt: 0.0,
            n: 1.0,
            kn: 1.0,
            texture: None,
        }
    }
}

/// A bounding volume (`Bounding volume = NONE | BOX [x0,x1]x[y0,y1]x[z0,z1] | SPHERE (x,y,z) r`).
/// For implicit surfaces it clips: only the part of the surface inside is traced.
#[derive(Clone, Debug, PartialEq, Default)]
pub enum BoundingVolume {
    /// No user bounding volume.
    #[default]
    None,
    /// An axis-aligned box in the object's coordinates.
    Box {
        /// Lowest corner.
        min: DVec3,
        /// Highest corner, `max ≥ min` componentwise.
        max: DVec3,
    },
    /// A sphere in the object's coordinates.
    Sphere {
        /// Centre.
        center: DVec3,
        /// Radius, positive.
        radius: f64,
    },
}

/// Placement of an object: `world_from_object = T(translate) · Rz · Ry · Rx · S(scale)`
/// (scale first, then rotate about x, then y, then z, then translate).
#[derive(Clone, Debug, PartialEq)]
pub struct ObjectTransform {
    /// Translation (`Translate`).
    pub translate: DVec3,
    /// Rotation angles about x, y and z, in degrees (`Rotate`).
    pub rotate_deg: DVec3,
    /// Scale factors per axis, non-zero (`Scale`).
    pub scale: DVec3,
}

impl Default for ObjectTransform {
    /// The identity.
    fn default() -> Self {
        ObjectTransform {
            translate: DVec3::ZERO,
            rotate_deg: DVec3::ZERO,
            scale: DVec3::ONE,
        }
    }
}

impl ObjectTransform {
    /// True when the transform is the identity (the tracer then skips the wrapper).
    pub fn is_identity(&self) -> bool {
        *self == ObjectTransform::default()
    }

    /// The map `world_from_object`: `T(translate)·Rz·Ry·Rx·S(scale)`; `None` when it is
    /// singular or not finite.
    pub fn world_from_object(&self) -> Option<Transform> {
        if *self == Self::default() {
            // No Scale/Rotate/Translate (every NFF object): the identity, without three
            // rotations' sines and cosines and an inverse per object (issue 12).
            return Some(Transform::IDENTITY);
        }
        let r = self.rotate_deg * (std::f64::consts::PI / 180.0);
        let rot =
            DMat3::from_rotation_z(r.z) * DMat3::from_rotation_y(r.y) * DMat3::from_rotation_x(r.x);
        Transform::new(DAffine3::from_mat3_translation(
            rot * DMat3::from_diagonal(self.scale),
            self.translate,
        ))
    }
}

/// A texture for [`Illumination::Texture`] (`#texture`).
#[derive(Clone, Debug, PartialEq)]
pub enum Texture {
    /// Stam's image texture, tiled over the plane (Annexe B `ColTexture`).
    Image(ImageTexture),
    /// A procedural two-colour checker.
    Checker(CheckerTexture),
}

/// A raster texture, already loaded by the build step.
#[derive(Clone, Debug, PartialEq)]
pub struct ImageTexture {
    /// Width in texels.
    pub width: u32,
    /// Height in texels.
    pub height: u32,
    /// Side length on the plane covered by one copy of the image (`Unit`).
    pub unit: f64,
    /// `width × height` colours, row-major, first row first.
    pub texels: Vec<Rgb>,
}

/// A checkerboard of squares of side `unit` on the plane.
#[derive(Clone, Debug, PartialEq)]
pub struct CheckerTexture {
    /// Side of one square.
    pub unit: f64,
    /// The two colours; the square containing the plane's origin corner `(0+, 0+)` gets
    /// `colors[0]`.
    pub colors: [Rgb; 2],
}

/// Why a model value is invalid: the offending key and a lower-case reason.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
#[error("{key} {reason}")]
pub struct InvalidModel {
    /// The scene-file key the problem belongs to (`Radius`, `Normal`, …).
    pub key: &'static str,
    /// What is wrong, lower case, no full stop.
    pub reason: &'static str,
}

impl InvalidModel {
    /// An error about `key`.
    pub fn new(key: &'static str, reason: &'static str) -> Self {
        InvalidModel { key, reason }
    }
}

impl Scene {
    /// Checks every invariant the tracer relies on: shapes ([`ShapeKind::validate`]),
    /// texture references, camera, viewport and lights. The error names the object or block.
    /// [`ValidScene::new`](super::ValidScene::new) runs it; the loaders run it once, at the end.
    pub fn validate(&self) -> Result<(), SceneInvalid> {
        self.check(true)
    }

    /// [`Scene::validate`] without the shapes' own checks, for a loader that ran
    /// [`ShapeKind::validate`] on each shape as it read it (both loaders do, to point at the
    /// offending key), so that no shape is checked twice.
    pub(super) fn validate_except_shapes(&self) -> Result<(), SceneInvalid> {
        self.check(false)
    }

    /// The checks of [`Scene::validate`], in its order; `shapes` runs [`ShapeKind::validate`].
    fn check(&self, shapes: bool) -> Result<(), SceneInvalid> {
        for (index, object) in self.objects.iter().enumerate() {
            let at = |e: InvalidModel| SceneInvalid::Object { index, error: e };
            if shapes {
                object.shape.validate().map_err(at)?;
            }
            if let BoundingVolume::Box { min, max } = object.bounding
                && !(min.is_finite() && max.is_finite() && min.cmple(max).all())
            {
                return Err(at(InvalidModel::new(
                    "Bounding volume",
                    "must be a finite box with min ≤ max",
                )));
            }
            if let BoundingVolume::Sphere { center, radius } = object.bounding
                && !(center.is_finite() && radius.is_finite() && radius > 0.0)
            {
                return Err(at(InvalidModel::new(
                    "Bounding volume",
                    "must be a finite sphere with a positive radius",
                )));
            }
            let t = &object.transform;
            if !(t.translate.is_finite() && t.rotate_deg.is_finite() && t.scale.is_finite()) {
                return Err(at(InvalidModel::new("Transform", "must be finite")));
            }
            if t.scale.cmpeq(DVec3::ZERO).any() {
                return Err(at(InvalidModel::new("Scale", "must not be zero")));
            }
            let m = &object.material;
            let coeffs = [m.ka, m.kd, m.ks, m.kt, m.n, m.kn];
            if !(coeffs.iter().all(|c| c.is_finite()) && m.cs.is_finite() && m.cr.is_finite()) {
                return Err(at(InvalidModel::new("Illumination", "must be finite")));
            }
            if m.kn <= 0.0 {
                return Err(at(InvalidModel::new("Kn", "must be positive")));
            }
            match (m.illumination, m.texture) {
                (Illumination::Texture, None) => {
                    return Err(at(InvalidModel::new(
                        "Illumination",
                        "TEXTURE needs a #texture",
                    )));
                }
                (_, Some(i)) if i >= self.textures.len() => {
                    return Err(at(InvalidModel::new("texture", "refers to no #texture")));
                }
                _ => {}
            }
            if shapes {
                // Last: its "Transform overflows" presumes the finite checks above passed.
                object.placement().map_err(at)?;
            }
        }
        let cam_err = |reason| SceneInvalid::Camera { reason };
        match &self.camera {
            CameraSpec::Stam(c) => {
                let ok = [c.focal, c.distance, c.view_field_deg]
                    .iter()
                    .all(|x| x.is_finite())
                    && c.rotation_deg.is_finite()
                    && c.center.is_finite();
                if !ok {
                    return Err(cam_err("camera values must be finite"));
                }
                if c.focal <= 0.0 {
                    return Err(cam_err("Focal must be positive"));
                }
                if !(c.view_field_deg > 0.0 && c.view_field_deg < 180.0) {
                    return Err(cam_err("ViewField must be in (0, 180) degrees"));
                }
            }
            CameraSpec::LookAt(c) => {
                if !(c.eye.is_finite() && c.look_at.is_finite() && c.up.is_finite()) {
                    return Err(cam_err("camera vectors must be finite"));
                }
                // As the camera builds its frame: unit vectors scaled before squaring, so a
                // distant LookAt is fine and a difference that overflows is refused (it made
                // every camera ray NaN).
                let Some(forward) = unit(c.look_at - c.eye) else {
                    return Err(cam_err(if c.look_at == c.eye {
                        "Eye and LookAt must differ"
                    } else {
                        "Eye and LookAt are too far apart: their difference overflows"
                    }));
                };
                if unit(c.up).and_then(|up| unit(forward.cross(up))).is_none() {
                    return Err(cam_err("Up must not be parallel to the view direction"));
                }
                if !(c.view_field_deg > 0.0 && c.view_field_deg < 180.0) {
                    return Err(cam_err("ViewField must be in (0, 180) degrees"));
                }
            }
        }
        let v = &self.viewport;
        if v.size.contains(&0) || v.resolution.contains(&0) {
            return Err(SceneInvalid::Viewport {
                reason: "Size and Resolution must be positive",
            });
        }
        for (index, l) in self.lights.iter().enumerate() {
            if !(l.source.is_finite() && l.color.is_finite()) {
                return Err(SceneInvalid::Light {
                    index,
                    reason: "Source and Color must be finite",
                });
            }
        }
        if !self.world.background.is_finite() {
            return Err(SceneInvalid::World {
                reason: "BackGnd must be finite",
            });
        }
        if self.world.max_depth == 0 {
            return Err(SceneInvalid::World {
                reason: "MaxDepth must be at least 1",
            });
        }
        Ok(())
    }
}

/// Why a [`Scene`] is invalid, naming the block.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
#[non_exhaustive]
pub enum SceneInvalid {
    /// An object's shape, material, bounds or transform.
    #[error("object {}: {error}", index + 1)]
    Object {
        /// Zero-based index into [`Scene::objects`] (messages count from one).
        index: usize,
        /// The problem.
        error: InvalidModel,
    },
    /// The camera.
    #[error("camera: {reason}")]
    Camera {
        /// The problem.
        reason: &'static str,
    },
    /// The viewport.
    #[error("viewport: {reason}")]
    Viewport {
        /// The problem.
        reason: &'static str,
    },
    /// A light.
    #[error("light {}: {reason}", index + 1)]
    Light {
        /// Zero-based index into [`Scene::lights`].
        index: usize,
        /// The problem.
        reason: &'static str,
    },
    /// The world block.
    #[error("world: {reason}")]
    World {
        /// The problem.
        reason: &'static str,
    },
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The identity placement's shortcut (issue 12) is the map the general formula builds.
    #[test]
    fn identity_placement_is_the_general_formula() {
        let general = Transform::new(glam::DAffine3::from_mat3_translation(
            glam::DMat3::from_rotation_z(0.0)
                * glam::DMat3::from_rotation_y(0.0)
                * glam::DMat3::from_rotation_x(0.0)
                * glam::DMat3::from_diagonal(DVec3::ONE),
            DVec3::ZERO,
        ));
        assert_eq!(ObjectTransform::default().world_from_object(), general);
    }

    #[test]
    fn object_transform_order_is_scale_rotate_translate() {
        let t = ObjectTransform {
            translate: DVec3::new(10.0, 0.0, 0.0),
            rotate_deg: DVec3::new(0.0, 0.0, 90.0),
            scale: DVec3::new(2.0, 1.0, 1.0),
        };
        let m = t.world_from_object().unwrap();
        let p = m.apply_point(DVec3::X);
        // scale → (2,0,0), rotate 90° about z → (0,2,0), translate → (10,2,0)
        assert!((p - DVec3::new(10.0, 2.0, 0.0)).length() < 1e-12, "{p}");
        let back = m.inverse().apply_point(p);
        assert!((back - DVec3::X).length() < 1e-12, "inverse: {back}");
        // Normals of the plane x = 1 (object) stay perpendicular to the image plane.
        let n = m.apply_normal(DVec3::X);
        let tangent = m.apply_vector(DVec3::Y);
        assert!(
            n.dot(tangent).abs() < 1e-12,
            "normal ⟂ tangent after the map"
        );
        assert!(
            Transform::new(DAffine3::from_scale(DVec3::new(1.0, 0.0, 1.0))).is_none(),
            "singular"
        );
    }

    #[test]
    fn validation_rejects_degenerate_shapes() {
        let bad = [
            ShapeKind::Sphere {
                center: DVec3::ZERO,
                radius: -1.0,
            },
            ShapeKind::Plane {
                origin: DVec3::ZERO,
                normal: DVec3::ZERO,
            },
            ShapeKind::Triangle {
                vertices: [DVec3::ZERO, DVec3::X, DVec3::X * 2.0],
            },
            ShapeKind::Box {
                min: DVec3::ONE,
                max: DVec3::ZERO,
            },
            ShapeKind::Torus {
                center: DVec3::ZERO,
                axis: DVec3::Z,
                major: 2.0,
                minor: f64::NAN,
            },
            ShapeKind::Algebraic {
                poly: Poly3::constant(3.0),
            },
        ];
        for shape in bad {
            assert!(shape.validate().is_err(), "{shape:?} should be rejected");
        }
        let good = ShapeKind::Torus {
            center: DVec3::ZERO,
            axis: DVec3::Z,
            major: 2.0,
            minor: 1.0,
        };
        assert_eq!(good.validate(), Ok(()), "a proper torus is valid");
    }

    #[test]
    fn scene_validation_names_the_object() {
        let mut scene = Scene::default();
        scene.objects.push(Object::new(ShapeKind::Sphere {
            center: DVec3::ZERO,
            radius: 1.0,
        }));
        scene.objects.push(Object::new(ShapeKind::Sphere {
            center: DVec3::ZERO,
            radius: 0.0,
        }));
        let err = scene.validate().unwrap_err();
        assert_eq!(
            err.to_string(),
            "object 2: Radius must be a positive finite number",
            "{err}"
        );
        assert_eq!(
            scene.validate_except_shapes(),
            Ok(()),
            "the shape's own check is the one left out"
        );
        scene.objects.pop();
        Arc::make_mut(&mut scene.objects[0].material).illumination = Illumination::Texture;
        assert!(
            scene.validate().is_err(),
            "TEXTURE without a texture is refused"
        );
        assert!(
            scene.validate_except_shapes().is_err(),
            "and so it is without the shape checks"
        );
    }
}

//! The build step: a [`SceneAst`] → a validated [`Scene`], and the entry points [`parse`] and
//! [`load`].
//!
//! Here the tree's values get their meaning: expressions are evaluated (`Let` constants in
//! file order), `Equation`s expanded into [`Poly3`], required keys checked, duplicates
//! refused, ranges checked, texture names resolved and texture files read (relative to the
//! scene file's directory; the only I/O besides reading the scene itself). Every error points
//! at the key or value it is about.

use std::path::{Path, PathBuf};
use std::sync::Arc;

use glam::DVec3;

use super::bpt::{parse_bpt, parse_control_points};
use super::control_net::ControlNet;
use super::error::{ErrorKind, SceneError, Span};
use super::expr::{Constants, eval_const, expand};
use super::lexer::end_position;
use super::model::MAX_SUPERQUADRIC_POWER;
use super::model::{
    BoundingVolume, CameraSpec, CheckerTexture, Illumination, ImageTexture, InvalidModel, Light,
    LookAtCamera, Material, Object, ObjectTransform, Rgb, Scene, ShapeKind, StamCamera, Texture,
    Viewport, World,
};
use super::obj::parse_obj;
use super::source::{
    MAX_CONTROL_POINT_BYTES, MAX_MESH_BYTES, MAX_SCENE_BYTES, MAX_TEXTURE_BYTES,
    MAX_TEXTURE_TEXELS, read_bounded,
};
use super::syntax::{
    Block, Command, Entry, Key, SceneAst, ShapeType, TextureType, Value, parse_syntax,
};
use super::valid_scene::{SceneSpans, ValidScene};
use crate::methods::PatchMethod;
use crate::trivariate::Poly3;

/// The largest image side `#viewport Size` and texture sizes accept, in pixels.
///
/// Derivation: 2¹⁶ is beyond any display or print use, and keeps `width · height · 3` bytes
/// of a texture inside `u64` and the image crate's limits.
pub const MAX_IMAGE_SIDE: u32 = 1 << 16;

/// The most pixels an image may have, from `--size` or `#viewport Size`: 2²⁶, e.g.
/// 8192 × 8192.
///
/// Derivation: memory. A render keeps 16 bytes per pixel of film (linear RGBA `f32`), 4 of
/// depth with `--depth`, and the PNG encoder's input of up to 8 (16-bit RGBA): at most 28
/// bytes per pixel, 1.75 GiB at the limit, which a workstation has. Twice the limit would
/// not fit a machine of 4 GiB.
pub const MAX_IMAGE_PIXELS: u64 = 1 << 26;

/// Checks an image size against [`MAX_IMAGE_SIDE`] and [`MAX_IMAGE_PIXELS`].
///
/// # Errors
/// A message naming the size and the limit it breaks.
pub fn check_image_size([w, h]: [u32; 2]) -> Result<(), String> {
    if w == 0 || h == 0 || w > MAX_IMAGE_SIDE || h > MAX_IMAGE_SIDE {
        return Err(format!(
            "image size {w}x{h}: each side must be from 1 to {MAX_IMAGE_SIDE} pixels"
        ));
    }
    let pixels = u64::from(w) * u64::from(h);
    if pixels > MAX_IMAGE_PIXELS {
        return Err(format!(
            "image size {w}x{h} has {pixels} pixels, more than the limit of {MAX_IMAGE_PIXELS} \
             (8192x8192; a render needs up to 28 bytes per pixel)"
        ));
    }
    Ok(())
}

/// The largest `MaxDepth`: far beyond any visible contribution (each bounce multiplies by
/// `k_s` or `k_t` < 1) and small enough that recursion cannot exhaust the stack.
pub const MAX_RECURSION_DEPTH: u32 = 64;

/// Parses and builds a scene from its text.
///
/// `file` names the text in error messages and is the base for relative texture file names
/// (its directory); the text itself is not read from it. This is [`parse_syntax`] followed
/// by [`build`].
///
/// # Errors
/// A [`SceneError`] naming file, line, column and the key or token for any problem: syntax,
/// unknown command or key, missing or duplicate key, malformed or out-of-range value, an
/// `Equation` that is not a polynomial, an unreadable texture.
///
/// # Examples
/// ```
/// use std::path::Path;
/// use render::scene::{parse, ShapeKind};
/// let scene = parse(
///     "#camera Eye = (0,-8,5) LookAt = (0,0,0) ViewField = 50\n\
///      #object Type = TORUS Center = (0,0,0) Axis = (0,0,1) MajorRadius = 2 MinorRadius = 1",
///     Path::new("torus.scene"),
/// )?;
/// assert!(matches!(scene.objects[0].shape, ShapeKind::Torus { major: 2.0, .. }));
///
/// let err = parse("#object Type = TORUS Kx = 1", Path::new("x.scene")).unwrap_err();
/// assert_eq!(err.to_string(), "x.scene:1:22: unknown key `Kx` in #object");
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn parse(text: &str, file: &Path) -> Result<ValidScene, SceneError> {
    let ast = parse_syntax(text, file)?;
    build(&ast, file)
}

/// Reads a scene file and builds the scene: what the `render` command does with its
/// argument. NFF files (`.nff`, or recognised by their content: [`is_nff`](super::is_nff))
/// are read by [`parse_nff`](super::parse_nff) into the same model.
///
/// # Errors
/// [`SceneError::Read`] when the file cannot be read, is not a regular file (a FIFO or a
/// device is refused: it could block or never end) or is longer than [`MAX_SCENE_BYTES`];
/// [`ErrorKind::InvalidUtf8`] at the first byte that is not UTF-8; otherwise as [`parse`].
///
/// # Examples
/// ```no_run
/// let scene = render::scene::load(std::path::Path::new("scenes/torus.scene"))?;
/// println!("{} objects", scene.objects.len());
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn load(path: &Path) -> Result<ValidScene, SceneError> {
    let bytes = read_bounded(path, MAX_SCENE_BYTES).map_err(|source| SceneError::Read {
        path: path.to_owned(),
        source,
    })?;
    let text = std::str::from_utf8(&bytes).map_err(|e| {
        let valid = &bytes[..e.valid_up_to()];
        // The prefix is valid UTF-8 by construction; place the bad byte as the lexer would.
        let prefix = std::str::from_utf8(valid).unwrap_or_default();
        SceneError::at(
            &end_position(prefix, path.into()),
            ErrorKind::InvalidUtf8 {
                byte: bytes[e.valid_up_to()],
            },
        )
    })?;
    if super::nff::is_nff(path, text) {
        return super::nff::parse_nff(text, path);
    }
    parse(text, path)
}

/// Builds a validated scene ([`ValidScene`]) from a syntax tree; `file` is the scene file's path, whose
/// directory is the base for texture file names.
///
/// Accepts any tree, including hand-made ones: values of the wrong kind for their key are
/// reported as errors, never panics.
///
/// # Errors
/// As [`parse`], except for syntax errors.
pub fn build(ast: &SceneAst, file: &Path) -> Result<ValidScene, SceneError> {
    let base = file.parent().map(Path::to_path_buf).unwrap_or_default();
    let mut scene = Scene::default();
    let mut seen: Vec<(Command, &Span)> = Vec::new();
    let mut camera = None;
    // Textures first: objects refer to them by name, wherever they are in the file.
    let mut texture_names: Vec<Option<String>> = Vec::new();
    for block in ast
        .blocks
        .iter()
        .filter(|b| b.command.value == Command::Texture)
    {
        let mut fields = Fields::new(block)?;
        let (texture, name) = build_texture(&mut fields, &base)?;
        if let Some((name, span)) = &name
            && texture_names
                .iter()
                .flatten()
                .any(|n| n.eq_ignore_ascii_case(name))
        {
            return Err(invalid(
                span,
                Key::Name,
                format!("a texture named `{name}` is already defined"),
            ));
        }
        texture_names.push(name.map(|(n, _)| n));
        scene.textures.push(texture);
    }
    let mut object_spans = Vec::new();
    let mut light_spans = Vec::new();
    for block in &ast.blocks {
        let command = block.command.value;
        if matches!(
            command,
            Command::World | Command::Camera | Command::Viewport | Command::Save
        ) {
            if let Some((_, first)) = seen.iter().find(|(c, _)| *c == command) {
                return Err(SceneError::at(
                    &block.command.span,
                    ErrorKind::DuplicateCommand {
                        command: command.name(),
                        first_line: first.line,
                    },
                ));
            }
            seen.push((command, &block.command.span));
        }
        let mut fields = Fields::new(block)?;
        match command {
            Command::World => scene.world = build_world(&mut fields)?,
            Command::Camera => camera = Some(build_camera(&mut fields)?),
            Command::Light => {
                scene.lights.push(build_light(&mut fields)?);
                light_spans.push(block.command.span.clone());
            }
            Command::Object => {
                scene
                    .objects
                    .push(build_object(&mut fields, &texture_names, &base)?);
                object_spans.push(block.command.span.clone());
            }
            Command::Viewport => scene.viewport = build_viewport(&mut fields)?,
            Command::Save => {
                let (name, _) = fields.required_path(Key::FileName)?;
                scene.output = Some(PathBuf::from(name));
            }
            Command::Texture => {} // built above
        }
    }
    let Some(camera) = camera else {
        return Err(SceneError::at(
            &ast.end,
            ErrorKind::MissingCommand { command: "camera" },
        ));
    };
    scene.camera = camera;
    // The scene-level checks, once, reported at the block they concern (each shape was
    // checked as its block was read).
    let find = |command| {
        seen.iter()
            .find(|(c, _)| *c == command)
            .map(|(_, span)| (*span).clone())
    };
    let spans = SceneSpans {
        objects: object_spans,
        lights: light_spans,
        camera: find(Command::Camera),
        viewport: find(Command::Viewport),
        world: find(Command::World),
    };
    spans.validate(scene, &ast.end)
}

fn invalid(span: &Span, key: Key, reason: impl Into<String>) -> SceneError {
    SceneError::at(
        span,
        ErrorKind::InvalidValue {
            key: key.name().to_owned(),
            reason: reason.into(),
        },
    )
}

/// A value evaluated: expressions replaced by numbers (or, for `Equation`, a polynomial).
enum Eval {
    Number(f64),
    Tuple(Vec<f64>),
    Poly(Poly3),
    Switch(bool),
    Shape(ShapeType),
    TextureType(TextureType),
    Illumination(Illumination),
    Bounds(Option<(DVec3, DVec3)>),
    Sphere(DVec3, f64),
    Text(String),
    Points(Vec<DVec3>),
}

impl Eval {
    fn describe(&self) -> &'static str {
        match self {
            Eval::Number(_) => "a number",
            Eval::Tuple(_) => "a tuple",
            Eval::Poly(_) => "an equation",
            Eval::Switch(_) => "ON or OFF",
            Eval::Shape(_) => "an object type",
            Eval::TextureType(_) => "a texture type",
            Eval::Illumination(_) => "an illumination model",
            Eval::Bounds(_) | Eval::Sphere(..) => "a bounding volume",
            Eval::Text(_) => "a name",
            Eval::Points(_) => "a list of points",
        }
    }
}

/// One `Key = value` of a block, evaluated.
struct Field {
    key: Key,
    key_span: Span,
    value_span: Span,
    value: Eval,
}

/// The entries of one block, evaluated in file order, without duplicates.
struct Fields<'a> {
    block: &'a Block,
    fields: Vec<Field>,
}

impl<'a> Fields<'a> {
    fn command(&self) -> &'static str {
        self.block.command.value.name()
    }

    /// Evaluates every entry in order: `Let` constants are visible to the entries after them.
    fn new(block: &'a Block) -> Result<Self, SceneError> {
        let mut constants = Constants::default();
        let mut fields: Vec<Field> = Vec::new();
        let command = block.command.value.name();
        for entry in &block.entries {
            match entry {
                Entry::Let { name, value } => {
                    if constants.get(&name.value).is_some() {
                        return Err(SceneError::at(
                            &name.span,
                            ErrorKind::BadConstant {
                                name: name.value.clone(),
                                reason: "it is already defined in this block",
                            },
                        ));
                    }
                    let v = eval_const(value, &constants)?;
                    constants.define(&name.value, v);
                }
                Entry::Set { key, value } => {
                    if let Some(first) = fields.iter().find(|f| f.key == key.value) {
                        return Err(SceneError::at(
                            &key.span,
                            ErrorKind::DuplicateKey {
                                key: key.value.name(),
                                command,
                                first_line: first.key_span.line,
                                first_col: first.key_span.col,
                            },
                        ));
                    }
                    let evaluated = match &value.value {
                        Value::Number(e) if key.value == Key::Equation => {
                            Eval::Poly(expand(e, &constants)?)
                        }
                        Value::Number(e) => Eval::Number(eval_const(e, &constants)?),
                        Value::Tuple(items) => Eval::Tuple(
                            items
                                .iter()
                                .map(|e| eval_const(e, &constants))
                                .collect::<Result<_, _>>()?,
                        ),
                        Value::Switch(b) => Eval::Switch(*b),
                        Value::Shape(s) => Eval::Shape(*s),
                        Value::TextureType(t) => Eval::TextureType(*t),
                        Value::Illumination(i) => Eval::Illumination(*i),
                        Value::Bounds(None) => Eval::Bounds(None),
                        Value::Bounds(Some(ranges)) => {
                            let mut lo = DVec3::ZERO;
                            let mut hi = DVec3::ZERO;
                            for (axis, [a, b]) in ranges.iter().enumerate() {
                                lo[axis] = eval_const(a, &constants)?;
                                hi[axis] = eval_const(b, &constants)?;
                                if lo[axis] > hi[axis] {
                                    return Err(invalid(
                                        &a.span,
                                        Key::BoundingVolume,
                                        format!("range [{}, {}] is empty", lo[axis], hi[axis]),
                                    ));
                                }
                            }
                            Eval::Bounds(Some((lo, hi)))
                        }
                        Value::BoundingSphere(s) => {
                            let c = |i: usize| eval_const(&s[i], &constants);
                            Eval::Sphere(DVec3::new(c(0)?, c(1)?, c(2)?), c(3)?)
                        }
                        Value::Path(p) | Value::Word(p) => Eval::Text(p.clone()),
                        Value::Points(points) => Eval::Points(
                            points
                                .iter()
                                .map(|p| -> Result<DVec3, SceneError> {
                                    let c = |i: usize| eval_const(&p[i], &constants);
                                    Ok(DVec3::new(c(0)?, c(1)?, c(2)?))
                                })
                                .collect::<Result<_, _>>()?,
                        ),
                    };
                    fields.push(Field {
                        key: key.value,
                        key_span: key.span.clone(),
                        value_span: value.span.clone(),
                        value: evaluated,
                    });
                }
            }
        }
        Ok(Fields { block, fields })
    }

    fn get(&self, key: Key) -> Option<&Field> {
        self.fields.iter().find(|f| f.key == key)
    }

    fn span_of(&self, key: Key) -> &Span {
        self.get(key)
            .map_or(&self.block.command.span, |f| &f.key_span)
    }

    fn missing(&self, key: Key, detail: impl Into<String>) -> SceneError {
        SceneError::at(
            &self.block.command.span,
            ErrorKind::MissingKey {
                key: key.name(),
                command: self.command(),
                detail: detail.into(),
            },
        )
    }

    fn wrong(field: &Field, expected: &str) -> SceneError {
        invalid(
            &field.value_span,
            field.key,
            format!("expected {expected}, found {}", field.value.describe()),
        )
    }

    fn number(&self, key: Key) -> Result<Option<(f64, &Span)>, SceneError> {
        let Some(f) = self.get(key) else {
            return Ok(None);
        };
        match f.value {
            Eval::Number(v) => Ok(Some((v, &f.value_span))),
            _ => Err(Self::wrong(f, "a number")),
        }
    }

    fn required_number(&self, key: Key, detail: &str) -> Result<(f64, &Span), SceneError> {
        self.number(key)?.ok_or_else(|| self.missing(key, detail))
    }

    /// `(x, y, z)`; with `broadcast`, a single number `v` means `(v, v, v)`.
    fn vector_in(&self, key: Key, broadcast: bool) -> Result<Option<DVec3>, SceneError> {
        let Some(f) = self.get(key) else {
            return Ok(None);
        };
        match &f.value {
            Eval::Tuple(v) if v.len() == 3 => Ok(Some(DVec3::new(v[0], v[1], v[2]))),
            Eval::Number(v) if broadcast => Ok(Some(DVec3::splat(*v))),
            _ => Err(Self::wrong(f, "a vector `(x, y, z)`")),
        }
    }

    fn vector(&self, key: Key) -> Result<Option<DVec3>, SceneError> {
        self.vector_in(key, false)
    }

    fn required_vector(&self, key: Key, detail: &str) -> Result<DVec3, SceneError> {
        self.vector(key)?.ok_or_else(|| self.missing(key, detail))
    }

    /// A required direction (`Axis`, `Normal`): only its direction matters, so a vector so
    /// small or large that its squared length under- or overflows (`(0, 0, 1e-200)`) is
    /// rescaled by its largest component, which normalising then handles; the zero vector is
    /// refused. Other vectors are kept bit for bit.
    fn required_direction(&self, key: Key, detail: &str) -> Result<DVec3, SceneError> {
        let v = self.required_vector(key, detail)?;
        let largest = v.abs().max_element();
        if largest == 0.0 {
            return Err(invalid(
                self.span_of(key),
                key,
                "must not be the zero vector",
            ));
        }
        let len2 = v.length_squared();
        Ok(if len2 < f64::MIN_POSITIVE || !len2.is_finite() {
            v / largest
        } else {
            v
        })
    }

    fn colour(&self, key: Key) -> Result<Option<Rgb>, SceneError> {
        self.vector_in(key, true)
    }

    fn switch(&self, key: Key) -> Result<Option<bool>, SceneError> {
        let Some(f) = self.get(key) else {
            return Ok(None);
        };
        match f.value {
            Eval::Switch(b) => Ok(Some(b)),
            _ => Err(Self::wrong(f, "ON or OFF")),
        }
    }

    fn text(&self, key: Key) -> Result<Option<(&str, &Span)>, SceneError> {
        let Some(f) = self.get(key) else {
            return Ok(None);
        };
        match &f.value {
            Eval::Text(t) => Ok(Some((t.as_str(), &f.value_span))),
            _ => Err(Self::wrong(f, "a name")),
        }
    }

    fn required_path(&self, key: Key) -> Result<(&str, &Span), SceneError> {
        self.text(key)?.ok_or_else(|| self.missing(key, ""))
    }

    /// `(w, h)` of whole numbers in `1..=MAX_IMAGE_SIDE`.
    fn size(&self, key: Key) -> Result<Option<[u32; 2]>, SceneError> {
        let Some(f) = self.get(key) else {
            return Ok(None);
        };
        let Eval::Tuple(v) = &f.value else {
            return Err(Self::wrong(f, "a pair `(w, h)`"));
        };
        let [w, h] = v.as_slice() else {
            return Err(Self::wrong(f, "a pair `(w, h)`"));
        };
        let side = |x: f64| whole(x, 1, MAX_IMAGE_SIDE);
        match (side(*w), side(*h)) {
            (Some(w), Some(h)) => Ok(Some([w, h])),
            _ => Err(invalid(
                &f.value_span,
                key,
                format!("sizes must be whole numbers from 1 to {MAX_IMAGE_SIDE}, found ({w}, {h})"),
            )),
        }
    }

    /// A number that must be finite and `> 0` (`>= 0` when `zero_ok`).
    fn checked(
        &self,
        key: Key,
        value: Option<(f64, &Span)>,
        zero_ok: bool,
    ) -> Result<Option<f64>, SceneError> {
        match value {
            Some((v, span)) if !(v > 0.0 || (zero_ok && v == 0.0)) => Err(invalid(
                span,
                key,
                if zero_ok {
                    format!("must not be negative, found {v}")
                } else {
                    format!("must be positive, found {v}")
                },
            )),
            other => Ok(other.map(|(v, _)| v)),
        }
    }

    /// The type of an `#object` or `#texture`.
    fn type_value(&self) -> Option<&Field> {
        self.get(Key::Type)
    }

    /// Fails on a key not in `allowed` (for hand-made trees and `#texture` types).
    fn only(&self, allowed: &[Key], type_name: &'static str) -> Result<(), SceneError> {
        match self.fields.iter().find(|f| !allowed.contains(&f.key)) {
            Some(f) => Err(SceneError::at(
                &f.key_span,
                ErrorKind::KeyNotForType {
                    key: f.key.name().to_owned(),
                    type_name,
                    command: self.command(),
                },
            )),
            None => Ok(()),
        }
    }
}

/// `x` as an integer in `lo..=hi`, if it is one.
fn whole(x: f64, lo: u32, hi: u32) -> Option<u32> {
    (x.fract() == 0.0 && x >= f64::from(lo) && x <= f64::from(hi)).then_some(x as u32)
}

fn build_world(f: &mut Fields<'_>) -> Result<World, SceneError> {
    f.only(
        &[Key::BackGnd, Key::Shadows, Key::MaxDepth, Key::Attenuation],
        "world",
    )?;
    let mut world = World::default();
    if let Some(c) = f.colour(Key::BackGnd)? {
        world.background = c;
    }
    if let Some(b) = f.switch(Key::Shadows)? {
        world.shadows = b;
    }
    if let Some(b) = f.switch(Key::Attenuation)? {
        world.attenuation = b;
    }
    if let Some((v, span)) = f.number(Key::MaxDepth)? {
        world.max_depth = whole(v, 1, MAX_RECURSION_DEPTH).ok_or_else(|| {
            invalid(
                span,
                Key::MaxDepth,
                format!("must be a whole number from 1 to {MAX_RECURSION_DEPTH}, found {v}"),
            )
        })?;
    }
    Ok(world)
}

fn build_camera(f: &mut Fields<'_>) -> Result<CameraSpec, SceneError> {
    const STAM: [Key; 4] = [Key::Focal, Key::Distance, Key::Rotation, Key::Center];
    const LOOK_AT: [Key; 3] = [Key::Eye, Key::LookAt, Key::Up];
    let mut all = STAM.to_vec();
    all.extend(LOOK_AT);
    all.push(Key::ViewField);
    f.only(&all, "camera")?;
    let stam = f.fields.iter().find(|x| STAM.contains(&x.key));
    let look = f.fields.iter().find(|x| LOOK_AT.contains(&x.key));
    if let (Some(a), Some(b)) = (stam, look) {
        let (first, later) =
            if (a.key_span.line, a.key_span.col) < (b.key_span.line, b.key_span.col) {
                (a, b)
            } else {
                (b, a)
            };
        return Err(SceneError::at(
            &later.key_span,
            ErrorKind::ConflictingKeys {
                key: later.key.name(),
                other: first.key.name(),
                command: "camera",
                detail: " (Stam's camera and the look-at camera are two different forms)",
            },
        ));
    }
    let (view_field, vf_span) = f.required_number(
        Key::ViewField,
        if stam.is_some() {
            ""
        } else {
            " (look-at camera: Eye, LookAt, ViewField and optional Up)"
        },
    )?;
    if !(view_field > 0.0 && view_field < 180.0) {
        return Err(invalid(
            vf_span,
            Key::ViewField,
            format!("must be between 0 and 180 degrees, found {view_field}"),
        ));
    }
    if stam.is_some() {
        let detail = " (Stam's camera: Focal, Distance, ViewField, Rotation, Center)";
        let (focal, focal_span) = f.required_number(Key::Focal, detail)?;
        if focal <= 0.0 {
            return Err(invalid(
                focal_span,
                Key::Focal,
                format!("must be positive, found {focal}"),
            ));
        }
        return Ok(CameraSpec::Stam(StamCamera {
            focal,
            distance: f.required_number(Key::Distance, detail)?.0,
            view_field_deg: view_field,
            rotation_deg: f.required_vector(Key::Rotation, detail)?,
            center: f.required_vector(Key::Center, detail)?,
        }));
    }
    let detail = " (look-at camera: Eye, LookAt, ViewField and optional Up)";
    let eye = f.required_vector(Key::Eye, detail)?;
    let look_at = f.required_vector(Key::LookAt, detail)?;
    let up = f.vector(Key::Up)?.unwrap_or(DVec3::Z);
    let view = look_at - eye;
    if view.length_squared() == 0.0 {
        return Err(invalid(
            f.span_of(Key::LookAt),
            Key::LookAt,
            "must differ from `Eye`",
        ));
    }
    if view.cross(up).length_squared() == 0.0 {
        let key = if f.get(Key::Up).is_some() {
            Key::Up
        } else {
            Key::LookAt
        };
        return Err(invalid(
            f.span_of(key),
            key,
            "the view direction must not be parallel to `Up` (default (0, 0, 1))",
        ));
    }
    Ok(CameraSpec::LookAt(LookAtCamera {
        eye,
        look_at,
        up,
        view_field_deg: view_field,
    }))
}

fn build_light(f: &mut Fields<'_>) -> Result<Light, SceneError> {
    f.only(&[Key::Source, Key::Color], "light")?;
    Ok(Light {
        source: f.required_vector(Key::Source, "")?,
        color: f.colour(Key::Color)?.unwrap_or(Rgb::ONE),
    })
}

fn build_viewport(f: &mut Fields<'_>) -> Result<Viewport, SceneError> {
    f.only(&[Key::Size, Key::Origin, Key::Resolution], "viewport")?;
    let size = f.size(Key::Size)?.ok_or_else(|| f.missing(Key::Size, ""))?;
    check_image_size(size).map_err(|reason| invalid(f.span_of(Key::Size), Key::Size, reason))?;
    // `Origin` placed Stam's window on his screen; it has no meaning for an image file and
    // is accepted (and checked to be a pair) so that his files read unchanged.
    if let Some(o) = f.get(Key::Origin)
        && !matches!(&o.value, Eval::Tuple(v) if v.len() == 2)
    {
        return Err(Fields::wrong(o, "a pair `(x, y)`"));
    }
    let resolution = f.size(Key::Resolution)?.unwrap_or([1, 1]);
    Ok(Viewport { size, resolution })
}

fn build_texture(
    f: &mut Fields<'_>,
    base: &Path,
) -> Result<(Texture, Option<(String, Span)>), SceneError> {
    let ty = match f.type_value() {
        None => TextureType::Image,
        Some(Field {
            value: Eval::TextureType(t),
            ..
        }) => *t,
        Some(other) => return Err(Fields::wrong(other, "IMAGE or CHECKER")),
    };
    let name = f.text(Key::Name)?.map(|(n, s)| (n.to_owned(), s.clone()));
    let unit = f
        .checked(Key::Unit, Some(f.required_number(Key::Unit, "")?), false)?
        .unwrap_or(1.0);
    let texture = match ty {
        TextureType::Checker => {
            f.only(
                &[Key::Type, Key::Name, Key::Unit, Key::Color1, Key::Color2],
                "CHECKER",
            )?;
            Texture::Checker(CheckerTexture {
                unit,
                colors: [
                    f.colour(Key::Color1)?.unwrap_or(Rgb::ONE),
                    f.colour(Key::Color2)?.unwrap_or(Rgb::ZERO),
                ],
            })
        }
        TextureType::Image => {
            f.only(
                &[Key::Type, Key::Name, Key::Unit, Key::Size, Key::FileName],
                "IMAGE",
            )?;
            let (file, span) = f.required_path(Key::FileName)?;
            let size = f.size(Key::Size)?;
            Texture::Image(read_texture(&base.join(file), size, unit, span, f)?)
        }
    };
    Ok((texture, name))
}

/// Decodes a PNG texture of at most [`MAX_TEXTURE_TEXELS`] texels. The error is a short
/// reason for the user: the decoder's own messages carry its internal state (debug dumps of
/// chunk types and decoder structs), which says nothing to someone who wrote a scene.
fn decode_png(bytes: &[u8]) -> Result<image::DynamicImage, String> {
    use image::error::{ImageError, LimitErrorKind};
    let mut reader =
        image::ImageReader::with_format(std::io::Cursor::new(bytes), image::ImageFormat::Png);
    let mut limits = image::Limits::default();
    // Sides as for every image; no more bytes than the most texels need in 16-bit RGBA.
    limits.max_image_width = Some(MAX_IMAGE_SIDE);
    limits.max_image_height = Some(MAX_IMAGE_SIDE);
    limits.max_alloc = Some(8 * MAX_TEXTURE_TEXELS);
    reader.limits(limits);
    let too_big =
        || format!("the image has more than the {MAX_TEXTURE_TEXELS} texels a texture may have");
    let img = reader.decode().map_err(|e| match e {
        ImageError::Limits(l)
            if matches!(
                l.kind(),
                LimitErrorKind::DimensionError | LimitErrorKind::InsufficientMemory
            ) =>
        {
            too_big()
        }
        ImageError::Unsupported(_) => "a PNG variant the decoder does not support".to_string(),
        ImageError::IoError(e) => e.to_string(),
        _ => "not a valid PNG file (corrupt or truncated)".to_string(),
    })?;
    if u64::from(img.width()) * u64::from(img.height()) > MAX_TEXTURE_TEXELS {
        return Err(too_big());
    }
    Ok(img)
}

/// Reads an image texture: a PNG (any size; `Size`, if given, must match), or Stam's raw
/// format (Annexe B `GetTexture`): `w·h` red bytes, then `w·h` green, then `w·h` blue, rows
/// first, with `Size = w x h` required.
fn read_texture(
    path: &Path,
    size: Option<[u32; 2]>,
    unit: f64,
    span: &Span,
    f: &Fields<'_>,
) -> Result<ImageTexture, SceneError> {
    let fail = |reason: String| {
        SceneError::at(
            span,
            ErrorKind::FileRead {
                path: path.display().to_string(),
                reason,
            },
        )
    };
    let is_png = path
        .extension()
        .is_some_and(|e| e.eq_ignore_ascii_case("png"));
    if is_png {
        let bytes = read_bounded(path, MAX_TEXTURE_BYTES).map_err(|e| fail(e.to_string()))?;
        let img = decode_png(&bytes).map_err(fail)?.to_rgb8();
        let (w, h) = img.dimensions();
        if let Some([sw, sh]) = size
            && [sw, sh] != [w, h]
        {
            return Err(invalid(
                f.span_of(Key::Size),
                Key::Size,
                format!("is {sw}x{sh} but the image is {w}x{h}"),
            ));
        }
        let texels = img
            .pixels()
            .map(|p| Rgb::new(p[0].into(), p[1].into(), p[2].into()) / 255.0)
            .collect();
        return Ok(ImageTexture {
            width: w,
            height: h,
            unit,
            texels,
        });
    }
    let [w, h] = size.ok_or_else(|| f.missing(Key::Size, " (a raw RGB texture needs its size)"))?;
    let n = u64::from(w) * u64::from(h);
    if n > MAX_TEXTURE_TEXELS {
        return Err(invalid(
            f.span_of(Key::Size),
            Key::Size,
            format!("{w}x{h} has more than the {MAX_TEXTURE_TEXELS} texels a texture may have"),
        ));
    }
    let bytes = read_bounded(path, MAX_TEXTURE_BYTES).map_err(|e| fail(e.to_string()))?;
    if bytes.len() as u64 != 3 * n {
        return Err(fail(format!(
            "expected 3 × {w} × {h} = {} bytes of planar RGB, found {}",
            3 * n,
            bytes.len()
        )));
    }
    let n = n as usize;
    let texels = (0..n)
        .map(|i| {
            Rgb::new(
                bytes[i].into(),
                bytes[n + i].into(),
                bytes[2 * n + i].into(),
            ) / 255.0
        })
        .collect();
    Ok(ImageTexture {
        width: w,
        height: h,
        unit,
        texels,
    })
}

fn build_object(
    f: &mut Fields<'_>,
    textures: &[Option<String>],
    base: &Path,
) -> Result<Object, SceneError> {
    let shape_type = match f.type_value() {
        Some(Field {
            value: Eval::Shape(s),
            ..
        }) => *s,
        Some(other) => return Err(Fields::wrong(other, "an object type")),
        None => return Err(f.missing(Key::Type, "")),
    };
    let mut allowed = vec![
        Key::Type,
        Key::Illumination,
        Key::Cs,
        Key::Cr,
        Key::Ka,
        Key::Kd,
        Key::Ks,
        Key::Kt,
        Key::N,
        Key::Kn,
        Key::Texture,
        Key::BoundingVolume,
        Key::Translate,
        Key::Rotate,
        Key::Scale,
    ];
    allowed.extend_from_slice(shape_type.keys());
    f.only(&allowed, shape_type.name())?;
    let shape = build_shape(f, shape_type, base)?;
    if let Err(e) = shape.validate() {
        return Err(model_error(f, shape_type, &e));
    }

    let mut material = Material::default();
    if let Some(field) = f.get(Key::Illumination) {
        match field.value {
            Eval::Illumination(i) => material.illumination = i,
            _ => return Err(Fields::wrong(field, "an illumination model")),
        }
    }
    material.cs = f.colour(Key::Cs)?.unwrap_or(material.cs);
    material.cr = f.colour(Key::Cr)?.unwrap_or(material.cr);
    for (key, slot) in [
        (Key::Ka, &mut material.ka),
        (Key::Kd, &mut material.kd),
        (Key::Ks, &mut material.ks),
        (Key::Kt, &mut material.kt),
        (Key::N, &mut material.n),
    ] {
        if let Some(v) = f.checked(key, f.number(key)?, true)? {
            *slot = v;
        }
    }
    if let Some(v) = f.checked(Key::Kn, f.number(Key::Kn)?, false)? {
        material.kn = v;
    }
    material.texture = match f.text(Key::Texture)? {
        Some((name, span)) => Some(
            textures
                .iter()
                .position(|t| t.as_deref().is_some_and(|t| t.eq_ignore_ascii_case(name)))
                .ok_or_else(|| {
                    SceneError::at(
                        span,
                        ErrorKind::Texture {
                            reason: format!("no #texture is named `{name}`"),
                        },
                    )
                })?,
        ),
        None if material.illumination == Illumination::Texture => {
            if textures.len() != 1 {
                return Err(SceneError::at(
                    f.span_of(Key::Illumination),
                    ErrorKind::Texture {
                        reason: format!(
                            "TEXTURE illumination needs `Texture = name` when the file has {} textures (it may omit it when there is exactly one)",
                            textures.len()
                        ),
                    },
                ));
            }
            Some(0)
        }
        None => None,
    };

    let bounding = match f.get(Key::BoundingVolume) {
        None => BoundingVolume::None,
        Some(Field {
            value: Eval::Bounds(None),
            ..
        }) => BoundingVolume::None,
        Some(Field {
            value: Eval::Bounds(Some((min, max))),
            ..
        }) => BoundingVolume::Box {
            min: *min,
            max: *max,
        },
        Some(Field {
            value: Eval::Sphere(center, radius),
            value_span,
            ..
        }) => {
            if !(*radius > 0.0 && radius.is_finite()) {
                return Err(invalid(
                    value_span,
                    Key::BoundingVolume,
                    format!("the sphere's radius must be positive, found {radius}"),
                ));
            }
            BoundingVolume::Sphere {
                center: *center,
                radius: *radius,
            }
        }
        Some(other) => {
            return Err(Fields::wrong(
                other,
                "NONE, BOX [x0,x1]x[y0,y1]x[z0,z1] or SPHERE (x,y,z) r",
            ));
        }
    };

    let mut transform = ObjectTransform::default();
    if let Some(v) = f.vector(Key::Translate)? {
        transform.translate = v;
    }
    if let Some(v) = f.vector(Key::Rotate)? {
        transform.rotate_deg = v;
    }
    if let Some(v) = f.vector_in(Key::Scale, true)? {
        if v.cmpeq(DVec3::ZERO).any() {
            return Err(invalid(
                f.span_of(Key::Scale),
                Key::Scale,
                "scale factors must not be zero",
            ));
        }
        let det = v.x * v.y * v.z;
        if !det.is_finite() || det == 0.0 {
            return Err(invalid(
                f.span_of(Key::Scale),
                Key::Scale,
                format!(
                    "the product of the scale factors, {:e}, {} the range of f64 (the \
                     transform's determinant must be a nonzero finite number)",
                    v.x * v.y * v.z,
                    if det == 0.0 {
                        "underflows"
                    } else {
                        "overflows"
                    }
                ),
            ));
        }
        transform.scale = v;
    }
    let object = Object {
        shape,
        material: Arc::new(material),
        bounding,
        transform,
    };
    // The tracer places the shape by this transform and a frame of its own (torus, cone,
    // superquadric): `PreparedScene` computes the same `Placement`, so check it here, where
    // the keys have places.
    if let Err(e) = object.placement() {
        if e.key == "Transform" {
            let transform_span = [Key::Scale, Key::Rotate, Key::Translate]
                .into_iter()
                .find_map(|k| f.get(k).map(|field| &field.key_span));
            return Err(invalid(
                transform_span.unwrap_or(&f.block.command.span),
                Key::Scale,
                "the object's transform overflows f64 or is singular",
            ));
        }
        return Err(model_error(f, shape_type, &e));
    }
    Ok(object)
}

/// A model error at its key. The model calls a polygon's corners `vertices`; here they are
/// the keys `a b c (d)`, and the one written last completes the degenerate polygon.
fn model_error(f: &Fields<'_>, shape_type: ShapeType, e: &InvalidModel) -> SceneError {
    let span = if e.key == "vertices" {
        shape_type
            .keys()
            .iter()
            .filter_map(|&k| f.get(k).map(|field| &field.key_span))
            .max_by_key(|span| (span.line, span.col))
    } else {
        Key::ALL
            .iter()
            .find(|k| k.name() == e.key)
            .map(|&k| f.span_of(k))
    };
    SceneError::at(
        span.unwrap_or(&f.block.command.span),
        ErrorKind::InvalidValue {
            key: e.key.to_owned(),
            reason: e.reason.to_owned(),
        },
    )
}

fn build_shape(f: &Fields<'_>, shape: ShapeType, base: &Path) -> Result<ShapeKind, SceneError> {
    let detail = format!(" of type {}", shape.name());
    let vector = |key| f.required_vector(key, &detail);
    Ok(match shape {
        ShapeType::Sphere => {
            let radius = match (f.number(Key::Radius)?, f.number(Key::Radius2)?) {
                (Some(_), Some(_)) => {
                    let (a, b) = (f.span_of(Key::Radius), f.span_of(Key::Radius2));
                    let (key, other, span) = if (a.line, a.col) < (b.line, b.col) {
                        (Key::Radius2, Key::Radius, b)
                    } else {
                        (Key::Radius, Key::Radius2, a)
                    };
                    return Err(SceneError::at(
                        span,
                        ErrorKind::ConflictingKeys {
                            key: key.name(),
                            other: other.name(),
                            command: "object",
                            detail: " (give the radius one way)",
                        },
                    ));
                }
                (Some((r, _)), None) => r,
                (None, Some((r2, span))) => {
                    if r2 <= 0.0 {
                        return Err(invalid(
                            span,
                            Key::Radius2,
                            format!("must be positive, found {r2}"),
                        ));
                    }
                    r2.sqrt()
                }
                (None, None) => {
                    return Err(f.missing(Key::Radius, format!("{detail} (or `Radius^2`)")));
                }
            };
            ShapeKind::Sphere {
                center: vector(Key::Center)?,
                radius,
            }
        }
        ShapeType::Plane => ShapeKind::Plane {
            origin: vector(Key::Origin)?,
            normal: f.required_direction(Key::Normal, &detail)?,
        },
        // Stam's four-sided polygon has `a` and `d` as opposite corners: `IntPolygon` tests
        // the wedge at `a` between `ab` and `ac`, and the wedge at `d` between `db` and `dc`
        // (Annexe B `CalculatePolygon`). Around the boundary the order is a, b, d, c.
        ShapeType::Polygon => ShapeKind::Polygon {
            vertices: vec![
                vector(Key::A)?,
                vector(Key::B)?,
                vector(Key::D)?,
                vector(Key::C)?,
            ],
        },
        ShapeType::Triangle => ShapeKind::Triangle {
            vertices: [vector(Key::A)?, vector(Key::B)?, vector(Key::C)?],
        },
        ShapeType::Box => ShapeKind::Box {
            min: vector(Key::Min)?,
            max: vector(Key::Max)?,
        },
        ShapeType::Superquadric => {
            let (p, span) = f.required_number(Key::Power, &detail)?;
            let power = whole(p, 1, MAX_SUPERQUADRIC_POWER).ok_or_else(|| {
                invalid(
                    span,
                    Key::Power,
                    if p > f64::from(MAX_SUPERQUADRIC_POWER) {
                        format!(
                            "must be at most {MAX_SUPERQUADRIC_POWER} (the largest power the \
                             ray polynomial's root finder handles), found {p}"
                        )
                    } else {
                        format!("must be a whole number ≥ 1, found {p}")
                    },
                )
            })?;
            ShapeKind::Superquadric {
                center: vector(Key::Center)?,
                size: vector(Key::Size)?,
                power,
            }
        }
        ShapeType::Torus => ShapeKind::Torus {
            center: vector(Key::Center)?,
            axis: f.required_direction(Key::Axis, &detail)?,
            major: f.required_number(Key::MajorRadius, &detail)?.0,
            minor: f.required_number(Key::MinorRadius, &detail)?.0,
        },
        ShapeType::AlgebraicSurface => {
            let field = f
                .get(Key::Equation)
                .ok_or_else(|| f.missing(Key::Equation, detail.clone()))?;
            match &field.value {
                Eval::Poly(p) => ShapeKind::Algebraic { poly: p.clone() },
                Eval::Number(c) => ShapeKind::Algebraic {
                    poly: Poly3::constant(*c),
                },
                _ => return Err(Fields::wrong(field, "an equation in x, y, z")),
            }
        }
        ShapeType::BezierPatch | ShapeType::BezierMesh => {
            read_patches(f, shape == ShapeType::BezierMesh, base, &detail)?
        }
        ShapeType::Mesh => read_mesh(f, base)?,
        ShapeType::Cone | ShapeType::Cylinder => {
            let (r0, r1) = if shape == ShapeType::Cone {
                let r0 = f.required_number(Key::BaseRadius, &detail)?.0;
                (r0, f.required_number(Key::ApexRadius, &detail)?.0)
            } else {
                let r = f.required_number(Key::Radius, &detail)?.0;
                (r, r)
            };
            ShapeKind::Cone {
                base: vector(Key::Base)?,
                base_radius: r0,
                apex: vector(Key::Apex)?,
                apex_radius: r1,
                caps: f.switch(Key::Caps)?.unwrap_or(false),
            }
        }
    })
}

/// `Control points = FILE` (read relative to the scene; Stam's `Control points in FILE` too),
/// or for a single patch the 16 points inline, and `Method = GROEBNER | RESULTANT |
/// GROEBNER_EXACT | RESULTANT_EXACT` of a Bézier patch or mesh; errors in the file name the
/// file and its line.
fn read_patches(
    f: &Fields<'_>,
    mesh: bool,
    base: &Path,
    detail: &str,
) -> Result<ShapeKind, SceneError> {
    let method = match f.text(Key::Method)? {
        None => PatchMethod::default(),
        Some((word, span)) => PatchMethod::parse(word).ok_or_else(|| {
            invalid(
                span,
                Key::Method,
                format!(
                    "must be GROEBNER, RESULTANT, GROEBNER_EXACT or RESULTANT_EXACT, found `{word}`"
                ),
            )
        })?,
    };
    let field = f
        .get(Key::ControlPoints)
        .ok_or_else(|| f.missing(Key::ControlPoints, detail))?;
    let span = &field.value_span;
    let file = match &field.value {
        Eval::Text(file) => file,
        Eval::Points(_) if mesh => {
            return Err(invalid(
                span,
                Key::ControlPoints,
                "a BEZIER_MESH reads its patches from a .bpt file; inline points are for a \
                 BEZIER_PATCH",
            ));
        }
        Eval::Points(points) if points.len() != 16 => {
            return Err(invalid(
                span,
                Key::ControlPoints,
                format!(
                    "a bicubic patch needs 16 control points, found {}",
                    points.len()
                ),
            ));
        }
        Eval::Points(points) => {
            let patch = ControlNet::new(3, 3, points.clone())
                .map_err(|e| invalid(span, Key::ControlPoints, e.to_string()))?;
            return Ok(ShapeKind::BezierPatches {
                patches: vec![patch],
                method,
            });
        }
        _ => return Err(Fields::wrong(field, "a file name or 16 points `(x, y, z)`")),
    };
    let patches = read_named(file, span, base, MAX_CONTROL_POINT_BYTES, |text| {
        if mesh {
            parse_bpt(text)
        } else {
            parse_control_points(text).map(|p| vec![p])
        }
    })?;
    Ok(ShapeKind::BezierPatches { patches, method })
}

/// `File Name = FILE` of a `MESH`: a Wavefront OBJ file read relative to the scene; errors in
/// it name the file, line and column.
fn read_mesh(f: &Fields<'_>, base: &Path) -> Result<ShapeKind, SceneError> {
    let (file, span) = f.required_path(Key::FileName)?;
    let mesh = read_named(file, span, base, MAX_MESH_BYTES, parse_obj)?;
    Ok(ShapeKind::Mesh {
        mesh: Box::new(mesh),
    })
}

/// Reads the file `name` (relative to `base`; at most `limit` bytes of UTF-8 text) that the
/// value at `span` names, and parses it: a read or parse error names the value's place and the
/// file, and the parser's message its place in the file.
fn read_named<T, E: std::fmt::Display>(
    name: &str,
    span: &Span,
    base: &Path,
    limit: u64,
    parse: impl FnOnce(&str) -> Result<T, E>,
) -> Result<T, SceneError> {
    let path = base.join(name);
    let fail = |reason: String| {
        SceneError::at(
            span,
            ErrorKind::FileRead {
                path: path.display().to_string(),
                reason,
            },
        )
    };
    let bytes = read_bounded(&path, limit).map_err(|e| fail(e.to_string()))?;
    let text = String::from_utf8(bytes).map_err(|e| {
        fail(format!(
            "not UTF-8 text (byte {} is 0x{:02X})",
            e.utf8_error().valid_up_to(),
            e.as_bytes()[e.utf8_error().valid_up_to()]
        ))
    })?;
    parse(&text).map_err(|e| fail(e.to_string()))
}

#[cfg(test)]
mod tests {
    use super::*;

    const CAMERA: &str = "#camera Eye = (0,-8,5) LookAt = (0,0,0) ViewField = 50\n";

    fn scene(text: &str) -> Result<ValidScene, SceneError> {
        parse(&format!("{CAMERA}{text}"), Path::new("b.scene"))
    }

    fn only_object(text: &str) -> Object {
        let s = scene(text).unwrap();
        assert_eq!(s.objects.len(), 1, "one object in {text:?}");
        s.into_scene()
            .objects
            .into_iter()
            .next()
            .unwrap_or_else(|| unreachable!())
    }

    #[test]
    fn stam_sphere_radius_squared_and_polygon_corner_order() {
        let o = only_object("#object Type = SPHERE Center = (1,2,3) Radius^2 = 6.25");
        assert_eq!(
            o.shape,
            ShapeKind::Sphere {
                center: DVec3::new(1.0, 2.0, 3.0),
                radius: 2.5
            },
            "sqrt of Radius^2"
        );
        // Stam's a and d are opposite corners: the boundary runs a, b, d, c.
        let o =
            only_object("#object Type = POLYGON a = (0,0,0) b = (1,0,0) c = (0,1,0) d = (1,1,0)");
        let v = |x, y| DVec3::new(x, y, 0.0);
        assert_eq!(
            o.shape,
            ShapeKind::Polygon {
                vertices: vec![v(0.0, 0.0), v(1.0, 0.0), v(1.0, 1.0), v(0.0, 1.0)]
            },
            "unit square in boundary order"
        );
    }

    #[test]
    fn defaults_and_shorthands() {
        let s = scene("#light Source = (1,2,3)\n#object Type = TORUS Center = (0,0,0) Axis = (0,0,1) MajorRadius = 2 MinorRadius = 1 Cs = 0.5 Scale = 2").unwrap();
        assert_eq!(s.world, World::default(), "no #world: defaults");
        assert_eq!(s.viewport, Viewport::default(), "no #viewport: defaults");
        assert_eq!(s.output, None, "no #save");
        assert_eq!(
            s.lights[0].color,
            Rgb::ONE,
            "light colour defaults to white"
        );
        let CameraSpec::LookAt(cam) = &s.camera else {
            panic!("look-at camera")
        };
        assert_eq!(cam.up, DVec3::Z, "Up defaults to z");
        let o = &s.objects[0];
        assert_eq!(o.material.cs, Rgb::splat(0.5), "one number is a grey");
        assert_eq!(o.transform.scale, DVec3::splat(2.0), "uniform scale");
        let d = Material::default();
        assert_eq!(
            (o.material.kd, o.material.ks, o.material.illumination),
            (d.kd, d.ks, d.illumination),
            "material defaults"
        );
    }

    #[test]
    fn full_world_viewport_save_and_stam_camera() {
        let s = parse(
            "#world BackGnd = (0.1,0.2,0.3) Shadows = OFF MaxDepth = 3 Attenuation = ON\n\
             #camera Focal = 2 Distance = 7.4 ViewField = 65 Rotation = (1,2,3) Center = (4,5,6)\n\
             #viewport Size = (640, 480) Origin = (0, 0) Resolution = (4, 2)\n\
             #save File Name = \"out dir/a.png\"",
            Path::new("w.scene"),
        )
        .unwrap();
        assert_eq!(
            s.world,
            World {
                background: DVec3::new(0.1, 0.2, 0.3),
                shadows: false,
                max_depth: 3,
                attenuation: true
            },
            "world"
        );
        assert_eq!(
            s.camera,
            CameraSpec::Stam(StamCamera {
                focal: 2.0,
                distance: 7.4,
                view_field_deg: 65.0,
                rotation_deg: DVec3::new(1.0, 2.0, 3.0),
                center: DVec3::new(4.0, 5.0, 6.0),
            }),
            "Stam's camera"
        );
        assert_eq!(
            s.viewport,
            Viewport {
                size: [640, 480],
                resolution: [4, 2]
            },
            "viewport"
        );
        assert_eq!(
            s.output,
            Some(PathBuf::from("out dir/a.png")),
            "output as written"
        );
    }

    #[test]
    fn textures_by_name_or_the_only_one() {
        let s = scene(
            "#object Type = PLANE Origin = (0,0,0) Normal = (0,0,1) Illumination = TEXTURE\n\
             #texture Type = CHECKER Unit = 0.5 Color1 = 1 Color2 = (0.5, 0, 0)",
        )
        .unwrap();
        assert_eq!(
            s.objects[0].material.texture,
            Some(0),
            "the only texture, declared later"
        );
        assert_eq!(
            s.textures[0],
            Texture::Checker(CheckerTexture {
                unit: 0.5,
                colors: [Rgb::ONE, DVec3::new(0.5, 0.0, 0.0)]
            }),
            "checker"
        );
        let s = scene(
            "#texture Type = CHECKER Unit = 1 Name = a\n#texture Type = CHECKER Unit = 2 Name = B\n\
             #object Type = PLANE Origin = (0,0,0) Normal = (0,0,1) Illumination = MIRROR Texture = b",
        )
        .unwrap();
        assert_eq!(
            s.objects[0].material.texture,
            Some(1),
            "by name, case-insensitive"
        );
        assert_eq!(
            s.objects[0].material.illumination,
            Illumination::Mirror,
            "a textured mirror"
        );
    }

    #[test]
    fn image_textures_are_read_relative_to_the_scene() {
        let dir = tempfile::tempdir().unwrap();
        // Stam's raw format: all red bytes, then green, then blue; 2 × 1 texels.
        std::fs::write(dir.path().join("t.rgb"), [255u8, 0, 0, 255, 51, 102]).unwrap();
        let mut png = image::RgbImage::new(1, 2);
        png.put_pixel(0, 1, image::Rgb([0, 255, 0]));
        png.save(dir.path().join("t.png")).unwrap();
        let file = dir.path().join("s.scene");
        let s = parse(
            &format!("{CAMERA}#texture Size = 2x1 File Name = t.rgb Unit = 3\n#texture File Name = t.png Unit = 1"),
            &file,
        )
        .unwrap();
        let Texture::Image(raw) = &s.textures[0] else {
            panic!("image")
        };
        assert_eq!(
            (raw.width, raw.height, raw.unit),
            (2, 1, 3.0),
            "raw size and unit"
        );
        assert_eq!(
            raw.texels,
            vec![DVec3::new(1.0, 0.0, 0.2), DVec3::new(0.0, 1.0, 0.4)],
            "planar RGB"
        );
        let Texture::Image(p) = &s.textures[1] else {
            panic!("image")
        };
        assert_eq!((p.width, p.height), (1, 2), "png size");
        assert_eq!(
            p.texels,
            vec![Rgb::ZERO, DVec3::Y],
            "png texels, first row first"
        );

        let err = parse(
            &format!("{CAMERA}#texture Size = 3x1 File Name = t.rgb Unit = 3"),
            &file,
        )
        .unwrap_err();
        assert!(
            err.to_string()
                .ends_with("expected 3 × 3 × 1 = 9 bytes of planar RGB, found 6"),
            "{err}"
        );
        let err = parse(
            &format!("{CAMERA}#texture Size = 1x1\nFile Name = nope.rgb Unit = 1"),
            &file,
        )
        .unwrap_err();
        assert_eq!(
            err.span().map(|s| (s.line, s.col)),
            Some((3, 13)),
            "points at the file name: {err}"
        );
        assert!(err.to_string().contains("cannot read `"), "{err}");
    }
}

//! The scene language's syntax tree and its parser: tokens → [`SceneAst`] with spans.
//!
//! The grammar (full version, for users, in `paper-notes/scene-language.md`):
//!
//! ```text
//! file     = { block }
//! block    = COMMAND { entry }                      COMMAND = "#" word at a line start
//! entry    = key "=" value  |  "Let" name "=" expr
//! key      = word { word } [ "^" integer ]          all on one line, up to and with the "="
//! value    = expr | "(" expr { "," expr } ")" | word | bounds | file-name
//! bounds   = "NONE" | "BOX" "[" expr "," expr "]" "x" "[" … "]" "x" "[" … "]"
//! expr     = term { ("+" | "-") term }
//! term     = unary { ("*" | "/") unary }
//! unary    = "-" unary | power
//! power    = atom [ "^" unary ]                     right-associative
//! atom     = number | name | "sqrt" "(" expr ")" | "(" expr ")"
//! ```
//!
//! **Keys with spaces.** A key is the run of words before `=` on one line, so `File Name`,
//! `Bounding volume` and `Radius^2` are keys like any other, and several `Key = value` pairs
//! may share a line. What ends a value is its type, which the key decides: a number ends
//! where the expression ends (the next word cannot continue it), a vector at `)`, an
//! enumerated word after one word, a file name at the next blank. So in
//! `Shadows = ON Attenuation = OFF`, `ON` is the whole value of `Shadows` and `Attenuation`
//! starts the next key. Keys and enumerated words are matched case-insensitively, with any
//! run of blanks inside a key read as one space.
//!
//! Every string of the language — commands, keys, enumerated values, function names — is
//! dispatched here, once, into the enums below ([`Command`], [`Key`], [`ShapeType`], …);
//! unknown ones are errors naming file, line, column and the word. Semantic checks (required
//! and duplicate keys, ranges, evaluating expressions) happen in the build step.

use std::path::Path;
use std::sync::Arc;

use super::error::{ErrorKind, SceneError, Span};
use super::expr::{Axis, BinOp, Expr, ExprKind, Spanned};
use super::lexer::{Lexer, Tok, Token};
use super::model::Illumination;

/// How deep parentheses, unary minus and exponents may nest. Bounds the parser's recursion
/// (a few stack frames per level) so no input can overflow the stack.
pub const MAX_NESTING: u32 = 128;

/// How deep an expression tree may be (a flat sum `a + b + c + …` is as deep as it is long).
/// Bounds the recursion of the build step, the printer and `Drop`; 1000 leaves room for a
/// fully expanded degree-12 polynomial (455 terms) written out by hand.
pub const MAX_EXPR_DEPTH: u32 = 1000;

/// A parsed scene file: its blocks in file order.
#[derive(Clone, Debug)]
pub struct SceneAst {
    /// The blocks, in file order.
    pub blocks: Vec<Block>,
    /// The end of the text (where "missing block" errors point).
    pub end: Span,
}

impl PartialEq for SceneAst {
    fn eq(&self, other: &Self) -> bool {
        self.blocks == other.blocks
    }
}

/// One `#command` and its entries.
#[derive(Clone, Debug, PartialEq)]
pub struct Block {
    /// The command; its span is the `#`.
    pub command: Spanned<Command>,
    /// The entries, in file order.
    pub entries: Vec<Entry>,
}

/// One entry of a block.
#[derive(Clone, Debug, PartialEq)]
pub enum Entry {
    /// `Key = value`.
    Set {
        /// The key; its span is the key's first word.
        key: Spanned<Key>,
        /// The value; its span is the value's first token.
        value: Spanned<Value>,
    },
    /// `Let name = expr`: a constant for the rest of the block.
    Let {
        /// The name as written; its span is the name.
        name: Spanned<String>,
        /// The defining expression.
        value: Expr,
    },
}

/// A value, typed by its key.
#[derive(Clone, Debug, PartialEq)]
pub enum Value {
    /// A number or expression (`0.5`, `3/2`, `sqrt(5)`, `phi`, or an `Equation`), or a single
    /// number where a colour or scale is expected (meaning all three components).
    Number(Expr),
    /// `(a, b, c)` or `(w, h)`; also `w x h` (Stam's texture size), stored as `(w, h)`.
    Tuple(Vec<Expr>),
    /// `ON` (`true`) or `OFF`.
    Switch(bool),
    /// An object type (`Type` in `#object`).
    Shape(ShapeType),
    /// A texture type (`Type` in `#texture`).
    TextureType(TextureType),
    /// An illumination model.
    Illumination(Illumination),
    /// `NONE` (`None`) or `BOX [x0,x1]x[y0,y1]x[z0,z1]` (the three `[lo, hi]` pairs).
    Bounds(Option<Box<[[Expr; 2]; 3]>>),
    /// `SPHERE (x, y, z) r`: a bounding sphere, centre then radius.
    BoundingSphere(Box<[Expr; 4]>),
    /// A file name, as written (quotes removed).
    Path(String),
    /// Inline points `(x, y, z) (x, y, z) …` (`Control points` of a Bézier patch), each
    /// exactly three expressions; the list may span lines.
    Points(Vec<Vec<Expr>>),
    /// A name (`Name` of a texture, `Texture` of an object), as written.
    Word(String),
}

/// The commands that start blocks.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Command {
    /// `#world`: background, shadows, recursion depth, attenuation.
    World,
    /// `#camera`: Stam's camera or the eye / look-at camera.
    Camera,
    /// `#light`: one point light.
    Light,
    /// `#object`: one object.
    Object,
    /// `#viewport`: image size and preview resolution.
    Viewport,
    /// `#save`: the output file.
    Save,
    /// `#texture`: an image or checker texture.
    Texture,
}

impl Command {
    /// Every command.
    pub const ALL: [Command; 7] = [
        Command::World,
        Command::Camera,
        Command::Light,
        Command::Object,
        Command::Viewport,
        Command::Save,
        Command::Texture,
    ];

    /// The command as written after `#` (lower case).
    pub fn name(self) -> &'static str {
        match self {
            Command::World => "world",
            Command::Camera => "camera",
            Command::Light => "light",
            Command::Object => "object",
            Command::Viewport => "viewport",
            Command::Save => "save",
            Command::Texture => "texture",
        }
    }

    fn from_name(name: &str) -> Option<Command> {
        Command::ALL
            .into_iter()
            .find(|c| c.name().eq_ignore_ascii_case(name))
    }
}

/// Object types (`Type = …` in `#object`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum ShapeType {
    /// `SPHERE`: `Center`, `Radius` or `Radius^2`.
    Sphere,
    /// `PLANE`: `Origin`, `Normal`.
    Plane,
    /// `POLYGON`: Stam's four corners `a b c d` (`a`, `d` opposite).
    Polygon,
    /// `TRIANGLE`: `a b c`.
    Triangle,
    /// `BOX`: `Min`, `Max`.
    Box,
    /// `SUPERQUADRIC`: `Center`, `Size`, `Power` (Kuchkuda §3.5).
    Superquadric,
    /// `TORUS`: `Center`, `Axis`, `MajorRadius`, `MinorRadius`.
    Torus,
    /// `ALGEBRAIC_SURFACE`: `Equation`.
    AlgebraicSurface,
    /// `BEZIER_PATCH`: `Control points` (a file of 16 points, Stam's form), `Method`.
    BezierPatch,
    /// `BEZIER_MESH`: `Control points` (a `.bpt` file of patches), `Method`.
    BezierMesh,
    /// `CONE`: `Base`, `BaseRadius`, `Apex`, `ApexRadius`, `Caps`.
    Cone,
    /// `CYLINDER`: `Base`, `Apex`, `Radius`, `Caps`.
    Cylinder,
    /// `MESH`: `File Name` (a Wavefront OBJ file of triangles or polygons).
    Mesh,
}

impl ShapeType {
    /// Every type.
    pub const ALL: [ShapeType; 13] = [
        ShapeType::Sphere,
        ShapeType::Plane,
        ShapeType::Polygon,
        ShapeType::Triangle,
        ShapeType::Box,
        ShapeType::Superquadric,
        ShapeType::Torus,
        ShapeType::AlgebraicSurface,
        ShapeType::BezierPatch,
        ShapeType::BezierMesh,
        ShapeType::Cone,
        ShapeType::Cylinder,
        ShapeType::Mesh,
    ];

    /// The type as written after `Type =`.
    pub fn name(self) -> &'static str {
        match self {
            ShapeType::Sphere => "SPHERE",
            ShapeType::Plane => "PLANE",
            ShapeType::Polygon => "POLYGON",
            ShapeType::Triangle => "TRIANGLE",
            ShapeType::Box => "BOX",
            ShapeType::Superquadric => "SUPERQUADRIC",
            ShapeType::Torus => "TORUS",
            ShapeType::AlgebraicSurface => "ALGEBRAIC_SURFACE",
            ShapeType::BezierPatch => "BEZIER_PATCH",
            ShapeType::BezierMesh => "BEZIER_MESH",
            ShapeType::Cone => "CONE",
            ShapeType::Cylinder => "CYLINDER",
            ShapeType::Mesh => "MESH",
        }
    }

    /// The type's own keys, required ones first (the build step says which are required).
    pub fn keys(self) -> &'static [Key] {
        match self {
            ShapeType::Sphere => &[Key::Center, Key::Radius, Key::Radius2],
            ShapeType::Plane => &[Key::Origin, Key::Normal],
            ShapeType::Polygon => &[Key::A, Key::B, Key::C, Key::D],
            ShapeType::Triangle => &[Key::A, Key::B, Key::C],
            ShapeType::Box => &[Key::Min, Key::Max],
            ShapeType::Superquadric => &[Key::Center, Key::Size, Key::Power],
            ShapeType::Torus => &[Key::Center, Key::Axis, Key::MajorRadius, Key::MinorRadius],
            ShapeType::AlgebraicSurface => &[Key::Equation],
            ShapeType::BezierPatch | ShapeType::BezierMesh => &[Key::ControlPoints, Key::Method],
            ShapeType::Cone => &[
                Key::Base,
                Key::BaseRadius,
                Key::Apex,
                Key::ApexRadius,
                Key::Caps,
            ],
            ShapeType::Cylinder => &[Key::Base, Key::Apex, Key::Radius, Key::Caps],
            ShapeType::Mesh => &[Key::FileName],
        }
    }
}

/// Texture types (`Type = …` in `#texture`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum TextureType {
    /// `IMAGE` (the default, Stam's texture): `Size`, `File Name`, `Unit`.
    Image,
    /// `CHECKER`: `Unit`, `Color1`, `Color2`.
    Checker,
}

impl TextureType {
    /// The type as written after `Type =`.
    pub fn name(self) -> &'static str {
        match self {
            TextureType::Image => "IMAGE",
            TextureType::Checker => "CHECKER",
        }
    }
}

/// The illumination names in Stam's spelling (§4.2.1), plus `AMBIENT` as an alias.
pub(crate) fn illumination_name(i: Illumination) -> &'static str {
    match i {
        Illumination::Blackbody => "BLACKBODY",
        Illumination::Ambient => "AMBIANT",
        Illumination::Diffuse => "DIFFUSE",
        Illumination::Texture => "TEXTURE",
        Illumination::Specular => "SPECULAR",
        Illumination::Mirror => "MIRROR",
        Illumination::Transparent => "TRANSPARENT",
    }
}

const ILLUMINATIONS: [Illumination; 7] = [
    Illumination::Blackbody,
    Illumination::Ambient,
    Illumination::Diffuse,
    Illumination::Texture,
    Illumination::Specular,
    Illumination::Mirror,
    Illumination::Transparent,
];

macro_rules! keys {
    ($($(#[$doc:meta])* $variant:ident => $name:literal,)*) => {
        /// Every key of the language, in its canonical spelling ([`Key::name`]).
        #[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
        pub enum Key {
            $($(#[$doc])* $variant,)*
        }

        impl Key {
            /// Every key.
            pub const ALL: &'static [Key] = &[$(Key::$variant,)*];

            /// The canonical spelling, as the printer writes it.
            pub fn name(self) -> &'static str {
                match self {
                    $(Key::$variant => $name,)*
                }
            }
        }
    };
}

keys! {
    /// `BackGnd = colour` (`#world`).
    BackGnd => "BackGnd",
    /// `Shadows = ON|OFF` (`#world`).
    Shadows => "Shadows",
    /// `MaxDepth = n` (`#world`).
    MaxDepth => "MaxDepth",
    /// `Attenuation = ON|OFF` (`#world`).
    Attenuation => "Attenuation",
    /// `Focal = f` (Stam's `#camera`).
    Focal => "Focal",
    /// `Distance = d` (Stam's `#camera`).
    Distance => "Distance",
    /// `ViewField = degrees` (`#camera`, both forms).
    ViewField => "ViewField",
    /// `Rotation = (a1, a2, a3)` (Stam's `#camera`).
    Rotation => "Rotation",
    /// `Center = (x, y, z)` (Stam's `#camera`; sphere, superquadric, torus).
    Center => "Center",
    /// `Eye = (x, y, z)` (look-at `#camera`).
    Eye => "Eye",
    /// `LookAt = (x, y, z)` (look-at `#camera`).
    LookAt => "LookAt",
    /// `Up = (x, y, z)` (look-at `#camera`).
    Up => "Up",
    /// `Source = (x, y, z)` (`#light`).
    Source => "Source",
    /// `Color = colour` (`#light`).
    Color => "Color",
    /// `Type = …` (`#object`, `#texture`).
    Type => "Type",
    /// `Illumination = …` (`#object`).
    Illumination => "Illumination",
    /// `Cs = colour` (`#object`).
    Cs => "Cs",
    /// `Cr = colour` (`#object`).
    Cr => "Cr",
    /// `Ka = k` (`#object`).
    Ka => "Ka",
    /// `Kd = k` (`#object`).
    Kd => "Kd",
    /// `Ks = k` (`#object`).
    Ks => "Ks",
    /// `Kt = k` (`#object`).
    Kt => "Kt",
    /// `n = exponent` (`#object`).
    N => "n",
    /// `Kn = index ratio` (`#object`).
    Kn => "Kn",
    /// `Texture = name` (`#object`).
    Texture => "Texture",
    /// `Bounding volume = NONE | BOX …` (`#object`).
    BoundingVolume => "Bounding volume",
    /// `Translate = (x, y, z)` (`#object`).
    Translate => "Translate",
    /// `Rotate = (ax, ay, az)` in degrees (`#object`).
    Rotate => "Rotate",
    /// `Scale = (sx, sy, sz)` or `Scale = s` (`#object`).
    Scale => "Scale",
    /// `Radius = r` (sphere).
    Radius => "Radius",
    /// `Radius^2 = r²` (sphere, Stam's form).
    Radius2 => "Radius^2",
    /// `Origin = (x, y, z)` (plane) or `Origin = (x, y)` (`#viewport`, ignored).
    Origin => "Origin",
    /// `Normal = (x, y, z)` (plane).
    Normal => "Normal",
    /// `a = (x, y, z)` (polygon, triangle).
    A => "a",
    /// `b = (x, y, z)` (polygon, triangle).
    B => "b",
    /// `c = (x, y, z)` (polygon, triangle).
    C => "c",
    /// `d = (x, y, z)` (polygon).
    D => "d",
    /// `Min = (x, y, z)` (box).
    Min => "Min",
    /// `Max = (x, y, z)` (box).
    Max => "Max",
    /// `Size = (sx, sy, sz)` (superquadric), `(w, h)` (`#viewport`, `#texture`).
    Size => "Size",
    /// `Power = p` (superquadric).
    Power => "Power",
    /// `Axis = (x, y, z)` (torus).
    Axis => "Axis",
    /// `MajorRadius = R` (torus).
    MajorRadius => "MajorRadius",
    /// `MinorRadius = r` (torus).
    MinorRadius => "MinorRadius",
    /// `Equation = polynomial in x, y, z` (algebraic surface).
    Equation => "Equation",
    /// `Control points = file` (Bézier patch: 16 points; Bézier mesh: a `.bpt` file).
    ControlPoints => "Control points",
    /// `Method = GROEBNER | RESULTANT` (Bézier patch and mesh).
    Method => "Method",
    /// `Resolution = (rx, ry)` (`#viewport`).
    Resolution => "Resolution",
    /// `File Name = name` (`#save`, `#texture`, `MESH`).
    FileName => "File Name",
    /// `Name = word` (`#texture`).
    Name => "Name",
    /// `Unit = length` (`#texture`).
    Unit => "Unit",
    /// `Color1 = colour` (checker `#texture`).
    Color1 => "Color1",
    /// `Color2 = colour` (checker `#texture`).
    Color2 => "Color2",
    /// `Base = (x, y, z)` (cone, cylinder: centre of the base circle).
    Base => "Base",
    /// `Apex = (x, y, z)` (cone, cylinder: centre of the apex circle).
    Apex => "Apex",
    /// `BaseRadius = r` (cone).
    BaseRadius => "BaseRadius",
    /// `ApexRadius = r` (cone).
    ApexRadius => "ApexRadius",
    /// `Caps = ON|OFF` (cone, cylinder: flat disks close the ends; default OFF).
    Caps => "Caps",
}

impl Key {
    /// The key whose canonical spelling matches `phrase` ignoring case; `phrase` has its
    /// words joined by single spaces.
    fn from_phrase(phrase: &str) -> Option<Key> {
        Key::ALL
            .iter()
            .copied()
            .find(|k| k.name().eq_ignore_ascii_case(phrase))
    }
}

/// What a key's value looks like; decides where the value ends.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum ValueKind {
    /// An expression.
    Number,
    /// `(a, b, c)`.
    Vector,
    /// `(a, b, c)` or a single expression meaning `(e, e, e)`.
    VectorOrScalar,
    /// `(w, h)` or `w x h`.
    Pair,
    /// `ON` or `OFF`.
    Switch,
    /// An object type.
    Shape,
    /// A texture type.
    TextureType,
    /// An illumination name.
    Illumination,
    /// `NONE` or `BOX […]x[…]x[…]`.
    Bounds,
    /// A file name.
    Path,
    /// A file name, or inline points `(x, y, z) …` when the value starts with `(`.
    ControlPoints,
    /// A name.
    Word,
}

/// Where a key may appear, and what its value is there.
pub(crate) enum KeyUse {
    /// Allowed, with this kind of value.
    Allowed(ValueKind),
    /// An `#object` key of another type.
    OtherShape,
    /// Not a key of this block.
    Unknown,
}

/// The value kind of `key` in a block `command` (for `#object`, of type `shape`).
pub(crate) fn key_use(command: Command, shape: Option<ShapeType>, key: Key) -> KeyUse {
    use KeyUse::Allowed;
    use ValueKind as V;
    match (command, key) {
        (Command::World, Key::BackGnd) => Allowed(V::VectorOrScalar),
        (Command::World, Key::Shadows | Key::Attenuation) => Allowed(V::Switch),
        (Command::World, Key::MaxDepth) => Allowed(V::Number),
        (Command::Camera, Key::Focal | Key::Distance | Key::ViewField) => Allowed(V::Number),
        (Command::Camera, Key::Rotation | Key::Center | Key::Eye | Key::LookAt | Key::Up) => {
            Allowed(V::Vector)
        }
        (Command::Light, Key::Source) => Allowed(V::Vector),
        (Command::Light, Key::Color) => Allowed(V::VectorOrScalar),
        (Command::Viewport, Key::Size | Key::Origin | Key::Resolution) => Allowed(V::Pair),
        (Command::Save, Key::FileName) => Allowed(V::Path),
        (Command::Texture, Key::Type) => Allowed(V::TextureType),
        (Command::Texture, Key::Name) => Allowed(V::Word),
        (Command::Texture, Key::Size) => Allowed(V::Pair),
        (Command::Texture, Key::FileName) => Allowed(V::Path),
        (Command::Texture, Key::Unit) => Allowed(V::Number),
        (Command::Texture, Key::Color1 | Key::Color2) => Allowed(V::VectorOrScalar),
        (Command::Object, key) => object_key_use(shape, key),
        _ => KeyUse::Unknown,
    }
}

fn object_key_use(shape: Option<ShapeType>, key: Key) -> KeyUse {
    use KeyUse::Allowed;
    use ValueKind as V;
    let common = match key {
        Key::Type => Some(V::Shape),
        Key::Illumination => Some(V::Illumination),
        Key::Cs | Key::Cr | Key::Scale => Some(V::VectorOrScalar),
        Key::Ka | Key::Kd | Key::Ks | Key::Kt | Key::N | Key::Kn => Some(V::Number),
        Key::Texture => Some(V::Word),
        Key::BoundingVolume => Some(V::Bounds),
        Key::Translate | Key::Rotate => Some(V::Vector),
        _ => None,
    };
    if let Some(kind) = common {
        return Allowed(kind);
    }
    let shape_kind = match key {
        Key::Radius | Key::Radius2 | Key::Power | Key::MajorRadius | Key::MinorRadius => V::Number,
        Key::BaseRadius | Key::ApexRadius => V::Number,
        Key::Base | Key::Apex => V::Vector,
        Key::Caps => V::Switch,
        Key::Equation => V::Number,
        Key::Center | Key::Origin | Key::Normal | Key::Min | Key::Max | Key::Axis => V::Vector,
        Key::A | Key::B | Key::C | Key::D | Key::Size => V::Vector,
        Key::ControlPoints => V::ControlPoints,
        Key::Method => V::Word,
        Key::FileName => V::Path,
        _ => return KeyUse::Unknown,
    };
    match shape {
        Some(s) if s.keys().contains(&key) => Allowed(shape_kind),
        _ if ShapeType::ALL.iter().any(|s| s.keys().contains(&key)) => KeyUse::OtherShape,
        _ => KeyUse::Unknown,
    }
}

/// Parses scene text into a syntax tree without interpreting it (no I/O).
///
/// `file` only names the text in spans. Errors name file, line, column and the offending
/// token or key; nothing panics on any input.
///
/// # Examples
/// ```
/// use std::path::Path;
/// use render::scene::{parse_syntax, Command};
/// let ast = parse_syntax("#world Shadows = ON\n#light Source = (5,-5,10)", Path::new("a.scene"))?;
/// assert_eq!(ast.blocks.len(), 2);
/// assert_eq!(ast.blocks[1].command.value, Command::Light);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn parse_syntax(text: &str, file: &Path) -> Result<SceneAst, SceneError> {
    Parser::new(text, Arc::from(file)).file()
}

struct Parser<'a> {
    lexer: Lexer<'a>,
    peeked: Option<Token>,
    /// The last token taken, for "missing operator" messages.
    last: Option<Tok>,
    /// Just after the last token taken (for errors at the end of the text).
    last_end: Option<Span>,
    /// Current recursion depth of the expression parser.
    nesting: u32,
}

/// A parsed sub-expression and the depth of its tree.
type Sub = (Expr, u32);

impl<'a> Parser<'a> {
    fn new(text: &'a str, file: Arc<Path>) -> Self {
        Parser {
            lexer: Lexer::new(text, file),
            peeked: None,
            last: None,
            last_end: None,
            nesting: 0,
        }
    }

    fn peek(&mut self) -> Result<&Token, SceneError> {
        match &mut self.peeked {
            Some(t) => Ok(t),
            slot @ None => Ok(slot.insert(self.lexer.next_token()?)),
        }
    }

    fn next(&mut self) -> Result<Token, SceneError> {
        let t = match self.peeked.take() {
            Some(t) => t,
            None => self.lexer.next_token()?,
        };
        if t.tok != Tok::Eof {
            self.last_end = Some(end_of(&t));
        }
        self.last = Some(t.tok.clone());
        Ok(t)
    }

    /// "expected …, found …" at `token`; at the end of the text, just after the last token
    /// instead, where the missing piece belongs.
    fn expected(&self, token: &Token, expected: impl Into<String>) -> SceneError {
        let span = match (&token.tok, &self.last_end) {
            (Tok::Eof, Some(end)) => end,
            _ => &token.span,
        };
        SceneError::at(
            span,
            ErrorKind::Expected {
                expected: expected.into(),
                found: token.tok.describe(),
            },
        )
    }

    /// Takes the next token if it is `tok`, else fails with "expected {what}".
    fn expect(&mut self, tok: &Tok, what: &str) -> Result<Token, SceneError> {
        let t = self.next()?;
        if &t.tok == tok {
            Ok(t)
        } else {
            Err(self.expected(&t, what))
        }
    }

    fn file(mut self) -> Result<SceneAst, SceneError> {
        let mut blocks = Vec::new();
        loop {
            let t = self.next()?;
            match t.tok {
                Tok::Eof => {
                    return Ok(SceneAst {
                        blocks,
                        end: t.span,
                    });
                }
                Tok::Command(ref name) => {
                    let Some(command) = Command::from_name(name) else {
                        return Err(SceneError::at(
                            &t.span,
                            ErrorKind::UnknownCommand { name: name.clone() },
                        ));
                    };
                    let command = Spanned {
                        value: command,
                        span: t.span,
                    };
                    blocks.push(self.block(command)?);
                }
                _ => {
                    return Err(self.expected(&t, "a command such as `#world` or `#object`"));
                }
            }
        }
    }

    fn block(&mut self, command: Spanned<Command>) -> Result<Block, SceneError> {
        let mut entries = Vec::new();
        let mut shape = None;
        while !matches!(self.peek()?.tok, Tok::Command(_) | Tok::Eof) {
            entries.push(self.entry(command.value, &mut shape)?);
        }
        Ok(Block { command, entries })
    }

    /// One `key = value` or `Let name = expr`.
    fn entry(
        &mut self,
        command: Command,
        shape: &mut Option<ShapeType>,
    ) -> Result<Entry, SceneError> {
        let first = self.next()?;
        let Tok::Word(ref word) = first.tok else {
            return Err(self.expected(&first, format!("a key or a command in #{}", command.name())));
        };
        let line = first.span.line;
        let mut words = vec![(word.clone(), first.span.clone())];
        let mut last_end = end_of(&first);
        let mut power = None;
        // Stam's reader (`GetPatch`, ray1.c) writes `Control points in FILE`: `in` stands for `=`.
        let mut stam_in = false;
        loop {
            let t = self.peek()?.clone();
            if t.span.line != line {
                break;
            }
            match &t.tok {
                Tok::Word(w)
                    if w.eq_ignore_ascii_case("in")
                        && words.len() == 2
                        && words[0].0.eq_ignore_ascii_case("control")
                        && words[1].0.eq_ignore_ascii_case("points") =>
                {
                    self.next()?;
                    stam_in = true;
                    break;
                }
                Tok::Word(w) => {
                    words.push((w.clone(), t.span.clone()));
                    self.next()?;
                    last_end = end_of(&t);
                }
                Tok::Caret if power.is_none() => {
                    self.next()?;
                    let n = self.next()?;
                    match &n.tok {
                        Tok::Number { text, .. } if n.span.line == line => {
                            power = Some(text.clone());
                            last_end = end_of(&n);
                        }
                        _ => return Err(self.expected(&n, "a number after `^` in a key")),
                    }
                    // `Radius^2` ends the key.
                    break;
                }
                _ => break,
            }
        }
        let mut phrase = words
            .iter()
            .map(|(w, _)| w.as_str())
            .collect::<Vec<_>>()
            .join(" ");
        if let Some(p) = &power {
            phrase.push('^');
            phrase.push_str(p);
        }
        if !stam_in {
            let t = self.peek()?.clone();
            if t.tok != Tok::Eq || t.span.line != line {
                // `Shadows ON`: point at the word after the longest known key, not at the end.
                for n in (1..words.len()).rev() {
                    let prefix = words[..n]
                        .iter()
                        .map(|(w, _)| w.as_str())
                        .collect::<Vec<_>>()
                        .join(" ");
                    if Key::from_phrase(&prefix).is_some() {
                        let (next, span) = &words[n];
                        return Err(SceneError::at(
                            span,
                            ErrorKind::Expected {
                                expected: format!("`=` after `{prefix}`"),
                                found: format!("`{next}`"),
                            },
                        ));
                    }
                }
                let what = format!("`=` after `{phrase}`");
                if t.span.line != line {
                    return Err(SceneError::at(
                        &last_end,
                        ErrorKind::Expected {
                            expected: what,
                            found: "end of line".into(),
                        },
                    ));
                }
                return Err(self.expected(&t, what));
            }
            self.next()?;
        }

        if words[0].0.eq_ignore_ascii_case("let") && power.is_none() {
            let [_, (name, name_span)] = <[_; 2]>::try_from(words).map_err(|_| {
                SceneError::at(
                    &first.span,
                    ErrorKind::Expected {
                        expected: "`Let name = value` with a one-word name".into(),
                        found: format!("`{phrase} =`"),
                    },
                )
            })?;
            let reason = if ["x", "y", "z"]
                .iter()
                .any(|v| v.eq_ignore_ascii_case(&name))
            {
                Some("it is a variable")
            } else if name.eq_ignore_ascii_case("sqrt") {
                Some("it is a function")
            } else if name.as_bytes().first().is_some_and(u8::is_ascii_digit) {
                Some("a name must start with a letter")
            } else {
                None
            };
            if let Some(reason) = reason {
                return Err(SceneError::at(
                    &name_span,
                    ErrorKind::BadConstant { name, reason },
                ));
            }
            let value = self.expr()?;
            return Ok(Entry::Let {
                name: Spanned {
                    value: name,
                    span: name_span,
                },
                value,
            });
        }

        let Some(key) = Key::from_phrase(&phrase) else {
            return Err(SceneError::at(
                &first.span,
                ErrorKind::UnknownKey {
                    key: phrase,
                    command: command.name(),
                },
            ));
        };
        if command == Command::Object && shape.is_none() && key != Key::Type {
            return Err(SceneError::at(
                &first.span,
                ErrorKind::TypeNotFirst { found: phrase },
            ));
        }
        let kind = match key_use(command, *shape, key) {
            KeyUse::Allowed(kind) => kind,
            KeyUse::OtherShape => {
                let type_name = shape.map_or("", ShapeType::name);
                return Err(SceneError::at(
                    &first.span,
                    ErrorKind::KeyNotForType {
                        key: phrase,
                        type_name,
                        command: command.name(),
                    },
                ));
            }
            KeyUse::Unknown => {
                return Err(SceneError::at(
                    &first.span,
                    ErrorKind::UnknownKey {
                        key: phrase,
                        command: command.name(),
                    },
                ));
            }
        };
        let value = self.value(key, kind)?;
        if let (Command::Object, Value::Shape(s)) = (command, &value.value) {
            if shape.is_some() {
                // A second `Type`: the build step reports the duplicate; keep the first type
                // for key checks.
            } else {
                *shape = Some(*s);
            }
        }
        Ok(Entry::Set {
            key: Spanned {
                value: key,
                span: first.span,
            },
            value,
        })
    }

    /// Reads one word for an enumerated value.
    fn word_value(
        &mut self,
        key: Key,
        expected: &'static str,
    ) -> Result<(String, Span), SceneError> {
        let t = self.next()?;
        match t.tok {
            Tok::Word(w) => Ok((w, t.span)),
            _ => Err(self.expected(&t, format!("{expected} after `{} =`", key.name()))),
        }
    }

    fn value(&mut self, key: Key, kind: ValueKind) -> Result<Spanned<Value>, SceneError> {
        if kind == ValueKind::Path {
            // Checked before peeking: a file name is not made of tokens.
            return self.path_value();
        }
        if kind == ValueKind::ControlPoints {
            if let Some(t) = self.peeked.take() {
                self.lexer.rewind(&t);
            }
            // A file name cannot start with `(` unquoted (the printer quotes such names).
            if self.lexer.next_char_on_line() != Some('(') {
                return self.path_value();
            }
            return self.point_list(key);
        }
        let span = self.peek()?.span.clone();
        let unknown = |found: String, expected: &'static str, span: &Span| {
            SceneError::at(
                span,
                ErrorKind::UnknownWord {
                    key: key.name(),
                    found,
                    expected,
                },
            )
        };
        let value = match kind {
            ValueKind::Number => Value::Number(self.expr()?),
            ValueKind::Vector | ValueKind::VectorOrScalar => {
                let v = self.tuple_or_expr()?;
                match (&v, kind) {
                    (Value::Tuple(items), _) if items.len() == 3 => v,
                    (Value::Number(_), ValueKind::VectorOrScalar) => v,
                    (Value::Tuple(items), _) => {
                        return Err(SceneError::at(
                            &span,
                            ErrorKind::Expected {
                                expected: format!("a vector `(x, y, z)` for `{}`", key.name()),
                                found: format!("{} components", items.len()),
                            },
                        ));
                    }
                    _ => {
                        return Err(SceneError::at(
                            &span,
                            ErrorKind::Expected {
                                expected: format!("a vector `(x, y, z)` for `{}`", key.name()),
                                found: "a single number".into(),
                            },
                        ));
                    }
                }
            }
            ValueKind::Pair => self.pair(key)?,
            ValueKind::Switch => {
                let (w, span) = self.word_value(key, "ON or OFF")?;
                match w.to_ascii_uppercase().as_str() {
                    "ON" => Value::Switch(true),
                    "OFF" => Value::Switch(false),
                    _ => return Err(unknown(w, "ON or OFF", &span)),
                }
            }
            ValueKind::Shape => {
                const TYPES: &str = "SPHERE, PLANE, POLYGON, TRIANGLE, BOX, SUPERQUADRIC, TORUS, ALGEBRAIC_SURFACE, BEZIER_PATCH, BEZIER_MESH, CONE, CYLINDER or MESH";
                let (w, span) = self.word_value(key, "an object type")?;
                match ShapeType::ALL
                    .into_iter()
                    .find(|s| s.name().eq_ignore_ascii_case(&w))
                {
                    Some(s) => Value::Shape(s),
                    None => return Err(unknown(w, TYPES, &span)),
                }
            }
            ValueKind::TextureType => {
                let (w, span) = self.word_value(key, "IMAGE or CHECKER")?;
                match [TextureType::Image, TextureType::Checker]
                    .into_iter()
                    .find(|t| t.name().eq_ignore_ascii_case(&w))
                {
                    Some(t) => Value::TextureType(t),
                    None => return Err(unknown(w, "IMAGE or CHECKER", &span)),
                }
            }
            ValueKind::Illumination => {
                const NAMES: &str =
                    "BLACKBODY, AMBIANT, DIFFUSE, SPECULAR, MIRROR, TRANSPARENT or TEXTURE";
                let (w, span) = self.word_value(key, "an illumination model")?;
                let found = ILLUMINATIONS
                    .into_iter()
                    .find(|i| illumination_name(*i).eq_ignore_ascii_case(&w))
                    .or_else(|| {
                        w.eq_ignore_ascii_case("AMBIENT")
                            .then_some(Illumination::Ambient)
                    });
                match found {
                    Some(i) => Value::Illumination(i),
                    None => return Err(unknown(w, NAMES, &span)),
                }
            }
            ValueKind::Bounds => self.bounds(key)?,
            ValueKind::Word => Value::Word(self.word_value(key, "a name")?.0),
            ValueKind::Path | ValueKind::ControlPoints => return self.path_value(),
        };
        Ok(Spanned { value, span })
    }

    /// A file name, read as raw text from the next token's start.
    fn path_value(&mut self) -> Result<Spanned<Value>, SceneError> {
        if let Some(t) = self.peeked.take() {
            self.lexer.rewind(&t);
        }
        let (path, span) = self.lexer.path()?;
        self.last = None;
        self.last_end = Some(self.lexer.position());
        if path.is_empty() {
            return Err(SceneError::at(
                &span,
                ErrorKind::Expected {
                    expected: "a file name".into(),
                    found: "`\"\"`".into(),
                },
            ));
        }
        Ok(Spanned {
            value: Value::Path(path),
            span,
        })
    }

    /// Inline points `(x, y, z) (x, y, z) …`, on one line or several: the list ends at the
    /// first token that is not `(` (the next key or command).
    fn point_list(&mut self, key: Key) -> Result<Spanned<Value>, SceneError> {
        let span = self.peek()?.span.clone();
        let mut points = Vec::new();
        while self.peek()?.tok == Tok::LParen {
            let at = self.peek()?.span.clone();
            let found = match self.tuple_or_expr()? {
                Value::Tuple(items) if items.len() == 3 => {
                    points.push(items);
                    continue;
                }
                Value::Tuple(items) => format!("{} components", items.len()),
                _ => "a single number".to_owned(),
            };
            return Err(SceneError::at(
                &at,
                ErrorKind::Expected {
                    expected: format!("a point `(x, y, z)` in `{}`", key.name()),
                    found,
                },
            ));
        }
        Ok(Spanned {
            value: Value::Points(points),
            span,
        })
    }

    /// `(w, h)` or Stam's `w x h` with plain numbers (`256x256`).
    fn pair(&mut self, key: Key) -> Result<Value, SceneError> {
        let span = self.peek()?.span.clone();
        let wrong = |found: String| {
            SceneError::at(
                &span,
                ErrorKind::Expected {
                    expected: format!("a pair `(w, h)` or `w x h` for `{}`", key.name()),
                    found,
                },
            )
        };
        if let Tok::Number { value: wv, .. } = self.peek()?.tok {
            let w = self.next()?;
            if !matches!(&self.peek()?.tok, Tok::Word(x) if x.eq_ignore_ascii_case("x")) {
                return Err(wrong("a single number".into()));
            }
            self.next()?;
            let h = self.next()?;
            let Tok::Number { value: hv, .. } = h.tok else {
                return Err(self.expected(&h, format!("a number in `{} = w x h`", key.name())));
            };
            let num = |v: f64, t: &Token| Expr {
                kind: ExprKind::Number(v),
                span: t.span.clone(),
            };
            return Ok(Value::Tuple(vec![num(wv, &w), num(hv, &h)]));
        }
        match self.tuple_or_expr()? {
            Value::Tuple(items) if items.len() == 2 => Ok(Value::Tuple(items)),
            Value::Tuple(items) => Err(wrong(format!("{} components", items.len()))),
            _ => Err(wrong("a single number".into())),
        }
    }

    /// `NONE` or `BOX [x0,x1]x[y0,y1]x[z0,z1]` (the box may start on the next line, as in
    /// Stam's §4.2.1).
    fn bounds(&mut self, key: Key) -> Result<Value, SceneError> {
        let (w, span) = self.word_value(key, "NONE, BOX or SPHERE")?;
        if w.eq_ignore_ascii_case("NONE") {
            return Ok(Value::Bounds(None));
        }
        if w.eq_ignore_ascii_case("SPHERE") {
            let at = self.peek()?.span.clone();
            let Value::Tuple(centre) = self.tuple_or_expr()? else {
                return Err(SceneError::at(
                    &at,
                    ErrorKind::Expected {
                        expected: "a centre `(x, y, z)` after `SPHERE`".into(),
                        found: "a single number".into(),
                    },
                ));
            };
            let Ok([x, y, z]) = <[Expr; 3]>::try_from(centre) else {
                return Err(SceneError::at(
                    &at,
                    ErrorKind::Expected {
                        expected: "a centre `(x, y, z)` after `SPHERE`".into(),
                        found: "another number of components".into(),
                    },
                ));
            };
            let radius = self.expr()?;
            return Ok(Value::BoundingSphere(Box::new([x, y, z, radius])));
        }
        if !w.eq_ignore_ascii_case("BOX") {
            return Err(SceneError::at(
                &span,
                ErrorKind::UnknownWord {
                    key: key.name(),
                    found: w,
                    expected: "NONE, BOX or SPHERE",
                },
            ));
        }
        let mut ranges = Vec::with_capacity(3);
        for axis in 0..3 {
            if axis > 0 {
                let t = self.next()?;
                if !matches!(&t.tok, Tok::Word(w) if w.eq_ignore_ascii_case("x")) {
                    return Err(self.expected(&t, "`x` between the ranges of a box"));
                }
            }
            self.expect(&Tok::LBracket, "`[` to start a range `[lo, hi]`")?;
            let lo = self.expr()?;
            self.expect(&Tok::Comma, "`,` between the ends of a range `[lo, hi]`")?;
            let hi = self.expr()?;
            self.expect(&Tok::RBracket, "`]` to end a range `[lo, hi]`")?;
            ranges.push([lo, hi]);
        }
        let [x, y, z]: [[Expr; 2]; 3] = ranges.try_into().map_err(|_| {
            SceneError::at(
                &span,
                ErrorKind::Expected {
                    expected: "three ranges".into(),
                    found: "fewer".into(),
                },
            )
        })?;
        Ok(Value::Bounds(Some(Box::new([x, y, z]))))
    }

    fn enter(&mut self, span: &Span) -> Result<(), SceneError> {
        self.nesting += 1;
        if self.nesting > MAX_NESTING {
            return Err(SceneError::at(
                span,
                ErrorKind::TooDeep { max: MAX_NESTING },
            ));
        }
        Ok(())
    }

    fn leave(&mut self) {
        self.nesting -= 1;
    }

    /// A parenthesised tuple `(a, b, …)` or an expression (which may itself start with `(`).
    fn tuple_or_expr(&mut self) -> Result<Value, SceneError> {
        if self.peek()?.tok != Tok::LParen {
            return Ok(Value::Number(self.expr()?));
        }
        let open = self.next()?;
        self.enter(&open.span)?;
        let (mut first, depth) = self.binary(0)?;
        if self.peek()?.tok == Tok::Comma {
            let mut items = vec![first];
            while self.peek()?.tok == Tok::Comma {
                self.next()?;
                items.push(self.binary(0)?.0);
            }
            self.close(&open)?;
            self.leave();
            return Ok(Value::Tuple(items));
        }
        self.close(&open)?;
        self.leave();
        first.span = open.span;
        let (e, _) = self.binary_rest(first, depth, 0)?;
        Ok(Value::Number(e))
    }

    fn close(&mut self, open: &Token) -> Result<(), SceneError> {
        let what = format!(
            "`)` to close the `(` at line {}, column {}",
            open.span.line, open.span.col
        );
        self.expect(&Tok::RParen, &what).map(|_| ())
    }

    /// A whole expression.
    fn expr(&mut self) -> Result<Expr, SceneError> {
        Ok(self.binary(0)?.0)
    }

    fn binary(&mut self, min_prec: u8) -> Result<Sub, SceneError> {
        let (lhs, depth) = self.unary()?;
        self.binary_rest(lhs, depth, min_prec)
    }

    /// Precedence climbing: `+ -` bind at 1, `* /` at 2, `^` at 4 (right-associative);
    /// unary minus sits at 3, so `-x^2` is `-(x^2)` and `2^-1` is allowed.
    fn binary_rest(
        &mut self,
        mut lhs: Expr,
        mut depth: u32,
        min_prec: u8,
    ) -> Result<Sub, SceneError> {
        loop {
            let t = self.peek()?.clone();
            let op = match t.tok {
                Tok::Plus => BinOp::Add,
                Tok::Minus => BinOp::Sub,
                Tok::Star => BinOp::Mul,
                Tok::Slash => BinOp::Div,
                Tok::Caret => BinOp::Pow,
                Tok::Number { .. } | Tok::Word(_) | Tok::LParen if !t.spaced => {
                    let after = t.tok.text();
                    let before = self.last.as_ref().map(Tok::text).unwrap_or_default();
                    return Err(SceneError::at(
                        &t.span,
                        ErrorKind::MissingOperator { before, after },
                    ));
                }
                _ => return Ok((lhs, depth)),
            };
            let prec = match op {
                BinOp::Add | BinOp::Sub => 1,
                BinOp::Mul | BinOp::Div => 2,
                BinOp::Pow => 4,
            };
            if prec < min_prec {
                return Ok((lhs, depth));
            }
            let op_tok = self.next()?;
            // `^` is right-associative: its right side parses at its own level.
            let (rhs, rhs_depth) = if op == BinOp::Pow {
                self.enter(&op_tok.span)?;
                let r = self.binary(prec)?;
                self.leave();
                r
            } else {
                self.binary(prec + 1)?
            };
            depth = depth.max(rhs_depth) + 1;
            if depth > MAX_EXPR_DEPTH {
                return Err(SceneError::at(
                    &op_tok.span,
                    ErrorKind::TooDeep {
                        max: MAX_EXPR_DEPTH,
                    },
                ));
            }
            let span = lhs.span.clone();
            lhs = Expr {
                kind: ExprKind::Binary {
                    op: Spanned {
                        value: op,
                        span: op_tok.span,
                    },
                    lhs: Box::new(lhs),
                    rhs: Box::new(rhs),
                },
                span,
            };
        }
    }

    fn unary(&mut self) -> Result<Sub, SceneError> {
        if self.peek()?.tok == Tok::Minus {
            let minus = self.next()?;
            self.enter(&minus.span)?;
            let (inner, depth) = self.binary(4)?;
            self.leave();
            let e = Expr {
                kind: ExprKind::Neg(Box::new(inner)),
                span: minus.span,
            };
            return Ok((e, depth + 1));
        }
        self.atom()
    }

    fn atom(&mut self) -> Result<Sub, SceneError> {
        let t = self.next()?;
        match t.tok {
            Tok::Number { value, .. } => Ok((
                Expr {
                    kind: ExprKind::Number(value),
                    span: t.span,
                },
                1,
            )),
            Tok::Word(ref w) => {
                let var = match w.as_str() {
                    "x" | "X" => Some(Axis::X),
                    "y" | "Y" => Some(Axis::Y),
                    "z" | "Z" => Some(Axis::Z),
                    _ => None,
                };
                if let Some(axis) = var {
                    return Ok((
                        Expr {
                            kind: ExprKind::Var(axis),
                            span: t.span,
                        },
                        1,
                    ));
                }
                let call = self.peek()?.tok == Tok::LParen;
                if w.eq_ignore_ascii_case("sqrt") {
                    let open = self.expect(&Tok::LParen, "`(` after `sqrt`")?;
                    self.enter(&open.span)?;
                    let (arg, depth) = self.binary(0)?;
                    self.close(&open)?;
                    self.leave();
                    return Ok((
                        Expr {
                            kind: ExprKind::Sqrt(Box::new(arg)),
                            span: t.span,
                        },
                        depth + 1,
                    ));
                }
                if call && !self.peek()?.spaced {
                    return Err(SceneError::at(
                        &t.span,
                        ErrorKind::UnknownFunction { name: w.clone() },
                    ));
                }
                Ok((
                    Expr {
                        kind: ExprKind::Name(w.clone()),
                        span: t.span,
                    },
                    1,
                ))
            }
            Tok::LParen => {
                self.enter(&t.span)?;
                let (mut inner, depth) = self.binary(0)?;
                self.close(&t)?;
                self.leave();
                // A parenthesised expression starts at its `(`, where messages point.
                inner.span = t.span;
                Ok((inner, depth))
            }
            _ => Err(self.expected(&t, "a number, a name or `(`")),
        }
    }
}

/// The position just after a one-line token.
fn end_of(t: &Token) -> Span {
    let width = t.tok.text().chars().count() as u32;
    Span {
        col: t.span.col.saturating_add(width),
        ..t.span.clone()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn parse(text: &str) -> Result<SceneAst, SceneError> {
        parse_syntax(text, Path::new("t.scene"))
    }

    /// The keys of a block, in order, with `Let` written as `Let name`.
    fn keys(block: &Block) -> Vec<String> {
        block
            .entries
            .iter()
            .map(|e| match e {
                Entry::Set { key, .. } => key.value.name().to_owned(),
                Entry::Let { name, .. } => format!("Let {}", name.value),
            })
            .collect()
    }

    fn value(block: &Block, key: Key) -> &Value {
        block
            .entries
            .iter()
            .find_map(|e| match e {
                Entry::Set { key: k, value } if k.value == key => Some(&value.value),
                _ => None,
            })
            .unwrap_or_else(|| panic!("no {key:?} in {block:?}"))
    }

    fn num(v: f64) -> Expr {
        Expr {
            kind: ExprKind::Number(v),
            span: Span {
                file: Arc::from(Path::new("")),
                line: 0,
                col: 0,
            },
        }
    }

    #[test]
    fn keys_with_spaces_and_several_pairs_per_line() {
        let ast = parse(
            "#save\n  file   NAME = out/t.png\n\
             #world Shadows = on Attenuation = OFF BackGnd = 0.2\n\
             #object Type = sphere Center = (0,0,0) RADIUS^2 = 4 Ka = 0.1 Kd = 0.7\n\
             Bounding Volume = BOX\n   [-1,1]x[-2, 2] X [-3,3]\n",
        )
        .unwrap();
        assert_eq!(
            keys(&ast.blocks[0]),
            ["File Name"],
            "two-word key, any case and spacing"
        );
        assert_eq!(
            value(&ast.blocks[0], Key::FileName),
            &Value::Path("out/t.png".into()),
            "raw path"
        );
        assert_eq!(
            keys(&ast.blocks[1]),
            ["Shadows", "Attenuation", "BackGnd"],
            "three pairs on a line"
        );
        assert_eq!(
            value(&ast.blocks[1], Key::Shadows),
            &Value::Switch(true),
            "`on` is ON"
        );
        assert_eq!(
            keys(&ast.blocks[2]),
            ["Type", "Center", "Radius^2", "Ka", "Kd", "Bounding volume"],
            "object keys"
        );
        let Value::Bounds(Some(b)) = value(&ast.blocks[2], Key::BoundingVolume) else {
            panic!("bounds expected")
        };
        let neg = |v: f64| Expr {
            kind: ExprKind::Neg(Box::new(num(v))),
            ..num(0.0)
        };
        assert_eq!(b[2], [neg(3.0), num(3.0)], "third range, on the next line");
        assert_eq!(ast.blocks[2].command.span.line, 4, "block line");
    }

    #[test]
    fn spans_point_at_keys_and_values() {
        let ast = parse("#light\n  Source = (5,-5,10)   Color = 1").unwrap();
        let Entry::Set { key, value } = &ast.blocks[0].entries[1] else {
            panic!("set")
        };
        assert_eq!((key.span.line, key.span.col), (2, 24), "`Color` position");
        assert_eq!((value.span.line, value.span.col), (2, 32), "`1` position");
    }

    #[test]
    fn precedence_and_associativity() {
        let ast = parse("#world Let a = -2^2 Let b = 2^3^2 Let c = 1 - 2 - 3 Let d = 2*-3 + 8/4/2")
            .unwrap();
        let lets: Vec<&Expr> = ast.blocks[0]
            .entries
            .iter()
            .map(|e| match e {
                Entry::Let { value, .. } => value,
                Entry::Set { .. } => panic!("only Let"),
            })
            .collect();
        let bin = |op, l, r| Expr {
            kind: ExprKind::Binary {
                op: Spanned {
                    value: op,
                    span: num(0.0).span,
                },
                lhs: Box::new(l),
                rhs: Box::new(r),
            },
            ..num(0.0)
        };
        let neg = |e| Expr {
            kind: ExprKind::Neg(Box::new(e)),
            ..num(0.0)
        };
        assert_eq!(
            *lets[0],
            neg(bin(BinOp::Pow, num(2.0), num(2.0))),
            "-2^2 is -(2^2)"
        );
        assert_eq!(
            *lets[1],
            bin(BinOp::Pow, num(2.0), bin(BinOp::Pow, num(3.0), num(2.0))),
            "^ is right-associative"
        );
        assert_eq!(
            *lets[2],
            bin(BinOp::Sub, bin(BinOp::Sub, num(1.0), num(2.0)), num(3.0)),
            "- is left-associative"
        );
        assert_eq!(
            *lets[3],
            bin(
                BinOp::Add,
                bin(BinOp::Mul, num(2.0), neg(num(3.0))),
                bin(BinOp::Div, bin(BinOp::Div, num(8.0), num(4.0)), num(2.0))
            ),
            "unary minus after an operator; / is left-associative"
        );
    }

    #[test]
    fn stam_texture_size_and_tuples() {
        let ast =
            parse("#texture Size = 256x128 File Name = \"wood texture.rgb\" Unit = 10").unwrap();
        let b = &ast.blocks[0];
        assert_eq!(
            value(b, Key::Size),
            &Value::Tuple(vec![num(256.0), num(128.0)]),
            "256x128"
        );
        assert_eq!(
            value(b, Key::FileName),
            &Value::Path("wood texture.rgb".into()),
            "quoted name"
        );
        assert_eq!(
            keys(b),
            ["Size", "File Name", "Unit"],
            "all three keys on one line"
        );
        let ast = parse("#object Type = TORUS Scale = (2) Cs = ((1), 2, 3)").unwrap();
        assert_eq!(
            value(&ast.blocks[0], Key::Scale),
            &Value::Number(num(2.0)),
            "(2) is a number"
        );
        assert!(
            matches!(value(&ast.blocks[0], Key::Cs), Value::Tuple(v) if v.len() == 3),
            "a tuple whose first item is parenthesised"
        );
    }

    #[test]
    fn nesting_is_bounded_without_overflowing_the_stack() {
        let deep = format!("#world Let a = {}1{}", "(".repeat(5000), ")".repeat(5000));
        let err = parse(&deep).unwrap_err();
        assert!(
            matches!(err.kind(), Some(ErrorKind::TooDeep { .. })),
            "{err}"
        );
        let minus = format!("#world Let a = {}1", "-".repeat(5000));
        assert!(
            matches!(
                parse(&minus).unwrap_err().kind(),
                Some(ErrorKind::TooDeep { .. })
            ),
            "unary chain"
        );
        let powers = format!("#world Let a = 1{}", "^1".repeat(5000));
        assert!(
            matches!(
                parse(&powers).unwrap_err().kind(),
                Some(ErrorKind::TooDeep { .. })
            ),
            "^ chain"
        );
        let long_sum = format!("#world Let a = 1{}", " + 1".repeat(5000));
        let err = parse(&long_sum).unwrap_err();
        assert!(
            matches!(
                err.kind(),
                Some(ErrorKind::TooDeep {
                    max: MAX_EXPR_DEPTH
                })
            ),
            "{err}"
        );
        let ok_sum = format!("#world Let a = 1{}", " + 1".repeat(900));
        assert!(parse(&ok_sum).is_ok(), "a 900-term sum is fine");
    }

    #[test]
    fn errors_name_line_column_and_token() {
        let cases: &[(&str, &str)] = &[
            (
                "Shadows = ON",
                "t.scene:1:1: expected a command such as `#world` or `#object`, found `Shadows`",
            ),
            (
                "#world\n  Kx = 1",
                "t.scene:2:3: unknown key `Kx` in #world",
            ),
            ("#dump\n", "t.scene:1:1: unknown command `#dump`"),
            (
                "#object\nRadius = 1",
                "t.scene:2:1: #object must start with `Type = …`, found `Radius`",
            ),
            (
                "#object Type = TORUS Radius = 1",
                "t.scene:1:22: key `Radius` does not apply to type TORUS in #object",
            ),
            (
                "#object Type = CUBE",
                "t.scene:1:16: unknown value `CUBE` for `Type` (expected SPHERE, PLANE, POLYGON, TRIANGLE, BOX, SUPERQUADRIC, TORUS, ALGEBRAIC_SURFACE, BEZIER_PATCH, BEZIER_MESH, CONE, CYLINDER or MESH)",
            ),
            (
                "#world Shadows = MAYBE",
                "t.scene:1:18: unknown value `MAYBE` for `Shadows` (expected ON or OFF)",
            ),
            (
                "#world Shadows ON",
                "t.scene:1:16: expected `=` after `Shadows`, found `ON`",
            ),
            (
                "#world Shadows\n= ON",
                "t.scene:1:15: expected `=` after `Shadows`, found end of line",
            ),
            (
                "#light Source = (1, 2)",
                "t.scene:1:17: expected a vector `(x, y, z)` for `Source`, found 2 components",
            ),
            (
                "#light Source = 1",
                "t.scene:1:17: expected a vector `(x, y, z)` for `Source`, found a single number",
            ),
            (
                "#light Source = (1, 2, 3",
                "t.scene:1:25: expected `)` to close the `(` at line 1, column 17, found end of file",
            ),
            (
                "#object Type = ALGEBRAIC_SURFACE Equation = 2x",
                "t.scene:1:46: missing `*` or space between `2` and `x`",
            ),
            (
                "#object Type = SPHERE Ka = 0.1Kd = 1",
                "t.scene:1:31: missing `*` or space between `0.1` and `Kd`",
            ),
            (
                "#object Type = SPHERE Ka = cos(1)",
                "t.scene:1:28: unknown function `cos` (the only function is `sqrt`)",
            ),
            (
                "#world Let x = 1",
                "t.scene:1:12: cannot define `x`: it is a variable",
            ),
            (
                "#world Let a b = 1",
                "t.scene:1:8: expected `Let name = value` with a one-word name, found `Let a b =`",
            ),
            (
                "#world BackGnd = (1, 2, *)",
                "t.scene:1:25: expected a number, a name or `(`, found `*`",
            ),
            (
                "#viewport Size = 3",
                "t.scene:1:18: expected a pair `(w, h)` or `w x h` for `Size`, found a single number",
            ),
            (
                "#viewport Size = (3, 4, 5)",
                "t.scene:1:18: expected a pair `(w, h)` or `w x h` for `Size`, found 3 components",
            ),
            (
                "#viewport Size = 3 x y",
                "t.scene:1:22: expected a number in `Size = w x h`, found `y`",
            ),
            (
                "#save File Name =\n out.png",
                "t.scene:1:18: expected a file name on the same line, found end of line",
            ),
            (
                "#object Type = BOX Bounding volume = BOX [0,1]x[0,1]",
                "t.scene:1:53: expected `x` between the ranges of a box, found end of file",
            ),
            (
                "#object Type = BOX Bounding volume = SPHERE",
                "t.scene:1:44: expected a number, a name or `(`, found end of file",
            ),
            (
                "#object Type = BOX Bounding volume = BALL (0,0,0) 1",
                "t.scene:1:38: unknown value `BALL` for `Bounding volume` (expected NONE, BOX or SPHERE)",
            ),
            (
                "#world Radius^x = 1",
                "t.scene:1:15: expected a number after `^` in a key, found `x`",
            ),
        ];
        for (text, message) in cases {
            let err = parse(text).unwrap_err();
            assert_eq!(err.to_string(), *message, "parsing {text:?}");
        }
    }
}

//! Malformed scene files: each error names the right line, column and key or token, and
//! nothing panics on random or mutated input.

use std::path::Path;

use proptest::prelude::*;
use render::scene::parse;

const CAMERA: &str = "#camera Eye = (0,-8,5) LookAt = (0,0,0) ViewField = 50\n";
const TORUS: &str =
    "#object Type = TORUS Center = (0,0,0) Axis = (0,0,1) MajorRadius = 2 MinorRadius = 1\n";

/// One malformed input: the text (after a valid camera line unless it starts with `!`), the
/// expected line and column, the key or token the message must quote, and the message.
struct Case {
    text: &'static str,
    line: u32,
    col: u32,
    quoted: &'static str,
    message: &'static str,
}

const fn case(
    text: &'static str,
    line: u32,
    col: u32,
    quoted: &'static str,
    message: &'static str,
) -> Case {
    Case {
        text,
        line,
        col,
        quoted,
        message,
    }
}

/// Lines count from the camera line (line 1) unless the text starts with `!`.
const CASES: &[Case] = &[
    // Lexer.
    case("#world BackGnd = @", 2, 18, "@", "unexpected character `@`"),
    case(
        "#world MaxDepth = 1e999",
        2,
        19,
        "1e999",
        "number `1e999` is out of range",
    ),
    case(
        "#world Shadows = ON #light",
        2,
        21,
        "#light",
        "command `#light` must start a line",
    ),
    // Structure and keys.
    case(
        "!Shadows = ON",
        1,
        1,
        "Shadows",
        "expected a command such as `#world` or `#object`, found `Shadows`",
    ),
    case("#worlds", 2, 1, "#worlds", "unknown command `#worlds`"),
    case(
        "#object Type = TORUS\n  Kx = 1",
        3,
        3,
        "Kx",
        "unknown key `Kx` in #object",
    ),
    case(
        "#light Source = (0,0,0)\nBackGnd = 1",
        3,
        1,
        "BackGnd",
        "unknown key `BackGnd` in #light",
    ),
    case(
        "#object Type = SPHERE\nMajorRadius = 2",
        3,
        1,
        "MajorRadius",
        "key `MajorRadius` does not apply to type SPHERE in #object",
    ),
    case(
        "#object\nCenter = (0,0,0)",
        3,
        1,
        "Center",
        "#object must start with `Type = …`, found `Center`",
    ),
    case(
        "#save File Nam = a.png",
        2,
        7,
        "File Nam",
        "unknown key `File Nam` in #save",
    ),
    case(
        "#world Shadows = YES",
        2,
        18,
        "YES",
        "unknown value `YES` for `Shadows` (expected ON or OFF)",
    ),
    case(
        "#object Type = TORUS Illumination = GLOSSY",
        2,
        37,
        "GLOSSY",
        "unknown value `GLOSSY` for `Illumination` (expected BLACKBODY, AMBIANT, DIFFUSE, SPECULAR, MIRROR, TRANSPARENT or TEXTURE)",
    ),
    case(
        "#light Source (0,0,0)",
        2,
        15,
        "=",
        "expected `=` after `Source`, found `(`",
    ),
    case(
        "#light Source = (0,0)",
        2,
        17,
        "Source",
        "expected a vector `(x, y, z)` for `Source`, found 2 components",
    ),
    case(
        "#world BackGnd = (1, 2, 3",
        2,
        26,
        ")",
        "expected `)` to close the `(` at line 2, column 18, found end of file",
    ),
    // Duplicates and missing pieces.
    case(
        "#world Shadows = ON\nShadows = OFF",
        3,
        1,
        "Shadows",
        "duplicate key `Shadows` in #world (first given at line 2, column 8)",
    ),
    case(
        "#world\n#world",
        3,
        1,
        "#world",
        "duplicate #world block (first given at line 2)",
    ),
    case(
        "#camera Eye = (0,0,1) LookAt = (0,0,0) ViewField = 50",
        2,
        1,
        "#camera",
        "duplicate #camera block (first given at line 1)",
    ),
    case(
        "!#world Shadows = ON\n",
        2,
        1,
        "#camera",
        "missing #camera block",
    ),
    case(
        "#object Type = TORUS Center = (0,0,0) Axis = (0,0,1) MajorRadius = 2",
        2,
        1,
        "MinorRadius",
        "missing key `MinorRadius` in #object of type TORUS",
    ),
    case(
        "#object Type = SPHERE Center = (0,0,0)",
        2,
        1,
        "Radius",
        "missing key `Radius` in #object of type SPHERE (or `Radius^2`)",
    ),
    case(
        "#light Color = 1",
        2,
        1,
        "Source",
        "missing key `Source` in #light",
    ),
    case(
        "!#camera Eye = (0,0,5) ViewField = 50",
        1,
        1,
        "LookAt",
        "missing key `LookAt` in #camera (look-at camera: Eye, LookAt, ViewField and optional Up)",
    ),
    case(
        "!#camera Focal = 1 Distance = 5 ViewField = 50 Rotation = (0,0,0)",
        1,
        1,
        "Center",
        "missing key `Center` in #camera (Stam's camera: Focal, Distance, ViewField, Rotation, Center)",
    ),
    case(
        "!#camera Eye = (0,0,5) LookAt = (0,0,0)\n  Focal = 2 ViewField = 50",
        2,
        3,
        "Focal",
        "`Focal` cannot be combined with `Eye` in #camera (Stam's camera and the look-at camera are two different forms)",
    ),
    case(
        "#object Type = SPHERE Center = (0,0,0) Radius = 1 Radius^2 = 1",
        2,
        51,
        "Radius^2",
        "`Radius^2` cannot be combined with `Radius` in #object (give the radius one way)",
    ),
    // Values out of range.
    case(
        "#world MaxDepth = 2.5",
        2,
        19,
        "MaxDepth",
        "invalid `MaxDepth`: must be a whole number from 1 to 64, found 2.5",
    ),
    case(
        "#viewport Size = (840, 0)",
        2,
        18,
        "Size",
        "invalid `Size`: sizes must be whole numbers from 1 to 65536, found (840, 0)",
    ),
    case(
        "#object Type = SPHERE Center = (0,0,0) Radius = -1",
        2,
        40,
        "Radius",
        "invalid `Radius`: must be a positive finite number",
    ),
    case(
        "#object Type = TORUS Center = (0,0,0) Axis = (0,0,0) MajorRadius = 2 MinorRadius = 1",
        2,
        39,
        "Axis",
        "invalid `Axis`: must not be the zero vector",
    ),
    case(
        "#object Type = SUPERQUADRIC Center = (0,0,0) Size = (1,1,1) Power = 2.5",
        2,
        69,
        "Power",
        "invalid `Power`: must be a whole number ≥ 1, found 2.5",
    ),
    case(
        "#object Type = BOX Min = (0,0,0) Max = (1,1,1) Kd = -0.5",
        2,
        53,
        "Kd",
        "invalid `Kd`: must not be negative, found -0.5",
    ),
    case(
        "#object Type = BOX Min = (0,0,0) Max = (1,1,1) Kn = 0",
        2,
        53,
        "Kn",
        "invalid `Kn`: must be positive, found 0",
    ),
    case(
        "#object Type = BOX Min = (0,0,0) Max = (1,1,1) Scale = (1,0,1)",
        2,
        48,
        "Scale",
        "invalid `Scale`: scale factors must not be zero",
    ),
    case(
        "#object Type = BOX Min = (0,0,0) Max = (1,1,1)\nBounding volume = BOX [0,1]x[2,1]x[0,1]",
        3,
        30,
        "Bounding volume",
        "invalid `Bounding volume`: range [2, 1] is empty",
    ),
    case(
        "#object Type = BOX Min = (0,0,0) Max = (1,1,1)\nBounding volume = SPHERE (0,0,0) -1",
        3,
        19,
        "Bounding volume",
        "invalid `Bounding volume`: the sphere's radius must be positive, found -1",
    ),
    case(
        "#object Type = BOX Min = (0,0,0) Max = (1,1,1)\nBounding volume = SPHERE (0,0) 1",
        3,
        26,
        "SPHERE",
        "expected a centre `(x, y, z)` after `SPHERE`, found another number of components",
    ),
    case(
        "!#camera Eye = (1,2,3) LookAt = (1,2,3) ViewField = 50",
        1,
        23,
        "LookAt",
        "invalid `LookAt`: must differ from `Eye`",
    ),
    case(
        "!#camera Eye = (0,0,5) LookAt = (0,0,0) ViewField = 50",
        1,
        23,
        "LookAt",
        "invalid `LookAt`: the view direction must not be parallel to `Up` (default (0, 0, 1))",
    ),
    case(
        "!#camera Eye = (0,-8,5) LookAt = (0,0,0) ViewField = 180",
        1,
        53,
        "ViewField",
        "invalid `ViewField`: must be between 0 and 180 degrees, found 180",
    ),
    // Textures.
    case(
        "#object Type = BOX Min = (0,0,0) Max = (1,1,1) Texture = wood",
        2,
        58,
        "wood",
        "no #texture is named `wood`",
    ),
    case(
        "#object Type = BOX Min = (0,0,0) Max = (1,1,1) Illumination = TEXTURE",
        2,
        48,
        "TEXTURE",
        "TEXTURE illumination needs `Texture = name` when the file has 0 textures (it may omit it when there is exactly one)",
    ),
    case(
        "#texture Type = CHECKER Unit = 1 File Name = a.rgb",
        2,
        34,
        "File Name",
        "key `File Name` does not apply to type CHECKER in #texture",
    ),
    case(
        "#texture Type = CHECKER",
        2,
        1,
        "Unit",
        "missing key `Unit` in #texture",
    ),
    // Equations and constants.
    case(
        "#object Type = ALGEBRAIC_SURFACE\nEquation = x^2 + y^2 + z^2 - R^2",
        3,
        30,
        "R",
        "unknown name `R` (define it earlier in the block with `Let R = …`)",
    ),
    case(
        "#object Type = ALGEBRAIC_SURFACE\nEquation = x^2/(y + 1)",
        3,
        16,
        "y + 1",
        "not a polynomial: division by `y + 1`, an expression in x, y, z",
    ),
    case(
        "#object Type = ALGEBRAIC_SURFACE\nEquation = z^-1",
        3,
        14,
        "-1",
        "not a polynomial: negative exponent -1 of an expression in x, y, z",
    ),
    case(
        "#object Type = ALGEBRAIC_SURFACE\nEquation = x^2 - x^2 + 1",
        3,
        1,
        "Equation",
        "invalid `Equation`: must have degree at least 1",
    ),
    case(
        "#object Type = ALGEBRAIC_SURFACE\nLet a = 1\nLet A = 2\nEquation = x",
        4,
        5,
        "A",
        "cannot define `A`: it is already defined in this block",
    ),
    case(
        "#object Type = SPHERE Center = (0,0,0) Radius = 1/0",
        2,
        51,
        "0",
        "division by zero in `1 / 0`",
    ),
    case(
        "#object Type = SPHERE Center = (0,0,0) Radius = x",
        2,
        49,
        "x",
        "`x` is a variable: only `Equation` may use x, y and z",
    ),
    case(
        "#object Type = BEZIER_PATCH Method = FAST Control points = saddle.pts",
        2,
        38,
        "Method",
        "invalid `Method`: must be GROEBNER, RESULTANT, GROEBNER_EXACT or RESULTANT_EXACT, found `FAST`",
    ),
];

#[test]
fn malformed_inputs_name_line_column_and_key() {
    for c in CASES {
        let text = match c.text.strip_prefix('!') {
            Some(t) => t.to_owned(),
            None => format!("{CAMERA}{}\n", c.text),
        };
        let err = match parse(&text, Path::new("bad.scene")) {
            Ok(_) => panic!("{:?} should be refused", c.text),
            Err(e) => e,
        };
        let span = err
            .span()
            .unwrap_or_else(|| panic!("{:?}: error without a place: {err}", c.text));
        assert_eq!(
            (span.line, span.col),
            (c.line, c.col),
            "{:?}: {err}",
            c.text
        );
        let message = err.to_string();
        assert!(
            message.contains(c.quoted),
            "{:?}: message should quote {:?}: {message}",
            c.text,
            c.quoted
        );
        assert_eq!(
            message,
            format!("bad.scene:{}:{}: {}", c.line, c.col, c.message),
            "{:?}",
            c.text
        );
    }
}

#[test]
fn a_clean_file_parses() {
    // The table's texts are errors only because of what they add to this valid base.
    let scene = parse(&format!("{CAMERA}{TORUS}"), Path::new("ok.scene")).expect("valid");
    assert_eq!(scene.objects.len(), 1, "the torus");
}

fn sample_scenes() -> Vec<String> {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("../scenes");
    let mut texts: Vec<String> = std::fs::read_dir(dir)
        .expect("scenes/")
        .filter_map(|e| {
            let p = e.ok()?.path();
            (p.extension()? == "scene")
                .then(|| std::fs::read_to_string(p).ok())
                .flatten()
        })
        .collect();
    texts.sort();
    texts.push(
        CASES
            .iter()
            .map(|c| c.text.trim_start_matches('!'))
            .collect::<Vec<_>>()
            .join("\n"),
    );
    texts
}

/// Characters that matter to the lexer and parser, for insertions.
const ALPHABET: &[char] = &[
    ' ', '\n', '\t', '#', '=', '(', ')', '[', ']', ',', '+', '-', '*', '/', '^', '.', '"', 'x',
    'X', 'y', 'z', '0', '1', '2', '9', 'e', 'E', 'a', 'O', 'N', 'é', '\u{2212}', '@',
];

#[derive(Clone, Debug)]
enum Edit {
    Insert(usize, char),
    Delete(usize, usize),
    Duplicate(usize, usize),
}

fn apply(text: &str, edits: &[Edit]) -> String {
    let mut chars: Vec<char> = text.chars().collect();
    for edit in edits {
        let n = chars.len().max(1);
        match *edit {
            Edit::Insert(at, c) => chars.insert(at % (chars.len() + 1), c),
            Edit::Delete(at, len) => {
                let at = at % n;
                let end = (at + len).min(chars.len());
                chars.drain(at.min(end)..end);
            }
            Edit::Duplicate(at, len) => {
                let at = at % n;
                let end = (at + len).min(chars.len());
                let piece: Vec<char> = chars[at.min(end)..end].to_vec();
                chars.splice(at..at, piece);
            }
        }
    }
    chars.into_iter().collect()
}

fn edit() -> impl Strategy<Value = Edit> {
    prop_oneof![
        (any::<usize>(), prop::sample::select(ALPHABET)).prop_map(|(a, c)| Edit::Insert(a, c)),
        (any::<usize>(), 1usize..8).prop_map(|(a, l)| Edit::Delete(a, l)),
        (any::<usize>(), 1usize..24).prop_map(|(a, l)| Edit::Duplicate(a, l)),
    ]
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(300))]

    /// Mutated scene files never panic: they parse or give an error with a place.
    #[test]
    fn mutated_scenes_never_panic(which in any::<prop::sample::Index>(), edits in prop::collection::vec(edit(), 1..6)) {
        let texts = sample_scenes();
        let text = apply(&texts[which.index(texts.len())], &edits);
        if let Err(e) = parse(&text, Path::new("/nonexistent/fuzz.scene")) {
            prop_assert!(!e.to_string().is_empty(), "an empty message");
        }
    }

    /// Random text, built from the language's own tokens, never panics.
    #[test]
    fn token_soup_never_panics(tokens in prop::collection::vec(prop::sample::select(vec![
        "#world", "#camera", "#object", "#texture", "#viewport", "#save", "#light", "\n", "=", "(", ")", "[", "]",
        ",", "x", "y", "z", "^", "-", "+", "*", "/", "2", "0.5", "1e3", "Type", "TORUS", "SPHERE", "ALGEBRAIC_SURFACE",
        "Equation", "Let", "phi", "sqrt", "Center", "Radius^2", "File Name", "Bounding volume", "BOX", "NONE",
        "Size", "256x256", "Kd", "Illumination", "TEXTURE", "Texture", "Name", "CHECKER", "Unit", "Eye", "LookAt",
        "ViewField", "Focal", "//", "\"", "out.png",
    ]), 0..60), spaces in prop::collection::vec(any::<bool>(), 60)) {
        let mut text = String::new();
        for (t, s) in tokens.iter().zip(&spaces) {
            text.push_str(t);
            if *s { text.push(' '); }
        }
        let _ = parse(&text, Path::new("soup.scene"));
    }
}

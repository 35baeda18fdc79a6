//! Errors of the scene language: where ([`Span`]) and what ([`ErrorKind`]).
//!
//! Every problem in a scene file — a character the lexer does not know, an unknown command or
//! key, a malformed value, a missing or duplicated key, an equation that is not a polynomial, a
//! texture file that cannot be read — becomes a [`SceneError`] whose message starts with
//! `file:line:column:` and names the offending key or token, for example
//!
//! ```text
//! scenes/x.scene:12:7: unknown key `Kx` in #object
//! ```
//!
//! Messages are lower case with no full stop (STYLE.md §4). The parser never panics on any
//! input; see `paper-notes/scene-language.md` §7 for the full list of checks.

use std::fmt;
use std::path::{Path, PathBuf};
use std::sync::Arc;

/// A place in a scene file: the file name as given, a 1-based line and a 1-based column.
///
/// Columns count Unicode characters (a tab counts as one), so an editor's "go to column"
/// lands on the offending token.
#[derive(Clone, Debug, PartialEq, Eq, Hash)]
pub struct Span {
    /// The file the text came from, as the caller named it (`parse`'s `file` argument).
    pub file: Arc<Path>,
    /// Line number, from 1.
    pub line: u32,
    /// Column number in characters, from 1.
    pub col: u32,
}

impl fmt::Display for Span {
    /// `file:line:col`, the form compilers and editors understand.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}:{}:{}", self.file.display(), self.line, self.col)
    }
}

/// The most characters of one backtick-quoted excerpt of the input (a key, a token, an
/// expression) that a message shows; longer ones end in `…`. A line of a terminal is 80
/// characters, and the excerpt only has to identify the token next to its line and column.
pub const MAX_QUOTED_CHARS: usize = 60;

/// The most characters of a whole message; the rest becomes `…`. Messages name a file, a
/// place and a few excerpts; beyond this the text can only come from a pathological input.
pub const MAX_MESSAGE_CHARS: usize = 1000;

/// Makes a message safe to print to a terminal: control characters (an ESC sequence in a
/// scene could recolour or retitle the terminal), bidirectional overrides and line
/// separators are written as `\u{…}` escapes, each backtick-quoted excerpt is cut to
/// [`MAX_QUOTED_CHARS`] characters and the whole message to [`MAX_MESSAGE_CHARS`]. Every
/// [`SceneError`] message goes through it; the `render` program also applies it to its whole
/// error chain (file names and system messages included). Applying it twice changes nothing.
///
/// # Examples
/// ```
/// use render::scene::escape_message;
/// assert_eq!(escape_message("unknown key `K\u{1b}[31m`"), "unknown key `K\\u{1b}[31m`");
/// ```
pub fn escape_message(message: &str) -> String {
    let mut out = String::with_capacity(message.len().min(MAX_MESSAGE_CHARS + 8));
    let (mut in_quote, mut quoted, mut cut) = (false, 0usize, false);
    let mut kept = 0usize;
    for c in message.chars() {
        if kept >= MAX_MESSAGE_CHARS {
            out.push('…');
            return out;
        }
        kept += 1;
        if c == '`' {
            if cut {
                out.push('…');
            }
            in_quote = !in_quote;
            (quoted, cut) = (0, false);
            out.push(c);
            continue;
        }
        if in_quote {
            quoted += 1;
            if quoted > MAX_QUOTED_CHARS {
                cut = true;
                kept -= 1;
                continue;
            }
        }
        let unsafe_char = c.is_control()
            || matches!(c, '\u{2028}' | '\u{2029}' | '\u{202a}'..='\u{202e}' | '\u{2066}'..='\u{2069}');
        if unsafe_char {
            out.push_str(&c.escape_unicode().to_string());
        } else {
            out.push(c);
        }
    }
    if cut {
        out.push('…');
    }
    out
}

/// An error while reading, parsing or building a scene.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum SceneError {
    /// The scene file itself could not be read ([`crate::scene::load`] only): missing,
    /// unreadable, not a regular file, or too long. The reason is
    /// the error's `source()` (print the chain, e.g. `anyhow`'s `{:#}`, to see it).
    #[error("cannot read {}", escape_message(&path.display().to_string()))]
    Read {
        /// The path that was opened.
        path: PathBuf,
        /// Why reading failed.
        #[source]
        source: std::io::Error,
    },
    /// A problem at a place in the scene text.
    #[error("{}", escape_message(&format!("{span}: {kind}")))]
    At {
        /// Where: file, line and column of the offending token.
        span: Span,
        /// What.
        kind: ErrorKind,
    },
}

impl SceneError {
    /// An error at `span`.
    pub(crate) fn at(span: &Span, kind: ErrorKind) -> Self {
        SceneError::At {
            span: span.clone(),
            kind,
        }
    }

    /// Where the problem is, when it has a place in the text.
    pub fn span(&self) -> Option<&Span> {
        match self {
            SceneError::At { span, .. } => Some(span),
            SceneError::Read { .. } => None,
        }
    }

    /// What the problem is, when it has a place in the text.
    pub fn kind(&self) -> Option<&ErrorKind> {
        match self {
            SceneError::At { kind, .. } => Some(kind),
            SceneError::Read { .. } => None,
        }
    }
}

/// What went wrong at a [`Span`]. Each variant names the key or token involved.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum ErrorKind {
    /// A character that starts no token.
    #[error("unexpected character `{found}`{hint}")]
    UnexpectedChar {
        /// The character.
        found: char,
        /// Extra advice (empty or starting with a space), e.g. for a typographic minus.
        hint: &'static str,
    },
    /// A byte of the scene file that is not UTF-8 ([`crate::scene::load`]): the span is the
    /// first such byte.
    #[error("invalid UTF-8 (byte 0x{byte:02X}): scene files are UTF-8 text")]
    InvalidUtf8 {
        /// The offending byte.
        byte: u8,
    },
    /// A number literal that does not fit in an `f64`.
    #[error("number `{text}` is out of range")]
    NumberOutOfRange {
        /// The literal as written.
        text: String,
    },
    /// A quoted file name without its closing quote on the same line.
    #[error("unterminated quoted file name (the closing `\"` must be on the same line)")]
    UnterminatedString,
    /// The parser wanted one thing and found another.
    #[error("expected {expected}, found {found}")]
    Expected {
        /// What would have been accepted, e.g. "`=` after `File Name`".
        expected: String,
        /// The token that was there, e.g. "`(`" or "end of file".
        found: String,
    },
    /// Two operands written side by side, e.g. `2x`.
    #[error("missing `*` or space between `{before}` and `{after}`")]
    MissingOperator {
        /// The token before the gap.
        before: String,
        /// The token after the gap.
        after: String,
    },
    /// `#name` that is not one of the commands.
    #[error("unknown command `#{name}`")]
    UnknownCommand {
        /// The name as written, without `#`.
        name: String,
    },
    /// `#name` that does not start its line.
    #[error("command `#{name}` must start a line")]
    CommandNotAtLineStart {
        /// The name as written, without `#`.
        name: String,
    },
    /// A key that no block of this kind accepts.
    #[error("unknown key `{key}` in #{command}")]
    UnknownKey {
        /// The key as written.
        key: String,
        /// The block's command, without `#`.
        command: &'static str,
    },
    /// A key that belongs to another `Type` of the block (`#object` or `#texture`).
    #[error("key `{key}` does not apply to type {type_name} in #{command}")]
    KeyNotForType {
        /// The key as written.
        key: String,
        /// The block's type, canonical spelling (`TORUS`, `CHECKER`).
        type_name: &'static str,
        /// The block's command.
        command: &'static str,
    },
    /// An `#object` whose first entry is not `Type = …`.
    #[error("#object must start with `Type = …`, found `{found}`")]
    TypeNotFirst {
        /// The key found instead.
        found: String,
    },
    /// A word that is not one of the accepted values of a key.
    #[error("unknown value `{found}` for `{key}` (expected {expected})")]
    UnknownWord {
        /// The key.
        key: &'static str,
        /// The word as written.
        found: String,
        /// The accepted words, e.g. "ON or OFF".
        expected: &'static str,
    },
    /// A type that exists in Stam's language but is not implemented yet.
    #[error("`{what}` is not supported yet")]
    Unsupported {
        /// The word as written.
        what: String,
    },
    /// A key given twice in one block.
    #[error(
        "duplicate key `{key}` in #{command} (first given at line {first_line}, column {first_col})"
    )]
    DuplicateKey {
        /// The key, canonical spelling.
        key: &'static str,
        /// The block's command.
        command: &'static str,
        /// Line of the first occurrence.
        first_line: u32,
        /// Column of the first occurrence.
        first_col: u32,
    },
    /// A block that may appear only once, given twice.
    #[error("duplicate #{command} block (first given at line {first_line})")]
    DuplicateCommand {
        /// The command.
        command: &'static str,
        /// Line of the first block.
        first_line: u32,
    },
    /// A required key that is absent; the span is the block's `#command`.
    #[error("missing key `{key}` in #{command}{detail}")]
    MissingKey {
        /// The key, canonical spelling.
        key: &'static str,
        /// The block's command.
        command: &'static str,
        /// Context such as " of type TORUS" (empty or starting with a space).
        detail: String,
    },
    /// A required block that is absent; the span is the end of the file.
    #[error("missing #{command} block")]
    MissingCommand {
        /// The command.
        command: &'static str,
    },
    /// Two keys that cannot be used together.
    #[error("`{key}` cannot be combined with `{other}` in #{command}{detail}")]
    ConflictingKeys {
        /// The later key.
        key: &'static str,
        /// The earlier key it conflicts with.
        other: &'static str,
        /// The block's command.
        command: &'static str,
        /// Why, e.g. " (Stam's camera and the look-at camera are two different forms)".
        detail: &'static str,
    },
    /// A value of the right shape but an unacceptable size or sign.
    #[error("invalid `{key}`: {reason}")]
    InvalidValue {
        /// The key, canonical spelling.
        key: String,
        /// Why, lower case.
        reason: String,
    },
    /// A name in an expression that is neither a variable, a function nor a `Let` constant
    /// defined earlier in the block.
    #[error("unknown name `{name}` (define it earlier in the block with `Let {name} = …`)")]
    UnknownName {
        /// The name as written.
        name: String,
    },
    /// `name(` where `name` is not a function.
    #[error("unknown function `{name}` (the only function is `sqrt`)")]
    UnknownFunction {
        /// The name as written.
        name: String,
    },
    /// `Let` of a reserved or already defined name.
    #[error("cannot define `{name}`: {reason}")]
    BadConstant {
        /// The name as written.
        name: String,
        /// Why, e.g. "it is a variable".
        reason: &'static str,
    },
    /// `x`, `y` or `z` where a constant is required.
    #[error("`{name}` is a variable: only `Equation` may use x, y and z")]
    VariableInConstant {
        /// The variable as written.
        name: String,
    },
    /// An equation that is not a polynomial in x, y, z.
    #[error("not a polynomial: {reason}")]
    NotPolynomial {
        /// Why, e.g. "division by an expression in x, y, z".
        reason: String,
    },
    /// Arithmetic that has no finite real answer (division by zero, square root of a negative
    /// number, overflow).
    #[error("{reason}")]
    Arithmetic {
        /// What happened.
        reason: String,
    },
    /// An expression nested deeper than the parser allows.
    #[error("expression nested too deeply (more than {max} levels)")]
    TooDeep {
        /// The limit.
        max: u32,
    },
    /// An equation whose degree exceeds the supported maximum.
    #[error("degree {degree} of `{expr}` exceeds the maximum {max}")]
    DegreeTooHigh {
        /// The degree the operation would produce.
        degree: u64,
        /// The limit.
        max: u32,
        /// The operation, as printed (shortened).
        expr: String,
    },
    /// A power whose exponent is so large that the degree it produces is not even a 64-bit
    /// integer (e.g. `x^1e308`).
    #[error("exponent {exponent:e} of `{expr}` gives a degree far above the maximum {max}")]
    ExponentTooLarge {
        /// The exponent as written.
        exponent: f64,
        /// The degree limit.
        max: u32,
        /// The operation, as printed (shortened).
        expr: String,
    },
    /// An equation whose expansion would take too long: one multiplication (or power) of it
    /// needs more term products than the limit.
    #[error(
        "expanding `{expr}` needs more than {max} term products; write it with fewer terms \
         or in a lower degree"
    )]
    ExpansionTooLarge {
        /// The limit (`MAX_TERM_PRODUCTS`).
        max: usize,
        /// The operation, as printed (shortened).
        expr: String,
    },
    /// `Texture = name` with no `#texture` of that name, or `TEXTURE` illumination without a
    /// texture to use.
    #[error("{reason}")]
    Texture {
        /// What is wrong.
        reason: String,
    },
    /// A check of the finished scene model failed (a backstop: the build step checks values
    /// where they are written first).
    #[error("{reason}")]
    Model {
        /// The model's message.
        reason: String,
    },
    /// A file named by the scene (a texture) could not be read or decoded.
    #[error("cannot read `{path}`: {reason}")]
    FileRead {
        /// The path as resolved (scene directory joined with the name written).
        path: String,
        /// Why.
        reason: String,
    },
}

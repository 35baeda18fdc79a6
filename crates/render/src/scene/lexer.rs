//! The scene-language lexer: text → [`Token`]s with [`Span`]s.
//!
//! Driven by the parser one token at a time, because one kind of value — an unquoted file
//! name such as `out/torus.png` — is not made of tokens: after `File Name =` the parser asks
//! for [`Lexer::path`], which reads raw characters up to the next blank. Everything else is
//! ordinary tokens (`paper-notes/scene-language.md` §2):
//!
//! - `#name` at the start of a line: a command;
//! - words `[A-Za-z_][A-Za-z0-9_]*` (keys, enum values, names in expressions);
//! - numbers `12`, `0.5`, `.5`, `1e-3` (never signed: `-` is an operator);
//! - punctuation `= ( ) [ ] , + - * / ^`;
//! - `//` starts a comment that runs to the end of the line.
//!
//! Each token records whether blank space (or a comment, or a line break) came before it, so
//! the parser can tell `2x` (a missing `*`) from `2 x`, and can keep a key on one line.

use std::path::Path;
use std::sync::Arc;

use super::error::{ErrorKind, SceneError, Span};

/// What a token is.
#[derive(Clone, Debug, PartialEq)]
pub(crate) enum Tok {
    /// `#name` at the start of a line (the name without `#`).
    Command(String),
    /// A word.
    Word(String),
    /// A non-negative number literal; `text` is the literal as written (for messages).
    Number { value: f64, text: String },
    /// `=`
    Eq,
    /// `(`
    LParen,
    /// `)`
    RParen,
    /// `[`
    LBracket,
    /// `]`
    RBracket,
    /// `,`
    Comma,
    /// `+`
    Plus,
    /// `-`
    Minus,
    /// `*`
    Star,
    /// `/`
    Slash,
    /// `^`
    Caret,
    /// The end of the text.
    Eof,
}

impl Tok {
    /// How the token reads in an error message: "`(`", "`Kd`", "number `0.5`", "end of file".
    pub(crate) fn describe(&self) -> String {
        match self {
            Tok::Command(name) => format!("`#{name}`"),
            Tok::Word(w) => format!("`{w}`"),
            Tok::Number { text, .. } => format!("number `{text}`"),
            Tok::Eof => "end of file".to_owned(),
            other => format!("`{}`", other.punct()),
        }
    }

    /// The token as it would be written (for messages such as "missing operator").
    pub(crate) fn text(&self) -> String {
        match self {
            Tok::Command(name) => format!("#{name}"),
            Tok::Word(w) => w.clone(),
            Tok::Number { text, .. } => text.clone(),
            Tok::Eof => String::new(),
            other => other.punct().to_owned(),
        }
    }

    fn punct(&self) -> &'static str {
        match self {
            Tok::Eq => "=",
            Tok::LParen => "(",
            Tok::RParen => ")",
            Tok::LBracket => "[",
            Tok::RBracket => "]",
            Tok::Comma => ",",
            Tok::Plus => "+",
            Tok::Minus => "-",
            Tok::Star => "*",
            Tok::Slash => "/",
            Tok::Caret => "^",
            Tok::Command(_) | Tok::Word(_) | Tok::Number { .. } | Tok::Eof => "",
        }
    }
}

/// A token, where it starts, and whether blank space precedes it.
#[derive(Clone, Debug)]
pub(crate) struct Token {
    /// What it is.
    pub(crate) tok: Tok,
    /// Where it starts.
    pub(crate) span: Span,
    /// Byte offset of its first character (lets the parser re-read raw text from there).
    pub(crate) start: usize,
    /// True when a blank, a comment or a line break separates it from the previous token (or
    /// it is the first token).
    pub(crate) spaced: bool,
}

/// Whether `c` ends a line: `\n`, or `\r` (alone in old Mac files, before `\n` in DOS ones).
fn is_line_break(c: char) -> bool {
    c == '\n' || c == '\r'
}

/// The lines of `text` without their ends, for the line-based formats (`.bpt`, control
/// points, NFF): each ends at `\n`, `\r\n` or a lone `\r`, as in the scene language (issue 13,
/// item 13). As `str::lines`, a line end at the very end starts no empty line.
pub(crate) fn text_lines(text: &str) -> TextLines<'_> {
    TextLines { rest: text }
}

/// The iterator of [`text_lines`].
#[derive(Clone, Debug)]
pub(crate) struct TextLines<'a> {
    rest: &'a str,
}

impl<'a> Iterator for TextLines<'a> {
    type Item = &'a str;

    fn next(&mut self) -> Option<&'a str> {
        if self.rest.is_empty() {
            return None;
        }
        // Searched as bytes: a line end is ASCII, never part of a longer UTF-8 character, and
        // a byte search skips the decoding of every character (issue 12: NFF files of 66 430
        // lines). `memchr2` tests 32 bytes a step where a byte loop tested one.
        let end = memchr::memchr2(b'\n', b'\r', self.rest.as_bytes());
        let (line, rest) = match end {
            Some(i) => {
                let end = if self.rest[i..].starts_with("\r\n") {
                    i + 2
                } else {
                    i + 1
                };
                (&self.rest[..i], &self.rest[end..])
            }
            None => (self.rest, ""),
        };
        self.rest = rest;
        Some(line)
    }
}

/// The place just after `text`, as the lexer counts lines and columns: where a file whose
/// first `text.len()` bytes are `text` goes wrong (the first byte that is not UTF-8).
///
/// Counted over bytes (a line end is ASCII, so it is never part of a longer UTF-8 character),
/// with the lexer's rules: each `\n`, `\r\n` or lone `\r` ends a line, and the column is one
/// more than the characters after the last line end (a leading byte-order mark not counted).
/// Walking the lexer over the whole text took a quarter of the parse of an NFF file, which asks
/// for this span on every load (issue 12).
pub(crate) fn end_position(text: &str, file: Arc<Path>) -> Span {
    let bytes = text.as_bytes();
    let (line, last_end) = if bytes.contains(&b'\r') {
        let (mut line, mut last_end) = (1u32, 0);
        for (i, &b) in bytes.iter().enumerate() {
            if b == b'\n' || (b == b'\r' && bytes.get(i + 1) != Some(&b'\n')) {
                line = line.saturating_add(1);
                last_end = i + 1;
            }
        }
        (line, last_end)
    } else {
        // `\n` only: a count the compiler vectorises.
        let breaks = bytes.iter().filter(|&&b| b == b'\n').count();
        let line = u32::try_from(breaks).map_or(u32::MAX, |n| n.saturating_add(1));
        (
            line,
            bytes.iter().rposition(|&b| b == b'\n').map_or(0, |i| i + 1),
        )
    };
    let tail = &text[last_end..];
    let tail = if last_end == 0 {
        tail.strip_prefix('\u{feff}').unwrap_or(tail)
    } else {
        tail
    };
    let col = u32::try_from(tail.chars().count()).map_or(u32::MAX, |n| n.saturating_add(1));
    Span { file, line, col }
}

/// The lexer state: a cursor into the text.
pub(crate) struct Lexer<'a> {
    text: &'a str,
    file: Arc<Path>,
    /// Byte offset of the next character.
    pos: usize,
    line: u32,
    col: u32,
    /// True until a token has been read on the current line.
    line_start: bool,
    /// True when the previous token was a number and nothing separated it from `pos`.
    after_number: bool,
}

impl<'a> Lexer<'a> {
    /// A lexer at the start of `text`; spans name `file`. A leading byte-order mark is skipped.
    pub(crate) fn new(text: &'a str, file: Arc<Path>) -> Self {
        let pos = if text.starts_with('\u{feff}') {
            '\u{feff}'.len_utf8()
        } else {
            0
        };
        Lexer {
            text,
            file,
            pos,
            line: 1,
            col: 1,
            line_start: true,
            after_number: false,
        }
    }

    /// Where the next character is.
    pub(crate) fn position(&self) -> Span {
        self.span()
    }

    fn span(&self) -> Span {
        Span {
            file: self.file.clone(),
            line: self.line,
            col: self.col,
        }
    }

    fn peek_char(&self) -> Option<char> {
        self.text[self.pos..].chars().next()
    }

    fn peek_char2(&self) -> Option<char> {
        let mut it = self.text[self.pos..].chars();
        it.next();
        it.next()
    }

    fn bump(&mut self) -> Option<char> {
        let c = self.peek_char()?;
        self.pos += c.len_utf8();
        // `\n`, `\r\n` and a lone `\r` (old Mac files) each end a line; the `\r` of `\r\n`
        // is an ordinary blank before its `\n`.
        if c == '\n' || (c == '\r' && self.peek_char() != Some('\n')) {
            self.line = self.line.saturating_add(1);
            self.col = 1;
            self.line_start = true;
        } else {
            self.col = self.col.saturating_add(1);
        }
        Some(c)
    }

    /// Skips blanks, line breaks and `//` comments; returns whether anything was skipped.
    fn skip_blank(&mut self) -> bool {
        let mut skipped = false;
        loop {
            match self.peek_char() {
                Some(c) if c.is_whitespace() => {
                    self.bump();
                    skipped = true;
                }
                Some('/') if self.peek_char2() == Some('/') => {
                    while let Some(c) = self.peek_char() {
                        if is_line_break(c) {
                            break;
                        }
                        self.bump();
                    }
                    skipped = true;
                }
                _ => return skipped,
            }
        }
    }

    /// Puts the cursor back at the start of `token` (which this lexer produced), so that the
    /// text from there can be read again, e.g. as a raw [`Lexer::path`].
    pub(crate) fn rewind(&mut self, token: &Token) {
        self.pos = token.start;
        self.line = token.span.line;
        self.col = token.span.col;
        self.line_start = false;
        self.after_number = false;
    }

    /// The next token.
    pub(crate) fn next_token(&mut self) -> Result<Token, SceneError> {
        let first = self.pos == 0 || (self.pos == 3 && self.text.starts_with('\u{feff}'));
        let skipped = self.skip_blank();
        let spaced = skipped || first;
        let after_number = std::mem::replace(&mut self.after_number, false) && !skipped;
        let at_line_start = self.line_start;
        let span = self.span();
        let start = self.pos;
        let token = |tok: Tok| Token {
            tok,
            span: span.clone(),
            start,
            spaced,
        };
        let Some(c) = self.peek_char() else {
            return Ok(token(Tok::Eof));
        };
        self.line_start = false;
        let punct = match c {
            '=' => Some(Tok::Eq),
            '(' => Some(Tok::LParen),
            ')' => Some(Tok::RParen),
            '[' => Some(Tok::LBracket),
            ']' => Some(Tok::RBracket),
            ',' => Some(Tok::Comma),
            '+' => Some(Tok::Plus),
            '-' => Some(Tok::Minus),
            '*' => Some(Tok::Star),
            '/' => Some(Tok::Slash),
            '^' => Some(Tok::Caret),
            _ => None,
        };
        if let Some(tok) = punct {
            self.bump();
            return Ok(token(tok));
        }
        if c == '#' {
            self.bump();
            let name = self.take_while(is_word_char);
            if name.is_empty() {
                let found = match self.peek_char() {
                    Some(c) if !c.is_whitespace() => format!("`{c}`"),
                    Some(_) | None => "nothing".to_owned(),
                };
                return Err(SceneError::at(
                    &span,
                    ErrorKind::Expected {
                        expected: "a command name after `#`".into(),
                        found,
                    },
                ));
            }
            if !at_line_start {
                return Err(SceneError::at(
                    &span,
                    ErrorKind::CommandNotAtLineStart { name },
                ));
            }
            return Ok(token(Tok::Command(name)));
        }
        if c.is_ascii_digit() || (c == '.' && self.peek_char2().is_some_and(|d| d.is_ascii_digit()))
        {
            let text = self.number_text();
            let value: f64 = text.parse().map_err(|_| {
                SceneError::at(&span, ErrorKind::NumberOutOfRange { text: text.clone() })
            })?;
            if !value.is_finite() {
                return Err(SceneError::at(&span, ErrorKind::NumberOutOfRange { text }));
            }
            self.after_number = true;
            return Ok(token(Tok::Number { value, text }));
        }
        if c.is_ascii_alphabetic() || c == '_' {
            // Stam writes texture sizes as `256x256` (Annexe B `GetTexture`): a word `x`
            // glued to a number is split off, so `256x256` reads as `256 x 256`.
            if after_number && (c == 'x' || c == 'X') {
                self.bump();
                return Ok(token(Tok::Word(c.to_string())));
            }
            let word = self.take_while(is_word_char);
            return Ok(token(Tok::Word(word)));
        }
        let hint = match c {
            '\u{2212}' | '\u{2013}' | '\u{2014}' => " (use the ASCII minus `-`)",
            '"' => " (quoted text is only allowed as a file name)",
            '{' | '}' => " (vectors are written `(x, y, z)`)",
            ';' => " (entries need no separator)",
            _ => "",
        };
        Err(SceneError::at(
            &span,
            ErrorKind::UnexpectedChar { found: c, hint },
        ))
    }

    fn take_while(&mut self, keep: impl Fn(char) -> bool) -> String {
        let start = self.pos;
        while self.peek_char().is_some_and(&keep) {
            self.bump();
        }
        self.text[start..self.pos].to_owned()
    }

    /// `digits [. digits] [e [+-] digits]` or `. digits [e …]`; the exponent is taken only
    /// when digits follow, so `2e` is the number 2 and the word `e`.
    fn number_text(&mut self) -> String {
        let start = self.pos;
        let digits = |l: &mut Self| {
            while l.peek_char().is_some_and(|c| c.is_ascii_digit()) {
                l.bump();
            }
        };
        digits(self);
        if self.peek_char() == Some('.') {
            self.bump();
            digits(self);
        }
        if matches!(self.peek_char(), Some('e' | 'E')) {
            let rest = &self.text[self.pos + 1..];
            let mut chars = rest.chars();
            let exp_ok = match chars.next() {
                Some(d) if d.is_ascii_digit() => true,
                Some('+' | '-') => chars.next().is_some_and(|d| d.is_ascii_digit()),
                _ => false,
            };
            if exp_ok {
                self.bump();
                if matches!(self.peek_char(), Some('+' | '-')) {
                    self.bump();
                }
                digits(self);
            }
        }
        self.text[start..self.pos].to_owned()
    }

    /// A file name: `"quoted text"` (no escapes; ends on the same line), or raw characters up
    /// to the next blank or `//`. Leading blanks on the same line are skipped; the name must
    /// start on the current line. Returns the name and where it starts.
    /// Skips spaces and tabs and returns the next character if it is on this line: lets the
    /// parser choose between a file name (raw text) and inline values (tokens) for one key.
    pub(crate) fn next_char_on_line(&mut self) -> Option<char> {
        while self
            .peek_char()
            .is_some_and(|c| c.is_whitespace() && !is_line_break(c))
        {
            self.bump();
        }
        self.peek_char().filter(|&c| !is_line_break(c))
    }

    pub(crate) fn path(&mut self) -> Result<(String, Span), SceneError> {
        while self
            .peek_char()
            .is_some_and(|c| c.is_whitespace() && !is_line_break(c))
        {
            self.bump();
        }
        let span = self.span();
        self.after_number = false;
        match self.peek_char() {
            None => Err(SceneError::at(
                &span,
                ErrorKind::Expected {
                    expected: "a file name on the same line".into(),
                    found: "end of file".into(),
                },
            )),
            Some(c) if is_line_break(c) => Err(SceneError::at(
                &span,
                ErrorKind::Expected {
                    expected: "a file name on the same line".into(),
                    found: "end of line".into(),
                },
            )),
            Some('"') => {
                self.bump();
                let start = self.pos;
                loop {
                    match self.peek_char() {
                        Some('"') => {
                            let name = self.text[start..self.pos].to_owned();
                            self.bump();
                            self.line_start = false;
                            return Ok((name, span));
                        }
                        None => {
                            return Err(SceneError::at(&span, ErrorKind::UnterminatedString));
                        }
                        Some(c) if is_line_break(c) => {
                            return Err(SceneError::at(&span, ErrorKind::UnterminatedString));
                        }
                        Some(_) => {
                            self.bump();
                        }
                    }
                }
            }
            Some(_) => {
                let start = self.pos;
                while let Some(c) = self.peek_char() {
                    if c.is_whitespace() || (c == '/' && self.peek_char2() == Some('/')) {
                        break;
                    }
                    self.bump();
                }
                self.line_start = false;
                Ok((self.text[start..self.pos].to_owned(), span))
            }
        }
    }
}

fn is_word_char(c: char) -> bool {
    c.is_ascii_alphanumeric() || c == '_'
}

#[cfg(test)]
mod tests {
    use super::*;

    fn lex(text: &str) -> Result<Vec<(Tok, u32, u32, bool)>, SceneError> {
        let mut lexer = Lexer::new(text, Arc::from(Path::new("t.scene")));
        let mut out = Vec::new();
        loop {
            let t = lexer.next_token()?;
            if t.tok == Tok::Eof {
                return Ok(out);
            }
            out.push((t.tok, t.span.line, t.span.col, t.spaced));
        }
    }

    fn word(w: &str) -> Tok {
        Tok::Word(w.to_owned())
    }

    fn num(text: &str) -> Tok {
        Tok::Number {
            value: text.parse().unwrap(),
            text: text.to_owned(),
        }
    }

    /// Lines end at `\n`, `\r\n` or a lone `\r`, found by a byte search among characters of
    /// several bytes; a line end at the very end starts no empty line.
    #[test]
    fn text_lines_split_at_each_kind_of_line_end() {
        let lines = |t| text_lines(t).collect::<Vec<_>>();
        assert_eq!(lines("a\r\nb\rc\nd é\n"), ["a", "b", "c", "d é"]);
        assert_eq!(lines("ü\r"), ["ü"]);
        assert_eq!(lines("\n\n∞"), ["", "", "∞"]);
        assert_eq!(lines(""), [""; 0]);
    }

    /// `end_position` counts lines and columns over bytes; the lexer walked over the whole
    /// text is its oracle (line ends of three kinds, a trailing `\r`, a byte-order mark,
    /// characters of several bytes).
    #[test]
    fn end_position_is_where_the_lexer_ends() {
        let file: Arc<Path> = Arc::from(Path::new("t.nff"));
        for text in [
            "",
            "s 0 0 0 1",
            "s 0 0 0 1\n",
            "a\r\nb\rc\nd",
            "a\nb\n\nc",
            "a\r",
            "a\r\n\r\n",
            "\u{feff}v é",
            "\u{feff}\nx",
            "é\n# ü ß\r\nfin ∞",
        ] {
            let mut lexer = Lexer::new(text, file.clone());
            while lexer.bump().is_some() {}
            let (want, got) = (lexer.span(), end_position(text, file.clone()));
            assert_eq!((got.line, got.col), (want.line, want.col), "{text:?}");
        }
    }

    #[test]
    fn tokens_carry_line_column_and_spacing() {
        let toks = lex("#world // comment\n  BackGnd = (0.2,.5,1e-1)\nRadius^2=4").unwrap();
        let expected = vec![
            (Tok::Command("world".into()), 1, 1, true),
            (word("BackGnd"), 2, 3, true),
            (Tok::Eq, 2, 11, true),
            (Tok::LParen, 2, 13, true),
            (num("0.2"), 2, 14, false),
            (Tok::Comma, 2, 17, false),
            (num(".5"), 2, 18, false),
            (Tok::Comma, 2, 20, false),
            (num("1e-1"), 2, 21, false),
            (Tok::RParen, 2, 25, false),
            (word("Radius"), 3, 1, true),
            (Tok::Caret, 3, 7, false),
            (num("2"), 3, 8, false),
            (Tok::Eq, 3, 9, false),
            (num("4"), 3, 10, false),
        ];
        assert_eq!(toks, expected, "token stream");
    }

    #[test]
    fn stam_sizes_split_after_numbers_only() {
        let toks: Vec<Tok> = lex("256x128 x2 2e 2e3")
            .unwrap()
            .into_iter()
            .map(|t| t.0)
            .collect();
        let expected = vec![
            num("256"),
            word("x"),
            num("128"),
            word("x2"),
            num("2"),
            word("e"),
            num("2e3"),
        ];
        assert_eq!(
            toks, expected,
            "`256x128` splits, `x2` alone is a word, `2e` is 2 then e"
        );
    }

    #[test]
    fn columns_count_characters_not_bytes() {
        let toks = lex("// é\nÀ").unwrap_err();
        let span = toks.span().unwrap();
        assert_eq!((span.line, span.col), (2, 1), "position of `À`");
        let err = lex("a = ééé @").unwrap_err();
        assert_eq!(
            err.span().unwrap().col,
            5,
            "`é` counts as one column: {err}"
        );
        assert_eq!(
            err.to_string(),
            "t.scene:1:5: unexpected character `é`",
            "message"
        );
    }

    #[test]
    fn lexer_errors_name_the_token() {
        let cases = [
            ("a = 1e999", "t.scene:1:5: number `1e999` is out of range"),
            (
                "  x #world",
                "t.scene:1:5: command `#world` must start a line",
            ),
            (
                "# world",
                "t.scene:1:1: expected a command name after `#`, found nothing",
            ),
            (
                "x = \u{2212}1",
                "t.scene:1:5: unexpected character `\u{2212}` (use the ASCII minus `-`)",
            ),
        ];
        for (text, message) in cases {
            let err = lex(text).unwrap_err();
            assert_eq!(err.to_string(), message, "lexing {text:?}");
        }
    }

    #[test]
    fn paths_are_raw_or_quoted() {
        let mut lexer = Lexer::new(
            "  out/a.png x\n\"my file.png\"y\n  \"open\n",
            Arc::from(Path::new("f")),
        );
        let (p, span) = lexer.path().unwrap();
        assert_eq!((p.as_str(), span.col), ("out/a.png", 3), "raw path");
        assert_eq!(
            lexer.next_token().unwrap().tok,
            word("x"),
            "token after the path"
        );
        lexer.skip_blank();
        let (p, _) = lexer.path().unwrap();
        assert_eq!(p, "my file.png", "quoted path");
        assert_eq!(
            lexer.next_token().unwrap().tok,
            word("y"),
            "token after the quote"
        );
        lexer.skip_blank();
        let err = lexer.path().unwrap_err();
        assert_eq!(
            err.to_string(),
            "f:3:3: unterminated quoted file name (the closing `\"` must be on the same line)",
            "unterminated"
        );
    }
}

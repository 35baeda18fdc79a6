//! Patch files: the `.bpt` format of the Utah teapot data (`scenes/teapot.bpt`) and Stam's
//! control-point files (16 lines `x y z`, `GetPatch` in `ray1.c`). Parsing only; the scene
//! build step reads the file and names it in errors.

use glam::DVec3;

use super::control_net::{ControlNet, MAX_PATCH_DEGREE, PatchError};
use super::lexer::text_lines;

/// Most patches accepted in one `.bpt` file (a guard against a corrupt count).
pub const MAX_BPT_PATCHES: usize = 1 << 20;

/// A syntax or content error in a patch file, at a 1-based line.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
#[error("line {line}: {message}")]
pub struct BptError {
    /// 1-based line number.
    pub line: usize,
    /// What is wrong.
    pub message: String,
}

/// Non-empty lines with their 1-based numbers (`#` or `//` start a comment); `\n`, `\r\n` and
/// a lone `\r` end a line.
fn lines(text: &str) -> impl Iterator<Item = (usize, &str)> {
    text_lines(text).enumerate().filter_map(|(i, l)| {
        let l = l.split("//").next().unwrap_or("");
        let l = l.split('#').next().unwrap_or("").trim();
        (!l.is_empty()).then_some((i + 1, l))
    })
}

fn err(line: usize, message: impl Into<String>) -> BptError {
    BptError {
        line,
        message: message.into(),
    }
}

/// Parses `k` whitespace-separated numbers of one line.
fn numbers<const K: usize>(line: usize, l: &str, what: &str) -> Result<[f64; K], BptError> {
    let mut out = [0.0; K];
    let mut it = l.split(|c: char| c.is_whitespace() || c == ',');
    let mut it = it.by_ref().filter(|w| !w.is_empty());
    for (k, slot) in out.iter_mut().enumerate() {
        let w = it
            .next()
            .ok_or_else(|| err(line, format!("expected {K} numbers ({what}), found {k}")))?;
        *slot = w
            .parse::<f64>()
            .ok()
            .filter(|x| x.is_finite())
            .ok_or_else(|| err(line, format!("`{w}` is not a finite number ({what})")))?;
    }
    if let Some(w) = it.next() {
        return Err(err(
            line,
            format!("unexpected `{w}` after {K} numbers ({what})"),
        ));
    }
    Ok(out)
}

fn patch_error(line: usize, e: PatchError) -> BptError {
    err(line, e.to_string())
}

/// Parses a `.bpt` file: the number of patches, then per patch a line `n m` and
/// `(n + 1)(m + 1)` lines `x y z`, row by row (`P_ij` with `i` along `u`).
///
/// # Errors
/// [`BptError`] with the line of the first problem (missing or extra numbers, a degree out of
/// range, too few points, text after the last patch).
///
/// # Examples
/// ```
/// let text = "1\n1 1\n0 0 0\n0 1 0\n1 0 0\n1 1 1\n";
/// let patches = render::scene::parse_bpt(text)?;
/// assert_eq!(patches.len(), 1);
/// assert_eq!(patches[0].degree(), [1, 1]);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn parse_bpt(text: &str) -> Result<Vec<ControlNet>, BptError> {
    let mut it = lines(text);
    let (line, l) = it
        .next()
        .ok_or_else(|| err(1, "empty file: expected the number of patches"))?;
    let count: usize = l
        .parse()
        .ok()
        .filter(|&c| (1..=MAX_BPT_PATCHES).contains(&c))
        .ok_or_else(|| {
            err(
                line,
                format!("`{l}` is not a patch count between 1 and {MAX_BPT_PATCHES}"),
            )
        })?;
    let mut patches = Vec::with_capacity(count);
    let mut last_line = line;
    for p in 0..count {
        let (line, l) = it
            .next()
            .ok_or_else(|| err(last_line, format!("expected patch {} of {count}", p + 1)))?;
        let [n, m] = numbers::<2>(line, l, "degrees n m")?;
        let whole = |x: f64| {
            (x.fract() == 0.0 && (1.0..=MAX_PATCH_DEGREE as f64).contains(&x)).then_some(x as usize)
        };
        let (Some(n), Some(m)) = (whole(n), whole(m)) else {
            return Err(err(
                line,
                format!("patch degrees `{l}` must be integers between 1 and {MAX_PATCH_DEGREE}"),
            ));
        };
        let mut points = Vec::with_capacity((n + 1) * (m + 1));
        last_line = line;
        for _ in 0..(n + 1) * (m + 1) {
            let (line, l) = it.next().ok_or_else(|| {
                err(
                    last_line,
                    format!("patch {} needs {} control points", p + 1, (n + 1) * (m + 1)),
                )
            })?;
            let [x, y, z] = numbers::<3>(line, l, "x y z")?;
            points.push(DVec3::new(x, y, z));
            last_line = line;
        }
        patches.push(ControlNet::new(n, m, points).map_err(|e| patch_error(last_line, e))?);
    }
    if let Some((line, l)) = it.next() {
        return Err(err(
            line,
            format!("unexpected `{l}` after the {count} patches"),
        ));
    }
    Ok(patches)
}

/// Parses Stam's control-point file (`GetPatch`, `ray1.c`): 16 lines `x y z`, the bicubic net
/// row by row, `P[0][0] P[0][1] … P[3][3]`.
///
/// # Errors
/// [`BptError`] with the line of the first problem.
pub(crate) fn parse_control_points(text: &str) -> Result<ControlNet, BptError> {
    let mut points = Vec::with_capacity(16);
    let mut last = 1;
    for (line, l) in lines(text) {
        if points.len() == 16 {
            return Err(err(
                line,
                format!("unexpected `{l}` after 16 control points"),
            ));
        }
        let [x, y, z] = numbers::<3>(line, l, "x y z")?;
        points.push(DVec3::new(x, y, z));
        last = line;
    }
    if points.len() != 16 {
        return Err(err(
            last,
            format!(
                "a bicubic patch needs 16 control points, found {}",
                points.len()
            ),
        ));
    }
    ControlNet::new(3, 3, points).map_err(|e| patch_error(last, e))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn errors_name_the_line() {
        let e = parse_bpt("1\n3 3\n0 0 0\n1 x 0\n").unwrap_err();
        assert_eq!(e.line, 4, "{e}");
        assert!(e.message.contains("`x`"), "{e}");
        let e = parse_bpt("2\n1 1\n0 0 0\n0 1 0\n1 0 0\n1 1 1\n").unwrap_err();
        assert!(e.message.contains("patch 2 of 2"), "{e}");
        let e = parse_bpt("1\n9 1\n").unwrap_err();
        assert_eq!(e.line, 2, "{e}");
        let e = parse_bpt("1\n1 1\n0 0 0\n0 1 0\n1 0 0\n1 1 1\n7\n").unwrap_err();
        assert_eq!(e.line, 7, "trailing text: {e}");
        let e = parse_control_points("0 0 0\n1 1 1\n").unwrap_err();
        assert!(e.message.contains("found 2"), "{e}");
        assert!(parse_bpt("").is_err(), "empty");
        assert!(
            parse_bpt("1\n1 1\n0 0 0\n0 1 0\n1 0 0\n1 1 nan\n").is_err(),
            "NaN"
        );
    }

    #[test]
    fn comments_and_commas_are_accepted() {
        let text = "// Stam's patch\n0 0 0\n0,1,0\n0 2 0\n0 3 0 # row 0\n\
                    1 0 0\n1 1 1\n1 2 1\n1 3 0\n2 0 0\n2 1 1\n2 2 1\n2 3 0\n\
                    3 0 0\n3 1 0\n3 2 0\n3 3 0\n";
        let p = parse_control_points(text).unwrap();
        assert_eq!(p.points()[1], DVec3::new(0.0, 1.0, 0.0), "P[0][1]");
        assert_eq!(p.points()[5], DVec3::new(1.0, 1.0, 1.0), "P[1][1]");
    }
}

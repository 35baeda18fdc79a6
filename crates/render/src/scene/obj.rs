//! Wavefront OBJ meshes for `Type = MESH` (`File Name = model.obj`): the statements that
//! describe the surface — `v x y z [w]` (a position; a `w` of 1 only: rational weights have no
//! meaning for flat triangles), `vn x y z` (a vertex normal) and `f` (a face: three or more
//! references `v`, `v/vt`, `v/vt/vn` or `v//vn`, 1-based, negative ones counted back from the
//! last entry read so far). A face of `n` vertices becomes the fan of triangles
//! `(v₀, vᵢ, vᵢ₊₁)`, as for NFF's polygons. Texture coordinates (`vt`) are read past, and the
//! statements that group, name, smooth or colour faces (`o`, `g`, `s`, `usemtl`, `mtllib`) or
//! draw no surface (`l`, `p`, free-form curves) are skipped: the scene's `#object` gives the
//! material. A line continued with `\\` is not joined (its words read as a malformed line).
//! Parsing only; the scene build reads the file and reports errors with its name.

use glam::DVec3;

use super::lexer::text_lines;
use super::model::MeshData;

/// A syntax or content error in an OBJ file, at a 1-based line and column (in characters).
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
#[error("line {line}, column {column}: {message}")]
pub struct ObjError {
    /// 1-based line number.
    pub line: usize,
    /// 1-based column of the offending word (1 for a problem with the whole line).
    pub column: usize,
    /// What is wrong.
    pub message: String,
}

/// The words of one line after its comment, each with its byte offset in the line (turned
/// into a column only for an error: counting characters per word would cost every line).
fn words(line: &str) -> impl Iterator<Item = (usize, &str)> {
    let code = line.split('#').next().unwrap_or("");
    // `w` is a sub-slice of `line`: its offset is the distance between their starts.
    code.split_ascii_whitespace()
        .map(move |w| (w.as_ptr() as usize - line.as_ptr() as usize, w))
}

/// Parses an OBJ file into positions, normals and triangles.
///
/// # Errors
/// [`ObjError`] at the first malformed `v`, `vn` or `f` line (a word that is not a finite
/// number, too few numbers, a reference out of range or zero, a face mixing references with and
/// without normals), or when the file has no face.
///
/// # Examples
/// ```
/// use render::scene::parse_obj;
/// let mesh = parse_obj("v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\n")?;
/// assert_eq!(mesh.triangles, vec![[0, 1, 2], [0, 2, 3]]);
/// # Ok::<(), render::scene::ObjError>(())
/// ```
pub fn parse_obj(text: &str) -> Result<MeshData, ObjError> {
    let mut mesh = MeshData::default();
    let mut last_line = 0;
    for (i, line) in text_lines(text).enumerate() {
        let number = i + 1;
        last_line = number;
        // `at`: the byte offset of the offending word (0: the line as a whole).
        let err = |at: usize, message: String| ObjError {
            line: number,
            column: line[..at].chars().count() + 1,
            message,
        };
        let mut it = words(line);
        let Some((_, keyword)) = it.next() else {
            continue;
        };
        match keyword {
            "v" => {
                let [x, y, z] = numbers(&mut it, "a position `v x y z`", &err)?;
                if let Some((at, w)) = it.next() {
                    match w.parse::<f64>() {
                        Ok(1.0) => {}
                        _ => {
                            return Err(err(
                                at,
                                format!("a weight `{w}`: only 1 (or none) is accepted"),
                            ));
                        }
                    }
                }
                mesh.positions.push(DVec3::new(x, y, z));
            }
            "vn" => {
                let [x, y, z] = numbers(&mut it, "a normal `vn x y z`", &err)?;
                if let Some((at, w)) = it.next() {
                    return Err(err(at, format!("`{w}`: a normal has three numbers")));
                }
                mesh.normals.push(DVec3::new(x, y, z));
            }
            "f" => face(&mut mesh, it, &err)?,
            _ => {}
        }
    }
    if mesh.triangles.is_empty() {
        return Err(ObjError {
            line: last_line.max(1),
            column: 1,
            message: "no face (`f`) in the file".into(),
        });
    }
    Ok(mesh)
}

/// The next `K` words as finite numbers.
fn numbers<'a, const K: usize>(
    it: &mut impl Iterator<Item = (usize, &'a str)>,
    what: &str,
    err: &impl Fn(usize, String) -> ObjError,
) -> Result<[f64; K], ObjError> {
    let mut out = [0.0; K];
    for (k, slot) in out.iter_mut().enumerate() {
        let (at, w) = it
            .next()
            .ok_or_else(|| err(0, format!("expected {what}, found {k} numbers")))?;
        *slot = w
            .parse::<f64>()
            .ok()
            .filter(|x| x.is_finite())
            .ok_or_else(|| err(at, format!("`{w}` is not a finite number ({what})")))?;
    }
    Ok(out)
}

/// A reference of an `f` line, 0-based: `count` entries read so far, `n` of them 1-based
/// (`n > 0`) or counted back from the last (`n < 0`).
fn reference(word: &str, count: usize, what: &str) -> Result<u32, String> {
    let n: i64 = word
        .parse()
        .map_err(|_| format!("`{word}` is not a whole number ({what} reference)"))?;
    let index = if n > 0 {
        n - 1
    } else if n < 0 {
        count as i64 + n
    } else {
        return Err(format!("{what} references start at 1 (0 names nothing)"));
    };
    if index < 0 || index >= count as i64 {
        return Err(format!("{what} {n} does not exist ({count} read so far)"));
    }
    u32::try_from(index).map_err(|_| format!("{what} {n} is beyond 2³² entries"))
}

/// An `f` line: its references, then its fan of triangles.
fn face<'a>(
    mesh: &mut MeshData,
    it: impl Iterator<Item = (usize, &'a str)>,
    err: &impl Fn(usize, String) -> ObjError,
) -> Result<(), ObjError> {
    let mut corners: Vec<(u32, Option<u32>)> = Vec::new();
    let mut with_normals = None;
    for (at, word) in it {
        // `v`, `v/vt`, `v/vt/vn` or `v//vn`; the texture part is skipped.
        let parts: Vec<&str> = word.splitn(4, '/').collect();
        if parts.len() > 3 {
            return Err(err(
                at,
                format!("`{word}`: a reference has at most three parts"),
            ));
        }
        let position =
            reference(parts[0], mesh.positions.len(), "vertex").map_err(|m| err(at, m))?;
        let normal = match parts.get(2) {
            Some(n) => Some(reference(n, mesh.normals.len(), "normal").map_err(|m| err(at, m))?),
            None => None,
        };
        if *with_normals.get_or_insert(normal.is_some()) != normal.is_some() {
            return Err(err(
                at,
                format!("`{word}`: a face's references must all have a normal or none"),
            ));
        }
        corners.push((position, normal));
    }
    if corners.len() < 3 {
        return Err(err(
            0,
            format!("a face needs three vertices, found {}", corners.len()),
        ));
    }
    for i in 1..corners.len() - 1 {
        let (a, b, c) = (corners[0], corners[i], corners[i + 1]);
        mesh.triangles.push([a.0, b.0, c.0]);
        mesh.triangle_normals.push(match (a.1, b.1, c.1) {
            (Some(x), Some(y), Some(z)) => Some([x, y, z]),
            _ => None,
        });
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_reference_form_and_negative_indices() {
        let text = "# a quad and a triangle\nv 0 0 0\nv 1 0 0 1.0\nv 1 1 0\nv 0 1 0\nvt 0 0\n\
                    vn 0 0 1\nvn 0 0 2\ng quad\nusemtl red\ns off\n\
                    f 1/1/1 2/1/2 3//1 4//2\nf -4 -3 -2 # the last three counted back\nf 1/1 2/1 4/1\n";
        let m = parse_obj(text).unwrap();
        assert_eq!(m.positions.len(), 4);
        assert_eq!(m.normals, vec![DVec3::Z, DVec3::new(0.0, 0.0, 2.0)]);
        assert_eq!(
            m.triangles,
            vec![[0, 1, 2], [0, 2, 3], [0, 1, 2], [0, 1, 3]],
            "the quad as a fan, then the relative and the textured faces"
        );
        assert_eq!(
            m.triangle_normals,
            vec![Some([0, 1, 0]), Some([0, 0, 1]), None, None]
        );
    }

    #[test]
    fn malformed_lines_name_line_and_column() {
        let cases = [
            (
                "v 0 0 x\nf 1 1 1",
                "line 1, column 7: `x` is not a finite number",
            ),
            (
                "v 0 0\n",
                "line 1, column 1: expected a position `v x y z`, found 2 numbers",
            ),
            ("v 0 0 0 2\n", "line 1, column 9: a weight `2`"),
            ("v 0 0 0 nan\n", "line 1, column 9: a weight `nan`"),
            (
                "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2  4\n",
                "line 4, column 8: vertex 4 does not exist (3 read so far)",
            ),
            (
                "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 0\n",
                "line 4, column 7: vertex references start at 1",
            ),
            (
                "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 -4 3\n",
                "line 4, column 5: vertex -4 does not exist",
            ),
            (
                "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2\n",
                "line 4, column 1: a face needs three vertices, found 2",
            ),
            (
                "v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 1\nf 1//1 2 3\n",
                "line 5, column 8: `2`: a face's references must all have a normal or none",
            ),
            (
                "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1//1 2//1 3//1\n",
                "line 4, column 3: normal 1 does not exist (0 read so far)",
            ),
            (
                "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1/1/1/1 2 3\n",
                "line 4, column 3: `1/1/1/1`: a reference has at most three parts",
            ),
            (
                "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2.5 3\n",
                "line 4, column 5: `2.5` is not a whole number",
            ),
            (
                "vn 0 0 1 1\n",
                "line 1, column 10: `1`: a normal has three numbers",
            ),
            (
                "v 0 0 0\n\n# nothing else\n",
                "line 3, column 1: no face (`f`) in the file",
            ),
            ("", "line 1, column 1: no face"),
            (
                "é v 0 0 0\nv é\n",
                "line 2, column 3: `é` is not a finite number",
            ),
        ];
        for (text, expected) in cases {
            let e = parse_obj(text).expect_err(text).to_string();
            assert!(e.starts_with(expected), "{text:?}: {e}");
        }
    }
}

//! [`ControlNet`]: the control points of a tensor-product Bézier patch, as the scene model
//! holds them (plain, validated data; the tracer's power-basis form is built from it by
//! `surface::BezierPatch`).
//!
//! The patch is `S(u, v) = Σ_i Σ_j P_ij B_i^n(u) B_j^m(v)` over `(u, v) ∈ [0, 1]²`, with the
//! control points `P_ij` given row by row (`i` along `u`, `j` along `v`; the `.bpt` order, where
//! line `k` of a bicubic patch is `P[k / 4][k % 4]`).

use glam::DVec3;

/// Largest degree accepted in `u` or in `v`. The eliminant of a degree `n × m` patch has
/// degree up to `2nm` (Kajiya's Bézout bound, 18 for a bicubic); 6 allows bisextic patches
/// (eliminant degree 72), beyond which `f64` elimination is hopeless anyway.
pub const MAX_PATCH_DEGREE: usize = 6;

/// Why a control net is not a patch.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
#[non_exhaustive]
pub enum PatchError {
    /// A degree is 0 or above [`MAX_PATCH_DEGREE`].
    #[error("patch degree {n}x{m} is not between 1 and {MAX_PATCH_DEGREE} in each direction")]
    Degree {
        /// Degree in `u`.
        n: usize,
        /// Degree in `v`.
        m: usize,
    },
    /// The number of points is not `(n + 1)(m + 1)`.
    #[error("a {n}x{m} patch needs {expected} control points, got {got}")]
    PointCount {
        /// Degree in `u`.
        n: usize,
        /// Degree in `v`.
        m: usize,
        /// `(n + 1)(m + 1)`.
        expected: usize,
        /// What was given.
        got: usize,
    },
    /// A coordinate is NaN or infinite.
    #[error("control point {index} is not finite")]
    NonFinite {
        /// Index of the point, row by row.
        index: usize,
    },
}

/// The control net of a Bézier patch of degree `n × m`: `(n + 1)(m + 1)` finite points, row by
/// row (`P_ij` at `i * (m + 1) + j`).
#[derive(Clone, Debug, PartialEq)]
pub struct ControlNet {
    degree: [usize; 2],
    points: Vec<DVec3>,
}

impl ControlNet {
    /// The net of degree `n` in `u` and `m` in `v` with control points `points`, row by row.
    ///
    /// # Errors
    /// [`PatchError`] for a degree outside `1..=MAX_PATCH_DEGREE`, a wrong number of points,
    /// or a non-finite coordinate.
    ///
    /// # Examples
    /// ```
    /// use glam::DVec3;
    /// use render::scene::{ControlNet, PatchError};
    /// let saddle = [(-1.0, -1.0, 1.0), (-1.0, 1.0, -1.0), (1.0, -1.0, -1.0), (1.0, 1.0, 1.0)]
    ///     .map(|(x, y, z)| DVec3::new(x, y, z));
    /// let net = ControlNet::new(1, 1, saddle.to_vec())?;
    /// assert_eq!(net.degree(), [1, 1]);
    /// assert!(matches!(ControlNet::new(3, 3, saddle.to_vec()), Err(PatchError::PointCount { .. })));
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn new(n: usize, m: usize, points: Vec<DVec3>) -> Result<Self, PatchError> {
        if !(1..=MAX_PATCH_DEGREE).contains(&n) || !(1..=MAX_PATCH_DEGREE).contains(&m) {
            return Err(PatchError::Degree { n, m });
        }
        let expected = (n + 1) * (m + 1);
        if points.len() != expected {
            return Err(PatchError::PointCount {
                n,
                m,
                expected,
                got: points.len(),
            });
        }
        if let Some(index) = points.iter().position(|p| !p.is_finite()) {
            return Err(PatchError::NonFinite { index });
        }
        Ok(ControlNet {
            degree: [n, m],
            points,
        })
    }

    /// `[n, m]`, the degrees in `u` and `v`.
    pub fn degree(&self) -> [usize; 2] {
        self.degree
    }

    /// The control points, row by row (`P_ij` at `i * (m + 1) + j`).
    pub fn points(&self) -> &[DVec3] {
        &self.points
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bad_nets_are_errors() {
        assert_eq!(
            ControlNet::new(3, 3, vec![DVec3::ZERO; 15]),
            Err(PatchError::PointCount {
                n: 3,
                m: 3,
                expected: 16,
                got: 15
            }),
            "point count"
        );
        assert_eq!(
            ControlNet::new(0, 3, vec![DVec3::ZERO; 4]),
            Err(PatchError::Degree { n: 0, m: 3 }),
            "degree"
        );
        let mut pts = vec![DVec3::ZERO; 4];
        pts[2].y = f64::NAN;
        assert_eq!(
            ControlNet::new(1, 1, pts),
            Err(PatchError::NonFinite { index: 2 }),
            "NaN"
        );
    }

    /// Issue 13, item 14: the docs said `.bpt` degrees ≤ 3 while up to 6 was accepted. The
    /// documented limit (`paper-notes/scene-language.md`: `n, m ≤ 6`) is the enforced one,
    /// and the message names it.
    #[test]
    fn the_documented_degree_limit_is_the_enforced_one() {
        assert_eq!(MAX_PATCH_DEGREE, 6, "paper-notes/scene-language.md says 6");
        assert!(
            ControlNet::new(6, 6, vec![DVec3::ZERO; 49]).is_ok(),
            "6 x 6 is accepted"
        );
        let e = ControlNet::new(7, 1, vec![DVec3::ZERO; 16]).unwrap_err();
        assert_eq!(e, PatchError::Degree { n: 7, m: 1 }, "7 is refused");
        assert!(e.to_string().contains("between 1 and 6"), "{e}");
    }
}

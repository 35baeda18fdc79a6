//! [`RayPatchSystem`]: the two implicit curves `F1(u, v) = F2(u, v) = 0` whose common roots are
//! the intersections of a ray with a polynomial patch (article §2, eqs. 1–5; `CalcBasis` and
//! `CalcT` in `ray3.c`).

use poly::{BiPoly, Scalar};

use crate::bicubic::{BICUBIC_SIDE, Bicubic};
use crate::error::Error;

/// The system of article §2 eq. 5 for one ray and one patch, and the map back to `t`.
///
/// For the patch `S(u, v) = Σ P_ij u^i v^j` and the ray `R(t) = O + t·D`, `S(u, v) = R(t)` is
/// three equations (eqs. 2–4). With the *pivot* axis `k` (the largest `|D_k|`, so the division
/// by `D_k` is the best conditioned; Stam takes the first non-zero component) and the two other
/// axes `a < b`, eliminating `t = (S_k − O_k) / D_k` gives
///
/// `F1 = D_k·(S_a − O_a) − D_a·(S_k − O_k)`,  `F2 = D_k·(S_b − O_b) − D_b·(S_k − O_k)`,
///
/// two polynomials with the degrees of the patch. Each common root `(u, v)` is a point where
/// the ray meets the patch's surface, at `t = (S_k(u, v) − O_k) / D_k`
/// ([`t_at`](RayPatchSystem::t_at)).
#[derive(Clone, Debug, PartialEq)]
pub struct RayPatchSystem<T> {
    /// `D_k·(S_a − O_a) − D_a·(S_k − O_k)`.
    pub f1: BiPoly<T>,
    /// `D_k·(S_b − O_b) − D_b·(S_k − O_k)`.
    pub f2: BiPoly<T>,
    /// The pivot axis `k` (0, 1, 2 for x, y, z).
    pub pivot: usize,
    /// `S_k(u, v)`, the pivot coordinate of the patch.
    s_pivot: BiPoly<T>,
    /// `O_k`.
    origin_pivot: T,
    /// `D_k`, non-zero.
    dir_pivot: T,
}

impl<T: Scalar> RayPatchSystem<T> {
    /// The ray parameter of the surface point `S(u, v)` on the ray, `(S_k(u, v) − O_k) / D_k`
    /// (article §4.4, `CalcT`). Meaningful at common roots of `F1`, `F2`.
    pub fn t_at(&self, u: &T, v: &T) -> T {
        (self.s_pivot.eval(u, v) - &self.origin_pivot) / &self.dir_pivot
    }
}

/// Builds `F1`, `F2` (article §2 eq. 5) for a patch given in the power basis and a ray.
///
/// `points[j * stride + i]` is the vector coefficient `P_ij` of `u^i v^j` (the [`BiPoly`] grid
/// layout; `stride = rows = 4` for a bicubic patch, whose Bézier control points must first be
/// converted to the power basis). `origin` and `dir` describe `R(t) = O + t·D`; `dir` need not
/// be normalised.
///
/// # Exactness
/// Exact over `Rat`. Over `f64` each coefficient `D_k·P_a − D_a·P_k` is a difference of two
/// products, and is set to zero when it is below `F64_NEGLIGIBLE_REL · (|D_k·P_a| + |D_a·P_k|)`
/// (the crate's zero rule applied to this first operation): a patch lying in a plane that
/// contains the ray direction then gives exact zeros instead of round-off residue.
///
/// # Errors
/// [`Error::GridShape`] if `points.len() != stride * rows`; [`Error::ZeroDirection`] if `dir` is
/// zero; [`Error::NonFinite`] for a NaN or infinite `f64` input.
///
/// # Examples
/// ```
/// use groebner::ray_patch_system;
/// // The bilinear patch S(u, v) = (u, v, u·v) and the vertical ray through (0.5, 0.5).
/// let z = [0.0; 3];
/// let points = [z, [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]]; // 1, u, v, uv
/// let sys = ray_patch_system(&points, 2, 2, &[0.5, 0.5, 5.0], &[0.0, 0.0, -1.0])?;
/// assert_eq!(sys.pivot, 2);
/// assert_eq!(sys.f1.eval(&0.5, &0.5), 0.0); // the root (u, v) = (0.5, 0.5) …
/// assert_eq!(sys.t_at(&0.5, &0.5), 4.75); // … is at z = 0.25, t = 4.75
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn ray_patch_system<T: Scalar>(
    points: &[[T; 3]],
    stride: usize,
    rows: usize,
    origin: &[T; 3],
    dir: &[T; 3],
) -> Result<RayPatchSystem<T>, Error> {
    if points.len() != stride * rows {
        return Err(Error::GridShape {
            len: points.len(),
            stride,
            rows,
        });
    }
    let (k, a, b) = check_and_pivot(points, origin, dir)?;
    let (f1, f2) = (
        BiPoly::from_grid(
            stride,
            rows,
            eliminated(points, k, a, origin, dir).collect(),
        ),
        BiPoly::from_grid(
            stride,
            rows,
            eliminated(points, k, b, origin, dir).collect(),
        ),
    );
    let s_pivot = BiPoly::from_grid(stride, rows, points.iter().map(|p| p[k].clone()).collect());
    Ok(RayPatchSystem {
        f1,
        f2,
        pivot: k,
        s_pivot,
        origin_pivot: origin[k].clone(),
        dir_pivot: dir[k].clone(),
    })
}

/// [`ray_patch_system`] for a patch of degree ≤ 3 in `u` and `v` over `f64`, in fixed-size
/// grids (the per-ray path, `per_ray.rs`); the same coefficients bit for bit. The caller has
/// checked `points.len() == stride * rows` with `stride, rows ≤ 4`.
pub(crate) fn ray_patch_bicubic(
    points: &[[f64; 3]],
    stride: usize,
    origin: &[f64; 3],
    dir: &[f64; 3],
) -> Result<BicubicSystem, Error> {
    let (k, a, b) = check_and_pivot(points, origin, dir)?;
    let grid = |it: &mut dyn Iterator<Item = f64>| {
        let mut c = [0.0; BICUBIC_SIDE * BICUBIC_SIDE];
        for (idx, x) in it.enumerate() {
            c[BICUBIC_SIDE * (idx / stride) + idx % stride] = x;
        }
        Bicubic { c }
    };
    Ok(BicubicSystem {
        f1: grid(&mut eliminated(points, k, a, origin, dir)),
        f2: grid(&mut eliminated(points, k, b, origin, dir)),
        s_pivot: grid(&mut points.iter().map(|p| p[k])),
        origin_pivot: origin[k],
        dir_pivot: dir[k],
    })
}

/// [`RayPatchSystem`] in fixed-size grids (see [`ray_patch_bicubic`]).
pub(crate) struct BicubicSystem {
    pub(crate) f1: Bicubic,
    pub(crate) f2: Bicubic,
    pub(crate) s_pivot: Bicubic,
    pub(crate) origin_pivot: f64,
    pub(crate) dir_pivot: f64,
}

/// Checks the inputs and picks the pivot: `(k, a, b)` with `k` the largest `|D_k|` (first one
/// on ties) and `a < b` the two other axes.
fn check_and_pivot<T: Scalar>(
    points: &[[T; 3]],
    origin: &[T; 3],
    dir: &[T; 3],
) -> Result<(usize, usize, usize), Error> {
    if !T::EXACT {
        let finite = |xs: &[T]| xs.iter().all(|x| x.nearest_f64().is_finite());
        if !points.iter().all(|p| finite(p)) {
            return Err(Error::NonFinite { what: "patch" });
        }
        if !finite(origin) {
            return Err(Error::NonFinite { what: "ray origin" });
        }
        if !finite(dir) {
            return Err(Error::NonFinite {
                what: "ray direction",
            });
        }
    }
    let mut k = 0;
    for axis in 1..3 {
        if dir[axis].abs() > dir[k].abs() {
            k = axis;
        }
    }
    if dir[k].is_zero() {
        return Err(Error::ZeroDirection);
    }
    let (a, b) = match k {
        0 => (1, 2),
        1 => (0, 2),
        _ => (0, 1),
    };
    Ok((k, a, b))
}

/// The coefficients of `D_k·(S_a − O_a) − D_a·(S_k − O_k)`, in the order of `points`.
fn eliminated<'a, T: Scalar>(
    points: &'a [[T; 3]],
    k: usize,
    a: usize,
    origin: &'a [T; 3],
    dir: &'a [T; 3],
) -> impl Iterator<Item = T> + 'a {
    points.iter().enumerate().map(move |(idx, p)| {
        if idx == 0 {
            // The constant term also carries −D_k·O_a + D_a·O_k.
            let x = dir[k].clone() * &p[a] + dir[a].clone() * &origin[k];
            let y = dir[a].clone() * &p[k] + dir[k].clone() * &origin[a];
            cancel(x, y)
        } else {
            cancel(dir[k].clone() * &p[a], dir[a].clone() * &p[k])
        }
    })
}

/// `x − y`, set to exactly zero when it is negligible against `|x| + |y|` (exact for `Rat`).
fn cancel<T: Scalar>(x: T, y: T) -> T {
    let scale = x.abs() + y.abs();
    let d = x - y;
    if d.is_negligible(&scale) {
        T::zero()
    } else {
        d
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::testutil::q;
    use poly::Rat;

    #[test]
    fn planted_intersection_is_a_common_root() {
        // S(u, v) = (u + v², v − u·v, 1 + u² + v³) in the power basis; the ray through
        // S(1/3, 1/2) with a direction whose largest component is y.
        let (u0, v0) = (q(1) / q(3), q(1) / q(2));
        let mut pts = vec![[q(0), q(0), q(0)]; 16];
        let at = |i: usize, j: usize| j * 4 + i;
        pts[at(1, 0)][0] = q(1);
        pts[at(0, 2)][0] = q(1);
        pts[at(0, 1)][1] = q(1);
        pts[at(1, 1)][1] = q(-1);
        pts[at(0, 0)][2] = q(1);
        pts[at(2, 0)][2] = q(1);
        pts[at(0, 3)][2] = q(1);
        let s = |u: &Rat, v: &Rat| {
            [
                u.clone() + v * v,
                v.clone() - u * v,
                q(1) + u * u + v * v * v,
            ]
        };
        let hit = s(&u0, &v0);
        let dir = [q(2), q(-7), q(3)];
        let t0 = q(5) / q(4);
        let origin: [Rat; 3] = std::array::from_fn(|i| hit[i].clone() - t0.clone() * &dir[i]);
        let sys = ray_patch_system(&pts, 4, 4, &origin, &dir).unwrap();
        assert_eq!(sys.pivot, 1, "|−7| is the largest component");
        assert_eq!(sys.f1.eval(&u0, &v0), q(0), "F1 vanishes at the hit");
        assert_eq!(sys.f2.eval(&u0, &v0), q(0), "F2 vanishes at the hit");
        assert_eq!(sys.t_at(&u0, &v0), t0, "t recovered exactly");
        assert_ne!(
            sys.f1.eval(&v0, &u0),
            q(0),
            "and not at a point off the ray"
        );
    }

    #[test]
    fn bad_input_is_an_error() {
        let pts = [[0.0; 3]; 4];
        assert_eq!(
            ray_patch_system(&pts, 2, 2, &[0.0; 3], &[0.0; 3]),
            Err(Error::ZeroDirection),
            "zero direction"
        );
        assert_eq!(
            ray_patch_system(&pts, 4, 4, &[0.0; 3], &[1.0, 0.0, 0.0]),
            Err(Error::GridShape {
                len: 4,
                stride: 4,
                rows: 4
            }),
            "grid shape"
        );
        assert_eq!(
            ray_patch_system(&pts, 2, 2, &[f64::NAN, 0.0, 0.0], &[1.0, 0.0, 0.0]),
            Err(Error::NonFinite { what: "ray origin" }),
            "NaN origin"
        );
    }

    #[test]
    fn ray_in_the_plane_of_a_flat_patch_gives_exact_zeros() {
        // The flat patch S(u, v) = (u, v, 0.1·u) lies in the plane z = 0.1·x, and so does the
        // ray: the y-component of (S − O) × D, which is F2 for pivot x, vanishes identically
        // and must come out as exact zeros, not round-off residue.
        let pts = [
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.1],
            [0.0, 1.0, 0.0],
            [0.0, 0.0, 0.0],
        ];
        let dir = [0.7, 0.3, 0.07];
        let origin = [0.2, 0.1, 0.02];
        let sys = ray_patch_system(&pts, 2, 2, &origin, &dir).unwrap();
        assert_eq!(sys.pivot, 0, "x is the largest component");
        let exact = ray_patch_system(
            &pts.map(|p| p.map(|x| Rat::from_f64_exact(x).unwrap())),
            2,
            2,
            &origin.map(|x| Rat::from_f64_exact(x).unwrap()),
            &dir.map(|x| Rat::from_f64_exact(x).unwrap()),
        )
        .unwrap();
        // The f64 data are not exactly coplanar (0.1 is not a dyadic rational), so the exact
        // system keeps tiny coefficients that the f64 zero rule removes.
        assert!(
            !exact.f2.is_zero(),
            "exact residue of 0.1's rounding: {}",
            exact.f2
        );
        assert!(sys.f2.is_zero(), "f64 residue zeroed: {}", sys.f2);
    }
}

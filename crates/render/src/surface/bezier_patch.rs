//! [`BezierPatch`]: a tensor-product Bézier patch of degree `n × m`, its power-basis form
//! (Stam's `CalcCoef`, article §4.1) and its evaluation.
//!
//! The patch is `S(u, v) = Σ_i Σ_j P_ij B_i^n(u) B_j^m(v)` over `(u, v) ∈ [0, 1]²`, with the
//! control points `P_ij` given row by row (`i` along `u`, `j` along `v`; the `.bpt` order, where
//! line `k` of a bicubic patch is `P[k / 4][k % 4]`). Tracing goes through
//! [`BezierMesh`](super::BezierMesh); `paper-notes/bezier-patches.md` explains the method.

use glam::DVec3;

use crate::geometry::Bounds3;
use crate::scene::ControlNet;

/// A power-basis coefficient no larger than `POWER_ZERO_REL · max_ij |P_ij|` (the largest
/// control-point coordinate) is set to exactly zero.
///
/// Such a coefficient moves the surface by at most a few times that fraction of the control
/// points' magnitude over `[0, 1]²` (the power basis has `|u^i v^j| ≤ 1`), far below
/// [`HIT_RESIDUAL_REL`](super::HIT_RESIDUAL_REL), yet it is what round-off leaves where the
/// true coefficient is zero: in a degree-elevated net (a bilinear saddle written with 16
/// points, decimal data) and after de Casteljau subdivision (about `γ(3(n + m))` relative).
/// Zeroing it lets the algebra see the true degree (the saddle's eliminant collapses from 18
/// to 2). The scale is the whole net's, not the coefficient's own terms: a row of control
/// points that is zero up to round-off has no scale of its own.
pub const POWER_ZERO_REL: f64 = 1e-12;

/// A Bézier patch: control points and the same surface in the power basis.
#[derive(Clone, Debug, PartialEq)]
pub struct BezierPatch {
    /// `[n, m]`: degree in `u` and in `v`.
    degree: [usize; 2],
    /// `P_ij` at `i * (m + 1) + j`.
    control: Vec<DVec3>,
    /// Power-basis coefficient of `u^i v^j` at `j * (n + 1) + i` (the `BiPoly` grid layout).
    power: Vec<DVec3>,
}

/// `C(n, k)` for the small degrees used here.
fn binomial(n: usize, k: usize) -> f64 {
    (0..k).fold(1.0, |c, i| c * (n - i) as f64 / (i + 1) as f64)
}

/// The matrix taking Bernstein coefficients of degree `n` to power coefficients:
/// `B_i^n(u) = Σ_k w[k][i] u^k` with `w[k][i] = C(n, i) C(n − i, k − i) (−1)^(k − i)` for
/// `k ≥ i` (Stam's `w[4][4]` in `CalcCoef` is the case `n = 3`). Entry `(k, i)` at
/// `k * (n + 1) + i`.
fn bernstein_to_power(n: usize) -> Vec<f64> {
    let mut w = vec![0.0; (n + 1) * (n + 1)];
    for k in 0..=n {
        for i in 0..=k {
            let sign = if (k - i) % 2 == 0 { 1.0 } else { -1.0 };
            w[k * (n + 1) + i] = binomial(n, i) * binomial(n - i, k - i) * sign;
        }
    }
    w
}

impl BezierPatch {
    /// The patch of the control net `net`, converted to the power basis once (Stam
    /// `CalcCoef`, article §4.1).
    ///
    /// # Examples
    /// ```
    /// use glam::DVec3;
    /// use render::scene::ControlNet;
    /// use render::surface::BezierPatch;
    /// // The bilinear saddle z = (2u − 1)(2v − 1) over [−1, 1]².
    /// let pts = [(-1.0, -1.0, 1.0), (-1.0, 1.0, -1.0), (1.0, -1.0, -1.0), (1.0, 1.0, 1.0)]
    ///     .map(|(x, y, z)| DVec3::new(x, y, z));
    /// let patch = BezierPatch::new(&ControlNet::new(1, 1, pts.to_vec())?);
    /// assert_eq!(patch.eval(0.5, 0.5), DVec3::ZERO);
    /// assert_eq!(patch.eval(1.0, 0.0), DVec3::new(1.0, -1.0, -1.0));
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn new(net: &ControlNet) -> Self {
        let [n, m] = net.degree();
        let points = net.points().to_vec();
        let expected = points.len();
        let (wu, wv) = (bernstein_to_power(n), bernstein_to_power(m));
        // P^power_kl = Σ_i Σ_j wu[k][i] wv[l][j] P_ij (CalcCoef, generalised to n × m).
        // Round-off residue is set to exactly zero, so that a degree-elevated net has the
        // degree of its surface and the algebra sees the collapse (see POWER_ZERO_REL).
        let zero = POWER_ZERO_REL
            * points
                .iter()
                .fold(0.0f64, |a, p| a.max(p.abs().max_element()));
        let mut power = vec![DVec3::ZERO; expected];
        for k in 0..=n {
            for l in 0..=m {
                let mut c = DVec3::ZERO;
                for i in 0..=k {
                    for j in 0..=l {
                        c += points[i * (m + 1) + j] * (wu[k * (n + 1) + i] * wv[l * (m + 1) + j]);
                    }
                }
                let keep = c.abs().cmpgt(DVec3::splat(zero));
                power[l * (n + 1) + k] = DVec3::select(keep, c, DVec3::ZERO);
            }
        }
        BezierPatch {
            degree: [n, m],
            control: points,
            power,
        }
    }

    /// `[n, m]`, the degrees in `u` and `v`.
    pub fn degree(&self) -> [usize; 2] {
        self.degree
    }

    /// The control points, row by row (`P_ij` at `i * (m + 1) + j`).
    pub fn control_points(&self) -> &[DVec3] {
        &self.control
    }

    /// The power-basis coefficients: that of `u^i v^j` at `j * (n + 1) + i`.
    pub fn power_coeffs(&self) -> &[DVec3] {
        &self.power
    }

    /// The box of the control points, which holds the patch (convex-hull property of the
    /// Bernstein basis).
    pub fn bounds(&self) -> Bounds3 {
        Bounds3::from_points(self.control.iter().copied())
    }

    /// `S(u, v)`, by nested Horner on the power basis.
    pub fn eval(&self, u: f64, v: f64) -> DVec3 {
        self.eval_with_partials(u, v).0
    }

    /// `S(u, v)`, `∂S/∂u` and `∂S/∂v` in one nested Horner pass.
    pub fn eval_with_partials(&self, u: f64, v: f64) -> (DVec3, DVec3, DVec3) {
        let stride = self.degree[0] + 1;
        let (mut s, mut su, mut sv) = (DVec3::ZERO, DVec3::ZERO, DVec3::ZERO);
        for row in self.power.chunks_exact(stride).rev() {
            let (mut r, mut dr) = (DVec3::ZERO, DVec3::ZERO);
            for &c in row.iter().rev() {
                dr = dr * u + r;
                r = r * u + c;
            }
            sv = sv * v + s;
            s = s * v + r;
            su = su * v + dr;
        }
        (s, su, sv)
    }

    /// The part of the patch over `[u0, u1] × [v0, v1]`, reparametrised to `[0, 1]²`, by
    /// de Casteljau's algorithm on the control net (exact in real arithmetic; the new control
    /// points bound the piece, which is what makes subdivided bounds tight).
    pub fn sub_patch(&self, u: [f64; 2], v: [f64; 2]) -> BezierPatch {
        let [n, m] = self.degree;
        // Along v, each row i.
        let mut rows = Vec::with_capacity(self.control.len());
        for i in 0..=n {
            rows.extend(sub_curve(&self.control[i * (m + 1)..(i + 1) * (m + 1)], v));
        }
        // Along u, each column j.
        let mut out = vec![DVec3::ZERO; self.control.len()];
        let mut column = Vec::with_capacity(n + 1);
        for j in 0..=m {
            column.clear();
            column.extend((0..=n).map(|i| rows[i * (m + 1) + j]));
            for (i, p) in sub_curve(&column, u).into_iter().enumerate() {
                out[i * (m + 1) + j] = p;
            }
        }
        // Non-finite only if de Casteljau overflowed; the whole patch then stands in.
        ControlNet::new(n, m, out).map_or_else(|_| self.clone(), |net| BezierPatch::new(&net))
    }
}

/// The control points of the piece `[a, b]` of the Bézier curve with control points `pts`,
/// reparametrised to `[0, 1]`: split at `b` keeping the left part, then split that at `a / b`
/// keeping the right part (or split at `a` directly when `b = 0`).
fn sub_curve(pts: &[DVec3], [a, b]: [f64; 2]) -> Vec<DVec3> {
    let left = if b > 0.0 {
        split(pts, b).0
    } else {
        pts.to_vec()
    };
    if a <= 0.0 {
        return left;
    }
    let s = if b > 0.0 { a / b } else { a };
    split(&left, s).1
}

/// De Casteljau split of a Bézier curve at `s`: `(left, right)` control points.
fn split(pts: &[DVec3], s: f64) -> (Vec<DVec3>, Vec<DVec3>) {
    let n = pts.len();
    let mut work = pts.to_vec();
    let mut left = Vec::with_capacity(n);
    let mut right = vec![DVec3::ZERO; n];
    for level in 0..n {
        left.push(work[0]);
        right[n - 1 - level] = work[n - 1 - level];
        for k in 0..n - 1 - level {
            work[k] = work[k].lerp(work[k + 1], s);
        }
    }
    (left, right)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A fixed, non-degenerate bicubic net.
    fn wavy() -> BezierPatch {
        let pts = (0..16)
            .map(|k| {
                let (i, j) = ((k / 4) as f64, (k % 4) as f64);
                DVec3::new(i, j, (i * 1.3 + j * 0.7).sin() + 0.1 * i * j)
            })
            .collect();
        BezierPatch::new(&ControlNet::new(3, 3, pts).unwrap())
    }

    /// `S(u, v)` straight from the Bernstein definition.
    fn bernstein_eval(p: &BezierPatch, u: f64, v: f64) -> DVec3 {
        let [n, m] = p.degree();
        let b = |n: usize, i: usize, x: f64| {
            binomial(n, i) * x.powi(i as i32) * (1.0 - x).powi((n - i) as i32)
        };
        let mut s = DVec3::ZERO;
        for i in 0..=n {
            for j in 0..=m {
                s += p.control_points()[i * (m + 1) + j] * b(n, i, u) * b(m, j, v);
            }
        }
        s
    }

    #[test]
    fn power_basis_matches_the_bernstein_form() {
        let p = wavy();
        for &(u, v) in &[(0.0, 0.0), (1.0, 1.0), (0.3, 0.8), (0.71, 0.05), (1.0, 0.4)] {
            let d = (p.eval(u, v) - bernstein_eval(&p, u, v)).length();
            assert!(d < 1e-13, "S({u}, {v}) differs by {d}");
        }
        // Stam's w matrix (CalcCoef) is the cubic case.
        assert_eq!(
            bernstein_to_power(3),
            vec![
                1.0, 0.0, 0.0, 0.0, -3.0, 3.0, 0.0, 0.0, 3.0, -6.0, 3.0, 0.0, -1.0, 3.0, -3.0, 1.0
            ],
            "Stam's w[4][4]"
        );
    }

    #[test]
    fn partials_match_finite_differences() {
        let p = wavy();
        let (u, v, h) = (0.37, 0.61, 1e-6);
        let (_, su, sv) = p.eval_with_partials(u, v);
        let fu = (p.eval(u + h, v) - p.eval(u - h, v)) / (2.0 * h);
        let fv = (p.eval(u, v + h) - p.eval(u, v - h)) / (2.0 * h);
        assert!((su - fu).length() < 1e-7, "dS/du {su} vs {fu}");
        assert!((sv - fv).length() < 1e-7, "dS/dv {sv} vs {fv}");
    }

    #[test]
    fn sub_patch_reparametrises_the_same_surface() {
        let p = wavy();
        let (u, v) = ([0.25, 0.5], [0.0, 0.75]);
        let s = p.sub_patch(u, v);
        for &(a, b) in &[(0.0, 0.0), (1.0, 1.0), (0.4, 0.9)] {
            let want = p.eval(u[0] + (u[1] - u[0]) * a, v[0] + (v[1] - v[0]) * b);
            let d = (s.eval(a, b) - want).length();
            assert!(d < 1e-12, "sub-patch at ({a}, {b}) off by {d}");
        }
        assert!(
            p.bounds().contains(s.bounds().min) && p.bounds().contains(s.bounds().max),
            "a piece's hull lies in the whole hull"
        );
    }
}

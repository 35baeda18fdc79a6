//! [`Superquadric`]: Kuchkuda's `|x/sx|^p + |y/sy|^p + |z/sz|^p = 1` (seed `000_…` §3.5)
//! for an integer power `p ≥ 1`.
//!
//! Kuchkuda refines the box entry point with the secant method. Here the surface goes through
//! the shared implicit path: inside one octant the signs of `x`, `y`, `z` are fixed, so `F` is
//! the polynomial `Σ (σᵢ xᵢ / sᵢ)^p − 1`. The ray is cut where it crosses the coordinate
//! planes (at most three cuts, four pieces; none for even `p`, where the signs do not matter),
//! and each piece is restricted and solved in order until one has a root.
//!
//! Scene syntax (the centre is applied by a translation):
//! ```text
//! #object
//! Type = SUPERQUADRIC
//! Center = (20,10,10)
//! Size = (10,20,5)        // half-extents
//! Power = 4
//! ```

use std::ops::Range;

use glam::DVec3;

use super::implicit::{ROOT_X_TOL_REL, SINGULAR_P_ERR_REL, clip, search_start, smallest_root_in};
use super::{Hit, Surface, SurfaceGeometry, SurfaceKind};
use crate::geometry::{Bounds3, Ray, gamma};
use crate::methods::RootMethods;
use crate::workspace::Workspace;

/// The largest superquadric `Power` (512): the ray polynomial has degree `p`, and its
/// coefficients `C(p, m)·a^(p−m)·b^m` span about `2^p` in magnitude.
///
pub use crate::scene::MAX_SUPERQUADRIC_POWER;

/// A superquadric centred at the origin with half-extents `size` and integer power.
#[derive(Clone, Debug)]
pub struct Superquadric {
    size: DVec3,
    power: u32,
    bounds: Bounds3,
    /// Binomial coefficients `C(p, m)`, `m = 0..=p`.
    binom: Vec<f64>,
    /// How each piece's smallest root is found (set once per render).
    roots: RootMethods,
}

impl Superquadric {
    /// The superquadric with half-extents `size` (positive) and power
    /// `1 ≤ power ≤ MAX_SUPERQUADRIC_POWER`; a larger power is clamped to the maximum (the
    /// scene model refuses it before this point).
    pub fn new(size: DVec3, power: u32) -> Self {
        let power = power.clamp(1, MAX_SUPERQUADRIC_POWER);
        let mut binom = vec![1.0; power as usize + 1];
        for m in 1..=power as usize {
            binom[m] = binom[m - 1] * f64::from(power - m as u32 + 1) / m as f64;
        }
        Superquadric {
            size,
            power,
            bounds: Bounds3::new(-size, size),
            binom,
            roots: RootMethods::default(),
        }
    }

    /// Finds roots with `roots` instead of the default methods.
    pub fn with_root_methods(mut self, roots: RootMethods) -> Self {
        self.roots = roots;
        self
    }

    /// Writes the restriction of `Σ (σᵢ (oᵢ + t dᵢ)/sᵢ)^p − 1` into `ws.coeffs`.
    fn restrict(&self, o: DVec3, d: DVec3, signs: DVec3, out: &mut Vec<f64>) {
        let p = self.power as usize;
        out.clear();
        out.resize(p + 1, 0.0);
        out[0] = -1.0;
        for k in 0..3 {
            let a = signs[k] * o[k] / self.size[k];
            let b = signs[k] * d[k] / self.size[k];
            // (a + b t)^p = Σ C(p, m) a^(p−m) b^m t^m.
            let mut bm = 1.0;
            for (m, (c, binom)) in out.iter_mut().zip(&self.binom).enumerate() {
                *c += binom * a.powi((p - m) as i32) * bm;
                bm *= b;
            }
        }
    }

    fn nearest(
        &self,
        ray: &Ray,
        t_range: Range<f64>,
        ws: &mut Workspace,
        any: bool,
    ) -> Option<(f64, DVec3, u32)> {
        let range_start = t_range.start;
        let seg = clip(
            Some(&self.bounds),
            ray,
            t_range,
            ws,
            SurfaceKind::Superquadric,
        )?;
        // Cut points: where the ray crosses a coordinate plane (odd powers only).
        let mut cuts = [seg.end; 4];
        let mut n = 0;
        if self.power % 2 == 1 {
            for k in 0..3 {
                if ray.dir[k] != 0.0 {
                    let t = -ray.origin[k] / ray.dir[k];
                    if t > seg.start && t < seg.end {
                        cuts[n] = t;
                        n += 1;
                    }
                }
            }
        }
        cuts[..n].sort_by(f64::total_cmp);
        cuts[n] = seg.end;
        let x_tol_full = ROOT_X_TOL_REL * self.bounds.diagonal() / ray.dir.length();
        let mut start = seg.start;
        for &end in &cuts[..=n] {
            let o = ray.at(start);
            // The octant of this piece, from its midpoint.
            let mid = ray.at(0.5 * (start + end));
            let signs = DVec3::new(sign(mid.x), sign(mid.y), sign(mid.z));
            self.restrict(o, ray.dir, signs, &mut ws.coeffs);
            let hi = end - start;
            let x_tol = if any { hi } else { x_tol_full };
            // Only the first piece starts at the box entry; later ones start where the previous
            // piece's search (closed at its end) stopped.
            let lo = if start == seg.start {
                search_start(range_start, start, hi)
            } else {
                0.0
            };
            if let Some(s) = smallest_root_in(ws, lo, hi, &self.roots.options(x_tol)) {
                let tag = octant_tag(signs);
                return Some((start + s, o + ray.dir * s, tag));
            }
            start = end;
        }
        None
    }
}

fn sign(x: f64) -> f64 {
    if x < 0.0 { -1.0 } else { 1.0 }
}

fn octant_tag(s: DVec3) -> u32 {
    u32::from(s.x < 0.0) | (u32::from(s.y < 0.0) << 1) | (u32::from(s.z < 0.0) << 2)
}

impl Surface for Superquadric {
    fn kind(&self) -> SurfaceKind {
        SurfaceKind::Superquadric
    }

    fn bounds(&self) -> Option<Bounds3> {
        Some(self.bounds)
    }

    fn intersect(&self, ray: &Ray, t_range: Range<f64>, ws: &mut Workspace) -> Option<Hit> {
        let (t, p, tag) = self.nearest(ray, t_range, ws, false)?;
        Some(Hit {
            t,
            local: p,
            uv: None,
            tag,
        })
    }

    fn occluded(&self, ray: &Ray, t_range: Range<f64>, ws: &mut Workspace) -> bool {
        self.nearest(ray, t_range, ws, true).is_some()
    }

    /// Normal `∇F = (p·sign(xᵢ)·|xᵢ/sᵢ|^(p−1)/sᵢ)ᵢ` (Kuchkuda `nrmsup`), error box from the
    /// residual as for every implicit surface (see `implicit::gradient_normal`).
    fn shading(&self, hit: &Hit) -> SurfaceGeometry {
        let p = hit.local;
        let pw = self.power as i32;
        let mut g = DVec3::ZERO;
        let mut f = -1.0;
        let mut f_abs = 1.0;
        for k in 0..3 {
            let u = (p[k] / self.size[k]).abs();
            let up = u.powi(pw);
            f += up;
            f_abs += up;
            g[k] = f64::from(self.power) * sign(p[k]) * u.powi(pw - 1) / self.size[k];
        }
        let glen = g.length();
        let g_err = g.abs().length() * gamma(self.power as usize + 3);
        if glen > g_err && glen.is_finite() {
            let dist = (f.abs() + gamma(self.power as usize + 4) * f_abs) / glen;
            SurfaceGeometry {
                p,
                p_err: DVec3::splat(dist),
                normal: Some(g / glen),
                uv: None,
            }
        } else {
            let size = self.bounds.diagonal();
            SurfaceGeometry {
                p,
                p_err: DVec3::splat(SINGULAR_P_ERR_REL * size),
                normal: None,
                uv: None,
            }
        }
    }
}

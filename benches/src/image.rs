//! Image-level comparison of solver settings: primary hits and shadow states of a scene's
//! implicit surface, per pixel, for each root finder and tolerance, against an exact reference.
//!
//! `render` does not (yet) let its user pick the root finder, so this traces the two queries
//! that decide what a pixel shows — the primary hit and the shadow ray towards the first light —
//! with `render`'s camera ([`render::Camera`]) and the same restrictions and bounding volumes
//! as `render`, and swaps the solver. The reference is exact: the restriction of `F` to each
//! ray computed in rationals from the `f64` ray data, and its smallest root found by exact
//! Sturm isolation to one `f64` spacing ([`poly::QPoly::smallest_root`]). Shading is not
//! computed: a pixel's state is (hit or miss, shadowed or lit) plus its depth.

use std::time::Instant;

use glam::DVec3;
use poly::{Poly, QPoly, RootStats, rat_from_f64};
use render::scene::{CameraSpec, LookAtCamera};
use render::{Camera, Poly3};

use crate::methods::Method;
use crate::rays::{
    TorusShape, poly3_restriction_exact, torus_restriction, torus_restriction_exact,
};

/// Start of every shadow ray's search, relative to the object's size: the shadow ray leaves
/// from the (computed) hit point, so roots within this distance are the surface it starts on.
/// A setting with a coarser tolerance starts at `SHADOW_EPS_TOLS · x_tol` instead (its hit
/// point may be that far inside the surface; a tracer offsets by the hit's error bound, as
/// `render` does).
pub const SHADOW_EPS_REL: f64 = 1e-7;

/// See [`SHADOW_EPS_REL`].
pub const SHADOW_EPS_TOLS: f64 = 4.0;

/// The implicit surface of a scene, with the bounding volume `render` gives it.
#[derive(Clone, Debug)]
pub enum Shape {
    /// A torus about `z` at the origin, bounded by the sphere of radius `R + r`.
    Torus(TorusShape),
    /// An algebraic surface bounded by the cube `[-h, h]³`.
    Algebraic(Poly3, f64),
}

impl Shape {
    /// Diagonal of the bounding box: the object's size.
    pub fn size(&self) -> f64 {
        match self {
            Shape::Torus(t) => {
                let e = t.major + t.minor;
                (8.0 * e * e + 4.0 * t.minor * t.minor).sqrt()
            }
            Shape::Algebraic(_, h) => 2.0 * h * 3f64.sqrt(),
        }
    }

    /// The parameter interval of the line `o + t·d` inside the bounding volume.
    fn chord(&self, o: DVec3, d: DVec3) -> Option<(f64, f64)> {
        match self {
            Shape::Torus(t) => crate::rays::sphere_chord(o, d, t.major + t.minor),
            Shape::Algebraic(_, h) => crate::rays::box_chord(o, d, *h),
        }
    }

    fn restrict(&self, o: DVec3, d: DVec3) -> Poly<f64> {
        match self {
            Shape::Torus(t) => torus_restriction(*t, o, d),
            Shape::Algebraic(f, _) => f.restrict_to_line(o, d),
        }
    }

    fn restrict_exact(&self, o: DVec3, d: DVec3) -> QPoly {
        match self {
            Shape::Torus(t) => torus_restriction_exact(*t, o, d),
            Shape::Algebraic(f, _) => poly3_restriction_exact(f, o, d),
        }
    }
}

/// Where the primary ray's polynomial is restricted.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Origin {
    /// At the bounding-volume entry, as `render` does.
    Entry,
    /// At the eye (the naive restriction).
    Eye,
}

/// A scene for the comparison.
#[derive(Clone, Debug)]
pub struct ImageScene {
    /// Name in the report.
    pub name: String,
    /// The surface.
    pub shape: Shape,
    /// The camera.
    pub camera: LookAtCamera,
    /// The light whose shadow is tested.
    pub light: DVec3,
}

impl ImageScene {
    /// The same view from `factor` times farther away, with the field of view narrowed so the
    /// object fills the same part of the frame.
    pub fn farther(&self, factor: f64, name: &str) -> ImageScene {
        let c = &self.camera;
        let eye = c.look_at + (c.eye - c.look_at) * factor;
        let half = (c.view_field_deg.to_radians() / 2.0).tan() / factor;
        ImageScene {
            name: name.to_owned(),
            camera: LookAtCamera {
                eye,
                view_field_deg: 2.0 * half.atan().to_degrees(),
                ..c.clone()
            },
            ..self.clone()
        }
    }
}

/// One pixel's state.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PixelState {
    /// Distance from the eye to the primary hit (`+∞` for a miss).
    pub depth: f64,
    /// Whether the hit point is in shadow (false for a miss).
    pub shadowed: bool,
}

/// A solver setting: method, absolute tolerance in `t`, and where primary rays are restricted.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Setting {
    /// The root finder.
    pub method: Method,
    /// Absolute tolerance in `t` (unit directions: a distance).
    pub x_tol: f64,
    /// Primary-ray restriction origin.
    pub origin: Origin,
}

/// The smallest root in `(lo, hi]`, by `setting` or exactly.
fn smallest(
    shape: &Shape,
    o: DVec3,
    d: DVec3,
    lo: f64,
    hi: f64,
    setting: Option<&Setting>,
) -> Option<f64> {
    match setting {
        Some(s) => {
            let p = shape.restrict(o, d);
            let mut stats = RootStats::default();
            s.method.smallest_root(&p, lo, hi, s.x_tol, &mut stats)
        }
        None => {
            let q = shape.restrict_exact(o, d);
            let (lo, hi) = (rat_from_f64(lo)?, rat_from_f64(hi)?);
            q.smallest_root(&lo, &hi, 0.0)
        }
    }
}

/// Traces every pixel of a `size × size` image with `setting` (`None`: the exact reference).
/// Returns the states, row-major, and the wall time in seconds.
pub fn trace_image(
    scene: &ImageScene,
    size: u32,
    setting: Option<&Setting>,
) -> (Vec<PixelState>, f64) {
    let camera = Camera::new(&CameraSpec::LookAt(scene.camera.clone()), size, size);
    let eps = (SHADOW_EPS_REL * scene.shape.size())
        .max(setting.map_or(0.0, |s| SHADOW_EPS_TOLS * s.x_tol));
    let origin = setting.map_or(Origin::Entry, |s| s.origin);
    let start = Instant::now();
    let mut out = Vec::with_capacity((size * size) as usize);
    for j in 0..size {
        for i in 0..size {
            let ray = camera.ray(f64::from(i) + 0.5, f64::from(j) + 0.5);
            let (eye, d) = (ray.origin, ray.dir);
            let miss = PixelState {
                depth: f64::INFINITY,
                shadowed: false,
            };
            let Some((t0, t1)) = scene.shape.chord(eye, d).filter(|c| c.1 > 0.0) else {
                out.push(miss);
                continue;
            };
            let t0 = t0.max(0.0);
            let hit = match origin {
                // The reference uses the eye too: its exact restriction does not depend on the
                // origin except through the rounding of the entry point, which it avoids.
                Origin::Eye => smallest(&scene.shape, eye, d, t0, t1, setting),
                Origin::Entry if setting.is_none() => smallest(&scene.shape, eye, d, t0, t1, None),
                Origin::Entry => {
                    let o = eye + d * t0;
                    smallest(&scene.shape, o, d, 0.0, t1 - t0, setting).map(|s| t0 + s)
                }
            };
            let Some(t) = hit else {
                out.push(miss);
                continue;
            };
            let p = eye + d * t;
            let to_light = scene.light - p;
            let dist = to_light.length();
            let s = to_light / dist;
            // Shadow rays start on the surface: restrict at the hit point (the origin is then
            // inside the bounding volume in both modes) and search past `eps`.
            let far = scene.shape.chord(p, s).map_or(0.0, |c| c.1.min(dist));
            let shadowed = far > eps && smallest(&scene.shape, p, s, eps, far, setting).is_some();
            out.push(PixelState { depth: t, shadowed });
        }
    }
    (out, start.elapsed().as_secs_f64())
}

/// How an image differs from the reference.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct ImageDiff {
    /// Pixels that hit in one image and miss in the other.
    pub hit_miss: usize,
    /// Pixels hit in both whose shadow state differs.
    pub shadow: usize,
    /// Largest `|depth − depth_ref|` over pixels hit in both.
    pub max_depth_err: f64,
    /// Differing pixels (hit/miss or shadow) none of whose 8 neighbours differ: speckles.
    pub speckles: usize,
}

/// Compares `img` with `reference` (both `size × size`, row-major).
pub fn diff(img: &[PixelState], reference: &[PixelState], size: u32) -> ImageDiff {
    let n = size as usize;
    let differs: Vec<bool> = img
        .iter()
        .zip(reference)
        .map(|(a, b)| a.depth.is_finite() != b.depth.is_finite() || a.shadowed != b.shadowed)
        .collect();
    let mut d = ImageDiff::default();
    for (k, (a, b)) in img.iter().zip(reference).enumerate() {
        match (a.depth.is_finite(), b.depth.is_finite()) {
            (true, true) => {
                d.max_depth_err = d.max_depth_err.max((a.depth - b.depth).abs());
                if a.shadowed != b.shadowed {
                    d.shadow += 1;
                }
            }
            (false, false) => {}
            _ => d.hit_miss += 1,
        }
        if differs[k] {
            let (i, j) = ((k % n) as i64, (k / n) as i64);
            let isolated = (-1..=1i64).all(|dj| {
                (-1..=1i64).all(|di| {
                    let (x, y) = (i + di, j + dj);
                    (di == 0 && dj == 0)
                        || x < 0
                        || y < 0
                        || x >= n as i64
                        || y >= n as i64
                        || !differs[y as usize * n + x as usize]
                })
            });
            if isolated {
                d.speckles += 1;
            }
        }
    }
    d
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::rays::SCENE_TORUS;

    fn torus_scene() -> ImageScene {
        ImageScene {
            name: "torus".to_owned(),
            shape: Shape::Torus(SCENE_TORUS),
            camera: LookAtCamera {
                eye: DVec3::new(0.0, -8.0, 5.0),
                look_at: DVec3::ZERO,
                up: DVec3::Z,
                view_field_deg: 50.0,
            },
            light: DVec3::new(5.0, -5.0, 10.0),
        }
    }

    #[test]
    fn certified_default_matches_the_exact_reference_on_a_tiny_torus_image() {
        let scene = torus_scene();
        let (reference, _) = trace_image(&scene, 12, None);
        let hits = reference.iter().filter(|p| p.depth.is_finite()).count();
        assert!(
            hits > 20 && hits < 144,
            "the torus covers part of the frame: {hits}"
        );
        let setting = Setting {
            method: Method::Bernstein(poly::RefineMethod::Illinois),
            x_tol: 1e-10,
            origin: Origin::Entry,
        };
        let (img, _) = trace_image(&scene, 12, Some(&setting));
        let d = diff(&img, &reference, 12);
        assert_eq!((d.hit_miss, d.shadow, d.speckles), (0, 0, 0), "{d:?}");
        assert!(d.max_depth_err <= 1e-9, "depth within tolerance: {d:?}");
    }

    #[test]
    fn an_isolated_difference_is_one_speckle() {
        let lit = PixelState {
            depth: 1.0,
            shadowed: false,
        };
        let reference = vec![lit; 9];
        let mut img = reference.clone();
        img[4].shadowed = true;
        let d = diff(&img, &reference, 3);
        assert_eq!((d.shadow, d.speckles), (1, 1), "centre pixel differs alone");
        img[5].shadowed = true;
        assert_eq!(
            diff(&img, &reference, 3).speckles,
            0,
            "two adjacent: not a speckle"
        );
    }
}

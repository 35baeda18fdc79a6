//! Real ray polynomials: the torus and Barth's sextic restricted to camera rays (Stam eq.
//! 3.7–3.8: `t ↦ F(o + t·d)`).
//!
//! Two ways to restrict, both measured:
//! * **camera origin**: `o` is the eye, so at camera distance `D` the coefficients grow like
//!   `D⁴` (torus) and the roots sit near `t ≈ D` — the naive tracer's polynomial, and where
//!   POV-Ray's solvers speckle;
//! * **bounding-volume entry**: `o` is moved to where the ray enters a bounding sphere (torus)
//!   or box (Barth), as `render` does, so the polynomial is built from numbers of the
//!   object's size whatever `D` is.
//!
//! For the torus the restriction is also computed exactly in rationals from the same `f64`
//! origin and direction ([`torus_restriction_exact`]), which separates the error of *building*
//! the `f64` polynomial from the error of *solving* it.

use glam::DVec3;
use poly::{Poly, QPoly, Rat, rat_from_f64};
use rand::Rng;
use render::Poly3;

/// The torus `(x² + y² + z² + R² − r²)² − 4R²(x² + y²) = 0` about the `z` axis.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TorusShape {
    /// Radius `R` of the centre circle.
    pub major: f64,
    /// Radius `r` of the tube.
    pub minor: f64,
}

/// The torus of `scenes/torus.scene`: `R = 2`, `r = 1`.
pub const SCENE_TORUS: TorusShape = TorusShape {
    major: 2.0,
    minor: 1.0,
};

/// Camera distances of the torus and Barth ray families (the 10 … 10 000).
pub const CAMERA_DISTANCES: [f64; 4] = [10.0, 100.0, 1000.0, 10_000.0];

/// `t ↦ F(o + t·d)` for the torus, in `f64`, low → high.
///
/// With `a = d·d`, `b = 2 o·d`, `c = o·o + R² − r²` the torus equation along the ray is
/// `(a t² + b t + c)² − 4R²((o_x + t d_x)² + (o_y + t d_y)²)`; expanding gives the five
/// coefficients below. This is the same algebra as `render`'s torus, written out here so the
/// suite does not depend on a private function.
pub fn torus_restriction(shape: TorusShape, o: DVec3, d: DVec3) -> Poly<f64> {
    let r2 = shape.major * shape.major;
    let a = d.length_squared();
    let b = 2.0 * o.dot(d);
    let c = o.length_squared() + r2 - shape.minor * shape.minor;
    let m = 4.0 * r2;
    Poly::new(vec![
        c * c - m * (o.x * o.x + o.y * o.y),
        2.0 * b * c - 2.0 * m * (o.x * d.x + o.y * d.y),
        b * b + 2.0 * a * c - m * (d.x * d.x + d.y * d.y),
        2.0 * a * b,
        a * a,
    ])
}

/// The same restriction computed exactly from the `f64` values of `o`, `d`, `R` and `r` (each a
/// dyadic rational): the polynomial an infinitely precise tracer would solve for this ray.
pub fn torus_restriction_exact(shape: TorusShape, o: DVec3, d: DVec3) -> QPoly {
    let q = |x: f64| rat_from_f64(x).expect("finite ray data");
    let (o, d) = ([q(o.x), q(o.y), q(o.z)], [q(d.x), q(d.y), q(d.z)]);
    let (big, small) = (q(shape.major), q(shape.minor));
    // Each coordinate o_k + t d_k as a linear polynomial.
    let lin: Vec<QPoly> = (0..3)
        .map(|k| Poly::new(vec![o[k].clone(), d[k].clone()]))
        .collect();
    let sq = |p: &QPoly| p * p;
    let radial = &sq(&lin[0]) + &sq(&lin[1]);
    let shift = &big * &big - &small * &small;
    let s = &(&radial + &sq(&lin[2])) + &Poly::constant(shift);
    let four_r2 = Rat::from_integer(4.into()) * &big * &big;
    &sq(&s) - &radial.scale(&four_r2)
}

/// `t ↦ F(o + t·d)` computed exactly from the `f64` coefficients of `F` and the `f64` values of
/// `o` and `d`: the polynomial an infinitely precise tracer would solve for this surface and
/// ray.
pub fn poly3_restriction_exact(f: &Poly3, o: DVec3, d: DVec3) -> QPoly {
    let q = |x: f64| rat_from_f64(x).expect("finite ray data");
    let lin: Vec<QPoly> = (0..3).map(|k| Poly::new(vec![q(o[k]), q(d[k])])).collect();
    // Powers (o_k + t d_k)^e for every exponent needed.
    let max_e = f.partial_degrees();
    let powers: Vec<Vec<QPoly>> = (0..3)
        .map(|k| {
            let mut v = vec![Poly::constant(q(1.0))];
            for e in 1..=max_e[k] as usize {
                let next = &v[e - 1] * &lin[k];
                v.push(next);
            }
            v
        })
        .collect();
    let mut out = QPoly::zero();
    for t in f.terms() {
        let [i, j, k] = t.exps.map(|e| e as usize);
        let m = &(&powers[0][i] * &powers[1][j]) * &powers[2][k];
        out = &out + &m.scale(&q(t.coeff));
    }
    out
}

/// Barth's sextic `4(φ²x² − y²)(φ²y² − z²)(φ²z² − x²) − (1 + 2φ)(x² + y² + z² − 1)²`, `φ` the
/// golden ratio (as in `scenes/barth.scene`), as a trivariate polynomial.
pub fn barth_sextic() -> Poly3 {
    let phi = (1.0 + 5f64.sqrt()) / 2.0;
    let (x, y, z) = (Poly3::x(), Poly3::y(), Poly3::z());
    let (x2, y2, z2) = (&x * &x, &y * &y, &z * &z);
    let p2 = phi * phi;
    let f1 = &(&x2 * p2) - &y2;
    let f2 = &(&y2 * p2) - &z2;
    let f3 = &(&z2 * p2) - &x2;
    let sphere = &(&(&x2 + &y2) + &z2) - &Poly3::constant(1.0);
    &(&(&(&f1 * &f2) * &f3) * 4.0) - &(&(&sphere * &sphere) * (1.0 + 2.0 * phi))
}

/// Half-side of Barth's bounding box `[-2, 2]³` (from `scenes/barth.scene`).
pub const BARTH_BOX: f64 = 2.0;

/// One ray polynomial with its search range `(lo, hi]` and, where available, its exact
/// restriction.
#[derive(Clone, Debug)]
pub struct RayPoly {
    /// The `f64` polynomial in `t` as a tracer would store it.
    pub poly: Poly<f64>,
    /// Search range start (excluded).
    pub lo: f64,
    /// Search range end (included).
    pub hi: f64,
    /// Exact restriction of the same ray (for the construction-error statistic).
    pub exact: Option<QPoly>,
}

/// An orthonormal pair spanning the plane perpendicular to unit `w`.
fn basis(w: DVec3) -> (DVec3, DVec3) {
    let helper = if w.z.abs() < 0.9 { DVec3::Z } else { DVec3::X };
    let u = w.cross(helper).normalize();
    (u, w.cross(u))
}

/// A point drawn uniformly from the disc of radius `radius` centred at the origin and
/// perpendicular to `w`.
fn disc_point(rng: &mut impl Rng, w: DVec3, radius: f64) -> DVec3 {
    let (u, v) = basis(w);
    let r = radius * rng.r#gen::<f64>().sqrt();
    let a = std::f64::consts::TAU * rng.r#gen::<f64>();
    u * (r * a.cos()) + v * (r * a.sin())
}

/// The parameter interval where the line `o + t·d` is inside the sphere `|p| ≤ radius`.
pub fn sphere_chord(o: DVec3, d: DVec3, radius: f64) -> Option<(f64, f64)> {
    let a = d.length_squared();
    let b = o.dot(d);
    let c = o.length_squared() - radius * radius;
    let disc = b * b - a * c;
    if disc <= 0.0 {
        return None;
    }
    // Stable quadratic roots (no cancellation in −b ± √disc).
    let q = -(b + b.signum() * disc.sqrt());
    let (t0, t1) = (q / a, c / q);
    Some((t0.min(t1), t0.max(t1)))
}

/// The parameter interval where the line is inside the cube `[-h, h]³` (slab method).
pub fn box_chord(o: DVec3, d: DVec3, h: f64) -> Option<(f64, f64)> {
    let (mut t0, mut t1) = (f64::NEG_INFINITY, f64::INFINITY);
    for k in 0..3 {
        if d[k] == 0.0 {
            if o[k].abs() > h {
                return None;
            }
            continue;
        }
        let (a, b) = ((-h - o[k]) / d[k], (h - o[k]) / d[k]);
        t0 = t0.max(a.min(b));
        t1 = t1.min(a.max(b));
    }
    (t0 < t1).then_some((t0, t1))
}

/// Torus rays from a camera at distance `dist` in the direction of `torus.scene`'s eye
/// `(0, −8, 5)`, aimed at points drawn uniformly in the disc of radius `R + r` facing the
/// camera (so every ray meets the bounding sphere; some miss the torus).
///
/// With `entry = false` the polynomial is restricted at the eye and searched on
/// `(0, dist + R + r + 1]`; with `entry = true` at the bounding-sphere entry and searched on
/// `(0, chord]`. Directions are unit vectors, so `t` is a distance.
pub fn torus_rays(
    shape: TorusShape,
    dist: f64,
    n: usize,
    entry: bool,
    rng: &mut impl Rng,
) -> Vec<RayPoly> {
    let eye = DVec3::new(0.0, -8.0, 5.0).normalize() * dist;
    let w = -eye.normalize();
    let radius = shape.major + shape.minor;
    let mut out = Vec::with_capacity(n);
    while out.len() < n {
        let target = disc_point(rng, w, radius);
        let d = (target - eye).normalize();
        let Some((t0, t1)) = sphere_chord(eye, d, radius) else {
            continue;
        };
        let (o, hi) = if entry {
            (eye + d * t0, t1 - t0)
        } else {
            (eye, dist + radius + 1.0)
        };
        if hi.is_nan() || hi <= 1e-6 {
            continue;
        }
        out.push(RayPoly {
            poly: torus_restriction(shape, o, d),
            lo: 0.0,
            hi,
            exact: Some(torus_restriction_exact(shape, o, d)),
        });
    }
    out
}

/// Barth rays from a camera at distance `dist` in the direction of `barth.scene`'s eye
/// `(5, −9, 6)`, aimed at points drawn uniformly in the bounding box `[-2, 2]³`.
///
/// With `entry = false` the sextic is restricted at the eye and searched on the box chord
/// `(t_in, t_out]`, shifted so the search starts at `t_in`: the range is `(t_in, t_out]` in the
/// eye's parameter. With `entry = true` it is restricted at the box entry and searched on
/// `(0, t_out − t_in]`, as `render` does.
pub fn barth_rays(f: &Poly3, dist: f64, n: usize, entry: bool, rng: &mut impl Rng) -> Vec<RayPoly> {
    let eye = DVec3::new(5.0, -9.0, 6.0).normalize() * dist;
    let mut out = Vec::with_capacity(n);
    while out.len() < n {
        let target = DVec3::new(
            rng.gen_range(-BARTH_BOX..BARTH_BOX),
            rng.gen_range(-BARTH_BOX..BARTH_BOX),
            rng.gen_range(-BARTH_BOX..BARTH_BOX),
        );
        let d = (target - eye).normalize();
        let Some((t0, t1)) = box_chord(eye, d, BARTH_BOX) else {
            continue;
        };
        let (o, lo, hi) = if entry {
            (eye + d * t0, 0.0, t1 - t0)
        } else {
            (eye, t0, t1)
        };
        if (hi - lo).is_nan() || hi - lo <= 1e-6 {
            continue;
        }
        out.push(RayPoly {
            poly: f.restrict_to_line(o, d),
            lo,
            hi,
            exact: Some(poly3_restriction_exact(f, o, d)),
        });
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use poly::rat_to_f64;
    use rand::SeedableRng;

    #[test]
    fn f64_and_exact_torus_restrictions_agree_and_vanish_on_the_torus() {
        let o = DVec3::new(0.5, -7.0, 4.25);
        let d = DVec3::new(0.0, 0.75, -0.5);
        let p = torus_restriction(SCENE_TORUS, o, d);
        let q = torus_restriction_exact(SCENE_TORUS, o, d);
        // These inputs are small dyadics: the f64 expansion is exact.
        assert_eq!(p, q.to_f64(), "f64 restriction is exact on dyadic data");
        // The torus point (3, 0, 0) is o + t d for no t here; check a known point instead:
        // the ray from (4, 0, 0) towards −x meets the torus at t = 1 (x = 3) and t = 3 (x = 1).
        let p = torus_restriction(SCENE_TORUS, DVec3::new(4.0, 0.0, 0.0), DVec3::NEG_X);
        assert_eq!(p.eval(&1.0), 0.0, "outer equator");
        assert_eq!(p.eval(&3.0), 0.0, "inner equator");
        let r = rat_to_f64(&q.eval(&Rat::from_integer(0.into())));
        assert_eq!(
            r,
            torus_restriction(SCENE_TORUS, o, d).coeffs()[0],
            "constant term"
        );
    }

    #[test]
    fn barth_vanishes_at_a_node_and_rays_have_degree_six() {
        // (0, 0, 1) lies on Barth's sextic: 4(0)(−1)(φ²) − (1 + 2φ)·0 = 0.
        let f = barth_sextic();
        assert_eq!(f.eval(DVec3::Z), 0.0, "(0, 0, 1) is on the surface");
        assert_eq!(f.degree(), 6, "sextic");
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(1);
        for ray in barth_rays(&f, 12.0, 4, true, &mut rng) {
            assert_eq!(ray.poly.degree(), 6, "restriction of a sextic");
            let exact = ray.exact.as_ref().expect("exact restriction").to_f64();
            for (a, b) in exact.coeffs().iter().zip(ray.poly.coeffs()) {
                assert!(
                    (a - b).abs() <= 1e-9 * a.abs().max(1.0),
                    "f64 restriction {b} vs exact {a}"
                );
            }
            assert!(ray.lo == 0.0 && ray.hi > 0.0, "search range (0, chord]");
        }
    }
}

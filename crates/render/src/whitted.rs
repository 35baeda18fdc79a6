//! The Whitted integrator with Stam's illumination model (thesis §2.3, eq. 2.6–2.16;
//! Annexe B `Intensity`, `IllumModel`, `TraceRay`). See `paper-notes/illumination.md`.
//!
//! `I = I_a + I_d + I_s + I_r + I_t` (2.6) with
//! - `I_a = k_a C_s` (2.7),
//! - `I_d = k_d C_s Σ_j I_j (N·L_j)` (2.8), lights hidden by a shadow ray skipped,
//! - `I_s = k_s C_r Σ_j I_j (N·H_j)^n`, `H_j = (L_j − V)/|L_j − V|` (2.9–2.10),
//! - `I_r = k_s M`, `M` traced along `R = W + 2N`, `W = V/|V·N|` (2.11–2.13),
//! - `I_t = k_t T`, `T` traced along `P` of eq. 2.15 with `k_n = n₂/n₁` (2.14–2.16).
//!
//! Each object's [`Illumination`] level selects the terms, as Stam's `IllumId` does.

use std::ops::Range;

use glam::DVec3;

use crate::geometry::{Ray, offset_ray_origin};
use crate::material::surface_color;
use crate::prepared::PreparedScene;
use crate::scene::{Illumination, Rgb};
use crate::surface::Hit;
use crate::workspace::Workspace;

/// Distance scale of Stam's attenuation (§2.3.6; `ray0.c` `IllumModel`:
/// `less = 5/(5 + distL)`), in scene units. Applied to the diffuse and specular terms when
/// `Attenuation = ON`.
pub const ATTENUATION_DISTANCE: f64 = 5.0;

/// `x^n` for the specular exponent: an integer `n` (Stam's `n` is "l'entier naturel n",
/// eq. 2.9) takes `powi`, several times cheaper than `powf`.
fn specular_power(x: f64, n: f64) -> f64 {
    if n.fract() == 0.0 && n.abs() <= 1024.0 {
        x.powi(n as i32)
    } else {
        x.powf(n)
    }
}

/// Adaptive depth control (POV-Ray's `adc_bailout`, default 1/255): a secondary ray whose
/// weight — the product of the `k_s` and `k_t` factors from the eye to it — is below this is
/// not traced.
///
/// Derivation: a traced colour is clamped to at most 1 per channel (Stam's `Intensity`), so
/// such a ray changes its pixel's linear value by less than `ADC_BAILOUT`; with it the ray
/// tree of a transparent, reflective scene stops growing after `log(ADC_BAILOUT)/log(k)`
/// levels whatever `MaxDepth` says (`k = max(k_s, k_t)`; 8 levels at `k = 0.5`), instead of
/// doubling per level up to `MaxDepth`. The value is POV-Ray's default, half an 8-bit step
/// in linear light; the golden images of `scenes/` are unchanged by it.
pub const ADC_BAILOUT: f64 = 1.0 / 255.0;

/// The ray parameter range of a new ray: open at 0. Self-intersection is prevented by moving
/// the origin off the surface by the hit point's error bound
/// ([`offset_ray_origin`]), not by a fixed epsilon.
const SPAWN_RANGE: Range<f64> = 0.0..f64::INFINITY;

/// What a primary ray returns.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PrimarySample {
    /// The colour (linear, each channel clamped to `[0, 1]` as in Stam's `Intensity`).
    pub color: Rgb,
    /// Distance to the first hit (`+∞` for a miss).
    pub depth: f64,
}

/// The nearest hit along `ray` among all primitives (through the scene's BVH): its index and
/// the hit.
pub fn nearest_hit(
    scene: &PreparedScene,
    ray: &Ray,
    t_range: Range<f64>,
    ws: &mut Workspace,
) -> Option<(usize, Hit)> {
    // Each primitive is asked over the whole range, so its answer does not depend on the
    // visiting order: the result is the least (t, index), as a loop over all would find.
    let mut visits = 0;
    let best = scene
        .aggregate
        .nearest(ray, t_range.clone(), &mut visits, |i| {
            let prim = &scene.primitives[i as usize];
            let kind = prim.surface.kind().index();
            ws.stats.per_kind[kind].tests += 1;
            let h = prim.surface.intersect(ray, t_range.clone(), ws)?;
            ws.stats.per_kind[kind].hits += 1;
            Some((h.t, h))
        });
    ws.stats.bvh_node_visits += visits;
    best.map(|(i, _, h)| (i as usize, h))
}

/// Whether any primitive blocks `ray` within `t_range` (through the scene's BVH); stops at the
/// first blocker.
pub fn occluded(scene: &PreparedScene, ray: &Ray, t_range: Range<f64>, ws: &mut Workspace) -> bool {
    let mut visits = 0;
    let blocked = scene.aggregate.any(ray, t_range.clone(), &mut visits, |i| {
        let prim = &scene.primitives[i as usize];
        let kind = prim.surface.kind().index();
        ws.stats.per_kind[kind].shadow_tests += 1;
        let hit = prim.surface.occluded(ray, t_range.clone(), ws);
        ws.stats.per_kind[kind].occlusions += u64::from(hit);
        hit
    });
    ws.stats.bvh_node_visits += visits;
    blocked
}

/// Traces a camera ray (depth 1, weight 1).
pub fn trace_primary(scene: &PreparedScene, ray: &Ray, ws: &mut Workspace) -> PrimarySample {
    ws.stats.primary_rays += 1;
    match nearest_hit(scene, ray, SPAWN_RANGE, ws) {
        Some((i, hit)) => {
            let depth = hit.t * ray.dir.length();
            PrimarySample {
                color: shade(scene, ray, i, &hit, Branch::PRIMARY, ws),
                depth,
            }
        }
        None => PrimarySample {
            color: scene.world.background,
            depth: f64::INFINITY,
        },
    }
}

/// Where a ray is in the ray tree: its recursion depth (1 for a camera ray) and its weight,
/// the factor by which its colour enters the pixel.
#[derive(Clone, Copy, Debug)]
struct Branch {
    depth: u32,
    weight: f64,
}

impl Branch {
    const PRIMARY: Branch = Branch {
        depth: 1,
        weight: 1.0,
    };

    /// The child ray carrying `factor` (`k_s`, `k_t` or their sum).
    fn child(self, factor: f64) -> Branch {
        Branch {
            depth: self.depth + 1,
            weight: self.weight * factor,
        }
    }
}

/// Stam's `TraceRay` for a secondary ray (depth ≥ 2).
fn trace(scene: &PreparedScene, ray: &Ray, branch: Branch, ws: &mut Workspace) -> Rgb {
    match nearest_hit(scene, ray, SPAWN_RANGE, ws) {
        Some((i, hit)) => shade(scene, ray, i, &hit, branch, ws),
        None => scene.world.background,
    }
}

/// Stam's `Intensity`: eq. 2.6 at an accepted hit.
fn shade(
    scene: &PreparedScene,
    ray: &Ray,
    index: usize,
    hit: &Hit,
    branch: Branch,
    ws: &mut Workspace,
) -> Rgb {
    let depth = branch.depth;
    let prim = &scene.primitives[index];
    let m = &prim.material;
    if m.illumination == Illumination::Blackbody {
        return Rgb::ZERO;
    }
    let g = prim.surface.shading(hit);
    let v = ray.dir.normalize(); // V: from the eye towards the surface
    let mut n = match g.normal {
        Some(n) => n,
        None => {
            // Singular point (∇F = 0, Stam §3.6.1): shade as if the surface faced the ray.
            ws.stats.singular_normals += 1;
            -v
        }
    };
    // Make N face the incoming ray; remember whether we are leaving the object.
    let cos_alpha = n.dot(v);
    let inside = cos_alpha > 0.0;
    if inside {
        n = -n;
    }
    let p = g.p;
    let cs = surface_color(m, &scene.textures, g.uv);

    // (2.7) ambient.
    let mut color = cs * m.ka;

    // (2.8)–(2.10) diffuse and specular, per light.
    if m.illumination >= Illumination::Diffuse {
        for light in &scene.lights {
            let to_light = light.source - p;
            let dist = to_light.length();
            let l = to_light / dist;
            let cos_theta = n.dot(l);
            if cos_theta <= 0.0 || cos_theta.is_nan() {
                ws.stats.light_below_surface += 1;
                continue;
            }
            if scene.world.shadows {
                let origin = offset_ray_origin(p, g.p_err, n, l);
                let shadow = Ray::new(origin, l);
                ws.stats.shadow_rays += 1;
                let reach = (light.source - origin).length();
                if occluded(scene, &shadow, 0.0..reach, ws) {
                    ws.stats.shadow_blocked += 1;
                    continue;
                }
            } else {
                ws.stats.shadow_skipped_off += 1;
            }
            let atten = if scene.world.attenuation {
                ATTENUATION_DISTANCE / (ATTENUATION_DISTANCE + dist)
            } else {
                1.0
            };
            color += cs * light.color * (m.kd * cos_theta * atten);
            if m.illumination >= Illumination::Specular {
                let h = (l - v).normalize();
                let cos_h = n.dot(h);
                if cos_h > 0.0 {
                    color += m.cr * light.color * (m.ks * specular_power(cos_h, m.n) * atten);
                }
            }
        }
    }

    // (2.11)–(2.13) reflection: R = V − 2(V·N)N, the normalised W + 2N. The reflected ray is
    // traced after the transmission below, which may add its own weight to it.
    let cos_alpha = v.dot(n); // ≤ 0 after the flip
    let reflect_dir = v - n * (2.0 * cos_alpha);
    let mut reflect_weight = 0.0;
    let mut mirror = false; // the reflected ray carries k_s (else only a k_t under TIR)
    if m.illumination >= Illumination::Mirror {
        if m.ks == 0.0 {
            ws.stats.secondary_skipped_material += 1;
        } else if depth >= scene.world.max_depth {
            ws.stats.secondary_skipped_depth += 1;
        } else {
            reflect_weight = m.ks;
            mirror = true;
        }
    }

    // (2.14)–(2.16) transmission. With k_n = n₂/n₁ (inverted when leaving the object), eq.
    // 2.15 is Snell's law: P = V/k_n + (−cos α/k_n − √(1 − (1 − cos²α)/k_n²))·N, as in
    // Stam's `Intensity`. When the root is imaginary (total internal reflection) the
    // transmitted energy follows the reflected direction: the same ray from the same origin
    // as the reflected one, so when that one is traced it carries both weights (k_s + k_t)
    // and is traced once.
    if m.illumination >= Illumination::Transparent {
        if m.kt == 0.0 {
            ws.stats.secondary_skipped_material += 1;
        } else if depth >= scene.world.max_depth {
            ws.stats.secondary_skipped_depth += 1;
        } else {
            let kn = if inside { 1.0 / m.kn } else { m.kn };
            let q = 1.0 - (1.0 - cos_alpha * cos_alpha) / (kn * kn);
            if q >= 0.0 {
                let dir = v / kn + n * (-cos_alpha / kn - q.sqrt());
                let origin = offset_ray_origin(p, g.p_err, n, dir);
                if branch.weight * m.kt < ADC_BAILOUT {
                    ws.stats.secondary_skipped_weight += 1;
                } else {
                    ws.stats.refracted_rays += 1;
                    let ray = Ray::new(origin, dir);
                    color += trace(scene, &ray, branch.child(m.kt), ws) * m.kt;
                }
            } else {
                ws.stats.total_internal_reflections += 1;
                if mirror {
                    ws.stats.tir_merged += 1;
                }
                reflect_weight += m.kt;
            }
        }
    }
    if reflect_weight > 0.0 && branch.weight * reflect_weight < ADC_BAILOUT {
        ws.stats.secondary_skipped_weight += 1;
    } else if reflect_weight > 0.0 {
        // One ray, counted once: reflected when it carries k_s, else transmitted (TIR).
        if mirror {
            ws.stats.reflected_rays += 1;
        } else {
            ws.stats.refracted_rays += 1;
        }
        let origin = offset_ray_origin(p, g.p_err, n, reflect_dir);
        let ray = Ray::new(origin, reflect_dir);
        color += trace(scene, &ray, branch.child(reflect_weight), ws) * reflect_weight;
    }

    // Stam clamps each intensity to at most 1 (end of `Intensity`).
    color.min(DVec3::ONE)
}

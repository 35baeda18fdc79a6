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
    nearest_hit_leaving(scene, ray, t_range, None, ws)
}

/// [`nearest_hit`] for a ray that leaves primitive `leaving` along its outward normal when
/// that primitive is [`Surface::convex`]: it cannot be hit again, so it is not asked (see
/// [`occluded_towards`]).
///
/// [`Surface::convex`]: crate::surface::Surface::convex
fn nearest_hit_leaving(
    scene: &PreparedScene,
    ray: &Ray,
    t_range: Range<f64>,
    leaving: Option<u32>,
    ws: &mut Workspace,
) -> Option<(usize, Hit)> {
    #[cfg(test)]
    let leaving = if ws.test_the_surface_left {
        None
    } else {
        leaving
    };
    // Each primitive is asked over the whole range, so its answer does not depend on the
    // visiting order: the result is the least (t, index), as a loop over all would find.
    let mut visits = 0;
    let range = t_range.clone();
    let best = if scene.aggregate.is_flat() {
        // A few surfaces, each testing its own box and ball at once: the hit interval would
        // only repeat that work (`paper-notes/bvh.md`, eighteenth session).
        scene.aggregate.nearest(ray, range, &mut visits, |i, _| {
            (Some(i) != leaving).then(|| test_surface(scene, i, ray, t_range.clone(), ws))?
        })
    } else {
        // A surface whose hits certainly all lie beyond the nearest hit so far, or before the
        // range, cannot be the answer (nor tie with it): skipped by its hit interval, as the
        // hierarchy skips nodes.
        scene
            .aggregate
            .nearest(ray, range, &mut visits, |i, t_max| {
                if Some(i) == leaving {
                    return None;
                }
                match scene.surfaces[i as usize].hit_interval(ray) {
                    Some(hits) if hits.start <= t_max && hits.end >= t_range.start => {}
                    _ => return None,
                }
                test_surface(scene, i, ray, t_range.clone(), ws)
            })
    };
    ws.stats.bvh_node_visits += visits;
    best.map(|(i, _, h)| (i as usize, h))
}

/// Primitive `i`'s nearest hit of `ray` in `t_range`, counted in the statistics.
#[inline(always)]
fn test_surface(
    scene: &PreparedScene,
    i: u32,
    ray: &Ray,
    t_range: Range<f64>,
    ws: &mut Workspace,
) -> Option<(f64, Hit)> {
    let surface = &scene.surfaces[i as usize];
    let kind = surface.kind().index();
    ws.stats.per_kind[kind].tests += 1;
    let h = surface.intersect(ray, t_range, ws)?;
    ws.stats.per_kind[kind].hits += 1;
    Some((h.t, h))
}

/// Whether any primitive blocks `ray` within `t_range` (through the scene's BVH); stops at the
/// first blocker.
pub fn occluded(scene: &PreparedScene, ray: &Ray, t_range: Range<f64>, ws: &mut Workspace) -> bool {
    first_blocker(scene, ray, t_range, [NO_BLOCKER; 2], ws).is_some()
}

/// Whether primitive `i` blocks `ray` within `t_range`, counted in the statistics.
fn blocks(
    scene: &PreparedScene,
    i: usize,
    ray: &Ray,
    t_range: Range<f64>,
    ws: &mut Workspace,
) -> bool {
    let surface = &scene.surfaces[i];
    let kind = surface.kind().index();
    ws.stats.per_kind[kind].shadow_tests += 1;
    let hit = surface.occluded(ray, t_range, ws);
    ws.stats.per_kind[kind].occlusions += u64::from(hit);
    hit
}

/// The first primitive found blocking `ray` within `t_range` (through the scene's BVH), other
/// than the `known_clear` ones ([`NO_BLOCKER`] for none), which the caller knows not to block.
fn first_blocker(
    scene: &PreparedScene,
    ray: &Ray,
    t_range: Range<f64>,
    known_clear: [u32; 2],
    ws: &mut Workspace,
) -> Option<u32> {
    let mut visits = 0;
    let mut blocker = None;
    scene.aggregate.any(ray, t_range.clone(), &mut visits, |i| {
        let hit = !known_clear.contains(&i) && blocks(scene, i as usize, ray, t_range.clone(), ws);
        if hit {
            blocker = Some(i);
        }
        hit
    });
    ws.stats.bvh_node_visits += visits;
    blocker
}

/// No cached blocker in [`Workspace::shadow_blockers`].
const NO_BLOCKER: u32 = u32::MAX;

/// [`occluded`] for a shadow ray towards light `light`, with a shadow cache (Haines and
/// Greenberg 1986, "The light buffer: a shadow-testing accelerator"; POV-Ray's per-light
/// cached object): the primitive that blocked this thread's last blocked shadow ray towards
/// the same light is tested first, and only when it does not block is the BVH traversed
/// (skipping that primitive), which then remembers the new blocker. Neighbouring shadow rays
/// tend to be blocked by the same object, and a hit on it saves the whole traversal. The
/// verdict is [`occluded`]'s: the cached primitive is one of those the traversal could test,
/// its verdict on the ray is the same either way, and any blocker answers yes.
///
/// `leaving`: the surface the ray leaves, when it is [`Surface::convex`] and the ray leaves
/// along its outward normal — it cannot block the ray, so it is not tested (on the SPD
/// sphereflakes every shadow ray's traversal reaches the sphere it starts on). See
/// `paper-notes/bvh.md` §2.
///
/// [`Surface::convex`]: crate::surface::Surface::convex
fn occluded_towards(
    scene: &PreparedScene,
    ray: &Ray,
    t_range: Range<f64>,
    light: usize,
    leaving: Option<u32>,
    ws: &mut Workspace,
) -> bool {
    let leaving = leaving.unwrap_or(NO_BLOCKER);
    #[cfg(test)]
    let leaving = if ws.test_the_surface_left {
        NO_BLOCKER
    } else {
        leaving
    };
    #[cfg(test)]
    if ws.shadow_cache_off {
        return first_blocker(scene, ray, t_range, [leaving, NO_BLOCKER], ws).is_some();
    }
    if ws.shadow_blockers.len() <= light {
        ws.shadow_blockers
            .resize(scene.lights.len().max(light + 1), NO_BLOCKER);
    }
    let cached = ws.shadow_blockers[light];
    // A workspace may come from another scene: an index out of range is no cache.
    let known_clear = if (cached as usize) < scene.surfaces.len() && cached != leaving {
        if blocks(scene, cached as usize, ray, t_range.clone(), ws) {
            ws.stats.shadow_cache_hits += 1;
            return true;
        }
        cached
    } else {
        NO_BLOCKER
    };
    match first_blocker(scene, ray, t_range, [known_clear, leaving], ws) {
        Some(i) => {
            ws.shadow_blockers[light] = i;
            true
        }
        None => false,
    }
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

/// Stam's `TraceRay` for a secondary ray (depth ≥ 2); `leaving` as in
/// [`nearest_hit_leaving`].
fn trace(
    scene: &PreparedScene,
    ray: &Ray,
    branch: Branch,
    leaving: Option<u32>,
    ws: &mut Workspace,
) -> Rgb {
    match nearest_hit_leaving(scene, ray, SPAWN_RANGE, leaving, ws) {
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
    let m = scene.material(index);
    if m.illumination == Illumination::Blackbody {
        return Rgb::ZERO;
    }
    let g = scene.surfaces[index].shading(hit);
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
    // A shadow ray below leaves along N (N·L > 0), and so does the reflected ray; when N is
    // the outward normal of a convex surface, that surface cannot block or meet them.
    let leaving =
        (g.normal.is_some() && !inside && scene.surfaces[index].convex()).then_some(index as u32);
    let p = g.p;
    let cs = surface_color(m, &scene.textures, g.uv);

    // (2.7) ambient.
    let mut color = cs * m.ka;

    // (2.8)–(2.10) diffuse and specular, per light.
    if m.illumination >= Illumination::Diffuse {
        for (light_index, light) in scene.lights.iter().enumerate() {
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
                if occluded_towards(scene, &shadow, 0.0..reach, light_index, leaving, ws) {
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
                    color += trace(scene, &ray, branch.child(m.kt), None, ws) * m.kt;
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
        // R·N = −V·N > 0: the reflected ray leaves along N, as the shadow rays do (a total
        // internal reflection is inside, where `leaving` is `None`).
        color += trace(scene, &ray, branch.child(reflect_weight), leaving, ws) * reflect_weight;
    }

    // Stam clamps each intensity to at most 1 (end of `Intensity`).
    color.min(DVec3::ONE)
}

#[cfg(test)]
mod tests {
    use rand::{Rng, SeedableRng};
    use rand_chacha::ChaCha8Rng;

    use super::*;
    use crate::scene::{Light, Object, Scene, ShapeKind, ValidScene};
    use crate::surface::SurfaceKind;

    /// `n` random spheres in a 10-unit cube and one light above them.
    fn spheres(n: usize, rng: &mut ChaCha8Rng) -> PreparedScene {
        spheres_and_shapes(n, rng).0
    }

    /// [`spheres`] with each sphere's `(centre, radius)`.
    fn spheres_and_shapes(n: usize, rng: &mut ChaCha8Rng) -> (PreparedScene, Vec<(DVec3, f64)>) {
        let mut scene = Scene::default();
        let mut shapes = Vec::with_capacity(n);
        for _ in 0..n {
            let center = DVec3::new(
                rng.gen_range(-5.0..5.0),
                rng.gen_range(-5.0..5.0),
                rng.gen_range(-5.0..5.0),
            );
            let radius = rng.gen_range(0.3..1.5);
            shapes.push((center, radius));
            scene
                .objects
                .push(Object::new(ShapeKind::Sphere { center, radius }));
        }
        scene.lights.push(Light {
            source: DVec3::new(0.0, 0.0, 20.0),
            color: DVec3::ONE,
        });
        let prepared =
            PreparedScene::new(&ValidScene::new(scene).expect("valid scene")).expect("prepared");
        (prepared, shapes)
    }

    /// The shadow cache answers as the uncached query on coherent shadow rays (origins
    /// creeping across the floor under the spheres, so the cached blocker often blocks the
    /// next ray too, and often does not), and a workspace that cached a blocker in a larger
    /// scene is harmless in a smaller one.
    #[test]
    fn shadow_cache_verdicts_equal_the_uncached_query() {
        let mut rng = ChaCha8Rng::seed_from_u64(12);
        let big = spheres(60, &mut rng);
        let small = spheres(3, &mut rng);
        let mut ws = Workspace::new();
        let (mut blocked, mut cached_blocks) = (0, 0);
        for scene in [&big, &small, &big] {
            let light = scene.lights[0].source;
            for k in 0..2000 {
                let origin = DVec3::new(
                    -6.0 + 12.0 * f64::from(k % 50) / 50.0,
                    -6.0 + 12.0 * f64::from(k / 50) / 40.0,
                    -6.0,
                );
                let ray = Ray::new(origin, light - origin);
                let range = 0.0..1.0;
                let before = ws.shadow_blockers.first().copied();
                let with_cache = occluded_towards(scene, &ray, range.clone(), 0, None, &mut ws);
                let brute = scene
                    .surfaces
                    .iter()
                    .any(|s| s.occluded(&ray, range.clone(), &mut ws));
                assert_eq!(with_cache, brute, "shadow verdict from {origin}");
                assert_eq!(occluded(scene, &ray, range, &mut ws), brute, "uncached");
                blocked += usize::from(brute);
                cached_blocks +=
                    usize::from(brute && before == ws.shadow_blockers.first().copied());
            }
        }
        assert!(
            blocked > 500 && blocked < 5500,
            "a mix of verdicts: {blocked}"
        );
        assert!(
            cached_blocks > blocked / 2,
            "the cache answers most: {cached_blocks}"
        );
    }

    /// Shadow rays leaving a sphere along its outward normal, from points just outside it
    /// (as `offset_ray_origin` puts them) towards lights around the scene: the verdict without
    /// testing the sphere left is the verdict of every sphere tested, and that sphere is then
    /// never tested.
    #[test]
    fn a_shadow_ray_leaving_a_sphere_is_not_blocked_by_it() {
        let mut rng = ChaCha8Rng::seed_from_u64(31);
        let (scene, shapes) = spheres_and_shapes(40, &mut rng);
        let mut ws = Workspace::new();
        let (mut blocked, mut rays) = (0, 0);
        for _ in 0..4000 {
            let i = rng.gen_range(0..shapes.len());
            let (center, radius) = shapes[i];
            let n = DVec3::new(
                rng.gen_range(-1.0..1.0),
                rng.gen_range(-1.0..1.0),
                rng.gen_range(-1.0..1.0),
            )
            .normalize();
            let light = DVec3::new(
                rng.gen_range(-20.0..20.0),
                rng.gen_range(-20.0..20.0),
                rng.gen_range(-20.0..20.0),
            );
            let origin = center + n * radius * (1.0 + 1e-9);
            let l = light - origin;
            if n.dot(l) <= 0.0 {
                continue;
            }
            rays += 1;
            let ray = Ray::new(origin, l);
            let brute = scene
                .surfaces
                .iter()
                .any(|s| s.occluded(&ray, 0.0..1.0, &mut ws));
            // The fact the skip rests on: the certified test of the sphere left says no.
            assert!(
                !scene.surfaces[i].occluded(&ray, 0.0..1.0, &mut ws),
                "sphere {i} blocks a ray leaving it from {origin}"
            );
            ws.shadow_blockers.clear();
            let skipping = occluded_towards(&scene, &ray, 0.0..1.0, 0, Some(i as u32), &mut ws);
            assert_eq!(skipping, brute, "shadow ray leaving sphere {i} at {origin}");
            blocked += usize::from(brute);
        }
        assert!(
            rays > 1000 && blocked > 100 && blocked < rays - 100,
            "{blocked} of {rays}"
        );
    }

    /// From the inside of a sphere (a ray refracted into glass), a shadow ray towards a light
    /// beyond the far wall goes into the ball, not out of it: the sphere blocks it and must be
    /// tested (the skip is only for rays leaving along the outward normal).
    #[test]
    fn a_shadow_ray_from_inside_a_sphere_is_blocked_by_it() {
        let mut scene = Scene::default();
        scene.objects.push(Object::new(ShapeKind::Sphere {
            center: DVec3::ZERO,
            radius: 2.0,
        }));
        scene.lights.push(Light {
            source: DVec3::new(0.0, 0.0, 10.0),
            color: DVec3::ONE,
        });
        let prepared =
            PreparedScene::new(&ValidScene::new(scene).expect("valid scene")).expect("prepared");
        let mut ws = Workspace::new();
        // From the centre down to the wall at z = −2, whose inner side faces the light.
        let _ = trace_primary(&prepared, &Ray::new(DVec3::ZERO, DVec3::NEG_Z), &mut ws);
        assert_eq!(ws.stats.shadow_rays, 1, "one shadow ray");
        assert_eq!(ws.stats.shadow_blocked, 1, "blocked by the sphere's top");
    }

    /// Traces every pixel of scenes/spd/balls-s2.nff at 48² with a default workspace and with
    /// one that `configure` changed, asserts the two give the same samples, and returns the
    /// two workspaces' counters (default first).
    fn sphereflake_pixels_agree(
        configure: impl Fn(&mut Workspace),
    ) -> (crate::stats::TraceStats, crate::stats::TraceStats) {
        let path =
            std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../scenes/spd/balls-s2.nff");
        let text = std::fs::read_to_string(&path).expect("scenes/spd/balls-s2.nff");
        let scene = crate::scene::parse_nff(&text, &path).expect("valid NFF");
        let prepared = PreparedScene::new(&scene).expect("prepared");
        let size = 48;
        let camera = crate::camera::Camera::new(&scene.camera, size, size);
        let (mut default, mut changed) = (Workspace::new(), Workspace::new());
        configure(&mut changed);
        for y in 0..size {
            for x in 0..size {
                let ray = camera.ray(f64::from(x) + 0.5, f64::from(y) + 0.5);
                let a = trace_primary(&prepared, &ray, &mut default);
                let b = trace_primary(&prepared, &ray, &mut changed);
                assert_eq!(a, b, "pixel ({x}, {y})");
            }
        }
        (default.stats, changed.stats)
    }

    /// Not testing the convex surface a shadow or reflected ray leaves changes no pixel of an
    /// SPD scene (balls-s2: mirror spheres over a floor polygon, both convex), and it saves
    /// tests: every shadow and reflected ray from a sphere reached its own sphere.
    #[test]
    fn skipping_the_surface_left_changes_no_pixel_of_the_sphereflake() {
        let (s, t) = sphereflake_pixels_agree(|ws| ws.test_the_surface_left = true);
        assert_eq!(s.shadow_rays, t.shadow_rays, "the same shadow rays");
        assert_eq!(s.shadow_blocked, t.shadow_blocked, "the same verdicts");
        let sphere = SurfaceKind::Sphere.index();
        let (ts, tt) = (
            s.per_kind[sphere].shadow_tests,
            t.per_kind[sphere].shadow_tests,
        );
        assert!(
            tt - ts > 300,
            "sphere shadow tests {ts} skipping against {tt} testing"
        );
        assert_eq!(
            s.reflected_rays, t.reflected_rays,
            "the same reflected rays"
        );
        let (ns, nt) = (s.per_kind[sphere].tests, t.per_kind[sphere].tests);
        assert!(
            nt - ns > 300 && nt - ns <= s.reflected_rays,
            "sphere tests {ns} skipping against {nt} testing, {} reflected rays",
            s.reflected_rays
        );
    }

    /// The shadow cache changes no pixel of an SPD scene (balls-s2: 91 spheres over a floor
    /// polygon, three lights, mirror spheres), and it is used: most blocked shadow rays are
    /// answered by the cached blocker without a traversal.
    #[test]
    fn shadow_cache_changes_no_pixel_of_the_sphereflake() {
        let (c, u) = sphereflake_pixels_agree(|ws| ws.shadow_cache_off = true);
        assert_eq!(c.shadow_rays, u.shadow_rays, "the same shadow rays");
        assert_eq!(c.shadow_blocked, u.shadow_blocked, "the same verdicts");
        assert_eq!(u.shadow_cache_hits, 0, "no cache, no hit");
        assert!(
            c.shadow_cache_hits * 2 > c.shadow_blocked && c.shadow_blocked > 100,
            "the cache answers most blocked rays: {} of {}",
            c.shadow_cache_hits,
            c.shadow_blocked
        );
        assert!(
            c.bvh_node_visits < u.bvh_node_visits,
            "and saves traversals: {} against {}",
            c.bvh_node_visits,
            u.bvh_node_visits
        );
    }
}

//! [`Transformed`]: a surface placed in the world by an affine map. Shapes never see world
//! space (pbrt-v4 `TransformedPrimitive`).

use std::ops::Range;

use super::{Hit, Surface, SurfaceGeometry, SurfaceKind};
use crate::geometry::{Bounds3, Ray, Transform};
use crate::workspace::Workspace;

/// `inner`, seen through `world_from_object`. Rays are mapped to object space without
/// normalising the direction, so `t` is the same in both spaces.
#[derive(Debug)]
pub struct Transformed<S> {
    inner: S,
    world_from_object: Transform,
    object_from_world: Transform,
    bounds: Option<Bounds3>,
}

impl<S: Surface> Transformed<S> {
    /// Places `inner` with `world_from_object`.
    pub fn new(inner: S, world_from_object: Transform) -> Self {
        let bounds = inner.bounds().map(|b| world_from_object.apply_bounds(&b));
        Transformed {
            object_from_world: world_from_object.inverse(),
            world_from_object,
            inner,
            bounds,
        }
    }
}

impl<S: Surface> Surface for Transformed<S> {
    fn kind(&self) -> SurfaceKind {
        self.inner.kind()
    }

    fn bounds(&self) -> Option<Bounds3> {
        self.bounds
    }

    fn intersect(&self, ray: &Ray, t_range: Range<f64>, ws: &mut Workspace) -> Option<Hit> {
        let r = self.object_from_world.apply_ray(ray);
        self.inner.intersect(&r, t_range, ws)
    }

    fn occluded(&self, ray: &Ray, t_range: Range<f64>, ws: &mut Workspace) -> bool {
        let r = self.object_from_world.apply_ray(ray);
        self.inner.occluded(&r, t_range, ws)
    }

    /// The inner surface's interval for the mapped ray (the map keeps `t`).
    fn hit_interval(&self, ray: &Ray) -> Option<Range<f64>> {
        self.inner
            .hit_interval(&self.object_from_world.apply_ray(ray))
    }

    /// An affine image of a convex body is convex, and `G(x) = F(M⁻¹(x − b))` is negative
    /// exactly inside it with `∇G = M⁻ᵀ∇F`: the normal [`Surface::shading`] gives below,
    /// `M⁻ᵀn` normalised, points out of it as `n` did, whatever the sign of `det M`.
    fn convex(&self) -> bool {
        self.inner.convex()
    }

    fn shading(&self, hit: &Hit) -> SurfaceGeometry {
        let g = self.inner.shading(hit);
        let (p, p_err) = self.world_from_object.apply_point_with_err(g.p, g.p_err);
        let normal = g
            .normal
            .map(|n| self.world_from_object.apply_normal(n).normalize());
        SurfaceGeometry {
            p,
            p_err,
            normal,
            uv: g.uv,
        }
    }
}

#[cfg(test)]
mod tests {
    use glam::{DAffine3, DMat3, DVec3};
    use rand::{Rng, SeedableRng};
    use rand_chacha::ChaCha8Rng;

    use super::*;
    use crate::surface::{Implicit, Sphere, leaving_ray_misses};

    /// A unit sphere under a map with a reflection, an uneven scale, a rotation and a shift
    /// (an ellipsoid) is still `convex`, its shading normal points out of it, and a ray
    /// leaving it along that normal from just outside never meets it.
    #[test]
    fn a_transformed_convex_surface_is_convex_with_the_outward_normal() {
        let m = DMat3::from_rotation_z(0.7)
            * DMat3::from_rotation_x(-0.4)
            * DMat3::from_diagonal(DVec3::new(-1.5, 2.0, 0.5));
        let shift = DVec3::new(3.0, -1.0, 2.0);
        let place = Transform::new(DAffine3::from_mat3_translation(m, shift)).expect("invertible");
        let s = Transformed::new(Implicit::new(Sphere::new(DVec3::ZERO, 1.0), None), place);
        assert!(s.convex(), "an ellipsoid is convex");
        let mut rng = ChaCha8Rng::seed_from_u64(8);
        let mut ws = Workspace::new();
        let mut rays = 0;
        for _ in 0..3000 {
            let q = DVec3::new(
                rng.gen_range(-1.0..1.0),
                rng.gen_range(-1.0..1.0),
                rng.gen_range(-1.0..1.0),
            )
            .normalize();
            let hit = Hit {
                t: 1.0,
                local: q,
                uv: None,
                tag: 0,
            };
            let g = s.shading(&hit);
            let n = g.normal.expect("a regular point");
            // Outward: a step along n leaves the ellipsoid (the object-space point's norm grows).
            let out = place.inverse().apply_point(g.p + n * 1e-3);
            assert!(out.length() > 1.0, "normal {n} at {} points inwards", g.p);
            rays += usize::from(leaving_ray_misses(&s, g.p + n * 1e-9, n, &mut rng, &mut ws));
        }
        assert!(rays > 1000, "{rays} rays");
    }
}

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

//! Rays, bounding boxes, affine transforms and polygon normals, with the floating-point error bounds that keep
//! spawned rays off the surface they leave (pbrt-v4 §6.8, "Managing Rounding Error").

mod bounds;
mod ray;
mod transform;

pub use bounds::{Bounds3, SlabRay};
pub use ray::{Ray, offset_ray_origin};
pub use transform::Transform;

/// `γ(n) = n·u/(1 − n·u)` with `u = ε/2`: the relative error bound of `n` chained
/// floating-point operations (Higham §3.1; re-exported from `poly`).
pub use poly::gamma;

use glam::DVec3;

/// The unit normal of a planar polygon (Newell's method), `None` when the area is zero.
pub(crate) fn polygon_normal(vertices: &[DVec3]) -> Option<DVec3> {
    let mut n = DVec3::ZERO;
    for (i, a) in vertices.iter().enumerate() {
        let b = vertices[(i + 1) % vertices.len()];
        n += a.cross(b);
    }
    let len = n.length();
    (len > 0.0 && len.is_finite()).then(|| n / len)
}

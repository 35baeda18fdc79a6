//! Rays, bounding boxes, affine transforms and polygon normals, with the floating-point error bounds that keep
//! spawned rays off the surface they leave (pbrt-v4 §6.8, "Managing Rounding Error").

mod bounds;
mod bounds4;
mod ray;
mod transform;

pub use bounds::{Bounds3, SlabRay};
pub use bounds4::Bounds4;
pub use ray::{Ray, offset_ray_origin};
pub use transform::Transform;

/// `γ(n) = n·u/(1 − n·u)` with `u = ε/2`: the relative error bound of `n` chained
/// floating-point operations (Higham §3.1; re-exported from `poly`).
pub use poly::gamma;

use glam::DVec3;

/// The unit vector along `v`, `None` for the zero vector or a non-finite one. `v` is first
/// divided by its largest component, so a direction whose squared length under- or overflows
/// (`(0, 0, 1e-200)`, `(1e200, 0, 1e200)`) is a direction like any other (issue 13, item 11).
pub fn unit(v: DVec3) -> Option<DVec3> {
    let largest = v.abs().max_element();
    if !(largest > 0.0 && largest.is_finite()) {
        return None;
    }
    let u = (v / largest).normalize();
    u.is_finite().then_some(u)
}

/// The unit normal of a planar polygon (Newell's method), `None` when the area is zero or
/// the corners' differences overflow. The corners are taken relative to the first and
/// scaled by the largest difference before the cross products, so a polygon with corners
/// of size 1e-200 or 1e200 is not called degenerate because `|n|²` under- or overflows.
pub(crate) fn polygon_normal(vertices: &[DVec3]) -> Option<DVec3> {
    let origin = *vertices.first()?;
    let scale = vertices
        .iter()
        .map(|v| (*v - origin).abs().max_element())
        .fold(0.0, f64::max);
    if !(scale > 0.0 && scale.is_finite()) {
        return None;
    }
    let local = |v: DVec3| (v - origin) / scale;
    let mut n = DVec3::ZERO;
    for (i, a) in vertices.iter().enumerate() {
        let b = vertices[(i + 1) % vertices.len()];
        n += local(*a).cross(local(b));
    }
    unit(n)
}

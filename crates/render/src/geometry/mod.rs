//! Rays, bounding boxes and affine transforms, with the floating-point error bounds that keep
//! spawned rays off the surface they leave (pbrt-v4 §6.8, "Managing Rounding Error").

mod bounds;
mod ray;
mod transform;

pub use bounds::Bounds3;
pub use ray::{Ray, offset_ray_origin};
pub use transform::Transform;

/// `γ(n) = n·u/(1 − n·u)` with `u = ε/2`: the relative error bound of `n` chained
/// floating-point operations (Higham §3.1; re-exported from `poly`).
pub use poly::gamma;

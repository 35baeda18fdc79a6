//! [`Transform`]: affine maps with their inverse, named `dst_from_src`.

use glam::{DAffine3, DMat3, DVec3};

use super::{Bounds3, Ray, gamma};
use crate::scene::ObjectTransform;

/// An affine map with its inverse and the matrix that maps normals (the inverse transpose of
/// the linear part). Name values `world_from_object` so compositions read right.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Transform {
    m: DAffine3,
    inv: DAffine3,
    normal_m: DMat3,
}

impl Transform {
    /// The identity.
    pub const IDENTITY: Transform = Transform {
        m: DAffine3::IDENTITY,
        inv: DAffine3::IDENTITY,
        normal_m: DMat3::IDENTITY,
    };

    /// The map `m`; `None` when it is singular or not finite.
    pub fn new(m: DAffine3) -> Option<Self> {
        let det = m.matrix3.determinant();
        if !(det.is_finite() && det != 0.0 && m.translation.is_finite()) {
            return None;
        }
        let inv = m.inverse();
        Some(Transform {
            m,
            inv,
            normal_m: inv.matrix3.transpose(),
        })
    }

    /// `world_from_object` for a scene object: `T(translate)·Rz·Ry·Rx·S(scale)`.
    pub fn from_object(t: &ObjectTransform) -> Option<Self> {
        let r = t.rotate_deg * (std::f64::consts::PI / 180.0);
        let rot =
            DMat3::from_rotation_z(r.z) * DMat3::from_rotation_y(r.y) * DMat3::from_rotation_x(r.x);
        let m = DAffine3::from_mat3_translation(rot * DMat3::from_diagonal(t.scale), t.translate);
        Transform::new(m)
    }

    /// A rigid map taking the origin to `origin` and the `z` axis to the unit vector along
    /// `axis` (non-zero), used to place canonical shapes (torus).
    pub fn frame(origin: DVec3, axis: DVec3) -> Option<Self> {
        let z = axis.normalize();
        if !z.is_finite() {
            return None;
        }
        let (x, y) = z.any_orthonormal_pair();
        Transform::new(DAffine3::from_mat3_translation(
            DMat3::from_cols(x, y, z),
            origin,
        ))
    }

    /// `self ∘ other`: apply `other` first.
    pub fn compose(&self, other: &Transform) -> Option<Transform> {
        Transform::new(self.m * other.m)
    }

    /// The inverse map.
    pub fn inverse(&self) -> Transform {
        Transform {
            m: self.inv,
            inv: self.m,
            normal_m: self.m.matrix3.transpose(),
        }
    }

    /// True when this is (exactly) the identity.
    pub fn is_identity(&self) -> bool {
        self.m == DAffine3::IDENTITY
    }

    /// The image of a point.
    pub fn apply_point(&self, p: DVec3) -> DVec3 {
        self.m.transform_point3(p)
    }

    /// The image of a vector (no translation).
    pub fn apply_vector(&self, v: DVec3) -> DVec3 {
        self.m.transform_vector3(v)
    }

    /// The image of a normal (inverse transpose), not normalised.
    pub fn apply_normal(&self, n: DVec3) -> DVec3 {
        self.normal_m * n
    }

    /// The image of a ray; `t` keeps its meaning because the direction is not normalised.
    pub fn apply_ray(&self, r: &Ray) -> Ray {
        Ray::new(self.apply_point(r.origin), self.apply_vector(r.dir))
    }

    /// The image of a point known to within the componentwise error box `p_err`, and the
    /// error box of the result: `|M|·p_err·(1 + γ(3)) + γ(3)·(|M|·|p| + |b|)` (pbrt-v4
    /// §6.8.6, transforming points with error).
    pub fn apply_point_with_err(&self, p: DVec3, p_err: DVec3) -> (DVec3, DVec3) {
        let abs = DMat3::from_cols(
            self.m.matrix3.x_axis.abs(),
            self.m.matrix3.y_axis.abs(),
            self.m.matrix3.z_axis.abs(),
        );
        let q = self.apply_point(p);
        let err =
            abs * p_err * (1.0 + gamma(3)) + (abs * p.abs() + self.m.translation.abs()) * gamma(3);
        (q, err)
    }

    /// The box holding the image of `b`.
    pub fn apply_bounds(&self, b: &Bounds3) -> Bounds3 {
        b.transformed(self)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn object_transform_order_is_scale_rotate_translate() {
        let t = ObjectTransform {
            translate: DVec3::new(10.0, 0.0, 0.0),
            rotate_deg: DVec3::new(0.0, 0.0, 90.0),
            scale: DVec3::new(2.0, 1.0, 1.0),
        };
        let m = Transform::from_object(&t).unwrap();
        let p = m.apply_point(DVec3::X);
        // scale → (2,0,0), rotate 90° about z → (0,2,0), translate → (10,2,0)
        assert!((p - DVec3::new(10.0, 2.0, 0.0)).length() < 1e-12, "{p}");
        let back = m.inverse().apply_point(p);
        assert!((back - DVec3::X).length() < 1e-12, "inverse: {back}");
        // Normals of the plane x = 1 (object) stay perpendicular to the image plane.
        let n = m.apply_normal(DVec3::X);
        let tangent = m.apply_vector(DVec3::Y);
        assert!(
            n.dot(tangent).abs() < 1e-12,
            "normal ⟂ tangent after the map"
        );
        assert!(
            Transform::new(DAffine3::from_scale(DVec3::new(1.0, 0.0, 1.0))).is_none(),
            "singular"
        );
    }
}

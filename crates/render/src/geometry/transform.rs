//! [`Transform`]: affine maps with their inverse, named `dst_from_src`.

use glam::{DAffine3, DMat3, DVec3};

use super::{Bounds3, Ray, gamma};

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

    /// A rigid map taking the origin to `origin` and the `z` axis to the unit vector along
    /// `axis` (non-zero, any finite length: see [`super::unit`]), used to place canonical
    /// shapes (torus, cone).
    pub fn frame(origin: DVec3, axis: DVec3) -> Option<Self> {
        let z = super::unit(axis)?;
        let (x, y) = z.any_orthonormal_pair();
        Transform::new(DAffine3::from_mat3_translation(
            DMat3::from_cols(x, y, z),
            origin,
        ))
    }

    /// `self ∘ other`: apply `other` first. With an identity on either side the other map is
    /// returned as it is (the product would be the same matrix, its inverse recomputed): every
    /// object of an NFF file composes identities, and the inverse cost more than the parse of
    /// its line (issue 12).
    pub fn compose(&self, other: &Transform) -> Option<Transform> {
        if self.is_identity() {
            return Some(*other);
        }
        if other.is_identity() {
            return Some(*self);
        }
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

    /// Composing with the identity, now a shortcut (issue 12), gives the map the product
    /// gives, on either side.
    #[test]
    fn compose_with_the_identity_is_the_product() {
        let m = DAffine3::from_mat3_translation(
            DMat3::from_rotation_z(0.3) * DMat3::from_diagonal(DVec3::new(1.0, 2.0, 0.5)),
            DVec3::new(1.0, -2.0, 3.0),
        );
        let t = Transform::new(m).expect("invertible");
        let id = Transform::IDENTITY;
        let product = Transform::new(DAffine3::IDENTITY * m).expect("invertible");
        assert_eq!(id.compose(&t), Some(product), "identity first");
        let product = Transform::new(m * DAffine3::IDENTITY).expect("invertible");
        assert_eq!(t.compose(&id), Some(product), "identity second");
    }
}

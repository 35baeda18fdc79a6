//! [`Camera`]: maps image positions to primary rays, for both of the scene's camera forms.

use glam::DVec3;

use crate::geometry::{Ray, unit};
use crate::scene::{CameraSpec, LookAtCamera, StamCamera};

/// A pinhole camera: the eye and the image rectangle in world space.
///
/// Image coordinates are continuous pixel units: `(0, 0)` is the top-left corner of the
/// image, `(w, h)` the bottom-right, and pixel `(i, j)` covers `[i, i+1) × [j, j+1)`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Camera {
    eye: DVec3,
    /// World point of the image's top-left corner.
    top_left: DVec3,
    /// World step for one pixel to the right.
    step_x: DVec3,
    /// World step for one pixel down.
    step_y: DVec3,
}

impl Camera {
    /// The camera of `spec` for a `width × height` image (both positive; the spec already
    /// validated by [`Scene::validate`](crate::Scene::validate)).
    pub fn new(spec: &CameraSpec, width: u32, height: u32) -> Self {
        match spec {
            CameraSpec::LookAt(c) => Self::look_at(c, width, height),
            CameraSpec::Stam(c) => Self::stam(c, width, height),
        }
    }

    /// Eye / look-at / up with a vertical field of view; square pixels.
    fn look_at(c: &LookAtCamera, width: u32, height: u32) -> Self {
        // Where squaring overflows (a LookAt 1e308 away, a long Up), the unit vectors come
        // from `unit`, which scales first; the scene's check refused the directions that have
        // none. Otherwise the plain normalisation, as before (the same rays, bit for bit).
        let normalised = |v: DVec3| {
            let u = v.normalize();
            (u.is_finite() && u.length_squared() > 0.5).then_some(u)
        };
        let forward = normalised(c.look_at - c.eye)
            .or_else(|| unit(c.look_at - c.eye))
            .unwrap_or(DVec3::Y);
        let right = normalised(forward.cross(c.up))
            .or_else(|| unit(forward.cross(unit(c.up)?)))
            .unwrap_or(DVec3::X);
        let up = right.cross(forward);
        let half_h = (c.view_field_deg.to_radians() / 2.0).tan();
        let half_w = half_h * f64::from(width) / f64::from(height);
        let top_left = c.eye + forward - right * half_w + up * half_h;
        Camera {
            eye: c.eye,
            top_left,
            step_x: right * (2.0 * half_w / f64::from(width)),
            step_y: -up * (2.0 * half_h / f64::from(height)),
        }
    }

    /// Stam's `ProjectPlane` (Annexe B, `ray0.c`): rotation `R` from the angles
    /// `(balance, left_right, top_bottom)`, eye at `center + (distance + focal)·R₃`, and a
    /// square window of half-side `bc = focal·tan(view_field/2)/√2` (so `view_field` is the
    /// window's diagonal opening angle) centred at `center + distance·R₃`, spanned by `R₁`
    /// (image right) and `R₂` (image up). The window fills the image whatever its aspect,
    /// as in Stam's program.
    fn stam(c: &StamCamera, width: u32, height: u32) -> Self {
        let deg = std::f64::consts::PI / 180.0;
        let bc = c.focal * (c.view_field_deg / 2.0 * deg).tan() / 2f64.sqrt();
        let (s1, c1) = (c.rotation_deg.x * deg).sin_cos(); // balance
        let (s3, c3) = (-c.rotation_deg.y * deg).sin_cos(); // left-right
        let (s2, c2) = (-c.rotation_deg.z * deg).sin_cos(); // top-bottom
        let col1 = DVec3::new(c1 * c3 + s1 * s2 * s3, c2 * s1, -c1 * s3 + c3 * s1 * s2);
        let col2 = DVec3::new(-c3 * s1 + c1 * s2 * s3, c1 * c2, s1 * s3 + c1 * c3 * s2);
        let col3 = DVec3::new(c2 * s3, -s2, c2 * c3);
        let eye = c.center + col3 * (c.distance + c.focal);
        let top_left = c.center + col3 * c.distance - col1 * bc + col2 * bc;
        Camera {
            eye,
            top_left,
            step_x: col1 * (2.0 * bc / f64::from(width)),
            step_y: -col2 * (2.0 * bc / f64::from(height)),
        }
    }

    /// The eye position.
    pub fn eye(&self) -> DVec3 {
        self.eye
    }

    /// The primary ray through image position `(x, y)` (pixel units, see [`Camera`]), with a
    /// unit direction so that `t` is the distance from the eye.
    pub fn ray(&self, x: f64, y: f64) -> Ray {
        let target = self.top_left + self.step_x * x + self.step_y * y;
        Ray::new(self.eye, (target - self.eye).normalize())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn look_at_centre_ray_points_at_target() {
        let spec = CameraSpec::LookAt(LookAtCamera {
            eye: DVec3::new(0.0, -8.0, 5.0),
            look_at: DVec3::ZERO,
            up: DVec3::Z,
            view_field_deg: 50.0,
        });
        let cam = Camera::new(&spec, 200, 100);
        let r = cam.ray(100.0, 50.0);
        let expect = (DVec3::ZERO - DVec3::new(0.0, -8.0, 5.0)).normalize();
        assert!((r.dir - expect).length() < 1e-12, "centre ray {:?}", r.dir);
        // Top edge centre is 25° above the axis (vertical field 50°).
        let top = cam.ray(100.0, 0.0);
        let angle = top.dir.dot(expect).acos().to_degrees();
        assert!((angle - 25.0).abs() < 1e-9, "half field {angle}");
        // Image right is +x for this camera.
        assert!(cam.ray(200.0, 50.0).dir.x > 0.0, "right is +x");
    }

    #[test]
    fn stam_camera_without_rotation_looks_down_z() {
        let spec = CameraSpec::Stam(StamCamera {
            focal: 2.0,
            distance: 8.0,
            view_field_deg: 60.0,
            rotation_deg: DVec3::ZERO,
            center: DVec3::ZERO,
        });
        let cam = Camera::new(&spec, 100, 100);
        assert!(
            (cam.eye() - DVec3::new(0.0, 0.0, 10.0)).length() < 1e-12,
            "eye"
        );
        let r = cam.ray(50.0, 50.0);
        assert!((r.dir - DVec3::NEG_Z).length() < 1e-12, "axis {:?}", r.dir);
        // The corner ray makes half the diagonal field with the axis.
        let corner = cam.ray(0.0, 0.0);
        let angle = corner.dir.dot(DVec3::NEG_Z).acos().to_degrees();
        assert!((angle - 30.0).abs() < 1e-9, "diagonal half-angle {angle}");
        assert!(
            corner.dir.x < 0.0 && corner.dir.y > 0.0,
            "top-left is −x, +y"
        );
    }
}

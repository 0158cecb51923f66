//! The camera and the matrices the shaders use (wgpu clip space: depth in
//! `[0, 1]`, y up).

use nalgebra::{Isometry3, Matrix4, Point3, Vector3};

use super::error::RenderError;

/// How the camera projects.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Projection {
    /// A pinhole camera with a vertical field of view in degrees, `(0, 180)`.
    Perspective {
        /// Vertical field of view, degrees.
        fov_y_degrees: f64,
    },
    /// Parallel projection showing `height` metres vertically (the thesis'
    /// force figures use it).
    Orthographic {
        /// Visible height, m.
        height: f64,
    },
}

/// A camera looking from `eye` at `target`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Camera {
    /// Eye position, world, m.
    pub eye: Point3<f64>,
    /// Point looked at, world, m.
    pub target: Point3<f64>,
    /// Up direction (need not be orthogonal to the view; default +y).
    pub up: Vector3<f64>,
    /// Perspective or orthographic.
    pub projection: Projection,
    /// Near clipping distance, m (> 0).
    pub near: f64,
    /// Far clipping distance, m (> near).
    pub far: f64,
}

impl Camera {
    /// A perspective camera with a vertical field of view of
    /// `fov_y_degrees`, near 0.05 m, far 1000 m.
    pub fn perspective(eye: Point3<f64>, target: Point3<f64>, fov_y_degrees: f64) -> Self {
        Self {
            eye,
            target,
            up: Vector3::y(),
            projection: Projection::Perspective { fov_y_degrees },
            near: 0.05,
            far: 1000.0,
        }
    }

    /// An orthographic camera showing `height` metres vertically.
    pub fn orthographic(eye: Point3<f64>, target: Point3<f64>, height: f64) -> Self {
        Self {
            projection: Projection::Orthographic { height },
            ..Self::perspective(eye, target, 45.0)
        }
    }

    /// Checks that the camera can make an image.
    pub fn validate(&self) -> Result<(), RenderError> {
        let bad = |detail: String| RenderError::Scene {
            what: "camera".into(),
            detail,
        };
        let finite = |v: &[f64]| v.iter().all(|c| c.is_finite());
        if !finite(self.eye.coords.as_slice())
            || !finite(self.target.coords.as_slice())
            || !finite(self.up.as_slice())
        {
            return Err(bad("eye, target and up must be finite".into()));
        }
        let forward = self.target - self.eye;
        if forward.norm() < 1e-9 {
            return Err(bad(format!(
                "eye and target coincide at {:?}",
                self.eye.coords.as_slice()
            )));
        }
        if forward.cross(&self.up).norm() < 1e-9 * forward.norm() * self.up.norm().max(1e-300) {
            return Err(bad("the up vector is parallel to the view direction".into()));
        }
        if !(self.near > 0.0 && self.far > self.near && self.far.is_finite()) {
            return Err(bad(format!(
                "near = {} and far = {} must satisfy 0 < near < far < ∞",
                self.near, self.far
            )));
        }
        match self.projection {
            Projection::Perspective { fov_y_degrees } if !(fov_y_degrees > 0.0 && fov_y_degrees < 180.0) => {
                Err(bad(format!(
                    "fov_y_degrees = {fov_y_degrees} is outside (0, 180)"
                )))
            }
            Projection::Orthographic { height } if !(height > 0.0 && height.is_finite()) => {
                Err(bad(format!("orthographic height = {height} must be positive")))
            }
            _ => Ok(()),
        }
    }

    /// World-to-view transform (right-handed, looking down −z).
    pub fn view(&self) -> Isometry3<f64> {
        Isometry3::look_at_rh(&self.eye, &self.target, &self.up)
    }

    /// View-to-clip matrix for an image of `aspect` = width/height, depth
    /// mapped to `[0, 1]`.
    pub fn projection_matrix(&self, aspect: f64) -> Matrix4<f64> {
        let (n, f) = (self.near, self.far);
        match self.projection {
            Projection::Perspective { fov_y_degrees } => {
                let t = 1.0 / (0.5 * fov_y_degrees.to_radians()).tan();
                #[rustfmt::skip]
                let m = Matrix4::new(
                    t / aspect, 0.0, 0.0, 0.0,
                    0.0, t, 0.0, 0.0,
                    0.0, 0.0, f / (n - f), n * f / (n - f),
                    0.0, 0.0, -1.0, 0.0,
                );
                m
            }
            Projection::Orthographic { height } => {
                let (w, h) = (height * aspect, height);
                #[rustfmt::skip]
                let m = Matrix4::new(
                    2.0 / w, 0.0, 0.0, 0.0,
                    0.0, 2.0 / h, 0.0, 0.0,
                    0.0, 0.0, -1.0 / (f - n), -n / (f - n),
                    0.0, 0.0, 0.0, 1.0,
                );
                m
            }
        }
    }

    /// World-to-clip matrix for an image of `aspect` = width/height.
    pub fn view_projection(&self, aspect: f64) -> Matrix4<f64> {
        self.projection_matrix(aspect) * self.view().to_homogeneous()
    }

    /// Whether the projection is orthographic.
    pub fn is_orthographic(&self) -> bool {
        matches!(self.projection, Projection::Orthographic { .. })
    }

    /// Unit view direction, eye to target.
    pub fn forward(&self) -> Vector3<f64> {
        (self.target - self.eye).normalize()
    }
}

/// A column-major `f32` copy of `m`, as WGSL's `mat4x4<f32>` expects.
pub(crate) fn to_gpu(m: &Matrix4<f64>) -> [[f32; 4]; 4] {
    std::array::from_fn(|c| std::array::from_fn(|r| m[(r, c)] as f32))
}

/// A light-space orthographic view-projection for a directional light
/// travelling along `-towards_light`, covering the sphere (`centre`,
/// `radius`) with depth in `[0, 1]`.
pub(crate) fn light_view_projection(
    towards_light: &Vector3<f64>,
    centre: &Point3<f64>,
    radius: f64,
) -> Matrix4<f64> {
    let l = towards_light.normalize();
    let eye = centre + l * (2.0 * radius);
    let up = if l.y.abs() > 0.99 {
        Vector3::z()
    } else {
        Vector3::y()
    };
    let view = Isometry3::look_at_rh(&eye, centre, &up).to_homogeneous();
    let (n, f) = (0.0, 4.0 * radius);
    let s = 1.0 / radius;
    #[rustfmt::skip]
    let proj = Matrix4::new(
        s, 0.0, 0.0, 0.0,
        0.0, s, 0.0, 0.0,
        0.0, 0.0, -1.0 / (f - n), -n / (f - n),
        0.0, 0.0, 0.0, 1.0,
    );
    proj * view
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn target_projects_to_the_centre_at_mid_depth_range() {
        let cam = Camera::perspective(Point3::new(3.0, 2.0, 5.0), Point3::new(0.0, 0.5, 0.0), 40.0);
        let m = cam.view_projection(16.0 / 9.0);
        let c = m * cam.target.to_homogeneous();
        let ndc = c.xyz() / c.w;
        assert!(ndc.x.abs() < 1e-12 && ndc.y.abs() < 1e-12);
        assert!(ndc.z > 0.0 && ndc.z < 1.0);
        // The near plane maps to 0, the far plane to 1.
        let d = cam.forward();
        for (dist, z) in [(cam.near, 0.0), (cam.far, 1.0)] {
            let p = cam.eye + d * dist;
            let c = m * p.to_homogeneous();
            assert!((c.z / c.w - z).abs() < 1e-9, "{dist}: {}", c.z / c.w);
        }
    }

    #[test]
    fn up_is_up_on_screen() {
        let cam = Camera::orthographic(Point3::new(0.0, 0.0, 5.0), Point3::origin(), 2.0);
        let m = cam.view_projection(1.0);
        let c = m * Point3::new(0.5, 0.5, 0.0).to_homogeneous();
        assert!((c.x - 0.5).abs() < 1e-12 && (c.y - 0.5).abs() < 1e-12);
    }
}

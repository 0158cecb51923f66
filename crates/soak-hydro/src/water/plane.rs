//! A plane surface, horizontal or tilted, with a uniform current or one
//! that changes linearly from place to place.

use nalgebra::{Matrix3, Point3, Vector3};
use serde::{Deserialize, Serialize};

use super::{Surface, SurfaceKind};
use crate::error::WaterError;

/// A plane surface `normal·p = offset`, horizontal unless tilted.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct Plane {
    /// Unit normal pointing up out of the water (`normal.y > 0`).
    pub normal: Vector3<f64>,
    /// `normal·p` on the surface, m.
    pub offset: f64,
    /// Uniform current, m/s.
    pub current: Vector3<f64>,
}

impl Plane {
    /// The horizontal plane `y = level` (m), still water.
    pub fn horizontal(level: f64) -> Self {
        Self {
            normal: Vector3::y(),
            offset: level,
            current: Vector3::zeros(),
        }
    }

    /// A plane through `point` (m) with the given up normal (normalised here).
    pub fn tilted(point: Point3<f64>, normal: Vector3<f64>) -> Result<Self, WaterError> {
        let n = normal.try_normalize(1e-12).ok_or(WaterError::PlaneNormal {
            normal: normal.into(),
        })?;
        if n.y <= 1e-6 || !n.iter().all(|c| c.is_finite()) || !point.iter().all(|c| c.is_finite()) {
            return Err(WaterError::PlaneNormal {
                normal: normal.into(),
            });
        }
        Ok(Self {
            normal: n,
            offset: n.dot(&point.coords),
            current: Vector3::zeros(),
        })
    }

    /// The same plane with a uniform current (m/s).
    pub fn with_current(mut self, current: Vector3<f64>) -> Self {
        self.current = current;
        self
    }

    /// The same plane with its current changing linearly over space: the
    /// fluid moves at `current + gradient (p − about)` at `p`, `gradient`
    /// the derivatives `∂u_i/∂p_j` (1/s, world axes) and `about` where the
    /// current is [`Plane::current`] (m).
    ///
    /// # Errors
    /// [`WaterError::Parameter`] naming the first entry of `gradient`
    /// (`flow gradient`), of `about` (`flow origin`) or of the plane's
    /// current (`current`) that is not finite.
    ///
    /// ```
    /// use nalgebra::{Matrix3, Point3, Vector3};
    /// use soak_hydro::{Plane, WaterError};
    ///
    /// // A shear, u_x = 0.1 y: two metres down, the water moves at 0.2 m/s toward −x.
    /// let shear = Matrix3::new(0.0, 0.1, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0);
    /// let flow = Plane::horizontal(0.0).with_gradient(shear, Point3::origin())?;
    /// # use soak_hydro::Surface;
    /// let u = flow.velocity(&Point3::new(0.0, -2.0, 0.0), 0.0);
    /// assert_eq!(u, Vector3::new(-0.2, 0.0, 0.0));
    ///
    /// let bad = Matrix3::from_element(f64::NAN);
    /// let e = Plane::horizontal(0.0).with_gradient(bad, Point3::origin()).unwrap_err();
    /// assert!(matches!(e, WaterError::Parameter { name: "flow gradient", .. }));
    /// # Ok::<(), WaterError>(())
    /// ```
    pub fn with_gradient(self, gradient: Matrix3<f64>, about: Point3<f64>) -> Result<FlowPlane, WaterError> {
        let named = [
            ("current", self.current.as_slice()),
            ("flow gradient", gradient.as_slice()),
            ("flow origin", about.coords.as_slice()),
        ];
        for (name, values) in named {
            if let Some(&value) = values.iter().find(|v| !v.is_finite()) {
                return Err(WaterError::Parameter { name, value });
            }
        }
        Ok(FlowPlane {
            plane: self,
            gradient,
            about,
        })
    }
}

/// A [`Plane`] whose fluid's velocity changes linearly over space (see
/// [`Plane::with_gradient`]): what a sea read as one plane over a body
/// hands the body's drag when the body is large enough against the waves
/// that the orbital velocity changes over it. Its surface and buoyancy are
/// the plane's.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct FlowPlane {
    /// The plane, its current at [`FlowPlane::about`].
    pub plane: Plane,
    /// `∂u_i/∂p_j`, 1/s, world axes.
    pub gradient: Matrix3<f64>,
    /// Where the current is the plane's own, m.
    pub about: Point3<f64>,
}

impl Surface for FlowPlane {
    fn height_bounds(&self, t: f64) -> Option<(f64, f64)> {
        self.plane.height_bounds(t)
    }
    fn as_any(&self) -> Option<&dyn std::any::Any> {
        Some(self)
    }
    fn height(&self, x: f64, z: f64, t: f64) -> f64 {
        self.plane.height(x, z, t)
    }
    fn slope(&self, x: f64, z: f64, t: f64, hint: &[f64; 2]) -> [f64; 2] {
        self.plane.slope(x, z, t, hint)
    }
    fn velocity(&self, p: &Point3<f64>, _t: f64) -> Vector3<f64> {
        self.plane.current + self.gradient * (p - self.about)
    }
    fn kind(&self, t: f64) -> SurfaceKind {
        self.plane.kind(t)
    }
}

impl Surface for Plane {
    fn height_bounds(&self, _t: f64) -> Option<(f64, f64)> {
        (self.normal.x == 0.0 && self.normal.z == 0.0).then_some((self.offset, self.offset))
    }
    fn as_any(&self) -> Option<&dyn std::any::Any> {
        Some(self)
    }
    fn height(&self, x: f64, z: f64, _t: f64) -> f64 {
        (self.offset - self.normal.x * x - self.normal.z * z) / self.normal.y
    }
    fn slope(&self, _x: f64, _z: f64, _t: f64, _hint: &[f64; 2]) -> [f64; 2] {
        [-self.normal.x / self.normal.y, -self.normal.z / self.normal.y]
    }
    fn velocity(&self, _p: &Point3<f64>, _t: f64) -> Vector3<f64> {
        self.current
    }
    fn kind(&self, _t: f64) -> SurfaceKind {
        SurfaceKind::Plane {
            normal: self.normal,
            offset: self.offset,
        }
    }
}

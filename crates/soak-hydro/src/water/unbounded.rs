//! A fluid without a free surface (air around a balloon).

use nalgebra::{Point3, Vector3};
use serde::{Deserialize, Serialize};

use super::{Surface, SurfaceKind};

/// A fluid without a free surface: bodies are wholly immersed (air).
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct Unbounded {
    /// Uniform wind or current, m/s.
    pub current: [f64; 3],
}

impl Surface for Unbounded {
    fn height_bounds(&self, _t: f64) -> Option<(f64, f64)> {
        Some((f64::INFINITY, f64::INFINITY))
    }
    fn as_any(&self) -> Option<&dyn std::any::Any> {
        Some(self)
    }
    fn height(&self, _x: f64, _z: f64, _t: f64) -> f64 {
        f64::INFINITY
    }
    fn slope(&self, _x: f64, _z: f64, _t: f64, _hint: &[f64; 2]) -> [f64; 2] {
        [0.0, 0.0]
    }
    fn velocity(&self, _p: &Point3<f64>, _t: f64) -> Vector3<f64> {
        Vector3::from(self.current)
    }
    fn kind(&self, _t: f64) -> SurfaceKind {
        SurfaceKind::Unbounded
    }
}

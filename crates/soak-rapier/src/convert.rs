//! Conversions between rapier3d's glam (f32) math and soak's nalgebra (f64).

use nalgebra::{Isometry3, Point3, Quaternion, Translation3, UnitQuaternion, Vector3};
use rapier3d::math::{Pose, Rotation, Vector};

/// A rapier vector as f64.
#[inline]
pub fn vector(v: Vector) -> Vector3<f64> {
    Vector3::new(v.x as f64, v.y as f64, v.z as f64)
}

/// A point or vector as a rapier vector (f32).
#[inline]
pub fn to_vector(v: &Vector3<f64>) -> Vector {
    Vector::new(v.x as f32, v.y as f32, v.z as f32)
}

/// A point as a rapier vector (f32).
#[inline]
pub fn point_to_vector(p: &Point3<f64>) -> Vector {
    Vector::new(p.x as f32, p.y as f32, p.z as f32)
}

/// A rapier rotation as f64.
#[inline]
pub fn rotation(q: Rotation) -> UnitQuaternion<f64> {
    UnitQuaternion::from_quaternion(Quaternion::new(q.w as f64, q.x as f64, q.y as f64, q.z as f64))
}

/// An f64 rotation as a rapier rotation.
#[inline]
pub fn to_rotation(q: &UnitQuaternion<f64>) -> Rotation {
    Rotation::from_xyzw(q.i as f32, q.j as f32, q.k as f32, q.w as f32).normalize()
}

/// A rapier pose as an f64 isometry.
#[inline]
pub fn pose(p: &Pose) -> Isometry3<f64> {
    Isometry3::from_parts(Translation3::from(vector(p.translation)), rotation(p.rotation))
}

/// An f64 isometry as a rapier pose.
#[inline]
pub fn to_pose(p: &Isometry3<f64>) -> Pose {
    Pose::from_parts(to_vector(&p.translation.vector), to_rotation(&p.rotation))
}

//! The viewer's camera: orbiting a target, panned and zoomed with the
//! mouse, and the ray under the cursor for picking.

use nalgebra::{Point3, Vector3};
use soak_shade::render::Camera;

/// Vertical field of view of the viewer, degrees (that of the frames
/// [`SceneRenderer`](crate::SceneRenderer) frames by itself).
pub(crate) const FOV_Y_DEGREES: f64 = 40.0;

/// A camera at `distance` from `target`, turned by `yaw` about the
/// vertical and raised by `pitch` (rad).
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Orbit {
    pub target: Point3<f64>,
    pub distance: f64,
    pub yaw: f64,
    pub pitch: f64,
}

/// Radians per pixel dragged.
const TURN: f64 = 0.005;
/// Steepest pitch, rad (short of straight down or up).
const STEEPEST: f64 = 1.55;

impl Orbit {
    /// The orbit that sees `target` from `eye`.
    pub fn looking(eye: Point3<f64>, target: Point3<f64>) -> Self {
        let d = eye - target;
        let distance = d.norm().max(1e-3);
        Self {
            target,
            distance,
            yaw: d.x.atan2(d.z),
            pitch: (d.y / distance).clamp(-1.0, 1.0).asin(),
        }
    }

    /// The eye, world, m.
    pub fn eye(&self) -> Point3<f64> {
        let (sy, cy) = self.yaw.sin_cos();
        let (sp, cp) = self.pitch.sin_cos();
        self.target + self.distance * Vector3::new(cp * sy, sp, cp * cy)
    }

    /// The renderer's camera.
    pub fn camera(&self) -> Camera {
        let mut camera = Camera::perspective(self.eye(), self.target, FOV_Y_DEGREES);
        camera.far = camera.far.max(20.0 * self.distance);
        camera.near = camera.near.min(0.01 * self.distance).max(1e-4);
        camera
    }

    /// Turns about the target by a drag of `(dx, dy)` pixels.
    pub fn turn(&mut self, dx: f64, dy: f64) {
        self.yaw -= dx * TURN;
        self.pitch = (self.pitch + dy * TURN).clamp(-STEEPEST, STEEPEST);
    }

    /// Moves the target (and the eye with it) by a drag of `(dx, dy)`
    /// pixels in a window `height` pixels high: the point under the cursor
    /// at the target's depth follows it.
    pub fn pan(&mut self, dx: f64, dy: f64, height: f64) {
        let (right, up, _) = self.axes();
        let per_pixel = 2.0 * self.distance * (0.5 * FOV_Y_DEGREES.to_radians()).tan() / height.max(1.0);
        self.target += (-dx * right + dy * up) * per_pixel;
    }

    /// Zooms by `steps` wheel steps (positive: closer).
    pub fn zoom(&mut self, steps: f64) {
        self.distance = (self.distance * 0.88f64.powf(steps)).clamp(1e-3, 1e5);
    }

    /// Right, up and forward unit vectors of the view.
    fn axes(&self) -> (Vector3<f64>, Vector3<f64>, Vector3<f64>) {
        let forward = (self.target - self.eye()).normalize();
        let right = forward.cross(&Vector3::y()).normalize();
        let up = right.cross(&forward);
        (right, up, forward)
    }

    /// The ray from the eye through pixel `(x, y)` of a `width`×`height`
    /// window (y down): its origin and unit direction.
    pub fn ray(&self, x: f64, y: f64, width: f64, height: f64) -> (Point3<f64>, Vector3<f64>) {
        let (right, up, forward) = self.axes();
        let t = (0.5 * FOV_Y_DEGREES.to_radians()).tan();
        let aspect = width / height.max(1.0);
        let nx = 2.0 * (x + 0.5) / width.max(1.0) - 1.0;
        let ny = 1.0 - 2.0 * (y + 0.5) / height.max(1.0);
        let direction = (forward + right * (nx * t * aspect) + up * (ny * t)).normalize();
        (self.eye(), direction)
    }
}

/// The nearest of `spheres` (centre, radius) the ray from `origin` along
/// the unit `direction` enters or starts inside, by index.
pub(crate) fn pick(
    origin: &Point3<f64>,
    direction: &Vector3<f64>,
    spheres: &[(Point3<f64>, f64)],
) -> Option<usize> {
    spheres
        .iter()
        .enumerate()
        .filter_map(|(i, (c, r))| {
            let oc = origin - c;
            let b = oc.dot(direction);
            let disc = b * b - (oc.norm_squared() - r * r);
            if disc < 0.0 {
                return None;
            }
            let root = disc.sqrt();
            let t = if -b - root >= 0.0 { -b - root } else { -b + root };
            (t >= 0.0).then_some((i, t))
        })
        .min_by(|a, b| a.1.total_cmp(&b.1))
        .map(|(i, _)| i)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn an_orbit_sees_its_target_from_its_eye() {
        let eye = Point3::new(3.0, 2.0, -4.0);
        let target = Point3::new(0.5, -0.2, 1.0);
        let o = Orbit::looking(eye, target);
        assert!((o.eye() - eye).norm() < 1e-12);
        // A turn keeps the distance; a pan moves eye and target alike.
        let mut turned = o;
        turned.turn(40.0, -25.0);
        assert!(((turned.eye() - target).norm() - o.distance).abs() < 1e-12);
        let mut panned = o;
        panned.pan(10.0, 5.0, 500.0);
        assert!(((panned.eye() - panned.target) - (o.eye() - o.target)).norm() < 1e-12);
        let mut closer = o;
        closer.zoom(2.0);
        assert!(closer.distance < o.distance);
    }

    #[test]
    fn the_ray_through_the_centre_hits_the_target_and_picks_the_nearest() {
        let o = Orbit::looking(Point3::new(0.0, 0.0, 10.0), Point3::origin());
        let (origin, direction) = o.ray(399.5, 299.5, 800.0, 600.0);
        assert!((direction - Vector3::new(0.0, 0.0, -1.0)).norm() < 1e-12);
        let spheres = [
            (Point3::new(0.0, 0.0, -5.0), 1.0),
            (Point3::new(0.0, 0.0, 2.0), 0.5),
            (Point3::new(3.0, 0.0, 5.0), 1.0),
        ];
        assert_eq!(pick(&origin, &direction, &spheres), Some(1));
        // The top left corner misses them all.
        let (origin, direction) = o.ray(0.0, 0.0, 800.0, 600.0);
        assert_eq!(pick(&origin, &direction, &spheres), None);
    }
}

//! The frame of one evaluation (pose, centre of mass, the surface as a plane
//! where it is one) and the depth and texel reads built on it.

use nalgebra::{Matrix3, Point3, Vector3};
use soak_bake::Atlas;

use super::body_state::BodyState;
use crate::mass::MassProperties;
use crate::water::{SurfaceKind, Water};

/// Per-evaluation constants shared by the CPU paths.
pub(crate) struct Frame {
    /// For planar water, depth `d(x) = α + β·x` in object coordinates
    /// relative to the atlas origin, and the world up axis in object axes.
    pub local_plane: Option<(f64, Vector3<f64>, Vector3<f64>)>,
    pub rot: Matrix3<f64>,
    /// World position of the atlas origin.
    pub ow: Vector3<f64>,
    /// World centre of mass.
    pub com: Vector3<f64>,
    pub plane: Option<(Vector3<f64>, f64)>,
    pub texels: usize,
    /// The body's bounding radius, m: the scale of the sea's tile
    /// tolerance ([`SEA_TILE_TOLERANCE`](crate::SEA_TILE_TOLERANCE)).
    pub depth_scale: f64,
    /// Depth past which a texel counts as deep, `δ` of
    /// [`deep_volume`](super::deep_volume::deep_volume), m: [`deep_scale`].
    pub deep_scale: f64,
}

/// The depth `δ` past which a texel of `atlas` counts as deep under a
/// surface that is not a plane, m: the atlas' mean thickness `3V/A`
/// ([`Atlas::mean_thickness`]) or `g dt²`, the distance the velocity
/// gravity gives a body in a step of `dt` seconds carries it in the next,
/// the larger ([`deep_thickness`]), at most the
/// bounding radius (which it is where the samples enclose no volume). For
/// a compact body the thickness and the radius are alike; a rod's or a
/// slab's thickness is its width, not its length.
pub(crate) fn deep_scale(atlas: &Atlas, gravity: f64, dt: f64) -> f64 {
    let (t, r) = (atlas.mean_thickness(), atlas.bounding_radius());
    if t > 0.0 {
        deep_thickness(t, gravity, dt).min(r)
    } else {
        r
    }
}

/// The thickness `t` (m, positive) widened to `g dt²` (gravity in m/s²,
/// the step `dt` in s), where that is larger: the ramp of
/// [`deep_volume`](super::deep_volume::deep_volume) from the samples'
/// sum to the enclosed volume then spans more than a step's heave under
/// gravity, so that a step does not jump across it. A zero step (or one
/// whose `g dt²` is not finite) leaves the thickness.
pub(crate) fn deep_thickness(t: f64, gravity: f64, dt: f64) -> f64 {
    let drop = gravity * dt * dt;
    if drop.is_finite() { t.max(drop) } else { t }
}

impl Frame {
    pub(crate) fn new(
        atlas: &Atlas,
        water: &Water,
        state: &BodyState,
        mass: &MassProperties,
        t: f64,
        dt: f64,
    ) -> Self {
        let rot = state.pose.rotation.to_rotation_matrix().into_inner();
        let ow = (state.pose * atlas.origin()).coords;
        let com = (state.pose * mass.center_of_mass).coords;
        let plane = Self::surface_plane(water, t, &ow, atlas.bounding_radius());
        let local_plane = plane.map(|(n, c)| {
            let alpha = (c - n.dot(&ow)) / n.y;
            let beta = -(rot.transpose() * n) / n.y;
            (alpha, beta, rot.transpose() * Vector3::y())
        });
        Self {
            local_plane,
            rot,
            ow,
            com,
            plane,
            texels: atlas.len(),
            depth_scale: atlas.bounding_radius(),
            deep_scale: deep_scale(atlas, water.gravity, dt),
        }
    }

    /// Whether this frame, made for `body` (an atlas of the same pose),
    /// is `other`'s too under planar water: the same origin and the same
    /// plane (where there is no free surface, the plane above the body is
    /// placed by the atlas' radius). The planar sums read nothing else of
    /// a frame.
    pub(crate) fn serves(&self, body: &Atlas, other: &Atlas, water: &Water, t: f64) -> bool {
        self.plane.is_some()
            && body.origin() == other.origin()
            && Self::surface_plane(water, t, &self.ow, other.bounding_radius()) == self.plane
    }

    /// The water's surface as a plane `(normal, offset)` at time `t`, if it
    /// is one, for a body whose atlas origin is at `ow` within `radius`.
    pub(crate) fn surface_plane(
        water: &Water,
        t: f64,
        ow: &Vector3<f64>,
        radius: f64,
    ) -> Option<(Vector3<f64>, f64)> {
        match water.surface.kind(t) {
            SurfaceKind::Plane { normal, offset } => Some((normal, offset)),
            // No free surface: a horizontal plane above the whole body gives
            // the same sums (Σ A = 0 for a closed surface) with finite depths.
            SurfaceKind::Unbounded => Some((Vector3::y(), ow.y + radius + 1.0)),
            SurfaceKind::General => None,
        }
    }

    #[inline]
    pub(crate) fn depth(&self, water: &Water, p: &Vector3<f64>, t: f64) -> f64 {
        match self.plane {
            Some((n, c)) => (c - n.dot(p)) / n.y,
            None => water.surface.depth(&Point3::from(*p), t),
        }
    }
}

#[inline]
pub(crate) fn texel(atlas: &Atlas, i: usize) -> (Vector3<f64>, Vector3<f64>) {
    let x = atlas.local_positions().get(i);
    let a = atlas.area_vectors().get(i);
    (
        Vector3::new(x[0] as f64, x[1] as f64, x[2] as f64),
        Vector3::new(a[0] as f64, a[1] as f64, a[2] as f64),
    )
}

#[cfg(test)]
mod tests {
    use super::*;
    use soak_bake::{BakeOptions, builtin};

    /// A 2 mm rod 10 µm thick: at 1/240 s the ramp is `g dt²`, not the
    /// thickness; at 1/10 s the radius bounds it; a 1 m cube at 1/60 s
    /// keeps its thickness, and no step leaves the thickness as it is.
    #[test]
    fn the_deep_scale_is_the_thickness_widened_to_a_steps_heave() {
        let g = 9.81;
        let rod = Atlas::bake(&builtin::cuboid(2e-3, 1e-5, 1e-5), BakeOptions::square(32)).unwrap();
        let (t, r) = (rod.mean_thickness(), rod.bounding_radius());
        assert!(t < 1e-5 && r > 9e-4, "thickness {t}, radius {r}");
        let dt = 1.0 / 240.0;
        assert_eq!(deep_scale(&rod, g, dt), g * dt * dt);
        assert_eq!(deep_scale(&rod, g, 0.1), r);
        assert_eq!(deep_scale(&rod, g, 0.0), t);
        assert_eq!(deep_thickness(t, g, f64::INFINITY), t);
        let cube = Atlas::bake(&builtin::cuboid(1.0, 1.0, 1.0), BakeOptions::square(32)).unwrap();
        let t = cube.mean_thickness();
        assert!((t - 0.5).abs() < 1e-3, "the cube's thickness {t}");
        assert_eq!(deep_scale(&cube, g, 1.0 / 60.0), t);
    }
}

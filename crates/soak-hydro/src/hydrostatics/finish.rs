//! Finishing an evaluation: the sums of any path turned into the forces of
//! the selected buoyancy mode, the centre of buoyancy and the drag.

use nalgebra::{Point3, Vector3};

use super::body_state::BodyState;
use super::deep_volume::deep_volume;
use super::forces::{HydroForces, Wrench};
use super::frame::Frame;
use super::implicit_drag::implicit_drag;
use super::options::{BuoyancyMode, HydroOptions};
use super::slope_torque::slope_torque;
use super::sums::{BuoyancySums, DragSums};
use crate::mass::MassProperties;
use crate::water::Water;

/// Turns the sums into forces.
pub(crate) fn finish(
    frame: &Frame,
    water: &Water,
    state: &BodyState,
    mass: &MassProperties,
    s: &BuoyancySums,
    drag: Option<&DragSums>,
    options: &HydroOptions,
) -> HydroForces {
    let rg = water.density * water.gravity;
    let com = frame.com;
    let ow = frame.ow;
    let (volume, deep) = deep_volume(frame, s, options.buoyancy == BuoyancyMode::Archimedes);
    let volume = volume.max(0.0);
    let cb = if s.vol > 0.0 {
        ow + (s.wr + Vector3::y() * s.wd2) / s.vol
    } else {
        com
    };
    let buoyancy = match options.buoyancy {
        BuoyancyMode::Archimedes => {
            let force = Vector3::new(0.0, rg * volume, 0.0);
            let slope_torque = rg * slope_torque(frame, s);
            Wrench {
                force,
                torque: (cb - com).cross(&force) + slope_torque,
            }
        }
        BuoyancyMode::Pressure => {
            let force = rg * s.f;
            // Σ (p − c) × F = Σ r × F − (c − o_w) × Σ F
            Wrench {
                force,
                torque: rg * s.rxf - (com - ow).cross(&force),
            }
        }
        BuoyancyMode::Off => Wrench::default(),
    };
    let (drag, drag_explicit) = match drag {
        // No texel under water: no drag, and no system to solve (the
        // solve's rounding would hand back a few ulps of the momentum).
        Some(d) if d.is_zero() => (Wrench::default(), Wrench::default()),
        Some(d) => {
            let added = options
                .added_mass
                .map(|a| a.scaled(&state.pose.rotation, water.density, volume));
            implicit_drag(d, state, mass, added.as_ref(), options.dt)
        }
        None => (Wrench::default(), Wrench::default()),
    };
    HydroForces {
        submerged_volume: volume,
        center_of_buoyancy: Point3::from(cb),
        wetted_area: s.area,
        submerged_texels: s.count,
        potential: rg * s.wd2,
        deep,
        buoyancy,
        drag,
        drag_explicit,
    }
}

//! A minimal engine ([`FreeBodies`]): rigid bodies without contacts,
//! stepped exactly as the driver predicts an engine steps them. For
//! examples, tests, and bodies that only ever touch water.

use nalgebra::{Isometry3, Matrix3, Vector3};
use soak_hydro::{MassProperties, Wrench};

use crate::engine::{Bodies, BodiesMut, EngineBody, EngineMass, StepParams};
use crate::predicted_step::predict_step;

/// Names a body of [`FreeBodies`] (its insertion index).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct FreeHandle(pub usize);

#[derive(Clone, Debug)]
struct FreeBody {
    body: EngineBody,
    mass: Option<MassProperties>,
    wrench: Wrench,
}

/// Rigid bodies with no contacts and no joints, under gravity and the
/// forces the driver hands them, each step integrated exactly as
/// [`predict_step`] says Rapier integrates a body (symplectic Euler over
/// substeps, the gyroscopic term, the cap on the spin). In f64 throughout.
///
/// It is the engine of soak's examples and engine-free tests, and a
/// template for an adapter ([`Bodies`] and [`BodiesMut`] over ~30 lines).
/// A body moves once it has mass properties (the driver hands it them
/// at registration); until then it stays where it is.
///
/// # Example
/// ```
/// use nalgebra::Isometry3;
/// use soak_bake::{Atlas, BakeOptions, builtin};
/// use soak_driver::{BodyDesc, Driver, Effects, FreeBodies, StepParams};
/// use soak_hydro::{Drag, MassModel, Water};
///
/// let mut engine = FreeBodies::new(9.81);
/// let handle = engine.insert(Isometry3::translation(0.0, 1.0, 0.0));
/// let atlas = Atlas::bake(&builtin::cuboid(1.0, 0.6, 0.8), BakeOptions::square(128))?;
/// let mut soak = Driver::new(Water::calm(0.0));
/// let id = soak.register(&mut engine, handle, BodyDesc {
///     name: "crate".into(),
///     atlas: atlas.into(),
///     mass_model: MassModel::Solid { density: 500.0 },
///     effects: Effects::buoyancy().with_drag(Drag { coefficient: 1.0, linear: 200.0 }),
/// })?;
/// let step = StepParams::new(1.0 / 60.0, 4);
/// for _ in 0..1200 {
///     soak.before_step(&mut engine, &step)?;
///     engine.step(&step);
///     soak.after_step(step.dt);
/// }
/// // Pine at 500 kg/m³ floats with half its 0.6 m height under water.
/// let draft = soak.draft(id, &engine).ok_or("no such body")?;
/// assert!((draft - 0.3).abs() < 1e-3, "draft {draft} m");
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
#[derive(Clone, Debug, Default)]
pub struct FreeBodies {
    gravity: f64,
    bodies: Vec<Option<FreeBody>>,
}

impl FreeBodies {
    /// No bodies yet, in `gravity` (m/s² along −y).
    pub fn new(gravity: f64) -> Self {
        Self {
            gravity,
            bodies: Vec::new(),
        }
    }

    /// Gravity, m/s² along −y.
    pub fn gravity(&self) -> f64 {
        self.gravity
    }

    /// A body at `pose`, at rest, with gravity scale 1, its spin capped
    /// at `π/4` per step and gyroscopic forces on (Rapier's defaults).
    pub fn insert(&mut self, pose: Isometry3<f64>) -> FreeHandle {
        self.insert_body(EngineBody {
            pose,
            linear_velocity: Vector3::zeros(),
            angular_velocity: Vector3::zeros(),
            mass: 0.0,
            gravity_scale: 1.0,
            fast_rotation: false,
            gyroscopic: true,
        })
    }

    /// A body as `body` says (its `mass` is replaced when the driver hands
    /// it mass properties).
    pub fn insert_body(&mut self, body: EngineBody) -> FreeHandle {
        self.bodies.push(Some(FreeBody {
            body,
            mass: None,
            wrench: Wrench::default(),
        }));
        FreeHandle(self.bodies.len() - 1)
    }

    /// Removes a body; its handle names nothing from then on.
    pub fn remove(&mut self, handle: FreeHandle) -> Option<EngineBody> {
        self.bodies.get_mut(handle.0)?.take().map(|b| b.body)
    }

    /// A body's state.
    pub fn get(&self, handle: FreeHandle) -> Option<&EngineBody> {
        Some(&self.bodies.get(handle.0)?.as_ref()?.body)
    }

    /// A body's state, to set its pose or velocities.
    pub fn get_mut(&mut self, handle: FreeHandle) -> Option<&mut EngineBody> {
        Some(&mut self.bodies.get_mut(handle.0)?.as_mut()?.body)
    }

    /// The force and torque the body's next step applies (world, about its
    /// centre of mass).
    pub fn wrench(&self, handle: FreeHandle) -> Option<&Wrench> {
        Some(&self.bodies.get(handle.0)?.as_ref()?.wrench)
    }

    /// Steps every body that has mass properties by `step`.
    pub fn step(&mut self, step: &StepParams) {
        for b in self.bodies.iter_mut().flatten() {
            let Some(mass) = &b.mass else {
                continue;
            };
            if let Some(end) = predict_step(&b.body, mass, &b.wrench, self.gravity, step) {
                b.body.pose = end.pose;
                b.body.linear_velocity = end.linear_velocity;
                b.body.angular_velocity = end.angular_velocity;
            }
        }
    }
}

impl Bodies for FreeBodies {
    type Handle = FreeHandle;

    fn body(&self, handle: FreeHandle) -> Option<EngineBody> {
        self.get(handle).copied()
    }
}

impl BodiesMut for FreeBodies {
    fn set_mass_properties(&mut self, handle: FreeHandle, mass: &EngineMass) -> bool {
        let Some(b) = self.bodies.get_mut(handle.0).and_then(Option::as_mut) else {
            return false;
        };
        let r = mass.principal_frame.to_rotation_matrix().into_inner();
        b.mass = Some(MassProperties {
            mass: mass.mass,
            center_of_mass: mass.center_of_mass,
            inertia: r * Matrix3::from_diagonal(&mass.principal_moments) * r.transpose(),
        });
        b.body.mass = mass.mass;
        true
    }

    fn set_wrench(&mut self, handle: FreeHandle, wrench: &Wrench) -> bool {
        let Some(b) = self.bodies.get_mut(handle.0).and_then(Option::as_mut) else {
            return false;
        };
        b.wrench = *wrench;
        true
    }
}

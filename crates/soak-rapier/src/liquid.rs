//! Water inside Rapier bodies: a [`Flooding`] liquid graph driven by the
//! body's pose, whose liquid's mass the [`ForceGenerator`] hands to Rapier.
//!
//! Each step, [`LiquidBody::update`] reads the body's pose from Rapier and
//! the fluid from the generator ([`ForceGenerator::water`]), advances the
//! liquid graph by the world's `dt` (wall exchange, then redistribution),
//! and, when the liquid changed, sets the body's extra mass
//! ([`ForceGenerator::set_extra_mass`]) to the liquid's point masses
//! (`ρ l_i` at the nodes, plus any fixed ballast), combined with the mass
//! model's about the common centre of mass. The buoyancy stays what the
//! atlas gives — the hull's enclosed volume — while the mass grows: a holed
//! hull sinks once the water inside outweighs its reserve of buoyancy.
//!
//! [`step`] does this for every liquid body and then steps the world.
//!
//! # Example
//! ```
//! use nalgebra::Point3;
//! use rapier3d::prelude::*;
//! use soak_bake::{Atlas, BakeOptions, builtin};
//! use soak_graph::{Flooding, FlowOptions, LiquidGraph, Node, Permeability};
//! use soak_hydro::{MassModel, Water};
//! use soak_rapier::liquid::{self, LiquidBody};
//! use soak_rapier::{BodyDesc, Effects, ForceGenerator};
//!
//! let mut world = PhysicsWorld::new();
//! world.integration_parameters.dt = 1.0 / 30.0;
//! let handle = world.bodies.insert(RigidBodyBuilder::dynamic());
//! let atlas = Atlas::bake(&builtin::cuboid(1.0, 1.0, 1.0), BakeOptions::square(32))?;
//! let mut permeability = Permeability::watertight(&atlas);
//! permeability.paint(&atlas, Point3::new(0.0, -0.5, 0.0), 0.2, 1e-6)?; // a hole in the bottom
//! let graph = LiquidGraph::new(vec![Node::new("hold", Point3::origin(), 1.0).with_height(1.0)], vec![])?;
//! let flooding = Flooding::for_atlas(&atlas, graph, permeability, FlowOptions::default())?;
//! let mut soak = ForceGenerator::new(Water::calm(0.0));
//! let id = soak.register(&mut world.bodies, &world.colliders, handle, BodyDesc {
//!     name: "box".into(),
//!     atlas,
//!     mass_model: MassModel::Shell { areal_density: 20.0 },
//!     effects: Effects::buoyancy(),
//! })?;
//! let mut liquids = vec![LiquidBody::attach(&mut soak, &mut world, id, flooding)?];
//! for _ in 0..300 {
//!     liquid::step(&mut soak, &mut liquids, &mut world)?;
//! }
//! // Water came in and the body is heavier by its mass.
//! let inside = liquids[0].flooding().inside();
//! assert!(inside > 0.1);
//! let mass = soak.body(id).unwrap().mass_properties().mass;
//! assert!((mass - (120.0 + 1000.0 * inside)).abs() < 1e-6 * mass);
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

use nalgebra::{Isometry3, Vector3};
use rapier3d::prelude::PhysicsWorld;
use soak_bake::Atlas;
use soak_graph::{Flooding, StepReport};
use soak_hydro::{MassProperties, Water};

use crate::convert;
use crate::error::SoakError;
use crate::generator::{ForceGenerator, SoakId};

/// A registered soak body with water inside.
#[derive(Clone, Debug)]
pub struct LiquidBody {
    id: SoakId,
    flooding: Flooding,
    ballast: Option<MassProperties>,
    density: Option<f64>,
    last: StepReport,
}

impl LiquidBody {
    /// Attaches `flooding` (whose permeability channel and texel map were
    /// made for the body's atlas) to the registered body `id`, and hands
    /// the liquid already inside to Rapier at once.
    ///
    /// # Errors
    /// An unknown id or a body Rapier no longer has.
    pub fn attach(
        soak: &mut ForceGenerator,
        world: &mut PhysicsWorld,
        id: SoakId,
        flooding: Flooding,
    ) -> Result<Self, SoakError> {
        let mut body = Self {
            id,
            flooding,
            ballast: None,
            density: None,
            last: StepReport::default(),
        };
        body.sync_mass(soak, world)?;
        Ok(body)
    }

    /// Adds a fixed mass carried with the liquid (ballast, cargo; local
    /// frame) and hands the total to Rapier at once.
    ///
    /// # Errors
    /// As [`LiquidBody::attach`]; non-finite ballast.
    pub fn set_ballast(
        &mut self,
        ballast: Option<MassProperties>,
        soak: &mut ForceGenerator,
        world: &mut PhysicsWorld,
    ) -> Result<(), SoakError> {
        self.ballast = ballast;
        self.sync_mass(soak, world)
    }

    /// Sets the density of the liquid inside, kg/m³ (default: the
    /// surrounding fluid's, [`Water::density`]).
    ///
    /// # Errors
    /// A density that is not a finite number ≥ 0.
    pub fn set_density(
        &mut self,
        density: f64,
        soak: &mut ForceGenerator,
        world: &mut PhysicsWorld,
    ) -> Result<(), SoakError> {
        if !(density.is_finite() && density >= 0.0) {
            return Err(SoakError::LiquidDensity {
                name: name_of(soak, self.id),
                density,
            });
        }
        self.density = Some(density);
        self.sync_mass(soak, world)
    }

    /// The soak body.
    pub fn id(&self) -> SoakId {
        self.id
    }

    /// The liquid graph in motion.
    pub fn flooding(&self) -> &Flooding {
        &self.flooding
    }

    /// The liquid graph, to punch a hole ([`Flooding::permeability_mut`])
    /// or pour water ([`Flooding::pour`]); call [`LiquidBody::sync_mass`]
    /// after pouring if the body must feel it before the next update.
    pub fn flooding_mut(&mut self) -> &mut Flooding {
        &mut self.flooding
    }

    /// What the last [`LiquidBody::update`] did.
    pub fn last_step(&self) -> &StepReport {
        &self.last
    }

    /// Density of the liquid inside in `water`, kg/m³.
    pub fn density(&self, water: &Water) -> f64 {
        self.density.unwrap_or(water.density)
    }

    /// The liquid's mass properties (local frame) in `water`'s density unless set.
    pub fn liquid_mass(&self, water: &Water) -> MassProperties {
        self.flooding.mass_properties(self.density(water))
    }

    /// Hands liquid plus ballast to the generator (and so to Rapier) now.
    ///
    /// # Errors
    /// An unknown id, a missing body, invalid mass properties.
    pub fn sync_mass(
        &mut self,
        soak: &mut ForceGenerator,
        world: &mut PhysicsWorld,
    ) -> Result<(), SoakError> {
        let liquid = self.liquid_mass(soak.water());
        let extra = match (self.ballast, liquid.mass > 0.0) {
            (Some(b), true) => Some(b.combine(&liquid)),
            (Some(b), false) => Some(b),
            (None, true) => Some(liquid),
            (None, false) => None,
        };
        soak.set_extra_mass(self.id, extra, &mut world.bodies, &world.colliders)?;
        Ok(())
    }

    /// Advances the liquid by the world's `dt` with the body's current pose
    /// at the generator's time, and hands its mass to Rapier when it
    /// changed. Call once per step, before [`ForceGenerator::step`] (or use
    /// [`step`]).
    ///
    /// The liquid's pressure uses the generator's fluid gravity, which
    /// [`ForceGenerator::step`] keeps equal to the world's; before the first
    /// step it is the fluid's own (standard gravity by default).
    ///
    /// # Errors
    /// An unknown id, a missing body, a liquid step that failed (the liquid
    /// is then unchanged).
    pub fn update(
        &mut self,
        soak: &mut ForceGenerator,
        world: &mut PhysicsWorld,
    ) -> Result<StepReport, SoakError> {
        let body = soak.body(self.id).ok_or(SoakError::UnknownId(self.id.0))?;
        let rb = world
            .bodies
            .get(body.handle())
            .ok_or_else(|| SoakError::MissingBody {
                name: body.name().to_string(),
            })?;
        let pose = convert::pose(rb.position());
        let dt = world.integration_parameters.dt as f64;
        let report = self
            .flooding
            .step(body.atlas(), &pose, soak.water(), soak.time(), dt)
            .map_err(|source| SoakError::Flow {
                name: body.name().to_string(),
                source,
            })?;
        self.last = report;
        if report.changed() {
            self.sync_mass(soak, world)?;
        }
        Ok(report)
    }
}

fn name_of(soak: &ForceGenerator, id: SoakId) -> String {
    soak.body(id)
        .map_or_else(|| format!("#{}", id.0), |b| b.name().to_string())
}

/// Updates every liquid body ([`LiquidBody::update`]), then applies the
/// fluid forces and steps the world ([`ForceGenerator::step`]).
///
/// # Errors
/// The first liquid body or generator step that failed.
pub fn step(
    soak: &mut ForceGenerator,
    liquids: &mut [LiquidBody],
    world: &mut PhysicsWorld,
) -> Result<(), SoakError> {
    soak.sync_gravity(world);
    for l in liquids.iter_mut() {
        l.update(soak, world)?;
    }
    soak.step(world)?;
    Ok(())
}

/// Pitch of a body whose bow points along its local +x, degrees: the angle
/// of that axis above the horizontal, positive bow-up (stern-down),
/// negative bow-down.
pub fn pitch_degrees(pose: &Isometry3<f64>) -> f64 {
    let bow = pose.rotation * Vector3::x();
    bow.y.clamp(-1.0, 1.0).asin().to_degrees()
}

/// Heel of a body whose starboard is its local +z, degrees: the angle of
/// that axis below the horizontal, positive listing to starboard.
pub fn heel_degrees(pose: &Isometry3<f64>) -> f64 {
    let starboard = pose.rotation * Vector3::z();
    (-starboard.y).clamp(-1.0, 1.0).asin().to_degrees()
}

/// Height of the body's highest texel above the water surface at time `t`
/// (s), m: negative once the whole body is under water (sunk). `+∞` for an
/// empty atlas, `−∞` in an unbounded fluid.
pub fn freeboard(atlas: &Atlas, pose: &Isometry3<f64>, water: &Water, t: f64) -> f64 {
    (0..atlas.len())
        .map(|i| -water.surface.depth(&(pose * atlas.position(i)), t))
        .filter(|d| !d.is_nan())
        .fold(f64::NEG_INFINITY, f64::max)
        .max(if atlas.is_empty() {
            f64::INFINITY
        } else {
            f64::NEG_INFINITY
        })
}

//! What the generator is configured with: the effects a body takes part in
//! ([`Effects`]), the CPU backend ([`Backend`]), what to register
//! ([`BodyDesc`]) and the id a registered body gets ([`SoakId`]).

use serde::{Deserialize, Serialize};
use soak_bake::Atlas;
use soak_hydro::{BuoyancyMode, Drag, MassModel};

/// Which effects a body takes part in. Effects left off allocate and cost nothing.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct Effects {
    /// Buoyancy, and in which mode; `None` for none.
    pub buoyancy: Option<BuoyancyMode>,
    /// Drag, if any.
    pub drag: Option<Drag>,
}

impl Effects {
    /// Archimedes buoyancy only.
    pub fn buoyancy() -> Self {
        Self {
            buoyancy: Some(BuoyancyMode::Archimedes),
            drag: None,
        }
    }

    /// The same effects with drag.
    pub fn with_drag(mut self, drag: Drag) -> Self {
        self.drag = Some(drag);
        self
    }

    /// The same effects with another buoyancy mode.
    pub fn with_mode(mut self, mode: BuoyancyMode) -> Self {
        self.buoyancy = Some(mode);
        self
    }

    /// Whether the body needs hydrostatics at all.
    pub fn any(&self) -> bool {
        self.buoyancy.is_some_and(|m| m != BuoyancyMode::Off) || self.drag.is_some()
    }
}

/// How texel sums are evaluated on the CPU; both give the same answer.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Backend {
    /// Every texel, every step.
    PerTexel,
    /// Closed forms for tiles wholly under planar water (the default).
    #[default]
    Tiled,
    /// All bodies in one GPU batch per step (the `gpu` feature; see
    /// `ForceGenerator::with_gpu`); the tiled path stands by on the CPU.
    Gpu,
}

/// Identifies a body registered with a [`ForceGenerator`](super::ForceGenerator).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize, Deserialize)]
pub struct SoakId(pub usize);

/// What to register: a mesh's atlas, its mass model and its effects.
#[derive(Clone, Debug)]
pub struct BodyDesc {
    /// A name for reports and log lines.
    pub name: String,
    /// The baked atlas of the body's mesh, in the rigid body's local frame.
    pub atlas: Atlas,
    /// How the body's mass is distributed.
    pub mass_model: MassModel,
    /// The effects it takes part in.
    pub effects: Effects,
}

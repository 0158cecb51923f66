//! The generator's evolving state, for saving and restoring: each body's
//! [`BodyRunState`], the whole [`GeneratorState`], and
//! [`Driver::state`] and [`Driver::restore_state`].

use serde::{Deserialize, Serialize};
use soak_graph::FloodingState;
use soak_hydro::{HydroForces, MassModel, MassProperties, Wrench};
use soak_wet::{Environment, StepReport, Wetting};

use crate::body::with_extra;
use crate::driver::Driver;
use crate::engine::Handle;
use crate::error::SoakError;

/// What a body's run changes, for saving: its mass model and extra mass,
/// the last forces, its wetting (liquid texture, ledger and settings) and
/// its flooding (liquid per node, the wall's permeability, the ledger).
#[derive(Clone, Debug, Serialize, Deserialize)]
pub struct BodyRunState {
    /// The mass model now.
    pub mass_model: MassModel,
    /// Extra mass now.
    pub extra_mass: Option<MassProperties>,
    /// Hydrostatics of the last step.
    pub forces: HydroForces,
    /// What was handed to the engine at the last step.
    pub applied: Wrench,
    /// Dry steps skipped so far.
    pub dry_skips: u64,
    /// The body's wetting, if it has any: the liquid texture (m per texel),
    /// the ledger of absorbed and evaporated volumes (m³) and the material,
    /// liquid and diffusion settings. The diffusion field's binning is not
    /// saved: it is rebuilt from the atlas, to the same bits.
    #[serde(default)]
    pub wetting: Option<Wetting>,
    /// What its last wetting step did.
    #[serde(default)]
    pub wet_report: Option<StepReport>,
    /// The liquid inside the body, if it has flooding: liquid per node
    /// (m³), the wall's permeability (holes punched so far), the ledger and
    /// the random stream. The graph and texel map come from the body's
    /// effects.
    #[serde(default)]
    pub flooding: Option<FloodingState>,
    /// Fixed mass carried with the liquid inside (flooding bodies).
    #[serde(default)]
    pub ballast: Option<MassProperties>,
    /// Density of the liquid inside, kg/m³, if set (flooding bodies).
    #[serde(default)]
    pub liquid_density: Option<f64>,
    /// The water-plane's added mass at the last step, kg (slamming bodies
    /// after their first step): the next step's impact is its growth.
    #[serde(default)]
    pub slam_added_mass: Option<f64>,
    /// The radiation memory (radiation bodies): one state per kernel pole
    /// and the last velocity recorded, and the last memory force (world,
    /// N and N·m).
    #[serde(default)]
    pub radiation: Option<(soak_seakeeping::RadiationState, Wrench)>,
    /// The body is no longer driven ([`Driver::retire`]): restored, it
    /// stays retired.
    #[serde(default)]
    pub retired: bool,
}

impl PartialEq for BodyRunState {
    fn eq(&self, other: &Self) -> bool {
        let same_wetting = match (&self.wetting, &other.wetting) {
            (None, None) => true,
            (Some(a), Some(b)) => same_wetting(a, b),
            _ => false,
        };
        self.mass_model == other.mass_model
            && self.extra_mass == other.extra_mass
            && self.forces == other.forces
            && self.applied == other.applied
            && self.dry_skips == other.dry_skips
            && self.wet_report == other.wet_report
            && self.flooding == other.flooding
            && self.ballast == other.ballast
            && self.liquid_density == other.liquid_density
            && self.slam_added_mass == other.slam_added_mass
            && self.radiation == other.radiation
            && self.retired == other.retired
            && same_wetting
    }
}

/// Whether two wetting states hold the same settings, liquid and ledger
/// (their rebuilt-on-demand field caches aside).
fn same_wetting(a: &Wetting, b: &Wetting) -> bool {
    a.material() == b.material()
        && a.liquid_params() == b.liquid_params()
        && a.response() == b.response()
        && a.diffusion() == b.diffusion()
        && a.permeability_map() == b.permeability_map()
        && a.liquid() == b.liquid()
        && a.ledger() == b.ledger()
}

/// The evolving state of a [`Driver`] (not its atlases or water,
/// which come from the scene).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct GeneratorState {
    /// Simulated time, s.
    pub time: f64,
    /// Steps taken.
    pub steps: u64,
    /// Per body, in registration order.
    pub bodies: Vec<BodyRunState>,
    /// The weather wet bodies dry in.
    #[serde(default)]
    pub environment: Environment,
    /// The interactive waves, if the generator has them: their surface
    /// and what each body pressed at the last step.
    #[serde(default)]
    pub waves: Option<crate::waves::CoupledWavesState>,
}

impl<H: Handle> Driver<H> {
    /// The evolving state, for saving.
    pub fn state(&self) -> GeneratorState {
        GeneratorState {
            time: self.time,
            steps: self.steps,
            bodies: self
                .bodies
                .iter()
                .map(|b| BodyRunState {
                    mass_model: b.mass_model.clone(),
                    extra_mass: b.extra_mass,
                    forces: b.forces,
                    applied: b.applied,
                    dry_skips: b.dry_skips,
                    wetting: b.effects.wetting.as_deref().cloned(),
                    wet_report: b.wet_report().copied(),
                    flooding: b.effects.flooding.as_ref().map(|f| f.state()),
                    ballast: b.ballast().copied(),
                    liquid_density: b.effects.flooding.as_ref().and(b.flood.density),
                    slam_added_mass: b.slam.as_ref().and_then(|s| s.last_added),
                    radiation: b.radiation.as_ref().map(|r| (r.state.clone(), r.force)),
                    retired: b.retired,
                })
                .collect(),
            environment: self.environment,
            waves: self.waves.as_deref().map(|w| w.state()),
        }
    }

    /// Restores a state saved from a driver with the same bodies (and
    /// the same liquid graphs in the flooding ones). The engine's world is
    /// restored separately (its bodies already carry the saved mass
    /// properties). Wetting is on afterwards for the bodies the state has
    /// it for.
    ///
    /// # Errors
    /// Another number of bodies, a liquid texture of another size, flooding
    /// for a body without it or none for a body with it, invalid mass
    /// properties, a flooding state of another graph or atlas. The checks
    /// that need no computation come first; should a later one fail the
    /// generator may be left partly restored.
    pub fn restore_state(&mut self, state: &GeneratorState) -> Result<(), SoakError> {
        if state.bodies.len() != self.bodies.len() {
            return Err(SoakError::StateBodies {
                saved: state.bodies.len(),
                registered: self.bodies.len(),
            });
        }
        for (b, s) in self.bodies.iter().zip(&state.bodies) {
            if let Some(w) = &s.wetting
                && w.texels() != b.atlas.len()
            {
                return Err(SoakError::StateTexels {
                    name: b.name.clone(),
                    saved: w.texels(),
                    atlas: b.atlas.len(),
                });
            }
            if let (Some(model), Some((saved, _))) = (&b.effects.radiation, &s.radiation)
                && !saved.fits(model)
            {
                return Err(SoakError::Radiation {
                    name: b.name.clone(),
                    reason: "the saved memory has other kernels than the body's model".into(),
                });
            }
            if s.radiation.is_some() != b.effects.radiation.is_some() && !s.retired && !b.retired {
                return Err(SoakError::Radiation {
                    name: b.name.clone(),
                    reason: if s.radiation.is_some() {
                        "the saved state has radiation, the body has none".into()
                    } else {
                        "the saved state has no radiation, the body has".into()
                    },
                });
            }
            if s.flooding.is_some() != b.effects.flooding.is_some() && !s.retired && !b.retired {
                return Err(SoakError::StateFlooding {
                    name: b.name.clone(),
                    saved: s.flooding.is_some(),
                });
            }
        }
        match (self.waves.as_deref_mut(), &state.waves) {
            (None, None) => {}
            (Some(w), Some(saved)) => {
                if saved.own.len() > self.bodies.len() {
                    return Err(SoakError::StateWaves {
                        reason: format!(
                            "the waves hold presses for {} bodies, the generator has {}",
                            saved.own.len(),
                            self.bodies.len()
                        ),
                    });
                }
                w.solver
                    .restore(&saved.surface)
                    .map_err(|e| SoakError::StateWaves {
                        reason: format!("the waves: {e}"),
                    })?;
                w.own = saved.own.clone();
                w.settle_pending = saved.settle_pending;
                w.follow = None;
                w.moved = true;
            }
            (mine, _) => {
                return Err(SoakError::StateWaves {
                    reason: if mine.is_some() {
                        "it has no interactive waves, the generator has".into()
                    } else {
                        "it has interactive waves, the generator has none".into()
                    },
                });
            }
        }
        self.environment = state.environment;
        for (b, s) in self.bodies.iter_mut().zip(&state.bodies) {
            // The body's own mass model again: its mass properties are the
            // ones it holds (worked out from the same atlas).
            let model_mass = if s.mass_model == b.mass_model {
                b.model_mass
            } else {
                s.mass_model
                    .mass_properties(&b.atlas)
                    .map_err(|source| SoakError::Hydro {
                        name: b.name.clone(),
                        source,
                    })?
            };
            if let (Some(f), Some(saved)) = (&mut b.effects.flooding, &s.flooding) {
                f.restore(saved).map_err(|source| SoakError::Flow {
                    name: b.name.clone(),
                    source,
                })?;
            }
            b.flood.ballast = s.ballast;
            b.flood.density = s.liquid_density;
            b.flood.last = soak_graph::StepReport::default();
            b.mass_model = s.mass_model.clone();
            b.model_mass = model_mass;
            b.extra_mass = s.extra_mass;
            b.mass = with_extra(&model_mass, s.extra_mass.as_ref());
            b.forces = s.forces;
            b.applied = s.applied;
            b.dry_skips = s.dry_skips;
            b.effects.wetting = s.wetting.clone().map(Box::new);
            b.wet_report = s.wet_report.unwrap_or_default();
            if let Some(slam) = &mut b.slam {
                slam.last_added = s.slam_added_mass;
            }
            if let (Some(run), Some((state, force))) = (&mut b.radiation, &s.radiation) {
                run.state = state.clone();
                run.force = *force;
            }
            if s.retired {
                b.retire();
            }
        }
        self.time = state.time;
        self.steps = state.steps;
        Ok(())
    }
}

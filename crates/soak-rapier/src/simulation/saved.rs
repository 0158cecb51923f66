//! Saving a run and resuming it bit for bit: [`SavedSimulation`].

use serde::Serialize;

use super::Simulation;
use crate::error::{SceneError, SoakError};
use crate::scene::LoadedScene;

/// Everything a running scene owns, for saving and resuming: the scene
/// itself, the Rapier world and the generator's state (with each wet
/// body's liquid texture, each flooding body's liquid inside, and the
/// environment).
/// A run resumed from it continues bit for bit as the uninterrupted run.
#[derive(Clone, Serialize, serde::Deserialize)]
pub struct SavedSimulation {
    /// The scene file's path (for relative paths and messages).
    pub scene_path: std::path::PathBuf,
    /// The scene file's text.
    pub scene_text: String,
    /// The Rapier world in rapier's own serde form, postcard-encoded
    /// (`PhysicsWorld` is serialisable but not `Clone`).
    pub world: Vec<u8>,
    /// The force generator's state, with the liquid inside flooding bodies.
    pub generator: crate::GeneratorState,
    /// Which permeable regions have opened.
    pub punched: Vec<bool>,
    /// Which splashes have landed.
    #[serde(default)]
    pub splashed: Vec<bool>,
    /// Steps taken.
    pub steps: u64,
    /// Per body: whether it went non-finite.
    pub non_finite: Vec<bool>,
}

impl SavedSimulation {
    /// The saved state as bytes: self-describing JSON (the state holds
    /// internally tagged enums, which a non-self-describing format cannot
    /// read back), with floats written so that they read back bit for bit.
    pub fn to_bytes(&self) -> Result<Vec<u8>, SoakError> {
        Ok(serde_json::to_vec(self)?)
    }

    /// Reads what [`SavedSimulation::to_bytes`] wrote; damaged or truncated
    /// input is a [`SoakError::Json`], never a panic.
    pub fn from_bytes(bytes: &[u8]) -> Result<Self, SoakError> {
        Ok(serde_json::from_slice(bytes)?)
    }
}

impl Simulation {
    /// Saves everything needed to resume this run exactly (see [`Simulation::resume`]).
    pub fn save(&self, scene: &LoadedScene) -> Result<SavedSimulation, SoakError> {
        Ok(SavedSimulation {
            scene_path: scene.path.clone(),
            scene_text: scene.text.clone(),
            world: postcard::to_stdvec(&self.world).map_err(|e| SoakError::World {
                reason: format!("the Rapier world: {e}"),
            })?,
            generator: self.soak.state(),
            punched: self.holes.iter().map(|h| h.2).collect(),
            splashed: self.splashes.iter().map(|s| s.1).collect(),
            steps: self.steps,
            non_finite: self.non_finite.clone(),
        })
    }

    /// Rebuilds a run from a save: the scene is built again (meshes baked
    /// as before), then the world and the generator (with the liquid inside
    /// flooding bodies) take their saved states.
    pub fn resume(saved: &SavedSimulation) -> Result<Self, SceneError> {
        let loaded = LoadedScene::from_str(&saved.scene_text, &saved.scene_path)?;
        Self::resume_scene(&loaded, saved)
    }

    /// [`Simulation::resume`] from a scene already loaded (and perhaps
    /// changed in code since: a duration or a backend set as on the
    /// command line), which must be the saved run's scene file, word for
    /// word.
    ///
    /// # Errors
    /// [`SceneError::Invalid`] when `loaded`'s text is not the save's (the
    /// scene file was edited since) or the save does not fit the scene;
    /// the scene's own errors building it.
    pub fn resume_scene(loaded: &LoadedScene, saved: &SavedSimulation) -> Result<Self, SceneError> {
        let bad = |message: String| SceneError::Invalid {
            path: loaded.path.clone(),
            line: 1,
            key: "(saved state)".into(),
            message,
        };
        if loaded.text != saved.scene_text {
            return Err(bad(format!(
                "the scene file is not the one the run was saved from (`{}`): it was edited since; restore it, or start the run again",
                saved.scene_path.display()
            )));
        }
        let mut sim = Self::from_scene(loaded)?;
        if saved.generator.bodies.len() != sim.soak.bodies().len()
            || saved.punched.len() != sim.holes.len()
            || saved.splashed.len() != sim.splashes.len()
        {
            return Err(bad(
                "the save does not match the scene's bodies, holes or splashes".into(),
            ));
        }
        sim.world = postcard::from_bytes(&saved.world).map_err(|e| bad(format!("the Rapier world: {e}")))?;
        sim.soak
            .restore_state(&saved.generator)
            .map_err(|e| bad(e.to_string()))?;
        for (h, &p) in sim.holes.iter_mut().zip(&saved.punched) {
            h.2 = p;
        }
        for (s, &landed) in sim.splashes.iter_mut().zip(&saved.splashed) {
            s.1 = landed;
        }
        sim.steps = saved.steps;
        sim.non_finite = saved.non_finite.clone();
        Ok(sim)
    }
}

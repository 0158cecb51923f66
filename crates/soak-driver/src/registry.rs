//! Registering bodies with a [`Driver`] and changing their mass, mass
//! model and shape between steps.

use std::sync::Arc;

use nalgebra::Point3;
use soak_hydro::{HydroForces, MassModel, MassProperties, TiledAtlas, Wrench};
use soak_wet::Wetting;

use crate::body::{FloodSettings, RadiationRun, Shape, SoakBody, atlas_twin, shared_tiles, with_extra};
use crate::config::{Backend, BodyDesc, SoakId};
use crate::driver::Driver;
use crate::engine::{BodiesMut, Handle, check_not_too_light, push_mass};
use crate::error::SoakError;

impl<H: Handle> Driver<H> {
    /// Registers the engine's body `handle` with its effects: computes its
    /// mass properties from the mass model (plus the liquid already inside
    /// a flooding body) and hands them to the engine. The engine must add
    /// no mass of its own (an adapter refuses colliders with a density:
    /// soak owns the body's mass).
    ///
    /// # Errors
    /// A body the engine does not have, invalid mass properties, a wetting
    /// state made for an atlas of another size, an effect's settings out
    /// of range (the sea's read too: the body's own, else the driver's).
    pub fn register<B: BodiesMut<Handle = H> + ?Sized>(
        &mut self,
        bodies: &mut B,
        handle: H,
        desc: BodyDesc,
    ) -> Result<SoakId, SoakError> {
        if bodies.body(handle).is_none() {
            return Err(SoakError::MissingBody { name: desc.name });
        }
        // A body sharing its atlas (the same `Arc`) with one registered
        // before takes that body's shape and, under the same mass model,
        // its mass properties: the passes over the texels are taken once
        // per atlas, not once per body.
        let twin = atlas_twin(&self.bodies, &desc.atlas);
        let mass = match twin.filter(|b| b.mass_model == desc.mass_model) {
            Some(b) => b.model_mass,
            None => desc
                .mass_model
                .mass_properties(&desc.atlas)
                .map_err(|source| SoakError::Hydro {
                    name: desc.name.clone(),
                    source,
                })?,
        };
        let shape = twin.map_or_else(|| Shape::of(&desc.atlas), |b| b.shape);
        if let Some(w) = &desc.effects.wetting {
            check_wetting(&desc.name, &desc.atlas, w)?;
        }
        if let Some(rule) = &desc.effects.impact_holes {
            let reason = rule.problem().or_else(|| {
                desc.effects
                    .flooding
                    .as_ref()
                    .is_none_or(|f| f.permeability().is_none())
                    .then(|| "needs flooding with a wall (a liquid graph made for the atlas)".to_string())
            });
            if let Some(reason) = reason {
                return Err(SoakError::ImpactHoles {
                    name: desc.name.clone(),
                    reason,
                });
            }
        }
        if let Some(reason) = desc.effects.slamming.and_then(|s| s.problem()) {
            return Err(SoakError::Slamming {
                name: desc.name.clone(),
                reason,
            });
        }
        // The sea read the body will take: its own, else the driver's
        // (whose setter takes any value: a bad one is caught here, on the
        // first body that would read it, rather than at every step).
        desc.effects
            .sea
            .unwrap_or(self.sea)
            .check()
            .map_err(|source| SoakError::Hydro {
                name: desc.name.clone(),
                source: source.into(),
            })?;
        if let Some(texels) = &desc.effects.drag_texels {
            texels.check(&desc.atlas).map_err(|source| SoakError::Hydro {
                name: desc.name.clone(),
                source,
            })?;
        }
        check_not_too_light(&desc.name, mass.mass, &desc.effects, &self.water, shape.volume)?;
        if let Some(added) = &desc.effects.added_mass
            && !added.is_valid()
        {
            return Err(SoakError::Hydro {
                name: desc.name.clone(),
                source: soak_hydro::HydroError::AddedMass {
                    reason: format!("{added:?} is not finite with a volume > 0"),
                },
            });
        }
        if let Some(model) = &desc.effects.radiation
            && let Some(reason) = radiation_mismatch(model, &self.water, mass.mass)
        {
            return Err(SoakError::Radiation {
                name: desc.name.clone(),
                reason,
            });
        }
        push_mass(&desc.name, bodies, handle, &mass)?;
        let tiled = (self.backend != Backend::PerTexel && desc.effects.needs_hydrostatics())
            .then(|| shared_tiles(&self.bodies, &desc.atlas));
        #[cfg(feature = "gpu")]
        if let Some(gpu) = &mut self.gpu {
            gpu.upload(&desc.atlas)?;
        }
        self.bodies.push(SoakBody {
            name: desc.name,
            handle,
            shape,
            atlas: desc.atlas,
            tiled,
            mass_model: desc.mass_model,
            model_mass: mass,
            extra_mass: None,
            mass,
            effects: desc.effects,
            forces: HydroForces::default(),
            applied: Wrench::default(),
            added_force: Wrench::default(),
            dry_skips: 0,
            wet_report: soak_wet::StepReport::default(),
            flood: FloodSettings::default(),
            slam: None,
            radiation: None,
            retired: false,
        });
        let id = SoakId(self.bodies.len() - 1);
        if let Some(model) = &self.bodies[id.0].effects.radiation {
            let state = soak_seakeeping::RadiationState::new(model);
            self.bodies[id.0].radiation = Some(Box::new(RadiationRun {
                state,
                force: Wrench::default(),
            }));
        }
        if self.bodies[id.0].effects.slamming.is_some() {
            self.bodies[id.0].slam = Some(Box::default());
        }
        if self.bodies[id.0].effects.flooding.is_some() {
            // The liquid already inside, at once.
            self.sync_liquid_mass(id, bodies)?;
        }
        Ok(id)
    }

    /// Changes a body's mass model (e.g. a shell density texture that
    /// changes every frame) and hands the engine the new mass properties at once.
    pub fn set_mass_model<B: BodiesMut<Handle = H> + ?Sized>(
        &mut self,
        id: SoakId,
        model: MassModel,
        bodies: &mut B,
    ) -> Result<(), SoakError> {
        let b = self.bodies.get_mut(id.0).ok_or(SoakError::UnknownId(id.0))?;
        let mass = model
            .mass_properties(&b.atlas)
            .map_err(|source| SoakError::Hydro {
                name: b.name.clone(),
                source,
            })?;
        let total = with_extra(&mass, b.extra_mass.as_ref());
        check_not_too_light(&b.name, total.mass, &b.effects, &self.water, b.shape.volume)?;
        push_mass(&b.name, bodies, b.handle, &total)?;
        b.mass = with_extra(&mass, b.extra_mass.as_ref());
        b.model_mass = mass;
        b.mass_model = model;
        Ok(())
    }

    /// Sets the mass a body carries besides its mass model (local frame):
    /// liquid inside, a gas, a payload. It is combined with the model's
    /// about the common centre of mass and handed to the engine at once. A
    /// flooding body's extra mass is its liquid and ballast, set again
    /// whenever its liquid changes: give it ballast with
    /// [`Driver::set_ballast`] instead.
    pub fn set_extra_mass<B: BodiesMut<Handle = H> + ?Sized>(
        &mut self,
        id: SoakId,
        extra: Option<MassProperties>,
        bodies: &mut B,
    ) -> Result<(), SoakError> {
        let b = self.bodies.get_mut(id.0).ok_or(SoakError::UnknownId(id.0))?;
        if let Some(e) = &extra
            && !e.is_finite()
        {
            return Err(SoakError::MassProperties {
                name: b.name.clone(),
                reason: format!("extra mass {e:?} is not finite"),
            });
        }
        let total = with_extra(&b.model_mass, extra.as_ref());
        push_mass(&b.name, bodies, b.handle, &total)?;
        b.extra_mass = extra;
        b.mass = total;
        Ok(())
    }

    /// Follows a deforming mesh: new vertex positions (local frame, m, same
    /// topology) refresh the atlas (and the drag texels, if any) from its
    /// barycentrics (no re-bake) and the mass properties.
    pub fn deform<B: BodiesMut<Handle = H> + ?Sized>(
        &mut self,
        id: SoakId,
        positions: &[Point3<f64>],
        bodies: &mut B,
    ) -> Result<(), SoakError> {
        let b = self.bodies.get_mut(id.0).ok_or(SoakError::UnknownId(id.0))?;
        let mut atlas = soak_bake::Atlas::clone(&b.atlas);
        atlas.refresh(positions).map_err(|source| SoakError::Bake {
            name: b.name.clone(),
            source,
        })?;
        // The drag texels follow the same vertices (a copy of their own:
        // other bodies may share them).
        let drag_texels = match &b.effects.drag_texels {
            Some(texels) => {
                let mut texels = soak_hydro::DragTexels::clone(texels);
                texels.refresh(positions).map_err(|source| SoakError::Bake {
                    name: b.name.clone(),
                    source,
                })?;
                Some(Arc::new(texels))
            }
            None => None,
        };
        let mass = b
            .mass_model
            .mass_properties(&atlas)
            .map_err(|source| SoakError::Hydro {
                name: b.name.clone(),
                source,
            })?;
        let total = with_extra(&mass, b.extra_mass.as_ref());
        let shape = Shape::of(&atlas);
        check_not_too_light(&b.name, total.mass, &b.effects, &self.water, shape.volume)?;
        push_mass(&b.name, bodies, b.handle, &total)?;
        if b.tiled.is_some() {
            b.tiled = Some(Arc::new(TiledAtlas::new(&atlas)));
        }
        if let Some(w) = &mut b.effects.wetting {
            // The texels moved in object space: rebin the diffusion field.
            w.refresh_field();
        }
        #[cfg(feature = "gpu")]
        if let Some(gpu) = &mut self.gpu {
            gpu.deform(id.0, positions)?;
        }
        b.shape = shape;
        b.atlas = Arc::new(atlas);
        b.effects.drag_texels = drag_texels;
        b.model_mass = mass;
        b.mass = total;
        Ok(())
    }
    /// Stops driving body `id` (its engine body removed, or the user done
    /// with it): its effects and the state they hold (liquid texture,
    /// liquid graph, its press on the waves) are dropped, nothing is
    /// evaluated, flooded or wetted for it from then on, and, if `bodies`
    /// still has it, the engine is handed a zero force and torque (an
    /// engine's forces persist: Rapier's do). Its id stays taken (ids are
    /// never reused) and its atlas is kept while other bodies share it.
    ///
    /// # Errors
    /// An unknown id.
    pub fn retire<B: BodiesMut<Handle = H> + ?Sized>(
        &mut self,
        id: SoakId,
        bodies: &mut B,
    ) -> Result<(), SoakError> {
        let b = self.bodies.get_mut(id.0).ok_or(SoakError::UnknownId(id.0))?;
        b.retire();
        bodies.set_wrench(b.handle, &Wrench::default());
        b.forces = HydroForces::default();
        b.applied = Wrench::default();
        b.added_force = Wrench::default();
        if let Some(w) = self.waves.as_deref_mut()
            && let Some(own) = w.own.get_mut(id.0)
        {
            own.clear();
        }
        Ok(())
    }
}

/// Refuses a wetting state made for an atlas of another size.
pub(crate) fn check_wetting(name: &str, atlas: &soak_bake::Atlas, w: &Wetting) -> Result<(), SoakError> {
    if w.texels() == atlas.len() {
        return Ok(());
    }
    Err(SoakError::Wet {
        name: name.to_string(),
        source: soak_wet::WetError::AtlasMismatch {
            state: w.texels(),
            atlas: atlas.len(),
        },
    })
}

/// Why `model` does not fit a body of `mass` (kg) in `water`, if it does
/// not: a density other than the water's (relative 1e-6) or a gravity
/// (relative 1e-3: 9.81 against the standard 9.80665 passes), a
/// mass more than 1 % off the one it was baked for (it would float at
/// another draft).
pub(crate) fn radiation_mismatch(
    model: &soak_seakeeping::RadiationModel,
    water: &soak_hydro::Water,
    mass: f64,
) -> Option<String> {
    let off = |a: f64, b: f64, tolerance: f64| (a - b).abs() > tolerance * b.abs() || a.is_nan();
    if off(model.density(), water.density, 1e-6) {
        return Some(format!(
            "baked for a density of {} kg/m³, the water's is {} kg/m³",
            model.density(),
            water.density
        ));
    }
    if off(model.gravity(), water.gravity, 1e-3) {
        return Some(format!(
            "baked for a gravity of {} m/s², the water's is {} m/s²",
            model.gravity(),
            water.gravity
        ));
    }
    if off(model.mass(), mass, 0.01) {
        return Some(format!(
            "baked for a mass of {} kg, the body's mass model gives {} kg",
            model.mass(),
            mass
        ));
    }
    None
}

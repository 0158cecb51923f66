//! The liquid of a [`Driver`]'s bodies between steps: turning wetting on
//! and off, the liquid graph inside a flooding body (ballast, the liquid's
//! density, its mass handed to the engine), and holes in its wall.

use nalgebra::Point3;
use soak_bake::Atlas;
use soak_graph::{Flooding, Permeability};
use soak_hydro::MassProperties;
use soak_wet::Wetting;

use crate::body::SoakBody;
use crate::config::SoakId;
use crate::driver::{Driver, Impact};
use crate::engine::{Bodies, BodiesMut, Handle};
use crate::error::SoakError;
use crate::registry::check_wetting;

impl<H: Handle> Driver<H> {
    /// Turns wetting on for a body with `Some(state)` (made for the body's
    /// atlas, e.g. `Wetting::new(body.atlas(), Material::wood(),
    /// Liquid::water())`, and keeping the liquid it already holds), or off
    /// with `None`, which drops the state and everything it allocated. A
    /// body registers with wetting through [`Effects::with_wetting`](crate::Effects::with_wetting).
    ///
    /// # Errors
    /// An unknown id; a state made for an atlas of another size.
    pub fn set_wetting(&mut self, id: SoakId, wetting: Option<Wetting>) -> Result<(), SoakError> {
        let b = self.bodies.get_mut(id.0).ok_or(SoakError::UnknownId(id.0))?;
        if let Some(w) = &wetting {
            check_wetting(&b.name, &b.atlas, w)?;
        }
        b.effects.wetting = wetting.map(Box::new);
        b.wet_report = soak_wet::StepReport::default();
        Ok(())
    }

    /// A body's wetting state, if it has one.
    pub fn wetting(&self, id: SoakId) -> Option<&Wetting> {
        self.bodies.get(id.0).and_then(SoakBody::wetting)
    }

    /// A body's wetting state, to splash, paint or change its settings
    /// (with the body's atlas: [`SoakBody::atlas`]).
    pub fn wetting_mut(&mut self, id: SoakId) -> Option<&mut Wetting> {
        self.bodies
            .get_mut(id.0)
            .and_then(|b| b.effects.wetting.as_deref_mut())
    }

    /// A body's liquid texture, if it has wetting: `h_i` per texel in atlas
    /// order, m³/m² = m. [`soak_wet::liquid_texture`] lays it out as an
    /// image, [`soak_wet::write_liquid_png`] writes it in pseudo-colour.
    pub fn liquid_texture(&self, id: SoakId) -> Option<&[f64]> {
        self.bodies.get(id.0).and_then(SoakBody::liquid)
    }

    /// The liquid graph inside a body, if it has flooding.
    pub fn flooding(&self, id: SoakId) -> Option<&Flooding> {
        self.bodies.get(id.0).and_then(SoakBody::flooding)
    }

    /// The liquid graph inside a body, to punch a hole
    /// ([`Flooding::permeability_mut`], or [`Driver::punch`]) or
    /// pour water ([`Flooding::pour`]); call
    /// [`Driver::sync_liquid_mass`] after pouring if the body must
    /// feel it before the next step.
    pub fn flooding_mut(&mut self, id: SoakId) -> Option<&mut Flooding> {
        self.bodies
            .get_mut(id.0)
            .and_then(|b| b.effects.flooding.as_deref_mut())
    }

    /// Punches a hole in a flooding body's hull: the wall's permeability
    /// becomes `kappa` (m) within `radius` (m) of `centre` (the mesh's own
    /// frame, m: `[x, y, z]` or a point). Returns the texels it covers; 0 for a sealed liquid graph, which
    /// has no wall ([`Flooding::sealed`]).
    ///
    /// # Errors
    /// An unknown id, a body without flooding, an invalid region or
    /// permeability.
    pub fn punch(
        &mut self,
        id: SoakId,
        centre: impl Into<Point3<f64>>,
        radius: f64,
        kappa: f64,
    ) -> Result<usize, SoakError> {
        let centre = centre.into();
        self.change_wall(id, |p, atlas| p.paint(atlas, centre, radius, kappa))
    }

    /// Changes a flooding body's wall with `change`; 0 for a sealed liquid
    /// graph, which has none.
    fn change_wall(
        &mut self,
        id: SoakId,
        change: impl FnOnce(&mut Permeability, &Atlas) -> Result<usize, soak_graph::PermeabilityError>,
    ) -> Result<usize, SoakError> {
        let b = self.bodies.get_mut(id.0).ok_or(SoakError::UnknownId(id.0))?;
        let flooding = b
            .effects
            .flooding
            .as_mut()
            .ok_or_else(|| SoakError::NoFlooding { name: b.name.clone() })?;
        let Some(p) = flooding.permeability_mut() else {
            return Ok(0);
        };
        change(p, &b.atlas).map_err(|source| SoakError::Permeability {
            name: b.name.clone(),
            source,
        })
    }

    /// Opens a hole in a flooding body's wall: every texel within `radius`
    /// (m) of `centre` (the mesh's own frame, m) becomes an opening, through
    /// which water flows freely (the orifice law, see
    /// [`soak_graph::Permeability`]) from the next step. Returns the texels
    /// it covers (0 when the region misses the surface, or for a sealed
    /// liquid graph, which has no wall). A hole opened during a run is part
    /// of the saved state.
    ///
    /// # Errors
    /// An unknown id, a body without flooding, an invalid region.
    pub fn open_hole(
        &mut self,
        id: SoakId,
        centre: impl Into<Point3<f64>>,
        radius: f64,
    ) -> Result<usize, SoakError> {
        let centre = centre.into();
        self.change_wall(id, |p, atlas| p.open(atlas, centre, radius))
    }

    /// [`Driver::open_hole`] at a world point (m): where a shell
    /// struck the hull, as the body stands now in `bodies`.
    ///
    /// # Errors
    /// As [`Driver::open_hole`]; a body the engine does not have.
    pub fn open_hole_at<B: Bodies<Handle = H> + ?Sized>(
        &mut self,
        id: SoakId,
        bodies: &B,
        point: impl Into<Point3<f64>>,
        radius: f64,
    ) -> Result<usize, SoakError> {
        let b = self.bodies.get(id.0).ok_or(SoakError::UnknownId(id.0))?;
        let pose = bodies
            .body(b.handle)
            .ok_or_else(|| SoakError::MissingBody { name: b.name.clone() })?
            .pose;
        let local = pose.inverse_transform_point(&point.into());
        self.open_hole(id, local, radius)
    }

    /// The holes hard contacts opened in the last step ([`ImpactHoles`](crate::ImpactHoles)).
    pub fn impacts(&self) -> &[Impact] {
        &self.impacts
    }

    /// Sets the fixed mass a flooding body carries with its liquid (ballast,
    /// cargo; local frame), or none, and hands the total to the engine at once.
    ///
    /// # Errors
    /// An unknown id, a body without flooding, a body the engine does not have,
    /// non-finite ballast.
    pub fn set_ballast<B: BodiesMut<Handle = H> + ?Sized>(
        &mut self,
        id: SoakId,
        ballast: Option<MassProperties>,
        bodies: &mut B,
    ) -> Result<(), SoakError> {
        let b = self.flooding_body(id)?;
        if let Some(m) = &ballast
            && !m.is_finite()
        {
            return Err(SoakError::MassProperties {
                name: b.name.clone(),
                reason: format!("ballast {m:?} is not finite"),
            });
        }
        b.flood.ballast = ballast;
        self.sync_liquid_mass(id, bodies)
    }

    /// Sets the density of the liquid inside a flooding body, kg/m³
    /// (default: the surrounding fluid's, [`Water::density`](soak_hydro::Water::density)), and hands
    /// its mass to the engine at once.
    ///
    /// # Errors
    /// An unknown id, a body without flooding, a body the engine does not have, a
    /// density that is not a finite number ≥ 0.
    pub fn set_liquid_density<B: BodiesMut<Handle = H> + ?Sized>(
        &mut self,
        id: SoakId,
        density: f64,
        bodies: &mut B,
    ) -> Result<(), SoakError> {
        let b = self.flooding_body(id)?;
        if !(density.is_finite() && density >= 0.0) {
            return Err(SoakError::LiquidDensity {
                name: b.name.clone(),
                density,
            });
        }
        b.flood.density = Some(density);
        self.sync_liquid_mass(id, bodies)
    }

    /// The liquid inside a flooding body: its mass properties (local frame;
    /// kg, m, kg·m²) at its density ([`SoakBody::liquid_density`]).
    pub fn liquid_mass(&self, id: SoakId) -> Option<MassProperties> {
        self.bodies.get(id.0)?.liquid_mass(&self.water)
    }

    /// Hands a flooding body's liquid plus ballast to the engine now, as the
    /// mass it carries besides its model ([`Driver::set_extra_mass`]).
    /// [`Driver::flood`] does it whenever the liquid changed.
    ///
    /// # Errors
    /// An unknown id, a body without flooding, a body the engine does not have,
    /// invalid mass properties.
    pub fn sync_liquid_mass<B: BodiesMut<Handle = H> + ?Sized>(
        &mut self,
        id: SoakId,
        bodies: &mut B,
    ) -> Result<(), SoakError> {
        let b = self.bodies.get(id.0).ok_or(SoakError::UnknownId(id.0))?;
        let extra = b
            .flooding_extra(&self.water)
            .ok_or_else(|| SoakError::NoFlooding { name: b.name.clone() })?;
        self.set_extra_mass(id, extra, bodies)
    }

    /// A registered body with flooding.
    fn flooding_body(&mut self, id: SoakId) -> Result<&mut SoakBody<H>, SoakError> {
        let b = self.bodies.get_mut(id.0).ok_or(SoakError::UnknownId(id.0))?;
        if b.effects.flooding.is_none() {
            return Err(SoakError::NoFlooding { name: b.name.clone() });
        }
        Ok(b)
    }
}

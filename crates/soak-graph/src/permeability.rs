//! The permeability channel: one value per atlas texel (the thesis'
//! *Textura de Permeabilidad*, TPM).

use nalgebra::Point3;
use serde::{Deserialize, Serialize};
use soak_bake::Atlas;

use crate::error::PermeabilityError;

/// κ = k/L per texel, m, and the texels that are **openings**. Serialises
/// as the list of values (with the openings beside them when there are
/// any); deserialising validates them.
///
/// # Openings
///
/// A texel can instead be an opening: a hole in the wall, or the cap over
/// an open container's rim ([`soak_bake::cap_openings`]), through which
/// liquid flows freely rather than seeping. Each opening texel of area `a`
/// at depth `d` passes the orifice flow
///
/// ```text
/// V = C_d a √(2 g |Δh|) Δt · sign(Δh),    Δh = max(d, 0) − max(h_n − y, 0)
/// ```
///
/// (`C_d` the discharge coefficient of [`FlowOptions`](crate::FlowOptions),
/// `h_n` the inside head): summed over an opening that lies under water it
/// is the orifice law `Q = C_d A √(2 g Δh)`; over one the surface cuts
/// (a rim partly under water) it is the weir law's integral
/// `Q = C_d ∫ b(z) √(2 g (H − z)) dz`.
///
/// # Units
///
/// Darcy's law puts the wall thickness `L` under the pressure drop: the flux
/// through an area `a` is `Q = (k a / μ) Δp / L` with `k` the intrinsic
/// permeability (m²). The thesis folds `L` into the texture, so the channel
/// stores **κ = k / L in metres**, and texel `i` at depth `d_i` passes
///
/// ```text
/// V_i = (κ_i a_i / μ) ρ g d_i Δt        [m · m² / (Pa·s) · Pa · s = m³]
/// ```
///
/// per step. Some orders of magnitude (water, μ = 10⁻³ Pa·s):
///
/// | surface | κ (m) |
/// |---|---|
/// | watertight hull | 0 |
/// | a hole, passing about what an open orifice of its area passes at 0.25 m depth (`a √(2 g d)`) | ≈ 10⁻⁶ |
/// | a leaking seam | 10⁻⁹ … 10⁻⁸ |
/// | felt or plush fabric a few mm thick | 10⁻¹⁰ … 10⁻⁹ |
///
/// The channel can come from an image laid over the UV square
/// ([`Permeability::from_image`]), from painted regions ("every texel within
/// 0.3 m of this point", [`Permeability::paint`]), and can change while the
/// simulation runs (a hole punched: [`Permeability::paint`] again, or
/// [`Permeability::set`]). It keeps the list of permeable texels so the
/// per-step loop only visits those.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(into = "Repr", try_from = "Repr")]
pub struct Permeability {
    values: Vec<f64>,
    permeable: Vec<u32>,
    /// Opening texels, ascending.
    openings: Vec<u32>,
}

/// The serialised form: the values alone (as before openings existed), or
/// the values and the openings.
#[derive(Serialize, Deserialize)]
#[serde(untagged)]
enum Repr {
    Values(Vec<f64>),
    Full { values: Vec<f64>, openings: Vec<u32> },
}

impl From<Permeability> for Repr {
    fn from(p: Permeability) -> Self {
        if p.openings.is_empty() {
            Repr::Values(p.values)
        } else {
            Repr::Full {
                values: p.values,
                openings: p.openings,
            }
        }
    }
}

impl TryFrom<Repr> for Permeability {
    type Error = PermeabilityError;
    fn try_from(repr: Repr) -> Result<Self, Self::Error> {
        let mut p = Self::try_from(match &repr {
            Repr::Values(v) | Repr::Full { values: v, .. } => v.clone(),
        })?;
        if let Repr::Full { mut openings, .. } = repr {
            let len = p.values.len();
            if let Some(&texel) = openings.iter().find(|&&i| i as usize >= len) {
                return Err(PermeabilityError::NoSuchTexel {
                    texel: texel as usize,
                    len,
                });
            }
            openings.sort_unstable();
            openings.dedup();
            p.openings = openings;
            p.reindex();
        }
        Ok(p)
    }
}

impl TryFrom<Vec<f64>> for Permeability {
    type Error = PermeabilityError;
    fn try_from(values: Vec<f64>) -> Result<Self, Self::Error> {
        for (i, &v) in values.iter().enumerate() {
            check(i, v)?;
        }
        let mut p = Self {
            values,
            permeable: Vec::new(),
            openings: Vec::new(),
        };
        p.reindex();
        Ok(p)
    }
}

fn check(texel: usize, value: f64) -> Result<(), PermeabilityError> {
    if value.is_finite() && value >= 0.0 {
        Ok(())
    } else {
        Err(PermeabilityError::Value { texel, value })
    }
}

impl Permeability {
    /// A watertight surface: κ = 0 on every texel of `atlas`.
    pub fn watertight(atlas: &Atlas) -> Self {
        Self {
            values: vec![0.0; atlas.len()],
            permeable: Vec::new(),
            openings: Vec::new(),
        }
    }

    /// A watertight wall whose caps ([`Atlas::is_opening`]: the rims of an
    /// open mesh closed by [`soak_bake::cap_openings`]) are openings.
    pub fn open_mesh(atlas: &Atlas) -> Self {
        let mut p = Self::watertight(atlas);
        p.openings = atlas.opening_samples();
        p
    }

    /// The same κ (m) on every texel of `atlas` (a fabric).
    ///
    /// # Errors
    /// [`PermeabilityError::Value`] for a negative or non-finite κ.
    pub fn uniform(atlas: &Atlas, kappa: f64) -> Result<Self, PermeabilityError> {
        check(0, kappa)?;
        let mut p = Self {
            values: vec![kappa; atlas.len()],
            permeable: Vec::new(),
            openings: Vec::new(),
        };
        p.reindex();
        Ok(p)
    }

    /// One κ per texel of `atlas`, m.
    ///
    /// # Errors
    /// A wrong length, or the first negative or non-finite value.
    pub fn from_values(atlas: &Atlas, values: Vec<f64>) -> Result<Self, PermeabilityError> {
        if values.len() != atlas.len() {
            return Err(PermeabilityError::Length {
                len: values.len(),
                texels: atlas.len(),
            });
        }
        Self::try_from(values)
    }

    /// From a `width`×`height` single-channel image over the UV square (row
    /// `y` holds `v·H ∈ [y, y+1)`, as [`Atlas::sample_image`]), nearest
    /// pixel, times `scale` (m): an image in [0, 1] with `scale` the κ of
    /// its white pixels. The image may have another resolution than the atlas.
    ///
    /// # Errors
    /// A zero side or wrong pixel count; a negative or non-finite pixel or scale.
    pub fn from_image(
        atlas: &Atlas,
        image: &[f32],
        width: u32,
        height: u32,
        scale: f64,
    ) -> Result<Self, PermeabilityError> {
        if width == 0 || height == 0 || image.len() as u64 != width as u64 * height as u64 {
            return Err(PermeabilityError::ImageSize {
                width,
                height,
                len: image.len(),
            });
        }
        check(0, scale)?;
        if let Some(i) = image.iter().position(|v| !(v.is_finite() && *v >= 0.0)) {
            return Err(PermeabilityError::Value {
                texel: i,
                value: image[i] as f64,
            });
        }
        let values = atlas
            .sample_image(image, width, height)
            .into_iter()
            .map(|v| v as f64 * scale)
            .collect();
        Self::from_values(atlas, values)
    }

    /// Sets κ (m) on every texel of `atlas` within `radius` (m) of `centre`
    /// (object space, m) — a painted region, or a hole punched at run time.
    /// Returns how many texels it covered.
    ///
    /// # Errors
    /// A non-finite centre or radius, a negative radius or κ, or a channel
    /// made for another atlas.
    pub fn paint(
        &mut self,
        atlas: &Atlas,
        centre: Point3<f64>,
        radius: f64,
        kappa: f64,
    ) -> Result<usize, PermeabilityError> {
        self.fits(atlas)?;
        check(0, kappa)?;
        if !(centre.iter().all(|c| c.is_finite()) && radius.is_finite() && radius >= 0.0) {
            return Err(PermeabilityError::Region {
                centre: [centre.x, centre.y, centre.z],
                radius,
            });
        }
        let r2 = radius * radius;
        let mut count = 0;
        for (i, v) in self.values.iter_mut().enumerate() {
            if (atlas.position(i) - centre).norm_squared() <= r2 {
                *v = kappa;
                count += 1;
            }
        }
        self.reindex();
        Ok(count)
    }

    /// Makes every texel of `atlas` within `radius` (m) of `centre` (object
    /// space, m) an opening (a hole torn in the wall; see *Openings*).
    /// Returns how many texels it covered (0 when the region misses the
    /// surface: a radius below the texel spacing may).
    ///
    /// # Errors
    /// A non-finite centre or radius, a negative radius, or a channel made
    /// for another atlas.
    pub fn open(
        &mut self,
        atlas: &Atlas,
        centre: Point3<f64>,
        radius: f64,
    ) -> Result<usize, PermeabilityError> {
        self.fits(atlas)?;
        if !(centre.iter().all(|c| c.is_finite()) && radius.is_finite() && radius >= 0.0) {
            return Err(PermeabilityError::Region {
                centre: [centre.x, centre.y, centre.z],
                radius,
            });
        }
        let r2 = radius * radius;
        let hit: Vec<u32> = (0..atlas.len() as u32)
            .filter(|&i| (atlas.position(i as usize) - centre).norm_squared() <= r2)
            .collect();
        let count = hit.len();
        self.open_texels(hit)?;
        Ok(count)
    }

    /// Makes the given texels openings.
    ///
    /// # Errors
    /// An index out of range (nothing changes).
    pub fn open_texels(&mut self, texels: impl IntoIterator<Item = u32>) -> Result<(), PermeabilityError> {
        let len = self.values.len();
        let texels: Vec<u32> = texels.into_iter().collect();
        if let Some(&texel) = texels.iter().find(|&&i| i as usize >= len) {
            return Err(PermeabilityError::NoSuchTexel {
                texel: texel as usize,
                len,
            });
        }
        self.openings.extend(texels);
        self.openings.sort_unstable();
        self.openings.dedup();
        self.reindex();
        Ok(())
    }

    /// Indices of the opening texels, ascending (see *Openings*).
    pub fn openings(&self) -> &[u32] {
        &self.openings
    }

    /// Sets texel `texel`'s κ, m.
    ///
    /// # Errors
    /// An index out of range or a negative or non-finite κ.
    pub fn set(&mut self, texel: usize, kappa: f64) -> Result<(), PermeabilityError> {
        check(texel, kappa)?;
        let len = self.values.len();
        let v = self
            .values
            .get_mut(texel)
            .ok_or(PermeabilityError::NoSuchTexel { texel, len })?;
        let was = *v > 0.0;
        *v = kappa;
        if was != (kappa > 0.0) {
            self.reindex();
        }
        Ok(())
    }

    /// Checks the channel has one value per texel of `atlas`.
    ///
    /// # Errors
    /// [`PermeabilityError::Length`].
    pub fn fits(&self, atlas: &Atlas) -> Result<(), PermeabilityError> {
        if self.values.len() == atlas.len() {
            Ok(())
        } else {
            Err(PermeabilityError::Length {
                len: self.values.len(),
                texels: atlas.len(),
            })
        }
    }

    /// κ per texel, m.
    pub fn values(&self) -> &[f64] {
        &self.values
    }

    /// κ of texel `i`, m (0 outside the channel).
    pub fn get(&self, i: usize) -> f64 {
        self.values.get(i).copied().unwrap_or(0.0)
    }

    /// Number of texels.
    pub fn len(&self) -> usize {
        self.values.len()
    }

    /// Whether the channel has no texel.
    pub fn is_empty(&self) -> bool {
        self.values.is_empty()
    }

    /// Indices of the texels with κ > 0 that are not openings, ascending:
    /// the ones Darcy's law applies to.
    pub fn permeable(&self) -> &[u32] {
        &self.permeable
    }

    /// Whether no texel lets liquid through (no κ > 0, no opening).
    pub fn is_watertight(&self) -> bool {
        self.permeable.is_empty() && self.openings.is_empty()
    }

    /// Σ κ_i a_i over `atlas`, m³: the Darcy conductance of the whole
    /// surface times μ / (ρ g).
    pub fn conductance(&self, atlas: &Atlas) -> f64 {
        self.permeable
            .iter()
            .map(|&i| self.values[i as usize] * atlas.areas().get(i as usize).copied().unwrap_or(0.0) as f64)
            .sum()
    }

    fn reindex(&mut self) {
        let openings = &self.openings;
        self.permeable = (0..self.values.len() as u32)
            .filter(|&i| self.values[i as usize] > 0.0 && openings.binary_search(&i).is_err())
            .collect();
    }
}

//! The permeability channel: one value per atlas texel (the thesis'
//! *Textura de Permeabilidad*, TPM).

use nalgebra::Point3;
use serde::{Deserialize, Serialize};
use soak_bake::Atlas;

use crate::error::PermeabilityError;

/// κ = k/L per texel, m. Serialises as the list of values; deserialising
/// validates them.
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
#[serde(into = "Vec<f64>", try_from = "Vec<f64>")]
pub struct Permeability {
    values: Vec<f64>,
    permeable: Vec<u32>,
}

impl From<Permeability> for Vec<f64> {
    fn from(p: Permeability) -> Self {
        p.values
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
        }
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

    /// Indices of the texels with κ > 0, ascending.
    pub fn permeable(&self) -> &[u32] {
        &self.permeable
    }

    /// Whether no texel lets liquid through.
    pub fn is_watertight(&self) -> bool {
        self.permeable.is_empty()
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
        self.permeable = (0..self.values.len() as u32)
            .filter(|&i| self.values[i as usize] > 0.0)
            .collect();
    }
}

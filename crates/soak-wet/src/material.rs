//! What a surface is made of and what soaks into it: the parameters of the
//! thesis' Table 5.1 with their SI units (the table is on [`Material`]).

use serde::{Deserialize, Serialize};

use crate::error::{WetError, non_negative, positive};

/// A porous surface material.
///
/// Liquid is stored per texel as a volume per area `h` (m³/m², that is
/// metres of liquid film), between 0 and [`Material::saturation`].
///
/// | Table 5.1 | here | unit |
/// |---|---|---|
/// | μ, viscosity of the liquid | [`Liquid::viscosity`] | Pa·s |
/// | k_L, evaporation rate of the liquid | [`Liquid::evaporation_rate`] | 1/(m·s) |
/// | C_M, permeability of the material | [`Material::permeability`] | m² |
/// | (L, wall thickness, folded into C_M by the thesis) | [`Material::thickness`] | m |
/// | (h_max, saturation) | [`Material::saturation`] | m³/m² = m |
/// | D, diffusion coefficient | [`crate::Diffusion::coefficient`] | m²/s |
/// | f_env, k_T, k_h, k_w | [`crate::Environment`], [`crate::EnvironmentResponse`] | K, –, m/s |
///
/// The liquid's density and gravity, which make the pressure `ρ g d` that
/// drives absorption, are the [`soak_hydro::Water`]'s.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct Material {
    /// Intrinsic permeability C_M (thesis Table 5.1), m². Drives absorption
    /// (with [`Material::thickness`]) and evaporation. Zero makes the
    /// surface impermeable: it neither absorbs nor dries.
    pub permeability: f64,
    /// Thickness L of the porous layer the liquid crosses, m. Darcy's law
    /// divides the pressure drop by it; absorption uses `κ = C_M / L`, in
    /// metres (permeability in m² over thickness in m), as the liquid graph's
    /// ingress does. The thesis folds L into its permeability texture.
    pub thickness: f64,
    /// Saturation `h_max`: the most liquid a unit of surface holds,
    /// m³/m² = m (porosity times the depth that wets, for a porous layer).
    pub saturation: f64,
}

impl Material {
    /// κ = C_M / L, m: the permeability over the layer thickness that
    /// absorption uses.
    pub fn kappa(&self) -> f64 {
        self.permeability / self.thickness
    }

    /// Checks every field is finite and in range (permeability ≥ 0,
    /// thickness > 0, saturation > 0).
    pub fn validate(&self) -> Result<(), WetError> {
        non_negative("material.permeability", self.permeability)?;
        positive("material.thickness", self.thickness)?;
        positive("material.saturation", self.saturation)?;
        Ok(())
    }

    /// Beach sand: C_M = 1e-11 m² (clean medium sand), a 1 cm layer of
    /// porosity 0.35 (saturation 3.5 mm).
    pub fn sand() -> Self {
        Self {
            permeability: 1e-11,
            thickness: 0.01,
            saturation: 3.5e-3,
        }
    }

    /// Sawn softwood across the grain: C_M = 1e-13 m², 5 mm wetted, 1 mm of
    /// liquid at saturation.
    pub fn wood() -> Self {
        Self {
            permeability: 1e-13,
            thickness: 5e-3,
            saturation: 1e-3,
        }
    }

    /// Weathered granite: C_M = 1e-15 m², 2 mm wetted, 0.2 mm at saturation.
    pub fn rock() -> Self {
        Self {
            permeability: 1e-15,
            thickness: 2e-3,
            saturation: 2e-4,
        }
    }

    /// Cotton fabric: C_M = 1e-10 m², 1 mm thick, 0.6 mm at saturation.
    pub fn cotton() -> Self {
        Self {
            permeability: 1e-10,
            thickness: 1e-3,
            saturation: 6e-4,
        }
    }
}

/// The liquid that wets the surface.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct Liquid {
    /// Dynamic viscosity μ, Pa·s.
    pub viscosity: f64,
    /// Evaporation rate k_L (thesis Eq. 5.8, Table 5.1), 1/(m·s): with the
    /// permeability C_M (m²) and the environment factor it gives the drying
    /// rate `f_env k_L C_M` in m/s of liquid film.
    pub evaporation_rate: f64,
}

impl Liquid {
    /// Fresh water at 20 °C: μ = 1.0e-3 Pa·s; k_L = 1e4 1/(m·s), so sand
    /// (C_M = 1e-11 m²) dries at 1e-7 m/s (0.36 mm an hour, 8.6 mm a day)
    /// in dry still air at 20 °C.
    pub fn water() -> Self {
        Self {
            viscosity: 1.0e-3,
            evaporation_rate: 1e4,
        }
    }

    /// Ethanol at 20 °C: μ = 1.2e-3 Pa·s and about 3× water's evaporation rate.
    pub fn ethanol() -> Self {
        Self {
            viscosity: 1.2e-3,
            evaporation_rate: 3e4,
        }
    }

    /// Checks viscosity > 0 and evaporation rate ≥ 0, both finite.
    pub fn validate(&self) -> Result<(), WetError> {
        positive("liquid.viscosity", self.viscosity)?;
        non_negative("liquid.evaporation_rate", self.evaporation_rate)?;
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn presets_are_valid() {
        for m in [
            Material::sand(),
            Material::wood(),
            Material::rock(),
            Material::cotton(),
        ] {
            m.validate().unwrap();
        }
        Liquid::water().validate().unwrap();
        Liquid::ethanol().validate().unwrap();
        assert!((Material::sand().kappa() - 1e-9).abs() < 1e-24);
    }

    #[test]
    fn bad_values_are_named() {
        let m = Material {
            thickness: 0.0,
            ..Material::sand()
        };
        let e = m.validate().unwrap_err().to_string();
        assert!(e.contains("material.thickness"), "{e}");
        let l = Liquid {
            viscosity: f64::NAN,
            ..Liquid::water()
        };
        assert!(l.validate().unwrap_err().to_string().contains("liquid.viscosity"));
    }
}

//! A scene read from its file and checked: [`LoadedScene`].

use std::path::{Path, PathBuf};

use super::Scene;
use super::bodies::{BodySpec, MassSpec, ResolutionSpec};
use super::key_path::line_of;
use super::liquid_graph::GraphSpec;
use super::water::WaterKind;
use super::wetting::{InitialLiquid, LiquidSpec, MaterialSpec, WettingSpec};
use crate::error::SceneError;

/// A scene with the file it came from (for relative paths and messages).
#[derive(Clone, Debug)]
pub struct LoadedScene {
    /// The scene.
    pub scene: Scene,
    /// The file, or a label for an embedded scene.
    pub path: PathBuf,
    /// The TOML text (for locating keys in messages).
    pub text: String,
}

impl LoadedScene {
    /// Reads and validates a scene file.
    pub fn from_file(path: &Path) -> Result<Self, SceneError> {
        let text = std::fs::read_to_string(path).map_err(|source| SceneError::Io {
            path: path.to_path_buf(),
            source,
        })?;
        Self::from_str(&text, path)
    }

    /// Parses and validates scene text; `path` names it in messages and
    /// anchors relative mesh paths.
    pub fn from_str(text: &str, path: &Path) -> Result<Self, SceneError> {
        let scene: Scene = toml::from_str(text).map_err(|e| SceneError::Parse {
            path: path.to_path_buf(),
            message: e.to_string().trim_end().to_string(),
        })?;
        let loaded = Self {
            scene,
            path: path.to_path_buf(),
            text: text.to_string(),
        };
        loaded.validate()?;
        Ok(loaded)
    }

    /// The 1-based line of a dotted key path (`bodies[1].mass.density`), or of
    /// its nearest existing parent.
    pub fn line_of(&self, key: &str) -> usize {
        line_of(&self.text, key)
    }

    /// An [`SceneError::Invalid`] for `key`.
    pub fn invalid(&self, key: &str, message: impl Into<String>) -> SceneError {
        SceneError::Invalid {
            path: self.path.clone(),
            line: self.line_of(key),
            key: key.to_string(),
            message: message.into(),
        }
    }

    /// The mesh of body `i` as the simulation takes it: its file (relative
    /// to the scene's) or `builtin:` mesh, unwrapped where the body asks.
    ///
    /// # Errors
    /// [`SceneError::Body`] naming the body and its line: no such body, a
    /// mesh that does not load or unwrap.
    pub fn body_mesh(&self, i: usize) -> Result<soak_bake::Mesh, SceneError> {
        let key = format!("bodies[{i}].mesh");
        let body_err = |name: &str, message: String| SceneError::Body {
            path: self.path.clone(),
            line: self.line_of(&key),
            body: name.to_string(),
            message,
        };
        let b = self
            .scene
            .bodies
            .get(i)
            .ok_or_else(|| body_err(&format!("#{i}"), "no such body in the scene".to_string()))?;
        let source = if b.mesh.starts_with("builtin:") {
            b.mesh.clone()
        } else {
            self.resolve(&b.mesh).to_string_lossy().into_owned()
        };
        let mut mesh = soak_bake::load_mesh(&source).map_err(|e| body_err(&b.name, e.to_string()))?;
        if b.open {
            mesh = open_mesh(mesh).map_err(|e| body_err(&b.name, e.to_string()))?.0;
        }
        if !b.unwrap {
            return Ok(mesh);
        }
        soak_bake::unwrap(&mesh, soak_bake::UnwrapOptions::default())
            .map(|(m, _)| m)
            .map_err(|e| body_err(&b.name, e.to_string()))
    }

    /// The closed mesh of body `i`'s walls when it is a thick-walled
    /// container (`open = true` on a closed mesh whose cavity
    /// [`soak_bake::cap_cavities`] found: its solid is the walls, while
    /// [`LoadedScene::body_mesh`] is the filled shape); `None` otherwise.
    ///
    /// # Errors
    /// As [`LoadedScene::body_mesh`].
    pub fn body_walls(&self, i: usize) -> Result<Option<soak_bake::Mesh>, SceneError> {
        let Some(b) = self.scene.bodies.get(i).filter(|b| b.open) else {
            return Ok(None);
        };
        let key = format!("bodies[{i}].mesh");
        let err = |message: String| SceneError::Body {
            path: self.path.clone(),
            line: self.line_of(&key),
            body: b.name.clone(),
            message,
        };
        let source = if b.mesh.starts_with("builtin:") {
            b.mesh.clone()
        } else {
            self.resolve(&b.mesh).to_string_lossy().into_owned()
        };
        let mesh = soak_bake::load_mesh(&source).map_err(|e| err(e.to_string()))?;
        let Some(walls) = open_mesh(mesh).map_err(|e| err(e.to_string()))?.1 else {
            return Ok(None);
        };
        if !b.unwrap {
            return Ok(Some(walls));
        }
        soak_bake::unwrap(&walls, soak_bake::UnwrapOptions::default())
            .map(|(m, _)| Some(m))
            .map_err(|e| err(e.to_string()))
    }

    /// A path relative to the scene file.
    pub fn resolve(&self, relative: &str) -> PathBuf {
        let p = Path::new(relative);
        if p.is_absolute() {
            return p.to_path_buf();
        }
        self.path
            .parent()
            .map(|d| d.join(p))
            .unwrap_or_else(|| p.to_path_buf())
    }

    /// Checks one set of weather values; `key` names the table they are in.
    fn check_weather(
        &self,
        key: &str,
        temperature_c: f64,
        relative_humidity: f64,
        wind_speed: f64,
        rain_mm_per_hour: f64,
    ) -> Result<(), SceneError> {
        if !(temperature_c.is_finite() && temperature_c > -273.15) {
            return Err(self.invalid(
                &format!("{key}.temperature_c"),
                format!("must be a temperature above absolute zero in °C, not {temperature_c}"),
            ));
        }
        if !(0.0..=1.0).contains(&relative_humidity) {
            return Err(self.invalid(
                &format!("{key}.relative_humidity"),
                format!("must be a fraction in [0, 1], not {relative_humidity}"),
            ));
        }
        if !(wind_speed.is_finite() && wind_speed >= 0.0) {
            return Err(self.invalid(
                &format!("{key}.wind_speed"),
                format!("must be ≥ 0 m/s, not {wind_speed}"),
            ));
        }
        if !(rain_mm_per_hour.is_finite() && rain_mm_per_hour >= 0.0) {
            return Err(self.invalid(
                &format!("{key}.rain_mm_per_hour"),
                format!("must be ≥ 0 mm/h, not {rain_mm_per_hour}"),
            ));
        }
        Ok(())
    }

    fn validate(&self) -> Result<(), SceneError> {
        let s = &self.scene;
        let positive = |key: &str, v: f64| -> Result<(), SceneError> {
            if v.is_finite() && v > 0.0 {
                Ok(())
            } else {
                Err(self.invalid(key, format!("must be a positive number, not {v}")))
            }
        };
        let finite = |key: &str, v: &[f64]| -> Result<(), SceneError> {
            if v.iter().all(|x| x.is_finite()) {
                Ok(())
            } else {
                Err(self.invalid(key, format!("must be finite, not {v:?}")))
            }
        };
        positive("dt", s.dt)?;
        if s.dt > 0.25 {
            return Err(self.invalid("dt", format!("{} s is too long a step (at most 0.25 s)", s.dt)));
        }
        // `"forever"` reads as +∞.
        if s.duration.is_nan() || s.duration <= 0.0 {
            return Err(self.invalid(
                "duration",
                format!(
                    "must be a positive number of seconds or \"forever\", not {}",
                    s.duration
                ),
            ));
        }
        finite("gravity", &s.gravity)?;
        if s.output.every == 0 {
            return Err(self.invalid("output.every", "must be at least 1"));
        }
        if s.output.liquid_png_every == Some(0) {
            return Err(self.invalid("output.liquid_png_every", "must be at least 1"));
        }
        if let Some(e) = &s.environment {
            self.check_weather(
                "environment",
                e.temperature_c,
                e.relative_humidity,
                e.wind_speed,
                e.rain_mm_per_hour,
            )?;
            let mut last = 0.0;
            for (i, (at, [t, h, w, r])) in e.resolved_keys().into_iter().enumerate() {
                let key = format!("environment.keys[{i}]");
                if !(at.is_finite() && at > last) {
                    return Err(self.invalid(
                        &format!("{key}.at"),
                        format!(
                            "must be a time in s after the start and after the previous key ({last}), not {at}"
                        ),
                    ));
                }
                last = at;
                self.check_weather(&key, t, h, w, r)?;
            }
        }
        for (i, sp) in s.splash.iter().enumerate() {
            let key = format!("splash[{i}]");
            if !(sp.at.is_finite() && sp.at >= 0.0) {
                return Err(self.invalid(
                    &format!("{key}.at"),
                    format!("must be a time ≥ 0 s, not {}", sp.at),
                ));
            }
            if !sp.center.iter().all(|c| c.is_finite()) {
                return Err(self.invalid(&format!("{key}.center"), "must be three finite numbers, m"));
            }
            if !(sp.radius.is_finite() && sp.radius > 0.0) {
                return Err(self.invalid(
                    &format!("{key}.radius"),
                    format!("must be > 0 m, not {}", sp.radius),
                ));
            }
            if !(sp.volume.is_finite() && sp.volume >= 0.0) {
                return Err(self.invalid(
                    &format!("{key}.volume"),
                    format!("must be ≥ 0 m³, not {}", sp.volume),
                ));
            }
        }
        let w = &s.water;
        let kind = w.kind;
        let only = |key: &str, present: bool, kinds: &[WaterKind]| -> Result<(), SceneError> {
            if present && !kinds.contains(&kind) {
                Err(self.invalid(
                    &format!("water.{key}"),
                    format!("does not apply to water of kind {kind:?}"),
                ))
            } else {
                Ok(())
            }
        };
        only(
            "level",
            w.level.is_some(),
            &[WaterKind::Plane, WaterKind::Gerstner, WaterKind::Spectrum],
        )?;
        only("waves", w.waves.is_some(), &[WaterKind::Gerstner])?;
        only(
            "sampling",
            w.sampling.is_some(),
            &[WaterKind::Gerstner, WaterKind::Spectrum],
        )?;
        only(
            "velocity",
            w.velocity.is_some(),
            &[WaterKind::Gerstner, WaterKind::Spectrum],
        )?;
        only("band", w.band.is_some(), &[WaterKind::Spectrum])?;
        if let Some(r) = w.band
            && !(r.is_finite() && r > 0.0)
        {
            return Err(self.invalid(
                "water.band",
                format!("must be a positive number of body lengths, not {r}"),
            ));
        }
        for (key, present) in [
            ("spectrum", w.spectrum.is_some()),
            ("significant_height", w.significant_height.is_some()),
            ("peak_period", w.peak_period.is_some()),
            ("gamma", w.gamma.is_some()),
            ("direction_deg", w.direction_deg.is_some()),
            ("spreading", w.spreading.is_some()),
            ("seed", w.seed.is_some()),
            ("tile", w.tile.is_some()),
            ("cells", w.cells.is_some()),
            ("choppiness", w.choppiness.is_some()),
        ] {
            only(key, present, &[WaterKind::Spectrum])?;
        }
        if w.gamma.is_some() && w.spectrum == Some(crate::scene::SpectrumName::PiersonMoskowitz) {
            return Err(self.invalid("water.gamma", "applies to `spectrum = \"jonswap\"` only"));
        }
        if kind == WaterKind::Spectrum {
            for (key, present) in [
                ("significant_height", w.significant_height.is_some()),
                ("peak_period", w.peak_period.is_some()),
            ] {
                if !present {
                    return Err(self.invalid("water", format!("a spectral sea needs `{key}`")));
                }
            }
            let g = nalgebra::Vector3::from(s.gravity).norm().max(1e-9);
            match w.spectral_sea(g) {
                Ok(_) => {}
                Err(soak_hydro::WaterError::Parameter { name, value }) => {
                    let why = match name {
                        "cells" => format!(
                            "{value} is not a power of two within {}..={}",
                            soak_hydro::SEA_CELLS.start(),
                            soak_hydro::SEA_CELLS.end()
                        ),
                        _ => format!("{value} is out of range"),
                    };
                    return Err(self.invalid(&format!("water.{name}"), why));
                }
                Err(e) => return Err(self.invalid("water", e.to_string())),
            }
        }
        if let Some(soak_hydro::SeaSampling::PerWavelength(n)) = w.sampling {
            positive("water.sampling.per_wavelength", n)?;
        }
        only("file", w.file.is_some(), &[WaterKind::HeightField])?;
        only("origin", w.origin.is_some(), &[WaterKind::HeightField])?;
        only("spacing", w.spacing.is_some(), &[WaterKind::HeightField])?;
        if let Some(d) = w.density {
            positive("water.density", d)?;
        }
        if let Some(l) = w.level {
            finite("water.level", &[l])?;
        }
        if let Some(c) = w.current {
            finite("water.current", &c)?;
        }
        if kind == WaterKind::Gerstner && w.waves.as_ref().is_none_or(|v| v.is_empty()) {
            return Err(self.invalid("water", "a gerstner sea needs `waves`"));
        }
        if let Some(waves) = &w.waves
            && let Err(soak_hydro::WaterError::Wave { index, field, value }) =
                soak_hydro::Gerstner::new(0.0, waves.clone(), 9.81)
        {
            return Err(self.invalid(
                &format!("water.waves[{index}].{field}"),
                format!("{value} is out of range"),
            ));
        }
        if kind == WaterKind::HeightField {
            for (key, present) in [("file", w.file.is_some()), ("spacing", w.spacing.is_some())] {
                if !present {
                    return Err(self.invalid("water", format!("a height field needs `{key}`")));
                }
            }
            let [dx, dz] = w.spacing.unwrap_or([1.0, 1.0]);
            positive("water.spacing", dx.min(dz))?;
        }
        let mut names = std::collections::HashSet::new();
        for (i, b) in s.bodies.iter().enumerate() {
            let key = |k: &str| format!("bodies[{i}].{k}");
            if !names.insert(b.name.as_str()) {
                return Err(self.invalid(&key("name"), format!("`{}` is used by another body", b.name)));
            }
            match b.resolution {
                ResolutionSpec::Texels(n) if n == 0 || n > soak_bake::MAX_RESOLUTION => {
                    return Err(self.invalid(
                        &key("resolution"),
                        format!("{n} is outside 1..={}", soak_bake::MAX_RESOLUTION),
                    ));
                }
                ResolutionSpec::Texels(_) if b.tolerance.is_some() => {
                    return Err(self.invalid(&key("tolerance"), "applies only to `resolution = \"auto\"`"));
                }
                _ => {}
            }
            if let Some(t) = b.tolerance {
                positive(&key("tolerance"), t)?;
            }
            match b.drag_resolution {
                Some(n) if n == 0 || n > soak_bake::MAX_RESOLUTION => {
                    return Err(self.invalid(
                        &key("drag_resolution"),
                        format!("{n} is outside 1..={}", soak_bake::MAX_RESOLUTION),
                    ));
                }
                Some(_) if b.drag.is_none() => {
                    return Err(self.invalid(&key("drag_resolution"), "applies only to a body with `drag`"));
                }
                _ => {}
            }
            match b.drag_coarsening {
                Some(k) if k == 0 || k > 256 => {
                    return Err(self.invalid(&key("drag_coarsening"), format!("{k} is outside 1..=256")));
                }
                Some(_) if b.drag.is_none() => {
                    return Err(self.invalid(&key("drag_coarsening"), "applies only to a body with `drag`"));
                }
                Some(_) if b.drag_resolution.is_some() => {
                    return Err(self.invalid(
                        &key("drag_coarsening"),
                        "give `drag_coarsening` or `drag_resolution`, not both",
                    ));
                }
                _ => {}
            }
            if b.sampling.is_some() && !matches!(kind, WaterKind::Gerstner | WaterKind::Spectrum) {
                return Err(self.invalid(
                    &key("sampling"),
                    format!("does not apply to water of kind {kind:?}"),
                ));
            }
            if let Some(soak_hydro::SeaSampling::PerWavelength(n)) = b.sampling {
                positive(&key("sampling.per_wavelength"), n)?;
            }
            match b.mass {
                MassSpec::Solid { density } => positive(&key("mass.density"), density)?,
                MassSpec::Shell { areal_density } => positive(&key("mass.areal_density"), areal_density)?,
                MassSpec::Walls { density, thickness } => {
                    positive(&key("mass.density"), density)?;
                    positive(&key("mass.thickness"), thickness)?;
                }
            }
            finite(&key("position"), &b.position)?;
            finite(&key("rotation_deg"), &b.rotation_deg)?;
            finite(&key("linear_velocity"), &b.linear_velocity)?;
            finite(&key("angular_velocity"), &b.angular_velocity)?;
            if let Some(GraphSpec::Auto(a)) = &b.graph {
                if !a.auto {
                    return Err(self.invalid(&key("graph.auto"), "must be true (or give a graph file)"));
                }
                if a.clusters == 0 {
                    return Err(self.invalid(&key("graph.clusters"), "must be at least 1"));
                }
                if !(0.0..=1.0).contains(&a.porosity) {
                    return Err(self.invalid(
                        &key("graph.porosity"),
                        format!("{} is outside [0, 1]", a.porosity),
                    ));
                }
            }
            if let Some(GraphSpec::Cavity(c)) = &b.graph
                && !c.cavity
            {
                return Err(self.invalid(&key("graph.cavity"), "must be true (or give a graph file)"));
            }
            let floods = b.graph.is_some() || b.open;
            if !b.permeability.is_empty() && !floods {
                return Err(self.invalid(
                    &key("permeability"),
                    "needs a `graph` (or `open = true`) for the water to go into",
                ));
            }
            if let Some(l) = b.liquid {
                if !(l.is_finite() && l >= 0.0) {
                    return Err(self.invalid(&key("liquid"), format!("must be a volume ≥ 0 m³, not {l}")));
                }
                if !floods {
                    return Err(self.invalid(
                        &key("liquid"),
                        "needs a `graph` (or `open = true`) for the water to be in",
                    ));
                }
            }
            if let Some(rule) = &b.impact_holes {
                if let Some(reason) = rule.problem() {
                    return Err(self.invalid(&key("impact_holes"), reason));
                }
                if !floods {
                    return Err(self.invalid(
                        &key("impact_holes"),
                        "needs a `graph` (or `open = true`) for the water to go into",
                    ));
                }
            }
            for (k, h) in b.permeability.iter().enumerate() {
                let hk = |f: &str| key(&format!("permeability[{k}].{f}"));
                finite(&hk("centre"), &h.centre)?;
                positive(&hk("radius"), h.radius)?;
                if let Some(kappa) = h.kappa
                    && !(kappa.is_finite() && kappa >= 0.0)
                {
                    return Err(self.invalid(&hk("kappa"), format!("must be ≥ 0 m, not {kappa}")));
                }
                if !(h.at.is_finite() && h.at >= 0.0) {
                    return Err(self.invalid(&hk("at"), format!("must be a time ≥ 0 s, not {}", h.at)));
                }
            }
            if let Some(w) = &b.wetting {
                self.validate_wetting(i, b, w)?;
            }
            if let Some(d) = b.drag {
                if !(d.coefficient.is_finite() && d.coefficient >= 0.0) {
                    return Err(self.invalid(
                        &key("drag.coefficient"),
                        format!("must be ≥ 0, not {}", d.coefficient),
                    ));
                }
                if !(d.linear.is_finite() && d.linear >= 0.0) {
                    return Err(self.invalid(&key("drag.linear"), format!("must be ≥ 0, not {}", d.linear)));
                }
            }
        }
        Ok(())
    }
}

impl LoadedScene {
    fn validate_wetting(&self, i: usize, b: &BodySpec, w: &WettingSpec) -> Result<(), SceneError> {
        let key = |k: &str| format!("bodies[{i}].wetting{k}");
        if b.fixed {
            return Err(self.invalid(
                &key(""),
                "does not apply to a fixed body (only bodies soak drives get wet)",
            ));
        }
        let check = |k: &str, v: f64, ok: bool, what: &str| -> Result<(), SceneError> {
            if v.is_finite() && ok {
                Ok(())
            } else {
                Err(self.invalid(&key(k), format!("must be {what}, not {v}")))
            }
        };
        match &w.material {
            MaterialSpec::Preset(name) if w.material.material().is_none() => {
                return Err(self.invalid(
                    &key(".material"),
                    format!("`{name}` is not a material (sand, wood, rock, cotton, or a table)"),
                ));
            }
            MaterialSpec::Custom(p) => {
                check(
                    ".material.permeability",
                    p.permeability,
                    p.permeability >= 0.0,
                    "≥ 0 m²",
                )?;
                check(".material.thickness", p.thickness, p.thickness > 0.0, "> 0 m")?;
                check(".material.saturation", p.saturation, p.saturation > 0.0, "> 0 m")?;
            }
            MaterialSpec::Preset(_) => {}
        }
        match &w.liquid {
            LiquidSpec::Preset(name) if w.liquid.liquid().is_none() => {
                return Err(self.invalid(
                    &key(".liquid"),
                    format!("`{name}` is not a liquid (water, ethanol, or a table)"),
                ));
            }
            LiquidSpec::Custom(p) => {
                check(".liquid.viscosity", p.viscosity, p.viscosity > 0.0, "> 0 Pa·s")?;
                check(
                    ".liquid.evaporation_rate",
                    p.evaporation_rate,
                    p.evaporation_rate >= 0.0,
                    "≥ 0 1/(m·s)",
                )?;
            }
            LiquidSpec::Preset(_) => {}
        }
        if let Some(d) = w.diffusion {
            check(".diffusion", d, d >= 0.0, "a diffusion coefficient ≥ 0 m²/s")?;
        }
        for (k, present) in [("mode", w.mode.is_some()), ("voxel_size", w.voxel_size.is_some())] {
            if present && w.diffusion.is_none() {
                return Err(self.invalid(&key(&format!(".{k}")), "needs `diffusion`"));
            }
        }
        if let Some(v) = w.voxel_size {
            check(".voxel_size", v, v > 0.0, "> 0 m")?;
        }
        if let InitialLiquid::Fill(f) = w.initial {
            check(
                ".initial",
                f,
                (0.0..=1.0).contains(&f),
                "a fill fraction in [0, 1] or an image path",
            )?;
        }
        Ok(())
    }
}

/// An open body's mesh: its rims capped; or, for a closed mesh, its
/// cavities' mouths capped with the walls' own closed mesh beside it.
fn open_mesh(
    mesh: soak_bake::Mesh,
) -> Result<(soak_bake::Mesh, Option<soak_bake::Mesh>), soak_bake::MeshError> {
    if !soak_bake::boundary_loops(&mesh)?.is_empty() {
        return Ok((soak_bake::cap_openings(&mesh)?, None));
    }
    let cavities = soak_bake::cap_cavities(&mesh)?;
    if cavities.inner.is_empty() {
        return Ok((mesh, None));
    }
    Ok((cavities.filled, Some(mesh)))
}

//! Checking a [`RenderScene`] before any GPU work, with errors that name
//! the object and the offending value.

use super::error::RenderError;
use super::geometry::check_mesh;
use super::scene::{Albedo, RenderScene, WaterShape};
use crate::error::check_unit_rgb;
use crate::wet_material::validate_albedo;

impl RenderScene {
    /// Checks everything in the scene that could fail on the GPU or
    /// mislead, naming the object and the value: camera, light,
    /// environment, water, arrows, and per object the material, albedo,
    /// mesh, pose, UVs, liquid texture and segment ids. Image sides are
    /// checked against `max_texture_side` (the device's
    /// `max_texture_dimension_2d`; [`Renderer::render`](super::Renderer::render) passes it).
    pub fn validate(&self, max_texture_side: u32) -> Result<(), RenderError> {
        let scene = self;
        let max_texture = max_texture_side;
        scene.camera.validate()?;
        let finite = |v: &[f64]| v.iter().all(|c| c.is_finite());
        if !finite(scene.light.direction.as_slice()) || scene.light.direction.norm() < 1e-12 {
            return Err(RenderError::Scene {
                what: "light".into(),
                detail: format!(
                    "direction {:?} is zero or not finite",
                    scene.light.direction.as_slice()
                ),
            });
        }
        let env = &scene.environment;
        for (name, v) in [
            ("light irradiance", scene.light.irradiance),
            ("environment zenith", env.zenith),
            ("environment horizon", env.horizon),
            ("environment ground", env.ground),
        ] {
            if !v.iter().all(|c| c.is_finite() && *c >= 0.0) {
                return Err(RenderError::Scene {
                    what: name.into(),
                    detail: format!("{v:?} must be finite and non-negative"),
                });
            }
        }
        if !(scene.exposure.is_finite() && scene.exposure >= 0.0) {
            return Err(RenderError::Scene {
                what: "exposure".into(),
                detail: format!("{} must be finite and non-negative", scene.exposure),
            });
        }
        if let Some(s) = &scene.subsurface {
            s.validate()?;
        }
        if let Some(w) = &scene.water {
            let bad = |detail: String| RenderError::Scene {
                what: "water".into(),
                detail,
            };
            check_unit_rgb(["water.colour.r", "water.colour.g", "water.colour.b"], w.colour)
                .map_err(|e| bad(e.to_string()))?;
            crate::error::check_unit("water.opacity", w.opacity).map_err(|e| bad(e.to_string()))?;
            crate::error::check_unit("water.roughness", w.roughness).map_err(|e| bad(e.to_string()))?;
            crate::error::check_refractive_index("water.refractive_index", w.refractive_index)
                .map_err(|e| bad(e.to_string()))?;
            if !(w.extent > 0.0 && w.extent.is_finite()) {
                return Err(bad(format!("extent {} must be positive", w.extent)));
            }
            if !(2..=1024).contains(&w.resolution) {
                return Err(bad(format!("resolution {} is outside 2..=1024", w.resolution)));
            }
            match &w.shape {
                WaterShape::Plane { level } if !level.is_finite() => {
                    return Err(bad(format!("level {level} is not finite")));
                }
                WaterShape::Gerstner { time, .. } if !time.is_finite() => {
                    return Err(bad(format!("time {time} is not finite")));
                }
                WaterShape::Spectral { fields } => {
                    let n = fields.cells;
                    let arrays = [&fields.height, &fields.displacement[0], &fields.displacement[1]]
                        .into_iter()
                        .chain(&fields.height_gradient)
                        .chain(&fields.displacement_gradient)
                        .chain(&fields.twist);
                    for a in arrays {
                        if n == 0 || a.len() != n * n {
                            return Err(bad(format!("spectral sea: a field not of {n}×{n} nodes")));
                        }
                        if let Some(v) = a.iter().find(|v| !v.is_finite()) {
                            return Err(bad(format!("spectral sea: a field's value {v} is not finite")));
                        }
                    }
                    if !(fields.size > 0.0 && fields.size.is_finite() && fields.level.is_finite()) {
                        return Err(bad(format!(
                            "spectral sea: tile {} m at level {} m",
                            fields.size, fields.level
                        )));
                    }
                }
                WaterShape::Interactive { waves, .. } => {
                    let n = waves.region.cells;
                    if waves.heights.len() != n * n {
                        return Err(bad(format!(
                            "interactive waves: {} heights for {n}×{n} cells",
                            waves.heights.len()
                        )));
                    }
                    if let Some(h) = waves.heights.iter().find(|h| !h.is_finite()) {
                        return Err(bad(format!("interactive waves: height {h} is not finite")));
                    }
                }
                _ => {}
            }
        }
        for (i, a) in scene.arrows.iter().enumerate() {
            if !finite(a.origin.coords.as_slice()) || !finite(a.vector.as_slice()) || !a.radius.is_finite() {
                return Err(RenderError::Scene {
                    what: format!("arrow {i}"),
                    detail: "origin, vector and radius must be finite".into(),
                });
            }
        }
        for (i, o) in scene.objects.iter().enumerate() {
            let name = || o.name.clone();
            let material = |source| RenderError::Material {
                object: i,
                name: name(),
                source,
            };
            o.material.validate().map_err(material)?;
            match &o.albedo {
                Albedo::Constant(c) => validate_albedo(*c).map_err(material)?,
                Albedo::Texture { image, tint } => {
                    check_unit_rgb(["tint.r", "tint.g", "tint.b"], *tint).map_err(material)?;
                    let (w, h) = image.dimensions();
                    if w == 0 || h == 0 || w > max_texture || h > max_texture {
                        return Err(RenderError::Texture {
                            object: i,
                            name: name(),
                            detail: format!(
                                "the albedo image is {w}×{h}; each side must be in 1..={max_texture}"
                            ),
                        });
                    }
                }
            }
            check_mesh(&o.mesh).map_err(|detail| RenderError::Mesh {
                object: i,
                name: name(),
                detail,
            })?;
            if !finite(o.pose.translation.vector.as_slice()) || !finite(o.pose.rotation.coords.as_slice()) {
                return Err(RenderError::Mesh {
                    object: i,
                    name: name(),
                    detail: "the pose is not finite".into(),
                });
            }
            if o.mesh.uvs.is_none() {
                let texture = if matches!(o.albedo, Albedo::Texture { .. }) {
                    Some("albedo")
                } else if o.liquid.is_some() {
                    Some("liquid")
                } else {
                    None
                };
                if let Some(texture) = texture {
                    return Err(RenderError::MissingUvs {
                        object: i,
                        name: name(),
                        texture,
                    });
                }
            }
            if let Some(l) = &o.liquid {
                let (w, h) = l.dimensions();
                if w == 0 || h == 0 || w > max_texture || h > max_texture {
                    return Err(RenderError::Texture {
                        object: i,
                        name: name(),
                        detail: format!(
                            "the liquid image is {w}×{h}; each side must be in 1..={max_texture}"
                        ),
                    });
                }
                if let Some(k) = l.as_raw().iter().position(|v| !v.is_finite()) {
                    return Err(RenderError::Texture {
                        object: i,
                        name: name(),
                        detail: format!(
                            "liquid texel ({}, {}) is {}",
                            k as u32 % w,
                            k as u32 / w,
                            l.as_raw()[k]
                        ),
                    });
                }
            }
            if let Some(s) = &o.segments {
                if s.len() != o.mesh.triangles.len() {
                    return Err(RenderError::SegmentCount {
                        object: i,
                        name: name(),
                        given: s.len(),
                        triangles: o.mesh.triangles.len(),
                    });
                }
            }
        }
        Ok(())
    }
}

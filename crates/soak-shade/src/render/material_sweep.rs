//! The thesis' Fig. 6.3 ("a generic material under different conditions:
//! dry, partly wet and saturated"), for several albedos and liquids: a grid
//! of spheres, one row per material, one column per wetness, rendered with
//! the same [`Renderer`] as the scenes.

use std::sync::Arc;

use nalgebra::{Isometry3, Point3, Vector3};

use super::camera::Camera;
use super::error::RenderError;
use super::procedural::{blotches, speckled};
use super::renderer::{Renderer, RendererOptions};
use super::scene::{Albedo, DirectionalLight, Environment, LiquidImage, RenderObject, RenderScene, ToneMap};
use crate::liquid::Liquid;
use crate::wet_material::WetMaterial;

/// One row of the sweep: a material.
#[derive(Debug, Clone)]
pub struct SweepRow {
    /// Label drawn left of the row (with a font).
    pub label: String,
    /// Dry albedo.
    pub albedo: Albedo,
    /// Liquid and Γ.
    pub material: WetMaterial,
}

/// How wet a column is.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum SweepWetness {
    /// The same saturation `h ∈ [0, 1]` everywhere.
    Uniform(f64),
    /// Saturated blotches covering a fraction `coverage` of the surface,
    /// dry elsewhere, with soft edges.
    Blotches {
        /// Wet fraction, `[0, 1]`.
        coverage: f64,
    },
}

/// One column of the sweep: a wetness.
#[derive(Debug, Clone, PartialEq)]
pub struct SweepColumn {
    /// Label drawn above the column (with a font).
    pub label: String,
    /// The liquid texture of every sphere in the column.
    pub wetness: SweepWetness,
}

/// A material sweep: rows × columns of spheres.
#[derive(Debug, Clone)]
pub struct MaterialSweep {
    /// Materials.
    pub rows: Vec<SweepRow>,
    /// Wetness states.
    pub columns: Vec<SweepColumn>,
    /// Side of one cell, pixels.
    pub cell: u32,
    /// The key light.
    pub light: DirectionalLight,
    /// The studio environment (also the background).
    pub environment: Environment,
    /// A font for the labels; `None` draws no labels.
    pub font: Option<ab_glyph::FontArc>,
}

impl MaterialSweep {
    /// Fig. 6.3 extended: terracotta, sand and grey cloth under clear
    /// water, light wood under coffee, white cotton under red wine and blue
    /// ink; dry, partly wet (blotches over 45 %), damp (h = 0.5 everywhere)
    /// and saturated. Arctan Γ with `r = 8`, 160-pixel cells, no font.
    pub fn thesis_fig_6_3() -> Self {
        let coloured = |colour: [f64; 3], thickness: f64| Liquid::from_colour(1.34, colour, 1e-2, thickness);
        let rows = [
            ("terracotta, water", [0.58, 0.30, 0.19], Liquid::water(), 1),
            ("sand, water", [0.72, 0.60, 0.42], Liquid::water(), 2),
            ("grey cloth, water", [0.40, 0.40, 0.40], Liquid::water(), 3),
            (
                "light wood, coffee",
                [0.70, 0.55, 0.38],
                coloured([0.45, 0.20, 0.06], 2e-3),
                4,
            ),
            (
                "white cotton, red wine",
                [0.80, 0.80, 0.78],
                coloured([0.50, 0.03, 0.08], 1.5e-3),
                5,
            ),
            (
                "white cotton, blue ink",
                [0.80, 0.80, 0.78],
                coloured([0.05, 0.20, 0.60], 2e-3),
                6,
            ),
        ]
        .into_iter()
        .map(|(label, colour, liquid, seed)| SweepRow {
            label: label.into(),
            albedo: Albedo::texture(speckled(256, 128, colour, 0.18, 10.0, seed)),
            material: WetMaterial {
                liquid,
                ..WetMaterial::default()
            },
        })
        .collect();
        let columns = [
            ("dry", SweepWetness::Uniform(0.0)),
            ("partly wet", SweepWetness::Blotches { coverage: 0.45 }),
            ("damp (h = 0.5)", SweepWetness::Uniform(0.5)),
            ("saturated", SweepWetness::Uniform(1.0)),
        ]
        .into_iter()
        .map(|(label, wetness)| SweepColumn {
            label: label.into(),
            wetness,
        })
        .collect();
        Self {
            rows,
            columns,
            cell: 160,
            light: DirectionalLight {
                direction: Vector3::new(-0.55, 0.6, 0.75),
                irradiance: [2.4; 3],
            },
            environment: Environment {
                zenith: [0.20, 0.21, 0.23],
                horizon: [0.16, 0.16, 0.17],
                ground: [0.08, 0.08, 0.08],
            },
            font: None,
        }
    }
}

/// Renders `sweep` on `device`: a `(columns × cell)` by `(rows × cell)`
/// image, plus margins for the labels when a font is given.
///
/// # Errors
/// As [`Renderer::render`]; [`RenderError::Scene`] for an empty sweep.
pub fn material_sweep(
    device: &wgpu::Device,
    queue: &wgpu::Queue,
    sweep: &MaterialSweep,
) -> Result<image::RgbaImage, RenderError> {
    let (rows, cols) = (sweep.rows.len(), sweep.columns.len());
    if rows == 0 || cols == 0 || sweep.cell == 0 {
        return Err(RenderError::Scene {
            what: "material sweep".into(),
            detail: format!("{rows} rows, {cols} columns and {}-pixel cells", sweep.cell),
        });
    }
    let (w, h) = (cols as u32 * sweep.cell, rows as u32 * sweep.cell);
    let mut renderer = Renderer::with_options(
        device,
        queue,
        w,
        h,
        RendererOptions {
            sample_count: 4,
            shadow_map_size: 256,
        },
    )?;
    // Cells are 1 m apart: column c at x = c, row r at y = −r.
    let centre = Point3::new((cols as f64 - 1.0) / 2.0, -(rows as f64 - 1.0) / 2.0, 0.0);
    let camera = Camera::orthographic(centre + Vector3::new(0.0, 0.0, 10.0), centre, rows as f64);
    let mut scene = RenderScene::new(camera);
    scene.light = sweep.light;
    scene.environment = sweep.environment;
    scene.shadows = false;
    scene.tone_map = ToneMap::Neutral;
    let sphere = Arc::new(soak_bake::builtin::sphere(0.43, 96, 48));
    let liquids: Vec<Arc<LiquidImage>> = sweep
        .columns
        .iter()
        .enumerate()
        .map(|(c, col)| {
            Arc::new(match col.wetness {
                SweepWetness::Uniform(h) => LiquidImage::from_pixel(1, 1, image::Luma([h as f32])),
                SweepWetness::Blotches { coverage } => blotches(256, 128, 5.0, coverage, 0.03, 17 + c as u64),
            })
        })
        .collect();
    for (r, row) in sweep.rows.iter().enumerate() {
        for (c, liquid) in liquids.iter().enumerate() {
            // Turn each sphere so the UV seam faces away.
            let pose = Isometry3::new(
                Vector3::new(c as f64, -(r as f64), 0.0),
                Vector3::new(0.35, 0.0, 0.0) + Vector3::y() * std::f64::consts::FRAC_PI_2,
            );
            scene.objects.push(
                RenderObject::new(Arc::clone(&sphere), pose)
                    .with_name(format!("{} / {}", row.label, sweep.columns[c].label))
                    .with_albedo(row.albedo.clone())
                    .with_liquid(Arc::clone(liquid))
                    .with_material(row.material.clone()),
            );
        }
    }
    let spheres = renderer.render(&scene)?;
    let Some(font) = &sweep.font else {
        return Ok(spheres);
    };
    // Margins for labels.
    let px = (sweep.cell as f32 * 0.11).clamp(11.0, 22.0);
    let left = sweep
        .rows
        .iter()
        .map(|r| super::text::width(font, px, &r.label))
        .fold(0.0f32, f32::max)
        .ceil() as u32
        + (px as u32);
    let top = (px * 2.0) as u32;
    // Margins in the backdrop's colour, labels in black or white on it.
    let background = *spheres.get_pixel(0, 0);
    let mut out = image::RgbaImage::from_pixel(w + left, h + top, background);
    image::imageops::overlay(&mut out, &spheres, i64::from(left), i64::from(top));
    let light = super::colour::luminance(super::colour::pixel_to_linear(background)) > 0.25;
    let ink = if light { [20, 20, 20] } else { [235, 235, 235] };
    for (c, col) in sweep.columns.iter().enumerate() {
        let tw = super::text::width(font, px, &col.label);
        let x = left as f32 + (c as f32 + 0.5) * sweep.cell as f32 - 0.5 * tw;
        super::text::draw(&mut out, font, px, x, 0.5 * px, ink, &col.label);
    }
    for (r, row) in sweep.rows.iter().enumerate() {
        let y = top as f32 + (r as f32 + 0.5) * sweep.cell as f32 - 0.5 * px;
        super::text::draw(&mut out, font, px, 0.5 * px, y, ink, &row.label);
    }
    Ok(out)
}

//! `soak bake MESH`: bake and summarise.

use std::path::PathBuf;
use std::time::Instant;

use anyhow::Context;
use serde::Serialize;
use soak_bake::{
    Atlas, AtlasImage, BakeOptions, Opening, UnwrapOptions, UnwrapReport, cap_openings, load_mesh, unwrap,
};

/// Arguments of `soak bake`.
#[derive(clap::Args)]
pub struct Args {
    /// A mesh file (.obj, .gltf, .glb) or a builtin name (builtin:sphere:0.5, builtin:box:4x1x1, ...).
    mesh: String,
    /// Texture side in texels.
    #[arg(long, short, default_value_t = 512)]
    resolution: u32,
    /// Replace the mesh's UVs with a generated physics atlas.
    #[arg(long)]
    unwrap: bool,
    /// An open mesh (a bucket, a rowing boat): cap its rims (listed) and bake the closed shape.
    #[arg(long)]
    open: bool,
    /// Print one JSON object instead of text.
    #[arg(long)]
    json: bool,
    /// Write position and area-vector textures (16-bit PNG and f32 EXR) into this folder.
    #[arg(long)]
    export: Option<PathBuf>,
}

#[derive(Serialize)]
struct Summary {
    mesh: String,
    resolution: u32,
    texels: usize,
    triangles: usize,
    centroid_samples: usize,
    tiles: usize,
    /// Σ a_i, m².
    area: f64,
    /// (1/3) Σ x_i·A_i, m³.
    volume: f64,
    /// |Σ A_i| / Σ a_i.
    closure: f64,
    /// The mesh's exact area, m².
    mesh_area: f64,
    /// The mesh's exact polyhedral volume, m³.
    mesh_volume: f64,
    bake_ms: f64,
    #[serde(skip_serializing_if = "Option::is_none")]
    unwrap: Option<UnwrapReport>,
    /// The rims an open mesh's caps close (`--open`).
    #[serde(skip_serializing_if = "Vec::is_empty")]
    openings: Vec<Opening>,
    /// Texels on the caps.
    #[serde(skip_serializing_if = "Option::is_none")]
    opening_texels: Option<usize>,
}

pub fn run(args: &Args) -> anyhow::Result<()> {
    let mut mesh = load_mesh(&args.mesh)?;
    if args.open {
        mesh = cap_openings(&mesh)?;
    }
    let mut report = None;
    if args.unwrap {
        let (m, r) = unwrap(&mesh, UnwrapOptions::default())?;
        mesh = m;
        report = Some(r);
    }
    let start = Instant::now();
    let atlas = Atlas::bake(&mesh, BakeOptions::square(args.resolution))?;
    let bake_ms = start.elapsed().as_secs_f64() * 1e3;
    let s = atlas.summary();
    let out = Summary {
        mesh: mesh.name.clone(),
        resolution: args.resolution,
        texels: s.texels,
        triangles: s.triangles,
        centroid_samples: s.centroid_samples,
        tiles: s.tiles,
        area: s.area,
        volume: s.volume,
        closure: s.closure,
        mesh_area: mesh.area(),
        mesh_volume: mesh.volume(),
        bake_ms,
        unwrap: report,
        opening_texels: args.open.then(|| atlas.opening_samples().len()),
        openings: mesh.openings.clone(),
    };
    if let Some(dir) = &args.export {
        std::fs::create_dir_all(dir).with_context(|| format!("cannot create {}", dir.display()))?;
        for (which, stem) in [
            (AtlasImage::Position, "position"),
            (AtlasImage::AreaVector, "area_vector"),
        ] {
            for ext in ["png", "exr"] {
                atlas.write_image(which, &dir.join(format!("{stem}.{ext}")))?;
            }
        }
    }
    if args.json {
        println!("{}", serde_json::to_string_pretty(&out)?);
    } else {
        println!("{}  at {}²", out.mesh, out.resolution);
        println!(
            "  texels       {:>12} ({} centroid samples, {} tiles)",
            out.texels, out.centroid_samples, out.tiles
        );
        println!("  triangles    {:>12}", out.triangles);
        println!(
            "  area         {:>12.6} m²  (mesh {:.6})",
            out.area, out.mesh_area
        );
        println!(
            "  volume       {:>12.6} m³  (mesh {:.6})",
            out.volume, out.mesh_volume
        );
        println!("  closure      {:>12.3e}", out.closure);
        println!("  bake         {:>12.2} ms", out.bake_ms);
        if let Some(r) = &out.unwrap {
            println!(
                "  unwrap       {:>12} charts, density {:.2}–{:.2} of mean (cv {:.3}), {:.1} ms",
                r.charts, r.density_min, r.density_max, r.density_cv, r.millis
            );
        }
        for (k, o) in out.openings.iter().enumerate() {
            let [nx, ny, nz] = o.normal;
            let [cx, cy, cz] = o.centroid;
            println!(
                "  rim {k:<8} {:>12} vertices, {:.4} m long, cap {:.6} m² at ({cx:.3}, {cy:.3}, {cz:.3}) m facing \
                 ({nx:.3}, {ny:.3}, {nz:.3}), {} triangles, warp {:.2e} m",
                o.rim.len(),
                o.length,
                o.area,
                o.triangles,
                o.warp
            );
        }
        if let Some(n) = out.opening_texels {
            println!("  cap texels   {n:>12}");
        }
        if let Some(dir) = &args.export {
            println!("  textures in  {}", dir.display());
        }
    }
    Ok(())
}

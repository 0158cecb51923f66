//! Building a [`Simulation`] from a scene: the fluid ([`water_of`]), then
//! every body with its mesh baked, its collider, its wetting and its liquid
//! graph.

use std::collections::HashMap;
use std::sync::Arc;

use nalgebra::{Isometry3, Translation3, UnitQuaternion, Vector3};
use rapier3d::prelude::*;
use soak_bake::{Atlas, BakeOptions};
use soak_hydro::{
    AddedMass, DragTexels, Gerstner, HeightField, MassModel, Plane, SeaBand, SpectralSurface, Unbounded,
    Water,
};

use super::{SimBody, Simulation};
use crate::convert;
use crate::error::SceneError;
use crate::scene::{
    ColliderSpec, DEFAULT_TOLERANCE, InitialLiquid, LoadedScene, MassSpec, ResolutionSpec, WaterKind,
    WettingSpec,
};
use crate::{BodyDesc, Effects, ForceGenerator};

/// The settings a scene bakes a body's radiation with in `water`: its
/// density and gravity, 150 panels and 24 frequencies. Against 300
/// panels and 40 frequencies, free-decay period and decay per cycle
/// within 0.9 % for a crate (heave, roll, pitch), a ball (heave) and a
/// capsule buoy (heave, roll), in a quarter of the time (`soak
/// seakeeping MESH --panels 150 --frequencies 24`).
pub fn radiation_settings(water: &Water) -> soak_seakeeping::RadiationSettings {
    soak_seakeeping::RadiationSettings {
        density: water.density,
        gravity: water.gravity,
        panels: 150,
        frequencies: 24,
        ..soak_seakeeping::RadiationSettings::default()
    }
}

/// Builds the fluid a scene describes.
pub fn water_of(loaded: &LoadedScene) -> Result<Water, SceneError> {
    let w = &loaded.scene.water;
    let g = Vector3::from(loaded.scene.gravity).norm();
    let current = Vector3::from(w.current.unwrap_or([0.0; 3]));
    let water = match w.kind {
        WaterKind::Plane => Water::new(Plane::horizontal(w.level.unwrap_or(0.0)).with_current(current)),
        WaterKind::Gerstner => {
            let sea = Gerstner::new(
                w.level.unwrap_or(0.0),
                w.waves.clone().unwrap_or_default(),
                g.max(1e-9),
            )
            .map_err(|e| loaded.invalid("water.waves", e.to_string()))?;
            Water::new(sea)
        }
        WaterKind::Spectrum => {
            let sea = w
                .spectral_sea(g.max(1e-9))
                .map_err(|e| loaded.invalid("water", e.to_string()))?;
            Water::new(SpectralSurface::new(sea))
        }
        WaterKind::HeightField => {
            let file = w.file.as_deref().unwrap_or_default();
            let path = loaded.resolve(file);
            let text = std::fs::read_to_string(&path).map_err(|e| {
                loaded.invalid("water.file", format!("cannot read `{}`: {e}", path.display()))
            })?;
            let mut rows: Vec<Vec<f64>> = Vec::new();
            for (n, line) in text.lines().enumerate() {
                if line.trim().is_empty() || line.trim_start().starts_with('#') {
                    continue;
                }
                let row: Result<Vec<f64>, _> = line.split(',').map(|t| t.trim().parse::<f64>()).collect();
                let row = row.map_err(|_| {
                    loaded.invalid(
                        "water.file",
                        format!("`{}` line {}: not a row of numbers", path.display(), n + 1),
                    )
                })?;
                rows.push(row);
            }
            let nx = rows.first().map_or(0, Vec::len);
            if let Some(bad) = rows.iter().position(|r| r.len() != nx) {
                return Err(loaded.invalid(
                    "water.file",
                    format!(
                        "`{}`: row {} has {} values, the first has {nx}",
                        path.display(),
                        bad + 1,
                        rows[bad].len()
                    ),
                ));
            }
            let nz = rows.len();
            let heights: Vec<f64> = rows.into_iter().flatten().collect();
            let mut hf = HeightField::new(
                w.origin.unwrap_or([0.0, 0.0]),
                w.spacing.unwrap_or([1.0, 1.0]),
                nx,
                nz,
                heights,
            )
            .map_err(|e| loaded.invalid("water.file", format!("`{}`: {e}", path.display())))?;
            hf.current = current.into();
            Water::new(hf)
        }
        WaterKind::Air => {
            let mut water = Water::new(Unbounded {
                current: current.into(),
            });
            water.density = soak_hydro::AIR_DENSITY;
            water
        }
    };
    let water = match w.density {
        Some(d) => water.with_density(d),
        None => water,
    };
    Ok(water.with_gravity(g))
}

#[cfg(feature = "gpu")]
fn with_gpu(soak: ForceGenerator) -> Result<ForceGenerator, String> {
    let (device, queue, _) = soak_hydro::gpu::headless_device().map_err(|e| format!("needs a GPU: {e}"))?;
    soak.with_gpu(&device, &queue).map_err(|e| e.to_string())
}

#[cfg(not(feature = "gpu"))]
fn with_gpu(_: ForceGenerator) -> Result<ForceGenerator, String> {
    Err("`gpu` needs soak built with its `gpu` feature".into())
}

/// What makes two scene bodies' atlases the same: mesh, unwrap, resolution
/// and tolerance (its bits).
type AtlasKey = (String, bool, ResolutionSpec, Option<u64>);

impl Simulation {
    /// Builds the world a scene describes: loads and bakes every mesh,
    /// registers the bodies with their effects.
    pub fn from_scene(loaded: &LoadedScene) -> Result<Self, SceneError> {
        let scene = &loaded.scene;
        let mut world = PhysicsWorld::new();
        world.gravity = convert::to_vector(&Vector3::from(scene.gravity));
        world.integration_parameters.dt = scene.dt as f32;
        let mut soak = ForceGenerator::new(water_of(loaded)?)
            .with_backend(scene.backend)
            .with_sea_sampling(scene.water.sampling.unwrap_or_default())
            .with_sea_velocity(scene.water.velocity.unwrap_or_default())
            .with_sea_band(scene.water.band.map_or(SeaBand::Full, SeaBand::BodyLengths));
        if let Some(waves) = scene.waves {
            soak = soak
                .with_waves(waves)
                .map_err(|e| loaded.invalid("waves", e.to_string()))?;
        }
        let mut weather = None;
        if let Some(env) = &scene.environment {
            soak.set_environment(env.environment())
                .map_err(|e| loaded.invalid("environment", e.to_string()))?;
            weather = env
                .track()
                .map_err(|e| loaded.invalid("environment.keys", e.to_string()))?;
        }
        if scene.backend == crate::Backend::Gpu {
            soak = with_gpu(soak).map_err(|message| SceneError::Invalid {
                path: loaded.path.clone(),
                line: loaded.line_of("backend"),
                key: "backend".into(),
                message,
            })?;
        }
        let mut bodies = Vec::new();
        let mut holes = Vec::new();
        let mut atlases: HashMap<AtlasKey, (Arc<Atlas>, u32)> = HashMap::new();
        let mut drag_bakes: HashMap<(String, bool, u32), Arc<DragTexels>> = HashMap::new();
        let mut coarsened: HashMap<(usize, u32), Arc<DragTexels>> = HashMap::new();
        type RadiationKey = (String, bool, u64, [u64; 3]);
        // Bodies floating on a sea of known waves radiate unless told not
        // to; where bodies make their own waves, they make them there.
        let on_sea =
            matches!(scene.water.kind, WaterKind::Gerstner | WaterKind::Spectrum) && scene.waves.is_none();
        let mut radiation_bakes: HashMap<RadiationKey, Arc<soak_seakeeping::RadiationModel>> = HashMap::new();
        for (i, b) in scene.bodies.iter().enumerate() {
            let body_err = |message: String| SceneError::Body {
                path: loaded.path.clone(),
                line: loaded.line_of(&format!("bodies[{i}].mesh")),
                body: b.name.clone(),
                message,
            };
            let mesh = loaded.body_mesh(i)?;
            let [rx, ry, rz] = b.rotation_deg.map(f64::to_radians);
            let pose = Isometry3::from_parts(
                Translation3::from(Vector3::from(b.position)),
                UnitQuaternion::from_euler_angles(rx, ry, rz),
            );
            let builder = if b.fixed {
                RigidBodyBuilder::fixed()
            } else {
                RigidBodyBuilder::dynamic()
            };
            let handle = world.bodies.insert(
                builder
                    .pose(convert::to_pose(&pose))
                    .linvel(convert::to_vector(&Vector3::from(b.linear_velocity)))
                    .angvel(convert::to_vector(&Vector3::from(b.angular_velocity))),
            );
            let points = || -> Vec<Vector> { mesh.positions.iter().map(convert::point_to_vector).collect() };
            let collider = match b.collider {
                ColliderSpec::None => None,
                ColliderSpec::ConvexHull => Some(
                    ColliderBuilder::convex_hull(&points())
                        .ok_or_else(|| body_err("no convex hull".into()))?,
                ),
                // An open mesh's caps are not solid: the trimesh is its walls.
                ColliderSpec::Trimesh => Some(
                    ColliderBuilder::trimesh(
                        points(),
                        mesh.triangles[..mesh
                            .first_opening_triangle()
                            .unwrap_or(mesh.triangles.len() as u32)
                            as usize]
                            .to_vec(),
                    )
                    .map_err(|e| body_err(format!("trimesh collider: {e}")))?,
                ),
            };
            if let Some(c) = collider {
                world
                    .colliders
                    .insert_with_parent(c.density(0.0), handle, &mut world.bodies);
            }
            let mut resolution = 0;
            let id = if b.fixed {
                None
            } else {
                // Bodies of one mesh at one resolution share one atlas (and
                // so its tiles): baked once, one copy in memory.
                let key = (
                    b.mesh.clone(),
                    b.unwrap,
                    b.resolution,
                    b.tolerance.map(f64::to_bits),
                );
                let (atlas, side) = match atlases.get(&key) {
                    Some(known) => known.clone(),
                    None => {
                        let made = match b.resolution {
                            ResolutionSpec::Texels(n) => (
                                Arc::new(
                                    Atlas::bake(&mesh, BakeOptions::square(n))
                                        .map_err(|e| body_err(e.to_string()))?,
                                ),
                                n,
                            ),
                            ResolutionSpec::Auto(_) => {
                                let tolerance = b.tolerance.unwrap_or(DEFAULT_TOLERANCE);
                                let (atlas, choice) =
                                    soak_hydro::bake_to_tolerance(&mesh, tolerance, BakeOptions::default())
                                        .map_err(|e| body_err(e.to_string()))?;
                                log::info!(
                                    "body `{}`: resolution {}² for tolerance {:.1e} (error {:.1e})",
                                    b.name,
                                    choice.resolution,
                                    tolerance,
                                    choice.error
                                );
                                (Arc::new(atlas), choice.resolution)
                            }
                        };
                        atlases.insert(key, made.clone());
                        made
                    }
                };
                resolution = side;
                // A thick-walled container's solid is its walls' closed mesh,
                // its atlas the filled shape.
                let walls_mesh = loaded.body_walls(i)?;
                let walls_solid = match (&walls_mesh, &b.mass) {
                    (Some(w), &MassSpec::Solid { density }) => {
                        let atlas = Atlas::bake(w, BakeOptions::square(side.max(64)))
                            .map_err(|e| body_err(format!("the walls: {e}")))?;
                        let m = MassModel::Solid { density }
                            .mass_properties(&atlas)
                            .map_err(|e| body_err(format!("the walls: {e}")))?;
                        Some((m, atlas.volume()))
                    }
                    _ => None,
                };
                let mass_model = match b.mass {
                    MassSpec::Solid { .. } if walls_solid.is_some() => MassModel::Given {
                        properties: Box::new(walls_solid.expect("checked").0),
                    },
                    MassSpec::Solid { density } => MassModel::Solid { density },
                    MassSpec::Shell { areal_density } => MassModel::Shell { areal_density },
                    MassSpec::Walls { density, thickness } => MassModel::Walls { density, thickness },
                };
                // The room thin walls take inside the surface.
                let walls_volume = match b.mass {
                    MassSpec::Walls { thickness, .. } => atlas.wall_area() * thickness,
                    _ => walls_solid.map_or(0.0, |w| w.1),
                };
                let wetting = b
                    .wetting
                    .as_ref()
                    .map(|spec| wetting_of(loaded, i, spec, &atlas))
                    .transpose()?;
                let cavity = crate::scene::GraphSpec::Cavity(crate::scene::CavitySpec { cavity: true });
                let graph = b.graph.as_ref().or(b.open.then_some(&cavity));
                let mut flooding = graph
                    .map(|spec| flooding(loaded, i, &mesh, &atlas, spec, walls_volume).map_err(body_err))
                    .transpose()?;
                if let (Some(f), Some(volume)) = (&mut flooding, b.liquid) {
                    let mut rest = volume;
                    for node in 0..f.graph().node_count() {
                        rest -= f.pour(node, rest).map_err(|e| body_err(e.to_string()))?;
                    }
                    if rest > 1e-9 * volume.max(1.0) {
                        return Err(loaded.invalid(
                            &format!("bodies[{i}].liquid"),
                            format!(
                                "{volume} m³ does not fit: the compartments hold {} m³",
                                volume - rest
                            ),
                        ));
                    }
                }
                // Drag texels are shared like atlases, by mesh and side.
                let drag_texels = match b.drag_resolution {
                    Some(n) => {
                        let key = (b.mesh.clone(), b.unwrap, n);
                        match drag_bakes.get(&key) {
                            Some(known) => Some(Arc::clone(known)),
                            None => {
                                let made = Arc::new(
                                    DragTexels::bake(&mesh, n)
                                        .map_err(|e| body_err(format!("drag texels: {e}")))?,
                                );
                                drag_bakes.insert(key, Arc::clone(&made));
                                Some(made)
                            }
                        }
                    }
                    None => match b.drag_coarsening {
                        // Coarsened from the body's atlas, shared with it.
                        Some(k) => {
                            // The atlases map keeps every shared atlas alive,
                            // so its address names it for the build.
                            let key = (Arc::as_ptr(&atlas) as usize, k);
                            match coarsened.get(&key) {
                                Some(known) => Some(Arc::clone(known)),
                                None => {
                                    let made = Arc::new(
                                        DragTexels::coarsened(Arc::clone(&atlas), k)
                                            .map_err(|e| body_err(format!("drag texels: {e}")))?,
                                    );
                                    coarsened.insert(key, Arc::clone(&made));
                                    Some(made)
                                }
                            }
                        }
                        None => None,
                    },
                };
                let added_mass = b
                    .added_mass
                    .then(|| AddedMass::of_atlas(&atlas).map(Box::new))
                    .transpose()
                    .map_err(|e| body_err(e.to_string()))?;
                // Radiation is baked from the mesh floating at rest in its
                // initial orientation, shared like atlases; on by default
                // for a body floating on a Gerstner sea (see
                // `BodySpec::radiation`).
                let by_default = on_sea
                    && !b.fixed
                    && b.buoyancy != soak_hydro::BuoyancyMode::Off
                    && !b.added_mass
                    && flooding.is_none()
                    && b.impact_holes.is_none()
                    && mesh.first_opening_triangle().is_none();
                let radiation = if b.radiation.unwrap_or(by_default) {
                    let mass = mass_model
                        .mass_properties(&atlas)
                        .map_err(|e| body_err(format!("radiation: {e}")))?;
                    let key = (
                        b.mesh.clone(),
                        b.unwrap,
                        mass.mass.to_bits(),
                        b.rotation_deg.map(f64::to_bits),
                    );
                    match radiation_bakes.get(&key) {
                        Some(known) => Some(Arc::clone(known)),
                        None => {
                            let settings = radiation_settings(soak.water());
                            let body = soak_seakeeping::FloatingBody {
                                mesh: &mesh,
                                mass: mass.mass,
                                center_of_mass: mass.center_of_mass,
                                inertia: mass.inertia,
                                rotation: pose.rotation,
                            };
                            match soak_seakeeping::RadiationModel::bake(&body, &settings) {
                                Ok(made) => {
                                    let made = Arc::new(made);
                                    radiation_bakes.insert(key, Arc::clone(&made));
                                    Some(made)
                                }
                                // Asked for by default: a body the panel
                                // method cannot float goes without.
                                Err(_) if b.radiation.is_none() => None,
                                Err(e) => return Err(body_err(format!("radiation: {e}"))),
                            }
                        }
                    }
                } else {
                    None
                };
                let effects = Effects {
                    radiation,
                    added_mass,
                    slamming: b.slamming,
                    buoyancy: Some(b.buoyancy),
                    drag: b.drag,
                    drag_texels,
                    flooding: flooding.map(Box::new),
                    wetting: wetting.map(Box::new),
                    impact_holes: b.impact_holes,
                    sea: b.sampling,
                };
                let desc = BodyDesc {
                    name: b.name.clone(),
                    atlas,
                    mass_model,
                    effects,
                };
                Some(
                    soak.register(&mut world.bodies, &world.colliders, handle, desc)
                        .map_err(|e| body_err(e.to_string()))?,
                )
            };
            if let Some(id) = id.filter(|&id| soak.flooding(id).is_some()) {
                for h in &b.permeability {
                    holes.push((id, h.clone(), false));
                }
            }
            bodies.push(SimBody {
                name: b.name.clone(),
                handle,
                id,
                resolution,
            });
        }
        let n = bodies.len();
        Ok(Self {
            world,
            soak,
            bodies,
            duration: scene.duration,
            holes,
            splashes: scene.splash.iter().map(|s| (*s, false)).collect(),
            weather,
            record_every: scene.output.every,
            recording: false,
            samples: Vec::new(),
            non_finite: vec![false; n],
            steps: 0,
        })
    }
}

/// The wetting state a body's `wetting` key asks for, over its atlas.
fn wetting_of(
    loaded: &LoadedScene,
    i: usize,
    spec: &WettingSpec,
    atlas: &Atlas,
) -> Result<soak_wet::Wetting, SceneError> {
    let key = |k: &str| format!("bodies[{i}].wetting{k}");
    let material = spec
        .material
        .material()
        .ok_or_else(|| loaded.invalid(&key(".material"), "is not a known material"))?;
    let liquid = spec
        .liquid
        .liquid()
        .ok_or_else(|| loaded.invalid(&key(".liquid"), "is not a known liquid"))?;
    let mut wetting = soak_wet::Wetting::new(atlas, material, liquid)
        .map_err(|e| loaded.invalid(&key(""), e.to_string()))?;
    if let Some(d) = spec.diffusion {
        let mut diffusion = soak_wet::Diffusion::new(d).with_mode(spec.mode.unwrap_or_default());
        if let Some(v) = spec.voxel_size {
            diffusion = diffusion.with_resolution(soak_wet::FieldResolution::VoxelSize(v));
        }
        wetting
            .set_diffusion(Some(diffusion))
            .map_err(|e| loaded.invalid(&key(".diffusion"), e.to_string()))?;
    }
    match &spec.initial {
        InitialLiquid::Fill(f) => {
            if *f > 0.0 {
                wetting
                    .fill(atlas, *f)
                    .map_err(|e| loaded.invalid(&key(".initial"), e.to_string()))?;
            }
        }
        InitialLiquid::Image(file) => {
            let path = loaded.resolve(file);
            let image = soak_wet::LiquidImage::open(&path)
                .map_err(|e| loaded.invalid(&key(".initial"), format!("`{}`: {e}", path.display())))?;
            wetting
                .set_liquid_from_image(atlas, &image, material.saturation)
                .map_err(|e| loaded.invalid(&key(".initial"), format!("`{}`: {e}", path.display())))?;
        }
    }
    Ok(wetting)
}

/// The liquid graph a body's `graph` key asks for, behind its atlas' wall.
fn flooding(
    loaded: &LoadedScene,
    i: usize,
    mesh: &soak_bake::Mesh,
    atlas: &Atlas,
    spec: &crate::scene::GraphSpec,
    walls_volume: f64,
) -> Result<soak_graph::Flooding, String> {
    use soak_graph::{Flooding, FlowOptions, LiquidGraph, Permeability, SegmentGraphOptions, TexelNodes};
    // An open mesh's caps are openings; every other wall starts watertight.
    let wall = Permeability::open_mesh(atlas);
    match spec {
        crate::scene::GraphSpec::Cavity(_) => {
            Flooding::open_container(atlas, walls_volume, FlowOptions::default()).map_err(|e| e.to_string())
        }
        crate::scene::GraphSpec::File(file) => {
            let path = loaded.resolve(file);
            let graph = soak_graph::load_graph(&path).map_err(|e| e.to_string())?;
            Flooding::for_atlas(atlas, graph, wall, FlowOptions::default()).map_err(|e| e.to_string())
        }
        crate::scene::GraphSpec::Auto(a) => {
            let options = soak_graph::segment::SegmentOptions {
                clusters: a.clusters,
                ..Default::default()
            };
            let seg = soak_graph::segment::segment(mesh, &options)
                .map_err(|e| format!("bodies[{i}].graph: {e}"))?;
            let graph_options = SegmentGraphOptions {
                porosity: a.porosity,
                ..Default::default()
            };
            let graph = LiquidGraph::from_segmentation(&seg, &graph_options).map_err(|e| e.to_string())?;
            let map = TexelNodes::from_segmentation(atlas, &seg).map_err(|e| e.to_string())?;
            Flooding::new(graph, wall, map, FlowOptions::default()).map_err(|e| e.to_string())
        }
    }
}

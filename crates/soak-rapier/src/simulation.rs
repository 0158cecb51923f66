//! A scene running: a Rapier world, the force generator and the records.

use nalgebra::{Isometry3, Translation3, UnitQuaternion, Vector3};
use rapier3d::prelude::*;
use serde::Serialize;
use soak_bake::{Atlas, BakeOptions, UnwrapOptions};
use soak_hydro::{Gerstner, HeightField, MassModel, Plane, Unbounded, Water};

use crate::convert;
use crate::error::{SceneError, SoakError};
use crate::generator::{BodyDesc, Effects, ForceGenerator, SoakId};
use crate::scene::{ColliderSpec, InitialLiquid, LoadedScene, MassSpec, WaterKind, WettingSpec};

/// One body of a running scene.
#[derive(Clone, Debug)]
pub struct SimBody {
    /// Its name in the scene.
    pub name: String,
    /// The Rapier body.
    pub handle: RigidBodyHandle,
    /// The soak body, if it is not fixed.
    pub id: Option<SoakId>,
}

/// One recorded sample of one body.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Sample {
    /// Time, s.
    pub t: f64,
    /// Body index in the scene.
    pub body: usize,
    /// Position of the body origin, m.
    pub position: [f64; 3],
    /// Orientation as a quaternion `[x, y, z, w]`.
    pub rotation: [f64; 4],
    /// Linear velocity, m/s.
    pub linear_velocity: [f64; 3],
    /// Angular velocity, rad/s.
    pub angular_velocity: [f64; 3],
    /// Buoyancy force, N.
    pub buoyancy: [f64; 3],
    /// Drag force, N.
    pub drag: [f64; 3],
    /// Submerged volume, m³.
    pub submerged_volume: f64,
    /// Mass as Rapier has it, kg.
    pub mass: f64,
    /// Liquid inside (liquid graph), m³.
    pub liquid_inside: f64,
    /// Liquid soaked into the surface (the wetting liquid texture,
    /// `Σ a_i h_i`), m³; 0 without wetting.
    pub surface_liquid: f64,
}

/// The final state of a body, as `soak simulate --json` prints it.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct BodyReport {
    /// Name.
    pub name: String,
    /// Position of the body origin, m.
    pub position: [f64; 3],
    /// Orientation as a quaternion `[x, y, z, w]`.
    pub rotation: [f64; 4],
    /// Orientation as Euler angles about x, y, z, degrees (`R = Rz Ry Rx`).
    pub euler_deg: [f64; 3],
    /// Linear velocity, m/s.
    pub linear_velocity: [f64; 3],
    /// Angular velocity, rad/s.
    pub angular_velocity: [f64; 3],
    /// Submerged volume over total volume.
    pub submerged_fraction: f64,
    /// Mass, kg.
    pub mass: f64,
    /// Liquid inside (bodies with a liquid graph), m³.
    pub liquid_inside: Option<f64>,
    /// Liquid soaked into the surface (bodies with wetting), m³.
    pub surface_liquid: Option<f64>,
    /// Whether any state or force went non-finite during the run.
    pub non_finite: bool,
}

/// Everything a running scene owns, for saving and resuming: the scene
/// itself, the Rapier world and the generator's state (with each wet
/// body's liquid texture, each flooding body's liquid inside, and the
/// environment).
/// A run resumed from it continues bit for bit as the uninterrupted run.
#[derive(Clone, Serialize, serde::Deserialize)]
pub struct SavedSimulation {
    /// The scene file's path (for relative paths and messages).
    pub scene_path: std::path::PathBuf,
    /// The scene file's text.
    pub scene_text: String,
    /// The Rapier world in rapier's own serde form, postcard-encoded
    /// (`PhysicsWorld` is serialisable but not `Clone`).
    pub world: Vec<u8>,
    /// The force generator's state, with the liquid inside flooding bodies.
    pub generator: crate::generator::GeneratorState,
    /// Which permeable regions have opened.
    pub punched: Vec<bool>,
    /// Which splashes have landed.
    #[serde(default)]
    pub splashed: Vec<bool>,
    /// Steps taken.
    pub steps: u64,
    /// Per body: whether it went non-finite.
    pub non_finite: Vec<bool>,
}

impl SavedSimulation {
    /// The saved state as bytes: self-describing JSON (the state holds
    /// internally tagged enums, which a non-self-describing format cannot
    /// read back), with floats written so that they read back bit for bit.
    pub fn to_bytes(&self) -> Result<Vec<u8>, SoakError> {
        Ok(serde_json::to_vec(self)?)
    }

    /// Reads what [`SavedSimulation::to_bytes`] wrote; damaged or truncated
    /// input is a [`SoakError::Json`], never a panic.
    pub fn from_bytes(bytes: &[u8]) -> Result<Self, SoakError> {
        Ok(serde_json::from_slice(bytes)?)
    }
}

/// A scene built into a Rapier world with its force generator.
pub struct Simulation {
    /// The Rapier world.
    pub world: PhysicsWorld,
    /// The force generator.
    pub soak: ForceGenerator,
    /// The bodies, in scene order.
    pub bodies: Vec<SimBody>,
    /// Duration from the scene, s.
    pub duration: f64,
    /// (flooding body, hole, punched)
    holes: Vec<(SoakId, crate::scene::HoleSpec, bool)>,
    /// (splash, landed)
    splashes: Vec<(crate::scene::SplashSpec, bool)>,
    /// The weather over time, when the scene changes it.
    weather: Option<soak_wet::EnvironmentTrack>,
    record_every: usize,
    recording: bool,
    samples: Vec<Sample>,
    non_finite: Vec<bool>,
    steps: u64,
}

impl std::fmt::Debug for Simulation {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Simulation")
            .field("bodies", &self.bodies)
            .field("duration", &self.duration)
            .field("steps", &self.steps)
            .finish_non_exhaustive()
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

impl Simulation {
    /// Builds the world a scene describes: loads and bakes every mesh,
    /// registers the bodies with their effects.
    pub fn from_scene(loaded: &LoadedScene) -> Result<Self, SceneError> {
        let scene = &loaded.scene;
        let mut world = PhysicsWorld::new();
        world.gravity = convert::to_vector(&Vector3::from(scene.gravity));
        world.integration_parameters.dt = scene.dt as f32;
        let mut soak = ForceGenerator::new(water_of(loaded)?).with_backend(scene.backend);
        let mut weather = None;
        if let Some(env) = &scene.environment {
            soak.set_environment(env.environment())
                .map_err(|e| loaded.invalid("environment", e.to_string()))?;
            weather = env
                .track()
                .map_err(|e| loaded.invalid("environment.keys", e.to_string()))?;
        }
        if scene.backend == crate::generator::Backend::Gpu {
            soak = with_gpu(soak).map_err(|message| SceneError::Invalid {
                path: loaded.path.clone(),
                line: loaded.line_of("backend"),
                key: "backend".into(),
                message,
            })?;
        }
        let mut bodies = Vec::new();
        let mut holes = Vec::new();
        for (i, b) in scene.bodies.iter().enumerate() {
            let body_err = |message: String| SceneError::Body {
                path: loaded.path.clone(),
                line: loaded.line_of(&format!("bodies[{i}].mesh")),
                body: b.name.clone(),
                message,
            };
            let source = if b.mesh.starts_with("builtin:") {
                b.mesh.clone()
            } else {
                loaded.resolve(&b.mesh).to_string_lossy().into_owned()
            };
            let mut mesh = soak_bake::load_mesh(&source).map_err(|e| body_err(e.to_string()))?;
            if b.unwrap {
                mesh = soak_bake::unwrap(&mesh, UnwrapOptions::default())
                    .map_err(|e| body_err(e.to_string()))?
                    .0;
            }
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
                ColliderSpec::Trimesh => Some(
                    ColliderBuilder::trimesh(points(), mesh.triangles.clone())
                        .map_err(|e| body_err(format!("trimesh collider: {e}")))?,
                ),
            };
            if let Some(c) = collider {
                world
                    .colliders
                    .insert_with_parent(c.density(0.0), handle, &mut world.bodies);
            }
            let id = if b.fixed {
                None
            } else {
                let atlas = Atlas::bake(&mesh, BakeOptions::square(b.resolution))
                    .map_err(|e| body_err(e.to_string()))?;
                let mass_model = match b.mass {
                    MassSpec::Solid { density } => MassModel::Solid { density },
                    MassSpec::Shell { areal_density } => MassModel::Shell { areal_density },
                };
                let wetting = b
                    .wetting
                    .as_ref()
                    .map(|spec| wetting_of(loaded, i, spec, &atlas))
                    .transpose()?;
                let flooding = b
                    .graph
                    .as_ref()
                    .map(|spec| flooding(loaded, i, &mesh, &atlas, spec).map_err(body_err))
                    .transpose()?;
                let effects = Effects {
                    buoyancy: Some(b.buoyancy),
                    drag: b.drag,
                    flooding,
                    wetting,
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

    /// Records a sample of every body each `output.every` steps from now on.
    pub fn record(&mut self, on: bool) {
        self.recording = on;
        if on && self.samples.is_empty() {
            self.sample();
        }
    }

    /// The recorded samples.
    pub fn samples(&self) -> &[Sample] {
        &self.samples
    }

    /// Time step, s.
    pub fn dt(&self) -> f64 {
        self.world.integration_parameters.dt as f64
    }

    /// Simulated time, s.
    pub fn time(&self) -> f64 {
        self.soak.time()
    }

    /// Steps taken so far (a resumed run counts the saved run's steps).
    pub fn steps_taken(&self) -> u64 {
        self.steps
    }

    /// Number of steps for the scene's duration.
    pub fn total_steps(&self) -> u64 {
        (self.duration / self.dt()).round() as u64
    }

    /// One step.
    pub fn step(&mut self) -> Result<(), SoakError> {
        let t = self.soak.time();
        for (id, hole, punched) in self.holes.iter_mut() {
            if !*punched && t >= hole.at {
                self.soak
                    .punch(*id, nalgebra::Point3::from(hole.centre), hole.radius, hole.kappa)?;
                *punched = true;
            }
        }
        if let Some(track) = &self.weather {
            self.soak.set_environment(track.at(t))?;
        }
        for (splash, landed) in self.splashes.iter_mut() {
            if !*landed && t >= splash.at {
                self.soak.splash(&self.world.bodies, &splash.splash())?;
                *landed = true;
            }
        }
        self.soak.step(&mut self.world)?;
        self.steps += 1;
        for (i, b) in self.bodies.iter().enumerate() {
            let rb = &self.world.bodies[b.handle];
            let ok = rb.translation().is_finite() && rb.linvel().is_finite() && rb.angvel().is_finite();
            self.non_finite[i] |= !ok;
        }
        if self.recording && self.steps.is_multiple_of(self.record_every as u64) {
            self.sample();
        }
        Ok(())
    }

    /// Runs to the scene's duration, calling `progress` with the step count after each step.
    pub fn run(&mut self, mut progress: impl FnMut(u64)) -> Result<(), SoakError> {
        for k in 0..self.total_steps() {
            self.step()?;
            progress(k + 1);
        }
        Ok(())
    }

    fn sample(&mut self) {
        let t = self.soak.time();
        for (i, b) in self.bodies.iter().enumerate() {
            let rb = &self.world.bodies[b.handle];
            let forces =
                b.id.and_then(|id| self.soak.body(id))
                    .map(|sb| *sb.forces())
                    .unwrap_or_default();
            let q = rb.rotation();
            self.samples.push(Sample {
                t,
                body: i,
                position: convert::vector(rb.translation()).into(),
                rotation: [q.x as f64, q.y as f64, q.z as f64, q.w as f64],
                linear_velocity: convert::vector(rb.linvel()).into(),
                angular_velocity: convert::vector(rb.angvel()).into(),
                buoyancy: forces.buoyancy.force.into(),
                drag: forces.drag.force.into(),
                submerged_volume: forces.submerged_volume,
                mass: rb.mass() as f64,
                liquid_inside: self.liquid_of(b.id).unwrap_or(0.0),
                surface_liquid: self.surface_liquid_of(b.id).unwrap_or(0.0),
            });
        }
    }

    /// Liquid in the body's surface (its wetting liquid texture), m³.
    fn surface_liquid_of(&self, id: Option<SoakId>) -> Option<f64> {
        let b = self.soak.body(id?)?;
        Some(b.wetting()?.total_liquid(b.atlas()))
    }

    /// Writes the liquid texture of every wet body as a pseudo-colour PNG
    /// (thesis Fig. 7.14, right column: dark blue dry through cyan and
    /// yellow to dark red at saturation; uncovered atlas texels dark grey)
    /// into `dir` (created if needed), one file per body named
    /// `{body}_liquid_{step:06}.png` with the steps taken so far. Returns
    /// the files written (none without wet bodies).
    pub fn write_liquid_pngs(&self, dir: &std::path::Path) -> Result<Vec<std::path::PathBuf>, SoakError> {
        let mut written = Vec::new();
        for b in &self.bodies {
            let Some(sb) = b.id.and_then(|id| self.soak.body(id)) else {
                continue;
            };
            let Some(w) = sb.wetting() else {
                continue;
            };
            if written.is_empty() {
                std::fs::create_dir_all(dir).map_err(|source| SoakError::Io {
                    path: dir.to_path_buf(),
                    source,
                })?;
            }
            let safe: String = b
                .name
                .chars()
                .map(|c| {
                    if c.is_alphanumeric() || c == '-' || c == '_' {
                        c
                    } else {
                        '_'
                    }
                })
                .collect();
            let path = dir.join(format!("{safe}_liquid_{:06}.png", self.steps));
            soak_wet::write_liquid_png(sb.atlas(), w.liquid(), w.material().saturation, &path).map_err(
                |source| SoakError::Wet {
                    name: b.name.clone(),
                    source,
                },
            )?;
            written.push(path);
        }
        Ok(written)
    }

    /// Liquid inside the body (its flooding), m³.
    fn liquid_of(&self, id: Option<SoakId>) -> Option<f64> {
        self.soak.flooding(id?).map(soak_graph::Flooding::inside)
    }

    /// Saves everything needed to resume this run exactly (see [`Simulation::resume`]).
    pub fn save(&self, scene: &LoadedScene) -> Result<SavedSimulation, SoakError> {
        Ok(SavedSimulation {
            scene_path: scene.path.clone(),
            scene_text: scene.text.clone(),
            world: postcard::to_stdvec(&self.world)?,
            generator: self.soak.state(),
            punched: self.holes.iter().map(|h| h.2).collect(),
            splashed: self.splashes.iter().map(|s| s.1).collect(),
            steps: self.steps,
            non_finite: self.non_finite.clone(),
        })
    }

    /// Rebuilds a run from a save: the scene is built again (meshes baked
    /// as before), then the world and the generator (with the liquid inside
    /// flooding bodies) take their saved states.
    pub fn resume(saved: &SavedSimulation) -> Result<Self, SceneError> {
        let loaded = LoadedScene::from_str(&saved.scene_text, &saved.scene_path)?;
        let mut sim = Self::from_scene(&loaded)?;
        let bad = |message: String| SceneError::Invalid {
            path: loaded.path.clone(),
            line: 1,
            key: "(saved state)".into(),
            message,
        };
        if saved.generator.bodies.len() != sim.soak.bodies().len()
            || saved.punched.len() != sim.holes.len()
            || saved.splashed.len() != sim.splashes.len()
        {
            return Err(bad(
                "the save does not match the scene's bodies, holes or splashes".into(),
            ));
        }
        sim.world = postcard::from_bytes(&saved.world).map_err(|e| bad(format!("the Rapier world: {e}")))?;
        sim.soak
            .restore_state(&saved.generator)
            .map_err(|e| bad(e.to_string()))?;
        for (h, &p) in sim.holes.iter_mut().zip(&saved.punched) {
            h.2 = p;
        }
        for (s, &landed) in sim.splashes.iter_mut().zip(&saved.splashed) {
            s.1 = landed;
        }
        sim.steps = saved.steps;
        sim.non_finite = saved.non_finite.clone();
        Ok(sim)
    }

    /// The final state of every body.
    pub fn report(&self) -> Vec<BodyReport> {
        self.bodies
            .iter()
            .enumerate()
            .map(|(i, b)| {
                let rb = &self.world.bodies[b.handle];
                let q = convert::rotation(*rb.rotation());
                let (rx, ry, rz) = q.euler_angles();
                let (fraction, non_finite) = match b.id.and_then(|id| self.soak.body(id)) {
                    Some(sb) => (
                        sb.forces().submerged_volume / sb.atlas().volume(),
                        !sb.forces().buoyancy.is_finite() || !sb.forces().drag.is_finite(),
                    ),
                    None => (0.0, false),
                };
                BodyReport {
                    name: b.name.clone(),
                    position: convert::vector(rb.translation()).into(),
                    rotation: [q.i, q.j, q.k, q.w],
                    euler_deg: [rx.to_degrees(), ry.to_degrees(), rz.to_degrees()],
                    linear_velocity: convert::vector(rb.linvel()).into(),
                    angular_velocity: convert::vector(rb.angvel()).into(),
                    submerged_fraction: fraction,
                    mass: rb.mass() as f64,
                    liquid_inside: self.liquid_of(b.id),
                    surface_liquid: self.surface_liquid_of(b.id),
                    non_finite: self.non_finite[i] || non_finite,
                }
            })
            .collect()
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
) -> Result<soak_graph::Flooding, String> {
    use soak_graph::{Flooding, FlowOptions, LiquidGraph, Permeability, SegmentGraphOptions, TexelNodes};
    let wall = Permeability::watertight(atlas);
    match spec {
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

//! Building the worlds and timing their steps.

use std::sync::Arc;

use std::time::Instant;

use rapier3d::prelude::*;
use soak_bake::{Atlas, BakeOptions, builtin};
use soak_hydro::{Drag, DragTexels, MassModel, SeaSampling, Water};
use soak_rapier::soak_seakeeping::{FloatingBody, RadiationModel};
use soak_rapier::{BodyDesc, Effects, ForceGenerator, SoakError, radiation_settings};

use super::{
    Case, Column, Device, Measurement, PhaseMeans, ScalingError, ScalingOptions, ScalingReport, Variant,
    WaterKind,
};

/// Solid density of every body, kg/m³.
pub const DENSITY: f64 = 500.0;
/// Grid spacing, m.
pub const SPACING: f64 = 2.0;
/// The drag of the buoyancy + drag columns.
pub const DRAG: Drag = Drag {
    coefficient: 0.8,
    linear: 20.0,
};
/// Box size, m.
pub const BOX: [f64; 3] = [1.0, 0.6, 0.8];
/// Sphere radius, m.
pub const RADIUS: f64 = 0.5;

/// The two meshes, each baked once, and what every body of that mesh
/// shares: its mass and volume.
#[derive(Clone, Debug)]
pub struct Fleet {
    /// The box's atlas (even bodies), shared by every box.
    pub box_atlas: Arc<Atlas>,
    /// The sphere's atlas (odd bodies), shared by every sphere.
    pub sphere_atlas: Arc<Atlas>,
    /// Volumes of the box and the sphere, m³.
    pub volumes: [f64; 2],
    /// Masses of the box and the sphere, kg.
    pub masses: [f64; 2],
    /// Baking both, ms.
    pub bake_ms: f64,
    /// The box's and the sphere's drag texels, when the drag is summed
    /// over their atlases coarsened ([`Fleet::coarsen_drag`]).
    pub drag_texels: Option<[Arc<DragTexels>; 2]>,
    /// The sphere's mesh (its radiation is baked from it).
    sphere_mesh: soak_bake::Mesh,
    /// The box's and the sphere's radiation, baked when first asked for
    /// ([`Fleet::radiation`]).
    radiation: std::sync::OnceLock<[Arc<RadiationModel>; 2]>,
}

impl Fleet {
    /// Bakes the box and the sphere at `resolution`².
    ///
    /// # Errors
    /// A mesh that does not bake.
    pub fn bake(resolution: u32, sphere_segments: (usize, usize)) -> Result<Self, ScalingError> {
        let start = Instant::now();
        let bake = |mesh: &soak_bake::Mesh, name: &'static str| {
            Atlas::bake(mesh, BakeOptions::square(resolution))
                .map_err(|source| ScalingError::Bake { mesh: name, source })
        };
        let box_atlas = bake(&builtin::cuboid(BOX[0], BOX[1], BOX[2]), "box")?;
        let sphere_mesh = builtin::sphere(RADIUS, sphere_segments.0, sphere_segments.1);
        let sphere_atlas = bake(&sphere_mesh, "sphere")?;
        let bake_ms = start.elapsed().as_secs_f64() * 1e3;
        let volumes = [box_atlas.volume(), sphere_atlas.volume()];
        Ok(Self {
            box_atlas: Arc::new(box_atlas),
            sphere_atlas: Arc::new(sphere_atlas),
            volumes,
            masses: volumes.map(|v| v * DENSITY),
            bake_ms,
            drag_texels: None,
            sphere_mesh,
            radiation: std::sync::OnceLock::new(),
        })
    }

    /// The radiation of body `i`'s mesh floating in `water`, baked once
    /// per fleet (the first water asked for: its density and gravity are
    /// every water's here) with a scene's settings.
    ///
    /// # Errors
    /// A mesh whose radiation does not bake.
    pub fn radiation(&self, i: usize, water: &Water) -> Result<Arc<RadiationModel>, ScalingError> {
        if self.radiation.get().is_none() {
            let bake = |mesh: &soak_bake::Mesh, atlas: &Atlas, name: &'static str| {
                let mass = MassModel::Solid { density: DENSITY }
                    .mass_properties(atlas)
                    .map_err(|source| {
                        ScalingError::Soak(SoakError::Hydro {
                            name: name.to_string(),
                            source,
                        })
                    })?;
                let body = FloatingBody {
                    mesh,
                    mass: mass.mass,
                    center_of_mass: mass.center_of_mass,
                    inertia: mass.inertia,
                    rotation: nalgebra::UnitQuaternion::identity(),
                };
                RadiationModel::bake(&body, &radiation_settings(water))
                    .map(Arc::new)
                    .map_err(|source| ScalingError::Radiation { mesh: name, source })
            };
            let made = [
                bake(&builtin::cuboid(BOX[0], BOX[1], BOX[2]), &self.box_atlas, "box")?,
                bake(&self.sphere_mesh, &self.sphere_atlas, "sphere")?,
            ];
            let _ = self.radiation.set(made);
        }
        Ok(self.radiation.get().expect("set above")[i % 2].clone())
    }

    /// Sums the drag of every body over its atlas coarsened by `factor`.
    ///
    /// # Errors
    /// A factor out of range.
    pub fn coarsen_drag(&mut self, factor: u32) -> Result<(), ScalingError> {
        let coarsen = |atlas: &Arc<Atlas>, name: &'static str| {
            DragTexels::coarsened(atlas.clone(), factor)
                .map(Arc::new)
                .map_err(|source| ScalingError::Bake { mesh: name, source })
        };
        self.drag_texels = Some([
            coarsen(&self.box_atlas, "box")?,
            coarsen(&self.sphere_atlas, "sphere")?,
        ]);
        Ok(())
    }

    /// The atlas of body `i`.
    pub fn atlas(&self, i: usize) -> &Arc<Atlas> {
        if i.is_multiple_of(2) {
            &self.box_atlas
        } else {
            &self.sphere_atlas
        }
    }
}

/// Bytes of an atlas' arrays (what each body's copy costs).
pub fn atlas_bytes(a: &Atlas) -> usize {
    use std::mem::size_of_val;
    let columns = |c: &soak_bake::Columns| 3 * size_of_val(c.x());
    columns(a.local_positions())
        + columns(a.area_vectors())
        + size_of_val(a.areas())
        + size_of_val(a.triangle_ids())
        + size_of_val(a.barycentrics())
        + size_of_val(a.texels())
        + size_of_val(a.centroid_samples())
        + size_of_val(a.tiles())
        + size_of_val(a.triangles())
        + size_of_val(a.texels_per_triangle())
}

/// Where body `i` of `n` sits on the grid (x, z), m.
fn grid(i: usize, n: usize) -> (f64, f64) {
    let side = (n as f64).sqrt().ceil().max(1.0) as usize;
    ((i % side) as f64 * SPACING, (i / side) as f64 * SPACING)
}

/// The water of a case.
fn water(kind: WaterKind) -> Result<Water, ScalingError> {
    Ok(match kind {
        WaterKind::Calm => Water::calm(0.0),
        WaterKind::Swell => crate::accuracy::swell()?,
        WaterKind::Jonswap => super::jonswap()?,
    })
}

/// A world of `n` bodies driven as `column` says, and the generator
/// driving it (none for Rapier alone). `gpu` makes the generator's GPU
/// backend (called before any body is registered).
fn build(
    fleet: &Fleet,
    n: usize,
    column: &Column,
    gpu: &dyn Fn(ForceGenerator) -> Result<ForceGenerator, ScalingError>,
    sea: Option<SeaSampling>,
) -> Result<(PhysicsWorld, Option<ForceGenerator>), ScalingError> {
    let mut world = PhysicsWorld::new();
    world.integration_parameters.dt = 1.0 / 60.0;
    let height = match column.water {
        Some(w) => Some(water(w)?),
        None => None,
    };
    let mut soak = match column.water {
        None => None,
        Some(w) => {
            let g = ForceGenerator::new(water(w)?);
            let g = match (column.device, w) {
                (Device::Cpu, _) => g,
                // The spectral sea's tile evaluated on the device in the
                // step's own submission, every texel reading it there.
                (Device::Gpu, WaterKind::Jonswap) => gpu(g)?.with_sea_sampling(SeaSampling::Exact),
                (Device::Gpu, _) => gpu(g)?,
            };
            Some(match sea {
                Some(s) => g.with_sea_sampling(s),
                None => g,
            })
        }
    };
    let effects = |i: usize| -> Result<Effects, ScalingError> {
        Ok(match column.variant {
            Variant::RapierAlone | Variant::Buoyancy => Effects::buoyancy(),
            Variant::BuoyancyDrag => match &fleet.drag_texels {
                Some(texels) => Effects::buoyancy()
                    .with_drag(DRAG)
                    .with_drag_texels(texels[i % 2].clone()),
                None => Effects::buoyancy().with_drag(DRAG),
            },
            Variant::BuoyancyRadiation => {
                let water = height.as_ref().expect("the generator's columns have a water");
                Effects::buoyancy().with_radiation(fleet.radiation(i, water)?)
            }
        })
    };
    for i in 0..n {
        let (x, z) = grid(i, n);
        // At the floating draft: half as dense as water, each body floats
        // with its centre at the surface.
        let y = height.as_ref().map_or(0.0, |w| w.surface.height(x, z, 0.0));
        let handle = world
            .bodies
            .insert(RigidBodyBuilder::dynamic().translation(Vector::new(x as f32, y as f32, z as f32)));
        let shape = if i.is_multiple_of(2) {
            ColliderBuilder::cuboid(
                (BOX[0] / 2.0) as f32,
                (BOX[1] / 2.0) as f32,
                (BOX[2] / 2.0) as f32,
            )
        } else {
            ColliderBuilder::ball(RADIUS as f32)
        };
        let collider = match &soak {
            // The same mass as the generator gives the body.
            None => shape.mass(fleet.masses[i % 2] as f32),
            Some(_) => shape.density(0.0),
        };
        world
            .colliders
            .insert_with_parent(collider, handle, &mut world.bodies);
        if let Some(soak) = &mut soak {
            soak.register(
                &mut world.bodies,
                &world.colliders,
                handle,
                BodyDesc {
                    name: format!("{} {i}", if i.is_multiple_of(2) { "box" } else { "sphere" }),
                    atlas: fleet.atlas(i).clone(),
                    mass_model: MassModel::Solid { density: DENSITY },
                    effects: effects(i)?,
                },
            )?;
        }
    }
    Ok((world, soak))
}

/// One step of the world.
fn step(world: &mut PhysicsWorld, soak: &mut Option<ForceGenerator>) -> Result<(), ScalingError> {
    match soak {
        Some(s) => s.step(world)?,
        None => world.step(),
    }
    Ok(())
}

/// Resident memory of this process, MB (from `/proc/self/status`).
fn rss_mb() -> Option<f64> {
    let status = std::fs::read_to_string("/proc/self/status").ok()?;
    let line = status.lines().find(|l| l.starts_with("VmRSS:"))?;
    let kb: f64 = line.split_whitespace().nth(1)?.parse().ok()?;
    Some(kb / 1024.0)
}

/// One case's world, built and settled, and its timed steps so far.
struct Running {
    case: Case,
    world: PhysicsWorld,
    soak: Option<ForceGenerator>,
    setup_ms: f64,
    rss_mb: Option<f64>,
    rss_growth_mb: Option<f64>,
    /// Step times, ms.
    times: Vec<f64>,
    /// The generator's phases summed over the timed steps, ms.
    phases: PhaseMeans,
}

impl Running {
    /// Builds `case`'s world and steps it `options.settle_steps` times.
    fn start(
        fleet: &Fleet,
        case: &Case,
        options: &ScalingOptions,
        gpu: &dyn Fn(ForceGenerator) -> Result<ForceGenerator, ScalingError>,
    ) -> Result<Self, ScalingError> {
        let before = rss_mb();
        let start = Instant::now();
        let (mut world, mut soak) = build(fleet, case.bodies, &case.column, gpu, options.sea_sampling)?;
        let setup_ms = start.elapsed().as_secs_f64() * 1e3;
        let rss_mb = rss_mb();
        for _ in 0..options.settle_steps {
            step(&mut world, &mut soak)?;
        }
        Ok(Self {
            case: *case,
            world,
            soak,
            setup_ms,
            rss_mb,
            rss_growth_mb: rss_mb.zip(before).map(|(a, b)| a - b),
            times: Vec::new(),
            phases: PhaseMeans::default(),
        })
    }

    /// One timed step.
    fn time_step(&mut self) -> Result<(), ScalingError> {
        let s = Instant::now();
        step(&mut self.world, &mut self.soak)?;
        self.times.push(s.elapsed().as_secs_f64() * 1e3);
        if let Some(soak) = &self.soak {
            let p = soak.driver().last_step_phases();
            let ms = |d: std::time::Duration| d.as_secs_f64() * 1e3;
            let sum = &mut self.phases;
            sum.predict_ms += ms(p.predict);
            sum.prepare_ms += ms(p.prepare);
            sum.evaluate_ms += ms(p.evaluate);
            sum.hand_ms += ms(p.hand);
            sum.engine_ms += ms(p.engine);
        }
        Ok(())
    }

    /// What the timed steps measured.
    fn finish(mut self, fleet: &Fleet) -> Measurement {
        let times = &mut self.times;
        let mean_ms = times.iter().sum::<f64>() / times.len().max(1) as f64;
        times.sort_by(f64::total_cmp);
        let median_ms = match times.len() {
            0 => f64::NAN,
            n if n % 2 == 1 => times[n / 2],
            n => 0.5 * (times[n / 2 - 1] + times[n / 2]),
        };
        let submerged = self.soak.as_ref().map(|s| {
            s.bodies()
                .iter()
                .enumerate()
                .map(|(i, b)| b.forces().submerged_volume / fleet.volumes[i % 2])
                .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), f| {
                    (lo.min(f), hi.max(f))
                })
        });
        Measurement {
            case: self.case,
            steps: times.len(),
            median_ms,
            mean_ms,
            min_ms: times.first().copied().unwrap_or(f64::NAN),
            max_ms: times.last().copied().unwrap_or(f64::NAN),
            setup_ms: self.setup_ms,
            rss_mb: self.rss_mb,
            rss_growth_mb: self.rss_growth_mb,
            submerged,
            firewall: self.soak.as_ref().map_or(0, |s| s.firewall().count()),
            phases: self.soak.as_ref().map(|_| {
                let n = times.len().max(1) as f64;
                let p = self.phases;
                PhaseMeans {
                    predict_ms: p.predict_ms / n,
                    prepare_ms: p.prepare_ms / n,
                    evaluate_ms: p.evaluate_ms / n,
                    hand_ms: p.hand_ms / n,
                    engine_ms: p.engine_ms / n,
                }
            }),
        }
    }
}

/// Whether timing goes on after `done` timed steps (each case's, or each
/// round's with several cases in turn) and `elapsed` seconds of them, for
/// `cases` cases sharing the budget.
fn more(options: &ScalingOptions, done: usize, elapsed: f64, cases: usize) -> bool {
    let max_steps = options.max_steps.max(options.min_steps).max(1);
    done < max_steps && (done < options.min_steps.max(1) || elapsed < options.budget_s * cases as f64)
}

/// Builds and times one case.
///
/// # Errors
/// A body that does not register or a step that fails.
pub fn measure(
    fleet: &Fleet,
    case: &Case,
    options: &ScalingOptions,
    gpu: &dyn Fn(ForceGenerator) -> Result<ForceGenerator, ScalingError>,
) -> Result<Measurement, ScalingError> {
    let mut running = Running::start(fleet, case, options, gpu)?;
    let timing = Instant::now();
    while more(options, running.times.len(), timing.elapsed().as_secs_f64(), 1) {
        running.time_step()?;
    }
    Ok(running.finish(fleet))
}

/// Builds every case of `cases` (one size), then times them in turn, one
/// step of each per round ([`ScalingOptions::interleave`]).
///
/// # Errors
/// A body that does not register or a step that fails.
fn measure_interleaved(
    fleet: &Fleet,
    cases: &[Case],
    options: &ScalingOptions,
    gpu: &dyn Fn(ForceGenerator) -> Result<ForceGenerator, ScalingError>,
) -> Result<Vec<Measurement>, ScalingError> {
    let mut running = cases
        .iter()
        .map(|case| Running::start(fleet, case, options, gpu))
        .collect::<Result<Vec<_>, _>>()?;
    let timing = Instant::now();
    let mut rounds = 0;
    while more(options, rounds, timing.elapsed().as_secs_f64(), cases.len()) {
        for r in &mut running {
            r.time_step()?;
        }
        rounds += 1;
    }
    Ok(running.into_iter().map(|r| r.finish(fleet)).collect())
}

/// Runs the bench: every size, every column, in that order; `progress`
/// sees each measurement as it is made.
///
/// With `options.gpu` but no `gpu` feature or no adapter, the GPU
/// columns are skipped with a note; they run up to
/// `options.gpu_max_bodies` bodies.
///
/// # Errors
/// No sizes, a mesh that does not bake, a body that does not register or
/// a step that fails.
pub fn run(
    options: &ScalingOptions,
    mut progress: impl FnMut(&Measurement),
) -> Result<ScalingReport, ScalingError> {
    if options.sizes.is_empty() || options.sizes.contains(&0) {
        return Err(ScalingError::Sizes(options.sizes.clone()));
    }
    let start = Instant::now();
    let mut fleet = Fleet::bake(options.resolution, options.sphere_segments)?;
    if let Some(k) = options.drag_coarsening {
        fleet.coarsen_drag(k)?;
    }
    let mut notes = vec![
        "Rapier alone: the same bodies and masses without the generator; with no water they fall freely (no contacts)."
            .to_string(),
        format!(
            "the bodies of one mesh share its atlas ({} B for the box, {} B for the sphere) and its tiles; each body holds its own state",
            atlas_bytes(&fleet.box_atlas),
            atlas_bytes(&fleet.sphere_atlas)
        ),
    ];
    #[cfg(feature = "gpu")]
    let (device, gpu_label) = if options.gpu {
        match soak_hydro::gpu::headless_device() {
            Ok((device, queue, info)) => {
                let mut label = soak_hydro::gpu::adapter_label(&info);
                if soak_hydro::gpu::is_software(&info) {
                    label.push_str(
                        " (a software adapter: its times are CPU times, meaningless for GPU speed)",
                    );
                }
                notes.push(format!("GPU: {label}"));
                (Some((device, queue)), Some(label))
            }
            Err(e) => {
                notes.push(format!("GPU columns skipped: no adapter ({e})"));
                (None, None)
            }
        }
    } else {
        (None, None)
    };
    #[cfg(not(feature = "gpu"))]
    let gpu_label: Option<String> = {
        if options.gpu {
            notes.push("GPU columns skipped: this soak was built without its `gpu` feature".to_string());
        }
        None
    };
    let run_gpu = gpu_label.is_some();
    let gpu = |g: ForceGenerator| -> Result<ForceGenerator, ScalingError> {
        #[cfg(feature = "gpu")]
        if let Some((device, queue)) = &device {
            return Ok(g.with_gpu(device, queue)?);
        }
        Ok(g)
    };
    if run_gpu && options.sizes.iter().any(|&n| n > options.gpu_max_bodies) {
        notes.push(format!(
            "GPU columns run up to {} bodies (every body's atlas is uploaded)",
            options.gpu_max_bodies
        ));
    }
    if options.interleave {
        notes.push(
            "interleaved: every column's world of a size built first, then stepped in turn, one step each per round (ratios between columns of one moment; memory counts every world of the size)"
                .to_string(),
        );
    }
    let columns = Column::on(run_gpu, &options.waters);
    let mut measurements = Vec::new();
    for &n in &options.sizes {
        let cases: Vec<Case> = columns
            .iter()
            .filter(|c| !(c.device == Device::Gpu && n > options.gpu_max_bodies))
            .map(|c| Case {
                bodies: n,
                column: *c,
            })
            .collect();
        if options.interleave {
            for m in measure_interleaved(&fleet, &cases, options, &gpu)? {
                progress(&m);
                measurements.push(m);
            }
        } else {
            for case in &cases {
                let m = measure(&fleet, case, options, &gpu)?;
                progress(&m);
                measurements.push(m);
            }
        }
    }
    Ok(ScalingReport {
        options: options.clone(),
        columns,
        measurements,
        texels: (fleet.box_atlas.len(), fleet.sphere_atlas.len()),
        atlas_bytes: (atlas_bytes(&fleet.box_atlas), atlas_bytes(&fleet.sphere_atlas)),
        bake_ms: fleet.bake_ms,
        threads: rayon_threads(),
        gpu: gpu_label,
        notes,
        seconds: start.elapsed().as_secs_f64(),
    })
}

fn rayon_threads() -> usize {
    std::thread::available_parallelism().map_or(1, |n| n.get())
}

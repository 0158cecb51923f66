//! `soak stress`: the stability matrix.
//!
//! Every cell drops one body into one fluid and runs Rapier with the force
//! generator for a while, checking at every step that nothing non-finite
//! reached Rapier, and at the end that the body's energy stayed within what
//! the fluid could give it, that the liquid inside and on it was conserved
//! and stayed within its bounds, and that it floats, sinks or hovers as
//! its density says. `docs/stress.md` explains each check and its bound.

use std::sync::Mutex;
use std::sync::atomic::{AtomicUsize, Ordering};
use std::time::Instant;

use anyhow::{Context, bail};
use nalgebra::{Isometry3, Translation3, UnitQuaternion, Vector3};
use rapier3d::prelude::{PhysicsWorld, RigidBodyBuilder};
use serde::Serialize;
use soak_bake::{Atlas, BakeOptions, builtin};
use soak_graph::{Flooding, FlowOptions, LiquidGraph, Node, Permeability, Pipe, WATER_VISCOSITY};
use soak_hydro::{BuoyancyMode, Drag, Gerstner, GerstnerWave, HeightField, MassModel, Water};
use soak_rapier::liquid::{self, LiquidBody};
use soak_rapier::{BodyDesc, Effects, ForceGenerator, convert};
use soak_wet::{Diffusion, Environment, FieldResolution, Liquid, Material, Wetting};

/// Run the stability matrix and print a table of its cells.
#[derive(clap::Args, Debug)]
pub struct Args {
    /// The reduced matrix for CI: every mesh, water and effect, each with
    /// one of the extreme densities, scales and time steps.
    #[arg(long)]
    pub quick: bool,
    /// Print the table as Markdown (one row per mesh, water and effects,
    /// summing its cells; failing cells listed below).
    #[arg(long, conflicts_with = "json")]
    pub markdown: bool,
    /// Print every cell as JSON.
    #[arg(long)]
    pub json: bool,
    /// Only the cells whose name contains this text (e.g. `torus/sea`).
    #[arg(long)]
    pub only: Option<String>,
    /// Atlas resolution, texels per side [default: 32].
    #[arg(long)]
    pub resolution: Option<u32>,
    /// Most steps per cell [default: 150 with --quick, 300 otherwise].
    #[arg(long)]
    pub max_steps: Option<usize>,
    /// Cells run at once [default: the number of cores].
    #[arg(long)]
    pub threads: Option<usize>,
    /// Buoyancy mode of every cell: `archimedes` (ρ g V_s, vertical, at the
    /// centre of buoyancy) or `pressure` (the sum of each submerged texel's
    /// pressure force and its moment).
    #[arg(long, value_enum, default_value_t = ModeArg::Archimedes)]
    pub buoyancy: ModeArg,
}

/// `--buoyancy`.
#[derive(clap::ValueEnum, Clone, Copy, Debug, PartialEq, Eq)]
pub enum ModeArg {
    /// `BuoyancyMode::Archimedes`.
    Archimedes,
    /// `BuoyancyMode::Pressure`.
    Pressure,
}

impl ModeArg {
    fn mode(self) -> BuoyancyMode {
        match self {
            ModeArg::Archimedes => BuoyancyMode::Archimedes,
            ModeArg::Pressure => BuoyancyMode::Pressure,
        }
    }
}

/// Density of the water, kg/m³ (soak's default fluid).
const RHO_W: f64 = 1000.0;
/// Rapier's default gravity, m/s².
const G: f64 = 9.81;

/// Relative densities of the full matrix.
const DENSITIES: [f64; 7] = [0.01, 0.1, 0.5, 0.9, 1.0, 2.0, 10.0];
/// Time steps of the full matrix, as steps per second: the ends and the
/// middle of 1/240 … 1/10 s (all five of 240, 120, 60, 30, 10 would take
/// the full run past a quarter of an hour on two cores).
const RATES: [u32; 3] = [240, 60, 10];
/// Scales of the full matrix (the mesh's coordinates are multiplied by them).
const SCALES: [f64; 3] = [1e-3, 1.0, 1e3];

/// A mesh of the matrix: a `builtin:` name and a short label.
struct MeshSpec {
    label: &'static str,
    source: &'static str,
}

/// The builtins (at modest tessellations: a 32² atlas cannot use more) and a
/// sliver: a box 200 times longer than it is thick, whose long faces are
/// triangles of aspect ratio 200 that cover almost no texel centre.
const MESHES: [MeshSpec; 7] = [
    MeshSpec {
        label: "sphere",
        source: "builtin:sphere:0.5:24:12",
    },
    MeshSpec {
        label: "box",
        source: "builtin:box",
    },
    MeshSpec {
        label: "cylinder",
        source: "builtin:cylinder:0.5:1:24",
    },
    MeshSpec {
        label: "capsule",
        source: "builtin:capsule:0.25:0.5:16",
    },
    MeshSpec {
        label: "torus",
        source: "builtin:torus:0.5:0.15:24:12",
    },
    MeshSpec {
        label: "boat",
        source: "builtin:boat",
    },
    MeshSpec {
        label: "sliver",
        source: "builtin:box:2x0.01x0.01",
    },
];

/// The fluid of a cell.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
enum WaterKind {
    /// Calm water at y = 0.
    Plane,
    /// Two steep Gerstner waves about y = 0.
    Sea,
    /// A static height field with a cliff under the body.
    Cliff,
}

const WATERS: [WaterKind; 3] = [WaterKind::Plane, WaterKind::Sea, WaterKind::Cliff];

impl WaterKind {
    fn label(self) -> &'static str {
        match self {
            WaterKind::Plane => "plane",
            WaterKind::Sea => "sea",
            WaterKind::Cliff => "cliff",
        }
    }
}

/// The effects of a cell; each level adds to the one before.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Serialize)]
#[serde(rename_all = "snake_case")]
enum Level {
    /// Archimedes buoyancy.
    Buoyancy,
    /// + quadratic drag.
    Drag,
    /// + water entering through a permeable hull into a two-node graph.
    Ingress,
    /// + surface wetting with diffusion at 10× its explicit limit.
    Wetting,
}

const LEVELS: [Level; 4] = [Level::Buoyancy, Level::Drag, Level::Ingress, Level::Wetting];

impl Level {
    fn label(self) -> &'static str {
        match self {
            Level::Buoyancy => "buoyancy",
            Level::Drag => "+drag",
            Level::Ingress => "+ingress",
            Level::Wetting => "+wetting",
        }
    }
}

/// One cell of the matrix.
#[derive(Clone, Copy, Debug)]
struct Cell {
    mesh: usize,
    density: f64,
    rate: u32,
    scale: f64,
    water: WaterKind,
    level: Level,
}

impl Cell {
    fn name(&self) -> String {
        format!(
            "{}/{}/{}/1/{}/{}/{}",
            MESHES[self.mesh].label,
            fmt_scale(self.scale),
            self.density,
            self.rate,
            self.water.label(),
            self.level.label()
        )
    }
}

fn fmt_scale(s: f64) -> String {
    if s == 1.0 { "1m".into() } else { format!("{s:e}m") }
}

/// The full product.
fn full_matrix() -> Vec<Cell> {
    let mut cells = Vec::new();
    for mesh in 0..MESHES.len() {
        for &water in &WATERS {
            for &level in &LEVELS {
                for &scale in &SCALES {
                    for &density in &DENSITIES {
                        for &rate in &RATES {
                            cells.push(Cell {
                                mesh,
                                density,
                                rate,
                                scale,
                                water,
                                level,
                            });
                        }
                    }
                }
            }
        }
    }
    cells
}

/// Every mesh × water × effects, each with one (density, time step, scale)
/// taken in turn from a list that pairs the extremes: the lightest and the
/// heaviest bodies, the neutral one, the smallest and largest scales, the
/// shortest and longest steps all appear, on every mesh and in every water.
fn quick_matrix() -> Vec<Cell> {
    const PICKS: [(f64, u32, f64); 6] = [
        (0.01, 10, 1e-3),
        (10.0, 240, 1e3),
        (0.5, 60, 1.0),
        (1.0, 10, 1e3),
        (0.01, 240, 1e3),
        (10.0, 10, 1e-3),
    ];
    let mut cells = Vec::new();
    let mut k = 0;
    for mesh in 0..MESHES.len() {
        for &water in &WATERS {
            for &level in &LEVELS {
                let (density, rate, scale) = PICKS[k % PICKS.len()];
                k += 1;
                cells.push(Cell {
                    mesh,
                    density,
                    rate,
                    scale,
                    water,
                    level,
                });
            }
            // Shift the rotation so each mesh meets the picks in another order.
            k += 1;
        }
    }
    cells
}

/// A mesh baked at one scale, shared by its cells.
struct Fixture {
    atlas: Atlas,
    /// Enclosed volume, m³.
    volume: f64,
    /// Nominal size `V^(1/3)`, m.
    size: f64,
    /// Bounding radius about the atlas origin, m.
    radius: f64,
}

fn fixture(mesh: usize, scale: f64, resolution: u32) -> anyhow::Result<Fixture> {
    let spec = &MESHES[mesh];
    let m = builtin::parse(spec.source)?.map_positions(|p| p * scale);
    let atlas = Atlas::bake(&m, BakeOptions::square(resolution))
        .with_context(|| format!("baking {} at scale {scale}", spec.label))?;
    let volume = atlas.volume();
    if !(volume.is_finite() && volume > 0.0) {
        bail!("{} at scale {scale}: atlas volume {volume}", spec.label);
    }
    Ok(Fixture {
        size: volume.cbrt(),
        radius: atlas.bounding_radius(),
        volume,
        atlas,
    })
}

/// The fluid of a cell, sized to the body (bounding radius `r`, m).
fn water(kind: WaterKind, r: f64) -> anyhow::Result<Water> {
    Ok(match kind {
        WaterKind::Plane => Water::calm(0.0),
        WaterKind::Sea => {
            let wave = |wavelength: f64, direction_deg: f64, phase: f64| GerstnerWave {
                amplitude: 0.07 * wavelength,
                wavelength,
                direction_deg,
                steepness: 0.9,
                phase,
            };
            Water::new(Gerstner::new(
                0.0,
                vec![wave(8.0 * r, 0.0, 0.0), wave(5.0 * r, 40.0, 1.0)],
                G,
            )?)
        }
        WaterKind::Cliff => {
            // 0.3 r above the mean level for x < 0, 0.3 r below it for
            // x > 0, the step between two samples 0.1 r apart: a slope of 6.
            let n = 41;
            let spacing = 0.1 * r;
            let origin = -spacing * ((n - 1) / 2) as f64 - 0.5 * spacing;
            let heights = (0..n * n)
                .map(|i| {
                    let ix = i % n;
                    if ix < n / 2 { 0.3 * r } else { -0.3 * r }
                })
                .collect();
            Water::new(HeightField::new(
                [origin, origin],
                [spacing, spacing],
                n,
                n,
                heights,
            )?)
        }
    })
}

/// Submerged volume `Σ −A_y d` (m³) and the columns' potential
/// `Σ −A_y d²/2` (m⁴) of the atlas at `pose` in `water` at time `t`.
///
/// Once every texel is under water the potential is `∫_V d dV`, and the
/// columns reaching up to the surface from far below would sum it as
/// differences of numbers that grow with the depth (`Σ −A_y h_i y_i`, with
/// the surface's heights over the top and the bottom samples differing by
/// the sampling wherever the surface is not flat). It is then summed by
/// columns that stop at the height `Y` of the atlas origin, as
/// `∫_V h dV − Y V + ∫_V (Y − y) dV`, each term bounded by the body's size.
fn columns(atlas: &Atlas, pose: &Isometry3<f64>, water: &Water, t: f64) -> (f64, f64) {
    let mut volume = 0.0;
    let mut potential = 0.0;
    let top = (pose * atlas.origin()).y;
    let (mut under, mut local_potential) = (true, 0.0);
    let mut hint = [0.0; 2];
    for (i, a) in atlas.area_vectors().iter().enumerate() {
        let p = pose * atlas.position(i);
        let d = water.surface.probe(&p, t, false, &mut hint).0;
        let ay = (pose.rotation * Vector3::new(a[0] as f64, a[1] as f64, a[2] as f64)).y;
        if d > 0.0 {
            volume -= ay * d;
            potential -= ay * d * d / 2.0;
        } else {
            under = false;
        }
        // Column from the sample up to `top`: the surface's height
        // `h = d + y` relative to `top`, times the column, plus `∫ (top − y) dy`.
        let column = top - p.y;
        local_potential -= ay * ((d - column) * column + column * column / 2.0);
    }
    if under {
        return (volume, local_potential);
    }
    (volume, potential)
}

/// The height at which the body, turned by `rotation`, displaces
/// `fraction` of its volume in `water` at t = 0 (bisection).
fn equilibrium(f: &Fixture, rotation: &UnitQuaternion<f64>, fraction: f64, water: &Water) -> f64 {
    let pose = |y: f64| Isometry3::from_parts(Translation3::new(0.0, y, 0.0), *rotation);
    let (lowest, highest) = water.surface.height_bounds(0.0).unwrap_or((0.0, 0.0));
    let (mut lo, mut hi) = (lowest - 2.0 * f.radius, highest + 2.0 * f.radius);
    for _ in 0..60 {
        let mid = 0.5 * (lo + hi);
        let (v, _) = columns(&f.atlas, &pose(mid), water, 0.0);
        if v / f.volume > fraction {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    0.5 * (lo + hi)
}

/// What physics says the body does.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
enum Expect {
    /// Lighter than water: floats with the displaced fraction equal to its
    /// relative density.
    Floats,
    /// Heavier: sinks.
    Sinks,
    /// As dense as water: once under, neither rises nor sinks.
    Neutral,
}

/// What one cell measured.
#[derive(Clone, Debug, Serialize)]
struct Outcome {
    cell: String,
    mesh: &'static str,
    scale: f64,
    density: f64,
    dt: f64,
    water: WaterKind,
    effects: Level,
    steps: usize,
    /// Simulated time over the body's natural time `√(size/g)`.
    natural_times: f64,
    wall_ms: f64,
    /// Body state and applied forces finite at every step.
    finite: bool,
    /// Firewall events (rejected forces or states).
    firewall: u64,
    /// Largest growth of specific energy over the allowance (≤ 1 passes).
    energy_ratio: f64,
    /// Largest growth of specific energy, J/kg, and the allowance.
    energy_growth: f64,
    energy_allowance: f64,
    /// Worst liquid error (ingress and wetting; ≤ 1 passes), `None` without liquid.
    liquid_ratio: Option<f64>,
    liquid_note: String,
    /// Relative density at the end (mass with the liquid inside over the
    /// displaced water's when fully submerged).
    density_end: f64,
    expect: Expect,
    /// Mean displaced fraction over the last half, and what was expected.
    mean_fraction: f64,
    expected_fraction: f64,
    final_fraction: f64,
    /// Final vertical velocity over `√(g·size)`.
    final_vy: f64,
    /// Mean vertical velocity over the last half of the run, over `√(g·size)`.
    mean_vy: f64,
    settled: bool,
    settle_note: String,
    pass: bool,
    failures: Vec<String>,
}

/// Run length of a cell: 30 natural times, at least 60 steps, at most
/// `max_steps`; in the sea also two periods of the longer wave, so that the
/// last half of the run holds one whole period, at most `10 max_steps`.
fn step_count(size: f64, dt: f64, max_steps: usize, sea_period: Option<f64>) -> usize {
    let tau = (size / G).sqrt();
    let cap = max_steps.max(60);
    let run = ((30.0 * tau / dt).ceil() as usize).clamp(60, cap);
    match sea_period {
        Some(period) => run.max(((2.0 * period / dt).ceil() as usize).min(10 * cap)),
        None => run,
    }
}

fn run_cell(cell: &Cell, f: &Fixture, max_steps: usize, mode: BuoyancyMode) -> anyhow::Result<Outcome> {
    let start = Instant::now();
    let dt = 1.0 / cell.rate as f64;
    let size = f.size;
    let tau = (size / G).sqrt();
    let water = water(cell.water, f.radius)?;
    let (lowest, highest) = water.surface.height_bounds(0.0).unwrap_or((0.0, 0.0));

    // Start tilted, near the equilibrium in the cell's own water at t = 0
    // and a little deeper (floaters), or just under its surface (neutral and
    // sinking bodies).
    let rotation = UnitQuaternion::from_euler_angles(3f64.to_radians(), 0.0, 5f64.to_radians());
    let y_eq = equilibrium(f, &rotation, cell.density.min(1.0), &water);
    let y0 = y_eq - 0.05 * size;
    let pose0 = Isometry3::from_parts(Translation3::new(0.0, y0, 0.0), rotation);

    let mut world = PhysicsWorld::new();
    world.integration_parameters.dt = dt as f32;
    let handle = world
        .bodies
        .insert(RigidBodyBuilder::dynamic().pose(convert::to_pose(&pose0)));
    let mut effects = Effects::buoyancy().with_mode(mode);
    if cell.level >= Level::Drag {
        effects = effects.with_drag(Drag::default());
    }
    let mut soak = ForceGenerator::new(water);
    let id = soak.register(
        &mut world.bodies,
        &world.colliders,
        handle,
        BodyDesc {
            name: cell.name(),
            atlas: f.atlas.clone(),
            mass_model: MassModel::Solid {
                density: cell.density * RHO_W,
            },
            effects,
        },
    )?;

    // Ingress: two compartments of 15 % of the volume each, fore and aft,
    // joined by a pipe, behind a hull permeable all over. κ is set so that
    // the hull would take in its whole capacity in about 10 natural times
    // half submerged (Darcy: the inflow is about κ ρ g V_s / μ).
    let mut liquids = Vec::new();
    let capacity = 0.3 * f.volume;
    if cell.level >= Level::Ingress {
        let o = f.atlas.origin();
        let half = 0.3 * f.radius;
        let nodes = vec![
            Node::new("fore", o + Vector3::new(half, 0.0, 0.0), capacity / 2.0),
            Node::new("aft", o - Vector3::new(half, 0.0, 0.0), capacity / 2.0),
        ];
        let graph = LiquidGraph::new(nodes, vec![(0, 1, Pipe::new(0.05 * f.radius, 2.0 * half))])?;
        let kappa = capacity * WATER_VISCOSITY / (10.0 * tau * RHO_W * G * 0.5 * f.volume);
        let permeability = Permeability::uniform(&f.atlas, kappa)?;
        let flooding = Flooding::for_atlas(&f.atlas, graph, permeability, FlowOptions::default())?;
        liquids.push(LiquidBody::attach(&mut soak, &mut world, id, flooding)?);
    }

    // Wetting: cotton, a checkerboard of saturated and dry texels (the
    // hardest input for an explicit kernel), conservative diffusion whose
    // coefficient asks for 10 times the explicit limit in one step.
    let env = Environment::default();
    let mut wetting = None;
    let mut substeps_expected = 0;
    if cell.level >= Level::Wetting {
        // Four voxels along the longest side: coarse, so that even the
        // sliver's few samples (one per triangle at 32²) have neighbours.
        let field = FieldResolution::Cells(4);
        let mut wet = Wetting::new(&f.atlas, Material::cotton(), Liquid::water())?
            .with_diffusion(Diffusion::new(1e-12).with_resolution(field));
        let sat = wet.material().saturation;
        let checker = f
            .atlas
            .texels()
            .iter()
            .map(|t| if (t[0] / 3 + t[1] / 3) % 2 == 0 { sat } else { 0.0 })
            .collect();
        wet.set_liquid(&f.atlas, checker)?;
        let probe = wet.step(&f.atlas, &pose0, soak.water(), &env, 0.0, 1e-12)?;
        let count = probe.diffusion.map_or(0, |d| d.count_max);
        let voxel = wet.field_grid().map_or(0.0, |g| g.voxel_size);
        if count == 0 || voxel <= 0.0 {
            bail!("{}: wetting field has no neighbours", cell.name());
        }
        let coefficient = 10.0 * 3.0 * voxel * voxel / (dt * count as f64);
        wet.set_diffusion(Some(Diffusion::new(coefficient).with_resolution(field)))?;
        substeps_expected = 10;
        wetting = Some(wet);
    }
    let wet_capacity: f64 =
        f.atlas.areas().iter().map(|&a| a as f64).sum::<f64>() * Material::cotton().saturation;

    let sea_period = (cell.water == WaterKind::Sea).then(|| wave_period(f.radius));
    let steps = step_count(size, dt, max_steps, sea_period);
    let sample_every = (steps / 32).max(1);
    let mut failures = Vec::new();
    let mut finite = true;

    // Specific energy e = (KE + m g (y − ȳ) + ρ g Σ −A_y d²/2) / m, J/kg.
    let energy = |world: &PhysicsWorld, soak: &ForceGenerator| -> f64 {
        let rb = &world.bodies[handle];
        let body = soak.body(id).expect("registered");
        let mp = body.mass_properties();
        let pose = convert::pose(rb.position());
        let v = convert::vector(rb.linvel());
        let w = pose.rotation.inverse() * convert::vector(rb.angvel());
        let com = pose * mp.center_of_mass;
        let (_, potential) = columns(&f.atlas, &pose, soak.water(), soak.time());
        let m = mp.mass;
        (0.5 * m * v.norm_squared() + 0.5 * w.dot(&(mp.inertia * w)) + m * G * com.y + RHO_W * G * potential)
            / m
    };
    let e0 = energy(&world, &soak);
    let mut e_max = e0;

    let mut fraction_sum = 0.0;
    let mut centre_depth_sum = 0.0;
    let mut vy_sum = 0.0;
    let mut window = 0usize;
    let half = steps / 2;
    let mut liquid_worst: f64 = 0.0;
    let mut liquid_note = String::new();
    let mut taken = 0;

    for k in 0..steps {
        if let Some(wet) = wetting.as_mut() {
            let pose = convert::pose(world.bodies[handle].position());
            let report = wet.step(&f.atlas, &pose, soak.water(), &env, soak.time(), dt)?;
            let plan = report.diffusion.map(|d| d.plan).unwrap_or_default();
            if plan.limited || plan.substeps < substeps_expected || plan.substeps > substeps_expected + 1 {
                liquid_worst = f64::INFINITY;
                liquid_note = format!("step {k}: diffusion plan {plan:?}");
            }
        }
        if liquids.is_empty() {
            soak.step(&mut world)?;
        } else {
            liquid::step(&mut soak, &mut liquids, &mut world)?;
        }
        taken = k + 1;
        let rb = &world.bodies[handle];
        let body = soak.body(id).expect("registered");
        let state_ok = [rb.translation(), rb.linvel(), rb.angvel()]
            .iter()
            .all(|v| v.is_finite())
            && rb.rotation().is_finite()
            && body.applied().is_finite();
        if !state_ok {
            finite = false;
            failures.push(format!("non-finite state at step {k}"));
            break;
        }
        if k >= half {
            fraction_sum += body.forces().submerged_volume / f.volume;
            let com = convert::pose(rb.position()) * body.mass_properties().center_of_mass;
            centre_depth_sum += soak.water().surface.depth(&com, soak.time()) / size;
            vy_sum += rb.linvel().y as f64;
            window += 1;
        }
        if k % sample_every == 0 || k + 1 == steps {
            e_max = e_max.max(energy(&world, &soak));
            // Liquid inside: every node within [0, capacity], the ledger balanced.
            for l in &liquids {
                let fl = l.flooding();
                let inside = fl.inside();
                let over = fl
                    .graph()
                    .nodes()
                    .map(|n| {
                        (-n.liquid).max(n.liquid - n.capacity).max(0.0) / n.capacity.max(f64::MIN_POSITIVE)
                    })
                    .fold(0.0, f64::max);
                let ledger = fl.ledger().relative_error(inside);
                let ratio = (over / 1e-12)
                    .max(ledger / 1e-9)
                    .max((inside - capacity).max(0.0) / (1e-12 * capacity));
                if ratio > liquid_worst {
                    liquid_worst = ratio;
                    liquid_note = format!(
                        "inside {:.3} of capacity, ledger error {ledger:.1e}",
                        inside / capacity
                    );
                }
            }
            // Liquid on the surface: every texel in [0, saturation], the
            // total within [0, capacity] and balanced by the ledger.
            if let Some(wet) = &wetting {
                let sat = wet.material().saturation;
                let out = wet
                    .liquid()
                    .iter()
                    .map(|&h| (-h).max(h - sat).max(0.0) / sat)
                    .fold(0.0, f64::max);
                let total = wet.total_liquid(&f.atlas);
                // A new Wetting is dry: everything on it is in the ledger.
                let balance = (total - wet.ledger().net()).abs() / wet_capacity;
                let ratio = (out / 1e-12).max(balance / 1e-9).max(if total.is_finite() {
                    0.0
                } else {
                    f64::INFINITY
                });
                if ratio > liquid_worst || (liquid_note.is_empty() && liquid_worst == 0.0) {
                    liquid_worst = liquid_worst.max(ratio);
                    liquid_note = format!(
                        "surface {:.3} of saturation, balance error {balance:.1e}",
                        total / wet_capacity
                    );
                }
            }
        }
    }

    let rb = &world.bodies[handle];
    let body = soak.body(id).expect("registered");
    let firewall = soak.firewall().count();
    let m = body.mass_properties().mass;
    let density_end = m / (RHO_W * f.volume);
    let expect = if cell.level >= Level::Ingress && density_end > 1.0 + 1e-9 {
        Expect::Sinks
    } else if cell.density < 1.0 {
        Expect::Floats
    } else if cell.density > 1.0 {
        Expect::Sinks
    } else {
        Expect::Neutral
    };
    let final_fraction = body.forces().submerged_volume / f.volume;
    let final_vy = rb.linvel().y as f64 / (G * size).sqrt();
    let window = window.max(1) as f64;
    let mean_fraction = fraction_sum / window;
    let mean_centre_depth = centre_depth_sum / window;
    // Mean vertical velocity over the last half, in √(g·size).
    let mean_vy = vy_sum / window / (G * size).sqrt();
    // The vertical velocity the settling checks take: in the sea, whose
    // orbits carry a body up and down with the water wherever drag acts,
    // the mean over the last half; over a static surface the final one (a
    // hull that fills only becomes heavier than water late in its run).
    let (vy, vy_label) = if cell.water == WaterKind::Sea {
        (mean_vy, "mean v_y over the last half")
    } else {
        (final_vy, "final v_y")
    };
    // How far the centre of mass can lie from a surface the body touches:
    // the farthest point of the body from it, at most the bounding radius
    // about the atlas origin plus the centre's offset from that origin
    // (for a compact body about its size V^(1/3), for a rod its half
    // length), in sizes.
    let reach = {
        let com = body.mass_properties().center_of_mass;
        ((com.coords - f.atlas.origin().coords).norm() + f.radius) / size
    };

    // Energy allowance, J/kg: see docs/stress.md. The columns' potential
    // makes e constant for a body in calm water; a static height field
    // can still hand over ρ g V (hi − lo) of potential as the body moves
    // across it, and moving waves do work on the body.
    let waves = highest - lowest;
    let rho = cell.density;
    let periods = match cell.water {
        WaterKind::Sea => (taken as f64 * dt / wave_period(f.radius)).ceil(),
        _ => 1.0,
    };
    let allowance = 0.02 * G * size + G * waves * periods / rho.min(1.0);
    let energy_growth = e_max - e0;
    let energy_ratio = energy_growth / allowance;
    if energy_ratio.is_nan() || energy_ratio > 1.0 {
        failures.push(format!(
            "energy grew by {energy_growth:.3e} J/kg, allowance {allowance:.3e}"
        ));
    }

    let liquid_ratio = (cell.level >= Level::Ingress).then_some(liquid_worst);
    if let Some(r) = liquid_ratio
        && (r.is_nan() || r > 1.0)
    {
        failures.push(format!("liquid: {liquid_note}"));
    }

    // Settled or sunk as physics says.
    let (settled, settle_note, expected_fraction) = match expect {
        Expect::Floats => {
            // At the surface over the last half: neither sunk nor flown off.
            // A floating body moves away from the surface only with energy:
            // having gained Δe per kilogram (≥ 0, bounded by the energy
            // check), its centre can go below the surface over it by at most
            // ρ Δe / ((1 − ρ) g) more than it floats at (the net lift of a
            // submerged body is (1/ρ − 1) g per kilogram), and above it by
            // at most Δe / g; the surface itself spans hi − lo. A body that
            // touches the surface has its centre within its reach of it (one
            // size V^(1/3) for a compact body; a tilted rod's centre can lie
            // deeper, up to its half length). So the mean centre depth over
            // the last half must lie within the larger of one size and the
            // reach, plus the surface's span plus those excursions, either
            // way. On calm water, where there is no energy to gain, it must
            // also, in a run of at least 10 natural times (long enough for
            // what the 5 % deeper start throws up to come back down), be
            // partly and never wholly under water on average. A run can end with
            // a light body in the air on a ballistic arc (a wave or the cliff
            // threw it): that is not flying off if its energy allowed it.
            let gained = (e_max - e0).max(0.0);
            let span = reach.max(1.0) + waves / size;
            let dive = span + density_end * gained / ((1.0 - density_end).max(1e-9) * G * size);
            let rise = span + gained / (G * size);
            let mut ok = mean_centre_depth <= dive
                && -mean_centre_depth <= rise
                && (cell.water != WaterKind::Plane
                    || taken as f64 * dt < 10.0 * tau
                    || (mean_fraction > 0.0 && mean_fraction < 0.999));
            let mut note = format!(
                "mean centre depth {mean_centre_depth:.3} sizes in [−{rise:.3}, {dive:.3}], mean fraction {mean_fraction:.3}"
            );
            if cell.water == WaterKind::Plane && cell.level >= Level::Drag && taken as f64 * dt >= 20.0 * tau
            {
                let tol = 0.05 + 0.1 * density_end;
                ok &= (final_fraction - density_end).abs() <= tol;
                note = format!(
                    "{note}; final fraction {final_fraction:.3}, expected {density_end:.3} ± {tol:.3}"
                );
            }
            (ok, note, density_end)
        }
        Expect::Sinks => {
            // No sea bed: a sinking body is below where it started and still
            // going down (in the sea, on average over the last half: in the
            // orbits of a wave drag can lift it for a moment).
            // In the sea, going down over the last half of the run (its
            // mean velocity there) is what is asked: a hull that floated
            // until it filled can have been lifted above where it started
            // by the waves, whose surface rises and falls by more than the
            // body's size in a period.
            let dy = (rb.translation().y as f64 - y0) / size;
            let ok = vy < 0.0 && (dy < 0.0 || cell.water == WaterKind::Sea);
            (
                ok,
                format!("{vy_label} {vy:.3} √(g·size), {dy:.3} sizes from the start"),
                1.0,
            )
        }
        Expect::Neutral => {
            // Stays under without rising; on calm water it also does not sink.
            // Waves and the cliff bare it in their troughs, where it is heavier
            // than the water it displaces: there it may drift down. In the
            // sea its velocity is taken on average over the last half: in a
            // wave's orbits drag carries it up and down with the water.
            let sinking_allowed = cell.water != WaterKind::Plane;
            let ok = mean_fraction > 0.85 && vy < 0.1 && (sinking_allowed || vy > -0.1);
            (
                ok,
                format!("mean fraction {mean_fraction:.3}, {vy_label} {vy:.3} √(g·size)"),
                1.0,
            )
        }
    };
    if !settled {
        failures.push(format!("{expect:?}: {settle_note}"));
    }

    Ok(Outcome {
        cell: cell.name(),
        mesh: MESHES[cell.mesh].label,
        scale: cell.scale,
        density: cell.density,
        dt,
        water: cell.water,
        effects: cell.level,
        steps: taken,
        natural_times: taken as f64 * dt / tau,
        wall_ms: start.elapsed().as_secs_f64() * 1e3,
        finite,
        firewall,
        energy_ratio,
        energy_growth,
        energy_allowance: allowance,
        liquid_ratio,
        liquid_note,
        density_end,
        expect,
        mean_fraction,
        expected_fraction,
        final_fraction,
        final_vy,
        mean_vy,
        settled,
        settle_note,
        pass: failures.is_empty(),
        failures,
    })
}

/// Period of the longer wave of the sea, s.
fn wave_period(r: f64) -> f64 {
    let k = std::f64::consts::TAU / (8.0 * r);
    std::f64::consts::TAU / (G * k).sqrt()
}

/// Runs `soak stress`.
pub fn run(args: &Args) -> anyhow::Result<()> {
    let start = Instant::now();
    let resolution = args.resolution.unwrap_or(32);
    let max_steps = args.max_steps.unwrap_or(if args.quick { 150 } else { 300 });
    let mut cells = if args.quick { quick_matrix() } else { full_matrix() };
    if let Some(only) = &args.only {
        cells.retain(|c| c.name().contains(only.as_str()));
    }
    if cells.is_empty() {
        bail!("no cell matches");
    }
    let threads = args
        .threads
        .unwrap_or_else(|| std::thread::available_parallelism().map_or(1, |n| n.get()))
        .max(1);

    // Bake each mesh once per scale.
    let mut keys: Vec<(usize, u64)> = cells.iter().map(|c| (c.mesh, c.scale.to_bits())).collect();
    keys.sort_unstable();
    keys.dedup();
    let mut fixtures = Vec::with_capacity(keys.len());
    for &(mesh, scale) in &keys {
        fixtures.push(fixture(mesh, f64::from_bits(scale), resolution)?);
    }
    let fixture_of = |c: &Cell| {
        let k = keys
            .binary_search(&(c.mesh, c.scale.to_bits()))
            .expect("baked above");
        &fixtures[k]
    };

    let next = AtomicUsize::new(0);
    let results: Mutex<Vec<Option<anyhow::Result<Outcome>>>> =
        Mutex::new((0..cells.len()).map(|_| None).collect());
    std::thread::scope(|s| {
        for _ in 0..threads.min(cells.len()) {
            s.spawn(|| {
                loop {
                    let i = next.fetch_add(1, Ordering::Relaxed);
                    let Some(cell) = cells.get(i) else { break };
                    let r = run_cell(cell, fixture_of(cell), max_steps, args.buoyancy.mode());
                    results.lock().expect("no worker panicked")[i] = Some(r);
                }
            });
        }
    });
    let results = results.into_inner().expect("no worker panicked");
    let mut outcomes = Vec::with_capacity(results.len());
    for (cell, r) in cells.iter().zip(results) {
        match r {
            Some(Ok(o)) => outcomes.push(o),
            Some(Err(e)) => bail!("cell {}: {e:#}", cell.name()),
            None => bail!("cell {} did not run", cell.name()),
        }
    }
    let seconds = start.elapsed().as_secs_f64();

    if args.json {
        println!("{}", serde_json::to_string_pretty(&outcomes)?);
    } else if args.markdown {
        print_markdown(&outcomes, args.quick, resolution, max_steps, seconds);
    } else {
        print_text(&outcomes, resolution, max_steps, seconds);
    }

    let failing: Vec<&Outcome> = outcomes.iter().filter(|o| !o.pass).collect();
    if !failing.is_empty() {
        eprintln!("{} of {} cells failed:", failing.len(), outcomes.len());
        for o in &failing {
            eprintln!("  {}: {}", o.cell, o.failures.join("; "));
        }
        bail!("{} of {} stress cells failed", failing.len(), outcomes.len());
    }
    Ok(())
}

fn mark(ok: bool) -> &'static str {
    if ok { "ok" } else { "FAIL" }
}

fn print_text(outcomes: &[Outcome], resolution: u32, max_steps: usize, seconds: f64) {
    println!(
        "soak stress: {} cells, {resolution}² atlases, at most {max_steps} steps per cell, {seconds:.1} s",
        outcomes.len()
    );
    println!(
        "{:<44} {:>5} {:>6} {:>9} {:>3} {:>8} {:>9} {:>8} {:>6} {:>6}  verdict",
        "cell (mesh/scale/density/dt/water/effects)",
        "steps",
        "τ",
        "finite",
        "fw",
        "energy",
        "liquid",
        "expect",
        "frac",
        "want"
    );
    for o in outcomes {
        println!(
            "{:<44} {:>5} {:>6.1} {:>9} {:>3} {:>8.3} {:>9} {:>8} {:>6.3} {:>6.3}  {}",
            o.cell,
            o.steps,
            o.natural_times,
            mark(o.finite),
            o.firewall,
            o.energy_ratio,
            o.liquid_ratio.map_or("-".to_string(), |r| format!("{r:.2e}")),
            format!("{:?}", o.expect).to_lowercase(),
            if o.expect == Expect::Sinks {
                o.final_fraction
            } else {
                o.mean_fraction
            },
            o.expected_fraction,
            if o.pass {
                "pass".to_string()
            } else {
                format!("FAIL: {}", o.failures.join("; "))
            }
        );
    }
    let passed = outcomes.iter().filter(|o| o.pass).count();
    println!("{passed} passed, {} failed", outcomes.len() - passed);
}

fn print_markdown(outcomes: &[Outcome], quick: bool, resolution: u32, max_steps: usize, seconds: f64) {
    println!(
        "`soak stress{}`: {} cells, {resolution}² atlases, at most {max_steps} steps per cell, {seconds:.0} s.\n",
        if quick { " --quick" } else { "" },
        outcomes.len()
    );
    println!(
        "One row per mesh, water and effects; each row sums its cells over relative density, scale and time step. \
         *energy* is the worst growth of specific energy over its allowance (≤ 1 passes), *liquid* the worst liquid error \
         over its tolerance (≤ 1 passes), *floats / sinks / neutral* count the cells of each expected outcome that \
         behaved so.\n"
    );
    println!(
        "| mesh | water | effects | cells | finite | firewall | energy | liquid | floats | sinks | neutral | passed |"
    );
    println!("|---|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|");
    let mut groups: Vec<(&str, WaterKind, Level)> =
        outcomes.iter().map(|o| (o.mesh, o.water, o.effects)).collect();
    groups.dedup();
    for (mesh, water, level) in groups {
        let g: Vec<&Outcome> = outcomes
            .iter()
            .filter(|o| o.mesh == mesh && o.water == water && o.effects == level)
            .collect();
        let count = |e: Expect| {
            let all = g.iter().filter(|o| o.expect == e).count();
            let ok = g.iter().filter(|o| o.expect == e && o.settled).count();
            if all == 0 {
                "-".to_string()
            } else {
                format!("{ok}/{all}")
            }
        };
        let energy = g.iter().map(|o| o.energy_ratio).fold(f64::NEG_INFINITY, f64::max);
        let liquid = g
            .iter()
            .filter_map(|o| o.liquid_ratio)
            .fold(None, |a: Option<f64>, r| Some(a.map_or(r, |a| a.max(r))));
        println!(
            "| {mesh} | {} | {} | {} | {}/{} | {} | {energy:.2} | {} | {} | {} | {} | {}/{} |",
            water.label(),
            level.label(),
            g.len(),
            g.iter().filter(|o| o.finite).count(),
            g.len(),
            g.iter().map(|o| o.firewall).sum::<u64>(),
            liquid.map_or("-".to_string(), |r| format!("{r:.1e}")),
            count(Expect::Floats),
            count(Expect::Sinks),
            count(Expect::Neutral),
            g.iter().filter(|o| o.pass).count(),
            g.len(),
        );
    }
    let failing: Vec<&Outcome> = outcomes.iter().filter(|o| !o.pass).collect();
    println!();
    if failing.is_empty() {
        println!("Every cell passed.");
    } else {
        println!("Failing cells ({}):\n", failing.len());
        for o in failing {
            println!("- `{}`: {}", o.cell, o.failures.join("; "));
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Lowering a body wholly under water by `Δ` adds `V Δ` to the columns'
    /// potential `∫_V d dV`, whatever the surface over it: the measure the
    /// energy check uses must say so at any depth, where columns summed up
    /// to the surface (`Σ −A_y d²/2` as such) drift with the depth over the
    /// cliff's step.
    #[test]
    fn the_potential_of_a_submerged_body_grows_by_its_volume_times_the_depth() {
        let atlas = Atlas::bake(&builtin::cylinder(0.5, 1.0, 24), BakeOptions::square(32)).unwrap();
        let r = atlas.bounding_radius();
        let water = water(WaterKind::Cliff, r).unwrap();
        let turn = UnitQuaternion::from_euler_angles(0.05, 0.3, 0.09);
        let at = |depth: f64| {
            let pose = Isometry3::from_parts(Translation3::new(0.02, -depth, -0.01), turn);
            columns(&atlas, &pose, &water, 0.0)
        };
        let v = soak_hydro::volume_moments(&atlas).volume;
        let (_, u0) = at(2.0);
        for depth in [20.0, 2e3, 2e5] {
            let (_, u) = at(depth);
            // The atlas' own volume and the columns' agree to ~1e-8.
            let drift = (u - u0 - v * (depth - 2.0)).abs() / (v * (r + depth));
            assert!(
                drift < 1e-6,
                "at {depth} m the potential drifts by {drift:.2e} V (r + depth)"
            );
        }
    }
}

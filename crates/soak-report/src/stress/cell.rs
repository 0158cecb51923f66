//! One cell of the stability matrix: the body dropped into its fluid with
//! its effects (buoyancy, drag, flooding, wetting, by level), Rapier stepped
//! with the force generator, and the checks.

use std::sync::Arc;
use std::time::Instant;

use nalgebra::{Isometry3, Translation3, UnitQuaternion, Vector3};
use rapier3d::prelude::{PhysicsWorld, RigidBodyBuilder};
use soak_graph::{Flooding, FlowOptions, LiquidGraph, Node, Permeability, Pipe, WATER_VISCOSITY};
use soak_hydro::{AddedMass, BuoyancyMode, Drag, MassModel};
use soak_rapier::soak_seakeeping::{FloatingBody, RadiationModel};
use soak_rapier::{BodyDesc, Effects, ForceGenerator, SoakError, convert};
use soak_wet::{Diffusion, Environment, FieldResolution, Liquid, Material, Wetting};

use super::RadiationBakes;
use super::energy::{allowance, periods, specific_energy};
use super::error::StressError;
use super::fixture::{Fixture, G, RHO_W, equilibrium, water, wave_period};
use super::liquid_check::LiquidCheck;
use super::matrix::{Cell, Level};
use super::outcome::{Expect, Outcome};
use super::settling::{Motion, settle};

/// Run length of a cell: 30 natural times, at least 60 steps, at most
/// `max_steps`; in the sea also two periods of the longer wave, so that the
/// last half of the run holds one whole period, where those are at most
/// `30 max_steps` (else `10 max_steps`).
fn step_count(size: f64, dt: f64, max_steps: usize, sea_period: Option<f64>) -> usize {
    let tau = (size / G).sqrt();
    let cap = max_steps.max(60);
    let run = ((30.0 * tau / dt).ceil() as usize).clamp(60, cap);
    match sea_period {
        Some(period) => {
            // Two periods where 30 times the cap holds them (at 60 Hz, the
            // kilometre's waves, 60–75 s long); where even that would not
            // (at 240 Hz), the window is a part of a period whatever the
            // run, and ten times the cap is spent.
            let two = (2.0 * period / dt).ceil() as usize;
            run.max(if two <= 30 * cap { two } else { 10 * cap })
        }
        None => run,
    }
}

/// Runs one cell on its baked mesh `f`, for at most `max_steps` steps (a
/// sea cell up to 30 times that, for two wave periods), with buoyancy in
/// `mode`.
pub(crate) fn run_cell(
    cell: &Cell,
    f: &Fixture,
    max_steps: usize,
    mode: BuoyancyMode,
    bakes: &RadiationBakes,
) -> Result<Outcome, StressError> {
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

    // Ingress: two compartments of 15 % of the volume each, fore and aft,
    // joined by a pipe, behind a hull permeable all over. κ is set so that
    // the hull would take in its whole capacity in about 10 natural times
    // half submerged (Darcy: the inflow is about κ ρ g V_s / μ).
    // An open container's ingress is its cavity, filled over the rims
    // (thin walls: the whole enclosed volume).
    let capacity = if f.atlas.has_openings() {
        f.volume
    } else {
        0.3 * f.volume
    };
    if cell.level >= Level::Ingress && f.atlas.has_openings() {
        effects = effects.with_flooding(Flooding::open_container(&f.atlas, 0.0, FlowOptions::default())?);
    } else if cell.level >= Level::Ingress {
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
        effects = effects.with_flooding(flooding);
    }

    // Wetting: cotton, a checkerboard of saturated and dry texels (the
    // hardest input for an explicit kernel), conservative diffusion whose
    // coefficient asks for 10 times the explicit limit in one step.
    let env = Environment::default();
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
            return Err(StressError::NoNeighbours);
        }
        let coefficient = 10.0 * 3.0 * voxel * voxel / (dt * count as f64);
        wet.set_diffusion(Some(Diffusion::new(coefficient).with_resolution(field)))?;
        substeps_expected = 10;
        effects = effects.with_wetting(wet);
    }
    // Added mass: the equivalent ellipsoid of the closed shape.
    if cell.level >= Level::AddedMass {
        let added = AddedMass::of_atlas(&f.atlas).map_err(|source| SoakError::Hydro {
            name: cell.name(),
            source,
        })?;
        effects = effects.with_added_mass(added);
    }
    // An open container's walls weigh what a solid of the cell's density
    // filling its closed shape would.
    let mass_model = if f.atlas.has_openings() {
        MassModel::Shell {
            areal_density: cell.density * RHO_W * f.volume / f.atlas.wall_area(),
        }
    } else {
        MassModel::Solid {
            density: cell.density * RHO_W,
        }
    };
    // Radiation: the closed shape floating at rest from the cell's start
    // orientation, baked as a scene bakes it, once per mesh, scale and
    // density; it supersedes the added mass.
    let mut radiates = false;
    if cell.level >= Level::Radiation {
        let mass = mass_model
            .mass_properties(&f.atlas)
            .map_err(|source| SoakError::Hydro {
                name: cell.name(),
                source,
            })?;
        let settings = soak_rapier::radiation_settings(soak.water());
        let key = (cell.mesh, cell.scale.to_bits(), cell.density.to_bits());
        let model = bakes.get(key, || {
            let body = FloatingBody {
                mesh: &f.mesh,
                mass: mass.mass,
                center_of_mass: mass.center_of_mass,
                inertia: mass.inertia,
                rotation,
            };
            RadiationModel::bake(&body, &settings).ok().map(Arc::new)
        });
        if let Some(model) = model {
            radiates = model.resolved_by(dt);
            effects = effects.with_radiation(model);
        }
    }
    let centroid = {
        let v = soak_hydro::volume_moments(&f.atlas);
        v.origin + v.first / v.volume
    };
    let centred = mass_model
        .mass_properties(&f.atlas)
        .is_ok_and(|m| (m.center_of_mass - centroid).norm() <= 0.01 * size);
    let id = soak.register(
        &mut world.bodies,
        &world.colliders,
        handle,
        BodyDesc {
            name: cell.name(),
            atlas: f.atlas.clone().into(),
            mass_model: mass_model.clone(),
            effects,
        },
    )?;
    let wet_capacity: f64 =
        f.atlas.areas().iter().map(|&a| a as f64).sum::<f64>() * Material::cotton().saturation;

    let sea_period = cell.water.moves().then(|| wave_period(f.radius));
    let steps = step_count(size, dt, max_steps, sea_period);
    let sample_every = (steps / 32).max(1);
    let mut failures = Vec::new();
    let mut finite = true;

    let energy = |world: &PhysicsWorld, soak: &ForceGenerator| specific_energy(world, soak, handle, id, f);
    let e0 = energy(&world, &soak);
    let mut e_max = e0;

    // Where the water the body moves through is read: the centroid of
    // each of its atlas' tiles, weighted by the tile's area (object frame).
    let hull = hull_points(&f.atlas);
    let mut fraction_sum = 0.0;
    let mut centre_depth_sum = 0.0;
    let mut vy_sum = 0.0;
    let mut vy_water_sum = 0.0;
    let mut window = 0usize;
    let half = steps / 2;
    let mut liquid_check = LiquidCheck::default();
    let mut taken = 0;

    for k in 0..steps {
        soak.step(&mut world)?;
        taken = k + 1;
        let rb = &world.bodies[handle];
        let body = soak.body(id).expect("registered");
        if let Some(report) = body.wet_report() {
            liquid_check.plan(k, report, substeps_expected);
        }
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
            let pose = convert::pose(rb.position());
            let com = pose * body.mass_properties().center_of_mass;
            centre_depth_sum += soak.water().surface.depth(&com, soak.time()) / size;
            vy_sum += rb.linvel().y as f64;
            let water_vy = hull
                .iter()
                .map(|(p, w)| w * soak.water().surface.velocity(&(pose * p), soak.time()).y)
                .sum::<f64>();
            vy_water_sum += rb.linvel().y as f64 - water_vy;
            window += 1;
        }
        if k % sample_every == 0 || k + 1 == steps {
            e_max = e_max.max(energy(&world, &soak));
            liquid_check.inside(body.flooding(), capacity);
            if let Some(wet) = body.wetting() {
                liquid_check.surface(wet, f, wet_capacity);
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
    // the mean over the last half, the lesser of its own and of the one
    // relative to the water around it (`hull_points`: a run can be a fraction
    // of the waves' period at the largest scales, and the water the body
    // sinks through can rise with the wave meanwhile; deep under the
    // waves, where the water hardly moves, the two are one); over a static
    // surface the final one (a hull that fills only becomes heavier than
    // water late in its run).
    let (vy, vy_label) = if cell.water.moves() {
        (
            mean_vy.min(vy_water_sum / window / (G * size).sqrt()),
            "mean v_y over the last half (its own or through the water, the lesser)",
        )
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

    // Energy allowance, J/kg: see `allowance`.
    let waves = highest - lowest;
    let rho = cell.density;
    let periods = periods(cell.water, taken as f64 * dt, wave_period(f.radius));
    let allowance = allowance(size, waves, periods, rho);
    let energy_growth = e_max - e0;
    let energy_ratio = energy_growth / allowance;
    if energy_ratio.is_nan() || energy_ratio > 1.0 {
        failures.push(format!(
            "energy grew by {energy_growth:.3e} J/kg, allowance {allowance:.3e}"
        ));
    }

    let liquid_ratio = (cell.level >= Level::Ingress).then_some(liquid_check.worst);
    if let Some(r) = liquid_ratio
        && (r.is_nan() || r > 1.0)
    {
        failures.push(format!("liquid: {}", liquid_check.note));
    }

    // Settled or sunk as physics says.
    let (settled, settle_note, expected_fraction) = settle(&Motion {
        expect,
        water: cell.water,
        level: cell.level,
        size,
        tau,
        time: taken as f64 * dt,
        waves,
        reach,
        energy_gained: e_max - e0,
        density_end,
        mean_centre_depth,
        mean_fraction,
        final_fraction,
        vy,
        vy_label,
        dy: (rb.translation().y as f64 - y0) / size,
        centred,
    });
    if !settled {
        failures.push(format!("{expect:?}: {settle_note}"));
    }

    Ok(Outcome {
        cell: cell.name(),
        mesh: cell.mesh.label().to_string(),
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
        liquid_note: liquid_check.note,
        density_end,
        expect,
        mean_fraction,
        expected_fraction,
        final_fraction,
        final_vy,
        mean_vy,
        settled,
        settle_note,
        radiates,
        pass: failures.is_empty(),
        failures,
    })
}

/// The centroids of `atlas`' tiles (object frame, m), each with its share
/// of the area: where the water a body moves through is read, and how
/// much each reading counts. The water's velocity at the centre of mass
/// alone is not the water's around a body as long as a wave is (a rod a
/// quarter wavelength long meets a vertical velocity a tenth lower on
/// average than at its middle).
fn hull_points(atlas: &soak_bake::Atlas) -> Vec<(nalgebra::Point3<f64>, f64)> {
    let areas = atlas.areas();
    let total: f64 = areas.iter().map(|&a| f64::from(a)).sum();
    atlas
        .tiles()
        .iter()
        .filter_map(|t| {
            let (mut sum, mut area) = (nalgebra::Vector3::zeros(), 0.0);
            for i in t.range() {
                let a = f64::from(areas[i]);
                sum += a * atlas.position(i).coords;
                area += a;
            }
            (area > 0.0).then(|| (nalgebra::Point3::from(sum / area), area / total))
        })
        .collect()
}

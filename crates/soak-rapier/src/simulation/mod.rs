//! A scene running: a Rapier world, the force generator and the records.
//!
//! Split by concept: this file holds [`Simulation`], what it records and
//! each step's work; `build` builds one from a scene (the fluid, the bodies,
//! their wetting and liquid graphs), and `saved` saves a run and resumes it
//! ([`SavedSimulation`]).

mod build;
mod checkpoint;
mod csv;
mod saved;

use rapier3d::prelude::*;
use serde::{Deserialize, Serialize};

use crate::convert;
use crate::error::SoakError;
use crate::{ForceGenerator, SoakId};

pub use self::build::{radiation_settings, water_of};
pub use self::checkpoint::{
    CHECKPOINT_MAGIC, CHECKPOINT_VERSION, CheckpointError, decode_checkpoint, read_checkpoint,
    write_atomically, write_checkpoint,
};
pub use self::csv::{CSV_HEADER, SampleCsv};
pub use self::saved::SavedSimulation;

/// One body of a running scene.
#[derive(Clone, Debug)]
pub struct SimBody {
    /// Its name in the scene.
    pub name: String,
    /// The Rapier body.
    pub handle: RigidBodyHandle,
    /// The soak body, if it is not fixed.
    pub id: Option<SoakId>,
    /// Its atlas side, texels: the scene's, or the one `resolution =
    /// "auto"` chose for its tolerance (0 for a fixed body, which has none).
    pub resolution: u32,
}

/// One recorded sample of one body.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
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
    /// The largest slamming force of the run, N (bodies with slamming).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub slamming_peak: Option<f64>,
    /// Whether any state or force went non-finite during the run.
    pub non_finite: bool,
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

impl Simulation {
    /// A simulation of a world of your own: your Rapier world, the force
    /// generator driving it, and the bodies to report (and to draw: see
    /// `soak_view::run_world`), run for `duration` seconds (s). Nothing is
    /// scheduled in it: holes, splashes and weather belong to scene files
    /// (do them on the generator between steps). Samples are recorded at
    /// every step once [`Simulation::record`] is on.
    pub fn from_parts(
        world: PhysicsWorld,
        soak: ForceGenerator,
        bodies: Vec<SimBody>,
        duration: f64,
    ) -> Self {
        let n = bodies.len();
        Self {
            world,
            soak,
            bodies,
            duration,
            holes: Vec::new(),
            splashes: Vec::new(),
            weather: None,
            record_every: 1,
            recording: false,
            samples: Vec::new(),
            non_finite: vec![false; n],
            steps: 0,
        }
    }

    /// Records a sample of every body each `output.every` steps from now on.
    pub fn record(&mut self, on: bool) {
        self.recording = on;
        if on && self.samples.is_empty() {
            self.sample();
        }
    }

    /// Whether samples are being recorded ([`Simulation::record`]).
    pub fn is_recording(&self) -> bool {
        self.recording
    }

    /// The recorded samples.
    pub fn samples(&self) -> &[Sample] {
        &self.samples
    }

    /// Takes the samples recorded so far (recording goes on): a run that
    /// streams them out keeps none in memory.
    pub fn take_samples(&mut self) -> Vec<Sample> {
        std::mem::take(&mut self.samples)
    }

    /// Records from now on as [`Simulation::record`] does, after the
    /// `samples` a saved run had recorded (none taken now: a resumed run's
    /// samples are the uninterrupted run's).
    pub fn resume_recording(&mut self, samples: Vec<Sample>) {
        self.recording = true;
        self.samples = samples;
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

    /// Number of steps for the scene's duration (`u64::MAX` for a scene
    /// that runs forever).
    pub fn total_steps(&self) -> u64 {
        if self.duration.is_infinite() {
            u64::MAX
        } else {
            (self.duration / self.dt()).round() as u64
        }
    }

    /// One step.
    pub fn step(&mut self) -> Result<(), SoakError> {
        let t = self.soak.time();
        for (id, hole, punched) in self.holes.iter_mut() {
            if !*punched && t >= hole.at {
                let centre = if hole.world {
                    let handle = self
                        .soak
                        .body(*id)
                        .map(|b| b.handle())
                        .ok_or(SoakError::UnknownId(id.0))?;
                    let rb = self
                        .world
                        .bodies
                        .get(handle)
                        .ok_or_else(|| SoakError::MissingBody {
                            name: self
                                .soak
                                .body(*id)
                                .map(|b| b.name().to_string())
                                .unwrap_or_default(),
                        })?;
                    let p = crate::convert::pose(rb.position())
                        .inverse_transform_point(&nalgebra::Point3::from(hole.centre));
                    [p.x, p.y, p.z]
                } else {
                    hole.centre
                };
                match hole.kappa {
                    Some(kappa) => self.soak.punch(*id, centre, hole.radius, kappa)?,
                    None => self.soak.open_hole(*id, centre, hole.radius)?,
                };
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
            // Written beside its name and renamed into place: a run killed
            // while writing leaves no half image.
            let file = format!("{safe}_liquid_{:06}.png", self.steps);
            let (path, partial) = (dir.join(&file), dir.join(format!(".{file}.partial")));
            soak_wet::write_liquid_png(sb.atlas(), w.liquid(), w.material().saturation, &partial).map_err(
                |source| SoakError::Wet {
                    name: b.name.clone(),
                    source,
                },
            )?;
            std::fs::rename(&partial, &path).map_err(|source| SoakError::Io {
                path: path.clone(),
                source,
            })?;
            written.push(path);
        }
        Ok(written)
    }

    /// Liquid inside the body (its flooding), m³.
    fn liquid_of(&self, id: Option<SoakId>) -> Option<f64> {
        self.soak.flooding(id?).map(soak_graph::Flooding::inside)
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
                    slamming_peak: b
                        .id
                        .and_then(|id| self.soak.body(id))
                        .and_then(|body| body.slamming())
                        .map(|s| s.peak),
                    non_finite: self.non_finite[i] || non_finite,
                }
            })
            .collect()
    }
}

//! Ready-made scenes for the examples, tests and benches: a terrain slab
//! mesh with a map-like UV layout, and the beach of the thesis' Fig. 7.11 —
//! waves running up the sand, a rock and a wooden crate sharing one field,
//! the sand drying behind the retreating water.

use std::f64::consts::TAU;

use nalgebra::{Isometry3, Point2, Point3, Translation3, UnitQuaternion, Vector3};
use soak_bake::{Atlas, BakeOptions, Mesh, builtin};
use soak_hydro::{Gerstner, GerstnerWave, Surface, Water};

use crate::diffusion::{Diffusion, DiffusionMode};
use crate::environment::{Environment, EnvironmentTrack};
use crate::error::WetError;
use crate::grid::FieldResolution;
use crate::ledger::StepReport;
use crate::material::{Liquid, Material};
use crate::shared_field::{FieldMember, SharedField, SharedReport};
use crate::source::Rain;
use crate::wetting::Wetting;

/// A closed slab of terrain: the height field `y = height(x, z)` over
/// `[x0, x1] × [z0, z1]` on a grid of `cells` (along x, z), walled down to a
/// flat base at `y = base`.
///
/// The UV map reads like a map: the top occupies `u ∈ [0, 1]`,
/// `v ∈ [0, 0.6]` (`u` along x, `v` along z); the base and the four walls
/// are packed below it (`v > 0.6`) at a lower texel density. Returns the
/// mesh; the top's texels are those with an upward normal.
pub fn terrain_slab(
    x: [f64; 2],
    z: [f64; 2],
    cells: [usize; 2],
    base: f64,
    height: impl Fn(f64, f64) -> f64,
) -> Mesh {
    let (nx, nz) = (cells[0].max(1), cells[1].max(1));
    let xs: Vec<f64> = (0..=nx)
        .map(|i| x[0] + (x[1] - x[0]) * i as f64 / nx as f64)
        .collect();
    let zs: Vec<f64> = (0..=nz)
        .map(|j| z[0] + (z[1] - z[0]) * j as f64 / nz as f64)
        .collect();
    let heights: Vec<f64> = zs
        .iter()
        .flat_map(|&zz| xs.iter().map(move |&xx| (xx, zz)))
        .map(|(xx, zz)| height(xx, zz))
        .collect();
    let top_of = |i: usize, j: usize| heights[j * (nx + 1) + i];
    let hmax = heights.iter().copied().fold(base, f64::max);
    let mut positions = Vec::new();
    let mut uvs = Vec::new();
    let mut triangles = Vec::new();
    // A grid chart: vertices (i, j) → (position, uv), quads split in two
    // and wound so their normal points along `out`.
    let mut chart = |ni: usize,
                     nj: usize,
                     vertex: &dyn Fn(usize, usize) -> (Point3<f64>, Point2<f64>),
                     out: Vector3<f64>| {
        let first = positions.len() as u32;
        for j in 0..=nj {
            for i in 0..=ni {
                let (p, uv) = vertex(i, j);
                positions.push(p);
                uvs.push(uv);
            }
        }
        let id = |i: usize, j: usize| first + (j * (ni + 1) + i) as u32;
        for j in 0..nj {
            for i in 0..ni {
                for t in [
                    [id(i, j), id(i + 1, j), id(i + 1, j + 1)],
                    [id(i, j), id(i + 1, j + 1), id(i, j + 1)],
                ] {
                    let [a, b, c] = t.map(|k| positions[k as usize]);
                    let n = (b - a).cross(&(c - a));
                    triangles.push(if n.dot(&out) >= 0.0 { t } else { [t[0], t[2], t[1]] });
                }
            }
        }
    };
    let (sx, sz) = (x[1] - x[0], z[1] - z[0]);
    let wall = |v0: f64, y: f64| v0 + 0.08 * (y - base) / (hmax - base).max(1e-9);
    chart(
        nx,
        nz,
        &|i, j| {
            (
                Point3::new(xs[i], top_of(i, j), zs[j]),
                Point2::new((xs[i] - x[0]) / sx, 0.6 * (zs[j] - z[0]) / sz),
            )
        },
        Vector3::y(),
    );
    chart(
        nx,
        nz,
        &|i, j| {
            (
                Point3::new(xs[i], base, zs[j]),
                Point2::new(0.48 * (xs[i] - x[0]) / sx, 0.62 + 0.36 * (zs[j] - z[0]) / sz),
            )
        },
        -Vector3::y(),
    );
    // Walls: (along, which side, v0 of its strip, outward normal).
    for (k, v0) in [(0usize, 0.62), (1, 0.71), (2, 0.80), (3, 0.89)] {
        let along_x = k < 2;
        let n = if along_x { nx } else { nz };
        let vertex = |i: usize, j: usize| {
            let (xx, zz, top) = match k {
                0 => (xs[i], zs[0], top_of(i, 0)),
                1 => (xs[i], zs[nz], top_of(i, nz)),
                2 => (xs[0], zs[i], top_of(0, i)),
                _ => (xs[nx], zs[i], top_of(nx, i)),
            };
            let y = if j == 0 { base } else { top };
            let s = if along_x {
                (xx - x[0]) / sx
            } else {
                (zz - z[0]) / sz
            };
            (Point3::new(xx, y, zz), Point2::new(0.5 + 0.5 * s, wall(v0, y)))
        };
        let out = match k {
            0 => -Vector3::z(),
            1 => Vector3::z(),
            2 => -Vector3::x(),
            _ => Vector3::x(),
        };
        chart(n, 1, &vertex, out);
    }
    Mesh::new("terrain slab", positions, Some(uvs), triangles)
}

/// Height of the beach's sand, m: a 1:10 slope rising towards −x with
/// ripples and a low dune.
pub fn beach_height(x: f64, z: f64) -> f64 {
    -0.1 * x
        + 0.06 * (0.9 * z + 0.3 * x).sin()
        + 0.04 * (1.7 * z - 0.8 * x).sin()
        + 0.35 * (-((x + 7.0) / 1.5).powi(2)).exp()
}

/// The beach's sea: Gerstner swell running up the slope (towards −x) on a
/// slow tide: `y = gerstner(x, z, t) + A_tide cos(2π t / T_tide)`.
#[derive(Clone, Debug)]
pub struct TidalSea {
    /// The waves about the mean level.
    pub waves: Gerstner,
    /// Tide amplitude, m.
    pub tide_amplitude: f64,
    /// Tide period, s.
    pub tide_period: f64,
}

impl TidalSea {
    /// The tide's offset of the mean level at time `t` (s), m.
    pub fn tide(&self, t: f64) -> f64 {
        self.tide_amplitude * (TAU * t / self.tide_period).cos()
    }
}

impl Surface for TidalSea {
    fn height(&self, x: f64, z: f64, t: f64) -> f64 {
        self.waves.height(x, z, t) + self.tide(t)
    }

    fn height_bounds(&self, t: f64) -> Option<(f64, f64)> {
        self.waves
            .height_bounds(t)
            .map(|(lo, hi)| (lo + self.tide(t), hi + self.tide(t)))
    }

    fn probe(
        &self,
        p: &Point3<f64>,
        t: f64,
        with_velocity: bool,
        hint: &mut [f64; 2],
    ) -> (f64, Vector3<f64>) {
        let (d, v) = self.waves.probe(p, t, with_velocity, hint);
        (d + self.tide(t), v)
    }
}

/// Resolution and settings of a [`Beach`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BeachOptions {
    /// Atlas resolution of the sand (texels per side).
    pub terrain_resolution: u32,
    /// Atlas resolution of the rock and the crate.
    pub object_resolution: u32,
    /// Voxel edge of the shared field, m.
    pub voxel_size: f64,
    /// Diffusion scheme.
    pub mode: DiffusionMode,
    /// Time step, s.
    pub dt: f64,
}

impl Default for BeachOptions {
    /// The example's settings: 1024² sand, 256² objects, 0.1 m voxels, 0.1 s steps.
    fn default() -> Self {
        Self {
            terrain_resolution: 1024,
            object_resolution: 256,
            voxel_size: 0.1,
            mode: DiffusionMode::Conservative,
            dt: 0.1,
        }
    }
}

impl BeachOptions {
    /// A small beach for tests: 128² sand, 64² objects, 0.5 m voxels.
    pub fn small() -> Self {
        Self {
            terrain_resolution: 128,
            object_resolution: 64,
            voxel_size: 0.5,
            ..Self::default()
        }
    }
}

/// One body of a scene: its atlas, pose and liquid.
#[derive(Clone, Debug)]
pub struct SceneBody {
    /// A name for files and reports.
    pub name: &'static str,
    /// The mesh (object frame, m), for drawing.
    pub mesh: std::sync::Arc<Mesh>,
    /// The texel atlas.
    pub atlas: Atlas,
    /// Object → world, m.
    pub pose: Isometry3<f64>,
    /// The liquid texture.
    pub wetting: Wetting,
}

/// The beach of thesis Fig. 7.11: a 20 m × 12 m slab of sand sloping into
/// a tidal sea with swell, a rock in the surf and a wooden crate on the
/// upper beach, all three in one shared field (0.1 m voxels by default), so
/// the crate also takes water from the wet sand it stands on.
///
/// It runs in time-lapse: the liquid evaporates 1000× faster than water
/// (k_L = 1e7 1/(m·s)) and the sand's diffusion coefficient is
/// 2e-3 m²/s, so a minute shows what takes hours on a real beach. The
/// tide (±0.25 m, period 120 s) starts high and ebbs, leaving a band of wet
/// sand that dries behind the water. Only the upper face of the slab is
/// permeable (its walls and base sit under the sea level but stand for
/// buried sand).
#[derive(Clone, Debug)]
pub struct Beach {
    /// Sand, rock and crate.
    pub bodies: Vec<SceneBody>,
    /// The sea.
    pub water: std::sync::Arc<Water>,
    /// The same sea as data (swell and tide), for drawing.
    pub sea: TidalSea,
    /// The weather over time.
    pub weather: EnvironmentTrack,
    /// The field the three bodies share.
    pub field: SharedField,
    /// Simulation time, s.
    pub time: f64,
    /// Time step, s.
    pub dt: f64,
}

/// The time-lapse liquid of the beach: water evaporating 1000× faster.
pub fn time_lapse_water() -> Liquid {
    Liquid {
        evaporation_rate: 1e7,
        ..Liquid::water()
    }
}

impl Beach {
    /// Builds the scene.
    pub fn new(options: BeachOptions) -> Result<Self, WetError> {
        let bake = |mesh: &Mesh, n: u32| Atlas::bake(mesh, BakeOptions::square(n));
        let liquid = time_lapse_water();

        let terrain = terrain_slab([-10.0, 10.0], [-6.0, 6.0], [80, 48], -3.0, beach_height);
        let sand_atlas = bake(&terrain, options.terrain_resolution)?;
        let mut sand = Wetting::new(&sand_atlas, Material::sand(), liquid)?;
        let top: Vec<f32> = sand_atlas
            .area_vectors()
            .iter()
            .zip(sand_atlas.areas())
            .map(|(a, &area)| if a[1] > 0.5 * area { 1.0 } else { 0.0 })
            .collect();
        sand.set_permeability_map(&sand_atlas, Some(top))?;

        let rock_mesh = builtin::sphere(0.7, 48, 24).map_positions(|p| {
            let bump = 1.0 + 0.12 * (3.1 * p.x).sin() * (2.3 * p.z).cos() + 0.08 * (4.0 * p.y + 1.0).sin();
            Point3::new(p.x * bump * 1.2, p.y * bump * 0.7, p.z * bump)
        });
        let rock_atlas = bake(&rock_mesh, options.object_resolution)?;
        let rock = Wetting::new(
            &rock_atlas,
            Material {
                permeability: 1e-13,
                ..Material::rock()
            },
            liquid,
        )?;
        let (rx, rz) = (0.3, 2.5);
        let rock_pose = Isometry3::from_parts(
            Translation3::new(rx, beach_height(rx, rz) + 0.15, rz),
            UnitQuaternion::from_euler_angles(0.1, 0.7, -0.05),
        );

        let crate_mesh = builtin::cuboid(1.0, 1.0, 1.0);
        let crate_atlas = bake(&crate_mesh, options.object_resolution)?;
        let crate_ = Wetting::new(
            &crate_atlas,
            Material {
                permeability: 1e-12,
                ..Material::wood()
            },
            liquid,
        )?;
        let (cx, cz) = (-2.6, -2.0);
        let crate_pose = Isometry3::from_parts(
            Translation3::new(cx, beach_height(cx, cz) + 0.42, cz),
            UnitQuaternion::from_euler_angles(0.0, 0.35, 0.0),
        );

        let sea = TidalSea {
            waves: Gerstner::new(
                0.0,
                vec![
                    GerstnerWave {
                        amplitude: 0.14,
                        wavelength: 9.0,
                        direction_deg: 180.0,
                        steepness: 0.5,
                        phase: 0.0,
                    },
                    GerstnerWave {
                        amplitude: 0.08,
                        wavelength: 7.5,
                        direction_deg: 170.0,
                        steepness: 0.4,
                        phase: 1.0,
                    },
                ],
                9.81,
            )?,
            tide_amplitude: 0.25,
            tide_period: 120.0,
        };
        let warm = Environment {
            temperature: 298.15,
            relative_humidity: 0.55,
            wind_speed: 3.0,
            rain: Rain::none(),
        };
        let breeze = Environment {
            wind_speed: 6.0,
            relative_humidity: 0.45,
            ..warm
        };
        let weather = EnvironmentTrack::new(vec![(0.0, warm), (90.0, breeze)])?;

        let diffusion = Diffusion::new(2e-3)
            .with_mode(options.mode)
            .with_resolution(FieldResolution::VoxelSize(options.voxel_size));
        let field = SharedField::new(
            Point3::new(-10.0, -3.0, -6.0),
            Point3::new(10.0, 2.0, 6.0),
            diffusion,
        )?;
        Ok(Self {
            bodies: vec![
                SceneBody {
                    name: "sand",
                    mesh: std::sync::Arc::new(terrain),
                    atlas: sand_atlas,
                    pose: Isometry3::identity(),
                    wetting: sand,
                },
                SceneBody {
                    name: "rock",
                    mesh: std::sync::Arc::new(rock_mesh),
                    atlas: rock_atlas,
                    pose: rock_pose,
                    wetting: rock,
                },
                SceneBody {
                    name: "crate",
                    mesh: std::sync::Arc::new(crate_mesh),
                    atlas: crate_atlas,
                    pose: crate_pose,
                    wetting: crate_,
                },
            ],
            water: std::sync::Arc::new(Water::new(sea.clone())),
            sea,
            weather,
            field,
            time: 0.0,
            dt: options.dt,
        })
    }

    /// One step: absorption and evaporation on every body, then the shared
    /// diffusion. Returns each body's report and the field's.
    pub fn step(&mut self) -> Result<(Vec<StepReport>, SharedReport), WetError> {
        let env = self.weather.at(self.time);
        let mut reports = Vec::with_capacity(self.bodies.len());
        for b in &mut self.bodies {
            reports.push(
                b.wetting
                    .step(&b.atlas, &b.pose, &self.water, &env, self.time, self.dt)?,
            );
        }
        let mut members: Vec<FieldMember<'_>> = self
            .bodies
            .iter_mut()
            .map(|b| FieldMember {
                wetting: &mut b.wetting,
                atlas: &b.atlas,
                pose: &b.pose,
            })
            .collect();
        let field = self.field.diffuse(&mut members, self.dt)?;
        self.time += self.dt;
        Ok((reports, field))
    }
}

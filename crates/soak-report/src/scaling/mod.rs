//! The scaling bench: the step time of a Rapier world against the number
//! of floating bodies.
//!
//! Each case builds one world of N bodies on a horizontal grid 2 m apart,
//! half boxes (1.0 × 0.6 × 0.8 m) and half spheres (r = 0.5 m), solid at
//! 500 kg/m³, each placed at its floating draft (its centre at the water's
//! height above it), and steps it at 60 Hz: a few steps to settle, then
//! timed steps until a time budget is spent. The world is driven
//!
//! - by Rapier alone (colliders carrying the same masses, no force
//!   generator: the bodies fall freely, there is no water),
//! - with buoyancy from the force generator,
//! - with buoyancy and drag,
//!
//! on calm water and on the two-wave swell of `buoy_on_waves.toml`, on the
//! CPU (the tiled backend) and, with the `gpu` feature and on request, on
//! the GPU. Each mesh is baked once; every body gets its own copy of the
//! atlas, as [`soak_rapier::BodyDesc`] owns one, and the time and memory
//! that costs are part of each case's setup.
//!
//! ```no_run
//! use soak_report::scaling::{ScalingOptions, run, text_table};
//!
//! let report = run(&ScalingOptions::quick(), |_| {})?;
//! print!("{}", text_table(&report));
//! # Ok::<(), soak_report::scaling::ScalingError>(())
//! ```

mod error;
mod figure;
mod measure;
mod table;

use serde::Serialize;

pub use error::ScalingError;
pub use figure::{figure, write_figure};
pub use measure::{Fleet, run};
pub use table::{format_ms, markdown_table, phases_table, text_table};

/// Body counts of the full bench.
pub const FULL_SIZES: [usize; 5] = [1, 10, 100, 1_000, 10_000];
/// Body counts of the quick bench.
pub const QUICK_SIZES: [usize; 4] = [1, 10, 100, 1_000];

/// What drives the bodies.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Variant {
    /// Rapier alone: colliders with the bodies' masses, no generator.
    RapierAlone,
    /// The force generator with buoyancy.
    Buoyancy,
    /// The force generator with buoyancy and drag (`Drag { coefficient:
    /// 0.8, linear: 20.0 }`).
    BuoyancyDrag,
    /// The force generator with buoyancy and radiation (one model per
    /// mesh, baked as a scene bakes it: what a scene gives a body floating
    /// on a sea by default).
    BuoyancyRadiation,
}

impl Variant {
    /// A short label.
    pub fn label(self) -> &'static str {
        match self {
            Variant::RapierAlone => "Rapier alone",
            Variant::Buoyancy => "buoyancy",
            Variant::BuoyancyDrag => "buoyancy + drag",
            Variant::BuoyancyRadiation => "buoyancy + radiation",
        }
    }
}

/// The water of a case.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum WaterKind {
    /// The calm plane `y = 0`.
    Calm,
    /// The two-wave swell of `data/scenes/buoy_on_waves.toml`
    /// ([`crate::accuracy::swell`]).
    Swell,
    /// A JONSWAP sea of significant height 2 m and peak period 8 s
    /// (`γ` 3.3, spreading 10, seed 0) on its default tile (800 m, 128
    /// cells): [`jonswap`].
    Jonswap,
}

/// The bench's spectral sea: JONSWAP, `H_s` 2 m, `T_p` 8 s, on its
/// default tile.
///
/// # Errors
/// None in practice (the parameters are valid); a [`ScalingError`] if the
/// realisation refused them.
pub fn jonswap() -> Result<soak_hydro::Water, ScalingError> {
    Ok(soak_hydro::Water::spectral(
        &soak_hydro::SeaSpectrum::jonswap(2.0, 8.0),
        0,
    )?)
}

impl WaterKind {
    /// Every water, in table order.
    pub const ALL: [WaterKind; 3] = [WaterKind::Calm, WaterKind::Swell, WaterKind::Jonswap];

    /// The water of a label ([`WaterKind::label`]).
    pub fn from_label(label: &str) -> Option<Self> {
        Self::ALL.into_iter().find(|w| w.label() == label)
    }

    /// A short label.
    pub fn label(self) -> &'static str {
        match self {
            WaterKind::Calm => "calm",
            WaterKind::Swell => "swell",
            WaterKind::Jonswap => "jonswap",
        }
    }
}

/// Where the texel sums run.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Device {
    /// The CPU, tiled backend (the default).
    Cpu,
    /// The GPU, all bodies in one batch per step.
    Gpu,
}

/// One column of the table: a variant on a water and a device. Rapier
/// alone has no water.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize)]
pub struct Column {
    /// What drives the bodies.
    pub variant: Variant,
    /// The water (none for Rapier alone).
    pub water: Option<WaterKind>,
    /// Where the texel sums run.
    pub device: Device,
}

impl Column {
    /// Rapier alone.
    pub const RAPIER: Column = Column {
        variant: Variant::RapierAlone,
        water: None,
        device: Device::Cpu,
    };

    /// The generator's `variant` on `water` and `device`.
    pub fn soak(variant: Variant, water: WaterKind, device: Device) -> Self {
        Self {
            variant,
            water: Some(water),
            device,
        }
    }

    /// The columns measured, in table order: Rapier alone, then per
    /// water (calm, swell, JONSWAP) buoyancy, buoyancy with drag and
    /// buoyancy with radiation on the CPU, then (with `gpu`) the first two
    /// on the GPU for each water (the swell read there through each body's
    /// patch, sampled on the CPU; the JONSWAP sea read exactly, its tile
    /// evaluated on the device in each step's batch).
    pub fn all(gpu: bool) -> Vec<Column> {
        Self::on(gpu, &WaterKind::ALL)
    }

    /// The columns of [`Column::all`] whose water is one of `waters`
    /// (Rapier alone always).
    pub fn on(gpu: bool, waters: &[WaterKind]) -> Vec<Column> {
        let mut v = vec![Column::RAPIER];
        let devices: &[Device] = if gpu {
            &[Device::Cpu, Device::Gpu]
        } else {
            &[Device::Cpu]
        };
        for &device in devices {
            for water in WaterKind::ALL.into_iter().filter(|w| waters.contains(w)) {
                for variant in [Variant::Buoyancy, Variant::BuoyancyDrag] {
                    v.push(Column::soak(variant, water, device));
                }
                if device == Device::Cpu {
                    v.push(Column::soak(Variant::BuoyancyRadiation, water, device));
                }
            }
        }
        v
    }

    /// A label: "Rapier alone", "calm, buoyancy", "swell, buoyancy + drag, GPU".
    pub fn label(&self) -> String {
        match self.water {
            None => self.variant.label().to_string(),
            Some(w) => {
                let gpu = if self.device == Device::Gpu { ", GPU" } else { "" };
                format!("{}, {}{gpu}", w.label(), self.variant.label())
            }
        }
    }
}

/// One world to build and time.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize)]
pub struct Case {
    /// Number of bodies.
    pub bodies: usize,
    /// Variant, water and device.
    #[serde(flatten)]
    pub column: Column,
}

/// How the bench runs.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct ScalingOptions {
    /// Body counts, one row each.
    pub sizes: Vec<usize>,
    /// Atlas resolution, texels per side (128).
    pub resolution: u32,
    /// Segments and rings of the sphere mesh (64 × 32).
    pub sphere_segments: (usize, usize),
    /// Untimed steps before timing (the bodies start at their draft; these
    /// let them settle into the swell and warm the caches).
    pub settle_steps: usize,
    /// Fewest timed steps per case.
    pub min_steps: usize,
    /// Most timed steps per case.
    pub max_steps: usize,
    /// Timing stops once this many seconds were spent on timed steps and
    /// `min_steps` are done.
    pub budget_s: f64,
    /// Also run the GPU columns (needs the `gpu` feature and an adapter).
    pub gpu: bool,
    /// Largest body count run on the GPU (each body's atlas is uploaded).
    pub gpu_max_bodies: usize,
    /// The waters measured (all three by default; Rapier alone is
    /// always measured).
    pub waters: Vec<WaterKind>,
    /// Build every column's world of a size first, then step them in
    /// turn, one step each per round, so that a change of the machine's
    /// speed during the run (a shared machine's drifts by a third from
    /// one minute to the next) falls on every column alike: the ratios
    /// between columns are then of one moment. The budget is then the
    /// whole size's (`budget_s` × the columns), and the memory after
    /// setup counts every world of the size at once.
    #[serde(default)]
    pub interleave: bool,
    /// Sum the drag columns' drag over each atlas coarsened by this factor
    /// ([`soak_hydro::DragTexels::coarsened`], made once per mesh) rather
    /// than over its own texels. `None`: the own texels.
    #[serde(default)]
    pub drag_coarsening: Option<u32>,
    /// How the bodies read the seas (the swell and JONSWAP columns):
    /// `None` the generator's default (sampled over each body's footprint;
    /// the GPU's JONSWAP column exactly, on the device).
    #[serde(default)]
    pub sea_sampling: Option<soak_hydro::SeaSampling>,
}

impl ScalingOptions {
    /// The full bench: 1 to 10,000 bodies, at most 200 timed steps or about
    /// two seconds of them per case, at least three.
    pub fn full() -> Self {
        Self {
            sizes: FULL_SIZES.to_vec(),
            resolution: 128,
            sphere_segments: (64, 32),
            settle_steps: 10,
            min_steps: 3,
            max_steps: 200,
            budget_s: 2.0,
            gpu: false,
            gpu_max_bodies: 1_000,
            waters: WaterKind::ALL.to_vec(),
            interleave: false,
            drag_coarsening: None,
            sea_sampling: None,
        }
    }

    /// The quick bench: 1 to 1,000 bodies, a few steps each.
    pub fn quick() -> Self {
        Self {
            sizes: QUICK_SIZES.to_vec(),
            settle_steps: 3,
            min_steps: 2,
            max_steps: 10,
            budget_s: 0.2,
            ..Self::full()
        }
    }
}

/// What one case measured.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Measurement {
    /// The case.
    #[serde(flatten)]
    pub case: Case,
    /// Timed steps.
    pub steps: usize,
    /// Median step time, ms.
    pub median_ms: f64,
    /// Mean step time, ms.
    pub mean_ms: f64,
    /// Fastest step, ms.
    pub min_ms: f64,
    /// Slowest step, ms.
    pub max_ms: f64,
    /// Building the world and registering its bodies (copying each
    /// body's atlas, its tiles and mass properties), ms; baking excluded.
    pub setup_ms: f64,
    /// Resident memory of the process after setup, MB (Linux only).
    pub rss_mb: Option<f64>,
    /// What setup added to the resident memory, MB (Linux only; memory the
    /// allocator kept from an earlier case is reused and not counted).
    pub rss_growth_mb: Option<f64>,
    /// Smallest and largest submerged fraction of a body's volume at the
    /// last step (none for Rapier alone, which has no water).
    pub submerged: Option<(f64, f64)>,
    /// Quantities the generator's firewall rejected (a GPU step that fell
    /// back to the CPU counts here too).
    pub firewall: u64,
    /// The generator's step phase by phase, the mean over the timed steps
    /// (none for Rapier alone).
    pub phases: Option<PhaseMeans>,
}

/// The mean wall time of each phase of the generator's step over a case's
/// timed steps, ms ([`soak_rapier::soak_driver::StepPhases`]); the rest of
/// a step is Rapier's.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize)]
pub struct PhaseMeans {
    /// Reading each body from Rapier and predicting its pose (one body at
    /// a time), ms.
    pub predict_ms: f64,
    /// The water readied and each body's options and sampled sea
    /// (parallel), ms.
    pub prepare_ms: f64,
    /// The bodies' buoyancy and drag (parallel), ms.
    pub evaluate_ms: f64,
    /// What each body hands Rapier: the implicit heave, radiation, the
    /// firewall's checks (parallel), ms.
    pub hand_ms: f64,
    /// The wrenches handed to Rapier one body at a time and the step's
    /// lists emptied, ms.
    pub engine_ms: f64,
}

/// A run of the bench.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct ScalingReport {
    /// How it ran.
    pub options: ScalingOptions,
    /// Columns measured, in table order.
    pub columns: Vec<Column>,
    /// Every case, row by row.
    pub measurements: Vec<Measurement>,
    /// Texels of the box's and the sphere's atlas.
    pub texels: (usize, usize),
    /// Bytes of the box's atlas and the sphere's (their arrays), which the
    /// bodies of each mesh share.
    pub atlas_bytes: (usize, usize),
    /// Baking both meshes, ms (once per run).
    pub bake_ms: f64,
    /// Threads of rayon's pool.
    pub threads: usize,
    /// The GPU adapter, when the GPU columns ran.
    pub gpu: Option<String>,
    /// Why something was skipped, and what the times mean.
    pub notes: Vec<String>,
    /// Wall-clock time of the run, s.
    pub seconds: f64,
}

impl ScalingReport {
    /// The measurement of `column` at `bodies`, if it ran.
    pub fn get(&self, bodies: usize, column: &Column) -> Option<&Measurement> {
        self.measurements
            .iter()
            .find(|m| m.case.bodies == bodies && m.case.column == *column)
    }
}

//! The GPU path (feature `gpu`) agrees with the CPU: one body of assertions
//! runs on both backends (`trait Backend`), then their results are compared
//! within stated tolerances. Also: batching, deformation on the device,
//! split atlases, and the typed errors.
//!
//! One file on purpose: the parity suite shares one harness (the `Backend`
//! trait and its two implementations) that every test runs through.
//!
//! Needs a wgpu adapter: Mesa's lavapipe (`WGPU_BACKEND=vulkan`) or llvmpipe
//! (`WGPU_BACKEND=gl`) do. Without one the tests print a notice and pass,
//! except under `CI=true`, where they fail.
#![cfg(feature = "gpu")]

use std::collections::HashMap;
use std::sync::OnceLock;

use nalgebra::{Isometry3, Point3, Quaternion, Translation3, UnitQuaternion, Vector3};
use soak_bake::{Atlas, BakeOptions, Mesh, builtin};
use soak_hydro::gpu::{GpuAtlasId, GpuBody, GpuError, GpuHydro, GpuHydroError, GpuOptions, adapter_label};
use soak_hydro::{
    BodyState, BuoyancyMode, Drag, Gerstner, GerstnerWave, HeightField, HydroForces, HydroOptions, MassModel,
    MassProperties, Plane, SeaSampling, SeaSpectrum, SeaVelocity, SpectralSea, SpectralSurface, Surface,
    SurfacePatch, Unbounded, Water, evaluate,
};

const MESHES: [&str; 7] = [
    "builtin:sphere",
    "builtin:box:4x1x1",
    "builtin:cylinder",
    "builtin:capsule",
    "builtin:torus",
    "builtin:boat",
    "builtin:dumbbell",
];

/// Relative tolerance of the parity checks (and, times the body's diameter,
/// of centres and lever arms).
const TOL: f64 = 1e-4;

// ---------------------------------------------------------------- harness

type Device = (wgpu::Device, wgpu::Queue, wgpu::AdapterInfo);

/// Options that read a sea exactly: the GPU inverts the Gerstner map at
/// every texel, the CPU too (the sampled read is held to the exact one in
/// `sea_sampling.rs`). The parity tests of the sampled read use the default
/// options, under which both sides sample the sea once per evaluation and
/// read that patch.
fn exact_options() -> HydroOptions {
    HydroOptions {
        sea: SeaSampling::Exact,
        ..HydroOptions::default()
    }
}

/// A headless device of its own for each test (on wgpu's GL backend a
/// device serialises all work behind one context lock, which wgpu gives up
/// on after 6 s: tests running in parallel on one GL device could trip it).
/// `None` (with a notice) when there is no adapter, a failure under `CI=true`.
fn device() -> Option<Device> {
    soak_hydro::gpu::test_device()
}

fn hydro(d: &Device) -> GpuHydro {
    GpuHydro::new(&d.0, &d.1).expect("kernels compile")
}

struct Baked {
    name: &'static str,
    mesh: Mesh,
    atlas: Atlas,
    mass: MassProperties,
    /// Enclosed volume, m³.
    volume: f64,
    /// Bounding diameter, m.
    diameter: f64,
    /// Surface area and the largest texel's, m².
    area: f64,
    max_texel_area: f64,
}

impl Baked {
    fn new(name: &'static str, mesh: Mesh, atlas: Atlas, mass: MassProperties) -> Self {
        let max_texel_area = atlas
            .area_vectors()
            .iter()
            .map(|a| Vector3::new(a[0], a[1], a[2]).norm() as f64)
            .fold(0.0, f64::max);
        Self {
            name,
            mesh,
            volume: atlas.volume(),
            diameter: 2.0 * atlas.bounding_radius(),
            area: atlas.area(),
            max_texel_area,
            mass,
            atlas,
        }
    }
}

fn baked(n: u32) -> &'static [Baked] {
    static SETS: OnceLock<std::sync::Mutex<HashMap<u32, &'static [Baked]>>> = OnceLock::new();
    let mut sets = SETS.get_or_init(Default::default).lock().unwrap();
    sets.entry(n).or_insert_with(|| {
        let v: Vec<Baked> = MESHES
            .iter()
            .map(|&name| {
                let mesh = builtin::parse(name).unwrap();
                let atlas = Atlas::bake(&mesh, BakeOptions::square(n)).unwrap();
                let mass = MassModel::Solid { density: 600.0 }
                    .mass_properties(&atlas)
                    .unwrap();
                Baked::new(name, mesh, atlas, mass)
            })
            .collect();
        Box::leak(v.into_boxed_slice())
    })
}

/// A tiny LCG: seeded, reproducible, no dependency.
struct Lcg(u64);

impl Lcg {
    fn next(&mut self) -> f64 {
        self.0 = self
            .0
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (self.0 >> 11) as f64 / (1u64 << 53) as f64
    }
    fn range(&mut self, lo: f64, hi: f64) -> f64 {
        lo + (hi - lo) * self.next()
    }
    fn vector(&mut self, scale: f64) -> Vector3<f64> {
        Vector3::new(
            self.range(-scale, scale),
            self.range(-scale, scale),
            self.range(-scale, scale),
        )
    }
    /// A uniformly random rotation (Shoemake).
    fn rotation(&mut self) -> UnitQuaternion<f64> {
        let (u1, u2, u3) = (self.next(), self.next(), self.next());
        let tau = std::f64::consts::TAU;
        let (a, b) = ((1.0 - u1).sqrt(), u1.sqrt());
        UnitQuaternion::from_quaternion(Quaternion::new(
            b * (tau * u3).cos(),
            a * (tau * u2).sin(),
            a * (tau * u2).cos(),
            b * (tau * u3).sin(),
        ))
    }
    /// A pose putting the atlas origin at height `level + [−0.8, 0.8] R`
    /// anywhere within `spread` m of the world origin horizontally, with
    /// velocities of up to `speed` m/s (and rad/s).
    fn state(&mut self, b: &Baked, level: f64, spread: f64, speed: f64) -> BodyState {
        let rotation = self.rotation();
        let r = b.diameter / 2.0;
        let ow = Vector3::new(
            self.range(-spread, spread),
            level + self.range(-0.8, 0.8) * r,
            self.range(-spread, spread),
        );
        let t = ow - rotation * b.atlas.origin().coords;
        BodyState {
            pose: Isometry3::from_parts(Translation3::from(t), rotation),
            linear_velocity: self.vector(speed),
            angular_velocity: self.vector(speed),
        }
    }
}

fn plane() -> Water {
    Water::calm(0.37)
}

fn sea() -> Water {
    let waves = vec![
        GerstnerWave {
            amplitude: 0.15,
            wavelength: 7.0,
            direction_deg: 10.0,
            steepness: 0.5,
            phase: 0.0,
        },
        GerstnerWave {
            amplitude: 0.1,
            wavelength: 4.3,
            direction_deg: 75.0,
            steepness: 0.5,
            phase: 1.0,
        },
        GerstnerWave {
            amplitude: 0.08,
            wavelength: 2.9,
            direction_deg: -40.0,
            steepness: 0.5,
            phase: 2.5,
        },
    ];
    Water::new(Gerstner::new(0.1, waves, 9.80665).unwrap())
}

/// The two-wave swell of `data/scenes/buoy_on_waves.toml` (as in
/// `sea_sampling.rs`).
fn swell() -> Water {
    Water::new(Gerstner::new(0.0, swell_waves(), 9.80665).unwrap())
}

fn swell_waves() -> Vec<GerstnerWave> {
    GerstnerWave::SWELL.to_vec()
}

/// A short JONSWAP sea (significant height 0.5 m, peak period 3 s: its
/// peak wave 14 m long) on its default tile of 64 cells.
fn spectral() -> Water {
    let spectrum = SeaSpectrum::jonswap(0.5, 3.0);
    let sea = SpectralSea::realize(&spectrum, 0.1, spectrum.default_tile(9.80665), 64, 5, 9.80665).unwrap();
    Water::new(SpectralSurface::new(sea))
}

fn height_field() -> Water {
    let (nx, nz) = (40, 30);
    let heights = (0..nx * nz)
        .map(|i| {
            let (x, z) = ((i % nx) as f64, (i / nx) as f64);
            0.2 + 0.1 * (0.4 * x).sin() + 0.07 * (0.3 * z + 0.5 * x).cos()
        })
        .collect();
    let mut h = HeightField::new([-10.0, -8.0], [0.5, 0.55], nx, nz, heights).unwrap();
    h.current = [0.3, 0.0, -0.2];
    Water::new(h)
}

fn tilted() -> Water {
    let p = Plane::tilted(Point3::new(0.0, 0.2, 0.0), Vector3::new(0.05, 1.0, -0.08))
        .unwrap()
        .with_current(Vector3::new(0.5, 0.0, 0.2));
    Water::new(p)
}

fn air() -> Water {
    Water {
        surface: Box::new(Unbounded {
            current: [2.0, 0.0, 1.0],
        }),
        ..Water::air()
    }
}

// ---------------------------------------------------------------- backends

/// What the assertions need from an implementation.
trait Backend {
    fn name(&self) -> String;
    /// Forces on bodies that all use `b`'s atlas.
    fn forces(
        &mut self,
        b: &'static Baked,
        bodies: &[(&Water, BodyState, HydroOptions)],
        t: f64,
    ) -> Vec<HydroForces>;
    fn mass(&mut self, b: &'static Baked, model: &MassModel) -> MassProperties;
}

struct Cpu;

impl Backend for Cpu {
    fn name(&self) -> String {
        "CPU".into()
    }
    fn forces(
        &mut self,
        b: &'static Baked,
        bodies: &[(&Water, BodyState, HydroOptions)],
        t: f64,
    ) -> Vec<HydroForces> {
        bodies
            .iter()
            .map(|(w, s, o)| evaluate(&b.atlas, w, s, &b.mass, t, o).unwrap())
            .collect()
    }
    fn mass(&mut self, b: &'static Baked, model: &MassModel) -> MassProperties {
        model.mass_properties(&b.atlas).unwrap()
    }
}

struct Gpu {
    hydro: GpuHydro,
    label: String,
    ids: HashMap<usize, GpuAtlasId>,
}

impl Gpu {
    fn new(d: &Device) -> Self {
        Self {
            hydro: hydro(d),
            label: adapter_label(&d.2),
            ids: HashMap::new(),
        }
    }
    fn id(&mut self, b: &'static Baked) -> GpuAtlasId {
        let key = b as *const Baked as usize;
        if let Some(id) = self.ids.get(&key) {
            return *id;
        }
        let id = self.hydro.upload(&b.atlas).unwrap();
        self.ids.insert(key, id);
        id
    }
}

impl Backend for Gpu {
    fn name(&self) -> String {
        format!("GPU on {}", self.label)
    }
    /// One batch: one submission, one readback.
    fn forces(
        &mut self,
        b: &'static Baked,
        bodies: &[(&Water, BodyState, HydroOptions)],
        t: f64,
    ) -> Vec<HydroForces> {
        let id = self.id(b);
        let batch: Vec<GpuBody> = bodies
            .iter()
            .map(|(w, s, o)| GpuBody::from((id, *w, *s, b.mass, *o)))
            .collect();
        self.hydro.evaluate_batch(&batch, t).unwrap()
    }
    fn mass(&mut self, b: &'static Baked, model: &MassModel) -> MassProperties {
        let id = self.id(b);
        self.hydro.mass_properties(id, model).unwrap()
    }
}

// ---------------------------------------------------------------- the test body

/// What every backend must satisfy on its own, whatever the other says.
fn check_forces(
    backend: &dyn Backend,
    b: &Baked,
    water: &Water,
    state: &BodyState,
    mode: BuoyancyMode,
    f: &HydroForces,
) {
    let ctx = || format!("{} {} at {:?}", backend.name(), b.name, state.pose);
    let finite = |w: &soak_hydro::Wrench| w.is_finite();
    assert!(
        f.submerged_volume.is_finite()
            && f.center_of_buoyancy.iter().all(|c| c.is_finite())
            && finite(&f.buoyancy)
            && finite(&f.drag)
            && finite(&f.drag_explicit),
        "non-finite result: {}",
        ctx()
    );
    assert!(
        f.submerged_volume >= 0.0 && f.submerged_volume <= b.volume * 1.001,
        "submerged volume {} outside [0, {}]: {}",
        f.submerged_volume,
        b.volume,
        ctx()
    );
    assert!(f.submerged_texels <= b.atlas.len(), "{}", ctx());
    assert!(f.wetted_area <= b.area * 1.0001, "{}", ctx());
    let rg = water.density * water.gravity;
    if mode == BuoyancyMode::Archimedes {
        assert!((f.buoyancy.force.y - rg * f.submerged_volume).abs() <= 1e-9 * rg * b.volume);
    }
    if f.submerged_volume > 0.01 * b.volume {
        let ow = state.pose * b.atlas.origin();
        assert!(
            (f.center_of_buoyancy - ow).norm() <= 0.5 * b.diameter * 1.001,
            "centre of buoyancy outside the body's sphere: {}",
            ctx()
        );
    }
}

/// Largest errors seen, as fractions of their tolerance scales.
#[derive(Debug, Default)]
struct Errors {
    volume: f64,
    force: f64,
    torque: f64,
    centre: f64,
    drag_force: f64,
    drag_torque: f64,
    wetted_texels: usize,
}

impl Errors {
    fn merge(&mut self, o: &Errors) {
        self.volume = self.volume.max(o.volume);
        self.force = self.force.max(o.force);
        self.torque = self.torque.max(o.torque);
        self.centre = self.centre.max(o.centre);
        self.drag_force = self.drag_force.max(o.drag_force);
        self.drag_torque = self.drag_torque.max(o.drag_torque);
        self.wetted_texels = self.wetted_texels.max(o.wetted_texels);
    }
    fn report(&self, what: &str) {
        eprintln!("{what}: max errors {self:?}");
        self.assert_within(what);
    }
    fn assert_within(&self, what: &str) {
        for (name, v) in [
            ("volume", self.volume),
            ("force", self.force),
            ("torque", self.torque),
            ("centre", self.centre),
            ("drag force", self.drag_force),
            ("drag torque", self.drag_torque),
        ] {
            assert!(v <= TOL, "{what}: {name} error {v:.3e} above {TOL:e}");
        }
        // A texel whose depth is within f32 rounding of zero may be wet on
        // one side and dry on the other: it moves the volume by ~1e-7 of a
        // texel column, and the wetted area and count by one texel.
        assert!(
            self.wetted_texels <= 3,
            "{what}: wet texel counts differ by {}",
            self.wetted_texels
        );
    }
}

/// GPU against CPU for one result. Scales: volume relative to
/// max(V, 1% of the body's volume); forces relative to max(|F|, ρ g 1% V);
/// torques relative to that force times the diameter; centres relative to
/// the diameter (when at least 1% is submerged); drag relative to the
/// larger of its force and torque/diameter, floored at 1% of ρ|v|²·area.
fn compare(b: &Baked, water: &Water, state: &BodyState, cpu: &HydroForces, gpu: &HydroForces) -> Errors {
    let rg = water.density * water.gravity;
    let v_scale = cpu.submerged_volume.max(0.01 * b.volume);
    let f_scale = cpu.buoyancy.force.norm().max(rg * 0.01 * b.volume);
    let d = b.diameter;
    let mut e = Errors {
        volume: (gpu.submerged_volume - cpu.submerged_volume).abs() / v_scale,
        wetted_texels: gpu.submerged_texels.abs_diff(cpu.submerged_texels),
        ..Errors::default()
    };
    let (c, g) = (&cpu.buoyancy, &gpu.buoyancy);
    e.force = (g.force - c.force).norm() / f_scale.max(c.force.norm());
    e.torque = (g.torque - c.torque).norm() / (f_scale.max(c.force.norm()) * d);
    if cpu.submerged_volume > 0.01 * b.volume {
        e.centre = (gpu.center_of_buoyancy - cpu.center_of_buoyancy).norm() / d;
    }
    assert!(
        (gpu.wetted_area - cpu.wetted_area).abs()
            <= TOL * cpu.wetted_area + e.wetted_texels as f64 * b.max_texel_area + 1e-12,
        "wetted area {} vs {}",
        gpu.wetted_area,
        cpu.wetted_area
    );
    let speed = state.linear_velocity.norm() + state.angular_velocity.norm() * d / 2.0;
    let drag_floor = 0.01 * water.density * speed * speed * cpu.wetted_area;
    for (c, g) in [(&cpu.drag, &gpu.drag), (&cpu.drag_explicit, &gpu.drag_explicit)] {
        let scale = c.force.norm().max(c.torque.norm() / d).max(drag_floor);
        if scale > 0.0 {
            e.drag_force = e.drag_force.max((g.force - c.force).norm() / scale);
            e.drag_torque = e.drag_torque.max((g.torque - c.torque).norm() / (scale * d));
        }
    }
    e
}

/// The shared test body: `poses` random states of every mesh in `water`,
/// through both backends, each result checked on its own, then compared;
/// a sea read as `sea` says.
#[allow(clippy::too_many_arguments)]
fn parity(
    cpu: &mut dyn Backend,
    gpu: &mut dyn Backend,
    set: &'static [Baked],
    water: &Water,
    poses: usize,
    drag: Option<Drag>,
    seed: u64,
    sea: SeaSampling,
) -> Errors {
    let mut rng = Lcg(seed);
    let mut all = Errors::default();
    for b in set {
        let level = water.surface.height(0.0, 0.0, 0.0).min(1e3);
        let t = rng.range(0.0, 10.0);
        let bodies: Vec<(&Water, BodyState, HydroOptions)> = (0..poses)
            .map(|k| {
                let state = rng.state(b, level, 20.0, if drag.is_some() { 2.0 } else { 0.0 });
                let buoyancy = if k % 2 == 0 {
                    BuoyancyMode::Archimedes
                } else {
                    BuoyancyMode::Pressure
                };
                let options = HydroOptions {
                    buoyancy,
                    drag,
                    dt: 1.0 / 60.0,
                    sea,
                    sea_velocity: SeaVelocity::PerTexel,
                    sea_band: soak_hydro::SeaBand::Full,
                    added_mass: None,
                };
                (water, state, options)
            })
            .collect();
        let expected = cpu.forces(b, &bodies, t);
        let got = gpu.forces(b, &bodies, t);
        assert_eq!(got.len(), bodies.len());
        let mut errors = Errors::default();
        for ((body, c), g) in bodies.iter().zip(&expected).zip(&got) {
            check_forces(cpu, b, water, &body.1, body.2.buoyancy, c);
            check_forces(gpu, b, water, &body.1, body.2.buoyancy, g);
            errors.merge(&compare(b, water, &body.1, c, g));
        }
        eprintln!("  {} ({} texels): {errors:?}", b.name, b.atlas.len());
        all.merge(&errors);
    }
    all
}

fn run_parity(n: u32, water: fn() -> Water, poses: usize, drag: Option<Drag>, seed: u64, what: &str) {
    run_parity_read(n, water, poses, drag, seed, what, SeaSampling::Exact);
}

/// [`run_parity`] with a sea read as `sea` says, on both sides.
fn run_parity_read(
    n: u32,
    water: fn() -> Water,
    poses: usize,
    drag: Option<Drag>,
    seed: u64,
    what: &str,
    sea: SeaSampling,
) {
    let Some(d) = device() else { return };
    let d = &d;
    let set = baked(n);
    let mut gpu = Gpu::new(d);
    eprintln!("{what} at {n}², {poses} poses per mesh, {}", gpu.name());
    let errors = parity(&mut Cpu, &mut gpu, set, &water(), poses, drag, seed, sea);
    errors.report(what);
}

// ---------------------------------------------------------------- parity tests

#[test]
fn plane_parity_256() {
    run_parity(256, plane, 50, None, 1, "plane");
}

#[test]
fn gerstner_parity_256() {
    run_parity(256, sea, 50, None, 2, "Gerstner sea");
}

#[test]
fn plane_parity_1024() {
    run_parity(1024, plane, 50, None, 3, "plane");
}

/// The CPU reference costs ~0.3 s per Gerstner evaluation at 1024² in the
/// test profile: 6 poses per mesh there (50 at 256²).
#[test]
fn gerstner_parity_1024() {
    run_parity(1024, sea, 6, None, 4, "Gerstner sea");
}

const DRAG: Drag = Drag {
    coefficient: 1.0,
    linear: 0.5,
};

#[test]
fn drag_parity_plane_with_current() {
    run_parity(256, tilted, 50, Some(DRAG), 5, "drag, tilted plane with current");
}

#[test]
fn drag_parity_gerstner() {
    run_parity(256, sea, 20, Some(DRAG), 6, "drag, Gerstner orbital velocity");
}

/// The sampled read (16 nodes per shortest wave, as the default read
/// samples a body large against the waves): the sea sampled once per
/// evaluation on both sides, the GPU reading the patch's polynomials in
/// f32.
#[test]
fn sampled_swell_parity_256() {
    let sampled = SeaSampling::PerWavelength(SeaSampling::DEFAULT_PER_WAVELENGTH);
    run_parity_read(256, swell, 30, None, 11, "swell, sampled", sampled);
    run_parity_read(256, sea, 20, None, 12, "Gerstner sea, sampled", sampled);
}

#[test]
fn sampled_swell_drag_parity() {
    let sampled = SeaSampling::PerWavelength(SeaSampling::DEFAULT_PER_WAVELENGTH);
    run_parity_read(256, swell, 20, Some(DRAG), 13, "drag, swell, sampled", sampled);
}

/// A sea read as one plane over each body (`SeaSampling::Plane`): the
/// plane fitted on the CPU for both, the device summing under it as under
/// any tilted plane with a current.
#[test]
fn plane_read_parity() {
    run_parity_read(
        256,
        spectral,
        20,
        Some(DRAG),
        17,
        "drag, JONSWAP sea read as a plane",
        SeaSampling::Plane,
    );
    run_parity_read(
        256,
        swell,
        20,
        None,
        18,
        "swell read as a plane",
        SeaSampling::Plane,
    );
}

/// A spectral sea, read through each body's patch sampled on the CPU as
/// the Gerstner sea is, agrees alike.
#[test]
fn sampled_spectral_parity_256() {
    let sampled = SeaSampling::PerWavelength(SeaSampling::DEFAULT_PER_WAVELENGTH);
    run_parity_read(256, spectral, 20, None, 15, "JONSWAP sea, sampled", sampled);
    run_parity_read(
        256,
        spectral,
        10,
        Some(DRAG),
        16,
        "drag, JONSWAP sea, sampled",
        sampled,
    );
}

/// A spectral sea read exactly: its tile evaluated on the device in the
/// batch's own submission (the layers of its modes, their inverse FFT, its
/// fields laid out per node) and its choppy map inverted at every texel,
/// against the CPU's exact read (its tile's fields by rustfft in f64).
#[test]
fn exact_spectral_parity_256() {
    run_parity(
        256,
        spectral,
        12,
        None,
        17,
        "JONSWAP sea, exact, tile on the device",
    );
    run_parity(
        256,
        spectral,
        8,
        Some(DRAG),
        18,
        "drag, JONSWAP sea, exact, tile on the device",
    );
}

/// Ten hours into a run the sea on the device keeps its phases: each mode is
/// turned to the time on the CPU, in f64.
#[test]
fn exact_spectral_parity_ten_hours_in() {
    let Some(d) = device() else { return };
    let mut gpu = Gpu::new(&d);
    let water = spectral();
    let mut rng = Lcg(19);
    let mut errors = Errors::default();
    for b in &baked(256)[..3] {
        let bodies: Vec<_> = (0..4)
            .map(|_| (&water, rng.state(b, 0.1, 20.0, 1.0), exact_options()))
            .collect();
        let t = 36_000.0 + rng.range(0.0, 10.0);
        let cpu = Cpu.forces(b, &bodies, t);
        let got = gpu.forces(b, &bodies, t);
        for ((body, c), g) in bodies.iter().zip(&cpu).zip(&got) {
            errors.merge(&compare(b, &water, &body.1, c, g));
        }
    }
    errors.report("JONSWAP sea, exact, ten hours in");
}

/// The exact read of the swell, for the sampled tests beside it.
#[test]
fn exact_swell_parity_256() {
    run_parity(256, swell, 20, Some(DRAG), 14, "drag, swell, exact");
}

#[test]
fn height_field_and_air_parity() {
    run_parity(256, height_field, 20, Some(DRAG), 7, "drag, height field");
    run_parity(256, air, 10, Some(DRAG), 8, "drag, unbounded air");
}

#[test]
fn mass_parity() {
    let Some(d) = device() else { return };
    let d = &d;
    let mut gpu = Gpu::new(d);
    for n in [256, 1024] {
        let mut worst = [0.0f64; 3];
        for b in baked(n) {
            let mut rng = Lcg(n as u64);
            let texture: Vec<f32> = (0..b.atlas.len()).map(|_| rng.range(0.5, 3.0) as f32).collect();
            let models = [
                MassModel::Solid { density: 650.0 },
                MassModel::Shell { areal_density: 2.5 },
                MassModel::ShellTexture {
                    areal_density: texture,
                },
            ];
            for model in &models {
                let c = Cpu.mass(b, model);
                let g = gpu.mass(b, model);
                let e = [
                    (g.mass - c.mass).abs() / c.mass,
                    (g.center_of_mass - c.center_of_mass).norm() / b.diameter,
                    (g.inertia - c.inertia).norm() / c.inertia.norm(),
                ];
                for k in 0..3 {
                    worst[k] = worst[k].max(e[k]);
                }
                assert!(
                    e.iter().all(|&x| x <= TOL),
                    "{} at {n}², {model:?}: mass, centre, inertia errors {e:?}",
                    b.name
                );
            }
        }
        eprintln!("mass properties at {n}²: max relative errors (mass, centre/diameter, inertia) {worst:?}");
    }
}

// ---------------------------------------------------------------- batching

#[test]
fn a_batch_of_100_equals_100_single_evaluations() {
    let Some(d) = device() else { return };
    let d = &d;
    let gpu = &mut Gpu::new(d);
    let set = baked(256);
    let waters = [plane(), sea(), height_field(), tilted(), air(), spectral()];
    let mut rng = Lcg(42);
    let mut bodies = Vec::new();
    for k in 0..100 {
        let b = &set[k % set.len()];
        let id = gpu.id(b);
        let water = &waters[(k / 7) % waters.len()];
        let level = water.surface.height(0.0, 0.0, 0.0).min(1e3);
        let state = rng.state(b, level, 20.0, 1.5);
        let options = HydroOptions {
            buoyancy: BuoyancyMode::Pressure,
            drag: (k % 3 != 0).then_some(DRAG),
            dt: 1.0 / 120.0,
            // A sea sampled once for a quarter of the bodies.
            sea: if k % 4 == 1 {
                SeaSampling::PerWavelength(SeaSampling::DEFAULT_PER_WAVELENGTH)
            } else {
                SeaSampling::Exact
            },
            ..HydroOptions::default()
        };
        bodies.push((b, GpuBody::from((id, water, state, b.mass, options))));
    }
    let batch: Vec<GpuBody> = bodies.iter().map(|(_, g)| *g).collect();
    let t = 3.25;
    let together = gpu.hydro.evaluate_batch(&batch, t).unwrap();
    assert_eq!(together.len(), 100);
    let mut all = Errors::default();
    for (k, ((b, body), f)) in bodies.iter().zip(&together).enumerate() {
        let alone = gpu
            .hydro
            .evaluate(body.atlas, body.water, &body.state, &body.mass, t, &body.options)
            .unwrap();
        assert_eq!(
            *f, alone,
            "body {k} ({}) differs between batch and single",
            b.name
        );
        let cpu = evaluate(&b.atlas, body.water, &body.state, &b.mass, t, &body.options).unwrap();
        all.merge(&compare(b, body.water, &body.state, &cpu, f));
    }
    all.report("a batch of 100 bodies, 6 waters, 7 meshes, against the CPU");
}

// ---------------------------------------------------------------- sampled surfaces

/// A water whose surface already is a [`SurfacePatch`] reads alike on both
/// sides: sampled with and without velocities, 50 m above the world's zero
/// and kilometres from its origin (f32 holds there: the kernel reads the
/// patch relative to the body), and where a body reaches past the patch's
/// rectangle (both sides clamp to it).
#[test]
fn a_surface_patch_reads_alike_on_both() {
    let Some(d) = device() else { return };
    let d = &d;
    let mut gpu = Gpu::new(d);
    let set = baked(256);
    let (level, t) = (50.0, 2.7);
    let at = Vector3::new(3000.0, 0.0, -2000.0);
    let sea = Gerstner::new(level, swell_waves(), 9.80665).unwrap();
    // 2.2 m a side: the larger meshes reach past it.
    let (min, max) = ([at.x - 1.1, at.z - 1.1], [at.x + 1.1, at.z + 1.1]);
    let spacing = 4.0 / 16.0;
    let with_velocity =
        SurfacePatch::sample(&sea, t, min, max, spacing, Some((level - 1.5, level + 1.5))).unwrap();
    let heights_only = SurfacePatch::sample(&sea, t, min, max, spacing, None).unwrap();
    assert!(with_velocity.has_velocity() && !heights_only.has_velocity());
    let mut all = Errors::default();
    for (patch, what) in [(with_velocity, "with velocities"), (heights_only, "heights only")] {
        let water = Water::new(patch);
        let mut rng = Lcg(21);
        for b in set {
            let bodies: Vec<(&Water, BodyState, HydroOptions)> = (0..12)
                .map(|k| {
                    let mut state = rng.state(b, level, 0.6, 2.0);
                    state.pose.translation.vector += at;
                    let options = HydroOptions {
                        buoyancy: if k % 2 == 0 {
                            BuoyancyMode::Archimedes
                        } else {
                            BuoyancyMode::Pressure
                        },
                        drag: (k % 3 != 2).then_some(DRAG),
                        dt: 1.0 / 60.0,
                        ..HydroOptions::default()
                    };
                    (&water, state, options)
                })
                .collect();
            let expected = Cpu.forces(b, &bodies, t);
            let got = gpu.forces(b, &bodies, t);
            let mut errors = Errors::default();
            for ((body, c), g) in bodies.iter().zip(&expected).zip(&got) {
                check_forces(&Cpu, b, &water, &body.1, body.2.buoyancy, c);
                check_forces(&gpu, b, &water, &body.1, body.2.buoyancy, g);
                errors.merge(&compare(b, &water, &body.1, c, g));
            }
            eprintln!("  {what}, {}: {errors:?}", b.name);
            all.merge(&errors);
        }
    }
    all.report(&format!("a SurfacePatch on both sides, {}", gpu.name()));
}

/// Sampling the sea for the GPU fails as it does on the CPU, as a value.
#[test]
fn a_bad_sampling_length_is_a_typed_error() {
    let Some(d) = device() else { return };
    let d = &d;
    let mut gpu = Gpu::new(d);
    let b = &baked(256)[0];
    let id = gpu.id(b);
    let water = swell();
    let state = BodyState::at_rest(Isometry3::identity());
    let bad = HydroOptions {
        sea: SeaSampling::PerWavelength(f64::NAN),
        ..HydroOptions::default()
    };
    assert!(evaluate(&b.atlas, &water, &state, &b.mass, 0.0, &bad).is_err());
    let calm = plane();
    let batch: Vec<GpuBody> = (0..3)
        .map(|k| GpuBody::from((id, if k == 2 { &water } else { &calm }, state, b.mass, bad)))
        .collect();
    let e = gpu.hydro.evaluate_batch(&batch, 0.0).unwrap_err();
    assert!(matches!(e, GpuHydroError::Water { body: 2, .. }), "{e:?}");
    eprintln!("{e}");
}

// ---------------------------------------------------------------- deformation

/// A smooth twist, stretch and bend of the object (m).
fn deform(p: &Point3<f64>, s: f64) -> Point3<f64> {
    let a = s * p.y;
    let (sn, cs) = a.sin_cos();
    Point3::new(
        (1.0 + 0.2 * s) * (cs * p.x - sn * p.z) + 0.1 * s * p.y * p.y,
        (1.0 - 0.1 * s) * p.y,
        sn * p.x + cs * p.z,
    )
}

#[test]
fn deformation_on_the_gpu_matches_refresh() {
    let Some(d) = device() else { return };
    let d = &d;
    let mut gpu = hydro(d);
    for b in [&baked(256)[4], &baked(256)[5]] {
        let id = gpu.upload_deformable(&b.atlas, &b.mesh.triangles).unwrap();
        let mut cpu_atlas = b.atlas.clone();
        for s in [0.3, 0.8] {
            let positions: Vec<Point3<f64>> = b.mesh.positions.iter().map(|p| deform(p, s)).collect();
            cpu_atlas.refresh(&positions).unwrap();
            gpu.deform(id, &positions).unwrap();
            let texels = gpu.download(id).unwrap();
            let r = cpu_atlas.bounding_radius();
            let mut worst = (0.0f64, 0.0f64);
            for i in 0..cpu_atlas.len() {
                let (x, y) = (cpu_atlas.local_positions().get(i), texels.positions[i]);
                let (a, c) = (cpu_atlas.area_vectors().get(i), texels.area_vectors[i]);
                let dx = (0..3).map(|k| (x[k] - y[k]).abs() as f64).fold(0.0, f64::max);
                let na = Vector3::new(a[0], a[1], a[2]).norm() as f64;
                let da = (0..3).map(|k| (a[k] - c[k]).abs() as f64).fold(0.0, f64::max);
                worst.0 = worst.0.max(dx / r);
                worst.1 = worst.1.max(da / na.max(1e-30));
            }
            eprintln!(
                "{} deformed by {s}: max position error / radius {:.2e}, max area-vector error / |A| {:.2e}",
                b.name, worst.0, worst.1
            );
            // Per texel, f32 edge differences of the smallest triangles lose
            // a few digits; the sums below agree to ~1e-7 all the same.
            assert!(worst.0 < 1e-6 && worst.1 < 1e-4, "{worst:?}");
            assert!((texels.bounding_radius - r).abs() < 1e-6 * r);

            // Hydrostatics and mass of the deformed body agree too.
            let mass = MassModel::Solid { density: 600.0 }
                .mass_properties(&cpu_atlas)
                .unwrap();
            let gm = gpu
                .mass_properties(id, &MassModel::Solid { density: 600.0 })
                .unwrap();
            assert!((gm.mass - mass.mass).abs() < TOL * mass.mass);
            let deformed = Baked::new(b.name, b.mesh.clone(), cpu_atlas.clone(), mass);
            let mut rng = Lcg(9);
            let mut all = Errors::default();
            for water in [plane(), sea(), air()] {
                let level = water.surface.height(0.0, 0.0, 0.0).min(1e3);
                for _ in 0..5 {
                    let state = rng.state(&deformed, level, 5.0, 1.0);
                    let options = HydroOptions {
                        drag: Some(DRAG),
                        ..exact_options()
                    };
                    let c = evaluate(&cpu_atlas, &water, &state, &mass, 0.5, &options).unwrap();
                    let g = gpu.evaluate(id, &water, &state, &mass, 0.5, &options).unwrap();
                    all.merge(&compare(&deformed, &water, &state, &c, &g));
                }
            }
            all.report(&format!("{} deformed by {s}, against the CPU", b.name));
        }
    }
    // Typed errors of the deformation path.
    let b = &baked(256)[0];
    let plain = gpu.upload(&b.atlas).unwrap();
    let positions = b.mesh.positions.clone();
    assert_eq!(
        gpu.deform(plain, &positions),
        Err(GpuHydroError::NotDeformable(plain))
    );
    let id = gpu.upload_deformable(&b.atlas, &b.mesh.triangles).unwrap();
    assert!(matches!(
        gpu.deform(id, &positions[1..]),
        Err(GpuHydroError::VertexCount { .. })
    ));
    let mut bad = positions.clone();
    bad[7].y = f64::NAN;
    assert_eq!(
        gpu.deform(id, &bad),
        Err(GpuHydroError::NonFiniteVertex { vertex: 7 })
    );
    assert!(matches!(
        gpu.upload_deformable(&b.atlas, &b.mesh.triangles[1..]),
        Err(GpuHydroError::Triangles { .. })
    ));
    let coarse = b.atlas.coarsened(4, 4).unwrap();
    assert_eq!(
        gpu.upload_deformable(&coarse, &b.mesh.triangles),
        Err(GpuHydroError::Coarsened { factor: 4 })
    );
}

// ---------------------------------------------------------------- limits and failures

#[test]
fn an_atlas_larger_than_the_binding_limit_is_split_and_agrees() {
    let Some(d) = device() else { return };
    let d = &d;
    let limit = 1 << 20; // 32768 texels per page
    let mut small =
        GpuHydro::with_options(&d.0, &d.1, GpuOptions::default().with_max_storage_binding(limit)).unwrap();
    assert_eq!(small.storage_binding_limit(), limit);
    let mut whole = hydro(d);
    let b = &baked(256)[5]; // the boat: more than one page of texels at 256²
    let mesh = builtin::parse("builtin:sphere").unwrap();
    let sphere = Atlas::bake(&mesh, BakeOptions::square(512)).unwrap();
    // One small atlas first, so the split atlas starts mid-page.
    let first = small.upload(&baked(256)[0].atlas).unwrap();
    let split = small.upload_deformable(&sphere, &mesh.triangles).unwrap();
    let boat = small.upload(&b.atlas).unwrap();
    assert!(small.atlas_pages(split).unwrap() >= 3, "{:?}", small);
    let ids = [
        whole.upload(&baked(256)[0].atlas).unwrap(),
        whole.upload_deformable(&sphere, &mesh.triangles).unwrap(),
        whole.upload(&b.atlas).unwrap(),
    ];
    assert_eq!(whole.atlas_pages(ids[1]).unwrap(), 1);
    let mass = MassModel::Solid { density: 300.0 }
        .mass_properties(&sphere)
        .unwrap();
    let sphere_baked = Baked::new("sphere 512²", mesh.clone(), sphere.clone(), mass);
    let mut rng = Lcg(77);
    let (mut vs_whole, mut vs_cpu) = (Errors::default(), Errors::default());
    let waters = [plane(), sea()];
    for water in &waters {
        for _ in 0..4 {
            let state = rng.state(&sphere_baked, 0.3, 10.0, 1.0);
            let options = HydroOptions {
                drag: Some(DRAG),
                ..exact_options()
            };
            let bodies: Vec<GpuBody> = [first, split, boat]
                .iter()
                .zip([baked(256)[0].mass, mass, b.mass])
                .map(|(&id, m)| GpuBody::from((id, water, state, m, options)))
                .collect();
            let got = small.evaluate_batch(&bodies, 1.0).unwrap();
            let bodies_whole: Vec<GpuBody> = bodies
                .iter()
                .zip(ids)
                .map(|(g, id)| GpuBody { atlas: id, ..*g })
                .collect();
            let reference = whole.evaluate_batch(&bodies_whole, 1.0).unwrap();
            let cpu = evaluate(&sphere, water, &state, &mass, 1.0, &options).unwrap();
            vs_whole.merge(&compare(&sphere_baked, water, &state, &reference[1], &got[1]));
            vs_cpu.merge(&compare(&sphere_baked, water, &state, &cpu, &got[1]));
            // With 32768 texels a page, the 256² sphere (33k texels) is split
            // too, and the boat straddles a page boundary.
            vs_whole.merge(&compare(&baked(256)[0], water, &state, &reference[0], &got[0]));
            vs_whole.merge(&compare(b, water, &state, &reference[2], &got[2]));
        }
    }
    vs_whole.report("split atlases against unsplit ones");
    vs_cpu.report("a split atlas against the CPU");
    // Mass properties across pages, a per-texel density included.
    let mut rng = Lcg(5);
    let texture: Vec<f32> = (0..sphere.len()).map(|_| rng.range(0.5, 3.0) as f32).collect();
    for model in [
        MassModel::Solid { density: 300.0 },
        MassModel::ShellTexture {
            areal_density: texture,
        },
    ] {
        let (c, g) = (
            model.mass_properties(&sphere).unwrap(),
            small.mass_properties(split, &model).unwrap(),
        );
        assert!((g.mass - c.mass).abs() < TOL * c.mass, "{model:?}");
        assert!((g.center_of_mass - c.center_of_mass).norm() < TOL * sphere_baked.diameter);
        assert!((g.inertia - c.inertia).norm() < TOL * c.inertia.norm());
    }
    // Deformation across pages.
    let positions: Vec<Point3<f64>> = mesh.positions.iter().map(|p| deform(p, 0.5)).collect();
    small.deform(split, &positions).unwrap();
    whole.deform(ids[1], &positions).unwrap();
    assert_eq!(small.download(split).unwrap(), whole.download(ids[1]).unwrap());
    assert_eq!(
        small.download(first).unwrap(),
        whole.download(ids[0]).unwrap(),
        "deforming the split atlas must not touch its page neighbours"
    );

    // What cannot be split is refused with the sizes named.
    let many: Vec<GpuBody> = (0..400)
        .map(|_| {
            GpuBody::from((
                split,
                &waters[0],
                BodyState::at_rest(Isometry3::identity()),
                mass,
                exact_options(),
            ))
        })
        .collect();
    match small.evaluate_batch(&many, 0.0) {
        Err(e @ GpuHydroError::Gpu(GpuError::TooLarge { needed, limit: l, .. })) => {
            assert!(needed > l && l == limit);
            eprintln!("refused as expected: {e}");
        }
        other => panic!("expected TooLarge, got {other:?}"),
    }
    // A spectral sea whose tile's fields (16 floats a node, 4 MB at 256²)
    // would not fit a binding, read on the device.
    let spectrum = SeaSpectrum::jonswap(0.5, 3.0);
    let ocean = Water::new(SpectralSurface::new(
        SpectralSea::realize(&spectrum, 0.0, 50.0, 256, 1, 9.80665).unwrap(),
    ));
    let one = [GpuBody::from((
        split,
        &ocean,
        BodyState::at_rest(Isometry3::identity()),
        mass,
        exact_options(),
    ))];
    match small.evaluate_batch(&one, 0.0) {
        Err(e @ GpuHydroError::Gpu(GpuError::TooLarge { needed, limit: l, .. })) => {
            assert!(needed > l && l == limit);
            eprintln!("refused as expected: {e}");
        }
        other => panic!("expected TooLarge, got {other:?}"),
    }
    assert!(matches!(
        GpuHydro::with_options(&d.0, &d.1, GpuOptions::default().with_max_storage_binding(1000)),
        Err(GpuHydroError::Gpu(GpuError::LimitTooSmall { .. }))
    ));
}

/// A surface the GPU does not know.
struct Ripples;

impl Surface for Ripples {
    fn height(&self, x: f64, z: f64, _t: f64) -> f64 {
        0.1 * (x + z).sin()
    }
}

#[test]
fn a_custom_surface_is_a_typed_error() {
    let Some(d) = device() else { return };
    let d = &d;
    let mut gpu = Gpu::new(d);
    let b = &baked(256)[0];
    let id = gpu.id(b);
    let custom = Water::new(Ripples);
    let calm = plane();
    let state = BodyState::at_rest(Isometry3::identity());
    let options = exact_options();
    assert_eq!(
        gpu.hydro.evaluate(id, &custom, &state, &b.mass, 0.0, &options),
        Err(GpuHydroError::UnsupportedSurface { body: 0 })
    );
    let batch: Vec<GpuBody> = (0..5)
        .map(|k| GpuBody::from((id, if k == 3 { &custom } else { &calm }, state, b.mass, options)))
        .collect();
    let e = gpu.hydro.evaluate_batch(&batch, 0.0).unwrap_err();
    assert_eq!(e, GpuHydroError::UnsupportedSurface { body: 3 });
    eprintln!("{e}");
    // The CPU evaluates it.
    assert!(evaluate(&b.atlas, &custom, &state, &b.mass, 0.0, &options).is_ok());
}

#[test]
fn non_finite_input_is_a_typed_error() {
    let Some(d) = device() else { return };
    let d = &d;
    let mut gpu = Gpu::new(d);
    let b = &baked(256)[1];
    let id = gpu.id(b);
    let water = plane();
    let ok = BodyState::at_rest(Isometry3::translation(0.0, 0.2, 0.0));
    let options = exact_options();
    let eval =
        |s: &BodyState, m: &MassProperties, t: f64, w: &Water| gpu.hydro.evaluate(id, w, s, m, t, &options);

    let mut s = ok;
    s.pose.translation.vector.x = f64::NAN;
    assert_eq!(
        eval(&s, &b.mass, 0.0, &water),
        Err(GpuHydroError::NonFiniteState {
            body: 0,
            field: "pose"
        })
    );
    let mut s = ok;
    s.linear_velocity.z = f64::INFINITY;
    assert_eq!(
        eval(&s, &b.mass, 0.0, &water),
        Err(GpuHydroError::NonFiniteState {
            body: 0,
            field: "linear_velocity"
        })
    );
    let mut s = ok;
    s.angular_velocity.y = f64::NAN;
    assert_eq!(
        eval(&s, &b.mass, 0.0, &water),
        Err(GpuHydroError::NonFiniteState {
            body: 0,
            field: "angular_velocity"
        })
    );
    let mut m = b.mass;
    m.inertia[(1, 1)] = f64::NAN;
    assert_eq!(
        eval(&ok, &m, 0.0, &water),
        Err(GpuHydroError::NonFiniteState {
            body: 0,
            field: "mass"
        })
    );
    assert_eq!(
        eval(&ok, &b.mass, f64::NAN, &water),
        Err(GpuHydroError::NonFiniteState { body: 0, field: "t" })
    );
    assert!(matches!(
        eval(&ok, &b.mass, 0.0, &plane().with_density(-1.0)),
        Err(GpuHydroError::Water { body: 0, .. })
    ));
    assert!(matches!(
        gpu.hydro
            .mass_properties(id, &MassModel::Solid { density: f64::NAN }),
        Err(GpuHydroError::Mass(_))
    ));
    assert!(matches!(
        gpu.hydro.mass_properties(
            id,
            &MassModel::ShellTexture {
                areal_density: vec![1.0; 3]
            }
        ),
        Err(GpuHydroError::Mass(_))
    ));
    // An id from another GpuHydro.
    let mut other = hydro(d);
    other.upload(&baked(256)[0].atlas).unwrap();
    let foreign = other.upload(&baked(256)[2].atlas).unwrap();
    let fresh = hydro(d);
    assert_eq!(
        fresh.evaluate(foreign, &water, &ok, &b.mass, 0.0, &options),
        Err(GpuHydroError::UnknownAtlas(foreign))
    );
    // Still works after all those refusals.
    assert!(eval(&ok, &b.mass, 0.0, &water).is_ok());
}

/// An open mesh's caps weigh nothing on the GPU as on the CPU, and a solid
/// of it is refused there too.
#[test]
fn open_mesh_walls_weigh_the_same_on_the_gpu() {
    let Some(d) = device() else { return };
    let mut gpu = hydro(&d);
    let atlas = Atlas::bake(
        &soak_bake::cap_openings(&builtin::open_box(1.2, 0.5, 0.8)).unwrap(),
        BakeOptions::square(128),
    )
    .unwrap();
    let id = gpu.upload(&atlas).unwrap();
    for model in [
        MassModel::Walls {
            density: 700.0,
            thickness: 0.02,
        },
        MassModel::Shell { areal_density: 9.0 },
        MassModel::ShellTexture {
            areal_density: vec![5.0; atlas.len()],
        },
    ] {
        let (cpu, on_gpu) = (
            model.mass_properties(&atlas).unwrap(),
            gpu.mass_properties(id, &model).unwrap(),
        );
        assert!(
            (cpu.mass - on_gpu.mass).abs() < 1e-4 * cpu.mass,
            "{model:?}: {} vs {}",
            cpu.mass,
            on_gpu.mass
        );
        assert!(
            (cpu.center_of_mass - on_gpu.center_of_mass).norm() < 1e-4,
            "{model:?}"
        );
    }
    assert!(matches!(
        gpu.mass_properties(id, &MassModel::Solid { density: 500.0 }),
        Err(GpuHydroError::Mass(soak_hydro::HydroError::OpenSolid))
    ));
}

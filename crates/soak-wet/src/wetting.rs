//! [`Wetting`]: the liquid texture of one body and its step.
//!
//! Its ledger and step report are in `ledger`, its own voxel field in
//! `body_field`.

use nalgebra::{Isometry3, Point3, Vector3};
use rayon::prelude::*;
use serde::{Deserialize, Serialize};
use soak_bake::Atlas;
use soak_hydro::{FlowPlane, Plane, Surface, SurfaceKind, Water};

use crate::body_field::BodyField;
use crate::diffusion::{self, Diffusion, DiffusionReport};
use crate::environment::{Environment, EnvironmentResponse};
use crate::error::WetError;
use crate::exchange::{Rates, exchange, exchange_dry_sky};
use crate::grid::VoxelGrid;
use crate::ledger::{Ledger, StepReport};
use crate::material::{Liquid, Material};
use crate::reduce::{CHUNK, chunks, liquid_volume, wide_vectors};
use crate::source::{LiquidImage, Splash};
use crate::stats::LiquidStats;

#[derive(Clone, Debug, Default)]
struct Cache {
    field: Option<BodyField>,
    partials: Vec<[f64; 4]>,
}

/// The liquid texture of one body: `h_i` per texel of its atlas (volume per
/// area, m³/m² = m, in `[0, h_max]`), with the material, liquid and
/// diffusion settings that evolve it.
///
/// Each [`Wetting::step`] absorbs water through submerged texels, catches
/// rain and evaporates from dry ones, then (if the body has its own
/// diffusion) spreads the liquid through a voxel field in object space.
/// Bodies that share a [`crate::SharedField`] leave diffusion to it.
///
/// The state is `serde`-serialisable; what is skipped (the field's binning
/// and buffers) is rebuilt from the atlas on the next step, so a saved state
/// restores exactly.
///
/// # Example
/// ```
/// use nalgebra::Isometry3;
/// use soak_bake::{Atlas, BakeOptions, builtin};
/// use soak_hydro::Water;
/// use soak_wet::prelude::*;
///
/// let atlas = Atlas::bake(&builtin::cuboid(1.0, 1.0, 1.0), BakeOptions::square(64))?;
/// let mut wet = Wetting::new(&atlas, Material::sand(), Liquid::water())?
///     .with_diffusion(Diffusion::new(1e-4));
/// // Half under water for ten seconds.
/// let (pose, water, env) = (Isometry3::identity(), Water::calm(0.0), Environment::default());
/// for k in 0..100 {
///     wet.step(&atlas, &pose, &water, &env, 0.1 * k as f64, 0.1)?;
/// }
/// let total = wet.total_liquid(&atlas);
/// assert!(total > 0.0);
/// assert!((total - wet.ledger().net()).abs() < 1e-12);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
#[derive(Clone, Debug, Serialize, Deserialize)]
pub struct Wetting {
    material: Material,
    liquid: Liquid,
    response: EnvironmentResponse,
    diffusion: Option<Diffusion>,
    h: Vec<f64>,
    permeability_map: Option<Vec<f32>>,
    ledger: Ledger,
    #[serde(skip)]
    cache: Cache,
}

impl Wetting {
    /// A dry surface over `atlas`, validated; no diffusion. An open mesh's
    /// caps ([`Atlas::is_opening`]) are no surface: their texels start with
    /// a permeability map of 0, so they neither absorb nor dry.
    pub fn new(atlas: &Atlas, material: Material, liquid: Liquid) -> Result<Self, WetError> {
        if atlas.is_empty() {
            return Err(WetError::EmptyAtlas);
        }
        material.validate()?;
        liquid.validate()?;
        Ok(Self {
            material,
            liquid,
            response: EnvironmentResponse::default(),
            diffusion: None,
            h: vec![0.0; atlas.len()],
            permeability_map: atlas.has_openings().then(|| {
                (0..atlas.len())
                    .map(|i| if atlas.is_opening(i) { 0.0 } else { 1.0 })
                    .collect()
            }),
            ledger: Ledger::default(),
            cache: Cache::default(),
        })
    }

    /// The same state with its own diffusion field (settings validated at
    /// the first step; see [`Wetting::set_diffusion`]).
    pub fn with_diffusion(mut self, diffusion: Diffusion) -> Self {
        self.diffusion = Some(diffusion);
        self.cache.field = None;
        self
    }

    /// The same state with another response to the environment.
    pub fn with_response(mut self, response: EnvironmentResponse) -> Self {
        self.response = response;
        self
    }

    /// Number of texels.
    pub fn texels(&self) -> usize {
        self.h.len()
    }

    /// The liquid texture: `h_i` per texel (atlas order), m³/m² = m.
    pub fn liquid(&self) -> &[f64] {
        &self.h
    }

    /// The material.
    pub fn material(&self) -> &Material {
        &self.material
    }

    /// The liquid's properties.
    pub fn liquid_params(&self) -> &Liquid {
        &self.liquid
    }

    /// The response to the environment.
    pub fn response(&self) -> &EnvironmentResponse {
        &self.response
    }

    /// The body's own diffusion settings, if any.
    pub fn diffusion(&self) -> Option<&Diffusion> {
        self.diffusion.as_ref()
    }

    /// The per-texel permeability multipliers, if any.
    pub fn permeability_map(&self) -> Option<&[f32]> {
        self.permeability_map.as_deref()
    }

    /// Cumulative liquid accounting.
    pub fn ledger(&self) -> &Ledger {
        &self.ledger
    }

    /// Replaces the material (validated). Liquid above the new saturation
    /// is removed and booked as painted; the field is rebuilt (capacities).
    pub fn set_material(&mut self, atlas: &Atlas, material: Material) -> Result<(), WetError> {
        self.check_atlas(atlas)?;
        material.validate()?;
        self.material = material;
        let cap = material.saturation;
        let before = self.total_liquid(atlas);
        self.h.par_iter_mut().for_each(|h| *h = h.min(cap));
        self.ledger.painted += self.total_liquid(atlas) - before;
        self.cache.field = None;
        Ok(())
    }

    /// Replaces the liquid's properties (validated).
    pub fn set_liquid_params(&mut self, liquid: Liquid) -> Result<(), WetError> {
        liquid.validate()?;
        self.liquid = liquid;
        Ok(())
    }

    /// Replaces the response to the environment (validated).
    pub fn set_response(&mut self, response: EnvironmentResponse) -> Result<(), WetError> {
        response.validate()?;
        self.response = response;
        Ok(())
    }

    /// Turns the body's own diffusion on (validated) or off. Off drops the
    /// field: no voxel is allocated and steps do no diffusion work.
    pub fn set_diffusion(&mut self, diffusion: Option<Diffusion>) -> Result<(), WetError> {
        if let Some(d) = &diffusion {
            d.validate()?;
        }
        self.diffusion = diffusion;
        self.cache.field = None;
        Ok(())
    }

    /// Sets a per-texel permeability multiplier (the thesis' permeability
    /// texture, TPM): texel `i` absorbs and dries with `map[i] · C_M`.
    /// Values must be finite and ≥ 0.
    pub fn set_permeability_map(&mut self, atlas: &Atlas, map: Option<Vec<f32>>) -> Result<(), WetError> {
        self.check_atlas(atlas)?;
        if let Some(m) = &map {
            self.check_channel("permeability map", m.len())?;
            if let Some(i) = m.iter().position(|v| !(v.is_finite() && *v >= 0.0)) {
                return Err(WetError::ChannelValue {
                    what: "permeability map",
                    texel: i,
                    value: m[i] as f64,
                    expected: "finite values >= 0",
                });
            }
        }
        self.permeability_map = map;
        Ok(())
    }

    /// Drops the field's binning so the next step rebuilds it: call after
    /// [`Atlas::refresh`] moved the texels of a deforming mesh.
    pub fn refresh_field(&mut self) {
        self.cache.field = None;
    }

    /// The grid of the body's own field once built (after the first step
    /// with diffusion), in object space.
    pub fn field_grid(&self) -> Option<VoxelGrid> {
        self.cache.field.as_ref().and_then(|f| f.layout.grid)
    }

    /// Bytes the body's own field holds (binning and buffers); zero without
    /// diffusion.
    pub fn field_bytes(&self) -> usize {
        self.cache
            .field
            .as_ref()
            .map_or(0, |f| f.layout.bytes() + f.scratch.bytes())
    }

    fn check_atlas(&self, atlas: &Atlas) -> Result<(), WetError> {
        if atlas.len() != self.h.len() {
            return Err(WetError::AtlasMismatch {
                state: self.h.len(),
                atlas: atlas.len(),
            });
        }
        Ok(())
    }

    fn check_channel(&self, what: &'static str, len: usize) -> Result<(), WetError> {
        if len != self.h.len() {
            return Err(WetError::ChannelLength {
                what,
                len,
                texels: self.h.len(),
            });
        }
        Ok(())
    }

    /// Total liquid `Σ a_i h_i`, m³ (deterministic f64 sum).
    /// `NaN` if `atlas` is not the state's.
    pub fn total_liquid(&self, atlas: &Atlas) -> f64 {
        if atlas.len() != self.h.len() {
            return f64::NAN;
        }
        liquid_volume(&self.h, atlas.areas(), &mut Vec::new())
    }

    /// Area-weighted statistics and histogram of the liquid.
    pub fn stats(&self, atlas: &Atlas) -> Result<LiquidStats, WetError> {
        self.check_atlas(atlas)?;
        Ok(LiquidStats::of(atlas, &self.h, self.material.saturation))
    }

    /// Replaces the liquid texture (m per texel, in `[0, h_max]`); the
    /// change is booked as painted.
    pub fn set_liquid(&mut self, atlas: &Atlas, h: Vec<f64>) -> Result<(), WetError> {
        self.check_atlas(atlas)?;
        self.check_channel("liquid", h.len())?;
        let hmax = self.material.saturation;
        if let Some(i) = h.iter().position(|v| !(v.is_finite() && *v >= 0.0 && *v <= hmax)) {
            return Err(WetError::ChannelValue {
                what: "liquid",
                texel: i,
                value: h[i],
                expected: "[0, saturation] m",
            });
        }
        let before = self.total_liquid(atlas);
        self.h = h;
        self.ledger.painted += self.total_liquid(atlas) - before;
        Ok(())
    }

    /// Sets every texel to the fraction `fraction` ∈ [0, 1] of saturation.
    pub fn fill(&mut self, atlas: &Atlas, fraction: f64) -> Result<(), WetError> {
        if !(0.0..=1.0).contains(&fraction) {
            return Err(WetError::parameter("fill.fraction", fraction, "in [0, 1]"));
        }
        self.set_liquid(atlas, vec![fraction * self.material.saturation; self.h.len()])
    }

    /// Sets the liquid from an artist-painted image: value 1 is `scale` m of
    /// liquid (clamped to saturation). See [`LiquidImage`].
    pub fn set_liquid_from_image(
        &mut self,
        atlas: &Atlas,
        image: &LiquidImage,
        scale: f64,
    ) -> Result<(), WetError> {
        self.check_atlas(atlas)?;
        let h = image.sample(atlas, scale, self.material.saturation)?;
        self.set_liquid(atlas, h)
    }

    /// Drops a splash on the body at `pose` (object → world) and returns
    /// the volume that stuck (m³; the rest ran off saturated texels).
    pub fn splash(&mut self, atlas: &Atlas, pose: &Isometry3<f64>, splash: &Splash) -> Result<f64, WetError> {
        self.check_atlas(atlas)?;
        splash.validate()?;
        check_pose(pose, "the body")?;
        let centre = pose.inverse() * Point3::from(splash.center);
        let o = atlas.origin();
        let c = [
            (centre.x - o.x) as f32,
            (centre.y - o.y) as f32,
            (centre.z - o.z) as f32,
        ];
        let r2 = splash.radius * splash.radius;
        let bump = |x: &[f32; 3]| {
            let d2 = (0..3).map(|k| ((x[k] - c[k]) as f64).powi(2)).sum::<f64>();
            if d2 < r2 { (1.0 - d2 / r2).powi(2) } else { 0.0 }
        };
        let local = atlas.local_positions();
        let areas = atlas.areas();
        let partials: Vec<f64> = areas
            .par_chunks(CHUNK)
            .enumerate()
            .map(|(c, a)| {
                a.iter()
                    .enumerate()
                    .map(|(k, &a)| a as f64 * bump(&local.get(c * CHUNK + k)))
                    .sum()
            })
            .collect();
        let weight: f64 = partials.iter().sum();
        if weight.is_nan() || weight <= 0.0 || splash.volume == 0.0 {
            return Ok(0.0);
        }
        let per = splash.volume / weight;
        let hmax = self.material.saturation;
        let stuck: Vec<f64> = self
            .h
            .par_chunks_mut(CHUNK)
            .zip(areas.par_chunks(CHUNK))
            .enumerate()
            .map(|(c, (h, a))| {
                let mut s = 0.0;
                for (k, (h, &a)) in h.iter_mut().zip(a).enumerate() {
                    let b = bump(&local.get(c * CHUNK + k));
                    if b > 0.0 {
                        let next = (*h + per * b).min(hmax);
                        s += (next - *h) * a as f64;
                        *h = next;
                    }
                }
                s
            })
            .collect();
        let stuck: f64 = stuck.iter().sum();
        self.ledger.splashed += stuck;
        Ok(stuck)
    }

    /// Advances the liquid by `dt` (s) at time `time` (s) for the body at
    /// `pose` (object → world, m) in `water` under `env`: absorption,
    /// rain and evaporation per texel, then the body's own diffusion.
    ///
    /// `time` is the water's clock (waves move with it). The per-texel work
    /// runs in parallel with rayon in fixed chunks; sums are added in a
    /// fixed order, so results are the same for any thread count.
    pub fn step(
        &mut self,
        atlas: &Atlas,
        pose: &Isometry3<f64>,
        water: &Water,
        env: &Environment,
        time: f64,
        dt: f64,
    ) -> Result<StepReport, WetError> {
        self.check_atlas(atlas)?;
        if !(dt.is_finite() && dt >= 0.0) {
            return Err(WetError::TimeStep { dt });
        }
        if !time.is_finite() {
            return Err(WetError::Time { t: time });
        }
        check_pose(pose, "the body")?;
        water.validate()?;
        env.validate()?;
        self.response.validate()?;
        if let Some(d) = &self.diffusion {
            d.validate()?;
        }
        let mut report = self.exchange(atlas, pose, water, env, time, dt);
        if let Some(d) = self.diffusion.filter(|d| d.coefficient > 0.0 && dt > 0.0) {
            if self.cache.field.is_none() {
                self.cache.field = Some(BodyField::build(atlas, &d, self.material.saturation)?);
            }
            let field = self.cache.field.as_mut().expect("built above");
            let grid = field.layout.grid.expect("a built layout has a grid");
            let plan = d.plan(dt, grid.voxel_size, field.layout.count_max);
            let drift = diffusion::run(&field.layout, &mut self.h, d.mode, &plan, &mut field.scratch);
            self.ledger.drift += drift;
            report.diffusion = Some(DiffusionReport {
                plan,
                voxels: field.layout.defined(),
                count_max: field.layout.count_max,
                outside: field.layout.outside,
                drift,
            });
        }
        Ok(report)
    }

    fn exchange(
        &mut self,
        atlas: &Atlas,
        pose: &Isometry3<f64>,
        water: &Water,
        env: &Environment,
        time: f64,
        dt: f64,
    ) -> StepReport {
        let rates = Rates::new(
            &self.material,
            &self.liquid,
            &self.response,
            env,
            water.density,
            water.gravity,
        );
        let rot = pose.rotation.to_rotation_matrix().into_inner();
        let ow = (pose * atlas.origin()).coords;
        let surface = &*water.surface;
        // Can any texel be under water? Not in an unbounded medium (air: no
        // liquid to absorb), nor when the body's lowest point is above the
        // highest crest.
        let lowest = ow.y - atlas.bounding_radius();
        let wet_possible = rates.absorb > 0.0
            && match surface.kind(time) {
                SurfaceKind::Unbounded => false,
                _ => surface.height_bounds(time).is_none_or(|(_, hi)| lowest <= hi),
            };
        let raining = rates.rain > 0.0;
        if dt == 0.0 || (!wet_possible && !raining && rates.evaporate <= 0.0) {
            return StepReport::default();
        }
        // Texels above the highest crest are dry; texels below the lowest
        // trough are submerged, and need no probe once saturated.
        let (trough, crest) = surface
            .height_bounds(time)
            .filter(|(lo, hi)| lo.is_finite() && hi.is_finite())
            .unwrap_or((f64::NEG_INFINITY, f64::INFINITY));
        let texels = Texels {
            atlas,
            map: self.permeability_map.as_deref(),
            rot,
            ow,
            time,
            dt,
            wet_possible,
            raining,
            trough,
            crest,
        };
        self.cache.partials.clear();
        self.cache.partials.resize(chunks(self.h.len()), [0.0; 4]);
        // A plane's depth is called directly (inlined), any other surface
        // through the trait object: the same arithmetic either way. A plane
        // whose current changes over space has the plane's heights.
        let plane = surface.as_any().and_then(|s| {
            s.downcast_ref::<Plane>()
                .or_else(|| s.downcast_ref::<FlowPlane>().map(|f| &f.plane))
        });
        match plane {
            Some(plane) if !raining => texels.run_plane(plane, &rates, &mut self.h, &mut self.cache.partials),
            Some(plane) => texels.run(plane, &rates, &mut self.h, &mut self.cache.partials),
            None => texels.run(surface, &rates, &mut self.h, &mut self.cache.partials),
        }
        let mut sum = [0.0; 4];
        for p in &self.cache.partials {
            for k in 0..4 {
                sum[k] += p[k];
            }
        }
        self.ledger.absorbed += sum[0];
        self.ledger.rained += sum[1];
        self.ledger.evaporated += sum[2];
        StepReport {
            absorbed: sum[0],
            rained: sum[1],
            evaporated: sum[2],
            submerged_texels: sum[3] as usize,
            diffusion: None,
        }
    }

    /// Mutable access to the liquid texture and ledger for a shared field.
    pub(crate) fn parts_mut(&mut self) -> (&mut Vec<f64>, &mut Ledger) {
        (&mut self.h, &mut self.ledger)
    }
}

/// Texels exchanged together (one per lane) by [`Texels::run_plane`].
const LANES: usize = 4;

/// What the per-texel exchange of one step reads besides the liquid.
struct Texels<'a> {
    atlas: &'a Atlas,
    map: Option<&'a [f32]>,
    /// Object → world rotation and the atlas origin in the world, m.
    rot: nalgebra::Matrix3<f64>,
    ow: Vector3<f64>,
    time: f64,
    dt: f64,
    wet_possible: bool,
    raining: bool,
    /// Lowest and highest surface height, m (infinite when unknown).
    trough: f64,
    crest: f64,
}

impl Texels<'_> {
    /// [`Texels::run`] for a plane and no rain, [`LANES`] texels at a time
    /// (vectorized, and compiled for AVX2 where the processor has it): the
    /// same operations per texel, and the chunk sums added texel by texel in
    /// the same order, so the same bits.
    fn run_plane(&self, plane: &Plane, rates: &Rates, h: &mut [f64], partials: &mut [[f64; 4]]) {
        let wide = wide_vectors();
        h.par_chunks_mut(CHUNK)
            .zip(partials.par_iter_mut())
            .enumerate()
            .for_each(|(c, (hs, part))| {
                #[cfg(target_arch = "x86_64")]
                if wide {
                    // SAFETY: the processor has AVX2 (`wide_vectors`).
                    #[allow(unsafe_code)]
                    unsafe {
                        *part = self.plane_chunk_avx2(plane, rates, c, hs);
                    }
                    return;
                }
                let _ = wide;
                *part = self.plane_chunk(plane, rates, c, hs);
            });
    }

    /// [`Texels::plane_chunk`] compiled for AVX2.
    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx2")]
    fn plane_chunk_avx2(&self, plane: &Plane, rates: &Rates, c: usize, hs: &mut [f64]) -> [f64; 4] {
        self.plane_chunk(plane, rates, c, hs)
    }

    /// Chunk `c` (liquid `hs`) of [`Texels::run_plane`]; its sums.
    #[inline(always)]
    fn plane_chunk(&self, plane: &Plane, rates: &Rates, c: usize, hs: &mut [f64]) -> [f64; 4] {
        let (rot, ow) = (&self.rot, &self.ow);
        let hmax = rates.saturation;
        let range = c * CHUNK..c * CHUNK + hs.len();
        let [xs, ys, zs] = self.atlas.local_positions().columns(range.clone());
        let areas = &self.atlas.areas()[range.clone()];
        let map = self.map.map(|m| &m[range]);
        let mut hint = [0.0; 2];
        let mut acc = [0.0; 4];
        for (k0, hs) in (0..hs.len()).step_by(LANES).zip(hs.chunks_mut(LANES)) {
            // A short last group repeats its first texel in the unused
            // lanes, whose results are dropped.
            let lane = |l: usize| k0 + if l < hs.len() { l } else { 0 };
            let (mut depth, mut h, mut a, mut scale) =
                ([0.0; LANES], [0.0; LANES], [0.0; LANES], [1.0; LANES]);
            for l in 0..LANES {
                let k = lane(l);
                h[l] = hs[k - k0];
                let r = rot * Vector3::new(xs[k] as f64, ys[k] as f64, zs[k] as f64);
                let p = Point3::from(ow + r);
                let probed = plane.probe(&p, self.time, false, &mut hint).0;
                depth[l] = if !self.wet_possible || p.y > self.crest {
                    -1.0
                } else if p.y < self.trough && h[l] >= hmax {
                    self.trough - p.y
                } else {
                    probed
                };
                a[l] = areas[k] as f64;
                if let Some(m) = map {
                    scale[l] = m[k] as f64;
                }
            }
            let mut x = [(0.0, 0.0, 0.0); LANES];
            for l in 0..LANES {
                x[l] = exchange_dry_sky(h[l], rates, depth[l], scale[l], self.dt);
            }
            for (l, h) in hs.iter_mut().enumerate() {
                let (next, absorbed, evaporated) = x[l];
                *h = next;
                acc[0] += absorbed * a[l];
                acc[1] += 0.0 * a[l];
                acc[2] += evaporated * a[l];
                acc[3] += if depth[l] > 0.0 { 1.0 } else { 0.0 };
            }
        }
        acc
    }

    /// Exchanges every texel of `h` with `surface` in chunks of [`CHUNK`],
    /// in parallel; `partials` receives each chunk's sums (absorbed, rained,
    /// evaporated, m³, and submerged texels).
    fn run<S: Surface + ?Sized>(&self, surface: &S, rates: &Rates, h: &mut [f64], partials: &mut [[f64; 4]]) {
        let (rot, ow) = (&self.rot, &self.ow);
        let hmax = rates.saturation;
        let local = self.atlas.local_positions();
        let area_vectors = self.atlas.area_vectors();
        let areas = self.atlas.areas();
        h.par_chunks_mut(CHUNK)
            .zip(partials.par_iter_mut())
            .enumerate()
            .for_each(|(c, (hs, part))| {
                let range = c * CHUNK..c * CHUNK + hs.len();
                let [xs, ys, zs] = local.columns(range.clone());
                let areas = &areas[range];
                let mut hint = [0.0; 2];
                let mut acc = [0.0; 4];
                for (k, h) in hs.iter_mut().enumerate() {
                    let i = c * CHUNK + k;
                    let r = rot * Vector3::new(xs[k] as f64, ys[k] as f64, zs[k] as f64);
                    let p = Point3::from(ow + r);
                    let depth = if !self.wet_possible || p.y > self.crest {
                        -1.0
                    } else if p.y < self.trough && *h >= hmax {
                        self.trough - p.y
                    } else {
                        surface.probe(&p, self.time, false, &mut hint).0
                    };
                    let a = areas[k] as f64;
                    let up = if self.raining && a > 0.0 {
                        let av = area_vectors.get(i);
                        (rot * Vector3::new(av[0] as f64, av[1] as f64, av[2] as f64)).y / a
                    } else {
                        0.0
                    };
                    let in_rain = self.raining && rates.region.contains(&p);
                    let scale = self.map.map_or(1.0, |m| m[i] as f64);
                    let x = exchange(h, rates, depth, scale, up, in_rain, self.dt);
                    acc[0] += x.absorbed * a;
                    acc[1] += x.rained * a;
                    acc[2] += x.evaporated * a;
                    acc[3] += if depth > 0.0 { 1.0 } else { 0.0 };
                }
                *part = acc;
            });
    }
}

/// Checks a pose is finite.
pub(crate) fn check_pose(pose: &Isometry3<f64>, what: &str) -> Result<(), WetError> {
    let finite = pose.translation.vector.iter().all(|c| c.is_finite())
        && pose.rotation.coords.iter().all(|c| c.is_finite());
    if finite {
        Ok(())
    } else {
        Err(WetError::NonFinitePose {
            what: what.to_owned(),
        })
    }
}

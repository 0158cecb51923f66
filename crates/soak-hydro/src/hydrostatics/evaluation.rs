//! The per-texel pass: buoyancy and drag summed over every texel of the
//! atlas, and the read that is the floor under it.

use nalgebra::{Point3, Vector3};
use soak_bake::Atlas;

use super::body_state::BodyState;
use super::drag_kernel::{Added, LocalDrag, add_drag_texels, uniform_velocity};
use super::finish::finish;
use super::forces::HydroForces;
use super::frame::{Frame, texel};
use super::options::{BuoyancyMode, Drag, HydroOptions, SeaSampling};
use super::planar_kernel::{PlanarTexels, add_planar_ranges};
use super::sea_drag::{SeaDragFrame, SeaDragSums, sea_drag_range};
use super::sea_kernel::{self, SeaFrame, SeaRead, add_sea_range};
use super::sums::{BuoyancySums, DragAcc, DragSums, TexelDrag};
use crate::error::HydroError;
use crate::mass::{CHUNK, MassProperties, chunked_sum};
use crate::water::{MAX_PATCH_NODES, Surface, SurfaceKind, SurfacePatch, Water};

/// Buoyancy and drag sums of one pass: the drag's as [`TexelDrag`] (world
/// axes, any surface) or [`SeaDragSums`] (object axes, a sampled sea).
#[derive(Clone, Copy, Default)]
struct Both<D> {
    b: BuoyancySums,
    d: D,
}

impl<D: std::ops::Add<Output = D>> std::ops::Add for Both<D> {
    type Output = Self;
    fn add(self, o: Self) -> Self {
        Self {
            b: self.b + o.b,
            d: self.d + o.d,
        }
    }
}

/// Reads every position, area vector and area of the atlas once and folds
/// their bits into a checksum, in the same chunks as [`evaluate`]: the
/// bytes a per-texel pass reads and nothing else, as fast as the memory
/// gives them, and so the floor under any such pass. Benchmarks compare
/// [`evaluate`]'s time against it.
///
/// The chunks go to rayon's pool alone, the calling thread waiting: of the
/// ways tried this reads fastest (handed out one by one to the calling
/// thread and a helper, as the passes' chunks are, the read took 1.4–1.6
/// times as long at 1024²), so the floor is the lowest one.
pub fn streaming_read(atlas: &Atlas) -> f64 {
    use rayon::prelude::*;
    let n = atlas.len();
    let chunk = |range: std::ops::Range<usize>| {
        let [x, y, z] = atlas.local_positions().columns(range.clone());
        let [ax, ay, az] = atlas.area_vectors().columns(range.clone());
        let areas = &atlas.areas()[range];
        // Wrapping integer sums of the bits, one array after the other: no
        // chain of dependent float additions, so the compiler reads with
        // SIMD and the time is the memory's, not an adder's latency.
        let bits = |v: &[f32]| v.iter().fold(0u32, |s, x| s.wrapping_add(x.to_bits()));
        let s = bits(x) ^ bits(y) ^ bits(z) ^ bits(ax) ^ bits(ay) ^ bits(az) ^ bits(areas);
        f64::from(s)
    };
    (0..n.div_ceil(CHUNK))
        .into_par_iter()
        .map(|c| chunk(c * CHUNK..((c + 1) * CHUNK).min(n)))
        .sum()
}

/// Buoyancy and drag on a body, summing over every texel (rayon, f64,
/// deterministic for any thread count).
///
/// For texel `i` at world position `p_i` with world area vector `A_i`,
/// depth `d_i = f(p_i) − p_i.y` and submerged set `S = {i : d_i > 0}`:
/// `V_s = Σ_S −A_{i,y} d_i` (signed columns, exact for non-convex bodies and
/// any surface `y = f(x, z)`), `C_B = (1/V_s) Σ_S −A_{i,y} d_i (p_x, p_y + d_i/2, p_z)`;
/// Archimedes mode applies `ρ g V_s` up at `C_B`; pressure mode sums
/// `−ρ g d_i A_i` and its torque (equal on a plane, and it also feels the
/// sideways push of a wave's slope). Drag is quadratic per submerged texel
/// facing its relative velocity, plus optional linear skin friction, and is
/// integrated implicitly over the step so it never reverses a velocity.
///
/// `mass` are the body's mass properties (object frame): the centre of mass
/// is where torques are taken, and mass and inertia make the implicit drag.
///
/// # Example
/// ```
/// use nalgebra::{Isometry3, Vector3};
/// use soak_bake::{Atlas, BakeOptions, builtin};
/// use soak_hydro::prelude::*;
///
/// let atlas = Atlas::bake(&builtin::cuboid(1.0, 1.0, 1.0), BakeOptions::square(128))?;
/// let mass = MassModel::Solid { density: 500.0 }.mass_properties(&atlas)?;
/// // Box centred 0.2 m below the surface at y = 0: 0.7 m³ submerged.
/// let state = BodyState::at_rest(Isometry3::translation(0.0, -0.2, 0.0));
/// let f = evaluate(&atlas, &Water::calm(0.0), &state, &mass, 0.0, &HydroOptions::default())?;
/// assert!((f.submerged_volume - 0.7).abs() < 1e-6);
/// assert!((f.buoyancy.force.y - 1000.0 * 9.80665 * 0.7).abs() < 1e-2);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn evaluate(
    atlas: &Atlas,
    water: &Water,
    state: &BodyState,
    mass: &MassProperties,
    t: f64,
    options: &HydroOptions,
) -> Result<HydroForces, HydroError> {
    water.validate()?;
    state.check()?;
    // A sea read as one plane over the body: the planar path on that plane.
    if let Some(plane) = plane_of(atlas, water, state, t, options)? {
        return evaluate(atlas, &plane, state, mass, t, options);
    }
    let frame = Frame::new(atlas, water, state, mass, t, options.dt);
    let pressure = options.buoyancy == BuoyancyMode::Pressure;
    let sums = match frame.local_plane {
        // Planar water: depth is affine in object coordinates, so sum there
        // and rotate once.
        Some((alpha, beta, g)) => chunked_sum(atlas.len(), BuoyancySums::default(), |range| {
            let mut s = BuoyancySums::default();
            add_planar_ranges(
                &mut s,
                atlas,
                &[range],
                alpha,
                &beta,
                &g,
                pressure,
                PlanarTexels::Wet,
            );
            s
        })
        .rotated(&frame.rot),
        None => {
            let (sums, drag) = match water
                .surface
                .as_any()
                .and_then(|s| s.downcast_ref::<SurfacePatch>())
            {
                Some(patch) => patch_sums(atlas, water, state, &frame, t, options, patch),
                None => match sample_patch(atlas, water, state, t, options)? {
                    Some(patch) => patch_sums(atlas, water, state, &frame, t, options, &patch),
                    None => exact_sums(atlas, water, state, &frame, t, options),
                },
            };
            return Ok(finish(&frame, water, state, mass, &sums, drag.as_ref(), options));
        }
    };
    let drag = options
        .drag
        .map(|drag| drag_sums(atlas, water, state, &frame, &drag, t, 0..atlas.len()));
    Ok(finish(&frame, water, state, mass, &sums, drag.as_ref(), options))
}

/// The sums of every texel under a surface that is not a plane, read
/// exactly at each (no sampled patch).
pub(crate) fn exact_sums(
    atlas: &Atlas,
    water: &Water,
    state: &BodyState,
    frame: &Frame,
    t: f64,
    options: &HydroOptions,
) -> (BuoyancySums, Option<DragSums>) {
    let both = general_sums(atlas, water, state, frame, t, options, &Exact(&*water.surface));
    (both.b, options.drag.map(|_| both.d.sums()))
}

/// How the texels of a pass over a surface that is not a plane read it.
trait TexelSurface: Sync {
    /// What one read leaves for the next (a warm start) and for
    /// [`TexelSurface::slope`] at the same point.
    type Hint: Default;
    /// Depth of `p` below the surface (m) and, when `with_velocity`, the
    /// fluid velocity there (m/s).
    fn depth(
        &self,
        p: &Vector3<f64>,
        t: f64,
        with_velocity: bool,
        hint: &mut Self::Hint,
    ) -> (f64, Vector3<f64>);
    /// The surface's slope above `p`, after a [`TexelSurface::depth`] at `p`.
    fn slope(&self, p: &Vector3<f64>, t: f64, hint: &Self::Hint) -> [f64; 2];
}

/// The surface itself, read at every texel.
struct Exact<'a>(&'a dyn Surface);

impl TexelSurface for Exact<'_> {
    type Hint = [f64; 2];
    #[inline]
    fn depth(
        &self,
        p: &Vector3<f64>,
        t: f64,
        with_velocity: bool,
        hint: &mut [f64; 2],
    ) -> (f64, Vector3<f64>) {
        self.0.probe(&Point3::from(*p), t, with_velocity, hint)
    }
    #[inline]
    fn slope(&self, p: &Vector3<f64>, t: f64, hint: &[f64; 2]) -> [f64; 2] {
        self.0.slope(p.x, p.z, t, hint)
    }
}

impl TexelSurface for SurfacePatch {
    /// The slope the depth's read found.
    type Hint = [f64; 2];
    #[inline]
    fn depth(
        &self,
        p: &Vector3<f64>,
        _t: f64,
        with_velocity: bool,
        hint: &mut [f64; 2],
    ) -> (f64, Vector3<f64>) {
        let (h, slope) = self.height_slope(p.x, p.z);
        *hint = slope;
        let u = if with_velocity && h > p.y {
            self.velocity_at(p)
        } else {
            Vector3::zeros()
        };
        (h - p.y, u)
    }
    #[inline]
    fn slope(&self, _p: &Vector3<f64>, _t: f64, hint: &[f64; 2]) -> [f64; 2] {
        *hint
    }
}

/// Buoyancy (and drag) sums over every texel under a surface that is not
/// a plane, read through `surface`.
fn general_sums<S: TexelSurface>(
    atlas: &Atlas,
    water: &Water,
    state: &BodyState,
    frame: &Frame,
    t: f64,
    options: &HydroOptions,
    surface: &S,
) -> Both<TexelDrag> {
    // A texel above the highest the surface reaches is dry without a read.
    let top = water.surface.height_bounds(t).map_or(f64::INFINITY, |(_, hi)| hi);
    let archimedes = options.buoyancy == BuoyancyMode::Archimedes;
    chunked_sum(atlas.len(), Both::<TexelDrag>::default(), |range| {
        let mut s = Both::<TexelDrag>::default();
        // Neighbouring texels warm-start each other.
        let mut hint = S::Hint::default();
        for i in range {
            let (x, a) = texel(atlas, i);
            let r = frame.rot * x;
            let p = frame.ow + r;
            if p.y >= top {
                continue;
            }
            let (d, u) = surface.depth(&p, t, options.drag.is_some(), &mut hint);
            if d > 0.0 {
                let aw = frame.rot * a;
                s.b.add_texel(&r, &aw, atlas.areas()[i] as f64, d);
                if archimedes {
                    let slope = surface.slope(&p, t, &hint);
                    s.b.slope
                        .add(&(p - frame.com), r.y, &aw, d, slope, frame.deep_scale);
                }
                if let Some(drag) = &options.drag {
                    let rc = p - frame.com;
                    let v = state.linear_velocity + state.angular_velocity.cross(&rc) - u;
                    s.d.add(drag, water.density, &rc, &aw, &v, &u);
                }
            }
        }
        s
    })
}

/// [`general_sums`] over a sampled surface: the sea kernel (AVX2) where
/// the processor has it, the per-texel loop elsewhere. With drag the
/// kernel hands each chunk's depths to a loop that gathers the submerged
/// texels with the fluid's velocity for the sea's drag kernel.
pub(crate) fn patch_sums(
    atlas: &Atlas,
    water: &Water,
    state: &BodyState,
    frame: &Frame,
    t: f64,
    options: &HydroOptions,
    patch: &SurfacePatch,
) -> (BuoyancySums, Option<DragSums>) {
    if !sea_kernel::available() {
        let both = general_sums(atlas, water, state, frame, t, options, patch);
        return (both.b, options.drag.map(|_| both.d.sums()));
    }
    let sea = SeaFrame {
        rot: frame.rot,
        ow: frame.ow,
        com: frame.com - frame.ow,
        top: patch.height_bounds(t).map_or(f64::INFINITY, |(_, hi)| hi),
        delta: frame.deep_scale,
        patch,
        archimedes: options.buoyancy == BuoyancyMode::Archimedes,
    };
    let Some(drag) = &options.drag else {
        let sums = chunked_sum(atlas.len(), BuoyancySums::default(), |range| {
            let mut s = BuoyancySums::default();
            add_sea_range(&mut s, atlas, range, &sea, None, SeaRead::Sums, None);
            s
        });
        return (sums, None);
    };
    let (drag_frame, c) = SeaDragFrame::of(drag, water, state, frame, patch);
    let both = chunked_sum(atlas.len(), Both::<SeaDragSums>::default(), |range| {
        let mut s = BuoyancySums::default();
        let mut depths = [0.0; CHUNK];
        let depths = &mut depths[..range.len()];
        add_sea_range(
            &mut s,
            atlas,
            range.clone(),
            &sea,
            None,
            SeaRead::Sums,
            Some(depths),
        );
        Both {
            b: s,
            d: sea_drag_range(atlas, range, depths, &drag_frame, None),
        }
    });
    (both.b, Some(both.d.system(&frame.rot, &c)))
}

/// The water's surface sampled once over the footprint of a body at
/// `state` (its bounding sphere's; one node spacing wider where the
/// surface does not give its nodes' twists, [`Surface::node_twists`]), as
/// [`HydroOptions::sea`] asks, with the waves [`HydroOptions::sea_band`]
/// asks for (all of them, or a band long against the body): `None` when it asks for the exact read, the
/// surface has no [`Surface::sampling_length`] (planes, height fields,
/// surfaces of your own), or the body is so large against the waves that
/// its patch would need more than [`MAX_PATCH_NODES`] nodes a side. With drag, the fluid's velocity is sampled too,
/// over the body's height.
///
/// [`evaluate`] samples on its own when handed a sea; sample once and
/// evaluate on the water [`sampled_water`] returns when one step evaluates
/// the same body more than once (an implicit solve at shifted heights).
pub(crate) fn sample_patch(
    atlas: &Atlas,
    water: &Water,
    state: &BodyState,
    t: f64,
    options: &HydroOptions,
) -> Result<Option<SurfacePatch>, HydroError> {
    sample_patch_around(atlas.origin(), atlas.bounding_radius(), water, state, t, options)
}

/// [`sample_patch`] for a body known by its atlas origin (object frame, m)
/// and the radius of a sphere about it that holds every texel (m), for
/// callers without the [`Atlas`] at hand (the GPU path).
pub(crate) fn sample_patch_around(
    origin: Point3<f64>,
    radius: f64,
    water: &Water,
    state: &BodyState,
    t: f64,
    options: &HydroOptions,
) -> Result<Option<SurfacePatch>, HydroError> {
    let per = match options.sea {
        SeaSampling::PerWavelength(per) => per,
        SeaSampling::Auto => SeaSampling::DEFAULT_PER_WAVELENGTH,
        SeaSampling::Exact | SeaSampling::Plane => return Ok(None),
    };
    if !matches!(water.surface.kind(t), SurfaceKind::General) {
        return Ok(None);
    }
    let surface = read_surface(water, radius, options)?;
    let Some(length) = surface.sampling_length(t) else {
        return Ok(None);
    };
    options.sea.check()?;
    let spacing = length / per;
    let centre = state.pose * origin;
    // A surface that gives its nodes' twists is sampled over the
    // footprint alone; otherwise one spacing wider, so that the nodes
    // under the body take central differences of the slopes.
    let reach = radius + if surface.node_twists() { 0.0 } else { spacing };
    // A body so large against the waves that its patch would need more
    // nodes than a patch holds is read exactly rather than more coarsely.
    if 2.0 * reach / spacing > (MAX_PATCH_NODES - 1) as f64 {
        return Ok(None);
    }
    let min = [centre.x - reach, centre.z - reach];
    let max = [centre.x + reach, centre.z + reach];
    let r = radius;
    let velocity = options.drag.map(|_| (centre.y - r, centre.y + r));
    Ok(Some(SurfacePatch::sample(
        surface, t, min, max, spacing, velocity,
    )?))
}

/// The waves a body of bounding radius `radius` (m) reads of `water`'s
/// surface, as [`HydroOptions::sea_band`] asks: all of them, or a band of
/// them long against it.
fn read_surface<'a>(
    water: &'a Water,
    radius: f64,
    options: &HydroOptions,
) -> Result<&'a dyn Surface, HydroError> {
    Ok(match options.sea_band.wavelength(radius)? {
        Some(wavelength) => water.surface.band_limited(wavelength),
        None => None,
    }
    .unwrap_or(&*water.surface))
}

/// Where the plane of [`SeaSampling::Plane`] reads the surface about a
/// body whose section at the sea's height is not known (wholly above or
/// under it), as a fraction of the body's bounding radius: at the centre
/// and at this distance either way along x and z, the five heights' mean
/// is the mean of any quadratic surface over the disc of the bounding
/// radius (`κ ρ²/5 = κ r²/8`), and their central differences its slope at
/// the centre.
pub(crate) const PLANE_READ_REACH: f64 = 0.790_569_415_042_094_9; // √(5/8)

/// The least distance (as a fraction of the bounding radius) at which the
/// plane read takes the surface's differences along a principal axis of
/// the body's section: a section narrow along an axis (a plate on edge)
/// still takes the slope across it over a length that the interpolated
/// surface resolves.
const PLANE_READ_LEAST_REACH: f64 = 0.1;

/// A horizontal section across a body's hull (world axes, m): its
/// centroid `(x, z)` and its second moments about it per unit area
/// `(xx, xz, zz)`, m².
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Section {
    pub centroid: [f64; 2],
    pub moments: [f64; 3],
}

/// The horizontal section of the hull of a body at `state` at world height
/// `level` (m), from the moments of its tiles (`tiles`, about `origin` in
/// object axes): by the divergence theorem the section's integral of any
/// function of the horizontal position is `−Σ f(x) A·ŷ` over the hull
/// below it, which the tiles whose centres lie below `level` add from
/// their moments, each run of consecutive ones from two running sums (a
/// tile the level cuts is taken whole or not at all, by its centre: an
/// error of the order of a tile's size at the section's rim). `None` where the level misses the body or the section
/// is too small a share of the hull below it to trust (a body wholly under
/// water, whose hull closes).
pub(crate) fn section(
    origin: Point3<f64>,
    tiles: &Tiles<'_>,
    state: &BodyState,
    level: f64,
) -> Option<Section> {
    let rot = state.pose.rotation.to_rotation_matrix().into_inner();
    let row = rot.row(1).transpose();
    // The height of the atlas origin; a tile's centre is `row·c` above it.
    let below = level - (state.pose * origin).y;
    let (centres, sums) = (tiles.centres, tiles.sums);
    if sums.len() != centres.len() + 1 {
        return None;
    }
    // Runs of consecutive tiles below the level, each from its two running
    // sums (taken in place: the run's end added, its start taken away).
    // The tiles are told apart 64 at a time into the bits of a word, and
    // only the bits where a run starts or ends are visited.
    let mut under = soak_bake::MomentSums::default();
    let mut inside = false;
    for (block, chunk) in centres.chunks(64).enumerate() {
        let mut bits = 0u64;
        for (i, c) in chunk.iter().enumerate() {
            bits |= u64::from(row.dot(c) < below) << i;
        }
        let mut changes = (bits ^ ((bits << 1) | u64::from(inside))) & (u64::MAX >> (64 - chunk.len()));
        while changes != 0 {
            let i = changes.trailing_zeros() as usize;
            let k = 64 * block + i;
            if bits >> i & 1 == 1 {
                under -= &sums[k];
            } else {
                under += &sums[k];
            }
            changes &= changes - 1;
        }
        inside = bits >> (chunk.len() - 1) & 1 == 1;
    }
    if inside {
        under += &sums[centres.len()];
    }
    // The world's up in object axes is `row`: −Σ (A·up) [1, x, x xᵀ].
    let area = -row.dot(&under.s0);
    if area.is_nan() || area <= 1e-3 * under.area {
        return None;
    }
    let first = -(under.s1.transpose() * row) / area;
    let s2 = &under.s2;
    let second = -(s2[0] * row.x + s2[1] * row.y + s2[2] * row.z) / area - first * first.transpose();
    let centroid = state.pose * (origin + first);
    let world = rot * second * rot.transpose();
    Some(Section {
        centroid: [centroid.x, centroid.z],
        moments: [world[(0, 0)], world[(0, 2)], world[(2, 2)]],
    })
}

/// An atlas' tiles as the plane read's section takes them: their centres
/// and the running sums of their moments ([`Atlas::tile_centres`],
/// [`Atlas::tile_moment_sums`]).
#[derive(Clone, Copy)]
pub(crate) struct Tiles<'a> {
    pub centres: &'a [Vector3<f64>],
    pub sums: &'a [soak_bake::MomentSums],
}

impl<'a> Tiles<'a> {
    /// The tiles of `atlas`.
    pub fn of(atlas: &'a Atlas) -> Self {
        Self {
            centres: atlas.tile_centres(),
            sums: atlas.tile_moment_sums(),
        }
    }
}

/// The water a body read as one plane ([`SeaSampling::Plane`]) sees.
///
/// The surface is probed at the centre of the body's bounding sphere
/// (`origin` in object axes, `radius` in m, at `state`), and the body's
/// horizontal section at that height taken from its tiles' moments
/// (`tiles`, [`section`]). The plane goes through the section's centroid
/// `P` at the mean of the surface over the section, to second order: with
/// the section's principal axes `e₁`, `e₂` and second moments `λ₁`, `λ₂`
/// (per unit area), the heights at `P` and at `P ± ρᵢ eᵢ`
/// (`ρᵢ = √(5 λᵢ / 2)`, at least a tenth of the radius) give
/// `h_P + Σ λᵢ / (2 ρᵢ²) (h₊ + h₋ − 2 h_P)`, the mean over the section of
/// any quadratic surface, and their central differences its slope at `P`.
/// So an upright wall-sided hull (a box, a barge) displaces under the
/// plane what it displaces under a quadratic surface, whatever its
/// waterplane's shape. Where the section is not known (the body wholly
/// above or under the surface there, or no tiles given) the section is
/// taken as the disc of the bounding radius about the centre: the heights
/// at the centre and [`PLANE_READ_REACH`] of the radius away along x and
/// z. The fluid's velocity at the centre (with drag; still water without)
/// is carried as a uniform current; for a body more than
/// [`SeaSampling::PLANE_BELOW`] of the shortest wave across (or on a
/// surface without a shortest wave), with its gradient there too
/// ([`FLOW_GRADIENT_STEP`]), as a current changing linearly over the body
/// ([`crate::FlowPlane`]): over such a body the orbital velocity changes
/// as much as the body moves through the water. `None` where the options
/// read the sea otherwise or the surface is a plane already (or no free
/// surface).
pub(crate) fn plane_around(
    origin: Point3<f64>,
    radius: f64,
    tiles: Option<Tiles<'_>>,
    water: &Water,
    state: &BodyState,
    t: f64,
    options: &HydroOptions,
) -> Result<Option<Water>, HydroError> {
    if !matches!(options.sea, SeaSampling::Plane | SeaSampling::Auto)
        || !matches!(water.surface.kind(t), SurfaceKind::General)
    {
        return Ok(None);
    }
    let surface = read_surface(water, radius, options)?;
    if options.sea.for_body(radius, surface, t) != SeaSampling::Plane {
        return Ok(None);
    }
    let c = state.pose * origin;
    let mut hint = [0.0; 2];
    let (depth, velocity) = surface.probe(&c, t, options.drag.is_some(), &mut hint);
    let centre = c.y + depth;
    let section = tiles
        .filter(|_| radius > 0.0)
        .and_then(|tiles| section(origin, &tiles, state, centre));
    let (at, slope) = if let Some(Section {
        centroid: [px, pz],
        moments: [xx, xz, zz],
    }) = section
    {
        // The section's principal axes and second moments: the first axis
        // along `(λ₁ − zz, xz)` (either axis where the moments are the same
        // about every one).
        let (mean, half) = (0.5 * (xx + zz), (0.5 * (xx - zz)).hypot(xz));
        let lambda = [(mean + half).max(0.0), (mean - half).max(0.0)];
        let (ex, ez) = (mean + half - zz, xz);
        let norm = ex.hypot(ez);
        let (cos, sin) = if norm > 1e-12 * mean.abs() && norm > 0.0 {
            (ex / norm, ez / norm)
        } else if xx >= zz {
            (1.0, 0.0)
        } else {
            (0.0, 1.0)
        };
        let axes = [[cos, sin], [-sin, cos]];
        let least = PLANE_READ_LEAST_REACH * radius;
        let reach = lambda.map(|l| (2.5 * l).sqrt().max(least));
        let points = [
            [px, pz],
            [px + reach[0] * axes[0][0], pz + reach[0] * axes[0][1]],
            [px - reach[0] * axes[0][0], pz - reach[0] * axes[0][1]],
            [px + reach[1] * axes[1][0], pz + reach[1] * axes[1][1]],
            [px - reach[1] * axes[1][0], pz - reach[1] * axes[1][1]],
        ];
        let (mut h, mut from) = ([0.0; 5], hint);
        surface.heights_near([c.x, c.z], &points, t, &mut from, &mut h);
        let [hp, a1, b1, a2, b2] = h;
        let level = hp
            + lambda[0] / (2.0 * reach[0] * reach[0]) * (a1 + b1 - 2.0 * hp)
            + lambda[1] / (2.0 * reach[1] * reach[1]) * (a2 + b2 - 2.0 * hp);
        let along = [(a1 - b1) / (2.0 * reach[0]), (a2 - b2) / (2.0 * reach[1])];
        let slope = [
            along[0] * axes[0][0] + along[1] * axes[1][0],
            along[0] * axes[0][1] + along[1] * axes[1][1],
        ];
        (Point3::new(px, level, pz), slope)
    } else {
        let rho = PLANE_READ_REACH * radius;
        let (level, slope) = if rho > 0.0 {
            let points = [
                [c.x + rho, c.z],
                [c.x - rho, c.z],
                [c.x, c.z + rho],
                [c.x, c.z - rho],
            ];
            let (mut h, mut from) = ([0.0; 4], hint);
            surface.heights_near([c.x, c.z], &points, t, &mut from, &mut h);
            let [xp, xm, zp, zm] = h;
            (
                (centre + xp + xm + zp + zm) / 5.0,
                [(xp - xm) / (2.0 * rho), (zp - zm) / (2.0 * rho)],
            )
        } else {
            (centre, surface.slope(c.x, c.z, t, &hint))
        };
        (Point3::new(c.x, level, c.z), slope)
    };
    let plane =
        crate::water::Plane::tilted(at, Vector3::new(-slope[0], 1.0, -slope[1]))?.with_current(velocity);
    let small = surface
        .sampling_length(t)
        .is_some_and(|shortest| 2.0 * radius <= SeaSampling::PLANE_BELOW * shortest);
    if options.drag.is_none() || small {
        return Ok(Some(water.under(plane)));
    }
    // The velocity's derivatives at the centre by central differences,
    // each point read under the centre's surface height.
    let h = FLOW_GRADIENT_STEP * radius.max(f64::MIN_POSITIVE);
    let mut gradient = nalgebra::Matrix3::zeros();
    for j in 0..3 {
        let mut d = Vector3::zeros();
        d[j] = h;
        let up = surface.velocity_under(&(c + d), t, centre, &hint);
        let down = surface.velocity_under(&(c - d), t, centre, &hint);
        gradient.set_column(j, &((up - down) / (2.0 * h)));
    }
    // A uniform current (a height field's) stays one.
    if !gradient.iter().all(|g| g.is_finite()) || gradient.iter().all(|g| *g == 0.0) {
        return Ok(Some(water.under(plane)));
    }
    Ok(Some(water.under(plane.with_gradient(gradient, c)?)))
}

/// The step of the central differences that give a plane read's current
/// its gradient ([`plane_around`]), as a fraction of the body's bounding
/// radius: small, for the derivatives at the centre.
pub(crate) const FLOW_GRADIENT_STEP: f64 = 1e-3;

/// [`plane_around`] for a body of atlas `atlas`: about its bounding
/// sphere, over its own section.
pub(crate) fn plane_of(
    atlas: &Atlas,
    water: &Water,
    state: &BodyState,
    t: f64,
    options: &HydroOptions,
) -> Result<Option<Water>, HydroError> {
    let tiles = Some(Tiles::of(atlas));
    plane_around(
        atlas.origin(),
        atlas.bounding_radius(),
        tiles,
        water,
        state,
        t,
        options,
    )
}

/// The water with its surface sampled once around a body at `state` (or
/// read as one plane over it, [`SeaSampling::Plane`]), for evaluations of
/// that body at time `t` (s) near that pose (an implicit solve that shifts
/// it vertically): `None` when [`HydroOptions::sea`] or the surface asks
/// for the exact read (see [`SeaSampling`]); evaluate on `water` itself
/// then. [`evaluate`] on the returned water reads the patch (or the
/// plane) and samples nothing.
pub fn sampled_water(
    atlas: &Atlas,
    water: &Water,
    state: &BodyState,
    t: f64,
    options: &HydroOptions,
) -> Result<Option<Water>, HydroError> {
    water.validate()?;
    state.check()?;
    read_water_around(
        atlas.origin(),
        atlas.bounding_radius(),
        Some(Tiles::of(atlas)),
        water,
        state,
        t,
        options,
    )
}

/// [`sampled_water`] for a body known by its atlas origin (object frame,
/// m) and the radius of a sphere about it that holds every texel (m): the
/// sea sampled over its footprint ([`SeaSampling::PerWavelength`]) or read
/// as one plane over it ([`SeaSampling::Plane`]); `None` to read the water
/// as it is.
pub(crate) fn read_water_around(
    origin: Point3<f64>,
    radius: f64,
    tiles: Option<Tiles<'_>>,
    water: &Water,
    state: &BodyState,
    t: f64,
    options: &HydroOptions,
) -> Result<Option<Water>, HydroError> {
    if let Some(plane) = plane_around(origin, radius, tiles, water, state, t, options)? {
        return Ok(Some(plane));
    }
    Ok(sample_patch_around(origin, radius, water, state, t, options)?.map(|patch| water.under(patch)))
}

/// Drag sums over the submerged texels of `range`.
///
/// Under planar water with a uniform current the texels add to the
/// symmetric sums of [`DragAcc`] in object axes, turned into the system
/// once; elsewhere each texel adds its own (with the fluid's velocity
/// where it is).
pub(crate) fn drag_sums(
    atlas: &Atlas,
    water: &Water,
    state: &BodyState,
    frame: &Frame,
    drag: &Drag,
    t: f64,
    range: std::ops::Range<usize>,
) -> DragSums {
    let start = range.start;
    if let (Some((alpha, beta, _)), Some(u)) = (frame.local_plane, uniform_velocity(water)) {
        let c = frame.rot.transpose() * (frame.com - frame.ow);
        let p = LocalDrag::new(
            drag,
            water.density,
            alpha,
            &beta,
            &frame.rot,
            &c,
            &state.linear_velocity,
            &state.angular_velocity,
            &u,
        );
        let acc = chunked_sum(range.len(), DragAcc::default(), |r| {
            let mut acc = DragAcc::default();
            add_drag_texels(
                &mut acc,
                atlas,
                r.start + start..r.end + start,
                &p,
                Added::default(),
            );
            acc
        });
        return acc.system(&frame.rot, &c, &u);
    }
    chunked_sum(range.len(), TexelDrag::default(), |r| {
        let mut s = TexelDrag::default();
        for i in r.start + start..r.end + start {
            let (x, a) = texel(atlas, i);
            let rr = frame.rot * x;
            let p = frame.ow + rr;
            let d = frame.depth(water, &p, t);
            if d > 0.0 {
                let rc = p - frame.com;
                let u = water.surface.velocity(&Point3::from(p), t);
                let v = state.linear_velocity + state.angular_velocity.cross(&rc) - u;
                s.add(drag, water.density, &rc, &(frame.rot * a), &v, &u);
            }
        }
        s
    })
    .sums()
}

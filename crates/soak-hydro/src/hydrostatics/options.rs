//! What an evaluation computes: the buoyancy model, the drag coefficients
//! and the step over which drag is integrated.

use serde::{Deserialize, Serialize};

/// Which buoyancy force is reported as [`HydroForces::buoyancy`](crate::HydroForces::buoyancy).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum BuoyancyMode {
    /// `ρ g V_s` straight up at the centre of buoyancy (the thesis' model).
    /// Where the surface over a floating body is not flat, its torque also
    /// takes the slope's part, so that force and torque together are the
    /// derivative of the water's potential and a body rocking over waves
    /// or a step neither gains nor loses energy by it; there is still no
    /// sideways force (no drift).
    #[default]
    Archimedes,
    /// Sum of hydrostatic pressure forces `−ρ g d_i A_i` and their torques.
    Pressure,
    /// No buoyancy.
    Off,
}

/// Drag coefficients.
///
/// [`Drag::default()`] is `C_d = 1.0` (a flat plate broadside on: bluff
/// hulls and crates) with no skin friction (`linear = 0.0`); a buoy or a
/// ball is nearer `C_d = 0.5`, and skin friction of some tens of N·s/m per
/// m² damps the slow drift that quadratic drag barely resists.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct Drag {
    /// Quadratic pressure-drag coefficient `C_d` (dimensionless); 1.0 is a
    /// flat plate, about 0.5 a sphere.
    pub coefficient: f64,
    /// Linear skin friction, N·s/m per m² of wetted surface, on the
    /// tangential relative velocity.
    #[serde(default)]
    pub linear: f64,
}

impl Default for Drag {
    /// `C_d = 1.0`, no skin friction (see [`Drag`]).
    fn default() -> Self {
        Self {
            coefficient: 1.0,
            linear: 0.0,
        }
    }
}

/// What to compute.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct HydroOptions {
    /// Buoyancy model.
    pub buoyancy: BuoyancyMode,
    /// Drag, if any.
    pub drag: Option<Drag>,
    /// Time step over which drag is integrated implicitly, s. Zero reports
    /// the explicit drag force of the current velocity.
    pub dt: f64,
    /// How a surface that is not a plane is read by the texels: exactly
    /// at every texel, or sampled once per evaluation over the body's
    /// footprint and interpolated.
    #[serde(default)]
    pub sea: SeaSampling,
    /// Which of a sampled sea's waves the body reads: all of them (the
    /// default), or only those long against the body
    /// ([`SeaBand::BodyLengths`]).
    #[serde(default)]
    pub sea_band: SeaBand,
    /// Where the tiled path ([`TiledAtlas`](crate::TiledAtlas)) reads the
    /// fluid's velocity for the drag under a sampled sea: once per tile
    /// (the default) or at every texel.
    #[serde(default)]
    pub sea_velocity: SeaVelocity,
    /// The body's added mass ([`AddedMass`](crate::AddedMass)), if it has
    /// one: the implicit drag solve then moves the body's mass and the
    /// water's it sets moving (the added mass scaled by the submerged
    /// fraction), not the body's alone. `None`: the body's mass alone.
    #[serde(default)]
    pub added_mass: Option<crate::AddedMass>,
}

/// Where the tiled path reads the fluid's velocity for the drag under a
/// sampled sea ([`SeaSampling::PerWavelength`]). Under a plane or in an
/// unbounded fluid the current is the same everywhere and both are the
/// same sums; the per-texel path ([`evaluate`](crate::evaluate)) and the
/// GPU read it at every texel.
///
/// Per tile, the fluid's velocity and its derivatives are read once at a
/// tile's centre and taken to first order over the tile (the trilinear
/// interpolant the per-texel read samples is nearly linear over a few
/// centimetres), so a tile wholly under the waves whose texels all face
/// the flow alike (or all turn from it) takes its drag in closed form from
/// its moments, and the others are summed texel by texel without a
/// velocity read at each; a tile wider than the patch's node spacing (a
/// coarse atlas on short waves) reads it at every texel. The error falls
/// as the square of the tile's size: on the two-wave swell the drag
/// differs from the per-texel read's by at most 2e-4 at 1024² and 6e-3 at
/// 128² (`soak accuracy`'s moving bodies, 16 nodes per wavelength), well
/// within what the sampled sea itself costs: 3e-2–5e-2 between its
/// velocities and the exact inversion's.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum SeaVelocity {
    /// The fluid's velocity once per tile, to first order about its
    /// centre.
    #[default]
    PerTile,
    /// The fluid's velocity at every texel: the reference.
    PerTexel,
}

/// How the texels read a surface that is not a plane (a Gerstner sea).
///
/// The exact read inverts the Gerstner map at every texel (Newton's
/// method over every wave), most of an evaluation's time on a sea. The
/// sampled read inverts it at the nodes of a grid over the body's
/// footprint ([`SurfacePatch`](crate::SurfacePatch)) and every texel reads
/// the bicubic Hermite interpolant, whose error falls as the fourth power
/// of the node spacing. Surfaces that do not report a
/// [`Surface::sampling_length`](crate::Surface::sampling_length) (height
/// fields, your own) are read exactly either way, and so is a body so large
/// against the waves that its patch would need more than
/// [`MAX_PATCH_NODES`](crate::MAX_PATCH_NODES) nodes a side. A body small
/// against the waves may read them as one plane fitted over it
/// ([`SeaSampling::Plane`]), at calm water's cost; the default
/// ([`SeaSampling::Auto`]) reads so the bodies at most an eighth of the
/// shortest wave across and samples the others.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum SeaSampling {
    /// Every texel reads the surface itself: the reference.
    Exact,
    /// Nodes this many per [`Surface::sampling_length`](crate::Surface::sampling_length)
    /// (the shortest wavelength of a Gerstner sea). At 16 (the nodes
    /// [`SeaSampling::Auto`] samples a body with),
    /// the submerged volume and centre of buoyancy of bodies on the
    /// two-wave sea of `buoy_on_waves.toml` are within 1e-5 of their
    /// volume and diagonal of the exact read (`soak accuracy`'s sea rows).
    PerWavelength(f64),
    /// The body reads the sea as one plane fitted over its footprint, the
    /// fluid's velocity at its centre as a uniform current: the planar
    /// path's cost (a calm-water evaluation, six reads of the surface and
    /// a pass over the atlas' tiles), for bodies small against the waves,
    /// where a game wants many of them. The plane goes through the mean
    /// over the body's horizontal section (at the surface's height above
    /// the centre of its bounding sphere, from its tiles' moments) of the
    /// surface's second-order polynomial: read at the section's centroid
    /// and either way along its principal axes, its heights weighted by the
    /// section's second moments, tilted by their central differences (the
    /// slope at the centroid). An upright wall-sided hull then displaces
    /// what it displaces under any quadratic surface, whatever the shape of
    /// its waterplane. A body wholly above or under the surface there
    /// takes the disc of its bounding radius `r` for its section (heights
    /// at the centre and `√(5/8) r` away along x and z). With drag, a body
    /// more than [`SeaSampling::PLANE_BELOW`] of the shortest wave across
    /// (or on a surface without one) also takes the velocity's gradient at
    /// its centre ([`crate::FlowPlane`]): the current changes linearly over
    /// it, as the orbital velocity does over a body that long (on the
    /// two-wave swell, the 1 m box's drag within 19 % of the exact read
    /// where it moves with the water, against 130 % with one current), its
    /// drag summed tile by tile in that current. The plane drops the
    /// surface's higher terms over the hull and the velocity's beyond the
    /// first: `soak accuracy`'s plane rows give what that costs against
    /// the exact read. Any surface that is not a plane is read so, height
    /// fields and surfaces of your own too.
    Plane,
    /// Each body as it is against the waves it reads (the default): one
    /// plane over a body whose bounding diameter is at most
    /// [`SeaSampling::PLANE_BELOW`] of the shortest of them
    /// ([`Surface::sampling_length`](crate::Surface::sampling_length), of
    /// the band the body reads), as [`SeaSampling::Plane`] reads it; the
    /// sea sampled over any other at
    /// [`SeaSampling::DEFAULT_PER_WAVELENGTH`] nodes per shortest wave, as
    /// [`SeaSampling::PerWavelength`] samples it. On the world bench's
    /// JONSWAP sea (its shortest wave 12.5 m) its 1 m box and ball are
    /// read as planes and a 4 m boat is sampled; `soak accuracy`'s plane
    /// rows give what the plane costs such a body against the exact read
    /// (the box: 1.4e-5 of its volume, 3 % of its drag, against 5.6e-6 and
    /// 0.7 % sampled). Surfaces without a shortest wave (height fields,
    /// your own) are read exactly, as the sampled read reads them.
    Auto,
}

/// Which of a sea's waves a body reads where the sea is sampled over its
/// footprint ([`SeaSampling::PerWavelength`]).
///
/// A wave much shorter than a body pushes its hull up under each crest and
/// lets it down under each trough: over the hull its push largely cancels
/// (the net heave force of a wave of length `λ` on a wall-sided body of
/// length `L` is `sinc(π L / λ)` times a short body's, zero at `L = λ`, at
/// most `λ / (π L)` beyond). Reading only the waves at least a few body
/// lengths long keeps what moves the body and samples the surface on a
/// coarser grid: a large body on a spectral sea reads fewer nodes, and
/// more of its tiles take their closed forms.
///
/// The cut-off: with [`SeaBand::BodyLengths`]`(r)` a body of bounding
/// diameter `D` reads every wave at least `r D` long, and the shorter
/// waves down to the longest of them that the surface can drop as a band
/// ([`Surface::band_limited`](crate::Surface::band_limited)): a
/// [`SpectralSurface`](crate::SpectralSurface) drops its modes shorter
/// than `2^L` times its tile's shortest wave, for the largest `L` that
/// keeps every wave of `r D` or longer (so the waves it drops are at
/// least half as long as `r D`'s cut-off and no longer). Other surfaces
/// are read whole. `soak accuracy`'s band rows give the error against the
/// whole sea. The exact read ([`SeaSampling::Exact`]) reads the whole sea
/// whatever this says.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum SeaBand {
    /// Every wave: the reference.
    #[default]
    Full,
    /// Only the waves at least this many times the body's bounding
    /// diameter long are sure to be read (see [`SeaBand`] for which
    /// shorter ones are).
    BodyLengths(f64),
}

impl SeaBand {
    /// The shortest wave the body must read (m), for a body of bounding
    /// radius `radius` (m): `None` for the whole sea.
    ///
    /// # Errors
    /// [`WaterError::Parameter`](crate::WaterError::Parameter)
    /// (`"sea band body lengths"`) when the ratio is not finite and
    /// positive.
    pub fn wavelength(&self, radius: f64) -> Result<Option<f64>, crate::WaterError> {
        match *self {
            Self::Full => Ok(None),
            Self::BodyLengths(r) if r.is_finite() && r > 0.0 => Ok(Some(2.0 * r * radius)),
            Self::BodyLengths(r) => Err(crate::WaterError::Parameter {
                name: "sea band body lengths",
                value: r,
            }),
        }
    }
}

impl SeaSampling {
    /// The sampled read's default: 16 nodes per shortest wavelength.
    pub const DEFAULT_PER_WAVELENGTH: f64 = 16.0;

    /// The largest bounding diameter, as a fraction of the shortest wave
    /// it reads, of a body that [`SeaSampling::Auto`] reads as one plane:
    /// an eighth (over a body that long centred on a crest, the shortest
    /// wave falls by `1 − cos(π/8)`, 8 %, of its amplitude).
    pub const PLANE_BELOW: f64 = 0.125;

    /// How a body of bounding radius `radius` (m) reads `surface` at time
    /// `t` (s): [`SeaSampling::Auto`] made [`SeaSampling::Plane`] or
    /// [`SeaSampling::PerWavelength`] for that body, any other read as it
    /// is.
    pub fn for_body(&self, radius: f64, surface: &dyn crate::Surface, t: f64) -> Self {
        match *self {
            Self::Auto => match surface.sampling_length(t) {
                Some(shortest) if 2.0 * radius <= Self::PLANE_BELOW * shortest => Self::Plane,
                _ => Self::PerWavelength(Self::DEFAULT_PER_WAVELENGTH),
            },
            read => read,
        }
    }

    /// Whether the setting can be read: nodes per wavelength finite and
    /// positive.
    ///
    /// # Errors
    /// [`WaterError::Parameter`](crate::WaterError::Parameter) naming the
    /// nodes per wavelength when they are not.
    pub fn check(&self) -> Result<(), crate::WaterError> {
        match *self {
            Self::PerWavelength(per) if !(per.is_finite() && per > 0.0) => {
                Err(crate::WaterError::Parameter {
                    name: "sea samples per wavelength",
                    value: per,
                })
            }
            _ => Ok(()),
        }
    }
}

impl Default for SeaSampling {
    /// [`SeaSampling::Auto`].
    fn default() -> Self {
        Self::Auto
    }
}

impl Default for HydroOptions {
    fn default() -> Self {
        Self {
            buoyancy: BuoyancyMode::Archimedes,
            drag: None,
            dt: 1.0 / 60.0,
            sea: SeaSampling::default(),
            sea_band: SeaBand::default(),
            sea_velocity: SeaVelocity::default(),
            added_mass: None,
        }
    }
}

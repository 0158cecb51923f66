//! The bodies of a scene: [`BodySpec`], with its [`MassSpec`] and [`ColliderSpec`].

use serde::{Deserialize, Serialize};
use soak_hydro::{BuoyancyMode, Drag};

use super::liquid_graph::{GraphSpec, HoleSpec};
use super::wetting::WettingSpec;

fn default_resolution() -> ResolutionSpec {
    ResolutionSpec::Texels(256)
}

/// A body's atlas side: texels, or `"auto"`, the coarsest side whose
/// buoyancy is within the body's `tolerance` of the exact clipping of its
/// mesh (see [`soak_hydro::bake_to_tolerance`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(untagged)]
pub enum ResolutionSpec {
    /// This many texels a side.
    Texels(u32),
    /// Chosen for the tolerance.
    Auto(Auto),
}

/// The keyword `"auto"`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Auto {
    /// `"auto"`.
    Auto,
}

/// The tolerance of `resolution = "auto"` when the body gives none: a
/// thousandth of its volume (and of its diagonal for the centre of buoyancy).
pub const DEFAULT_TOLERANCE: f64 = 1e-3;

/// How a body's mass is distributed.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(tag = "model", rename_all = "snake_case", deny_unknown_fields)]
pub enum MassSpec {
    /// Uniform solid.
    Solid {
        /// kg/m³
        density: f64,
    },
    /// Mass on the surface (a hollow body).
    Shell {
        /// kg/m²
        areal_density: f64,
    },
    /// Thin walls of a material (an open container's single-sided mesh):
    /// a shell of `density × thickness` kg/m², whose walls take
    /// `area × thickness` of the cavity's room.
    Walls {
        /// kg/m³
        density: f64,
        /// m
        thickness: f64,
    },
}

/// A collider for contacts with other bodies (massless: soak sets the mass).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum ColliderSpec {
    /// No contacts.
    #[default]
    None,
    /// The convex hull of the mesh (over an open mesh's mouth too: a lid
    /// for contacts).
    ConvexHull,
    /// The triangle mesh itself; an open mesh's walls without its caps, so
    /// things fall into an open boat.
    Trimesh,
}

/// One body.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct BodySpec {
    /// Name for reports.
    pub name: String,
    /// Mesh path (relative to the scene file) or `builtin:` name.
    pub mesh: String,
    /// Atlas side, texels, or `"auto"` (see [`ResolutionSpec`]).
    #[serde(default = "default_resolution")]
    pub resolution: ResolutionSpec,
    /// With `resolution = "auto"`: the largest error allowed, as a fraction
    /// of the body's volume (default [`DEFAULT_TOLERANCE`]).
    pub tolerance: Option<f64>,
    /// Generate a physics atlas instead of using the mesh's UVs.
    #[serde(default)]
    pub unwrap: bool,
    /// An open mesh (a bucket, a rowing boat): its rims are capped
    /// ([`soak_bake::cap_openings`]), the closed shape displaces water, and
    /// water flows in and out over the caps into a liquid graph (the
    /// cavity's one compartment unless `graph` gives another).
    #[serde(default)]
    pub open: bool,
    /// Mass model.
    pub mass: MassSpec,
    /// Initial position of the mesh origin, m.
    #[serde(default)]
    pub position: [f64; 3],
    /// Initial rotation, degrees about x, then y, then z.
    #[serde(default)]
    pub rotation_deg: [f64; 3],
    /// Initial velocity, m/s.
    #[serde(default)]
    pub linear_velocity: [f64; 3],
    /// Initial angular velocity, rad/s.
    #[serde(default)]
    pub angular_velocity: [f64; 3],
    /// Buoyancy mode (`archimedes`, `pressure`, `off`).
    #[serde(default)]
    pub buoyancy: BuoyancyMode,
    /// Drag coefficients; no drag when absent.
    pub drag: Option<Drag>,
    /// Added mass: the water the body sets moving when it accelerates,
    /// from the equivalent ellipsoid of its enclosed volume
    /// ([`soak_hydro::AddedMass::of_atlas`]), scaled by the submerged
    /// fraction (see [`crate::Effects::added_mass`]). Off by default.
    #[serde(default)]
    pub added_mass: bool,
    /// Radiation: the waves the body makes as it moves take its energy
    /// away (Cummins' equation with coefficients from a panel method on
    /// its mesh floating at rest in its initial orientation, see
    /// [`crate::Effects::radiation`]), and on a Gerstner sea it takes
    /// linear theory's wave excitation; supersedes `added_mass`. Baked
    /// when the scene is built ([`crate::radiation_settings`]: one to
    /// three seconds per mesh and mass on two cores in a release build),
    /// shared by bodies of one mesh, mass and orientation.
    ///
    /// When absent it is **on for a body that floats on a Gerstner or a
    /// spectral sea** (`[water] kind = "gerstner"` or `"spectrum"`, without
    /// interactive `[waves]`; on a spectral sea the waves' excitation is
    /// the relative-motion approximation of other moving water): a
    /// dynamic body with buoyancy and a closed mesh, without `added_mass`,
    /// `graph`, `open` or impact holes, that the panel method can float
    /// (a body too heavy to float goes without). Buoyancy alone on waves
    /// has no damping: such a body is pumped out of the water. Off
    /// everywhere else (calm water and static height fields pay nothing).
    /// `false` turns it off; `true` asks for it on any water, and a body
    /// that cannot be baked is then an error.
    #[serde(default)]
    pub radiation: Option<bool>,
    /// Slamming: the impact of entering the water (see [`crate::Slamming`]):
    /// `slamming = {}` for the defaults, `slamming = { cap = 0.5 }` to
    /// let one step's impact take at most half the body's downward
    /// momentum. Off when absent.
    pub slamming: Option<crate::Slamming>,
    /// Sum the drag over a second bake of the mesh at this side, texels,
    /// rather than over the body's own atlas (see
    /// [`soak_hydro::DragTexels`]): 64 takes a 1024² body's drag to within
    /// about 1 % for a fraction of its cost. Needs `drag`; the buoyancy
    /// stays the body's own atlas'. Absent: the body's own texels.
    pub drag_resolution: Option<u32>,
    /// Sum the drag over the body's own atlas coarsened by this factor:
    /// each `k × k` block of its texels merged into one drag texel (see
    /// [`soak_hydro::DragTexels::coarsened`]; 4 takes a 128² body's drag
    /// to a 32² grid), made once per atlas and shared by its bodies. Unlike
    /// `drag_resolution`, as few texels as the blocks whatever the mesh's
    /// triangle count. Needs `drag`; not with `drag_resolution`; the
    /// buoyancy stays the body's own atlas'. Absent: the body's own texels.
    pub drag_coarsening: Option<u32>,
    /// How this body reads a sea (`[water] kind = "gerstner"` or
    /// `"spectrum"`), when not as `[water] sampling` says: `"plane"` (one
    /// plane fitted over the body, a calm-water evaluation's cost, for a
    /// body small against the waves), `"exact"`, `{ per_wavelength = n }`
    /// or `"auto"` (see [`crate::Effects::sea`]). Absent: the water's.
    pub sampling: Option<soak_hydro::SeaSampling>,
    /// Contacts.
    #[serde(default)]
    pub collider: ColliderSpec,
    /// A fixed (immovable) body, e.g. a terrain.
    #[serde(default)]
    pub fixed: bool,
    /// Liquid graph inside the body (water that enters through permeable
    /// texels): a graph file relative to the scene, or `{ auto = true }`.
    pub graph: Option<GraphSpec>,
    /// Permeable regions (holes) of the wall; needs `graph` (or `open`).
    #[serde(default)]
    pub permeability: Vec<HoleSpec>,
    /// Liquid inside at the start, m³ (a bucket half full, a boat's bilge
    /// water), poured into the compartments in order (an open mesh's cavity:
    /// from the bottom up); needs `graph` (or `open`).
    pub liquid: Option<f64>,
    /// Holes torn where a hard contact hits the body: `{ impulse = N·s,
    /// radius = m }` (see [`crate::ImpactHoles`]); needs `graph` (or `open`).
    pub impact_holes: Option<crate::ImpactHoles>,
    /// Surface wetting: the body's liquid texture soaks up the water it is
    /// dipped in, dries and diffuses. Off when absent (and then nothing is
    /// allocated for it).
    pub wetting: Option<WettingSpec>,
}

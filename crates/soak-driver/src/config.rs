//! What the generator is configured with: the effects a body takes part in
//! ([`Effects`]: buoyancy, drag, flooding, wetting), the CPU backend ([`Backend`]), what to register
//! ([`BodyDesc`]) and the id a registered body gets ([`SoakId`]).

use std::sync::Arc;

use serde::{Deserialize, Serialize};
use soak_bake::Atlas;
use soak_graph::Flooding;
use soak_hydro::{AddedMass, BuoyancyMode, Drag, DragTexels, MassModel, SeaSampling};
use soak_seakeeping::RadiationModel;
use soak_wet::Wetting;

/// The effects a body takes part in, each `None` when off: buoyancy and
/// drag (evaluated over the atlas' texels every step), flooding (water
/// entering the hull, whose mass the body carries) and wetting (liquid
/// soaking into its surface). The last two hold their evolving state.
/// Effects left off allocate and cost nothing.
///
/// Register a body with its effects through [`BodyDesc`]; the generator
/// keeps them ([`SoakBody::effects`](crate::SoakBody::effects)) and lets
/// them change between steps
/// ([`Driver::set_wetting`](crate::Driver::set_wetting),
/// [`Driver::flooding_mut`](crate::Driver::flooding_mut)).
#[derive(Clone, Debug, Default)]
pub struct Effects {
    /// Buoyancy, and in which mode; `None` for none.
    pub buoyancy: Option<BuoyancyMode>,
    /// Drag, if any.
    pub drag: Option<Drag>,
    /// The texels the drag is summed over, when not the body's own atlas':
    /// a coarser bake of the same mesh ([`DragTexels::bake`], e.g. 64² for
    /// a 1024² body), or the body's atlas coarsened
    /// ([`DragTexels::coarsened`], e.g. by 4: one drag texel per 4 × 4 of
    /// its texels, whatever the mesh's triangle count), shared by the
    /// bodies of one mesh (a set per body is no faster than the body's own
    /// texels: the sets no longer stay in cache). The buoyancy stays
    /// the body's own atlas'. On the CPU backends only: the GPU backend
    /// sums the drag over the body's own texels (there a texel costs
    /// little). `None`: the body's own texels.
    pub drag_texels: Option<Arc<DragTexels>>,
    /// Flooding: a liquid graph behind the hull's permeability, made for
    /// the body's atlas ([`Flooding::for_atlas`]). Each step the liquid
    /// advances by the world's `dt` with the body's pose, and its mass
    /// (`ρ l_i` at the nodes, kg, plus any ballast) is carried by the body
    /// about the common centre of mass. The buoyancy stays the hull's
    /// enclosed volume's: a holed hull sinks once the water inside
    /// outweighs its reserve of buoyancy. Boxed (832 bytes inline): a
    /// body without it carries a pointer's width for it, and a step's
    /// walk over the bodies' records reads fewer cache lines.
    pub flooding: Option<Box<Flooding>>,
    /// Wetting: the body's liquid texture, made for its atlas (e.g.
    /// `Wetting::new(&atlas, Material::wood(), Liquid::water())`). Each
    /// step it absorbs water through the submerged texels, dries in the
    /// generator's environment and diffuses. It changes neither the body's
    /// mass nor its forces. Boxed (800 bytes inline), as
    /// [`Effects::flooding`].
    pub wetting: Option<Box<Wetting>>,
    /// Holes torn by hard contacts (a cannonball, a rock): see
    /// [`ImpactHoles`]. Needs flooding, whose wall takes the holes.
    pub impact_holes: Option<ImpactHoles>,
    /// Added mass: the water a body sets moving when it accelerates
    /// ([`AddedMass`], in the body's axes; [`AddedMass::of_atlas`] gives
    /// the equivalent ellipsoid's), scaled each step by the submerged
    /// fraction and counted implicitly in the step: a bubble rises at no
    /// more than about `2 g`, a floating body heaves with the period of its
    /// mass and the water's. The buoyancy, the drag's implicit solve and
    /// the stiff-step treatment all move the larger mass; the engine is handed
    /// the wrench that gives the body alone the same accelerations
    /// (contacts still see the body's own mass). `None`: the body's mass
    /// alone, and a body lighter than a millionth of the fluid it
    /// displaces is refused ([`SoakError::TooLight`](crate::SoakError::TooLight)).
    /// Boxed: a body without it carries a pointer's width for it.
    pub added_mass: Option<Box<AddedMass>>,
    /// Slamming: the impact of a body entering the water, from the added
    /// mass of its water-plane growing as it goes under (see [`Slamming`]).
    /// `None`: none, and nothing is summed for it.
    pub slamming: Option<Slamming>,
    /// Radiation: the waves a floating body makes as it moves carry its
    /// energy away, and the water it sets moving depends on how fast it
    /// moves ([`RadiationModel`], baked once per mesh and mass and shared
    /// by the bodies of that mesh: `Arc`). Each step the body is given
    /// Cummins' radiation force, `−A∞ ẍ − ∫ K(t − τ) ẋ(τ) dτ` in its
    /// axes at rest turned with it: A∞ counted implicitly like
    /// [`Effects::added_mass`] (which it supersedes: with both, A∞ alone is
    /// counted), the memory from the model's fitted kernel states. Both
    /// are whole while the body displaces at least half its rest volume
    /// and fade linearly to none as it leaves the water.
    ///
    /// This is linear potential flow on top of the nonlinear texel
    /// hydrostatics and Froude–Krylov forces (the usual "weakly nonlinear"
    /// time-domain model): exact for small motions about the rest draft,
    /// an approximation for large ones (a body leaving the water, heeling
    /// far, capsizing), where the coefficients of the rest draft no longer
    /// hold. A body with radiation does not press the interactive waves
    /// ([`Driver::with_waves`](crate::Driver::with_waves)): the waves it
    /// makes are its memory's; it still floats on the waves the others make.
    pub radiation: Option<Arc<RadiationModel>>,
    /// How this body reads a sea (a surface that is not a plane), when not
    /// as the generator's other bodies do
    /// ([`Driver::with_sea_sampling`](crate::Driver::with_sea_sampling)):
    /// a ship sampled over its hull and the flotsam around it each read as
    /// one plane ([`SeaSampling::Plane`]), at close to calm water's cost.
    /// The body's forces are the ones it would have in a generator that
    /// read every body so. `None`: the generator's read.
    pub sea: Option<SeaSampling>,
}

/// Slamming, von Kármán's momentum theory in three dimensions: as a body
/// enters the water, the region where the surface cuts it (its water-plane,
/// summed from the submerged texels: [`soak_hydro::water_plane`]) grows, and
/// so does the water it sets moving, the added mass of that region as a
/// flat plate on a free surface
/// ([`WaterPlane::plate_added_mass`](soak_hydro::WaterPlane::plate_added_mass):
/// `½ π ρ c²` per length for a strip of half-width `c`). Each step the
/// momentum the new added mass takes, `F = (dm/dt) w` upwards at the
/// water-plane's centroid (`w` the downward speed of that point), is
/// applied, and reported with its peak
/// ([`SoakBody::slamming`](crate::SoakBody::slamming)). For a 2-D wedge it
/// is von Kármán's `ρ π V c ċ` per length; Wagner's theory, with the water
/// piled up along the body, gives a wetted width `π/2` wider and more force
/// at small deadrise. The water's own vertical motion (a sea) is not
/// counted.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct Slamming {
    /// The largest share of the body's downward momentum relative to the
    /// water (with its added mass, if it has one) one step's slamming
    /// impulse may take, in `(0, 1]`: at 1 a step's impact can stop the
    /// entry but never throw the body back, at any time step. Default 1.
    pub cap: f64,
}

impl Default for Slamming {
    fn default() -> Self {
        Self { cap: 1.0 }
    }
}

impl Slamming {
    /// Why the settings are invalid, if they are.
    pub fn problem(&self) -> Option<String> {
        (!(self.cap > 0.0 && self.cap <= 1.0)).then(|| format!("cap {} must be in (0, 1]", self.cap))
    }
}

/// The rule that tears a hole where something hits a body hard: after each
/// step, every contact pair of the body's colliders whose impulse over the
/// step (the sum of its contact impulses, N·s) exceeds `impulse` opens
/// every texel within `radius` (m) of the pair's deepest contact point on
/// the body ([`Driver::open_hole`](crate::Driver::open_hole)):
/// water flows through it freely from the next step. A body resting on
/// another presses with `m g Δt` per step, far below a blow's impulse.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ImpactHoles {
    /// The impulse over one step that tears the wall, N·s (> 0).
    pub impulse: f64,
    /// The hole's radius, m (> 0).
    pub radius: f64,
}

impl ImpactHoles {
    /// Why the rule is invalid, if it is.
    pub fn problem(&self) -> Option<String> {
        if !(self.impulse.is_finite() && self.impulse > 0.0) {
            return Some(format!("impulse {} N·s must be finite and > 0", self.impulse));
        }
        if !(self.radius.is_finite() && self.radius > 0.0) {
            return Some(format!("radius {} m must be finite and > 0", self.radius));
        }
        None
    }
}

impl Effects {
    /// Archimedes buoyancy only.
    pub fn buoyancy() -> Self {
        Self {
            buoyancy: Some(BuoyancyMode::Archimedes),
            ..Self::default()
        }
    }

    /// The same effects with drag.
    pub fn with_drag(mut self, drag: Drag) -> Self {
        self.drag = Some(drag);
        self
    }

    /// The same effects with the drag summed over `texels` (a bake of the
    /// body's mesh, or its atlas coarsened; see [`Effects::drag_texels`]).
    ///
    /// # Example
    /// ```
    /// use nalgebra::Isometry3;
    /// use soak_bake::{Atlas, BakeOptions, builtin};
    /// use soak_driver::{BodyDesc, Driver, Effects, FreeBodies, StepParams};
    /// use soak_hydro::{Drag, DragTexels, MassModel, Water};
    ///
    /// let mesh = builtin::sphere(0.5, 48, 24);
    /// let mut engine = FreeBodies::new(9.81);
    /// let handle = engine.insert(Isometry3::identity());
    /// engine.get_mut(handle).unwrap().linear_velocity.x = 1.0;
    /// let mut soak = Driver::new(Water::calm(0.0));
    /// let effects = Effects::buoyancy()
    ///     .with_drag(Drag::default())
    ///     .with_drag_texels(DragTexels::bake(&mesh, 64)?.into());
    /// soak.register(&mut engine, handle, BodyDesc {
    ///     name: "buoy".into(),
    ///     atlas: Atlas::bake(&mesh, BakeOptions::square(512))?.into(),
    ///     mass_model: MassModel::Solid { density: 500.0 },
    ///     effects,
    /// })?;
    /// soak.before_step(&mut engine, &StepParams::new(1.0 / 60.0, 4))?;
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn with_drag_texels(mut self, texels: Arc<DragTexels>) -> Self {
        self.drag_texels = Some(texels);
        self
    }

    /// The same effects with another buoyancy mode.
    pub fn with_mode(mut self, mode: BuoyancyMode) -> Self {
        self.buoyancy = Some(mode);
        self
    }

    /// The same effects with water entering the hull through `flooding`
    /// (made for the body's atlas).
    ///
    /// # Example
    /// ```
    /// use nalgebra::{Isometry3, Point3};
    /// use soak_bake::{Atlas, BakeOptions, builtin};
    /// use soak_driver::{BodyDesc, Driver, Effects, FreeBodies, StepParams};
    /// use soak_graph::{Flooding, FlowOptions, LiquidGraph, Node, Permeability};
    /// use soak_hydro::{MassModel, Water};
    ///
    /// let mut engine = FreeBodies::new(9.81);
    /// let step = StepParams::new(1.0 / 30.0, 4);
    /// let handle = engine.insert(Isometry3::identity());
    /// let atlas = Atlas::bake(&builtin::cuboid(1.0, 1.0, 1.0), BakeOptions::square(32))?;
    /// let mut permeability = Permeability::watertight(&atlas);
    /// permeability.paint(&atlas, Point3::new(0.0, -0.5, 0.0), 0.2, 1e-6)?; // a hole in the bottom
    /// let graph = LiquidGraph::new(vec![Node::new("hold", Point3::origin(), 1.0).with_height(1.0)], vec![])?;
    /// let flooding = Flooding::for_atlas(&atlas, graph, permeability, FlowOptions::default())?;
    /// let mut soak = Driver::new(Water::calm(0.0));
    /// let id = soak.register(&mut engine, handle, BodyDesc {
    ///     name: "box".into(),
    ///     atlas: atlas.into(),
    ///     mass_model: MassModel::Shell { areal_density: 20.0 },
    ///     effects: Effects::buoyancy().with_flooding(flooding),
    /// })?;
    /// for _ in 0..300 {
    ///     soak.before_step(&mut engine, &step)?;
    ///     engine.step(&step);
    ///     soak.after_step(step.dt);
    /// }
    /// // Water came in and the body is heavier by its mass.
    /// let inside = soak.flooding(id).unwrap().inside();
    /// assert!(inside > 0.1);
    /// let mass = soak.body(id).unwrap().mass_properties().mass;
    /// assert!((mass - (120.0 + 1000.0 * inside)).abs() < 1e-6 * mass);
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn with_flooding(mut self, flooding: Flooding) -> Self {
        self.flooding = Some(Box::new(flooding));
        self
    }

    /// The same effects with an added mass ([`Effects::added_mass`]; e.g.
    /// [`AddedMass::of_atlas`] of the body's atlas).
    ///
    /// # Example
    /// ```
    /// use nalgebra::Isometry3;
    /// use soak_bake::{Atlas, BakeOptions, builtin};
    /// use soak_driver::{BodyDesc, Driver, Effects, FreeBodies, StepParams};
    /// use soak_hydro::{AddedMass, MassModel, Water};
    ///
    /// // A hollow sphere of 1 kg/m³, 10 m down: buoyancy alone would fling it
    /// // up at a thousand g, the water it must push aside holds it to 2 g.
    /// let mut engine = FreeBodies::new(9.81);
    /// let handle = engine.insert(Isometry3::translation(0.0, -10.0, 0.0));
    /// let atlas = Atlas::bake(&builtin::sphere(0.5, 48, 24), BakeOptions::square(128))?;
    /// let added = AddedMass::of_atlas(&atlas)?;
    /// let mut soak = Driver::new(Water::calm(0.0));
    /// soak.register(&mut engine, handle, BodyDesc {
    ///     name: "bubble".into(),
    ///     atlas: atlas.into(),
    ///     mass_model: MassModel::Solid { density: 1.0 },
    ///     effects: Effects::buoyancy().with_added_mass(added),
    /// })?;
    /// let step = StepParams::new(1.0 / 60.0, 4);
    /// soak.before_step(&mut engine, &step)?;
    /// engine.step(&step);
    /// let a = engine.get(handle).unwrap().linear_velocity.y / step.dt;
    /// assert!((a / 9.81 - 2.0).abs() < 0.05, "{a} m/s²");
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn with_added_mass(mut self, added: AddedMass) -> Self {
        self.added_mass = Some(Box::new(added));
        self
    }

    /// The same effects with radiation ([`Effects::radiation`]): `model`
    /// baked from the body's mesh with its mass and rest orientation.
    ///
    /// # Example
    /// ```
    /// use std::sync::Arc;
    /// use nalgebra::{Isometry3, UnitQuaternion};
    /// use soak_bake::{Atlas, BakeOptions, builtin};
    /// use soak_driver::{BodyDesc, Driver, Effects, FreeBodies, StepParams};
    /// use soak_hydro::{MassModel, Water};
    /// use soak_seakeeping::{FloatingBody, RadiationModel, RadiationSettings};
    ///
    /// // A buoy of half the water's density, dropped 5 cm below where it floats.
    /// let mesh = builtin::sphere(0.5, 24, 12);
    /// let atlas: Arc<Atlas> = Atlas::bake(&mesh, BakeOptions::square(64))?.into();
    /// let mass_model = MassModel::Solid { density: 500.0 };
    /// let mass = mass_model.mass_properties(&atlas)?;
    /// let settings = RadiationSettings { panels: 120, frequencies: 24, ..RadiationSettings::default() };
    /// let model = RadiationModel::bake(&FloatingBody {
    ///     mesh: &mesh,
    ///     mass: mass.mass,
    ///     center_of_mass: mass.center_of_mass,
    ///     inertia: mass.inertia,
    ///     rotation: UnitQuaternion::identity(),
    /// }, &settings)?;
    /// let mut engine = FreeBodies::new(9.81);
    /// let handle = engine.insert(Isometry3::translation(0.0, -0.05, 0.0));
    /// let mut soak = Driver::new(Water::calm(0.0));
    /// soak.register(&mut engine, handle, BodyDesc {
    ///     name: "buoy".into(),
    ///     atlas,
    ///     mass_model,
    ///     effects: Effects::buoyancy().with_radiation(model.into()),
    /// })?;
    /// let step = StepParams::new(1.0 / 60.0, 4);
    /// for _ in 0..600 {
    ///     soak.before_step(&mut engine, &step)?;
    ///     engine.step(&step);
    ///     soak.after_step(step.dt);
    /// }
    /// // Ten seconds on, the waves it made have taken its bobbing away.
    /// let y = engine.get(handle).unwrap().pose.translation.y;
    /// assert!(y.abs() < 0.005, "{y}");
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn with_radiation(mut self, model: Arc<RadiationModel>) -> Self {
        self.radiation = Some(model);
        self
    }

    /// The same effects reading a sea as `sea` says, whatever the
    /// generator's other bodies do (see [`Effects::sea`]).
    ///
    /// # Example
    /// A ship reads the sea sampled over its hull (the generator's
    /// default), a buoy reads it as one plane:
    /// ```
    /// use soak_driver::Effects;
    /// use soak_hydro::{Drag, SeaSampling};
    ///
    /// let buoy = Effects::buoyancy()
    ///     .with_drag(Drag::default())
    ///     .with_sea_sampling(SeaSampling::Plane);
    /// assert_eq!(buoy.sea, Some(SeaSampling::Plane));
    /// ```
    pub fn with_sea_sampling(mut self, sea: SeaSampling) -> Self {
        self.sea = Some(sea);
        self
    }

    /// The same effects with slamming ([`Slamming`]).
    pub fn with_slamming(mut self, slamming: Slamming) -> Self {
        self.slamming = Some(slamming);
        self
    }

    /// The same effects with holes torn by hard contacts ([`ImpactHoles`];
    /// needs flooding).
    pub fn with_impact_holes(mut self, rule: ImpactHoles) -> Self {
        self.impact_holes = Some(rule);
        self
    }

    /// The same effects with the surface wetting `wetting` (made for the
    /// body's atlas).
    pub fn with_wetting(mut self, wetting: Wetting) -> Self {
        self.wetting = Some(Box::new(wetting));
        self
    }

    /// Whether the body needs hydrostatics (texel sums) at all: buoyancy
    /// in a mode other than [`BuoyancyMode::Off`], drag or slamming.
    pub fn needs_hydrostatics(&self) -> bool {
        self.buoyancy.is_some_and(|m| m != BuoyancyMode::Off)
            || self.drag.is_some()
            || self.slamming.is_some()
    }
}

/// How texel sums are evaluated on the CPU; both give the same answer.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Backend {
    /// Every texel, every step.
    PerTexel,
    /// Closed forms for tiles wholly under planar water (the default).
    #[default]
    Tiled,
    /// All bodies in one GPU batch per step (the `gpu` feature; see
    /// `Driver::with_gpu`); the tiled path stands by on the CPU.
    Gpu,
}

/// Identifies a body registered with a [`Driver`](crate::Driver).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize, Deserialize)]
pub struct SoakId(pub usize);

/// What to register: a mesh's atlas, its mass model and its effects.
#[derive(Clone, Debug)]
pub struct BodyDesc {
    /// A name for reports and log lines.
    pub name: String,
    /// The baked atlas of the body's mesh, in the rigid body's local frame,
    /// shared: bodies registered with clones of one `Arc` (a hundred crates
    /// of one mesh) share its texels and its tiles, in memory and in the
    /// cache (`Arc::new(atlas)`, or `atlas.into()`).
    pub atlas: Arc<Atlas>,
    /// How the body's mass is distributed.
    pub mass_model: MassModel,
    /// The effects it takes part in.
    pub effects: Effects,
}

//! Frames of a scene file's simulation: [`SceneRenderer`] draws a
//! [`Simulation`] with soak-shade's renderer (shared by `soak render`, the
//! demo's stills and the viewer).

use std::sync::Arc;

use nalgebra::{Isometry3, Point3, Vector3};
use soak_bake::Mesh;
use soak_hydro::{Gerstner, SpectralSurface};
use soak_rapier::scene::{LoadedScene, WaterKind};
use soak_rapier::{Simulation, convert};
use soak_shade::render::{
    Albedo, Arrow, Camera, DebugView, DirectionalLight, LiquidImage, RenderObject, RenderScene, RenderWater,
    Renderer, adapter_label, headless_device, liquid_image_from_texels, speckled, wood_planks,
};
use soak_shade::{Gamma, Liquid, WetMaterial};

use crate::error::ViewError;

/// What the frames show.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum View {
    /// The shaded scene.
    #[default]
    Shaded,
    /// Liquid saturation in pseudo-colour (blue dry, red saturated).
    Liquid,
    /// Compartments of the liquid graph (nearest node per triangle) with its pipes; each triangle apart for a body without a graph.
    Segments,
    /// World-space normals as colours.
    Normals,
}

impl From<View> for DebugView {
    fn from(v: View) -> Self {
        match v {
            View::Shaded => DebugView::Shaded,
            View::Liquid => DebugView::Liquid,
            View::Segments => DebugView::Segments,
            View::Normals => DebugView::Normals,
        }
    }
}

/// What a frame shows and how it is framed.
#[derive(Clone, Debug, PartialEq)]
pub struct FrameOptions {
    /// Width, height in pixels.
    pub size: (u32, u32),
    /// Debug view.
    pub view: View,
    /// Force arrows.
    pub forces: bool,
    /// Camera eye and target; `None` frames the bodies.
    pub eye: Option<Point3<f64>>,
    /// See [`FrameOptions::eye`].
    pub target: Option<Point3<f64>>,
}

/// A sea that moves, drawn as it is at each frame's time.
enum Sea {
    /// A sum of Gerstner waves.
    Gerstner(Gerstner),
    /// A spectral sea, its tile evaluated at each frame's time (the last
    /// few times kept, as the simulation keeps them).
    Spectral(Arc<SpectralSurface>),
}

impl Sea {
    /// The mean level, m.
    fn level(&self) -> f64 {
        match self {
            Self::Gerstner(sea) => sea.level,
            Self::Spectral(surface) => surface.sea().level,
        }
    }

    /// The water drawn at time `t` (s).
    fn water(&self, t: f64) -> RenderWater {
        match self {
            Self::Gerstner(sea) => RenderWater::gerstner(sea.clone(), t),
            Self::Spectral(surface) => RenderWater::spectral(surface.fields(t)),
        }
    }
}

/// Draws a [`Simulation`] built from a scene file: every body's mesh at its
/// pose with its liquid texture (when the body is wet), the water surface,
/// the sun and the sky; the debug views and force arrows of [`FrameOptions`].
pub struct SceneRenderer {
    renderer: Renderer,
    meshes: Vec<Arc<Mesh>>,
    albedos: Vec<Albedo>,
    sea: Option<Sea>,
    level: Option<f64>,
    options: FrameOptions,
    radius: Vec<f64>,
    /// Per body, the liquid-graph node nearest each triangle (segments view).
    segments: Vec<Option<Arc<Vec<u32>>>>,
    adapter: String,
    /// How long a wet body's liquid texture is drawn before it is made
    /// again from its wetting state (`None`: every frame).
    liquid_every: Option<std::time::Duration>,
    /// Per body, its last liquid texture and when it was made.
    liquids: Vec<Option<(std::time::Instant, Arc<LiquidImage>)>>,
}

impl SceneRenderer {
    /// Loads the scene's meshes (as the simulation did) and opens a headless device.
    ///
    /// # Errors
    /// No GPU adapter, a mesh that does not load, a sea that is not valid,
    /// a renderer that cannot be made.
    pub fn new(loaded: &LoadedScene, options: FrameOptions) -> Result<Self, ViewError> {
        let (device, queue, info) = headless_device()?;
        Self::with_device(loaded, options, &device, &queue, adapter_label(&info))
    }

    /// [`SceneRenderer::new`] on a device of the caller's (a window's),
    /// `adapter` naming it for reports.
    ///
    /// # Errors
    /// As [`SceneRenderer::new`], but for the adapter.
    pub fn with_device(
        loaded: &LoadedScene,
        options: FrameOptions,
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        adapter: String,
    ) -> Result<Self, ViewError> {
        let mut meshes = Vec::new();
        let mut albedos = Vec::new();
        for (i, b) in loaded.scene.bodies.iter().enumerate() {
            albedos.push(albedo_for(&b.name, &b.mesh, i, b.fixed));
            meshes.push(Arc::new(loaded.body_mesh(i)?));
        }
        let w = &loaded.scene.water;
        let g = Vector3::from(loaded.scene.gravity).norm().max(1e-9);
        let (sea, level) = match w.kind {
            WaterKind::Plane => (None, Some(w.level.unwrap_or(0.0))),
            WaterKind::Gerstner => (
                Some(Sea::Gerstner(
                    Gerstner::new(w.level.unwrap_or(0.0), w.waves.clone().unwrap_or_default(), g)
                        .map_err(soak_hydro::HydroError::from)?,
                )),
                None,
            ),
            WaterKind::Spectrum => (
                Some(Sea::Spectral(Arc::new(SpectralSurface::new(
                    w.spectral_sea(g).map_err(soak_hydro::HydroError::from)?,
                )))),
                None,
            ),
            // A height field is drawn as its mean level; air has no surface.
            WaterKind::HeightField => (None, w.level.or(Some(0.0))),
            WaterKind::Air => (None, None),
        };
        Self::assemble((device, queue), meshes, albedos, (sea, level), options, adapter)
    }

    /// Frames of a world of your own ([`Simulation::from_parts`]): `meshes`
    /// holds the mesh of each of `sim.bodies` (its local frame, the frame
    /// its atlas was baked in), the water drawn is the generator's (a
    /// plane at its level, a Gerstner or spectral sea as it moves; other surfaces as a
    /// plane at their level at the origin at time 0), on a device of the
    /// caller's.
    ///
    /// # Errors
    /// [`ViewError::Meshes`] when there is not one mesh per body; those of
    /// [`Renderer::new`].
    pub fn for_world(
        sim: &Simulation,
        meshes: Vec<Arc<Mesh>>,
        options: FrameOptions,
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        adapter: String,
    ) -> Result<Self, ViewError> {
        if meshes.len() != sim.bodies.len() {
            return Err(ViewError::Meshes {
                bodies: sim.bodies.len(),
                meshes: meshes.len(),
            });
        }
        let albedos = sim
            .bodies
            .iter()
            .enumerate()
            .map(|(i, b)| albedo_for(&b.name, "", i, b.id.is_none()))
            .collect();
        let water = sim.soak.water();
        let any = water.surface.as_any();
        let sea = any
            .and_then(|a| a.downcast_ref::<Gerstner>())
            .map(|sea| Sea::Gerstner(sea.clone()))
            .or_else(|| {
                any.and_then(|a| a.downcast_ref::<SpectralSurface>())
                    .map(|surface| Sea::Spectral(Arc::new(SpectralSurface::new(surface.sea().clone()))))
            });
        let level = match (&sea, water.surface.kind(0.0)) {
            (Some(_), _) | (None, soak_hydro::SurfaceKind::Unbounded) => None,
            (None, soak_hydro::SurfaceKind::Plane { normal, offset }) => Some(offset / normal.y.max(1e-9)),
            (None, soak_hydro::SurfaceKind::General) => Some(water.surface.height(0.0, 0.0, 0.0)),
        };
        Self::assemble((device, queue), meshes, albedos, (sea, level), options, adapter)
    }

    /// The renderer of `meshes` with their looks over the water drawn, on
    /// `device`.
    fn assemble(
        (device, queue): (&wgpu::Device, &wgpu::Queue),
        meshes: Vec<Arc<Mesh>>,
        albedos: Vec<Albedo>,
        (sea, level): (Option<Sea>, Option<f64>),
        options: FrameOptions,
        adapter: String,
    ) -> Result<Self, ViewError> {
        let renderer = Renderer::new(device, queue, options.size.0, options.size.1)?;
        let radius = meshes
            .iter()
            .map(|m| {
                m.positions
                    .iter()
                    .map(|p| p.coords.norm())
                    .fold(0.0_f64, f64::max)
            })
            .collect();
        let n = meshes.len();
        Ok(Self {
            renderer,
            meshes,
            albedos,
            sea,
            level,
            options,
            segments: vec![None; n],
            radius,
            adapter,
            liquid_every: None,
            liquids: vec![None; n],
        })
    }

    /// Makes a wet body's liquid texture again from its wetting state at
    /// most every `every` (wall clock), drawing the last one in between:
    /// for a viewer, whose frames follow one another faster than liquid
    /// soaks in, and for which a 1024² texture made every frame would cost
    /// as much as the frame. `None` (the default) makes it every frame.
    pub fn set_liquid_every(&mut self, every: Option<std::time::Duration>) {
        self.liquid_every = every;
    }

    /// The options frames are made with.
    pub fn options(&self) -> &FrameOptions {
        &self.options
    }

    /// Changes what frames show (view, arrows, size, camera).
    ///
    /// # Errors
    /// A size the renderer cannot take.
    pub fn set_options(&mut self, options: FrameOptions) -> Result<(), ViewError> {
        self.renderer.resize(options.size.0, options.size.1)?;
        if options.view != View::Segments {
            // Kept: the compartments do not change; only drawn in that view.
        }
        self.options = options;
        Ok(())
    }

    /// The radius of a sphere about body `i`'s origin that holds its mesh, m.
    pub fn radius(&self, i: usize) -> f64 {
        self.radius.get(i).copied().unwrap_or(0.0)
    }

    /// The adapter's name (a software adapter's timings are CPU timings).
    pub fn adapter(&self) -> &str {
        &self.adapter
    }

    /// The frame for the simulation's current state.
    ///
    /// # Errors
    /// Those of [`Renderer::render`].
    pub fn frame(&mut self, sim: &Simulation) -> Result<image::RgbaImage, ViewError> {
        let scene = self.scene(sim);
        self.render(&scene)
    }

    /// Renders `scene` (one of [`SceneRenderer::scene`], its camera moved
    /// perhaps) at the options' size.
    ///
    /// # Errors
    /// Those of [`Renderer::render`].
    pub fn render(&mut self, scene: &RenderScene) -> Result<image::RgbaImage, ViewError> {
        Ok(self.renderer.render(scene)?)
    }

    /// What the frame of the simulation's current state draws, its camera
    /// the options' (or framing the bodies).
    pub fn scene(&mut self, sim: &Simulation) -> RenderScene {
        let t = sim.time();
        let mut objects = Vec::new();
        let mut arrows = Vec::new();
        let mut pipes = Vec::new();
        let mut lo = Point3::new(f64::INFINITY, f64::INFINITY, f64::INFINITY);
        let mut hi = -lo;
        let mut weight_scale = 0.0_f64;
        for (i, b) in sim.bodies.iter().enumerate() {
            let Some(rb) = sim.world.bodies.get(b.handle) else {
                continue;
            };
            let pose: Isometry3<f64> = convert::pose(rb.position());
            let r = self.radius[i];
            // Fixed terrain does not decide the framing.
            if b.id.is_some() || sim.bodies.len() == 1 {
                let c = pose.translation.vector;
                lo = lo.inf(&Point3::from(c.add_scalar(-r)));
                hi = hi.sup(&Point3::from(c.add_scalar(r)));
            }
            let mut object = RenderObject::new(self.meshes[i].clone(), pose)
                .with_name(b.name.clone())
                .with_albedo(self.albedos[i].clone())
                .with_material(WetMaterial {
                    liquid: Liquid::water(),
                    gamma: Gamma::Arctan { roughness: 8.0 },
                });
            // A wet body shows its liquid texture (saturation h / h_max).
            if let Some(id) = b.id
                && let (Some(body), Some(wetting)) = (sim.soak.body(id), sim.soak.wetting(id))
            {
                let fresh = match (&self.liquids[i], self.liquid_every) {
                    (Some((made, image)), Some(every)) if made.elapsed() < every => Some(Arc::clone(image)),
                    _ => None,
                };
                let image = fresh.unwrap_or_else(|| {
                    let atlas = body.atlas();
                    let saturation = wetting.material().saturation;
                    let values: Vec<f32> = wetting
                        .liquid()
                        .iter()
                        .map(|h| (h / saturation).clamp(0.0, 1.0) as f32)
                        .collect();
                    let image = Arc::new(liquid_image_from_texels(
                        atlas.width(),
                        atlas.height(),
                        atlas.texels(),
                        &values,
                        3,
                    ));
                    self.liquids[i] = Some((std::time::Instant::now(), Arc::clone(&image)));
                    image
                });
                object = object.with_liquid(image);
            }
            // An open container shows the liquid it holds, at its
            // compartment's level (the highest, with several).
            if !self.meshes[i].openings.is_empty()
                && let Some(id) = b.id
                && let Some(flooding) = sim.soak.flooding(id)
            {
                let level = flooding
                    .graph()
                    .nodes()
                    .filter(|n| n.liquid > 0.0)
                    .map(|n| n.head_at((pose * n.position).y))
                    .fold(f64::NEG_INFINITY, f64::max);
                if level.is_finite() {
                    object = object.with_inner_water(level);
                }
            }
            // The segments view colours a body with a liquid graph by
            // compartment (the node nearest each triangle) and draws the
            // graph's pipes between the nodes.
            if self.options.view == View::Segments
                && let Some(id) = b.id
                && let Some(flooding) = sim.soak.flooding(id)
            {
                let graph = flooding.graph();
                let nodes: Vec<Point3<f64>> = graph.nodes().map(|n| n.position).collect();
                let segments = self.segments[i]
                    .get_or_insert_with(|| Arc::new(nearest_node_per_triangle(&self.meshes[i], &nodes)));
                object.segments = Some(segments.clone());
                for (a, c, _) in graph.edges() {
                    let (pa, pc) = (pose * nodes[a], pose * nodes[c]);
                    pipes.push(Arrow::new(pa, pc - pa, [0.95, 0.95, 0.95]).with_radius(0.02 * r));
                }
            }
            objects.push(object);
            if let (true, Some(id)) = (self.options.forces, b.id)
                && let Some(body) = sim.soak.body(id)
            {
                let mass = body.mass_properties();
                let g = sim.soak.water().gravity;
                let weight = mass.mass * g;
                weight_scale = weight_scale.max(weight);
                let com = pose * mass.center_of_mass;
                arrows.push((com, Vector3::new(0.0, -weight, 0.0), *body.forces(), r));
            }
        }
        if !lo.x.is_finite() {
            lo = Point3::new(-1.0, -1.0, -1.0);
            hi = Point3::new(1.0, 1.0, 1.0);
        }
        let centre = nalgebra::center(&lo, &hi);
        let size = (hi - lo).norm().max(0.1);
        let target = self.options.target.unwrap_or(centre);
        let eye = self.options.eye.unwrap_or_else(|| {
            let mut eye = target + Vector3::new(0.62, 0.34, 1.0).normalize() * (0.9 * size + 0.5);
            // Keep the eye above the water: a sunken body is seen through it.
            if let Some(level) = self.level.or(self.sea.as_ref().map(Sea::level)) {
                eye.y = eye.y.max(level + 0.3 * size + 0.5);
            }
            eye
        });
        let mut scene = RenderScene::new(Camera::perspective(eye, target, 40.0));
        scene.light = DirectionalLight::from_angles(38.0, 60.0, [2.7, 2.5, 2.3]);
        scene.water = match (&self.sea, self.level) {
            (Some(sea), _) => Some(sea.water(t)),
            (None, Some(level)) => Some(RenderWater::plane(level)),
            (None, None) => None,
        };
        // The waves the bodies make, on the water.
        if let Some(waves) = sim.soak.waves() {
            scene.water = scene.water.take().map(|w| w.with_waves(waves.snapshot()));
        }
        scene.objects = objects;
        scene.view = self.options.view.into();
        scene.arrows.extend(pipes);
        if weight_scale > 0.0 {
            let metres_per_newton = 0.3 * size / weight_scale;
            for (com, weight, forces, r) in arrows {
                let radius = (0.015 * size).max(0.004 * r);
                scene
                    .arrows
                    .push(Arrow::weight(com, weight, metres_per_newton).with_radius(radius));
                if forces.submerged_volume > 0.0 {
                    scene.arrows.push(
                        Arrow::buoyancy(
                            forces.center_of_buoyancy,
                            forces.buoyancy.force,
                            metres_per_newton,
                        )
                        .with_radius(radius),
                    );
                }
            }
        }
        scene
    }
}

/// For each triangle of `mesh`, the index of the node nearest its centroid
/// (object space): the compartments of a liquid graph drawn on its mesh.
fn nearest_node_per_triangle(mesh: &Mesh, nodes: &[Point3<f64>]) -> Vec<u32> {
    mesh.triangles
        .iter()
        .map(|t| {
            let c = Point3::from(
                (mesh.positions[t[0] as usize].coords
                    + mesh.positions[t[1] as usize].coords
                    + mesh.positions[t[2] as usize].coords)
                    / 3.0,
            );
            nodes
                .iter()
                .enumerate()
                .map(|(k, n)| (k, (n - c).norm_squared()))
                .min_by(|x, y| x.1.total_cmp(&y.1))
                .map_or(0, |(k, _)| k as u32)
        })
        .collect()
}

/// A look for a body: wood for boats and crates, sand for terrain, bright
/// colours for the rest.
fn albedo_for(name: &str, mesh: &str, index: usize, fixed: bool) -> Albedo {
    let n = format!("{name} {mesh}").to_lowercase();
    if n.contains("boat") || n.contains("crate") || n.contains("hull") || n.contains("wood") {
        Albedo::texture(wood_planks(512, 512, 14, [0.62, 0.40, 0.22], 7 + index as u64))
    } else if fixed || n.contains("beach") || n.contains("sand") || n.contains("terrain") {
        Albedo::texture(speckled(
            512,
            512,
            [0.76, 0.66, 0.47],
            0.08,
            24.0,
            11 + index as u64,
        ))
    } else {
        const PALETTE: [[f64; 3]; 5] = [
            [0.75, 0.18, 0.08],
            [0.85, 0.62, 0.10],
            [0.20, 0.45, 0.75],
            [0.35, 0.62, 0.25],
            [0.70, 0.70, 0.68],
        ];
        Albedo::Constant(PALETTE[index % PALETTE.len()])
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn each_triangle_goes_to_the_node_nearest_its_centroid() {
        let mesh = soak_bake::builtin::parse("builtin:box:2x1x1").expect("builtin");
        let nodes = [Point3::new(-0.5, 0.0, 0.0), Point3::new(0.5, 0.0, 0.0)];
        let segments = nearest_node_per_triangle(&mesh, &nodes);
        assert_eq!(segments.len(), mesh.triangles.len());
        for (t, &s) in mesh.triangles.iter().zip(&segments) {
            let x: f64 = t.iter().map(|&v| mesh.positions[v as usize].x).sum::<f64>() / 3.0;
            if x.abs() > 1e-9 {
                assert_eq!(s, u32::from(x > 0.0), "triangle with centroid x = {x}");
            }
        }
        // Both ends of the box are there.
        assert!(segments.contains(&0) && segments.contains(&1));
        assert!(nearest_node_per_triangle(&mesh, &[]).iter().all(|&s| s == 0));
    }
}

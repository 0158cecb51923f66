//! `soak render`: frames of a scene file, shaded with the wet-surface optics
//! of `soak-shade` on an offscreen wgpu renderer.
//!
//! The scene is simulated up to the requested step and drawn: every body's
//! mesh at its pose with its liquid texture (when the body is wet), the
//! water surface, the sun and the sky; debug views show the liquid in
//! pseudo-colour, the compartments of a body's liquid graph (each triangle
//! coloured by its nearest node, the graph's pipes drawn between nodes; each
//! triangle apart for a body without one), or the normals, and `--forces`
//! draws weight (red, at the centre of mass) and buoyancy (green, at the
//! centre of buoyancy) as in the thesis' Fig. 7.3.

use std::path::{Path, PathBuf};
use std::sync::Arc;
use std::time::Instant;

use anyhow::{Context, Result, bail};
use nalgebra::{Isometry3, Point3, Vector3};
use soak_bake::Mesh;
use soak_hydro::Gerstner;
use soak_rapier::scene::{LoadedScene, WaterKind};
use soak_rapier::{Simulation, convert};
use soak_shade::render::{
    Albedo, Arrow, Camera, DebugView, DirectionalLight, RenderObject, RenderScene, RenderWater, Renderer,
    adapter_label, headless_device, liquid_image_from_texels, speckled, wood_planks,
};
use soak_shade::{Gamma, Liquid, WetMaterial};

/// What the frames show.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, clap::ValueEnum)]
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

/// `soak render SCENE.toml [--frame N] [--every K]`
#[derive(clap::Args, Debug)]
pub struct Args {
    /// Scene file (TOML).
    pub scene: PathBuf,
    /// Step to render (0 is the initial state); default: the scene's last step.
    #[arg(long)]
    pub frame: Option<u64>,
    /// Also write every K-th step before `--frame` as a numbered sequence
    /// (`frame_000000.png`, ...).
    #[arg(long)]
    pub every: Option<u64>,
    /// Also encode the frames written as a video (H.264 in MP4, at the
    /// simulation's pace) with the `ffmpeg` found on the `PATH`; needs
    /// `--every`.
    #[arg(long, value_name = "OUT.mp4", requires = "every")]
    pub video: Option<PathBuf>,
    /// Image width, pixels.
    #[arg(long, default_value_t = 640)]
    pub width: u32,
    /// Image height, pixels.
    #[arg(long, default_value_t = 360)]
    pub height: u32,
    /// What the image shows.
    #[arg(long, value_enum, default_value_t = View::Shaded)]
    pub view: View,
    /// Draw weight and buoyancy as arrows.
    #[arg(long)]
    pub forces: bool,
    /// Camera position `x,y,z` in m (default: framing the bodies).
    #[arg(long, value_parser = parse_point)]
    pub eye: Option<Point3<f64>>,
    /// Point the camera looks at, `x,y,z` in m (default: the bodies' centre).
    #[arg(long, value_parser = parse_point)]
    pub target: Option<Point3<f64>>,
    /// Output directory.
    #[arg(long, default_value = "out/render")]
    pub out: PathBuf,
}

fn parse_point(s: &str) -> Result<Point3<f64>, String> {
    let v: Vec<f64> = s
        .split(',')
        .map(|t| t.trim().parse::<f64>())
        .collect::<Result<_, _>>()
        .map_err(|e| format!("`{s}`: {e} (expected x,y,z in metres)"))?;
    match v[..] {
        [x, y, z] if v.iter().all(|c| c.is_finite()) => Ok(Point3::new(x, y, z)),
        _ => Err(format!("`{s}`: expected three finite numbers x,y,z in metres")),
    }
}

/// Frame options shared by `soak render` and `soak demo`.
#[derive(Clone, Debug)]
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

/// Draws a [`Simulation`] built from a scene file.
pub struct SceneRenderer {
    renderer: Renderer,
    meshes: Vec<Arc<Mesh>>,
    albedos: Vec<Albedo>,
    sea: Option<Gerstner>,
    level: Option<f64>,
    options: FrameOptions,
    radius: Vec<f64>,
    /// Per body, the liquid-graph node nearest each triangle (segments view).
    segments: Vec<Option<Arc<Vec<u32>>>>,
    adapter: String,
}

impl SceneRenderer {
    /// Loads the scene's meshes (as the simulation did) and opens a headless device.
    pub fn new(loaded: &LoadedScene, options: FrameOptions) -> Result<Self> {
        let (device, queue, info) = headless_device().context("no GPU adapter for rendering")?;
        let renderer = Renderer::new(&device, &queue, options.size.0, options.size.1)?;
        let mut meshes = Vec::new();
        let mut albedos = Vec::new();
        let mut radius = Vec::new();
        for (i, b) in loaded.scene.bodies.iter().enumerate() {
            let mesh = loaded.body_mesh(i)?;
            let r = mesh
                .positions
                .iter()
                .map(|p| p.coords.norm())
                .fold(0.0_f64, f64::max);
            radius.push(r);
            albedos.push(albedo_for(&b.name, &b.mesh, i, b.fixed));
            meshes.push(Arc::new(mesh));
        }
        let w = &loaded.scene.water;
        let g = Vector3::from(loaded.scene.gravity).norm().max(1e-9);
        let (sea, level) = match w.kind {
            WaterKind::Plane => (None, Some(w.level.unwrap_or(0.0))),
            WaterKind::Gerstner => (
                Some(Gerstner::new(
                    w.level.unwrap_or(0.0),
                    w.waves.clone().unwrap_or_default(),
                    g,
                )?),
                None,
            ),
            // A height field is drawn as its mean level; air has no surface.
            WaterKind::HeightField => (None, w.level.or(Some(0.0))),
            WaterKind::Air => (None, None),
        };
        Ok(Self {
            renderer,
            meshes,
            albedos,
            sea,
            level,
            options,
            segments: vec![None; loaded.scene.bodies.len()],
            radius,
            adapter: adapter_label(&info),
        })
    }

    /// The adapter's name (a software adapter's timings are CPU timings).
    pub fn adapter(&self) -> &str {
        &self.adapter
    }

    /// The frame for the simulation's current state.
    pub fn frame(&mut self, sim: &Simulation) -> Result<image::RgbaImage> {
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
                let atlas = body.atlas();
                let saturation = wetting.material().saturation;
                let values: Vec<f32> = wetting
                    .liquid()
                    .iter()
                    .map(|h| (h / saturation).clamp(0.0, 1.0) as f32)
                    .collect();
                object = object.with_liquid(liquid_image_from_texels(
                    atlas.width(),
                    atlas.height(),
                    atlas.texels(),
                    &values,
                    3,
                ));
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
            if let Some(level) = self.level.or(self.sea.as_ref().map(|s| s.level)) {
                eye.y = eye.y.max(level + 0.3 * size + 0.5);
            }
            eye
        });
        let mut scene = RenderScene::new(Camera::perspective(eye, target, 40.0));
        scene.light = DirectionalLight::from_angles(38.0, 60.0, [2.7, 2.5, 2.3]);
        scene.water = match (&self.sea, self.level) {
            (Some(sea), _) => Some(RenderWater::gerstner(sea.clone(), t)),
            (None, Some(level)) => Some(RenderWater::plane(level)),
            (None, None) => None,
        };
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
        Ok(self.renderer.render(&scene)?)
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

/// Encodes `frames` (PNG files of one size), each shown `seconds` long, as
/// H.264 in MP4 with the `ffmpeg` on the `PATH`.
fn encode_video(frames: &[PathBuf], seconds: f64, video: &Path) -> Result<()> {
    use std::fmt::Write as _;
    if frames.is_empty() {
        bail!("no frame to encode into {}", video.display());
    }
    // The concat demuxer's list: the frames written, each for its time.
    let mut list = String::from("ffconcat version 1.0\n");
    for f in frames {
        let name = std::fs::canonicalize(f).with_context(|| format!("cannot find {}", f.display()))?;
        let _ = writeln!(list, "file '{}'\nduration {seconds}", name.display());
    }
    // The last frame once more, so that its duration counts.
    let last = std::fs::canonicalize(&frames[frames.len() - 1])?;
    let _ = writeln!(list, "file '{}'", last.display());
    let list_path = video.with_extension("ffconcat");
    std::fs::write(&list_path, list).with_context(|| format!("cannot write {}", list_path.display()))?;
    let run = std::process::Command::new("ffmpeg")
        .args(["-y", "-loglevel", "error", "-f", "concat", "-safe", "0", "-i"])
        .arg(&list_path)
        .args([
            "-c:v",
            "libx264",
            "-pix_fmt",
            "yuv420p",
            "-vf",
            "pad=ceil(iw/2)*2:ceil(ih/2)*2",
        ])
        .arg(video)
        .output();
    let _ = std::fs::remove_file(&list_path);
    match run {
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => bail!(
            "--video needs ffmpeg, which is not on the PATH (Debian: `apt install ffmpeg`); \
             the {} frame(s) are written, and `ffmpeg -framerate {:.3} -pattern_type glob -i 'frame_*.png' {}` \
             encodes them once it is installed",
            frames.len(),
            1.0 / seconds,
            video.display()
        ),
        Err(e) => Err(e).context("running ffmpeg"),
        Ok(out) if !out.status.success() => bail!(
            "ffmpeg could not encode {}: {}",
            video.display(),
            String::from_utf8_lossy(&out.stderr).trim()
        ),
        Ok(_) => Ok(()),
    }
}

fn frame_path(out: &Path, step: u64) -> PathBuf {
    out.join(format!("frame_{step:06}.png"))
}

/// `soak render`.
pub fn run(args: &Args) -> Result<()> {
    let loaded = LoadedScene::from_file(&args.scene)?;
    let mut sim = Simulation::from_scene(&loaded)?;
    let last = args.frame.unwrap_or_else(|| sim.total_steps());
    if args.every == Some(0) {
        bail!("--every must be at least 1 (steps between frames)");
    }
    if args.width == 0 || args.height == 0 || args.width > 8192 || args.height > 8192 {
        bail!("--width and --height must be within 1..=8192 pixels");
    }
    std::fs::create_dir_all(&args.out).with_context(|| format!("cannot create {}", args.out.display()))?;
    let mut renderer = SceneRenderer::new(
        &loaded,
        FrameOptions {
            size: (args.width, args.height),
            view: args.view,
            forces: args.forces,
            eye: args.eye,
            target: args.target,
        },
    )?;
    let mut written = 0;
    let mut frames = Vec::new();
    let mut render_time = 0.0;
    crate::interrupt::install();
    let mut progress = crate::progress::Progress::new(args.scene.display().to_string(), "steps", last);
    let mut reached = 0;
    for step in 0..=last {
        if crate::interrupt::requested() {
            break;
        }
        if step > 0 {
            sim.step()?;
        }
        reached = step;
        progress.set(step, || {
            format!("t = {:.2} s, {written} frame(s) written", sim.time())
        });
        let wanted = step == last || args.every.is_some_and(|k| step.is_multiple_of(k));
        if wanted {
            let start = Instant::now();
            let image = renderer.frame(&sim)?;
            render_time += start.elapsed().as_secs_f64();
            let path = frame_path(&args.out, step);
            image
                .save(&path)
                .with_context(|| format!("cannot write {}", path.display()))?;
            frames.push(path);
            written += 1;
        }
    }
    progress.finish();
    println!(
        "wrote {written} frame(s) of {}×{} to {} (last: step {reached}, t = {:.3} s); {:.0} ms per frame on {}",
        args.width,
        args.height,
        args.out.display(),
        sim.time(),
        1e3 * render_time / f64::from(written.max(1)),
        renderer.adapter()
    );
    if let (Some(video), Some(every)) = (&args.video, args.every) {
        let seconds_per_frame = sim.dt() * every as f64;
        encode_video(&frames, seconds_per_frame, video)?;
        println!(
            "encoded {} frame(s) at {:.1} frames per second into {}",
            frames.len(),
            1.0 / seconds_per_frame,
            video.display()
        );
    }
    if reached < last {
        return Err(crate::interrupt::Interrupted {
            done: format!("at step {reached} of {last}: {written} frame(s) written"),
        }
        .into());
    }
    Ok(())
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
